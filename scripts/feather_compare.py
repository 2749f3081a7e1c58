"""feather_compare.py — examples/feather_resolved.sinew's two feathers: the
rachis tip's height (z) over the stroke, kinematic and resolved, each run
at two steps, against the root's rigid turn; a table and a plot.

  scripts/feather_compare.py RUN.h5 HALF_STEP_RUN.h5 [--plot FILE]

The root turns about y by theta = 20 deg (1 - cos 2 pi f t), f = 2.63 Hz;
a rigid feather's tip would be at z = -L sin(theta), L = 0.46 m.
"""
import argparse

import h5py
import numpy as np

F, L = 2.63, 0.46


def tips(path):
    f = h5py.File(path, "r")
    t = f["time"][:]
    k = f["probes/tip_k"][:]
    r = f["probes/tip_r"][:] - np.array([0, 1, 0])
    return t, k[:, 2], r[:, 2]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run")
    ap.add_argument("half")
    ap.add_argument("--plot")
    o = ap.parse_args()
    t, k, r = tips(o.run)
    t2, k2, r2 = tips(o.half)
    assert np.allclose(t, t2)
    rigid = -L * np.sin(np.radians(20) * (1 - np.cos(2 * np.pi * F * t)))
    print("| t (s) | root's turn (deg) | rigid tip z (mm) | kinematic tip z (mm) | resolved tip z (mm) |")
    print("|--:|--:|--:|--:|--:|")
    for i in range(0, len(t), 19):
        print("| %.3f | %.1f | %.1f | %.1f | %.1f |" % (t[i], np.degrees(np.radians(20) * (1 - np.cos(2 * np.pi * F * t[i]))),
                                                  1e3 * rigid[i], 1e3 * k[i], 1e3 * r[i]))
    print()
    print("largest |z|: rigid %.1f mm, kinematic %.1f mm, resolved %.1f mm" %
          (1e3 * abs(rigid).max(), 1e3 * abs(k).max(), 1e3 * abs(r).max()))
    print("step against half the step, largest tip difference: kinematic %.3g mm (%.2g of its largest), "
          "resolved %.3g mm (%.2g)" % (1e3 * abs(k - k2).max(), abs(k - k2).max() / abs(k).max(),
                                       1e3 * abs(r - r2).max(), abs(r - r2).max() / abs(r).max()))
    if o.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 3.6))
        ax.plot(t, 1e3 * rigid, "k:", label="root's turn, a rigid feather")
        ax.plot(t, 1e3 * k, label="kinematic barbs (the wing model)")
        ax.plot(t, 1e3 * r, label="resolved: barbs on fixed joints")
        ax.plot(t2, 1e3 * r2, "--", label="resolved, half the step")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("rachis tip z (mm)")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(o.plot, dpi=110)


if __name__ == "__main__":
    main()
