#!/usr/bin/python3
"""wing_fig13.py — Suppl. Fig. 13 of Zhang et al. 2019 with sinew: the
pigeon wing's shoulder and elbow angles (scripts/wing_angles.py, as the
reference's code defines them) for the original wing and its hardened or
softened variants, each variant's largest difference from the original as a
percentage of the original angle's range over the run, and a plot.

  scripts/wing_fig13.py ORIGINAL.h5 LABEL=VARIANT.h5 ... [--plot FILE]
                        [--table FILE] [--until T] [--title TEXT]

The reference states (Suppl. Note 6.7): twist and shear x10 on muscles,
tendons, bones and feathers changes the angles by up to ~3% (x25, x50, x100
change nothing further); shear and twist /5 on the muscles and tendons by up
to ~60%; twist alone softened, indiscernibly.  Runs that stopped early are
compared over the time they cover; a variant whose frames fall at other
times is interpolated linearly at the original's.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from wing_angles import angles  # noqa: E402

NAMES = ("shoulder, dorsal-ventral", "shoulder, antero-posterior", "elbow")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("original")
    ap.add_argument("variants", nargs="*", help="LABEL=FILE.h5")
    ap.add_argument("--plot")
    ap.add_argument("--table")
    ap.add_argument("--title", default="The kinematic wing hardened and softened "
                    "(Suppl. Fig. 13; models/pigeon_wing.sinew)")
    ap.add_argument("--until", type=float, default=0.42,
                    help="also compare up to this time (s): the antero-posterior angle, "
                         "atan(-x / |y|), is ill-conditioned where the humerus' end crosses y = 0")
    o = ap.parse_args()
    t0, *base = angles(o.original)
    rows = []
    curves = []
    for spec in o.variants:
        label, path = spec.split("=", 1)
        t, *ang = angles(path)
        n = int(np.sum(t0 <= t[-1] + 1e-12))   # the original's frames the variant covers
        if not (len(t) >= n and np.allclose(t[:n], t0[:n], rtol=0, atol=1e-9)):
            # frames at other times (another step, other --every): the
            # variant's angles interpolated linearly at the original's times
            ang = [np.interp(t0[:n], t, a) for a in ang]
            t = t0[:n]
        diffs = []
        early = int(np.sum(t[:n] <= o.until + 1e-12))
        for a, b in zip(ang, base):
            row = []
            for m in (n, early):
                rng = np.ptp(b[:m]) if m > 1 else 0.0
                d = np.max(np.abs(a[:m] - b[:m])) if m else 0.0
                row += [d, 100 * d / rng if rng > 0 else float("nan")]
            diffs.append(row)
        rows.append((label, t[n - 1] if n else 0.0, diffs))
        curves.append((label, t[:n], [a[:n] for a in ang]))
    lines = ["| variant | compared up to (s) | " + " | ".join(
        "%s: largest difference, deg (%% of the original's range); up to %g s" % (nm, o.until)
        for nm in NAMES) + " |",
        "|---|---|" + "---|" * len(NAMES)]
    for label, tend, diffs in rows:
        lines.append("| %s | %.3f | " % (label, tend) + " | ".join(
            "%.3g (%.1f%%); %.3g (%.1f%%)" % tuple(r) for r in diffs) + " |")
    print("\n".join(lines))
    if o.table:
        with open(o.table, "w") as f:
            f.write("\n".join(lines) + "\n")
    if o.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axs = plt.subplots(3, 1, figsize=(7, 7), sharex=True)
        for k, (ax, name) in enumerate(zip(axs, NAMES)):
            ax.plot(t0, base[k], "k-", lw=1.5, label="original")
            for (label, t, ang), style in zip(curves, ("C0--", "C3-", "C2:", "C1-.", "C7:", "C4--", "C5-.")):
                ax.plot(t, ang[k], style, lw=1, label=label)
            ax.set_ylabel(name + " (deg)", fontsize=8)
            ax.axvline(0.125, color="0.7", lw=0.8)
        axs[0].legend(fontsize=7, loc="best")
        axs[-1].set_xlabel("t (s); the initiation phase ends at 0.125 s")
        fig.suptitle(o.title, fontsize=9)
        fig.tight_layout()
        fig.savefig(o.plot, dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
