#!/usr/bin/env bash
# One run on several threads (engine/workers.c, issue 44): the contact loop's live pairs, the
# joint measures and the body loops run on an OpenMP team, and every sum that pairs share is
# played back in the serial loop's order, so a run gives the same bits on any number of threads.
# 1. A 400-brick wall (bench/wall.py 400, about 1,200 live pairs: threaded in bin/rockdem) on
#    1, 2 and 3 threads (OMP_NUM_THREADS, then --set model.threads): the perf line must report
#    the threads asked for (threads ignored fail here), and every numeric dataset and /summary
#    attribute but the wall time must equal the 1-thread run's to the bit (NaN equal to NaN).
# 2. Small scenes of every kind of contact (a block's edges on a pedestal, impacts, slip and a
#    topple, dashpots, drums, a mesh, bonds) with $(BUILD)/tests/rockdem-threads, the program
#    whose loops are threaded however few their items: on 3 threads it must give bin/rockdem's
#    1-thread bits.
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}
THR=${RD_BUILD:-build}/tests/rockdem-threads
[ -x "$THR" ] || { echo "FAIL threads: $THR not built (make test builds it)"; exit 1; }
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BIN=$(cd "$(dirname "$BIN")" && pwd)/$(basename "$BIN")
THR=$(cd "$(dirname "$THR")" && pwd)/$(basename "$THR")
T=${RD_TMP:-$(mktemp -d)}/threads; mkdir -p "$T"; cd "$T" || exit 1
unset OMP_NUM_THREADS
fails=0

# same NAME A.h5 B.h5: every numeric dataset and /summary attribute (but wall_seconds) equal
same() {
    /usr/bin/python3 - "$@" <<'PY'
import sys, h5py, numpy as np
name, fa, fb = sys.argv[1], h5py.File(sys.argv[2], "r"), h5py.File(sys.argv[3], "r")
n, bad = 0, []
def equal(key, x, y):
    x, y = np.asarray(x), np.asarray(y)
    if x.shape != y.shape:
        bad.append("%s shape %s vs %s" % (key, x.shape, y.shape)); return
    if x.dtype.kind == "f":
        ok = (x == y) | (np.isnan(x) & np.isnan(y))
    else:
        ok = x == y
    if not np.all(ok):
        bad.append("%s max|diff| %.3g" % (key, np.nanmax(np.abs(x.astype(float) - y.astype(float))))
                   if x.dtype.kind in "fiub" else key)
def visit(key, obj):
    global n
    if not isinstance(obj, h5py.Dataset) or obj.dtype.kind not in "fiub":
        return
    if key not in fb:
        bad.append(key + " (missing)"); return
    n += 1
    equal(key, obj[()], fb[key][()])
fa.visititems(visit)
for k, v in fa["summary"].attrs.items():
    if k != "wall_seconds":
        n += 1
        equal("summary@" + k, v, fb["summary"].attrs[k])
if n == 0 or bad:
    print("FAIL threads %s: %d of %d values differ: %s" % (name, len(bad), n, "; ".join(bad[:4])))
    sys.exit(1)
print("CHECK threads %s: %d datasets and attributes bit-identical to 1 thread" % (name, n))
PY
}

# threads_of OUTPUT: the perf line's threads=N
threads_of() { sed -n 's/^perf: .* threads=\([0-9]*\) .*/\1/p' <<< "$1"; }

/usr/bin/python3 "$ROOT/bench/wall.py" 400 > wall.dat
# case | environment | overrides | threads the perf line must report
cases=(
    "1|OMP_NUM_THREADS=1||1"
    "2|OMP_NUM_THREADS=2||2"
    "3|OMP_NUM_THREADS=3||3"
    "set-2|OMP_NUM_THREADS=1|--set model.threads=2|2"
)
for row in "${cases[@]}"; do
    IFS='|' read -r name envv over want <<< "$row"
    # shellcheck disable=SC2086  # the overrides are words
    out=$(env $envv "$BIN" run wall.dat $over -o "wall-$name.h5" 2>&1) ||
        { echo "FAIL threads wall $name: run failed: $(tail -n 2 <<< "$out")"; fails=$((fails + 1)); continue; }
    got=$(threads_of "$out")
    if [ "$got" != "$want" ]; then
        echo "FAIL threads wall $name: perf line reports threads=${got:-none}, asked for $want"
        fails=$((fails + 1)); continue
    fi
    [ "$name" = 1 ] && continue
    same "wall $name (threads=$got)" wall-1.h5 "wall-$name.h5" || fails=$((fails + 1))
done

cp "$ROOT/scenarios/pbr.obj" . 2>/dev/null || { echo "FAIL threads: scenarios/pbr.obj missing (make test makes it)"; exit 1; }
sed "s#'pbr.obj'#'$T/pbr.obj'#" "$ROOT/scenarios/pbr.dat" > pbr.dat
# name | scenario | overrides
scenes=(
    "default|$ROOT/scenarios/default.dat|--set model.duration=0.5"
    "brick-topples|$ROOT/tests/cli/data/sweep_brick.dat|--set motion.amplitude=1.0g"
    "impact|$ROOT/scenarios/seed000_impact.dat|--set model.duration=0.06"
    "damped-column|$ROOT/tests/cli/data/column4_damped.dat|--set model.duration=0.06"
    "cask-drum|$ROOT/scenarios/cask_drum.dat|--set model.duration=0.3"
    "joint-groups|$ROOT/scenarios/joint_groups.dat|--set model.duration=0.3"
    "stack-bonded|$ROOT/tests/cli/data/stack_bonded.dat|--set model.duration=0.5"
    "pbr|pbr.dat|--set model.duration=0.3"
)
for row in "${scenes[@]}"; do
    IFS='|' read -r name scene over <<< "$row"
    # shellcheck disable=SC2086
    OMP_NUM_THREADS=1 "$BIN" run "$scene" $over -q -o "$name-1.h5" > /dev/null 2>&1
    rc1=$?
    # shellcheck disable=SC2086
    out=$(OMP_NUM_THREADS=3 "$THR" run "$scene" $over -o "$name-3.h5" 2>&1)
    rc3=$?
    if [ "$rc1" != "$rc3" ]; then
        echo "FAIL threads $name: exit status $rc1 (1 thread) vs $rc3 (3 threads)"
        fails=$((fails + 1)); continue
    fi
    got=$(threads_of "$out")
    if [ "$got" != 3 ]; then
        echo "FAIL threads $name: rockdem-threads reports threads=${got:-none}, asked for 3"
        fails=$((fails + 1)); continue
    fi
    same "$name (rockdem-threads, threads=3)" "$name-1.h5" "$name-3.h5" || fails=$((fails + 1))
done
[ "$fails" -eq 0 ]
