#!/usr/bin/env bash
# A slab overhanging its pedestal on every side: a 0.8 x 0.8 x 0.2 m slab on a fixed 0.6 x 0.6 m
# pad, default contact (corner points). Its corners lie beyond the pad, so only the pad's top
# edges bear, as edge subcontacts (src/engine/edge.c), at the two ends of each edge's part
# inside the slab.
#   rest:  a 0.6 g 2 Hz one-sine (below sliding, tan 40 deg = 0.84 g, and tipping, 3 g), 3 s.
#          The run's energy residual within issue 10's 1e-3; the slab reported seated with a
#          joint, not "FELL FREELY" (the monitor once counted only vertex subcontacts).
#   slide: 1.2 g. Sliding is friction against the weight, which does not depend on which
#          subcontacts carry it, so the same slab on a 1 x 1 m pad (its corner points bear) is
#          the reference: the largest slide must agree to within what the springs' compliance
#          makes of it. A rigid-plastic slab slides alike on both; the two supports differ in
#          their springs, an effect that shrinks as they stiffen (the gap is 5.7e-7 m at the
#          default KN 1e10, KS 1e11 Pa/m, 8.7e-9 m at ten times those, 9.7e-9 m at a hundred,
#          where the step's error is as large), so the check runs at ten times the default. Its displacement scales there are the
#          slab's sink under its weight m g / (KN A) = 5.1e-8 m and its shear stretch at the
#          Coulomb limit tan(phi) m g / (KS A) = 4.3e-9 m (m = 332.8 kg, A = 0.64 m^2: both
#          supports' springs share the slab's base area; 40 deg). Tolerance: those two for each
#          scene, plus each scene's change from a step of 2.8e-6 s (the automatic one, 2.85e-6)
#          to half of it (the step's error).
#   off:   2.5 g at 0.7 Hz slides it off the pad: it counts as overturned (fell off its support),
#          not as a run that lost a body of unknown fate.
#   rock:  a 0.4 x 0.4 x 1.2 m block on a fixed 0.3 x 0.3 m pad, released at 6 deg, rocks on the
#          pad's top edges; a 0.3 x 0.3 x 1.2 m block on a wide pad rocks on its own corners
#          (vertex subcontacts, whose plastic impacts give Housner's r). Both pivots are 0.3 m
#          apart at 0.6 m below the centre of mass, so Housner's r differs only by the blocks'
#          inertia (0.833 and 0.831). Measured: the energy ratio over six impacts from the second
#          (the peaks' heights of the centre of mass), as a fraction of each block's own r_H; they
#          must agree within the 0.5 % issue 11 asks of a restitution measure. Before the edge
#          springs took the joint's impact loss they were elastic: the block bounced on the pad's
#          edges (ratios 0.71-1.36 from one impact to the next) and slid 19.7 mm.
# Before (one spring per edge at its deepest point): the level edges' deepest point jumped from
# end to end as the slab tilted by a hair, a kink in the potential at its rest pose; at rest the
# run made energy (residual 0.80 of its scale, status untrusted) and reported the slab as having
# touched nothing; at ten times the stiffness the slide differed by 2.8e-6 m (residual 4.9e-2,
# untrusted); sliding off stopped the run as lost.
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/overhang; rm -rf "$T"; mkdir -p "$T"
for pad in 0.6 1.0; do
    cat > "$T/pad$pad.dat" <<EOF
block create brick size $pad $pad 0.4 position 0 0 -0.2 fixed name pad
block create brick size 0.8 0.8 0.2 seat-on pad name slab density 2600
ground-motion pulse one-sine amplitude 0.6g frequency 2 direction 0
model solve time 3
output hdf5 'x.h5' interval 0.01
EOF
done
attr() { /usr/bin/python3 -c "import h5py; v = h5py.File('$1', 'r')['summary'].attrs['$2']; print('%.10g' % (v[0] if hasattr(v, '__len__') else v))"; }
fail=0

out=$("$BIN" run "$T/pad0.6.dat" -o "$T/rest.h5" 2>&1) || { echo "FAIL overhang/rest: the run failed"; printf '%s\n' "$out" | tail -3; exit 1; }
echo "rest: $(printf '%s\n' "$out" | grep -E '^slab:|^joint|^run:' | head -3 | tr '\n' ' ')"
check_residual "overhang/rest" "$(energy_residual "$T/rest.h5")" || fail=1
printf '%s\n' "$out" | grep -q '^slab: stayed seated' || { echo "FAIL overhang/rest: the slab is not reported seated"; fail=1; }
printf '%s\n' "$out" | grep -q '^joint pad-slab:' || { echo "FAIL overhang/rest: no joint between pad and slab"; fail=1; }

slide() { # scene step: the slab's largest slide at ten times the default stiffness, m
    "$BIN" run "$T/$1.dat" --set motion.amplitude=1.2g --set model.timestep="$2" --set contact.stiffness-normal=1e11 \
        --set contact.stiffness-shear=1e12 -o "$T/$1-$2.h5" >/dev/null 2>&1 &&
        attr "$T/$1-$2.h5" max_slide
}
o=$(slide pad0.6 2.8e-6); of=$(slide pad0.6 1.4e-6); w=$(slide pad1.0 2.8e-6); wf=$(slide pad1.0 1.4e-6)
echo "largest slide at 1.2 g: overhang $o m ($of at half the step), wide pad $w m ($wf)"
if [ -n "$o" ] && [ -n "$of" ] && [ -n "$w" ] && [ -n "$wf" ]; then
    el=$(awk 'BEGIN { m = 0.8 * 0.8 * 0.2 * 2600; A = 0.64; W = m * 9.81; phi = 40 * atan2(0, -1) / 180
        printf "%.6g", 2 * (W / (1e11 * A) + W * sin(phi) / cos(phi) / (1e12 * A)) }') # both scenes' scales, m
    read -r gap tol ok < <(step_gap "$o" "$of" "$w" "$wf" "$el")
    echo "slide gap $gap m, tolerance $tol m"
    verdict "overhang/slide (m, overhang against wide pad)" "$ok" "$gap" "$tol" strict || fail=1
else
    echo "FAIL overhang/slide: a run failed"; fail=1
fi

out=$("$BIN" run "$T/pad0.6.dat" --set motion.amplitude=2.5g --set motion.frequency=0.7 -o "$T/off.h5" 2>&1)
echo "off: $(printf '%s\n' "$out" | grep -E '^slab:|^run:' | head -1)"
printf '%s\n' "$out" | grep -q 'OVERTURNED (fell off its support' ||
    { echo "FAIL overhang/off: the slab sliding off its pad is not counted as fallen off"; fail=1; }
for b in 0.4 0.3; do
    pad=$([ "$b" = 0.4 ] && echo 0.3 || echo 2)
    cat > "$T/rock$b.dat" <<EOF
block create brick size $pad $pad 0.4 position 0 0 -0.2 fixed name pad
block create brick size $b $b 1.2 seat-on pad name b density 2600
model settle off
block initial name b tilt 6 direction 0
model solve time 4
output hdf5 'x.h5' interval 0.0005
EOF
    "$BIN" run "$T/rock$b.dat" -o "$T/rock$b.h5" >/dev/null 2>&1 || { echo "FAIL overhang/rock: the $b m block's run failed"; fail=1; }
done
read -r gap ok note < <(/usr/bin/python3 - "$T/rock0.4.h5" "$T/rock0.3.h5" <<'EOF'
import sys, h5py, numpy as np
def share(fn, width):  # energy ratio per impact over the first six, over Housner's r
    f = h5py.File(fn, "r"); th = np.abs(f["rotation"][:, 0, 0]); t = f["time"][:]
    pk = [i for i in range(1, len(th) - 1)  # the peaks after the release's (t = 0)
          if th[i] >= th[i - 1] and th[i] > th[i + 1] and th[i] > 1e-3 and t[i] > 0.05]
    b, h = 0.15, 0.6  # half the pivots' spacing and the height of the centre of mass above them, m
    R, al = np.hypot(b, h), np.arctan(b / h)
    E = np.array([R * np.cos(al - th[i]) - h for i in pk])  # rise of the centre of mass at a peak
    if len(E) < 7: return float("nan")
    r = (E[6] / E[0]) ** (1 / 6)
    rH = (1 - 2 * b * b / ((width ** 2 + 1.2 ** 2) / 12 + R * R)) ** 2
    return r / rH
a, c = share(sys.argv[1], 0.4), share(sys.argv[2], 0.3)
g = abs(a / c - 1)
print("%.4g %d r/r_H:_pad_edges_%.4f_own_corners_%.4f" % (g, g <= 5e-3, a, c))
EOF
)
echo "rock: ${note//_/ }, gap $gap (tolerance 5e-3)"
verdict "overhang/rock (r/r_H on the pad's edges against own corners)" "${ok:-0}" "${gap:-nan}" 5e-3 strict || fail=1
exit $fail
