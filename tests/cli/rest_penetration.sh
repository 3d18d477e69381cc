#!/usr/bin/env bash
# Interpenetration at rest deeper than ten contact bands (1 % of the smaller radius, where the
# lever arms of the verdicts are off by 1 %) is an error, not a result (issue 47): a 1 kg cube
# under a 1e6 kg cube on a floor at KN 5e8 Pa/m settles 19.6 mm into the floor (m g / (KN A) =
# 9.81e6 N / (5e8 Pa/m x 1 m^2)), 2.3 % of the 0.866 m radius: the run stops as penetrated (exit
# 3, one line naming the pair, the depth and how much stiffer the joint must be). Before, it ran
# to the end, exit 0. The same stack at KN 1e11 (0.098 mm) runs done.
# `check` does not settle: it estimates each joint's static sink, W / (KN A) with W the weight
# of the body and every free body above it, A its support area, and warns (check --strict exits
# 1) past the contact band (0.1 % of the smaller radius, 0.866 mm), naming the pair and the
# figures. Before, check said nothing. At KN 1e10 the estimate, 0.981 mm for both joints, is what
# the run settles to (to 1e-3 of it: settling stops at an unbalanced force of 1e-6 of the weight).
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/rest_penetration; rm -rf "$T"; mkdir -p "$T"
scene() {
    cat <<DAT
block create brick size 2 2 0.2 position 0 0 -0.1 fixed name floor
block create brick size 1 1 1 position 0 0 0.5 mass 1 name light
block create brick size 1 1 1 position 0 0 1.5 mass 1e6 name heavy
contact property stiffness-normal $1 stiffness-shear $1 friction 35 spacing vertices
ground-motion pulse one-sine amplitude 0.1g frequency 2 direction 0
model solve time 0.2
DAT
}
scene 5e8 > "$T/soft.dat"
rc=0; "$BIN" run "$T/soft.dat" -q -o "$T/soft.h5" > /dev/null 2> "$T/soft.err" || rc=$?
[ "$rc" -eq 3 ] && [ "$(wc -l < "$T/soft.err")" -eq 1 ] &&
    grep -q "at rest, blocks 'floor' and 'light' interpenetrate by 19.[0-9] mm, more than 8.66 mm (1 % of the smaller radius)" "$T/soft.err" ||
    { echo "FAIL the soft stack: exit $rc"; cat "$T/soft.err"; exit 1; }
echo "CHECK a stack 19.6 mm into its floor at rest stops as penetrated, naming the pair"
scene 1e11 > "$T/stiff.dat"
"$BIN" run "$T/stiff.dat" -q -o "$T/stiff.h5" > /dev/null
echo "CHECK the same stack at KN 1e11 (0.098 mm) runs"

# check: the static sink past the contact band is a warning naming the pair and the figures
rc=0; "$BIN" check "$T/soft.dat" -q > "$T/soft.chk" 2>&1 || rc=$?
for pair in "'light' on 'floor'" "'heavy' on 'light'"; do
    [ "$rc" -eq 0 ] && grep -q "^warning: block $pair sinks about 19.6 mm at rest, W / (KN A) = 9.81e+06 N (.*) / (5e+08 Pa/m x 1 m^2), more than the contact band 0.866 mm" "$T/soft.chk" ||
        { echo "FAIL check of the soft stack: exit $rc, no sink warning for $pair"; cat "$T/soft.chk"; exit 1; }
done
echo "CHECK check warns that both joints of the soft stack sink 19.6 mm, past the 0.866 mm band"
rc=0; "$BIN" check "$T/soft.dat" -q --strict > /dev/null 2>&1 || rc=$?
[ "$rc" -eq 1 ] || { echo "FAIL check --strict of the soft stack: exit $rc"; exit 1; }
echo "CHECK check --strict exits 1 on it"
! "$BIN" check "$T/stiff.dat" -q | grep -q "sinks about" || { echo "FAIL check warns of the stiff stack's 0.098 mm"; exit 1; }
echo "CHECK no sink warning for the stiff stack (0.098 mm)"
scene 1e10 > "$T/mid.dat"
"$BIN" check "$T/mid.dat" -q > "$T/mid.chk"
"$BIN" run "$T/mid.dat" -q -o "$T/mid.h5" > /dev/null
est=$(sed -n "s/^warning: block 'light' on 'floor' sinks about \([0-9.e+-]*\) mm.*/\1/p" "$T/mid.chk")
[ -n "$est" ] || { echo "FAIL check of the KN 1e10 stack: no sink warning"; cat "$T/mid.chk"; exit 1; }
/usr/bin/python3 - "$T/mid.h5" "$est" <<'PY'
import sys, h5py
p = h5py.File(sys.argv[1], "r")["position"][0]     # settled, before the pulse
floor, upper = 0.5 - p[0, 2], (1.5 - p[1, 2]) - (0.5 - p[0, 2])
est = float(sys.argv[2]) * 1e-3
w = 9.81e6 / (1e10 * 1.0)                            # W / (KN A), m
bad = [x for x in (floor, upper) if abs(x - w) > 1e-3 * w] + ([est] if abs(est - w) > 1e-3 * w else [])
print("%s the KN 1e10 stack settles %.6g and %.6g mm; check estimates %.3g mm; W / (KN A) %.6g mm: gap=%.3g tol=%.3g"
      % ("FAIL" if bad else "CHECK", 1e3 * floor, 1e3 * upper, 1e3 * est, 1e3 * w,
         max(abs(floor - w), abs(upper - w)), 1e-3 * w))
sys.exit(1 if bad else 0)
PY
