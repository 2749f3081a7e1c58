/* muscle_via.c — muscle paths through via points: frictionless rings on bones.
 *
 * Design.  A muscle with via points is laid, at t = 0, along the polyline
 * P_0 = start, P_1 .. P_K = the via points, P_{K+1} = end, the way a path
 * point model (OpenSim's PathPoint, MuJoCo's tendon sites) routes a muscle
 * around a joint.  Here the path is made of filaments, Cosserat rods, so the
 * via points cannot be kinks of a massless line: each is a ring the filament
 * slides through.
 *
 * Layout.  Each filament's n elements are shared out among the K+1 segments
 * in proportion to their lengths (largest remainders, at least one each), so
 * that every via point is a node at t = 0 and the ring starts with no gap;
 * the nodes of a segment are spread evenly along it, and each element's
 * frame has d3 along its segment and d1 carried from segment to segment by
 * parallel transport (no twist at the bends).  The rest length is the laid
 * length of each element, so l0 = sum |P_{j+1} - P_j|, the path's length,
 * and eta = l / l0 = 1 at rest.  The rest curvature is zero: the filament is
 * straight at rest (a muscle's fibres are), the bend at a via point is held
 * by the ring, not built into the material.  A kink in the rest shape would
 * travel with the material as the filament slides, and pushing it through
 * the ring would cost bending energy, a resistance to sliding that no
 * frictionless ring has; with a straight rest shape the bending energy at
 * the ring is the same wherever the material is.  (A filament's bending
 * stiffness E I is small next to its tension: for 10 kPa tissue of 2 mm
 * radius, E I / T ~ 1e-7 m^2 at 1 N.)
 *
 * The ring law.  Via point k of filament f is the point p(t), carried by
 * element e of its bone: p = x_c + Q_e^T o, x_c the element's centre, o its
 * offset in the element's material frame at t = 0 (or fixed in space).  The
 * filament's contact is the closest point of its centreline to p,
 * c = x_j + s (x_{j+1} - x_j), s in [0, 1], on element j.  With tau the
 * filament's tangent at c (the node tangents, the normalised sums of the
 * two element tangents at a node, interpolated linearly in s, normalised):
 *   g = p - c,  g_perp = g - (g . tau) tau,
 *   F = k g_perp + nu (v_p - v_c)_perp     on the filament at c,
 * shared (1 - s) F to node j and s F to node j + 1, and -F on the bone: -F/2
 * on each node of element e and the couple (c - x_c) x (-F) on the element,
 * so the bone feels -F at c.  The pair of forces acts at one point, so the
 * ring conserves momentum and angular momentum exactly.  F has no component
 * along tau: the ring cannot hold the filament along its length, so the
 * filament slides freely and the tension is the same on both sides (at a
 * node contact tau bisects the two elements, and a node in equilibrium
 * then has T_before = T_after exactly).
 *
 * Why the smooth tangent.  A polyline can bend only at its nodes, so when
 * the ring sits inside element j the filament must bend at both of its
 * nodes, and the path is longer than with a node in the ring by about
 * l theta^2 / 8 (theta the wrap angle): sliding the material by half an
 * element over that bump would take a force near T theta^2 / 4, whatever
 * the element length, a discrete friction.  The force normal to the
 * interpolated tangent is the ring's force on the smooth rope the nodes
 * stand for; its part along element j (of order T theta^2 s / 2) is what
 * carries the material over the bump.  Measured (test_via, theta = 45
 * deg, 12 elements): equal tensions to 1e-3.  Projecting on element j's
 * own tangent instead (F normal to the element) left the filament stuck
 * with a node in the ring and 5 % between the two sides.  This makes F a
 * frictionless law and not the gradient of k |g|^2 / 2 (which would hold a
 * node in the ring's corner, a sticking friction), so the ring stores no
 * energy: its whole force goes into ext_force, and the kick books its work
 * like the muscle's own pull; kinetic + elastic - work still balances.
 *
 * The closest element changes as the filament slides: each evaluation
 * starts from the last one's element and walks to the neighbour while the
 * closest point lies beyond the element's end (never turning back), which is
 * deterministic, allocation-free and O(1) per step; at t = 0 (and after
 * sw_reset) every element is tried.
 *
 * Defaults, chosen as the attachments' (muscle.c) and joint.c's:
 *   k  = 100 F_max,k / l0 per filament ring: under the reaction of a ring
 *        that turns the filament by theta at peak force, 2 F_max sin(theta/2),
 *        the gap is 2 sin(theta/2) % of l0, the attachments' 1 %;
 *   nu = 0.1 * 2 sqrt(k m), m the lightest node of the filament (any node
 *        may come into the ring): a tenth of critical, as joint.c.
 * The ring is one more spring on the contact node; sw_via_stable_dt bounds
 * the step by it (stability.c takes the filament bounds).  Under imex the
 * rings of an implicit filament are taken into its Hill solve
 * (via_implicit.c), and only their bone's side bounds the step.
 */
#include <math.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

static const double SW_VIA_ZETA = 0.1; /* default damping, fraction of critical */

/* ---- the specification side ---- */

/* Point k of the path start, via..., end. */
static const double *path_point(const swMuscleDesc *md, int k) {
  return k == 0 ? md->start : k <= md->nvia ? md->via[k - 1] : md->end;
}

double sw_via_path_rest(const swMuscleDesc *md) {
  double L = 0;
  for (int k = 0; k <= md->nvia; k++) {
    double d[3];
    sw_v3_sub(d, path_point(md, k + 1), path_point(md, k));
    L += sw_v3_norm(d);
  }
  return L;
}

int sw_via_check(const swMuscleDesc *md, int nrod, char *err, size_t errlen) {
  const char *nm = md->name;
  if (md->nvia < 0 || md->nvia > SW_MUSCLE_MAX_VIA)
    return sw_fail(err, errlen, "muscle '%s': has %d via points, at most %d are allowed", nm,
                   md->nvia, SW_MUSCLE_MAX_VIA);
  if (md->nvia == 0) return 1;
  if (md->nelem < md->nvia + 1)
    return sw_fail(err, errlen, "muscle '%s': %d via points need at least %d elements per "
                   "filament (one per segment), have %d", nm, md->nvia, md->nvia + 1, md->nelem);
  for (int k = 0; k <= md->nvia; k++) {
    double d[3];
    sw_v3_sub(d, path_point(md, k + 1), path_point(md, k));
    if (!(sw_v3_norm(d) > 0) || !isfinite(sw_v3_norm(d)))
      return sw_fail(err, errlen, "muscle '%s': %s and %s coincide", nm,
                     k == 0 ? "start" : "a via point", k == md->nvia ? "end" : "the next via point");
  }
  for (int k = 0; k < md->nvia; k++)
    if (md->via_rod[k] >= nrod)
      return sw_fail(err, errlen, "muscle '%s': via point %d on rod %d, the scene has %d rods", nm,
                     k + 1, md->via_rod[k], nrod);
  if (!(md->via_stiffness >= 0) || !(md->via_damping >= 0) || !isfinite(md->via_stiffness) ||
      !isfinite(md->via_damping))
    return sw_fail(err, errlen, "muscle '%s': via stiffness and damping must be >= 0", nm);
  return 1;
}

/* Elements per segment in proportion to the segment lengths: floors, then
 * the largest remainders, with at least one element each. */
static void share_elements(const swMuscleDesc *md, int *count) {
  const int K = md->nvia + 1, n = md->nelem;
  double len[SW_MUSCLE_MAX_VIA + 1], L = sw_via_path_rest(md), rem[SW_MUSCLE_MAX_VIA + 1];
  int used = 0;
  for (int j = 0; j < K; j++) {
    double d[3];
    sw_v3_sub(d, path_point(md, j + 1), path_point(md, j));
    len[j] = sw_v3_norm(d);
    const double want = (n - K) * len[j] / L; /* beyond the one each gets */
    count[j] = 1 + (int)floor(want);
    rem[j] = want - floor(want);
    used += count[j];
  }
  while (used < n) { /* the largest remainder first, the first of equals */
    int best = 0;
    for (int j = 1; j < K; j++)
      if (rem[j] > rem[best]) best = j;
    count[best]++;
    rem[best] = -1;
    used++;
  }
}

int sw_via_lay(const swMuscleDesc *md, const double *normal, double *x, double *Q) {
  int count[SW_MUSCLE_MAX_VIA + 1];
  share_elements(md, count);
  double d1[3];
  memcpy(d1, normal, sizeof d1);
  int i = 0;
  memcpy(x, md->start, 3 * sizeof *x);
  for (int j = 0; j <= md->nvia; j++) {
    const double *a = path_point(md, j), *b = path_point(md, j + 1);
    double t[3];
    sw_v3_sub(t, b, a);
    sw_v3_scale(t, t, 1.0 / sw_v3_norm(t));
    /* d1 carried over: the part of the previous d1 normal to this tangent */
    double F[9];
    sw_v3_scale(F, t, sw_v3_dot(d1, t));
    sw_v3_sub(d1, d1, F);
    if (!sw_frame_from(F, t, d1)) { /* d1 along t: any normal */
      int c = 0;
      for (int k = 1; k < 3; k++)
        if (fabs(t[k]) < fabs(t[c])) c = k;
      double e[3] = {0, 0, 0};
      e[c] = 1;
      sw_frame_from(F, t, e);
    }
    memcpy(d1, F, sizeof d1);
    for (int q = 1; q <= count[j]; q++, i++) {
      const double w = (double)q / count[j];
      for (int k = 0; k < 3; k++)
        x[3 * (i + 1) + k] = q == count[j] ? b[k] : a[k] + w * (b[k] - a[k]);
      memcpy(Q + 9 * i, F, sizeof F);
    }
  }
  return i == md->nelem;
}

/* ---- compilation ---- */

/* The element of rod r whose centreline passes nearest to p at t = 0 (the
 * first of equals). */
static int nearest_element(const swModel *m, int r, const double *p) {
  int best = m->elem_adr[r];
  double dbest = INFINITY;
  for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) {
    double a[3], b[3], ab[3], ap[3];
    sw_get3(m, m->x0, e, a);
    sw_get3(m, m->x0, e + 1, b);
    sw_v3_sub(ab, b, a);
    sw_v3_sub(ap, p, a);
    double s = sw_v3_dot(ap, ab) / sw_v3_dot(ab, ab);
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    double c[3];
    for (int k = 0; k < 3; k++) c[k] = a[k] + s * ab[k] - p[k];
    const double dist = sw_v3_norm(c);
    if (dist < dbest) dbest = dist, best = e;
  }
  return best;
}

void sw_via_setup_ring(swModel *m, int q, const swMuscleDesc *md, int k, int f) {
  const int rb = md->via_rod[k];
  if (rb < 0) {
    m->ring_elem[q] = -1;
    memcpy(m->ring_point + 3 * q, md->via[k], 3 * sizeof(double));
  } else {
    const int e = nearest_element(m, rb, md->via[k]);
    double a[3], b[3], arm[3], Q[9];
    sw_get3(m, m->x0, e, a);
    sw_get3(m, m->x0, e + 1, b);
    for (int c = 0; c < 3; c++) arm[c] = md->via[k][c] - 0.5 * (a[c] + b[c]);
    sw_getQ(m, m->Q0, e, Q);
    m->ring_elem[q] = e;
    sw_mat_vec(m->ring_point + 3 * q, Q, arm);
  }
  const int r = m->fil_rod[f], na = m->node_adr[r], n = m->rod_nelem[r];
  double mass = INFINITY;
  for (int i = na; i <= na + n; i++) mass = fmin(mass, m->mass[i]);
  const double kk = md->via_stiffness > 0 ? md->via_stiffness : 100.0 * m->fil_fmax[f] / m->fil_l0[f];
  m->ring_stiffness[q] = kk;
  m->ring_damping[q] = md->via_damping > 0 ? md->via_damping : SW_VIA_ZETA * 2.0 * sqrt(kk * mass);
}

/* ---- the kernels ---- */

/* Via point of ring q and its velocity, now. */
static void ring_point(const swModel *m, const swData *d, int q, double *p, double *vp) {
  const int e = m->ring_elem[q];
  if (e < 0) {
    memcpy(p, m->ring_point + 3 * q, 3 * sizeof *p);
    vp[0] = vp[1] = vp[2] = 0;
    return;
  }
  double a[3], b[3], va[3], vb[3], Q[9], arm[3], w_mat[3], w[3], wxr[3];
  sw_get3(m, d->x, e, a);
  sw_get3(m, d->x, e + 1, b);
  sw_get3(m, d->v, e, va);
  sw_get3(m, d->v, e + 1, vb);
  sw_getQ(m, d->Q, e, Q);
  sw_matT_vec(arm, Q, m->ring_point + 3 * q); /* material -> lab */
  sw_get3(m, d->omega, e, w_mat);
  sw_matT_vec(w, Q, w_mat);
  sw_v3_cross(wxr, w, arm);
  for (int k = 0; k < 3; k++) {
    p[k] = 0.5 * (a[k] + b[k]) + arm[k];
    vp[k] = 0.5 * (va[k] + vb[k]) + wxr[k];
  }
}

/* Unclamped parameter of the point of element slot e's line nearest to p. */
static double line_param(const swModel *m, const swData *d, int e, const double *p) {
  double a[3], b[3], ab[3], ap[3];
  sw_get3(m, d->x, e, a);
  sw_get3(m, d->x, e + 1, b);
  sw_v3_sub(ab, b, a);
  sw_v3_sub(ap, p, a);
  return sw_v3_dot(ap, ab) / sw_v3_dot(ab, ab);
}

static double clamp01(double s) { return s < 0 ? 0 : s > 1 ? 1 : s; }

/* Squared distance from p to element slot e. */
static double element_dist2(const swModel *m, const swData *d, int e, const double *p) {
  const double s = clamp01(line_param(m, d, e, p));
  double a[3], b[3], g[3];
  sw_get3(m, d->x, e, a);
  sw_get3(m, d->x, e + 1, b);
  for (int k = 0; k < 3; k++) g[k] = p[k] - (a[k] + s * (b[k] - a[k]));
  return sw_v3_dot(g, g);
}

/* Unit tangent at node i (slot) of a rod with slots [na, na + n]. */
static void node_tangent(const swModel *m, const swData *d, int na, int n, int i, double *tau) {
  double t[3] = {0, 0, 0};
  for (int e = i - 1; e <= i; e++) {
    if (e < na || e >= na + n) continue;
    double a[3], b[3], ab[3];
    sw_get3(m, d->x, e, a);
    sw_get3(m, d->x, e + 1, b);
    sw_v3_sub(ab, b, a);
    sw_v3_scale(ab, ab, 1.0 / sw_v3_norm(ab));
    sw_v3_add(t, t, ab);
  }
  sw_v3_scale(tau, t, 1.0 / sw_v3_norm(t));
}

/* Ring q's row (SW_RING_ROW doubles): the contact element (its index in the
 * filament), s, the force F on the filament at the contact (lab), the
 * contact point c. */
enum { RING_J = 0, RING_S = 1, RING_F = 2, RING_C = 5 };
static void ring_row(const swModel *m, swData *d, int q, int r) {
  double *row = d->ring_row + SW_RING_ROW * q;
  const int na = m->node_adr[r], n = m->rod_nelem[r];
  double p[3], vp[3];
  ring_point(m, d, q, p, vp);
  int j = (int)row[RING_J];
  if (j < 0 || j >= n) { /* every element */
    double best = INFINITY;
    for (int e = 0; e < n; e++) {
      const double d2 = element_dist2(m, d, na + e, p);
      if (d2 < best) best = d2, j = e;
    }
  } else { /* from the last contact, one way only */
    for (int dir = 0, it = 0; it < n; it++) {
      const double s = line_param(m, d, na + j, p);
      if (s < 0 && j > 0 && dir <= 0) j--, dir = -1;
      else if (s > 1 && j < n - 1 && dir >= 0) j++, dir = 1;
      else break;
    }
  }
  const int a = na + j;
  const double s = clamp01(line_param(m, d, a, p));
  double xa[3], xb[3], va[3], vb[3], c[3], g[3], dv[3], ta[3], tb[3], tau[3];
  sw_get3(m, d->x, a, xa);
  sw_get3(m, d->x, a + 1, xb);
  sw_get3(m, d->v, a, va);
  sw_get3(m, d->v, a + 1, vb);
  node_tangent(m, d, na, n, a, ta);
  node_tangent(m, d, na, n, a + 1, tb);
  for (int k = 0; k < 3; k++) {
    c[k] = xa[k] + s * (xb[k] - xa[k]);
    g[k] = p[k] - c[k];
    dv[k] = vp[k] - ((1 - s) * va[k] + s * vb[k]);
    tau[k] = (1 - s) * ta[k] + s * tb[k];
  }
  sw_v3_scale(tau, tau, 1.0 / sw_v3_norm(tau));
  const double gt = sw_v3_dot(g, tau), vt = sw_v3_dot(dv, tau);
  const double k_ring = m->ring_stiffness[q], nu = m->ring_damping[q];
  row[RING_J] = j;
  row[RING_S] = s;
  for (int k = 0; k < 3; k++) {
    row[RING_F + k] = k_ring * (g[k] - gt * tau[k]) + nu * (dv[k] - vt * tau[k]);
    row[RING_C + k] = c[k];
  }
}

void sw_via_rows(const swModel *m, swData *d, int f) {
  for (int q = m->fil_ring_adr[f]; q < m->fil_ring_adr[f + 1]; q++) ring_row(m, d, q, m->fil_rod[f]);
}

static inline void add_if(const swModel *m, double *a, int i, int lo, int hi, const double *v,
                          double w) {
  if (i < lo || i >= hi) return;
  for (int k = 0; k < 3; k++) SW_AT(m, a, i, k) += w * v[k];
}

/* Force F on ring q's filament f at its contact (the row's), shared by the
 * contact's two nodes, and -F on its bone: half on each node of the
 * carrying element and the couple (c - x_c) x (-F) on it; into the slots
 * [lo, hi) only, as external loads. */
void sw_via_add(const swModel *m, swData *d, int f, int q, const double *F, int lo, int hi) {
  const double *row = d->ring_row + SW_RING_ROW * (size_t)q;
  const int a = m->node_adr[m->fil_rod[f]] + (int)row[RING_J];
  const double s = row[RING_S];
  add_if(m, d->force, a, lo, hi, F, 1 - s);
  add_if(m, d->ext_force, a, lo, hi, F, 1 - s);
  add_if(m, d->force, a + 1, lo, hi, F, s);
  add_if(m, d->ext_force, a + 1, lo, hi, F, s);
  const int e = m->ring_elem[q];
  if (e < 0) return;
  add_if(m, d->force, e, lo, hi, F, -0.5);
  add_if(m, d->ext_force, e, lo, hi, F, -0.5);
  add_if(m, d->force, e + 1, lo, hi, F, -0.5);
  add_if(m, d->ext_force, e + 1, lo, hi, F, -0.5);
  if (e < lo || e >= hi) return;
  /* the couple (c - x_c) x (-F), in the element's material frame */
  double xa[3], xb[3], arm[3], C[3], Q[9], Cm[3];
  sw_get3(m, d->x, e, xa);
  sw_get3(m, d->x, e + 1, xb);
  for (int k = 0; k < 3; k++) arm[k] = row[RING_C + k] - 0.5 * (xa[k] + xb[k]);
  sw_v3_cross(C, F, arm); /* = arm x (-F) */
  sw_getQ(m, d->Q, e, Q);
  sw_mat_vec(Cm, Q, C);
  add_if(m, d->torque, e, lo, hi, Cm, 1.0);
  add_if(m, d->ext_torque, e, lo, hi, Cm, 1.0);
}

/* Every ring's row into the slots [lo, hi) (this thread's), ring by ring,
 * so each slot gets them in the same order for any number of threads. */
void sw_via_apply(const swModel *m, swData *d, int lo, int hi) {
  for (int f = 0; f < m->nfil; f++)
    for (int q = m->fil_ring_adr[f]; q < m->fil_ring_adr[f + 1]; q++)
      sw_via_add(m, d, f, q, d->ring_row + SW_RING_ROW * (size_t)q + RING_F, lo, hi);
}

/* Ring q's (of filament f) contact, from its row: the filament's node before it (slot),
 * the share s of the node after, and the unit tangent there (ring_row's). */
void sw_via_contact(const swModel *m, const swData *d, int f, int q, int *a, double *s, double *tau) {
  const double *row = d->ring_row + SW_RING_ROW * (size_t)q;
  const int r = m->fil_rod[f], na = m->node_adr[r], n = m->rod_nelem[r];
  *a = na + (int)row[RING_J];
  *s = row[RING_S];
  double ta[3], tb[3];
  node_tangent(m, d, na, n, *a, ta);
  node_tangent(m, d, na, n, *a + 1, tb);
  for (int k = 0; k < 3; k++) tau[k] = (1 - *s) * ta[k] + *s * tb[k];
  sw_v3_scale(tau, tau, 1.0 / sw_v3_norm(tau));
}

void sw_via_reset(const swModel *m, swData *d) {
  for (int q = 0; q < m->nring; q++) {
    double *row = d->ring_row + SW_RING_ROW * q;
    memset(row, 0, SW_RING_ROW * sizeof *row);
    row[RING_J] = -1; /* the first evaluation tries every element */
  }
}

/* Whether ring q's contact at rest is on an element touching an end of
 * filament f whose velocity the joints' system gives (via_implicit.c: the
 * ring's share there stays explicit): the filament's node nearest to the
 * ring's point at t = 0 is next to such an end. */
static int rest_contact_at_system_end(const swModel *m, int f, int q) {
  if (!m->fil_system || !m->fil_system[f]) return 0;
  const int r = m->fil_rod[f], na = m->node_adr[r], n = m->rod_nelem[r], e = m->ring_elem[q];
  double p[3];
  if (e < 0) memcpy(p, m->ring_point + 3 * q, sizeof p);
  else {
    double a[3], b[3], Q[9], arm[3];
    sw_get3(m, m->x0, e, a);
    sw_get3(m, m->x0, e + 1, b);
    sw_getQ(m, m->Q0, e, Q);
    sw_matT_vec(arm, Q, m->ring_point + 3 * q);
    for (int k = 0; k < 3; k++) p[k] = 0.5 * (a[k] + b[k]) + arm[k];
  }
  int near = 0;
  double best = INFINITY;
  for (int i = 0; i <= n; i++) {
    double x[3], g[3];
    sw_get3(m, m->x0, na + i, x);
    sw_v3_sub(g, p, x);
    if (sw_v3_dot(g, g) < best) best = sw_v3_dot(g, g), near = i;
  }
  return near <= 1 || near >= n - 1;
}

/* The rings' bound on filament f's step: the ring is one more spring k (and
 * damper nu) on the node in contact, whose Gershgorin row (stability.c's
 * joint_node_dt) is then w^2 = (4 max(EA, GA)/l + k) / m at the lightest
 * node and shortest element, with damping rate nu / m.  A ring taken
 * implicitly (via_implicit.c) leaves only its bone's side explicit: the
 * same row at the lighter node of the carrying element, with its axial
 * stiffness (none for a rigid bone or a point in space); when its contact
 * at rest touches an end of a filament in the joints' system, whose share
 * stays explicit, the filament's row as well. */
double sw_via_stable_dt(const swModel *m, int f) {
  double dt = INFINITY;
  const int r = m->fil_rod[f], na = m->node_adr[r], n = m->rod_nelem[r], ea = m->elem_adr[r];
  if (m->fil_ring_adr[f] == m->fil_ring_adr[f + 1]) return dt;
  double mass = INFINITY, axial = 0;
  for (int i = na; i <= na + n; i++) mass = fmin(mass, m->mass[i]);
  for (int e = ea; e < ea + n; e++)
    axial = fmax(axial, fmax(SW_AT(m, m->shear_stiff, e, 2), SW_AT(m, m->shear_stiff, e, 0)) *
                            m->inv_rest_len[e]);
  for (int q = m->fil_ring_adr[f]; q < m->fil_ring_adr[f + 1]; q++) {
    double mq = mass, aq = axial;
    if (sw_via_ring_implicit(m, f, q) && !rest_contact_at_system_end(m, f, q)) {
      const int e = m->ring_elem[q];
      if (e < 0) continue;
      mq = fmin(m->mass[e], m->mass[e + 1]);
      aq = e < m->nslot_elastic && !(m->nimplicit && m->rod_implicit[sw_rod_of_elem(m, e)])
               ? fmax(SW_AT(m, m->shear_stiff, e, 2), SW_AT(m, m->shear_stiff, e, 0)) * m->inv_rest_len[e]
               : 0.0;
    }
    const double w = sqrt((4.0 * aq + m->ring_stiffness[q]) / mq);
    const double c = m->ring_damping[q] / mq;
    dt = fmin(dt, sw_integrator_stability_limit(m->integrator, c / (2 * w)) / w);
  }
  return dt;
}

/* Filament f's path length: from its first node through its via points to
 * its last node (the end-to-end distance without via points). */
double sw_via_path(const swModel *m, const swData *d, int f) {
  const int r = m->fil_rod[f];
  double a[3], b[3], vp[3];
  sw_get3(m, d->x, m->node_adr[r], a);
  double L = 0;
  for (int q = m->fil_ring_adr[f]; q <= m->fil_ring_adr[f + 1]; q++) {
    if (q < m->fil_ring_adr[f + 1]) ring_point(m, d, q, b, vp);
    else sw_get3(m, d->x, m->node_adr[r] + m->rod_nelem[r], b);
    const double dx[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    L += sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
    memcpy(a, b, sizeof a);
  }
  return L;
}
