#!/usr/bin/env bash
# Ctrl-C (SIGINT), kill (SIGTERM) and a hang-up (SIGHUP) during a run: the program stops at the
# next step, says so, exits 130, and the HDF5 file is valid and holds the samples computed so
# far plus a summary with status interrupted (also the root status attribute).
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}
for sig in INT TERM HUP; do
    rm -f "$T/int.h5"   # a new file each time (an earlier one would be kept, issue 47)
    "$BIN" run scenarios/default.dat --set model.duration=600 -o "$T/int.h5" > "$T/int.out" 2> "$T/int.err" &
    pid=$!
    sleep 1.5
    kill -"$sig" "$pid"
    rc=0; wait "$pid" || rc=$?
    [ "$rc" -eq 130 ] || { echo "SIG$sig: exit $rc, expected 130"; cat "$T/int.err"; exit 1; }
    grep -q "interrupted at t =" "$T/int.err"
    /usr/bin/python3 - "$T/int.h5" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
n = f["time"].shape[0]
assert n > 10, n
names = {v: k for k, v in h5py.check_enum_dtype(f["summary"].attrs.get_id("status").dtype).items()}
assert names[int(f["summary"].attrs["status"])] == "interrupted"
assert f.attrs["status"] == "interrupted"
assert abs(f["summary"].attrs["end_time"] - f["time"][-1]) < 0.01
PY
done
