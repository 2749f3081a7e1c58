#!/bin/sh
# test_param_default.sh — two models differing only in a param default give
# the same C except for that constant.  The generated file necessarily also
# embeds the model text (the one source line that differs) and its sha256;
# every other line, the whole of build() and main() included, must be equal.
. "$(dirname "$0")/tap.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/a" "$tmp/b"
cp "$ROOT/examples/cantilever.sinew" "$tmp/a/model.sinew"
sed 's/^param load = 0.5 N;/param load = 0.75 N;/' "$ROOT/examples/cantilever.sinew" > "$tmp/b/model.sinew"
ok "$(cmp -s "$tmp/a/model.sinew" "$tmp/b/model.sinew"; echo $((1 - $?)))" "the two models differ"
# compiled from inside their directories, so file names in the C are equal
(cd "$tmp/a" && "$SINEWC_ASAN" model.sinew --emit-c -o ../a.c); ok $? "model a compiles to C"
(cd "$tmp/b" && "$SINEWC_ASAN" model.sinew --emit-c -o ../b.c); ok $? "model b compiles to C"
diff "$tmp/a.c" "$tmp/b.c" | grep '^[<>]' > "$tmp/d"
diag < "$tmp/d"
n=$(wc -l < "$tmp/d")
ok "$([ "$n" -eq 6 ]; echo $?)" "exactly three lines differ ($((n / 2)) found)"
grep -q '^< *{"load", 0.5, {1, 1, -2, 0}, "N"' "$tmp/d" && grep -q '^> *{"load", 0.75, {1, 1, -2, 0}, "N"' "$tmp/d"
ok $? "the param table holds the two defaults"
grep -q '^[<>] *"param load = 0.*N;' "$tmp/d"; ok $? "the embedded model text differs in the param line"
grep -q '^[<>] *\.sha256 = ' "$tmp/d"; ok $? "the embedded sha256 differs"
grep -q 'load.signal.b = P\[0\];' "$tmp/a.c"; ok $? "build() reads the param from P[0], not a folded constant"
done_testing
