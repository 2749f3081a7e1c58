/* bench_obstacle.c — the obstacles' broad phase (obstacle.c): one rope of
 * 1024 elements lying across a field of N spheres, capsules and boxes (N =
 * 10, 100, 1000), all far from it but the few under it, one evaluation of
 * obstacle.c's kernel by the chunk boxes and by the brute force loop over
 * every element-obstacle pair, and a whole step; medians of NREP batches.
 * Writes (or replaces) its section of docs/benchmarks.md.
 *
 * Design.  The scenes are built through the public API like a model's;
 * the kernel is called directly (internal.h), as bench_contact.c does. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sinew.h"
#include "internal.h"
#include "bench_util.h"

#define SECTION "## Rigid obstacles: the broad phase (issue 34)"
enum { NELEM = 1024, NREP = 5, NSCENE = 3 };
static const double BATCH_SECONDS = 0.2;
static const int NOBS[NSCENE] = {10, 100, 1000};

typedef struct {
  swModel *m;
  swData *d;
  int nobs, contacts;
  long tests_grid, tests_brute;
  double ns_grid, ns_brute, ns_step;
} Scene;

static void die(const char *what, const char *detail) { bench_die("bench_obstacle", what, detail); }

/* The rope along x at z = 1 mm over z = 0, 1 m long; obstacles on a 2 m
 * square, their tops at z = 0 (the rope rests on the few under it). */
static void build(Scene *sc, int nobs) {
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "rope";
  r.nelem = NELEM;
  r.length = 1.0;
  r.radius_start = r.radius_end = 1e-3;
  r.start[0] = -0.5, r.start[2] = 1e-3;
  r.direction[0] = 1, r.direction[1] = r.direction[2] = 0;
  r.normal[0] = 0, r.normal[1] = 0, r.normal[2] = 1;
  r.youngs = 1e6, r.density = 1000;
  if (sw_spec_add_rod(s, &r) < 0) die("cannot add the rope", NULL);
  unsigned seed = 2024;
  for (int k = 0; k < nobs; k++) {
    swObstacleDesc o;
    sw_obstacle_desc_init(&o);
    o.shape = (swObstacleShape)(k % 3 == 2 ? SW_OBSTACLE_BOX : k % 3);
    seed = seed * 1103515245u + 12345u;
    o.centre[0] = ((seed >> 8) % 2000) * 1e-3 - 1.0;
    seed = seed * 1103515245u + 12345u;
    o.centre[1] = ((seed >> 8) % 2000) * 1e-3 - 1.0;
    o.radius = 0.01, o.length = 0.02;
    o.half[0] = o.half[1] = o.half[2] = 0.01;
    o.centre[2] = -0.01;
    o.stiffness = 100, o.damping = 0.01;
    if (sw_spec_add_obstacle(s, &o) < 0) die("cannot add an obstacle", NULL);
  }
  sc->m = bench_compile_at("bench_obstacle", s, 0.5);
  sw_spec_free(s);
  sc->d = sw_data_new(sc->m);
  if (!sc->d) die("out of memory", NULL);
  sc->nobs = nobs;
}

static double time_eval(Scene *sc, swObstaclePhase phase) {
  long count = 0;
  double spent = 0;
  while (spent < BATCH_SECONDS || count == 0) {
    double t0 = wall_seconds();
    sw_obstacle_loads_with(sc->m, sc->d, phase);
    spent += wall_seconds() - t0;
    count++;
  }
  return 1e9 * spent / (double)count;
}

static double time_step(Scene *sc) {
  sw_reset(sc->m, sc->d); /* from the scene as laid, each batch */
  return bench_ns_per_step("bench_obstacle", sc->m, sc->d, 4, BATCH_SECONDS, NULL);
}

static void measure(Scene *sc) {
  double grid[NREP], brute[NREP], step[NREP];
  sw_obstacle_loads_with(sc->m, sc->d, SW_OBSTACLE_BRUTE);
  sc->tests_brute = sc->d->obstacle_tests;
  sw_obstacle_loads_with(sc->m, sc->d, SW_OBSTACLE_GRID);
  sc->tests_grid = sc->d->obstacle_tests;
  sc->contacts = sc->d->obstacle_contacts;
  for (int rep = 0; rep < NREP; rep++) {
    grid[rep] = time_eval(sc, SW_OBSTACLE_GRID);
    brute[rep] = time_eval(sc, SW_OBSTACLE_BRUTE);
    step[rep] = time_step(sc);
  }
  sc->ns_grid = median(grid, NREP);
  sc->ns_brute = median(brute, NREP);
  sc->ns_step = median(step, NREP);
}

static void write_section(FILE *f, const Scene *sc) {
  fprintf(f, "%s\n\n", SECTION);
  fprintf(f, "Written by bench/bench_obstacle.c, which `make bench` runs after bench_contact\n"
             "(same machine, compiler and flags as above; this section is replaced on every run).\n\n"
             "- Scenes: one rope of %d elements (1 m, r = 1 mm) lying on a field of N spheres,\n"
             "  capsules and boxes (size 2 cm) at random on a 2 m square (fixed seed): most are\n"
             "  far from it, a few under it.\n"
             "- One evaluation: obstacle.c's kernel alone (`sw_obstacle_loads_with`), by the\n"
             "  chunk boxes (%d elements a chunk) and by brute force over every element-obstacle\n"
             "  pair (each pair still first tested against the shape's frame box); median of %d\n"
             "  batches of at least %.2f s. Step: a whole position Verlet step (`sw_steps`),\n  each batch from the scene as laid.\n\n",
          NELEM, SW_OBSTACLE_CHUNK, NREP, BATCH_SECONDS);
  fprintf(f, "| obstacles | contacts | pairs tested (chunks / brute) | chunk evaluation | brute force "
             "| brute / chunks | whole step | obstacle share |\n|--:|--:|--:|--:|--:|--:|--:|--:|\n");
  for (int i = 0; i < NSCENE; i++) {
    char g[32], b[32], st[32];
    fprintf(f, "| %d | %d | %ld / %ld | %s | %s | %.1f | %s | %.0f%% |\n", sc[i].nobs, sc[i].contacts,
            sc[i].tests_grid, sc[i].tests_brute, bench_fmt_time(g, sizeof g, sc[i].ns_grid),
            bench_fmt_time(b, sizeof b, sc[i].ns_brute), sc[i].ns_brute / sc[i].ns_grid,
            bench_fmt_time(st, sizeof st, sc[i].ns_step), 100 * sc[i].ns_grid / sc[i].ns_step);
  }
  fprintf(f, "\nThe chunk boxes cost N x %d box tests an evaluation plus the elements near an\n"
             "obstacle; the brute force N x %d element tests. tests/runtime/test_obstacle.c checks\n"
             "that both find the same loads, bit for bit.\n", NELEM / SW_OBSTACLE_CHUNK, NELEM);
}

int main(int argc, char **argv) {
  if (argc > 2) {
    fprintf(stderr, "usage: %s [report.md]\n", argv[0]);
    return SW_EUSAGE;
  }
  Scene sc[NSCENE];
  for (int i = 0; i < NSCENE; i++) {
    build(&sc[i], NOBS[i]);
    measure(&sc[i]);
  }
  char *text = NULL;
  size_t size = 0;
  FILE *f = open_memstream(&text, &size);
  if (!f) die("out of memory", NULL);
  write_section(f, sc);
  fclose(f);
  fputs(text, stdout);
  if (argc == 2 && bench_replace_section(argv[1], SECTION, text) != 0) die("cannot write the report", argv[1]);
  free(text);
  for (int i = 0; i < NSCENE; i++) sw_data_free(sc[i].d), sw_model_free(sc[i].m);
  return 0;
}
