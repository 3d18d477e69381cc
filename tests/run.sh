#!/usr/bin/env bash
# Run every test: the CMocka unit/physics binaries in $BUILD/tests and the CLI checks in
# tests/cli/*.sh. Each test case lands in exactly one class:
#   passed   - every check met its tolerance;
#   failed   - a check missed, the program crashed, ran no test, or an expected failure passed
#              ("XPASS": its gap closed, so the mark must be removed and the check made strict);
#   skipped  - it could not run here: a CMocka skip() or a script exiting 77; the reason is the
#              test's line starting "SKIP:" (a script's last line will do; a skip without any
#              printed reason is a failure);
#   xfail    - an expected failure: a known, documented disagreement. The test prints one line
#              "XFAIL: <what> gap=<measured> tol=<tolerance>" on every run and otherwise passes.
# Conventions for test writers: tests/check.h (C) and tests/cli/lib/check.sh (shell).
# The last line is "N passed, N failed"; the line before it lists the skips and expected failures.
# Exits non-zero when anything failed (CI, .ci/run, runs this through `make test`).
set -u
BUILD=${1:-build}
BIN=${2:-bin}
SKIP_RC=77   # automake's convention for "skipped"
RD_BIN="$(cd "$(dirname "$BIN/rockdem")" 2>/dev/null && pwd)/rockdem"  # absolute: scripts may cd
RD_BUILD="$(cd "$BUILD" 2>/dev/null && pwd)"  # tests/cli/sweep_mpi.sh builds bin/rockdem-mpi from it
export RD_BIN RD_BUILD RD_TMP=$(mktemp -d)
trap 'rm -rf "$RD_TMP"' EXIT
pass=0; fail=0; skip=0; xfail=0
skips=(); xfails=()

# classify_cmocka NAME OUTPUT RC: one line per test case "CLASS<TAB>case<TAB>detail"
classify_cmocka() {
    printf '%s\n' "$2" | awk -v prog="$1" '
        /^\[ RUN      \] / { tc = $4; xf = ""; sk = ""; next }
        /^XFAIL: /  { d = substr($0, 8); sub(/ \(.*$/, "", d); xf = (xf == "" ? "" : xf "; ") d; next }
        /^XPASS: /  { xp[tc] = substr($0, 8); next }
        /^SKIP: /   { sk = substr($0, 7); next }
        /^\[       OK \] / {
            if (tc in xp) print "fail\t" prog "/" tc "\tXPASS: " xp[tc]
            else if (xf != "") print "xfail\t" prog "/" tc "\t" xf
            else print "pass\t" prog "/" tc "\t"
            ran++; next }
        /^\[  FAILED  \] / && $4 !~ /^[0-9]/ { if (!($4 in seen)) print "fail\t" prog "/" $4 "\t"; seen[$4] = 1; ran++; next }
        /^\[  SKIPPED \] / && $4 !~ /^[0-9]/ {
            if (!($4 in seen)) {
                if (sk == "") print "fail\t" prog "/" $4 "\tskipped without a SKIP: reason"
                else print "skip\t" prog "/" $4 "\t" sk
            }
            seen[$4] = 1; ran++; next }
        END { if (!ran) print "fail\t" prog "\tran no test" }'
    # a crash after the summary (or before any test) with a non-zero status
    if [ "$3" -ne 0 ] && ! printf '%s\n' "$2" | grep -q '^\[  FAILED  \]'; then
        printf 'fail\t%s\texit status %d without a failed test (crash?)\n' "$1" "$3"
    fi
}

# classify_script NAME OUTPUT RC. A script that prints one line per check ("CHECK ..." when met,
# "XFAIL: ..." for a known gap, "FAIL ..." when missed: tools/validate/ladder.py) is counted per
# check; any other script is one case.
classify_script() {
    local xp sk nchk
    xp=$(printf '%s\n' "$2" | sed -n 's/^XPASS: //p' | paste -sd ';' -)
    sk=$(printf '%s\n' "$2" | sed -n 's/^SKIP: //p' | paste -sd ';' -)
    nchk=$(printf '%s\n' "$2" | grep -cE '^(CHECK |XFAIL: |FAIL )')
    if [ "$3" -eq "$SKIP_RC" ]; then   # the reason: its "SKIP:" line, else its last line
        [ -z "$sk" ] && sk=$(printf '%s\n' "$2" | sed '/^[[:space:]]*$/d' | tail -n1)
        if [ -n "$sk" ]; then printf 'skip\t%s\t%s\n' "$1" "$sk"
        else printf 'fail\t%s\texit %d (skip) without a printed reason\n' "$1" "$SKIP_RC"; fi
        return
    fi
    [ -n "$xp" ] && printf 'fail\t%s\tXPASS: %s\n' "$1" "$xp"
    if [ "$nchk" -gt 0 ]; then
        printf '%s\n' "$2" | awk -v n="$1" '
            /^CHECK / { print "pass\t" n "\t"; next }
            /^XFAIL: / { d = substr($0, 8); sub(/ \(.*$/, "", d); print "xfail\t" n "\t" d; next }
            /^FAIL / { print "fail\t" n "\t" substr($0, 6); f++ }
            END { if (!f && rc != 0) print "fail\t" n "\texit status " rc }' rc="$3"
    elif [ "$3" -ne 0 ]; then printf 'fail\t%s\texit status %d\n' "$1" "$3"
    elif [ -z "$xp" ]; then printf 'pass\t%s\t\n' "$1"; fi
}

# tally OUTPUT CLASSES: add the classified cases to the counts, print one line per program
tally() {
    local name=$1 out=$2 lines=$3 cls tc detail p=0 f=0 s=0 x=0
    while IFS=$'\t' read -r cls tc detail; do
        case $cls in
            pass) p=$((p + 1)) ;;
            fail) f=$((f + 1)); [ -n "$detail" ] && echo "  FAILED $tc: $detail" ;;
            skip) s=$((s + 1)); skips+=("$tc ($detail)") ;;
            xfail) x=$((x + 1)); xfails+=("$tc: $detail") ;;
        esac
    done <<< "$lines"
    printf '%-40s %3d passed, %d failed, %d skipped, %d xfail\n' "$name" "$p" "$f" "$s" "$x"
    printf '%s\n' "$out" | grep -E '^(XFAIL|XPASS|SKIP): ' | sed 's/^/  /'
    [ "$f" -ne 0 ] && printf '%s\n' "$out" | grep -E 'FAILED|ERROR|error|Assert|FAIL|Traceback' | grep -v '^XFAIL' | head -30
    pass=$((pass + p)); fail=$((fail + f)); skip=$((skip + s)); xfail=$((xfail + x))
}

# Every test runs in its own scratch directory ($RD_TMP/NAME), RD_JOBS at a time (default: one
# per core); a script with the line "# rd-test: alone" (it times itself or builds) runs after the
# others, by itself. Results are tallied in the listed order, whatever order they finished in.
JOBS=${RD_JOBS:-$(nproc)}
OUT="$RD_TMP/.results"; mkdir -p "$OUT"
tests=(); alone=()
for t in "$BUILD"/tests/test_*; do [ -x "$t" ] && tests+=("$t"); done
for s in tests/cli/*.sh; do
    [ "${RD_TESTS:-all}" = unit ] && break   # RD_TESTS=unit: the CMocka binaries only
    [ -f "$s" ] || continue
    tests+=("$s")
    grep -q '^# rd-test: alone' "$s" && alone+=("$s")
done

# run_one PATH: its output in $OUT/NAME.out, its exit status in .rc, its wall seconds in .s
run_one() {
    local name start; name=$(basename "$1"); start=$(date +%s)
    mkdir -p "$RD_TMP/$name"
    case $1 in
        *.sh) RD_TMP="$RD_TMP/$name" bash "$1" > "$OUT/$name.out" 2>&1 ;;
        *) "$1" > "$OUT/$name.out" 2>&1 ;;
    esac
    echo $? > "$OUT/$name.rc"; echo $(($(date +%s) - start)) > "$OUT/$name.s"
}
is_alone() { local a; for a in "${alone[@]}"; do [ "$a" = "$1" ] && return 0; done; return 1; }
for t in "${tests[@]}"; do
    is_alone "$t" && continue
    while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n; done
    run_one "$t" &
done
wait
for t in "${alone[@]}"; do run_one "$t"; done

for t in "${tests[@]}"; do
    name=$(basename "$t"); out=$(cat "$OUT/$name.out"); rc=$(cat "$OUT/$name.rc")
    case $t in
        *.sh) lines=$(classify_script "$name" "$out" "$rc")
              tally "$name ($(cat "$OUT/$name.s") s)" "$out" "$lines"
              case $lines in fail*) printf '%s\n' "$out" | tail -30 ;; esac ;;
        *) tally "$name ($(cat "$OUT/$name.s") s)" "$out" "$(classify_cmocka "$name" "$out" "$rc")" ;;
    esac
done
summary="$skip skipped"
[ "$skip" -gt 0 ] && summary="$summary ($(printf '%s; ' "${skips[@]}" | sed 's/; $//'))"
summary="$summary, $xfail expected failures"
[ "$xfail" -gt 0 ] && summary="$summary ($(printf '%s; ' "${xfails[@]}" | sed 's/; $//'))"
echo "$summary"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
