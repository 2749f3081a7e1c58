/* gen_c.c — the C generator: one readable, deterministic C file per model.
 *
 * Design.  A plain walk over the checked scene (chibicc's way): the model
 * source as a string table, the param table, a build() function that fills
 * the runtime's swSpec one definition at a time, and a main() that hands
 * everything to the runtime's command line (sw_main).  Each block starts with
 * a #line directive and a comment quoting the model line it comes from, so
 * both a reader and a C compiler message lead back to the model.  Constants
 * are printed folded (shortest round-trip decimal); param-dependent values
 * are C expressions over P[i].  Nothing from the model reaches the C text
 * unescaped: strings go through c_string() (octal escapes for everything but
 * plain printable ASCII), comments through c_comment() (no "*" "/" can close
 * them), and identifiers only inside those.  No timestamps, no paths of the
 * machine, stable order: the same model gives the same bytes.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diag.h"
#include "gen.h"

/* A C string literal of text[0..len), escaped. */
static void c_string(FILE *out, const char *text, size_t len) {
  fputc('"', out);
  for (size_t i = 0; i < len; i++) {
    unsigned char c = (unsigned char)text[i];
    if (c == '"' || c == '\\') fprintf(out, "\\%c", c);
    else if (c == '\n') fputs("\\n", out);
    else if (c == '\t') fputs("\\t", out);
    else if (c == '?') fputs("\\?", out);          /* no trigraphs */
    else if (c >= 0x20 && c < 0x7f) fputc(c, out);
    else fprintf(out, "\\%03o", c);
  }
  fputc('"', out);
}

void gen_c_string(FILE *out, const char *text) { c_string(out, text, strlen(text)); }

/* Model text inside a C comment: printable ASCII only, and nothing that could
 * end or nest the comment or splice lines. */
void gen_c_comment(FILE *out, const char *text, size_t len) {
  for (size_t i = 0; i < len; i++) {
    unsigned char c = (unsigned char)text[i];
    if (c == '*' && i + 1 < len && text[i + 1] == '/') fputs("* ", out);
    else if (c == '/' && i + 1 < len && text[i + 1] == '*') fputs("/ ", out);
    else if (c == '\\' || c == '?') fputc(c == '\\' ? '|' : '.', out);
    else if (c == '\t') fputc(' ', out);
    else if (c >= 0x20 && c < 0x7f) fputc(c, out);
    else fputc('.', out);
  }
}

/* #line and a comment quoting the model line of loc. */
void gen_origin(FILE *out, swLoc loc, const char *indent) {
  const swSource *f = diag_file(loc.file);
  if (!f || loc.line < 1) return;
  const char *p = f->text, *end = f->text + f->len;
  for (int l = 1; l < loc.line && p < end; l++) {
    const char *nl = memchr(p, '\n', (size_t)(end - p));
    p = nl ? nl + 1 : end;
  }
  const char *nl = memchr(p, '\n', (size_t)(end - p));
  size_t len = (size_t)((nl ? nl : end) - p);
  while (len && (p[0] == ' ' || p[0] == '\t')) { p++; len--; }
  if (len > 100) len = 100;
  fprintf(out, "#line %d ", loc.line);
  gen_c_string(out, f->name);
  fprintf(out, "\n%s/* ", indent);
  gen_c_comment(out, p, len);
  fputs(" */\n", out);
}

void gen_assign_fields(FILE *out, swArena *a, const char *var, const swLowField *f, int n) {
  for (int i = 0; i < n; i++) {
    if (f[i].n == 1)
      fprintf(out, "    %s.%s = %s;\n", var, f[i].member, val_c(a, f[i].value, 0));
    else
      for (int k = 0; k < f[i].n; k++)
        fprintf(out, "    %s.%s[%d] = %s;\n", var, f[i].member, k, val_c(a, f[i].value, k));
  }
}

/* The assignments of a signal to the lvalue `var` (load.signal, ...). */
void gen_emit_signal(FILE *out, swArena *a, const char *var, const swSignalVal *sig) {
  if (!sig) {
    fprintf(out, "    %s = sw_signal_const(1.0);\n", var);
    return;
  }
  if (sig->kind == SW_SIG_FUNC) {   /* a signal NAME(t) of the model: gen_signal.c */
    swValue span = val_num(a, sig->func->span, DIM_TIME, sig->func->loc);
    fprintf(out, "    %s = sw_signal_func(signal_%d, signal_P, 0.0, %s);   /* ", var,
            sig->func->index, val_c(a, &span, 0));
    gen_c_comment(out, sig->func->name, strlen(sig->func->name));
    fputs(" */\n", out);
    if (sig->a.kind == VAL_NUM && !(val_is_const(&sig->a) && sig->a.v[0] == 1))
      fprintf(out, "    %s.a = %s;   /* its scale */\n", var, val_c(a, &sig->a, 0));
    return;
  }
  static const char *kinds[] = {"SW_SIG_CONST", "SW_SIG_RAMP", "SW_SIG_SINE", "SW_SIG_STEP",
                                "SW_SIG_TABLE", "SW_SIG_BSPLINE", "SW_SIG_FUNC"};
  fprintf(out, "    %s.kind = %s;\n", var, kinds[sig->kind]);
  swLowField f[GEN_MAX_FIELDS];
  gen_assign_fields(out, a, var, f, gen_signal_fields(sig, f));
  if (sig->kind == SW_SIG_TABLE) {
    fprintf(out, "    %s.npts = %d;\n", var, sig->npts);
    for (int k = 0; k < sig->npts; k++)
      fprintf(out, "    %s.times[%d] = %s; %s.values[%d] = %s;\n", var, k,
              val_c(a, &sig->times, k), var, k, val_c(a, &sig->values, k));
  }
  if (sig->kind == SW_SIG_BSPLINE) {
    fprintf(out, "    %s.npts = %d;   /* B-spline coefficients */\n", var, sig->npts);
    for (int k = 0; k < sig->npts; k++)
      fprintf(out, "    %s.values[%d] = %s;\n", var, k, val_c(a, &sig->values, k));
  }
}

static const char *rod_kind_word(swRodKind k) {
  static const char *w[] = {"rod", "bone", "tendon"};
  return w[k];
}

/* A node a joint or a muscle's end holds: the number, or the expression of
 * the params that moves it (ROD.at(param)), with its default's node beside. */
static void gen_node(FILE *out, int node, const char *node_c) {
  if (node_c) fprintf(out, "%s; /* %d at the defaults */", node_c, node);
  else fprintf(out, "%d;", node);
}

/* the rod's name as a comment after its index */
static void rod_comment(FILE *out, const swScene *sc, int rod) {
  fputs("   /* ", out);
  gen_c_comment(out, sc->rod[rod].name, strlen(sc->rod[rod].name));
  fputs(" */\n", out);
}

/* What the output's group says of a rod or a muscle: its kind, material
 * and model line (VAR.kind, VAR.material, VAR.where). */
static void emit_description(FILE *out, const char *var, const char *kind, const char *material,
                             swLoc loc) {
  char where[512];
  if (kind) {
    fprintf(out, "    %s.kind = ", var);
    gen_c_string(out, kind);
    fputs(";\n", out);
  }
  if (material) {
    fprintf(out, "    %s.material = ", var);
    gen_c_string(out, material);
    fputs(";\n", out);
  }
  fprintf(out, "    %s.where = ", var);
  gen_c_string(out, diag_name_where(loc, where, sizeof where));
  fputs(";\n", out);
}

static void emit_rod(FILE *out, swArena *a, const swSceneRod *r) {
  swLowField f[GEN_MAX_FIELDS];
  fputc('\n', out);
  gen_origin(out, r->loc, "  ");
  fputs("  {\n    swRodDesc rod;\n    sw_rod_desc_init(&rod);\n    rod.name = ", out);
  gen_c_string(out, r->name);
  fprintf(out, ";   /* %s, rod %d */\n", rod_kind_word(r->kind), r->id);
  fprintf(out, "    rod.nelem = %d;\n", r->nelem);
  static const char *damp[] = {"SW_DAMP_NONE", "SW_DAMP_LINEAR", "SW_DAMP_ANALYTIC"};
  fprintf(out, "    rod.damping = %s;\n", damp[r->damping]);
  if (r->rigid) fputs("    rod.rigid = 1;\n", out);
  if (r->implicit) fputs("    rod.implicit = 1;\n", out);
  if (r->weightless) fputs("    rod.weightless = 1;   /* gravity = false */\n", out);
  if (r->variational) fputs("    rod.law = SW_LAW_VARIATIONAL;\n", out);
  emit_description(out, "rod", rod_kind_word(r->kind), r->material, r->loc);
  gen_assign_fields(out, a, "rod", f, gen_rod_fields(r, f));
  if (r->swell_radius || r->swell_curvature || r->swell_twist || r->swell_twist_radius) {
    /* geometry that changes in time (runtime/engine/swell.c), opened by the
     * radius line when the radius is a signal */
    if (r->swell_radius) gen_origin(out, r->swell_loc, "    ");
    fputs("    rod.swell = 1;   /* geometry that changes in time */\n", out);
    if (r->swell_radius) {
      gen_emit_signal(out, a, "rod.swell_radius", r->swell_radius);
      fputs("    rod.radius_start = rod.radius_end = sw_signal_eval(&rod.swell_radius, 0.0);\n", out);
    } else {
      fputs("    rod.swell_radius = sw_signal_const(rod.radius_start);   /* constant */\n", out);
    }
    if (r->swell_curvature) gen_emit_signal(out, a, "rod.swell_curvature", r->swell_curvature);
    if (r->swell_twist) gen_emit_signal(out, a, "rod.swell_twist", r->swell_twist);
    if (r->swell_twist_radius)
      fputs("    rod.swell_twist_radius = 1;   /* rest twist ~ r(0) / r(t) */\n", out);
    if (r->swell_radius)
      fprintf(out, "    rod.swell_mass_grows = %d;   /* mass = %s */\n", r->swell_mass_grows,
              r->swell_mass_grows ? "grows" : "conserved");
  }
  fputs("    ok &= sw_spec_add_rod(s, &rod) >= 0;\n", out);
  gen_shape_build(out, a, r);
  fputs("  }\n", out);
}

/* A muscle: sw_muscle_desc_init's defaults, then what the model wrote. */
static void emit_muscle(FILE *out, swArena *a, const swScene *sc, int mi) {
  const swSceneMuscle *m = &sc->muscle[mi];
  swLowField f[GEN_MAX_FIELDS];
  fputc('\n', out);
  gen_origin(out, m->loc, "  ");
  fputs("  {\n    swMuscleDesc muscle;\n    sw_muscle_desc_init(&muscle);\n    muscle.name = ",
        out);
  gen_c_string(out, m->name);
  fprintf(out, ";   /* muscle %d: filaments are rods %d to %d */\n", mi, m->id,
          m->id + m->filaments - 1);
  fprintf(out, "    muscle.filaments = %d;\n", m->filaments);
  if (m->has_nelem) fprintf(out, "    muscle.nelem = %d;\n", m->nelem);
  if (m->motor_units) fprintf(out, "    muscle.motor_units = %ld;\n", m->motor_units);
  static const char *damp[] = {"SW_DAMP_NONE", "SW_DAMP_LINEAR", "SW_DAMP_ANALYTIC"};
  if (m->has_damping) fprintf(out, "    muscle.damping = %s;\n", damp[m->damping]);
  if (m->variational == 2) fputs("    muscle.law = SW_LAW_VARIATIONAL;   /* a muscle's default */\n", out);
  else if (m->variational) fputs("    muscle.law = SW_LAW_VARIATIONAL;\n", out);
  if (m->weightless) fputs("    muscle.weightless = 1;   /* gravity = false */\n", out);
  emit_description(out, "muscle", NULL, m->material, m->loc);
  for (int e = 0; e < 2; e++)
    if (m->attach_rod[e] >= 0) {
      fprintf(out, "    muscle.attach_rod[%d] = %d; muscle.attach_node[%d] = ", e,
              gen_rod_id(sc, m->attach_rod[e]), e);
      gen_node(out, m->attach_node[e], m->attach_node_c[e]);
      rod_comment(out, sc, m->attach_rod[e]);
    }
  if (m->nvia) fprintf(out, "    muscle.nvia = %d;\n", m->nvia);
  for (int k = 0; k < m->nvia; k++)
    if (m->via_rod[k] >= 0) {
      fprintf(out, "    muscle.via_rod[%d] = %d;", k, gen_rod_id(sc, m->via_rod[k]));
      rod_comment(out, sc, m->via_rod[k]);
    }
  gen_assign_fields(out, a, "muscle", f, gen_muscle_fields(m, f));
  if (m->force) {   /* a prescribed pull instead of the Hill law */
    fputs("    muscle.prescribed = 1;\n", out);
    gen_emit_signal(out, a, "muscle.force", m->force);
  }
  if (m->activation) {
    gen_origin(out, m->activation_loc, "    ");
    const swSignalVal *sig = m->activation;
    if (sig->kind == SW_SIG_CONST)
      fprintf(out, "    muscle.activation = sw_signal_const(%s);\n", val_c(a, &sig->a, 0));
    else {
      fputs("    muscle.activation = sw_signal_const(0.0);\n", out);
      gen_emit_signal(out, a, "muscle.activation", sig);
    }
  }
  fputs("    ok &= sw_spec_add_muscle(s, &muscle) >= 0;\n  }\n", out);
}

/* ---- output selection ---- */

static const char *const scope_word[] = {"rod", "joint", "muscle"};

static int has_selection(const swScene *sc, int scope) {
  for (int i = 0; i < sc->nselect; i++)
    if ((int)sc->select[i].scope == scope) return 1;
  return 0;
}

/* What each item of a scope writes (SW_OUT_* bits), from the selections in
 * model order.  A quantity written by default (positions; a joint's and a
 * muscle's quantities) goes to every item until a selection names it, then
 * to the items selected; the others only to the items selected. */
static unsigned selected_bits(const swScene *sc, int scope, int count, unsigned *bits) {
  const unsigned defaults = scope == OUT_RODS     ? SW_OUT_POSITION
                            : scope == OUT_JOINTS ? SW_OUT_ANGLE | SW_OUT_JOINT_FORCE |
                                                        SW_OUT_LIMIT_TORQUE
                                                  : SW_OUT_MUSCLE_FORCE | SW_OUT_STRETCH |
                                                        SW_OUT_ACTIVATION | SW_OUT_FILAMENT_FORCE;
  unsigned named = 0;
  for (int k = 0; k < count; k++) bits[k] = defaults;
  for (int i = 0; i < sc->nselect; i++) {
    const swOutSelect *o = &sc->select[i];
    if ((int)o->scope != scope) continue;
    if (!(named & o->bit))
      for (int k = 0; k < count; k++) bits[k] &= ~o->bit;
    named |= o->bit;
    if (o->n < 0)
      for (int k = 0; k < count; k++) bits[k] |= o->bit;
    for (int k = 0; k < o->n; k++) bits[o->id[k]] |= o->bit;
  }
  return defaults & ~named;   /* what an item no selection can name keeps */
}

/* The name of runtime rod `id`: a rod's, or a muscle's filament's. */
static const char *runtime_rod_name(const swScene *sc, int id, char *buf, size_t len) {
  for (int r = 0; r < sc->nrod; r++)
    if (sc->rod[r].id == id) return sc->rod[r].name;
  for (int m = 0; m < sc->nmuscle; m++)
    if (id >= sc->muscle[m].id && id < sc->muscle[m].id + sc->muscle[m].filaments) {
      snprintf(buf, len, "%s.f%02d", sc->muscle[m].name, id - sc->muscle[m].id + 1);
      return buf;
    }
  return "?";
}

/* Bits by name: "SW_OUT_POSITION | SW_OUT_STRAIN", or "0". */
static void emit_bits(FILE *out, unsigned bits) {
  static const char *const bit_name[] = {
      "SW_OUT_POSITION",       "SW_OUT_VELOCITY",        "SW_OUT_DIRECTORS",
      "SW_OUT_ANGULAR_VELOCITY", "SW_OUT_STRAIN",        "SW_OUT_CURVATURE",
      "SW_OUT_INTERNAL_FORCE", "SW_OUT_INTERNAL_COUPLE", "SW_OUT_ANGLE",
      "SW_OUT_JOINT_FORCE",    "SW_OUT_MUSCLE_FORCE",    "SW_OUT_STRETCH",
      "SW_OUT_ACTIVATION",     "SW_OUT_FILAMENT_FORCE",  "SW_OUT_LIMIT_TORQUE"};
  int any = 0;
  for (unsigned b = 0; b < sizeof bit_name / sizeof bit_name[0]; b++)
    if (bits & (1u << b)) fprintf(out, "%s%s", any++ ? " | " : "", bit_name[b]);
  if (!any) fputs("0", out);
}

/* Items of a scope the compiler knows, when the model selects any of them. */
static int selection_count(const swScene *sc, int scope) {
  if (!has_selection(sc, scope)) return 0;
  return scope == OUT_RODS ? sc->nrodid : scope == OUT_JOINTS ? sc->njoint : sc->nmuscle;
}

/* static const unsigned rod_out[N] = {...}: one line per item, its bits by
 * name and the item's name; joints also by name (joint_out_name[N]), as the
 * runtime adds joints of its own. */
static void emit_selection(FILE *out, const swScene *sc, int scope) {
  const int count = selection_count(sc, scope);
  if (count == 0) return;
  unsigned *bits = calloc((size_t)count, sizeof *bits);
  if (!bits) abort();
  selected_bits(sc, scope, count, bits);
  fprintf(out, "\n/* What the output writes of each %s (output's selections). */\n",
          scope_word[scope]);
  if (scope == OUT_JOINTS) {
    fprintf(out, "static const char *const joint_out_name[%d] = {", count);
    for (int k = 0; k < count; k++) {
      fputs(k ? ", " : "", out);
      gen_c_string(out, sc->joint[k].name);
    }
    fputs("};\n", out);
  }
  fprintf(out, "static const unsigned %s_out[%d] = {\n", scope_word[scope], count);
  for (int k = 0; k < count; k++) {
    char buf[128];
    const char *name = scope == OUT_RODS     ? runtime_rod_name(sc, k, buf, sizeof buf)
                       : scope == OUT_JOINTS ? sc->joint[k].name
                                             : sc->muscle[k].name;
    fputs("  ", out);
    emit_bits(out, bits[k]);
    fputs(",   /* ", out);
    gen_c_comment(out, name, strlen(name));
    fputs(" */\n", out);
  }
  fputs("};\n", out);
  free(bits);
}

/* The program's members that point at the selections. */
static void emit_selection_members(FILE *out, const swScene *sc) {
  if (selection_count(sc, OUT_RODS)) fputs(",\n    .rod_out = rod_out", out);
  if (selection_count(sc, OUT_MUSCLES)) fputs(",\n    .muscle_out = muscle_out", out);
  const int nj = selection_count(sc, OUT_JOINTS);
  if (!nj) return;
  unsigned *bits = calloc((size_t)nj, sizeof *bits);
  if (!bits) abort();
  unsigned rest = selected_bits(sc, OUT_JOINTS, nj, bits);
  free(bits);
  fprintf(out, ",\n    .njoint_out = %d,\n    .joint_out_name = joint_out_name,\n"
          "    .joint_out = joint_out,\n    /* every other joint (a muscle's attachments) */\n"
          "    .joint_out_rest = ", nj);
  emit_bits(out, rest);
}

/* derive(): the quantities derived from the params (swSceneDerived), each
 * traced to the model line that defines it; build() and objective() start
 * with it. */
static void emit_derived(FILE *out, const swScene *sc) {
  if (!sc->nderived) return;
  fputs("/* The quantities the model derives from the params P: its lets and rod\n"
        " * geometry that a param changes, in the order they are defined. */\n"
        "static void derive(const double *P, double *D) {\n", out);
  for (int i = 0; i < sc->nderived; i++) {
    const swSceneDerived *d = &sc->derived[i];
    gen_origin(out, d->loc, "  ");
    fprintf(out, "  D[%d] = %s;   /* ", i, d->text);
    gen_c_comment(out, d->what, strlen(d->what));
    fputs(" */\n", out);
  }
  fputs("}\n\n", out);
}

/* The start of a function over P: D, the derived quantities, when any. */
static void open_derived(FILE *out, const swScene *sc) {
  if (sc->nderived) fprintf(out, "  double D[%d];\n  derive(P, D);\n", sc->nderived);
}

static void emit_build(FILE *out, swArena *a, const swScene *sc) {
  fputs("/* Builds the scene from the param values P (SI units, in the order of\n"
        " * params[]).  Returns SW_OK or SW_EMODEL with a message in err.\n"
        " *\n"
        " * It runs once, so GCC compiles it without optimisation: for a scene of\n"
        " * thousands of rods (a wing's barbs) that takes the C compiler 6 s\n"
        " * instead of 27 s (-O3) or 184 s (-O1); in ISO C (-std=c11) no\n"
        " * operation is contracted at any level, so every value is the same. */\n"
        "#if defined(__GNUC__) && !defined(__clang__)\n"
        "__attribute__((optimize(\"O0\")))\n"
        "#endif\n"
        "static int build(swSpec *s, const double *P, char *err, size_t errlen) {\n"
        "  int ok = 1;\n"
        "  (void)P;\n", out);
  open_derived(out, sc);
  gen_signal_build(out, a, sc);
  /* the runtime numbers joints with its own (a muscle's attachments) */
  if (sc->njoint)
    fprintf(out, "  int joint_id[%d];   /* the runtime's id of each joint */\n", sc->njoint);
  swLowField f[GEN_MAX_FIELDS];
  /* rods and muscles in the order of their runtime ids */
  for (int ri = 0, mi = 0; ri < sc->nrod || mi < sc->nmuscle;) {
    if (gen_rod_next(sc, ri, mi)) emit_rod(out, a, &sc->rod[ri++]);
    else emit_muscle(out, a, sc, mi++);
  }
  for (int i = 0; i < sc->npassive; i++) {
    const swScenePassive *p = &sc->passive[i];
    fputc('\n', out);
    gen_origin(out, p->loc, "  ");
    fprintf(out, "  ok &= sw_spec_set_filament_passive(s, %d, %d) == SW_OK;   /* ", p->muscle,
            p->filament);
    gen_c_comment(out, sc->muscle[p->muscle].name, strlen(sc->muscle[p->muscle].name));
    fprintf(out, ", filament %d */\n", p->filament + 1);
  }
  for (int i = 0; i < sc->njoint; i++) {
    const swSceneJoint *j = &sc->joint[i];
    static const char *kinds[] = {"SW_JOINT_SPHERICAL", "SW_JOINT_HINGE", "SW_JOINT_FIXED"};
    fputc('\n', out);
    gen_origin(out, j->loc, "  ");
    fputs("  {\n    swJointDesc joint;\n    sw_joint_desc_init(&joint);\n    joint.name = ", out);
    gen_c_string(out, j->name);
    fprintf(out, ";\n    joint.kind = %s;\n", kinds[j->kind]);
    fprintf(out, "    joint.rod_a = %d; joint.node_a = ", gen_rod_id(sc, j->rod_a));
    gen_node(out, j->node_a, j->node_a_c);
    rod_comment(out, sc, j->rod_a);
    fprintf(out, "    joint.rod_b = %d; joint.node_b = ", gen_rod_id(sc, j->rod_b));
    gen_node(out, j->node_b, j->node_b_c);
    if (j->rod_b >= 0) rod_comment(out, sc, j->rod_b);
    else fputs("   /* anchored in space */\n", out);
    if (j->undamped) fputs("    joint.undamped = 1;\n", out);
    if (j->has_range) fputs("    joint.has_range = 1;\n", out);
    gen_assign_fields(out, a, "joint", f, gen_joint_fields(j, f));
    fprintf(out, "    joint_id[%d] = sw_spec_add_joint(s, &joint);\n"
            "    ok &= joint_id[%d] >= 0;\n  }\n", i, i);
  }
  for (int i = 0; i < sc->nkin; i++) {
    const swSceneKinematic *k = &sc->kin[i];
    fputc('\n', out);
    gen_origin(out, k->loc, "  ");
    fputs("  {\n    swKinematicDesc kin;\n    sw_kinematic_desc_init(&kin);\n    kin.name = ", out);
    gen_c_string(out, k->name);
    swValue xi = val_num(a, k->leader_xi, DIM_NONE, k->loc);
    fprintf(out, ";\n    kin.leader_rod = %d; kin.leader_elem = %d; kin.leader_xi = %s;",
            gen_rod_id(sc, k->leader_rod), k->leader_elem, val_c(a, &xi, 0));
    rod_comment(out, sc, k->leader_rod);
    fprintf(out, "    kin.follower_rod = %d; kin.follower_node = %d; kin.follower_elem = %d;",
            gen_rod_id(sc, k->follower_rod), k->follower_node, k->follower_elem);
    rod_comment(out, sc, k->follower_rod);
    if (k->reaction_rod >= 0) {
      fprintf(out, "    kin.reaction_rod = %d; kin.reaction_node = %d;",
              gen_rod_id(sc, k->reaction_rod), k->reaction_node);
      rod_comment(out, sc, k->reaction_rod);
    }
    fprintf(out, "    kin.stiffness = %s;\n", val_c(a, &k->stiffness, 0));
    if (k->damping.kind == VAL_NUM) fprintf(out, "    kin.damping = %s;\n", val_c(a, &k->damping, 0));
    if (k->reaction_weight.kind == VAL_NUM)
      fprintf(out, "    kin.reaction_weight = %s;\n", val_c(a, &k->reaction_weight, 0));
    fputs("    ok &= sw_spec_add_kinematic(s, &kin) >= 0;\n  }\n", out);
  }
  for (int i = 0; i < sc->nact; i++) {
    const swSceneAction *act = &sc->act[i];
    fputc('\n', out);
    gen_origin(out, act->loc, "  ");
    if (act->is_bc) {
      static const char *kinds[] = {"SW_BC_CLAMP", "SW_BC_VELOCITY", "SW_BC_OMEGA", "SW_BC_SLIDE_LINE",
                                    "SW_BC_SLIDE_PLANE", "SW_BC_SLEEVE"};
      fputs("  {\n    swBCDesc bc = {0};\n", out);
      fprintf(out, "    bc.kind = %s;\n    bc.rod = %d;", kinds[act->kind], gen_rod_id(sc, act->rod));
      rod_comment(out, sc, act->rod);
      fprintf(out, "    bc.end = %d;\n", act->index);
      if (act->kind != SW_BC_CLAMP)
        for (int k = 0; k < 3; k++)
          fprintf(out, "    bc.vec[%d] = %s;\n", k, val_c(a, &act->vec, k));
      gen_emit_signal(out, a, "bc.signal", act->sig);
      if (act->until.kind == VAL_NUM) fprintf(out, "    bc.until = %s;\n", val_c(a, &act->until, 0));
      fputs("    ok &= sw_spec_add_bc(s, &bc) >= 0;\n  }\n", out);
    } else {
      static const char *kinds[] = {"SW_LOAD_FORCE", "SW_LOAD_TORQUE"};
      fputs("  {\n    swLoadDesc load = {0};\n", out);
      fprintf(out, "    load.kind = %s;\n    load.rod = %d;", kinds[act->kind],
              gen_rod_id(sc, act->rod));
      rod_comment(out, sc, act->rod);
      fprintf(out, "    load.index = %d;\n", act->index);
      for (int k = 0; k < 3; k++)
        fprintf(out, "    load.vec[%d] = %s;\n", k, val_c(a, &act->vec, k));
      gen_emit_signal(out, a, "load.signal", act->sig);
      fputs("    ok &= sw_spec_add_load(s, &load) >= 0;\n  }\n", out);
    }
  }
  gen_env_build(out, a, sc);
  static const char *const quantities[] = {"SW_EXPECT_JOINT_ANGLE", "SW_EXPECT_JOINT_FORCE",
                                           "SW_EXPECT_MUSCLE_FORCE", "SW_EXPECT_MUSCLE_STRETCH",
                                           "SW_EXPECT_PROBE"};
  static const char *const reductions[] = {"SW_REDUCE_NONE", "SW_REDUCE_AT", "SW_REDUCE_MEAN",
                                           "SW_REDUCE_MAX", "SW_REDUCE_MIN"};
  for (int i = 0, r = 0; i < sc->nexpect; i++) {
    swExpectDesc d;
    gen_expect_desc(&sc->expect[i], &d);
    char where[300];
    diag_name_where(sc->expect[i].loc, where, sizeof where); /* no machine path in the C */
    fputc('\n', out);
    gen_origin(out, sc->expect[i].loc, "  ");
    fputs("  {\n    swExpectDesc expect;\n    sw_expect_desc_init(&expect);\n    expect.text = ",
          out);
    gen_c_string(out, d.text);
    fputs(";\n    expect.where = ", out);
    gen_c_string(out, where);
    fprintf(out, ";\n    expect.quantity = %s;\n", quantities[d.quantity]);
    if (d.quantity == SW_EXPECT_JOINT_ANGLE || d.quantity == SW_EXPECT_JOINT_FORCE)
      fprintf(out, "    expect.index = joint_id[%d];\n", d.index);
    else
      fprintf(out, "    expect.index = %d;\n", d.index);
    if (d.quantity == SW_EXPECT_PROBE) fprintf(out, "    expect.component = %d;\n", d.component);
    if (d.window) fputs("    expect.window = 1;\n", out);
    fprintf(out, "    expect.t0 = %.17g;\n    expect.t1 = %.17g;\n", d.t0, d.t1);
    if (d.reduce) {   /* a reduction the objective reads */
      fprintf(out, "    expect.reduce = %s;   /* R[%d] of objective() */\n",
              reductions[d.reduce], r++);
    } else {
      fprintf(out, "    expect.lo = %.17g;\n    expect.hi = %.17g;\n", d.lo, d.hi);
      fprintf(out, "    expect.scale = %.17g;\n    expect.unit = ", d.scale);
      gen_c_string(out, d.unit);
      fputs(";\n", out);
    }
    fputs("    ok &= sw_spec_add_expect(s, &expect) >= 0;\n  }\n", out);
  }
  if (sc->gravity.kind == VAL_VEC) {
    fputc('\n', out);
    gen_origin(out, sc->gravity_loc, "  ");
    fprintf(out, "  {\n    const double g[3] = {%s, %s, %s};\n    sw_spec_set_gravity(s, g);\n",
            val_c(a, &sc->gravity, 0), val_c(a, &sc->gravity, 1), val_c(a, &sc->gravity, 2));
    if (sc->gravity_sig) {   /* times a signal of time */
      fputs("    swSignal gs = sw_signal_const(1.0);\n", out);
      gen_emit_signal(out, a, "gs", sc->gravity_sig);
      fputs("    sw_spec_set_gravity_signal(s, gs);\n", out);
    }
    fputs("  }\n", out);
  }
  static const char *integrators[] = {"SW_VERLET", "SW_PEFRL", "SW_IMEX"};
  fprintf(out, "\n  sw_spec_set_integrator(s, %s);\n", integrators[sc->integrator]);
  fputs("  if (!ok) {\n    snprintf(err, errlen, \"out of memory while building the scene\");\n"
        "    return SW_EMODEL;\n  }\n  return SW_OK;\n}\n", out);
}

/* objective(): the objective and the sum of the penalties over the params P
 * and the values R of the reductions build() adds. */
static void emit_objective(FILE *out, swArena *a, const swScene *sc) {
  const swSceneObjective *o = &sc->objective;
  if (!o->sense) return;
  fputs("\n/* The objective and the sum of the penalties (SI) from the params P and the\n"
        " * values R of the reductions of the run, in the order build() adds them:", out);
  for (int i = 0, r = 0; i < sc->nexpect; i++)
    if (sc->expect[i].reduce) {
      fprintf(out, "\n *   R[%d] ", r++);
      gen_c_comment(out, sc->expect[i].text, strlen(sc->expect[i].text));
    }
  fputs(" */\nstatic void objective(const double *P, const double *R, double *value, "
        "double *penalty) {\n  (void)P;\n  (void)R;\n", out);
  open_derived(out, sc);
  gen_origin(out, o->loc, "  ");
  fprintf(out, "  *value = %s;\n  *penalty = 0.0;\n", val_c(a, &o->value, 0));
  for (int i = 0; i < o->npenalty; i++) {
    gen_origin(out, o->penalty_loc[i], "  ");
    fprintf(out, "  *penalty += %s;\n", val_c(a, &o->penalty[i], 0));
  }
  fputs("}\n", out);
}

/* The program's members that describe the objective. */
static void emit_objective_members(FILE *out, swArena *a, const swScene *sc) {
  const swSceneObjective *o = &sc->objective;
  if (!o->sense) return;
  char where[512];
  swValue scale = val_num(a, o->scale, DIM_NONE, o->loc);
  fprintf(out, ",\n    .sense = %d,\n    .objective_text = ", o->sense);
  gen_c_string(out, o->text);
  fputs(",\n    .objective_where = ", out);
  gen_c_string(out, diag_name_where(o->loc, where, sizeof where));
  fputs(",\n    .objective_unit = ", out);
  gen_c_string(out, o->unit);
  fprintf(out, ",\n    .objective_scale = %s,\n    .objective_si_unit = ", val_c(a, &scale, 0));
  gen_c_string(out, o->si_unit);
  fprintf(out, ",\n    .npenalty = %d,\n    .nreduce = %d,\n    .objective = objective",
          o->npenalty, o->nreduce);
}

static void emit_source(FILE *out, const char *src) {
  fputs("/* The model source, imports inlined: the output's model_source attribute. */\n"
        "static const char model_source[] =\n", out);
  const char *p = src;
  if (!*p) fputs("  \"\"", out);
  while (*p) {
    const char *nl = strchr(p, '\n');
    size_t len = nl ? (size_t)(nl - p) + 1 : strlen(p);
    fputs("  ", out);
    c_string(out, p, len);
    p += len;
    if (*p) fputc('\n', out);
  }
  fputs(";\n\n", out);
}

int gen_c(FILE *out, swArena *a, const swScene *sc, const swGenOptions *opt) {
  const swSource *main_src = diag_file(0);
  fputs("/* Generated by ", out);
  gen_c_comment(out, opt->compiler, strlen(opt->compiler));
  fputs(" from ", out);
  if (main_src) gen_c_comment(out, main_src->name, strlen(main_src->name));
  fputs(".\n * Do not edit: change the model and compile it again.  Each block of\n"
        " * build() starts with the model line it comes from.", out);
  if (sc->nlet) {
    fputs("\n *\n * Compiled with sinewc --let: these lets of the model take the values given\n"
          " * instead of their own (model_source ends with the same list):", out);
    for (int i = 0; i < sc->nlet; i++) {
      char where[512];
      fputs("\n *   --let ", out);
      gen_c_comment(out, sc->let[i].text, strlen(sc->let[i].text));
      fputs("   (the let at ", out);
      diag_name_where(sc->let[i].let_loc, where, sizeof where);
      gen_c_comment(out, where, strlen(where));
      fputc(')', out);
    }
    fputs("\n", out);
  }
  fputs(" */\n#include \"sinew.h\"\n\n", out);
  emit_source(out, sc->source ? sc->source : "");
  if (sc->nparam) {
    fputs("/* Params, overridable with --set NAME=VALUE; defaults in SI units.\n"
          " * Dimensions are exponents of (kg, m, s, rad). */\n", out);
    fprintf(out, "static const swParam params[%d] = {\n", sc->nparam);
    for (int i = 0; i < sc->nparam; i++) {
      const swSceneParam *p = &sc->param[i];
      char where[512];
      fputs("  {", out);
      gen_c_string(out, p->name);
      fprintf(out, ", %s, {%d, %d, %d, %d}, ", val_c(a, &p->value, 0), p->value.dim.e[0],
              p->value.dim.e[1], p->value.dim.e[2], p->value.dim.e[3]);
      gen_c_string(out, p->unit);
      fputs(", ", out);
      gen_c_string(out, diag_name_where(p->loc, where, sizeof where));
      /* in (lo, hi): what a study varies (0: fixed in studies) */
      swValue lo = val_num(a, p->lo, p->value.dim, p->loc);
      swValue hi = val_num(a, p->hi, p->value.dim, p->loc);
      fprintf(out, ", %d, %s, %s", p->ranged, val_c(a, &lo, 0), val_c(a, &hi, 0));
      fprintf(out, "},   /* P[%d] */\n", i);
    }
    fputs("};\n\n", out);
  }
  emit_derived(out, sc);
  gen_env_heights(out, a, sc);
  gen_shape_functions(out, a, sc);
  gen_signal_functions(out, a, sc);
  emit_build(out, a, sc);
  emit_objective(out, a, sc);
  for (int scope = OUT_RODS; scope <= OUT_MUSCLES; scope++) emit_selection(out, sc, scope);
  /* without "output ... every T", a thousand frames over the run */
  double duration = sc->has_duration ? sc->duration : 1.0;
  swValue ev = val_num(a, sc->every > 0 ? sc->every : duration / 1000, DIM_TIME, (swLoc){0});
  swValue dt = val_num(a, sc->dt, DIM_TIME, (swLoc){0});
  swValue du = val_num(a, duration, DIM_TIME, (swLoc){0});
  fputs("\nint main(int argc, char **argv) {\n  static const swProgram program = {\n    .name = ",
        out);
  gen_c_string(out, sc->model_name);
  fputs(",\n    .source = model_source,\n    .sha256 = ", out);
  gen_c_string(out, sc->sha256);
  fprintf(out, ",\n    .nparam = %d,\n    .param = %s,\n    .build = build,\n", sc->nparam,
          sc->nparam ? "params" : "NULL");
  fprintf(out, "    .dt = %s,%s\n    .duration = %s,\n    .every = %s,\n    .out = ",
          val_c(a, &dt, 0), sc->dt > 0 ? "" : "   /* half the stable estimate */",
          val_c(a, &du, 0), val_c(a, &ev, 0));
  if (sc->out) gen_c_string(out, sc->out);
  else {
    char def[512];
    snprintf(def, sizeof def, "%s.h5", sc->model_name);
    gen_c_string(out, def);
  }
  emit_selection_members(out, sc);
  emit_objective_members(out, a, sc);
  fputs(",\n  };\n  return sw_main(&program, argc, argv);\n}\n", out);
  return ferror(out) ? -1 : 0;
}

int gen_check(const swScene *sc, double *stable_dt) {
  swSpec *s = gen_spec(sc);
  if (!s) {
    diag_plain("out of memory");
    return 1;
  }
  char err[512] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  sw_spec_free(s);
  swLoc whole = {0, 0, 0, 0, 0};
  if (!m) {
    diag_error(whole, "the runtime rejects this scene: %s", err[0] ? err : "unknown reason");
    return 1;
  }
  /* a rod laid inside an obstacle by more than a tenth of its radius: the
   * penalty would fling it out at the first step */
  for (int k = 0; k < sc->nobstacle && k < m->nobstacle; k++) {
    int rod, elem;
    const double depth = sw_obstacle_start_depth(m, k, &rod, &elem);
    if (rod < 0) continue;
    const double r = m->radius[m->elem_adr[rod] + elem];
    if (depth > 0.1 * r)
      diag_error(sc->obstacle[k].loc, "rod '%s' starts %.3g mm inside obstacle '%s' (element %d, "
                 "radius %.3g mm; the tolerance is a tenth of the radius): lay the rod outside it, "
                 "or move the obstacle", m->rod_name[rod], depth * 1e3, sc->obstacle[k].name, elem,
                 r * 1e3);
  }
  if (sc->dt > 0 && m->nrod > 0) {
    double est = sw_stable_dt(m);
    int worst = 0;
    for (int r = 1; r < m->nrod; r++)
      if (sw_stable_dt_rod(m, r) < sw_stable_dt_rod(m, worst)) worst = r;
    if (sc->dt > est)
      diag_warning(sc->dt_loc, "dt = %g s is above the stable estimate %.3g s of this scene "
                   "(set by rod '%s'); the run will likely become unstable", sc->dt, est,
                   m->rod_name[worst]);
  }
  /* An activation the model drives outside [0, 1] through a param's default
   * or a signal's values is clamped; a plain number out of range is warned
   * of where it is read (sema_activate).  The runtime's muscles are the
   * scene's, in order (gen_spec). */
  for (int mu = 0; mu < sc->nmuscle && mu < m->nmuscle; mu++) {
    const swSignalVal *act = sc->muscle[mu].activation;
    if (!act) continue;
    int listed = act->kind == SW_SIG_TABLE || act->kind == SW_SIG_BSPLINE;
    int by_param = act->kind == SW_SIG_FUNC ? !val_is_const(&act->a)
                   : listed ? !val_is_const(&act->values)
                            : !val_is_const(&act->a) || !val_is_const(&act->b);
    if (act->kind == SW_SIG_CONST && !by_param) continue;
    double lo, hi;
    sw_signal_range(&m->muscle_activation[mu], &lo, &hi);
    if (lo < 0 || hi > 1)
      diag_warning(sc->muscle[mu].activation_loc, "the activation of muscle '%s' %s %g%s; it acts "
                   "as %g (activations are clamped to [0, 1])", sc->muscle[mu].name,
                   hi > 1 ? "reaches" : "goes down to", hi > 1 ? hi : lo,
                   by_param ? " with the params' defaults" : "", hi > 1 ? 1.0 : 0.0);
  }
  if (stable_dt) *stable_dt = m->nrod > 0 ? sw_stable_dt(m) : 0;
  sw_model_free(m);
  return 0;
}
