#!/usr/bin/python3
"""rdrunout — runout pictures (docs/RUNOUT.md).
  plan RUN.h5 [RUN2.h5 ...] [--terrain GRID.asc] [--labels A,B,...]: plan view of each free
      body's centre path over the terrain's height contours, with each fence (named) and its
      crossings, start and end points and the runout figures; several run files of one scene
      (an ensemble's cases, `rockdem sweep --keep-runs`) draw one path each, labelled by
      --labels (default: the files' names), the fences from the first;
  exceedance TABLE.h5: the sweep's exceedance curves of runout and of the fence energy (one
      curve per fence when there are several),
      P(X > x) = (number of cases above x) / (cases), against x."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rdtools import cli  # noqa: E402


def read_asc(path):
    """An ESRI ASCII grid: x (cell centres), y (south to north), z [y][x]."""
    head, rows = {}, []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0][0].isalpha():
                head[w[0].lower()] = float(w[1])
            else:
                rows.append([float(v) for v in w])
    nx, ny, c = int(head["ncols"]), int(head["nrows"]), head["cellsize"]
    x0 = head["xllcenter"] if "xllcenter" in head else head["xllcorner"] + 0.5 * c
    y0 = head["yllcenter"] if "yllcenter" in head else head["yllcorner"] + 0.5 * c
    z = np.array([v for r in rows for v in r]).reshape(ny, nx)[::-1]
    return x0 + c * np.arange(nx), y0 + c * np.arange(ny), z


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def fences(f):
    """Each fence of a run file: (name, polyline [point][x, y], per body {quantity: value})."""
    r = f["runout"]
    if "fences" in r:
        for name in r["fences"]:
            g = r["fences"][name]
            q = [text(v) for v in g["quantity"][:]]
            yield name, g["points"][:], [dict(zip(q, row)) for row in g["bodies"][:]]
    elif "fence" in r:  # a file written before fences were named
        q = [text(v) for v in r["quantity"][:]]
        hits = [{k[6:] if k.startswith("fence_") else k: v for k, v in zip(q, row)}
                for row in r["bodies"][:]]
        yield "fence", r["fence"][:], hits


def plan(a):
    import h5py
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    labels = a.labels.split(",") if a.labels else [os.path.splitext(os.path.basename(r))[0] for r in a.run]
    if len(labels) != len(a.run):
        raise cli.RDError("--labels: %d labels for %d run files" % (len(labels), len(a.run)))
    files = [h5py.File(r, "r") for r in a.run]
    fig, ax = plt.subplots(figsize=(7.2, 4.2))
    if a.terrain:
        x, y, z = read_asc(a.terrain)
        cf = ax.contourf(x, y, z, levels=16, cmap="Greys_r", alpha=0.45)
        ax.contour(x, y, z, levels=cf.levels, colors="0.5", linewidths=0.4)
        fig.colorbar(cf, ax=ax, shrink=0.8, label="terrain height (m)")
    first, npath = True, 0
    for f, tag in zip(files, labels):
        names = [text(b) for b in f["body"][:]]
        q = [text(v) for v in f["runout/quantity"][:]]
        rb = f["runout/bodies"][:]
        pos = f["position"][:]
        for k, name in enumerate(names):
            r = dict(zip(q, rb[k]))
            who = name if len(files) == 1 else f"{tag}: {name}"
            line, = ax.plot(pos[:, k, 0], pos[:, k, 1], lw=1.4,
                            label=f"{who}: runout {r['runout']:.2f} m, top speed {r['max_speed']:.2f} m/s")
            ax.plot(pos[0, k, 0], pos[0, k, 1], "o", color=line.get_color(), ms=4,
                    label="start" if first else None)
            ax.plot(pos[-1, k, 0], pos[-1, k, 1], "s", color=line.get_color(), ms=4,
                    label="end" if first else None)
            first, npath = False, npath + 1
    for k, f in enumerate(files):
        for fname, fe, hits in fences(f):
            if k == 0:
                ax.plot(fe[:, 0], fe[:, 1], "k-", lw=2.0)
                ax.annotate(fname, (fe[-1, 0], fe[-1, 1]), textcoords="offset points", xytext=(3, 3),
                            fontsize=7)
            for h in hits:
                if h["crossings"] > 0:
                    ax.plot(h["x"], h["y"], "x", color="k", ms=6)
                    if len(files) == 1:   # one run: each crossing's figures beside it
                        ax.annotate(f"{h['energy'] / 1e3:.2f} kJ, {h['height']:.2f} m up",
                                    (h["x"], h["y"]), textcoords="offset points", xytext=(4, -10),
                                    fontsize=7)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_aspect("equal")
    f = files[0]
    ax.set_title(text(f.attrs.get("title", "")) or os.path.basename(a.run[0]), fontsize=9)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=1 if len(files) > 1 else 3,
              frameon=False)
    fig.tight_layout()
    fig.savefig(a.output, dpi=a.dpi, bbox_inches="tight")  # the legend below the axes
    return "%s: %d path%s from %d run file%s" % (a.output, npath, "s"[npath == 1:], len(files), "s"[len(files) == 1:])


def exceedance(a):
    import h5py
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    s = h5py.File(a.run, "r")["sweep"]
    fig, axs = plt.subplots(1, 2, figsize=(7.2, 3.0))
    energy = [("all fences", s["fence_energy"][:])]
    if "fence" in s and "fence_max_energy" in s and len(s["fence"]) > 1:
        energy = [(text(n), s["fence_max_energy"][:, j]) for j, n in enumerate(s["fence"][:])]
    for ax, key, unit, curves in ((axs[0], "runout", "m", [("", s["runout"][:])]),
                                  (axs[1], "fence energy", "J", energy)):
        for label, col in curves:
            v = np.sort(col)
            p = 1.0 - np.arange(1, len(v) + 1) / len(v)  # P(X > v_i) for the sorted cases
            ax.step(np.r_[v[0], v], np.r_[1.0, p], where="post", label=label or None)
        if len(curves) > 1:
            ax.legend(fontsize=7, loc="lower left", frameon=False)
        ax.set_xlabel(f"{key} ({unit})")
        ax.set_ylabel("probability of exceedance")
        ax.set_ylim(0, 1.02)
        ax.set_title(f"{len(v)} cases", fontsize=8)
    fig.tight_layout()
    fig.savefig(a.output, dpi=a.dpi)
    return a.output


def main():
    p = cli.Parser(prog="rdrunout", description=cli.describe(__doc__))
    p.add_argument("what", choices=("plan", "exceedance"))
    p.add_argument("run", metavar="FILE.h5", nargs="+",
                   help="run files (plan: one or more of one scene) or a sweep table (exceedance)")
    p.add_argument("--terrain", metavar="GRID.asc", help="ESRI ASCII grid for the contours (plan)")
    p.add_argument("--labels", metavar="A,B,...", help="one label per run file (plan; default: the file names)")
    p.add_argument("-o", "--output", metavar="OUT.png", help="PNG to write (default: FILE_WHAT.png)")
    p.add_argument("--dpi", type=int, default=300, help="resolution (default 300)")
    a = p.parse_args()
    for path in a.run:
        if not os.path.isfile(path):
            p.error("%s: no such file" % path)
    if a.what == "exceedance":
        if len(a.run) != 1:
            p.error("exceedance takes one sweep table, got %d files" % len(a.run))
        a.run = a.run[0]
    a.output = a.output or os.path.splitext(a.run if a.what == "exceedance" else a.run[0])[0] + "_" + a.what + ".png"
    cli.ensure_writable(a.output)
    print("wrote %s" % (plan(a) if a.what == "plan" else exceedance(a)))


if __name__ == "__main__":
    sys.exit(cli.run(main, "rdrunout"))
