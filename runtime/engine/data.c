/* data.c — the mutable state of a simulation: swData.
 *
 * Design.  sw_data_new allocates every array a step touches, sized by the
 * model (planar per-slot arrays of m->stride doubles, 64-byte aligned;
 * per-joint, per-filament, per-body rows; the scratch of the implicit
 * solvers, the probes and the contact grid), so that nothing allocates after
 * it; sw_reset puts the state at the model's rest configuration at t = 0.
 * One model may have any number of states.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"
#include "model.h"

void sw_data_free(swData *d) {
  if (!d) return;
  free(d->x); free(d->v); free(d->Q); free(d->omega);
  free(d->length); free(d->dilatation); free(d->shortest); free(d->shortest_time);
  free(d->sigma); free(d->stress); free(d->vor_dilatation); free(d->kappa); free(d->couple);
  free(d->force); free(d->torque); free(d->ext_force); free(d->ext_torque);
  free(d->scratch_f); free(d->scratch_h); free(d->scratch_flag); free(d->scratch_phi);
  free(d->chunk_sum); free(d->bc_work); free(d->bc_free); free(d->joint_scratch); free(d->team);
  free(d->joint_force); free(d->joint_angle); free(d->joint_limit_torque);
  free(d->kinematic_force); free(d->kinematic_turn); free(d->kinematic_delta);
  free(d->kinematic_work);
  free(d->fil_activation); free(d->fil_stretch); free(d->fil_rate); free(d->fil_tension); free(d->fil_sys);
  free(d->ring_row); free(d->ring_imp); free(d->hold);
  free(d->rod_strain_peak); free(d->rod_bend_peak); free(d->muscle_spread_peak);
  free(d->rigid_X); free(d->rigid_V); free(d->rigid_R); free(d->rigid_L); free(d->rigid_omega);
  free(d->rigid_load); free(d->rigid_sys); free(d->rigid_lanes); free(d->implicit_sys);
  sw_probe_data_free(d);
  sw_swell_data_free(d);
  /* the contact grid's scratch (contact.c, through the environment's data_new) */
  free(d->obstacle_contact); free(d->obstacle_box); /* obstacle.c's, likewise */
  free(d->obstacle_anchor); free(d->obstacle_anchor_old);
  free(d->contact_anchor); free(d->contact_anchor_old);
  free(d->contact_cell); free(d->contact_bucket); free(d->contact_sorted);
  free(d->contact_start); free(d->contact_occupied); free(d->contact_sorted_cell);
  free(d);
}

swData *sw_data_new(const swModel *m) {
  swData *d = calloc(1, sizeof *d);
  if (!d) return NULL;
  if (!sw_swell_data_new(m, d)) { free(d); return NULL; }
  d->x = sw_palloc(m, 3); d->v = sw_palloc(m, 3); d->Q = sw_palloc(m, 9); d->omega = sw_palloc(m, 3);
  d->length = sw_palloc(m, 1); d->dilatation = sw_palloc(m, 1);
  d->shortest = sw_palloc(m, 1); d->shortest_time = sw_palloc(m, 1);
  d->sigma = sw_palloc(m, 3); d->stress = sw_palloc(m, 3);
  d->vor_dilatation = sw_palloc(m, 1); d->kappa = sw_palloc(m, 3); d->couple = sw_palloc(m, 3);
  d->force = sw_palloc(m, 3); d->torque = sw_palloc(m, 3);
  d->ext_force = sw_palloc(m, 3); d->ext_torque = sw_palloc(m, 3);
  d->scratch_f = sw_palloc(m, 3); d->scratch_h = sw_palloc(m, 3);
  d->scratch_flag = sw_palloc(m, 1); d->scratch_phi = sw_palloc(m, 8);
  d->chunk_sum = sw_dalloc((size_t)sw_nchunk(m, m->stride));
  d->bc_work = sw_dalloc((size_t)m->nbc);
  d->bc_free = sw_dalloc((size_t)m->nbc);
  d->joint_scratch = sw_dalloc(SW_JOINT_ROW * (size_t)m->njoint);
  d->threads = 1;
  d->team_size = 1;
  d->team = aligned_alloc(64, sizeof(swTeam));
  if (d->team) memset(d->team, 0, sizeof(swTeam));
  d->joint_force = sw_dalloc(3 * (size_t)m->njoint); d->joint_angle = sw_dalloc((size_t)m->njoint);
  d->joint_limit_torque = sw_dalloc(3 * (size_t)m->njoint);
  d->kinematic_force = sw_dalloc(3 * (size_t)m->nkinematic);
  d->kinematic_turn = sw_dalloc(3 * (size_t)m->nkinematic);
  d->kinematic_delta = sw_dalloc(3 * (size_t)m->nkinematic);
  d->kinematic_work = sw_dalloc((size_t)m->nkinematic);
  size_t F = (size_t)m->nfil;
  d->fil_activation = sw_dalloc(F); d->fil_stretch = sw_dalloc(F); d->fil_rate = sw_dalloc(F);
  d->fil_tension = sw_dalloc(F);
  d->fil_sys = sw_dalloc(8 * F);
  d->ring_row = sw_dalloc(SW_RING_ROW * (size_t)m->nring);
  d->ring_imp = sw_dalloc(SW_RING_IMP * (size_t)m->nring);
  d->hold = sw_dalloc(sw_hold_size(m));
  d->rod_strain_peak = sw_dalloc((size_t)m->nrod);
  d->rod_bend_peak = sw_dalloc((size_t)m->nrod);
  d->muscle_spread_peak = sw_dalloc((size_t)m->nmuscle);
  if (!d->x || !d->v || !d->Q || !d->omega || !d->length || !d->dilatation ||
      !d->shortest || !d->shortest_time ||
      !d->sigma || !d->stress || !d->vor_dilatation || !d->kappa ||
      !d->couple || !d->force || !d->torque || !d->ext_force || !d->ext_torque ||
      !d->scratch_f || !d->scratch_h || !d->scratch_flag || !d->scratch_phi ||
      !d->chunk_sum || !d->bc_work || !d->bc_free || !d->joint_scratch || !d->team || !d->joint_force ||
      !d->joint_angle || !d->joint_limit_torque || !d->kinematic_force || !d->kinematic_turn || !d->kinematic_delta || !d->kinematic_work || !d->fil_activation || !d->fil_stretch ||
      !d->fil_rate || !d->fil_tension || !d->fil_sys || !d->ring_row || !d->ring_imp || !d->hold ||
      !d->rod_strain_peak || !d->rod_bend_peak || !d->muscle_spread_peak) {
    sw_data_free(d);
    return NULL;
  }
  size_t B = (size_t)m->nrigid;
  d->rigid_X = sw_dalloc(3 * B); d->rigid_V = sw_dalloc(3 * B); d->rigid_R = sw_dalloc(9 * B);
  d->rigid_L = sw_dalloc(3 * B); d->rigid_omega = sw_dalloc(3 * B); d->rigid_load = sw_dalloc(6 * B);
  d->rigid_sys = sw_dalloc(sw_rigid_joints_scratch(m));
  d->rigid_lanes = sw_dalloc(sw_rigid_lanes_scratch(m));
  d->implicit_sys = sw_dalloc(sw_implicit_scratch(m));
  if (!d->rigid_X || !d->rigid_V || !d->rigid_R || !d->rigid_L || !d->rigid_omega ||
      !d->rigid_load || !d->rigid_sys || !d->rigid_lanes || !d->implicit_sys ||
      !sw_probe_data_new(m, d) ||
      (sw_env_ops(m) && !sw_env_ops(m)->data_new(m, d))) { /* the contact grid's scratch */
    sw_data_free(d);
    return NULL;
  }
  sw_reset(m, d);
  return d;
}

void sw_reset(const swModel *m, swData *d) {
  d->time = 0;
  d->step = 0;
  d->held = d->whole = 0;
  d->work = 0;
  d->error[0] = 0;
  d->swell_time = NAN; /* the geometry at t = 0, set by the loads below */
  const size_t plane = sizeof(double) * (size_t)m->stride;
  memcpy(d->x, m->x0, 3 * plane);
  memcpy(d->Q, m->Q0, 9 * plane);
  memset(d->v, 0, 3 * plane);
  memset(d->omega, 0, 3 * plane);
  for (int i = 0; i < m->stride; i++) {
    d->dilatation[i] = d->vor_dilatation[i] = d->shortest[i] = 1.0;
    d->shortest_time[i] = 0;
  }
  if (m->nrigid) sw_rigid_reset(m, d);
  if (m->nimplicit) sw_implicit_reset(m, d); /* no factorisation kept */
  sw_probe_reset(m, d);
  if (d->obstacle_anchor) d->obstacle_anchor[0] = 0; /* no friction anchor yet (obstacle.c) */
  d->contact_pairs = 0; /* contact.c's figures are those of the last evaluation */
  d->contact_max_overlap = 0;
  if (d->contact_anchor) d->contact_anchor[0] = 0; /* no friction anchor yet (contact.c) */
  d->contact_stuck = d->contact_slipping = 0;
  d->friction_full = 0;
  sw_rigidity_reset(m, d);
  if (m->nbc) memset(d->bc_free, 0, sizeof *d->bc_free * (size_t)m->nbc); /* every hold holds */
  sw_apply_bc_velocity(m, d, 0.0);
  sw_internal_loads(m, d); /* strains of the initial state */
  if (m->nmuscle) {
    sw_muscle_ops(m)->reset(m, d);
    sw_muscle_ops(m)->loads(m, d); /* stretch and tension of the initial state */
  }
  for (int j = 0; j < m->njoint; j++) {
    d->joint_angle[j] = m->joint_angle0[j]; /* the reference of the unwrapping */
    sw_joint_measure(m, d, j);
  }
}
