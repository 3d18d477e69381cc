#!/usr/bin/env bash
# rockdem sweep: a brick under one-sine pulses at 3 scales x 2 directions (-j 2); its overturned
# column matches independent `rockdem run`s with the same --set values; -j 1 gives the same
# outcome columns; the table has what rdfragility reads; bad axes give one clear line.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/sweep; mkdir -p "$T"
S=tests/cli/data/sweep_brick.dat
"$BIN" sweep "$S" --scales 1.0g,2.0g,3.0g --directions 0,45 -j 2 -q -o "$T/sw2.h5"
"$BIN" sweep "$S" --scales 1.0g,2.0g,3.0g --directions 0,45 -j 1 -q -o "$T/sw1.h5"
i=0; : > "$T/single.txt"
for a in 1.0g 2.0g 3.0g; do
    for d in 0 45; do
        out=$("$BIN" run "$S" --set motion.amplitude=$a --set motion.direction=$d -q -o "$T/one.h5")
        case "$out" in *OVERTURNED*) echo 1 ;; *) echo 0 ;; esac >> "$T/single.txt"
        i=$((i + 1))
    done
done
/usr/bin/python3 - "$T/sw2.h5" "$T/sw1.h5" "$T/single.txt" <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
single = [int(x) for x in open(sys.argv[3]).read().split()]
s = a["sweep"]
assert list(s["case"][()]) == list(range(6)), s["case"][()]
assert list(s["overturned"][()]) == single, (list(s["overturned"][()]), single)
assert 0 < sum(single) < 6, single            # the levels straddle the threshold
assert np.allclose(s["scale"][()], np.repeat([1, 2, 3], 2) * 9.80665)
assert list(s["direction"][()]) == [0, 45] * 3
assert np.allclose(s["pga"][()], s["scale"][()])  # a pulse's PGA is its amplitude
assert np.allclose(s["pgv_pga"][()], 1 / (2 * np.pi), rtol=1e-6)  # one-sine: v peaks at 2a/w
for k in s:
    if k != "wall_seconds":
        assert np.array_equal(s[k][()], b["sweep"][k][()]), k
ax = a.attrs["axes"]
assert (ax.decode() if isinstance(ax, bytes) else ax) == "scale=1.0g,2.0g,3.0g\ndirection=0,45\n", ax
assert "rockdem" in str(a.attrs["program"])
PY
# the fragility tool reads the table; one pulse frequency = one PGV/PGA, so the 2-D surface
# cannot be fitted and it says so (no coefficients with nan standard errors)
/usr/bin/python3 tools/rdfragility.py "$T/sw2.h5" --json "$T/frag.json" -o "$T/frag.png" > "$T/frag.txt"
grep -q "surface: not fitted: 2-D surface: PGV/PGA is the same (.*) in every run" "$T/frag.txt"
if grep -q "nan" "$T/frag.txt"; then echo "unexpected: nan $T/frag.txt"; exit 1; fi
# a finished table: re-running runs nothing
"$BIN" sweep "$S" --scales 1.0g,2.0g,3.0g --directions 0,45 -j 2 -o "$T/sw2.h5" 2>/dev/null | grep -q "0 run now, 6 already"
# changed axes: refused
rc=0; "$BIN" sweep "$S" --scales 1.0g,2.0g --directions 0,45 -o "$T/sw2.h5" 2> "$T/err" || rc=$?
[ "$rc" -eq 2 ] && grep -q "holds a sweep with other axes" "$T/err"
# in one line, naming what the table holds (was: the stored axes on lines of their own)
{ [ "$(wc -l < "$T/err")" -eq 1 ] && grep -qF "(it has: " "$T/err"; } || { echo "changed axes: $(cat "$T/err")"; exit 1; }
# another scenario text: refused in one line, without the stored text
{ cat "$S"; echo "model title 'changed'"; } > "$T/changed.dat"
rc=0; "$BIN" sweep "$T/changed.dat" --scales 1.0g,2.0g,3.0g --directions 0,45 -o "$T/sw2.h5" 2> "$T/err" || rc=$?
{ [ "$rc" -eq 2 ] && [ "$(wc -l < "$T/err")" -eq 1 ] && grep -q "holds a sweep of another scenario text" "$T/err"; } ||
    { echo "changed scenario: rc $rc, $(cat "$T/err")"; exit 1; }
# bad axis syntax and values: one line each, exit 2
check() { rc=0; "$BIN" sweep "$S" "$@" -o "$T/bad.h5" 2> "$T/err" || rc=$?; [ "$rc" -eq 2 ] && [ "$(wc -l < "$T/err")" -eq 1 ]; }
check --axis contact.stiffness-normal && grep -q "expected KEY=V1,V2" "$T/err"
check --axis contact.stiffness-normal=1e9,,2e9 && grep -q "empty value 2" "$T/err"
check --axis contact.stiffness-normal=1e9,abc && grep -q "axis contact.stiffness-normal=abc" "$T/err"
check --axis contact.nosuch=1,2 && grep -q "unknown key" "$T/err"
check --scales 0.3g,2 && grep -q "not both" "$T/err"
check --axis interface=0 && grep -q "expected interface=K" "$T/err"
check --directions 0,north && grep -q "direction in degrees" "$T/err"
check --scales 0.5g -j 0 && grep -q "\-j expects" "$T/err"
[ ! -e "$T/bad.h5" ]
check --axis interface=3 && grep -q "no 'contact interface-perturbation'" "$T/err"
check --set contact.model=surface --set contact.restitution=1 --set contact.interface-remove=0.5 --axis interface=3 &&
    grep -q "contact model surface has no subcontact points to perturb" "$T/err"
# an interface sweep: 3 seeds of a perturbed bed
"$BIN" sweep "$S" --set contact.spacing=0.1 --set contact.interface-remove=0.5 --set contact.interface-scatter=0.3 \
    --scales 1.0g --axis interface=3 -j 2 -q -o "$T/iface.h5"
/usr/bin/python3 -c "
import sys, h5py
s = h5py.File(sys.argv[1], 'r')['sweep']
assert list(s['interface'][()]) == [1, 2, 3]
assert len(set(s['max_tilt_ratio'][()])) == 3   # three different interfaces" "$T/iface.h5"
