#!/usr/bin/env bash
# Determinism (Box2D's test_determinism): the final state of a fixed scene, hashed, equals the
# pinned DET_HASH (tests/cli/lib/determinism.sh, with how to update it) for single runs, for a
# -j 1 sweep and for a -j 2 sweep (fork pool; the MPI sweep: determinism_mpi.sh). Each case is
# run as its own `rockdem run` and through `rockdem sweep --keep-runs --full` (the sweep's quiet
# end, src/engine/quiet_end.c, would stop cases that the single runs run on).
set -u
. "$(dirname "$0")/lib/determinism.sh"
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/determinism; mkdir -p "$T"
fails=0
files=()
for s in ${DET_SCALES//,/ }; do
    for d in ${DET_DIRECTIONS//,/ }; do
        f="$T/single-$s-$d.h5"
        "$BIN" run "$DET_SCENE" --set motion.amplitude=$s --set motion.direction=$d -q -o "$f" >/dev/null || fails=$((fails + 1))
        files+=("$f")
    done
done
det_check "single runs" "$(det_hash "${files[@]}")" || fails=$((fails + 1))
for j in 1 2; do
    rm -rf "$T/j$j"; mkdir -p "$T/j$j"
    "$BIN" sweep "$DET_SCENE" --scales "$DET_SCALES" --directions "$DET_DIRECTIONS" --full -j $j -q \
        --keep-runs "$T/j$j" -o "$T/sweep-j$j.h5" >/dev/null || fails=$((fails + 1))
    det_check "sweep -j $j" "$(det_hash "$T"/j$j/case-*.h5)" || fails=$((fails + 1))
done
[ "$fails" -eq 0 ]
