#!/usr/bin/env bash
# Live YADE check for CI (.ci/run): translate tests/data/yade/free.dat, run it in YADE for 0.5 s
# and compare with the stored run tests/data/yade/free.h5 (made the same way by regen.py): the
# stored data the tests rely on must be what this YADE produces. Tolerance on the first impact
# time: YADE's own change when its step is halved (stored free.h5 against half/free.h5),
# computed here; the release tilt must agree to 1e-6 (the same initial condition).
#   bash tools/yade/live_check.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
command -v yade >/dev/null || { echo "live_check: yade not installed (apt-get install yade)" >&2; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
dat="$root/tests/data/yade/free.dat"
/usr/bin/python3 "$root/tools/yade/translate.py" "$dat" --set model.duration=0.5 -o "$tmp/yade.h5" </dev/null | grep '^yade-run:'
cd "$root"
/usr/bin/python3 - "$tmp/yade.h5" tests/data/yade/free.h5 tests/data/yade/half/free.h5 <<'PY'
import sys
sys.path.insert(0, "tools/yade")
from compare import RunFile
live, stored, half = (RunFile(p) for p in sys.argv[1:])
t = [R.impacts(0)[0][0] for R in (live, stored, half)]
tol = abs(t[1] - t[2])
print("first impact: live %.6f s, stored %.6f s, diff %.3g s, tol %.3g s (YADE's dt/2 change)" % (t[0], t[1], abs(t[0] - t[1]), tol))
assert abs(t[0] - t[1]) <= tol, "live YADE differs from the stored run"
a, b = live.sumval("max_tilt", 0), stored.sumval("max_tilt", 0)
assert abs(a - b) <= 1e-6 * b, (a, b)
PY
echo "live_check: ok"
