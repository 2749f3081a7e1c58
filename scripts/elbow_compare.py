#!/usr/bin/python3
"""elbow_compare.py — compare the elbow angle of two runs of the same scene
(bench/bench_elbow.sh, validation 6 of issue 4) and print a Markdown report.

Usage: elbow_compare.py REF.h5 RUN.h5 WALL_REF WALL_RUN DT_RUN DURATION
The second run is interpolated to the first one's frame times.  The figure is the
largest difference of the elbow angle over the run, relative to the angle
itself and to the flexion (the angle's excursion from its start)."""
import sys
import h5py
import numpy as np

ref, run, wref, wrun, dtrun, dur = sys.argv[1:7]
def load(path):
    with h5py.File(path, "r") as f:
        return np.array(f["time"]), np.array(f["joints/arm.elbow/angle"]), f.attrs["status"]
t0, a0, s0 = load(ref)
t1, a1, s1 = load(run)
# a dt that does not divide the frame interval puts frames a little off the
# reference's times: compare at the reference's times, interpolated
n = int(np.searchsorted(t0, t1[-1], side="right"))
a1 = np.interp(t0[:n], t1, a1)
d = np.abs(a1 - a0[:n])
rel_angle = np.max(d / np.abs(a0[:n]))
excursion = np.max(np.abs(a0[:n] - a0[0]))
rel_flex = np.max(d) / excursion
verdict = "within" if rel_angle <= 0.01 else "NOT within"
print(f"""Scene `examples/elbow_flexion.sinew` ({dur} of simulated time, frames every 1 ms),
run once at the reference's dt = 50 ns and once at the stable-dt estimate
({dtrun}) that `--info` reports.  Wall times on this machine (2 shared cores,
one run at a time, one sample each: each takes minutes):

| dt | wall time | status |
|---|---|---|
| 50 ns (Zhang et al. 2019, Suppl. Table 5) | {float(wref):.1f} s | {s0} |
| {dtrun} (stable estimate) | {float(wrun):.1f} s | {s1} |

Speed-up {float(wref)/float(wrun):.1f}x.  Elbow flexion over the run: {np.degrees(excursion):.2f} deg
(from {np.degrees(a0[0]):.2f} to {np.degrees(a0[n-1]):.2f} deg).  Largest difference of the elbow angle
between the two runs: {np.degrees(np.max(d)):.4f} deg, {rel_angle:.2e} of the angle ({verdict} 1%),
{rel_flex:.2e} of the flexion.""")
