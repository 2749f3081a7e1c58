/* sema.c — the checker's driver: the walk over a file's items, component
 * instances, and sema_check with what follows the last item (--let
 * overrides, "never used" warnings).
 *
 * Design.  Items are walked twice: first every name is declared (in the
 * scopes of sema_scope.c), so definitions may refer to each other in any
 * order; then everything is evaluated in file order, definitions lazily on
 * first use (see sema_def.c).  A component instance gets a scope of its own
 * (named PREFIX.NAME.), its arguments bound to the component's parameters,
 * and its body walked there the same way.  An import is checked where it
 * stands (sema_import.c), its items walked by sema_check_file here.
 */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lex.h"
#include "sema_int.h"

/* ---- items ---- */

static const char *const def_kinds[] = {"material", "rod", "bone", "tendon", "muscle",
                                        "ground", "terrain", "fluid", "contact", "torque_wave"};

/* A scene statement, which a runnable scene imported for its definitions
 * keeps to itself: an action (clamp, gravity, force, activate ...),
 * simulate, output, expect, use, and the environments. */
static int scene_statement(const swAst *it) {
  if (sema_is_signal_def(it)) return 0;   /* signal NAME(t) = ...: a definition */
  return it->kind == AST_ACTION || it->kind == AST_SIMULATE || it->kind == AST_OUTPUT ||
         it->kind == AST_EXPECT || it->kind == AST_USE || it->kind == AST_FOR ||
         (it->kind == AST_DEF && sema_is_env_kind(it->text));
}

static void declare_items(swSema *S, swScope *scope, const swAst *items, int first) {
  for (int i = first; i < items->nkid && !diag_stopped(); i++) {
    const swAst *it = items->kid[i];
    if (S->defs_only && scene_statement(it)) continue;
    switch (it->kind) {
    case AST_IMPORT:
      if (!scope->file_level) {
        diag_error(it->loc, "import is only allowed at the top of a file, not in a component");
      } else {
        if (it->name) {   /* the namespace: its uses fail quietly if the file does */
          swSymbol *ns = sema_declare(S, scope, SYM_INSTANCE, it->name, it->loc, it);
          if (!ns) break;
          ns->state = 2;
          ns->used = 1;
        }
        sema_import(S, it, scope);
      }
      break;
    case AST_PARAM:
      if (!scope->file_level) {
        diag_error(it->loc, "a param belongs at file level; a component takes parameters "
                   "in its header: component NAME(%s = ...)", it->name);
        /* declared as a let all the same, so its uses are not also unknown */
        sema_declare(S, scope, SYM_LET, it->name, it->loc, it);
        break;
      }
      sema_declare(S, scope, SYM_PARAM, it->name, it->loc, it);
      break;
    case AST_LET:
      sema_declare(S, scope, SYM_LET, it->name, it->loc, it);
      break;
    case AST_DEF: {
      int k;
      if (sema_is_env_kind(it->text)) {   /* ground, terrain, fluid, contact, torque_wave */
        if (it->name) sema_declare(S, scope, SYM_ENV, it->name, it->loc, it);
        break;
      }
      for (k = 0; k < 5; k++)
        if (!strcmp(it->text, def_kinds[k])) break;
      if (k < 5 && !it->name) {
        diag_error(it->loc, "a %s needs a name: %s NAME { ... }", it->text, it->text);
        break;
      }
      if (k == 5) {
        const char *near = diag_suggest(it->text, def_kinds, 10);
        swLoc at = it->loc;
        at.end_col = at.col + (int)strlen(it->text) - 1;
        at.end_line = at.line;
        if (near)
          diag_error(at, "unknown kind of definition '%s'; did you mean '%s'?", it->text, near);
        else
          diag_error(at, "unknown kind of definition '%s' (expected material, rod, bone, "
                     "tendon, muscle, ground, terrain, fluid, contact or torque_wave)", it->text);
        break;
      }
      sema_declare(S, scope, k == 0 ? SYM_MATERIAL : k == 4 ? SYM_MUSCLE : SYM_ROD, it->name,
                   it->loc, it);
      break;
    }
    case AST_JOINT:
      sema_declare(S, scope, SYM_JOINT, it->name, it->loc, it);
      break;
    case AST_ACTION:
      if (sema_is_signal_def(it)) {
        const char *name = sema_signal_def_name(it);
        if (!name) {
          diag_error(it->loc, "a signal is declared as signal NAME(t) = expression;");
          break;
        }
        sema_declare(S, scope, SYM_SIGNAL, name, ast_kid(it, 0)->loc, it);
      }
      break;
    case AST_COMPONENT:
      if (!scope->file_level) {
        diag_error(it->loc, "components cannot be defined inside components");
        break;
      }
      sema_declare(S, scope, SYM_COMPONENT, it->name, it->loc, it);
      break;
    case AST_USE:
      sema_declare(S, scope, SYM_INSTANCE, it->name, it->loc, it);
      break;
    case AST_FOR:
      sema_declare(S, scope, SYM_LOOP, it->name, it->loc, it);
      break;
    default:
      break;
    }
  }
}

/* A component by name, NAME or NAMESPACE.NAME (import "f" as NAMESPACE);
 * NULL after reporting what is unknown. */
static swSymbol *lookup_qualified(swSema *S, swScope *scope, const char *text, swLoc loc) {
  const char *dot = strchr(text, '.');
  if (!dot) {
    swSymbol *s = sema_lookup(S, scope, text);
    if (!s) sema_report_unknown(S, scope, text, loc, "component");
    return s;
  }
  char *head = ast_strdup(S->a, text, (size_t)(dot - text));
  swSymbol *ns = sema_lookup(S, scope, head);
  if (!ns) {
    sema_report_unknown(S, scope, head, loc, "name");
    return NULL;
  }
  if (ns->kind == SYM_INSTANCE && !ns->members) {
    /* a namespace whose import failed: that error is the one to read */
    if (!diag_errors())
      diag_error(loc, "'%s' has no components: its import gave none", head);
    return NULL;
  }
  if (ns->kind != SYM_INSTANCE) {
    diag_error(loc, "'%s' is %s, not an imported namespace or an instance", head,
               sema_sym_a_noun(ns->kind));
    return NULL;
  }
  ns->used = 1;
  swSymbol *s = sema_lookup_local(ns->members, dot + 1);
  if (!s) {
    const char *cands[256];
    int n = 0;
    for (int i = 0; i < ns->members->n && n < 256; i++) cands[n++] = ns->members->sym[i]->name;
    const char *near = diag_suggest(dot + 1, cands, n);
    if (near) diag_error(loc, "'%s' has no component '%s'; did you mean '%s'?", head, dot + 1, near);
    else diag_error(loc, "'%s' has no component '%s'", head, dot + 1);
  }
  return s;
}

static void instantiate(swSema *S, swScope *scope, const swAst *it) {
  swSymbol *inst = sema_lookup_local(scope, it->name);
  if (!inst || inst->def != it) return;   /* declaration failed */
  inst->state = 2;   /* instantiated, or its error reported: members may stay NULL */
  swSymbol *comp = lookup_qualified(S, scope, it->text, it->loc);
  if (!comp) return;   /* reported */
  comp->used = 1;
  if (comp->kind != SYM_COMPONENT) {
    diag_error(it->loc, "'%s' is %s, not a component", it->text, sema_sym_a_noun(comp->kind));
    return;
  }
  /* a component whose body uses itself, directly or through others, would
   * instantiate without end (and with two such uses, exponentially) */
  if (comp->state == 1) {
    diag_error(it->loc, "component '%s' uses itself", comp->name);
    return;
  }
  if (S->instance_depth >= SEMA_MAX_INSTANCE_DEPTH) {
    diag_error(it->loc, "components are nested more than %d deep", SEMA_MAX_INSTANCE_DEPTH);
    return;
  }
  /* each instance costs the items of its body (at least one): nesting
   * multiplies them, so the total is bounded */
  int before = S->nexpanded;
  S->nexpanded += comp->def->nkid;
  if (S->nexpanded > SEMA_MAX_EXPANDED) {
    if (before <= SEMA_MAX_EXPANDED)
      diag_error(it->loc, "the components of this model expand to more than %d definitions "
                 "and statements", SEMA_MAX_EXPANDED);
    S->nexpanded = SEMA_MAX_EXPANDED + 1;
    return;
  }
  const swAst *def = comp->def, *formals = def->kid[0], *args = it->kid[0];
  size_t plen = strlen(scope->prefix) + strlen(it->name) + 2;
  char *prefix = ast_alloc(S->a, plen);
  snprintf(prefix, plen, "%s%s.", scope->prefix, it->name);
  swScope *inner = sema_scope_new(S, comp->scope, prefix);
  inst->members = inner;
  /* bind arguments to formals: positional first, then by name */
  const swAst **bound = ast_alloc(S->a, (size_t)(formals->nkid + 1) * sizeof *bound);
  int pos = 0;
  for (int i = 0; i < args->nkid; i++) {
    const swAst *arg = args->kid[i];
    int slot = -1;
    if (arg->name) {
      for (int k = 0; k < formals->nkid; k++)
        if (!strcmp(formals->kid[k]->name, arg->name)) slot = k;
      if (slot < 0) {
        const char *cands[64];
        int n = 0;
        for (int k = 0; k < formals->nkid && n < 64; k++) cands[n++] = formals->kid[k]->name;
        const char *near = diag_suggest(arg->name, cands, n);
        if (near)
          diag_error(arg->loc, "component '%s' has no parameter '%s'; did you mean '%s'?",
                     comp->name, arg->name, near);
        else
          diag_error(arg->loc, "component '%s' has no parameter '%s'", comp->name, arg->name);
        continue;
      }
    } else {
      if (pos >= formals->nkid) {
        diag_error(arg->loc, "component '%s' takes %d parameters", comp->name, formals->nkid);
        continue;
      }
      slot = pos++;
    }
    if (bound[slot]) {
      diag_error(arg->loc, "parameter '%s' of '%s' is given twice", formals->kid[slot]->name,
                 comp->name);
      continue;
    }
    bound[slot] = arg;
  }
  S->instance_depth++;
  diag_push_context(it->loc, "in '%s%s', an instance of component '%s'", scope->prefix,
                    it->name, comp->name);
  comp->state = 1;   /* its body is being instantiated */
  for (int k = 0; k < formals->nkid; k++) {
    const swAst *f = formals->kid[k];
    swSymbol *sym = sema_declare(S, inner, SYM_FORMAL, f->name, f->loc, f);
    if (!sym) continue;
    sym->used = 1;
    sym->state = 2;
    if (bound[k]) {
      sym->value = sema_eval(S, scope, ast_kid(bound[k], 0));   /* in the caller's scope */
      if (sym->value.kind == VAL_WORD) {
        sema_report_unknown(S, scope, sym->value.word, sym->value.loc, "name");
        sym->value = val_error();
      }
    } else if (f->nkid) {
      sym->value = sema_eval(S, inner, f->kid[0]);
    } else {
      diag_error(it->loc, "'%s' needs a value for parameter '%s' (it has no default)",
                 comp->name, f->name);
      sym->value = val_error();
    }
  }
  declare_items(S, inner, def, 1);
  sema_items(S, inner, def, 1);
  comp->state = 0;
  diag_pop_context();
  S->instance_depth--;
}

/* A loop without a pass still names what it would use: those names are not
 * "defined but never used" (a lever or a material kept for a scene
 * variant that `--let` leaves out).  Only the first part of a dotted name
 * is looked up; a name the loop defines itself is not found, and nothing
 * is reported. */
static void mark_names_used(swSema *S, swScope *scope, const swAst *node) {
  if (!node) return;
  if (node->kind == AST_NAME && node->name) {
    char head[256];
    size_t n = strcspn(node->name, ".[");
    if (n < sizeof head) {
      memcpy(head, node->name, n);
      head[n] = 0;
      swSymbol *sym = sema_lookup(S, scope, head);
      if (sym) sym->used = 1;
    }
  }
  for (int i = 0; i < node->nkid; i++) mark_names_used(S, scope, node->kid[i]);
}

/* for NAME[VAR] in (FIRST, LAST) { items }: the items once for each whole VAR
 * from FIRST to LAST, each pass an instance of its own named NAME[VAR] (its
 * rods NAME[3].barb ...) whose scope sees the enclosing one, with VAR a
 * plain number there.  The passes count against the expansion bound as a
 * component's instances do. */
static void run_loop(swSema *S, swScope *scope, const swAst *it) {
  swSymbol *loop = sema_lookup_local(scope, it->name);
  if (!loop || loop->def != it) return;   /* declaration failed */
  loop->state = 2;
  loop->used = 1;
  swValue r = sema_eval(S, scope, it->kid[0]);
  if (r.kind == VAL_WORD) {
    sema_report_unknown(S, scope, r.word, r.loc, "name");
    return;
  }
  if (r.kind == VAL_ERROR) return;
  if (r.kind != VAL_VEC || r.n != 2 || !dim_is_none(r.dim) || !val_is_const(&r) ||
      r.v[0] != floor(r.v[0]) || r.v[1] != floor(r.v[1]) || fabs(r.v[0]) > 1e9 ||
      fabs(r.v[1]) > 1e9) {
    diag_error(r.loc, "a loop runs over whole numbers known when compiling, its first and last: "
               "for %s[%s] in (0, 9) { ... }", it->name, it->text);
    return;
  }
  const long first = (long)r.v[0], last = (long)r.v[1];
  /* (1, 0): a count of none, as `for hurt[k] in (1, injured)` with injured
   * = 0 writes it, is a loop without a pass and says nothing; a LAST further
   * below FIRST is more likely a slip. */
  if (last < first) {
    mark_names_used(S, scope, it);
    if (last < first - 1)
      diag_warning(r.loc, "loop '%s' runs from %ld to %ld: no pass", it->name, first, last);
    return;
  }
  const long n = last - first + 1;
  if (S->nexpanded + n * (it->nkid - 1) > SEMA_MAX_EXPANDED) {
    diag_error(it->loc, "loop '%s' expands to %ld definitions and statements; the model may have "
               "at most %d", it->name, n * (it->nkid - 1), SEMA_MAX_EXPANDED);
    S->nexpanded = SEMA_MAX_EXPANDED + 1;
    return;
  }
  S->nexpanded += (int)(n * (it->nkid - 1));
  loop->first_pass = (int)first;
  loop->npass = (int)n;
  loop->pass = ast_alloc(S->a, (size_t)n * sizeof *loop->pass);
  for (long k = 0; k < n && !diag_stopped(); k++) {
    char name[256];
    snprintf(name, sizeof name, "%s[%ld]", it->name, first + k);
    size_t plen = strlen(scope->prefix) + strlen(name) + 2;
    char *prefix = ast_alloc(S->a, plen);
    snprintf(prefix, plen, "%s%s.", scope->prefix, name);
    swSymbol *pass = ast_alloc(S->a, sizeof *pass);
    pass->kind = SYM_INSTANCE;
    pass->name = ast_strdup(S->a, name, strlen(name));
    pass->full = ast_strdup(S->a, prefix, plen - 2);
    pass->loc = it->loc;
    pass->def = it;
    pass->scope = scope;
    pass->state = 2;
    pass->used = 1;
    pass->members = sema_scope_new(S, scope, prefix);
    loop->pass[k] = pass;
    swSymbol *var = sema_declare(S, pass->members, SYM_LET, it->text, it->loc, it);
    if (var) {
      var->value = val_num(S->a, (double)(first + k), DIM_NONE, it->loc);
      var->state = 2;
      var->used = 1;
    }
    diag_push_context(it->loc, "in pass %s = %ld of loop '%s'", it->text, first + k, it->name);
    declare_items(S, pass->members, it, 1);
    sema_items(S, pass->members, it, 1);
    diag_pop_context();
  }
}

void sema_items(swSema *S, swScope *scope, const swAst *items, int first) {
  /* past the error limit nothing more is reported: the rest is not checked
   * (a model whose components expand into tens of thousands of errors took
   * 0.1-0.2 s to count them) */
  for (int i = first; i < items->nkid && !diag_stopped(); i++) {
    const swAst *it = items->kid[i];
    if (S->defs_only && scene_statement(it)) continue;
    switch (it->kind) {
    case AST_PARAM:
    case AST_LET:
    case AST_DEF: {
      if (it->kind == AST_DEF && sema_is_env_kind(it->text)) {
        swSymbol *sym = it->name ? sema_lookup_local(scope, it->name) : NULL;
        if (!it->name || (sym && sym->def == it)) {
          if (sym) sym->used = 1;
          sema_env(S, scope, it);
        }
        break;
      }
      if (!it->name) break;
      swSymbol *sym = sema_lookup_local(scope, it->name);
      if (sym && sym->def == it) sema_eval_symbol(S, sym);
      break;
    }
    case AST_JOINT: {
      swSymbol *sym = sema_lookup_local(scope, it->name);
      if (sym && sym->def == it) sema_joint(S, scope, it);
      break;
    }
    case AST_USE:
      instantiate(S, scope, it);
      break;
    case AST_FOR:
      run_loop(S, scope, it);
      break;
    case AST_ACTION:
      if (sema_action_until(it) && (sema_is_signal_def(it) || sema_is_objective_word(it->text)))
        sema_until_misplaced(it);
      else if (sema_is_signal_def(it)) sema_signal_def(S, scope, it);
      else if (sema_is_objective_word(it->text)) sema_objective_later(S, scope, it);
      else sema_action(S, scope, it);
      break;
    case AST_SIMULATE:
      sema_simulate(S, scope, it);
      break;
    case AST_OUTPUT:
      sema_output(S, scope, it);
      break;
    case AST_EXPECT:
      sema_expectation_later(S, scope, it);
      break;
    default:
      break;
    }
  }
}

/* A runnable scene: a file with 'simulate' or 'output'. */
static int is_scene(const swAst *root) {
  for (int i = 0; i < root->nkid; i++)
    if (root->kid[i]->kind == AST_SIMULATE || root->kid[i]->kind == AST_OUTPUT) return 1;
  return 0;
}

/* The items of a file, into `scope` (the global scope or a namespace's).  An
 * imported runnable scene gives its definitions only. */
void sema_check_file(swSema *S, int file, swScope *scope) {
  swAst *root = parse_file(S->a, file);
  if (!root) return;
  if (S->import_depth < SEMA_MAX_IMPORT_DEPTH) {
    S->import_stack[S->import_depth] = file;
    S->import_depth++;
  }
  int outer = S->defs_only;
  S->defs_only = file != S->main_file && is_scene(root);
  declare_items(S, scope, root, 0);
  sema_items(S, scope, root, 0);
  S->defs_only = outer;
  S->import_depth--;
}


/* Definitions never used, in a scene (a file with 'simulate'): a library of
 * materials and components exists to be imported, and after an error the
 * uses that failed would make false reports. */
static void warn_unused(swSema *S) {
  if (!S->has_simulate || diag_errors()) return;
  for (int i = 0; i < S->nall; i++) {
    swSymbol *s = S->all[i];
    if (s->used || !s->main_file) continue;
    if (s->kind == SYM_PARAM || s->kind == SYM_LET || s->kind == SYM_MATERIAL ||
        s->kind == SYM_COMPONENT || s->kind == SYM_SIGNAL)
      diag_warning(s->loc, "%s '%s' is defined but never used", sema_sym_noun(s->kind), s->name);
  }
}

/* An override of sinewc --let that met no top-level let of the main file:
 * what the name is instead, or the nearest let's name, or the lets there are. */
static void let_not_found(swSema *S, swLetOverride *o) {
  const char *main_path = diag_file(S->main_file)->path;
  char msg[1024], where[256];
  swSymbol *g = sema_lookup_local(S->global, o->name), *inner = NULL;
  for (int i = 0; i < S->nall && !g && !inner; i++)
    if ((S->all[i]->kind == SYM_LET || S->all[i]->kind == SYM_FORMAL) &&
        !strcmp(S->all[i]->name, o->name))
      inner = S->all[i];
  if (g && g->kind == SYM_PARAM)
    snprintf(msg, sizeof msg, "--let %s: '%s' is a param, not a let: the simulator sets it when "
             "it runs (SIM --set %s=VALUE)", o->name, o->name, o->name);
  else if (g)
    snprintf(msg, sizeof msg, "--let %s: '%s' is %s of %s, not a top-level let of %s",
             o->name, o->name, sema_sym_a_noun(g->kind), diag_where(g->loc, where, sizeof where),
             main_path);
  else if (inner)
    snprintf(msg, sizeof msg, "--let %s: '%s' is %s inside component instance '%.*s' (%s), "
             "not a top-level let of %s", o->name, o->name, sema_sym_a_noun(inner->kind),
             (int)strlen(inner->scope->prefix) - 1, inner->scope->prefix,
             diag_where(inner->loc, where, sizeof where), main_path);
  else {
    enum { MAXC = 512 };
    const char *cands[MAXC];
    int n = 0;
    for (int i = 0; i < S->global->n && n < MAXC; i++)
      if (S->global->sym[i]->kind == SYM_LET && S->global->sym[i]->main_file)
        cands[n++] = S->global->sym[i]->name;
    const char *near = diag_suggest(o->name, cands, n);
    if (near)
      snprintf(msg, sizeof msg, "--let: unknown let '%s' (did you mean '%s'?)", o->name, near);
    else if (!n)
      snprintf(msg, sizeof msg, "--let: unknown let '%s' (%s has no top-level lets)", o->name,
               main_path);
    else {
      char list[512];
      diag_join(list, sizeof list, cands, n);
      snprintf(msg, sizeof msg, "--let: unknown let '%s' (the lets of %s: %s)", o->name,
               main_path, list);
    }
  }
  o->error = ast_strdup(S->a, msg, strlen(msg));
}

/* The model source records the overrides after the files, so the output's
 * model_source (and model_sha256, its hash) tell what was compiled. */
static void record_lets(swSema *S) {
  char line[1024];
  int n = snprintf(line, sizeof line, "\n# ---- sinewc --let: lets of %s given on the command "
                   "line ----\n", diag_file(S->main_file)->name);
  sema_append_source(S, line, (size_t)n);
  for (int i = 0; i < S->nlets; i++) {
    n = snprintf(line, sizeof line, "# --let %s (in place of the let at line %d)\n",
                 S->lets[i].text, S->lets[i].let_loc.line);
    sema_append_source(S, line, (size_t)n);
  }
}

int sema_check(swArena *arena, int file, swScene *scene) {
  return sema_check_lets(arena, file, NULL, 0, scene);
}

int sema_check_lets(swArena *arena, int file, swLetOverride *lets, int nlets, swScene *scene) {
  swSema S;
  memset(&S, 0, sizeof S);
  memset(scene, 0, sizeof *scene);
  S.a = arena;
  S.scene = scene;
  S.main_file = file;
  S.lets = lets;
  S.nlets = nlets;
  S.global = sema_scope_new(&S, NULL, "");
  S.global->file_level = 1;
  scene->integrator = SW_VERLET;
  scene->gravity = val_error();
  const swSource *src = diag_file(file);
  char canon[PATH_MAX];
  if (realpath(src->path, canon)) {
    sema_mark_done(&S, canon);                               /* its text is in the source */
    sema_mark_done(&S, sema_done_key(&S, S.global, canon));  /* and its items are global's */
  }
  sema_append_source(&S, src->text, src->len);
  /* the model's name: the file's stem */
  const char *base = strrchr(src->path, '/');
  base = base ? base + 1 : src->path;
  const char *dot = strrchr(base, '.');
  scene->model_name = ast_strdup(arena, base, dot && dot != base ? (size_t)(dot - base) : strlen(base));
  int before = diag_errors();
  sema_check_file(&S, file, S.global);
  sema_output_selections(&S);
  sema_expectations(&S);
  sema_objectives(&S);
  warn_unused(&S);
  /* the times a signal's range is sampled over: the run's (sw_signal_func) */
  for (int i = 0; i < scene->nsignal; i++)
    scene->signal[i]->span = scene->duration > 0 ? scene->duration : 1.0;
  sema_swell_check(&S);   /* the radius signals over the run */
  int lets_ok = 1;
  for (int i = 0; i < nlets; i++) {
    /* after the model's own errors a let may not have been reached */
    if (!lets[i].applied && !lets[i].error && diag_errors() == before) let_not_found(&S, &lets[i]);
    if (!lets[i].applied || lets[i].error) lets_ok = 0;
  }
  if (nlets && lets_ok) {
    record_lets(&S);
    scene->let = lets;
    scene->nlet = nlets;
  }
  scene->source = S.src;
  sha256_hex(S.src ? S.src : "", S.srclen, scene->sha256);
  for (int i = 0; i < S.ndone; i++) free(S.done_paths[i]);
  free(S.done_paths);
  free(S.expects.item);
  free(S.expects.scope);
  free(S.objectives.item);
  free(S.objectives.scope);
  free(S.bad_probe);
  return diag_errors() - before;
}

void sema_scene_free(swScene *scene) {
  free(scene->source);
  free(scene->rod);
  free(scene->act);
  free(scene->joint);
  free(scene->kin);
  free(scene->param);
  free(scene->derived);
  free(scene->muscle);
  free(scene->passive);
  free(scene->ground);
  free(scene->fluid);
  free(scene->contact);
  free(scene->obstacle);
  free(scene->wave);
  free(scene->probe);
  free(scene->expect);
  free(scene->select);
  memset(scene, 0, sizeof *scene);
}
