#!/bin/sh
# fuzz.sh [SECONDS] — fuzz sinewc's front end (lexer, parser, checker, runtime
# validation, C generator) with AFL++; see docs/fuzzing.md.
#
#   scripts/fuzz.sh          600 s (10 minutes), one afl-fuzz instance
#   scripts/fuzz.sh 3600     an hour
#   FUZZ_JOBS=2 scripts/fuzz.sh   a main and a secondary instance (2 cores)
#   FUZZ_FRESH=1 scripts/fuzz.sh  forget the previous run's corpus
#   FUZZ_SANITIZE=0 scripts/fuzz.sh   the harness without ASan and UBSan:
#                            5-20x the executions a second, finding what
#                            crashes or hangs outright; its queue is then
#                            replayed through build/asan/fuzz_sinewc
#                            (docs/fuzzing.md, "Campaigns")
#   FUZZ_TIMEOUT=200 scripts/fuzz.sh  an input slower than 200 ms is a hang
#                            (default 2000): keeps inputs that take the front
#                            end half a second (nested component uses, up
#                            to SEMA_MAX_EXPANDED) out of the queue, where
#                            they stalled run 8 (docs/fuzzing.md)
#   FUZZ_EXECS=10000000 scripts/fuzz.sh 10800
#                            stop at about 10^7 executions (afl-fuzz -E), or
#                            after the seconds given, whichever comes first
#
# Builds tests/fuzz/fuzz_sinewc.c with afl-clang-fast under ASan and UBSan
# (persistent mode) plus a CmpLog build, runs afl-fuzz in an empty directory
# (imports in the inputs then fail cleanly) with the seeds, the regressions
# and the dictionary, and copies every crash and hang it found into
# tests/fuzz/regressions/, minimised and named by content hash, for
# tests/lang/test_fuzz_regressions.sh.  Run from anywhere; the state of the
# last run stays in build/fuzz/out (fuzzer_stats has the figures).
set -eu
SECONDS_TO_RUN=${1:-600}
JOBS=${FUZZ_JOBS:-1}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
OUT=build/fuzz

# AFL++ is in Debian; scripts/deps.sh installs it when missing, and clang's
# OpenMP library (libomp-dev), which the runtime's threads need when built by
# afl-clang-fast (GCC's libgomp serves the other builds).
sh scripts/deps.sh afl++:/usr/bin/afl-clang-fast libomp-dev:/usr/lib/llvm-14/lib/libomp.so

# ---- build: the generated parser, then one afl-clang-fast link each
make --no-print-directory build/lang/sinew.tab.c build/lang/lex.yy.c >/dev/null
mkdir -p "$OUT"
SRC="tests/fuzz/fuzz_sinewc.c build/lang/sinew.tab.c build/lang/lex.yy.c"
for f in compiler/*.c runtime/*/*.c; do
  case $f in   # sinewc.c has main(); study_mpi.c needs MPI and is not in the library
    compiler/sinewc.c|runtime/study/study_mpi.c) ;;
    *) SRC="$SRC $f" ;;
  esac
done
# -fopenmp as in the Makefile: the runtime calls omp_get_num_threads() and
# the like, which only link with it
CFLAGS="-std=c11 -D_DEFAULT_SOURCE -O1 -g -fno-omit-frame-pointer -fopenmp -w
        -Icompiler -Ibuild/lang -Iruntime/include -Iruntime $(pkg-config --cflags hdf5 gsl)"
LIBS="$(pkg-config --libs hdf5 gsl) -lm"
echo "fuzz: building $OUT/fuzz_sinewc (ASan+UBSan) and $OUT/fuzz_sinewc.cmplog" >&2
# shellcheck disable=SC2086
if [ "${FUZZ_SANITIZE:-1}" = 0 ]; then
  echo "fuzz: FUZZ_SANITIZE=0: no ASan or UBSan in this build" >&2
  AFL_QUIET=1 afl-clang-fast $CFLAGS $SRC -o "$OUT/fuzz_sinewc" $LIBS
else
  AFL_QUIET=1 AFL_USE_ASAN=1 AFL_USE_UBSAN=1 afl-clang-fast $CFLAGS $SRC -o "$OUT/fuzz_sinewc" $LIBS
fi
# shellcheck disable=SC2086
AFL_QUIET=1 AFL_LLVM_CMPLOG=1 afl-clang-fast $CFLAGS $SRC -o "$OUT/fuzz_sinewc.cmplog" $LIBS

# ---- corpus: seeds, every earlier finding, and the queue of the previous
# run if there is one (FUZZ_FRESH=1 starts from the seeds alone)
IN=$OUT/in
rm -rf "$IN"
mkdir -p "$IN"
cp tests/fuzz/seeds/* "$IN"/
for f in tests/fuzz/regressions/*; do [ -f "$f" ] && cp "$f" "$IN"/; done
if [ "${FUZZ_FRESH:-0}" != 1 ]; then
  n=0
  for f in "$OUT"/out/*/queue/id:*; do
    [ -f "$f" ] || continue
    n=$((n + 1)); cp "$f" "$IN/prev-$n"
  done
  [ "$n" = 0 ] || echo "fuzz: starting from the seeds and $n inputs of the previous run" >&2
fi
rm -rf "$OUT/out"

# ---- run in an empty directory, so that `import "x";` in an input finds nothing
WORK=$(mktemp -d "${TMPDIR:-/tmp}/sinew-fuzz.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
export AFL_SKIP_CPUFREQ=1 AFL_NO_UI=1
# crashes must reach afl-fuzz, not a core-dump helper
if [ "$(cat /proc/sys/kernel/core_pattern 2>/dev/null)" != core ]; then
  echo core 2>/dev/null >/proc/sys/kernel/core_pattern ||
    export AFL_I_DONT_CARE_ABOUT_MISSING_CRASHES=1
fi
# afl-fuzz's own ASAN_OPTIONS (it sets them when there are none; it wants
# abort_on_error=1 and symbolize=0), plus a quarantine of 16 MB instead of
# 256: with the default, freed memory waits in a 256 MB quarantine, so a
# persistent-mode process keeps touching fresh pages and most of its time
# went to page faults: the harness took 2.3 ms of CPU per input of a corpus,
# 0.9 ms with 16 MB (a use after free is still caught while the block is
# among the last 16 MB freed, far more than one input allocates).
# UBSAN_OPTIONS are afl-fuzz's.
export ASAN_OPTIONS=abort_on_error=1:detect_leaks=0:malloc_context_size=0:symbolize=0:\
allocator_may_return_null=1:detect_odr_violation=0:handle_segv=0:handle_sigbus=0:\
handle_abort=0:handle_sigfpe=0:handle_sigill=0:quarantine_size_mb=16
BIN="$ROOT/$OUT/fuzz_sinewc"
ARGS="-i $ROOT/$IN -o $ROOT/$OUT/out -x $ROOT/tests/fuzz/sinew.dict -t ${FUZZ_TIMEOUT:-2000} -m none -V $SECONDS_TO_RUN"
[ -z "${FUZZ_EXECS:-}" ] || ARGS="$ARGS -E $FUZZ_EXECS"
echo "fuzz: running $JOBS afl-fuzz instance(s) for $SECONDS_TO_RUN s (log: $OUT/fuzz-*.log)" >&2
pids=""
i=0
while [ "$i" -lt "$JOBS" ]; do
  if [ "$i" = 0 ]; then role="-M main"; else role="-S sec$i"; fi
  # the main instance uses CmpLog (solves comparisons with keywords and units)
  cmplog=""; [ "$i" = 0 ] && cmplog="-c $ROOT/$OUT/fuzz_sinewc.cmplog"
  # shellcheck disable=SC2086
  (cd "$WORK" && exec afl-fuzz $role $ARGS $cmplog -- "$BIN") >"$OUT/fuzz-$i.log" 2>&1 &
  pids="$pids $!"
  i=$((i + 1))
done
status=0
for p in $pids; do wait "$p" || status=$?; done
# afl-fuzz 4.04c can leave its CmpLog fork server behind, stopped and pinned to
# a core (the next run then finds "no more free CPU cores"): end exactly the
# processes running the binaries built above
for p in /proc/[0-9]*; do
  case "$(readlink "$p/exe" 2>/dev/null)" in
    "$BIN" | "$BIN.cmplog") kill -9 "${p#/proc/}" 2>/dev/null || true ;;
  esac
done

# ---- figures and findings
for stats in "$OUT"/out/*/fuzzer_stats; do
  [ -f "$stats" ] || continue
  echo "fuzz: $stats"
  grep -E '^(run_time|execs_done|execs_per_sec|corpus_count|saved_crashes|saved_hangs|stability|bitmap_cvg) ' "$stats"
done
# Each crash is shrunk with afl-tmin (test cases over shared memory, as when
# fuzzing) and kept under the hash of its minimised text, so one bug found
# many times mostly collapses to a few small files.  Hangs are kept as found:
# every try of a minimiser on a hang costs a timeout, so only the first hang
# is also shrunk (-H, 0.5 s per try, at most 5 minutes).
new=0
keep() {   # keep FILE KIND: copy into tests/fuzz/regressions/KIND-HASH.sinew
  h=$(sha256sum "$1" | cut -c1-16)
  dest="tests/fuzz/regressions/$2-$h.sinew"
  if [ ! -e "$dest" ]; then cp "$1" "$dest"; new=$((new + 1)); echo "fuzz: new $2: $dest"; fi
}
min="$OUT/min.tmp"
for f in "$OUT"/out/*/crashes/id:*; do
  [ -f "$f" ] || continue
  rm -f "$min"
  (cd "$WORK" && afl-tmin -t 2000 -m none -i "$ROOT/$f" -o "$ROOT/$min" -- "$BIN") >/dev/null 2>&1 &&
    [ -s "$min" ] || cp "$f" "$min"
  keep "$min" crash
done
first=1
for f in "$OUT"/out/*/hangs/id:*; do
  [ -f "$f" ] || continue
  keep "$f" hang
  if [ "$first" = 1 ]; then
    first=0
    rm -f "$min"
    (cd "$WORK" && timeout 300 afl-tmin -H -t 500 -m none -i "$ROOT/$f" -o "$ROOT/$min" -- "$BIN") \
      >/dev/null 2>&1 && [ -s "$min" ] && keep "$min" hang
  fi
done
rm -f "$min"
echo "fuzz: $new new finding(s) copied to tests/fuzz/regressions/"
[ "$status" = 0 ] || { echo "fuzz: afl-fuzz failed (status $status); see $OUT/fuzz-*.log" >&2; exit "$status"; }
