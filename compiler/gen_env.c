/* gen_env.c — the generated C of environments: ground, terrain, fluid,
 * contact, obstacle, torque wave and probe blocks of build(), and each terrain's
 * height function.
 *
 * Design.  Environment blocks follow the rods' pattern: the description's
 * init (the runtime's defaults), then one assignment per field the model
 * gave, from the lowering tables of gen_lower.c, and a rod list as a static
 * array with the rods' names in a comment.  A terrain's height(x, y)
 * becomes a C function of type swHeightFn that returns h and fills its
 * gradient by forward-mode differentiation: every quantity is a dual number
 * (value, d/dx, d/dy) and each operation is a small helper applying the
 * chain rule (dual_mul: (ab)' = a'b + ab', dual_sin: sin(a)' = cos(a) a',
 * ...), printed once above the first height.  A let of the terrain's body
 * is one statement, piecewise() a chain of conditional expressions (only
 * the chosen value is evaluated, so a branch may take sqrt of what is
 * negative elsewhere).  The compiler evaluates the same tree with the same
 * rules (sema_height_eval); tests/lang/test_terrain.sh holds the two
 * together and against finite differences.  Params reach the function
 * through its ctx pointer: build() copies P into a static array that lives
 * as long as the model.
 */
#include <stdio.h>
#include <string.h>

#include "diag.h"
#include "gen.h"

/* ---- height functions ---- */

static void dual_helpers(FILE *out) {
  fputs(
    "/* Terrain heights with their gradient, by forward-mode differentiation: a\n"
    " * dual number carries a value and its derivatives along x and y, and each\n"
    " * operation applies the chain rule. */\n"
    "typedef struct { double v, x, y; } dual;\n"
    "static inline dual dual_const(double c) { dual r = {c, 0.0, 0.0}; return r; }\n"
    "static inline dual dual_add(dual a, dual b) { dual r = {a.v + b.v, a.x + b.x, a.y + b.y}; return r; }\n"
    "static inline dual dual_sub(dual a, dual b) { dual r = {a.v - b.v, a.x - b.x, a.y - b.y}; return r; }\n"
    "static inline dual dual_mul(dual a, dual b) {\n"
    "  dual r = {a.v * b.v, a.x * b.v + a.v * b.x, a.y * b.v + a.v * b.y};\n"
    "  return r;\n"
    "}\n"
    "static inline dual dual_div(dual a, dual b) {\n"
    "  dual r = {a.v / b.v, (a.x * b.v - a.v * b.x) / (b.v * b.v), (a.y * b.v - a.v * b.y) / (b.v * b.v)};\n"
    "  return r;\n"
    "}\n"
    "static inline dual dual_neg(dual a) { dual r = {-a.v, -a.x, -a.y}; return r; }\n"
    "/* f(a) with f'(a) = df */\n"
    "static inline dual dual_chain(double f, double df, dual a) { dual r = {f, df * a.x, df * a.y}; return r; }\n"
    "static inline dual dual_pow(dual a, double p) {\n"
    "  return dual_chain(pow(a.v, p), p == 0 ? 0.0 : p * pow(a.v, p - 1), a);\n"
    "}\n"
    "static inline dual dual_sqrt(dual a) { double f = sqrt(a.v); return dual_chain(f, 0.5 / f, a); }\n"
    "static inline dual dual_sin(dual a) { return dual_chain(sin(a.v), cos(a.v), a); }\n"
    "static inline dual dual_cos(dual a) { return dual_chain(cos(a.v), -sin(a.v), a); }\n"
    "static inline dual dual_tan(dual a) { return dual_chain(tan(a.v), 1 / (cos(a.v) * cos(a.v)), a); }\n"
    "static inline dual dual_exp(dual a) { double f = exp(a.v); return dual_chain(f, f, a); }\n"
    "static inline dual dual_log(dual a) { return dual_chain(log(a.v), 1 / a.v, a); }\n\n",
    out);
}

static void expr(FILE *out, swArena *a, const swHExpr *e, int depth);

/* the value alone (a comparison needs no derivatives) */
static void value(FILE *out, swArena *a, const swHExpr *e, int depth) {
  if (e->op == HX_CONST) {
    fputs(val_c(a, &e->k, 0), out);
    return;
  }
  expr(out, a, e, depth);
  fputs(".v", out);
}

void gen_fexpr_condition(FILE *out, swArena *a, const swHExpr *e, int depth, gen_fexpr_fn operand) {
  if (e->op == HX_AND || e->op == HX_OR) {
    fputc('(', out);
    gen_fexpr_condition(out, a, e->kid[0], depth, operand);
    fputs(e->op == HX_AND ? " && " : " || ", out);
    gen_fexpr_condition(out, a, e->kid[1], depth, operand);
    fputc(')', out);
    return;
  }
  static const char *const cmp[] = {"<", "<=", ">", ">="};
  fputc('(', out);
  operand(out, a, e->kid[0], depth);
  fprintf(out, " %s ", cmp[e->op - HX_LT]);
  operand(out, a, e->kid[1], depth);
  fputc(')', out);
}

/* cond0 ? value0 : cond1 ? value1 : default, one case a line */
void gen_fexpr_piecewise(FILE *out, swArena *a, const swHExpr *e, int depth, gen_fexpr_fn operand,
                         gen_fexpr_fn branch) {
  fputc('(', out);
  for (int i = 0; i + 1 < e->nkid; i += 2) {
    gen_fexpr_condition(out, a, e->kid[i], depth + 1, operand);
    fputs(" ? ", out);
    branch(out, a, e->kid[i + 1], depth + 1);
    fprintf(out, "\n%*s: ", 4 + 2 * depth, "");
  }
  branch(out, a, e->kid[e->nkid - 1], depth + 1);
  fputc(')', out);
}

static void expr(FILE *out, swArena *a, const swHExpr *e, int depth) {
  static const char *const fn[] = {
    [HX_ADD] = "dual_add", [HX_SUB] = "dual_sub", [HX_MUL] = "dual_mul", [HX_DIV] = "dual_div",
    [HX_NEG] = "dual_neg", [HX_SQRT] = "dual_sqrt", [HX_SIN] = "dual_sin", [HX_COS] = "dual_cos",
    [HX_TAN] = "dual_tan", [HX_EXP] = "dual_exp", [HX_LOG] = "dual_log",
  };
  switch (e->op) {
  case HX_CONST: fprintf(out, "dual_const(%s)", val_c(a, &e->k, 0)); return;
  case HX_X: fputs("X", out); return;
  case HX_Y: fputs("Y", out); return;
  case HX_LET: fprintf(out, "let_%d", e->let); return;
  case HX_POW: {
    swValue p = val_num(a, e->p, DIM_NONE, e->loc);
    fputs("dual_pow(", out);
    expr(out, a, e->kid[0], depth);
    fprintf(out, ", %s)", val_c(a, &p, 0));
    return;
  }
  case HX_PIECEWISE:
    gen_fexpr_piecewise(out, a, e, depth, value, expr);
    return;
  default:
    fprintf(out, "%s(", fn[e->op]);
    for (int i = 0; i < e->nkid; i++) {
      if (i) fputs(", ", out);
      expr(out, a, e->kid[i], depth);
    }
    fputc(')', out);
    return;
  }
}

static int any_terrain(const swScene *sc) {
  for (int i = 0; i < sc->nground; i++)
    if (sc->ground[i].height) return 1;
  return 0;
}

void gen_env_heights(FILE *out, swArena *a, const swScene *sc) {
  if (!any_terrain(sc)) return;
  dual_helpers(out);
  if (sc->nparam)
    fprintf(out, "/* the param values the heights read (ctx), set by build() */\n"
            "static double height_P[%d];\n\n", sc->nparam);
  if (sc->nderived)
    fprintf(out, "/* the derived quantities the heights read, set by build() */\n"
            "static double height_D[%d];\n\n", sc->nderived);
  for (int i = 0; i < sc->nground; i++) {
    const swSceneGround *g = &sc->ground[i];
    const swHeight *h = g->height;
    if (!h) continue;
    fputs("/* terrain ", out);
    gen_c_comment(out, g->name, strlen(g->name));
    fputs(": z = height(", out);
    gen_c_comment(out, h->xname, strlen(h->xname));
    fputs(", ", out);
    gen_c_comment(out, h->yname, strlen(h->yname));
    fprintf(out, "), m; grad = (dh/dx, dh/dy) */\n"
            "static double height_%d(double x, double y, double grad[2], const void *ctx) {\n"
            "  const double *P = ctx;\n  (void)P;\n"
            "%s"
            "  const dual X = {x, 1.0, 0.0}, Y = {y, 0.0, 1.0};\n  (void)X;\n  (void)Y;\n", i,
            sc->nderived ? "  const double *D = height_D;\n  (void)D;\n" : "");
    for (int l = 0; l < h->nlet; l++) {
      gen_origin(out, h->let_loc[l], "  ");
      fprintf(out, "  const dual let_%d = ", l);
      expr(out, a, h->let[l], 1);
      fputs(";   /* ", out);
      gen_c_comment(out, h->let_name[l], strlen(h->let_name[l]));
      fputs(" */\n", out);
    }
    gen_origin(out, h->loc, "  ");
    fputs("  const dual h = ", out);
    expr(out, a, h->expr, 1);
    fputs(";\n  grad[0] = h.x;\n  grad[1] = h.y;\n  return h.v;\n}\n\n", out);
  }
}

/* ---- build() blocks ---- */

/* "    static const int rods[N] = {...};   / * names * /" and the two members */
static void rod_list(FILE *out, const char *var, const swRodList *r) {
  if (r->n == 0) {
    fprintf(out, "    /* every rod of the scene */\n");
    return;
  }
  fprintf(out, "    static const int rods[%d] = {", r->n);
  for (int k = 0; k < r->n; k++) fprintf(out, "%s%d", k ? ", " : "", r->id[k]);
  fputs("};   /* ", out);
  for (int k = 0; k < r->n; k++) {
    if (k && r->name[k] == r->name[k - 1]) continue;   /* a muscle's filaments: once */
    if (k) fputs(", ", out);
    gen_c_comment(out, r->name[k], strlen(r->name[k]));
  }
  fprintf(out, " */\n    %s.nrods = %d;\n    %s.rods = rods;\n", var, r->n, var);
}

static void open_block(FILE *out, swLoc loc, const char *type, const char *var, const char *name) {
  fputc('\n', out);
  gen_origin(out, loc, "  ");
  fprintf(out, "  {\n    %s %s;\n    sw_%s_desc_init(&%s);\n    %s.name = ", type, var, var, var, var);
  gen_c_string(out, name);
  fputs(";\n", out);
}

void gen_env_build(FILE *out, swArena *a, const swScene *sc) {
  swLowField f[GEN_MAX_FIELDS];
  if (any_terrain(sc) && sc->nparam)
    fprintf(out, "\n  for (int i = 0; i < %d; i++) height_P[i] = P[i];\n", sc->nparam);
  if (any_terrain(sc) && sc->nderived)
    fprintf(out, "  for (int i = 0; i < %d; i++) height_D[i] = D[i];\n", sc->nderived);
  for (int i = 0; i < sc->nground; i++) {
    const swSceneGround *g = &sc->ground[i];
    open_block(out, g->loc, "swGroundDesc", "ground", g->name);
    if (g->height)
      fprintf(out, "    ground.height = height_%d;\n    ground.height_ctx = %s;\n", i,
              sc->nparam ? "height_P" : "NULL");
    rod_list(out, "ground", &g->rods);
    if (g->contact_point) fputs("    ground.contact_point = 1;\n", out);
    gen_assign_fields(out, a, "ground", f, gen_ground_fields(g, f));
    fputs("    ok &= sw_spec_add_ground(s, &ground) >= 0;\n  }\n", out);
  }
  for (int i = 0; i < sc->nfluid; i++) {
    const swSceneFluid *fl = &sc->fluid[i];
    open_block(out, fl->loc, "swFluidDesc", "fluid", fl->name);
    fprintf(out, "    fluid.model = %s;\n",
            fl->model == SW_FLUID_STOKES ? "SW_FLUID_STOKES" : "SW_FLUID_QUADRATIC");
    if (fl->area != SW_FLUID_SILHOUETTE)
      fprintf(out, "    fluid.area = %s;\n",
              fl->area == SW_FLUID_CROSS_SECTION ? "SW_FLUID_CROSS_SECTION" : "SW_FLUID_BROADSIDE");
    if (fl->buoyancy) fputs("    fluid.buoyancy = 1;\n", out);
    rod_list(out, "fluid", &fl->rods);
    gen_assign_fields(out, a, "fluid", f, gen_fluid_fields(fl, f));
    fputs("    ok &= sw_spec_add_fluid(s, &fluid) >= 0;\n  }\n", out);
  }
  for (int i = 0; i < sc->ncontact; i++) {
    const swSceneContact *c = &sc->contact[i];
    open_block(out, c->loc, "swContactDesc", "contact", c->name);
    if (c->self) fputs("    contact.self = 1;\n", out);
    rod_list(out, "contact", &c->rods);
    gen_assign_fields(out, a, "contact", f, gen_contact_fields(c, f));
    fputs("    ok &= sw_spec_add_contact(s, &contact) >= 0;\n  }\n", out);
  }
  static const char *const shapes[] = {"SW_OBSTACLE_SPHERE", "SW_OBSTACLE_CAPSULE",
                                        "SW_OBSTACLE_CYLINDER", "SW_OBSTACLE_BOX",
                                        "SW_OBSTACLE_ELLIPSOID"};
  for (int i = 0; i < sc->nobstacle; i++) {
    const swSceneObstacle *o = &sc->obstacle[i];
    open_block(out, o->loc, "swObstacleDesc", "obstacle", o->name);
    fprintf(out, "    obstacle.shape = %s;\n", shapes[o->shape]);
    if (o->carrier_rod >= 0) {
      fprintf(out, "    obstacle.carrier_rod = %d; obstacle.carrier_node = %d;   /* ", o->carrier_rod,
              o->carrier_node);
      gen_c_comment(out, o->carrier_name, strlen(o->carrier_name));
      fputs(" */\n", out);
    }
    rod_list(out, "obstacle", &o->rods);
    gen_assign_fields(out, a, "obstacle", f, gen_obstacle_fields(o, f));
    fputs("    ok &= sw_spec_add_obstacle(s, &obstacle) >= 0;\n  }\n", out);
  }
  for (int i = 0; i < sc->nwave; i++) {
    const swSceneWave *w = &sc->wave[i];
    open_block(out, w->loc, "swWaveDesc", "wave", w->name);
    fprintf(out, "    wave.rod = %d;   /* ", w->rod);
    gen_c_comment(out, w->rod_name, strlen(w->rod_name));
    fprintf(out, " */\n    wave.ncoef = %d;\n", w->coef.n);
    if (w->reverse) fputs("    wave.reverse = 1;\n", out);
    gen_assign_fields(out, a, "wave", f, gen_wave_fields(w, f));
    fputs("    ok &= sw_spec_add_wave(s, &wave) >= 0;\n  }\n", out);
  }
  static const char *const kinds[] = {"SW_PROBE_COM", "SW_PROBE_COM_VELOCITY",
                                      "SW_PROBE_MEAN_VELOCITY", "SW_PROBE_NODE"};
  for (int i = 0; i < sc->nprobe; i++) {
    const swSceneProbe *p = &sc->probe[i];
    open_block(out, p->loc, "swProbeDesc", "probe", p->name);
    fprintf(out, "    probe.kind = %s;\n", kinds[p->kind]);
    if (p->kind == SW_PROBE_NODE) {
      fprintf(out, "    probe.rod = %d; probe.node = %d;   /* ", p->rod, p->node);
      gen_c_comment(out, p->rod_name, strlen(p->rod_name));
      fputs(" */\n", out);
    } else {
      rod_list(out, "probe", &p->rods);
    }
    if (p->window.kind == VAL_NUM) fprintf(out, "    probe.window = %s;\n", val_c(a, &p->window, 0));
    fputs("    ok &= sw_spec_add_probe(s, &probe) >= 0;\n  }\n", out);
  }
}
