#!/usr/bin/python3
"""plectoneme.py — torque, twist, writhe, link, crossings and contact of
examples/plectoneme.sinew's run, beside the analytic references.

  plectoneme.py RUN.h5 [--csv OUT.csv] [--json OUT.json] [--plot OUT.png]
                [--quiet]

The run wrote positions, directors and internal_couple of the rod `strand`
(clamped at its start; its end slid along z under a tension F and turned
about z).  For every frame the script prints the imposed rotation (turns),
the torque at the clamp, Tw, Wr and Lk (scripts/sinew-link's link()), the
average crossing number of the centreline, the number of self-contacts and
the smallest distance between elements that the contact pairs, over 2 r.

Design.
  * Torque at the clamp: the internal couple at the first Voronoi node
    (B kappa, C kappa_3 in the material frame) turned into the lab frame with
    the first element's directors; its z component.  The couple acts half an
    element from the clamp, so the clamp's own torque differs by the shear
    force times l / 2 in the lever arm, which a straight or slowly loaded rod
    makes vanish.
  * Pre-buckling slope: a straight rod twisted through Phi carries
    M = C Phi / L (C = G J, J = pi r^4 / 2), whatever the tension.  The
    discrete rod twists over L - l/2: its clamp holds a frame at the end
    node (boundary.c: a half Voronoi domain), the turned end its last
    element's frame, at the element's centre; so it reads C / (L - l / 2),
    first order in l = L / n.
  * Buckling (Greenhill, with tension): linearised about the straight rod
    under tension F and axial moment M, the lateral deflection u = x + i y
    obeys B u'''' - i M u''' - F u'' = 0 (Love 1927, secs. 270-272; van der
    Heijden & Thompson, Nonlinear Dyn. 21:71, 2000, eq. 1), so
    u = a + b s + c exp(i k1 s) + d exp(i k2 s), k1,2 the roots of
    B k^2 - M k + F = 0.  Clamped ends (u = u' = 0 at s = 0, L) leave a
    non-zero u when the 4 x 4 determinant vanishes; the first M > 0 at which
    it does (found by bisection on its real part once the phase
    exp(-i M L / 2B) is taken out) is M_c, and Phi_c = M_c L / C.  With F = 0
    it is Greenhill's tan(theta / 2) = theta / 2, theta = M L / B; for
    L sqrt(F / B) -> infinity it tends to M_c = 2 sqrt(B F).
  * Plateau: a ply of two strands of the rod wound round each other as
    helices of radius R at angle theta to the ply's axis, touching
    (R = r: the strands' axes 2 r apart), has curvature sin^2 theta / R and
    writhe sin(2 theta) / (4 pi R) per length of rod in it (the writhe of
    an interwound ply as Neukirch & Marko, PRL 106:138104, 2011, use it;
    checked with sinew-link's writhe() on ideal plies of 4 and 8 turns,
    whose difference per length matched it to 4e-6).  Taking a length dl of rod from
    the straight tails into the ply costs (B kappa^2 / 2 + F) dl (bending,
    and work against F as the end is reeled in) and buys dWr of writhe, paid
    for at the torque M3 = C times the twist density, uniform along a
    frictionless isotropic rod.  Stationarity in dl and theta gives
        M3 sin(theta) cos(theta) / R = B sin^4(theta) / (2 R^2) + F,
        M3 cos(2 theta) / R          = 2 B sin^3(theta) cos(theta) / R^2,
    whence sin^4 theta (2 cos^2 theta / cos 2 theta - 1/2) = F R^2 / B and
    M3.  This is the zero-temperature, hard-wall limit of that paper's
    energy balance, derived here; it leaves out the end loop and the two
    tails' transition into the ply, which a short ply feels: it holds for a
    ply much longer than the loop, whose size is sqrt(B / F).
  * Loop: a single loop closed by contact, the first structure past
    buckling, stores about one turn of writhe for the energy of the planar
    elastica's homoclinic loop under tension: with theta' = 2 a sech(a s),
    a = sqrt(F / B), the bending energy (B / 2) int theta'^2 ds = 4 sqrt(B F)
    and the end shortening int (1 - cos theta) ds = 4 / a, so 8 sqrt(B F)
    with the work against F (the loop is the limit of the localised
    solutions of Thompson & Champneys, Proc. R. Soc. A 452:117, 1996); paid at the torque that adds a turn, M_loop = 8 sqrt(B F) /
    (2 pi) = (4 / pi) sqrt(B F) (the Maxwell torque of forming the loop).
  * Crossings: the average crossing number, the number of crossings of the
    centreline projected on a plane, averaged over 200 directions spread
    evenly on the sphere (its signed version averages to the writhe).
  * Self-contacts: pairs of elements that the contact pairs (their rest
    arc gap at least pi r, contact.c) and that are closer than 2 r, grouped
    into clusters of neighbouring pairs; and the smallest distance of such
    pairs over 2 r (1 - sink / 2 r; below 0.5 the rod has passed through
    itself or nearly).
"""
import argparse
import importlib.machinery
import importlib.util
import json
import math
import os
import sys

import numpy as np

_here = os.path.dirname(os.path.abspath(__file__))
_ld = importlib.machinery.SourceFileLoader("sinew_link", os.path.join(_here, "sinew-link"))
_spec = importlib.util.spec_from_loader("sinew_link", _ld)
sinew_link = importlib.util.module_from_spec(_spec)
_ld.exec_module(sinew_link)


# ---- references ----

def greenhill_tension(B, C, F, L):
    """Critical moment M_c and twist Phi_c (rad) of a rod clamped at both
    ends under tension F: the first zero of the clamped determinant."""
    def f(M):
        disc = np.sqrt(complex(M * M - 4 * B * F))
        k1, k2 = (M + disc) / (2 * B), (M - disc) / (2 * B)
        e1, e2 = np.exp(1j * k1 * L), np.exp(1j * k2 * L)
        A = np.array([[1, 0, 1, 1], [0, 1, 1j * k1, 1j * k2],
                      [1, L, e1, e2], [0, 1, 1j * k1 * e1, 1j * k2 * e2]], complex)
        # the trivial zero where k1 = k2 (two equal columns) divided out;
        # what is left, with the phase taken out, is imaginary
        return (np.linalg.det(A) * np.exp(-1j * M * L / (2 * B)) / (k1 - k2)).imag
    lo = 1e-3 * B / L
    grid = np.linspace(lo, 20 * B / L + 4 * math.sqrt(B * F), 4001)
    grid = grid[np.abs(grid - 2 * math.sqrt(B * F)) > 1e-9 * grid[-1]]
    vals = [f(M) for M in grid]
    for a, b, fa, fb in zip(grid[:-1], grid[1:], vals[:-1], vals[1:]):
        if fa * fb < 0:
            for _ in range(200):
                c = 0.5 * (a + b)
                fc = f(c)
                if fa * fc <= 0:
                    b = c
                else:
                    a, fa = c, fc
            M = 0.5 * (a + b)
            return M, M * L / C
    raise RuntimeError("no critical moment found")


def ply(B, F, R):
    """(theta, M3, writhe per rod length) of the touching ply (docstring)."""
    eps = F * R * R / B
    def g(th):
        s, c = math.sin(th), math.cos(th)
        return s ** 4 * (2 * c * c / math.cos(2 * th) - 0.5) - eps
    a, b = 1e-9, math.pi / 4 - 1e-9
    for _ in range(200):
        m = 0.5 * (a + b)
        if g(a) * g(m) <= 0:
            b = m
        else:
            a = m
    th = 0.5 * (a + b)
    s, c = math.sin(th), math.cos(th)
    M3 = 2 * B * s ** 3 * c / (R * math.cos(2 * th))
    return th, M3, math.sin(2 * th) / (4 * math.pi * R)


# ---- geometry ----

def _seg_dist(p0, p1, q0, q1):
    """Closest distance between segments p0p1 and q0q1 (arrays [k, 3])."""
    d1, d2, r = p1 - p0, q1 - q0, p0 - q0
    a = np.sum(d1 * d1, -1)
    e = np.sum(d2 * d2, -1)
    f = np.sum(d2 * r, -1)
    c = np.sum(d1 * r, -1)
    b = np.sum(d1 * d2, -1)
    den = a * e - b * b
    s = np.where(den > 1e-300, np.clip((b * f - c * e) / np.where(den > 1e-300, den, 1), 0, 1), 0.0)
    t = (b * s + f) / e
    t = np.clip(t, 0, 1)
    s = np.clip((b * t - c) / a, 0, 1)
    d = p0 + d1 * s[:, None] - (q0 + d2 * t[:, None])
    return np.linalg.norm(d, axis=-1)


def contact_pairs(n, lrest, r):
    """Element pairs (i, j) the self-contact pairs: rest gap >= pi r."""
    i, j = np.triu_indices(n, k=1)
    gap = (j - i - 1) * lrest
    keep = gap >= 0.5 * math.pi * (2 * r) - 1e-12
    return i[keep], j[keep]


def contacts(x, pi_, pj, r):
    """(smallest distance, number of clusters of touching pairs)."""
    d = _seg_dist(x[pi_], x[pi_ + 1], x[pj], x[pj + 1])
    touch = d < 2 * r
    ti, tj = pi_[touch], pj[touch]
    # clusters: touching pairs that neighbour each other (|di|, |dj| <= 2)
    left = set(zip(ti.tolist(), tj.tolist()))
    clusters = 0
    while left:
        clusters += 1
        stack = [left.pop()]
        while stack:
            a, b = stack.pop()
            for da in (-2, -1, 0, 1, 2):
                for db in (-2, -1, 0, 1, 2):
                    q = (a + da, b + db)
                    if q in left:
                        left.remove(q)
                        stack.append(q)
    return float(d.min()), clusters


def _directions(k=200):
    g = math.pi * (3 - math.sqrt(5))
    z = 1 - (np.arange(k) + 0.5) * 2 / k
    rr = np.sqrt(1 - z * z)
    ph = g * np.arange(k)
    return np.stack([rr * np.cos(ph), rr * np.sin(ph), z], 1)


_DIRS = _directions()


def crossings(x):
    """Average crossing number of the open centreline x [n+1, 3]."""
    n = len(x) - 1
    i, j = np.triu_indices(n, k=2)
    tot = 0
    for v in _DIRS:
        a = np.cross(v, [1.0, 0, 0]) if abs(v[0]) < 0.9 else np.cross(v, [0, 1.0, 0])
        a /= np.linalg.norm(a)
        b = np.cross(v, a)
        p = np.stack([x @ a, x @ b], 1)
        P0, P1, Q0, Q1 = p[i], p[i + 1], p[j], p[j + 1]
        def orient(o, s, t):
            return (s[:, 0] - o[:, 0]) * (t[:, 1] - o[:, 1]) - (s[:, 1] - o[:, 1]) * (t[:, 0] - o[:, 0])
        o1, o2 = orient(P0, P1, Q0), orient(P0, P1, Q1)
        o3, o4 = orient(Q0, Q1, P0), orient(Q0, Q1, P1)
        tot += int(np.sum((o1 * o2 < 0) & (o3 * o4 < 0)))
    return tot / len(_DIRS)


# ---- the run ----

def analyse(path, rod="strand", every_crossing=1):
    import h5py
    f = h5py.File(path, "r")
    g = f[f"rods/{rod}"]
    X, Q, cpl, t = g["position"][...], g["directors"][...], g["internal_couple"][...], f["time"][...]
    nf = min(len(X), len(Q), len(cpl), len(t))
    L = float(g.attrs["length"])
    r = float(np.atleast_1d(g.attrs["radius"])[0])
    E, G = float(g.attrs["E"]), float(g.attrs["G"])
    I = math.pi * r ** 4 / 4
    B, C = E * I, G * 2 * I
    scale = {"N": 1.0, "mN": 1e-3, "uN": 1e-6, "kN": 1e3}
    def _s(v):
        return v.decode() if isinstance(v, bytes) else v
    F = [float(p["value"]) * scale[_s(p["unit"])] for p in f["params"][...] if _s(p["name"]) == "tension"][0]
    damp = [float(p["value"]) for p in f["params"][...] if _s(p["name"]) == "damp" and _s(p["unit"]) == "kg/m/s"]
    # the imposed rotation: the end element's d1 about z, unwrapped
    ang = np.unwrap(np.arctan2(Q[:nf, -1, 0, 1], Q[:nf, -1, 0, 0]) - math.atan2(Q[0, -1, 0, 1], Q[0, -1, 0, 0]))
    imp = ang / (2 * math.pi)
    T = float(t[int(np.argmax(imp >= imp.max() - 1e-9))])
    turns = float(imp.max())
    n = Q.shape[1]
    pi_, pj = contact_pairs(n, L / n, r)
    rows = []
    for k in range(nf):
        m = cpl[k, 0]
        tau = float((Q[k, 0].T @ m)[2])
        tw, wr, _ = sinew_link.link(X[k], Q[k], Q[0, 0], Q[k, -1])
        dmin, ncl = contacts(X[k], pi_, pj, r)
        acn = crossings(X[k]) if (k % every_crossing == 0 or k == nf - 1) else float("nan")
        imposed = imp[k]
        rows.append((t[k], imposed, tau, tw, wr, tw + wr, acn, ncl, dmin / (2 * r), X[k, -1, 2]))
    rows = np.array(rows)
    Mc, Phic = greenhill_tension(B, C, F, L)
    M0, Phi0 = greenhill_tension(B, C, 1e-12 * B / L ** 2, L)
    th, Mp, w = ply(B, F, r)
    ref = dict(L=L, r=r, B=B, C=C, F=F, turns=turns, twist_time=T, n=n,
               slope_ref=C / L, slope_discrete=C / (L - 0.5 * L / n), Mc=Mc, Phic_turns=Phic / (2 * math.pi),
               Mc_free=M0, Phic_free_turns=Phi0 / (2 * math.pi),
               Mc_long=2 * math.sqrt(B * F), lam=L * math.sqrt(F / B),
               ply_theta_deg=math.degrees(th), M_plateau=Mp, ply_writhe_per_m=w,
               M_loop=4 / math.pi * math.sqrt(B * F), loop_size=math.sqrt(B / F),
               damping=damp[0] if damp else float("nan"))
    return rows, ref


def summarise(rows, ref):
    t, ph, tau = rows[:, 0], rows[:, 1], rows[:, 2]
    k_pk = int(np.argmax(tau))
    pre = (ph > 0.05 * ref["Phic_turns"]) & (ph < 0.6 * ref["Phic_turns"])
    slope = np.polyfit(ph[pre] * 2 * math.pi, tau[pre], 1)[0] if pre.sum() >= 2 else float("nan")
    post = t >= ref["twist_time"] - 1e-9
    s = dict(slope=slope, slope_ratio=slope / ref["slope_ref"],
             slope_ratio_discrete=slope / ref["slope_discrete"],
             peak_tau=float(tau[k_pk]), peak_turns=float(ph[k_pk]),
             peak_ratio=float(ph[k_pk] / ref["Phic_turns"]),
             lk_err=float(np.abs(rows[:, 5] - rows[:, 1]).max()),
             final_tau=float(tau[post].mean()) if post.any() else float(tau[-1]),
             final_wr=float(rows[-1, 4]), final_tw=float(rows[-1, 3]),
             final_acn=float(rows[-1, 6]),
             wr_at_phic=float(np.interp(ref["Phic_turns"], ph[t <= ref["twist_time"]], np.abs(rows[t <= ref["twist_time"], 4]))),
             turns_wr_01=float(ph[np.argmax(np.abs(rows[:, 4]) > 0.1)]) if (np.abs(rows[:, 4]) > 0.1).any() else float("nan"),
             turns_wr_001=float(np.interp(0.01, np.abs(rows[:k_pk + 1, 4]), ph[:k_pk + 1])),
             first_lk_jump_t=float(t[np.argmax(np.abs(rows[:, 5] - rows[:, 1]) > 0.5)]) if (np.abs(rows[:, 5] - rows[:, 1]) > 0.5).any() else float("nan"), final_contacts=int(rows[-1, 7]),
             min_gap=float(np.nanmin(rows[:, 8])), final_z=float(rows[-1, 9]))
    s["plateau_ratio"] = s["final_tau"] / ref["M_plateau"]
    return s


def plot(rows, ref, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ph, tau = rows[:, 1], rows[:, 2]
    tw = ref["twist_time"]
    ramp = rows[:, 0] <= tw + 1e-9
    ax[0].plot(ph[ramp], 1e3 * tau[ramp], "k.-", ms=3, label="sinew, torque at the clamp")
    ax[0].plot(ph[~ramp], 1e3 * tau[~ramp], "o", mfc="none", color="0.5", ms=4, label="held at the last turn")
    xs = np.linspace(0, ref["Phic_turns"], 10)
    ax[0].plot(xs, 1e3 * ref["slope_ref"] * 2 * math.pi * xs, "b--", label="C Phi / L (straight rod)")
    ax[0].axvline(ref["Phic_turns"], color="r", ls=":", label="Greenhill under tension")
    ax[0].axhline(1e3 * ref["M_plateau"], color="g", ls="--", label="touching ply (energy balance)")
    ax[0].axhline(1e3 * ref["Mc_long"], color="0.6", ls=":", label="2 sqrt(B F)")
    ax[0].set_xlabel("end rotation (turns)")
    ax[0].set_ylabel("torque (mN m)")
    ax[0].legend(fontsize=7)
    ax[1].plot(ph[ramp], rows[ramp, 4], "k-", label="writhe Wr")
    ax[1].plot(ph[ramp], rows[ramp, 3], "b-", label="twist Tw")
    ax[1].plot(ph[ramp], rows[ramp, 6], "m-", label="average crossing number")
    ax[1].plot(ph[ramp], rows[ramp, 7], "g.", ms=3, label="self-contact clusters")
    ax[1].plot(ph, ph, "k:", lw=0.8, label="Lk imposed")
    ax[1].set_xlabel("end rotation (turns)")
    ax[1].set_ylabel("turns / count")
    ax[1].legend(fontsize=7)
    fig.suptitle(f"plectoneme: L = {ref['L']:g} m, r = {1e3 * ref['r']:g} mm, "
                 f"F = {1e3 * ref['F']:.3g} mN (L sqrt(F/B) = {ref['lam']:.2f}), n = {ref['n']}")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("file")
    ap.add_argument("--csv")
    ap.add_argument("--json")
    ap.add_argument("--plot")
    ap.add_argument("--quiet", action="store_true")
    ap.add_argument("--crossings-every", type=int, default=1, help="crossings of every K-th frame only (and the last)")
    a = ap.parse_args(argv)
    rows, ref = analyse(a.file, every_crossing=a.crossings_every)
    s = summarise(rows, ref)
    hdr = "t_s,imposed_turns,torque_Nm,Tw,Wr,Lk,crossings,contacts,min_dist_over_2r,z_end"
    if a.csv:
        np.savetxt(a.csv, rows, delimiter=",", header=hdr, comments="", fmt="%.10g")
    if not a.quiet:
        print(hdr.replace(",", " "))
        for rw in rows:
            print(" ".join(f"{v:.6g}" for v in rw))
    print("references: " + ", ".join(f"{k} {v:.6g}" for k, v in ref.items()))
    print("measured: " + ", ".join(f"{k} {v:.6g}" for k, v in s.items()))
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(dict(ref=ref, summary=s), fh, indent=1)
    if a.plot:
        plot(rows, ref, a.plot)


if __name__ == "__main__":
    main()
