#!/usr/bin/python3
"""study_same.py A.h5 B.h5 — 0 when two study files hold the same results:
every dataset and attribute bit for bit (NaN where NaN), but the two that
say how the work was done (/evaluations/wall_time and /evaluations/rank);
else 1, naming the first difference."""
import sys
import h5py
import numpy as np

SKIP = {"evaluations/wall_time", "evaluations/rank"}


def items(f):
    out = {}
    def visit(name, obj):
        if name in SKIP:
            return
        for k, v in obj.attrs.items():
            out[f"{name}@{k}"] = v
        if isinstance(obj, h5py.Dataset):
            out[name] = obj[()]
    f.visititems(visit)
    for k, v in f.attrs.items():
        out[f"/@{k}"] = v
    return out


def same(x, y):
    x, y = np.asarray(x), np.asarray(y)
    if x.shape != y.shape or x.dtype != y.dtype:
        return False
    return x.tobytes() == y.tobytes() if x.dtype.kind in "fiub" else bool(np.all(x == y))


a, b = (items(h5py.File(p, "r")) for p in sys.argv[1:3])
if set(a) != set(b):
    print(f"study_same: objects differ: {sorted(set(a) ^ set(b))[:5]}")
    sys.exit(1)
for k in sorted(a):
    if not same(a[k], b[k]):
        print(f"study_same: {k} differs")
        sys.exit(1)
print(f"study_same: {len(a)} datasets and attributes equal")
