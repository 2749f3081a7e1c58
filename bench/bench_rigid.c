/* bench_rigid.c — what a rigid bone saves: one scene with its bone elastic
 * and rigid, the stable step, the cost of a step and the wall time to
 * simulate a fixed stretch of physical time.
 *
 * Design.  The scene is an arm in miniature built with the public API: a
 * bone (E = 15 GPa, density 1750 kg/m^3, L = 0.34 m, r = 10.5 mm, 20
 * elements) hung from the shoulder on an anchored spherical joint, released
 * 30 degrees from the vertical, and a soft strand (E = 1 MPa, 1060 kg/m^3,
 * L = 0.3 m, r = 5 mm, 14 elements, a muscle-like rod) hung from the bone's
 * end on a second spherical joint, under gravity.  Four variants: the bone
 * elastic or rigid (swRodDesc.rigid), with the joints' default stiffness or
 * with the fixed k = 5e5 N/m of Zhang et al. 2019 (Suppl. Table 5).  Each
 * runs at dt = 0.5 x sw_stable_dt() of its own model, as a simulator does by
 * default.  Per variant: ns per step is the median of NREP batches of
 * sw_steps() (each at least BATCH_SECONDS), and the wall time to simulate
 * SIM_SECONDS of physical time is the median of NREP runs from sw_reset();
 * the variants run in the same process, interleaved repeat by repeat, so the
 * ratios compare like with like.  The section goes to stdout and into the
 * report named by argv[1]: its own section (from "## Rigid rods" to the next
 * heading) is replaced, or appended, so running it twice leaves one section.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "sinew.h"
#include "bench_util.h"

enum { NREP = 9, NVAR = 4 };
static const double BATCH_SECONDS = 0.2;   /* minimum wall time of a timed batch, s */
static const double SIM_SECONDS = 0.01;    /* physical time of a timed run, s       */
static const char SECTION[] = "## Rigid rods";

static void die(const char *msg, const char *detail) {
  fprintf(stderr, "bench_rigid: %s%s%s\n", msg, detail ? ": " : "", detail ? detail : "");
  exit(1);
}

/* ---- the scene ---- */

typedef struct {
  int rigid;          /* the bone is rigid                         */
  double k;           /* joint stiffness, N/m; 0 = default          */
  swModel *m;
  swData *d;
  double estimate;    /* sw_stable_dt of the model, s               */
  long sim_steps;     /* steps for SIM_SECONDS                      */
  double ns_step[NREP], wall_sim[NREP];
  double tip[3];      /* bone tip after SIM_SECONDS, m              */
} Variant;

static swModel *compile_or_die(const swSpec *s) {
  char err[512] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  if (!m) die("sw_compile failed", err);
  return m;
}

static void build(Variant *v) {
  swSpec *s = sw_spec_new();
  if (!s) die("out of memory", NULL);
  const double tilt = 30.0 * 3.14159265358979323846 / 180.0;
  swRodDesc bone;
  sw_rod_desc_init(&bone);
  bone.name = "humerus";
  bone.nelem = 20;
  bone.length = 0.34;
  bone.radius_start = bone.radius_end = 0.0105;
  bone.youngs = 15e9;
  bone.density = 1750;
  bone.direction[0] = sin(tilt), bone.direction[1] = 0, bone.direction[2] = -cos(tilt);
  bone.normal[0] = 0, bone.normal[1] = 1, bone.normal[2] = 0;
  bone.rigid = v->rigid;
  swRodDesc strand;
  sw_rod_desc_init(&strand);
  strand.name = "strand";
  strand.nelem = 14;
  strand.length = 0.3;
  strand.radius_start = strand.radius_end = 0.005;
  strand.youngs = 1e6;
  strand.density = 1060;
  for (int k = 0; k < 3; k++) strand.start[k] = bone.length * bone.direction[k];
  strand.direction[0] = 0, strand.direction[1] = 0, strand.direction[2] = -1;
  strand.normal[0] = 1, strand.normal[1] = 0, strand.normal[2] = 0;
  if (sw_spec_add_rod(s, &bone) < 0 || sw_spec_add_rod(s, &strand) < 0) die("out of memory", NULL);
  swJointDesc j;
  sw_joint_desc_init(&j);
  j.name = "shoulder";
  j.rod_a = 0, j.node_a = 0, j.rod_b = -1;
  j.stiffness = v->k;
  if (sw_spec_add_joint(s, &j) < 0) die("out of memory", NULL);
  j.name = "insertion";
  j.rod_a = 0, j.node_a = -1, j.rod_b = 1, j.node_b = 0;
  if (sw_spec_add_joint(s, &j) < 0) die("out of memory", NULL);
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  swModel *estimate = compile_or_die(s);
  v->estimate = sw_stable_dt(estimate);
  sw_model_free(estimate);
  sw_spec_set_dt(s, 0.5 * v->estimate);
  v->m = compile_or_die(s);
  sw_spec_free(s);
  v->d = sw_data_new(v->m);
  if (!v->d) die("out of memory", NULL);
  v->sim_steps = (long)ceil(SIM_SECONDS / v->m->dt - 1e-9);
}

static void steps_or_die(Variant *v, long k) {
  if (sw_steps(v->m, v->d, k) != SW_OK) die("sw_steps failed", v->d->error);
}

/* One repeat of both measurements.  ns per step: a batch of whole 10 ms
 * runs (reset outside the timer), at least BATCH_SECONDS long. */
static void measure(Variant *v, int rep) {
  sw_reset(v->m, v->d);
  double t0 = wall_seconds();
  steps_or_die(v, v->sim_steps);
  v->wall_sim[rep] = wall_seconds() - t0;
  sw_get3(v->m, v->d->x, v->m->node_adr[0] + v->m->rod_nelem[0], v->tip);
  double spent = 0;
  long steps = 0;
  while (spent < BATCH_SECONDS) {
    sw_reset(v->m, v->d);
    t0 = wall_seconds();
    steps_or_die(v, v->sim_steps);
    spent += wall_seconds() - t0;
    steps += v->sim_steps;
  }
  v->ns_step[rep] = 1e9 * spent / (double)steps;
}

/* ---- the report ---- */

static const char *fmt_time(char *buf, size_t len, double t) {
  if (t >= 1) snprintf(buf, len, "%.3g s", t);
  else if (t >= 1e-3) snprintf(buf, len, "%.3g ms", t * 1e3);
  else if (t >= 1e-6) snprintf(buf, len, "%.3g us", t * 1e6);
  else snprintf(buf, len, "%.3g ns", t * 1e9);
  return buf;
}

static void write_section(FILE *f, Variant *v, const double *ns, const double *wall) {
  char a[32], b[32], c[32];
  fprintf(f, "%s: one bone elastic vs rigid\n\n", SECTION);
  fprintf(f, "Written by bench/bench_rigid.c, which `make bench` runs after bench_rod (same\n"
             "machine, compiler and flags as above; this section is replaced on every run).\n\n");
  fprintf(f, "- Scene: a bone (E = 15 GPa, 1750 kg/m^3, L = 0.34 m, r = 10.5 mm, 20 elements)\n"
             "  hung from an anchored spherical joint at the shoulder, released 30 degrees from\n"
             "  the vertical, with a soft strand (E = 1 MPa, 1060 kg/m^3, L = 0.3 m, r = 5 mm,\n"
             "  14 elements) hung from its end on a second spherical joint; gravity. The bone is\n"
             "  elastic or rigid (`swRodDesc.rigid`); the joints have their default stiffness\n"
             "  (derived from the joined elements) or Zhang et al. 2019's k = 5e5 N/m.\n"
             "- Each variant runs at dt = 0.5 x sw_stable_dt() of its own model (a simulator's\n"
             "  default). ns/step: median of %d batches of whole %s runs from sw_reset(),\n"
             "  each batch at least %.1f s; wall for %s: median of %d single runs. The\n"
             "  variants are measured in the same process, interleaved repeat by repeat.\n"
             "- Tip: the bone's free end after %s; \"vs elastic\" is its distance to the\n"
             "  elastic bone's tip with the same joints, over the distance the tip moved.\n\n",
          NREP, fmt_time(a, sizeof a, SIM_SECONDS), BATCH_SECONDS, fmt_time(b, sizeof b, SIM_SECONDS),
          NREP, fmt_time(c, sizeof c, SIM_SECONDS));
  fprintf(f, "| bone | joints | stable dt estimate | dt used | steps for %s | ns/step (median) | "
             "wall for %s (median) | tip vs elastic |\n",
          fmt_time(a, sizeof a, SIM_SECONDS), fmt_time(b, sizeof b, SIM_SECONDS));
  fprintf(f, "|---|---|--:|--:|--:|--:|--:|--:|\n");
  for (int i = 0; i < NVAR; i++) {
    const Variant *e = &v[i & ~1]; /* the elastic twin */
    char est[32], dt[32], w[32], tipdiff[32];
    double x0[3];
    sw_get3(v[i].m, v[i].m->x0, v[i].m->node_adr[0] + v[i].m->rod_nelem[0], x0);
    double moved = 0, diff = 0;
    for (int k = 0; k < 3; k++) {
      moved += (v[i].tip[k] - x0[k]) * (v[i].tip[k] - x0[k]);
      diff += (v[i].tip[k] - e->tip[k]) * (v[i].tip[k] - e->tip[k]);
    }
    if (v[i].rigid) snprintf(tipdiff, sizeof tipdiff, "%.2g", sqrt(diff / moved));
    else snprintf(tipdiff, sizeof tipdiff, "—");
    fprintf(f, "| %s | %s | %s | %s | %ld | %.0f | %s | %s |\n", v[i].rigid ? "rigid" : "elastic",
            v[i].k > 0 ? "k = 5e5 N/m" : "default", fmt_time(est, sizeof est, v[i].estimate),
            fmt_time(dt, sizeof dt, v[i].m->dt), v[i].sim_steps, ns[i],
            fmt_time(w, sizeof w, wall[i]), tipdiff);
  }
  fprintf(f, "\nElastic / rigid, same joints, same run:\n\n");
  fprintf(f, "| joints | step (dt) | cost of a step | wall for %s |\n",
          fmt_time(a, sizeof a, SIM_SECONDS));
  fprintf(f, "|---|--:|--:|--:|\n");
  for (int i = 0; i < NVAR; i += 2)
    fprintf(f, "| %s | rigid %.1f x longer | rigid %.2f x cheaper | rigid %.1f x faster |\n",
            v[i].k > 0 ? "k = 5e5 N/m" : "default", v[i + 1].m->dt / v[i].m->dt,
            ns[i] / ns[i + 1], wall[i] / wall[i + 1]);
  fprintf(f, "\nWhat rigid saves: the bone's elastic waves set the step of the elastic scene;\n"
             "rigid, the bone sets no step of its own and the step is set by the joints (their\n"
             "spring on the body's effective mass) or the strand. A step is also cheaper (no\n"
             "strains or internal loads for the bone, only sums of its loads and one body\n"
             "update). What it costs: the bone's deformation, which under these loads moves its\n"
             "tip by the fraction in the last column.\n");
}

/* Replaces the section in the report at path (bench_util.h), or appends it. */
static void write_report(const char *path, Variant *v, const double *ns, const double *wall) {
  char *text = NULL;
  size_t size = 0;
  FILE *f = open_memstream(&text, &size);
  if (!f) die("out of memory", NULL);
  write_section(f, v, ns, wall);
  fclose(f);
  if (bench_replace_section(path, SECTION, text) != 0) die("cannot write the report", path);
  free(text);
  fprintf(stderr, "bench_rigid: wrote %s\n", path);
}

int main(int argc, char **argv) {
  if (argc > 2) {
    fprintf(stderr, "usage: %s [report.md]\n", argv[0]);
    return SW_EUSAGE;
  }
  Variant v[NVAR];
  memset(v, 0, sizeof v);
  for (int i = 0; i < NVAR; i++) {
    v[i].rigid = i & 1;
    v[i].k = i >= 2 ? 5e5 : 0;
    build(&v[i]);
  }
  for (int rep = 0; rep < NREP; rep++)
    for (int i = 0; i < NVAR; i++) measure(&v[i], rep);
  double ns[NVAR], wall[NVAR];
  for (int i = 0; i < NVAR; i++) {
    ns[i] = median(v[i].ns_step, NREP);
    wall[i] = median(v[i].wall_sim, NREP);
    fprintf(stderr, "bench_rigid: %s bone, %s joints: dt %.3g s, %.0f ns/step, %.3g s for 10 ms\n",
            v[i].rigid ? "rigid" : "elastic", v[i].k > 0 ? "k = 5e5 N/m" : "default", v[i].m->dt,
            ns[i], wall[i]);
  }
  write_section(stdout, v, ns, wall);
  if (argc == 2) write_report(argv[1], v, ns, wall);
  for (int i = 0; i < NVAR; i++) {
    sw_data_free(v[i].d);
    sw_model_free(v[i].m);
  }
  return 0;
}
