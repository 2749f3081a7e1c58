/* sema_value.c — arithmetic on checked values, with dimensions and with the
 * C text of anything that depends on a param.
 *
 * Design.  Every operation computes the numbers (params at their defaults)
 * and the dimension; if an operand depends on a param, it also builds the C
 * expression that recomputes the result at run time.  Constant operands are
 * printed as the shortest decimal that reads back to the same double, so the
 * generated simulator computes with exactly the numbers the checker saw.
 * Numbers broadcast over vectors (2 * (1, 2, 3)); two vectors combine only
 * component by component under + and -.  A time signal can only be scaled.
 * Errors are reported here, naming both dimensions, and give VAL_ERROR, which
 * every later step passes through silently.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diag.h"
#include "sema.h"

swValue val_error(void) {
  swValue v;
  memset(&v, 0, sizeof v);
  v.kind = VAL_ERROR;
  return v;
}

swValue val_truth(int truth, swLoc loc) {
  swValue v = val_error();
  v.kind = VAL_TRUTH;
  v.word = truth ? "true" : "false";
  v.loc = loc;
  return v;
}

swValue val_vec(swArena *a, int n, const double *x, swDim dim, swLoc loc) {
  swValue v = val_error();
  v.kind = n == 1 ? VAL_NUM : VAL_VEC;
  v.n = n;
  v.v = ast_alloc(a, (size_t)n * sizeof *v.v);
  if (x) memcpy(v.v, x, (size_t)n * sizeof *v.v);
  v.dim = dim;
  v.loc = loc;
  return v;
}

swValue val_num(swArena *a, double x, swDim dim, swLoc loc) {
  return val_vec(a, 1, &x, dim, loc);
}

int val_is_const(const swValue *v) {
  if (v->c)
    for (int i = 0; i < v->n; i++)
      if (v->c[i]) return 0;
  return 1;
}

/* Shortest decimal that reads back to x exactly: "%.Ng", or "%.Nf" for
 * moderate magnitudes so that 1000 reads 1000.0 rather than 1e+03. */
static void format_double(char *buf, size_t len, double x) {
  for (int prec = 1; prec <= 17; prec++) {
    snprintf(buf, len, "%.*g", prec, x);
    if (strtod(buf, NULL) == x) break;
  }
  double ax = fabs(x);
  if (strchr(buf, 'e') && ax >= 1 && ax < 1e15) {
    char fixed[64];
    for (int k = 0; k <= 17; k++) {
      snprintf(fixed, sizeof fixed, "%.*f", k, x);
      if (strtod(fixed, NULL) == x) {
        snprintf(buf, len, "%s", fixed);
        break;
      }
    }
  }
  /* keep it a floating constant in C */
  if (!strpbrk(buf, ".eEn")) {
    size_t l = strlen(buf);
    if (l + 2 < len) memcpy(buf + l, ".0", 3);
  }
}

const char *val_c(swArena *a, const swValue *v, int i) {
  if (v->c && v->c[i]) return v->c[i];
  char buf[40];
  double x = i < v->n ? v->v[i] : 0;
  if (!isfinite(x)) return "0.0 /* not finite */";
  if (x == 0) return "0.0";   /* also -0.0 */
  format_double(buf, sizeof buf, x);
  if (x < 0) {
    char wrapped[44];
    snprintf(wrapped, sizeof wrapped, "(%s)", buf);
    return ast_strdup(a, wrapped, strlen(wrapped));
  }
  return ast_strdup(a, buf, strlen(buf));
}

#define NOT_POW10 1000

/* k if x == 10^k exactly (as a double), for |k| <= 30; NOT_POW10 otherwise.
 * 10^k is the double strtod reads for "1ek" (correctly rounded, which
 * pow(10, k) need not be), read once into a table: a binary operation with
 * a constant operand asks, and formatting and reading 61 numbers each time
 * was a quarter of the front end's time on the fuzzer's inputs. */
static int power_of_ten(double x) {
  static double pow10[61];
  static int ready;
  if (!ready) {
    for (int k = -30; k <= 30; k++) {
      char buf[16];
      snprintf(buf, sizeof buf, "1e%d", k);
      pow10[k + 30] = strtod(buf, NULL);
    }
    ready = 1;
  }
  if (!(x > 0)) return NOT_POW10;
  for (int k = -30; k <= 30; k++)
    if (x == pow10[k + 30]) return k;
  return NOT_POW10;
}

/* x * 10^k rounded once: the shortest decimal of x with its exponent moved. */
static double decimal_shift(double x, int k) {
  if (!isfinite(x) || x == 0) return x * pow(10, k);
  char buf[64];
  format_double(buf, sizeof buf, x);
  char *e = strpbrk(buf, "eE");
  int exp10 = 0;
  if (e) {
    exp10 = atoi(e + 1);
    *e = 0;
  }
  char shifted[96];
  snprintf(shifted, sizeof shifted, "%se%d", buf, exp10 + k);
  return strtod(shifted, NULL);
}

static void set_c(swArena *a, swValue *r, int i, const char *text) {
  if (!r->c) r->c = ast_alloc(a, (size_t)r->n * sizeof *r->c);
  r->c[i] = ast_strdup(a, text, strlen(text));
}

static const char *op_verb(int op) {
  switch (op) {
  case '+': return "add";
  case '-': return "subtract";
  case '*': return "multiply";
  default: return "divide";
  }
}

const char *val_kind_noun(const swValue *v) {
  switch (v->kind) {
  case VAL_TRUTH: return "true or false";
  case VAL_POINT: return "a point on a rod";
  case VAL_SIGNAL: return "a time signal";
  case VAL_REF: return "a definition";
  case VAL_WORD: return "a name";
  case VAL_VEC: return "a vector";
  default: return "a number";
  }
}

static swValue scale_signal(swArena *a, int op, swValue sig, swValue k, swLoc loc) {
  swSignalVal *s = ast_alloc(a, sizeof *s);
  *s = *sig.sig;
  /* the first scale of a signal replaces its unit scale: P[0], not (1.0 * P[0]) */
  if (op == '*' && s->scale.kind == VAL_NUM && val_is_const(&s->scale) && s->scale.v[0] == 1 &&
      dim_is_none(s->scale.dim) && k.kind != VAL_ERROR)
    s->scale = k;
  else
    s->scale = val_binop(a, op, s->scale, k, loc);
  if (s->scale.kind == VAL_ERROR) return val_error();
  swValue r = sig;
  r.sig = s;
  r.dim = dim_mul(s->scale.dim, s->base);
  r.loc = loc;
  return r;
}

swValue val_binop(swArena *a, int op, swValue x, swValue y, swLoc loc) {
  if (x.kind == VAL_ERROR || y.kind == VAL_ERROR) return val_error();
  /* in arithmetic a point on a rod is its position: insertion - humerus.start
   * is a vector, humerus.end + (1, 0, 0) cm a position on no rod */
  if (x.kind == VAL_POINT) x.kind = VAL_VEC;
  if (y.kind == VAL_POINT) y.kind = VAL_VEC;
  if (op == '*' && x.kind == VAL_SIGNAL && (y.kind == VAL_NUM || y.kind == VAL_VEC))
    return scale_signal(a, '*', x, y, loc);
  if (op == '*' && y.kind == VAL_SIGNAL && (x.kind == VAL_NUM || x.kind == VAL_VEC))
    return scale_signal(a, '*', y, x, loc);
  if (op == '/' && x.kind == VAL_SIGNAL && y.kind == VAL_NUM)
    return scale_signal(a, '/', x, y, loc);
  if (x.kind == VAL_SIGNAL || y.kind == VAL_SIGNAL) {
    diag_error(loc, "cannot %s %s and %s here: a time signal is only scaled where it is used; "
               "combine signals in a signal declaration, signal NAME(t) = ...;", op_verb(op),
               val_kind_noun(&x), val_kind_noun(&y));
    return val_error();
  }
  if ((x.kind != VAL_NUM && x.kind != VAL_VEC) || (y.kind != VAL_NUM && y.kind != VAL_VEC)) {
    diag_error(loc, "cannot %s %s and %s", op_verb(op),
               val_kind_noun(&x), val_kind_noun(&y));
    return val_error();
  }
  swDim dim;
  if (op == '+' || op == '-') {
    if (!dim_eq(x.dim, y.dim)) {
      diag_error(loc, "cannot %s %s and %s", op_verb(op), dim_describe(a, x.dim),
                 dim_describe(a, y.dim));
      return val_error();
    }
    if (x.n != y.n) {
      diag_error(loc, "cannot %s a %d-component and a %d-component value", op_verb(op), x.n, y.n);
      return val_error();
    }
    dim = x.dim;
  } else {
    if (x.n > 1 && y.n > 1) {
      diag_error(loc, "cannot %s two vectors", op_verb(op));
      return val_error();
    }
    if (op == '/' && y.n > 1) {
      diag_error(loc, "cannot divide by a vector");
      return val_error();
    }
    dim = op == '*' ? dim_mul(x.dim, y.dim) : dim_div(x.dim, y.dim);
  }
  int n = x.n > y.n ? x.n : y.n;
  swValue r = val_vec(a, n, NULL, dim, loc);
  int shift_y = (op == '*' || op == '/') && y.n == 1 && val_is_const(&y) ? power_of_ten(y.v[0]) : NOT_POW10;
  int shift_x = op == '*' && x.n == 1 && val_is_const(&x) ? power_of_ten(x.v[0]) : NOT_POW10;
  r.param = x.param ? x.param : y.param;
  int divzero = 0;
  for (int i = 0; i < n; i++) {
    double p = x.v[x.n > 1 ? i : 0], q = y.v[y.n > 1 ? i : 0];
    switch (op) {
    case '+': r.v[i] = p + q; break;
    case '-': r.v[i] = p - q; break;
    case '*': r.v[i] = p * q; break;
    default:
      if (q == 0) divzero = 1;
      r.v[i] = q != 0 ? p / q : 0;
      break;
    }
    /* a unit scale 10^k shifts the decimal exponent exactly: 20 us is the
     * double nearest 2e-5, not 20 * 1e-6 rounded twice */
    if (shift_y != NOT_POW10) r.v[i] = decimal_shift(p, op == '*' ? shift_y : -shift_y);
    else if (shift_x != NOT_POW10) r.v[i] = decimal_shift(q, shift_x);
    int ix = x.n > 1 ? i : 0, iy = y.n > 1 ? i : 0;
    const char *cx = x.c ? x.c[ix] : NULL, *cy = y.c ? y.c[iy] : NULL;
    /* identities keep the C short (x + 0, x - 0, x * 1, x / 1: x; x * 0: 0),
       exact for the finite values a model's geometry has */
    if (cx && !cy && (((op == '+' || op == '-') && q == 0) || ((op == '*' || op == '/') && q == 1))) {
      set_c(a, &r, i, cx);
      continue;
    }
    if (cy && !cx && ((op == '+' && p == 0) || (op == '*' && p == 1))) {
      set_c(a, &r, i, cy);
      continue;
    }
    if (op == '*' && ((cx && !cy && q == 0) || (cy && !cx && p == 0))) continue;
    if (cx || cy) {
      char buf[4096];
      int len = snprintf(buf, sizeof buf, "(%s %c %s)", val_c(a, &x, ix), op, val_c(a, &y, iy));
      if (len >= (int)sizeof buf) {
        diag_error(loc, "expression is too long to generate");
        return val_error();
      }
      set_c(a, &r, i, buf);
    }
  }
  if (divzero) {
    diag_error(loc, "division by zero");
    return val_error();
  }
  return r;
}

swValue val_neg(swArena *a, swValue x, swLoc loc) {
  if (x.kind == VAL_POINT) x.kind = VAL_VEC;
  if (x.kind == VAL_SIGNAL) {
    swValue m1 = val_num(a, -1, DIM_NONE, loc);
    return val_binop(a, '*', x, m1, loc);
  }
  if (x.kind != VAL_NUM && x.kind != VAL_VEC) {
    if (x.kind != VAL_ERROR) diag_error(loc, "cannot negate %s", val_kind_noun(&x));
    return val_error();
  }
  swValue m1 = val_num(a, -1, DIM_NONE, loc);
  return val_binop(a, '*', m1, x, loc);
}

swValue val_pow(swArena *a, swValue x, double p, swLoc loc) {
  if (x.kind == VAL_ERROR) return x;
  if (x.kind != VAL_NUM) {
    diag_error(loc, "cannot raise %s to a power", val_kind_noun(&x));
    return val_error();
  }
  swDim dim;
  if (!dim_pow(x.dim, p, &dim)) {
    diag_error(loc, "%s can only be raised to an integer power, not %g", dim_describe(a, x.dim), p);
    return val_error();
  }
  double r = pow(x.v[0], p);
  int k = power_of_ten(x.v[0]);
  if (k != NOT_POW10 && p == floor(p) && fabs(k * p) <= 300) r = decimal_shift(1.0, (int)(k * p));
  if (!isfinite(r) && isfinite(x.v[0])) {   /* NaN: known at the end of a run */
    diag_error(loc, "the power is not a finite number");
    return val_error();
  }
  swValue v = val_num(a, r, dim, loc);
  v.param = x.param;
  if (x.c && x.c[0]) {
    char buf[4096];
    if (snprintf(buf, sizeof buf, "pow(%s, %.17g)", x.c[0], p) >= (int)sizeof buf) {
      diag_error(loc, "expression is too long to generate");
      return val_error();
    }
    set_c(a, &v, 0, buf);
  }
  return v;
}

swValue val_func(swArena *a, const char *fn, swValue x, swLoc loc) {
  if (x.kind == VAL_ERROR) return x;
  if (x.kind != VAL_NUM) {
    diag_error(loc, "%s() takes a number, not %s", fn, val_kind_noun(&x));
    return val_error();
  }
  swDim dim = DIM_NONE;
  double r;
  if (!strcmp(fn, "sqrt")) {
    for (int i = 0; i < SW_NDIM; i++) {
      if (x.dim.e[i] % 2) {
        diag_error(loc, "sqrt() of %s has no dimension", dim_describe(a, x.dim));
        return val_error();
      }
      dim.e[i] = (signed char)(x.dim.e[i] / 2);
    }
    if (x.v[0] < 0) {
      diag_error(loc, "sqrt() of a negative number");
      return val_error();
    }
    r = sqrt(x.v[0]);
  } else if (!strcmp(fn, "log")) {
    if (!dim_is_none(x.dim)) {
      diag_error(loc, "log() takes a plain number, not %s", dim_describe(a, x.dim));
      return val_error();
    }
    if (!(x.v[0] > 0)) {
      diag_error(loc, "log() of %g: the logarithm takes a positive number", x.v[0]);
      return val_error();
    }
    r = log(x.v[0]);
  } else if (!strcmp(fn, "exp")) {
    if (!dim_is_none(x.dim)) {
      diag_error(loc, "exp() takes a plain number, not %s", dim_describe(a, x.dim));
      return val_error();
    }
    r = exp(x.v[0]);
    if (!isfinite(r) && !isnan(x.v[0])) {
      diag_error(loc, "exp() of %g is not a finite number", x.v[0]);
      return val_error();
    }
  } else {
    if (!dim_is_none(x.dim) && !dim_eq(x.dim, DIM_ANGLE)) {
      diag_error(loc, "%s() takes an angle or a plain number, not %s", fn,
                 dim_describe(a, x.dim));
      return val_error();
    }
    /* a plain number is taken in radians; `let slope = 5;` meant as degrees
     * would turn silently by 286 deg, so say which it is */
    if (dim_is_none(x.dim))
      diag_warning(loc, "%s() of the plain number %g takes it in radians (%g deg); give the "
                   "angle its unit: %g rad, or %g deg if degrees were meant", fn, x.v[0],
                   x.v[0] * 180 / M_PI, x.v[0], x.v[0]);
    r = !strcmp(fn, "sin") ? sin(x.v[0]) : !strcmp(fn, "cos") ? cos(x.v[0]) : tan(x.v[0]);
  }
  swValue v = val_num(a, r, dim, loc);
  v.param = x.param;
  if (x.c && x.c[0]) {
    char buf[4096];
    if (snprintf(buf, sizeof buf, "%s(%s)", fn, x.c[0]) >= (int)sizeof buf) {
      diag_error(loc, "expression is too long to generate");
      return val_error();
    }
    set_c(a, &v, 0, buf);
  }
  return v;
}

swValue val_norm(swArena *a, swValue x, swLoc loc) {
  if (x.kind == VAL_ERROR) return x;
  swValue sum = val_num(a, 0, dim_mul(x.dim, x.dim), loc);
  for (int i = 0; i < x.n; i++) {
    swValue xi = val_num(a, x.v[i], x.dim, loc);
    if (x.c && x.c[i]) {
      xi.c = ast_alloc(a, sizeof *xi.c);
      xi.c[0] = x.c[i];
      xi.param = x.param;
    }
    sum = val_binop(a, '+', sum, val_binop(a, '*', xi, xi, loc), loc);
  }
  return val_func(a, "sqrt", sum, loc);
}
