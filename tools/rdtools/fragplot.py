"""Figure of rdfragility: (A) data and the 2-D logistic surface over (PGA, PGV/PGA) with its 10,
50 and 95 % contours and the binned (seed 002) fragility points at each bin's median PGV/PGA;
(B) the binned logistic curves against PGA; (C) the lognormal fit with its 95 % band."""
import numpy as np

from . import fragility as F

LEVEL_STYLE = {0.10: ("tab:green", "o"), 0.50: ("tab:orange", "s"), 0.95: ("tab:red", "^")}


def plot_fragility(out, pga, T, y, bins, surf, ln, ustr, form, dpi=110):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 3, figsize=(15, 4.8))
    y = np.asarray(y, bool)
    xlo, xhi = pga.min() / 1.15, pga.max() * 1.15
    tlo, thi = T.min() / 1.15, T.max() * 1.15

    # (A) surface
    a = ax[0]
    if surf is not None:
        xs = np.linspace(xlo, xhi, 200)
        ts = np.geomspace(tlo, thi, 200)
        Xg, Tg = np.meshgrid(xs, ts)
        Pg = F.surface_prob(surf, Xg, Tg)
        cf = a.contourf(Xg, Tg, Pg, levels=np.linspace(0, 1, 11), cmap="Greys", alpha=0.55)
        fig.colorbar(cf, ax=a, label="P(overturning), 2-D logistic")
        cs = a.contour(Xg, Tg, Pg, levels=list(F.LEVELS),
                       colors=[LEVEL_STYLE[q][0] for q in F.LEVELS], linewidths=1.8)
        a.clabel(cs, fmt={q: "%d %%" % round(100 * q) for q in F.LEVELS}, fontsize=8)
    a.scatter(pga[~y], T[~y], s=14, marker="o", facecolors="none", edgecolors="tab:blue",
              label="not overturned")
    a.scatter(pga[y], T[y], s=16, marker="x", color="tab:red", label="overturned")
    for q in F.LEVELS:
        pts = [(d["pga_at"][q], d["T_median"]) for d in bins if np.isfinite(d["pga_at"][q])]
        if pts:
            px, pt = zip(*pts)
            col, mk = LEVEL_STYLE[q]
            a.plot(px, pt, marker=mk, color=col, ls="--", lw=1, mec="k", ms=7,
                   label="binned fit, %d %%" % round(100 * q))
    for d in bins[1:]:
        a.axhline(d["lo"], color="0.6", lw=0.6, ls=":")
    a.set_yscale("log")
    a.set_xlim(xlo, xhi)
    a.set_ylim(tlo, thi)
    a.set_xlabel("PGA (%s)" % ustr)
    a.set_ylabel("PGV/PGA (s)")
    a.set_title("(A) fragility surface, contours 10/50/95 %", fontsize=10)
    a.legend(fontsize=7, loc="upper right")

    # (B) binned curves
    b = ax[1]
    xs = np.linspace(xlo, xhi, 300)
    for i, d in enumerate(bins):
        col = "C%d" % i
        m = (T >= d["lo"]) & ((T <= d["hi"]) if i == len(bins) - 1 else (T < d["hi"]))
        lab = "T %.3g-%.3g s (n=%d)" % (d["lo"], d["hi"], d["n"])
        if "b0" in d:
            b.plot(xs, F.binned_prob(d, xs), color=col, label=lab + (" firth" if d.get("method") == "firth" else ""))
        else:
            lab += " " + d["note"]
        jitter = (i - len(bins) / 2) * 0.012
        b.plot(pga[m], y[m] + jitter, ls="none", marker="|", color=col, ms=8,
               label=None if "b0" in d else lab)
    b.set_xlim(xlo, xhi)
    b.set_ylim(-0.08, 1.08)
    b.set_xlabel("PGA (%s)" % ustr)
    b.set_ylabel("P(overturning)")
    b.set_title("(B) logistic in %s per PGV/PGA bin (seed 002 eq. 3)"
                % ("PGA" if form == "linear" else "ln PGA"), fontsize=10)
    b.legend(fontsize=7, loc="center right")

    # (C) lognormal
    c = ax[2]
    xs = np.geomspace(xlo, xhi, 300)
    e = np.quantile(pga, np.linspace(0, 1, min(8, max(2, len(pga) // 8)) + 1))
    e = np.unique(e)
    for i in range(len(e) - 1):
        m = (pga >= e[i]) & ((pga <= e[i + 1]) if i == len(e) - 2 else (pga < e[i + 1]))
        if m.any():
            c.plot(np.exp(np.log(pga[m]).mean()), y[m].mean(), "ks", ms=5,
                   label="fraction overturned (PGA bins)" if i == 0 else None)
    if ln["separated"] is None:
        pass  # not fitted (degenerate input): the data points only
    elif not ln["separated"]:
        lo, hi = ln["band"](xs)
        c.fill_between(xs, lo, hi, color="tab:blue", alpha=0.25,
                       label="95 %% band (%s)" % ("Fisher information" if ln["band_method"] == "fisher"
                                                  else ln["band_method"]))
        c.plot(xs, F.lognormal_prob(ln["theta"], ln["beta"], xs), color="tab:blue",
               label="lognormal ML: median %.3g %s, beta %.3g" % (ln["theta"], ustr, ln["beta"]))
    else:
        c.axvspan(*ln["theta_range"], color="tab:blue", alpha=0.2, label="separated: median in here")
    c.set_xscale("log")
    c.set_xlim(xlo, xhi)
    c.set_ylim(-0.03, 1.03)
    c.set_xlabel("PGA (%s)" % ustr)
    c.set_ylabel("P(overturning)")
    c.set_title("(C) lognormal fragility in PGA, all runs", fontsize=10)
    c.legend(fontsize=7, loc="upper left")
    for x in ax:
        x.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
