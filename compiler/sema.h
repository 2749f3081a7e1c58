/* sema.h — the checked model: values with dimensions, symbols, and the scene
 * that code generation and the in-compiler checks read.
 *
 * Design.  The checker evaluates every expression of the model to a swValue:
 * a kind (number, vector, point on a rod, time signal, reference to a
 * definition, the word true or false, bare word), a dimension, the numbers it has with every param at
 * its default, and -- only when it depends on a param -- the C expression that
 * recomputes it at run time from the param array P.  So constants are folded
 * by construction and a param default appears in the generated C exactly
 * once, in the param table.  The checked scene (swScene) is a flat list of
 * rods, muscles, loads, boundary conditions and joints in definition order,
 * each field a swValue and each entry with the location of the model line it
 * came from.  Scene entries refer to rods by their index in swScene.rod; the
 * runtime numbers rods differently, because a muscle adds one rod per
 * filament, so each rod and muscle also carries its runtime rod id and code
 * generation maps one to the other (gen_rod_id).  Code generation (gen_c.c) prints it; sema_spec.c turns it into the
 * runtime's swSpec to reuse the runtime's own checks and stable-dt estimate.
 */
#ifndef SINEW_SEMA_H
#define SINEW_SEMA_H

#include "ast.h"
#include "sinew.h"

typedef struct { signed char e[SW_NDIM]; } swDim;

typedef enum {
  VAL_ERROR = 0,  /* already reported; silences follow-on errors          */
  VAL_NUM,        /* n == 1                                                */
  VAL_VEC,        /* n >= 2                                                */
  VAL_POINT,      /* a node of a rod: position (3) + rod + node            */
  VAL_SIGNAL,     /* a time signal times a scale (number or vector)        */
  VAL_REF,        /* a definition: material, rod, joint, component, ...    */
  VAL_WORD,       /* an identifier with no definition (all, pefrl, ...)    */
  VAL_TRUTH       /* true or false (word): a switch fixed when compiling;
                     it flows through lets and component parameters        */
} swValKind;

struct swSymbol;
struct swSignalVal;

typedef struct swValue {
  swValKind kind;
  swDim dim;
  int n;                      /* components                                */
  double *v;                  /* (n) values with params at their defaults;
                                 NaN when known only at the end of a run (an
                                 objective's reduction, R[k] in its C text) */
  const char **c;             /* (n) C expressions, NULL entries constant; NULL if all */
  const char *param;          /* a param it depends on (for messages)      */
  swLoc loc;
  /* read through a component's parameter: its name and where its value is
   * written (the default, or the use's argument), for a note on an error */
  const char *via_formal;
  swLoc formal_loc;
  /* VAL_POINT */
  int rod, node;
  double at;                  /* its fraction along the rod (0 start, 1 end) */
  const char *node_c;         /* the node's C expression when a param moves the
                                 point (ROD.at(param)), NULL when constant   */
  /* VAL_SIGNAL */
  struct swSignalVal *sig;
  /* VAL_REF, VAL_WORD, VAL_TRUTH ("true" or "false") */
  struct swSymbol *ref;
  const char *word;
} swValue;

/* swSignal's fields as values (each scalar, dimension checked). */
typedef struct swSignalVal {
  swSignalKind kind;
  swValue a, b, t0, T, freq, phase;
  swValue period;             /* VAL_ERROR: not periodic                    */
  int npts;
  struct swSceneSignal *func; /* SW_SIG_FUNC: a signal NAME(t) = ... of the model */
  swValue times, values;      /* SW_SIG_TABLE (times, values); SW_SIG_BSPLINE
                                 (values: the coefficients)                 */
  swValue scale;              /* number or vector the signal multiplies     */
  swDim base;                 /* dimension of the signal's own values       */
} swSignalVal;

typedef enum {
  SYM_PARAM, SYM_LET, SYM_FORMAL, SYM_MATERIAL, SYM_ROD, SYM_JOINT, SYM_COMPONENT, SYM_INSTANCE,
  SYM_MUSCLE, SYM_ENV, SYM_SIGNAL, SYM_LOOP
} swSymKind;

struct swScope;
typedef struct swSymbol {
  swSymKind kind;
  const char *name;
  const char *full;           /* with instance prefix: "left.humerus"      */
  swLoc loc;
  const swAst *def;
  struct swScope *scope;      /* where it is defined                       */
  int used;
  int state;                  /* 0 new, 1 evaluating, 2 done               */
  int main_file;              /* defined in the compiled file itself       */
  int index;                  /* rod, muscle, param or joint index in the scene */
  swValue value;              /* params, lets, formals                     */
  struct swScope *members;    /* instances: their scope                    */
  struct swSymbol **pass;     /* loops: one instance a pass (npass), or NULL */
  int first_pass, npass;      /* loops: the variable's first value, passes  */
  struct swMaterial *material;
} swSymbol;

typedef struct swScope {
  struct swScope *parent;
  const char *prefix;         /* "" or "left."                             */
  int file_level;             /* a file's top level: the main file's (global)
                                 or a namespace's (import "f" as ns;)     */
  swSymbol **sym;
  int n, cap;
} swScope;

typedef struct swMaterial {
  swValue E, G, poisson, density;
  int variational;            /* variational = true (1): the energy-consistent
                                 law; false (0): Gazzola et al. 2018's; not
                                 said (-1): each user's default (a rod
                                 Gazzola's, a muscle the variational law) */
} swMaterial;

typedef enum { ROD_PLAIN, ROD_BONE, ROD_TENDON } swRodKind;

/* A rod's rest or starting shape other than straight (sema_shape.c): a
 * helix, or a centreline given as a function of the arc length s.  Every
 * value in it is known when compiling. */
typedef enum { SHAPE_HELIX = 1, SHAPE_CURVE } swShapeKind;
struct swHExpr;
typedef struct {
  swShapeKind kind;
  swLoc loc;                  /* the field                                 */
  const char *field;          /* "shape", "rest_shape" or "start_shape"     */
  double radius, pitch;       /* helix: m, m per turn along its axis        */
  int hand;                   /* helix: +1 right-handed, -1 left            */
  struct swHExpr *r[3];       /* curve: the offset from the rod's start (m) */
  const char *sname;          /* curve: the name of its arc length          */
  int index;                  /* curve: its function shape_K in the C       */
} swSceneShape;

typedef struct {
  const char *name;           /* full name                                 */
  swRodKind kind;
  swLoc loc;
  int id;                     /* the runtime's rod id (sw_spec_add_rod)    */
  int nelem;                  /* known at compile time                     */
  int rigid;                  /* rigid = true                              */
  int implicit;               /* implicit = true (under integrator = imex) */
  int weightless;             /* gravity = false                           */
  int variational;            /* the variational constitutive law          */
  swValue start, direction, normal, length, radius_start, radius_end;
  swValue density, youngs, shear_modulus, poisson;
  swValue shear_hardening, twist_hardening, rest_kappa, rest_sigma, gamma;
  swValue gamma_rot;           /* rotational_damping, N s/rad; VAL_ERROR: not given */
  swDampingKind damping;
  int has_material;
  const char *material;       /* its material's name (NULL: none), output   */
  /* shapes (sema_shape.c); NULL: straight along 'direction' */
  const swSceneShape *rest_shape, *start_shape;
  double *x0, *Q0;            /* (nelem+1)x3, nelem x 9: where a shaped rod
                                 starts (NULL: straight), for its points     */
  double *xr, *Qr;            /* the same at rest (NULL: straight)          */
  /* geometry that changes in time (sema_swell.c): radius = a signal, the
   * rest curvature and twist scaled by signals, NULL where constant */
  struct swSignalVal *swell_radius, *swell_curvature, *swell_twist;
  int swell_twist_radius;     /* rest_twist_scale = follows_radius           */
  int swell_mass_grows;       /* mass = grows (density fixed)               */
  swLoc swell_loc;            /* the radius field, for the range check      */
} swSceneRod;

/* A muscle (swMuscleDesc): values the model did not give are VAL_ERROR and
 * keep sw_muscle_desc_init's defaults. */
typedef struct {
  const char *name;           /* full name                                 */
  swLoc loc;
  int id;                     /* runtime rod id of its first filament      */
  int filaments, nelem;       /* known at compile time                     */
  int has_nelem;              /* elements written (else the runtime's)     */
  long motor_units;           /* 0: not given                              */
  swValue start, end, normal, radius;
  swValue density, youngs, shear_modulus, poisson;
  swValue shear_hardening, twist_hardening, gamma;
  int variational;            /* the filaments' law is the variational one:
                                 1 as written, 2 by default (neither the
                                 muscle nor its material says); 0 Gazzola's */
  int weightless;             /* gravity = false: not on the filaments     */
  int has_damping;            /* damping written: damping, gamma set       */
  swDampingKind damping;
  swValue sigma_max, size_ratio, twitch_small, twitch_large, hill_a, v_max, fibre_diameter;
  swValue attach_stiffness, attach_damping;
  int nvia;                   /* via points (muscle_via.c), in path order    */
  swValue via[SW_MUSCLE_MAX_VIA];  /* positions at t = 0                     */
  int via_rod[SW_MUSCLE_MAX_VIA];  /* scene rod index carrying each, -1 space */
  int attach_rod[2];          /* scene rod index tied at from / to, -1 none */
  int attach_node[2];
  const char *attach_node_c[2];      /* param-dependent nodes' C text, or NULL */
  swSignalVal *activation;    /* NULL: not activated (the runtime's default) */
  swSignalVal *force;         /* force = ...: a prescribed pull (N); NULL: Hill's law */
  swLoc activation_loc;       /* the activate statement                    */
  const char *material;       /* its material's name (NULL: none), output   */
} swSceneMuscle;

/* passive MUSCLE.filament(K); */
typedef struct {
  swLoc loc;
  int muscle;                 /* index in swScene.muscle (= runtime muscle id) */
  int filament;               /* 0-based                                   */
} swScenePassive;

typedef struct {
  swLoc loc;
  int is_bc;                  /* 0: load, 1: boundary condition            */
  int kind;                   /* swLoadKind or swBCKind                     */
  int rod, index;             /* node/element (loads) or end 0/1 (BCs)      */
  swValue vec;                /* scale vector (3)                          */
  swSignalVal *sig;           /* NULL: constant                            */
  swValue until;              /* BCs: the time the hold lets go, s;
                                 VAL_ERROR: held for the whole run          */
} swSceneAction;

typedef struct {
  const char *name;
  swLoc loc;
  swJointKind kind;
  int rod_a, node_a, rod_b, node_b;
  const char *node_a_c, *node_b_c;   /* param-dependent nodes' C text, or NULL */
  swValue anchor, axis, stiffness, damping, rot_stiffness, rot_damping;
  swValue arm_a;              /* POINT + ARM as the first end: the arm (lab, t = 0);
                                 VAL_ERROR: none                            */
  int undamped;               /* damping = 0 written: no damping at all     */
  /* limits; VAL_ERROR: not given */
  int has_range;              /* range = (lower, upper) on a hinge          */
  swValue angle_min, angle_max, cone, limit_stiffness, limit_damping;
} swSceneJoint;

/* joint NAME = kinematic(LEADER, FOLLOWER) { ... }  (sema_kinematic.c) */
typedef struct {
  const char *name;
  swLoc loc;
  int leader_rod, leader_elem;   /* scene rod index, element 0..n-1        */
  double leader_xi;              /* 0..1 along that element                */
  int follower_rod, follower_node, follower_elem;
  swValue stiffness, damping;    /* damping VAL_ERROR: none                 */
  int reaction_rod, reaction_node; /* -1: on the leader                     */
  swValue reaction_weight;       /* VAL_ERROR: 1                            */
} swSceneKinematic;

typedef struct {
  const char *name;
  swLoc loc;
  swValue value;              /* default                                   */
  const char *unit;           /* as written, for --help                    */
  int ranged;                 /* `in (lo, hi)` given: a study varies it     */
  double lo, hi;              /* the range, SI, lo < hi                     */
} swSceneParam;

/* ---- environments (sema_env.c, sema_terrain.c) ---- */

/* Rods an environment acts on, as runtime rod ids (a muscle stands for its
 * filaments); n = 0: every rod of the scene. */
typedef struct {
  int n;
  int *id;                    /* (n) runtime rod ids                       */
  const char **name;          /* (n) for comments in the generated C       */
} swRodList;

/* A function expression (sema_fexpr.c): a terrain's height z = h(x, y) or a
 * time signal s(t), as a tree over its formals: each node a constant (a
 * swValue, possibly param-dependent), a formal, a local let, an operation
 * or a piecewise choice; in a signal also a built-in signal (ramp, sine,
 * ...) at a time, another signal at a time, or mod.  Checked for dimensions
 * when built; generated as C (gen_env.c: heights as forward-mode dual
 * numbers, signals as plain doubles) and evaluated with the same rules
 * inside the compiler (sema_height_eval, sema_signal_eval). */
typedef enum {
  HX_CONST, HX_X, HX_Y, HX_LET, HX_ADD, HX_SUB, HX_MUL, HX_DIV, HX_NEG, HX_POW,
  HX_SQRT, HX_SIN, HX_COS, HX_TAN, HX_EXP,
  HX_LT, HX_LE, HX_GT, HX_GE, HX_AND, HX_OR,
  HX_PIECEWISE,              /* kid: cond0, value0, cond1, value1, ..., default */
  HX_T,                      /* a signal's time formal                      */
  HX_MOD,                    /* kid: a, b; a - b floor(a / b)               */
  HX_ATOM,                   /* kid: the time; swScene.atom[ref] there      */
  HX_CALL,                   /* kid: the time; swScene.signal[ref] there    */
  HX_S,                      /* a shape's arc length formal                 */
  HX_LOG                     /* natural logarithm                           */
} swHOp;
typedef struct swHExpr {
  swHOp op;
  swDim dim;
  int boolean;                /* a condition, not a quantity               */
  swLoc loc;
  swValue k;                  /* HX_CONST                                  */
  double p;                   /* HX_POW exponent                           */
  int let;                    /* HX_LET: index into swHeight.let           */
  int ref;                    /* HX_ATOM, HX_CALL: index in the scene       */
  struct swSignalVal *atom;   /* HX_ATOM: the built-in signal               */
  struct swSceneSignal *callee; /* HX_CALL: the signal called               */
  int nkid;
  struct swHExpr **kid;
} swHExpr;
typedef struct {
  swHExpr *expr;
  int nlet;
  swHExpr **let;              /* (nlet) lets of the body that depend on x, y */
  const char **let_name;
  swLoc *let_loc;
  const char *xname, *yname;  /* the formals of height(x, y)               */
  swLoc loc;                  /* the height field                          */
} swHeight;
/* swHeightFn over a swHeight (ctx), params at their defaults. */
double sema_height_eval(double x, double y, double grad[2], const void *ctx);

/* signal NAME(t) = expr;  a time signal of the model (sema_signal.c), a
 * function of its formal, generated as signal_K(t) (gen_env.c). */
typedef struct swSceneSignal {
  const char *name;           /* full name                                 */
  const char *formal;         /* the time's name                           */
  swLoc loc;
  int index;                  /* in swScene.signal                          */
  swHExpr *expr;              /* NULL while it is being checked             */
  swDim dim;
  double span;                /* the run's duration: its range is sampled over [0, span] */
} swSceneSignal;
/* swSignalFn over a swSceneSignal (ctx), params at their defaults. */
double sema_signal_eval(double t, const void *ctx);

typedef struct {
  const char *name;
  swLoc loc;
  swHeight *height;           /* terrain; NULL: a plane                     */
  swValue origin, normal, stiffness, damping, mu_kinetic, mu_static, mu_rolling, slip_velocity;
  int contact_point;          /* 1: sideways friction at the contact point   */
  swRodList rods;             /* values not given are VAL_ERROR: the runtime's default */
} swSceneGround;

typedef struct {
  const char *name;
  swLoc loc;
  swFluidModel model;
  swFluidArea area;           /* quadratic drag's A (silhouette unless given) */
  swValue viscosity, density, drag_coefficient, body_length, velocity;
  int buoyancy;
  swRodList rods;
} swSceneFluid;

typedef struct {
  const char *name;
  swLoc loc;
  swValue stiffness, damping;
  swValue static_friction, kinetic_friction, tangential_stiffness; /* val_error: not given */
  int self;
  swRodList rods;
} swSceneContact;

/* obstacle NAME { shape = ...; ... }: values not given are VAL_ERROR (the
 * runtime's default); `half` is the box's size / 2 or the ellipsoid's
 * semi-axes */
typedef struct {
  const char *name;
  swLoc loc;
  swObstacleShape shape;
  swValue centre, axis, normal, radius, length, half, stiffness, damping;
  swValue static_friction, kinetic_friction, tangential_stiffness; /* friction: the
                                     one `friction` sets both coefficients */
  int carrier_rod, carrier_node;  /* runtime rod id and node (-1: fixed)    */
  const char *carrier_name;
  swRodList rods;
} swSceneObstacle;

typedef struct {
  const char *name;
  swLoc loc;
  int rod;                    /* runtime rod id                            */
  const char *rod_name;
  swValue coef;               /* (ncoef) N m                               */
  swValue wavelength, period, phase, ramp, direction;
  int reverse;
} swSceneWave;

typedef struct {
  const char *name;
  swLoc loc;
  swProbeKind kind;
  swRodList rods;             /* COM, COM_VELOCITY, MEAN_VELOCITY           */
  int rod, node;              /* NODE: runtime rod id and node             */
  const char *rod_name;
  swValue window;             /* MEAN_VELOCITY; VAL_ERROR: frame interval  */
} swSceneProbe;

/* An expectation (swExpectDesc; expect.c): constants, fixed when compiling. */
typedef struct {
  const char *text;           /* the statement as written, on one line     */
  swLoc loc;
  swExpectQuantity quantity;
  int index, component;       /* runtime joint, muscle or probe id         */
  int window;                 /* 0: at t0; 1: every step of [t0, t1]      */
  double t0, t1, lo, hi;      /* SI                                        */
  double scale;               /* the report's unit, in SI ...              */
  const char *unit;           /* ... and its name                          */
  int reduce;                 /* SW_REDUCE_NONE: an expect statement; else a
                                 reduction the objective reads (lo, hi, scale
                                 and unit unused), R[k] for the k-th of them */
} swSceneExpect;

/* The model's objective (sema_objective.c): maximize or minimize EXPR, and
 * the penalties, as values over the params P and the reductions R (the
 * entries of swScene.expect with `reduce` set, in order). */
typedef struct {
  int sense;                  /* +1 maximize, -1 minimize, 0: none          */
  const char *text;           /* "maximize EXPR" as written, on one line    */
  swLoc loc;
  swValue value;              /* a number; its C text reads P and R         */
  int npenalty;
  swValue *penalty;           /* (npenalty) of the objective's dimension     */
  swLoc *penalty_loc;         /* (npenalty) the statements                   */
  int nreduce;
  const char *unit;           /* the unit reports show it in ("" none) ...  */
  double scale;               /* ... its SI value                           */
  const char *si_unit;        /* its SI unit ("m/s"; "" none)               */
} swSceneObjective;

/* One selection of output: quantity `bit` (SW_OUT_*) for the listed items
 * of one scope: rods as runtime rod ids (a muscle stands for its
 * filaments), joints and muscles as scene indices; n < 0: all of them. */
typedef enum { OUT_RODS, OUT_JOINTS, OUT_MUSCLES } swOutScope;
typedef struct {
  unsigned bit;
  swOutScope scope;
  int n;
  int *id;
  swLoc loc;
} swOutSelect;

/* A quantity derived from the params (D[k] in the generated C): a let's
 * component or a rod's geometry that depends on a param, computed once when
 * the simulator builds the scene, so that what is written in terms of it
 * (a point on that rod, a rib laid from that point) reads D[k] rather than
 * repeating its expression. */
typedef struct {
  const char *text;           /* C over P and earlier D                    */
  const char *what;           /* "let p1.xa.x", "rod p1.rib_a: length"      */
  swLoc loc;
} swSceneDerived;

typedef struct {
  swSceneRod *rod;       int nrod, caprod;
  swSceneMuscle *muscle; int nmuscle, capmuscle;
  swScenePassive *passive; int npassive, cappassive;
  int nrodid;                 /* rods of the runtime: rods + filaments      */
  long nelem;                 /* elements of the whole scene                */
  swSceneAction *act;    int nact, capact;
  swSceneJoint *joint;   int njoint, capjoint;
  swSceneKinematic *kin; int nkin, capkin;
  swSceneParam *param;   int nparam, capparam;
  swSceneDerived *derived; int nderived, capderived;
  swSceneGround *ground; int nground, capground;
  swSceneFluid *fluid;   int nfluid, capfluid;
  swSceneContact *contact; int ncontact, capcontact;
  swSceneObstacle *obstacle; int nobstacle, capobstacle;
  swSceneWave *wave;     int nwave, capwave;
  swSceneProbe *probe;   int nprobe, capprobe;
  swSceneSignal **signal; int nsignal, capsignal;  /* signal NAME(t) = ...  */
  int ncurve;                 /* rods' shapes given as curves (shape_K)     */
  struct swSignalVal **atom; int natom, capatom;   /* built-in signals inside them */
  swSceneExpect *expect; int nexpect, capexpect;
  swSceneObjective objective;
  swValue gravity;            /* kind VAL_ERROR when absent                 */
  swSignalVal *gravity_sig;   /* NULL: constant; else gravity times it       */
  swLoc gravity_loc;
  swIntegrator integrator;
  double dt, duration, every; /* s; dt 0 = choose                          */
  swLoc dt_loc;
  int has_dt, has_duration;
  const char *out;            /* output path                               */
  swOutSelect *select;   int nselect, capselect;   /* output selections    */
  const struct swLetOverride *let;   /* (nlet) sinewc --let, applied      */
  int nlet;
  const char *model_name;     /* stem of the main file                     */
  char *source;               /* main file and imports, inlined (malloc)   */
  char sha256[65];
} swScene;

/* sinewc --let NAME=VALUE: a top-level let of the main file that takes the
 * value given on the command line instead of its own (like cc -D).  The
 * value must be of the let's own kind: a number of the same dimension, or
 * true or false. */
typedef struct swLetOverride {
  const char *name;           /* NAME                                      */
  const char *text;           /* "NAME=VALUE" as given                     */
  int truth;                  /* 1 true, 0 false, -1 a number              */
  double value;               /* the number, SI                            */
  swDim dim;
  /* set by the checker */
  int applied;                /* it replaced a let of the main file        */
  swLoc let_loc;              /* that let                                  */
  const char *error;          /* why it cannot apply (a usage error), or NULL */
} swLetOverride;

/* Check the model in file `file` (registered with diag) and build its scene.
 * Returns the number of errors (also counted by diag). */
int sema_check(swArena *arena, int file, swScene *scene);
/* The same with the overrides of sinewc --let: each one applied, or its
 * `error` set (an unknown name only when the model itself checked clean). */
int sema_check_lets(swArena *arena, int file, swLetOverride *lets, int nlets, swScene *scene);
void sema_scene_free(swScene *scene);
char *sema_read_file(const char *path, size_t *len, const char **why, int *not_text);

/* ---- values (sema_value.c) ---- */
swValue val_error(void);
swValue val_num(swArena *a, double x, swDim dim, swLoc loc);
swValue val_vec(swArena *a, int n, const double *x, swDim dim, swLoc loc);
int val_is_const(const swValue *v);
const char *val_c(swArena *a, const swValue *v, int i);  /* C text of component i */
swValue val_binop(swArena *a, int op, swValue x, swValue y, swLoc loc);
swValue val_neg(swArena *a, swValue x, swLoc loc);
swValue val_pow(swArena *a, swValue x, double p, swLoc loc);
swValue val_func(swArena *a, const char *fn, swValue x, swLoc loc);   /* sqrt, sin, cos, tan, exp */
swValue val_norm(swArena *a, swValue x, swLoc loc);
swValue val_truth(int truth, swLoc loc);                 /* VAL_TRUTH        */
/* "a number", "a vector", "true or false", ... for messages */
const char *val_kind_noun(const swValue *v);

/* ---- dimensions (units_dim.c) ---- */
extern const swDim DIM_NONE, DIM_LENGTH, DIM_TIME, DIM_MASS, DIM_ANGLE, DIM_PRESSURE, DIM_DENSITY;
swDim dim_make(int kg, int m, int s, int rad);
int dim_eq(swDim a, swDim b);
/* equal, ignoring the angle exponent unless `want` is a pure angle */
int dim_fits(swDim want, swDim got);
swDim dim_mul(swDim a, swDim b);
swDim dim_div(swDim a, swDim b);
int dim_pow(swDim a, double p, swDim *out);        /* 0 if p not integer */
int dim_is_none(swDim a);
const char *dim_describe(swArena *a, swDim d);

/* ---- sha256 (sha256.c) ---- */
void sha256_hex(const void *data, size_t len, char out[65]);

#endif
