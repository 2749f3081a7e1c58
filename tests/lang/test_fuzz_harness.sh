#!/bin/sh
# test_fuzz_harness.sh — the fuzzing harness tests/fuzz/fuzz_sinewc.c keeps
# building and running without AFL++ (docs/fuzzing.md).  make check builds
# it with the plain C compiler under ASan and UBSan as build/asan/fuzz_sinewc
# (a replay program: `fuzz_sinewc FILE...` runs the front end in-process on
# each file, as afl-fuzz does on each test case); this test
#   - builds it again through make (a no-op after make check; a harness that
#     no longer compiles, or compiles with a warning, fails here);
#   - runs it on every file of tests/fuzz/seeds/ and tests/fuzz/regressions/,
#     one file per process, in an empty directory (imports find nothing, as
#     when fuzzing), under `timeout 10`: it must exit 0 with no sanitizer
#     report and no leak (exit 99, set below); a hang is exit 124;
#   - checks that it did what sinewc does on the same file: errors exactly
#     when `sinewc --check` exits 1, and on a clean model the runtime's check
#     (when there are rods) and the generated C, so a harness that skips a
#     stage or stops early does not pass.
# tests/lang/test_fuzz_regressions.sh replays the same files through sinewc.
. "$(dirname "$0")/tap.sh"
HARNESS=${FUZZ_HARNESS:-$ROOT/build/asan/fuzz_sinewc}
scratch fuzzharness
mkdir "$TMP/run"

# (make check's MAKEFLAGS name a jobserver this make cannot reach: dropped)
(cd "$ROOT" && unset MAKEFLAGS MFLAGS MAKELEVEL &&
  exec make --no-print-directory build/asan/fuzz_sinewc) >"$TMP/build" 2>&1
rc=$?
[ "$rc" -eq 0 ] && [ -x "$HARNESS" ]; ok $? "make build/asan/fuzz_sinewc builds the harness"
[ "$rc" -eq 0 ] || tail -n 30 "$TMP/build" | diag
grep -q 'warning:' "$TMP/build"; [ $? -ne 0 ]; ok $? "and without a warning"
grep 'warning:' "$TMP/build" | diag
if [ ! -x "$HARNESS" ]; then done_testing; exit 1; fi

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:exitcode=99
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1:exitcode=99
unset SINEW_PATH
n=0
for f in "$ROOT"/tests/fuzz/seeds/* "$ROOT"/tests/fuzz/regressions/*; do
  [ -f "$f" ] || continue
  case "$f" in */README*) continue ;; esac
  name=${f#"$ROOT"/tests/fuzz/}
  n=$((n + 1))
  cp "$f" "$TMP/run/input.sinew"
  (cd "$TMP/run" && exec timeout 10 "$HARNESS" input.sinew) >"$TMP/out" 2>"$TMP/err"
  rc=$?
  line=$(sed -n 's/^input\.sinew: //p' "$TMP/out")
  if [ "$rc" -eq 0 ] && [ ! -s "$TMP/err" ] && [ -n "$line" ]; then
    ok 0 "harness: $name ($line)"
  else
    case $rc in
      0) why="no report line or output on stderr" ;;
      124) why="hang (timeout)" ;;
      99) why="sanitizer report" ;;
      *) why="crash" ;;
    esac
    ok 1 "harness: $name: exit $rc, $why"
    diag <"$TMP/out"
    tail -n 30 "$TMP/err" | diag
    continue
  fi
  # the same file through sinewc --check (the sanitizer build when built)
  (cd "$TMP/run" && exec timeout 10 "$SINEWC_CHECK" --check input.sinew) >/dev/null 2>"$TMP/check"
  src=$?
  # sinewc gives the runtime a scene with rods or muscles' filaments
  if grep -q ': ok: .* 0 rods (.*(0 filaments)' "$TMP/check"; then runtime=no; else runtime=yes; fi
  case $src:$line in
    1:skipped*) agree=0 ;;   # a NUL byte: sinewc refuses the file
    0:"0 errors, "*", runtime check: $runtime, C: generated") agree=0 ;;
    1:"0 errors,"*) agree=1 ;;
    1:*) agree=0 ;;
    *) agree=1 ;;
  esac
  ok "$agree" "agrees with sinewc --check (exit $src): $name"
  [ "$agree" -eq 0 ] || { echo "harness: $line"; cat "$TMP/check"; } | tail -n 20 | diag
done
[ "$n" -gt 0 ]; ok $? "$n inputs replayed"
done_testing
