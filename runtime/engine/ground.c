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
 * Each element sees its nodes' loads as they were before this ground acted
 * on the rod, read before any element's response is added, so that the
 * response does not depend on the order the elements are visited in.  A
 * block of elements is taken in three passes (see "a rod on a ground"
 * below): what depends on the state alone (contact, surface, directions,
 * slip), then the response to the loads, each a vector loop into arrays on
 * the stack, then the responses added to the nodes; nothing is allocated in
 * the step.
 */
#include <math.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* Gazzola 2018's slip function: 1 (static) up to v_eps, 0 (kinetic) beyond
 * 2 v_eps, linear in between (without a branch: vec.h, sw_select). */
static inline double slip_function(double speed, double v_eps) {
  return sw_select(speed <= v_eps, 1.0, sw_max(0.0, 2.0 - speed / v_eps));
}

/* 1, -1 or 0 (also for a NaN), as a number, without a branch. */
static inline double sign_of(double x) { return (double)((x > 0) - (x < 0)); }

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
 * normal force N: kinetic, -(1 - phi) mu_k N u / |u_s|, with mu_kp (u > 0)
 * or mu_km (u < 0), at most m_h |u| (m_h: the mass the friction moves along
 * the direction over the step, m / h, so that it never reverses the slip
 * within one step), then static against the remaining load T + kinetic, at
 * most phi mu_s N with mu_sp (load > 0) or mu_sm (load < 0); phi the slip
 * function of |u| (design note).  In two parts: what the slip alone decides
 * (coulomb_slip), which the element loop computes for a block of elements
 * at once, and the friction under N and T (coulomb_load), which waits for
 * the loads. */
typedef struct {
  double phi;     /* slip function of |u|                                   */
  double kinetic; /* -(1 - phi) mu_k, mu_k by the sign of u                 */
  double share;   /* u / |u_s|: the slip's direction cosine (u/|u| alone)   */
  double limit;   /* m_h |u|: the largest kinetic friction that keeps u's sign */
  double stop;    /* -m_h u: the friction that stops the slip in one step  */
} swSlip;

static inline swSlip coulomb_slip(double u, double speed, double v_eps, double m_h, double mu_kp,
                                  double mu_km) {
  const double phi = slip_function(fabs(u), v_eps);
  return (swSlip){phi, -(1.0 - phi) * sw_select(u > 0, mu_kp, mu_km), sw_select(speed > 0, u / speed, 0.0),
                  m_h * fabs(u), -m_h * u};
}

static inline double coulomb_load(swSlip s, double T, double N, double mu_sp, double mu_sm) {
  double kinetic = s.kinetic * N * s.share;
  kinetic = fabs(kinetic) > s.limit ? s.stop : kinetic;
  const double rest = T + kinetic;
  const double cap = s.phi * (rest > 0 ? mu_sp : mu_sm) * N;
  return kinetic - sign_of(rest) * sw_min(fabs(rest), cap);
}

static double coulomb(double u, double speed, double T, double N, double v_eps, double m_h,
                      double mu_kp, double mu_km, double mu_sp, double mu_sm) {
  return coulomb_load(coulomb_slip(u, speed, v_eps, m_h, mu_kp, mu_km), T, N, mu_sp, mu_sm);
}

/* ---- a rod on a ground, a block of elements at a time ----
 *
 * Element i of a rod (nodes i, i+1) takes the share wa of node i's loads
 * and wb of node i+1's (1/2, or 1 at a rod end) as they were before this
 * ground acted.  A block of elements is done in three passes: the first
 * (ground_geometry) computes what depends on the state alone, its contact,
 * the surface, the directions a and b, the slip and what the slip decides
 * of the friction (coulomb_slip); the second (ground_response) reads the
 * nodes' loads, none of them yet changed by this ground (the block's first
 * node as it was before the previous block's last element added to it),
 * and computes each element's normal response and friction; the third
 * (ground_apply) adds them to the nodes, with the couples and the rare
 * element standing on end.  The first two are vector loops into the arrays
 * below (on the stack: nothing is allocated in the step).  Until git
 * 53f0982 the elements were a chain, each subtracting what the previous one
 * had put on their shared node, (f + h) - h, which is f only to round-off:
 * a scalar loop, 13% of the muscular snake's step. */
#define GROUND_BLOCK 64

typedef struct {
  double phi[GROUND_BLOCK], kinetic[GROUND_BLOCK], share[GROUND_BLOCK], limit[GROUND_BLOCK],
      stop[GROUND_BLOCK];
} swSlipBlock;

typedef struct {
  double contact[GROUND_BLOCK];  /* 1: p >= -tol                            */
  double n[3][GROUND_BLOCK];     /* the surface's normal                    */
  double spring[GROUND_BLOCK];   /* k_w max(p, 0)                           */
  double damper[GROUND_BLOCK];   /* gamma_w v_c . n                         */
  double axis[GROUND_BLOCK];     /* 1: the tangent has a part in the surface */
  double a[3][GROUND_BLOCK];     /* in-plane axial direction                */
  double b[3][GROUND_BLOCK];     /* sideways, a x n                         */
  double u[3][GROUND_BLOCK];     /* slip velocity of the centre, in the surface */
  double me[GROUND_BLOCK];       /* the element's mass, wa m_a + wb m_b     */
  double mb[GROUND_BLOCK];       /* the mass the sideways friction moves    */
  double tq[GROUND_BLOCK];       /* contact point: r tau_a / J_a            */
  double ta[GROUND_BLOCK];       /* rolling: tau_a, the couple about a      */
  swSlipBlock sa, sb, sr;        /* forward, sideways, rolling              */
  /* the response (ground_response) */
  double N[GROUND_BLOCK];        /* the normal force, spring + normal_ext   */
  double ext[3][GROUND_BLOCK];   /* normal_ext n + friction: ext_force's share */
  double T[3][GROUND_BLOCK];     /* the tangential load, in the surface     */
  double fb[GROUND_BLOCK];       /* the sideways friction (contact point's couple) */
} swGroundBlock;

static inline void slip_store(swSlipBlock *b, int j, swSlip s) {
  b->phi[j] = s.phi, b->kinetic[j] = s.kinetic, b->share[j] = s.share, b->limit[j] = s.limit,
  b->stop[j] = s.stop;
}
static inline swSlip slip_load(const swSlipBlock *b, int j) {
  return (swSlip){b->phi[j], b->kinetic[j], b->share[j], b->limit[j], b->stop[j]};
}

/* Elements [i0, i1) of a rod of n elements (first node na, first element
 * ea) into blk from entry 0: the first pass.  `terrain`: the surface comes
 * from blk's n and from gap[] (the terrain's height function is a call,
 * made before, element by element); else the plane's.  `spin`: the ground
 * has contact_point or rolling friction, which read the element's spin. */
static inline __attribute__((always_inline)) void ground_geometry(const swModel *m, const swData *d,
                                                                const swGroundDesc *g, int n, int na,
                                                                int ea, int i0, int i1,
                                                                const double *restrict gap,
                                                                swGroundBlock *restrict blk,
                                                                const int terrain, const int spin) {
  const size_t S = (size_t)m->stride;
  const double *restrict x = d->x, *restrict v = d->v, *restrict Q = d->Q, *restrict omega = d->omega;
  const double *restrict tau = d->torque, *restrict dil = d->dilatation, *restrict J = d->inertia_now;
  const double *restrict radius = d->radius_now, *restrict mass = d->mass_now, *restrict var = m->elem_variational;
  const double inv_h = 1.0 / m->dt, ve = g->slip_velocity, ct = g->contact_tolerance;
  const double *mk = g->mu_kinetic;
  const sw3 plane = {g->normal[0], g->normal[1], g->normal[2]};
  const sw3 origin = {g->origin[0], g->origin[1], g->origin[2]};
  const int cp = g->contact_point, variational = m->nvariational > 0;
#pragma omp simd
  for (int i = i0; i < i1; i++) {
    const int j = i - i0, ia = na + i, e = ea + i;
    const double wa = sw_select(i == 0, 1.0, 0.5), wb = sw_select(i == n - 1, 1.0, 0.5);
    const sw3 xa = sw3_load(x, S, ia), xb = sw3_load(x, S, ia + 1);
    const sw3 va = sw3_load(v, S, ia), vb = sw3_load(v, S, ia + 1);
    const sw3 c = {0.5 * (xa.x + xb.x), 0.5 * (xa.y + xb.y), 0.5 * (xa.z + xb.z)};
    const sw3 vc = {0.5 * (va.x + vb.x), 0.5 * (va.y + vb.y), 0.5 * (va.z + vb.z)};
    const double r = radius[e];
    /* the surface below c (surface_gap) and the penetration p = r - gap */
    const sw3 nrm = terrain ? (sw3){blk->n[0][j], blk->n[1][j], blk->n[2][j]} : plane;
    const double pen = r - (terrain ? gap[j] : sw3_dot(sw3_sub(c, origin), nrm));
    const double tol = sw_select(ct > 0, ct, 1e-6 * r);
    blk->contact[j] = sw_select(pen >= -tol, 1.0, 0.0);
    sw3_store(&blk->n[0][0], GROUND_BLOCK, j, nrm);
    const double vn = sw3_dot(vc, nrm);
    blk->spring[j] = g->stiffness * sw_max(pen, 0.0);
    blk->damper[j] = g->damping * vn;
    /* in-plane axial direction a and sideways direction b = a x n */
    const sw3 t = sw3_sub(xb, xa);
    const double tn = sw3_dot(t, nrm);
    const sw3 along = {t.x - tn * nrm.x, t.y - tn * nrm.y, t.z - tn * nrm.z};
    const double alen = sqrt(sw3_dot(along, along)), tlen = sqrt(sw3_dot(t, t));
    blk->axis[j] = sw_select(alen > 1e-9 * tlen, 1.0, 0.0);
    const sw3 a = sw3_scale(along, 1.0 / alen), b = sw3_cross(a, nrm);
    sw3_store(&blk->a[0][0], GROUND_BLOCK, j, a);
    sw3_store(&blk->b[0][0], GROUND_BLOCK, j, b);
    const sw3 u = {vc.x - vn * nrm.x, vc.y - vn * nrm.y, vc.z - vn * nrm.z};
    sw3_store(&blk->u[0][0], GROUND_BLOCK, j, u);
    const double ua = sw3_dot(u, a), me = wa * mass[ia] + wb * mass[ia + 1];
    double ub = sw3_dot(u, b), mb = me, slip = sqrt(sw3_dot(u, u));
    if (spin) {
      /* the element's spin and couple in the lab frame */
      const swFrame Qe = sw_frame_load(Q, S, e);
      const sw3 wl = sw_frame_apply_t(Qe, sw3_load(omega, S, e));
      const sw3 tl = sw_frame_apply_t(Qe, sw3_load(tau, S, e));
      const double Ja = J[2 * S + e] / sw_select(variational && var[e] != 0.0, 1.0, dil[e]);
      const double wla = sw3_dot(wl, a), tla = sw3_dot(tl, a);
      /* the contact point -r n slips sideways at u_b - r w_a and moves as
       * a mass 1 / (1 / m_e + r^2 / J_a) (design note) */
      const double ubc = ub - r * wla;
      const double mbc = 1.0 / (1.0 / me + r * r / Ja);
      blk->tq[j] = r * tla / Ja;
      ub = sw_select(cp, ubc, ub);
      mb = sw_select(cp, mbc, mb);
      slip = sw_select(cp, sqrt(ua * ua + ubc * ubc), slip);
      /* rolling resistance about a */
      const double rate = r * wla, mr = g->mu_rolling * r;
      blk->ta[j] = tla;
      slip_store(&blk->sr, j, coulomb_slip(rate, fabs(rate), ve, Ja * inv_h / r, mr, mr));
    }
    blk->me[j] = me;
    blk->mb[j] = mb;
    /* forward = along the tangent: mu[0] for slip (or load) along +a */
    slip_store(&blk->sa, j, coulomb_slip(ua, slip, ve, me * inv_h, mk[0], mk[1]));
    slip_store(&blk->sb, j, coulomb_slip(ub, slip, ve, mb * inv_h, mk[2], mk[2]));
  }
}

/* The second pass: elements [i0, i1) of the rod (entry j = i - i0 of blk)
 * under their nodes' loads as they were before this ground acted (node i0's
 * in f0: its entry of d->force may already hold the previous block's last
 * response).  Normal response: Gazzola 2018 eq. 4.8; friction: design note.
 * Standing on end (no axis in the surface) leaves friction to ground_apply. */
static inline __attribute__((always_inline)) void ground_response(const swModel *m, const swData *d,
                                                                const swGroundDesc *g, int n, int na,
                                                                int i0, int i1, const double f0[3],
                                                                swGroundBlock *restrict blk, const int cp) {
  const size_t S = (size_t)m->stride;
  const double *restrict force = d->force;
  const double *ms = g->mu_static;
  const sw3 first = {f0[0], f0[1], f0[2]};
#pragma omp simd
  for (int i = i0; i < i1; i++) {
    const int j = i - i0, ia = na + i;
    const double wa = sw_select(i == 0, 1.0, 0.5), wb = sw_select(i == n - 1, 1.0, 0.5);
    const sw3 fa_ = i == i0 ? first : sw3_load(force, S, ia), fb_ = sw3_load(force, S, ia + 1);
    const sw3 nrm = {blk->n[0][j], blk->n[1][j], blk->n[2][j]};
    const double spring = blk->spring[j], touch = blk->contact[j];
    /* the element's share of its other loads (Gazzola 2018, eq. 4.8: F_perp) */
    const sw3 F = {wa * fa_.x + wb * fb_.x, wa * fa_.y + wb * fb_.y, wa * fa_.z + wb * fb_.z};
    const double Fn = sw3_dot(F, nrm);
    const double balance = sw_max(0.0, -Fn);
    const double normal_ext = sw_max(balance - blk->damper[j], -spring); /* never pulls */
    const double N = spring + normal_ext;
    const sw3 T = {F.x - Fn * nrm.x, F.y - Fn * nrm.y, F.z - Fn * nrm.z}; /* in the surface */
    const sw3 a = {blk->a[0][j], blk->a[1][j], blk->a[2][j]};
    const sw3 b = {blk->b[0][j], blk->b[1][j], blk->b[2][j]};
    const double Tb0 = sw3_dot(T, b);
    /* contact point: the load that accelerates the point, as a force there,
     * (T_b / m_e - r tau_a / J_a) / (1 / m_e + r^2 / J_a) (design note) */
    const double Tb = cp ? (Tb0 / blk->me[j] - blk->tq[j]) * blk->mb[j] : Tb0;
    const double fa = coulomb_load(slip_load(&blk->sa, j), sw3_dot(T, a), N, ms[0], ms[1]);
    const double fb = coulomb_load(slip_load(&blk->sb, j), Tb, N, ms[2], ms[2]);
    /* selected, not multiplied by 0 or 1: without an axis in the surface
     * a and b are not finite (ground_geometry divides by its length) */
    const int on = touch != 0.0 && N > 0 && blk->axis[j] != 0.0;
    const double ne = sw_select(touch != 0.0, normal_ext, 0.0);
    blk->N[j] = sw_select(touch != 0.0, N, 0.0);
    blk->fb[j] = sw_select(on, fb, 0.0);
    blk->ext[0][j] = ne * nrm.x + sw_select(on, fa * a.x + fb * b.x, 0.0);
    blk->ext[1][j] = ne * nrm.y + sw_select(on, fa * a.y + fb * b.y, 0.0);
    blk->ext[2][j] = ne * nrm.z + sw_select(on, fa * a.z + fb * b.z, 0.0);
    sw3_store(&blk->T[0][0], GROUND_BLOCK, j, T);
  }
}

/* The third pass: each touching element's response (ground_response) half
 * to each of its nodes, the penalty only into d->force; the couples of
 * contact_point and rolling friction; and an element standing on end (no
 * axis in the surface), given isotropic friction with the sideways
 * coefficients along its slip (or, at rest, along its tangential load). */
static void ground_apply(const swModel *m, swData *d, const swGroundDesc *g, int nel, int na, int ea,
                         int i0, int i1, swGroundBlock *blk) {
  const double *ms = g->mu_static, *mk = g->mu_kinetic;
  for (int i = i0; i < i1; i++) {
    const int j = i - i0, ia = na + i, ib = ia + 1, e = ea + i;
    if (blk->contact[j] == 0.0) continue;
    const double N = blk->N[j];
    const double n[3] = {blk->n[0][j], blk->n[1][j], blk->n[2][j]};
    double couple[3] = {0, 0, 0};
    if (N > 0 && blk->axis[j] != 0.0 && (g->contact_point || g->mu_rolling > 0)) {
      const double a[3] = {blk->a[0][j], blk->a[1][j], blk->a[2][j]};
      const double r = d->radius_now[e];
      double cl[3] = {0, 0, 0}, Q[9]; /* the couple in the lab frame */
      if (g->contact_point)
        for (int k = 0; k < 3; k++) cl[k] = -r * blk->fb[j] * a[k];
      if (g->mu_rolling > 0) {
        /* rolling resistance about a (design note) */
        const double mr = g->mu_rolling * r;
        const double ca = coulomb_load(slip_load(&blk->sr, j), blk->ta[j], N, mr, mr);
        for (int k = 0; k < 3; k++) cl[k] += ca * a[k];
      }
      sw_getQ(m, d->Q, e, Q);
      sw_mat_vec(couple, Q, cl);
    } else if (N > 0 && blk->axis[j] == 0.0) {
      const double u[3] = {blk->u[0][j], blk->u[1][j], blk->u[2][j]};
      const double T[3] = {blk->T[0][j], blk->T[1][j], blk->T[2][j]};
      const double us = sw_v3_norm(u), Ts = sw_v3_norm(T), len = us > 0 ? us : Ts;
      if (len > 0) {
        const double wa = i == 0 ? 1.0 : 0.5, wb = i == nel - 1 ? 1.0 : 0.5;
        double dir[3];
        sw_v3_scale(dir, us > 0 ? u : T, 1.0 / len);
        const double ud = sw_v3_dot(u, dir);
        const double mh = (wa * d->mass_now[ia] + wb * d->mass_now[ib]) / m->dt;
        const double f = coulomb(ud, fabs(ud), sw_v3_dot(T, dir), N, g->slip_velocity, mh, mk[2], mk[2],
                                 ms[2], ms[2]);
        for (int k = 0; k < 3; k++) blk->ext[k][j] += f * dir[k];
      }
    }
    for (int k = 0; k < 3; k++) {
      const double ext = blk->ext[k][j];
      const double half = 0.5 * (ext + blk->spring[j] * n[k]);
      SW_AT(m, d->ext_force, ia, k) += 0.5 * ext;
      SW_AT(m, d->ext_force, ib, k) += 0.5 * ext;
      SW_AT(m, d->force, ia, k) += half;
      SW_AT(m, d->force, ib, k) += half;
      SW_AT(m, d->ext_torque, e, k) += couple[k];
      SW_AT(m, d->torque, e, k) += couple[k];
    }
  }
}

/* Rod r on ground g, block by block: the three passes above. */
static void ground_rod(const swModel *m, swData *d, const swGroundDesc *g, int r) {
  const int n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r];
  const int spin = g->contact_point || g->mu_rolling > 0, cp = g->contact_point;
  swGroundBlock blk;
  double gap[GROUND_BLOCK];
  double f0[3]; /* the block's first node's loads before this ground acted */
  for (int k = 0; k < 3; k++) f0[k] = SW_AT(m, d->force, na, k);
  for (int i0 = 0; i0 < n; i0 += GROUND_BLOCK) {
    const int i1 = i0 + GROUND_BLOCK < n ? i0 + GROUND_BLOCK : n;
    if (g->height) {
      /* the terrain under each centre, a call each (surface_gap) */
      for (int i = i0; i < i1; i++) {
        double c[3], nrm[3];
        for (int k = 0; k < 3; k++)
          c[k] = 0.5 * (SW_AT(m, d->x, na + i, k) + SW_AT(m, d->x, na + i + 1, k));
        gap[i - i0] = surface_gap(g, c, nrm);
        for (int k = 0; k < 3; k++) blk.n[k][i - i0] = nrm[k];
      }
      if (spin) ground_geometry(m, d, g, n, na, ea, i0, i1, gap, &blk, 1, 1);
      else ground_geometry(m, d, g, n, na, ea, i0, i1, gap, &blk, 1, 0);
    } else {
      if (spin) ground_geometry(m, d, g, n, na, ea, i0, i1, gap, &blk, 0, 1);
      else ground_geometry(m, d, g, n, na, ea, i0, i1, gap, &blk, 0, 0);
    }
    if (cp) ground_response(m, d, g, n, na, i0, i1, f0, &blk, 1);
    else ground_response(m, d, g, n, na, i0, i1, f0, &blk, 0);
    for (int k = 0; k < 3; k++) f0[k] = SW_AT(m, d->force, na + i1, k); /* before the block's last adds */
    ground_apply(m, d, g, n, na, ea, i0, i1, &blk);
  }
}

void sw_ground_loads(const swModel *m, swData *d, int lo, int hi) {
  for (int q = 0; q < m->nground; q++) {
    const swGroundDesc *g = &m->ground[q];
    for (int j = 0; j < g->nrods; j++) {
      const int r = g->rods[j];
      if (m->node_adr[r] < lo || m->node_adr[r] >= hi) continue; /* another thread's rod */
      ground_rod(m, d, g, r);
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
        double pen = d->radius_now[ea + i] - surface_gap(g, c, nrm);
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
