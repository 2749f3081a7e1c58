#!/bin/sh
# test_terrain.sh — a terrain's height(x, y) and its gradient: the C function
# sinewc generates (forward-mode dual numbers) against the compiler's own
# evaluator (sinewc --eval-height) and against central finite differences of
# the generated height; and a param reaching the height through ctx.
#
# The model uses every operation a height may: lets over x and y,
# piecewise with and/or, +, -, *, / by a function of x, integer and
# fractional powers, sqrt, sin, cos, tan, exp, negation and two params.
# The harness includes the generated C (its main renamed), builds the scene
# with the params' defaults, compiles it with the runtime and calls the
# height through the model's swGroundDesc.height, as the ground kernel does.
. "$(dirname "$0")/tap.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
CFLAGS_RT="-fopenmp -I$ROOT/runtime/include $(pkg-config --cflags hdf5 gsl 2>/dev/null)"
LIBS_RT="$ROOT/build/libsinewrt.a $(pkg-config --libs hdf5 gsl 2>/dev/null) -lm -fopenmp"

cat > "$tmp/hills.sinew" <<'MODEL'
# every operation of a height
param bump = 0.2 m;
param scale = 1 m;
material tissue { E = 1 MPa; density = 1.1 g/cm^3; }
rod snake { material = tissue; start = (0, 0, 0.5) m; direction = (1, 0, 0); length = 1 m; radius = 1 cm; elements = 10; }
terrain hills {
  let u = (x - 3 m) / scale;
  let r = sqrt(x^2 + y^2 + 1 m^2);
  height(x, y) = piecewise(x < 3 m and y > -5 m: 0.1 m * sin(x / 1 m) * cos(y / 2 m),
                           x <= 4 m or y >= 5 m: -0.4 m * u^3 + 0.6 m * u^2,
                           bump)
                 + 0.01 m * exp(-(y / 1 m)^2) - r / (10 + (x / 1 m)^2)
                 + 1 mm * tan(y / 10 m) + 1 cm * (r / 1 m)^1.5 - -(2 mm);
  stiffness = 1e3 N/m;
}
simulate { duration = 1 ms; }
MODEL

# points away from the piecewise boundaries x = 3, 4 and y = -5, 5
cat > "$tmp/points" <<'POINTS'
-1.3 0.2
0.7 -2.1
2.2 1.9
2.9 -4.0
3.1 0.4
3.5 -0.8
3.9 2.5
4.3 -1.7
6.0 6.5
1.1 7.2
-2.5 -6.3
POINTS

"$SINEWC_ASAN" "$tmp/hills.sinew" --emit-c -o "$tmp/hills.c"; ok $? "the terrain model compiles to C"
out=$(cc -std=c11 -Wall -Wextra -Werror $CFLAGS_RT -c "$tmp/hills.c" -o "$tmp/hills.o" 2>&1); rc=$?
echo "$out" | diag; ok $rc "its C compiles with -Wall -Wextra -Werror"
grep -q 'static double height_0(double x, double y, double grad\[2\], const void \*ctx)' "$tmp/hills.c"
ok $? "the height is a swHeightFn"
grep -q 'const dual let_1 = ' "$tmp/hills.c"; ok $? "each let of the body is one statement"

cat > "$tmp/harness.c" <<'HARNESS'
#include <stdlib.h>
#define main simulator_main
#include "hills.c"
#undef main
#include <stdio.h>

/* "k x y h dh/dx dh/dy fd_x fd_y" at each point of stdin; argv[1] scales
 * the param bump */
int main(int argc, char **argv) {
  double P[2] = {params[0].value, params[1].value};
  if (argc > 1) P[0] *= atof(argv[1]);
  swSpec *s = sw_spec_new();
  char err[256];
  if (build(s, P, err, sizeof err) != SW_OK) return 1;
  swModel *m = sw_compile(s, err, sizeof err);
  if (!m) { fprintf(stderr, "%s\n", err); return 1; }
  double x, y, e = 1e-6;
  while (scanf("%lf %lf", &x, &y) == 2)
    for (int k = 0; k < m->nground; k++) {
      const swGroundDesc *g = &m->ground[k];
      if (!g->height) continue;
      double grad[2], dummy[2];
      double h = g->height(x, y, grad, g->height_ctx);
      double fx = (g->height(x + e, y, dummy, g->height_ctx) -
                   g->height(x - e, y, dummy, g->height_ctx)) / (2 * e);
      double fy = (g->height(x, y + e, dummy, g->height_ctx) -
                   g->height(x, y - e, dummy, g->height_ctx)) / (2 * e);
      printf("%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", k, x, y, h, grad[0], grad[1], fx, fy);
    }
  sw_model_free(m);
  sw_spec_free(s);
  return 0;
}
HARNESS
out=$(cd "$tmp" && cc -std=c11 -O2 -Wall $CFLAGS_RT harness.c -o harness $LIBS_RT 2>&1); rc=$?
echo "$out" | diag; ok $rc "the harness builds"
"$tmp/harness" <"$tmp/points" >"$tmp/gen"; ok $? "the harness runs"
"$SINEWC_ASAN" --eval-height "$tmp/hills.sinew" <"$tmp/points" >"$tmp/eval"; ok $? "sinewc --eval-height runs"
[ "$(wc -l <"$tmp/gen")" -eq 11 ] && [ "$(wc -l <"$tmp/eval")" -eq 11 ]
ok $? "both give the 11 points"

# generated C and the compiler's evaluator agree (value and gradient)
paste -d' ' "$tmp/gen" "$tmp/eval" | awk '
  function rel(a, b) { d = a - b; if (d < 0) d = -d; s = (a < 0 ? -a : a); return d / (1 + s) }
  { for (i = 4; i <= 6; i++) { r = rel($i, $(i + 8)); if (r > worst) worst = r } }
  END { printf "# generated C vs evaluator: largest difference %.3e (relative to 1 + |value|)\n", worst
        exit !(worst <= 1e-12) }'
ok $? "the generated height and gradient equal the compiler's evaluator (within 1e-12)"

# the gradient against central differences (step 1e-6 m: truncation ~1e-12,
# rounding ~1e-10)
awk '
  function rel(a, b) { d = a - b; if (d < 0) d = -d; s = (a < 0 ? -a : a); return d / (1 + s) }
  { for (i = 5; i <= 6; i++) { r = rel($i, $(i + 2)); if (r > worst) worst = r } }
  END { printf "# dual-number gradient vs central differences: largest difference %.3e\n", worst
        exit !(worst <= 1e-7) }' "$tmp/gen"
ok $? "the gradient matches central finite differences (within 1e-7)"

# the param bump reaches the height through ctx: at x > 4 m (and |y| < 5 m)
# the height differs from the default by exactly the change of bump
echo "6.0 0.3" | "$tmp/harness" 1 >"$tmp/b1"
echo "6.0 0.3" | "$tmp/harness" 3 >"$tmp/b3"
paste -d' ' "$tmp/b1" "$tmp/b3" | awk '{ d = $12 - $4 - 0.4; if (d < 0) d = -d
  printf "# height with bump = 0.6 m minus with 0.2 m: %.17g m\n", $12 - $4; exit !(d < 1e-12) }'
ok $? "a param in the height is read from ctx (bump tripled raises the plateau by 0.4 m)"

# hand-checked value: at (3.5, 0) m, u = 0.5: -0.4*0.125 + 0.6*0.25 = 0.1 m
cat > "$tmp/one.sinew" <<'MODEL'
material tissue { E = 1 MPa; density = 1.1 g/cm^3; }
rod snake { material = tissue; start = (0, 0, 0.5) m; direction = (1, 0, 0); length = 1 m; radius = 1 cm; elements = 10; }
terrain step {
  let u = (x - 3 m) / 1 m;
  height(x, y) = piecewise(x < 3 m: 0 m, x <= 4 m: -0.4 m * u^3 + 0.6 m * u^2, 0.2 m);
  stiffness = 1e3 N/m;
}
simulate { duration = 1 ms; }
MODEL
echo "3.5 0" | "$SINEWC_ASAN" --eval-height "$tmp/one.sinew" | awk '{
  printf "# h(3.5, 0) = %.17g m, dh/dx = %.17g, dh/dy = %.17g\n", $4, $5, $6
  exit !($4 > 0.1 - 1e-15 && $4 < 0.1 + 1e-15 && $5 > 0.3 - 1e-15 && $5 < 0.3 + 1e-15 && $6 == 0) }'
ok $? "hand-computed: the smooth step gives h(3.5 m, 0) = 0.1 m, dh/dx = 0.3, dh/dy = 0"
done_testing
