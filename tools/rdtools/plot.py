"""One run on one page, sized for a two-column journal page (7.2 in wide, 9-pt text): rocking
(tilt as a fraction of alpha, the body's static tipping angle towards the side it leans to,
for every shape, as the summary's max tilt ratio), sliding, the
ground motion (acceleration and velocity on two axes aligned at zero, one colour per component)
and the energies (in J, kJ or MJ, no offset) against time, events marked."""
import textwrap

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
COMPONENT_COLOUR = {"x": "#1f77b4", "y": "#ff7f0e", "z": "#2ca02c"}
G = 9.80665
WIDTH_IN = 7.2
RIGHT_OF_AXES = 1.02   # legends start just right of a panel (axes fraction)
RIGHT_OF_TWIN = 1.16   # ... or right of a twin axis's labels
SHOW_ALPHA_LINE = 0.5  # draw tilt = alpha only if some tilt ratio reaches this
FONT_PT = 9


def energy_unit(peak):
    """(divisor, label) so that energies of this size read as plain numbers."""
    for d, u in ((1e9, "GJ"), (1e6, "MJ"), (1e3, "kJ")):
        if peak >= d:
            return d, u
    return 1.0, "J"


def outside(x):
    """Legend keywords: beside the panel, at x axes-widths from its left edge, so that no
    legend covers a curve."""
    return dict(loc="upper left", bbox_to_anchor=(x, 1.0), frameon=False, borderaxespad=0.0)


def _symmetric(ax, values, pad=1.12):
    """y limits symmetric about zero (so twin axes share their zero line)."""
    m = float(np.nanmax(np.abs(values))) if np.size(values) else 1.0
    m = m if m > 0 else 1.0
    ax.set_ylim(-pad * m, pad * m)


def plot_run(path, out, dpi=300, max_event_lines=400, width=WIDTH_IN):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({"font.size": FONT_PT, "axes.labelsize": FONT_PT,
                         "legend.fontsize": FONT_PT - 1.5, "xtick.labelsize": FONT_PT - 1,
                         "ytick.labelsize": FONT_PT - 1})

    with Run(path) as r:
        t = r.time()
        names = r.body_names()
        tilt = r.data("tilt")
        acc = r.data("ground/acceleration")
        vel = r.data("ground/velocity") if r.has("ground/velocity") else None
        en = r.energies()
        events = r.events()
        ratios = [r.tilt_ratio(k, n) for k, n in enumerate(names)]
        slides = [slide_series(r, k, n) for k, n in enumerate(names)]
        s = r.summary()
        title = r.title or path
        sets = r.overrides()
        if sets:
            title += "  [--set " + ", ".join(sets) + "]"
        status = s.get("status", "no summary")
        damping = r.attr("damping", "")

    fig, ax = plt.subplots(4, 1, figsize=(width, 8.4), sharex=True,
                           gridspec_kw=dict(height_ratios=[1.2, 1, 1, 1.1], hspace=0.12))
    use_ratio = all(x is not None for x in ratios)
    for k, n in enumerate(names):
        yk = ratios[k] if use_ratio else np.degrees(tilt[:, k])
        ax[0].plot(t, yk, lw=1.0, label=n)
    if use_ratio:
        peak_ratio = max((float(np.nanmax(np.abs(x))) for x in ratios if np.size(x)), default=0.0)
        if peak_ratio >= SHOW_ALPHA_LINE:   # the overturn line only where it is near the data
            ax[0].axhline(1.0, color="0.5", lw=0.8, ls="--", label="tilt = α")
        ax[0].set_ylabel("tilt / α (1)\nα toward the lean")
    else:
        ax[0].set_ylabel("tilt (°)")
    for k, n in enumerate(names):
        ax[1].plot(t, slides[k] * 1e3, lw=1.0, label=n)
    ax[1].set_ylabel("base slide (mm)")

    big = max(float(np.abs(acc).max()), 1e-300)
    comps = [c for c in range(acc.shape[1]) if np.abs(acc[:, c]).max() > 1e-9 * big]
    for c in comps:
        xyz = "xyz"[c]
        ax[2].plot(t, acc[:, c] / G, lw=1.0, color=COMPONENT_COLOUR[xyz], label="a_%s" % xyz)
    ax[2].set_ylabel("ground acceleration (g)\nsolid")
    _symmetric(ax[2], acc[:, comps] / G if comps else np.zeros(1))
    if vel is not None:
        tw = ax[2].twinx()
        vbig = max(float(np.abs(vel).max()), 1e-300)
        vc = [c for c in range(vel.shape[1]) if np.abs(vel[:, c]).max() > 1e-9 * vbig]
        for c in vc:
            xyz = "xyz"[c]
            tw.plot(t, vel[:, c], lw=0.9, ls="--", color=COMPONENT_COLOUR[xyz], label="v_%s" % xyz)
        tw.set_ylabel("ground velocity (m/s)\ndashed")
        _symmetric(tw, vel[:, vc] if vc else np.zeros(1))
        tw.tick_params(labelsize=FONT_PT - 1)
        h1, l1 = ax[2].get_legend_handles_labels()
        h2, l2 = tw.get_legend_handles_labels()
        ax[2].legend(h1 + h2, l1 + l2, **outside(RIGHT_OF_TWIN))
    else:
        ax[2].legend(**outside(RIGHT_OF_AXES))
    ax[2].axhline(0, color="0.6", lw=0.6)

    peak = max((float(np.nanmax(np.abs(v))) for v in en.values() if np.size(v)), default=1.0)
    div, unit = energy_unit(peak)
    for k, v in en.items():
        ax[3].plot(t, v / div, lw=1.3 if k == "residual" else 1.0, color=ENERGY_STYLE.get(k),
                   label=k.replace("_", " "))
    ax[3].ticklabel_format(axis="y", useOffset=False, style="plain")
    ax[3].set_ylabel("energy (%s)" % unit)
    ax[3].set_xlabel("time (s)")
    ax[3].legend(loc="upper center", bbox_to_anchor=(0.5, -0.32), ncol=4, frameon=False)

    seen = set()
    shown = events if len(events) <= max_event_lines else \
        [e for e in events if e[2] in ("overturn", "recover", "unstable")]
    for (te, b, ty, _v) in shown:
        col, ls, lw = EVENT_STYLE.get(ty, ("0.3", "-.", 0.6))
        for a in ax:
            a.axvline(te, color=col, ls=ls, lw=lw, alpha=0.5, zorder=0)
        if 0 <= b < len(names) and t.size:
            yv = np.interp(te, t, ratios[b] if use_ratio else np.degrees(tilt[:, b]))
            ax[0].plot([te], [yv], marker="v" if ty != "overturn" else "X", color=col,
                       ms=4 if ty != "overturn" else 8, ls="none", label=None if ty in seen else ty)
            seen.add(ty)
    ax[0].legend(**outside(RIGHT_OF_AXES))
    ax[1].legend(**outside(RIGHT_OF_AXES))
    nev = {}
    for e in events:
        nev[e[2]] = nev.get(e[2], 0) + 1
    evtxt = ", ".join("%d %s" % (v, k) for k, v in sorted(nev.items())) or "no events"
    if len(shown) < len(events):
        evtxt += " (only overturn/recover drawn)"
    head = textwrap.fill(title, 95)
    fig.suptitle("%s\nstatus %s; damping %s; events: %s" % (head, status, damping or "?", evtxt),
                 fontsize=FONT_PT, y=0.995)
    for a in ax:
        a.grid(alpha=0.3)
    if t.size:
        ax[3].set_xlim(t[0], t[-1])
    fig.savefig(out, dpi=dpi, bbox_inches="tight")
    plt.close(fig)
    return out
