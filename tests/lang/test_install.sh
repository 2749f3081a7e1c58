#!/bin/sh
# test_install.sh — `make install PREFIX=...` gives a sinewc that works
# outside the tree: the compiler, the runtime libraries and the public
# header with all its parts (runtime/include/: sinew.h includes
# sinew_spec.h, sinew_model.h, sinew_io.h, sinew_program.h), so a model
# compiles against the installed files alone and its simulator runs;
# `sinewc --help` names every part as what SINEW_RUNTIME must hold, and a
# SINEW_RUNTIME without one is an error naming it (exit 4), not a C compiler
# failure; the installed sinew-plot, which has no scripts/deps.sh beside it,
# says in one line how to install ffmpeg when `movie` finds none (exit 1).
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

# what SINEW_RUNTIME must hold, in --help: every part of the header and the library
"$TMP/inst/bin/sinewc" --help >"$TMP/help"
for h in runtime/include/*.h libsinewrt.a libsinewrt-portable.a; do
  grep -qwF "$(basename "$h")" "$TMP/help" || echo "--help does not name $(basename "$h")"
done >"$TMP/unnamed"
[ -s "$TMP/unnamed" ]; [ $? -ne 0 ]
ok $? "sinewc --help names what SINEW_RUNTIME holds: $(ls runtime/include | tr '\n' ' ')and the libraries"
diag <"$TMP/unnamed"
mkdir "$TMP/rt"
cp "$TMP/inst/include/sinew/"*.h "$TMP/inst/lib/libsinewrt.a" "$TMP/rt/"
rm "$TMP/rt/sinew_io.h"
SINEW_RUNTIME=$TMP/rt "$TMP/inst/bin/sinewc" examples/pendulum.sinew -o "$TMP/x" 2>"$TMP/err"
rc=$?
want="sinewc: cannot find the runtime's header '$TMP/rt/sinew_io.h' (sinew.h and its parts sinew_spec.h, sinew_model.h, sinew_io.h, sinew_program.h belong in one directory)"
[ $rc -eq 4 ] && [ "$(cat "$TMP/err")" = "$want" ]
ok $? "SINEW_RUNTIME without sinew_io.h: exit 4 naming it (got $rc)"
diag <"$TMP/err"

# the installed sinew-plot, ffmpeg out of reach (an empty PATH): how to get it
mkdir "$TMP/nobin"
env PATH="$TMP/nobin" "$TMP/inst/bin/sinew-plot" movie "$TMP/p.h5" -o "$TMP/p.mp4" >"$TMP/err" 2>&1
rc=$?
want="sinew-plot: ffmpeg is missing: install Debian's ffmpeg package (apt-get install ffmpeg, as root)"
[ $rc -eq 1 ] && [ "$(tail -n 1 "$TMP/err")" = "$want" ] && [ ! -e "$TMP/p.mp4" ]
ok $? "installed sinew-plot movie without ffmpeg: exit 1, \"$want\" (got $rc)"
[ $rc -eq 1 ] || diag <"$TMP/err"
done_testing
