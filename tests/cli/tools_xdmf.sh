#!/usr/bin/env bash
# rdxdmf: the XDMF sidecar parses, has one grid per output sample, and its step-0 world vertices
# equal position + R(q) v computed independently (vector form of the quaternion rotation).
# With pvpython on PATH the .xmf is also loaded headless and its point count checked.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/tools_xdmf; mkdir -p "$T"
PY=/usr/bin/python3
cat > "$T/s.dat" <<'DAT'
model title 'xdmf test: two bricks, tilted start'
block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.3 1.2 position -0.6 0 0.6 rotation 4 3 30 name b1
block create brick size 0.5 0.5 0.8 position 0.6 0.2 0.4 name b2
contact property stiffness-normal 1e9 stiffness-shear 1e8 friction 35
ground-motion pulse one-sine amplitude 0.4g frequency 3 direction 20
model solve time 0.3
output hdf5 'x.h5' interval 0.01
DAT
"$BIN" run "$T/s.dat" -q -o "$T/run.h5" >/dev/null
$PY tools/rdxdmf.py "$T/run.h5" -o "$T/run.xmf" >/dev/null
test -s "$T/run.vis.h5"
$PY - "$T/run.h5" "$T/run.xmf" "$T/run.vis.h5" <<'PY'
import sys, os, xml.etree.ElementTree as ET, h5py, numpy as np
run, xmf, vis = sys.argv[1:]
f = h5py.File(run, "r"); v = h5py.File(vis, "r")
n = f["time"].shape[0]
root = ET.parse(xmf).getroot()
coll = root.find("Domain/Grid")
assert coll.get("CollectionType") == "Temporal"
grids = coll.findall("Grid")
assert len(grids) == n, (len(grids), n)
times = [float(g.find("Time").get("Value")) for g in grids]
assert np.allclose(times, f["time"][:], rtol=0, atol=1e-12)
names = [x.decode().rstrip("\0") if isinstance(x, bytes) else x for x in f["bodies/names"][:]]
assert len(names) == 2
# every DataItem points at an existing dataset of the right shape
for g in grids[:3] + grids[-2:]:
    for di in g.iter("DataItem"):
        fn, path = di.text.split(":")
        assert os.path.join(os.path.dirname(xmf), fn) == vis
        dims = tuple(int(d) for d in di.get("Dimensions").split())
        assert v[path].shape == dims, (path, v[path].shape, dims)
# independent world vertices at step 0: x = p + v + 2w (u x v) + 2 u x (u x v)
xyz = v["step_0/xyz"][:]
topo = v["topology"][:]
off, expect = 0, []
for k, nm in enumerate(names):
    V = f["bodies/%s/vertices" % nm][:]; F = f["bodies/%s/faces" % nm][:]
    q = f["quaternion"][0, k, :]; q = q / np.linalg.norm(q); w, u = q[0], q[1:]
    t = 2 * np.cross(u, V)
    expect.append(f["position"][0, k, :] + V + w * t + np.cross(u, t))
    off += len(V)
expect = np.vstack(expect)
assert xyz.shape == expect.shape
err = np.abs(xyz - expect).max()
assert err < 1e-12, err
# the tilted body really is rotated at step 0 (the check is not trivially identity)
assert abs(f["quaternion"][0, 0, 0]) < 0.9999
# topology: the faces of body 1 are offset by the vertex count of body 0
n0 = f["bodies/%s/vertices" % names[0]].shape[0]
nf0 = f["bodies/%s/faces" % names[0]].shape[0]
assert (topo[nf0:] == f["bodies/%s/faces" % names[1]][:] + n0).all()
print("xdmf ok: %d grids, step-0 vertex error %.2e" % (len(grids), err))
PY
# bad input: one line, non-zero exit
out=$($PY tools/rdxdmf.py "$T/nope.h5" 2>&1 >/dev/null) && { echo "missing file accepted"; exit 1; }
echo "$out" | grep -q "no such file"
if command -v pvpython >/dev/null 2>&1; then
    cat > "$T/pv.py" <<PVPY
from paraview.simple import XDMFReader, UpdatePipeline
r = XDMFReader(FileNames=["$T/run.xmf"])
r.UpdatePipeline(0.0)
n = r.GetDataInformation().GetNumberOfPoints()
assert n == 16, n
print("pvpython ok:", n, "points")
PVPY
    timeout 60 pvpython "$T/pv.py"
else
    echo "pvpython not on PATH: ParaView load check skipped"
fi
