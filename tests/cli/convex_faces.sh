#!/usr/bin/env bash
# A convex body may have any number of faces (docs/LIMITS.md, "Convex bodies"): the vertex
# contact's plane masks and per-side arrays are sized by the body with the most faces
# (src/engine/contact.c, edge.c). Before, a convex body of more than 130 faces was refused.
# 1. `check` takes a 500-face drum (498 sides and its two caps) and the 500-triangle hull of 252
#    points on a sphere.
# 2. The same slender drum (radius 0.2 m, height 1.6 m, alpha 0.245 rad), seated on a fixed base
#    and rocked by a 2 Hz one-sine pulse of 0.4 g (about 1.6 times its uplift threshold), as a
#    64-, 128- and 498-sided prism:
#    - seated: its centre rests at h/2 - rho g h / KN, the same for every tessellation (the sink
#      of a uniformly pressed base, W / (KN A) = rho g h / KN, does not depend on its area); to
#      1e-3 of that sink (the settling stops at an unbalanced force of 1e-6 of the weight);
#    - rocking: the peak tilt converges as the polygon approaches the circle. The tolerance is a
#      convergence bound from the two coarser tessellations: a discretisation error of order p >= 1
#      in 1/N changes the peak tilt from N = 128 to 498 by at most
#      (1/128 - 1/498) / (1/64 - 1/128) = 0.74 of its change from 64 to 128.
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}
T=${RD_TMP:-$(mktemp -d)}/convex_faces; mkdir -p "$T"; cd "$T" || exit 1
fails=0

# 1. check takes 500-face convex bodies
/usr/bin/python3 - > sphere.dat <<'PY'
import math
n = 252  # a hull of n points in general position on a sphere has 2 n - 4 = 500 triangles
pts = []
for i in range(n):  # a Fibonacci sphere, radius 0.3 m
    z = 1 - (2 * i + 1) / n
    r, a = math.sqrt(1 - z * z), i * math.pi * (3 - math.sqrt(5))
    pts += ["%.12f %.12f %.12f" % (0.3 * r * math.cos(a), 0.3 * r * math.sin(a), 0.3 * z)]
print("block create brick size 2 2 0.4 position 0 0 -0.2 fixed name base")
print("block create polyhedron vertices " + " ".join(pts) + " seat-on base name ball")
print("contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 35")
print("ground-motion pulse one-sine amplitude 0.1g frequency 2 direction 0")
print("model solve time 0.1")
PY
drum() { # drum SIDES: the rocking scene
    cat <<DAT
block create brick size 2 2 0.4 position 0 0 -0.2 fixed name base
block create prism sides $1 radius 0.2 height 1.6 seat-on base name drum
contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 35
model damping viscous 0.2
ground-motion pulse one-sine amplitude 0.4g frequency 2 direction 0
model solve time 1.0
output hdf5 'drum.h5' interval 0.002
DAT
}
for n in 64 128 498; do drum "$n" > "drum$n.dat"; done
for scene in drum498 sphere; do
    if out=$("$BIN" check "$scene.dat" 2>&1); then
        echo "CHECK convex faces: check takes $scene.dat (500 faces)"
    else
        echo "FAIL convex faces: check refuses $scene.dat: $(echo "$out" | head -1)"
        fails=$((fails + 1))
    fi
done

# 2. seated and rocking, three tessellations
for n in 64 128 498; do
    if ! "$BIN" run "drum$n.dat" -q -o "drum$n.h5" > "run$n.txt" 2>&1; then
        echo "FAIL convex faces: run drum$n.dat: $(head -1 "run$n.txt")"
        exit 1
    fi
done
/usr/bin/python3 - drum64.h5 drum128.h5 drum498.h5 <<'PY' || fails=$((fails + 1))
import sys, h5py, numpy as np
rho, g, h, kn = 2700.0, 9.81, 1.6, 1e10  # the default density, the scene's drum and joint
sink = rho * g * h / kn
runs = [h5py.File(f, "r") for f in sys.argv[1:]]
seated = [f["position"][0, 0, 2] for f in runs]   # the first sample: settled, before the pulse
tilt = [float(np.max(f["tilt"][:, 0])) for f in runs]
bad = 0
for n, z in zip((64, 128, 498), seated):
    gap, tol = abs(z - (h / 2 - sink)), 1e-3 * sink
    ok = gap <= tol
    print("%s convex faces: %d-sided drum seated at z %.9f m, h/2 - rho g h/KN %.9f m: gap=%.3g tol=%.3g"
          % ("CHECK" if ok else "FAIL", n, z, h / 2 - sink, gap, tol))
    bad += not ok
step = abs(tilt[1] - tilt[0])
gap, tol = abs(tilt[2] - tilt[1]), (1 / 128 - 1 / 498) / (1 / 64 - 1 / 128) * step
ok = gap <= tol and tilt[1] > 0.5 * runs[1]["summary"].attrs["alpha"][0]  # it rocked
print("%s convex faces: peak tilt 64 / 128 / 498 sides %.6f / %.6f / %.6f rad: |498 - 128| gap=%.3g tol=%.3g (0.74 |128 - 64|)"
      % ("CHECK" if ok else "FAIL", tilt[0], tilt[1], tilt[2], gap, tol))
bad += not ok
sys.exit(1 if bad else 0)
PY
[ "$fails" -eq 0 ]
