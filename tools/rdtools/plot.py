"""One run on one page: rocking, sliding, ground motion and energies against time, events marked."""
import numpy as np

from .runfile import Run
from .table import slide_series

EVENT_STYLE = {  # colour, line style, line width
    "uplift": ("tab:green", ":", 0.7),
    "impact": ("tab:orange", "-", 0.5),
    "slip": ("tab:purple", "--", 0.5),
    "overturn": ("tab:red", "-", 2.0),
    "recover": ("tab:blue", "-", 1.0),
    "unstable": ("black", "-", 2.0),
}
ENERGY_STYLE = {"kinetic": "tab:blue", "gravitational": "tab:green", "elastic": "tab:olive",
                "friction": "tab:purple", "damping": "tab:brown", "ground_work": "black",
                "residual": "tab:red"}


def plot_run(path, out, dpi=110, max_event_lines=400, width=9.0):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with Run(path) as r:
        t = r.time()
        names = r.body_names()
        tilt = r.data("tilt")
        acc = r.data("ground/acceleration")
        vel = r.data("ground/velocity") if r.has("ground/velocity") else None
        en = r.energies()
        events = r.events()
        alphas = [r.body_attr(n, "alpha", None) for n in names]
        slides = [slide_series(r, k, n) for k, n in enumerate(names)]
        s = r.summary()
        title = r.title or path
        sets = r.overrides()
        if sets:
            title += "  [--set " + ", ".join(sets) + "]"
        status = s.get("status", "no summary")
        damping = r.attr("damping", "")

    fig, ax = plt.subplots(4, 1, figsize=(width, 10), sharex=True,
                           gridspec_kw=dict(height_ratios=[1.2, 1, 1, 1.2]))
    use_ratio = all(a is not None and np.isfinite(a) and a > 0 for a in alphas)
    for k, n in enumerate(names):
        y = tilt[:, k] / alphas[k] if use_ratio else tilt[:, k]
        ax[0].plot(t, y, lw=1.0, label=n)
    if use_ratio:
        ax[0].axhline(1.0, color="0.5", lw=0.8, ls="--")
        ax[0].set_ylabel("tilt / alpha")
    else:
        ax[0].set_ylabel("tilt (rad)")
    for k, n in enumerate(names):
        ax[1].plot(t, slides[k] * 1e3, lw=1.0, label=n)
    ax[1].set_ylabel("base slide (mm)")

    g = 9.80665
    comp = ["x", "y", "z"]
    for c in range(acc.shape[1]):
        if np.any(acc[:, c] != 0):
            ax[2].plot(t, acc[:, c] / g, lw=1.0, label="a_%s" % comp[c])
    ax[2].set_ylabel("ground acc. (g)")
    if vel is not None:
        tw = ax[2].twinx()
        for c in range(vel.shape[1]):
            if np.any(vel[:, c] != 0):
                tw.plot(t, vel[:, c], lw=0.9, ls="--", color="C%d" % (c + 3), label="v_%s" % comp[c])
        tw.set_ylabel("ground vel. (m/s), dashed")
        h1, l1 = ax[2].get_legend_handles_labels()
        h2, l2 = tw.get_legend_handles_labels()
        ax[2].legend(h1 + h2, l1 + l2, loc="upper right", fontsize=7, ncol=2)
    else:
        ax[2].legend(loc="upper right", fontsize=7)

    for k, y in en.items():
        ax[3].plot(t, y, lw=1.3 if k == "residual" else 1.0, color=ENERGY_STYLE.get(k),
                   label=k)
    ax[3].set_ylabel("energy (J)")
    ax[3].set_xlabel("time (s)")
    ax[3].legend(loc="upper left", fontsize=7, ncol=4)

    # events: vertical lines on every panel, markers on the tilt curve
    seen = set()
    shown = events if len(events) <= max_event_lines else \
        [e for e in events if e[2] in ("overturn", "recover", "unstable")]
    for (te, b, ty, _v) in shown:
        col, ls, lw = EVENT_STYLE.get(ty, ("0.3", "-.", 0.6))
        for a in ax:
            a.axvline(te, color=col, ls=ls, lw=lw, alpha=0.6, zorder=0)
        if 0 <= b < len(names) and t.size:
            y = np.interp(te, t, tilt[:, b] / alphas[b] if use_ratio else tilt[:, b])
            ax[0].plot([te], [y], marker="v" if ty != "overturn" else "X", color=col, ms=4 if ty != "overturn" else 9,
                       ls="none", label=None if ty in seen else ty)
            seen.add(ty)
    h, l = ax[0].get_legend_handles_labels()
    ax[0].legend(h, l, loc="upper left", fontsize=7, ncol=3)
    ax[1].legend(loc="upper left", fontsize=7)
    nev = {}
    for e in events:
        nev[e[2]] = nev.get(e[2], 0) + 1
    evtxt = ", ".join("%d %s" % (v, k) for k, v in sorted(nev.items())) or "no events"
    if len(shown) < len(events):
        evtxt += " (only overturn/recover drawn)"
    fig.suptitle("%s\nstatus %s; damping %s; events: %s" % (title, status, damping or "?", evtxt),
                 fontsize=9)
    for a in ax:
        a.grid(alpha=0.3)
    if t.size:
        ax[3].set_xlim(t[0], t[-1])
    fig.tight_layout()
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out
