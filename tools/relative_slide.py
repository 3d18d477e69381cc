#!/usr/bin/python3
"""Slide of the upper of two stacked free blocks on the lower one, from a rockdem HDF5 run.

The upper block's footprint centre (the mean of its lowest body-frame vertices at the start) is
expressed in the lower block's body frame; its horizontal displacement from the start is the
slip at the joint, free of the rocking sway that moves both blocks together. Prints the largest
and the final slip (mm). Usage: relative_slide.py RUN.h5
"""
import sys

import h5py
import numpy as np
from scipy.spatial.transform import Rotation


def main(path):
    with h5py.File(path, "r") as f:
        x, q = f["position"][:], f["quaternion"][:]
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["bodies"]["names"][:]]
        verts = f["bodies"][names[1]]["vertices"][:]
    rot = [Rotation.from_quat(np.c_[q[:, k, 1], q[:, k, 2], q[:, k, 3], q[:, k, 0]]) for k in range(2)]
    world0 = x[0, 1] + rot[1][0].apply(verts)
    base = np.argsort(world0[:, 2])[:4]
    foot = verts[base].mean(axis=0)                           # upper's footprint, its own frame
    foot_w = x[:, 1] + rot[1].apply(foot)                     # ... in the world
    rel = rot[0].inv().apply(foot_w - x[:, 0])                # ... in the lower block's frame
    d = np.hypot(rel[:, 0] - rel[0, 0], rel[:, 1] - rel[0, 1])
    print("slide of the upper block on the lower one: max %.3f mm, final %.3f mm" % (1e3 * d.max(), 1e3 * d[-1]))


if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(sys.argv) == 2 else 2)
    main(sys.argv[1])
