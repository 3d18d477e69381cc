#!/bin/bash
# rd-test: alone
# rd-test: alone
# The surface model's setup grows as n log n in a mesh's faces, not n^2 (issue 39): grouping the
# faces into planes compared each face with every plane so far, and a scanned rock has nearly
# as many planes as faces (tools/make_pbr.py --nlat 158, 99,540 triangles: 3.8 CPU-s of setup
# against 0.24 at --nlat 79, 24,648 triangles, 16x for 4x the faces). The rock of
# scenarios/pbr.dat under `contact model surface`, run for 0.001 s without settling (a few
# steps: the time is the meshes' load, hull, planes, cells, trees). Four times the faces must
# cost less than 8 times the CPU time: linear setup gives 4x (n log n a little more), a
# quadratic part 16x; 8 is their geometric mean, the midpoint between the two hypotheses on a
# shared machine whose load moves either figure by a factor of about 1.5 (as
# tests/cli/setup_scaling.sh). Each size takes the lower of two runs' user + system CPU time.
set -u
. "$(dirname "$0")/lib/check.sh"
T=${RD_TMP:-$(mktemp -d)}
bin=${RD_BIN:-bin/rockdem}
fail=0

cpu_of() { # cpu_of NLAT: the lower CPU time (s) of two setups of an NLAT rock on its pedestal
    /usr/bin/python3 tools/make_pbr.py --seed 1 --nlat "$1" -o "$T/rock$1.obj" > /dev/null ||
        return 1
    sed "s|'pbr.obj'|'$T/rock$1.obj'|; s|^contact property .*|contact model surface\n& restitution 1|" \
        scenarios/pbr.dat > "$T/rock$1.dat"
    least_cpu "$T/time$1" "$bin" run "$T/rock$1.dat" -q --set model.duration=0.001 \
        --set model.settle=off -o "$T/rock$1.h5"
}

small=$(cpu_of 79) || { echo "FAIL run of the 24,648-triangle rock"; exit 1; }
large=$(cpu_of 158) || { echo "FAIL run of the 99,540-triangle rock"; exit 1; }
ratio=$(awk -v a="$small" -v b="$large" 'BEGIN { printf "%.3g", (a > 0) ? b / a : 1e9 }')
echo "CHECK surface setup CPU-s: 24,648 triangles $small, 99,540 triangles $large, ratio $ratio (linear 4, quadratic 16)"
verdict "surface setup of 4x the faces within 8x the CPU time" \
    "$(awk -v q="$ratio" 'BEGIN { print (q < 8) ? 1 : 0 }')" "$ratio" "<8" strict || fail=1
exit $fail
