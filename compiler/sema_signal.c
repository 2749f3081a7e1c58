/* sema_signal.c — signal NAME(t) = expr;  the model's own time signals.
 *
 * Design.  A signal declaration is a definition: a name, a time formal and a
 * body, any function of the time built from arithmetic, sqrt, sin, cos, tan,
 * exp, piecewise(cond: value, ..., default), mod(a, b), the built-in signals
 * (ramp, sine, step, table, bspline) and the model's other signals called at
 * a time, NAME(t - 0.125 s).  So a drive of the form of Zhang et al. 2019,
 * Suppl. eqs. 6-10 (an initiation phase, then a cycle of sines and linear
 * pieces) is written as it is printed, and sums and products of signals are
 * ordinary arithmetic.  The parser reads the declaration as an action
 * ("signal" EXPR = EXPR); this file checks its shape, declares the name
 * (sema.c), checks the body into a function expression (sema_fexpr.c) the
 * first time the signal is used or reached, and keeps it in swScene.signal,
 * from which gen_env.c prints one C function per signal.  Where a value
 * goes, the signal's name stands for the signal at the current time, with
 * the dimension of its body, so `force arm.end = (0, 0, 1) * lift;` scales a
 * direction by it as by a ramp().  A signal that calls itself, directly or
 * through others, is an error naming the chain.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sema_int.h"

int sema_is_signal_def(const swAst *it) {
  return it->kind == AST_ACTION && it->text && !strcmp(it->text, "signal");
}

/* The NAME of "signal NAME(t) = ...", NULL if the head is not NAME(FORMAL). */
const char *sema_signal_def_name(const swAst *it) {
  const swAst *head = ast_kid(it, 0);
  if (!head || head->kind != AST_CALL) return NULL;
  return head->name;
}

/* The formal of the head, NULL (reported) if it is not one plain name. */
static const char *formal(const swAst *it) {
  const swAst *head = ast_kid(it, 0), *args = ast_kid(head, 0);
  if (!args || args->nkid != 1 || args->kid[0]->kind != AST_ARG || args->kid[0]->name ||
      ast_kid(args->kid[0], 0)->kind != AST_NAME) {
    diag_error(head->loc, "a signal is a function of one name, the time: signal %s(t) = ...;",
               head->name);
    return NULL;
  }
  return ast_kid(args->kid[0], 0)->name;
}

static void add_signal(swSema *S, swSceneSignal *g) {
  swScene *sc = S->scene;
  if (sc->nsignal == sc->capsignal) {
    sc->capsignal = sc->capsignal ? 2 * sc->capsignal : 8;
    swSceneSignal **grown = ast_alloc(S->a, (size_t)sc->capsignal * sizeof *grown);
    if (sc->nsignal) memcpy(grown, sc->signal, (size_t)sc->nsignal * sizeof *grown);
    sc->signal = grown;
  }
  g->index = sc->nsignal;
  sc->signal[sc->nsignal++] = g;
}

swSceneSignal *sema_signal_of(swSema *S, swSymbol *sym, swLoc use) {
  sym->used = 1;
  if (sym->state == 2) return sym->index >= 0 ? S->scene->signal[sym->index] : NULL;
  if (sym->state == 1) {
    char where[256];
    diag_error(use, "signal '%s' is defined in terms of itself (its definition is at %s)",
               sym->name, diag_where(sym->loc, where, sizeof where));
    return NULL;
  }
  sym->state = 1;
  sym->index = -1;
  const swAst *it = sym->def;
  const char *t = formal(it);
  swSceneSignal *g = NULL;
  if (t) {
    swFCtx C;
    memset(&C, 0, sizeof C);
    C.S = S;
    C.scope = sym->scope;
    C.nformal = 1;
    C.formal[0] = t;
    C.formal_op[0] = HX_T;
    C.formal_dim[0] = DIM_TIME;
    C.time = 1;
    C.term = "a term of a signal";
    char w[300];
    snprintf(w, sizeof w, "signal '%s'", sym->full ? sym->full : sym->name);
    C.what = ast_strdup(S->a, w, strlen(w));
    swHExpr *e = sema_fexpr(&C, ast_kid(it, 1), C.what);
    if (e) {
      g = ast_alloc(S->a, sizeof *g);
      memset(g, 0, sizeof *g);
      g->name = sym->full ? sym->full : sym->name;
      g->formal = t;
      g->loc = it->loc;
      g->expr = e;
      g->dim = e->dim;
      add_signal(S, g);
      sym->index = g->index;
    }
  }
  sym->state = 2;
  return g;
}

void sema_signal_def(swSema *S, swScope *scope, const swAst *it) {
  const char *name = sema_signal_def_name(it);
  if (!name) return;   /* reported when declared */
  swSymbol *sym = sema_lookup_local(scope, name);
  if (!sym || sym->def != it) return;   /* a duplicate, reported when declared */
  int used = sym->used;
  sema_signal_of(S, sym, it->loc);
  sym->used = used;
}

swValue sema_signal_value(swSema *S, swSymbol *sym, swLoc loc) {
  swSceneSignal *g = sema_signal_of(S, sym, loc);
  if (!g) return val_error();
  swSignalVal *sig = ast_alloc(S->a, sizeof *sig);
  memset(sig, 0, sizeof *sig);
  sig->kind = SW_SIG_FUNC;
  sig->func = g;
  sig->b = sig->t0 = sig->T = sig->freq = sig->phase = sig->period = val_error();
  sig->a = val_num(S->a, 1, DIM_NONE, loc);   /* the factor an activation folds a scale into */
  sig->times = sig->values = val_error();
  return sema_make_signal(S, sig, g->dim, loc);
}

double sema_signal_eval(double t, const void *ctx) {
  const swSceneSignal *g = ctx;
  if (!g->expr) return 0.0;
  swDual T = {t, 0, 0}, none = {0, 0, 0};
  return sema_fexpr_eval(g->expr, T, none, NULL).v;
}
