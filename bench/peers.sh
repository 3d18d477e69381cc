#!/usr/bin/env bash
# Time to solution at equal accuracy, rockdem against PyBullet, MuJoCo and YADE in one run
# (issue 13, item 6; bench/peers.py says what is measured).
#
#   bash bench/peers.sh [BINDIR [BUILDDIR]]     (`make bench-peers`; about 10-20 min on 2 cores)
#
# PyBullet and MuJoCo come from PyPI into a virtual environment under BUILDDIR (default build)
# made here on the first run (BUILDDIR/peers-venv); without the network (or pip) they are skipped
# and the table says why. YADE is Debian's (apt-get install yade); without it, skipped the same
# way. Writes the full table to BUILDDIR/bench/peers.md, and each code's best row with the
# sentence they support into README.md and docs/PERFORMANCE.md (between their peers markers).
# Environment: NO_YADE=1 skips YADE; README="FILE ..." writes those files instead (README= : none).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd); root=$(dirname "$here")
bindir=${1:-bin}; case $bindir in /*) ;; *) bindir="$PWD/$bindir" ;; esac
build=${2:-build}; case $build in /*) ;; *) build="$PWD/$build" ;; esac
[ -x "$bindir/rockdem" ] || { echo "bench/peers.sh: no rockdem at $bindir/rockdem (build it first: make)" >&2; exit 1; }
venv="$build/peers-venv"; py="$venv/bin/python"; reason=""
if ! "$py" -c "import pybullet, mujoco" >/dev/null 2>&1; then
    rm -rf "$venv"
    if ! out=$(/usr/bin/python3 -m venv "$venv" 2>&1); then
        reason="cannot make a virtual environment ($(printf '%s' "$out" | tail -n1); apt-get install python3-venv)"
    elif ! out=$("$venv/bin/pip" install --quiet --disable-pip-version-check --timeout 30 pybullet mujoco 2>&1); then
        reason="pip install pybullet mujoco failed (offline?): $(printf '%s' "$out" | tail -n1)"
    elif ! "$py" -c "import pybullet, mujoco" >/dev/null 2>&1; then
        reason="pybullet or mujoco does not import after pip install"
    fi
fi
[ -z "$reason" ] || { echo "SKIP PyBullet and MuJoCo: $reason"; py=""; }
[ -n "$py" ] && echo "peers: $("$py" -c 'import mujoco; print("mujoco", mujoco.__version__)' 2>/dev/null)," \
    "$("$py" -m pip show pybullet 2>/dev/null | sed -n 's/^Version: /pybullet /p')"
yade=(); [ "${NO_YADE:-0}" = 1 ] && yade=(--no-yade)
readme_opt=(); for f in ${README-$root/README.md $root/docs/PERFORMANCE.md}; do readme_opt+=(--readme "$f"); done
mkdir -p "$build/bench"
/usr/bin/python3 "$here/peers.py" --bin "$bindir/rockdem" --venv-python "$py" --skip-reason "$reason" \
    "${yade[@]}" "${readme_opt[@]}" -o "$build/bench/peers.md"
