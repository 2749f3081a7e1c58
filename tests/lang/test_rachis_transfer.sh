#!/bin/sh
# test_rachis_transfer.sh — the minimal study of Zhang et al. 2019, Suppl.
# Fig. 4 (models/rachis_wall.sinew, scripts/rachis_transfer.py): a rachis
# clamped at a wall, a point force ramped at L_F.
#   - static limit: loaded slowly (ramp 0.75 s, the rachis' first bending
#     period is 0.3 s), the wall takes the whole force wherever it acts
#     (equilibrium of the rod), within 1%;
#   - the reference's claim: at t_m = 0.25 T and 0.5 T the reaction decays
#     with L_F / L, near linearly; the fit R = 1 - b L_F / L to all four
#     series (instantaneous and averaged, 5 positions) has b within 15% of
#     the reference wing's 1 (its barbs' loads reach the bone weighted
#     1 - L_F / L), and every series decreases.
. "$(dirname "$0")/tap.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$SINEWC" "$ROOT/models/rachis_wall.sinew" --let at_frac=1 -o "$tmp/tip" >/dev/null 2>&1
ok $? "the rachis with its load at the tip compiles"
(cd "$tmp" && ./tip --quiet --set t_m=1.5s --duration 1.5s --out "$tmp/slow.h5") >/dev/null 2>&1
ok $? "it runs loaded slowly"
/usr/bin/python3 - "$tmp/slow.h5" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
R = f["/rods/rachis/internal_force"][-1, 0, 0] / 1e-3
print("# loaded slowly, the wall takes %.5f of the force at the tip" % R)
sys.exit(0 if abs(R - 1) < 0.01 else 1)
PY
ok $? "the static limit: the wall takes the whole force (within 1%)"

/usr/bin/python3 "$ROOT/scripts/rachis_transfer.py" --sinewc "$SINEWC" --points 5 >"$tmp/table" 2>&1
ok $? "scripts/rachis_transfer.py runs"
diag <"$tmp/table"
awk -F'|' '/^\| [0-9]/ { for (c = 3; c <= 6; c++) { v = $c + 0; if (NR > 3 && v >= prev[c]) bad++; prev[c] = v } }
           END { exit bad > 0 }' "$tmp/table"
ok $? "every series decreases with L_F / L"
awk '/through the wall/ { b = $(NF - 3) + 0; printf "# slope %.3f against the reference wing'"'"'s 1\n", b
                          exit !(b > 0.85 && b < 1.15) }' "$tmp/table"
ok $? "the fit through the wall decays like the reference wing's weight 1 - L_F / L (slope within 15%)"
done_testing
