"""One row per run and body: the outcome of a rockdem run in a table (and CSV in/out).

Values come from the /summary attributes when present; a run that stopped before writing its
summary (Ctrl-C, crash) still gets a row, computed from the time series, with status
'no-summary'. Intensity measures: every numeric attribute on /ground is copied (for records
rockdem writes h1_pga, h1_pgv, h1_arias, h1_sa_1s, ... and h2_*, vertical_* per component). The
pga and pgv columns are: /ground pga/pgv if present; else the larger of h1_pga/h2_pga (h1_pgv/
h2_pgv) of the whole record (im_source 'attrs:h1' or 'attrs:max(h1,h2)'); else (pulses) computed
from the applied motion
(/ground/acceleration, /ground/velocity: peak of the horizontal resultant) and the column
im_source says which ('attrs', 'computed', or 'computed-partial' when the run stopped early, e.g.
at overturning, while the ground still moved: the peaks cover only the motion before the stop)."""
import csv
import math
import os

import numpy as np

from . import RDError
from .rotation import quat_to_matrix, base_point
from .runfile import Run

BASE_COLUMNS = ["file", "title", "body", "overturned", "overturn_time", "max_tilt",
                "max_tilt_ratio", "max_slide", "final_slide", "uplifted", "slid", "ever_overturned",
                "status", "dt",
                "end_time", "energy_residual", "pga", "pgv", "pgv_pga", "im_source", "overrides"]


def slide_series(run, k, name):
    """Horizontal displacement [N] of body k's base centre from its position at the first sample
    (rockdem's 'slide': the base centre, so rocking alone moves it little)."""
    pos = run.data("position")[:, k, :]
    q = run.data("quaternion")[:, k, :]
    v, _ = run.body_geometry(name)
    R = quat_to_matrix(q)
    # lowest vertices at the first sample, in the body frame
    w0 = v @ R[0].T
    size = max(np.ptp(w0, axis=0).max(), 1e-300)
    low = w0[:, 2] <= w0[:, 2].min() + 1e-6 * size
    b = v[low].mean(axis=0) if low.any() else base_point(v)
    bw = pos + np.einsum("nij,j->ni", R, b)
    d = bw[:, :2] - bw[0, :2]
    return np.hypot(d[:, 0], d[:, 1])


def peak_horizontal(a):
    a = np.asarray(a, float)
    if a.ndim == 1:
        return float(np.max(np.abs(a))) if a.size else float("nan")
    return float(np.max(np.hypot(a[:, 0], a[:, 1]))) if a.size else float("nan")


def _arr(s, key, k, default=float("nan")):
    if key not in s:
        return default
    a = np.atleast_1d(s[key])
    return a[k].item() if k < a.size else default


def run_rows(path):
    """Rows (dicts) for one run file, one per free body."""
    with Run(path) as r:
        names = r.body_names()
        s = r.summary()
        g = r.ground_attrs()
        gt = r.ground_text_attrs()
        title = r.title
        status = s.get("status", "no-summary")
        dt = float(s.get("dt", r.attr("dt", float("nan"))))
        t = r.time()
        end_time = float(s.get("end_time", t[-1] if t.size else float("nan")))
        eres = float(s.get("energy_residual_max", float("nan")))
        comps = [c for c in ("h1", "h2") if c + "_pga" in g]
        if "pga" in g or "pgv" in g:
            pga, pgv, src = g.get("pga", float("nan")), g.get("pgv", float("nan")), "attrs"
        elif comps:  # records: per-component IMs of the whole record (rd_h5_ground_im)
            pga = max(g[c + "_pga"] for c in comps)
            pgv = max(g.get(c + "_pgv", float("nan")) for c in comps)
            src = "attrs:" + ("h1" if comps == ["h1"] else "max(%s)" % ",".join(comps))
        else:
            acc = r.data("ground/acceleration")
            pga = peak_horizontal(acc)
            pgv = peak_horizontal(r.data("ground/velocity"))
            # a run that stopped early (overturned with stop on, interrupted, unstable) while the
            # ground was still moving saw only part of the motion: its peaks may be too low
            moving = acc.size and np.any(acc[-1] != 0)
            src = "computed-partial" if status != "done" and moving else "computed"
        rows = []
        for k, name in enumerate(names):
            row = dict(file=path, title=title, body=name, status=status, dt=dt,
                       end_time=end_time, energy_residual=eres, pga=pga, pgv=pgv,
                       pgv_pga=(pgv / pga) if pga and pga > 0 else float("nan"), im_source=src,
                       overrides="; ".join(r.overrides()))
            if s:
                row.update(overturned=int(_arr(s, "overturned", k, 0)),
                           overturn_time=_arr(s, "overturn_time", k),
                           max_tilt=_arr(s, "max_tilt", k),
                           max_tilt_ratio=_arr(s, "max_tilt_ratio", k),
                           max_slide=_arr(s, "max_slide", k),
                           final_slide=_arr(s, "final_slide", k),
                           uplifted=int(_arr(s, "uplifted", k, 0)),
                           slid=int(_arr(s, "slid", k, 0)))
            else:  # no summary: from the time series and the events
                tilt = r.data("tilt")[:, k]
                alpha = r.body_attr(name, "alpha", float("nan"))
                sl = slide_series(r, k, name)
                ev = [e for e in r.events() if e[1] == k]
                over = [e[0] for e in ev if e[2] == "overturn"]
                rec = [e[0] for e in ev if e[2] == "recover"]
                is_over = bool(over) and (not rec or rec[-1] < over[-1])
                row.update(overturned=int(is_over), overturn_time=over[-1] if is_over else -1.0,
                           max_tilt=float(tilt.max()), max_tilt_ratio=float(tilt.max() / alpha),
                           max_slide=float(sl.max()), final_slide=float(sl[-1]),
                           uplifted=int(any(e[2] == "uplift" for e in ev)),
                           slid=int(any(e[2] == "slip" for e in ev)))
            # 'overturned' is the criterion at the end of the run; with 'stop off' a body that fell
            # and tumbled on can end below the criterion. ever_overturned: any overturn event.
            row["ever_overturned"] = int(row["overturned"] or any(
                e[1] == k and e[2] == "overturn" for e in r.events()))
            for key, val in g.items():
                if key not in ("pga", "pgv"):
                    row[key] = val
            row.update(gt)
            rows.append(row)
        return rows


def columns_of(rows):
    cols = list(BASE_COLUMNS)
    for r in rows:
        for k in r:
            if k not in cols:
                cols.append(k)
    return cols


def fmt(v):
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        return "%.6g" % v
    return str(v)


def write_csv(rows, path):
    cols = columns_of(rows)
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(cols)
        for r in rows:
            w.writerow([fmt(r.get(c, "")) for c in cols])


def print_table(rows, out, columns=None):
    cols = columns or ["file", "body", "overturned", "overturn_time", "max_tilt", "max_tilt_ratio",
                       "max_slide", "status", "dt", "energy_residual", "pga", "pgv", "title"]
    cells = [[os.path.basename(fmt(r.get(c, ""))) if c == "file" else fmt(r.get(c, "")) for c in cols]
             for r in rows]
    width = [max([len(c)] + [len(x[i]) for x in cells]) for i, c in enumerate(cols)]
    out.write("  ".join(c.ljust(w) for c, w in zip(cols, width)).rstrip() + "\n")
    for x in cells:
        out.write("  ".join(c.ljust(w) for c, w in zip(x, width)).rstrip() + "\n")


def read_csv(path):
    """(columns, list of dict rows) from a CSV file; RDError on a missing/empty file."""
    if not os.path.exists(path):
        raise RDError("%s: no such file" % path)
    with open(path, newline="") as fh:
        try:
            rd = csv.DictReader(fh)
            rows = list(rd)
        except (csv.Error, UnicodeDecodeError) as e:
            raise RDError("%s: not a readable CSV file: %s" % (path, e))
        if not rd.fieldnames:
            raise RDError("%s: empty CSV file (no header line)" % path)
        return [c.strip() for c in rd.fieldnames], [{k.strip(): (v or "").strip() for k, v in r.items() if k} for r in rows]
