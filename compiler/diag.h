/* diag.h — source files and diagnostics of the compiler.
 *
 * Design.  Every file the compiler reads is registered here once and keeps
 * its text for the whole compilation, so a diagnostic at any stage can print
 * "file:line:col: error: message", the source line and a caret under the
 * columns it names (the convention of gcc and clang).  Diagnostics are held
 * until diag_flush() and printed in the order of the model text, whichever
 * stage found them.  Errors are counted,
 * not fatal: every stage goes on and reports everything it can.  The output
 * stream is settable so the tests can capture the exact text.
 */
#ifndef SINEW_DIAG_H
#define SINEW_DIAG_H

#include <stdio.h>
#include "ast.h"

typedef struct {
  char *path;        /* as shown in messages                  */
  char *text;        /* whole file, NUL-terminated            */
  size_t len;
  char *name;        /* the same on every machine, for what the compiler
                        writes (model source, generated C): the main file's
                        base name, an import's name as written; the path
                        until diag_set_name gives one             */
} swSource;

void diag_reset(FILE *out);                /* forget all files and counts */
int diag_add_file(const char *path, const char *text, size_t len);  /* file id */
const swSource *diag_file(int id);
void diag_set_name(int id, const char *name);
/* "name:line" of a place, in the machine-independent name (generated C) */
const char *diag_name_where(swLoc loc, char *buf, size_t len);
int diag_nfiles(void);

void diag_error(swLoc loc, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void diag_warning(swLoc loc, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void diag_note(swLoc loc, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* While a context is pushed (a component instance being expanded), every
 * error and warning carries a note at its place; pops in reverse order. */
void diag_push_context(swLoc loc, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void diag_pop_context(void);
/* A message with no place in a model ("sinewc: cannot read x.sinew"). */
void diag_plain(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Print pending diagnostics sorted by file, line and column. */
void diag_flush(void);
int diag_errors(void);
/* Whether the error limit was reached: nothing more is reported, so the
 * checker may stop (sema.c does, item by item). */
int diag_stopped(void);
int diag_warnings(void);
void diag_set_werror(int on);

/* The closest of n candidate names to `name`, or NULL when none is close
 * enough to be a likely misspelling (edit distance, transpositions count 1). */
const char *diag_suggest(const char *name, const char *const *cands, int n);
/* Where column `col` (1-based, in characters) of line `line` is in the text
 * of src (the line's end if it is shorter). */
const char *diag_at(const swSource *src, int line, int col);
/* "a, b, c" (", ..." when the next would not fit in len, which must be > 8) */
const char *diag_join(char *buf, size_t len, const char *const *items, int n);

/* "file:line" of a location, for messages that point elsewhere. */
const char *diag_where(swLoc loc, char *buf, size_t len);
/* Where `at` is, as a message at `from` cites it: "line N" in the same file,
 * "file:N" in another (a component's body, an imported scene statement). */
const char *diag_where_from(swLoc at, swLoc from, char *buf, size_t len);

#endif
