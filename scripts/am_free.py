#!/usr/bin/python3
"""am_free.py — the figure of docs/validation.md, "A free artificial muscle".

Reads the runs of examples/am_free.sinew at the release rates 1, 0.5 and
0.25 /s (build/am_free/rate{1,0.5,0.25}.h5; `--run` compiles the example
with bin/sinewc and makes them, about a minute of one core each) and draws
three panels into docs/img/am_free.png (or the file given by --plot):

  (a) the free coil's end-to-end length against r / a, beside the helix of
      curvature kappa and torsion tau a / r (docs/physics.md, "Geometry that
      changes in time");
  (b) the held coil's force (/joints/hold/force, axial) against r / a,
      beside Kirchhoff's helical spring held at its ends, F = C tau (1 - a/r)
      cos(alpha) / R with C = G pi r^4 / 2 (docs/physics.md, "A twisted coil
      held at its ends");
  (c) that force against time at the three rates (Zhang et al. 2019, Suppl.
      Fig. 7c: a higher rate, more force).

It also prints the figures it plots at r / a = 1.25, 1.5, 1.75, 2."""
import argparse, math, os, subprocess, sys
import h5py, numpy as np

R, A0, G, N, CORE = 0.01, 5e-3, 1e10, 9, 0.425          # Zhang et al. 2019, Table 3
C_RISE = CORE / N / (2 * math.pi)
Q = R * R + C_RISE * C_RISE
KAPPA, TAU, COS_A = R / Q, C_RISE / Q, R / math.sqrt(Q)
RATES = (1.0, 0.5, 0.25)


def helix_span(k, t, length):
    """End-to-end length of a helix of curvature k, torsion t, arc length."""
    qq = k * k + t * t
    rh, ch, th = k / qq, t / qq, length * math.sqrt(qq)
    return math.sqrt((ch * th) ** 2 + (2 * rh * math.sin(th / 2)) ** 2)


def kirchhoff(g):
    """Blocked force of the held coil at r = g a (Love's helical spring)."""
    return G * math.pi * (g * A0) ** 4 / 2 * TAU * (1 - 1 / g) * COS_A / R


def run(outdir):
    os.makedirs(outdir, exist_ok=True)
    sim = os.path.join(outdir, "am_free")
    subprocess.run(["bin/sinewc", "examples/am_free.sinew", "-o", sim], check=True)
    for rate in RATES:
        subprocess.run([sim, "--quiet", "--dt", "500ns", "--set", f"rate={rate:g}Hz",
                        "--out", os.path.join(outdir, f"rate{rate:g}.h5")], check=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dir", default="build/am_free")
    ap.add_argument("--run", action="store_true", help="make the runs first")
    ap.add_argument("--plot", default="docs/img/am_free.png")
    o = ap.parse_args()
    if o.run:
        run(o.dir)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    length = 2 * math.pi * N * math.sqrt(Q)       # the continuum helix's arc length
    for rate, style in zip(RATES, ("-", "--", ":")):
        f = h5py.File(os.path.join(o.dir, f"rate{rate:g}.h5"), "r")
        t = f["/time"][:]
        g = 1 + np.minimum(rate * t, 1.0)
        x = f["/rods/free.am/position"][:]
        span = np.linalg.norm(x[:, -1] - x[:, 0], axis=1)
        force = f["/joints/hold/force"][:, 2]
        if rate == 1.0:
            ax[0].plot(g, span, "C0", label="free coil, 1 /s")
            ax[1].plot(g, force / 1e3, "C0", label="held coil, 1 /s")
            for gg in (1.25, 1.5, 1.75, 2.0):
                i = int(np.argmin(abs(g - gg)))
                s_ref = helix_span(KAPPA, TAU / g[i], length)
                print(f"r/a = {g[i]:.3f}: end-to-end {span[i]:.4f} m (helix {s_ref:.4f}, "
                      f"{span[i]/s_ref-1:+.1e}); held force {force[i]:.4g} N (Kirchhoff "
                      f"{kirchhoff(g[i]):.4g}, ratio {force[i]/kirchhoff(g[i]):.3f})")
        ax[2].plot(t, force / 1e3, "k" + style, label=f"{rate:g} /s")
    gs = np.linspace(1, 2, 101)
    ax[0].plot(gs, [helix_span(KAPPA, TAU / g, length) for g in gs], "k:",
               label="helix of torsion tau a/r")
    ax[1].plot(gs, [kirchhoff(g) / 1e3 for g in gs], "k:", label="Kirchhoff, held ends")
    ax[0].set(xlabel="r / a", ylabel="end-to-end length (m)", title="(a) free stroke")
    ax[1].set(xlabel="r / a", ylabel="axial force (kN)", title="(b) blocked force")
    ax[2].set(xlabel="t (s)", ylabel="axial force (kN)", title="(c) held coil, release rates")
    for a in ax:
        a.legend(fontsize=8)
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(o.plot, dpi=110)
    print(f"am_free.py: wrote {o.plot}")


if __name__ == "__main__":
    sys.exit(main())
