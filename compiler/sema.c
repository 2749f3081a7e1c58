/* sema.c — the checker's driver: scopes, names, imports, components, and the
 * walk over a file's items.
 *
 * Design.  Names live in scopes: the file scope (shared by a file and every
 * file it imports, so an imported arm model's bones can be clamped by the
 * scene) and one scope per component instance, whose parent is the scope the
 * component was defined in (lexical scoping) and whose names are reached from
 * outside as members (left.humerus).  Items are walked twice: first every
 * name is declared, so definitions may refer to each other in any order; then
 * everything is evaluated in file order, definitions lazily on first use (see
 * sema_def.c).  An import is read, parsed and fully checked where it stands;
 * a file is read once however often it is imported, and a file that imports
 * itself through a chain is an error naming the chain.  Imports resolve
 * relative to the importing file, then along SINEW_PATH, then in the models
 * shipped with sinew (models/ of the tree, or share/sinew/models installed).  The model source
 * recorded in the output is the main file followed by each imported file,
 * each introduced by a comment line naming it.
 */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lex.h"
#include "sema_int.h"

#define MAX_SOURCE_BYTES (16 << 20)

/* ---- scopes ---- */

static swScope *scope_new(swSema *S, swScope *parent, const char *prefix) {
  swScope *sc = ast_alloc(S->a, sizeof *sc);
  sc->parent = parent;
  sc->prefix = prefix;
  return sc;
}

swSymbol *sema_lookup_local(swScope *scope, const char *name) {
  for (int i = 0; scope && i < scope->n; i++)
    if (!strcmp(scope->sym[i]->name, name)) return scope->sym[i];
  return NULL;
}

swSymbol *sema_lookup(swSema *S, swScope *scope, const char *name) {
  (void)S;
  for (swScope *sc = scope; sc; sc = sc->parent) {
    swSymbol *sym = sema_lookup_local(sc, name);
    if (sym) return sym;
  }
  return NULL;
}

void sema_report_unknown(swSema *S, swScope *scope, const char *name, swLoc loc,
                         const char *what) {
  enum { MAXC = 512 };
  const char *cands[MAXC] = {0};
  int n = 0;
  for (swScope *sc = scope; sc; sc = sc->parent)
    for (int i = 0; i < sc->n && n < MAXC; i++) cands[n++] = sc->sym[i]->name;
  /* a value may also be one of the words that are values of their own */
  if (!strcmp(what, "name") && n + 2 <= MAXC) {
    cands[n++] = "true";
    cands[n++] = "false";
  }
  const char *near = diag_suggest(name, cands, n);
  /* the suggested definition is what the user meant: do not also call it unused */
  if (near) {
    swSymbol *meant = sema_lookup(S, scope, near);
    if (meant) meant->used = 1;
  }
  if (near) {
    diag_error(loc, "unknown %s '%s'; did you mean '%s'?", what, name, near);
  } else if (S->failed_import) {   /* the cause is more likely the import */
    char where[300];
    const swLoc at = S->failed_import->loc;
    if (at.file == loc.file) snprintf(where, sizeof where, "line %d", at.line);
    else diag_name_where(at, where, sizeof where);
    diag_error(loc, "unknown %s '%s' (perhaps defined in \"%s\", which could not be imported "
               "at %s)", what, name, S->failed_import->text, where);
  } else {
    diag_error(loc, "unknown %s '%s'", what, name);
  }
}

const char *sema_sym_noun(swSymKind k) {
  static const char *nouns[] = {"param", "let", "component parameter", "material", "rod",
                                "joint", "component", "instance", "muscle", "environment"};
  return nouns[k];
}

static swSymbol *declare(swSema *S, swScope *scope, swSymKind kind, const char *name, swLoc loc,
                         const swAst *def) {
  swSymbol *old = sema_lookup_local(scope, name);
  if (old) {
    char where[256];
    diag_error(loc, "'%s' is already defined (as a %s at %s)", name, sema_sym_noun(old->kind),
               diag_where(old->loc, where, sizeof where));
    return NULL;
  }
  if (!strcmp(name, "pi") || !strcmp(name, "all") || !strcmp(name, "true") ||
      !strcmp(name, "false")) {
    diag_error(loc, "'%s' is a reserved name", name);
    return NULL;
  }
  swSymbol *sym = ast_alloc(S->a, sizeof *sym);
  sym->kind = kind;
  sym->name = name;
  size_t plen = strlen(scope->prefix), nlen = strlen(name);
  char *full = ast_alloc(S->a, plen + nlen + 1);
  memcpy(full, scope->prefix, plen);
  memcpy(full + plen, name, nlen + 1);
  sym->full = full;
  sym->loc = loc;
  sym->def = def;
  sym->scope = scope;
  sym->index = -1;
  sym->main_file = loc.file == S->main_file && S->instance_depth == 0;
  if (scope->n == scope->cap) {
    int cap = scope->cap ? 2 * scope->cap : 8;
    swSymbol **syms = ast_alloc(S->a, (size_t)cap * sizeof *syms);
    if (scope->n) memcpy(syms, scope->sym, (size_t)scope->n * sizeof *syms);
    scope->sym = syms;
    scope->cap = cap;
  }
  scope->sym[scope->n++] = sym;
  if (S->nall == S->capall) {
    int cap = S->capall ? 2 * S->capall : 32;
    swSymbol **all = ast_alloc(S->a, (size_t)cap * sizeof *all);
    if (S->nall) memcpy(all, S->all, (size_t)S->nall * sizeof *all);
    S->all = all;
    S->capall = cap;
  }
  S->all[S->nall++] = sym;
  return sym;
}

/* ---- files and imports ---- */

static void append_source(swSema *S, const char *text, size_t len) {
  if (S->srclen + len + 1 > S->srccap) {
    size_t cap = S->srccap ? S->srccap : 4096;
    while (cap < S->srclen + len + 1) cap *= 2;
    char *p = realloc(S->src, cap);
    if (!p) abort();
    S->src = p;
    S->srccap = cap;
  }
  memcpy(S->src + S->srclen, text, len);
  S->srclen += len;
  S->src[S->srclen] = 0;
}

/* Read a whole model file; NULL and a reason when it cannot (*not_text set
 * when the file was read but holds NUL bytes).  Used for imports and, by
 * sinewc, for the model itself. */
char *sema_read_file(const char *path, size_t *len, const char **why, int *not_text) {
  *not_text = 0;
  struct stat st;
  if (stat(path, &st) != 0) {
    *why = strerror(errno);
    return NULL;
  }
  if (S_ISDIR(st.st_mode)) {
    *why = "it is a directory";
    return NULL;
  }
  if (!S_ISREG(st.st_mode)) {   /* a FIFO or /dev/stdin would hang the compiler */
    *why = "it is not a regular file";
    return NULL;
  }
  FILE *f = fopen(path, "rb");
  if (!f) {
    *why = strerror(errno);
    return NULL;
  }
  size_t cap = 4096, n = 0;
  char *buf = malloc(cap);
  for (;;) {
    if (n == cap) {
      if (cap >= MAX_SOURCE_BYTES) {
        free(buf);
        fclose(f);
        *why = "it is larger than 16 MiB";
        return NULL;
      }
      cap *= 2;
      buf = realloc(buf, cap);
    }
    size_t got = fread(buf + n, 1, cap - n, f);
    n += got;
    if (got == 0) break;
  }
  int bad = ferror(f);
  fclose(f);
  if (bad) {
    free(buf);
    *why = "read error";
    return NULL;
  }
  if (memchr(buf, 0, n)) {
    free(buf);
    *not_text = 1;
    *why = "it contains NUL bytes (not a text file)";
    return NULL;
  }
  *len = n;
  return buf;
}

static int already_done(swSema *S, const char *canon) {
  for (int i = 0; i < S->ndone; i++)
    if (!strcmp(S->done_paths[i], canon)) return 1;
  return 0;
}

static void mark_done(swSema *S, const char *canon) {
  if (S->ndone == S->capdone) {
    S->capdone = S->capdone ? 2 * S->capdone : 8;
    S->done_paths = realloc(S->done_paths, (size_t)S->capdone * sizeof *S->done_paths);
    if (!S->done_paths) abort();
  }
  S->done_paths[S->ndone++] = strdup(canon);
}

static void check_file(swSema *S, int file, swScope *scope);

/* A file imported into a scope: "PREFIX\x1fPATH" (the global scope's prefix
 * is ""), so a file imported under two namespaces is read into each. */
static const char *done_key(swSema *S, const swScope *scope, const char *canon) {
  size_t n = strlen(scope->prefix) + strlen(canon) + 2;
  char *key = ast_alloc(S->a, n);
  snprintf(key, n, "%s\x1f%s", scope->prefix, canon);
  return key;
}

/* Candidate path for `name` imported from file `from`: its directory first. */
static int resolve_import(const char *from, const char *name, char *out, size_t len) {
  struct stat st;
  if (name[0] == '/') {
    snprintf(out, len, "%s", name);
    return stat(out, &st) == 0;
  }
  const char *slash = strrchr(from, '/');
  if (slash) snprintf(out, len, "%.*s/%s", (int)(slash - from), from, name);
  else snprintf(out, len, "%s", name);
  if (stat(out, &st) == 0) return 1;
  const char *path = getenv("SINEW_PATH");
  while (path && *path) {
    const char *colon = strchr(path, ':');
    size_t n = colon ? (size_t)(colon - path) : strlen(path);
    if (n) {
      snprintf(out, len, "%.*s/%s", (int)n, path, name);
      if (stat(out, &st) == 0) return 1;
    }
    path = colon ? colon + 1 : NULL;
  }
  /* the models shipped with sinew: the source tree's models/ or the
   * installed share/sinew/models, found from the compiler's own place */
  char exe[PATH_MAX];
  ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) {
    exe[n] = 0;
    char *cut = strrchr(exe, '/');
    if (cut) {
      *cut = 0;
      static const char *dirs[] = {"/../models", "/../share/sinew/models", "/../../models"};
      for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        if (snprintf(out, len, "%s%s/%s", exe, dirs[i], name) >= (int)len) continue;
        if (stat(out, &st) == 0) return 1;
      }
    }
  }
  return 0;
}

static void do_import(swSema *S, const swAst *item, swScope *scope) {
  const swSource *from = diag_file(item->loc.file);
  const char *name = item->text;
  if (!name[0]) {
    diag_error(item->loc, "import needs a file name");
    return;
  }
  char path[PATH_MAX];
  if (!resolve_import(from->path, name, path, sizeof path)) {
    diag_error(item->loc, "cannot find \"%s\" (looked next to %s%s)", name, from->path,
               getenv("SINEW_PATH") ? " and along SINEW_PATH" : "; SINEW_PATH is not set");
    if (!S->failed_import) S->failed_import = item;
    return;
  }
  char canon[PATH_MAX];
  if (!realpath(path, canon)) snprintf(canon, sizeof canon, "%s", path);
  /* a cycle: the file is on the stack of files being imported */
  for (int i = 0; i < S->import_depth; i++) {
    const swSource *f = diag_file(S->import_stack[i]);
    char c2[PATH_MAX];
    if (f && realpath(f->path, c2) && !strcmp(c2, canon)) {
      char chain[2048] = "";
      for (int k = i; k < S->import_depth; k++) {
        const swSource *fk = diag_file(S->import_stack[k]);
        strncat(chain, fk ? fk->path : "?", sizeof chain - strlen(chain) - 1);
        strncat(chain, " -> ", sizeof chain - strlen(chain) - 1);
      }
      strncat(chain, path, sizeof chain - strlen(chain) - 1);
      diag_error(item->loc, "import cycle: %s", chain);
      return;
    }
  }
  /* import "f" as ns: the file's definitions in a scope of their own, named
   * ns.x and reached through the instance-like symbol ns */
  if (item->name) {
    swSymbol *ns = sema_lookup_local(scope, item->name);
    if (!ns || ns->def != item) return;   /* the name clashed (reported) */
    size_t plen = strlen(scope->prefix) + strlen(item->name) + 2;
    char *prefix = ast_alloc(S->a, plen);
    snprintf(prefix, plen, "%s%s.", scope->prefix, item->name);
    swScope *inner = scope_new(S, NULL, prefix);
    inner->file_level = 1;
    ns->members = inner;
    ns->state = 2;
    scope = inner;
  }
  const char *key = done_key(S, scope, canon);
  if (already_done(S, key)) return;
  if (S->import_depth >= SEMA_MAX_IMPORT_DEPTH) {
    diag_error(item->loc, "imports are nested more than %d deep", SEMA_MAX_IMPORT_DEPTH);
    return;
  }
  size_t len;
  const char *why;
  int not_text;
  char *text = sema_read_file(path, &len, &why, &not_text);
  if (!text) {
    diag_error(item->loc, "cannot read \"%s\": %s", path, why);
    return;
  }
  mark_done(S, key);
  int file = diag_add_file(path, text, len);
  /* the import as written, not where it was found: the model's source, and
   * its hash, are the same wherever sinewc runs and is installed */
  diag_set_name(file, name);
  if (!already_done(S, canon)) {   /* its text once, however often imported */
    mark_done(S, canon);
    char header[PATH_MAX + 64];
    int hl = snprintf(header, sizeof header, "\n# ---- imported: %s ----\n", name);
    append_source(S, header, (size_t)hl);
    append_source(S, text, len);
  }
  free(text);
  check_file(S, file, scope);
}

/* ---- items ---- */

static const char *const def_kinds[] = {"material", "rod", "bone", "tendon", "muscle",
                                        "ground", "terrain", "fluid", "contact", "torque_wave"};

/* A scene statement, which a runnable scene imported for its definitions
 * keeps to itself: an action (clamp, gravity, force, activate ...),
 * simulate, output, expect, use, and the environments. */
static int scene_statement(const swAst *it) {
  return it->kind == AST_ACTION || it->kind == AST_SIMULATE || it->kind == AST_OUTPUT ||
         it->kind == AST_EXPECT || it->kind == AST_USE ||
         (it->kind == AST_DEF && sema_is_env_kind(it->text));
}

static void declare_items(swSema *S, swScope *scope, const swAst *items, int first) {
  for (int i = first; i < items->nkid; i++) {
    const swAst *it = items->kid[i];
    if (S->defs_only && scene_statement(it)) continue;
    switch (it->kind) {
    case AST_IMPORT:
      if (!scope->file_level) {
        diag_error(it->loc, "import is only allowed at the top of a file, not in a component");
      } else {
        if (it->name) {   /* the namespace: its uses fail quietly if the file does */
          swSymbol *ns = declare(S, scope, SYM_INSTANCE, it->name, it->loc, it);
          if (!ns) break;
          ns->state = 2;
          ns->used = 1;
        }
        do_import(S, it, scope);
      }
      break;
    case AST_PARAM:
      if (!scope->file_level) {
        diag_error(it->loc, "a param belongs at file level; a component takes parameters "
                   "in its header: component NAME(%s = ...)", it->name);
        /* declared as a let all the same, so its uses are not also unknown */
        declare(S, scope, SYM_LET, it->name, it->loc, it);
        break;
      }
      declare(S, scope, SYM_PARAM, it->name, it->loc, it);
      break;
    case AST_LET:
      declare(S, scope, SYM_LET, it->name, it->loc, it);
      break;
    case AST_DEF: {
      int k;
      if (sema_is_env_kind(it->text)) {   /* ground, terrain, fluid, contact, torque_wave */
        if (it->name) declare(S, scope, SYM_ENV, it->name, it->loc, it);
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
      declare(S, scope, k == 0 ? SYM_MATERIAL : k == 4 ? SYM_MUSCLE : SYM_ROD, it->name, it->loc,
              it);
      break;
    }
    case AST_JOINT:
      declare(S, scope, SYM_JOINT, it->name, it->loc, it);
      break;
    case AST_COMPONENT:
      if (!scope->file_level) {
        diag_error(it->loc, "components cannot be defined inside components");
        break;
      }
      declare(S, scope, SYM_COMPONENT, it->name, it->loc, it);
      break;
    case AST_USE:
      declare(S, scope, SYM_INSTANCE, it->name, it->loc, it);
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
  if (ns->kind != SYM_INSTANCE || !ns->members) {
    diag_error(loc, "'%s' is a %s, not an imported namespace or an instance", head,
               sema_sym_noun(ns->kind));
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
    diag_error(it->loc, "'%s' is a %s, not a component", it->text, sema_sym_noun(comp->kind));
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
  swScope *inner = scope_new(S, comp->scope, prefix);
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
    swSymbol *sym = declare(S, inner, SYM_FORMAL, f->name, f->loc, f);
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

void sema_items(swSema *S, swScope *scope, const swAst *items, int first) {
  for (int i = first; i < items->nkid; i++) {
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
    case AST_ACTION:
      if (sema_is_objective_word(it->text)) sema_objective_later(S, scope, it);
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
static void check_file(swSema *S, int file, swScope *scope) {
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
        s->kind == SYM_COMPONENT)
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
    snprintf(msg, sizeof msg, "--let %s: '%s' is a %s of %s, not a top-level let of %s",
             o->name, o->name, sema_sym_noun(g->kind), diag_where(g->loc, where, sizeof where),
             main_path);
  else if (inner)
    snprintf(msg, sizeof msg, "--let %s: '%s' is a %s inside component instance '%.*s' (%s), "
             "not a top-level let of %s", o->name, o->name, sema_sym_noun(inner->kind),
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
  append_source(S, line, (size_t)n);
  for (int i = 0; i < S->nlets; i++) {
    n = snprintf(line, sizeof line, "# --let %s (in place of the let at line %d)\n",
                 S->lets[i].text, S->lets[i].let_loc.line);
    append_source(S, line, (size_t)n);
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
  S.global = scope_new(&S, NULL, "");
  S.global->file_level = 1;
  scene->integrator = SW_VERLET;
  scene->gravity = val_error();
  const swSource *src = diag_file(file);
  char canon[PATH_MAX];
  if (realpath(src->path, canon)) {
    mark_done(&S, canon);                          /* its text is in the source */
    mark_done(&S, done_key(&S, S.global, canon));  /* and its items are global's */
  }
  append_source(&S, src->text, src->len);
  /* the model's name: the file's stem */
  const char *base = strrchr(src->path, '/');
  base = base ? base + 1 : src->path;
  const char *dot = strrchr(base, '.');
  scene->model_name = ast_strdup(arena, base, dot && dot != base ? (size_t)(dot - base) : strlen(base));
  int before = diag_errors();
  check_file(&S, file, S.global);
  sema_output_selections(&S);
  sema_expectations(&S);
  sema_objectives(&S);
  warn_unused(&S);
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
  free(scene->param);
  free(scene->derived);
  free(scene->muscle);
  free(scene->passive);
  free(scene->ground);
  free(scene->fluid);
  free(scene->contact);
  free(scene->wave);
  free(scene->probe);
  free(scene->expect);
  free(scene->select);
  memset(scene, 0, sizeof *scene);
}
