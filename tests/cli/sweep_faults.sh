#!/usr/bin/env bash
# Sweeps that always finish (issue 17):
#   1. a table that cannot grow (file-size limit) stops the sweep with exit 3, one line naming
#      the table and the reason, "incomplete" reported; the table holds only whole rows; the
#      same command without the limit completes it and equals an uninterrupted table;
#   2. a table with a partially written last row (what older versions left after a full disk:
#      case 0, hash 0, empty status) is reported, the row dropped and its case run again;
#   3. an unusable output folder is an error (exit 2) with the system's reason; an unusable
#      TMPDIR is none (cases write no run files, issue 14) and the table equals the full one;
#   4. workers die with their coordinator, even one killed by SIGKILL.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/sweep_faults; rm -rf "$T"; mkdir -p "$T"
S=tests/cli/data/sweep_brick.dat
# 70 short cases: the table needs a second chunk of rows at row 64
args=(--set model.duration=0.05 --set model.settle=off --directions 0,5,10,15,20,25,30
      --scales 0.01g,0.02g,0.03g,0.04g,0.05g,0.06g,0.07g,0.08g,0.09g,0.1g -j 1 -q)
"$BIN" sweep "$S" "${args[@]}" -o "$T/full.h5"

# 1. the file-size limit: room for the first chunk of rows (the size of a 1-case table plus
#    40 KiB: more than the 32 KiB kept in reserve per row), not for the second (52 kB more)
"$BIN" sweep "$S" --set model.duration=0.05 --set model.settle=off --scales 0.01g -q -o "$T/one.h5"
lim=$(( ($(stat -c %s "$T/one.h5") + 40 * 1024) / 1024 ))
rc=0; (ulimit -f "$lim"; exec "$BIN" sweep "$S" "${args[@]}" -o "$T/part.h5") 2> "$T/part.err" || rc=$?
[ "$rc" -eq 3 ] || { echo "file-size limit: exit $rc"; cat "$T/part.err"; exit 1; }
grep -q "rockdem sweep: $T/part.h5: cannot extend the table by [0-9]* bytes for row 64: File too large" "$T/part.err"
grep -q "rockdem sweep: $T/part.h5 is incomplete: 64 of 70 cases" "$T/part.err"
h5dump -A "$T/part.h5" > /dev/null
/usr/bin/python3 - "$T/part.h5" <<'PY'
import sys, h5py
g = h5py.File(sys.argv[1], "r")["sweep"]
n = len(g["case"])
assert n == 64, n
rows = [k for k in g if k != "body"]            # /sweep/body: the per-body axis' scale
assert all(len(g[k]) == n for k in rows), {k: len(g[k]) for k in rows}
assert sorted(g["case"][()]) == list(range(64))
names = {v: k for k, v in h5py.check_enum_dtype(g["status"].dtype).items()}
assert all(names[int(s)] in ("done", "overturned") for s in g["status"][()])
PY
"$BIN" sweep "$S" "${args[@]}" -o "$T/part.h5" 2> "$T/resume.err"
cmp_tables() {
    /usr/bin/python3 - "$1" "$2" <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r")["sweep"], h5py.File(sys.argv[2], "r")["sweep"]
assert list(b["case"][()]) == list(range(len(a["case"]))), b["case"][()]
for k in a:
    if k not in ("wall_seconds", "body"):
        assert np.array_equal(a[k][()], b[k][()]), k
PY
}
cmp_tables "$T/full.h5" "$T/part.h5"

# 2. a phantom last row as older versions left it: every column one row longer, fill values
two=(--set model.duration=0.05 --set model.settle=off --scales 0.01g,0.02g -q)
"$BIN" sweep "$S" "${two[@]}" -o "$T/phantom.h5"
/usr/bin/python3 - "$T/phantom.h5" <<'PY'
import sys, h5py
g = h5py.File(sys.argv[1], "r+")["sweep"]
for k in g:                       # row 1 becomes fill values: case 0, hash 0, status 0
    if k == "body": continue      # the per-body axis' scale
    g[k].resize(1, axis=0)
    g[k].resize(2, axis=0)
PY
"$BIN" sweep "$S" "${two[@]}" -o "$T/phantom.h5" 2> "$T/phantom.err"
grep -q "rockdem sweep: $T/phantom.h5: dropped 1 partially written row(s)" "$T/phantom.err"
/usr/bin/python3 -c "
import sys, h5py
g = h5py.File(sys.argv[1], 'r')['sweep']
assert list(g['case'][()]) == [0, 1] and all(len(g[k]) == 2 for k in g if k != 'body')" "$T/phantom.h5"

# 3. unusable TMPDIR and output folder
TMPDIR=/nonexistent/rd "$BIN" sweep "$S" "${args[@]}" -o "$T/tmp.h5"
/usr/bin/python3 -c "
import h5py, sys, numpy as np
a, b = (h5py.File(f, 'r')['sweep'] for f in sys.argv[1:])
assert sorted(a) == sorted(b)
for k in a:
    if k != 'wall_seconds': assert np.array_equal(a[k][()], b[k][()]), k" "$T/full.h5" "$T/tmp.h5"
rc=0; "$BIN" sweep "$S" "${args[@]}" -o /nonexistent/rd/t.h5 2> "$T/out.err" || rc=$?
[ "$rc" -eq 2 ]
grep -q "/nonexistent/rd/t.h5: cannot create the table: No such file or directory" "$T/out.err"

# 4. SIGKILL the coordinator: its two workers (running 600 s cases to their end, --full: about
#    a minute of work each) leave within 3 s
"$BIN" sweep "$S" --set model.duration=600 --scales 0.1g,0.2g -j 2 --full -q -o "$T/kill.h5" 2> /dev/null &
pid=$!
for _ in $(seq 100); do [ "$(pgrep -P "$pid" | wc -l)" -ge 2 ] && break; sleep 0.05; done
workers=$(pgrep -P "$pid" | tr '\n' ' ')
[ -n "$workers" ]
kill -KILL "$pid"
wait "$pid" 2> /dev/null || true
for _ in $(seq 30); do
    alive=0; for w in $workers; do kill -0 "$w" 2> /dev/null && alive=1; done
    [ "$alive" -eq 0 ] && break
    sleep 0.1
done
[ "$alive" -eq 0 ] || { echo "workers $workers outlived their coordinator"; kill $workers; exit 1; }
