#!/usr/bin/env python3
"""Random bricks on free pedestals: how many runs the energy balance leaves untrusted.

    /usr/bin/python3 bench/free_pedestals.py [BIN]      (default bin/rockdem; about 3 minutes)

Seventy scenes, drawn with fixed seeds (docs/CONTACT.md section 1, "Crossings that no vertex
holds"): 40 of a brick on a free brick pedestal on a fixed floor (sizes 0.3-0.8 m, heights up to
1.2 m, half offset by up to 0.1 m, some turned 0-90 deg; 0.2, 0.4 or 0.7 g, 2 Hz one-sine, 2 s)
and 30 stacks of two or three bricks (0.15-0.8 g at 1-3 Hz, 2.5 s). Prints each run's exit
status and energy residual (summary energy_residual_max), then the count of untrusted runs
(exit 3) and the largest residual of the others.
"""
import os
import random
import subprocess
import sys
import tempfile

import h5py

FLOOR = "block create brick size 3 3 0.4 position 0 0 -0.2 fixed name floor"


def pedestal_scenes():
    rng = random.Random(7)
    for i in range(40):
        px, py, pz = rng.uniform(0.3, 0.8), rng.uniform(0.3, 0.8), rng.uniform(0.3, 0.8)
        bx, by, bz = rng.uniform(0.3, 0.8), rng.uniform(0.3, 0.8), rng.uniform(0.3, 1.2)
        rot = rng.choice([0, rng.uniform(0, 90)])
        ox, oy = rng.choice([(0, 0), (rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1))])
        amp, d = rng.choice([0.2, 0.4, 0.7]), rng.uniform(0, 90)
        yield "r%02d" % i, "\n".join([
            FLOOR,
            f"block create brick size {px:.3f} {py:.3f} {pz:.3f} seat-on floor name ped density 2600",
            f"block create brick size {bx:.3f} {by:.3f} {bz:.3f} seat-on ped at {ox:.3f} {oy:.3f} name b "
            f"density 2600 rotation 0 0 {rot:.2f}",
            f"ground-motion pulse one-sine amplitude {amp}g frequency 2 direction {d:.1f}",
            "model solve time 2", "output hdf5 'x.h5' interval 0.01"])


def stack_scenes():
    rng = random.Random(11)
    for i in range(30):
        lines, prev = [FLOOR], "floor"
        for k in range(rng.choice([2, 3])):
            x, y, z = rng.uniform(0.3, 0.7), rng.uniform(0.3, 0.7), rng.uniform(0.25, 0.8)
            rot = rng.choice([0, 0, rng.uniform(0, 90)])
            at = "" if k == 0 or rng.random() < 0.4 else " at %.3f %.3f" % (rng.uniform(-0.08, 0.08),
                                                                           rng.uniform(-0.08, 0.08))
            lines.append(f"block create brick size {x:.3f} {y:.3f} {z:.3f} seat-on {prev}{at} name b{k} "
                         f"density 2600 rotation 0 0 {rot:.2f}")
            prev = f"b{k}"
        amp, d = rng.choice([0.15, 0.3, 0.5, 0.8]), rng.uniform(0, 90)
        lines += [f"ground-motion pulse one-sine amplitude {amp}g frequency {rng.choice([1, 2, 3])} direction {d:.1f}",
                  "model solve time 2.5", "output hdf5 'x.h5' interval 0.01"]
        yield "q%02d" % i, "\n".join(lines)


def main():
    rockdem = sys.argv[1] if len(sys.argv) > 1 else "bin/rockdem"
    untrusted, worst = 0, 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in list(pedestal_scenes()) + list(stack_scenes()):
            dat, h5 = os.path.join(tmp, name + ".dat"), os.path.join(tmp, name + ".h5")
            with open(dat, "w") as f:
                f.write(text + "\n")
            rc = subprocess.run([rockdem, "run", dat, "-q", "-o", h5], stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL).returncode
            with h5py.File(h5, "r") as f:
                r = float(f["summary"].attrs["energy_residual_max"])
            print("%s exit %d residual %.2e" % (name, rc, r), flush=True)
            if rc == 3:
                untrusted += 1
            else:
                worst = max(worst, r)
    print("untrusted %d of 70; largest residual of the others %.2e" % (untrusted, worst))


if __name__ == "__main__":
    main()
