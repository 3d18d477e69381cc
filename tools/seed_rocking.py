#!/usr/bin/python3
"""Free-rocking figures of a rockdem run, per free body: the time of each impact and the
coefficient of restitution of each impact, r_n = w_(n+1) / w_n, the ratio of the angular
speeds just before two successive impacts (for free rocking between impacts this equals
sqrt(E_(n+1) / E_n) of successive kinetic-energy maxima, seed 001's definition).

usage: /usr/bin/python3 tools/seed_rocking.py RUN.h5 [--impacts N]
Reads /events (layout 2: columns time, body, type enum, value = angular speed before impact)."""
import argparse

import h5py
import numpy as np


def impacts(path):
    """{body: [(time s, angular speed before rad/s), ...]} from the run's impact events."""
    with h5py.File(path, "r") as f:
        e = f["events"]
        kinds = h5py.check_enum_dtype(e["type"].dtype)
        impact = kinds["impact"]
        out = {}
        for t, b, k, v in zip(e["time"][()], e["body"][()], e["type"][()], e["value"][()]):
            if k == impact:
                out.setdefault(b.decode() if isinstance(b, bytes) else b, []).append((t, v))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("--impacts", type=int, default=5, help="impacts to list (default 5)")
    a = ap.parse_args()
    for body, imp in impacts(a.run).items():
        t = np.array([x for x, _ in imp])[: a.impacts]
        w = np.array([y for _, y in imp])[: a.impacts + 1]
        r = w[1:] / w[:-1]
        print("%s: impacts at %s s; r per impact %s" % (
            body, ", ".join("%.3f" % x for x in t), ", ".join("%.3f" % x for x in r)))


if __name__ == "__main__":
    main()
