#!/usr/bin/env python3
"""snake_report.py — the figures of the snake scenes run by bench/bench_snake.sh.

Reads the HDF5 outputs in DIR (continuum, original, shear25, twist25, both25,
terrain_original, terrain_hardened; the variants R_original, R_both25,
RC_original, RC_both25, RC_terrain_original, RC_terrain_hardened) and
DIR/wall.txt, prints a Markdown
section "Snakes (issue 9)", puts it into BENCHMARKS (replacing an older one)
and draws into IMG:
  snake_trajectories.png  centre of mass in the ground plane, the four
                          hardening cases (Zhang et al. 2019, Suppl. Fig. 10b)
  snake_terrain.png       centre of mass x and z against time on the barrier
                          (Suppl. Figs. 11-12), original and hardened x100
  snake_reference_damping.png  centre of mass x against time, the variants
Usage: snake_report.py DIR BENCHMARKS IMG
"""
import re
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def load(path):
    with h5py.File(path, "r") as f:
        return f["/time"][:], f["/probes/com"][:]


def speed(t, com, t0, t1):
    """Speed of the centre of mass between t0 and t1 (whole periods), m/s."""
    k0, k1 = np.argmin(abs(t - t0)), np.argmin(abs(t - t1))
    return np.hypot(*(com[k1, :2] - com[k0, :2])) / (t[k1] - t[k0])


def excursion(t, com, t0, t1):
    """Largest distance of the centre of mass from its mean line, m."""
    k0, k1 = np.argmin(abs(t - t0)), np.argmin(abs(t - t1))
    d = com[k1, :2] - com[k0, :2]
    d /= np.hypot(*d)
    rel = com[k0:k1 + 1, :2] - com[k0, :2]
    return np.max(abs(rel[:, 0] * d[1] - rel[:, 1] * d[0]))


def switch_time(t, com, v_ref):
    """First time after 2 s at which the speed over the last second exceeds
    1.5 v_ref (the gait switch), or None."""
    for k in range(len(t)):
        if t[k] < 2:
            continue
        j = np.argmin(abs(t - (t[k] - 1)))
        if np.hypot(*(com[k, :2] - com[j, :2])) / (t[k] - t[j]) > 1.5 * v_ref:
            return t[k]
    return None


def variants(out, wall, img):
    """The section's part on the reference's modelling choices: R, its
    rotational dissipation; RC, that and friction at the contact point."""
    lines = ["### Under the reference's rotational dissipation", "",
             "R: the snake with `rotational_damping = 5 N s/rad` (the reference's gamma "
             "on the angular velocity); RC: R with `contact_point = true` on the ground. "
             "Original and shear and twist x25, 20 s at dt = 10 us; the switch is the "
             "first time the speed over the last second exceeds 1.5 times the original's.",
             "", "| variant | case | speed 2-10 s (m/s) | speed 12-20 s (m/s) | lateral "
             "excursion 2-10 s (m) | gait switch (s) | wall (s) |",
             "|---|---|--:|--:|--:|--:|--:|"]
    fig, ax = plt.subplots(figsize=(6, 4))
    for v in ("R", "RC"):
        t0, c0 = load(f"{out}/{v}_original.h5")
        v_ref = speed(t0, c0, 2, 10)
        for label, name in (("original", f"{v}_original"), ("x25", f"{v}_both25")):
            t, com = load(f"{out}/{name}.h5")
            sw = switch_time(t, com, v_ref)
            lines.append(f"| {v} | {label} | {speed(t, com, 2, 10):.4f} | "
                         f"{speed(t, com, 12, 20):.4f} | {excursion(t, com, 2, 10):.4f} | "
                         f"{'none' if sw is None else f'{sw:.2f}'} | "
                         f"{float(wall[name]):.1f} |")
            ax.plot(t, com[:, 0], label=f"{v}, {label}")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("centre of mass x (m)")
    ax.set_title("continuum snake under the reference's rotational dissipation")
    ax.legend()
    fig.tight_layout()
    fig.savefig(f"{img}/snake_reference_damping.png", dpi=110)
    lines += ["", "| RC on the barrier, 30 s | furthest x (m) | highest z (m) | x, z at the "
              "end (m) | wall (s) |", "|---|--:|--:|--:|--:|"]
    for label, name in (("original", "RC_terrain_original"),
                        ("shear and twist x100", "RC_terrain_hardened")):
        t, com = load(f"{out}/{name}.h5")
        lines.append(f"| {label} | {com[:, 0].max():.3f} | {com[:, 2].max():.3f} | "
                     f"{com[-1, 0]:.3f}, {com[-1, 2]:.3f} | {float(wall[name]):.1f} |")
    return lines + [""]


def main():
    out, bench, img = sys.argv[1:4]
    wall = dict(line.split() for line in open(f"{out}/wall.txt"))
    lines = ["## Snakes (issue 9)", "",
             "Written by bench/bench_snake.sh (`make bench`): the full scenes, "
             "speeds over t = 2..10 s (whole periods after the 1 s ramp), lateral "
             "excursion of the centre of mass from its mean line over the same "
             "window. One run each, on a shared machine.", ""]
    t, com = load(f"{out}/continuum.h5")
    lines += [f"- `snake_continuum`, 10 s at dt = 10 us, n = 50: forward speed "
              f"{speed(t, com, 2, 10):.4f} m/s ({speed(t, com, 2, 10):.3f} L/T); wall "
              f"time {float(wall['continuum']):.1f} s.", ""]
    lines += ["| hardening (Suppl. Fig. 10) | speed (m/s) | change | lateral excursion (m) "
              "| change | wall (s) |", "|---|--:|--:|--:|--:|--:|"]
    cases = [("original", "original"), ("shear x25", "shear25"), ("twist x25", "twist25"),
             ("shear and twist x25", "both25")]
    base = load(f"{out}/original.h5")
    v0, e0 = speed(*base, 2, 10), excursion(*base, 2, 10)
    fig, ax = plt.subplots(figsize=(6, 4))
    for label, name in cases:
        t, com = load(f"{out}/{name}.h5")
        v, e = speed(t, com, 2, 10), excursion(t, com, 2, 10)
        lines.append(f"| {label} | {v:.5f} | {100 * (v / v0 - 1):+.2f}% | {e:.4f} | "
                     f"{100 * (e / e0 - 1):+.1f}% | {float(wall[name]):.1f} |")
        ax.plot(com[:, 0], com[:, 1], label=label)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title("continuum snake: centre of mass, 10 s")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend()
    fig.tight_layout()
    fig.savefig(f"{img}/snake_trajectories.png", dpi=110)
    lines += ["", "The reference reports up to 10% in speed and 60% in lateral excursion "
              "between these cases (Suppl. Note 6.5); docs/validation.md discusses the gap.", ""]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6, 5), sharex=True)
    lines += ["| `snake_terrain`, 30 s | furthest x (m) | highest z (m) | x, z at the end (m) "
              "| wall (s) |", "|---|--:|--:|--:|--:|"]
    for label, name in [("original", "terrain_original"), ("shear and twist x100",
                                                          "terrain_hardened")]:
        t, com = load(f"{out}/{name}.h5")
        lines.append(f"| {label} | {com[:, 0].max():.3f} | {com[:, 2].max():.3f} | "
                     f"{com[-1, 0]:.3f}, {com[-1, 2]:.3f} | {float(wall[name]):.1f} |")
        ax1.plot(t, com[:, 0], label=label)
        ax2.plot(t, com[:, 2], label=label)
    for x in (3, 4):
        ax1.axhline(x, color="grey", lw=0.5)
    ax2.axhline(0.2 + 0.025, color="grey", lw=0.5)
    ax1.set_ylabel("centre of mass x (m)")
    ax2.set_ylabel("centre of mass z (m)")
    ax2.set_xlabel("t (s)")
    ax1.set_title("snake on the barrier (slope from x = 3 m to 4 m, 0.2 m high)")
    ax1.legend()
    fig.tight_layout()
    fig.savefig(f"{img}/snake_terrain.png", dpi=110)
    lines += ["", "The barrier's top is at x = 4 m (z = 0.2 m; the centre of mass of a snake "
              "lying on the upper plane is at z = 0.225 m).", ""]
    lines += variants(out, wall, img)
    section = "\n".join(lines)
    print(section)
    text = open(bench).read()
    pat = re.compile(r"## Snakes \(issue 9\)\n.*?(?=\n## |\Z)", re.S)
    if pat.search(text):
        text = pat.sub(lambda _: section.rstrip("\n"), text)
    else:
        text = text.rstrip("\n") + "\n\n" + section
    open(bench, "w").write(text)


if __name__ == "__main__":
    main()
