#!/usr/bin/python3
"""wing_resolved_compare.py — the pigeon wing's joint angles, kinematic
(models/pigeon_wing.sinew: the reference's shortcut of Suppl. Note 5.3)
against fully resolved (models/pigeon_wing_resolved.sinew: every barb and
rachis on an ordinary joint), and optionally a third run (the resolved wing
at another step).  The angles are scripts/wing_angles.py's (the reference
code's definitions).  Prints the angles at a few times and the largest
differences, over the whole run and before the last 0.09 s (where the
antero-posterior angle is ill-conditioned: the humerus' end passes over
y = 0 of its root); with --plot FILE draws the angles of both runs.

  scripts/wing_resolved_compare.py KINEMATIC.h5 RESOLVED.h5 [--other RUN.h5 --other-label L]
      [--plot FILE]
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from wing_angles import angles  # noqa: E402

NAMES = ("shoulder, dorsal-ventral", "shoulder, antero-posterior", "elbow")


def common(a, b):
    """Both runs on the frames they share (the same output times)."""
    ta, tb = a[0], b[0]
    n = min(len(ta), len(tb))
    if not np.allclose(ta[:n], tb[:n], atol=1e-9):
        sys.exit("the runs' frames are at different times")
    return [x[:n] for x in a], [x[:n] for x in b]


def report(label, a, b):
    t = a[0]
    early = t <= 0.42
    print("# %s: largest difference (deg), whole run / to 0.42 s; and of the first run's range" % label)
    for k, name in enumerate(NAMES):
        d = np.abs(a[k + 1] - b[k + 1])
        rng = np.ptp(a[k + 1])
        print("#   %-28s %.4g / %.4g deg  (%.3g%% / %.3g%% of %.4g deg)" % (
            name, d.max(), d[early].max(), 100 * d.max() / rng, 100 * d[early].max() / rng, rng))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("kinematic")
    p.add_argument("resolved")
    p.add_argument("--other")
    p.add_argument("--other-label", default="resolved, other step")
    p.add_argument("--plot")
    o = p.parse_args()
    kin, res = common(angles(o.kinematic), angles(o.resolved))
    t = kin[0]
    print("t_s  kin_dv res_dv  kin_ap res_ap  kin_elbow res_elbow  (deg)")
    for tt in (0.05, 0.1, 0.125, 0.2, 0.3, 0.4, 0.5):
        k = int(np.argmin(np.abs(t - tt)))
        if abs(t[k] - tt) > 0.003:
            continue
        print("%.3f  %7.2f %7.2f  %7.2f %7.2f  %7.2f %7.2f" % (
            t[k], kin[1][k], res[1][k], kin[2][k], res[2][k], kin[3][k], res[3][k]))
    report("resolved - kinematic", kin, res)
    other = None
    if o.other:
        res2, oth = common(res, angles(o.other))
        report("%s - resolved" % o.other_label, res2, oth)
        other = oth
    if o.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(3, 1, figsize=(6.5, 6.5), sharex=True)
        for k, a in enumerate(ax):
            a.plot(kin[0], kin[k + 1], "k-", lw=1.2, label="kinematic (the reference's shortcut)")
            a.plot(res[0], res[k + 1], "r--", lw=1.2, label="fully resolved")
            if other is not None:
                a.plot(other[0], other[k + 1], "b:", lw=1.2, label=o.other_label)
            a.set_ylabel(NAMES[k] + " (deg)", fontsize=8)
            a.axvline(0.125, color="0.7", lw=0.8)
        ax[0].legend(fontsize=7, loc="best")
        ax[-1].set_xlabel("t (s); the initiation phase ends at 0.125 s")
        fig.suptitle("The pigeon wing's joint angles, kinematic and fully resolved", fontsize=9)
        fig.tight_layout()
        fig.savefig(o.plot, dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
