#!/usr/bin/python3
"""Error against run time (DESIGN.md section 5, rung 4): each reference case is run with the
DEM at several KN, time-step safety factors and subcontact spacings, and with its rigid reference
(`rockdem reference`, CVODE); both write the same HDF5 layout. Error = max |tilt_DEM - tilt_ref|
over the run, relative to the reference's peak tilt (DEM tilts interpolated to the reference's
sample times); wall time = the DEM's shaking stage (its `perf:` line).
Usage: tools/study.py ROCKDEM OUTDIR   (writes OUTDIR/study.md and OUTDIR/study.png)
       tools/study.py --replot OUTDIR/study.md [--png PATH]   (redraws study.png from the table)"""
import os, re, subprocess, sys, tempfile
import h5py, numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

BASE = """block create brick size 4 4 1 position 0 0 -0.5 fixed name base
block create brick size 0.5 0.5 1.0 position 0 0 0.5 name b
{upper}contact preset rigid
{motion}
output hdf5 'x.h5' interval 0.002
"""
UPPER = "block create brick size 0.4 0.4 0.8 position 0 0 1.4 name upper\n"
CASES = [  # name, upper block, motion; the contact preset `rigid` (plastic point impacts, KS = 10 KN)
    # against the references' own impact laws (Housner's r, Kounadis' plastic impacts)
    ("free rocking, 1 block", "", "block initial name b tilt 13.28 direction 0\nmodel solve time 1.5"),
    ("one-sine 0.6 g 2.5 Hz, 1 block", "", "ground-motion pulse one-sine amplitude 0.6g frequency 2.5\nmodel solve time 1.5"),
    ("one-sine 0.5 g 2 Hz, stack", UPPER, "ground-motion pulse one-sine amplitude 0.5g frequency 2\nmodel solve time 1.0"),
]
KN = [1e8, 1e9, 1e10, 1e11]
SAFETY = [0.4, 0.2, 0.1]
SPACING = ["vertices", "0.1"]


def tilts(path):
    with h5py.File(path, "r") as f:
        return f["time"][:], f["tilt"][:]


def run(exe, scen, args, out):
    r = subprocess.run([exe, args[0], scen] + args[1:] + ["-o", out], capture_output=True, text=True)
    if r.returncode:
        sys.exit(f"{' '.join(args)} failed: {r.stderr.strip()}")
    m = re.search(r"wall_s=([0-9.eE+-]+)", r.stdout)
    return float(m.group(1)) if m else float("nan")


SAFETY_COLOUR = {0.4: "#1b9e77", 0.2: "#d95f02", 0.1: "#7570b3"}
SPACING_STYLE = {"vertices": ("o", "-"), "0.1": ("s", "--")}


def figure(rows, path):
    """A work-precision plot, one panel per case, sized for a two-column page: the error
    against the wall time, both logarithmic, so the best setting at a given cost is the lowest
    point above it. One colour per time-step safety factor, one marker and line style per
    subcontact spacing; each line joins KN 1e8 to 1e11, labelled at its points on the first
    line. The legend lies below the panels, over no data."""
    plt.rcParams.update({"font.size": 9, "legend.fontsize": 7.5, "axes.titlesize": 9})
    names = list(dict.fromkeys(r[0] for r in rows))
    fig, ax = plt.subplots(1, len(names), figsize=(7.2, 3.2), squeeze=False)
    for ci, name in enumerate(names):
        a = ax[0, ci]
        first = True
        for sf, col in SAFETY_COLOUR.items():
            for sp, (mk, ls) in SPACING_STYLE.items():
                pts = sorted((r[1], r[5], r[4]) for r in rows
                             if r[0] == name and float(r[2]) == sf and str(r[3]) == sp)
                if not pts:
                    continue
                kn, err, wall = zip(*pts)
                lab = "safety %g, spacing %s" % (sf, sp) if ci == 0 else None
                a.loglog(wall, err, marker=mk, ls=ls, color=col, ms=4, lw=1, label=lab)
                if first:   # which point is which KN, on one line of each panel
                    for k, e, w in zip(kn, err, wall):
                        a.annotate("KN %.0e" % k, (w, e), textcoords="offset points", xytext=(3, 3),
                                   fontsize=6, color="0.3")
                    first = False
        a.set_title(name)
        a.set_xlabel("wall time, shaking stage (s)")
        a.grid(True, which="major", alpha=0.3)
        a.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax[0, 0].set_ylabel("tilt error (1)\nmax |tilt − ref| / peak ref")
    fig.legend(loc="lower center", ncol=3, frameon=False, bbox_to_anchor=(0.5, -0.12))
    fig.suptitle("DEM against the rigid reference (CVODE): error against run time as KN "
                 "(1e8-1e11 Pa/m),\nthe time-step safety factor and the subcontact spacing vary",
                 fontsize=9)
    fig.tight_layout(rect=(0, 0.05, 1, 0.97))
    fig.savefig(path, dpi=300, bbox_inches="tight")
    plt.close(fig)


def read_table(md):
    """The rows of an earlier study.md (to redraw the figure without running again)."""
    rows = []
    for ln in open(md):
        c = [x.strip() for x in ln.strip().strip("|").split("|")]
        if len(c) == 6 and c[1][:1].isdigit():
            rows.append((c[0], float(c[1]), float(c[2]), c[3], float(c[4]), float(c[5])))
    return rows


def main():
    if len(sys.argv) in (3, 5) and sys.argv[1] == "--replot" and sys.argv[3:4] in ([], ["--png"]):
        md = sys.argv[2]
        png = sys.argv[4] if len(sys.argv) == 5 else os.path.join(os.path.dirname(md), "study.png")
        figure(read_table(md), png)
        print("redrew %s" % png)
        return
    if len(sys.argv) != 3 or sys.argv[1].startswith("-"):
        if sys.argv[1:2] in (["-h"], ["--help"]):
            print(__doc__)
            return
        sys.stderr.write("study: error: usage: tools/study.py ROCKDEM OUTDIR, or --replot "
                         "TABLE.md [--png PATH]\n")
        sys.exit(2)
    exe, outdir = sys.argv[1], sys.argv[2]
    tmp = tempfile.mkdtemp(prefix="rockdem_study_")
    rows = []
    for ci, (name, upper, motion) in enumerate(CASES):
        scen = os.path.join(tmp, f"case{ci}.dat")
        text = BASE.format(upper=upper, motion=motion)
        with open(scen, "w") as fh:
            fh.write(text)
        ref = os.path.join(tmp, f"ref{ci}.h5")
        subprocess.run([exe, "reference", scen, "-o", ref], check=True, capture_output=True)
        tr, thr = tilts(ref)
        peak = np.abs(thr).max()
        for kn in KN:
            for sf in SAFETY:
                for sp in SPACING:
                    out = os.path.join(tmp, "dem.h5")
                    wall = run(exe, scen, ["run", "--set", f"contact.stiffness-normal={kn}",
                                           "--set", f"contact.stiffness-shear={10 * kn}",
                                           "--set", f"model.safety={sf}",
                                           "--set", f"contact.spacing={sp}"], out)
                    td, thd = tilts(out)
                    tend = min(td[-1], tr[-1])
                    mask = tr <= tend
                    err = max(np.max(np.abs(np.interp(tr[mask], td, thd[:, j]) - thr[mask, j]))
                              for j in range(thr.shape[1])) / peak
                    rows.append((name, kn, sf, sp, wall, err))
    figure(rows, os.path.join(outdir, "study.png"))
    with open(os.path.join(outdir, "study.md"), "w") as fh:
        fh.write("# Error against run time\n\nGenerated by `make study` (tools/study.py): DEM vs the "
                 "CVODE rigid reference (`rockdem reference`, same HDF5 layout). Error = max |tilt_DEM - "
                 "tilt_ref| over the run / peak reference tilt; wall = DEM shaking stage. KS = KN, "
                 "friction 80 deg; spacing `vertices` = corner subcontacts, `0.1` = a bed of points "
                 "every 0.1 m. The figure shows the error against the wall time (work-precision), one "
                 "colour per time-step safety factor, one line style per spacing "
                 "(`tools/study.py --replot docs/study.md` redraws it from this table).\n\n"
                 "![study](study.png)\n\n")
        fh.write("| case | KN (Pa/m) | safety | spacing | wall (s) | error |\n|---|---|---|---|---|---|\n")
        for r in rows:
            fh.write(f"| {r[0]} | {r[1]:.0e} | {r[2]} | {r[3]} | {r[4]:.4f} | {r[5]:.3e} |\n")
    print(f"wrote {outdir}/study.md and {outdir}/study.png ({len(rows)} DEM runs)")


main()
