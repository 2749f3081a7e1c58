#!/usr/bin/python3
"""assisted_report.py — Suppl. Fig. 7 of Zhang et al. 2019 with sinew: the
injured elbow assisted by a twisted-fibre artificial muscle (AM), from the
runs of scripts/assisted_study.sh (DIR/healthy.h5, injured.h5, am_RATE.h5).

  scripts/assisted_report.py DIR [--plot FILE] [--table FILE] [--check]
                             [--from T]

Panels as the reference's: (b) the elbow's flexion against time, healthy,
injured and injured with the AM at each release rate; (c) the AM's force
(its attachment's spring) against time at each rate; (d) for the fastest
rate, the AM's twist k3 (its mean over the coil, measured, beside its rest
twist k3(0) r0 / r, the law the model sets) and its filament radius
r0 (1 + rate t) against time.  The table gives the flexion and the AM's
force at a few times, and the AM's shortening.

The reference states (Suppl. Note 6.2): the healthy elbow reaches higher
angles than the injured one; with the AM the injured one rises, more with
a faster release, towards the healthy one; the faster the release, the more
force.  Each statement is printed as holding or failing over the runs'
common time span from T (--from, default 0.2 s: past the ramps of the load
and the activation, before which the healthy and injured arms move alike);
with --check the script exits 1 if one fails.
"""
import argparse
import glob
import os
import re
import sys

import h5py
import numpy as np

R0 = 5e-3  # the AM's filament radius at t = 0 (Suppl. Table 3)


def load(path):
    with h5py.File(path, "r") as f:
        t = f["time"][:]
        flexion = -np.degrees(f["joints/arm.elbow/angle"][:])   # hinge angle: 0 straight, -flexion
        run = {"t": t, "flexion": flexion}
        if "joints/am[1].attach/force" in f:
            run["force"] = np.linalg.norm(f["joints/am[1].attach/force"][:], axis=1)
            x = f["rods/am[1].coil/position"][:]
            run["length"] = np.linalg.norm(x[:, -1] - x[:, 0], axis=1)
            if "rods/am[1].coil/curvature" in f:
                run["k3"] = f["rods/am[1].coil/curvature"][:, :, 2].mean(axis=1)
            run["rate"] = rate = float(dict(zip([n.decode() if isinstance(n, bytes) else n
                                          for n in f["params"]["name"]],
                                         f["params"]["value"]))["release_rate"])
            # the surface gap between neighbouring turns (nodes one turn
            # apart: 9 turns), against which the coil's self-contact acts;
            # the model's radius ramps over the 0.7 s of the study
            per_turn = (x.shape[1] - 1) // 9
            radius = R0 * (1 + rate * np.minimum(t, 0.7))
            d = np.linalg.norm(x[:, per_turn:] - x[:, :-per_turn], axis=2).min(axis=1)
            run["turn_gap"] = d - 2 * radius
    return run


def runs_of(d):
    runs = {}
    def take(name, p):
        try:
            runs[name] = load(p)
        except (OSError, KeyError) as e:   # a run still writing its file, or cut short
            print("assisted_report.py: %s skipped: %s" % (p, e), file=sys.stderr)

    for name in ("healthy", "injured"):
        p = os.path.join(d, name + ".h5")
        if os.path.exists(p):
            take(name, p)
    ams = []
    for p in glob.glob(os.path.join(d, "am_*.h5")):
        m = re.match(r"am_([0-9.]+)\.h5$", os.path.basename(p))
        if m:
            ams.append((float(m.group(1)), p))
    for rate, p in sorted(ams):
        take("am_%g" % rate, p)
    return runs


def at(run, key, t):
    return float(np.interp(t, run["t"], run[key]))


def table(runs, out):
    times = (0.1, 0.3, 0.5, 0.7)
    lines = ["| case | " + " | ".join("flexion at %g s" % t for t in times) +
             " | AM force at 0.35 s | at 0.7 s | AM shortening at 0.7 s | turns' least gap |",
             "|---|" + "--:|" * (len(times) + 4)]
    for name, r in runs.items():
        tend = r["t"][-1]
        cells = ["%.1f deg" % at(r, "flexion", t) if t <= tend + 1e-9 else "-" for t in times]
        if "force" in r:
            cells += ["%.0f N" % at(r, "force", 0.35) if tend >= 0.35 else "-",
                      "%.0f N" % at(r, "force", 0.7) if tend >= 0.7 - 1e-9 else "-",
                      "%.1f cm" % (100 * (r["length"][0] - at(r, "length", min(0.7, tend)))),
                      "%.1f mm" % (1e3 * r["turn_gap"].min())]
        else:
            cells += ["-", "-", "-", "-"]
        lines.append("| %s | %s |" % (name, " | ".join(cells)))
    text = "\n".join(lines) + "\n"
    if out:
        with open(out, "w") as f:
            f.write(text)
    sys.stdout.write(text)


def check(runs, t_from, found=None):
    """The reference's statements, each over the runs' common span from
    t_from: True when it holds at every one of 50 times there.  Each is
    printed and, when found is a list, appended to it as (statement,
    holds, figure)."""
    ams = [(r["rate"], r) for n, r in runs.items() if n.startswith("am_")]
    ams.sort(key=lambda x: x[0])
    tend = min(r["t"][-1] for r in runs.values())
    tt = np.linspace(t_from, tend, 50)
    flex = {n: np.interp(tt, r["t"], r["flexion"]) for n, r in runs.items()}
    ok = True

    def claim(text, holds, figure):
        nonlocal ok
        ok &= bool(holds)
        if found is not None:
            found.append((text, bool(holds), figure))
        print("%s: %s (%s)" % ("holds" if holds else "FAILS", text, figure))

    if "healthy" in flex and "injured" in flex:
        d = flex["healthy"] - flex["injured"]
        claim("the healthy elbow flexes more than the injured one", d.min() > 0,
              "least margin %.1f deg, at %.2f s %.1f vs %.1f deg" %
              (d.min(), tt[-1], flex["healthy"][-1], flex["injured"][-1]))
    if "injured" in flex:
        for rate, r in ams:
            d = flex["am_%g" % rate] - flex["injured"]
            claim("the AM at %g/s lifts the injured elbow" % rate, d.min() > 0,
                  "least margin %.1f deg" % d.min())
    for (ra, a), (rb, b) in zip(ams, ams[1:]):
        d = flex["am_%g" % rb] - flex["am_%g" % ra]
        claim("a release at %g/s flexes more than at %g/s" % (rb, ra), d.min() > 0,
              "least margin %.1f deg" % d.min())
        fa = np.interp(tt, a["t"], a["force"])
        fb = np.interp(tt, b["t"], b["force"])
        claim("a release at %g/s pulls harder than at %g/s on average" % (rb, ra),
              fb.mean() > fa.mean(), "mean %.0f vs %.0f N" % (fb.mean(), fa.mean()))
    return ok


def plot(runs, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
    styles = {"healthy": ("k", "-"), "injured": ("tab:red", "-")}
    dashes = [":", "--", "-"]
    ams = [n for n in runs if n.startswith("am_")]
    for name, r in runs.items():
        if name in styles:
            c, ls = styles[name]
            ax[0].plot(r["t"], r["flexion"], color=c, ls=ls, label=name)
    for i, name in enumerate(ams):
        r = runs[name]
        ls = dashes[max(0, len(dashes) - len(ams) + i)]
        lab = "injured + AM, %g/s" % r["rate"]
        ax[0].plot(r["t"], r["flexion"], color="tab:blue", ls=ls, label=lab)
        ax[1].plot(r["t"], r["force"], color="tab:blue", ls=ls, label="%g/s" % r["rate"])
    ax[0].set_xlabel("t (s)")
    ax[0].set_ylabel("elbow flexion (deg)")
    ax[0].set_title("(b) elbow angle")
    ax[0].legend(fontsize=8)
    ax[1].set_xlabel("t (s)")
    ax[1].set_ylabel("AM force (N)")
    ax[1].set_title("(c) artificial muscle's force")
    ax[1].legend(title="release rate", fontsize=8)
    if ams:
        r = runs[ams[-1]]
        t = r["t"]
        radius = R0 * (1 + r["rate"] * np.minimum(t, 0.7))
        a2 = ax[2].twinx()
        if "k3" in r:
            ax[2].plot(t, r["k3"], color="k", label="k3, mean over the coil")
            ax[2].plot(t, r["k3"][0] * R0 / radius, color="k", ls="--",
                       label="rest k3 = k3(0) r0 / r")
        ax[2].set_ylabel("k3 (1/m)")
        ax[2].set_xlabel("t (s)")
        ax[2].legend(fontsize=8, loc="lower left")
        a2.plot(t, 1e3 * radius, color="tab:blue")
        a2.set_ylabel("filament radius (mm)", color="tab:blue")
        ax[2].set_title("(d) twist released, %g/s" % r["rate"])
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--plot")
    ap.add_argument("--table")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--from", dest="t_from", type=float, default=0.2)
    o = ap.parse_args()
    runs = runs_of(o.dir)
    if not runs:
        sys.exit("assisted_report.py: no runs in %s" % o.dir)
    table(runs, o.table)
    if o.plot:
        plot(runs, o.plot)
    ok = check(runs, o.t_from)
    if o.check and not ok:
        sys.exit(1)


if __name__ == "__main__":
    main()
