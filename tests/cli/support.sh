#!/usr/bin/env bash
# The support polygon of a block that does not sit squarely on one body (issue 14's 5,000-brick
# wall): a brick overhanging the one below is held only where that body is, and a brick in
# running bond rests on two. Each scene is placed exactly (settle off), so the static tipping
# angle is pure geometry, alpha = atan(d / h), d the distance from the centre of mass to the
# edge of the part of the base that lies over the bodies below, h = 0.1 m; nothing may be
# reported overturned in a quiet run, and no joint may open more than elastically.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/support; rm -rf "$T"; mkdir -p "$T"
# overhang: b (0.4 x 0.2 x 0.2 m) shifted 0.15 m along x on a: held over x in [-0.05, 0.2],
# its centre at x = 0.15, so d = 0.05 m towards +x (the least) and alpha = atan(0.5)
cat > "$T/overhang.dat" <<'EOF'
block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.2 0.2 position 0 0 0.1 name a
block create brick size 0.4 0.2 0.2 position 0.15 0 0.3 name b
model settle off
model solve time 0.005
EOF
# running bond: c (0.4 x 0.4 x 0.2 m) over the joint between a1 and a2 (0.4 x 0.2 x 0.2 m each,
# side by side along x): held over x in [-0.15, 0.25] (both bricks) and y in [-0.1, 0.1] (their
# width, narrower than c's 0.4 m), centre at x = 0.05: d = 0.1 m towards y, alpha = atan(1)
cat > "$T/bond.dat" <<'EOF'
block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.2 0.2 position -0.2 0 0.1 name a1
block create brick size 0.4 0.2 0.2 position 0.2 0 0.1 name a2
block create brick size 0.4 0.4 0.2 position 0.05 0 0.3 name c
model settle off
model solve time 0.005
EOF
check() { # scene, body, expected alpha_min (rad)
    out=$("$BIN" run "$T/$1.dat" -o "$T/$1.h5")
    if grep -q OVERTURNED <<< "$out"; then echo "FAIL: $1: a quiet run reports an overturn"; echo "$out"; exit 1; fi
    # a quiet joint opens only elastically: placed at zero force, a 0.2 m brick of 2700 kg/m^3
    # bounces on KN = 1e10 Pa/m by about 2 rho g H / KN = 1e-6 m; 0.1 mm is a hundred times that
    # (the part of a base beside the body below is not an opening: it read 100-250 mm)
    awk '/^joint .* max opening/ { v = $0; sub(/.*max opening /, "", v); sub(/ mm.*/, "", v);
        if (v + 0 > 0.1) { print "FAIL: " $0; bad = 1 } } END { exit bad }' <<< "$out"
    /usr/bin/python3 - "$T/$1.h5" "$2" "$3" <<'EOF'
import math, sys
import h5py
f, body, want = h5py.File(sys.argv[1], "r"), sys.argv[2], float(sys.argv[3])
names = [x.decode() for x in f["bodies/names"][()]]
got = f["summary"].attrs["alpha_min"][names.index(body)]
# exact placement: the polygon is built from vertex coordinates, so only round-off remains
# (1e-12 m on 0.1 m); 1e-9 rad is a thousand times that.
assert abs(got - want) < 1e-9, (sys.argv[1], body, got, want)
print("%s: %s alpha_min %.9f rad, geometry %.9f" % (sys.argv[1].split("/")[-1], body, got, want))
EOF
}
check overhang b "$(/usr/bin/python3 -c 'import math; print(repr(math.atan(0.5)))')"
check bond c "$(/usr/bin/python3 -c 'import math; print(repr(math.atan(1.0)))')"
