#!/usr/bin/env bash
# A PBR study, timed on a sample (issue 13, item 5; issue 44, item 7): the shipped PBR
# (scenarios/pbr_fragility.dat: scenarios/pbr.obj on its pedestal, seed 002's joint) under
# 20 s Kanai-Tajimi records, the study being, by STUDY:
#   seed002     97 record seeds x 6 PGA levels (0.15-1.0 g) along x (the thin side) = 582 runs,
#               as seed 002's 582 records per interface and stiffness; target under 10 min
#   echo-cliff  140 record seeds x 19 PGA levels (0.1-1.0 g by 0.05 g) x 8 directions (0-315
#               deg by 45) = 21,280 runs, as seed 000's Echo Cliff study (140 records); target
#               under 30 min
#
#   bash bench/pbr_study.sh [BINDIR]          (`make bench-study`: seed002, about 2-4 min on
#   STUDY=echo-cliff bash bench/pbr_study.sh   2 idle cores; `make bench-echo-cliff`: 3-6 min)
#
# It sweeps a sample of the study with `rockdem sweep` on all cores (SEEDS record seeds x every
# level x the sample's directions: default 2 x 6 x 1 = 12 runs for seed002, 1 x 19 x 4 = 76
# for echo-cliff, directions 0, 90, 180, 270: every level, so overturning and standing runs in
# the study's proportions per level, and both axes of the rock both ways) and projects the
# study from it:
#   from the sample's wall time:  wall x study runs / runs x workers / 2   (2 cores, loaded as now)
#   from its CPU time:            CPU s x study runs / runs / 2            (2 idle cores: each
#                                 run on a core of its own; the workers, user + system time)
# The load average is printed beside the figures: other jobs on the machine slow the first
# (and the per-run wall times in the table), not the second.
# Environment: STUDY (seed002 or echo-cliff, default seed002), SEEDS (record seeds of the
# sample), DIRECTIONS (the sample's directions, deg, comma-separated), JOBS (workers, default
# the number of online cores), DURATION (record and run length, s, default 20), FULL (1: run
# every case to its end, `rockdem sweep --full`; default: a case ends once at rest with the
# record left unable to lift or slide it, column quiet_end), TABLE (keep the sample's table
# there), SAFETY (the step's safety factor, `--set model.safety`, in (0, 1]; default: the
# scene's, 0.2).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd); root=$(dirname "$here")
bindir=${1:-bin}; case $bindir in /*) ;; *) bindir="$PWD/$bindir" ;; esac
rockdem="$bindir/rockdem"
die() { echo "bench/pbr_study.sh: $*" >&2; exit 1; }
posint() { case $2 in ''|*[!0-9]*|0) die "$1 must be a positive integer, got '$2'" ;; esac; }
study=${STUDY:-seed002}
case $study in
seed002)
    STUDY_SEEDS=97   # seed 002: 582 records per interface and stiffness = 97 seeds x 6 levels
    LEVELS=0.15g,0.25g,0.35g,0.5g,0.7g,1.0g
    STUDY_DIRECTIONS=1; sample_dirs=${DIRECTIONS:-0}; seeds=${SEEDS:-2}
    TARGET_S=600 ;;  # issue 13: under 10 min on 2 cores
echo-cliff)
    STUDY_SEEDS=140  # seed 000's Echo Cliff study: 140 records x 19 PGA levels x 8 directions
    LEVELS=$(seq -s, 0.10 0.05 1.00 | sed 's/\([0-9.]*\)/\1g/g')
    STUDY_DIRECTIONS=8; sample_dirs=${DIRECTIONS:-0,90,180,270}; seeds=${SEEDS:-1}
    TARGET_S=1800 ;; # issue 44: under 30 min on 2 cores
*) die "STUDY must be seed002 or echo-cliff, got '$study'" ;;
esac
jobs=${JOBS:-$(nproc)}; duration=${DURATION:-20}
case ${FULL:-0} in 0) full= ;; 1) full=--full ;; *) die "FULL must be 0 or 1, got '$FULL'" ;; esac
posint SEEDS "$seeds"; posint JOBS "$jobs"; posint DURATION "$duration"
safety=()
if [ -n "${SAFETY:-}" ]; then
    awk -v s="$SAFETY" 'BEGIN { exit !(s ~ /^[0-9.]+$/ && s > 0 && s <= 1) }' ||
        die "SAFETY must be a number in (0, 1], got '$SAFETY'"
    safety=(--set "model.safety=$SAFETY")
fi
[ -x "$rockdem" ] || die "no rockdem executable at $rockdem (build it first: make)"
[ -f "$root/scenarios/pbr.obj" ] || die "no scenarios/pbr.obj (make scenarios/pbr.obj)"
nlevels=$(echo "$LEVELS" | tr , '\n' | wc -l)
ndirs=$(echo "$sample_dirs" | tr , '\n' | wc -l)
STUDY_RUNS=$((STUDY_SEEDS * nlevels * STUDY_DIRECTIONS))
[ "$seeds" -le "$STUDY_SEEDS" ] || die "SEEDS must be at most $STUDY_SEEDS"
[ "$ndirs" -le "$STUDY_DIRECTIONS" ] || [ "$study" = seed002 ] ||
    die "DIRECTIONS: at most $STUDY_DIRECTIONS directions"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# the fragility scene with 20 s records and runs, the mesh by its absolute path
sed -e "s|'pbr.obj'|'$root/scenarios/pbr.obj'|" \
    -e "s|^ground-motion stochastic \(.*\) duration [0-9.]* |ground-motion stochastic \1 duration $duration |" \
    -e "s|^model solve time .*|model solve time $duration|" \
    -e "s|^output hdf5 .*|output hdf5 '$tmp/run.h5' interval 0.05|" \
    "$root/scenarios/pbr_fragility.dat" > "$tmp/study.dat"
grep -q "duration $duration " "$tmp/study.dat" && grep -q "solve time $duration$" "$tmp/study.dat" ||
    die "scenarios/pbr_fragility.dat no longer has the lines this script edits"
seedlist=$(seq -s, 1 "$seeds")
runs=$((seeds * nlevels * ndirs))
load0=$(cut -d' ' -f1-3 /proc/loadavg)
t0=$(date +%s.%N)
# the CPU time of the sweep and its workers (waited for): the children line of `times`
cpu_s=$(
    "$rockdem" sweep "$tmp/study.dat" "${safety[@]}" --axis "motion.seed=$seedlist" --directions "$sample_dirs" --scales "$LEVELS" \
        -j "$jobs" $full -q -o "$tmp/sample.h5" >/dev/null || exit 1
    times > "$tmp/times" # (a builtin in this shell: a pipe would fork a shell with no children)
    sed -n 2p "$tmp/times" | awk '{ n = split($1 " " $2, f, " "); s = 0
        for (i = 1; i <= n; i++) { split(f[i], ms, "m"); s += ms[1] * 60 + ms[2] }; printf "%.2f", s }'
) || die "the sample sweep failed"
wall=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
load1=$(cut -d' ' -f1-3 /proc/loadavg)
cpu=$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo | head -n1)

[ -z "${TABLE:-}" ] || cp "$tmp/sample.h5" "$TABLE"
/usr/bin/python3 - "$tmp/sample.h5" "$wall" "$cpu_s" "$runs" "$jobs" "$STUDY_RUNS" "$TARGET_S" "$duration" "$study" <<'PY'
import sys
import h5py
import numpy as np
path = sys.argv[1]
wall, cpu, runs, jobs, study, target, dur = float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), \
    int(sys.argv[5]), int(sys.argv[6]), float(sys.argv[7]), float(sys.argv[8])
name = sys.argv[9]
with h5py.File(path, "r") as f:
    s = f["sweep"]
    per = s["wall_seconds"][:]
    over = s["overturned"][:].astype(bool)
    end = s["end_time"][:]
    pga = s["pga"][:]
    quiet = s["quiet_end"][:]
    direction = s["direction"][:] if "direction" in s else None
if len(per) != runs:
    sys.exit("bench/pbr_study.sh: the table has %d rows, expected %d" % (len(per), runs))
from_wall = wall * study / runs * jobs / 2
from_cpu = cpu * study / runs / 2
print("per run: %.1f CPU s on average; wall (as loaded): %.1f s (standing %.1f s, overturned "
      "%.1f s), %.1f simulated s" % (cpu / runs, per.mean(), per[~over].mean() if (~over).any() else float("nan"),
                                      per[over].mean() if over.any() else float("nan"), end.mean()))
print("ended quietly (at rest, the record left unable to lift or slide the rock): %d of %d runs, "
      "%.1f simulated s on average of the standing runs" % ((quiet >= 0).sum(), runs,
      end[~over].mean() if (~over).any() else float("nan")))
for g in np.unique(np.round(pga / 9.80665, 2)):
    sel = np.round(pga / 9.80665, 2) == g
    print("  PGA %.2f g: %d/%d overturned, %.1f s per run" % (g, over[sel].sum(), sel.sum(), per[sel].mean()))
if direction is not None and len(np.unique(direction)) > 1:
    for d in np.unique(direction):
        sel = direction == d
        print("  direction %g deg: %d/%d overturned, %.1f s per run" % (d, over[sel].sum(), sel.sum(), per[sel].mean()))
print("sample: %d runs of %g s records on %d workers: %.1f s wall, %.1f CPU s" % (runs, dur, jobs, wall, cpu))
print("projected %d-run %s study on 2 cores: %.1f min from the sample's wall time (as loaded), %.1f min "
      "from its CPU time (2 idle cores; target < %.0f min: %s)" % (study, name, from_wall / 60, from_cpu / 60,
      target / 60, "met" if from_cpu < target else "NOT met"))
PY
echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')  cpu: ${cpu:-unknown} ($(nproc) cpus)  load average before: $load0, after: $load1"
