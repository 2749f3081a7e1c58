#!/bin/sh
# test_link.sh — a simulator carries the code of the parts its scene uses
# (issue 10): the runtime reaches muscle.c and the environments (environment.c,
# ground.c, fluid.c, contact.c, wave.c) only through the spec and the model,
# so the static link pulls them in only for a scene that adds them.  The
# cantilever's simulator must hold neither, the elbow's the muscles, the
# snake's the environment, and all must run.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
SC=$ROOT/bin/sinewc
TMP=$(mktemp -d "${TMPDIR:-/tmp}/sinew-link.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM

"$SC" examples/cantilever.sinew -o "$TMP/cantilever" 2>"$TMP/err"; ok $? "sinewc builds the cantilever"
"$SC" examples/elbow_flexion.sinew -o "$TMP/elbow" 2>>"$TMP/err"; ok $? "sinewc builds the elbow"
"$SC" examples/snake_continuum.sinew -o "$TMP/snake" 2>>"$TMP/err"; ok $? "sinewc builds the snake"
diag <"$TMP/err"
nc=$(nm "$TMP/cantilever" | grep -c ' [Tt] .*sw_muscle\| [Tt] filament_')
ne=$(nm "$TMP/elbow" | grep -c ' [Tt] .*sw_muscle\| [Tt] filament_')
echo "# muscle functions: cantilever $nc, elbow $ne; text: cantilever $(size "$TMP/cantilever" | awk 'NR == 2 { print $1 }') B, elbow $(size "$TMP/elbow" | awk 'NR == 2 { print $1 }') B"
[ "$nc" -eq 0 ]; ok $? "the cantilever's simulator holds no muscle code"
[ "$ne" -gt 0 ]; ok $? "the elbow's simulator holds the muscle code"
env() { nm "$1" | grep -c ' [Tt] sw_\(env\|ground\|fluid\|contact\|wave\)_'; }
ec=$(env "$TMP/cantilever"); es=$(env "$TMP/snake")
echo "# environment functions: cantilever $ec, snake $es; text: snake $(size "$TMP/snake" | awk 'NR == 2 { print $1 }') B"
[ "$ec" -eq 0 ]; ok $? "the cantilever's simulator holds no environment code"
[ "$es" -gt 0 ]; ok $? "the snake's simulator holds the environment code"
"$TMP/snake" --quiet --duration 1ms --out "$TMP/s.h5" >/dev/null 2>&1; ok $? "the snake runs"
"$TMP/cantilever" --quiet --duration 1ms --out "$TMP/c.h5" >/dev/null 2>&1; ok $? "the cantilever runs"
"$TMP/elbow" --quiet --duration 20us --out "$TMP/e.h5" >/dev/null 2>&1; ok $? "the elbow runs"
done_testing
