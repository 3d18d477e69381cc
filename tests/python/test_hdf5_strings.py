"""Every string rockdem writes into a run file is variable-length UTF-8 (h5py returns str, not
b'm': before, /history and /joints units and long names and the root status were fixed-length),
and every group opens in xarray with a coordinate on each dimension (rockdem.open_run)."""
import subprocess

import h5py
import numpy as np
import pytest

import rockdem
from conftest import BLOCK

HISTORIES = """history interval 0.01
history body 'block' all
history joint 'pad' 'block' all
history energy
"""
H5DS_OWN = {"CLASS", "NAME", "REFERENCE_LIST", "DIMENSION_LIST"}  # HDF5's dimension-scale library


@pytest.fixture(scope="module")
def run_file(tmp_path_factory):
    d = tmp_path_factory.mktemp("h5")
    (d / "h.dat").write_text(BLOCK.replace("model solve time 1", "model solve time 0.3") + HISTORIES)
    out = str(d / "h.h5")
    subprocess.run([rockdem.program(), "run", str(d / "h.dat"), "-q", "-o", out], check=True,
                   stdout=subprocess.DEVNULL)
    return out


def _strings(f):
    """(where, dtype) of every string attribute and dataset in the file, H5DS's own left out."""
    out = []

    def visit(name, obj):
        for k in obj.attrs:
            t = obj.attrs.get_id(k).dtype
            if k not in H5DS_OWN and h5py.check_string_dtype(t) is not None:
                out.append(("%s@%s" % (name, k), t))
        if isinstance(obj, h5py.Dataset) and h5py.check_string_dtype(obj.dtype) is not None:
            out.append((name, obj.dtype))
    visit("/", f)
    f.visititems(visit)
    return out


def test_every_string_is_utf8_variable_length(run_file):
    with h5py.File(run_file, "r") as f:
        found = _strings(f)
        assert len(found) > 50
        bad = [(w, h5py.check_string_dtype(t)) for w, t in found
               if h5py.check_string_dtype(t).length is not None
               or h5py.check_string_dtype(t).encoding != "utf-8"]
        assert not bad, bad
        assert f.attrs["status"] == "done" and f.attrs["status_message"] == ""
        assert f["history/time"].attrs["units"] == "s"
        assert f["history/joint/pad-block/slip"].attrs["units"] == "m"
        assert f["joints/outcomes"].attrs["units"] == "m,m,m,1"


def test_every_group_has_its_coordinates(run_file):
    groups = [None]
    with h5py.File(run_file, "r") as f:
        f.visit(lambda n: groups.append(n) if isinstance(f[n], h5py.Group) else None)
        root_time, hist_time = f["time"][()], f["history/time"][()]
    for g in groups:
        ds = rockdem.open_run(run_file, g)
        assert all(d in ds.coords for d in ds.dims), (g, dict(ds.sizes), list(ds.coords))
    for g in ("ground", "energy"):
        assert np.array_equal(rockdem.open_run(run_file, g)["time"].values, root_time)
    for g in ("history/body/block", "history/joint/pad-block"):
        t = rockdem.open_run(run_file, g)["time"]
        assert np.array_equal(t.values, hist_time) and t.attrs["units"] == "s"
    assert list(rockdem.open_run(run_file, "joints")["joint"].values) == ["pad-block"]
    assert list(rockdem.open_run(run_file, "outcomes")["body"].values) == ["block"]
