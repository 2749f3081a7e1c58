#!/bin/sh
# test_install.sh — `make install PREFIX=...` gives a sinewc that works
# outside the tree: the compiler, the runtime libraries and the public
# header with all its parts (runtime/include/: sinew.h includes
# sinew_spec.h, sinew_model.h, sinew_io.h, sinew_program.h), so a model
# compiles against the installed files alone and its simulator runs.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch install

make --no-print-directory install PREFIX="$TMP/inst" >"$TMP/log" 2>&1; ok $? "make install PREFIX=... runs"
diag <"$TMP/log"
for h in runtime/include/*.h; do
  cmp -s "$h" "$TMP/inst/include/sinew/$(basename "$h")" || echo "missing or different: $h"
done >"$TMP/headers"
[ -s "$TMP/headers" ]; [ $? -ne 0 ]; ok $? "every part of the public header is installed ($(ls runtime/include | wc -l) files)"
diag <"$TMP/headers"
# the installed sinewc finds its runtime beside itself (bin/../include/sinew, bin/../lib)
env -u SINEW_RUNTIME "$TMP/inst/bin/sinewc" examples/pendulum.sinew -o "$TMP/pendulum" 2>"$TMP/err"
ok $? "the installed sinewc compiles the pendulum"
diag <"$TMP/err"
"$TMP/pendulum" --quiet --duration 2ms --out "$TMP/p.h5" >/dev/null 2>"$TMP/err"
ok $? "its simulator runs"
diag <"$TMP/err"
done_testing
