#!/usr/bin/env bash
# Joint measures and histories of the surface contact model (`contact model surface`, issue 39):
#  - at rest, the 0.5 x 0.5 x 1.0 m block (rho 2700) on its base: the joint's normal force is
#    its weight m g = 6621.75 N and its area the base's 0.25 m^2 plus the strips of the side
#    faces below the base's plane, perimeter times the Winkler sink m g / (KN A): 2 m x
#    2.6487e-6 m = 5.2974e-6 m^2; the centre of pressure under the centre of mass. A Winkler
#    joint at rest is exact (the patch integrals are), so the tolerances are round-off's and
#    settling's: 1e-4 of the weight (the settling stops at a force ratio of 1e-5 of it; 1e-4
#    leaves ten times that), 1e-9 m^2 (2e-4 of the strips), 1 mm (a lean of the
#    seated block of 1e-5 rad moves it 5e-6 m: 1 mm is far below the 0.25 m half-width and
#    far above that). Before, the joint measures read the vertex subcontacts, which the surface
#    model leaves idle: 0 N and 0 m^2.
#  - measuring never changes a result: the block under a 0.5 g 2 Hz one-sine with its dashpot
#    (zeta 0.3), with and without every joint, body and energy history, writes the same
#    /summary to the bit.
# (Checkpoints of the patches: tests/cli/checkpoint_surface.sh.)
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=$(cd "$(dirname "${RD_BIN:-bin/rockdem}")" && pwd)/rockdem; T=${RD_TMP:-$(mktemp -d)}/surface_measures; rm -rf "$T"; mkdir -p "$T"
PY=/usr/bin/python3
scene() { # scene FILE EXTRA...
    local f=$1; shift
    {
        echo "block create brick size 4 4 1 position 0 0 -0.5 fixed name base"
        echo "block create brick size 0.5 0.5 1.0 position 0 0 0.5 density 2700 name b"
        echo "contact model surface"
        echo "contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 40 restitution 1"
        echo "model damping viscous 0.3"
        for l in "$@"; do echo "$l"; done
        echo "output hdf5 '$(basename "$f" .dat).h5' interval 0.01"
    } > "$T/$f"
}
scene rest.dat "model solve time 0.2" "history interval 0.01" \
    "history joint 'base' 'b' normal-force area pressure-centre shear-force"
scene shake.dat "ground-motion pulse one-sine amplitude 0.5g frequency 2 direction 0" "model solve time 2"
scene shake_h.dat "ground-motion pulse one-sine amplitude 0.5g frequency 2 direction 0" "model solve time 2" \
    "history interval 0.001" "history joint 'base' 'b' all" "history body 'b' all" "history energy"
cd "$T" || exit 1
fail=0
for f in rest shake shake_h; do "$BIN" run "$f.dat" -q > "$f.out" 2>&1 || { echo "FAIL run $f: $(tail -1 "$f.out")"; exit 1; }; done
read -r fn area cx cy <<< "$($PY -c "
import h5py
j = h5py.File('rest.h5', 'r')['history/joint/base-b']
print(j['normal_force'][-1], j['area'][-1], j['pressure_centre'][-1][0], j['pressure_centre'][-1][1])")"
echo "CHECK joint normal force at rest: rockdem $fn, reference 6621.75 (m g)"
verdict "normal force at rest vs m g" "$(awk -v a="$fn" 'BEGIN { d = a / 6621.75 - 1; print (d < 0 ? -d : d) <= 1e-4 }')" "$fn" "1e-4 rel" strict || fail=1
aref=$(awk 'BEGIN { printf "%.12g", 0.25 + 2 * 6621.75 / (1e10 * 0.25) }')
echo "CHECK joint area at rest: rockdem $area, reference $aref"
verdict "area at rest vs base and side strips" "$(awk -v a="$area" -v r="$aref" 'BEGIN { d = a - r; print (d < 0 ? -d : d) <= 1e-9 }')" "$area" 1e-9 strict || fail=1
echo "CHECK centre of pressure at rest: rockdem ($cx, $cy), reference (0, 0)"
verdict "centre of pressure at rest" "$(awk -v x="$cx" -v y="$cy" 'BEGIN { print (x * x + y * y) <= 1e-6 }')" "$cx,$cy" 1e-3 strict || fail=1
same=$($PY -c "
import h5py, numpy as np
a, b = h5py.File('shake.h5', 'r')['summary'], h5py.File('shake_h.h5', 'r')['summary']
def items(g):
    out = {}
    g.visititems(lambda n, o: out.__setitem__(n, o[()]) if isinstance(o, h5py.Dataset) else None)
    return out
da, db = items(a), items(b)
ok = sorted(da) == sorted(db) and all(np.array_equal(da[k], db[k]) for k in da if k != 'wall_seconds')
ok = ok and all(np.array_equal(a.attrs[k], b.attrs[k]) for k in a.attrs if 'wall' not in k)
print(int(ok))")
echo "CHECK /summary with and without histories: identical $same"
verdict "/summary unchanged by histories" "$same" "$same" 1 strict || fail=1
exit $fail
