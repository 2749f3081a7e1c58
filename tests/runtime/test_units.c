/* test_units.c — tests of units.c: the unit table, the parser of quantities,
 * its error messages (by exact text) and the names of dimensions.
 *
 * Design.  Expected SI values are written as decimal literals, and quantities
 * whose units are powers of ten are required to equal them exactly: the parser
 * promises a single rounding ("1.75 g/cm^3" is 1750, not 1750.0000000000002),
 * so a value passed on the command line compares equal to the same value in
 * SI.  Units that are not powers of ten (deg, min, h) get a relative tolerance
 * of one rounding. */
#include "testutil.h"

#define PI 3.14159265358979323846

typedef struct {
  const char *text;
  double si;
  signed char dim[SW_NDIM]; /* kg m s rad */
} swQuantityCase;

/* ---- the table ---- */

static void test_unit_find(void **state) {
  (void)state;
  static const swQuantityCase cases[] = {
    {"m", 1, {0, 1, 0, 0}},       {"mm", 1e-3, {0, 1, 0, 0}},   {"cm", 1e-2, {0, 1, 0, 0}},
    {"um", 1e-6, {0, 1, 0, 0}},   {"nm", 1e-9, {0, 1, 0, 0}},   {"km", 1e3, {0, 1, 0, 0}},
    {"kg", 1, {1, 0, 0, 0}},      {"g", 1e-3, {1, 0, 0, 0}},    {"mg", 1e-6, {1, 0, 0, 0}},
    {"s", 1, {0, 0, 1, 0}},       {"ms", 1e-3, {0, 0, 1, 0}},   {"us", 1e-6, {0, 0, 1, 0}},
    {"ns", 1e-9, {0, 0, 1, 0}},   {"min", 60, {0, 0, 1, 0}},
    {"N", 1, {1, 1, -2, 0}},      {"mN", 1e-3, {1, 1, -2, 0}},  {"uN", 1e-6, {1, 1, -2, 0}},
    {"kN", 1e3, {1, 1, -2, 0}},
    {"Pa", 1, {1, -1, -2, 0}},    {"kPa", 1e3, {1, -1, -2, 0}}, {"MPa", 1e6, {1, -1, -2, 0}},
    {"GPa", 1e9, {1, -1, -2, 0}},
    {"J", 1, {1, 2, -2, 0}},      {"mJ", 1e-3, {1, 2, -2, 0}},  {"W", 1, {1, 2, -3, 0}},
    {"Hz", 1, {0, 0, -1, 0}},     {"kHz", 1e3, {0, 0, -1, 0}},
    {"rad", 1, {0, 0, 0, 1}},     {"mrad", 1e-3, {0, 0, 0, 1}}, {"deg", PI / 180, {0, 0, 0, 1}},
    {"\xc2\xb5m", 1e-6, {0, 1, 0, 0}}, {"\xc2\xb5s", 1e-6, {0, 0, 1, 0}},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    const swUnit *u = sw_unit_find(cases[i].text, strlen(cases[i].text));
    if (!u) fprintf(stderr, "# %s: unit '%s' not found\n", __func__, cases[i].text);
    assert_non_null(u);
    assert_string_equal(u->name, cases[i].text);
    assert_true(u->scale == cases[i].si);
    assert_memory_equal(u->dim, cases[i].dim, SW_NDIM);
  }
  /* length-delimited: "kPa" inside a longer text, and its prefixes */
  const char *text = "kPa/m";
  assert_string_equal(sw_unit_find(text, 3)->name, "kPa");
  assert_null(sw_unit_find(text, 1));                 /* "k" */
  assert_string_equal(sw_unit_find("mmHg", 2)->name, "mm");
  assert_null(sw_unit_find("sec", 3));
  assert_null(sw_unit_find("MPA", 3));
  assert_null(sw_unit_find("m", 0));
  assert_null(sw_unit_find(NULL, 1));
}

/* Every entry is found under its own name, once; scales are positive. */
static void test_unit_table(void **state) {
  (void)state;
  int count = -1;
  const swUnit *table = sw_unit_table(&count);
  fprintf(stderr, "# %s: %d units in the table\n", __func__, count);
  assert_non_null(table);
  assert_true(count >= 30);
  for (int i = 0; i < count; i++) {
    assert_true(table[i].scale > 0 && isfinite(table[i].scale));
    assert_ptr_equal(sw_unit_find(table[i].name, strlen(table[i].name)), &table[i]);
    for (int j = 0; j < i; j++) assert_string_not_equal(table[i].name, table[j].name);
  }
  assert_non_null(sw_unit_table(NULL));
}

/* ---- quantities ---- */

static void expect_quantity(const swQuantityCase *c, double rtol) {
  double si = -12345;
  signed char dim[SW_NDIM] = {9, 9, 9, 9};
  char err[256] = "?";
  int rc = sw_parse_quantity(c->text, &si, dim, err, sizeof err);
  fprintf(stderr, "# \"%s\" -> rc %d, %.17g [%d %d %d %d] %s\n", c->text, rc, si, dim[0], dim[1],
          dim[2], dim[3], err);
  assert_int_equal(rc, 0);
  assert_string_equal(err, "");
  if (rtol == 0) assert_true(si == c->si);
  else assert_true(fabs(si - c->si) <= rtol * fabs(c->si));
  assert_memory_equal(dim, c->dim, SW_NDIM);
}

static void test_parse_quantity(void **state) {
  (void)state;
  /* exact: decimal units */
  static const swQuantityCase exact[] = {
    {"0.3 m", 0.3, {0, 1, 0, 0}},
    {"1.75 g/cm^3", 1750, {1, -3, 0, 0}},
    {"1.06 g/cm^3", 1060, {1, -3, 0, 0}},
    {"50ns", 50e-9, {0, 0, 1, 0}},
    {"10 kPa", 1e4, {1, -1, -2, 0}},
    {"15 GPa", 15e9, {1, -1, -2, 0}},
    {"10.5 mm", 10.5e-3, {0, 1, 0, 0}},
    {"-2", -2, {0, 0, 0, 0}},
    {"+.5e1 mm", 5e-3, {0, 1, 0, 0}},
    {"1.e2cm", 1, {0, 1, 0, 0}},
    {"1e-3", 1e-3, {0, 0, 0, 0}},
    {"  7  ", 7, {0, 0, 0, 0}},
    {"10 N/m", 10, {1, 0, -2, 0}},
    {"1 kg m^-3", 1, {1, -3, 0, 0}},
    {"9.81 m/s^2", 9.81, {0, 1, -2, 0}},
    {"5 N m", 5, {1, 2, -2, 0}},
    {"5 N*m", 5, {1, 2, -2, 0}},
    {"5 N\xc2\xb7m", 5, {1, 2, -2, 0}},   /* N·m */
    {"5e5 N/m", 5e5, {1, 0, -2, 0}},
    {"2 kg/m/s", 2, {1, -1, -1, 0}},      /* '/' takes one factor: kg m^-1 s^-1 */
    {"3 m / s", 3, {0, 1, -1, 0}},
    {"2 Hz", 2, {0, 0, -1, 0}},
    {"4 rad/s", 4, {0, 0, -1, 1}},
    {"7 mrad", 7e-3, {0, 0, 0, 1}},
    {"1 N m/rad", 1, {1, 2, -2, -1}},
    {"3 m^+2", 3, {0, 2, 0, 0}},
    {"2 mN", 2e-3, {1, 1, -2, 0}},
    {"2 \xc2\xb5m", 2e-6, {0, 1, 0, 0}},  /* µm */
    {"2 \xce\xbcs", 2e-6, {0, 0, 1, 0}},  /* μs, Greek mu */
    {"1e-400 m", 0, {0, 1, 0, 0}},        /* underflows to 0 */
    {"0.5 kHz", 500, {0, 0, -1, 0}},
    {"2/s", 2, {0, 0, -1, 0}},            /* a rate, as a model writes 2 / s */
    {"0.5 / s", 0.5, {0, 0, -1, 0}},
    {"3/m/s", 3, {0, -1, -1, 0}},
  };
  for (size_t i = 0; i < sizeof exact / sizeof exact[0]; i++) expect_quantity(&exact[i], 0);
  /* one rounding after the decimal conversion */
  static const swQuantityCase rounded[] = {
    {"30 deg", PI / 6, {0, 0, 0, 1}},
    {"2 min", 120, {0, 0, 1, 0}},
    {"1.5 h", 5400, {0, 0, 1, 0}},
    {"90 deg/s", PI / 2, {0, 0, -1, 1}},
    {"1 deg^2", PI * PI / (180.0 * 180.0), {0, 0, 0, 2}},
  };
  for (size_t i = 0; i < sizeof rounded / sizeof rounded[0]; i++)
    expect_quantity(&rounded[i], 4e-16);

  /* optional outputs */
  assert_int_equal(sw_parse_quantity("3 m", NULL, NULL, NULL, 0), 0);
}

static void expect_error(const char *text, const char *message) {
  double si = -12345;
  signed char dim[SW_NDIM] = {9, 9, 9, 9};
  char err[256] = "";
  int rc = sw_parse_quantity(text, &si, dim, err, sizeof err);
  fprintf(stderr, "# \"%s\" -> rc %d: %s\n", text ? text : "(null)", rc, err);
  assert_int_not_equal(rc, 0);
  assert_string_equal(err, message);
  /* outputs untouched on error */
  assert_true(si == -12345);
  assert_true(dim[0] == 9 && dim[3] == 9);
}

static void test_parse_errors(void **state) {
  (void)state;
  expect_error("", "expected a number in ''");
  expect_error("   ", "expected a number in '   '");
  expect_error("kg m^-3", "expected a number in 'kg m^-3'");
  expect_error("inf", "expected a number in 'inf'");
  expect_error("nan", "expected a number in 'nan'");
  expect_error("+-1", "expected a number in '+-1'");
  expect_error(".", "expected a number in '.'");
  expect_error(NULL, "expected a number, got nothing");
  expect_error("5 sec", "unknown unit 'sec' in '5 sec'");
  expect_error("5 MPA", "unknown unit 'MPA' in '5 MPA' (did you mean 'MPa'?)");
  expect_error("1 g/cc", "unknown unit 'cc' in '1 g/cc'");
  expect_error("0x10", "unknown unit 'x' in '0x10'");
  expect_error("1,5 s", "unexpected ',5 s' in '1,5 s'");
  expect_error("5 m2", "unexpected '2' in '5 m2' (powers are written m^2)");
  expect_error("2ms3", "unexpected '3' in '2ms3' (powers are written ms^3)");
  expect_error("5 m (tip)", "unexpected '(tip)' in '5 m (tip)'");
  expect_error("5 m/", "expected a unit after '/' in '5 m/'");
  expect_error("5 m/ 3", "expected a unit after '/' in '5 m/ 3'");
  expect_error("5 /", "expected a unit after '/' in '5 /'");
  expect_error("5 N*", "expected a unit after '*' in '5 N*'");
  expect_error("5 m^", "expected an integer exponent after '^' in '5 m^'");
  expect_error("5 m^x", "expected an integer exponent after '^' in '5 m^x'");
  expect_error("5 m^13", "exponent out of range in '5 m^13'");
  expect_error("1 m^12 m^12 m", "exponent out of range in '1 m^12 m^12 m'");
  expect_error("1e999", "number out of range in '1e999'");
  expect_error("1e300 km^3", "number out of range in '1e300 km^3'");

  /* a short buffer is truncated, not overrun; no buffer is fine */
  char small[8];
  assert_int_not_equal(sw_parse_quantity("5 sec", NULL, NULL, small, sizeof small), 0);
  assert_string_equal(small, "unknown");
  assert_int_not_equal(sw_parse_quantity("5 sec", NULL, NULL, NULL, 0), 0);
}

/* ---- names of dimensions ---- */

static void test_dim_describe(void **state) {
  (void)state;
  static const struct {
    signed char dim[SW_NDIM];
    const char *text;
  } cases[] = {
    {{0, 1, 0, 0}, "length (m)"},
    {{1, 0, 0, 0}, "mass (kg)"},
    {{0, 0, 1, 0}, "time (s)"},
    {{0, 0, 0, 1}, "angle (rad)"},
    {{1, -1, -2, 0}, "pressure (Pa)"},
    {{1, 1, -2, 0}, "force (N)"},
    {{1, -3, 0, 0}, "density (kg/m^3)"},
    {{0, 1, -1, 0}, "velocity (m/s)"},
    {{0, 1, -2, 0}, "acceleration (m/s^2)"},
    {{0, 0, -1, 0}, "frequency (Hz)"},
    {{0, 0, -1, 1}, "angular velocity (rad/s)"},
    {{1, 0, -2, 0}, "stiffness (N/m)"},
    {{1, 2, -2, 0}, "torque or energy (N m)"},
    {{0, 2, 0, 0}, "area (m^2)"},
    {{0, -1, 0, 0}, "curvature (1/m)"},
    {{1, 2, -2, -1}, "rotational stiffness (N m/rad)"},
    {{0, 0, 0, 0}, "dimensionless"},
    {{1, -1, -3, 0}, "kg m^-1 s^-3"},
    {{0, 1, 0, 2}, "m rad^2"},
    {{-1, 0, 4, 0}, "kg^-1 s^4"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char buf[64];
    const char *text = sw_dim_describe(buf, sizeof buf, cases[i].dim);
    fprintf(stderr, "# [%d %d %d %d] -> %s\n", cases[i].dim[0], cases[i].dim[1], cases[i].dim[2],
            cases[i].dim[3], text);
    assert_ptr_equal(text, buf);
    assert_string_equal(text, cases[i].text);
  }
  /* every dimension a unit of the table has gets a name */
  int count;
  const swUnit *table = sw_unit_table(&count);
  for (int i = 0; i < count; i++) {
    char buf[64];
    sw_dim_describe(buf, sizeof buf, table[i].dim);
    assert_non_null(strchr(buf, '('));
  }
  /* truncation */
  char small[6];
  signed char odd[SW_NDIM] = {1, -1, -3, 0};
  assert_string_equal(sw_dim_describe(small, sizeof small, odd), "kg m^");
}

/* ---- quantities and sw_parse_time agree ---- */

static void test_parse_time_on_units(void **state) {
  (void)state;
  double t = -1;
  assert_int_equal(sw_parse_time("1.5 h", &t), 0);
  assert_true(t == 5400);
  assert_int_equal(sw_parse_time("50 ns", &t), 0);
  assert_true(t == 50e-9);
  assert_int_equal(sw_parse_time("-0", &t), 0);
  assert_true(t == 0 && !signbit(t));
  t = -1;
  assert_int_not_equal(sw_parse_time("3 Hz", &t), 0);
  assert_int_not_equal(sw_parse_time("3 s^2", &t), 0);
  assert_int_not_equal(sw_parse_time("30 deg", &t), 0);
  assert_true(t == -1);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_unit_find),
    cmocka_unit_test(test_unit_table),
    cmocka_unit_test(test_parse_quantity),
    cmocka_unit_test(test_parse_errors),
    cmocka_unit_test(test_dim_describe),
    cmocka_unit_test(test_parse_time_on_units),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
