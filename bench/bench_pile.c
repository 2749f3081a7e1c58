/* bench_pile.c — what contact-heavy scenes cost (issue 34): a rope coiled
 * into a box and settled there under gravity, touching itself and the box
 * everywhere, and a rope hung over a post with a weight on each end, each
 * at several sizes, as ns per element-step against the contacts in play.
 *
 * Design.  The pile: ropes of r = 2 mm, 4 mm elements (E = 0.2 MPa, 1000
 * kg/m^3, linear damping 0.3 kg m^-1 s^-1) laid as a helix of radius 2 cm,
 * 1.2 diameters a turn (a K-start helix for K ropes: rope k starts k
 * diameters above rope 0), straight at rest, dropped from 5 mm onto the
 * floor of an open box of five fixed boxes (floor and four walls, a 5.2 cm
 * square inside, frictional: mu_s = 0.3, mu_k = 0.25), with rod-rod
 * contact among all ropes and self-contact on (k_c = 300 N/m).  Gravity
 * closes the coil, its turns lie on one another and the coil, which would
 * rather be straight, presses out on the walls.  Each scene settles for
 * SETTLE_SECONDS of simulated time, then the step (sw_steps at half the
 * stable estimate, the scene still moving on) is timed in NREP batches of
 * at least BATCH_SECONDS; the median is quoted.  The post: a rope of 600
 * elements (60 cm, r = 1 mm) laid over a fixed cylinder of radius R across
 * it (mu_s = 0.4, mu_k = 0.3; E = 1 MPa), its legs hanging, 50 mN on one end and 100
 * mN on the other (less than the capstan's ratio e^{0.4 pi} = 3.5, so it
 * holds); R from 5 mm to 8 cm sets how many elements touch.  Contact counts
 * (rod-rod pairs and element-obstacle contacts) are those of the last
 * evaluation; the kernels' share is their evaluation by contact.c and
 * obstacle.c alone (internal.h, as bench_contact.c does) over the step.
 * Writes (or replaces) its section of the report named by argv[1]. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sinew.h"
#include "internal.h"
#include "bench_util.h"

#define SECTION "## Contact-heavy scenes: a rope pile and a rope on a post (issue 34)"
#define PROG "bench_pile"
#ifndef SW_BENCH_CFLAGS
#define SW_BENCH_CFLAGS "unknown (built without -DSW_BENCH_CFLAGS)"
#endif
enum { NREP = 5, NPILE = 4, NPOST = 5, POST_N = 600 };
static const double BATCH_SECONDS = 0.2, SETTLE_SECONDS = 0.6, POST_SETTLE_SECONDS = 0.05;
static const struct { int ropes, nelem; } PILE[NPILE] = {{1, 200}, {1, 400}, {1, 800}, {4, 400}};
static const double POST_R[NPOST] = {0.005, 0.01, 0.02, 0.04, 0.08};
static const double PILE_R = 0.002, PILE_DL = 0.004, COIL_R = 0.02, BOX_HALF = 0.026;
static const double POST_LEN = 0.6, POST_ROPE_R = 0.001;

typedef struct {
  swModel *m;
  swData *d;
  int nelem, pairs, touching;  /* rod-rod pairs, element-obstacle contacts */
  double ns_step, ns_kernels;  /* a step, and contact + obstacle kernels   */
  double ns_cpu;               /* the step's CPU time (the thread's)       */
  double size;                 /* pile: ropes; post: R                     */
} Scene;

static swRodDesc rope(int nelem, double length, double radius, double youngs) {
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "rope";
  r.nelem = nelem;
  r.length = length;
  r.radius_start = r.radius_end = radius;
  r.youngs = youngs, r.density = 1000;
  r.damping = SW_DAMP_LINEAR, r.gamma = 0.3;
  return r;
}

/* A fixed box of half sizes h at c, frictional. */
static void add_box(swSpec *s, double cx, double cy, double cz, double hx, double hy, double hz) {
  swObstacleDesc o;
  sw_obstacle_desc_init(&o);
  o.shape = SW_OBSTACLE_BOX;
  o.centre[0] = cx, o.centre[1] = cy, o.centre[2] = cz;
  o.half[0] = hx, o.half[1] = hy, o.half[2] = hz;
  o.stiffness = 300, o.damping = 0.01;
  o.static_friction = 0.3, o.kinetic_friction = 0.25;
  if (sw_spec_add_obstacle(s, &o) < 0) bench_die(PROG, "cannot add a box", NULL);
}

static void build_pile(Scene *sc, int ropes, int nelem) {
  swSpec *s = sw_spec_new();
  if (!s) bench_die(PROG, "out of memory", NULL);
  const double pitch = 1.2 * 2 * PILE_R * ropes, length = nelem * PILE_DL, wall = 0.01, height = 0.15;
  double *x = malloc(sizeof(double) * 3 * (size_t)(nelem + 1)), *Q = malloc(sizeof(double) * 9 * (size_t)nelem);
  if (!x || !Q) bench_die(PROG, "out of memory", NULL);
  for (int k = 0; k < ropes; k++) {
    swRodDesc r = rope(nelem, length, PILE_R, 2e5);
    const int id = sw_spec_add_rod(s, &r);
    const double start[3] = {COIL_R, 0, PILE_R + 0.005 + k * 1.2 * 2 * PILE_R}, axis[3] = {0, 0, 1},
                 normal[3] = {-1, 0, 0};
    char err[256] = "";
    if (id < 0 || sw_shape_helix(nelem, COIL_R, pitch, length, 1, start, axis, normal, x, Q, err, sizeof err) != SW_OK ||
        sw_spec_set_start_shape(s, id, x, Q) != SW_OK)
      bench_die(PROG, "cannot lay the coil", err);
  }
  free(x), free(Q);
  add_box(s, 0, 0, -wall, BOX_HALF + 2 * wall, BOX_HALF + 2 * wall, wall); /* floor, top at z = 0 */
  for (int side = -1; side <= 1; side += 2) {
    add_box(s, side * (BOX_HALF + wall), 0, height, wall, BOX_HALF + 2 * wall, height);
    add_box(s, 0, side * (BOX_HALF + wall), height, BOX_HALF + 2 * wall, wall, height);
  }
  swContactDesc c;
  sw_contact_desc_init(&c);
  c.stiffness = 300, c.damping = 0.01, c.self = 1;
  if (sw_spec_add_contact(s, &c) < 0) bench_die(PROG, "out of memory", NULL);
  sw_spec_set_gravity(s, (const double[3]){0, 0, -9.81});
  sc->m = bench_compile_at(PROG, s, 0.5);
  sw_spec_free(s);
  sc->size = ropes;
}

/* The rope over the post: a leg down at x = -a, the half circle of radius
 * a = R + r over the top, the other leg down at x = +a (arc length s). */
static void draped(double s, double p[3], const void *ctx) {
  const double a = *(const double *)ctx, leg = 0.5 * (POST_LEN - M_PI * a);
  p[1] = 0;
  if (s < leg) p[0] = -a, p[2] = s - leg;
  else if (s > leg + M_PI * a) p[0] = a, p[2] = leg + M_PI * a - s;
  else p[0] = -a * cos((s - leg) / a), p[2] = a * sin((s - leg) / a);
}

static void build_post(Scene *sc, double radius) {
  swSpec *s = sw_spec_new();
  if (!s) bench_die(PROG, "out of memory", NULL);
  swRodDesc r = rope(POST_N, POST_LEN, POST_ROPE_R, 1e6);
  const int id = sw_spec_add_rod(s, &r);
  double *x = malloc(sizeof(double) * 3 * (POST_N + 1)), *Q = malloc(sizeof(double) * 9 * POST_N);
  const double a = radius + POST_ROPE_R, normal[3] = {0, 1, 0};
  char err[256] = "";
  if (id < 0 || !x || !Q || sw_shape_curve(POST_N, POST_LEN, draped, &a, normal, x, Q, err, sizeof err) != SW_OK ||
      sw_spec_set_start_shape(s, id, x, Q) != SW_OK)
    bench_die(PROG, "cannot drape the rope", err);
  free(x), free(Q);
  swObstacleDesc o;
  sw_obstacle_desc_init(&o);
  o.shape = SW_OBSTACLE_CYLINDER;
  o.axis[0] = 0, o.axis[1] = 1, o.axis[2] = 0;
  o.radius = radius;
  o.stiffness = 300, o.damping = 0.01;
  o.static_friction = 0.4, o.kinetic_friction = 0.3;
  if (sw_spec_add_obstacle(s, &o) < 0) bench_die(PROG, "cannot add the post", NULL);
  for (int end = 0; end < 2; end++) {
    swLoadDesc w = {.kind = SW_LOAD_FORCE, .rod = id, .index = end ? -1 : 0, .vec = {0, 0, end ? -0.1 : -0.05},
                    .signal = sw_signal_const(1)};
    if (sw_spec_add_load(s, &w) < 0) bench_die(PROG, "cannot hang a weight", NULL);
  }
  sw_spec_set_gravity(s, (const double[3]){0, 0, -9.81});
  sc->m = bench_compile_at(PROG, s, 0.5);
  sw_spec_free(s);
  sc->size = radius;
}

/* ns per evaluation of both contact kernels, one batch (no state but the
 * scratch and the friction anchors, which an evaluation at the same state
 * leaves as they were). */
static double time_kernels(Scene *sc) {
  long count = 0;
  double spent = 0;
  while (spent < 0.25 * BATCH_SECONDS || count == 0) {
    double t0 = wall_seconds();
    sw_contact_loads_with(sc->m, sc->d, SW_CONTACT_GRID);
    sw_obstacle_loads_with(sc->m, sc->d, SW_OBSTACLE_GRID);
    spent += wall_seconds() - t0;
    count++;
  }
  return 1e9 * spent / (double)count;
}

static void settle_and_measure(Scene *sc, double settle) {
  sc->d = sw_data_new(sc->m);
  if (!sc->d) bench_die(PROG, "out of memory", NULL);
  sc->nelem = sc->m->nelem;
  const int steps = (int)ceil(settle / sc->m->dt);
  if (sw_steps(sc->m, sc->d, steps) != SW_OK) bench_die(PROG, "sw_steps failed", sc->d->error);
  double step[NREP], kern[NREP], cpu[NREP];
  for (int rep = 0; rep < NREP; rep++) {
    step[rep] = bench_ns_per_step(PROG, sc->m, sc->d, 8, BATCH_SECONDS, &cpu[rep]);
    kern[rep] = time_kernels(sc);
  }
  sc->pairs = sc->d->contact_pairs;
  sc->touching = sc->d->obstacle_contacts;
  sc->ns_step = median(step, NREP);
  sc->ns_kernels = median(kern, NREP);
  sc->ns_cpu = median(cpu, NREP);
}

static void write_row(FILE *f, const char *what, const Scene *sc) {
  char st[32], pe[32], pc[32];
  fprintf(f, "| %s | %d | %d | %d | %.2f | %s | %s | %s | %.0f%% |\n", what, sc->nelem, sc->pairs, sc->touching,
          (double)(sc->pairs + sc->touching) / sc->nelem, bench_fmt_time(st, sizeof st, sc->ns_step),
          bench_fmt_time(pe, sizeof pe, sc->ns_step / sc->nelem), bench_fmt_time(pc, sizeof pc, sc->ns_cpu / sc->nelem),
          100 * sc->ns_kernels / sc->ns_step);
}

static double pile_min_per_elem(const Scene *pile) {
  double v = INFINITY;
  for (int i = 0; i < NPILE; i++) v = fmin(v, pile[i].ns_cpu / pile[i].nelem);
  return v;
}
static double pile_max_per_elem(const Scene *pile) {
  double v = 0;
  for (int i = 0; i < NPILE; i++) v = fmax(v, pile[i].ns_cpu / pile[i].nelem);
  return v;
}

static void write_section(FILE *f, const Scene *pile, const Scene *post) {
  char cpu[160], load[32] = "unknown";
  bench_cpu_model(cpu, sizeof cpu);
  FILE *la = fopen("/proc/loadavg", "r");
  if (la && fscanf(la, "%31s", load) != 1) snprintf(load, sizeof load, "unknown");
  if (la) fclose(la);
  fprintf(f, "%s\n\n", SECTION);
  fprintf(f, "Written by bench/bench_pile.c, which `make bench` runs after bench_obstacle (same\n"
             "machine, compiler and flags as above; this section is replaced on every run).\n\n"
             "- Pile: ropes of 4 mm elements (r = 2 mm, E = 0.2 MPa, 1000 kg/m^3, damped) laid as a\n"
             "  helix of radius 2 cm (K ropes: a K-start helix), straight at rest, dropped onto the\n"
             "  floor of an open box of five fixed frictional boxes (5.2 cm square inside), with\n"
             "  rod-rod contact among them and self-contact; settled for %.2f s of simulated time\n"
             "  (the coil closes, its turns lie on each other and it presses out on the walls).\n"
             "- Post: a rope of %d elements (60 cm, r = 1 mm) over a fixed frictional cylinder of\n"
             "  radius R, 50 mN on one end and 100 mN on the other (it holds: capstan), settled\n"
             "  for %.2f s.\n"
             "- Step: `sw_steps` at half the stable estimate, the scene moving on; median of %d\n"
             "  batches of at least %.2f s. Kernels: contact.c's and obstacle.c's evaluations\n"
             "  alone over the step (over 100%%: the two medians' noise). CPU: the thread's CPU\n"
             "  time over the same batches (what the wall time is, less the waits for a core\n"
             "  on a shared machine). Contacts: those of the last evaluation.\n"
             "- Machine: %s, built with `%s` (%s); one thread; the load average\n"
             "  (/proc/loadavg, 1 min) was %s when the last scene was measured.\n\n",
          SETTLE_SECONDS, POST_N, POST_SETTLE_SECONDS, NREP, BATCH_SECONDS, cpu, SW_BENCH_CFLAGS, bench_isa(),
          load);
  fprintf(f, "| scene | elements | rod-rod pairs | element-obstacle contacts | contacts per element "
             "| step | per element-step | CPU per element-step | kernels / step |\n"
             "|:--|--:|--:|--:|--:|--:|--:|--:|--:|\n");
  char what[64];
  for (int i = 0; i < NPILE; i++) {
    snprintf(what, sizeof what, "pile, %d rope%s of %d", PILE[i].ropes, PILE[i].ropes > 1 ? "s" : "",
             PILE[i].nelem);
    write_row(f, what, &pile[i]);
  }
  for (int i = 0; i < NPOST; i++) {
    snprintf(what, sizeof what, "post, R = %g cm", 100 * POST_R[i]);
    write_row(f, what, &post[i]);
  }
  /* the post's step (CPU time) against its contacts: least squares, ns a contact */
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < NPOST; i++) {
    const double c = post[i].touching, t = post[i].ns_cpu;
    sx += c, sy += t, sxx += c * c, sxy += c * t;
  }
  const double slope = (NPOST * sxy - sx * sy) / (NPOST * sxx - sx * sx), base = (sy - slope * sx) / NPOST;
  char b[32], c[32], lo[32], hi[32];
  const Scene *first = &pile[0], *last = &pile[NPILE - 1];
  fprintf(f, "\nOn the post the step grows with the elements touching it: a least-squares\n"
             "line through the five rows' CPU times gives %s a step with none and %s more for each\n"
             "frictional contact (its anchor found, moved and kept); on this shared machine the\n"
             "rows' wall times move by tens of percent from run to run. The pile costs %s to\n"
             "%s of CPU per element-step, %.1f times as much per element at %d elements as at\n"
             "%d while the elements grow %d times (and the contacts per element from %.2f to\n"
             "%.2f, and the grid's arrays outgrow the caches): far from the square a pairwise\n"
             "search would give. In a dense pile each element has, by estimate, tens of\n"
             "candidates in its grid cell (side: the element length plus two radii) and its 13\n"
             "half-neighbours, most of them within reach, so contact is nearly all of the step,\n"
             "30 to 60 times a free rope's step per element (bench_rod's first table). The whole\n"
             "benchmark takes about 35 s of CPU.\n",
          bench_fmt_time(b, sizeof b, base), bench_fmt_time(c, sizeof c, slope),
          bench_fmt_time(lo, sizeof lo, pile_min_per_elem(pile)), bench_fmt_time(hi, sizeof hi, pile_max_per_elem(pile)),
          (last->ns_cpu / last->nelem) / (first->ns_cpu / first->nelem), last->nelem, first->nelem,
          last->nelem / first->nelem, (double)(first->pairs + first->touching) / first->nelem,
          (double)(last->pairs + last->touching) / last->nelem);
}

int main(int argc, char **argv) {
  if (argc > 2) {
    fprintf(stderr, "usage: %s [report.md]\n", argv[0]);
    return SW_EUSAGE;
  }
  Scene pile[NPILE] = {0}, post[NPOST] = {0};
  for (int i = 0; i < NPILE; i++) {
    build_pile(&pile[i], PILE[i].ropes, PILE[i].nelem);
    settle_and_measure(&pile[i], SETTLE_SECONDS);
    fprintf(stderr, PROG ": pile %d x %d: %.0f ns a step, %d pairs, %d on the box\n", PILE[i].ropes,
            PILE[i].nelem, pile[i].ns_step, pile[i].pairs, pile[i].touching);
  }
  for (int i = 0; i < NPOST; i++) {
    build_post(&post[i], POST_R[i]);
    settle_and_measure(&post[i], POST_SETTLE_SECONDS);
    fprintf(stderr, PROG ": post R = %g: %.0f ns a step, %d on the post\n", POST_R[i], post[i].ns_step,
            post[i].touching);
  }
  char *text = NULL;
  size_t size = 0;
  FILE *f = open_memstream(&text, &size);
  if (!f) bench_die(PROG, "out of memory", NULL);
  write_section(f, pile, post);
  fclose(f);
  fputs(text, stdout);
  if (argc == 2 && bench_replace_section(argv[1], SECTION, text) != 0) bench_die(PROG, "cannot write the report", argv[1]);
  free(text);
  for (int i = 0; i < NPILE; i++) sw_data_free(pile[i].d), sw_model_free(pile[i].m);
  for (int i = 0; i < NPOST; i++) sw_data_free(post[i].d), sw_model_free(post[i].m);
  return 0;
}
