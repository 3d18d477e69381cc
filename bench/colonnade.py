#!/usr/bin/env python3
"""A colonnade for rockdem: `colonnade.py [COLUMNS [DRUMS]]` prints a scenario of COLUMNS
free-standing drum columns (default 10) of DRUMS drums each (default 5: 50 drums), in a row
along x on one fixed stylobate, shaken across the row by a one-sine pulse that rocks them.

The drums are scenarios/column.dat's (marble, 0.8 m diameter, 0.9 m tall, 24 sides, 10 % taper,
its stone joint, beds sampled every 0.1 m), the columns 2.4 m (three diameters) apart, so no
two columns touch: the scene is many costly pairs (about 90 points a drum bed) and few bodies,
where a wall is many cheap pairs. Settling is cut at 0.02 s (the force ratio is still about
0.03 then, and rockdem warns so): a benchmark of the steps, not a study. Timed 1 vs 2 threads
in docs/PERFORMANCE.md."""
import sys

SPAN = 2.4  # axis-to-axis distance of the columns, m


def colonnade(columns=10, drums=5):
    length = (columns - 1) * SPAN + 3.0
    lines = ["; colonnade: %d columns of %d drums (bench/colonnade.py)" % (columns, drums),
             "model title 'colonnade, %d x %d drums, 2 Hz one-sine pulse'" % (columns, drums),
             "block create brick size %g 3 0.5 position %g 0 -0.25 fixed name stylobate"
             % (length, (columns - 1) * SPAN / 2)]
    for c in range(columns):
        lines.append("block create column drums %d diameter 0.8 height 0.9 sides 24 taper 0.9 "
                     "seat-on stylobate at %g 0 name col%d density 2700" % (drums, c * SPAN, c))
    lines += ["contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 37 spacing 0.1",
              "model damping viscous 0.1",
              "model settle time-limit 0.02",
              "ground-motion pulse one-sine amplitude 0.25g frequency 2 direction 90",
              "model solve time 0.5",
              ""]
    return "\n".join(lines)


if __name__ == "__main__":
    a = [int(x) for x in sys.argv[1:3]]
    sys.stdout.write(colonnade(*a))
