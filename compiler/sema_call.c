/* sema_call.c — calls of the built-in functions: the time signals (ramp,
 * sine, step, table, bspline), max, min, abs, round, and sqrt, sin, cos,
 * tan, exp.
 *
 * Design.  sema_eval (sema_expr.c) hands every call here, to sema_eval_call,
 * which dispatches on the function's name.  Time signals are the runtime's
 * (constant, ramp, sine, step, table) with their arguments, positional or
 * by name, checked by dimension; a signal may only be scaled.  max(a, b),
 * min(a, b) and abs(a) take numbers (of one dimension); the reductions of the
 * run, at() and the *_over() windows, are sema_objective.c's.  An unknown
 * function gets the nearest known one.  Apart from sema_expr.c because each
 * function has arguments and checks of its own, while the walk over an
 * expression is the same for all.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sema_int.h"

static const char *const functions[] = {"sqrt", "sin", "cos", "tan", "ramp", "sine", "step",
                                        "table", "bspline", "exp", "piecewise", "max", "min",
                                        "abs", "round", "at", "mean_over", "max_over", "min_over",
                                        "atan2", "log"};
enum { NFUNCTIONS = sizeof functions / sizeof functions[0] };

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
  *a = sema_operand(S, scope, ea);
  *b = sema_operand(S, scope, eb);
  if (a->kind == VAL_ERROR || b->kind == VAL_ERROR) return 0;
  snprintf(what, sizeof what, "argument '%s' of %s()", na, call->name);
  *a = sema_expect_value(S, *a, 1, a->dim, ast_strdup(S->a, what, strlen(what)));
  snprintf(what, sizeof what, "argument '%s' of %s()", nb, call->name);
  *b = sema_expect_value(S, *b, 1, b->dim, ast_strdup(S->a, what, strlen(what)));
  if (a->kind == VAL_ERROR || b->kind == VAL_ERROR) return 0;
  if (!dim_eq(a->dim, b->dim)) {
    diag_error(call->loc, "%s() needs '%s' and '%s' in one dimension, but '%s' is %s and '%s' "
               "is %s", call->name, na, nb, na, sema_describe_value(S, a), nb,
               sema_describe_value(S, b));
    return 0;
  }
  return 1;
}

swValue sema_make_signal(swSema *S, swSignalVal *sig, swDim dim, swLoc loc) {
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
      coef[n] = sema_operand(S, scope, ast_kid(arg, 0));
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
  return sema_make_signal(S, sig, coef[0].dim, call->loc);
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
    return sema_make_signal(S, sig, sig->a.dim, loc);
  }
  if (!strcmp(call->name, "sine")) {
    static const char *const names[] = {"amplitude", "freq", "mean", "phase", "start", "period"};
    if (!bind_args(S, call, args, names, 6, 2, slot)) return val_error();
    if (!signal_period(S, scope, call, slot[5], sig)) return val_error();
    sig->kind = SW_SIG_SINE;
    sig->b = sema_operand(S, scope, slot[0]);
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
    return sema_make_signal(S, sig, sig->b.dim, loc);
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
    return sema_make_signal(S, sig, sig->a.dim, loc);
  }
  /* table(times = (...) s, values = (...)) */
  if (!strcmp(call->name, "bspline")) return eval_bspline(S, scope, call, sig);
  static const char *const names[] = {"times", "values", "period"};
  if (!bind_args(S, call, args, names, 3, 2, slot)) return val_error();
  if (!signal_period(S, scope, call, slot[2], sig)) return val_error();
  sig->kind = SW_SIG_TABLE;
  sig->times = sema_operand(S, scope, slot[0]);
  sig->values = sema_operand(S, scope, slot[1]);
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
  return sema_make_signal(S, sig, sig->values.dim, loc);
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
    x[i] = sema_operand(S, scope, ast_kid(args->kid[i], 0));
    if (x[i].kind != VAL_ERROR && x[i].kind != VAL_NUM) {
      diag_error(x[i].loc, "%s() takes numbers, not %s", fn, sema_describe_value(S, &x[i]));
      x[i] = val_error();
    }
  }
  if (x[0].kind == VAL_ERROR || (n == 2 && x[1].kind == VAL_ERROR)) return val_error();
  if (n == 2 && !dim_eq(x[0].dim, x[1].dim)) {
    diag_error(e->loc, "%s() compares numbers of one dimension, but the first is %s and the "
               "second %s", fn, sema_describe_value(S, &x[0]), sema_describe_value(S, &x[1]));
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
  if (!sema_known_at_build(S, &x, "the argument of round()")) return val_error();
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

/* atan2(y, x): the angle of the vector (x, y), in (-pi, pi] rad, of two
 * numbers of one dimension known when compiling (a direction's angle in a
 * plane, for a layout). */
static swValue eval_atan2(swSema *S, swScope *scope, const swAst *e) {
  const swAst *args = ast_kid(e, 0);
  if (!args || args->nkid != 2 || args->kid[0]->name || args->kid[1]->name) {
    diag_error(e->loc, "atan2() takes two numbers, y and x: atan2(d.y, d.x)");
    return val_error();
  }
  swValue y = sema_operand(S, scope, ast_kid(args->kid[0], 0));
  swValue x = sema_operand(S, scope, ast_kid(args->kid[1], 0));
  if (y.kind == VAL_ERROR || x.kind == VAL_ERROR) return val_error();
  if (y.kind != VAL_NUM || x.kind != VAL_NUM || !dim_eq(x.dim, y.dim)) {
    diag_error(e->loc, "atan2() takes two numbers of one dimension, y and x");
    return val_error();
  }
  if (!val_is_const(&x) || !val_is_const(&y)) {
    diag_error(e->loc, "atan2() takes numbers known when compiling");
    return val_error();
  }
  return val_num(S->a, atan2(y.v[0], x.v[0]), DIM_ANGLE, e->loc);
}

swValue sema_eval_call(swSema *S, swScope *scope, const swAst *e) {
  const char *fn = e->name;
  const swAst *args = ast_kid(e, 0);
  if (!strcmp(fn, "atan2")) return eval_atan2(S, scope, e);
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
    diag_error(e->loc, "piecewise() belongs in a terrain's height(x, y) or a signal NAME(t)");
    return val_error();
  }
  if (!strcmp(fn, "sqrt") || !strcmp(fn, "sin") || !strcmp(fn, "cos") || !strcmp(fn, "tan") ||
      !strcmp(fn, "exp") || !strcmp(fn, "log")) {
    if (!args || args->nkid != 1 || args->kid[0]->name) {
      diag_error(e->loc, "%s() takes one argument", fn);
      return val_error();
    }
    return val_func(S->a, fn, sema_operand(S, scope, ast_kid(args->kid[0], 0)), e->loc);
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
