/* sema_muscle.c — muscles and the statements that drive them: activate and
 * passive.
 *
 * Design.  A muscle is not a rod: it becomes one swMuscleDesc, which the
 * runtime turns into `filaments` rods (NAME.f01 ...), laid from `from` to
 * `to` and tied by spherical joints to the rods those points are on (Zhang et
 * al. 2019, Suppl. Note 1).  So a muscle has no points of its own to clamp or
 * join, and its fields are the bundle's: geometry (from, to, radius),
 * tissue (material and overrides, as rods), the filament count and motor
 * units, and the contraction model (sigma_max, size_ratio, twitch times,
 * Hill's a, v_max).  A field the model does not write stays VAL_ERROR in the
 * scene and keeps the runtime's default (sw_muscle_desc_init), so the runtime
 * is the one source of defaults (the checker reads the default of `elements`
 * from sw_muscle_desc_init too, since it must know the scene's size).  The muscle takes the
 * next `filaments` runtime rod ids, which shifts the ids of every rod after
 * it (swSceneRod.id).  `activate NAME = u;` sets the activation signal, a
 * dimensionless number or time signal whose constant scale is folded into
 * the signal's values (swSignal has no separate scale); `passive
 * NAME.filament(K);` marks filament K (1 = smallest) as never contracting.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sema_int.h"

#define MAX_FILAMENTS 10000
#define MAX_MOTOR_UNITS 1000000000L

static const char *const muscle_keys[] = {
  "material", "from", "to", "normal", "radius", "filaments", "motor_units", "elements",
  "E", "G", "poisson", "density", "sigma_max", "size_ratio", "twitch_small", "twitch_large",
  "hill_a", "v_max", "fibre_diameter", "attach_stiffness", "attach_damping",
  "shear_hardening", "twist_hardening", "damping", "damping_model", "variational", "via",
  "gravity", "force",
  /* rod fields that a muscle does not take, refused with a reason below */
  "start", "direction", "length", "radius_start", "radius_end", "shape", "rest_shape",
  "start_shape",
};
enum { NMUSCLE_KEYS = sizeof muscle_keys / sizeof muscle_keys[0] };


void sema_muscle_not_rod(swSema *S, const swSymbol *muscle, swLoc loc) {
  (void)S;
  diag_error(loc, "'%s' is a muscle: a bundle of filaments attached by its 'from' and 'to', "
             "with no points of its own; use a point on a rod it is attached to",
             muscle->name);
}

/* A muscle's end written as a point on a rod moved by an offset
 * (shank.end + (0, 0, 5) mm) is a position off the rod: the end would hang
 * free there, not attached, so it is an error, as a joint's gap is (a free
 * end is written as a position in space).  Returns 0 after reporting it. */
static int end_on_body(swSema *S, swScope *sc, const swAst *e, const char *which,
                       const char *what) {
  const swAst *base = e;
  while (base->kind == AST_BINOP && (base->op == '+' || base->op == '-')) base = base->kid[0];
  if (base == e) return 1;
  int rod = -1, node = 0;
  swValue b = sema_position_on(S, sc, base, which, &rod, &node, NULL);
  if (b.kind == VAL_ERROR || rod < 0) return 1;   /* reported already, or not a rod's point */
  swValue v = sema_position_on(S, sc, e, which, NULL, NULL, NULL);
  if (v.kind != VAL_VEC) return 1;
  double gap = sqrt((v.v[0] - b.v[0]) * (v.v[0] - b.v[0]) + (v.v[1] - b.v[1]) * (v.v[1] - b.v[1]) +
                    (v.v[2] - b.v[2]) * (v.v[2] - b.v[2]));
  diag_error(e->loc, "%s of %s is %g mm off rod '%s' (a point on it moved by an offset), so "
             "the muscle would hang free there instead of attaching; a muscle attaches at a "
             "point on a rod (e.g. %s.at(0.95)), and a free end is a position in space",
             which, what, gap * 1e3, S->scene->rod[rod].name, S->scene->rod[rod].name);
  return 0;
}

/* The via points (`via = P;` or `via = (P1, P2, ...);`), each a point on a
 * rod, that point plus an offset (humerus.at(0.95) + (0, 0, 1) cm: the offset
 * is taken at t = 0 and the point is carried by that rod), or a position in
 * space.  Fills m->via, m->via_rod and m->nvia; 0 after an error. */
static int eval_via(swSema *S, swScope *sc, const swSymbol *sym, const swAst *e,
                    swSceneMuscle *m) {
  const swAst *item[SW_MUSCLE_MAX_VIA + 64];
  int n = 0;
  /* a list of points, or one point; a vector of numbers is one position */
  int list = e->kind == AST_VEC && e->nkid > 0;
  for (int i = 0; list && i < e->nkid; i++) {
    const swAst *k = e->kid[i];
    if (k->kind == AST_NUM || k->kind == AST_APPLY || k->kind == AST_NEG) list = 0;
  }
  if (list) {
    if (e->nkid > SW_MUSCLE_MAX_VIA) {
      diag_error(e->loc, "'via' lists %d points; a muscle takes at most %d via points", e->nkid,
                 SW_MUSCLE_MAX_VIA);
      return 0;
    }
    for (int i = 0; i < e->nkid; i++) item[n++] = e->kid[i];
  } else item[n++] = e;
  int ok = 1;
  for (int i = 0; i < n; i++) {
    char what[64];
    snprintf(what, sizeof what, "via point %d", i + 1);
    /* the rod: of the point itself, or of the point an offset is added to */
    const swAst *base = item[i];
    while (base->kind == AST_BINOP && (base->op == '+' || base->op == '-')) base = base->kid[0];
    const swAst *owner = base->kind == AST_MEMBER || base->kind == AST_METHOD ? base->kid[0] : NULL;
    if (owner && owner->kind == AST_NAME && sema_lookup(S, sc, owner->name) == sym) {
      diag_error(base->loc, "a via point of muscle '%s' cannot be on the muscle itself; put it on "
                 "a rod the muscle passes (e.g. humerus.at(0.95))", sym->name);
      ok = 0;
      continue;
    }
    int rod = -1, node = 0;
    if (base != item[i]) {
      swValue b = sema_position_on(S, sc, base, what, &rod, &node, NULL);
      if (b.kind == VAL_ERROR) {
        ok = 0;
        continue;
      }
    }
    swValue v = sema_position_on(S, sc, item[i], what, base != item[i] ? NULL : &rod, &node,
                                 NULL);
    if (v.kind == VAL_ERROR) {
      ok = 0;
      continue;
    }
    /* coinciding with the point before it (from, or the previous via) */
    const swValue *prev = i == 0 ? &m->start : &m->via[i - 1];
    if (prev->kind == VAL_VEC && prev->v[0] == v.v[0] && prev->v[1] == v.v[1] &&
        prev->v[2] == v.v[2]) {
      diag_error(item[i]->loc, "via point %d is the same point as %s, so the muscle's path has "
                 "a segment of no length", i + 1, i == 0 ? "'from'" : "the via point before it");
      ok = 0;
    }
    m->via[i] = v;
    m->via_rod[i] = rod;
  }
  if (ok && m->end.kind == VAL_VEC && m->via[n - 1].kind == VAL_VEC &&
      !memcmp(m->via[n - 1].v, m->end.v, 3 * sizeof(double))) {
    diag_error(item[n - 1]->loc, "via point %d is the same point as 'to', so the muscle's path "
               "has a segment of no length", n);
    ok = 0;
  }
  m->nvia = ok ? n : 0;
  return ok;
}

/* An optional scalar field: its value, VAL_ERROR when absent; *ok cleared on
 * an error. */
static swValue opt_scalar(swSema *S, swScope *sc, const swFields *f, const char *key, swDim dim,
                          int *ok) {
  if (!sema_field(f, key)) return val_error();
  swValue v = sema_field_value(S, sc, f, key, 1, dim);
  if (v.kind == VAL_ERROR) *ok = 0;
  return v;
}

static void not_negative(const swValue *v, const char *key, int *ok) {
  if (v->kind == VAL_NUM && v->v[0] < 0) {
    diag_error(v->loc, "'%s' must not be negative, got %g", key, v->v[0]);
    *ok = 0;
  }
}

static void must_be_positive(swSema *S, const swValue *v, const char *key, const char *unit,
                             int *ok) {
  char what[64];
  snprintf(what, sizeof what, "'%s'", key);
  if (v->kind == VAL_NUM && !sema_positive(S, v, what, unit)) *ok = 0;
}

void sema_eval_muscle(swSema *S, swSymbol *sym) {
  swFields f;
  char what[160];
  snprintf(what, sizeof what, "muscle '%s'", sym->name);
  sema_fields(S, sym->def, 0, what, muscle_keys, NMUSCLE_KEYS, &f);
  swScope *sc = sym->scope;
  swLoc loc = sym->loc;
  swSceneMuscle m;
  memset(&m, 0, sizeof m);
  m.name = sym->full;
  m.loc = loc;
  m.attach_rod[0] = m.attach_rod[1] = -1;
  int ok = 1;

  /* rod fields that do not apply */
  static const struct { const char *key, *why; } rodonly[] = {
    {"start", "a muscle runs from 'from' to 'to'; write 'from' for its first end"},
    {"direction", "a muscle's direction follows from its 'from' and 'to'"},
    {"length", "a muscle's rest length follows from its 'from' and 'to'"},
    {"radius_start", "a muscle has one rest 'radius', shared out among its filaments"},
    {"radius_end", "a muscle has one rest 'radius', shared out among its filaments"},
    {"shape", "a muscle's filaments run straight between its attachments (through its 'via' "
              "points); a coiled actuator is a rod with shape = helix(...)"},
    {"rest_shape", "a muscle's filaments rest straight between its attachments; a coiled "
                   "actuator is a rod with rest_shape = helix(...)"},
    {"start_shape", "a muscle's filaments start straight between its attachments (through "
                    "its 'via' points)"},
  };
  for (size_t i = 0; i < sizeof rodonly / sizeof rodonly[0]; i++) {
    const swAst *e = sema_field(&f, rodonly[i].key);
    if (e) {
      diag_error(e->loc, "%s", rodonly[i].why);
      ok = 0;
    }
  }

  /* tissue: material and overrides; what neither gives is the runtime's */
  swTissue t;
  if (!sema_tissue(S, sc, &f, &t)) ok = 0;
  m.youngs = t.youngs;
  m.density = t.density;
  m.shear_modulus = t.shear_modulus;
  m.poisson = t.poisson;
  /* unsaid (neither the muscle nor its material): the variational law (2:
   * by default), as Gazzola's stiffens without bound as a filament shortens
   * (n ~ 1/e, c ~ 1/eps^3) and soft tissue under its own active stress, tens
   * of times its E, is squeezed and spins up (docs/physics.md, "Muscles and
   * the constitutive law"); `variational = false` keeps the reference's law */
  m.variational = t.variational < 0 ? 2 : t.variational;
  m.material = t.mat_name;
  const swAst *gv = sema_field(&f, "gravity");   /* gravity = false: weightless filaments */
  if (gv) {
    int truth = sema_truth(S, sc, gv, "'gravity'");
    if (truth < 0) ok = 0;
    else m.weightless = !truth;
  }
  if (!t.mat && !t.me && (!t.E_ast || !t.rho_ast)) {
    swMuscleDesc tissue;
    sw_muscle_desc_init(&tissue);
    if (!t.E_ast && !t.rho_ast)
      diag_warning(loc, "%s has no material; it gets the runtime's muscle tissue, E = %g Pa and "
                   "density = %g kg/m^3", what, tissue.youngs, tissue.density);
    else if (!t.E_ast)
      diag_warning(loc, "%s has no material and no E; it gets E = %g Pa", what, tissue.youngs);
    else
      diag_warning(loc, "%s has no material and no density; it gets density = %g kg/m^3", what,
                   tissue.density);
  }

  /* placement: from and to, each a point on a rod (tied) or a position */
  const swAst *from = sema_field(&f, "from"), *to = sema_field(&f, "to");
  if (!from || !to) {
    sema_missing(&f, loc, "%s needs '%s', %s (a point on a rod, e.g. humerus.at(0.1), or a position)",
               what, !from ? "from" : "to", !from ? "where it starts" : "where it ends");
    ok = 0;
  }
  /* a point on a rod ties the filaments there; a position leaves that end free */
  m.start = from ? sema_position_on(S, sc, from, "'from'", &m.attach_rod[0], &m.attach_node[0],
                                    &m.attach_node_c[0])
                 : val_error();
  m.end = to ? sema_position_on(S, sc, to, "'to'", &m.attach_rod[1], &m.attach_node[1],
                                &m.attach_node_c[1])
             : val_error();
  if (from && m.start.kind == VAL_ERROR) ok = 0;
  if (to && m.end.kind == VAL_ERROR) ok = 0;
  if (from && m.start.kind != VAL_ERROR && !end_on_body(S, sc, from, "'from'", what)) ok = 0;
  if (to && m.end.kind != VAL_ERROR && !end_on_body(S, sc, to, "'to'", what)) ok = 0;
  const swAst *via = sema_field(&f, "via");
  if (via && !eval_via(S, sc, sym, via, &m)) ok = 0;
  double axis[3] = {0, 0, 0};
  if (m.start.kind == VAL_VEC && m.end.kind == VAL_VEC) {
    /* the first segment's direction: to the first via point, or to 'to' */
    const swValue *next = m.nvia > 0 ? &m.via[0] : &m.end;
    for (int k = 0; k < 3; k++) axis[k] = next->v[k] - m.start.v[k];
    if (!m.nvia && !(fabs(axis[0]) + fabs(axis[1]) + fabs(axis[2]) > 0)) {
      diag_error(to->loc, "'to' is the same point as 'from', so the muscle has no length");
      ok = 0;
    }
  }
  if (sema_field(&f, "normal")) {
    m.normal = sema_field_value(S, sc, &f, "normal", 3, DIM_NONE);
    if (m.normal.kind == VAL_ERROR) ok = 0;
    else if (fabs(axis[0]) + fabs(axis[1]) + fabs(axis[2]) > 0) {
      const double *a = m.normal.v, *b = axis;
      double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2],
             cz = a[0] * b[1] - a[1] * b[0];
      if (!(cx * cx + cy * cy + cz * cz > 1e-24 * (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]))) {
        diag_error(m.normal.loc, "'normal' must not be parallel to the muscle (from 'from' to "
                   "'to')");
        ok = 0;
      }
    }
  }

  /* cross section and filaments */
  if (!sema_field(&f, "radius")) {
    sema_missing(&f, loc, "%s needs a 'radius', the whole muscle's rest radius (e.g. radius = 5 mm;)",
               what);
    ok = 0;
  } else {
    m.radius = sema_field_value(S, sc, &f, "radius", 1, DIM_LENGTH);
    if (m.radius.kind == VAL_ERROR || !sema_positive(S, &m.radius, "'radius'", "m")) ok = 0;
  }
  long filaments = 0;
  if (!sema_field(&f, "filaments")) {
    sema_missing(&f, loc, "%s needs 'filaments', the number of rods that stand for its motor units "
               "(e.g. filaments = 18;)", what);
    ok = 0;
  } else {
    swValue v = sema_field_value(S, sc, &f, "filaments", 1, DIM_NONE);
    if (!sema_const_int(S, v, "'filaments'", 1, MAX_FILAMENTS, &filaments)) ok = 0;
  }
  m.filaments = (int)filaments;
  if (sema_field(&f, "motor_units")) {
    swValue v = sema_field_value(S, sc, &f, "motor_units", 1, DIM_NONE);
    long mu = 0;
    if (!sema_const_int(S, v, "'motor_units'", 1, MAX_MOTOR_UNITS, &mu)) ok = 0;
    else if (filaments > 0 && mu < filaments) {
      diag_error(v.loc, "'motor_units' (%ld) must be at least 'filaments' (%ld): each filament "
                 "stands for a group of motor units", mu, filaments);
      ok = 0;
    } else m.motor_units = mu;
  }
  /* the runtime's default when not written; known here, for the scene's size */
  swMuscleDesc def;
  sw_muscle_desc_init(&def);
  long nelem = def.nelem;
  if (sema_field(&f, "elements")) {
    swValue ne = sema_field_value(S, sc, &f, "elements", 1, DIM_NONE);
    if (!sema_const_int(S, ne, "'elements'", 2, 100000, &nelem)) ok = 0;
    m.has_nelem = 1;
  }
  m.nelem = (int)nelem;
  long total = S->scene->nelem + filaments * nelem;
  if (ok && total > SEMA_MAX_ELEMENTS) {
    diag_error(loc, "the scene would have %ld elements with %s (%ld filaments of %ld); at most "
               "%d are allowed", total, what, filaments, nelem, SEMA_MAX_ELEMENTS);
    ok = 0;
  }

  /* contraction: a prescribed force, or sigma_max and the Hill law */
  const swAst *force = sema_field(&f, "force");
  if (force) {
    swValue v = sema_eval(S, sc, force);
    if (v.kind == VAL_WORD) {
      sema_report_unknown(S, sc, v.word, v.loc, "name");
      ok = 0;
    } else if (v.kind != VAL_ERROR && v.kind != VAL_NUM && v.kind != VAL_SIGNAL) {
      diag_error(v.loc, "'force' is a force or a time signal of one (e.g. force = 2 N * "
                 "ramp(0, 1, over = 0.1 s);), not %s", val_kind_noun(&v));
      ok = 0;
    } else if (v.kind != VAL_ERROR && !dim_eq(v.dim, dim_make(1, 1, -2, 0))) {
      diag_error(v.loc, "'force' is the muscle's pull, a force (N), got %s",
                 dim_describe(S->a, v.dim));
      ok = 0;
    } else if (v.kind == VAL_ERROR ||
               !(m.force = sema_scalar_signal(S, v, "'force' (the pull along the muscle)"))) {
      ok = 0;
    }
    static const char *const hill[] = {"sigma_max", "twitch_small", "twitch_large", "hill_a",
                                       "v_max"};
    for (int k = 0; k < 5; k++) {
      const swAst *h = sema_field(&f, hill[k]);
      if (h)
        diag_warning(h->loc, "'%s' has no effect on %s: it pulls with its prescribed 'force', "
                     "not by the Hill law", hill[k], what);
    }
  } else if (!sema_field(&f, "sigma_max")) {
    sema_missing(&f, loc, "%s needs 'sigma_max', its peak isometric stress: the force per area of "
               "a fully activated muscle at rest length (e.g. sigma_max = 300 kPa;)", what);
    ok = 0;
  } else {
    m.sigma_max = sema_field_value(S, sc, &f, "sigma_max", 1, DIM_PRESSURE);
    if (m.sigma_max.kind == VAL_ERROR) ok = 0;
    else must_be_positive(S, &m.sigma_max, "sigma_max", "Pa", &ok);
  }
  m.size_ratio = opt_scalar(S, sc, &f, "size_ratio", DIM_NONE, &ok);
  if (m.size_ratio.kind == VAL_NUM && !(m.size_ratio.v[0] >= 1)) {
    diag_error(m.size_ratio.loc, "'size_ratio' must be at least 1 (the largest filament's "
               "cross-section over the smallest's), got %g", m.size_ratio.v[0]);
    ok = 0;
  }
  m.twitch_small = opt_scalar(S, sc, &f, "twitch_small", DIM_TIME, &ok);
  m.twitch_large = opt_scalar(S, sc, &f, "twitch_large", DIM_TIME, &ok);
  not_negative(&m.twitch_small, "twitch_small", &ok);
  not_negative(&m.twitch_large, "twitch_large", &ok);
  m.hill_a = opt_scalar(S, sc, &f, "hill_a", DIM_NONE, &ok);
  must_be_positive(S, &m.hill_a, "hill_a", "", &ok);
  m.v_max = opt_scalar(S, sc, &f, "v_max", dim_make(0, 0, -1, 0), &ok);
  must_be_positive(S, &m.v_max, "v_max", "/s", &ok);
  m.fibre_diameter = opt_scalar(S, sc, &f, "fibre_diameter", DIM_LENGTH, &ok);
  must_be_positive(S, &m.fibre_diameter, "fibre_diameter", "m", &ok);
  m.attach_stiffness = opt_scalar(S, sc, &f, "attach_stiffness", dim_make(1, 0, -2, 0), &ok);
  m.attach_damping = opt_scalar(S, sc, &f, "attach_damping", dim_make(1, 0, -1, 0), &ok);
  not_negative(&m.attach_stiffness, "attach_stiffness", &ok);
  not_negative(&m.attach_damping, "attach_damping", &ok);
  if ((m.attach_stiffness.kind || m.attach_damping.kind) && m.attach_rod[0] < 0 &&
      m.attach_rod[1] < 0 && ok)
    diag_warning(sema_field(&f, m.attach_stiffness.kind ? "attach_stiffness" : "attach_damping")
                 ->loc, "%s is tied to no rod (neither 'from' nor 'to' is a point on a rod), so "
                 "'%s' has no effect", what,
                 m.attach_stiffness.kind ? "attach_stiffness" : "attach_damping");

  /* rod mechanics of each filament */
  m.shear_hardening = opt_scalar(S, sc, &f, "shear_hardening", DIM_NONE, &ok);
  m.twist_hardening = opt_scalar(S, sc, &f, "twist_hardening", DIM_NONE, &ok);
  must_be_positive(S, &m.shear_hardening, "shear_hardening", "", &ok);
  must_be_positive(S, &m.twist_hardening, "twist_hardening", "", &ok);
  m.gamma = opt_scalar(S, sc, &f, "damping", dim_make(1, -1, -1, 0), &ok);
  not_negative(&m.gamma, "damping", &ok);
  m.has_damping = sema_field(&f, "damping") != NULL;
  m.damping = sema_damping_kind(S, sc, &f, &ok);

  if (!ok) {
    sym->index = -1;
    return;
  }
  swScene *scn = S->scene;
  if (scn->nmuscle == scn->capmuscle) {
    scn->capmuscle = scn->capmuscle ? 2 * scn->capmuscle : 8;
    scn->muscle = realloc(scn->muscle, (size_t)scn->capmuscle * sizeof *scn->muscle);
    if (!scn->muscle) abort();
  }
  sym->index = scn->nmuscle;
  m.id = scn->nrodid;
  scn->nrodid += m.filaments;
  scn->nelem += (long)m.filaments * m.nelem;
  scn->muscle[scn->nmuscle++] = m;
}

/* ---- activate and passive ---- */

/* The muscle a statement names, evaluated; NULL after an error (reported). */
static swSymbol *muscle_target(swSema *S, swScope *scope, const swAst *e, const char *stmt) {
  swValue v = sema_eval(S, scope, e);
  if (v.kind == VAL_ERROR) return NULL;
  /* the muscles in scope, for "did you mean" */
  enum { MAXC = 256 };
  const char *cands[MAXC];
  int n = 0;
  for (swScope *s = scope; s; s = s->parent)
    for (int i = 0; i < s->n && n < MAXC; i++)
      if (s->sym[i]->kind == SYM_MUSCLE) cands[n++] = s->sym[i]->name;
  /* without a close name, the muscles there are (up to four) */
  char list[256] = "";
  if (n > 0) {
    snprintf(list, sizeof list, " (muscles here: ");
    for (int i = 0; i < n && i < 4; i++) {
      strncat(list, cands[i], sizeof list - strlen(list) - 1);
      strncat(list, i + 1 < n && i < 3 ? ", " : n > 4 ? ", ...)" : ")",
              sizeof list - strlen(list) - 1);
    }
  } else snprintf(list, sizeof list, " (there are no muscles here)");
  if (v.kind == VAL_WORD) {
    const char *near = diag_suggest(v.word, cands, n);
    char hint[300];
    if (near) {
      sema_lookup(S, scope, near)->used = 1;
      diag_error(v.loc, "unknown muscle '%s'; did you mean '%s'?", v.word, near);
    } else if (sema_member_hint(scope, v.word, SYM_MUSCLE, hint, sizeof hint)[0])
      diag_error(v.loc, "unknown muscle '%s'%s", v.word, hint);
    else diag_error(v.loc, "unknown muscle '%s'%s", v.word, list);
    return NULL;
  }
  if (v.kind == VAL_REF && v.ref->kind == SYM_MUSCLE) {
    sema_eval_symbol(S, v.ref);
    return v.ref->index >= 0 && v.ref->state == 2 ? v.ref : NULL;
  }
  if (v.kind == VAL_REF) {
    static const char *nouns[] = {"param", "let", "component parameter", "material", "rod",
                                  "joint", "component", "instance", "muscle"};
    const char *near = diag_suggest(v.ref->name, cands, n);
    if (near)
      diag_error(v.loc, "'%s' is a %s, not a muscle; did you mean '%s'?", v.ref->name,
                 nouns[v.ref->kind], near);
    else
      diag_error(v.loc, "'%s' is a %s, and '%s' applies to a muscle%s", v.ref->name,
                 nouns[v.ref->kind], stmt, list);
    return NULL;
  }
  diag_error(v.loc, "'%s' applies to a muscle, by its name", stmt);
  return NULL;
}

/* s * k for a value s of the signal (k a dimensionless number) */
static swValue scaled(swSema *S, swValue s, const swValue *k) {
  if (s.kind == VAL_ERROR) return s;
  return val_binop(S->a, '*', s, *k, s.loc);
}

/* A number or a scalar time signal as one swSignal (NULL after an error):
 * swSignal has no scale of its own, so a signal's scale is folded into its
 * values (a ramp's ends, a sine's mean and amplitude, a table's values, a
 * signal NAME(t)'s factor a). */
swSignalVal *sema_scalar_signal(swSema *S, swValue v, const char *what) {
  swSignalVal *sig = ast_alloc(S->a, sizeof *sig);
  memset(sig, 0, sizeof *sig);
  if (v.kind == VAL_NUM) {
    sig->kind = SW_SIG_CONST;
    sig->a = v;
  } else {
    if (v.sig->scale.kind != VAL_NUM) {
      diag_error(v.loc, "%s is a number or a time signal, not a vector", what);
      return NULL;
    }
    *sig = *v.sig;
    const swValue *k = &v.sig->scale;
    sig->a = scaled(S, sig->a, k);
    sig->b = scaled(S, sig->b, k);
    /* a table's and a B-spline's values are in values[], a and b unused */
    int listed = sig->kind == SW_SIG_TABLE || sig->kind == SW_SIG_BSPLINE;
    if (listed) sig->values = scaled(S, sig->values, k);
    if (listed ? sig->values.kind == VAL_ERROR : sig->a.kind == VAL_ERROR) return NULL;
    sig->scale = val_num(S->a, 1, DIM_NONE, v.loc);
  }
  sig->base = v.dim;
  return sig;
}

/* activate MUSCLE = ACTIVATION; */
void sema_activate(swSema *S, swScope *scope, const swAst *it) {
  if (it->nkid != 2) {
    diag_error(it->kid[0]->loc, "'activate' needs a value: activate MUSCLE = ACTIVATION; "
               "(a number from 0 to 1 or a time signal, e.g. ramp(0, 1, over = 0.1 s))");
    return;
  }
  swSymbol *mus = muscle_target(S, scope, it->kid[0], "activate");
  swValue v = sema_eval(S, scope, it->kid[1]);
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, scope, v.word, v.loc, "name");
    return;
  }
  if (v.kind == VAL_ERROR) return;
  if (v.kind != VAL_NUM && v.kind != VAL_SIGNAL) {
    diag_error(v.loc, "an activation is a number from 0 to 1 or a time signal "
               "(e.g. ramp(0, 1, over = 0.1 s)), not %s",
               val_kind_noun(&v));
    return;
  }
  if (!dim_is_none(v.dim)) {
    diag_error(v.loc, "an activation is dimensionless (0 = rest, 1 = full), got %s",
               dim_describe(S->a, v.dim));
    return;
  }
  if (v.kind == VAL_NUM && val_is_const(&v) && !(v.v[0] >= 0 && v.v[0] <= 1))
    diag_warning(v.loc, "an activation is clamped to [0, 1]: %g acts as %g", v.v[0],
                 v.v[0] < 0 ? 0.0 : 1.0);
  swSignalVal *sig = sema_scalar_signal(S, v, "an activation");
  if (!sig) return;
  if (!mus) return;
  swSceneMuscle *m = &S->scene->muscle[mus->index];
  if (m->activation) {
    char first[300];
    diag_error(it->loc, "muscle '%s' is activated twice (first at %s)", mus->name,
               diag_where_from(m->activation_loc, it->loc, first, sizeof first));
    return;
  }
  if (m->force) {
    diag_error(it->loc, "muscle '%s' pulls with its prescribed 'force'; it has no activation",
               mus->name);
    return;
  }
  m->activation = sig;
  m->activation_loc = it->loc;
}

/* passive MUSCLE.filament(K); */
void sema_passive(swSema *S, swScope *scope, const swAst *it) {
  if (it->nkid != 1) {
    diag_error(it->kid[1]->loc, "'passive' takes no '= value'");
    return;
  }
  const swAst *e = it->kid[0];
  const swAst *args = e->kind == AST_METHOD ? ast_kid(e, 1) : NULL;
  if (e->kind != AST_METHOD || strcmp(e->name, "filament") || !args || args->nkid != 1 ||
      args->kid[0]->name) {
    diag_error(e->loc, "'passive' names one filament of a muscle: passive MUSCLE.filament(K); "
               "with K from 1 (the smallest)");
    return;
  }
  swSymbol *mus = muscle_target(S, scope, e->kid[0], "passive");
  swValue k = sema_expect(S, scope, ast_kid(args->kid[0], 0), 1, DIM_NONE, "the filament number");
  if (!mus || k.kind == VAL_ERROR) return;
  if (!sema_require_const(S, &k, "the filament number")) return;
  const swSceneMuscle *m = &S->scene->muscle[mus->index];
  double x = k.v[0];
  if (x != floor(x) || x < 1 || x > m->filaments) {
    diag_error(k.loc, "muscle '%s' has filaments 1 to %d (1 is the smallest), not %g", mus->name,
               m->filaments, x);
    return;
  }
  swScene *scn = S->scene;
  for (int i = 0; i < scn->npassive; i++)
    if (scn->passive[i].muscle == mus->index && scn->passive[i].filament == (int)x - 1) {
      char first[300];
      diag_error(it->loc, "filament %d of muscle '%s' is already passive (%s)", (int)x,
                 mus->name, diag_where_from(scn->passive[i].loc, it->loc, first, sizeof first));
      return;
    }
  if (scn->npassive == scn->cappassive) {
    scn->cappassive = scn->cappassive ? 2 * scn->cappassive : 8;
    scn->passive = realloc(scn->passive, (size_t)scn->cappassive * sizeof *scn->passive);
    if (!scn->passive) abort();
  }
  swScenePassive p = {it->loc, mus->index, (int)x - 1};
  scn->passive[scn->npassive++] = p;
}
