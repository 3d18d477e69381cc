#!/usr/bin/env bash
# rockdem sweep is resumable: a sweep stopped half-way (SIGTERM, as Ctrl-C) keeps every
# finished case; the same command finishes it, and the table equals an uninterrupted one
# (every column but wall_seconds, rows in case order).
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/sweep_resume; mkdir -p "$T"
S=tests/cli/data/sweep_brick.dat
args=(--set model.duration=8 --set contact.spacing=0.05 --scales 0.2g,0.3g --directions 0,30,60,90)
"$BIN" sweep "$S" "${args[@]}" -j 2 -q -o "$T/full.h5"
mkdir -p "$T/runs"
"$BIN" sweep "$S" "${args[@]}" -j 1 -q --keep-runs "$T/runs" -o "$T/part.h5" 2> "$T/part.err" &
pid=$!
for _ in $(seq 200); do   # the 4th case has started: 3 are in the table
    [ "$(ls "$T/runs" | wc -l)" -ge 4 ] && break
    sleep 0.05
done
kill -TERM "$pid"
rc=0; wait "$pid" || rc=$?
[ "$rc" -eq 130 ]
grep -q "run the same command to resume" "$T/part.err"
/usr/bin/python3 -c "
import sys, h5py
n = len(h5py.File(sys.argv[1], 'r')['sweep/case'])
assert 3 <= n < 8, n" "$T/part.h5"
"$BIN" sweep "$S" "${args[@]}" -j 2 -o "$T/part.h5" 2>/dev/null | grep -q "already in the table"
/usr/bin/python3 - "$T/full.h5" "$T/part.h5" <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r")["sweep"], h5py.File(sys.argv[2], "r")["sweep"]
assert sorted(a) == sorted(b)
assert list(b["case"][()]) == list(range(8))
for k in a:
    if k != "wall_seconds":
        assert np.array_equal(a[k][()], b[k][()]), k
PY
