#!/usr/bin/env bash
# rdxdmf: the XDMF sidecar parses; it is a temporal collection with one spatial collection per
# written step (--every K: every K-th sample and the last), each holding the free bodies and the
# fixed ones (the base); every HDF5 reference is "./<file>" relative to the .xmf; the step-0
# world vertices equal position + R(q) v computed independently (vector form of the quaternion
# rotation); the fixed base sits where the scenario put it; tilt_ratio peaks at the summary's
# max_tilt_ratio.
# (tests/cli/paraview.sh loads the files in ParaView.)
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/tools_xdmf; mkdir -p "$T"
PY=/usr/bin/python3
cat > "$T/s.dat" <<'DAT'
model title 'xdmf test: two bricks, tilted start'
block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.3 1.2 position -0.6 0 0.62 rotation 4 3 30 name b1
block create brick size 0.5 0.5 0.8 position 0.6 0.2 0.4 name b2
contact property stiffness-normal 1e9 stiffness-shear 1e8 friction 35
ground-motion pulse one-sine amplitude 0.4g frequency 3 direction 20
model solve time 0.3
output hdf5 'x.h5' interval 0.01
DAT
"$BIN" run "$T/s.dat" -q -o "$T/run.h5" >/dev/null
$PY tools/rdxdmf.py "$T/run.h5" -o "$T/run.xmf" --float64 >/dev/null
$PY tools/rdxdmf.py "$T/run.h5" -o "$T/every.xmf" --every 4 >/dev/null
test -s "$T/run.vis.h5"
$PY - "$T/run.h5" "$T/run.xmf" "$T/run.vis.h5" "$T/every.xmf" <<'PY'
import sys, os, xml.etree.ElementTree as ET, h5py, numpy as np
run, xmf, vis, every = sys.argv[1:]
f = h5py.File(run, "r"); v = h5py.File(vis, "r")
n = f["time"].shape[0]
root = ET.parse(xmf).getroot()
coll = root.find("Domain/Grid")
assert coll.get("CollectionType") == "Temporal"
steps = coll.findall("Grid")
assert len(steps) == n, (len(steps), n)
assert all(s.get("CollectionType") == "Spatial" for s in steps)
assert [g.get("Name") for g in steps[0].findall("Grid")] == ["bodies", "fixed"]
times = [float(g.find("Time").get("Value")) for g in steps]
assert np.allclose(times, f["time"][:], rtol=0, atol=1e-12)
names = list(f["bodies/names"].asstr()[()])
assert names == ["b1", "b2"]
# every DataItem is "./run.vis.h5:/path" and points at a dataset of the right shape
for g in steps[:3] + steps[-2:]:
    for di in g.iter("DataItem"):
        fn, path = di.text.split(":")
        assert fn == "./run.vis.h5", fn
        assert os.path.join(os.path.dirname(xmf), fn) == os.path.join(os.path.dirname(vis), "./run.vis.h5")
        dims = tuple(int(d) for d in di.get("Dimensions").split())
        assert v[path].shape == dims, (path, v[path].shape, dims)
# independent world vertices at step 0: x = p + v + 2w (u x v) + 2 u x (u x v)
xyz = v["step_0/xyz"][:]
expect = []
# layout 3: each body's rows of the concatenated tables, in block order (free bodies first)
v0 = np.concatenate([[0], np.cumsum(f["bodies/vertex_count"][:])])
f0 = np.concatenate([[0], np.cumsum(f["bodies/face_count"][:])])
p0 = np.concatenate([[0], np.cumsum(f["bodies/lean_count"][:])])
for k, nm in enumerate(names):
    V = f["bodies/vertices"][v0[k]:v0[k + 1]]
    q = f["quaternion"][0, k, :]; q = q / np.linalg.norm(q); w, u = q[0], q[1:]
    t = 2 * np.cross(u, V)
    expect.append(f["position"][0, k, :] + V + w * t + np.cross(u, t))
expect = np.vstack(expect)
err = np.abs(xyz - expect).max()
assert err < 1e-12, err
assert abs(f["quaternion"][0, 0, 0]) < 0.9999  # the tilted body really is rotated
topo = v["topology"][:]
n0, nf0 = v0[1], f0[1]
assert (topo[nf0:] == f["bodies/faces"][f0[1]:f0[2]] + n0).all()
# the fixed base: 3 x 3 x 0.5 m with its top at z = 0, where the scenario put it
fx = v["fixed/xyz"][:]
assert fx.shape == (8, 3) and np.allclose(fx.min(0), [-1.5, -1.5, -0.5]) and np.allclose(fx.max(0), [1.5, 1.5, 0])
assert np.isnan(v["fixed/tilt"][:]).all()
# tilt ratio: tilt / alpha towards the lean, so its peak over the samples is the summary's
# max_tilt_ratio (the engine's, over every step: the 0.01 s samples may miss a few per cent)
tri_body = v["body"][:]
for b in range(2):
    tri = np.flatnonzero(tri_body == b)[0]
    peak = max(v["step_%d/tilt_ratio" % k][tri] for k in range(n))
    want = f["summary"].attrs["max_tilt_ratio"][b]
    assert abs(peak - want) <= 0.05 * want, (b, peak, want)
    a = f["tilt"][n - 1, b] / v["step_%d/tilt_ratio" % (n - 1)][tri]  # the alpha used
    tab = f["bodies/precariousness"][p0[b]:p0[b + 1], 1]
    assert tab.min() * (1 - 1e-6) <= a <= tab.max() * (1 + 1e-6), (a, tab.min(), tab.max())
# --every 4: samples 0, 4, 8, ... and the last; single precision
ev = ET.parse(every).getroot().find("Domain/Grid").findall("Grid")
want = list(range(0, n, 4)) + ([n - 1] if (n - 1) % 4 else [])
assert [g.get("Name") for g in ev] == ["step_%d" % i for i in want], [g.get("Name") for g in ev][:5]
assert h5py.File(every[:-4] + ".vis.h5", "r")["step_0/xyz"].dtype == np.float32
print("xdmf ok: %d steps (%d with --every 4), step-0 vertex error %.2e" % (len(steps), len(ev), err))
PY
# bad input: one line, non-zero exit
out=$($PY tools/rdxdmf.py "$T/nope.h5" 2>&1 >/dev/null) && { echo "missing file accepted"; exit 1; }
echo "$out" | grep -q "no such file"
