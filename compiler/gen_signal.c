/* gen_signal.c — the generated C of the model's signals: one function of
 * time per `signal NAME(t) = ...;`, and the build() lines they need.
 *
 * Design.  A signal is a swSignalFn, `static double signal_K(double t,
 * const void *ctx)`, whose body is its tree (sema_fexpr.c) printed as one C
 * expression over doubles: piecewise() a chain of conditional expressions
 * (only the chosen value is evaluated), mod(a, b) a - b floor(a / b), a
 * call of another signal signal_J(time, ctx), and a built-in signal (ramp,
 * sine, ...) inside it the runtime's own, sw_signal_eval(&signal_atom[k],
 * time), so a ramp means the same in a signal as in a force.  The
 * functions are declared first, so a signal may call one defined below it.
 * Params reach them as the heights' do: build() copies P (and the derived
 * D) into static arrays that live as long as the model, and the atoms,
 * whose arguments may be params, are filled there too.  The compiler
 * evaluates the same trees with the same rules (sema_signal_eval);
 * tests/lang/test_signal.sh holds the two together.
 */
#include <stdio.h>
#include <string.h>

#include "diag.h"
#include "gen.h"

static void value(FILE *out, swArena *a, const swHExpr *e, int depth);

void gen_fexpr_value(FILE *out, swArena *a, const swHExpr *e) { value(out, a, e, 1); }

static void value(FILE *out, swArena *a, const swHExpr *e, int depth) {
  static const char *const infix[] = {[HX_ADD] = " + ", [HX_SUB] = " - ", [HX_MUL] = " * ",
                                      [HX_DIV] = " / "};
  static const char *const fn[] = {[HX_SQRT] = "sqrt", [HX_SIN] = "sin", [HX_COS] = "cos",
                                   [HX_TAN] = "tan", [HX_EXP] = "exp", [HX_LOG] = "log"};
  switch (e->op) {
  case HX_CONST: fprintf(out, "%s", val_c(a, &e->k, 0)); return;
  case HX_T: fputs("t", out); return;
  case HX_S: fputs("s", out); return;
  case HX_ADD: case HX_SUB: case HX_MUL: case HX_DIV:
    fputc('(', out);
    value(out, a, e->kid[0], depth);
    fputs(infix[e->op], out);
    value(out, a, e->kid[1], depth);
    fputc(')', out);
    return;
  case HX_NEG:
    fputs("(-", out);
    value(out, a, e->kid[0], depth);
    fputc(')', out);
    return;
  case HX_POW: {
    swValue p = val_num(a, e->p, DIM_NONE, e->loc);
    fputs("pow(", out);
    value(out, a, e->kid[0], depth);
    fprintf(out, ", %s)", val_c(a, &p, 0));
    return;
  }
  case HX_MOD:
    fputs("signal_mod(", out);
    value(out, a, e->kid[0], depth);
    fputs(", ", out);
    value(out, a, e->kid[1], depth);
    fputc(')', out);
    return;
  case HX_ATOM:
    fprintf(out, "sw_signal_eval(&signal_atom[%d], ", e->ref);
    value(out, a, e->kid[0], depth);
    fputc(')', out);
    return;
  case HX_CALL:
    fprintf(out, "signal_%d(", e->ref);
    value(out, a, e->kid[0], depth);
    fputs(", ctx)", out);
    return;
  case HX_PIECEWISE:
    gen_fexpr_piecewise(out, a, e, depth, value, value);
    return;
  default:   /* sqrt, sin, cos, tan, exp, log */
    fprintf(out, "%s(", fn[e->op]);
    value(out, a, e->kid[0], depth);
    fputc(')', out);
    return;
  }
}

void gen_signal_functions(FILE *out, swArena *a, const swScene *sc) {
  if (!sc->nsignal) return;
  fputs("/* The model's signals, functions of the time t (s), in SI units. */\n"
        "static inline double signal_mod(double a, double b) { return a - b * floor(a / b); }\n",
        out);
  if (sc->natom)
    fprintf(out, "/* the built-in signals inside them, set by build() */\n"
            "static swSignal signal_atom[%d];\n", sc->natom);
  fprintf(out, "/* the param values they read (ctx), set by build() */\n"
          "static double signal_P[%d];\n", sc->nparam > 0 ? sc->nparam : 1);
  if (sc->nderived)
    fprintf(out, "/* the derived quantities they read, set by build() */\n"
            "static double signal_D[%d];\n", sc->nderived);
  for (int i = 0; i < sc->nsignal; i++)
    fprintf(out, "static double signal_%d(double t, const void *ctx);\n", i);
  fputc('\n', out);
  for (int i = 0; i < sc->nsignal; i++) {
    const swSceneSignal *g = sc->signal[i];
    fputs("/* signal ", out);
    gen_c_comment(out, g->name, strlen(g->name));
    fputc('(', out);
    gen_c_comment(out, g->formal, strlen(g->formal));
    fprintf(out, "), %s */\n", dim_describe(a, g->dim));
    fprintf(out, "static double signal_%d(double t, const void *ctx) {\n"
            "  const double *P = ctx;\n  (void)P;\n%s", i,
            sc->nderived ? "  const double *D = signal_D;\n  (void)D;\n" : "");
    gen_origin(out, g->loc, "  ");
    fputs("  return ", out);
    value(out, a, g->expr, 1);
    fputs(";\n}\n\n", out);
  }
}

void gen_signal_build(FILE *out, swArena *a, const swScene *sc) {
  if (!sc->nsignal) return;
  fputc('\n', out);
  if (sc->nparam) fprintf(out, "  for (int i = 0; i < %d; i++) signal_P[i] = P[i];\n", sc->nparam);
  if (sc->nderived)
    fprintf(out, "  for (int i = 0; i < %d; i++) signal_D[i] = D[i];\n", sc->nderived);
  for (int k = 0; k < sc->natom; k++) {
    char var[64];
    snprintf(var, sizeof var, "signal_atom[%d]", k);
    gen_emit_signal(out, a, var, sc->atom[k]);
  }
}
