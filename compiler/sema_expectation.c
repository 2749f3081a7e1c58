/* sema_expectation.c — expect statements: a model's own golden test.
 *
 *   expect angle(elbow) at 0.5 s in (-155 deg, -150 deg);
 *   expect force(biceps) over (0.2 s, 0.5 s) in (0 N, 300 N);
 *   expect z(head) at 2 s within 1 mm of 25 mm;
 *
 * Design.  The parser keeps the statement's words as they were written
 * (lang/sinew.y); this file checks them, resolves the quantity and turns
 * the statement into a swSceneExpect of constants, which gen_c.c prints into
 * build() and the simulator checks as it runs (runtime/engine/expect.c).  A
 * quantity is one of angle(JOINT) (a hinge's angle), force(JOINT) (the size
 * of a joint's force), force(MUSCLE) (its tension), stretch(MUSCLE), and
 * x, y, z or size of a probe declared in `output` (a position or a velocity;
 * a mean velocity is sampled at frames only, so it is refused).  Probes are
 * declared in the output block, which may come after the statement, so the
 * statements are kept when met (with their scope: inside a component,
 * `angle(elbow)` is the instance's joint) and checked after the last item.
 * The bounds are fixed when compiling: a golden test states numbers, and a
 * run with other params (--set) is held to the same ones.  The report shows
 * values in the unit the bounds were written in.  The reductions of an
 * objective (sema_objective.c) read their quantities through the same
 * sema_quantity. */
#include <stdlib.h>
#include <string.h>

#include "sema_int.h"

static const swDim DIM_FORCE_ = {{1, 1, -2, 0}};
static const swDim DIM_SPEED_ = {{0, 1, -1, 0}};

void sema_expectation_later(swSema *S, swScope *scope, const swAst *it) {
  sema_later(&S->expects, scope, it);
}

void sema_later(swLater *l, swScope *scope, const swAst *it) {
  if (l->n == l->cap) {
    l->cap = l->cap ? 2 * l->cap : 8;
    l->item = realloc(l->item, (size_t)l->cap * sizeof *l->item);
    l->scope = realloc(l->scope, (size_t)l->cap * sizeof *l->scope);
    if (!l->item || !l->scope) abort();
  }
  l->item[l->n] = it;
  l->scope[l->n++] = scope;
}

/* The text of loc on one line, blanks folded: a statement for the report,
 * an objective or a reduction. */
const char *sema_source_text(swSema *S, swLoc loc) {
  const swSource *src = diag_file(loc.file);
  const char *p = diag_at(src, loc.line, loc.col), *end = diag_at(src, loc.end_line, loc.end_col + 1);
  char *out = ast_alloc(S->a, (size_t)(end - p) + 2);
  size_t k = 0;
  int blank = 0;
  for (const char *q = p; q < end; q++) {
    if (*q == ' ' || *q == '\t' || *q == '\n' || *q == '\r') {
      blank = k > 0;
      continue;
    }
    if (blank) out[k++] = ' ';
    blank = 0;
    out[k++] = *q;
  }
  out[k] = 0;
  return out;
}

/* The statement's text for the report: "expect ...;". */
static const char *statement_text(swSema *S, swLoc loc) {
  const char *text = sema_source_text(S, loc);
  size_t n = strlen(text);
  char *out = ast_alloc(S->a, n + 2);
  memcpy(out, text, n);
  out[n] = ';';
  return out;
}

/* The unit a bound was written in (its first component's, through a minus
 * sign), for the report; NULL when it has none of its own. */
static const swUnit *written_unit(const swAst *e) {
  if (e && e->kind == AST_VEC && e->nkid) e = e->kid[0];
  while (e && e->kind == AST_NEG) e = ast_kid(e, 0);
  if (!e || e->kind != AST_APPLY) return NULL;
  const swAst *u = ast_kid(e, 1);
  if (!u || u->kind != AST_UNIT) return NULL;
  return sw_unit_find(u->name, strlen(u->name));
}

/* Which quantity `q` reads, into x (quantity, index, component) and its
 * dimension; 0 after reporting why not.  `who` reads it ("an expectation"). */
int sema_quantity(swSema *S, swScope *scope, const swAst *q, const char *who, swSceneExpect *x,
                  swDim *dim) {
  static const char *const funcs[] = {"angle", "force", "stretch", "x", "y", "z", "size"};
  const int nfuncs = (int)(sizeof funcs / sizeof funcs[0]);
  if (q->kind != AST_CALL) {
    diag_error(q->loc, "%s reads a quantity: angle(JOINT), force(JOINT or MUSCLE), "
               "stretch(MUSCLE), or x, y, z or size of a probe", who);
    return 0;
  }
  int k;
  for (k = 0; k < nfuncs; k++)
    if (!strcmp(q->name, funcs[k])) break;
  if (k == nfuncs) {
    const char *near = diag_suggest(q->name, funcs, nfuncs);
    if (near) diag_error(q->loc, "unknown quantity '%s'; did you mean '%s'?", q->name, near);
    else diag_error(q->loc, "unknown quantity '%s' (expected angle, force, stretch, x, y, z or "
                    "size)", q->name);
    return 0;
  }
  const swAst *args = ast_kid(q, 0);
  const swAst *arg = args && args->nkid == 1 && !args->kid[0]->name ? ast_kid(args->kid[0], 0)
                                                                      : NULL;
  if (!arg) {
    diag_error(q->loc, "%s() takes one name: %s(%s)", q->name, q->name,
               k == 0 ? "elbow" : k <= 2 ? "biceps" : "com");
    return 0;
  }
  swScene *scn = S->scene;
  if (k >= 3) { /* a probe's component */
    int p;
    for (p = 0; p < scn->nprobe; p++)
      if (arg->kind == AST_NAME && !strcmp(scn->probe[p].name, arg->name)) break;
    for (int i = 0; p == scn->nprobe && arg->kind == AST_NAME && i < S->nbad_probe; i++)
      if (!strcmp(S->bad_probe[i], arg->name)) return 0; /* its declaration was reported */
    if (p == scn->nprobe) {
      const char *cands[64];
      int n = 0;
      for (int i = 0; i < scn->nprobe && n < 64; i++) cands[n++] = scn->probe[i].name;
      const char *near = arg->kind == AST_NAME ? diag_suggest(arg->name, cands, n) : NULL;
      char list[256];
      diag_join(list, sizeof list, cands, n);
      if (near) diag_error(arg->loc, "%s() reads a probe of 'output'; did you mean '%s'?",
                           q->name, near);
      else if (n) diag_error(arg->loc, "%s() reads a probe declared in 'output' (the probes: %s)",
                             q->name, list);
      else diag_error(arg->loc, "%s() reads a probe declared in 'output' (probe NAME = ...;), "
                      "and the model declares none", q->name);
      return 0;
    }
    if (scn->probe[p].kind == SW_PROBE_MEAN_VELOCITY) {
      diag_error(arg->loc, "probe '%s' is a mean velocity, which is sampled at frames only; "
                 "expect a position or velocity(RODS) instead", scn->probe[p].name);
      return 0;
    }
    x->quantity = SW_EXPECT_PROBE;
    x->index = p;
    x->component = k - 3;
    *dim = scn->probe[p].kind == SW_PROBE_COM_VELOCITY ? DIM_SPEED_ : DIM_LENGTH;
    return 1;
  }
  swValue v = sema_eval(S, scope, arg);
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, scope, v.word, v.loc, k == 0 ? "joint" : k == 2 ? "muscle" : "name");
    return 0;
  }
  if (v.kind == VAL_ERROR) return 0;
  const swSymbol *sym = v.kind == VAL_REF ? v.ref : NULL;
  if (sym && sym->kind == SYM_JOINT && k <= 1) {
    int j;
    for (j = 0; j < scn->njoint; j++)
      if (!strcmp(scn->joint[j].name, sym->full)) break;
    if (j == scn->njoint) return 0; /* the joint had errors */
    if (k == 0 && scn->joint[j].kind != SW_JOINT_HINGE) {
      diag_error(arg->loc, "joint '%s' is not a hinge: only a hinge has an angle", sym->full);
      return 0;
    }
    x->quantity = k == 0 ? SW_EXPECT_JOINT_ANGLE : SW_EXPECT_JOINT_FORCE;
    x->index = j;
    *dim = k == 0 ? DIM_ANGLE : DIM_FORCE_;
    return 1;
  }
  if (sym && sym->kind == SYM_MUSCLE && k >= 1) {
    if (sym->index < 0) return 0; /* the muscle had errors */
    x->quantity = k == 1 ? SW_EXPECT_MUSCLE_FORCE : SW_EXPECT_MUSCLE_STRETCH;
    x->index = sym->index;
    *dim = k == 1 ? DIM_FORCE_ : DIM_NONE;
    return 1;
  }
  const char *reads = k == 0 ? "a hinge joint" : k == 1 ? "a joint or a muscle" : "a muscle";
  if (sym) diag_error(arg->loc, "%s() reads %s; '%s' is %s", q->name, reads, sym->name,
                      sema_sym_a_noun(sym->kind));
  else diag_error(arg->loc, "%s() reads %s, given by its name", q->name, reads);
  return 0;
}

/* A constant of the dimension `want` (n components) named `what`. */
static int constant(swSema *S, swScope *scope, const swAst *e, int n, swDim want,
                    const char *what, double *out) {
  swValue v = sema_expect(S, scope, e, n, want, what);
  if (v.kind == VAL_ERROR || !sema_require_const(S, &v, what)) return 0;
  for (int k = 0; k < n; k++) out[k] = v.v[k];
  return 1;
}

/* Two constants (a window, a pair of bounds), the first not above the
 * second: `backwards` names that mistake. */
static int ordered_pair(swSema *S, swScope *scope, const swAst *e, swDim want, const char *what,
                        const char *backwards, double out[2]) {
  if (!constant(S, scope, e, 2, want, what, out)) return 0;
  if (out[0] <= out[1]) return 1;
  diag_error(e->loc, "%s", backwards);
  return 0;
}

static void check_one(swSema *S, swScope *scope, const swAst *it) {
  swSceneExpect x;
  memset(&x, 0, sizeof x);
  x.loc = it->loc;
  const swAst *q = ast_kid(it, 0), *when = ast_kid(it, 1), *test = ast_kid(it, 2),
              *of = ast_kid(it, 3);
  swDim dim = DIM_NONE;
  int ok = sema_quantity(S, scope, q, "an expectation", &x, &dim);
  /* at T | over (T0, T1) */
  if (!strcmp(when->name, "at")) {
    ok &= constant(S, scope, ast_kid(when, 0), 1, DIM_TIME, "'at T'", &x.t0);
    x.t1 = x.t0;
  } else if (!strcmp(when->name, "over")) {
    double w[2] = {0, 0};
    ok &= ordered_pair(S, scope, ast_kid(when, 0), DIM_TIME, "'over (T0, T1)'",
                       "the window ends before it starts", w);
    x.window = 1;
    x.t0 = w[0];
    x.t1 = w[1];
  } else {
    diag_error(when->loc, "an expectation says when: 'at T' or 'over (T0, T1)', not '%s'",
               when->name);
    ok = 0;
  }
  if (ok && !(x.t0 >= 0)) {
    diag_error(ast_kid(when, 0)->loc, "an expectation's time must not be negative");
    ok = 0;
  }
  /* in (LO, HI) | within TOL of VALUE */
  const swUnit *unit = NULL;
  if (!strcmp(test->name, "in") && !of) {
    double b[2] = {0, 0};
    ok &= ok && ordered_pair(S, scope, ast_kid(test, 0), dim, "'in (LO, HI)'",
                             "the lower bound is above the upper one", b);
    x.lo = b[0];
    x.hi = b[1];
    unit = written_unit(ast_kid(test, 0));
  } else if (!strcmp(test->name, "within") && of && !strcmp(of->name, "of")) {
    double tol = 0, value = 0;
    ok &= ok && constant(S, scope, ast_kid(test, 0), 1, dim, "'within TOL'", &tol);
    ok &= ok && constant(S, scope, ast_kid(of, 0), 1, dim, "'of VALUE'", &value);
    if (ok && !(tol >= 0)) {
      diag_error(ast_kid(test, 0)->loc, "the tolerance must not be negative");
      ok = 0;
    }
    x.lo = value - tol;
    x.hi = value + tol;
    unit = written_unit(ast_kid(of, 0));
  } else {
    const swAst *bad = of && strcmp(of->name, "of") ? of : test;
    diag_error(bad->loc, "an expectation bounds its value: 'in (LO, HI)' or 'within TOL of "
               "VALUE', not '%s'", bad->name);
    ok = 0;
  }
  if (!ok) return;
  x.scale = unit ? unit->scale : 1.0;
  x.unit = unit ? unit->name
           : x.quantity == SW_EXPECT_JOINT_ANGLE ? "rad"
           : x.quantity == SW_EXPECT_MUSCLE_STRETCH ? ""
           : x.quantity == SW_EXPECT_PROBE ? (dim.e[2] ? "m/s" : "m") : "N";
  x.text = statement_text(S, it->loc);
  sema_add_expect(S, &x);
}

void sema_add_expect(swSema *S, const swSceneExpect *x) {
  swScene *scn = S->scene;
  if (scn->nexpect == scn->capexpect) {
    scn->capexpect = scn->capexpect ? 2 * scn->capexpect : 8;
    scn->expect = realloc(scn->expect, (size_t)scn->capexpect * sizeof *scn->expect);
    if (!scn->expect) abort();
  }
  scn->expect[scn->nexpect++] = *x;
}

void sema_expectations(swSema *S) {
  for (int i = 0; i < S->expects.n; i++) check_one(S, S->expects.scope[i], S->expects.item[i]);
}
