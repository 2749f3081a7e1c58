/* sema_def.c — definitions: field tables, params, lets, materials, rods and
 * the points on rods.
 *
 * Design.  Each definition is evaluated once, on first use or in file order,
 * with its body's fields checked against the list of keys it accepts (an
 * unknown key gets the nearest known one).  A rod's fields fall back on its
 * material, then on the runtime's defaults; the checked rod is appended to
 * the scene with every field a swValue, so a param-dependent field keeps its
 * C expression.  Positions of points on a rod (start, end, at(f)) follow from
 * its straight rest shape: start + f * length * direction.  Muscles are in
 * sema_muscle.c, statements (joints, clamp, force, ...) in sema_stmt.c.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdarg.h>
#include <string.h>

#include "sema_int.h"

/* ---- field tables ---- */

void sema_missing(const swFields *f, swLoc loc, const char *fmt, ...) {
  if (!sema_fields_whole(f)) return; /* lost or misspelt: already reported */
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  diag_error(loc, "%s", msg);
}

void sema_fields(swSema *S, const swAst *body, int first, const char *what,
                 const char *const *keys, int nkeys, swFields *f) {
  (void)S;
  if (nkeys > SEMA_MAX_FIELDS) abort();   /* a key table longer than swFields holds */
  f->keys = keys;
  f->nkeys = nkeys;
  f->damaged = body && body->damaged;
  f->unknown = 0;
  for (int k = 0; k < SEMA_MAX_FIELDS; k++) f->value[k] = NULL;
  for (int i = first; body && i < body->nkid; i++) {
    const swAst *fl = body->kid[i];
    if (fl->kind == AST_SELECT) {
      diag_error(fl->loc, "expected '%s = value;' in %s", fl->name, what);
      continue;
    }
    /* a let in a body and "key(x, y) = value" are a terrain's height(x, y)'s
     * (sema_terrain.c); a body whose keys have no height takes neither */
    int takes_height = 0;
    for (int k = 0; k < nkeys; k++) takes_height |= !strcmp(keys[k], "height");
    if (fl->kind == AST_LET && !takes_height) {
      diag_error(fl->loc, "a 'let' inside %s is not allowed (only a terrain's body has lets); "
                 "put it at file level", what);
      continue;
    }
    if (fl->kind != AST_FIELD) continue;
    int k;
    for (k = 0; k < nkeys; k++)
      if (!strcmp(fl->name, keys[k])) break;
    if (k < nkeys && fl->nkid > 1 && strcmp(fl->name, "height")) {
      diag_error(fl->loc, "'%s' is a value, not a function: write '%s = ...;'", fl->name,
                 fl->name);
      continue;
    }
    if (k == nkeys) {
      f->unknown = 1;
      const char *near = diag_suggest(fl->name, keys, nkeys);
      swLoc at = fl->loc;
      if (near)
        diag_error(at, "%s has no field '%s'; did you mean '%s'?", what, fl->name, near);
      else
        diag_error(at, "%s has no field '%s'", what, fl->name);
      continue;
    }
    if (f->value[k]) {
      char first_at[300];
      diag_error(fl->loc, "field '%s' is given twice (first at %s)", fl->name,
                 diag_where_from(f->value[k]->loc, fl->loc, first_at, sizeof first_at));
      continue;
    }
    f->value[k] = fl;
  }
}

const swAst *sema_field(const swFields *f, const char *key) {
  for (int k = 0; k < f->nkeys; k++)
    if (!strcmp(f->keys[k], key)) return f->value[k] ? f->value[k]->kid[0] : NULL;
  return NULL;
}

swValue sema_field_value(swSema *S, swScope *scope, const swFields *f, const char *key, int n,
                         swDim want) {
  const swAst *e = sema_field(f, key);
  if (!e) return val_error();
  char what[64];
  snprintf(what, sizeof what, "'%s'", key);
  return sema_expect(S, scope, e, n, want, ast_strdup(S->a, what, strlen(what)));
}


/* ---- params and lets ---- */

/* Whether every leaf of e other than `num` is a unit or an exponent. */
static int units_only(const swAst *e, const swAst *num) {
  if (e == num || e->kind == AST_UNIT) return 1;
  if (e->kind == AST_NUM) return 0;
  if (e->kind == AST_NEG) return units_only(e->kid[0], num);   /* -180 deg */
  if (e->kind == AST_BINOP && e->op == '^') return e->kid[0]->kind == AST_UNIT;
  if (e->kind == AST_APPLY || e->kind == AST_BINOP)
    return units_only(e->kid[0], num) && units_only(e->kid[1], num);
  return 0;
}

/* param NAME = V in (LO, HI): the range a study varies the param over;
 * constants of its dimension, LO below HI, V within [LO, HI].  After an
 * error the param stays, without a range. */
static void param_range(swSema *S, const swSymbol *sym, const swAst *range, int idx) {
  /* the bounds may name params, evaluated (and added to the table) here */
  const swValue value = S->scene->param[idx].value;
  const swAst *pair = ast_kid(range, 0);
  if (pair->kind != AST_VEC || pair->nkid != 2) {
    diag_error(pair->loc, "the range of param '%s' is two values: in (LO, HI)", sym->name);
    return;
  }
  char what[160];
  snprintf(what, sizeof what, "the range of param '%s'", sym->name);
  const char *w = ast_strdup(S->a, what, strlen(what));
  double b[2] = {0, 0};
  int ok = 1;
  for (int k = 0; k < 2; k++) {
    swValue v = sema_expect(S, sym->scope, pair->kid[k], 1, value.dim, w);
    if (v.kind == VAL_ERROR || !sema_require_const(S, &v, w)) ok = 0;
    else b[k] = v.v[0];
  }
  if (!ok) return;
  const char *text = sema_source_text(S, pair->loc);
  if (!(b[0] < b[1])) {
    diag_error(pair->loc, "the range %s of param '%s' is empty: its lower bound must be below "
               "its upper bound", text, sym->name);
    return;
  }
  if (!(value.v[0] >= b[0] && value.v[0] <= b[1])) {
    diag_error(sym->def->kid[0]->loc, "the value of param '%s' is outside its range %s (a "
               "study starts from it)", sym->name, text);
    return;
  }
  swSceneParam *p = &S->scene->param[idx];
  p->ranged = 1;
  p->lo = b[0];
  p->hi = b[1];
}

static void eval_param(swSema *S, swSymbol *sym) {
  const swAst *def = sym->def;
  swValue v = sema_eval(S, sym->scope, def->kid[0]);
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, sym->scope, v.word, v.loc, "name");
    v = val_error();
  }
  if (v.kind == VAL_TRUTH) {
    diag_error(def->kid[0]->loc, "a param is a number the simulator can change when it runs "
               "(--set); %s is fixed when the model is compiled: make '%s' a let (sinewc --let "
               "changes it)", v.word, sym->name);
    v = val_error();
  }
  if (v.kind != VAL_ERROR && v.kind != VAL_NUM) {
    diag_error(def->kid[0]->loc, "a param must be a number (with a unit or without)");
    v = val_error();
  }
  if (v.kind != VAL_ERROR && !val_is_const(&v)) {
    diag_error(def->kid[0]->loc, "the default of param '%s' cannot depend on param '%s'",
               sym->name, v.param);
    v = val_error();
  }
  if (v.kind == VAL_ERROR) {
    sym->value = v;
    return;
  }
  swScene *sc = S->scene;
  if (sc->nparam == sc->capparam) {
    sc->capparam = sc->capparam ? 2 * sc->capparam : 8;
    sc->param = realloc(sc->param, (size_t)sc->capparam * sizeof *sc->param);
    if (!sc->param) abort();
  }
  int idx = sc->nparam++;
  swSceneParam *p = &sc->param[idx];
  memset(p, 0, sizeof *p);   /* no range until param_range finds one */
  p->name = sym->full;
  p->loc = sym->loc;
  p->value = v;
  /* the unit as written, when the default is "number unit" */
  p->unit = "";
  /* "number unit-expression" on one line: keep the unit as written, for
   * --help ("0.34 m", "1 N s/m") */
  const swAst *e = def->kid[0], *num = e;
  while (num->kind == AST_APPLY || num->kind == AST_NEG ||
         (num->kind == AST_BINOP && num->op != '^' && num->op != '+' && num->op != '-'))
    num = num->kid[0];
  if (num->kind == AST_NUM && num != e && units_only(e, num) && e->loc.line == e->loc.end_line) {
    const swSource *f = diag_file(e->loc.file);
    if (f) {   /* the text after the number, blanks skipped */
      const char *from = diag_at(f, e->loc.line, num->loc.end_col + 1);
      const char *to = diag_at(f, e->loc.line, e->loc.end_col + 1);
      while (from < to && (*from == ' ' || *from == '\t')) from++;
      if (to > from) p->unit = ast_strdup(S->a, from, (size_t)(to - from));
    }
  }
  const swAst *range = ast_kid(def, 1);
  if (range) param_range(S, sym, range, idx);
  sym->index = idx;
  char buf[32];
  snprintf(buf, sizeof buf, "P[%d]", idx);
  sym->value = v;
  sym->value.c = ast_alloc(S->a, sizeof *sym->value.c);
  sym->value.c[0] = ast_strdup(S->a, buf, strlen(buf));
  sym->value.param = sym->full;
}

/* sinewc --let NAME=VALUE on the top-level let `sym` of the main file,
 * just evaluated: the given value replaces the let's own when it is of the
 * same kind (true or false, or a number of the same dimension); otherwise
 * the override's error says why, and the let keeps its value. */
static void let_override(swSema *S, swSymbol *sym) {
  swLetOverride *o = NULL;
  for (int i = 0; i < S->nlets && !o; i++)
    if (!strcmp(S->lets[i].name, sym->name)) o = &S->lets[i];
  if (!o) return;
  o->applied = 1;
  o->let_loc = sym->loc;
  const swValue *own = &sym->value;
  if (own->kind == VAL_ERROR) return;   /* the model's own error, reported */
  char where[256], msg[512];
  diag_where(sym->loc, where, sizeof where);
  const char *value = strchr(o->text, '=') + 1;
  msg[0] = 0;
  if (own->kind == VAL_TRUTH) {
    if (o->truth < 0)
      snprintf(msg, sizeof msg, "--let %s: the let at %s is true or false, not a number "
               "('%s')", o->name, where, value);
  } else if (own->kind != VAL_NUM) {
    snprintf(msg, sizeof msg, "--let %s: the let at %s is %s; --let gives a let a number or "
             "true or false", o->name, where, val_kind_noun(own));
  } else if (o->truth >= 0) {
    snprintf(msg, sizeof msg, "--let %s: the let at %s is a number (%s), not true or false",
             o->name, where, dim_describe(S->a, own->dim));
  } else if (!dim_eq(own->dim, o->dim)) {
    /* as the simulator's --set words it */
    if (dim_is_none(o->dim))
      snprintf(msg, sizeof msg, "--let %s: expected %s, as the let at %s, got a number without "
               "a unit in '%s'", o->name, dim_describe(S->a, own->dim), where, value);
    else
      snprintf(msg, sizeof msg, "--let %s: expected %s, as the let at %s, got %s in '%s'",
               o->name, dim_describe(S->a, own->dim), where, dim_describe(S->a, o->dim), value);
  }
  if (msg[0]) {
    o->error = ast_strdup(S->a, msg, strlen(msg));
    return;
  }
  /* the value stands where the let's own was written */
  swLoc at = own->loc;
  sym->value = o->truth >= 0 ? val_truth(o->truth, at) : val_num(S->a, o->value, o->dim, at);
}

/* ---- materials ---- */

static const char *const material_keys[] = {"E", "G", "poisson", "density", "variational"};
enum { NMATERIAL_KEYS = sizeof material_keys / sizeof material_keys[0] };

static void eval_material(swSema *S, swSymbol *sym) {
  swFields f;
  char what[128];
  snprintf(what, sizeof what, "material '%s'", sym->name);
  sema_fields(S, sym->def, 0, what, material_keys, NMATERIAL_KEYS, &f);
  swMaterial *m = ast_alloc(S->a, sizeof *m);
  m->E = sema_field_value(S, sym->scope, &f, "E", 1, DIM_PRESSURE);
  m->G = sema_field_value(S, sym->scope, &f, "G", 1, DIM_PRESSURE);
  m->poisson = sema_field_value(S, sym->scope, &f, "poisson", 1, DIM_NONE);
  m->density = sema_field_value(S, sym->scope, &f, "density", 1, DIM_DENSITY);
  if (!sema_field(&f, "E"))
    sema_missing(&f, sym->loc, "material '%s' needs Young's modulus E (e.g. E = 10 kPa;)", sym->name);
  if (!sema_field(&f, "density"))
    sema_missing(&f, sym->loc, "material '%s' needs a density (e.g. density = 1.06 g/cm^3;)", sym->name);
  if (m->E.kind == VAL_NUM && !(m->E.v[0] > 0))
    diag_error(m->E.loc, "E must be positive, got %g Pa", m->E.v[0]);
  if (m->density.kind == VAL_NUM && !(m->density.v[0] > 0))
    diag_error(m->density.loc, "density must be positive, got %g kg/m^3", m->density.v[0]);
  if (m->poisson.kind == VAL_NUM && !(m->poisson.v[0] > -1 && m->poisson.v[0] <= 0.5))
    diag_error(m->poisson.loc, "poisson must be in (-1, 0.5], got %g", m->poisson.v[0]);
  /* variational = true: rods of this material take the law whose loads are
   * the gradient of their elastic energy (the runtime's rod.c); a switch,
   * so fixed when compiling, through a let or component parameter too */
  const swAst *var = sema_field(&f, "variational");
  m->variational = var ? sema_truth(S, sym->scope, var, "'variational'") > 0 : 0;
  sym->material = m;
}

/* material = NAME and the per-definition overrides E, G, poisson, density
 * and variational of a rod or a muscle.  Each value comes from the override, else from the
 * material; one given by neither stays VAL_ERROR.  Returns 0 after an error
 * (reported here, or in the material). */
int sema_tissue(swSema *S, swScope *sc, const swFields *f, swTissue *t) {
  memset(t, 0, sizeof *t);
  int ok = 1;
  t->me = sema_field(f, "material");
  if (t->me) {
    swValue mv = sema_eval(S, sc, t->me);
    if (mv.kind == VAL_WORD) {
      sema_report_unknown(S, sc, mv.word, mv.loc, "material");
      ok = 0;
    } else if (mv.kind == VAL_REF && mv.ref->kind == SYM_MATERIAL) {
      sema_eval_symbol(S, mv.ref);
      t->mat = mv.ref->material;
      t->mat_name = mv.ref->full;
    } else if (mv.kind != VAL_ERROR && t->me->kind == AST_UNIT) {
      diag_error(t->me->loc, "'%s' is a unit, so it cannot name a material", t->me->name);
      ok = 0;
    } else if (mv.kind != VAL_ERROR) {
      diag_error(t->me->loc, "'material' expects the name of a material");
      ok = 0;
    } else ok = 0;
  }
  const swMaterial *mat = t->mat;
  t->E_ast = sema_field(f, "E");
  t->rho_ast = sema_field(f, "density");
  const swAst *G_ast = sema_field(f, "G"), *nu_ast = sema_field(f, "poisson");
  t->youngs = t->E_ast ? sema_field_value(S, sc, f, "E", 1, DIM_PRESSURE)
              : mat ? mat->E : val_error();
  t->density = t->rho_ast ? sema_field_value(S, sc, f, "density", 1, DIM_DENSITY)
               : mat ? mat->density : val_error();
  t->shear_modulus = G_ast ? sema_field_value(S, sc, f, "G", 1, DIM_PRESSURE)
                     : mat ? mat->G : val_error();
  t->poisson = nu_ast ? sema_field_value(S, sc, f, "poisson", 1, DIM_NONE)
               : mat ? mat->poisson : val_error();
  /* a value written here that failed, or the material's E or density
   * (required there, so reported there) */
  if ((t->E_ast || mat) && t->youngs.kind == VAL_ERROR) ok = 0;
  if ((t->rho_ast || mat) && t->density.kind == VAL_ERROR) ok = 0;
  if (G_ast && t->shear_modulus.kind == VAL_ERROR) ok = 0;
  if (nu_ast && t->poisson.kind == VAL_ERROR) ok = 0;
  if (nu_ast && t->poisson.kind == VAL_NUM && !(t->poisson.v[0] > -1 && t->poisson.v[0] <= 0.5)) {
    diag_error(t->poisson.loc, "poisson must be in (-1, 0.5], got %g", t->poisson.v[0]);
    ok = 0;
  }
  if (G_ast && t->shear_modulus.kind == VAL_NUM && !(t->shear_modulus.v[0] > 0)) {
    diag_error(t->shear_modulus.loc, "G must be positive, got %g Pa", t->shear_modulus.v[0]);
    ok = 0;
  }
  const swAst *var = sema_field(f, "variational");
  if (var) {
    int truth = sema_truth(S, sc, var, "'variational'");
    if (truth < 0) ok = 0;
    else t->variational = truth;
  } else if (mat) t->variational = mat->variational;
  if (t->E_ast && t->youngs.kind == VAL_NUM) sema_positive(S, &t->youngs, "E", "Pa");
  if (t->rho_ast && t->density.kind == VAL_NUM) sema_positive(S, &t->density, "density", "kg/m^3");
  return ok;
}

/* ---- rods ---- */

static const char *const rod_keys[] = {
  "material", "start", "from", "to", "direction", "normal", "length", "radius", "radius_start",
  "radius_end", "elements", "E", "G", "poisson", "density", "shear_hardening",
  "twist_hardening", "rest_curvature", "rest_strain", "damping", "rotational_damping",
  "damping_model", "rigid", "variational", "implicit", "gravity",
};
enum { NROD_KEYS = sizeof rod_keys / sizeof rod_keys[0] };

static swRodKind rod_kind(const char *word) {
  if (!strcmp(word, "bone")) return ROD_BONE;
  if (!strcmp(word, "tendon")) return ROD_TENDON;
  return ROD_PLAIN;
}

swValue sema_vec3(swSema *S, double x, double y, double z, swDim dim, swLoc loc) {
  double v[3] = {x, y, z};
  return val_vec(S->a, 3, v, dim, loc);
}

int sema_positive(swSema *S, const swValue *v, const char *what, const char *unit) {
  (void)S;
  if (v->kind != VAL_NUM) return 0;
  if (!(v->v[0] > 0)) {
    diag_error(v->loc, "%s must be positive, got %g%s%s", what, v->v[0], unit[0] ? " " : "", unit);
    return 0;
  }
  return 1;
}

/* A position: a point on a rod, or a length vector.  When rod, node and
 * node_c are given they receive the rod, the node and the node's C text (NULL
 * unless a param moves it) of a point on a rod; -1, 0 and NULL else. */
swValue sema_position_on(swSema *S, swScope *scope, const swAst *e, const char *what, int *rod,
                         int *node, const char **node_c) {
  if (rod) *rod = -1;
  if (node) *node = 0;
  if (node_c) *node_c = NULL;
  swValue v = sema_eval(S, scope, e);
  if (v.kind == VAL_POINT) {
    if (rod) *rod = v.rod;
    if (node) *node = v.node;
    if (node_c) *node_c = v.node_c;
    v.kind = VAL_VEC;
    return v;
  }
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, scope, v.word, v.loc, "name");
    return val_error();
  }
  return sema_expect_value(S, v, 3, DIM_LENGTH, what);
}

swValue sema_position(swSema *S, swScope *scope, const swAst *e, const char *what) {
  return sema_position_on(S, scope, e, what, NULL, NULL, NULL);
}

/* The damping kind of a definition with fields `damping` (and, on rods,
 * `rotational_damping`) and `damping_model` (rods and muscles): none without
 * either damping, else linear unless damping_model says analytic.  A
 * damping_model that is no model is reported, leaves the default kind and
 * clears *ok (when ok is given). */
swDampingKind sema_damping_kind(swSema *S, swScope *sc, const swFields *f, int *ok) {
  const int damped = sema_field(f, "damping") || sema_field(f, "rotational_damping");
  swDampingKind kind = damped ? SW_DAMP_LINEAR : SW_DAMP_NONE;
  const swAst *dm = sema_field(f, "damping_model");
  if (!dm) return kind;
  static const char *const models[] = {"linear", "analytic"};
  const char *w = sema_word(S, sc, dm, "damping model", models, 2);
  if (!w && ok) *ok = 0;
  else if (w && !strcmp(w, "analytic")) kind = SW_DAMP_ANALYTIC;
  if (!damped) diag_warning(dm->loc, "'damping_model' has no effect without 'damping'");
  return kind;
}

/* Each component of v that depends on a param through more than a bare
 * P[k] or D[k] becomes a derived quantity D[k] of the scene (swSceneDerived),
 * so that expressions built on it stay short: a rib laid from a point that a
 * param moves, a tendon from that rib's end and a joint at that tendon's
 * start would otherwise each repeat the whole chain.  what names it in the
 * generated C. */
static void derive(swSema *S, swValue *v, const char *what, swLoc loc) {
  if (!v->c || (v->kind != VAL_NUM && v->kind != VAL_VEC && v->kind != VAL_POINT)) return;
  for (int i = 0; i < v->n; i++)   /* a reduction of the run: the objective's own */
    if (v->c[i] && strstr(v->c[i], "R[")) return;
  const char **c = ast_alloc(S->a, (size_t)v->n * sizeof *c);
  for (int i = 0; i < v->n; i++) {
    c[i] = v->c[i];
    int len = 0, k;
    if (!c[i] || ((sscanf(c[i], "P[%d]%n", &k, &len) == 1 ||
                   sscanf(c[i], "D[%d]%n", &k, &len) == 1) && c[i][len] == '\0'))
      continue;
    swScene *scn = S->scene;
    if (scn->nderived == scn->capderived) {
      scn->capderived = scn->capderived ? 2 * scn->capderived : 16;
      scn->derived = realloc(scn->derived, (size_t)scn->capderived * sizeof *scn->derived);
      if (!scn->derived) abort();
    }
    char name[512], ref[32];
    if (v->n == 1) snprintf(name, sizeof name, "%s", what);
    else if (v->n <= 3) snprintf(name, sizeof name, "%s.%c", what, "xyz"[i]);
    else snprintf(name, sizeof name, "%s[%d]", what, i);
    swSceneDerived *d = &scn->derived[scn->nderived];
    d->text = c[i];
    d->what = ast_strdup(S->a, name, strlen(name));
    d->loc = loc;
    snprintf(ref, sizeof ref, "D[%d]", scn->nderived++);
    c[i] = ast_strdup(S->a, ref, strlen(ref));
  }
  v->c = c;
}

static void eval_rod(swSema *S, swSymbol *sym) {
  swFields f;
  char what[160];
  snprintf(what, sizeof what, "%s '%s'", sym->def->text, sym->name);
  sema_fields(S, sym->def, 0, what, rod_keys, NROD_KEYS, &f);
  swScope *sc = sym->scope;
  swSceneRod r;
  memset(&r, 0, sizeof r);
  r.name = sym->full;
  r.kind = rod_kind(sym->def->text);
  r.loc = sym->loc;
  swLoc loc = sym->loc;
  int ok = 1;

  /* material, then rod-level overrides; without them, defaults and a warning */
  swTissue t;
  if (!sema_tissue(S, sc, &f, &t)) ok = 0;
  r.youngs = t.youngs.kind || t.mat ? t.youngs : val_num(S->a, 1e6, DIM_PRESSURE, loc);
  r.density = t.density.kind || t.mat ? t.density : val_num(S->a, 1000, DIM_DENSITY, loc);
  r.shear_modulus = t.shear_modulus.kind ? t.shear_modulus : val_num(S->a, 0, DIM_PRESSURE, loc);
  r.poisson = t.poisson.kind ? t.poisson : val_num(S->a, 0.5, DIM_NONE, loc);
  r.variational = t.variational;
  r.material = t.mat_name;
  r.has_material = t.mat != NULL || (t.E_ast && t.rho_ast);
  if (!t.mat && !t.me && !t.E_ast && !t.rho_ast)
    diag_warning(loc, "%s has no material; it gets E = %g Pa and density = %g kg/m^3", what,
                 r.youngs.kind == VAL_NUM ? r.youngs.v[0] : 0,
                 r.density.kind == VAL_NUM ? r.density.v[0] : 0);
  else if (!t.mat && !t.me && !t.E_ast)
    diag_warning(loc, "%s has no material and no E; it gets E = %g Pa", what,
                 r.youngs.kind == VAL_NUM ? r.youngs.v[0] : 0);
  else if (!t.mat && !t.me && !t.rho_ast)
    diag_warning(loc, "%s has no material and no density; it gets density = %g kg/m^3", what,
                 r.density.kind == VAL_NUM ? r.density.v[0] : 0);

  /* placement: start/from, and either to or direction + length */
  const swAst *start = sema_field(&f, "start"), *from = sema_field(&f, "from");
  const swAst *to = sema_field(&f, "to"), *dir = sema_field(&f, "direction");
  const swAst *len = sema_field(&f, "length");
  if (start && from) {
    diag_error(from->loc, "give either 'start' or 'from', not both");
    ok = 0;
  }
  const swAst *s0 = start ? start : from;
  if (!s0) {
    sema_missing(&f, loc, "%s needs a 'start' (or 'from') position", what);
    ok = 0;
    r.start = val_error();
  } else r.start = sema_position(S, sc, s0, start ? "'start'" : "'from'");
  char field[512];
  const char *name = sym->full ? sym->full : sym->name;
  snprintf(field, sizeof field, "rod %s: start", name);
  derive(S, &r.start, field, sym->loc);
  if (to) {
    if (dir || len) {
      diag_error(to->loc, "give either 'to', or 'direction' and 'length', not both");
      ok = 0;
    }
    swValue end = sema_position(S, sc, to, "'to'");
    swValue d = val_binop(S->a, '-', end, r.start, to->loc);
    /* a param that moves the ends: the axis and its length once each */
    snprintf(field, sizeof field, "rod %s: to - from", name);
    derive(S, &d, field, sym->loc);
    r.length = val_norm(S->a, d, to->loc);
    snprintf(field, sizeof field, "rod %s: length", name);
    derive(S, &r.length, field, sym->loc);
    if (r.length.kind == VAL_NUM && !(r.length.v[0] > 0)) {
      diag_error(to->loc, "'to' is the same point as the start, so the rod has no length");
      ok = 0;
    }
    r.direction = r.length.kind == VAL_NUM ? val_binop(S->a, '/', d, r.length, to->loc) : val_error();
  } else {
    if (!dir || !len) {
      sema_missing(&f, loc, "%s needs 'to', or 'direction' and 'length'", what);
      ok = 0;
    }
    r.direction = dir ? sema_field_value(S, sc, &f, "direction", 3, DIM_NONE) : val_error();
    r.length = len ? sema_field_value(S, sc, &f, "length", 1, DIM_LENGTH) : val_error();
    if (len) sema_positive(S, &r.length, "'length'", "m");
  }
  if (r.direction.kind == VAL_VEC) {
    double n = sqrt(r.direction.v[0] * r.direction.v[0] + r.direction.v[1] * r.direction.v[1] +
                    r.direction.v[2] * r.direction.v[2]);
    if (!(n > 0)) {
      diag_error(r.direction.loc, "'direction' must not be the zero vector");
      ok = 0;
    }
  }
  if (sema_field(&f, "normal")) {
    r.normal = sema_field_value(S, sc, &f, "normal", 3, DIM_NONE);
    if (r.normal.kind == VAL_VEC && r.direction.kind == VAL_VEC) {
      const double *a = r.normal.v, *b = r.direction.v;
      double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2],
             cz = a[0] * b[1] - a[1] * b[0];
      if (!(cx * cx + cy * cy + cz * cz > 1e-24)) {
        diag_error(r.normal.loc, "'normal' must not be parallel to the rod's direction");
        ok = 0;
      }
    }
  } else if (r.direction.kind == VAL_VEC) {
    /* any unit vector perpendicular to the direction: x, unless nearly parallel */
    const double *d = r.direction.v;
    double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double ax = fabs(d[0]) / n < 0.9 ? 1 : 0, ay = 1 - ax;
    double dot = (ax * d[0] + ay * d[1]) / (n * n);
    double nx = ax - dot * d[0], ny = ay - dot * d[1], nz = -dot * d[2];
    double nn = sqrt(nx * nx + ny * ny + nz * nz);
    r.normal = sema_vec3(S, nx / nn, ny / nn, nz / nn, DIM_NONE, loc);
  }
  /* cross section */
  const swAst *rad = sema_field(&f, "radius"), *rs = sema_field(&f, "radius_start"),
              *re = sema_field(&f, "radius_end");
  if (rad && (rs || re)) {
    diag_error(rad->loc, "give either 'radius', or 'radius_start' and 'radius_end' (a taper)");
    ok = 0;
  }
  if (rad) {
    r.radius_start = r.radius_end = sema_field_value(S, sc, &f, "radius", 1, DIM_LENGTH);
    sema_positive(S, &r.radius_start, "'radius'", "m");
  } else if (rs && re) {
    r.radius_start = sema_field_value(S, sc, &f, "radius_start", 1, DIM_LENGTH);
    r.radius_end = sema_field_value(S, sc, &f, "radius_end", 1, DIM_LENGTH);
    sema_positive(S, &r.radius_start, "'radius_start'", "m");
    sema_positive(S, &r.radius_end, "'radius_end'", "m");
  } else {
    sema_missing(&f, loc, "%s needs a 'radius' (or 'radius_start' and 'radius_end')", what);
    ok = 0;
  }
  /* discretisation */
  long nelem = 20;
  if (sema_field(&f, "elements")) {
    swValue ne = sema_field_value(S, sc, &f, "elements", 1, DIM_NONE);
    if (!sema_const_int(S, ne, "'elements'", 2, 100000, &nelem)) ok = 0;
  }
  r.nelem = (int)nelem;
  /* a bound on the whole scene, so a 20 kB file cannot ask for gigabytes
   * (the checker hands the scene to the runtime, which allocates it) */
  long total = S->scene->nelem + nelem;
  if (ok && total > SEMA_MAX_ELEMENTS) {
    diag_error(loc, "the scene would have %ld elements with %s; at most %d are allowed", total,
               what, SEMA_MAX_ELEMENTS);
    ok = 0;
  }
  /* hardening, rest shape, damping */
  r.shear_hardening = sema_field(&f, "shear_hardening")
                      ? sema_field_value(S, sc, &f, "shear_hardening", 1, DIM_NONE)
                      : val_num(S->a, 1, DIM_NONE, loc);
  r.twist_hardening = sema_field(&f, "twist_hardening")
                      ? sema_field_value(S, sc, &f, "twist_hardening", 1, DIM_NONE)
                      : val_num(S->a, 1, DIM_NONE, loc);
  sema_positive(S, &r.shear_hardening, "'shear_hardening'", "");
  sema_positive(S, &r.twist_hardening, "'twist_hardening'", "");
  r.rest_kappa = sema_field(&f, "rest_curvature")
                 ? sema_field_value(S, sc, &f, "rest_curvature", 3, dim_make(0, -1, 0, 0))
                 : sema_vec3(S, 0, 0, 0, dim_make(0, -1, 0, 0), loc);
  r.rest_sigma = sema_field(&f, "rest_strain")
                 ? sema_field_value(S, sc, &f, "rest_strain", 3, DIM_NONE)
                 : sema_vec3(S, 0, 0, 0, DIM_NONE, loc);
  r.gamma = sema_field(&f, "damping") ? sema_field_value(S, sc, &f, "damping", 1, dim_make(1, -1, -1, 0))
            : val_num(S->a, 0, dim_make(1, -1, -1, 0), loc);
  if (r.gamma.kind == VAL_NUM && r.gamma.v[0] < 0) {
    diag_error(r.gamma.loc, "'damping' must not be negative");
    ok = 0;
  }
  /* rotational_damping: the couple density -gamma_rot w of Gazzola 2018, in
   * N s/rad; without it the couples are damped in proportion to the inertia */
  r.gamma_rot.kind = VAL_ERROR;
  if (sema_field(&f, "rotational_damping")) {
    r.gamma_rot = sema_field_value(S, sc, &f, "rotational_damping", 1, dim_make(1, 1, -1, -1));
    if (r.gamma_rot.kind == VAL_ERROR) ok = 0;
    else if (r.gamma_rot.kind == VAL_NUM && r.gamma_rot.v[0] < 0) {
      diag_error(r.gamma_rot.loc, "'rotational_damping' must not be negative");
      ok = 0;
    }
  }
  r.damping = sema_damping_kind(S, sc, &f, NULL);
  /* rigid = true: the runtime moves the rod as one rigid body.  It changes
   * the layout the runtime builds, so it is fixed when compiling: the word
   * itself, or a let or component parameter holding it, never a param. */
  const swAst *rg = sema_field(&f, "rigid");
  if (rg) {
    int truth = sema_truth(S, sc, rg, "'rigid'");
    if (truth < 0) ok = 0;
    else r.rigid = truth;
  }
  /* implicit = true: under integrator = imex the runtime kicks the rod's
   * elasticity by the trapezoidal rule (a switch, like rigid) */
  const swAst *im = sema_field(&f, "implicit");
  if (im) {
    int truth = sema_truth(S, sc, im, "'implicit'");
    if (truth < 0) ok = 0;
    else r.implicit = truth;
    if (ok && r.implicit && r.rigid) {
      diag_error(im->loc, "rod '%s' is rigid: it has no elasticity to make implicit", sym->name);
      ok = 0;
    } else if (ok && r.implicit && r.damping == SW_DAMP_ANALYTIC) {
      diag_error(im->loc, "rod '%s': analytic damping is not supported on an implicit rod (use "
                 "damping_model = linear, which the implicit kick integrates by the "
                 "trapezoidal rule)", sym->name);
      ok = 0;
    }
  }
  /* gravity = false: gravity does not act on the rod (a switch, like rigid) */
  const swAst *gv = sema_field(&f, "gravity");
  if (gv) {
    int truth = sema_truth(S, sc, gv, "'gravity'");
    if (truth < 0) ok = 0;
    else r.weightless = !truth;
  }
  const swValue *all[] = {&r.youngs, &r.density, &r.shear_modulus, &r.poisson, &r.start,
                          &r.direction, &r.normal, &r.length, &r.radius_start, &r.radius_end,
                          &r.shear_hardening, &r.twist_hardening, &r.rest_kappa, &r.rest_sigma,
                          &r.gamma};
  for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
    if (all[i]->kind == VAL_ERROR) ok = 0;
  if (!ok) {
    sym->index = -1;
    return;
  }
  /* a rod's points (start, end, at(f)) are built on these three */
  snprintf(field, sizeof field, "rod %s: direction", name);
  derive(S, &r.direction, field, sym->loc);
  snprintf(field, sizeof field, "rod %s: length", name);
  derive(S, &r.length, field, sym->loc);
  swScene *scn = S->scene;
  if (scn->nrod == scn->caprod) {
    scn->caprod = scn->caprod ? 2 * scn->caprod : 8;
    scn->rod = realloc(scn->rod, (size_t)scn->caprod * sizeof *scn->rod);
    if (!scn->rod) abort();
  }
  sym->index = scn->nrod;
  r.id = scn->nrodid++;
  scn->nelem += r.nelem;
  scn->rod[scn->nrod++] = r;
}

static void eval_symbol(swSema *S, swSymbol *sym) {
  if (sym->state == 2) return;
  if (sym->state == 1) {
    /* the chain from sym's own evaluation to here: "b -> c -> b" */
    char chain[512] = "";
    size_t used = 0;
    int from = S->nevaluating;
    while (from > 0 && S->evaluating[from - 1] != sym) from--;
    for (int k = from > 0 ? from - 1 : S->nevaluating; k < S->nevaluating && used < sizeof chain;
         k++)
      used += (size_t)snprintf(chain + used, sizeof chain - used, "%s -> ",
                               S->evaluating[k]->name);
    if (from > 0 && from < S->nevaluating && used < sizeof chain) {   /* not a -> a */
      snprintf(chain + used, sizeof chain - used, "%s", sym->name);
      diag_error(sym->loc, "'%s' is defined in terms of itself (%s)", sym->name, chain);
    } else {
      diag_error(sym->loc, "'%s' is defined in terms of itself", sym->name);
    }
    sym->value = val_error();
    return;
  }
  sym->state = 1;
  if (S->nevaluating < (int)(sizeof S->evaluating / sizeof S->evaluating[0]))
    S->evaluating[S->nevaluating] = sym;
  S->nevaluating++;
  switch (sym->kind) {
  case SYM_PARAM:
    eval_param(S, sym);
    break;
  case SYM_LET: {
    swValue v = sema_eval(S, sym->scope, sym->def->kid[0]);
    if (v.kind == VAL_WORD) {
      sema_report_unknown(S, sym->scope, v.word, v.loc, "name");
      v = val_error();
    }
    sym->value = v;
    if (S->nlets && sym->scope == S->global && sym->main_file) let_override(S, sym);
    char what[512];
    snprintf(what, sizeof what, "let %s", sym->full ? sym->full : sym->name);
    derive(S, &sym->value, what, sym->loc);
    break;
  }
  case SYM_MATERIAL:
    eval_material(S, sym);
    break;
  case SYM_ROD:
    eval_rod(S, sym);
    break;
  case SYM_MUSCLE:
    sema_eval_muscle(S, sym);
    break;
  default:
    break;
  }
  S->nevaluating--;
  sym->state = 2;
}

/* A definition means the same wherever it is first used: a reduction of the
 * run in a let is not the objective's, even when the objective is what
 * reads the let first. */
void sema_eval_symbol(swSema *S, swSymbol *sym) {
  const int reducing = S->reducing;
  S->reducing = 0;
  eval_symbol(S, sym);
  S->reducing = reducing;
}

/* A point whose node must be known when compiling (a load's, a boundary
 * condition's, a probe's): 0 with an error naming what when a param moves it. */
int sema_point_fixed(const swValue *p, const char *what) {
  if (p->kind != VAL_POINT || !p->node_c) return 1;
  diag_error(p->loc, "%s must be known when the model is compiled, but it depends on param '%s' "
             "(a param may move a joint's or a muscle's point, not this one)", what,
             p->param ? p->param : "?");
  return 0;
}

swValue sema_rod_length(swSema *S, swSymbol *rod, swLoc loc) {
  sema_eval_symbol(S, rod);
  if (rod->index < 0 || rod->state != 2) return val_error();
  swValue v = S->scene->rod[rod->index].length;
  v.loc = loc;
  return v;
}

/* node: >= 0 a node, -1 the last node, -2 the node nearest to frac.  A
 * fraction that depends on a param (ROD.at(param)) moves the point: its
 * position is then an expression of the params, and so is its node, which
 * the generated simulator computes when it builds the scene, with the same
 * lround the default's node is taken with here. */
swValue sema_rod_point(swSema *S, swSymbol *rod, swValue f, int node, swLoc loc) {
  rod->used = 1;
  sema_eval_symbol(S, rod);
  if (rod->index < 0 || rod->state != 2) return val_error();
  const swSceneRod *r = &S->scene->rod[rod->index];
  int n = r->nelem;
  const char *node_c = NULL;
  if (node == -1) node = n;
  if (node == -2) {
    node = (int)lround(f.v[0] * n);
    if (f.c && f.c[0]) {
      char buf[4200];
      if (snprintf(buf, sizeof buf, "(int)lround(%s * %d)", f.c[0], n) >= (int)sizeof buf) {
        diag_error(loc, "expression is too long to generate");
        return val_error();
      }
      node_c = ast_strdup(S->a, buf, strlen(buf));
    }
  }
  swValue dir = r->direction;
  /* direction is normalised by the runtime: do the same here */
  swValue unit = val_binop(S->a, '/', dir, val_norm(S->a, dir, loc), loc);
  swValue off = val_binop(S->a, '*', val_binop(S->a, '*', f, r->length, loc), unit, loc);
  swValue p = val_binop(S->a, '+', r->start, off, loc);
  if (p.kind == VAL_ERROR) return p;
  p.kind = VAL_POINT;
  p.rod = rod->index;
  p.node = node;
  p.node_c = node_c;
  p.loc = loc;
  return p;
}
