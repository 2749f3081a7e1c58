#!/usr/bin/python3
"""plectoneme_report.py — the figure and the table of `make plectoneme`
(scripts/plectoneme_study.sh) from its runs' .csv and .json files.

  plectoneme_report.py DIR [--plot OUT.png]

Prints a Markdown table; --plot draws (a) the thick rod's torque against
the end's rotation at three twisting rates beside C / L, Greenhill's
critical twist under tension, the loop's and the ply's torques; (b) its
writhe, twist, average crossing number and self-contacts at the slowest
rate, and the control's link; (c) the buckling onset (|Wr| = 0.01 turns)
against the square root of the twisting rate, extrapolated to rate zero;
(d) the torque of the three rods (thick at the slowest rate, thin, very
thin) over the loop's torque against the rotation over Phi_c, beside each
one's long-ply torque.

Design.  A bifurcation crossed by a slow ramp of its parameter is seen late:
the unstable mode must grow from the imperfection, and near the threshold
its rate grows as the square root of the distance past it, so the delay in
the parameter goes as the square root of the ramp's rate (times the
logarithm of the imperfection; the slow passage through a pitchfork,
e.g. Lobry, Dynamic bifurcations, 1991).  The onset at three rates is fitted
by Phi_on = Phi_0 + a sqrt(rate) (least squares) and Phi_0 is compared with
Greenhill's Phi_c; a free exponent, fitted exactly through the three, is
printed beside it.
"""
import argparse
import json
import math
import os

import numpy as np

RATES = (40, 80, 160)


def load(d, name):
    p = os.path.join(d, name)
    if not os.path.exists(p + ".json"):
        return None, None
    rows = np.loadtxt(p + ".csv", delimiter=",", skiprows=1)
    return rows, json.load(open(p + ".json"))


def after_snap(rows, j):
    """The frames of the twisting after the snap, before any Lk jump: from
    0.2 turns after the torque has fallen half-way from its peak to its last
    value, to the end of the twist."""
    s, r = j["summary"], j["ref"]
    t, ph, tau = rows[:, 0], rows[:, 1], rows[:, 2]
    k = int(np.argmax(tau))
    half = 0.5 * (tau[k] + tau[-1])
    down = np.nonzero((np.arange(len(tau)) > k) & (tau < half))[0]
    if not len(down):
        return np.zeros(len(t), bool)
    ok = (ph > ph[down[0]] + 0.2) & (t <= r["twist_time"] + 1e-9)
    return ok & (np.abs(rows[:, 5] - rows[:, 1]) < 0.5)


def plateau(rows, j):
    """Mean torque and its spread over the twisting after the snap."""
    t, ph, tau = rows[:, 0], rows[:, 1], rows[:, 2]
    ok = after_snap(rows, j)
    if not ok.any():
        return float("nan"), float("nan"), 0.0
    v = tau[ok]
    return float(v.mean()), float((v.max() - v.min()) / v.mean()), float(ph[ok].max() - ph[ok].min())


def held(rows, j):
    """Mean torque over the last 2 s of the hold, if Lk held to then."""
    t = rows[:, 0]
    ok = t >= t[-1] - 2.0
    if (np.abs(rows[:, 5] - rows[:, 1]) > 0.5).any() or t[-1] <= j["ref"]["twist_time"] + 2.0:
        return float("nan")
    return float(rows[ok, 2].mean())


def drag(rows, j):
    """The damping's drag on the whole rod moving at the end's reel-in speed
    after the snap, over the tension: gamma |dz/dt| L / F (an upper bound of
    how far the twisting is from quasi-static)."""
    r = j["ref"]
    t = rows[:, 0]
    ok = after_snap(rows, j)
    if ok.sum() < 3:
        return float("nan")
    v = abs(np.polyfit(t[ok], rows[ok, 9], 1)[0])
    return r.get("damping", float("nan")) * v * r["L"] / r["F"]


def writhe_rate(rows, j):
    """dWr / d(turns) over the same stretch: the share of each further turn
    that goes into writhe."""
    ph = rows[:, 1]
    ok = after_snap(rows, j)
    if ok.sum() < 3:
        return float("nan")
    return float(np.polyfit(ph[ok], rows[ok, 4], 1)[0])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--plot")
    a = ap.parse_args()
    runs = {n: load(a.dir, n) for n in [f"thick_{k}" for k in RATES] + ["control_40", "thin", "vthin"]}
    print("| run | C/(L-l/2) slope ratio | Phi_c Greenhill (turns) | onset, abs(Wr) = 0.01 (turns) | "
          "torque peak (mN m) at (turns) | torque after the snap (mN m), spread, over (turns) | held (mN m) | drag / F | "
          "(4/pi) sqrt(BF), ply model (mN m) | max abs(Lk - rotation) | min distance / 2r | "
          "dWr/dturn after the snap | final Wr, ACN, contacts, end z (m) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for n, (rows, j) in runs.items():
        if j is None:
            continue
        s, r = j["summary"], j["ref"]
        pm, spread, over = plateau(rows, j)
        print(f"| {n} | {s['slope_ratio_discrete']:.5f} | {r['Phic_turns']:.4f} | {s['turns_wr_001']:.3f} "
              f"({s['turns_wr_001'] / r['Phic_turns']:.3f} Phi_c) | {1e3 * s['peak_tau']:.3f} at {s['peak_turns']:.2f} | "
              f"{1e3 * pm:.4f}, {100 * spread:.0f} %, {over:.2f} | {1e3 * held(rows, j):.4f} | {drag(rows, j):.2f} | "
              f"{1e3 * r['M_loop']:.4f}, {1e3 * r['M_plateau']:.4f} | "
              f"{s['lk_err']:.2e} (first jump t = {s['first_lk_jump_t']:g} s) | {s['min_gap']:.4f} | "
              f"{writhe_rate(rows, j):.3f} | {s['final_wr']:.3f}, {s['final_acn']:.2f}, {s['final_contacts']}, {s['final_z']:.3f} |")
    # onset against sqrt(rate)
    on, rate = [], []
    for k in RATES:
        rows, j = runs[f"thick_{k}"]
        if j is None:
            continue
        on.append(j["summary"]["turns_wr_001"])
        rate.append(j["ref"]["turns"] / j["ref"]["twist_time"])
    fit = None
    if len(on) >= 2:
        A = np.stack([np.ones(len(on)), np.sqrt(rate)], 1)
        fit = np.linalg.lstsq(A, np.array(on), rcond=None)[0]
        phic = runs["thick_40"][1]["ref"]["Phic_turns"]
        print(f"\nonset fit Phi_on = Phi_0 + a sqrt(rate): Phi_0 = {fit[0]:.4f} turns = {fit[0] / phic:.4f} Phi_c "
              f"(Greenhill under tension {phic:.4f}), a = {fit[1]:.3f}; residuals "
              + ", ".join(f"{v:+.4f}" for v in np.array(on) - A @ fit))
        if len(on) == 3:
            # free exponent: (on1 - on2) / (on2 - on3) = (r1^p - r2^p) / (r2^p - r3^p), rates halving
            q = (on[0] - on[1]) / (on[1] - on[2])
            p = math.log(q) / math.log(2) if q > 0 else float("nan")
            x = np.array(rate) ** p
            b = (on[0] - on[1]) / (x[0] - x[1])
            print(f"free exponent: p = {p:.3f}, Phi_0 = {on[0] - b * x[0]:.4f} turns = {(on[0] - b * x[0]) / phic:.4f} Phi_c")
    if not a.plot:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 2, figsize=(11, 8))
    rows40, j40 = runs["thick_40"]
    r = j40["ref"]
    for k, c in zip(RATES, ("0.6", "0.35", "k")):
        rows, j = runs[f"thick_{k}"]
        if j is None:
            continue
        ramp = rows[:, 0] <= j["ref"]["twist_time"] + 1e-9
        ax[0, 0].plot(rows[ramp, 1], 1e3 * rows[ramp, 2], "-", color=c, lw=1.2,
                      label=f"sinew, {j['ref']['turns']:.0f} turns in {j['ref']['twist_time']:.0f} s")
        ax[0, 0].plot(rows[~ramp, 1], 1e3 * rows[~ramp, 2], "o", mfc="none", color=c, ms=4)
    xs = np.linspace(0, 4, 10)
    ax[0, 0].plot(xs, 1e3 * r["slope_discrete"] * 2 * math.pi * xs, "b--", lw=0.8, label="C Phi / (L - l/2)")
    ax[0, 0].axvline(r["Phic_turns"], color="r", ls=":", label="Greenhill under tension")
    ax[0, 0].axhline(1e3 * r["M_loop"], color="m", ls="--", lw=0.8, label="loop: (4/pi) sqrt(B F)")
    ax[0, 0].axhline(1e3 * r["M_plateau"], color="g", ls="--", lw=0.8, label="long touching ply")
    ax[0, 0].set_xlabel("end rotation (turns)")
    ax[0, 0].set_ylabel("torque at the clamp (mN m)")
    ax[0, 0].set_title(f"(a) r = 5 mm, n = 50, L sqrt(F/B) = {r['lam']:.0f}; circles: held", fontsize=9)
    ax[0, 0].legend(fontsize=7)
    rows, j = runs["thick_160"]
    if j is not None:
        ramp = rows[:, 0] <= j["ref"]["twist_time"] + 1e-9
        b = ax[0, 1]
        b.plot(rows[ramp, 1], rows[ramp, 4], "k-", label="writhe Wr")
        b.plot(rows[ramp, 1], rows[ramp, 3], "b-", label="twist Tw")
        ok = ramp & np.isfinite(rows[:, 6])
        b.plot(rows[ok, 1], rows[ok, 6], "m.-", ms=3, label="average crossing number")
        b.plot(rows[ramp, 1], rows[ramp, 7], "g.", ms=3, label="self-contact clusters")
        b.plot(rows[ramp, 1], rows[ramp, 5], "k:", lw=0.8, label="Lk = Tw + Wr")
    rc, jc = runs["control_40"]
    if jc is not None:
        ramp = rc[:, 0] <= jc["ref"]["twist_time"] + 1e-9
        ax[0, 1].plot(rc[ramp, 1], rc[ramp, 5], "r--", lw=1, label="Lk, control (no self-contact)")
    ax[0, 1].set_xlabel("end rotation (turns)")
    ax[0, 1].set_ylabel("turns / count")
    ax[0, 1].set_title("(b) 4 turns in 160 s", fontsize=9)
    ax[0, 1].legend(fontsize=7)
    if fit is not None:
        sr = np.sqrt(rate)
        ax[1, 0].plot(sr, on, "ko", label="sinew: abs(Wr) = 0.01 turns")
        xx = np.linspace(0, sr.max() * 1.1, 20)
        ax[1, 0].plot(xx, fit[0] + fit[1] * xx, "k--", lw=0.8, label="Phi_0 + a sqrt(rate)")
        ax[1, 0].axhline(r["Phic_turns"], color="r", ls=":", label="Greenhill under tension")
        ax[1, 0].set_xlabel("sqrt(twisting rate) (sqrt(turns/s))")
        ax[1, 0].set_ylabel("onset (turns)")
        ax[1, 0].set_title("(c) buckling onset against the rate", fontsize=9)
        ax[1, 0].legend(fontsize=7)
    d = ax[1, 1]
    for name, c in (("thick_160", "k"), ("thin", "b"), ("vthin", "m")):
        rt, jt = runs[name]
        if jt is None:
            continue
        q = jt["ref"]
        ramp = rt[:, 0] <= q["twist_time"] + 1e-9
        good = np.abs(rt[:, 5] - rt[:, 1]) < 0.5
        lab = f"r = {1e3 * q['r']:g} mm, L sqrt(F/B) = {q['lam']:.0f}, n = {q['n']}"
        d.plot(rt[ramp & good, 1] / q["Phic_turns"], rt[ramp & good, 2] / q["M_loop"], "-", color=c, lw=1, label=lab)
        d.plot(rt[~ramp & good, 1] / q["Phic_turns"], rt[~ramp & good, 2] / q["M_loop"], "o", mfc="none", color=c, ms=4)
        d.axhline(q["M_plateau"] / q["M_loop"], color=c, ls="--", lw=0.8)
    d.axhline(1.0, color="0.5", ls=":", label="loop: (4/pi) sqrt(B F)")
    d.set_ylim(0, 3)
    d.set_xlabel("end rotation / Phi_c")
    d.set_ylabel("torque / ((4/pi) sqrt(B F))")
    d.set_title("(d) after the snap, three rods; dashed: each one's long ply", fontsize=9)
    d.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(a.plot, dpi=100)


if __name__ == "__main__":
    main()
