#!/usr/bin/env python3
"""Drum columns as built: how many runs leave an energy residual above issue 10's 1e-3.

    /usr/bin/python3 bench/random_columns.py [BIN [N]]   (default bin/rockdem, 24; about 1 minute)

N columns drawn with a fixed seed (docs/CONTACT.md section 1, "Crossings that no vertex holds"):
3 to 5 drums (12, 16, 20 or 24 sides, circumradius 0.25-0.45 m, height 0.4-0.8 m) on a fixed
plinth, each turned by up to 3 degrees and set up to 5 mm off the drum below, as real drums are
laid; a 2 Hz one-sine of 0.05, 0.1, 0.2 or 0.35 g in a random direction, 2 s. Prints each run's
exit status and energy residual (summary energy_residual_max), then how many runs were untrusted
(exit 3) or above 1e-3, and the largest residual.
"""
import os
import random
import subprocess
import sys
import tempfile

import h5py


def scenes(n):
    rng = random.Random(11)
    for i in range(n):
        nd, sides = rng.choice([3, 4, 5]), rng.choice([12, 16, 20, 24])
        radius, height = rng.uniform(0.25, 0.45), rng.uniform(0.4, 0.8)
        amp, direction = rng.choice([0.05, 0.1, 0.2, 0.35]), rng.uniform(0, 90)
        lines = ["block create brick size 2.5 2.5 0.5 position 0 0 -0.25 fixed name plinth"]
        below = "plinth"
        for k in range(nd):
            turn, ox, oy = rng.uniform(-3, 3), rng.uniform(-0.005, 0.005), rng.uniform(-0.005, 0.005)
            lines.append(f"block create prism sides {sides} radius {radius:.3f} height {height:.3f} "
                         f"seat-on {below} at {ox:.4f} {oy:.4f} name d{k + 1} rotation 0 0 {turn:.2f}")
            below = f"d{k + 1}"
        lines += [f"ground-motion pulse one-sine amplitude {amp}g frequency 2 direction {direction:.1f}",
                  "model solve time 2", "output hdf5 'x.h5' interval 0.01"]
        yield "c%02d" % i, "\n".join(lines) + "\n"


def main():
    rockdem = sys.argv[1] if len(sys.argv) > 1 else "bin/rockdem"
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 24
    bad, worst = 0, 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in scenes(n):
            dat, h5 = os.path.join(tmp, name + ".dat"), os.path.join(tmp, name + ".h5")
            with open(dat, "w") as f:
                f.write(text)
            p = subprocess.run([rockdem, "run", dat, "-o", h5, "-q"], capture_output=True, text=True)
            if not os.path.exists(h5):
                print("%s: no output (exit %d): %s" % (name, p.returncode, p.stderr.strip()[-200:]))
                bad += 1
                continue
            with h5py.File(h5) as h:
                r = float(h["summary"].attrs["energy_residual_max"])
            worst = max(worst, r)
            bad += p.returncode == 3 or not r < 1e-3
            print("%s exit %d residual %.2e" % (name, p.returncode, r), flush=True)
    print("untrusted or above 1e-3: %d of %d; largest residual %.2e" % (bad, n, worst))


if __name__ == "__main__":
    main()
