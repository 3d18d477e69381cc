#!/usr/bin/env bash
# Cost of the surface contact model against the vertex model, wall s per simulated s (issue 39,
# item 6; docs/CONTACT.md section 8.9), from the perf line of `rockdem run`, interleaved:
#   pbr     the shipped PBR (scenarios/pbr.obj, 3,968 faces, on its brick pedestal; seed 002's
#           joint, 0.3 g 2 Hz one-sine), 0.5 s
#   pbr36   the 5,040-face PBR (tools/make_pbr.py --seed 1 --nlat 36), the same scene, 0.3 s
#   stack   the 0.4 x 0.4 x 0.8 m block on the 0.5 x 0.5 x 1.0 m one on a fixed base (KN 1e10,
#           KS 1e11 Pa/m, 40 deg, dashpot 0.3), 0.6 g 2 Hz one-sine, 1 s
# The surface runs take `contact property restitution 1` (the vertex model's default 0 has no
# patch form; their impact loss is the dashpot), the vertex runs the defaults.
#
#   bash bench/surface_cost.sh [BIN [OLD_BIN]]     (ROUNDS, default 3; about 1 min a round)
#
# BIN (default bin/rockdem) runs both models; OLD_BIN, when given, runs the surface model too,
# in the same rounds (a build to compare against). Each row is one round: the machine's load
# moves all columns of a round together, so compare ratios within a row.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${1:-bin/rockdem}
OLD=${2:-}
ROUNDS=${ROUNDS:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[ -f scenarios/pbr.obj ] || make -s scenarios/pbr.obj
cp scenarios/pbr.obj "$tmp/pbr.obj"
/usr/bin/python3 tools/make_pbr.py --seed 1 --nlat 36 -o "$tmp/pbr36.obj" > /dev/null
sed -e 's/model solve time 4/model solve time 0.5/' -e '/output hdf5/d' scenarios/pbr.dat \
    > "$tmp/pbr_v.dat"
sed -e 's/pbr.obj/pbr36.obj/' -e 's/model solve time 0.5/model solve time 0.3/' \
    "$tmp/pbr_v.dat" > "$tmp/pbr36_v.dat"
cat > "$tmp/stack_v.dat" << 'EOF'
block create brick size 4 4 1 position 0 0 -0.5 fixed name base
block create brick size 0.5 0.5 1.0 position 0 0 0.5 name lower
block create brick size 0.4 0.4 0.8 position 0 0 1.4 name upper
contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 40
model damping viscous 0.3
ground-motion pulse one-sine amplitude 0.6g frequency 2 direction 0
model solve time 1
EOF
for sc in pbr pbr36 stack; do
    { echo "contact model surface"; cat "$tmp/${sc}_v.dat"
      echo "contact property restitution 1"; } > "$tmp/${sc}_s.dat"
done
cost() { (cd "$tmp" && "$1" run "$2" 2>&1 | sed -n 's/.*wall_per_sim_s=//p'); }
BIN=$(realpath "$BIN")
[ -z "$OLD" ] || OLD=$(realpath "$OLD")
printf '%-6s %-6s %9s %9s %7s' round scene vertex surface ratio
[ -z "$OLD" ] || printf ' %9s %7s' old_surf old_rat
printf ' %s\n' load
for r in $(seq 1 "$ROUNDS"); do
    for sc in pbr pbr36 stack; do
        v=$(cost "$BIN" "${sc}_v.dat")
        s=$(cost "$BIN" "${sc}_s.dat")
        printf '%-6s %-6s %9.3f %9.3f %7.2f' "$r" "$sc" "$v" "$s" "$(echo "$s / $v" | bc -l)"
        if [ -n "$OLD" ]; then
            o=$(cost "$OLD" "${sc}_s.dat")
            printf ' %9.3f %7.2f' "$o" "$(echo "$o / $v" | bc -l)"
        fi
        printf ' %s\n' "$(cut -d' ' -f1 /proc/loadavg)"
    done
done
