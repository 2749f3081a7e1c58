/* sema_def.c — definitions: field tables, params, lets, materials, and the
 * evaluation of a definition on first use.
 *
 * Design.  Each definition is evaluated once, on first use or in file order,
 * with its body's fields checked against the list of keys it accepts (an
 * unknown key gets the nearest known one); sema_eval_symbol dispatches on the
 * definition's kind, and a definition met again while it is being evaluated
 * is a cycle, named as a chain.  A component of a value that depends on a
 * param through more than a bare P[k] becomes a derived quantity D[k] of the
 * scene (sema_derive), for rods and lets alike.  Rods and the points on them
 * are in sema_rod.c, muscles in sema_muscle.c, statements (joints, clamp,
 * force, ...) in sema_stmt.c.
 */
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
    /* and so are a rod's shapes: rest_shape(s) = (x, y, z); (sema_shape.c) */
    if (k < nkeys && fl->nkid > 1 && strcmp(fl->name, "height") && strcmp(fl->name, "shape") &&
        strcmp(fl->name, "rest_shape") && strcmp(fl->name, "start_shape")) {
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

const swAst *sema_field_node(const swFields *f, const char *key) {
  for (int k = 0; k < f->nkeys; k++)
    if (!strcmp(f->keys[k], key)) return f->value[k];
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
   * the gradient of their elastic energy (the runtime's rod.c); false:
   * Gazzola et al. 2018's.  A switch, so fixed when compiling, through a let
   * or component parameter too.  Unsaid (-1), a rod takes Gazzola's law and
   * a muscle the variational one (sema_tissue's callers) */
  const swAst *var = sema_field(&f, "variational");
  m->variational = -1;
  if (var) {
    int truth = sema_truth(S, sym->scope, var, "'variational'");
    if (truth >= 0) m->variational = truth;
  }
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
  } else t->variational = mat ? mat->variational : -1;
  if (t->E_ast && t->youngs.kind == VAL_NUM) sema_positive(S, &t->youngs, "E", "Pa");
  if (t->rho_ast && t->density.kind == VAL_NUM) sema_positive(S, &t->density, "density", "kg/m^3");
  return ok;
}

/* ---- shared by the definitions ---- */

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
void sema_derive(swSema *S, swValue *v, const char *what, swLoc loc) {
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

/* ---- a definition, evaluated once ---- */

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
  if (S->nevaluating >= SEMA_MAX_DEF_CHAIN) {
    /* not evaluated here: its own line (state 0) will evaluate it */
    if (!S->eval_too_deep)
      diag_error(sym->loc, "'%s' is needed by %d definitions evaluated inside one another, "
                 "each using a name defined below it; define each name above the line that "
                 "uses it", sym->name, SEMA_MAX_DEF_CHAIN);
    S->eval_too_deep = 1;
    sym->value = val_error();
    return;
  }
  sym->state = 1;
  S->evaluating[S->nevaluating++] = sym;
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
    sema_derive(S, &sym->value, what, sym->loc);
    break;
  }
  case SYM_MATERIAL:
    eval_material(S, sym);
    break;
  case SYM_ROD:
    sema_eval_rod(S, sym);
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
