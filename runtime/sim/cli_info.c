/* cli_info.c — what a simulator tells of its model: --help (the options and
 * their defaults, the params, the objective) and --info (the compiled scene:
 * rods, joints, muscles, environments, loads, the law, the scheme and its
 * step, the frames, memory, threads, params), and the formatting of times,
 * sizes and param values they show.
 *
 * Design.  Both print to stdout and change nothing.  --help is made from the
 * table of options (cli_options.c) and the program's params; --info is
 * printed after the scene is built and compiled (cli.c), so it reports the
 * model a run would use: the step taken and where it comes from, the part
 * that sets the stable estimate, the frames and the memory.  Values are shown
 * as a reader writes them: a time in the unit that keeps the number readable,
 * a param in the unit the model wrote it in (in SI, named by its dimension,
 * when that unit does not fit); the run's summary and a study's units use
 * the same two functions (sw_cli_format_time, sw_cli_param_in_unit). */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "cli.h"
#include "engine/internal.h"

/* ---- values ---- */

/* "50 ns", "1.5 ms", "2 s": the unit that keeps the number readable. */
const char *sw_cli_format_time(char *buf, size_t len, double t) {
  double a = fabs(t);
  if (a == 0 || !isfinite(a) || a >= 1) snprintf(buf, len, "%.6g s", t);
  else if (a >= 1e-3) snprintf(buf, len, "%.6g ms", t * 1e3);
  else if (a >= 1e-6) snprintf(buf, len, "%.6g us", t * 1e6);
  else snprintf(buf, len, "%.6g ns", t * 1e9);
  return buf;
}

/* "0.19 mm", "2 cm", "1.5 m" */
static const char *format_length(char *buf, size_t len, double x) {
  double a = fabs(x);
  if (a == 0 || !isfinite(a) || a >= 1) snprintf(buf, len, "%.3g m", x);
  else if (a >= 1e-2) snprintf(buf, len, "%.3g cm", x * 1e2);
  else if (a >= 1e-3) snprintf(buf, len, "%.3g mm", x * 1e3);
  else snprintf(buf, len, "%.3g um", x * 1e6);
  return buf;
}

static const char *format_bytes(char *buf, size_t len, double bytes) {
  if (bytes < 1024) snprintf(buf, len, "%.0f B", bytes);
  else if (bytes < 1024 * 1024) snprintf(buf, len, "%.1f KiB", bytes / 1024);
  else if (bytes < 1024.0 * 1024 * 1024) snprintf(buf, len, "%.1f MiB", bytes / (1024 * 1024));
  else snprintf(buf, len, "%.2f GiB", bytes / (1024.0 * 1024 * 1024));
  return buf;
}

/* A param's value in the unit the model wrote it in, or in SI when that unit
 * cannot be read or does not fit the param's dimension; the unit's name in
 * *unit ("" when dimensionless).  For --help, --info and /params. */
double sw_cli_param_in_unit(const swParam *q, double value, char *unit, size_t len) {
  if (q->unit && q->unit[0]) {
    char text[96];
    double scale;
    signed char dim[SW_NDIM];
    snprintf(text, sizeof text, "1 %s", q->unit);
    if (!sw_parse_quantity(text, &scale, dim, NULL, 0) && !memcmp(dim, q->dim, SW_NDIM) &&
        scale != 0) {
      snprintf(unit, len, "%s", q->unit);
      return value / scale;
    }
  }
  unit[0] = '\0';
  if (memcmp(q->dim, DIM_NONE, SW_NDIM)) {
    /* "length (m)" -> "m"; "kg m^-1 s^-2" as it is */
    char what[64];
    const char *d = sw_dim_describe(what, sizeof what, q->dim), *open = strchr(d, '(');
    if (open) snprintf(unit, len, "%.*s", (int)strcspn(open + 1, ")"), open + 1);
    else snprintf(unit, len, "%s", d);
  }
  return value;
}

/* "0.3 m", "0.3 (SI, length (m))", "2" */
static const char *format_param(char *buf, size_t len, const swParam *q, double value) {
  char unit[48], what[64];
  double v = sw_cli_param_in_unit(q, value, unit, sizeof unit);
  if (q->unit && q->unit[0] && !strcmp(unit, q->unit)) snprintf(buf, len, "%.6g %s", v, unit);
  else if (unit[0])
    snprintf(buf, len, "%.6g (SI, %s)", v, sw_dim_describe(what, sizeof what, q->dim));
  else snprintf(buf, len, "%.6g", v);
  return buf;
}

/* "in (0 N, 50 N)": a param's range in its unit ("" without one). */
static const char *format_range(char *buf, size_t len, const swParam *q) {
  char lo[48], hi[48], unit[48];
  if (!q->ranged) {
    snprintf(buf, len, "%s", "");
    return buf;
  }
  snprintf(lo, sizeof lo, "%.6g", sw_cli_param_in_unit(q, q->lo, unit, sizeof unit));
  snprintf(hi, sizeof hi, "%.6g", sw_cli_param_in_unit(q, q->hi, unit, sizeof unit));
  if (unit[0]) snprintf(buf, len, "in (%s %s, %s %s)", lo, unit, hi, unit);
  else snprintf(buf, len, "in (%s, %s)", lo, hi);
  return buf;
}

/* The model's objective, for --help and --info. */
static void print_objective(const swProgram *p) {
  printf("objective: %s  # %s\n", p->objective_text, p->objective_where);
  printf("  shown in %s; %d penalt%s; score = %s\n",
         p->objective_unit[0] ? p->objective_unit : "no unit (a plain number)", p->npenalty,
         p->npenalty == 1 ? "y" : "ies",
         p->sense > 0 ? "objective - penalties" : "-(objective + penalties)");
}

/* ---- --help ---- */

void sw_cli_print_help(const swCli *c, const char *default_out) {
  const swProgram *p = c->p;
  char buf[128];
  printf("usage: %s [options]\n\n", c->prog);
  printf("Simulates the sinew model '%s' and writes its output as HDF5.\n\n", p->name);
  printf("options:\n");
  for (size_t i = 0; i < sw_cli_noptions; i++) {
    const swOption *o = &sw_cli_options[i];
    char head[64];
    snprintf(head, sizeof head, "%s%s%s", o->name, o->arg ? " " : "", o->arg ? o->arg : "");
    const char *def = NULL;
    switch (o->id) {
    case OPT_OUT: def = default_out; break;
    case OPT_DURATION: def = sw_cli_format_time(buf, sizeof buf, p->duration); break;
    case OPT_DT:
      def = p->dt > 0 ? sw_cli_format_time(buf, sizeof buf, p->dt) : "half the stable estimate";
      break;
    case OPT_EVERY: def = p->every > 0 ? sw_cli_format_time(buf, sizeof buf, p->every) : "every step";
      break;
    case OPT_THREADS: def = "1; the results are the same for any N"; break;
    case OPT_INTEGRATOR: def = "the model's"; break;
    case OPT_RTOL: def = "1e-9"; break;
    case OPT_TOLERANCE: def = "none: one comparison, differences beyond 1% reported"; break;
    case OPT_BUDGET: def = "1000"; break;
    case OPT_POPSIZE: def = "4 + floor(3 ln n), n the ranged params"; break;
    case OPT_SIGMA: def = "0.25"; break;
    case OPT_RESTARTS: def = "0"; break;
    case OPT_START: def = "each param's value: its default, or --set"; break;
    case OPT_SEED: def = "1"; break;
    case OPT_STUDY: def = buf, snprintf(buf, sizeof buf, "%s_study.h5", p->name); break;
    case OPT_REPLAY: def = "best"; break;
    case OPT_EVAL_TIMEOUT: def = "20 times the slowest evaluation, at least 60 s"; break;
    default: break;
    }
    printf("  %-18s %s", head, o->help);
    if (def) printf(" (default: %s)", def);
    printf("\n");
  }
  printf("An option takes its value as '--dt 50ns' or '--dt=50ns'. Times take a unit\n"
         "(s, ms, us, ns, min, h); a number without one is in seconds.\n\n");

  if (p->nparam) {
    int width = 4, what_width = 0;
    char what[64];
    for (int i = 0; i < p->nparam; i++) {
      int n = (int)strlen(p->param[i].name);
      int w = (int)strlen(sw_dim_describe(what, sizeof what, p->param[i].dim));
      if (n > width) width = n;
      if (w > what_width) what_width = w;
    }
    int range_width = 0;
    for (int i = 0; i < p->nparam; i++) {
      int n = (int)strlen(format_range(buf, sizeof buf, &p->param[i]));
      if (n > range_width) range_width = n;
    }
    printf("params (--set NAME=VALUE, VALUE in the dimension shown%s):\n",
           range_width ? "; a study varies those with a range" : "");
    for (int i = 0; i < p->nparam; i++) {
      const swParam *q = &p->param[i];
      char value[96], range[200];
      format_param(value, sizeof value, q, q->value);
      format_range(range, sizeof range, q);
      sw_dim_describe(what, sizeof what, q->dim);
      printf("  %-*s = %-12s ", width, q->name, value);
      if (range_width) printf("%-*s ", range_width, range);
      if (q->where && q->where[0]) printf("%-*s  %s\n", what_width, what, q->where);
      else printf("%s\n", what);
    }
    printf("\n");
  } else {
    printf("The model has no params.\n\n");
  }
  if (p->sense) {
    print_objective(p);
    printf("\n");
  }
  printf("exit status: 0 ok, 1 model error, 2 usage error, 3 the simulation became\n"
         "unstable, 4 I/O error, 5 an expect of the model (or --compare) failed, 130\n"
         "interrupted (the file holds every frame written).\n");
  fflush(stdout);
}

/* ---- --info ---- */

/* Approximate bytes of the model's and the state's arrays (sinew.h lists
 * them with their shapes: per slot, joint, filament, body).  A per-slot
 * array is planar (sinew.h, "Layout"): one plane of m->stride doubles per
 * scalar, three per vector, nine per frame, whatever the slot holds. */
static double model_bytes(const swModel *m) {
  double b = sizeof *m;
  b += (double)m->nrod * (sizeof(char *) + 4 * sizeof(int) + sizeof(double) + sizeof(swDampingKind));
  for (int r = 0; r < m->nrod; r++) b += m->rod_name[r] ? (double)strlen(m->rod_name[r]) + 1 : 0;
  /* planes of the node (8), element (36) and Voronoi (7) arrays */
  b += sizeof(double) * ((8.0 + 36.0 + 7.0) * m->stride);
  b += (double)m->nload * sizeof(swLoadDesc) + (double)m->nbc * sizeof(swBCDesc);
  /* per joint: description, name, 4 indices, axes (2x3), rest rotation (9),
   * initial angle and stable dt */
  b += (double)m->njoint * (sizeof(swJointDesc) + sizeof(char *) + 4 * sizeof(int) +
                            17 * sizeof(double));
  /* per muscle: name, first filament, activation signal; per filament: 2
   * ints and 10 doubles */
  b += (double)m->nmuscle * (sizeof(char *) + sizeof(int) + sizeof(swSignal));
  b += (double)m->nfil * (2 * sizeof(int) + 10 * sizeof(double));
  /* rigid rods: per rod its body, per body 4 indices and 16 numbers, per
   * node of a body p (3), per element B (9) */
  b += (double)m->nrod * sizeof(int) + (double)m->nrigid * (4 * sizeof(int) + 16 * sizeof(double));
  for (int k = 0; k < m->nrigid; k++)
    b += sizeof(double) * (3.0 * (m->rod_nelem[m->rigid_rod[k]] + 1) + 9.0 * m->rod_nelem[m->rigid_rod[k]]);
  /* torque waves: per node of each wave's rod s, beta and 2 phase terms */
  if (m->nwave) b += 4.0 * sizeof(double) * m->wave_node_adr[m->nwave];
  return b;
}

static double data_bytes(const swModel *m) {
  /* planes of the node (12), element (26) and Voronoi (7) arrays */
  return sizeof(swData) + sizeof(double) * ((12.0 + 26.0 + 7.0) * m->stride +
                                            4.0 * m->njoint + 4.0 * m->nfil + 21.0 * m->nrigid) +
         (double)m->nprobe * (4.0 * SW_PROBE_RING * sizeof(double) + 2 * sizeof(int));
}

/* Frames a run of nsteps steps writes (run.c: step 0, every k steps, the last). */
static long frame_count(long nsteps, double every, double dt) {
  const double k_steps = every > 0 ? round(every / dt) : 1;
  long k = k_steps > (double)nsteps ? nsteps + 1 : (long)k_steps;
  if (k < 1) k = 1;
  return 1 + nsteps / k + (nsteps % k != 0);
}

/* The rods an environment acts on: "all rods" or "rods a, b". */
static const char *rod_list(char *buf, size_t len, const swModel *m, int nrods, const int *rods) {
  if (nrods == m->nrod) return "all rods";
  if (nrods > 8) { /* a long list: its count, its first and its last */
    snprintf(buf, len, "%d rods, %s ... %s", nrods, m->rod_name[rods[0]], m->rod_name[rods[nrods - 1]]);
    return buf;
  }
  size_t used = (size_t)snprintf(buf, len, "rod%s", nrods == 1 ? "" : "s");
  for (int k = 0; k < nrods && used < len; k++)
    used += (size_t)snprintf(buf + used, len - used, "%s %s", k ? "," : "", m->rod_name[rods[k]]);
  return buf;
}

/* Grounds, fluids, contacts, torque waves and probes, one line each. */
static void print_environments(const swModel *m) {
  char a[256], b[64];
  printf("environments: %d grounds, %d fluids, %d contacts, %d torque waves, %d probes",
         m->nground, m->nfluid, m->ncontact, m->nwave, m->nprobe);
  if (m->nobstacle) printf(", %d obstacles", m->nobstacle);
  printf("\n");
  static const char *const shapes[] = {"sphere", "capsule", "cylinder", "box", "ellipsoid"};
  for (int k = 0; k < m->nobstacle; k++) {
    const swObstacleDesc *o = &m->obstacle[k];
    printf("  obstacle %s: %s at (%g, %g, %g) m, stiffness %g N/m, damping %g kg/s, ", o->name,
           shapes[o->shape], o->centre[0], o->centre[1], o->centre[2], o->stiffness, o->damping);
    if (o->static_friction > 0)
      printf("friction %g static, %g kinetic, tangential stiffness %g N/m, ", o->static_friction,
             o->kinetic_friction, o->tangential_stiffness > 0 ? o->tangential_stiffness : o->stiffness);
    if (o->carrier_rod >= 0)
      printf("carried by %s node %d, ", m->rod_name[o->carrier_rod],
             o->carrier_node < 0 ? m->rod_nelem[o->carrier_rod] : o->carrier_node);
    else printf("fixed, ");
    printf("%s\n", rod_list(a, sizeof a, m, o->nrods, o->rods));
  }
  for (int k = 0; k < m->nground; k++) {
    const swGroundDesc *g = &m->ground[k];
    printf("  ground %s: %s, stiffness %g N/m, damping %g kg/s, kinetic friction %g/%g/%g "
           "(forward/backward/sideways), static %g/%g/%g, %s\n", g->name,
           g->height ? "terrain" : "plane", g->stiffness, g->damping, g->mu_kinetic[0],
           g->mu_kinetic[1], g->mu_kinetic[2], g->mu_static[0], g->mu_static[1], g->mu_static[2],
           rod_list(a, sizeof a, m, g->nrods, g->rods));
  }
  for (int k = 0; k < m->nfluid; k++) {
    const swFluidDesc *f = &m->fluid[k];
    if (f->model == SW_FLUID_STOKES)
      printf("  fluid %s: Stokes drag, viscosity %g Pa s", f->name, f->viscosity);
    else
      printf("  fluid %s: quadratic drag, density %g kg/m^3, C_d %g", f->name, f->density,
             f->drag_coefficient);
    printf("%s, %s\n", f->buoyancy ? ", buoyancy" : "", rod_list(a, sizeof a, m, f->nrods, f->rods));
    swArea area;
    if (sw_rods_area(m, f->nrods, f->rods, &area))
      printf("    area of its rods at rest: planform %.6g m^2 (+- %.2g; the outline on their mean "
             "plane, normal (%.3f, %.3f, %.3f), overlaps once, on %s cells), silhouettes "
             "%.6g m^2 (the sum of 2 r l)\n", area.planform, area.planform_error, area.normal[0],
             area.normal[1], area.normal[2], format_length(b, sizeof b, area.cell),
             area.silhouette);
  }
  for (int k = 0; k < m->ncontact; k++) {
    const swContactDesc *c = &m->contact[k];
    printf("  contact %s: stiffness %g N/m, damping %g kg/s%s, ", c->name, c->stiffness, c->damping,
           c->self ? ", self-contact" : "");
    if (c->static_friction > 0)
      printf("friction %g static, %g kinetic, tangential stiffness %g N/m, ", c->static_friction,
             c->kinetic_friction, c->tangential_stiffness > 0 ? c->tangential_stiffness : c->stiffness);
    printf("%s\n", rod_list(a, sizeof a, m, c->nrods, c->rods));
  }
  for (int k = 0; k < m->nwave; k++) {
    const swWaveDesc *w = &m->wave[k];
    double peak = 0;
    for (int i = m->wave_node_adr[k]; i < m->wave_node_adr[k + 1]; i++)
      if (fabs(m->wave_beta[i]) > fabs(peak)) peak = m->wave_beta[i];
    printf("  torque wave %s: rod %s, %d coefficients (peak beta %g N m), wavelength %g m, "
           "period %g s, about (%g, %g, %g), from the rod's %s\n", w->name, m->rod_name[w->rod],
           w->ncoef, peak, w->wavelength, w->period, w->direction[0], w->direction[1],
           w->direction[2], w->reverse ? "end" : "start");
  }
  for (int k = 0; k < m->nprobe; k++) {
    const swProbeDesc *p = &m->probe[k];
    if (p->kind == SW_PROBE_NODE)
      printf("  probe %s: node_position, node %d of rod %s\n", p->name, p->node,
             m->rod_name[p->rod]);
    else if (p->kind == SW_PROBE_MEAN_VELOCITY)
      printf("  probe %s: mean_velocity over %s (%s)\n", p->name,
             p->window > 0 ? sw_cli_format_time(b, sizeof b, p->window) : "the frame interval",
             rod_list(a, sizeof a, m, p->nrods, p->rods));
    else
      printf("  probe %s: %s (%s)\n", p->name, sw_probe_kind_name(p->kind),
             rod_list(a, sizeof a, m, p->nrods, p->rods));
  }
}

/* What the scheme treats apart from the explicit kick: rods held rigid and
 * (imex) the implicit terms, the filaments' Hill damping and the joints
 * between rigid bodies; filaments a scene could make implicit but whose
 * scheme keeps explicit are named with the step they cost. */
static void print_stiff_parts(const swModel *m) {
  char a[64];
  int nrigid = 0, nimplicit = 0;
  for (int r = 0; r < m->nrod; r++) nrigid += m->nrigid && m->rod_rigid[r] >= 0;
  for (int f = 0; f < m->nfil; f++) nimplicit += (m->fil_implicit[f] & SW_FIL_IMPLICIT) != 0;
  if (nrigid) {
    printf("  held rigid (one body each, no elastic waves): %d rod%s:", nrigid, nrigid == 1 ? "" : "s");
    for (int r = 0, k = 0; r < m->nrod && k < 8; r++)
      if (m->rod_rigid[r] >= 0) printf("%s %s", k++ ? "," : "", m->rod_name[r]);
    printf("%s\n", nrigid > 8 ? ", ..." : "");
  }
  if (nimplicit) {
    int nring = 0; /* via rings taken with their filament (via_implicit.c) */
    for (int f = 0; m->nring && f < m->nfil; f++)
      for (int q = m->fil_ring_adr[f]; q < m->fil_ring_adr[f + 1]; q++) nring += sw_via_ring_implicit(m, f, q);
    printf("  linearly implicit: the Hill damping of %d of %d muscle filaments", nimplicit, m->nfil);
    if (m->nring) printf(", %d of %d via rings (the bone's side explicit)", nring, m->nring);
    printf("\n");
  }
  int nrod_implicit = 0;
  for (int r = 0; r < m->nrod; r++) nrod_implicit += m->rod_implicit[r];
  if (nrod_implicit) {
    printf("  %s: the elasticity and linear damping of %d rod%s:",
           m->nimplicit ? "trapezoidal (implicit)" : "explicit, implicit only under imex",
           nrod_implicit, nrod_implicit == 1 ? "" : "s");
    for (int r = 0, k = 0; r < m->nrod && k < 8; r++)
      if (m->rod_implicit[r]) printf("%s %s", k++ ? "," : "", m->rod_name[r]);
    printf("%s\n", nrod_implicit > 8 ? ", ..." : "");
  }
  int njimplicit = 0;
  for (int j = 0; j < m->njoint; j++) njimplicit += m->joint_implicit[j];
  if (njimplicit) {
    int nbody = 0, nrods = 0, nfil = 0;
    for (int k = 0; k < m->nrigid_block; k++) {
      nbody += m->rigid_block_body[k] >= 0;
      nrods += m->rigid_block_rod[k] >= 0;
    }
    for (int f = 0; f < m->nfil; f++) nfil += m->fil_system[f];
    printf("  trapezoidal (implicit): %d of %d joints, those on a rigid body or an implicit rod to "
           "a body, an implicit rod, space, a clamped node or a free node of an elastic rod (",
           njimplicit, m->njoint);
    const char *sep = "";
    if (nbody) printf("%d bod%s", nbody, nbody == 1 ? "y" : "ies"), sep = ", ";
    if (nrods)
      printf("%s%d implicit rod%s through %d node%s", sep, nrods, nrods == 1 ? "" : "s",
             m->nrigid_port, m->nrigid_port == 1 ? "" : "s"), sep = ", ";
    if (m->nrigid_attach)
      printf("%s%d rod node%s", sep, m->nrigid_attach, m->nrigid_attach == 1 ? "" : "s");
    if (nfil) printf(", the Hill damping of %d filament%s between their ends", nfil, nfil == 1 ? "" : "s");
    int nband = 0; /* groups of one implicit rod and leaves: solved in its band (joint_ports.c) */
    int nmember = 0; /* groups whose rod members take lone leaves into their bands */
    for (int g = 0; g < m->nrigid_group; g++)
      nband += m->rigid_group_band[g] == 1, nmember += m->rigid_group_band[g] == 2;
    printf(" in %d independent group%s", m->nrigid_group, m->nrigid_group == 1 ? "" : "s");
    if (nband) printf(", %d of them an implicit rod and its leaves, solved in its band", nband);
    if (nmember) printf(", %d with leaves eliminated into their rods' bands", nmember);
    printf(")\n");
  }
  int nhill = 0;   /* filaments under the Hill law (not a prescribed force) */
  for (int i = 0; i < m->nmuscle; i++)
    if (!m->muscle_prescribed[i]) nhill += m->muscle_fil_adr[i + 1] - m->muscle_fil_adr[i];
  if (nhill > nimplicit) {
    double worst = INFINITY;
    for (int f = 0; f < m->nfil; f++)
      if (!(m->fil_implicit[f] & SW_FIL_IMPLICIT))
        worst = fmin(worst, 0.95 * sw_muscle_ops(m)->stable_dt_filament(m, f));
    printf("  explicit: the Hill damping of %d muscle filament%s (alone it limits dt to %s%s)\n",
           nhill - nimplicit, nhill - nimplicit == 1 ? "" : "s", sw_cli_format_time(a, sizeof a, worst),
           m->integrator == SW_IMEX ? "; a prescribed velocity or analytic damping keeps it explicit"
                                    : "; integrator = imex makes it implicit");
  }
}

/* The rods' constitutive law (rod.c): Gazzola's unless the spec asks for
 * the variational one (the language's default for muscles, and whatever a
 * material, rod or muscle says); the elastic ones of each law are named
 * (rigid rods have none). */
static void print_law(const swModel *m) {
  int nelastic = 0;
  for (int r = 0; r < m->nrod; r++) nelastic += !(m->nrigid && m->rod_rigid[r] >= 0);
  if (!m->nvariational) {
    printf("constitutive law: Gazzola et al. 2018 (n = S^ s / e, c = B^ k / eps^3), all %d elastic rod%s\n",
           nelastic, nelastic == 1 ? "" : "s");
    return;
  }
  printf("constitutive law: variational (loads the gradient of the elastic energy) on %d of %d "
         "elastic rod%s:", m->nvariational, nelastic, nelastic == 1 ? "" : "s");
  for (int r = 0, k = 0; r < m->nrod && k < 8; r++)
    if (m->rod_law[r] == SW_LAW_VARIATIONAL && !(m->nrigid && m->rod_rigid[r] >= 0))
      printf("%s %s", k++ ? "," : "", m->rod_name[r]);
  printf("%s%s\n", m->nvariational > 8 ? ", ..." : "",
         m->nvariational < nelastic ? "; Gazzola et al. 2018 on the others" : "");
}

/* The part whose bound is the stable estimate: a rod, a joint, a kinematic
 * joint's tie, or the environments. */
static void print_step_limit(const swModel *m, double stable) {
  char a[64];
  if (!isfinite(stable)) return;
  for (int r = 0; r < m->nrod; r++)
    if (m->rod_wave_dt[r] == stable) {
      printf("  set by rod %s (%s)\n", m->rod_name[r], sw_cli_format_time(a, sizeof a, stable));
      return;
    }
  for (int j = 0; j < m->njoint; j++)
    if (m->joint_wave_dt[j] == stable) {
      printf("  set by joint %s (%s)\n", m->joint_name[j], sw_cli_format_time(a, sizeof a, stable));
      return;
    }
  for (int j = 0; j < m->nkinematic; j++)
    if (m->kinematic_dt[j] == stable) {
      printf("  set by kinematic joint %s, its tie's spring on the follower's first node (%s)\n",
             m->kinematic_name[j], sw_cli_format_time(a, sizeof a, stable));
      return;
    }
  printf("  set by the environments (%s)\n", sw_cli_format_time(a, sizeof a, stable));
}

/* ---- loops: the rods their passes make, one line a pattern ---- */

/* name with every [index] written [*]: "feather[3].barb[12]" ->
 * "feather[*].barb[*]"; 0 when the name has no index */
static int loop_pattern(const char *name, char *out, size_t len) {
  size_t o = 0;
  int indexed = 0;
  for (const char *c = name; *c && o + 1 < len; c++) {
    out[o++] = *c;
    if (*c == '[') {
      const char *close = strchr(c, ']');
      if (close && o + 2 < len) {
        out[o++] = '*';
        c = close - 1;
        indexed = 1;
      }
    }
  }
  out[o] = '\0';
  return indexed;
}

/* Every name's pattern (NULL: no index), made once: the grouping below
 * compares them pairwise.  NULL when out of memory (then nothing is grouped). */
static char **loop_patterns(char *const *names, int n) {
  char **pat = calloc((size_t)(n ? n : 1), sizeof *pat);
  for (int i = 0; pat && i < n; i++) {
    char buf[256];
    if (loop_pattern(names[i], buf, sizeof buf) && !(pat[i] = strdup(buf))) {
      for (int k = 0; k < i; k++) free(pat[k]);
      free(pat);
      return NULL;
    }
  }
  return pat;
}

static void free_patterns(char **pat, int n) {
  for (int i = 0; pat && i < n; i++) free(pat[i]);
  free(pat);
}

/* Name i of n with patterns pat: 1 when it is alone (no index, or the only
 * one of its pattern), the size of its pattern's group when it is the
 * group's first, -1 when an earlier name of the group stands for it. */
static int loop_group(char *const *pat, int n, int i) {
  if (!pat || !pat[i]) return 1;
  int count = 0;
  for (int k = 0; k < n; k++) {
    if (!pat[k] || strcmp(pat[k], pat[i])) continue;
    if (k < i) return -1;
    count++;
  }
  return count;
}

/* Two rods of one material: the same name and the same constants. */
static int same_material(const swRodInfo *a, const swRodInfo *b) {
  const char *na = a->material ? a->material : "", *nb = b->material ? b->material : "";
  return !strcmp(na, nb) && a->youngs == b->youngs && a->shear_modulus == b->shear_modulus &&
         a->density == b->density;
}

/* Rod r at rest: its length and mass. */
static void rod_rest(const swModel *m, int r, double *length, double *mass) {
  const int n = m->rod_nelem[r], ea = m->elem_adr[r], na = m->node_adr[r];
  *length = *mass = 0;
  for (int i = 0; i < n; i++) *length += m->rest_len[ea + i];
  for (int i = 0; i <= n; i++) *mass += m->mass[na + i];
}

/* The rods' materials, one line for each distinct (name, E, G, density):
 * the moduli and density the model was given (G before any hardening, the
 * density at t = 0), and the rods that have it.  Grouped by value, not by
 * rod, so that a scene of thousands of rods prints a few lines; what a
 * reference's table gives (tests/lang/test_tables.sh reads them). */
static void print_materials(const swModel *m) {
  if (!m->rod_info) return;
  int nmat = 0;
  for (int r = 0; r < m->nrod; r++) {
    int seen = 0;
    for (int q = 0; q < r && !seen; q++) seen = same_material(&m->rod_info[q], &m->rod_info[r]);
    nmat += !seen;
  }
  printf("materials: %d\n", nmat);
  for (int r = 0; r < m->nrod; r++) {
    const swRodInfo *info = &m->rod_info[r];
    int seen = 0, count = 0, last = r;
    for (int q = 0; q < r && !seen; q++) seen = same_material(&m->rod_info[q], info);
    if (seen) continue;
    for (int q = r; q < m->nrod; q++)
      if (same_material(&m->rod_info[q], info)) count++, last = q;
    printf("  %s: E %.6g Pa, G %.6g Pa, density %.6g kg/m^3; ",
           info->material ? info->material : "(unnamed)", info->youngs, info->shear_modulus,
           info->density);
    if (count == 1) printf("rod %s\n", m->rod_name[r]);
    else if (count == 2) printf("rods %s, %s\n", m->rod_name[r], m->rod_name[last]);
    else printf("%d rods, %s ... %s\n", count, m->rod_name[r], m->rod_name[last]);
  }
}

/* The end of a rod's line: its hardened G (model.c: shear_hardening
 * multiplies G in S11 and S22, twist_hardening in B33), when hardened. */
static void print_hardening(const swModel *m, int r) {
  const double hs = m->rod_info[r].shear_hardening, ht = m->rod_info[r].twist_hardening;
  if (hs != 1) printf(", shear G x%g = %.4g Pa", hs, hs * m->rod_info[r].shear_modulus);
  if (ht != 1) printf(", twist G x%g = %.4g Pa", ht, ht * m->rod_info[r].shear_modulus);
  putchar('\n');
}

/* One line for the rods of pattern pat[first]: their count and the ranges
 * of what a rod line shows. */
static void print_rod_group(const swModel *m, char *const *pat, int first, int members) {
  char a[64], b[64];
  double lmin = INFINITY, lmax = 0, rmin = INFINITY, rmax = 0, mmin = INFINITY, mmax = 0;
  double dmin = INFINITY, dmax = 0;
  int emin = 1 << 30, emax = 0;
  for (int r = first; r < m->nrod; r++) {
    if (!pat[r] || strcmp(pat[r], pat[first])) continue;
    const int n = m->rod_nelem[r], ea = m->elem_adr[r];
    double length, mass;
    rod_rest(m, r, &length, &mass);
    for (int i = 0; i < n; i++) {
      rmin = fmin(rmin, m->radius[ea + i]);
      rmax = fmax(rmax, m->radius[ea + i]);
    }
    lmin = fmin(lmin, length); lmax = fmax(lmax, length);
    mmin = fmin(mmin, mass); mmax = fmax(mmax, mass);
    dmin = fmin(dmin, m->rod_wave_dt[r]); dmax = fmax(dmax, m->rod_wave_dt[r]);
    emin = n < emin ? n : emin; emax = n > emax ? n : emax;
  }
  const swDampingKind damping = m->rod_damping[first]; /* the first member's */
  printf("  %s: %d rods, %d", pat[first], members, emin);
  if (emax != emin) printf(" to %d", emax);
  printf(" elements, length %.4g to %.4g m, radius %.4g", lmin, lmax, rmin * 1e3);
  if (rmax != rmin) printf(" to %.4g", rmax * 1e3);
  printf(" mm, mass %.4g to %.4g kg, stable dt %s to %s%s", mmin, mmax,
         isinf(dmin) ? "none" : sw_cli_format_time(a, sizeof a, dmin),
         isinf(dmax) ? "none" : sw_cli_format_time(b, sizeof b, dmax),
         damping == SW_DAMP_ANALYTIC ? ", analytic damping" : damping == SW_DAMP_LINEAR ? ", linear damping" : "");
  print_hardening(m, first);   /* the first member's */
}

void sw_cli_print_info(const swCli *c, const swModel *m, double stable, const char *dt_source,
                              const char *out) {
  const swProgram *p = c->p;
  char a[64], b[64], e[64];
  printf("model: %s\n", p->name ? p->name : "(unnamed)");
  printf("  sha256: %s\n", p->sha256 && p->sha256[0] ? p->sha256 : "(none)");
  printf("rods: %d (%d elements, %d nodes)\n", m->nrod, m->nelem, m->nnode);
  char **rod_pat = loop_patterns(m->rod_name, m->nrod);
  for (int r = 0; r < m->nrod; r++) {
    const int members = loop_group(rod_pat, m->nrod, r);
    if (members < 0) continue; /* printed with its group */
    if (members > 1) {
      print_rod_group(m, rod_pat, r, members);
      continue;
    }
    int n = m->rod_nelem[r], ea = m->elem_adr[r], na = m->node_adr[r];
    double length, mass;
    rod_rest(m, r, &length, &mass);
    double r0 = m->radius[ea], r1 = m->radius[ea + n - 1];
    printf("  %s: %d elements, length %.6g m, radius %.4g mm", m->rod_name[r], n, length,
           r0 * 1e3);
    if (r1 != r0) printf(" to %.4g mm", r1 * 1e3);
    const int sk = m->nswell ? sw_swell_of_rod(m, r) : -1;
    if (sk >= 0) /* geometry that changes in time (swell.c) */
      printf(" at t = 0, x%.4g to x%.4g in time (mass %s%s)", m->swell_range[2 * sk],
             m->swell_range[2 * sk + 1], m->swell_flags[sk] & SW_SWELL_MASS_GROWS ? "grows" : "conserved",
             m->swell_flags[sk] & SW_SWELL_TWIST_RADIUS ? ", rest twist ~ r0/r" : "");
    printf(", mass %.6g kg%s, stable dt %s%s%s%s", mass, sk >= 0 ? " at t = 0" : "",
           isinf(m->rod_wave_dt[r]) ? "none" : sw_cli_format_time(a, sizeof a, m->rod_wave_dt[r]),
           m->rod_damping[r] == SW_DAMP_ANALYTIC ? ", analytic damping"
           : m->rod_damping[r] == SW_DAMP_LINEAR ? ", linear damping" : "",
           m->nrigid && m->rod_rigid[r] >= 0 ? ", rigid" : m->nimplicit && m->rod_implicit[r] ? ", implicit" : "",
           m->weight && m->weight[na] == 0 && m->mass[na] > 0 ? ", weightless (no gravity)" : "");
    print_hardening(m, r);
  }
  free_patterns(rod_pat, m->nrod);
  print_materials(m);
  printf("joints: %d\n", m->njoint);
  for (int j = 0; j < m->njoint; j++) {
    const char *name = m->joint_name && m->joint_name[j] ? m->joint_name[j]
                       : m->joint && m->joint[j].name ? m->joint[j].name : "(unnamed)";
    printf("  %s: %s", name, m->joint ? sw_joint_kind_name(m->joint[j].kind) : "joint");
    if (m->joint) printf(", stiffness %g N/m", m->joint[j].stiffness);
    printf("\n");
  }
  if (m->nkinematic) {   /* kinematic.c: frames imposed, no couple back */
    printf("kinematic joints: %d (a follower element turns with its leader's)\n", m->nkinematic);
    char **kin_pat = loop_patterns(m->kinematic_name, m->nkinematic);
    for (int j = 0; j < m->nkinematic; j++) {
      const swKinematicDesc *k = &m->kinematic[j];
      const int members = loop_group(kin_pat, m->nkinematic, j);
      if (members < 0) continue; /* printed with its group */
      if (members > 1) { /* a loop's joints: their count and patterns */
        char fpat[256], lpat[256];
        double kmin = INFINITY, kmax = 0;
        for (int i = j; i < m->nkinematic; i++)
          if (kin_pat[i] && !strcmp(kin_pat[i], kin_pat[j])) {
            kmin = fmin(kmin, m->kinematic[i].stiffness);
            kmax = fmax(kmax, m->kinematic[i].stiffness);
          }
        loop_pattern(m->rod_name[k->follower_rod], fpat, sizeof fpat);
        loop_pattern(m->rod_name[k->leader_rod], lpat, sizeof lpat);
        printf("  %s: %d joints, %s follows %s, spring %g", kin_pat[j], members, fpat, lpat, kmin);
        if (kmax != kmin) printf(" to %g", kmax);
        printf(" N/m%s\n", k->reaction_rod >= 0 ? ", reactions sent on with weights" : "");
        continue;
      }
      printf("  %s: %s follows %s, spring %g N/m", k->name, m->rod_name[k->follower_rod],
             m->rod_name[k->leader_rod], k->stiffness);
      if (k->reaction_rod >= 0)
        printf(", reaction x %g to %s", k->reaction_weight, m->rod_name[k->reaction_rod]);
      printf("\n");
    }
    free_patterns(kin_pat, m->nkinematic);
  }
  printf("muscles: %d\n", m->nmuscle);
  for (int i = 0; i < m->nmuscle; i++) {
    const int f0 = m->muscle_fil_adr[i], f1 = m->muscle_fil_adr[i + 1];
    double fmax = 0, area = 0, fibres = 0;
    int passive = 0;
    for (int f = f0; f < f1; f++) {
      fmax += m->fil_fmax[f];
      area += m->fil_area[f];
      fibres += m->fil_fibres[f];
      passive += m->fil_passive[f];
    }
    if (m->muscle_prescribed[i])   /* muscle.c: F(t) shared by cross-section */
      printf("  %s: %d filaments (%.4g to %.4g mm^2, %.0f fibres), a prescribed force of at "
             "most %.6g N (no Hill law), l0 %.6g m", m->muscle_name[i], f1 - f0,
             m->fil_area[f0] * 1e6, m->fil_area[f1 - 1] * 1e6, fibres, fmax, m->fil_l0[f0]);
    else
      printf("  %s: %d filaments (%.4g to %.4g mm^2, %.0f fibres), area %.6g mm^2, F_max %.6g N, "
             "l0 %.6g m, twitch %s to %s, Hill a %.4g F_qs, v_max %.4g l0/s", m->muscle_name[i],
             f1 - f0, m->fil_area[f0] * 1e6, m->fil_area[f1 - 1] * 1e6, fibres, area * 1e6, fmax,
             m->fil_l0[f0], sw_cli_format_time(a, sizeof a, m->fil_tau[f0]),
             sw_cli_format_time(b, sizeof b, m->fil_tau[f1 - 1]), m->fil_hill_a[f0],
             m->fil_v_max[f0]);
    if (passive) printf(", %d passive", passive);
    printf("\n");
  }
  print_environments(m);
  int nforce = 0, ntorque = 0, nclamp = 0, nvel = 0, nomega = 0, nslide = 0, nuntil = 0;
  for (int k = 0; k < m->nload; k++) {
    if (m->load[k].kind == SW_LOAD_TORQUE) ntorque++;
    else nforce++;
  }
  for (int k = 0; k < m->nbc; k++)
    switch (m->bc[k].kind) {
    case SW_BC_CLAMP: nclamp++; break;
    case SW_BC_VELOCITY: nvel++; break;
    case SW_BC_OMEGA: nomega++; break;
    case SW_BC_SLIDE_LINE:
    case SW_BC_SLIDE_PLANE:
    case SW_BC_SLEEVE: nslide++; break;
    }
  for (int k = 0; k < m->nbc; k++) nuntil += m->bc[k].until > 0;
  printf("loads: %d (%d point force%s, %d point couple%s)\n", m->nload, nforce,
         nforce == 1 ? "" : "s", ntorque, ntorque == 1 ? "" : "s");
  printf("boundary conditions: %d (%d clamped end%s, %d prescribed velocit%s, "
         "%d prescribed angular velocit%s", m->nbc, nclamp, nclamp == 1 ? "" : "s", nvel,
         nvel == 1 ? "y" : "ies", nomega, nomega == 1 ? "y" : "ies");
  if (nslide) printf(", %d sliding end%s", nslide, nslide == 1 ? "" : "s");
  if (nuntil) printf("; %d released at a time", nuntil);
  printf(")\n");
  if (m->has_gravity)
    printf("gravity: (%g, %g, %g) m/s^2%s\n", m->gravity[0], m->gravity[1], m->gravity[2],
           m->gravity_signal.kind != SW_SIG_CONST || m->gravity_signal.a != 1.0
               ? " times a signal of time" : "");
  else printf("gravity: none\n");
  printf("forces in use: elasticity (stretch, shear, bend, twist)%s%s%s%s%s%s%s%s%s%s%s\n",
         m->has_gravity ? ", gravity" : "", m->nload ? ", point loads" : "",
         m->nbc ? ", boundary conditions" : "", m->njoint ? ", joints" : "",
         m->nmuscle ? ", muscles" : "", m->nwave ? ", torque waves" : "",
         m->nground ? ", ground contact and friction" : "", m->nfluid ? ", fluid" : "",
         m->ncontact ? ", rod-rod contact" : "", m->nobstacle ? ", rigid obstacles" : "",
         m->has_damping ? ", damping" : "");
  print_law(m);
  printf("integrator: %s\n", m->integrator == SW_PEFRL ? "PEFRL"
                             : m->integrator == SW_IMEX ? "position Verlet, stiff terms linearly implicit (imex)"
                                                        : "position Verlet");
  print_stiff_parts(m);
  printf("dt: %s (%s; stable estimate %s)\n", sw_cli_format_time(a, sizeof a, m->dt), dt_source,
         isfinite(stable) ? sw_cli_format_time(b, sizeof b, stable) : "none: nothing in the scene bounds it");
  print_step_limit(m, stable);
  if (m->nimplicit) /* the tangent's dropped terms (rod_implicit.c) */
    printf("  note: the estimate leaves out the loads' own stiffness on implicit rods (bending\n"
           "  under load, compression), which can bound the step well below it: the arm of\n"
           "  examples/elbow_flexion.sinew with implicit bones and tendons holds 450 us of its\n"
           "  1.59 ms (docs/physics.md, \"Joints on implicit rods\"); check a step with --accuracy\n");
  long nsteps = 0;
  char why[256];
  sw_step_count(c->duration, m->dt, &nsteps, why, sizeof why); /* checked by build_model */
  long frames = frame_count(nsteps, c->every, m->dt);
  printf("duration: %s, %ld steps; a frame every %s: %ld frames\n",
         sw_cli_format_time(a, sizeof a, c->duration), nsteps,
         c->every > 0 ? sw_cli_format_time(b, sizeof b, c->every) : "step", frames);
  printf("output: %s (position%s%s, energy%s)\n", out, p->velocity ? ", velocity" : "",
         p->directors ? ", directors" : "", m->nmuscle ? ", muscles" : "");
  double mb = model_bytes(m), db = data_bytes(m);
  printf("memory: about %s (model %s, state %s)\n", format_bytes(a, sizeof a, mb + db),
         format_bytes(b, sizeof b, mb), format_bytes(e, sizeof e, db));
  printf("threads: %ld (%s; %d processor%s available; results do not depend on it)\n",
         sw_cli_threads_for(c, m), c->threads_auto ? "--threads auto: one per 8192 slots, rounded, up to the processors"
                            : c->threads_set ? "--threads" : "default",
         omp_get_num_procs(), omp_get_num_procs() == 1 ? "" : "s");
  if (p->nparam) {
    printf("params:\n");
    for (int i = 0; i < p->nparam; i++) {
      const swParam *q = &p->param[i];
      char range[200];
      printf("  %s = %s", q->name, format_param(a, sizeof a, q, c->P[i]));
      if (q->ranged) printf(" %s", format_range(range, sizeof range, q));
      if (c->overridden[i]) printf(" (--set; default %s)", format_param(b, sizeof b, q, q->value));
      printf("\n");
    }
  } else {
    printf("params: none\n");
  }
  if (p->sense) print_objective(p);
  fflush(stdout);
}
