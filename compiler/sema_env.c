/* sema_env.c — environments: ground, terrain, fluid, contact, obstacle and
 * torque_wave definitions, the probes of an output block, and the rod lists
 * they share.
 *
 * Design.  An environment is a definition like a rod ("ground floor { ... }",
 * or without a name, "ground { ... }", named after its kind), checked once
 * in file order against the keys its kind accepts, and appended to the
 * scene as a flat entry of swValues, so params keep their C expressions and
 * constants are folded.  A field the model does not give stays VAL_ERROR and
 * keeps the runtime's default (sw_*_desc_init), as a muscle's do; only what
 * the runtime cannot default (a ground's stiffness, a Stokes fluid's
 * viscosity, a wave's coefficients ...) is required here, with a message
 * that shows how to write it.  Rod lists are written as one name, a list in
 * parentheses or the word all; a muscle in a list stands for its filaments,
 * rods of component instances are reached as members (arm.humerus), and an
 * instance or a loop stands for every rod and muscle it holds.
 * They are resolved to runtime rod ids here, since ids are fixed once a rod
 * or muscle is evaluated.  The terrain's height(x, y) is sema_terrain.c's,
 * the obstacle sema_obstacle.c's (with this file's field helpers).
 * Physics: runtime/include/sinew.h "environments" and docs/physics.md.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sema_int.h"

static const char *const env_kinds[] = {"ground", "terrain", "fluid", "contact", "torque_wave",
                                        "obstacle"};
enum { ENV_GROUND, ENV_TERRAIN, ENV_FLUID, ENV_CONTACT, ENV_WAVE, ENV_OBSTACLE, NENV };

int sema_is_env_kind(const char *kind) {
  for (int k = 0; k < NENV; k++)
    if (!strcmp(kind, env_kinds[k])) return 1;
  return 0;
}

/* dimensions of the environments' fields */
static const swDim DIM_SPEED = {{0, 1, -1, 0}};       /* m/s  */
static const swDim DIM_VISCOSITY = {{1, -1, -1, 0}};  /* Pa s */
static const swDim DIM_TORQUE = {{1, 2, -2, 0}};      /* N m  */

/* Grows a scene array by one and returns the new slot (zeroed). */
void *sema_env_append(void **arr, int *n, int *cap, size_t item) {
  if (*n == *cap) {
    *cap = *cap ? 2 * *cap : 4;
    void *p = realloc(*arr, (size_t)*cap * item);
    if (!p) abort();
    *arr = p;
  }
  void *slot = (char *)*arr + (size_t)(*n)++ * item;
  memset(slot, 0, item);
  return slot;
}

/* ---- rod lists ---- */

/* A list being built: runtime rod ids and the names they were listed by. */
typedef struct {
  int *ids;
  const char **names;
  int n, cap;
} rodAcc;

/* Appends rod ids first .. first + count - 1 listed as `full`; 0 after an
 * error (a rod listed twice). */
static int add_rods(swSema *S, const swAst *e, const char *what, rodAcc *acc, int first, int count,
                    const char *full) {
  for (int k = 0; k < count; k++) {
    for (int i = 0; i < acc->n; i++)
      if (acc->ids[i] == first + k) {
        diag_error(e->loc, "'%s' is listed twice in %s", full, what);
        return 0;
      }
    if (acc->n == acc->cap) {
      int nc = acc->cap ? 2 * acc->cap : 8;
      int *ni = ast_alloc(S->a, (size_t)nc * sizeof *ni);
      const char **nn = ast_alloc(S->a, (size_t)nc * sizeof *nn);
      if (acc->n) {
        memcpy(ni, acc->ids, (size_t)acc->n * sizeof *ni);
        memcpy(nn, acc->names, (size_t)acc->n * sizeof *nn);
      }
      acc->ids = ni;
      acc->names = nn;
      acc->cap = nc;
    }
    acc->ids[acc->n] = first + k;
    acc->names[acc->n] = full;
    acc->n++;
  }
  return 1;
}

/* A rod, a muscle (its filaments), or every rod and muscle an instance or
 * a loop's passes hold, depth first in definition order. */
static int add_symbol(swSema *S, swSymbol *sym, const swAst *e, const char *what, rodAcc *acc) {
  sym->used = 1;
  char made[300];
  if (sym->kind == SYM_LOOP) {
    if (!sym->pass) {   /* its line comes later, or it failed (reported there) */
      if (sym->state != 2)
        diag_error(e->loc, "loop '%s' is used before the line that runs it (%s)", sym->name,
                   diag_where_from(sym->loc, e->loc, made, sizeof made));
      return 0;
    }
    for (int k = 0; k < sym->npass; k++)
      if (!add_symbol(S, sym->pass[k], e, what, acc)) return 0;
    return 1;
  }
  if (sym->kind == SYM_INSTANCE) {
    if (!sym->members) {   /* its 'use' comes later, or it failed (reported there) */
      if (sym->state != 2)
        diag_error(e->loc, "'%s' is used before the line that creates it (%s)", sym->name,
                   diag_where_from(sym->loc, e->loc, made, sizeof made));
      return 0;
    }
    for (int i = 0; i < sym->members->n; i++) {
      swSymbol *m = sym->members->sym[i];
      if (m->kind == SYM_ROD || m->kind == SYM_MUSCLE || m->kind == SYM_INSTANCE || m->kind == SYM_LOOP)
        if (!add_symbol(S, m, e, what, acc)) return 0;
    }
    return 1;
  }
  sema_eval_symbol(S, sym);
  if (sym->index < 0) return 0;   /* its own error is reported */
  if (sym->kind == SYM_ROD) return add_rods(S, e, what, acc, S->scene->rod[sym->index].id, 1, sym->full);
  return add_rods(S, e, what, acc, S->scene->muscle[sym->index].id,
                  S->scene->muscle[sym->index].filaments, sym->full);
}

/* One entry of a rod list: a rod, a muscle (its filaments), a component
 * instance or a loop (all the rods and muscles it holds).  Returns 0 after
 * an error. */
static int rod_entry(swSema *S, swScope *scope, const swAst *e, const char *what, rodAcc *acc) {
  swValue v = sema_eval(S, scope, e);
  if (v.kind == VAL_ERROR) return 0;
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, scope, v.word, v.loc, "rod");
    return 0;
  }
  if (v.kind != VAL_REF || (v.ref->kind != SYM_ROD && v.ref->kind != SYM_MUSCLE &&
                            v.ref->kind != SYM_INSTANCE && v.ref->kind != SYM_LOOP)) {
    diag_error(e->loc, "%s lists rods, muscles, instances and loops (or all), not %s", what,
               v.kind == VAL_REF ? "another kind of definition" : "a value");
    return 0;
  }
  return add_symbol(S, v.ref, e, what, acc);
}

int sema_rod_list(swSema *S, swScope *scope, const swAst *e, const char *what, swRodList *out) {
  memset(out, 0, sizeof *out);
  if (e->kind == AST_NAME && !strcmp(e->name, "all")) return 1;
  rodAcc acc = {0};
  int ok = 1;
  if (e->kind == AST_VEC) {
    for (int i = 0; i < e->nkid; i++) {
      if (e->kid[i]->kind == AST_NAME && !strcmp(e->kid[i]->name, "all")) {
        diag_error(e->kid[i]->loc, "'all' stands alone: write rods = all;");
        ok = 0;
        continue;
      }
      ok &= rod_entry(S, scope, e->kid[i], what, &acc);
    }
  } else {
    ok = rod_entry(S, scope, e, what, &acc);
  }
  out->id = acc.ids;
  out->name = acc.names;
  out->n = acc.n;
  return ok;
}

/* ---- fields ---- */

/* A number that must be >= 0 (friction, damping ...); 0 after an error. */
static int nonnegative(const swValue *v, const char *what) {
  for (int i = 0; v->kind != VAL_ERROR && i < v->n; i++)
    if (v->v[i] < 0) {
      diag_error(v->loc, "%s must not be negative, got %g", what, v->v[i]);
      return 0;
    }
  return 1;
}

/* A friction coefficient: one number (the same forward, backward and
 * sideways) or three (forward, backward, sideways), each >= 0. */
static swValue friction(swSema *S, swScope *sc, const swFields *f, const char *key) {
  const swAst *e = sema_field(f, key);
  if (!e) return val_error();
  swValue v = sema_eval(S, sc, e);
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, sc, v.word, v.loc, "name");
    return val_error();
  }
  char what[96];
  snprintf(what, sizeof what, "'%s' (forward, backward, sideways)", key);
  const char *w = ast_strdup(S->a, what, strlen(what));
  if (v.kind == VAL_NUM) {
    v = sema_expect_value(S, v, 1, DIM_NONE, w);
    if (v.kind == VAL_ERROR) return v;
    swValue three = val_vec(S->a, 3, NULL, DIM_NONE, v.loc);
    for (int k = 0; k < 3; k++) three.v[k] = v.v[0];
    if (v.c && v.c[0]) {
      three.c = ast_alloc(S->a, 3 * sizeof *three.c);
      for (int k = 0; k < 3; k++) three.c[k] = v.c[0];
      three.param = v.param;
    }
    v = three;
  } else {
    v = sema_expect_value(S, v, 3, DIM_NONE, w);
  }
  snprintf(what, sizeof what, "a friction coefficient ('%s')", key);
  if (!nonnegative(&v, what)) return val_error();
  return v;
}

/* An optional field of dimension `want` (n components) that must be >= 0
 * (pos = 0) or > 0 (pos = 1). */
swValue sema_env_bounded(swSema *S, swScope *sc, const swFields *f, const char *key, int n,
                       swDim want, int pos) {
  if (!sema_field(f, key)) return val_error();
  swValue v = sema_field_value(S, sc, f, key, n, want);
  char what[64];
  snprintf(what, sizeof what, "'%s'", key);
  if (v.kind == VAL_ERROR) return v;
  if (pos) {
    if (!(v.v[0] > 0)) {
      diag_error(v.loc, "%s must be positive, got %g", what, v.v[0]);
      return val_error();
    }
  } else if (!nonnegative(&v, what)) {
    return val_error();
  }
  return v;
}

swValue sema_env_nonzero_vector(swSema *S, swScope *sc, const swFields *f, const char *key,
                              swDim want) {
  if (!sema_field(f, key)) return val_error();
  swValue v = sema_field_value(S, sc, f, key, 3, want);
  if (v.kind == VAL_VEC && !(fabs(v.v[0]) + fabs(v.v[1]) + fabs(v.v[2]) > 0)) {
    diag_error(v.loc, "'%s' must not be the zero vector", key);
    return val_error();
  }
  return v;
}

int sema_env_rods_field(swSema *S, swScope *sc, const swFields *f, const char *what,
                      swRodList *out) {
  memset(out, 0, sizeof *out);
  const swAst *e = sema_field(f, "rods");
  if (!e) return 1;
  char w[160];
  snprintf(w, sizeof w, "'rods' of %s", what);
  return sema_rod_list(S, sc, e, ast_strdup(S->a, w, strlen(w)), out);
}

/* ---- the kinds ---- */

static const char *const ground_keys[] = {"normal", "origin", "stiffness", "damping", "mu_kinetic",
                                          "mu_static", "mu_rolling", "slip_velocity",
                                          "contact_point", "rods"};
static const char *const terrain_keys[] = {"height", "stiffness", "damping", "mu_kinetic",
                                           "mu_static", "mu_rolling", "slip_velocity",
                                           "contact_point", "rods"};
enum {
  NGROUND_KEYS = sizeof ground_keys / sizeof ground_keys[0],
  NTERRAIN_KEYS = sizeof terrain_keys / sizeof terrain_keys[0]
};

static void ground(swSema *S, swScope *sc, const swAst *it, const char *name, const char *what,
                   int terrain) {
  swFields f;
  if (terrain) sema_fields(S, it, 0, what, terrain_keys, NTERRAIN_KEYS, &f);
  else sema_fields(S, it, 0, what, ground_keys, NGROUND_KEYS, &f);
  swSceneGround g;
  memset(&g, 0, sizeof g);
  g.name = name;
  g.loc = it->loc;
  int ok = 1;
  if (terrain) {
    g.height = sema_height(S, sc, it, f.value[0], what);
    ok &= g.height != NULL;
    g.origin = g.normal = val_error();
  } else {
    g.origin = sema_field(&f, "origin") ? sema_field_value(S, sc, &f, "origin", 3, DIM_LENGTH)
               : val_error();
    g.normal = sema_env_nonzero_vector(S, sc, &f, "normal", DIM_NONE);
    ok &= !sema_field(&f, "origin") || g.origin.kind != VAL_ERROR;
    ok &= !sema_field(&f, "normal") || g.normal.kind != VAL_ERROR;
  }
  if (!sema_field(&f, "stiffness")) {
    sema_missing(&f, it->loc, "%s needs a 'stiffness' (the penalty of the surface, e.g. "
               "stiffness = 100 N/m;)", what);
    ok = 0;
  }
  g.stiffness = sema_env_bounded(S, sc, &f, "stiffness", 1, DIM_STIFFNESS, 1);
  g.damping = sema_env_bounded(S, sc, &f, "damping", 1, DIM_DAMPING, 0);
  g.mu_kinetic = friction(S, sc, &f, "mu_kinetic");
  g.mu_static = friction(S, sc, &f, "mu_static");
  g.mu_rolling = sema_env_bounded(S, sc, &f, "mu_rolling", 1, DIM_NONE, 0);
  g.slip_velocity = sema_env_bounded(S, sc, &f, "slip_velocity", 1, DIM_SPEED, 1);
  const char *keys[] = {"stiffness", "damping", "mu_kinetic", "mu_static", "mu_rolling",
                        "slip_velocity"};
  const swValue *vals[] = {&g.stiffness, &g.damping, &g.mu_kinetic, &g.mu_static, &g.mu_rolling,
                           &g.slip_velocity};
  for (int i = 0; i < 6; i++)
    if (sema_field(&f, keys[i]) && vals[i]->kind == VAL_ERROR) ok = 0;
  const swAst *cp = sema_field(&f, "contact_point");
  if (cp) {
    int t = sema_truth(S, sc, cp, "'contact_point'");
    if (t < 0) ok = 0;
    else g.contact_point = t;
  }
  ok &= sema_env_rods_field(S, sc, &f, what, &g.rods);
  if (!ok) return;
  swScene *scn = S->scene;
  *(swSceneGround *)sema_env_append((void **)&scn->ground, &scn->nground, &scn->capground, sizeof g) = g;
}

static const char *const fluid_keys[] = {"model", "viscosity", "density", "drag_coefficient",
                                         "area", "buoyancy", "flow", "body_length", "rods"};

static void fluid(swSema *S, swScope *sc, const swAst *it, const char *name, const char *what) {
  swFields f;
  sema_fields(S, it, 0, what, fluid_keys, 9, &f);
  swSceneFluid fl;
  memset(&fl, 0, sizeof fl);
  fl.name = name;
  fl.loc = it->loc;
  int ok = 1;
  fl.model = SW_FLUID_STOKES;
  const swAst *model = sema_field(&f, "model");
  if (model) {
    static const char *const models[] = {"stokes", "quadratic"};
    const char *w = sema_word(S, sc, model, "fluid model", models, 2);
    if (!w) ok = 0;
    else fl.model = !strcmp(w, "stokes") ? SW_FLUID_STOKES : SW_FLUID_QUADRATIC;
  }
  /* quadratic drag's A: the runtime's swFluidArea, in its order */
  fl.area = SW_FLUID_SILHOUETTE;
  const swAst *area = sema_field(&f, "area");
  if (area) {
    static const char *const areas[] = {"silhouette", "cross_section", "broadside"};
    const char *w = sema_word(S, sc, area, "fluid area", areas, 3);
    if (!w) ok = 0;
    else fl.area = !strcmp(w, "silhouette") ? SW_FLUID_SILHOUETTE
                   : !strcmp(w, "cross_section") ? SW_FLUID_CROSS_SECTION : SW_FLUID_BROADSIDE;
  }
  fl.viscosity = sema_env_bounded(S, sc, &f, "viscosity", 1, DIM_VISCOSITY, 1);
  fl.density = sema_env_bounded(S, sc, &f, "density", 1, DIM_DENSITY, 1);
  fl.drag_coefficient = sema_env_bounded(S, sc, &f, "drag_coefficient", 1, DIM_NONE, 1);
  fl.body_length = sema_env_bounded(S, sc, &f, "body_length", 1, DIM_LENGTH, 1);
  fl.velocity = sema_field(&f, "flow") ? sema_field_value(S, sc, &f, "flow", 3, DIM_SPEED)
                : val_error();
  const char *keys[] = {"viscosity", "density", "drag_coefficient", "body_length", "flow"};
  const swValue *vals[] = {&fl.viscosity, &fl.density, &fl.drag_coefficient, &fl.body_length,
                           &fl.velocity};
  for (int i = 0; i < 5; i++)
    if (sema_field(&f, keys[i]) && vals[i]->kind == VAL_ERROR) ok = 0;
  const swAst *b = sema_field(&f, "buoyancy");
  if (b) {
    int t = sema_truth(S, sc, b, "'buoyancy'");
    if (t < 0) ok = 0;
    else fl.buoyancy = t;
  }
  if (ok && fl.model == SW_FLUID_STOKES && !sema_field(&f, "viscosity")) {
    sema_missing(&f, it->loc, "%s: Stokes drag needs a 'viscosity' (e.g. viscosity = 1e-3 Pa s;)", what);
    ok = 0;
  }
  if (ok && fl.model == SW_FLUID_QUADRATIC &&
      (!sema_field(&f, "density") || !sema_field(&f, "drag_coefficient"))) {
    sema_missing(&f, it->loc, "%s: quadratic drag needs a 'density' and a 'drag_coefficient' (e.g. "
               "density = 1000 kg/m^3; drag_coefficient = 1.2;)", what);
    ok = 0;
  }
  if (ok && fl.buoyancy && !sema_field(&f, "density")) {
    diag_error(b->loc, "buoyancy needs the fluid's 'density'");
    ok = 0;
  }
  /* fields the chosen drag model does not read */
  static const char *const quadratic_only[] = {"drag_coefficient", "area"};
  const swAst *unused;
  for (int i = 0; ok && fl.model == SW_FLUID_STOKES && i < 2; i++)
    if ((unused = sema_field(&f, quadratic_only[i])))
      diag_warning(unused->loc, "'%s' has no effect on Stokes drag", quadratic_only[i]);
  static const char *const stokes_only[] = {"viscosity", "body_length"};
  for (int i = 0; ok && fl.model == SW_FLUID_QUADRATIC && i < 2; i++)
    if ((unused = sema_field(&f, stokes_only[i])))
      diag_warning(unused->loc, "'%s' has no effect on quadratic drag", stokes_only[i]);
  ok &= sema_env_rods_field(S, sc, &f, what, &fl.rods);
  if (!ok) return;
  swScene *scn = S->scene;
  *(swSceneFluid *)sema_env_append((void **)&scn->fluid, &scn->nfluid, &scn->capfluid, sizeof fl) = fl;
}

/* The friction of an obstacle or a rod-rod contact: `friction` (mu_s =
 * mu_k) or static_friction and kinetic_friction (either alone sets both),
 * and tangential_stiffness, into *mu_s, *mu_k, *k_t; 0 after an error. */
int sema_env_friction(swSema *S, swScope *sc, const swFields *f, const char *what, swValue *mu_s,
                      swValue *mu_k, swValue *k_t) {
  const swAst *one = sema_field(f, "friction"), *st = sema_field(f, "static_friction");
  const swAst *ki = sema_field(f, "kinetic_friction"), *kt = sema_field(f, "tangential_stiffness");
  *mu_s = *mu_k = *k_t = val_error();
  if (one && (st || ki)) {
    diag_error(one->loc, "%s: give either 'friction' (static and kinetic alike) or "
               "'static_friction' and 'kinetic_friction', not both", what);
    return 0;
  }
  int ok = 1;
  if (one) {
    *mu_s = *mu_k = sema_env_bounded(S, sc, f, "friction", 1, DIM_NONE, 0);
    ok &= mu_s->kind != VAL_ERROR;
  } else if (st || ki) {
    if (st) *mu_s = sema_env_bounded(S, sc, f, "static_friction", 1, DIM_NONE, 0);
    if (ki) *mu_k = sema_env_bounded(S, sc, f, "kinetic_friction", 1, DIM_NONE, 0);
    ok &= (!st || mu_s->kind != VAL_ERROR) && (!ki || mu_k->kind != VAL_ERROR);
    if (!st) *mu_s = *mu_k;
    if (!ki) *mu_k = *mu_s;
    if (ok && st && ki && mu_k->v[0] > mu_s->v[0]) {
      diag_error(mu_k->loc, "%s: 'kinetic_friction' (%g) must not exceed "
                 "'static_friction' (%g): a contact that slips would need more force to go on "
                 "slipping than to start", what, mu_k->v[0], mu_s->v[0]);
      ok = 0;
    }
  }
  if (kt) {
    *k_t = sema_env_bounded(S, sc, f, "tangential_stiffness", 1, DIM_STIFFNESS, 1);
    ok &= k_t->kind != VAL_ERROR;
    if (!one && !st && !ki)
      diag_warning(kt->loc, "'tangential_stiffness' has no effect without friction (friction = 0.3;)");
  }
  return ok;
}

static const char *const contact_keys[] = {"rods", "stiffness", "damping", "self", "friction",
                                           "static_friction", "kinetic_friction",
                                           "tangential_stiffness"};

static void contact(swSema *S, swScope *sc, const swAst *it, const char *name, const char *what) {
  swFields f;
  sema_fields(S, it, 0, what, contact_keys, (int)(sizeof contact_keys / sizeof contact_keys[0]), &f);
  swSceneContact c;
  memset(&c, 0, sizeof c);
  c.name = name;
  c.loc = it->loc;
  int ok = 1;
  if (!sema_field(&f, "stiffness")) {
    sema_missing(&f, it->loc, "%s needs a 'stiffness' (e.g. stiffness = 1e4 N/m;)", what);
    ok = 0;
  }
  c.stiffness = sema_env_bounded(S, sc, &f, "stiffness", 1, DIM_STIFFNESS, 1);
  c.damping = sema_env_bounded(S, sc, &f, "damping", 1, DIM_DAMPING, 0);
  if (sema_field(&f, "stiffness") && c.stiffness.kind == VAL_ERROR) ok = 0;
  if (sema_field(&f, "damping") && c.damping.kind == VAL_ERROR) ok = 0;
  ok &= sema_env_friction(S, sc, &f, what, &c.static_friction, &c.kinetic_friction,
                          &c.tangential_stiffness);
  const swAst *self = sema_field(&f, "self");
  if (self) {
    int t = sema_truth(S, sc, self, "'self'");
    if (t < 0) ok = 0;
    else c.self = t;
  }
  if (!sema_env_rods_field(S, sc, &f, what, &c.rods)) ok = 0;
  else if (c.rods.n == 1 && !c.self && (!self || ok)) {
    diag_error(sema_field(&f, "rods")->loc, "%s lists one rod and no self-contact, so nothing "
               "can touch: list two rods or more, or add self = true;", what);
    ok = 0;
  }
  if (!ok) return;
  swScene *scn = S->scene;
  *(swSceneContact *)sema_env_append((void **)&scn->contact, &scn->ncontact, &scn->capcontact,
                            sizeof c) = c;
}

static const char *const wave_keys[] = {"rod", "coefficients", "wavelength", "period", "phase",
                                        "ramp", "direction", "reverse"};

static void wave(swSema *S, swScope *sc, const swAst *it, const char *name, const char *what) {
  swFields f;
  sema_fields(S, it, 0, what, wave_keys, 8, &f);
  swSceneWave w;
  memset(&w, 0, sizeof w);
  w.name = name;
  w.loc = it->loc;
  int ok = 1;
  static const char *const required[] = {"rod", "coefficients", "wavelength", "period"};
  char missing[160] = "";
  int nmissing = 0;
  for (int i = 0; i < 4; i++)
    if (!sema_field(&f, required[i])) {
      size_t l = strlen(missing);
      snprintf(missing + l, sizeof missing - l, "%s'%s'", nmissing ? ", " : "", required[i]);
      nmissing++;
    }
  if (nmissing) {
    sema_missing(&f, it->loc, "%s needs %s (e.g. rod = snake; coefficients = (0, 17.4, 48.5, 5.4, "
               "14.7, 0) N m; wavelength = 1 m; period = 1 s;)", what, missing);
    ok = 0;
  }
  const swAst *re = sema_field(&f, "rod");
  if (re) {
    swRodList one;
    char wr[160];
    snprintf(wr, sizeof wr, "'rod' of %s", what);
    if (!sema_rod_list(S, sc, re, ast_strdup(S->a, wr, strlen(wr)), &one)) ok = 0;
    else if (one.n != 1) {
      diag_error(re->loc, "%s acts on one rod, not %s", what, one.n ? "several" : "all");
      ok = 0;
    } else {
      w.rod = one.id[0];
      w.rod_name = one.name[0];
    }
  }
  const swAst *ce = sema_field(&f, "coefficients");
  if (ce) {
    swValue v = sema_eval(S, sc, ce);
    if (v.kind == VAL_WORD) {
      sema_report_unknown(S, sc, v.word, v.loc, "name");
      v = val_error();
    }
    if (v.kind == VAL_NUM || v.kind == VAL_VEC) {
      if (v.n < 4 || v.n > SW_WAVE_MAXCOEF) {
        diag_error(v.loc, "'coefficients' of %s has %d values; the cubic B-spline of its "
                   "amplitude needs 4 to %d", what, v.n, SW_WAVE_MAXCOEF);
        v = val_error();
      } else {
        v = sema_expect_value(S, v, v.n, DIM_TORQUE, "'coefficients'");
      }
    } else if (v.kind != VAL_ERROR) {
      diag_error(v.loc, "'coefficients' is a list of couples: (0, 17.4, 48.5, 5.4, 14.7, 0) N m");
      v = val_error();
    }
    w.coef = v;
    if (v.kind == VAL_ERROR) ok = 0;
  }
  w.wavelength = sema_env_bounded(S, sc, &f, "wavelength", 1, DIM_LENGTH, 1);
  w.period = sema_env_bounded(S, sc, &f, "period", 1, DIM_TIME, 1);
  w.phase = sema_field(&f, "phase") ? sema_field_value(S, sc, &f, "phase", 1, DIM_ANGLE)
            : val_error();
  w.ramp = sema_env_bounded(S, sc, &f, "ramp", 1, DIM_TIME, 0);
  w.direction = sema_env_nonzero_vector(S, sc, &f, "direction", DIM_NONE);
  const char *keys[] = {"wavelength", "period", "phase", "ramp", "direction"};
  const swValue *vals[] = {&w.wavelength, &w.period, &w.phase, &w.ramp, &w.direction};
  for (int i = 0; i < 5; i++)
    if (sema_field(&f, keys[i]) && vals[i]->kind == VAL_ERROR) ok = 0;
  const swAst *rv = sema_field(&f, "reverse");
  if (rv) {
    int t = sema_truth(S, sc, rv, "'reverse'");
    if (t < 0) ok = 0;
    else w.reverse = t;
  }
  if (!ok) return;
  swScene *scn = S->scene;
  *(swSceneWave *)sema_env_append((void **)&scn->wave, &scn->nwave, &scn->capwave, sizeof w) = w;
}

void sema_env(swSema *S, swScope *scope, const swAst *it) {
  int k;
  for (k = 0; k < NENV; k++)
    if (!strcmp(it->text, env_kinds[k])) break;
  const char *name = it->name;
  if (name) {
    swSymbol *sym = sema_lookup_local(scope, name);
    if (sym) name = sym->full;
  } else {
    name = env_kinds[k];
  }
  char what[160];
  const char *noun = k == ENV_WAVE ? "torque wave" : env_kinds[k];
  if (it->name) snprintf(what, sizeof what, "%s '%s'", noun, name);
  else snprintf(what, sizeof what, "%s", noun);   /* ground { ... } */
  const char *w = ast_strdup(S->a, what, strlen(what));
  switch (k) {
  case ENV_GROUND: ground(S, scope, it, name, w, 0); break;
  case ENV_TERRAIN: ground(S, scope, it, name, w, 1); break;
  case ENV_FLUID: fluid(S, scope, it, name, w); break;
  case ENV_CONTACT: contact(S, scope, it, name, w); break;
  case ENV_OBSTACLE: sema_obstacle(S, scope, it, name, w); break;
  default: wave(S, scope, it, name, w); break;
  }
}

/* ---- probes: "probe NAME = WHAT;" in an output block ---- */

static const char *const probe_funcs[] = {"centre_of_mass", "velocity", "mean_velocity"};

/* The probe `fl` declares into *out (its name checked by the caller);
 * 0 when it is wrong (reported). */
static int make_probe(swSema *S, swScope *scope, const swAst *fl, swSceneProbe *out) {
  const swAst *target = ast_kid(fl, 1), *e = ast_kid(fl, 0);
  swScene *scn = S->scene;
  for (int i = 0; i < scn->nprobe; i++)
    if (!strcmp(scn->probe[i].name, target->name)) {
      char first[300];
      diag_error(target->loc, "probe '%s' is given twice (first at %s)", target->name,
                 diag_where_from(scn->probe[i].loc, target->loc, first, sizeof first));
      return 0;
    }
  swSceneProbe p;
  memset(&p, 0, sizeof p);
  p.name = target->name;
  p.loc = fl->loc;
  p.window = val_error();
  char what[160];
  if (e->kind == AST_CALL) {
    int k;
    for (k = 0; k < 3; k++)
      if (!strcmp(e->name, probe_funcs[k])) break;
    if (k == 3) {
      const char *near = diag_suggest(e->name, probe_funcs, 3);
      if (near) diag_error(e->loc, "unknown probe '%s'; did you mean '%s'?", e->name, near);
      else diag_error(e->loc, "unknown probe '%s' (expected centre_of_mass, velocity, "
                      "mean_velocity or a point on a rod)", e->name);
      return 0;
    }
    p.kind = k == 0 ? SW_PROBE_COM : k == 1 ? SW_PROBE_COM_VELOCITY : SW_PROBE_MEAN_VELOCITY;
    const swAst *args = ast_kid(e, 0);
    const swAst *rods = NULL;
    for (int i = 0; args && i < args->nkid; i++) {
      const swAst *a = args->kid[i];
      if (a->kind == AST_ARG && a->name && k == 2 && !strcmp(a->name, "window")) {
        p.window = sema_expect(S, scope, a->kid[0], 1, DIM_TIME, "'window' of mean_velocity()");
        if (p.window.kind == VAL_ERROR) return 0;
        if (!(p.window.v[0] > 0)) {
          diag_error(p.window.loc, "'window' of mean_velocity() must be positive, got %g s",
                     p.window.v[0]);
          return 0;
        }
      } else if (a->kind == AST_ARG && !a->name && i == 0) {
        rods = a->kid[0];
      } else {
        diag_error(a->loc, "%s() takes the rods (a name, a list in parentheses or all)%s",
                   e->name, k == 2 ? " and window = T" : "");
        return 0;
      }
    }
    if (!rods) {
      diag_error(e->loc, "%s() needs the rods it reads: %s(all), %s(snake)", e->name, e->name,
                 e->name);
      return 0;
    }
    snprintf(what, sizeof what, "probe '%s'", p.name);
    if (!sema_rod_list(S, scope, rods, ast_strdup(S->a, what, strlen(what)), &p.rods)) return 0;
  } else {
    swValue v = sema_eval(S, scope, e);
    if (v.kind == VAL_WORD) {
      sema_report_unknown(S, scope, v.word, v.loc, "rod");
      return 0;
    }
    if (v.kind == VAL_ERROR) return 0;
    if (v.kind != VAL_POINT) {
      diag_error(e->loc, "a probe reads a point on a rod (snake.end), centre_of_mass(rods), "
                 "velocity(rods) or mean_velocity(rods, window = T)");
      return 0;
    }
    if (!sema_point_fixed(&v, "the point a probe reads")) return 0;
    p.kind = SW_PROBE_NODE;
    p.rod = scn->rod[v.rod].id;
    p.rod_name = scn->rod[v.rod].name;
    p.node = v.node;
  }
  *out = p;
  return 1;
}

void sema_probe(swSema *S, swScope *scope, const swAst *fl) {
  const swAst *target = ast_kid(fl, 1);
  if (target && target->kind == AST_UNIT) {   /* probe h = ...: h is the hour */
    const swUnit *u = sw_unit_find(target->name, strlen(target->name));
    char dim[64] = "";
    if (u) sw_dim_describe(dim, sizeof dim, u->dim);
    diag_error(target->loc, "'%s' is a unit, of %s, and cannot name a probe; call the probe "
               "something else (e.g. 'height')", target->name, u ? dim : "a quantity");
    return;
  }
  if (!target || target->kind != AST_NAME) {
    diag_error(fl->loc, "a probe reads 'probe NAME = centre_of_mass(rods);'");
    return;
  }
  swSceneProbe p;
  if (make_probe(S, scope, fl, &p)) {
    swScene *scn = S->scene;
    *(swSceneProbe *)sema_env_append((void **)&scn->probe, &scn->nprobe, &scn->capprobe, sizeof p) = p;
  } else {
    *(const char **)sema_env_append((void **)&S->bad_probe, &S->nbad_probe, &S->capbad_probe,
                           sizeof(const char *)) = target->name;
  }
}
