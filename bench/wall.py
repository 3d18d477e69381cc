#!/usr/bin/env python3
"""A dry-stone wall for rockdem: `wall.py N [COURSES]` prints a scenario of about N bricks
(0.4 x 0.2 x 0.2 m granite, running bond: every other course shifted by half a brick, with
half bricks at its ends) laid
in COURSES courses (default 5) on a fixed footing, shaken by a small one-sine pulse.

The wall grows in length with N at a fixed height, so the contacts per brick, and so the cost
per brick per step, stay the same: bench/scale.sh times 50, 500 and 5,000 bricks with it."""
import sys

L, W, H = 0.4, 0.2, 0.2  # brick length, width, height, m


def wall(n, courses=5):
    per = max(2, round(n / courses))
    lines = ["; dry-stone wall: %d courses of %d bricks (bench/wall.py)" % (courses, per),
             "block create brick size %g %g 1 position %g 0 -0.5 fixed name footing"
             % (per * L + 2, W + 1, per * L / 2)]
    for c in range(courses):
        # running bond: every other course starts and ends with a half brick, so each joint
        # is covered by the brick above and no brick overhangs the end of the course below
        # (a quarter-brick overhang puts the centre of mass on the edge: alpha 0)
        parts = [L / 2] + [L] * (per - 1) + [L / 2] if c % 2 else [L] * per
        x = 0.0
        for k, length in enumerate(parts):
            lines.append("block create brick size %g %g %g position %.6g 0 %.6g name c%d-b%d"
                         % (length - 1e-3, W, H, x + length / 2, c * H + H / 2, c, k))
            x += length
    lines += ["contact property stiffness-normal 1e9 stiffness-shear 1e8 friction 35 spacing vertices",
              "model settle time-limit 0.05",
              "ground-motion pulse one-sine amplitude 0.05g frequency 5",
              "model solve time 0.02",
              ""]
    return "\n".join(lines)


if __name__ == "__main__":
    sys.stdout.write(wall(int(sys.argv[1]), int(sys.argv[2]) if len(sys.argv) > 2 else 5))
