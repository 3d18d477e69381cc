#!/usr/bin/env bash
# `rockdem restitution` under the surface contact model (issue 39, item 4; docs/CONTACT.md
# section 8.6): the surface model has no permanent set, so its impact loss is the joint's
# dashpot and the calibrator varies the dashpot's ratio (model damping viscous). On the
# 0.5 x 0.5 x 1.0 m block (h/b = 2, rho 2700; KN 1e10, KS 1e11 Pa/m, 40 deg):
#  - the calibration reaches r = 0.80 to the tolerance asked, --rtol 5e-4 (a quarter of its
#    default, RD_CAL_RTOL, issue 11's 0.002); a --rtol outside 1e-4 .. 0.002 is refused;
#  - a free-rocking run of the brick and of the 10 x 10 cut mesh at that ratio, read here from
#    the run files (amplitude decay of impacts 1-3, rigid energy between impacts), gives 0.80
#    within 0.002 + 1 % (the issue's tessellation tolerance);
#  - r = 0.95, which the issue asks for, is out of reach (exit 4; the closest r printed): an
#    expected failure that prints its gap (the continuous base's bound, section 8.6).
set -u
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/restitution_surface; rm -rf "$T"; mkdir -p "$T"
D=$(cd "$(dirname "$0")/../data/surface" && pwd)
PY=${RD_PYTHON:-/usr/bin/python3}
fails=0
scene() { # $1 file, $2 the block's line, $3 extra lines
    printf '%s\n' "model gravity 9.81" "block create brick size 4 4 1 position 0 0 -0.5 fixed name base" \
        "$2" "contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 40 restitution 1" \
        "contact model surface" "model solve time 3" "output hdf5 'b.h5' interval 0.0005" "$3" > "$1"
}
BRICK="block create brick size 0.5 0.5 1.0 position 0 0 0.5 density 2700 name b"
MESH="block import mesh 'box_cut10.obj' position 0 0 0.5 density 2700 name b"
cp "$D/box_cut10.obj" "$T/"
scene "$T/brick.dat" "$BRICK" ""
for bad in 1e-5 0.01 x; do
    rc=0; "$BIN" restitution "$T/brick.dat" --rtol "$bad" > "$T/bad.txt" 2>&1 || rc=$?
    if [ "$rc" -eq 2 ] && [ "$(wc -l < "$T/bad.txt")" -eq 1 ] && grep -q -- "--rtol" "$T/bad.txt"; then
        echo "CHECK rtol-refused-$bad ($(cat "$T/bad.txt"))"
    else
        echo "FAIL rtol-refused-$bad: rc=$rc: $(head -n2 "$T/bad.txt")"; fails=$((fails + 1))
    fi
done
rc=0; "$BIN" restitution "$T/brick.dat" --target 0.8 --rtol 5e-4 -q > "$T/cal.txt" 2>&1 || rc=$?
zeta=$(sed -n 's/^calibrated: model damping viscous \([0-9.]*\) gives r = \([0-9.]*\).*/\1/p' "$T/cal.txt")
got=$(sed -n 's/^calibrated: model damping viscous \([0-9.]*\) gives r = \([0-9.]*\).*/\2/p' "$T/cal.txt")
if [ "$rc" -eq 0 ] && [ -n "$zeta" ] && awk -v r="$got" 'BEGIN { exit !(r - 0.8 < 5e-4 && 0.8 - r < 5e-4) }'; then
    echo "CHECK calibrated-0.8 (zeta $zeta, r $got)"
else
    echo "FAIL calibrated-0.8: rc=$rc: $(grep -m1 -E 'calibrated|UNREACH|restitution:' "$T/cal.txt")"
    fails=$((fails + 1)); zeta=1
fi
# the release at alpha / 2 towards +x, the calibrated ratio, every 0.5 ms sampled
tilt=$(awk 'BEGIN { printf "%.12g", atan2(0.5, 1) / 2 * 45 / atan2(1, 1) }')
for k in brick mesh; do
    shape=$BRICK; [ "$k" = mesh ] && shape=$MESH
    scene "$T/$k-run.dat" "$shape" "model damping viscous $zeta
block initial name b tilt $tilt direction 0"
    if ! "$BIN" run "$T/$k-run.dat" -q -o "$T/$k.h5" > "$T/$k.txt" 2>&1; then
        echo "FAIL $k-run: $(tail -n1 "$T/$k.txt")"; fails=$((fails + 1)); continue
    fi
    r=$("$PY" - "$T/$k.h5" <<'PY'
import math, sys
import h5py
alpha = math.atan2(0.5, 1.0)
with h5py.File(sys.argv[1], "r") as f:
    th = f["rotation"][:, 0, 0]
eps, sign, amps = 1e-3 * alpha / 2, 0, [alpha / 2]
for t in th:   # swings: runs of one sign beyond eps; each swing's amplitude
    if abs(t) <= eps:
        continue
    s = 1 if t > 0 else -1
    if s != sign:
        if sign:
            amps.append(0.0)
        sign = s
    if sign and len(amps) > 1:
        amps[-1] = max(amps[-1], abs(t))
e = lambda a: math.cos(alpha - a) - math.cos(alpha)
rs = [math.sqrt(e(amps[i + 1]) / e(amps[i])) for i in range(3)]
print("%.5f" % math.exp(sum(map(math.log, rs)) / 3))
PY
)
    if awk -v r="${r:-0}" 'BEGIN { exit !(r > 0 && (r - 0.8) ^ 2 < (0.002 + 0.008) ^ 2) }'; then
        echo "CHECK $k-r-at-calibrated-zeta (r $r from its run file, tol 0.8 +- 0.010)"
    else
        echo "FAIL $k-r-at-calibrated-zeta: r '$r' (want 0.8 +- 0.010)"; fails=$((fails + 1))
    fi
done
# the issue's upper end: 0.95 for h/b = 2
rc=0; "$BIN" restitution "$T/brick.dat" --target 0.95 -q > "$T/high.txt" 2>&1 || rc=$?
best=$(sed -n 's/^UNREACHABLE: .*closest this contact gets is r = \([0-9.]*\).*/\1/p' "$T/high.txt")
if [ "$rc" -eq 4 ] && [ -n "$best" ]; then
    echo "XFAIL: free-rocking r = 0.95 (h/b = 2) under the surface model, closest r $best gap=$(awk -v b="$best" 'BEGIN { printf "%.4f", 0.95 - b }') tol=0.002"
elif [ "$rc" -eq 0 ]; then
    echo "XPASS: r = 0.95 reached: $(grep -m1 calibrated "$T/high.txt")"
else
    echo "FAIL target-0.95: rc=$rc: $(tail -n1 "$T/high.txt")"; fails=$((fails + 1))
fi
[ "$fails" -eq 0 ]
