#!/usr/bin/env bash
# A scene of more free bodies than the old fixed summary array held (256, issue 14): 300 free
# bricks, apart from one another on a fixed base, run by the CLI to an HDF5 file. The run must
# succeed and print one verdict per body, and /summary must carry one entry per body in /body
# order, each with the brick's tipping angle (its own support polygon, not a copy of another's).
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/many; rm -rf "$T"; mkdir -p "$T"
N=300       # free bricks: more than 256
COLS=20     # bricks per row, 0.5 m apart (0.2 m wide: no brick touches another)
/usr/bin/python3 - "$N" "$COLS" > "$T/many.dat" <<'EOF'
import sys
n, cols = int(sys.argv[1]), int(sys.argv[2])
rows = (n + cols - 1) // cols
print("block create brick size %g %g 0.5 position %g %g -0.25 fixed name base"
      % (0.5 * cols + 2, 0.5 * rows + 2, 0.25 * (cols - 1), 0.25 * (rows - 1)))
for k in range(n):
    print("block create brick size 0.2 0.2 0.4 position %g %g 0.2 name b%d"
          % (0.5 * (k % cols), 0.5 * (k // cols), k))
print("contact property stiffness-normal 1e9 stiffness-shear 1e8 friction 35 spacing vertices")
print("model settle off")
print("ground-motion pulse one-sine amplitude 0.05g frequency 5")
print("model solve time 0.01")
EOF
out=$("$BIN" run "$T/many.dat" -o "$T/many.h5")
[ "$(grep -c '^b[0-9]*: .*; max tilt ' <<< "$out")" -eq "$N" ] || { echo "FAIL: not $N verdicts"; exit 1; }
/usr/bin/python3 - "$T/many.h5" "$N" <<'EOF'
import math, sys
import h5py
f, n = h5py.File(sys.argv[1], "r"), int(sys.argv[2])
names = [x.decode() for x in f["bodies/names"][()]]
assert names == ["b%d" % k for k in range(n)], names[:3]
s = f["summary"]
assert s.attrs["status"] == 0, s.attrs["status"]   # done
for key in ("alpha", "max_tilt", "overturned", "max_slide", "tip_accel_min"):
    assert len(s.attrs[key]) == n, (key, len(s.attrs[key]))
# a 0.2 x 0.2 x 0.4 m brick on its base: alpha = atan(b / h) = atan(0.1 / 0.2). The support
# polygon comes from the contact points at rest, whose compression under the brick's weight,
# rho g H / KN = 2700 x 9.81 x 0.4 / 1e9 = 1.1e-5 m against h = 0.2 m, moves alpha by 5e-5 of
# itself: 1e-3 allows 20 times that.
want = math.atan(0.5)
worst = max(abs(a - want) for a in s.attrs["alpha"]) / want
assert worst < 1e-3, worst
assert f["outcomes/bodies"].shape[0] == n, f["outcomes/bodies"].shape
print("%d bodies: /summary has %d entries, alpha within %.1e of atan(1/2)" % (n, n, worst))
EOF
