/* sema_expr.c — evaluation of expressions: numbers with units, vectors,
 * names, points on rods, function calls and time signals.
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
 * (sema_truth); arithmetic refuses them.  Time
 * signals are the runtime's (constant, ramp, sine, step, table) with their
 * arguments checked by dimension; a signal may only be scaled.  max(a, b),
 * min(a, b) and abs(a) take numbers (of one dimension); the reductions of
 * the run, at() and the *_over() windows, are sema_objective.c's.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sema_int.h"

#define PI 3.14159265358979323846

static const char *const functions[] = {"sqrt", "sin", "cos", "tan", "ramp", "sine", "step",
                                        "table", "bspline", "exp", "piecewise", "max", "min",
                                        "abs", "round", "at", "mean_over", "max_over", "min_over"};
enum { NFUNCTIONS = sizeof functions / sizeof functions[0] };

static const char *describe_value(swSema *S, const swValue *v) {
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
static swValue operand(swSema *S, swScope *scope, const swAst *e) {
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
      diag_error(v.loc, "%s expects a number, got %s", what, describe_value(S, &v));
    else
      diag_error(v.loc, "%s expects a %d-component vector, got %s", what, n,
                 describe_value(S, &v));
    return val_error();
  }
  if (!dim_fits(want, v.dim)) {
    diag_error(v.loc, "%s expects %s, got %s", what, dim_describe(S->a, want),
               dim_is_none(v.dim) ? "dimensionless (a number without a unit)"
                                  : dim_describe(S->a, v.dim));
    return val_error();
  }
  if (v.kind == VAL_POINT) {
    v.kind = VAL_VEC;
  }
  return v;
}

swValue sema_expect(swSema *S, swScope *scope, const swAst *e, int n, swDim want,
                    const char *what) {
  swValue v = operand(S, scope, e);
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
static int known_at_build(swSema *S, const swValue *v, const char *what) {
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
    diag_error(e->loc, "%s is true or false, but '%s' is a %s", what, sym->name,
               sema_sym_noun(sym->kind));
  else diag_error(e->loc, "%s is true or false, not %s", what, val_kind_noun(&v));
  return -1;
}

/* ---- calls ---- */

typedef struct {
  const char *name;      /* keyword name                       */
  const swAst *value;
} swArgSlot;

/* Match positional and keyword arguments to the parameter names of a call. */
static int bind_args(swSema *S, const swAst *call, const swAst *args, const char *const *names,
                     int nnames, int nrequired, const swAst **out) {
  (void)S;
  int ok = 1, pos = 0;
  for (int i = 0; i < nnames; i++) out[i] = NULL;
  for (int i = 0; args && i < args->nkid; i++) {
    const swAst *arg = args->kid[i];
    int slot = -1;
    if (arg->name) {
      for (int k = 0; k < nnames; k++)
        if (!strcmp(arg->name, names[k])) slot = k;
      if (slot < 0) {
        const char *near = diag_suggest(arg->name, names, nnames);
        if (near)
          diag_error(arg->loc, "%s() has no argument '%s'; did you mean '%s'?", call->name,
                     arg->name, near);
        else
          diag_error(arg->loc, "%s() has no argument '%s'", call->name, arg->name);
        ok = 0;
        continue;
      }
    } else {
      if (pos >= nnames) {
        diag_error(arg->loc, "%s() takes at most %d arguments", call->name, nnames);
        ok = 0;
        continue;
      }
      slot = pos++;
    }
    if (out[slot]) {
      diag_error(arg->loc, "argument '%s' of %s() is given twice", names[slot], call->name);
      ok = 0;
      continue;
    }
    out[slot] = ast_kid(arg, 0);
  }
  /* a misspelled keyword is already reported: do not also call its slot missing */
  for (int i = 0; ok && i < nrequired; i++)
    if (!out[i]) {
      diag_error(call->loc, "%s() needs the argument '%s'", call->name, names[i]);
      ok = 0;
    }
  return ok;
}

static swValue scalar_arg(swSema *S, swScope *scope, const swAst *e, swDim want, const char *fn,
                          const char *arg, double fallback, swLoc loc) {
  if (!e) return val_num(S->a, fallback, want, loc);
  char what[96];
  snprintf(what, sizeof what, "argument '%s' of %s()", arg, fn);
  return sema_expect(S, scope, e, 1, want, ast_strdup(S->a, what, strlen(what)));
}

/* Two numbers that must share a dimension (a ramp's ends, a step's levels);
 * when they do not, the message names both rather than blaming the second. */
static int same_dims(swSema *S, swScope *scope, const swAst *call, const swAst *ea,
                     const swAst *eb, const char *na, const char *nb, swValue *a, swValue *b) {
  char what[96];
  *a = operand(S, scope, ea);
  *b = operand(S, scope, eb);
  if (a->kind == VAL_ERROR || b->kind == VAL_ERROR) return 0;
  snprintf(what, sizeof what, "argument '%s' of %s()", na, call->name);
  *a = sema_expect_value(S, *a, 1, a->dim, ast_strdup(S->a, what, strlen(what)));
  snprintf(what, sizeof what, "argument '%s' of %s()", nb, call->name);
  *b = sema_expect_value(S, *b, 1, b->dim, ast_strdup(S->a, what, strlen(what)));
  if (a->kind == VAL_ERROR || b->kind == VAL_ERROR) return 0;
  if (!dim_eq(a->dim, b->dim)) {
    diag_error(call->loc, "%s() needs '%s' and '%s' in one dimension, but '%s' is %s and '%s' "
               "is %s", call->name, na, nb, na, describe_value(S, a), nb, describe_value(S, b));
    return 0;
  }
  return 1;
}

static swValue make_signal(swSema *S, swSignalVal *sig, swDim dim, swLoc loc) {
  swValue v = val_error();
  v.kind = VAL_SIGNAL;
  v.sig = sig;
  v.dim = dim;
  v.loc = loc;
  v.n = 1;
  sig->scale = val_num(S->a, 1, DIM_NONE, loc);
  sig->base = dim;
  return v;
}

static int any_error(const swValue *v, int n) {
  for (int i = 0; i < n; i++)
    if (v[i].kind == VAL_ERROR) return 1;
  return 0;
}

/* period = T, an argument of every signal: the signal repeats with period T
 * from its start (swSignal.period); absent, the signal is not periodic. */
static int signal_period(swSema *S, swScope *scope, const swAst *call, const swAst *e,
                         swSignalVal *sig) {
  sig->period = val_error();
  if (!e) return 1;
  sig->period = scalar_arg(S, scope, e, DIM_TIME, call->name, "period", 0, call->loc);
  if (sig->period.kind == VAL_ERROR) return 0;
  if (!(sig->period.v[0] > 0)) {
    diag_error(sig->period.loc, "the period of %s() must be positive, got %g s", call->name,
               sig->period.v[0]);
    return 0;
  }
  return 1;
}

/* bspline(c0, c1, c2, c3, ..., over = T, from = t0, period = P): a clamped
 * cubic B-spline with the coefficients c_i on uniform knots over [t0, t0+T]
 * (SW_SIG_BSPLINE); the coefficients are positional, share one dimension
 * and are at least 4 (a cubic needs 4) and at most SW_SIGNAL_MAXPTS. */
static swValue eval_bspline(swSema *S, swScope *scope, const swAst *call, swSignalVal *sig) {
  const swAst *args = ast_kid(call, 0);
  static const char *const names[] = {"over", "from", "period"};
  const swAst *slot[3] = {NULL, NULL, NULL};
  swValue *coef = ast_alloc(S->a, (size_t)(args ? args->nkid : 0) * sizeof *coef + 1);
  int n = 0, ok = 1;
  sig->kind = SW_SIG_BSPLINE;
  for (int i = 0; args && i < args->nkid; i++) {
    const swAst *arg = args->kid[i];
    if (arg->kind != AST_ARG) {
      diag_error(arg->loc, "bspline() takes coefficients and over =, from =, period =");
      ok = 0;
      continue;
    }
    if (!arg->name) {
      if (slot[0] || slot[1] || slot[2]) {
        diag_error(arg->loc, "the coefficients of bspline() come before its named arguments");
        return val_error();
      }
      char what[64];
      snprintf(what, sizeof what, "coefficient %d of bspline()", n + 1);
      coef[n] = operand(S, scope, ast_kid(arg, 0));
      if (coef[n].kind != VAL_ERROR)
        coef[n] = sema_expect_value(S, coef[n], 1, n ? coef[0].dim : coef[n].dim,
                                    ast_strdup(S->a, what, strlen(what)));
      if (coef[n].kind == VAL_ERROR) ok = 0;
      n++;
      continue;
    }
    int k;
    for (k = 0; k < 3; k++)
      if (!strcmp(arg->name, names[k])) break;
    if (k == 3) {
      const char *near = diag_suggest(arg->name, names, 3);
      if (near)
        diag_error(arg->loc, "bspline() has no argument '%s'; did you mean '%s'?", arg->name, near);
      else
        diag_error(arg->loc, "bspline() has no argument '%s'", arg->name);
      ok = 0;
    } else if (slot[k]) {
      diag_error(arg->loc, "argument '%s' of bspline() is given twice", names[k]);
      ok = 0;
    } else slot[k] = ast_kid(arg, 0);
  }
  if (!ok) return val_error();
  if (n < 4 || n > SW_SIGNAL_MAXPTS) {
    diag_error(call->loc, "bspline() has %d coefficients; a cubic B-spline needs 4 to %d", n,
               SW_SIGNAL_MAXPTS);
    return val_error();
  }
  if (!slot[0]) {
    diag_error(call->loc, "bspline() needs the argument 'over' (the time it spans)");
    return val_error();
  }
  sig->T = scalar_arg(S, scope, slot[0], DIM_TIME, "bspline", "over", 0, call->loc);
  sig->t0 = scalar_arg(S, scope, slot[1], DIM_TIME, "bspline", "from", 0, call->loc);
  if (sig->T.kind == VAL_ERROR || sig->t0.kind == VAL_ERROR) return val_error();
  if (!(sig->T.v[0] > 0)) {
    diag_error(sig->T.loc, "bspline() needs a positive duration 'over', got %g s", sig->T.v[0]);
    return val_error();
  }
  if (!signal_period(S, scope, call, slot[2], sig)) return val_error();
  sig->values = val_vec(S->a, n, NULL, coef[0].dim, call->loc);
  for (int i = 0; i < n; i++) {
    sig->values.v[i] = coef[i].v[0];
    if (coef[i].c && coef[i].c[0]) {
      if (!sig->values.c) sig->values.c = ast_alloc(S->a, (size_t)n * sizeof *sig->values.c);
      sig->values.c[i] = coef[i].c[0];
      sig->values.param = coef[i].param;
    }
  }
  sig->npts = n;
  return make_signal(S, sig, coef[0].dim, call->loc);
}

static swValue eval_signal(swSema *S, swScope *scope, const swAst *call) {
  const swAst *args = ast_kid(call, 0);
  const swAst *slot[6];
  swSignalVal *sig = ast_alloc(S->a, sizeof *sig);
  swLoc loc = call->loc;
  if (!strcmp(call->name, "ramp")) {
    static const char *const names[] = {"from", "to", "over", "start", "period"};
    if (!bind_args(S, call, args, names, 5, 3, slot)) return val_error();
    if (!signal_period(S, scope, call, slot[4], sig)) return val_error();
    sig->kind = SW_SIG_RAMP;
    if (!same_dims(S, scope, call, slot[0], slot[1], "from", "to", &sig->a, &sig->b))
      return val_error();
    sig->T = scalar_arg(S, scope, slot[2], DIM_TIME, "ramp", "over", 0, loc);
    sig->t0 = scalar_arg(S, scope, slot[3], DIM_TIME, "ramp", "start", 0, loc);
    if (sig->T.kind == VAL_NUM && !(sig->T.v[0] > 0)) {
      diag_error(sig->T.loc, "ramp() needs a positive duration 'over', got %g s", sig->T.v[0]);
      return val_error();
    }
    if (any_error(&sig->a, 2) || sig->T.kind == VAL_ERROR || sig->t0.kind == VAL_ERROR)
      return val_error();
    return make_signal(S, sig, sig->a.dim, loc);
  }
  if (!strcmp(call->name, "sine")) {
    static const char *const names[] = {"amplitude", "freq", "mean", "phase", "start", "period"};
    if (!bind_args(S, call, args, names, 6, 2, slot)) return val_error();
    if (!signal_period(S, scope, call, slot[5], sig)) return val_error();
    sig->kind = SW_SIG_SINE;
    sig->b = operand(S, scope, slot[0]);
    if (sig->b.kind != VAL_ERROR)
      sig->b = sema_expect_value(S, sig->b, 1, sig->b.dim, "argument 'amplitude' of sine()");
    if (sig->b.kind == VAL_ERROR) return val_error();
    sig->freq = scalar_arg(S, scope, slot[1], dim_make(0, 0, -1, 0), "sine", "freq", 0, loc);
    sig->a = scalar_arg(S, scope, slot[2], sig->b.dim, "sine", "mean", 0, loc);
    sig->phase = scalar_arg(S, scope, slot[3], DIM_ANGLE, "sine", "phase", 0, loc);
    sig->t0 = scalar_arg(S, scope, slot[4], DIM_TIME, "sine", "start", 0, loc);
    if (sig->freq.kind == VAL_ERROR || sig->a.kind == VAL_ERROR ||
        sig->phase.kind == VAL_ERROR || sig->t0.kind == VAL_ERROR)
      return val_error();
    return make_signal(S, sig, sig->b.dim, loc);
  }
  if (!strcmp(call->name, "step")) {
    static const char *const names[] = {"before", "after", "at", "period"};
    if (!bind_args(S, call, args, names, 4, 3, slot)) return val_error();
    if (!signal_period(S, scope, call, slot[3], sig)) return val_error();
    sig->kind = SW_SIG_STEP;
    if (!same_dims(S, scope, call, slot[0], slot[1], "before", "after", &sig->a, &sig->b))
      return val_error();
    sig->t0 = scalar_arg(S, scope, slot[2], DIM_TIME, "step", "at", 0, loc);
    if (sig->t0.kind == VAL_ERROR) return val_error();
    return make_signal(S, sig, sig->a.dim, loc);
  }
  /* table(times = (...) s, values = (...)) */
  if (!strcmp(call->name, "bspline")) return eval_bspline(S, scope, call, sig);
  static const char *const names[] = {"times", "values", "period"};
  if (!bind_args(S, call, args, names, 3, 2, slot)) return val_error();
  if (!signal_period(S, scope, call, slot[2], sig)) return val_error();
  sig->kind = SW_SIG_TABLE;
  sig->times = operand(S, scope, slot[0]);
  sig->values = operand(S, scope, slot[1]);
  if (sig->times.kind == VAL_ERROR || sig->values.kind == VAL_ERROR) return val_error();
  if (sig->times.kind != VAL_VEC || sig->values.kind != VAL_VEC) {
    diag_error(loc, "table() takes two lists of at least 2 numbers: times = (t0, t1, ...) s, "
               "values = (v0, v1, ...)");
    return val_error();
  }
  if (sig->times.n != sig->values.n) {
    diag_error(loc, "table() has %d times but %d values", sig->times.n, sig->values.n);
    return val_error();
  }
  if (sig->times.n > SW_SIGNAL_MAXPTS) {
    diag_error(loc, "table() holds at most %d points, got %d", SW_SIGNAL_MAXPTS, sig->times.n);
    return val_error();
  }
  sig->times = sema_expect_value(S, sig->times, sig->times.n, DIM_TIME, "argument 'times' of table()");
  if (sig->times.kind == VAL_ERROR) return val_error();
  if (!sema_require_const(S, &sig->times, "the times of table()")) return val_error();
  for (int i = 1; i < sig->times.n; i++)
    if (!(sig->times.v[i] > sig->times.v[i - 1])) {
      diag_error(sig->times.loc, "the times of table() must increase, but time %d (%g s) is "
                 "not after time %d (%g s)", i + 1, sig->times.v[i], i, sig->times.v[i - 1]);
      return val_error();
    }
  sig->npts = sig->times.n;
  return make_signal(S, sig, sig->values.dim, loc);
}

/* max(a, b), min(a, b): numbers of one dimension; abs(a).  A value known
 * only at the end of a run (NaN) stays unknown. */
static swValue eval_extreme(swSema *S, swScope *scope, const swAst *e) {
  const char *fn = e->name;
  const swAst *args = ast_kid(e, 0);
  const int n = fn[0] == 'a' ? 1 : 2;
  int ok = args && args->nkid == n;
  for (int i = 0; ok && i < n; i++) ok = args->kid[i]->kind == AST_ARG && !args->kid[i]->name;
  if (!ok) {
    diag_error(e->loc, n == 1 ? "abs() takes one number" : "%s() takes two numbers", fn);
    return val_error();
  }
  swValue x[2];
  for (int i = 0; i < n; i++) {
    x[i] = operand(S, scope, ast_kid(args->kid[i], 0));
    if (x[i].kind != VAL_ERROR && x[i].kind != VAL_NUM) {
      diag_error(x[i].loc, "%s() takes numbers, not %s", fn, describe_value(S, &x[i]));
      x[i] = val_error();
    }
  }
  if (x[0].kind == VAL_ERROR || (n == 2 && x[1].kind == VAL_ERROR)) return val_error();
  if (n == 2 && !dim_eq(x[0].dim, x[1].dim)) {
    diag_error(e->loc, "%s() compares numbers of one dimension, but the first is %s and the "
               "second %s", fn, describe_value(S, &x[0]), describe_value(S, &x[1]));
    return val_error();
  }
  const double a = x[0].v[0], b = n == 2 ? x[1].v[0] : 0;
  double r = n == 1 ? fabs(a) : isnan(a) || isnan(b) ? NAN : fn[1] == 'a' ? fmax(a, b) : fmin(a, b);
  swValue v = val_num(S->a, r, x[0].dim, e->loc);
  v.param = x[0].param ? x[0].param : n == 2 ? x[1].param : NULL;
  if (!val_is_const(&x[0]) || (n == 2 && !val_is_const(&x[1]))) {
    char buf[4096];
    int len = n == 1 ? snprintf(buf, sizeof buf, "fabs(%s)", val_c(S->a, &x[0], 0))
                     : snprintf(buf, sizeof buf, "%s(%s, %s)", fn[1] == 'a' ? "fmax" : "fmin",
                                val_c(S->a, &x[0], 0), val_c(S->a, &x[1], 0));
    if (len >= (int)sizeof buf) {
      diag_error(e->loc, "expression is too long to generate");
      return val_error();
    }
    v.c = ast_alloc(S->a, sizeof *v.c);
    v.c[0] = ast_strdup(S->a, buf, (size_t)len);
  }
  return v;
}

/* round(x): the whole number nearest a plain number known when compiling,
 * halves away from zero as ROD.at(f) picks its node (lround), so that a model
 * can put a point exactly on a node: ROD.at(round(f * n) / n) of a rod of n
 * elements.  A plain number only: the whole number nearest a length would
 * depend on its unit. */
static swValue eval_round(swSema *S, swScope *scope, const swAst *e) {
  const swAst *args = ast_kid(e, 0);
  if (!args || args->nkid != 1 || args->kid[0]->name) {
    diag_error(e->loc, "round() takes one argument, a plain number");
    return val_error();
  }
  swValue x = sema_expect(S, scope, ast_kid(args->kid[0], 0), 1, DIM_NONE,
                          "the argument of round()");
  if (!known_at_build(S, &x, "the argument of round()")) return val_error();
  swValue r = val_num(S->a, round(x.v[0]), DIM_NONE, e->loc);
  if (x.c && x.c[0]) {   /* a param's: rounded when the simulator builds the scene */
    char buf[4200];
    if (snprintf(buf, sizeof buf, "round(%s)", x.c[0]) >= (int)sizeof buf) {
      diag_error(e->loc, "expression is too long to generate");
      return val_error();
    }
    r.c = ast_alloc(S->a, sizeof *r.c);
    r.c[0] = ast_strdup(S->a, buf, strlen(buf));
    r.param = x.param;
  }
  return r;
}

static swValue eval_call(swSema *S, swScope *scope, const swAst *e) {
  const char *fn = e->name;
  const swAst *args = ast_kid(e, 0);
  if (!strcmp(fn, "max") || !strcmp(fn, "min") || !strcmp(fn, "abs"))
    return eval_extreme(S, scope, e);
  if (!strcmp(fn, "round")) return eval_round(S, scope, e);
  if (!strcmp(fn, "at") || !strcmp(fn, "mean_over") || !strcmp(fn, "max_over") ||
      !strcmp(fn, "min_over"))
    return sema_reduction(S, scope, e);
  if (!strcmp(fn, "ramp") || !strcmp(fn, "sine") || !strcmp(fn, "step") ||
      !strcmp(fn, "table") || !strcmp(fn, "bspline"))
    return eval_signal(S, scope, e);
  if (!strcmp(fn, "piecewise")) {
    diag_error(e->loc, "piecewise() belongs in a terrain's height(x, y)");
    return val_error();
  }
  if (!strcmp(fn, "sqrt") || !strcmp(fn, "sin") || !strcmp(fn, "cos") || !strcmp(fn, "tan") ||
      !strcmp(fn, "exp")) {
    if (!args || args->nkid != 1 || args->kid[0]->name) {
      diag_error(e->loc, "%s() takes one argument", fn);
      return val_error();
    }
    return val_func(S->a, fn, operand(S, scope, ast_kid(args->kid[0], 0)), e->loc);
  }
  const char *near = diag_suggest(fn, functions, NFUNCTIONS);
  if (near)
    diag_error(e->loc, "unknown function '%s'; did you mean '%s'?", fn, near);
  else {
    char list[256];
    diag_join(list, sizeof list, functions, NFUNCTIONS);
    diag_error(e->loc, "unknown function '%s' (the functions: %s)", fn, list);
  }
  return val_error();
}

/* ---- names and members ---- */

static swValue symbol_value(swSema *S, swSymbol *sym, swLoc loc) {
  sym->used = 1;
  switch (sym->kind) {
  case SYM_PARAM:
  case SYM_LET:
  case SYM_FORMAL: {
    sema_eval_symbol(S, sym);
    swValue v = sym->value;
    if (v.kind != VAL_ERROR) v.loc = loc;
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
  diag_error(e->loc, "%s has no member '%s'", describe_value(S, &b), e->name);
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
      diag_error(e->loc, "'%s(...)' applies to a rod, not to %s", e->name, describe_value(S, &b));
    return val_error();
  }
  const swAst *args = ast_kid(e, 1);
  if (!args || args->nkid != 1 || args->kid[0]->name) {
    diag_error(e->loc, "at() takes one argument, the fraction of the rod's length (0 to 1)");
    return val_error();
  }
  swValue f = sema_expect(S, scope, ast_kid(args->kid[0], 0), 1, DIM_NONE,
                          "the fraction in at()");
  if (!known_at_build(S, &f, "the fraction in at()")) return val_error();
  /* a param's fraction is checked here at its default; the simulator refuses
     a node off the rod when it builds the scene */
  if (!(f.v[0] >= 0 && f.v[0] <= 1)) {
    diag_error(f.loc, "the fraction in at() must be between 0 and 1, got %g%s", f.v[0],
               f.param ? " with the params at their defaults" : "");
    return val_error();
  }
  return sema_rod_point(S, b.ref, f, -2, e->loc);
}

static swValue eval_vector(swSema *S, swScope *scope, const swAst *e) {
  swValue *parts = ast_alloc(S->a, (size_t)e->nkid * sizeof *parts);
  int bad = 0;
  for (int i = 0; i < e->nkid; i++) {
    parts[i] = operand(S, scope, e->kid[i]);
    if (parts[i].kind == VAL_ERROR) bad = 1;
    else if (parts[i].kind != VAL_NUM) {
      diag_error(e->kid[i]->loc, "a vector component must be a number, not %s",
                 describe_value(S, &parts[i]));
      bad = 1;
    }
  }
  if (bad) return val_error();
  for (int i = 1; i < e->nkid; i++)
    if (!dim_eq(parts[i].dim, parts[0].dim)) {
      diag_error(e->kid[i]->loc, "vector components must share one dimension: component 1 is "
                 "%s, component %d is %s", describe_value(S, &parts[0]), i + 1,
                 describe_value(S, &parts[i]));
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

swValue sema_eval(swSema *S, swScope *scope, const swAst *e) {
  if (!e) return val_error();
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
      swValue x = operand(S, scope, e->kid[0]);
      swValue p = operand(S, scope, e->kid[1]);
      if (x.kind == VAL_ERROR || p.kind == VAL_ERROR) return val_error();
      if (p.kind != VAL_NUM || !dim_is_none(p.dim) || !val_is_const(&p)) {
        diag_error(e->kid[1]->loc, "an exponent must be a plain number known when compiling");
        return val_error();
      }
      return val_pow(S->a, x, p.v[0], e->loc);
    }
    swValue x = operand(S, scope, e->kid[0]);
    swValue y = operand(S, scope, e->kid[1]);
    return val_binop(S->a, e->op, x, y, e->loc);
  }
  case AST_APPLY: {
    swValue x = operand(S, scope, e->kid[0]);
    swValue u = operand(S, scope, e->kid[1]);
    return val_binop(S->a, '*', x, u, e->loc);
  }
  case AST_NEG:
    return val_neg(S->a, operand(S, scope, e->kid[0]), e->loc);
  case AST_VEC:
    return eval_vector(S, scope, e);
  case AST_CALL:
    return eval_call(S, scope, e);
  case AST_MEMBER:
    return eval_member(S, scope, e);
  case AST_METHOD:
    return eval_method(S, scope, e);
  default:
    diag_error(e->loc, "a %s is not a value", ast_kind_name(e->kind));
    return val_error();
  }
}
