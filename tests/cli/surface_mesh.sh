#!/usr/bin/env bash
# Mesh against mesh in the surface contact model (issue 39, items 2-4; docs/CONTACT.md section
# 8.5): an L-shaped prism rocking and sliding on an L-shaped fixed prism, and on a free one, under
# a 1.2 g 2 Hz one-sine. Each run must end done (no body passed into another), move (the block
# rocks: max tilt above 1e-3 rad), and keep its energy residual below the issue's 1e-3. The
# vertex model cannot pair two meshes (before, the block fell through: status lost, and `check`
# said ok): `check` and `run` refuse a pair within reach at the start, and a run stops with one
# line when two meshes come within reach later (the toppling column), naming both blocks.
set -u
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/surface_mesh; rm -rf "$T"; mkdir -p "$T"
D=$(cd "$(dirname "$0")/../data/mesh" && pwd)
fails=0
for f in L_on_L L_on_L_free; do
    cp "$D/$f.dat" "$D/L_base.obj" "$D/L_block.obj" "$T/"
    rc=0; "$BIN" run "$T/$f.dat" -o "$T/$f.h5" > "$T/$f.txt" 2>&1 || rc=$?
    st=$(sed -n 's/^run: status \([a-z]*\),.*/\1/p' "$T/$f.txt")
    res=$(sed -n 's/^run: .*energy residual \([0-9.e+-]*\).*/\1/p' "$T/$f.txt")
    tilt=$(sed -n 's/^block: .*max tilt \([0-9.e+-]*\) rad.*/\1/p' "$T/$f.txt")
    if [ "$rc" -eq 0 ] && [ "$st" = done ]; then echo "CHECK $f-done"
    else echo "FAIL $f-done: rc=$rc status '$st': $(grep -m1 -E 'passed|left|refus|error' "$T/$f.txt")"; fails=$((fails + 1)); fi
    if awk -v t="${tilt:-0}" 'BEGIN { exit !(t > 1e-3) }'; then echo "CHECK $f-rocks (max tilt $tilt rad)"
    else echo "FAIL $f-rocks: max tilt '$tilt' rad (want > 1e-3)"; fails=$((fails + 1)); fi
    # two free meshes rocking and sliding at 1.2 g: 1.13e-3 (an expected failure) until the
    # springs' resize was booked at mid-step (docs/CONTACT.md section 8.10), 1.6e-4 since
    if awk -v r="${res:-1}" 'BEGIN { exit !(r < 1e-3) }'; then echo "CHECK $f-energy (residual $res, tol 1e-3)"
    else echo "FAIL $f-energy: residual '$res' (tol 1e-3)"; fails=$((fails + 1)); fi
done
# a toppling L column strikes its free neighbour (both meshes): the run ends done, the neighbour
# is struck (its tilt above 1e-3 rad), and the energy residual is the known gap (section 8.5)
cp "$D/topple.dat" "$D/L_column.obj" "$T/"
rc=0; "$BIN" run "$T/topple.dat" -o "$T/topple.h5" > "$T/topple.txt" 2>&1 || rc=$?
st=$(sed -n 's/^run: status \([a-z]*\),.*/\1/p' "$T/topple.txt")
res=$(sed -n 's/^run: .*energy residual \([0-9.e+-]*\).*/\1/p' "$T/topple.txt")
tb=$(sed -n 's/^b: .*max tilt \([0-9.e+-]*\) rad.*/\1/p' "$T/topple.txt")
if [ "$rc" -eq 0 ] && [ "$st" = done ]; then echo "CHECK topple-done"
else echo "FAIL topple-done: rc=$rc status '$st': $(grep -m1 -E 'passed|left|refus|error' "$T/topple.txt")"; fails=$((fails + 1)); fi
if awk -v t="${tb:-0}" 'BEGIN { exit !(t > 1e-3) }'; then echo "CHECK topple-strikes-neighbour (its max tilt $tb rad)"
else echo "FAIL topple-strikes-neighbour: max tilt '$tb' rad"; fails=$((fails + 1)); fi
if awk -v r="${res:-1}" 'BEGIN { exit !(r < 1e-3) }'; then echo "CHECK topple-energy (residual $res, tol 1e-3)"
else echo "XFAIL: energy residual of a toppling mesh column striking a mesh gap=$res tol=1e-3"; fi
# the vertex model: one line naming the pair, exit 2 from check, 3 from run
vertex=(--set contact.model=vertex --set contact.restitution=0)
want="blocks 'base' and 'block' are within reach of each other at t = 0 s, and the vertex contact model cannot touch them"
rc=0; "$BIN" check "$T/L_on_L.dat" "${vertex[@]}" > /dev/null 2> "$T/v_check.err" || rc=$?
if [ "$rc" -eq 2 ] && [ "$(wc -l < "$T/v_check.err")" -eq 1 ] && grep -qF "$T/L_on_L.dat: $want" "$T/v_check.err"; then
    echo "CHECK vertex-check-refuses"
else echo "FAIL vertex-check-refuses: rc=$rc: $(cat "$T/v_check.err")"; fails=$((fails + 1)); fi
rc=0; "$BIN" run "$T/L_on_L.dat" "${vertex[@]}" -o "$T/v.h5" > /dev/null 2> "$T/v_run.err" || rc=$?
if [ "$rc" -eq 3 ] && [ "$(wc -l < "$T/v_run.err")" -eq 1 ] && grep -qF "$want" "$T/v_run.err"; then
    echo "CHECK vertex-run-refuses"
else echo "FAIL vertex-run-refuses: rc=$rc: $(cat "$T/v_run.err")"; fails=$((fails + 1)); fi
rc=0; "$BIN" run "$T/topple.dat" "${vertex[@]}" -o "$T/vt.h5" > "$T/vt.txt" 2> "$T/vt.err" || rc=$?
if [ "$rc" -eq 3 ] && grep -q "^run: status error" "$T/vt.txt" &&
    grep -qE "blocks 'a' and 'b' are within reach of each other at t = 0\.[0-9]+ s" "$T/vt.err"; then
    echo "CHECK vertex-topple-stops ($(grep -o 't = [0-9.]* s' "$T/vt.err" | head -n1))"
else echo "FAIL vertex-topple-stops: rc=$rc: $(cat "$T/vt.err")"; fails=$((fails + 1)); fi
[ "$fails" -eq 0 ]
