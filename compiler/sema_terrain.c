/* sema_terrain.c — a terrain's height(x, y): its formals and lets, checked
 * into a function expression over x and y (sema_fexpr.c), and evaluated
 * with its gradient inside the compiler.
 *
 * Design.  "height(x, y) = expr;" is a function of the horizontal lab
 * coordinates, both lengths, and must give a length.  The terrain's body may
 * hold lets that use x and y; they are kept as named nodes, so the
 * generated C has one statement per let.  The runtime needs the gradient
 * too (the surface normal): gen_env.c prints the tree as forward-mode
 * dual-number C (value, d/dx, d/dy); sema_height_eval here evaluates the
 * same tree with the same rules, for the in-compiler sw_compile check and
 * for the test that compares the two (sinewc --eval-height).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sema_int.h"

/* The formals of height(x, y): two distinct names. */
static int formals(swSema *S, const swAst *f, swHeight *h) {
  if (!f || f->kind != AST_VEC || f->nkid != 2 || f->kid[0]->kind != AST_NAME ||
      f->kid[1]->kind != AST_NAME || !strcmp(f->kid[0]->name, f->kid[1]->name)) {
    diag_error(f ? f->loc : h->loc, "a height is a function of two names, the lab x and y: "
               "height(x, y) = ...;");
    return 0;
  }
  (void)S;
  h->xname = f->kid[0]->name;
  h->yname = f->kid[1]->name;
  return 1;
}

swHeight *sema_height(swSema *S, swScope *scope, const swAst *body, const swAst *field,
                      const char *what) {
  if (!field) {
    diag_error(body->loc, "%s needs its surface: height(x, y) = ...; (a length, e.g. "
               "height(x, y) = 0.1 m * sin(x / 1 m);)", what);
    return NULL;
  }
  swHeight *h = ast_alloc(S->a, sizeof *h);
  memset(h, 0, sizeof *h);
  h->loc = field->loc;
  if (field->nkid < 2) {
    diag_error(field->loc, "'height' is a function of x and y: write height(x, y) = ...;");
    return NULL;
  }
  if (!formals(S, field->kid[1], h)) return NULL;
  swFCtx C;
  memset(&C, 0, sizeof C);
  C.S = S;
  C.scope = scope;
  C.nformal = 2;
  C.formal[0] = h->xname;
  C.formal[1] = h->yname;
  C.formal_op[0] = HX_X;
  C.formal_op[1] = HX_Y;
  C.formal_dim[0] = C.formal_dim[1] = DIM_LENGTH;
  C.term = "a term of a height";
  char w[200];
  snprintf(w, sizeof w, "the height of %s", what);
  C.what = ast_strdup(S->a, w, strlen(w));
  int ok = 1;
  h->let = ast_alloc(S->a, SW_FEXPR_MAX_LETS * sizeof *h->let);
  h->let_name = ast_alloc(S->a, SW_FEXPR_MAX_LETS * sizeof *h->let_name);
  h->let_loc = ast_alloc(S->a, SW_FEXPR_MAX_LETS * sizeof *h->let_loc);
  for (int i = 0; i < body->nkid; i++) {
    const swAst *l = body->kid[i];
    if (l->kind != AST_LET) continue;
    if (C.nlocal == SW_FEXPR_MAX_LETS) {
      diag_error(l->loc, "a terrain holds at most %d lets", SW_FEXPR_MAX_LETS);
      return NULL;
    }
    if (!strcmp(l->name, h->xname) || !strcmp(l->name, h->yname)) {
      diag_error(l->loc, "'%s' names a coordinate of height(%s, %s)", l->name, h->xname, h->yname);
      ok = 0;
      continue;
    }
    swHExpr *v = sema_fexpr(&C, l->kid[0], "a let");
    if (!v) {
      ok = 0;
      continue;
    }
    if (v->op != HX_CONST) {   /* depends on x or y: one statement of the C */
      swHExpr *ref = sema_fexpr_node(S, HX_LET, v->dim, l->loc, 0);
      ref->let = h->nlet;
      h->let[h->nlet] = v;
      h->let_name[h->nlet] = l->name;
      h->let_loc[h->nlet] = l->loc;
      h->nlet++;
      v = ref;
    }
    C.local_name[C.nlocal] = l->name;
    C.local_loc[C.nlocal] = l->loc;
    C.local[C.nlocal++] = v;
  }
  swHExpr *e = sema_fexpr(&C, field->kid[0], C.what);
  if (!e || !ok) return NULL;
  for (int i = 0; i < C.nlocal; i++)
    if (!C.local_used[i])
      diag_warning(C.local_loc[i], "let '%s' of %s is never used", C.local_name[i], what);
  if (!dim_eq(e->dim, DIM_LENGTH)) {
    diag_error(field->kid[0]->loc, "%s must be a length, got %s", C.what, sema_fexpr_dim_text(S, e));
    return NULL;
  }
  h->expr = e;
  return h;
}

double sema_height_eval(double x, double y, double grad[2], const void *ctx) {
  const swHeight *h = ctx;
  swDual X = {x, 1, 0}, Y = {y, 0, 1}, lets[SW_FEXPR_MAX_LETS];
  for (int i = 0; i < h->nlet; i++) lets[i] = sema_fexpr_eval(h->let[i], X, Y, lets);
  swDual r = sema_fexpr_eval(h->expr, X, Y, lets);
  grad[0] = r.x;
  grad[1] = r.y;
  return r.v;
}
