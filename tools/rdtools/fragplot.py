"""Figure of rdfragility, sized for a two-column journal page (7.2 in wide, 9-pt text, every
axis with its unit): (A) the runs over (PGA, PGV/PGA) with the 2-D logistic surface's 10, 50 and
95 % contours and the binned (seed 002) fragility points at each bin's median PGV/PGA; (B) the
binned logistic curves against PGA with their 95 % bands and the outcomes; (C) the fragility in
PGA from all runs — the lognormal (probit GLM) with its 95 % band, or, when the outcomes are
separated by PGA, Firth's logistic in ln PGA with its Wald band — and the fraction overturned
per PGA level (the sweep's own scale index) with Wilson 95 % intervals (statsmodels)."""
import numpy as np
from scipy import special

from . import fragility as F

LEVEL_STYLE = {0.10: ("#1b9e77", "o", "-."), 0.50: ("#d95f02", "s", "-"), 0.95: ("#7570b3", "^", "--")}
WIDTH_IN = 7.2     # two-column figure width, in
FONT_PT = 9


def _rc(plt):
    plt.rcParams.update({"font.size": FONT_PT, "axes.titlesize": FONT_PT + 0.5,
                         "axes.labelsize": FONT_PT, "legend.fontsize": FONT_PT - 1.5,
                         "xtick.labelsize": FONT_PT - 1, "ytick.labelsize": FONT_PT - 1,
                         "axes.titlelocation": "left", "axes.titleweight": "bold"})


def wilson(k, n):
    """95 % Wilson score interval of k/n (statsmodels proportion_confint)."""
    from .planes import interval
    return interval(k, n)


def _logit_band(beta, cov, X):
    """P and its pointwise 95 % Wald band for a logistic model at design rows X."""
    eta = X @ beta
    sd = np.sqrt(np.einsum("ij,jk,ik->i", X, cov, X))
    return special.expit(eta), special.expit(eta - 1.96 * sd), special.expit(eta + 1.96 * sd)


def _fractions(ax, pga, y, level=None, color="k"):
    """Fraction overturned per PGA level, Wilson 95 % bars. level: the sweep's own scale index of
    each run (planes.table; PGA values equal to 1e-9 relative when the input has none), so runs
    scaled to one level are one group whatever their rounding; more than 12 levels: 8 quantile
    bins of PGA instead."""
    from .planes import level_groups
    lv = np.asarray(level if level is not None else level_groups(pga), int)
    u = np.unique(lv)
    groups = [lv == v for v in u] if len(u) <= 12 else None
    if groups is None:
        e = np.unique(np.quantile(pga, np.linspace(0, 1, 9)))
        groups = [(pga >= e[i]) & ((pga <= e[i + 1]) if i == len(e) - 2 else (pga < e[i + 1]))
                  for i in range(len(e) - 1)]
    xs, fr, lo, hi = [], [], [], []
    for m in groups:
        if m.any():
            n, k = m.sum(), y[m].sum()
            a, b = wilson(k, n)
            xs.append(np.exp(np.log(pga[m]).mean()))
            fr.append(k / n)
            lo.append(a)
            hi.append(b)
    xs, fr = np.array(xs), np.array(fr)
    err = np.clip([fr - np.array(lo), np.array(hi) - fr], 0, None)  # rounding at 0 and 1
    ax.errorbar(xs, fr, yerr=err, fmt="s", color=color, ms=4,
                capsize=2, lw=0.8, label="fraction overturned (Wilson 95 %)", zorder=5)
    return dict(x=xs, fraction=fr, n=[int(m.sum()) for m in groups if m.any()])


def _ticks(axis, lo, hi, data):
    """Readable ticks on a log axis spanning less than a decade or two: the distinct data values
    when there are few, else 5 rounded values; plain numbers, no minor labels."""
    import matplotlib.ticker as mt
    u = np.unique(np.round(np.asarray(data, float), 3))
    u = u[(u > lo) & (u < hi)]
    if not 2 <= len(u) <= 8:
        u = np.unique([float("%.2g" % v) for v in np.geomspace(lo * 1.05, hi / 1.05, 5)])
    axis.set_major_locator(mt.FixedLocator(u))
    axis.set_major_formatter(mt.FormatStrFormatter("%.3g"))
    axis.set_minor_formatter(mt.NullFormatter())


def plot_fragility(out, pga, T, y, bins, surf, ln, ustr, form, dpi=300, level=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    _rc(plt)
    y = np.asarray(y, bool)
    fig = plt.figure(figsize=(WIDTH_IN, 6.4))
    gs = fig.add_gridspec(2, 2, height_ratios=[1.15, 1], hspace=0.42, wspace=0.28)
    axA, axB, axC = fig.add_subplot(gs[0, :]), fig.add_subplot(gs[1, 0]), fig.add_subplot(gs[1, 1])
    xlo, xhi = pga.min() / 1.12, pga.max() * 1.12
    tlo, thi = T.min() / 1.12, T.max() * 1.12

    # (A) runs and the surface's contours
    a = axA
    if surf is not None:
        xs, ts = np.geomspace(xlo, xhi, 200), np.geomspace(tlo, thi, 200)
        Xg, Tg = np.meshgrid(xs, ts)
        Pg = F.surface_prob(surf, Xg, Tg)
        for q in F.LEVELS:
            col, _, ls = LEVEL_STYLE[q]
            cs = a.contour(Xg, Tg, Pg, levels=[q], colors=[col], linewidths=1.6, linestyles=ls)
            a.plot([], [], color=col, ls=ls, lw=1.6, label="surface, P = %d %%" % round(100 * q))
    # the runs: a small horizontal jitter separates coincident points (same PGA, same T)
    key = np.round(np.log(pga), 6) * 1e6 + np.round(np.log(T), 6)
    jit = np.zeros(len(pga))
    for kv in np.unique(key):
        m = np.flatnonzero(key == kv)
        if len(m) > 1:
            jit[m] = np.linspace(-1, 1, len(m)) * 0.012 * len(m) ** 0.5
    px = pga * np.exp(jit)
    a.scatter(px[~y], T[~y], s=16, marker="o", facecolors="white", edgecolors="#2c7bb6", lw=0.9,
              label="stood (%d)" % (~y).sum(), zorder=4)
    a.scatter(px[y], T[y], s=18, marker="x", color="#d7191c", lw=1.0,
              label="overturned (%d)" % y.sum(), zorder=4)
    for q in F.LEVELS:
        pts = [(d["pga_at"][q], d["T_median"]) for d in bins if np.isfinite(d["pga_at"][q])]
        if pts:
            bx, bt = zip(*pts)
            col, mk, _ = LEVEL_STYLE[q]
            a.plot(bx, bt, marker=mk, color=col, ls="none", mec="k", mew=0.6, ms=6, zorder=6,
                   label="binned fit, %d %%" % round(100 * q))
    for d in bins[1:]:
        a.axhline(d["lo"], color="0.75", lw=0.6, ls=":", zorder=1)
    a.set_xscale("log")
    a.set_yscale("log")
    a.set_xlim(xlo, xhi)
    a.set_ylim(tlo, thi)
    _ticks(a.xaxis, xlo, xhi, pga)
    _ticks(a.yaxis, tlo, thi, [])
    a.set_xlabel("PGA (%s)" % ustr)
    a.set_ylabel("PGV/PGA (s)")
    title = "A  runs and the 2-D logistic fragility surface"
    if surf is None:
        title += " (not fitted)"
    elif surf.get("method") == "firth":
        title += " (Firth: data separated)"
    a.set_title(title)
    a.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False)

    # (B) binned logistic curves with bands
    b = axB
    xs = np.geomspace(xlo, xhi, 300)
    for i, d in enumerate(bins):
        col = "C%d" % i
        m = (T >= d["lo"]) & ((T <= d["hi"]) if i == len(bins) - 1 else (T < d["hi"]))
        lab = "T %.3g–%.3g s" % (d["lo"], d["hi"])
        if "b0" in d:
            x1 = np.log(xs) if d["form"] == "log" else xs
            X = np.column_stack([np.ones(len(xs)), x1])
            cov = np.array(d.get("cov", [[np.nan] * 2] * 2), float)
            p, lo, hi = _logit_band(np.array([d["b0"], d["b1"]]), cov, X)
            b.plot(xs, p, color=col, lw=1.4, label=lab + (" (Firth)" if d.get("method") == "firth" else ""))
            if np.all(np.isfinite(cov)):
                b.fill_between(xs, lo, hi, color=col, alpha=0.12, lw=0)
                b.plot(xs, lo, color=col, lw=0.5, ls=":")
                b.plot(xs, hi, color=col, lw=0.5, ls=":")
        else:
            lab += ": " + d["note"]
        off = (i - (len(bins) - 1) / 2) * 0.035
        b.plot(pga[m], y[m] + off, ls="none", marker="|", color=col, ms=7, mew=1.2,
               label=None if "b0" in d else lab)
    b.set_xscale("log")
    _ticks(b.xaxis, xlo, xhi, pga)
    b.set_xlim(xlo, xhi)
    b.set_ylim(-0.1, 1.1)
    b.set_xlabel("PGA (%s)" % ustr)
    b.set_ylabel("P(overturning)")
    b.set_title("B  per PGV/PGA bin (seed 002 eq. 3)")
    b.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), frameon=False,
             title="curves: fit, dotted: 95 % Wald band", title_fontsize=FONT_PT - 1.5)

    # (C) fragility in PGA from all runs
    c = axC
    if ln.get("separated") is False:
        lo, hi = ln["band"](xs)
        c.fill_between(xs, lo, hi, color="#2c7bb6", alpha=0.2, lw=0,
                       label="95 %% band (%s)" % ("Fisher" if ln["band_method"] == "fisher"
                                                  else ln["band_method"]))
        c.plot(xs, F.lognormal_prob(ln["theta"], ln["beta"], xs), color="#2c7bb6", lw=1.6,
               label="lognormal: median %.3g %s, β %.2f" % (ln["theta"], ustr, ln["beta"]))
    elif ln.get("firth") is not None:
        fb, fc = ln["firth"]["beta"], ln["firth"]["cov"]
        p, lo, hi = _logit_band(fb, fc, np.column_stack([np.ones(len(xs)), np.log(xs)]))
        c.fill_between(xs, lo, hi, color="#2c7bb6", alpha=0.2, lw=0, label="95 % Wald band")
        c.plot(xs, p, color="#2c7bb6", lw=1.6, label="Firth logistic in ln PGA: median %.3g %s"
               % (np.exp(-fb[0] / fb[1]), ustr))
    _fractions(c, pga, y.astype(float), level)
    c.set_xscale("log")
    _ticks(c.xaxis, xlo, xhi, pga)
    c.set_xlim(xlo, xhi)
    c.set_ylim(-0.05, 1.05)
    c.set_xlabel("PGA (%s)" % ustr)
    c.set_ylabel("P(overturning)")
    c.set_title("C  all runs, against PGA")
    c.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), frameon=False)
    for x in (axA, axB, axC):
        x.grid(alpha=0.25, which="major")
    fig.savefig(out, dpi=dpi, bbox_inches="tight")
    plt.close(fig)
