#!/usr/bin/env bash
# The quiet end of a sweep case (src/engine/quiet_end.c): a case ends once the brick is at rest
# and what is left of its record can no longer lift or slide it, with the answer of the full
# run (`rockdem sweep --full`), and a case whose remaining record could still lift it runs on.
# The brick of tests/cli/data/sweep_brick.dat (tan alpha = 0.4, g tan alpha = 0.4 g; friction
# 40 deg) under two text records (g, dt 5 ms, no baseline correction):
#   tail: 1 s of a 3 Hz sine at 0.2 g (half the uplift limit), then 5 s at 0.01 g (0.025 of
#         it, under the quiet end's margin 0.1): it must end early, not before its last
#         sample above 0.04 g (near 1 s), and agree;
#   late: 3 s at 0.01 g, then two 2 Hz cycles at 0.6 g (past the uplift limit), then 2.5 s of
#         rest: the brick is at rest at first, under a small ground motion, but the record left
#         can lift it, so it must not end before the strong part, and it must rock (max tilt /
#         alpha > 0.01) as in the full run. A naive criterion (at rest, or the acceleration now
#         below the limit) ends it in the first second, at a max tilt / alpha near 0.
# Tolerances: max tilt / alpha within RD_MODE_TILT_MIN = 1e-3 (the sweep's rocking resolution,
# include/rockdem/sweep.h), max slide within RD_MODE_SLIP_MIN = 1e-3 m (seed 002's mm
# displacement resolution); overturned and mode identical.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/quiet_end; mkdir -p "$T"
/usr/bin/python3 - "$T" <<'PY'
import sys, numpy as np
d = sys.argv[1]; dt = 0.005; t = np.arange(0, 6 + dt / 2, dt)
tail = np.where(t < 1, 0.2, 0.01) * np.sin(2 * np.pi * 3 * t)
late = np.where(t < 3, 0.01 * np.sin(2 * np.pi * 3 * t),
                np.where(t < 4, 0.6 * np.sin(2 * np.pi * 2 * (t - 3)), 0.0))
np.savetxt(d + "/tail.txt", tail); np.savetxt(d + "/late.txt", late)
PY
sed -e '/^ground-motion/d' -e 's/^model solve time .*/model solve time 6/' \
    -e "s|^output hdf5 .*|output hdf5 '$T/run.h5' interval 0.01|" tests/cli/data/sweep_brick.dat > "$T/brick.dat"
echo "ground-motion import '$T/tail.txt' format text units g dt 0.005 baseline off direction 0" >> "$T/brick.dat"
"$BIN" sweep "$T/brick.dat" --records "$T/tail.txt,$T/late.txt" -j 2 -q -o "$T/quiet.h5"
"$BIN" sweep "$T/brick.dat" --records "$T/tail.txt,$T/late.txt" -j 2 -q --full -o "$T/full.h5"
/usr/bin/python3 - "$T/quiet.h5" "$T/full.h5" "$T/tail.txt" <<'PY'
import sys, h5py, numpy as np
q, f = h5py.File(sys.argv[1], "r")["sweep"], h5py.File(sys.argv[2], "r")["sweep"]
TILT, SLIDE = 1e-3, 1e-3  # RD_MODE_TILT_MIN, RD_MODE_SLIP_MIN
ok = True
def check(cond, what):
    global ok
    print(("CHECK " if cond else "FAIL ") + what)
    ok &= bool(cond)
for k, name in enumerate(["tail", "late"]):
    qe, fe = q["quiet_end"][k], f["quiet_end"][k]
    dq = abs(q["max_tilt_ratio"][k] - f["max_tilt_ratio"][k])
    ds = abs(q["max_slide"][k] - f["max_slide"][k])
    check(fe == -1 and f["end_time"][k] > 5.99, "quiet_end %s: --full runs to 6 s (quiet_end %g)" % (name, fe))
    check(q["overturned"][k] == f["overturned"][k] and q["mode"][k] == f["mode"][k],
          "quiet_end %s: overturned %d / %d, mode %s / %s (quiet / full)" % (
              name, q["overturned"][k], f["overturned"][k], q["mode"][k], f["mode"][k]))
    check(dq <= TILT and ds <= SLIDE, "quiet_end %s: max tilt/alpha %.4g / %.4g, max slide %.3g / %.3g m "
          "(tol %g, %g m)" % (name, q["max_tilt_ratio"][k], f["max_tilt_ratio"][k],
                              q["max_slide"][k], f["max_slide"][k], TILT, SLIDE))
    if name == "tail":
        a = np.loadtxt(sys.argv[3])  # g; the last sample above 0.1 tan(alpha) = 0.04 g
        t_last = 0.005 * np.nonzero(np.abs(a) > 0.04)[0][-1]
        check(t_last - 0.005 <= qe < 2.0 and q["end_time"][k] == qe,
              "quiet_end tail: ends quietly at %g s (after %g s, its last sample above 0.04 g, "
              "before 2 s)" % (qe, t_last))
    else:
        check(qe == -1 or qe >= 4.0, "quiet_end late: not ended before the strong part (quiet_end %g s)" % qe)
        check(f["max_tilt_ratio"][k] > 0.01, "quiet_end late: the strong part rocks it (max tilt/alpha %.3g)"
              % f["max_tilt_ratio"][k])
sys.exit(0 if ok else 1)
PY
