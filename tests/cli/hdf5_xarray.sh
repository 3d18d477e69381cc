#!/usr/bin/env bash
# Self-describing HDF5 (docs/HDF5-LAYOUT.md): xarray (h5netcdf engine, no phony_dims option)
# opens every group of a run file and of a sweep table with named dimensions; every variable
# has a long_name, every non-index variable that has units carries them; status and event type
# are HDF5 enums; events name their body.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/xr; mkdir -p "$T"
/usr/bin/python3 -c "import xarray, h5netcdf" 2>/dev/null || {
    echo "skipped: python3-xarray / python3-h5netcdf not installed (tools/install-deps.sh)"; exit 77; }
"$BIN" run scenarios/default.dat --set model.duration=1 -q -o "$T/run.h5" > /dev/null
"$BIN" sweep tests/cli/data/sweep_brick.dat --scales 1.0g,2.0g --directions 0,45 -j 2 -q \
    -o "$T/sweep.h5" > /dev/null
/usr/bin/python3 - "$T/run.h5" "$T/sweep.h5" <<'PY'
import sys, h5py, numpy as np, xarray as xr
run, sweep = sys.argv[1:3]

def groups(path):
    out = ["/"]
    with h5py.File(path, "r") as f:
        f.visit(lambda n: out.append(n) if isinstance(f[n], h5py.Group) else None)
    return out

def check(path, g):
    ds = xr.open_dataset(path, engine="h5netcdf", group=None if g == "/" else g)
    dims = set(ds.dims)
    assert not any(d.startswith("phony_dim") for d in dims), (path, g, dims)
    for name, v in ds.variables.items():
        assert "long_name" in v.attrs, (path, g, name)
    return ds

for g in groups(run):
    check(run, g)
ds = check(run, "/")
assert ds["position"].dims == ("time", "body", "xyz"), ds["position"].dims
assert ds["quaternion"].dims == ("time", "body", "wxyz")
assert ds["rotation"].dims == ("time", "body", "rotation_part")
assert list(ds["body"].values) == ["cask"]
assert ds["time"].attrs["units"] == "s" and ds["position"].attrs["units"] == "m"
assert ds.attrs["Conventions"] == "rockdem-3" and ds.attrs["layout_version"] == 3
assert ds.attrs["kn_units"] == "Pa/m" and ds.attrs["dt_units"] == "s"
gr = check(run, "ground")
assert gr["acceleration"].dims == ("time", "xyz") and gr["acceleration"].attrs["units"] == "m/s^2"
en = check(run, "energy")
assert en["kinetic"].dims == ("time",) and en["kinetic"].attrs["units"] == "J"
# a tilted ground-frame series sliced by label
assert float(ds["position"].sel(body="cask", xyz="z")[0]) > 0
ev = check(run, "events")
assert ev["time"].dims == ("event",) and ev.sizes["event"] > 0
assert set(ev["body"].values) <= {"cask", ""}
with h5py.File(run, "r") as f:
    et = h5py.check_enum_dtype(f["events/type"].dtype)
    assert et and {"uplift", "impact", "overturn"} <= set(et), et
    st = h5py.check_enum_dtype(f["summary"].attrs.get_id("status").dtype)
    assert st and {v: k for k, v in st.items()}[int(f["summary"].attrs["status"])] == "done"
    assert f["summary"].attrs["max_slide_units"] == "m"
    assert h5py.check_string_dtype(f["bodies/names"].dtype).length is None  # variable length
    assert h5py.check_string_dtype(f["bodies/names"].dtype).encoding == "utf-8"
    sr = h5py.check_enum_dtype(f.attrs.get_id("spacing_rule").dtype)
    assert {v: k for k, v in sr.items()}[int(f.attrs["spacing_rule"])] == "vertices"  # the default
    assert "spacing" not in f.attrs  # no 0 standing for "vertices"
    # layout 3: a row per body over `block` (free bodies first), geometry concatenated
    blk = list(f["bodies/block"].asstr()[()])
    assert blk == ["cask", "pad"], blk
    assert list(f["bodies/fixed"][()]) == [0, 1] and f["bodies/vertices"].shape[1] == 3
    vc = f["bodies/vertex_count"]
    assert vc.attrs["sample_dimension"] == "vertex" and vc[1] == 8  # the pad: a brick
    assert sum(vc[()]) == f["bodies/vertices"].shape[0]
    assert sum(f["bodies/face_count"][()]) == f["bodies/faces"].shape[0]
    assert list(f["bodies/lean_count"][()]) == [72, 0]  # free bodies at rest only
    assert f["bodies/precariousness"].shape == (72, 3)
sw = check(sweep, "sweep")
assert sw["pga"].dims == ("case",) and sw["pga"].attrs["units"] == "m/s^2"
assert sw["body_max_tilt_ratio"].dims == ("case", "body")
with h5py.File(sweep, "r") as f:
    assert f["sweep"].attrs["ncases"] == 4 and np.issubdtype(f["sweep"].attrs["ncases"].dtype, np.integer)
    assert h5py.check_enum_dtype(f["sweep/status"].dtype)
# every group opens with a coordinate for each of its dimensions (its outside scales are
# hard-linked into it: /ground has time and xyz, /history/body/NAME time)
for g in groups(run):
    ds = xr.open_dataset(run, engine="h5netcdf", group=g or None)
    missing = [d for d in ds.dims if d not in ds.coords]
    assert not missing, (g, missing)
print("xarray: %d run groups and the sweep table open with named dimensions and coordinates" % len(groups(run)))
PY
