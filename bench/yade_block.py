# YADE 2023.02a side of the rockdem speed benchmark (same scene as bench/block.dat).
#
#   yade -n -j1 -x bench/yade_block.py [STEPS] [DT] [--tilt DEG] [--reps R] [--trace K] [--lift M]
#
# Defaults: 20000 steps, dt 5e-5 s, tilt 2 deg, KN 1e10 Pa/m, KS 1e9 Pa/m, friction 40 deg.
# --reps R rebuilds and reruns the scene R times (same window each time) and reports the fastest;
# --trace K prints the block's state every K steps instead of timing (for checking the physics).
#
# A 0.5 x 0.5 x 1.0 m granite block (density 2700) stands on a fixed 2 x 2 x 0.5 m base, tilted by
# --tilt degrees (default 2) about its +x bottom edge, and rocks freely (no ground motion).
# Polyhedra with the volumetric law: normal force = kn * overlap volume, so kn (N/m^3) plays the
# role of rockdem's per-area normal stiffness KN (Pa/m). Ip2 gives kn = 1/(1/Y1 + 1/Y2) = young/2,
# hence young = 2*KN. YADE's shear stiffness is absolute (N/m): ks = young*poisson/2, set here to
# KS * (block base area) so that the whole base has rockdem's shear stiffness.
# Damping 0, gravity 9.81, FIXED time step (YADE's automatic steppers misread polyhedra stiffness).
#
# Only O.run(STEPS, True) is timed (not import or setup). Prints one line
#   yade: steps=<N> wall_s=<s> steps_per_s=<x> dt=<dt>
# followed by a sanity line with the block's final state (z of the centre, tilt, drift).
import argparse
import math
import sys
import time

from yade import log, utils

ap = argparse.ArgumentParser(prog="yade_block.py")
ap.add_argument("steps", nargs="?", type=int, default=20000, help="number of steps (default 20000)")
ap.add_argument("dt", nargs="?", type=float, default=5e-5, help="fixed time step in s (default 5e-5)")
ap.add_argument("--tilt", type=float, default=2.0, help="initial tilt in degrees about the +x edge")
ap.add_argument("--lift", type=float, default=1e-6,
                help="initial gap under the block's lowest edge, m (negative: overlap)")
ap.add_argument("--kn", type=float, default=1e10, help="normal stiffness per area, Pa/m")
ap.add_argument("--ks", type=float, default=1e9, help="shear stiffness per area, Pa/m")
ap.add_argument("--friction", type=float, default=40.0, help="friction angle, degrees")
ap.add_argument("--reps", type=int, default=1,
                help="rebuild and rerun the scene this many times; report the fastest run")
ap.add_argument("--verbose", action="store_true", help="keep YADE's warnings")
ap.add_argument("--trace", type=int, default=0,
                help="print the block state every K steps (slows the run; for checks, not timing)")
args = ap.parse_args(sys.argv[1:])
if not args.verbose:
    log.setLevel("Default", log.ERROR)  # Polyhedra_support warns on every degenerate intersection

BX, BY, BZ = 0.5, 0.5, 1.0  # block size (m)
RHO = 2700.0
AREA = BX * BY

young = 2.0 * args.kn
poisson = args.ks * AREA / args.kn  # ks = young*poisson/2 = KS*AREA


def box_vertices(sx, sy, sz, cx, cy, cz):
    return [Vector3(cx + i * sx / 2, cy + j * sy / 2, cz + k * sz / 2)
            for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)]


th = math.radians(args.tilt)


def build():
    """Fresh scene; returns the block body."""
    O.reset()
    mat = O.materials.append(PolyhedraMat(young=young, poisson=poisson, density=RHO,
                                          frictionAngle=math.radians(args.friction),
                                          IsSplitable=False))
    # Base: top face at z = 0.
    base = utils.polyhedron(box_vertices(2.0, 2.0, 0.5, 0, 0, -0.25), fixed=True, material=mat)
    # Block: bottom at z = 0, rotated about its +x bottom edge (x = BX/2, z = 0) so the top moves
    # to +x; lifted by --lift (1e-6 m) so the first contact is not a degenerate edge-on-face touch.
    c, s = math.cos(th), math.sin(th)
    px = BX / 2
    verts = []
    for v in box_vertices(BX, BY, BZ, 0, 0, BZ / 2):
        x, z = v[0] - px, v[2]
        verts.append(Vector3(px + c * x + s * z, v[1], -s * x + c * z + args.lift))
    block = utils.polyhedron(verts, material=mat)
    ids = O.bodies.append([base, block])
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Polyhedra_Aabb()]),
        InteractionLoop([Ig2_Polyhedra_Polyhedra_PolyhedraGeom()],
                        [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                        [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()]),
        NewtonIntegrator(damping=0.0, gravity=(0, 0, -9.81)),
    ]
    O.dt = args.dt
    return O.bodies[ids[1]]


bb = build()
pos0 = Vector3(bb.state.pos)
# Orientation of the upright block (the tilt is measured against it): ori0 = Ry(th) * ori_up.
ori_up = Quaternion(Vector3(0, 1, 0), -th) * Quaternion(bb.state.ori)


def tilt_deg():
    q = bb.state.ori * ori_up.conjugate()
    ax = q * Vector3(0, 0, 1)  # where the vertical body axis points now
    return math.degrees(math.acos(max(-1.0, min(1.0, ax[2])))) * (1 if ax[0] >= 0 else -1)


walls = []
if args.trace > 0:
    print("yade-trace: t z x tilt_deg contacts")
    done = 0
    while done < args.steps:
        k = min(args.trace, args.steps - done)
        O.run(k, True)
        done += k
        p = bb.state.pos
        print("yade-trace: %.4f %.6f %.6f %.3f %d" % (O.time, p[2], p[0], tilt_deg(),
                                                    len([i for i in O.interactions if i.isReal])))
    walls.append(float("nan"))
else:
    for rep in range(args.reps):
        if rep > 0:
            bb = build()
        t0 = time.perf_counter()
        O.run(args.steps, True)
        walls.append(time.perf_counter() - t0)
        if args.reps > 1:
            print("yade-rep: %d wall_s=%.4f" % (rep + 1, walls[-1]))
wall = min(walls)

p = bb.state.pos
sane = all(math.isfinite(x) for x in p) and 0.3 < p[2] < 0.7 and abs(tilt_deg()) < 60
print("yade: steps=%d wall_s=%.4f steps_per_s=%.1f dt=%g" % (args.steps, wall, args.steps / wall, args.dt))
print("yade-state: sim_t=%.4f z0=%.6f z=%.6f dx=%.3e dy=%.3e tilt_deg=%.3f contacts=%d sane=%s" % (
    O.time, pos0[2], p[2], p[0] - pos0[0], p[1] - pos0[1], tilt_deg(),
    len([i for i in O.interactions if i.isReal]), "yes" if sane else "NO"))
sys.stdout.flush()
