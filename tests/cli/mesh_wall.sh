#!/usr/bin/env bash
# A scanned rock (scenarios/pbr.obj) tipped towards a fixed wall beside its pedestal by a 0.8 g
# 2 Hz one-sine (issue 39: "passes 422 of its 1,986 vertices into the wall ... exit 0,
# OVERTURNED"). The vertex model puts a mesh's points on the faces that touch at the start or
# face down near its base, so the rock's side meets the wall unseen: the run must stop as
# penetrated (exit 3), one line naming the rock and the wall and the surface model, its output
# kept. The surface model (every face) must hold the rock against the wall: status done, a
# wall-rock joint in the summary, no rock centre past the wall's face. The rock alone overturning off its pedestal at 1.5 g keeps
# its verdict (its falling side crossing the pedestal's edge ends the run, status overturned).
set -u
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/mesh_wall; rm -rf "$T"; mkdir -p "$T"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
[ -f "$ROOT/scenarios/pbr.obj" ] || { echo "FAIL mesh_wall: no scenarios/pbr.obj (make scenarios/pbr.obj)"; exit 1; }
fails=0
cat > "$T/wall.dat" <<EOF
block create brick size 1.2 1.2 0.3 position 0 0 -0.15 fixed name pedestal
block create brick size 1.2 0.2 1.5 position 0 0.5 0.75 fixed name wall
block import mesh '$ROOT/scenarios/pbr.obj' seat-on pedestal density 2750 name rock
contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40
ground-motion pulse one-sine amplitude 0.8g frequency 2 direction 270
model overturn tilt-ratio 1.0 stop off
model solve time 1
output hdf5 'wall.h5' interval 0.005
EOF
rc=0; "$BIN" run "$T/wall.dat" -o "$T/v.h5" > "$T/v.txt" 2> "$T/v.err" || rc=$?
if [ "$rc" -eq 3 ] && [ "$(wc -l < "$T/v.err")" -eq 1 ] && grep -q "^run: status penetrated" "$T/v.txt" &&
    grep -qF "body 'rock' passed into body 'wall'" "$T/v.err" && grep -qF "give 'contact model surface'" "$T/v.err" &&
    [ -s "$T/v.h5" ]; then
    echo "CHECK vertex model: rock into the wall stops as penetrated ($(grep -o 'at t = [0-9.]* s' "$T/v.err"))"
else echo "FAIL vertex model: rc=$rc $(grep '^run:' "$T/v.txt"): $(cat "$T/v.err")"; fails=$((fails + 1)); fi
surf=(--set contact.model=surface --set contact.restitution=1)
rc=0; "$BIN" run "$T/wall.dat" "${surf[@]}" -o "$T/s.h5" > "$T/s.txt" 2>&1 || rc=$?
/usr/bin/python3 - "$T/s.h5" > "$T/s.py" 2>&1 <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
y = f["position"][:, 0, 1]  # the one free body's centre, m
print("%.4f" % y.max())
PY
ymax=$(tail -n 1 "$T/s.py")
if [ "$rc" -eq 0 ] && grep -q "^run: status done" "$T/s.txt" && grep -q "^joint wall-rock: max slip" "$T/s.txt" &&
    awk -v y="$ymax" 'BEGIN { exit !(y + 0 == y && y < 0.4) }'; then
    echo "CHECK surface model: the rock strikes the wall and is held (its centre at most y = $ymax m, the face at 0.4 m)"
else echo "FAIL surface model: rc=$rc $(grep '^run:' "$T/s.txt"), rock centre y max '$ymax'"; fails=$((fails + 1)); fi
rc=0; "$BIN" run "$ROOT/scenarios/pbr.dat" --set motion.amplitude=1.5g -o "$T/o.h5" > "$T/o.txt" 2>&1 || rc=$?
if [ "$rc" -eq 0 ] && grep -q "^run: status overturned" "$T/o.txt" && grep -q "^rock: OVERTURNED" "$T/o.txt"; then
    echo "CHECK the rock alone at 1.5 g: overturned"
else echo "FAIL the rock alone at 1.5 g: rc=$rc $(grep '^run:\|^rock:' "$T/o.txt" | head -n 2)"; fails=$((fails + 1)); fi
[ "$fails" -eq 0 ]
