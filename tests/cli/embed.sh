#!/usr/bin/env bash
# docs/examples/embed.c, built against librockdem.a with the public headers only, runs its built-in
# scene without writing anything: no file appears in its working directory, and the observer's
# peak tilt (the largest of the 5 ms samples) agrees with the summary's (tracked every step).
set -eu
build=${RD_BUILD:-build}
T=${RD_TMP:-$(mktemp -d)}/embed; rm -rf "$T"; mkdir -p "$T"
out=$(cd "$T" && "$build/embed")
[ -z "$(ls -A "$T")" ] || { echo "embed wrote files: $(ls "$T")"; exit 1; }
grep -q '^status 0: 1 free + 1 fixed bodies' <<< "$out"
obs=$(sed -nE 's/^body 0: peak tilt ([0-9.e+-]+) rad \(observer\), ([0-9.e+-]+) rad \(summary\).*/\1 \2/p' <<< "$out")
# a smooth peak of a motion at the pulse's 2 Hz sampled every 5 ms is missed by at most
# 1 - cos(2 pi 2 Hz x 2.5 ms) = 5e-4 of itself; the 4-digit printing adds 1e-4
/usr/bin/python3 -c "import sys; a, b = map(float, sys.argv[1:]); assert a > 0 and abs(a - b) <= 1e-3 * b, (a, b)" $obs
