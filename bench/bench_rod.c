/* bench_rod.c — the cost of the rod time step, in nanoseconds per element-step.
 *
 * Design.  One clamped rod lying along x sags under gravity (undamped, so it
 * keeps bending and the kernels never settle into a trivial state); it is
 * built only through the public API, as a generated simulator would build it,
 * with dt = 0.5 x sw_stable_dt() of its own model.  For each size n the step
 * is warmed up while the batch length is calibrated, then timed in NBATCH
 * batches of sw_steps() calls (the run loop's path), each at least
 * BATCH_SECONDS of wall time and at
 * least BATCH_MIN_ELEM_STEPS element-steps; we report the median (robust to a
 * batch disturbed by the machine) and the minimum (the best the code can do).
 * An element-step is one element advanced by one whole step, so the figure is
 * batch time / (steps x n) and a flat column across n means linear cost.
 * Cycles come from the hardware cycle counter through perf_event_open (user
 * space only) when the kernel allows it, else from the x86 time-stamp counter
 * (which ticks at the nominal clock, not the current one), else "n/a"; the
 * report says which.  The same Markdown document goes to stdout and to the
 * file named by argv[1]: its structure (sections, rows, columns) is fixed, so
 * two runs differ only in their figures, machine, date and commit.  The
 * modes --verlet, --tip and --cpu serve the scripts that run this program
 * (bench_isa.sh, bench_pyelastica.sh): rows of one size, the cantilever's
 * tip after a number of steps, what the CPU runs.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <linux/perf_event.h>
#include <sys/syscall.h>
#endif
#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#define HAVE_TSC 1
#endif
#include "sinew.h"

/* the compiler that built this file (and, through make, the runtime) */
#if defined(__clang__)
#define COMPILER __VERSION__
#elif defined(__GNUC__)
#define COMPILER "GCC " __VERSION__
#else
#define COMPILER "unknown compiler"
#endif

#ifndef SW_BENCH_CFLAGS
#define SW_BENCH_CFLAGS "unknown (built without -DSW_BENCH_CFLAGS)"
#endif

enum { NBATCH = 9 };                           /* timed batches per row (median of 9) */
static const double BATCH_SECONDS = 0.2;       /* minimum wall time of a batch, s     */
static const double BATCH_MIN_ELEM_STEPS = 1e6;
static const double WARMUP_SECONDS = 0.1;      /* calibration doubles as the warm-up  */
static const double SEGMENT_SECONDS = 1.0;     /* simulated time between resets, s    */
static const double TARGET_NS = 30.0;          /* ns per element-step, one thread     */
static const double GOAL_NS = 15.0;            /* and the goal beyond it (issue 10)   */
static const int TARGET_MIN_N = 100;           /* the target applies from this n on   */

static const int VERLET_N[] = {25, 50, 100, 200, 400, 800};
static const int PEFRL_N[] = {100, 400};
static const int ENERGY_N = 100;
static const int LAW_N[] = {100, 800};         /* the two laws, side by side      */
enum { LAW_ROUNDS = 3 };                       /* interleaved rounds per law and n */
static swLaw bench_law = SW_LAW_GAZZOLA;       /* the law of bench_model's rod    */
#define NVERLET ((int)(sizeof VERLET_N / sizeof VERLET_N[0]))
#define NPEFRL ((int)(sizeof PEFRL_N / sizeof PEFRL_N[0]))

static void die(const char *fmt, ...) __attribute__((format(printf, 1, 2), noreturn));
static void die(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "bench_rod: ");
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  exit(1);
}

/* ---- clocks ---- */

static double wall_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef enum { CYC_NONE = 0, CYC_PERF, CYC_TSC } CycleSource;

/* One reading of the cycle source; enabled/running are perf's multiplexing
 * times (a counter that shared the PMU is scaled by enabled / running). */
typedef struct {
  uint64_t count, enabled, running;
} CycleReading;

static CycleSource cycle_source = CYC_NONE;
static int perf_fd = -1;
static char perf_failure[160] = "";  /* why perf_event_open was not used */

static CycleReading cycles_read(void) {
  CycleReading c = {0, 1, 1};
#ifdef __linux__
  if (cycle_source == CYC_PERF) {
    uint64_t buf[3];
    if (read(perf_fd, buf, sizeof buf) == (ssize_t)sizeof buf) {
      c.count = buf[0];
      c.enabled = buf[1];
      c.running = buf[2];
    }
    return c;
  }
#endif
#ifdef HAVE_TSC
  if (cycle_source == CYC_TSC) c.count = (uint64_t)__rdtsc();
#endif
  return c;
}

/* Cycles between two readings, NAN when there is no source. */
static double cycles_between(CycleReading a, CycleReading b) {
  if (cycle_source == CYC_NONE) return NAN;
  double count = (double)(b.count - a.count);
  double running = (double)(b.running - a.running), enabled = (double)(b.enabled - a.enabled);
  if (cycle_source == CYC_PERF && running > 0 && running < enabled) count *= enabled / running;
  return count;
}

/* perf first: it counts the core's real cycles in user space only.  A counter
 * that opens but never advances (some virtual machines) counts as absent. */
static void cycles_init(void) {
#ifdef __linux__
  struct perf_event_attr attr;
  memset(&attr, 0, sizeof attr);
  attr.type = PERF_TYPE_HARDWARE;
  attr.size = sizeof attr;
  attr.config = PERF_COUNT_HW_CPU_CYCLES;
  attr.exclude_kernel = 1;
  attr.exclude_hv = 1;
  attr.read_format = PERF_FORMAT_TOTAL_TIME_ENABLED | PERF_FORMAT_TOTAL_TIME_RUNNING;
  perf_fd = (int)syscall(SYS_perf_event_open, &attr, 0, -1, -1, 0);
  if (perf_fd >= 0) {
    cycle_source = CYC_PERF;
    CycleReading a = cycles_read();
    volatile double sink = 0;
    for (int i = 0; i < 1000000; i++) sink = sink + 1.0;
    CycleReading b = cycles_read();
    if (b.count > a.count) return;
    snprintf(perf_failure, sizeof perf_failure, "the cycle counter opened but did not advance");
    close(perf_fd);
    perf_fd = -1;
    cycle_source = CYC_NONE;
  } else {
    snprintf(perf_failure, sizeof perf_failure, "perf_event_open failed: %s", strerror(errno));
  }
#else
  snprintf(perf_failure, sizeof perf_failure, "perf_event_open is Linux only");
#endif
#ifdef HAVE_TSC
  cycle_source = CYC_TSC;
#endif
}

static const char *cycles_header(void) {
  switch (cycle_source) {
  case CYC_PERF: return "cycles/element-step (perf)";
  case CYC_TSC: return "cycles/element-step (TSC)";
  default: return "cycles/element-step";
  }
}

/* ---- the model ---- */

static swModel *compile_or_die(const swSpec *s) {
  char err[512] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  if (!m) die("sw_compile failed: %s", err);
  return m;
}

/* How the start of bench_model's rod is held: sinew's clamp (the end node and
 * the end cross-section, with a clamp domain of half an element between that
 * cross-section and element 0: boundary.c), or as PyElastica's OneEndFixedBC
 * holds it (node 0 and element 0's frame, the velocity and the angular
 * velocity of both held at zero), for the comparison of `--tip`. */
typedef enum { END_CLAMP, END_PYELASTICA } EndKind;

/* A rod of n elements along x, held at its start by `end`, under gravity,
 * stepped with integ at dt, or at half its stable time step when dt <= 0. */
static swModel *bench_model_held(int n, swIntegrator integ, EndKind end, double dt) {
  swSpec *s = sw_spec_new();
  if (!s) die("out of memory");
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "bench";
  r.nelem = n;
  r.length = 1.0;
  r.radius_start = r.radius_end = 0.01;
  r.youngs = 1e6;
  r.density = 1000.0;
  r.direction[0] = 1; r.direction[1] = 0; r.direction[2] = 0;
  r.normal[0] = 0; r.normal[1] = 0; r.normal[2] = 1;
  r.law = bench_law;
  int rod = sw_spec_add_rod(s, &r);
  if (rod < 0) die("sw_spec_add_rod failed");
  const swBCKind held[2][2] = {{SW_BC_CLAMP, SW_BC_CLAMP}, {SW_BC_VELOCITY, SW_BC_OMEGA}};
  for (int k = 0; k < (end == END_CLAMP ? 1 : 2); k++) {
    swBCDesc bc;
    memset(&bc, 0, sizeof bc);   /* vec = 0: held at rest */
    bc.kind = held[end][k];
    bc.rod = rod;
    bc.end = 0;
    bc.signal = sw_signal_const(1);
    if (sw_spec_add_bc(s, &bc) < 0) die("sw_spec_add_bc failed");
  }
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  sw_spec_set_integrator(s, integ);
  if (dt <= 0) {
    swModel *estimate = compile_or_die(s);   /* only for its stable dt */
    dt = 0.5 * sw_stable_dt(estimate);
    sw_model_free(estimate);
  }
  sw_spec_set_dt(s, dt);
  swModel *m = compile_or_die(s);
  sw_spec_free(s);
  return m;
}

/* The benchmark's rod: clamped, at half its stable step. */
static swModel *bench_model(int n, swIntegrator integ) {
  return bench_model_held(n, integ, END_CLAMP, 0);
}

/* ---- timing ---- */

/* The work being timed: reps repetitions of one kernel. */
typedef void (*Kernel)(const swModel *m, swData *d, long reps);

/* sw_steps() is what the run loop calls between frames (Verlet half drifts
 * of consecutive steps fused), so that is the step we time. */
static void kernel_step(const swModel *m, swData *d, long reps) {
  if (sw_steps(m, d, reps) != SW_OK) die("sw_steps failed: %s", d->error);
}

static volatile double energy_sink; /* keeps the diagnostics' result alive */

static void kernel_energy(const swModel *m, swData *d, long reps) {
  double e[3];
  for (long k = 0; k < reps; k++) {
    sw_energy(m, d, e);
    energy_sink = e[0] + e[1];
  }
}

typedef struct {
  int n;
  double ns_median, ns_min;  /* per element per repetition     */
  double cyc_median;         /* per element per repetition, NAN when unknown */
  double reps_per_s;         /* from the median                */
  long batch_reps;
  double dt;                 /* s                              */
} Cost;

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int count) {
  qsort(v, (size_t)count, sizeof *v, cmp_double);
  return v[count / 2];
}

/* A kernel on one model and state.  Stepping runs are cut into segments of
 * `segment` repetitions, after each of which the state goes back to rest
 * outside the timer: an undamped rod left to whip for tens of seconds of
 * simulated time ends up exceeding the runtime's per-step rotation check,
 * and the first second of the fall is the motion worth timing anyway. */
typedef struct {
  Kernel kernel;
  const swModel *m;
  swData *d;
  int n;
  long segment;      /* repetitions between resets; 0 = never reset */
  long since_reset;
} Bench;

/* Wall time of reps repetitions (resets excluded); *cycles gets their cycles. */
static double timed_run(Bench *b, long reps, double *cycles) {
  double t = 0, cyc = 0;
  while (reps > 0) {
    if (b->segment && b->since_reset >= b->segment) {
      sw_reset(b->m, b->d);
      b->since_reset = 0;
    }
    long chunk = reps;
    if (b->segment && chunk > b->segment - b->since_reset) chunk = b->segment - b->since_reset;
    CycleReading c0 = cycles_read();
    double t0 = wall_seconds();
    b->kernel(b->m, b->d, chunk);
    double t1 = wall_seconds();
    CycleReading c1 = cycles_read();
    t += t1 - t0;
    cyc += cycles_between(c0, c1);
    reps -= chunk;
    b->since_reset += chunk;
  }
  *cycles = cyc;
  return t;
}

static Cost measure(Bench *b) {
  /* warm-up and calibration: double the repetitions until one run is long
   * enough to time, and keep going until the warm-up time is spent; the
   * fastest such run sets the batch length, so a disturbed warm-up cannot
   * shorten the batches below BATCH_SECONDS */
  long reps = 1;
  double warm = 0, per_rep = INFINITY, cyc;
  for (;;) {
    double t = timed_run(b, reps, &cyc);
    warm += t;
    if (t >= 0.25 * WARMUP_SECONDS) {
      per_rep = fmin(per_rep, t / (double)reps);
      if (warm >= WARMUP_SECONDS) break;
    } else {
      reps *= 2;
    }
  }
  long batch = (long)ceil(fmax(BATCH_SECONDS / per_rep, BATCH_MIN_ELEM_STEPS / b->n));

  double ns[NBATCH], cyc_per[NBATCH];
  for (int k = 0; k < NBATCH; k++) {
    double units = (double)batch * b->n;
    ns[k] = 1e9 * timed_run(b, batch, &cyc) / units;
    cyc_per[k] = cyc / units;
  }
  Cost c;
  c.n = b->n;
  c.ns_median = median(ns, NBATCH);  /* sorts ns */
  c.ns_min = ns[0];
  c.cyc_median = cycle_source == CYC_NONE ? NAN : median(cyc_per, NBATCH);
  c.reps_per_s = 1e9 / (c.ns_median * b->n);
  c.batch_reps = batch;
  c.dt = b->m->dt;
  return c;
}

static Cost bench_step(int n, swIntegrator integ) {
  swModel *m = bench_model(n, integ);
  swData *d = sw_data_new(m);
  if (!d) die("sw_data_new failed");
  sw_reset(m, d);
  Bench b = {kernel_step, m, d, n, (long)ceil(SEGMENT_SECONDS / m->dt), 0};
  Cost c = measure(&b);
  fprintf(stderr, "bench_rod: %s%s n = %d: %.2f ns/element-step\n",
          integ == SW_PEFRL ? "PEFRL" : "Verlet", bench_law == SW_LAW_VARIATIONAL ? ", variational law" : "",
          n, c.ns_median);
  sw_data_free(d);
  sw_model_free(m);
  return c;
}

/* sw_energy on a bent, moving rod (half a segment after release). */
static Cost bench_energy(int n) {
  swModel *m = bench_model(n, SW_VERLET);
  swData *d = sw_data_new(m);
  if (!d) die("sw_data_new failed");
  sw_reset(m, d);
  kernel_step(m, d, (long)ceil(0.5 * SEGMENT_SECONDS / m->dt));
  Bench b = {kernel_energy, m, d, n, 0, 0};
  Cost c = measure(&b);
  fprintf(stderr, "bench_rod: sw_energy n = %d: %.2f ns/element\n", n, c.ns_median);
  sw_data_free(d);
  sw_model_free(m);
  return c;
}

/* ---- where and how ---- */

typedef struct {
  char cpu[160];
  long ncpu;
  char date[64];
  char commit[64];
  int dirty;          /* runtime/, bench/ or the Makefile differ from the commit */
  char cycles_note[320];
} Machine;

/* First line of a command's output, or "" (newline stripped). */
static void command_line(const char *cmd, char *out, size_t len) {
  out[0] = 0;
  FILE *p = popen(cmd, "r");
  if (!p) return;
  if (!fgets(out, (int)len, p)) out[0] = 0;
  out[strcspn(out, "\r\n")] = 0;
  pclose(p);
}

static void machine_describe(Machine *mc) {
  snprintf(mc->cpu, sizeof mc->cpu, "unknown CPU");
  FILE *f = fopen("/proc/cpuinfo", "r");
  if (f) {
    char line[512];
    while (fgets(line, sizeof line, f)) {
      if (strncmp(line, "model name", 10) != 0) continue;
      const char *colon = strchr(line, ':');
      if (!colon) continue;
      colon++;
      while (*colon == ' ' || *colon == '\t') colon++;
      snprintf(mc->cpu, sizeof mc->cpu, "%s", colon);
      mc->cpu[strcspn(mc->cpu, "\r\n")] = 0;
      break;
    }
    fclose(f);
  }
  mc->ncpu = sysconf(_SC_NPROCESSORS_ONLN);
  time_t now = time(NULL);
  struct tm utc;
  if (gmtime_r(&now, &utc)) strftime(mc->date, sizeof mc->date, "%Y-%m-%d %H:%M UTC", &utc);
  else snprintf(mc->date, sizeof mc->date, "unknown");
  command_line("git rev-parse --short HEAD 2>/dev/null", mc->commit, sizeof mc->commit);
  if (!mc->commit[0]) snprintf(mc->commit, sizeof mc->commit, "unknown");
  char status[256];
  command_line("git status --porcelain --untracked-files=normal -- runtime bench Makefile 2>/dev/null",
               status, sizeof status);
  mc->dirty = status[0] != 0;
  switch (cycle_source) {
  case CYC_PERF:
    snprintf(mc->cycles_note, sizeof mc->cycles_note,
             "core clock cycles counted in user space by perf_event_open "
             "(PERF_COUNT_HW_CPU_CYCLES), median over the batches");
    break;
  case CYC_TSC:
    snprintf(mc->cycles_note, sizeof mc->cycles_note,
             "the x86 time-stamp counter (__rdtsc), which ticks at the CPU's nominal "
             "frequency, not its current clock, median over the batches (%s)", perf_failure);
    break;
  default:
    snprintf(mc->cycles_note, sizeof mc->cycles_note,
             "not available on this machine (%s; no time-stamp counter)", perf_failure);
  }
}

/* ---- the report ---- */

static void fmt_cycles(char *out, size_t len, double cyc) {
  if (isnan(cyc)) snprintf(out, len, "n/a");
  else snprintf(out, len, "%.1f", cyc);
}

static const char *verdict(const Cost *c) {
  if (c->n < TARGET_MIN_N) return "—";
  return c->ns_median <= TARGET_NS ? "yes" : "no";
}

static void step_table(FILE *f, const Cost *rows, int count, const Cost *verlet) {
  fprintf(f, "| n | ns/element-step (median) | min | %s | steps/s | dt (s) | %s | meets target |\n",
          cycles_header(), verlet ? "x Verlet" : "batch steps");
  fprintf(f, "|--:|--:|--:|--:|--:|--:|--:|:-:|\n");
  for (int i = 0; i < count; i++) {
    const Cost *c = rows + i;
    char cyc[32], extra[32];
    fmt_cycles(cyc, sizeof cyc, c->cyc_median);
    if (verlet) {
      double ratio = NAN;
      for (int j = 0; j < NVERLET; j++)
        if (verlet[j].n == c->n) ratio = c->ns_median / verlet[j].ns_median;
      snprintf(extra, sizeof extra, "%.2f", ratio);
    } else {
      snprintf(extra, sizeof extra, "%ld", c->batch_reps);
    }
    fprintf(f, "| %d | %.2f | %.2f | %s | %.0f | %.3g | %s | %s |\n", c->n, c->ns_median,
            c->ns_min, cyc, c->reps_per_s, c->dt, extra, verdict(c));
  }
}

static void target_line(FILE *f, const char *scheme, const Cost *c) {
  if (c->n < TARGET_MIN_N)
    fprintf(f, "- %s, n = %d: %.2f ns (below n = %d, not judged)\n", scheme, c->n, c->ns_median,
            TARGET_MIN_N);
  else
    fprintf(f, "- %s, n = %d: %.2f ns, %s\n", scheme, c->n, c->ns_median,
            c->ns_median <= TARGET_NS ? "meets the target" : "misses the target");
}

enum { NLAW = sizeof LAW_N / sizeof LAW_N[0] };

/* Median of the LAW_ROUNDS row medians of one law and size. */
static double rounds_median(const Cost *rounds) {
  double v[LAW_ROUNDS];
  for (int k = 0; k < LAW_ROUNDS; k++) v[k] = rounds[k].ns_median;
  return median(v, LAW_ROUNDS);
}

static void law_table(FILE *f, const Cost (*g18)[LAW_ROUNDS], const Cost (*var)[LAW_ROUNDS]) {
  fprintf(f, "\n## Constitutive law: Gazzola et al. 2018 and the variational one (Verlet)\n\n");
  fprintf(f, "The same rod with `variational = true` (docs/physics.md, \"The variational\n"
             "law\"): the exact gradient of the energy costs the beta term of each bending\n"
             "couple and a selection per slot. Each law measured %d times per n, the rounds\n"
             "interleaved (Gazzola, variational, Gazzola, ...); the median of the rows' medians.\n\n",
          LAW_ROUNDS);
  fprintf(f, "| n | Gazzola ns/element-step | variational ns/element-step | variational / Gazzola |\n");
  fprintf(f, "|--:|--:|--:|--:|\n");
  for (int i = 0; i < NLAW; i++) {
    const double a = rounds_median(g18[i]), b = rounds_median(var[i]);
    fprintf(f, "| %d | %.2f | %.2f | %.2f |\n", LAW_N[i], a, b, b / a);
  }
}

static void write_report(FILE *f, const Machine *mc, const Cost *verlet, const Cost *pefrl,
                         const Cost *energy, const Cost (*g18)[LAW_ROUNDS],
                         const Cost (*var)[LAW_ROUNDS]) {
  fprintf(f, "# sinew runtime benchmarks\n\n");
  fprintf(f, "Written by `make bench` (bench/bench_rod.c); run it again to refresh this file.\n"
             "Figures are wall time per element per step: a flat column across n means the\n"
             "step costs the same per element at every size.\n\n");

  fprintf(f, "## How it was measured\n\n");
  fprintf(f, "- Model: one rod of n elements, length 1 m, radius 0.01 m, E = 1 MPa, density\n"
             "  1000 kg/m^3, undamped, lying along x (normal z), clamped at its start and\n"
             "  bending under gravity (0, 0, -9.81) m/s^2; built with the public API and\n"
             "  stepped at dt = 0.5 x sw_stable_dt() of its own model.\n");
  fprintf(f, "- Timing: one thread; a warm-up of at least %.1f s that also calibrates the batch\n"
             "  length, then %d batches of sw_steps() calls (what the run loop calls between\n"
             "  frames: consecutive Verlet half drifts fused), each at least %.1f s and at least\n"
             "  %.0f element-steps; wall time from clock_gettime(CLOCK_MONOTONIC). Tables give\n"
             "  the median and the minimum over the batches. An element-step is one element\n"
             "  advanced by one whole step (all load evaluations of the scheme). After every\n"
             "  %.0f s of simulated time the rod is put back at rest outside the timer, so the\n"
             "  steps timed are those of the first second of its fall (left undamped for tens\n"
             "  of seconds, the soft rod whips until the runtime's per-step rotation check\n"
             "  stops it).\n",
          WARMUP_SECONDS, NBATCH, BATCH_SECONDS, BATCH_MIN_ELEM_STEPS, SEGMENT_SECONDS);
  fprintf(f, "- Cycles: %s.\n", mc->cycles_note);
  fprintf(f, "- Machine: %s, %ld logical CPUs online.\n", mc->cpu, mc->ncpu);
  fprintf(f, "- Compiler: %s; flags: `%s`.\n", COMPILER, SW_BENCH_CFLAGS);
  fprintf(f, "- Date: %s.\n", mc->date);
  fprintf(f, "- Code: git %s%s.\n\n", mc->commit,
          mc->dirty ? ", with uncommitted changes in runtime/, bench/ or the Makefile" : "");

  fprintf(f, "## Position Verlet (the default; one load evaluation per step)\n\n");
  step_table(f, verlet, NVERLET, NULL);
  fprintf(f, "\n## PEFRL (fourth order; four load evaluations per step)\n\n");
  fprintf(f, "Cost of a whole PEFRL step per element; \"x Verlet\" is the ratio to the\n"
             "Verlet row of the same n.\n\n");
  step_table(f, pefrl, NPEFRL, verlet);
  law_table(f, g18, var);

  fprintf(f, "\n## Diagnostics: sw_energy at n = %d\n\n", energy->n);
  fprintf(f, "sw_energy() recomputes the strains and sums the energies; the run loop calls\n"
             "it once per frame written, so a frame costs this much on top of the steps.\n\n");
  double verlet_step_ns = NAN;
  for (int j = 0; j < NVERLET; j++)
    if (verlet[j].n == energy->n) verlet_step_ns = verlet[j].ns_median;
  char cyc[32];
  fmt_cycles(cyc, sizeof cyc, energy->cyc_median);
  const char *cyc_head = cycle_source == CYC_PERF ? "cycles/element (perf)"
                         : cycle_source == CYC_TSC ? "cycles/element (TSC)" : "cycles/element";
  fprintf(f, "| n | ns/element per call (median) | min | %s | ns per call | Verlet steps per call |\n",
          cyc_head);
  fprintf(f, "|--:|--:|--:|--:|--:|--:|\n");
  fprintf(f, "| %d | %.2f | %.2f | %s | %.0f | %.2f |\n\n", energy->n, energy->ns_median,
          energy->ns_min, cyc, energy->ns_median * energy->n,
          energy->ns_median / verlet_step_ns);

  fprintf(f, "## Target\n\n");
  fprintf(f, "Target: at most %.0f ns per element-step for n >= %d, one thread (median of the\n"
             "batches, whole step); the goal is %.0f ns.\n\n", TARGET_NS, TARGET_MIN_N, GOAL_NS);
  int judged = 0, met = 0;
  for (int i = 0; i < NVERLET; i++) {
    target_line(f, "Verlet", verlet + i);
    if (verlet[i].n >= TARGET_MIN_N) { judged++; met += verlet[i].ns_median <= TARGET_NS; }
  }
  for (int i = 0; i < NPEFRL; i++) {
    target_line(f, "PEFRL", pefrl + i);
    if (pefrl[i].n >= TARGET_MIN_N) { judged++; met += pefrl[i].ns_median <= TARGET_NS; }
  }
  fprintf(f, "\n%d of %d judged rows meet the target.\n", met, judged);
}

/* `bench_rod --verlet N...`: the Verlet rows of the sizes given and nothing
 * else, for bench/bench_isa.sh, which runs two builds of this program
 * (x86-64-v3 and -v4) row by row, interleaved: a first line "# cycles: "
 * and what they are, then one line a size, "n ns_median ns_min
 * cycles_median" (cycles "nan" when there is no source). */
static int verlet_rows(int count, char **sizes) {
  cycles_init();
  Machine mc;
  machine_describe(&mc);
  printf("# cycles: %s\n", mc.cycles_note);
  for (int i = 0; i < count; i++) {
    char *end;
    const long n = strtol(sizes[i], &end, 10);
    if (*end || n < 2 || n > 1000000) die("--verlet: not a number of elements: %s", sizes[i]);
    const Cost c = bench_step((int)n, SW_VERLET);
    printf("%d %.4f %.4f %.2f\n", c.n, c.ns_median, c.ns_min, c.cyc_median);
    fflush(stdout);
  }
  if (perf_fd >= 0) close(perf_fd);
  return 0;
}

/* `bench_rod --tip N STEPS [DT]`: where the cantilever's free end is after
 * STEPS Verlet steps from rest, for bench/bench_pyelastica.sh, which runs the
 * same rod in PyElastica and compares.  Lines "dt DT" (bench_rod's step for
 * n = N unless DT is given; both ends use it) and "clamp N STEPS x y z" (sinew's clamp, the rod timed
 * above) and "pyelastica N STEPS x y z" (the start held as PyElastica's
 * OneEndFixedBC holds it), positions in m to 17 digits. */
static int tip_rows(const char *size, const char *count, const char *step) {
  char *end1, *end2, *end3 = "";
  const long n = strtol(size, &end1, 10), steps = strtol(count, &end2, 10);
  double dt = step ? strtod(step, &end3) : 0;
  if (*end1 || n < 2 || n > 1000000) die("--tip: not a number of elements: %s", size);
  if (*end2 || steps < 0) die("--tip: not a number of steps: %s", count);
  if (*end3 || (step && !(dt > 0))) die("--tip: not a time step: %s", step);
  for (int k = 0; k < 2; k++) {
    swModel *m = bench_model_held((int)n, SW_VERLET, k ? END_PYELASTICA : END_CLAMP, dt);
    dt = m->dt;
    if (!k) printf("dt %.17g\n", dt);
    swData *d = sw_data_new(m);
    if (!d) die("sw_data_new failed");
    sw_reset(m, d);
    kernel_step(m, d, steps);
    double x[3];
    sw_get3(m, d->x, m->node_adr[0] + (int)n, x);
    printf("%s %ld %ld %.17g %.17g %.17g\n", k ? "pyelastica" : "clamp", n, steps, x[0], x[1], x[2]);
    sw_data_free(d);
    sw_model_free(m);
  }
  return 0;
}

/* `bench_rod --cpu`: what the CPU runs, for bench/bench_isa.sh, which
 * builds and runs the x86-64-v4 benchmark only where it can: lines "model
 * NAME", "avx2 yes|no", "avx512f yes|no", "x86-64-v3 yes|no" and
 * "x86-64-v4 yes|no" (the levels as GCC's __builtin_cpu_supports knows
 * them: v3 is AVX2, FMA, BMI1/2, F16C, LZCNT and MOVBE, v4 adds AVX-512
 * F, BW, CD, DQ and VL; all "no" off x86). */
static int cpu_report(void) {
  Machine mc;
  machine_describe(&mc);
  int avx2 = 0, avx512f = 0, v3 = 0, v4 = 0;
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  __builtin_cpu_init();
  avx2 = __builtin_cpu_supports("avx2") != 0;
  avx512f = __builtin_cpu_supports("avx512f") != 0;
  v3 = __builtin_cpu_supports("x86-64-v3") != 0;
  v4 = __builtin_cpu_supports("x86-64-v4") != 0;
#endif
  printf("model %s\navx2 %s\navx512f %s\nx86-64-v3 %s\nx86-64-v4 %s\n", mc.cpu, avx2 ? "yes" : "no",
         avx512f ? "yes" : "no", v3 ? "yes" : "no", v4 ? "yes" : "no");
  return 0;
}

int main(int argc, char **argv) {
  if (argc > 1 && strcmp(argv[1], "--verlet") == 0) return verlet_rows(argc - 2, argv + 2);
  if (argc == 2 && strcmp(argv[1], "--cpu") == 0) return cpu_report();
  if ((argc == 4 || argc == 5) && strcmp(argv[1], "--tip") == 0)
    return tip_rows(argv[2], argv[3], argc == 5 ? argv[4] : NULL);
  if (argc > 2) {
    fprintf(stderr, "usage: %s [report.md]\n       %s --verlet N...\n       %s --tip N STEPS [DT]\n       %s --cpu\n",
            argv[0], argv[0], argv[0], argv[0]);
    return SW_EUSAGE;
  }
  cycles_init();
  Cost verlet[NVERLET], pefrl[NPEFRL];
  for (int i = 0; i < NVERLET; i++) verlet[i] = bench_step(VERLET_N[i], SW_VERLET);
  for (int i = 0; i < NPEFRL; i++) pefrl[i] = bench_step(PEFRL_N[i], SW_PEFRL);
  Cost energy = bench_energy(ENERGY_N);
  Cost g18[NLAW][LAW_ROUNDS], var[NLAW][LAW_ROUNDS];
  for (int i = 0; i < NLAW; i++)
    for (int k = 0; k < LAW_ROUNDS; k++) {
      bench_law = SW_LAW_GAZZOLA;
      g18[i][k] = bench_step(LAW_N[i], SW_VERLET);
      bench_law = SW_LAW_VARIATIONAL;
      var[i][k] = bench_step(LAW_N[i], SW_VERLET);
    }
  bench_law = SW_LAW_GAZZOLA;

  Machine mc;
  machine_describe(&mc);
  write_report(stdout, &mc, verlet, pefrl, &energy, (const Cost (*)[LAW_ROUNDS])g18,
               (const Cost (*)[LAW_ROUNDS])var);
  if (argc == 2) {
    FILE *f = fopen(argv[1], "w");
    if (!f) die("cannot write the report: %s", argv[1]);
    write_report(f, &mc, verlet, pefrl, &energy, (const Cost (*)[LAW_ROUNDS])g18,
                 (const Cost (*)[LAW_ROUNDS])var);
    if (fclose(f) != 0) die("cannot write the report: %s", argv[1]);
    fprintf(stderr, "bench_rod: wrote %s\n", argv[1]);
  }
  if (perf_fd >= 0) close(perf_fd);
  return 0;
}
