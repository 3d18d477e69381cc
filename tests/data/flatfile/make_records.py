#!/usr/bin/python3
"""Writes the made-up flatfile and AT2 records of this folder (rockdem test data; no real
earthquake): 8 records, each 6 s at dt 0.01 s, two horizontal components and, for 5 of them, a
vertical one. Each component is seeded white noise band-passed around a dominant frequency
f0 (1.2-6 Hz, so PGV/PGA spans about 0.02-0.15 s) under a Saragoni-Hart-like envelope, in g.
The flatfile uses the NGA-West2 flatfile's column names. Run: /usr/bin/python3 make_records.py"""
import csv
import numpy as np
from scipy import signal

DT, DUR = 0.01, 6.0
# RSN, M, Rrup km, Vs30 m/s, mechanism (NGA-West2 code: 0 strike-slip, 1 normal, 2 reverse,
# 3 reverse-oblique, 4 normal-oblique), dominant frequency Hz, PGA g, vertical?
RECORDS = [
    (9001, 6.1, 12.0, 380.0, 0, 5.5, 0.25, True),
    (9002, 6.5, 8.5, 520.0, 2, 3.5, 0.35, True),
    (9003, 6.9, 22.0, 300.0, 0, 2.2, 0.20, False),
    (9004, 7.2, 15.0, 450.0, 3, 1.6, 0.30, True),
    (9005, 5.8, 30.0, 760.0, 1, 6.0, 0.10, False),
    (9006, 6.7, 5.0, 270.0, 2, 2.8, 0.45, True),
    (9007, 7.0, 40.0, 600.0, 0, 1.2, 0.15, False),
    (9008, 6.3, 18.0, 350.0, 4, 4.2, 0.22, True),
]


def component(seed, f0, pga):
    rng = np.random.default_rng(seed)
    n = int(round(DUR / DT))
    t = np.arange(n) * DT
    sos = signal.butter(2, [0.6 * f0, 1.6 * f0], btype="bandpass", fs=1.0 / DT, output="sos")
    a = signal.sosfiltfilt(sos, rng.standard_normal(n))
    env = (t / 1.2) ** 2 * np.exp(2.0 * (1.0 - t / 1.2))   # peak at 1.2 s
    a *= env
    return a * pga / np.abs(a).max()


def write_at2(path, rsn, comp, a):
    with open(path, "w") as fh:
        fh.write("PEER NGA STRONG MOTION DATABASE RECORD\n")
        fh.write("Made-up record RSN%d component %s (rockdem test data, not a real earthquake)\n"
                 % (rsn, comp))
        fh.write("ACCELERATION TIME SERIES IN UNITS OF G\n")
        fh.write("NPTS=%6d, DT=%8.4f SEC\n" % (len(a), DT))
        for i in range(0, len(a), 5):
            fh.write("".join("%15.7E" % v for v in a[i:i + 5]) + "\n")


def main():
    rows = []
    for rsn, M, rrup, vs30, mech, f0, pga, vert in RECORDS:
        names = {}
        for j, comp in enumerate(("H1", "H2", "V")):
            if comp == "V" and not vert:
                names[comp] = ""
                continue
            scale = 1.0 if comp == "H1" else 0.8 if comp == "H2" else 0.5
            a = component(rsn * 10 + j, f0 * (1.0 if comp != "V" else 1.8), pga * scale)
            names[comp] = "RSN%d_%s.AT2" % (rsn, comp)
            write_at2(names[comp], rsn, comp, a)
        rows.append({"Record Sequence Number": rsn, "Earthquake Name": "Made-up %d" % rsn,
                     "Earthquake Magnitude": M, "Mechanism Based on Rake Angle": mech,
                     "ClstD (km)": rrup, "Vs30 (m/s) selected for analysis": vs30,
                     "File Name (Horizontal 1)": names["H1"],
                     "File Name (Horizontal 2)": names["H2"],
                     "File Name (Vertical)": names["V"]})
    with open("flatfile.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
