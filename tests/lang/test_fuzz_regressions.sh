#!/bin/sh
# test_fuzz_regressions.sh — the compiler survives every input the fuzzer
# ever broke it with (tests/fuzz/regressions/, minimised by scripts/fuzz.sh)
# and the fuzzing seeds (tests/fuzz/seeds/): the sanitizer build, run with
# --check, must exit 0 (clean) or 1 (model errors) within 10 s.  A crash, an
# abort, a sanitizer report (exit 99, set below) or a hang (timeout: 124)
# fails the case.  Runs in an empty directory, as the fuzzer does, so that
# imports in the inputs find nothing.  See docs/fuzzing.md.
. "$(dirname "$0")/tap.sh"
CHECKER=$SINEWC_ASAN
if [ ! -x "$CHECKER" ]; then
  echo "# $CHECKER is not built; checking with $SINEWC instead"
  CHECKER=$SINEWC
fi
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:exitcode=99
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1:exitcode=99
unset SINEW_PATH
TMP=$(mktemp -d "${TMPDIR:-/tmp}/sinew-fuzzreg.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
mkdir "$TMP/run"

for f in "$ROOT"/tests/fuzz/regressions/* "$ROOT"/tests/fuzz/seeds/*; do
  [ -f "$f" ] || continue
  case "$f" in */README*) continue ;; esac
  name=${f#"$ROOT"/tests/fuzz/}
  cp "$f" "$TMP/run/input.sinew"
  (cd "$TMP/run" && exec timeout 10 "$CHECKER" --check input.sinew) >"$TMP/log" 2>&1
  rc=$?
  if [ "$rc" -eq 0 ] || [ "$rc" -eq 1 ]; then
    ok 0 "$name (exit $rc)"
  else
    case $rc in 124) why="hang (timeout)" ;; 99) why="sanitizer report" ;; *) why="crash" ;; esac
    ok 1 "$name: exit $rc, $why"
    tail -n 30 "$TMP/log" | diag
  fi
done
done_testing
