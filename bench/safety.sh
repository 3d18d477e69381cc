#!/usr/bin/env bash
# The step's safety factor by measured time to solution (issue 44, item 6): for each factor of
# SAFETIES, the fast validation ladder (tools/validate/ladder.py --depth fast, every DEM run
# with --set model.safety=S: its rows against the references and their tolerances) and the
# shipped PBR study's cost per run (bench/pbr_study.sh, SAFETY=S: a 12-run sample of 20 s
# records). A factor is usable when its ladder has no FAIL; the cheapest usable one is the
# time to solution at the accuracy the docs promise.
#
#   bash bench/safety.sh [BINDIR]       (about 10-15 min per factor on 2 idle cores)
#
# Environment: SAFETIES (comma-separated, default 0.1,0.2,0.3,0.5,1.0), OUT (keep each factor's
# ladder report and log there; default: a temporary folder, deleted). Also ladder overrides:
# a row whose own run sets model.safety (the 10-drum column at 0.1) runs at S as well.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd); root=$(dirname "$here")
bindir=${1:-bin}; case $bindir in /*) ;; *) bindir="$PWD/$bindir" ;; esac
die() { echo "bench/safety.sh: $*" >&2; exit 1; }
[ -x "$bindir/rockdem" ] || die "no rockdem executable at $bindir/rockdem (build it first: make)"
safeties=${SAFETIES:-0.1,0.2,0.3,0.5,1.0}
for s in ${safeties//,/ }; do
    awk -v s="$s" 'BEGIN { exit !(s ~ /^[0-9.]+$/ && s > 0 && s <= 1) }' ||
        die "SAFETIES: each factor must be a number in (0, 1], got '$s'"
done
if [ -n "${OUT:-}" ]; then out=$OUT; mkdir -p "$out"; else out=$(mktemp -d); trap 'rm -rf "$out"' EXIT; fi

printf '%-7s %5s %5s %6s %6s %9s %12s\n' safety pass FAIL xfail xpass ladder_s pbr_cpu_s/run
for s in ${safeties//,/ }; do
    t0=$(date +%s)
    # the ladder exits 1 on a FAIL: that is a measurement here, not an error of this script
    /usr/bin/python3 "$root/tools/validate/ladder.py" --depth fast --bin "$bindir/rockdem" \
        --set "model.safety=$s" --md "$out/ladder-$s.md" > "$out/ladder-$s.log" 2>&1 || true
    t1=$(date +%s)
    line=$(grep '^ladder (' "$out/ladder-$s.log") || die "safety $s: the ladder did not finish ($out/ladder-$s.log)"
    read -r pass fail xfail xpass <<< "$(echo "$line" | sed -E 's/.*: ([0-9]+) pass, ([0-9]+) FAIL, ([0-9]+) xfail, ([0-9]+) xpass.*/\1 \2 \3 \4/')"
    SAFETY=$s bash "$here/pbr_study.sh" "$bindir" > "$out/study-$s.log" 2>&1 ||
        die "safety $s: bench/pbr_study.sh failed ($out/study-$s.log)"
    cpu=$(sed -nE 's/^per run: ([0-9.]+) CPU s.*/\1/p' "$out/study-$s.log")
    printf '%-7s %5s %5s %6s %6s %9s %12s\n' "$s" "$pass" "$fail" "$xfail" "$xpass" $((t1 - t0)) "$cpu"
    grep '^FAIL\|^XPASS' "$out/ladder-$s.log" | sed 's/^/    /' || true
done
echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')  load average: $(cut -d' ' -f1-3 /proc/loadavg)  ($(nproc) cpus)"
