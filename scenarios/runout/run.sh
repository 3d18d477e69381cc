#!/usr/bin/env bash
# The runout examples (docs/RUNOUT.md), figures into OUT (default docs/runout):
#  1. pbr_runout.dat, a convex rock: its run and plan view, then a 4-case ensemble (2 directions
#     x 2 amplitudes) and its exceedance curves (about 4 min and 20 min at -j 1, shared machine);
#  2. pbr_scan_runout.dat, the scanned PBR (scenarios/pbr.obj): a 2-case ensemble (0.5 g and
#     0.6 g, every run file kept), the plan view of its 0.6 g case, the exceedance curves, and
#     the energy residuals against the trusted 1e-3 (about 25 min at -j 2, shared machine).
# EXAMPLE=1 or 2 runs one of them; ENSEMBLE=0 skips the first one's ensemble.
set -eu
cd "$(dirname "$0")"
ROOT=../..; OUT=${1:-$ROOT/docs/runout}; mkdir -p "$OUT"
BIN=$ROOT/bin/rockdem; PY=/usr/bin/python3
if [ "${EXAMPLE:-1}" = 1 ] || [ -z "${EXAMPLE:-}" ]; then
    "$BIN" run pbr_runout.dat -q -o "$OUT/pbr_runout.h5"
    $PY $ROOT/tools/rdrunout.py plan "$OUT/pbr_runout.h5" --terrain hillside.asc -o "$OUT/pbr_runout_plan.png"
    if [ "${ENSEMBLE:-1}" != 0 ]; then
        "$BIN" sweep pbr_runout.dat --directions -20,0 --axis motion.amplitude=0.6g,0.9g -j "${JOBS:-1}" -q \
            -o "$OUT/pbr_runout_sweep.h5"
        $PY $ROOT/tools/rdrunout.py exceedance "$OUT/pbr_runout_sweep.h5" -o "$OUT/pbr_runout_exceedance.png"
    fi
fi
[ "${EXAMPLE:-2}" = 2 ] || [ -z "${EXAMPLE:-}" ] || exit 0
[ -f ../pbr.obj ] || $PY $ROOT/tools/make_pbr.py --seed 1 -o ../pbr.obj > /dev/null # as make does
RUNS=$(mktemp -d)
"$BIN" sweep pbr_scan_runout.dat --axis motion.amplitude=0.5g,0.6g -j "${JOBS:-2}" -q --keep-runs "$RUNS" \
    -o "$OUT/pbr_scan_sweep.h5"
$PY - "$OUT/pbr_scan_sweep.h5" "$RUNS" "$OUT/pbr_scan_runout.h5" <<'PY'
# the 0.6 g case's run file is the example's run; every case's energy residual against the
# trusted limit 1e-3 (docs/VALIDATION.md): an XFAIL with its gap when above
import shutil, sys, h5py
t = h5py.File(sys.argv[1], "r")["sweep"]
amps = [a.decode() if isinstance(a, bytes) else str(a) for a in t["motion.amplitude"][:]]
for k, res in enumerate(t["energy_residual"][:]):
    if amps[k] == "0.6g":
        shutil.copy(f"{sys.argv[2]}/case-{int(t['case'][k]):06d}.h5", sys.argv[3])
    print(("CHECK" if res <= 1e-3 else "XFAIL") + f": scanned PBR tumbling at {amps[k]}: energy "
          f"residual {res:.3g} gap={max(res - 1e-3, 0):.3g} tol=1e-3")
PY
rm -rf "$RUNS"
$PY $ROOT/tools/rdrunout.py plan "$OUT/pbr_scan_runout.h5" --terrain hillside_wide.asc \
    -o "$OUT/pbr_scan_runout_plan.png"
$PY $ROOT/tools/rdrunout.py exceedance "$OUT/pbr_scan_sweep.h5" -o "$OUT/pbr_scan_runout_exceedance.png"
