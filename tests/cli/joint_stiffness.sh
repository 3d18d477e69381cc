#!/usr/bin/env bash
# The stiffness of a joint between two free blocks of unequal footprint: a statue on a wider
# free pedestal, and a wide block on a narrower free pedestal, each on a fixed floor. A joint
# of normal stiffness KN (Pa/m) over its contact area A (the smaller face) sinks under the
# upper block's weight by m g / (KN A), the static solution of a uniform bed of springs (exact
# for a flat joint, whatever its discretisation, when the points' areas sum to A).
# Where two free bodies both carry points, each set integrates its own face over the joint and
# the two carry half the stiffness each. The wider face's points lie outside the joint: with
# vertex subcontacts (the default) none of them bore, so the joint sank twice as far (half its
# KN; KS likewise); with a bed (`spacing auto`) those under the smaller face bore, its area
# only to within the bed's spacing (a 0.45 m statue on the 1 m pedestal's 11 x 11 bed: 1.23
# times it, the sink 0.895 of m g / (KN A)). The pair is now one-sided: the contained face's
# points at full weight (engine/pairs.c, faces_within). Equal faces keep both sets (the
# control case).
# Tolerance 1e-3 of the sink: settling stops at an unbalanced force of 1e-6 of the weight
# (docs/GUIDE.md, `model settle`), and the floor joint's own sink is subtracted exactly; the errors
# this catches are factors of 2 and 1.22.
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/joint_stiffness; rm -rf "$T"; mkdir -p "$T"
fails=0

# run_scene NAME: runs $T/NAME.dat; 1 when rockdem fails (after printing why)
run_scene() {
    "$BIN" run "$T/$1.dat" -q > "$T/$1.log" 2>&1 && return 0
    echo "FAIL $1: rockdem run failed"; cat "$T/$1.log"; fails=$((fails + 1)); return 1
}

# judge NAME WHAT "SINK WANT GAP OK": prints and checks a measured joint sink (m) against
# m g / (KN A)
judge() {
    local sink want gap ok
    read -r sink want gap ok <<< "$3"
    echo "$1: $2 sink $sink m, m g / (KN A) = $want m, relative gap $gap"
    verdict "$1: $2 sink against m g / (KN A)" "$ok" "$gap" 1e-3 strict || fails=$((fails + 1))
}

# case NAME LOWER_SIDE UPPER_SIDE SPACING: a 1.2 m lower block and a 0.6 m upper one, square
# footprints, density 2600, KN 1e10; checks the upper joint's sink
case_sink() {
    local name=$1 lo=$2 up=$3 spacing=$4
    cat > "$T/$name.dat" <<EOF
model gravity 9.81
block create brick size 4 4 0.4 position 0 0 -0.2 fixed name floor
block create brick size $lo $lo 1.2 seat-on floor name low density 2600
block create brick size $up $up 0.6 seat-on low name up density 2600
contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 40 spacing $spacing
model solve time 0.05
output hdf5 '$T/$name.h5' interval 0.01
EOF
    run_scene "$name" || return
    local out
    out=$(/usr/bin/python3 - "$T/$name.h5" "$lo" "$up" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
lo, up = float(sys.argv[2]), float(sys.argv[3])
z = f["position"][-1, :, 2]                  # centres of low and up, m
sink = 1.5 - z[1] - (0.6 - z[0])   # the upper joint's closure (the floor joint's taken off), m
m_up = 2600.0 * up * up * 0.6
want = m_up * 9.81 / (1e10 * min(lo, up) ** 2)
gap = abs(sink - want) / want
print("%.4g %.4g %.4g %d" % (sink, want, gap, gap <= 1e-3))
PY
)
    judge "$name" joint "$out"
}

# case_side NAME SPACING: two 1 m cubes placed side by side, touching, on the fixed floor;
# checks each one's floor joint sink. Their touching side faces carry points (a face placed on
# another body's), and those merged with the bases' at the shared corners bore with both
# faces' areas on the floor (and on the neighbour): the floor joint sank 0.75 of m g / (KN A).
# A point now merges only with points of faces within 60 deg of its own and bears only on a
# face it looks at (engine/merge.c, engine/contact.c).
case_side() {
    local name=$1 spacing=$2
    cat > "$T/$name.dat" <<EOF
model gravity 9.81
block create brick size 4 4 0.4 position 0 0 -0.2 fixed name floor
block create brick size 1 1 1 position -0.5 0 0.5 name a density 2600
block create brick size 1 1 1 position 0.5 0 0.5 name b density 2600
contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 40 spacing $spacing
model solve time 0.05
output hdf5 '$T/$name.h5' interval 0.01
EOF
    run_scene "$name" || return
    local out
    out=$(/usr/bin/python3 - "$T/$name.h5" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
sink = max(abs(0.5 - z) for z in f["position"][-1, :, 2])  # the floor joints' closure, m
want = 2600.0 * 9.81 / 1e10                                 # m g / (KN A), A = 1 m^2
gap = abs(sink - want) / want
print("%.4g %.4g %.4g %d" % (sink, want, gap, gap <= 1e-3))
PY
)
    judge "$name" "floor joint" "$out"
}

case_sink statue-vertices 1.0 0.5 vertices
case_sink statue-bed 1.0 0.45 auto
case_sink wide-top-vertices 0.5 1.0 vertices
case_sink equal-vertices 0.5 0.5 vertices
case_side side-by-side-vertices vertices
case_side side-by-side-bed auto
exit $((fails > 0))
