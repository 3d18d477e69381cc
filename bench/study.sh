#!/usr/bin/env bash
# `make study`: DEM error against the CVODE rigid references as KN, the time-step safety factor
# and the subcontact spacing vary (tools/study.py); writes docs/study.md and docs/study.png.
set -euo pipefail
BIN=${1:-bin}
/usr/bin/python3 "$(dirname "$0")/../tools/study.py" "$BIN/rockdem" "$(dirname "$0")/../docs"
