#!/usr/bin/env bash
# Speed benchmark: rockdem vs YADE on the same scene (a 0.5 x 0.5 x 1.0 m block rocking freely on a
# fixed base, bench/block.dat; YADE side: bench/yade_block.py).
#
#   bash bench/run.sh [BINDIR]        (BINDIR holds rockdem; default: bin)
#
# rockdem runs bench/block.dat REPS times (default 3) and the fastest run counts. If `yade` is on
# PATH, the YADE script runs the same window (same dt, same number of steps) rebuilt and rerun
# enough times to take ~10-20 s, and its fastest run counts. Prints a table and writes it, with the
# date, `uname -m` and the CPU model, to bench/results.txt (overwritten). Needs no network.
# Environment: REPS (rockdem repetitions), YADE_STEPS, YADE_REPS (override the YADE run),
# NO_YADE=1 (skip YADE even if installed).
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
bindir=${1:-bin}
case $bindir in /*) ;; *) bindir="$PWD/$bindir" ;; esac
rockdem="$bindir/rockdem"
scene="$here/block.dat"
yscript="$here/yade_block.py"
results="$here/results.txt"
reps=${REPS:-5}

die() { echo "bench: $*" >&2; exit 1; }
[ -x "$rockdem" ] || die "no rockdem executable at $rockdem (build it first: make)"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Value of key=value in a line of key=value words ("" if absent).
kv() { printf '%s\n' "$1" | tr ' ' '\n' | sed -n "s/^$2=//p" | head -n1; }
# Floating-point arithmetic / formatting through awk.
calc() { awk "BEGIN { printf \"%.6g\", $1 }"; }
calc3() { awk "BEGIN { printf \"%.3g\", $1 }"; }

# Scene parameters, read from block.dat so the YADE run matches it.
dt=$(sed -n 's/^[[:space:]]*model[[:space:]]\{1,\}timestep[[:space:]]\{1,\}fixed[[:space:]]\{1,\}\([^[:space:];]*\).*/\1/p' "$scene" | tail -n1)
tsim=$(sed -n 's/^[[:space:]]*model[[:space:]]\{1,\}solve[[:space:]]\{1,\}time[[:space:]]\{1,\}\([^[:space:];]*\).*/\1/p' "$scene" | tail -n1)
tilt=$(sed -n 's/^[[:space:]]*block[[:space:]]\{1,\}initial.*[[:space:]]tilt[[:space:]]\{1,\}\([^[:space:];]*\).*/\1/p' "$scene" | tail -n1)
dt=${dt:-5e-5}; tsim=${tsim:-2}; tilt=${tilt:-2}

# ---- rockdem ----------------------------------------------------------------------------------
# Two contact discretisations of the same block: its four base corners (3DEC's default
# fewest-triangle subcontacts, the natural match for YADE's one-force-per-contact law) and an
# 11 x 11 Winkler bed (rockdem's automatic spacing, a tenth of the shortest edge).
cd "$root"
run_rockdem() { # run_rockdem LABEL SPACING -> sets r_* globals for the best of $reps runs
    local label=$1 spacing=$2 best="" best_wall="" out line w
    for i in $(seq 1 "$reps"); do
        if ! out=$("$rockdem" run "$scene" --set "output.file=$tmp/bench-$i.h5" \
                   --set "contact.spacing=$spacing" </dev/null 2>&1); then
            printf '%s\n' "$out" | tail -n 20 >&2
            die "rockdem run $i ($label) failed"
        fi
        line=$(printf '%s\n' "$out" | grep -o 'perf: steps=.*' | tail -n1 || true)
        [ -n "$line" ] || { printf '%s\n' "$out" | tail -n 20 >&2; die "rockdem printed no 'perf:' line"; }
        w=$(kv "$line" wall_s)
        echo "rockdem $label run $i: $line"
        if [ -z "$best_wall" ] || awk "BEGIN { exit !($w < $best_wall) }"; then best=$line; best_wall=$w; fi
    done
    r_steps=$(kv "$best" steps)
    r_wall=$(kv "$best" wall_s)
    r_sps=$(kv "$best" steps_per_s)
    r_ns=$(kv "$best" ns_per_subcontact_step)
    r_act=$(kv "$best" mean_active_subcontacts)
    r_wps=$(kv "$best" wall_per_sim_s)
}
run_rockdem corners vertices
c_steps=$r_steps c_wall=$r_wall c_sps=$r_sps c_ns=$r_ns c_act=$r_act c_wps=$r_wps
run_rockdem bed auto

# ---- YADE -------------------------------------------------------------------------------------
have_yade=0; yade_note=""
if [ "${NO_YADE:-0}" != 1 ] && command -v yade >/dev/null 2>&1; then
    have_yade=1
    ysteps=${YADE_STEPS:-$(awk "BEGIN { printf \"%d\", $tsim / $dt + 0.5 }")}
    yargs=("$ysteps" "$dt" --tilt "$tilt")
    if [ -n "${YADE_REPS:-}" ]; then
        yreps=$YADE_REPS
    else  # one probe run, then enough repetitions for ~12 s of timed work (1 to 30)
        probe=$(yade -n -j1 -x "$yscript" "${yargs[@]}" </dev/null 2>&1 | grep '^yade: ' || true)
        [ -n "$probe" ] || die "the YADE probe run printed no 'yade:' line"
        pw=$(kv "$probe" wall_s)
        yreps=$(awk "BEGIN { n = int(12 / $pw + 0.999); if (n < 1) n = 1; if (n > 30) n = 30; print n }")
    fi
    yout=$(yade -n -j1 -x "$yscript" "${yargs[@]}" --reps "$yreps" </dev/null 2>&1) || {
        printf '%s\n' "$yout" | tail -n 20 >&2; die "YADE run failed"; }
    yline=$(printf '%s\n' "$yout" | grep '^yade: ' | tail -n1 || true)
    ystate=$(printf '%s\n' "$yout" | grep '^yade-state: ' | tail -n1 || true)
    [ -n "$yline" ] || { printf '%s\n' "$yout" | tail -n 20 >&2; die "YADE printed no 'yade:' line"; }
    echo "YADE (best of $yreps): $yline"
    echo "$ystate"
    y_steps=$(kv "$yline" steps)
    y_wall=$(kv "$yline" wall_s)
    y_sps=$(kv "$yline" steps_per_s)
    y_wps=$(calc "$y_wall / ($y_steps * $dt)")
else
    if [ "${NO_YADE:-0}" = 1 ]; then yade_note="YADE skipped (NO_YADE=1)"
    else yade_note="YADE not found on PATH: rockdem figures only (install: apt-get install yade)"; fi
fi

# ---- report -----------------------------------------------------------------------------------
cpu=$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo 2>/dev/null | head -n1)
[ -n "$cpu" ] || cpu=$(lscpu 2>/dev/null | sed -n 's/^Model name:[[:space:]]*//p' | head -n1)
[ -n "$cpu" ] || cpu=unknown
{
    echo "rockdem speed benchmark: bench/block.dat (0.5 x 0.5 x 1.0 m block rocking from ${tilt} deg on a base)"
    echo "date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')   arch: $(uname -m)   cpu: $cpu ($(nproc 2>/dev/null || echo ?) cpus)"
    echo "dt = $dt s, simulated window = $(calc "$r_steps * $dt") s; best of $reps rockdem runs"
    echo
    printf '%-16s %8s %10s %14s %14s %28s\n' code steps wall_s steps_per_s wall_s/sim_s ns/subcontact-step
    printf '%-16s %8s %10s %14s %14s %28s\n' "rockdem corners" "$c_steps" "$c_wall" "$c_sps" "$c_wps" \
        "${c_ns:-?} (mean ${c_act:-?} active)"
    printf '%-16s %8s %10s %14s %14s %28s\n' "rockdem bed" "$r_steps" "$r_wall" "$r_sps" "$r_wps" \
        "${r_ns:-?} (mean ${r_act:-?} active)"
    if [ "$have_yade" = 1 ]; then
        printf '%-16s %8s %10s %14s %14s %28s\n' yade "$y_steps" "$y_wall" "$y_sps" "$y_wps" -
        echo
        echo "ratio rockdem/YADE, steps per second: corners $(calc3 "$c_sps / $y_sps")x, bed $(calc3 "$r_sps / $y_sps")x"
        echo "ratio YADE/rockdem, wall s per simulated s: corners $(calc3 "$y_wps / $c_wps")x, bed $(calc3 "$y_wps / $r_wps")x"
        echo "YADE: yade -n -j1 -x bench/yade_block.py ${yargs[*]} --reps $yreps (best of $yreps runs)"
        echo "YADE final state: ${ystate#yade-state: }"
    else
        echo
        echo "$yade_note"
    fi
    echo "rockdem: $rockdem run bench/block.dat --set contact.spacing=vertices|auto --set output.file=<tmp>.h5"
} > "$tmp/table"
echo
cat "$tmp/table"
cp "$tmp/table" "$results"
# multi-body scenes (two-block stack, 4-drum column), same step in both codes: bench/scenes.sh
{ echo; echo "multi-body scenes (bench/scenes.sh; ratio = YADE / rockdem wall s per simulated s):"
  bash "$here/scenes.sh" "$bindir"; } | tee -a "$results"
