/* cli_accuracy.c — SIM --accuracy [--tolerance R]: how much the answer of a
 * run depends on its time step, seen by the user.
 *
 * Design.  The default step is half the stable estimate: chosen so that the
 * run does not blow up, not so that it is accurate, and a scene with
 * contact, joint limits or a chaotic motion can move far with the step.
 * --accuracy runs the model at its step dt into --out, as a plain run does
 * (messages, expectations, objective), and at dt/2 into OUT.dt2.h5 in a
 * child process at the same time (the second core), then compares the two
 * files (io/accuracy.c): for each probe and hinge angle the largest
 * difference, that difference over the observable's range, and the time
 * where the two runs part (their difference first exceeds the tolerance of
 * the range); and the objective at each step.  A difference beyond the
 * tolerance (1% without --tolerance) is reported as sensitivity to the step.
 * With --tolerance R the step is halved on, one run at a time
 * (OUT.dt4.h5, OUT.dt8.h5, ...), until a run agrees with the run at half its
 * step within R on every observable and the objective, at most
 * ACCURACY_MAX_HALVINGS times; the step it finds is named with its file, and
 * a search that ends without one exits 5, as a failed expectation does.
 * A child's messages go to a temporary file and are shown only when its run
 * fails, so the report is the parent's. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sinew.h"
#include "cli.h"

#define ACCURACY_REPORT_TOL 0.01 /* without --tolerance: what "differs" means */
#define ACCURACY_MAX_HALVINGS 4  /* --tolerance: runs down to dt/32           */

/* OUT at level 0; OUT with ".dtN" (N = 2^level) before a trailing ".h5". */
static void level_path(char *buf, size_t len, const char *out, int level) {
  if (level == 0) {
    snprintf(buf, len, "%s", out);
    return;
  }
  const size_t n = strlen(out);
  const int h5 = n > 3 && !strcmp(out + n - 3, ".h5");
  snprintf(buf, len, "%.*s.dt%ld.h5", (int)(h5 ? n - 3 : n), out, 1L << level);
}

/* "dt", "dt/2", "dt/4" */
static const char *level_name(char *buf, size_t len, int level) {
  if (level == 0) snprintf(buf, len, "dt");
  else snprintf(buf, len, "dt/%ld", 1L << level);
  return buf;
}

/* A value of an observable in a unit a reader takes in at a glance:
 * angles in degrees, small lengths in mm or um. */
static const char *quantity(char *buf, size_t len, double v, const char *units) {
  if (!strcmp(units, "rad")) snprintf(buf, len, "%.3g deg", v * 180 / M_PI);
  else if (!strcmp(units, "m") && fabs(v) < 1e-4 && v != 0) snprintf(buf, len, "%.3g um", v * 1e6);
  else if (!strcmp(units, "m") && fabs(v) < 0.1) snprintf(buf, len, "%.3g mm", v * 1e3);
  else if (units[0] && strcmp(units, "-")) snprintf(buf, len, "%.3g %s", v, units);
  else snprintf(buf, len, "%.3g", v);
  return buf;
}

/* The run of c at step dt into `out`, in a child process whose messages go
 * to `log`; the child's pid, or -1. */
static pid_t spawn_run(const swCli *c, double dt, const char *out, FILE *log) {
  fflush(stdout);
  fflush(stderr);
  const pid_t pid = fork();
  if (pid != 0) return pid;
  if (log) dup2(fileno(log), STDERR_FILENO);
  swCli k = *c;
  k.dt = dt;
  k.dt_given = 1;
  k.out = out;
  k.quiet = 1;
  k.golden = NULL;
  k.accuracy = 0;
  const int rc = sw_cli_simulate(&k);
  fflush(stderr);
  _exit(rc);
}

/* Waits for the child; its exit code, with its messages shown when it
 * failed (not for a failed expectation, which the parent's run reports). */
static int join_run(const swCli *c, pid_t pid, FILE *log, const char *what) {
  int status = 0, rc;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  rc = WIFEXITED(status) ? WEXITSTATUS(status) : SW_EINTERRUPT;
  if (rc != SW_OK && rc != SW_EEXPECT && log) {
    fprintf(stderr, "%s: accuracy: the run at %s ended with exit %d:\n", c->prog, what, rc);
    rewind(log);
    char line[1024];
    while (fgets(line, sizeof line, log)) fprintf(stderr, "    %s", line);
  }
  return rc;
}

/* The run at dt/2^level into its file; its exit code. */
static int run_level(const swCli *c, double dt, int level) {
  char path[1024], name[32];
  level_path(path, sizeof path, c->out, level);
  level_name(name, sizeof name, level);
  FILE *log = tmpfile();
  const pid_t pid = spawn_run(c, dt / (double)(1L << level), path, log);
  if (pid < 0) {
    if (log) fclose(log);
    fprintf(stderr, "%s: accuracy: cannot start the run at %s: %s\n", c->prog, name, strerror(errno));
    return SW_EIO;
  }
  const int rc = join_run(c, pid, log, name);
  if (log) fclose(log);
  return rc;
}

/* The comparison of levels `level` and level + 1, reported; how many
 * observables (the objective counted) differ by more than tol. */
static int compare_levels(const swCli *c, double dt, int level, double tol, int *rc) {
  const swProgram *p = c->p;
  char coarse[1024], fine[1024], err[512], a_name[32], b_name[32], t1[32], t2[32];
  level_path(coarse, sizeof coarse, c->out, level);
  level_path(fine, sizeof fine, c->out, level + 1);
  level_name(a_name, sizeof a_name, level);
  level_name(b_name, sizeof b_name, level + 1);
  swAccuracy *a = malloc(sizeof *a);
  if (!a) {
    *rc = SW_EMODEL;
    return -1;
  }
  if (sw_accuracy_compare(coarse, fine, tol, a, err, sizeof err) != SW_OK) {
    fprintf(stderr, "%s: accuracy: %s\n", c->prog, err);
    free(a);
    *rc = SW_EIO;
    return -1;
  }
  const double h = dt / (double)(1L << level);
  fprintf(stderr, "%s: accuracy: %s = %s (%s) against %s = %s (%s), over %ld frames:\n", c->prog,
          a_name, sw_cli_format_time(t1, sizeof t1, h), coarse, b_name,
          sw_cli_format_time(t2, sizeof t2, h / 2), fine, a->frames);
  if (a->frames_coarse != a->frames_fine)
    fprintf(stderr, "    (the run at %s wrote %ld frames, the run at %s %ld: the first %ld are "
            "compared)\n", a_name, a->frames_coarse, b_name, a->frames_fine, a->frames);
  int beyond = 0;
  const swAccuracyItem *worst = NULL;
  for (int i = 0; i < a->n; i++) {
    const swAccuracyItem *it = &a->item[i];
    const double rel = it->scale > 0 ? it->worst / it->scale : it->worst > 0 ? INFINITY : 0;
    char w[48], s[48], part[96] = "";
    if (!isnan(it->part_time)) {
      char t[32];
      snprintf(part, sizeof part, "; they part at t = %s", sw_cli_format_time(t, sizeof t, it->part_time));
      beyond++;
      if (!worst || rel > worst->worst / worst->scale) worst = it;
    }
    fprintf(stderr, "    %s: differs by up to %s, %.2g%% of its range (%s)%s\n", it->name,
            quantity(w, sizeof w, it->worst, it->units), 100 * rel,
            quantity(s, sizeof s, it->scale, it->units), part);
  }
  if (a->more) fprintf(stderr, "    (and %d more observables, not shown)\n", a->more);
  double obj_rel = 0;
  const int objective = a->has_objective && p->sense && !(isnan(a->objective[0]) && isnan(a->objective[1]));
  if (a->has_objective && p->sense && !objective)
    fprintf(stderr, "    objective %s: not reached at either step (the runs end before the times "
            "it reads)\n", p->objective_text);
  if (objective) {
    const double k = p->objective_scale > 0 ? p->objective_scale : 1;
    const char *u = p->objective_unit, *sp = u[0] ? " " : "";
    const double o1 = a->objective[0], o2 = a->objective[1];
    const double big = fmax(fabs(o1), fabs(o2));
    obj_rel = isnan(o1) || isnan(o2) ? NAN : big > 0 ? fabs(o1 - o2) / big : 0;
    char ratio[64] = "";
    const double small = fmin(fabs(o1), fabs(o2));
    if (o1 * o2 > 0 && big >= 2 * small) snprintf(ratio, sizeof ratio, ", a factor %.3g apart", big / small);
    if (isnan(obj_rel))
      fprintf(stderr, "    objective %s: not reached at %s (its run stopped before the times it reads)\n",
              p->objective_text, isnan(o1) ? a_name : b_name);
    else
      fprintf(stderr, "    objective %s: %.6g%s%s at %s, %.6g%s%s at %s: differs by %.2g%%%s\n",
              p->objective_text, o1 / k, sp, u, a_name, o2 / k, sp, u, b_name, 100 * obj_rel, ratio);
    if (!(obj_rel <= tol)) beyond++;
  }
  const int count = a->n + objective;
  if (beyond == 0) {
    if (count == 1)
      fprintf(stderr, "%s: accuracy: the one observable agrees within %.3g%% of its range between %s "
              "and %s\n", c->prog, 100 * tol, a_name, b_name);
    else
      fprintf(stderr, "%s: accuracy: all %d observables agree within %.3g%% of their ranges between "
              "%s and %s\n", c->prog, count, 100 * tol, a_name, b_name);
  } else {
    char what[160] = "";
    if (isnan(obj_rel))
      snprintf(what, sizeof what, " (the objective is not reached at one of them)");
    else if (!(obj_rel <= tol))
      snprintf(what, sizeof what, " (the objective by %.2g%%)", 100 * obj_rel);
    else if (worst)
      snprintf(what, sizeof what, " (%s by %.2g%% of its range)", worst->name, 100 * worst->worst / worst->scale);
    fprintf(stderr, "%s: accuracy: %d of %d observables differ by more than %.3g%% between %s and %s"
            "%s: the outcome is sensitive to the step\n", c->prog, beyond, count, 100 * tol,
            a_name, b_name, what);
  }
  free(a);
  return beyond;
}

int sw_cli_accuracy(const swCli *c, const swModel *m) {
  const double dt = m->dt;
  const double tol = c->tolerance > 0 ? c->tolerance : ACCURACY_REPORT_TOL;
  char half[1024];
  level_path(half, sizeof half, c->out, 1);
  if (!strcmp(half, c->out)) return sw_cli_complain(c, "--accuracy: --out %s names no file of its own", c->out);
  /* dt/2 on the second core while this process runs dt as usual */
  FILE *log = tmpfile();
  swCli k = *c;
  k.accuracy = 0;
  const pid_t pid = spawn_run(&k, dt / 2, half, log);
  if (pid < 0) {
    if (log) fclose(log);
    return sw_cli_complain(c, "--accuracy: cannot start the run at dt/2: %s", strerror(errno));
  }
  int rc = sw_cli_run(c, m, c->out);
  const int half_rc = join_run(c, pid, log, "dt/2");
  if (log) fclose(log);
  if (half_rc == SW_EINTERRUPT || rc == SW_EINTERRUPT) return SW_EINTERRUPT;
  if (rc == SW_EIO || half_rc == SW_EIO || rc == SW_EUSAGE || rc == SW_EMODEL) return rc ? rc : half_rc;
  int acc_rc = SW_OK;
  int beyond = compare_levels(c, dt, 0, tol, &acc_rc);
  if (beyond < 0) return acc_rc;
  if (!(c->tolerance > 0)) {
    if (beyond > 0)
      fprintf(stderr, "%s: accuracy: the default step is chosen for stability, not accuracy: give a "
              "smaller --dt, or --tolerance R to halve it until two runs agree\n", c->prog);
    return rc;
  }
  int level = 0;
  while (beyond > 0 && level < ACCURACY_MAX_HALVINGS) {
    level++;
    char path[1024], name[32], t[32];
    level_path(path, sizeof path, c->out, level + 1);
    fprintf(stderr, "%s: accuracy: halving: the run at %s = %s into %s\n", c->prog,
            level_name(name, sizeof name, level + 1),
            sw_cli_format_time(t, sizeof t, dt / (double)(1L << (level + 1))), path);
    const int lrc = run_level(c, dt, level + 1);
    if (lrc == SW_EINTERRUPT || lrc == SW_EIO) return lrc;
    beyond = compare_levels(c, dt, level, c->tolerance, &acc_rc);
    if (beyond < 0) return acc_rc;
  }
  char name[32], t[32], path[1024];
  level_path(path, sizeof path, c->out, level);
  if (beyond == 0) {
    fprintf(stderr, "%s: accuracy: the step %s = %s is accurate to %.3g%%: its run is %s (--dt %s "
            "gives it again)\n", c->prog, level_name(name, sizeof name, level),
            sw_cli_format_time(t, sizeof t, dt / (double)(1L << level)), 100 * c->tolerance, path, t);
    return rc;
  }
  fprintf(stderr, "%s: accuracy: no step down to %s = %s agrees with its half within %.3g%%: the "
          "outcome is sensitive to the step (a chaotic motion, or contact and limits that switch "
          "on at other instants); exit 5\n", c->prog, level_name(name, sizeof name, level + 1),
          sw_cli_format_time(t, sizeof t, dt / (double)(1L << (level + 1))), 100 * c->tolerance);
  return rc == SW_OK ? SW_EEXPECT : rc;
}
