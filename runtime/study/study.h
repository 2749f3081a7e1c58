/* study.h — sweeps and optimisations of a model's params (SIM --sweep,
 * --optimize, --resume), on one machine or across MPI ranks.  Internal to the
 * runtime: cli.c calls sw_study_main(); study_file.c keeps the study's HDF5
 * file; study_pool.c hands evaluations to workers (a thread of this process
 * and, under mpirun, the other ranks through study_mpi.c).
 *
 * The study does not know what an evaluation is: it calls swStudyEvalFn with
 * every param's value (SI) and gets a status and a score back.  cli.c makes
 * that a run of the model (sw_evaluate); the tests make it a test function. */
#ifndef SINEW_STUDY_H
#define SINEW_STUDY_H
#include <stddef.h>
#include <stdint.h>

/* How an evaluation ended (an HDF5 enum in the file, so that readers see the
 * names).  Every status but OK is a scored failure: it ranks below any
 * design that ran, and the study goes on. */
typedef enum {
  SW_EVAL_PENDING = 0,    /* not evaluated yet (a row the file reserves)     */
  SW_EVAL_OK = 1,
  SW_EVAL_UNSTABLE = 2,   /* the simulation became unstable                   */
  SW_EVAL_INVALID = 3,    /* the params give no valid scene                   */
  SW_EVAL_FAILED = 4      /* anything else (out of memory, ...)               */
} swEvalStatus;
/* "pending", "ok", "unstable", "invalid", "failed" (study_file.c) */
const char *sw_eval_status_name(int status);

typedef struct {
  int status;             /* swEvalStatus                                    */
  double objective;       /* SI; NaN when not reached                        */
  double penalty;         /* sum of the penalties, SI                        */
  double score;           /* larger is better; -INFINITY unless OK          */
  double sim_time;        /* s simulated                                     */
  double wall;            /* s of wall time the evaluation took              */
  double dt;              /* s: the step it ran with (0: not compiled)       */
  int rank;               /* the MPI rank that ran it (0 without MPI)        */
  int interrupted;        /* Ctrl-C stopped it: not a result                 */
  char message[256];      /* why it failed ("" when OK)                      */
} swStudyEval;

/* Evaluates the design P (all nparam params, SI) into r, with everything as
 * the study runs it but the time step: the step the study's evaluation of P
 * takes, times dt_scale (1 for the study's designs; 0.5 for the recheck of
 * its best at dt/2).  Called on one thread at a time per process; must not
 * print. */
typedef void (*swStudyEvalFn)(void *ctx, const double *P, double dt_scale, swStudyEval *r);

typedef enum { SW_STUDY_GRID = 0, SW_STUDY_LHS, SW_STUDY_CMAES } swStudyKind;

typedef struct {
  const char *prog;          /* prefix of messages                          */
  const char *path;          /* the study's HDF5 file                        */
  int resume;                /* continue the study `path` holds              */
  int quiet;
  swStudyKind kind;
  long levels;               /* grid: points per varied param (>= 2)        */
  long samples;              /* lhs: designs; cmaes: budget of evaluations   */
  long popsize;              /* cmaes: lambda (0: 4 + floor(3 ln n))         */
  double sigma;              /* cmaes: initial step, fraction of each range  */
  long restarts;             /* cmaes: IPOP restarts (population doubled)    */
  uint64_t seed;
  double eval_timeout;       /* s; an evaluation running longer than this on
                                another rank is re-queued (0: automatic)    */
  /* the params: all of them, the values of those not varied */
  int nparam;
  const char *const *name;
  const char *const *unit;   /* unit shown ("" for none)                     */
  const double *scale;       /* SI value of one unit                         */
  const char *const *si_unit; /* the SI unit of each ("m", "Pa"; "" for none;
                                NULL: none given), of /evaluations/params_si */
  const double *value;       /* SI: defaults and --set; the varied ones'
                                values are the start of an optimisation     */
  const int *vary;           /* 1: ranged and not fixed by --set             */
  const double *lo, *hi;     /* SI, for the varied ones                       */
  /* the objective */
  int sense;                 /* +1 maximize, -1 minimize                     */
  const char *objective_text, *objective_unit;
  double objective_scale;
  /* the model, recorded and checked on --resume */
  const char *model_name, *model_sha256;
  const char *run_settings;  /* "duration=...;dt=...;integrator=..."          */
  /* the recheck (study_recheck.c): once the study is complete, its best
   * `recheck` distinct designs are evaluated again at dt/2 and the report
   * says how much each objective moved (0: no recheck, the file's /recheck
   * left as it is) */
  int recheck;
  int no_recheck;            /* --no-recheck: evaluate none, report those the
                                file already holds for the best designs      */
  swStudyEvalFn eval;
  void *ctx;
} swStudyOptions;

/* Runs (or continues) the study on this process and, under mpirun, on every
 * rank; returns the exit code (SW_OK; SW_EUSAGE; SW_EIO; SW_EINTERRUPT). On
 * ranks other than 0 it serves evaluations and returns SW_OK. */
int sw_study_run(const swStudyOptions *o);

/* What a study file says about how it was made, for --resume.  Strings are
 * copied into the buffers; value/vary/lo/hi are arrays of nparam that the
 * caller allocates after sw_study_file_count.  SW_OK or SW_EIO with err. */
typedef struct {
  swStudyKind kind;
  long levels, samples, popsize, restarts;
  double sigma;
  uint64_t seed;
  char model_sha256[65];
  char run_settings[512];
  char fixed[2048];           /* "name=value;..." SI, every param's start value */
  char varied[2048];          /* "name;name;..." the varied params            */
} swStudySettings;
int sw_study_file_settings(const char *path, swStudySettings *s, char *err, size_t errlen);

/* One design of a study file, for --start and --replay. */
typedef struct {
  long index;                /* its row (the best's, when asked for -1)       */
  long rows;                 /* the rows of /evaluations                      */
  int status;                /* swEvalStatus                                  */
  double objective, penalty, score;   /* as stored: in the objective's unit  */
  int exact;                 /* 1: the values are /evaluations/params_si's, the
                                SI values evaluated, bit for bit; 0: the file
                                predates params_si (or lacks that row): the
                                values shown, converted to SI, which may
                                differ from those evaluated in the last bits */
} swStudyDesign;

/* Design `index` of a study file (-1: its best, /best's index): value[i]
 * (SI) and found[i] = 1 for each of the nparam params name[] the file's
 * study also varied or held, found[i] = 0 for the others.  The values are
 * /evaluations/params_si's; a file without it stores them in the units its
 * model showed them in, converted here: each must be this model's unit[i]
 * (whose SI value is scale[i]) or another unit of the same dimension, else
 * an error names the param (a unit of another dimension is refused either
 * way).  SW_OK; SW_EUSAGE with err when there is no such row (or no best);
 * SW_EIO with err when the file cannot be read as a study. */
int sw_study_file_design(const char *path, long index, int nparam, const char *const *name,
                         const char *const *unit, const double *scale, double *value,
                         int *found, swStudyDesign *d, char *err, size_t errlen);

/* ---- the command line's side (cli_study.c) ---- */
#include "sinew.h"

/* What --sweep, --optimize, --budget, --popsize, --sigma, --restarts,
 * --seed, --study, --resume, --eval-timeout and --no-recheck asked for
 * (cli_options.c). */
typedef struct {
  int mode;                  /* 0: no study; 1: --sweep; 2: --optimize        */
  swStudyKind kind;
  long levels, samples, popsize, restarts;
  double sigma;
  uint64_t seed;
  double eval_timeout;
  int no_recheck;            /* --no-recheck                                  */
  const char *study, *resume;
  const char *start;         /* --start: the study whose best design CMA-ES starts at */
  int start_given;           /* --start FILE or NAME=VALUE                     */
  int kind_given, budget_given, popsize_given, sigma_given, restarts_given, seed_given;
} swStudyArgs;

typedef struct {
  const swProgram *p;
  const char *prog;
  double *P;                 /* every param's value (defaults and --set), SI   */
  const char *overridden;    /* 1: given with --set                           */
  const char *started;       /* 1: given a start with --start NAME=VALUE      */
  const char *const *unit;   /* the unit each param is shown in, its SI value  */
  const double *scale;
  const char *const *si_unit; /* the SI unit of each param ("" for none)      */
  double duration, dt;
  int duration_given, dt_given, integrator, quiet;
  swStudyArgs args;
} swStudyCall;

/* Runs the study the command line asked for; returns the exit code. */
int sw_study_cli(swStudyCall *c);

/* --replay PATH [best|N]: design `index` of the study PATH (-1: its best)
 * into c: every param's value as evaluated (c->P) and the evaluations'
 * duration, dt and integrator, checked against those the command line
 * gave; prints the design (unless quiet).  The design, as the file has it,
 * in *d.  SW_OK; SW_EUSAGE (no such evaluation, one that failed, a --set
 * or run setting that disagrees); SW_EIO (not a study file, a study of
 * another model). */
int sw_study_replay(swStudyCall *c, const char *path, long index, swStudyDesign *d);

/* 1 when this process was started by mpirun (or srun) with more than one
 * rank; its rank in *rank. */
int sw_study_launched(int *rank, int *size);
/* 1 when the runtime was linked with its MPI transport. */
int sw_study_have_mpi(void);

#endif
