"""Fragility over intensity planes, per direction, with response modes (docs/FRAGILITY.md).

The field's displays of a PBR sweep (seed 000, Echo Cliff: overturning probability over
PGA x PGV, PGA x PGD, PGV x PGD and PGA x duration for 8 directions, each column one PGA level;
seed 002: PGA x PGV/PGA) and Purvance's normalised axes, from a `rockdem sweep` table:

  table(paths, where)            the sweep's columns as numpy arrays (+ 'level', its scale index)
  binned(t, x, y, ...)           cells over (x, y): runs n, overturned k, P = k/n and its 95 %
                                 Wilson interval (statsmodels proportion_confint); x grouped by
                                 the sweep's own scale index when x is the scaled measure
  surface(t, x, y)               logit P = c0 + c1 ln x + c2 ln y (statsmodels GLM; Firth's
                                 penalised likelihood where the outcomes separate)
  median_curve(fit, y)           x at P = 50 % along y: exp(-(c0 + c2 ln y) / c1)
  capacity(x, outcome)           the median capacity in x alone (logistic in ln x) with its 95 %
                                 interval (delta method on ln x50 = -b0/b1)
  rose(t, x, by)                 capacity per direction
  geometry(run_h5)               alpha(lean direction), R, p of a body for the normalised axes
  normalised(t, geo)             PGA / (g tan alpha(theta)) and p(theta) PGV/PGA per row
  modes(t, ...)                  P(mode | scale level) with intervals

analyse(...) runs them all and returns one dict (what `rdfragility planes` prints and plots);
fragility(paths, pairs, ..., output=PREFIX) is the one call from files to results and figures."""
import math
import re

import numpy as np
from statsmodels.stats.proportion import proportion_confint

from . import RDError
from . import fragility as F
from .fraginput import load, select
from .bodies import Bodies
from .runfile import open_h5, as_str

G = 9.80665
ALPHA_CI = 0.05          # 95 % intervals throughout
MODES = ("rest", "slide", "rock", "rock-slide", "rock-twist", "overturn")

# intensity measures of the table: column, symbol, unit, definition
IMS = {
    "pga": ("PGA", "m/s²", "peak ground acceleration"),
    "pgv": ("PGV", "m/s", "peak ground velocity"),
    "pgd": ("PGD", "m", "peak ground displacement"),
    "pgv_pga": ("PGV/PGA", "s", "peak ground velocity over peak ground acceleration"),
    "arias": ("$I_a$", "m/s", "Arias intensity"),
    "d5_95": ("$D_{5-95}$", "s", "significant duration, 5-95 % of the Arias intensity"),
    "sa_0_2": ("Sa(0.2 s)", "m/s²", "pseudo-spectral acceleration, 5 % damping, T = 0.2 s"),
    "sa_1": ("Sa(1 s)", "m/s²", "pseudo-spectral acceleration, 5 % damping, T = 1 s"),
    "pga_n": ("PGA/(g tan α)", "1", "PGA over the static tipping acceleration in the direction"),
    "pgvpga_n": ("p PGV/PGA", "1", "PGV/PGA times the rock's frequency parameter p"),
}
ALIASES = {"duration": "d5_95", "d595": "d5_95", "pgv/pga": "pgv_pga", "sa0.2": "sa_0_2",
           "sa1": "sa_1", "sa(0.2)": "sa_0_2", "sa(1)": "sa_1"}


def im_name(name):
    """The table column of an intensity measure named by the user."""
    k = ALIASES.get(name.strip().lower(), name.strip().lower())
    if k not in IMS:
        raise RDError("unknown intensity measure '%s' (expected one of %s, or duration)"
                      % (name, ", ".join(IMS)))
    return k


# ---------------------------------------------------------------- the table
def _axes_sizes(text):
    """[(key, n values)] of a sweep's `axes` attribute ("key=v1,v2\\n" per axis, then --set)."""
    out = []
    for line in (text or "").splitlines():
        if line.startswith("--set ") or "=" not in line:
            continue
        key, _, vals = line.partition("=")
        out.append((key, len(vals.split(","))))
    return out


def scale_index(case, axes_text):
    """The sweep's own value index of its `scale` axis for each case (rd_sweep_value_index:
    the last axis varies fastest), or None when the sweep has no scale axis."""
    sizes = _axes_sizes(axes_text)
    keys = [k for k, _ in sizes]
    if "scale" not in keys:
        return None
    a = keys.index("scale")
    inner = int(np.prod([n for _, n in sizes[a + 1:]])) if a + 1 < len(sizes) else 1
    return (np.asarray(case, np.int64) // inner) % sizes[a][1]


def level_groups(values, rtol=1e-9):
    """Group index of each value, values within rtol (relative) of the group's first in one
    group: the fallback for inputs without a scale index (a CSV, run files)."""
    v = np.asarray(values, float)
    order = np.argsort(v, kind="stable")
    idx = np.empty(len(v), int)
    g, ref = -1, None
    for i in order:
        if ref is None or abs(v[i] - ref) > rtol * max(abs(ref), 1e-300):
            g, ref = g + 1, v[i]
        idx[i] = g
    return idx


def row_levels(rows):
    """The scale level of each row (fraginput.load rows): the sweep's own scale index where all
    rows come from one sweep table with a scale axis; else equal `scale` values (1e-9
    relative); else equal PGA values (1e-9 relative)."""
    srcs = sorted({r["source"] for r in rows})
    cols = [r.get("cols", {}) for r in rows]
    if (len(srcs) == 1 and srcs[0].lower().endswith((".h5", ".hdf5")) and
            all("case" in c and "scale" in c for c in cols)):
        f = open_h5(srcs[0], "sweep table")
        try:
            level = scale_index([c["case"] for c in cols], as_str(f.attrs.get("axes", "")))
        finally:
            f.close()
        if level is not None:
            return np.asarray(level, int)
    if all("scale" in c for c in cols):
        try:
            return level_groups([float(c["scale"]) for c in cols])
        except (TypeError, ValueError):
            pass
    return level_groups([r["pga"] for r in rows])


def table(paths, where=None, outcome="overturned"):
    """All 1-D columns of the rows (sweep tables, rdtable CSVs) as numpy arrays, plus
    'overturned' (0/1 outcome), 'level' (the scale index: the sweep's own where it has a scale
    axis, else PGA values equal to 1e-9 relative) and 'level_value'."""
    rows = select(load(paths, None, None, outcome), where)
    if not rows:
        raise RDError("no rows")
    keys = set(rows[0].get("cols", {}))
    for r in rows[1:]:
        keys &= set(r.get("cols", {}))
    t = {}
    for k in keys:
        vals = [r["cols"][k] for r in rows]
        try:
            t[k] = np.array([float(v) for v in vals])
        except (TypeError, ValueError):
            t[k] = np.array([as_str(v) for v in vals], dtype=object)
    t["pga"] = np.array([r["pga"] for r in rows], float)
    t["pgv"] = np.array([r["pgv"] for r in rows], float)
    t["overturned"] = np.array([r["overturned"] for r in rows], float)
    if "pgv_pga" not in t:
        t["pgv_pga"] = t["pgv"] / t["pga"]
    t["level"] = row_levels(rows)
    base = t["scale"] if "scale" in t else t["pga"]
    t["level_value"] = np.array([base[t["level"] == i][0] if (t["level"] == i).any() else np.nan
                                 for i in range(t["level"].max() + 1)])
    return t


# ---------------------------------------------------------------- binned probabilities
def interval(k, n):
    """95 % Wilson interval of k/n (statsmodels proportion_confint); nan where n = 0."""
    k, n = np.asarray(k, float), np.asarray(n, float)
    lo, hi = np.full(k.shape, np.nan), np.full(k.shape, np.nan)
    m = n > 0
    if m.any():
        lo[m], hi[m] = proportion_confint(k[m], n[m], alpha=ALPHA_CI, method="wilson")
    return lo, hi


def log_edges(v, nbins):
    """nbins + 1 bin edges over the positive values v, equal counts (quantiles) in ln v, widened
    by 1e-9 so the extremes fall inside."""
    v = np.asarray(v, float)
    v = v[np.isfinite(v) & (v > 0)]
    if len(v) == 0:
        raise RDError("no positive finite values to bin")
    e = np.unique(np.exp(np.quantile(np.log(v), np.linspace(0, 1, max(1, nbins) + 1))))
    if len(e) < 2:
        e = np.array([v.min() * 0.9, v.max() * 1.1])
    e[0] *= 1 - 1e-9
    e[-1] *= 1 + 1e-9
    return e


def _bin_of(v, edges):
    i = np.searchsorted(edges, v, side="right") - 1
    return np.where((i >= 0) & (i < len(edges) - 1), i, -1)


def binned(t, x, y, outcome="overturned", nx=6, ny=6, mask=None):
    """Cells over (x, y) for the rows in mask (default all). The edges come from all rows, so the
    panels of one plane (one per direction) share their cells. x is grouped by the scale index
    when x is the measure the sweep scaled (pga for --scales ...g) and the rows hold several
    levels; else both are binned in equal-count log bins. Returns dict: xedges, yedges (bin
    edges; for x by level, geometric midpoints between the levels' median values), n, k, p, lo,
    hi [nx][ny], x_by_level (bool)."""
    m = np.ones(len(t["pga"]), bool) if mask is None else np.asarray(mask, bool)
    xa, ya = np.asarray(t[x], float), np.asarray(t[y], float)
    o = np.asarray(t[outcome], float)
    by_level = x == "pga" and "level" in t and len(np.unique(t["level"])) > 1
    if by_level:
        levels = np.unique(t["level"])
        centre = np.array([np.median(xa[t["level"] == L]) for L in levels])
        mid = np.sqrt(centre[1:] * centre[:-1])
        xe = np.concatenate([[centre[0] ** 2 / mid[0]], mid, [centre[-1] ** 2 / mid[-1]]])
        xi = np.searchsorted(levels, t["level"])
    else:
        xe = log_edges(xa, nx)
        xi = _bin_of(xa, xe)
    ye = log_edges(ya, ny)
    yi = _bin_of(ya, ye)
    n = np.zeros((len(xe) - 1, len(ye) - 1))
    k = np.zeros_like(n)
    ok = m & (xi >= 0) & (yi >= 0)
    np.add.at(n, (xi[ok], yi[ok]), 1)
    np.add.at(k, (xi[ok], yi[ok]), o[ok])
    lo, hi = interval(k, n)
    with np.errstate(invalid="ignore", divide="ignore"):
        p = np.where(n > 0, k / np.maximum(n, 1), np.nan)
    return dict(x=x, y=y, xedges=xe, yedges=ye, n=n, k=k, p=p, lo=lo, hi=hi, x_by_level=by_level)


# ---------------------------------------------------------------- fits
def surface(t, x, y, outcome="overturned", mask=None, method="auto"):
    """logit P = c0 + c1 ln x + c2 ln y; None (with the reason) when it cannot be fitted."""
    m = np.ones(len(t["pga"]), bool) if mask is None else np.asarray(mask, bool)
    xv, yv, o = t[x][m], t[y][m], np.asarray(t[outcome], float)[m]
    ok = np.isfinite(xv) & np.isfinite(yv) & (xv > 0) & (yv > 0)
    xv, yv, o = xv[ok], yv[ok], o[ok]
    if not 0 < o.sum() < len(o):
        return None, "all %d runs have the same outcome" % len(o)
    try:
        F.check_varies(x, xv, "surface")
        F.check_varies(y, yv, "surface")
    except F.DegenerateInput as e:
        return None, str(e)
    X = np.column_stack([np.ones(len(o)), np.log(xv), np.log(yv)])
    if np.linalg.matrix_rank(X, tol=1e-9 * np.abs(X).max()) < 3:
        return None, ("ln %s and ln %s are collinear in these runs (one pulse shape scaled): "
                      "their effects cannot be told apart; fit one of them" % (x, y))
    fit = F.logistic_fit(X, o, method)
    fit.update(x=x, y=y)
    return fit, ""


def surface_prob(fit, xv, yv):
    c0, c1, c2 = fit["beta"]
    return 1.0 / (1.0 + np.exp(-(c0 + c1 * np.log(xv) + c2 * np.log(yv))))


def median_curve(fit, yv, p=0.5):
    """x at probability p along y (the median-capacity curve for p = 0.5); nan if c1 <= 0."""
    c0, c1, c2 = fit["beta"]
    yv = np.asarray(yv, float)
    if c1 <= 0:
        return np.full(yv.shape, np.nan)
    return np.exp((math.log(p / (1 - p)) - c0 - c2 * np.log(yv)) / c1)


def capacity(xv, o, method="auto"):
    """Median capacity x50 from logit P = b0 + b1 ln x (Firth where separated), its 95 %
    interval exp(ln x50 +- 1.96 s), s from the delta method on ln x50 = -b0/b1; dict, or None
    when every run has the same outcome (then only a bound: 'below' or 'above' the data)."""
    xv, o = np.asarray(xv, float), np.asarray(o, float)
    ok = np.isfinite(xv) & (xv > 0)
    xv, o = xv[ok], o[ok]
    if len(o) == 0:
        return None
    if o.sum() in (0, len(o)) or np.ptp(np.log(xv)) == 0:
        return dict(bound="above" if o.sum() == 0 else "below" if o.sum() == len(o) else "none",
                    x_min=float(xv.min()), x_max=float(xv.max()), n=int(len(o)), k=int(o.sum()))
    X = np.column_stack([np.ones(len(o)), np.log(xv)])
    f = F.logistic_fit(X, o, method)
    b0, b1 = f["beta"]
    if b1 <= 0:
        return dict(bound="none", note="slope <= 0", n=int(len(o)), k=int(o.sum()),
                    x_min=float(xv.min()), x_max=float(xv.max()))
    J = np.array([-1.0 / b1, b0 / b1 ** 2])
    s = float(math.sqrt(max(J @ f["cov"] @ J, 0.0)))
    l50 = -b0 / b1
    return dict(median=math.exp(l50), ci=(math.exp(l50 - 1.96 * s), math.exp(l50 + 1.96 * s)),
                se_ln=s, b=[float(b0), float(b1)], cov=f["cov"].tolist(), method=f["method"],
                separated=f["separated"], n=int(len(o)), k=int(o.sum()),
                x_min=float(xv.min()), x_max=float(xv.max()))


def rose(t, x="pga", by="direction", outcome="overturned", method="auto"):
    """{direction: capacity(...)} over the values of column `by`."""
    if by not in t:
        raise RDError("no column '%s' to group by (a sweep with --directions has 'direction')" % by)
    return {float(d): capacity(t[x][t[by] == d], np.asarray(t[outcome], float)[t[by] == d], method)
            for d in np.unique(t[by])}


# ---------------------------------------------------------------- normalised axes
def geometry(run_path, body=None):
    """A body's rocking geometry from a `rockdem run` file of the scene: lean directions (rad),
    alpha per lean direction (rad, /bodies/<name>/precariousness), the centre of mass height h
    over its lowest point at rest (m), R(d) = h / cos alpha(d) (m), and Housner's frequency
    parameter p(d) = sqrt(m g R / I_O) (1/s), I_O the inertia about the base edge normal to d
    (the principal inertia turned to the ground frame, plus m R^2)."""
    f = open_h5(run_path, "rockdem run file")
    try:
        names = [as_str(n) for n in f["body"][()]] if "body" in f else []
        if not names:
            raise RDError("%s: no free bodies" % run_path)
        name = body or names[0]
        if name not in names:
            raise RDError("%s: no free body '%s' (it has %s)" % (run_path, name, ", ".join(names)))
        k = names.index(name)
        b = Bodies(f)
        pr = b.precariousness(name)
        if pr is None:
            raise RDError("%s: /bodies has no precariousness table of '%s'" % (run_path, name))
        mass = float(b.attr(name, "mass"))
        Ip = np.asarray(b.attr(name, "inertia_principal"), float)
        verts = b.vertices(name)
        q = f["quaternion"][0, k, :]
        m = re.search(r"^\s*model\s+gravity\s+([0-9.eE+-]+)", as_str(f.attrs.get("scenario", "")), re.M)
        g = float(m.group(1)) if m else G
    finally:
        f.close()
    w, xq, yq, zq = q / np.linalg.norm(q)
    Rq = np.array([[1 - 2 * (yq * yq + zq * zq), 2 * (xq * yq - w * zq), 2 * (xq * zq + w * yq)],
                   [2 * (xq * yq + w * zq), 1 - 2 * (xq * xq + zq * zq), 2 * (yq * zq - w * xq)],
                   [2 * (xq * zq - w * yq), 2 * (yq * zq + w * xq), 1 - 2 * (xq * xq + yq * yq)]])
    h = float(-(verts @ Rq.T)[:, 2].min())
    Iw = Rq @ np.diag(Ip) @ Rq.T
    d, alpha = pr[:, 0], pr[:, 1]
    R = h / np.cos(alpha)
    e = np.column_stack([-np.sin(d), np.cos(d), np.zeros(len(d))])
    I_O = np.einsum("ij,jk,ik->i", e, Iw, e) + mass * R * R
    p = np.sqrt(mass * g * R / I_O)
    return dict(body=name, direction=d, alpha=alpha, h=h, R=R, p=p, mass=mass, g=g)


def along(geo, theta_deg):
    """alpha and p for shaking along theta (deg): the weaker of the two lean directions
    theta and theta + 180 (the least alpha), linearly interpolated over the table."""
    d = np.degrees(geo["direction"]) % 360.0
    order = np.argsort(d)
    d, a, p = d[order], geo["alpha"][order], geo["p"][order]
    dd = np.concatenate([d - 360, d, d + 360])

    def at(v, th):
        return np.interp(np.asarray(th, float) % 360.0, dd, np.concatenate([v, v, v]))
    a1, a2 = at(a, theta_deg), at(a, np.asarray(theta_deg, float) + 180.0)
    p1, p2 = at(p, theta_deg), at(p, np.asarray(theta_deg, float) + 180.0)
    return np.where(a1 <= a2, a1, a2), np.where(a1 <= a2, p1, p2)


def normalised(t, geo):
    """Adds pga_n = PGA / (g tan alpha(theta)) and pgvpga_n = p(theta) PGV/PGA to t (theta: the
    row's direction, 0 if the table has none)."""
    th = t["direction"] if "direction" in t else np.zeros(len(t["pga"]))
    a, p = along(geo, th)
    t["pga_n"] = t["pga"] / (geo["g"] * np.tan(a))
    t["pgvpga_n"] = p * t["pgv"] / t["pga"]
    return t


# ---------------------------------------------------------------- response modes
def modes(t, mask=None):
    """P(mode | scale level) for each of MODES: dict(levels, level_value, n [L], k [M][L],
    p, lo, hi) from the table's `mode` column (None if the table has none)."""
    if "mode" not in t:
        return None
    m = np.ones(len(t["pga"]), bool) if mask is None else np.asarray(mask, bool)
    lv, md = t["level"][m], np.array([as_str(v) for v in t["mode"][m]])
    unknown = sorted(set(md) - set(MODES))
    if unknown:
        raise RDError("unknown response mode(s) in the table: %s" % ", ".join(unknown))
    levels = np.unique(lv)
    n = np.array([(lv == L).sum() for L in levels], float)
    k = np.array([[((lv == L) & (md == M)).sum() for L in levels] for M in MODES], float)
    lo, hi = interval(k, np.broadcast_to(n, k.shape))
    pga = np.array([np.median(t["pga"][m][lv == L]) for L in levels])
    return dict(levels=levels, pga=pga, n=n, k=k, p=k / n, lo=lo, hi=hi, modes=MODES)


# ---------------------------------------------------------------- everything
def analyse(t, pairs, by="direction", outcome="overturned", nx=6, ny=6, method="auto"):
    """Binned cells and the surface per (pair, group of `by`), the rose, the modes."""
    groups = [float(v) for v in np.unique(t[by])] if by and by in t else [None]
    res = dict(n=int(len(t["pga"])), k=int(np.sum(t[outcome])), by=by, groups=groups, planes={})
    for x, y in pairs:
        per = []
        for g in groups:
            mask = None if g is None else t[by] == g
            cells = binned(t, x, y, outcome, nx, ny, mask)
            fit, why = surface(t, x, y, outcome, mask, method)
            per.append(dict(group=g, cells=cells, fit=fit, why=why))
        res["planes"]["%s:%s" % (x, y)] = per
    if by and by in t:
        res["rose"] = rose(t, "pga", by, outcome, method)
        if "pga_n" in t:
            res["rose_n"] = rose(t, "pga_n", by, outcome, method)
    res["modes"] = modes(t)
    return res


def fragility(paths, pairs=(("pga", "pgv"),), by="direction", geometry_run=None, body=None,
              where=None, outcome="overturned", nx=6, ny=5, method="auto", output=None):
    """The one call: table, normalised axes (geometry_run: a rockdem run file of the scene),
    analyse(), and with output=PREFIX the figures (PNG 300 dpi + PDF). Pairs are names as
    im_name takes them ('pga', 'duration', 'pga_n', ...). Returns analyse()'s dict (+ 'files')."""
    t = table(list(paths), where, outcome)
    if geometry_run:
        normalised(t, geometry(geometry_run, body))
    pairs = [(im_name(a), im_name(b)) for a, b in pairs]
    for x, y in pairs:
        for c in (x, y):
            if c not in t:
                raise RDError("the input has no column '%s'" % c)
    res = analyse(t, pairs, by if by in t else None, outcome, nx, ny, method)
    if output:
        from . import planeplot as PP
        files = []
        for key in res["planes"]:
            files += PP.planes_figure(res, key, "%s_%s" % (output, key.replace(":", "_")))
        if "rose" in res:
            files += PP.rose_figure(res, output + "_rose")
        if res["modes"] is not None:
            files += PP.modes_figure(res, output + "_modes")
        res["files"] = files
    return res
