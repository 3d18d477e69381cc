#!/usr/bin/env bash
# Checkpoints (issue 15): `model save` after settling and `model restore` in another scenario
# continue bit for bit: the six-drum column (nine bodies: the sort-and-sweep broad phase, many
# joints) is shaken once straight through and once from the restored state, and every output
# sample (positions, orientations, velocities, energies) must be identical, not merely close.
# A checkpoint of another scene is refused with one line naming the difference.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}
SET="--set model.duration=0.25 --set contact.spacing=0.25"
grep -v '^output' scenarios/column.dat > "$T/save.dat"
echo "model save '$T/settled.h5'" >> "$T/save.dat"
grep -v '^output' scenarios/column.dat > "$T/restore.dat"
echo "model restore '$T/settled.h5'" >> "$T/restore.dat"
"$BIN" run "$T/save.dat" $SET -o "$T/straight.h5" -q > "$T/straight.txt"
"$BIN" run "$T/restore.dat" $SET -o "$T/restored.h5" -q > "$T/restored.txt"
cmp "$T/straight.txt" "$T/restored.txt"   # the same verdicts and joint outcomes
/usr/bin/python3 - "$T/straight.h5" "$T/restored.h5" <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
n = 0
for k in ["time", "position", "quaternion", "velocity", "angular_velocity", "rotation",
          "energy/kinetic", "energy/elastic", "energy/friction", "joints/outcomes",
          "joints/properties", "outcomes/bodies"]:
    x, y = a[k][...], b[k][...]
    assert x.shape == y.shape and np.array_equal(x, y), k   # bit-identical, no tolerance
    n += x.size
assert a["time"].shape[0] > 20
print("checkpoint: %d values bit-identical" % n)
PY
# a checkpoint of another scene: one error line, non-zero exit
printf "block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base\nblock create brick size 1 1 2 seat-on base name b\nmodel solve time 0.1\nmodel restore '%s'\n" "$T/settled.h5" > "$T/other.dat"
if "$BIN" run "$T/other.dat" -o "$T/other.h5" -q 2> "$T/err"; then exit 1; fi
grep -q "model restore.*holds 9 blocks, this scenario 2" "$T/err"
# a checkpoint of the same names but other blocks: one line naming the checkpoint, the block
# and what differs, never a run from a state that does not belong to the scene
cat > "$T/b.dat" <<'DAT'
block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.4 1.6 position 0 0 0.8 name b
ground-motion pulse one-sine amplitude 0.2g frequency 2 direction 0
model solve time 0.05
DAT
{ cat "$T/b.dat"; echo "model save '$T/b.h5'"; } > "$T/b_save.dat"
"$BIN" run "$T/b_save.dat" -o "$T/b_saved.h5" -q > /dev/null
refused() { # refused NAME SED-EXPRESSION EXPECTED-SUBSTRING
    { sed "$2" "$T/b.dat"; echo "model restore '$T/b.h5'"; } > "$T/$1.dat"
    if "$BIN" run "$T/$1.dat" -o "$T/$1.h5" -q > /dev/null 2> "$T/err"; then
        echo "checkpoint $1: restored, wanted a refusal"; exit 1
    fi
    [ "$(wc -l < "$T/err")" -eq 1 ] && grep -qF -- "model restore '$T/b.h5': $3" "$T/err" ||
        { echo "checkpoint $1: $(cat "$T/err") (wanted: $3)"; exit 1; }
}
refused smaller 's/size 0.4 0.4 1.6/size 0.1 0.1 0.3/' "block 'b' has another shape (vertex 1 at"
refused taller 's/size 0.4 0.4 1.6/size 0.4 0.4 1.6000001/' "block 'b' has another shape"
refused denser 's/name b$/density 8000 name b/' "block 'b' has another mass (691.2 kg there, 2048 kg here)"
refused lower 's/position 0 0 -0.25/position 0 0 -5.25/' "fixed block 'base' stands elsewhere (centre of mass at (0, 0, -0.25) m there, (0, 0, -5.25) m here)"
refused turned 's/-0.25 fixed/-0.25 rotation 0 0 10 fixed/' "fixed block 'base' is turned otherwise"
refused freed 's/ fixed name base/ name base/' "block 'base' is fixed there, free here"
# check reads and compares the checkpoint as run does (it said ok, exit 0, for a checkpoint of
# other blocks and for one that does not exist)
if "$BIN" check "$T/smaller.dat" -q > /dev/null 2> "$T/err"; then echo "check smaller: ok, wanted a refusal"; exit 1; fi
[ "$(wc -l < "$T/err")" -eq 1 ] && grep -qF "model restore '$T/b.h5': block 'b' has another shape" "$T/err" ||
    { echo "check smaller: $(cat "$T/err")"; exit 1; }
{ cat "$T/b.dat"; echo "model restore '$T/nonexistent.h5'"; } > "$T/b_none.dat"
if "$BIN" check "$T/b_none.dat" -q > /dev/null 2> "$T/err"; then echo "check b_none: ok, wanted a refusal"; exit 1; fi
grep -qF "model restore: cannot open '$T/nonexistent.h5' as a checkpoint" "$T/err" || { echo "check b_none: $(cat "$T/err")"; exit 1; }
{ cat "$T/b.dat"; echo "model restore '$T/b.h5'"; } > "$T/b_same.dat"
"$BIN" run "$T/b_same.dat" -o "$T/b_same.h5" -q > /dev/null   # the same blocks restore
