/* eval_sundials.c — should sinew hand its stiff terms to SUNDIALS (ARKODE's
 * IMEX ARKStep and multirate MRIStep) or keep its own linearly implicit kick?
 * Measured on a 1-D model of the piece of the elbow that sets the step.
 *
 * Design.  The model is the biceps filament's axial chain between its two
 * tendons: a proximal tendon (7 elements, clamped at its first node), a joint
 * spring, one muscle filament (14 elements), a joint spring, a distal tendon
 * (7 elements) whose last node carries a 1 kg mass under a constant 9.81 N
 * load.  Every element and joint is a linear axial spring between consecutive
 * nodes; masses are lumped, half an element's to each of its nodes.  The
 * filament pulls its two end nodes together with Hill's tension
 * T = F_qs g(u), u = -(dl/dt) / l0 (docs/physics.md, "Force-velocity"), with
 * F_qs ramped from 0 to 40 N over 0.1 s; its slope c = dT/d(dl/dt) is a
 * rank-one dashpot across the whole filament, which is what limits the
 * elbow's explicit step.  The schemes compared, each over 0.2 s:
 *   verlet   position Verlet (drift h/2, kick h, drift h/2), tension explicit;
 *   imex     the same Verlet with the tension linearly implicit in the kick,
 *            in closed form (runtime/engine/muscle.c, Rosenbrock-Euler):
 *            T* = (T0 + c h p) / (1 + c h s), p = b.M^-1 F, s = b.M^-1 b;
 *   ark      ARKODE's ARKStep, additive Runge-Kutta: the tension (and in one
 *            variant the joint springs) implicit, solved by Newton with
 *            SUNDIALS' dense LU (SUNLinSol_Dense, SUNDenseMatrix), the rest
 *            explicit; fixed steps, and adaptive at rtol 1e-6, atol 1e-9
 *            (and the looser 1e-4, 1e-7);
 *   mri      ARKODE's MRIStep: the filament (tension, elasticity, its nodes'
 *            x' = v) fast, integrated by an explicit ARKStep at a step the
 *            damper allows, everything else slow at the fixed slow step.
 * ARKODE integrates y' = f(t, y) on R^n, so for it the state is one flat
 * vector y = (x_1..x_30, v_1..v_30) (node 0 is clamped and not in it).  The
 * observable is the end mass's position, sampled every 1 ms; the error of a
 * run is its largest distance from the reference: explicit Verlet at 1/20 of
 * the stable step and at 1/40, Richardson-extrapolated, because both Verlet
 * variants are first order here (the kick takes the dashpot at the old
 * velocity) and Verlet at 1/20 alone is less accurate than ARKODE's runs.
 * Times are medians of NREP runs of the integration loop (the integrators'
 * creation is not timed), as wall time and as the thread's CPU time, since
 * the machine's vCPUs are shared.  SUNDIALS's own time is what remains of a
 * run's CPU time after the right-hand sides and Jacobians it called, each
 * timed alone in a loop.  Besides the table of the brief, the largest fixed
 * steps explicit Verlet, ARK3 and MRIStep survive are found by bisection.
 * A markdown table goes to stdout.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_mristep.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunlinsol/sunlinsol_dense.h>
#include "bench_util.h"

/* CPU time of the calling thread: the machine's two vCPUs are shared, so
 * wall time also counts the time others' processes held them. */
static double cpu_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the model problem (the biceps of models/human_arm.sinew, simplified) */
enum {
  NT = 7,                      /* elements per tendon                      */
  NF = 14,                     /* elements of the filament                 */
  FIL_FIRST = NT + 1,          /* the filament's first node (8)            */
  FIL_LAST = FIL_FIRST + NF,   /* its last node (22)                       */
  NNODE = FIL_LAST + 1 + NT + 1, /* 31 nodes, node 0 clamped              */
  NSPRING = NNODE - 1,         /* spring i joins nodes i and i + 1         */
  NFREE = NNODE - 1,           /* free nodes 1..30                         */
  NEQ = 2 * NFREE,             /* ARKODE's state: positions, velocities    */
  END_NODE = NNODE - 1,        /* carries the 1 kg mass                    */
  NSAMPLE = 200,               /* observable every T_END / NSAMPLE = 1 ms  */
  NREP = 5                     /* timed repeats, median                    */
};
static const double T_END = 0.2;           /* simulated time, s                  */
static const double TENDON_E = 500e6;      /* Pa                                 */
static const double TENDON_R = 4e-3;       /* m                                  */
static const double TENDON_LEN = 0.04;     /* 7 elements of 5.7 mm, m            */
static const double TENDON_MASS = 3.5e-3;  /* kg per tendon                      */
static const double FIL_E = 10e3;          /* Pa (muscle tissue)                 */
static const double FIL_R = 3.77e-3;       /* m                                  */
static const double FIL_RHO = 1060.0;      /* kg/m^3                             */
static const double FIL_L0 = 0.2;          /* rest length l0, m                  */
static const double JOINT_K = 5e5;         /* joint springs, N/m (Suppl. Table 5)*/
static const double END_MASS = 1.0;        /* kg                                 */
static const double END_LOAD = 9.81;       /* N, distal                          */
static const double FQS_MAX = 40.0;        /* N, active pull after the ramp      */
static const double RAMP = 0.1;            /* s, 0 -> FQS_MAX                    */
static const double HILL_K = 0.16;         /* a / F_qs                           */
static const double HILL_U0 = 6.0;         /* largest shortening rate, 1/s       */
static const double DIVERGED = 1.0;        /* m of end-mass travel: unstable     */

/* The kinds of spring, as bits, so a part of a split can hold a subset. */
enum { SPRING_TENDON = 1u, SPRING_JOINT = 2u, SPRING_FILAMENT = 4u, SPRING_ALL = 7u };

typedef struct {
  double mass[NNODE];     /* lumped nodal mass, kg (nnode)                     */
  double inv_mass[NNODE]; /* 1 / mass, 0 at the clamped node (nnode)           */
  double x0[NNODE];       /* rest position along the axis, m (nnode)           */
  double load[NNODE];     /* constant external load, N (nnode)                 */
  double stiff[NSPRING];  /* axial stiffness EA / l or joint k, N/m (nspring)  */
  double rest[NSPRING];   /* rest length, m (nspring)                          */
  unsigned kind[NSPRING]; /* SPRING_* (nspring)                                */
} Model;

static void model_build(Model *m) {
  memset(m, 0, sizeof *m);
  const double tendon_area = M_PI * TENDON_R * TENDON_R, fil_area = M_PI * FIL_R * FIL_R;
  const double tendon_le = TENDON_LEN / NT, fil_le = FIL_L0 / NF;
  for (int i = 0; i < NSPRING; i++) {
    double k, l, me;
    if (i < NT || i > FIL_LAST) {          /* tendon element */
      k = TENDON_E * tendon_area / tendon_le, l = tendon_le, me = TENDON_MASS / NT;
      m->kind[i] = SPRING_TENDON;
    } else if (i == NT || i == FIL_LAST) { /* joint: coincident nodes, no mass */
      k = JOINT_K, l = 0, me = 0;
      m->kind[i] = SPRING_JOINT;
    } else {                               /* filament element */
      k = FIL_E * fil_area / fil_le, l = fil_le, me = FIL_RHO * fil_area * fil_le;
      m->kind[i] = SPRING_FILAMENT;
    }
    m->stiff[i] = k, m->rest[i] = l;
    m->mass[i] += 0.5 * me, m->mass[i + 1] += 0.5 * me;
    m->x0[i + 1] = m->x0[i] + l;
  }
  m->mass[END_NODE] += END_MASS;
  m->load[END_NODE] = END_LOAD;
  for (int i = 1; i < NNODE; i++) m->inv_mass[i] = 1.0 / m->mass[i];
}

/* Adds the forces of the springs whose kind is in `kinds` to f (nnode). */
static void spring_forces(const Model *m, const double *x, unsigned kinds, double *f) {
  for (int i = 0; i < NSPRING; i++) {
    if (!(m->kind[i] & kinds)) continue;
    const double tension = m->stiff[i] * (x[i + 1] - x[i] - m->rest[i]);
    f[i] += tension, f[i + 1] -= tension;
  }
}

/* F_qs(t): the activation ramp. */
static double active_force(double t) { return FQS_MAX * (t < RAMP ? t / RAMP : 1.0); }

/* Hill's tension T = F_qs g(u), u = -(dl/dt) / l0 (docs/physics.md):
 *   g = 1 - (1 + k) u / (u + k u0)   0 <= u < u0   (Hill 1938)
 *   g = 1 - (1 + k) u / (k u0)       u < 0         (lengthening, slope kept)
 *   g = 0                            u >= u0
 * and its slope c = dT/d(dl/dt) = -F_qs g'(u) / l0 >= 0, the dashpot. */
static double hill_tension(double fqs, double ldot, double *slope) {
  const double u = -ldot / FIL_L0, ku0 = HILL_K * HILL_U0;
  if (u >= HILL_U0) {
    *slope = 0;
    return 0;
  }
  if (u < 0) {
    *slope = fqs * (1 + HILL_K) / (ku0 * FIL_L0);
    return fqs * (1 - (1 + HILL_K) * u / ku0);
  }
  *slope = fqs * (1 + HILL_K) * ku0 / (FIL_L0 * (u + ku0) * (u + ku0));
  return fqs * (1 - (1 + HILL_K) * u / (u + ku0));
}

/* ---- stable steps */

/* Largest eigenvalue of M^-1 K over the free nodes: M^-1/2 K M^-1/2 is
 * tridiagonal for a chain, so bisection on its Sturm count (the number of
 * negative pivots of A - lambda I is the number of eigenvalues below lambda). */
static double omega_max_sq(const Model *m) {
  double diag[NFREE], off2[NFREE]; /* off2[i]: squared coupling of free nodes i-1, i */
  for (int j = 0; j < NFREE; j++) {
    const int node = j + 1;
    const double k_left = m->stiff[node - 1], k_right = node < NSPRING ? m->stiff[node] : 0;
    diag[j] = (k_left + k_right) * m->inv_mass[node];
    off2[j] = j ? m->stiff[node - 1] * m->stiff[node - 1] * m->inv_mass[node - 1] * m->inv_mass[node] : 0;
  }
  double lo = 0, hi = 0;
  for (int j = 0; j < NFREE; j++) /* Gershgorin */
    hi = fmax(hi, diag[j] + sqrt(off2[j]) + (j + 1 < NFREE ? sqrt(off2[j + 1]) : 0));
  for (int it = 0; it < 200; it++) {
    const double lambda = 0.5 * (lo + hi);
    int below = 0;
    double q = 1;
    for (int j = 0; j < NFREE; j++) {
      q = diag[j] - lambda - (j ? off2[j] / q : 0);
      if (q == 0) q = -1e-300;
      below += q < 0;
    }
    if (below == NFREE) hi = lambda; else lo = lambda;
  }
  return hi;
}

typedef struct {
  double damper;   /* 2 mu / c_max, mu the filament ends' reduced mass, s */
  double elastic;  /* 2 / omega_max of all the springs, s                 */
  double c_max;    /* the dashpot at F_qs max, lengthening, N s/m          */
  double mu;       /* reduced mass of the filament's end nodes, kg         */
} Limits;

static Limits stable_limits(const Model *m) {
  Limits L;
  double c;
  hill_tension(FQS_MAX, 0, &c);   /* c(u <= 0) = F_qs (1 + k) / (k u0 l0) */
  L.c_max = c;
  L.mu = 1.0 / (m->inv_mass[FIL_FIRST] + m->inv_mass[FIL_LAST]);
  L.damper = 2 * L.mu / c;        /* explicit kick: |1 - h c s| < 1, s = 1/mu */
  L.elastic = 2 / sqrt(omega_max_sq(m));
  return L;
}

/* ---- one run and its counters */
typedef struct {
  double obs[NSAMPLE + 1]; /* end-mass displacement at t = k T_END / NSAMPLE, m */
  double h;                /* step taken (fixed-step runs), slow step for mri, s */
  double wall;             /* wall time of the integration loop, s */
  double cpu;              /* CPU time of the same (this thread), s */
  long steps;              /* steps (slow steps for mri) */
  long nfe, nfi;           /* explicit / implicit (slow / fast for mri) rhs evaluations */
  long newton, lsetups, jevals, fast_steps;
  int failed;              /* diverged, or SUNDIALS gave up */
} Run;

static int obs_ok(double dx) { return isfinite(dx) && fabs(dx) < DIVERGED; }

/* Position Verlet; the kick's tension explicit (T0) or linearly implicit
 * (imex).  h_target is rounded down so that the samples fall on steps. */
static void run_verlet(const Model *m, int imex, double h_target, Run *r) {
  long per_sample = (long)ceil(T_END / NSAMPLE / h_target);
  const double h = T_END / NSAMPLE / per_sample;
  double x[NNODE], v[NNODE], f[NNODE];
  memcpy(x, m->x0, sizeof x);
  memset(v, 0, sizeof v);
  memset(r, 0, sizeof *r);
  r->h = h;
  r->obs[0] = 0;
  const double t0 = wall_seconds(), c0 = cpu_seconds();
  long n = 0;
  for (int k = 1; k <= NSAMPLE && !r->failed; k++) {
    for (long j = 0; j < per_sample; j++, n++) {
      for (int i = 1; i < NNODE; i++) x[i] += 0.5 * h * v[i];       /* drift h/2 */
      memcpy(f, m->load, sizeof f);
      spring_forces(m, x, SPRING_ALL, f);
      double c;
      const double ldot = v[FIL_LAST] - v[FIL_FIRST];               /* b . v */
      double tension = hill_tension(active_force((n + 0.5) * h), ldot, &c);
      if (imex) {
        /* T* = (T0 + c h p) / (1 + c h s), p = b.M^-1 F, s = b.M^-1 b (muscle.c) */
        const double p = f[FIL_LAST] * m->inv_mass[FIL_LAST] - f[FIL_FIRST] * m->inv_mass[FIL_FIRST];
        const double s = m->inv_mass[FIL_LAST] + m->inv_mass[FIL_FIRST];
        tension = fmax(0.0, (tension + c * h * p) / (1 + c * h * s));
      }
      f[FIL_FIRST] += tension, f[FIL_LAST] -= tension;             /* -T b */
      for (int i = 1; i < NNODE; i++) {
        v[i] += h * f[i] * m->inv_mass[i];                          /* kick h */
        x[i] += 0.5 * h * v[i];                                     /* drift h/2 */
      }
    }
    r->obs[k] = x[END_NODE] - m->x0[END_NODE];
    if (!obs_ok(r->obs[k])) r->failed = 1;
  }
  r->wall = wall_seconds() - t0;
  r->cpu = cpu_seconds() - c0;
  r->steps = n;
  r->nfe = n;
}

/* ---- SUNDIALS: the right-hand side split in two parts */

/* One part of y' = f(t, y): which forces it holds, and which nodes' x' = v. */
typedef struct {
  unsigned springs;  /* SPRING_* bits */
  int hill;          /* holds the Hill tension */
  int load;          /* holds the end load */
  int xdot;          /* XDOT_*: nodes whose x' = v this part holds */
} Part;
enum { XDOT_NONE, XDOT_ALL, XDOT_FILAMENT, XDOT_NOT_FILAMENT };

typedef struct {
  const Model *m;
  Part part[2];      /* ark: explicit, implicit; mri: slow, fast */
  double x[NNODE], v[NNODE], f[NNODE]; /* scratch, so no allocation in a call */
} Problem;

static int on_filament(int node) { return node >= FIL_FIRST && node <= FIL_LAST; }
static int holds_xdot(int xdot, int node) {
  return xdot == XDOT_ALL || (xdot == XDOT_FILAMENT && on_filament(node)) ||
         (xdot == XDOT_NOT_FILAMENT && !on_filament(node));
}

static void unpack(Problem *pb, const double *y) {
  pb->x[0] = pb->m->x0[0], pb->v[0] = 0;
  for (int i = 1; i < NNODE; i++) pb->x[i] = y[i - 1], pb->v[i] = y[NFREE + i - 1];
}

/* ydot = the part's share of (v, M^-1 F). */
static void part_rhs(Problem *pb, const Part *part, double t, const double *y, double *ydot) {
  const Model *m = pb->m;
  unpack(pb, y);
  memset(pb->f, 0, sizeof pb->f);
  if (part->load) memcpy(pb->f, m->load, sizeof pb->f);
  spring_forces(m, pb->x, part->springs, pb->f);
  if (part->hill) {
    double c;
    const double tension = hill_tension(active_force(t), pb->v[FIL_LAST] - pb->v[FIL_FIRST], &c);
    pb->f[FIL_FIRST] += tension, pb->f[FIL_LAST] -= tension;
  }
  for (int i = 1; i < NNODE; i++) {
    ydot[i - 1] = holds_xdot(part->xdot, i) ? pb->v[i] : 0;
    ydot[NFREE + i - 1] = pb->f[i] * m->inv_mass[i];
  }
}

/* ARKStep's split: explicit = x' = v, the load and the springs not made
 * implicit; implicit = the Hill tension and implicit_springs. */
static void ark_parts(Problem *pb, unsigned implicit_springs) {
  pb->part[0] = (Part){SPRING_ALL & ~implicit_springs, 0, 1, XDOT_ALL};
  pb->part[1] = (Part){implicit_springs, 1, 0, XDOT_NONE};
}

/* MRIStep's split: slow = tendons, joints, load and x' = v off the filament;
 * fast = the filament's elasticity, its tension and its nodes' x' = v. */
static void mri_parts(Problem *pb) {
  pb->part[0] = (Part){SPRING_TENDON | SPRING_JOINT, 0, 1, XDOT_NOT_FILAMENT};
  pb->part[1] = (Part){SPRING_FILAMENT, 1, 0, XDOT_FILAMENT};
}

static int rhs_part0(realtype t, N_Vector y, N_Vector ydot, void *data) {
  Problem *pb = data;
  part_rhs(pb, &pb->part[0], t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
  return 0;
}
static int rhs_part1(realtype t, N_Vector y, N_Vector ydot, void *data) {
  Problem *pb = data;
  part_rhs(pb, &pb->part[1], t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
  return 0;
}

/* d(part 1)/dy, the implicit part's Jacobian: the dashpot's 2x2 block in the
 * filament ends' velocities, the implicit springs' blocks in positions. */
static int jac_part1(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *data,
                     N_Vector tmp1, N_Vector tmp2, N_Vector tmp3) {
  (void)fy, (void)tmp1, (void)tmp2, (void)tmp3;
  Problem *pb = data;
  const Model *m = pb->m;
  const Part *part = &pb->part[1];
  unpack(pb, N_VGetArrayPointer(y));
  SUNMatZero(J);
  for (int i = 1; i < NNODE; i++)
    if (holds_xdot(part->xdot, i)) SM_ELEMENT_D(J, i - 1, NFREE + i - 1) = 1;
  for (int s = 0; s < NSPRING; s++) {
    if (!(m->kind[s] & part->springs)) continue;
    const int a = s, b = s + 1;      /* f_a = +k (x_b - x_a - l), f_b = -f_a */
    const double k = m->stiff[s];
    if (a > 0) {
      SM_ELEMENT_D(J, NFREE + a - 1, a - 1) -= k * m->inv_mass[a];
      SM_ELEMENT_D(J, NFREE + a - 1, b - 1) += k * m->inv_mass[a];
      SM_ELEMENT_D(J, NFREE + b - 1, a - 1) += k * m->inv_mass[b];
    }
    SM_ELEMENT_D(J, NFREE + b - 1, b - 1) -= k * m->inv_mass[b];
  }
  if (part->hill) {                  /* f_first = +T, f_last = -T, dT/d(v_last - v_first) = c */
    double c;
    hill_tension(active_force(t), pb->v[FIL_LAST] - pb->v[FIL_FIRST], &c);
    const int vf = NFREE + FIL_FIRST - 1, vl = NFREE + FIL_LAST - 1;
    SM_ELEMENT_D(J, vf, vf) -= c * m->inv_mass[FIL_FIRST];
    SM_ELEMENT_D(J, vf, vl) += c * m->inv_mass[FIL_FIRST];
    SM_ELEMENT_D(J, vl, vf) += c * m->inv_mass[FIL_LAST];
    SM_ELEMENT_D(J, vl, vl) -= c * m->inv_mass[FIL_LAST];
  }
  return 0;
}

/* SUNDIALS reports a failure of an unstable fixed step by an error message;
 * the run is marked failed instead. */
static void quiet_errors(int code, const char *module, const char *function, char *msg, void *data) {
  (void)code, (void)module, (void)function, (void)msg, (void)data;
}

static void init_state(const Model *m, N_Vector y) {
  double *p = N_VGetArrayPointer(y);
  for (int i = 1; i < NNODE; i++) p[i - 1] = m->x0[i], p[NFREE + i - 1] = 0;
}

typedef struct {
  unsigned implicit_springs; /* springs moved to the implicit part           */
  int order;                 /* ARK method order (3: ARK324L2SA, 4: ARK436L2SA) */
  int dq_jacobian;           /* 1: SUNDIALS' difference-quotient Jacobian     */
  double h;                  /* fixed step, or 0 for adaptive                  */
  double rtol, atol;         /* adaptive: tolerances (positions m, velocities m/s) */
} ArkConfig;

/* ARKStep IMEX (ark_parts), the implicit stages by Newton with dense LU;
 * fixed steps (cfg->h) or adaptive.  Order 3 is ARKODE's ARK324L2SA pair,
 * order 4 ARK436L2SA (Kennedy & Carpenter 2003); Newton and the Jacobian's
 * reuse (at most 20 steps) are ARKODE's defaults. */
static void run_ark(const Model *m, SUNContext ctx, const ArkConfig *cfg, Run *r) {
  Problem pb = {.m = m};
  ark_parts(&pb, cfg->implicit_springs);
  memset(r, 0, sizeof *r);
  N_Vector y = N_VNew_Serial(NEQ, ctx);
  init_state(m, y);
  void *ark = ARKStepCreate(rhs_part0, rhs_part1, 0.0, y, ctx);
  SUNMatrix A = SUNDenseMatrix(NEQ, NEQ, ctx);
  SUNLinearSolver LS = SUNLinSol_Dense(y, A, ctx);
  ARKStepSetUserData(ark, &pb);
  ARKStepSetErrHandlerFn(ark, quiet_errors, NULL);
  ARKStepSetLinearSolver(ark, LS, A);
  if (!cfg->dq_jacobian) ARKStepSetJacFn(ark, jac_part1);
  ARKStepSetOrder(ark, cfg->order);
  ARKStepSetMaxNumSteps(ark, 1000000);
  long per_sample = 0;
  if (cfg->h > 0) {
    per_sample = (long)ceil(T_END / NSAMPLE / cfg->h);
    r->h = T_END / NSAMPLE / per_sample;
    ARKStepSetFixedStep(ark, r->h);
  }
  ARKStepSStolerances(ark, cfg->h > 0 ? 1e-6 : cfg->rtol, cfg->h > 0 ? 1e-9 : cfg->atol);
  const double *py = N_VGetArrayPointer(y);
  realtype t = 0;
  const double t0 = wall_seconds(), c0 = cpu_seconds();
  for (int k = 1; k <= NSAMPLE && !r->failed; k++) {
    const double tout = k * (T_END / NSAMPLE);
    if (per_sample) {
      for (long j = 0; j < per_sample && !r->failed; j++) {
        r->failed = ARKStepEvolve(ark, tout, y, &t, ARK_ONE_STEP) < 0;
        if (!isfinite(py[END_NODE - 1])) r->failed = 1;
      }
    } else {
      ARKStepSetStopTime(ark, tout);  /* samples from steps, not the interpolant */
      r->failed = ARKStepEvolve(ark, tout, y, &t, ARK_NORMAL) < 0;
    }
    r->obs[k] = py[END_NODE - 1] - m->x0[END_NODE];
    if (!obs_ok(r->obs[k])) r->failed = 1;
  }
  r->wall = wall_seconds() - t0;
  r->cpu = cpu_seconds() - c0;
  ARKStepGetNumSteps(ark, &r->steps);
  ARKStepGetNumRhsEvals(ark, &r->nfe, &r->nfi);
  ARKStepGetNumNonlinSolvIters(ark, &r->newton);
  ARKStepGetNumLinSolvSetups(ark, &r->lsetups);
  ARKStepGetNumJacEvals(ark, &r->jevals);
  ARKStepFree(&ark);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
}

/* MRIStep (mri_parts): the slow part by ARKODE's default explicit coupling
 * of order 3 (MIS-KW3) at the fixed step h_slow, the fast part by an
 * explicit ARKStep of order 3 (Bogacki-Shampine) at the fixed step h_fast. */
static void run_mri(const Model *m, SUNContext ctx, double h_slow, double h_fast, Run *r) {
  Problem pb = {.m = m};
  mri_parts(&pb);
  memset(r, 0, sizeof *r);
  N_Vector y = N_VNew_Serial(NEQ, ctx);
  init_state(m, y);
  void *fast = ARKStepCreate(rhs_part1, NULL, 0.0, y, ctx);
  ARKStepSetUserData(fast, &pb);
  ARKStepSetErrHandlerFn(fast, quiet_errors, NULL);
  ARKStepSetOrder(fast, 3);
  ARKStepSetFixedStep(fast, h_fast);
  ARKStepSetMaxNumSteps(fast, 1000000);
  MRIStepInnerStepper inner = NULL;
  ARKStepCreateMRIStepInnerStepper(fast, &inner);
  void *mri = MRIStepCreate(rhs_part0, NULL, 0.0, y, inner, ctx);
  MRIStepSetUserData(mri, &pb);
  MRIStepSetErrHandlerFn(mri, quiet_errors, NULL);
  MRIStepSetOrder(mri, 3);
  long per_sample = (long)ceil(T_END / NSAMPLE / h_slow);
  r->h = T_END / NSAMPLE / per_sample;
  MRIStepSetFixedStep(mri, r->h);
  const double *py = N_VGetArrayPointer(y);
  realtype t = 0;
  const double t0 = wall_seconds(), c0 = cpu_seconds();
  for (int k = 1; k <= NSAMPLE && !r->failed; k++) {
    for (long j = 0; j < per_sample && !r->failed; j++) {
      r->failed = MRIStepEvolve(mri, k * (T_END / NSAMPLE), y, &t, ARK_ONE_STEP) < 0;
      if (!isfinite(py[END_NODE - 1])) r->failed = 1;
    }
    r->obs[k] = py[END_NODE - 1] - m->x0[END_NODE];
    if (!obs_ok(r->obs[k])) r->failed = 1;
  }
  r->wall = wall_seconds() - t0;
  r->cpu = cpu_seconds() - c0;
  MRIStepGetNumSteps(mri, &r->steps);
  long nfsi;
  MRIStepGetNumRhsEvals(mri, &r->nfe, &nfsi);
  long nffi;
  ARKStepGetNumRhsEvals(fast, &r->nfi, &nffi);
  ARKStepGetNumSteps(fast, &r->fast_steps);
  MRIStepFree(&mri);
  MRIStepInnerStepper_Free(&inner);
  ARKStepFree(&fast);
  N_VDestroy(y);
}

/* ---- what the callbacks cost on their own, to separate SUNDIALS's share */
typedef struct { double part[2], jac; } CallbackCost; /* s per call */

static double time_calls(Problem *pb, int which, SUNMatrix J, N_Vector y, N_Vector ydot) {
  enum { CALLS = 100000 };
  double reps[NREP];
  for (int rep = 0; rep < NREP; rep++) {
    const double t0 = cpu_seconds();
    for (int i = 0; i < CALLS; i++) {
      const double t = 1e-6 * i;
      if (which == 2) jac_part1(t, y, ydot, J, pb, ydot, ydot, ydot);
      else if (which == 1) rhs_part1(t, y, ydot, pb);
      else rhs_part0(t, y, ydot, pb);
    }
    reps[rep] = (cpu_seconds() - t0) / CALLS;
  }
  return median(reps, NREP);
}

static CallbackCost callback_cost(Problem *pb, SUNContext ctx) {
  N_Vector y = N_VNew_Serial(NEQ, ctx), ydot = N_VNew_Serial(NEQ, ctx);
  SUNMatrix J = SUNDenseMatrix(NEQ, NEQ, ctx);
  init_state(pb->m, y);
  CallbackCost c = {{time_calls(pb, 0, J, y, ydot), time_calls(pb, 1, J, y, ydot)},
                    time_calls(pb, 2, J, y, ydot)};
  SUNMatDestroy(J);
  N_VDestroy(ydot);
  N_VDestroy(y);
  return c;
}

/* ---- the report */
static double max_error(const Run *r, const Run *ref) {
  double e = 0;
  for (int k = 0; k <= NSAMPLE; k++) e = fmax(e, fabs(r->obs[k] - ref->obs[k]));
  return e;
}

/* Richardson: the Verlet runs' error is first order in h here (the kick
 * takes the dashpot at the old velocity), so 2 V(h/2) - V(h) is O(h^2). */
static void richardson(Run *out, const Run *fine, const Run *coarse) {
  *out = *fine;
  for (int k = 0; k <= NSAMPLE; k++) out->obs[k] = 2 * fine->obs[k] - coarse->obs[k];
}

/* Repeats a run NREP times; *r keeps the last, with the median wall and
 * CPU times. */
#define TIMED(r, call)                                                     \
  do {                                                                     \
    double walls_[NREP], cpus_[NREP];                                      \
    for (int rep_ = 0; rep_ < NREP; rep_++) {                              \
      call;                                                                \
      walls_[rep_] = (r)->wall, cpus_[rep_] = (r)->cpu;                    \
    }                                                                      \
    (r)->wall = median(walls_, NREP), (r)->cpu = median(cpus_, NREP);      \
  } while (0)

/* One table row; cc (NULL for Verlet) gives SUNDIALS's own time: the run's
 * CPU time less the callbacks it made, each at its CPU cost measured alone. */
static void row(const char *scheme, const Run *r, const Run *ref, const CallbackCost *cc, int mri) {
  if (r->failed) {
    printf("| %s | %.3g | - | unstable | - | - | - | - | - |\n", scheme, 1e6 * r->h);
    return;
  }
  char h[32];
  if (r->h > 0) snprintf(h, sizeof h, "%.3g", 1e6 * r->h);
  else snprintf(h, sizeof h, "%.3g (mean)", 1e6 * T_END / r->steps);
  printf("| %s | %s | %ld | %.2g | %.3g | %.3g | ", scheme, h, r->steps, 1e6 * max_error(r, ref),
         1e3 * r->wall / T_END, 1e3 * r->cpu / T_END);
  if (!cc) {
    printf("1 | - | - |\n");
    return;
  }
  const double callbacks = r->nfe * cc->part[0] + r->nfi * cc->part[1] + r->jevals * cc->jac;
  const double own = r->cpu - callbacks;
  if (mri)
    printf("%.1f slow + %.1f fast (%.1f fast steps) | - | ", (double)r->nfe / r->steps,
           (double)r->nfi / r->steps, (double)r->fast_steps / r->steps);
  else
    printf("%.1f fe + %.1f fi | %.2f | ", (double)r->nfe / r->steps, (double)r->nfi / r->steps,
           (double)r->newton / r->steps);
  printf("%.3g (%.0f%%) |\n", 1e6 * own / r->steps, 100 * own / r->cpu);
}

#ifndef EVAL_SUNDIALS_BUILD
#define EVAL_SUNDIALS_BUILD "as linked"
#endif

int main(void) {
  static Model model;
  model_build(&model);
  const Model *m = &model;
  const Limits lim = stable_limits(m);
  const double h_stable = fmin(lim.damper, lim.elastic);
  const double h_a = 0.9 * h_stable, h_tendon = 0.9 * lim.elastic;
  double fil_mass = 0;
  for (int i = FIL_FIRST; i <= FIL_LAST; i++) fil_mass += m->mass[i];
  printf("SUNDIALS %s (%s).\n", SUNDIALS_VERSION, EVAL_SUNDIALS_BUILD);
  printf("Model: filament %.4g kg, end nodes %.3g kg (mu = %.3g kg), c_max = %.4g N s/m;\n",
         fil_mass, m->mass[FIL_FIRST], lim.mu, lim.c_max);
  printf("explicit limits: Hill damper 2 mu / c = %.4g us, elastic 2 / omega_max = %.4g us.\n",
         1e6 * lim.damper, 1e6 * lim.elastic);

  SUNContext ctx;
  if (SUNContext_Create(NULL, &ctx)) {
    fprintf(stderr, "eval_sundials: SUNContext_Create failed\n");
    return 1;
  }
  /* the reference, and how good it is: Verlet at h/20 and h/40, extrapolated;
   * the same from h/40 and h/80 bounds the extrapolation's own error */
  static Run v20, v40, v80, ref, ref_fine, r;
  run_verlet(m, 0, h_stable / 20, &v20);
  run_verlet(m, 0, h_stable / 40, &v40);
  run_verlet(m, 0, h_stable / 80, &v80);
  richardson(&ref, &v40, &v20);
  richardson(&ref_fine, &v80, &v40);
  printf("Reference: explicit Verlet at h/20 = %.4g us and h/40, Richardson-extrapolated; "
         "Verlet at h/20 alone is %.2g um from it, the extrapolation from h/40 and h/80 %.2g um.\n",
         1e6 * v20.h, 1e6 * max_error(&v20, &ref), 1e6 * max_error(&ref_fine, &ref));
  printf("End mass: %.4g mm at 0.1 s, %.4g mm at 0.2 s (positive: distal).\n",
         1e3 * ref.obs[NSAMPLE / 2], 1e3 * ref.obs[NSAMPLE]);

  /* how far explicit Verlet runs in practice: the shortening filament's
   * slope is below c_max for most of the run */
  double lo = h_stable, hi = 8 * h_stable;
  for (int it = 0; it < 12; it++) {
    run_verlet(m, 0, 0.5 * (lo + hi), &r);
    if (r.failed) hi = 0.5 * (lo + hi); else lo = 0.5 * (lo + hi);
  }
  printf("Explicit Verlet on this run stays bounded up to h = %.3g us (%.2f x the worst-case limit).\n",
         1e6 * lo, lo / h_stable);

  /* the largest fixed steps ARK3 (Hill implicit) and MRIStep's slow method
   * survive on this run, for comparison with Verlet's 2 / omega_max */
  lo = h_tendon, hi = 4 * lim.elastic;
  for (int it = 0; it < 8; it++) {
    ArkConfig cfg = {0, 3, 0, 0.5 * (lo + hi), 0, 0};
    run_ark(m, ctx, &cfg, &r);
    if (r.failed) hi = 0.5 * (lo + hi); else lo = 0.5 * (lo + hi);
  }
  printf("ARKStep ARK3 (Hill implicit) at fixed steps stays bounded up to h = %.3g us (%.2f x 2 / omega_max).\n",
         1e6 * lo, lo / lim.elastic);
  lo = 5 * h_a, hi = h_tendon;
  for (int it = 0; it < 8; it++) {
    run_mri(m, ctx, 0.5 * (lo + hi), h_a, &r);
    if (r.failed) hi = 0.5 * (lo + hi); else lo = 0.5 * (lo + hi);
  }
  printf("MRIStep's slow step stays bounded up to h = %.3g us (%.2f x 2 / omega_max).\n\n",
         1e6 * lo, lo / lim.elastic);

  const double steps_b[3] = {2 * h_a, 5 * h_a, h_tendon};
  const char *label_b[3] = {"2x", "5x", "tendon limit"};
  Problem pb_hill = {.m = m}, pb_joint = {.m = m}, pb_mri = {.m = m};
  ark_parts(&pb_hill, 0);
  ark_parts(&pb_joint, SPRING_JOINT);
  mri_parts(&pb_mri);
  const CallbackCost cc_hill = callback_cost(&pb_hill, ctx), cc_joint = callback_cost(&pb_joint, ctx),
                     cc_mri = callback_cost(&pb_mri, ctx);
  char name[128];

  printf("| scheme | h (us) | steps | max error (um) | wall per simulated s (ms) | CPU per simulated s (ms) "
         "| rhs evaluations per step | Newton iterations per step | SUNDIALS's own CPU time per step (us, share) |\n");
  printf("|---|---|---|---|---|---|---|---|---|\n");
  TIMED(&r, run_verlet(m, 0, h_a, &r));
  row("(a) explicit Verlet, 0.9 x stable", &r, &ref, NULL, 0);
  for (int i = 0; i < 3; i++) {
    TIMED(&r, run_verlet(m, 1, steps_b[i], &r));
    snprintf(name, sizeof name, "(b) imex Verlet, %s", label_b[i]);
    row(name, &r, &ref, NULL, 0);
  }
  for (int i = 0; i < 3; i++) {
    ArkConfig cfg = {0, 3, 0, steps_b[i], 0, 0};
    TIMED(&r, run_ark(m, ctx, &cfg, &r));
    snprintf(name, sizeof name, "(c) ARKStep ARK3, Hill implicit, %s", label_b[i]);
    row(name, &r, &ref, &cc_hill, 0);
  }
  for (int i = 0; i < 3; i++) {
    ArkConfig cfg = {SPRING_JOINT, 3, 0, steps_b[i], 0, 0};
    TIMED(&r, run_ark(m, ctx, &cfg, &r));
    snprintf(name, sizeof name, "(c) ARKStep ARK3, Hill + joints implicit, %s", label_b[i]);
    row(name, &r, &ref, &cc_joint, 0);
  }
  {
    ArkConfig cfg = {0, 3, 1, h_tendon, 0, 0};
    TIMED(&r, run_ark(m, ctx, &cfg, &r));
    row("(c) ARKStep ARK3, Hill implicit, DQ Jacobian, tendon limit", &r, &ref, &cc_hill, 0);
  }
  /* adaptive: the brief's tolerances for both orders, and a looser pair */
  const struct { int order; double rtol, atol; } adaptive[3] = {{3, 1e-6, 1e-9}, {4, 1e-6, 1e-9}, {3, 1e-4, 1e-7}};
  for (int i = 0; i < 3; i++) {
    ArkConfig cfg = {0, adaptive[i].order, 0, 0, adaptive[i].rtol, adaptive[i].atol};
    TIMED(&r, run_ark(m, ctx, &cfg, &r));
    snprintf(name, sizeof name, "(c) ARKStep ARK%d, Hill implicit, adaptive rtol %g atol %g",
             adaptive[i].order, adaptive[i].rtol, adaptive[i].atol);
    row(name, &r, &ref, &cc_hill, 0);
  }
  for (int i = 0; i < 3; i++) {
    TIMED(&r, run_mri(m, ctx, steps_b[i], h_a, &r));
    snprintf(name, sizeof name, "(d) MRIStep, slow %s, fast ERK3 at (a)'s h", label_b[i]);
    row(name, &r, &ref, &cc_mri, 1);
  }
  printf("\nCallbacks alone (ARK, Hill implicit): explicit rhs %.0f ns, implicit rhs %.0f ns, "
         "Jacobian %.0f ns; wall times are medians of %d runs.\n",
         1e9 * cc_hill.part[0], 1e9 * cc_hill.part[1], 1e9 * cc_hill.jac, NREP);
  SUNContext_Free(&ctx);
  return 0;
}
