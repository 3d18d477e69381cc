#!/usr/bin/env bash
# Every bad input gets one clear line naming the file (and line:col for scenario text) and a
# non-zero exit; never a crash or a silent default.
set -u
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}
fails=0
# expect_status RC NAME EXPECTED-SUBSTRING -- command...: one stderr line holding the substring
# and exit status RC ("any": 1 to 3)
expect_status() {
    local want_rc=$1 name=$2 want=$3; shift 4
    local out rc
    out=$("$@" 2>&1 >/dev/null); rc=$?
    if { [ "$want_rc" = any ] && { [ "$rc" -eq 0 ] || [ "$rc" -gt 3 ]; }; } ||
       { [ "$want_rc" != any ] && [ "$rc" -ne "$want_rc" ]; } ||
       ! printf '%s' "$out" | grep -qF -- "$want" || [ "$(printf '%s\n' "$out" | wc -l)" -ne 1 ]; then
        echo "FAIL $name: rc=$rc, stderr: $out (wanted: $want, exit ${want_rc})"; fails=$((fails + 1))
    fi
}
expect() { expect_status any "$@"; }   # expect NAME EXPECTED-SUBSTRING -- command...
expect2() { expect_status 2 "$@"; }    # the same, exit 2: bad input or option, refused before any run
good="$T/good.dat"
cat > "$good" <<'DAT'
block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.4 1.6 position 0 0 0.8 name b
model solve time 0.01
DAT
printf 'block create brick size 1 1 1 position 0 0 0.5\ncontact property frction 30\n' > "$T/kw.dat"
printf 'block create brick size 1 1 position 0 0 0.5\n' > "$T/num.dat"
printf "model title 'open\n" > "$T/str.dat"
printf 'block create brick size 2 2 0.5 position 0 0 -0.25 fixed\nmodel solve time 1\n' > "$T/nofree.dat"
cp "$good" "$T/dt.dat"; echo 'model timestep fixed 1e-2' >> "$T/dt.dat"
cp "$good" "$T/pulse.dat"; echo 'ground-motion pulse one-sine amplitude 0.2g frequency 2 direction 0' >> "$T/pulse.dat"

# bodies placed into each other (engine/overlap.c): a block sunk 0.1 m into its pedestal, and
# two blocks side by side 0.1 m into each other, where no vertex of either lies inside the
# other (each was run and flung apart: the first 130 m up, ending `done`)
sed 's/position 0 0 0.8 name b/position 0 0 0.7 name b/' "$good" > "$T/sunk.dat"
{ cat "$good"; echo 'block create brick size 0.4 0.4 1.6 position 0.3 0 0.8 name c'; } > "$T/side.dat"

expect missing-file "$T/nope.dat: cannot open" -- "$BIN" run "$T/nope.dat"
expect overlap-sunk "sunk.dat: blocks 'base' and 'b' overlap by 0.1 m as placed" -- "$BIN" run "$T/sunk.dat" -o "$T/x.h5"
expect overlap-side "side.dat: blocks 'b' and 'c' overlap by 0.1 m as placed" -- "$BIN" run "$T/side.dat" -o "$T/x.h5"
expect unknown-keyword "kw.dat:2:18: unknown keyword 'frction'" -- "$BIN" run "$T/kw.dat"
expect bad-number "num.dat:1:" -- "$BIN" run "$T/num.dat"
expect unterminated-string "str.dat:1:" -- "$BIN" run "$T/str.dat"
expect no-free-block "no free block" -- "$BIN" run "$T/nofree.dat"
expect unstable-step "above the stable limit" -- "$BIN" run "$T/dt.dat" -o "$T/x.h5"
expect bad-override "--set contact.stiffnes-normal=1" -- "$BIN" run "$good" --set contact.stiffnes-normal=1
expect bad-override-value "--set contact.friction=abc" -- "$BIN" run "$good" --set contact.friction=abc
expect unwritable-output "/nonexistent-dir/x.h5" -- "$BIN" run "$good" -o /nonexistent-dir/x.h5
expect unknown-option "unknown option '--bogus'" -- "$BIN" run "$good" --bogus
# strtod also reads hexadecimal: 0x10 was taken as 16 Hz, 0x1p1 as 2
sed 's/model solve time 0.01/model solve time 0x1p1/' "$good" > "$T/hex.dat"
expect hex-number "hex.dat:3:18: expected a number" -- "$BIN" run "$T/hex.dat" -o "$T/x.h5"
expect hex-override "--set model.duration=0x1" -- "$BIN" run "$good" --set model.duration=0x1 -o "$T/x.h5"
# a single-valued setting given twice: the last one won silently (KN 2e10 here); now the
# repeat is refused with the line of the first (tests/test_scenario.c test_error_repeated_setting)
{ cat "$good"; printf 'contact property stiffness-normal 1e10 friction 30\ncontact property stiffness-normal 2e10\n'; } > "$T/twice.dat"
expect2 repeated-setting "twice.dat:5:18: 'stiffness-normal' of 'contact property' already given on line 4; give each setting once" -- "$BIN" check "$T/twice.dat"
{ cat "$good"; echo 'model solve time 2'; } > "$T/twice_solve.dat"
expect2 repeated-solve-time "twice_solve.dat:4:13: 'time' of 'model solve' already given on line 3" -- "$BIN" run "$T/twice_solve.dat" -o "$T/x.h5"
# an option or an override key given twice: the last one won silently (a run of 2 s here, a
# sweep over the second --axis list only); now refused with both places
expect2 repeated-set "rockdem run: --set 'model.duration' given twice (arguments 3 and 5); give each key once" -- "$BIN" run "$good" --set model.duration=1 --set=model.duration=2 -o "$T/x.h5"
expect2 repeated-output "rockdem run: option '-o' given twice (arguments 3 and 5); give each option once" -- "$BIN" run "$good" -o "$T/x.h5" -o "$T/y.h5"
expect2 repeated-axis "rockdem sweep: --axis 'contact.friction' given twice (arguments 3 and 5); give each key once" -- "$BIN" sweep "$good" --axis contact.friction=30,40 --axis=contact.friction=20 -q -o "$T/sw.h5"
# a scenario that never ends (a device) grew its buffer until memory ran out; a pipe still reads
expect2 scenario-device "/dev/zero: more than 64 MiB: not a scenario text" -- timeout 20 "$BIN" check /dev/zero
# study runs KN x 0.1 to x 10: a yardstick beyond KN's range ran for minutes at dt < 1e-9 s
expect2 study-kn-above "the study runs KN x 0.1 to x 10 (5e+13 to 5e+15 Pa/m), outside stiffness-normal's range" -- timeout 60 "$BIN" study "$good" --set contact.stiffness-normal=5e14
# an initial state past the runaway speed (1000 m/s: RD_RUNAWAY_V2), within each number's own
# range: b (0.4 x 0.4 x 1.6 m, radius sqrt(0.2^2 + 0.2^2 + 0.8^2) = 0.849 m) spun at 2000 rad/s
# moves its corners at 1697 m/s; it stopped at step 1 as "unstable ... contact forces blew up"
{ cat "$good"; echo 'block initial name b angular-velocity 0 0 2000'; } > "$T/spin.dat"
expect runaway-start "spin.dat:4: block 'b' starts at 1.7e+03 m/s" -- "$BIN" run "$T/spin.dat" -o "$T/x.h5"
expect runaway-start-check "spin.dat:4: block 'b' starts at 1.7e+03 m/s" -- "$BIN" check "$T/spin.dat" -o "$T/x.h5"
# option values out of range are refused, never replaced by a default (timeout: a run that
# goes ahead instead fails here rather than hanging the suite)
TH="timeout 60 $BIN threshold $T/pulse.dat --engine reference"
expect2 threshold-lo-negative "--lo expects an amplitude above 0 (m/s^2, or with a g suffix), got '-1'" -- $TH --lo -1
expect2 threshold-lo-zero "--lo expects an amplitude above 0" -- $TH --lo 0
expect2 threshold-hi-zero "--hi expects an amplitude above 0" -- $TH --hi 0
expect2 threshold-hi-negative "--hi expects an amplitude above 0 (m/s^2, or with a g suffix), got '-5'" -- $TH --hi -5
expect2 threshold-steps-zero "--steps expects a number of coarse scan steps (1 to 1000), got '0'" -- $TH --steps 0
expect2 threshold-steps-negative "--steps expects a number of coarse scan steps (1 to 1000), got '-3'" -- $TH --steps -3
expect2 threshold-steps-huge "--steps expects a number of coarse scan steps (1 to 1000), got '1e9'" -- $TH --steps 1e9
expect2 threshold-steps-fraction "got '2.5'" -- $TH --steps 2.5
expect2 threshold-frequencies-empty "--frequencies expects positive numbers (Hz) separated by commas, got '1,,2'" -- $TH --frequencies 1,,2
expect2 threshold-frequencies-trailing "got '1,' (an empty item)" -- $TH --frequencies 1,
expect2 threshold-frequencies-zero "--frequencies expects positive frequencies (Hz), got '0'" -- $TH --frequencies 0
RS="timeout 60 $BIN restitution $T/pulse.dat"
expect2 restitution-target-negative "--target expects a restitution above 0, at most 1, got '-1'" -- $RS --target -1
expect2 restitution-target-zero "--target expects a restitution above 0, at most 1, got '0'" -- $RS --target 0
expect2 restitution-target-above-1 "--target expects a restitution above 0, at most 1, got '2'" -- $RS --target 2
expect2 restitution-theta0-zero "--theta0 expects an initial tilt above 0 (rad), got '0'" -- $RS --theta0 0
expect2 restitution-theta0-negative "--theta0 expects an initial tilt above 0 (rad), got '-5'" -- $RS --theta0 -5
expect2 restitution-theta0-past-alpha "--theta0 expects an initial tilt below the block's alpha = 0.244979 rad, got 1" -- $RS --theta0 1
# --rtol out of range exited 3 after the scene was read (0, -1), or bisected for ever (1e-300:
# the bracket reaches round-off before it closes); --lo not below --hi (given or defaulted) and
# a scene without a pulse exited 3; --hi 1e300 failed in CVODE, --frequencies 2,1e9 ran the
# 2 Hz row before it failed (rc 3)
expect2 threshold-repeated-lo "rockdem threshold: option '--lo' given twice (arguments 5 and 7); give each option once" -- $TH --lo 1 --lo 2
expect2 threshold-rtol-zero "--rtol expects a relative bracket from 1e-06 to 1, got '0'" -- $TH --rtol 0
expect2 threshold-rtol-negative "--rtol expects a relative bracket from 1e-06 to 1, got '-1'" -- $TH --rtol -1
expect2 threshold-rtol-tiny "--rtol expects a relative bracket from 1e-06 to 1, got '1e-300'" -- $TH --rtol 1e-300
expect2 threshold-rtol-above-1 "--rtol expects a relative bracket from 1e-06 to 1, got '2'" -- $TH --rtol 2
expect2 threshold-lo-above-hi "pulse.dat: threshold: --lo 2 m/s^2 is not below --hi 1 m/s^2" -- $TH --lo 2 --hi 1
expect2 threshold-lo-above-default "pulse.dat: threshold: --lo 980.66 m/s^2 is not below --hi 24.525 m/s^2 (their defaults" -- $TH --lo 100g
expect2 threshold-hi-huge "--hi expects an amplitude of at most 1e+06 m/s^2 (docs/LIMITS.md), got '1e300'" -- $TH --hi 1e300
expect2 threshold-frequencies-huge "--frequencies expects frequencies from 0.0001 to 1000 Hz (docs/LIMITS.md), got '1e9'" -- $TH --frequencies 2,1e9
expect2 threshold-no-pulse "good.dat: threshold: the scenario has no horizontal pulse to scale" -- timeout 60 "$BIN" threshold "$good" --engine reference
# sweep --keep-runs naming a file was taken, and every case then failed to write there (exit 3,
# a line per case) after running
expect2 sweep-keep-runs-file "rockdem sweep: --keep-runs $T/good.dat: not a folder" -- timeout 60 "$BIN" sweep "$T/pulse.dat" --scales 1 --keep-runs "$T/good.dat" -q -o "$T/keep.h5"
# an option given last without its value is named as needing one, not as unknown
expect set-no-value "--set needs a value (see rockdem run --help)" -- "$BIN" run "$good" --set
expect out-no-value "-o needs a value (see rockdem run --help)" -- "$BIN" run "$good" -o
expect engine-no-value "--engine needs a value (see rockdem threshold --help)" -- "$BIN" threshold "$T/pulse.dat" --engine
expect target-no-value "--target needs a value (see rockdem restitution --help)" -- "$BIN" restitution "$T/pulse.dat" --target

# Subcontact spacing: its range [1e-6, 1e4] m, 0 refused (corners are 'vertices'), and the point
# budget checked before any face is meshed (1e-4 m and 3e-4 m on a 0.4 m base hung for minutes).
base="$T/base.dat"
cat > "$base" <<'DAT'
block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.4 1.6 position 0 0 0.8 name b
ground-motion pulse one-sine amplitude 0.2g frequency 2 direction 0
model solve time 0.05
output hdf5 'base.h5' interval 0.01
DAT
spacing() { cp "$base" "$T/sp.dat"; echo "contact property spacing $1" >> "$T/sp.dat"; }
spacing 1e308; expect spacing-huge "sp.dat:6:26: 'spacing' 1e308 is outside its valid range [1e-06, 10000] m" -- "$BIN" check "$T/sp.dat"
spacing 1e5; expect spacing-1e5 "sp.dat:6:26: 'spacing' 1e5 is outside its valid range" -- "$BIN" check "$T/sp.dat"
spacing 0; expect spacing-zero "sp.dat:6:26: 'spacing' 0 is no edge length" -- "$BIN" check "$T/sp.dat"
spacing 1e-6; expect spacing-1e-6 "sp.dat:2: body 'b' would carry about 1.6e+11 subcontact points at spacing 1e-06 m" -- timeout 20 "$BIN" check "$T/sp.dat"
spacing 1e-4; expect spacing-1e-4-check "sp.dat:2: body 'b' would carry about 1.6e+07 subcontact points at spacing 0.0001 m" -- timeout 20 "$BIN" check "$T/sp.dat"
expect spacing-1e-4-run "sp.dat:2: body 'b' would carry about 1.6e+07" -- timeout 20 "$BIN" run "$T/sp.dat" -o "$T/sp.h5"
spacing 3e-4; expect spacing-3e-4 "more than the budget of 1e+06" -- timeout 20 "$BIN" run "$T/sp.dat" -o "$T/sp.h5"
expect spacing-set-huge "--set contact.spacing=1e308: 1e308 is outside its valid range" -- "$BIN" check "$base" --set contact.spacing=1e308
expect spacing-set-zero "--set contact.spacing=0: 0 is no edge length" -- "$BIN" check "$base" --set contact.spacing=0

# Records: a sample of 1e308 g passed check ("Arias -nan") and failed run as "contact forces blew
# up"; a bad first row was dropped as a header; 1-2 samples ran without the baseline, 3-4 were
# refused without the file's name.
record() { head -2 "$base" > "$T/rec.dat"; echo "ground-motion import '$1' dt 0.01" >> "$T/rec.dat"; echo "model solve time 0.05" >> "$T/rec.dat"; }
printf '0.1\n0.2\n1e308\n0.1\n0.1\n0.1\n' > "$T/huge.txt"; record huge.txt
expect record-huge-check "huge.txt:3: acceleration '1e308' is outside the valid |acceleration| <= 1e+06 m/s^2" -- "$BIN" check "$T/rec.dat"
expect record-huge-run "huge.txt:3: acceleration '1e308' is outside" -- "$BIN" run "$T/rec.dat" -o "$T/rec.h5"
{ echo 'O 0.2'; awk 'BEGIN { for (i = 1; i < 200; i++) printf "%.2f 0.1\n", i * 0.01 }'; } > "$T/row.txt"; record row.txt
sed -i 's/ dt 0.01//' "$T/rec.dat"
expect record-bad-first-row "row.txt:1: non-numeric value 'O'" -- "$BIN" check "$T/rec.dat"
for n in 1 2 3; do
    seq 1 $n | sed 's/.*/0.1/' > "$T/short$n.txt"; record "short$n.txt"
    expect "record-$n-samples" "short$n.txt: $n sample" -- "$BIN" check "$T/rec.dat"
    expect "record-$n-samples-baseline" "too few for the degree-4 baseline (at least 5, or 'baseline off')" -- "$BIN" run "$T/rec.dat" -o "$T/rec.h5"
done
# an output path that is a device, folder or pipe is refused before HDF5 opens it (was: a crash
# at exit on /dev/null, a dump from HDF5's exit hook on /dev/full)
expect output-dev-null "/dev/null: cannot write the output there: not a regular file" -- "$BIN" run "$good" -q -o /dev/null
expect output-dev-full "/dev/full: cannot write the output there: not a regular file" -- "$BIN" run "$good" -q -o /dev/full
expect output-folder "$T: cannot write the output there: not a regular file" -- "$BIN" run "$good" -q -o "$T"
expect check-dev-null "/dev/null: cannot write the output there" -- "$BIN" check "$good" -q -o /dev/null
{ cat "$good"; echo "model save '/dev/null'"; } > "$T/save_dev.dat"
expect save-dev-null "save_dev.dat: model save '/dev/null': not a regular file" -- "$BIN" run "$T/save_dev.dat" -q -o "$T/x.h5"
# a checkpoint into a missing folder is refused before settling (it failed after it, rc 3)
{ cat "$good"; echo "model save '/nonexistent-dir/ck.h5'"; } > "$T/save_dir.dat"
expect save-missing-folder "save_dir.dat: model save '/nonexistent-dir/ck.h5': cannot create the file in /nonexistent-dir" -- "$BIN" run "$T/save_dir.dat" -q -o "$T/x.h5"
expect check-save-missing-folder "model save '/nonexistent-dir/ck.h5': cannot create the file" -- "$BIN" check "$T/save_dir.dat" -q
# an output or checkpoint that is a file the run reads is refused, the file left as it was
cp "$good" "$T/self_out.dat"
expect output-is-scenario "it is the scenario file being read" -- "$BIN" run "$T/self_out.dat" -q -o "$T/self_out.dat"
cmp -s "$good" "$T/self_out.dat" || { echo "FAIL output-is-scenario: the scenario was overwritten"; fails=$((fails + 1)); }
{ cat "$good"; echo "model save '$T/self_save.dat'"; } > "$T/self_save.dat"; cp "$T/self_save.dat" "$T/self_save.orig"
expect save-is-scenario "self_save.dat': it is the scenario file being read" -- "$BIN" run "$T/self_save.dat" -q -o "$T/x.h5"
cmp -s "$T/self_save.orig" "$T/self_save.dat" || { echo "FAIL save-is-scenario: the scenario was overwritten"; fails=$((fails + 1)); }
printf '0 0\n0.005 0.1\n0.01 0\n' > "$T/rec.txt"
{ cat "$good"; echo "ground-motion import '$T/rec.txt' baseline off"; } > "$T/rec.dat"
expect output-is-record "it is a ground-motion record the scenario reads" -- "$BIN" run "$T/rec.dat" -q -o "$T/rec.txt"
{ cat "$good"; echo "model save '$T/both.h5'"; } > "$T/both.dat"
expect output-is-checkpoint "it is also the run's checkpoint (model save)" -- "$BIN" run "$T/both.dat" -q -o "$T/both.h5"
# reference checks its output as run does, before the CVODE solve (it was refused only after
# it, exit 3, with the scenario's name in front)
expect2 reference-output-missing-folder "/nonexistent-dir/r.h5: cannot create the output file in /nonexistent-dir" -- "$BIN" reference "$T/pulse.dat" -o /nonexistent-dir/r.h5
expect2 reference-output-folder "$T: cannot write the output there: not a regular file" -- "$BIN" reference "$T/pulse.dat" -o "$T"
expect2 reference-output-dev-null "/dev/null: cannot write the output there: not a regular file" -- "$BIN" reference "$T/pulse.dat" -o /dev/null
cp "$T/pulse.dat" "$T/ref_self.dat"
expect2 reference-output-is-scenario "ref_self.dat: cannot write the output there: it is the scenario file being read" -- "$BIN" reference "$T/ref_self.dat" -o "$T/ref_self.dat"
cmp -s "$T/pulse.dat" "$T/ref_self.dat" || { echo "FAIL reference-output-is-scenario: the scenario was overwritten"; fails=$((fails + 1)); }
# a mesh, record or checkpoint that is a device or a pipe is refused before it is opened: /dev/zero
# was read until memory ran out, a pipe without a writer blocked the open for ever (timeout)
ln -sf /dev/zero "$T/zero.obj"; mkfifo "$T/fifo.obj" "$T/fifo.txt" "$T/fifo.h5"
{ head -1 "$good"; echo "block import mesh 'zero.obj' position 0 0 1 name r"; echo 'model solve time 0.01'; } > "$T/mesh_dev.dat"
expect2 input-mesh-device "mesh_dev.dat:2: block 'r': $T/zero.obj: not a regular file (a device, folder or pipe)" -- timeout 20 "$BIN" check "$T/mesh_dev.dat"
sed 's/zero.obj/fifo.obj/' "$T/mesh_dev.dat" > "$T/mesh_fifo.dat"
expect2 input-mesh-pipe "block 'r': $T/fifo.obj: not a regular file" -- timeout 20 "$BIN" check "$T/mesh_fifo.dat"
{ cat "$good"; echo "ground-motion import '/dev/zero' dt 0.01"; } > "$T/rec_dev.dat"
expect2 input-record-device "rec_dev.dat:4:22: /dev/zero: not a regular file (a device, folder or pipe)" -- timeout 20 "$BIN" check "$T/rec_dev.dat"
{ cat "$good"; echo "ground-motion import 'fifo.txt' dt 0.01"; } > "$T/rec_fifo.dat"
expect2 input-record-pipe "fifo.txt: not a regular file" -- timeout 20 "$BIN" check "$T/rec_fifo.dat"
{ cat "$good"; echo "ground-motion import 'fifo.h5' record 1"; } > "$T/fema_fifo.dat"
expect2 input-fema-pipe "fifo.h5: not a regular file" -- timeout 20 "$BIN" check "$T/fema_fifo.dat"
{ cat "$good"; echo "model restore '$T/fifo.h5'"; } > "$T/restore_fifo.dat"
expect2 input-restore-pipe "restore_fifo.dat: model restore '$T/fifo.h5': not a regular file" -- timeout 20 "$BIN" run "$T/restore_fifo.dat" -q -o "$T/x.h5"
# a run that fails after settling gave up says both in its one error line (was: a settling
# warning line, then the error)
sed 's/position 0 0 0.8 name b/position 100 0 0.8 name b/' "$good" > "$T/falls.dat"
expect settle-then-lost "left the scene while settling at t = " -- "$BIN" run "$T/falls.dat" -q -o "$T/x.h5"
expect settle-then-lost-ratio "(nothing holds it); settling stopped at force ratio" -- "$BIN" run "$T/falls.dat" -q -o "$T/x.h5"
# a mistyped subcommand or help topic: one line naming it (was: the 15-line usage, or for help
# the usage on stdout and nothing on stderr)
expect unknown-subcommand "rockdem: unknown subcommand 'bogus' (rockdem help lists them)" -- "$BIN" bogus "$good"
expect unknown-subcommand-help "unknown subcommand 'bogus'" -- "$BIN" bogus --help
expect unknown-help-topic "rockdem: unknown help topic 'nosuch'" -- "$BIN" help nosuch
expect missing-scenario "rockdem run: missing FILE" -- "$BIN" run
[ "$fails" -eq 0 ]
