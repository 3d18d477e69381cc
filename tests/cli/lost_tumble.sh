#!/usr/bin/env bash
# A body that overturned and fell out of the scene keeps its verdict (issue 10: a run reports
# what it found). A slender block topples off its narrow pedestal (nothing below it) while a
# stocky block on another pad stays, so the run goes on; the fallen block tumbles in free fall,
# and a tumbling block passes upright again. That counted as "recover", and the next escape
# check found a body below the scene that had not overturned: the run stopped with status
# "lost" and no verdict for either block (seen on a six-drum column at 0.6 g whose upper drums
# fell off the stylobate). Checks: the run ends "done"; the slender block is overturned, has
# one "lost" event and no "recover" after it; the stocky block has its verdict.
# Second case: a body that passes upright again while it is still falling, before it is below
# the scene: the YADE two-block stack at 1.0 g along 30 deg, whose upper block overturns at
# 1.80 s, falls off the base tumbling, "recovers" at 2.78 s and leaves the scene at 2.90 s. It
# had lost its verdict there (status "lost", no verdict for either block). Checks: exit 0, the
# upper block overturned at 1.80 s with one "lost" event, the lower block's verdict stands, and
# the case still takes that path (a "recover" before "lost": fails otherwise, so a change of
# trajectory cannot turn the check into one that passes without exercising it).
set -u
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/lost_tumble; rm -rf "$T"; mkdir -p "$T"
cat > "$T/fall.dat" <<'EOS'
block create brick size 1.2 1.2 0.4 position 0 0 -0.2 fixed name padA
block create brick size 0.4 0.4 0.4 position 3 0 -0.2 fixed name padB
block create brick size 0.8 0.8 0.5 seat-on padA name stocky
block create brick size 0.4 0.4 1.6 seat-on padB name slender
ground-motion pulse one-sine amplitude 1.5g frequency 1 direction 0
model overturn tilt-ratio 1.0
model solve time 4
output hdf5 'fall.h5' interval 0.01
EOS
out=$("$BIN" run "$T/fall.dat" -o "$T/fall.h5" 2>&1); rc=$?
[ "$rc" -eq 0 ] || { echo "FAIL lost-tumble: exit $rc"; printf '%s\n' "$out" | tail -5; exit 1; }
out=$("$BIN" run tests/data/yade/stack.dat --set motion.amplitude=1.0g --set motion.direction=30 \
      --set model.duration=4 -o "$T/stack.h5" 2>&1); rc=$?
[ "$rc" -eq 0 ] || { echo "FAIL lost-tumble (stack): exit $rc"; printf '%s\n' "$out" | tail -5; exit 1; }
/usr/bin/python3 - "$T/fall.h5" "$T/stack.h5" <<'PY' || exit 1
import sys, h5py

def run(path, body):
    """The run's summary attributes, its body names, and body's overturn, recover and lost
    events as (time, kind)."""
    f = h5py.File(path, "r")
    ev = f["events"]
    kinds = {v: k for k, v in h5py.check_enum_dtype(ev["type"].dtype).items()}
    mine = [(float(t), kinds[int(y)]) for t, b, y in zip(ev["time"][:], ev["body"][:], ev["type"][:])
            if b.decode() == body and kinds[int(y)] in ("overturn", "recover", "lost")]
    a = f["summary"].attrs
    print("%s: status %d; overturned %s; %s's events: %s" % (path.rsplit("/", 1)[-1], a["status"],
          list(a["overturned"]), body, [(round(t, 3), k) for t, k in mine]))
    return a, [n.decode() for n in f["body"][:]], mine

a, names, slender = run(sys.argv[1], "slender")
lost = [t for t, k in slender if k == "lost"]
ok = (a["status"] == 0 and a["overturned"][names.index("slender")] == 1 and
      a["overturned"][names.index("stocky")] == 0 and len(lost) == 1 and
      not any(k == "recover" and t > lost[0] for t, k in slender))
if not ok:
    print("FAIL lost-tumble: the fallen block lost its verdict"); sys.exit(1)

a, names, upper = run(sys.argv[2], "upper")
lost = [t for t, k in upper if k == "lost"]
if len(lost) != 1 or not any(k == "recover" and t < lost[0] for t, k in upper):
    print("FAIL lost-tumble (stack): the case no longer passes upright before it leaves the scene; "
          "pick another that does"); sys.exit(1)
ok = (a["status"] == 0 and a["overturned"][names.index("upper")] == 1 and
      a["overturned"][names.index("lower")] == 0)
if not ok:
    print("FAIL lost-tumble (stack): the fallen block lost its verdict"); sys.exit(1)
PY
