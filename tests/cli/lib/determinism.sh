# Shared by tests/cli/determinism.sh and determinism_mpi.sh (sourced). Box2D's test_determinism
# is the model: a fixed scene is run and a hash of its final state is compared with a pinned
# value, so that any change of results, wanted or not, shows up as a deliberate hash update.
#
# Scene: tests/cli/data/sweep_brick.dat (a brick rocking under a 2 Hz one-sine pulse, with
# impacts, slip and, at 1 g, overturning) at 0.5 g and 1.0 g, along 0 and 30 degrees: 4 cases.
# Hash: 64-bit FNV-1a over the text "%.17g" (round-trip exact) of every body's final position,
# quaternion, velocity and angular velocity, case by case in case order.
#
# DET_HASH changes whenever the engine's results change (the contact physics of issues 10/11,
# an integrator change, a different summation order). To update it after a deliberate change:
#     make && bash tests/cli/determinism.sh      # prints "new hash: ..." when it differs
# then paste the printed value here, and say in the commit message why the results changed.
DET_HASH=1cf88d15811354ad
DET_SCENE=tests/cli/data/sweep_brick.dat
DET_SCALES=0.5g,1.0g
DET_DIRECTIONS=0,30

# det_hash FILE.h5...: the hash of the final states of these run files, in the order given
det_hash() {
    /usr/bin/python3 - "$@" <<'PY'
import sys, h5py
h = 0xcbf29ce484222325
for path in sys.argv[1:]:
    f = h5py.File(path, "r")
    for key in ("position", "quaternion", "velocity", "angular_velocity"):
        for v in f[key][-1].ravel():
            for byte in ("%.17g\n" % v).encode():
                h = ((h ^ byte) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
print("%016x" % h)
PY
}

# det_check LABEL HASH: compare with the pinned value; returns 1 and prints the new hash if not
det_check() {
    if [ "$2" = "$DET_HASH" ]; then echo "determinism $1: $2 ok"; return 0; fi
    echo "FAIL determinism $1: hash $2, pinned $DET_HASH"
    echo "new hash: $2 (if the change of results is deliberate, set DET_HASH in tests/cli/lib/determinism.sh)"
    return 1
}
