#!/usr/bin/python3
"""rms axial strain (sigma_3) along the rod vs time, all runs (log scale)."""
import glob, os
import numpy as np
import matplotlib; matplotlib.use("Agg")
import matplotlib.pyplot as plt
fig, ax = plt.subplots(figsize=(9, 5))
ax.set_prop_cycle(color=plt.cm.tab20(np.linspace(0, 1, 20)))
for p in sorted(glob.glob(os.path.join(os.environ.get("ORACLE_RUNS", "runs"), "*.npz"))):
    n = os.path.basename(p)[:-4]
    if n.startswith(("test", "val")):
        continue
    d = np.load(p)
    t = d["time"]; s = d["sigma"]
    ax.semilogy(t[1:], np.sqrt((s[1:, 2, :] ** 2).mean(1)), lw=0.8, label=n)
ax.set_xlabel("t [s]"); ax.set_ylabel("rms axial strain sigma_3 along rod"); ax.set_xlim(0, 30)
ax.legend(fontsize=6); ax.set_title("axial-strain growth (all runs; runs named permass use the v0.2-style damping)")
fig.tight_layout(); fig.savefig(os.path.join(os.environ.get("ORACLE_OUT", "."), "strain_growth.png"), dpi=110)
