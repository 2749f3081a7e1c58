#!/usr/bin/python3
"""study_snake_report.py — the table and plots of the muscular snake's study
(docs/validation.md, "The muscular snake's study"; Zhang et al. 2019,
Supplementary Note 4 and Fig. 2).

  study_snake_report.py DIR [--img DIR]

Design.  Reads DIR/continuum_study.h5 and DIR/K_study.h5 (K = 1..5 pairs)
that scripts/study_snake.sh writes, and DIR/walltime.txt.  For each
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
pairs do not.  Writes DIR/report.md and the plots docs/img/study_snake_*.png.
"""
import os
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
    names = [n.decode() if isinstance(n, bytes) else str(n)
             for n in f["evaluations/params"].attrs["names"]]
    P = f["evaluations/params"][()]
    units = [u.decode() if isinstance(u, bytes) else str(u)
             for u in f["evaluations/params"].attrs["units"]]
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


def wall_times(d):
    t = {}
    p = os.path.join(d, "walltime.txt")
    if os.path.exists(p):
        for line in open(p):
            a, np_, budget, secs, n = line.split()
            t.setdefault(a, []).append((int(np_), float(secs), int(n)))
    return t


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    d = sys.argv[1]
    img = sys.argv[sys.argv.index("--img") + 1] if "--img" in sys.argv else "docs/img"
    os.makedirs(img, exist_ok=True)
    walls = wall_times(d)
    rows, best = [], {}
    cont = None
    path = os.path.join(d, "continuum_study.h5")
    if os.path.exists(path):
        with h5py.File(path) as f:
            cont = float(f["best"].attrs["score"])
            sc = f["evaluations/score"][()]
            st = f["evaluations/status"][()]
            sc, st = sc[st != 0], st[st != 0]
            best["continuum"] = (np.maximum.accumulate(np.where(st == 1, sc, -np.inf)), None)
            rows.append(("continuum", len(sc), int((st != 1).sum()), cont, None, None, None))
    for a in ARCHS:
        path = os.path.join(d, "%s_study.h5" % a)
        if not os.path.exists(path):
            continue
        with h5py.File(path) as f:
            score, status, pairs = designs(f)
        done = status != 0                     # not pending (an interrupted study)
        score, status, pairs = score[done], status[done], pairs[done]
        ok = status == 1
        ov = overlapping(pairs) if pairs.shape[1] > 1 else np.zeros(len(score), bool)
        b_ov = score[ok & ov].max() if (ok & ov).any() else np.nan
        b_no = score[ok & ~ov].max() if (ok & ~ov).any() else np.nan
        ib = int(np.argmax(np.where(ok, score, -np.inf)))   # the study's /best when complete
        best[a] = (np.maximum.accumulate(np.where(ok, score, -np.inf)), pairs[ib])
        rows.append((a, len(score), int((~ok).sum()), score[ib], bool(ov[ib]), b_ov, b_no))
    if not rows:
        sys.exit("study_snake_report: no study files in %s" % d)

    # ---- the table ----
    out = ["| snake | evaluations | failed | wall time (ranks) | best speed | of the continuum's "
           "| best design overlaps | best overlapping / non-overlapping | non-overlapping slower by |",
           "|---|--:|--:|--:|--:|--:|---|--:|--:|"]
    for a, n, nfail, s, ov, b_ov, b_no in rows:
        wt = walls.get(a)
        wtxt = " + ".join("%.0f s (%d)" % (w[1], w[0]) for w in wt) if wt else "—"
        share = "%.0f%%" % (100 * s / cont) if cont and a != "continuum" else "—"
        name = "continuum (torque wave)" if a == "continuum" else "%s pair%s" % (a, "" if a == "1" else "s")
        if ov is None:
            out.append("| %s | %d | %d | %s | %.1f mm/s | %s | — | — | — |" % (name, n, nfail, wtxt, 1e3 * s, share))
            continue
        if a == "1":
            cmp, slower = "—", "—"
        else:
            cmp = "%.1f / %.1f mm/s" % (1e3 * b_ov, 1e3 * b_no)
            slower = "%.0f%%" % (100 * (1 - b_no / b_ov)) if b_ov > 0 and np.isfinite(b_no) else "—"
        out.append("| %s | %d | %d | %s | %.1f mm/s | %s | %s | %s | %s |" %
                   (name, n, nfail, wtxt, 1e3 * s, share, "yes" if ov else "no", cmp, slower))
    out.append("")
    out.append("Best designs (pair: attachments at backbone nodes a-b of %d, peak force, phase):" % N_BODY)
    out.append("")
    for a in ARCHS:
        if a not in best:
            continue
        p = best[a][1]
        out.append("- %s: " % a + "; ".join("%d-%d, %.0f N, %.0f deg" % tuple(r) for r in p))
    text = "\n".join(out) + "\n"
    open(os.path.join(d, "report.md"), "w").write(text)
    print(text)

    # ---- speed against the number of pairs, and the optimisations' paths ----
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    ks = [int(a) for a in ARCHS if a in best]
    ax[0].plot(ks, [1e3 * r[3] for r in rows if r[0] != "continuum"], "o-", label="muscular snake, best found")
    if cont:
        ax[0].axhline(1e3 * cont, color="k", ls="--", label="continuum snake, best found")
    ax[0].set_xlabel("muscle-tendon pairs")
    ax[0].set_ylabel("forward speed of the centre of mass, 1-5 s (mm/s)")
    ax[0].set_xticks(range(1, 6))
    ax[0].legend()
    ax[0].set_title("best speed against number of pairs")
    for a, (path_, _) in best.items():
        y = 1e3 * path_
        ax[1].plot(np.arange(1, len(y) + 1), np.where(np.isfinite(y), y, np.nan),
                   label=a if a == "continuum" else "%s pair%s" % (a, "" if a == "1" else "s"))
    ax[1].set_xlabel("evaluation")
    ax[1].set_ylabel("best speed so far (mm/s)")
    ax[1].legend()
    ax[1].set_title("CMA-ES, seed 1")
    fig.tight_layout()
    fig.savefig(os.path.join(img, "study_snake_speed.png"), dpi=110)

    # ---- the best designs, as in the reference's Fig. 2c ----
    n = len(ks)
    fig, ax = plt.subplots(1, max(n, 1), figsize=(3.2 * max(n, 1), 3.2), sharey=True, squeeze=False)
    for c, k in enumerate(ks):
        p = best[str(k)][1]
        for i, (a, b, amp, ph) in enumerate(p):
            ax[0][c].plot([a, b], [amp, amp], "-", lw=3, color="C%d" % i)
            ax[0][c].plot([a, b], [amp, amp], "|", ms=10, color="C%d" % i)
        ax[0][c].set_xlim(0, N_BODY)
        ax[0][c].set_xlabel("vertebra (tail 0, head %d)" % N_BODY)
        ax[0][c].set_title("%d pair%s" % (k, "" if k == 1 else "s"))
    ax[0][0].set_ylabel("peak muscle force (N)")
    fig.tight_layout()
    fig.savefig(os.path.join(img, "study_snake_designs.png"), dpi=110)


if __name__ == "__main__":
    main()
