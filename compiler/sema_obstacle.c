/* sema_obstacle.c — the obstacle definition: obstacle NAME { shape = ...; },
 * its shape and size fields, its friction (sema_env_friction) and its carrier, checked with
 * sema_env.c's field helpers and appended to the scene as the other
 * environments are (sema_env.c says how).  Physics: docs/physics.md, "Rigid
 * obstacles".
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sema_int.h"

/* ---- obstacle NAME { shape = ...; } ---- */

static const char *const obstacle_keys[] = {"shape", "centre", "axis", "normal", "radius", "length",
                                            "size", "semi_axes", "stiffness", "damping",
                                            "carried_by", "rods", "friction", "static_friction",
                                            "kinetic_friction", "tangential_stiffness"};
/* swObstacleShape's order */
static const char *const obstacle_shapes[] = {"sphere", "capsule", "cylinder", "box", "ellipsoid"};

/* The size fields each shape reads: radius, length, size, semi_axes. */
static int shape_reads(swObstacleShape shape, const char *key) {
  static const char *const reads[][2] = {{"radius", NULL}, {"radius", "length"}, {"radius", NULL},
                                         {"size", NULL}, {"semi_axes", NULL}};
  return (reads[shape][0] && !strcmp(key, reads[shape][0])) ||
         (reads[shape][1] && !strcmp(key, reads[shape][1]));
}

/* v / 2, its C expressions too (a box's size to its half sizes). */
static swValue halved(swSema *S, swValue v) {
  swValue h = v;
  h.v = ast_alloc(S->a, (size_t)v.n * sizeof *h.v);
  for (int k = 0; k < v.n; k++) h.v[k] = 0.5 * v.v[k];
  if (v.c) {
    h.c = ast_alloc(S->a, (size_t)v.n * sizeof *h.c);
    for (int k = 0; k < v.n; k++) {
      if (!v.c[k]) {
        h.c[k] = NULL;
        continue;
      }
      size_t len = strlen(v.c[k]) + 16;
      char *c = ast_alloc(S->a, len);
      snprintf(c, len, "(0.5 * (%s))", v.c[k]);
      h.c[k] = c;
    }
  }
  return h;
}

void sema_obstacle(swSema *S, swScope *sc, const swAst *it, const char *name, const char *what) {
  swFields f;
  sema_fields(S, it, 0, what, obstacle_keys, (int)(sizeof obstacle_keys / sizeof obstacle_keys[0]), &f);
  swSceneObstacle o;
  memset(&o, 0, sizeof o);
  o.name = name;
  o.loc = it->loc;
  o.carrier_rod = o.carrier_node = -1;
  int ok = 1;
  const swAst *se = sema_field(&f, "shape");
  if (!se) {
    sema_missing(&f, it->loc, "%s needs a 'shape': sphere, capsule, cylinder, box or ellipsoid "
                 "(e.g. shape = sphere;)", what);
    return;
  }
  const char *shape = sema_word(S, sc, se, "obstacle shape", obstacle_shapes, 5);
  if (!shape) return;
  for (int k = 0; k < 5; k++)
    if (!strcmp(shape, obstacle_shapes[k])) o.shape = (swObstacleShape)k;
  /* the size fields: those of the shape required, the others warned of */
  static const char *const sizes[] = {"radius", "length", "size", "semi_axes"};
  static const char *const example[] = {"radius = 1 cm;", "length = 5 cm;", "size = (10, 10, 1) cm;",
                                        "semi_axes = (3, 2, 1) cm;"};
  for (int i = 0; i < 4; i++) {
    const swAst *e = sema_field(&f, sizes[i]);
    if (!shape_reads(o.shape, sizes[i])) {
      if (e) diag_warning(e->loc, "'%s' has no effect on a %s", sizes[i], shape);
      continue;
    }
    if (!e) {
      sema_missing(&f, it->loc, "%s, a %s, needs a '%s' (e.g. %s)", what, shape, sizes[i], example[i]);
      ok = 0;
      continue;
    }
    swValue v = i < 2 ? sema_env_bounded(S, sc, &f, sizes[i], 1, DIM_LENGTH, i == 0)
                      : sema_field_value(S, sc, &f, sizes[i], 3, DIM_LENGTH);
    for (int k = 0; i >= 2 && v.kind != VAL_ERROR && k < 3; k++)
      if (!(v.v[k] > 0)) {
        diag_error(v.loc, "'%s' must be positive in each direction, got %g m", sizes[i], v.v[k]);
        v = val_error();
      }
    if (v.kind == VAL_ERROR) ok = 0;
    if (i == 0) o.radius = v;
    else if (i == 1) o.length = v;
    else o.half = i == 2 && v.kind != VAL_ERROR ? halved(S, v) : v;
  }
  if (!sema_field(&f, "stiffness")) {
    sema_missing(&f, it->loc, "%s needs a 'stiffness' (the penalty of its surface, e.g. "
                 "stiffness = 1e3 N/m;)", what);
    ok = 0;
  }
  o.stiffness = sema_env_bounded(S, sc, &f, "stiffness", 1, DIM_STIFFNESS, 1);
  o.damping = sema_env_bounded(S, sc, &f, "damping", 1, DIM_DAMPING, 0);
  o.axis = sema_env_nonzero_vector(S, sc, &f, "axis", DIM_NONE);
  o.normal = sema_env_nonzero_vector(S, sc, &f, "normal", DIM_NONE);
  o.centre = sema_field(&f, "centre") ? sema_field_value(S, sc, &f, "centre", 3, DIM_LENGTH) : val_error();
  const char *keys[] = {"stiffness", "damping", "axis", "normal", "centre"};
  const swValue *vals[] = {&o.stiffness, &o.damping, &o.axis, &o.normal, &o.centre};
  for (int i = 0; i < 5; i++)
    if (sema_field(&f, keys[i]) && vals[i]->kind == VAL_ERROR) ok = 0;
  ok &= sema_env_friction(S, sc, &f, what, &o.static_friction, &o.kinetic_friction, &o.tangential_stiffness);
  const swAst *cb = sema_field(&f, "carried_by");
  if (cb) {
    swValue p = sema_eval(S, sc, cb);
    if (p.kind == VAL_WORD) {
      sema_report_unknown(S, sc, p.word, p.loc, "rod");
      ok = 0;
    } else if (p.kind != VAL_ERROR && p.kind != VAL_POINT) {
      diag_error(cb->loc, "'carried_by' is a point on a rod (humerus.at(0.5), humerus.end), the "
                 "element that carries %s", what);
      ok = 0;
    } else if (p.kind == VAL_ERROR || !sema_point_fixed(&p, "the point that carries an obstacle")) {
      ok = 0;
    } else {
      o.carrier_rod = S->scene->rod[p.rod].id;
      o.carrier_node = p.node;
      o.carrier_name = S->scene->rod[p.rod].name;
      if (!sema_field(&f, "centre")) o.centre = p; /* at the point itself */
    }
  } else if (!sema_field(&f, "centre") && ok) {
    sema_missing(&f, it->loc, "%s needs a 'centre' (e.g. centre = (0, 0, 0) m;) or 'carried_by' "
                 "(a point on a rod it moves with)", what);
    ok = 0;
  }
  if (o.centre.kind == VAL_POINT) o.centre.kind = VAL_VEC; /* its position */
  ok &= sema_env_rods_field(S, sc, &f, what, &o.rods);
  for (int i = 0; ok && o.carrier_rod >= 0 && i < o.rods.n; i++)
    if (o.rods.id[i] == o.carrier_rod) {
      diag_error(sema_field(&f, "rods")->loc, "%s is carried by '%s', which cannot touch it; list "
                 "the other rods", what, o.carrier_name);
      ok = 0;
    }
  if (!ok) return;
  swScene *scn = S->scene;
  *(swSceneObstacle *)sema_env_append((void **)&scn->obstacle, &scn->nobstacle, &scn->capobstacle,
                             sizeof o) = o;
}
