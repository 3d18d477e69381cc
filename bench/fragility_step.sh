#!/usr/bin/env bash
# How the step moves a PBR fragility study's answer, against how a 0.01 deg turn of the shaking
# moves it (`make bench-fragility-step`, about 15 min on 2 idle cores).
#
#   bash bench/fragility_step.sh [BINDIR]
#
# The Echo Cliff-sized study's sample (bench/pbr_study.sh, STUDY=echo-cliff: the shipped PBR
# under 20 s Kanai-Tajimi records, SEEDS record seeds x 19 PGA levels 0.1-1.0 g x directions
# 0, 90, 180, 270; default SEEDS=3: 228 runs) is swept at the step's safety factors 0.1, 0.2
# (the default) and 0.5, and once more at 0.2 with every direction turned by 0.01 deg, a
# change far below what any record's orientation is known to. bench/fragility_step.py then
# prints, per setting, the runs whose outcome (overturned or not) differs from the 0.1 sweep's
# and from the default's, the runs above the energy bound (1e-3) and above the trust limit
# (1e-2), the CPU time per run, and the lognormal fragility (median PGA, beta; maximum
# likelihood) across the rock's thin side (0 and 180 deg) and its long side (90 and 270 deg),
# with a 95 % interval from a bootstrap over the records.
# Environment: SEEDS (record seeds, default 3), JOBS (workers, default all cores), KEEP (keep
# the four sweep tables in that directory).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bindir=${1:-bin}; case $bindir in /*) ;; *) bindir="$PWD/$bindir" ;; esac
seeds=${SEEDS:-3}
out=${KEEP:-$(mktemp -d)}; mkdir -p "$out"
[ -n "${KEEP:-}" ] || trap 'rm -rf "$out"' EXIT
sweep() { # NAME SAFETY DIRECTIONS
    STUDY=echo-cliff SEEDS=$seeds SAFETY=$2 DIRECTIONS=$3 TABLE="$out/$1.h5" \
        bash "$here/pbr_study.sh" "$bindir" > "$out/$1.txt" 2>&1 ||
        { tail -n 3 "$out/$1.txt" >&2; echo "bench/fragility_step.sh: the $1 sweep failed" >&2; exit 1; }
    sed -n 's/^sample: .* \([0-9.]*\) CPU s$/\1/p' "$out/$1.txt" > "$out/$1.cpu"
}
sweep safety-0.1 0.1 0,90,180,270
sweep safety-0.2 0.2 0,90,180,270
sweep safety-0.2-turned-0.01deg 0.2 0.01,90.01,180.01,270.01
sweep safety-0.5 0.5 0,90,180,270
/usr/bin/python3 "$here/fragility_step.py" "$out/safety-0.1.h5" "$out/safety-0.2.h5" \
    "$out/safety-0.2-turned-0.01deg.h5" "$out/safety-0.5.h5"
echo "date: $(date -u '+%Y-%m-%d %H:%M UTC'), $(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo '?'), load average $(cut -d' ' -f1-3 /proc/loadavg)"
