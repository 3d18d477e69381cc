#!/usr/bin/python3
"""Overturning threshold of a one-sine scene by bisection on the pulse amplitude, for scenes that
`rockdem threshold` cannot map onto its rigid reference (a mesh block): each run is
`rockdem run SCENE --set motion.amplitude=Ag`, overturned when its status line says so.
The bracket [LO, HI] g must hold the threshold (a run at LO stands, one at HI overturns); the
answer is the bracket's midpoint after N halvings (its half-width is printed with it). It
assumes one crossing in the bracket (`rockdem threshold` scans first for that reason).

usage: tools/threshold_bisect.py BIN SCENE [LO HI N]
"""
import subprocess
import sys
import tempfile


def overturned(binary, scene, a):
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run([binary, "run", scene, "--set", "motion.amplitude=%.6gg" % a, "--set",
                              "output.file=%s/x.h5" % tmp], capture_output=True, text=True)
    text = out.stdout + out.stderr
    if "status overturned" in text:
        return True
    if "status done" in text:
        return False
    sys.exit("run at %.4g g: %s" % (a, text.strip().splitlines()[-1] if text.strip() else out.returncode))


def main():
    binary, scene = sys.argv[1], sys.argv[2]
    lo, hi, n = (float(sys.argv[3]), float(sys.argv[4]), int(sys.argv[5])) if len(sys.argv) > 5 else (0.5, 1.6, 8)
    if overturned(binary, scene, lo) or not overturned(binary, scene, hi):
        sys.exit("the bracket [%g, %g] g does not hold the threshold" % (lo, hi))
    for _ in range(n):
        mid = 0.5 * (lo + hi)
        if overturned(binary, scene, mid):
            hi = mid
        else:
            lo = mid
    print("%s: threshold %.4f g (+- %.4f)" % (scene, 0.5 * (lo + hi), 0.5 * (hi - lo)))


if __name__ == "__main__":
    main()
