/* model.h — what the files of a model's life share, and nothing else of the
 * engine: the spec's struct (spec.c builds it, spec_check.c validates it,
 * model.c compiles it), the rods' owned descriptions, and the allocators of
 * the model's and the state's arrays (model.c, data.c).  The rest of the
 * engine reaches the spec through the accessors of internal.h.
 */
#ifndef SW_MODEL_H
#define SW_MODEL_H
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"

struct swSpec {
  int nrod, nload, nbc, njoint;
  int caprod, capload, capbc, capjoint;
  swRodDesc *rod;
  char **rod_name;
  swRodInfo *rod_info;           /* owned copies of rod[k].kind, material, where */
  double **rest_x, **rest_Q;     /* optional rest shapes, per rod */
  double **start_x, **start_Q;   /* optional starting shapes, per rod (NULL: the rest shape) */
  swLoadDesc *load;
  swBCDesc *bc;
  swJointDesc *joint;
  char **joint_name;             /* owned copies of joint[k].name */
  double gravity[3];
  swSignal gravity_signal;       /* scales gravity (sw_spec_set_gravity_signal) */
  int has_gravity_signal;
  double dt;
  swIntegrator integrator;
  swMuscleSpec *muscles;         /* owned by muscle.c */
  const swMuscleOps *muscle_ops; /* set by muscle.c with the first muscle */
  swEnvSpec *env;                /* owned by environment.c */
  const swEnvOps *env_ops;       /* set by environment.c with the first */
  swExpectList expects;          /* owned by expect.c */
  swKinematicDesc *kin;          /* kinematic joints (kinematic.c) */
  char **kin_name;
  int nkin, capkin;
};

/* Owned copies of a rod's kind, material and where (spec.c). */
void sw_rod_info_free(swRodInfo *i);
int sw_rod_info_copy(swRodInfo *to, const char *kind, const char *material, const char *where);

/* The checks sw_compile runs on a spec (spec_check.c): 0 with a message
 * naming the rod, load, condition or joint and the field. */
int sw_check_rod(const swRodDesc *r, char *err, size_t errlen);
int sw_check_loads_bcs(const swSpec *s, char *err, size_t errlen);
int sw_check_joints(const swSpec *s, char *err, size_t errlen);

static inline int sw_finite_pos(double x) { return isfinite(x) && x > 0; }

static inline double *sw_dalloc(size_t n) { return calloc(n ? n : 1, sizeof(double)); }

/* `planes` planes of m->stride doubles, zeroed and 64-byte aligned (the
 * per-slot arrays; sinew.h, "Layout"). */
static inline double *sw_palloc(const swModel *m, int planes) {
  size_t bytes = sizeof(double) * (size_t)planes * (size_t)m->stride;
  double *p = aligned_alloc(64, bytes); /* stride is a multiple of 8 doubles */
  if (p) memset(p, 0, bytes);
  return p;
}

#endif
