#!/bin/bash
# A rockdem sweep on a Slurm cluster (docs/FRAGILITY.md, "MPI"): one MPI rank per core, every
# rank running cases; rank 0 also writes the table. Submit from the rockdem checkout:
#     sbatch docs/examples/slurm_sweep.sh
# Build first on the cluster, with its own MPI (module load openmpi, or Debian's libopenmpi-dev):
#     make && make mpi
# The checkout, the scenario, its mesh and records, and the table's folder must be on a file
# system every node sees; each case's run file goes to $TMPDIR (node-local is best) and is
# deleted after the run unless --keep-runs DIR is given (DIR then on the shared file system).
#SBATCH --job-name=rockdem-sweep
#SBATCH --nodes=2
#SBATCH --ntasks-per-node=32
#SBATCH --cpus-per-task=1
#SBATCH --time=01:00:00
#SBATCH --output=rockdem-sweep-%j.log
set -euo pipefail
export TMPDIR=${SLURM_TMPDIR:-${TMPDIR:-/tmp}}
# the fragility example of the README: 6 record seeds x 2 directions x 6 PGA levels = 72 runs
# (a real study gives --axis motion.seed=1,...,140 and the 19 levels and 8 directions it needs)
SCENE=scenarios/pbr_fragility.dat
TABLE=${TABLE:-pbr_sweep-$SLURM_JOB_ID.h5}   # resume: TABLE=<the earlier table> sbatch ...
# srun starts the ranks under Slurm's own launcher (mpirun -n $SLURM_NTASKS does the same where
# the MPI is not built with Slurm's PMI support). An interrupted job (scancel, the time limit)
# keeps every finished case: resubmit with TABLE set to its table to resume.
# tests/cli/slurm_script.sh runs this script under a stand-in srun (mpirun on 2 ranks).
srun bin/rockdem-mpi sweep "$SCENE" --axis motion.seed=1,2,3,4,5,6 --directions 0,90 \
    --scales 0.15g,0.25g,0.35g,0.5g,0.7g,1.0g -q -o "$TABLE"
echo "table: $TABLE (tools/rdfragility.py reads it: docs/FRAGILITY.md)"
