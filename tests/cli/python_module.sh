#!/usr/bin/env bash
# The Python module tools/rockdem over build/librockdem.so (ctypes): a scenario built in code and
# one loaded from a file run in this process and give the same summary as `rockdem run` of the
# same text (the engine is deterministic) and as the HDF5 file they wrote; overrides apply;
# histories and the xarray Dataset have the file's shape; threshold() equals `rockdem
# threshold`; sweep() returns the table of `rockdem sweep`; bad input raises one-line errors.
# Then the package is pip-installed (building its C library) into a fresh virtual environment and
# imported from there.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/py; mkdir -p "$T"
LIB=${RD_BUILD:-build}/librockdem.so
[ -f "$LIB" ] || { echo "no $LIB (make python builds it)"; exit 1; }
export ROCKDEM_LIB=$(cd "$(dirname "$LIB")" && pwd)/librockdem.so ROCKDEM_BIN=$BIN
# a sanitizer build (make asan): Python itself is not instrumented, so the sanitizer runtime
# must be loaded first; Python's own allocations are not ours to leak-check
if nm -D "$LIB" 2>/dev/null | grep -q __asan_init; then
    export LD_PRELOAD="$(${CC:-cc} -print-file-name=libasan.so) $(${CC:-cc} -print-file-name=libubsan.so)"
    export ASAN_OPTIONS=detect_leaks=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}
fi
cat > "$T/block.dat" <<'DAT'
model title 'python test: a slender block on a pad'
block create brick size 4 4 0.5 position 0 0 -0.25 fixed name pad
block create brick size 0.4 0.4 1.6 position 0 0 0.8 name block
contact property stiffness-normal 1e9 stiffness-shear 1e8 friction 40
ground-motion pulse one-sine amplitude 0.35g frequency 2 direction 0
model solve time 3
output hdf5 'x.h5' interval 0.01
DAT
"$BIN" run "$T/block.dat" --set motion.amplitude=0.3g -q -o "$T/cli.h5" > /dev/null
"$BIN" threshold "$T/block.dat" --engine reference -q > "$T/threshold.txt"
/usr/bin/python3 - "$T" <<'PY'
import os, sys
sys.path.insert(0, "tools")
import h5py, numpy as np, rockdem
T = sys.argv[1]
# the same scene built in code, with the pulse overridden as on the command line
sc = (rockdem.Scene("python test: a slender block on a pad", folder=T)
      .brick("pad", size=(4, 4, 0.5), position=(0, 0, -0.25), fixed=True)
      .brick("block", size=(0.4, 0.4, 1.6), position=(0, 0, 0.8))
      .contact(kn=1e9, ks=1e8, friction=40)
      .pulse("one-sine", amplitude="0.35g", frequency=2, direction=0)
      .solve(3).output("x.h5", 0.01)).build()
run = sc.set("motion.amplitude", "0.3g").run(os.path.join(T, "py.h5"), progress=False)
b = run.summary["bodies"]["block"]
with h5py.File(os.path.join(T, "cli.h5"), "r") as c, h5py.File(run.path, "r") as p:
    # same engine, same input: identical to the last bit (max tilt, tilt history)
    assert c["summary"].attrs["max_tilt"][0] == b["max_tilt"], (c["summary"].attrs["max_tilt"], b)
    assert np.array_equal(c["tilt"][()], p["tilt"][()])
    # the ctypes summary struct reads what the C wrote into the file
    for k in ("max_tilt_ratio", "max_slide", "alpha", "overturn_time", "final_twist"):
        assert p["summary"].attrs[k][0] == b[k], k
    assert p["summary"].attrs["steps"] == run.summary["steps"]
    assert "--set motion.amplitude=0.3g" in p.attrs["scenario"]
assert run.status in ("done", "overturned") and b["uplifted"]
h = run.histories()
n = h["time"].shape[0]
assert h["tilt"].shape == (n, 1) and h["position"].shape == (n, 1, 3) and n > 100
a_used = h["tilt"][1:, 0] / h["tilt_ratio"][1:, 0]  # alpha towards the lean (t > 0: tilt > 0)
with h5py.File(run.path, "r") as p:
    tab = p["bodies/precariousness"][:p["bodies/lean_count"][0], 1]  # free body 0's rows
assert np.all((a_used >= tab.min() * (1 - 1e-9)) & (a_used <= tab.max() * (1 + 1e-9)))
assert abs(np.nanmax(h["tilt_ratio"]) - b["max_tilt_ratio"]) < 0.05 * b["max_tilt_ratio"]  # sampled vs every step
ds = run.dataset()
assert ds["tilt"].dims == ("time", "body") and list(ds["body"].values) == ["block"]
assert float(ds["max_tilt"].sel(body="block")) == b["max_tilt"] and ds.attrs["status"] == run.status
ev = rockdem.open_run(run.path, "events")
assert set(ev["type"].values) >= {"uplift"} and set(ev["body"].values) <= {"block", ""}
assert list(run.events["type"]) == list(ev["type"].values)
# loaded from the file: the same as the CLI
sc2 = rockdem.Scenario.load(os.path.join(T, "block.dat")).update({"motion.amplitude": "0.3g"})
assert sc2.run(os.path.join(T, "py2.h5"), progress=False).summary["bodies"]["block"]["max_tilt"] == b["max_tilt"]
# threshold through the library equals the CLI's (same code, same options)
th = rockdem.threshold(rockdem.Scenario.load(os.path.join(T, "block.dat")), engine="reference")
cli_amp = float(open(os.path.join(T, "threshold.txt")).read().split("amplitude ")[1].split()[0])
assert th["found"] and abs(th["amplitude"] - cli_amp) <= 1e-4 * cli_amp, (th, cli_amp)
# progress callback: called with increasing t up to the end
seen = []
rockdem.Scenario.load(os.path.join(T, "block.dat")).run(os.path.join(T, "py3.h5"),
                                                        progress=lambda t, e: seen.append((t, e)))
assert seen and seen[-1][1] == 3 and abs(seen[-1][0] - 3) < 1e-3 and all(a[0] <= b_[0] for a, b_ in zip(seen, seen[1:]))
# a sweep with the program's worker pool: half and twice the rigid threshold amplitude (the
# DEM's threshold lies within a few per cent of the reference's for this slender block)
a_th = th["amplitude"] / 9.80665
tab = rockdem.sweep(os.path.join(T, "block.dat"), os.path.join(T, "sw.h5"),
                    scales=["%.4gg" % (0.5 * a_th), "%.4gg" % (2 * a_th)], jobs=2)
assert tab.sizes["case"] == 2 and set(tab["status"].values) <= {"done", "overturned"}
assert list(tab["overturned"].values) == [0, 1], tab["overturned"].values
# errors: one line naming the problem; a run whose energy balance fails (a block dropped at 5 m/s
# on elastic springs at 0.91 of the stable step) is refused as the command line refuses it
untrusted = ("block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base\n"
             "block create brick size 0.5 0.5 1.0 position 0 0 0.6 name b\n"
             "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40 restitution 1 spacing vertices\n"
             "model timestep fixed 1.9e-4\nmodel settle off\nblock initial name b velocity 0 0 -5\n"
             "model solve time 0.5\noutput hdf5 'x.h5' interval 0.01\n")
for bad, want in ((lambda: sc2.set("motion.nonsense", "1"), "unknown key"),
                  (lambda: rockdem.Scenario.from_text(untrusted).run(os.path.join(T, "untrusted.h5"), progress=False),
                   "energy balance"),
                  (lambda: rockdem.Scenario.from_text("block create brick size -1 1 1\n"), "scenario.dat:1"),
                  (lambda: rockdem.Scenario.load(os.path.join(T, "nope.dat")), "nope.dat")):
    try:
        bad()
        raise AssertionError("accepted: " + want)
    except rockdem.RockdemError as e:
        assert want in str(e) and "\n" not in str(e), str(e)
print("python module ok: max tilt/alpha %.4f, threshold %.4g m/s^2, %d progress calls"
      % (b["max_tilt_ratio"], th["amplitude"], len(seen)))
PY
# the documented example (shorter loop) runs from the repository
ROCKDEM_EXAMPLE_QUICK=1 /usr/bin/python3 docs/examples/pbr_study.py > "$T/example.txt"
grep -q "minimum overturning amplitude" "$T/example.txt"
# pip install into a fresh virtual environment (Debian's numpy/h5py/xarray via system site packages)
/usr/bin/python3 -m venv --system-site-packages "$T/venv" 2>/dev/null || {
    echo "skipped: python3 -m venv unavailable (Debian python3-venv)"; exit 77; }
# the package's own build step compiles the library and the program with the Makefile (in
# tools/build/, incremental across runs); Debian's numpy and h5py come from the system
"$T/venv/bin/pip" install -q --no-index --no-build-isolation --no-deps ./tools > "$T/pip.txt" 2>&1 || {
    cat "$T/pip.txt"; exit 1; }
(cd "$T" && env -u ROCKDEM_LIB -u ROCKDEM_BIN "$T/venv/bin/python" - <<'PY'
import os, rockdem, rockdem._lib as L
assert "site-packages" in rockdem.__file__, rockdem.__file__
assert L.lib()._name.startswith(os.path.dirname(rockdem.__file__)), L.lib()._name
assert rockdem.program().startswith(os.path.dirname(rockdem.__file__)), rockdem.program()
r = rockdem.Scenario.load("block.dat").set("model.duration", 0.3).run("venv.h5", progress=False)
assert os.path.exists("venv.h5") and r.status == "done"
print("venv ok:", rockdem.__file__)
PY
)
