"""`rdfragility calibrate`: fit contact parameters (any --set key: contact.stiffness-normal,
contact.friction, contact.restitution, contact.interface-remove, ...) to observed overturning
outcomes by a search over one parallel `rockdem sweep` (its -j workers); reports the best set,
its 95 % likelihood-ratio uncertainty and the confusion table (docs/FRAGILITY.md)."""
import json
import os
import sys

from . import cli
from . import calibrate as C


def main(argv):
    p = cli.Parser(prog="rdfragility calibrate", description=cli.describe(__doc__))
    p.add_argument("scenario", metavar="SCENE.dat")
    p.add_argument("--observed", required=True, metavar="OBS.csv",
                   help="columns record (a file; or motion.record, a set id), scale (as --scales: "
                        "0.3g or a factor), direction (deg), overturned (yes/no, 1/0)")
    p.add_argument("--param", action="append", required=True, metavar="KEY=V1,V2,...",
                   help="a parameter and its candidate values (repeatable)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="fixed override for every run (repeatable)")
    p.add_argument("--objective", choices=("likelihood", "f1"), default="likelihood",
                   help="what the best set maximises (default likelihood)")
    p.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 1, help="sweep workers")
    p.add_argument("--table", metavar="TABLE.h5",
                   help="the sweep's table (default OUT.h5 with -o, else calibration.h5); an existing "
                        "one of the same sweep is resumed")
    p.add_argument("--rockdem", default=None, metavar="PATH", help="the rockdem binary")
    p.add_argument("-o", "--output", metavar="OUT", help="OUT.json with every grid point's scores")
    a = p.parse_args(argv)
    params = []
    for spec in a.param:
        key, sep, vals = spec.partition("=")
        if not sep or not key or not vals:
            p.error("--param: expected KEY=V1,V2,..., got '%s'" % spec)
        params.append((key.strip(), [v.strip() for v in vals.split(",")]))
    obs, rkey = C.read_observed(a.observed)
    axes = C.plan(obs, rkey, params)
    table = a.table or ((a.output + ".h5") if a.output else "calibration.h5")
    cli.ensure_writable(table)
    cmd = C.sweep_command(a.rockdem or C.default_rockdem(), a.scenario, axes, table, a.jobs, a.set)
    o = sys.stdout
    o.write("sweep: %s\n" % " ".join(cmd))
    o.flush()
    C.run_sweep(cmd)
    res = C.evaluate(table, axes, obs, len(params), a.objective)
    keys = [k for k, _ in params]
    o.write("\n%d observations; %d parameter sets; misclassification likelihood, 95 %% set: "
            "2 (l_max - l) <= %.3f (chi2, %d dof)\n" % (res["N"], len(res["grid"]), res["threshold"],
                                                        len(params)))
    o.write("  %s %10s %5s %8s  %s\n" % (" ".join("%14s" % k[-14:] for k in keys), "loglik",
                                       "miss", "F1", "in 95 % set"))
    for i, g in enumerate(res["grid"]):
        o.write("  %s %10.4f %5d %8.4f  %s%s\n" % (" ".join("%14s" % v for v in g), res["loglik"][i],
                                                  res["mismatches"][i], res["F1"][i],
                                                  "yes" if i in res["conf_set"] else "",
                                                  "  <- best" if i == res["best"] else ""))
    b = res["best"]
    tp, tn, fp, fn = res["confusion"][b]
    o.write("\nbest (%s): %s\n" % (res["objective"], ", ".join("%s = %s" % kv for kv in zip(keys, res["grid"][b]))))
    if len(res["tied"]) > 1:
        o.write("  tied with %d other sets\n" % (len(res["tied"]) - 1))
    for k in keys:
        lo, hi = res["ranges"][k][0], res["ranges"][k][-1]
        blo, bhi = res["brackets"][k][0], res["brackets"][k][-1]
        o.write("  %s: 95 %% set holds grid values %s to %s; uncertainty (to the excluded "
                "neighbours) (%s, %s)\n" % (k, lo, hi, blo, bhi))
    o.write("confusion (simulated vs observed, positive = overturned): TP %d TN %d FP %d FN %d\n"
            % (tp, tn, fp, fn))
    if a.output:
        with open(a.output + ".json", "w") as fh:
            json.dump(dict(res, keys=keys, command=cmd), fh, indent=1, default=float)
        o.write("wrote %s.json\n" % a.output)
    return 0
