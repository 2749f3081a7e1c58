#!/usr/bin/python3
"""compare_h5.py A.h5 B.h5 [--except PREFIX]... — how two sinew outputs of the
same scene differ.

Compares every dataset the two files share (attributes that record the run,
such as wall time, are left out): prints one line per file pair, "bitwise" when
every dataset is byte-for-byte equal, else the largest absolute difference and
the largest difference relative to the dataset's largest magnitude, with the
dataset where it occurs.  Exit status 0 if bitwise equal, 1 if not, 2 if the
files do not hold the same datasets.  --except leaves out the datasets whose
path starts with PREFIX (say, diagnostics/energy, whose work sum depends on
the vector width).  Used by bench/compare_outputs.sh to say
how a change of the runtime moves results (docs/benchmarks.md)."""
import sys
import h5py
import numpy as np


def datasets(f):
    out = {}
    f.visititems(lambda name, obj: out.__setitem__(name, obj) if isinstance(obj, h5py.Dataset) else None)
    return out


def main():
    args, skip = [], []
    it = iter(sys.argv[1:])
    for x in it:
        if x == "--except":
            skip.append(next(it))
        else:
            args.append(x)
    a, b = h5py.File(args[0], "r"), h5py.File(args[1], "r")
    keep = lambda d: {k: v for k, v in d.items() if not any(k.startswith(p) for p in skip)}
    da, db = keep(datasets(a)), keep(datasets(b))
    if set(da) != set(db):
        print("different datasets:", sorted(set(da) ^ set(db)))
        return 2
    worst_abs, worst_rel, where, same = 0.0, 0.0, "", True
    for name in sorted(da):
        x, y = da[name][()], db[name][()]
        if x.shape != y.shape:
            print(f"{name}: shapes {x.shape} and {y.shape}")
            return 2
        if x.dtype.kind not in "fiu":
            same &= bool(np.array_equal(x, y))
            continue
        if x.tobytes() == y.tobytes():
            continue
        same = False
        x, y = x.astype(float), y.astype(float)
        d = np.nanmax(np.abs(x - y)) if x.size else 0.0
        scale = np.nanmax(np.abs(x)) if x.size else 0.0
        rel = d / scale if scale > 0 else d
        if rel > worst_rel:
            worst_abs, worst_rel, where = d, rel, name
    if same:
        print("bitwise")
        return 0
    print(f"max abs {worst_abs:.3g}, max rel {worst_rel:.3g} (of the dataset's largest value) in {where}")
    return 1


sys.exit(main())
