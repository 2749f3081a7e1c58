/* gen.h — from the checked scene to the runtime: the lowering tables shared by
 * the compiler's checks and the C generator, and the generator itself.
 *
 * Design.  See gen_lower.c (one table per runtime struct) and gen_c.c (the
 * printer).  gen_check() runs the runtime's own validation and stable-dt
 * estimate on the scene with every param at its default.
 */
#ifndef SINEW_GEN_H
#define SINEW_GEN_H

#include <stdio.h>
#include "sema.h"

#define GEN_MAX_FIELDS 32

typedef struct {
  const char *member;        /* C member of the runtime struct            */
  size_t offset;             /* its offset                                */
  int n;                     /* doubles                                   */
  const swValue *value;
} swLowField;

int gen_rod_fields(const swSceneRod *r, swLowField *out);
/* the fields of a muscle that the model gives (the rest keep the runtime's
 * defaults from sw_muscle_desc_init) */
int gen_muscle_fields(const swSceneMuscle *m, swLowField *out);
int gen_joint_fields(const swSceneJoint *j, swLowField *out);
int gen_signal_fields(const swSignalVal *s, swLowField *out);
/* environments: the fields the model gives (the rest keep sw_*_desc_init's) */
int gen_ground_fields(const swSceneGround *g, swLowField *out);
int gen_fluid_fields(const swSceneFluid *f, swLowField *out);
int gen_contact_fields(const swSceneContact *c, swLowField *out);
int gen_obstacle_fields(const swSceneObstacle *o, swLowField *out);
int gen_wave_fields(const swSceneWave *w, swLowField *out);
swSignal gen_signal(const swSignalVal *sig);
/* The runtime's id of scene rod `rod` (scene indices skip muscles' filaments,
 * runtime ids do not), or -1 for -1. */
int gen_rod_id(const swScene *sc, int rod);
/* Rods and muscles are added to the runtime in the order of their ids: with
 * ri rods and mi muscles added so far, whether a rod comes next. */
int gen_rod_next(const swScene *sc, int ri, int mi);
swSpec *gen_spec(const swScene *sc);
void gen_expect_desc(const swSceneExpect *x, swExpectDesc *d);   /* constants */

/* Validate the scene with the runtime (sw_compile) and warn when dt is above
 * the stable estimate.  Returns the number of errors. */
int gen_check(const swScene *sc, double *stable_dt);

/* Print the simulator's C source. */
typedef struct {
  const char *compiler;      /* "sinewc 0.1.0"                            */
} swGenOptions;
int gen_c(FILE *out, swArena *a, const swScene *sc, const swGenOptions *opt);

/* gen_c.c's printing helpers, shared with gen_env.c */
void gen_c_string(FILE *out, const char *text);               /* escaped literal */
void gen_c_comment(FILE *out, const char *text, size_t len);  /* safe in a comment */
void gen_origin(FILE *out, swLoc loc, const char *indent);    /* #line + quoted line */
void gen_assign_fields(FILE *out, swArena *a, const char *var, const swLowField *f, int n);
/* the assignments of a signal to the lvalue var (load.signal, ...) */
void gen_emit_signal(FILE *out, swArena *a, const char *var, const swSignalVal *sig);

/* gen_env.c: the terrains' height functions (before build) and the
 * environments' blocks of build() */
void gen_env_heights(FILE *out, swArena *a, const swScene *sc);
void gen_env_build(FILE *out, swArena *a, const swScene *sc);

/* A function expression's condition (comparisons, and, or) as C, its
 * operands printed by `operand` (gen_env.c; a height's dual numbers, a
 * signal's doubles). */
typedef void (*gen_fexpr_fn)(FILE *out, swArena *a, const swHExpr *e, int depth);
void gen_fexpr_condition(FILE *out, swArena *a, const swHExpr *e, int depth, gen_fexpr_fn operand);
/* piecewise(): a chain of conditional expressions, one case a line, its
 * conditions' operands printed by `operand` and its values by `branch` */
void gen_fexpr_piecewise(FILE *out, swArena *a, const swHExpr *e, int depth, gen_fexpr_fn operand,
                         gen_fexpr_fn branch);

/* gen_shape.c: the rods' shapes given as curves, as C functions (before
 * build), and the lines of a shaped rod's block of build() */
void gen_shape_functions(FILE *out, swArena *a, const swScene *sc);
void gen_shape_build(FILE *out, swArena *a, const swSceneRod *r);

/* gen_signal.c: the model's signals as C functions (before build) and
 * their lines of build(); gen_fexpr_value prints a function expression
 * over plain doubles (a signal's t, a shape's s) */
void gen_fexpr_value(FILE *out, swArena *a, const swHExpr *e);
void gen_signal_functions(FILE *out, swArena *a, const swScene *sc);
void gen_signal_build(FILE *out, swArena *a, const swScene *sc);

#endif
