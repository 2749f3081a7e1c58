#!/usr/bin/python3
"""pyelastica_cantilever.py — bench_rod's cantilever in PyElastica, timed or run to a time.

Design.  The rod of bench/bench_rod.c (n elements, length 1 m, radius 0.01 m,
E = 1 MPa, G = E / 3 as sinew's default Poisson ratio 0.5 gives, density
1000 kg/m^3, no damping, along x with normal z, gravity (0, 0, -9.81) m/s^2)
built with PyElastica's own API: CosseratRod.straight_rod, OneEndFixedBC on
node 0 and element 0, GravityForces, and its PositionVerlet stepped by
`stepper.step(simulator, time, dt)`, the loop PyElastica's examples use.  The
time step is given on the command line, so the caller passes the one
sinew's bench_rod uses (0.5 x sinew's stable dt of the same rod).

    pyelastica_cantilever.py time N DT      one line: "n ns_median ns_min batch_steps"
    pyelastica_cantilever.py tip N DT STEPS two lines: "KIND n steps x y z" of the last node

`tip` runs the rod twice: as PyElastica builds it (KIND "pyelastica"), whose
shear coefficient is alpha_c = 27/28 (Kaneko 1975, in its factory function),
and with alpha_c = 4/3 as sinew and Gazzola et al. 2018 have it (KIND
"alpha43"), the one difference between the two models that the comparison
found (bench/bench_pyelastica.sh, docs/benchmarks.md).

`time` first runs steps until numba has compiled every kernel and the loop
has run for WARMUP seconds (that time is not counted), then NBATCH batches of
at least BATCH_SECONDS each; like bench_rod, the rod is put back at rest
outside the timer after every second of simulated time, and the figure is
the batch wall time / (steps x n), median and minimum over the batches.
PyElastica is imported from PYTHONPATH (bench/bench_pyelastica.sh sets it).
"""
import sys
import time as clock

import numpy as np
import elastica as ea

NBATCH = 9
BATCH_SECONDS = 0.2
WARMUP = 1.0            # s of wall time after the first (compiling) step
SEGMENT_SECONDS = 1.0   # simulated time between resets, as in bench_rod


class Cantilever(ea.BaseSystemCollection, ea.Constraints, ea.Forcing):
    pass


def build(n, alpha_c=None):
    """The cantilever; alpha_c replaces PyElastica's shear coefficient."""
    sim = Cantilever()
    E = 1e6
    rod = ea.CosseratRod.straight_rod(
        n, np.zeros(3), np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0]),
        1.0, 0.01, 1000.0, youngs_modulus=E, shear_modulus=E / 3.0)
    if alpha_c is not None:
        for k in (0, 1):
            rod.shear_matrix[k, k, :] = alpha_c * E / 3.0 * np.pi * 0.01**2
    sim.append(rod)
    sim.constrain(rod).using(ea.OneEndFixedBC, constrained_position_idx=(0,),
                             constrained_director_idx=(0,))
    sim.add_forcing_to(rod).using(ea.GravityForces, acc_gravity=np.array([0.0, 0.0, -9.81]))
    sim.finalize()
    return sim, rod


def main(argv):
    mode, n, dt = argv[1], int(argv[2]), float(argv[3])
    stepper = ea.PositionVerlet()
    if mode == "tip":
        for kind, alpha_c in (("pyelastica", None), ("alpha43", 4.0 / 3.0)):
            sim, rod = build(n, alpha_c)
            t = 0.0
            for _ in range(int(argv[4])):
                t = stepper.step(sim, t, dt)
            x = rod.position_collection[:, -1]
            print(f"{kind} {n} {argv[4]} {x[0]:.17g} {x[1]:.17g} {x[2]:.17g}")
        return 0
    sim, rod = build(n)
    state = [rod.position_collection, rod.director_collection,
             rod.velocity_collection, rod.omega_collection]
    rest = [a.copy() for a in state]
    t = 0.0
    if mode != "time":
        sys.exit(f"usage: {argv[0]} time N DT | tip N DT STEPS")
    segment = int(np.ceil(SEGMENT_SECONDS / dt))
    since = 0

    def run(k):
        """Wall time of k steps, the resets to rest excluded."""
        nonlocal t, since
        spent = 0.0
        while k > 0:
            if since >= segment:
                for a, r in zip(state, rest):
                    a[...] = r
                t, since = 0.0, 0
            chunk = min(k, segment - since)
            t0 = clock.perf_counter()
            for _ in range(chunk):
                t = stepper.step(sim, t, dt)
            spent += clock.perf_counter() - t0
            k -= chunk
            since += chunk
        return spent

    run(1)  # numba compiles the kernels here
    reps, warm, per_step = 16, 0.0, float("inf")
    while warm < WARMUP:
        s = run(reps)
        warm += s
        per_step = min(per_step, s / reps)
        reps *= 2
    batch = max(int(np.ceil(BATCH_SECONDS / per_step)), 1)
    ns = sorted(1e9 * run(batch) / (batch * n) for _ in range(NBATCH))
    print(f"{n} {ns[NBATCH // 2]:.4f} {ns[0]:.4f} {batch}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
