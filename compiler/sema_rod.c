/* sema_rod.c — rods (rod, bone and tendon definitions) and the points on
 * them.
 *
 * Design.  A rod's fields fall back on its material, then on the runtime's
 * defaults; the checked rod is appended to the scene with every field a
 * swValue, so a param-dependent field keeps its C expression.  Positions of
 * points on a rod (start, end, at(f)) follow from its straight starting shape:
 * start + f * length * direction; a position is such a point or a 3-vector
 * of lengths; on a rod with a shape (sema_shape.c) they lie where it starts,
 * between its nodes.  Apart from sema_def.c, which keeps the field tables,
 * materials and the evaluation of every kind of definition, because the rod
 * is the largest definition and its points are what joints, muscles, loads
 * and probes are placed with.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sema_int.h"

/* ---- rods ---- */

static const char *const rod_keys[] = {
  "material", "start", "from", "to", "direction", "normal", "length", "radius", "radius_start",
  "radius_end", "elements", "E", "G", "poisson", "density", "shear_hardening",
  "twist_hardening", "rest_curvature", "rest_strain", "damping", "rotational_damping",
  "damping_model", "rigid", "variational", "implicit", "gravity", "shape", "rest_shape",
  "start_shape", "rest_curvature_scale", "rest_twist_scale", "mass",
};
enum { NROD_KEYS = sizeof rod_keys / sizeof rod_keys[0] };

static swRodKind rod_kind(const char *word) {
  if (!strcmp(word, "bone")) return ROD_BONE;
  if (!strcmp(word, "tendon")) return ROD_TENDON;
  return ROD_PLAIN;
}

void sema_eval_rod(swSema *S, swSymbol *sym) {
  swFields f;
  char what[160];
  snprintf(what, sizeof what, "%s '%s'", sym->def->text, sym->name);
  sema_fields(S, sym->def, 0, what, rod_keys, NROD_KEYS, &f);
  swScope *sc = sym->scope;
  swSceneRod r;
  memset(&r, 0, sizeof r);
  r.name = sym->full;
  r.kind = rod_kind(sym->def->text);
  r.loc = sym->loc;
  swLoc loc = sym->loc;
  int ok = 1;

  /* material, then rod-level overrides; without them, defaults and a warning */
  swTissue t;
  if (!sema_tissue(S, sc, &f, &t)) ok = 0;
  r.youngs = t.youngs.kind || t.mat ? t.youngs : val_num(S->a, 1e6, DIM_PRESSURE, loc);
  r.density = t.density.kind || t.mat ? t.density : val_num(S->a, 1000, DIM_DENSITY, loc);
  r.shear_modulus = t.shear_modulus.kind ? t.shear_modulus : val_num(S->a, 0, DIM_PRESSURE, loc);
  r.poisson = t.poisson.kind ? t.poisson : val_num(S->a, 0.5, DIM_NONE, loc);
  r.variational = t.variational > 0;   /* unsaid: Gazzola et al. 2018's law */
  r.material = t.mat_name;
  r.has_material = t.mat != NULL || (t.E_ast && t.rho_ast);
  if (!t.mat && !t.me && !t.E_ast && !t.rho_ast)
    diag_warning(loc, "%s has no material; it gets E = %g Pa and density = %g kg/m^3", what,
                 r.youngs.kind == VAL_NUM ? r.youngs.v[0] : 0,
                 r.density.kind == VAL_NUM ? r.density.v[0] : 0);
  else if (!t.mat && !t.me && !t.E_ast)
    diag_warning(loc, "%s has no material and no E; it gets E = %g Pa", what,
                 r.youngs.kind == VAL_NUM ? r.youngs.v[0] : 0);
  else if (!t.mat && !t.me && !t.rho_ast)
    diag_warning(loc, "%s has no material and no density; it gets density = %g kg/m^3", what,
                 r.density.kind == VAL_NUM ? r.density.v[0] : 0);

  /* placement: start/from, and either to or direction + length */
  const swAst *start = sema_field(&f, "start"), *from = sema_field(&f, "from");
  const swAst *to = sema_field(&f, "to"), *dir = sema_field(&f, "direction");
  const swAst *len = sema_field(&f, "length");
  /* shapes first (sema_shape.c): a helix may set the length */
  swRodShapes sh;
  memset(&sh, 0, sizeof sh);
  swValue lenv = val_error();
  double shape_len = 0;
  if (len) {
    lenv = sema_field_value(S, sc, &f, "length", 1, DIM_LENGTH);
    sema_positive(S, &lenv, "'length'", "m");
    if (lenv.kind == VAL_NUM) shape_len = lenv.v[0];
  }
  int shape_err = 0;   /* reported: the placement's own errors would follow from it */
  if ((!len || lenv.kind == VAL_NUM) && !sema_rod_shapes(S, sc, &f, what, &shape_len, &sh)) {
    ok = 0;
    shape_err = 1;
  }
  const int shaped = sh.rest || sh.start;
  const int start_curve = sh.start && sh.start->kind == SHAPE_CURVE;
  const int helix_len = !len && shape_len > 0;   /* a helix set the length */
  if (start && from) {
    diag_error(from->loc, "give either 'start' or 'from', not both");
    ok = 0;
  }
  const swAst *s0 = start ? start : from;
  if (!s0) {
    sema_missing(&f, loc, "%s needs a 'start' (or 'from') position", what);
    ok = 0;
    r.start = val_error();
  } else r.start = sema_position(S, sc, s0, start ? "'start'" : "'from'");
  char field[512];
  const char *name = sym->full ? sym->full : sym->name;
  snprintf(field, sizeof field, "rod %s: start", name);
  sema_derive(S, &r.start, field, sym->loc);
  if (to && (shaped || helix_len)) {
    diag_error(to->loc, "'to' places a straight rod, from its start to that point; a rod with a "
               "shape is placed by 'start' and 'direction' (for a helix, its axis)");
    ok = 0;
    r.direction = r.length = val_error();
  } else if (to) {
    if (dir || len) {
      diag_error(to->loc, "give either 'to', or 'direction' and 'length', not both");
      ok = 0;
    }
    swValue end = sema_position(S, sc, to, "'to'");
    swValue d = val_binop(S->a, '-', end, r.start, to->loc);
    /* a param that moves the ends: the axis and its length once each */
    snprintf(field, sizeof field, "rod %s: to - from", name);
    sema_derive(S, &d, field, sym->loc);
    r.length = val_norm(S->a, d, to->loc);
    snprintf(field, sizeof field, "rod %s: length", name);
    sema_derive(S, &r.length, field, sym->loc);
    if (r.length.kind == VAL_NUM && !(r.length.v[0] > 0)) {
      diag_error(to->loc, "'to' is the same point as the start, so the rod has no length");
      ok = 0;
    }
    r.direction = r.length.kind == VAL_NUM ? val_binop(S->a, '/', d, r.length, to->loc) : val_error();
  } else {
    if (start_curve && dir) {
      diag_error(dir->loc, "'direction' has no place in a rod that starts on a curve: its "
                 "%s(s) sets the way it goes", sh.start->field);
      ok = 0;
    } else if (((!dir && !start_curve) || (!len && !helix_len)) && !shape_err) {
      sema_missing(&f, loc, "%s needs 'to', or 'direction' and 'length'", what);
      ok = 0;
    }
    r.direction = dir && !start_curve ? sema_field_value(S, sc, &f, "direction", 3, DIM_NONE)
                                      : val_error();
    r.length = len ? lenv : helix_len ? val_num(S->a, shape_len, DIM_LENGTH, loc) : val_error();
  }
  if (r.direction.kind == VAL_VEC) {
    double n = sqrt(r.direction.v[0] * r.direction.v[0] + r.direction.v[1] * r.direction.v[1] +
                    r.direction.v[2] * r.direction.v[2]);
    if (!(n > 0)) {
      diag_error(r.direction.loc, "'direction' must not be the zero vector");
      ok = 0;
    }
  }
  if (sema_field(&f, "normal")) {
    r.normal = sema_field_value(S, sc, &f, "normal", 3, DIM_NONE);
    if (r.normal.kind == VAL_VEC && !(fabs(r.normal.v[0]) + fabs(r.normal.v[1]) +
                                      fabs(r.normal.v[2]) > 0)) {
      diag_error(r.normal.loc, "'normal' must not be the zero vector");
      ok = 0;
    }
    if (r.normal.kind == VAL_VEC && r.direction.kind == VAL_VEC) {
      const double *a = r.normal.v, *b = r.direction.v;
      double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2],
             cz = a[0] * b[1] - a[1] * b[0];
      if (!(cx * cx + cy * cy + cz * cz > 1e-24)) {
        diag_error(r.normal.loc, "'normal' must not be parallel to the rod's direction");
        ok = 0;
      }
    }
  } else if (r.direction.kind == VAL_VEC) {
    /* any unit vector perpendicular to the direction: x, unless nearly parallel */
    const double *d = r.direction.v;
    double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double ax = fabs(d[0]) / n < 0.9 ? 1 : 0, ay = 1 - ax;
    double dot = (ax * d[0] + ay * d[1]) / (n * n);
    double nx = ax - dot * d[0], ny = ay - dot * d[1], nz = -dot * d[2];
    double nn = sqrt(nx * nx + ny * ny + nz * nz);
    r.normal = sema_vec3(S, nx / nn, ny / nn, nz / nn, DIM_NONE, loc);
  }
  /* cross section */
  const swAst *rad = sema_field(&f, "radius"), *rs = sema_field(&f, "radius_start"),
              *re = sema_field(&f, "radius_end");
  if (rad && (rs || re)) {
    diag_error(rad->loc, "give either 'radius', or 'radius_start' and 'radius_end' (a taper)");
    ok = 0;
  }
  if (rad) {
    /* a length or a time signal of one: below, with the fields that change
     * the geometry in time (sema_swell.c) */
  } else if (rs && re) {
    r.radius_start = sema_field_value(S, sc, &f, "radius_start", 1, DIM_LENGTH);
    r.radius_end = sema_field_value(S, sc, &f, "radius_end", 1, DIM_LENGTH);
    sema_positive(S, &r.radius_start, "'radius_start'", "m");
    sema_positive(S, &r.radius_end, "'radius_end'", "m");
  } else {
    sema_missing(&f, loc, "%s needs a 'radius' (or 'radius_start' and 'radius_end')", what);
    ok = 0;
  }
  /* discretisation */
  long nelem = 20;
  if (sema_field(&f, "elements")) {
    swValue ne = sema_field_value(S, sc, &f, "elements", 1, DIM_NONE);
    if (!sema_const_int(S, ne, "'elements'", 2, 100000, &nelem)) ok = 0;
  }
  r.nelem = (int)nelem;
  /* a bound on the whole scene, so a 20 kB file cannot ask for gigabytes
   * (the checker hands the scene to the runtime, which allocates it) */
  long total = S->scene->nelem + nelem;
  if (ok && total > SEMA_MAX_ELEMENTS) {
    diag_error(loc, "the scene would have %ld elements with %s; at most %d are allowed", total,
               what, SEMA_MAX_ELEMENTS);
    ok = 0;
  }
  /* hardening, rest shape, damping */
  r.shear_hardening = sema_field(&f, "shear_hardening")
                      ? sema_field_value(S, sc, &f, "shear_hardening", 1, DIM_NONE)
                      : val_num(S->a, 1, DIM_NONE, loc);
  r.twist_hardening = sema_field(&f, "twist_hardening")
                      ? sema_field_value(S, sc, &f, "twist_hardening", 1, DIM_NONE)
                      : val_num(S->a, 1, DIM_NONE, loc);
  sema_positive(S, &r.shear_hardening, "'shear_hardening'", "");
  sema_positive(S, &r.twist_hardening, "'twist_hardening'", "");
  r.rest_kappa = sema_field(&f, "rest_curvature")
                 ? sema_field_value(S, sc, &f, "rest_curvature", 3, dim_make(0, -1, 0, 0))
                 : sema_vec3(S, 0, 0, 0, dim_make(0, -1, 0, 0), loc);
  r.rest_sigma = sema_field(&f, "rest_strain")
                 ? sema_field_value(S, sc, &f, "rest_strain", 3, DIM_NONE)
                 : sema_vec3(S, 0, 0, 0, DIM_NONE, loc);
  r.gamma = sema_field(&f, "damping") ? sema_field_value(S, sc, &f, "damping", 1, dim_make(1, -1, -1, 0))
            : val_num(S->a, 0, dim_make(1, -1, -1, 0), loc);
  if (r.gamma.kind == VAL_NUM && r.gamma.v[0] < 0) {
    diag_error(r.gamma.loc, "'damping' must not be negative");
    ok = 0;
  }
  /* rotational_damping: the couple density -gamma_rot w of Gazzola 2018, in
   * N s/rad; without it the couples are damped in proportion to the inertia */
  r.gamma_rot.kind = VAL_ERROR;
  if (sema_field(&f, "rotational_damping")) {
    r.gamma_rot = sema_field_value(S, sc, &f, "rotational_damping", 1, dim_make(1, 1, -1, -1));
    if (r.gamma_rot.kind == VAL_ERROR) ok = 0;
    else if (r.gamma_rot.kind == VAL_NUM && r.gamma_rot.v[0] < 0) {
      diag_error(r.gamma_rot.loc, "'rotational_damping' must not be negative");
      ok = 0;
    }
  }
  r.damping = sema_damping_kind(S, sc, &f, NULL);
  /* rigid = true: the runtime moves the rod as one rigid body.  It changes
   * the layout the runtime builds, so it is fixed when compiling: the word
   * itself, or a let or component parameter holding it, never a param. */
  const swAst *rg = sema_field(&f, "rigid");
  if (rg) {
    int truth = sema_truth(S, sc, rg, "'rigid'");
    if (truth < 0) ok = 0;
    else r.rigid = truth;
  }
  /* implicit = true: under integrator = imex the runtime kicks the rod's
   * elasticity by the trapezoidal rule (a switch, like rigid) */
  const swAst *im = sema_field(&f, "implicit");
  if (im) {
    int truth = sema_truth(S, sc, im, "'implicit'");
    if (truth < 0) ok = 0;
    else r.implicit = truth;
    if (ok && r.implicit && r.rigid) {
      diag_error(im->loc, "rod '%s' is rigid: it has no elasticity to make implicit", sym->name);
      ok = 0;
    } else if (ok && r.implicit && r.damping == SW_DAMP_ANALYTIC) {
      diag_error(im->loc, "rod '%s': analytic damping is not supported on an implicit rod (use "
                 "damping_model = linear, which the implicit kick integrates by the "
                 "trapezoidal rule)", sym->name);
      ok = 0;
    }
  }
  /* gravity = false: gravity does not act on the rod (a switch, like rigid) */
  const swAst *gv = sema_field(&f, "gravity");
  if (gv) {
    int truth = sema_truth(S, sc, gv, "'gravity'");
    if (truth < 0) ok = 0;
    else r.weightless = !truth;
  }
  /* the shapes, now that the rod is placed and its elements known */
  const int tried = ok && shaped;   /* an earlier error leaves the shapes unplaced */
  if (tried && !sema_rod_place_shapes(S, &r, &sh, sema_field(&f, "normal") != NULL, what))
    ok = 0;
  /* the radius, and the geometry that changes in time (sema_swell.c); a
   * shape not placed after an earlier error leaves the rest twist unknown,
   * not absent */
  if (!sema_rod_swell(S, sc, &f, &r, what, shaped && !tried)) ok = 0;
  const swValue *all[] = {&r.youngs, &r.density, &r.shear_modulus, &r.poisson, &r.start,
                          &r.direction, &r.normal, &r.length, &r.radius_start, &r.radius_end,
                          &r.shear_hardening, &r.twist_hardening, &r.rest_kappa, &r.rest_sigma,
                          &r.gamma};
  for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
    if (all[i]->kind == VAL_ERROR) ok = 0;
  if (!ok) {
    sym->index = -1;
    return;
  }
  /* a rod's points (start, end, at(f)) are built on these three */
  snprintf(field, sizeof field, "rod %s: direction", name);
  sema_derive(S, &r.direction, field, sym->loc);
  snprintf(field, sizeof field, "rod %s: length", name);
  sema_derive(S, &r.length, field, sym->loc);
  swScene *scn = S->scene;
  if (scn->nrod == scn->caprod) {
    scn->caprod = scn->caprod ? 2 * scn->caprod : 8;
    scn->rod = realloc(scn->rod, (size_t)scn->caprod * sizeof *scn->rod);
    if (!scn->rod) abort();
  }
  sym->index = scn->nrod;
  r.id = scn->nrodid++;
  scn->nelem += r.nelem;
  scn->rod[scn->nrod++] = r;
}

/* ---- points on rods ---- */

/* A position: a point on a rod, or a length vector.  When rod, node and
 * node_c are given they receive the rod, the node and the node's C text (NULL
 * unless a param moves it) of a point on a rod; -1, 0 and NULL else. */
swValue sema_position_on(swSema *S, swScope *scope, const swAst *e, const char *what, int *rod,
                         int *node, const char **node_c) {
  if (rod) *rod = -1;
  if (node) *node = 0;
  if (node_c) *node_c = NULL;
  swValue v = sema_eval(S, scope, e);
  if (v.kind == VAL_POINT) {
    if (rod) *rod = v.rod;
    if (node) *node = v.node;
    if (node_c) *node_c = v.node_c;
    v.kind = VAL_VEC;
    return v;
  }
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, scope, v.word, v.loc, "name");
    return val_error();
  }
  return sema_expect_value(S, v, 3, DIM_LENGTH, what);
}

swValue sema_position(swSema *S, swScope *scope, const swAst *e, const char *what) {
  return sema_position_on(S, scope, e, what, NULL, NULL, NULL);
}

/* A point whose node must be known when compiling (a load's, a boundary
 * condition's, a probe's): 0 with an error naming what when a param moves it. */
int sema_point_fixed(const swValue *p, const char *what) {
  if (p->kind != VAL_POINT || !p->node_c) return 1;
  diag_error(p->loc, "%s must be known when the model is compiled, but it depends on param '%s' "
             "(a param may move a joint's or a muscle's point, not this one)", what,
             p->param ? p->param : "?");
  return 0;
}

swValue sema_rod_length(swSema *S, swSymbol *rod, swLoc loc) {
  sema_eval_symbol(S, rod);
  if (rod->index < 0 || rod->state != 2) return val_error();
  swValue v = S->scene->rod[rod->index].length;
  v.loc = loc;
  return v;
}

/* node: >= 0 a node, -1 the last node, -2 the node nearest to frac.  A
 * fraction that depends on a param (ROD.at(param)) moves the point: its
 * position is then an expression of the params, and so is its node, which
 * the generated simulator computes when it builds the scene, with the same
 * lround the default's node is taken with here. */
swValue sema_rod_point(swSema *S, swSymbol *rod, swValue f, int node, swLoc loc) {
  rod->used = 1;
  sema_eval_symbol(S, rod);
  if (rod->index < 0 || rod->state != 2) return val_error();
  const swSceneRod *r = &S->scene->rod[rod->index];
  int n = r->nelem;
  const char *node_c = NULL;
  if (node == -1) node = n;
  if (node == -2) {
    node = (int)lround(f.v[0] * n);
    if (f.c && f.c[0]) {
      char buf[4200];
      if (snprintf(buf, sizeof buf, "(int)lround(%s * %d)", f.c[0], n) >= (int)sizeof buf) {
        diag_error(loc, "expression is too long to generate");
        return val_error();
      }
      node_c = ast_strdup(S->a, buf, strlen(buf));
    }
  }
  if (r->x0) {   /* a shaped rod: where it starts, between its nodes */
    if (f.c && f.c[0]) {
      diag_error(loc, "a point on rod '%s', which has a shape, must be at a fraction known "
                 "when compiling, but this depends on param '%s'", rod->name,
                 f.param ? f.param : "?");
      return val_error();
    }
    double x[3];
    sema_shape_point(r, f.v[0], x);
    swValue p = sema_vec3(S, x[0], x[1], x[2], DIM_LENGTH, loc);
    p.kind = VAL_POINT;
    p.rod = rod->index;
    p.node = node;
    p.at = f.v[0];
    return p;
  }
  swValue dir = r->direction;
  /* direction is normalised by the runtime: do the same here */
  swValue unit = val_binop(S->a, '/', dir, val_norm(S->a, dir, loc), loc);
  swValue off = val_binop(S->a, '*', val_binop(S->a, '*', f, r->length, loc), unit, loc);
  swValue p = val_binop(S->a, '+', r->start, off, loc);
  if (p.kind == VAL_ERROR) return p;
  p.kind = VAL_POINT;
  p.rod = rod->index;
  p.node = node;
  p.at = f.v[0];
  p.node_c = node_c;
  p.loc = loc;
  return p;
}
