#!/bin/sh
# test_golden.sh — diagnostic golden tests: each bad model beside the exact
# text the compiler must print for it.
#
#   tests/lang/errors/NAME.sinew     a model with mistakes (its first line, a
#                                    comment, says which)
#   tests/lang/errors/NAME.args      optional: more words for the command line
#                                    (split at blanks), e.g. --let n=3cm
#   tests/lang/errors/NAME.expected  the exact stderr of
#                                        cd tests/lang/errors && sinewc --check NAME.sinew ARGS
#                                    followed by one line "exit: N" with the
#                                    exit code (1 for errors, 2 for usage errors,
#                                    0 for warnings only)
#   tests/lang/errors/lib/           imported helper files, not cases themselves
#
# Each case runs the sanitizer build ($SINEWC_ASAN), so a case also fails on
# any AddressSanitizer or UBSan report; stdout must stay empty.  On a mismatch
# the unified diff (expected -> got) is printed as TAP comments.
#
#   UPDATE=1 tests/lang/test_golden.sh   rewrite every .expected from the
#                                        compiler's current output (after a
#                                        deliberate change of a message; review
#                                        the diff before committing)
. "$(dirname "$0")/tap.sh"
DIR=$ROOT/tests/lang/errors
CHECKER=$SINEWC_ASAN
if [ ! -x "$CHECKER" ]; then
  echo "# $CHECKER is not built; checking with $SINEWC instead"
  CHECKER=$SINEWC
fi
# messages about imports mention SINEW_PATH; the goldens assume it unset
unset SINEW_PATH
TMP=$(mktemp -d "${TMPDIR:-/tmp}/sinew-golden.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM

for src in "$DIR"/*.sinew; do
  name=$(basename "$src" .sinew)
  args=
  [ -f "$DIR/$name.args" ] && args=$(cat "$DIR/$name.args")
  # shellcheck disable=SC2086 # the words of NAME.args, split at blanks
  (cd "$DIR" && set -f && exec timeout 60 "$CHECKER" --check "$name.sinew" $args) >"$TMP/out" 2>"$TMP/got"
  rc=$?
  echo "exit: $rc" >>"$TMP/got"
  if [ -s "$TMP/out" ]; then
    echo "stdout (must be empty):" >>"$TMP/got"
    cat "$TMP/out" >>"$TMP/got"
  fi
  if [ "${UPDATE:-0}" = 1 ]; then
    cp "$TMP/got" "$DIR/$name.expected"
    ok 0 "$name (updated)"
  elif [ ! -f "$DIR/$name.expected" ]; then
    ok 1 "$name: no $name.expected (run UPDATE=1 $0 and review it)"
  elif diff -u --label "$name.expected" --label "$name (got)" "$DIR/$name.expected" "$TMP/got" >"$TMP/diff"; then
    ok 0 "$name"
  else
    ok 1 "$name: diagnostics differ"
    diag <"$TMP/diff"
  fi
done
done_testing
