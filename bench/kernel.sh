#!/usr/bin/env bash
# rockdem's contact cost against the reference point kernel (bench/kernel.c, issue 13 item 4).
#
#   bash bench/kernel.sh [BINDIR [KERNELDIR]]    (defaults: bin, build/bench; `make bench` runs it)
#
# Scenes: the corner block (bench/block.dat, 4 vertex subcontacts), the 11 x 11 bed (the same
# block, default contact), the shipped PBR (scenarios/pbr.dat, 3,968 triangles), the same rock
# as a 5,040-triangle mesh (`tools/make_pbr.py --seed 1 --nlat 36`, on the same pedestal) and a
# 20-drum column (bench/column_scene.sh, 0.1 s). REPS rounds (default 3); in each round every scene runs once in
# rockdem and then once in each kernel build on as many points as rockdem's mean active
# subcontacts, so the two share the machine's state. The fastest of the rounds counts for each.
# rockdem's figure is its `perf:` line: ns per active subcontact-step (wall time over steps times
# mean active subcontacts) and wall s per simulated s. The kernel figure is ns per point-step;
# ratio = rockdem / kernel (1 = the kernel's speed). Kernel builds: `kernel` with rockdem's own
# flags (Makefile OPT), `kernel-native` with -O3 -march=native -fno-math-errno.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd); root=$(dirname "$here")
bindir=${1:-bin}; case $bindir in /*) ;; *) bindir="$PWD/$bindir" ;; esac
kdir=${2:-build/bench}; case $kdir in /*) ;; *) kdir="$PWD/$kdir" ;; esac
rockdem="$bindir/rockdem"; reps=${REPS:-3}
die() { echo "bench/kernel.sh: $*" >&2; exit 1; }
[ -x "$rockdem" ] || die "no rockdem executable at $rockdem (build it first: make)"
for k in kernel kernel-native; do [ -x "$kdir/$k" ] || die "no $kdir/$k (build it: make bench)"; done
[ -f "$root/scenarios/pbr.obj" ] || die "no scenarios/pbr.obj (make scenarios/pbr.obj)"
case $reps in ''|*[!0-9]*|0) die "REPS must be a positive integer, got '$reps'" ;; esac
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
kv() { printf '%s\n' "$1" | tr ' ' '\n' | sed -n "s/^$2=//p" | head -n1; }
KERNEL_POINT_STEPS=30000000 # per kernel run: ~0.2-0.6 s at 6-20 ns per point-step

bash "$here/column_scene.sh" 20 0.1 "$tmp/column.h5" > "$tmp/column20.dat"
/usr/bin/python3 "$root/tools/make_pbr.py" --seed 1 --nlat 36 -o "$tmp/pbr5k.obj" > /dev/null
sed "s|'pbr.obj'|'$tmp/pbr5k.obj'|" "$root/scenarios/pbr.dat" > "$tmp/pbr5k.dat"
grep -q "pbr5k.obj" "$tmp/pbr5k.dat" || die "scenarios/pbr.dat no longer imports 'pbr.obj'"
scenes=(corners bed pbr pbr5k column20)
scene_args() { # the rockdem run arguments of scene $1
    case $1 in
        corners) echo "$here/block.dat --set contact.spacing=vertices" ;;
        bed) echo "$here/block.dat" ;;
        pbr) echo "$root/scenarios/pbr.dat" ;;
        pbr5k) echo "$tmp/pbr5k.dat" ;;
        column20) echo "$tmp/column20.dat" ;;
    esac
}
declare -A best # best[scene.field]: fastest figure over the rounds
keep_min() { # keep_min KEY VALUE
    if [ -z "${best[$1]:-}" ] || awk "BEGIN { exit !($2 < ${best[$1]}) }"; then best[$1]=$2; fi
}
for round in $(seq 1 "$reps"); do
    for sc in "${scenes[@]}"; do
        # shellcheck disable=SC2046
        out=$("$rockdem" run $(scene_args "$sc") --set "output.file=$tmp/$sc.h5" </dev/null 2>&1) || {
            printf '%s\n' "$out" | tail -n 5 >&2; die "rockdem run of $sc failed"; }
        line=$(printf '%s\n' "$out" | grep -o 'perf: steps=.*' | tail -n1) || die "$sc: rockdem printed no perf: line"
        act=$(kv "$line" mean_active_subcontacts)
        keep_min "$sc.ns" "$(kv "$line" ns_per_subcontact_step)"
        keep_min "$sc.wps" "$(kv "$line" wall_per_sim_s)"
        best[$sc.act]=$act
        n=$(awk "BEGIN { n = int($act + 0.5); print n < 4 ? 4 : n }")
        steps=$(awk "BEGIN { printf \"%d\", $KERNEL_POINT_STEPS / $n + 1 }")
        for k in kernel kernel-native; do
            kout=$("$kdir/$k" "$n" "$steps") || die "$k $n $steps failed: $kout"
            kl=$(printf '%s\n' "$kout" | grep 'variant=scalar'); keep_min "$sc.$k.scalar" "$(kv "$kl" ns_per_point_step)"
            kl=$(printf '%s\n' "$kout" | grep 'variant=soa'); keep_min "$sc.$k.soa" "$(kv "$kl" ns_per_point_step)"
            best[$sc.$k.n]=$(kv "$kl" n)
        done
        echo "round $round $sc: rockdem $(kv "$line" ns_per_subcontact_step) ns/active subcontact-step" \
             "($act active), kernel scalar/soa ${best[$sc.kernel.scalar]}/${best[$sc.kernel.soa]}," \
             "native ${best[$sc.kernel-native.scalar]}/${best[$sc.kernel-native.soa]} ns/point-step (best so far)"
    done
done

ratio() { awk "BEGIN { printf \"%.2fx\", $1 / $2 }"; }
cpu=$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo | head -n1)
echo
echo "rockdem vs the reference point kernel (bench/kernel.c), best of $reps interleaved rounds"
echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')  cpu: ${cpu:-unknown} ($(nproc) cpus)"
echo "ns = ns per active subcontact-step (rockdem) or per point-step (kernel); ratio = rockdem / kernel"
printf '%-9s %7s %9s %11s | %-16s %-16s | %-16s %-16s\n' scene active rockdem wall/sim_s \
    "scalar (OPT)" "soa (OPT)" "scalar (native)" "soa (native)"
for sc in "${scenes[@]}"; do
    r=${best[$sc.ns]}
    cell() { printf '%s ns %s' "${best[$sc.$1.$2]}" "$(ratio "$r" "${best[$sc.$1.$2]}")"; }
    printf '%-9s %7.0f %9.4g %11.3g | %-16s %-16s | %-16s %-16s\n' "$sc" "${best[$sc.act]}" "$r" "${best[$sc.wps]}" \
        "$(cell kernel scalar)" "$(cell kernel soa)" "$(cell kernel-native scalar)" "$(cell kernel-native soa)"
done
echo "kernel points: the scene's mean active subcontacts rounded up to a square grid (at least 4)"
