/* sema_kinematic.c — joint NAME = kinematic(LEADER, FOLLOWER) { ... }
 *
 * Design.  A kinematic joint (Zhang et al. 2019, Suppl. Note 5.3; the
 * runtime's kinematic.c) makes the follower rod's element at FOLLOWER turn
 * with the leader rod's element at LEADER, and ties the follower's node there
 * to the leader's point by a spring-damper; no couple goes back.  The leader
 * is a point anywhere along its rod, ROD.at(f) taken as it is written (the
 * point f of the way along, on the element it falls in, not the nearest
 * node: barbs sit between the rachis' nodes); the follower is a node, and the
 * element it turns is the one the node starts (the last for ROD.end).  The
 * two must start at one place, as a joint's ends must, unless allow_gap =
 * true.  `reaction = POINT` sends the tie's reaction to that node instead of
 * the leader, scaled by `reaction_weight` (the reference's transfer of each
 * barb's load to the bone at its rachis' base, weighted by where the barb
 * sits).  Fields: stiffness (N/m, required), damping (N s/m, 0), reaction,
 * reaction_weight (a plain number, 1), allow_gap.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sema_int.h"

static const char *const kin_keys[] = {"stiffness", "damping", "reaction", "reaction_weight",
                                       "allow_gap"};
enum { NKIN_KEYS = sizeof kin_keys / sizeof kin_keys[0] };

static swValue point(swSema *S, swScope *scope, const swAst *e, const char *which,
                     const char *name) {
  swValue v = sema_eval(S, scope, e);
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, scope, v.word, v.loc, "name");
    return val_error();
  }
  if (v.kind != VAL_ERROR && v.kind != VAL_POINT) {
    diag_error(v.loc, "the %s of kinematic joint '%s' must be a point on a rod (rod.start, "
               "rod.end, rod.at(f)), not %s", which, name, sema_describe_value(S, &v));
    return val_error();
  }
  if (v.kind == VAL_POINT && v.node_c) {
    diag_error(v.loc, "the %s of kinematic joint '%s' is moved by param '%s'; a kinematic "
               "joint's points are fixed when compiling", which, name, v.param);
    return val_error();
  }
  return v;
}

void sema_kinematic(swSema *S, swScope *scope, const swAst *it, const char *name) {
  const swAst *args = it->kid[0];
  if (args->nkid != 2 || args->kid[0]->name || args->kid[1]->name) {
    diag_error(it->loc, "kinematic() joins a leader's point and a follower's: "
               "kinematic(bone.at(0.5), feather.start)");
    return;
  }
  swValue a = point(S, scope, ast_kid(args->kid[0], 0), "leader", name);
  swValue b = point(S, scope, ast_kid(args->kid[1], 0), "follower", name);
  swFields f;
  char what[160];
  snprintf(what, sizeof what, "kinematic joint '%s'", name);
  sema_fields(S, it, 1, what, kin_keys, NKIN_KEYS, &f);
  int ok = a.kind == VAL_POINT && b.kind == VAL_POINT;
  swSceneKinematic k;
  memset(&k, 0, sizeof k);
  k.name = name;
  k.loc = it->loc;
  k.reaction_rod = k.reaction_node = -1;
  static const swDim kN = {{1, 0, -2, 0}}, kD = {{1, 0, -1, 0}};
  if (!sema_field(&f, "stiffness")) {
    sema_missing(&f, it->loc, "%s needs a 'stiffness', the tie's spring (e.g. stiffness = "
                 "5e5 N/m;)", what);
    ok = 0;
  } else {
    k.stiffness = sema_field_value(S, scope, &f, "stiffness", 1, kN);
    if (k.stiffness.kind == VAL_ERROR) ok = 0;
    else if (!(k.stiffness.v[0] > 0)) {
      diag_error(k.stiffness.loc, "%s: 'stiffness' must be positive", what);
      ok = 0;
    }
  }
  k.damping = sema_field(&f, "damping") ? sema_field_value(S, scope, &f, "damping", 1, kD)
                                        : val_error();
  if (k.damping.kind == VAL_NUM && k.damping.v[0] < 0) {
    diag_error(k.damping.loc, "%s: 'damping' must not be negative", what);
    ok = 0;
  } else if (sema_field(&f, "damping") && k.damping.kind == VAL_ERROR) ok = 0;
  k.reaction_weight = sema_field(&f, "reaction_weight")
                      ? sema_field_value(S, scope, &f, "reaction_weight", 1, DIM_NONE)
                      : val_error();
  if (sema_field(&f, "reaction_weight") && k.reaction_weight.kind == VAL_ERROR) ok = 0;
  const swAst *re = sema_field(&f, "reaction");
  if (re) {
    swValue r = point(S, scope, re, "reaction", name);
    if (r.kind != VAL_POINT) ok = 0;
    else {
      k.reaction_rod = r.rod;
      k.reaction_node = r.node;
    }
  } else if (sema_field(&f, "reaction_weight")) {
    diag_warning(sema_field(&f, "reaction_weight")->loc, "%s: 'reaction_weight' scales a "
                 "reaction sent elsewhere ('reaction = POINT;'); without it the reaction acts "
                 "on the leader whole", what);
    k.reaction_weight = val_error();
  }
  int allow_gap = 0;
  if (sema_field(&f, "allow_gap")) {
    allow_gap = sema_truth(S, scope, sema_field(&f, "allow_gap"), "'allow_gap'");
    if (allow_gap < 0) ok = 0;
  }
  if (!ok) return;
  if (a.rod == b.rod) {
    diag_error(it->loc, "%s: a rod cannot lead itself", what);
    return;
  }
  const swScene *sc = S->scene;
  const int nl = sc->rod[a.rod].nelem, nf = sc->rod[b.rod].nelem;
  const double s = a.at * nl;
  k.leader_rod = a.rod;
  k.leader_elem = s >= nl ? nl - 1 : (int)floor(s);
  k.leader_xi = s - k.leader_elem;
  k.follower_rod = b.rod;
  k.follower_node = b.node;
  k.follower_elem = b.node >= nf ? nf - 1 : b.node;
  if (sc->rod[b.rod].rigid || sc->rod[b.rod].implicit) {
    diag_error(b.loc, "%s: the follower '%s' must be an elastic, explicit rod: its element's "
               "frame is imposed (not rigid = true, not implicit = true)", what, sc->rod[b.rod].name);
    return;
  }
  for (int i = 0; i < sc->nkin; i++)
    if (sc->kin[i].follower_rod == k.follower_rod && sc->kin[i].follower_elem == k.follower_elem) {
      char first[300];
      diag_error(it->loc, "%s turns element %d of '%s', which kinematic joint '%s' turns already "
                 "(%s)", what, k.follower_elem + 1, sc->rod[b.rod].name, sc->kin[i].name,
                 diag_where_from(sc->kin[i].loc, it->loc, first, sizeof first));
      return;
    }
  double xf[3];
  sema_node_position(sc, &b, xf);
  if (!allow_gap) {
    const double gap = sqrt((a.v[0] - xf[0]) * (a.v[0] - xf[0]) + (a.v[1] - xf[1]) * (a.v[1] - xf[1]) +
                            (a.v[2] - xf[2]) * (a.v[2] - xf[2]));
    const double elem = sc->rod[b.rod].length.v[0] / nf;
    if (gap > 1e-6 * elem) {
      diag_error(it->loc, "%s: the follower's node starts %.3g mm from the leader's point; its "
                 "spring would pull them together on the first step (write allow_gap = true; if "
                 "that is meant)", what, gap * 1e3);
      return;
    }
  }
  swScene *scn = S->scene;
  if (scn->nkin == scn->capkin) {
    scn->capkin = scn->capkin ? 2 * scn->capkin : 8;
    scn->kin = realloc(scn->kin, (size_t)scn->capkin * sizeof *scn->kin);
    if (!scn->kin) abort();
  }
  scn->kin[scn->nkin++] = k;
}
