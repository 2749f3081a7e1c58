#!/usr/bin/python3
"""wrap_report.py — the long version of tests/lang/test_wrap.sh: runs
examples/constructs/wrap.sinew at 12, 24 and 48 elements a muscle and
contact stiffnesses 1e3, 1e4 and 1e5 N/m, prints the table of
docs/validation.md ("Wrapping by contact") and draws
docs/img/wrap_moment_arm.png: (a) the moment arm against the joint angle,
the contact muscle's (from its tie's torque and from dL/dalpha) and the
via-point muscle's, on the geodesic and the via polygon's closed forms;
(b) the wrapped range's mean error against the element count, per stiffness;
and the finest run at 1, 2 and 4 rad/s (the dynamic allowance).

    scripts/wrap_report.py [--sinewc bin/sinewc] [--dir build/wrap] [-o PNG]

About 15 s of one core.
"""
import argparse
import math
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import wrap_analysis as w  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sinewc", default=os.path.join(ROOT, "bin/sinewc"))
    ap.add_argument("--dir", default=os.path.join(ROOT, "build/wrap"))
    ap.add_argument("-o", default=os.path.join(ROOT, "docs/img/wrap_moment_arm.png"))
    a = ap.parse_args()
    os.makedirs(a.dir, exist_ok=True)
    ex = os.path.join(ROOT, "examples/constructs/wrap.sinew")
    ns, ks = (12, 24, 48), (1e3, 1e4, 1e5)
    res = {}
    for n in ns:
        sim = os.path.join(a.dir, "wrap%d" % n)
        subprocess.run([a.sinewc, ex, "--let", "muscle_elements=%d" % n, "-o", sim], check=True)
        for k in ks:
            out = os.path.join(a.dir, "w_%d_%.0e.h5" % (n, k))
            subprocess.run([sim, "--quiet", "--set", "contact_stiffness=%g N/m" % k, "--out", out],
                           check=True)
            res[(n, k)] = w.analyse(out)
    print("| elements | k (N/m) | dphi (rad) | bias (mm) | largest error (mm) | "
          "bound: sink + polygon + dynamic (mm) | dL/dalpha largest error (mm) | L error |")
    print("|---|---|---|---|---|---|---|---|")
    for n in ns:
        for k in ks:
            d = res[(n, k)]
            m = w.wrapped_mask(d)
            dp = float(np.mean(d["le"][m] / d["R_eff"]))
            eF = np.abs(d["rF_w"] - d["r_geo"])[m]
            eL = np.abs(d["rL_w"] - d["r_geo"])[m]
            B = w.bound(d, k)[m]
            print("| %d | %.0e | %.3f | %+.4f | %.4f | %.4f + %.4f + %.2f | %.4f | %.1e |"
                  % (n, k, dp, 1e3 * w.bias(d), 1e3 * eF.max(), 1e3 * 5 * dp / k,
                     1e3 * d["R_eff"] * dp * dp / 8, 1e3 * w.E_DYN, 1e3 * eL.max(),
                     np.max(np.abs(d["L_w"] - d["L_geo"]) / d["L_geo"])))
    # the dynamic allowance: the finest run swept at 1, 2 and 4 rad/s over
    # the same angles (alpha up to 213 deg)
    sim = os.path.join(a.dir, "wrap48")
    for turn, dur in ((1, 2.275), (2, 1.2), (4, 0.6625)):
        out = os.path.join(a.dir, "speed_%d.h5" % turn)
        subprocess.run([sim, "--quiet", "--set", "contact_stiffness=1e5 N/m", "--set",
                        "turn=%g rad/s" % turn, "--duration", "%gs" % dur, "--out", out], check=True)
        r = w.analyse(out)
        m = w.wrapped_mask(r)
        print("48 elements, k = 1e5 N/m, %d rad/s: largest wrapped error %.4f mm (bias %+.4f mm)"
              % (turn, 1e3 * np.max(np.abs(r["rF_w"] - r["r_geo"])[m]), 1e3 * w.bias(r)))
    d = res[(24, 1e4)]
    s = w.summary(d)
    print("\ndefault (24, 1e4):", s)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker  # noqa: F401
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.2))
    deg = np.degrees(d["alpha"])
    al = np.linspace(d["alpha"][0], d["alpha"][-1], 400)
    a_, b_ = np.mean(d["a"]), np.mean(d["b"])
    ax.plot(np.degrees(al), [1e3 * w.geodesic(x, a_, b_, d["R_eff"])[1] for x in al], "k-",
            lw=1.5, label="geodesic over the cylinder (closed form)")
    ax.plot(deg[::3], 1e3 * d["rF_w"][::3], "o", ms=3.5, mfc="none", color="C0",
            label="contact: tie torque / tension")
    ax.plot(deg[::3], 1e3 * d["rL_w"][::3], "+", ms=5, color="C2", label="contact: dL/dalpha")
    ax.plot(deg, 1e3 * d["r_poly"], "--", color="C3", lw=1, label="via polygon R_v cos(gamma/2)")
    ax.plot(deg[::3], 1e3 * d["rL_r"][::3], "x", ms=4, color="C3", label="via points: dL/dalpha")
    ax.axvline(math.degrees(d["beta_sum"]), color="0.6", lw=0.8, ls=":")
    ax.text(math.degrees(d["beta_sum"]) + 1, 36, "wrap\nonset", fontsize=8, color="0.4")
    ax.set_xlabel("joint angle alpha (deg)")
    ax.set_ylabel("moment arm (mm)")
    ax.set_title("(a) 24 elements, k = 1e4 N/m, 5 N, 2 rad/s", fontsize=10)
    ax.legend(fontsize=7.5, loc="upper right")
    for k, c in zip(ks, ("C1", "C0", "C4")):
        bias = [w.bias(res[(n, k)]) for n in ns]
        bx.plot(ns, [1e3 * abs(b) for b in bias], "o-", color=c, label="k = %.0e N/m" % k)
        for n, b in zip(ns, bias):
            if b < 0:
                bx.plot([n], [1e3 * abs(b)], "s", mfc="none", ms=9, color=c)
    nn = np.array([12, 48])
    dp12 = np.mean(res[(12, 1e5)]["le"][w.wrapped_mask(res[(12, 1e5)])]) / d["R_eff"]
    bx.plot(nn, 1e3 * d["R_eff"] * (dp12 * 12 / nn) ** 2 / 8, "k:", lw=1, label="R dphi^2 / 8 (polygon)")
    bx.set_xscale("log")
    bx.set_yscale("log")
    bx.set_xticks(ns)
    bx.set_xticklabels([str(n) for n in ns])
    bx.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    bx.set_xlabel("elements of the muscle")
    bx.set_ylabel("|mean moment arm - R_eff| while wrapped (mm)")
    bx.set_title("(b) convergence (squares: below R_eff, the sink)", fontsize=10)
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.o, dpi=110)
    print("wrote", a.o)


if __name__ == "__main__":
    main()
