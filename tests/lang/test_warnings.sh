#!/bin/sh
# test_warnings.sh — every C file of the project compiles warning-free with
# the Makefile's warning set (WARN: -Wall -Wextra and the rest): the runtime's
# rooms, the compiler, the runtime and end-to-end tests, the fuzzing harness,
# the benchmarks and the MPI test driver (where mpi.h is).  Checked with
# -fsyntax-only, one file at a time, so a warning names its file whatever make
# has built already; the warnings only an optimiser finds show in the builds
# themselves.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch warnings

WARN=$(sed -n 's/^WARN *= *//p' Makefile)
[ -n "$WARN" ]; ok $? "the Makefile's warning set: $WARN"
INC="-Iruntime/include -Iruntime -Iruntime/engine -Iruntime/io -Iruntime/study -Itests/runtime
     -Itests/e2e -Ibench -Icompiler -Ibuild/lang $(pkg-config --cflags hdf5 gsl 2>/dev/null)"
MPI_INC=$(mpicc --showme:compile 2>/dev/null)
n=0
for f in runtime/*/*.c compiler/*.c tests/runtime/*.c tests/e2e/*.c tests/mpi/*.c tests/fuzz/*.c \
         bench/*.c; do
  case $f in
    runtime/study/study_mpi.c|tests/mpi/*) [ -n "$MPI_INC" ] || continue; extra=$MPI_INC ;;
    bench/eval_sundials.c) [ -e /usr/include/arkode/arkode_arkstep.h ] || continue; extra= ;;
    *) extra= ;;
  esac
  # shellcheck disable=SC2086
  ${CC:-cc} -std=c11 -D_DEFAULT_SOURCE $WARN -fopenmp $INC $extra -fsyntax-only "$f" 2>>"$TMP/out"
  n=$((n + 1))
done
grep -q 'warning:' "$TMP/out"; [ $? -ne 0 ]; ok $? "$n C files compile without a warning"
grep 'warning:' "$TMP/out" | diag
grep -q 'error:' "$TMP/out"; [ $? -ne 0 ]; ok $? "and without an error"
grep 'error:' "$TMP/out" | head -20 | diag
done_testing
