#!/usr/bin/python3
"""Write the 0.5 x 0.5 x 1.0 m block as closed triangle meshes of four tessellations (OBJ),
for the contact model's tessellation tests (tests/test_surface.c, docs/CONTACT.md section 8):

  box8.obj       the 8 corners, 12 triangles
  box_cut10.obj  every face cut 10 x 10 (1,200 triangles)
  box_remesh.obj an irregular remesh: each face's edges cut evenly (shared by the faces around
                 them), its interior points jittered and Delaunay-triangulated (scipy), 5,120
                 triangles
and the 0.5 m cube with every face cut 10 x 10 (cube_cut10.obj, the spin-down test).

usage: tools/box_meshes.py OUTDIR
"""
import sys
import numpy as np
from scipy.spatial import Delaunay

SIZE = (0.5, 0.5, 1.0)


def face_axes():
    # (normal axis, side, u axis, v axis) with u x v = outward normal
    out = []
    for ax in range(3):
        u, v = (ax + 1) % 3, (ax + 2) % 3
        out.append((ax, +1, u, v))
        out.append((ax, -1, v, u))
    return out


def box_mesh(cuts, jitter, seed=1, size=SIZE):
    """cuts[axis]: segments along each axis; jitter: fraction of a cell the interior points move."""
    rng = np.random.default_rng(seed)
    verts, index, tris = [], {}, []

    def vid(p):
        key = tuple(np.round(np.asarray(p) / 1e-9).astype(np.int64))
        if key not in index:
            index[key] = len(verts)
            verts.append(np.asarray(p, float))
        return index[key]

    h = [s / 2 for s in size]
    for ax, side, u, v in face_axes():
        nu, nv = cuts[u], cuts[v]
        pts2, ids = [], []
        for i in range(nu + 1):
            for j in range(nv + 1):
                a, b = -h[u] + size[u] * i / nu, -h[v] + size[v] * j / nv
                interior = 0 < i < nu and 0 < j < nv
                if interior and jitter > 0:
                    a += (rng.random() - 0.5) * jitter * size[u] / nu
                    b += (rng.random() - 0.5) * jitter * size[v] / nv
                p = [0.0, 0.0, 0.0]
                p[ax], p[u], p[v] = side * h[ax], a, b
                pts2.append((a, b))
                ids.append(vid(p))
        pts2 = np.array(pts2)
        if jitter > 0:
            simp = Delaunay(pts2).simplices
        else:
            simp = []
            for i in range(nu):
                for j in range(nv):
                    k = i * (nv + 1) + j
                    simp += [(k, k + nv + 1, k + nv + 2), (k, k + nv + 2, k + 1)]
        for t in simp:
            a, b, c = (pts2[t[0]], pts2[t[1]], pts2[t[2]])
            cr = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
            t = list(t) if cr > 0 else [t[0], t[2], t[1]]  # counter-clockwise in (u, v): outward
            tris.append([ids[t[0]], ids[t[1]], ids[t[2]]])
    return np.array(verts), tris


def write_obj(path, verts, tris):
    with open(path, "w") as f:
        f.write("# tools/box_meshes.py\n")
        for p in verts:
            f.write("v %.12g %.12g %.12g\n" % tuple(p))
        for t in tris:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    write_obj(out + "/box8.obj", *box_mesh((1, 1, 1), 0))
    write_obj(out + "/box_cut10.obj", *box_mesh((10, 10, 10), 0))
    v, t = box_mesh((16, 16, 32), 0.6)
    write_obj(out + "/box_remesh.obj", v, t)
    print("box_remesh.obj: %d triangles" % len(t))
    write_obj(out + "/cube_cut10.obj", *box_mesh((10, 10, 10), 0, size=(0.5, 0.5, 0.5)))


if __name__ == "__main__":
    main()
