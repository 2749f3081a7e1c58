#!/usr/bin/python3
"""Suppl. Fig. 13 (b) in the reference's code beside sinew's kinematic wing.

usage: hardened_table.py CODE_OUT.txt [CODE_OUT.txt ...] --sinew LABEL=RUN.h5 [LABEL=RUN.h5 ...] [--every MS]

CODE_OUT.txt: the standard output of the patched code (PATCHES.md) run with
WING_SHEAR_X=10, in the order of its restarts (a resumed run's file after
the one it resumed); its "diag" lines come every 0.1 ms.  RUN.h5: runs of
sinew's kinematic wing (original, hardened, at other steps) written with
the energy diagnostic (bench/oracle/wing/README.md, "sinew's side"), each
headed LABEL in the table.  Prints a markdown table every MS milliseconds
(default 1): the code's kinetic energy, its translational part (sum m v^2 /
2, which its imposed elements' integrated spin does not reach), its largest
|w| and the element that has it, and each sinew run's kinetic energy ("-"
where a run has no frame: it had stopped).
"""
import re
import sys

import h5py
import numpy as np


def code_rows(paths):
    rows, cur = {}, None
    for path in paths:
        for line in open(path):
            m = re.match(r'diag t (\S+) ms step \d+ KE (\S+) J \(trans (\S+) rot (\S+)\)', line)
            if m:
                t = round(float(m.group(1)), 4)
                cur = rows[t] = {'ke': float(m.group(2)), 'trans': float(m.group(3)), 'top': None}
                continue
            m = re.match(r'\s+top1 rod\s+\d+ \((.*)\) elem (\d+)/\d+ \|w\| (\S+)', line)
            if m and cur is not None and cur['top'] is None:
                cur['top'] = (m.group(1), int(m.group(2)), float(m.group(3)))
    return rows


def sinew_ke(path):
    f = h5py.File(path, 'r', locking=False)
    return f['time'][:], f['diagnostics/energy'][:, 0]


def at(series, t_ms):
    t, ke = series
    i = int(np.argmin(abs(t - t_ms * 1e-3)))
    return '%.3g' % ke[i] if abs(t[i] - t_ms * 1e-3) < 2e-5 else '-'


def main(argv):
    if '--sinew' not in argv:
        sys.exit(__doc__)
    every = 1.0
    if '--every' in argv:
        i = argv.index('--every')
        every = float(argv[i + 1])
        del argv[i:i + 2]
    k = argv.index('--sinew')
    paths, runs = argv[:k], [a.split('=', 1) for a in argv[k + 1:]]
    rows, series = code_rows(paths), [sinew_ke(f) for _, f in runs]
    print('| t (ms) | the code x10: kinetic energy (J) | its translational part (J) '
          '| its largest \\|w\\| (rad/s), element |' + ''.join(' sinew %s (J) |' % l for l, _ in runs))
    print('|---|---|---|---|' + '---|' * len(runs))
    for t in sorted(rows):
        if abs(t / every - round(t / every)) > 1e-6:
            continue
        r = rows[t]
        top = '%.3g, %s elem %d' % (r['top'][2], r['top'][0], r['top'][1]) if r['top'] else '-'
        print('| %g | %.3g | %.3g | %s |' % (t, r['ke'], r['trans'], top) + ''.join(' %s |' % at(x, t) for x in series))


if __name__ == '__main__':
    main(sys.argv[1:])
