/* internal.h — declarations shared between runtime files but not part of the
 * public interface (generated code never sees them). */
#ifndef SW_INTERNAL_H
#define SW_INTERNAL_H
#include <omp.h>
#include <stdatomic.h>
#include "sinew.h"

/* Shared helpers (spec.c): grow an array to hold n+1 items (0: out of
 * memory); write a message into err and return 0. */
int sw_grow(void **p, int *cap, int n, size_t item);
int sw_fail(char *err, size_t errlen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Expectations (expect.c): the spec's list (kept in swSpec by spec.c), the
 * model's copies, and the run loop's hooks: sw_expect_next is the first step
 * after `step` at which one is sampled (LONG_MAX: none), sw_expect_sample
 * samples those due at d->step. */
typedef struct { swExpectDesc *item; int n, cap; } swExpectList;
swExpectList *sw_spec_expects(swSpec *s);                                   /* spec.c */
void sw_expect_list_free(swExpectList *l);
int sw_expect_setup(swModel *m, const swExpectList *l, char *err, size_t errlen);
void sw_expect_free(swModel *m);
long sw_expect_next(const swModel *m, long step);
/* The running state of the expectations (SW_EXPECT_SAVED doubles each:
 * samples, last step, minimum, maximum, last value, trapezoidal sum), for
 * the checkpoint (restart.c); r may be NULL (save writes zeros, load does
 * nothing). */
#define SW_EXPECT_SAVED 6
void sw_expect_run_save(const swModel *m, const swExpectRun *r, double *out);
void sw_expect_run_load(const swModel *m, swExpectRun *r, const double *in);
void sw_expect_sample(const swModel *m, swData *d, swExpectRun *r);
/* At a held step (integrate.c), when sw_expect_held_ok: the entries due
 * sampled from the held state as the whole step would show them (probe.c,
 * "Read at a held step"), without sw_whole_begin. */
int sw_expect_held_ok(const swModel *m);
void sw_expect_sample_held(const swModel *m, swData *d, swExpectRun *r);
int sw_probe_held_ok(const swModel *m, int p);                              /* probe.c */
void sw_probe_measure_held(const swModel *m, const swData *d, int p, double out[3]);
/* The values of the objective's reductions (the entries with `reduce`, in
 * order) into R; SW_OK, or SW_EUSAGE with the reason in why when one was
 * not reached.  sw_expect_reduced_last: the last step any of them samples. */
int sw_expect_reduced(const swModel *m, const swExpectRun *r, double *R, char *why, size_t len);
long sw_expect_reduced_last(const swModel *m);
/* Threads (integrate.c).  A step on more than one thread runs inside one
 * OpenMP parallel region that sw_steps opens, and every function of the step
 * is entered by all threads of the team.  Loops over slots are cut into the
 * model's chunks of m->chunk slots; SW_FOR_CHUNKS runs this thread's share of
 * them (contiguous, by rank), and sw_team_barrier() is where a phase waits for
 * the others.  Parts that are not split run on the leader (rank 0) and end in
 * a barrier.  Outside a parallel region the team is the caller alone: all
 * chunks are its share, the barrier is a test of d->team_size, and no OpenMP
 * construct runs, so a one-thread run pays nothing for the threads (the
 * same code also serves the set-up and the diagnostics).  Chunks depend on the model only,
 * and so does every partial sum: results are the same bits for any team. */
/* The team's barrier (d->team): a counter and a generation, each on its own
 * cache line.  The last thread to arrive resets the counter and opens the
 * next generation; the others spin on the generation, with a pause, and
 * after a while also yield the processor, so a team larger than the machine
 * still makes progress.  It costs about a fifth of libgomp's barrier on this
 * machine's two cores (docs/performance.md), which matters at a dozen
 * barriers in a step of a few microseconds. */
typedef struct {
  _Alignas(64) atomic_int count;
  _Alignas(64) atomic_int generation;
} swTeam;
void sw_team_wait(swTeam *t, int size); /* integrate.c */
size_t sw_hold_size(const swModel *m); /* integrate.c: doubles of swData.hold */
static inline int sw_team_rank(const swData *d) { return d->team_size > 1 ? omp_get_thread_num() : 0; }
static inline int sw_team_leader(const swData *d) { return sw_team_rank(d) == 0; }
static inline void sw_team_barrier(swData *d) {
  if (d->team_size > 1) sw_team_wait((swTeam *)d->team, d->team_size);
}
/* First and end of this thread's share of n items. */
static inline int sw_share_lo(const swData *d, int n) {
  return d->team_size > 1 ? (int)((long)n * sw_team_rank(d) / d->team_size) : 0;
}
static inline int sw_share_hi(const swData *d, int n) {
  return d->team_size > 1 ? (int)((long)n * (sw_team_rank(d) + 1) / d->team_size) : n;
}
static inline int sw_nchunk(const swModel *m, int n) { return (n + m->chunk - 1) / m->chunk; }
static inline int sw_chunk_lo(const swModel *m, int c) { return c * m->chunk; }
static inline int sw_chunk_hi(const swModel *m, int c, int n) {
  const int hi = (c + 1) * m->chunk;
  return hi < n ? hi : n;
}
/* The slots this thread owns: its share of the chunks of the elastic slots,
 * the last thread also the rigid slots and the padding.  Loads that land on
 * scattered slots (joints, boundary conditions, muscles, each rod's waves,
 * drag and ground) are added by the owner of each slot (or of the rod's first
 * slot), so no slot has two writers and each slot gets its loads in the
 * order of the one-thread code. */
static inline void sw_owned_slots(const swModel *m, const swData *d, int *lo, int *hi) {
  if (d->team_size <= 1) {
    *lo = 0, *hi = m->stride;
    return;
  }
  const int n = m->nslot_elastic, nc = sw_nchunk(m, n), rank = sw_team_rank(d);
  const int c0 = sw_share_lo(d, nc), c1 = sw_share_hi(d, nc);
  *lo = rank == 0 ? 0 : sw_chunk_lo(m, c0);
  *hi = rank == d->team_size - 1 ? m->stride : c1 > c0 ? sw_chunk_hi(m, c1 - 1, n) : *lo;
}
/* This thread's share of the slots [0, n), the chunks of its share as one
 * range (empty when lo == hi): kernels whose results do not depend on how
 * the range is cut (no sums) take it in one call, which saves the set-up of
 * their vector loops per chunk. */
static inline void sw_share_slots(const swModel *m, const swData *d, int n, int *lo, int *hi) {
  const int nc = sw_nchunk(m, n), c0 = sw_share_lo(d, nc), c1 = sw_share_hi(d, nc);
  *lo = c1 > c0 ? sw_chunk_lo(m, c0) : 0;
  *hi = c1 > c0 ? sw_chunk_hi(m, c1 - 1, n) : 0;
}
/* for (c in this thread's chunks of slots [0, n)): kernels with sums */
#define SW_FOR_CHUNKS(m, d, c, n) \
  for (int c##_all = sw_nchunk(m, n), c = sw_share_lo(d, c##_all), c##_end = sw_share_hi(d, c##_all); \
       c < c##_end; c++)
/* doubles per joint in d->joint_scratch (joint.c) */
#define SW_JOINT_ROW 18
/* Scratch windows.  The step's scratch arrays (the strains, couples and
 * flags of rod.c, the loads, the drift's rotations) are planes of m->stride
 * like the state.  The kernels below that take `so` (scratch origin) find
 * slot i of a scratch plane at index i - so, and of a state or model plane
 * at i.  The phased step and the diagnostics pass so = 0 and use the planes
 * whole.  The fused sweep (integrate.c) passes so = b - 1 for its block of
 * slots [b, e), so that every block reuses the first entries of the
 * scratch planes, which stay in the cache, instead of streaming whole
 * planes through memory (index 0 holds the slot before the block). */
/* The rod kernels over a range of elastic slots [lo, hi) (rod.c): the
 * element and Voronoi pass (bent domains flagged in flag[i - so]), then the
 * gather of their neighbours' terms. */
void sw_rod_pass(const swModel *m, swData *d, int lo, int hi, int so, double *flag);
void sw_rod_gather(const swModel *m, swData *d, int lo, int hi, int so);
/* Whether a one-thread Verlet step of the model runs its kick and drift as
 * one sweep over the slots (integrate.c): more slots than a block, and no
 * load that reaches beyond a slot's neighbours (joints, muscles,
 * environments) or off the slots (rigid bodies). */
int sw_sweep_fits(const swModel *m);
/* Gravity, point loads and linear damping on slots [lo, hi), added into the
 * totals (loads.c; sw_external_loads takes the thread's owned slots). */
void sw_external_loads_slots(const swModel *m, swData *d, int lo, int hi, int so);
/* Boundary conditions (boundary.c), each applied by the thread that owns
 * its end (slots [lo, hi)); the kick's work of condition k into work[k]. */
void sw_bc_kick(const swModel *m, swData *d, double h, double t, int lo, int hi, int so, double *work);
void sw_bc_loads(const swModel *m, swData *d, int lo, int hi, int so);
/* Whether a condition lets its end go at a kick whose loads are those of
 * time t, and the release itself (on one thread: it books the work). */
int sw_bc_release_due(const swModel *m, const swData *d, double t);
void sw_bc_release(const swModel *m, swData *d, double t);

/* The dilatation that divides element e's rotational inertia: J^ / e on
 * Gazzola's rods, J^ alone on variational ones (rod.c, Simo's kinetic
 * energy). */
static inline double sw_inertia_dilatation(const swModel *m, const swData *d, int e) {
  return m->nvariational && m->elem_variational[e] != 0.0 ? 1.0 : d->dilatation[e];
}
/* The slot of the end node a condition holds. */
static inline int sw_bc_node(const swModel *m, const swBCDesc *b) {
  return m->node_adr[b->rod] + (b->end ? m->rod_nelem[b->rod] : 0);
}
double sw_bc_energy(const swModel *m, const swData *d);               /* boundary.c  */
/* Largest h * omega for which the integrator is stable on the damped
 * oscillator x'' = -omega^2 x - c x', as a function of zeta = c / (2 omega). */
double sw_integrator_stability_limit(swIntegrator integ, double zeta); /* stability.c */
/* sw_check_finite on the rigid rods alone (rigid_only) or on all (stability.c). */
int sw_check_rods(const swModel *m, swData *d, int rigid_only);
/* How many elastic slots of [lo, hi) sw_check_finite would flag; records
 * each element's shortest (d->shortest) on the way. */
int sw_check_slots(const swModel *m, swData *d, int lo, int hi);  /* stability.c */
/* The stable step of elastic rod r's elasticity (its zig-zag bound, as
 * sw_stable_dt_rod's without the filaments' and rings' terms) with every
 * element at dilatation e and every Voronoi domain at eps, under the rod's
 * law: what the report of an unstable run quotes for a shortened rod. */
double sw_stable_dt_rod_at(const swModel *m, int r, double e, double eps);  /* stability.c */
/* Joints (joint.c).  sw_joint_setup resolves the defaults and the rest
 * geometry of m->joint into the joint_* arrays (called by sw_compile after the
 * rods are built); sw_joint_rows and sw_joint_apply add the joint loads to d->force/d->torque
 * (damping also to ext_force/ext_torque, whose work the kick books);
 * sw_joint_measure refreshes d->joint_force[j] and d->joint_angle[j] for the
 * current state; sw_joint_energy is the energy stored in the joint springs. */
/* Kinematic joints (kinematic.c): the follower frames imposed before every
 * load evaluation, then their loads (both on the team's leader). */
int sw_kinematic_check(const struct swSpec *s, char *err, size_t errlen);
int sw_kinematic_setup(swModel *m, const struct swSpec *s);
void sw_kinematic_free(swModel *m);
void sw_kinematic_spec_free(struct swSpec *s);
void sw_kinematic_impose(const swModel *m, swData *d);
void sw_kinematic_book(const swModel *m, swData *d); /* after the rod pass: the corrections' energy */
void sw_kinematic_follow(const swModel *m, swData *d);
void sw_kinematic_loads(const swModel *m, swData *d);
/* rigidity.c: each elastic rod's largest strain and bend over the frames */
void sw_rigidity_reset(const swModel *m, swData *d);
void sw_rigidity_sample(const swModel *m, swData *d);
double sw_stable_dt_kinematic(const swModel *m, int j);              /* stability.c */
void sw_joint_setup(swModel *m);
void sw_joint_rows(const swModel *m, swData *d);  /* each joint's loads, from the state */
void sw_joint_apply(const swModel *m, swData *d); /* the rows into this thread's slots */
void sw_joint_measure(const swModel *m, swData *d, int j);
double sw_joint_energy(const swModel *m, const swData *d);
/* Limits (joint.c, "Limits"): whether joint j has one; the stiffness and
 * damping that bound its elements' rotation (the larger of the joint's own
 * and its limit's, which act about different directions); the direction g
 * of a limit in violation, for rigid_joint.c's tangent (0: inside). */
int sw_joint_limited(const swJointDesc *jd);
/* A joint whose point on side a is off node a, on an arm (joint.c). */
static inline int sw_joint_has_arm(const swJointDesc *jd) {
  return jd->arm_a[0] != 0 || jd->arm_a[1] != 0 || jd->arm_a[2] != 0;
}
double sw_joint_rot_bound_stiffness(const swJointDesc *jd);
double sw_joint_rot_bound_damping(const swJointDesc *jd);
int sw_joint_limit_tangent(const swModel *m, const swData *d, int j, double *g);
/* Muscles (muscle.c).  The swSpec keeps its muscles in an opaque list that
 * muscle.c owns (sw_spec_muscles gives its slot; spec.c frees it with
 * sw_muscle_spec_free); sw_muscle_setup fills the model's muscle and filament
 * arrays after the rods are built (0 and a message on a bad muscle);
 * sw_muscle_reset sets the activations of t = 0; sw_muscle_advance moves the
 * activation dynamics over a step [t, t + h]; sw_muscle_loads adds the
 * filament tensions to d->force and d->ext_force; sw_stable_dt_filament is the
 * step limit of filament f's Hill damping. */
typedef struct swMuscleSpec swMuscleSpec;
/* What the rest of the runtime calls of muscle.c, reached through the spec
 * (set by sw_spec_add_muscle) and the model (m->muscle_ops), never by name:
 * a static simulator then links muscle.o only when its scene adds a muscle,
 * so a scene without muscles carries no muscle code. */
typedef struct {
  int (*check)(const swMuscleSpec *ms, int nrod, char *err, size_t errlen);
  int (*setup)(swModel *m, const swMuscleSpec *ms, char *err, size_t errlen);
  void (*free_model)(swModel *m);
  void (*free_spec)(swMuscleSpec *ms);
  void (*reset)(const swModel *m, swData *d);
  void (*advance)(const swModel *m, swData *d, double t, double h);
  void (*loads)(const swModel *m, swData *d); /* the three parts, with barriers */
  void (*rates)(const swModel *m, swData *d);    /* the parts, on a thread's slots: */
  void (*tensions)(const swModel *m, swData *d, double h); /* after the rod pass, then after */
  void (*pull)(const swModel *m, swData *d);     /*   a barrier each               */
  double (*stable_dt_filament)(const swModel *m, int f);
  /* a muscle's tension (its filaments' sum) and stretch (their end-to-end
   * length over rest length, averaged by area), for the output and expect.c */
  double (*force)(const swModel *m, const swData *d, int mu);
  double (*stretch)(const swModel *m, const swData *d, int mu);
  /* the via rings' loads (muscle_via.c) into this thread's slots: in the
   * tensions' phase, before an implicit filament reads its loads */
  void (*rings)(const swModel *m, swData *d);
  /* a filament in the joints' system (m->fil_system): its tension from its
   * end nodes' velocity changes (NULL: held), the pull on its other nodes
   * adjusted to it and its via rings' force changes computed, which
   * rigid_joint.c adds (after the system's solve) */
  void (*system_tension)(const swModel *m, swData *d, int f, const double *dv_start,
                         const double *dv_end);
} swMuscleOps;
static inline const swMuscleOps *sw_muscle_ops(const swModel *m) {
  return (const swMuscleOps *)m->muscle_ops;
}
swMuscleSpec **sw_spec_muscles(swSpec *s);                            /* spec.c */
const swMuscleOps **sw_spec_muscle_ops(swSpec *s);                    /* spec.c */
int sw_spec_nrod(const swSpec *s);                                    /* spec.c */
void sw_muscle_spec_free(swMuscleSpec *ms);
int sw_muscle_check(const swMuscleSpec *ms, int nrod, char *err, size_t errlen);
int sw_muscle_setup(swModel *m, const swMuscleSpec *ms, char *err, size_t errlen);
void sw_muscle_free(swModel *m);
void sw_muscle_reset(const swModel *m, swData *d);
void sw_muscle_advance(const swModel *m, swData *d, double t, double h);
void sw_muscle_loads(const swModel *m, swData *d);
double sw_muscle_tension(const swModel *m, int f, double eta, double edot, double a);
double sw_stable_dt_filament(const swModel *m, int f);
/* The Hill damping under imex (muscle_implicit.c): the law's slope
 * dT/d(edot); filament f's tension over a kick h from its tension T0
 * without it; and for a filament in the joints' system (m->fil_system) the
 * part without its ends, then, after the system's solve, its tension from
 * the ends' velocity changes (NULL: clamped). */
double sw_muscle_tension_slope(const swModel *m, int f, double eta, double edot, double a);
double sw_muscle_implicit_tension(const swModel *m, swData *d, int f, double T0, double eta,
                                  double edot, double h);
double sw_muscle_system_part(const swModel *m, swData *d, int f, double T0, double eta, double edot,
                             double h);
void sw_muscle_system_tension(const swModel *m, swData *d, int f, const double *dv_start,
                              const double *dv_end);
/* Via points (muscle_via.c, for muscle.c): the checks of a description's
 * via points; the rest length of its path; the filament laid along it (x:
 * (n+1)*3 nodes, Q: n*9 frames, d1 from `normal`; 0 if the elements do not
 * add up); ring q (via point k of filament f) resolved on the compiled
 * model; the rings' rows of filament f from the state (SW_RING_ROW doubles
 * each in d->ring_row) and the rows into slots [lo, hi); the rows' contact
 * search reset; the rings' step bound; the path length now. */
/* The rod of element slot e (a real element; 0 otherwise).  Rods' slots
 * are not in rod order (elastic rods come first, sinew.h "Layout"), so each
 * rod's range is tested. */
static inline int sw_rod_of_elem(const swModel *m, int e) {
  for (int r = 0; r < m->nrod; r++)
    if (m->elem_adr[r] <= e && e < m->elem_adr[r] + m->rod_nelem[r]) return r;
  return 0;
}
#define SW_RING_ROW 8
int sw_via_check(const swMuscleDesc *md, int nrod, char *err, size_t errlen);
double sw_via_path_rest(const swMuscleDesc *md);
int sw_via_lay(const swMuscleDesc *md, const double *normal, double *x, double *Q);
void sw_via_setup_ring(swModel *m, int q, const swMuscleDesc *md, int k, int f);
void sw_via_rows(const swModel *m, swData *d, int f);
void sw_via_apply(const swModel *m, swData *d, int lo, int hi);
void sw_via_add(const swModel *m, swData *d, int f, int q, const double *F, int lo, int hi);
void sw_via_contact(const swModel *m, const swData *d, int f, int q, int *a, double *s, double *tau);
/* The rings of an implicit filament under imex (via_implicit.c): whether
 * ring q of filament f is one; the Hill solve's sums p and s of filament f
 * taken through its rings over a kick h (each ring's part stored in
 * d->ring_imp, SW_RING_IMP doubles, for this evaluation); the rings' force
 * changes at the tension T; their rows cleared before an evaluation; the
 * changes into slots [lo, hi). */
#define SW_RING_IMP 14
int sw_via_ring_implicit(const swModel *m, int f, int q);
void sw_via_implicit_sums(const swModel *m, swData *d, int f, double h, double *p, double *s);
void sw_via_implicit_force(const swModel *m, swData *d, int f, double T);
void sw_via_implicit_clear(const swModel *m, swData *d, int f);
void sw_via_implicit_add(const swModel *m, swData *d, int f, int lo, int hi);
void sw_via_reset(const swModel *m, swData *d);
double sw_via_stable_dt(const swModel *m, int f);
double sw_via_path(const swModel *m, const swData *d, int f);
/* Implicit rods (rod_implicit.c): sw_implicit_setup marks the elastic
 * rods of wanted[r] != 0 and, when the model's integrator is SW_IMEX, lists
 * them for the implicit kick (0: out of memory); sw_implicit_scratch is the doubles of swData's
 * workspace; sw_implicit_kick, entered by every thread after the kick's
 * loads, replaces those rods' loads by the trapezoidal rule's. */
int sw_implicit_setup(swModel *m, const int *wanted);
void sw_implicit_free(swModel *m);
size_t sw_implicit_scratch(const swModel *m);
void sw_implicit_kick(const swModel *m, swData *d, double h);
/* sw_implicit_reset forgets every kept factorisation (sw_reset). */
void sw_implicit_reset(const swModel *m, swData *d);
/* The bound of rod r's elastic waves on an explicit kick, implicit or not
 * (stability.c). */
double sw_stable_dt_elastic(const swModel *m, int r);
/* The tangent stiffness K of rod r's internal loads in its band (the
 * unknowns v_0, w_0, v_1, ..., v_n; A(i, j), j <= i <= j + SW_IMPLICIT_BAND,
 * at A[i (SW_IMPLICIT_BAND + 1) + SW_IMPLICIT_BAND - (i - j)]), for the tests. */
#define SW_IMPLICIT_BAND 8
void sw_implicit_stiffness(const swModel *m, const swData *d, int r, double *A);
/* Rod r as a member of the joints' system (joint_ports.c): its unknowns
 * (node, element, node, ...); sw_implicit_solve_many factors this kick's
 * system and solves it for the right-hand sides in X (row-major, N rows of
 * ld doubles, ld a multiple of SW_SOLVE_BLOCK, with SW_IMPLICIT_BAND rows
 * of zeros before and after), column 0 overwritten with h F (0: not
 * factored); sw_implicit_apply sets the rod's loads to those that give the
 * velocity changes du (every stride-th double). */
#define SW_SOLVE_BLOCK 8
size_t sw_implicit_unknowns(const swModel *m, int r);
int sw_implicit_solve_many(const swModel *m, swData *d, int r, double h, double *X, int ld);
void sw_implicit_apply(const swModel *m, swData *d, int r, const double *du, size_t stride,
                       double h);
/* Rod r's band as the band path of the joints' system fills it
 * (joint_ports.c, sw_band_group_solve): sw_implicit_band_begin assembles
 * this kick's A = M + h/2 C + h^2/4 K afresh (no kept factorisation: the
 * caller adds to it) and rhs = h F, returns the band (A(i, j) at
 * sw_band_at) and points *rhs at the right-hand side (NULL: r is not an
 * implicit rod); sw_implicit_band_solve factors it and solves it into rhs
 * (0: not positive definite). */
double *sw_implicit_band_begin(const swModel *m, swData *d, int r, double h, double **rhs);
int sw_implicit_band_solve(const swModel *m, swData *d, int r);
/* The same band factored, and solved for rhs (into column 0 of X) and
 * X's other columns at once (X as sw_implicit_solve_many's). */
int sw_implicit_band_solve_many(const swModel *m, swData *d, int r, double *X, int ld);
/* A member's band path keeping its band (rod_implicit.c): this kick's
 * right-hand side h F assembled alone, when the rod's kept factorisation
 * holds (else NULL); the band just factored kept; the right-hand side
 * (with what the caller added) solved with the kept band into column 0 of
 * X, and X's other columns too if all (else left as they are); and element
 * e's frame (slot e) when the band was kept. */
double *sw_implicit_band_kept(const swModel *m, swData *d, int r, double h, double *theta);
void sw_implicit_band_keep(const swModel *m, swData *d, int r, double h);
void sw_implicit_band_solve_kept(const swModel *m, swData *d, int r, double *X, int ld, int all);
void sw_implicit_kept_frame(const swModel *m, const swData *d, int r, int e, double *Q);
static inline double *sw_band_at(double *A, size_t i, size_t j) {
  return A + i * (SW_IMPLICIT_BAND + 1) + SW_IMPLICIT_BAND - (i - j);
}
/* Rigid rods (rigid.c).  sw_rigid_setup fills the rigid_* arrays of the
 * model (mass, principal inertia, body-frame nodes and element frames; called
 * by sw_compile once the rods, loads and boundary conditions are in);
 * sw_rigid_reset puts the bodies at rest at t = 0; sw_rigid_internal stands
 * for rod.c's kernels on rigid rod r (no internal loads, rest strains), and
 * sw_rigid_clear_loads for them in a step's loads (integrate.c: the loads
 * zeroed on all rigid slots, the rest strains left as sw_reset set them);
 * sw_rigid_drift and sw_rigid_kick are the bodies' parts of integrate.c's
 * drift and kick, the kick's loads taken by sw_rigid_loads (the bodies' and
 * the implicit joints' solve, before the elastic slots are kicked, since it
 * changes the loads of the nodes joined to bodies); sw_rigid_stable_dt is body b's own bound (linear damping
 * only) and sw_rigid_joint_dt the bound of all joints on it (stability.c). */
static inline int sw_rod_is_rigid(const swModel *m, int r) {
  return m->nrigid > 0 && m->rod_rigid[r] >= 0;
}
void sw_rigid_setup(swModel *m);
void sw_rigid_reset(const swModel *m, swData *d);
void sw_rigid_internal(const swModel *m, swData *d, int r);
void sw_rigid_clear_loads(const swModel *m, swData *d);
void sw_rigid_drift(const swModel *m, swData *d, double h);
void sw_rigid_loads(const swModel *m, swData *d, double h);
void sw_rigid_kick(const swModel *m, swData *d, double h);
double sw_rigid_stable_dt(const swModel *m, int b);
double sw_rigid_joint_dt(const swModel *m, int b);
/* Joints on rigid bodies under SW_IMEX (rigid_joint.c): setup marks those
 * between bodies, space and free elastic nodes (joint_implicit), finds the
 * independent groups of bodies and nodes they join and numbers them group
 * by group (rigid_block*, joint_block, rigid_group_*); the kick turns the
 * members' loads into those of the trapezoidal step, solving each group's
 * block of the system on its own (0: a block that could not be factored,
 * whose members keep their loads); scratch is the doubles of its
 * workspace, swData.rigid_sys. */
int sw_rigid_joints_setup(swModel *m);
/* The same with rod leaves (joint_groups.c, find_leaves) or, rod_leaves 0,
 * every implicit rod a dense member: what the tests compare them with. */
int sw_rigid_joints_setup_leaves(swModel *m, int rod_leaves);
void sw_rigid_joints_free(swModel *m);
size_t sw_rigid_joints_scratch(const swModel *m);
int sw_rigid_group_unknowns(const swModel *m, int g); /* group g's unknowns */
/* The order of each group's dense members (joint_order.c): members 0 ..
 * nb - 1 in group group[s] (-1: not ordered), dof[s] unknowns each, joined
 * by the nedge pairs edges[2 q], edges[2 q + 1]; order[] receives the
 * ordered members group by group, each group's chosen to cost its envelope
 * Cholesky least.  Returns 0 when out of memory. */
int sw_order_members(int nb, const int *group, int ngroup, const int *dof, int nedge,
                     const int *edges, int *order);
int sw_rigid_joints_kick(const swModel *m, swData *d, double h, double *load);
/* Groups of one shape solved together (joint_lanes.c): setup fills
 * m->rigid_group_lanes; sw_cholesky_lanes factors and solves the nl <=
 * SW_GROUP_LANES blocks A[u] (n x n, their lower triangles within the
 * envelope of the first group's env, reach, off, dof numbered from base)
 * with right-hand sides rhs[u], solutions into rhs, the bits of
 * rigid_joint.c's scalar solve of each, leaving A as it was; 0 (rhs as it
 * was too) when a block is not positive definite.  ws: the doubles
 * sw_rigid_lanes_scratch gives (swData.rigid_lanes). */
#define SW_GROUP_LANES 4
/* One group's block A (n x n) factored in place and A x = rhs solved into
 * rhs (joint_envelope.c): its members' unknowns at off, dof, envelopes env
 * and reach numbered from base; col: n doubles of scratch.  0 if A is not
 * positive definite. */
int sw_envelope_cholesky_solve(double *restrict A, int n, double *restrict rhs,
                               double *restrict col, const int *env, const int *reach,
                               const int *off, const int *dof, int base);
int sw_group_lanes_setup(swModel *m);
size_t sw_rigid_lanes_scratch(const swModel *m);
int sw_cholesky_lanes(double *const *A, double *const *rhs, int nl, int n, const int *env,
                      const int *reach, const int *off, const int *dof, int base, double *ws);
/* Implicit rods and leaves in that system (joint_ports.c): a rod member k's
 * block S and right-hand side S p0 into A (n x n, its unknowns from off)
 * and rhs, with its workspace ws (sw_port_member_scratch doubles; 0: the
 * rod's system could not be factored), and after the solve its loads from
 * its ports' velocity changes pu; a unit of leaves (one, or a filament's
 * two ends) eliminated into its ports' blocks of A and rhs, and its
 * velocity changes from the ports' in u, in its workspace (sw_leaf_condense
 * takes nu units of the same du, dQ, np and qdof, each with its workspace
 * ws[u] and ports' places qoff[u], in the order their updates of A are made). */
static inline int sw_port_dof(const swModel *m, int q) { return m->rigid_port_rot[q] ? 6 : 3; }
/* With band = 1 (rigid_group_band 2: a member's band path), the member's
 * kept ports alone (rigid_port_moff), its band ports' blocks P + 42 t and
 * right-hand sides R + 6 t (as sw_band_group_solve's) in its band first,
 * S added to A and S p0 to rhs (the joints' and leaves' terms are in
 * them), and the band ports' lab velocity changes written over R. */
size_t sw_port_member_scratch(const swModel *m, int k, int band);
int sw_port_member_assemble(const swModel *m, swData *d, double h, int k, double *ws, double *A,
                            int n, int off, double *rhs, const double *P, const double *R);
void sw_port_member_finish(const swModel *m, swData *d, double h, int k, double *ws,
                           const double *pu, double *R);
/* For the tests: a member's band path keeps Z = A^-1 E with its band and
 * turns it by the ports' frames (joint_ports.c, kept_turns); forgotten
 * (member k's workspace ws; every member's, sw_rigid_forget_kept_maps),
 * its next kicks on the kept band solve for Z as they did before Z was
 * kept, until the band is factored afresh. */
void sw_port_member_forget(const swModel *m, int k, double *ws);
void sw_rigid_forget_kept_maps(const swModel *m, swData *d);
/* Ports of one rod member that turn one element (joint_alias.c): the
 * later one's rotation is the earlier's (m->rigid_port_alias, set up after
 * the groups' paths); its rows of group g's block A (n x n, the members'
 * unknowns at off[k], dof[k], k numbered as the model's) and rhs folded
 * into its target's, and after the solve du's copied from them. */
int sw_port_alias_setup(swModel *m);
void sw_port_alias_fold(const swModel *m, int g, const int *off, const int *dof, double *A,
                        int n, double *rhs);
void sw_port_alias_copy(const swModel *m, int g, const int *off, double *du);
/* A unit of leaves (up to 12 unknowns joined to up to 12 of ports): its
 * workspace A_uu (du x du), C (du x dQ), X (du x dQ), b (du) and, for a
 * lone leaf's closed form (leaf_plain.c), its mass and lab inertia (1 + 9),
 * one after another, rounded up to whole cache lines; rigid_leaf_unit holds each
 * unit's place (SW_LEAF_UNIT ints a leaf, the last its workspace's first
 * double among its group's units'). */
#define SW_LEAF_UNIT 11
static inline size_t sw_unit_size(int du, int dQ) {
  return ((size_t)(du * du + 2 * du * dQ + du + 10) + 7) / 8 * 8;
}
static inline double *sw_unit_C(double *ws, int du) { return ws + du * du; }
static inline double *sw_unit_X(double *ws, int du, int dQ) { return ws + du * du + du * dQ; }
static inline double *sw_unit_b(double *ws, int du, int dQ) { return ws + du * du + 2 * du * dQ; }
static inline double *sw_unit_M(double *ws, int du, int dQ) {
  return ws + du * du + 2 * du * dQ + du;
}
int sw_leaf_condense(double *const *ws, const int *const *qoff, int nu, int du, int dQ, int np,
                     const int *qdof, double *A, int n, double *rhs); /* nu units of one shape */
void sw_leaf_recover(double *ws, int du, int dQ, int np, const int *qoff, const int *qdof,
                     const double *u);
/* The same for a lone leaf without a dashpot (one port at qoff), in closed
 * form (leaf_plain.c), which adds its joints' block on the port as well
 * (W A_uu^-1 M, their series with the leaf's inertia M; the assembly leaves
 * it out). */
int sw_leaf_condense_plain(double *ws, int du, int dQ, int qoff, double *A, int n, double *rhs);
void sw_leaf_recover_plain(double *ws, int du, int dQ, int qoff, const double *u);
/* The band path (joint_ports.c) of a group that is one implicit rod member
 * k and leaves on its ports (m->rigid_group_band): each port's block of
 * joints and eliminated leaves (lower triangle, port t's at P + 42 t, rows
 * 6 apart: the diagonal blocks of a matrix of row length 6 whose port t
 * starts at row and column 6 t) and right-hand side (R + 6 t) added to the
 * rod's band through E, the band factored and solved, the rod's loads set,
 * and each port's lab velocity change written over R (0: not factored). */
#define SW_BAND_PORT 42
int sw_band_group_solve(const swModel *m, swData *d, double h, int k, const double *P, double *R);
/* Environments (environment.c).  The swSpec keeps them in an opaque slot
 * (sw_spec_env); sw_env_check validates them in sw_compile, sw_env_setup
 * puts resolved copies and each kind's derived data in the model, sw_env_free
 * releases them; sw_env_loads adds their loads after all others (integrate.c;
 * entered by every thread of a step: each rod's by the thread that owns it),
 * sw_env_energy is their stored energy, sw_env_stable_dt their step limit. */
typedef struct swEnvSpec swEnvSpec;
/* What the rest of the runtime calls of the environments, reached through
 * the spec (set by the first sw_spec_add_ground, _fluid, _contact, _wave or
 * _probe) and the model (m->env_ops), as for muscles: a scene without any
 * links none of environment.c, ground.c, fluid.c, contact.c and wave.c. */
typedef struct {
  int (*check)(const swEnvSpec *e, int nrod, char *err, size_t errlen);
  int (*setup)(swModel *m, const swEnvSpec *e, char *err, size_t errlen);
  void (*free_model)(swModel *m);
  void (*free_spec)(swEnvSpec *e);
  void (*loads)(const swModel *m, swData *d);
  double (*energy)(const swModel *m, const swData *d);
  double (*stable_dt)(const swModel *m);
  int (*data_new)(const swModel *m, swData *d); /* the contact grid's scratch */
} swEnvOps;
static inline const swEnvOps *sw_env_ops(const swModel *m) { return (const swEnvOps *)m->env_ops; }
swEnvSpec **sw_spec_env(swSpec *s);                                   /* spec.c */
const swEnvOps **sw_spec_env_ops(swSpec *s);                          /* spec.c */
void sw_env_spec_free(swEnvSpec *e);
int sw_env_check(const swEnvSpec *e, int nrod, char *err, size_t errlen);
int sw_env_setup(swModel *m, const swEnvSpec *e, char *err, size_t errlen);
void sw_env_free(swModel *m);
static inline int sw_has_env(const swModel *m) {
  return m->nground + m->nfluid + m->ncontact + m->nwave + m->nobstacle > 0;
}
void sw_env_loads(const swModel *m, swData *d);
double sw_env_energy(const swModel *m, const swData *d);
double sw_env_stable_dt(const swModel *m);
int sw_env_data_new(const swModel *m, swData *d);
/* Fluids (fluid.c).  sw_fluid_setup fills the model's fluid_* planes and the
 * Stokes drag's step limit from m->fluid (called by sw_env_setup; 0 and a
 * message naming the fluid and rod when slender-body drag is meaningless);
 * sw_fluid_free releases them; sw_fluid_loads adds drag and buoyancy to
 * d->ext_force and d->force; sw_fluid_stable_dt is the step limit. */
int sw_fluid_setup(swModel *m, char *err, size_t errlen);
void sw_fluid_free(swModel *m);
void sw_fluid_loads(const swModel *m, swData *d, int lo, int hi);
double sw_fluid_stable_dt(const swModel *m);

/* The area rods show at rest (planform.c): the sum of their silhouettes
 * 2 r l, and their planform, the outline they cover on their mean plane
 * (normal `normal`) with overlaps counted once, measured on square cells of
 * side `cell`, with the change on cells twice as large as its error.
 * Returns 0 when the rods have no area or memory runs out. */
typedef struct {
  double silhouette, planform, planform_error, cell, normal[3];
} swArea;
int sw_rods_area(const swModel *m, int nrods, const int *rods, swArea *out);
/* Grounds and terrains (ground.c).  sw_ground_setup normalises the planes'
 * normals (from sw_env_setup); sw_ground_loads adds the normal response and
 * friction of every ground (its balance, damping and friction also to
 * ext_force/ext_torque), called last by sw_env_loads; sw_ground_energy is the
 * energy of the ground penalties; sw_ground_stable_dt their step limit. */
void sw_ground_setup(swModel *m);
void sw_ground_loads(const swModel *m, swData *d, int lo, int hi);
double sw_ground_energy(const swModel *m, const swData *d);
double sw_ground_stable_dt(const swModel *m);
/* Torque waves (wave.c): sw_wave_setup fills the wave_* arrays of the model
 * (beta and the wave's phase at every node; 0 when out of memory), called by
 * sw_env_setup; sw_wave_loads adds the couples to d->ext_torque and
 * d->torque, called by sw_env_loads. */
int sw_wave_setup(swModel *m);
void sw_wave_free(swModel *m);
void sw_wave_loads(const swModel *m, swData *d, int lo, int hi);
/* Probes (probe.c): their samples live in swData (sw_data_new, sw_data_free
 * and sw_reset call these); kind names and units for output and --info. */
int sw_probe_data_new(const swModel *m, swData *d);
void sw_probe_data_free(swData *d);
void sw_probe_reset(const swModel *m, swData *d);
const char *sw_probe_kind_name(swProbeKind kind);
/* "spherical", "hinge", "fixed" (joint.c) */
const char *sw_joint_kind_name(swJointKind kind);
const char *sw_probe_units(swProbeKind kind);
/* Rod-rod contact (contact.c).  sw_contact_setup lists each contact's
 * elements in the model and sizes the friction's anchor table (0: out of
 * memory; from sw_env_setup), sw_contact_free
 * releases them (sw_env_free); sw_contact_data_new/free the hash grid's
 * scratch in the state (sw_data_new/free); sw_contact_loads adds the contact
 * loads (from sw_env_loads), sw_contact_loads_with by the grid or by brute
 * force over all pairs (tests and benchmark); sw_contact_energy is the
 * springs' energy, sw_contact_stable_dt their step limit. */
typedef enum { SW_CONTACT_GRID = 0, SW_CONTACT_BRUTE = 1 } swContactPhase;
int sw_contact_setup(swModel *m);
void sw_contact_free(swModel *m);
int sw_contact_data_new(const swModel *m, swData *d);
void sw_contact_loads(const swModel *m, swData *d);
void sw_contact_loads_with(const swModel *m, swData *d, swContactPhase phase);
double sw_contact_energy(const swModel *m, const swData *d);
double sw_contact_stable_dt(const swModel *m);

/* Rigid obstacles (obstacle.c).  sw_obstacle_setup fills the model's
 * obstacle_* arrays from m->obstacle (0: out of memory; from sw_env_setup),
 * sw_obstacle_free releases them; sw_obstacle_data_new the contact records
 * and chunk boxes of the state (data.c frees them); sw_obstacle_loads adds the contact
 * loads on the rods and the carriers (from sw_env_loads, on one thread),
 * sw_obstacle_loads_with by the chunk boxes or by brute force over all
 * element-obstacle pairs (tests and benchmark); sw_obstacle_energy is the
 * springs' energy, sw_obstacle_stable_dt their step limit.  Rod-rod
 * contact's closest points of two segments serve the capsule. */
#define SW_OBSTACLE_CHUNK 16
typedef enum { SW_OBSTACLE_GRID = 0, SW_OBSTACLE_BRUTE = 1 } swObstaclePhase;
int sw_obstacle_setup(swModel *m);
void sw_obstacle_free(swModel *m);
int sw_obstacle_data_new(const swModel *m, swData *d);
void sw_obstacle_loads(const swModel *m, swData *d);
void sw_obstacle_loads_with(const swModel *m, swData *d, swObstaclePhase phase);
double sw_obstacle_energy(const swModel *m, const swData *d);
double sw_obstacle_stable_dt(const swModel *m);
/* obstacle_shape.c: the least signed distance from the local segment a + s d
 * to obstacle o's surface, its s and the outward normal (the shape's frame);
 * *s_out brings in the element's radius, beyond which a lower bound may be
 * returned. */
double sw_obstacle_segment_distance(const swObstacleDesc *o, const double a[3], const double d[3],
                                    double *s_out, double n[3]);
double sw_segment_closest(const double *a0, const double *da, const double *b0, const double *db,
                          double *s_out, double *t_out, double *pq);   /* contact.c */

/* The elastic-Coulomb friction law of obstacle.c and contact.c (friction.c):
 * sw_coulomb_cap turns the tangential separation u_t and relative velocity
 * w_t of a pair's anchor points into the force F = -k_t u_t - gamma w_t,
 * capped at mu_k N when it exceeds mu_s N; returns 1 if stuck, 0 if it
 * slips.  Anchor tables are rows of `width` doubles ordered by their first
 * (the key): sw_anchor_find bisects for a key (NULL: none), sw_anchor_sort
 * sorts n rows in place. */
int sw_coulomb_cap(const double ut[3], const double wt[3], double kt, double gamma, double mu_s,
                   double mu_k, double N, double F[3]);
const double *sw_anchor_find(const double *rows, int n, int width, double key);
void sw_anchor_sort(double *rows, int n, int width);

/* A rod element's side of a touching pair with friction (friction.c), for
 * both kernels: the element's first node slot, its element slot, the
 * closest point's place `at` on its segment and the element's radius; once
 * anchored, the anchor's place anchor_at and its arm from the centreline
 * point there to the anchored surface point (lab).  sw_side_point places
 * the anchor of arm y (element frame) at `at`: the point and its velocity
 * v_c + omega x arm; sw_side_arm turns a lab offset into an arm y;
 * sw_side_apply puts the force f at the anchor: split over the nodes at the
 * centreline point, the couple arm x f on the element, all of it into the
 * external loads too (the kick books its work); sw_side_centre interpolates
 * the node array x (positions or velocities) at the place `at`. */
typedef struct {
  int node, elem;
  double at, radius;
  double anchor_at, arm[3];
} swFrictionSide;
void sw_side_centre(const swModel *m, const double *x, const swFrictionSide *e, double at, double p[3]);
void sw_side_point(const swModel *m, const swData *d, swFrictionSide *e, double at, const double y[3],
                   double p[3], double v[3]);
void sw_side_arm(const swModel *m, const swData *d, const swFrictionSide *e, const double off[3],
                 double y[3]);
void sw_side_apply(const swModel *m, const swData *d, const swFrictionSide *e, const double f[3],
                   double *force, double *ext_force, double *torque, double *ext_torque);
/* After the cap both kernels re-anchor each pair at its touching surface
 * points (arms -r n from the centreline) and keep the spring's tangential
 * stretch: sw_friction_reanchor gives the stretch (u_t when stuck, -F / k_t
 * when slipping, so that the spring alone gives F) and the place on side
 * e's segment (kept while stuck, the closest point's when slipping). */
double sw_friction_reanchor(const swFrictionSide *e, int stuck, const double ut[3], const double F[3],
                            double kt, double stretch[3]);

/* swell.c: rods whose geometry changes in time */
int sw_swell_setup(swModel *m, const swSpec *s);
void sw_swell_free(swModel *m);
int sw_swell_of_rod(const swModel *m, int r);
int sw_swell_data_new(const swModel *m, swData *d);
void sw_swell_data_free(swData *d);
const double *sw_swell_clamp_bend(const swModel *m, const swData *d);
void sw_swell_update(const swModel *m, swData *d, double t);
/* stability.c: rod r's elastic bound at radius scale g (swell.c's rods) */
double sw_stable_dt_elastic_at(const swModel *m, int r, double g);
/* swell.c: the least and the greatest g swelling rod k reaches over
 * [0, duration], sampled at 4097 times and the signal's own range when it
 * is a built-in one */
void sw_swell_range_over(const swModel *m, int k, double duration, double *lo, double *hi);

#endif
