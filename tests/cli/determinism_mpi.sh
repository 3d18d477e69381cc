#!/usr/bin/env bash
# rd-test: alone
# Determinism over MPI: the sweep of tests/cli/determinism.sh run by rockdem-mpi on 2 ranks
# (rank 0 coordinates; rank 0 and rank 1 both run cases) gives the pinned DET_HASH. Skipped (exit 77)
# without mpicc/mpirun.
set -u
. "$(dirname "$0")/lib/check.sh"
. "$(dirname "$0")/lib/determinism.sh"
command -v mpicc > /dev/null && command -v mpirun > /dev/null ||
    skip "no mpicc/mpirun on PATH (Debian libopenmpi-dev openmpi-bin: tools/install-deps.sh)"
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/determinism_mpi; mkdir -p "$T/runs"
BINDIR=$(dirname "$BIN"); BUILD=${RD_BUILD:-build}
san=""   # a sanitizer build (make asan): link rockdem-mpi the same way
if nm "$BUILD/librockdem.a" 2>/dev/null | grep -q __asan_init; then
    san="-fsanitize=address,undefined"
    export ASAN_OPTIONS=detect_leaks=0   # OpenMPI's own allocations outlive MPI_Finalize
fi
make -s mpi BUILD="$BUILD" BIN="$BINDIR" SAN="$san" > "$T/mpi.log" 2>&1 || { cat "$T/mpi.log"; exit 1; }
mpirun --allow-run-as-root --oversubscribe -n 2 "$BINDIR/rockdem-mpi" sweep "$DET_SCENE" --scales "$DET_SCALES" \
    --directions "$DET_DIRECTIONS" --full -q --keep-runs "$T/runs" -o "$T/mpi.h5" >/dev/null || exit 1
det_check "MPI sweep (2 ranks)" "$(det_hash "$T"/runs/case-*.h5)"
