/* sema_import.c — files and imports: reading a model file, finding and
 * reading an imported one, and the model source recorded in the output.
 *
 * Design.  An import is read, parsed and fully checked where it stands (the
 * walk over its items is the driver's, sema_check_file in sema.c); a file is
 * read once however often it is imported, and a file that imports itself
 * through a chain is an error naming the chain.  Imports resolve relative to
 * the importing file, then along SINEW_PATH, then in the models shipped with
 * sinew (models/ of the tree, or share/sinew/models installed).  The model
 * source recorded in the output is the main file followed by each imported
 * file, each introduced by a comment line naming it.  Apart from the driver
 * because all of it is about files, paths and text, none about the items.
 */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sema_int.h"

#define MAX_SOURCE_BYTES (16 << 20)

/* ---- files and imports ---- */

void sema_append_source(swSema *S, const char *text, size_t len) {
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

void sema_mark_done(swSema *S, const char *canon) {
  if (S->ndone == S->capdone) {
    S->capdone = S->capdone ? 2 * S->capdone : 8;
    S->done_paths = realloc(S->done_paths, (size_t)S->capdone * sizeof *S->done_paths);
    if (!S->done_paths) abort();
  }
  S->done_paths[S->ndone++] = strdup(canon);
}

/* A file imported into a scope: "PREFIX\x1fPATH" (the global scope's prefix
 * is ""), so a file imported under two namespaces is read into each. */
const char *sema_done_key(swSema *S, const swScope *scope, const char *canon) {
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

void sema_import(swSema *S, const swAst *item, swScope *scope) {
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
    swScope *inner = sema_scope_new(S, NULL, prefix);
    inner->file_level = 1;
    ns->members = inner;
    ns->state = 2;
    scope = inner;
  }
  const char *key = sema_done_key(S, scope, canon);
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
  sema_mark_done(S, key);
  int file = diag_add_file(path, text, len);
  /* the import as written, not where it was found: the model's source, and
   * its hash, are the same wherever sinewc runs and is installed */
  diag_set_name(file, name);
  if (!already_done(S, canon)) {   /* its text once, however often imported */
    sema_mark_done(S, canon);
    char header[PATH_MAX + 64];
    int hl = snprintf(header, sizeof header, "\n# ---- imported: %s ----\n", name);
    sema_append_source(S, header, (size_t)hl);
    sema_append_source(S, text, len);
  }
  free(text);
  sema_check_file(S, file, scope);
}
