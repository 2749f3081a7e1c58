/* ground.c — grounds and terrains: the surface's normal response and the
 * anisotropic Coulomb friction it exerts on the elements of its rods.
 *
 * Design.  Each element (centre c, velocity v_c = the mean of its two nodes,
 * radius r) meets the surface at most once.  For a plane the normal n and the
 * gap (the distance of c from the surface along n) are exact; for a terrain
 * z = h(x, y) the normal is taken at the point below c, n = (-h_x, -h_y, 1) /
 * s with s = sqrt(1 + h_x^2 + h_y^2), and the gap is the vertical one scaled
 * by 1/s, (c_z - h) / s: exact for a plane; on a curved terrain, at gap r,
 * the true distance is r - r^2 h'^2 h'' / (2 s^3) + O(r^3) along a slope h'
 * of curvature h'' (test_ground's barrier measures it), exact where the
 * terrain is level or straight.  An
 * element touches while its penetration p = r - gap is >= -tol, with tol the
 * description's contact_tolerance (default 1e-6 r); the penalty acts on
 * max(p, 0).  The balance below holds a resting element exactly at p = 0, the
 * edge of contact, where a round-off would otherwise lift it out for a step
 * of free fall (and give it a slip that static friction, which only balances
 * loads, never takes back); PyElastica has the same band (1e-4 m).
 *
 * Normal response (Gazzola et al., R. Soc. Open Sci. 2018, sec. 4, eq. 4.8):
 * the ground cancels the part of the element's other loads that pushes into
 * it, B = max(0, -F . n), and adds a penalty k_w p and a damper -gamma_w
 * v_c . n; the total never pulls, N = k_w p + max(B - gamma_w v_n, -k_w p)
 * >= 0.  The element's share of its nodes' loads is half of each node (all
 * of an end node: the lumped mass of model.c puts half an element on each
 * node, so a uniform load is balanced node by node), and the ground's force
 * on the element goes half to each node.  The penalty is conservative: it
 * goes into d->force only and its energy k_w p^2 / 2 is reported by
 * sw_ground_energy; balance, damping and friction go into d->ext_force too,
 * so that the kick books their work.
 *
 * Friction (Gazzola 2018, sec. 4, and PyElastica's AnisotropicFrictionalPlane,
 * which implements it): the in-plane axial direction a (the element
 * tangent projected onto the surface) and the sideways direction b = a x n
 * each get their own Coulomb friction against the slip of the element centre
 * along them, u_a = v_c . a and u_b = v_c . b.  Along a the coefficient is
 * the forward one when u_a > 0 (slip along the tangent), the backward one
 * when u_a < 0.  The slip function phi(u) = 1 for |u| <= v_eps, 2 - |u|/v_eps
 * up to 2 v_eps and 0 beyond blends the two laws: kinetic friction
 * -(1 - phi) mu_k N u / |u_s| with |u_s| the whole slip speed in the
 * surface, so that each coefficient is weighted by the slip's direction
 * cosine along its direction (the anisotropic Coulomb law of Hu et al.,
 * PNAS 2009, that Gazzola 2018 and PyElastica's snake use), then static
 * friction, which cancels the remaining tangential load T (others plus
 * kinetic) up to phi mu_s N, with the coefficient chosen by the sign of T.
 * Kinetic friction is capped at m |u| / h, the force that stops the slip in
 * one step (m: the mass it moves along its direction), so that it never
 * carries a slip past zero and chatters there; the cap vanishes as h -> 0.
 *
 * By default friction acts at the element centre (no couple): with
 * mu_static = 0 and mu_rolling = 0 this is kinetic anisotropic friction on
 * the element velocity, the reference's snake.  With contact_point the
 * sideways friction acts where the element touches, at -r n: the point slips
 * at u_b - r w_a (w_a = (Q^T w) . a, the roll rate), a force f b there also
 * turns the element by -r f a, so the point moves as a mass
 * m_b = 1 / (1/m_e + r^2/J_a) (m_e / 3 for a solid cylinder), and static
 * friction cancels the load that accelerates the point,
 * m_b (T_b / m_e - r tau_a / J_a).  Only the roll is free: pitch and yaw are
 * held by the surface and the neighbours, so the forward direction keeps
 * the centre's slip.  (PyElastica's rolling-direction friction has the same
 * couple but takes the force's direction from the centre's velocity, so it
 * can keep spinning a rod that already rolls; this one only dissipates.)
 *
 * Rolling friction, mu_rolling, is a rolling resistance: a couple about a
 * against the element's rolling rate w_a, of magnitude mu_rolling r N (the
 * classical rolling-resistance force mu_rolling N at lever arm r), blended
 * by the same slip function of the contact-point speed r |w_a|, kinetic and
 * static alike.
 *
 * The elements of a rod are visited in order and each sees its nodes' loads
 * as they were before this ground acted: what the previous element has just
 * put on the shared node is subtracted (`carry`), so no scratch storage is
 * needed and nothing is allocated in the step.
 */
#include <math.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* Gazzola 2018's slip function: 1 (static) up to v_eps, 0 (kinetic) beyond
 * 2 v_eps, linear in between. */
static double slip_function(double speed, double v_eps) {
  if (speed <= v_eps) return 1.0;
  return fmax(0.0, 2.0 - speed / v_eps);
}

static double sign_of(double x) { return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0); }

/* The surface under point c: unit normal n out of the ground and the gap of c
 * above it along n (see the design note for the terrain's approximation). */
static double surface_gap(const swGroundDesc *g, const double c[3], double n[3]) {
  if (!g->height) {
    for (int k = 0; k < 3; k++) n[k] = g->normal[k];
    double rel[3];
    sw_v3_sub(rel, c, g->origin);
    return sw_v3_dot(rel, n);
  }
  double grad[2] = {0, 0};
  double h = g->height(c[0], c[1], grad, g->height_ctx);
  double inv_s = 1.0 / sqrt(1.0 + grad[0] * grad[0] + grad[1] * grad[1]);
  n[0] = -grad[0] * inv_s;
  n[1] = -grad[1] * inv_s;
  n[2] = inv_s;
  return (c[2] - h) * inv_s;
}

void sw_ground_setup(swModel *m) {
  for (int k = 0; k < m->nground; k++) {
    swGroundDesc *g = &m->ground[k];
    if (g->height) continue;
    double len = sw_v3_norm(g->normal); /* > 0: checked by sw_env_check */
    sw_v3_scale(g->normal, g->normal, 1.0 / len);
  }
}

/* Coulomb friction along one direction against the slip u along it, under
 * normal force N: kinetic with mu_kp (u > 0) or mu_km (u < 0), at most
 * m_h |u| (m_h: the mass the friction moves along the direction over the
 * step, m / h, so that it never reverses the slip within one step), then
 * static against the remaining load T + kinetic with mu_sp (load > 0) or
 * mu_sm (load < 0), blended by the slip function.  Returns the friction
 * along the direction. */
static double coulomb(double u, double speed, double T, double N, double v_eps, double m_h,
                      double mu_kp, double mu_km, double mu_sp, double mu_sm) {
  double phi = slip_function(fabs(u), v_eps);
  double share = speed > 0 ? u / speed : 0.0; /* u/|u| = sign(u) along a single direction */
  double kinetic = -(1.0 - phi) * (u > 0 ? mu_kp : mu_km) * N * share;
  if (fabs(kinetic) > m_h * fabs(u)) kinetic = -m_h * u;
  double rest = T + kinetic;
  double cap = phi * (rest > 0 ? mu_sp : mu_sm) * N;
  return kinetic - sign_of(rest) * fmin(fabs(rest), cap);
}

/* One element e (nodes ia, ia+1) of a rod on ground g; wa, wb: the shares of
 * the nodes' loads the element takes (1/2, or 1 at a rod end); carry: the
 * force this ground has already put on node ia (from the previous element),
 * replaced by the force it puts on node ia+1.  Returns 1 when in contact. */
static int ground_element(const swModel *m, swData *d, const swGroundDesc *g, int e, int ia,
                          double wa, double wb, double carry[3]) {
  const int ib = ia + 1;
  double xa[3], xb[3], c[3], vc[3], n[3];
  sw_get3(m, d->x, ia, xa);
  sw_get3(m, d->x, ib, xb);
  for (int k = 0; k < 3; k++) {
    c[k] = 0.5 * (xa[k] + xb[k]);
    vc[k] = 0.5 * (SW_AT(m, d->v, ia, k) + SW_AT(m, d->v, ib, k));
  }
  const double r = m->radius[e];
  const double pen = r - surface_gap(g, c, n);
  const double tol = g->contact_tolerance > 0 ? g->contact_tolerance : 1e-6 * r;
  if (!(pen >= -tol)) return 0;

  /* the element's share of its other loads (Gazzola 2018, eq. 4.8: F_perp) */
  double F[3];
  for (int k = 0; k < 3; k++)
    F[k] = wa * (SW_AT(m, d->force, ia, k) - carry[k]) + wb * SW_AT(m, d->force, ib, k);
  const double Fn = sw_v3_dot(F, n), vn = sw_v3_dot(vc, n);
  const double balance = fmax(0.0, -Fn), spring = g->stiffness * fmax(pen, 0.0);
  const double normal_ext = fmax(balance - g->damping * vn, -spring); /* never pulls */
  const double N = spring + normal_ext;

  /* in-plane axial direction a and sideways direction b = a x n */
  double t[3], a[3], b[3];
  sw_v3_sub(t, xb, xa);
  double tn = sw_v3_dot(t, n);
  for (int k = 0; k < 3; k++) a[k] = t[k] - tn * n[k];
  double alen = sw_v3_norm(a), tlen = sw_v3_norm(t);
  double friction[3] = {0, 0, 0}, couple[3] = {0, 0, 0};
  double u[3], T[3]; /* slip velocity and tangential load, in the surface */
  for (int k = 0; k < 3; k++) {
    u[k] = vc[k] - vn * n[k];
    T[k] = F[k] - Fn * n[k];
  }
  const double *mk = g->mu_kinetic, *ms = g->mu_static, ve = g->slip_velocity;
  if (N > 0 && alen > 1e-9 * tlen) {
    sw_v3_scale(a, a, 1.0 / alen);
    sw_v3_cross(b, a, n);
    /* the element's spin and couples in the lab frame (contact point and
     * rolling resistance) */
    double Q[9], wl[3] = {0, 0, 0}, tl[3] = {0, 0, 0};
    if (g->contact_point || g->mu_rolling > 0) {
      double w[3], tau[3];
      sw_getQ(m, d->Q, e, Q);
      sw_get3(m, d->omega, e, w);
      sw_get3(m, d->torque, e, tau);
      sw_matT_vec(wl, Q, w);
      sw_matT_vec(tl, Q, tau);
    }
    const double ua = sw_v3_dot(u, a);
    const double me = wa * m->mass[ia] + wb * m->mass[ib], inv_h = 1.0 / m->dt;
    double ub = sw_v3_dot(u, b), Tb = sw_v3_dot(T, b), mb = me;
    if (g->contact_point) {
      /* the contact point -r n slips sideways at u_b - r w_a; a force f
       * along b there also turns the element about a by -r f, so it moves
       * the point as a mass 1 / (1 / m_e + r^2 / J_a) would, and the load
       * that accelerates the point, as a force there, is
       * (T_b / m_e - r tau_a / J_a) / (1 / m_e + r^2 / J_a) (design note) */
      const double Ja = SW_AT(m, m->inertia, e, 2) / sw_inertia_dilatation(m, d, e);
      ub -= r * sw_v3_dot(wl, a);
      mb = 1.0 / (1.0 / me + r * r / Ja);
      Tb = (Tb / me - r * sw_v3_dot(tl, a) / Ja) * mb;
    }
    /* forward = along the tangent: mu[0] for slip (or load) along +a */
    const double slip = g->contact_point ? sqrt(ua * ua + ub * ub) : sw_v3_norm(u);
    double fa = coulomb(ua, slip, sw_v3_dot(T, a), N, ve, me * inv_h, mk[0], mk[1], ms[0], ms[1]);
    double fb = coulomb(ub, slip, Tb, N, ve, mb * inv_h, mk[2], mk[2], ms[2], ms[2]);
    for (int k = 0; k < 3; k++) friction[k] = fa * a[k] + fb * b[k];
    double cl[3] = {0, 0, 0}; /* the couple in the lab frame */
    if (g->contact_point)
      for (int k = 0; k < 3; k++) cl[k] = -r * fb * a[k];
    if (g->mu_rolling > 0) {
      /* rolling resistance about a (design note) */
      double wa_rate = sw_v3_dot(wl, a);
      double mr = g->mu_rolling * r;
      double Jh = SW_AT(m, m->inertia, e, 2) / sw_inertia_dilatation(m, d, e) * inv_h / r;
      double ca = coulomb(r * wa_rate, fabs(r * wa_rate), sw_v3_dot(tl, a), N, ve, Jh, mr, mr, mr,
                          mr);
      for (int k = 0; k < 3; k++) cl[k] += ca * a[k];
    }
    if (g->contact_point || g->mu_rolling > 0) sw_mat_vec(couple, Q, cl);
  } else if (N > 0) {
    /* element standing on end: no axis in the surface, isotropic friction
     * with the sideways coefficients, along the slip (or, at rest, along the
     * tangential load) */
    double us = sw_v3_norm(u), Ts = sw_v3_norm(T), dir[3];
    const double *src = us > 0 ? u : T;
    double len = us > 0 ? us : Ts;
    if (len > 0) {
      sw_v3_scale(dir, src, 1.0 / len);
      double ud = sw_v3_dot(u, dir);
      double mh = (wa * m->mass[ia] + wb * m->mass[ib]) / m->dt;
      double f = coulomb(ud, fabs(ud), sw_v3_dot(T, dir), N, ve, mh, mk[2], mk[2], ms[2], ms[2]);
      sw_v3_scale(friction, dir, f);
    }
  }

  /* half of the element's force to each node; the penalty only into force */
  for (int k = 0; k < 3; k++) {
    double ext = normal_ext * n[k] + friction[k];
    double half = 0.5 * (ext + spring * n[k]);
    SW_AT(m, d->ext_force, ia, k) += 0.5 * ext;
    SW_AT(m, d->ext_force, ib, k) += 0.5 * ext;
    SW_AT(m, d->force, ia, k) += half;
    SW_AT(m, d->force, ib, k) += half;
    carry[k] = half;
    SW_AT(m, d->ext_torque, e, k) += couple[k];
    SW_AT(m, d->torque, e, k) += couple[k];
  }
  return 1;
}

void sw_ground_loads(const swModel *m, swData *d, int lo, int hi) {
  for (int q = 0; q < m->nground; q++) {
    const swGroundDesc *g = &m->ground[q];
    for (int j = 0; j < g->nrods; j++) {
      const int r = g->rods[j], n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r];
      if (na < lo || na >= hi) continue; /* another thread's rod */
      double carry[3] = {0, 0, 0};
      for (int i = 0; i < n; i++) {
        double wa = i == 0 ? 1.0 : 0.5, wb = i == n - 1 ? 1.0 : 0.5;
        if (!ground_element(m, d, g, ea + i, na + i, wa, wb, carry))
          carry[0] = carry[1] = carry[2] = 0;
      }
    }
  }
}

/* Energy stored in the ground penalties, sum of k_w p^2 / 2, J. */
double sw_ground_energy(const swModel *m, const swData *d) {
  double energy = 0;
  for (int q = 0; q < m->nground; q++) {
    const swGroundDesc *g = &m->ground[q];
    for (int j = 0; j < g->nrods; j++) {
      const int r = g->rods[j], n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r];
      for (int i = 0; i < n; i++) {
        double c[3], nrm[3];
        for (int k = 0; k < 3; k++)
          c[k] = 0.5 * (SW_AT(m, d->x, na + i, k) + SW_AT(m, d->x, na + i + 1, k));
        double pen = m->radius[ea + i] - surface_gap(g, c, nrm);
        if (pen > 0) energy += 0.5 * g->stiffness * pen * pen;
      }
    }
  }
  return energy;
}

/* Step limit of the ground springs and dampers.  Node i's Gershgorin row:
 * each element in contact moves its centre, the mean of its two nodes, so
 * its spring puts k_w/4 on the diagonal and k_w/4 off it for each of its
 * nodes: w^2 = sum_e (k_w / 2) / m_i, c = sum_e (gamma_w / 2) / m_i over the
 * node's elements (w^2 = k_w / m_e for an interior node, whose lumped mass is
 * one element's; the same for an end node, which has half of both).  The
 * scheme's limit at zeta = c / (2 w), times 0.95 as in stability.c; a pure
 * damper (k_w = 0) is stable for h c < 2. */
double sw_ground_stable_dt(const swModel *m) {
  double dt = INFINITY;
  for (int q = 0; q < m->nground; q++) {
    const swGroundDesc *g = &m->ground[q];
    if (!(g->stiffness > 0) && !(g->damping > 0)) continue;
    for (int j = 0; j < g->nrods; j++) {
      const int r = g->rods[j], n = m->rod_nelem[r], na = m->node_adr[r];
      for (int i = 0; i <= n; i++) {
        int nel = (i > 0) + (i < n);
        double w2 = 0.5 * nel * g->stiffness * m->inv_mass[na + i];
        double c = 0.5 * nel * g->damping * m->inv_mass[na + i];
        double lim;
        if (w2 > 0) {
          double w = sqrt(w2);
          lim = 0.95 * sw_integrator_stability_limit(m->integrator, c / (2 * w)) / w;
        } else {
          lim = 0.95 * 2.0 / c;
        }
        dt = fmin(dt, lim);
      }
    }
  }
  return dt;
}
