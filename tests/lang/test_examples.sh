#!/bin/sh
# test_examples.sh — every model in the tree checks cleanly, and every
# construct example compiles, runs a few steps and writes its HDF5 file.
#
#   examples/**/*.sinew, models/*.sinew   sinewc --check -Werror exits 0
#                                         (sanitizer build)
#   examples/constructs/*.sinew           sinewc -o SIM, then
#                                         SIM --quiet --duration 1ms --out F.h5
#                                         exits 0 and F.h5 exists
#   docs/language.md                      every line of every ```sinew block
#                                         is a line of some file under
#                                         examples/constructs/ (the reference
#                                         shows only examples that compile)
#
# Library files (no `simulate` block, only imported) are checked the same way:
# a file of materials and components must check clean on its own.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1

CHECKER=$SINEWC_ASAN
if [ ! -x "$CHECKER" ]; then
  echo "# $CHECKER is not built; checking with $SINEWC instead"
  CHECKER=$SINEWC
fi
TMP=$(mktemp -d "${TMPDIR:-/tmp}/sinew-examples.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM

is_library() { ! grep -Eq '^[[:space:]]*simulate[[:space:]]*\{' "$1"; }

# ---- every model checks without errors or warnings
MODELS=$(find examples -name '*.sinew' | sort)
[ -d models ] && MODELS="$MODELS $(find models -maxdepth 1 -name '*.sinew' | sort)"
for f in $MODELS; do
  "$CHECKER" --check -Werror "$f" >"$TMP/out" 2>&1
  rc=$?
  if is_library "$f"; then ok $rc "$f: sinewc --check -Werror (library)"
  else ok $rc "$f: sinewc --check -Werror"; fi
  [ $rc -eq 0 ] || diag <"$TMP/out"
done

# ---- construct examples compile and run a few steps
for f in examples/constructs/*.sinew; do
  name=$(basename "$f" .sinew)
  if is_library "$f"; then continue; fi
  "$SINEWC" "$f" -o "$TMP/$name" >"$TMP/out" 2>&1
  rc=$?
  ok $rc "$f: compiles"
  [ $rc -eq 0 ] || { diag <"$TMP/out"; continue; }
  (cd "$TMP" && "./$name" --quiet --duration 1ms --out "$TMP/$name.h5") >"$TMP/out" 2>&1
  rc=$?
  ok $rc "$f: runs 1 ms"
  [ $rc -eq 0 ] || diag <"$TMP/out"
  [ -s "$TMP/$name.h5" ]
  ok $? "$f: writes $name.h5"
done

# ---- the reference's sinew examples are taken from examples/constructs
DOC=docs/language.md
if [ -f "$DOC" ]; then
  # every line of the examples, stripped of surrounding blanks
  find examples/constructs -name '*.sinew' -exec cat {} + |
    sed 's/^[[:space:]]*//; s/[[:space:]]*$//' >"$TMP/lines"
  # each ```sinew block of the doc: "LINE<tab>text" per line, blocks split
  awk '/^```sinew[[:space:]]*$/ { inb = 1; start = NR; next }
       /^```/ { inb = 0; next }
       inb { sub(/^[[:space:]]+/, ""); sub(/[[:space:]]+$/, ""); print start "\t" $0 }' \
    "$DOC" >"$TMP/doc"
  for start in $(cut -f1 "$TMP/doc" | uniq); do
    missing=$(awk -F'\t' -v s="$start" '$1 == s && $2 != "" && $2 != "..." { print $2 }' "$TMP/doc" |
      while IFS= read -r line; do
        grep -Fxq -- "$line" "$TMP/lines" || printf '%s\n' "$line"
      done)
    [ -z "$missing" ]
    ok $? "$DOC: the sinew block at line $start is in examples/constructs"
    [ -z "$missing" ] || printf 'not in any example: %s\n' "$missing" | diag
  done
fi

done_testing
