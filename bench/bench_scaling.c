/* bench_scaling.c — how the step's cost grows with the size of the scene, on
 * one thread and on two (issue 10).
 *
 * Design.  Two families of scenes, from 10^2 to 10^6 elements in all: one
 * long rod, and many short rods of 100 elements each (1 to 10^4 rods; the
 * row of 10^4 elements is the 100-rod scene).  Every rod is a clamped
 * cantilever sagging under gravity, undamped, at half its stable step, built
 * through the public API as a generated simulator builds its scene.  Each
 * size is run on 1 and on 2 threads (sw_set_threads), the two interleaved
 * batch by batch, each batch at least BATCH_SECONDS of sw_steps() after a
 * warm-up that calibrates the batch; the figure is the median of NBATCH
 * batches, in nanoseconds per element-step (batch time / (steps x elements)),
 * and the ratio of the two medians.  Memory per element is what the model and
 * the state take from the allocator (glibc's mallinfo2, before and after
 * sw_compile and sw_data_new), divided by the elements.  The Markdown section
 * goes to stdout and replaces its own section of the report named by argv[1].
 */
#include <malloc.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sinew.h"
#include "bench_util.h"

enum { NBATCH = 5, NSIZE = 5, SHORT = 100 };
static const double BATCH_SECONDS = 0.15;
static const double SEGMENT_SECONDS = 0.2;  /* simulated time from rest, s */
static const char SECTION[] = "## Scaling: elements, rods and threads (issue 10)";
static const long SIZES[NSIZE] = {100, 1000, 10000, 100000, 1000000};

typedef struct {
  long elements;
  int nrod;
  double ns[2];    /* median ns per element-step on 1 and 2 threads */
  double bytes;    /* model + state per element                     */
} Row;

static void die(const char *what) {
  fprintf(stderr, "bench_scaling: %s\n", what);
  exit(1);
}

static size_t heap_bytes(void) {
  struct mallinfo2 mi = mallinfo2();
  return mi.uordblks + mi.hblkhd;
}

/* nrod clamped rods of n elements, side by side 5 cm apart, 1 m long and
 * 1 cm thick, E = 1 MPa, rho = 1000 kg/m^3 (bench_rod.c's cantilever). */
static swSpec *scene(int nrod, long n) {
  swSpec *s = sw_spec_new();
  if (!s) die("out of memory");
  char name[32];
  for (int r = 0; r < nrod; r++) {
    swRodDesc rd;
    sw_rod_desc_init(&rd);
    snprintf(name, sizeof name, "rod%d", r);
    rd.name = name;
    rd.nelem = (int)n;
    rd.length = 1.0;
    rd.radius_start = rd.radius_end = 0.01;
    rd.density = 1000;
    rd.youngs = 1e6;
    rd.start[0] = 0, rd.start[1] = 0.05 * r, rd.start[2] = 0;
    rd.direction[0] = 1, rd.direction[1] = 0, rd.direction[2] = 0;
    rd.normal[0] = 0, rd.normal[1] = 0, rd.normal[2] = 1;
    if (sw_spec_add_rod(s, &rd) < 0) die("cannot add a rod");
    swBCDesc bc = {.kind = SW_BC_CLAMP, .rod = r, .end = 0, .signal = sw_signal_const(1)};
    if (sw_spec_add_bc(s, &bc) < 0) die("cannot add a clamp");
  }
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  return s;
}

/* Wall seconds of `segments` runs of `steps` steps, each from rest (the
 * resets not timed); -1 if a run became unstable. */
static double batch(const swModel *m, swData *d, long steps, long segments) {
  double total = 0;
  for (long k = 0; k < segments; k++) {
    sw_reset(m, d);
    const double t0 = wall_seconds();
    if (sw_steps(m, d, steps) != SW_OK) return -1;
    total += wall_seconds() - t0;
  }
  return total;
}

static void measure(Row *row) {
  const long n = row->nrod == 1 ? row->elements : SHORT;
  swSpec *s = scene(row->nrod, n);
  char err[256];
  swModel *m0 = sw_compile(s, err, sizeof err);
  if (!m0) die(err);
  sw_spec_set_dt(s, 0.5 * sw_stable_dt(m0));
  sw_model_free(m0);
  const size_t before = heap_bytes();
  swModel *m = sw_compile(s, err, sizeof err);
  if (!m) die(err);
  swData *d[2] = {sw_data_new(m), NULL};
  row->bytes = (double)(heap_bytes() - before) / (double)row->elements; /* model + one state */
  d[1] = sw_data_new(m);
  if (!d[0] || !d[1]) die("out of memory");
  sw_set_threads(d[1], 2);
    /* warm-up and calibration on one thread.  A batch is `segments` runs of
   * `steps` steps, each from rest and at most SEGMENT_SECONDS of simulated
   * time, so the undamped cantilevers never swing long enough to whip; only
   * the steps are timed. */
  const long seg_max = (long)(SEGMENT_SECONDS / m->dt) + 1;
  long steps = 1, segments = 1;
  for (;;) {
    const double t = batch(m, d[0], steps, segments);
    if (t < 0) die("the cantilever became unstable");
    if (t >= BATCH_SECONDS) break;
    const double grow = t > 0.01 ? 1.2 * BATCH_SECONDS / t : 4.0;
    if ((double)steps * grow <= (double)seg_max) steps = (long)((double)steps * grow) + 1;
    else segments = (long)((double)segments * grow) + 1, steps = steps < seg_max ? seg_max : steps;
  }
  if (batch(m, d[1], steps, segments) < 0) die("the cantilever became unstable");
  double t[2][NBATCH];
  for (int b = 0; b < NBATCH; b++)
    for (int k = 0; k < 2; k++) {
      const double s_ = batch(m, d[k], steps, segments);
      if (s_ < 0) die("the cantilever became unstable");
      t[k][b] = s_ / ((double)steps * (double)segments * (double)row->elements) * 1e9;
    }
  for (int k = 0; k < 2; k++) row->ns[k] = median(t[k], NBATCH);
  sw_data_free(d[0]);
  sw_data_free(d[1]);
  sw_model_free(m);
  sw_spec_free(s);
}

static void write_section(FILE *f, const Row *rows) {
  fprintf(f, "%s\n\n", SECTION);
  fprintf(f, "Written by bench/bench_scaling.c, which `make bench` runs (machine, compiler\n"
             "and flags as at the top of this report). Clamped cantilevers under gravity at half\n"
             "their stable step: one long rod, or rods of %d elements side by side; median of\n"
             "%d batches of at least %.2f s (runs of at most %.1f s of simulated time, each\n"
             "from rest), one and two threads interleaved batch by batch.\n"
             "The 10000 elements in 100 rods are the 100-rod scene. Memory: model and one\n"
             "state, per element. One thread runs these scenes' steps as the fused sweep\n"
             "(above 512 slots), two threads the phased step; both give the same bits.\n\n",
          SHORT, NBATCH, BATCH_SECONDS, SEGMENT_SECONDS);
  fprintf(f, "| elements | rods | ns/element-step, 1 thread | 2 threads | 2 threads vs 1 | bytes/element |\n");
  fprintf(f, "|--:|--:|--:|--:|--:|--:|\n");
  for (int i = 0; i < 2 * NSIZE; i++)
    if (rows[i].elements > 0)
      fprintf(f, "| %ld | %d | %.1f | %.1f | %.2fx | %.0f |\n", rows[i].elements, rows[i].nrod,
            rows[i].ns[0], rows[i].ns[1], rows[i].ns[0] / rows[i].ns[1], rows[i].bytes);
}

int main(int argc, char **argv) {
  if (argc > 2) {
    fprintf(stderr, "usage: %s [report.md]\n", argv[0]);
    return SW_EUSAGE;
  }
  Row rows[2 * NSIZE];
  for (int i = 0; i < NSIZE; i++) {
    rows[2 * i] = (Row){SIZES[i], 1, {0, 0}, 0};
    rows[2 * i + 1] = (Row){SIZES[i], (int)(SIZES[i] / SHORT), {0, 0}, 0};
  }
  rows[1].elements = 0; /* 100 elements in rods of 100: the one-rod row again */
  for (int i = 0; i < 2 * NSIZE; i++) {
    if (!rows[i].elements) continue;
    measure(&rows[i]);
    fprintf(stderr, "bench_scaling: %ld elements in %d rod(s): %.1f ns (1 thread), %.1f ns (2), %.0f B/element\n",
            rows[i].elements, rows[i].nrod, rows[i].ns[0], rows[i].ns[1], rows[i].bytes);
  }
  char *text = NULL;
  size_t size = 0;
  FILE *f = open_memstream(&text, &size);
  if (!f) die("out of memory");
  write_section(f, rows);
  fclose(f);
  fputs(text, stdout);
  if (argc == 2 && bench_replace_section(argv[1], SECTION, text) != 0) die("cannot write the report");
  free(text);
  return 0;
}
