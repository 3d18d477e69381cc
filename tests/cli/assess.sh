#!/usr/bin/env bash
# rockdem assess end to end (issue 43, docs/ASSESS.md): the shipped cask (scenarios/cask.dat)
# under an EN 1998 type 1 ground A spectrum at a_g = 0.6 g with five matched records through the
# DEM, then the report tool; and bad input, each refused with one line and exit status 2.
# Checks: seed 001 Table 2's EN static allowable PGA against rocking, g b / (h + 0.3 (2/3) b)
# = 9.81 / 2.2 m/s^2 for the cask (b = 1, h = 2 m), to round-off; the seed's ratio 4.1 of the
# ASCE 43-05 allowable PGA to it (half a unit of its last digit, 0.05); every record's spectrum
# within the stated band 0.9-1.3; the JSON's DEM peaks equal to the runs' own HDF5 summaries;
# the report with its four figures at 300 dpi.
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}
T=${RD_TMP:-$(mktemp -d)}/assess
PY=/usr/bin/python3
fail=0

out=$("$BIN" assess scenarios/cask.dat --ag 0.6g --out "$T" -q 2>"$T.err")
rc=$?
[ $rc -eq 0 ] || { echo "FAIL assess exit $rc: $(cat "$T.err")"; exit 1; }
echo "$out" | grep -E "EN 1990|A\.2|A\.1|mean peak" | sed 's/^/  /'
$PY - "$T" <<'PYEOF' || fail=1
import json, sys, h5py
d = sys.argv[1]
a = json.load(open(d + "/assess.json"))
bad = 0
def check(what, got, want, tol):
    global bad
    e = abs(got - want) / abs(want) if tol < 1e-6 else abs(got - want)
    print("CHECK %s: rockdem %.6g, reference %.6g, error %.3g, tol %.3g" % (what, got, want, e, tol))
    if e > tol:
        print("FAIL %s: gap=%.4g tol=%.4g" % (what, e, tol)); bad = 1
en = [c for c in a["static"] if c["code"].startswith("EN")][0]
check("EN static allowable PGA (Table 2: g / 2.2)", en["pga_rock"], 9.81 / 2.2, 1e-9)
check("seed 001: ASCE 43-05 / EN static allowable PGA (4.1)", a["rocking"]["pga_allow"] / en["pga_rock"], 4.1, 0.05)
ev = a["evidence"]
if ev["n"] != 5 or not all(r["in_band"] for r in ev["records"]):
    print("FAIL records: %d, in band %s" % (ev["n"], [r["in_band"] for r in ev["records"]])); bad = 1
for k, r in enumerate(ev["records"]):
    with h5py.File("%s/%s" % (d, r["run"]), "r") as f:
        s = f["summary"].attrs
        tilt, slide = float(s["max_tilt"][0]), float(s["max_slide"][0])
    # the JSON holds 10 significant digits
    if abs(tilt - r["tilt"]) > 1e-9 * tilt or abs(slide - r["slide"]) > 1e-9 * slide:
        print("FAIL record %d: JSON tilt %g slide %g, run %g %g" % (k + 1, r["tilt"], r["slide"], tilt, slide)); bad = 1
    # the run was shaken by the record, not by the scene's pulse (0.6 g one-sine): its ground
    # PGA is the record's (1 %: the digits an engineer reads; the pulse would be 10-20 % off)
    with h5py.File("%s/%s" % (d, r["run"]), "r") as f:
        pga = float(abs(f["ground/acceleration"][:, 0]).max())
    check("record %d applied (ground PGA)" % (k + 1), pga, r["pga"], 0.01)
sys.exit(bad)
PYEOF
$PY tools/rdassess.py "$T" >/dev/null 2>"$T.err" || { echo "FAIL rdassess: $(cat "$T.err")"; fail=1; }
for f in report.md fig_spectrum.png fig_records.png fig_histories.png fig_margins.png; do
    [ -s "$T/$f" ] || { echo "FAIL no $f"; fail=1; }
done
$PY -c "
import sys
from PIL import Image
for f in sys.argv[1:]:
    d = Image.open(f).info.get('dpi', (0, 0))
    if round(d[0]) != 300: print('FAIL %s at %s dpi' % (f, d)); sys.exit(1)
print('CHECK figures at 300 dpi')" "$T"/fig_*.png || fail=1

# a spectrum table sampled from the same EN spectrum every 0.005 s to 4 s (beyond, both fall as
# 1/T^2): the same static checks to round-off, and A.2's angle to 1e-4: at its period, 0.5 s,
# the table's linear interpolation of c / T errs by at most h^2 / (4 T^2) = 2.5e-5, and the
# angle goes as Sa^2 there (phi = m h Sa / K_t with Sa ~ f ~ sqrt(K_t) and K_t ~ 2 m g b / phi),
# so 5e-5
$PY -c "
for i in range(801):
    T = 0.005 * i
    ag = 0.6
    sa = ag * (1 + T / 0.15 * 1.5) if T <= 0.15 else 2.5 * ag if T <= 0.4 else 2.5 * ag * 0.4 / T if T <= 2 else 2.5 * ag * 0.8 / T**2
    print('%.4f %.9f' % (T, sa))" > "$T/en_table.txt"
"$BIN" assess scenarios/cask.dat --spectrum "$T/en_table.txt" --records 0 --out "$T/table" -q >/dev/null 2>"$T.err" ||
    { echo "FAIL table spectrum: $(cat "$T.err")"; fail=1; }
$PY -c "
import json, sys
a = json.load(open(sys.argv[1] + '/assess.json')); b = json.load(open(sys.argv[1] + '/table/assess.json'))
e1 = abs(a['static'][1]['rock_margin'] / b['static'][1]['rock_margin'] - 1)
e2 = abs(a['rocking']['phi'] / b['rocking']['phi'] - 1)
print('CHECK table spectrum: EN static margin error %.3g tol 1e-9; A.2 phi %.6g vs %.6g error %.3g tol 1e-4'
      % (e1, b['rocking']['phi'], a['rocking']['phi'], e2))
sys.exit(0 if e1 <= 1e-9 and e2 <= 1e-4 else 1)" "$T" || { echo "FAIL table spectrum differs from EN"; fail=1; }

# the Python call runs the same program (this test's, also under `make asan`): the same numbers
ROCKDEM_BIN=$(cd "$(dirname "$BIN")" && pwd)/$(basename "$BIN") PYTHONPATH=tools $PY -c "
import json, sys, rockdem
a = rockdem.assess('scenarios/cask.dat', sys.argv[1] + '_py', ag='0.6g', records=0, report=False)
b = json.load(open(sys.argv[1] + '/assess.json'))
ok = a['rocking'] == b['rocking'] and a['static'] == b['static'] and a['sliding'] == b['sliding']
print('CHECK Python rockdem.assess: the same checks as the program' if ok else 'FAIL Python rockdem.assess differs')
sys.exit(0 if ok else 1)" "$T" || fail=1

# bad input: one line on stderr, nothing on stdout, exit 2
printf '0 0.3\n0.5 x\n' > "$T/bad_table.txt"
bad() {
    local what=$1; shift
    local o e rc
    o=$("$BIN" assess "$@" --records 0 --out "$T/bad" 2>"$T.err"); rc=$?
    e=$(cat "$T.err")
    if [ $rc -ne 2 ] || [ -n "$o" ] || [ "$(wc -l < "$T.err")" -ne 1 ]; then
        echo "FAIL bad input ($what): exit $rc, stdout '$o', stderr '$e'"; fail=1
    else echo "CHECK bad input ($what): $e"; fi
}
bad "spectrum type 3" scenarios/cask.dat --spectrum en1998-3A --ag 0.3g
bad "ground type F" scenarios/cask.dat --spectrum en1998-1F --ag 0.3g
bad "no a_g" scenarios/cask.dat
bad "3 records" scenarios/cask.dat --ag 0.3g --records 3
bad "table line" scenarios/cask.dat --spectrum "$T/bad_table.txt"
bad "missing table" scenarios/cask.dat --spectrum "$T/none.txt"
bad "two free bodies" scenarios/seed001_cask.dat --ag 0.3g
bad "no such body" scenarios/cask.dat --ag 0.3g --body nosuch
bad "negative mu" scenarios/cask.dat --ag 0.3g --mu -1
bad "bad code" scenarios/cask.dat --ag 0.3g --code asce8
exit $fail
