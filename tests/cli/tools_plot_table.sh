#!/usr/bin/env bash
# rdplot and rdtable on a real run: the PNG is written, its energies are the energy terms, the
# table's values equal the /summary attributes, pga/pgv equal the applied pulse; bad inputs
# (missing file, not HDF5, not a rockdem file, missing dataset) give one line and exit 2.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/tools_pt; mkdir -p "$T"
PY=/usr/bin/python3
"$BIN" run scenarios/default.dat --set model.duration=1.5 -q -o "$T/run.h5" >/dev/null
$PY tools/rdplot.py "$T/run.h5" -o "$T/run.png" >/dev/null
$PY tools/rdtable.py "$T/run.h5" "$T/run.h5" --csv "$T/t.csv" > "$T/t.txt" 2>/dev/null
grep -q '^file  *body  *overturned' "$T/t.txt"
$PY - "$T/run.h5" "$T/run.png" "$T/t.csv" <<'PY'
import sys, csv, h5py, numpy as np
run, png, tab = sys.argv[1:]
b = open(png, "rb").read()
assert b[:8] == b"\x89PNG\r\n\x1a\n" and len(b) > 20000, len(b)
rows = list(csv.DictReader(open(tab)))
assert len(rows) == 2 and rows[0]["body"] == "cask", rows
f = h5py.File(run, "r"); s = f["summary"].attrs
r = rows[0]
for k in ["max_tilt", "max_tilt_ratio", "max_slide", "final_slide"]:
    assert abs(float(r[k]) - s[k][0]) <= 1e-5 * abs(s[k][0]), (k, r[k], s[k])
assert int(r["overturned"]) == s["overturned"][0]
assert r["status"] == "done" and abs(float(r["dt"]) - s["dt"]) < 1e-5 * s["dt"]
assert r["title"].startswith("seed 001 cask")
# 0.6 g one-sine at 1 Hz: PGA = 0.6 g, PGV = A / (pi f), PGV/PGA = 1/pi s
A = 0.6 * 9.80665
assert abs(float(r["pga"]) - A) < 0.01 * A, r["pga"]
assert abs(float(r["pgv"]) - A / np.pi) < 0.01 * A / np.pi, r["pgv"]
assert r["im_source"] == "computed"
# rdplot's energy panel: the energy terms, not the /time scale linked into /energy for xarray
sys.path.insert(0, "tools")
from rdtools.runfile import Run
with Run(run) as rr:
    en = list(rr.energies())
assert en == ["kinetic", "gravitational", "elastic", "friction", "damping", "ground_work",
              "residual"], en
print("table ok")
PY
# a record run: pga/pgv come from the /ground attributes of the whole record (h1_pga, h1_pgv)
$PY -c "
import numpy as np
t = np.arange(0, 2, 0.005)
np.savetxt('$T/rec.csv', np.column_stack([t, 0.3 * np.sin(2 * np.pi * 2 * t) * np.exp(-t)]), delimiter=',')"
cat > "$T/rec.dat" <<'DAT'
block create brick size 1 1 0.3 position 0 0 -0.15 fixed name pedestal
block create brick size 0.4 0.4 1.0 position 0 0 0.5 name rock
ground-motion import 'rec.csv' direction 30
model solve time 0.5
output hdf5 'r.h5' interval 0.01
DAT
(cd "$T" && "$BIN" run rec.dat -q -o rec.h5 >/dev/null)
$PY tools/rdtable.py "$T/rec.h5" --csv "$T/rec_t.csv" -q 2>/dev/null
$PY - "$T/rec.h5" "$T/rec_t.csv" <<'PY'
import sys, csv, h5py
g = h5py.File(sys.argv[1], "r")["ground"].attrs
r = list(csv.DictReader(open(sys.argv[2])))[0]
assert r["im_source"] == "attrs:h1", r["im_source"]
assert abs(float(r["pga"]) - g["h1_pga"]) < 1e-5 * g["h1_pga"] and abs(float(r["pgv"]) - g["h1_pgv"]) < 1e-5 * g["h1_pgv"]
assert r["h1_record"] == "rec.csv" and abs(float(r["h1_arias"]) - g["h1_arias"]) < 1e-5 * g["h1_arias"]
print("record table ok")
PY
# a copy without /tilt, a non-rockdem HDF5 file, a text file
$PY - "$T" <<'PY'
import sys, h5py, shutil
T = sys.argv[1]
shutil.copy(T + "/run.h5", T + "/notilt.h5")
with h5py.File(T + "/notilt.h5", "a") as f:
    del f["tilt"]
with h5py.File(T + "/other.h5", "w") as f:
    f["x"] = [1, 2, 3]
PY
echo "hello" > "$T/text.h5"
fails=0
expect() { # expect WANTED-SUBSTRING command...
    local want=$1; shift
    local out rc
    out=$("$@" 2>&1 >/dev/null); rc=$?
    if [ "$rc" -ne 2 ] || ! printf '%s' "$out" | grep -qF -- "$want" || [ "$(printf '%s\n' "$out" | wc -l)" -ne 1 ]; then
        echo "FAIL: $*: rc=$rc, stderr: $out (wanted: $want)"; fails=$((fails + 1))
    fi
}
set +e
for tool in rdplot rdtable rdxdmf; do
    expect "no such file" $PY tools/$tool.py "$T/missing.h5"
    expect "not an HDF5 file" $PY tools/$tool.py "$T/text.h5"
    expect "not a rockdem run file" $PY tools/$tool.py "$T/other.h5"
done
expect "missing dataset /tilt" $PY tools/rdplot.py "$T/notilt.h5" -o "$T/x.png"
expect "required" $PY tools/rdplot.py
expect "output folder does not exist" $PY tools/rdplot.py "$T/run.h5" -o "$T/no/dir/x.png"
for tool in rdplot rdtable rdxdmf rdfragility; do
    $PY tools/$tool.py --help | grep -q "^usage: $tool" || { echo "FAIL: $tool --help"; fails=$((fails + 1)); }
done
[ "$fails" -eq 0 ]
