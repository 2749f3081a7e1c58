/* ast.c — arena allocation and construction of syntax-tree nodes.
 *
 * Design.  The arena is a list of large blocks; nothing is freed until the
 * compilation ends, so the parser's error recovery can drop half-built nodes
 * without bookkeeping.  Child lists grow by doubling inside the arena.
 */
#include <stdlib.h>
#include <string.h>

#include "ast.h"

typedef struct swBlock {
  struct swBlock *next;
  size_t used, size;
  max_align_t data[];
} swBlock;

struct swArena {
  swBlock *head;
};

swArena *ast_arena_new(void) {
  return calloc(1, sizeof(swArena));
}

void ast_arena_free(swArena *a) {
  if (!a) return;
  for (swBlock *b = a->head, *next; b; b = next) {
    next = b->next;
    free(b);
  }
  free(a);
}

void *ast_alloc(swArena *a, size_t size) {
  size_t align = sizeof(max_align_t);
  size = (size + align - 1) / align * align;
  swBlock *b = a->head;
  if (!b || b->size - b->used < size) {
    size_t cap = size > 65536 ? size : 65536;
    b = malloc(sizeof *b + cap);
    if (!b) abort();   /* out of memory: nothing sensible to report */
    b->next = a->head;
    b->used = 0;
    b->size = cap;
    a->head = b;
  }
  void *p = (char *)b->data + b->used;
  b->used += size;
  memset(p, 0, size);
  return p;
}

char *ast_strdup(swArena *a, const char *s, size_t len) {
  char *p = ast_alloc(a, len + 1);
  memcpy(p, s, len);
  p[len] = 0;
  return p;
}

swAst *ast_new(swArena *a, swAstKind kind, swLoc loc) {
  swAst *n = ast_alloc(a, sizeof *n);
  n->kind = kind;
  n->loc = loc;
  n->depth = 1;
  return n;
}

swAst *ast_push(swArena *a, swAst *parent, swAst *child) {
  if (!parent) return NULL;
  if (parent->nkid == parent->capkid) {
    int cap = parent->capkid ? 2 * parent->capkid : 4;
    swAst **kid = ast_alloc(a, (size_t)cap * sizeof *kid);
    if (parent->nkid) memcpy(kid, parent->kid, (size_t)parent->nkid * sizeof *kid);
    parent->kid = kid;
    parent->capkid = cap;
  }
  parent->kid[parent->nkid++] = child;
  if (child && child->depth >= parent->depth) parent->depth = child->depth + 1;
  return parent;
}

swAst *ast_kid(const swAst *n, int i) {
  return n && i >= 0 && i < n->nkid ? n->kid[i] : NULL;
}

swLoc ast_span(swLoc a, swLoc b) {
  swLoc l = a;
  if (b.file == a.file &&
      (b.end_line > a.end_line || (b.end_line == a.end_line && b.end_col > a.end_col))) {
    l.end_line = b.end_line;
    l.end_col = b.end_col;
  }
  return l;
}

const char *ast_kind_name(swAstKind kind) {
  static const char *names[] = {
    "import", "param", "let", "definition", "joint", "component", "use", "loop", "statement",
    "simulate", "output", "field", "selection", "number", "string", "name", "unit",
    "operator", "negation", "quantity", "vector", "call", "member", "index", "method call",
    "arguments", "argument", "parameters", "condition", "file", "expect",
  };
  return (unsigned)kind < sizeof names / sizeof names[0] ? names[kind] : "?";
}
