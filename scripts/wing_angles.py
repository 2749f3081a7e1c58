#!/usr/bin/python3
"""wing_angles.py — the pigeon wing's three joint angles from a run of
models/pigeon_wing.sinew, defined as the reference's code defines them
(GitHub mattialab/elastica, source/ExternalContact.h, the wing's
RodRodAttach): the shoulder's dorsal-ventral angle atan((z_n - z_0) / |y_n|)
and antero-posterior angle atan(-x_n / |y_n|) of the humerus' end node n,
and the elbow 90 deg less the angle between the humerus' last tangent and
the radius' first.  Prints them at every frame; with --plot FILE draws them.

  scripts/wing_angles.py RUN.h5 [--plot FILE]
"""
import argparse
import sys

import h5py
import numpy as np


def angles(path):
    with h5py.File(path, "r") as f:
        t = f["/time"][:]
        H = f["/rods/humerus/position"][:]
        dh = f["/rods/humerus/directors"][:, -1, 2]
        dr = f["/rods/radius/directors"][:, 0, 2]
    dv = np.degrees(np.arctan((H[:, -1, 2] - H[:, 0, 2]) / np.abs(H[:, -1, 1])))
    ap = np.degrees(np.arctan(-H[:, -1, 0] / np.abs(H[:, -1, 1])))
    cosang = np.clip(np.sum(dh * dr, axis=1), -1, 1)
    el = 90 - np.degrees(np.arccos(cosang))
    return t, dv, ap, el


def main():
    ap_ = argparse.ArgumentParser()
    ap_.add_argument("run")
    ap_.add_argument("--plot")
    o = ap_.parse_args()
    t, dv, ap, el = angles(o.run)
    print("t_s shoulder_dv_deg shoulder_ap_deg elbow_deg")
    for k in range(len(t)):
        print("%.4f %.4f %.4f %.4f" % (t[k], dv[k], ap[k], el[k]))
    if o.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(3, 1, figsize=(6, 6), sharex=True)
        for a, y, name in zip(ax, (dv, ap, el), ("shoulder, dorsal-ventral", "shoulder, antero-posterior", "elbow")):
            a.plot(t, y, "k-", lw=1)
            a.set_ylabel(name + " (deg)", fontsize=8)
            a.axvline(0.125, color="0.7", lw=0.8)
        ax[-1].set_xlabel("t (s); the initiation phase ends at 0.125 s")
        fig.suptitle("The kinematic wing (models/pigeon_wing.sinew)", fontsize=9)
        fig.tight_layout()
        fig.savefig(o.plot, dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
