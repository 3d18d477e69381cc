#!/usr/bin/env bash
# rd-test: alone
# rockdem-mpi: the same sweep over 2 MPI ranks (rank 0 writes the table; both ranks run cases)
# gives exactly the outcome columns of the single-machine sweep. Skipped (exit 77, counted as
# skipped by tests/run.sh) without mpicc/mpirun.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/sweep_mpi; mkdir -p "$T"
. "$(dirname "$0")/lib/check.sh"
command -v mpicc > /dev/null && command -v mpirun > /dev/null ||
    skip "no mpicc/mpirun on PATH (Debian libopenmpi-dev openmpi-bin: tools/install-deps.sh)"
BINDIR=$(dirname "$BIN")
BUILD=${RD_BUILD:-build}   # tests/run.sh passes its build folder
san=""   # a sanitizer build (make asan): link rockdem-mpi the same way
if nm "$BUILD/librockdem.a" 2>/dev/null | grep -q __asan_init; then
    san="-fsanitize=address,undefined"
    export ASAN_OPTIONS=detect_leaks=0   # OpenMPI's own allocations outlive MPI_Finalize
fi
make -s mpi BUILD="$BUILD" BIN="$BINDIR" SAN="$san" > "$T/mpi.log" 2>&1 || { cat "$T/mpi.log"; exit 1; }
S=tests/cli/data/sweep_brick.dat
args=(--scales 1.0g,2.0g,3.0g --directions 0,45)
"$BIN" sweep "$S" "${args[@]}" -j 2 -q -o "$T/one.h5"
mpirun --allow-run-as-root --oversubscribe -n 2 "$BINDIR/rockdem-mpi" sweep "$S" "${args[@]}" -q -o "$T/mpi.h5"
/usr/bin/python3 - "$T/one.h5" "$T/mpi.h5" <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r")["sweep"], h5py.File(sys.argv[2], "r")["sweep"]
assert sorted(a) == sorted(b)
for k in a:
    if k != "wall_seconds":
        assert np.array_equal(a[k][()], b[k][()]), k
PY
