"""Figures of `rdfragility planes` for print: 7.2 in wide (two journal columns), 8-9 pt text,
every axis labelled with its unit, every symbol defined in the caption line under the panels,
legends and colour bars outside the data; each figure written as a 300 dpi PNG and a vector PDF.

  planes_figure   one intensity plane, one panel per direction: the cells' P = k/n (colour)
                  with their counts k/n, the fitted surface's 10/50/90 % contours (the 50 %
                  one is the median-capacity curve)
  rose_figure     the median capacity (PGA, and PGA / (g tan alpha) where the geometry is
                  known) against the shaking direction, with 95 % intervals
  modes_figure    P(mode | PGA level) for the six response modes, with 95 % intervals"""
import textwrap

import numpy as np

from . import planes as P

WIDTH_IN = 7.2
DPI = 300
CONTOURS = ((0.1, ":"), (0.5, "-"), (0.9, "--"))
MODE_COLOURS = {"rest": "#bdbdbd", "slide": "#fdae61", "rock": "#2c7bb6", "rock-slide": "#abd9e9",
                "rock-twist": "#7b3294", "overturn": "#d7191c"}


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({"font.size": 8, "axes.titlesize": 8, "axes.labelsize": 8,
                         "legend.fontsize": 7, "xtick.labelsize": 7, "ytick.labelsize": 7,
                         "pdf.fonttype": 42, "savefig.dpi": DPI})
    return plt


def save(fig, prefix):
    """prefix.png (300 dpi) and prefix.pdf (vector); returns both paths."""
    out = [prefix + ".png", prefix + ".pdf"]
    fig.savefig(out[0], dpi=DPI, bbox_inches="tight")
    fig.savefig(out[1], bbox_inches="tight")
    return out


def caption(fig, text, width_in):
    """A caption under the axes, wrapped to the figure's width (about 17 characters per inch
    at 6.5 pt)."""
    fig.text(0.01, 0.0, "\n".join(textwrap.wrap(text, int(17 * width_in))), fontsize=6.5,
             ha="left", va="top", transform=fig.transFigure)


def label(name, scale_g=False):
    sym, unit, _ = P.IMS[name]
    if scale_g and name == "pga":
        unit = "g"
    return "%s (%s)" % (sym, unit) if unit != "1" else sym


def _direction_title(g, by):
    if g is None:
        return "all runs"
    return "%s %g°" % ("direction" if by == "direction" else by, g)


def planes_figure(res, pair, prefix, g_units=True, ncols=4):
    """One figure for plane 'x:y' of analyse()'s result."""
    plt = _plt()
    from matplotlib.colors import Normalize
    x, y = pair.split(":")
    per = res["planes"][pair]
    ng = len(per)
    nc = min(ncols, ng)
    nr = int(np.ceil(ng / nc))
    width = min(WIDTH_IN, 1.55 * nc + 1.3)
    fig, axs = plt.subplots(nr, nc, figsize=(width, 1.7 * nr + 0.6), squeeze=False,
                            sharex=True, sharey=True)
    fig.subplots_adjust(left=0.1 if nc > 2 else 0.17, right=0.86, bottom=0.12 / nr ** 0.5 + 0.08,
                        top=1 - 0.16 / nr, wspace=0.08, hspace=0.3)
    cmap = plt.get_cmap("viridis")
    norm = Normalize(0, 1)
    sx = P.G if (g_units and x == "pga") else 1.0
    sy = P.G if (g_units and y == "pga") else 1.0
    for i, d in enumerate(per):
        ax = axs[i // nc][i % nc]
        c = d["cells"]
        xe, ye = c["xedges"] / sx, c["yedges"] / sy
        ax.pcolormesh(xe, ye, np.ma.masked_invalid(c["p"].T), cmap=cmap, norm=norm,
                      edgecolors="white", linewidth=0.4)
        for a in range(len(xe) - 1):
            for b in range(len(ye) - 1):
                if c["n"][a, b] > 0:
                    xm, ym = np.sqrt(xe[a] * xe[a + 1]), np.sqrt(ye[b] * ye[b + 1])
                    ax.text(xm, ym, "%d/%d" % (c["k"][a, b], c["n"][a, b]), ha="center",
                            va="center", fontsize=5.5,
                            color="white" if c["p"][a, b] < 0.6 else "black")
        if d["fit"] is not None:
            xs = np.geomspace(xe[0], xe[-1], 120)
            ys = np.geomspace(ye[0], ye[-1], 120)
            X, Y = np.meshgrid(xs, ys)
            Z = P.surface_prob(d["fit"], X * sx, Y * sy)
            for q, ls in CONTOURS:
                if Z.min() < q < Z.max():  # a level outside the panel draws nothing
                    ax.contour(X, Y, Z, levels=[q], colors="#ff7f00", linestyles=ls, linewidths=1.1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
            axis.set_major_formatter(FuncFormatter(lambda v, _: "%g" % v))
            axis.set_minor_formatter(NullFormatter())
        ax.set_xlim(xe[0], xe[-1])
        ax.set_ylim(ye[0], ye[-1])
        t = _direction_title(d["group"], res["by"])
        if d["fit"] is not None and d["fit"]["method"] == "firth":
            t += " (Firth)"
        elif d["fit"] is None:
            t += " (no fit)"
        ax.set_title(t, loc="left")
        if i // nc == nr - 1:
            ax.set_xlabel(label(x, g_units))
        if i % nc == 0:
            ax.set_ylabel(label(y, g_units))
    for j in range(ng, nr * nc):
        axs[j // nc][j % nc].set_visible(False)
    sm = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    cax = fig.add_axes([0.88, fig.subplotpars.bottom, 0.018, fig.subplotpars.top - fig.subplotpars.bottom])
    cb = fig.colorbar(sm, cax=cax)
    cb.set_label("P(overturning) = k/n in the cell")
    for q, ls in CONTOURS:
        axs[0][0].plot([], [], color="#ff7f00", ls=ls, lw=1.1, label="fitted P = %d %%" % (100 * q))
    if any(d["fit"] is not None for d in per):
        fig.legend(*axs[0][0].get_legend_handles_labels(), loc="lower center", ncol=3, frameon=False,
                   bbox_to_anchor=(0.5, 1 - 0.1 / nr))
    sym = "; ".join("%s: %s" % (P.IMS[v][0], P.IMS[v][2]) for v in (x, y))
    caption(fig, "Cells: k of n runs overturned (colour k/n); x by the sweep's PGA level where x "
            "is the scaled PGA. Lines: the fitted surface logit P = c0 + c1 ln x + c2 ln y (Firth's "
            "penalised likelihood where the outcomes separate); its 50 %% line is the "
            "median-capacity curve. %s." % sym, width)
    out = save(fig, prefix)
    plt.close(fig)
    return out


def rose_figure(res, prefix, g_units=True):
    """Median capacity per direction: PGA (g), and PGA / (g tan alpha) if res has rose_n."""
    plt = _plt()
    panels = [("rose", "median PGA capacity (%s)" % ("g" if g_units else "m/s²"),
               P.G if g_units else 1.0)]
    if res.get("rose_n"):
        panels.append(("rose_n", "median PGA/(g tan α) capacity", 1.0))
    fig = plt.figure(figsize=(WIDTH_IN if len(panels) > 1 else 3.6, 3.6))
    fig.subplots_adjust(wspace=0.55)
    for i, (key, lab, s) in enumerate(panels):
        ax = fig.add_subplot(1, len(panels), i + 1, projection="polar")
        ax.set_theta_zero_location("E")
        ax.set_theta_direction(1)
        th, med, lo, hi, bnd = [], [], [], [], []
        for d, c in sorted(res[key].items()):
            if c is None:
                continue
            if "median" in c:
                th.append(np.radians(d))
                med.append(c["median"] / s)
                lo.append(c["ci"][0] / s)
                hi.append(c["ci"][1] / s)
            else:
                bnd.append((np.radians(d), c))
        if th:
            th, med, lo, hi = map(np.array, (th, med, lo, hi))
            top = np.nanmax(np.r_[med, np.minimum(hi, 3 * med.max())]) * 1.1
            cl = np.r_[th, th[:1]]
            ax.plot(cl, np.r_[med, med[:1]], "-o", color="#2c7bb6", ms=3.5, lw=1.2,
                    label="median (logistic in ln PGA)")
            for a, l_, h_ in zip(th, lo, np.minimum(hi, top)):
                ax.plot([a, a], [l_, h_], color="#2c7bb6", lw=2.2, alpha=0.35)
            ax.plot([], [], color="#2c7bb6", lw=2.2, alpha=0.35, label="95 % interval")
            ax.set_ylim(0, top)
        for a, c in bnd:
            r = c["x_max"] / s if c["bound"] == "above" else c["x_min"] / s
            ax.plot([a], [r], marker="^" if c["bound"] == "above" else "v", color="k", ms=5, ls="none")
        if bnd:
            ax.plot([], [], marker="^", color="k", ls="none", label="bound: no run (▲) / every run (▼) fell")
        from matplotlib.ticker import MaxNLocator
        ax.yaxis.set_major_locator(MaxNLocator(4))
        ax.set_rlabel_position(112.5)
        ax.tick_params(axis="y", labelsize=6.5)
        ax.set_title(lab, pad=14)
        ax.set_xlabel("shaking direction θ (deg, counter-clockwise from +x)", labelpad=8)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.18), frameon=False)
    out = save(fig, prefix)
    plt.close(fig)
    return out


def modes_figure(res, prefix, g_units=True):
    """P(mode | PGA level), all directions together."""
    plt = _plt()
    md = res["modes"]
    fig, ax = plt.subplots(figsize=(3.6, 2.8))
    s = P.G if g_units else 1.0
    x = md["pga"] / s
    for i, m in enumerate(md["modes"]):
        if md["k"][i].sum() == 0:
            continue
        off = np.exp((i - 2.5) * 0.012)
        err = np.clip([md["p"][i] - md["lo"][i], md["hi"][i] - md["p"][i]], 0, None)
        ax.errorbar(x * off, md["p"][i], yerr=err, color=MODE_COLOURS[m], marker="o", ms=3.5,
                    lw=1.1, capsize=2, label=m)
    ax.set_xscale("log")
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter
    ax.xaxis.set_major_locator(FixedLocator(x))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: "%.3g" % v))
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_ylim(-0.03, 1.03)
    ax.set_xlabel("PGA level (%s)" % ("g" if g_units else "m/s²"))
    ax.set_ylabel("P(mode), fraction of runs")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False, title="mode")
    ax.grid(alpha=0.25)
    fig.text(0.0, -0.06, "Per PGA level (median PGA of its runs), all directions; bars: 95 % "
             "Wilson intervals (statsmodels). Modes: docs/FRAGILITY.md.", fontsize=6.5,
             ha="left", va="top", wrap=True)
    out = save(fig, prefix)
    plt.close(fig)
    return out
