#!/usr/bin/env bash
# A body placed pressed into its support, with settle off, is at rest, not landing: the
# contacts that the run finds pressed as placed are seated, as settling seats its own
# (engine/sim.c restore_or_settle). A 0.3 m granite cube on a level pad, placed at its static
# compression d = m g / (KN A) = 7.95e-7 m, default joint (restitution < 1: a new contact's
# first unloading takes the impact loss), 0.02 s with no ground motion: its height must stay
# within 1 % of d of where it was placed (the bed's points carry the weight to round-off).
# Before, the first round-off unloading turned the whole compression into a permanent set and
# the cube fell to oscillate about 2 d (a drop of 100 % of d, energy residual 1.7e-5).
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/placed_pressed; rm -rf "$T"; mkdir -p "$T"
read -r d z0 < <(/usr/bin/python3 -c "
m, A = 2700 * 0.3 ** 3, 0.3 * 0.3
d = m * 9.81 / (1e10 * A)
print('%.17g %.17g' % (d, 0.25 - d))")
cat > "$T/cube.dat" <<EOF
model gravity 9.81
block create brick size 2 2 0.2 position 0 0 0 fixed name pad
block create brick size 0.3 0.3 0.3 position 0 0 $z0 density 2700 name b
contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 30 spacing auto
model settle off
model solve time 0.02
output hdf5 'x.h5' interval 0.0002
EOF
"$BIN" run "$T/cube.dat" -o "$T/cube.h5" > "$T/out" 2>&1 || { echo "FAIL placed-pressed: run failed"; tail -3 "$T/out"; exit 1; }
read -r gap tol ok < <(/usr/bin/python3 -c "
import h5py, numpy as np
z = h5py.File('$T/cube.h5', 'r')['position'][()][:, 0, 2]
gap = np.max(np.abs(z - $z0))
print('%.4g %.4g %d' % (gap, 0.01 * $d, gap <= 0.01 * $d))")
echo "placed-pressed: largest height change $gap m (static compression $d m)"
verdict "placed-pressed/height (m)" "$ok" "$gap" "$tol" strict || exit 1
check_residual "placed-pressed" "$(energy_residual "$T/cube.h5")" || exit 1
