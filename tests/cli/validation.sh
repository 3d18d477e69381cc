#!/usr/bin/env bash
# rockdem reference / threshold / restitution / study from the command line: the reference run
# writes the DEM's HDF5 layout; the reference threshold of the 0.5 x 1.0 m block under a 2 Hz
# one-sine pulse with Housner's r = 0.70 is 1.26 g (DESIGN.md section 2, two digits); scenes
# the references cannot take are refused with one line and a non-zero exit.
set -u
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
blk="$T/val_block.dat"
cat > "$blk" <<'DAT'
block create brick size 4 4 1 position 0 0 -0.5 fixed name base
block create brick size 0.5 0.5 1.0 position 0 0 0.5 name b
contact property stiffness-normal 1e10 stiffness-shear 1e10 friction 80 spacing vertices
model damping viscous 0.5
ground-motion pulse one-sine amplitude 1.3g frequency 2
model solve time 3
DAT
out=$("$BIN" reference "$blk" -o "$T/ref.h5") || fail "reference run: $out"
printf '%s' "$out" | grep -q "Housner" || fail "reference: no model line: $out"
for d in time position quaternion tilt ground/acceleration energy/kinetic events summary; do
    h5ls "$T/ref.h5/$d" >/dev/null 2>&1 || fail "reference file lacks /$d"
done
out=$("$BIN" threshold "$blk" --engine reference --rtol 0.002) || fail "threshold: $out"
g=$(printf '%s' "$out" | sed -n 's/.*= \([0-9.]*\) g .*/\1/p')
awk -v g="$g" 'BEGIN { exit !(g > 1.25 && g < 1.27) }' || fail "threshold $g g, expected 1.26 g"
"$BIN" reference "$blk" --set reference.restitution=0.8 -o "$T/r8.h5" | grep -q "e = 0.8" ||
    fail "reference.restitution override not used"
err=$("$BIN" reference "$blk" --set motion.direction=30 2>&1 >/dev/null); rc=$?
{ [ "$rc" -eq 2 ] && printf '%s' "$err" | grep -q "oblique"; } || fail "oblique direction: rc=$rc $err"
three="$T/val_three.dat"
{ cat "$blk"; echo "block create brick size 0.2 0.2 0.2 position 1 1 0.1 name pebble"; } > "$three"
err=$("$BIN" reference "$three" 2>&1 >/dev/null); rc=$?
{ [ "$rc" -eq 2 ] && [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] && printf '%s' "$err" | grep -q "does not stand on"; } ||
    fail "unstacked pair: rc=$rc $err"
# the minimum-overturning curve: rises with w/p (Housner), 2 Hz gives the single threshold above
curve=$("$BIN" threshold "$blk" --engine reference --frequencies 1,1.5,2) || fail "curve: $curve"
printf '%s\n' "$curve" | awk 'NR > 2 { if (NR > 3 && $3 <= prev) bad = 1; prev = $3; g = $4 }
    END { exit !(NR == 5 && !bad && g > 1.25 && g < 1.27) }' || fail "curve not rising to 1.26 g: $curve"
# restitution: the damping ratio that gives Housner's r = 1 - 1.5 sin^2(alpha) = 0.70 for the
# 0.5 x 0.5 x 1 m block with corner subcontacts (over-critical, about 4.3), within the
# calibration tolerance
free="$T/val_free.dat"
grep -v "ground-motion" "$blk" | sed 's/^model solve time .*/model solve time 3/' > "$free"
cal=$("$BIN" restitution "$free" | grep '^calibrated:') || fail "no Housner calibration: $cal"
r=$(printf '%s' "$cal" | sed -n 's/.* gives r = \([0-9.]*\) .*/\1/p')
awk -v r="$r" 'BEGIN { exit !(r > 0.69 && r < 0.71) }' || fail "calibrated r $r, expected 0.70"
err=$("$BIN" threshold "$blk" --engine nope 2>&1 >/dev/null); rc=$?
[ "$rc" -eq 2 ] || fail "bad engine accepted: $err"
[ "$fails" -eq 0 ]
