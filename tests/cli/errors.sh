#!/usr/bin/env bash
# Every bad input gets one clear line naming the file (and line:col for scenario text) and a
# non-zero exit; never a crash or a silent default.
set -u
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}
fails=0
expect() { # expect NAME EXPECTED-SUBSTRING -- command...
    local name=$1 want=$2; shift 3
    local out rc
    out=$("$@" 2>&1 >/dev/null); rc=$?
    if [ "$rc" -eq 0 ] || [ "$rc" -gt 3 ] || ! printf '%s' "$out" | grep -qF -- "$want" || [ "$(printf '%s\n' "$out" | wc -l)" -ne 1 ]; then
        echo "FAIL $name: rc=$rc, stderr: $out (wanted: $want)"; fails=$((fails + 1))
    fi
}
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
[ "$fails" -eq 0 ]
