#!/usr/bin/python3
"""rdfragility — overturning fragility from many runs: (1) logistic regression on PGA within
PGV/PGA bins (seed 002 eq. 3), (2) a 2-D logistic surface logit P = c0 + c1 ln PGA + c2 ln(PGV/PGA)
with its 10/50/95 % contours, (3) a lognormal fragility in PGA (median, beta) by maximum
likelihood with 95 % bands (Fisher information, or --bootstrap N), (4) accuracy, precision,
recall and F1 of the simulated outcome against an observed column (seed 002 Table 4).
Inputs: the CSV of rdtable.py --csv, a sweep HDF5 (/sweep with fields pga, pgv, overturned), or
rockdem run files; SI units in (m/s^2, m/s).
Subcommands: `rdfragility planes` (intensity planes per direction, rose, modes, normalised axes),
`rdfragility select` (records from a flatfile), `rdfragility calibrate` (fit contact parameters
to observed outcomes); each has --help."""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rdtools import cli, RDError  # noqa: E402

G = 9.80665


def num(v):
    return None if v is None or (isinstance(v, float) and not math.isfinite(v)) else v


SUBCOMMANDS = ("planes", "select", "calibrate")


def main():
    if len(sys.argv) > 1 and sys.argv[1] in SUBCOMMANDS:
        import importlib
        mod = importlib.import_module("rdtools.%s_cli" % sys.argv[1])
        return mod.main(sys.argv[2:])
    p = cli.Parser(prog="rdfragility", description=cli.describe(__doc__))
    p.add_argument("inputs", nargs="+", metavar="TABLE.csv|SWEEP.h5|RUN.h5")
    p.add_argument("-o", "--output", metavar="OUT.png", help="figure: surface with contours, "
                   "binned fits, lognormal fit (default: none)")
    p.add_argument("--json", metavar="OUT.json", help="write all results as JSON")
    p.add_argument("--bins", type=int, default=4, metavar="N",
                   help="number of PGV/PGA bins, equal counts (default 4)")
    p.add_argument("--bin-edges", metavar="T0,T1,...", help="PGV/PGA bin edges in s (overrides --bins)")
    p.add_argument("--form", choices=("linear", "log"), default="linear",
                   help="binned model: linear = seed 002 eq. 3, b0 + b1 PGA (default); log = b0 + b1 ln PGA")
    p.add_argument("--method", choices=("auto", "ml", "firth"), default="auto",
                   help="logistic estimator: ml, firth, or auto = ML unless the data are separated (default)")
    p.add_argument("--units", choices=("g", "si"), default="g",
                   help="PGA unit of the report, coefficients and figure (g, default; si = m/s^2)")
    p.add_argument("--observed", metavar="COL", default="auto",
                   help="column with the observed outcome (0/1) for the metrics (default: 'observed' if present)")
    p.add_argument("--outcome", metavar="COL", default="overturned",
                   help="0/1 column taken as the simulated outcome (default overturned; "
                        "ever_overturned counts a body that fell and tumbled on)")
    p.add_argument("--body", metavar="NAME", help="use only the rows of this body")
    p.add_argument("--where", metavar="COL=VALUE", action="append",
                   help="use only the rows whose column COL equals VALUE (sweep tables and CSVs; "
                        "repeatable), e.g. --where direction=0")
    p.add_argument("--bootstrap", type=int, default=0, metavar="N",
                   help="lognormal 95 %% bands from N bootstrap resamples instead of the Fisher information")
    a = p.parse_args()

    import numpy as np
    from rdtools import fragility as F
    from rdtools.fraginput import load, arrays, select

    edges = None
    if a.bin_edges:
        try:
            edges = [float(x) for x in a.bin_edges.split(",")]
        except ValueError:
            p.error("--bin-edges: expected numbers separated by commas")
        if len(edges) < 2:
            p.error("--bin-edges: need at least two edges")
    if a.bins < 1:
        p.error("--bins must be >= 1")
    for out in (a.output, a.json):
        if out:
            cli.ensure_writable(out)

    rows = select(load(a.inputs, a.observed, a.body, a.outcome), a.where)
    from rdtools.planes import row_levels, interval
    level = row_levels(rows)
    pga_si, pgv, y, obs, ok = arrays(rows)
    if (~ok).any():
        sys.stderr.write("rdfragility: warning: %d rows without a positive finite pga/pgv skipped\n"
                         % int((~ok).sum()))
    pga_si, pgv, y, level = pga_si[ok], pgv[ok], y[ok], level[ok]
    obs = obs[ok] if obs is not None else None
    if len(y) < 3:
        raise RDError("need at least 3 runs with pga, pgv > 0 (got %d)" % len(y))
    scale = G if a.units == "g" else 1.0
    ustr = "g" if a.units == "g" else "m/s^2"
    pga = pga_si / scale
    T = pgv / pga_si  # s (PGV/PGA in SI)

    res = dict(n=int(len(y)), n_overturned=int(y.sum()), pga_unit=ustr, inputs=a.inputs)
    o = sys.stdout
    o.write("runs: %d, overturned: %d; PGA %.4g-%.4g %s, PGV/PGA %.4g-%.4g s\n"
            % (len(y), y.sum(), pga.min(), pga.max(), ustr, T.min(), T.max()))

    # (1) binned fits (seed 002 eq. 3)
    bins = F.binned_fits(pga, pgv / scale, y, a.bins, edges, a.form, a.method)
    form = "b0 + b1*PGA" if a.form == "linear" else "b0 + b1*ln(PGA)"
    o.write("\n(1) binned logistic, P = 1/(1+exp(-(%s))), PGA in %s, per PGV/PGA bin:\n" % (form, ustr))
    o.write("  %-17s %5s %5s %8s %10s %10s %8s  %9s %9s %9s\n" % (
        "PGV/PGA bin (s)", "n", "over", "median", "b0", "b1", "method", "PGA10%", "PGA50%", "PGA95%"))
    for d in bins:
        if "b0" in d:
            # a linear-PGA logistic can put a low quantile below PGA 0: say so, not nan
            at = ["%9.4g" % x if x == x else "%9s" % "<0" for x in (d["pga_at"][q] for q in F.LEVELS)]
            o.write("  %7.4g-%-9.4g %5d %5d %8.4g %10.4g %10.4g %8s  %s %s %s%s\n" % (
                d["lo"], d["hi"], d["n"], d["n_over"], d["T_median"], d["b0"], d["b1"], d["method"],
                *at, ("  " + d["note"]) if "note" in d else ""))
        else:
            o.write("  %7.4g-%-9.4g %5d %5d %8.4g  (%s)\n" % (d["lo"], d["hi"], d["n"], d["n_over"],
                                                            d["T_median"], d["note"]))
    res["binned"] = [{k: (num(v) if not isinstance(v, dict) else {str(q): num(x) for q, x in v.items()})
                      for k, v in d.items()} for d in bins]

    # (2) surface
    surf, why = None, "all runs have the same outcome"
    if 0 < y.sum() < len(y):
        try:
            surf = F.surface_fit(pga, pgv / scale, y, a.method)
        except F.DegenerateInput as e:
            why = str(e)
    if surf is not None:
        c, se = surf["beta"], surf["se"]
        o.write("\n(2) surface: logit P = c0 + c1 ln PGA[%s] + c2 ln(PGV/PGA[s])  (%s%s)\n"
                % (ustr, surf["method"], ", data separated" if surf["separated"] else ""))
        for i in range(3):
            o.write("  c%d = %10.5g  +- %.3g (1 s.e.)\n" % (i, c[i], se[i]))
        Tq = np.quantile(T, [0.1, 0.5, 0.9])
        for q in F.LEVELS:
            o.write("  PGA at P = %2.0f %%: %s\n" % (100 * q, ", ".join(
                "%.4g %s at T=%.3g s" % (x, ustr, t) for x, t in zip(F.surface_contour(surf, q, Tq), Tq))))
        res["surface"] = dict(c=[float(x) for x in c], se=[float(x) for x in se],
                              method=surf["method"], separated=surf["separated"])
        m = F.metrics(*F.confusion(F.surface_prob(surf, pga, T) >= 0.5, y))
        o.write("  in-sample classification (P >= 0.5 vs simulated): accuracy %.4f, F1 %.4f\n"
                % (m["accuracy"], m["F1"]))
        res["surface"]["in_sample"] = {k: num(v) for k, v in m.items()}
    else:
        o.write("\n(2) surface: not fitted: %s\n" % why)
        res["surface"] = dict(fitted=False, reason=why)

    # (3) lognormal
    try:
        ln = F.lognormal_fit(pga, y, bootstrap=a.bootstrap)
    except F.DegenerateInput as e:
        ln = dict(separated=None, note=str(e))
    o.write("\n(3) lognormal fragility in PGA, P = Phi(ln(PGA/theta)/beta), probit GLM (statsmodels):\n")
    if ln["separated"] is None:
        o.write("  not fitted: %s\n" % ln["note"])
        res["lognormal"] = dict(fitted=False, reason=ln["note"])
    elif ln["separated"]:
        o.write("  %s: theta in [%.4g, %.4g] %s\n" % (ln["note"], *ln["theta_range"], ustr))
        res["lognormal"] = dict(separated=True, theta_range=list(ln["theta_range"]), note=ln["note"])
        if ln.get("firth") is not None:
            fb, fse = ln["firth"]["beta"], ln["firth"]["se"]
            o.write("  Firth's logistic in ln PGA instead: logit P = %.4g + %.4g ln PGA (s.e. %.3g, %.3g); "
                    "median %.4g %s\n" % (fb[0], fb[1], fse[0], fse[1], math.exp(-fb[0] / fb[1]), ustr))
            res["lognormal"]["firth"] = dict(b=[float(x) for x in fb], se=[float(x) for x in fse],
                                             median=math.exp(-fb[0] / fb[1]))
    else:
        o.write("  theta (median) = %.4g %s  95%% CI [%.4g, %.4g]  (s.e. of ln theta %.3g)\n"
                % (ln["theta"], ustr, *ln["theta_ci"], ln["se_ln_theta"]))
        o.write("  beta = %.4g  95%% CI [%.4g, %.4g]  (s.e. %.3g)\n"
                % (ln["beta"], *ln["beta_ci"], ln["se_beta"]))
        o.write("  bands: %s\n" % ("Fisher information (expected), delta method, pointwise 95 %"
                                   if ln["band_method"] == "fisher" else
                                   "scipy.stats.bootstrap, paired rows, percentiles (%s)" % ln["band_method"]))
        res["lognormal"] = dict(separated=False, theta=ln["theta"], beta=ln["beta"],
                                se_ln_theta=ln["se_ln_theta"], se_beta=ln["se_beta"],
                                theta_ci=list(ln["theta_ci"]), beta_ci=list(ln["beta_ci"]),
                                band_method=ln["band_method"])

    # (5 in the JSON: levels) the fraction overturned per PGA level (the sweep's scale index)
    res["levels"] = []
    for L in np.unique(level):
        m = level == L
        lo, hi = interval(y[m].sum(), m.sum())
        res["levels"].append(dict(pga=float(np.exp(np.log(pga[m]).mean())), n=int(m.sum()),
                                  k=int(y[m].sum()), ci=[float(lo), float(hi)]))
    o.write("\nfraction overturned per PGA level (%s; Wilson 95 %%, statsmodels):\n  %s\n" % (
        "the sweep's scale index" if len(a.inputs) == 1 and a.inputs[0].lower().endswith((".h5", ".hdf5"))
        else "equal values", "; ".join("%.4g %s: %d/%d" % (d["pga"], ustr, d["k"], d["n"])
                                        for d in res["levels"])))

    # (4) metrics
    if obs is not None:
        m = F.metrics(*F.confusion(y, obs))
        o.write("\n(4) simulated vs observed (positive = overturned): TP %d TN %d FP %d FN %d\n"
                "  accuracy %.6f  precision %.6f  recall %.6f  F1 %.6f\n"
                % (m["TP"], m["TN"], m["FP"], m["FN"], m["accuracy"], m["precision"], m["recall"], m["F1"]))
        res["metrics"] = {k: num(v) for k, v in m.items()}
    else:
        o.write("\n(4) metrics: no observed column (give --observed COL)\n")

    if a.output:
        from rdtools.fragplot import plot_fragility
        plot_fragility(a.output, pga, T, y, bins, surf, ln, ustr, a.form, level=level)
        o.write("\nwrote %s\n" % a.output)
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(res, fh, indent=1, default=float)
        o.write("wrote %s\n" % a.json)


if __name__ == "__main__":
    sys.exit(cli.run(main, "rdfragility"))
