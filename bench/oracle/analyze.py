#!/usr/bin/python3
"""Post-process snake_oracle.py outputs: metrics table (JSON + markdown), CSVs, plots."""
import glob
import json
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

RUNS = os.environ.get("ORACLE_RUNS", "runs")
OUT = os.environ.get("ORACLE_OUT", ".")


def load(name):
    d = np.load(os.path.join(RUNS, name + ".npz"))
    out = {k: d[k] for k in d.files}
    out["args"] = json.loads(str(d["args"]))
    out["name"] = name
    return out


def wall_from_log(name):
    p = os.path.join(RUNS, name + ".log")
    if not os.path.exists(p):
        return None
    w = None
    for line in open(p):
        if line.startswith("WALL"):
            w = float(line.split()[1])
    return w


def spec(sig):
    x = sig - sig.mean()
    P = np.abs(np.fft.rfft(x)) ** 2
    return P


def upper_half_share(sig):
    P = spec(sig)
    ks = np.arange(P.size)
    tot = P[1:].sum()
    return float(P[ks > 0.5 * (sig.size // 2)].sum() / tot) if tot > 0 else 0.0


def dominant_k(sig):
    P = spec(sig)
    return int(np.argmax(P[1:]) + 1)


def grid_share(sig):
    """sig: (n_elem,) -> share of (mean-removed) variance in the top quarter of
    the rFFT wavenumbers (k > 0.75 k_Nyquist)."""
    x = sig - sig.mean()
    P = np.abs(np.fft.rfft(x)) ** 2
    n = x.size
    kmax = n // 2
    ks = np.arange(P.size)
    top = ks > 0.75 * kmax
    tot = P[1:].sum()
    return float(P[top].sum() / tot) if tot > 0 else 0.0


def save_csv(r):
    t = r["time"]
    com = r["com"]
    head = r["position"][:, :, -1]
    tail = r["position"][:, :, 0]
    arr = np.column_stack([t, com, head, tail])
    np.savetxt(os.path.join(RUNS, r["name"] + "_com.csv"), arr, delimiter=",",
               header="t,com_x,com_y,com_z,head_x,head_y,head_z,tail_x,tail_y,tail_z", comments="")


def flat_metrics(r, t0=2.0, t1=10.0, last=None):
    t = r["time"]
    if last is None:
        last = (t[-1] - 4.0, t[-1])
    com = r["com"]
    pos = r["position"]
    finite = bool(np.all(np.isfinite(pos)))
    i0 = np.argmin(abs(t - t0))
    i1 = np.argmin(abs(t - min(t1, t[-1])))
    disp = com[i1] - com[i0]
    dt = t[i1] - t[i0]
    m = {}
    m["t_end"] = float(t[-1])
    m["finite"] = finite
    m["vx_mean_2_10"] = float(disp[0] / dt)
    m["speed_mean_2_10"] = float(np.linalg.norm(disp[:2]) / dt)
    m["heading_deg_2_10"] = float(np.degrees(np.arctan2(disp[1], disp[0])))
    m["com_final"] = com[-1].tolist()
    sel = (t >= last[0] - 1e-9) & (t <= last[1] + 1e-9)
    y = com[sel, 1]
    tt = t[sel]
    m["com_y_ptp_last4"] = float(np.ptp(y))
    w = (t >= 2.0 - 1e-9) & (t <= 5.0 + 1e-9)
    for lab, yy in (("com", com[w, 1]), ("head", pos[w, 1, -1])):
        cc = np.polyfit(t[w], yy, 1)
        m[lab + "_y_ptp_detrended_2_5"] = float(np.ptp(yy - np.polyval(cc, t[w])))
    # remove the linear drift (heading not exactly +x) before ptp
    c = np.polyfit(tt, y, 1)
    m["com_y_ptp_detrended_last4"] = float(np.ptp(y - np.polyval(c, tt)))
    hy = pos[sel, 1, -1]
    m["head_y_ptp_last4"] = float(np.ptp(hy))
    c = np.polyfit(tt, hy, 1)
    m["head_y_ptp_detrended_last4"] = float(np.ptp(hy - np.polyval(c, tt)))
    # body envelope: lateral extent of the body (perpendicular to mean heading), time-averaged
    hd = disp[:2] / np.linalg.norm(disp[:2])
    perp = np.array([-hd[1], hd[0]])
    lat = np.einsum("i,tin->tn", perp, pos[sel, :2, :])
    m["body_lateral_extent_mean_last4"] = float(np.mean(lat.max(1) - lat.min(1)))
    # envelope of body relative to CoM across last 4 periods (Fig. 10c style)
    latc = lat - np.einsum("i,ti->t", perp, com[sel, :2])[:, None]
    m["body_envelope_ptp_last4"] = float(latc.max() - latc.min())
    vp = []
    for kk in range(1, int(round(t[-1]))):
        a = np.argmin(abs(t - kk)); b = np.argmin(abs(t - kk - 1))
        vp.append(round(float((com[b, 0] - com[a, 0]) / (t[b] - t[a])), 4))
    m["vx_per_period_1_to_end"] = vp
    m["vx_mean_2_5"] = float((com[np.argmin(abs(t - 5)), 0] - com[np.argmin(abs(t - 2)), 0]) / 3.0)
    m["axial_strain_rms_at_integer_t"] = [float("%.2e" % np.sqrt(np.mean(r["sigma"][np.argmin(abs(t - kk)), 2] ** 2))) for kk in range(0, int(round(t[-1])) + 1)]
    m["max_abs_z_com"] = float(np.max(np.abs(com[:, 2])))
    m["max_z_any_node"] = float(np.max(pos[:, 2, :]))
    # grid-scale content of sigma
    sig = r["sigma"]  # (nt, 3, n_elem)
    gs = {}
    for lab, comp in (("shear1", 0), ("shear2", 1), ("axial", 2)):
        at = {}
        for tq in (2.5, 5.0, 7.5, 10.0):
            if tq <= t[-1] + 1e-9:
                j = np.argmin(abs(t - tq))
                at[f"t{tq}"] = round(grid_share(sig[j, comp]), 4)
        ssel = (t >= 2.0) & (t <= t[-1])
        shares = [grid_share(sig[j, comp]) for j in np.where(ssel)[0]]
        at["mean_2_end"] = round(float(np.mean(shares)), 4)
        j = len(t) - 1
        at["upper_half_share_t_end"] = round(upper_half_share(sig[j, comp]), 4)
        at["dominant_k_t_end(of %d)" % (sig.shape[2] // 2)] = dominant_k(sig[j, comp])
        at["rms_2_end"] = float(np.sqrt(np.mean(sig[ssel, comp, :] ** 2)))
        gs[lab] = at
    m["grid_share"] = gs
    return m


def terrain_metrics(r):
    t = r["time"]
    com = r["com"]
    pos = r["position"]
    m = {"t_end": float(t[-1]), "finite": bool(np.all(np.isfinite(pos)))}
    m["com_x_max"] = float(com[:, 0].max())
    m["com_z_max"] = float(com[:, 2].max())
    m["com_final"] = com[-1].tolist()
    m["head_x_max"] = float(pos[:, 0, -1].max())
    m["any_node_x_max"] = float(pos[:, 0, :].max())
    m["node_z_max"] = float(pos[:, 2, :].max())
    for xc in (2.5, 3.0, 3.5, 4.0):
        idx = np.where(com[:, 0] >= xc)[0]
        m[f"t_com_reaches_x{xc}"] = float(t[idx[0]]) if idx.size else None
    m["passes_x4_com"] = bool(com[:, 0].max() >= 4.0)
    m["t_com_x_max"] = float(t[np.argmax(com[:, 0])])
    m["head_z_max"] = float(pos[:, 2, -1].max())
    m["com_y_min"] = float(com[:, 1].min())
    m["axial_strain_rms_every_5s"] = [float("%.2e" % np.sqrt(np.mean(r["sigma"][np.argmin(abs(t - kk)), 2] ** 2))) for kk in range(0, int(round(t[-1])) + 1, 5)]
    # progress in the last 10 s
    sel = t >= t[-1] - 10.0
    m["com_x_change_last10s"] = float(com[sel, 0][-1] - com[sel, 0][0])
    return m


def main():
    names = sorted(os.path.basename(p)[:-4] for p in glob.glob(os.path.join(RUNS, "*.npz")))
    names = [n for n in names if not n.startswith(("test", "val"))]
    names = [n for n in names if os.path.exists(os.path.join(RUNS, n + ".log")) and "WALL" in open(os.path.join(RUNS, n + ".log")).read()]
    res = {}
    for n in names:
        r = load(n)
        save_csv(r)
        if r["args"]["ground"] == "flat":
            m = flat_metrics(r)
        else:
            m = terrain_metrics(r)
        m["args"] = r["args"]
        m["wall_s"] = wall_from_log(n)
        m["wall_internal_s"] = float(r["wall"])
        res[n] = m
    json.dump(res, open(os.path.join(OUT, "results.json"), "w"), indent=1)
    print(json.dumps(res, indent=1))
    plots(res)


def plots(res):
    flats = [n for n in res if res[n]["args"]["ground"] == "flat"]
    if flats:
        fig, ax = plt.subplots(2, 1, figsize=(9, 8))
        for n in flats:
            r = load(n)
            ax[0].plot(r["com"][:, 0], r["com"][:, 1], label=n)
            ax[1].plot(r["time"], r["com"][:, 0], label=n)
        ax[0].set_xlabel("CoM x [m]"); ax[0].set_ylabel("CoM y [m]"); ax[0].legend(fontsize=7)
        ax[0].set_title("flat ground: CoM trajectory")
        ax[1].set_xlabel("t [s]"); ax[1].set_ylabel("CoM x [m]"); ax[1].legend(fontsize=7)
        fig.tight_layout(); fig.savefig(os.path.join(OUT, "flat_com.png"), dpi=110); plt.close(fig)

        pair = [n for n in ("flat_orig", "flat_st25") if n in res]
        if len(pair) == 2:
            fig, axs = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
            for a, n in zip(axs, pair):
                r = load(n)
                t = r["time"]
                for tq in np.arange(9.0, 10.0, 0.1):
                    j = np.argmin(abs(t - tq))
                    p = r["position"][j]
                    a.plot(p[0] - r["com"][j, 0], p[1] - r["com"][j, 1], lw=0.8)
                a.set_aspect("equal"); a.set_title(f"{n}: body, t=9..10 s (CoM frame)")
                a.set_xlabel("x - x_com [m]")
            axs[0].set_ylabel("y - y_com [m]")
            fig.tight_layout(); fig.savefig(os.path.join(OUT, "flat_gait.png"), dpi=110); plt.close(fig)

    ters = [n for n in res if res[n]["args"]["ground"] == "terrain"]
    if ters:
        fig, ax = plt.subplots(3, 1, figsize=(9, 10))
        xs = np.linspace(0, 5, 500)
        h = np.where(xs < 3, 0, np.where(xs > 4, 0.2, -0.4 * (xs - 3) ** 3 + 0.6 * (xs - 3) ** 2))
        for n in ters:
            r = load(n)
            ax[0].plot(r["time"], r["com"][:, 0], label=n)
            ax[1].plot(r["time"], r["com"][:, 2], label=n)
            ax[2].plot(r["com"][:, 0], r["com"][:, 2], label=n + " CoM")
        ax[2].plot(xs, h, "k--", label="terrain h(x) (centreline rest height)")
        for a in ax[:2]:
            a.set_xlabel("t [s]"); a.legend(fontsize=7)
        ax[0].set_ylabel("CoM x [m]"); ax[0].axhline(3, color="k", lw=0.5); ax[0].axhline(4, color="k", lw=0.5)
        ax[1].set_ylabel("CoM z [m]")
        ax[2].set_xlabel("x [m]"); ax[2].set_ylabel("z [m]"); ax[2].legend(fontsize=7)
        fig.tight_layout(); fig.savefig(os.path.join(OUT, "terrain_com.png"), dpi=110); plt.close(fig)

        fig, axs = plt.subplots(len(ters), 1, figsize=(10, 3 * len(ters)), squeeze=False)
        for a, n in zip(axs[:, 0], ters):
            r = load(n)
            t = r["time"]
            for tq in np.arange(0, t[-1] + 1e-9, max(1.0, t[-1] / 12)):
                j = np.argmin(abs(t - tq))
                p = r["position"][j]
                a.plot(p[0], p[2], lw=0.8)
            a.plot(xs, h, "k--", lw=0.8)
            a.set_title(f"{n}: centreline x-z snapshots"); a.set_xlabel("x"); a.set_ylabel("z")
        fig.tight_layout(); fig.savefig(os.path.join(OUT, "terrain_snapshots.png"), dpi=110); plt.close(fig)


if __name__ == "__main__":
    main()
