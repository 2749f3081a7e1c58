/* sema_scope.c — scopes and names: an empty scope, declaring a name in one,
 * looking a name up, and the message for an unknown name.
 *
 * Design.  Names live in scopes: the file scope (shared by a file and every
 * file it imports, so an imported arm model's bones can be clamped by the
 * scene) and one scope per component instance, whose parent is the scope the
 * component was defined in (lexical scoping) and whose names are reached from
 * outside as members (left.humerus).  A name is declared once per scope, with
 * its full name (the scope's prefix and the name), and recorded in the list
 * of every symbol, for "never used" warnings.  Kept apart from the driver
 * (sema.c), which declares the names, because every part of the checker looks
 * them up.
 */
#include <stdio.h>
#include <string.h>

#include "sema_int.h"

/* ---- scopes ---- */

swScope *sema_scope_new(swSema *S, swScope *parent, const char *prefix) {
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

/* Instances' members (and theirs, three levels down) called `name`, of kind
 * `kind` (-1: any), by their full names ("right.extensor"), for a hint where
 * a bare name is unknown but an instance holds it. */
static int members_named(const swScope *sc, const char *name, int kind, const char **out, int n,
                         int max, int depth) {
  for (int i = 0; sc && i < sc->n && n < max; i++) {
    const swSymbol *s = sc->sym[i];
    if (s->kind != SYM_INSTANCE || !s->members) continue;
    const swSymbol *m = sema_lookup_local(s->members, name);
    if (m && (kind < 0 || (int)m->kind == kind) && m->full) out[n++] = m->full;
    if (depth > 0) n = members_named(s->members, name, kind, out, n, max, depth - 1);
  }
  return n;
}

int sema_members_named(const swScope *scope, const char *name, int kind, const char **out,
                       int max) {
  int n = 0;
  for (const swScope *sc = scope; sc && n < max; sc = sc->parent)
    n = members_named(sc, name, kind, out, n, max, 2);
  return n;
}

/* " did you mean 'right.extensor'?" or " (an instance's: 'left.x', 'right.x')"
 * into buf when instances hold `name`; "" otherwise. */
const char *sema_member_hint(const swScope *scope, const char *name, int kind, char *buf,
                             size_t len) {
  const char *full[4];
  int n = sema_members_named(scope, name, kind, full, 4);
  buf[0] = '\0';
  if (n == 1) snprintf(buf, len, "; did you mean '%s'?", full[0]);
  else if (n > 1) {
    snprintf(buf, len, " (instances hold it: ");
    for (int i = 0; i < n; i++) {
      strncat(buf, "'", len - strlen(buf) - 1);
      strncat(buf, full[i], len - strlen(buf) - 1);
      strncat(buf, i + 1 < n ? "', " : "')", len - strlen(buf) - 1);
    }
  }
  return buf;
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
  char hint[300];
  if (near) {
    diag_error(loc, "unknown %s '%s'; did you mean '%s'?", what, name, near);
  } else if (sema_member_hint(scope, name, -1, hint, sizeof hint)[0]) {
    diag_error(loc, "unknown %s '%s'%s", what, name, hint);
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
                                "joint", "component", "instance", "muscle", "environment",
                                "signal", "loop"};
  return nouns[k];
}

const char *sema_sym_a_noun(swSymKind k) {
  static const char *nouns[] = {"a param", "a let", "a component parameter", "a material",
                                "a rod", "a joint", "a component", "an instance", "a muscle",
                                "an environment", "a signal", "a loop"};
  return nouns[k];
}

swSymbol *sema_declare(swSema *S, swScope *scope, swSymKind kind, const char *name, swLoc loc,
                       const swAst *def) {
  swSymbol *old = sema_lookup_local(scope, name);
  if (old) {
    char where[256];
    diag_error(loc, "'%s' is already defined (as %s at %s)", name, sema_sym_a_noun(old->kind),
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
