/* sema_output.c — the output statement: its file, its frame interval, its
 * probes and what it writes of each rod, joint and muscle.
 *
 * Design.  `output "F.h5" every T { ... }` is met once per scene.  The file
 * name, `every` and the probes are checked where the statement stands (the
 * probes are what `expect` reads).  The selections (`velocity humerus;`,
 * `angle elbow;`, `force biceps;`) name rods, joints and muscles that may be
 * defined further down, so they are kept and checked once the whole scene is
 * known (sema_output_selections), as swOutSelect entries: one quantity (an
 * SW_OUT_* bit of the runtime) for a list of items of one kind, or for all
 * of them.  gen_c.c turns them into the per-item bit arrays the simulator
 * hands to its output.  Each name is looked up as what the quantity can be
 * written for: `force` is a joint's or a muscle's, `angle` a hinge's,
 * `limit_torque` a limited joint's, the rod quantities a rod's or a muscle's
 * filaments'.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sema_int.h"

/* What a selection word writes, and of what. */
typedef struct {
  const char *word;
  unsigned rod_bit, joint_bit, muscle_bit;   /* 0: not of that kind */
} swOutWord;

static const swOutWord out_words[] = {
  {"positions", SW_OUT_POSITION, 0, 0},
  {"velocity", SW_OUT_VELOCITY, 0, 0},
  {"directors", SW_OUT_DIRECTORS, 0, 0},
  {"angular_velocity", SW_OUT_ANGULAR_VELOCITY, 0, 0},
  {"strain", SW_OUT_STRAIN, 0, 0},
  {"curvature", SW_OUT_CURVATURE, 0, 0},
  {"internal_force", SW_OUT_INTERNAL_FORCE, 0, 0},
  {"internal_couple", SW_OUT_INTERNAL_COUPLE, 0, 0},
  {"angle", 0, SW_OUT_ANGLE, 0},
  {"force", 0, SW_OUT_JOINT_FORCE, SW_OUT_MUSCLE_FORCE},
  {"limit_torque", 0, SW_OUT_LIMIT_TORQUE, 0},
  {"stretch", 0, 0, SW_OUT_STRETCH},
  {"activation", 0, 0, SW_OUT_ACTIVATION},
  {"filament_force", 0, 0, SW_OUT_FILAMENT_FORCE},
  {"energy", 0, 0, 0},
};
#define NWORDS ((int)(sizeof out_words / sizeof out_words[0]))

/* Rod quantities computed from the strains, which a rigid rod does not have. */
static const unsigned strain_bits = SW_OUT_STRAIN | SW_OUT_CURVATURE | SW_OUT_INTERNAL_FORCE |
                                    SW_OUT_INTERNAL_COUPLE;

void sema_output(swSema *S, swScope *scope, const swAst *it) {
  if (S->has_output) {
    char first[300];
    diag_error(it->loc, "a second 'output' (the first is at %s)",
               diag_where_from(S->output_loc, it->loc, first, sizeof first));
    return;
  }
  S->has_output = 1;
  S->output_loc = it->loc;
  S->output_item = it;
  S->output_scope = scope;
  swScene *sc = S->scene;
  if (!it->text[0]) diag_error(it->loc, "the output file name is empty");
  else sc->out = it->text;
  const swAst *every = ast_kid(it, 0);
  if (every) {
    swValue e = sema_expect(S, scope, every, 1, DIM_TIME, "'every'");
    if (e.kind == VAL_NUM && sema_require_const(S, &e, "'every'")) {
      if (!(e.v[0] > 0)) diag_error(e.loc, "'every' must be positive, got %g s", e.v[0]);
      else sc->every = e.v[0];
    }
  }
  for (int i = 1; i < it->nkid; i++) {
    const swAst *s = it->kid[i];
    if (s->kind == AST_FIELD && !strcmp(s->name, "probe")) {   /* probe NAME = WHAT; */
      sema_probe(S, scope, s);
      continue;
    }
    if (s->kind == AST_FIELD)
      diag_error(s->loc, "an output selection reads 'velocity all;', not '%s = ...'", s->name);
  }
}

/* ---- selections ---- */

static swOutSelect *new_select(swScene *sc, unsigned bit, swOutScope scope, swLoc loc) {
  if (sc->nselect == sc->capselect) {
    sc->capselect = sc->capselect ? 2 * sc->capselect : 8;
    sc->select = realloc(sc->select, (size_t)sc->capselect * sizeof *sc->select);
    if (!sc->select) abort();
  }
  swOutSelect *o = &sc->select[sc->nselect++];
  memset(o, 0, sizeof *o);
  o->bit = bit;
  o->scope = scope;
  o->loc = loc;
  return o;
}

static void push_id(swSema *S, swOutSelect *o, int id) {
  int *ids = ast_alloc(S->a, (size_t)(o->n + 1) * sizeof *ids);
  if (o->n) memcpy(ids, o->id, (size_t)o->n * sizeof *ids);
  ids[o->n++] = id;
  o->id = ids;
}

/* The rods of `target` (a rod, a muscle's filaments, or a list of them)
 * for a rod quantity; refuses rigid rods for the strain quantities. */
static void select_rods(swSema *S, swScope *scope, const swOutWord *w, const swAst *target,
                        swOutSelect *o) {
  char what[96];
  snprintf(what, sizeof what, "'%s'", w->word);
  swRodList list;
  if (!sema_rod_list(S, scope, target, ast_strdup(S->a, what, strlen(what)), &list)) return;
  const swScene *sc = S->scene;
  for (int k = 0; k < list.n; k++) {
    if (w->rod_bit & strain_bits)
      for (int r = 0; r < sc->nrod; r++)
        if (sc->rod[r].id == list.id[k] && sc->rod[r].rigid) {
          diag_error(target->loc, "rod '%s' is rigid: it has no %s to write", sc->rod[r].name,
                     w->word);
          return;
        }
    push_id(S, o, list.id[k]);
  }
}

/* A joint or a muscle for `force`, `angle`, `stretch` ...: adds it to the
 * selection of its kind (made on first use). */
static void select_named(swSema *S, swScope *scope, const swOutWord *w, const swAst *target,
                         swOutSelect **joints, swOutSelect **muscles, swLoc loc) {
  swScene *sc = S->scene;
  swValue v = sema_eval(S, scope, target);
  const char *reads = w->joint_bit && w->muscle_bit       ? "a joint or a muscle"
                      : w->joint_bit == SW_OUT_LIMIT_TORQUE ? "a joint with a limit"
                      : w->joint_bit                        ? "a hinge joint"
                                                            : "a muscle";
  if (v.kind == VAL_WORD) {
    sema_report_unknown(S, scope, v.word, v.loc, w->joint_bit ? "joint" : "muscle");
    return;
  }
  if (v.kind == VAL_ERROR) return;
  const swSymbol *sym = v.kind == VAL_REF ? v.ref : NULL;
  if (sym && sym->kind == SYM_JOINT && w->joint_bit) {
    int j;
    for (j = 0; j < sc->njoint; j++)
      if (!strcmp(sc->joint[j].name, sym->full)) break;
    if (j == sc->njoint) return;   /* the joint had errors */
    if (w->joint_bit == SW_OUT_ANGLE && sc->joint[j].kind != SW_JOINT_HINGE) {
      diag_error(target->loc, "joint '%s' is not a hinge: only a hinge has an angle",
                 sym->full);
      return;
    }
    if (w->joint_bit == SW_OUT_LIMIT_TORQUE && !sc->joint[j].has_range &&
        sc->joint[j].cone.kind != VAL_NUM) {
      diag_error(target->loc, "joint '%s' has no limit (a hinge's 'range' or a spherical "
                 "joint's 'cone'): it has no limit_torque", sym->full);
      return;
    }
    if (!*joints) *joints = new_select(sc, w->joint_bit, OUT_JOINTS, loc);
    push_id(S, *joints, j);
    return;
  }
  if (sym && sym->kind == SYM_MUSCLE && w->muscle_bit) {
    if (sym->index < 0) return;   /* the muscle had errors */
    if (!*muscles) *muscles = new_select(sc, w->muscle_bit, OUT_MUSCLES, loc);
    push_id(S, *muscles, sym->index);
    return;
  }
  if (sym) diag_error(target->loc, "'%s' is written for %s; '%s' is %s", w->word, reads, sym->name,
                      sema_sym_a_noun(sym->kind));
  else diag_error(target->loc, "'%s' is written for %s, given by its name", w->word, reads);
}

/* One selection statement `WORD [TARGETS];`. */
static void selection(swSema *S, swScope *scope, const swAst *s) {
  int k;
  for (k = 0; k < NWORDS; k++)
    if (!strcmp(s->name, out_words[k].word)) break;
  if (k == NWORDS && !strcmp(s->name, "probe")) {
    diag_error(s->loc, "a probe has a name and a value: probe NAME = centre_of_mass(RODS);");
    return;
  }
  if (k == NWORDS) {
    const char *cands[NWORDS + 1];
    for (int i = 0; i < NWORDS; i++) cands[i] = out_words[i].word;
    cands[NWORDS] = "probe";
    const char *near = diag_suggest(s->name, cands, NWORDS + 1);
    char list[512];
    diag_join(list, sizeof list, cands, NWORDS + 1);
    if (near) diag_error(s->loc, "unknown output '%s'; did you mean '%s'?", s->name, near);
    else diag_error(s->loc, "unknown output '%s' (the outputs: %s)", s->name, list);
    return;
  }
  const swOutWord *w = &out_words[k];
  if (!w->rod_bit && !w->joint_bit && !w->muscle_bit) {   /* energy: always written */
    if (s->nkid) diag_error(s->kid[0]->loc, "'%s' is of the whole scene: write '%s;'", w->word,
                            w->word);
    return;
  }
  swScene *sc = S->scene;
  /* nothing after the word, or `all`: every item of each kind it has */
  int all = s->nkid == 0;
  for (int t = 0; t < s->nkid; t++)
    if (s->kid[t]->kind == AST_NAME && !strcmp(s->kid[t]->name, "all")) {
      if (s->nkid > 1) {
        diag_error(s->kid[t]->loc, "'all' stands alone: write '%s all;'", w->word);
        return;
      }
      all = 1;
    }
  if (all) {
    if (w->rod_bit) new_select(sc, w->rod_bit, OUT_RODS, s->loc)->n = -1;
    if (w->joint_bit) new_select(sc, w->joint_bit, OUT_JOINTS, s->loc)->n = -1;
    if (w->muscle_bit) new_select(sc, w->muscle_bit, OUT_MUSCLES, s->loc)->n = -1;
    return;
  }
  if (w->rod_bit) {
    swOutSelect *o = new_select(sc, w->rod_bit, OUT_RODS, s->loc);
    for (int t = 0; t < s->nkid; t++) select_rods(S, scope, w, s->kid[t], o);
    return;
  }
  swOutSelect *joints = NULL, *muscles = NULL;
  for (int t = 0; t < s->nkid; t++) {
    const swAst *tg = s->kid[t];
    if (tg->kind == AST_VEC)   /* force (a, b); */
      for (int i = 0; i < tg->nkid; i++)
        select_named(S, scope, w, tg->kid[i], &joints, &muscles, s->loc);
    else
      select_named(S, scope, w, tg, &joints, &muscles, s->loc);
  }
}

void sema_output_selections(swSema *S) {
  const swAst *it = S->output_item;
  if (!it) return;
  for (int i = 1; i < it->nkid; i++)
    if (it->kid[i]->kind == AST_SELECT) selection(S, S->output_scope, it->kid[i]);
}
