#!/usr/bin/env bash
# Errors that say what to do (issue 47):
#   1. a run shorter than one time step is refused (exit 2, one line), where a 1e-6 s run of a
#      seated cask reported that it fell freely;
#   2. a sweep table or a run file held open for writing by another program (HDF5's file lock)
#      is refused naming the lock and what to do, where the messages read "Resource temporarily
#      unavailable" and "HDF5 library error";
#   3. a scenario given to the library with its length (rd_scenario_parse_n, tests/test_scenario.c)
#      refuses a NUL byte; a file with one is refused by `check` with one line.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/locks_short; rm -rf "$T"; mkdir -p "$T"
one() {   # one NAME EXPECTED-RC REGEX FILE: a one-line error
    [ "$2" -eq "$5" ] && [ "$(wc -l < "$4")" -eq 1 ] && grep -q "$3" "$4" || { echo "FAIL $1: exit $5"; cat "$4"; exit 1; }
    echo "CHECK $1"
}
rc=0; "$BIN" run scenarios/default.dat --set model.duration=1e-6 -o "$T/short.h5" > /dev/null 2> "$T/short.err" || rc=$?
one "a run shorter than one step is refused" 2 "the run of 1e-06 s is shorter than one time step" "$T/short.err" "$rc"
[ ! -e "$T/short.h5" ]

"$BIN" sweep tests/cli/data/sweep_brick.dat --set model.duration=0.05 --set model.settle=off --scales 0.01g,0.02g -q -o "$T/t.h5"
"$BIN" run scenarios/default.dat -q --set model.duration=0.1 -o "$T/r.h5" > /dev/null
/usr/bin/python3 - "$BIN" "$T" <<'PY'
import h5py, subprocess, sys
b, t = sys.argv[1:]
held = [h5py.File(t + "/t.h5", "r+"), h5py.File(t + "/r.h5", "r+")]   # the file locks
cmds = {"sweep": [b, "sweep", "tests/cli/data/sweep_brick.dat", "--set", "model.duration=0.05", "--set",
                  "model.settle=off", "--scales", "0.01g,0.02g,0.03g", "-q", "-o", t + "/t.h5"],
        "run": [b, "run", "scenarios/default.dat", "-q", "--set", "model.duration=0.1", "-o", t + "/r.h5"]}
for k, c in cmds.items():
    r = subprocess.run(c, capture_output=True, text=True)
    lines = r.stderr.splitlines()
    assert r.returncode == 2 and len(lines) == 1 and "open for writing in another program (HDF5's file lock" in lines[0], (k, r.returncode, r.stderr)
    print("CHECK a %s onto a file locked by another program says so and what to do" % k)
PY

printf 'block create brick size 1 1 1 position 0 0 0.5 name a\0\n' > "$T/nul.dat"
rc=0; "$BIN" check "$T/nul.dat" > /dev/null 2> "$T/nul.err" || rc=$?
one "a scenario file with a NUL byte is refused" 2 "contains a NUL byte" "$T/nul.err" "$rc"
