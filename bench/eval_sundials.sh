#!/bin/sh
# eval_sundials.sh SUNDIALS_SRC — bench/eval_sundials.c against SUNDIALS built
# from source with optimisation, beside the run against Debian's package that
# `make bench-sundials` does.  Debian's libsundials-dev 6.4.1 is compiled
# without optimisation (its loops keep their counters on the stack), which
# would charge SUNDIALS for a packaging choice; this builds the same release
# with CMAKE_BUILD_TYPE=Release (-O3) into build/sundials/ (ARKODE only,
# static) and runs the benchmark linked to it.
#
#   git clone --depth 1 --branch v6.4.1 https://github.com/LLNL/sundials /tmp/sundials-6.4.1
#   make bench-sundials SUNDIALS_SRC=/tmp/sundials-6.4.1
set -eu
SRC=${1:?usage: eval_sundials.sh SUNDIALS_SOURCE_TREE}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SRC=$(cd "$SRC" && pwd)
OUT=$ROOT/build/sundials
CC=${CC:-cc}
command -v cmake >/dev/null || { echo "eval_sundials: cmake is needed to build SUNDIALS" >&2; exit 1; }
if [ ! -e "$OUT/inst/lib/libsundials_arkode.a" ]; then
  echo "eval_sundials: building SUNDIALS from $SRC (Release) into $OUT" >&2
  mkdir -p "$OUT/build"
  (cd "$OUT/build" &&
   cmake "$SRC" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$OUT/inst" \
     -DCMAKE_INSTALL_LIBDIR=lib -DBUILD_SHARED_LIBS=OFF -DBUILD_STATIC_LIBS=ON \
     -DBUILD_CVODE=OFF -DBUILD_CVODES=OFF -DBUILD_IDA=OFF -DBUILD_IDAS=OFF -DBUILD_KINSOL=OFF \
     -DEXAMPLES_ENABLE_C=OFF -DEXAMPLES_INSTALL=OFF >cmake.log &&
   make -j2 install >make.log) || { echo "eval_sundials: build failed, see $OUT/build/*.log" >&2; exit 1; }
fi
L=$OUT/inst/lib
version=$(sed -n 's/^#define SUNDIALS_VERSION "\(.*\)"/\1/p' "$OUT/inst/include/sundials/sundials_config.h")
mkdir -p "$ROOT/build/bench"
$CC -std=c11 -D_DEFAULT_SOURCE -Wall -Wextra -Wshadow -Wstrict-prototypes -Wmissing-prototypes \
  -O3 -march=native -g -DEVAL_SUNDIALS_BUILD="\"built from source $version, Release -O3\"" \
  -I"$OUT/inst/include" "$ROOT/bench/eval_sundials.c" -o "$ROOT/build/bench/eval_sundials_release" \
  "$L/libsundials_arkode.a" "$L/libsundials_nvecserial.a" "$L/libsundials_sunlinsoldense.a" \
  "$L/libsundials_sunmatrixdense.a" "$L/libsundials_sunnonlinsolnewton.a" "$L/libsundials_generic.a" -lm
exec "$ROOT/build/bench/eval_sundials_release"
