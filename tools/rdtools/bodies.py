"""Every body of a rockdem run file (/bodies, docs/HDF5-LAYOUT.md), whatever its layout.

Layout 3 stores one row per body over the axis `block` (/bodies/block: the free bodies in /body
order, then the fixed ones) and the vertices, triangles and precariousness rows of all bodies
concatenated in block order, with a count per block (vertex_count, face_count, lean_count: the
CF contiguous ragged array). Layout 2 (and tools/yade/translate.py's files) gave each body a
group /bodies/<name> with attributes and its own tables. Bodies(f) reads either the same way:

    b = Bodies(h5py_file)
    b.names                      # every body, block order
    b.attr("rock", "mass")       # a per-body value (None when absent)
    b.vertices("rock"), b.faces("rock"), b.precariousness("rock")   # arrays, or None
"""
import numpy as np


def _str(v):
    return v.decode("utf-8", "replace") if isinstance(v, (bytes, np.bytes_)) else str(v)


def _is_group(obj):
    return hasattr(obj, "keys")


class Bodies:
    """The bodies of an open h5py.File f (read lazily, each table at most once)."""

    def __init__(self, f):
        self.f = f
        self.g = f["bodies"] if "bodies" in f else None
        self.tables = self.g is not None and "block" in self.g and not _is_group(self.g["block"])
        self._cache = {}
        if self.tables:
            self.names = [_str(n) for n in np.atleast_1d(self.g["block"][()])]
        elif self.g is not None:
            free = [_str(n) for n in np.atleast_1d(self.g["names"][()])] if "names" in self.g else []
            groups = [k for k in self.g if _is_group(self.g[k])]
            self.names = [n for n in free if n in groups] + [n for n in groups if n not in free]
        else:
            self.names = []
        self._index = {n: k for k, n in enumerate(self.names)}

    def __contains__(self, name):
        return name in self._index

    def _table(self, key):
        if key not in self._cache:
            self._cache[key] = self.g[key][()] if key in self.g else None
        return self._cache[key]

    def _rows(self, name, key, count):
        """Body name's rows of the concatenated table key (None when absent)."""
        t, c = self._table(key), self._table(count)
        if t is None or c is None:
            return None
        if count + "/start" not in self._cache:
            self._cache[count + "/start"] = np.concatenate([[0], np.cumsum(c)])
        start, k = self._cache[count + "/start"], self._index[name]
        return t[start[k]:start[k + 1]]

    def attr(self, name, key, default=None):
        """The per-body value key (mass, inertia_principal, size, alpha, fixed, position,
        quaternion) of body name; default when the file has none."""
        if name not in self._index:
            return default
        if self.tables:
            t = self._table(key)
            return t[self._index[name]] if t is not None and len(t) == len(self.names) else default
        return self.g[name].attrs.get(key, default)

    def _own(self, name, key, count):
        if name not in self._index:
            return None
        if self.tables:
            return self._rows(name, key, count)
        g = self.g[name]
        return g[key][()] if key in g else None

    def vertices(self, name):
        """[nv, 3] body frame about the centre of mass, m."""
        return self._own(name, "vertices", "vertex_count")

    def faces(self, name):
        """[nf, 3] triangles, indices into the body's own vertices."""
        return self._own(name, "faces", "face_count")

    def precariousness(self, name):
        """[n, 3] lean direction (rad), alpha (rad), g tan(alpha) (m/s^2); None before rest."""
        return self._own(name, "precariousness", "lean_count")

    def fixed_names(self):
        return [n for n in self.names if int(self.attr(n, "fixed", 0)) == 1]
