#!/usr/bin/env bash
# rdfragility planes / select / calibrate (docs/FRAGILITY.md): Firth's estimate equals its known
# closed form on a separated 2x2 table; runs scaled to one level are one group whatever the
# rounding of their PGA (the sweep's own scale index); the cells count exactly; the surface and
# the per-direction capacities recover known values within 4 standard errors; the normalised
# axes give a brick Housner's closed-form alpha and p; the sweep's response modes; the record
# selection from the made-up flatfile; a calibration recovers hidden contact settings within
# its stated uncertainty; the figures are 300 dpi PNG and vector PDF.
set -eu
T=${RD_TMP:-$(mktemp -d)}/frag_planes; mkdir -p "$T"
PY=/usr/bin/python3
RD=${RD_BIN:-bin/rockdem}
BRICK=tests/cli/data/sweep_brick.dat
FLAT=tests/data/flatfile

# -- the sweep: brick, 2 directions x 4 levels, and the mode of each case ---------------------
"$RD" sweep "$BRICK" --scales 0.05g,0.45g,0.6g,1.0g --directions 0,45 --set contact.friction=60 \
    -j 2 -q -o "$T/b.h5"
"$RD" sweep "$BRICK" --scales 0.3g --set contact.friction=10 -j 1 -q -o "$T/slide.h5"
"$RD" run "$BRICK" --set model.duration=0.05 --set output.file="$T/brick_run.h5" -q > /dev/null

$PY - "$T" <<'PY'
import sys, math, os
import numpy as np
import h5py
from scipy import special
sys.path.insert(0, "tools")
from rdtools import fragility as F, planes as P
T = sys.argv[1]
rng = np.random.default_rng(41)

# 1. Firth on a separated 2x2 table = the log odds ratio with 1/2 added to every cell (Firth
#    1993; the Haldane-Anscombe correction): x=0: 2 of 7 overturned, x=1: 5 of 5.
x = np.r_[np.zeros(7), np.ones(5)]
y = np.r_[np.ones(2), np.zeros(5), np.ones(5)]
f = F.logistic_fit(np.column_stack([np.ones(12), x]), y)
assert f["method"] == "firth" and f["separated"], f
want = [math.log(2.5 / 5.5), math.log((5.5 / 0.5) / (2.5 / 5.5))]
assert np.allclose(f["beta"], want, rtol=0, atol=1e-7), (f["beta"], want)

# 2. the scale index: 6 runs of one level whose PGA differ in the last bit are one group
pga = np.array([1.9613299999999998, 1.96133, 1.96133, 1.9613299999999998, 1.96133, 1.96133,
                3.9, 3.9, 3.9, 3.9, 3.9, 3.9])
with h5py.File(T + "/round.h5", "w") as h:
    h.attrs["axes"] = "scale=0.2g,0.4g\nrecord=a,b,c,d,e,f\n"
    s = h.create_group("sweep")
    s["case"] = np.arange(12)
    s["scale"] = np.repeat([1.96133, 3.9], 6)
    s["pga"], s["pgv"] = pga, pga * 0.1
    s["overturned"] = np.r_[[0, 1, 0, 1, 0, 1], [1] * 6]
t = P.table([T + "/round.h5"])
assert list(t["level"]) == [0] * 6 + [1] * 6, t["level"]
c = P.binned(t, "pga", "pgv", ny=1)
assert c["x_by_level"] and list(c["n"][:, 0]) == [6, 6] and list(c["k"][:, 0]) == [3, 6], c
# the index comes from the case number (case // 6 here), not from the values
assert list(P.scale_index(np.arange(12), "scale=0.2g,0.4g\nrecord=a,b,c,d,e,f\n")) == [0] * 6 + [1] * 6
lo, hi = P.interval(3, 6)
from statsmodels.stats.proportion import proportion_confint
assert (lo, hi) == proportion_confint(3, 6, alpha=0.05, method="wilson")

# 3. cells: exact counts on a made-up table (x binned in 2 log bins, y in 2)
tt = dict(pga=np.array([1., 1, 1, 10, 10, 10, 10, 1]), pgd=np.array([1., 5, 5, 1, 1, 5, 5, 1]),
          overturned=np.array([0., 1, 1, 0, 1, 1, 1, 1]), level=np.zeros(8, int))
c = P.binned(tt, "pgd", "pga", nx=2, ny=2)
assert c["n"].tolist() == [[2, 2], [2, 2]] and c["k"].tolist() == [[1, 1], [2, 2]], c

# 4. the surface over (PGA, PGD) and the median-capacity curve recover known coefficients
n = 3000
tb = dict(pga=np.exp(rng.uniform(np.log(1), np.log(10), n)), pgd=np.exp(rng.uniform(np.log(0.01), np.log(0.3), n)))
ct = np.array([2.0, 1.8, 1.2])
tb["overturned"] = (rng.random(n) < special.expit(ct[0] + ct[1] * np.log(tb["pga"]) + ct[2] * np.log(tb["pgd"]))).astype(float)
fit, why = P.surface(tb, "pga", "pgd")
assert fit is not None and np.all(np.abs(fit["beta"] - ct) < 4 * fit["se"]), (fit["beta"], fit["se"])
yv = np.array([0.02, 0.1])
assert np.allclose(P.surface_prob(fit, P.median_curve(fit, yv), yv), 0.5, atol=1e-12)

# 5. rose: median capacities 3 and 6 m/s^2 in two directions recovered within 4 s.e.
d = np.repeat([0.0, 90.0], 1500)
med = np.where(d == 0, 3.0, 6.0)
pg = np.exp(rng.uniform(np.log(0.5), np.log(30), len(d)))
o = (rng.random(len(d)) < special.ndtr(np.log(pg / med) / 0.5)).astype(float)
r = P.rose(dict(pga=pg, direction=d, overturned=o))
for k, m in ((0.0, 3.0), (90.0, 6.0)):
    assert abs(math.log(r[k]["median"] / m)) < 4 * r[k]["se_ln"], (k, r[k])

# 6. the normalised axes on the brick: alpha = atan(b/h), p = sqrt(3 g / (4 R)) (Housner, a
#    rectangular block, R = sqrt(b^2 + h^2)); the seated pose differs from the placed one by
#    the bed's elastic sinkage, ~1e-5 m here, so 1e-4 relative
g = P.geometry(T + "/brick_run.h5")
b_, h_ = 0.2, 0.5
a0 = math.atan(b_ / h_)
R0 = math.hypot(b_, h_)
p0 = math.sqrt(3 * g["g"] / (4 * R0))
al, pp = P.along(g, np.array([0.0, 90.0]))
assert np.allclose(al, a0, rtol=1e-4) and np.allclose(pp, p0, rtol=1e-4), (al, a0, pp, p0)
tn = P.normalised(dict(pga=np.array([g["g"] * 0.4]), pgv=np.array([0.1]), direction=np.array([0.0])), g)
assert abs(tn["pga_n"][0] - 1.0) < 1e-3 and abs(tn["pgvpga_n"][0] - p0 * 0.1 / (g["g"] * 0.4)) < 1e-4 * p0

# 7. modes from the sweep: brick, friction 60: 0.05 g rest, 0.45 g rock(-slide), 1 g overturn;
#    (along x); friction 10 at 0.3 g (mu g = 0.18 g < 0.3 g < g tan alpha = 0.4 g): slide
with h5py.File(T + "/b.h5") as h:
    s = h["sweep"]
    mode = [m.decode() for m in s["mode"][()]]
    sc = s["scale"][()] / 9.80665
    dr = s["direction"][()]
    bm = s["body_mode"][()][:, 0]
    for k, v in enumerate(sc):
        if abs(v - 0.05) < 1e-9:
            assert mode[k] == "rest", (v, mode[k])
        if abs(v - 1.0) < 1e-9 and dr[k] == 0:   # along a face; the diagonal (45) is stabler
            assert mode[k] == "overturn", (v, mode[k])
    assert any(mode[k] in ("rock", "rock-slide") for k, v in enumerate(sc) if abs(v - 0.6) < 1e-9), mode
    assert [P.MODES[i] for i in bm] == mode
    for col in ("sa_0_2", "sa_1", "max_twist", "max_slip"):
        assert np.all(np.isfinite(s[col][()])), col
with h5py.File(T + "/slide.h5") as h:
    s = h["sweep"]
    assert s["mode"][0].decode() == "slide" and s["max_slip"][0] > 1e-3, (s["mode"][0], s["max_slip"][0])
# Sa(0.2 s) and Sa(1 s) of the 0.45 g, 2 Hz one-sine pulse, computed independently
# with scipy's lsim of the 5 %-damped oscillator on the same pulse (1 part in 1e3: the sweep's
# 4000 samples of the pulse)
from scipy import signal
A = 0.45 * 9.80665
tt_ = np.linspace(0, 2.5, 25001)
ag = np.where(tt_ <= 0.5, A * np.sin(2 * np.pi * 2 * tt_), 0.0)
for Tn, col in ((0.2, "sa_0_2"), (1.0, "sa_1")):
    w = 2 * np.pi / Tn
    sys_ = signal.lti([-1.0], [1.0, 2 * 0.05 * w, w * w])
    _, u, _ = signal.lsim(sys_, ag, tt_)
    with h5py.File(T + "/b.h5") as h:
        s = h["sweep"]
        k = int(np.flatnonzero(np.abs(s["scale"][()] / 9.80665 - 0.45) < 1e-9)[0])
        got = s[col][k]
    assert abs(got - w * w * np.abs(u).max()) < 1e-3 * got, (col, got, w * w * np.abs(u).max())
print("planes module ok")
PY

# issue 40 item 6: rdfragility's fraction per PGA level reads 3 of 6 and 6 of 6, not 1-of-2 splits
$PY tools/rdfragility.py "$T/round.h5" --json "$T/round.json" -o "$T/round.png" > /dev/null
$PY -c "
import json; L = json.load(open('$T/round.json'))['levels']
assert [(d['n'], d['k']) for d in L] == [(6, 3), (6, 6)], L"

# -- the command: figures (300 dpi PNG, PDF) and JSON -----------------------------------------
$PY tools/rdfragility.py planes "$T/b.h5" --pairs pga:pgv,pga:sa_1 --geometry "$T/brick_run.h5" \
    -o "$T/fig" --json "$T/planes.json" > "$T/planes.txt"
grep -q "median PGA capacity per direction" "$T/planes.txt"
grep -q "response modes per PGA level" "$T/planes.txt"
$PY - "$T" <<'PY'
import sys, json
T = sys.argv[1]
from PIL import Image
for f in ("fig_pga_pgv", "fig_pga_sa_1", "fig_rose", "fig_modes"):
    im = Image.open("%s/%s.png" % (T, f))
    dpi = im.info.get("dpi", (0, 0))
    assert abs(dpi[0] - 300) < 1, (f, dpi)
    assert open("%s/%s.pdf" % (T, f), "rb").read(5) == b"%PDF-", f
r = json.load(open(T + "/planes.json"))
assert r["n"] == 8 and set(r["planes"]) == {"pga:pgv", "pga:sa_1"}
assert set(r["rose"]) == {"0.0", "45.0"}
sys.path.insert(0, "tools")
from rdtools import planes as P  # the one Python call gives what the command wrote
res = P.fragility([T + "/b.h5"], pairs=[("pga", "pgv")], geometry_run=T + "/brick_run.h5",
                  output=T + "/api")
assert {k: v["median"] for k, v in res["rose"].items() if v and "median" in v} == \
       {float(k): v["median"] for k, v in r["rose"].items() if v and "median" in v}
assert len(res["files"]) == 6
print("planes command ok")
PY

# -- record selection from the made-up flatfile -----------------------------------------------
$PY tools/rdfragility.py select "$FLAT/flatfile.csv" --magnitude 6:7 --rrup :25 -n 3 --seed 2 \
    --scenario "$BRICK" -o "$T/sel" > "$T/sel.txt"
$PY - "$T" "$FLAT" <<'PY'
import sys, csv
import numpy as np, h5py
T, FLAT = sys.argv[1:]
rows = list(csv.DictReader(open(FLAT + "/flatfile.csv")))
keep = [r for r in rows if 6 <= float(r["Earthquake Magnitude"]) <= 7 and float(r["ClstD (km)"]) <= 25]
ids = {r["Record Sequence Number"] for r in keep}
got = [l.split(",")[0] for l in open(T + "/sel.csv").read().splitlines()[1:]]
assert len(got) == 3 and set(got) <= ids, (got, ids)
assert open(T + "/sel.txt").readline().startswith("%d of %d records pass" % (len(keep), len(rows)))
with h5py.File(T + "/sel.h5") as h:
    for rid in got:
        r = [x for x in rows if x["Record Sequence Number"] == rid][0]
        for comp, col in (("a", "File Name (Horizontal 1)"), ("b", "File Name (Horizontal 2)")):
            vals = np.array([float(v) for ln in open(FLAT + "/" + r[col]).read().splitlines()[4:] for v in ln.split()])
            assert np.array_equal(h["_timeseries/%s/%s/RecordedAcceleration" % (rid, comp)][()], vals)
        assert ("v" in h["_timeseries/" + rid]) == bool(r["File Name (Vertical)"])
print("select ok")
PY
# rockdem reads the set: h1 of the first drawn record has the AT2's peak (in g; no baseline
# correction, which moves it by ~1e-5 g)
first=$(sed -n 2p "$T/sel.csv" | cut -d, -f1)
"$RD" check "$T/sel.dat" --set motion.baseline=off > "$T/check.txt" 2>&1
peak=$($PY -c "
import numpy as np; import sys
v=[float(x) for l in open('$FLAT/RSN${first}_H1.AT2').read().splitlines()[4:] for x in l.split()]
print('%.6g' % np.abs(v).max())")
grep -q "FEMA P695 ${first}a; PGA ${peak} g" "$T/check.txt" || { echo "FAIL: rockdem check of the set: wanted PGA $peak g"; cat "$T/check.txt"; exit 1; }
# a vertical is required: only records with one are drawn, and the scenario applies it
$PY tools/rdfragility.py select "$FLAT/flatfile.csv" --vertical require -o "$T/selv" --scenario "$BRICK" > /dev/null
grep -q "component v" "$T/selv.dat"
"$RD" check "$T/selv.dat" 2>&1 | grep -q "motion vertical: FEMA P695"

# -- calibration: hidden friction 35 deg, restitution 0.25, off the grid ------------------------
"$RD" sweep "$BRICK" --scales 0.6g,0.65g,0.7g,0.75g,0.8g,0.9g --directions 0 \
    --set contact.friction=35 --set contact.restitution=0.25 -j 2 -q -o "$T/hidden.h5"
$PY - "$T" > "$T/obs.csv" <<'PY'
import sys, h5py
s = h5py.File(sys.argv[1] + "/hidden.h5")["sweep"]
sc = ["0.6g", "0.65g", "0.7g", "0.75g", "0.8g", "0.9g"]
print("scale,direction,overturned")
for i, v in enumerate(s["overturned"][()]):
    print("%s,0,%s" % (sc[i], "yes" if v else "no"))
PY
$PY tools/rdfragility.py calibrate "$BRICK" --observed "$T/obs.csv" -j 2 \
    --param contact.friction=20,25,30,40 --param contact.restitution=0,0.5,1 -o "$T/cal" > "$T/cal.txt"
$PY - "$T" <<'PY'
import sys, json
r = json.load(open(sys.argv[1] + "/cal.json"))
fr, re_ = r["brackets"]["contact.friction"], r["brackets"]["contact.restitution"]
assert fr[0] < 35 < fr[1] or fr[0] <= 35 <= fr[1], fr
assert re_[0] <= 0.25 <= re_[1], re_
best = dict(zip(r["keys"], r["grid"][r["best"]]))
assert r["mismatches"][r["best"]] == 0, r["mismatches"]
# the data exclude what they should: friction 20 (the brick slides instead of rocking) and
# restitution 1 (no overturning at these levels) are outside the 95 % set
assert all(not (g[0] == "20" or g[1] == "1") for i, g in enumerate(r["grid"]) if i in r["conf_set"]), r["conf_set"]
print("calibration ok: best", best, "friction in", fr, "restitution in", re_)
PY

# -- bad input: one line, exit 2 ------------------------------------------------------------
fails=0
expect() {
    local want=$1; shift
    local out rc
    out=$("$@" 2>&1 >/dev/null); rc=$?
    if [ "$rc" -ne 2 ] || ! printf '%s' "$out" | grep -qF -- "$want" || [ "$(printf '%s\n' "$out" | wc -l)" -ne 1 ]; then
        echo "FAIL: $*: rc=$rc, stderr: $out (wanted: $want)"; fails=$((fails + 1))
    fi
}
set +e
expect "unknown intensity measure 'pgx'" $PY tools/rdfragility.py planes "$T/b.h5" --pairs pga:pgx
expect "give --geometry" $PY tools/rdfragility.py planes "$T/b.h5" --pairs pga_n:pgvpga_n
printf 'RSN,M,Rrup\n1,6,10\n' > "$T/bad_flat.csv"
expect "no Vs30 column" $PY tools/rdfragility.py select "$T/bad_flat.csv" -o "$T/x"
expect "only 7 pass the filters" $PY tools/rdfragility.py select "$FLAT/flatfile.csv" --vs30 :700 -n 9 -o "$T/x"
sed 's/UNITS OF G/VELOCITY TIME SERIES IN UNITS OF CM\/SEC/' "$FLAT/RSN9001_H1.AT2" > "$T/vel.AT2"
printf 'Record Sequence Number,Earthquake Magnitude,ClstD (km),Vs30 (m/s) selected for analysis,Mechanism Based on Rake Angle,File Name (Horizontal 1),File Name (Horizontal 2)\n1,6,10,400,0,vel.AT2,vel.AT2\n' > "$T/velflat.csv"
expect "a velocity time series, not an acceleration" $PY tools/rdfragility.py select "$T/velflat.csv" -o "$T/x"
printf 'scale,overturned\n0.5g,maybe\n' > "$T/badobs.csv"
expect "expected 0/1" $PY tools/rdfragility.py calibrate "$BRICK" --observed "$T/badobs.csv" --param contact.friction=30
[ "$fails" -eq 0 ]
