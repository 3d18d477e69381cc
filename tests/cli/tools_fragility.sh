#!/usr/bin/env bash
# rdfragility: estimators recover known parameters within a tolerance set by their standard
# error; the metrics equal hand-computed values exactly and reproduce seed 002 Table 4; the CLI
# reads CSV and both forms of a sweep HDF5 table and rejects bad input with one line.
set -eu
T=${RD_TMP:-$(mktemp -d)}/tools_frag; mkdir -p "$T"
PY=/usr/bin/python3
$PY - "$T" <<'PY'
import sys, os, csv, json, math
from fractions import Fraction
import numpy as np
from scipy import special
sys.path.insert(0, "tools")
from rdtools import fragility as F
T = sys.argv[1]
rng = np.random.default_rng(20240601)

# 1. logistic, seed 002 eq. 3 form, b0 + b1 PGA: n = 3000 -> s.e. about 0.1-0.2; accept 4 s.e.
n = 3000
x = rng.uniform(0.0, 1.0, n)
b_true = np.array([-3.0, 6.0])
y = (rng.random(n) < special.expit(b_true[0] + b_true[1] * x)).astype(float)
f = F.logistic_fit(np.column_stack([np.ones(n), x]), y)
assert f["method"] == "ml" and f["converged"] and not f["separated"]
z = (f["beta"] - b_true) / f["se"]
assert np.all(np.abs(z) < 4), (f["beta"], f["se"])
assert np.all(f["se"] < [0.3, 0.5]), f["se"]          # the s.e. is as small as n promises
# the reported s.e. is calibrated: spread of 150 replicate estimates (n=400) vs mean reported s.e.
est, ses = [], []
for _ in range(150):
    xx = rng.uniform(0.0, 1.0, 400)
    yy = (rng.random(400) < special.expit(b_true[0] + b_true[1] * xx)).astype(float)
    g = F.logistic_fit(np.column_stack([np.ones(400), xx]), yy, method="ml")
    est.append(g["beta"]); ses.append(g["se"])
ratio = np.std(est, axis=0) / np.mean(ses, axis=0)
assert np.all((ratio > 0.75) & (ratio < 1.35)), ratio   # sampling error of an s.d. from 150: ~6 %

# 2. 2-D surface: logit = c0 + c1 ln PGA + c2 ln(PGV/PGA)
n = 4000
pga = np.exp(rng.uniform(np.log(0.05), np.log(2.0), n))
Tp = np.exp(rng.uniform(np.log(0.03), np.log(0.5), n))
c_true = np.array([4.0, 2.5, 1.5])
yy = (rng.random(n) < special.expit(c_true[0] + c_true[1] * np.log(pga) + c_true[2] * np.log(Tp))).astype(float)
s = F.surface_fit(pga, pga * Tp, yy)
assert np.all(np.abs((s["beta"] - c_true) / s["se"]) < 4), (s["beta"], s["se"])
# contour inversion: P(PGA_p(T), T) = p
for p in F.LEVELS:
    xs = F.surface_contour(s, p, np.array([0.05, 0.2]))
    assert np.allclose(F.surface_prob(s, xs, np.array([0.05, 0.2])), p, atol=1e-12)

# 3. binned fits: in each of 3 PGV/PGA bins a different known (b0, b1) is recovered
n = 6000
Tb = rng.choice([0.05, 0.15, 0.4], n)
truth = {0.05: (-6.0, 4.0), 0.15: (-4.0, 5.0), 0.4: (-2.0, 6.0)}
pg = rng.uniform(0.0, 2.5, n)
b0 = np.array([truth[t][0] for t in Tb]); b1 = np.array([truth[t][1] for t in Tb])
yb = (rng.random(n) < special.expit(b0 + b1 * pg)).astype(float)
bins = F.binned_fits(pg, pg * Tb, yb, edges=[0.01, 0.1, 0.3, 1.0])
assert len(bins) == 3
for d, t in zip(bins, [0.05, 0.15, 0.4]):
    assert d["T_median"] == t and d["method"] == "ml"
    assert abs(d["b0"] - truth[t][0]) < 4 * d["se_b0"] and abs(d["b1"] - truth[t][1]) < 4 * d["se_b1"], d
    assert abs(d["pga_at"][0.5] + d["b0"] / d["b1"]) < 1e-12       # PGA50 = -b0/b1

# 4. separation: detected exactly; Firth gives the finite, symmetric answer (midpoint 0.5)
xs = np.linspace(0, 1, 20); ys = (xs > 0.5).astype(float)
Xs = np.column_stack([np.ones(20), xs])
yo = ys.copy(); yo[5], yo[14] = 1.0, 0.0      # overlapping classes: not separated
assert F.is_separated(Xs, ys) and not F.is_separated(Xs, yo)
assert F.logistic_fit(Xs, yo)["method"] == "ml"
g = F.logistic_fit(Xs, ys)
assert g["method"] == "firth" and g["converged"] and abs(-g["beta"][0] / g["beta"][1] - 0.5) < 1e-6

# 5. lognormal: theta 0.3 g, beta 0.45, n = 3000; accept 4 s.e.; Fisher s.e. calibrated
th, be = 0.3, 0.45
def draw(n):
    x = np.exp(rng.uniform(np.log(0.05), np.log(2.0), n))
    return x, (rng.random(n) < special.ndtr(np.log(x / th) / be)).astype(float)
x, y = draw(3000)
L = F.lognormal_fit(x, y)
assert abs(math.log(L["theta"] / th)) < 4 * L["se_ln_theta"], L
assert abs(L["beta"] - be) < 4 * L["se_beta"], L
assert L["se_ln_theta"] < 0.05 and L["se_beta"] < 0.05
lo, hi = L["band"](np.array([0.1, 0.3, 1.0]))
P = special.ndtr(np.log(np.array([0.1, 0.3, 1.0]) / th) / be)
assert np.all(lo < hi) and np.all((lo - 0.03 < P) & (P < hi + 0.03))
est = []; sel = []
for _ in range(100):
    x, y = draw(300)
    r = F.lognormal_fit(x, y)
    est.append([math.log(r["theta"]), r["beta"]]); sel.append([r["se_ln_theta"], r["se_beta"]])
ratio = np.std(est, axis=0) / np.mean(sel, axis=0)
assert np.all((ratio > 0.7) & (ratio < 1.4)), ratio
# separated data: no MLE, the median is bracketed
r = F.lognormal_fit(np.array([0.1, 0.2, 0.3, 0.4]), np.array([0, 0, 1, 1.0]))
assert r["separated"] and r["theta_range"] == (0.2, 0.3)

# 6. metrics: a hand-made confusion table, exact
m = F.metrics(3, 4, 2, 1)   # TP TN FP FN
assert m["accuracy"] == 7 / 10 and m["precision"] == 3 / 5 and m["recall"] == 3 / 4
assert Fraction(m["F1"]).limit_denominator(1000) == Fraction(2, 3) and abs(m["F1"] - 2 / 3) < 1e-15
assert F.confusion([1, 1, 0, 0, 1], [1, 0, 0, 1, 1]) == (2, 1, 1, 1)
assert math.isnan(F.metrics(0, 5, 0, 0)["precision"])
# seed 002 Table 4 rows, from the counts they imply (582 tests, 243 observed overturnings)
table4 = {(204, 304, 35, 39): (0.872852, 0.853556, 0.839506, 0.846473),   # SP1 KN=10
          (240, 225, 114, 3): (0.798969, 0.677966, 0.987654, 0.804020)}   # SP1 KN=3
for (tp, tn, fp, fn), want in table4.items():
    m = F.metrics(tp, tn, fp, fn)
    got = (m["accuracy"], m["precision"], m["recall"], m["F1"])
    assert all(abs(a - b) < 6e-7 for a, b in zip(got, want)), (got, want)

# 7. CLI inputs: a CSV with an observed column, the same as a compound /sweep and as a group
n = 400
pga = np.exp(rng.uniform(np.log(1.0), np.log(15.0), n)); pgv = pga * np.exp(rng.uniform(np.log(0.05), np.log(0.5), n))
over = (rng.random(n) < special.ndtr(np.log(pga / 5.0) / 0.4)).astype(int)
obs = over.copy(); flip = rng.random(n) < 0.15; obs[flip] = 1 - obs[flip]
with open(T + "/t.csv", "w", newline="") as fh:
    w = csv.writer(fh); w.writerow(["file", "body", "pga", "pgv", "overturned", "observed"])
    for i in range(n):
        w.writerow(["r%d.h5" % i, "b", repr(pga[i]), repr(pgv[i]), over[i], obs[i]])
import h5py
dt = np.dtype([("pga", "f8"), ("pgv", "f8"), ("overturned", "i4"), ("observed", "i4")])
tab = np.zeros(n, dt); tab["pga"], tab["pgv"], tab["overturned"], tab["observed"] = pga, pgv, over, obs
with h5py.File(T + "/sweep_c.h5", "w") as h:
    h["sweep"] = tab
with h5py.File(T + "/sweep_g.h5", "w") as h:
    for k in dt.names:
        h["sweep/" + k] = tab[k]
tp, tn, fp, fn = F.confusion(over, obs)
json.dump(dict(TP=tp, TN=tn, FP=fp, FN=fn), open(T + "/expect.json", "w"))
print("fragility module ok")
PY
for inp in t.csv sweep_c.h5 sweep_g.h5; do
    png=(); [ "$inp" = t.csv ] && png=(-o "$T/$inp.png")
    $PY tools/rdfragility.py "$T/$inp" --bins 3 --json "$T/$inp.json" "${png[@]}" > "$T/$inp.txt"
    grep -q "(4) simulated vs observed" "$T/$inp.txt"
done
$PY - "$T" <<'PY'
import sys, json
T = sys.argv[1]
e = json.load(open(T + "/expect.json"))
tp, tn, fp, fn = e["TP"], e["TN"], e["FP"], e["FN"]
res = [json.load(open("%s/%s.json" % (T, k))) for k in ("t.csv", "sweep_c.h5", "sweep_g.h5")]
for r in res:
    m = r["metrics"]
    assert (m["TP"], m["TN"], m["FP"], m["FN"]) == (tp, tn, fp, fn)
    assert m["accuracy"] == (tp + tn) / (tp + tn + fp + fn) and m["precision"] == tp / (tp + fp)
    assert m["recall"] == tp / (tp + fn)
    p, q = tp / (tp + fp), tp / (tp + fn)
    assert m["F1"] == 2 * p * q / (p + q)
    # data drawn with median 5 m/s^2 = 0.5099 g, beta 0.4
    ln = r["lognormal"]
    assert abs(ln["theta"] - 5.0 / 9.80665) < 4 * ln["theta"] * ln["se_ln_theta"], ln
    assert abs(ln["beta"] - 0.4) < 4 * ln["se_beta"], ln
    assert len(r["binned"]) == 3
assert res[0]["lognormal"] == res[1]["lognormal"] == res[2]["lognormal"]
assert res[0]["surface"] == res[1]["surface"]
print("fragility CLI ok")
PY
printf 'pga,overturned\n1,0\n' > "$T/bad.csv"
printf 'pga,pgv,overturned\n1,0.1,maybe\n' > "$T/bad2.csv"
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
expect "no such file" $PY tools/rdfragility.py "$T/none.csv"
expect "missing column pgv" $PY tools/rdfragility.py "$T/bad.csv"
expect "expected 0/1" $PY tools/rdfragility.py "$T/bad2.csv"
expect "no column 'truth'" $PY tools/rdfragility.py "$T/t.csv" --observed truth
$PY -c "import h5py; h5py.File('$T/plain.h5','w')['x']=[1]"
expect "neither a sweep table (/sweep) nor a rockdem run file" $PY tools/rdfragility.py "$T/plain.h5"
# --where keeps the rows of one direction of docs/FRAGILITY.md's PBR sweep (36 of 72), and a missing
# column is one clear error
n=$(/usr/bin/python3 tools/rdfragility.py docs/pbr_sweep.h5 --where direction=0 2>&1 | sed -n 's/^runs: \([0-9]*\),.*/\1/p')
[ "$n" = 36 ] || { echo "--where direction=0 kept '$n' rows, expected 36"; exit 1; }
if err=$(/usr/bin/python3 tools/rdfragility.py docs/pbr_sweep.h5 --where nope=1 2>&1); then
    echo "--where on a missing column did not fail"; exit 1; fi
printf '%s\n' "$err" | grep -q "no column 'nope'" || { echo "unexpected message: $err"; exit 1; }
[ "$fails" -eq 0 ]
