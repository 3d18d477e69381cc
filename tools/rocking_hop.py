#!/usr/bin/python3
"""Hop and slide of a single block in free rocking, from a rockdem HDF5 run.

Prints "HOP | SLIDE" in mm: HOP is the largest height of the block's lowest vertex above the
ground top (z = 0; a negative value is the pivot's elastic sinking, i.e. no hop), SLIDE the
horizontal distance of its footprint centre at the end from its upright place (0, 0), i.e. the
slip accumulated beyond the rolling of the pivot. Usage: rocking_hop.py RUN.h5
"""
import sys

import h5py
import numpy as np
from scipy.spatial.transform import Rotation

from rdtools.bodies import Bodies  # tools/ is this script's folder


def main(path):
    with h5py.File(path, "r") as f:
        x = f["position"][:, 0]
        q = f["quaternion"][:, 0]
        bodies = Bodies(f)
        verts = bodies.vertices(bodies.names[0])  # the first free body
    rot = Rotation.from_quat(np.c_[q[:, 1], q[:, 2], q[:, 3], q[:, 0]])
    world = np.stack([x + rot.apply(v) for v in verts], axis=1)
    hop = world[:, :, 2].min(axis=1).max()
    base = np.argsort(world[-1, :, 2])[:4]
    slide = np.hypot(*world[-1, base, :2].mean(axis=0))
    print("%.3f | %.3f" % (1e3 * hop, 1e3 * slide))


if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(sys.argv) == 2 else 2)
    main(sys.argv[1])
