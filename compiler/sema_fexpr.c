/* sema_fexpr.c — function expressions: a terrain's height(x, y) and a time
 * signal's body, checked into a tree over their formals, and evaluated
 * inside the compiler.
 *
 * Design.  A height or a signal is not a value when compiling: it is a
 * function of its formals (x and y, lengths; t, a time).  It is checked into
 * a swHExpr tree (sema.h), apart from the value walk of sema_expr.c: every
 * subexpression that does not depend on a formal is evaluated by sema_eval
 * and folded into one constant node (a swValue, so a param keeps its C
 * expression), the rest keeps its operation and dimension.  Beyond +, -, *,
 * /, ^ (constant exponent), sqrt, sin, cos, tan, exp and log, the tree may
 * compare (< <= > >=, and, or) and choose with piecewise(cond: value, ...,
 * default), the first true condition winning.  A signal may also hold the
 * built-in signals (ramp, sine, step, table, bspline) read at its time, the
 * model's other signals called at a time expression, and mod(a, b), which
 * makes anything periodic.  The two users, sema_terrain.c and
 * sema_signal.c, set the formals and what they admit in a swFCtx; gen_env.c
 * prints the trees as C, and sema_fexpr_eval here evaluates them with the
 * same rules (a height's gradient by forward mode, a signal's value alone).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gen.h"
#include "sema_int.h"

static swHExpr *hx(swFCtx *C, const swAst *e);
static swHExpr *hx_value(swFCtx *C, const swAst *e);

swHExpr *sema_fexpr_node(swSema *S, swHOp op, swDim dim, swLoc loc, int nkid) {
  swHExpr *e = ast_alloc(S->a, sizeof *e);
  memset(e, 0, sizeof *e);
  e->op = op;
  e->dim = dim;
  e->loc = loc;
  e->k = val_error();
  e->nkid = nkid;
  if (nkid) e->kid = ast_alloc(S->a, (size_t)nkid * sizeof *e->kid);
  return e;
}

static swHExpr *constant(swSema *S, swValue v) {
  swHExpr *e = sema_fexpr_node(S, HX_CONST, v.dim, v.loc, 0);
  e->k = v;
  return e;
}

const char *sema_fexpr_dim_text(swSema *S, const swHExpr *e) {
  if (e->boolean) return "a condition";
  if (dim_is_none(e->dim)) return "dimensionless (a number without a unit)";
  return dim_describe(S->a, e->dim);
}


/* A quantity (not a condition); NULL after an error. */
swHExpr *sema_fexpr(swFCtx *C, const swAst *e, const char *role) {
  swHExpr *q = hx(C, e);
  if (q && q->boolean) {
    diag_error(e->loc, "%s must be a value, not a condition", role);
    return NULL;
  }
  return q;
}

static swHExpr *condition(swFCtx *C, const swAst *e) {
  swHExpr *q = hx(C, e);
  if (q && !q->boolean) {
    diag_error(e->loc, "a condition of piecewise() must be a comparison (%s < 3 %s), not a value", C->formal[0], C->time ? "s" : "m");
    return NULL;
  }
  return q;
}

static swHExpr *name(swFCtx *C, const swAst *e) {
  swSema *S = C->S;
  for (int i = 0; i < C->nformal; i++)
    if (!strcmp(e->name, C->formal[i])) return sema_fexpr_node(S, C->formal_op[i], C->formal_dim[i], e->loc, 0);
  for (int i = C->nlocal - 1; i >= 0; i--)
    if (!strcmp(e->name, C->local_name[i])) {
      C->local_used[i] = 1;
      return C->local[i];
    }
  if (C->time) {   /* another signal of the model, named without a time: at this one's */
    swSymbol *sym = sema_lookup(S, C->scope, e->name);
    if (sym && sym->kind == SYM_SIGNAL) {
      diag_error(e->loc, "signal '%s' is a function of time: call it at a time, %s(%s)", e->name,
                 e->name, C->formal[0]);
      return NULL;
    }
  }
  swValue v = sema_eval(S, C->scope, e);
  if (v.kind == VAL_WORD) {
    const char *cands[SW_FEXPR_MAX_LETS + 2];
    int n = 0;
    for (int i = 0; i < C->nformal; i++) cands[n++] = C->formal[i];
    for (int i = 0; i < C->nlocal; i++) cands[n++] = C->local_name[i];
    const char *near = diag_suggest(e->name, cands, n);
    if (near) diag_error(e->loc, "unknown name '%s' in %s; did you mean '%s'?", e->name, C->what, near);
    else sema_report_unknown(S, C->scope, e->name, e->loc, "name");
    return NULL;
  }
  if (v.kind == VAL_ERROR) return NULL;
  if (v.kind == VAL_SIGNAL) {
    diag_error(e->loc, "'%s' is a time signal; inside %s call a signal at a time, NAME(%s)",
               e->name, C->what, C->nformal ? C->formal[0] : "t");
    return NULL;
  }
  v = sema_expect_value(S, v, 1, v.dim, C->term);
  return v.kind == VAL_ERROR ? NULL : constant(S, v);
}

static swHExpr *binop(swFCtx *C, const swAst *e, int op, const swAst *l, const swAst *r) {
  swSema *S = C->S;
  if (op == '&' || op == '|') {
    swHExpr *a = condition(C, l), *b = condition(C, r);
    if (!a || !b) return NULL;
    swHExpr *n = sema_fexpr_node(S, op == '&' ? HX_AND : HX_OR, DIM_NONE, e->loc, 2);
    n->boolean = 1;
    n->kid[0] = a;
    n->kid[1] = b;
    return n;
  }
  swHExpr *a = sema_fexpr(C, l, "an operand"), *b = sema_fexpr(C, r, "an operand");
  if (!a || !b) return NULL;
  if (strchr("<>lg", op)) {
    if (!dim_eq(a->dim, b->dim)) {
      diag_error(e->loc, "cannot compare %s and %s", sema_fexpr_dim_text(S, a), sema_fexpr_dim_text(S, b));
      return NULL;
    }
    swHExpr *n = sema_fexpr_node(S, op == '<' ? HX_LT : op == '>' ? HX_GT : op == 'l' ? HX_LE : HX_GE,
                      DIM_NONE, e->loc, 2);
    n->boolean = 1;
    n->kid[0] = a;
    n->kid[1] = b;
    return n;
  }
  if (a->op == HX_CONST && b->op == HX_CONST) {
    swValue v = val_binop(S->a, op, a->k, b->k, e->loc);
    return v.kind == VAL_ERROR ? NULL : constant(S, v);
  }
  swDim dim;
  if (op == '+' || op == '-') {
    if (!dim_eq(a->dim, b->dim)) {
      diag_error(e->loc, "cannot %s %s and %s", op == '+' ? "add" : "subtract", sema_fexpr_dim_text(S, a),
                 sema_fexpr_dim_text(S, b));
      return NULL;
    }
    dim = a->dim;
  } else {
    dim = op == '*' ? dim_mul(a->dim, b->dim) : dim_div(a->dim, b->dim);
  }
  swHExpr *n = sema_fexpr_node(S, op == '+' ? HX_ADD : op == '-' ? HX_SUB : op == '*' ? HX_MUL : HX_DIV, dim,
                    e->loc, 2);
  n->kid[0] = a;
  n->kid[1] = b;
  return n;
}

static swHExpr *power(swFCtx *C, const swAst *e) {
  swSema *S = C->S;
  swHExpr *a = sema_fexpr(C, e->kid[0], "a base");
  swValue p = sema_eval(S, C->scope, e->kid[1]);
  if (!a || p.kind == VAL_ERROR) return NULL;
  if (p.kind != VAL_NUM || !dim_is_none(p.dim) || !val_is_const(&p)) {
    diag_error(e->kid[1]->loc, "an exponent must be a plain number known when compiling");
    return NULL;
  }
  if (a->op == HX_CONST) {
    swValue v = val_pow(S->a, a->k, p.v[0], e->loc);
    return v.kind == VAL_ERROR ? NULL : constant(S, v);
  }
  swDim dim;
  if (!dim_pow(a->dim, p.v[0], &dim)) {
    diag_error(e->loc, "%s can only be raised to an integer power, not %g", sema_fexpr_dim_text(S, a), p.v[0]);
    return NULL;
  }
  swHExpr *n = sema_fexpr_node(S, HX_POW, dim, e->loc, 1);
  n->kid[0] = a;
  n->p = p.v[0];
  return n;
}

static const char *const funcs[] = {"sqrt", "sin", "cos", "tan", "exp", "log", "piecewise"};

static swHExpr *piecewise(swFCtx *C, const swAst *e, const swAst *args) {
  swSema *S = C->S;
  int n = args ? args->nkid : 0;
  if (n < 2) {
    diag_error(e->loc, "piecewise() takes cases 'condition: value' and a default value last: "
               "piecewise(x < 1 m: 0 m, 0.2 m)");
    return NULL;
  }
  if (args->kid[n - 1]->kind == AST_CASE) {
    diag_error(args->kid[n - 1]->loc, "piecewise() needs a default value last, for when no "
               "condition holds: piecewise(x < 1 m: 0 m, 0.2 m)");
    return NULL;
  }
  swHExpr *pw = sema_fexpr_node(S, HX_PIECEWISE, DIM_NONE, e->loc, 2 * (n - 1) + 1);
  const swHExpr *first = NULL;   /* the first good value sets the dimension */
  int ok = 1, nfirst = 0;
  for (int i = 0; i < n; i++) {
    const swAst *a = args->kid[i];
    if (a->kind != AST_CASE && i < n - 1) {
      diag_error(a->loc, "every argument of piecewise() but the last is 'condition: value'");
      ok = 0;
      continue;
    }
    if (a->kind == AST_ARG && a->name) {
      diag_error(a->loc, "piecewise() has no argument '%s'", a->name);
      ok = 0;
      continue;
    }
    const swAst *ve = a->kind == AST_CASE ? a->kid[1] : ast_kid(a, 0);
    if (a->kind == AST_CASE) {
      pw->kid[2 * i] = condition(C, a->kid[0]);
      if (!pw->kid[2 * i]) ok = 0;
    }
    swHExpr *v = sema_fexpr(C, ve, "a value of piecewise()");
    if (!v) {
      ok = 0;
      continue;
    }
    pw->kid[i < n - 1 ? 2 * i + 1 : 2 * (n - 1)] = v;
    if (!first) {
      first = v;
      nfirst = i + 1;
      pw->dim = v->dim;
    } else if (!dim_eq(v->dim, pw->dim)) {
      diag_error(ve->loc, "the values of piecewise() must share one dimension: value %d is %s, "
                 "value %d is %s", nfirst, sema_fexpr_dim_text(S, first), i + 1, sema_fexpr_dim_text(S, v));
      ok = 0;
    }
  }
  return ok ? pw : NULL;
}

/* ---- what only a signal may hold ---- */

/* A built-in signal (ramp, sine, step, table, bspline) read at the formal
 * time: checked as everywhere else (sema_call.c), kept as the scene's atom. */
static swHExpr *atom(swFCtx *C, const swAst *e) {
  swSema *S = C->S;
  swValue v = sema_eval_call(S, C->scope, e);
  if (v.kind == VAL_ERROR) return NULL;
  swScene *sc = S->scene;
  if (sc->natom == sc->capatom) {
    sc->capatom = sc->capatom ? 2 * sc->capatom : 8;
    swSignalVal **grown = ast_alloc(S->a, (size_t)sc->capatom * sizeof *grown);
    if (sc->natom) memcpy(grown, sc->atom, (size_t)sc->natom * sizeof *grown);
    sc->atom = grown;
  }
  swHExpr *n = sema_fexpr_node(S, HX_ATOM, v.dim, e->loc, 1);
  n->ref = sc->natom;
  n->atom = v.sig;
  sc->atom[sc->natom++] = v.sig;
  n->kid[0] = sema_fexpr_node(S, HX_T, DIM_TIME, e->loc, 0);
  return n;
}

/* mod(a, b) = a - b floor(a / b): of one dimension, b > 0 when known */
static swHExpr *mod(swFCtx *C, const swAst *e, const swAst *args) {
  swSema *S = C->S;
  if (!args || args->nkid != 2 || args->kid[0]->name || args->kid[1]->name ||
      args->kid[0]->kind != AST_ARG || args->kid[1]->kind != AST_ARG) {
    diag_error(e->loc, "mod() takes two values of one dimension: mod(t, 0.38 s)");
    return NULL;
  }
  swHExpr *a = sema_fexpr(C, args->kid[0]->kid[0], "an argument of mod()");
  swHExpr *b = sema_fexpr(C, args->kid[1]->kid[0], "an argument of mod()");
  if (!a || !b) return NULL;
  if (!dim_eq(a->dim, b->dim)) {
    diag_error(e->loc, "mod() takes two values of one dimension, but the first is %s and the "
               "second %s", sema_fexpr_dim_text(S, a), sema_fexpr_dim_text(S, b));
    return NULL;
  }
  if (b->op == HX_CONST && !(b->k.v[0] > 0)) {
    diag_error(args->kid[1]->loc, "the divisor of mod() must be positive, got %g", b->k.v[0]);
    return NULL;
  }
  swHExpr *n = sema_fexpr_node(S, HX_MOD, a->dim, e->loc, 2);
  n->kid[0] = a;
  n->kid[1] = b;
  return n;
}

/* NAME(time): another signal of the model at a time */
static swHExpr *signal_call(swFCtx *C, const swAst *e, swSymbol *sym, const swAst *args) {
  swSema *S = C->S;
  if (!args || args->nkid != 1 || args->kid[0]->name || args->kid[0]->kind != AST_ARG) {
    diag_error(e->loc, "signal '%s' takes one argument, a time: %s(%s - 0.1 s)", e->name, e->name,
               C->formal[0]);
    return NULL;
  }
  swHExpr *at = sema_fexpr(C, args->kid[0]->kid[0], "the time of a signal");
  if (!at) return NULL;
  if (!dim_eq(at->dim, DIM_TIME)) {
    diag_error(args->kid[0]->loc, "signal '%s' is a function of time, but its argument is %s",
               e->name, sema_fexpr_dim_text(S, at));
    return NULL;
  }
  swSceneSignal *callee = sema_signal_of(S, sym, e->loc);
  if (!callee) return NULL;
  swHExpr *n = sema_fexpr_node(S, HX_CALL, callee->dim, e->loc, 1);
  n->ref = callee->index;
  n->callee = callee;
  n->kid[0] = at;
  return n;
}

static swHExpr *call(swFCtx *C, const swAst *e) {
  swSema *S = C->S;
  const swAst *args = ast_kid(e, 0);
  int k;
  for (k = 0; k < 7; k++)
    if (!strcmp(e->name, funcs[k])) break;
  if (k == 6) return piecewise(C, e, args);
  if (k == 7) {
    const int builtin = !strcmp(e->name, "ramp") || !strcmp(e->name, "sine") ||
                        !strcmp(e->name, "step") || !strcmp(e->name, "table") ||
                        !strcmp(e->name, "bspline");
    if (builtin && !C->time) {
      diag_error(e->loc, "%s does not change in time: %s() has no place in it",
                 C->shape ? "a shape" : "a height", e->name);
      return NULL;
    }
    if (C->time) {
      if (builtin) return atom(C, e);
      if (!strcmp(e->name, "mod")) return mod(C, e, args);
      swSymbol *sym = sema_lookup(S, C->scope, e->name);
      if (sym && sym->kind == SYM_SIGNAL) return signal_call(C, e, sym, args);
    }
    static const char *const all[] = {"sqrt", "sin", "cos", "tan", "exp", "log", "piecewise",
                                      "mod", "ramp", "sine", "step", "table", "bspline"};
    const char *near = diag_suggest(e->name, all, C->time ? 13 : 7);
    if (near) diag_error(e->loc, "unknown function '%s'; did you mean '%s'?", e->name, near);
    else if (C->time)
      diag_error(e->loc, "unknown function '%s' (a signal may use sqrt, sin, cos, tan, exp, "
                 "log, piecewise, mod, ramp, sine, step, table, bspline and the model's signals)",
                 e->name);
    else diag_error(e->loc, "unknown function '%s' (%s may use sqrt, sin, cos, tan, exp, log "
                    "and piecewise)", e->name, C->shape ? "a shape" : "a height");
    return NULL;
  }
  if (!args || args->nkid != 1 || args->kid[0]->kind != AST_ARG || args->kid[0]->name) {
    diag_error(e->loc, "%s() takes one argument", e->name);
    return NULL;
  }
  swHExpr *a = sema_fexpr(C, args->kid[0]->kid[0], "an argument");
  if (!a) return NULL;
  if (a->op == HX_CONST) {
    swValue v = val_func(S->a, e->name, a->k, e->loc);
    return v.kind == VAL_ERROR ? NULL : constant(S, v);
  }
  swDim dim = DIM_NONE;
  if (k == 0) {
    for (int i = 0; i < SW_NDIM; i++) {
      if (a->dim.e[i] % 2) {
        diag_error(e->loc, "sqrt() of %s has no dimension", sema_fexpr_dim_text(S, a));
        return NULL;
      }
      dim.e[i] = (signed char)(a->dim.e[i] / 2);
    }
  } else if (k < 4 ? !dim_is_none(a->dim) && !dim_eq(a->dim, DIM_ANGLE) : !dim_is_none(a->dim)) {
    diag_error(e->loc, "%s() takes %s, not %s", e->name,
               k < 4 ? "an angle or a plain number" : "a plain number", sema_fexpr_dim_text(S, a));
    return NULL;
  }
  static const swHOp ops[] = {HX_SQRT, HX_SIN, HX_COS, HX_TAN, HX_EXP, HX_LOG};
  swHExpr *n = sema_fexpr_node(S, ops[k], dim, e->loc, 1);
  n->kid[0] = a;
  return n;
}

static swHExpr *hx(swFCtx *C, const swAst *e) {
  swSema *S = C->S;
  switch (e->kind) {
  case AST_NAME:
    return name(C, e);
  case AST_UNIT:   /* a formal spelt as a unit: a shape's s (not seconds there) */
    for (int i = 0; i < C->nformal; i++)
      if (!strcmp(e->name, C->formal[i])) return name(C, e);
    return hx_value(C, e);
  case AST_BINOP:
    if (e->op == '^') return power(C, e);
    return binop(C, e, e->op, e->kid[0], e->kid[1]);
  case AST_APPLY:
    return binop(C, e, '*', e->kid[0], e->kid[1]);
  case AST_NEG: {
    swHExpr *a = sema_fexpr(C, e->kid[0], "an operand");
    if (!a) return NULL;
    if (a->op == HX_CONST) {
      swValue v = val_neg(S->a, a->k, e->loc);
      return v.kind == VAL_ERROR ? NULL : constant(S, v);
    }
    swHExpr *n = sema_fexpr_node(S, HX_NEG, a->dim, e->loc, 1);
    n->kid[0] = a;
    return n;
  }
  case AST_CALL:
    return call(C, e);
  case AST_VEC:
    diag_error(e->loc, "%s is one number at each %s, not a vector", C->what,
               C->time ? "time" : C->shape ? "arc length" : "(x, y)");
    return NULL;
  default:
    return hx_value(C, e);
  }
}

/* numbers, units, members (rod.length, v.x): values without a formal */
static swHExpr *hx_value(swFCtx *C, const swAst *e) {
  swSema *S = C->S;
  swValue v = sema_eval(S, C->scope, e);
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, C->scope, v.word, v.loc, "name");
    return NULL;
  }
  if (v.kind == VAL_ERROR) return NULL;
  v = sema_expect_value(S, v, 1, v.dim, C->term);
  return v.kind == VAL_ERROR ? NULL : constant(S, v);
}

/* ---- evaluation, with the gradient by forward mode ---- */



static int truth(const swHExpr *e, swDual X, swDual Y, const swDual *lets) {
  if (e->op == HX_AND) return truth(e->kid[0], X, Y, lets) && truth(e->kid[1], X, Y, lets);
  if (e->op == HX_OR) return truth(e->kid[0], X, Y, lets) || truth(e->kid[1], X, Y, lets);
  double a = sema_fexpr_eval(e->kid[0], X, Y, lets).v, b = sema_fexpr_eval(e->kid[1], X, Y, lets).v;
  switch (e->op) {
  case HX_LT: return a < b;
  case HX_LE: return a <= b;
  case HX_GT: return a > b;
  default: return a >= b;
  }
}

/* The rules are those of the generated C's dual_* helpers (gen_env.c). */
swDual sema_fexpr_eval(const swHExpr *e, swDual X, swDual Y, const swDual *lets) {
  swDual r = {0, 0, 0}, a, b;
  switch (e->op) {
  case HX_CONST: r.v = e->k.v[0]; return r;
  case HX_X:
  case HX_S:
  case HX_T: return X;
  case HX_Y: return Y;
  case HX_LET: return lets[e->let];
  case HX_ATOM: {   /* value only: a signal needs no gradient */
    swSignal s = gen_signal(e->atom);
    r.v = sw_signal_eval(&s, sema_fexpr_eval(e->kid[0], X, Y, lets).v);
    return r;
  }
  case HX_CALL:
    if (!e->callee->expr) return r;
    X.v = sema_fexpr_eval(e->kid[0], X, Y, lets).v;
    X.x = X.y = 0;
    return sema_fexpr_eval(e->callee->expr, X, Y, NULL);
  case HX_MOD: {
    a = sema_fexpr_eval(e->kid[0], X, Y, lets);
    b = sema_fexpr_eval(e->kid[1], X, Y, lets);
    r.v = a.v - b.v * floor(a.v / b.v);
    return r;
  }
  case HX_PIECEWISE:
    for (int i = 0; i + 1 < e->nkid; i += 2)
      if (truth(e->kid[i], X, Y, lets)) return sema_fexpr_eval(e->kid[i + 1], X, Y, lets);
    return sema_fexpr_eval(e->kid[e->nkid - 1], X, Y, lets);
  default: break;
  }
  a = sema_fexpr_eval(e->kid[0], X, Y, lets);
  b = e->nkid > 1 ? sema_fexpr_eval(e->kid[1], X, Y, lets) : r;
  double f;   /* derivative of the one-argument function at a.v */
  switch (e->op) {
  case HX_ADD: return (swDual){a.v + b.v, a.x + b.x, a.y + b.y};
  case HX_SUB: return (swDual){a.v - b.v, a.x - b.x, a.y - b.y};
  case HX_MUL: return (swDual){a.v * b.v, a.x * b.v + a.v * b.x, a.y * b.v + a.v * b.y};
  case HX_DIV:
    return (swDual){a.v / b.v, (a.x * b.v - a.v * b.x) / (b.v * b.v),
                    (a.y * b.v - a.v * b.y) / (b.v * b.v)};
  case HX_NEG: return (swDual){-a.v, -a.x, -a.y};
  case HX_POW:
    r.v = pow(a.v, e->p);
    f = e->p == 0 ? 0 : e->p * pow(a.v, e->p - 1);
    break;
  case HX_SQRT: r.v = sqrt(a.v); f = 0.5 / r.v; break;
  case HX_SIN: r.v = sin(a.v); f = cos(a.v); break;
  case HX_COS: r.v = cos(a.v); f = -sin(a.v); break;
  case HX_TAN: r.v = tan(a.v); f = 1 / (cos(a.v) * cos(a.v)); break;
  case HX_LOG: r.v = log(a.v); f = 1 / a.v; break;
  default: r.v = exp(a.v); f = r.v; break;   /* HX_EXP */
  }
  r.x = f * a.x;
  r.y = f * a.y;
  return r;
}

