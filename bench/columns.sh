#!/usr/bin/env bash
# Cost per step of drum columns of 2, 5, 10, 20 and 50 drums (issue: shapes and scenes). Each
# column (bench/column_scene.sh: 0.8 m drums, 0.6 m tall, 16 sides, subcontact spacing 0.2 m)
# stands on a fixed base under a gentle 2 Hz harmonic so every joint is loaded; the step is
# fixed so all columns do the same number of steps. The cost must grow linearly: ns per step
# per drum stays flat.
#   bash bench/columns.sh [BINDIR]
set -eu
bindir=${1:-bin}
case $bindir in /*) ;; *) bindir="$PWD/$bindir" ;; esac
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
printf '%-6s %10s %12s %14s %18s\n' drums steps wall_s ns_per_step ns_per_step_drum
for n in 2 5 10 20 50; do
    bash "$(dirname "$0")/column_scene.sh" "$n" 0.1 "$tmp/col.h5" > "$tmp/col.dat"
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
