#!/usr/bin/env bash
# The time step is bounded per contact pair (src/engine/timestep.c, issue 47): a small block on
# a large one runs within 2x of the small block's own step (alone on a fixed floor), and stays
# stable there.
#   1. 5 cm and 1 cm cubes on a 2 m cube, a 1 mm cube on a 10 m cube (KN = KS = 1e10 Pa/m):
#      step within 2x of the small cube's alone (before: 46x and 230x shorter, and the 1 mm
#      cube refused by the step budget at dt 2e-10 s);
#   2. the 5 cm cube on the 2 m cube shaken 2 s at 0.5 g at a fixed step of 0.95 x the limit
#      (not the 0.2 x of the automatic step): done, the energy residual under RD_ENERGY_TRUST
#      (status untrusted otherwise), no blow-up;
#   3. a scene whose step is past the budget names the pair that sets it.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/timestep_pairs; rm -rf "$T"; mkdir -p "$T"
scene() {   # scene SMALL BIG [extra lines]: a cube of edge SMALL on a cube of edge BIG on a floor
    awk -v s="$1" -v b="$2" 'BEGIN {
        w = b > 0 ? 2 * b : 1
        printf "block create brick size %g %g 0.2 position 0 0 -0.1 fixed name floor\n", w, w
        if (b > 0) printf "block create brick size %g %g %g position 0 0 %g density 2700 name big\n", b, b, b, b / 2
        printf "block create brick size %g %g %g position 0 0 %g density 2700 name small\n", s, s, s, b + s / 2
        print "contact property stiffness-normal 1e10 stiffness-shear 1e10 friction 35 spacing vertices"
        print "ground-motion pulse one-sine amplitude 0.5g frequency 2 direction 0"
        print "model solve time 1" }'
}
step() { "$BIN" check "$1" 2>&1 | sed -n 's/^time step \([0-9.e+-]*\) s.*/\1/p'; }
for c in "0.05 2" "0.01 2" "0.001 10"; do
    set -- $c
    scene "$1" "$2" > "$T/pair.dat"; scene "$1" 0 > "$T/alone.dat"
    on=$(step "$T/pair.dat"); alone=$(step "$T/alone.dat")
    [ -n "$on" ] && [ -n "$alone" ] || { echo "FAIL $1 m cube on a $2 m cube: no step"; "$BIN" check "$T/pair.dat"; exit 1; }
    awk -v a="$on" -v b="$alone" 'BEGIN { exit !(b / a <= 2) }' ||
        { echo "FAIL $1 m cube on a $2 m cube: step $on s, alone $alone s"; exit 1; }
    echo "CHECK $1 m cube on a $2 m cube: step $on s, alone $alone s (within 2x)"
done

# 2. stable at 0.95 x the limit
scene 0.05 2 > "$T/shake.dat"
lim=$("$BIN" check "$T/shake.dat" 2>&1 | sed -n 's/.*(stability limit \([0-9.e+-]*\) s).*/\1/p')
dt=$(awk -v l="$lim" 'BEGIN { printf "%.4g", 0.95 * l }')
printf 'model solve time 2\nmodel timestep fixed %s\n' "$dt" | cat - "$T/shake.dat" | grep -v "model solve time 1" > "$T/fixed.dat"
"$BIN" run "$T/fixed.dat" -q -o "$T/fixed.h5" > "$T/fixed.out" 2>&1 || { echo "FAIL at 0.95 x the limit:"; cat "$T/fixed.out"; exit 1; }
/usr/bin/python3 - "$T/fixed.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
names = {v: k for k, v in h5py.check_enum_dtype(f["summary"].attrs.get_id("status").dtype).items()}
st = names[int(f["summary"].attrs["status"])]
assert st == "done", st
assert np.isfinite(f["position"][()]).all()
print("CHECK 5 cm cube on a 2 m cube at 0.95 x the step limit: status done, energy residual %.2e"
      % np.abs(f["energy/residual"][()]).max())
PY

# 3. past the budget: the pair is named
{ scene 0.001 1; echo "model solve time 100"; } | sed 's/1e10/1e15/g' | grep -v "model solve time 1$" > "$T/budget.dat"
rc=0; "$BIN" check "$T/budget.dat" > "$T/budget.out" 2>&1 || rc=$?
[ "$rc" -eq 2 ] && grep -q "the run would take about .* set by block '\(big\|small\)' bearing on '\(big\|small\)'" "$T/budget.out" ||
    { echo "FAIL the budget message names no pair (exit $rc)"; cat "$T/budget.out"; exit 1; }
echo "CHECK a scene past the step budget names the pair that sets the step"
