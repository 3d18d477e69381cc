#!/usr/bin/python3
"""Generate an irregular granite-like precariously balanced rock (PBR) as a closed OBJ mesh.

The rock has seed 002's size: plan extents about 0.30 x 0.64 m, 0.80 m tall, 354 kg at
2750 kg/m^3 (0.129 m^3). Construction (all deterministic for a seed):
  1. a superellipsoid radial surface r(u) on a latitude-longitude grid of unit directions u,
     times 1 + seeded low-order noise (a few random plane waves over u);
  2. the base is flattened by central projection from the origin onto the plane z = -0.9 c:
     points below the plane slide along their ray onto it, so the surface stays star-shaped
     (no folds) and the support is a small, irregular flat region;
  3. a taper narrows the lower part (precarious: small base, wide body);
  4. the plan is scaled so its extents have the ratio 0.30 : 0.64 and the volume is exactly
     the target (the irregular rock fills less of its box than the target's 84 %, so the plan
     comes out about 10 % larger than 0.30 x 0.64 m); the height is 0.80 m and the base sits
     on z = 0, centred on the origin.
Triangles are counter-clockwise seen from outside. Prints volume and mass.
Usage: make_pbr.py [--seed N] [-o rock.obj] [--density 2750] [--mass 354] [--nlat 32] [--roughness R]
(--nlat sets the resolution: bench/mesh_setup.sh times 10k, 100k and 1M-triangle rocks.)
"""
import argparse
import sys

import numpy as np

PLAN = (0.30, 0.64)  # plan extents before the volume scaling, m
HEIGHT = 0.80        # m
EXPONENT = 6.0       # superellipsoid exponent: boxier than an ellipsoid


def directions(nlat, nlon):
    """Unit directions: north pole, nlat-1 rings of nlon, south pole; and the triangles."""
    th = np.pi * np.arange(1, nlat) / nlat
    ph = 2 * np.pi * np.arange(nlon) / nlon
    T, P = np.meshgrid(th, ph, indexing="ij")
    ring = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], axis=-1).reshape(-1, 3)
    u = np.vstack([[0.0, 0.0, 1.0], ring, [0.0, 0.0, -1.0]])
    tris = []
    south = len(u) - 1
    def vid(i, j):
        return 1 + i * nlon + j % nlon
    for j in range(nlon):
        tris.append((0, vid(0, j), vid(0, j + 1)))
        tris.append((south, vid(nlat - 2, j + 1), vid(nlat - 2, j)))
        for i in range(nlat - 2):  # theta grows southwards, phi eastwards: outward order
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            tris.append((a, b, c))
            tris.append((a, c, d))
    return u, np.array(tris)


def volume(x, tris):
    a, b, c = x[tris[:, 0]], x[tris[:, 1]], x[tris[:, 2]]
    return float(np.sum(np.einsum("ij,ij->i", a, np.cross(b, c)))) / 6.0


def rock(seed, target_volume, nlat=32, roughness=0.0):
    rng = np.random.default_rng(seed)
    u, tris = directions(nlat, 2 * nlat)
    semi = np.array([PLAN[0] / 2, PLAN[1] / 2, HEIGHT / 2])
    r = np.sum(np.abs(u / semi) ** EXPONENT, axis=1) ** (-1.0 / EXPONENT)
    noise = np.zeros(len(u))
    for _ in range(6):  # low-order plane waves over the direction sphere
        k = rng.normal(size=3)
        k *= rng.uniform(1.0, 3.0) / np.linalg.norm(k)
        noise += rng.uniform(0.02, 0.05) * np.cos(u @ k + rng.uniform(0, 2 * np.pi))
    x = u * (r * (1 + noise))[:, None]
    zcut = -0.9 * semi[2]
    low = x[:, 2] < zcut
    x[low] *= (zcut / x[low, 2])[:, None]        # central projection onto the base plane
    zmin, zmax = zcut, x[:, 2].max()
    s = 1 - 0.3 * ((zmax - x[:, 2]) / (zmax - zmin)) ** 2
    x[:, :2] *= s[:, None]                        # taper: narrow base
    x[:, 2] = (x[:, 2] - zmin) * HEIGHT / (zmax - zmin)
    base = x[:, 2] == 0
    x[:, :2] -= x[base, :2].mean(axis=0)          # base centred on the origin
    ext = x[:, :2].max(axis=0) - x[:, :2].min(axis=0)
    x[:, :2] *= np.sqrt(ext[::-1] / ext * np.array(PLAN) / PLAN[::-1])  # plan ratio, same area
    x[:, :2] *= np.sqrt(target_volume / volume(x, tris))
    if roughness > 0:  # a scanned base: each base vertex raised by up to `roughness` (m), seeded
        x[base, 2] += np.random.default_rng(seed + 1).uniform(0, roughness, base.sum())
    return x, tris


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("-o", "--output", default="pbr.obj")
    ap.add_argument("--density", type=float, default=2750.0, help="kg/m^3")
    ap.add_argument("--mass", type=float, default=354.0, help="target mass, kg")
    ap.add_argument("--nlat", type=int, default=32,
                    help="latitude rings + 1: 4 nlat (nlat - 1) triangles (32: 3968, 50: 9800, "
                         "158: 99224, 500: 998000)")
    ap.add_argument("--roughness", type=float, default=0.0,
                    help="raise each base vertex by a seeded uniform 0..R m (an irregular scanned base)")
    a = ap.parse_args()
    x, tris = rock(a.seed, a.mass / a.density, a.nlat, a.roughness)
    lines = [f"# precariously balanced rock, tools/make_pbr.py --seed {a.seed}; metres, base on z = 0"]
    lines += [f"v {p[0]:.6f} {p[1]:.6f} {p[2]:.6f}" for p in x]
    lines += [f"f {t[0] + 1} {t[1] + 1} {t[2] + 1}" for t in tris]
    with open(a.output, "w", encoding="ascii", newline="\n") as f:
        f.write("\n".join(lines) + "\n")
    xr = np.array([[float(c) for c in ln.split()[1:]] for ln in lines if ln.startswith("v ")])
    v = volume(xr, tris)
    ext = xr.max(axis=0) - xr.min(axis=0)
    print(f"{a.output}: {len(xr)} vertices, {len(tris)} triangles, volume {v:.6f} m^3, "
          f"mass {v * a.density:.1f} kg, extents {ext[0]:.3f} x {ext[1]:.3f} x {ext[2]:.3f} m")
    return 0


if __name__ == "__main__":
    sys.exit(main())
