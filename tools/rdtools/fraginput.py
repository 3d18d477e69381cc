"""Input of rdfragility: one table of runs with pga (m/s^2), pgv (m/s), overturned (0/1; another
0/1 column can be chosen as the outcome, e.g. ever_overturned) and optionally an observed outcome
column, from any mix of:

  *.csv          the CSV written by rdtable.py --csv (or any CSV with columns pga, pgv,
                 overturned; more columns are fine: body, observed, ...)
  sweep HDF5     a file with /sweep: either a compound dataset with fields pga, pgv, overturned
                 (+ optional observed, body, ...) or a group of equal-length 1-D datasets of those
                 names. PGA in m/s^2 and PGV in m/s (SI, as everywhere in rockdem); a 'units'
                 attribute 'g' on the pga field's dataset (group form) or a /sweep attribute
                 pga_units='g' converts from g.
  rockdem runs   HDF5 files written by 'rockdem run' (rows made as rdtable does)."""
import numpy as np

from . import RDError
from .runfile import open_h5, is_rockdem, as_str, enum_names, h5py
from .table import read_csv, run_rows

G = 9.80665
TRUE = {"1", "true", "yes", "y", "t", "o", "overturned"}
FALSE = {"0", "false", "no", "n", "f", "not"}


def parse_bool(v, where):
    s = str(v).strip().lower()
    if s in TRUE:
        return 1
    if s in FALSE:
        return 0
    try:
        x = float(s)
    except ValueError:
        raise RDError("%s: expected 0/1 (or true/false), got '%s'" % (where, v))
    if x in (0.0, 1.0):
        return int(x)
    raise RDError("%s: expected 0/1 (or true/false), got '%s'" % (where, v))


def parse_float(v, where):
    try:
        return float(v)
    except (TypeError, ValueError):
        raise RDError("%s: expected a number, got '%s'" % (where, v))


def _rows_from_csv(path, observed, outcome="overturned"):
    cols, rows = read_csv(path)
    need = [c for c in ("pga", "pgv", outcome) if c not in cols]
    if need:
        raise RDError("%s: missing column%s %s (expected pga, pgv, overturned: the CSV of "
                      "rdtable.py --csv)" % (path, "s" if len(need) > 1 else "", ", ".join(need)))
    if observed and observed not in cols:
        raise RDError("%s: no column '%s' for --observed" % (path, observed))
    out = []
    for i, r in enumerate(rows, start=2):
        w = "%s:%d" % (path, i)
        d = dict(pga=parse_float(r["pga"], w + ": pga"), pgv=parse_float(r["pgv"], w + ": pgv"),
                 overturned=parse_bool(r[outcome], w + ": " + outcome),
                 body=r.get("body", ""), source=path, im_source=r.get("im_source", ""), cols=r)
        if observed:
            d["observed"] = parse_bool(r[observed], w + ": " + observed)
        out.append(d)
    return out


def _rows_from_sweep(path, f, observed, outcome="overturned"):
    s = f["sweep"]
    scale = G if as_str(s.attrs.get("pga_units", "")).strip().lower() == "g" else 1.0
    if isinstance(s, h5py.Dataset):
        a = s[()]
        if a.dtype.names is None:
            raise RDError("%s: /sweep is not a compound table (fields pga, pgv, overturned)" % path)
        fields = {k: a[k] for k in a.dtype.names}
    else:
        fields = {}
        for k in s:
            d = s[k]
            if not isinstance(d, h5py.Dataset) or d.ndim != 1:
                continue
            if k in ("body", "fence") and as_str(d.attrs.get("CLASS", b"")) == "DIMENSION_SCALE":
                continue  # the per-body (layout 2) or per-fence (layout 5) axis, not a row column
            fields[k] = d[()]
            names = enum_names(d.dtype)
            if names:  # status (layout 2): an HDF5 enum, compared by name (--where status=done)
                fields[k] = np.array([names.get(int(v), str(v)) for v in fields[k]], dtype=object)
                if k == "pga" and as_str(s[k].attrs.get("units", "")).strip().lower() == "g":
                    scale = G
    need = [c for c in ("pga", "pgv", outcome) if c not in fields]
    if need:
        raise RDError("%s: /sweep lacks field%s %s (expected pga, pgv, overturned)"
                      % (path, "s" if len(need) > 1 else "", ", ".join(need)))
    if observed and observed not in fields:
        raise RDError("%s: /sweep has no field '%s' for --observed" % (path, observed))
    n = len(fields["pga"])
    if any(len(v) != n for v in fields.values()):
        raise RDError("%s: /sweep fields differ in length" % path)
    out = []
    for i in range(n):
        d = dict(pga=float(fields["pga"][i]) * scale, pgv=float(fields["pgv"][i]),
                 overturned=parse_bool(fields[outcome][i], "%s:/sweep[%d].%s" % (path, i, outcome)),
                 body=as_str(fields["body"][i]) if "body" in fields else "", source=path,
                 cols={k: v[i] for k, v in fields.items()})
        if observed:
            d["observed"] = parse_bool(fields[observed][i], "%s:/sweep[%d].%s" % (path, i, observed))
        out.append(d)
    return out


def _matches(value, want):
    """A table cell equals the text of --where: numerically if both are numbers."""
    try:
        return float(value) == float(want)
    except (TypeError, ValueError):
        return as_str(value) == want


def select(rows, where):
    """Rows whose column COL equals VALUE for every "COL=VALUE" in where (sweep tables, CSVs)."""
    for w in where or []:
        col, sep, want = w.partition("=")
        if not sep or not col:
            raise RDError("--where: expected COL=VALUE, got '%s'" % w)
        if any(col not in r.get("cols", {}) for r in rows):
            raise RDError("--where: no column '%s' in the input" % col)
        rows = [r for r in rows if _matches(r["cols"][col], want)]
        if not rows:
            raise RDError("--where %s: no rows left" % w)
    return rows


def load(paths, observed=None, body=None, outcome="overturned"):
    """Rows (dicts pga, pgv, overturned[, observed], body, source) from the given files.
    observed: column name, or None; 'auto' uses a column called 'observed' only where present."""
    rows = []
    for p in paths:
        obs = observed
        if p.lower().endswith(".csv"):
            if obs == "auto":
                cols, _ = read_csv(p)
                obs = "observed" if "observed" in cols else None
            rows += _rows_from_csv(p, obs, outcome)
            continue
        f = open_h5(p, "sweep table or rockdem run")
        try:
            if "sweep" in f:
                if obs == "auto":
                    s = f["sweep"]
                    names = s.dtype.names if isinstance(s, h5py.Dataset) else list(s)
                    obs = "observed" if names and "observed" in names else None
                rows += _rows_from_sweep(p, f, obs, outcome)
                continue
            if not is_rockdem(f):
                raise RDError("%s: neither a sweep table (/sweep) nor a rockdem run file" % p)
        finally:
            f.close()
        if obs and obs != "auto":
            raise RDError("%s: a single run has no observed outcome; give a CSV with a '%s' "
                          "column" % (p, obs))
        for r in run_rows(p):
            if outcome not in r:
                raise RDError("%s: a run has no outcome '%s' (use overturned or ever_overturned)"
                              % (p, outcome))
            rows.append(dict(pga=r["pga"], pgv=r["pgv"], overturned=int(r[outcome]),
                             body=r["body"], source=p, im_source=r["im_source"]))
    partial = sum(1 for r in rows if r.get("im_source") == "computed-partial")
    if partial:
        import sys
        sys.stderr.write("rdfragility: warning: %d rows have pga/pgv computed from a run that "
                         "stopped early (im_source computed-partial): the peaks may be too low; "
                         "run with 'model overturn ... stop off' or give the record's IMs\n" % partial)
    if body:
        rows = [r for r in rows if r["body"] == body]
        if not rows:
            raise RDError("no rows for body '%s'" % body)
    return rows


def arrays(rows):
    pga = np.array([r["pga"] for r in rows], float)
    pgv = np.array([r["pgv"] for r in rows], float)
    y = np.array([r["overturned"] for r in rows], float)
    obs = (np.array([r["observed"] for r in rows], float)
           if rows and all("observed" in r for r in rows) else None)
    ok = np.isfinite(pga) & np.isfinite(pgv) & (pga > 0) & (pgv > 0)
    return pga, pgv, y, obs, ok
