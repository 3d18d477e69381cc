# Shared helpers for tests/cli/*.sh (sourced: `. "$(dirname "$0")/lib/check.sh"`).
# Conventions (tests/run.sh): exit 77 after a "SKIP: reason" line = skipped; a line
# "XFAIL: <what> gap=<measured> tol=<tol>" = an expected failure (known gap, printed every run);
# "XPASS: ..." = an expected failure that now meets its tolerance (counted as failed).
RD_SKIP=77

# skip REASON: the test cannot run here
skip() { echo "SKIP: $*"; exit "$RD_SKIP"; }

# verdict WHAT OK(0|1) GAP TOL MODE(strict|xfail): returns 1 for a strict failure
verdict() {
    local what=$1 ok=$2 gap=$3 tol=$4 mode=$5
    if [ "$mode" = xfail ]; then
        if [ "$ok" = 1 ]; then echo "XPASS: $what gap=$gap tol=$tol (remove the xfail mark: it is met now)"
        else echo "XFAIL: $what gap=$gap tol=$tol"; fi
        return 0
    fi
    [ "$ok" = 1 ] && return 0
    echo "FAIL $what: gap=$gap tol=$tol"
    return 1
}

# energy_residual FILE: the run's summary energy_residual_max
energy_residual() {
    /usr/bin/python3 -c "import h5py; print('%.6g' % h5py.File('$1', 'r')['summary'].attrs['energy_residual_max'])"
}

# check_residual WHAT R: R within issue 10's bound, 1e-3 of the energy scale; returns 1 if not
check_residual() {
    verdict "$1 (energy residual)" "$(awk -v r="$2" 'BEGIN { print (r <= 1e-3) ? 1 : 0 }')" "$2" 1e-3 strict
}

# step_gap A A_FINE B B_FINE [EXTRA]: prints "gap tol ok": gap = |A - B|, tol = EXTRA (default 0)
# plus each scene's own change at a finer step, |A - A_FINE| + |B - B_FINE| (its step error),
# ok = 1 if gap <= tol
step_gap() {
    awk -v p="$1" -v pf="$2" -v w="$3" -v wf="$4" -v x="${5:-0}" 'BEGIN {
        g = p - w; if (g < 0) g = -g; a = p - pf; if (a < 0) a = -a; b = w - wf; if (b < 0) b = -b
        printf "%.4g %.4g %d\n", g, x + a + b, g <= x + a + b }'
}

# check_order WHAT A B: the residual A at a step falls to B at half of it by at least 2^1.5 = 2.83
# (order >= 1.5: between a first-order booking error's 2 and leapfrog's own second order's 4)
check_order() {
    local ratio
    ratio=$(awk -v a="$2" -v b="$3" 'BEGIN { printf "%.4g", (b > 0) ? a / b : 1e9 }')
    verdict "$1" "$(awk -v q="$ratio" 'BEGIN { print (q >= 2.83) ? 1 : 0 }')" "$ratio" ">=2.83" strict
}

# least_cpu TIMEFILE CMD...: runs CMD twice (its output discarded) and prints the lower user +
# system CPU time in s (less noise from a shared machine's load than wall time); returns 1 when
# a run fails
least_cpu() {
    local tf=$1 best="" t
    shift
    for _ in 1 2; do
        /usr/bin/time -o "$tf" -f '%U %S' "$@" > /dev/null 2>&1 || return 1
        t=$(awk 'END { print $1 + $2 }' "$tf")
        if [ -z "$best" ] || awk "BEGIN { exit !($t < $best) }"; then best=$t; fi
    done
    echo "$best"
}
