/* lex.h — the state shared by the flex scanner (lang/sinew.l) and the bison
 * parser (lang/sinew.y), and the entry point of parsing.
 *
 * Design.  The scanner is reentrant; everything it needs (file id, line and
 * column, arena, bracket stack) lives in swLexState, passed as flex's "extra"
 * data.  parse_file() runs scanner and parser over one source text and
 * returns its tree; syntax errors are reported through diag and the tree
 * holds whatever the error recovery could keep.
 */
#ifndef SINEW_LEX_H
#define SINEW_LEX_H

#include <stddef.h>
#include "ast.h"
#include "diag.h"

#define LEX_MAX_DEPTH 64

struct swLexState {
  int file;
  int line, col;
  swArena *arena;
  void *buffer;                 /* flex buffer state                       */
  int depth;                    /* open brackets                           */
  char open[LEX_MAX_DEPTH];
  swLoc open_loc[LEX_MAX_DEPTH];
  swAst *root;                  /* the parser's result                     */
  const char *last_unit;        /* spelling of the last UNIT token          */
  int cur_unit, prev_unit;      /* this token / the one before is a UNIT    */
  int cur_value, prev_value;    /* this token / the one before ends a value
                                   (a number or ')'), where a unit may follow */
  swLoc cur_loc, prev_loc;      /* where this token and the one before are  */
};

/* Parse text of file `file` (already registered with diag_add_file). */
swAst *parse_file(swArena *arena, int file);

#endif
