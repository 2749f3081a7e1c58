/* sema_stmt.c — statements: joints, actions (clamp, gravity, force, torque,
 * velocity, angular_velocity; activate and passive are handed to
 * sema_muscle.c) and simulate.
 *
 * Design.  Statements are checked in file order.  They become scene joints
 * and actions (loads and boundary conditions) that refer to rods by scene
 * index and to nodes by number, which must be known when compiling; the
 * runtime's rod ids are applied when lowering (gen_rod_id).  simulate is
 * met once per scene and fills the scene's options (output: sema_output.c).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sema_int.h"

/* ---- joints ---- */

static const char *const joint_kinds[] = {"spherical", "hinge", "fixed"};
static const char *const joint_keys[] = {"axis", "stiffness", "damping", "rot_stiffness",
                                         "rot_damping", "allow_gap", "range", "cone",
                                         "limit_stiffness", "limit_damping"};
enum { NJOINT_KEYS = sizeof joint_keys / sizeof joint_keys[0] };

/* "5 mm", "12 um", "0.3 m": a length in the unit that reads best. */
static const char *length_text(char *buf, size_t len, double metres) {
  if (metres < 1e-3) snprintf(buf, len, "%.3g um", metres * 1e6);
  else if (metres < 1) snprintf(buf, len, "%.3g mm", metres * 1e3);
  else snprintf(buf, len, "%.4g m", metres);
  return buf;
}

/* Where the node a point on a rod acts on lies at t = 0: on the rod's
 * straight initial shape, node / n of its length from its start; on a
 * shaped rod, its node where it starts (sema_shape.c).  A point
 * ROD.at(f) has the coordinates of f * length but acts on the node nearest
 * to it, which differ when f * n is not whole. */
void sema_node_position(const swScene *scn, const swValue *p, double x[3]) {
  const swSceneRod *r = &scn->rod[p->rod];
  memcpy(x, p->v, 3 * sizeof *x);
  if (r->x0 && p->node >= 0 && p->node <= r->nelem) {
    memcpy(x, r->x0 + 3 * p->node, 3 * sizeof *x);
    return;
  }
  if (r->nelem <= 0 || r->start.kind != VAL_VEC || r->direction.kind != VAL_VEC ||
      r->length.kind != VAL_NUM)
    return;
  const double *d = r->direction.v;
  double norm = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(norm > 0)) return;
  double s = r->length.v[0] * p->node / r->nelem / norm;
  for (int k = 0; k < 3; k++) x[k] = r->start.v[k] + s * d[k];
}

/* A joint's two points must start together: its spring pulls a gap shut
 * with stiffness x gap on the first step (654 kN for 5 mm on the elbow's
 * default).  The tolerance is a millionth of the shorter element at the
 * joint, far below anything a model means; allow_gap = true says the gap is
 * intended (the joint then pulls the points together).  The gap is the one
 * between the nodes the joint holds: a rib laid from spine.at(0.325) (100
 * elements) starts 5 mm from node 33, which its joint holds, and that
 * joint's 4.9 kN on the first step drove the muscular snake (issue 13).
 * Positions are those of the params' defaults. */
static int joint_gap_ok(swSema *S, swScope *scope, const swFields *f, const swAst *it,
                        const swValue *a, const swValue *b, const swValue *arm) {
  const swAst *allow = sema_field(f, "allow_gap");
  int allowed = 0;
  if (allow) {
    allowed = sema_truth(S, scope, allow, "'allow_gap'");
    if (allowed < 0) return 0;
  }
  if (a->kind != VAL_POINT || (b->kind != VAL_POINT && b->kind != VAL_VEC)) return 1;
  const swScene *scn = S->scene;
  double xa[3], xb[3];
  sema_node_position(scn, a, xa);
  if (arm->kind == VAL_VEC)   /* the first end is off its node, on an arm */
    for (int k = 0; k < 3; k++) xa[k] += arm->v[k];
  if (b->kind == VAL_POINT) sema_node_position(scn, b, xb);
  else memcpy(xb, b->v, sizeof xb);
  double gap = 0;
  for (int k = 0; k < 3; k++) gap += (xa[k] - xb[k]) * (xa[k] - xb[k]);
  gap = sqrt(gap);
  double element = INFINITY;
  const swValue *ends[2] = {a, b};
  for (int e = 0; e < 2; e++) {
    if (ends[e]->kind != VAL_POINT) continue;
    const swSceneRod *r = &scn->rod[ends[e]->rod];
    if (r->length.kind == VAL_NUM && r->nelem > 0) element = fmin(element, r->length.v[0] / r->nelem);
  }
  if (!isfinite(element) || gap <= 1e-6 * element || allowed) return 1;
  char g[64], pa[160], pb[160], na[200] = "", nb[200] = "";
  snprintf(pa, sizeof pa, "(%.4g, %.4g, %.4g) m", xa[0], xa[1], xa[2]);
  snprintf(pb, sizeof pb, "(%.4g, %.4g, %.4g) m", xb[0], xb[1], xb[2]);
  /* say so when a point's node is not where its coordinates are */
  const double *xs[2] = {xa, xb};
  char *notes[2] = {na, nb};
  for (int e = 0; e < 2; e++) {
    const swValue *p = ends[e];
    if (p->kind != VAL_POINT) continue;
    double off = 0;
    for (int k = 0; k < 3; k++) {
      const double on = xs[e][k] - (e == 0 && arm->kind == VAL_VEC ? arm->v[k] : 0);
      off += (p->v[k] - on) * (p->v[k] - on);
    }
    if (sqrt(off) > 1e-6 * element)
      snprintf(notes[e], 200, "; the point at (%.4g, %.4g, %.4g) m on '%s' acts on its "
               "nearest node, %d", p->v[0], p->v[1], p->v[2], scn->rod[p->rod].name, p->node);
  }
  diag_error(it->loc, "joint '%s': its two points are %s apart (%s and %s), and its spring "
             "would pull them together on the first step; move them together, or write "
             "allow_gap = true; if the gap is intended%s%s", it->name,
             length_text(g, sizeof g, gap), pa, pb, na, nb);
  return 0;
}

/* ---- limits ---- */

/* "-150 deg": an angle for messages. */
static const char *deg_text(char *buf, size_t len, double rad) {
  snprintf(buf, len, "%.4g deg", rad * 180.0 / M_PI);
  return buf;
}

/* An angle field (n components): a bare number is refused with the units
 * it could have, since a limit in radians and one in degrees differ by 57. */
static swValue angle_field(swSema *S, swScope *scope, const swFields *f, const char *key, int n,
                           const char *example) {
  const swAst *e = sema_field(f, key);
  swValue v = sema_eval(S, scope, e);
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, scope, v.word, v.loc, "name");
    return val_error();
  }
  if ((v.kind == VAL_NUM || v.kind == VAL_VEC) && dim_is_none(v.dim)) {
    diag_error(v.loc, "'%s' is an angle: write its unit (deg or rad), e.g. %s", key, example);
    return val_error();
  }
  char what[64];
  snprintf(what, sizeof what, "'%s'", key);
  return sema_expect_value(S, v, n, DIM_ANGLE, ast_strdup(S->a, what, strlen(what)));
}

/* A scene rod's tangent at t = 0 (rods start straight along 'direction';
 * a shaped rod's is not one: 0, the runtime checks its angle). */
static int rod_tangent(const swScene *sc, int rod, double t[3]) {
  if (sc->rod[rod].x0) return 0;
  const swValue *d = &sc->rod[rod].direction;
  if (d->kind != VAL_VEC || d->n != 3) return 0;
  double len = sqrt(d->v[0] * d->v[0] + d->v[1] * d->v[1] + d->v[2] * d->v[2]);
  if (!(len > 0)) return 0;
  for (int k = 0; k < 3; k++) t[k] = d->v[k] / len;
  return 1;
}

/* The hinge angle at t = 0 (the runtime's convention, joint.c): between two
 * rods, from rod a's tangent to rod b's about the axis; anchored, 0.
 * Returns 0 when a direction is not known here. */
static int hinge_angle0(const swScene *sc, const swSceneJoint *j, double *angle) {
  *angle = 0;
  if (j->rod_b < 0) return 1;
  double ta[3], tb[3], u[3], c[3];
  if (!rod_tangent(sc, j->rod_a, ta) || !rod_tangent(sc, j->rod_b, tb)) return 0;
  double len = sqrt(j->axis.v[0] * j->axis.v[0] + j->axis.v[1] * j->axis.v[1] +
                    j->axis.v[2] * j->axis.v[2]);
  for (int k = 0; k < 3; k++) u[k] = j->axis.v[k] / len;
  c[0] = ta[1] * tb[2] - ta[2] * tb[1];
  c[1] = ta[2] * tb[0] - ta[0] * tb[2];
  c[2] = ta[0] * tb[1] - ta[1] * tb[0];
  double tu_a = ta[0] * u[0] + ta[1] * u[1] + ta[2] * u[2];
  double tu_b = tb[0] * u[0] + tb[1] * u[1] + tb[2] * u[2];
  *angle = atan2(u[0] * c[0] + u[1] * c[1] + u[2] * c[2],
                 ta[0] * tb[0] + ta[1] * tb[1] + ta[2] * tb[2] - tu_a * tu_b);
  return 1;
}

/* range = (lower, upper) on a hinge, cone = ANGLE on a spherical joint,
 * limit_stiffness and limit_damping (joint.c, "Limits").  Values with params
 * are checked at the params' defaults (the simulator checks the values it
 * runs with).  Returns 0 after an error. */
static int joint_limits(swSema *S, swScope *scope, const swFields *f, const swAst *it,
                        swSceneJoint *j, int ends_ok) {
  static const swDim kR = {{1, 2, -2, -1}}, kRD = {{1, 2, -1, -1}};
  const char *kind = joint_kinds[j->kind];
  const swAst *range = sema_field(f, "range"), *cone = sema_field(f, "cone");
  int ok = 1;
  char lo[32], hi[32], a0[32];
  j->angle_min = j->angle_max = j->cone = val_error();
  if (range && j->kind != SW_JOINT_HINGE) {
    diag_error(range->loc, "'range' limits a hinge's angle, and joint '%s' is a %s joint%s",
               it->name, kind, j->kind == SW_JOINT_SPHERICAL ? " (its limit is a 'cone')" : "");
    ok = 0;
  } else if (range) {
    swValue r = angle_field(S, scope, f, "range", 2, "range = (-150 deg, 0 deg);");
    if (r.kind == VAL_ERROR) {
      ok = 0;
    } else {
      swValue c0 = r, c1 = r;
      c0.kind = c1.kind = VAL_NUM;
      c0.n = c1.n = 1;
      c1.v = r.v + 1;
      if (r.c) c1.c = r.c + 1;
      if (!(r.v[0] < r.v[1])) {
        diag_error(r.loc, "joint '%s': a range is (lower, upper) with lower < upper, got (%s, %s)",
                   it->name, deg_text(lo, sizeof lo, r.v[0]), deg_text(hi, sizeof hi, r.v[1]));
        ok = 0;
      } else {
        j->has_range = 1;
        j->angle_min = c0;
        j->angle_max = c1;
        double angle0;
        if (ends_ok && j->axis.kind == VAL_VEC && hinge_angle0(S->scene, j, &angle0) &&
            (angle0 < r.v[0] || angle0 > r.v[1])) {
          diag_error(r.loc, "joint '%s': its hinge angle at t = 0 is %s, outside its range (%s, %s): "
                     "the limit would throw the joint on the first step; widen the range or "
                     "start the rods inside it", it->name, deg_text(a0, sizeof a0, angle0),
                     deg_text(lo, sizeof lo, r.v[0]), deg_text(hi, sizeof hi, r.v[1]));
          ok = 0;
        }
      }
    }
  }
  if (cone && j->kind != SW_JOINT_SPHERICAL) {
    diag_error(cone->loc, "'cone' limits a spherical joint's swing, and joint '%s' is a %s%s",
               it->name, j->kind == SW_JOINT_HINGE ? "hinge" : "fixed joint",
               j->kind == SW_JOINT_HINGE ? " (its limit is a 'range')" : "");
    ok = 0;
  } else if (cone) {
    swValue c = angle_field(S, scope, f, "cone", 1, "cone = 60 deg;");
    if (c.kind == VAL_ERROR) {
      ok = 0;
    } else if (!(c.v[0] > 0 && c.v[0] < M_PI)) {
      diag_error(c.loc, "joint '%s': 'cone' is the largest swing, between 0 and 180 deg "
                 "(both excluded), got %s", it->name, deg_text(a0, sizeof a0, c.v[0]));
      ok = 0;
    } else {
      j->cone = c;
    }
  }
  const int limited = range || cone;
  j->limit_stiffness = sema_field(f, "limit_stiffness")
                       ? sema_field_value(S, scope, f, "limit_stiffness", 1, kR) : val_error();
  j->limit_damping = sema_field(f, "limit_damping")
                     ? sema_field_value(S, scope, f, "limit_damping", 1, kRD) : val_error();
  const swValue *coef[] = {&j->limit_stiffness, &j->limit_damping};
  const char *coef_key[] = {"limit_stiffness", "limit_damping"};
  for (int i = 0; i < 2; i++) {
    if (!sema_field(f, coef_key[i])) continue;
    if (coef[i]->kind == VAL_ERROR) {
      ok = 0;
    } else if (coef[i]->v[0] < 0) {
      diag_error(coef[i]->loc, "joint '%s': '%s' must not be negative", it->name, coef_key[i]);
      ok = 0;
    } else if (!limited) {
      diag_warning(sema_field(f, coef_key[i])->loc, "'%s' has no effect without a 'range' or "
                   "a 'cone'", coef_key[i]);
    }
  }
  if (j->undamped && j->limit_damping.kind == VAL_NUM && j->limit_damping.v[0] != 0) {
    diag_error(j->limit_damping.loc, "joint '%s' has damping = 0 (none) but a limit_damping; "
               "give both or neither", it->name);
    ok = 0;
  }
  return ok;
}

void sema_joint(swSema *S, swScope *scope, const swAst *it) {
  swSceneJoint j;
  memset(&j, 0, sizeof j);
  j.loc = it->loc;
  swSymbol *sym = sema_lookup_local(scope, it->name);
  j.name = sym ? sym->full : it->name;
  if (sym) sym->used = 1;
  if (!strcmp(it->text, "kinematic")) {   /* a frame imposed: sema_kinematic.c */
    sema_kinematic(S, scope, it, j.name);
    return;
  }
  int k;
  for (k = 0; k < 3; k++)
    if (!strcmp(it->text, joint_kinds[k])) break;
  if (k == 3) {
    const char *near = diag_suggest(it->text, joint_kinds, 3);
    if (near) diag_error(it->loc, "unknown kind of joint '%s'; did you mean '%s'?", it->text, near);
    else diag_error(it->loc, "unknown kind of joint '%s' (expected hinge, spherical, fixed or "
                    "kinematic)", it->text);
    return;
  }
  j.kind = (swJointKind)k;
  const swAst *args = it->kid[0];
  int ok = 1;
  if (args->nkid != 2 || args->kid[0]->name || args->kid[1]->name) {
    diag_error(it->loc, "%s() joins two points: %s(rod_a.end, rod_b.start), or a point and a "
               "fixed position: %s(rod.start, (0, 0, 0) m)", it->text, it->text, it->text);
    return;
  }
  /* the first end may be a point on a rod plus an arm carried by it:
   * humerus.end + (8.4, 0, 0) mm */
  const swAst *ea = ast_kid(args->kid[0], 0);
  swValue a, arm = val_error();
  if (ea->kind == AST_BINOP && (ea->op == '+' || ea->op == '-') &&
      (a = sema_eval(S, scope, ea->kid[0])).kind == VAL_POINT) {
    arm = sema_expect(S, scope, ea->kid[1], 3, DIM_LENGTH, "a joint's arm");
    if (arm.kind == VAL_ERROR) return;
    if (ea->op == '-') arm = val_neg(S->a, arm, ea->loc);
    if (!val_is_const(&arm)) {
      diag_error(arm.loc, "a joint's arm is fixed when compiling, but it depends on param '%s'",
                 arm.param);
      return;
    }
  } else {
    a = sema_eval(S, scope, ea);
  }
  const swAst *eb = ast_kid(args->kid[1], 0);
  swValue b = sema_eval(S, scope, eb);
  if (b.kind == VAL_VEC && eb->kind == AST_BINOP && (eb->op == '+' || eb->op == '-') &&
      sema_eval(S, scope, eb->kid[0]).kind == VAL_POINT)
    diag_warning(eb->loc, "the second end of joint '%s' is a fixed point in space, where this "
                 "position is at t = 0; an arm carried by a rod goes on the first end: "
                 "%s(ROD.end + ARM, ...)", it->name, it->text);
  if (a.kind == VAL_WORD) { sema_report_unknown(S, scope, a.word, a.loc, "name"); ok = 0; }
  if (b.kind == VAL_WORD) { sema_report_unknown(S, scope, b.word, b.loc, "name"); ok = 0; }
  if (a.kind != VAL_ERROR && a.kind != VAL_WORD && a.kind != VAL_POINT) {
    diag_error(a.loc, "the first end of a joint must be a point on a rod (rod.start, rod.end, "
               "rod.at(f))");
    ok = 0;
  }
  if (b.kind == VAL_POINT) {
    j.rod_b = b.rod;
    j.node_b = b.node;
    j.node_b_c = b.node_c;
    j.anchor = sema_vec3(S, 0, 0, 0, DIM_LENGTH, it->loc);
  } else if (b.kind == VAL_VEC || b.kind == VAL_NUM) {
    j.rod_b = -1;
    j.node_b = 0;
    j.anchor = sema_expect_value(S, b, 3, DIM_LENGTH, "a joint's fixed position");
    if (j.anchor.kind == VAL_ERROR) ok = 0;
  } else if (b.kind != VAL_WORD) {
    if (b.kind != VAL_ERROR)
      diag_error(b.loc, "the second end of a joint must be a point on a rod or a position");
    ok = 0;
  }
  j.arm_a = arm;
  if (a.kind == VAL_POINT) {
    j.rod_a = a.rod;
    j.node_a = a.node;
    j.node_a_c = a.node_c;
    if (b.kind == VAL_POINT && a.rod == b.rod) {
      diag_error(it->loc, "a joint must connect two different rods");
      ok = 0;
    }
  }
  swFields f;
  char what[128];
  snprintf(what, sizeof what, "joint '%s'", it->name);
  sema_fields(S, it, 1, what, joint_keys, NJOINT_KEYS, &f);
  if (ok && !joint_gap_ok(S, scope, &f, it, &a, &b, &arm)) ok = 0; /* after the ends are sound */
  swLoc loc = it->loc;
  j.axis = sema_field(&f, "axis") ? sema_field_value(S, scope, &f, "axis", 3, DIM_NONE)
           : sema_vec3(S, 0, 0, 0, DIM_NONE, loc);
  if (j.kind == SW_JOINT_HINGE && !sema_field(&f, "axis")) {
    sema_missing(&f, loc, "hinge '%s' needs an 'axis' (e.g. axis = (0, 1, 0);)", it->name);
    ok = 0;
  } else if (j.kind != SW_JOINT_HINGE && sema_field(&f, "axis")) {
    diag_warning(sema_field(&f, "axis")->loc, "'axis' has no effect on a %s joint", it->text);
  }
  if (j.axis.kind == VAL_VEC && j.kind == SW_JOINT_HINGE && sema_field(&f, "axis") &&
      !(fabs(j.axis.v[0]) + fabs(j.axis.v[1]) + fabs(j.axis.v[2]) > 0)) {
    diag_error(j.axis.loc, "a hinge's 'axis' must not be the zero vector");
    ok = 0;
  }
  static const swDim kN = {{1, 0, -2, 0}}, kD = {{1, 0, -1, 0}}, kR = {{1, 2, -2, -1}},
                     kRD = {{1, 2, -1, -1}};
  j.stiffness = sema_field(&f, "stiffness") ? sema_field_value(S, scope, &f, "stiffness", 1, kN)
                : val_num(S->a, 0, kN, loc);
  j.damping = sema_field(&f, "damping") ? sema_field_value(S, scope, &f, "damping", 1, kD)
              : val_num(S->a, 0, kD, loc);
  j.rot_stiffness = sema_field(&f, "rot_stiffness")
                    ? sema_field_value(S, scope, &f, "rot_stiffness", 1, kR) : val_num(S->a, 0, kR, loc);
  j.rot_damping = sema_field(&f, "rot_damping")
                  ? sema_field_value(S, scope, &f, "rot_damping", 1, kRD) : val_num(S->a, 0, kRD, loc);
  /* 0 lets the runtime choose a damping; "damping = 0" written out means
   * none at all (the runtime's undamped flag, both parts) */
  if (sema_field(&f, "damping") && j.damping.kind == VAL_NUM && j.damping.v[0] == 0 &&
      val_is_const(&j.damping)) {
    j.undamped = 1;
    if (j.rot_damping.kind == VAL_NUM && j.rot_damping.v[0] != 0) {
      diag_error(j.rot_damping.loc, "joint '%s' has damping = 0 (none) but a rot_damping; "
                 "give both or neither", it->name);
      ok = 0;
    }
  }
  const swValue *vals[] = {&j.axis, &j.stiffness, &j.damping, &j.rot_stiffness, &j.rot_damping,
                           &j.anchor};
  for (size_t i = 0; i < sizeof vals / sizeof vals[0]; i++) {
    if (vals[i]->kind == VAL_ERROR) ok = 0;
    else if (i >= 1 && i <= 4 && vals[i]->v[0] < 0) {
      diag_error(vals[i]->loc, "joint stiffness and damping must not be negative");
      ok = 0;
    }
  }
  if (!joint_limits(S, scope, &f, it, &j, ok && a.kind == VAL_POINT)) ok = 0;
  if (!ok || a.kind != VAL_POINT) return;
  swScene *sc = S->scene;
  if (sc->njoint == sc->capjoint) {
    sc->capjoint = sc->capjoint ? 2 * sc->capjoint : 8;
    sc->joint = realloc(sc->joint, (size_t)sc->capjoint * sizeof *sc->joint);
    if (!sc->joint) abort();
  }
  sc->joint[sc->njoint++] = j;
}

/* ---- actions ---- */

static const char *const actions[] = {"clamp", "gravity", "force", "torque", "velocity",
                                      "angular_velocity", "activate", "passive", "slide",
                                      "slide_in_plane", "sleeve"};
enum { NACTIONS = sizeof actions / sizeof actions[0] };

static void add_action(swSema *S, const swSceneAction *a) {
  swScene *sc = S->scene;
  if (sc->nact == sc->capact) {
    sc->capact = sc->capact ? 2 * sc->capact : 8;
    sc->act = realloc(sc->act, (size_t)sc->capact * sizeof *sc->act);
    if (!sc->act) abort();
  }
  sc->act[sc->nact++] = *a;
}

/* a 3-vector of dimension `want`, constant or scaled by a time signal */
static int action_value(swSema *S, swScope *scope, const swAst *e, swDim want, const char *what,
                        swSceneAction *act) {
  swValue v = sema_eval(S, scope, e);
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, scope, v.word, v.loc, "name");
    return 0;
  }
  if (v.kind == VAL_SIGNAL) {
    if (!dim_fits(want, v.dim)) {
      diag_error(v.loc, "%s expects %s, got %s", what, dim_describe(S->a, want),
                 dim_describe(S->a, v.dim));
      return 0;
    }
    if (v.sig->scale.kind != VAL_VEC || v.sig->scale.n != 3) {
      diag_error(v.loc, "%s expects a vector: multiply the signal by a direction, e.g. "
                 "(0, 0, 1) * ramp(...)", what);
      return 0;
    }
    act->vec = v.sig->scale;
    act->sig = v.sig;
    return 1;
  }
  act->vec = sema_expect_value(S, v, 3, want, what);
  act->sig = NULL;
  return act->vec.kind != VAL_ERROR;
}

const swAst *sema_action_until(const swAst *it) {
  const swAst *last = it->nkid ? it->kid[it->nkid - 1] : NULL;
  return last && last->kind == AST_ARG && last->name && !strcmp(last->name, "until") ? last : NULL;
}

/* "STATEMENT ... until T;" on a statement that holds nothing. */
void sema_until_misplaced(const swAst *it) {
  diag_error(sema_action_until(it)->loc, "'until' ends a hold: it applies to clamp, slide, "
             "slide_in_plane, sleeve, velocity and angular_velocity, not to '%s'", it->text);
}

/* The time a hold lets its end go (seconds, known when the scene is built:
 * a param may set it); VAL_ERROR when reported. */
static swValue hold_until(swSema *S, swScope *scope, const swAst *until) {
  swValue t = sema_eval(S, scope, until->kid[0]);
  if (t.kind == VAL_WORD) {
    sema_report_unknown(S, scope, t.word, t.loc, "name");
    return val_error();
  }
  if (t.kind == VAL_SIGNAL) {
    diag_error(t.loc, "'until' takes a time (until 0.5 s), not a signal of time");
    return val_error();
  }
  t = sema_expect_value(S, t, 1, DIM_TIME, "'until'");
  if (t.kind == VAL_ERROR || !sema_known_at_build(S, &t, "'until'")) return val_error();
  if (val_is_const(&t) && !sema_positive(S, &t, "'until'", "s")) return val_error();
  return t;
}

/* A slide's end is held by no other statement on its node (clamp, velocity
 * or another slide), and a sleeve's by none on its node or its frame (nor
 * angular_velocity): the two holds would contradict each other.  An
 * angular_velocity holds the end element's frame, not the node, so it goes
 * with a slide whichever of the two is written first. */
static int slide_alone(swSema *S, const swSceneAction *a, const char *word) {
  for (int i = 0; i < S->scene->nact; i++) {
    const swSceneAction *o = &S->scene->act[i];
    if (!o->is_bc || o->rod != a->rod || o->index != a->index) continue;
    const int sleeve = o->kind == SW_BC_SLEEVE || a->kind == SW_BC_SLEEVE;
    if (sleeve) {
      char first[300];
      diag_error(a->loc, "'%s' holds an end that another statement already holds (at %s): a "
                 "sleeve keeps the end node on a line and the end's frame turning about it, and "
                 "cannot share the end with any other hold", word,
                 diag_where_from(o->loc, a->loc, first, sizeof first));
      return 0;
    }
    if (o->kind == SW_BC_OMEGA || a->kind == SW_BC_OMEGA) continue;
    if (o->kind != SW_BC_SLIDE_LINE && o->kind != SW_BC_SLIDE_PLANE && a->kind != SW_BC_SLIDE_LINE &&
        a->kind != SW_BC_SLIDE_PLANE)
      continue;
    char first[300];
    diag_error(a->loc, "'%s' holds an end that another statement already holds (at %s): a "
               "slide keeps the end node on a line or plane, and cannot share it with clamp, "
               "velocity or another slide", word, diag_where_from(o->loc, a->loc, first, sizeof first));
    return 0;
  }
  return 1;
}

void sema_action(swSema *S, swScope *scope, const swAst *it) {
  const char *word = it->text;
  int k;
  for (k = 0; k < NACTIONS; k++)
    if (!strcmp(word, actions[k])) break;
  swLoc wloc = it->loc;
  if (k == NACTIONS) {
    /* the statements of the objective are sema_objective.c's, but a
     * misspelt one is only an unknown statement here */
    static const char *const all[] = {"clamp", "gravity", "force", "torque", "velocity",
                                      "angular_velocity", "activate", "passive", "maximize",
                                      "minimize", "penalty", "slide", "slide_in_plane", "sleeve"};
    const char *near = diag_suggest(word, all, (int)(sizeof all / sizeof all[0]));
    if (near) diag_error(wloc, "unknown statement '%s'; did you mean '%s'?", word, near);
    else
      diag_error(wloc, "unknown statement '%s' (expected clamp, slide, slide_in_plane, sleeve, gravity, "
                 "force, torque, velocity, angular_velocity, activate or passive)", word);
    return;
  }
  const int is_hold = k == 0 || k == 4 || k == 5 || k >= 8;
  const swAst *until = sema_action_until(it);
  if (until && !is_hold) {
    sema_until_misplaced(it);
    return;
  }
  if (k == 6) {
    sema_activate(S, scope, it);
    return;
  }
  if (k == 7) {
    sema_passive(S, scope, it);
    return;
  }
  int has_value = it->nkid - (until != NULL) == 2;
  if (k == 0 || k == 1) {
    if (has_value) {
      diag_error(it->kid[1]->loc, "'%s' takes no '= value'", word);
      return;
    }
  } else if (!has_value) {
    diag_error(it->kid[0]->loc, "'%s' needs a value: %s POINT = VALUE;", word, word);
    return;
  }
  if (k == 1) {   /* gravity (0, 0, -9.81) m/s^2;  or  ... * SIGNAL */
    swValue g = sema_eval(S, scope, it->kid[0]);
    swSignalVal *sig = NULL;
    if (g.kind == VAL_SIGNAL) {   /* a direction times a dimensionless signal */
      if (g.sig->scale.kind != VAL_VEC || !dim_is_none(g.sig->base)) {
        diag_error(g.loc, "gravity varying in time is an acceleration times a dimensionless "
                   "signal: gravity (0, 0, -9.81) m/s^2 * ramp(0, 1, over = 0.1 s);");
        return;
      }
      sig = g.sig;
      g = sema_expect_value(S, g.sig->scale, 3, dim_make(0, 1, -2, 0), "gravity");
    } else if (g.kind == VAL_WORD) {
      sema_report_unknown(S, scope, g.word, g.loc, "name");
      return;
    } else if (g.kind != VAL_ERROR) {
      g = sema_expect_value(S, g, 3, dim_make(0, 1, -2, 0), "gravity");
    }
    if (g.kind == VAL_ERROR) return;
    if (S->scene->gravity.kind != VAL_ERROR) {
      char first[300];
      diag_error(it->loc, "gravity is given twice (first at %s)",
                 diag_where_from(S->scene->gravity_loc, it->loc, first, sizeof first));
      return;
    }
    S->scene->gravity = g;
    S->scene->gravity_sig = sig;
    S->scene->gravity_loc = it->loc;
    return;
  }
  swValue p = sema_eval(S, scope, it->kid[0]);
  if (p.kind == VAL_WORD) {
    sema_report_unknown(S, scope, p.word, p.loc, "name");
    return;
  }
  if (p.kind == VAL_ERROR) {   /* a rod with errors: its value may have its own */
    if (has_value) {
      swValue v = sema_eval(S, scope, it->kid[1]);
      if (v.kind == VAL_WORD) sema_report_unknown(S, scope, v.word, v.loc, "name");
    }
    return;
  }
  if (p.kind != VAL_POINT) {
    diag_error(p.loc, "'%s' applies to a point on a rod (rod.start, rod.end, rod.at(f))", word);
    return;
  }
  char what[64];
  snprintf(what, sizeof what, "the point of '%s'", word);
  if (!sema_point_fixed(&p, what)) return;
  swSceneAction act;
  memset(&act, 0, sizeof act);
  act.loc = it->loc;
  act.rod = p.rod;
  int n = S->scene->rod[p.rod].nelem;
  if (is_hold) {   /* boundary conditions act on a rod's end */
    if (p.node != 0 && p.node != n) {
      diag_error(p.loc, "'%s' applies to the start or end of a rod, not to a point inside it",
                 word);
      return;
    }
    act.is_bc = 1;
    act.index = p.node == 0 ? 0 : 1;
    act.kind = k == 0 ? SW_BC_CLAMP : k == 4 ? SW_BC_VELOCITY : k == 5 ? SW_BC_OMEGA
             : k == 8 ? SW_BC_SLIDE_LINE : k == 9 ? SW_BC_SLIDE_PLANE : SW_BC_SLEEVE;
    act.until = until ? hold_until(S, scope, until) : val_error();
    if (until && act.until.kind == VAL_ERROR) return;
    const swSceneRod *rod = &S->scene->rod[p.rod];
    if ((until || k >= 8) && (rod->rigid || rod->implicit)) {
      diag_error(it->loc, "%s on the %s rod '%s' is not supported: a %s rod keeps its holds "
                 "whole for the whole run (clamp it, or join it with a joint)",
                 k >= 8 ? (k == 10 ? "a sleeve" : "a slide") : "a hold that ends ('until')", rod->rigid ? "rigid" : "implicit",
                 rod->name, rod->rigid ? "rigid" : "implicit");
      return;
    }
    if (k == 0) {
      act.vec = sema_vec3(S, 0, 0, 0, DIM_NONE, it->loc);
      add_action(S, &act);
      return;
    }
    if (k >= 8) { /* slide, sleeve POINT = DIRECTION;  slide_in_plane POINT = NORMAL; */
      swValue dir = sema_eval(S, scope, it->kid[1]);
      if (dir.kind == VAL_WORD) {
        sema_report_unknown(S, scope, dir.word, dir.loc, "name");
        return;
      }
      if (dir.kind == VAL_SIGNAL) {
        diag_error(dir.loc, "'%s' takes a fixed direction, not a signal of time", word);
        return;
      }
      char dir_what[64];
      snprintf(dir_what, sizeof dir_what, "'%s' (%s)", word, k != 9 ? "the line's direction" : "the plane's normal");
      act.vec = sema_expect_value(S, dir, 3, DIM_NONE, dir_what);
      if (act.vec.kind == VAL_ERROR || !sema_known_at_build(S, &act.vec, dir_what)) return;
      if (val_is_const(&act.vec) && act.vec.v[0] == 0 && act.vec.v[1] == 0 && act.vec.v[2] == 0) {
        diag_error(dir.loc, "%s must not be (0, 0, 0)", dir_what);
        return;
      }
      act.sig = NULL;
      if (slide_alone(S, &act, word)) add_action(S, &act);
      return;
    }
    swDim want = k == 4 ? dim_make(0, 1, -1, 0) : dim_make(0, 0, -1, 1);
    if (action_value(S, scope, it->kid[1], want, k == 4 ? "velocity" : "angular_velocity", &act) &&
        slide_alone(S, &act, word))
      add_action(S, &act);
    return;
  }
  act.is_bc = 0;
  act.kind = k == 2 ? SW_LOAD_FORCE : SW_LOAD_TORQUE;
  act.index = k == 2 ? p.node : (p.node < n ? p.node : n - 1);
  swDim want = k == 2 ? dim_make(1, 1, -2, 0) : dim_make(1, 2, -2, 0);
  if (action_value(S, scope, it->kid[1], want, word, &act)) add_action(S, &act);
}

/* ---- simulate and output ---- */

static const char *const simulate_keys[] = {"dt", "duration", "integrator"};

void sema_simulate(swSema *S, swScope *scope, const swAst *it) {
  if (S->has_simulate) {
    char first[300];
    diag_error(it->loc, "a second 'simulate' block (the first is at %s)",
               diag_where_from(S->simulate_loc, it->loc, first, sizeof first));
    return;
  }
  S->has_simulate = 1;
  S->simulate_loc = it->loc;
  swFields f;
  sema_fields(S, it, 0, "simulate", simulate_keys, 3, &f);
  swScene *sc = S->scene;
  if (sema_field(&f, "dt")) {
    swValue dt = sema_field_value(S, scope, &f, "dt", 1, DIM_TIME);
    if (dt.kind == VAL_NUM && sema_require_const(S, &dt, "'dt'") && sema_positive(S, &dt, "'dt'", "s")) {
      sc->dt = dt.v[0];
      sc->has_dt = 1;
      sc->dt_loc = sema_field(&f, "dt")->loc;
    }
  }
  if (sema_field(&f, "duration")) {
    swValue T = sema_field_value(S, scope, &f, "duration", 1, DIM_TIME);
    if (T.kind == VAL_NUM && sema_require_const(S, &T, "'duration'")) {
      if (T.v[0] < 0) diag_error(T.loc, "'duration' must not be negative");
      else {
        sc->duration = T.v[0];
        sc->has_duration = 1;
      }
    }
  }
  const swAst *integ = sema_field(&f, "integrator");
  if (integ) {
    /* in the order of swIntegrator */
    static const char *const names[] = {"verlet", "pefrl", "imex"};
    const char *w = sema_word(S, scope, integ, "integrator", names, 3);
    for (int k = 0; w && k < 3; k++)
      if (!strcmp(w, names[k])) sc->integrator = (swIntegrator)k;
  }
}

