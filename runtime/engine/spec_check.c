/* spec_check.c — the checks of a scene before it is compiled.
 *
 * Design.  sw_compile (model.c) calls these on the whole spec before it
 * allocates anything, so a bad scene costs nothing and every message names
 * the item and the field at fault ("rod 'arm': length must be > 0", "load 0
 * on rod 'arm': node index 6 out of range [0, 6)", "joint 'elbow': ...").
 * Rods, loads, boundary conditions and their signals, and joints with their
 * limits are checked here; muscles and environments check their own
 * descriptors (muscle.c, environment.c).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"
#include "model.h"

int sw_check_rod(const swRodDesc *r, char *err, size_t errlen) {
  const char *nm = r->name;
  if (r->nelem < 2)
    return sw_fail(err, errlen, "rod '%s': needs at least 2 elements, has %d", nm, r->nelem);
  if (r->nelem > 10000000)
    return sw_fail(err, errlen, "rod '%s': %d elements is more than this build supports", nm, r->nelem);
  if (!sw_finite_pos(r->length)) return sw_fail(err, errlen, "rod '%s': length must be > 0", nm);
  if (!sw_finite_pos(r->radius_start) || !sw_finite_pos(r->radius_end))
    return sw_fail(err, errlen, "rod '%s': radius must be > 0", nm);
  if (!sw_finite_pos(r->density)) return sw_fail(err, errlen, "rod '%s': density must be > 0", nm);
  if (!sw_finite_pos(r->youngs)) return sw_fail(err, errlen, "rod '%s': Young's modulus must be > 0", nm);
  if (r->shear_modulus == 0 && !(r->poisson > -1.0 && r->poisson <= 0.5))
    return sw_fail(err, errlen, "rod '%s': Poisson ratio %g outside (-1, 0.5]", nm, r->poisson);
  if (r->shear_modulus != 0 && !sw_finite_pos(r->shear_modulus))
    return sw_fail(err, errlen, "rod '%s': shear modulus must be > 0", nm);
  if (!sw_finite_pos(r->shear_hardening) || !sw_finite_pos(r->twist_hardening))
    return sw_fail(err, errlen, "rod '%s': hardening factors must be > 0", nm);
  if (!(r->gamma >= 0) || !isfinite(r->gamma))
    return sw_fail(err, errlen, "rod '%s': dissipation constant must be >= 0", nm);
  if (isnan(r->gamma_rot) || !isfinite(r->gamma_rot))
    return sw_fail(err, errlen, "rod '%s': rotational dissipation must be finite", nm);
  if (r->damping != SW_DAMP_NONE && r->damping != SW_DAMP_LINEAR && r->damping != SW_DAMP_ANALYTIC)
    return sw_fail(err, errlen, "rod '%s': unknown damping kind %d", nm, (int)r->damping);
  if (r->rigid != 0 && r->rigid != 1)
    return sw_fail(err, errlen, "rod '%s': rigid must be 0 or 1, got %d", nm, r->rigid);
  if (r->implicit != 0 && r->implicit != 1)
    return sw_fail(err, errlen, "rod '%s': implicit must be 0 or 1, got %d", nm, r->implicit);
  if (r->swell) { /* geometry that changes in time (swell.c) */
    if (r->rigid)
      return sw_fail(err, errlen, "rod '%s': a rigid rod cannot change its radius in time", nm);
    double lo, hi, r0 = sw_signal_eval(&r->swell_radius, 0.0);
    sw_signal_range(&r->swell_radius, &lo, &hi);
    if (!sw_finite_pos(r0) || !(lo > 0) || !isfinite(hi))
      return sw_fail(err, errlen, "rod '%s': its radius signal must stay > 0 and finite, but "
                     "reaches %g m (at t = 0: %g m)", nm, lo, r0);
    if (r->swell_twist_radius && r->swell_twist.kind != SW_SIG_CONST)
      return sw_fail(err, errlen, "rod '%s': its rest twist follows either the radius or a "
                     "signal, not both", nm);
  }
  if (r->implicit && r->rigid)
    return sw_fail(err, errlen, "rod '%s': a rigid rod has no elasticity to make implicit", nm);
  if (r->weightless != 0 && r->weightless != 1)
    return sw_fail(err, errlen, "rod '%s': weightless must be 0 or 1, got %d", nm, r->weightless);
  if (r->implicit && r->damping == SW_DAMP_ANALYTIC && (r->gamma > 0 || r->gamma_rot > 0))
    return sw_fail(err, errlen, "rod '%s': analytic damping is not supported on an implicit rod "
                "(use linear damping, which the implicit kick integrates by the trapezoidal rule)", nm);
  if (r->law != SW_LAW_GAZZOLA && r->law != SW_LAW_VARIATIONAL)
    return sw_fail(err, errlen, "rod '%s': unknown constitutive law %d", nm, (int)r->law);
  if (r->rigid && r->damping == SW_DAMP_ANALYTIC && (r->gamma > 0 || r->gamma_rot > 0))
    return sw_fail(err, errlen, "rod '%s': analytic damping is not supported on a rigid rod "
                "(use linear damping)", nm);
  double Q[9];
  if (!sw_frame_from(Q, r->direction, r->normal))
    return sw_fail(err, errlen, "rod '%s': direction is zero or parallel to normal", nm);
  return 1;
}
static int check_signal(const swSignal *g, char *err, size_t errlen, const char *what, int k,
                        const char *rod) {
  if (g->kind < SW_SIG_CONST || g->kind > SW_SIG_FUNC)
    return sw_fail(err, errlen, "%s %d on rod '%s': unknown signal kind %d", what, k, rod, (int)g->kind);
  if (g->kind == SW_SIG_FUNC && !g->fn)
    return sw_fail(err, errlen, "%s %d on rod '%s': function signal without a function", what, k,
                   rod);
  if (!(g->period >= 0) || !isfinite(g->period))
    return sw_fail(err, errlen, "%s %d on rod '%s': signal period must be >= 0 (0: not periodic), "
                "got %g", what, k, rod, g->period);
  if (g->kind == SW_SIG_BSPLINE) {
    if (g->npts < 4 || g->npts > SW_SIGNAL_MAXPTS)
      return sw_fail(err, errlen, "%s %d on rod '%s': B-spline signal needs 4..%d coefficients, "
                  "has %d", what, k, rod, SW_SIGNAL_MAXPTS, g->npts);
    if (!(g->T > 0) || !isfinite(g->T))
      return sw_fail(err, errlen, "%s %d on rod '%s': B-spline signal duration must be > 0", what, k,
                  rod);
    for (int i = 0; i < g->npts; i++)
      if (!isfinite(g->values[i]))
        return sw_fail(err, errlen, "%s %d on rod '%s': B-spline coefficient %d is not finite", what,
                    k, rod, i);
    return 1;
  }
  if (g->kind != SW_SIG_TABLE) return 1;
  if (g->npts < 1 || g->npts > SW_SIGNAL_MAXPTS)
    return sw_fail(err, errlen, "%s %d on rod '%s': table signal needs 1..%d points, has %d", what, k,
                rod, SW_SIGNAL_MAXPTS, g->npts);
  for (int i = 0; i < g->npts; i++) {
    if (!isfinite(g->times[i]) || !isfinite(g->values[i]))
      return sw_fail(err, errlen, "%s %d on rod '%s': table point %d is not finite", what, k, rod, i);
    if (i > 0 && !(g->times[i] > g->times[i - 1]))
      return sw_fail(err, errlen, "%s %d on rod '%s': table times must increase (point %d)", what, k,
                  rod, i);
  }
  return 1;
}

int sw_check_loads_bcs(const swSpec *s, char *err, size_t errlen) {
  for (int k = 0; k < s->nload; k++) {
    const swLoadDesc *l = &s->load[k];
    if (l->rod < 0 || l->rod >= s->nrod)
      return sw_fail(err, errlen, "load %d: rod index %d out of range", k, l->rod);
    const char *nm = s->rod[l->rod].name;
    if (l->kind != SW_LOAD_FORCE && l->kind != SW_LOAD_TORQUE)
      return sw_fail(err, errlen, "load %d on rod '%s': unknown kind %d", k, nm, (int)l->kind);
    int n = s->rod[l->rod].nelem, lim = l->kind == SW_LOAD_FORCE ? n + 1 : n;
    if (l->index < -1 || l->index >= lim)
      return sw_fail(err, errlen, "load %d on rod '%s': %s index %d out of range [0, %d)", k, nm,
                  l->kind == SW_LOAD_FORCE ? "node" : "element", l->index, lim);
    if (!isfinite(l->vec[0]) || !isfinite(l->vec[1]) || !isfinite(l->vec[2]))
      return sw_fail(err, errlen, "load %d on rod '%s': vector is not finite", k, nm);
    if (!check_signal(&l->signal, err, errlen, "load", k, nm)) return 0;
  }
  for (int k = 0; k < s->nbc; k++) {
    const swBCDesc *b = &s->bc[k];
    if (b->rod < 0 || b->rod >= s->nrod)
      return sw_fail(err, errlen, "boundary condition %d: rod index %d out of range", k, b->rod);
    const char *nm = s->rod[b->rod].name;
    if (b->end != 0 && b->end != 1)
      return sw_fail(err, errlen, "boundary condition %d on rod '%s': end must be 0 (start) or 1 (end)",
                  k, nm);
    if (b->kind < SW_BC_CLAMP || b->kind > SW_BC_SLEEVE)
      return sw_fail(err, errlen, "boundary condition %d on rod '%s': unknown kind %d", k, nm, (int)b->kind);
    if (!isfinite(b->vec[0]) || !isfinite(b->vec[1]) || !isfinite(b->vec[2]))
      return sw_fail(err, errlen, "boundary condition %d on rod '%s': vector is not finite", k, nm);
    if (!check_signal(&b->signal, err, errlen, "boundary condition", k, nm)) return 0;
    const int slide = b->kind == SW_BC_SLIDE_LINE || b->kind == SW_BC_SLIDE_PLANE || b->kind == SW_BC_SLEEVE;
    if (s->rod[b->rod].rigid && b->kind != SW_BC_CLAMP && !slide)
      return sw_fail(err, errlen, "boundary condition %d on rod '%s': a prescribed %s is not "
                  "supported on a rigid rod (clamp it, or hold it with a joint)", k, nm,
                  b->kind == SW_BC_VELOCITY ? "velocity" : "angular velocity");
    if (!isfinite(b->until) || b->until < 0)
      return sw_fail(err, errlen, "boundary condition %d on rod '%s': until must be a time >= 0 "
                  "(0: for ever), got %g", k, nm, b->until);
    if (slide && !(sw_v3_norm(b->vec) > 0))
      return sw_fail(err, errlen, "boundary condition %d on rod '%s': a slide needs a direction, "
                  "not (0, 0, 0)", k, nm);
    if ((slide || b->until > 0) && (s->rod[b->rod].rigid || s->rod[b->rod].implicit))
      return sw_fail(err, errlen, "boundary condition %d on rod '%s': a %s is not supported on a "
                  "%s rod (boundary.c)", k, nm, slide ? "slide" : "hold released with until",
                  s->rod[b->rod].rigid ? "rigid" : "implicit");
  }
  return 1;
}

/* A joint's stiffness or damping: finite and >= 0 (0 = chosen by joint.c). */
static int check_joint_coef(const swJointDesc *j, double v, const char *what, char *err,
                            size_t errlen) {
  if (isfinite(v) && v >= 0) return 1;
  return sw_fail(err, errlen, "joint '%s': %s must be finite and >= 0 (0 = automatic), got %g",
              j->name, what, v);
}

/* A joint's limits (joint.c, "Limits"): a range on hinges only, ordered; a
 * cone on spherical joints only, in (0, pi); their coefficients >= 0. */
static int check_joint_limits(const swJointDesc *j, char *err, size_t errlen) {
  const char *nm = j->name, *kind = sw_joint_kind_name(j->kind);
  if (j->has_range && j->kind != SW_JOINT_HINGE)
    return sw_fail(err, errlen, "joint '%s': an angle range is for a hinge, not a %s joint", nm,
                   kind);
  if (j->has_range && !(isfinite(j->angle_min) && isfinite(j->angle_max) &&
                        j->angle_min < j->angle_max))
    return sw_fail(err, errlen, "joint '%s': angle range must be finite with angle_min < "
                   "angle_max, got [%g, %g] rad", nm, j->angle_min, j->angle_max);
  if (j->cone != 0 && j->kind != SW_JOINT_SPHERICAL)
    return sw_fail(err, errlen, "joint '%s': a cone is for a spherical joint, not a %s joint", nm,
                   kind);
  if (!(j->cone >= 0 && j->cone < SW_PI))
    return sw_fail(err, errlen, "joint '%s': cone must be in (0, pi) rad (0 = none), got %g", nm,
                   j->cone);
  if (!check_joint_coef(j, j->limit_stiffness, "limit stiffness", err, errlen) ||
      !check_joint_coef(j, j->limit_damping, "limit damping", err, errlen))
    return 0;
  if (j->undamped && j->limit_damping != 0)
    return sw_fail(err, errlen, "joint '%s': declared undamped but limit damping is given", nm);
  return 1;
}

/* Node index of a joint end on rod r: -1 (last) or 0..n. */
static int check_joint_node(const swSpec *s, const swJointDesc *j, int rod, int node,
                            const char *end, char *err, size_t errlen) {
  int n = s->rod[rod].nelem;
  if (node >= -1 && node <= n) return 1;
  return sw_fail(err, errlen, "joint '%s': %s %d out of range for rod '%s' (nodes 0..%d, -1 = last)",
              j->name, end, node, s->rod[rod].name, n);
}

int sw_check_joints(const swSpec *s, char *err, size_t errlen) {
  for (int k = 0; k < s->njoint; k++) {
    const swJointDesc *j = &s->joint[k];
    const char *nm = j->name;
    for (int i = 0; i < k; i++)
      if (!strcmp(s->joint[i].name, nm))
        return sw_fail(err, errlen, "joint '%s': name already used by joint %d", nm, i);
    if (j->kind != SW_JOINT_SPHERICAL && j->kind != SW_JOINT_HINGE && j->kind != SW_JOINT_FIXED)
      return sw_fail(err, errlen, "joint '%s': unknown kind %d", nm, (int)j->kind);
    if (j->rod_a < 0 || j->rod_a >= s->nrod)
      return sw_fail(err, errlen, "joint '%s': rod_a index %d out of range [0, %d)", nm, j->rod_a,
                  s->nrod);
    if (j->rod_b < -1 || j->rod_b >= s->nrod)
      return sw_fail(err, errlen, "joint '%s': rod_b index %d out of range [0, %d) (-1 = anchored)",
                  nm, j->rod_b, s->nrod);
    if (!check_joint_node(s, j, j->rod_a, j->node_a, "node_a", err, errlen)) return 0;
    if (j->rod_b >= 0) {
      if (!check_joint_node(s, j, j->rod_b, j->node_b, "node_b", err, errlen)) return 0;
      int n = s->rod[j->rod_a].nelem;
      int na = j->node_a < 0 ? n : j->node_a, nb = j->node_b < 0 ? n : j->node_b;
      if (j->rod_b == j->rod_a && na == nb)
        return sw_fail(err, errlen, "joint '%s': joins node %d of rod '%s' to itself", nm, na,
                    s->rod[j->rod_a].name);
    } else if (!isfinite(j->anchor[0]) || !isfinite(j->anchor[1]) || !isfinite(j->anchor[2])) {
      return sw_fail(err, errlen, "joint '%s': anchor is not finite", nm);
    }
    if (!isfinite(j->arm_a[0]) || !isfinite(j->arm_a[1]) || !isfinite(j->arm_a[2])) {
      return sw_fail(err, errlen, "joint '%s': the arm of its first point is not finite", nm);
    }
    if (j->kind == SW_JOINT_HINGE) {
      double a2 = j->axis[0] * j->axis[0] + j->axis[1] * j->axis[1] + j->axis[2] * j->axis[2];
      if (!isfinite(a2) || !(a2 > 0))
        return sw_fail(err, errlen, "joint '%s': hinge axis must be finite and nonzero", nm);
    }
    if (!check_joint_coef(j, j->stiffness, "stiffness", err, errlen) ||
        !check_joint_coef(j, j->damping, "damping", err, errlen) ||
        !check_joint_coef(j, j->rot_stiffness, "rotational stiffness", err, errlen) ||
        !check_joint_coef(j, j->rot_damping, "rotational damping", err, errlen))
      return 0;
    if (j->undamped && (j->damping != 0 || j->rot_damping != 0))
      return sw_fail(err, errlen, "joint '%s': declared undamped but damping is given", nm);
    if (!check_joint_limits(j, err, errlen)) return 0;
  }
  return 1;
}
