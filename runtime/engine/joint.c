/* joint.c — joints: penalty connections between a node of one rod and a node
 * of another (or the same) rod, or a fixed point in space.
 *
 * Design.  A joint is a spring-damper, as in Zhang et al. 2019 (Methods,
 * "joints") and PyElastica's joint.py, and never a hard constraint: it adds
 * loads to the step like any other load and needs no solver.  Every joint
 * holds its two nodes together; a hinge and a fixed joint also exchange an
 * equal and opposite couple between the two elements next to the nodes (node
 * 0 -> element 0, node n -> element n-1, interior node i -> element i).  Side
 * a is always a rod; side b is a rod or, when rod_b < 0, space (an anchor
 * point with zero velocity and a frame that never turns).
 *
 *   position (all kinds), gap g = x_b - x_a:
 *     F_a = k g + nu (v_b - v_a),  F_b = -F_a;      U = k |g|^2 / 2
 *   hinge: the axis is carried by both sides, a_a = Q_a^T alpha_a and
 *     a_b = Q_b^T alpha_b (alpha the axis in each element's material frame at
 *     t = 0; a_b is the lab axis itself when anchored):
 *     U = k_t (1 - a_a . a_b),  couple on a  C_a = k_t a_a x a_b,  C_b = -C_a,
 *     plus  C_a = c_t (w_b - w_a)_perp, the relative angular velocity
 *     without its component along the axis.
 *   fixed: with Q_b* = (Q_b Q_a^T)|_{t=0} Q_a the frame rod b would have if
 *     it moved rigidly with rod a, and phi = log(Q_b Q_b*^T) the rotation
 *     from there to Q_b (lab components Phi = Q_b^T phi; vec.h):
 *     U = k_t |phi|^2 / 2,  C_b = -k_t Phi,  C_a = k_t Phi,
 *     plus  C_a = c_t (w_b - w_a).  Anchored: Q_b* = Q_a(t = 0), C_a = -k_t Phi.
 *   spherical: position only (and its cone, below).
 * The couples are exact gradients of U (for the fixed joint because the
 * rotation vector of exp(phi) is its own gradient, J(phi)^T phi = phi), and
 * they come in equal and opposite pairs, so an undamped jointed system
 * conserves energy and angular momentum.  Why a hinge constrains the axis on
 * both sides and not only rod b's tangent (U = k_t (d3_b . a)^2 / 2, as in
 * PyElastica): a hinge removes two relative rotations; the tangent form
 * removes one, leaving rod b free to spin about its own tangent, and it would
 * force the tangent perpendicular to the axis even when the scene starts it
 * otherwise.  For bending out of the hinge's plane both give the couple
 * k_t theta to leading order.
 *
 * Energy bookkeeping: the spring parts go into d->force / d->torque only,
 * like the rods' own elastic loads, and sw_joint_energy() adds their U to the
 * elastic energy; the damping parts also go into d->ext_force / ext_torque,
 * so the kick books their (negative) work.  Then kinetic + elastic - work is
 * conserved, damped or not.
 *
 * Hinge angle (d->joint_angle, /joints/NAME/angle): between two rods, the
 * angle from rod a's tangent to rod b's tangent about the axis at t = 0 (0
 * when they continue each other straight), plus the relative rotation of
 * element b with respect to element a about the axis since then; anchored,
 * the rotation of rod a's element about the axis since t = 0.  It is unwrapped
 * from evaluation to evaluation, so it is continuous past +-pi.
 *
 * Limits.  A hinge may have an angle range [angle_min, angle_max] and a
 * spherical joint a cone (the largest swing); outside them a one-sided
 * penalty couple pushes back, as a contact does (MuJoCo's joint limits and
 * OpenSim's coordinate limit forces are of this kind).  Each limit measures a
 * coordinate q whose rate is a projection of the relative angular velocity,
 *   dq = (dalpha_F - dalpha_M) . g,
 * F the side carrying the reference (rod a; space when anchored) and M the
 * side that moves against it (rod b; rod a when anchored), dalpha their
 * small rotations (lab):
 *   hinge: e1, e2 = u x e1 carried by F (e1 normal to the axis u at t = 0),
 *     r carried by M (= e1 at t = 0); x = e1 . r, y = e2 . r,
 *     q = angle0 + atan2(y, x) (unwrapped against the hinge angle),
 *     g = (x e2 - y e1) x r / (x^2 + y^2);
 *     turning M by +dphi about u gives dq = +dphi (g = -u when r lies in
 *     the plane), so q is the hinge angle above; the two differ only by the
 *     square of the hinge's small off-axis misalignment.
 *   cone: r carried by F (rod b's tangent at t = 0, or rod a's when
 *     anchored), t the tangent of M's element;
 *     q = psi = atan2(|t x r|, t . r),  g = (t x r) / |t x r|.
 * With the violation delta = q - q_max above the upper bound, q - q_min below
 * the lower (the cone's lower bound is none), 0 inside,
 *   U = k_l delta^2 / 2,  generalised force f = -k_l delta - c_l dq/dt,
 *   couple on F  C_F = f g,  on M  C_M = -f g,
 * the spring part the exact gradient of U (equal and opposite), the damping
 * part acting only while delta != 0.  f is clipped so that it never pulls
 * the joint further into the limit (f <= 0 above, >= 0 below: the contact
 * does not stick); the clipped damping still only takes energy out.  The
 * spring part is bookkept like the other springs (U into the elastic
 * energy), the damping part like the other dampers (into ext_torque).  The
 * limit's couple on rod a (its spring and damping parts; the one on rod b
 * is its opposite) is d->joint_limit_torque, /joints/NAME/limit_torque.
 *
 * Defaults (0 in swJointDesc means "choose"; the compiled model->joint holds
 * what was chosen).  The penalty has to be stiff enough that the gap stays a
 * small fraction of an element and soft enough not to lower the stable time
 * step, which the rods' stiffest elements already set:
 *   k   = min(EA/l) / 2 over the connected elements.  With it the gap under a
 *         force F is 2 F l / (EA), the stretch of two elements of the softer
 *         rod, and a lumped chain with such a joint (two rods, or a rod and an
 *         anchor) keeps its highest axial frequency within 10 % of the rod's
 *         own, while the element shear/rotation frequency that sets a rod's
 *         step is at least 1.2 times higher (for G = E/3), so the step does
 *         not change: two rods of 10 elements joined this way blow up at the
 *         same step as one rod of 20 (undamped joint) or at 0.98 of it
 *         (default damping), and stability.c's joint bound stays 5-10 %
 *         below the measured limit, as the rods' own does.
 *   k_t = min(EI) / D, D the distance between the two element centres
 *         ((l_a + l_b)/2; l_a/2 when anchored): the Voronoi domain the joint
 *         stands in for, so that two rods joined by a fixed joint bend like
 *         one rod, and an anchored fixed joint is the clamp of boundary.c.
 *   nu  = 0.1 * 2 sqrt(k mu), c_t = 0.1 * 2 sqrt(k_t J_mu): a tenth of
 *         critical for the joint's own spring with the reduced node mass mu
 *         (node mass when anchored) or reduced element inertia J_mu (bending
 *         inertia rho l I).  Damping is explicit in the kick, and the explicit
 *         schemes lose stable step quickly with damping at the highest
 *         frequencies (position Verlet: h w < 2 undamped, < 0.83 at critical),
 *         so critical damping would cost up to half the step; a tenth still
 *         damps a gap oscillation by e^-0.63 per period.
 *   k_l = k_t for a hinge's range (the joint's own rotational stiffness, as
 *         given or chosen), min(EI) / D for a spherical joint's cone (what
 *         k_t would be): the same stiffness about the axis as across it, so
 *         the element's rotation bound in stability.c, which takes the larger
 *         of k_t and k_l, does not change by default, and the overshoot under
 *         a couple tau is tau / k_l, the bend of the Voronoi domain the joint
 *         stands in for.  c_l = 0.1 * 2 sqrt(k_l J_mu), as c_t.
 */
#include <math.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

static const double SW_JOINT_ZETA = 0.1; /* default damping, fraction of critical */

void sw_joint_desc_init(swJointDesc *j) {
  memset(j, 0, sizeof *j);
  j->name = "joint";
  j->kind = SW_JOINT_SPHERICAL;
  j->rod_a = 0;
  j->node_a = -1;
  j->rod_b = -1;
  j->node_b = 0;
}

/* C = A B^T */
static void mat_mul_T(double *C, const double *A, const double *B) {
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) T[3 * i + k] = sw_v3_dot(A + 3 * i, B + 3 * k);
  memcpy(C, T, sizeof T);
}

/* The element of rod r that takes the couples of a joint at its node i. */
static int joint_element(const swModel *m, int r, int i) {
  int n = m->rod_nelem[r];
  return m->elem_adr[r] + (i < n ? i : n - 1);
}

int sw_joint_limited(const swJointDesc *jd) {
  return (jd->kind == SW_JOINT_HINGE && jd->has_range) ||
         (jd->kind == SW_JOINT_SPHERICAL && jd->cone > 0);
}

/* Whether the joint exchanges couples (rows ROW_CA..ROW_CDB). */
static int has_couples(const swJointDesc *jd) {
  return jd->kind != SW_JOINT_SPHERICAL || sw_joint_limited(jd) || sw_joint_has_arm(jd);
}

/* The limits' reference directions (the top of the file), ref = 9 doubles:
 *   hinge, two rods:  e1, e2 in rod a's material frame, r = e1 in rod b's;
 *   hinge, anchored:  e1, e2 in the lab, r = e1 in rod a's material frame;
 *   cone, two rods:   rod b's tangent at t = 0 in rod a's material frame;
 *   cone, anchored:   rod a's tangent at t = 0 in the lab.
 * e1 is rod a's tangent without its part along the axis (any normal to the
 * axis when the tangent lies along it; q does not depend on the choice). */
static void limit_setup(swModel *m, int j, const double *Qa0, const double *Qb0) {
  const swJointDesc *jd = &m->joint[j];
  double *ref = m->joint_limit_ref + 9 * j;
  memset(ref, 0, 9 * sizeof *ref);
  if (!sw_joint_limited(jd)) return;
  if (jd->kind == SW_JOINT_SPHERICAL) {
    if (Qb0) sw_mat_vec(ref, Qa0, Qb0 + 6);
    else memcpy(ref, Qa0 + 6, 3 * sizeof *ref);
    return;
  }
  double u[3], e1[3], e2[3];
  sw_v3_scale(u, jd->axis, 1.0 / sw_v3_norm(jd->axis));
  const double *ta = Qa0 + 6;
  for (int k = 0; k < 3; k++) e1[k] = ta[k] - sw_v3_dot(ta, u) * u[k];
  if (sw_v3_norm(e1) < 1e-6) { /* tangent along the axis: any normal */
    const double x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
    sw_v3_cross(e1, u, fabs(u[0]) < 0.9 ? x : y);
  }
  sw_v3_scale(e1, e1, 1.0 / sw_v3_norm(e1));
  sw_v3_cross(e2, u, e1);
  if (Qb0) {
    sw_mat_vec(ref, Qa0, e1);
    sw_mat_vec(ref + 3, Qa0, e2);
    sw_mat_vec(ref + 6, Qb0, e1);
  } else {
    memcpy(ref, e1, sizeof e1);
    memcpy(ref + 3, e2, sizeof e2);
    sw_mat_vec(ref + 6, Qa0, e1);
  }
}

double sw_joint_rot_bound_stiffness(const swJointDesc *jd) {
  return fmax(jd->rot_stiffness, jd->limit_stiffness);
}
double sw_joint_rot_bound_damping(const swJointDesc *jd) {
  return fmax(jd->rot_damping, jd->limit_damping);
}

void sw_joint_setup(swModel *m) {
  for (int j = 0; j < m->njoint; j++) {
    swJointDesc *jd = &m->joint[j];
    const int anchored = jd->rod_b < 0;
    int ra = jd->rod_a, rb = jd->rod_b;
    if (jd->node_a < 0) jd->node_a = m->rod_nelem[ra];
    int na = m->node_adr[ra] + jd->node_a, ea = joint_element(m, ra, jd->node_a);
    int nb = -1, eb = -1;
    if (!anchored) {
      if (jd->node_b < 0) jd->node_b = m->rod_nelem[rb];
      nb = m->node_adr[rb] + jd->node_b;
      eb = joint_element(m, rb, jd->node_b);
    } else {
      jd->node_b = -1;
    }
    m->joint_node_a[j] = na;
    m->joint_node_b[j] = nb;
    m->joint_elem_a[j] = ea;
    m->joint_elem_b[j] = eb;
    { /* side a's arm in its element's material frame: o = Q_a(0) r */
      double Qa0[9];
      sw_getQ(m, m->Q0, ea, Qa0);
      sw_mat_vec(m->joint_arm_a + 3 * j, Qa0, jd->arm_a);
    }

    /* defaults (see the top of the file) */
    double axial_a = SW_AT(m, m->shear_stiff, ea, 2) * m->inv_rest_len[ea];
    double axial = anchored ? axial_a
                            : fmin(axial_a, SW_AT(m, m->shear_stiff, eb, 2) * m->inv_rest_len[eb]);
    double mu = anchored ? m->mass[na] : m->mass[na] * m->mass[nb] / (m->mass[na] + m->mass[nb]);
    if (jd->stiffness == 0) jd->stiffness = 0.5 * axial;
    if (jd->damping == 0 && !jd->undamped)
      jd->damping = SW_JOINT_ZETA * 2.0 * sqrt(jd->stiffness * mu);
    double bend = anchored ? SW_AT(m, m->clamp_bend, ea, 0)
                           : fmin(SW_AT(m, m->clamp_bend, ea, 0), SW_AT(m, m->clamp_bend, eb, 0));
    double D = 0.5 * m->rest_len[ea] + (anchored ? 0.0 : 0.5 * m->rest_len[eb]);
    double Ja = SW_AT(m, m->inertia, ea, 0);
    double Jmu = anchored ? Ja : Ja * SW_AT(m, m->inertia, eb, 0) / (Ja + SW_AT(m, m->inertia, eb, 0));
    if (jd->kind == SW_JOINT_SPHERICAL) {
      jd->rot_stiffness = jd->rot_damping = 0;
    } else {
      if (jd->rot_stiffness == 0) jd->rot_stiffness = bend / D;
      if (jd->rot_damping == 0 && !jd->undamped)
        jd->rot_damping = SW_JOINT_ZETA * 2.0 * sqrt(jd->rot_stiffness * Jmu);
    }
    if (sw_joint_limited(jd)) {
      if (jd->limit_stiffness == 0)
        jd->limit_stiffness = jd->kind == SW_JOINT_HINGE ? jd->rot_stiffness : bend / D;
      if (jd->limit_damping == 0 && !jd->undamped)
        jd->limit_damping = SW_JOINT_ZETA * 2.0 * sqrt(jd->limit_stiffness * Jmu);
    } else {
      jd->limit_stiffness = jd->limit_damping = 0;
    }

    /* rest geometry */
    double Qa0[9], Qb0[9] = {0}; /* Qb0 is read only when not anchored */
    sw_getQ(m, m->Q0, ea, Qa0);
    if (!anchored) sw_getQ(m, m->Q0, eb, Qb0);
    double *rest = m->joint_rest_rot + 9 * j;
    if (anchored) {
      memset(rest, 0, 9 * sizeof *rest);
      rest[0] = rest[4] = rest[8] = 1.0;
    } else {
      mat_mul_T(rest, Qb0, Qa0);
    }
    m->joint_angle0[j] = 0;
    if (jd->kind == SW_JOINT_HINGE) {
      double u[3];
      sw_v3_scale(u, jd->axis, 1.0 / sw_v3_norm(jd->axis));
      sw_mat_vec(m->joint_axis_a + 3 * j, Qa0, u);
      if (anchored) {
        memcpy(m->joint_axis_b + 3 * j, u, sizeof u);
      } else {
        sw_mat_vec(m->joint_axis_b + 3 * j, Qb0, u);
        /* angle from tangent a to tangent b about u, in the plane normal to u */
        const double *ta = Qa0 + 6, *tb = Qb0 + 6;
        double c[3];
        sw_v3_cross(c, ta, tb);
        m->joint_angle0[j] =
            atan2(sw_v3_dot(u, c), sw_v3_dot(ta, tb) - sw_v3_dot(ta, u) * sw_v3_dot(tb, u));
      }
    }
    limit_setup(m, j, Qa0, anchored ? NULL : Qb0);
  }
}

/* The continuous branch of an angle known modulo 2 pi, nearest to prev. */
static double unwrap(double angle, double prev) {
  return angle + 2.0 * SW_PI * nearbyint((prev - angle) / (2.0 * SW_PI));
}

/* One joint in the current state: loads on side a (side b gets minus), lab. */
typedef struct {
  double force[3];       /* spring force on node a                          */
  double force_damp[3];  /* damping force on node a                         */
  double couple[3];      /* spring couple on element a                      */
  double couple_damp[3]; /* damping couple on element a                     */
  double arm[3];         /* the spring force's couple on element a about node a
                            (side a's arm; not passed on to element b)     */
  double arm_damp[3];    /* the damping force's                              */
  double energy;         /* stored in the springs, J                        */
  double angle;          /* hinge angle, not unwrapped (0 for other kinds)  */
  double limit[3];       /* the limit's couple on element a (in the above)  */
} swJointEval;

/* The limit's coordinate q, its direction g (dq = (dalpha_F - dalpha_M) . g)
 * and the sign of rod a's side (+1: rod a is F), from the current frames
 * (the top of the file); returns 0 if g is undefined (the reference and the
 * moving direction parallel, or for a hinge the moving one along the axis). */
static int limit_coordinate(const swModel *m, const swData *d, int j, const double *Qa,
                            const double *Qb, double *q, double *g, double *sign_a) {
  const swJointDesc *jd = &m->joint[j];
  const double *ref = m->joint_limit_ref + 9 * j;
  *sign_a = Qb ? 1.0 : -1.0;
  if (jd->kind == SW_JOINT_SPHERICAL) {
    double r[3], t[3], c[3];
    if (Qb) {
      sw_matT_vec(r, Qa, ref);
      memcpy(t, Qb + 6, sizeof t);
    } else {
      memcpy(r, ref, sizeof r);
      memcpy(t, Qa + 6, sizeof t);
    }
    sw_v3_cross(c, t, r);
    const double s = sw_v3_norm(c);
    *q = atan2(s, sw_v3_dot(t, r));
    if (!(s > 1e-12)) return 0;
    sw_v3_scale(g, c, 1.0 / s);
    return 1;
  }
  double e1[3], e2[3], r[3], w[3];
  if (Qb) {
    sw_matT_vec(e1, Qa, ref);
    sw_matT_vec(e2, Qa, ref + 3);
    sw_matT_vec(r, Qb, ref + 6);
  } else {
    memcpy(e1, ref, sizeof e1);
    memcpy(e2, ref + 3, sizeof e2);
    sw_matT_vec(r, Qa, ref + 6);
  }
  const double x = sw_v3_dot(e1, r), y = sw_v3_dot(e2, r), rho2 = x * x + y * y;
  if (!(rho2 > 1e-12)) return 0;
  *q = unwrap(m->joint_angle0[j] + atan2(y, x), d->joint_angle[j]);
  for (int k = 0; k < 3; k++) w[k] = (x * e2[k] - y * e1[k]) / rho2;
  sw_v3_cross(g, w, r);
  return 1;
}

/* The limit's couple (the top of the file) into o: spring and damping parts
 * on element a, the energy, and the whole in o->limit.  dw = w_b - w_a. */
static void limit_eval(const swModel *m, const swData *d, int j, const double *Qa,
                       const double *Qb, const double *dw, swJointEval *o) {
  const swJointDesc *jd = &m->joint[j];
  double q, g[3], sign_a;
  if (!limit_coordinate(m, d, j, Qa, Qb, &q, g, &sign_a)) return;
  const double lo = jd->kind == SW_JOINT_HINGE ? jd->angle_min : -INFINITY;
  const double hi = jd->kind == SW_JOINT_HINGE ? jd->angle_max : jd->cone;
  const double delta = q > hi ? q - hi : q < lo ? q - lo : 0.0;
  if (delta == 0) return;
  /* dq/dt = (w_F - w_M) . g = -sign_a (w_b - w_a) . g (anchored, w_b = 0) */
  const double rate = -sign_a * sw_v3_dot(dw, g);
  const double spring = -jd->limit_stiffness * delta;
  double f = spring - jd->limit_damping * rate;
  f = delta > 0 ? fmin(f, 0.0) : fmax(f, 0.0); /* never pulls into the limit */
  for (int k = 0; k < 3; k++) {
    o->couple[k] += sign_a * spring * g[k];
    o->couple_damp[k] += sign_a * (f - spring) * g[k];
    o->limit[k] = sign_a * f * g[k];
  }
  o->energy += 0.5 * jd->limit_stiffness * delta * delta;
}

/* A limit's direction for rigid_joint.c's tangent: 1 and g when joint j is
 * outside its limits ((w_b - w_a) . g is the rate of q up to sign), 0
 * otherwise. */
int sw_joint_limit_tangent(const swModel *m, const swData *d, int j, double *g) {
  if (!sw_joint_limited(&m->joint[j])) return 0;
  const int ea = m->joint_elem_a[j], eb = m->joint_elem_b[j];
  double Qa[9], Qb[9], q, sign_a;
  sw_getQ(m, d->Q, ea, Qa);
  if (eb >= 0) sw_getQ(m, d->Q, eb, Qb);
  if (!limit_coordinate(m, d, j, Qa, eb >= 0 ? Qb : NULL, &q, g, &sign_a)) return 0;
  const swJointDesc *jd = &m->joint[j];
  if (jd->kind == SW_JOINT_HINGE) return q > jd->angle_max || q < jd->angle_min;
  return q > jd->cone;
}

static void joint_eval(const swModel *m, const swData *d, int j, swJointEval *o) {
  const swJointDesc *jd = &m->joint[j];
  const int na = m->joint_node_a[j], nb = m->joint_node_b[j];
  const int ea = m->joint_elem_a[j], eb = m->joint_elem_b[j];
  static const double zero[3] = {0, 0, 0};
  memset(o, 0, sizeof *o);

  /* position: side a's point, node a plus its arm r = Q_a^T o moving with
   * element a (v + w x r) */
  double xa[3], va[3], xb[3], vb[3], r[3] = {0, 0, 0};
  sw_get3(m, d->x, na, xa);
  sw_get3(m, d->v, na, va);
  const int arm = sw_joint_has_arm(jd);
  if (arm) {
    double Q[9], w[3], wl[3], wr[3];
    sw_getQ(m, d->Q, ea, Q);
    sw_matT_vec(r, Q, m->joint_arm_a + 3 * j);
    sw_get3(m, d->omega, ea, w);
    sw_matT_vec(wl, Q, w);
    sw_v3_cross(wr, wl, r);
    sw_v3_add(xa, xa, r);
    sw_v3_add(va, va, wr);
  }
  if (nb >= 0) {
    sw_get3(m, d->x, nb, xb);
    sw_get3(m, d->v, nb, vb);
  } else {
    memcpy(xb, jd->anchor, sizeof xb);
    memcpy(vb, zero, sizeof vb);
  }
  double g[3], dv[3];
  sw_v3_sub(g, xb, xa);
  sw_v3_sub(dv, vb, va);
  sw_v3_scale(o->force, g, jd->stiffness);
  sw_v3_scale(o->force_damp, dv, jd->damping);
  o->energy = 0.5 * jd->stiffness * sw_v3_dot(g, g);
  if (arm) { /* the arm turns element a: r x F, the exact gradient of U in its rotation */
    sw_v3_cross(o->arm, r, o->force);
    sw_v3_cross(o->arm_damp, r, o->force_damp);
  }
  if (!has_couples(jd)) return;

  /* relative angular velocity w_b - w_a, lab */
  double Qa_[9], Qb_[9], om[3];
  const double *Qa = Qa_, *Qb = eb >= 0 ? Qb_ : NULL;
  sw_getQ(m, d->Q, ea, Qa_);
  if (Qb) sw_getQ(m, d->Q, eb, Qb_);
  double wa[3], wb[3] = {0, 0, 0}, dw[3];
  sw_get3(m, d->omega, ea, om);
  sw_matT_vec(wa, Qa, om);
  if (Qb) {
    sw_get3(m, d->omega, eb, om);
    sw_matT_vec(wb, Qb, om);
  }
  sw_v3_sub(dw, wb, wa);
  if (sw_joint_limited(jd)) limit_eval(m, d, j, Qa, Qb, dw, o);
  if (jd->kind == SW_JOINT_SPHERICAL) return;

  /* relative rotation Phi (lab) of side b from where it would be had it
   * moved rigidly with side a; anchored, of rod a from its initial frame */
  double target[9], phi[3], Phi[3];
  if (Qb) {
    sw_mat_mul(target, m->joint_rest_rot + 9 * j, Qa);
    sw_frame_log(phi, target, Qb);
    sw_matT_vec(Phi, Qb, phi);
  } else {
    double Qa0[9];
    sw_getQ(m, m->Q0, ea, Qa0);
    sw_frame_log(phi, Qa0, Qa);
    sw_matT_vec(Phi, Qa, phi);
  }

  const double kt = jd->rot_stiffness, ct = jd->rot_damping;
  if (jd->kind == SW_JOINT_HINGE) {
    double aa[3], ab[3];
    sw_matT_vec(aa, Qa, m->joint_axis_a + 3 * j);
    if (Qb) sw_matT_vec(ab, Qb, m->joint_axis_b + 3 * j);
    else memcpy(ab, m->joint_axis_b + 3 * j, sizeof ab);
    double c[3];
    sw_v3_cross(c, aa, ab);
    for (int k = 0; k < 3; k++) o->couple[k] += kt * c[k];
    o->energy += kt * (1.0 - sw_v3_dot(aa, ab));
    double along = sw_v3_dot(dw, aa);
    for (int k = 0; k < 3; k++) o->couple_damp[k] += ct * (dw[k] - along * aa[k]);
    /* anchored: the rod's rotation about the fixed axis */
    o->angle = m->joint_angle0[j] + sw_v3_dot(Phi, Qb ? aa : ab);
  } else { /* fixed */
    sw_v3_scale(o->couple, Phi, Qb ? kt : -kt);
    o->energy += 0.5 * kt * sw_v3_dot(phi, phi);
    sw_v3_scale(o->couple_damp, dw, ct);
  }
}

static void record(const swModel *m, swData *d, int j, const swJointEval *o) {
  sw_v3_add(d->joint_force + 3 * j, o->force, o->force_damp);
  memcpy(d->joint_limit_torque + 3 * j, o->limit, sizeof o->limit);
  d->joint_angle[j] = m->joint[j].kind == SW_JOINT_HINGE ? unwrap(o->angle, d->joint_angle[j]) : 0.0;
}

void sw_joint_measure(const swModel *m, swData *d, int j) {
  swJointEval o;
  joint_eval(m, d, j, &o);
  record(m, d, j, &o);
}

/* Joint j's loads, ready to add (row of SW_JOINT_ROW doubles): the force on
 * node a and its damping part (lab), then the couple on element a and its
 * damping part, and those on element b, in each element's material frame
 * (loads.c).  Reads the state only, so joints are evaluated in parallel. */
enum { ROW_F = 0, ROW_FD = 3, ROW_CA = 6, ROW_CDA = 9, ROW_CB = 12, ROW_CDB = 15 };
static void joint_row(const swModel *m, swData *d, int j, double *row) {
  swJointEval o;
  joint_eval(m, d, j, &o);
  record(m, d, j, &o);
  sw_v3_add(row + ROW_F, o.force, o.force_damp);
  memcpy(row + ROW_FD, o.force_damp, sizeof o.force_damp);
  if (!has_couples(&m->joint[j])) return;
  const int ea = m->joint_elem_a[j], eb = m->joint_elem_b[j];
  double c[3], ca[3], cda[3], Q[9];
  sw_v3_add(c, o.couple, o.couple_damp);
  sw_v3_add(ca, c, o.arm); /* side a alone takes its arm's couple */
  sw_v3_add(ca, ca, o.arm_damp);
  sw_v3_add(cda, o.couple_damp, o.arm_damp);
  sw_getQ(m, d->Q, ea, Q);
  sw_mat_vec(row + ROW_CA, Q, ca);
  sw_mat_vec(row + ROW_CDA, Q, cda);
  if (eb >= 0) {
    sw_getQ(m, d->Q, eb, Q);
    sw_mat_vec(row + ROW_CB, Q, c);
    sw_mat_vec(row + ROW_CDB, Q, o.couple_damp);
  }
}

/* Joint j's row into the loads of the slots [lo, hi) (this thread's).  Each
 * thread goes through all joints in joint order, so every slot gets its
 * joints' loads in the same order for any number of threads. */
static inline void add_to(const swModel *m, double *a, int i, int lo, int hi, const double *v, double sign) {
  if (i < lo || i >= hi) return;
  for (int k = 0; k < 3; k++) SW_AT(m, a, i, k) += sign * v[k];
}
static void apply_row(const swModel *m, swData *d, int j, const double *row, int lo, int hi) {
  const int na = m->joint_node_a[j], nb = m->joint_node_b[j];
  const int ea = m->joint_elem_a[j], eb = m->joint_elem_b[j];
  add_to(m, d->force, na, lo, hi, row + ROW_F, 1.0);
  add_to(m, d->ext_force, na, lo, hi, row + ROW_FD, 1.0);
  if (nb >= 0) {
    add_to(m, d->force, nb, lo, hi, row + ROW_F, -1.0);
    add_to(m, d->ext_force, nb, lo, hi, row + ROW_FD, -1.0);
  }
  if (!has_couples(&m->joint[j])) return;
  add_to(m, d->torque, ea, lo, hi, row + ROW_CA, 1.0);
  add_to(m, d->ext_torque, ea, lo, hi, row + ROW_CDA, 1.0);
  if (eb >= 0) {
    add_to(m, d->torque, eb, lo, hi, row + ROW_CB, -1.0);
    add_to(m, d->ext_torque, eb, lo, hi, row + ROW_CDB, -1.0);
  }
}

/* The joints' rows, each by the owner of its node a (whose state it mostly
 * reads); from the state alone, so they run beside the rod pass. */
void sw_joint_rows(const swModel *m, swData *d) {
  int lo, hi;
  sw_owned_slots(m, d, &lo, &hi);
  for (int j = 0; j < m->njoint; j++)
    if (m->joint_node_a[j] >= lo && m->joint_node_a[j] < hi)
      joint_row(m, d, j, d->joint_scratch + SW_JOINT_ROW * j);
}

/* Every thread adds the rows to its own slots (after the rows are made). */
void sw_joint_apply(const swModel *m, swData *d) {
  int lo, hi;
  sw_owned_slots(m, d, &lo, &hi);
  for (int j = 0; j < m->njoint; j++) apply_row(m, d, j, d->joint_scratch + SW_JOINT_ROW * j, lo, hi);
}

double sw_joint_energy(const swModel *m, const swData *d) {
  double u = 0;
  for (int j = 0; j < m->njoint; j++) {
    swJointEval o;
    joint_eval(m, d, j, &o);
    u += o.energy;
  }
  return u;
}

const char *sw_joint_kind_name(swJointKind kind) {
  switch (kind) {
  case SW_JOINT_SPHERICAL: return "spherical";
  case SW_JOINT_HINGE: return "hinge";
  case SW_JOINT_FIXED: return "fixed";
  }
  return "joint";
}
