/* muscle.c — muscles as bundles of contracting Cosserat filaments.
 *
 * Design.  A muscle is N filaments (Zhang et al. 2019, Suppl. Note 1), each an
 * ordinary rod of the scene standing for a group of motor units, laid from the
 * muscle's start to its end and tied there by spherical joints to the rods it
 * attaches to (tendons, bones).  The rods bend, twist, shear and stretch like
 * any other (the tissue's own E, 10 kPa for muscle); this file adds the
 * contraction.  Each filament k pulls with one tension T_k, the same in every
 * element and directed along each element's current tangent t_i, so node i
 * gets +T t_i and node i+1 gets -T t_i: a central pair per element, which
 * conserves momentum and angular momentum without couples.  T_k is a function
 * of the filament's stretch eta = l / l0 (l the arc length) and strain rate
 * de/dt = (sum_i t_i . (v_{i+1} - v_i)) / l0, so the law sees the whole
 * filament, as the reference's eta does, and cannot localise strain:
 *
 *   F_qs(eta) = a_k f_act(eta) F_max,k + F_max,k p(eta)          Suppl. eq. 4
 *   f_act(eta) = 6.405 eta^4 - 24.42 eta^3 + 29.64 eta^2 - 12.01 eta + 1.385
 *   p(eta)     = 3.375 eta^3 - 11.33 eta^2 + 13 eta - 5.05  (eta >= 1)
 *                (= E_membrane(eta) A (eta - 1) / F_max of Suppl. eq. 3)
 *   T_k = F_qs - zeta(v) v / l0,  v = -dl/dt the shortening speed  eq. 5
 *   zeta(v) = (F_qs + a) F_qs l0 / (a v0 + v F_qs),  a = hill_a F_qs,
 *             v0 = v_max l0                              (Hill 1938)
 * so that T_k = F_qs (1 - (1 + k) u / (u + k u0)) with u = v / l0 and
 * u0 = v_max, which is Hill's hyperbola (T + a)(v + b) = (F_qs + a) b.
 * Outside what the fits cover: f_act is 0 outside its roots (0.4406 and
 * 1.5736, just outside the fitted range [0.5, 1.6]); p is floored at 0 (the
 * fit is -0.005 at eta = 1, a slack membrane cannot push); at u >= u0 the tension is 0; when
 * lengthening (u < 0) the damping keeps its value at u = 0, zeta(0), so the
 * law is continuous with a continuous slope.
 *
 * Size principle (Suppl. Note 1): the N cross-sections grow geometrically from
 * the smallest to the largest by `size_ratio` and sum to the muscle's A;
 * F_max,k = sigma_max A_k; activation time constants fall linearly with A_k
 * from twitch_small to twitch_large.  Recruitment: the muscle activation u(t)
 * drives filament k with clamp((u - C_{k-1}) / (C_k - C_{k-1}), 0, 1), C_k
 * the cumulative share of peak force of filaments 0..k, so the small ones are
 * recruited first and the bundle's peak isometric force is u F_max.  With a
 * time constant tau_k the filament's activation follows its drive by
 * da/dt = (drive - a) / tau_k, advanced once a step with the exact
 * exponential of a drive held at the step's midpoint value.
 *
 * The muscle's forces are active: they enter ext_force as well, so the kick
 * books their work as work done on the rods (energy diagnostic).
 *
 * A muscle may instead pull with a prescribed force F(t) (swMuscleDesc.
 * prescribed, as Zhang et al. 2019 drive the wing, Suppl. eqs. 6-10): each
 * filament carries T_k = F(t) A_k / A, its share by cross-section, with the
 * same central pair per element and nothing of the Hill law (no stretch,
 * rate or activation dependence, no damping, no step limit of its own).
 *
 * Implicit Hill damping (SW_IMEX): muscle_implicit.c.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <limits.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* The fit of f_act (Suppl. eq. 3, stated for 0.5 <= eta <= 1.6) is positive
 * between its roots 0.44059 and 1.57358; outside them the active force is 0,
 * so it vanishes continuously at both ends (the quartic turns up again beyond
 * them, which no muscle does). */
#define ETA_ACT_LO 0.44058965597893646
#define ETA_ACT_HI 1.5735803537167226

double sw_muscle_f_act(double eta) {
  if (!(eta > ETA_ACT_LO && eta < ETA_ACT_HI)) return 0;
  double f = (((6.405 * eta - 24.42) * eta + 29.64) * eta - 12.01) * eta + 1.385;
  return f > 0 ? f : 0;
}

double sw_muscle_f_pass(double eta) {
  if (eta < 1) return 0;
  double p = ((3.375 * eta - 11.33) * eta + 13.0) * eta - 5.05;
  return p > 0 ? p : 0;
}

void sw_muscle_desc_init(swMuscleDesc *md) {
  memset(md, 0, sizeof *md);
  md->name = "muscle";
  md->filaments = 1;
  md->nelem = 14;                  /* n_m of Suppl. Table 5 */
  md->end[2] = 0.1;
  md->radius = 0.01;
  md->density = 1060.0;            /* Suppl. Table 1 */
  md->youngs = 10e3;
  md->poisson = 0.5;
  md->shear_hardening = md->twist_hardening = 1.0;
  md->sigma_max = 0;               /* must be given */
  md->size_ratio = 1.0;
  md->hill_a = 0.16;               /* a = 0.16 F_qs, Suppl. Note 7.1 (Hill 1938) */
  md->v_max = 6.0;                 /* v0 = 6 l0 /s, Suppl. Note 7.1 (Winter 2009) */
  md->fibre_diameter = 75e-6;      /* Suppl. Note 1 (Klein et al. 2003) */
  md->activation = sw_signal_const(0.0);
  md->attach_rod[0] = md->attach_rod[1] = -1;
  md->attach_node[0] = 0;
  md->attach_node[1] = -1;
  for (int k = 0; k < SW_MUSCLE_MAX_VIA; k++) md->via_rod[k] = -1;
}

static double dist3(const double *a, const double *b) {
  double d[3];
  sw_v3_sub(d, a, b);
  return sw_v3_norm(d);
}

/* The filaments' d1: `normal` if it is usable, else the lab axis least
 * aligned with dir (any perpendicular serves a round filament). */
static void filament_normal(double *out, const double *dir, const double *normal) {
  double Q[9];
  if (sw_frame_from(Q, dir, normal)) {
    memcpy(out, normal, 3 * sizeof *out);
    return;
  }
  int k = 0;
  for (int c = 1; c < 3; c++)
    if (fabs(dir[c]) < fabs(dir[k])) k = c;
  out[0] = out[1] = out[2] = 0;
  out[k] = 1;
}

/* ---- the specification side ---- */

typedef struct {
  swMuscleDesc desc;             /* name points to `name` */
  char *name;
  int rod0;                      /* first filament rod */
  unsigned char *passive;        /* (filaments) */
} swMuscleItem;

struct swMuscleSpec {
  int n, cap;
  swMuscleItem *item;
};

void sw_muscle_spec_free(swMuscleSpec *ms) {
  if (!ms) return;
  for (int i = 0; i < ms->n; i++) {
    free(ms->item[i].name);
    free(ms->item[i].passive);
  }
  free(ms->item);
  free(ms);
}

/* Cross-sections of the N filaments, smallest first: A q^k / sum q^j with
 * q = ratio^(1/(N-1)). */
static void filament_areas(int N, double A, double ratio, double *out) {
  double q = N > 1 ? pow(ratio, 1.0 / (N - 1)) : 1.0, sum = 0, w = 1;
  for (int k = 0; k < N; k++, w *= q) sum += (out[k] = w);
  for (int k = 0; k < N; k++) out[k] *= A / sum;
}

static int check_item(const swMuscleItem *it, int nrod, char *err, size_t errlen);



/* The step reaches this file through this table (internal.h, swMuscleOps). */
static void muscle_rates(const swModel *m, swData *d);
static void muscle_tensions(const swModel *m, swData *d, double h);
static void muscle_pull(const swModel *m, swData *d);
static void muscle_rings(const swModel *m, swData *d);
/* The bundle's tension, the sum of its filaments' (they pull in parallel),
 * and its stretch, each filament's path length (end to end through its via
 * points, muscle_via.c) over its rest length averaged by cross-section, of
 * the last force evaluation. */
static double muscle_force(const swModel *m, const swData *d, int mu) {
  double T = 0;
  for (int f = m->muscle_fil_adr[mu]; f < m->muscle_fil_adr[mu + 1]; f++) T += d->fil_tension[f];
  return T;
}

static double muscle_stretch(const swModel *m, const swData *d, int mu) {
  double s = 0, w = 0;
  for (int f = m->muscle_fil_adr[mu]; f < m->muscle_fil_adr[mu + 1]; f++) {
    s += m->fil_area[f] * sw_via_path(m, d, f) / m->fil_l0[f];
    w += m->fil_area[f];
  }
  return s / w;
}

static const swMuscleOps muscle_ops = {sw_muscle_check,  sw_muscle_setup,     sw_muscle_free,
                                       sw_muscle_spec_free, sw_muscle_reset, sw_muscle_advance,
                                       sw_muscle_loads,  muscle_rates,        muscle_tensions,
                                       muscle_pull,      sw_stable_dt_filament,
                                       muscle_force,     muscle_stretch,      muscle_rings,
                                       sw_muscle_system_tension};

/* F_max,k per unit area: sigma_max, or for a prescribed force the largest
 * size it reaches over its range, spread over the muscle's cross-section. */
static double peak_stress(const swMuscleDesc *md) {
  if (!md->prescribed) return md->sigma_max;
  double lo, hi;
  sw_signal_range(&md->force, &lo, &hi);
  return fmax(fabs(lo), fabs(hi)) / (SW_PI * md->radius * md->radius);
}

int sw_spec_add_muscle(swSpec *s, const swMuscleDesc *md) {
  *sw_spec_muscle_ops(s) = &muscle_ops;
  swMuscleSpec **slot = sw_spec_muscles(s);
  if (!*slot && !(*slot = calloc(1, sizeof **slot))) return -1;
  swMuscleSpec *ms = *slot;
  if (ms->n == ms->cap) {
    int nc = ms->cap ? 2 * ms->cap : 4;
    swMuscleItem *p = realloc(ms->item, (size_t)nc * sizeof *p);
    if (!p) return -1;
    ms->item = p;
    ms->cap = nc;
  }
  swMuscleItem *it = &ms->item[ms->n];
  memset(it, 0, sizeof *it);
  it->desc = *md;
  it->name = strdup(md->name ? md->name : "muscle");
  if (!it->name) return -1;
  it->desc.name = it->name;
  it->desc.material = it->desc.where = NULL;  /* the caller's; its filaments keep copies */
  it->rod0 = sw_spec_nrod(s);
  /* Invalid descriptions are kept and reported by sw_compile (sw_muscle_check),
   * which names the muscle; only the rods of a sensible muscle are made. */
  int N = md->filaments >= 1 && md->filaments <= 100000 ? md->filaments : 1;
  it->passive = calloc((size_t)N, 1);
  if (!it->passive) {
    free(it->name);
    return -1;
  }
  ms->n++;
  char why[256];
  if (!check_item(it, INT_MAX, why, sizeof why)) return ms->n - 1;

  double *area = malloc(sizeof(double) * (size_t)N);
  if (!area) return -1;
  filament_areas(N, SW_PI * md->radius * md->radius, md->size_ratio, area);
  double dir[3];
  sw_v3_sub(dir, md->nvia > 0 ? md->via[0] : md->end, md->start);
  const double L = sw_via_path_rest(md); /* |end - start| without via points */
  double *lay_x = NULL, *lay_Q = NULL;   /* the polyline through the via points */
  if (md->nvia > 0) {
    double d1[3];
    filament_normal(d1, dir, md->normal);
    lay_x = malloc(sizeof(double) * 3 * (size_t)(md->nelem + 1));
    lay_Q = malloc(sizeof(double) * 9 * (size_t)md->nelem);
    if (!lay_x || !lay_Q || !sw_via_lay(md, d1, lay_x, lay_Q)) {
      free(lay_x); free(lay_Q); free(area);
      return -1;
    }
  }
  for (int k = 0; k < N; k++) {
    char name[96];
    snprintf(name, sizeof name, "%s.f%02d", it->name, k + 1);
    swRodDesc r;
    sw_rod_desc_init(&r);
    r.name = name;
    r.nelem = md->nelem;
    memcpy(r.start, md->start, sizeof r.start);
    memcpy(r.direction, dir, sizeof dir);
    filament_normal(r.normal, dir, md->normal);
    r.length = L;
    r.radius_start = r.radius_end = sqrt(area[k] / SW_PI);
    r.density = md->density;
    r.youngs = md->youngs;
    r.shear_modulus = md->shear_modulus;
    r.poisson = md->poisson;
    r.shear_hardening = md->shear_hardening;
    r.twist_hardening = md->twist_hardening;
    r.law = md->law;
    r.weightless = md->weightless;
    r.damping = md->damping;
    r.gamma = md->gamma;
    r.kind = "muscle filament";
    r.material = md->material;
    r.where = md->where;
    int rod = sw_spec_add_rod(s, &r);
    if (rod < 0 || (lay_x && sw_spec_set_rest_shape(s, rod, lay_x, lay_Q) != SW_OK)) {
      free(area); free(lay_x); free(lay_Q);
      return -1;
    }
    for (int end = 0; end < 2; end++) {
      if (md->attach_rod[end] < 0) continue;
      swJointDesc j;
      sw_joint_desc_init(&j);
      char jname[112];
      snprintf(jname, sizeof jname, "%s.%s", name, end ? "end" : "start");
      j.name = jname;
      j.kind = SW_JOINT_SPHERICAL;
      j.rod_a = rod;
      j.node_a = end ? -1 : 0;
      j.rod_b = md->attach_rod[end];
      j.node_b = md->attach_node[end];
      /* 0 = 100 F_max,k / l0: the attachment gives 1% of l0 under peak force */
      j.stiffness = md->attach_stiffness > 0 ? md->attach_stiffness
                                             : 100.0 * peak_stress(md) * area[k] / L;
      j.damping = md->attach_damping;
      if (sw_spec_add_joint(s, &j) < 0) {
        free(area); free(lay_x); free(lay_Q);
        return -1;
      }
    }
  }
  free(area); free(lay_x); free(lay_Q);
  return ms->n - 1;
}

int sw_spec_set_filament_passive(swSpec *s, int muscle, int filament) {
  swMuscleSpec *ms = *sw_spec_muscles(s);
  if (!ms || muscle < 0 || muscle >= ms->n) return SW_EUSAGE;
  swMuscleItem *it = &ms->item[muscle];
  if (filament < 0 || filament >= it->desc.filaments) return SW_EUSAGE;
  it->passive[filament] = 1;
  return SW_OK;
}

/* ---- compilation ---- */

static int check_item(const swMuscleItem *it, int nrod, char *err, size_t errlen) {
  const swMuscleDesc *md = &it->desc;
  const char *nm = it->name;
#define BAD(...) (snprintf(err, errlen, __VA_ARGS__), 0)
  if (md->filaments < 1 || md->filaments > 100000)
    return BAD("muscle '%s': needs 1 to 100000 filaments, has %d", nm, md->filaments);
  if (md->motor_units != 0 && md->motor_units < md->filaments)
    return BAD("muscle '%s': %d motor units cannot fill %d filaments", nm, md->motor_units,
               md->filaments);
  if (md->nelem < 2)
    return BAD("muscle '%s': filaments need at least 2 elements, have %d", nm, md->nelem);
  double L = dist3(md->start, md->end);
  if (md->nvia == 0 && (!(L > 0) || !isfinite(L)))
    return BAD("muscle '%s': start and end coincide", nm);
  {
    swMuscleDesc named = *md;
    named.name = nm;
    if (!sw_via_check(&named, nrod, err, errlen)) return 0;
  }
  if (!(md->radius > 0) || !isfinite(md->radius))
    return BAD("muscle '%s': radius must be > 0", nm);
  if (!md->prescribed && (!(md->sigma_max > 0) || !isfinite(md->sigma_max)))
    return BAD("muscle '%s': sigma_max (peak isometric stress) must be > 0", nm);
  if (md->prescribed) {
    if (md->force.kind < SW_SIG_CONST || md->force.kind > SW_SIG_FUNC ||
        (md->force.kind == SW_SIG_FUNC && !md->force.fn))
      return BAD("muscle '%s': its prescribed force is not a signal", nm);
    if (!(peak_stress(md) > 0) || !isfinite(peak_stress(md)))
      return BAD("muscle '%s': its prescribed force is 0 over the whole run, or not finite", nm);
  }
  if (!(md->size_ratio >= 1) || !isfinite(md->size_ratio))
    return BAD("muscle '%s': size_ratio must be >= 1, got %g", nm, md->size_ratio);
  if (!(md->twitch_small >= 0) || !(md->twitch_large >= 0) || !isfinite(md->twitch_small) ||
      !isfinite(md->twitch_large))
    return BAD("muscle '%s': twitch times must be >= 0", nm);
  if (!(md->hill_a > 0) || !isfinite(md->hill_a))
    return BAD("muscle '%s': hill_a must be > 0", nm);
  if (!(md->v_max > 0) || !isfinite(md->v_max))
    return BAD("muscle '%s': v_max must be > 0", nm);
  if (!(md->fibre_diameter > 0) || !isfinite(md->fibre_diameter))
    return BAD("muscle '%s': fibre_diameter must be > 0", nm);
  if (!(md->attach_stiffness >= 0) || !(md->attach_damping >= 0))
    return BAD("muscle '%s': attachment stiffness and damping must be >= 0", nm);
  for (int e = 0; e < 2; e++)
    if (md->attach_rod[e] >= nrod)
      return BAD("muscle '%s': %s attached to rod %d, the scene has %d rods", nm,
                 e ? "end" : "start", md->attach_rod[e], nrod);
#undef BAD
  return 1;
}

void sw_muscle_free(swModel *m) {
  if (m->muscle_name)
    for (int i = 0; i < m->nmuscle; i++) free(m->muscle_name[i]);
  free(m->muscle_name); free(m->muscle_fil_adr); free(m->muscle_activation);
  free(m->muscle_force); free(m->muscle_prescribed);
  free(m->fil_rod); free(m->fil_passive); free(m->fil_area); free(m->fil_fmax);
  free(m->fil_l0); free(m->fil_tau); free(m->fil_recruit); free(m->fil_hill_a);
  free(m->fil_v_max); free(m->fil_fibres); free(m->fil_elem); free(m->fil_implicit);
  free(m->fil_ring_adr); free(m->ring_elem); free(m->ring_point); free(m->ring_stiffness);
  free(m->ring_damping); free(m->muscle_via); free(m->muscle_nvia);
}

int sw_muscle_check(const swMuscleSpec *ms, int nrod, char *err, size_t errlen) {
  for (int i = 0; ms && i < ms->n; i++)
    if (!check_item(&ms->item[i], nrod, err, errlen)) return 0;
  return 1;
}

/* Whether filament rod r takes the implicit tension (the header), as the
 * bits of m->fil_implicit: the scheme is SW_IMEX and every node of r is
 * kicked by dv = h F / m, or held by a clamp (dv = 0: an infinite mass). */
static int filament_implicit_bits(const swModel *m, int r) {
  if (m->integrator != SW_IMEX || sw_rod_is_rigid(m, r)) return 0;
  int bits = SW_FIL_IMPLICIT;
  for (int k = 0; k < m->nbc; k++) {
    if (m->bc[k].rod != r || m->bc[k].kind == SW_BC_OMEGA) continue; /* OMEGA: frames only */
    if (m->bc[k].kind != SW_BC_CLAMP || m->bc[k].until > 0) return 0; /* a prescribed dv */
    bits |= m->bc[k].end ? SW_FIL_HELD_END : SW_FIL_HELD_START;
  }
  for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++)
    if (m->kick_exact[i] != 0.0) return 0;
  return bits;
}

int sw_muscle_setup(swModel *m, const swMuscleSpec *ms, char *err, size_t errlen) {
  if (!ms || ms->n == 0) return 1;
  if (!sw_muscle_check(ms, m->nrod, err, errlen)) return 0;
  int nf = 0, nring = 0;
  for (int i = 0; i < ms->n; i++) {
    nf += ms->item[i].desc.filaments;
    nring += ms->item[i].desc.filaments * ms->item[i].desc.nvia;
  }
  const size_t M = (size_t)ms->n, F = (size_t)nf;
  m->nmuscle = ms->n;
  m->nfil = nf;
  m->muscle_name = calloc(M, sizeof *m->muscle_name);
  m->muscle_fil_adr = calloc(M + 1, sizeof *m->muscle_fil_adr);
  m->muscle_activation = calloc(M, sizeof *m->muscle_activation);
  m->muscle_force = calloc(M, sizeof *m->muscle_force);
  m->muscle_prescribed = calloc(M, sizeof *m->muscle_prescribed);
  m->fil_rod = calloc(F, sizeof *m->fil_rod);
  m->fil_passive = calloc(F, sizeof *m->fil_passive);
  m->fil_area = calloc(F, sizeof(double));
  m->fil_fmax = calloc(F, sizeof(double));
  m->fil_l0 = calloc(F, sizeof(double));
  m->fil_tau = calloc(F, sizeof(double));
  m->fil_recruit = calloc(2 * F, sizeof(double));
  m->fil_hill_a = calloc(F, sizeof(double));
  m->fil_v_max = calloc(F, sizeof(double));
  m->fil_fibres = calloc(F, sizeof(double));
  m->fil_implicit = calloc(F, sizeof(int));
  const size_t R = (size_t)nring;
  m->nring = nring;
  m->fil_ring_adr = calloc(F + 1, sizeof(int));
  m->ring_elem = calloc(R + 1, sizeof(int));
  m->ring_point = calloc(3 * R + 1, sizeof(double));
  m->ring_stiffness = calloc(R + 1, sizeof(double));
  m->ring_damping = calloc(R + 1, sizeof(double));
  m->muscle_via = calloc(M * SW_MUSCLE_MAX_VIA * 3, sizeof(double));
  m->muscle_nvia = calloc(M, sizeof(int));
  if (!m->fil_ring_adr || !m->ring_elem || !m->ring_point || !m->ring_stiffness ||
      !m->ring_damping || !m->muscle_via || !m->muscle_nvia) {
    snprintf(err, errlen, "out of memory");
    return 0;
  }
  if (!m->fil_implicit || !m->muscle_name || !m->muscle_fil_adr || !m->muscle_activation ||
      !m->muscle_force || !m->muscle_prescribed || !m->fil_rod ||
      !m->fil_passive || !m->fil_area || !m->fil_fmax || !m->fil_l0 || !m->fil_tau ||
      !m->fil_recruit || !m->fil_hill_a || !m->fil_v_max || !m->fil_fibres) {
    snprintf(err, errlen, "out of memory");
    return 0;
  }
  int f = 0, q = 0;
  for (int i = 0; i < ms->n; i++) {
    const swMuscleItem *it = &ms->item[i];
    const swMuscleDesc *md = &it->desc;
    const int N = md->filaments;
    m->muscle_nvia[i] = md->nvia;
    memcpy(m->muscle_via + 3 * SW_MUSCLE_MAX_VIA * i, md->via, sizeof md->via);
    if (!(m->muscle_name[i] = strdup(it->name))) {
      snprintf(err, errlen, "out of memory");
      return 0;
    }
    m->muscle_fil_adr[i] = f;
    m->muscle_activation[i] = md->activation;
    m->muscle_force[i] = md->prescribed ? md->force : sw_signal_const(0.0);
    m->muscle_prescribed[i] = md->prescribed;
    double *A = m->fil_area + f;
    filament_areas(N, SW_PI * md->radius * md->radius, md->size_ratio, A);
    const double Amin = A[0], Amax = A[N - 1];
    const double fibre_area = 0.25 * SW_PI * md->fibre_diameter * md->fibre_diameter;
    double total = 0, cum = 0;
    for (int k = 0; k < N; k++) total += A[k];
    for (int k = 0; k < N; k++, f++) {
      const int r = it->rod0 + k;
      m->fil_rod[f] = r;
      m->fil_passive[f] = it->passive[k];
      m->fil_fmax[f] = peak_stress(md) * A[k];
      double l0 = 0;
      for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) l0 += m->rest_len[e];
      m->fil_l0[f] = l0;
      /* twitch time linear in size; equal sizes take the mean of the two */
      double w = Amax > Amin ? (A[k] - Amin) / (Amax - Amin) : 0.5;
      m->fil_tau[f] = md->prescribed ? 0.0   /* no activation to follow */
                                     : md->twitch_small + w * (md->twitch_large - md->twitch_small);
      m->fil_recruit[2 * f] = cum / total;
      cum += A[k];
      m->fil_recruit[2 * f + 1] = k == N - 1 ? 1.0 : cum / total;
      m->fil_hill_a[f] = md->hill_a;
      m->fil_v_max[f] = md->v_max;
      m->fil_fibres[f] = A[k] / fibre_area;
      /* via rings; the filament is straight at rest (muscle_via.c) */
      m->fil_ring_adr[f] = q;
      for (int v = 0; v < md->nvia; v++) sw_via_setup_ring(m, q++, md, v, f);
      if (md->nvia > 0)
        for (int v = m->vor_adr[r]; v < m->vor_adr[r] + m->rod_nelem[r] - 1; v++)
          for (int c = 0; c < 3; c++) SW_AT(m, m->rest_kappa, v, c) = 0;
    }
  }
  m->fil_ring_adr[nf] = q;
  m->muscle_fil_adr[ms->n] = f;
  for (int i = 0; i < ms->n; i++)   /* a prescribed force has no Hill damping to solve */
    for (int g = m->muscle_fil_adr[i]; g < m->muscle_fil_adr[i + 1]; g++)
      if (!m->muscle_prescribed[i] && (m->fil_implicit[g] = filament_implicit_bits(m, m->fil_rod[g])))
        m->muscle_implicit = 1;
  for (int g = 0; g < nf; g++) m->rod_wave_dt[m->fil_rod[g]] = sw_stable_dt_rod(m, m->fil_rod[g]);
  /* which element slots pull (sw_muscle_loads' slot loops) */
  const size_t plane = sizeof(double) * (size_t)m->stride;
  if (!(m->fil_elem = aligned_alloc(64, plane))) {
    snprintf(err, errlen, "out of memory");
    return 0;
  }
  memset(m->fil_elem, 0, plane);
  m->fil_slot_lo = m->nslot_elastic;
  m->fil_slot_hi = 0;
  for (int g = 0; g < nf; g++) {
    const int r = m->fil_rod[g];
    for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) m->fil_elem[e] = 1.0;
    /* the nodes elem_adr .. elem_adr + n (a node and the element after it share a slot) */
    if (m->elem_adr[r] < m->fil_slot_lo) m->fil_slot_lo = m->elem_adr[r];
    if (m->elem_adr[r] + m->rod_nelem[r] + 1 > m->fil_slot_hi) m->fil_slot_hi = m->elem_adr[r] + m->rod_nelem[r] + 1;
  }
  return 1;
}

/* ---- the kernels ---- */

/* The drive of filament f under muscle activation u (recruitment). */
static double drive(const swModel *m, int f, double u) {
  if (m->fil_passive[f]) return 0;
  const double lo = m->fil_recruit[2 * f], hi = m->fil_recruit[2 * f + 1];
  double x = (u - lo) / (hi - lo);
  return x < 0 ? 0 : x > 1 ? 1 : x;
}

static double muscle_input(const swModel *m, int i, double t) {
  double u = sw_signal_eval(&m->muscle_activation[i], t);
  return u < 0 ? 0 : u > 1 ? 1 : u;
}

void sw_muscle_reset(const swModel *m, swData *d) {
  sw_via_reset(m, d);
  for (int i = 0; i < m->nmuscle; i++) {
    const double u = muscle_input(m, i, 0.0);
    for (int f = m->muscle_fil_adr[i]; f < m->muscle_fil_adr[i + 1]; f++)
      d->fil_activation[f] = m->fil_tau[f] > 0 || m->muscle_prescribed[i] ? 0.0 : drive(m, f, u);
  }
}

void sw_muscle_advance(const swModel *m, swData *d, double t, double h) {
  for (int i = 0; i < m->nmuscle; i++) {
    const double u = muscle_input(m, i, t + 0.5 * h);
    for (int f = m->muscle_fil_adr[i]; f < m->muscle_fil_adr[i + 1]; f++) {
      if (!(m->fil_tau[f] > 0)) continue;
      const double x = drive(m, f, u);
      d->fil_activation[f] += (x - d->fil_activation[f]) * -expm1(-h / m->fil_tau[f]);
    }
  }
}

/* Tension of filament f at stretch eta, strain rate edot (1/s), activation a. */
double sw_muscle_tension(const swModel *m, int f, double eta, double edot, double a) {
  const double Fmax = m->fil_fmax[f];
  const double Fqs = a * sw_muscle_f_act(eta) * Fmax + Fmax * sw_muscle_f_pass(eta);
  const double k = m->fil_hill_a[f], u0 = m->fil_v_max[f], u = -edot;
  double g; /* T / F_qs */
  if (u >= u0) g = 0;
  else if (u >= 0) g = 1.0 - (1.0 + k) * u / (u + k * u0);
  else g = 1.0 - (1.0 + k) * u / (k * u0);
  return Fqs * g;
}

/* The filaments' pull, in three parts, each over a thread's own slots
 * (internal.h, sw_owned_slots):
 *   1. every filament element e: q_e = t_e . (v_{e+1} - v_e), one vector loop
 *      over the slots (m->fil_elem marks the elements that pull);
 *   2. every filament (by the owner of its first node): l = sum of l_e and
 *      dl/dt = sum of q_e in element order, the stretch, strain rate and
 *      tension T (the header), and T on each of its element slots;
 *   3. every node i: -T t_{i-1} from the element before it, then +T t_i from
 *      its own (T t_e = (T / l_e)(x_{e+1} - x_e)), into d->force and
 *      d->ext_force, one vector loop over the slots.
 * Slot loops instead of one loop per filament: the filaments are short (14
 * elements in the elbow), and a loop that short spends more on its set-up
 * than on its elements.  d->scratch_phi, the drift's scratch, holds q_e
 * (plane 0) and T (plane 1) between the parts.  The order of every sum and
 * of the two terms of each node is fixed, so the result is the same bits for
 * any split, as it was for the loop per filament. */
static void filament_rates(const swModel *m, swData *d, int lo, int hi) {
  const size_t S = (size_t)m->stride;
  const double *restrict x = d->x, *restrict v = d->v, *restrict len = d->length;
  const double *restrict pull = m->fil_elem;
  double *restrict q = d->scratch_phi;
#pragma omp simd
  for (int e = lo; e < hi; e++) {
    const sw3 dx = sw3_sub(sw3_load(x, S, e + 1), sw3_load(x, S, e));
    const sw3 dv = sw3_sub(sw3_load(v, S, e + 1), sw3_load(v, S, e));
    q[e] = sw_select(pull[e] != 0.0, sw3_dot(dx, dv) / len[e], 0.0);
  }
}

/* The muscle whose filaments include f. */
static int muscle_of(const swModel *m, int f) {
  int i = 0;
  while (m->muscle_fil_adr[i + 1] <= f) i++;
  return i;
}

static void filament_tension(const swModel *m, swData *d, int mu, int f, double u, double h) {
  const int r = m->fil_rod[f], lo = m->elem_adr[r], hi = lo + m->rod_nelem[r];
  const double *len = d->length, *q = d->scratch_phi;
  double *T_e = d->scratch_phi + m->stride;
  double l = 0, ldot = 0;
  for (int e = lo; e < hi; e++) {
    l += len[e];
    ldot += q[e];
  }
  if (m->nring) sw_via_implicit_clear(m, d, f); /* set again by an implicit kick's solve */
  if (!(m->fil_tau[f] > 0) && !m->muscle_prescribed[mu]) d->fil_activation[f] = drive(m, f, u);
  const double inv_l0 = 1.0 / m->fil_l0[f];
  const double eta = l * inv_l0, edot = ldot * inv_l0;
  if (m->muscle_prescribed[mu]) {   /* T_k = F(t) A_k / A (the header) */
    const double share = m->fil_recruit[2 * f + 1] - m->fil_recruit[2 * f];   /* A_k / A */
    const double T = sw_signal_eval(&m->muscle_force[mu], d->time) * share;
    d->fil_stretch[f] = eta;
    d->fil_rate[f] = edot;
    d->fil_tension[f] = T;
    for (int e = lo; e < hi; e++) T_e[e] = T;
    return;
  }
  double T = sw_muscle_tension(m, f, eta, edot, d->fil_activation[f]);
  if (m->fil_system && m->fil_system[f]) T = sw_muscle_system_part(m, d, f, T, eta, edot, h);
  else if (h > 0 && m->fil_implicit[f]) T = sw_muscle_implicit_tension(m, d, f, T, eta, edot, h);
  d->fil_stretch[f] = eta;
  d->fil_rate[f] = edot;
  d->fil_tension[f] = T;
  for (int e = lo; e < hi; e++) T_e[e] = T;
}

static void filament_pull(const swModel *m, swData *d, int lo, int hi) {
  const size_t S = (size_t)m->stride;
  const double *restrict x = d->x, *restrict len = d->length, *restrict pull = m->fil_elem;
  const double *restrict T_e = d->scratch_phi + S;
  for (int k = 0; k < 3; k++) {
    const double *restrict xk = x + k * S;
    double *restrict F = d->force + k * S, *restrict ef = d->ext_force + k * S;
    /* slot 0 has no element before it */
    const int start = lo > 0 ? lo : 1;
    if (lo == 0 && hi > 0 && pull[0] != 0.0) {
      const double after = T_e[0] / len[0] * (xk[1] - xk[0]);
      F[0] += after;
      ef[0] += after;
    }
#pragma omp simd
    for (int i = start; i < hi; i++) {
      const int before_pulls = pull[i - 1] != 0.0, own_pulls = pull[i] != 0.0;
      const double before = T_e[i - 1] / len[i - 1] * (xk[i] - xk[i - 1]);
      const double after = T_e[i] / len[i] * (xk[i + 1] - xk[i]);
      const double Fi = sw_select(before_pulls, F[i] - before, F[i]);
      const double efi = sw_select(before_pulls, ef[i] - before, ef[i]);
      F[i] = sw_select(own_pulls, Fi + after, Fi);
      ef[i] = sw_select(own_pulls, efi + after, efi);
    }
  }
}


/* A thread's slots [lo, hi) cut to those the filaments span (the wing's 4
 * filaments hold 28 of its 16,000 slots). */
static void clip_to_filaments(const swModel *m, int *lo, int *hi) {
  if (*lo < m->fil_slot_lo) *lo = m->fil_slot_lo;
  if (*hi > m->fil_slot_hi) *hi = m->fil_slot_hi;
  if (*hi > m->nslot_elastic) *hi = m->nslot_elastic;
}

/* The three parts of the pull (above), each on this thread's slots; the
 * step puts a barrier between them (integrate.c). */
static void muscle_rates(const swModel *m, swData *d) {
  int lo, hi;
  sw_owned_slots(m, d, &lo, &hi);
  if (m->nring) /* each filament's rings by the owner of its first node */
    for (int f = 0; f < m->nfil; f++) {
      const int first = m->node_adr[m->fil_rod[f]];
      if (first >= lo && first < hi) sw_via_rows(m, d, f);
    }
  clip_to_filaments(m, &lo, &hi);
  if (lo < hi) filament_rates(m, d, lo, hi);
}

static void muscle_tensions(const swModel *m, swData *d, double h) {
  int lo, hi, muscle = -1;
  double u = 0;
  sw_owned_slots(m, d, &lo, &hi);
  for (int f = 0; f < m->nfil; f++) {
    const int first = m->node_adr[m->fil_rod[f]];
    if (first < lo || first >= hi) continue;
    if (muscle_of(m, f) != muscle) { /* filaments come muscle by muscle */
      muscle = muscle_of(m, f);
      u = muscle_input(m, muscle, d->time);
    }
    filament_tension(m, d, muscle, f, u, h);
  }
}

static void muscle_pull(const swModel *m, swData *d) {
  int lo, hi;
  sw_owned_slots(m, d, &lo, &hi);
  if (m->nring) /* the implicit rings' force changes (via_implicit.c), on the
                 * filament and its bones; a filament in the joints' system
                 * has them after the system's solve (system_tension) */
    for (int f = 0; f < m->nfil; f++)
      if (!(m->fil_system && m->fil_system[f])) sw_via_implicit_add(m, d, f, lo, hi);
  clip_to_filaments(m, &lo, &hi);
  if (lo < hi) filament_pull(m, d, lo, hi);
}

static void muscle_rings(const swModel *m, swData *d) {
  int lo, hi;
  sw_owned_slots(m, d, &lo, &hi);
  if (m->nring) sw_via_apply(m, d, lo, hi);
}

void sw_muscle_loads(const swModel *m, swData *d) {
  muscle_rates(m, d);
  sw_team_barrier(d);
  muscle_rings(m, d);
  muscle_tensions(m, d, 0.0); /* no kick: the explicit tension */
  sw_team_barrier(d);
  muscle_pull(m, d);
  sw_team_barrier(d);
}

/* Largest stable step for the Hill damping of filament f: the dashpot
 * zeta(0) / l0 on the filament's length, with zeta(0) = (1 + k) F_qs / (k u0)
 * per unit strain rate at the largest F_qs of the law, acts between the end
 * nodes (reduced mass m_end / 2); the explicit kick of a damper of rate c / mu
 * is stable for h c / mu < 2. */
double sw_stable_dt_filament(const swModel *m, int f) {
  const double ring = m->fil_ring_adr ? sw_via_stable_dt(m, f) : INFINITY; /* muscle_via.c */
  if (m->fil_implicit && m->fil_implicit[f]) return ring; /* L-stable (the header) */
  if (m->muscle_prescribed[muscle_of(m, f)]) return ring;  /* no Hill damping */
  double peak = 0; /* max of f_act + p over the fitted range */
  for (int s = 0; s <= 120; s++) {
    double eta = 0.4 + 0.01 * s, q = sw_muscle_f_act(eta) + sw_muscle_f_pass(eta);
    if (q > peak) peak = q;
  }
  const double k = m->fil_hill_a[f], u0 = m->fil_v_max[f];
  const double c = (1.0 + k) * peak * m->fil_fmax[f] / (k * u0) / m->fil_l0[f];
  const int r = m->fil_rod[f], na = m->node_adr[r];
  double mass = fmin(m->mass[na], m->mass[na + m->rod_nelem[r]]);
  return fmin(ring, c > 0 ? 2.0 * (0.5 * mass) / c : INFINITY);
}
