#!/usr/bin/python3
"""Joint slip of stacked free bodies (a two-block stack, a drum column), from a rockdem HDF5 run.

Free body k + 1 is taken to rest on free body k (output order, bottom up), and free body 0 on
the fixed base. A body's footprint centre (the mean of its lowest vertices at the start: the
centre of its base face) is expressed in the frame of the body below (the fixed frame for body
0); its horizontal displacement from the start is the slip at that joint, free of the rocking
sway that moves the bodies together (a rigid block rocking on its edges without slip returns its
footprint to the start whenever it stands upright). Prints, per joint, the largest and the final
slip (mm).
Usage: relative_slide.py RUN.h5
"""
import sys

import h5py
import numpy as np
from scipy.spatial.transform import Rotation

from rdtools.bodies import Bodies  # tools/ is this script's folder


FIXED = "(fixed base)"   # the lower side of the lowest free body's joint


def joint_slips(path):
    """[(lower name, upper name, max slip m, final slip m)] for each joint, the lowest free body on
    the fixed base first."""
    with h5py.File(path, "r") as f:
        x, q = f["position"][:], f["quaternion"][:]
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["bodies"]["names"][:]]
        bodies = Bodies(f)
        verts = [bodies.vertices(n) for n in names]
    free = list(range(x.shape[1]))  # /position holds the free bodies, in output order
    rot = [Rotation.from_quat(np.c_[q[:, k, 1], q[:, k, 2], q[:, k, 3], q[:, k, 0]]) for k in free]
    out = []
    for up in free:
        world0 = x[0, up] + rot[up][0].apply(verts[up])
        low = world0[:, 2] < world0[:, 2].min() + 1e-6 * np.ptp(world0[:, 2])
        foot = x[:, up] + rot[up].apply(verts[up][low].mean(axis=0))   # its base face's centre
        rel = foot if up == 0 else rot[up - 1].inv().apply(foot - x[:, up - 1])
        d = np.hypot(rel[:, 0] - rel[0, 0], rel[:, 1] - rel[0, 1])
        out.append((FIXED if up == 0 else names[up - 1], names[up], float(d.max()), float(d[-1])))
    return out


def main(path):
    for lo, up, dmax, dend in joint_slips(path):
        print("joint %s/%s: slip max %.3f mm, final %.3f mm" % (lo, up, 1e3 * dmax, 1e3 * dend))


if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(sys.argv) == 2 else 2)
    main(sys.argv[1])
