/* sema_terrain.c — a terrain's height(x, y): checked into an expression tree
 * over x and y, and evaluated with its gradient inside the compiler.
 *
 * Design.  "height(x, y) = expr;" is a function of the horizontal lab
 * coordinates, both lengths, and must give a length.  It is checked into a
 * swHExpr tree (sema.h), separately from the value walk of sema_expr.c,
 * because its value is not known when compiling: every subexpression that
 * does not depend on x or y is evaluated by sema_eval and folded into one
 * constant node (a swValue, so a param keeps its C expression), the rest
 * keeps its operation and dimension.  Beyond +, -, *, /, ^ (constant
 * exponent), sqrt, sin, cos, tan and exp, the height may compare (< <= > >=,
 * and, or) and choose with piecewise(cond: value, ..., default), evaluated
 * top to bottom, the first true condition winning.  The terrain's body may
 * hold lets that use x and y; they are kept as named nodes, so the
 * generated C has one statement per let.  The runtime needs the gradient
 * too (the surface normal): gen_env.c prints the tree as forward-mode
 * dual-number C (value, d/dx, d/dy); sema_height_eval here evaluates the
 * same tree with the same rules, for the in-compiler sw_compile check and
 * for the test that compares the two (sinewc --eval-height).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sema_int.h"

#define MAX_LETS 64

typedef struct {
  swSema *S;
  swScope *scope;
  swHeight *h;
  const char *what;
  int nlocal;
  const char *local_name[MAX_LETS];
  swHExpr *local[MAX_LETS];   /* each local let's tree (HX_LET or a constant) */
  swLoc local_loc[MAX_LETS];
  int local_used[MAX_LETS];
} swHCtx;

static swHExpr *node(swSema *S, swHOp op, swDim dim, swLoc loc, int nkid) {
  swHExpr *e = ast_alloc(S->a, sizeof *e);
  memset(e, 0, sizeof *e);
  e->op = op;
  e->dim = dim;
  e->loc = loc;
  e->k = val_error();
  e->nkid = nkid;
  if (nkid) e->kid = ast_alloc(S->a, (size_t)nkid * sizeof *e->kid);
  return e;
}

static swHExpr *constant(swSema *S, swValue v) {
  swHExpr *e = node(S, HX_CONST, v.dim, v.loc, 0);
  e->k = v;
  return e;
}

static const char *dim_text(swSema *S, const swHExpr *e) {
  if (e->boolean) return "a condition";
  if (dim_is_none(e->dim)) return "dimensionless (a number without a unit)";
  return dim_describe(S->a, e->dim);
}

static swHExpr *hx(swHCtx *C, const swAst *e);

/* A quantity (not a condition); NULL after an error. */
static swHExpr *quantity(swHCtx *C, const swAst *e, const char *role) {
  swHExpr *q = hx(C, e);
  if (q && q->boolean) {
    diag_error(e->loc, "%s must be a value, not a condition", role);
    return NULL;
  }
  return q;
}

static swHExpr *condition(swHCtx *C, const swAst *e) {
  swHExpr *q = hx(C, e);
  if (q && !q->boolean) {
    diag_error(e->loc, "a condition of piecewise() must be a comparison (x < 3 m), not a value");
    return NULL;
  }
  return q;
}

static swHExpr *name(swHCtx *C, const swAst *e) {
  swSema *S = C->S;
  if (!strcmp(e->name, C->h->xname)) return node(S, HX_X, DIM_LENGTH, e->loc, 0);
  if (!strcmp(e->name, C->h->yname)) return node(S, HX_Y, DIM_LENGTH, e->loc, 0);
  for (int i = C->nlocal - 1; i >= 0; i--)
    if (!strcmp(e->name, C->local_name[i])) {
      C->local_used[i] = 1;
      return C->local[i];
    }
  swValue v = sema_eval(S, C->scope, e);
  if (v.kind == VAL_WORD) {
    const char *cands[MAX_LETS + 2];
    int n = 0;
    cands[n++] = C->h->xname;
    cands[n++] = C->h->yname;
    for (int i = 0; i < C->nlocal; i++) cands[n++] = C->local_name[i];
    const char *near = diag_suggest(e->name, cands, n);
    if (near) diag_error(e->loc, "unknown name '%s' in %s; did you mean '%s'?", e->name, C->what, near);
    else sema_report_unknown(S, C->scope, e->name, e->loc, "name");
    return NULL;
  }
  if (v.kind == VAL_ERROR) return NULL;
  v = sema_expect_value(S, v, 1, v.dim, "a name in a height");
  return v.kind == VAL_ERROR ? NULL : constant(S, v);
}

static swHExpr *binop(swHCtx *C, const swAst *e, int op, const swAst *l, const swAst *r) {
  swSema *S = C->S;
  if (op == '&' || op == '|') {
    swHExpr *a = condition(C, l), *b = condition(C, r);
    if (!a || !b) return NULL;
    swHExpr *n = node(S, op == '&' ? HX_AND : HX_OR, DIM_NONE, e->loc, 2);
    n->boolean = 1;
    n->kid[0] = a;
    n->kid[1] = b;
    return n;
  }
  swHExpr *a = quantity(C, l, "an operand"), *b = quantity(C, r, "an operand");
  if (!a || !b) return NULL;
  if (strchr("<>lg", op)) {
    if (!dim_eq(a->dim, b->dim)) {
      diag_error(e->loc, "cannot compare %s and %s", dim_text(S, a), dim_text(S, b));
      return NULL;
    }
    swHExpr *n = node(S, op == '<' ? HX_LT : op == '>' ? HX_GT : op == 'l' ? HX_LE : HX_GE,
                      DIM_NONE, e->loc, 2);
    n->boolean = 1;
    n->kid[0] = a;
    n->kid[1] = b;
    return n;
  }
  if (a->op == HX_CONST && b->op == HX_CONST) {
    swValue v = val_binop(S->a, op, a->k, b->k, e->loc);
    return v.kind == VAL_ERROR ? NULL : constant(S, v);
  }
  swDim dim;
  if (op == '+' || op == '-') {
    if (!dim_eq(a->dim, b->dim)) {
      diag_error(e->loc, "cannot %s %s and %s", op == '+' ? "add" : "subtract", dim_text(S, a),
                 dim_text(S, b));
      return NULL;
    }
    dim = a->dim;
  } else {
    dim = op == '*' ? dim_mul(a->dim, b->dim) : dim_div(a->dim, b->dim);
  }
  swHExpr *n = node(S, op == '+' ? HX_ADD : op == '-' ? HX_SUB : op == '*' ? HX_MUL : HX_DIV, dim,
                    e->loc, 2);
  n->kid[0] = a;
  n->kid[1] = b;
  return n;
}

static swHExpr *power(swHCtx *C, const swAst *e) {
  swSema *S = C->S;
  swHExpr *a = quantity(C, e->kid[0], "a base");
  swValue p = sema_eval(S, C->scope, e->kid[1]);
  if (!a || p.kind == VAL_ERROR) return NULL;
  if (p.kind != VAL_NUM || !dim_is_none(p.dim) || !val_is_const(&p)) {
    diag_error(e->kid[1]->loc, "an exponent must be a plain number known when compiling");
    return NULL;
  }
  if (a->op == HX_CONST) {
    swValue v = val_pow(S->a, a->k, p.v[0], e->loc);
    return v.kind == VAL_ERROR ? NULL : constant(S, v);
  }
  swDim dim;
  if (!dim_pow(a->dim, p.v[0], &dim)) {
    diag_error(e->loc, "%s can only be raised to an integer power, not %g", dim_text(S, a), p.v[0]);
    return NULL;
  }
  swHExpr *n = node(S, HX_POW, dim, e->loc, 1);
  n->kid[0] = a;
  n->p = p.v[0];
  return n;
}

static const char *const funcs[] = {"sqrt", "sin", "cos", "tan", "exp", "piecewise"};

static swHExpr *piecewise(swHCtx *C, const swAst *e, const swAst *args) {
  swSema *S = C->S;
  int n = args ? args->nkid : 0;
  if (n < 2) {
    diag_error(e->loc, "piecewise() takes cases 'condition: value' and a default value last: "
               "piecewise(x < 1 m: 0 m, 0.2 m)");
    return NULL;
  }
  if (args->kid[n - 1]->kind == AST_CASE) {
    diag_error(args->kid[n - 1]->loc, "piecewise() needs a default value last, for when no "
               "condition holds: piecewise(x < 1 m: 0 m, 0.2 m)");
    return NULL;
  }
  swHExpr *pw = node(S, HX_PIECEWISE, DIM_NONE, e->loc, 2 * (n - 1) + 1);
  const swHExpr *first = NULL;   /* the first good value sets the dimension */
  int ok = 1, nfirst = 0;
  for (int i = 0; i < n; i++) {
    const swAst *a = args->kid[i];
    if (a->kind != AST_CASE && i < n - 1) {
      diag_error(a->loc, "every argument of piecewise() but the last is 'condition: value'");
      ok = 0;
      continue;
    }
    if (a->kind == AST_ARG && a->name) {
      diag_error(a->loc, "piecewise() has no argument '%s'", a->name);
      ok = 0;
      continue;
    }
    const swAst *ve = a->kind == AST_CASE ? a->kid[1] : ast_kid(a, 0);
    if (a->kind == AST_CASE) {
      pw->kid[2 * i] = condition(C, a->kid[0]);
      if (!pw->kid[2 * i]) ok = 0;
    }
    swHExpr *v = quantity(C, ve, "a value of piecewise()");
    if (!v) {
      ok = 0;
      continue;
    }
    pw->kid[i < n - 1 ? 2 * i + 1 : 2 * (n - 1)] = v;
    if (!first) {
      first = v;
      nfirst = i + 1;
      pw->dim = v->dim;
    } else if (!dim_eq(v->dim, pw->dim)) {
      diag_error(ve->loc, "the values of piecewise() must share one dimension: value %d is %s, "
                 "value %d is %s", nfirst, dim_text(S, first), i + 1, dim_text(S, v));
      ok = 0;
    }
  }
  return ok ? pw : NULL;
}

static swHExpr *call(swHCtx *C, const swAst *e) {
  swSema *S = C->S;
  const swAst *args = ast_kid(e, 0);
  int k;
  for (k = 0; k < 6; k++)
    if (!strcmp(e->name, funcs[k])) break;
  if (k == 5) return piecewise(C, e, args);
  if (k == 6) {
    if (!strcmp(e->name, "ramp") || !strcmp(e->name, "sine") || !strcmp(e->name, "step") ||
        !strcmp(e->name, "table") || !strcmp(e->name, "bspline")) {
      diag_error(e->loc, "a height does not change in time: %s() has no place in it", e->name);
      return NULL;
    }
    const char *near = diag_suggest(e->name, funcs, 6);
    if (near) diag_error(e->loc, "unknown function '%s'; did you mean '%s'?", e->name, near);
    else diag_error(e->loc, "unknown function '%s' (a height may use sqrt, sin, cos, tan, exp "
                    "and piecewise)", e->name);
    return NULL;
  }
  if (!args || args->nkid != 1 || args->kid[0]->kind != AST_ARG || args->kid[0]->name) {
    diag_error(e->loc, "%s() takes one argument", e->name);
    return NULL;
  }
  swHExpr *a = quantity(C, args->kid[0]->kid[0], "an argument");
  if (!a) return NULL;
  if (a->op == HX_CONST) {
    swValue v = val_func(S->a, e->name, a->k, e->loc);
    return v.kind == VAL_ERROR ? NULL : constant(S, v);
  }
  swDim dim = DIM_NONE;
  if (k == 0) {
    for (int i = 0; i < SW_NDIM; i++) {
      if (a->dim.e[i] % 2) {
        diag_error(e->loc, "sqrt() of %s has no dimension", dim_text(S, a));
        return NULL;
      }
      dim.e[i] = (signed char)(a->dim.e[i] / 2);
    }
  } else if (k < 4 ? !dim_is_none(a->dim) && !dim_eq(a->dim, DIM_ANGLE) : !dim_is_none(a->dim)) {
    diag_error(e->loc, "%s() takes %s, not %s", e->name,
               k < 4 ? "an angle or a plain number" : "a plain number", dim_text(S, a));
    return NULL;
  }
  static const swHOp ops[] = {HX_SQRT, HX_SIN, HX_COS, HX_TAN, HX_EXP};
  swHExpr *n = node(S, ops[k], dim, e->loc, 1);
  n->kid[0] = a;
  return n;
}

static swHExpr *hx(swHCtx *C, const swAst *e) {
  swSema *S = C->S;
  switch (e->kind) {
  case AST_NAME:
    return name(C, e);
  case AST_BINOP:
    if (e->op == '^') return power(C, e);
    return binop(C, e, e->op, e->kid[0], e->kid[1]);
  case AST_APPLY:
    return binop(C, e, '*', e->kid[0], e->kid[1]);
  case AST_NEG: {
    swHExpr *a = quantity(C, e->kid[0], "an operand");
    if (!a) return NULL;
    if (a->op == HX_CONST) {
      swValue v = val_neg(S->a, a->k, e->loc);
      return v.kind == VAL_ERROR ? NULL : constant(S, v);
    }
    swHExpr *n = node(S, HX_NEG, a->dim, e->loc, 1);
    n->kid[0] = a;
    return n;
  }
  case AST_CALL:
    return call(C, e);
  case AST_VEC:
    diag_error(e->loc, "%s is one number at each (x, y), not a vector", C->what);
    return NULL;
  default: {
    /* numbers, units, members (rod.length, v.x): values without x or y */
    swValue v = sema_eval(S, C->scope, e);
    if (v.kind == VAL_WORD) {
      sema_report_unknown(S, C->scope, v.word, v.loc, "name");
      return NULL;
    }
    if (v.kind == VAL_ERROR) return NULL;
    v = sema_expect_value(S, v, 1, v.dim, "a term of a height");
    return v.kind == VAL_ERROR ? NULL : constant(S, v);
  }
  }
}

/* The formals of height(x, y): two distinct names. */
static int formals(swSema *S, const swAst *f, swHeight *h) {
  if (!f || f->kind != AST_VEC || f->nkid != 2 || f->kid[0]->kind != AST_NAME ||
      f->kid[1]->kind != AST_NAME || !strcmp(f->kid[0]->name, f->kid[1]->name)) {
    diag_error(f ? f->loc : h->loc, "a height is a function of two names, the lab x and y: "
               "height(x, y) = ...;");
    return 0;
  }
  (void)S;
  h->xname = f->kid[0]->name;
  h->yname = f->kid[1]->name;
  return 1;
}

swHeight *sema_height(swSema *S, swScope *scope, const swAst *body, const swAst *field,
                      const char *what) {
  if (!field) {
    diag_error(body->loc, "%s needs its surface: height(x, y) = ...; (a length, e.g. "
               "height(x, y) = 0.1 m * sin(x / 1 m);)", what);
    return NULL;
  }
  swHeight *h = ast_alloc(S->a, sizeof *h);
  memset(h, 0, sizeof *h);
  h->loc = field->loc;
  if (field->nkid < 2) {
    diag_error(field->loc, "'height' is a function of x and y: write height(x, y) = ...;");
    return NULL;
  }
  if (!formals(S, field->kid[1], h)) return NULL;
  swHCtx C;
  memset(&C, 0, sizeof C);
  C.S = S;
  C.scope = scope;
  C.h = h;
  char w[200];
  snprintf(w, sizeof w, "the height of %s", what);
  C.what = ast_strdup(S->a, w, strlen(w));
  int ok = 1;
  h->let = ast_alloc(S->a, MAX_LETS * sizeof *h->let);
  h->let_name = ast_alloc(S->a, MAX_LETS * sizeof *h->let_name);
  h->let_loc = ast_alloc(S->a, MAX_LETS * sizeof *h->let_loc);
  for (int i = 0; i < body->nkid; i++) {
    const swAst *l = body->kid[i];
    if (l->kind != AST_LET) continue;
    if (C.nlocal == MAX_LETS) {
      diag_error(l->loc, "a terrain holds at most %d lets", MAX_LETS);
      return NULL;
    }
    if (!strcmp(l->name, h->xname) || !strcmp(l->name, h->yname)) {
      diag_error(l->loc, "'%s' names a coordinate of height(%s, %s)", l->name, h->xname, h->yname);
      ok = 0;
      continue;
    }
    swHExpr *v = quantity(&C, l->kid[0], "a let");
    if (!v) {
      ok = 0;
      continue;
    }
    if (v->op != HX_CONST) {   /* depends on x or y: one statement of the C */
      swHExpr *ref = node(S, HX_LET, v->dim, l->loc, 0);
      ref->let = h->nlet;
      h->let[h->nlet] = v;
      h->let_name[h->nlet] = l->name;
      h->let_loc[h->nlet] = l->loc;
      h->nlet++;
      v = ref;
    }
    C.local_name[C.nlocal] = l->name;
    C.local_loc[C.nlocal] = l->loc;
    C.local[C.nlocal++] = v;
  }
  swHExpr *e = quantity(&C, field->kid[0], C.what);
  if (!e || !ok) return NULL;
  for (int i = 0; i < C.nlocal; i++)
    if (!C.local_used[i])
      diag_warning(C.local_loc[i], "let '%s' of %s is never used", C.local_name[i], what);
  if (!dim_eq(e->dim, DIM_LENGTH)) {
    diag_error(field->kid[0]->loc, "%s must be a length, got %s", C.what, dim_text(S, e));
    return NULL;
  }
  h->expr = e;
  return h;
}

/* ---- evaluation with the gradient (forward mode) ---- */

typedef struct { double v, x, y; } swDual;

static swDual eval(const swHExpr *e, swDual X, swDual Y, const swDual *lets);

static int truth(const swHExpr *e, swDual X, swDual Y, const swDual *lets) {
  if (e->op == HX_AND) return truth(e->kid[0], X, Y, lets) && truth(e->kid[1], X, Y, lets);
  if (e->op == HX_OR) return truth(e->kid[0], X, Y, lets) || truth(e->kid[1], X, Y, lets);
  double a = eval(e->kid[0], X, Y, lets).v, b = eval(e->kid[1], X, Y, lets).v;
  switch (e->op) {
  case HX_LT: return a < b;
  case HX_LE: return a <= b;
  case HX_GT: return a > b;
  default: return a >= b;
  }
}

/* The rules are those of the generated C's dual_* helpers (gen_env.c). */
static swDual eval(const swHExpr *e, swDual X, swDual Y, const swDual *lets) {
  swDual r = {0, 0, 0}, a, b;
  switch (e->op) {
  case HX_CONST: r.v = e->k.v[0]; return r;
  case HX_X: return X;
  case HX_Y: return Y;
  case HX_LET: return lets[e->let];
  case HX_PIECEWISE:
    for (int i = 0; i + 1 < e->nkid; i += 2)
      if (truth(e->kid[i], X, Y, lets)) return eval(e->kid[i + 1], X, Y, lets);
    return eval(e->kid[e->nkid - 1], X, Y, lets);
  default: break;
  }
  a = eval(e->kid[0], X, Y, lets);
  b = e->nkid > 1 ? eval(e->kid[1], X, Y, lets) : r;
  double f;   /* derivative of the one-argument function at a.v */
  switch (e->op) {
  case HX_ADD: return (swDual){a.v + b.v, a.x + b.x, a.y + b.y};
  case HX_SUB: return (swDual){a.v - b.v, a.x - b.x, a.y - b.y};
  case HX_MUL: return (swDual){a.v * b.v, a.x * b.v + a.v * b.x, a.y * b.v + a.v * b.y};
  case HX_DIV:
    return (swDual){a.v / b.v, (a.x * b.v - a.v * b.x) / (b.v * b.v),
                    (a.y * b.v - a.v * b.y) / (b.v * b.v)};
  case HX_NEG: return (swDual){-a.v, -a.x, -a.y};
  case HX_POW:
    r.v = pow(a.v, e->p);
    f = e->p == 0 ? 0 : e->p * pow(a.v, e->p - 1);
    break;
  case HX_SQRT: r.v = sqrt(a.v); f = 0.5 / r.v; break;
  case HX_SIN: r.v = sin(a.v); f = cos(a.v); break;
  case HX_COS: r.v = cos(a.v); f = -sin(a.v); break;
  case HX_TAN: r.v = tan(a.v); f = 1 / (cos(a.v) * cos(a.v)); break;
  default: r.v = exp(a.v); f = r.v; break;   /* HX_EXP */
  }
  r.x = f * a.x;
  r.y = f * a.y;
  return r;
}

double sema_height_eval(double x, double y, double grad[2], const void *ctx) {
  const swHeight *h = ctx;
  swDual X = {x, 1, 0}, Y = {y, 0, 1}, lets[MAX_LETS];
  for (int i = 0; i < h->nlet; i++) lets[i] = eval(h->let[i], X, Y, lets);
  swDual r = eval(h->expr, X, Y, lets);
  grad[0] = r.x;
  grad[1] = r.y;
  return r.v;
}
