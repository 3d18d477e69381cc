#!/usr/bin/env bash
# Checkpoints under `contact model surface` (issue 39; docs/CONTACT.md section 8.7): `model
# save` after settling and `model restore` continue bit for bit, as under the vertex model
# (tests/cli/checkpoint.sh). Three scenes, each shaken once straight through and once from the
# restored state; every output sample must be identical, not merely close:
#  - the six-drum column (convex pairs, free on free, the joint dashpot 0.1: the dashpot's last
#    forces carry across the save);
#  - the shipped PBR mesh on its box pedestal (a mesh on a convex body: patches of many planes);
#  - an L block on a free L base on a fixed L floor (mesh against mesh: the face-pair table).
# Before, both were refused ("'model save' is not supported yet"). A checkpoint written under one
# contact model is refused by a scenario of the other, with one line.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/checkpoint_surface; rm -rf "$T"; mkdir -p "$T"
D=$(cd "$(dirname "$0")/../data/mesh" && pwd)
SURF="--set contact.model=surface --set contact.restitution=1"
compare() { # compare NAME: the straight and restored runs' outputs, bit for bit
    /usr/bin/python3 - "$T/$1_straight.h5" "$T/$1_restored.h5" "$1" <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
n = 0
for k in ["time", "position", "quaternion", "velocity", "angular_velocity", "rotation",
          "energy/kinetic", "energy/elastic", "energy/friction", "energy/damping",
          "joints/outcomes", "joints/properties", "outcomes/bodies"]:
    x, y = a[k][...], b[k][...]
    assert x.shape == y.shape and np.array_equal(x, y), "%s: %s differs" % (sys.argv[3], k)
    n += x.size
assert a["time"].shape[0] > 10, "%s: too few samples" % sys.argv[3]
moved = np.abs(a["rotation"][...]).max()
assert moved > 1e-6, "%s: nothing moved (max rotation %g rad)" % (sys.argv[3], moved)
print("checkpoint %s: %d values bit-identical (max rotation %.3g rad)" % (sys.argv[3], n, moved))
PY
}
run_pair() { # run_pair NAME SCENARIO [--set ...]: save while running straight, then restore
    local name=$1 dat=$2; shift 2
    grep -v '^output' "$dat" > "$T/${name}_save.dat"
    echo "model save '$T/$name.h5'" >> "$T/${name}_save.dat"
    grep -v '^output' "$dat" > "$T/${name}_restore.dat"
    echo "model restore '$T/$name.h5'" >> "$T/${name}_restore.dat"
    "$BIN" run "$T/${name}_save.dat" "$@" -o "$T/${name}_straight.h5" -q > "$T/${name}_straight.txt"
    "$BIN" run "$T/${name}_restore.dat" "$@" -o "$T/${name}_restored.h5" -q > "$T/${name}_restored.txt"
    cmp "$T/${name}_straight.txt" "$T/${name}_restored.txt" # the same verdicts and joint outcomes
    compare "$name"
}
run_pair column scenarios/column.dat $SURF --set model.duration=0.25
# `check` of the restoring scenario counts no settling in its step estimate (duration / dt: the
# run starts shaking at once; it counted the settling's 5 s limit too, 21 times the run)
"$BIN" check "$T/column_restore.dat" $SURF --set model.duration=0.25 > "$T/check.txt"
/usr/bin/python3 - "$T/check.txt" <<'PY'
import re, sys
last = open(sys.argv[1]).read().splitlines()[-1]
m = re.search(r"([0-9.e+-]+) s; dt ([0-9.e+-]+) s, about ([0-9.e+-]+) steps", last)
dur, dt, n = (float(x) for x in m.groups())
assert abs(n - dur / dt) <= 0.01 * dur / dt, "check's estimate %g steps, the run takes %g" % (n, dur / dt)
print("checkpoint: check estimates %g steps for the restored run (duration / dt %g)" % (n, dur / dt))
PY
sed "s|'pbr.obj'|'$PWD/scenarios/pbr.obj'|" scenarios/pbr.dat > "$T/pbr.dat"
run_pair pbr "$T/pbr.dat" $SURF --set "model.damping=viscous 3.2" --set model.duration=0.5 \
    --set motion.amplitude=0.5g
cp "$D/L_on_L_free.dat" "$D/L_base.obj" "$D/L_block.obj" "$T/"
run_pair mesh "$T/L_on_L_free.dat" --set model.duration=0.3
# a checkpoint of the other contact model: one line, non-zero exit
grep -v '^output' scenarios/column.dat > "$T/vertex.dat"
echo "model restore '$T/column.h5'" >> "$T/vertex.dat"
if "$BIN" run "$T/vertex.dat" --set model.duration=0.25 -o "$T/vertex.h5" -q > /dev/null 2> "$T/err"; then
    echo "checkpoint: a surface checkpoint restored under the vertex model"; exit 1
fi
[ "$(wc -l < "$T/err")" -eq 1 ] &&
    grep -qF "model restore '$T/column.h5': saved under contact model surface, this scenario uses contact model vertex" "$T/err" ||
    { echo "checkpoint: $(cat "$T/err")"; exit 1; }
echo "checkpoint surface: ok"
