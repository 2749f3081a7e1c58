/* diag.c — diagnostics: "file:line:col: error: message", the source line and
 * a caret, and the "did you mean" search.
 *
 * Design.  The file table owns copies of every source text.  A diagnostic
 * prints its header, then the line it points at with a gutter holding the line
 * number, then a caret under the first column and tildes under the rest of the
 * token (only within the first line of a multi-line span).  Tabs in the source
 * are reproduced in the caret line so the caret stays aligned whatever the tab
 * width.  After 100 errors the compiler stops talking: by then the first ones
 * are what matters.
 */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "diag.h"
#include "sinew.h"

#define MAX_ERRORS 100

typedef struct {
  int file, line, col;
  long seq;                     /* order of reporting, to keep sorts stable */
  char severity;                /* 'e'rror, 'w'arning or 'n'ote             */
  char *text;                   /* the whole formatted diagnostic           */
  size_t head;                  /* its length without the context notes     */
} swPending;

/* Where the checker is when a diagnostic comes: the component instances
 * being expanded, innermost last; each error or warning gets a note per
 * instance ("in 'thumb', an instance of 'finger'"), with the use's line,
 * which shows its arguments. */
#define MAX_CONTEXT 32
static struct { swLoc loc; char *text; } context[MAX_CONTEXT];
static int ncontext;

static swPending *pending;
static long npending, cappending;
static swSource *files;
static int nfiles, capfiles;
static int nerrors, nwarnings, werror;
static int stopped;             /* MAX_ERRORS reached: report nothing more */
static FILE *diag_out;

void diag_reset(FILE *out) {
  diag_flush();
  for (int i = 0; i < nfiles; i++) {
    free(files[i].path);
    free(files[i].text);
    free(files[i].name);
  }
  free(files);
  files = NULL;
  nfiles = capfiles = 0;
  nerrors = nwarnings = 0;
  werror = 0;
  stopped = 0;
  diag_out = out;
}

int diag_add_file(const char *path, const char *text, size_t len) {
  if (nfiles == capfiles) {
    capfiles = capfiles ? 2 * capfiles : 8;
    files = realloc(files, (size_t)capfiles * sizeof *files);
    if (!files) abort();
  }
  swSource *f = &files[nfiles];
  f->path = strdup(path);
  f->name = strdup(path);
  f->text = malloc(len + 1);
  if (!f->path || !f->name || !f->text) abort();
  memcpy(f->text, text, len);
  f->text[len] = 0;
  f->len = len;
  return nfiles++;
}

const swSource *diag_file(int id) {
  return id >= 0 && id < nfiles ? &files[id] : NULL;
}

void diag_set_name(int id, const char *name) {
  if (id < 0 || id >= nfiles) return;
  char *copy = strdup(name);
  if (!copy) abort();
  free(files[id].name);
  files[id].name = copy;
}

int diag_nfiles(void) { return nfiles; }
int diag_errors(void) { return nerrors; }
int diag_stopped(void) { return stopped; }
int diag_warnings(void) { return nwarnings; }
void diag_set_werror(int on) { werror = on; }

static FILE *out_stream(void) { return diag_out ? diag_out : stderr; }

/* Start and length of line `line` (1-based) of file f, without the newline. */
static const char *line_text(const swSource *f, int line, size_t *len) {
  const char *p = f->text, *end = f->text + f->len;
  for (int l = 1; l < line && p < end; l++) {
    const char *nl = memchr(p, '\n', (size_t)(end - p));
    if (!nl) return NULL;
    p = nl + 1;
  }
  if (p > end) return NULL;
  const char *nl = memchr(p, '\n', (size_t)(end - p));
  *len = (size_t)((nl ? nl : end) - p);
  if (*len && p[*len - 1] == '\r') (*len)--;
  return p;
}

/* Columns count characters (UTF-8 code points), not bytes, as the lexer
 * counts them: a continuation byte 10xxxxxx starts no character. */
static int starts_char(char c) { return ((unsigned char)c & 0xC0) != 0x80; }

const char *diag_at(const swSource *src, int line, int col) {
  const char *p = src->text, *end = src->text + src->len;
  for (int l = 1; l < line && p < end; p++)
    if (*p == '\n') l++;
  for (int c = 1; c < col && p < end && *p != '\n'; c++)
    do p++; while (p < end && !starts_char(*p));
  return p;
}

static void show_source(FILE *out, swLoc loc) {
  const swSource *f = diag_file(loc.file);
  size_t len;
  const char *text = f && loc.line > 0 ? line_text(f, loc.line, &len) : NULL;
  if (!text) return;
  fprintf(out, "%5d | ", loc.line);
  int chars = 0;   /* characters on the line */
  for (size_t i = 0; i < len; i++) {
    unsigned char c = (unsigned char)text[i];
    fputc(c == '\t' || c >= 0x20 ? c : '?', out);   /* control bytes shown as ? */
    chars += starts_char((char)c);
  }
  fputs("\n      | ", out);
  int col = loc.col < 1 ? 1 : loc.col;
  /* under each character before the column a blank (a tab under a tab) */
  const char *p = text, *end = text + len;
  for (int i = 1; i < col && p < end; i++) {
    fputc(*p == '\t' ? '\t' : ' ', out);
    do p++; while (p < end && !starts_char(*p));
  }
  fputc('^', out);
  int last = loc.end_line == loc.line ? loc.end_col : chars;
  if (last > chars) last = chars;
  for (int i = col + 1; i <= last; i++) fputc('~', out);
  fputc('\n', out);
}

/* Format one diagnostic into the pending list; diag_flush() prints them. */
static void report(const char *severity, swLoc loc, const char *fmt, va_list ap) {
  char *text = NULL;
  size_t size = 0;
  FILE *out = open_memstream(&text, &size);
  if (!out) abort();
  const swSource *f = diag_file(loc.file);
  if (f && loc.line > 0) fprintf(out, "%s:%d:%d: %s: ", f->path, loc.line, loc.col, severity);
  else if (f) fprintf(out, "%s: %s: ", f->path, severity);   /* the file as a whole */
  else fprintf(out, "sinewc: %s: ", severity);
  vfprintf(out, fmt, ap);
  fputc('\n', out);
  if (f && loc.line > 0) show_source(out, loc);
  fflush(out);
  size_t head = size;
  if (severity[0] != 'n')
    for (int k = ncontext - 1; k >= 0 && k < MAX_CONTEXT; k--) {
      const swSource *g = diag_file(context[k].loc.file);
      if (!g || (context[k].loc.file == loc.file && context[k].loc.line == loc.line))
        continue; /* the diagnostic is on the use's own line */
      fprintf(out, "%s:%d:%d: note: %s\n", g->path, context[k].loc.line, context[k].loc.col,
              context[k].text);
      show_source(out, context[k].loc);
    }
  fclose(out);
  if (npending == cappending) {
    cappending = cappending ? 2 * cappending : 16;
    pending = realloc(pending, (size_t)cappending * sizeof *pending);
    if (!pending) abort();
  }
  pending[npending] =
      (swPending){f ? loc.file : -1, loc.line, loc.col, npending, severity[0], text, head};
  npending++;
}

static int by_place(const void *pa, const void *pb) {
  const swPending *a = pa, *b = pb;
  if (a->file != b->file) return a->file < b->file ? -1 : 1;
  if (a->line != b->line) return a->line < b->line ? -1 : 1;
  if (a->col != b->col) return a->col < b->col ? -1 : 1;
  return a->seq < b->seq ? -1 : a->seq > b->seq;
}

/* Print what is pending, in file order and then by line and column, the
 * order a reader goes through the model. */
void diag_flush(void) {
  if (npending) qsort(pending, (size_t)npending, sizeof *pending, by_place);
  FILE *out = out_stream();
  for (long i = 0; i < npending; i++) {
    /* the same message at the same place once more (an error in the body of
     * a component is found again for every use of it): print it once, with
     * the notes of the first use that met it */
    int again = 0;
    for (long k = i - 1; k >= 0 && !again; k--) {
      if (pending[k].file != pending[i].file || pending[k].line != pending[i].line ||
          pending[k].col != pending[i].col)
        break;
      again = pending[k].head == pending[i].head &&
              !strncmp(pending[k].text, pending[i].text, pending[i].head);
    }
    if (!again) fputs(pending[i].text, out);
    else if (pending[i].severity == 'e') nerrors--;
    else if (pending[i].severity == 'w') nwarnings--;
  }
  for (long i = 0; i < npending; i++) free(pending[i].text);
  free(pending);
  pending = NULL;
  npending = cappending = 0;
  fflush(out);
}

void diag_error(swLoc loc, const char *fmt, ...) {
  nerrors++;
  if (stopped) return;
  if (nerrors > MAX_ERRORS) {
    stopped = 1;
    diag_flush();
    fprintf(out_stream(), "sinewc: too many errors (%d); stopping here\n", MAX_ERRORS);
    return;
  }
  va_list ap;
  va_start(ap, fmt);
  report("error", loc, fmt, ap);
  va_end(ap);
}

void diag_warning(swLoc loc, const char *fmt, ...) {
  if (stopped) return;
  va_list ap;
  va_start(ap, fmt);
  if (werror) {
    nerrors++;
    report("error", loc, fmt, ap);
  } else {
    nwarnings++;
    report("warning", loc, fmt, ap);
  }
  va_end(ap);
}

void diag_push_context(swLoc loc, const char *fmt, ...) {
  if (ncontext < MAX_CONTEXT) {
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (!(context[ncontext].text = strdup(buf))) abort();
    context[ncontext].loc = loc;
  }
  ncontext++;
}

void diag_pop_context(void) {
  if (ncontext <= 0) return;
  ncontext--;
  if (ncontext < MAX_CONTEXT) free(context[ncontext].text);
}

void diag_note(swLoc loc, const char *fmt, ...) {
  if (stopped) return;
  va_list ap;
  va_start(ap, fmt);
  report("note", loc, fmt, ap);
  va_end(ap);
}

void diag_plain(const char *fmt, ...) {
  nerrors++;
  diag_flush();
  FILE *out = out_stream();
  va_list ap;
  va_start(ap, fmt);
  fputs("sinewc: ", out);
  vfprintf(out, fmt, ap);
  fputc('\n', out);
  va_end(ap);
}

const char *diag_where(swLoc loc, char *buf, size_t len) {
  const swSource *f = diag_file(loc.file);
  snprintf(buf, len, "%s:%d", f ? f->path : "?", loc.line);
  return buf;
}

const char *diag_where_from(swLoc at, swLoc from, char *buf, size_t len) {
  if (at.file == from.file) {
    snprintf(buf, len, "line %d", at.line);
    return buf;
  }
  return diag_where(at, buf, len);
}

const char *diag_name_where(swLoc loc, char *buf, size_t len) {
  const swSource *f = diag_file(loc.file);
  snprintf(buf, len, "%s:%d", f ? f->name : "?", loc.line);
  return buf;
}

const char *diag_join(char *buf, size_t len, const char *const *items, int n) {
  if (!len) return buf;
  buf[0] = 0;
  for (int i = 0; i < n; i++) {
    if (strlen(buf) + strlen(items[i]) + 8 > len) {
      strcat(buf, ", ...");
      break;
    }
    if (i) strcat(buf, ", ");
    strcat(buf, items[i]);
  }
  return buf;
}

const char *diag_suggest(const char *name, const char *const *cands, int n) {
  const char *best = NULL;
  int best_d = 1000;
  int len = (int)strlen(name);
  int limit = len <= 3 ? 1 : len <= 6 ? 2 : 3;
  for (int i = 0; i < n; i++) {
    if (!cands[i] || !strcmp(cands[i], name)) continue;
    /* the distance is at least the difference of the lengths: a candidate
     * that cannot come within the limit, or beat the best so far, is not
     * measured (the answer is the same, the first closest within it) */
    const int gap = abs((int)strlen(cands[i]) - len);
    if (gap > limit || gap >= best_d) continue;
    int dist = sw_edit_distance(name, (size_t)len, cands[i]);
    if (dist < best_d) {
      best_d = dist;
      best = cands[i];
    }
  }
  return best_d <= limit ? best : NULL;
}
