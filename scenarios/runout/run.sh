#!/usr/bin/env bash
# The runout example (docs/RUNOUT.md): a PBR on its pedestal above a hillside, shaken until it
# topples, run until it rests; its plan view, then a 4-case ensemble (2 directions x 2
# amplitudes) and its exceedance curves. Figures into OUT (default docs/runout).
# Wall time on the shared 2-core machine: about 4 min for the run, 20 min for the ensemble (-j 1).
set -eu
cd "$(dirname "$0")"
ROOT=../..; OUT=${1:-$ROOT/docs/runout}; mkdir -p "$OUT"
BIN=$ROOT/bin/rockdem; PY=/usr/bin/python3
"$BIN" run pbr_runout.dat -q -o "$OUT/pbr_runout.h5"
$PY $ROOT/tools/rdrunout.py plan "$OUT/pbr_runout.h5" --terrain hillside.asc -o "$OUT/pbr_runout_plan.png"
[ "${ENSEMBLE:-1}" = 0 ] && exit 0
"$BIN" sweep pbr_runout.dat --directions -20,0 --axis motion.amplitude=0.6g,0.9g -j "${JOBS:-1}" -q \
    -o "$OUT/pbr_runout_sweep.h5"
$PY $ROOT/tools/rdrunout.py exceedance "$OUT/pbr_runout_sweep.h5" -o "$OUT/pbr_runout_exceedance.png"
