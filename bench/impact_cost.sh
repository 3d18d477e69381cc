#!/usr/bin/env bash
# Cost of the impact-loss model (issue: a run calibrated to Housner's r may cost at most 1.5 x
# the undamped run at the same KN). One scene, the 0.5 x 0.5 x 1.0 m block on the defaults
# (corners, KN 1e10, KS 1e11) under a 0.8 g, 2 Hz one-sine pulse for 5 s, run three ways,
# interleaved REPS times (fastest counts):
#   undamped    restitution 1: the springs keep every impact's energy
#   calibrated  restitution E (found here by `rockdem restitution --target 0.70`, Housner's r)
#   dashpot     the same energy loss sought by a normal dashpot instead (model damping viscous Z,
#               Z = 1 by default), which shrinks the stable step by sqrt(1 + Z^2) - Z
# and prints wall-s per simulated s, the step, and the ratio to the undamped run.
#
#   bash bench/impact_cost.sh [BINDIR]     (environment: REPS, default 3; Z, default 1)
set -euo pipefail
bindir=${1:-bin}
rockdem="$bindir/rockdem"
reps=${REPS:-3}
zeta=${Z:-1}
[ -x "$rockdem" ] || { echo "impact_cost: no rockdem at $rockdem (make first)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

cat > "$tmp/free.dat" <<EOF
block create brick size 4 4 1 position 0 0 -0.5 fixed name base
block create brick size 0.5 0.5 1.0 position 0 0 0.5 name b
EOF
cp "$tmp/free.dat" "$tmp/shake.dat"
cat >> "$tmp/shake.dat" <<EOF
ground-motion pulse one-sine amplitude 0.8g frequency 2
model solve time 5
output hdf5 '$tmp/x.h5' interval 0.01
EOF
cat >> "$tmp/free.dat" <<EOF
model solve time 2
output hdf5 '$tmp/f.h5' interval 0.001
EOF

e=$("$rockdem" restitution "$tmp/free.dat" --target 0.70 2>/dev/null |
    sed -n 's/^calibrated: contact property restitution \([0-9.e+-]*\) .*/\1/p' | head -n1)
[ -n "$e" ] || { echo "impact_cost: the calibration gave no e (run: rockdem restitution FILE --target 0.70)" >&2; exit 1; }

# wall-s per simulated s and dt of one run: the `perf:` and `run:` lines
one() {
    local out
    out=$("$rockdem" run "$tmp/shake.dat" "$@" 2>&1)
    printf '%s %s\n' "$(printf '%s\n' "$out" | sed -n 's/.*wall_per_sim_s=\([0-9.e+-]*\).*/\1/p')" \
        "$(printf '%s\n' "$out" | sed -n 's/^run:.* dt = \([0-9.e+-]*\) s.*/\1/p')"
}
declare -A best dt
for ((r = 0; r < reps; r++)); do
    for mode in undamped calibrated dashpot; do
        case $mode in
        undamped) set -- --set contact.restitution=1 ;;
        calibrated) set -- --set contact.restitution="$e" ;;
        dashpot) set -- --set contact.restitution=1 --set model.damping="viscous $zeta" ;;
        esac
        read -r w d < <(one "$@")
        dt[$mode]=$d
        if [ -z "${best[$mode]:-}" ] || awk "BEGIN { exit !($w < ${best[$mode]}) }"; then best[$mode]=$w; fi
    done
done
printf 'impact cost (0.5 x 1.0 m block, defaults, 0.8 g 2 Hz one-sine, 5 s; fastest of %d; load %s)\n' \
    "$reps" "$(cut -d' ' -f1 /proc/loadavg)"
printf '%-11s %-26s %-12s %-16s %s\n' run setting dt_s wall_s_per_sim_s ratio
for mode in undamped calibrated dashpot; do
    case $mode in
    undamped) s="restitution 1" ;;
    calibrated) s="restitution $e" ;;
    dashpot) s="viscous $zeta, restitution 1" ;;
    esac
    printf '%-11s %-26s %-12s %-16s %s\n' "$mode" "$s" "${dt[$mode]}" "${best[$mode]}" \
        "$(awk "BEGIN { printf \"%.2f\", ${best[$mode]} / ${best[undamped]} }")"
done
