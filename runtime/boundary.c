/* boundary.c — boundary conditions at rod ends: clamps and prescribed
 * velocity or angular velocity with a time profile.
 *
 * Design.  A boundary condition is a constraint on the velocities of one end
 * (node 0 and element 0, or node n and element n-1).  The integrator kicks
 * every node and element freely and then calls sw_bc_kick(), which overwrites
 * the constrained velocities with their prescribed values and books the work
 * the constraint did: the constraint force is whatever makes the kick land on
 * the prescribed velocity, F_c = m (v_new - v_free) / h, and its work over
 * the kick is F_c . (v_old + v_new)/2 h, the same midpoint rule the
 * integrator uses for the loads.  Positions of a clamped end never move
 * because its velocities are zero after every kick.
 */
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* Prescribed node velocity (lab) and element angular velocity (material) of
 * boundary condition b at time t.  Returns which of the two it constrains:
 * bit 0 the node, bit 1 the element. */
static int bc_target(const swModel *m, const swData *d, const swBCDesc *b, double t,
                     int *node, int *elem, double vnode[3], double welem[3]) {
  int n = m->rod_nelem[b->rod];
  *node = m->node_adr[b->rod] + (b->end ? n : 0);
  *elem = m->elem_adr[b->rod] + (b->end ? n - 1 : 0);
  memset(vnode, 0, 3 * sizeof(double));
  memset(welem, 0, 3 * sizeof(double));
  switch (b->kind) {
  case SW_BC_CLAMP:
    return 3;
  case SW_BC_VELOCITY: {
    double g = sw_signal_eval(&b->signal, t);
    sw_v3_scale(vnode, b->vec, g);
    return 1;
  }
  case SW_BC_OMEGA: {
    double g = sw_signal_eval(&b->signal, t), wl[3];
    sw_v3_scale(wl, b->vec, g);
    sw_mat_vec(welem, d->Q + 9 * *elem, wl);
    return 2;
  }
  }
  return 0;
}

void sw_apply_bc_velocity(const swModel *m, swData *d, double t) {
  for (int k = 0; k < m->nbc; k++) {
    int node, elem;
    double vn[3], we[3];
    int what = bc_target(m, d, &m->bc[k], t, &node, &elem, vn, we);
    if (what & 1) memcpy(d->v + 3 * node, vn, sizeof vn);
    if (what & 2) memcpy(d->omega + 3 * elem, we, sizeof we);
  }
}

/* Called right after a free kick of size h: v_free = v_old + h F / m. */
void sw_bc_kick(const swModel *m, swData *d, double h) {
  for (int k = 0; k < m->nbc; k++) {
    int node, elem;
    double vn[3], we[3];
    int what = bc_target(m, d, &m->bc[k], d->time, &node, &elem, vn, we);
    if (what & 1) {
      double *v = d->v + 3 * node, *F = d->force + 3 * node, mass = m->mass[node];
      for (int c = 0; c < 3; c++) {
        double v_old = v[c] - h * F[c] * m->inv_mass[node];
        d->work += mass * (vn[c] - v[c]) * 0.5 * (v_old + vn[c]);
        v[c] = vn[c];
      }
    }
    if (what & 2) {
      double *w = d->omega + 3 * elem, *T = d->torque + 3 * elem, e = d->dilatation[elem];
      for (int c = 0; c < 3; c++) {
        double Je = m->inertia[3 * elem + c] / e;
        double w_old = w[c] - h * T[c] / Je;
        d->work += Je * (we[c] - w[c]) * 0.5 * (w_old + we[c]);
        w[c] = we[c];
      }
    }
  }
}
