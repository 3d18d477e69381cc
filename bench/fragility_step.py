#!/usr/bin/env python3
"""The table of bench/fragility_step.sh: sweep tables of one study sample at several settings
(the first the reference, the second the default), compared run by run and by their fitted
lognormal fragilities. Each TABLE.h5 has a NAME.cpu beside it (the sweep's CPU s)."""
import os
import sys
import warnings

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from rdtools.fragility import lognormal_fit  # noqa: E402  (rdfragility's probit GLM)

G = 9.80665
ENERGY_BOUND, TRUST = 1e-3, 1e-2  # the tests' energy bound; the run's own trust limit
SIDES = (("thin side (0, 180 deg)", (0, 180)), ("long side (90, 270 deg)", (90, 270)))
BOOT = 400  # bootstrap resamples of the records


def load(path):
    with h5py.File(path, "r") as f:
        s = f["sweep"]
        d = dict(over=s["overturned"][:].astype(bool), pga=s["pga"][:] / G,
                 direction=np.round(s["direction"][:]).astype(int) % 360,
                 seed=s["motion.seed"][:], residual=s["energy_residual"][:])
    cpu = os.path.splitext(path)[0] + ".cpu"
    d["cpu"] = float(open(cpu).read()) if os.path.exists(cpu) else float("nan")
    d["name"] = os.path.splitext(os.path.basename(path))[0]
    # the run's place in the study: record, direction (rounded: a turned sweep's 0.01 deg
    # matches its plain one) and level
    d["key"] = list(zip(d["seed"], d["direction"], np.round(d["pga"], 4)))
    return d


def lognormal(pga, over):
    """Median (g) and beta of P(overturn) = Phi(ln(pga / median) / beta) (rdfragility's maximum
    likelihood fit); NaN where the outcomes are separated in PGA (no finite estimate)."""
    r = lognormal_fit(pga, over.astype(float))
    return float(r["theta"]), float(r["beta"])


def fit(d, dirs, rng):
    sel = np.isin(d["direction"], dirs)
    med, beta = lognormal(d["pga"][sel], d["over"][sel])
    groups = sorted(set(zip(d["seed"][sel], d["direction"][sel])))
    rows = {g: np.where(sel & (d["seed"] == g[0]) & (d["direction"] == g[1]))[0] for g in groups}
    boot = []
    for _ in range(BOOT):
        pick = rng.integers(0, len(groups), len(groups))
        m = np.concatenate([rows[groups[i]] for i in pick])
        boot.append(lognormal(d["pga"][m], d["over"][m])[0])
    lo, hi = np.nanpercentile(boot, [2.5, 97.5])  # a separated resample has no median
    return med, beta, lo, hi


def flips(d, ref):
    at = {k: i for i, k in enumerate(ref["key"])}
    if set(at) != set(d["key"]):
        sys.exit("bench/fragility_step.py: %s and %s hold different runs" % (d["name"], ref["name"]))
    idx = np.array([at[k] for k in d["key"]])
    return int((d["over"] != ref["over"][idx]).sum())


def main(paths):
    # a bootstrap resample near separation makes statsmodels warn of log(0); its fit still counts
    warnings.filterwarnings("ignore", category=RuntimeWarning)
    if len(paths) < 2:
        sys.exit("usage: fragility_step.py REFERENCE.h5 DEFAULT.h5 [OTHER.h5 ...]")
    tables = [load(p) for p in paths]
    ref, default = tables[0], tables[1]
    n = len(ref["over"])
    print("| setting | outcome differs from %s | from %s | overturned | residual > 1e-3 | "
          "> 1e-2 (untrusted) | CPU s per run | %s: median g (95 %%), beta | %s: median g "
          "(95 %%), beta |" % (ref["name"], default["name"], SIDES[0][0], SIDES[1][0]))
    print("|---|---|---|---|---|---|---|---|---|")
    for d in tables:
        rng = np.random.default_rng(1)  # the same resamples for every setting
        cells = [d["name"], "%d / %d" % (flips(d, ref), n), "%d / %d" % (flips(d, default), n),
                 "%d" % d["over"].sum(), "%d" % (d["residual"] > ENERGY_BOUND).sum(),
                 "%d" % (d["residual"] > TRUST).sum(), "%.2f" % (d["cpu"] / n)]
        for _, dirs in SIDES:
            med, beta, lo, hi = fit(d, dirs, rng)
            cells.append("%.3f (%.3f-%.3f), %.2f" % (med, lo, hi, beta))
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
