/* run.c — the run loop: steps, output frames, Ctrl-C, progress; and the
 * parser of time arguments ("50ns", "0.5 s"; a time quantity of units.c).
 *
 * Design.  Everything is counted in steps, never by comparing accumulated
 * times: the run is nsteps = llround(duration / dt) calls of sw_step(), and a
 * frame is written at step 0, at every multiple of llround(every / dt) and at
 * the last step, so the frame times are exactly those a user predicts.
 * Ctrl-C only sets a flag (the one thing a handler may safely do); the loop
 * looks at it between steps, writes a last frame of the state it stopped in and
 * returns SW_EINTERRUPT, leaving the caller to close the file with a status
 * that says so.  An unstable step writes nothing more: the frames already on
 * disk are valid and a frame of NaNs would help nobody.  Progress is shown on
 * one line rewritten with '\r', only for runs longer than a second and at most
 * twice a second; the wall clock is read on a stride of steps re-estimated
 * from the measured step rate, so a tiny rod does not pay a clock read per
 * step and a huge one is not left silent.  A model's expectations (expect.c)
 * are sampled at the steps they name: the chunks end there.  A chunk ends
 * held (sw_steps_held, integrate.c), its last half drift fused with the
 * next chunk's first as within a chunk, and the state is made whole only
 * while it is read: so frames, samples and the 256-step cut leave the
 * trajectory's bits alone, and `--every`, an `expect` line or an objective
 * change nothing but what is read.  Frames are scheduled on the step count
 * since t = 0, and after each frame of the schedule the output takes a
 * checkpoint of the held state (restart.c), so a run continued from its
 * file (`resumed`) fuses its steps as one that never stopped.  A silent
 * run (swRunOptions.silent: sw_evaluate's, one of many of a study) prints
 * nothing at all; an instability's reason stays in d->error. */
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sinew.h"
#include "engine/internal.h"

#define PROGRESS_AFTER 1.0      /* s of wall time before the first line   */
#define PROGRESS_EVERY 0.5      /* s of wall time between lines           */
#define CLOCK_PROBE 0.05        /* s of wall time between clock reads     */

static volatile sig_atomic_t interrupted;

/* A message of the run to log, or nowhere when the run is silent (NULL). */
static void say(FILE *log, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void say(FILE *log, const char *fmt, ...) {
  if (!log) return;
  va_list ap;
  va_start(ap, fmt);
  vfprintf(log, fmt, ap);
  va_end(ap);
}

static void on_sigint(int sig) {
  (void)sig;
  interrupted = 1;
}

double sw_wall_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* "42 s", "3 min 20 s", "2 h 05 min" */
static void format_wall(char *buf, size_t len, double seconds) {
  if (!isfinite(seconds) || seconds < 0) snprintf(buf, len, "?");
  else if (seconds < 60) snprintf(buf, len, "%.0f s", seconds);
  else if (seconds < 3600)
    snprintf(buf, len, "%d min %02d s", (int)(seconds / 60), (int)fmod(seconds, 60));
  else snprintf(buf, len, "%d h %02d min", (int)(seconds / 3600), (int)fmod(seconds / 60, 60));
}

typedef struct {
  FILE *log;
  int quiet;
  long nsteps;
  double duration;
  double start;            /* wall clock at the first step            */
  double last_line;        /* wall clock of the last progress line    */
  long next_probe;         /* step at which to read the clock next    */
  int shown;               /* a progress line is on the terminal      */
} swProgress;

static void progress_update(swProgress *p, const swData *d, long k) {
  if (p->quiet || k < p->next_probe) return;
  double now = sw_wall_seconds(), elapsed = now - p->start;
  double rate = elapsed > 0 ? (double)k / elapsed : 0;
  long stride = (long)(rate * CLOCK_PROBE);
  p->next_probe = k + (stride > 1 ? stride : 1);
  if (elapsed < PROGRESS_AFTER || now - p->last_line < PROGRESS_EVERY) return;
  char left[32];
  format_wall(left, sizeof left, rate > 0 ? (double)(p->nsteps - k) / rate : -1);
  fprintf(p->log, "\rsinew: t = %.6g s of %.6g s (%3.0f%%), %.3g steps/s, %s left   ",
          d->time, p->duration, p->nsteps ? 100.0 * (double)k / (double)p->nsteps : 100.0,
          rate, left);
  fflush(p->log);
  p->last_line = now;
  p->shown = 1;
}

/* End the progress line before any other message or at the end of the run. */
static void progress_end(swProgress *p) {
  if (p->shown) say(p->log, "\n");
  p->shown = 0;
}

static int write_frame(const swModel *m, swData *d, swOutput *out, swProgress *p) {
  if (!out) return SW_OK; /* a study's evaluation: no file, no summary to sample for */
  sw_rigidity_sample(m, d); /* the rods' strain peaks, for the run's summary (rigidity.c) */
  if (sw_output_frame(out, m, d) == SW_OK) return SW_OK;
  progress_end(p);
  say(p->log, "sinew: %s\n", sw_output_error());
  return SW_EIO;
}

/* After a frame of the schedule: the state a continued run starts from
 * (restart.c); the run's last frame always. */
static int checkpoint(const swModel *m, const swData *d, swOutput *out, const swRunOptions *ro,
                      swProgress *p, int last) {
  if (!out || sw_output_checkpoint(out, m, d, ro->expect, last) == SW_OK) return SW_OK;
  progress_end(p);
  say(p->log, "sinew: %s\n", sw_output_error());
  return SW_EIO;
}

int sw_step_count(double duration, double dt, long *nsteps, char *err, size_t errlen) {
  *nsteps = 0;
  if (!(dt > 0) || !isfinite(dt)) {
    snprintf(err, errlen, "dt = %g s: the time step must be positive and finite", dt);
    return SW_EUSAGE;
  }
  if (!(duration >= 0) || !isfinite(duration)) {
    snprintf(err, errlen, "duration = %g s: must be zero or positive, and finite", duration);
    return SW_EUSAGE;
  }
  const double steps = round(duration / dt);
  if (duration > 0 && !(steps >= 1)) {
    snprintf(err, errlen, "dt = %g s is longer than twice the duration %g s: not one step "
             "would be taken", dt, duration);
    return SW_EUSAGE;
  }
  if (!(steps <= SW_MAX_STEPS)) {
    snprintf(err, errlen, "a duration of %g s at dt = %g s is %.3g steps, more than the %.0e "
             "a run may take", duration, dt, duration / dt, SW_MAX_STEPS);
    return SW_EUSAGE;
  }
  *nsteps = (long)steps;
  return SW_OK;
}

int sw_run(const swModel *m, swData *d, swOutput *out, const swRunOptions *ro) {
  FILE *log = ro && ro->silent ? NULL : ro && ro->log ? ro->log : stderr;
  if (!m || !d || !ro) {
    say(log, "sinew: sw_run: no model, state or options\n");
    return SW_EUSAGE;
  }
  if (!(m->dt > 0) || !isfinite(m->dt) || !(ro->duration >= 0) || !isfinite(ro->duration) ||
      !(ro->every >= 0) || !isfinite(ro->every)) {
    say(log, "sinew: invalid run: dt = %g s, duration = %g s, every = %g s\n", m->dt,
            ro->duration, ro->every);
    return SW_EUSAGE;
  }
  /* Counted from the present state, so a resumed run ends at `duration`
   * (a held state's positions are half a step behind its count). */
  double remaining = ro->duration - sw_time(m, d);
  long nsteps = 0;
  char why[256];
  if (remaining > 0 && sw_step_count(remaining, m->dt, &nsteps, why, sizeof why) != SW_OK) {
    say(log, "sinew: %s\n", why);
    return SW_EUSAGE;
  }
  /* Frames are scheduled on the step count since t = 0 (d->step), so a run
   * continued from its file keeps the schedule; a frame interval longer
   * than the run: the first and last frames only. */
  const long last_step = d->step + nsteps;
  double every_steps = ro->every > 0 ? round(ro->every / m->dt) : 1;
  long every = every_steps > (double)last_step ? last_step + 1 : (long)every_steps;
  if (every < 1) every = 1;

  swProgress p = {log, ro->quiet || !log, nsteps, ro->duration, 0, 0, 1, 0};
  struct sigaction action, previous;
  memset(&action, 0, sizeof action);
  action.sa_handler = on_sigint;
  sigemptyset(&action.sa_mask);
  interrupted = 0;
  int handler_installed = sigaction(SIGINT, &action, &previous) == 0;

  int rc = SW_OK;
  if (!ro->resumed) {   /* a continued run's first frame is in its file */
    rc = write_frame(m, d, out, &p);
    if (ro->expect) sw_expect_sample(m, d, ro->expect);
    if (rc == SW_OK) rc = checkpoint(m, d, out, ro, &p, nsteps == 0);
  }
  long k = 0, last_frame = 0;
  const int expect_held = sw_expect_held_ok(m);
  p.start = p.last_line = sw_wall_seconds();
  while (rc == SW_OK && k < nsteps && !interrupted) {
    /* as many fused steps as fit before the next frame (at most 256, so
     * that SIGINT and the progress line stay responsive) and before the
     * next step an expectation samples (expect.c) */
    long chunk = every - d->step % every;
    if (chunk > nsteps - k) chunk = nsteps - k;
    if (chunk > 256) chunk = 256;
    if (ro->expect) {
      long due = sw_expect_next(m, d->step);
      if (due - d->step < chunk) chunk = due - d->step;
    }
    /* held steps (integrate.c): the chunks' ends leave the bits alone */
    int step_rc = sw_steps_held(m, d, chunk);
    k += chunk;
    const int frame = d->step % every == 0 || k == nsteps;
    /* the expectations read at the held step when they can (probe.c), so
     * that a step without a frame is not made whole for them */
    const int held_sample = ro->expect && !frame && d->held && expect_held;
    if (step_rc == SW_OK && (frame || (ro->expect && !held_sample))) step_rc = sw_whole_begin(m, d);
    if (step_rc == SW_OK && ro->expect) {
      if (held_sample) sw_expect_sample_held(m, d, ro->expect);
      else sw_expect_sample(m, d, ro->expect);
    }
    if (step_rc != SW_OK) {
      progress_end(&p);
      say(log, "sinew: %s\n", d->error[0] ? d->error : "the step failed");
      rc = step_rc;
      break;
    }
    if (frame) rc = write_frame(m, d, out, &p);
    sw_whole_end(m, d);
    if (frame) { /* the held state: a continued run fuses as this one does */
      if (rc == SW_OK) rc = checkpoint(m, d, out, ro, &p, k == nsteps);
      last_frame = k;
    }
    progress_update(&p, d, k);
  }
  /* the run ends at a whole step (its checkpoint keeps the held one) */
  int settle_rc = sw_settle(m, d);
  if (rc == SW_OK && settle_rc != SW_OK) {
    progress_end(&p);
    say(log, "sinew: %s\n", d->error[0] ? d->error : "the step failed");
    rc = settle_rc;
  }
  if (rc == SW_OK && interrupted && k < nsteps) {
    if (last_frame != k) rc = write_frame(m, d, out, &p);
    progress_end(&p);
    if (out)
      say(log, "sinew: interrupted at t = %.9g s; %ld frames written to output\n", d->time,
              sw_output_frames(out));
    else
      say(log, "sinew: interrupted at t = %.9g s; no output\n", d->time);
    if (rc == SW_OK) rc = SW_EINTERRUPT;
  }
  progress_end(&p);
  if (d->friction_full) /* contact.c, obstacle.c: never silently */
    say(log, "sinew: warning: %ld times a touching pair found the friction anchors' table full "
             "(4 rows per element in contact) and was frictionless for that evaluation; the "
             "friction of this run is short there\n", d->friction_full);
  if (log) fflush(log);
  if (handler_installed) sigaction(SIGINT, &previous, NULL);
  return rc;
}

/* ---- time arguments ---- */

/* A quantity (units.c) of time, or a bare number of seconds; not negative. */
int sw_parse_time(const char *text, double *seconds) {
  double value;
  signed char dim[SW_NDIM];
  static const signed char time_dim[SW_NDIM] = {0, 0, 1, 0}, none[SW_NDIM] = {0, 0, 0, 0};
  if (!text || !seconds || sw_parse_quantity(text, &value, dim, NULL, 0)) return 1;
  if (memcmp(dim, time_dim, SW_NDIM) && memcmp(dim, none, SW_NDIM)) return 1;
  if (!(value >= 0)) return 1;
  *seconds = value + 0.0; /* no -0 */
  return 0;
}
