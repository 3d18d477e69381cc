"""Reading what a run or a sweep wrote: numpy arrays (h5py) or xarray Datasets (h5netcdf), with
the HDF5 enums (status, event type) decoded to their names (docs/HDF5-LAYOUT.md)."""
from __future__ import annotations

import os
import sys
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

SERIES = ("position", "quaternion", "velocity", "angular_velocity", "tilt", "rotation")


def _h5py() -> Any:
    try:
        import h5py
    except ImportError:
        raise ImportError("rockdem: reading results needs h5py (Debian python3-h5py)")
    return h5py


def _xarray(need_h5netcdf: bool = True) -> Any:
    try:
        import xarray
        if need_h5netcdf:
            import h5netcdf  # noqa: F401 (the engine)
    except ImportError:
        raise ImportError("rockdem: datasets need xarray and h5netcdf (Debian python3-xarray, "
                          "python3-h5netcdf)")
    return xarray


def _decode_enum(h5py: Any, dset_or_dtype: Any, values: Any) -> Any:
    m = h5py.check_enum_dtype(getattr(dset_or_dtype, "dtype", dset_or_dtype))
    if not m:
        return values
    names = {int(v): k for k, v in m.items()}
    return np.array([names.get(int(v), str(v)) for v in np.atleast_1d(values)], dtype=object)


EVENT_DTYPE = np.dtype([("time", "f8"), ("body", "i4"), ("body_name", "U64"), ("type", "U16"),
                        ("value", "f8")])


def event_table(events: List[Tuple[float, int, str, float]], names: List[str]) -> Any:
    """Events (time s, body index, type, value) as a pandas DataFrame (columns time, body,
    body_name, type, value) when pandas is installed, else a numpy structured array with the
    same fields. body is the index among the free bodies, -1 for the whole scene."""
    rows = [(t, b, names[b] if 0 <= b < len(names) else "", ty, v) for t, b, ty, v in events]
    arr = np.array(rows, dtype=EVENT_DTYPE)
    try:
        import pandas
    except ImportError:
        return arr
    return pandas.DataFrame.from_records(arr)


class Run:
    """A finished run: summary (dict, from the library), events (a table: see event_table),
    histories (numpy arrays, in memory or from the run file at path), joints (a list of
    dicts), message (the cause of a failed or stopped run). A Run is plain data: it copies and
    pickles (multiprocessing) as any Python object."""

    def __init__(self, path: Optional[str], summary: Dict[str, Any],
                 events: List[Tuple[float, int, str, float]], samples: Optional[list] = None,
                 body_names: Optional[List[str]] = None, joints: Optional[list] = None,
                 message: str = "", precariousness: Optional[Dict[str, np.ndarray]] = None) -> None:
        self.path = path
        self.summary = summary
        self.event_list = list(events)
        self.names = list(body_names) if body_names is not None else list(summary["bodies"])
        self.events = event_table(self.event_list, self.names)
        self.joints = joints or []
        self.message = message
        self._samples = samples
        self._prec = precariousness or {}

    @property
    def status(self) -> str:
        """The run's status: done, overturned, interrupted, or a failure's name."""
        return self.summary["status"]

    def body_names(self) -> List[str]:
        """Free bodies, in output order (the body axis of every history)."""
        return list(self.names)

    def histories(self) -> Dict[str, np.ndarray]:
        """dict of numpy arrays: time [N] (s), position/velocity/angular_velocity [N][nb][3]
        (m, m/s, rad/s), quaternion [N][nb][4], tilt [N][nb] (rad), rotation [N][nb][3] (rad),
        tilt_ratio [N][nb] (tilt / alpha towards the lean, as the summary's max_tilt_ratio),
        ground_acceleration/velocity/displacement [N][3] (m/s^2, m/s, m), energy_<name> [N] (J).
        From memory when the run was made in this process, else from the run file."""
        if self._samples is not None:
            out = self._from_memory()
        elif self.path is not None:
            out = self._from_file()
        else:
            raise ValueError("rockdem: this Run has neither samples nor a file")
        out["tilt_ratio"] = self._tilt_ratio(out)
        return out

    def _from_memory(self) -> Dict[str, np.ndarray]:
        S, nb = self._samples, len(self.names)
        out = {"time": np.array([s["time"] for s in S])}
        shapes = {"position": 3, "quaternion": 4, "velocity": 3, "angular_velocity": 3,
                  "rotation": 3}
        for k in SERIES:
            shape = (len(S), nb) + ((shapes[k],) if k in shapes else ())
            out[k] = np.array([s[k] for s in S]).reshape(shape)
        for k in ("acceleration", "velocity", "displacement"):
            out["ground_" + k] = np.array([s["ground_" + k] for s in S]).reshape(len(S), 3)
        for k in (S[0]["energy"] if S else ()):
            out["energy_" + k] = np.array([s["energy"][k] for s in S])
        return out

    def _from_file(self) -> Dict[str, np.ndarray]:
        h5py = _h5py()
        out = {}
        with h5py.File(self.path, "r") as f:
            out["time"] = f["time"][()]
            for k in SERIES:
                out[k] = f[k][()]
            for g in ("ground", "energy"):   # not the dimension scales linked in for xarray
                for k, d in f[g].items():
                    if d.attrs.get("CLASS") != b"DIMENSION_SCALE":
                        out[g + "_" + k] = d[()]
            sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
            from rdtools.bodies import Bodies
            bodies = Bodies(f)
            for name in self.names:
                prec = bodies.precariousness(name) if name in bodies else None
                if name not in self._prec and prec is not None:
                    self._prec[name] = prec
        return out

    def _tilt_ratio(self, h: Dict[str, np.ndarray]) -> np.ndarray:
        """tilt / alpha towards the side each body leans to (its precariousness table), as the
        summary's max_tilt_ratio; the summary's least alpha where there is no table."""
        sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        from rdtools.rotation import alpha_toward, lean_direction
        ratio = np.full(h["tilt"].shape, np.nan)
        for k, name in enumerate(self.names):
            b = self.summary["bodies"][name]
            prec = self._prec.get(name)
            if prec is not None and prec.shape[0] >= 3:
                a = alpha_toward(prec, lean_direction(h["quaternion"][:, k, :]))
            else:
                a = b["alpha"] if b["alpha"] > 0 else np.nan
            ratio[:, k] = h["tilt"][:, k] / a
        return ratio

    def dataset(self, group: Optional[str] = None) -> Any:
        """The run as an xarray.Dataset (dims time, body, xyz, ...): the run file's group when
        there is a file, else the in-memory histories (root group only)."""
        if self.path is not None:
            return open_run(self.path, group)
        if group not in (None, "/"):
            raise ValueError("rockdem: a run without a file has only its root dataset")
        xr = _xarray(need_h5netcdf=False)
        h = self.histories()
        dims = {3: "xyz", 4: "wxyz"}
        data = {}
        for k, v in h.items():
            if k == "time":
                continue
            if k.startswith("ground_"):
                data[k] = (("time", "xyz"), v)
            elif k.startswith("energy_"):
                data[k] = (("time",), v, {"units": "J"})
            elif k == "rotation":
                data[k] = (("time", "body", "rotation_part"), v, {"units": "rad"})
            elif v.ndim == 3:
                data[k] = (("time", "body", dims[v.shape[2]]), v)
            else:
                data[k] = (("time", "body"), v)
        ds = xr.Dataset(data, coords={"time": ("time", h["time"], {"units": "s"}),
                                      "body": ("body", self.names)})
        for k in ("max_tilt", "max_tilt_ratio", "alpha", "max_slide", "overturned"):
            ds[k] = ("body", np.array([self.summary["bodies"][n][k] for n in self.names]))
        ds.attrs["status"] = self.status
        return ds

    def __repr__(self) -> str:
        b = ", ".join("%s: max tilt/alpha %.3g%s" % (n, d["max_tilt_ratio"],
                                                     " OVERTURNED" if d["overturned"] else "")
                      for n, d in self.summary["bodies"].items())
        return "<rockdem.Run %s: %s; %s>" % (self.path or "(in memory)", self.status, b)


def _inherited_coords(f: Any, group: str, ds: Any) -> Any:
    """ds with a coordinate for each of its dimensions that has none in its own group, taken
    from the nearest enclosing group holding a one-dimensional variable of that name (netCDF-4's
    inherited dimensions: /ground and /energy share the root's `time`, /history/body/NAME the
    `time` of /history, every group the root's `body` and `xyz`); strings decoded to str."""
    parts = [p for p in group.strip("/").split("/") if p]
    for dim in ds.dims:
        if dim in ds.coords:
            continue
        for k in range(len(parts) - 1, -1, -1):
            name = "/".join([""] + parts[:k] + [dim])
            if name in f and getattr(f[name], "ndim", 0) == 1 and f[name].shape[0] == ds.sizes[dim]:
                v = f[name][()]
                if v.dtype.kind in "SO":
                    v = np.array([x.decode("utf-8") if isinstance(x, bytes) else str(x) for x in v])
                attrs = {a: f[name].attrs[a] for a in ("units", "long_name") if a in f[name].attrs}
                ds = ds.assign_coords({dim: (dim, v, attrs)})
                break
    return ds


def open_run(path: Any, group: Optional[str] = None) -> Any:
    """A group of a run file as an xarray.Dataset with a coordinate on every dimension that has
    one in the file (its own group's, else the nearest enclosing group's: `time` on /ground,
    /energy and /history/*, body and joint names); for the root group the summary's per-body
    values are added as variables over `body` and the status is decoded (attrs['status'])."""
    xr, h5py = _xarray(), _h5py()
    ds = xr.open_dataset(os.fspath(path), engine="h5netcdf", group=group)
    with h5py.File(path, "r") as f:
        if group not in (None, "/"):
            ds = _inherited_coords(f, group, ds)
        if group in (None, "/") and "summary" in f:
            s = f["summary"]
            for k in s.attrs:
                v = s.attrs[k]
                if k.endswith("_units"):
                    continue
                if np.ndim(v) == 1 and len(v) == ds.sizes.get("body", -1):
                    ds[k] = ("body", np.asarray(v), {"units": str(s.attrs.get(k + "_units", ""))})
                elif k == "status":
                    ds.attrs["status"] = _decode_enum(h5py, s.attrs.get_id(k).dtype, v)[0]
        if group == "events":
            ds["type"] = ("event", _decode_enum(h5py, f["events/type"], ds["type"].values),
                          ds["type"].attrs)
    return ds


def open_sweep(path: Any) -> Any:
    """The /sweep table as an xarray.Dataset over `case` (status decoded to its names)."""
    xr, h5py = _xarray(), _h5py()
    ds = xr.open_dataset(os.fspath(path), engine="h5netcdf", group="sweep")
    with h5py.File(path, "r") as f:
        if "status" in f["sweep"]:
            ds["status"] = ("case", _decode_enum(h5py, f["sweep/status"], ds["status"].values),
                            ds["status"].attrs)
    return ds.load()
