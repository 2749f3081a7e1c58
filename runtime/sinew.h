/* sinew.h — the public interface of libsinewrt, the Cosserat rod runtime.
 *
 * Design.  A scene is described by a mutable swSpec (rods, loads, boundary
 * conditions, options), compiled once by sw_compile() into an immutable swModel
 * (flat arrays sized once, every derived constant precomputed), and simulated
 * in a mutable swData (positions, directors, velocities, time, scratch).  Every
 * kernel has the shape  f(const swModel *m, swData *d)  and nothing allocates
 * inside a step.
 *
 * Layout (docs/runtime.md, "Layout").  Nodes, elements and Voronoi domains of
 * all rods share one index space of slots, rods back to back (elastic rods
 * first, then rigid ones): rod r of n elements owns the n + 1 slots
 * [node_adr[r], node_adr[r] + n]; node i is slot node_adr[r] + i, element i is
 * slot elem_adr[r] + i and Voronoi domain j is slot vor_adr[r] + j, with
 * node_adr[r] == elem_adr[r] == vor_adr[r].  The last slot of a rod is a ghost
 * element and its last two slots ghost domains: they hold neutral values
 * (zero stiffness and load, unit lengths, identity frames) so that a kernel
 * can run one loop over all slots, as PyElastica's block layout does.  Arrays
 * are structure-of-arrays: a per-slot vector is three planes of m->stride
 * doubles and a frame nine, so component k of slot i is a[k * stride + i]
 * (SW_AT below) and entry (row a, column b) of a frame is plane 3a + b.
 * Vectors are 3-vectors, director frames are 3x3 matrices Q whose rows are
 * d1, d2, d3 in the lab frame (Gazzola et al. 2018, sec. 2), so Q maps lab
 * components to material ones; sw_get3/sw_getQ gather one slot's into a
 * plain double[3] or row-major double[9].
 *
 * This header is all that the compiler's generated C may include.
 */
#ifndef SINEW_H
#define SINEW_H

#include <math.h>     /* generated code computes param-dependent values with sqrt, pow, sin */
#include <stddef.h>
#include <stdio.h>

#define SW_VERSION "0.1.0"

/* Status codes; they double as the process exit codes of SPEC.md. */
enum {
  SW_OK = 0,
  SW_EMODEL = 1,    /* the scene is invalid (bad sizes, materials, indices) */
  SW_EUSAGE = 2,    /* bad call or command-line argument */
  SW_EUNSTABLE = 3, /* the simulation became unstable */
  SW_EIO = 4,       /* file could not be written */
  SW_EEXPECT = 5,   /* an expect of the model (or --compare) failed */
  SW_EINTERRUPT = 130 /* stopped by SIGINT; output is valid up to the last frame */
};

/* SW_IMEX: position Verlet with the stiff terms linearly implicit (integrate.c):
 * the muscle filaments' Hill damping, solved per filament in closed form, so
 * it sets no stable-dt limit.  The rest of the loads stay explicit. */
typedef enum { SW_VERLET = 0, SW_PEFRL = 1, SW_IMEX = 2 } swIntegrator;
enum { SW_FIL_IMPLICIT = 1, SW_FIL_HELD_START = 2, SW_FIL_HELD_END = 4 }; /* swModel.fil_implicit */
typedef enum { SW_DAMP_NONE = 0, SW_DAMP_LINEAR = 1, SW_DAMP_ANALYTIC = 2 } swDampingKind;

/* The rods' constitutive law (rod.c).  SW_LAW_GAZZOLA is the law of Gazzola
 * et al. 2018 and PyElastica: n = S^ (s - s0) / e, c = B^ (k - k0) / eps^3,
 * whose stiffness follows the cross-section as the rod stretches; it is not
 * the gradient of an energy.  SW_LAW_VARIATIONAL is the hyperelastic law of
 * the energy sw_energy reports, sum l^ (s-s0).S^(s-s0)/2 + D^ (k-k0).B^(k-k0)/2:
 * every internal force and couple is its exact negative gradient. */
typedef enum { SW_LAW_GAZZOLA = 0, SW_LAW_VARIATIONAL = 1 } swLaw;

/* ---- time signals: scalar functions of time that scale loads and BCs ---- */
typedef enum {
  SW_SIG_CONST = 0, /* value = a                                              */
  SW_SIG_RAMP,      /* a -> b linearly over [t0, t0+T], constant outside       */
  SW_SIG_SINE,      /* a + b sin(2 pi f (t - t0) + phase)                      */
  SW_SIG_STEP,      /* a before t0, b from t0 on                               */
  SW_SIG_TABLE,     /* piecewise linear through (times[k], values[k]), clamped */
  SW_SIG_BSPLINE    /* clamped cubic B-spline with coefficients values[0..npts)
                       on uniform knots over [t0, t0+T], constant outside   */
} swSignalKind;

#define SW_SIGNAL_MAXPTS 64
typedef struct {
  swSignalKind kind;
  double a, b, t0, T, freq, phase;
  double period;                     /* > 0: periodic, s(t) = s(t0 + (t - t0) mod period) */
  int npts;                          /* SW_SIG_TABLE and SW_SIG_BSPLINE   */
  double times[SW_SIGNAL_MAXPTS];    /* strictly increasing               */
  double values[SW_SIGNAL_MAXPTS];
} swSignal;

swSignal sw_signal_const(double value);
swSignal sw_signal_ramp(double from, double to, double t0, double duration);
swSignal sw_signal_sine(double mean, double amplitude, double freq_hz, double phase, double t0);
swSignal sw_signal_step(double before, double after, double t0);
/* Clamped cubic B-spline through coefficients c[0..n) (4 <= n <= 64) on
 * uniform knots over [t0, t0 + duration]: c[0] before t0, c[n-1] after. */
swSignal sw_signal_bspline(const double *c, int n, double t0, double duration);
/* The same signal repeated with `period` (> 0) from its t0 on. */
swSignal sw_signal_periodic(swSignal s, double period);
double sw_signal_eval(const swSignal *s, double t);

/* ---- scene description ---- */
typedef struct {
  const char *name;           /* used in output and error messages        */
  int nelem;                  /* number of elements n (nodes n+1)         */
  double start[3];            /* position of node 0, m                    */
  double direction[3];        /* tangent d3 of the straight rest shape    */
  double normal[3];           /* d1; made orthogonal to direction         */
  double length;              /* rest length, m                           */
  double radius_start;        /* radius at element 0 and element n-1, m;  */
  double radius_end;          /* linear taper in between                  */
  double density;             /* kg/m^3                                   */
  double youngs;              /* E, Pa                                    */
  double shear_modulus;       /* G, Pa; 0 means E / (2 (1 + poisson))     */
  double poisson;             /* used only when shear_modulus == 0        */
  double shear_hardening;     /* multiplies G in S11, S22 (> 0; 1 = none) */
  double twist_hardening;     /* multiplies G in B33 (> 0; 1 = none)      */
  double rest_kappa[3];       /* uniform rest curvature/twist, 1/m        */
  double rest_sigma[3];       /* uniform rest shear/stretch strain        */
  swDampingKind damping;
  double gamma;               /* force dissipation, kg m^-1 s^-1 (Zhang 2019) */
  double gamma_rot;           /* couple dissipation per unit length, N s/rad:
                                 c = -gamma_rot w (Gazzola 2018's rotational
                                 dissipation); < 0 (the default): gamma I_k / A,
                                 so rotation decays at translation's rate   */
  swLaw law;                  /* constitutive law (0: Gazzola 2018)       */
  int rigid;                  /* 1: the rod moves as one rigid body (rigid.c):
                                 no deformation, so its stiffness sets no
                                 stable-dt limit; mass and inertia as if it
                                 were elastic                               */
  int implicit;               /* 1: under SW_IMEX the rod's elasticity (shear,
                                 stretch, bending, twist) and linear damping
                                 are linearly implicit (rod_implicit.c), so
                                 its stiffness sets no stable-dt limit;
                                 explicit under the other integrators       */
  int weightless;             /* 1: gravity does not act on the rod (mass
                                 and inertia stay): a rig whose weight the
                                 model leaves out, as PyElastica's snakes put
                                 gravity on the body only                   */
  /* What the rod is, for the output's /rods/NAME group only (copied; NULL:
   * not written): its tissue ("bone", "tendon", "muscle filament", "rod"),
   * its material's name and the model line that made it ("arm.sinew:12"). */
  const char *kind, *material, *where;
} swRodDesc;

typedef enum { SW_LOAD_FORCE = 0, SW_LOAD_TORQUE = 1 } swLoadKind;
typedef struct {
  swLoadKind kind;
  int rod;
  int index;         /* node for forces, element for torques; -1 = last  */
  double vec[3];     /* N or N m, lab frame, multiplied by the signal     */
  swSignal signal;
} swLoadDesc;

typedef enum {
  SW_BC_CLAMP = 0,     /* end node and end element held in place           */
  SW_BC_VELOCITY = 1,  /* end node velocity = vec * signal(t), lab frame   */
  SW_BC_OMEGA = 2      /* end element angular velocity = vec*signal, lab  */
} swBCKind;
typedef struct {
  swBCKind kind;
  int rod;
  int end;           /* 0 = start (node 0, element 0), 1 = end             */
  double vec[3];
  swSignal signal;
} swBCDesc;

/* A rod's description for the output (owned copies of swRodDesc's kind,
 * material and where; NULL: not given). */
typedef struct {
  char *kind, *material, *where;
  double youngs, shear_modulus, density;  /* Pa, Pa (G, before hardening), kg/m^3 */
  double length;                          /* rest length, m                   */
} swRodInfo;

typedef struct swSpec swSpec;
swSpec *sw_spec_new(void);
void sw_spec_free(swSpec *s);
void sw_rod_desc_init(swRodDesc *r);        /* fills defaults */
int sw_spec_add_rod(swSpec *s, const swRodDesc *r);      /* returns rod id */
int sw_spec_add_load(swSpec *s, const swLoadDesc *l);
int sw_spec_add_bc(swSpec *s, const swBCDesc *b);
void sw_spec_set_gravity(swSpec *s, const double g[3]);
void sw_spec_set_integrator(swSpec *s, swIntegrator integ);
void sw_spec_set_dt(swSpec *s, double dt);
/* Rest shape override for rod r: node positions (n+1)x3 and element directors
 * n x 9 (rows d1 d2 d3).  Optional; default is the straight rod. */
int sw_spec_set_rest_shape(swSpec *s, int rod, const double *x, const double *Q);

/* ---- joints (joint.c): penalty connections between rod nodes ----
 * A joint ties node `node_a` of rod `rod_a` to node `node_b` of rod `rod_b`,
 * or, when rod_b < 0, to the fixed point `anchor` in space (a rod hung on a
 * hinge).  Node index -1 means the last node.  The positional constraint is a
 * spring-damper on the gap (Zhang et al. 2019, Methods, "joints"); a hinge
 * adds a couple that keeps the axis, carried in the material frame of each
 * connected element (in space when anchored), common to both, so only the
 * rotation about it is free (U = k_t (1 - a_a . a_b)); a fixed joint adds a
 * couple that holds the relative rotation of the two elements at its initial
 * value.  docs/physics.md, "Joints". */
typedef enum { SW_JOINT_SPHERICAL = 0, SW_JOINT_HINGE = 1, SW_JOINT_FIXED = 2 } swJointKind;
typedef struct {
  const char *name;         /* used in output and error messages            */
  swJointKind kind;
  int rod_a, node_a;        /* node -1 = last node of the rod               */
  int rod_b, node_b;        /* rod_b = -1: anchored to `anchor`             */
  double anchor[3];         /* m, lab frame (rod_b < 0 only)                */
  double axis[3];           /* hinge axis, lab frame at t = 0               */
  double stiffness;         /* k, N/m, positional penalty                   */
  double damping;           /* nu, N s/m                                    */
  double rot_stiffness;     /* k_t, N m / rad, hinge and fixed couples      */
  double rot_damping;       /* N m s / rad                                  */
  int undamped;             /* 1: no damping at all (damping, rot_damping   */
                            /* must then be 0; 0 otherwise means "choose")  */
  /* limits (joint.c, "Limits"): a one-sided penalty couple outside them   */
  int has_range;            /* 1: the hinge angle is held in the range      */
  double angle_min, angle_max; /* rad, hinge angle (its convention, joint.c) */
  double cone;              /* rad, spherical: largest swing of rod b's     */
                            /* tangent from its t = 0 direction relative to */
                            /* rod a (anchored: rod a's tangent from its    */
                            /* t = 0 direction); 0 = no cone, < pi          */
  double limit_stiffness;   /* k_l, N m / rad; 0 = choose                   */
  double limit_damping;     /* c_l, N m s / rad; 0 = choose                 */
} swJointDesc;
/* sw_joint_desc_init: spherical, rod_a 0 node -1 to anchor (0,0,0) (rod_b -1,
 * node_b 0), no limits, and 0 for stiffness, damping, rot_stiffness,
 * rot_damping, limit_stiffness and limit_damping,
 * which sw_compile replaces by values derived from the connected elements
 * (joint.c explains them; the compiled model->joint holds the values used). */
void sw_joint_desc_init(swJointDesc *j);    /* fills defaults */
int sw_spec_add_joint(swSpec *s, const swJointDesc *j);  /* returns joint id */

/* ---- muscles (muscle.c): bundles of contracting filaments ----
 * A muscle is N filaments, each a Cosserat rod standing for a group of motor
 * units, laid from `start` to `end` and tied there to the attachment rods by
 * spherical joints (Zhang et al. 2019, Suppl. Note 1).  By the size principle
 * the filament cross-sections A_k grow geometrically from the smallest to the
 * largest (ratio `size_ratio`, summing to A = pi radius^2), peak force is
 * sigma_max A_k, and the activation time constant falls linearly from
 * twitch_small to twitch_large.  Each filament pulls on its nodes along its
 * elements with one tension T_k (uniform along it), computed from its
 * stretch eta = l / l0 and strain rate (docs/physics.md, "Muscles"):
 *   F_qs = a_k f_act(eta) F_max,k + F_max,k p(eta)      Suppl. eqs. 3-4
 *   T_k  = F_qs - zeta(v) v / l0,  v = -dl/dt             Suppl. eq. 5 (Hill)
 * The muscle's activation u(t) recruits filaments smallest first: filament k
 * is driven by clamp((u - C_{k-1}) / (C_k - C_{k-1}), 0, 1) with C_k the
 * cumulative share of peak force, so the bundle's peak force is u F_max. */
#define SW_MUSCLE_MAX_VIA 8
typedef struct {
  const char *name;           /* output group /muscles/NAME, rods NAME.f01..  */
  int filaments;              /* N >= 1                                       */
  int motor_units;            /* total motor units (0 = one per filament)     */
  int nelem;                  /* elements of each filament (>= 2)             */
  double start[3], end[3];    /* attachment points at t = 0, m                */
  double normal[3];           /* d1 of the filaments                          */
  double radius;              /* whole muscle at rest, A = pi radius^2, m     */
  double density, youngs, shear_modulus, poisson; /* filament tissue (as rods) */
  double shear_hardening, twist_hardening;
  swLaw law;                  /* the filaments' constitutive law              */
  int weightless;             /* 1: gravity does not act on the filaments     */
  swDampingKind damping;      /* rod dissipation of each filament             */
  double gamma;
  double sigma_max;           /* peak isometric stress, Pa                    */
  double size_ratio;          /* largest / smallest filament section, >= 1    */
  double twitch_small;        /* s: activation time constant of the smallest  */
  double twitch_large;        /*    and of the largest filament; 0 = instant  */
  double hill_a;              /* Hill's a / F_qs (0.16, Hill 1938)            */
  double v_max;               /* maximum shortening rate v0 / l0, 1/s (6)      */
  double fibre_diameter;      /* m (75 um): fibre counts in --info only       */
  swSignal activation;        /* u(t), clamped to [0, 1]                      */
  int attach_rod[2];          /* rod tied to start / end (-1: not tied)       */
  int attach_node[2];         /* node of that rod (-1 = last)                 */
  double attach_stiffness;    /* N/m per filament end; 0 = 100 F_max,k / l0  */
  double attach_damping;      /* N s/m per filament end; 0 = choose (joint.c) */
  /* Via points (muscle_via.c): the filaments are laid along the polyline
   * start -> via[0] -> ... -> end and each via point is a frictionless ring
   * they slide through.  via[k] is the point at t = 0 (lab, m); it moves
   * and turns with the element of rod via_rod[k] nearest to it (a point off
   * the centreline keeps its offset in that element's material frame), or
   * stays fixed in space when via_rod[k] is -1. */
  int nvia;                           /* 0 .. SW_MUSCLE_MAX_VIA             */
  double via[SW_MUSCLE_MAX_VIA][3];
  int via_rod[SW_MUSCLE_MAX_VIA];
  double via_stiffness;       /* N/m per filament ring; 0 = 100 F_max,k / l0  */
  double via_damping;         /* N s/m per filament ring; 0 = choose          */
  /* For the output only, given to its filament rods (swRodDesc): its
   * material's name and the model line; NULL: not written. */
  const char *material, *where;
} swMuscleDesc;
void sw_muscle_desc_init(swMuscleDesc *md);  /* fills defaults */
/* Adds the filaments as rods [nrod, nrod + filaments), smallest first, named
 * NAME.f01, NAME.f02, ..., and for each tied end a spherical joint named
 * NAME.f01.start / NAME.f01.end; returns the muscle id (-1: out of memory). */
int sw_spec_add_muscle(swSpec *s, const swMuscleDesc *md);
/* Filament k (0-based, smallest first) of muscle `muscle` is passive (an
 * injured motor unit): it keeps its tissue and membrane but never contracts. */
int sw_spec_set_filament_passive(swSpec *s, int muscle, int filament);
/* The reference's fits (Suppl. eq. 3): f_act(eta), the active force factor,
 * and p(eta) = E_membrane(eta) A (eta - 1) / F_max, the passive factor. */
double sw_muscle_f_act(double eta);
double sw_muscle_f_pass(double eta);

/* ---- environments: ground and terrain, fluids, rod-rod contact, the
 * travelling torque wave, probes (environment.c keeps the lists and compiles
 * them; ground.c, fluid.c, contact.c, wave.c and probe.c are the kernels;
 * docs/physics.md, "Environments").  Each description that lists rods copies
 * the list (rods[0..nrods), runtime rod ids) when it is added; nrods = 0
 * means every rod of the scene. ---- */

/* Terrain height z = h(x, y), lab frame, z up, m; fills grad with
 * (dh/dx, dh/dy).  `ctx` is the description's height_ctx (the generated
 * simulator passes its param values). */
typedef double (*swHeightFn)(double x, double y, double grad[2], const void *ctx);

/* A ground: the half space below a plane (height == NULL) or below the
 * terrain z = height(x, y).  Elements touching it feel a penalty response
 * along the surface normal (stiffness k_w and damping gamma_w, Gazzola et
 * al. 2018, sec. 4.3) and anisotropic Coulomb friction against their slip:
 * coefficients forward (along the element tangent d3), backward (against it)
 * and sideways, kinetic and static, blended by the slip-velocity tolerance;
 * optional rolling friction. */
typedef struct {
  const char *name;
  double origin[3];         /* a point of the plane, m (plane only)          */
  double normal[3];         /* out of the ground (plane only; normalised)    */
  swHeightFn height;        /* terrain: z = height(x, y); NULL: the plane     */
  const void *height_ctx;
  double stiffness;         /* k_w, N/m per element                          */
  double damping;           /* gamma_w, kg/s per element                     */
  double mu_kinetic[3];     /* forward, backward, sideways (>= 0)            */
  double mu_static[3];      /* forward, backward, sideways (>= 0; 0: none)   */
  double mu_rolling;        /* rolling friction coefficient (>= 0; 0: none)  */
  int contact_point;        /* 1: sideways friction acts at the contact point
                               r below the axis, against that point's slip,
                               so it rolls the rod and its twist resists;
                               0: at the centreline (no couple)              */
  double slip_velocity;     /* v_eps, m/s, below which friction is static    */
  int nrods;                /* rods it acts on (0: all)                      */
  const int *rods;
  double contact_tolerance; /* m: an element whose gap exceeds its radius by
                               up to this still touches (the balance, damper
                               and friction act, the penalty starts at the
                               radius), so round-off cannot lift a resting
                               rod; 0: 1e-6 of the element's radius          */
} swGroundDesc;
void sw_ground_desc_init(swGroundDesc *g);   /* fills defaults */
int sw_spec_add_ground(swSpec *s, const swGroundDesc *g);   /* returns its id */

/* A fluid acting on the elements of its rods (fluid.c): drag on each
 * element's velocity relative to the flow, quadratic drag on the area the
 * element shows the flow (2 r l |sin| plus the rod's end caps), and
 * buoyancy (docs/physics.md, "Fluids"). */
typedef enum {
  SW_FLUID_STOKES = 0,      /* slender-body Stokes drag, Zhang 2019 Suppl. eq. 1 */
  SW_FLUID_QUADRATIC = 1    /* quadratic (Morison) drag, Zhang 2019 Suppl. eq. 2 */
} swFluidModel;
typedef struct {
  const char *name;
  swFluidModel model;
  double viscosity;         /* mu, Pa s (Stokes)                             */
  double density;           /* rho_f, kg/m^3 (quadratic drag, buoyancy)      */
  double drag_coefficient;  /* C_d (quadratic)                               */
  double body_length;       /* L of ln(L / r) (Stokes); 0: each rod's length */
  double velocity[3];       /* uniform background flow, m/s                  */
  int buoyancy;             /* 1: buoyancy -rho_f V g on each element        */
  int nrods;                /* rods immersed (0: all)                        */
  const int *rods;
} swFluidDesc;
void sw_fluid_desc_init(swFluidDesc *f);     /* fills defaults */
int sw_spec_add_fluid(swSpec *s, const swFluidDesc *f);

/* Rod-rod contact among a set of rods: every pair of elements of different
 * rods, and, with `self`, pairs within one rod that are not neighbours along
 * it, whose centrelines come closer than the sum of their radii repel with
 * k_c times the overlap plus gamma_c times the approach speed (Zhang et al.
 * 2019, Suppl. Table 4); a broad phase keeps far pairs out. */
typedef struct {
  const char *name;
  double stiffness;         /* k_c, N/m                                      */
  double damping;           /* gamma_c, kg/s                                 */
  int self;                 /* 1: also within each rod                       */
  int nrods;                /* rods in contact (0: all)                      */
  const int *rods;
} swContactDesc;
void sw_contact_desc_init(swContactDesc *c); /* fills defaults */
int sw_spec_add_contact(swSpec *s, const swContactDesc *c);

/* The travelling muscle-torque wave of Gazzola et al. 2018 (sec. 4.3):
 *   tau(s, t) = ramp(t) beta(s) sin(2 pi t / T - 2 pi s / lambda + phi),
 * ramp(t) = min(1, t / ramp) (1 when ramp = 0).  tau is a bending moment,
 * N m (not per unit length): the couple the muscles hold across the
 * cross-section at s, about `direction` (body-fixed: the axis each element
 * had at t = 0, turning with it; wave.c), so a rod at rest under it takes
 * the curvature tau / (E I) about that axis.  beta is the clamped cubic B-spline with coefficients
 * `coef` on uniform knots over s in [0, L] (beta(0) = coef[0], beta(L) =
 * coef[ncoef-1]); the coefficients are in N m, unscaled, as in Gazzola 2018,
 * Zhang 2019 (Suppl. Fig. 12) and PyElastica's MuscleTorques.  s runs from
 * the rod's start, or from its end with `reverse` (PyElastica's convention,
 * head at the rod's end); the wave travels towards growing s at lambda / T.
 * The moment acts at the rod's interior nodes (none at its free ends), each
 * element getting the difference of the moments at its two ends, so it is
 * an internal couple: no net force or torque on the rod (wave.c). */
#define SW_WAVE_MAXCOEF 32
typedef struct {
  const char *name;
  int rod;
  int ncoef;                /* 4 .. SW_WAVE_MAXCOEF                          */
  double coef[SW_WAVE_MAXCOEF]; /* beta_i, N m (B-spline coefficients)      */
  double wavelength;        /* lambda, m                                     */
  double period;            /* T, s                                          */
  double phase;             /* phi, rad                                      */
  double ramp;              /* s over which the amplitude grows from 0; 0: none */
  double direction[3];      /* couple axis, lab frame at t = 0; turns with
                               each element afterwards (body-fixed)        */
  int reverse;              /* 1: s measured from the rod's end               */
} swWaveDesc;
void sw_wave_desc_init(swWaveDesc *w);       /* fills defaults */
int sw_spec_add_wave(swSpec *s, const swWaveDesc *w);

/* ---- expectations (expect.c): a model as its own golden test ----
 * An expectation bounds one quantity at one time (the step nearest t0) or
 * at every step of a window [t0, t1]; the simulator checks it while it
 * runs and reports at the end (exit SW_EEXPECT when one fails). */
typedef enum {
  SW_EXPECT_JOINT_ANGLE = 0,  /* hinge angle of joint `index`, rad              */
  SW_EXPECT_JOINT_FORCE,      /* magnitude of joint `index`'s force, N          */
  SW_EXPECT_MUSCLE_FORCE,     /* tension of muscle `index` (its filaments'), N  */
  SW_EXPECT_MUSCLE_STRETCH,   /* its stretch l / l0                             */
  SW_EXPECT_PROBE             /* component `component` of probe `index` (0-2: x,
                                 y, z; 3: length); not a mean-velocity probe   */
} swExpectQuantity;
typedef struct {
  const char *text;           /* the expectation as written, for the report    */
  const char *where;          /* "file.sinew:12"                               */
  swExpectQuantity quantity;
  int index, component;
  int window;                 /* 0: at t0; 1: every step of [t0, t1]          */
  double t0, t1;              /* s                                            */
  double lo, hi;              /* bounds, SI                                   */
  double scale;               /* the report shows value / scale ...           */
  const char *unit;           /* ... in this unit ("deg"); "" for none        */
  int reduce;                 /* SW_REDUCE_NONE: a check, as above; otherwise
                                 a reduction of the model's objective, sampled
                                 the same way but neither checked nor reported
                                 (lo, hi unused; evaluate.c reads it)         */
} swExpectDesc;
/* The reductions an objective reads (maximize, minimize, penalty): the value
 * at the step nearest t0, or the time average (trapezoidal rule over the
 * steps of [t0, t1]), the largest or the smallest value over the window. */
enum { SW_REDUCE_NONE = 0, SW_REDUCE_AT, SW_REDUCE_MEAN, SW_REDUCE_MAX, SW_REDUCE_MIN };
void sw_expect_desc_init(swExpectDesc *e);   /* fills defaults */
int sw_spec_add_expect(swSpec *s, const swExpectDesc *e);
/* Observables for /probes/NAME, one row [3] a frame. */
typedef enum {
  SW_PROBE_COM = 0,         /* centre of mass of the rods, m                 */
  SW_PROBE_COM_VELOCITY,    /* its velocity, m/s                             */
  SW_PROBE_MEAN_VELOCITY,   /* displacement of the centre of mass over the
                               last `window` s (or since the previous frame)
                               divided by that time, m/s                     */
  SW_PROBE_NODE             /* position of node `node` of rod `rod` (tip), m */
} swProbeKind;
typedef struct {
  const char *name;
  swProbeKind kind;
  int nrods;                /* rods of the centre of mass (0: all)           */
  const int *rods;
  int rod, node;            /* SW_PROBE_NODE; node -1 = last                 */
  double window;            /* SW_PROBE_MEAN_VELOCITY, s (0: frame interval) */
} swProbeDesc;
void sw_probe_desc_init(swProbeDesc *p);     /* fills defaults */
int sw_spec_add_probe(swSpec *s, const swProbeDesc *p);
#define SW_PROBE_RING 128    /* centre-of-mass samples kept per probe        */

/* ---- the compiled model (immutable) ---- */
typedef struct {
  /* sizes: nnode, nelem and nvor count real nodes, elements and domains;
   * arrays are sized by stride (see Layout at the top) */
  int nrod, nnode, nelem, nvor, nload, nbc, njoint;
  int nslot;                 /* slots of all rods (= nnode)                  */
  int nslot_elastic;         /* slots [0, nslot_elastic) are elastic rods'   */
  int stride;                /* doubles per plane: nslot + 2 rounded up to a
                                multiple of 8 (64-byte rows; a kernel at the
                                last slot reads two past it)               */
  int chunk;                 /* slots per chunk of the threaded kernels: a
                                multiple of 8 fixed by the model alone, so
                                that any thread count splits every loop and
                                every sum the same way (docs/performance.md) */
  /* options */
  double dt;                 /* time step, s                                 */
  swIntegrator integrator;
  double gravity[3];         /* m/s^2                                        */
  /* per rod (nrod) */
  char **rod_name;
  swRodInfo *rod_info;       /* kind, material, where (output.c)             */
  int *rod_nelem;            /* n of each rod                                */
  int *node_adr;             /* first node                                   */
  int *elem_adr;             /* first element                                */
  int *vor_adr;              /* first Voronoi domain                         */
  double *rod_wave_dt;       /* stable dt estimate of each rod, s            */
  swDampingKind *rod_damping;
  /* per node slot; (3) marks three planes of stride */
  double *mass;              /* lumped node mass, kg                         */
  double *weight;            /* the mass gravity acts on: mass, 0 on the
                                nodes of weightless rods; NULL when no rod
                                is weightless (gravity acts on mass)        */
  double *inv_mass;          /* (0 in ghost-free padding)                    */
  double *node_gamma;        /* gamma * Voronoi rest length, kg/s            */
  double *node_decay;        /* analytic damping decay factor                */
  double *node_kick;         /* analytic damping kick length, s              */
  double *x0;                /* (3) initial positions                        */
  /* per element slot (ghost elements: rest lengths 1, stiffness 0) */
  double *rest_len;          /* l^, m                                        */
  double *inv_rest_len;      /* 1 / l^                                       */
  double *radius;            /* m                                            */
  double *shear_stiff;       /* (3) S^ = diag(4GA/3, 4GA/3, EA), N           */
  double *inertia;           /* (3) J^ = rho l^ diag(I1, I2, I3)             */
  double *inv_inertia;       /* (3)                                          */
  double *rest_sigma;        /* (3) rest shear/stretch strain                */
  double *elem_gamma;        /* (3) rotational dissipation, kg m^2/s         */
  double *elem_decay;        /* (3) analytic damping decay factor            */
  double *elem_kick;         /* (3) analytic damping kick length, s          */
  double *Q0;                /* (9) initial directors                        */
  double *clamp_bend;        /* (3) B^ of the element, for clamps            */
  double *elem_ghost;        /* 1 at ghost element slots and padding, else 0  */
  double *elem_variational;  /* 1 on the element and Voronoi slots of rods of
                                SW_LAW_VARIATIONAL, else 0                   */
  double *damp_linear;       /* 1 on the slots of rods with linear damping
                                (loads.c)                                  */
  double *kick_exact;        /* 1 where the kick integrates analytic damping
                                exactly (Verlet, SW_DAMP_ANALYTIC), else 0   */
  /* per Voronoi slot (ghost domains: rest length 1, stiffness 0) */
  double *rest_vor_len;      /* D^, m                                        */
  double *inv_rest_vor_len;  /* 1 / D^                                       */
  double *bend_stiff;        /* (3) B^ = diag(EI1, EI2, GJ), N m^2           */
  double *rest_kappa;        /* (3) 1/m                                      */
  /* loads and boundary conditions */
  swLoadDesc *load;          /* (nload)                                      */
  swBCDesc *bc;              /* (nbc)                                        */
  int bc_slot_order;         /* 1: the conditions' end nodes are in slot order */
  swJointDesc *joint;        /* (njoint), names owned by the model, nodes,
                                stiffness and damping resolved (joint.c)    */
  char **joint_name;         /* (njoint)                                     */
  int *joint_node_a;         /* (njoint)   global node on rod a              */
  int *joint_node_b;         /* (njoint)   global node on rod b, -1 anchored */
  int *joint_elem_a;         /* (njoint)   element of rod a taking couples   */
  int *joint_elem_b;         /* (njoint)   element of rod b, -1 anchored     */
  double *joint_axis_a;      /* (njoint*3) hinge axis, material frame of elem a */
  double *joint_axis_b;      /* (njoint*3) of elem b; lab frame when anchored */
  double *joint_rest_rot;    /* (njoint*9) Q_b Q_a^T at t = 0 (two rods)      */
  double *joint_angle0;      /* (njoint)   hinge angle at t = 0, rad         */
  double *joint_limit_ref;   /* (njoint*9) the limits' reference directions
                                           (joint.c, "Limits")               */
  double *joint_wave_dt;     /* (njoint)   stable dt estimate of each joint  */
  int *joint_implicit;       /* (njoint)   1: between rigid bodies, linearly
                                           implicit (SW_IMEX, rigid_joint.c) */
  int *rigid_block;          /* (nrigid)   the body's block in that system, -1;
                                           numbered group by group           */
  int nrigid_block;          /* bodies in it                                 */
  int nrigid_group;          /* its independent groups: the connected
                                components of the bodies under those joints,
                                one diagonal block of the system each       */
  int *rigid_group_adr;      /* (nrigid_group+1) first block of each group    */
  int *rigid_block_body;     /* (nrigid_block) the body of each block         */
  int *rigid_block_env;      /* (nrigid_block) the earliest block joined to
                                           each, or itself: the envelope     */
  int *rigid_block_reach;    /* (nrigid_block) the last block whose envelope
                                           reaches each, or itself           */
  int *rigid_group_joint_adr; /* (nrigid_group+1) first entry of each group
                                           in rigid_group_joint              */
  int *rigid_group_joint;    /* (implicit joints) each group's joints, in
                                           joint order                       */
  /* rods whose elasticity is linearly implicit (SW_IMEX, rod_implicit.c) */
  int nimplicit;
  int *rod_implicit;         /* (nrod)     1: the rod asks for it (elastic);
                                           it is kicked so when nimplicit > 0 */
  int *implicit_rod;         /* (nimplicit) the rods, in rod order           */
  size_t *implicit_adr;      /* (nimplicit+1) each one's first double in
                                           swData.implicit_sys              */
  /* rigid rods (rigid.c).  A rod with swRodDesc.rigid keeps its nodes and
   * elements in the arrays above and moves as one rigid body b: node
   * x_i = X + R p_i, element frame Q_e = B_e R^T, with R the rotation from the
   * body frame (the principal axes of the inertia tensor) to the lab frame.
   * Body b owns rows [rigid_node_adr[b], +nelem+1) of rigid_p and
   * [rigid_elem_adr[b], +nelem) of rigid_B. */
  int nvariational;          /* rods of SW_LAW_VARIATIONAL (0: rod.c's passes
                                are Gazzola's alone)                        */
  swLaw *rod_law;            /* (nrod)                                       */
  int nrigid;
  int *rod_rigid;            /* (nrod)      rigid body of each rod, -1 elastic */
  int *rigid_rod;            /* (nrigid)    rod of each rigid body            */
  int *rigid_fixed;          /* (nrigid)    1: clamped, never moves           */
  int *rigid_node_adr;       /* (nrigid)    first row in rigid_p              */
  int *rigid_elem_adr;       /* (nrigid)    first row in rigid_B              */
  double *rigid_mass;        /* (nrigid)    M = sum of the node masses, kg    */
  double *rigid_inertia;     /* (nrigid*3)  principal moments about X, kg m^2 */
  double *rigid_X0;          /* (nrigid*3)  initial centre of mass, m         */
  double *rigid_R0;          /* (nrigid*9)  initial R (columns: principal axes) */
  double *rigid_p;           /* (rigid nodes*3)    node in the body frame, m  */
  double *rigid_B;           /* (rigid elements*9) Q_e R, constant            */
  /* muscles (muscle.c) */
  int nmuscle, nfil;
  char **muscle_name;        /* (nmuscle)                                    */
  int *muscle_fil_adr;       /* (nmuscle+1) first filament of each muscle    */
  swSignal *muscle_activation; /* (nmuscle)                                  */
  const void *muscle_ops;    /* muscle.c's functions (NULL: no muscles)      */
  const void *env_ops;       /* environment.c's (NULL: no environment)       */
  int *fil_rod;              /* (nfil)     rod of each filament              */
  int *fil_passive;          /* (nfil)     1: never contracts                */
  double *fil_area;          /* (nfil)     rest cross-section A_k, m^2       */
  double *fil_fmax;          /* (nfil)     peak isometric force, N           */
  double *fil_l0;            /* (nfil)     rest length, m                    */
  double *fil_tau;           /* (nfil)     activation time constant, s       */
  double *fil_recruit;       /* (nfil*2)   C_{k-1}, C_k: recruitment window  */
  double *fil_hill_a;        /* (nfil)     Hill a / F_qs                     */
  double *fil_v_max;         /* (nfil)     v0 / l0, 1/s                      */
  double *fil_fibres;        /* (nfil)     muscle fibres in the filament     */
  double *fil_elem;          /* (1 plane)  1 at the element slots of filaments */
  int *fil_implicit;         /* (nfil)     SW_FIL_* bits: Hill damping linearly
                                           implicit (SW_IMEX), end nodes held */
  int muscle_implicit;       /* some filament is implicit                    */
  /* via rings (muscle_via.c): one per via point per filament, filament by
   * filament, each filament's in path order */
  int nring;
  int *fil_ring_adr;         /* (nfil+1)   first ring of each filament        */
  int *ring_elem;            /* (nring)    element slot carrying the point, -1: space */
  double *ring_point;        /* (nring*3)  offset from that element's centre in
                                           its material frame; the lab point
                                           when fixed in space, m             */
  double *ring_stiffness;    /* (nring)    N/m                                */
  double *ring_damping;      /* (nring)    N s/m                              */
  double *muscle_via;        /* (nmuscle*SW_MUSCLE_MAX_VIA*3) via points at t = 0 */
  int *muscle_nvia;          /* (nmuscle)                                     */
  /* environments (environment.c): resolved copies of the descriptions, in
   * the order added; rod lists owned by the model (every rod listed when the
   * description said 0) */
  int nground, nfluid, ncontact, nwave, nprobe;
  swGroundDesc *ground;      /* (nground)                                    */
  swFluidDesc *fluid;        /* (nfluid)                                     */
  swContactDesc *contact;    /* (ncontact)                                   */
  swWaveDesc *wave;          /* (nwave)                                      */
  swProbeDesc *probe;        /* (nprobe)                                     */
  int nexpect;
  swExpectDesc *expect;      /* (nexpect) copies, strings owned (expect.c)   */
  /* fluid.c: fluid k acts on rows [fluid_row_adr[k], fluid_row_adr[k+1]), one
   * row per element of its rods, in the order of its rod list */
  int nfluidrow;
  int *fluid_row_adr;        /* (nfluid+1) first row of each fluid           */
  int *fluid_elem;           /* (nfluidrow) global element of the row         */
  int *fluid_node;           /* (nfluidrow) its first node (second: +1)       */
  int *fluid_first;          /* (nfluidrow) first node of its rod (the thread
                                that owns it applies the row)                */
  double *fluid_stokes;      /* (nfluidrow) 4 pi mu / ln(L/r), Pa s (Stokes)  */
  double *fluid_cap;         /* (nfluidrow) exposed end-cap silhouette, m^2:
                                pi r^2 / 2 per rod end on it (quadratic)     */
  double *fluid_displaced;   /* (nfluidrow) rho_f pi r^2 l^, kg (buoyancy)    */
  double fluid_dt;           /* step limit of the Stokes drag, s (INFINITY: none) */
  /* wave.c: wave w owns rows [wave_node_adr[w], wave_node_adr[w+1]), one
   * per node of its rod, in the rod's node order */
  int *wave_node_adr;        /* (nwave+1)  first row of each wave             */
  double *wave_s;            /* (rows)     s of the node (from the start, or
                                from the end with `reverse`), m              */
  double *wave_beta;         /* (rows)     beta(s), N m; 0 at the two end nodes */
  double *wave_amp;          /* (rows*2)   beta cos(theta), beta sin(theta),
                                theta = 2 pi s / lambda - phi               */
  /* contact.c: the rows of contact c are [contact_row_adr[c],
   * contact_row_adr[c+1]), its elements rod by rod (each rod once) */
  int *contact_row_adr;      /* (ncontact+1) first row of each contact       */
  int *contact_elem;         /* (rows)     global element                    */
  int *contact_rod;          /* (rows)     its rod                           */
  double *contact_arc;       /* (rows)     rest arc length from the rod's start
                                           to the element's start, m         */
  int contact_maxrows;       /* rows of the largest contact                  */
  int contact_nbucket;       /* hash grid buckets, a power of two            */
  int has_gravity;
  int has_damping;
  int has_exact_kick;        /* some rod's kick integrates its damping exactly */
} swModel;

/* ---- the state (mutable) ---- */
typedef struct {
  double time;
  long step;
  int threads;               /* OpenMP threads of a step (sw_set_threads; 1) */
  void *team;                /* their barrier (integrate.c)                  */
  int team_size;             /* threads of the step running now (1 outside)  */
  double work;               /* work done on the rods by loads, boundaries
                                and dissipation since t = 0, J            */
  /* state, per slot in the layout of the model: x, v (3 planes, node
   * slots), Q (9 planes), omega (3 planes, element slots) */
  double *x, *v, *Q, *omega;
  /* Derived and accumulated per slot.  The dilatation is kept with the
   * state (the drift and the kick use it); the others are scratch of the
   * step: they hold the current state's values after sw_internal_loads()
   * (which sw_energy and sw_data_new call), not after sw_steps(), since a
   * one-thread step may keep only a window of them (integrate.c, the fused
   * sweep). */
  double *dilatation;        /* e = l / l^ (1 at ghosts)                     */
  /* derived per element slot */
  double *length;            /* current length l                             */
  double *sigma;             /* (3) shear/stretch strain, material           */
  double *stress;            /* (3) internal force n = S^ (s-s0) / e (Gazzola)
                                or S^ (s-s0) (variational), material        */
  /* derived per Voronoi slot */
  double *vor_dilatation;
  double *kappa;             /* (3) curvature/twist, material frame          */
  double *couple;            /* (3) the bending couple as Delta^h applies it:
                                B^ (k - k0) / eps^3 (Gazzola), or
                                (I + beta [phi]x^2) B^ (k - k0) (variational,
                                rod.c)                                      */
  /* accumulated loads */
  double *force;             /* (3) total force on nodes, lab                */
  double *torque;            /* (3) total couple on elements, material frame */
  double *ext_force;         /* (3) external force, lab                      */
  double *ext_torque;        /* (3) external couple, material frame          */
  /* rod.c's scratch between its two passes: Q^T n of each element (lab) and
   * half the transport couple kappa x c D^ of each domain (3 planes each) */
  double *scratch_f, *scratch_h;
  /* per-slot scratch of integrate.c and rod.c: scratch_flag (1 plane) holds
   * the rod pass's bent-domain flags, then the kick's work per slot;
   * scratch_phi (3 planes) the drift's rotation vectors, which muscle.c
   * borrows while the loads are evaluated and the one-thread sweep uses for
   * its bent-domain flags */
  double *scratch_flag, *scratch_phi;
  /* one partial sum per chunk (the kick's work), added in chunk order, and
   * the work of each boundary condition in a kick (nbc) */
  double *chunk_sum, *bc_work;
  int kick_pending;          /* integrate.c: a kick whose work and rigid part */
  double kick_h;             /* the next drift's leader adds (its h)          */
  /* joint.c: each joint's loads, evaluated in parallel and applied in joint
   * order (SW_JOINT_ROW doubles per joint) */
  double *joint_scratch;
  /* joints, updated with each force evaluation */
  double *joint_force;       /* (njoint*3) force of the joint on rod a, lab, N */
  double *joint_angle;       /* (njoint)  hinge angle, rad (0 for others)     */
  double *joint_limit_torque; /* (njoint*3) the limit's couple on rod a's
                                 element, lab, N m (0 inside the limits)     */
  /* rigid bodies (rigid.c), the state the nodes and elements of a rigid rod
   * are set from after every drift and kick */
  double *rigid_X;           /* (nrigid*3) centre of mass, lab, m              */
  double *rigid_V;           /* (nrigid*3) its velocity, m/s                   */
  double *rigid_R;           /* (nrigid*9) rotation body -> lab, row-major     */
  double *rigid_L;           /* (nrigid*3) angular momentum about X, lab, kg m^2/s */
  double *rigid_load;        /* (nrigid*6) a kick's force and torque on each body */
  double *rigid_sys;         /* the implicit joints' system (rigid_joint.c)    */
  double *implicit_sys;      /* the implicit rods' banded systems (rod_implicit.c) */
  double *rigid_omega;       /* (nrigid*3) angular velocity, lab, rad/s        */
  /* muscles, updated with each force evaluation (activation once a step) */
  double *fil_activation;    /* (nfil)    a_k in [0, 1]                        */
  double *fil_stretch;       /* (nfil)    eta = l / l0                          */
  double *fil_rate;          /* (nfil)    strain rate dl/dt / l0, 1/s           */
  double *fil_tension;       /* (nfil)    T_k, N                                */
  double *ring_row;          /* (nring*SW_RING_ROW) each ring's contact and
                                           load, last evaluation (muscle_via.c) */
  /* environments, updated with each force evaluation */
  /* contact.c: the last evaluation's figures, and the hash grid's scratch */
  int contact_pairs;         /* element pairs in contact                     */
  double contact_max_overlap; /* deepest overlap r_a + r_b - D, m (0: none)  */
  int *contact_cell;         /* (contact_maxrows*3) cell of each row         */
  int *contact_bucket;       /* (contact_maxrows)   its bucket               */
  int *contact_sorted;       /* (contact_maxrows)   rows by bucket           */
  int *contact_start;        /* (contact_nbucket+1) first sorted row of each bucket */
  int *contact_sorted_cell;  /* (contact_maxrows*3) cell of each sorted row  */
  unsigned long long *contact_occupied; /* (contact_nbucket/64+1) bit set: bucket not empty */
  /* probe.c: the centre-of-mass samples (t, X) that mean-velocity probes
   * difference, a ring of SW_PROBE_RING per probe (probe.c) */
  double *probe_ring;        /* (nprobe*SW_PROBE_RING*4) t, X of each sample  */
  int *probe_head;           /* (nprobe)  slot of the oldest sample           */
  int *probe_count;          /* (nprobe)  samples held                        */
  /* instability report, filled when sw_step returns SW_EUNSTABLE */
  char error[512];
} swData;

/* ---- access to the planar arrays (see Layout at the top) ---- */
/* Component k of slot i of a per-slot array with planes of m->stride. */
#define SW_AT(m, a, i, k) ((a)[(size_t)(k) * (size_t)(m)->stride + (size_t)(i)])
static inline void sw_get3(const swModel *m, const double *a, int i, double out[3]) {
  out[0] = SW_AT(m, a, i, 0); out[1] = SW_AT(m, a, i, 1); out[2] = SW_AT(m, a, i, 2);
}
static inline void sw_set3(const swModel *m, double *a, int i, const double in[3]) {
  SW_AT(m, a, i, 0) = in[0]; SW_AT(m, a, i, 1) = in[1]; SW_AT(m, a, i, 2) = in[2];
}
static inline void sw_add3(const swModel *m, double *a, int i, const double in[3]) {
  SW_AT(m, a, i, 0) += in[0]; SW_AT(m, a, i, 1) += in[1]; SW_AT(m, a, i, 2) += in[2];
}
/* Frame of slot i as a row-major 3x3 matrix (rows d1, d2, d3). */
static inline void sw_getQ(const swModel *m, const double *Q, int i, double out[9]) {
  for (int k = 0; k < 9; k++) out[k] = SW_AT(m, Q, i, k);
}
static inline void sw_setQ(const swModel *m, double *Q, int i, const double in[9]) {
  for (int k = 0; k < 9; k++) SW_AT(m, Q, i, k) = in[k];
}

swModel *sw_compile(const swSpec *s, char *err, size_t errlen);
void sw_model_free(swModel *m);
swData *sw_data_new(const swModel *m);
void sw_data_free(swData *d);
void sw_reset(const swModel *m, swData *d);

/* Kernels. */
void sw_internal_loads(const swModel *m, swData *d);   /* rod.c: strains and internal loads */
void sw_external_loads(const swModel *m, swData *d);   /* loads.c       */
void sw_apply_bc_velocity(const swModel *m, swData *d, double t); /* boundary.c */
int sw_step(const swModel *m, swData *d);              /* integrate.c   */
int sw_steps(const swModel *m, swData *d, long k);     /* k steps, fused */
/* Threads a step runs on (OpenMP; 1 by default).  The result does not depend
 * on n: the kernels split their loops into the model's fixed chunks and add
 * partial sums in chunk order.  Returns the count set (n < 1 counts as 1). */
int sw_set_threads(swData *d, int n);                  /* integrate.c   */
int sw_check_finite(const swModel *m, swData *d);      /* stability.c   */
/* Sets the motion of rigid rod `rod` (rigid.c): centre-of-mass velocity V and
 * angular velocity omega, lab frame; node and element velocities follow.
 * Returns SW_OK, or SW_EUSAGE if the rod is not rigid or is clamped. */
int sw_rigid_set_motion(const swModel *m, swData *d, int rod, const double V[3],
                        const double omega[3]);

/* The row of probe p for the current state (probe.c; what /probes/NAME
 * gets).  A mean-velocity probe also records the sample it differences
 * later, so call it once per frame, in time order (sw_reset forgets them). */
void sw_probe_measure(const swModel *m, swData *d, int p, double out[3]);

/* Energies (J): kinetic (translational + rotational), elastic
 * (bend/twist + shear/stretch), and the work done on the system. */
void sw_energy(const swModel *m, swData *d, double out[3]);

/* Stable time step estimates, s (stability.c). */
double sw_stable_dt(const swModel *m);
double sw_stable_dt_rod(const swModel *m, int rod);
double sw_stable_dt_joint(const swModel *m, int joint);

/* The record of one run's expectations (created before the run, sampled by
 * sw_run through swRunOptions.expect, reported after it). */
typedef struct swExpectRun swExpectRun;
swExpectRun *sw_expect_run_new(const swModel *m);
void sw_expect_run_free(swExpectRun *r);
/* Writes the report to f (quiet: the failures only); returns how many
 * expectations failed (those the run did not reach are listed, not counted). */
int sw_expect_report(const swModel *m, const swExpectRun *r, FILE *f, const char *prog,
                     int quiet);

/* ---- output (output.c, the only file that touches HDF5) ---- */
typedef struct swOutput swOutput;
typedef struct {
  const char *model_source;   /* full text, imports inlined (may be NULL)   */
  const char *model_sha256;   /* hex digest (may be NULL)                   */
  const char *params;         /* "name=value;..." (may be NULL)             */
  double duration;            /* s                                           */
  int velocity;               /* also write /rods/NAME/velocity             */
  int directors;              /* also write /rods/NAME/directors            */
  /* Per-item selection (SW_OUT_* bits), each array NULL for the default:
   * rods write their position (and velocity, directors as above), joints and
   * muscles every quantity they have. */
  const unsigned *rod_out;    /* (nrod)                                     */
  const unsigned *joint_out;  /* (njoint)                                   */
  const unsigned *muscle_out; /* (nmuscle)                                  */
  /* The params as a table /params of nparam rows (name, value, unit,
   * default): value and default in unit ("" if none); nparam may be 0. */
  int nparam;
  const char *const *param_name;
  const double *param_value, *param_default;
  const char *const *param_unit;
  double every;               /* s between frames (0: every step), recorded
                                 so that a continued run keeps it          */
} swOutputOptions;

/* What the output writes of each rod, joint and muscle (bits). */
enum {
  /* rods */
  SW_OUT_POSITION = 1u << 0,         /* /rods/NAME/position          [F, n+1, 3] m   */
  SW_OUT_VELOCITY = 1u << 1,         /* velocity                     [F, n+1, 3] m/s */
  SW_OUT_DIRECTORS = 1u << 2,        /* directors                    [F, n, 3, 3]    */
  SW_OUT_ANGULAR_VELOCITY = 1u << 3, /* angular_velocity (material)  [F, n, 3] rad/s */
  SW_OUT_STRAIN = 1u << 4,           /* strain sigma (material)      [F, n, 3]       */
  SW_OUT_CURVATURE = 1u << 5,        /* curvature kappa (material)   [F, n-1, 3] rad/m */
  SW_OUT_INTERNAL_FORCE = 1u << 6,   /* internal_force n (material)  [F, n, 3] N     */
  SW_OUT_INTERNAL_COUPLE = 1u << 7,  /* internal_couple (material)   [F, n-1, 3] N m */
  /* joints */
  SW_OUT_ANGLE = 1u << 8,            /* /joints/NAME/angle (hinges)  [F] rad         */
  SW_OUT_JOINT_FORCE = 1u << 9,      /* force                        [F, 3] N        */
  SW_OUT_LIMIT_TORQUE = 1u << 14,    /* limit_torque (limited joints) [F, 3] N m     */
  /* muscles */
  SW_OUT_MUSCLE_FORCE = 1u << 10,    /* /muscles/NAME/force          [F] N           */
  SW_OUT_STRETCH = 1u << 11,         /* stretch                      [F]             */
  SW_OUT_ACTIVATION = 1u << 12,      /* activation                   [F]             */
  SW_OUT_FILAMENT_FORCE = 1u << 13   /* filament_force               [F, filaments] N */
};

swOutput *sw_output_open(const char *path, const swModel *m, const swOutputOptions *o,
                         char *err, size_t errlen);
int sw_output_frame(swOutput *o, const swModel *m, swData *d);
/* SIM --restart (restart.c): reopens a file a run of the same model (same
 * model_sha256, params and `every`) wrote, puts the state of its checkpoint
 * into d (and the expectations' into x, may be NULL), cuts its datasets back
 * to the frames it held then, and appends from there. */
swOutput *sw_output_resume(const char *path, const swModel *m, const swOutputOptions *o,
                           swData *d, swExpectRun *x, char *err, size_t errlen);
/* The model's hash (sha256[65]), the params ("name=value;...", SI), the
 * time step and the frame interval (s; -1 if not recorded) a file's run
 * had, for SIM --restart.  SW_OK or SW_EIO. */
int sw_output_read_run(const char *path, char *sha256, char *params, size_t len, double *dt,
                       double *every);
/* The run loop's checkpoint at a scheduled frame, just written: kept in
 * memory, written to /restart every 10 s of wall time and at close. */
int sw_output_checkpoint(swOutput *o, const swModel *m, const swData *d, const swExpectRun *x);
int sw_output_close(swOutput *o, const char *status);
/* The run's objective as root attributes objective, penalty, score (SI;
 * NaN when not reached) with their units (objective_units, penalty_units,
 * score_units: `units`) and objective_text ("maximize EXPR"); written
 * again if given again. */
int sw_output_objective(swOutput *o, const char *text, double objective, double penalty,
                        double score, const char *units);
long sw_output_frames(const swOutput *o);
/* SIM --compare (compare.c): every numeric dataset of the golden file against
 * the run's, within rtol of the dataset's largest magnitude; the report to
 * f.  Returns how many datasets differ or are missing, -1 when a file cannot
 * be opened. */
int sw_compare_files(const char *run_path, const char *golden_path, double rtol, FILE *f,
                     const char *prog);
/* Message of the most recent failed sw_output_* call in this thread (names the
 * file and the object; "" if none failed).  Added because sw_output_frame()
 * and sw_output_close() have no err argument. */
const char *sw_output_error(void);

/* ---- the run loop (run.c): steps, frames, SIGINT, progress ---- */
typedef struct {
  double duration;       /* s */
  double every;          /* s between frames; 0 = every step            */
  int quiet;             /* no progress line                             */
  FILE *log;             /* messages (stderr when NULL)                  */
  swExpectRun *expect;   /* expectations to sample (NULL: none)          */
  int resumed;           /* the state is the output's last frame, already
                            written and sampled (sw_output_resume)      */
  int silent;            /* no message at all, not even an instability's
                            (it stays in d->error): sw_evaluate         */
} swRunOptions;

int sw_run(const swModel *m, swData *d, swOutput *out, const swRunOptions *ro);

/* The number of steps of dt that span `duration` (rounded to the nearest),
 * into *nsteps.  SW_EUSAGE, with the reason in err, when the run is absurd:
 * dt or duration not finite or not positive (a duration of 0 is 0 steps),
 * a positive duration shorter than half a step (no step would be taken),
 * or more than SW_MAX_STEPS steps (10^13: at a microsecond a step, four
 * months of wall time; beyond what any run here is for). */
#define SW_MAX_STEPS 1e13
int sw_step_count(double duration, double dt, long *nsteps, char *err, size_t errlen);

/* Parse a duration with optional unit ("50ns", "0.5 s", "2ms", "1e-3").
 * Returns 0 on success. */
int sw_parse_time(const char *text, double *seconds);

/* ---- units (units.c): the one table of unit names, shared with the
 * compiler, and the parser of quantities on the command line ---- */
enum { SW_DIM_MASS = 0, SW_DIM_LENGTH, SW_DIM_TIME, SW_DIM_ANGLE, SW_NDIM };
typedef struct {
  const char *name;            /* "kPa", "g", "deg"                         */
  double scale;                /* value of 1 name in SI (rad for angles)    */
  signed char dim[SW_NDIM];    /* exponents of kg, m, s, rad                */
} swUnit;
const swUnit *sw_unit_find(const char *name, size_t len);   /* NULL: unknown */
const swUnit *sw_unit_table(int *count);
/* Parse "0.3 m", "1.75 g/cm^3", "50ns", "-2", "10 N/m" into SI value and
 * dimension.  Returns 0, or nonzero with a message in err. */
int sw_parse_quantity(const char *text, double *si, signed char dim[SW_NDIM], char *err,
                      size_t errlen);
/* "length (m)", "pressure (Pa)", "kg m^-1 s^-2", "dimensionless" */
const char *sw_dim_describe(char *buf, size_t len, const signed char dim[SW_NDIM]);

/* ---- the simulator's command line (cli.c), called by generated main ---- */
typedef struct {
  const char *name;            /* as written in the model                   */
  double value;                /* default, SI                               */
  signed char dim[SW_NDIM];
  const char *unit;            /* unit to show in --help ("m", "" if none)  */
  const char *where;           /* "arm.sinew:3" for messages                */
  int ranged;                  /* 1: `in (lo, hi)` given: a study varies it */
  double lo, hi;               /* its range, SI, lo < hi (ranged only)      */
} swParam;

typedef struct {
  const char *name;            /* model name (file stem)                    */
  const char *source;          /* full model text, imports inlined          */
  const char *sha256;          /* hex digest of source                      */
  int nparam;
  const swParam *param;
  /* Builds the scene from parameter values P (SI, in the order of param).
   * Returns SW_OK, or SW_EMODEL with a message in err. */
  int (*build)(swSpec *s, const double *P, char *err, size_t errlen);
  double dt;                   /* s; 0 = half the stable estimate           */
  double duration;             /* s                                         */
  double every;                /* s between frames; 0 = every step          */
  const char *out;             /* default output path                       */
  int velocity, directors;     /* output selection                          */
  const unsigned *rod_out;     /* (rods) SW_OUT_* bits, NULL: the defaults  */
  const unsigned *muscle_out;  /* (muscles)                                 */
  /* Joints by name, since the runtime adds joints of its own (a muscle's
   * attachments): njoint_out named joints and their bits; every other joint
   * gets joint_out_rest.  njoint_out = 0: the defaults. */
  int njoint_out;
  const char *const *joint_out_name;
  const unsigned *joint_out;
  unsigned joint_out_rest;
  /* The study's objective (0 / NULL when the model has none): maximize or
   * minimize EXPR and the penalties, over the values R of its reductions
   * (the entries of the model's expectations with `reduce` set, in order). */
  int sense;                   /* +1 maximize, -1 minimize, 0 none          */
  const char *objective_text;  /* "maximize EXPR" as written, for reports   */
  const char *objective_where; /* "snake.sinew:40"                          */
  const char *objective_unit;  /* unit to show it in ("m/s"; "" none)       */
  double objective_scale;      /* SI value of one objective_unit            */
  const char *objective_si_unit; /* its SI unit ("m/s"; "" none): the unit of
                                  the values of swEvalResult and the HDF5  */
  int npenalty;                /* penalty statements                        */
  int nreduce;                 /* reductions the objective reads            */
  /* The objective's value and the sum of the penalties (SI) from the param
   * values P and the reductions R[0..nreduce). */
  void (*objective)(const double *P, const double *R, double *value, double *penalty);
} swProgram;

/* Optimal-string-alignment edit distance between a[0..la) and b (a
 * transposition counts one edit); INT_MAX for names over 63 characters.
 * For "did you mean" suggestions, here and in the compiler. */
int sw_edit_distance(const char *a, size_t la, const char *b);

/* ---- one evaluation of the objective, in process (evaluate.c) ---- */
typedef struct {
  int status;          /* SW_OK; SW_EUNSTABLE; SW_EMODEL (the params give no
                          valid scene, or the objective is not a number);
                          SW_EUSAGE (no objective, or a run too short for
                          it); SW_EINTERRUPT                                */
  double objective;    /* SI, NaN when not reached                          */
  double penalty;      /* sum of the penalties, SI (0 if none; NaN when the
                          objective is not reached)                         */
  double score;        /* maximize: objective - penalty; minimize:
                          -(objective + penalty); -INFINITY when status != SW_OK */
  double sim_time;     /* s simulated                                       */
  long steps;
  char message[256];   /* why it failed ("" when ok)                        */
} swEvalResult;

/* Builds the scene from P (SI, p->nparam values; NULL: the defaults),
 * compiles it with the dt the CLI would use (dt > 0: that; else the
 * model's, else half the stable estimate, shortened to divide the model's
 * frame interval), runs `duration` (<= 0: the model's) with one thread, no
 * output file, no progress and no messages on stderr, samples the
 * objective's reductions, and fills r.  integrator -1: the model's.  Never
 * exits; never prints.  Returns r->status. */
int sw_evaluate(const swProgram *p, const double *P, double duration, double dt,
                int integrator, swEvalResult *r);

/* The model of program p at params P, compiled at dt (> 0), else at the
 * model's dt, else at half the stable estimate shortened so that a whole
 * number of steps spans `every` (> 0); integrator -1: the model's.  The
 * stable estimate in *stable.  NULL when it cannot be built, with the
 * status in *status (SW_EMODEL, or build()'s) and the reason in err. */
swModel *sw_program_compile(const swProgram *p, const double *P, double dt, int integrator,
                            double every, double *stable, int *status, char *err, size_t errlen);

/* The objective of a run of p's model m whose reductions x sampled
 * (x may hold expectations too): objective, penalty sum and score, SI.
 * SW_OK, or SW_EUSAGE with the reason in why when a reduction was not
 * reached (the run ended before its time, or no step fell in its window),
 * SW_EMODEL when the objective is not a number; the values are then NaN
 * and the score -INFINITY. */
int sw_objective(const swProgram *p, const swModel *m, const swExpectRun *x, const double *P,
                 double *objective, double *penalty, double *score, char *why, size_t len);

/* Parses --out --duration --dt --every --set NAME=VALUE --threads --compare
 * --rtol --quiet --info --help, builds, compiles and runs (checking the
 * model's expectations and, with --compare, the output against a golden
 * file); returns the exit code. */
int sw_main(const swProgram *p, int argc, char **argv);

#endif
