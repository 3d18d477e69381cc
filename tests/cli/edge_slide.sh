#!/usr/bin/env bash
# A block sliding back over the edge of its pedestal (a statue on a pedestal of the same
# footprint): a 0.4 x 0.4 x 0.2 m block (too squat to rock: alpha 63 deg) on a 0.4 x 0.4 m
# pedestal, friction 10 deg, a 0.5 g 2 Hz one-sine: it slides out by about 69 mm and back.
# Sliding is friction against the weight, which does not depend on where the pedestal's edge
# is while the block's centre stays over it, so the same block on a 2 x 2 m pad is the
# reference: the final slide must agree. Tolerance: each scene's own change from the automatic
# step (3e-5 s) to 5e-6 s, added (the difference is the step's error, not physics).
# Before the entrance face's level rule (contact.c entrance_face), the block's points that slid
# back over the pedestal's edge, level with its top face and moving parallel to it, took the
# pedestal's side as their entrance face: a spring against the return slide, which stopped at
# 41.5 mm against the wide pad's 12.2 mm.
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/edge_slide; rm -rf "$T"; mkdir -p "$T"
for pad in 0.4 2; do
    cat > "$T/pad$pad.dat" <<EOF
block create brick size $pad $pad 0.3 position 0 0 -0.15 fixed name pad
block create brick size 0.4 0.4 0.2 seat-on pad name b
contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 10 spacing auto
ground-motion pulse one-sine amplitude 0.5g frequency 2 direction 0
model solve time 2
output hdf5 'x.h5' interval 0.01
EOF
done
slide() { # scene [step]: the block's final slide, mm
    local set=(); [ -n "${2:-}" ] && set=(--set "model.timestep=$2")
    "$BIN" run "$T/$1.dat" "${set[@]}" -o "$T/$1-${2:-auto}.h5" 2>&1 | sed -n 's/.*final slip \([0-9.e+-]*\) mm.*/\1/p'
}
ped=$(slide pad0.4); ped_fine=$(slide pad0.4 5e-6); wide=$(slide pad2); wide_fine=$(slide pad2 5e-6)
echo "final slide: pedestal $ped mm ($ped_fine at 5e-6 s), wide pad $wide mm ($wide_fine at 5e-6 s)"
[ -n "$ped" ] && [ -n "$ped_fine" ] && [ -n "$wide" ] && [ -n "$wide_fine" ] || { echo "FAIL edge-slide: a run printed no slip"; exit 1; }
read -r gap tol ok < <(step_gap "$ped" "$ped_fine" "$wide" "$wide_fine")
verdict "edge-slide/final-slide (mm, pedestal against wide pad)" "$ok" "$gap" "$tol" strict || exit 1
