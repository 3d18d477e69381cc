#!/usr/bin/env bash
# rd-test: alone
# The docs' generated blocks and figures are what the program prints and draws now
# (tools/docgen.py check): the README's quick-start output, docs/CONTACT.md's preset restitutions
# and the defaults' row of its layout table, docs/FRAGILITY.md's worked-example table against
# docs/pbr_sweep.h5 with 6 of its cases rerun (every result to the bit, CPU time within the stated
# noise), docs/PERFORMANCE.md's CPU times (within the noise), docs/PHYSICS.md's energy residuals
# of the shipped scenes, and the figures redrawn pixel for pixel. Each finding is one FAIL line
# naming the block; `make docs` rewrites them.
set -u
BIN=${RD_BIN:-bin/rockdem}
cd "$(dirname "$0")/../.."
# a sanitizer build (make asan) runs 3-20x slower: its CPU times are not the docs' figures
san=(); ldd "$BIN" 2>/dev/null | grep -q 'libasan\|libubsan' && san=(--no-times)
/usr/bin/python3 tools/docgen.py check --bin "$BIN" "${san[@]}"
