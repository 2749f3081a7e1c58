#!/usr/bin/python3
"""wing_frames.py — the flapping wing in a few pictures: sinew-plot draws
every frame of a run of models/pigeon_wing.sinew (its bones and the 19
rachises it writes), and the frames nearest the times asked for are tiled
into one image with their times.

  scripts/wing_frames.py RUN.h5 -o OUT.png [--times 0,0.06,...] [--view ELEV,AZIM]
"""
import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--times", default="0,0.06,0.12,0.2,0.33,0.42")
    ap.add_argument("--view", default="25,-120")
    o = ap.parse_args()
    with h5py.File(o.run, "r") as f:
        t = f["/time"][:]
    want = [float(x) for x in o.times.split(",")]
    picks = [int(np.argmin(np.abs(t - w))) for w in want]
    here = os.path.dirname(os.path.abspath(__file__))
    with tempfile.TemporaryDirectory() as tmp:
        r = subprocess.run([os.path.join(here, "sinew-plot"), "frames", o.run, "-o", tmp, "--every", "1",
                            "--view", o.view], capture_output=True, text=True)
        if r.returncode != 0:
            sys.stderr.write(r.stderr)
            return 1
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import matplotlib.image as mpimg
        cols = 3
        rows = (len(picks) + cols - 1) // cols
        fig, axs = plt.subplots(rows, cols, figsize=(4 * cols, 3 * rows))
        for ax in np.ravel(axs):
            ax.axis("off")
        for ax, k in zip(np.ravel(axs), picks):
            img = mpimg.imread(os.path.join(tmp, "frame_%05d.png" % k))
            h, w = img.shape[:2]
            ax.imshow(img[int(0.08 * h):int(0.92 * h), int(0.1 * w):int(0.8 * w)])
            ax.set_title("t = %.3f s" % t[k], fontsize=9)
        fig.suptitle("The kinematic wing's stroke (models/pigeon_wing.sinew; bones and rachises)", fontsize=10)
        fig.tight_layout()
        fig.savefig(o.output, dpi=100)
    return 0


if __name__ == "__main__":
    sys.exit(main())
