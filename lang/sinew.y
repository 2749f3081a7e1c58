/* sinew.y — the grammar of the sinew language.
 *
 * Design.  A pure (reentrant) LALR(1) parser with locations, no conflicts
 * (%expect 0), building the tree of compiler/ast.h.  The grammar is small and
 * regular: a file is a list of items; most items are "KIND NAME { key = value;
 * ... }" or "ACTION operand [= value];", and the words that pick a kind of
 * definition (material, bone, muscle, ...) or an action (clamp, force,
 * gravity, ...) are ordinary identifiers that the checker validates, so a
 * misspelled one gets a "did you mean" rather than a bare syntax error.
 * Expressions have the usual precedence (from the loosest: or, and, the
 * comparisons, which do not chain, + -, * /); a unit written after a value
 * multiplies it and binds tighter than * and /, so `1.75 g/cm^3` reads as
 * (1.75 g) / cm^3 and `(0, 0, -9.81) m/s^2` as ((0, 0, -9.81) m) / s^2.
 * Error recovery resynchronises on ';' and '}', so one run reports every
 * syntax error of a file.  Each rule is headed by the construct it reads.
 */
%define api.pure full
%define api.prefix {sinew_yy}
%define api.location.type {swLoc}
%define parse.error custom
%locations
%expect 0
%param {yyscan_t scanner}
%parse-param {struct swLexState *st}

%code requires {
#include "ast.h"
typedef void *yyscan_t;
struct swLexState;
}

%code provides {
int sinew_yylex(SINEW_YYSTYPE *yylval, swLoc *yylloc, yyscan_t scanner);
int lex_init(yyscan_t *scanner, struct swLexState *st, const char *text, size_t len);
void lex_done(yyscan_t scanner);
}

%code {
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "lex.h"

#define YYLLOC_DEFAULT(Cur, Rhs, N)                                   \
  do {                                                                \
    if (N) (Cur) = ast_span(YYRHSLOC(Rhs, 1), YYRHSLOC(Rhs, N));      \
    else {                                                            \
      (Cur) = YYRHSLOC(Rhs, 0);                                       \
      (Cur).line = (Cur).end_line;                                    \
      (Cur).col = (Cur).end_col + 1;                                  \
      (Cur).end_col = (Cur).col;                                      \
    }                                                                 \
  } while (0)

#define A (st->arena)
static swAst *node(struct swLexState *st, swAstKind k, swLoc loc) { return ast_new(st->arena, k, loc); }
/* Every child is added here.  A value (number ... method call) nested deeper
 * than AST_MAX_DEPTH is reported once and replaced, with every value that
 * encloses it, by a number the checker passes over in silence (NaN, as for a
 * number out of range), so no tree the checker walks is deeper than that and
 * a few levels of fields and arguments. */
#define AST_CUT (INT_MAX / 2)   /* depth of a replaced value, above any real one */
static swAst *push(struct swLexState *st, swAst *parent, swAst *child) {
  if (child && child->kind >= AST_NUM && child->kind <= AST_METHOD && child->depth > AST_MAX_DEPTH) {
    if (child->depth < AST_CUT)
      diag_error(child->loc, "this expression is nested more than %d levels deep; split it with "
                 "let", AST_MAX_DEPTH);
    swAst *cut = node(st, AST_NUM, child->loc);
    cut->num = NAN;
    cut->depth = AST_CUT;
    child = cut;
  }
  return ast_push(st->arena, parent, child);
}
static swAst *named(struct swLexState *st, swAstKind k, swLoc loc, const char *name) {
  swAst *n = ast_new(st->arena, k, loc);
  n->name = name;
  return n;
}
static swAst *binop(struct swLexState *st, int op, swAst *a, swAst *b, swLoc loc) {
  swAst *n = ast_new(st->arena, AST_BINOP, loc);
  n->op = op;
  push(st, n, a);
  push(st, n, b);
  return n;
}
static void sinew_yyerror(swLoc *loc, yyscan_t scanner, struct swLexState *st, const char *msg) {
  (void)scanner; (void)st;
  diag_error(*loc, "%s", msg);
}
}

%union {
  double num;
  const char *str;
  swAst *ast;
}

%token <num> NUMBER "number"
%token <str> IDENT  "name"
%token <str> UNIT   "unit"
%token <str> STRING "string"
%token IMPORT "'import'" PARAM "'param'" LET "'let'" JOINT "'joint'"
%token COMPONENT "'component'" USE "'use'" SIMULATE "'simulate'"
%token OUTPUT "'output'" EVERY "'every'" EXPECT "'expect'"
%token AND "'and'" OR "'or'" LE "'<='" GE "'>='" IN "'in'" FOR "'for'" UNTIL "'until'"

%left OR
%left AND
%nonassoc '<' '>' LE GE
%left '+' '-'
%left '*' '/'
%precedence NEG
%precedence UNIT
%right '^'

%type <ast> items item body fields field expr primary args arglist arg
%type <ast> formals formallist formal exprlist every_opt unit_factor
%type <num> exponent

%%

/* file: item* */
file
  : items                    { st->root = $1; }
  ;

items
  : %empty                   { $$ = node(st, AST_FILE, @$); if (!st->root) st->root = $$; }
  | items item               { $$ = $2 ? push(st, $1, $2) : $1; }
  ;

item
  /* import "path"; */
  : IMPORT STRING ';'        { $$ = node(st, AST_IMPORT, @$); $$->text = $2; }
  /* import "path" as NAME;    its definitions as NAME.x */
  | IMPORT STRING IDENT IDENT ';'
                             { $$ = node(st, AST_IMPORT, @$); $$->text = $2; $$->name = $4;
                               if (strcmp($3, "as"))
                                 diag_error(@3, "unexpected name '%s' after the file name, "
                                            "expected ';' or 'as NAME'", $3); }
  /* param NAME = expr; */
  | PARAM IDENT '=' expr ';' { $$ = named(st, AST_PARAM, @2, $2); push(st, $$, $4); }
  /* param NAME = expr in (LO, HI);   the range a study varies it over (the
     pair is checked by sema_def.c) */
  | PARAM IDENT '=' expr IN expr ';'
                             { $$ = named(st, AST_PARAM, @2, $2); push(st, $$, $4);
                               push(st, $$, push(st, named(st, AST_ARG, @5, "in"), $6)); }
  /* let NAME = expr; */
  | LET IDENT '=' expr ';'   { $$ = named(st, AST_LET, @2, $2); push(st, $$, $4); }
  /* KIND NAME { fields }      material bone { E = 15 GPa; } */
  | IDENT IDENT body         { $$ = named(st, AST_DEF, @2, $2); $$->text = $1;
                               $$->kid = $3->kid; $$->nkid = $3->nkid; $$->capkid = $3->capkid;
                               $$->damaged = $3->damaged; $$->loc = ast_span(@1, @2); }
  /* KIND UNIT { fields }      material m { ... }: a unit cannot name a definition;
     the body is read (and dropped), so its fields raise no errors of their own */
  | IDENT UNIT body          { $$ = NULL;
                               diag_error(@2, "'%s' is a unit and cannot be used as a name", $2); }
  /* KIND { fields }           ground { stiffness = 1e4 N/m; }  (named after its kind) */
  | IDENT body               { $$ = named(st, AST_DEF, @1, NULL); $$->text = $1;
                               $$->kid = $2->kid; $$->nkid = $2->nkid; $$->capkid = $2->capkid;
                               $$->damaged = $2->damaged; }
  /* joint NAME = KIND(args) [{ fields }] */
  | JOINT IDENT '=' IDENT '(' args ')' body
                             { $$ = named(st, AST_JOINT, @2, $2); $$->text = $4;
                               $$->damaged = $8->damaged; push(st, $$, $6);
                               for (int i = 0; i < $8->nkid; i++) push(st, $$, $8->kid[i]); }
  | JOINT IDENT '=' IDENT '(' args ')' ';'
                             { $$ = named(st, AST_JOINT, @2, $2); $$->text = $4; push(st, $$, $6); }
  /* component NAME(formals) { items } */
  | COMPONENT IDENT '(' formals ')' '{' items '}'
                             { $$ = named(st, AST_COMPONENT, @2, $2); push(st, $$, $4);
                               for (int i = 0; i < $7->nkid; i++) push(st, $$, $7->kid[i]); }
  /* for NAME[VAR] in (FIRST, LAST) { items }   the items once for each whole
     VAR from FIRST to LAST, in a scope of its own named NAME[VAR] */
  | FOR IDENT '[' IDENT ']' IN expr '{' items '}'
                             { $$ = named(st, AST_FOR, @2, $2); $$->text = $4;
                               $$->loc = ast_span(@1, @5); push(st, $$, $7);
                               for (int i = 0; i < $9->nkid; i++) push(st, $$, $9->kid[i]); }
  /* use NAME = COMPONENT(args); */
  | USE IDENT '=' IDENT '(' args ')' ';'
                             { $$ = named(st, AST_USE, @2, $2); $$->text = $4;
                               $$->loc = ast_span(@2, @7); push(st, $$, $6); }
  /* use NAME = NAMESPACE.COMPONENT(args); */
  | USE IDENT '=' IDENT '.' IDENT '(' args ')' ';'
                             { $$ = named(st, AST_USE, @2, $2);
                               size_t n = strlen($4) + strlen($6) + 2;
                               char *q = ast_alloc(A, n);
                               snprintf(q, n, "%s.%s", $4, $6);
                               $$->text = q;
                               $$->loc = ast_span(@2, @9); push(st, $$, $8); }
  /* ACTION operand;   ACTION operand = value;      clamp bar.start;  force bar.end = (0, 0, -1) N; */
  | IDENT expr ';'           { $$ = node(st, AST_ACTION, @1); $$->text = $1; push(st, $$, $2); }
  | IDENT expr '=' expr ';'  { $$ = node(st, AST_ACTION, @1); $$->text = $1;
                               push(st, $$, $2); push(st, $$, $4); }
  /* ACTION operand [= value] until T;     clamp rope.start until 0.5 s;
     the time goes last, as an argument named "until" (sema_stmt.c) */
  | IDENT expr UNTIL expr ';'
                             { $$ = node(st, AST_ACTION, @1); $$->text = $1; push(st, $$, $2);
                               push(st, $$, push(st, named(st, AST_ARG, @3, "until"), $4)); }
  | IDENT expr '=' expr UNTIL expr ';'
                             { $$ = node(st, AST_ACTION, @1); $$->text = $1;
                               push(st, $$, $2); push(st, $$, $4);
                               push(st, $$, push(st, named(st, AST_ARG, @5, "until"), $6)); }
  /* simulate { fields } */
  | SIMULATE body            { $$ = $2; $$->kind = AST_SIMULATE; $$->loc = @1; }
  /* output "file.h5" [every T] [{ selections }] */
  | OUTPUT STRING every_opt body
                             { $$ = $4; $$->kind = AST_OUTPUT; $$->loc = ast_span(@1, @2); $$->text = $2;
                               swAst *every = $3;
                               push(st, $$, every);
                               /* every goes first */
                               for (int i = $$->nkid - 1; i > 0; i--) $$->kid[i] = $$->kid[i - 1];
                               $$->kid[0] = every; }
  | OUTPUT STRING every_opt ';'
                             { $$ = node(st, AST_OUTPUT, ast_span(@1, @2)); $$->text = $2; push(st, $$, $3); }
  /* expect QUANTITY WORD expr WORD expr [WORD expr];
       expect angle(elbow) at 0.5 s in (-155 deg, -150 deg);
       expect force(biceps) over (0.2 s, 0.5 s) in (0 N, 300 N);
       expect angle(elbow) at 0.5 s within 1 deg of -152 deg;
     the words (at/over, in/within, of) are checked by sema_expect.c; 'in' is
     a keyword, since `param NAME = V in (LO, HI)` takes it too */
  | EXPECT expr IDENT expr IN expr ';'
                             { $$ = node(st, AST_EXPECT, ast_span(@1, @6)); push(st, $$, $2);
                               push(st, $$, push(st, named(st, AST_ARG, @3, $3), $4));
                               push(st, $$, push(st, named(st, AST_ARG, @5, "in"), $6)); }
  | EXPECT expr IDENT expr IDENT expr ';'
                             { $$ = node(st, AST_EXPECT, ast_span(@1, @6)); push(st, $$, $2);
                               push(st, $$, push(st, named(st, AST_ARG, @3, $3), $4));
                               push(st, $$, push(st, named(st, AST_ARG, @5, $5), $6)); }
  | EXPECT expr IDENT expr IDENT expr IDENT expr ';'
                             { $$ = node(st, AST_EXPECT, ast_span(@1, @8)); push(st, $$, $2);
                               push(st, $$, push(st, named(st, AST_ARG, @3, $3), $4));
                               push(st, $$, push(st, named(st, AST_ARG, @5, $5), $6));
                               push(st, $$, push(st, named(st, AST_ARG, @7, $7), $8)); }
  | error ';'                { $$ = NULL; yyerrok; }
  | error '}'                { $$ = NULL; yyerrok; }
  /* a statement whose ';' is missing: the next line's item is kept (no
     yyerrok: what does not fit after it is dropped without more errors) */
  | IDENT expr error         { $$ = NULL; }
  | PARAM IDENT '=' expr error { $$ = NULL; }
  | LET IDENT '=' expr error { $$ = NULL; }
  ;

every_opt
  : %empty                   { $$ = NULL; }
  | EVERY expr               { $$ = $2; }
  ;

/* body: { field* } */
body
  : '{' fields '}'           { $$ = $2; }
  | '{' fields error '}'     { $$ = $2; $$->damaged = 1; yyerrok; }
  ;

fields
  : %empty                   { $$ = node(st, AST_SIMULATE, @$); }
  | fields field             { $$ = $2 ? push(st, $1, $2) : $1; if (!$2) $$->damaged = 1; }
  ;

field
  /* key = value; */
  : IDENT '=' expr ';'       { $$ = named(st, AST_FIELD, @1, $1); push(st, $$, $3); }
  /* what targets;            velocity all;  energy; */
  | IDENT exprlist ';'       { $$ = $2; $$->kind = AST_SELECT; $$->name = $1; $$->loc = @1; }
  | IDENT ';'                { $$ = named(st, AST_SELECT, @1, $1); }
  /* key(formals) = value;    height(x, y) = 0.1 m * sin(x / 1 m); */
  | IDENT expr '=' expr ';'  { $$ = named(st, AST_FIELD, @1, $1); push(st, $$, $4); push(st, $$, $2); }
  /* let NAME = value;         a name local to the body (terrain) */
  | LET IDENT '=' expr ';'   { $$ = named(st, AST_LET, @2, $2); push(st, $$, $4); }
  | error ';'                { $$ = NULL; yyerrok; }
  /* a field whose ';' is missing: the next line's field is kept */
  | IDENT '=' expr error     { $$ = NULL; }
  ;

formals
  : %empty                   { $$ = node(st, AST_FORMALS, @$); }
  | formallist               { $$ = $1; }
  ;
formallist
  : formal                   { $$ = push(st, node(st, AST_FORMALS, @1), $1); }
  | formallist ',' formal    { $$ = push(st, $1, $3); }
  ;
/* NAME [= default] */
formal
  : IDENT                    { $$ = named(st, AST_ARG, @1, $1); }
  | IDENT '=' expr           { $$ = named(st, AST_ARG, @1, $1); push(st, $$, $3); }
  ;

args
  : %empty                   { $$ = node(st, AST_ARGS, @$); }
  | arglist                  { $$ = $1; }
  ;
arglist
  : arg                      { $$ = push(st, node(st, AST_ARGS, @1), $1); }
  | arglist ',' arg          { $$ = push(st, $1, $3); }
  ;
/* value | name = value | condition: value */
arg
  : expr                     { $$ = push(st, node(st, AST_ARG, @1), $1); }
  | expr ':' expr            { $$ = node(st, AST_CASE, @$); push(st, $$, $1); push(st, $$, $3); }
  | IDENT '=' expr           { $$ = named(st, AST_ARG, @1, $1); push(st, $$, $3); }
  ;

exprlist
  : expr                     { $$ = push(st, node(st, AST_ARGS, @1), $1); }
  | exprlist ',' expr        { $$ = push(st, $1, $3); }
  ;

expr
  : expr '+' expr            { $$ = binop(st, '+', $1, $3, @$); }
  | expr '-' expr            { $$ = binop(st, '-', $1, $3, @$); }
  | expr '*' expr            { $$ = binop(st, '*', $1, $3, @$); }
  | expr '/' expr            { $$ = binop(st, '/', $1, $3, @$); }
  | '-' expr %prec NEG       { $$ = push(st, node(st, AST_NEG, @$), $2); }
  | expr '^' expr            { $$ = binop(st, '^', $1, $3, @$); }
  /* comparisons and logic, for piecewise(): x < 3 m and y >= 0 m */
  | expr '<' expr            { $$ = binop(st, '<', $1, $3, @$); }
  | expr '>' expr            { $$ = binop(st, '>', $1, $3, @$); }
  | expr LE expr             { $$ = binop(st, 'l', $1, $3, @$); }
  | expr GE expr             { $$ = binop(st, 'g', $1, $3, @$); }
  | expr AND expr            { $$ = binop(st, '&', $1, $3, @$); }
  | expr OR expr             { $$ = binop(st, '|', $1, $3, @$); }
  /* value unit: juxtaposition multiplies */
  | expr unit_factor %prec UNIT
                             { $$ = node(st, AST_APPLY, @$); push(st, $$, $1); push(st, $$, $2); }
  | primary                  { $$ = $1; }
  ;

unit_factor
  : UNIT                     { $$ = named(st, AST_UNIT, @1, $1); }
  | UNIT '^' exponent        { $$ = binop(st, '^', named(st, AST_UNIT, @1, $1),
                                          node(st, AST_NUM, @3), @$);
                               $$->kid[1]->num = $3; }
  ;

exponent
  : NUMBER                   { $$ = $1; }
  | '-' NUMBER               { $$ = -$2; }
  ;

primary
  : NUMBER                   { $$ = node(st, AST_NUM, @1); $$->num = $1; }
  | IDENT                    { $$ = named(st, AST_NAME, @1, $1); }
  | UNIT                     { $$ = named(st, AST_UNIT, @1, $1); }
  | '(' expr ')'             { $$ = $2; }
  /* vector: (x, y, z) */
  | '(' expr ',' exprlist ')'
                             { $$ = node(st, AST_VEC, @$); push(st, $$, $2);
                               for (int i = 0; i < $4->nkid; i++) push(st, $$, $4->kid[i]); }
  /* call: ramp(0, 1, over = 0.1 s) */
  | IDENT '(' args ')'       { $$ = named(st, AST_CALL, @$, $1); push(st, $$, $3); }
  /* member: humerus.end */
  | primary '.' IDENT        { $$ = named(st, AST_MEMBER, @$, $3); push(st, $$, $1); }
  /* index: barbs[3], one pass of a loop */
  | primary '[' expr ']'     { $$ = node(st, AST_INDEX, @$); push(st, $$, $1); push(st, $$, $3); }
  /* method: humerus.at(0.3) */
  | primary '.' IDENT '(' args ')'
                             { $$ = named(st, AST_METHOD, @$, $3); push(st, $$, $1); push(st, $$, $5); }
  ;

%%

/* The message of a syntax error: what was found, what would have fitted, and,
 * when a bracket is left open, where it was opened (as Lua does). */
static int yyreport_syntax_error(const yypcontext_t *ctx, yyscan_t scanner, struct swLexState *st) {
  (void)scanner;
  enum { NEXPECT = 64 };
  yysymbol_kind_t expected[NEXPECT];
  int n = yypcontext_expected_tokens(ctx, expected, NEXPECT);
  yysymbol_kind_t found = yypcontext_token(ctx);
  const swLoc *loc = yypcontext_location(ctx);
  char msg[512];
  int len = 0;
  /* a unit where a name belongs: "let g = ...", "material m {" */
  if (!strcmp(yysymbol_name(found), "'{'") && st->prev_unit && st->last_unit) {   /* material m { */
    diag_error(*loc, "'%s' is a unit and cannot be used as a name", st->last_unit);
    return 0;
  }
  if (found == YYSYMBOL_UNIT && st->last_unit) {
    for (int i = 0; i < n; i++)
      if (expected[i] == YYSYMBOL_IDENT) {
        diag_error(*loc, "'%s' is a unit and cannot be used as a name", st->last_unit);
        return 0;
      }
  }
  const swSource *src = diag_file(loc->file);
  /* a ';' missing at the end of a line: said there, as C compilers do,
   * quoting the statement's line ("expected ';' after 'clamp beam.start'") */
  const swLoc *prev = &st->prev_loc;
  int semicolon = 0;
  for (int i = 0; i < n; i++) semicolon |= !strcmp(yysymbol_name(expected[i]), "';'");
  if (semicolon && src && prev->line > 0 && loc->line > prev->end_line &&
      prev->line == prev->end_line) {
    const char *p = diag_at(src, prev->line, 1), *end = src->text + src->len;
    /* the statement or field: from the line's last ';' or '{' before it */
    const char *last = diag_at(src, prev->line, prev->end_col + 1);   /* one past the token */
    const char *first = p;
    for (const char *q = p; q < last && q < end; q++)
      if (*q == ';' || *q == '{') first = q + 1;
    while (first < end && (*first == ' ' || *first == '\t')) first++;
    swLoc at = {prev->file, prev->end_line, prev->end_col + 1, prev->end_line, prev->end_col + 1};
    if (last <= end && last > first && last - first <= 60)
      diag_error(at, "expected ';' after '%.*s'", (int)(last - first), first);
    else
      diag_error(at, "expected ';' at the end of this line");
    return 0;
  }
  /* a name or number is quoted as written: "unexpected name 'G'" */
  const char *text = NULL;
  int tlen = 0;
  if ((found == YYSYMBOL_IDENT || found == YYSYMBOL_NUMBER) && src && loc->line == loc->end_line) {
    if (loc->end_col >= loc->col) {
      text = diag_at(src, loc->line, loc->col);
      tlen = (int)(diag_at(src, loc->line, loc->end_col + 1) - text);
    }
  }
  if (found == YYSYMBOL_YYEOF)
    len = snprintf(msg, sizeof msg, "unexpected end of file");
  else if (text && tlen <= 40)
    len = snprintf(msg, sizeof msg, "unexpected %s '%.*s'", yysymbol_name(found), tlen, text);
  else
    len = snprintf(msg, sizeof msg, "unexpected %s", yysymbol_name(found));
  /* Where an expression could go on, every operator and unit is "expected";
   * listing them helps nobody.  Say "a value" where an expression may start,
   * "a definition or statement" where an item may, "a name" or "a string"
   * where one is due, with the punctuation that would end or structure
   * something (';', '}', ')', ',', '=', '{'); otherwise up to four tokens. */
  int want_value = 0, want_item = 0, want_name = 0, want_string = 0;
  for (int i = 0; i < n; i++) {
    want_value |= expected[i] == YYSYMBOL_NUMBER;
    want_item |= expected[i] == YYSYMBOL_IMPORT;
    want_name |= expected[i] == YYSYMBOL_IDENT;
    want_string |= expected[i] == YYSYMBOL_STRING;
  }
  static const char *const structural[] = {"';'", "'}'", "')'", "','", "'='", "'{'"};
  const char *show[10];
  int nshow = 0;
  if (want_value) show[nshow++] = "a value";
  else if (want_item) show[nshow++] = "a definition or statement";
  else {
    if (want_name) show[nshow++] = "a name";
    if (want_string) show[nshow++] = "a string";
  }
  for (size_t k = 0; k < sizeof structural / sizeof structural[0]; k++)
    for (int i = 0; i < n; i++)
      if (!strcmp(yysymbol_name(expected[i]), structural[k])) show[nshow++] = structural[k];
  if (nshow == 0 && n > 0 && n <= 4)
    for (int i = 0; i < n; i++)
      show[nshow++] = expected[i] == YYSYMBOL_YYEOF ? "the end of the file"
                      : expected[i] == YYSYMBOL_UNIT ? "a unit" : yysymbol_name(expected[i]);
  /* an unclosed bracket explains an unexpected end of file or keyword: say
   * which bracket, and where it was opened (as Lua does) */
  char open = 0;
  if (st->depth > 0 && st->depth <= LEX_MAX_DEPTH) {
    char o = st->open[st->depth - 1], want = o == '{' ? '}' : ')';
    int wanted = found == YYSYMBOL_YYEOF;
    for (int i = 0; i < n; i++)
      if (!strcmp(yysymbol_name(expected[i]), want == '}' ? "'}'" : "')'")) wanted = 1;
    if (wanted) open = o;
  }
  if (open) {
    snprintf(msg + len, sizeof msg - (size_t)len, ", expected '%c' (to close '%c' at line %d)",
             open == '{' ? '}' : ')', open, st->open_loc[st->depth - 1].line);
  } else {
    for (int i = 0; i < nshow && len < (int)sizeof msg; i++) {
      len += snprintf(msg + len, sizeof msg - (size_t)len, "%s%s",
                      i == 0 ? ", expected " : i == nshow - 1 ? " or " : ", ", show[i]);
    }
  }
  diag_error(*loc, "%s", msg);
  return 0;
}

swAst *parse_file(swArena *arena, int file) {
  const swSource *src = diag_file(file);
  struct swLexState st;
  memset(&st, 0, sizeof st);
  st.file = file;
  st.line = st.col = 1;
  st.arena = arena;
  yyscan_t scanner;
  if (lex_init(&scanner, &st, src->text, src->len)) {
    diag_plain("cannot start the scanner for %s", src->path);
    return NULL;
  }
  sinew_yyparse(scanner, &st);
  lex_done(scanner);
  if (!st.root) {
    swLoc loc = {file, 1, 1, 1, 1};
    st.root = ast_new(arena, AST_FILE, loc);
  }
  return st.root;
}
