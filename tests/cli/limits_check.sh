#!/usr/bin/env bash
# Limits on every number and a `check` that validates what `run` would (issue 17):
#   - a number outside its keyword's valid range (docs/LIMITS.md) is refused by check and run
#     alike, with file:line:col, and by --set overrides with the key;
#   - a run whose estimated step count exceeds the budget (1e9) is refused with the estimate
#     unless forced (`model solve ... force on` or --force);
#   - check reads meshes (missing, malformed with the line), records (printing their IMs),
#     builds the perturbed subcontact points and checks the output folder; it writes nothing.
set -u
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/limits; mkdir -p "$T"
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
# same CMD... : check and run both fail (exit 2) with the same one line containing WANT
same() {
    local want=$1; shift
    local oc orun rc1 rc2
    oc=$("$BIN" check "$@" 2>&1 >/dev/null); rc1=$?
    orun=$("$BIN" run "$@" -q -o "$T/never.h5" 2>&1 >/dev/null); rc2=$?
    [ "$rc1" -eq 2 ] && [ "$rc2" -eq 2 ] || fail "$want: exit check $rc1, run $rc2"
    [ "$oc" = "$orun" ] || fail "check and run differ: '$oc' / '$orun'"
    printf '%s' "$oc" | grep -qF -- "$want" || fail "wanted '$want', got '$oc'"
    [ "$(printf '%s\n' "$oc" | wc -l)" -eq 1 ] || fail "more than one line: $oc"
    [ ! -e "$T/never.h5" ] || fail "$want: an output file was written"
}
base() { cat <<'DAT'
block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.4 1.6 position 0 0 0.8 density 2500 name b
contact property stiffness-normal 1e9 stiffness-shear 1e8 friction 35
ground-motion pulse one-sine amplitude 0.2g frequency 2 direction 0
model solve time 0.05
DAT
}
base > "$T/ok.dat"
"$BIN" check "$T/ok.dat" > "$T/ok.out" || fail "a good scenario does not pass check"
grep -q "ok (2 bodies, [0-9]* subcontact points" "$T/ok.out" || fail "check summary: $(cat "$T/ok.out")"

# keyword limits: parse (file:line:col) and override (the key)
base | sed 's/stiffness-normal 1e9/stiffness-normal 1e30/' > "$T/kn.dat"
same "kn.dat:3:35: 'stiffness-normal' 1e30 is outside its valid range [10000, 1e+15] Pa/m" "$T/kn.dat"
base | sed 's/stiffness-normal 1e9/stiffness-normal 1e-3/' > "$T/kn2.dat"
same "kn2.dat:3:35: 'stiffness-normal' 1e-3 is outside its valid range" "$T/kn2.dat"
base | sed 's/frequency 2/frequency 2 start 1e300/' > "$T/start.dat"
same "start.dat:4:63: 'start' 1e300 is outside its valid range [0, 10000] s" "$T/start.dat"
base | sed 's/size 0.4 0.4 1.6/size 0.4 0.4 1e300/' > "$T/size.dat"
same "size.dat:2:33: 'size' 1e300 is outside its valid range" "$T/size.dat"
same "--set contact.stiffness-normal=1e30: 1e30 is outside its valid range" "$T/ok.dat" --set contact.stiffness-normal=1e30
same "--set motion.start=1e300: 1e300 is outside its valid range [0, 10000] s" "$T/ok.dat" --set motion.start=1e300
{ base; echo "contact interface-perturbation seed 1e300"; } > "$T/seed.dat"
same "seed.dat:6:37: 'seed' 1e300 is outside its valid range [0, 4.29497e+09]" "$T/seed.dat"

# the step budget: KN 1e15 Pa/m gives dt ~ 1e-7 s; 1e5 s of it is ~1e12 steps
base | sed 's/stiffness-normal 1e9/stiffness-normal 1e15/; s/model solve time 0.05/model solve time 1e5/' > "$T/steps.dat"
same "steps.dat:5: the run would take about " "$T/steps.dat"
"$BIN" check "$T/steps.dat" 2>&1 | grep -q "more than the budget of 1e+09" || fail "budget message"
"$BIN" check "$T/steps.dat" --force > /dev/null || fail "--force does not lift the budget"
sed 's/model solve time 1e5/model solve time 1e5 force on/' "$T/steps.dat" > "$T/forced.dat"
"$BIN" check "$T/forced.dat" > /dev/null || fail "'model solve ... force on' does not lift the budget"
# the budget counts the shaking the run takes: without a tail a run stops at its duration, so a
# motion that ends later does not count (0.05 s at KN 1e15 under a pulse starting at 1e4 s:
# (5 s of settling + 0.05 s) / ~1e-7 s = ~5e7 steps; the motion's end made it ~1e11, refused);
# with a tail (model.tail) the run goes on to the motion's end, and is refused
base | sed 's/stiffness-normal 1e9/stiffness-normal 1e15/; s/direction 0/direction 0 start 1e4/' > "$T/late.dat"
out=$("$BIN" check "$T/late.dat" 2>&1); rc=$?
{ [ "$rc" -ne 2 ] && ! printf '%s' "$out" | grep -q "budget"; } ||
    fail "a motion ending after a run without a tail counted in its step budget (exit $rc): $(printf '%s' "$out" | tail -1)"
same "late.dat:5: the run would take about " "$T/late.dat" --set model.tail=1

# meshes: missing, malformed (with the line), good
{ base | sed '2d'; echo "block import mesh 'rock.obj' seat-on base density 2500 name rock"; } > "$T/mesh.dat"
same "mesh.dat:5: block 'rock': $T/rock.obj: cannot open: No such file or directory" "$T/mesh.dat"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n' > "$T/rock.obj"
printf 'f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\n' >> "$T/rock.obj"   # a cube without its +x side
same "mesh.dat:5: block 'rock': $T/rock.obj:9: open mesh: edge (2, 4) belongs to 1 face" "$T/mesh.dat"
printf 'f 2 4 8 6\n' >> "$T/rock.obj"
"$BIN" check "$T/mesh.dat" > /dev/null || fail "a closed cube does not pass check"

# records: read and their intensity measures printed
{ printf 'PEER\nevent\nunits\nNPTS=   40, DT=   .0100 SEC\n'; for i in $(seq 10); do echo "0.1 -0.2 0.1 0.0"; done; } > "$T/r.AT2"
{ base | sed '4d'; echo "ground-motion import 'r.AT2' scale 1"; } > "$T/rec.dat"
"$BIN" check "$T/rec.dat" > "$T/rec.out" || fail "record scenario: $(cat "$T/rec.out")"
grep -q "^motion h1: r.AT2; PGA [0-9.]* g, PGV .*Arias" "$T/rec.out" || fail "check does not print the record's IMs: $(cat "$T/rec.out")"
sed -i 's/DT=   .0100/DT=   1e300/' "$T/r.AT2"
same "r.AT2:4: DT must be in [1e-06, 1] s, found 1e+300 s" "$T/rec.dat"

# the output folder
out=$("$BIN" check "$T/ok.dat" -o /nonexistent/rd/x.h5 2>&1 >/dev/null); rc=$?
[ "$rc" -eq 2 ] || fail "unwritable output: check exit $rc"
printf '%s' "$out" | grep -qF "/nonexistent/rd/x.h5: cannot create the output file in /nonexistent/rd: No such file or directory" ||
    fail "unwritable output: $out"
[ "$fails" -eq 0 ]
