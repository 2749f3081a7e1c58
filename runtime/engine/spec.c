/* spec.c — the scene specification: swSpec, filled one call at a time.
 *
 * Design.  swSpec is a growable list of rod, load, boundary-condition and
 * joint descriptions filled by the caller (the generated simulator or a
 * test); muscles, environments and expectations keep their own lists in it
 * (muscle.c, environment.c, expect.c), reached through the accessors below.
 * The spec copies what it is given (names, a rod's kind, material and where,
 * rest shapes), so the caller's strings may be temporaries.  Nothing is
 * checked here beyond memory: spec_check.c validates the whole scene when
 * sw_compile (model.c) turns it into a model.  The engine's shared helpers
 * sw_grow and sw_fail live here too.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sinew.h"
#include "internal.h"
#include "model.h"

swMuscleSpec **sw_spec_muscles(swSpec *s) { return &s->muscles; }
const swMuscleOps **sw_spec_muscle_ops(swSpec *s) { return &s->muscle_ops; }
swEnvSpec **sw_spec_env(swSpec *s) { return &s->env; }
swExpectList *sw_spec_expects(swSpec *s) { return &s->expects; }
const swEnvOps **sw_spec_env_ops(swSpec *s) { return &s->env_ops; }
int sw_spec_nrod(const swSpec *s) { return s->nrod; }

void sw_rod_info_free(swRodInfo *i) {
  free(i->kind);
  free(i->material);
  free(i->where);
}

/* Owned copies of kind, material and where (each NULL when absent); 0: out
 * of memory. */
int sw_rod_info_copy(swRodInfo *to, const char *kind, const char *material,
                         const char *where) {
  to->kind = kind ? strdup(kind) : NULL;
  to->material = material ? strdup(material) : NULL;
  to->where = where ? strdup(where) : NULL;
  if ((kind && !to->kind) || (material && !to->material) || (where && !to->where)) {
    sw_rod_info_free(to);
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
    sw_rod_info_free(&s->rod_info[r]);
    free(s->rest_x[r]);
    free(s->rest_Q[r]);
    free(s->start_x[r]);
    free(s->start_Q[r]);
  }
  free(s->rod); free(s->rod_name); free(s->rod_info); free(s->rest_x); free(s->rest_Q);
  free(s->start_x); free(s->start_Q);
  for (int k = 0; k < s->njoint; k++) free(s->joint_name[k]);
  free(s->load); free(s->bc); free(s->joint); free(s->joint_name);
  if (s->muscle_ops) s->muscle_ops->free_spec(s->muscles);
  if (s->env_ops) s->env_ops->free_spec(s->env);
  sw_expect_list_free(&s->expects);
  sw_kinematic_spec_free(s);
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
  r->swell_radius = sw_signal_const(0.01);
  r->swell_curvature = sw_signal_const(1.0);
  r->swell_twist = sw_signal_const(1.0);
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
  cap = s->caprod;
  if (!sw_grow((void **)&s->start_x, &cap, s->nrod, sizeof *s->start_x)) return -1;
  cap = s->caprod;
  if (!sw_grow((void **)&s->start_Q, &cap, s->nrod, sizeof *s->start_Q)) return -1;
  if (!sw_grow((void **)&s->rest_Q, &s->caprod, s->nrod, sizeof *s->rest_Q)) return -1;
  int id = s->nrod++;
  s->rod[id] = *r;
  s->rod_name[id] = strdup(r->name ? r->name : "rod");
  s->rod[id].name = s->rod_name[id];
  int copied = sw_rod_info_copy(&s->rod_info[id], r->kind, r->material, r->where);
  s->rod[id].kind = s->rod_info[id].kind;
  s->rod[id].material = s->rod_info[id].material;
  s->rod[id].where = s->rod_info[id].where;
  s->rest_x[id] = s->rest_Q[id] = NULL;
  s->start_x[id] = s->start_Q[id] = NULL;
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
void sw_spec_set_gravity_signal(swSpec *s, swSignal signal) {
  s->gravity_signal = signal;
  s->has_gravity_signal = 1;
}
void sw_spec_set_integrator(swSpec *s, swIntegrator integ) { s->integrator = integ; }
void sw_spec_set_dt(swSpec *s, double dt) { s->dt = dt; }

/* A shape of rod `rod` into *px, *pQ (owned copies): (n+1) nodes, n frames. */
static int set_shape(swSpec *s, int rod, const double *x, const double *Q, double **px,
                     double **pQ) {
  int n = s->rod[rod].nelem;
  if (n < 1) return SW_EMODEL;
  free(*px);
  free(*pQ);
  *px = malloc(sizeof(double) * 3 * (size_t)(n + 1));
  *pQ = malloc(sizeof(double) * 9 * (size_t)n);
  if (!*px || !*pQ) return SW_EMODEL;
  memcpy(*px, x, sizeof(double) * 3 * (size_t)(n + 1));
  memcpy(*pQ, Q, sizeof(double) * 9 * (size_t)n);
  return SW_OK;
}

int sw_spec_set_rest_shape(swSpec *s, int rod, const double *x, const double *Q) {
  if (rod < 0 || rod >= s->nrod) return SW_EUSAGE;
  return set_shape(s, rod, x, Q, &s->rest_x[rod], &s->rest_Q[rod]);
}

int sw_spec_set_start_shape(swSpec *s, int rod, const double *x, const double *Q) {
  if (rod < 0 || rod >= s->nrod) return SW_EUSAGE;
  return set_shape(s, rod, x, Q, &s->start_x[rod], &s->start_Q[rod]);
}

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
