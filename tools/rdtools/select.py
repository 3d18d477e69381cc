"""Ground-motion selection from a user's flatfile (the NGA-West2 flatfile's columns, or a PEER
search-results CSV): filter by magnitude, rupture distance, Vs30 and mechanism, draw N records
that have both horizontal components (and the vertical where present or required), read their
AT2 files and write them as one record set in the FEMA P695 layout that `rockdem` reads:

    /_timeseries/<RSN>/a|b|v/Time                  [n] s
    /_timeseries/<RSN>/a|b|v/RecordedAcceleration  [n] g

so that `rockdem sweep SCENE --axis motion.record=RSN1,RSN2,...` runs every record with its
own pair of horizontals (and vertical) together, scaled and turned as the sweep says.

API: read_flatfile(path) -> rows; choose(rows, ranges, n, seed, vertical) -> rows;
read_at2(path) -> (acc in g, dt); write_set(rows, out, base_dir); scenario_text(...)."""
import csv
import os
import re

import numpy as np

from . import RDError

# column aliases: NGA-West2 flatfile first, then PEER search results, then plain names
COLUMNS = {
    "id": ("Record Sequence Number", "RSN", "record", "record_id"),
    "M": ("Earthquake Magnitude", "Magnitude", "M", "magnitude"),
    "Rrup": ("ClstD (km)", "Rrup (km)", "Rrup", "rrup"),
    "Vs30": ("Vs30 (m/s) selected for analysis", "Vs30 (m/sec)", "Vs30", "vs30"),
    "mechanism": ("Mechanism Based on Rake Angle", "Mechanism", "mechanism"),
    "h1": ("File Name (Horizontal 1)", "Horizontal-1 Acc. Filename", "h1"),
    "h2": ("File Name (Horizontal 2)", "Horizontal-2 Acc. Filename", "h2"),
    "v": ("File Name (Vertical)", "Vertical Acc. Filename", "vertical", "v"),
}
# NGA-West2 mechanism codes (Ancheta et al. 2014) and the names a user may write
MECHANISMS = {0: "strike-slip", 1: "normal", 2: "reverse", 3: "reverse-oblique", 4: "normal-oblique"}
UNITS = {"g": 1.0, "cm/sec/sec": 1.0 / 980.665, "cm/s/s": 1.0 / 980.665, "cm/s^2": 1.0 / 980.665,
         "m/sec/sec": 1.0 / 9.80665, "m/s/s": 1.0 / 9.80665, "m/s^2": 1.0 / 9.80665}


def _mech_name(v):
    s = str(v).strip()
    try:
        return MECHANISMS[int(float(s))]
    except (ValueError, KeyError):
        return s.lower().replace(" ", "-").replace("_", "-")


def read_flatfile(path):
    """Rows (dicts id, M, Rrup, Vs30, mechanism, h1, h2, v, line) of a flatfile CSV."""
    try:
        fh = open(path, newline="", encoding="utf-8-sig")
    except OSError as e:
        raise RDError("%s: %s" % (path, e.strerror))
    with fh:
        r = csv.DictReader(fh)
        head = r.fieldnames or []
        col = {}
        for key, names in COLUMNS.items():
            hit = [h for h in head if h.strip() in names]
            if hit:
                col[key] = hit[0]
            elif key != "v":
                raise RDError("%s: no %s column (expected one of: %s)" % (path, key, "; ".join(names)))
        rows = []
        for i, row in enumerate(r, start=2):
            d = dict(line=i)
            for key in ("M", "Rrup", "Vs30"):
                try:
                    d[key] = float(row[col[key]])
                except (TypeError, ValueError):
                    raise RDError("%s:%d: %s: expected a number, got '%s'" % (path, i, col[key], row[col[key]]))
            d["id"] = str(row[col["id"]]).strip()
            if not re.fullmatch(r"[A-Za-z0-9_.-]{1,64}", d["id"]):
                raise RDError("%s:%d: record id '%s': expected 1-64 letters, digits, _ . -" % (path, i, d["id"]))
            d["mechanism"] = _mech_name(row[col["mechanism"]])
            for key in ("h1", "h2", "v"):
                d[key] = (row.get(col[key]) or "").strip() if key in col else ""
            rows.append(d)
    ids = [d["id"] for d in rows]
    dup = sorted({x for x in ids if ids.count(x) > 1})
    if dup:
        raise RDError("%s: record id %s appears more than once" % (path, dup[0]))
    return rows


def parse_range(text, what):
    """'LO:HI' (either side may be empty) -> (lo, hi)."""
    lo, sep, hi = text.partition(":")
    if not sep:
        raise RDError("--%s: expected LO:HI, got '%s'" % (what, text))
    try:
        return (float(lo) if lo.strip() else -np.inf, float(hi) if hi.strip() else np.inf)
    except ValueError:
        raise RDError("--%s: expected numbers LO:HI, got '%s'" % (what, text))


def choose(rows, ranges=None, mechanisms=None, n=None, seed=1, vertical="auto"):
    """Rows inside every (lo, hi) of ranges {M, Rrup, Vs30} and of mechanisms (names), with both
    horizontal files (and a vertical one for vertical='require'); then n of them drawn without
    replacement (numpy default_rng(seed)), in flatfile order; all if n is None."""
    out = []
    for d in rows:
        if any(not (lo <= d[k] <= hi) for k, (lo, hi) in (ranges or {}).items()):
            continue
        if mechanisms and d["mechanism"] not in mechanisms:
            continue
        if not d["h1"] or not d["h2"]:
            continue
        if vertical == "require" and not d["v"]:
            continue
        out.append(d)
    if not out:
        raise RDError("no record of the flatfile passes the filters")
    if n is not None:
        if n > len(out):
            raise RDError("asked for %d records but only %d pass the filters" % (n, len(out)))
        pick = np.sort(np.random.default_rng(seed).choice(len(out), n, replace=False))
        out = [out[i] for i in pick]
    return out


def read_at2(path):
    """A PEER NGA-West2 AT2 file: (acceleration in g, dt s). The 3rd header line must say the
    units (g, cm/sec/sec, m/sec/sec) of an ACCELERATION series; velocity and displacement
    files are refused."""
    try:
        with open(path) as fh:
            lines = fh.read().splitlines()
    except OSError as e:
        raise RDError("%s: %s" % (path, e.strerror))
    if len(lines) < 5:
        raise RDError("%s: not an AT2 file (fewer than 5 lines)" % path)
    h3 = lines[2].upper()
    if "VELOCITY" in h3 or "DISPLACEMENT" in h3:
        raise RDError("%s:3: a %s time series, not an acceleration" % (
            path, "velocity" if "VELOCITY" in h3 else "displacement"))
    m = re.search(r"UNITS OF\s+(\S+)", h3)
    unit = m.group(1).lower() if m else "g"
    if unit not in UNITS:
        raise RDError("%s:3: unknown units '%s' (expected G, CM/SEC/SEC or M/SEC/SEC)" % (path, unit))
    mn = re.search(r"NPTS\s*=\s*(\d+)", lines[3], re.I)
    md = re.search(r"DT\s*=\s*([0-9.eE+-]+)", lines[3], re.I)
    if not mn or not md:
        nums = re.findall(r"[0-9.eE+-]+", lines[3])
        if len(nums) < 2:
            raise RDError("%s:4: expected NPTS= and DT=" % path)
        npts, dt = int(float(nums[0])), float(nums[1])
    else:
        npts, dt = int(mn.group(1)), float(md.group(1))
    if not dt > 0:
        raise RDError("%s:4: DT %g s must be positive" % (path, dt))
    vals = []
    for i, ln in enumerate(lines[4:], start=5):
        for tok in ln.split():
            try:
                vals.append(float(tok))
            except ValueError:
                raise RDError("%s:%d: expected a number, got '%s'" % (path, i, tok))
    if len(vals) != npts:
        raise RDError("%s: NPTS says %d values but the file has %d" % (path, npts, len(vals)))
    a = np.asarray(vals) * UNITS[unit]
    if not np.all(np.isfinite(a)):
        raise RDError("%s: a value is not a finite number" % path)
    return a, dt


def write_set(rows, out, base_dir, vertical="auto"):
    """Write the chosen records to the HDF5 set `out` (FEMA P695 layout, a = h1, b = h2, v =
    vertical). Returns whether every record got a vertical (then the scenario reads it)."""
    import h5py
    with_v = vertical != "off" and all(d["v"] for d in rows)
    with h5py.File(out, "w") as f:
        f.attrs["source"] = "rdfragility select (rockdem)"
        for d in rows:
            for comp, key in (("a", "h1"), ("b", "h2"), ("v", "v")):
                if key == "v" and not (vertical != "off" and d["v"]):
                    continue
                path = d[key] if os.path.isabs(d[key]) else os.path.join(base_dir, d[key])
                a, dt = read_at2(path)
                g = f.create_group("_timeseries/%s/%s" % (d["id"], comp))
                g["Time"] = np.arange(len(a)) * dt
                g["RecordedAcceleration"] = a
                g.attrs["file"] = os.path.basename(path)
            f["_timeseries/" + d["id"]].attrs.update(
                M=d["M"], Rrup_km=d["Rrup"], Vs30_m_s=d["Vs30"], mechanism=d["mechanism"])
    return with_v


def scenario_text(base_text, base_dir, set_path, first_id, with_v):
    """The user's scenario with its ground-motion commands (and their '&' continuation lines)
    replaced by imports of the set's record first_id (a -> h1, b -> h2, v -> vertical); quoted
    paths of existing files (meshes) made absolute against base_dir, so the scenario can be
    written anywhere. The sweep's --axis motion.record=... changes the id."""
    keep, dropping = [], False
    for ln in base_text.splitlines():
        code = ln.split(";", 1)[0].rstrip()
        if dropping or re.match(r"\s*ground-motion\b", ln):
            dropping = code.endswith("&")
            continue

        def absolute(m):
            p = m.group(1)
            full = p if os.path.isabs(p) else os.path.join(base_dir, p)
            return "'%s'" % os.path.abspath(full) if os.path.isfile(full) else m.group(0)
        keep.append(ln if ln.lstrip().startswith(";") else re.sub(r"'([^']+)'", absolute, ln))
    comps = ("a", "b", "v") if with_v else ("a", "b")
    keep += ["; records drawn by rdfragility select: the sweep's --axis motion.record=... picks one"]
    keep += ["ground-motion import '%s' record %s component %s" % (os.path.abspath(set_path), first_id, c)
             for c in comps]
    return "\n".join(keep) + "\n"
