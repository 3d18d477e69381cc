#!/usr/bin/env python3
"""Write a right prism over a simple (possibly non-convex) polygon as a closed OBJ triangle mesh:
the test bodies of the surface model's mesh-against-mesh path (tests/data/mesh, issue 39).

    /usr/bin/python3 tools/prism_mesh.py -o L.obj --height 0.4 0 0  0.6 0  0.6 0.2  0.2 0.2  0.2 0.6  0 0.6

The polygon (x y pairs, counter-clockwise, m) is triangulated by ear clipping; each side is
two triangles. Faces run counter-clockwise seen from outside.
"""
import argparse


def ear_clip(poly):
    """Triangles (index triples) of a counter-clockwise simple polygon."""
    idx = list(range(len(poly)))
    tris = []

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    def inside(p, a, b, c):
        return cross(a, b, p) >= 0 and cross(b, c, p) >= 0 and cross(c, a, p) >= 0

    while len(idx) > 3:
        for k in range(len(idx)):
            i0, i1, i2 = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            a, b, c = poly[i0], poly[i1], poly[i2]
            if cross(a, b, c) <= 0:
                continue
            if any(inside(poly[j], a, b, c) for j in idx if j not in (i0, i1, i2)):
                continue
            tris.append((i0, i1, i2))
            idx.pop(k)
            break
        else:
            raise SystemExit("prism_mesh.py: the polygon is not simple and counter-clockwise")
    tris.append(tuple(idx))
    return tris


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--height", type=float, required=True, help="m")
    ap.add_argument("xy", type=float, nargs="+", help="polygon vertices x y ..., m")
    a = ap.parse_args()
    if len(a.xy) % 2 or len(a.xy) < 6:
        raise SystemExit("prism_mesh.py: give at least three x y pairs")
    poly = [(a.xy[k], a.xy[k + 1]) for k in range(0, len(a.xy), 2)]
    n = len(poly)
    with open(a.output, "w") as f:
        f.write("# prism of height %g m over a %d-gon (tools/prism_mesh.py)\n" % (a.height, n))
        for z in (0.0, a.height):
            for x, y in poly:
                f.write("v %.9g %.9g %.9g\n" % (x, y, z))
        for t in ear_clip(poly):  # OBJ indices from 1: bottom (reversed), top
            f.write("f %d %d %d\n" % (t[2] + 1, t[1] + 1, t[0] + 1))
            f.write("f %d %d %d\n" % (t[0] + 1 + n, t[1] + 1 + n, t[2] + 1 + n))
        for k in range(n):
            j = (k + 1) % n
            f.write("f %d %d %d\n" % (k + 1, j + 1, j + 1 + n))
            f.write("f %d %d %d\n" % (k + 1, j + 1 + n, k + 1 + n))


if __name__ == "__main__":
    main()
