#!/usr/bin/env bash
# Scene-control commands (issue 15) refuse bad input with one line naming file, line and
# problem: joint ranges, histories, checkpoints and what the surface model cannot model.
set -u
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}
fails=0
expect() { # expect NAME EXPECTED-SUBSTRING SCENARIO-LINE
    printf "block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base group 'rock'\nblock create brick size 0.4 0.4 1.6 seat-on base name b\nmodel solve time 0.01\n%s\n" "$3" > "$T/e.dat"
    local out rc
    out=$("$BIN" run "$T/e.dat" -o "$T/e.h5" 2>&1 >/dev/null); rc=$?
    if [ "$rc" -eq 0 ] || [ "$rc" -gt 3 ] || ! printf '%s' "$out" | grep -qF -- "$2" || [ "$(printf '%s\n' "$out" | wc -l)" -ne 1 ]; then
        echo "FAIL $1: rc=$rc, stderr: $out (wanted: $2)"; fails=$((fails + 1))
    fi
}
expect range-empty "e.dat:4:30: expected group NAME or block NAME after 'range'" "contact property friction 10 range"
expect range-kind "e.dat:4:36: expected group or block after 'range', got 'name'" "contact property friction 10 range name 'b'"
expect range-noprop "e.dat:4:9: a contact property range sets no property" "contact property range group 'rock'"
expect range-spacing "e.dat:4:18: 'spacing' belongs to the bodies" "contact property spacing 0.1 range group 'rock'"
expect range-unknown "e.dat:4: contact property range: no block is in group 'pad'" "contact property friction 10 range group 'pad'"
expect history-block "e.dat:4: history: no block named 'nosuch'" "history body 'nosuch' position"
expect history-what "e.dat:4:18: unknown quantity 'speed'" "history body 'b' speed"
expect history-joint "e.dat:4:19: a joint needs two different blocks" "history joint 'b' 'b' slip"
expect restore-missing "model restore: cannot open '$T/none.h5'" "model restore '$T/none.h5'"
expect save-and-restore "'model save' and 'model restore' in one scenario" "model save 'a.h5'
model restore 'a.h5'"
expect surface-restitution "e.dat:4: contact model surface: restitution 0 is not modelled" "contact model surface"
expect surface-cohesion "e.dat:4: contact model surface: cohesion and tension are not modelled" "contact model surface
contact property restitution 1 cohesion 1e5"
expect surface-range-restitution "$T/e.dat:6: contact model surface ($T/e.dat:5): restitution 0.3 is not modelled" "contact property restitution 1
contact model surface
contact property restitution 0.3 range group 'rock'"
expect surface-perturbation "$T/e.dat:6: contact model surface ($T/e.dat:5): contact interface-perturbation is not modelled" "contact property restitution 1
contact model surface
contact interface-perturbation seed 2 remove 0.3"
# the same perturbation from --set: the file, no line
printf "block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base\nblock create brick size 0.4 0.4 1.6 seat-on base name b\nmodel solve time 0.01\n" > "$T/p.dat"
out=$("$BIN" run "$T/p.dat" -o "$T/p.h5" --set contact.model=surface --set contact.restitution=1 \
    --set contact.interface-seed=2 --set contact.interface-scatter=0.3 2>&1 >/dev/null)
case $out in
"$T/p.dat (--set contact.interface-*): contact model surface ($T/p.dat (--set contact.model=surface)): contact interface-perturbation is not modelled"*) ;;
*) echo "FAIL surface-perturbation-set: $out"; fails=$((fails + 1)) ;;
esac
[ "$fails" -eq 0 ]
