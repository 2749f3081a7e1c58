/* model.c — scene specification, compilation into the immutable swModel, and
 * allocation of the mutable swData.
 *
 * Design.  swSpec is a growable list of rod, load and boundary descriptions
 * filled by the caller (the generated simulator or a test).  sw_compile()
 * validates it, sizes every flat array once, and precomputes everything that
 * does not change during a run: lumped node masses, element stiffness
 * diagonals S^ and inertias J^, Voronoi bending stiffness B^ (rest-length
 * weighted average of the two neighbouring elements, as in PyElastica), rest
 * lengths, rest strains and the per-rod stable time step; joints are
 * validated here and resolved by joint.c (sw_joint_setup).  All memory of a
 * model and of its data is allocated here and nowhere else.
 *
 * Constitutive constants (Gazzola et al. 2018, sec. 2; Zhang et al. 2019,
 * Suppl. Note on snake settings):  A = pi r^2, I1 = I2 = pi r^4 / 4,
 * I3 = 2 I1;  S^ = diag(alpha_c G A, alpha_c G A, E A) with alpha_c = 4/3,
 * B^ = diag(E I1, E I2, G I3);  J^ = rho l^ diag(I1, I2, I3).  Shear and
 * twist hardening multiply G in S^11, S^22 and in B^33 respectively.
 */
#include <stdlib.h>
#include <string.h>
#include <stdarg.h>
#include <math.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

struct swSpec {
  int nrod, nload, nbc, njoint;
  int caprod, capload, capbc, capjoint;
  swRodDesc *rod;
  char **rod_name;
  swRodInfo *rod_info;           /* owned copies of rod[k].kind, material, where */
  double **rest_x, **rest_Q;     /* optional rest shapes, per rod */
  swLoadDesc *load;
  swBCDesc *bc;
  swJointDesc *joint;
  char **joint_name;             /* owned copies of joint[k].name */
  double gravity[3];
  double dt;
  swIntegrator integrator;
  swMuscleSpec *muscles;         /* owned by muscle.c */
  const swMuscleOps *muscle_ops; /* set by muscle.c with the first muscle */
  swEnvSpec *env;                /* owned by environment.c */
  const swEnvOps *env_ops;       /* set by environment.c with the first */
  swExpectList expects;          /* owned by expect.c */
};

swMuscleSpec **sw_spec_muscles(swSpec *s) { return &s->muscles; }
const swMuscleOps **sw_spec_muscle_ops(swSpec *s) { return &s->muscle_ops; }
swEnvSpec **sw_spec_env(swSpec *s) { return &s->env; }
swExpectList *sw_spec_expects(swSpec *s) { return &s->expects; }
const swEnvOps **sw_spec_env_ops(swSpec *s) { return &s->env_ops; }
int sw_spec_nrod(const swSpec *s) { return s->nrod; }

static const double SW_ALPHA_SHEAR = 4.0 / 3.0; /* circular section */

static void free_rod_info(swRodInfo *i) {
  free(i->kind);
  free(i->material);
  free(i->where);
}

/* Owned copies of kind, material and where (each NULL when absent); 0: out
 * of memory. */
static int copy_rod_info(swRodInfo *to, const char *kind, const char *material,
                         const char *where) {
  to->kind = kind ? strdup(kind) : NULL;
  to->material = material ? strdup(material) : NULL;
  to->where = where ? strdup(where) : NULL;
  if ((kind && !to->kind) || (material && !to->material) || (where && !to->where)) {
    free_rod_info(to);
    *to = (swRodInfo){0};
    return 0;
  }
  return 1;
}

swSpec *sw_spec_new(void) {
  swSpec *s = calloc(1, sizeof *s);
  if (s) s->dt = 1e-5;
  return s;
}

void sw_spec_free(swSpec *s) {
  if (!s) return;
  for (int r = 0; r < s->nrod; r++) {
    free(s->rod_name[r]);
    free_rod_info(&s->rod_info[r]);
    free(s->rest_x[r]);
    free(s->rest_Q[r]);
  }
  free(s->rod); free(s->rod_name); free(s->rod_info); free(s->rest_x); free(s->rest_Q);
  for (int k = 0; k < s->njoint; k++) free(s->joint_name[k]);
  free(s->load); free(s->bc); free(s->joint); free(s->joint_name);
  if (s->muscle_ops) s->muscle_ops->free_spec(s->muscles);
  if (s->env_ops) s->env_ops->free_spec(s->env);
  sw_expect_list_free(&s->expects);
  free(s);
}

void sw_rod_desc_init(swRodDesc *r) {
  memset(r, 0, sizeof *r);
  r->name = "rod";
  r->nelem = 50;
  r->direction[2] = 1.0;
  r->normal[0] = 1.0;
  r->length = 1.0;
  r->radius_start = r->radius_end = 0.01;
  r->density = 1000.0;
  r->youngs = 1e6;
  r->poisson = 0.5;
  r->shear_hardening = 1.0;
  r->twist_hardening = 1.0;
  r->gamma_rot = -1.0;
}

/* Grow an array to hold at least n+1 items (0: out of memory). */
int sw_grow(void **p, int *cap, int n, size_t item) {
  if (n < *cap) return 1;
  int nc = *cap ? 2 * *cap : 8;
  void *q = realloc(*p, (size_t)nc * item);
  if (!q) return 0;
  *p = q;
  *cap = nc;
  return 1;
}

int sw_spec_add_rod(swSpec *s, const swRodDesc *r) {
  int cap = s->caprod;
  if (!sw_grow((void **)&s->rod, &cap, s->nrod, sizeof *s->rod)) return -1;
  cap = s->caprod;
  if (!sw_grow((void **)&s->rod_name, &cap, s->nrod, sizeof *s->rod_name)) return -1;
  cap = s->caprod;
  if (!sw_grow((void **)&s->rod_info, &cap, s->nrod, sizeof *s->rod_info)) return -1;
  cap = s->caprod;
  if (!sw_grow((void **)&s->rest_x, &cap, s->nrod, sizeof *s->rest_x)) return -1;
  if (!sw_grow((void **)&s->rest_Q, &s->caprod, s->nrod, sizeof *s->rest_Q)) return -1;
  int id = s->nrod++;
  s->rod[id] = *r;
  s->rod_name[id] = strdup(r->name ? r->name : "rod");
  s->rod[id].name = s->rod_name[id];
  int copied = copy_rod_info(&s->rod_info[id], r->kind, r->material, r->where);
  s->rod[id].kind = s->rod_info[id].kind;
  s->rod[id].material = s->rod_info[id].material;
  s->rod[id].where = s->rod_info[id].where;
  s->rest_x[id] = s->rest_Q[id] = NULL;
  return copied && s->rod_name[id] ? id : -1;
}

int sw_spec_add_load(swSpec *s, const swLoadDesc *l) {
  if (!sw_grow((void **)&s->load, &s->capload, s->nload, sizeof *s->load)) return -1;
  s->load[s->nload] = *l;
  return s->nload++;
}

int sw_spec_add_bc(swSpec *s, const swBCDesc *b) {
  if (!sw_grow((void **)&s->bc, &s->capbc, s->nbc, sizeof *s->bc)) return -1;
  s->bc[s->nbc] = *b;
  return s->nbc++;
}

int sw_spec_add_joint(swSpec *s, const swJointDesc *j) {
  int cap = s->capjoint;
  if (!sw_grow((void **)&s->joint, &cap, s->njoint, sizeof *s->joint)) return -1;
  if (!sw_grow((void **)&s->joint_name, &s->capjoint, s->njoint, sizeof *s->joint_name)) return -1;
  char *name = strdup(j->name ? j->name : "joint");
  if (!name) return -1;
  int id = s->njoint++;
  s->joint[id] = *j;
  s->joint[id].name = s->joint_name[id] = name;
  return id;
}

void sw_spec_set_gravity(swSpec *s, const double g[3]) {
  memcpy(s->gravity, g, sizeof s->gravity);
}
void sw_spec_set_integrator(swSpec *s, swIntegrator integ) { s->integrator = integ; }
void sw_spec_set_dt(swSpec *s, double dt) { s->dt = dt; }

int sw_spec_set_rest_shape(swSpec *s, int rod, const double *x, const double *Q) {
  if (rod < 0 || rod >= s->nrod) return SW_EUSAGE;
  int n = s->rod[rod].nelem;
  if (n < 1) return SW_EMODEL;
  free(s->rest_x[rod]);
  free(s->rest_Q[rod]);
  s->rest_x[rod] = malloc(sizeof(double) * 3 * (size_t)(n + 1));
  s->rest_Q[rod] = malloc(sizeof(double) * 9 * (size_t)n);
  if (!s->rest_x[rod] || !s->rest_Q[rod]) return SW_EMODEL;
  memcpy(s->rest_x[rod], x, sizeof(double) * 3 * (size_t)(n + 1));
  memcpy(s->rest_Q[rod], Q, sizeof(double) * 9 * (size_t)n);
  return SW_OK;
}

/* ---- compilation ---- */

/* A message into err (when given); returns 0, so checks can `return
 * sw_fail(...)`. */
int sw_fail(char *err, size_t errlen, const char *fmt, ...) {
  if (err && errlen) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
  }
  return 0;
}

static int finite_pos(double x) { return isfinite(x) && x > 0; }

static int check_rod(const swRodDesc *r, char *err, size_t errlen) {
  const char *nm = r->name;
  if (r->nelem < 2)
    return sw_fail(err, errlen, "rod '%s': needs at least 2 elements, has %d", nm, r->nelem);
  if (r->nelem > 10000000)
    return sw_fail(err, errlen, "rod '%s': %d elements is more than this build supports", nm, r->nelem);
  if (!finite_pos(r->length)) return sw_fail(err, errlen, "rod '%s': length must be > 0", nm);
  if (!finite_pos(r->radius_start) || !finite_pos(r->radius_end))
    return sw_fail(err, errlen, "rod '%s': radius must be > 0", nm);
  if (!finite_pos(r->density)) return sw_fail(err, errlen, "rod '%s': density must be > 0", nm);
  if (!finite_pos(r->youngs)) return sw_fail(err, errlen, "rod '%s': Young's modulus must be > 0", nm);
  if (r->shear_modulus == 0 && !(r->poisson > -1.0 && r->poisson <= 0.5))
    return sw_fail(err, errlen, "rod '%s': Poisson ratio %g outside (-1, 0.5]", nm, r->poisson);
  if (r->shear_modulus != 0 && !finite_pos(r->shear_modulus))
    return sw_fail(err, errlen, "rod '%s': shear modulus must be > 0", nm);
  if (!finite_pos(r->shear_hardening) || !finite_pos(r->twist_hardening))
    return sw_fail(err, errlen, "rod '%s': hardening factors must be > 0", nm);
  if (!(r->gamma >= 0) || !isfinite(r->gamma))
    return sw_fail(err, errlen, "rod '%s': dissipation constant must be >= 0", nm);
  if (isnan(r->gamma_rot) || !isfinite(r->gamma_rot))
    return sw_fail(err, errlen, "rod '%s': rotational dissipation must be finite", nm);
  if (r->damping != SW_DAMP_NONE && r->damping != SW_DAMP_LINEAR && r->damping != SW_DAMP_ANALYTIC)
    return sw_fail(err, errlen, "rod '%s': unknown damping kind %d", nm, (int)r->damping);
  if (r->rigid != 0 && r->rigid != 1)
    return sw_fail(err, errlen, "rod '%s': rigid must be 0 or 1, got %d", nm, r->rigid);
  if (r->implicit != 0 && r->implicit != 1)
    return sw_fail(err, errlen, "rod '%s': implicit must be 0 or 1, got %d", nm, r->implicit);
  if (r->implicit && r->rigid)
    return sw_fail(err, errlen, "rod '%s': a rigid rod has no elasticity to make implicit", nm);
  if (r->weightless != 0 && r->weightless != 1)
    return sw_fail(err, errlen, "rod '%s': weightless must be 0 or 1, got %d", nm, r->weightless);
  if (r->implicit && r->damping == SW_DAMP_ANALYTIC && (r->gamma > 0 || r->gamma_rot > 0))
    return sw_fail(err, errlen, "rod '%s': analytic damping is not supported on an implicit rod "
                "(use linear damping, which the implicit kick integrates by the trapezoidal rule)", nm);
  if (r->law != SW_LAW_GAZZOLA && r->law != SW_LAW_VARIATIONAL)
    return sw_fail(err, errlen, "rod '%s': unknown constitutive law %d", nm, (int)r->law);
  if (r->rigid && r->damping == SW_DAMP_ANALYTIC && (r->gamma > 0 || r->gamma_rot > 0))
    return sw_fail(err, errlen, "rod '%s': analytic damping is not supported on a rigid rod "
                "(use linear damping)", nm);
  double Q[9];
  if (!sw_frame_from(Q, r->direction, r->normal))
    return sw_fail(err, errlen, "rod '%s': direction is zero or parallel to normal", nm);
  return 1;
}

static double *dalloc(size_t n) { return calloc(n ? n : 1, sizeof(double)); }

/* `planes` planes of m->stride doubles, zeroed and 64-byte aligned (the
 * per-slot arrays; sinew.h, "Layout"). */
static double *palloc(const swModel *m, int planes) {
  size_t bytes = sizeof(double) * (size_t)planes * (size_t)m->stride;
  double *p = aligned_alloc(64, bytes); /* stride is a multiple of 8 doubles */
  if (p) memset(p, 0, bytes);
  return p;
}

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
  m->rigid_mass = dalloc(B); m->rigid_inertia = dalloc(3 * B); m->rigid_X0 = dalloc(3 * B);
  m->rigid_R0 = dalloc(9 * B); m->rigid_p = dalloc(3 * nodes); m->rigid_B = dalloc(9 * elems);
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
    if (m->rod_info) free_rod_info(&m->rod_info[r]);
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
  free(m->joint); free(m->joint_name); free(m->joint_node_a); free(m->joint_node_b);
  free(m->joint_elem_a); free(m->joint_elem_b); free(m->joint_axis_a); free(m->joint_axis_b);
  free(m->joint_rest_rot); free(m->joint_angle0); free(m->joint_wave_dt); free(m->joint_limit_ref);
  sw_rigid_joints_free(m);
  sw_implicit_free(m);
  if (sw_muscle_ops(m)) sw_muscle_ops(m)->free_model(m);
  if (sw_env_ops(m)) sw_env_ops(m)->free_model(m);
  rigid_free(m);
  free(m);
}

/* Initial node positions and directors of rod r: straight, or the rest shape
 * given with sw_spec_set_rest_shape. */
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

static int check_signal(const swSignal *g, char *err, size_t errlen, const char *what, int k,
                        const char *rod) {
  if (g->kind < SW_SIG_CONST || g->kind > SW_SIG_BSPLINE)
    return sw_fail(err, errlen, "%s %d on rod '%s': unknown signal kind %d", what, k, rod, (int)g->kind);
  if (!(g->period >= 0) || !isfinite(g->period))
    return sw_fail(err, errlen, "%s %d on rod '%s': signal period must be >= 0 (0: not periodic), "
                "got %g", what, k, rod, g->period);
  if (g->kind == SW_SIG_BSPLINE) {
    if (g->npts < 4 || g->npts > SW_SIGNAL_MAXPTS)
      return sw_fail(err, errlen, "%s %d on rod '%s': B-spline signal needs 4..%d coefficients, "
                  "has %d", what, k, rod, SW_SIGNAL_MAXPTS, g->npts);
    if (!(g->T > 0) || !isfinite(g->T))
      return sw_fail(err, errlen, "%s %d on rod '%s': B-spline signal duration must be > 0", what, k,
                  rod);
    for (int i = 0; i < g->npts; i++)
      if (!isfinite(g->values[i]))
        return sw_fail(err, errlen, "%s %d on rod '%s': B-spline coefficient %d is not finite", what,
                    k, rod, i);
    return 1;
  }
  if (g->kind != SW_SIG_TABLE) return 1;
  if (g->npts < 1 || g->npts > SW_SIGNAL_MAXPTS)
    return sw_fail(err, errlen, "%s %d on rod '%s': table signal needs 1..%d points, has %d", what, k,
                rod, SW_SIGNAL_MAXPTS, g->npts);
  for (int i = 0; i < g->npts; i++) {
    if (!isfinite(g->times[i]) || !isfinite(g->values[i]))
      return sw_fail(err, errlen, "%s %d on rod '%s': table point %d is not finite", what, k, rod, i);
    if (i > 0 && !(g->times[i] > g->times[i - 1]))
      return sw_fail(err, errlen, "%s %d on rod '%s': table times must increase (point %d)", what, k,
                  rod, i);
  }
  return 1;
}

static int check_loads_bcs(const swSpec *s, char *err, size_t errlen) {
  for (int k = 0; k < s->nload; k++) {
    const swLoadDesc *l = &s->load[k];
    if (l->rod < 0 || l->rod >= s->nrod)
      return sw_fail(err, errlen, "load %d: rod index %d out of range", k, l->rod);
    const char *nm = s->rod[l->rod].name;
    if (l->kind != SW_LOAD_FORCE && l->kind != SW_LOAD_TORQUE)
      return sw_fail(err, errlen, "load %d on rod '%s': unknown kind %d", k, nm, (int)l->kind);
    int n = s->rod[l->rod].nelem, lim = l->kind == SW_LOAD_FORCE ? n + 1 : n;
    if (l->index < -1 || l->index >= lim)
      return sw_fail(err, errlen, "load %d on rod '%s': %s index %d out of range [0, %d)", k, nm,
                  l->kind == SW_LOAD_FORCE ? "node" : "element", l->index, lim);
    if (!isfinite(l->vec[0]) || !isfinite(l->vec[1]) || !isfinite(l->vec[2]))
      return sw_fail(err, errlen, "load %d on rod '%s': vector is not finite", k, nm);
    if (!check_signal(&l->signal, err, errlen, "load", k, nm)) return 0;
  }
  for (int k = 0; k < s->nbc; k++) {
    const swBCDesc *b = &s->bc[k];
    if (b->rod < 0 || b->rod >= s->nrod)
      return sw_fail(err, errlen, "boundary condition %d: rod index %d out of range", k, b->rod);
    const char *nm = s->rod[b->rod].name;
    if (b->end != 0 && b->end != 1)
      return sw_fail(err, errlen, "boundary condition %d on rod '%s': end must be 0 (start) or 1 (end)",
                  k, nm);
    if (b->kind < SW_BC_CLAMP || b->kind > SW_BC_OMEGA)
      return sw_fail(err, errlen, "boundary condition %d on rod '%s': unknown kind %d", k, nm, (int)b->kind);
    if (!isfinite(b->vec[0]) || !isfinite(b->vec[1]) || !isfinite(b->vec[2]))
      return sw_fail(err, errlen, "boundary condition %d on rod '%s': vector is not finite", k, nm);
    if (!check_signal(&b->signal, err, errlen, "boundary condition", k, nm)) return 0;
    if (s->rod[b->rod].rigid && b->kind != SW_BC_CLAMP)
      return sw_fail(err, errlen, "boundary condition %d on rod '%s': a prescribed %s is not "
                  "supported on a rigid rod (clamp it, or hold it with a joint)", k, nm,
                  b->kind == SW_BC_VELOCITY ? "velocity" : "angular velocity");
  }
  return 1;
}

/* A joint's stiffness or damping: finite and >= 0 (0 = chosen by joint.c). */
static int check_joint_coef(const swJointDesc *j, double v, const char *what, char *err,
                            size_t errlen) {
  if (isfinite(v) && v >= 0) return 1;
  return sw_fail(err, errlen, "joint '%s': %s must be finite and >= 0 (0 = automatic), got %g",
              j->name, what, v);
}

/* A joint's limits (joint.c, "Limits"): a range on hinges only, ordered; a
 * cone on spherical joints only, in (0, pi); their coefficients >= 0. */
static int check_joint_limits(const swJointDesc *j, char *err, size_t errlen) {
  const char *nm = j->name, *kind = sw_joint_kind_name(j->kind);
  if (j->has_range && j->kind != SW_JOINT_HINGE)
    return sw_fail(err, errlen, "joint '%s': an angle range is for a hinge, not a %s joint", nm,
                   kind);
  if (j->has_range && !(isfinite(j->angle_min) && isfinite(j->angle_max) &&
                        j->angle_min < j->angle_max))
    return sw_fail(err, errlen, "joint '%s': angle range must be finite with angle_min < "
                   "angle_max, got [%g, %g] rad", nm, j->angle_min, j->angle_max);
  if (j->cone != 0 && j->kind != SW_JOINT_SPHERICAL)
    return sw_fail(err, errlen, "joint '%s': a cone is for a spherical joint, not a %s joint", nm,
                   kind);
  if (!(j->cone >= 0 && j->cone < SW_PI))
    return sw_fail(err, errlen, "joint '%s': cone must be in (0, pi) rad (0 = none), got %g", nm,
                   j->cone);
  if (!check_joint_coef(j, j->limit_stiffness, "limit stiffness", err, errlen) ||
      !check_joint_coef(j, j->limit_damping, "limit damping", err, errlen))
    return 0;
  if (j->undamped && j->limit_damping != 0)
    return sw_fail(err, errlen, "joint '%s': declared undamped but limit damping is given", nm);
  return 1;
}

/* Node index of a joint end on rod r: -1 (last) or 0..n. */
static int check_joint_node(const swSpec *s, const swJointDesc *j, int rod, int node,
                            const char *end, char *err, size_t errlen) {
  int n = s->rod[rod].nelem;
  if (node >= -1 && node <= n) return 1;
  return sw_fail(err, errlen, "joint '%s': %s %d out of range for rod '%s' (nodes 0..%d, -1 = last)",
              j->name, end, node, s->rod[rod].name, n);
}

static int check_joints(const swSpec *s, char *err, size_t errlen) {
  for (int k = 0; k < s->njoint; k++) {
    const swJointDesc *j = &s->joint[k];
    const char *nm = j->name;
    for (int i = 0; i < k; i++)
      if (!strcmp(s->joint[i].name, nm))
        return sw_fail(err, errlen, "joint '%s': name already used by joint %d", nm, i);
    if (j->kind != SW_JOINT_SPHERICAL && j->kind != SW_JOINT_HINGE && j->kind != SW_JOINT_FIXED)
      return sw_fail(err, errlen, "joint '%s': unknown kind %d", nm, (int)j->kind);
    if (j->rod_a < 0 || j->rod_a >= s->nrod)
      return sw_fail(err, errlen, "joint '%s': rod_a index %d out of range [0, %d)", nm, j->rod_a,
                  s->nrod);
    if (j->rod_b < -1 || j->rod_b >= s->nrod)
      return sw_fail(err, errlen, "joint '%s': rod_b index %d out of range [0, %d) (-1 = anchored)",
                  nm, j->rod_b, s->nrod);
    if (!check_joint_node(s, j, j->rod_a, j->node_a, "node_a", err, errlen)) return 0;
    if (j->rod_b >= 0) {
      if (!check_joint_node(s, j, j->rod_b, j->node_b, "node_b", err, errlen)) return 0;
      int n = s->rod[j->rod_a].nelem;
      int na = j->node_a < 0 ? n : j->node_a, nb = j->node_b < 0 ? n : j->node_b;
      if (j->rod_b == j->rod_a && na == nb)
        return sw_fail(err, errlen, "joint '%s': joins node %d of rod '%s' to itself", nm, na,
                    s->rod[j->rod_a].name);
    } else if (!isfinite(j->anchor[0]) || !isfinite(j->anchor[1]) || !isfinite(j->anchor[2])) {
      return sw_fail(err, errlen, "joint '%s': anchor is not finite", nm);
    }
    if (j->kind == SW_JOINT_HINGE) {
      double a2 = j->axis[0] * j->axis[0] + j->axis[1] * j->axis[1] + j->axis[2] * j->axis[2];
      if (!isfinite(a2) || !(a2 > 0))
        return sw_fail(err, errlen, "joint '%s': hinge axis must be finite and nonzero", nm);
    }
    if (!check_joint_coef(j, j->stiffness, "stiffness", err, errlen) ||
        !check_joint_coef(j, j->damping, "damping", err, errlen) ||
        !check_joint_coef(j, j->rot_stiffness, "rotational stiffness", err, errlen) ||
        !check_joint_coef(j, j->rot_damping, "rotational damping", err, errlen))
      return 0;
    if (j->undamped && (j->damping != 0 || j->rot_damping != 0))
      return sw_fail(err, errlen, "joint '%s': declared undamped but damping is given", nm);
    if (!check_joint_limits(j, err, errlen)) return 0;
  }
  return 1;
}

swModel *sw_compile(const swSpec *s, char *err, size_t errlen) {
  if (s && s->muscle_ops && !s->muscle_ops->check(s->muscles, s->nrod, err, errlen)) return NULL;
  if (!s || s->nrod < 1) {
    sw_fail(err, errlen, "the scene has no rods");
    return NULL;
  }
  if (!finite_pos(s->dt)) {
    sw_fail(err, errlen, "time step must be > 0, got %g", s->dt);
    return NULL;
  }
  if (s->integrator != SW_VERLET && s->integrator != SW_PEFRL && s->integrator != SW_IMEX) {
    sw_fail(err, errlen, "unknown integrator %d", (int)s->integrator);
    return NULL;
  }
  for (int r = 0; r < s->nrod; r++)
    if (!check_rod(&s->rod[r], err, errlen)) return NULL;
  if (!check_loads_bcs(s, err, errlen)) return NULL;
  if (!check_joints(s, err, errlen)) return NULL;
  if (s && s->env_ops && !s->env_ops->check(s->env, s->nrod, err, errlen)) return NULL;

  swModel *m = calloc(1, sizeof *m);
  if (!m) return NULL;
  m->nrod = s->nrod;
  m->dt = s->dt;
  m->integrator = s->integrator;
  memcpy(m->gravity, s->gravity, sizeof m->gravity);
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
  m->rod_wave_dt = dalloc((size_t)nr);
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
      if (!m->rod_name[r] || !copy_rod_info(&m->rod_info[r], s->rod[r].kind,
                                            s->rod[r].material, s->rod[r].where))
        goto oom;
      m->rod_info[r].youngs = s->rod[r].youngs;
      m->rod_info[r].shear_modulus = s->rod[r].shear_modulus > 0
                                         ? s->rod[r].shear_modulus
                                         : s->rod[r].youngs / (2 * (1 + s->rod[r].poisson));
      m->rod_info[r].density = s->rod[r].density;
      m->rod_info[r].length = s->rod[r].length;
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
  m->mass = palloc(m, 1); m->inv_mass = palloc(m, 1); m->node_gamma = palloc(m, 1); m->node_decay = palloc(m, 1); m->node_kick = palloc(m, 1); m->x0 = palloc(m, 3);
  m->rest_len = palloc(m, 1); m->inv_rest_len = palloc(m, 1); m->radius = palloc(m, 1); m->shear_stiff = palloc(m, 3);
  m->inertia = palloc(m, 3); m->inv_inertia = palloc(m, 3); m->rest_sigma = palloc(m, 3);
  m->elem_gamma = palloc(m, 3); m->elem_decay = palloc(m, 3); m->elem_kick = palloc(m, 3); m->Q0 = palloc(m, 9); m->clamp_bend = palloc(m, 3);
  m->rest_vor_len = palloc(m, 1); m->bend_stiff = palloc(m, 3); m->rest_kappa = palloc(m, 3);
  m->elem_ghost = palloc(m, 1); m->elem_variational = palloc(m, 1); m->kick_exact = palloc(m, 1); m->damp_linear = palloc(m, 1); m->inv_rest_vor_len = palloc(m, 1);
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
    double *x = dalloc(3 * (size_t)(n + 1)), *Q = dalloc(9 * (size_t)n);
    double *bend_elem = dalloc(3 * (size_t)n); /* element B^ before Voronoi averaging */
    if (!x || !Q || !bend_elem) {
      free(x); free(Q); free(bend_elem);
      goto oom;
    }
    place_rod(s, r, x, Q);
    for (int i = 0; i <= n; i++) sw_set3(m, m->x0, na + i, x + 3 * i);
    for (int i = 0; i < n; i++) sw_setQ(m, m->Q0, ea + i, Q + 9 * i);
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
      if (!(m->weight = palloc(m, 1))) goto oom;
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
  m->bc_slot_order = 1; /* boundary.c looks only near a call's slots then */
  for (int k = 1; k < m->nbc; k++)
    if (sw_bc_node(m, &m->bc[k]) < sw_bc_node(m, &m->bc[k - 1])) m->bc_slot_order = 0;
  for (int k = 0; k < m->nload; k++)
    if (m->load[k].index == -1)
      m->load[k].index = m->rod_nelem[m->load[k].rod] - (m->load[k].kind == SW_LOAD_TORQUE);
  if (!rigid_alloc(m, s)) goto oom;
  sw_rigid_setup(m);
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
  m->joint_axis_a = dalloc(3 * J); m->joint_axis_b = dalloc(3 * J);
  m->joint_rest_rot = dalloc(9 * J); m->joint_angle0 = dalloc(J); m->joint_wave_dt = dalloc(J);
  m->joint_limit_ref = dalloc(9 * J);
  if (!m->joint || !m->joint_name || !m->joint_node_a || !m->joint_node_b || !m->joint_elem_a ||
      !m->joint_elem_b || !m->joint_axis_a || !m->joint_axis_b || !m->joint_rest_rot ||
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
  if (!sw_rigid_joints_setup(m)) goto oom;
  for (int j = 0; j < m->njoint; j++) m->joint_wave_dt[j] = sw_stable_dt_joint(m, j);
  m->muscle_ops = s->muscle_ops;
  m->env_ops = s->env_ops;
  if ((s->muscle_ops && !s->muscle_ops->setup(m, s->muscles, err, errlen)) ||
      (s->env_ops && !s->env_ops->setup(m, s->env, err, errlen)) ||
      !sw_expect_setup(m, &s->expects, err, errlen)) {
    sw_model_free(m);
    return NULL;
  }
  return m;

oom:
  sw_fail(err, errlen, "out of memory while building the model");
  sw_model_free(m);
  return NULL;
}

/* ---- data ---- */

void sw_data_free(swData *d) {
  if (!d) return;
  free(d->x); free(d->v); free(d->Q); free(d->omega);
  free(d->length); free(d->dilatation);
  free(d->sigma); free(d->stress); free(d->vor_dilatation); free(d->kappa); free(d->couple);
  free(d->force); free(d->torque); free(d->ext_force); free(d->ext_torque);
  free(d->scratch_f); free(d->scratch_h); free(d->scratch_flag); free(d->scratch_phi);
  free(d->chunk_sum); free(d->bc_work); free(d->joint_scratch); free(d->team);
  free(d->joint_force); free(d->joint_angle); free(d->joint_limit_torque);
  free(d->fil_activation); free(d->fil_stretch); free(d->fil_rate); free(d->fil_tension);
  free(d->ring_row);
  free(d->rigid_X); free(d->rigid_V); free(d->rigid_R); free(d->rigid_L); free(d->rigid_omega);
  free(d->rigid_load); free(d->rigid_sys); free(d->implicit_sys);
  sw_probe_data_free(d);
  /* the contact grid's scratch (contact.c, through the environment's data_new) */
  free(d->contact_cell); free(d->contact_bucket); free(d->contact_sorted);
  free(d->contact_start); free(d->contact_occupied); free(d->contact_sorted_cell);
  free(d);
}

swData *sw_data_new(const swModel *m) {
  swData *d = calloc(1, sizeof *d);
  if (!d) return NULL;
  d->x = palloc(m, 3); d->v = palloc(m, 3); d->Q = palloc(m, 9); d->omega = palloc(m, 3);
  d->length = palloc(m, 1); d->dilatation = palloc(m, 1);
  d->sigma = palloc(m, 3); d->stress = palloc(m, 3);
  d->vor_dilatation = palloc(m, 1); d->kappa = palloc(m, 3); d->couple = palloc(m, 3);
  d->force = palloc(m, 3); d->torque = palloc(m, 3);
  d->ext_force = palloc(m, 3); d->ext_torque = palloc(m, 3);
  d->scratch_f = palloc(m, 3); d->scratch_h = palloc(m, 3);
  d->scratch_flag = palloc(m, 1); d->scratch_phi = palloc(m, 3);
  d->chunk_sum = dalloc((size_t)sw_nchunk(m, m->stride));
  d->bc_work = dalloc((size_t)m->nbc);
  d->joint_scratch = dalloc(SW_JOINT_ROW * (size_t)m->njoint);
  d->threads = 1;
  d->team_size = 1;
  d->team = aligned_alloc(64, sizeof(swTeam));
  if (d->team) memset(d->team, 0, sizeof(swTeam));
  d->joint_force = dalloc(3 * (size_t)m->njoint); d->joint_angle = dalloc((size_t)m->njoint);
  d->joint_limit_torque = dalloc(3 * (size_t)m->njoint);
  size_t F = (size_t)m->nfil;
  d->fil_activation = dalloc(F); d->fil_stretch = dalloc(F); d->fil_rate = dalloc(F);
  d->fil_tension = dalloc(F);
  d->ring_row = dalloc(SW_RING_ROW * (size_t)m->nring);
  if (!d->x || !d->v || !d->Q || !d->omega || !d->length || !d->dilatation ||
      !d->sigma || !d->stress || !d->vor_dilatation || !d->kappa ||
      !d->couple || !d->force || !d->torque || !d->ext_force || !d->ext_torque ||
      !d->scratch_f || !d->scratch_h || !d->scratch_flag || !d->scratch_phi ||
      !d->chunk_sum || !d->bc_work || !d->joint_scratch || !d->team || !d->joint_force ||
      !d->joint_angle || !d->joint_limit_torque || !d->fil_activation || !d->fil_stretch ||
      !d->fil_rate || !d->fil_tension || !d->ring_row) {
    sw_data_free(d);
    return NULL;
  }
  size_t B = (size_t)m->nrigid;
  d->rigid_X = dalloc(3 * B); d->rigid_V = dalloc(3 * B); d->rigid_R = dalloc(9 * B);
  d->rigid_L = dalloc(3 * B); d->rigid_omega = dalloc(3 * B); d->rigid_load = dalloc(6 * B);
  d->rigid_sys = dalloc(sw_rigid_joints_scratch(m));
  d->implicit_sys = dalloc(sw_implicit_scratch(m));
  if (!d->rigid_X || !d->rigid_V || !d->rigid_R || !d->rigid_L || !d->rigid_omega ||
      !d->rigid_load || !d->rigid_sys || !d->implicit_sys ||
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
  d->work = 0;
  d->error[0] = 0;
  const size_t plane = sizeof(double) * (size_t)m->stride;
  memcpy(d->x, m->x0, 3 * plane);
  memcpy(d->Q, m->Q0, 9 * plane);
  memset(d->v, 0, 3 * plane);
  memset(d->omega, 0, 3 * plane);
  for (int i = 0; i < m->stride; i++) d->dilatation[i] = d->vor_dilatation[i] = 1.0;
  if (m->nrigid) sw_rigid_reset(m, d);
  sw_probe_reset(m, d);
  d->contact_pairs = 0; /* contact.c's figures are those of the last evaluation */
  d->contact_max_overlap = 0;
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
