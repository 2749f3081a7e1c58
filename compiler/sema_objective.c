/* sema_objective.c — the problem in the model: what a study maximizes or
 * minimizes, and the penalties it subtracts.
 *
 *   maximize (at(x(com), 5 s) - at(x(com), 1 s)) / 4 s;
 *   penalty 10 m/s * max(at(stretch(m1), 5 s) - 1.3, 0);
 *
 * Design.  The statements are parsed as any "WORD expr;" statement
 * (lang/sinew.y); sema_items hands them here and they are checked after the
 * last item, beside the expectations, because the quantities they read may
 * name probes an output block declares later.  Each is an expression like
 * any other (params, lets, units, max, min, abs) in which, and only in
 * which, the reductions of the run may stand: at(Q, T), mean_over(Q, T0,
 * T1), max_over and min_over, with Q a quantity as `expect` reads it
 * (sema_quantity) and times that are constants of the run (T >= 0, T0 <
 * T1).  A reduction becomes an entry of the scene's expectations with
 * `reduce` set, so the runtime samples it as it samples an expectation
 * (runtime/engine/expect.c), and, in the expression, a value known only at the end
 * of the run: NaN for the checker, R[k] in its C text; equal reductions
 * share an entry.  A let is evaluated where it is defined, so a reduction
 * in a let is refused even when the objective reads the let (sema_def.c).
 * The objective is one statement at the top level of the model (each
 * instance of a component would add one); a penalty may also stand in a
 * component, one per instance, reading that instance's joints and muscles.
 * Every penalty has the objective's dimension, being subtracted from it.
 * Reports show the objective in a unit the model writes for that dimension
 * (after a number, or as a param's unit; the objective first, then the
 * penalties), else in SI.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sema_int.h"

int sema_is_objective_word(const char *word) {
  return !strcmp(word, "maximize") || !strcmp(word, "minimize") || !strcmp(word, "penalty");
}

void sema_objective_later(swSema *S, swScope *scope, const swAst *it) {
  if (it->nkid != 1) {
    diag_error(it->kid[1]->loc, "'%s' takes no '= value': %s EXPR;", it->text, it->text);
    return;
  }
  if (strcmp(it->text, "penalty") && !scope->file_level) {
    diag_error(it->loc, "'%s' belongs at the top level of the model, not in a component "
               "(each instance would add an objective); a penalty may stand in one", it->text);
    return;
  }
  sema_later(&S->objectives, scope, it);
}

/* ---- reductions ---- */

static const char *const reductions[] = {"at", "mean_over", "max_over", "min_over"};

/* The index k of reduction x among the scene's (R[k]): an equal one's, or a
 * new entry's. */
static int reduction_index(swSema *S, const swSceneExpect *x) {
  swScene *scn = S->scene;
  int k = 0;
  for (int i = 0; i < scn->nexpect; i++) {
    const swSceneExpect *y = &scn->expect[i];
    if (!y->reduce) continue;
    if (y->reduce == x->reduce && y->quantity == x->quantity && y->index == x->index &&
        y->component == x->component && y->t0 == x->t0 && y->t1 == x->t1)
      return k;
    k++;
  }
  sema_add_expect(S, x);
  return k;
}

swValue sema_reduction(swSema *S, swScope *scope, const swAst *call) {
  const char *fn = call->name;
  int kind = SW_REDUCE_AT;
  while (strcmp(fn, reductions[kind - SW_REDUCE_AT])) kind++;
  if (!S->reducing) {
    diag_error(call->loc, "%s() reads the run, so it belongs in maximize, minimize or penalty, "
               "written there (not through a let)", fn);
    return val_error();
  }
  const swAst *args = ast_kid(call, 0), *a[3] = {NULL, NULL, NULL};
  const int nargs = kind == SW_REDUCE_AT ? 2 : 3;
  int ok = args && args->nkid == nargs;
  for (int i = 0; ok && i < nargs; i++) {
    ok = args->kid[i]->kind == AST_ARG && !args->kid[i]->name;
    a[i] = ok ? ast_kid(args->kid[i], 0) : NULL;
  }
  if (!ok) {
    if (kind == SW_REDUCE_AT)
      diag_error(call->loc, "at() takes a quantity and a time: at(angle(elbow), 0.5 s)");
    else
      diag_error(call->loc, "%s() takes a quantity and a window: %s(x(com), 1 s, 5 s)", fn, fn);
    return val_error();
  }
  swSceneExpect x;
  memset(&x, 0, sizeof x);
  x.loc = call->loc;
  x.reduce = kind;
  x.window = kind != SW_REDUCE_AT;
  x.scale = 1;   /* unused: a reduction is not reported */
  x.unit = "";
  swDim dim = DIM_NONE;
  char who[32];
  snprintf(who, sizeof who, "%s()", fn);
  ok = sema_quantity(S, scope, a[0], ast_strdup(S->a, who, strlen(who)), &x, &dim);
  double t[2] = {0, 0};
  for (int i = 1; i < nargs; i++) {
    char what[64];
    snprintf(what, sizeof what, "the %s of %s()", kind == SW_REDUCE_AT ? "time" :
             i == 1 ? "window's start" : "window's end", fn);
    const char *w = ast_strdup(S->a, what, strlen(what));
    swValue v = sema_expect(S, scope, a[i], 1, DIM_TIME, w);
    if (v.kind == VAL_ERROR || !sema_require_const(S, &v, w)) {
      ok = 0;
    } else if (!(v.v[0] >= 0)) {
      diag_error(a[i]->loc, "%s is a time of the run, which starts at 0 s; it must not be "
                 "negative", w);
      ok = 0;
    } else {
      t[i - 1] = v.v[0];
    }
  }
  if (ok && x.window && !(t[0] < t[1])) {
    diag_error(call->loc, "the window of %s() must end after it starts (T0 < T1)", fn);
    ok = 0;
  }
  if (!ok) return val_error();
  x.t0 = t[0];
  x.t1 = x.window ? t[1] : t[0];
  const swScene *scn = S->scene;
  if (scn->has_duration && x.t1 > scn->duration)
    diag_warning(call->loc, "%s() reads the run at %g s, after its end (simulate's duration is "
                 "%g s)", fn, x.t1, scn->duration);
  x.text = sema_source_text(S, call->loc);
  char c[32];
  snprintf(c, sizeof c, "R[%d]", reduction_index(S, &x));
  swValue v = val_num(S->a, NAN, dim, call->loc);
  v.c = ast_alloc(S->a, sizeof *v.c);
  v.c[0] = ast_strdup(S->a, c, strlen(c));
  return v;
}

/* ---- the objective's unit ---- */

/* Whether e is a unit factor: m, s^2. */
static int unit_factor(const swAst *e) {
  return e->kind == AST_UNIT || (e->kind == AST_BINOP && e->op == '^' &&
                                 e->kid[0]->kind == AST_UNIT);
}

/* A number followed by units, "10 m/s": the first unit factor's location,
 * or NULL when e is not one. */
static const swAst *number_units(const swAst *e) {
  const swAst *first = NULL;
  while ((e->kind == AST_APPLY || (e->kind == AST_BINOP && (e->op == '*' || e->op == '/'))) &&
         unit_factor(e->kid[1])) {
    first = e->kid[1];
    e = e->kid[0];
  }
  return e->kind == AST_NUM ? first : NULL;
}

/* A unit written in e (a number's, or a param's) whose dimension is `want`:
 * its text and scale into *unit, *scale; 0 if none. */
static int unit_written(swSema *S, swScope *scope, const swAst *e, swDim want,
                        const char **unit, double *scale) {
  if (!e) return 0;
  const char *text = NULL;
  const swAst *first = number_units(e);
  if (first && first->loc.line == e->loc.end_line) {
    const swSource *f = diag_file(e->loc.file);
    const char *from = diag_at(f, first->loc.line, first->loc.col);
    const char *to = diag_at(f, e->loc.end_line, e->loc.end_col + 1);
    text = ast_strdup(S->a, from, (size_t)(to - from));
  } else if (e->kind == AST_NAME) {
    const swSymbol *sym = sema_lookup(S, scope, e->name);
    if (sym && sym->kind == SYM_PARAM && sym->index >= 0)
      text = S->scene->param[sym->index].unit;
  }
  if (text && text[0]) {
    char q[256], err[128];
    double si;
    signed char dim[SW_NDIM];
    snprintf(q, sizeof q, "1 %s", text);
    if (!sw_parse_quantity(q, &si, dim, err, sizeof err) && !memcmp(dim, want.e, SW_NDIM) &&
        si > 0) {
      *unit = text;
      *scale = si;
      return 1;
    }
  }
  if (first) return 0;   /* a number's units: nothing more inside */
  for (int i = 0; i < e->nkid; i++)
    if (unit_written(S, scope, e->kid[i], want, unit, scale)) return 1;
  return 0;
}

/* The SI unit of a dimension: "m/s" (from "velocity (m/s)"), "kg m^-1 s^-3",
 * or "" for none. */
static const char *si_unit(swSema *S, swDim d) {
  if (dim_is_none(d)) return "";
  char buf[96];
  const char *text = sw_dim_describe(buf, sizeof buf, d.e), *open = strchr(text, '(');
  if (open) return ast_strdup(S->a, open + 1, strcspn(open + 1, ")"));
  return ast_strdup(S->a, text, strlen(text));
}

/* ---- the statements ---- */

/* An objective's or a penalty's expression, reductions allowed: a number. */
static swValue evaluate(swSema *S, swScope *scope, const swAst *e, const char *what) {
  S->reducing = 1;
  swValue v = sema_eval(S, scope, e);
  S->reducing = 0;
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, scope, v.word, v.loc, "name");
    return val_error();
  }
  return sema_expect_value(S, v, 1, v.dim, what);
}

void sema_objectives(swSema *S) {
  swSceneObjective *o = &S->scene->objective;
  memset(o, 0, sizeof *o);
  o->value = val_error();
  const swAst *objective = NULL;
  swScope *objective_scope = NULL;
  for (int i = 0; i < S->objectives.n; i++) {
    const swAst *it = S->objectives.item[i];
    if (!strcmp(it->text, "penalty")) continue;
    if (objective) {
      char first[300];
      diag_error(it->loc, "a second objective: a model has one, and its first is at %s (make "
                 "one expression of both, or one a penalty)",
                 diag_where_from(objective->loc, it->loc, first, sizeof first));
      continue;
    }
    objective = it;
    objective_scope = S->objectives.scope[i];
  }
  if (objective) {
    o->sense = objective->text[1] == 'a' ? 1 : -1;
    o->loc = ast_span(objective->loc, objective->kid[0]->loc);
    o->text = sema_source_text(S, o->loc);
    o->value = evaluate(S, objective_scope, objective->kid[0], "an objective");
  }
  int npenalty = 0;
  for (int i = 0; i < S->objectives.n; i++) npenalty += !strcmp(S->objectives.item[i]->text,
                                                                   "penalty");
  o->penalty = ast_alloc(S->a, (size_t)(npenalty + 1) * sizeof *o->penalty);
  o->penalty_loc = ast_alloc(S->a, (size_t)(npenalty + 1) * sizeof *o->penalty_loc);
  for (int i = 0; i < S->objectives.n; i++) {
    const swAst *it = S->objectives.item[i];
    if (strcmp(it->text, "penalty")) continue;
    if (!objective)
      diag_error(it->loc, "a penalty is subtracted from the objective, and the model has none "
                 "(maximize EXPR; or minimize EXPR;)");
    swValue v = evaluate(S, S->objectives.scope[i], it->kid[0], "a penalty");
    if (v.kind == VAL_ERROR || o->value.kind == VAL_ERROR) continue;
    if (!dim_fits(o->value.dim, v.dim)) {
      char where[300];
      diag_error(it->kid[0]->loc, "a penalty is subtracted from the objective, so it has the "
                 "objective's dimension, %s (the objective at %s); this one is %s",
                 dim_describe(S->a, o->value.dim),
                 diag_where_from(objective->loc, it->loc, where, sizeof where),
                 dim_is_none(v.dim) ? "dimensionless" : dim_describe(S->a, v.dim));
      continue;
    }
    o->penalty_loc[o->npenalty] = ast_span(it->loc, it->kid[0]->loc);
    o->penalty[o->npenalty++] = v;
  }
  for (int i = 0; i < S->scene->nexpect; i++) o->nreduce += S->scene->expect[i].reduce != 0;
  if (o->value.kind == VAL_ERROR) return;
  o->si_unit = si_unit(S, o->value.dim);
  o->unit = o->si_unit;
  o->scale = 1;
  if (!unit_written(S, objective_scope, objective->kid[0], o->value.dim, &o->unit, &o->scale))
    for (int i = 0; i < S->objectives.n; i++) {
      const swAst *it = S->objectives.item[i];
      if (!strcmp(it->text, "penalty") &&
          unit_written(S, S->objectives.scope[i], it->kid[0], o->value.dim, &o->unit, &o->scale))
        break;
    }
}
