/* stability.c — the stable time step estimate and the detection of runs that
 * have gone unstable.
 *
 * Design.  An explicit symplectic scheme on a linear oscillator of angular
 * frequency w is stable while h w stays below a limit that depends only on
 * the scheme and on the damping ratio; we get that limit exactly by building
 * the scheme's 2x2 amplification matrix and finding where its spectral
 * radius first exceeds one (position Verlet undamped: h w < 2).  The highest
 * frequency of a discrete rod is bounded element by element from the
 * zig-zag modes of the lumped model (every neighbour moving in opposition):
 *   axial          w^2 = 4 E / (rho l^2)
 *   shear+rotation w^2 = (16/3) hs G / rho (1/l^2 + 1/r^2) + 4 E / (rho l D)
 *                  (lateral zig-zag and alternating element rotation load
 *                   the same shear strain; bending adds its couple)
 *   twist          w^2 = 4 ht G / (rho l D)
 * with l the element rest length, D the Voronoi rest length, r the radius,
 * hs and ht the hardening factors.  The estimate is the scheme's limit over
 * the largest of these, and tests/runtime/test_stability.c measures how close
 * it is to the step at which a rod really blows up.
 *
 * A run is declared unstable when a position, velocity or angular velocity
 * stops being finite, or the motion is no longer resolved by the step: an
 * element changing by more than half its length (from the relative velocity
 * of its nodes), or turning more than half a radian, in one step.  An unstable explicit scheme does not
 * always reach infinity (geometric nonlinearity can saturate the growth in
 * a chaotic state), but it always ends up there.  The report names the rod,
 * the element, the time and the estimate.
 *
 * A joint (joint.c) adds a spring to two nodes and a couple to two elements;
 * its bound (sw_stable_dt_joint) is the same analysis with the joint's spring
 * counted in, and sw_stable_dt is the smallest over rods and joints.
 *
 * A rigid rod (rigid.c) has no elastic waves: its own bound is its linear
 * damping's alone, and a joint side on it is bounded by the body's effective
 * mass and inertia at the joint, all the body's joints summed
 * (sw_rigid_joint_dt).  A joint on a rigid body under SW_IMEX (to another
 * body, space, or a free node of an elastic rod) is integrated by the
 * trapezoidal rule (rigid_joint.c) and bounds nothing but its limit, if it
 * has one (implicit_limit_dt); the elastic rod keeps its own bound.
 *
 * The estimate is the oscillator limit times 0.95: the zig-zag analysis
 * ignores the half-mass end nodes, and a shear-hardened rod was measured to
 * go unstable at 0.9999 of the unreduced value.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* One step of the scheme on x'' = -x - 2 zeta x' (w = 1), applied to (x, v). */
static void oscillator_step(swIntegrator integ, double h, double zeta, double *x, double *v) {
  static const double XI = 0.1786178958448091, LA = -0.2123418310626054, CHI = -0.06626458266981849;
  const double verlet[] = {0.5, 1.0, 0.5};
  const double pefrl[] = {XI, 0.5 * (1 - 2 * LA), CHI, LA, 1 - 2 * (CHI + XI), LA, CHI,
                          0.5 * (1 - 2 * LA), XI};
  const double *c = integ == SW_PEFRL ? pefrl : verlet;
  int nc = integ == SW_PEFRL ? 9 : 3;
  for (int k = 0; k < nc; k++) {
    if (k % 2 == 0) *x += c[k] * h * *v;                      /* drift */
    else *v += c[k] * h * (-*x - 2 * zeta * *v);              /* kick  */
  }
}

static double spectral_radius(swIntegrator integ, double h, double zeta) {
  double a = 1, c = 0, b = 0, d = 1;
  oscillator_step(integ, h, zeta, &a, &c); /* first column  */
  oscillator_step(integ, h, zeta, &b, &d); /* second column */
  double tr = a + d, det = a * d - b * c, disc = tr * tr / 4 - det;
  if (disc >= 0) {
    double s = sqrt(disc);
    return fmax(fabs(tr / 2 + s), fabs(tr / 2 - s));
  }
  return sqrt(det); /* complex pair: |lambda|^2 = det */
}

static double stability_limit(swIntegrator integ, double zeta) {
  /* scan up from 0 for the first unstable h, then bisect */
  const double tol = 1e-12;
  double lo = 0, hi = 0;
  for (int k = 1; k <= 4000; k++) {
    double h = 5.0 * k / 4000;
    if (spectral_radius(integ, h, zeta) > 1 + tol) { hi = h; break; }
    lo = h;
  }
  if (hi == 0) return lo;
  for (int it = 0; it < 60; it++) {
    double mid = 0.5 * (lo + hi);
    if (spectral_radius(integ, mid, zeta) > 1 + tol) hi = mid; else lo = mid;
  }
  return lo;
}

/* Memoised: every element asks for its (scheme, zeta), and a scene of
 * many like rods (the wing's 3144 barbs come in a few dozen lengths) asks
 * for the same few again and again; each answer is some 4000 oscillator
 * steps.  A small table indexed by a hash of the pair keeps the last
 * answer for each slot. */
#define LIMIT_MEMO 64
double sw_integrator_stability_limit(swIntegrator integ, double zeta) {
  static _Thread_local struct {
    swIntegrator integ;
    double zeta, limit;
    int used;
  } memo[LIMIT_MEMO];
  uint64_t bits;
  memcpy(&bits, &zeta, sizeof bits);
  const unsigned slot = (unsigned)(((bits ^ (uint64_t)integ) * 0x9E3779B97F4A7C15ull) >> 58);
  if (!memo[slot].used || memo[slot].integ != integ || memo[slot].zeta != zeta) {
    memo[slot].limit = stability_limit(integ, zeta);
    memo[slot].integ = integ;
    memo[slot].zeta = zeta;
    memo[slot].used = 1;
  }
  return memo[slot].limit;
}

/* Element i of elastic rod r at rest, what its zig-zag bounds are made of:
 * rest length l, radius, density, E, the shear modulus with its hardening
 * Gs, the shorter Voronoi rest length D beside it (or l at an end) and the
 * twist modulus Gt with its hardening. */
typedef struct {
  double l, rad, rho, E, Gs, D, Gt;
} elemRest;

static elemRest elem_rest(const swModel *m, int r, int i) {
  const int n = m->rod_nelem[r], e = m->elem_adr[r] + i, va = m->vor_adr[r];
  elemRest p;
  p.l = m->rest_len[e];
  p.rad = m->radius[e];
  double A = SW_PI * p.rad * p.rad;
  double rhoA = SW_AT(m, m->inertia, e, 0) / (p.l * p.rad * p.rad / 4.0) ; /* rho A from J^ = rho l A r^2/4 */
  p.rho = rhoA / A;
  p.E = SW_AT(m, m->shear_stiff, e, 2) / A;
  p.Gs = SW_AT(m, m->shear_stiff, e, 0) / (A * 4.0 / 3.0);
  /* the Voronoi domains on either side (or the element itself at the ends) */
  p.D = p.l;
  p.Gt = p.Gs;
  if (i > 0) p.D = fmin(p.D, m->rest_vor_len[va + i - 1]);
  if (i < n - 1) p.D = fmin(p.D, m->rest_vor_len[va + i]);
  int v = va + (i < n - 1 ? i : i - 1);
  if (n > 1) p.Gt = SW_AT(m, m->bend_stiff, v, 2) / (2.0 * SW_AT(m, m->bend_stiff, v, 0)) * p.E;
  return p;
}

/* The same element of a swelling rod (swell.c) at radius scale g: the
 * moduli stay, the radius is g rad, and the density rho / g^2 when the mass
 * is conserved, rho when the density is fixed.  Conserved, every w^2 above
 * but the shear-rotation term's G / (rho r^2) grows as g^2 (E / rho does),
 * so a thickening rod needs a shorter step, dt ~ 1 / g; fixed density, only
 * that term moves (as g^-2).  mass_scale is what the node masses are
 * multiplied by. */
static elemRest elem_at_scale(elemRest p, double g, int grows, double *mass_scale) {
  p.rad *= g;
  if (!grows) p.rho /= g * g;
  *mass_scale = grows ? g * g : 1.0;
  return p;
}

/* The radius scales g a swelling rod's bound is taken at: the least and the
 * greatest its signal reaches (swell_range; each zig-zag frequency is a
 * power of g, so its largest is at one of them), else 1 alone.  Returns
 * how many, and whether its mass grows. */
static int rod_scales(const swModel *m, int r, double g[2], int *grows) {
  const int k = m->nswell ? sw_swell_of_rod(m, r) : -1;
  *grows = 0;
  if (k < 0) {
    g[0] = 1.0;
    return 1;
  }
  *grows = (m->swell_flags[k] & SW_SWELL_MASS_GROWS) != 0;
  g[0] = m->swell_range[2 * k];
  g[1] = m->swell_range[2 * k + 1];
  return 2;
}

/* The damping ratio of element i's linear dissipation at frequency w (0
 * without it). */
static double elem_zeta(const swModel *m, int r, int i, double w, double mass_scale) {
  if (m->rod_damping[r] != SW_DAMP_LINEAR) return 0;
  const int na = m->node_adr[r], e = m->elem_adr[r] + i;
  double c = fmax(m->node_gamma[na + i] * m->inv_mass[na + i],
                  m->node_gamma[na + i + 1] * m->inv_mass[na + i + 1]);
  /* the element's rotational rate: the same up to round-off under the
   * default mass-proportional damping, larger with rotational_damping */
  for (int k = 0; k < 3; k++) {
    double ce = SW_AT(m, m->elem_gamma, e, k) * SW_AT(m, m->inv_inertia, e, k);
    if (ce > c * (1 + 1e-9)) c = ce;
  }
  return c / (2 * w * mass_scale); /* heavier nodes, the same gamma */
}

/* The stable step of element i (its rest p at a radius scale whose node
 * masses are mass_scale times the model's) with its stiffnesses scaled
 * away from rest (sw_stable_dt_rod_at; all 1 at rest): the axial, shear
 * and twist frequencies of the header, the damping's ratio at the largest. */
static double elem_limit(const swModel *m, int r, int i, const elemRest *p, double mass_scale,
                         double axial, double lateral, double turn, double bend) {
  const double w2_axial = 4 * p->E / (p->rho * p->l * p->l) * axial;
  const double w2_shear = 16.0 / 3.0 * p->Gs / p->rho * (lateral / (p->l * p->l) + turn / (p->rad * p->rad)) +
                          4 * p->E / (p->rho * p->l * p->D) * bend;
  const double w2_twist = 4 * p->Gt / (p->rho * p->l * p->D) * bend;
  const double w = sqrt(fmax(w2_axial, fmax(w2_shear, w2_twist)));
  return 0.95 * sw_integrator_stability_limit(m->integrator, elem_zeta(m, r, i, w, mass_scale)) / w;
}

/* The bound of rod r's elastic waves on an explicit kick, whether or not
 * the rod is kicked so: an implicit rod keeps its factorisation while its
 * frames turn by a small fraction of (this / dt)^2 (rod_implicit.c). */
static double elastic_at(const swModel *m, int r, const double *g, int ng, int grows);

double sw_stable_dt_elastic(const swModel *m, int r) {
  int grows;
  double g[2];
  const int ng = rod_scales(m, r, g, &grows);
  return elastic_at(m, r, g, ng, grows);
}

/* Rod r's elastic bound at radius scales g[0..ng) (the rod's own mass
 * mode; 1 for a rod that does not swell): for the simulator, which checks
 * a run longer than the compiled one against the radius it reaches. */
double sw_stable_dt_elastic_at(const swModel *m, int r, double g) {
  const int k = m->nswell ? sw_swell_of_rod(m, r) : -1;
  return elastic_at(m, r, &g, 1, k >= 0 && (m->swell_flags[k] & SW_SWELL_MASS_GROWS));
}

static double elastic_at(const swModel *m, int r, const double *g, int ng, int grows) {
  double dt = INFINITY;
  for (int i = 0; i < m->rod_nelem[r]; i++)
    for (int a = 0; a < ng; a++) {
      double ms;
      const elemRest p = elem_at_scale(elem_rest(m, r, i), g[a], grows, &ms);
      dt = fmin(dt, elem_limit(m, r, i, &p, ms, 1.0, 1.0, 1.0, 1.0));
    }
  return dt;
}

double sw_stable_dt_rod(const swModel *m, int r) {
  /* a rigid rod has no elastic waves; only its damping limits the step */
  if (sw_rod_is_rigid(m, r)) return sw_rigid_stable_dt(m, m->rod_rigid[r]);
  /* an implicit rod's elasticity and linear damping are integrated by the
   * trapezoidal rule (rod_implicit.c): nothing of its own bounds the step */
  if (m->nimplicit && m->rod_implicit[r]) return INFINITY;
  double dt = sw_stable_dt_elastic(m, r);
  /* a muscle filament's Hill damping (muscle.c) */
  for (int f = 0; f < m->nfil; f++)
    if (m->fil_rod[f] == r) dt = fmin(dt, 0.95 * sw_muscle_ops(m)->stable_dt_filament(m, f));
  return dt;
}

/* The same bound away from rest, at dilatation e of every element and eps
 * of every Voronoi domain, the rod kept straight.  Linearising each law about
 * that state (docs/physics.md, "Muscles and the constitutive law"):
 *   Gazzola's n = S^ (s - s0) / e, c = B^ k / eps^3, J^ / e:
 *     stretch      dn3/de = S^3 (1 + s0_3) / e^2      axial      x (1+s0_3) / e^2
 *     shear        dn1/ds1 = S^1 / e                  lateral    x 1 / e
 *     shear couple (l^ e) (S^1 e theta / e), J^ / e  rotation   x e^2
 *     bend, twist  B^ / eps^3, J^ / e                           x e / eps^3
 *   the variational law (no 1/e, no 1/eps^3, Simo's J^): only the shear
 *   couple's lever, x e^2.
 * The compression's own geometric stiffness is left out (it is what buckles
 * a compressed rod, at a rate no step changes).  At e = eps = 1 and s0 = 0
 * this is sw_stable_dt_rod's bound without the filaments' terms. */
double sw_stable_dt_rod_at(const swModel *m, int r, double e, double eps) {
  if (sw_rod_is_rigid(m, r) || (m->nimplicit && m->rod_implicit[r])) return INFINITY;
  const int var = m->rod_law[r] == SW_LAW_VARIATIONAL, n = m->rod_nelem[r];
  double dt = INFINITY, g[2];
  int grows;
  const int ng = rod_scales(m, r, g, &grows);
  for (int i = 0; i < n; i++)
    for (int a = 0; a < ng; a++) {
      double ms;
      const elemRest p = elem_at_scale(elem_rest(m, r, i), g[a], grows, &ms);
      const double s03 = SW_AT(m, m->rest_sigma, m->elem_adr[r] + i, 2);
      const double axial = var ? 1 : (1 + s03) / (e * e), lateral = var ? 1 : 1 / e;
      const double turn = e * e, bend = var ? 1 : e / (eps * eps * eps);
      dt = fmin(dt, elem_limit(m, r, i, &p, ms, axial, lateral, turn, bend));
    }
  return dt;
}

/* Node i's side of joint j: the joint spring k is one more spring on the
 * node, so the Gershgorin row of the node in the lumped chain (of which the
 * rod's axial bound 4 EA/(l m) is the interior-node instance) bounds the
 * frequency: w^2 = (2 sum EA/l + s k) / m_i over the node's elements, with
 * s = 2 when the other end is a node that can move against it and s = 1
 * for an anchor (EA is replaced by the shear stiffness where larger, the
 * transverse row).  The joint damper adds c = s nu / m_i to the node's
 * damping rate.
 *
 * On an implicit rod under imex (rod_kept_implicitly) the rod's own terms
 * drop out and the joint's alone are left: its kick is (M + h^2/4 K) du =
 * h (F_rod + F_joint), and for K the rod's stiffness and k the explicit
 * joint's the step is stable while h^2 (K + k) <= 4 (M + h^2 K / 4) in
 * every mode, that is h^2 k <= 4 M: K cancels (one node: w^2 = s k / m_i).
 * Counted, the rod's stiffness made a joint with an arm on a thin bone the
 * scene's bound (the wing with the reference code's hand: 545 ns, where it
 * runs at 1 us, docs/validation.md). */
static int rod_kept_implicitly(const swModel *m, int r) {
  return m->nimplicit && m->rod_implicit[r];
}

static double joint_node_dt(const swModel *m, const swJointDesc *jd, int i, int e, double s) {
  int r = sw_rod_of_elem(m, e);
  int first = m->node_adr[r], last = first + m->rod_nelem[r];
  double ksum = 0;
  for (int q = i - 1; q <= i && !rod_kept_implicitly(m, r); q++) { /* elements i-1, i of node i */
    if (q < first || q >= last) continue;
    int el = m->elem_adr[r] + (q - first);
    ksum += fmax(SW_AT(m, m->shear_stiff, el, 2), SW_AT(m, m->shear_stiff, el, 0)) * m->inv_rest_len[el];
  }
  double w = sqrt((2 * ksum + s * jd->stiffness) * m->inv_mass[i]);
  if (!(w > 0)) return INFINITY; /* nothing stiff on the node */
  double c = s * jd->damping * m->inv_mass[i];
  if (m->rod_damping[r] == SW_DAMP_LINEAR && !rod_kept_implicitly(m, r))
    c += m->node_gamma[i] * m->inv_mass[i];
  return 0.95 * sw_integrator_stability_limit(m->integrator, c / (2 * w)) / w;
}

/* Element e's side of joint j: the element's rotation row of the rod bound
 * above, 16/3 Gs/rho (1/l^2 + 1/r^2) + 2 sum B/(D J) over its Voronoi domains,
 * with the joint couple k_t as one more domain, s k_t / J (J the bending
 * inertia rho l I).  For an end element the rod bound counts two domains where
 * the rod has one, so the default k_t = B/D costs nothing there.  A limit's
 * penalty k_l acts about the hinge axis (or the cone's swing), k_t across
 * it, so the row takes the larger of the two (joint.c, "Limits").  On an
 * implicit rod the joint's terms alone (joint_node_dt). */
static double joint_elem_dt(const swModel *m, const swJointDesc *jd, int e, int s) {
  int r = sw_rod_of_elem(m, e), i = e - m->elem_adr[r], n = m->rod_nelem[r], va = m->vor_adr[r];
  double l = m->rest_len[e], rad = m->radius[e], A = SW_PI * rad * rad;
  double rho = SW_AT(m, m->inertia, e, 0) / (l * A * rad * rad / 4.0);
  double Gs = SW_AT(m, m->shear_stiff, e, 0) / (A * 4.0 / 3.0);
  double J = SW_AT(m, m->inertia, e, 0), bend = 0;
  if (i > 0) bend += SW_AT(m, m->bend_stiff, va + i - 1, 0) / m->rest_vor_len[va + i - 1];
  if (i < n - 1) bend += SW_AT(m, m->bend_stiff, va + i, 0) / m->rest_vor_len[va + i];
  const int own = !rod_kept_implicitly(m, r); /* the rod's own terms */
  double w2 = own ? 16.0 / 3.0 * Gs / rho * (1 / (l * l) + 1 / (rad * rad)) +
                        (2 * bend + s * sw_joint_rot_bound_stiffness(jd)) / J
                  : s * sw_joint_rot_bound_stiffness(jd) / J;
  double w = sqrt(w2);
  if (!(w > 0)) return INFINITY;
  double c = s * sw_joint_rot_bound_damping(jd) / J;
  if (m->rod_damping[r] == SW_DAMP_LINEAR && own) c += SW_AT(m, m->elem_gamma, e, 0) / J;
  return 0.95 * sw_integrator_stability_limit(m->integrator, c / (2 * w)) / w;
}

/* A side on a rigid rod is bounded by rigid.c instead: the body's effective
 * mass and inertia at the joint, with every joint on the body counted. */
static double joint_side_dt(const swModel *m, const swJointDesc *jd, int rod, int node, int elem,
                            int s) {
  if (sw_rod_is_rigid(m, rod)) return sw_rigid_joint_dt(m, m->rod_rigid[rod]);
  double dt = joint_node_dt(m, jd, node, elem, s);
  if (jd->kind != SW_JOINT_SPHERICAL || sw_joint_limited(jd)) dt = fmin(dt, joint_elem_dt(m, jd, elem, s));
  return dt;
}

/* A limit on a joint integrated implicitly (rigid_joint.c): its tangent is
 * in the system, but whether it acts is decided at the kick's midpoint, so
 * a step that enters and leaves contact within a swing of the limit's own
 * frequency chatters (measured: a rigid pendulum pressed on a stiff hinge
 * limit settles at 0.5 of 2 / w and never settles at 0.9), so the limit
 * keeps its explicit bound, w^2 = s k_l / I_min of each moving body, or of
 * the element of an elastic side (its bending inertia J^_1: an attachment's
 * or an implicit rod's port's). */
static double implicit_limit_dt(const swModel *m, int j) {
  const swJointDesc *jd = &m->joint[j];
  if (!sw_joint_limited(jd)) return INFINITY;
  const int s = jd->rod_b >= 0 ? 2 : 1;
  double dt = INFINITY;
  for (int side = 0; side < 2; side++) {
    const int k = m->joint_block[2 * j + side];
    if (k < 0) continue; /* space or a fixed body */
    const int b = m->rigid_block_body[k], e = side ? m->joint_elem_b[j] : m->joint_elem_a[j];
    const double Imin = b >= 0 ? m->rigid_inertia[3 * b] : SW_AT(m, m->inertia, e, 0);
    const double w = sqrt(s * jd->limit_stiffness / Imin), c = s * jd->limit_damping / Imin;
    if (w > 0) dt = fmin(dt, 0.95 * sw_integrator_stability_limit(m->integrator, c / (2 * w)) / w);
  }
  return dt;
}

double sw_stable_dt_joint(const swModel *m, int j) {
  if (m->joint_implicit[j]) return implicit_limit_dt(m, j); /* rigid_joint.c */
  const swJointDesc *jd = &m->joint[j];
  int s = m->joint_node_b[j] >= 0 ? 2 : 1;
  double dt = joint_side_dt(m, jd, jd->rod_a, m->joint_node_a[j], m->joint_elem_a[j], s);
  if (sw_joint_has_arm(jd) && !sw_rod_is_rigid(m, jd->rod_a)) {
    /* the arm r turns element a with k |r|^2 (and c |r|^2): one more domain
     * of its rotation row, as a hinge's couple is */
    swJointDesc turn = *jd;
    const double r2 = sw_v3_dot(jd->arm_a, jd->arm_a);
    turn.rot_stiffness = sw_joint_rot_bound_stiffness(jd) + jd->stiffness * r2;
    turn.rot_damping = sw_joint_rot_bound_damping(jd) + jd->damping * r2;
    turn.limit_stiffness = turn.limit_damping = 0;
    dt = fmin(dt, joint_elem_dt(m, &turn, m->joint_elem_a[j], 1));
  }
  if (m->joint_node_b[j] >= 0)
    dt = fmin(dt, joint_side_dt(m, jd, jd->rod_b, m->joint_node_b[j], m->joint_elem_b[j], s));
  return dt;
}

/* A kinematic joint's spring on its follower node (kinematic.c), bounded as
 * a joint's node row whose spring pulls, at its other end, the point p the
 * reaction goes to: the leader's element at xi, shared (1 - xi), xi by its
 * two nodes, or a reaction node with weight w.  Two masses on a spring have
 * w^2 = k (1 / m_f + 1 / m_p), so the row's s = 1 + m_f / m_p with p's
 * inverse mass 1 / m_p = (1 - xi)^2 / m_a + xi^2 / m_b (w^2 / m_r): 2 for
 * equal masses, as a joint between two free nodes, and about 1 against a
 * heavy leader (a rachis on a bone).  On an explicit rod the kick moves
 * the node by its lumped mass; on an implicit one (M + h^2 K / 4)^-1 moves
 * it less.  A rigid body's point may move more than its node's lumped mass
 * says (its turn adds r^2 / I), so against a rigid body the row keeps
 * s = 2, as a joint's. */
double sw_stable_dt_kinematic(const swModel *m, int j) {
  const swKinematicDesc *k = &m->kinematic[j];
  swJointDesc jd;
  memset(&jd, 0, sizeof jd);
  jd.stiffness = k->stiffness;
  jd.damping = k->damping;
  const double xi = k->leader_xi, w = k->reaction_weight;
  const int a = k->leader_elem; /* its first node's slot; the second is a + 1 */
  const double inv_mp = k->reaction_rod >= 0 ? w * w * m->inv_mass[k->reaction_node]
                                             : (1 - xi) * (1 - xi) * m->inv_mass[a] + xi * xi * m->inv_mass[a + 1];
  const int rigid = sw_rod_is_rigid(m, k->reaction_rod >= 0 ? k->reaction_rod : k->leader_rod);
  const double s = rigid ? 2 : 1 + inv_mp / m->inv_mass[k->follower_node];
  return joint_node_dt(m, &jd, k->follower_node, k->follower_elem, s);
}

double sw_stable_dt(const swModel *m) {
  double dt = INFINITY;
  for (int r = 0; r < m->nrod; r++) dt = fmin(dt, m->rod_wave_dt[r]);
  for (int j = 0; j < m->njoint; j++) dt = fmin(dt, m->joint_wave_dt[j]);
  for (int j = 0; j < m->nkinematic; j++) dt = fmin(dt, m->kinematic_dt[j]);
  if (sw_has_env(m)) dt = fmin(dt, sw_env_ops(m)->stable_dt(m));
  return dt;
}

/* How many elastic slots in [lo, hi) sw_check_finite would object to: the
 * same tests with the same arithmetic, as one vector loop, so that a threaded
 * step checks its own chunks and calls the full check (which finds the rod
 * and writes the message) only when something is wrong.  On the way, each
 * element's shortest (d->shortest, with the time), which the message quotes:
 * a step that fails below the stable estimate usually fails because a rod
 * was squeezed far from rest, and by then it may have lengthened again. */
int sw_check_slots(const swModel *m, swData *d, int lo, int hi) {
  const size_t S = (size_t)m->stride;
  const double dt = m->dt, wmax2 = 0.25 / (dt * dt), t = d->time;
  const double *restrict x = d->x, *restrict v = d->v, *restrict w = d->omega;
  const double *restrict rl = m->rest_len, *restrict ghost = m->elem_ghost, *restrict dil = d->dilatation;
  double *restrict shortest = d->shortest, *restrict when = d->shortest_time;
  int bad = 0;
#pragma omp simd reduction(+ : bad)
  for (int i = lo; i < hi; i++) {
    const sw3 xi = sw3_load(x, S, i), vi = sw3_load(v, S, i);
    const double sum = xi.x + xi.y + xi.z + vi.x + vi.y + vi.z;
    const int real = ghost[i] == 0.0;
    const sw3 dv = sw3_sub(sw3_load(v, S, i + 1), vi);
    const double lim = 0.5 * rl[i] / dt, dv2 = sw3_dot(dv, dv);
    const sw3 wi = sw3_load(w, S, i);
    const double w2 = sw3_dot(wi, wi);
    bad += (!(sum - sum == 0.0)) | (real & (!(dv2 <= lim * lim))) | (real & (!(w2 <= wmax2)));
    const int shorter = real & (dil[i] < shortest[i]);
    shortest[i] = shorter ? dil[i] : shortest[i];
    when[i] = shorter ? t : when[i];
  }
  return bad;
}

/* A factor as the report prints it: whole above 10, two digits below. */
static void factor_text(char *out, size_t len, double f) {
  if (f >= 10) snprintf(out, len, "%.0f", f);
  else snprintf(out, len, "%.2g", f);
}

/* What the report adds when a rod fails at a step below the stable
 * estimate, which the rest state then does not explain: how short the rod
 * had become (its shortest element, now or at a check), the stable step of
 * the rod at that length (sw_stable_dt_rod_at), and on Gazzola's law, which
 * stiffens without bound as e -> 0, what the law does there and the way out.
 * Appended to msg (of size len). */
static void explain_below_estimate(const swModel *m, const swData *d, int r, char *msg, size_t len) {
  const int ea = m->elem_adr[r], na = m->node_adr[r], n = m->rod_nelem[r];
  double e_min = INFINITY, t_min = d->time;
  int i_min = 0;
  for (int i = 0; i < n; i++) {
    double x0[3], x1[3], dx[3];
    sw_get3(m, d->x, na + i, x0);
    sw_get3(m, d->x, na + i + 1, x1);
    sw_v3_sub(dx, x1, x0);
    const double now = sqrt(sw_v3_dot(dx, dx)) / m->rest_len[ea + i];
    if (now < e_min) { e_min = now; t_min = d->time; i_min = i; }
    if (d->shortest[ea + i] < e_min) { e_min = d->shortest[ea + i]; t_min = d->shortest_time[ea + i]; i_min = i; }
  }
  if (!(e_min > 0 && e_min < INFINITY)) return; /* nothing finite to say */
  const int gazzola = m->rod_law[r] != SW_LAW_VARIATIONAL;
  const double dt_at = sw_stable_dt_rod_at(m, r, e_min, e_min);
  size_t k = strlen(msg);
  k += (size_t)snprintf(msg + k, k < len ? len - k : 0,
                        ". As dt is below the estimate, the rest state does not explain it: the rod had "
                        "shortened to %.2g%% of its rest length (element %d, t = %.6g s)",
                        100 * e_min, i_min, t_min);
  const double s03 = SW_AT(m, m->rest_sigma, ea + i_min, 2);
  if (gazzola && e_min < 0.5 && k < len) {
    /* n3 = S^3 (e - 1 - s0_3) / e and its slope S^3 (1 + s0_3) / e^2, in
     * units of the rest ones (the element kept straight) */
    char push[32], stiff[32];
    factor_text(push, sizeof push, (1 + s03 - e_min) / e_min);
    factor_text(stiff, sizeof stiff, (1 + s03) / (e_min * e_min));
    k += (size_t)snprintf(msg + k, len - k,
                          ", where Gazzola et al. 2018's law (n = S^ s / e, c = B^ k / eps^3) pushes "
                          "back with %s times E A and is %s times as stiff in stretch as at rest",
                          push, stiff);
  }
  if (k < len && isfinite(dt_at)) /* an implicit rod's elasticity bounds nothing */
    k += (size_t)snprintf(msg + k, len - k,
                          "; the rod's stable dt at that length is %.2g s (%.2g s at rest), %s", dt_at,
                          sw_stable_dt_rod_at(m, r, 1, 1),
                          dt_at > m->dt ? "still above dt, so the step is not the cause"
                                        : "and dt is above it");
  if (gazzola && e_min < 0.5 && k < len)
    snprintf(msg + k, len - k, ". The variational law (`variational = true` on its material, the "
             "default for muscles) keeps the loads bounded as a rod shortens");
}

/* sw_check_finite on every rod, or (rigid_only) on the rigid ones alone,
 * which sw_check_slots' vector count does not cover (integrate.c calls it
 * so every few steps: a scene with rigid bodies used to run the whole
 * scalar check there, 1.3% of the kinematic wing's step). */
int sw_check_rods(const swModel *m, swData *d, int rigid_only) {
  const double dt = m->dt;
  for (int r = 0; r < m->nrod; r++) {
    if (rigid_only && !sw_rod_is_rigid(m, r)) continue;
    int na = m->node_adr[r], ea = m->elem_adr[r], n = m->rod_nelem[r];
    /* unresolved motion: an element changing by half its rest length, or
     * turning half a radian, in a single step (relative velocities, so a
     * rod in free fall or carried along is not flagged) */
    const double wmax2 = 0.25 / (dt * dt);
    int bad = -1;
    const char *what = "";
    double val = 0;
    for (int i = na; i <= na + n && bad < 0; i++) {
      double x[3], v[3];
      sw_get3(m, d->x, i, x);
      sw_get3(m, d->v, i, v);
      if (!isfinite(x[0] + x[1] + x[2] + v[0] + v[1] + v[2])) {
        bad = i - na;
        what = "position or velocity is not finite";
      } else if (i < na + n && !sw_rod_is_rigid(m, r)) { /* rigid: the turn check below */
        double v1[3], dv[3];
        sw_get3(m, d->v, i + 1, v1);
        sw_v3_sub(dv, v1, v);
        double lim = 0.5 * m->rest_len[ea + i - na] / dt, dv2 = sw_v3_dot(dv, dv);
        if (!(dv2 <= lim * lim)) {
          bad = i - na;
          what = "an element deforms by more than half its length per step";
          val = sqrt(dv2);
        }
      }
    }
    for (int e = ea; e < ea + n && bad < 0; e++) {
      double w[3];
      sw_get3(m, d->omega, e, w);
      double w2 = sw_v3_dot(w, w);
      if (!(w2 <= wmax2)) {
        bad = e - ea;
        what = isfinite(w2) ? "an element turns more than half a radian per step"
                            : "angular velocity is not finite";
      }
    }
    if (bad >= 0) {
      int elem = bad < n ? bad : n - 1; /* a node's element: the one it starts */
      char speed[64] = "";
      if (val > 0) snprintf(speed, sizeof speed, " (relative speed %.3g m/s)", val);
      const double estimate = sw_stable_dt(m);
      snprintf(d->error, sizeof d->error,
               "rod '%s' became unstable at element %d, t = %.9g s: %s%s; "
               "dt = %.3g s, stable dt estimate %.3g s",
               m->rod_name[r], elem, d->time, what, speed, m->dt, estimate);
      if (m->dt <= estimate && !sw_rod_is_rigid(m, r)) explain_below_estimate(m, d, r, d->error, sizeof d->error);
      return SW_EUNSTABLE;
    }
  }
  return SW_OK;
}

int sw_check_finite(const swModel *m, swData *d) { return sw_check_rods(m, d, 0); }
