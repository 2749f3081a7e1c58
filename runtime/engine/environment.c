/* environment.c — the scene's environments: grounds and terrains, fluids,
 * rod-rod contact, rigid obstacles, travelling torque waves and probes, from description to
 * compiled model, and the one place the step reaches them from.
 *
 * Design.  Like muscles, environments are lists the swSpec keeps in an
 * opaque slot (swEnvSpec) that this file owns.  Adding a description copies
 * it with its name and rod list, so a caller's buffers can go away; checking
 * happens in sw_compile (sw_env_check), where every message names the
 * description and what is wrong with it; compiling (sw_env_setup) puts
 * resolved copies in the model, with "every rod" (nrods = 0) expanded into
 * an explicit list, so kernels never special-case it.  Each kind's physics
 * lives in its own file (ground.c, fluid.c, contact.c, wave.c, probe.c);
 * this file only dispatches: sw_env_loads is called by integrate.c after all
 * other loads (the ground's response balances the normal part of the others,
 * so it must come last), sw_env_energy adds the stored contact and ground
 * energies, sw_env_stable_dt the environments' step limits.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"

struct swEnvSpec {
  swGroundDesc *ground;   int nground, capground;
  swFluidDesc *fluid;     int nfluid, capfluid;
  swContactDesc *contact; int ncontact, capcontact;
  swWaveDesc *wave;       int nwave, capwave;
  swProbeDesc *probe;     int nprobe, capprobe;
  swObstacleDesc *obstacle; int nobstacle, capobstacle;
};

/* ---- defaults ---- */

void sw_ground_desc_init(swGroundDesc *g) {
  memset(g, 0, sizeof *g);
  g->name = "ground";
  g->normal[2] = 1.0;
  g->slip_velocity = 1e-4; /* PyElastica's default slip tolerance, m/s */
}

void sw_fluid_desc_init(swFluidDesc *f) {
  memset(f, 0, sizeof *f);
  f->name = "fluid";
  f->model = SW_FLUID_STOKES;
}

void sw_contact_desc_init(swContactDesc *c) {
  memset(c, 0, sizeof *c);
  c->name = "contact";
}

void sw_obstacle_desc_init(swObstacleDesc *o) {
  memset(o, 0, sizeof *o);
  o->name = "obstacle";
  o->shape = SW_OBSTACLE_SPHERE;
  o->axis[2] = 1.0;
  o->normal[0] = 1.0;
  o->carrier_rod = -1;
  o->carrier_node = -1;
}

void sw_wave_desc_init(swWaveDesc *w) {
  memset(w, 0, sizeof *w);
  w->name = "wave";
  w->direction[2] = 1.0;
}

void sw_probe_desc_init(swProbeDesc *p) {
  memset(p, 0, sizeof *p);
  p->name = "probe";
  p->kind = SW_PROBE_COM;
  p->node = -1;
}

/* ---- the spec's lists ---- */

static const swEnvOps env_ops = {sw_env_check, sw_env_setup,     sw_env_free,     sw_env_spec_free,
                                 sw_env_loads, sw_env_energy,    sw_env_stable_dt, sw_env_data_new};

static swEnvSpec *env_of(swSpec *s) {
  *sw_spec_env_ops(s) = &env_ops; /* the step reaches this file through these */
  swEnvSpec **slot = sw_spec_env(s);
  if (!*slot) *slot = calloc(1, sizeof **slot);
  return *slot;
}

/* Append item (size bytes) to the list *p of *n items; its index, or -1
 * when out of memory. */
static int push(void **p, int *n, int *cap, const void *item, size_t size) {
  if (!sw_grow(p, cap, *n, size)) return -1;
  memcpy((char *)*p + (size_t)*n * size, item, size);
  return (*n)++;
}

/* Owned copies of a name and a rod list; 0 when out of memory (nothing kept). */
static int own(const char **name, const int **rods, int nrods, const char *fallback) {
  char *nm = strdup(*name ? *name : fallback);
  int *list = NULL;
  if (nrods > 0 && *rods) {
    list = malloc(sizeof(int) * (size_t)nrods);
    if (list) memcpy(list, *rods, sizeof(int) * (size_t)nrods);
  }
  if (!nm || (nrods > 0 && *rods && !list)) {
    free(nm);
    free(list);
    return 0;
  }
  *name = nm;
  *rods = list;
  return 1;
}

static void disown(const char *name, const int *rods) {
  free((char *)name);
  free((int *)rods);
}

int sw_spec_add_ground(swSpec *s, const swGroundDesc *g) {
  swGroundDesc c = *g;
  if (!own(&c.name, &c.rods, c.nrods, "ground")) return -1;
  swEnvSpec *e = env_of(s);
  int id = e ? push((void **)&e->ground, &e->nground, &e->capground, &c, sizeof c) : -1;
  if (id < 0) disown(c.name, c.rods);
  return id;
}

int sw_spec_add_fluid(swSpec *s, const swFluidDesc *f) {
  swFluidDesc c = *f;
  if (!own(&c.name, &c.rods, c.nrods, "fluid")) return -1;
  swEnvSpec *e = env_of(s);
  int id = e ? push((void **)&e->fluid, &e->nfluid, &e->capfluid, &c, sizeof c) : -1;
  if (id < 0) disown(c.name, c.rods);
  return id;
}

int sw_spec_add_contact(swSpec *s, const swContactDesc *cd) {
  swContactDesc c = *cd;
  if (!own(&c.name, &c.rods, c.nrods, "contact")) return -1;
  swEnvSpec *e = env_of(s);
  int id = e ? push((void **)&e->contact, &e->ncontact, &e->capcontact, &c, sizeof c) : -1;
  if (id < 0) disown(c.name, c.rods);
  return id;
}

int sw_spec_add_obstacle(swSpec *s, const swObstacleDesc *o) {
  swObstacleDesc c = *o;
  if (!own(&c.name, &c.rods, c.nrods, "obstacle")) return -1;
  swEnvSpec *e = env_of(s);
  int id = e ? push((void **)&e->obstacle, &e->nobstacle, &e->capobstacle, &c, sizeof c) : -1;
  if (id < 0) disown(c.name, c.rods);
  return id;
}

int sw_spec_add_wave(swSpec *s, const swWaveDesc *w) {
  swWaveDesc c = *w;
  const int *none = NULL;
  if (!own(&c.name, &none, 0, "wave")) return -1;
  swEnvSpec *e = env_of(s);
  int id = e ? push((void **)&e->wave, &e->nwave, &e->capwave, &c, sizeof c) : -1;
  if (id < 0) disown(c.name, NULL);
  return id;
}

int sw_spec_add_probe(swSpec *s, const swProbeDesc *p) {
  swProbeDesc c = *p;
  if (!own(&c.name, &c.rods, c.nrods, "probe")) return -1;
  swEnvSpec *e = env_of(s);
  int id = e ? push((void **)&e->probe, &e->nprobe, &e->capprobe, &c, sizeof c) : -1;
  if (id < 0) disown(c.name, c.rods);
  return id;
}

void sw_env_spec_free(swEnvSpec *e) {
  if (!e) return;
  for (int k = 0; k < e->nground; k++) disown(e->ground[k].name, e->ground[k].rods);
  for (int k = 0; k < e->nfluid; k++) disown(e->fluid[k].name, e->fluid[k].rods);
  for (int k = 0; k < e->ncontact; k++) disown(e->contact[k].name, e->contact[k].rods);
  for (int k = 0; k < e->nwave; k++) disown(e->wave[k].name, NULL);
  for (int k = 0; k < e->nprobe; k++) disown(e->probe[k].name, e->probe[k].rods);
  for (int k = 0; k < e->nobstacle; k++) disown(e->obstacle[k].name, e->obstacle[k].rods);
  free(e->ground); free(e->fluid); free(e->contact); free(e->wave); free(e->probe);
  free(e->obstacle);
  free(e);
}

/* ---- checks ---- */



static int nonneg(double x) { return isfinite(x) && x >= 0; }
static int positive(double x) { return isfinite(x) && x > 0; }
static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

static int check_rods(const char *what, const char *name, int nrods, const int *rods, int nrod,
                      char *err, size_t errlen) {
  if (nrods < 0 || (nrods > 0 && !rods))
    return sw_fail(err, errlen, "%s '%s': bad rod list (%d rods)", what, name, nrods);
  for (int k = 0; k < nrods; k++) {
    if (rods[k] < 0 || rods[k] >= nrod)
      return sw_fail(err, errlen, "%s '%s': rod %d does not exist (the scene has %d)", what, name,
                  rods[k], nrod);
    for (int j = 0; j < k; j++) /* a rod twice would feel a fluid or ground twice */
      if (rods[j] == rods[k])
        return sw_fail(err, errlen, "%s '%s': rod %d is listed twice", what, name, rods[k]);
  }
  return 1;
}

/* A coefficient triple (forward, backward, sideways) of friction. */
static int check_mu(const char *name, const char *which, const double mu[3], char *err,
                    size_t errlen) {
  static const char *const dir[3] = {"forward", "backward", "sideways"};
  for (int k = 0; k < 3; k++)
    if (!nonneg(mu[k]))
      return sw_fail(err, errlen, "ground '%s': %s friction coefficient %s is %g, must be >= 0", name,
                  which, dir[k], mu[k]);
  return 1;
}

static int check_ground(const swGroundDesc *g, int nrod, char *err, size_t errlen) {
  const char *nm = g->name;
  if (!check_rods("ground", nm, g->nrods, g->rods, nrod, err, errlen)) return 0;
  if (!g->height) {
    if (!finite3(g->origin)) return sw_fail(err, errlen, "ground '%s': origin is not finite", nm);
    if (!finite3(g->normal) || !(sw_v3_norm(g->normal) > 0))
      return sw_fail(err, errlen, "ground '%s': normal must be a nonzero vector", nm);
  }
  if (!nonneg(g->stiffness)) return sw_fail(err, errlen, "ground '%s': stiffness must be >= 0", nm);
  if (!nonneg(g->damping)) return sw_fail(err, errlen, "ground '%s': damping must be >= 0", nm);
  if (!check_mu(nm, "kinetic", g->mu_kinetic, err, errlen)) return 0;
  if (!check_mu(nm, "static", g->mu_static, err, errlen)) return 0;
  if (!nonneg(g->mu_rolling))
    return sw_fail(err, errlen, "ground '%s': rolling friction coefficient must be >= 0", nm);
  if (!positive(g->slip_velocity))
    return sw_fail(err, errlen, "ground '%s': slip velocity tolerance must be > 0", nm);
  if (!nonneg(g->contact_tolerance))
    return sw_fail(err, errlen, "ground '%s': contact tolerance must be >= 0", nm);
  return 1;
}

static int check_fluid(const swFluidDesc *f, int nrod, char *err, size_t errlen) {
  const char *nm = f->name;
  if (!check_rods("fluid", nm, f->nrods, f->rods, nrod, err, errlen)) return 0;
  if (f->model != SW_FLUID_STOKES && f->model != SW_FLUID_QUADRATIC)
    return sw_fail(err, errlen, "fluid '%s': unknown model %d", nm, (int)f->model);
  if (f->area != SW_FLUID_SILHOUETTE && f->area != SW_FLUID_CROSS_SECTION && f->area != SW_FLUID_BROADSIDE)
    return sw_fail(err, errlen, "fluid '%s': unknown drag area %d", nm, (int)f->area);
  if (f->model == SW_FLUID_STOKES && !positive(f->viscosity))
    return sw_fail(err, errlen, "fluid '%s': Stokes drag needs a viscosity > 0", nm);
  if (f->model == SW_FLUID_QUADRATIC && !positive(f->density))
    return sw_fail(err, errlen, "fluid '%s': quadratic drag needs a density > 0", nm);
  if (f->model == SW_FLUID_QUADRATIC && !positive(f->drag_coefficient))
    return sw_fail(err, errlen, "fluid '%s': quadratic drag needs a drag coefficient > 0", nm);
  if (f->buoyancy && !positive(f->density))
    return sw_fail(err, errlen, "fluid '%s': buoyancy needs a density > 0", nm);
  if (!nonneg(f->viscosity) || !nonneg(f->density) || !nonneg(f->drag_coefficient))
    return sw_fail(err, errlen, "fluid '%s': viscosity, density and drag coefficient must be >= 0", nm);
  if (!nonneg(f->body_length)) return sw_fail(err, errlen, "fluid '%s': body length must be >= 0", nm);
  if (!finite3(f->velocity)) return sw_fail(err, errlen, "fluid '%s': flow velocity is not finite", nm);
  return 1;
}

static int check_contact(const swContactDesc *c, int nrod, char *err, size_t errlen) {
  const char *nm = c->name;
  if (!check_rods("contact", nm, c->nrods, c->rods, nrod, err, errlen)) return 0;
  if (!positive(c->stiffness)) return sw_fail(err, errlen, "contact '%s': stiffness must be > 0", nm);
  if (!nonneg(c->damping)) return sw_fail(err, errlen, "contact '%s': damping must be >= 0", nm);
  if (c->self != 0 && c->self != 1)
    return sw_fail(err, errlen, "contact '%s': self must be 0 or 1, got %d", nm, c->self);
  if (!c->self && c->nrods == 1)
    return sw_fail(err, errlen, "contact '%s': one rod and no self-contact: nothing can touch", nm);
  if (!nonneg(c->static_friction) || !nonneg(c->kinetic_friction))
    return sw_fail(err, errlen, "contact '%s': friction coefficients must be >= 0", nm);
  if (c->kinetic_friction > c->static_friction)
    return sw_fail(err, errlen, "contact '%s': kinetic friction %g exceeds static friction %g", nm,
                   c->kinetic_friction, c->static_friction);
  if (!nonneg(c->tangential_stiffness))
    return sw_fail(err, errlen, "contact '%s': tangential stiffness must be >= 0", nm);
  return 1;
}

static int check_obstacle(const swObstacleDesc *o, int nrod, char *err, size_t errlen) {
  const char *nm = o->name;
  if (!check_rods("obstacle", nm, o->nrods, o->rods, nrod, err, errlen)) return 0;
  if (o->shape < SW_OBSTACLE_SPHERE || o->shape > SW_OBSTACLE_ELLIPSOID)
    return sw_fail(err, errlen, "obstacle '%s': unknown shape %d", nm, (int)o->shape);
  if (!finite3(o->centre)) return sw_fail(err, errlen, "obstacle '%s': centre is not finite", nm);
  if (!finite3(o->axis) || !(sw_v3_norm(o->axis) > 0))
    return sw_fail(err, errlen, "obstacle '%s': axis must be a nonzero vector", nm);
  if (!finite3(o->normal) || !(sw_v3_norm(o->normal) > 0))
    return sw_fail(err, errlen, "obstacle '%s': normal must be a nonzero vector", nm);
  const int round = o->shape <= SW_OBSTACLE_CYLINDER;
  if (round && !positive(o->radius)) return sw_fail(err, errlen, "obstacle '%s': radius must be > 0", nm);
  if (o->shape == SW_OBSTACLE_CAPSULE && !nonneg(o->length))
    return sw_fail(err, errlen, "obstacle '%s': length must be >= 0", nm);
  if (!round && !(positive(o->half[0]) && positive(o->half[1]) && positive(o->half[2])))
    return sw_fail(err, errlen, "obstacle '%s': its three half sizes must be > 0", nm);
  if (!positive(o->stiffness)) return sw_fail(err, errlen, "obstacle '%s': stiffness must be > 0", nm);
  if (!nonneg(o->damping)) return sw_fail(err, errlen, "obstacle '%s': damping must be >= 0", nm);
  if (!nonneg(o->static_friction) || !nonneg(o->kinetic_friction))
    return sw_fail(err, errlen, "obstacle '%s': friction coefficients must be >= 0", nm);
  if (o->kinetic_friction > o->static_friction)
    return sw_fail(err, errlen, "obstacle '%s': kinetic friction %g exceeds static friction %g", nm,
                   o->kinetic_friction, o->static_friction);
  if (!nonneg(o->tangential_stiffness))
    return sw_fail(err, errlen, "obstacle '%s': tangential stiffness must be >= 0", nm);
  if (o->carrier_rod >= nrod || o->carrier_rod < -1)
    return sw_fail(err, errlen, "obstacle '%s': carrier rod %d does not exist (the scene has %d)", nm,
                   o->carrier_rod, nrod);
  return 1;
}

static int check_wave(const swWaveDesc *w, int nrod, char *err, size_t errlen) {
  const char *nm = w->name;
  if (w->rod < 0 || w->rod >= nrod)
    return sw_fail(err, errlen, "torque wave '%s': rod %d does not exist (the scene has %d)", nm,
                w->rod, nrod);
  if (w->ncoef < 4 || w->ncoef > SW_WAVE_MAXCOEF)
    return sw_fail(err, errlen, "torque wave '%s': %d B-spline coefficients; a cubic B-spline needs "
                "4 to %d", nm, w->ncoef, SW_WAVE_MAXCOEF);
  for (int k = 0; k < w->ncoef; k++)
    if (!isfinite(w->coef[k]))
      return sw_fail(err, errlen, "torque wave '%s': coefficient %d is not finite", nm, k);
  if (!positive(w->wavelength)) return sw_fail(err, errlen, "torque wave '%s': wavelength must be > 0", nm);
  if (!positive(w->period)) return sw_fail(err, errlen, "torque wave '%s': period must be > 0", nm);
  if (!isfinite(w->phase)) return sw_fail(err, errlen, "torque wave '%s': phase is not finite", nm);
  if (!nonneg(w->ramp)) return sw_fail(err, errlen, "torque wave '%s': ramp time must be >= 0", nm);
  if (!finite3(w->direction) || !(sw_v3_norm(w->direction) > 0))
    return sw_fail(err, errlen, "torque wave '%s': direction must be a nonzero vector", nm);
  return 1;
}

static int check_probe(const swProbeDesc *p, int nrod, char *err, size_t errlen) {
  const char *nm = p->name;
  if (p->kind == SW_PROBE_NODE) {
    if (p->rod < 0 || p->rod >= nrod)
      return sw_fail(err, errlen, "probe '%s': rod %d does not exist (the scene has %d)", nm, p->rod,
                  nrod);
    return 1;
  }
  if (p->kind != SW_PROBE_COM && p->kind != SW_PROBE_COM_VELOCITY &&
      p->kind != SW_PROBE_MEAN_VELOCITY)
    return sw_fail(err, errlen, "probe '%s': unknown kind %d", nm, (int)p->kind);
  if (!nonneg(p->window)) return sw_fail(err, errlen, "probe '%s': window must be >= 0", nm);
  return check_rods("probe", nm, p->nrods, p->rods, nrod, err, errlen);
}

int sw_env_check(const swEnvSpec *e, int nrod, char *err, size_t errlen) {
  if (!e) return 1;
  for (int k = 0; k < e->nground; k++)
    if (!check_ground(&e->ground[k], nrod, err, errlen)) return 0;
  for (int k = 0; k < e->nfluid; k++)
    if (!check_fluid(&e->fluid[k], nrod, err, errlen)) return 0;
  for (int k = 0; k < e->ncontact; k++)
    if (!check_contact(&e->contact[k], nrod, err, errlen)) return 0;
  for (int k = 0; k < e->nwave; k++)
    if (!check_wave(&e->wave[k], nrod, err, errlen)) return 0;
  for (int k = 0; k < e->nprobe; k++)
    if (!check_probe(&e->probe[k], nrod, err, errlen)) return 0;
  for (int k = 0; k < e->nobstacle; k++)
    if (!check_obstacle(&e->obstacle[k], nrod, err, errlen)) return 0;
  return 1;
}

/* ---- compilation into the model ---- */

/* The model's own copy of a name and rod list, "all" expanded. */
static int resolve(const char **name, const int **rods, int *nrods, int nrod) {
  char *nm = strdup(*name);
  int n = *nrods > 0 ? *nrods : nrod;
  int *list = malloc(sizeof(int) * (size_t)(n ? n : 1));
  if (!nm || !list) {
    free(nm);
    free(list);
    *name = NULL;
    *rods = NULL;
    *nrods = 0;
    return 0;
  }
  for (int k = 0; k < n; k++) list[k] = *nrods > 0 ? (*rods)[k] : k;
  *name = nm;
  *rods = list;
  *nrods = n;
  return 1;
}

int sw_env_setup(swModel *m, const swEnvSpec *e, char *err, size_t errlen) {
  int ng = e ? e->nground : 0, nf = e ? e->nfluid : 0, nc = e ? e->ncontact : 0;
  int nw = e ? e->nwave : 0, np = e ? e->nprobe : 0, no = e ? e->nobstacle : 0;
  m->ground = calloc((size_t)(ng ? ng : 1), sizeof *m->ground);
  m->fluid = calloc((size_t)(nf ? nf : 1), sizeof *m->fluid);
  m->contact = calloc((size_t)(nc ? nc : 1), sizeof *m->contact);
  m->wave = calloc((size_t)(nw ? nw : 1), sizeof *m->wave);
  m->probe = calloc((size_t)(np ? np : 1), sizeof *m->probe);
  m->obstacle = calloc((size_t)(no ? no : 1), sizeof *m->obstacle);
  if (!m->ground || !m->fluid || !m->contact || !m->wave || !m->probe || !m->obstacle) goto oom;
  for (int k = 0; k < ng; k++) {
    m->ground[k] = e->ground[k];
    if (!resolve(&m->ground[k].name, &m->ground[k].rods, &m->ground[k].nrods, m->nrod)) goto oom;
    m->nground = k + 1; /* owned by the model from here on */
  }
  for (int k = 0; k < nf; k++) {
    m->fluid[k] = e->fluid[k];
    if (!resolve(&m->fluid[k].name, &m->fluid[k].rods, &m->fluid[k].nrods, m->nrod)) goto oom;
    m->nfluid = k + 1;
  }
  for (int k = 0; k < nc; k++) {
    m->contact[k] = e->contact[k];
    if (!resolve(&m->contact[k].name, &m->contact[k].rods, &m->contact[k].nrods, m->nrod)) goto oom;
    m->ncontact = k + 1;
  }
  for (int k = 0; k < nw; k++) {
    m->wave[k] = e->wave[k];
    if (!(m->wave[k].name = strdup(e->wave[k].name))) goto oom;
    m->nwave = k + 1;
  }
  for (int k = 0; k < np; k++) {
    m->probe[k] = e->probe[k];
    if (!resolve(&m->probe[k].name, &m->probe[k].rods, &m->probe[k].nrods, m->nrod)) goto oom;
    m->nprobe = k + 1;
    if (m->probe[k].kind == SW_PROBE_NODE) {
      const int n = m->rod_nelem[m->probe[k].rod], node = m->probe[k].node;
      if (node < -1 || node > n)
        return sw_fail(err, errlen, "probe '%s': node %d out of range for rod '%s' (nodes 0..%d, "
                    "-1 = last)", m->probe[k].name, node, m->rod_name[m->probe[k].rod], n);
      if (node < 0) m->probe[k].node = n;
    }
  }
  for (int k = 0; k < no; k++) {
    m->obstacle[k] = e->obstacle[k];
    if (!resolve(&m->obstacle[k].name, &m->obstacle[k].rods, &m->obstacle[k].nrods, m->nrod)) goto oom;
    m->nobstacle = k + 1;
    const int r = m->obstacle[k].carrier_rod, node = m->obstacle[k].carrier_node;
    if (r >= 0 && (node < -1 || node > m->rod_nelem[r]))
      return sw_fail(err, errlen, "obstacle '%s': carrier node %d out of range for rod '%s' (nodes "
                     "0..%d, -1 = last)", m->obstacle[k].name, node, m->rod_name[r], m->rod_nelem[r]);
  }
  /* each kind's derived data */
  if (!sw_fluid_setup(m, err, errlen)) return 0;
  sw_ground_setup(m);
  if (!sw_wave_setup(m)) goto oom;
  if (!sw_contact_setup(m)) goto oom;
  if (!sw_obstacle_setup(m)) goto oom;
  return 1;
oom:
  return sw_fail(err, errlen, "out of memory while building the environments");
}

void sw_env_free(swModel *m) {
  sw_fluid_free(m);
  sw_contact_free(m);
  sw_obstacle_free(m);
  for (int k = 0; k < m->nobstacle; k++) disown(m->obstacle[k].name, m->obstacle[k].rods);
  for (int k = 0; k < m->nground; k++) disown(m->ground[k].name, m->ground[k].rods);
  for (int k = 0; k < m->nfluid; k++) disown(m->fluid[k].name, m->fluid[k].rods);
  for (int k = 0; k < m->ncontact; k++) disown(m->contact[k].name, m->contact[k].rods);
  for (int k = 0; k < m->nwave; k++) disown(m->wave[k].name, NULL);
  for (int k = 0; k < m->nprobe; k++) disown(m->probe[k].name, m->probe[k].rods);
  sw_wave_free(m);
  free(m->ground); free(m->fluid); free(m->contact); free(m->wave); free(m->probe);
  free(m->obstacle);
  m->ground = NULL; m->fluid = NULL; m->contact = NULL; m->wave = NULL; m->probe = NULL;
  m->obstacle = NULL;
  m->nground = m->nfluid = m->ncontact = m->nwave = m->nprobe = m->nobstacle = 0;
}

/* ---- dispatch from the step ---- */

/* Loads of the environments, after every other load of this evaluation. */
void sw_env_loads(const swModel *m, swData *d) {
  /* each rod's waves and ground by the thread that owns the rod (its first
   * slot; internal.h), drag by the thread that owns each node (fluid.c),
   * contact, which couples rods, on the leader; waves load elements and the
   * drag nodes, so they need no barrier between them */
  int lo, hi;
  sw_owned_slots(m, d, &lo, &hi);
  if (m->nwave) sw_wave_loads(m, d, lo, hi);
  if (m->nfluid) sw_fluid_loads(m, d, lo, hi);
  if (m->ncontact || m->nobstacle) {
    sw_team_barrier(d);
    if (sw_team_leader(d) && m->ncontact) sw_contact_loads(m, d);
    if (sw_team_leader(d) && m->nobstacle) sw_obstacle_loads(m, d); /* a carrier may be any rod */
    sw_team_barrier(d);
  }
  if (m->nground) { /* last: the ground balances the rest */
    /* a rod's ground loads go onto all its nodes, some another thread's,
     * whose drag must be in first: the one-thread order, and the total the
     * ground reads (without this barrier they raced) */
    if (m->nfluid) sw_team_barrier(d);
    sw_ground_loads(m, d, lo, hi);
  }
}

/* Energy stored in environment springs (contact and ground penalties), J. */
double sw_env_energy(const swModel *m, const swData *d) {
  double energy = 0.0;
  if (m->nground) energy += sw_ground_energy(m, d);
  if (m->ncontact) energy += sw_contact_energy(m, d);
  if (m->nobstacle) energy += sw_obstacle_energy(m, d);
  return energy;
}

/* The smallest step limit of the environments, s (INFINITY: none). */
double sw_env_stable_dt(const swModel *m) {
  double dt = INFINITY;
  if (m->nfluid) dt = fmin(dt, sw_fluid_stable_dt(m));
  if (m->nground) dt = fmin(dt, sw_ground_stable_dt(m));
  if (m->ncontact) dt = fmin(dt, sw_contact_stable_dt(m));
  if (m->nobstacle) dt = fmin(dt, sw_obstacle_stable_dt(m));
  return dt;
}

/* The state's scratch of contact and obstacles (sw_data_new). */
int sw_env_data_new(const swModel *m, swData *d) {
  return sw_contact_data_new(m, d) && sw_obstacle_data_new(m, d);
}
