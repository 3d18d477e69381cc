#!/usr/bin/env bash
# Cost per step against scene size (issue 14): dry-stone walls of 50, 500 and 5,000 bricks
# (bench/wall.py: 5 courses, running bond, the wall growing in length) loaded, settled and
# shaken through the library with no file (docs/examples/embed.c), CPU time per step (settling and
# shaking steps; CPU rather than wall time, steadier on a shared machine).
#
#   bash bench/scale.sh [BUILD]     (BUILD holds librockdem.a and embed; default: build)
#
# Prints one line per size and the cost per brick per step; linear growth means that last
# column stays flat. Writes the table to bench/scale.txt.
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
make -s "$build/embed"
out="$here/scale.txt"
{
    echo "# $(date -u +%F) $(uname -m) $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
    printf '%8s %12s %14s %18s\n' bricks steps cpu_us_per_step cpu_us_per_brick_step
    for n in ${SIZES:-50 500 5000}; do
        /usr/bin/python3 "$here/wall.py" "$n" > "$tmp/wall.dat"
        line=$("$build/embed" "$tmp/wall.dat" | grep '^cost:')
        steps=$(sed -E 's/.*CPU for ([0-9]+) settling.*/\1/' <<< "$line")
        us=$(sed -E 's/.* ([0-9.e+]+) us per step$/\1/' <<< "$line")
        printf '%8d %12d %14.1f %18.3f\n' "$n" "$steps" "$us" "$(awk -v u="$us" -v n="$n" 'BEGIN { print u / n }')"
    done
} | tee "$out"
