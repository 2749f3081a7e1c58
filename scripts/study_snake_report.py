#!/usr/bin/python3
"""study_snake_report.py — the table and plots of the muscular snake's study
(docs/validation.md, "The muscular snake's study"; Zhang et al. 2019,
Supplementary Note 4 and Fig. 2).

  study_snake_report.py DIR [--img DIR]

Design.  Reads DIR/continuum_study.h5 and DIR/K_study.h5 (K = 1..5 pairs)
that scripts/study_snake.sh writes, DIR/K_chain.h5 and DIR/chain_sources.txt
of its --chain (each stage started at the best design with one pair fewer),
and DIR/walltime.txt.  A chained stage's start design (the best design with
one pair fewer, the new pair at 20 N) is run too: what the stage had to beat.  For each
architecture: the evaluations, how many failed, the wall time, the best
forward speed (the scenes' objective, m/s) and its share of the continuum
snake's.  For the muscular ones, each pair's attachments are recomputed
from its position and span exactly as models/muscular_snake.sinew rounds
them to backbone nodes (x_a = round(pos (1 - span) n) / n, x_b =
round((pos (1 - span) + span) n) / n, n = 100), and two pairs overlap when
their attachment intervals share more than one node.  The reference's
claim that non-overlapping arrangements are 25-60% slower than overlapping
ones (Suppl. Note 4) is checked over every evaluated design: the best
speed among designs whose pairs overlap against the best among those whose
pairs do not.  Each architecture's best design is run again from its
simulator in DIR (as scripts/study_snake.sh left it), at the study's dt and
at half of it, with output: the first must give the objective the study
recorded, bit for bit; the second says how much of the speed is the step's;
and the first's frames give the body's largest roll (the ribs' tilt about
the body's axis) and the largest lift of its centre of mass.  Writes
DIR/report.md and the plots docs/img/study_snake_*.png.
"""
import os
import subprocess
import sys

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

N_BODY = 100          # backbone elements (Table 9, n_b)
ARCHS = ["1", "2", "3", "4", "5"]


def attachments(pos, span):
    """Element indices of a pair's two ends, as the model rounds them."""
    a = np.round(pos * (1 - span) * N_BODY)
    b = np.round((pos * (1 - span) + span) * N_BODY)
    return a, b


def designs(f):
    """Per evaluation: (score m/s, ok, [(a, b, amp, phase) per pair])."""
    names = texts(f["evaluations/params"].attrs["names"])
    P = f["evaluations/params"][()]
    units = texts(f["evaluations/params"].attrs["units"])
    score = f["evaluations/score"][()]
    status = f["evaluations/status"][()]
    k = 1
    pairs = []
    while "pos%d" % k in names:
        i = [names.index(s % k) for s in ("pos%d", "span%d", "amp%d", "phase%d")]
        a, b = attachments(P[:, i[0]], P[:, i[1]])
        phase = P[:, i[3]] * (180 / np.pi if units[i[3]] == "rad" else 1.0)
        pairs.append(np.stack([a, b, P[:, i[2]], phase], axis=1))
        k += 1
    return score, status, (np.stack(pairs, axis=1) if pairs else None)


def overlapping(pairs):
    """True where some two pairs' attachment intervals share more than a node."""
    n = pairs.shape[1]
    out = np.zeros(pairs.shape[0], dtype=bool)
    for i in range(n):
        for j in range(i + 1, n):
            lo = np.maximum(pairs[:, i, 0], pairs[:, j, 0])
            hi = np.minimum(pairs[:, i, 1], pairs[:, j, 1])
            out |= hi - lo > 0
    return out


def texts(values):
    """An HDF5 list of names or units as str."""
    return [v.decode() if isinstance(v, bytes) else str(v) for v in values]


def best_sets(f, only=None):
    """--set arguments giving the params of study file f's best design (those
    named in only, if given) in the units the file holds them in."""
    names = texts(f["evaluations/params"].attrs["names"])
    units = texts(f["evaluations/params"].attrs["units"])
    args = []
    for n, u, v in zip(names, units, f["best/params"][()]):
        if only is None or n in only:
            args += ["--set", ("%s=%.17g %s" % (n, v, u)).strip()]
    return args


def rerun(d, a, scene, f, dt=None):
    """The best design of study file f run alone: its output file (made once)."""
    out = os.path.join(d, "best_%s%s.h5" % (a, "_" + dt if dt else ""))
    if not os.path.exists(out):
        args = [os.path.join(d, scene), "--quiet", "--out", out]
        args += best_sets(f, texts(f["design/name"][()]))
        if dt:
            args += ["--dt", dt]
        subprocess.run(args, check=False, stdout=subprocess.DEVNULL)
    return h5py.File(out, "r") if os.path.exists(out) else None


def start_speed(d, k, scene, src):
    """The design a chained stage of k pairs started at, run alone: the best
    design of src (one pair fewer) and pair k at 20 N, its other params at
    the scene's values.  Its objective (m/s), or nan."""
    out = os.path.join(d, "best_%sc_start.h5" % k)
    if not os.path.exists(out) and os.path.exists(os.path.join(d, src)):
        with h5py.File(os.path.join(d, src), "r") as f:
            sets = best_sets(f)
        args = [os.path.join(d, scene), "--quiet", "--out", out, "--set", "amp%s=20 N" % k]
        subprocess.run(args + sets, check=False, stdout=subprocess.DEVNULL)
    if not os.path.exists(out):
        return np.nan
    with h5py.File(out, "r") as r:
        return float(r.attrs["objective"])


def planarity(run):
    """Largest rib tilt about the body axis (deg) and lift of the centre of mass (mm)."""
    z = run["probes/com"][:, 2]
    ribs = [k for k in run["rods"] if ".rib_" in k]
    roll = 0.0
    for r in ribs:
        x = run["rods/%s/position" % r][()]
        tip = x[:, -1] - x[:, 0]
        roll = max(roll, np.degrees(np.arcsin(np.abs(tip[:, 2]) / np.linalg.norm(tip, axis=1))).max())
    return roll, 1e3 * (z.max() - z[0])


def wall_times(d):
    t = {}
    p = os.path.join(d, "walltime.txt")
    if os.path.exists(p):
        for line in open(p):
            a, np_, budget, secs, n = line.split()
            t.setdefault(a, []).append((int(np_), float(secs), int(n)))
    return t


def check_best(d, a, scene, f, row):
    """The best design run again: at the study's dt (the same objective, bit
    for bit) and at half of it, and how planar its gait is."""
    ib = int(f["best"].attrs["index"])
    r20 = rerun(d, a, scene, f)
    r10 = rerun(d, a, scene, f, "10us")
    want = float(f["evaluations/objective"][ib])
    row["same"] = r20 is not None and float(r20.attrs["objective"]) == want
    row["rediff"] = abs(float(r20.attrs["objective"]) / want - 1) if r20 is not None else np.nan
    row["obj10"] = float(r10.attrs["objective"]) if r10 is not None else np.nan
    row["roll"], row["lift"] = planarity(r20) if r20 is not None else (np.nan, np.nan)


def studies(d):
    """The study files in d: (tag, path, scene, name), the continuum's first,
    then each architecture's own study and its chained one."""
    out = [("continuum", "continuum_study.h5", "snake_continuum_opt", "continuum (torque wave)")]
    for k in ARCHS:
        plural = "" if k == "1" else "s"
        out.append((k, "%s_study.h5" % k, "snake_pairs" + k, "%s pair%s" % (k, plural)))
        out.append((k + "c", "%s_chain.h5" % k, "snake_pairs" + k, "%s pair%s, chained" % (k, plural)))
    return [(t, os.path.join(d, p), sc, n) for t, p, sc, n in out if os.path.exists(os.path.join(d, p))]


def chain_sources(d):
    """Where each stage of the chain started: {k: (file, score)}."""
    src = {}
    p = os.path.join(d, "chain_sources.txt")
    if os.path.exists(p):
        for line in open(p):
            k, f, score = line.split()
            src[k] = (f, float(score))
    return src


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    d = sys.argv[1]
    img = sys.argv[sys.argv.index("--img") + 1] if "--img" in sys.argv else "docs/img"
    os.makedirs(img, exist_ok=True)
    walls = wall_times(d)
    sources = chain_sources(d)
    rows, best = [], {}
    cont = None
    for a, path, scene, name in studies(d):
        with h5py.File(path) as f:
            score, status, pairs = designs(f)
            objective = f["evaluations/objective"][()]
            penalty = f["evaluations/penalty"][()]
            done = status != 0                     # not pending (an interrupted study)
            score, status, objective, penalty = score[done], status[done], objective[done], penalty[done]
            ok = status == 1
            ib = int(np.argmax(np.where(ok, score, -np.inf)))   # the study's /best when complete
            row = {"a": a, "name": name, "n": len(score), "fail": int((~ok).sum()), "obj": objective[ib],
                   "pen": penalty[ib], "score": score[ib], "ov": None,
                   "status": str(f.attrs["status"]).split(":")[0]}
            if str(f.attrs["status"]).startswith("complete"):
                check_best(d, a, scene, f, row)
        if a.endswith("c") and a[:-1] in sources:
            row["from"] = sources[a[:-1]]
            row["start"] = start_speed(d, a[:-1], scene, sources[a[:-1]][0])
        if pairs is not None:
            pairs = pairs[done]
            ov = overlapping(pairs) if pairs.shape[1] > 1 else np.zeros(len(score), bool)
            row["ov"] = bool(ov[ib])
            row["b_ov"] = score[ok & ov].max() if (ok & ov).any() else np.nan
            row["b_no"] = score[ok & ~ov].max() if (ok & ~ov).any() else np.nan
            best[a] = (np.maximum.accumulate(np.where(ok, score, -np.inf)), pairs[ib])
        else:
            cont = row["obj"]
            best[a] = (np.maximum.accumulate(np.where(ok, score, -np.inf)), None)
        rows.append(row)
    if not rows:
        sys.exit("study_snake_report: no study files in %s" % d)

    # ---- the table ----
    out = ["| snake | evaluations (failed) | wall time (ranks) | best speed | of the continuum's "
           "| rerun = study | at 10 us | largest roll, lift | best overlaps | best overlapping / "
           "non-overlapping | non-overlapping slower by |",
           "|---|--:|--:|--:|--:|---|--:|--:|---|--:|--:|"]
    for r in rows:
        a = r["a"]
        wt = walls.get(a)
        wtxt = " + ".join("%.0f s (%d)" % (w[1], w[0]) for w in wt) if wt else "—"
        share = "%.0f%%" % (100 * r["obj"] / cont) if cont and a != "continuum" else "—"
        name = r["name"]
        if "from" in r:
            name += " from %s (%.1f mm/s; the start design: %.1f mm/s)" % (
                r["from"][0], 1e3 * r["from"][1], 1e3 * r["start"])
        if r["status"] != "complete":
            name += " (%s)" % r["status"]
        speed = "%.1f mm/s" % (1e3 * r["obj"]) + (" (penalty %.1f)" % (1e3 * r["pen"]) if r["pen"] > 0 else "")
        same = ("yes" if r["same"] else "%.0e apart" % r["rediff"]) if "same" in r else "—"
        at10 = ("%.1f mm/s (%+.1f%%)" % (1e3 * r["obj10"], 100 * (r["obj10"] / r["obj"] - 1))
                if "obj10" in r else "—")
        plan = "%.1f deg, %.1f mm" % (r["roll"], r["lift"]) if "roll" in r else "—"
        if r["ov"] is None or a == "1":
            ovtxt, cmp, slower = ("—" if r["ov"] is None else "no"), "—", "—"
        else:
            ovtxt = "yes" if r["ov"] else "no"
            mm = lambda v: "%.1f" % (1e3 * v) if np.isfinite(v) else "none"
            cmp = "%s / %s mm/s" % (mm(r["b_ov"]), mm(r["b_no"]))
            slower = ("%.0f%%" % (100 * (1 - r["b_no"] / r["b_ov"]))
                      if r["b_ov"] > 0 and np.isfinite(r["b_no"]) else "—")
        out.append("| %s | %d (%d) | %s | %s | %s | %s | %s | %s | %s | %s | %s |" %
                   (name, r["n"], r["fail"], wtxt, speed, share, same, at10, plan, ovtxt, cmp, slower))
    out.append("")
    out.append("Best designs (pair: attachments at backbone nodes a-b of %d, peak force, phase):" % N_BODY)
    out.append("")
    for r in rows:
        a = r["a"]
        if a == "continuum":
            continue
        p = best[a][1]
        out.append("- %s: " % r["name"] + "; ".join("%d-%d, %.0f N, %.0f deg" % tuple(q) for q in p))
    text = "\n".join(out) + "\n"
    open(os.path.join(d, "report.md"), "w").write(text)
    print(text)

    # ---- speed against the number of pairs, and the optimisations' paths ----
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    obj = {r["a"]: 1e3 * r["obj"] for r in rows}
    own = [(int(k), obj[k]) for k in ARCHS if k in obj]
    chained = [(int(k), obj[k + "c"]) for k in ARCHS if k + "c" in obj]
    if chained and "1" in obj:                 # the chain begins at the one-pair study
        chained = [(1, obj["1"])] + chained
    if own:
        ax[0].plot(*zip(*own), "o-", label="own study (CMA-ES from the scene's design)")
    if chained:
        ax[0].plot(*zip(*chained), "s--", label="chained (from the best with one pair fewer)")
    starts = [(int(r["a"][:-1]), 1e3 * r["start"]) for r in rows
              if "start" in r and np.isfinite(r["start"])]
    if starts:
        ax[0].plot(*zip(*starts), "x", color="C1", ms=8,
                   label="a chained stage's start (best with one pair fewer, new pair at 20 N)")
    if cont:
        ax[0].axhline(1e3 * cont, color="k", ls=":", label="continuum snake, best found")
    ax[0].set_xlabel("muscle-tendon pairs")
    ax[0].set_ylabel("forward speed of the centre of mass, 1-5 s (mm/s)")
    ax[0].set_xticks(range(1, 6))
    ax[0].legend(fontsize=8)
    ax[0].set_title("best speed against number of pairs")
    for r in rows:
        y = 1e3 * best[r["a"]][0]
        ax[1].plot(np.arange(1, len(y) + 1), np.where(np.isfinite(y), y, np.nan),
                   ls="--" if r["a"].endswith("c") else "-", label=r["name"])
    ax[1].set_xlabel("evaluation")
    ax[1].set_ylabel("best score so far: speed - penalty (mm/s)")
    ax[1].legend(fontsize=7)
    ax[1].set_title("CMA-ES, seed 1")
    fig.tight_layout()
    fig.savefig(os.path.join(img, "study_snake_speed.png"), dpi=110)

    # ---- the best designs, as in the reference's Fig. 2c: a row per kind ----
    kinds = [k for k in ("", "c") if any(a + k in best for a in ARCHS if a + k != "1c")]
    fig, ax = plt.subplots(len(kinds), 5, figsize=(16, 3.2 * len(kinds)), sharey=True, squeeze=False)
    for row, kind in enumerate(kinds):
        for c, k in enumerate(ARCHS):
            tag = k + kind if not (kind == "c" and k == "1") else "1"
            axis = ax[row][c]
            axis.set_xlim(0, N_BODY)
            axis.set_ylim(0, 520)                 # the box: 0 to 500 N
            axis.set_title("%s pair%s%s" % (k, "" if k == "1" else "s", ", chained" if kind else ""))
            axis.set_xlabel("vertebra (tail 0, head %d)" % N_BODY)
            if tag not in best:
                continue
            for i, (a, b, amp, ph) in enumerate(best[tag][1]):
                axis.plot([a, b], [amp, amp], "-", lw=3, color="C%d" % i)
                axis.plot([a, b], [amp, amp], "|", ms=10, color="C%d" % i)
        ax[row][0].set_ylabel("peak muscle force (N)")
    fig.tight_layout()
    fig.savefig(os.path.join(img, "study_snake_designs.png"), dpi=110)


if __name__ == "__main__":
    main()
