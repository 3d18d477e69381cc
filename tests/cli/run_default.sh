#!/usr/bin/env bash
# The default scenario runs, prints a one-line verdict per body plus the run line, and writes a
# valid HDF5 file with the documented layout and a summary.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}
out=$("$BIN" run scenarios/default.dat -o "$T/default.h5")
printf '%s\n' "$out" | grep -q '^cask: '
printf '%s\n' "$out" | grep -q '^run: status done'
h5dump -A -g /summary "$T/default.h5" | grep -q 'max_tilt_ratio'
/usr/bin/python3 - "$T/default.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
n = f["time"].shape[0]
assert n > 1000, n
assert f["position"].shape == (n, 1, 3) and f["quaternion"].shape == (n, 1, 4)
for k in ["kinetic", "gravitational", "elastic", "friction", "damping", "ground_work", "residual"]:
    assert f["energy/" + k].shape == (n,), k
q = f["quaternion"][:, 0, :]
assert np.allclose(np.linalg.norm(q, axis=1), 1, atol=1e-12)
assert abs(f["ground/acceleration"][:, 0].max() - 0.6 * 9.80665) < 0.05   # 0.6 g one-sine
names = {v: k for k, v in h5py.check_enum_dtype(f["summary"].attrs.get_id("status").dtype).items()}
assert names[int(f["summary"].attrs["status"])] == "done"
assert "one-sine" in f.attrs["scenario"]
assert len(f["events/time"]) > 0
assert set(f["events/body"].asstr()[()]) <= {"cask", ""}
PY
