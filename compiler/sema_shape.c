/* sema_shape.c — a rod's rest and starting shapes: straight, a helix, or a
 * centreline given as a function of the arc length s.
 *
 * Design.  Three fields of a rod say its shapes: `shape` (it rests and
 * starts in it), `rest_shape` and `start_shape` (each alone; the other stays
 * straight).  A value is the word `straight`, a call
 * helix(radius = R, turns = N | pitch = P | core = C, hand = right | left),
 * or a function field "rest_shape(s) = (x, y, z);" whose three components
 * are lengths over s, a centreline in lab axes moved to begin at the rod's
 * start (node i at start + f(s_i) - f(0)), checked as a terrain's height is (sema_fexpr.c, with the formal
 * HX_S).  The rod's `length` is always its arc length at rest, the range of
 * s.  A helix is set by its radius and two of turns, pitch (the advance
 * along its axis per turn), core (its length along the axis) and the rod's
 * length; with c = pitch / 2 pi its arc length is 2 pi N sqrt(R^2 + c^2).
 * Every value of a shape, and the start, direction and normal of a shaped
 * rod, must be known when compiling: the checker builds the shapes here with
 * the runtime's own functions (engine/shape.c), params at their defaults,
 * so that points on the rod (ROD.at(f), its ends) lie where it starts, and
 * the generated C calls the same functions with the same numbers
 * (gen_shape.c).  A rest curve must be parametrised by its arc length
 * (|dr/ds| = 1, checked at every node and element middle), since the rest
 * lengths come from it; a starting curve may stretch (|dr/ds| is its
 * stretch).  Muscles take no shape: their filaments run between their
 * attachments.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sema_int.h"

/* ---- reading the fields ---- */

/* A helix's numbers: each a constant of its dimension, or an error. */
static int helix_number(swSema *S, swScope *sc, const swAst *arg, swDim dim, const char *name,
                        double *out) {
  char what[64];
  snprintf(what, sizeof what, "a helix's '%s'", name);
  swValue v = sema_expect(S, sc, arg, 1, dim, ast_strdup(S->a, what, strlen(what)));
  if (v.kind == VAL_ERROR) return 0;
  if (!val_is_const(&v)) {
    diag_error(v.loc, "%s must be known when compiling, but it depends on param '%s' (a param "
               "cannot change a shape)", what, v.param ? v.param : "?");
    return 0;
  }
  *out = v.v[0];
  return 1;
}

/* helix(radius = R, two of turns / pitch / core with the rod's length,
 * hand = right | left).  *length: in, the rod's length (> 0) or 0 when not
 * given; out, the arc length. */
static swSceneShape *helix(swSema *S, swScope *sc, const swAst *call, const char *field,
                           const char *what, double *length) {
  static const char *const keys[] = {"radius", "turns", "pitch", "core", "hand"};
  const swAst *arg[5] = {0};
  const swAst *args = ast_kid(call, 0);
  int ok = 1;
  for (int i = 0; args && i < args->nkid; i++) {
    const swAst *a = args->kid[i];
    if (!a->name) {
      diag_error(a->loc, "the arguments of helix() are named: helix(radius = 1 cm, turns = 5, "
                 "core = 10 cm)");
      ok = 0;
      continue;
    }
    int k;
    for (k = 0; k < 5; k++)
      if (!strcmp(a->name, keys[k])) break;
    if (k == 5) {
      const char *near = diag_suggest(a->name, keys, 5);
      if (near) diag_error(a->loc, "helix() has no argument '%s'; did you mean '%s'?", a->name, near);
      else diag_error(a->loc, "helix() has no argument '%s' (it takes radius, turns, pitch, core "
                      "and hand)", a->name);
      ok = 0;
    } else if (arg[k]) {
      diag_error(a->loc, "helix() is given '%s' twice", a->name);
      ok = 0;
    } else arg[k] = a;
  }
  swSceneShape *h = ast_alloc(S->a, sizeof *h);
  memset(h, 0, sizeof *h);
  h->kind = SHAPE_HELIX;
  h->loc = call->loc;
  h->field = field;
  h->hand = 1;
  if (!arg[0]) {
    diag_error(call->loc, "%s: helix() needs its 'radius' (of the cylinder its centreline winds "
               "on)", what);
    ok = 0;
  }
  double R = 1, N = 0, P = 0, C = 0;
  if (arg[0] && !helix_number(S, sc, ast_kid(arg[0], 0), DIM_LENGTH, "radius", &R)) ok = 0;
  else if (arg[0] && !(R > 0)) {
    diag_error(arg[0]->loc, "a helix's 'radius' must be positive, got %g m", R);
    ok = 0;
  }
  if (arg[1] && helix_number(S, sc, ast_kid(arg[1], 0), DIM_NONE, "turns", &N) && !(N > 0)) {
    diag_error(arg[1]->loc, "a helix's 'turns' must be positive, got %g", N);
    ok = 0;
  } else if (arg[1] && !(N > 0)) ok = 0;
  if (arg[2] && helix_number(S, sc, ast_kid(arg[2], 0), DIM_LENGTH, "pitch", &P) && !(P >= 0)) {
    diag_error(arg[2]->loc, "a helix's 'pitch' must not be negative, got %g m (a left-handed "
               "helix is hand = left)", P);
    ok = 0;
  } else if (arg[2] && !(P >= 0)) ok = 0;
  if (arg[3] && helix_number(S, sc, ast_kid(arg[3], 0), DIM_LENGTH, "core", &C) && !(C >= 0)) {
    diag_error(arg[3]->loc, "a helix's 'core' (its length along the axis) must not be negative, "
               "got %g m", C);
    ok = 0;
  } else if (arg[3] && !(C >= 0)) ok = 0;
  if (arg[4]) {
    const swAst *hv = ast_kid(arg[4], 0);
    if (hv->kind == AST_NAME && !strcmp(hv->name, "right")) h->hand = 1;
    else if (hv->kind == AST_NAME && !strcmp(hv->name, "left")) h->hand = -1;
    else {
      diag_error(hv->loc, "a helix's 'hand' is right or left");
      ok = 0;
    }
  }
  if (!ok) return NULL;
  /* two of turns, pitch, core and the rod's length */
  const int given = !!arg[1] + !!arg[2] + !!arg[3] + (*length > 0);
  if (given != 2) {
    diag_error(call->loc, "%s: a helix is set by its radius and two of 'turns', 'pitch', 'core' "
               "and the rod's 'length' (its arc length); %s %d", what,
               given < 2 ? "got" : "got too many:", given);
    return NULL;
  }
  const double turn = 2 * M_PI * R;   /* the length of one turn seen along the axis */
  double L = *length;
  if (arg[1] && arg[2]) {
    L = N * sqrt(turn * turn + P * P);
  } else if (arg[1] && arg[3]) {
    P = C / N;
    L = sqrt(turn * N * turn * N + C * C);
  } else if (arg[2] && arg[3]) {
    if (!(P > 0)) {
      diag_error(arg[2]->loc, "a helix of pitch 0 has no length along its axis: give 'turns' "
                 "instead of 'core'");
      return NULL;
    }
    L = C / P * sqrt(turn * turn + P * P);
  } else if (arg[1]) {
    if (!(L > turn * N)) {
      diag_error(call->loc, "%s: %g turns of radius %g m need more than %g m of rod, but its "
                 "'length' is %g m", what, N, R, turn * N, L);
      return NULL;
    }
    P = sqrt(L * L - turn * N * turn * N) / N;
  } else if (arg[2]) {
    /* P as given: the turns follow from the length */
  } else {
    if (!(L > C)) {
      diag_error(arg[3]->loc, "a helix's 'core' (%g m) must be shorter than the rod's 'length' "
                 "(%g m), its arc length", C, L);
      return NULL;
    }
    N = sqrt(L * L - C * C) / turn;
    P = C / N;
  }
  h->radius = R;
  h->pitch = P;
  *length = L;
  return h;
}

/* Every constant of a curve known when compiling. */
static int curve_const(const swHExpr *e) {
  if (e->op == HX_CONST && !val_is_const(&e->k)) {
    diag_error(e->loc, "a shape must be known when compiling, but this depends on param '%s' "
               "(a param cannot change a shape)", e->k.param ? e->k.param : "?");
    return 0;
  }
  int ok = 1;
  for (int i = 0; i < e->nkid; i++) ok &= curve_const(e->kid[i]);
  return ok;
}

/* "rest_shape(s) = (x, y, z);" */
static swSceneShape *curve(swSema *S, swScope *sc, const swAst *fl, const char *what) {
  const swAst *formal = fl->kid[1], *body = fl->kid[0];
  /* s, the natural name, is also the unit second: either spelling */
  if (formal->kind != AST_NAME && formal->kind != AST_UNIT) {
    diag_error(formal->loc, "a shape is a function of one name, the arc length: %s(s) = (x, y, "
               "z);", fl->name);
    return NULL;
  }
  if (body->kind != AST_VEC || body->nkid != 3) {
    diag_error(body->loc, "%s(%s) is a point, three lengths: %s(%s) = (x, y, z);", fl->name,
               formal->name, fl->name, formal->name);
    return NULL;
  }
  swSceneShape *c = ast_alloc(S->a, sizeof *c);
  memset(c, 0, sizeof *c);
  c->kind = SHAPE_CURVE;
  c->loc = fl->loc;
  c->field = fl->name;
  c->sname = formal->name;
  swFCtx C;
  memset(&C, 0, sizeof C);
  C.S = S;
  C.scope = sc;
  C.nformal = 1;
  C.formal[0] = formal->name;
  C.formal_op[0] = HX_S;
  C.formal_dim[0] = DIM_LENGTH;
  C.shape = 1;
  C.term = "a term of a shape";
  char w[240];
  snprintf(w, sizeof w, "the %s of %s", fl->name, what);
  C.what = ast_strdup(S->a, w, strlen(w));
  int ok = 1;
  static const char axis[] = "xyz";
  for (int k = 0; k < 3; k++) {
    swHExpr *e = sema_fexpr(&C, body->kid[k], C.what);
    if (!e) {
      ok = 0;
      continue;
    }
    if (!dim_eq(e->dim, DIM_LENGTH)) {
      diag_error(body->kid[k]->loc, "the %c of %s must be a length, got %s", axis[k], C.what,
                 sema_fexpr_dim_text(S, e));
      ok = 0;
      continue;
    }
    if (!curve_const(e)) ok = 0;
    c->r[k] = e;
  }
  if (!ok) return NULL;
  c->index = S->scene->ncurve++;
  return c;
}

/* One shape field (value or function); *straight set for `straight`. */
static int shape_field(swSema *S, swScope *sc, const swAst *fl, const char *what, double *length,
                       const swSceneShape **out) {
  *out = NULL;
  if (fl->nkid > 1) return (*out = curve(S, sc, fl, what)) != NULL;
  const swAst *v = fl->kid[0];
  if (v->kind == AST_NAME && !strcmp(v->name, "straight")) return 1;
  if (v->kind == AST_CALL && !strcmp(v->name, "helix"))
    return (*out = helix(S, sc, v, fl->name, what, length)) != NULL;
  diag_error(v->loc, "'%s' is straight, helix(radius = ..., turns = ..., ...), or a curve of the "
             "arc length: %s(s) = (x, y, z);", fl->name, fl->name);
  return 0;
}

int sema_rod_shapes(swSema *S, swScope *sc, const swFields *f, const char *what,
                    double *length, swRodShapes *out) {
  memset(out, 0, sizeof *out);
  const swAst *both = sema_field_node(f, "shape"), *rest = sema_field_node(f, "rest_shape"),
              *start = sema_field_node(f, "start_shape");
  out->given = both || rest || start;
  int ok = 1;
  if (both && (rest || start)) {
    diag_error((rest ? rest : start)->loc, "give either 'shape' (the rod rests and starts in "
               "it), or 'rest_shape' and 'start_shape', not both");
    return 0;
  }
  if (both) {
    ok = shape_field(S, sc, both, what, length, &out->rest);
    out->start = out->rest;
    out->same = 1;
    return ok;
  }
  if (rest) ok &= shape_field(S, sc, rest, what, length, &out->rest);
  if (start) ok &= shape_field(S, sc, start, what, length, &out->start);
  return ok;
}

/* ---- building them ---- */

typedef struct {
  const swSceneShape *shape;
  const double *start;
} CurveCtx;

/* swCurveFn over a curve, params at their defaults: start + f(s) - f(0),
 * as the generated shape_K computes it */
static void eval_curve(double s, double r[3], const void *ctx) {
  const CurveCtx *c = ctx;
  swDual X = {s, 1, 0}, X0 = {0, 1, 0}, Y = {0, 0, 0};
  for (int k = 0; k < 3; k++)
    r[k] = c->start[k] + (sema_fexpr_eval(c->shape->r[k], X, Y, NULL).v -
                          sema_fexpr_eval(c->shape->r[k], X0, Y, NULL).v);
}

/* At rest, s must be the curve's arc length. */
static int curve_ok(const swSceneShape *c, double L, int n, int rest, const char *what) {
  swDual X = {0, 1, 0}, Y = {0, 0, 0};
  if (!rest) return 1;
  for (int i = 0; i <= 2 * n; i++) {
    X.v = L * i / (2 * n);
    double sp = 0;
    for (int k = 0; k < 3; k++) {
      const double d = sema_fexpr_eval(c->r[k], X, Y, NULL).x;
      sp += d * d;
    }
    sp = sqrt(sp);
    if (!(fabs(sp - 1) <= 1e-6)) {
      diag_error(c->loc, "%s: %s must be the arc length of its rest shape, but |d%s/d%s| is "
                 "%.6g at %s = %.6g m, not 1 (a rest shape sets the rod's rest lengths; a "
                 "starting shape may stretch)", what, c->sname, c->field, c->sname, sp,
                 c->sname, X.v);
      return 0;
    }
  }
  return 1;
}

/* A value of a shaped rod's placement known when compiling. */
static int placement_const(const swValue *v, const char *key, const char *what) {
  if (v->kind == VAL_ERROR || val_is_const(v)) return 1;
  diag_error(v->loc, "%s has a shape, so its '%s' must be known when compiling, but it depends "
             "on param '%s'", what, key, v->param ? v->param : "?");
  return 0;
}

/* One shape's nodes and frames into x, Q. */
static int build(const swSceneShape *sh, int n, double L, const double *start, const double *dir,
                 const double *normal, double *x, double *Q, const char *what) {
  char err[256] = "";
  int rc;
  if (sh->kind == SHAPE_HELIX) {
    rc = sw_shape_helix(n, sh->radius, sh->pitch, L, sh->hand, start, dir, normal, x, Q, err,
                        sizeof err);
  } else {
    CurveCtx c = {sh, start};
    rc = sw_shape_curve(n, L, eval_curve, &c, normal, x, Q, err, sizeof err);
  }
  if (rc != SW_OK) diag_error(sh->loc, "%s: %s: %s", what, sh->field, err);
  return rc == SW_OK;
}

int sema_rod_place_shapes(swSema *S, swSceneRod *r, const swRodShapes *sh, int normal_given,
                          const char *what) {
  if (!sh->rest && !sh->start) return 1;
  if (!placement_const(&r->start, "start", what) | !placement_const(&r->length, "length", what) |
      !placement_const(&r->direction, "direction", what) |
      !placement_const(&r->normal, "normal", what))
    return 0;
  if (r->start.kind != VAL_VEC || r->length.kind != VAL_NUM) return 0;
  const int n = r->nelem;
  const double L = r->length.v[0];
  const double *start = r->start.v;
  /* a curve's checks at the params' defaults */
  if (sh->rest && sh->rest->kind == SHAPE_CURVE && !curve_ok(sh->rest, L, n, 1, what)) return 0;
  if (sh->start && sh->start->kind == SHAPE_CURVE && !sh->same &&
      !curve_ok(sh->start, L, n, 0, what))
    return 0;
  /* a rod starting on a curve goes the way of its first element; its
   * normal, unless given, is perpendicular to that */
  if (sh->start && sh->start->kind == SHAPE_CURVE) {
    CurveCtx c = {sh->start, start};
    double a[3], b[3], d[3];
    eval_curve(0, a, &c);
    eval_curve(L / n, b, &c);
    for (int k = 0; k < 3; k++) d[k] = b[k] - a[k];
    double dn = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(dn > 0)) {
      diag_error(sh->start->loc, "%s: %s: its first element has no length", what,
                 sh->start->field);
      return 0;
    }
    r->direction = sema_vec3(S, d[0] / dn, d[1] / dn, d[2] / dn, DIM_NONE, sh->start->loc);
    if (!normal_given) {
      double ax = fabs(d[0]) / dn < 0.9 ? 1 : 0, ay = 1 - ax;
      double dot = (ax * d[0] + ay * d[1]) / (dn * dn);
      double nx = ax - dot * d[0], ny = ay - dot * d[1], nz = -dot * d[2];
      double nn = sqrt(nx * nx + ny * ny + nz * nz);
      r->normal = sema_vec3(S, nx / nn, ny / nn, nz / nn, DIM_NONE, sh->start->loc);
    }
  }
  if (r->direction.kind != VAL_VEC || r->normal.kind != VAL_VEC) return 0;
  const double *dir = r->direction.v, *normal = r->normal.v;
  double *xr = ast_alloc(S->a, sizeof(double) * 3 * (size_t)(n + 1));
  double *Qr = ast_alloc(S->a, sizeof(double) * 9 * (size_t)n);
  double *xs = ast_alloc(S->a, sizeof(double) * 3 * (size_t)(n + 1));
  double *Qs = ast_alloc(S->a, sizeof(double) * 9 * (size_t)n);
  char err[256] = "";
  if (sh->rest && !build(sh->rest, n, L, start, dir, normal, xr, Qr, what)) return 0;
  if (sh->same) {
    xs = xr;
    Qs = Qr;
  } else if (sh->start) {
    if (!build(sh->start, n, L, start, dir, normal, xs, Qs, what)) return 0;
  } else if (sw_shape_straight(n, xr, start, dir, normal, xs, Qs, err, sizeof err) != SW_OK) {
    diag_error(r->loc, "%s: %s", what, err);
    return 0;
  }
  r->rest_shape = sh->rest;
  r->start_shape = sh->start;
  r->x0 = xs;
  r->Q0 = Qs;
  if (sh->rest) {
    r->xr = xr;
    r->Qr = Qr;
  }
  return 1;
}

/* The point of a shaped rod at fraction f of its length, where it starts:
 * between the nodes around f n, in proportion. */
void sema_shape_point(const swSceneRod *r, double f, double x[3]) {
  const int n = r->nelem;
  double u = f * n;
  int i = (int)floor(u);
  if (i < 0) i = 0;
  if (i > n - 1) i = n - 1;
  u -= i;
  for (int k = 0; k < 3; k++)
    x[k] = (1 - u) * r->x0[3 * i + k] + u * r->x0[3 * (i + 1) + k];
}
