#!/usr/bin/python3
"""implicit_snake_report.py — the table of bench/bench_implicit_snake.sh.

Usage: implicit_snake_report.py OUT DURATION
Reads OUT/walls.txt and the runs' HDF5 files; prints Markdown: per
hardening, the median wall times of the explicit and implicit runs and
their ratio, the forward speed and lateral excursion of the centre of mass
over 2 s to the end, and the grid-scale share of the strains (the top
quarter of their cosine spectrum, as tests/e2e/test_snake.c measures it)."""
import subprocess
import sys

import h5py
import numpy as np

out, dur = sys.argv[1:3]
walls, dts = {}, {}
for line in open(f"{out}/walls.txt"):
    f, kind, val = line.split()
    if kind == "explicit_dt":
        dts[f.lstrip("x")] = val
    else:
        walls.setdefault((f.lstrip("x"), kind), []).append(float(val))


def gait(path):
    """Forward speed and lateral excursion of the centre of mass, t >= 2 s."""
    with h5py.File(path, "r") as h:
        t, com = h["/time"][:], h["/probes/com"][:]
    k0 = np.argmin(abs(t - 2.0))
    d = com[-1, :2] - com[k0, :2]
    speed = np.hypot(*d) / (t[-1] - t[k0])
    rel = com[k0:, :2] - com[k0, :2]
    lateral = np.max(abs(rel[:, 0] * d[1] - rel[:, 1] * d[0]) / np.hypot(*d))
    return speed, lateral


def grid_share(path):
    """Largest share of the strains' variance in the top quarter of their
    cosine spectrum over the interior elements, frames after 1 s; a strain
    component that stays below a millionth of the largest (the vertical
    shear: zero, or round-off in the implicit solve) is skipped."""
    with h5py.File(path, "r") as h:
        t, x, Q = h["/time"][:], h["/rods/snake.body/position"][:], h["/rods/snake.body/directors"][:]
    n = Q.shape[1]
    frames = np.nonzero(t >= 1.0)[0][::10]
    sigs = [np.einsum("irc,ic->ir", Q[k], np.diff(x[k], axis=0) * n) - np.array([0, 0, 1.0]) for k in frames]
    size = np.max([abs(s).max(axis=0) for s in sigs], axis=0)
    worst = 0.0
    for sig in sigs:
        for c in range(3):
            f = sig[2:n - 2, c]
            if size[c] < 1e-6 * size.max():
                continue
            m = len(f)
            i = np.arange(m)
            coef = np.array([np.sum((f - f.mean()) * np.cos(np.pi * q * (i + 0.5) / m)) for q in range(1, m)])
            total = np.sum(coef ** 2)
            top = np.sum(coef[np.arange(1, m) * 4 > 3 * m] ** 2)
            worst = max(worst, top / total if total > 0 else 0.0)
    return worst


rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
print(f"`make bench` (bench/bench_implicit_snake.sh), {dur} of `snake_hardening` on flat ground, "
      f"commit {rev}; medians of {len(walls[('25', 'explicit')])} interleaved runs of each on this "
      "2-core machine.  Explicit: position Verlet at 0.9 of the hardened snake's own stable "
      "estimate; implicit: `sinewc --let implicit=true`, `--integrator imex --dt 125us`, a step the "
      "original snake's explicit scheme runs at (its estimate is 121 us).\n")
print("| hardening | explicit dt | explicit wall | implicit wall (125 us) | speed-up | forward speed, "
      "explicit / implicit (m/s) | lateral excursion, explicit / implicit (m) | grid-scale share, "
      "explicit / implicit |")
print("|---|--:|--:|--:|--:|--:|--:|--:|")
for f in ("25", "100"):
    we, wi = np.median(walls[(f, "explicit")]), np.median(walls[(f, "implicit")])
    se, le = gait(f"{out}/explicit_{f}.h5")
    si, li = gait(f"{out}/implicit_{f}.h5")
    ge, gi = grid_share(f"{out}/explicit_{f}.h5"), grid_share(f"{out}/implicit_{f}.h5")
    print(f"| x{f} | {dts[f]} | {we:.1f} s | {wi:.1f} s | {we / wi:.2f}x | {se:.5f} / {si:.5f} "
          f"({100 * (si / se - 1):+.3f}%) | {le:.4f} / {li:.4f} ({100 * (li / le - 1):+.2f}%) | "
          f"{ge:.1e} / {gi:.1e} |")
so, lo = gait(f"{out}/original.h5")
print(f"\nThe original snake, explicit at 125 us: {so:.5f} m/s, lateral excursion {lo:.4f} m, "
      f"{float(open(f'{out}/original.wall').read()):.1f} s of wall time.")
