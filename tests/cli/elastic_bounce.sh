#!/usr/bin/env bash
# Issue 10, item 3: an elastic joint (restitution 1) gives an impact back whole, wherever the
# touch falls between two steps.
# A 0.4 x 0.4 x 0.8 m block (345.6 kg) dropped flat from 5 mm onto a fixed base, corner
# subcontacts, KN 1e10 Pa/m, no damping: its four corners (0.16 m^2 together) make a vertical
# spring of 1.6e9 N/m, omega = 2152 rad/s, so omega dt = 0.108 at dt 5e-5 s and 0.161 at 7.5e-5 s.
# A rigid bounce on a linear elastic spring returns the block to its drop height (energy
# conservation: at the apex the springs are open and the block is at rest).
# Leapfrog gives the bodies F(n) dt over [t(n) - dt/2, t(n) + dt/2]. With the spring force at
# t(n) alone, a spring that switches on or off inside that interval gave an impulse off by up to
# (omega dt)^2 / 4 of the impact's energy, with a sign set by where the touch fell in the step
# (a point mass, touches spread over the step: +-0.24 % at omega dt 0.1, +-0.9 % at 0.2); the
# apexes of this block then wandered by 0.2-0.6 % at 5e-5 s. With the spring's mean force over
# that interval (engine/law.h rd_law_switch_stretch) the same point mass keeps its energy to 1e-5
# (omega dt 0.1) and 1e-4 (0.2) a bounce.
# Check: each of the first 6 apexes within 1e-3 of the drop height (6 bounces at 1e-4 each, the
# point mass's bound at omega dt 0.2, give 6e-4), at both steps.
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}
T=${RD_TMP:-$(mktemp -d)}/elastic_bounce; rm -rf "$T"; mkdir -p "$T"
cat > "$T/drop.dat" <<'DAT'
block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.4 0.8 position 0 0 0.405 density 2700 name blk
contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40 restitution 1 spacing vertices
model settle off
ground-motion pulse one-sine amplitude 0g frequency 2 direction 0
model solve time 0.4
output hdf5 'drop.h5' interval 0.0002
DAT
fails=0
for dt in 5e-5 7.5e-5; do
    "$BIN" run "$T/drop.dat" --set model.timestep=$dt -q -o "$T/drop_$dt.h5" > "$T/drop_$dt.log" 2>&1 ||
        { echo "FAIL elastic-bounce: run at dt $dt failed"; cat "$T/drop_$dt.log"; exit 1; }
    out=$(/usr/bin/python3 - "$T/drop_$dt.h5" <<'PY'
import sys, h5py, numpy as np
z = h5py.File(sys.argv[1], "r")["position"][:, 0, 2] - 0.4   # m above the resting contact
drop = 0.005
apex = [z[i] for i in range(1, len(z) - 1) if z[i] > z[i - 1] and z[i] >= z[i + 1] and z[i] > drop / 2][:6]
err = max(abs(a - drop) / drop for a in apex) if len(apex) == 6 else float("inf")
print("%.3g %d %s" % (err, len(apex), " ".join("%.5f" % (1e3 * a) for a in apex)))
PY
)
    read -r err n apexes <<< "$out"
    echo "dt $dt: $n apexes (mm) $apexes, largest relative error $err"
    verdict "elastic-bounce/apex-dt$dt (largest |apex - drop| / drop over 6 bounces)" \
        "$(awk -v e="$err" 'BEGIN { print (e <= 1e-3) ? 1 : 0 }')" "$err" 1e-3 strict || fails=$((fails + 1))
done
[ "$fails" -eq 0 ]
