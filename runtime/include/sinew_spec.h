/* sinew_spec.h — part of sinew.h (include that): the description of a scene.
 *
 * Design.  A scene is described in a mutable swSpec, built one call at a time
 * (rods, loads, boundary conditions, joints, muscles, environments,
 * expectations, probes) by the generated code, then compiled by sw_compile()
 * (sinew_model.h).  The descriptors are plain structs the caller fills and
 * the spec copies; time signals scale any magnitude that varies.  Implemented
 * in runtime/engine/ (spec.c keeps the spec, each kernel's file checks its
 * own descriptor). */
#ifndef SINEW_SPEC_H
#define SINEW_SPEC_H

#include <stddef.h>


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
  SW_SIG_BSPLINE,   /* clamped cubic B-spline with coefficients values[0..npts)
                       on uniform knots over [t0, t0+T], constant outside   */
  SW_SIG_FUNC       /* a fn(t, ctx): any function of time, e.g. a model's
                       signal NAME(t) = ... compiled to C, times a; its
                       range is sampled over [t0, t0 + T]                 */
} swSignalKind;

/* A signal given as a function of time; ctx is the signal's fn_ctx. */
typedef double (*swSignalFn)(double t, const void *ctx);

#define SW_SIGNAL_MAXPTS 64
typedef struct {
  swSignalKind kind;
  double a, b, t0, T, freq, phase;
  double period;                     /* > 0: periodic, s(t) = s(t0 + (t - t0) mod period) */
  int npts;                          /* SW_SIG_TABLE and SW_SIG_BSPLINE   */
  double times[SW_SIGNAL_MAXPTS];    /* strictly increasing               */
  double values[SW_SIGNAL_MAXPTS];
  swSignalFn fn;                     /* SW_SIG_FUNC                       */
  const void *fn_ctx;
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
/* fn(t, ctx) (times its a, 1 here: set a to scale it); its range
 * (sw_signal_range) is sampled at 4097 points over [t0, t0 + span] (span >
 * 0), the times a run covers. */
swSignal sw_signal_func(swSignalFn fn, const void *ctx, double t0, double span);
double sw_signal_eval(const swSignal *s, double t);
/* The least and the greatest value s takes (a B-spline's to about 1e-4 of
 * its spread): what the compiler and the simulator check an activation by. */
void sw_signal_range(const swSignal *s, double *lo, double *hi);

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
  /* Geometry that changes in time (engine/swell.c; docs/physics.md,
   * "Geometry that changes in time").  With swell = 1 the radius profile
   * (radius_start..radius_end, the radius at t = 0) is scaled by
   * g(t) = swell_radius(t) / swell_radius(0): bending and twist stiffness
   * follow g^4, shear and stretch g^2, the contact and ground radius g; the
   * mass is conserved (density ~ g^-2, inertia J^ ~ g^2) or, with
   * swell_mass_grows, the density is fixed (mass ~ g^2, J^ ~ g^4).  The
   * rest curvature about d1, d2 is multiplied by swell_curvature(t) and the
   * rest twist about d3 by swell_twist(t), or by 1 / g(t) with
   * swell_twist_radius (the reference's law, k3 ~ r0 / r).  Not on a rigid
   * rod; an implicit rod factors its system afresh at every kick. */
  int swell;
  swSignal swell_radius;      /* r(t), m: > 0 over the run                   */
  swSignal swell_curvature;   /* c(t), dimensionless (constant 1: none)      */
  swSignal swell_twist;       /* w(t), dimensionless (constant 1: none)      */
  int swell_twist_radius;     /* 1: w(t) = r(0) / r(t) instead of swell_twist */
  int swell_mass_grows;       /* 0: mass conserved; 1: density fixed         */
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
  SW_BC_OMEGA = 2,     /* end element angular velocity = vec*signal, lab  */
  SW_BC_SLIDE_LINE = 3,  /* end node kept on the line through its start
                            position along vec, free along it; frame free */
  SW_BC_SLIDE_PLANE = 4, /* end node kept on the plane through its start
                            position normal to vec, free in it; frame free */
  SW_BC_SLEEVE = 5       /* a sleeve: the end node as SLIDE_LINE, the end
                            element's frame free to turn about vec only   */
} swBCKind;
typedef struct {
  swBCKind kind;
  int rod;
  int end;           /* 0 = start (node 0, element 0), 1 = end             */
  double vec[3];     /* SLIDE_*: the direction (any length but zero)       */
  swSignal signal;
  double until;      /* s: the hold acts on the kicks before this time and
                        then lets the end go (boundary.c); 0 = for ever    */
} swBCDesc;

/* A rod's description for the output (owned copies of swRodDesc's kind,
 * material and where; NULL: not given). */
typedef struct {
  char *kind, *material, *where;
  double youngs, shear_modulus, density;  /* Pa, Pa (G, before hardening), kg/m^3 */
  double length;                          /* rest length, m                   */
  double shear_hardening, twist_hardening; /* factors on G in S11, S22 and B33 */
} swRodInfo;

typedef struct swSpec swSpec;
swSpec *sw_spec_new(void);
void sw_spec_free(swSpec *s);
void sw_rod_desc_init(swRodDesc *r);        /* fills defaults */
int sw_spec_add_rod(swSpec *s, const swRodDesc *r);      /* returns rod id */
int sw_spec_add_load(swSpec *s, const swLoadDesc *l);
int sw_spec_add_bc(swSpec *s, const swBCDesc *b);
void sw_spec_set_gravity(swSpec *s, const double g[3]);
/* Gravity g times a dimensionless signal of time (default: 1). */
void sw_spec_set_gravity_signal(swSpec *s, swSignal signal);
void sw_spec_set_integrator(swSpec *s, swIntegrator integ);
void sw_spec_set_dt(swSpec *s, double dt);
/* Rest shape override for rod r: node positions (n+1)x3 and element directors
 * n x 9 (rows d1 d2 d3).  Optional; default is the straight rod. */
int sw_spec_set_rest_shape(swSpec *s, int rod, const double *x, const double *Q);
/* Starting shape of rod r, apart from its rest shape: node positions (n+1)x3
 * and element directors n x 9 (rows d1 d2 d3) at t = 0.  Optional; default
 * is the rest shape (the one given above, or the straight rod).  The rest
 * shape keeps setting the rest lengths and the rest curvature. */
int sw_spec_set_start_shape(swSpec *s, int rod, const double *x, const double *Q);

/* ---- shapes (shape.c): the nodes and frames of a curved rod ----
 * Each fills x (n+1 nodes, 3 doubles each) and Q (n frames, rows d1 d2 d3)
 * for sw_spec_set_rest_shape / sw_spec_set_start_shape, with d3 along each
 * element's chord, so that a rod placed in the shape it rests in carries no
 * shear strain.  Each returns SW_OK, or SW_EMODEL with a message in err. */

/* A centreline r(s) in the lab, s in [0, length] the arc length of the rest
 * rod (a curve with |dr/ds| != 1 starts stretched by |dr/ds|). */
typedef void (*swCurveFn)(double s, double r[3], const void *ctx);
/* Nodes r(i length / n); d1 of the first element is `normal` made
 * perpendicular to its chord, and every next frame is the previous one
 * carried by the smallest rotation that takes its d3 to the next chord (the
 * discrete parallel transport, or Bishop frame: no twist about d3). */
int sw_shape_curve(int n, double length, swCurveFn curve, const void *ctx,
                   const double normal[3], double *x, double *Q, char *err, size_t errlen);
/* A circular helix of `radius` (m, > 0), `pitch` (m per turn along its axis,
 * >= 0) and arc length `length` (m), right-handed (hand = +1) or left-handed
 * (-1): its first node at `start`; `axis` the way it advances; `normal` the
 * way from the start to the axis (made perpendicular to it).  Nodes are at
 * equal arc lengths; d1 is the principal normal at the element's middle
 * (towards the axis), d3 the chord, d2 = d3 x d1 (the Frenet frame). */
int sw_shape_helix(int n, double radius, double pitch, double length, int hand,
                   const double start[3], const double axis[3], const double normal[3],
                   double *x, double *Q, char *err, size_t errlen);
/* The straight rod along `direction` from `start` whose element lengths are
 * those of the nodes `rest_x` (so it starts unstretched from a curved rest
 * shape); every frame from direction and normal. */
int sw_shape_straight(int n, const double *rest_x, const double start[3],
                      const double direction[3], const double normal[3], double *x, double *Q,
                      char *err, size_t errlen);

/* ---- kinematic joints (kinematic.c): a frame imposed, loads exchanged ----
 * Zhang et al. 2019, Suppl. Note 5.3: the element `follower_elem` of the
 * follower rod takes its frame from element `leader_elem` of the leader rod
 * (times the fixed rotation between the two at t = 0) before every load
 * evaluation, with the matching angular velocity; no couple is fed back.
 * Node `follower_node` is tied to the point p = x_e + xi (x_{e+1} - x_e) of
 * the leader's element e = leader_elem by a spring-damper:
 *   F = k (p - x_f) + c (v_p - v_f)  on the follower node,
 * and -F on the leader at p (shared (1 - xi), xi by its two nodes), or,
 * with reaction_rod >= 0, -w F on node reaction_node of that rod instead
 * (w = reaction_weight; the reference's transfer of the barbs' loads to
 * the bone at the rachis base).  Node and element -1 = the rod's last.
 * All these loads are booked as external work, and so is the energy the
 * imposed turn gives the follower element (its turning kinetic energy and
 * the elastic energy of its shear and of its two bending domains), so that
 * kinetic + elastic - work still balances. */
typedef struct {
  const char *name;
  int leader_rod, leader_elem;
  double leader_xi;           /* 0..1 along the leader's element               */
  int follower_rod, follower_node, follower_elem;
  double stiffness;           /* k, N/m (> 0)                                  */
  double damping;             /* c, N s/m (>= 0)                               */
  int reaction_rod, reaction_node; /* -1: the reaction acts on the leader      */
  double reaction_weight;     /* w (1)                                         */
} swKinematicDesc;
void sw_kinematic_desc_init(swKinematicDesc *k);
int sw_spec_add_kinematic(swSpec *s, const swKinematicDesc *k);  /* returns its id */

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
  double arm_a[3];          /* m, lab frame at t = 0: side a's point is node_a
                               plus this arm, carried by node a's element
                               (a joint's frame offset on its first body);
                               the spring then turns that element too      */
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
  /* prescribed = 1: the muscle pulls with `force` (N, the whole muscle's,
   * shared by the filaments in proportion to their cross-sections) instead
   * of its activation and the Hill law: no force-length, force-velocity or
   * damping, as Zhang et al. 2019 drive the wing's muscles (Suppl. eqs.
   * 6-10).  sigma_max is then not needed; F_max,k (the attachments' default
   * stiffness) is the force's largest size over its range times the share. */
  int prescribed;
  swSignal force;
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
 * element's velocity relative to the flow, quadratic drag on an area A per
 * element (by default the area the element shows the flow, 2 r l |sin| plus
 * the rod's end caps), and buoyancy (docs/physics.md, "Fluids"). */
typedef enum {
  SW_FLUID_STOKES = 0,      /* slender-body Stokes drag, Zhang 2019 Suppl. eq. 1 */
  SW_FLUID_QUADRATIC = 1    /* quadratic (Morison) drag, Zhang 2019 Suppl. eq. 2 */
} swFluidModel;
typedef enum {                /* quadratic drag's A, per element of length l  */
  SW_FLUID_SILHOUETTE = 0,    /* 2 r l |sin a| + the rod's end caps pi r^2 |cos a|,
                                 a between the axis and the relative flow   */
  SW_FLUID_CROSS_SECTION = 1, /* pi r^2, Suppl. Note 5.2 as worded           */
  SW_FLUID_BROADSIDE = 2      /* 2 r l whatever the flow's direction (the
                                 reference's released wing code)             */
} swFluidArea;
typedef struct {
  const char *name;
  swFluidModel model;
  double viscosity;         /* mu, Pa s (Stokes)                             */
  double density;           /* rho_f, kg/m^3 (quadratic drag, buoyancy)      */
  double drag_coefficient;  /* C_d (quadratic)                               */
  swFluidArea area;         /* A of quadratic drag (0: the silhouette)       */
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
 * 2019, Suppl. Table 4); a broad phase keeps far pairs out.  With friction
 * (mu_s > 0) each touching pair keeps an anchor, the material point of
 * each element's surface where they touched, tied by a tangential spring
 * k_t (and the damper gamma_c) capped at mu_s N, slipping at mu_k N beyond:
 * the law of the obstacles' friction, acting at the surfaces with its
 * couples (docs/physics.md, "Rod-rod contact"). */
typedef struct {
  const char *name;
  double stiffness;         /* k_c, N/m                                      */
  double damping;           /* gamma_c, kg/s                                 */
  double static_friction;   /* mu_s (0: frictionless, the default)           */
  double kinetic_friction;  /* mu_k <= mu_s, the force while slipping        */
  double tangential_stiffness; /* k_t, N/m per pair (0: the stiffness k_c)   */
  int self;                 /* 1: also within each rod                       */
  int nrods;                /* rods in contact (0: all)                      */
  const int *rods;
} swContactDesc;
void sw_contact_desc_init(swContactDesc *c); /* fills defaults */
int sw_spec_add_contact(swSpec *s, const swContactDesc *c);

/* A rigid obstacle (obstacle.c): a sphere, a capsule, an infinite cylinder,
 * a box or an ellipsoid, fixed in the lab or carried by an element of a rod
 * (a bone), that the elements of its rods touch.  Each element is a capsule
 * of its radius around the segment between its nodes; where it comes closer
 * to the shape than its radius, a penalty k p along the shape's outward
 * normal plus a damper gamma times the approach speed (never pulling) push
 * it out, at the point of the segment nearest to the shape; a carried
 * obstacle takes the opposite force and its couple back to its element
 * (docs/physics.md, "Rigid obstacles").  With friction (mu_s > 0) each
 * touching element keeps an anchor, the material point where it touched and
 * the obstacle's point there, tied by a tangential spring k_t (and the
 * damper gamma) capped at mu_s N: below the cap the contact holds still,
 * beyond it the anchor slides and the force is mu_k N (an elastic-Coulomb
 * law, Cundall & Strack 1979).  The shape's own frame has its
 * third axis along `axis` and its first along `normal` (made perpendicular
 * to axis); both are lab directions at t = 0. */
typedef enum {
  SW_OBSTACLE_SPHERE = 0,     /* radius                                      */
  SW_OBSTACLE_CAPSULE = 1,    /* radius, length (of the cylinder between the
                                 centres of its round caps), along axis      */
  SW_OBSTACLE_CYLINDER = 2,   /* radius, infinite along axis                 */
  SW_OBSTACLE_BOX = 3,        /* half sizes along (normal, axis x normal, axis) */
  SW_OBSTACLE_ELLIPSOID = 4   /* semi-axes along (normal, axis x normal, axis) */
} swObstacleShape;
typedef struct {
  const char *name;
  swObstacleShape shape;
  double centre[3];         /* m, lab frame at t = 0                         */
  double axis[3];           /* the shape's third axis, lab at t = 0 ((0,0,1)) */
  double normal[3];         /* its first axis, lab at t = 0 ((1,0,0); the
                               part perpendicular to axis is kept)           */
  double radius;            /* m: sphere, capsule, cylinder                  */
  double length;            /* m: capsule                                    */
  double half[3];           /* m: box half sizes, ellipsoid semi-axes        */
  double stiffness;         /* k, N/m per element                            */
  double damping;           /* gamma, kg/s per element                       */
  double static_friction;   /* mu_s (0: frictionless, the default)           */
  double kinetic_friction;  /* mu_k <= mu_s, the force while slipping        */
  double tangential_stiffness; /* k_t, N/m per element (0: the stiffness k)  */
  int carrier_rod;          /* -1: fixed in the lab; else the rod whose      */
  int carrier_node;         /* node (-1: last) element carries it, as a joint's
                               arm: node i's element is i (the last: n - 1) */
  int nrods;                /* rods that touch it (0: all but the carrier)   */
  const int *rods;
} swObstacleDesc;
void sw_obstacle_desc_init(swObstacleDesc *o); /* fills defaults */
int sw_spec_add_obstacle(swSpec *s, const swObstacleDesc *o);

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

#endif
