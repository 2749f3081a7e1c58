/* sinew_program.h — part of sinew.h (include that): a compiled model as a
 * program.
 *
 * Design.  swProgram is what the generated C hands the runtime: the model's
 * params, its build function, its run settings, output selection and
 * objective.  On it stand one evaluation of the objective in process
 * (runtime/study/evaluate.c), the studies over its params (runtime/study/)
 * and the simulator's command line, sw_main (runtime/sim/). */
#ifndef SINEW_PROGRAM_H
#define SINEW_PROGRAM_H

#include "sinew_io.h"

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
  double dt;           /* s: the step it ran with (0 when the scene was not
                          compiled)                                         */
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
