#!/usr/bin/env bash
# The benchmarks behind docs/PERFORMANCE.md's tables (`make docs-bench`): each script's output,
# with a first line (script, date, commit, load) and a last one (end time, load), into
# BUILD/bench/out/NAME.txt, which tools/docgen.py copies into the doc.
#   bash bench/docs_bench.sh [BINDIR [BUILD]]
set -eu
bindir=${1:-bin}; build=${2:-build}
here=$(cd "$(dirname "$0")" && pwd)
out="$build/bench/out"; mkdir -p "$out"
load() { cut -d' ' -f1-3 /proc/loadavg; }
for s in kernel run impact_cost columns pbr_study; do
    args=("$bindir"); [ "$s" = kernel ] && args+=("$build/bench")
    echo "bench/$s.sh ..." >&2
    { echo "# bench/$s.sh $(date -u '+%F %H:%M UTC') $(git -C "$here" rev-parse --short HEAD) load $(load)"
      bash "$here/$s.sh" "${args[@]}"
      echo "# end $(date -u '+%H:%M UTC') load $(load)"; } > "$out/$s.txt.tmp" 2>&1
    mv "$out/$s.txt.tmp" "$out/$s.txt"
done
