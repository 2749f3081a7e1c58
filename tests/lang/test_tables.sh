#!/bin/sh
# test_tables.sh — the reference's tables, checked by machine: every number
# of Zhang et al. 2019's Supplementary Tables 1-10 that a shipped scene uses
# (elastic moduli, densities, lengths, radii, element counts, k, k_f, k_c,
# gamma_c, T_sim, muscle parameters) against what the compiled scene reports
# in `--info` (no simulation).  The numbers, how each is read and the
# documented deviations are tests/reference/tables.tsv; the comparison is
# tests/lang/tables_check.py, one TAP line per entry, naming it: "Suppl.
# Table 5, k (elbow hinge): scene 4e+05 kg/s^2, table 5e5 kg/s^2".
# Deviations (a scene that differs from its table on purpose) are printed
# with their reason; numbers that are sinew's own are listed, and their
# model's header must say so.  docs/validation.md, "The reference's tables,
# checked".
. "$(dirname "$0")/tap.sh"
scratch tables
export SINEW_PATH="$ROOT/models"
TSV="$ROOT/tests/reference/tables.tsv"

# The scenes the data file names, each compiled once (two at a time), but
# the wing: its C takes 5 s to compile, and tests/lang/test_wing.sh, which
# builds it anyway, checks its rows with the same checker.
ELSEWHERE=pigeon_wing
scenes=$(awk -F'\t' '!/^#/ && $3 != "scene" { print $3 }' "$TSV" | sort -u)
for s in $scenes; do
  [ "$s" = "$ELSEWHERE" ] && continue
  f="$ROOT/examples/$s.sinew"
  [ -f "$f" ] || f="$ROOT/models/$s.sinew"
  echo "$s $f"
done >"$TMP/scenes"
compile() {   # compile NAME FILE: $TMP/NAME.info, or $TMP/NAME.err
  "$SINEWC" "$2" -o "$TMP/$1" 2>"$TMP/$1.err" && "$TMP/$1" --info >"$TMP/$1.info" 2>>"$TMP/$1.err" ||
    rm -f "$TMP/$1.info"
}
start=$(date +%s)
n=0
while read -r name file; do
  compile "$name" "$file" &
  n=$((n + 1))
  [ $((n % 2)) -eq 0 ] && wait
done <"$TMP/scenes"
wait
echo "# $(wc -l <"$TMP/scenes") scenes compiled and --info read in $(($(date +%s) - start)) s"
while read -r name file; do
  [ -f "$TMP/$name.info" ]; ok $? "$name ($file) compiles and prints --info"
  [ -f "$TMP/$name.info" ] || diag <"$TMP/$name.err"
done <"$TMP/scenes"

# one TAP line per entry from the checker
/usr/bin/python3 "$ROOT/tests/lang/tables_check.py" "$TSV" "$TMP" "$ROOT" \
  $(cut -d' ' -f1 "$TMP/scenes") >"$TMP/check" 2>&1
rc=$?
while IFS= read -r line; do
  case "$line" in
    "ok - "*) ok 0 "${line#ok - }" ;;
    "not ok - "*) ok 1 "${line#not ok - }" ;;
    *) echo "$line" ;;
  esac
done <"$TMP/check"
[ $rc -eq 0 ] || [ $TAP_FAILED -gt 0 ] || ok 1 "tables_check.py failed: $(tail -1 "$TMP/check")"
echo "# $ELSEWHERE: $(grep -c "	$ELSEWHERE	" "$TSV") rows, checked by tests/lang/test_wing.sh"

# every shipped scene or model that cites a Suppl. Table is read by a row:
# it is a scene of the data file, or a model one of them imports
missing=""
for f in "$ROOT"/examples/*.sinew "$ROOT"/models/*.sinew; do
  grep -q 'Table [0-9]' "$f" || continue
  name=$(basename "$f" .sinew)
  grep -q "	$name	" "$TSV" && continue
  used=0
  for s in $scenes; do
    for g in "$ROOT/examples/$s.sinew" "$ROOT/models/$s.sinew"; do
      [ -f "$g" ] && grep -q "^import \"$name.sinew\"" "$g" && used=1
    done
  done
  [ $used -eq 1 ] || missing="$missing ${f#"$ROOT"/}"
done
[ -z "$missing" ]; ok $? "every scene and model of examples/ and models/ citing a Suppl. Table has rows in tables.tsv${missing:+ (not:$missing)}"
done_testing
