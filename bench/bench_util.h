/* bench_util.h — the clock, the median and the report splicing shared by the
 * benchmarks (bench_rigid.c, bench_contact.c, bench_obstacle.c, bench_pile.c,
 * bench_scaling.c), the format of a time, and what the contact benchmarks
 * all do to a scene: compile it at a share of its stable step, and time
 * whole steps in batches. */
#ifndef SW_BENCH_UTIL_H
#define SW_BENCH_UTIL_H
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "sinew.h"

static inline double wall_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The CPU time of the calling thread, s: on a machine others share, what
 * the step cost without the time it waited for a core. */
static inline double thread_cpu_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static inline int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Median of v[0..n) (sorts v); the mean of the middle two for even n. */
static inline double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Replaces the section of the Markdown file at path that starts with the
 * line `heading` (up to the next "## " heading, or the end) by `text`, or
 * appends it; so running a benchmark twice leaves one section.  0 on
 * success, -1 when the file cannot be written. */
static inline int bench_replace_section(const char *path, const char *heading, const char *text) {
  char *old = NULL;
  size_t len = 0, head = 0, tail = 0;
  FILE *f = fopen(path, "r");
  if (f) {
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    old = calloc((size_t)(size > 0 ? size : 0) + 1, 1);
    if (!old) {
      fclose(f);
      return -1;
    }
    len = fread(old, 1, (size_t)(size > 0 ? size : 0), f);
    old[len] = 0;
    fclose(f);
    char key[128];
    snprintf(key, sizeof key, "\n%s", heading);
    char *at = strstr(old, key);
    head = at ? (size_t)(at - old) + 1 : len;
    char *next = at ? strstr(at + 1, "\n## ") : NULL;
    tail = next ? (size_t)(next - old) + 1 : len;
    while (head > 0 && old[head - 1] == '\n') head--;
  }
  f = fopen(path, "w");
  if (!f) {
    free(old);
    return -1;
  }
  if (head) {
    fwrite(old, 1, head, f);
    fputs("\n\n", f);
  }
  fputs(text, f);
  if (old && tail < len) {
    fputs("\n", f);
    fwrite(old + tail, 1, len - tail, f);
  }
  free(old);
  return fclose(f) == 0 ? 0 : -1;
}
/* A time in ns as "12.3 us" (ns, us, ms or s, three digits). */
static inline const char *bench_fmt_time(char *buf, size_t len, double ns) {
  if (ns >= 1e9) snprintf(buf, len, "%.3g s", ns * 1e-9);
  else if (ns >= 1e6) snprintf(buf, len, "%.3g ms", ns * 1e-6);
  else if (ns >= 1e3) snprintf(buf, len, "%.3g us", ns * 1e-3);
  else snprintf(buf, len, "%.3g ns", ns);
  return buf;
}

/* The CPU's model name from /proc/cpuinfo ("unknown CPU" without it). */
static inline void bench_cpu_model(char *out, size_t len) {
  snprintf(out, len, "unknown CPU");
  FILE *f = fopen("/proc/cpuinfo", "r");
  char line[512];
  while (f && fgets(line, sizeof line, f)) {
    const char *colon = strchr(line, ':');
    if (strncmp(line, "model name", 10) != 0 || !colon) continue;
    snprintf(out, len, "%s", colon + 1 + strspn(colon + 1, " \t"));
    out[strcspn(out, "\r\n")] = 0;
    break;
  }
  if (f) fclose(f);
}

/* The vector instructions this file was compiled for, from the compiler's
 * predefined macros (-march=native names the build machine's). */
static inline const char *bench_isa(void) {
#if defined(__AVX512F__)
  return "AVX-512 (x86-64-v4 or above)";
#elif defined(__AVX2__) && defined(__FMA__)
  return "AVX2 and FMA (x86-64-v3)";
#elif defined(__SSE4_2__)
  return "SSE4.2 (x86-64-v2)";
#elif defined(__x86_64__)
  return "SSE2 (x86-64)";
#elif defined(__aarch64__)
  return "AArch64 (NEON)";
#else
  return "unknown";
#endif
}

/* Prints "prog: what: detail" and exits 1. */
static inline void bench_die(const char *prog, const char *what, const char *detail) {
  fprintf(stderr, "%s: %s%s%s\n", prog, what, detail ? ": " : "", detail ? detail : "");
  exit(1);
}

/* Compiles s once for its stable-step estimate, sets dt to `share` of it
 * and compiles again; exits with the compiler's message on failure. */
static inline swModel *bench_compile_at(const char *prog, swSpec *s, double share) {
  char err[512] = "";
  swModel *m0 = sw_compile(s, err, sizeof err);
  if (!m0) bench_die(prog, "sw_compile failed", err);
  sw_spec_set_dt(s, share * sw_stable_dt(m0));
  sw_model_free(m0);
  swModel *m = sw_compile(s, err, sizeof err);
  if (!m) bench_die(prog, "sw_compile failed", err);
  return m;
}

/* ns per step of sw_steps(), `chunk` steps a call, over at least `seconds`
 * of calls (one batch), and in *cpu_ns (unless NULL) the thread's CPU time
 * per step over the same calls; exits on a failed step. */
static inline double bench_ns_per_step(const char *prog, const swModel *m, swData *d, int chunk,
                                       double seconds, double *cpu_ns) {
  long count = 0;
  double spent = 0, cpu = 0;
  while (spent < seconds || count == 0) {
    double t0 = wall_seconds(), c0 = thread_cpu_seconds();
    if (sw_steps(m, d, chunk) != SW_OK) bench_die(prog, "sw_steps failed", d->error);
    cpu += thread_cpu_seconds() - c0;
    spent += wall_seconds() - t0;
    count += chunk;
  }
  if (cpu_ns) *cpu_ns = 1e9 * cpu / (double)count;
  return 1e9 * spent / (double)count;
}

#endif
