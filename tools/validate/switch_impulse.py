#!/usr/bin/python3
"""Energy a point mass keeps when it bounces once on a compression-only linear spring, integrated
by leapfrog as rockdem's contact loop does, with the spring's force at t(n) or with its mean force
over the step (engine/law.h rd_law_switch_stretch). Touches are spread evenly over a step. Second
table: what the touch step takes from leapfrog's conserved energy of the bearing spring (a point
that touches and stays keeps it; a bounce gets it back at the let-go).

    /usr/bin/python3 tools/validate/switch_impulse.py        (the table of docs/CONTACT.md section 6)

Units: mass 1, stiffness 1 (omega = 1), approach speed 1; x > 0 is the gap, the stretch is -x.
"""
import numpy as np


def mean_stretch(s, w):
    """The mean of max(stretch, 0) over a step in which the stretch moves linearly through s by w."""
    if w <= 0 or s >= 0.5 * w:
        return max(s, 0.0)
    if s <= -0.5 * w:
        return 0.0
    return (s + 0.5 * w) ** 2 / (2.0 * w)


def bounce(dt, phase, mean):
    """Kinetic energy after the bounce over the energy before; phase in (0, 1): where in the step
    the touch falls."""
    v, x = -1.0, phase * dt        # v at t(n) - dt/2, x at t(n)
    for _ in range(100000):
        s = -x
        f = mean_stretch(s, abs(v) * dt) if mean else max(s, 0.0)
        v += f * dt
        x += v * dt
        if x > abs(v) * dt and v > 0:
            return v * v
    raise RuntimeError("no rebound")


def deepest(dt, phase, mean):
    """Leapfrog's conserved energy of the bearing spring, KE(n) + s(n)^2 / 2 with KE(n) = v(n-1/2)
    v(n+1/2) / 2, at the deepest point of the bounce, less the energy before (1/2): what the touch
    step changed, which a point that touches and stays keeps."""
    v, x = -1.0, phase * dt
    for _ in range(100000):
        s = -x
        f = mean_stretch(s, abs(v) * dt) if mean else max(s, 0.0)
        vn = v + f * dt
        if v < 0 <= vn:
            return 0.5 * v * vn + 0.5 * max(s, 0.0) ** 2 - 0.5
        v = vn
        x += v * dt
    raise RuntimeError("no turning point")


def spread(f, dt, mean, fmt):
    """f over touches spread evenly over a step, as "min - max"."""
    e = np.array([f(dt, p, mean) for p in np.linspace(0.001, 0.999, 400)])
    return (fmt + " - " + fmt) % (e.min(), e.max())


def main():
    print("| omega dt | force at t(n) | the step's mean force |")
    print("|---|---|---|")
    for dt in (0.1, 0.2, 0.4):
        print("| %g | %s | %s |" % (dt, spread(bounce, dt, False, "%.5f"), spread(bounce, dt, True, "%.5f")))
    print()
    print("energy change of the touch step (kept while the point bears), against -dt^2 / 8:")
    print("| omega dt | force at t(n) | the step's mean force | -dt^2 / 8 |")
    print("|---|---|---|---|")
    for dt in (0.1, 0.2, 0.4):
        print("| %g | %s | %s | %.3e |" % (dt, spread(deepest, dt, False, "%.3e"), spread(deepest, dt, True, "%.3e"),
                                          -dt * dt / 8))


if __name__ == "__main__":
    main()
