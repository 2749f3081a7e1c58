#!/usr/bin/python3
"""helical_buckling.py — the buckled envelope of bench/helical_buckling.sinew
against the localised helix of van der Heijden & Thompson.

  helical_buckling.py RUN.h5 [RUN.h5 ...] [--rod strand] [--plot OUT.png]

Design.  A rod of length L, bending stiffness B and twist stiffness C,
twisted through R = 2 pi N between its ends and with its ends brought a
distance D = d L closer (the slack), buckles into a localised helix
(Gazzola et al. 2018, sec. 3.4.4).  Its dimensionless end moment
m = M L / B and tension t = T L^2 / B solve (van der Heijden, Champneys &
Thompson, "Writhing instabilities of twisted rods: from infinite to finite
length", 2001/2002, eqs. 14-15, in the form Gazzola et al. 2018 use)

    d = sqrt(16 / t (1 - m^2 / (4 t))),   R = m / gamma + 4 acos(m / (2 sqrt t)),

with gamma = C / B; this script solves them by Newton's method from the
values PyElastica's HelicalBucklingCase states (m = 98.54, t = 2901).  The
localised helix (van der Heijden, Neukirch, Goss & Thompson, Int. J. Mech.
Sci. 45:161, 2003, eqs. 27 and 52), with s in [-1/2, 1/2] of L,
tau = t / (4 pi^2), mu = m / (2 pi) and rho = sqrt(4 tau - mu^2), has

    z(s) / L = s - rho / (2 pi tau) tanh(pi rho s),

so the cosine of the angle phi between its tangent and the axis is
dz/ds = 1 - rho^2 / (2 tau) sech^2(pi rho s), and the normalised envelope
(cos phi - cos phi_max) / (1 - cos phi_max) is tanh^2(pi rho s).  The
rod's envelope is the same quantity from its element chords (the axis is
the line through its end nodes), at the chords' mid arc lengths; the error
is its largest and its root-mean-square difference from the analytic
envelope there.
"""
import argparse
import math
import sys

import numpy as np

B, C = 1.345, 0.789            # N m^2 (PyElastica HelicalBucklingCase)
TURNS, SLACK_FRAC = 27.0, 0.03


def loads():
    """(m, t): the dimensionless end moment and tension, by Newton."""
    gam, R, d = C / B, 2 * math.pi * TURNS, SLACK_FRAC
    def f(v):
        m, t = v
        return np.array([math.sqrt(16 / t * (1 - m * m / (4 * t))) - d,
                         m / gam + 4 * math.acos(m / (2 * math.sqrt(t))) - R])
    v = np.array([98.5, 2900.0])
    for _ in range(50):
        J = np.empty((2, 2))
        for k in range(2):
            h = np.zeros(2)
            h[k] = 1e-7 * abs(v[k])
            J[:, k] = (f(v + h) - f(v - h)) / (2 * h[k])
        v = v - np.linalg.solve(J, f(v))
    return v


def analytic_envelope(s):
    """tanh^2(pi rho s) at s in [-1/2, 1/2] (fractions of L from the middle)."""
    m, t = loads()
    tau, mu = t / (4 * math.pi ** 2), m / (2 * math.pi)
    rho = math.sqrt(4 * tau - mu * mu)
    return np.tanh(math.pi * rho * s) ** 2


def rod_envelope(x):
    """Arc length from the middle (fraction of the length) and envelope."""
    axis = x[-1] - x[0]
    axis /= np.linalg.norm(axis)
    ch = np.diff(x, axis=0)
    ln = np.linalg.norm(ch, axis=1)
    cphi = ch @ axis / ln
    cmax = cphi.min()
    s = (np.cumsum(ln) - 0.5 * ln) / ln.sum() - 0.5
    return s, (cphi - cmax) / (1 - cmax)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("files", nargs="+")
    ap.add_argument("--rod", default="strand")
    ap.add_argument("--plot")
    a = ap.parse_args()
    import h5py
    m, t = loads()
    print(f"end moment m = M L / B = {m:.6f}, tension t = T L^2 / B = {t:.6f}")
    curves = []
    for fn in a.files:
        with h5py.File(fn, "r") as f:
            x = f[f"rods/{a.rod}/position"][-1]
            tt = f["time"][-1]
        s, env = rod_envelope(x)
        ref = analytic_envelope(s)
        err = env - ref
        print(f"{fn}: n = {len(x) - 1}, t = {tt:g} s: envelope error max {abs(err).max():.4f}, "
              f"rms {math.sqrt((err ** 2).mean()):.4f}")
        curves.append((len(x) - 1, s, env))
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 3.5))
        ss = np.linspace(-0.5, 0.5, 2001)
        ax.plot(ss, analytic_envelope(ss), "k-", lw=2, label="van der Heijden et al. 2003")
        for n, s, env in curves:
            ax.plot(s, env, ".-", ms=3, lw=0.8, label=f"sinew, n = {n}")
        ax.set_xlabel("s / L (from the middle)")
        ax.set_ylabel("(cos phi - cos phi_max) / (1 - cos phi_max)")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=110)


if __name__ == "__main__":
    sys.exit(main())
