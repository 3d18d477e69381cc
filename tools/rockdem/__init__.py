"""rockdem — drive the rockdem simulator from Python (over librockdem.so, with ctypes).

    import rockdem
    sc = rockdem.Scenario.load("scenarios/pbr.dat")        # or Scenario.from_text(...) / Scene()
    sc.set("motion.amplitude", "0.4g")                      # any `rockdem keys` override
    run = sc.run("pbr_04g.h5")                              # settle, shake, write the HDF5 file
    run.summary["bodies"]["rock"]["max_tilt_ratio"]         # the C summary, as a dict
    run.histories()["tilt"]                                 # numpy arrays [time][body]
    ds = run.dataset()                                      # xarray.Dataset with named dims
    rockdem.threshold(sc, engine="dem")                     # minimum overturning amplitude
    rockdem.sweep("scenarios/pbr_fragility.dat", scales=["0.2g", "0.4g"], jobs=2, output="t.h5")
    rockdem.assess("scenarios/cask.dat", "cask_assess", ag="0.6g")  # code checks + report

Scenario, run and threshold call the library in this process; sweep runs `rockdem sweep` (its
fork pool of workers, resumable table) and returns the table. Units: SI throughout, as in the
scenario language (m, kg, s, rad; accelerations may be written "0.3g").
"""
import ctypes
import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np

from . import _lib
from ._lib import STATUS
from .scene import Scene
from .results import Run, open_run, open_sweep

__version__ = "0.1.0"
__all__ = ["Scenario", "Scene", "Run", "RockdemError", "open_run", "open_sweep", "threshold",
           "sweep", "assess", "keys", "program"]


class RockdemError(RuntimeError):
    """A one-line error from the library (file:line: problem) or from the rockdem program."""


def _check(rc, err):
    if rc != 0:
        raise RockdemError(err.text or "rockdem: failed")


class Scenario:
    """A parsed scenario (rd_scenario, owned). Build with load(), from_text() or Scene().build()."""

    def __init__(self, _handle, source):
        self._h = _handle
        self.source = source
        self.overrides = []

    @classmethod
    def _new(cls, source):
        h = _lib.lib().rd_scenario_new()
        if not h:
            raise MemoryError("rockdem: cannot allocate a scenario")
        return cls(h, source)

    @classmethod
    def load(cls, path):
        """Parse a scenario file (relative paths inside it: to its folder)."""
        sc = cls._new(os.fspath(path))
        err = _lib.Error()
        _check(_lib.lib().rd_scenario_load(sc._h, os.fsencode(path), ctypes.byref(err)), err)
        return sc

    @classmethod
    def from_text(cls, text, name="scenario.dat"):
        """Parse scenario text; `name` names it in messages and its folder anchors relative
        paths (mesh files, records)."""
        sc = cls._new(name)
        err = _lib.Error()
        _check(_lib.lib().rd_scenario_parse(sc._h, os.fsencode(name), text.encode("utf-8"),
                                            ctypes.byref(err)), err)
        sc.text = text
        return sc

    def set(self, key, value=None):
        """Override one key: set("motion.amplitude", "0.4g") or set("motion.amplitude=0.4g").
        The keys are those of `rockdem keys` (and --set on the command line)."""
        assignment = key if value is None else "%s=%s" % (key, value)
        err = _lib.Error()
        _check(_lib.lib().rd_scenario_set(self._h, assignment.encode("utf-8"), ctypes.byref(err)), err)
        self.overrides.append(assignment)
        return self

    def update(self, overrides):
        """set() every item of a dict (or iterable of "key=value")."""
        items = overrides.items() if isinstance(overrides, dict) else ((o, None) for o in overrides)
        for k, v in items:
            self.set(k, v)
        return self

    def validate(self):
        err = _lib.Error()
        _check(_lib.lib().rd_scenario_validate(self._h, ctypes.byref(err)), err)

    def run(self, output, progress=None):
        """Settle and shake; write the HDF5 run file `output`; return a Run (summary, events,
        histories). progress: None (a bar on a terminal), False, or a callable(t, t_end)."""
        self.set("output.file", os.fspath(output))
        self.validate()
        lib = _lib.lib()
        err = _lib.Error()
        sim = lib.rd_sim_create(self._h, ctypes.byref(err))
        if not sim:
            raise RockdemError(err.text)
        if lib.rd_sim_write_hdf5(sim, os.fsencode(output), ctypes.byref(err)):
            lib.rd_sim_free(sim)
            raise RockdemError(err.text)
        try:
            with _progress(progress), _interruptible():
                status = lib.rd_sim_run(sim)
            summ = _lib.Summary()
            lib.rd_sim_summary(sim, ctypes.byref(summ))
            summary = _summary_dict(summ)  # now: summ.body points into the simulation
            n = ctypes.c_int(0)
            ev = lib.rd_sim_events(sim, ctypes.byref(n))
            events = [(ev[k].time, ev[k].body, ev[k].type.decode(), ev[k].value) for k in range(n.value)]
            message = (lib.rd_sim_error(sim) or b"").decode("utf-8", "replace")
        finally:
            lib.rd_sim_free(sim)
        if STATUS[status] in ("unstable", "io_error", "error", "penetrated", "lost", "untrusted"):
            raise RockdemError("%s: %s" % (self.source, message))
        return Run(os.fspath(output), summary, events)

    def __del__(self):
        h, self._h = getattr(self, "_h", None), None
        if h:
            _lib.lib().rd_scenario_delete(h)


def _summary_dict(s):
    bodies = {}
    for k in range(s.nbodies):
        b = s.body[k]
        d = {name: getattr(b, name) for name, _ in _lib.BodySummary._fields_ if name != "name"}
        d["overturned"] = bool(d["overturned"])
        d["uplifted"], d["slid"] = bool(d["uplifted"]), bool(d["slid"])
        d["unsupported"], d["final_position"] = bool(d["unsupported"]), list(d["final_position"])
        bodies[b.name.decode()] = d
    return {"status": STATUS[s.status], "any_overturned": bool(s.any_overturned),
            "end_time": s.end_time, "dt": s.dt, "dt_critical": s.dt_critical, "steps": s.steps,
            "settle_time": s.settle_time, "energy_residual_max": s.energy_residual_max,
            "wall_seconds": s.wall_seconds, "bodies": bodies}


class _interruptible:
    """Ctrl-C during a run asks the library to stop at the next step (the file stays valid)."""

    def __enter__(self):
        self.old = None
        try:
            self.old = signal.signal(signal.SIGINT, lambda *a: _lib.lib().rd_sim_request_stop())
        except ValueError:  # not the main thread
            pass

    def __exit__(self, *exc):
        if self.old is not None:
            signal.signal(signal.SIGINT, self.old)


class _progress:
    """Install the library's progress callback for the duration of a run."""

    def __init__(self, how):
        if how is None:
            how = _Bar() if sys.stderr.isatty() else False
        self.fn = how

    def __enter__(self):
        if self.fn:
            fn = self.fn
            self.cb = _lib.PROGRESS(lambda ctx, t, end: fn(t, end))
            _lib.lib().rd_set_progress(self.cb, None)

    def __exit__(self, *exc):
        if self.fn:
            _lib.lib().rd_set_progress(_lib.PROGRESS(), None)
            if isinstance(self.fn, _Bar):
                self.fn.done()


class _Bar:
    """t / t_end with an ETA on stderr, at most twice a second."""

    def __init__(self):
        self.t0 = time.monotonic()
        self.last = 0.0

    def __call__(self, t, end):
        now = time.monotonic()
        if now - self.last < 0.5 or end <= 0:
            return
        self.last = now
        f = min(max(t / end, 0.0), 1.0)
        eta = (now - self.t0) * (1 - f) / f if f > 0 else float("nan")
        sys.stderr.write("\r  t = %.3g / %.3g s  %3.0f %%  ETA %.0f s " % (t, end, 100 * f, eta))
        sys.stderr.flush()

    def done(self):
        if self.last:
            sys.stderr.write("\n")


def threshold(scenario, engine="dem", lo=None, hi=None, rtol=None, steps=None,
              frequencies=None, jobs=None):
    """Minimum overturning amplitude of the scenario's horizontal pulse (rd_threshold, the code
    of `rockdem threshold`). Returns a dict: found, amplitude and below (m/s^2, the final
    bracket), static (g tan alpha, m/s^2), ratio (amplitude / static), w_over_p, runs. With
    frequencies (Hz), a list of such dicts, one per pulse frequency (the minimum-overturning
    curve). jobs: coarse-scan runs at once, each in a forked worker process (default: the
    number of cores; 1: all in this process); the result does not depend on it."""
    if frequencies is not None:
        out = []
        for f in frequencies:
            scenario.set("motion.frequency", repr(float(f)))
            r = threshold(scenario, engine, lo, hi, rtol, steps, jobs=jobs)
            r["frequency"] = float(f)
            out.append(r)
        return out
    lib = _lib.lib()
    opts = lib.rd_threshold_opts_default()
    if lo is not None: opts.lo = float(lo)
    if hi is not None: opts.hi = float(hi)
    if rtol is not None: opts.rtol = float(rtol)
    if steps is not None: opts.nscan = int(steps)
    if jobs is not None: opts.jobs = int(jobs)
    res, err = _lib.ThresholdResult(), _lib.Error()
    scenario.validate()
    eng = {"dem": 0, "reference": 1}[engine]
    _check(lib.rd_threshold(scenario._h, eng, ctypes.byref(opts), ctypes.byref(res),
                            ctypes.byref(err)), err)
    return {"found": bool(res.found), "amplitude": res.amplitude, "below": res.below,
            "static": res.static_amp, "ratio": res.amplitude / res.static_amp if res.found else None,
            "w_over_p": res.w_over_p, "runs": res.runs}


def program():
    """Path of the rockdem program: $ROCKDEM_BIN, beside this package (pip install), the
    repository's bin/rockdem, or rockdem on PATH."""
    for p in (os.environ.get("ROCKDEM_BIN"), os.path.join(_lib.HERE, "bin", "rockdem"),
              os.path.join(_lib.REPO, "bin", "rockdem"), shutil.which("rockdem")):
        if p and os.access(p, os.X_OK):
            return p
    raise RockdemError("rockdem: the rockdem program was not found; run `make` or set ROCKDEM_BIN")


def sweep(scenario_file, output, axes=None, records=None, scales=None, directions=None,
          overrides=None, jobs=None, keep_runs=None, quiet=True):
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
    if jobs:
        cmd += ["-j", str(int(jobs))]
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


def assess(scenario_file, out, ag=None, spectrum=None, overrides=None, report=True, **options):
    """The seismic assessment of the scene's body on its pad with `rockdem assess` (docs/ASSESS.md):
    static code checks, ASCE 43-05 A.1/A.2, allowable PGAs and matched-record DEM runs, written
    into folder `out`. ag: EN 1998 a_g ("0.3g" or m/s^2); spectrum: "en1998-1A" (default) or
    a table file; options: any other option by name, e.g. records=5, mu=0.6, slide_limit=1.0,
    vertical=0.667, code="en1998,kta", body="cask" (True for a flag: neglect_vertical=True).
    report=True also writes out/report.md and its figures (tools/rdassess.py). Returns the
    parsed out/assess.json."""
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
        raise RockdemError((p.stderr.strip() or p.stdout.strip() or "rockdem assess failed").splitlines()[-1])
    if report:
        tool = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "rdassess.py")
        r = subprocess.run([sys.executable, tool, os.fspath(out)], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            raise RockdemError((r.stderr.strip() or "rdassess failed").splitlines()[-1])
    with open(os.path.join(os.fspath(out), "assess.json")) as f:
        return json.load(f)


def keys():
    """Every override key with its units and default, as `rockdem keys` prints them:
    a list of dicts (key, units, default, meaning)."""
    p = subprocess.run([program(), "keys", "--tsv"], stdout=subprocess.PIPE, text=True, check=True)
    rows = [ln.split("\t") for ln in p.stdout.splitlines() if ln.strip()]
    return [dict(zip(("key", "units", "default", "meaning"), r)) for r in rows[1:]]
