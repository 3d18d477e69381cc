#!/usr/bin/python3
"""Compare a DEM run of a two-block stack with its rigid (Kounadis) reference.

Usage: stack_compare.py DEM.h5 REF.h5
Prints, for each block, the largest tilt (rad) of both runs and their relative difference, and
the times (s) of the first uplift of each block (lower: the stack lifts off its base; upper:
the upper block separates from the lower one) and of the lower block's first impact on the
base, with their differences relative to the reference time. Events come from /events (the
DEM's monitor; the reference's root-found transitions).
"""
import sys

import h5py
import numpy as np


def events(path):
    """{(body, type): [times]} from /events (layout 2: body names, enum types)."""
    out = {}
    with h5py.File(path, "r") as f:
        g = f["events"]
        names = {v: k for k, v in h5py.check_enum_dtype(g["type"].dtype).items()}
        for b, ty, t in zip(g["body"][:], g["type"][:], g["time"][:]):
            b = b.decode() if isinstance(b, bytes) else str(b)
            out.setdefault((b, names[int(ty)]), []).append(float(t))
        bodies = [n.decode() if isinstance(n, bytes) else str(n) for n in f["bodies"]["names"][:]]
        tilt = f["tilt"][:]
    return out, bodies, tilt


def main(dem, ref):
    ed, bodies, td = events(dem)
    er, _, tr = events(ref)
    rows = []
    for k, b in enumerate(bodies):
        a, r = np.abs(td[:, k]).max(), np.abs(tr[:, k]).max()
        rows.append(("%s max tilt (rad)" % b, a, r, (a - r) / r))
    for b, what, ty in ((bodies[0], "stack uplift", "uplift"), (bodies[1], "upper separation", "uplift"),
                        (bodies[0], "first ground impact", "impact")):
        a, r = ed.get((b, ty), [None])[0], er.get((b, ty), [None])[0]
        rows.append(("%s time (s)" % what, a, r, None if a is None or r is None else (a - r) / r))
    for name, a, r, d in rows:
        fmt = lambda v: "%12s" % "-" if v is None else "%12.5g" % v
        print("%-32s %s %s %s" % (name, fmt(a), fmt(r), "%+9.2f %%" % (100 * d) if d is not None else "%11s" % "-"))


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(sys.argv) == 2 else 2)
    main(sys.argv[1], sys.argv[2])
