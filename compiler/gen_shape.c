/* gen_shape.c — the generated C of rods' shapes: one function of the arc
 * length per curve, and the lines of a shaped rod's block in build().
 *
 * Design.  A curve "start_shape(s) = (x, y, z);" becomes its three
 * components over doubles (printed as a signal's body is, gen_fexpr_value),
 * `static void shape_K_at(double s, double f[3])`, and a swCurveFn,
 * `static void shape_K(double s, double r[3], const void *ctx)`, that
 * places it at the rod's start passed in ctx: start + f(s) - f(0).  The rod's block then
 * fills static arrays with the runtime's shape functions (engine/shape.c:
 * sw_shape_curve, sw_shape_helix, and sw_shape_straight for a straight start
 * away from a curved rest) and hands them to sw_spec_set_rest_shape and
 * sw_spec_set_start_shape.  Every number is a constant (sema_shape.c
 * refuses params), and they are the very calls the checker made to place
 * the rod's points, so the simulator starts where the checker said.
 */
#include <stdio.h>
#include <string.h>

#include "gen.h"

static void curve_function(FILE *out, swArena *a, const swSceneRod *r, const swSceneShape *c) {
  fputs("/* rod ", out);
  gen_c_comment(out, r->name, strlen(r->name));
  fprintf(out, ": %s(", c->field);
  gen_c_comment(out, c->sname, strlen(c->sname));
  fputs("), its centreline (m) at arc length s (m) */\n", out);
  fprintf(out, "static void shape_%d_at(double s, double f[3]) {\n", c->index);
  gen_origin(out, c->loc, "  ");
  for (int k = 0; k < 3; k++) {
    fprintf(out, "  f[%d] = ", k);
    gen_fexpr_value(out, a, c->r[k]);
    fputs(";\n", out);
  }
  fputs("}\n", out);
  fprintf(out, "/* ... moved to begin at the rod's start (ctx) */\n"
          "static void shape_%d(double s, double r[3], const void *ctx) {\n"
          "  const double *start = ctx;\n  double f[3], f0[3];\n"
          "  shape_%d_at(s, f);\n  shape_%d_at(0.0, f0);\n"
          "  for (int k = 0; k < 3; k++) r[k] = start[k] + (f[k] - f0[k]);\n}\n\n",
          c->index, c->index, c->index);
}

void gen_shape_functions(FILE *out, swArena *a, const swScene *sc) {
  if (!sc->ncurve) return;
  fputs("/* The rods' shapes given as curves of the arc length, in SI units. */\n", out);
  for (int i = 0; i < sc->nrod; i++) {
    const swSceneRod *r = &sc->rod[i];
    if (r->rest_shape && r->rest_shape->kind == SHAPE_CURVE)
      curve_function(out, a, r, r->rest_shape);
    if (r->start_shape && r->start_shape != r->rest_shape && r->start_shape->kind == SHAPE_CURVE)
      curve_function(out, a, r, r->start_shape);
  }
}

static const char *num(swArena *a, double v) {
  swValue x = val_num(a, v, DIM_NONE, (swLoc){0});
  return val_c(a, &x, 0);
}

/* The call that fills x, Q with shape sh of rod r. */
static void shape_call(FILE *out, swArena *a, const swSceneRod *r, const swSceneShape *sh,
                       const char *x, const char *Q) {
  gen_origin(out, sh->loc, "    ");
  if (sh->kind == SHAPE_HELIX) {
    fprintf(out, "    ok &= sw_shape_helix(%d, %s, %s, rod.length, %d, rod.start, rod.direction, "
            "rod.normal, %s, %s, err, errlen) == SW_OK;   /* radius, pitch (m), %s-handed */\n",
            r->nelem, num(a, sh->radius), num(a, sh->pitch), sh->hand, x, Q,
            sh->hand > 0 ? "right" : "left");
  } else {
    fprintf(out, "    ok &= sw_shape_curve(%d, rod.length, shape_%d, rod.start, rod.normal, %s, "
            "%s, err, errlen) == SW_OK;\n", r->nelem, sh->index, x, Q);
  }
}

void gen_shape_build(FILE *out, swArena *a, const swSceneRod *r) {
  const swSceneShape *rest = r->rest_shape, *start = r->start_shape;
  if (!rest && !start) return;
  const int n = r->nelem;
  fprintf(out, "    static double x[3 * %d], Q[9 * %d];   /* nodes, frames (rows d1 d2 d3) */\n",
          n + 1, n);
  if (rest) {
    shape_call(out, a, r, rest, "x", "Q");
    fprintf(out, "    ok &= sw_spec_set_rest_shape(s, %d, x, Q) == SW_OK;%s\n", r->id,
            rest == start ? "   /* and it starts in it */" : "");
  }
  if (rest == start) return;
  if (start) {
    shape_call(out, a, r, start, "x", "Q");
  } else {
    fputs("    /* it starts straight along its direction, unstretched */\n"
          "    static double xs[sizeof x / sizeof x[0]];\n", out);
    fprintf(out, "    ok &= sw_shape_straight(%d, x, rod.start, rod.direction, rod.normal, xs, Q, "
            "err, errlen) == SW_OK;\n", n);
  }
  fprintf(out, "    ok &= sw_spec_set_start_shape(s, %d, %s, Q) == SW_OK;\n", r->id,
          start ? "x" : "xs");
}
