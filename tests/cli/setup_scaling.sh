#!/bin/bash
# rd-test: alone
# Setup and output of a run file grow linearly with the bodies (issue 44): bench/wall.py walls
# of 1,000 and 4,000 bricks (layout 3 sets up 1,000 in about 0.2 CPU-s: the smaller wall
# stays well above the 0.01 s resolution of the timer) with `model settle off` and a 1e-4 s solve (a few steps: the time is
# the scene's setup and the HDF5 file). Four times the bricks must cost less than 8 times the
# CPU time: linear setup gives 4x, a quadratic part (one that scans every body for each body,
# as the scale linking did: 3.97 -> 76.2 CPU-s from 500 to 2,000 bricks, 19x) gives 16x; 8 is
# their geometric mean, the midpoint between the two hypotheses on a shared machine whose load
# moves either figure by a factor of about 1.5. Each size takes the lower of two runs' user +
# system CPU time (less noise from the load than wall time).
set -u
. "$(dirname "$0")/lib/check.sh"
T=${RD_TMP:-$(mktemp -d)}
bin=${RD_BIN:-bin/rockdem}
fail=0

cpu_of() { # cpu_of N: the lower CPU time (s) of two setups of an N-brick wall
    /usr/bin/python3 bench/wall.py "$1" |
        sed 's/^model settle .*/model settle off/; s/^model solve time .*/model solve time 0.0001/' \
            > "$T/wall$1.dat"
    least_cpu "$T/time$1" "$bin" run "$T/wall$1.dat" -q -o "$T/wall$1.h5" ||
        { echo "FAIL run of the $1-brick wall" >&2; return 1; }
}

small=$(cpu_of 1000) || { echo "FAIL run of the 1000-brick wall"; exit 1; }
large=$(cpu_of 4000) || { echo "FAIL run of the 4000-brick wall"; exit 1; }
ratio=$(awk -v a="$small" -v b="$large" 'BEGIN { printf "%.3g", (a > 0) ? b / a : 1e9 }')
echo "CHECK setup CPU-s: 1000 bricks $small, 4000 bricks $large, ratio $ratio (linear 4, quadratic 16)"
verdict "setup of 4x the bricks within 8x the CPU time" \
    "$(awk -v q="$ratio" 'BEGIN { print (q < 8) ? 1 : 0 }')" "$ratio" "<8" strict || fail=1
exit $fail
