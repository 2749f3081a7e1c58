/* boundary.c — boundary conditions at rod ends: clamps and prescribed
 * velocity or angular velocity with a time profile.
 *
 * A clamp holds the end node in place and the end cross-section at its
 * initial orientation Q_c.  The cross-section at the very end of the rod is
 * not any element's frame (element frames sit at element centres), so the
 * clamp is modelled as one more Voronoi domain of rest length l^/2 between the
 * fixed frame Q_c and the end element, carrying the end element's bending
 * stiffness: the end element stays free to rotate against it.  Fixing the end
 * element's frame instead (PyElastica's OneEndFixedBC) makes the first half
 * element rigid: the bending compliance of the first half element is lost,
 * an error of first order in the element length.  With the clamp domain the
 * cantilever's static error falls at second order (tests/runtime/
 * test_statics.c measures the order).
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
 *
 * Partial holds.  A slide keeps the end node on a line (free along the unit
 * direction a) or on a plane (free across its unit normal n) through its
 * start position: the kick's free velocity is projected onto the free
 * subspace, v_new = (v_free . a) a, or v_new = v_free - (v_free . n) n.  The
 * constraint force m (v_new - v_free) / h is then normal to the free
 * subspace, so the hold does no work along it and takes no share of a load
 * along it: a dead load along the line reaches the rod whole.  The node's
 * positions stay on the line or plane (each drift moves it by h v_new).
 * The end element's frame is free (hold it with an angular velocity).  A
 * sleeve is a slide on a line whose end element may turn only about the
 * line: its free angular velocity w (material frame) is projected onto the
 * line's direction there, w_new = (w_free . a_m) a_m with a_m = Q a, so the
 * constraint couple J (w_new - w_free) / h is across the line, does no work
 * about it, and a dead torque about the line (a twisting couple) reaches
 * the rod whole; the element's d3, along the line at the start, stays so.
 *
 * Release.  A condition with `until` > 0 acts on the kicks whose loads are
 * taken before that time; at the first kick at or after it (sw_bc_release)
 * it lets its end go for good (d->bc_free[k] = 1, state that a restart
 * keeps).  The end keeps the velocity the hold left it with: nothing jumps.
 * A clamp's domain (below) goes with it; the elastic energy it stored is
 * booked as work the clamp takes back, W -= U_domain, so that the energy
 * diagnostic K + U - W stays level across the release.
 */
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* The velocity a slide leaves its node with: v projected onto the line along
 * the unit a, or onto the plane across the unit normal a (the header). */
static void slide_velocity(const swBCDesc *b, const double v[3], double out[3]) {
  const double along = sw_v3_dot(v, b->vec);
  for (int c = 0; c < 3; c++)
    out[c] = b->kind != SW_BC_SLIDE_PLANE ? along * b->vec[c] : v[c] - along * b->vec[c];
}

/* Prescribed node velocity (lab) and element angular velocity (material) of
 * boundary condition b at time t; a slide's node velocity is its free one
 * (d->v, after the kick) projected.  Returns which of the two it
 * constrains: bit 0 the node, bit 1 the element. */
static int bc_target(const swModel *m, const swData *d, const swBCDesc *b, double t,
                     int *node, int *elem, double vnode[3], double welem[3]) {
  int n = m->rod_nelem[b->rod];
  *node = m->node_adr[b->rod] + (b->end ? n : 0);
  *elem = m->elem_adr[b->rod] + (b->end ? n - 1 : 0);
  memset(vnode, 0, 3 * sizeof(double));
  memset(welem, 0, 3 * sizeof(double));
  switch (b->kind) {
  case SW_BC_CLAMP:
    return 1; /* the frame is held by the clamp couple of sw_bc_loads */
  case SW_BC_VELOCITY: {
    double g = sw_signal_eval(&b->signal, t);
    sw_v3_scale(vnode, b->vec, g);
    return 1;
  }
  case SW_BC_OMEGA: {
    double g = sw_signal_eval(&b->signal, t), wl[3], Q[9];
    sw_v3_scale(wl, b->vec, g);
    sw_getQ(m, d->Q, *elem, Q);
    sw_mat_vec(welem, Q, wl);
    return 2;
  }
  case SW_BC_SLIDE_LINE:
  case SW_BC_SLIDE_PLANE: {
    double v[3];
    for (int c = 0; c < 3; c++) v[c] = SW_AT(m, d->v, *node, c);
    slide_velocity(b, v, vnode);
    return 1;
  }
  case SW_BC_SLEEVE: { /* the node as on a line, the frame turning about it (the header) */
    double v[3], w[3], a[3], Q[9];
    for (int c = 0; c < 3; c++) v[c] = SW_AT(m, d->v, *node, c), w[c] = SW_AT(m, d->omega, *elem, c);
    slide_velocity(b, v, vnode);
    sw_getQ(m, d->Q, *elem, Q);
    sw_mat_vec(a, Q, b->vec);
    sw_v3_scale(welem, a, sw_v3_dot(w, a));
    return 3;
  }
  }
  return 0;
}


/* Whether condition k still holds its end. */
static inline int bc_holds(const swData *d, int k) { return d->bc_free[k] == 0.0; }

/* Whether a condition lets its end go at a kick whose loads are those of
 * time t (the header, "Release"). */
static inline int bc_due(const swModel *m, const swData *d, int k, double t) {
  return m->bc[k].until > 0 && bc_holds(d, k) && t >= m->bc[k].until;
}

int sw_bc_release_due(const swModel *m, const swData *d, double t) {
  for (int k = 0; k < m->nbc; k++)
    if (bc_due(m, d, k, t)) return 1;
  return 0;
}

static double clamp_domain_energy(const swModel *m, const swData *d, const swBCDesc *b);

void sw_bc_release(const swModel *m, swData *d, double t) {
  for (int k = 0; k < m->nbc; k++) {
    if (!bc_due(m, d, k, t)) continue;
    if (m->bc[k].kind == SW_BC_CLAMP && !sw_rod_is_rigid(m, m->bc[k].rod))
      d->work -= clamp_domain_energy(m, d, &m->bc[k]); /* the domain's energy, taken back */
    d->bc_free[k] = 1;
  }
}

void sw_apply_bc_velocity(const swModel *m, swData *d, double t) {
  for (int k = 0; k < m->nbc; k++) {
    if (sw_rod_is_rigid(m, m->bc[k].rod) || !bc_holds(d, k)) continue; /* a clamp holds the body (rigid.c) */
    int node, elem;
    double vn[3], we[3];
    int what = bc_target(m, d, &m->bc[k], t, &node, &elem, vn, we);
    if (what & 1) sw_set3(m, d->v, node, vn);
    if (what & 2) sw_set3(m, d->omega, elem, we);
  }
}

/* The first condition that may hold a node at slot `lo` or later: when the
 * conditions are in slot order (as the compiler emits them, rod by rod),
 * a block of the fused sweep looks only at its own, not at all of them. */
static int first_bc(const swModel *m, int lo) {
  if (!m->bc_slot_order) return 0;
  int a = 0, z = m->nbc; /* bisection: the first k with node >= lo */
  while (a < z) {
    const int mid = (a + z) / 2;
    if (sw_bc_node(m, &m->bc[mid]) < lo) a = mid + 1; else z = mid;
  }
  return a;
}

/* Called right after a free kick of size h: v_free = v_old + h F / m.  The
 * prescribed values are those of time t (the integrator passes the
 * midpoint of the drift the new velocities will be used for).  Only the
 * conditions whose end node is in [lo, hi) (a thread's slots, or a block of
 * the fused sweep, whose loads are at i - so: internal.h, "Scratch
 * windows"), each booking its work in work[k], which the integrator adds
 * up in condition order. */
void sw_bc_kick(const swModel *m, swData *d, double h, double t, int lo, int hi, int so, double *work) {
  for (int k = first_bc(m, lo); k < m->nbc; k++) {
    if (sw_rod_is_rigid(m, m->bc[k].rod)) continue; /* a clamp holds the body (rigid.c) */
    const swBCDesc *b = &m->bc[k];
    const int end_node = sw_bc_node(m, b);
    if (end_node >= hi && m->bc_slot_order) break;
    if (end_node < lo || end_node >= hi) continue; /* before the signal is evaluated */
    if (!bc_holds(d, k)) { /* let go: the end's free kick stands */
      work[k] = 0;
      continue;
    }
    int node, elem;
    double vn[3], we[3];
    int what = bc_target(m, d, b, t, &node, &elem, vn, we);
    /* The kick booked the external load's work with the free velocity,
     * h f . (v_old + v_free) / 2; rebook it with the prescribed one and add
     * the constraint force's, h f_c = m (v_new - v_free). */
    double w = 0;
    if (what & 1) {
      double mass = d->mass_now[node];
      for (int c = 0; c < 3; c++) {
        const double F = SW_AT(m, d->force, node - so, c), ef = SW_AT(m, d->ext_force, node - so, c);
        double v_free = SW_AT(m, d->v, node, c), v_old = v_free - h * F * d->inv_mass_now[node];
        w -= 0.5 * h * ef * (v_old + v_free);
        w += 0.5 * (h * ef + mass * (vn[c] - v_free)) * (v_old + vn[c]);
        SW_AT(m, d->v, node, c) = vn[c];
      }
    }
    if (what & 2) {
      double e = sw_inertia_dilatation(m, d, elem);
      for (int c = 0; c < 3; c++) {
        const double T = SW_AT(m, d->torque, elem - so, c), et = SW_AT(m, d->ext_torque, elem - so, c);
        double Je = SW_AT(m, d->inertia_now, elem, c) / e;
        double w_free = SW_AT(m, d->omega, elem, c), w_old = w_free - h * T / Je;
        w -= 0.5 * h * et * (w_old + w_free);
        w += 0.5 * (h * et + Je * (we[c] - w_free)) * (w_old + we[c]);
        SW_AT(m, d->omega, elem, c) = we[c];
      }
    }
    work[k] = w;
  }
}

/* The clamp domain of boundary condition b: rest curvature zero with respect
 * to the clamp frame.  kappa, couple and the rotation come out; the return
 * value is the end element.  The couple follows the rod's law (rod.c): with
 * Gazzola's B^ kappa / eps^3, with the variational law B^ kappa and the
 * caller adds its beta term. */
static int clamp_domain(const swModel *m, const swData *d, const swBCDesc *b,
                        double kappa[3], double couple[3], double *D) {
  int n = m->rod_nelem[b->rod];
  int e = m->elem_adr[b->rod] + (b->end ? n - 1 : 0);
  double Qc[9], Qe[9], phi[3];
  sw_getQ(m, m->Q0, e, Qc);
  sw_getQ(m, d->Q, e, Qe);
  /* the domain lies clamp -> element at the start, element -> clamp at the end */
  if (b->end) sw_frame_log(phi, Qe, Qc); else sw_frame_log(phi, Qc, Qe);
  *D = 0.5 * m->rest_len[e];
  /* the end element's own B^ (model.c: clamp_bend) */
  double eps = d->dilatation[e];
  double inv_eps3 = m->rod_law[b->rod] == SW_LAW_VARIATIONAL ? 1.0 : 1.0 / (eps * eps * eps);
  for (int k = 0; k < 3; k++) {
    kappa[k] = phi[k] / *D;
    couple[k] = SW_AT(m, sw_swell_clamp_bend(m, d), e, k) * kappa[k] * inv_eps3;
  }
  return e;
}

/* The clamp couples on the end elements in [lo, hi) (a thread's slots, or a
 * block of the fused sweep: couples at i - so). */
void sw_bc_loads(const swModel *m, swData *d, int lo, int hi, int so) {
  for (int k = first_bc(m, lo); k < m->nbc; k++) { /* the end element is the node's slot or the one before */
    const swBCDesc *b = &m->bc[k];
    if (sw_bc_node(m, b) > hi && m->bc_slot_order) break;
    if (b->kind != SW_BC_CLAMP || !bc_holds(d, k)) continue;
    const int end = m->elem_adr[b->rod] + (b->end ? m->rod_nelem[b->rod] - 1 : 0);
    if (end < lo || end >= hi) continue;
    double kappa[3], c[3], h[3], D;
    int e = clamp_domain(m, d, b, kappa, c, &D);
    sw_v3_cross(h, kappa, c);
    /* as in rod.c: the element before the domain gets +c, the one after -c,
     * and each gets half of kappa x c D^ (the clamp's half is not needed) */
    double sgn = b->end ? 1.0 : -1.0;
    if (m->rod_law[b->rod] == SW_LAW_VARIATIONAL) {
      /* the beta term of rod.c's variational couple: c += beta phi x (phi x c) */
      double kkc[3];
      sw_v3_cross(kkc, kappa, h);
      const double beta = sw_dexpinv_beta(D * D * sw_v3_dot(kappa, kappa)) * D * D;
      for (int i = 0; i < 3; i++) c[i] += beta * kkc[i];
    }
    for (int i = 0; i < 3; i++) SW_AT(m, d->torque, e - so, i) += sgn * c[i] + 0.5 * h[i] * D;
  }
}

/* The elastic energy of a clamp's domain, 1/2 D^ B^ kappa . kappa. */
static double clamp_domain_energy(const swModel *m, const swData *d, const swBCDesc *b) {
  double kappa[3], c[3], D, u = 0;
  int e = clamp_domain(m, d, b, kappa, c, &D);
  for (int i = 0; i < 3; i++) u += 0.5 * D * SW_AT(m, sw_swell_clamp_bend(m, d), e, i) * kappa[i] * kappa[i];
  return u;
}

double sw_bc_energy(const swModel *m, const swData *d) {
  double u = 0;
  for (int k = 0; k < m->nbc; k++)
    if (m->bc[k].kind == SW_BC_CLAMP && bc_holds(d, k)) u += clamp_domain_energy(m, d, &m->bc[k]);
  return u;
}
