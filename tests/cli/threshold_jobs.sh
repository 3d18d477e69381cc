#!/usr/bin/env bash
# rockdem threshold -j N: the coarse scan runs N amplitudes at once in worker processes and takes
# their outcomes in scan order, so the result must be the serial scan's exactly (same amplitudes,
# same arithmetic, deterministic runs): every printed number but the run count is compared as
# text between -j 1 and -j 2, 3, 5 and the default, with the DEM (a brick whose scan crosses
# overturning after several batches) and the reference (a two-frequency curve). The run count
# shows the batches: with --rtol 1 (no bisection) the serial scan makes k + 1 runs (k: the index
# of the first overturning amplitude) and -j N makes k + 1 rounded up to a multiple of N (at most
# steps + 1). Bad -j values give one clear line and exit 2.
set -u
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/threshold_jobs; mkdir -p "$T"
S=tests/cli/data/sweep_brick.dat
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
# a fine scan of the brick (g tan alpha = 3.92 m/s^2, DEM threshold near 6.4 m/s^2): 12 steps
# of 0.29 m/s^2, so the first overturning amplitude is several batches in for every -j below
scan=(--engine dem --lo 3.5 --hi 7 --steps 12 -q)
strip_runs() { sed 's/, [0-9]* runs)/)/'; }

"$BIN" threshold "$S" "${scan[@]}" --rtol 0.01 -j 1 > "$T/j1.txt" || fail "dem -j 1: $(cat "$T/j1.txt")"
grep -q "minimum overturning amplitude" "$T/j1.txt" || fail "dem -j 1 found no threshold: $(cat "$T/j1.txt")"
for j in 2 3 5 default; do
    opt=(-j "$j"); [ "$j" = default ] && opt=()
    "$BIN" threshold "$S" "${scan[@]}" --rtol 0.01 "${opt[@]}" > "$T/j$j.txt" || fail "dem -j $j failed"
    cmp -s <(strip_runs < "$T/j1.txt") <(strip_runs < "$T/j$j.txt") ||
        fail "dem -j $j differs from the serial scan: $(cat "$T/j$j.txt") vs $(cat "$T/j1.txt")"
done

# the batches, seen in the run count of the scan alone
runs() { sed -n 's/.*, \([0-9]*\) runs).*/\1/p' "$1"; }
"$BIN" threshold "$S" "${scan[@]}" --rtol 1 -j 1 > "$T/r1.txt" || fail "dem --rtol 1 -j 1 failed"
k1=$(runs "$T/r1.txt")
[ -n "$k1" ] && [ "$k1" -ge 3 ] || fail "the scan should cross after several batches: $k1 runs"
for j in 2 3 5; do
    "$BIN" threshold "$S" "${scan[@]}" --rtol 1 -j "$j" > "$T/r$j.txt" || fail "dem --rtol 1 -j $j failed"
    want=$(( (k1 + j - 1) / j * j )); [ "$want" -gt 13 ] && want=13
    got=$(runs "$T/r$j.txt")
    [ "$got" = "$want" ] || fail "-j $j: $got scan runs, expected $want (serial $k1, in batches of $j)"
    cmp -s <(strip_runs < "$T/r1.txt") <(strip_runs < "$T/r$j.txt") || fail "dem --rtol 1 -j $j: other bracket"
done

# the reference engine: a two-frequency curve (the runs column aside)
blk="$T/block.dat"
cat > "$blk" <<'DAT'
block create brick size 4 4 1 position 0 0 -0.5 fixed name base
block create brick size 0.5 0.5 1.0 position 0 0 0.5 name b
contact property stiffness-normal 1e10 stiffness-shear 1e10 friction 80 spacing vertices
ground-motion pulse one-sine amplitude 1.3g frequency 2
model solve time 3
DAT
for j in 1 4; do
    "$BIN" threshold "$blk" --engine reference --frequencies 1,2 -j "$j" -q | awk '{ $NF = ""; print }' \
        > "$T/ref$j.txt" || fail "reference -j $j failed"
done
[ "$(grep -c '^ *[0-9]' "$T/ref1.txt")" -eq 2 ] || fail "reference curve: $(cat "$T/ref1.txt")"
cmp -s "$T/ref1.txt" "$T/ref4.txt" || fail "reference -j 4 differs: $(cat "$T/ref4.txt") vs $(cat "$T/ref1.txt")"

for bad in 0 -2 1.5 x 100000; do
    err=$("$BIN" threshold "$S" -j "$bad" 2>&1 >/dev/null); rc=$?
    { [ "$rc" -eq 2 ] && [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] && printf '%s' "$err" | grep -q -- "-j"; } ||
        fail "-j $bad: rc=$rc $err"
done
[ "$fails" -eq 0 ] && echo "CHECK rockdem threshold -j: the serial scan's result (dem and reference), batches of N"
exit $((fails > 0))
