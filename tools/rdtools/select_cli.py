"""`rdfragility select`: draw records from a flatfile (NGA-West2 columns: record id, M, Rrup,
Vs30, mechanism, the AT2 file of each component) by ranges, write them as one record set the
sweep reads (both horizontals and the vertical where present), a scenario that imports it, and
print the `rockdem sweep` command that runs them."""
import os
import sys

from . import cli, RDError
from . import select as S


def main(argv):
    p = cli.Parser(prog="rdfragility select", description=cli.describe(__doc__))
    p.add_argument("flatfile", metavar="FLATFILE.csv")
    p.add_argument("--records-dir", metavar="DIR",
                   help="folder of the AT2 files (default: the flatfile's folder)")
    p.add_argument("--magnitude", metavar="LO:HI", help="moment magnitude range")
    p.add_argument("--rrup", metavar="LO:HI", help="closest distance to the rupture, km")
    p.add_argument("--vs30", metavar="LO:HI", help="Vs30, m/s")
    p.add_argument("--mechanism", metavar="M1,M2",
                   help="mechanisms kept: strike-slip, normal, reverse, reverse-oblique, normal-oblique")
    p.add_argument("-n", "--count", type=int, metavar="N", help="draw N records (default: all that pass)")
    p.add_argument("--seed", type=int, default=1, help="seed of the draw (default 1)")
    p.add_argument("--vertical", choices=("auto", "require", "off"), default="auto",
                   help="auto: the vertical is applied when every drawn record has one; require: "
                        "draw only records with a vertical; off: horizontals only")
    p.add_argument("--scenario", metavar="BASE.dat",
                   help="write OUT.dat: this scenario with its ground motion replaced by the set")
    p.add_argument("-o", "--output", required=True, metavar="OUT",
                   help="OUT.h5 (the record set), OUT.csv (the drawn records), OUT.dat (with --scenario)")
    a = p.parse_args(argv)
    if a.count is not None and a.count < 1:
        p.error("-n must be >= 1")
    cli.ensure_writable(a.output + ".h5")
    rows = S.read_flatfile(a.flatfile)
    ranges = {k: S.parse_range(v, name) for k, v, name in
              (("M", a.magnitude, "magnitude"), ("Rrup", a.rrup, "rrup"), ("Vs30", a.vs30, "vs30")) if v}
    mechs = None
    if a.mechanism:
        mechs = [m.strip().lower() for m in a.mechanism.split(",")]
        bad = [m for m in mechs if m not in S.MECHANISMS.values()]
        if bad:
            raise RDError("--mechanism: unknown '%s' (expected %s)" % (bad[0], ", ".join(S.MECHANISMS.values())))
    chosen = S.choose(rows, ranges, mechs, a.count, a.seed, a.vertical)
    base = a.records_dir or os.path.dirname(os.path.abspath(a.flatfile))
    with_v = S.write_set(chosen, a.output + ".h5", base, a.vertical)
    with open(a.output + ".csv", "w") as fh:
        fh.write("id,M,Rrup_km,Vs30_m_s,mechanism,h1,h2,vertical\n")
        for d in chosen:
            fh.write("%s,%g,%g,%g,%s,%s,%s,%s\n" % (d["id"], d["M"], d["Rrup"], d["Vs30"],
                                                   d["mechanism"], d["h1"], d["h2"], d["v"]))
    o = sys.stdout
    o.write("%d of %d records pass the filters; drew %d (seed %d); vertical %s\n" % (
        len(S.choose(rows, ranges, mechs, None, a.seed, a.vertical)), len(rows), len(chosen), a.seed,
        "applied (every drawn record has one)" if with_v else
        ("off" if a.vertical == "off" else "not applied: %d of %d drawn records lack one"
         % (sum(1 for d in chosen if not d["v"]), len(chosen)))))
    for d in chosen:
        o.write("  %-8s M %.2f  Rrup %6.1f km  Vs30 %5.0f m/s  %-15s %s\n" % (
            d["id"], d["M"], d["Rrup"], d["Vs30"], d["mechanism"], "h1 h2 v" if d["v"] else "h1 h2"))
    ids = ",".join(d["id"] for d in chosen)
    o.write("wrote %s.h5 %s.csv" % (a.output, a.output))
    scen = "SCENE.dat"
    if a.scenario:
        try:
            text = open(a.scenario).read()
        except OSError as e:
            raise RDError("%s: %s" % (a.scenario, e.strerror))
        with open(a.output + ".dat", "w") as fh:
            fh.write(S.scenario_text(text, os.path.dirname(os.path.abspath(a.scenario)),
                                     a.output + ".h5", chosen[0]["id"], with_v))
        scen = a.output + ".dat"
        o.write(" %s" % scen)
    o.write("\nrun them: rockdem sweep %s --axis motion.record=%s --scales ... --directions ... -o TABLE.h5\n"
            % (scen, ids))
    return 0
