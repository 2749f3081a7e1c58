#!/usr/bin/python3
"""rachis_transfer.py — Zhang et al. 2019, Suppl. Fig. 4, reproduced: how much
of a load on a feather's rachis reaches the bone, against where it acts.

Runs models/rachis_wall.sinew (a rachis clamped at a wall, a point force of
1 mN at L_F ramped over 0.5 t_m and held) for L_F / L from 0.1 to 1 and for
t_m = 0.25 T and 0.5 T (T = 0.38 s), and reads the wall's reaction along the
force (the internal force of the first element, transverse, material d1 =
the force's direction): instantaneous at t_m over the peak force, and its
mean over [0, t_m] over the force's (the squares and diamonds of the
supplement's figure).  Then it fits R = a + b L_F / L to each of the four
series and to all of them, and R = 1 - b L_F / L (a load at the wall reaches
it whole) to all of them, least squares, and prints a table; with --plot
FILE it draws the figure.  With --points it takes fewer L_F (the test).

  scripts/rachis_transfer.py [--sinewc bin/sinewc] [--points N] [--plot FILE]
"""
import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

T = 0.38


def run(sinewc, model, frac, tm, work):
    exe = os.path.join(work, "rachis_%g" % frac)
    if not os.path.exists(exe):
        subprocess.run([sinewc, model, "-o", exe, "--let", "at_frac=%r" % frac], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    out = os.path.join(work, "r_%g_%g.h5" % (frac, tm))
    subprocess.run([exe, "--quiet", "--set", "t_m=%rs" % tm, "--duration", "%rs" % tm,
                    "--out", out], check=True, stdout=subprocess.DEVNULL)
    with h5py.File(out, "r") as f:
        t = f["/time"][:]
        n = f["/rods/rachis/internal_force"][:, 0, 0]   # transverse, along the force
    ramp = np.clip(t / (0.5 * tm), 0, 1) * 1e-3          # the force, N
    inst = n[-1] / 1e-3
    mean = np.trapz(n, t) / np.trapz(ramp, t)
    return inst, mean


def fit_through_wall(x, y):
    """R = 1 - b L_F / L: a load at the wall reaches it whole."""
    b = -np.dot(x, y - 1) / np.dot(x, x)
    return b, np.sqrt(np.mean((1 - b * x - y) ** 2))


def fit(x, y):
    A = np.vstack([np.ones_like(x), x]).T
    (a, b), res, *_ = np.linalg.lstsq(A, y, rcond=None)
    rms = np.sqrt(np.mean((A @ [a, b] - y) ** 2))
    return a, b, rms


def main():
    ap = argparse.ArgumentParser()
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--sinewc", default=os.path.join(here, "..", "bin", "sinewc"))
    ap.add_argument("--model", default=os.path.join(here, "..", "models", "rachis_wall.sinew"))
    ap.add_argument("--points", type=int, default=10)
    ap.add_argument("--plot")
    o = ap.parse_args()
    fracs = np.linspace(1.0 / o.points, 1.0, o.points)
    series = {}
    with tempfile.TemporaryDirectory() as work:
        for tm, label in ((0.25 * T, "0.25 T"), (0.5 * T, "0.5 T")):
            inst, mean = [], []
            for frac in fracs:
                i, m = run(o.sinewc, o.model, float(frac), tm, work)
                inst.append(i)
                mean.append(m)
            series["instantaneous, t_m = " + label] = np.array(inst)
            series["averaged, t_m = " + label] = np.array(mean)
    print("| L_F / L | " + " | ".join(series) + " |")
    print("|---" * (len(series) + 1) + "|")
    for k, frac in enumerate(fracs):
        print("| %.2f | " % frac + " | ".join("%.3f" % v[k] for v in series.values()) + " |")
    print()
    allx = np.concatenate([fracs] * len(series))
    ally = np.concatenate(list(series.values()))
    for name, y in list(series.items()) + [("all four", None)]:
        a, b, rms = fit(fracs, y) if y is not None else fit(allx, ally)
        print("fit %s: R = %.3f %+.3f L_F/L (rms %.3f)" % (name, a, b, rms))
    b, rms = fit_through_wall(allx, ally)
    print("fit all four through the wall: R = 1 - %.3f L_F/L (rms %.3f)" % (b, rms))
    if o.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        style = {"instantaneous, t_m = 0.25 T": ("s", "tab:red"),
                 "averaged, t_m = 0.25 T": ("D", "tab:red"),
                 "instantaneous, t_m = 0.5 T": ("s", "tab:blue"),
                 "averaged, t_m = 0.5 T": ("D", "tab:blue")}
        for name, y in series.items():
            mk, c = style[name]
            ax.plot(fracs, y, mk, color=c, label=name, mfc="none" if mk == "D" else c)
        b, _ = fit_through_wall(allx, ally)
        xs = np.linspace(0, 1, 50)
        ax.plot(xs, 1 - b * xs, "k-", lw=1, label="fit through the wall: 1 - %.2f L_F/L" % b)
        ax.plot(xs, 1 - xs, "k:", lw=1, label="the reference's wing: 1 - L_F/L")
        ax.set_xlabel("L_F / L")
        ax.set_ylabel("wall reaction / force")
        ax.set_xlim(0, 1.02)
        ax.set_ylim(-0.1, 1.2)
        ax.legend(fontsize=7)
        ax.set_title("A rachis at a wall (Zhang et al. 2019, Suppl. Fig. 4)", fontsize=9)
        fig.tight_layout()
        fig.savefig(o.plot, dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
