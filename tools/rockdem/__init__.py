"""rockdem — drive the rockdem simulator from Python (over librockdem.so, with ctypes).

    import rockdem
    sc = rockdem.Scenario.load("scenarios/pbr.dat")        # or Scenario.from_text(...) / Scene()
    sc.set("motion.amplitude", "0.4g")                      # any `rockdem keys` override
    run = sc.run("pbr_04g.h5")                              # settle, shake, write the HDF5 file
    run.summary["bodies"]["rock"]["max_tilt_ratio"]         # the C summary, as a dict
    run.histories()["tilt"]                                 # numpy arrays [time][body]
    ds = run.dataset()                                      # xarray.Dataset with named dims
    sim = rockdem.Simulation(sc)                            # or step it, results in memory:
    sim.add_callback(lambda sim, s: print(s["time"], s["tilt"]), every=20)
    sim.run_until(1.0); sim.bodies["rock"].position; run = sim.run()
    rockdem.threshold(sc, engine="dem")                     # minimum overturning amplitude
    rockdem.sweep("scenarios/pbr_fragility.dat", scales=["0.2g", "0.4g"], jobs=2, output="t.h5")
    rockdem.assess("scenarios/cask.dat", "cask_assess", ag="0.6g")  # code checks + report

Scenario, Simulation and threshold call the library in this process; sweep runs `rockdem
sweep` (its fork pool of workers, resumable table) and returns the table. Scenarios copy and
pickle as real copies (multiprocessing: spawn, forkserver, fork); Ctrl-C stops a run, completes
its file and raises KeyboardInterrupt. Units: SI throughout, as in the scenario language (m, kg,
s, rad, J; accelerations may be written "0.3g" with g = 9.80665 m/s^2). docs/PYTHON.md.
"""
from __future__ import annotations

import ctypes
import os
import shutil
import subprocess
import sys
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _lib
from ._lib import STATUS
from .results import Run, event_table, open_run, open_sweep
from .scenario import RockdemError, Scenario, check
from .scene import Scene
from .simulation import Body, Joint, Simulation, _Bar, count_arg

__version__ = "0.1.0"
__all__ = ["Scenario", "Scene", "Simulation", "Body", "Joint", "Run", "RockdemError",
           "open_run", "open_sweep", "event_table", "threshold", "sweep", "assess", "keys",
           "program", "STATUS"]


class _progress:
    """Install the library's process-wide progress callback for the duration of a threshold
    search (its runs may be in forked workers, which relay their progress)."""

    def __init__(self, how: Any) -> None:
        if how is None:
            how = _Bar() if sys.stderr.isatty() else False
        self.fn = how

    def __enter__(self) -> None:
        if self.fn:
            fn = self.fn
            self.cb = _lib.PROGRESS(lambda ctx, t, end: fn(t, end))
            _lib.lib().rd_set_progress(self.cb, None)

    def __exit__(self, *exc: Any) -> None:
        if self.fn:
            _lib.lib().rd_set_progress(_lib.PROGRESS(), None)
            if isinstance(self.fn, _Bar):
                self.fn.done()


def _limit(keyword: str) -> Tuple[float, float]:
    """The valid range of a scenario number (docs/LIMITS.md), from the library."""
    lo, hi = ctypes.c_double(), ctypes.c_double()
    _lib.lib().rd_scenario_limit(keyword.encode(), ctypes.byref(lo), ctypes.byref(hi))
    return lo.value, hi.value


def _amplitude_arg(name: str, v: Any) -> float:
    """An amplitude in m/s^2 (a number, or a str such as "0.3g") within the pulse amplitude's
    range, as `rockdem threshold --lo/--hi` reads it."""
    if isinstance(v, str):
        t = v.strip()
        try:
            a = float(t[:-1]) * G if t.endswith("g") else float(t)
        except ValueError:
            raise ValueError("rockdem: %s expects an amplitude in m/s^2 or like '0.3g', got %r"
                             % (name, v)) from None
    elif isinstance(v, (int, float, np.floating, np.integer)) and not isinstance(v, bool):
        a = float(v)
    else:
        raise TypeError("rockdem: %s expects an amplitude in m/s^2, got %r" % (name, v))
    lo, hi = _limit("amplitude")
    if not (a > 0 and a <= hi):
        raise ValueError("rockdem: %s expects an amplitude above 0 and at most %g m/s^2, got %r"
                         % (name, hi, v))
    return a


G = 9.80665  # standard gravity, m/s^2: what "0.3g" means in the scenario language
RTOL_RANGE = (1e-6, 1.0)  # RD_THRESHOLD_RTOL_MIN / MAX (include/rockdem/validate.h)
SCAN_MAX = 1000           # RD_THRESHOLD_SCAN_MAX (include/rockdem/validate.h)
JOBS_MAX = 256            # `rockdem threshold -j`'s cap (src/cli/cli_threshold.c)


def threshold(scenario: Scenario, engine: str = "dem", lo: Any = None, hi: Any = None,
              rtol: Optional[float] = None, steps: Optional[int] = None,
              frequencies: Optional[Sequence[float]] = None, jobs: Optional[int] = None,
              progress: Any = False) -> Union[Dict[str, Any], List[Dict[str, Any]]]:
    """Minimum overturning amplitude of the scenario's horizontal pulse (rd_threshold, the code
    of `rockdem threshold`). Returns a dict: found, amplitude and below (m/s^2, the final
    bracket), static (g tan alpha, m/s^2), ratio (amplitude / static), w_over_p, runs. With
    frequencies (Hz), a list of such dicts, one per pulse frequency (the minimum-overturning
    curve). jobs: coarse-scan runs at once, each in a forked worker process (default: the
    number of cores; 1: all in this process); the result does not depend on it. Every
    argument is range-checked as `rockdem threshold` checks its options (ValueError,
    TypeError): lo, hi above 0 up to the pulse amplitude's cap; rtol in [1e-6, 1]; steps 1 to
    1000; jobs 1 to 256; frequencies within the pulse frequency's range, at most 64. The
    scenario is not changed (frequencies are set on a copy)."""
    if not isinstance(scenario, Scenario):
        raise TypeError("rockdem: threshold expects a Scenario, got %s" % type(scenario).__name__)
    if engine not in ("dem", "reference"):
        raise ValueError("rockdem: engine expects 'dem' or 'reference', got %r" % (engine,))
    lib = _lib.lib()
    opts = lib.rd_threshold_opts_default()
    if lo is not None: opts.lo = _amplitude_arg("lo", lo)
    if hi is not None: opts.hi = _amplitude_arg("hi", hi)
    if rtol is not None:
        if isinstance(rtol, bool) or not isinstance(rtol, (int, float, np.floating)) \
                or not RTOL_RANGE[0] <= float(rtol) <= RTOL_RANGE[1]:
            raise ValueError("rockdem: rtol expects a relative bracket from %g to %g, got %r"
                             % (RTOL_RANGE + (rtol,)))
        opts.rtol = float(rtol)
    if steps is not None: opts.nscan = count_arg("steps", steps, 1, SCAN_MAX)
    if jobs is not None: opts.jobs = count_arg("jobs", jobs, 1, JOBS_MAX)
    if frequencies is not None:
        fs = [float(f) for f in frequencies]
        flo, fhi = _limit("frequency")
        if not 1 <= len(fs) <= 64 or not all(flo <= f <= fhi and f > 0 for f in fs):
            raise ValueError("rockdem: frequencies expects 1 to 64 pulse frequencies in (0, %g] "
                             "Hz, got %r" % (fhi, frequencies))
        out = []
        for f in fs:
            r = threshold(scenario.copy().set("motion.frequency", repr(f)), engine, lo, hi,
                          rtol, steps, jobs=jobs, progress=progress)
            r["frequency"] = f
            out.append(r)
        return out
    res, err = _lib.ThresholdResult(), _lib.Error()
    scenario.validate()
    eng = {"dem": 0, "reference": 1}[engine]
    with _progress(progress), scenario._lock:
        check(lib.rd_threshold(scenario._h, eng, ctypes.byref(opts), ctypes.byref(res),
                               ctypes.byref(err)), err)
    return {"found": bool(res.found), "amplitude": res.amplitude, "below": res.below,
            "static": res.static_amp, "ratio": res.amplitude / res.static_amp if res.found else None,
            "w_over_p": res.w_over_p, "runs": res.runs}


def program() -> str:
    """Path of the rockdem program: $ROCKDEM_BIN, beside this package (pip install), the
    repository's bin/rockdem, or rockdem on PATH."""
    for p in (os.environ.get("ROCKDEM_BIN"), os.path.join(_lib.HERE, "bin", "rockdem"),
              os.path.join(_lib.REPO, "bin", "rockdem"), shutil.which("rockdem")):
        if p and os.access(p, os.X_OK):
            return p
    raise RockdemError("rockdem: the rockdem program was not found; run `make` or set ROCKDEM_BIN")


def sweep(scenario_file: Any, output: Any, axes: Optional[Mapping[str, Sequence[Any]]] = None,
          records: Optional[Sequence[str]] = None, scales: Optional[Sequence[Any]] = None,
          directions: Optional[Sequence[float]] = None,
          overrides: Optional[Mapping[str, Any]] = None, jobs: Optional[int] = None,
          keep_runs: Any = None, quiet: bool = True) -> Any:
    """A fragility sweep with `rockdem sweep` (the same fork pool, -j workers, resumable table).
    axes: {"motion.seed": [1, 2, 3]}; records, scales, directions: lists; overrides: {key: value}.
    Returns open_sweep(output): an xarray.Dataset over dimension `case`."""
    cmd = [program(), "sweep", os.fspath(scenario_file)]
    for k, v in (overrides or {}).items():
        cmd += ["--set", "%s=%s" % (k, v)]
    for k, vals in (axes or {}).items():
        cmd += ["--axis", "%s=%s" % (k, ",".join(str(v) for v in vals))]
    for opt, vals in (("--records", records), ("--scales", scales), ("--directions", directions)):
        if vals is not None:
            cmd += [opt, ",".join(str(v) for v in vals)]
    if jobs is not None:
        cmd += ["-j", str(count_arg("jobs", jobs, 1, JOBS_MAX))]
    if keep_runs:
        cmd += ["--keep-runs", os.fspath(keep_runs)]
    if quiet:
        cmd.append("-q")
    cmd += ["-o", os.fspath(output)]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        raise RockdemError((p.stderr.strip() or p.stdout.strip() or "rockdem sweep failed")
                           .splitlines()[-1])
    return open_sweep(output)


def assess(scenario_file: Any, out: Any, ag: Any = None, spectrum: Any = None,
           overrides: Optional[Mapping[str, Any]] = None, report: bool = True,
           **options: Any) -> Dict[str, Any]:
    """The seismic assessment of the scene's body on its pad with `rockdem assess` (docs/ASSESS.md):
    static code checks, ASCE 43-05 A.1/A.2, allowable PGAs and matched-record DEM runs, written
    into folder `out`. ag: EN 1998 a_g ("0.3g", or a number in m/s^2); spectrum: "en1998-1A"
    (default) or a table file; options: any other option by name, e.g. records=5, mu=0.6,
    slide_limit=1.0 (m), vertical=0.667, code="en1998,kta", body="cask" (True for a flag:
    neglect_vertical=True). report=True also writes out/report.md and its figures
    (tools/rdassess.py, where the repository is there). Returns the parsed out/assess.json."""
    import json
    cmd = [program(), "assess", os.fspath(scenario_file), "--out", os.fspath(out), "-q"]
    if ag is not None:
        cmd += ["--ag", str(ag)]
    if spectrum is not None:
        cmd += ["--spectrum", os.fspath(spectrum)]
    for k, v in (overrides or {}).items():
        cmd += ["--set", "%s=%s" % (k, v)]
    for k, v in options.items():
        opt = "--" + k.replace("_", "-")
        if v is True:
            cmd.append(opt)
        elif v is not False and v is not None:
            cmd += [opt, str(v)]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        raise RockdemError((p.stderr.strip() or p.stdout.strip() or "rockdem assess failed")
                           .splitlines()[-1])
    if report:
        tool = os.path.join(_lib.REPO, "tools", "rdassess.py")
        r = subprocess.run([sys.executable, tool, os.fspath(out)], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            raise RockdemError((r.stderr.strip() or "rdassess failed").splitlines()[-1])
    with open(os.path.join(os.fspath(out), "assess.json")) as f:
        return json.load(f)


def keys() -> List[Dict[str, str]]:
    """Every override key with its units and default, as `rockdem keys` prints them:
    a list of dicts (key, units, default, meaning)."""
    p = subprocess.run([program(), "keys", "--tsv"], stdout=subprocess.PIPE, text=True, check=True)
    rows = [ln.split("\t") for ln in p.stdout.splitlines() if ln.strip()]
    return [dict(zip(("key", "units", "default", "meaning"), r)) for r in rows[1:]]
