#!/usr/bin/env bash
# Two-block stacks, DEM (contact preset rigid, undamped) against the CVODE Kounadis reference:
# time histories (largest tilts; stack uplift, upper separation, first ground impact times) and
# one-sine overturning thresholds at three frequencies, for three stacks: unequal widths
# (0.5x1.0 under 0.4x0.8), equal widths h/b = 2 (0.5x1.0 twice) and equal slender h/b = 4
# (0.4x1.6 twice). Then the high-friction stack's slide of the upper block on the lower one.
# Usage: bash bench/stack_validation.sh [bin/rockdem]   (about 17 minutes on one core)
set -eu
BIN=$(realpath "${1:-bin/rockdem}")
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
stack() { # name lower(w h) upper(w h)
  cat > "$T/$1.dat" <<DAT
block create brick size 4 4 1 position 0 0 -0.5 fixed name base
block create brick size $2 $2 $3 position 0 0 $(echo "$3 / 2" | bc -l) name lower
block create brick size $4 $4 $5 position 0 0 $(echo "$3 + $5 / 2" | bc -l) name upper
contact preset rigid
ground-motion pulse one-sine amplitude 1g frequency 2
model solve time 4
output hdf5 'x.h5' interval 0.002
DAT
}
stack unequal 0.5 1.0 0.4 0.8
stack equal2 0.5 1.0 0.5 1.0
stack equal4 0.4 1.6 0.4 1.6
for s in unequal equal2 equal4; do
  echo "## $s: history at 2 Hz, 1.5 x the static uplift acceleration"
  a=$(/usr/bin/python3 - "$T/$s.dat" <<'PY'
import sys
# static uplift of the stack (Kounadis, docs/ROCKING-EQUATIONS.md): min(stack, upper), times g
w = {}
for line in open(sys.argv[1]):
    t = line.split()
    if t[:3] == ["block", "create", "brick"] and "fixed" not in t:
        w[t[-1]] = (float(t[4]) / 2, float(t[6]) / 2)
(b1, h1), (b2, h2) = w["lower"], w["upper"]
m1, m2 = b1 * b1 * h1, b2 * b2 * h2
st = b1 * (m1 + m2) / (m1 * h1 + m2 * (2 * h1 + h2))
print(1.5 * 9.81 * min(st, b2 / h2))
PY
)
  (cd "$T" && "$BIN" reference $s.dat --set motion.amplitude=$a -o ref.h5 > /dev/null 2>&1 || true)
  # the preset's KN 1e11, then 1e12 (KS = 10 KN): the elastic joint's event-time errors (the lag
  # or lead of its rocking mode, up to 1/omega, omega ~ sqrt KN) must shrink as KN grows
  for kn in 1e11 1e12; do
    echo "# KN $kn"
    (cd "$T" && "$BIN" run $s.dat --set motion.amplitude=$a --set contact.stiffness-normal=$kn \
       --set contact.stiffness-shear=${kn/e/0e} -o dem.h5 -q > /dev/null 2>&1 || true)
    /usr/bin/python3 tools/stack_compare.py "$T/dem.h5" "$T/ref.h5"
  done
  echo "## $s: thresholds (a / a_uplift), reference then DEM"
  for f in 1 1.5 2.5; do
    r=$("$BIN" threshold "$T/$s.dat" --engine reference --set motion.frequency=$f 2>&1 | tail -1)
    d=$("$BIN" threshold "$T/$s.dat" --engine dem --set motion.frequency=$f 2>&1 | tail -1)
    echo "$f Hz  reference: $r"
    echo "$f Hz  DEM:       $d"
  done
done
echo "## high-friction stack (equal widths h/b = 4, friction 80 deg, 0.3 g at 2 Hz, 5 s): slide of the upper block on the lower one"
(cd "$T" && "$BIN" run equal4.dat --set motion.amplitude=0.3g --set model.duration=5 -o mu.h5 -q > /dev/null 2>&1 || true)
/usr/bin/python3 tools/relative_slide.py "$T/mu.h5"
