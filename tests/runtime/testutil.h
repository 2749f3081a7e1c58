/* testutil.h — shared helpers for the runtime tests (cmocka, TAP output).
 *
 * Every physics test prints the figure it measured on stderr as
 *   # test_name: quantity = value (reference r, error e, tolerance t)
 * so the numbers appear in `make test` output next to pass/fail.  Tests
 * that take long read SW_SANITIZED and shrink their sizes when it is set, so
 * that the sanitizer build exercises the same code in reasonable time. */
#ifndef SW_TESTUTIL_H
#define SW_TESTUTIL_H
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <cmocka.h>
#include "sinew.h"

static inline int sw_test_sanitized(void) {
  const char *s = getenv("SW_SANITIZED");
  return s && *s && *s != '0';
}

/* Print a measured figure and assert it is within tolerance. */
#define SW_EXPECT_REL(what, measured, reference, tol)                              \
  do {                                                                            \
    double m_ = (measured), r_ = (reference), e_ = fabs(m_ - r_) / fabs(r_);      \
    fprintf(stderr, "# %s: %s = %.9g (reference %.9g, rel. error %.3e, tol %.1e)\n", \
            __func__, (what), m_, r_, e_, (double)(tol));                         \
    assert_true(e_ <= (tol));                                                     \
  } while (0)

#define SW_EXPECT_ABS(what, measured, reference, tol)                              \
  do {                                                                            \
    double m_ = (measured), r_ = (reference), e_ = fabs(m_ - r_);                 \
    fprintf(stderr, "# %s: %s = %.9g (reference %.9g, abs. error %.3e, tol %.1e)\n", \
            __func__, (what), m_, r_, e_, (double)(tol));                         \
    assert_true(e_ <= (tol));                                                     \
  } while (0)

static inline swModel *sw_test_compile(swSpec *s) {
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  if (!m) fprintf(stderr, "# compile failed: %s\n", err);
  assert_non_null(m);
  return m;
}
#endif
