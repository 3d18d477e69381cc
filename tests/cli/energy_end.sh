#!/usr/bin/env bash
# Issue 10, item 3: the energy sample taken at the end of a run. Inside a step, samples are taken
# after the kick and before the drift: the mean velocity v(n) and the position x(n) belong to the
# same time. The end-of-run sample came after the last drift, with x(n+1) against v(n), which left
# m g vz dt in the balance of a body still falling: 1.62 J for a 0.5 m cube (312.5 kg) falling
# for 1 s at a 5e-5 s step, a residual of 1.0e-4 of the energy scale in a scene with no contact.
# Free fall is integrated exactly by the leapfrog (constant force), so the balance of a body
# that never touches anything must close to round-off; tolerance 1e-9 of the energy scale
# (the scale is about 16 kJ here; round-off of the summed terms is near 1e-12 of it).
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=$(cd "$(dirname "${RD_BIN:-bin/rockdem}")" && pwd)/rockdem; T=${RD_TMP:-$(mktemp -d)}/energy_end; rm -rf "$T"; mkdir -p "$T"
cat > "$T/fall.dat" <<'EOS'
block create brick size 4 4 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.5 0.5 0.5 position 0 0 20.25 name blk
model settle off
model timestep fixed 5e-5
model solve time 1.0
output hdf5 'fall.h5' interval 0.01
EOS
(cd "$T" && "$BIN" run fall.dat -o fall.h5 > fall.log 2>&1) || { echo "FAIL energy-end: the run failed"; cat "$T/fall.log"; exit 1; }
r=$(energy_residual "$T/fall.h5")
echo "free fall, 1 s at 5e-5 s: energy residual $r"
ok=$(awk -v r="$r" 'BEGIN { print (r <= 1e-9) ? 1 : 0 }')
verdict "energy-end/free-fall (energy residual)" "$ok" "$r" 1e-9 strict || exit 1
