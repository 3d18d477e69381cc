#!/usr/bin/env bash
# Run every test: the CMocka unit/physics binaries in $BUILD/tests and the CLI checks in
# tests/cli/*.sh. Ends with one line "N passed, N failed"; exits non-zero when anything failed.
set -u
BUILD=${1:-build}
BIN=${2:-bin}
RD_BIN="$(cd "$(dirname "$BIN/rockdem")" 2>/dev/null && pwd)/rockdem"  # absolute: scripts may cd
RD_BUILD="$(cd "$BUILD" 2>/dev/null && pwd)"  # tests/cli/sweep_mpi.sh builds bin/rockdem-mpi from it
export RD_BIN RD_BUILD RD_TMP=$(mktemp -d)
trap 'rm -rf "$RD_TMP"' EXIT
pass=0; fail=0; skip=0
for t in "$BUILD"/tests/test_*; do
    [ -x "$t" ] || continue
    out=$("$t" 2>&1); rc=$?
    p=$(printf '%s\n' "$out" | sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' | tail -n1)
    f=$(printf '%s\n' "$out" | sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' | tail -n1)
    p=${p:-0}; f=${f:-0}
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi   # crashed before its summary
    printf '%-40s %3d passed, %d failed\n' "$(basename "$t")" "$p" "$f"
    [ "$f" -ne 0 ] && printf '%s\n' "$out" | grep -E 'FAILED|ERROR|error|Assert|fail' | head -20
    pass=$((pass + p)); fail=$((fail + f))
done
for s in tests/cli/*.sh; do
    [ -f "$s" ] || continue
    out=$(bash "$s" 2>&1); rc=$?
    if [ "$rc" -eq 0 ]; then
        pass=$((pass + 1)); printf '%-40s ok\n' "$(basename "$s")"
    elif [ "$rc" -eq 77 ]; then   # the environment lacks what the script needs: it says what
        skip=$((skip + 1)); printf '%-40s SKIPPED: %s\n' "$(basename "$s")" "$(printf '%s\n' "$out" | tail -n1)"
    else
        fail=$((fail + 1)); printf '%-40s FAILED\n%s\n' "$(basename "$s")" "$out" | head -30
    fi
done
[ "$skip" -gt 0 ] && echo "$skip skipped (not counted as passed)"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
