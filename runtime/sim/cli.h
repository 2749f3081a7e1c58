/* cli.h — what the files of the simulator's command line share: the table
 * of options, swCli (what the command line asked for) and the functions one
 * of them calls in another.  Internal to sim/: generated code never sees it.
 *
 * Design.  The command line is split by what its parts do: cli_options.c
 * reads argv into a swCli, cli_info.c prints --help and --info, cli.c is
 * sw_main (building the model, a run, the study entry) and cli_study.c
 * turns a study's options into swStudyOptions and a study's design into a
 * run's params (it sees swStudyCall, from study/study.h, not swCli), and
 * cli_accuracy.c runs a model again at smaller steps for --accuracy, and
 * cli_rigidity.c names the rods a run found nearly rigid.  A function called from another of these files
 * is declared here and named sw_cli_*; everything else stays static in its
 * file. */
#ifndef SINEW_CLI_H
#define SINEW_CLI_H
#include <stddef.h>

#include "sinew.h"
#include "study/study.h"

/* ---- the options (cli_options.c) ---- */

typedef enum {
  OPT_OUT, OPT_DURATION, OPT_DT, OPT_INTEGRATOR, OPT_EVERY, OPT_SET, OPT_THREADS, OPT_COMPARE,
  OPT_RTOL, OPT_RESTART, OPT_SWEEP, OPT_OPTIMIZE, OPT_BUDGET, OPT_POPSIZE, OPT_SIGMA,
  OPT_RESTARTS, OPT_START, OPT_SEED, OPT_STUDY, OPT_RESUME, OPT_REPLAY, OPT_EVAL_TIMEOUT,
  OPT_NO_RECHECK, OPT_ACCURACY, OPT_TOLERANCE, OPT_QUIET,
  OPT_INFO, OPT_HELP
} swOptionId;

typedef struct {
  swOptionId id;
  const char *name;
  const char *arg;           /* what the value is called; NULL for a flag   */
  const char *help;
} swOption;

/* The table of options and its length (cli_options.c): the parser and
 * --help are made from it. */
extern const swOption sw_cli_options[];
extern const size_t sw_cli_noptions;

/* A dimensionless quantity: a bare number, or a param without a unit. */
static const signed char DIM_NONE[SW_NDIM] = {0, 0, 0, 0};

/* What the command line asked for. */
typedef struct {
  const swProgram *p;
  const char *prog;          /* basename of argv[0], prefix of messages     */
  const char *out;           /* output path                                 */
  double duration, every, dt;
  int dt_given;              /* --dt was given                              */
  int duration_given;        /* --duration was given                        */
  int integrator;            /* --integrator, or -1: the model's            */
  long threads;
  int threads_set;           /* given on the command line */
  int threads_auto;          /* --threads auto: chosen for the model */
  int quiet, info, help;
  const char *golden;        /* --compare: the stored run, or NULL          */
  double rtol;               /* its tolerance (--rtol; default 1e-9)        */
  int rtol_given;
  const char *restart;       /* --restart: the run to continue, or NULL     */
  int out_given, every_given;
  double *P;                 /* (nparam) param values, SI                   */
  char *overridden;          /* (nparam) set by --set                       */
  char *started;             /* (nparam) given a start by --start NAME=VALUE */
  swStudyArgs study;         /* --sweep, --optimize, --resume and theirs     */
  const char *replay;        /* --replay: the study file, or NULL            */
  long replay_index;         /* its evaluation, or -1: the best              */
  swStudyDesign replayed;    /* that evaluation, as the file has it          */
  int accuracy;              /* --accuracy: the run again at dt/2, compared  */
  double tolerance;          /* --tolerance: halve dt until within it (0: no) */
} swCli;

/* ---- cli.c ---- */

/* A usage error: "PROG: message" on stderr; returns SW_EUSAGE. */
int sw_cli_complain(const swCli *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The threads of each step: --threads N, or for --threads auto by the model's size. */
long sw_cli_threads_for(const swCli *c, const swModel *m);
/* The run of c with m into out: output, expectations, objective, summary;
 * returns the exit code. */
int sw_cli_run(const swCli *c, const swModel *m, const char *out);
/* Builds the model at c's step and runs it into c->out (sw_cli_run). */
int sw_cli_simulate(const swCli *c);

/* ---- cli_accuracy.c ---- */

/* --accuracy: the run at m's step into c->out and at half of it, compared
 * (and with --tolerance, halved on until two agree); returns the exit code. */
int sw_cli_accuracy(const swCli *c, const swModel *m);

/* ---- cli_options.c ---- */

/* Reads argv[1..argc) into c and checks the options against each other. */
int sw_cli_parse_args(swCli *c, int argc, char **argv);

/* ---- cli_info.c ---- */

/* A time in the unit that keeps the number readable ("50 ns", "1.5 ms"). */
const char *sw_cli_format_time(char *buf, size_t len, double t);
/* A param's value in the unit the model wrote it in (its name in unit). */
double sw_cli_param_in_unit(const swParam *q, double value, char *unit, size_t len);
/* --help: the options with their defaults, the params, the objective. */
void sw_cli_print_help(const swCli *c, const char *default_out);
/* --info: the compiled scene m at its step, and what a run would write to out. */
void sw_cli_print_info(const swCli *c, const swModel *m, double stable, const char *dt_source,
                       const char *out);

/* ---- cli_rigidity.c ---- */

/* After a run's summary: the elastic rods that kept their rest shape
 * within SW_CLI_RIGID_LIKE over the frames (engine/rigidity.c), named as
 * rods the scene could hold rigid. */
void sw_cli_rigidity_note(const swCli *c, const swModel *m, const swData *d);

#endif
