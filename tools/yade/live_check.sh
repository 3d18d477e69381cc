#!/usr/bin/env bash
# Live YADE cross-check for CI (.ci/run): translate tests/data/yade/free.dat (0.5 s simulated),
# run it in YADE and in rockdem, and compare the first impact time (tolerance 5 ms: YADE moves
# 0.04 ms when its step is halved, rockdem vs YADE differ by ~1.5 ms, docs/YADE.md) and the
# peak tilt (release tilt, must agree to 1e-3).
#   bash tools/yade/live_check.sh [BINDIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bindir=${1:-bin}; case $bindir in /*) ;; *) bindir="$PWD/$bindir" ;; esac
command -v yade >/dev/null || { echo "live_check: yade not installed (apt-get install yade)" >&2; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
dat="$root/tests/data/yade/free.dat"
"$bindir/rockdem" run "$dat" --set model.duration=0.5 --set output.interval=0.001 -o "$tmp/rd.h5" -q </dev/null >/dev/null
/usr/bin/python3 "$root/tools/yade/translate.py" "$dat" --set model.duration=0.5 \
    --set output.interval=0.001 -o "$tmp/yade.h5" </dev/null | grep '^yade-run:'
/usr/bin/python3 "$root/tools/yade/compare.py" free "$tmp/rd.h5" "$tmp/yade.h5" --tol-time 0.005 --tol-amp 10
/usr/bin/python3 "$root/tools/yade/compare.py" outcome "$tmp/rd.h5" "$tmp/yade.h5" --tol-tilt 1e-3
echo "live_check: ok"
