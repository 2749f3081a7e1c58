#!/usr/bin/env python3
"""snake_muscular_report.py (reproduce) — the rows of the muscular snake's
study for `make reproduce`, from the study files scripts/study_snake.sh
left (read with scripts/study_snake_report.py's functions, which rounds the
pairs to backbone nodes as the model does).

Claims of Suppl. Note 4 tested: the best speed rises with the pairs and
plateaus after four; the best designs' muscles overlap, unasked; among all
the evaluated designs, non-overlapping ones are 25-60% slower than
overlapping ones.  Fig. 2b: the centre of mass of each best design over its
first 3 s.

  snake_muscular_report.py OUTDIR quick|full
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(HERE))
import h5py  # noqa: E402
import numpy as np  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import study_snake_report as sr  # noqa: E402
from rows import Study  # noqa: E402


def best_of(path):
    """(best objective m/s, evaluations, its pairs or None, overlapping/non-overlapping bests, MPI ranks)"""
    with h5py.File(path, "r") as f:
        score, status, pairs = sr.designs(f)
        objective = f["evaluations/objective"][()]
        done = status != 0
        score, status, objective = score[done], status[done], objective[done]
        ok = status == 1
        ib = int(np.argmax(np.where(ok, score, -np.inf)))
        r = {"obj": float(objective[ib]), "n": int(len(score)), "pairs": None}
        if pairs is not None:
            pairs = pairs[done]
            ov = sr.overlapping(pairs) if pairs.shape[1] > 1 else np.zeros(len(score), bool)
            r["pairs"] = pairs[ib]
            r["ov"] = bool(ov[ib])
            r["b_ov"] = score[ok & ov].max() if (ok & ov).any() else np.nan
            r["b_no"] = score[ok & ~ov].max() if (ok & ~ov).any() else np.nan
        return r


def main():
    out, budget = sys.argv[1], sys.argv[2]
    archs = {}
    for a, path, scene, name in sr.studies(out):
        b = best_of(path)
        if a.endswith("c"):            # a chained stage: keep the better of the two
            k = a[:-1]
            if k in archs and archs[k]["obj"] >= b["obj"]:
                continue
            b["chained"] = True
        archs[a.rstrip("c")] = b
    n = {a: archs[a]["n"] for a in archs}
    s = Study(out, "Muscular snake: how many muscle pairs", "Suppl. Note 4, Figs. 2-3",
              models=["models/muscular_snake.sinew"] + ["examples/study/snake_pairs%d.sinew" % k for k in range(1, 6)] +
              ["examples/study/snake_continuum_opt.sinew"],
              commands=["scripts/study_snake.sh --budget %d --out DIR   # make study-snake; mpirun -np 2, seed 1"
                        % (32 if budget == "quick" else 300)] +
              (["scripts/study_snake.sh --chain --budget 250 --out DIR"] if budget == "full" else []))
    cont = archs.get("continuum", {}).get("obj", np.nan)
    speeds = [archs[str(k)]["obj"] if str(k) in archs else np.nan for k in range(1, 6)]
    txt = ", ".join("%d: %.1f" % (k, 1e3 * v) for k, v in zip(range(1, 6), speeds))
    short = ("" if budget == "full" else
             "at %d evaluations per architecture CMA-ES has run its first generations only (the reference: "
             "thousands); the full budget's study is in docs/validation.md, 'The muscular snake's study'" %
             min(n.values()))
    s.statement("Fig. 2a", "the best speed rises with the number of pairs, from one to four",
                all(np.diff(speeds[:4]) > 0), "best speed (mm/s) by pairs %s; continuum snake %.1f" % (txt, 1e3 * cont),
                short)
    s.statement("Fig. 2a", "the speed plateaus after four pairs (five pairs gain little)",
                speeds[4] <= speeds[3] * 1.05, "5 pairs %.1f mm/s against 4 pairs %.1f" % (1e3 * speeds[4], 1e3 * speeds[3]),
                short)
    s.statement("Fig. 2a", "the muscular snakes approach the continuum snake's speed",
                max(speeds) > 0.5 * cont, "the fastest reaches %.0f%% of the continuum's %.1f mm/s"
                % (100 * max(speeds) / cont, 1e3 * cont), short)
    ov = [k for k in range(2, 6) if str(k) in archs and archs[str(k)]["ov"]]
    s.statement("Fig. 2c, Fig. 3", "the optimiser finds designs whose muscles overlap, unasked",
                len(ov) >= 3, "the best design overlaps for %s pairs" % (", ".join(map(str, ov)) or "no number of"))
    slower = []
    for k in range(2, 6):
        r = archs.get(str(k))
        if r and np.isfinite(r["b_ov"]) and np.isfinite(r["b_no"]) and r["b_ov"] > 0:
            slower.append((k, 1 - r["b_no"] / r["b_ov"]))
    s.statement("Suppl. Note 4", "non-overlapping designs are 25-60% slower than overlapping ones",
                bool(slower) and all(0.25 <= x <= 0.6 for k, x in slower),
                "; ".join("%d pairs: %.0f%% slower" % (k, 100 * x) for k, x in slower) or
                "no architecture evaluated both kinds", short)
    # Fig. 2b: the best designs' centre of mass over their first 3 s
    fig, ax = plt.subplots(figsize=(6.4, 3.8))
    steps = set()  # the step the muscular snakes' best designs ran at (their files say)
    for a in ["1", "2", "3", "4", "5", "continuum"]:
        p = os.path.join(out, "best_%s.h5" % a)
        if not os.path.exists(p):
            p = os.path.join(out, "best_%sc.h5" % a)
        if not os.path.exists(p):
            continue
        with h5py.File(p, "r") as f:
            t, com = f["/time"][:], f["/probes/com"][:]
            if a != "continuum":
                steps.add("%.3g us" % (1e6 * f.attrs["dt"]))
        w = t <= 3.0 + 1e-9
        ax.plot(com[w, 0] - com[0, 0], com[w, 1] - com[0, 1], label=a if a == "continuum" else "%s pair%s" % (a, "s" if a != "1" else ""))
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title("centre of mass, t = 0 to 3 s (Suppl. Fig. 2b)")
    ax.legend(fontsize=8, frameon=False)
    s.save_plot(fig, "com_3s.png")
    s.note("Every evaluation runs 5 s of the scene at dt = %s (imex; the best designs' runs) and scores the centre "
           "of mass's mean forward "
           "speed over 1-5 s less a penalty for lifting it more than 5 mm. The evaluations of a study are spread "
           "over MPI ranks, but each one's result depends only on its design: the study files are the same for "
           "any number of ranks." % " and ".join(sorted(steps)))
    s.write()


if __name__ == "__main__":
    main()
