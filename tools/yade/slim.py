#!/usr/bin/python3
"""Shrink a YADE run file for tests/data/yade/: keep time, position, quaternion, tilt, rotation,
bodies, events, summary and the root attributes except the embedded script (< 60 kB a file).
    /usr/bin/python3 tools/yade/slim.py [--stride K] FILE.h5 ...
--stride K keeps every K-th sample of the time histories (the summary keeps the full-rate
extremes computed during the run)."""
import os
import sys

import h5py

KEEP = ("time", "position", "quaternion", "tilt", "rotation", "bodies", "events", "summary")
args = sys.argv[1:]
stride = 1
if args[:1] == ["--stride"]:
    stride, args = int(args[1]), args[2:]
SERIES = ("time", "position", "quaternion", "tilt", "rotation")
for p in args:
    tmp = p + ".slim"
    with h5py.File(p, "r") as src, h5py.File(tmp, "w") as dst:
        for k, v in src.attrs.items():
            if k != "yade_script":
                dst.attrs[k] = v
        for k in KEEP:
            if k in src and k in SERIES:
                dst.create_dataset(k, data=src[k][::stride], compression="gzip", compression_opts=9,
                                   shuffle=True)
            elif k in src:
                src.copy(k, dst)
    os.replace(tmp, p)
