#!/usr/bin/env bash
# Faults outside the sample flushes (tests/cli/faults_output.sh has those) leave a file that
# h5dump and h5py open, and one line naming the file:
# 1. A fault while the end-of-run tables are written (/history, /joints, /outcomes: after the
# last sample's flush): the file holds every sample of the run and the root status "io_error"
# with the reason, and the run stops with exit 3.
# The default scene with 6 s of histories every 0.1 ms (60 001 rows of 20 doubles: 9.6 MB)
# under a file-size limit of 2 MB, over the 0.27 MB of its samples: HDF5 wrote the history past
# the limit; the file's superblock then gave an end of file beyond the file's ("truncated
# file"), so no reader opened it and the whole run was lost, its status had read "done", and
# stderr held HDF5's error stack (16 lines). The tables' space is now reserved first
# (output_scene.c), as before every batch of samples.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/faults_tables; rm -rf "$T"; mkdir -p "$T"
cp scenarios/default.dat "$T/hist.dat"
printf '%s\n' "history interval 1e-4" "history energy" "history body 'cask' all" >> "$T/hist.dat"
"$BIN" run scenarios/default.dat -q -o "$T/whole.h5" > /dev/null
rc=0; (ulimit -f 2000; exec "$BIN" run "$T/hist.dat" -q -o "$T/fsize.h5") > /dev/null 2> "$T/fsize.err" || rc=$?
echo "exit $rc; stderr: $(head -c 300 "$T/fsize.err")"
[ "$rc" -eq 3 ] || { echo "FAIL faults-tables: exit $rc, expected 3"; exit 1; }
[ "$(wc -l < "$T/fsize.err")" -eq 1 ] || { echo "FAIL faults-tables: expected one line on stderr"; exit 1; }
grep -q "$T/fsize.h5: .*: File too large" "$T/fsize.err" || { echo "FAIL faults-tables: reason"; exit 1; }
h5dump -A "$T/fsize.h5" > /dev/null 2>&1 || { echo "FAIL faults-tables: h5dump cannot read the file"; exit 1; }
/usr/bin/python3 - "$T/fsize.h5" "$T/whole.h5" <<'PY'
import sys, h5py, numpy as np
try:
    f = h5py.File(sys.argv[1], "r")
except OSError as e:
    sys.exit("FAIL faults-tables: h5py cannot open the file: %s" % e)
w = h5py.File(sys.argv[2], "r")
st, msg = f.attrs["status"], f.attrs["status_message"]
print("status %s: %s; %d samples (the whole run: %d)" % (st, msg, f["time"].shape[0], w["time"].shape[0]))
assert st == "io_error" and sys.argv[1] in msg and "File too large" in msg, (st, msg)
for k in ("time", "position", "quaternion", "energy/kinetic"):   # every sample, bit for bit
    assert np.array_equal(f[k][()], w[k][()]), k
PY

# 2. A size limit below what opening the file writes (the bodies' groups): a 31-body drum column
# under 160 KB. The space reserved at opening counted the free bodies' vertex tables alone (98
# KB with its fixed 64 KiB), short of the 171 KB written: HDF5 wrote past the limit, and the
# file's root group could not be read ("addr overflow"; h5dump -A failed). Now every body's group is reserved: the run is
# refused before any HDF5 write (exit 2, nothing computed), the file an empty, readable one.
cat > "$T/column.dat" <<'EOS'
block create brick size 3 3 0.5 position 0 0 -0.25 fixed name stylobate
block create column drums 30 diameter 0.8 height 0.5 sides 12 seat-on stylobate name col
model solve time 1
EOS
rc=0; (ulimit -f 160; exec "$BIN" run "$T/column.dat" -q -o "$T/open.h5") > /dev/null 2> "$T/open.err" || rc=$?
echo "opening under 160 KB: exit $rc; stderr: $(head -c 300 "$T/open.err")"
[ "$rc" -eq 2 ] && [ "$(wc -l < "$T/open.err")" -eq 1 ] && grep -q "$T/open.h5: .*File too large" "$T/open.err" ||
    { echo "FAIL faults-tables (opening): exit $rc, stderr as above"; exit 1; }
h5dump -A "$T/open.h5" > /dev/null 2>&1 || { echo "FAIL faults-tables (opening): h5dump cannot read the file"; exit 1; }
/usr/bin/python3 -c "import h5py, sys; dict(h5py.File(sys.argv[1], 'r').attrs)" "$T/open.h5" ||
    { echo "FAIL faults-tables (opening): h5py cannot read the file"; exit 1; }
