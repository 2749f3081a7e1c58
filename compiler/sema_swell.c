/* sema_swell.c — the checks of a rod whose geometry changes in time.
 *
 * Design.  A rod's `radius` may be a time signal of a length (radius =
 * 5 mm * ramp(1, 2, over = 1 s); or a `signal NAME(t)` of the model), and
 * two fields scale its rest shape in time: `rest_curvature_scale` (its rest
 * curvature about d1 and d2) and `rest_twist_scale` (its rest twist about
 * d3), each a number or a dimensionless signal, the twist's also the word
 * `follows_radius`, r(0) / r(t), the law of the reference's code (Zhang et
 * al. 2019's elastica, source/Polymer.cpp) and of Charles, Gazzola &
 * Mahadevan's twisted-fibre muscles (PRL 2019).  `mass = conserved` (the
 * default: the density falls as (r0 / r)^2) or `mass = grows` (the density
 * stays) says what the radius does to the mass.  What follows the radius,
 * and why, is the runtime's (engine/swell.c; docs/physics.md).  The checks
 * are made where each field is written; the radius's range over the run is
 * checked once the run's duration is known (sema_swell_check), at the
 * params' defaults, as the runtime checks it again at their run values.
 */
#include <math.h>
#include <string.h>

#include "diag.h"
#include "gen.h"
#include "sema_int.h"

/* A dimensionless scale: a number or a dimensionless signal (NULL after an
 * error, reported). */
static swSignalVal *scale_signal(swSema *S, swScope *scope, const swAst *e, const char *field,
                                 const char *what) {
  swValue v = sema_eval(S, scope, e);
  if (v.kind == VAL_ERROR) return NULL;
  if (v.kind != VAL_NUM && v.kind != VAL_SIGNAL) {
    diag_error(v.loc, "%s: '%s' is a number or a dimensionless time signal (e.g. ramp(1, 0.5, "
               "over = 1 s)), not %s", what, field, v.kind == VAL_WORD ? v.word : "that");
    return NULL;
  }
  if (!dim_eq(v.dim, DIM_NONE)) {
    diag_error(v.loc, "%s: '%s' multiplies the rest shape, so it is dimensionless, got %s", what,
               field, dim_describe(S->a, v.dim));
    return NULL;
  }
  char w[96];
  snprintf(w, sizeof w, "'%s'", field);
  return sema_scalar_signal(S, v, ast_strdup(S->a, w, strlen(w)));
}

/* Whether rod r rests with some twist about d3: a rest_curvature whose third
 * component is not zero, or a helix of non-zero pitch (a curve's frames are
 * parallel-transported: no twist). */
static int has_rest_twist(const swSceneRod *r) {
  if (r->rest_shape) return r->rest_shape->kind == SHAPE_HELIX && r->rest_shape->pitch != 0;
  return r->rest_kappa.kind == VAL_VEC && r->rest_kappa.v[2] != 0;
}

static int has_rest_curvature(const swSceneRod *r) {
  if (r->rest_shape) return 1;
  return r->rest_kappa.kind == VAL_VEC && (r->rest_kappa.v[0] != 0 || r->rest_kappa.v[1] != 0);
}

/* The radius (evaluated already, into r->radius_start when constant) and
 * the fields above.  shape_unknown: the rod has a shape that an earlier
 * error kept from being placed, so whether it rests twisted is not known
 * (nothing is said of it).  Returns 0 after an error. */
int sema_rod_swell(swSema *S, swScope *scope, const swFields *f, swSceneRod *r, const char *what,
                   int shape_unknown) {
  int ok = 1;
  const swAst *rad = sema_field(f, "radius");
  if (rad) {
    swValue v = sema_eval(S, scope, rad);
    if (v.kind == VAL_SIGNAL) {
      if (!dim_eq(v.dim, DIM_LENGTH)) {
        diag_error(v.loc, "%s: 'radius' expects length (m), or a time signal of one, got %s", what,
                   dim_describe(S->a, v.dim));
        return 0;
      }
      r->swell_radius = sema_scalar_signal(S, v, "'radius'");
      if (!r->swell_radius) return 0;
      r->swell_loc = v.loc;
      /* the radius at t = 0, at the params' defaults, for what reads it
       * when compiling; the generated C takes it from the signal */
      swSignal sig = gen_signal(r->swell_radius);
      const double r0 = sw_signal_eval(&sig, 0.0);
      r->radius_start = r->radius_end = val_num(S->a, r0, DIM_LENGTH, v.loc);
      if (!(r0 > 0)) {
        diag_error(v.loc, "%s: its radius at t = 0 is %g mm; a radius must be positive", what,
                   r0 * 1e3);
        ok = 0;
      }
    } else {
      r->radius_start = r->radius_end = sema_expect_value(S, v, 1, DIM_LENGTH, "'radius'");
      sema_positive(S, &r->radius_start, "'radius'", "m");
    }
  }
  const swAst *cs = sema_field(f, "rest_curvature_scale"), *ts = sema_field(f, "rest_twist_scale"),
              *ms = sema_field(f, "mass");
  if (cs) {
    r->swell_curvature = scale_signal(S, scope, cs, "rest_curvature_scale", what);
    if (!r->swell_curvature) ok = 0;
    else if (!has_rest_curvature(r))
      diag_warning(cs->loc, "%s rests straight (no rest curvature about d1, d2): "
                   "'rest_curvature_scale' has nothing to scale", what);
  }
  if (ts) {
    swValue w = ts->kind == AST_NAME ? sema_eval(S, scope, ts) : val_error();
    if (w.kind == VAL_WORD && !strcmp(w.word, "follows_radius")) {
      r->swell_twist_radius = 1;
      if (!r->swell_radius) {
        diag_error(ts->loc, "%s: 'rest_twist_scale = follows_radius' ties the rest twist to a "
                   "radius that changes in time, but its radius is constant (write radius = a "
                   "signal, e.g. 5 mm * ramp(1, 2, over = 1 s))", what);
        ok = 0;
      }
    } else {
      r->swell_twist = scale_signal(S, scope, ts, "rest_twist_scale", what);
      if (!r->swell_twist) ok = 0;
    }
    if (ok && !shape_unknown && !has_rest_twist(r)) {
      diag_error(ts->loc, "%s has no rest twist for 'rest_twist_scale' to scale (give it "
                 "rest_curvature = (k1, k2, k3) with k3 != 0, or a helix of non-zero pitch)", what);
      ok = 0;
    }
  }
  if (ms) {
    swValue w = sema_eval(S, scope, ms);
    if (w.kind == VAL_WORD && (!strcmp(w.word, "conserved") || !strcmp(w.word, "grows"))) {
      r->swell_mass_grows = !strcmp(w.word, "grows");
      if (!r->swell_radius) {
        diag_error(ms->loc, "%s: 'mass' says what a radius that changes in time does to the mass, "
                   "but its radius is constant", what);
        ok = 0;
      }
    } else if (w.kind != VAL_ERROR) {
      diag_error(ms->loc, "%s: 'mass' is 'conserved' (the density falls as the radius grows) or "
                 "'grows' (the density stays); a rod's mass follows from its density and size",
                 what);
      ok = 0;
    }
  }
  if (r->rigid && (r->swell_radius || r->swell_curvature || r->swell_twist)) {
    diag_error(rad && r->swell_radius ? r->swell_loc : (cs ? cs->loc : ts->loc),
               "%s is rigid: its radius and rest shape cannot change in time", what);
    ok = 0;
  }
  return ok;
}

/* Every radius signal over the run, [0, duration] (a signal NAME(t) is
 * sampled there; a built-in signal over all its values): > 0 throughout. */
void sema_swell_check(swSema *S) {
  for (int i = 0; i < S->scene->nrod; i++) {
    const swSceneRod *r = &S->scene->rod[i];
    if (!r->swell_radius) continue;
    swSignal sig = gen_signal(r->swell_radius);
    double lo, hi;
    sw_signal_range(&sig, &lo, &hi);
    if (!(lo > 0))
      diag_error(r->swell_loc, "rod '%s': its radius falls to %g mm during the run; a radius must "
                 "stay positive", r->name, lo * 1e3);
  }
}
