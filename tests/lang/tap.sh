# tap.sh — helpers for the language tests, sourced by tests/lang/test_*.sh.
# Each script prints TAP (plan, "ok N - ...", "not ok N - ...") for prove.
# Paths: run from the repository root (make check does), or set SINEW_ROOT.
ROOT=${SINEW_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
SINEWC=${SINEWC:-$ROOT/bin/sinewc}
SINEWC_ASAN=${SINEWC_ASAN:-$ROOT/build/asan/sinewc}
# the sanitizer build must not report leaks from the C compiler it spawns
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0}
TAP_N=0
TAP_FAILED=0
ok() {     # ok CONDITION_EXIT_CODE DESCRIPTION
  TAP_N=$((TAP_N + 1))
  if [ "$1" -eq 0 ]; then echo "ok $TAP_N - $2"
  else echo "not ok $TAP_N - $2"; TAP_FAILED=$((TAP_FAILED + 1)); fi
}
diag() { sed '/^$/d; s/^/# /'; }   # pipe text into TAP comments
done_testing() { echo "1..$TAP_N"; [ "$TAP_FAILED" -eq 0 ]; }
# The sanitizer build of sinewc for checking, or the optimised one if it is
# not built.
SINEWC_CHECK=$SINEWC_ASAN
[ -x "$SINEWC_CHECK" ] || SINEWC_CHECK=$SINEWC
scratch() {   # scratch NAME: a fresh directory $TMP, removed on exit
  TMP=$(mktemp -d "${TMPDIR:-/tmp}/sinew-$1.XXXXXX") || exit 1
  trap 'rm -rf "$TMP"' EXIT INT TERM
}
