#!/usr/bin/python3
"""Regenerate the stored YADE results in tests/data/yade/ (needs `yade`): `make check-yade`.

    /usr/bin/python3 tools/yade/regen.py [--out DIR] [--jobs N] [--only CASE,...] [--no-half]

Each case runs YADE at the scenario's step (stored as <case>[-<amp>].h5) and, for the cases
marked `half`, again at half the step (stored as half/<case>[-<amp>].h5, slimmed the same way):
the comparison tolerances in tests/cli/yade_compare.sh are computed from how far YADE's own
answer moves when its step is halved (printed here as 'convergence'), so both files are kept.
"""
import argparse
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DATA = os.path.join(ROOT, "tests", "data", "yade")
PY = "/usr/bin/python3"

# (case, scenario, amplitudes (None = scenario's), halve-the-step check, extra translate args)
CASES = [
    ("free", "free.dat", [None], True, []),
    ("overturn", "overturn.dat", ["0.77g", "0.78g"], True, []),
    ("stack", "stack.dat", ["0.3g", "0.6g", "1.0g"], True, []),
    ("column", "column.dat", ["0.4g", "0.7g", "1.0g", "1.6g"], True, []),
    ("slide", "slide.dat", [None], True, []),
    ("creep", "creep.dat", [None], False, []),
    ("creep-nohook", "creep.dat", [None], False, ["--no-hook"]),
]


def name_of(case, amp):
    return case if amp is None else "%s-%s" % (case, amp.rstrip("g"))


def run_one(job):
    case, scen, amp, dt_factor, extra, out = job
    args = [PY, os.path.join(HERE, "translate.py"), os.path.join(DATA, scen), "-o", out, "-q"] + extra
    if amp:
        args += ["--set", "motion.amplitude=" + amp]
    if dt_factor != 1:
        args += ["--dt", str(5e-5 * dt_factor)]
    p = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode == 0:  # stored: slim it (about 1.4 MB for the whole set, dt and dt/2)
        stride = "1" if case in ("free", "slide") else "4"
        subprocess.run([PY, os.path.join(HERE, "slim.py"), "--stride", stride, out])
    return job, p.returncode, p.stdout


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=DATA)
    ap.add_argument("--jobs", type=int, default=max(1, os.cpu_count() or 1))
    ap.add_argument("--only")
    ap.add_argument("--no-half", action="store_true")
    a = ap.parse_args()
    half_dir = os.path.join(a.out, "half")
    os.makedirs(half_dir, exist_ok=True)
    only = set(a.only.split(",")) if a.only else None
    jobs = []
    for case, scen, amps, half, extra in CASES:
        if only and case not in only:
            continue
        for amp in amps:
            n = name_of(case, amp)
            jobs.append((case, scen, amp, 1, extra, os.path.join(a.out, n + ".h5")))
            if half and not a.no_half:
                jobs.append((case, scen, amp, 0.5, extra, os.path.join(half_dir, n + ".h5")))
    fails = 0
    with ThreadPoolExecutor(a.jobs) as ex:
        for job, rc, out in ex.map(run_one, jobs):
            print("%s (dt x %g): %s" % (os.path.basename(job[5]), job[3], "ok" if rc == 0 else "FAILED"))
            if rc:
                print(out[-2000:])
                fails += 1
    # convergence: stored (dt) vs half step
    cmp = os.path.join(HERE, "compare.py")
    for case, scen, amps, half, extra in CASES:
        if (only and case not in only) or not half or a.no_half:
            continue
        mode = {"free": "free", "slide": "slide"}.get(case, "outcome")
        for amp in amps:
            n = name_of(case, amp)
            print("== convergence %s: dt 5e-5 (A) vs 2.5e-5 (B)" % n)
            sys.stdout.flush()
            subprocess.run([PY, cmp, mode, os.path.join(a.out, n + ".h5"), os.path.join(half_dir, n + ".h5"),
                            "--tol-tilt", "1", "--tol", "1", "--tol-amp", "1", "--tol-time", "1"])
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
