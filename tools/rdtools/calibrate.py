"""Calibration of contact parameters against observed overturning outcomes (a shake table's or
field evidence's table of record, scale, direction, overturned yes/no), by a search over one
`rockdem sweep` whose axes are the observed conditions and the candidate parameter values
(KN, friction angle, joint restitution, interface perturbation: any --set key).

Likelihood. A simulation is deterministic: for parameters theta it predicts s_i(theta) in {0, 1}
for observed condition i. The observation is modelled as the prediction flipped with an
unknown probability eps (misclassification: the shake table's repeatability, seed 002's
+-50 % overturning demand, lumps everything the model misses), so with m(theta) mismatches out
of N the profile log-likelihood (eps at its MLE m/N) is
    l(theta) = m ln(m/N) + (N - m) ln(1 - m/N)          (0 ln 0 = 0).
The estimate is the grid point of largest l (ties: all are reported, the first is taken); the
95 % confidence set is {theta : 2 (l_max - l(theta)) <= chi2_k(0.95)} (Wilks; k = number of
calibrated parameters), and each parameter's uncertainty is the span of its values over that
set. The grid resolves that set only to its spacing: the set's true edge lies between its
outermost grid value and the next grid value outside it, so the stated uncertainty of a
parameter is that bracket (open at an excluded neighbour). F1 (seed 002 Table 4) is reported for every grid point and can be the objective instead.
Outcomes are piecewise constant in theta, so a gradient optimiser has nothing to follow: the
search is over the sweep's grid (scipy.stats.chi2 gives the threshold)."""
import csv
import math
import os
import subprocess

import numpy as np
from scipy import stats

from . import RDError
from . import fragility as F
from .runfile import open_h5, as_str, enum_names

G = 9.80665


def read_observed(path):
    """Rows of the observed table: dicts record (text, or ''), scale (text as written),
    direction (text, or ''), observed (0/1). Columns: scale and overturned required; record
    (a file) or motion.record (a set id), direction optional."""
    from .fraginput import parse_bool
    try:
        fh = open(path, newline="")
    except OSError as e:
        raise RDError("%s: %s" % (path, e.strerror))
    with fh:
        r = csv.DictReader(fh)
        head = [h.strip() for h in (r.fieldnames or [])]
        for need in ("scale", "overturned"):
            if need not in head:
                raise RDError("%s: no '%s' column (expected record, scale, direction, overturned)"
                              % (path, need))
        rkey = "motion.record" if "motion.record" in head else "record" if "record" in head else None
        rows = []
        for i, row in enumerate(r, start=2):
            row = {k.strip(): (v or "").strip() for k, v in row.items() if k}
            if not row["scale"]:
                raise RDError("%s:%d: empty scale" % (path, i))
            rows.append(dict(record=row.get(rkey, "") if rkey else "", scale=row["scale"],
                             direction=row.get("direction", ""),
                             observed=parse_bool(row["overturned"], "%s:%d: overturned" % (path, i)),
                             line=i))
    if not rows:
        raise RDError("%s: no observations" % path)
    return rows, rkey


def _unique(seq):
    out = []
    for v in seq:
        if v not in out:
            out.append(v)
    return out


def plan(obs, rkey, params):
    """The sweep's axes: (flag, key, values) in the sweep's order (records, scales, directions,
    then the parameters as given)."""
    axes = []
    recs = _unique(r["record"] for r in obs)
    if any(recs):
        if not all(recs):
            raise RDError("some observations name a record and some do not")
        axes.append(("--records", "record", recs) if rkey == "record"
                    else ("--axis", "motion.record", recs))
    axes.append(("--scales", "scale", _unique(r["scale"] for r in obs)))
    dirs = _unique(r["direction"] for r in obs)
    if any(dirs):
        if not all(dirs):
            raise RDError("some observations give a direction and some do not")
        axes.append(("--directions", "direction", dirs))
    for key, vals in params:
        axes.append(("--axis", key, vals))
    return axes


def sweep_command(rockdem, scene, axes, out, jobs, sets=()):
    cmd = [rockdem, "sweep", scene]
    for flag, key, vals in axes:
        cmd += [flag, (key + "=" if flag == "--axis" else "") + ",".join(vals)]
    for s in sets:
        cmd += ["--set", s]
    return cmd + ["-j", str(jobs), "-q", "-o", out]


def run_sweep(cmd):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise RDError("the sweep failed (exit %d): %s" % (r.returncode, r.stderr.strip().splitlines()[-1]
                                                           if r.stderr.strip() else " ".join(cmd)))


def _value_indices(case, nvals):
    """Per axis, the value index of every case (the last axis varies fastest)."""
    case = np.asarray(case, np.int64)
    out = []
    inner = 1
    for n in reversed(nvals):
        out.append((case // inner) % n)
        inner *= n
    return out[::-1]


def evaluate(table_path, axes, obs, nparams, objective="likelihood", outcome="overturned"):
    """Score every parameter grid point against the observations. Returns dict: grid (list of
    value tuples), loglik, mismatches, F1, confusion per point; best (index), tied, conf_set
    (indices), ranges {key: (lo, hi)} over the confidence set, N, threshold."""
    f = open_h5(table_path, "sweep table")
    try:
        s = f["sweep"]
        case = s["case"][()]
        names = enum_names(s["status"].dtype)
        status = [names.get(int(v), str(v)) if names else as_str(v) for v in s["status"][()]]
        out = s[outcome][()].astype(float)
    finally:
        f.close()
    nvals = [len(v) for _, _, v in axes]
    if len(case) != int(np.prod(nvals)):
        raise RDError("%s: %d rows, the sweep has %d cases: run it to the end first"
                      % (table_path, len(case), int(np.prod(nvals))))
    idx = _value_indices(case, nvals)
    ncond = len(axes) - nparams
    # the simulated outcome at [condition axes..., parameter axes...]
    cube = np.full(nvals, np.nan)
    cube[tuple(idx)] = out
    if any(st not in ("done", "overturned") for st in status):
        bad = sum(1 for st in status if st not in ("done", "overturned"))
        raise RDError("%s: %d cases did not end as done/overturned (see its status column)"
                      % (table_path, bad))
    cond_keys = []
    for o in obs:
        k = []
        for flag, key, vals in axes[:ncond]:
            v = o["record"] if key in ("record", "motion.record") else o[key]
            k.append(vals.index(v))
        cond_keys.append(tuple(k))
    y = np.array([o["observed"] for o in obs], float)
    pgrid = [list(range(n)) for n in nvals[ncond:]]
    points = [tuple(p) for p in np.array(np.meshgrid(*pgrid, indexing="ij")).reshape(nparams, -1).T]
    N = len(y)
    res = dict(grid=[], loglik=[], mismatches=[], F1=[], confusion=[], N=N)
    for p in points:
        sim = np.array([cube[c + p] for c in cond_keys])
        m = int(np.sum(sim != y))
        ll = (m * math.log(m / N) if m else 0.0) + ((N - m) * math.log(1 - m / N) if m < N else 0.0)
        cf = F.confusion(sim, y)
        res["grid"].append(tuple(axes[ncond + j][2][i] for j, i in enumerate(p)))
        res["loglik"].append(ll)
        res["mismatches"].append(m)
        res["F1"].append(F.metrics(*cf)["F1"])
        res["confusion"].append(cf)
    score = np.array(res["loglik"] if objective == "likelihood" else
                     [v if v == v else -1.0 for v in res["F1"]])
    best = int(np.argmax(score))
    res["best"] = best
    res["tied"] = [int(i) for i in np.flatnonzero(score == score[best])]
    thr = float(stats.chi2.ppf(0.95, nparams))
    ll = np.array(res["loglik"])
    conf = [int(i) for i in np.flatnonzero(2 * (ll.max() - ll) <= thr)]
    res.update(threshold=thr, conf_set=conf, objective=objective)
    res["ranges"], res["brackets"] = {}, {}
    for j in range(nparams):
        key, allv = axes[ncond + j][1], axes[ncond + j][2]
        vals = [res["grid"][i][j] for i in conf]
        try:
            nums, grid = [float(v) for v in vals], sorted(float(v) for v in allv)
        except ValueError:
            res["ranges"][key] = res["brackets"][key] = tuple(sorted(set(vals)))
            continue
        lo, hi = min(nums), max(nums)
        res["ranges"][key] = (lo, hi)
        # the set's edge lies between its last grid value and the next one outside it
        below, above = [g for g in grid if g < lo], [g for g in grid if g > hi]
        res["brackets"][key] = (below[-1] if below else lo, above[0] if above else hi)
    return res


def default_rockdem():
    """$RD_BIN, else bin/rockdem of this checkout, else rockdem on PATH."""
    if os.environ.get("RD_BIN"):
        return os.environ["RD_BIN"]
    here = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                        "bin", "rockdem")
    return here if os.path.exists(here) else "rockdem"
