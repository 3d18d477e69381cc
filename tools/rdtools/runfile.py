"""Open a rockdem run file (layout: docs/HDF5-LAYOUT.md) and read it with clear errors.

Run(path) validates that the file exists, is HDF5, carries the root attribute program='rockdem',
and gives accessors that raise RDError('FILE: missing dataset /x') instead of KeyError."""
import os

import numpy as np

from . import RDError

try:
    import h5py
except ImportError:  # the python3 first on PATH has no h5py; Debian's /usr/bin/python3 has
    raise SystemExit("rdtools: needs h5py: run with /usr/bin/python3 (Debian python3-h5py)")

ENERGY_NAMES = ("kinetic", "gravitational", "elastic", "friction", "damping", "ground_work",
                "residual")


def as_str(v):
    """HDF5 strings come back as bytes, str or 0-d arrays; make them str."""
    if isinstance(v, np.ndarray) and v.shape == ():
        v = v[()]
    if isinstance(v, (bytes, np.bytes_)):
        return v.decode("utf-8", "replace").rstrip("\0")
    return str(v)


def enum_names(dtype):
    """{value: name} of an HDF5 enum dtype (h5py), {} for any other dtype."""
    m = h5py.check_enum_dtype(dtype)
    return {int(v): k for k, v in m.items()} if m else {}


def decoded_attrs(obj):
    """Attributes of an h5py object as a dict: strings as str, enum values by their names;
    the '<name>_units' companions of layout 2 are left out (see attr_units)."""
    out = {}
    for k in obj.attrs:
        if k.endswith("_units") and k[:-6] in obj.attrs:
            continue
        v = obj.attrs[k]
        names = enum_names(obj.attrs.get_id(k).dtype)
        if names:
            v = names.get(int(np.asarray(v).reshape(())), str(v))
        elif isinstance(v, (bytes, np.bytes_, str)):
            v = as_str(v)
        out[k] = v
    return out


def attr_units(obj, name, default=""):
    """Units of attribute name on obj: its '<name>_units' companion (layout 2)."""
    u = obj.attrs.get(name + "_units")
    return as_str(u) if u is not None else default


def open_h5(path, what="file"):
    """h5py.File(path, 'r') with one-line errors for a missing or non-HDF5 file."""
    if not os.path.exists(path):
        raise RDError("%s: no such file" % path)
    if os.path.isdir(path):
        raise RDError("%s: is a folder, expected an HDF5 %s" % (path, what))
    try:
        ok = h5py.is_hdf5(path)
    except OSError as e:
        raise RDError("%s: cannot read: %s" % (path, e.strerror or e))
    if not ok:
        raise RDError("%s: not an HDF5 file" % path)
    try:
        return h5py.File(path, "r")
    except OSError as e:
        raise RDError("%s: cannot open as HDF5: %s" % (path, e))


def is_rockdem(f):
    return as_str(f.attrs.get("program", b"")) == "rockdem"


class Run:
    """A rockdem run file, opened read-only. Use as a context manager or call close()."""

    def __init__(self, path):
        self.path = path
        self.f = open_h5(path, "rockdem run file")
        if not is_rockdem(self.f):
            self.f.close()
            raise RDError("%s: not a rockdem run file (no root attribute program='rockdem')" % path)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self.f.close()

    # ---- generic access ----
    def has(self, name):
        return name in self.f

    def data(self, name):
        """The whole dataset as a numpy array; RDError if absent."""
        if name not in self.f:
            raise RDError("%s: missing dataset /%s" % (self.path, name.lstrip("/")))
        obj = self.f[name]
        if not isinstance(obj, h5py.Dataset):
            raise RDError("%s: /%s is not a dataset" % (self.path, name.lstrip("/")))
        return obj[()]

    def attr(self, name, default=None, obj="/"):
        a = self.f[obj].attrs if obj in self.f else {}
        if name not in a:
            return default
        v = a[name]
        if isinstance(v, (bytes, np.bytes_, str)) or (isinstance(v, np.ndarray) and v.dtype.kind in "SOU"):
            return as_str(v) if not (isinstance(v, np.ndarray) and v.shape) else [as_str(x) for x in v]
        return v

    # ---- rockdem specifics ----
    @property
    def title(self):
        return self.attr("title", "") or ""

    def overrides(self):
        """The command-line overrides of the run ('--set key=value' lines rockdem appends to the
        scenario text as '; --set ...'), e.g. ['motion.amplitude=1.1g']."""
        text = self.attr("scenario", "") or ""
        return [ln.strip()[len("; --set "):].strip() for ln in text.splitlines()
                if ln.strip().startswith("; --set ")]

    def body_names(self):
        names = self.data("bodies/names")
        return [as_str(n) for n in np.atleast_1d(names)]

    def time(self):
        return self.data("time")

    def nsamples(self):
        return self.data("time").shape[0]

    def bodies(self):
        """Every body's mass, geometry and precariousness (rdtools.bodies.Bodies), either layout."""
        if getattr(self, "_bodies", None) is None:
            from .bodies import Bodies
            self._bodies = Bodies(self.f)
        return self._bodies

    def body_geometry(self, name):
        """(vertices [nv,3] body frame about the centre of mass, faces [nf,3] int)."""
        b = self.bodies()
        if name not in b or b.vertices(name) is None or b.faces(name) is None:
            raise RDError("%s: /bodies has no vertices and faces of '%s'" % (self.path, name))
        v, fc = b.vertices(name).astype(float), b.faces(name).astype(np.int64)
        if v.ndim != 2 or v.shape[1] != 3 or fc.ndim != 2 or fc.shape[1] != 3:
            raise RDError("%s: /bodies: vertices/faces of '%s' must be [n][3]" % (self.path, name))
        if fc.size and (fc.min() < 0 or fc.max() >= len(v)):
            raise RDError("%s: /bodies: faces of '%s': vertex index out of range" % (self.path, name))
        return v, fc

    def body_attr(self, name, key, default=None):
        return self.bodies().attr(name, key, default)

    def tilt_ratio(self, k, name):
        """tilt / alpha of free body k (named name) at every sample, alpha being the static
        tipping angle towards the side the body leans to (its precariousness table, any shape)
        as in the summary's max_tilt_ratio; without a table, the summary's (least) alpha. None
        when neither is known."""
        from .rotation import alpha_toward, lean_direction
        tilt = self.data("tilt")[:, k]
        prec = self.bodies().precariousness(name)
        if prec is not None and prec.shape[0] >= 3:
            psi = lean_direction(self.data("quaternion")[:, k, :])
            return tilt / alpha_toward(prec, psi)
        a = np.atleast_1d(np.asarray(self.summary().get("alpha", [np.nan] * (k + 1)), float))
        a = a[k] if k < len(a) else np.nan
        if not (a > 0):
            a = float(self.body_attr(name, "alpha", np.nan))
        return tilt / a if a > 0 else None

    def energies(self):
        """dict name -> [N] array for the /energy datasets present (in the canonical order).
        The dimension scales linked into the group for netCDF readers (/energy/time, the same
        dataset as /time) are coordinates, not energies, and are left out."""
        if "energy" not in self.f:
            raise RDError("%s: missing group /energy" % self.path)
        out = {}
        for k in ENERGY_NAMES:
            if "energy/" + k in self.f:
                out[k] = self.f["energy/" + k][()]
        for k, d in self.f["energy"].items():
            scale = d.attrs.get("CLASS") == b"DIMENSION_SCALE"
            if k not in out and isinstance(d, h5py.Dataset) and not scale:
                out[k] = d[()]
        return out

    def events(self):
        """list of (time, body index, type str, value); [] if the run has no /events. Reads the
        /events group of layout 2 (columns, type an HDF5 enum) and the compound table of
        layout 1."""
        if "events" not in self.f:
            return []
        g = self.f["events"]
        if isinstance(g, h5py.Group):
            if not {"time", "body_index", "type", "value"} <= set(g):
                raise RDError("%s: /events lacks its columns (time, body_index, type, value)" % self.path)
            names = enum_names(g["type"].dtype)
            return [(float(t), int(b), names.get(int(ty), str(ty)), float(v))
                    for t, b, ty, v in zip(g["time"][()], g["body_index"][()], g["type"][()],
                                           g["value"][()])]
        ev = g[()]
        if ev.dtype.names is None or not {"time", "body", "type"} <= set(ev.dtype.names):
            raise RDError("%s: /events is not the compound table (time, body, type, value)" % self.path)
        val = ev["value"] if "value" in ev.dtype.names else np.zeros(len(ev))
        return [(float(t), int(b), as_str(ty), float(v))
                for t, b, ty, v in zip(ev["time"], ev["body"], ev["type"], val)]

    def summary(self):
        """dict of /summary attributes (strings and enums decoded to str, '<name>_units'
        companions left out); {} if the run wrote no summary."""
        if "summary" not in self.f:
            return {}
        return decoded_attrs(self.f["summary"])

    def ground_attrs(self):
        """Intensity-measure attributes on /ground (pga, pgv, ...), numeric scalars only."""
        if "ground" not in self.f:
            return {}
        out = {}
        for k, v in self.f["ground"].attrs.items():
            a = np.asarray(v)
            if a.dtype.kind in "fiu" and a.size == 1:
                out[k] = float(a.reshape(()))
        return out

    def ground_text_attrs(self):
        """String attributes on /ground (h1_record, h1_source, ...)."""
        if "ground" not in self.f:
            return {}
        return {k: as_str(v) for k, v in self.f["ground"].attrs.items()
                if isinstance(v, (bytes, np.bytes_, str))}
