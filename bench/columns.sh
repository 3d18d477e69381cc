#!/usr/bin/env bash
# Cost per step of drum columns of 1, 2, 5, 10, 20 and 50 drums (issue: shapes and scenes). Each
# column (bench/column_scene.sh: 0.8 m drums, 0.6 m tall, 16 sides, subcontact spacing 0.2 m)
# stands on a fixed base under a gentle 2 Hz harmonic so every joint is loaded; the step is
# fixed so all columns do the same number of steps. Fastest of 3 runs per column.
#   bash bench/columns.sh [BINDIR]
# Columns: ns per step, per step and drum, per active subcontact-step, and the marginal cost of
# the drums added since the row above (ns per step per added drum).
# Reading it: a column of n drums has one base joint and n - 1 drum-drum joints. The fixed base
# carries no points, so the base joint is one-sided (drum 1's points against the base), while
# both drums of a drum-drum joint carry points and each side is evaluated (half weight each): a
# drum-drum joint costs about 2.6 times the base joint (instruction counts, callgrind: 91k vs
# 35k per joint-step). The mean cost per drum, (base + (n - 1) drum-drum) / n, therefore rises
# from 2 drums towards the drum-drum joint's cost; the marginal cost per added drum is what
# must stay flat (no per-pair or per-body cost that grows with n).
set -eu
bindir=${1:-bin}
case $bindir in /*) ;; *) bindir="$PWD/$bindir" ;; esac
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
kv() { printf '%s\n' "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"; }
printf '%-6s %8s %10s %12s %17s %15s %20s\n' drums steps wall_s ns_per_step ns_per_step_drum ns_per_active marginal_ns_per_drum
prev_n=0; prev_c=0
for n in 1 2 5 10 20 50; do
    bash "$(dirname "$0")/column_scene.sh" "$n" 0.1 "$tmp/col.h5" > "$tmp/col.dat"
    best=""
    for r in 1 2 3; do
        line=$("$bindir/rockdem" run "$tmp/col.dat" | grep -o 'perf: .*')
        if [ -z "$best" ] || awk "BEGIN { exit !($(kv "$line" wall_s) < $(kv "$best" wall_s)) }"; then best=$line; fi
    done
    read -r c row < <(awk -v n="$n" -v s="$(kv "$best" steps)" -v w="$(kv "$best" wall_s)" \
        -v a="$(kv "$best" mean_active_subcontacts)" -v pn="$prev_n" -v pc="$prev_c" 'BEGIN {
        c = 1e9 * w / s
        m = pn > 0 ? sprintf("%.0f", (c - pc) / (n - pn)) : "-"
        printf "%.6f %-6d %8d %10.4f %12.0f %17.0f %15.2f %20s\n", c, n, s, w, c, c / n, c / a, m }')
    printf '%s\n' "$row"
    prev_n=$n; prev_c=$c
done
