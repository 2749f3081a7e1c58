/* internal.h — declarations shared between runtime files but not part of the
 * public interface (generated code never sees them). */
#ifndef SW_INTERNAL_H
#define SW_INTERNAL_H
#include "sinew.h"

/* Shared helpers (model.c): grow an array to hold n+1 items (0: out of
 * memory); write a message into err and return 0. */
int sw_grow(void **p, int *cap, int n, size_t item);
int sw_fail(char *err, size_t errlen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* The rod kernels over a range of elastic slots [lo, hi) (rod.c): the
 * element and Voronoi pass, then the gather of their neighbours' terms. */
void sw_rod_pass(const swModel *m, swData *d, int lo, int hi);
void sw_rod_gather(const swModel *m, swData *d, int lo, int hi);
void sw_bc_kick(const swModel *m, swData *d, double h, double t);     /* boundary.c  */
void sw_bc_loads(const swModel *m, swData *d);                        /* boundary.c  */
double sw_bc_energy(const swModel *m, const swData *d);               /* boundary.c  */
/* Largest h * omega for which the integrator is stable on the damped
 * oscillator x'' = -omega^2 x - c x', as a function of zeta = c / (2 omega). */
double sw_integrator_stability_limit(swIntegrator integ, double zeta); /* stability.c */
/* Joints (joint.c).  sw_joint_setup resolves the defaults and the rest
 * geometry of m->joint into the joint_* arrays (called by sw_compile after the
 * rods are built); sw_joint_loads adds the joint loads to d->force/d->torque
 * (damping also to ext_force/ext_torque, whose work the kick books);
 * sw_joint_measure refreshes d->joint_force[j] and d->joint_angle[j] for the
 * current state; sw_joint_energy is the energy stored in the joint springs. */
void sw_joint_setup(swModel *m);
void sw_joint_loads(const swModel *m, swData *d);
void sw_joint_measure(const swModel *m, swData *d, int j);
double sw_joint_energy(const swModel *m, const swData *d);
/* Muscles (muscle.c).  The swSpec keeps its muscles in an opaque list that
 * muscle.c owns (sw_spec_muscles gives its slot; model.c frees it with
 * sw_muscle_spec_free); sw_muscle_setup fills the model's muscle and filament
 * arrays after the rods are built (0 and a message on a bad muscle);
 * sw_muscle_reset sets the activations of t = 0; sw_muscle_advance moves the
 * activation dynamics over a step [t, t + h]; sw_muscle_loads adds the
 * filament tensions to d->force and d->ext_force; sw_stable_dt_filament is the
 * step limit of filament f's Hill damping. */
typedef struct swMuscleSpec swMuscleSpec;
swMuscleSpec **sw_spec_muscles(swSpec *s);                            /* model.c */
int sw_spec_nrod(const swSpec *s);                                    /* model.c */
void sw_muscle_spec_free(swMuscleSpec *ms);
int sw_muscle_check(const swMuscleSpec *ms, int nrod, char *err, size_t errlen);
int sw_muscle_setup(swModel *m, const swMuscleSpec *ms, char *err, size_t errlen);
void sw_muscle_free(swModel *m);
void sw_muscle_reset(const swModel *m, swData *d);
void sw_muscle_advance(const swModel *m, swData *d, double t, double h);
void sw_muscle_loads(const swModel *m, swData *d);
double sw_muscle_tension(const swModel *m, int f, double eta, double edot, double a);
double sw_stable_dt_filament(const swModel *m, int f);
/* Rigid rods (rigid.c).  sw_rigid_setup fills the rigid_* arrays of the
 * model (mass, principal inertia, body-frame nodes and element frames; called
 * by sw_compile once the rods, loads and boundary conditions are in);
 * sw_rigid_reset puts the bodies at rest at t = 0; sw_rigid_internal stands
 * for rod.c's kernels on rigid rod r (no internal loads, rest strains);
 * sw_rigid_drift and sw_rigid_kick are the bodies' parts of integrate.c's
 * drift and kick; sw_rigid_stable_dt is body b's own bound (linear damping
 * only) and sw_rigid_joint_dt the bound of all joints on it (stability.c). */
static inline int sw_rod_is_rigid(const swModel *m, int r) {
  return m->nrigid > 0 && m->rod_rigid[r] >= 0;
}
void sw_rigid_setup(swModel *m);
void sw_rigid_reset(const swModel *m, swData *d);
void sw_rigid_internal(const swModel *m, swData *d, int r);
void sw_rigid_drift(const swModel *m, swData *d, double h);
void sw_rigid_kick(const swModel *m, swData *d, double h);
double sw_rigid_stable_dt(const swModel *m, int b);
double sw_rigid_joint_dt(const swModel *m, int b);
/* Environments (environment.c).  The swSpec keeps them in an opaque slot
 * (sw_spec_env); sw_env_check validates them in sw_compile, sw_env_setup
 * puts resolved copies and each kind's derived data in the model, sw_env_free
 * releases them; sw_env_loads adds their loads after all others (integrate.c),
 * sw_env_energy is their stored energy, sw_env_stable_dt their step limit. */
typedef struct swEnvSpec swEnvSpec;
swEnvSpec **sw_spec_env(swSpec *s);                                   /* model.c */
void sw_env_spec_free(swEnvSpec *e);
int sw_env_check(const swEnvSpec *e, int nrod, char *err, size_t errlen);
int sw_env_setup(swModel *m, const swEnvSpec *e, char *err, size_t errlen);
void sw_env_free(swModel *m);
static inline int sw_has_env(const swModel *m) {
  return m->nground + m->nfluid + m->ncontact + m->nwave > 0;
}
void sw_env_loads(const swModel *m, swData *d);
double sw_env_energy(const swModel *m, const swData *d);
double sw_env_stable_dt(const swModel *m);
/* Fluids (fluid.c).  sw_fluid_setup fills the model's fluid_* rows and the
 * Stokes drag's step limit from m->fluid (called by sw_env_setup; 0 and a
 * message naming the fluid and rod when slender-body drag is meaningless);
 * sw_fluid_free releases them; sw_fluid_loads adds drag and buoyancy to
 * d->ext_force and d->force; sw_fluid_stable_dt is the step limit. */
int sw_fluid_setup(swModel *m, char *err, size_t errlen);
void sw_fluid_free(swModel *m);
void sw_fluid_loads(const swModel *m, swData *d);
double sw_fluid_stable_dt(const swModel *m);
/* Grounds and terrains (ground.c).  sw_ground_setup normalises the planes'
 * normals (from sw_env_setup); sw_ground_loads adds the normal response and
 * friction of every ground (its balance, damping and friction also to
 * ext_force/ext_torque), called last by sw_env_loads; sw_ground_energy is the
 * energy of the ground penalties; sw_ground_stable_dt their step limit. */
void sw_ground_setup(swModel *m);
void sw_ground_loads(const swModel *m, swData *d);
double sw_ground_energy(const swModel *m, const swData *d);
double sw_ground_stable_dt(const swModel *m);
/* Torque waves (wave.c): sw_wave_setup fills the wave_* arrays of the model
 * (beta and the wave's phase at every node; 0 when out of memory), called by
 * sw_env_setup; sw_wave_loads adds the couples to d->ext_torque and
 * d->torque, called by sw_env_loads. */
int sw_wave_setup(swModel *m);
void sw_wave_free(swModel *m);
void sw_wave_loads(const swModel *m, swData *d);
/* Probes (probe.c): their samples live in swData (sw_data_new, sw_data_free
 * and sw_reset call these); kind names and units for output and --info. */
int sw_probe_data_new(const swModel *m, swData *d);
void sw_probe_data_free(swData *d);
void sw_probe_reset(const swModel *m, swData *d);
const char *sw_probe_kind_name(swProbeKind kind);
const char *sw_probe_units(swProbeKind kind);
/* Rod-rod contact (contact.c).  sw_contact_setup lists each contact's
 * elements in the model (0: out of memory; from sw_env_setup), sw_contact_free
 * releases them (sw_env_free); sw_contact_data_new/free the hash grid's
 * scratch in the state (sw_data_new/free); sw_contact_loads adds the contact
 * loads (from sw_env_loads), sw_contact_loads_with by the grid or by brute
 * force over all pairs (tests and benchmark); sw_contact_energy is the
 * springs' energy, sw_contact_stable_dt their step limit. */
typedef enum { SW_CONTACT_GRID = 0, SW_CONTACT_BRUTE = 1 } swContactPhase;
int sw_contact_setup(swModel *m);
void sw_contact_free(swModel *m);
int sw_contact_data_new(const swModel *m, swData *d);
void sw_contact_data_free(swData *d);
void sw_contact_loads(const swModel *m, swData *d);
void sw_contact_loads_with(const swModel *m, swData *d, swContactPhase phase);
double sw_contact_energy(const swModel *m, const swData *d);
double sw_contact_stable_dt(const swModel *m);
#endif
