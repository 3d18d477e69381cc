"""`rdfragility planes`: fragility over intensity planes and directions, the direction rose of
the median capacity, the response modes, and Purvance's normalised axes (docs/FRAGILITY.md)."""
import json
import sys

import numpy as np

from . import cli, RDError
from . import planes as P

DEFAULT_PAIRS = "pga:pgv,pga:pgd,pgv:pgd,pga:duration"


def _pairs(text):
    out = []
    for item in text.split(","):
        a, sep, b = item.partition(":")
        if not sep:
            raise RDError("--pairs: expected X:Y[,X:Y...], got '%s'" % item)
        out.append((P.im_name(a), P.im_name(b)))
    return out


def _num(v):
    return None if v is None or (isinstance(v, float) and not np.isfinite(v)) else v


def _jsonable(res):
    def conv(o):
        if isinstance(o, dict):
            return {str(k): conv(v) for k, v in o.items() if not callable(v)}
        if isinstance(o, (list, tuple)):
            return [conv(v) for v in o]
        if isinstance(o, np.ndarray):
            return conv(o.tolist())
        if isinstance(o, (np.floating, float)):
            return _num(float(o))
        if isinstance(o, np.integer):
            return int(o)
        if isinstance(o, np.bool_):
            return bool(o)
        return o
    return conv(res)


def main(argv):
    p = cli.Parser(prog="rdfragility planes", description=cli.describe(__doc__))
    p.add_argument("inputs", nargs="+", metavar="SWEEP.h5|TABLE.csv")
    p.add_argument("--pairs", default=DEFAULT_PAIRS, metavar="X:Y,...",
                   help="intensity planes (columns pga, pgv, pgd, pgv_pga, arias, d5_95 = duration, "
                        "sa_0_2, sa_1; pga_n, pgvpga_n with --geometry); default " + DEFAULT_PAIRS)
    p.add_argument("--by", default="direction", metavar="COL",
                   help="one panel and one rose point per value of this column (default direction)")
    p.add_argument("--geometry", metavar="RUN.h5",
                   help="a rockdem run file of the scene: alpha(direction) and p for the normalised "
                        "axes pga_n = PGA/(g tan alpha), pgvpga_n = p PGV/PGA")
    p.add_argument("--body", metavar="NAME", help="the body of --geometry (default the first free one)")
    p.add_argument("--outcome", default="overturned", metavar="COL", help="0/1 outcome column")
    p.add_argument("--where", action="append", metavar="COL=VALUE", help="keep rows (repeatable)")
    p.add_argument("--xbins", type=int, default=6, metavar="N",
                   help="x bins where x is not the sweep's scaled PGA (default 6)")
    p.add_argument("--ybins", type=int, default=5, metavar="N", help="y bins (default 5)")
    p.add_argument("--method", choices=("auto", "ml", "firth"), default="auto",
                   help="logistic estimator (auto: ML unless the outcomes separate, then Firth)")
    p.add_argument("--units", choices=("g", "si"), default="g", help="PGA in the figures")
    p.add_argument("-o", "--output", metavar="PREFIX",
                   help="figures PREFIX_<x>_<y>, PREFIX_rose, PREFIX_modes (.png 300 dpi and .pdf)")
    p.add_argument("--json", metavar="OUT.json", help="all results as JSON")
    a = p.parse_args(argv)
    if a.xbins < 1 or a.ybins < 1:
        p.error("--xbins and --ybins must be >= 1")
    pairs = _pairs(a.pairs)
    if a.output:
        cli.ensure_writable(a.output + "_x")
    if a.json:
        cli.ensure_writable(a.json)
    t = P.table(a.inputs, a.where, a.outcome)
    if a.geometry:
        geo = P.geometry(a.geometry, a.body)
        P.normalised(t, geo)
    for x, y in pairs:
        for c in (x, y):
            if c not in t:
                raise RDError("the input has no column '%s'%s" % (
                    c, " (give --geometry RUN.h5)" if c in ("pga_n", "pgvpga_n") else
                    " (a sweep table from an older rockdem?)"))
    by = a.by if a.by in t else None
    if a.by != "direction" and by is None:
        raise RDError("no column '%s' for --by" % a.by)
    res = P.analyse(t, pairs, by, a.outcome, a.xbins, a.ybins, a.method)
    o = sys.stdout
    o.write("runs: %d, overturned: %d; PGA levels (sweep scale index): %d; groups by %s: %s\n"
            % (res["n"], res["k"], len(np.unique(t["level"])), by or "-",
               ", ".join("%g" % g for g in res["groups"]) if by else "all"))
    for key, per in res["planes"].items():
        x, y = key.split(":")
        o.write("\nplane %s x %s: logit P = c0 + c1 ln %s + c2 ln %s (SI units)\n" % (
            P.IMS[x][0], P.IMS[y][0], x, y))
        for d in per:
            g = "all" if d["group"] is None else "%g" % d["group"]
            c = d["cells"]
            if d["fit"] is None:
                o.write("  %s %-6s n %4d: no fit: %s\n" % (by or "", g, int(c["n"].sum()), d["why"]))
                continue
            f = d["fit"]
            o.write("  %s %-6s n %4d  c = %s  s.e. %s  (%s)\n" % (
                by or "", g, int(c["n"].sum()), " ".join("%9.4g" % v for v in f["beta"]),
                " ".join("%8.3g" % v for v in f["se"]), f["method"]))
    if "rose" in res:
        o.write("\nmedian PGA capacity per %s (logistic in ln PGA; 95 %% interval):\n" % by)
        for d, c in sorted(res["rose"].items()):
            o.write("  %7g  %s\n" % (d, _cap_text(c, P.G, "g")))
        if "rose_n" in res:
            o.write("median PGA/(g tan alpha) capacity per %s:\n" % by)
            for d, c in sorted(res["rose_n"].items()):
                o.write("  %7g  %s\n" % (d, _cap_text(c, 1.0, "")))
    md = res["modes"]
    if md is not None:
        o.write("\nresponse modes per PGA level (fraction of runs):\n  %-10s %s\n" % (
            "PGA (g)", " ".join("%10s" % m for m in md["modes"])))
        for j, L in enumerate(md["levels"]):
            o.write("  %-10.4g %s\n" % (md["pga"][j] / P.G, " ".join(
                "%10s" % ("%d/%d" % (md["k"][i][j], md["n"][j])) for i in range(len(md["modes"])))))
    if a.output:
        from . import planeplot as PP
        files = []
        for key in res["planes"]:
            files += PP.planes_figure(res, key, "%s_%s" % (a.output, key.replace(":", "_")),
                                      a.units == "g")
        if "rose" in res:
            files += PP.rose_figure(res, a.output + "_rose", a.units == "g")
        if md is not None:
            files += PP.modes_figure(res, a.output + "_modes", a.units == "g")
        o.write("\nwrote %s\n" % " ".join(files))
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(_jsonable(res), fh, indent=1)
        o.write("wrote %s\n" % a.json)
    return 0


def _cap_text(c, s, u):
    """One line for a direction's capacity (s: divisor of the PGA unit, u: its name)."""
    if c is None:
        return "no runs"
    if "median" in c:
        return "%.4g %s [%.4g, %.4g]  (%s, %d of %d fell)" % (
            c["median"] / s, u, c["ci"][0] / s, c["ci"][1] / s, c["method"], c["k"], c["n"])
    if c["bound"] == "above":
        return "none of %d runs fell: capacity above %.4g %s" % (c["n"], c["x_max"] / s, u)
    if c["bound"] == "below":
        return "all %d runs fell: capacity below %.4g %s" % (c["n"], c["x_min"] / s, u)
    return "no estimate (%s)" % c.get("note", "one PGA value")
