#!/usr/bin/python3
"""The first milliseconds of sinew's wing, in the oracle's terms.

Reads a run of a copy of models/pigeon_wing.sinew whose output block writes
`velocity; angular_velocity; energy;` for every rod (README.md says how it is
made) and prints, every frame: the kinetic energy of /diagnostics/energy, the
same rebuilt from the rods (lumped node masses rho A l / 2 per element end,
element inertia rho l (I1, I2, 2 I1), I1 = pi r^4 / 4), by group (bones,
rachises, barbs, muscles), and the 5 elements with the largest |w|, with
their rod's kinetic energy: the figures bench/oracle/wing/PATCHES.md makes
the reference's code print.

usage: sinew_first_ms.py RUN.h5
"""
import sys

import h5py
import numpy as np


def group(name):
    if '.f.' not in name:
        return 'muscles' if name.split('.')[0] in ('sup', 'pect', 'bc', 'st') \
            else 'bones'
    return 'rachises' if name.endswith('.rachis') else 'barbs'


def main(path):
    f = h5py.File(path, 'r')
    t = f['time'][:]
    ke_diag = f['diagnostics/energy'][:, 0]
    rods = []
    for name, g in f['rods'].items():
        if 'velocity' not in g or g.attrs.get('rigid', 0):
            continue
        n = int(g.attrs['elements'])
        r = np.asarray(g.attrs['radius'], float) * np.ones(n)
        le = float(g.attrs['length']) / n
        rho = float(g.attrs['density'])
        me = rho * np.pi * r**2 * le
        mn = np.zeros(n + 1)
        mn[:-1] += me / 2
        mn[1:] += me / 2
        i1 = np.pi * r**4 / 4
        jj = rho * le * np.stack([i1, i1, 2 * i1], axis=1)
        v = g['velocity'][:]
        w = g['angular_velocity'][:]
        ket = 0.5 * np.einsum('n,fnk->f', mn, v * v)
        ker = 0.5 * np.einsum('nk,fnk->f', jj, w * w)
        rods.append((name, group(name), ket + ker, np.linalg.norm(w, axis=2)))
    for fr in range(len(t)):
        by = {}
        tot = 0.0
        cand = []
        for name, grp, ke, wn in rods:
            by[grp] = by.get(grp, 0.0) + ke[fr]
            tot += ke[fr]
            cand.extend((wn[fr][k], name, k, ke[fr], wn.shape[1])
                        for k in np.argsort(wn[fr])[-5:])
        cand.sort(reverse=True)
        print(f"t {t[fr] * 1e3:.2f} ms KE(diag) {ke_diag[fr]:.4e} J rebuilt "
              f"{tot:.4e} bones {by.get('bones', 0):.3e} rachises "
              f"{by.get('rachises', 0):.3e} barbs {by.get('barbs', 0):.3e} "
              f"muscles {by.get('muscles', 0):.3e}")
        for q, (wv, name, k, ke, n) in enumerate(cand[:5]):
            print(f"  top{q + 1} {name} elem {k}/{n} |w| {wv:.4g} rad/s "
                  f"rodKE {ke:.3e} J")


if __name__ == '__main__':
    main(sys.argv[1])
