/* ast.h — the syntax tree of a sinew model.
 *
 * Design.  One node type for everything (items, fields, expressions), tagged
 * by kind, with a source location, an optional name or text, a number and a
 * growable list of children.  The parser (lang/sinew.y) builds it; the checker
 * (sema_*.c) reads it and never changes it.  Nodes live in one arena per
 * compilation and are freed together.  Every node knows its file, line and
 * column, so every later stage can point at the model text.
 */
#ifndef SINEW_AST_H
#define SINEW_AST_H

#include <stddef.h>

typedef struct {
  int file;                 /* index into the diagnostics file table */
  int line, col;            /* 1-based start                         */
  int end_line, end_col;    /* 1-based, inclusive end column         */
} swLoc;

typedef enum {
  /* items */
  AST_IMPORT,     /* text = path                                        */
  AST_PARAM,      /* name, kid[0] = default, kid[1] = range: ARG (name
                     "in", kid[0] = the pair), or absent                 */
  AST_LET,        /* name, kid[0] = value                               */
  AST_DEF,        /* text = kind word (material, rod, bone, ...), name, kids = body */
  AST_JOINT,      /* name, text = joint kind, kid[0] = ARGS, kids[1..] = body */
  AST_COMPONENT,  /* name, kid[0] = FORMALS, kids[1..] = items          */
  AST_USE,        /* name = instance, text = component, kid[0] = ARGS   */
  AST_FOR,        /* name = loop, text = its variable, kid[0] = range, kids[1..] = items */
  AST_ACTION,     /* text = keyword (clamp, gravity, force, ...), kids = operands */
  AST_SIMULATE,   /* kids = body                                        */
  AST_OUTPUT,     /* text = path, kid[0] = every (or NULL), kids[1..] = body */
  /* body entries */
  AST_FIELD,      /* name = key, kid[0] = value, kid[1] = formals of
                     "key(x, y) = value" (a VEC of names, or one name)  */
  AST_SELECT,     /* name = what, kids = targets                        */
  /* expressions */
  AST_NUM,        /* num                                                */
  AST_STR,        /* text                                               */
  AST_NAME,       /* name                                               */
  AST_UNIT,       /* name = unit spelling                               */
  AST_BINOP,      /* op in + - * / ^, < > l (<=) g (>=) & (and) | (or)  */
  AST_NEG,        /* kid[0]                                             */
  AST_APPLY,      /* juxtaposition "expr unit": kid[0] value, kid[1] unit */
  AST_VEC,        /* kids = components                                  */
  AST_CALL,       /* name = function, kid[0] = ARGS                     */
  AST_MEMBER,     /* kid[0] . name                                      */
  AST_INDEX,      /* kid[0] [ kid[1] ]                                  */
  AST_METHOD,     /* kid[0] . name ( kid[1] = ARGS )                    */
  AST_ARGS,       /* kids = ARG                                         */
  AST_ARG,        /* name = keyword or NULL, kid[0] = value             */
  AST_FORMALS,    /* kids = ARG (name, kid[0] = default or NULL)        */
  AST_CASE,       /* piecewise argument "cond: value": kid[0], kid[1]   */
  AST_FILE,       /* kids = items                                       */
  AST_EXPECT      /* kid[0] = quantity, kids[1..] = ARG (name = word, kid[0]) */
} swAstKind;

typedef struct swAst swAst;
struct swAst {
  swAstKind kind;
  swLoc loc;
  int op;            /* AST_BINOP operator character                      */
  double num;        /* AST_NUM                                           */
  const char *name;  /* identifier (arena)                                */
  const char *text;  /* string literal or keyword (arena)                 */
  int nkid, capkid;
  int damaged;       /* a body (or a definition) that lost a field to a syntax
                        error: its "needs a field" checks stay silent       */
  int depth;         /* levels of the tree from here down: 1 for a leaf    */
  swAst **kid;
};

/* The deepest expression the parser keeps: the checker and the generator
 * walk expressions recursively, and a much deeper one overflows the stack
 * (9000 minus signs in a row crashed sinewc; the fuzzer's sanitizer build,
 * whose frames are larger, crashed from about 1000).  lang/sinew.y reports
 * a deeper one and cuts it off. */
#define AST_MAX_DEPTH 256

/* The arena: every node and string of one compilation. */
typedef struct swArena swArena;
swArena *ast_arena_new(void);
void ast_arena_free(swArena *a);
void *ast_alloc(swArena *a, size_t size);
char *ast_strdup(swArena *a, const char *s, size_t len);

swAst *ast_new(swArena *a, swAstKind kind, swLoc loc);
swAst *ast_push(swArena *a, swAst *parent, swAst *child);   /* returns parent;
                                                               updates its depth */
swAst *ast_kid(const swAst *n, int i);                      /* NULL if absent */
const char *ast_kind_name(swAstKind kind);

/* A location spanning a..b. */
swLoc ast_span(swLoc a, swLoc b);

#endif
