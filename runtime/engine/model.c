/* model.c — compilation of a scene's spec into the immutable swModel.
 *
 * Design.  The spec (spec.c) is a growable list of rod, load and boundary
 * descriptions filled by the caller (the generated simulator or a test).
 * sw_compile() validates it (spec_check.c), sizes every flat array once,
 * and precomputes everything that does not change during a run: lumped node
 * masses, element stiffness diagonals S^ and inertias J^, Voronoi bending
 * stiffness B^ (rest-length weighted average of the two neighbouring
 * elements, as in PyElastica), rest lengths, rest strains and the per-rod
 * stable time step; joints are resolved by joint.c (sw_joint_setup).  All memory of a model is allocated
 * here, and of its state in data.c, and nowhere else.
 *
 * Constitutive constants (Gazzola et al. 2018, sec. 2; Zhang et al. 2019,
 * Suppl. Note on snake settings):  A = pi r^2, I1 = I2 = pi r^4 / 4,
 * I3 = 2 I1;  S^ = diag(alpha_c G A, alpha_c G A, E A) with alpha_c = 4/3,
 * B^ = diag(E I1, E I2, G I3);  J^ = rho l^ diag(I1, I2, I3).  Shear and
 * twist hardening multiply G in S^11, S^22 and in B^33 respectively.
 */
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"
#include "model.h"

static const double SW_ALPHA_SHEAR = 4.0 / 3.0; /* circular section */

/* Rigid rods (rigid.c fills these): which rod is which body, and room for
 * each body's nodes and elements in the body frame. */
static int rigid_alloc(swModel *m, const swSpec *s) {
  size_t nodes = 0, elems = 0;
  m->rod_rigid = calloc((size_t)m->nrod, sizeof(int));
  if (!m->rod_rigid) return 0;
  for (int r = 0; r < m->nrod; r++) m->nrigid += s->rod[r].rigid != 0;
  size_t B = (size_t)m->nrigid;
  m->rigid_rod = calloc(B ? B : 1, sizeof(int));
  m->rigid_fixed = calloc(B ? B : 1, sizeof(int));
  m->rigid_node_adr = calloc(B ? B : 1, sizeof(int));
  m->rigid_elem_adr = calloc(B ? B : 1, sizeof(int));
  if (!m->rigid_rod || !m->rigid_fixed || !m->rigid_node_adr || !m->rigid_elem_adr) return 0;
  for (int r = 0, b = 0; r < m->nrod; r++) {
    m->rod_rigid[r] = s->rod[r].rigid ? b : -1;
    if (!s->rod[r].rigid) continue;
    m->rigid_rod[b] = r;
    m->rigid_node_adr[b] = (int)nodes;
    m->rigid_elem_adr[b] = (int)elems;
    nodes += (size_t)m->rod_nelem[r] + 1;
    elems += (size_t)m->rod_nelem[r];
    b++;
  }
  m->rigid_mass = sw_dalloc(B); m->rigid_inertia = sw_dalloc(3 * B); m->rigid_X0 = sw_dalloc(3 * B);
  m->rigid_R0 = sw_dalloc(9 * B); m->rigid_p = sw_dalloc(3 * nodes); m->rigid_B = sw_dalloc(9 * elems);
  return m->rigid_mass && m->rigid_inertia && m->rigid_X0 && m->rigid_R0 && m->rigid_p &&
         m->rigid_B;
}

static void rigid_free(swModel *m) {
  free(m->rod_rigid); free(m->rigid_rod); free(m->rigid_fixed); free(m->rigid_node_adr);
  free(m->rigid_elem_adr); free(m->rigid_mass); free(m->rigid_inertia); free(m->rigid_X0);
  free(m->rigid_R0); free(m->rigid_p); free(m->rigid_B);
}

void sw_model_free(swModel *m) {
  if (!m) return;
  for (int r = 0; r < m->nrod; r++) {
    free(m->rod_name[r]);
    if (m->rod_info) sw_rod_info_free(&m->rod_info[r]);
  }
  free(m->rod_name); free(m->rod_info); free(m->rod_nelem); free(m->node_adr); free(m->elem_adr);
  free(m->vor_adr); free(m->rod_wave_dt); free(m->rod_damping); free(m->rod_law);
  free(m->mass); free(m->weight); free(m->inv_mass); free(m->node_gamma); free(m->node_decay); free(m->elem_decay); free(m->node_kick); free(m->elem_kick); free(m->x0);
  free(m->rest_len); free(m->inv_rest_len); free(m->radius); free(m->shear_stiff); free(m->inertia);
  free(m->inv_inertia); free(m->rest_sigma); free(m->elem_gamma); free(m->Q0); free(m->clamp_bend);
  free(m->rest_vor_len); free(m->bend_stiff); free(m->rest_kappa);
  free(m->elem_ghost); free(m->elem_variational); free(m->kick_exact); free(m->damp_linear); free(m->inv_rest_vor_len);
  free(m->load); free(m->bc);
  for (int j = 0; j < m->njoint; j++) free(m->joint_name[j]);
  sw_expect_free(m);
  sw_kinematic_free(m);
  free(m->joint); free(m->joint_name); free(m->joint_node_a); free(m->joint_node_b);
  free(m->joint_elem_a); free(m->joint_elem_b); free(m->joint_axis_a); free(m->joint_axis_b);
  free(m->joint_arm_a);
  free(m->joint_rest_rot); free(m->joint_angle0); free(m->joint_wave_dt); free(m->joint_limit_ref);
  sw_rigid_joints_free(m);
  sw_implicit_free(m);
  sw_swell_free(m);
  if (sw_muscle_ops(m)) sw_muscle_ops(m)->free_model(m);
  if (sw_env_ops(m)) sw_env_ops(m)->free_model(m);
  rigid_free(m);
  free(m);
}
/* Rest node positions and directors of rod r: straight, or the rest shape
 * given with sw_spec_set_rest_shape.  The rod starts in it unless a starting
 * shape is given (sw_spec_set_start_shape): then the rest shape sets only
 * the rest strains (rest lengths, rest curvature), and the start the state
 * at t = 0 (x0, Q0). */
static void place_rod(const swSpec *s, int r, double *x, double *Q) {
  const swRodDesc *rd = &s->rod[r];
  int n = rd->nelem;
  if (s->rest_x[r]) {
    memcpy(x, s->rest_x[r], sizeof(double) * 3 * (size_t)(n + 1));
    memcpy(Q, s->rest_Q[r], sizeof(double) * 9 * (size_t)n);
    return;
  }
  double Q0[9];
  sw_frame_from(Q0, rd->direction, rd->normal);
  for (int i = 0; i <= n; i++) {
    double f = rd->length * i / n;
    for (int k = 0; k < 3; k++) x[3 * i + k] = rd->start[k] + f * Q0[6 + k];
  }
  for (int i = 0; i < n; i++) memcpy(Q + 9 * i, Q0, sizeof Q0);
}
swModel *sw_compile(const swSpec *s, char *err, size_t errlen) {
  if (s && s->muscle_ops && !s->muscle_ops->check(s->muscles, s->nrod, err, errlen)) return NULL;
  if (!s || s->nrod < 1) {
    sw_fail(err, errlen, "the scene has no rods");
    return NULL;
  }
  if (!sw_finite_pos(s->dt)) {
    sw_fail(err, errlen, "time step must be > 0, got %g", s->dt);
    return NULL;
  }
  if (s->integrator != SW_VERLET && s->integrator != SW_PEFRL && s->integrator != SW_IMEX) {
    sw_fail(err, errlen, "unknown integrator %d", (int)s->integrator);
    return NULL;
  }
  for (int r = 0; r < s->nrod; r++)
    if (!sw_check_rod(&s->rod[r], err, errlen)) return NULL;
  if (!sw_check_loads_bcs(s, err, errlen)) return NULL;
  if (!sw_check_joints(s, err, errlen)) return NULL;
  if (!sw_kinematic_check(s, err, errlen)) return NULL;
  if (s && s->env_ops && !s->env_ops->check(s->env, s->nrod, err, errlen)) return NULL;

  swModel *m = calloc(1, sizeof *m);
  if (!m) return NULL;
  m->nrod = s->nrod;
  m->dt = s->dt;
  m->integrator = s->integrator;
  memcpy(m->gravity, s->gravity, sizeof m->gravity);
  m->gravity_signal = s->has_gravity_signal ? s->gravity_signal : sw_signal_const(1.0);
  m->has_gravity = s->gravity[0] != 0 || s->gravity[1] != 0 || s->gravity[2] != 0;
  int nr = m->nrod;
  m->rod_name = calloc((size_t)nr, sizeof(char *));
  m->rod_info = calloc((size_t)nr, sizeof *m->rod_info);
  m->rod_nelem = calloc((size_t)nr, sizeof(int));
  m->node_adr = calloc((size_t)nr, sizeof(int));
  m->elem_adr = calloc((size_t)nr, sizeof(int));
  m->vor_adr = calloc((size_t)nr, sizeof(int));
  m->rod_damping = calloc((size_t)nr, sizeof(swDampingKind));
  m->rod_law = calloc((size_t)nr, sizeof(swLaw));
  m->rod_wave_dt = sw_dalloc((size_t)nr);
  if (!m->rod_name || !m->rod_info || !m->rod_nelem || !m->node_adr || !m->elem_adr || !m->vor_adr ||
      !m->rod_damping || !m->rod_law || !m->rod_wave_dt)
    goto oom;
  /* Slots: elastic rods first, in rod order, then rigid ones, so the rod
   * kernels run one loop over [0, nslot_elastic) (sinew.h, "Layout"). */
  for (int pass = 0; pass < 2; pass++)
    for (int r = 0; r < nr; r++) {
      if ((s->rod[r].rigid != 0) != pass) continue;
      int n = s->rod[r].nelem;
      m->rod_name[r] = strdup(s->rod[r].name);
      if (!m->rod_name[r] || !sw_rod_info_copy(&m->rod_info[r], s->rod[r].kind,
                                            s->rod[r].material, s->rod[r].where))
        goto oom;
      m->rod_info[r].youngs = s->rod[r].youngs;
      m->rod_info[r].shear_modulus = s->rod[r].shear_modulus > 0
                                         ? s->rod[r].shear_modulus
                                         : s->rod[r].youngs / (2 * (1 + s->rod[r].poisson));
      m->rod_info[r].density = s->rod[r].density;
      m->rod_info[r].length = s->rod[r].length;
      m->rod_info[r].shear_hardening = s->rod[r].shear_hardening;
      m->rod_info[r].twist_hardening = s->rod[r].twist_hardening;
      m->rod_nelem[r] = n;
      m->node_adr[r] = m->elem_adr[r] = m->vor_adr[r] = m->nslot;
      m->nslot += n + 1;
      if (!pass) m->nslot_elastic = m->nslot;
      m->nnode += n + 1;
      m->nelem += n;
      m->nvor += n - 1;
      m->rod_damping[r] = s->rod[r].gamma > 0 || s->rod[r].gamma_rot > 0 ? s->rod[r].damping
                                                                          : SW_DAMP_NONE;
      if (m->rod_damping[r] != SW_DAMP_NONE) m->has_damping = 1;
      m->rod_law[r] = s->rod[r].law;
      /* a rigid rod has no internal loads, so no law to apply */
      m->nvariational += !pass && s->rod[r].law == SW_LAW_VARIATIONAL;
    }
  m->stride = (m->nslot + 2 + 7) / 8 * 8;
  /* Chunks of the threaded kernels (internal.h): at most 32 over the elastic
   * slots, so two to a few threads share them evenly, and at least 64 slots,
   * so the set-up of each vector loop is paid on enough slots. */
  m->chunk = ((m->nslot_elastic + 31) / 32 + 7) / 8 * 8;
  if (m->chunk < 64) m->chunk = 64;
  m->mass = sw_palloc(m, 1); m->inv_mass = sw_palloc(m, 1); m->node_gamma = sw_palloc(m, 1); m->node_decay = sw_palloc(m, 1); m->node_kick = sw_palloc(m, 1); m->x0 = sw_palloc(m, 3);
  m->rest_len = sw_palloc(m, 1); m->inv_rest_len = sw_palloc(m, 1); m->radius = sw_palloc(m, 1); m->shear_stiff = sw_palloc(m, 3);
  m->inertia = sw_palloc(m, 3); m->inv_inertia = sw_palloc(m, 3); m->rest_sigma = sw_palloc(m, 3);
  m->elem_gamma = sw_palloc(m, 3); m->elem_decay = sw_palloc(m, 3); m->elem_kick = sw_palloc(m, 3); m->Q0 = sw_palloc(m, 9); m->clamp_bend = sw_palloc(m, 3);
  m->rest_vor_len = sw_palloc(m, 1); m->bend_stiff = sw_palloc(m, 3); m->rest_kappa = sw_palloc(m, 3);
  m->elem_ghost = sw_palloc(m, 1); m->elem_variational = sw_palloc(m, 1); m->kick_exact = sw_palloc(m, 1); m->damp_linear = sw_palloc(m, 1); m->inv_rest_vor_len = sw_palloc(m, 1);
  if (!m->elem_ghost || !m->elem_variational || !m->kick_exact || !m->damp_linear || !m->inv_rest_vor_len ||!m->mass || !m->inv_mass || !m->node_gamma || !m->node_decay || !m->elem_decay || !m->node_kick || !m->elem_kick || !m->x0 || !m->rest_len || !m->inv_rest_len || !m->radius ||
      !m->shear_stiff || !m->inertia || !m->inv_inertia || !m->rest_sigma || !m->elem_gamma ||
      !m->Q0 || !m->clamp_bend || !m->rest_vor_len || !m->bend_stiff || !m->rest_kappa)
    goto oom;
  /* Neutral values in every slot, so ghosts and padding divide by nothing
   * and carry no stiffness, mass or load: unit rest lengths, identity
   * frames, no decay; the rods overwrite their own slots below. */
  for (int i = 0; i < m->stride; i++) {
    m->rest_len[i] = m->inv_rest_len[i] = m->rest_vor_len[i] = m->inv_rest_vor_len[i] = 1.0;
    m->node_decay[i] = 1.0;
    m->elem_ghost[i] = 1.0;
    for (int k = 0; k < 3; k++) {
      SW_AT(m, m->Q0, i, 4 * k) = 1.0;
      SW_AT(m, m->elem_decay, i, k) = 1.0;
    }
  }

  for (int r = 0; r < nr; r++) {
    const swRodDesc *rd = &s->rod[r];
    int n = rd->nelem, na = m->node_adr[r], ea = m->elem_adr[r], va = m->vor_adr[r];
    /* the rod's rest shape, row by row, then into the planes */
    double *x = sw_dalloc(3 * (size_t)(n + 1)), *Q = sw_dalloc(9 * (size_t)n);
    double *bend_elem = sw_dalloc(3 * (size_t)n); /* element B^ before Voronoi averaging */
    if (!x || !Q || !bend_elem) {
      free(x); free(Q); free(bend_elem);
      goto oom;
    }
    place_rod(s, r, x, Q);
    const double *xs = s->start_x[r] ? s->start_x[r] : x, *Qs = s->start_Q[r] ? s->start_Q[r] : Q;
    for (int i = 0; i <= n; i++) sw_set3(m, m->x0, na + i, xs + 3 * i);
    for (int i = 0; i < n; i++) sw_setQ(m, m->Q0, ea + i, Qs + 9 * i);
    double G = rd->shear_modulus > 0 ? rd->shear_modulus : rd->youngs / (2.0 * (1.0 + rd->poisson));
    double Gs = G * rd->shear_hardening, Gt = G * rd->twist_hardening;
    for (int i = 0; i < n; i++) {
      int e = ea + i;
      m->elem_ghost[e] = 0.0;
      m->elem_variational[e] = rd->law == SW_LAW_VARIATIONAL && !rd->rigid;
      double dx[3];
      sw_v3_sub(dx, x + 3 * (i + 1), x + 3 * i);
      double l = sw_v3_norm(dx);
      if (!(l > 0)) {
        free(x); free(Q); free(bend_elem);
        sw_fail(err, errlen, "rod '%s': element %d has zero rest length", rd->name, i);
        sw_model_free(m);
        return NULL;
      }
      /* radius tapers linearly from the first to the last element centre */
      double f = n > 1 ? (double)i / (n - 1) : 0.0;
      double rad = rd->radius_start + f * (rd->radius_end - rd->radius_start);
      double A = SW_PI * rad * rad, I1 = A * rad * rad / 4.0;
      m->rest_len[e] = l;
      m->inv_rest_len[e] = 1.0 / l;
      m->radius[e] = rad;
      SW_AT(m, m->shear_stiff, e, 0) = SW_ALPHA_SHEAR * Gs * A;
      SW_AT(m, m->shear_stiff, e, 1) = SW_ALPHA_SHEAR * Gs * A;
      SW_AT(m, m->shear_stiff, e, 2) = rd->youngs * A;
      double Ik[3] = {I1, I1, 2.0 * I1};
      for (int k = 0; k < 3; k++) {
        SW_AT(m, m->inertia, e, k) = rd->density * l * Ik[k];
        SW_AT(m, m->inv_inertia, e, k) = 1.0 / SW_AT(m, m->inertia, e, k);
        SW_AT(m, m->rest_sigma, e, k) = rd->rest_sigma[k];
        /* rotational dissipation: gamma I_k / A per unit length, so that
         * rotation and translation decay at the same rate gamma/(rho A), or
         * the couple density -gamma_rot w of Gazzola 2018 when given */
        SW_AT(m, m->elem_gamma, e, k) = rd->gamma_rot >= 0 ? rd->gamma_rot * l
                                                            : rd->gamma * l * Ik[k] / A;
      }
      bend_elem[3 * i + 0] = rd->youngs * I1;
      bend_elem[3 * i + 1] = rd->youngs * I1;
      bend_elem[3 * i + 2] = Gt * 2.0 * I1;
      for (int k = 0; k < 3; k++) SW_AT(m, m->clamp_bend, e, k) = bend_elem[3 * i + k];
      /* lumped mass: half of each element to each of its nodes */
      double me = rd->density * A * l;
      m->mass[na + i] += 0.5 * me;
      m->mass[na + i + 1] += 0.5 * me;
      m->node_gamma[na + i] += 0.5 * rd->gamma * l;
      m->node_gamma[na + i + 1] += 0.5 * rd->gamma * l;
    }
    for (int j = 0; j < n - 1; j++) {
      int v = va + j, e = ea + j;
      double la = m->rest_len[e], lb = m->rest_len[e + 1];
      m->rest_vor_len[v] = 0.5 * (la + lb);
      m->inv_rest_vor_len[v] = 1.0 / m->rest_vor_len[v];
      for (int k = 0; k < 3; k++) {
        SW_AT(m, m->bend_stiff, v, k) = (bend_elem[3 * j + k] * la + bend_elem[3 * (j + 1) + k] * lb) / (la + lb);
        SW_AT(m, m->rest_kappa, v, k) = rd->rest_kappa[k];
      }
      /* A given rest shape fixes the rest curvature unless one is given. */
      if (s->rest_Q[r] && rd->rest_kappa[0] == 0 && rd->rest_kappa[1] == 0 && rd->rest_kappa[2] == 0) {
        double phi[3];
        sw_frame_log(phi, Q + 9 * j, Q + 9 * (j + 1));
        for (int k = 0; k < 3; k++) SW_AT(m, m->rest_kappa, v, k) = phi[k] / m->rest_vor_len[v];
      }
    }
    free(x); free(Q); free(bend_elem);
    for (int i = 0; i <= n; i++) m->inv_mass[na + i] = 1.0 / m->mass[na + i];
    /* Analytic damping.  Position Verlet: the kick integrates
     * dv/dt = a - c v exactly over the step with a held constant,
     *   v <- v exp(-c dt) + a (1 - exp(-c dt)) / c,
     * so node_decay = exp(-c dt) and node_kick = (1 - exp(-c dt)) / c (= dt
     * as c -> 0): stable for every c, and an overdamped rod creeps at the
     * right terminal velocity a / c.  PEFRL has kicks of negative length,
     * where that factor would grow, so there the decay exp(-c dt/2) is
     * applied before and after the step instead (Strang).  Rates:
     * c = gamma D^ / m for nodes and elem_gamma / J^ for elements (the
     * dilatation taken as 1 in the rate). */
    int analytic = m->rod_damping[r] == SW_DAMP_ANALYTIC;
    const int verlet_kick = s->integrator != SW_PEFRL; /* Verlet and IMEX */
    double span = verlet_kick ? s->dt : 0.5 * s->dt;
    for (int i = 0; i <= n; i++) m->kick_exact[na + i] = analytic && verlet_kick;
    if (analytic && verlet_kick) m->has_exact_kick = 1;
    for (int i = 0; i <= n; i++) m->damp_linear[na + i] = m->rod_damping[r] == SW_DAMP_LINEAR;
    for (int i = 0; i <= n; i++) {
      double c = analytic ? m->node_gamma[na + i] * m->inv_mass[na + i] : 0.0;
      m->node_decay[na + i] = exp(-span * c);
      m->node_kick[na + i] = c * s->dt > 1e-8 ? -expm1(-s->dt * c) / c : s->dt;
    }
    for (int i = 0; i < n; i++)
      for (int k = 0; k < 3; k++) {
        int e = ea + i;
        double c = analytic ? SW_AT(m, m->elem_gamma, e, k) * SW_AT(m, m->inv_inertia, e, k) : 0.0;
        SW_AT(m, m->elem_decay, e, k) = exp(-span * c);
        SW_AT(m, m->elem_kick, e, k) = c * s->dt > 1e-8 ? -expm1(-s->dt * c) / c : s->dt;
      }
  }

  /* gravity's mass: the lumped mass but on weightless rods (loads.c) */
  for (int r = 0; r < nr; r++) {
    if (!s->rod[r].weightless) continue;
    if (!m->weight) {
      if (!(m->weight = sw_palloc(m, 1))) goto oom;
      memcpy(m->weight, m->mass, sizeof(double) * (size_t)m->nslot);
    }
    for (int i = 0; i <= s->rod[r].nelem; i++) m->weight[m->node_adr[r] + i] = 0.0;
  }

  m->nload = s->nload;
  m->nbc = s->nbc;
  m->load = calloc((size_t)(s->nload ? s->nload : 1), sizeof *m->load);
  m->bc = calloc((size_t)(s->nbc ? s->nbc : 1), sizeof *m->bc);
  if (!m->load || !m->bc) goto oom;
  if (s->nload) memcpy(m->load, s->load, sizeof *m->load * (size_t)s->nload);
  if (s->nbc) memcpy(m->bc, s->bc, sizeof *m->bc * (size_t)s->nbc);
  for (int k = 0; k < m->nbc; k++) /* a slide's direction, made a unit vector (boundary.c) */
    if (m->bc[k].kind == SW_BC_SLIDE_LINE || m->bc[k].kind == SW_BC_SLIDE_PLANE || m->bc[k].kind == SW_BC_SLEEVE)
      sw_v3_scale(m->bc[k].vec, m->bc[k].vec, 1.0 / sw_v3_norm(m->bc[k].vec));
  m->bc_slot_order = 1; /* boundary.c looks only near a call's slots then */
  for (int k = 1; k < m->nbc; k++)
    if (sw_bc_node(m, &m->bc[k]) < sw_bc_node(m, &m->bc[k - 1])) m->bc_slot_order = 0;
  for (int k = 0; k < m->nload; k++)
    if (m->load[k].index == -1)
      m->load[k].index = m->rod_nelem[m->load[k].rod] - (m->load[k].kind == SW_LOAD_TORQUE);
  if (!rigid_alloc(m, s)) goto oom;
  sw_rigid_setup(m);
  /* swelling rods (swell.c), before every stable-dt estimate: they cover
   * the range of the radius */
  if (!sw_swell_setup(m, s)) goto oom;
  { /* implicit rods, before the stable-dt estimates that leave them out */
    int *wanted = calloc((size_t)nr, sizeof(int));
    if (!wanted) goto oom;
    for (int r = 0; r < nr; r++) wanted[r] = s->rod[r].implicit;
    const int ok = sw_implicit_setup(m, wanted);
    free(wanted);
    if (!ok) goto oom;
  }
  for (int r = 0; r < nr; r++) m->rod_wave_dt[r] = sw_stable_dt_rod(m, r);

  /* joints: copies of the descriptions, resolved by joint.c */
  size_t J = (size_t)s->njoint, J1 = J ? J : 1;
  m->joint = calloc(J1, sizeof *m->joint);
  m->joint_name = calloc(J1, sizeof *m->joint_name);
  m->joint_node_a = calloc(J1, sizeof(int)); m->joint_node_b = calloc(J1, sizeof(int));
  m->joint_elem_a = calloc(J1, sizeof(int)); m->joint_elem_b = calloc(J1, sizeof(int));
  m->joint_axis_a = sw_dalloc(3 * J); m->joint_axis_b = sw_dalloc(3 * J);
  m->joint_arm_a = sw_dalloc(3 * J);
  m->joint_rest_rot = sw_dalloc(9 * J); m->joint_angle0 = sw_dalloc(J); m->joint_wave_dt = sw_dalloc(J);
  m->joint_limit_ref = sw_dalloc(9 * J);
  if (!m->joint || !m->joint_name || !m->joint_node_a || !m->joint_node_b || !m->joint_elem_a ||
      !m->joint_elem_b || !m->joint_axis_a || !m->joint_axis_b || !m->joint_arm_a ||
      !m->joint_rest_rot ||
      !m->joint_angle0 || !m->joint_wave_dt || !m->joint_limit_ref)
    goto oom;
  for (int j = 0; j < s->njoint; j++) {
    if (!(m->joint_name[j] = strdup(s->joint[j].name))) goto oom;
    m->njoint = j + 1; /* names freed by sw_model_free from here on */
    m->joint[j] = s->joint[j];
    m->joint[j].name = m->joint_name[j];
  }
  sw_joint_setup(m);
  for (int j = 0; j < m->njoint; j++) {
    const swJointDesc *jd = &m->joint[j];
    const double a0 = m->joint_angle0[j];
    if (jd->has_range && (a0 < jd->angle_min || a0 > jd->angle_max)) {
      sw_fail(err, errlen, "joint '%s': its hinge angle at t = 0 is %g rad, outside its range "
              "[%g, %g] rad: the limit would throw it on the first step", jd->name, a0,
              jd->angle_min, jd->angle_max);
      sw_model_free(m);
      return NULL;
    }
  }
  if (!sw_kinematic_setup(m, s)) goto oom;
  m->muscle_ops = s->muscle_ops;
  m->env_ops = s->env_ops;
  if ((s->muscle_ops && !s->muscle_ops->setup(m, s->muscles, err, errlen)) ||
      (s->env_ops && !s->env_ops->setup(m, s->env, err, errlen)) ||
      !sw_expect_setup(m, &s->expects, err, errlen)) {
    sw_model_free(m);
    return NULL;
  }
  /* after the muscles: which filaments take the implicit tension decides
   * which of their joints can be implicit (joint_groups.c) */
  if (!sw_rigid_joints_setup(m)) goto oom;
  for (int j = 0; j < m->njoint; j++) m->joint_wave_dt[j] = sw_stable_dt_joint(m, j);
  return m;

oom:
  sw_fail(err, errlen, "out of memory while building the model");
  sw_model_free(m);
  return NULL;
}
