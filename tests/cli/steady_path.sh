#!/usr/bin/env bash
# The contact's steady path (engine/contact.c, steady_point) repeats the general law's common
# cases expression for expression, so that a steady point costs less; it must never change a
# result. build/tests/rockdem-general is the program built with the steady path switched off
# (-DRD_STEADY_PATH=0: every point goes through subcontact). Each scene below is run by both
# programs, and every numeric HDF5 dataset must be equal to the bit (NaN equal to NaN). The
# scenes visit every branch the steady path takes or hands over: a point bed and corners, impacts
# (new points unloading), points idle above their face and below their permanent set, late faces
# (a brick that topples), slip, bonds that break (cohesion, tension), dashpots, a mesh, and
# free-free drum joints (the shear force turning with the lower drum), and elastic joints
# (restitution 1: a spring within w/2 of switching bears its mean force over the step, in the
# general law only) on the YADE stack and column.
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}
GEN=${RD_BUILD:-build}/tests/rockdem-general
[ -x "$GEN" ] || { echo "FAIL steady path: $GEN not built (make test builds it)"; exit 1; }
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
T=${RD_TMP:-$(mktemp -d)}/steady_path; mkdir -p "$T"; cd "$T" || exit 1

cat > column.dat <<'DAT'
block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base
block create column drums 6 diameter 0.8 height 0.6 sides 16 seat-on base name c
contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 30
ground-motion pulse one-sine amplitude 0.5g frequency 2 direction 10
model solve time 0.4
output hdf5 'x.h5' interval 0.01
DAT
cp "$ROOT/scenarios/pbr.obj" . 2>/dev/null || { echo "FAIL steady path: scenarios/pbr.obj missing (make test makes it)"; exit 1; }
sed "s#'pbr.obj'#'$T/pbr.obj'#" "$ROOT/scenarios/pbr.dat" > pbr.dat

# name | scenario | overrides
scenes=(
    "bed|$ROOT/bench/block.dat|--set model.duration=0.6"
    "brick-topples|$ROOT/tests/cli/data/sweep_brick.dat|--set motion.amplitude=1.0g"
    "landing-topple|$ROOT/scenarios/seed000_topple.dat|--set model.duration=0.6"
    "default|$ROOT/scenarios/default.dat|--set model.duration=2"
    "stack-bonded|$ROOT/tests/cli/data/stack_bonded.dat|"
    "column|column.dat|"
    "pbr|pbr.dat|--set model.duration=0.3"
    "elastic-stack|$ROOT/tests/data/yade/stack.dat|--set motion.amplitude=1.0g --set model.duration=2.1"
    "elastic-column|$ROOT/tests/data/yade/column.dat|--set motion.amplitude=0.7g --set model.duration=1"
)
fails=0
for row in "${scenes[@]}"; do
    IFS='|' read -r name scene over <<< "$row"
    # shellcheck disable=SC2086  # the overrides are words
    "$BIN" run "$scene" $over -q -o "$T/$name-fast.h5" > /dev/null 2>&1
    rc_fast=$?
    # shellcheck disable=SC2086
    "$GEN" run "$scene" $over -q -o "$T/$name-general.h5" > /dev/null 2>&1
    rc_gen=$?
    if [ "$rc_fast" != "$rc_gen" ]; then
        echo "FAIL steady path $name: exit status $rc_fast (steady path) vs $rc_gen (general law)"
        fails=$((fails + 1)); continue
    fi
    if ! /usr/bin/python3 - "$name" "$T/$name-fast.h5" "$T/$name-general.h5" <<'PY'
import sys, h5py, numpy as np
name, fa, fb = sys.argv[1], h5py.File(sys.argv[2], "r"), h5py.File(sys.argv[3], "r")
n, bad = 0, []
def visit(key, obj):
    global n
    if not isinstance(obj, h5py.Dataset) or obj.dtype.kind not in "fiub":
        return
    if key not in fb:
        bad.append(key + " (missing)"); return
    x, y = np.asarray(obj[()]), np.asarray(fb[key][()])
    n += 1
    if x.shape != y.shape:
        bad.append("%s shape %s vs %s" % (key, x.shape, y.shape)); return
    same = (x == y) | (np.isnan(x) & np.isnan(y)) if x.dtype.kind == "f" else (x == y)
    if not np.all(same):
        d = np.abs(x.astype(float) - y.astype(float))
        bad.append("%s max|diff| %.3g" % (key, np.nanmax(d)))
fa.visititems(visit)
if n == 0 or bad:
    print("FAIL steady path %s: %d of %d datasets differ: %s" % (name, len(bad), n, "; ".join(bad[:4])))
    sys.exit(1)
print("CHECK steady path %s: %d datasets bit-identical to the general law" % (name, n))
PY
    then fails=$((fails + 1)); fi
done
[ "$fails" -eq 0 ]
