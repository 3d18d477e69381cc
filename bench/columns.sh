#!/usr/bin/env bash
# Cost per step of drum columns of 2, 5, 10, 20 and 50 drums (issue: shapes and scenes). Each
# column (0.8 m drums, 0.6 m tall, 16 sides, subcontact spacing 0.2 m) stands on a fixed base
# under a gentle 2 Hz harmonic so every joint is loaded; the step is fixed so all columns do
# the same number of steps. The cost must grow linearly: ns per step per drum stays flat.
#   bash bench/columns.sh [BINDIR]
set -eu
bindir=${1:-bin}
case $bindir in /*) ;; *) bindir="$PWD/$bindir" ;; esac
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
printf '%-6s %10s %12s %14s %18s\n' drums steps wall_s ns_per_step ns_per_step_drum
for n in 2 5 10 20 50; do
    cat > "$tmp/col.dat" <<DAT
block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base
block create column drums $n diameter 0.8 height 0.6 sides 16 seat-on base name c
contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40 spacing 0.2
model timestep fixed 2e-5
model settle off
ground-motion pulse harmonic amplitude 0.02g frequency 2 cycles 1
model solve time 0.1
output hdf5 '$tmp/col.h5' interval 0.05
DAT
    best=""
    for r in 1 2 3; do
        line=$("$bindir/rockdem" run "$tmp/col.dat" | grep -o 'perf: .*')
        w=$(printf '%s\n' "$line" | tr ' ' '\n' | sed -n 's/^wall_s=//p')
        if [ -z "$best" ] || awk "BEGIN { exit !($w < $(printf '%s\n' "$best" | tr ' ' '\n' | sed -n 's/^wall_s=//p')) }"; then best=$line; fi
    done
    steps=$(printf '%s\n' "$best" | tr ' ' '\n' | sed -n 's/^steps=//p')
    wall=$(printf '%s\n' "$best" | tr ' ' '\n' | sed -n 's/^wall_s=//p')
    awk -v n="$n" -v s="$steps" -v w="$wall" 'BEGIN { printf "%-6d %10d %12.4f %14.0f %18.0f\n", n, s, w, 1e9 * w / s, 1e9 * w / s / n }'
done
