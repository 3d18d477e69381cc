"""Reading what a run or a sweep wrote: numpy arrays (h5py) or xarray Datasets (h5netcdf), with
the HDF5 enums (status, event type) decoded to their names (docs/HDF5-LAYOUT.md)."""
import os

import numpy as np

SERIES = ("position", "quaternion", "velocity", "angular_velocity", "tilt", "rotation")


def _h5py():
    try:
        import h5py
    except ImportError:
        raise ImportError("rockdem: reading results needs h5py (Debian python3-h5py)")
    return h5py


def _xarray():
    try:
        import xarray
        import h5netcdf  # noqa: F401 (the engine)
    except ImportError:
        raise ImportError("rockdem: datasets need xarray and h5netcdf (Debian python3-xarray, "
                          "python3-h5netcdf)")
    return xarray


def _decode_enum(h5py, dset_or_dtype, values):
    m = h5py.check_enum_dtype(getattr(dset_or_dtype, "dtype", dset_or_dtype))
    if not m:
        return values
    names = {int(v): k for k, v in m.items()}
    return np.array([names.get(int(v), str(v)) for v in np.atleast_1d(values)], dtype=object)


class Run:
    """A finished run: path of its HDF5 file, summary (dict, from the library) and events
    (time s, body index, type, value)."""

    def __init__(self, path, summary, events):
        self.path = path
        self.summary = summary
        self.events = events

    @property
    def status(self):
        return self.summary["status"]

    def body_names(self):
        return list(self.summary["bodies"])

    def histories(self):
        """dict of numpy arrays: time [N] (s), position/velocity/angular_velocity [N][nb][3],
        quaternion [N][nb][4], tilt [N][nb] (rad), rotation [N][nb][3] (rad), tilt_ratio
        [N][nb] (tilt / alpha towards the lean, as the summary's max_tilt_ratio), ground_acceleration/velocity/displacement [N][3],
        energy_<name> [N] (J)."""
        h5py = _h5py()
        out = {}
        with h5py.File(self.path, "r") as f:
            out["time"] = f["time"][()]
            for k in SERIES:
                out[k] = f[k][()]
            for k in f["ground"]:
                out["ground_" + k] = f["ground"][k][()]
            for k in f["energy"]:
                out["energy_" + k] = f["energy"][k][()]
        out["tilt_ratio"] = self._tilt_ratio(out)
        return out

    def _tilt_ratio(self, h):
        """tilt / alpha towards the side each body leans to (its precariousness table), as the
        summary's max_tilt_ratio; the summary's least alpha where there is no table."""
        import sys
        sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        from rdtools.rotation import alpha_toward, lean_direction
        h5py = _h5py()
        ratio = np.full(h["tilt"].shape, np.nan)
        with h5py.File(self.path, "r") as f:
            for k, (name, b) in enumerate(self.summary["bodies"].items()):
                prec = "bodies/%s/precariousness" % name
                if prec in f and f[prec].shape[0] >= 3:
                    a = alpha_toward(f[prec][()], lean_direction(h["quaternion"][:, k, :]))
                else:
                    a = b["alpha"] if b["alpha"] > 0 else np.nan
                ratio[:, k] = h["tilt"][:, k] / a
        return ratio

    def dataset(self, group=None):
        """The run file's group as an xarray.Dataset (dims time, body, xyz, ...)."""
        return open_run(self.path, group)

    def __repr__(self):
        b = ", ".join("%s: max tilt/alpha %.3g%s" % (n, d["max_tilt_ratio"],
                                                     " OVERTURNED" if d["overturned"] else "")
                      for n, d in self.summary["bodies"].items())
        return "<rockdem.Run %s: %s; %s>" % (self.path, self.status, b)


def open_run(path, group=None):
    """A group of a run file as an xarray.Dataset; for the root group the summary's per-body
    values are added as variables over `body` and the status is decoded (attrs['status'])."""
    xr, h5py = _xarray(), _h5py()
    ds = xr.open_dataset(os.fspath(path), engine="h5netcdf", group=group)
    with h5py.File(path, "r") as f:
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


def open_sweep(path):
    """The /sweep table as an xarray.Dataset over `case` (status decoded to its names)."""
    xr, h5py = _xarray(), _h5py()
    ds = xr.open_dataset(os.fspath(path), engine="h5netcdf", group="sweep")
    with h5py.File(path, "r") as f:
        if "status" in f["sweep"]:
            ds["status"] = ("case", _decode_enum(h5py, f["sweep/status"], ds["status"].values),
                            ds["status"].attrs)
    return ds.load()
