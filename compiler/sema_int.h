/* sema_int.h — state shared by the checker's files (sema.c and the
 * sema_*.c beside it); not used outside the checker.
 *
 * Design.  One swSema per compilation: the arena, the scene being built, the
 * global scope, the stack of files being imported (for cycle messages) and
 * the list of every symbol (for "never used" warnings).  Definitions are
 * evaluated lazily, on first use or in file order, whichever comes first; a
 * definition met again while it is being evaluated is a cycle.
 */
#ifndef SINEW_SEMA_INT_H
#define SINEW_SEMA_INT_H

#include "diag.h"
#include "sema.h"

#define SEMA_MAX_IMPORT_DEPTH 32
#define SEMA_MAX_ELEMENTS 1000000   /* elements in a whole scene */
#define SEMA_MAX_INSTANCE_DEPTH 16
/* definitions and statements that component instances may add to a model:
 * nesting multiplies them (ten uses of a component that uses ten ...) */
#define SEMA_MAX_EXPANDED 50000
/* Definitions are evaluated in the order of the file, and one that uses a
 * name defined further down evaluates that definition first, inside its own
 * evaluation: 20000 lets, each using the one defined below it, overflowed
 * the stack (so did 2000 such bones, whose evaluation takes more of it).
 * Bounded: definitions evaluated inside one another, and sema_eval calls
 * inside one another (an expression's levels, at most AST_MAX_DEPTH, and
 * those of the definitions it evaluates on the way). */
#define SEMA_MAX_DEF_CHAIN 64
#define SEMA_MAX_EVAL_DEPTH 512

/* Statements kept when met, with their scopes, and checked after the last
 * item (sema_later). */
typedef struct {
  const swAst **item;
  swScope **scope;
  int n, cap;
} swLater;
void sema_later(swLater *l, swScope *scope, const swAst *it);   /* sema_expectation.c */

typedef struct {
  swArena *a;
  swScene *scene;
  swScope *global;
  int main_file;
  int import_stack[SEMA_MAX_IMPORT_DEPTH];
  swLoc import_loc[SEMA_MAX_IMPORT_DEPTH];
  int import_depth;
  char **done_paths;          /* canonical paths of files already read */
  int ndone, capdone;
  swSymbol **all;             /* every symbol, for unused warnings      */
  int nall, capall;
  int instance_depth;
  int nexpanded;              /* items added by instances, against SEMA_MAX_EXPANDED */
  /* source text with imports, for model_source */
  char *src;
  size_t srclen, srccap;
  /* sinewc --let: overrides of the main file's top-level lets */
  swLetOverride *lets;
  int nlets;
  /* items met once per scene */
  swLoc simulate_loc, output_loc;
  int has_simulate, has_output;
  /* the items of a runnable scene imported for its definitions: its scene
   * statements (actions, simulate, output, expect, use, environments) are
   * skipped (sema_check_file) */
  int defs_only;
  /* the first import that could not be read: unknown names may be its */
  const swAst *failed_import;
  /* the symbols being evaluated, outermost first, to name a cycle */
  swSymbol *evaluating[SEMA_MAX_DEF_CHAIN];
  int nevaluating;
  int eval_depth;             /* sema_eval calls under way, against SEMA_MAX_EVAL_DEPTH */
  int eval_too_deep;          /* the error of either bound, said once */
  /* output's selections, checked once every rod, joint and muscle is known */
  const swAst *output_item;
  swScope *output_scope;
  /* expect statements, checked once the whole scene (its probes) is known */
  swLater expects;
  /* maximize, minimize and penalty statements, likewise */
  swLater objectives;
  /* set while one of them is evaluated: a reduction (at, mean_over, ...)
   * is allowed there and nowhere else */
  int reducing;
  /* probes whose declaration failed (already reported): a quantity that
   * reads one is not reported again as naming no probe */
  const char **bad_probe;
  int nbad_probe, capbad_probe;
} swSema;

/* sema_scope.c: scopes and names */
swScope *sema_scope_new(swSema *S, swScope *parent, const char *prefix);   /* an empty scope */
/* `name` declared in `scope`; NULL after reporting a clash or a reserved name */
swSymbol *sema_declare(swSema *S, swScope *scope, swSymKind kind, const char *name, swLoc loc,
                       const swAst *def);
swSymbol *sema_lookup(swSema *S, swScope *scope, const char *name);
swSymbol *sema_lookup_local(swScope *scope, const char *name);
void sema_report_unknown(swSema *S, swScope *scope, const char *name, swLoc loc,
                         const char *what);
const char *sema_sym_noun(swSymKind kind);   /* "let", "component parameter", ... */
const char *sema_sym_a_noun(swSymKind kind); /* with its article: "a let", "an instance" */
/* Instances' members called `name` (of kind `kind`, -1 any) by full name,
 * at most max; and the hint made of them ("; did you mean 'right.x'?"), ""
 * when none (sema_scope.c). */
int sema_members_named(const swScope *scope, const char *name, int kind, const char **out,
                       int max);
const char *sema_member_hint(const swScope *scope, const char *name, int kind, char *buf,
                             size_t len);

/* sema_import.c: files, imports and the recorded model source */
/* import "f" [as NAMESPACE]: the file found, read and checked into the scope */
void sema_import(swSema *S, const swAst *item, swScope *scope);
void sema_append_source(swSema *S, const char *text, size_t len);   /* to the model source */
void sema_mark_done(swSema *S, const char *canon);   /* a path (or sema_done_key) as read */
/* "PREFIX\x1fPATH": the key of a file imported into a scope */
const char *sema_done_key(swSema *S, const swScope *scope, const char *canon);

/* sema.c: the driver */
void sema_items(swSema *S, swScope *scope, const swAst *items, int first);
void sema_check_file(swSema *S, int file, swScope *scope);   /* a file's items, into scope */

/* sema_expr.c */
swValue sema_eval(swSema *S, swScope *scope, const swAst *e);
/* an operand of arithmetic; an unknown name, a definition or a switch: reported, VAL_ERROR */
swValue sema_operand(swSema *S, swScope *scope, const swAst *e);
const char *sema_describe_value(swSema *S, const swValue *v);   /* "a time signal", ... */
/* a constant or an expression of params (1); a reduction of the run is reported (0) */
int sema_known_at_build(swSema *S, const swValue *v, const char *what);
/* a value required to be a number (n == 1) or vector of n components with
 * dimension `want` (dim_fits); `what` names it in messages */
swValue sema_expect(swSema *S, swScope *scope, const swAst *e, int n, swDim want,
                    const char *what);
swValue sema_expect_value(swSema *S, swValue v, int n, swDim want, const char *what);
int sema_const_int(swSema *S, swValue v, const char *what, long lo, long hi, long *out);
int sema_require_const(swSema *S, const swValue *v, const char *what);
const char *sema_word(swSema *S, swScope *scope, const swAst *e, const char *what,
                      const char *const *choices, int nchoices);
/* A switch: true or false, written as the word or held by a let or a
 * component parameter; 1 or 0, -1 after an error (reported, naming `what`
 * and, for a name holding something else, where its value was written). */
int sema_truth(swSema *S, swScope *scope, const swAst *e, const char *what);
/* A scalar signal's value with its scale folded in (sema_muscle.c): a
 * number as a constant signal; NULL after an error. */
struct swSignalVal *sema_scalar_signal(swSema *S, swValue v, const char *what);

/* sema_call.c */
swValue sema_eval_call(swSema *S, swScope *scope, const swAst *call);   /* a built-in function */

/* sema_def.c */
void sema_eval_symbol(swSema *S, swSymbol *sym);
swValue sema_vec3(swSema *S, double x, double y, double z, swDim dim, swLoc loc);
/* reports "WHAT must be positive" unless v is a positive number; 0 if not */
int sema_positive(swSema *S, const swValue *v, const char *what, const char *unit);
/* each component of v that a param reaches beyond a bare P[k] or D[k] made a D[k] of its own */
void sema_derive(swSema *S, swValue *v, const char *what, swLoc loc);

/* sema_rod.c: rods and the points on them */
void sema_eval_rod(swSema *S, swSymbol *sym);   /* a rod, bone or tendon, into the scene */
/* a position: a point on a rod (kept as VAL_VEC with its rod and node), or a
 * 3-vector of lengths */
swValue sema_position(swSema *S, swScope *scope, const swAst *e, const char *what);
swValue sema_position_on(swSema *S, swScope *scope, const swAst *e, const char *what, int *rod,
                         int *node, const char **node_c);   /* also the rod and node of a
                                                               point on a rod */
swValue sema_rod_point(swSema *S, swSymbol *rod, swValue frac, int node, swLoc loc);
int sema_point_fixed(const swValue *p, const char *what);
swValue sema_rod_length(swSema *S, swSymbol *rod, swLoc loc);


/* sema_stmt.c */
void sema_joint(swSema *S, swScope *scope, const swAst *item);
void sema_action(swSema *S, swScope *scope, const swAst *item);
/* The "until T" of an action (an argument named until, its last child), or
 * NULL; and the error for one on a statement that holds nothing. */
const swAst *sema_action_until(const swAst *item);
void sema_until_misplaced(const swAst *item);
void sema_simulate(swSema *S, swScope *scope, const swAst *item);
void sema_output(swSema *S, swScope *scope, const swAst *item);      /* sema_output.c */
void sema_output_selections(swSema *S);

/* sema_env.c: ground, terrain, fluid, contact, torque_wave definitions and
 * the probes of an output block */
int sema_is_env_kind(const char *kind);
void sema_env(swSema *S, swScope *scope, const swAst *item);
void sema_probe(swSema *S, swScope *scope, const swAst *field);
/* sema_expectation.c: an expect statement is kept when met and checked by
 * sema_expectations after the last item */
void sema_expectation_later(swSema *S, swScope *scope, const swAst *it);
void sema_expectations(swSema *S);
/* the quantity an expectation or a reduction reads (`who` names it in
 * messages): its swExpectQuantity, index and component into x, its
 * dimension into dim; 0 after reporting why not */
int sema_quantity(swSema *S, swScope *scope, const swAst *q, const char *who,
                  swSceneExpect *x, swDim *dim);
/* appends an entry (an expectation or a reduction) to the scene's list */
void sema_add_expect(swSema *S, const swSceneExpect *x);
/* the source text of loc on one line, blanks folded */
const char *sema_source_text(swSema *S, swLoc loc);
/* sema_objective.c: maximize, minimize and penalty statements are kept when
 * met (sema_objective_later: 1 when `it` is one) and checked by
 * sema_objectives after the expectations; sema_reduction evaluates at(),
 * mean_over(), max_over() and min_over() inside them */
int sema_is_objective_word(const char *word);
void sema_objective_later(swSema *S, swScope *scope, const swAst *it);
void sema_objectives(swSema *S);
swValue sema_reduction(swSema *S, swScope *scope, const swAst *call);
/* a rod list: NAME, (NAME, NAME, ...), all; muscles stand for their filaments */
int sema_rod_list(swSema *S, swScope *scope, const swAst *e, const char *what, swRodList *out);

/* sema_fexpr.c: function expressions over formals (a height's x and y, a
 * signal's t).  The context says which formals there are, the lets local to
 * the body, and whether the body is a signal's (built-in signals, the
 * model's signals and mod() allowed). */
#define SW_FEXPR_MAX_LETS 64
typedef struct swFCtx {
  swSema *S;
  swScope *scope;
  const char *what;           /* "the height of terrain 'hills'"            */
  const char *term;           /* "a term of a height", for sema_expect_value */
  int nformal;
  const char *formal[2];
  swHOp formal_op[2];         /* HX_X, HX_Y; HX_T                           */
  swDim formal_dim[2];
  int time;                   /* a signal's body                            */
  int shape;                  /* a rod's shape (sema_shape.c)               */
  int nlocal;
  const char *local_name[SW_FEXPR_MAX_LETS];
  swHExpr *local[SW_FEXPR_MAX_LETS];   /* each local let's tree (HX_LET or a constant) */
  swLoc local_loc[SW_FEXPR_MAX_LETS];
  int local_used[SW_FEXPR_MAX_LETS];
} swFCtx;
/* a quantity (not a condition); NULL after an error */
swHExpr *sema_fexpr(swFCtx *C, const swAst *e, const char *role);
swHExpr *sema_fexpr_node(swSema *S, swHOp op, swDim dim, swLoc loc, int nkid);
const char *sema_fexpr_dim_text(swSema *S, const swHExpr *e);
typedef struct { double v, x, y; } swDual;   /* a value and its d/dx, d/dy */
/* e at (X, Y) (a signal's time in X), lets[] the values of the body's lets */
swDual sema_fexpr_eval(const swHExpr *e, swDual X, swDual Y, const swDual *lets);

/* sema_signal.c: signal NAME(t) = expr; */
int sema_is_signal_def(const swAst *it);
const char *sema_signal_def_name(const swAst *it);
/* the signal of a symbol, checked first if it is not yet; NULL after an error */
swSceneSignal *sema_signal_of(swSema *S, swSymbol *sym, swLoc use);
void sema_signal_def(swSema *S, swScope *scope, const swAst *it);
/* sema_call.c: sig as a value of dimension dim, scaled by 1 */
swValue sema_make_signal(swSema *S, swSignalVal *sig, swDim dim, swLoc loc);
/* a signal named where a value goes: the signal, scaled by 1 */
swValue sema_signal_value(swSema *S, swSymbol *sym, swLoc loc);

/* sema_stmt.c: where the node a point on a rod acts on lies at t = 0 */
void sema_node_position(const swScene *scn, const swValue *p, double x[3]);

/* sema_kinematic.c: joint NAME = kinematic(LEADER, FOLLOWER) { ... } */
void sema_kinematic(swSema *S, swScope *scope, const swAst *it, const char *name);

/* sema_terrain.c: the height(x, y) of a terrain; NULL after an error */
swHeight *sema_height(swSema *S, swScope *scope, const swAst *body, const swAst *field,
                      const char *what);

/* sema_muscle.c */
void sema_eval_muscle(swSema *S, swSymbol *sym);
void sema_activate(swSema *S, swScope *scope, const swAst *item);
void sema_passive(swSema *S, swScope *scope, const swAst *item);
/* the error for a muscle used where a rod or a point on one is expected */
void sema_muscle_not_rod(swSema *S, const swSymbol *muscle, swLoc loc);

/* Field table of a definition body: the entries under their keys, unknown
 * and repeated keys reported. */
#define SEMA_MAX_FIELDS 48            /* keys of the longest table (the muscle's: 33) */
typedef struct {
  const char *const *keys;
  int nkeys;
  const swAst *value[SEMA_MAX_FIELDS];
  int damaged;                /* the body lost a field to a syntax error     */
  int unknown;                /* it has a field of no known key (misspelt)   */
} swFields;
/* Whether a body is whole, so that a field it lacks is really missing: not
 * lost to a syntax error, nor misspelt (that error is already reported). */
static inline int sema_fields_whole(const swFields *f) { return !f->damaged && !f->unknown; }
/* A field is missing: the error, unless the body is not whole. */
void sema_missing(const swFields *f, swLoc loc, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
void sema_fields(swSema *S, const swAst *body, int first, const char *what,
                 const char *const *keys, int nkeys, swFields *f);
const swAst *sema_field(const swFields *f, const char *key);
/* the whole field (its formals in kid[1], if any), or NULL */
const swAst *sema_field_node(const swFields *f, const char *key);
/* the value of field `key` as a number (n == 1) or n-vector of dimension
 * `want`; VAL_ERROR when absent or wrong */
swValue sema_field_value(swSema *S, swScope *scope, const swFields *f, const char *key, int n,
                         swDim want);
/* damping and damping_model of rods and muscles (sema_def.c); clears *ok
 * (if given) on a bad model word */
swDampingKind sema_damping_kind(swSema *S, swScope *sc, const swFields *f, int *ok);

/* material = NAME and the overrides E, G, poisson, density, variational
 * (sema_tissue) */
typedef struct {
  const swMaterial *mat;      /* NULL: no material                         */
  const char *mat_name;       /* its full name (NULL: none)                */
  const swAst *me, *E_ast, *rho_ast;   /* the fields, when written         */
  swValue youngs, density, shear_modulus, poisson;   /* VAL_ERROR: not given */
  int variational;            /* the law, written or the material's: 1
                                 variational, 0 Gazzola's, -1 said by neither */
} swTissue;
int sema_tissue(swSema *S, swScope *sc, const swFields *f, swTissue *t);

/* sema_shape.c: a rod's shape, rest_shape and start_shape fields.  The
 * shapes are read first (sema_rod_shapes: *length in, the rod's length or 0
 * when not written; out, the arc length, which a helix may set), then built
 * once the rod is placed (sema_rod_place_shapes: x0, Q0 and, for a rod
 * starting on a curve, its direction and default normal). */
typedef struct {
  const swSceneShape *rest, *start;   /* NULL: straight                    */
  int same;                           /* `shape`: one shape for both        */
  int given;                          /* any of the three fields written    */
} swRodShapes;
int sema_rod_shapes(swSema *S, swScope *sc, const swFields *f, const char *what,
                    double *length, swRodShapes *out);
int sema_rod_place_shapes(swSema *S, swSceneRod *r, const swRodShapes *sh, int normal_given,
                          const char *what);
/* the point at fraction f of a shaped rod (x0 set), where it starts */
void sema_shape_point(const swSceneRod *r, double f, double x[3]);

/* sema_swell.c: a rod's geometry that changes in time */
int sema_rod_swell(swSema *S, swScope *scope, const swFields *f, swSceneRod *r, const char *what,
                   int shape_unknown);
void sema_swell_check(swSema *S);

/* The environments' field helpers (sema_env.c): a scene array grown by one
 * (zeroed slot); an optional field of dimension `want` that must be >= 0
 * (pos = 0) or > 0; a vector that must not be zero; the `rods` list; the
 * friction fields of obstacles and contacts.  The
 * obstacle definition (sema_obstacle.c). */
static const swDim DIM_STIFFNESS = {{1, 0, -2, 0}};   /* N/m  */
static const swDim DIM_DAMPING = {{1, 0, -1, 0}};     /* kg/s */
void *sema_env_append(void **arr, int *n, int *cap, size_t item);
swValue sema_env_bounded(swSema *S, swScope *sc, const swFields *f, const char *key, int n, swDim want,
                         int pos);
swValue sema_env_nonzero_vector(swSema *S, swScope *sc, const swFields *f, const char *key, swDim want);
int sema_env_rods_field(swSema *S, swScope *sc, const swFields *f, const char *what, swRodList *out);
int sema_env_friction(swSema *S, swScope *sc, const swFields *f, const char *what, swValue *mu_s,
                      swValue *mu_k, swValue *k_t);
void sema_obstacle(swSema *S, swScope *sc, const swAst *it, const char *name, const char *what);

#endif
