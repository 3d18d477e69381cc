#!/usr/bin/env bash
# Units explicit and checked (issue 40): an AT2 header's units are read (cm/s^2 is not g) and
# velocity files refused; a CSV record, a mesh and a friction say their units; `check` and the
# run header echo every dimensional input with its units, and each likely unit mistake of the
# issue is warned with the likely intent; `check --strict` fails on a warning; options go
# anywhere on the command line (`rockdem run -q FILE`). Each check fails on a003247 (the
# mistakes passed silently, or `-q FILE` was refused).
set -u
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}
fails=0
ok() { echo "CHECK $1"; }
bad() { echo "FAIL $1"; fails=$((fails + 1)); }
# has NAME PATTERN FILE: FILE holds a line matching the fixed string PATTERN
has() { if grep -qF -- "$2" "$3"; then ok "$1"; else bad "$1: no '$2' in: $(cat "$3")"; fi; }
hasnt() { if grep -qF -- "$2" "$3"; then bad "$1: '$2' in: $(grep -F -- "$2" "$3")"; else ok "$1"; fi; }

base() { # a brick on a pad, with extra scenario lines from stdin; 0.5 s (the records' length)
    { printf 'block create brick size 2 2 0.5 position 0 0 -0.25 fixed name pad\n'
      printf 'block create brick size 0.5 0.5 1.0 seat-on pad name b\n'
      printf "model solve time 0.5\noutput hdf5 '%s/o.h5' interval 0.01\n" "$T"; cat; } > "$1"
}
# pga FILE: the motion line's PGA (g) of a check's output
pga() { sed -n 's/^motion h1: [^;]*; PGA \([0-9.e+-]*\) g.*/\1/p' "$1"; }
# ratio NAME A B WANT: PGA A / PGA B is WANT to 1e-5 (the same samples, read in other units:
# the processing is linear, so only the unit factor stays; 1e-5: two PGAs printed to 6 digits)
ratio() {
    if awk -v a="$2" -v b="$3" -v w="$4" 'BEGIN { exit !(a != "" && b > 0 && (a / b / w - 1) ^ 2 < 1e-10) }'; then
        ok "$1 (PGA $2 g / $3 g = $4)"
    else bad "$1: PGA $2 g / $3 g is not $4"; fi
}
# sine PEAK [time]: 51 samples (dt 0.01 s) of one 2 Hz cycle of peak PEAK; with time, two columns
sine() { awk -v a="$1" -v t="${2:-}" 'BEGIN { for (i = 0; i <= 50; i++) { v = a * sin(2 * 3.14159265358979 * 2 * 0.01 * i)
    if (t != "") printf "%.2f %.8g\n", 0.01 * i, v; else printf "%.8g\n", v } }'; }

# --- AT2 header units -------------------------------------------------------------------------
at2() { # file, header line 3, peak: a 2 Hz sine in the file's units
    printf 'PEER NGA STRONG MOTION DATABASE RECORD\nevent, station\n%s\nNPTS=   51, DT=   .0100 SEC\n' "$2" > "$1"
    sine "$3" >> "$1"
}
at2 "$T/g.AT2" "ACCELERATION TIME SERIES IN UNITS OF G" 0.1
at2 "$T/cm.AT2" "ACCELERATION TIME SERIES IN UNITS OF CM/SEC/SEC" 98.0665
at2 "$T/ms2.AT2" "ACCELERATION TIME SERIES IN UNITS OF M/SEC/SEC" 0.980665
at2 "$T/vel.AT2" "VELOCITY TIME SERIES IN UNITS OF CM/SEC" 1
at2 "$T/fur.AT2" "ACCELERATION TIME SERIES IN UNITS OF FURLONGS" 1
for f in g cm ms2 vel fur; do base "$T/$f.dat" <<DAT
ground-motion import '$f.AT2' direction 0
DAT
done
for f in g cm ms2; do "$BIN" check "$T/$f.dat" > "$T/$f.txt" 2>&1; done
# 98.0665 cm/s^2 and 0.980665 m/s^2 are 0.1 g (read as g, the cm/s^2 file was 980 times stronger)
ratio at2-cm/s2-read "$(pga "$T/cm.txt")" "$(pga "$T/g.txt")" 1
ratio at2-m/s2-read "$(pga "$T/ms2.txt")" "$(pga "$T/g.txt")" 1
rc=0; "$BIN" check "$T/vel.dat" > "$T/out.txt" 2>&1 || rc=$?
has at2-velocity-refused "vel.AT2:3: a PEER VELOCITY file" "$T/out.txt"
[ "$rc" -eq 2 ] && ok at2-velocity-exit-2 || bad "at2-velocity-exit-2: rc=$rc"
rc=0; "$BIN" check "$T/fur.dat" > "$T/out.txt" 2>&1 || rc=$?
has at2-unknown-units "unknown units 'FURLONGS' in the header" "$T/out.txt"
at2 "$T/dis.AT2" "DISPLACEMENT TIME SERIES IN UNITS OF CM" 1
base "$T/dis.dat" <<'DAT'
ground-motion import 'dis.AT2' direction 0
DAT
rc=0; "$BIN" check "$T/dis.dat" > "$T/out.txt" 2>&1 || rc=$?
has at2-displacement-refused "dis.AT2:3: a PEER DISPLACEMENT file" "$T/out.txt"
base "$T/atu.dat" <<'DAT'
ground-motion import 'g.AT2' direction 0 units cm/s2
DAT
rc=0; "$BIN" check "$T/atu.dat" > "$T/out.txt" 2>&1 || rc=$?
has at2-units-keyword-refused "'units' applies only to text/CSV records (an AT2 header states its units" "$T/out.txt"

# --- CSV records: undeclared units are g, and a PGA above 5 g warns with the fix -------------
sine 99.2 time > "$T/cm.csv"
base "$T/csv.dat" <<'DAT'
ground-motion import 'cm.csv' direction 0
DAT
base "$T/csv_cm.dat" <<'DAT'
ground-motion import 'cm.csv' direction 0 units cm/s2
DAT
"$BIN" check "$T/csv_cm.dat" > "$T/cm.txt" 2>&1
"$BIN" check "$T/csv.dat" > "$T/out.txt" 2>&1
ratio csv-undeclared-is-g "$(pga "$T/out.txt")" "$(pga "$T/cm.txt")" 980.665
has csv-pga-warning "is above 5 g, beyond any earthquake: its values were read as g" "$T/out.txt"
has csv-units-hint "needs 'units cm/s2' or 'units m/s2'" "$T/out.txt"
has csv-units-echo "values in g (no 'units' declared: g is the default)" "$T/out.txt"
"$BIN" check "$T/csv_cm.dat" > "$T/out.txt" 2>&1
hasnt csv-cm-no-warning "warning:" "$T/out.txt"
has csv-cm-echo "values in cm/s^2 (declared); applied PGA" "$T/out.txt"

# --- friction, gravity, amplitude --------------------------------------------------------------
base "$T/slips.dat" <<'DAT'
contact property friction 0.6
model gravity 1
ground-motion pulse one-sine amplitude 0.3 frequency 2 direction 0
DAT
rc=0; "$BIN" check "$T/slips.dat" > "$T/out.txt" 2>&1 || rc=$?
has friction-deg-warning "friction 0.6 deg (mu 0.0105) is nearly frictionless: did you mean friction-coefficient 0.6 (= 31 deg)?" "$T/out.txt"
has gravity-warning "gravity 1 m/s^2 (0.102 g) is not the Earth's 9.807 m/s^2" "$T/out.txt"
has amplitude-warning "horizontal pulse amplitude 0.3 m/s^2 = 0.0306 g (a number without a g suffix is m/s^2): did you mean 0.3g" "$T/out.txt"
has amplitude-echo "amplitude 0.3 m/s^2 = 0.03059 g (written in m/s^2)" "$T/out.txt"
has friction-echo "friction 0.6 deg (mu 0.01047)" "$T/out.txt"
[ "$rc" -eq 0 ] && ok check-warns-exit-0 || bad "check-warns-exit-0: rc=$rc"
rc=0; "$BIN" check --strict "$T/slips.dat" > /dev/null 2>&1 || rc=$?
[ "$rc" -eq 1 ] && ok check-strict-exit-1 || bad "check-strict-exit-1: rc=$rc"
base "$T/mu.dat" <<'DAT'
contact property friction-coefficient 0.6
ground-motion pulse one-sine amplitude 0.3g frequency 2 direction 0
DAT
rc=0; "$BIN" check --strict "$T/mu.dat" > "$T/out.txt" 2>&1 || rc=$?
[ "$rc" -eq 0 ] && ok mu-strict-clean || bad "mu-strict-clean: rc=$rc: $(grep warning "$T/out.txt")"
has mu-echo "friction 30.96 deg (mu 0.6)" "$T/out.txt"
has g-amplitude-echo "amplitude 2.942 m/s^2 = 0.3 g (written in g)" "$T/out.txt"
"$BIN" check --set contact.friction-coefficient=1 "$T/mu.dat" > "$T/out.txt" 2>&1
has mu-override "friction 45 deg (mu 1)" "$T/out.txt"
base "$T/both.dat" <<'DAT'
contact property friction 30 friction-coefficient 0.6
DAT
rc=0; "$BIN" check "$T/both.dat" > "$T/out.txt" 2>&1 || rc=$?
has friction-twice "'friction' of 'contact property' already given" "$T/out.txt"
base "$T/both_range.dat" <<'DAT'
contact property friction 30 friction-coefficient 0.6 range block 'b'
DAT
rc=0; "$BIN" check "$T/both_range.dat" > "$T/out.txt" 2>&1 || rc=$?
has friction-twice-range "give the friction once: 'friction' (degrees) or 'friction-coefficient' (mu)" "$T/out.txt"

# --- meshes: millimetres and y-up ----------------------------------------------------------------
M=scenarios/pbr.obj
if [ -f "$M" ]; then
    awk '/^v /{printf "v %.17g %.17g %.17g\n", 1000*$2, 1000*$3, 1000*$4; next} {print}' "$M" > "$T/mm.obj"
    awk '/^v /{printf "v %.17g %.17g %.17g\n", $2, $4, -$3; next} {print}' "$M" > "$T/yup.obj"
    cp "$M" "$T/m.obj"
    k=0
    for v in "m.obj'" "mm.obj'" "mm.obj' units mm" "yup.obj'" "yup.obj' up y"; do
        k=$((k + 1))
        sed "s|'pbr.obj'|'$v|; s|output hdf5 'pbr.h5'|output hdf5 '$T/o.h5'|" scenarios/pbr.dat > "$T/mesh$k.dat"
        "$BIN" check "$T/mesh$k.dat" > "$T/mesh$k.txt" 2>&1
    done
    seated="rock         free  mass 354 kg, volume 0.1287 m^3, tipping angle 12.8 deg"
    has mesh-m "$seated" "$T/mesh1.txt"
    has mesh-mm-warning "mesh in mm? its coordinates are read as m: add 'units mm'" "$T/mesh2.txt"
    has mesh-mm-mass "mass 3.54e+11 kg" "$T/mesh2.txt"
    has mesh-units-mm "$seated" "$T/mesh3.txt"
    has mesh-yup-warning "a mesh drawn y-up is read z-up: add 'up y'" "$T/mesh4.txt"
    has mesh-up-y "$seated" "$T/mesh5.txt"
    hasnt mesh-up-y-clean "warning:" "$T/mesh5.txt"
    for bad_kw in "units ft" "up x"; do
        sed "s|'pbr.obj'|'m.obj' $bad_kw|; s|output hdf5 'pbr.h5'|output hdf5 '$T/o.h5'|" scenarios/pbr.dat > "$T/badmesh.dat"
        rc=0; "$BIN" check "$T/badmesh.dat" > "$T/out.txt" 2>&1 || rc=$?
        [ "$rc" -eq 2 ] && [ "$(wc -l < "$T/out.txt")" -eq 1 ] && ok "mesh-$bad_kw-refused: $(cat "$T/out.txt")" ||
            bad "mesh-$bad_kw-refused: rc=$rc: $(cat "$T/out.txt")"
    done
    has mesh-up-x-message "unknown up axis 'x' (expected y or z)" "$T/out.txt"
else
    bad "mesh cases: $M missing (make scenarios/pbr.obj)"
fi

# --- options anywhere; the run header echoes the inputs --------------------------------------------
base "$T/run.dat" <<'DAT'
ground-motion pulse one-sine amplitude 0.1g frequency 2 direction 0
DAT
rc=0; "$BIN" run -q "$T/run.dat" > "$T/out.txt" 2>&1 || rc=$?
[ "$rc" -eq 0 ] && has run-q-first "b: " "$T/out.txt" || bad "run-q-first: rc=$rc: $(cat "$T/out.txt")"
rc=0; "$BIN" run --set model.duration=0.1 -o "$T/x.h5" "$T/run.dat" > "$T/out.txt" 2>&1 || rc=$?
[ "$rc" -eq 0 ] && [ -f "$T/x.h5" ] && ok run-options-before-file || bad "run-options-before-file: rc=$rc $(cat "$T/out.txt")"
has run-header-inputs "inputs: horizontal pulse one-sine: amplitude 0.9807 m/s^2 = 0.1 g (written in g)" "$T/out.txt"
has run-header-body "inputs: block b: 0.5 x 0.5 x 1 m (x, y, z), mass 675 kg" "$T/out.txt"
rc=0; "$BIN" run -q -q "$T/run.dat" > "$T/out.txt" 2>&1 || rc=$?
has repeated-option-refused "option '-q' given twice" "$T/out.txt"
rc=0; "$BIN" run -q > "$T/out.txt" 2>&1 || rc=$?
has missing-file "rockdem run: missing FILE" "$T/out.txt"
[ "$rc" -eq 2 ] && ok missing-file-exit-2 || bad "missing-file-exit-2: rc=$rc"
"$BIN" check --set motion.amplitude=0.3 "$T/run.dat" > "$T/out.txt" 2>&1
has amplitude-override-warning "amplitude 0.3 m/s^2 = 0.0306 g (a number without a g suffix is m/s^2)" "$T/out.txt"
rc=0; "$BIN" check --strict "$T/run.dat" > /dev/null 2>&1 || rc=$?
[ "$rc" -eq 0 ] && ok check-strict-first || bad "check-strict-first: rc=$rc"

[ "$fails" -eq 0 ]
