#!/usr/bin/python3
"""wrap_analysis.py — moment arms of examples/constructs/wrap.sinew against
the closed-form geodesic wrap (docs/physics.md, "Wrapping over a cylinder").

Reads the simulator's HDF5 output and, for every frame of the sweep, finds
the joint angle alpha (between the upper bone above the joint and the lower
bone, through the muscles' side), then

  * for the muscle `wrapped` (touching the cylinder): its path length L (tie
    gap + filament arc length + tie gap, from the bone nodes O and I) and its
    moment arm from the force of its distal tie on the lower bone,
    r_F = |((I - c) x F) . y| / |F|;
  * for the muscle `routed` (via points): its path length from its stretch
    (end to end through the rings, times l0) and the tie gaps;

and the closed forms: the geodesic (L_geo, r_geo) for a cylinder of radius
R_eff = R + rho (the muscle's centreline lies a filament radius rho off the
surface), and the via polygon's r_poly = R_v cos(gamma / 2).  Moment arms
from the path are central differences dL/dalpha over the frames.

Used by tests/lang/test_wrap.sh (prints figures, returns them) and by
scripts/plot_wrap.py.  Run alone: wrap_analysis.py FILE.h5 [R rho]
"""
import math
import sys

import h5py
import numpy as np

Y = np.array([0.0, 1.0, 0.0])


def geodesic(alpha, a, b, R):
    """Path length and moment arm of the shortest path from a point at
    distance a from the axis of a cylinder of radius R (in the plane across
    it) to a point at distance b, alpha apart about the axis, on one side of
    the cylinder: straight while it clears it, else tangent + arc + tangent."""
    ba, bb = math.acos(R / a), math.acos(R / b)
    if alpha <= ba + bb:
        L = math.sqrt(a * a + b * b - 2 * a * b * math.cos(alpha))
        return L, a * b * math.sin(alpha) / L
    return math.sqrt(a * a - R * R) + math.sqrt(b * b - R * R) + R * (alpha - ba - bb), R


def angle_about_y(v):
    """Angle of v in the x-z plane from +z towards +x, in [0, 2 pi)."""
    return math.atan2(v[0], v[2]) % (2 * math.pi)


def analyse(path, R=0.02, rho=0.003, t_from=0.2):
    f = h5py.File(path, "r")
    t = f["time"][:] if "time" in f else None
    up = f["rods/upper/position"][:]
    lo = f["rods/lower/position"][:]
    nf = lo.shape[0]
    if t is None:
        t = np.arange(nf) * float(f.attrs.get("dt_output", 0.005))
    # the muscles' bone points: upper node at 0.7 (z = 6 cm), lower node 1
    nu = up.shape[1] - 1
    io = int(round(0.7 * nu))
    out = {"alpha": [], "t": [], "a": [], "b": []}
    res = {k: [] for k in ("L_w", "rF_w", "L_r", "L_geo", "r_geo", "r_poly", "gamma")}
    Rw = R + rho
    fw = f["rods/wrapped.f01/position"][:]
    fr = f["rods/routed.f01/position"][:]
    Fw = f["joints/wrapped.f01.end/force"][:]
    l0r = float(f["muscles/routed"].attrs["l0"])
    st_r = f["muscles/routed/stretch"][:]
    via = np.array(f["muscles/routed"].attrs["via"]).reshape(-1, 3)
    for k in range(nf):
        c = lo[k, 0]
        O, I = up[k, io], lo[k, 1]
        alpha = angle_about_y(lo[k, 1] - c)
        a = np.linalg.norm((O - c)[[0, 2]])
        b = np.linalg.norm((I - c)[[0, 2]])
        x = fw[k]
        Lw = np.linalg.norm(x[0] - O) + np.sum(np.linalg.norm(np.diff(x, axis=0), axis=1)) \
            + np.linalg.norm(x[-1] - I)
        F = Fw[k]
        rF = abs(np.dot(np.cross(I - c, F), Y)) / max(np.linalg.norm(F), 1e-300)
        xr = fr[k]
        Lr = np.linalg.norm(xr[0] - O) + st_r[k] * l0r + np.linalg.norm(xr[-1] - I)
        Lg, rg = geodesic(alpha, a, b, Rw)
        # the rings: the first is fixed (clamped upper bone), the second turns
        # with the lower bone; gamma is the angle between them about the axis
        Rv = np.linalg.norm(via[0][[0, 2]])
        g1 = angle_about_y(via[0])
        g2 = angle_about_y(via[1]) + (alpha - math.pi / 2)
        gamma = g2 - g1
        out["alpha"].append(alpha)
        out["t"].append(t[k])
        out["a"].append(a)
        out["b"].append(b)
        for key, v in (("L_w", Lw), ("rF_w", rF), ("L_r", Lr), ("L_geo", Lg), ("r_geo", rg),
                       ("r_poly", Rv * math.cos(gamma / 2)), ("gamma", gamma)):
            res[key].append(v)
    d = {k: np.array(v) for k, v in {**out, **res}.items()}
    keep = d["t"] >= t_from
    d = {k: v[keep] for k, v in d.items()}
    al = d["alpha"]
    # moment arms from the path: central differences of L against alpha
    for key, src in (("rL_w", "L_w"), ("rL_r", "L_r")):
        r = np.full(al.shape, np.nan)
        r[1:-1] = (d[src][2:] - d[src][:-2]) / (al[2:] - al[:-2])
        d[key] = r
    d["R_eff"] = Rw
    d["beta_sum"] = math.acos(Rw / np.mean(d["a"])) + math.acos(Rw / np.mean(d["b"]))
    return d


def summary(d, margin=math.radians(3)):
    """Largest errors, relative to R_eff, in the wrapped range (alpha past
    the onset by `margin`), in the clear range (before it by `margin`), and
    of L overall."""
    al, on, Rw = d["alpha"], d["beta_sum"], d["R_eff"]
    wr = (al > on + margin) & np.isfinite(d["rL_w"])
    cl = (al < on - margin) & np.isfinite(d["rL_w"])
    e = lambda x, ref, m: float(np.max(np.abs(x[m] - ref[m])) / Rw) if np.any(m) else float("nan")
    allm = np.isfinite(d["rL_w"])
    return {
        "alpha_range_deg": (math.degrees(al[0]), math.degrees(al[-1])),
        "onset_deg": math.degrees(on),
        "wrapped_frames": int(np.sum(wr)), "clear_frames": int(np.sum(cl)),
        "rF_wrapped": e(d["rF_w"], d["r_geo"], wr), "rF_clear": e(d["rF_w"], d["r_geo"], cl),
        "rL_wrapped": e(d["rL_w"], d["r_geo"], wr), "rL_clear": e(d["rL_w"], d["r_geo"], cl),
        "rF_vs_rL": e(d["rF_w"], d["rL_w"], allm),
        "L_rel": float(np.max(np.abs(d["L_w"] - d["L_geo"]) / d["L_geo"])),
        "via_poly": e(d["rL_r"], d["r_poly"], allm),
        "via_vs_geo_max": e(d["rL_r"], d["r_geo"], allm),
        "rF_wrapped_mean_mm": float(np.mean(d["rF_w"][wr]) * 1e3) if np.any(wr) else float("nan"),
    }


if __name__ == "__main__":
    d = analyse(sys.argv[1], *(float(x) for x in sys.argv[2:4]))
    for k, v in summary(d).items():
        print(k, v)
