#!/bin/sh
# test_reproduce.sh — the machinery of `make reproduce` on studies made up
# here (the real studies take half an hour and more: `make reproduce`):
#   - scripts/reproduce/rows.py writes a study's meta, rows and conventions,
#     compares a number with the reference's (agree within the tolerance,
#     differ beyond it) and refuses a verdict that is not one of the four;
#   - scripts/reproduce_page.py counts the verdicts per study and in all,
#     says a failed study failed, lists the conventions and the figures that
#     are not bitwise reproducible, and copies the plots beside the page;
#   - scripts/reproduce.sh refuses a study it does not have, naming them.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch reproduce
PY=/usr/bin/python3
OUT=$TMP/out
mkdir -p "$OUT/good" "$OUT/bad"
$PY - "$ROOT/scripts/reproduce" "$OUT" >"$TMP/rows.log" 2>&1 <<'PYEOF'
import sys
sys.path.insert(0, sys.argv[1])
from rows import Study
out = sys.argv[2]
s = Study(out + "/good", "A good study", "Suppl. Note 0", models=["m.sinew"], commands=["SIM"])
assert s.compare("Fig. 1", "a length of 1 m", 1.004, 1.0, 0.01, "m") == "agree"
assert s.compare("Fig. 2", "a speed of 2 m/s", 2.5, 2.0, 0.01, "m/s", why_differ="the model differs") == "differ"
s.statement("Fig. 3", "it moves", True, "by 3 m", bitwise=False, why="threads sum in another order")
s.convention("sinew's default", "the reference's", "m.sinew", "+1%")
try:
    s.row("Fig. 4", "x", "y", "maybe")
    print("a verdict 'maybe' was accepted")
    sys.exit(1)
except ValueError as e:
    print("refused:", e)
open(out + "/good/plot.png", "wb").write(b"\x89PNG\r\n")
s.plot("plot.png")
s.write()
b = Study(out + "/bad", "A bad study", "Suppl. Note 9")
b.statement("Fig. 9", "it runs", False, "it stopped")
b.write()
PYEOF
ok $? "rows.py writes two studies, compares numbers and refuses a verdict that is not one of the four"
diag <"$TMP/rows.log"
printf '{"exit": 0, "wall": 61, "budget": "quick", "commit": "abc", "made": "now", "load": 0.5}\n' >"$OUT/good/status"
printf '{"exit": 1, "wall": 5, "budget": "quick", "commit": "abc", "made": "now", "load": 0.5}\n' >"$OUT/bad/status"
mkdir -p "$TMP/docs"
$PY scripts/reproduce_page.py "$OUT" --budget quick --page "$TMP/docs/page.md" --studies good bad >"$TMP/page.log" 2>&1
ok $? "reproduce_page.py writes the page"
diag <"$TMP/page.log"
grep -q "2 studies, 4 claims (2 agree or hold, 2 differ or fail); failed runs: bad" "$TMP/page.log"
ok $? "it counts the claims and names the failed study"
grep -q '^| \[A good study\](#good) | Suppl. Note 0 | 3 | 2 | 1 | 61 s (0.5) |' "$TMP/docs/page.md"
ok $? "the summary row of a study: its claims, verdicts, wall time and load"
grep -q '^| Fig. 1 | a length of 1 m | 1.004 m (+0.4%) | agree |' "$TMP/docs/page.md" &&
  grep -q '^| Fig. 2 | a speed of 2 m/s | 2.5 m/s (+25.0%) | \*\*differ\*\* | the model differs |' "$TMP/docs/page.md"
ok $? "a number within its tolerance agrees, one beyond it differs with its why"
grep -q '^\*\*The run failed\*\* (exit 1)' "$TMP/docs/page.md"
ok $? "a failed study says so in its section"
grep -q "^| sinew's default | the reference's | m.sinew | +1% |" "$TMP/docs/page.md"
ok $? "the conventions are listed with their effect"
grep -q "^- A good study, Fig. 3: threads sum in another order" "$TMP/docs/page.md"
ok $? "a figure that is not bitwise reproducible is listed with why"
[ -f "$TMP/docs/img/reproduce/good_plot.png" ] && grep -q '(img/reproduce/good_plot.png)' "$TMP/docs/page.md"
ok $? "the plots are copied beside the page and linked"
sh scripts/reproduce.sh quick --out "$TMP/none" nosuch 2>"$TMP/err"; rc=$?
[ $rc -eq 2 ] && grep -q "no study 'nosuch'.*the studies are: elbow" "$TMP/err"
ok $? "reproduce.sh refuses a study it does not have, naming its studies (exit $rc)"
done_testing
