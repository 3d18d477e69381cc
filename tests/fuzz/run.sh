#!/usr/bin/env bash
# Run each libFuzzer target for a fixed time on one core: tests/fuzz/run.sh DIR SECONDS TARGET...
# DIR holds the fuzz_<target> binaries (make fuzz). Each target starts from the committed seed
# corpus tests/fuzz/corpus/<target>/ plus the regression inputs tests/fuzz/regress/<target>/; the
# inputs it finds interesting go to a scratch corpus ($RD_FUZZ_WORK, default build-fuzz/work) so
# the repository is not touched; crashes, leaks and timeouts are written to
# tests/fuzz/found/<target>/ for triage (fix, then move the input to tests/fuzz/regress/<target>/,
# which tests/test_fuzz_regress.c replays in make test). Prints one summary line per target.
set -u
dir=$1; secs=$2; shift 2
here=$(cd "$(dirname "$0")" && pwd)
work=${RD_FUZZ_WORK:-build-fuzz/work}
status=0
for t in "$@"; do
    mkdir -p "$work/$t" "$here/found/$t" "$here/regress/$t"
    log="$work/$t.log"; t0=$SECONDS
    # -timeout: one input may take at most 10 s; -rss_limit_mb: 2 GiB; -max_len: 64 KiB inputs
    "$dir/fuzz_$t" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
        -dict="$here/scenario.dict" -artifact_prefix="$here/found/$t/" -print_final_stats=1 \
        "$work/$t" "$here/corpus/$t" "$here/regress/$t" > "$log" 2>&1
    rc=$?
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n1)
    found=$(find "$here/found/$t" -type f | wc -l)
    printf 'fuzz %-9s %5ss of %5ss %10s executions  exit %d  %d input(s) in tests/fuzz/found/%s/\n' \
        "$t" "$((SECONDS - t0))" "$secs" "${execs:-?}" "$rc" "$found" "$t"
    [ "$rc" -ne 0 ] && { status=1; grep -m3 -E 'ERROR|SUMMARY|runtime error' "$log"; }
done
exit $status
