#!/usr/bin/env bash
# Issue 10, item 5: `rockdem reference` takes every scene the Housner or Kounadis model can
# describe (one brick on a fixed base; a two-brick stack, however it was built) and refuses any
# other with one line naming the file, the line and why, and a non-zero exit: three free bodies.
# Before, a mesh rock passed the scene checks as a brick of size 0 and the Housner solver
# stopped with "need b, h, g > 0 (got 0 0 9.81 -1)". Issue 40: one free body that is no brick (a
# mesh rock, a drum, a hull) gets Housner's equation with its own alpha, R and pivot inertia,
# said to be APPROXIMATE; a hull that is a box gives exactly the brick's answer.
set -u
BIN=$(cd "$(dirname "${RD_BIN:-bin/rockdem}")" && pwd)/rockdem
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
T=${RD_TMP:-$(mktemp -d)}/reference_scenes; rm -rf "$T"; mkdir -p "$T"
fails=0
base="block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base"
tail="ground-motion pulse one-sine amplitude 0.5g frequency 2 direction 0
model solve time 0.5
output hdf5 'r.h5' interval 0.01"
refuse() { # refuse NAME FILE EXPECTED-SUBSTRING
    local out rc
    out=$(cd "$T" && "$BIN" reference "$2" -o "$T/r.h5" 2>&1 >/dev/null); rc=$?
    if [ "$rc" -eq 0 ] || [ "$rc" -gt 3 ] || ! printf '%s' "$out" | grep -qF -- "$3" || [ "$(printf '%s\n' "$out" | wc -l)" -ne 1 ]; then
        echo "FAIL reference-scenes/$1: rc=$rc, stderr: $out (wanted one line with: $3)"; fails=$((fails + 1))
    fi
}
accept() { # accept NAME FILE
    local out
    out=$(cd "$T" && "$BIN" reference "$2" -o "$T/$1.h5" 2>&1) || { echo "FAIL reference-scenes/$1: refused: $out"; fails=$((fails + 1)); }
}
approximate() { # approximate NAME FILE: accepted, and said to be approximate
    local out
    out=$(cd "$T" && "$BIN" reference "$2" -o "$T/$1.h5" 2>&1) || { echo "FAIL reference-scenes/$1: refused: $out"; fails=$((fails + 1)); return; }
    printf '%s\n' "$out" > "$T/$1.txt"
    grep -q "^reference: APPROXIMATE: body .* is no brick; Housner's one-block equation with its own alpha" "$T/$1.txt" ||
        { echo "FAIL reference-scenes/$1: not said to be approximate: $out"; fails=$((fails + 1)); }
}
if [ -f "$ROOT/scenarios/pbr.obj" ]; then approximate pbr-mesh "$ROOT/scenarios/pbr.dat"
else echo "FAIL reference-scenes/pbr-mesh: scenarios/pbr.obj missing (make scenarios/pbr.obj)"; fails=$((fails + 1)); fi
printf '%s\nblock create column drums 1 diameter 0.8 height 1.6 sides 16 seat-on base name c\n%s\n' "$base" "$tail" > "$T/drum.dat"
approximate drum "$T/drum.dat"
printf '%s\nblock create polyhedron vertices 0 0 0  0.4 0 0  0.4 0.4 0  0 0.4 0  0 0 1.2  0.4 0 1.2  0.4 0.4 1.2  0 0.4 1.2 position 0 0 0.6 name h\n%s\n' "$base" "$tail" > "$T/hull.dat"
approximate hull "$T/hull.dat"
# the hull is the 0.4 x 0.4 x 1.2 m box: its own alpha, R and pivot inertia are the brick's, so
# the equivalent block is the brick (b 0.2, h 0.6 m) and the rocking the same to the digits printed
printf '%s\nblock create brick size 0.4 0.4 1.2 position 0.2 0.2 0.6 name h\n%s\n' "$base" "$tail" > "$T/box.dat"
out=$(cd "$T" && "$BIN" reference "$T/box.dat" -o "$T/box.h5" 2>&1)
if [ "$(grep '^h:' "$T/hull.txt" 2>/dev/null)" = "$(printf '%s\n' "$out" | grep '^h:')" ] && grep -q "b = 0.2 m, h = 0.6 m" "$T/hull.txt"; then :
else echo "FAIL reference-scenes/hull-is-brick: hull $(grep '^h:' "$T/hull.txt"), brick $(printf '%s\n' "$out" | grep '^h:')"; fails=$((fails + 1)); fi
printf '%s\nblock create column drums 3 diameter 0.8 height 0.6 sides 4 seat-on base name c\n%s\n' "$base" "$tail" > "$T/three.dat"
refuse three-bodies "$T/three.dat" "reference: this scene has 1 fixed and 3 free bodies"
printf '%s\nblock create brick size 0.4 0.4 1.2 seat-on base name lower\nblock create brick size 0.3 0.3 0.9 seat-on lower name upper\n%s\n' "$base" "$tail" > "$T/seat.dat"
accept seat-on "$T/seat.dat"
printf '%s\nblock create brick size 0.4 0.4 1.2 position 0 0 0.6 name lower\nblock create brick size 0.3 0.3 0.9 position 0 0 1.65 name upper\n%s\n' "$base" "$tail" > "$T/bricks.dat"
accept brick-lines "$T/bricks.dat"
accept statue-stack "$ROOT/scenarios/statue.dat"
[ "$fails" -eq 0 ]
