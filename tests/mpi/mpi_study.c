/* mpi_study.c — the study driver under mpirun without a simulation: the
 * designs of a grid, a Latin hypercube or CMA-ES on Rosenbrock's function
 * in three params, each evaluation taking EVAL_MS milliseconds of sleep (so
 * that the ranks share the work), written to FILE.  tests/lang/test_mpi.sh
 * runs it with -np 1, 2 and 4 and compares the files.
 *   mpi_study FILE grid|lhs|cmaes [resume] [timeout_s] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sinew.h"
#include "study.h"

static void rosenbrock(void *ctx, const double *P, double dt_scale, swStudyEval *r) {
  (void)ctx;
  (void)dt_scale;
  const char *ms = getenv("EVAL_MS");
  struct timespec ts = {0, (ms ? atol(ms) : 20) * 1000000L};
  nanosleep(&ts, NULL);
  double f = 0;
  for (int i = 0; i < 2; i++)
    f += 100 * pow(P[i + 1] - P[i] * P[i], 2) + pow(1 - P[i], 2);
  r->status = P[0] > 1.9 ? SW_EVAL_UNSTABLE : SW_EVAL_OK;   /* a corner fails */
  r->objective = f;
  r->penalty = 0;
  r->score = r->status == SW_EVAL_OK ? -f : -INFINITY;
  r->sim_time = 1;
}

int main(int argc, char **argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: mpi_study FILE grid|lhs|cmaes [resume] [timeout_s]\n");
    return 2;
  }
  static const char *const names[] = {"a", "b", "c"}, *const units[] = {"", "", ""};
  static const double scale[] = {1, 1, 1}, value[] = {-1, 1.5, 0.5}, lo[] = {-2, -2, -2},
                      hi[] = {2, 2, 2};
  static const int vary[] = {1, 1, 1};
  swStudyOptions o;
  memset(&o, 0, sizeof o);
  o.prog = "mpi_study";
  o.path = argv[1];
  o.kind = !strcmp(argv[2], "grid") ? SW_STUDY_GRID : !strcmp(argv[2], "lhs") ? SW_STUDY_LHS
                                                                               : SW_STUDY_CMAES;
  o.resume = argc > 3 && !strcmp(argv[3], "resume");
  o.eval_timeout = argc > 4 ? atof(argv[4]) : 0;
  o.quiet = getenv("QUIET") != NULL;
  o.levels = 4;
  o.samples = o.kind == SW_STUDY_LHS ? 40 : 200;
  o.sigma = 0.25;
  o.seed = 7;
  o.nparam = 3;
  o.name = names;
  o.unit = units;
  o.scale = scale;
  o.value = value;
  o.vary = vary;
  o.lo = lo;
  o.hi = hi;
  o.sense = -1;
  o.objective_text = "rosenbrock(a, b, c)";
  o.objective_unit = "";
  o.objective_scale = 1;
  o.model_name = "mpi_study";
  o.model_sha256 = "-";
  o.run_settings = "";
  o.eval = rosenbrock;
  return sw_study_run(&o);
}
