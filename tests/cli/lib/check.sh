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
