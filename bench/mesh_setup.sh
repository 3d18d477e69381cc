#!/usr/bin/env bash
# Mesh load + setup time against triangle count (issue 17: setup was quadratic, 160k triangles
# took 39 s). Generates tools/make_pbr.py rocks of about 10k, 100k and 1M triangles in a
# temporary folder and runs scenarios/pbr.dat on each for 0.001 s without settling. Prints the
# total wall time, the stepping time (the run's own "perf: wall_s") and their difference: load,
# check, setup and output of the mesh. Usage: bench/mesh_setup.sh [BIN_DIR]  (about 1 minute)
set -eu
BIN=${1:-bin}/rockdem
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
printf '%10s %10s %10s %12s\n' triangles total_s steps_s load_setup_s
for nlat in 50 158 500; do
    /usr/bin/python3 tools/make_pbr.py --seed 1 --nlat "$nlat" -o "$T/rock.obj" > /dev/null
    sed "s|'pbr.obj'|'$T/rock.obj'|" scenarios/pbr.dat > "$T/rock.dat"
    t0=$(date +%s.%N)
    out=$("$BIN" run "$T/rock.dat" --set model.duration=0.001 --set model.settle=off -o "$T/rock.h5")
    t1=$(date +%s.%N)
    steps=$(printf '%s\n' "$out" | sed -n 's/^perf: .*wall_s=\([0-9.e+-]*\).*/\1/p')
    printf '%10d %10.2f %10.2f %12.2f\n' $((4 * nlat * (nlat - 1))) "$(echo "$t1 - $t0" | bc)" "$steps" \
        "$(echo "$t1 - $t0 - $steps" | bc)"
done
