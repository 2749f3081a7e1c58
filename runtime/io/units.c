/* units.c — the one table of unit names, the parser of quantities ("1.75
 * g/cm^3", "50ns", "10 N/m") and the names of dimensions for messages.
 *
 * Design.  A unit is a name, its value in SI and its exponents over (kg, m,
 * s, rad); the angle is a dimension of its own, so "30 deg" cannot be passed
 * where a dimensionless number is expected and "N m/rad" is not "N m".  The
 * table is the only place unit names are spelt; the compiler reads it through
 * sw_unit_table(), the command line through sw_parse_quantity().  A quantity
 * is a decimal number (no hex, inf or nan) optionally followed, with or
 * without a space, by a unit expression: factors separated by '/', '*', '·'
 * or a space, each optionally raised to an integer power ("kg m^-3",
 * "m/s^2"), or begun by '/' for a rate ("2/s", as a model writes 2 / s).
 * A space binds tighter than '/' and '*', as juxtaposition does in a model:
 * "N/m s" is N/(m s), "kg/m/s" is kg m^-1 s^-1.  Conversion is done in
 * decimal where it can be: units whose scale is a power of ten shift the
 * number's decimal exponent and the text is converted once by strtod, so
 * "1.75 g/cm^3" is exactly 1750 and "50 ns" is the double nearest 5e-8, as a
 * user who compares with a value in SI expects; only the other factors (deg,
 * min, h) multiply afterwards.
 * Error messages name the offending piece and quote what was written. */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"

#define PI 3.14159265358979323846

/* ---- the table ---- */

/*                        kg  m   s  rad */
#define DIM_LENGTH      { 0,  1,  0,  0}
#define DIM_MASS        { 1,  0,  0,  0}
#define DIM_TIME        { 0,  0,  1,  0}
#define DIM_ANGLE       { 0,  0,  0,  1}
#define DIM_FORCE       { 1,  1, -2,  0}
#define DIM_PRESSURE    { 1, -1, -2,  0}
#define DIM_ENERGY      { 1,  2, -2,  0}
#define DIM_POWER       { 1,  2, -3,  0}
#define DIM_FREQUENCY   { 0,  0, -1,  0}

/* "\xc2\xb5" is the micro sign µ (U+00B5), "\xce\xbc" the Greek letter μ
 * (U+03BC); keyboards produce either. */
static const swUnit units[] = {
  {"m", 1, DIM_LENGTH},      {"km", 1e3, DIM_LENGTH},   {"cm", 1e-2, DIM_LENGTH},
  {"mm", 1e-3, DIM_LENGTH},  {"um", 1e-6, DIM_LENGTH},  {"\xc2\xb5m", 1e-6, DIM_LENGTH},
  {"\xce\xbcm", 1e-6, DIM_LENGTH},                      {"nm", 1e-9, DIM_LENGTH},
  {"kg", 1, DIM_MASS},       {"g", 1e-3, DIM_MASS},     {"mg", 1e-6, DIM_MASS},
  {"s", 1, DIM_TIME},        {"ms", 1e-3, DIM_TIME},    {"us", 1e-6, DIM_TIME},
  {"\xc2\xb5s", 1e-6, DIM_TIME},                        {"\xce\xbcs", 1e-6, DIM_TIME},
  {"ns", 1e-9, DIM_TIME},    {"min", 60, DIM_TIME},     {"h", 3600, DIM_TIME},
  {"N", 1, DIM_FORCE},       {"kN", 1e3, DIM_FORCE},    {"mN", 1e-3, DIM_FORCE},
  {"uN", 1e-6, DIM_FORCE},   {"\xc2\xb5N", 1e-6, DIM_FORCE},
  {"\xce\xbcN", 1e-6, DIM_FORCE},
  {"Pa", 1, DIM_PRESSURE},   {"kPa", 1e3, DIM_PRESSURE}, {"MPa", 1e6, DIM_PRESSURE},
  {"GPa", 1e9, DIM_PRESSURE}, {"mPa", 1e-3, DIM_PRESSURE}, /* viscosities: 1 mPa s */
  {"J", 1, DIM_ENERGY},      {"mJ", 1e-3, DIM_ENERGY},
  {"W", 1, DIM_POWER},
  {"Hz", 1, DIM_FREQUENCY},  {"kHz", 1e3, DIM_FREQUENCY},
  {"rad", 1, DIM_ANGLE},     {"mrad", 1e-3, DIM_ANGLE}, {"deg", PI / 180, DIM_ANGLE},
};
#define NUNITS ((int)(sizeof units / sizeof units[0]))

const swUnit *sw_unit_table(int *count) {
  if (count) *count = NUNITS;
  return units;
}

const swUnit *sw_unit_find(const char *name, size_t len) {
  if (!name) return NULL;
  for (int u = 0; u < NUNITS; u++)
    if (strlen(units[u].name) == len && !memcmp(units[u].name, name, len)) return &units[u];
  return NULL;
}

/* A unit whose name differs from the one written only in case ("MPA"). */
static const swUnit *find_ignoring_case(const char *name, size_t len) {
  for (int u = 0; u < NUNITS; u++) {
    if (strlen(units[u].name) != len) continue;
    size_t i = 0;
    while (i < len && tolower((unsigned char)name[i]) == tolower((unsigned char)units[u].name[i]))
      i++;
    if (i == len) return &units[u];
  }
  return NULL;
}

/* ---- names of dimensions ---- */

static const struct {
  signed char dim[SW_NDIM];
  const char *name;
} dim_names[] = {
  {{0, 0, 0, 0}, "dimensionless"},
  {DIM_LENGTH, "length (m)"},
  {DIM_MASS, "mass (kg)"},
  {DIM_TIME, "time (s)"},
  {DIM_ANGLE, "angle (rad)"},
  {DIM_PRESSURE, "pressure (Pa)"},          /* also stress and elastic moduli */
  {DIM_FORCE, "force (N)"},
  {{1, -3, 0, 0}, "density (kg/m^3)"},
  {{0, 1, -1, 0}, "velocity (m/s)"},
  {{0, 1, -2, 0}, "acceleration (m/s^2)"},
  {DIM_FREQUENCY, "frequency (Hz)"},
  {{0, 0, -1, 1}, "angular velocity (rad/s)"},
  {{0, 0, -2, 1}, "angular acceleration (rad/s^2)"},
  {{1, 0, -2, 0}, "stiffness (N/m)"},
  /* a couple and an energy share kg m^2 s^-2; N m is the SI unit of both */
  {DIM_ENERGY, "torque or energy (N m)"},
  {DIM_POWER, "power (W)"},
  {{0, 2, 0, 0}, "area (m^2)"},
  {{0, 3, 0, 0}, "volume (m^3)"},
  {{0, -1, 0, 0}, "curvature (1/m)"},
  {{1, 0, -1, 0}, "damping (N s/m)"},
  {{1, -1, -1, 0}, "viscosity (Pa s)"},       /* the rods' gamma, kg m^-1 s^-1 */
  {{1, 3, -2, 0}, "bending stiffness (N m^2)"},
  {{1, 2, -2, -1}, "rotational stiffness (N m/rad)"},
  {{1, 2, -1, -1}, "rotational damping (N m s/rad)"},
  {{1, 1, -1, -1}, "rotational damping per length (N s/rad)"}, /* a rod's gamma_rot */
  {{1, -1, 0, 0}, "linear density (kg/m)"},
  {{1, 2, 0, 0}, "moment of inertia (kg m^2)"},
};

const char *sw_dim_describe(char *buf, size_t len, const signed char dim[SW_NDIM]) {
  static const char *const base[SW_NDIM] = {"kg", "m", "s", "rad"};
  if (!buf || !len) return buf;
  buf[0] = '\0';
  if (!dim) return buf;
  for (size_t k = 0; k < sizeof dim_names / sizeof dim_names[0]; k++)
    if (!memcmp(dim_names[k].dim, dim, SW_NDIM)) {
      snprintf(buf, len, "%s", dim_names[k].name);
      return buf;
    }
  size_t used = 0;
  for (int k = 0; k < SW_NDIM && used < len; k++) {
    if (!dim[k]) continue;
    int n = dim[k] == 1 ? snprintf(buf + used, len - used, "%s%s", used ? " " : "", base[k])
                        : snprintf(buf + used, len - used, "%s%s^%d", used ? " " : "", base[k],
                                   dim[k]);
    if (n < 0) break;
    used += (size_t)n;
  }
  return buf;
}

/* ---- quantities ---- */

/* Largest power a factor may carry, and largest exponent of a result. */
#define MAX_FACTOR_POWER 12
#define MAX_DIM 24

/* Format a message into err (if given); returns 1, the failure code. */
static int fail(char *err, size_t errlen, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int fail(char *err, size_t errlen, const char *fmt, ...) {
  if (!err || !errlen) return 1;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, errlen, fmt, ap);
  va_end(ap);
  return 1;
}

/* A unit name: ASCII letters and any UTF-8 sequence except the middle dot
 * "·" (U+00B7, "\xc2\xb7"), which is a multiplication sign. */
static int is_middle_dot(const char *p) {
  return (unsigned char)p[0] == 0xc2 && (unsigned char)p[1] == 0xb7;
}
static int is_name_char(const char *p) {
  unsigned char c = (unsigned char)*p;
  return isalpha(c) || (c >= 0x80 && !is_middle_dot(p));
}

/* Length of the decimal number at p: [+-] digits [. digits] [(e|E) [+-] digits],
 * with at least one digit before the exponent; 0 if there is none.  Sets
 * *exp_at to the offset of the 'e' (or the length when there is none). */
static size_t scan_number(const char *p, size_t *exp_at) {
  size_t i = 0, digits = 0;
  if (p[i] == '+' || p[i] == '-') i++;
  while (isdigit((unsigned char)p[i])) i++, digits++;
  if (p[i] == '.') {
    i++;
    while (isdigit((unsigned char)p[i])) i++, digits++;
  }
  if (!digits) return 0;
  *exp_at = i;
  if (p[i] == 'e' || p[i] == 'E') {
    size_t j = i + 1;
    if (p[j] == '+' || p[j] == '-') j++;
    if (isdigit((unsigned char)p[j])) {
      while (isdigit((unsigned char)p[j])) j++;
      i = j;
    }
  }
  return i;
}

/* The exact decimal exponent of a scale that is a power of ten, or 0 with
 * *is_decimal cleared for any other scale. */
static int decimal_exponent(double scale, int *is_decimal) {
  char text[16];
  int p10 = (int)lround(log10(scale));
  snprintf(text, sizeof text, "1e%d", p10);
  *is_decimal = strtod(text, NULL) == scale;
  return *is_decimal ? p10 : 0;
}

int sw_parse_quantity(const char *text, double *si, signed char dim[SW_NDIM], char *err,
                      size_t errlen) {
  if (err && errlen) err[0] = '\0';
  if (!text) return fail(err, errlen, "expected a number, got nothing");
  const char *p = text;
  while (isspace((unsigned char)*p)) p++;
  size_t exp_at = 0, num_len = scan_number(p, &exp_at);
  if (!num_len) return fail(err, errlen, "expected a number in '%s'", text);
  const char *number = p;
  long number_exp = exp_at < num_len ? strtol(number + exp_at + 1, NULL, 10) : 0;
  if (number_exp > 100000) number_exp = 100000;
  if (number_exp < -100000) number_exp = -100000;
  p += num_len;

  /* the unit expression: factor { ('/' | '*' | '·' | ' ') factor } */
  int power[SW_NDIM] = {0};
  long shift = 0;            /* decimal exponent contributed by the units  */
  double factor = 1.0;       /* product of the other scales               */
  int denominator = 0;       /* the factor being read follows a '/'       */
  const char *op = NULL;     /* the operator before it, for messages      */
  while (isspace((unsigned char)*p)) p++;
  if (*p == '/') {
    /* a rate as a model writes it: "2/s", "0.5 / s" (the number over the
     * unit) */
    denominator = 1;
    op = "/";
    p++;
    while (isspace((unsigned char)*p)) p++;
    if (!*p) return fail(err, errlen, "expected a unit after '/' in '%s'", text);
  }
  while (*p) {
    /* factor: name [ '^' integer ] */
    const char *name = p;
    while (*p && is_name_char(p)) p++;
    int name_len = (int)(p - name);
    if (!name_len) {
      if (op) return fail(err, errlen, "expected a unit after '%s' in '%s'", op, text);
      return fail(err, errlen, "unexpected '%s' in '%s'", name, text);
    }
    const swUnit *u = sw_unit_find(name, (size_t)name_len);
    if (!u) {
      const swUnit *like = find_ignoring_case(name, (size_t)name_len);
      if (like)
        return fail(err, errlen, "unknown unit '%.*s' in '%s' (did you mean '%s'?)", name_len,
                    name, text, like->name);
      return fail(err, errlen, "unknown unit '%.*s' in '%s'", name_len, name, text);
    }
    long e = 1;
    if (*p == '^') {
      const char *q = p + 1;
      char *end;
      if (*q == '+' || *q == '-') q++;
      if (!isdigit((unsigned char)*q))
        return fail(err, errlen, "expected an integer exponent after '^' in '%s'", text);
      e = strtol(p + 1, &end, 10);
      if (e > MAX_FACTOR_POWER || e < -MAX_FACTOR_POWER)
        return fail(err, errlen, "exponent out of range in '%s'", text);
      p = end;
    }
    if (denominator) e = -e;
    for (int k = 0; k < SW_NDIM; k++) power[k] += (int)e * u->dim[k];
    int is_decimal;
    int p10 = decimal_exponent(u->scale, &is_decimal);
    if (is_decimal) shift += (long)p10 * e;
    else factor *= pow(u->scale, (double)e);

    /* what separates this factor from the next */
    const char *after = p;
    while (isspace((unsigned char)*p)) p++;
    if (!*p) break;
    if (*p == '/' || *p == '*' || is_middle_dot(p)) {
      denominator = *p == '/';
      op = denominator ? "/" : *p == '*' ? "*" : "\xc2\xb7";
      p += is_middle_dot(p) ? 2 : 1;
      while (isspace((unsigned char)*p)) p++;
      if (!*p) return fail(err, errlen, "expected a unit after '%s' in '%s'", op, text);
    } else if (p > after && is_name_char(p)) {
      /* a space multiplies but binds tighter than '/', as in a model:
       * "N/m s" is N/(m s), the denominator goes on */
      op = " ";
    } else if (p == after && strspn(p, "0123456789") == strlen(p)) {
      return fail(err, errlen, "unexpected '%s' in '%s' (powers are written %.*s^%s)", p, text,
                  name_len, name, p);
    } else {
      return fail(err, errlen, "unexpected '%s' in '%s'", p, text);
    }
  }
  for (int k = 0; k < SW_NDIM; k++)
    if (power[k] > MAX_DIM || power[k] < -MAX_DIM)
      return fail(err, errlen, "exponent out of range in '%s'", text);

  /* the number with the units' decimal exponent folded into its own, read
   * once: a single rounding */
  long total_exp = number_exp + shift;
  int mantissa_len = (int)exp_at;
  size_t size = (size_t)mantissa_len + 24;
  char *decimal = malloc(size);
  if (!decimal) return fail(err, errlen, "out of memory reading '%s'", text);
  snprintf(decimal, size, "%.*se%ld", mantissa_len, number, total_exp);
  double value = strtod(decimal, NULL) * factor;
  free(decimal);
  if (!isfinite(value)) return fail(err, errlen, "number out of range in '%s'", text);
  if (si) *si = value;
  if (dim)
    for (int k = 0; k < SW_NDIM; k++) dim[k] = (signed char)power[k];
  return 0;
}
