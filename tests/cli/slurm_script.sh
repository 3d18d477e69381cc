#!/usr/bin/env bash
# docs/examples/slurm_sweep.sh, the Slurm batch script of docs/FRAGILITY.md ("MPI"), is run as
# sbatch would run it: bash's syntax check; every #SBATCH directive before the first command
# (sbatch reads none after it) and spelled --key=value; then the script itself with a stand-in
# `srun` on PATH that starts the same command under mpirun on 2 ranks, each case shortened to
# 0.3 s (model.duration: the command line, not the physics, is under test). It must leave a
# finished table of the script's 72 cases. Skipped (exit 77) without mpicc/mpirun.
set -eu
. "$(dirname "$0")/lib/check.sh"
command -v mpicc > /dev/null && command -v mpirun > /dev/null ||
    skip "no mpicc/mpirun on PATH (Debian libopenmpi-dev openmpi-bin: tools/install-deps.sh)"
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/slurm_script; mkdir -p "$T/bin"
BINDIR=$(cd "$(dirname "$BIN")" && pwd); BUILD=${RD_BUILD:-build}
S=docs/examples/slurm_sweep.sh
bash -n "$S"
# the directives: a block of comments and #SBATCH lines before the first command
awk '/^#SBATCH/ { if (cmd) { print "FAIL #SBATCH after the first command, line " NR; bad = 1 }
                  else if ($0 !~ /^#SBATCH --[a-z-]+=[^ ]+$/) { print "FAIL line " NR ": " $0; bad = 1 }
                  else n++ }
     !/^#/ && !/^[ \t]*$/ { cmd = 1 }
     END { if (n < 4) { print "FAIL only " n " #SBATCH directives"; bad = 1 } exit bad }' "$S"
san=""   # a sanitizer build (make asan): link rockdem-mpi the same way
if nm "$BUILD/librockdem.a" 2>/dev/null | grep -q __asan_init; then
    san="-fsanitize=address,undefined"
    export ASAN_OPTIONS=detect_leaks=0   # OpenMPI's own allocations outlive MPI_Finalize
fi
make -s mpi BUILD="$BUILD" BIN="$BINDIR" SAN="$san" > "$T/mpi.log" 2>&1 || { cat "$T/mpi.log"; exit 1; }
make -s scenarios/pbr.obj > /dev/null
# srun as a Slurm allocation of 2 tasks would run it: the script's bin/rockdem-mpi is this build's
cat > "$T/bin/srun" <<SH
#!/usr/bin/env bash
[ "\$1" = bin/rockdem-mpi ] || { echo "srun runs \$1, not bin/rockdem-mpi" >&2; exit 1; }
shift
exec mpirun --allow-run-as-root --oversubscribe -n 2 "$BINDIR/rockdem-mpi" "\$@" --set model.duration=0.3
SH
chmod +x "$T/bin/srun"
# the script writes its table in the checkout (where sbatch is run): a name of this test's own
job=slurm-test-$$; table=pbr_sweep-$job.h5
trap 'rm -f "$table"' EXIT
PATH="$T/bin:$PATH" TABLE= SLURM_JOB_ID=$job SLURM_TMPDIR="$T" bash "$S" > "$T/out.txt" 2>&1 ||
    { cat "$T/out.txt"; exit 1; }
/usr/bin/python3 - "$table" <<'PY'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "r") as f:
    s = f["sweep"]
    n = int(s.attrs["ncases"])
    assert n == 72, n
    assert np.array_equal(np.sort(s["case"][()]), np.arange(n)), "cases missing"
PY
