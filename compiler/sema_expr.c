/* sema_expr.c — evaluation of expressions: numbers with units, vectors,
 * names, members and points on rods; and the checks of a value's kind and
 * dimension that the rest of the checker asks for (sema_expect, sema_truth).
 *
 * Design.  sema_eval() is a plain walk over the expression tree returning a
 * swValue (see sema.h); it reports every error it finds and answers
 * VAL_ERROR, which the callers pass on silently, so one mistake gives one
 * message.  A name is looked up through the enclosing scopes; a name with no
 * definition evaluates to a bare word (VAL_WORD), which only the few places
 * that take a word (integrator = pefrl, velocity all) accept -- everywhere
 * else it is reported as unknown, with the nearest defined name.  The words
 * true and false are values of their own (VAL_TRUTH): a let or a component
 * parameter may hold one and pass it on to a switch such as rigid
 * (sema_truth); arithmetic refuses them.  Calls of the built-in functions
 * (time signals, max, min, abs, round, sqrt, ...) are sema_call.c's.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sema_int.h"

#define PI 3.14159265358979323846

const char *sema_describe_value(swSema *S, const swValue *v) {
  switch (v->kind) {
  case VAL_POINT: return "a point on a rod";
  case VAL_SIGNAL: return "a time signal";
  case VAL_REF: return "a definition";
  case VAL_WORD: return "a name";
  case VAL_TRUTH: return "true or false";
  case VAL_VEC: {
    char buf[160];
    snprintf(buf, sizeof buf, "a %d-component vector of %s", v->n, dim_describe(S->a, v->dim));
    return ast_strdup(S->a, buf, strlen(buf));
  }
  default: {
    if (dim_is_none(v->dim)) return "dimensionless (a number without a unit)";
    return dim_describe(S->a, v->dim);
  }
  }
}

/* Evaluate an operand of arithmetic: a bare word here is an unknown name. */
swValue sema_operand(swSema *S, swScope *scope, const swAst *e) {
  swValue v = sema_eval(S, scope, e);
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, scope, v.word, v.loc, "name");
    return val_error();
  }
  if (v.kind == VAL_REF) {
    diag_error(e->loc, "'%s' is a %s, not a value", v.ref->name,
               v.ref->kind == SYM_MATERIAL ? "material" : v.ref->kind == SYM_ROD ? "rod"
               : v.ref->kind == SYM_JOINT ? "joint" : v.ref->kind == SYM_COMPONENT ? "component"
               : v.ref->kind == SYM_MUSCLE ? "muscle" : v.ref->kind == SYM_ENV ? "environment"
               : "instance");
    return val_error();
  }
  if (v.kind == VAL_TRUTH) {
    if (e->kind == AST_NAME && strcmp(e->name, v.word))
      diag_error(e->loc, "'%s' is %s, a switch fixed when compiling, not a number", e->name,
                 v.word);
    else diag_error(e->loc, "%s is a switch fixed when compiling, not a number", v.word);
    return val_error();
  }
  return v;
}

swValue sema_expect_value(swSema *S, swValue v, int n, swDim want, const char *what) {
  if (v.kind == VAL_ERROR) return v;
  if (v.kind == VAL_WORD) {
    /* reported by the caller's scope-aware path; here a plain message */
    diag_error(v.loc, "unknown name '%s'", v.word);
    return val_error();
  }
  int ok_kind = n == 1 ? v.kind == VAL_NUM : (v.kind == VAL_VEC && v.n == n);
  if (!ok_kind) {
    if (n == 3 && v.kind == VAL_POINT) ok_kind = 1;   /* a point is a position */
  }
  if (!ok_kind) {
    if (n == 1)
      diag_error(v.loc, "%s expects a number, got %s", what, sema_describe_value(S, &v));
    else
      diag_error(v.loc, "%s expects a %d-component vector, got %s", what, n,
                 sema_describe_value(S, &v));
    return val_error();
  }
  if (!dim_fits(want, v.dim)) {
    /* a component parameter's value is written elsewhere: say where */
    char from[340] = "";
    if (v.via_formal && v.formal_loc.line && v.formal_loc.line != v.loc.line) {
      char where[300];
      snprintf(from, sizeof from, "; it is the value of '%s', given at %s", v.via_formal,
               diag_where_from(v.formal_loc, v.loc, where, sizeof where));
    }
    diag_error(v.loc, "%s expects %s, got %s%s", what, dim_describe(S->a, want),
               dim_is_none(v.dim) ? "dimensionless (a number without a unit)"
                                  : dim_describe(S->a, v.dim), from);
    return val_error();
  }
  if (v.kind == VAL_POINT) {
    v.kind = VAL_VEC;
  }
  return v;
}

swValue sema_expect(swSema *S, swScope *scope, const swAst *e, int n, swDim want,
                    const char *what) {
  swValue v = sema_operand(S, scope, e);
  return sema_expect_value(S, v, n, want, what);
}

int sema_require_const(swSema *S, const swValue *v, const char *what) {
  (void)S;
  if (v->kind == VAL_ERROR || val_is_const(v)) return 1;
  if (v->param)
    diag_error(v->loc, "%s must be known when the model is compiled, but it depends on param "
               "'%s'", what, v->param);
  else   /* a reduction of the run (sema_objective.c) */
    diag_error(v->loc, "%s must be known when the model is compiled, but it depends on the run",
               what);
  return 0;
}

/* A value the simulator knows when it builds the scene: a constant or an
 * expression of params, not a reduction of the run (refused as such). */
int sema_known_at_build(swSema *S, const swValue *v, const char *what) {
  if (v->kind == VAL_ERROR) return 0;
  if (val_is_const(v) || v->param) return 1;
  sema_require_const(S, v, what);
  return 0;
}

int sema_const_int(swSema *S, swValue v, const char *what, long lo, long hi, long *out) {
  if (v.kind == VAL_ERROR || !sema_require_const(S, &v, what)) return 0;
  double x = v.v[0];
  if (x != floor(x) || x < (double)lo || x > (double)hi) {
    diag_error(v.loc, "%s must be a whole number from %ld to %ld, got %g", what, lo, hi, x);
    return 0;
  }
  *out = (long)x;
  return 1;
}

const char *sema_word(swSema *S, swScope *scope, const swAst *e, const char *what,
                      const char *const *choices, int nchoices) {
  (void)S;
  (void)scope;
  /* "verlet, pefrl or imex" */
  char list[256] = "";
  for (int i = 0; i < nchoices; i++) {
    strncat(list, !i ? "" : i + 1 < nchoices ? ", " : " or ", sizeof list - strlen(list) - 1);
    strncat(list, choices[i], sizeof list - strlen(list) - 1);
  }
  if (e->kind != AST_NAME) {
    diag_error(e->loc, "%s expects one of the words %s", what, list);
    return NULL;
  }
  for (int i = 0; i < nchoices; i++)
    if (!strcmp(e->name, choices[i])) return choices[i];
  const char *near = diag_suggest(e->name, choices, nchoices);
  if (near)
    diag_error(e->loc, "unknown %s '%s'; did you mean '%s'?", what, e->name, near);
  else
    diag_error(e->loc, "unknown %s '%s' (expected %s)", what, e->name, list);
  return NULL;
}

/* The words a switch takes, then the names that could hold one. */
static const char *truth_suggestion(swSema *S, swScope *scope, const char *word) {
  static const char *const truth[] = {"true", "false"};
  const char *near = diag_suggest(word, truth, 2);
  if (near) return near;
  enum { MAXC = 512 };
  const char *cands[MAXC];
  int n = 0;
  for (swScope *sc = scope; sc; sc = sc->parent)
    for (int i = 0; i < sc->n && n < MAXC; i++)
      if (sc->sym[i]->kind == SYM_LET || sc->sym[i]->kind == SYM_FORMAL) cands[n++] = sc->sym[i]->name;
  near = diag_suggest(word, cands, n);
  if (near) sema_lookup(S, scope, near)->used = 1;   /* what was meant: not "unused" */
  return near;
}

int sema_truth(swSema *S, swScope *scope, const swAst *e, const char *what) {
  swValue v = sema_eval(S, scope, e);
  if (v.kind == VAL_TRUTH) return !strcmp(v.word, "true");
  if (v.kind == VAL_ERROR) return -1;
  if (v.kind == VAL_WORD) {
    const char *near = truth_suggestion(S, scope, v.word);
    if (near) diag_error(e->loc, "%s is true or false, not '%s'; did you mean '%s'?", what, v.word, near);
    else diag_error(e->loc, "%s is true or false, not '%s'", what, v.word);
    return -1;
  }
  /* a switch changes what is compiled (rigid: the layout of the rods), so
   * it cannot wait for the run's values */
  if (v.param) {
    diag_error(e->loc, "%s is fixed when the model is compiled, but param '%s' is a run-time "
               "value (SIM --set changes it); give true or false through a let or a component "
               "parameter", what, v.param);
    return -1;
  }
  const swSymbol *sym = e->kind == AST_NAME ? sema_lookup(S, scope, e->name) : NULL;
  char where[256];
  if (sym && (sym->kind == SYM_LET || sym->kind == SYM_FORMAL))
    diag_error(e->loc, "%s is true or false, but %s '%s' is %s (its value is at %s)", what,
               sema_sym_noun(sym->kind), sym->name, val_kind_noun(&sym->value),
               diag_where(sym->value.loc, where, sizeof where));
  else if (sym)
    diag_error(e->loc, "%s is true or false, but '%s' is %s", what, sym->name,
               sema_sym_a_noun(sym->kind));
  else diag_error(e->loc, "%s is true or false, not %s", what, val_kind_noun(&v));
  return -1;
}

/* ---- names and members ---- */

static swValue symbol_value(swSema *S, swSymbol *sym, swLoc loc) {
  sym->used = 1;
  switch (sym->kind) {
  case SYM_SIGNAL:
    return sema_signal_value(S, sym, loc);
  case SYM_PARAM:
  case SYM_LET:
  case SYM_FORMAL: {
    sema_eval_symbol(S, sym);
    swValue v = sym->value;
    if (v.kind != VAL_ERROR) {
      if (sym->kind == SYM_FORMAL) {
        v.via_formal = sym->name;
        v.formal_loc = v.loc;
      }
      v.loc = loc;
    }
    return v;
  }
  default: {
    swValue v = val_error();
    v.kind = VAL_REF;
    v.ref = sym;
    v.loc = loc;
    return v;
  }
  }
}

static swValue eval_member(swSema *S, swScope *scope, const swAst *e) {
  const swAst *base = ast_kid(e, 0);
  swValue b = sema_eval(S, scope, base);
  if (b.kind == VAL_ERROR) return b;
  if (b.kind == VAL_WORD) {
    sema_report_unknown(S, scope, b.word, b.loc, "name");
    return val_error();
  }
  if (b.kind == VAL_REF && b.ref->kind == SYM_INSTANCE) {
    if (!b.ref->members) {   /* its 'use' failed (reported there) or comes later */
      char made[300];
      if (b.ref->state != 2)
        diag_error(e->loc, "'%s' is used before the line that creates it (%s)", b.ref->name,
                   diag_where_from(b.ref->loc, e->loc, made, sizeof made));
      return val_error();
    }
    swSymbol *m = sema_lookup_local(b.ref->members, e->name);
    if (!m) {
      const char *cands[256];
      int n = 0;
      for (int i = 0; i < b.ref->members->n && n < 256; i++) cands[n++] = b.ref->members->sym[i]->name;
      const char *near = diag_suggest(e->name, cands, n);
      if (near)
        diag_error(e->loc, "'%s' has no member '%s'; did you mean '%s'?", b.ref->name, e->name, near);
      else
        diag_error(e->loc, "'%s' has no member '%s'", b.ref->name, e->name);
      return val_error();
    }
    return symbol_value(S, m, e->loc);
  }
  if (b.kind == VAL_REF && b.ref->kind == SYM_MUSCLE) {
    sema_muscle_not_rod(S, b.ref, e->loc);
    return val_error();
  }
  if (b.kind == VAL_REF && b.ref->kind == SYM_ROD) {
    static const char *const members[] = {"start", "end", "length", "at"};
    if (!strcmp(e->name, "start"))
      return sema_rod_point(S, b.ref, val_num(S->a, 0, DIM_NONE, e->loc), 0, e->loc);
    if (!strcmp(e->name, "end"))
      return sema_rod_point(S, b.ref, val_num(S->a, 1, DIM_NONE, e->loc), -1, e->loc);
    if (!strcmp(e->name, "length")) return sema_rod_length(S, b.ref, e->loc);
    const char *near = diag_suggest(e->name, members, 4);
    if (!strcmp(e->name, "at"))
      diag_error(e->loc, "'at' needs a fraction of the length: %s.at(0.5)", b.ref->name);
    else if (near)
      diag_error(e->loc, "rod '%s' has no member '%s'; did you mean '%s'?", b.ref->name, e->name, near);
    else
      diag_error(e->loc, "rod '%s' has no member '%s' (it has start, end, length and at(f))",
                 b.ref->name, e->name);
    return val_error();
  }
  if (b.kind == VAL_POINT) b.kind = VAL_VEC;   /* a point's coordinates: rod.end.z */
  if (b.kind == VAL_VEC && (!strcmp(e->name, "x") || !strcmp(e->name, "y") ||
                            !strcmp(e->name, "z"))) {
    int i = e->name[0] - 'x';
    if (i >= b.n) {
      diag_error(e->loc, "a %d-component vector has no '%s'", b.n, e->name);
      return val_error();
    }
    swValue r = val_num(S->a, b.v[i], b.dim, e->loc);
    r.param = b.param;
    if (b.c && b.c[i]) {
      r.c = ast_alloc(S->a, sizeof *r.c);
      r.c[0] = b.c[i];
    }
    return r;
  }
  diag_error(e->loc, "%s has no member '%s'", sema_describe_value(S, &b), e->name);
  return val_error();
}

static swValue eval_method(swSema *S, swScope *scope, const swAst *e) {
  swValue b = sema_eval(S, scope, ast_kid(e, 0));
  if (b.kind == VAL_ERROR) return b;
  if (b.kind == VAL_WORD) {
    sema_report_unknown(S, scope, b.word, b.loc, "name");
    return val_error();
  }
  if (b.kind == VAL_REF && b.ref->kind == SYM_MUSCLE) {
    sema_muscle_not_rod(S, b.ref, e->loc);
    return val_error();
  }
  if (b.kind != VAL_REF || b.ref->kind != SYM_ROD || strcmp(e->name, "at")) {
    if (b.kind == VAL_REF && b.ref->kind == SYM_ROD)
      diag_error(e->loc, "rod '%s' has no method '%s' (points are start, end and at(f))",
                 b.ref->name, e->name);
    else
      diag_error(e->loc, "'%s(...)' applies to a rod, not to %s", e->name,
                 sema_describe_value(S, &b));
    return val_error();
  }
  const swAst *args = ast_kid(e, 1);
  if (!args || args->nkid != 1 || args->kid[0]->name) {
    diag_error(e->loc, "at() takes one argument, the fraction of the rod's length (0 to 1)");
    return val_error();
  }
  swValue f = sema_expect(S, scope, ast_kid(args->kid[0], 0), 1, DIM_NONE,
                          "the fraction in at()");
  if (!sema_known_at_build(S, &f, "the fraction in at()")) return val_error();
  /* a param's fraction is checked here at its default; the simulator refuses
     a node off the rod when it builds the scene */
  if (!(f.v[0] >= 0 && f.v[0] <= 1)) {
    diag_error(f.loc, "the fraction in at() must be between 0 and 1, got %g%s", f.v[0],
               f.param ? " with the params at their defaults" : "");
    return val_error();
  }
  return sema_rod_point(S, b.ref, f, -2, e->loc);
}

/* LOOP[K]: pass K of a loop, an instance whose members are read with '.' */
static swValue eval_index(swSema *S, swScope *scope, const swAst *e) {
  swValue b = sema_eval(S, scope, e->kid[0]);
  if (b.kind == VAL_ERROR) return b;
  if (b.kind == VAL_WORD) {
    sema_report_unknown(S, scope, b.word, b.loc, "name");
    return val_error();
  }
  if (b.kind != VAL_REF || b.ref->kind != SYM_LOOP) {
    if (b.kind == VAL_REF)
      diag_error(e->loc, "only a loop's passes are numbered, LOOP[K], and '%s' is %s",
                 b.ref->name, sema_sym_a_noun(b.ref->kind));
    else
      diag_error(e->loc, "only a loop's passes are numbered, LOOP[K], not %s",
                 sema_describe_value(S, &b));
    return val_error();
  }
  swValue k = sema_expect(S, scope, e->kid[1], 1, DIM_NONE, "a pass of a loop");
  if (k.kind == VAL_ERROR) return k;
  const swSymbol *loop = b.ref;
  if (!val_is_const(&k) || k.v[0] != floor(k.v[0])) {
    diag_error(k.loc, "a pass of loop '%s' is a whole number known when compiling", loop->name);
    return val_error();
  }
  if (!loop->pass) {   /* its line comes later, or it failed (reported there) */
    char made[300];
    if (loop->state != 2)
      diag_error(e->loc, "loop '%s' is used before the line that runs it (%s)", loop->name,
                 diag_where_from(loop->loc, e->loc, made, sizeof made));
    return val_error();
  }
  const long i = (long)k.v[0] - loop->first_pass;
  if (i < 0 || i >= loop->npass) {
    diag_error(k.loc, "loop '%s' has passes %d to %d, not %g", loop->name, loop->first_pass,
               loop->first_pass + loop->npass - 1, k.v[0]);
    return val_error();
  }
  swValue v = val_error();
  v.kind = VAL_REF;
  v.ref = loop->pass[i];
  v.loc = e->loc;
  return v;
}

static swValue eval_vector(swSema *S, swScope *scope, const swAst *e) {
  swValue *parts = ast_alloc(S->a, (size_t)e->nkid * sizeof *parts);
  int bad = 0;
  for (int i = 0; i < e->nkid; i++) {
    parts[i] = sema_operand(S, scope, e->kid[i]);
    if (parts[i].kind == VAL_ERROR) bad = 1;
    else if (parts[i].kind != VAL_NUM) {
      diag_error(e->kid[i]->loc, "a vector component must be a number, not %s",
                 sema_describe_value(S, &parts[i]));
      bad = 1;
    }
  }
  if (bad) return val_error();
  for (int i = 1; i < e->nkid; i++)
    if (!dim_eq(parts[i].dim, parts[0].dim)) {
      diag_error(e->kid[i]->loc, "vector components must share one dimension: component 1 is "
                 "%s, component %d is %s", sema_describe_value(S, &parts[0]), i + 1,
                 sema_describe_value(S, &parts[i]));
      return val_error();
    }
  swValue v = val_vec(S->a, e->nkid, NULL, parts[0].dim, e->loc);
  for (int i = 0; i < e->nkid; i++) {
    v.v[i] = parts[i].v[0];
    if (parts[i].c && parts[i].c[0]) {
      if (!v.c) v.c = ast_alloc(S->a, (size_t)v.n * sizeof *v.c);
      v.c[i] = parts[i].c[0];
      v.param = parts[i].param;
    }
  }
  return v;
}

static swValue eval_node(swSema *S, swScope *scope, const swAst *e) {
  switch (e->kind) {
  case AST_NUM:   /* NaN: a number the lexer reported out of range */
    return isnan(e->num) ? val_error() : val_num(S->a, e->num, DIM_NONE, e->loc);
  case AST_UNIT: {
    const swUnit *u = sw_unit_find(e->name, strlen(e->name));
    if (!u) {
      diag_error(e->loc, "unknown unit '%s'", e->name);
      return val_error();
    }
    swDim d;
    memcpy(d.e, u->dim, sizeof d.e);
    return val_num(S->a, u->scale, d, e->loc);
  }
  case AST_NAME: {
    swSymbol *sym = sema_lookup(S, scope, e->name);
    if (sym) return symbol_value(S, sym, e->loc);
    if (!strcmp(e->name, "pi")) return val_num(S->a, PI, DIM_NONE, e->loc);
    if (!strcmp(e->name, "true") || !strcmp(e->name, "false"))
      return val_truth(e->name[0] == 't', e->loc);
    swValue w = val_error();
    w.kind = VAL_WORD;
    w.word = e->name;
    w.loc = e->loc;
    return w;
  }
  case AST_BINOP: {
    if (strchr("<>lg&|", e->op)) {
      diag_error(e->loc, "a comparison is a condition of piecewise(), not a value");
      return val_error();
    }
    if (e->op == '^') {
      swValue x = sema_operand(S, scope, e->kid[0]);
      swValue p = sema_operand(S, scope, e->kid[1]);
      if (x.kind == VAL_ERROR || p.kind == VAL_ERROR) return val_error();
      if (p.kind != VAL_NUM || !dim_is_none(p.dim) || !val_is_const(&p)) {
        diag_error(e->kid[1]->loc, "an exponent must be a plain number known when compiling");
        return val_error();
      }
      return val_pow(S->a, x, p.v[0], e->loc);
    }
    swValue x = sema_operand(S, scope, e->kid[0]);
    swValue y = sema_operand(S, scope, e->kid[1]);
    return val_binop(S->a, e->op, x, y, e->loc);
  }
  case AST_APPLY: {
    swValue x = sema_operand(S, scope, e->kid[0]);
    swValue u = sema_operand(S, scope, e->kid[1]);
    return val_binop(S->a, '*', x, u, e->loc);
  }
  case AST_NEG:
    return val_neg(S->a, sema_operand(S, scope, e->kid[0]), e->loc);
  case AST_VEC:
    return eval_vector(S, scope, e);
  case AST_CALL:
    return sema_eval_call(S, scope, e);
  case AST_MEMBER:
    return eval_member(S, scope, e);
  case AST_INDEX:
    return eval_index(S, scope, e);
  case AST_METHOD:
    return eval_method(S, scope, e);
  default:
    diag_error(e->loc, "a %s is not a value", ast_kind_name(e->kind));
    return val_error();
  }
}

swValue sema_eval(swSema *S, swScope *scope, const swAst *e) {
  if (!e) return val_error();
  if (S->eval_depth >= SEMA_MAX_EVAL_DEPTH) {
    if (!S->eval_too_deep)
      diag_error(e->loc, "this value is nested more than %d levels deep through the definitions "
                 "it uses; define each name above the line that uses it", SEMA_MAX_EVAL_DEPTH);
    S->eval_too_deep = 1;
    return val_error();
  }
  S->eval_depth++;
  swValue v = eval_node(S, scope, e);
  S->eval_depth--;
  return v;
}
