"""A running simulation (the C rd_sim) as a Python object: bodies and joints with their state,
step(n), run_until(t), callbacks every k samples (the C observer API, include/rockdem/observer.h)
and results in memory, with or without an HDF5 run file.

    sim = rockdem.Simulation(rockdem.Scenario.load("scenarios/pbr.dat"))
    sim.add_callback(lambda sim, s: print(s["time"], s["tilt"]), every=20)
    sim.run_until(1.0)                  # settles first, then shakes to t = 1 s
    sim.bodies["rock"].position         # m, ground frame, now
    run = sim.run()                     # on to the end: a Run (summary, events, histories)

Units: SI (m, kg, s, rad, J); time is counted from the start of shaking (after settling)."""
from __future__ import annotations

import ctypes
import math
import os
import sys
import threading
import time
from typing import Any, Callable, Dict, List, Optional, Union

import numpy as np

from . import _lib
from ._lib import STATUS
from .results import Run
from .scenario import PathLike, RockdemError, Scenario, check

FAILED = ("unstable", "io_error", "error", "penetrated", "lost", "untrusted")
# Most steps one step()/advance call may ask for: RD_STEP_BUDGET of include/rockdem/rockdem.h
STEP_BUDGET = 10 ** 9

Callback = Callable[["Simulation", Dict[str, Any]], Any]


def count_arg(name: str, value: Any, lo: int, hi: int) -> int:
    """value as a whole number in [lo, hi], else TypeError / ValueError naming name."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        if isinstance(value, float) and value.is_integer():
            value = int(value)
        else:
            raise TypeError("rockdem: %s expects a whole number, got %r" % (name, value))
    if not lo <= value <= hi:
        raise ValueError("rockdem: %s expects a whole number from %d to %d, got %d"
                         % (name, lo, hi, value))
    return int(value)


def time_arg(name: str, value: Any) -> float:
    """value as a time in s >= 0 (math.inf: no end), else TypeError / ValueError naming name."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise TypeError("rockdem: %s expects a time in s, got %r" % (name, value))
    v = float(value)
    if not v >= 0:
        raise ValueError("rockdem: %s expects a time >= 0 s, got %r" % (name, value))
    return v


class Body:
    """One body of a simulation. name, fixed, mass (kg), inertia (principal moments, kg m^2),
    size (extents at rest along x, y, z, m) and alpha (static tipping angle, rad; 0 before the
    run) come from the C rd_body_info; position (m), quaternion (w, x, y, z), velocity (m/s) and
    angular_velocity (rad/s, ground frame) are read from the running simulation at each access
    (a fixed body's never change)."""

    def __init__(self, sim: "Simulation", index: int, free_index: int) -> None:
        self._sim, self._k, self.index = sim, index, free_index
        info = self._info()
        self.name: str = info.name.decode("utf-8", "replace")
        self.fixed: bool = bool(info.fixed)
        self.mass: float = info.mass
        self.inertia: np.ndarray = np.array(info.inertia[:])
        self.size: np.ndarray = np.array(info.size[:])

    def _info(self) -> _lib.BodyInfo:
        info = _lib.BodyInfo()
        _lib.lib().rd_sim_body_info(self._sim._handle(), self._k, ctypes.byref(info))
        return info

    @property
    def alpha(self) -> float:
        """Static tipping angle about the edge of its support polygon at rest, rad (0 before
        the scene has settled, and for fixed bodies)."""
        return self._info().alpha

    @property
    def vertices(self) -> np.ndarray:
        """[nvert][3] vertices in the body frame (centre of mass, principal axes), m."""
        info = self._info()
        return np.ctypeslib.as_array(info.vertices, (info.nvert, 3)).copy()

    @property
    def precariousness(self) -> np.ndarray:
        """[n][3]: lean direction (rad from +x), alpha (rad), g tan(alpha) (m/s^2); empty
        before the scene has settled."""
        info = self._info()
        if info.nprec == 0:
            return np.zeros((0, 3))
        return np.ctypeslib.as_array(info.precariousness, (info.nprec, 3)).copy()

    def _state(self) -> List[np.ndarray]:
        if self.fixed:
            info = self._info()
            return [np.array(info.position[:]), np.array(info.quaternion[:]), np.zeros(3),
                    np.zeros(3)]
        out = [np.zeros(3), np.zeros(4), np.zeros(3), np.zeros(3)]
        p = [a.ctypes.data_as(_lib._DP) for a in out]
        _lib.lib().rd_sim_body_state(self._sim._handle(), self.index, *p)
        return out

    @property
    def position(self) -> np.ndarray:
        """Centre of mass now, ground frame, m."""
        return self._state()[0]

    @property
    def quaternion(self) -> np.ndarray:
        """Orientation now (w, x, y, z), body frame to ground frame."""
        return self._state()[1]

    @property
    def velocity(self) -> np.ndarray:
        """Velocity of the centre of mass now, relative to the ground, m/s."""
        return self._state()[2]

    @property
    def angular_velocity(self) -> np.ndarray:
        """Angular velocity now, ground frame, rad/s."""
        return self._state()[3]

    def summary(self) -> Dict[str, Any]:
        """What the run found for this free body so far (rd_body_summary as a dict)."""
        if self.fixed:
            raise RockdemError("rockdem: %s is fixed: only free bodies have a summary" % self.name)
        b = _lib.BodySummary()
        _lib.lib().rd_sim_body_summary(self._sim._handle(), self.index, ctypes.byref(b))
        return body_summary_dict(b)

    def __repr__(self) -> str:
        return "<rockdem.Body %s%s, %.4g kg at %s m>" % (
            self.name, " (fixed)" if self.fixed else "", self.mass,
            np.array2string(self.position, precision=4))


class Joint:
    """A joint: a pair of bodies that came near each other, with its law (kn, ks in Pa/m,
    friction in rad, cohesion and tension in Pa, damping ratio) and what it did (closed,
    max_opening, max_slip, final_slip in m), read at each access."""

    def __init__(self, sim: "Simulation", index: int) -> None:
        self._sim, self.index = sim, index
        j = self._read()
        self.a: str = j.a.decode("utf-8", "replace")
        self.b: str = j.b.decode("utf-8", "replace")

    def _read(self) -> _lib.JointSummary:
        j = _lib.JointSummary()
        _lib.lib().rd_sim_joint(self._sim._handle(), self.index, ctypes.byref(j))
        return j

    def state(self) -> Dict[str, Any]:
        """The joint's law and what it did so far, as a dict (SI units, friction in rad)."""
        j = self._read()
        d = {k: getattr(j, k) for k, _ in _lib.JointSummary._fields_ if k not in ("a", "b")}
        d["closed"] = bool(d["closed"])
        d["a"], d["b"] = self.a, self.b
        return d

    def __getattr__(self, key: str) -> Any:
        if key.startswith("_"):
            raise AttributeError(key)
        st = self.state()
        if key in st:
            return st[key]
        raise AttributeError("rockdem.Joint has no attribute %r" % key)

    def __repr__(self) -> str:
        return "<rockdem.Joint %s-%s>" % (self.a, self.b)


class _Names(dict):
    """Bodies by name, iterated in order (free bodies in output order, then the fixed ones)."""

    def __iter__(self):
        return iter(self.values())

    def __getitem__(self, key):
        if isinstance(key, int):
            return list(self.values())[key]
        return dict.__getitem__(self, key)


def body_summary_dict(b: _lib.BodySummary) -> Dict[str, Any]:
    """An rd_body_summary as a dict (flags as bools, final_position as a list, m)."""
    skip = ("name", "nfences", "fence")
    d = {name: getattr(b, name) for name, _ in _lib.BodySummary._fields_ if name not in skip}
    for k in ("overturned", "uplifted", "slid", "unsupported"):
        d[k] = bool(d[k])
    for k in ("final_position", "final_quaternion"):
        d[k] = list(d[k])
    d["fence"] = [{name: (list(getattr(h, name)) if name == "point" else getattr(h, name))
                   for name, _ in _lib.FenceHit._fields_} for h in b.fence[:b.nfences]]
    return d


def summary_dict(s: _lib.Summary) -> Dict[str, Any]:
    """An rd_summary as a dict: status (its name), run figures (s, J) and bodies by name."""
    bodies = {s.body[k].name.decode("utf-8", "replace"): body_summary_dict(s.body[k])
              for k in range(s.nbodies)}
    return {"status": STATUS[s.status], "any_overturned": bool(s.any_overturned),
            "end_time": s.end_time, "dt": s.dt, "dt_critical": s.dt_critical, "steps": s.steps,
            "settle_time": s.settle_time, "energy_residual_max": s.energy_residual_max,
            "wall_seconds": s.wall_seconds, "at_rest": bool(s.at_rest), "bodies": bodies}


class _Recorder:
    """The Python observer: keeps every sample and event in memory and calls the callbacks."""

    def __init__(self, sim: "Simulation") -> None:
        self.sim = sim
        self.samples: List[Dict[str, Any]] = []
        self.callbacks: List[List[Any]] = []  # [fn, every, samples seen]
        self.progress: Optional[Callable[[float, float], Any]] = None
        self.error: Optional[BaseException] = None
        c = _lib.Observer()
        c.every = 1
        self._cbs = (_lib.OBS_SAMPLE(self._sample), _lib.OBS_EVENT(self._event))
        c.sample, c.event = self._cbs
        self.struct = c

    def _guard(self, fn: Callable[[], Any], err: Any) -> int:
        try:
            fn()
            return 0
        except BaseException as e:  # noqa: B902 (re-raised by the caller after the run stops)
            self.error = e
            err[0].msg = ("python callback: %s: %s" % (type(e).__name__, e)).encode(
                "utf-8", "replace")[:_lib.RD_ERROR_MAX - 1]
            return 1

    def _sample(self, user: int, sim: int, s: Any, err: Any) -> int:
        return self._guard(lambda: self._on_sample(s[0]), err)

    def _on_sample(self, s: _lib.Sample) -> None:
        n = s.nbodies

        def arr(p: Any, *shape: int) -> np.ndarray:
            return np.ctypeslib.as_array(p, (n,) + shape).copy() if n else np.zeros((0,) + shape)

        d = {"time": s.time, "position": arr(s.position, 3), "quaternion": arr(s.quaternion, 4),
             "velocity": arr(s.velocity, 3), "angular_velocity": arr(s.angular_velocity, 3),
             "tilt": np.ctypeslib.as_array(s.tilt, (n,)).copy() if n else np.zeros(0),
             "rotation": arr(s.rotation, 3), "ground_acceleration": np.array(s.ground_acc[:]),
             "ground_velocity": np.array(s.ground_vel[:]),
             "ground_displacement": np.array(s.ground_disp[:]),
             "energy": dict(zip(_lib.ENERGY, s.energy[:]))}
        self.samples.append(d)
        for cb in self.callbacks:
            if cb[2] % cb[1] == 0:
                cb[0](self.sim, d)
            cb[2] += 1
        if self.progress:
            self.progress(s.time, self.sim.end_time)

    def _event(self, user: int, sim: int, e: Any, err: Any) -> int:
        return 0  # events are read whole from rd_sim_events when asked for


class Simulation:
    """A simulation built from a Scenario, a scenario file path, scenario text or a Scene.

    output: an HDF5 run file to write as `rockdem run -o` does (None: results stay in memory
    only). progress: None (a bar on a terminal), False, or a callable f(t, t_end) (s).
    A Simulation holds live C state: it cannot be copied or pickled (copy its scenario:
    Simulation(sim.scenario)). Use it from one thread at a time; separate Simulations run in
    parallel threads (the library releases the GIL) or processes."""

    def __init__(self, scenario: Union[Scenario, "Scene", PathLike], output: Optional[PathLike] = None,  # noqa: F821
                 progress: Any = None) -> None:
        self._sim = None
        self._finished: Optional[Run] = None
        self._started = False
        self._over = False
        self.output = os.fspath(output) if output is not None else None
        self.scenario = _as_scenario(scenario)  # our own copy: later changes to the caller's stay there
        if self.output is not None:
            self.scenario.set("output.file", self.output)
        self.scenario.validate()
        lib = _lib.lib()
        err = _lib.Error()
        sim = lib.rd_sim_create(self.scenario._h, ctypes.byref(err))
        if not sim:
            raise RockdemError(err.text)
        self._sim = sim
        self._rec = _Recorder(self)
        if progress is None:
            progress = _Bar() if sys.stderr.isatty() else False
        self._rec.progress = progress or None
        check(lib.rd_sim_add_observer(sim, ctypes.byref(self._rec.struct), ctypes.byref(err)), err)
        nfixed = ctypes.c_int(0)
        nfree = lib.rd_sim_body_count(sim, ctypes.byref(nfixed))
        self.bodies: Dict[str, Body] = _Names()
        for k in range(nfree + nfixed.value):
            b = Body(self, k, k if k < nfree else -1)
            self.bodies[b.name] = b

    def _handle(self) -> int:
        if not self._sim:
            raise RockdemError("rockdem: this Simulation is closed")
        return self._sim

    # --- state ---------------------------------------------------------------------------
    @property
    def t(self) -> float:
        """Simulated time since the start of shaking, s (0 before and while settling)."""
        return _lib.lib().rd_sim_time(self._handle())

    @property
    def end_time(self) -> float:
        """Time the shaking stage ends at, s (its duration, or longer with a tail); NaN before
        the scene has settled."""
        return _lib.lib().rd_sim_end_time(self._handle())

    @property
    def dt(self) -> float:
        """Time step, s."""
        return _lib.lib().rd_sim_dt(self._handle())

    @property
    def joints(self) -> List[Joint]:
        """The joints so far (pairs of bodies that came near each other)."""
        return [Joint(self, k) for k in range(_lib.lib().rd_sim_joint_count(self._handle()))]

    @property
    def energy(self) -> Dict[str, float]:
        """Energies of the last step, J: kinetic, gravitational, elastic, friction, damping,
        ground_work, residual (balance residual)."""
        e = (ctypes.c_double * _lib.RD_NENERGY)()
        _lib.lib().rd_sim_energy(self._handle(), e)
        return dict(zip(_lib.ENERGY, e[:]))

    @property
    def running(self) -> bool:
        """False once the shaking stage is over (its end, a stop, overturning, a failure)."""
        return not self._over

    # --- callbacks -----------------------------------------------------------------------
    def add_callback(self, fn: Callback, every: int = 1) -> "Simulation":
        """Call fn(sim, sample) every `every` samples (one sample each `model output interval`
        s of shaking, rd_sample: time s, position m, quaternion, velocity m/s, angular_velocity
        rad/s, tilt rad, rotation rad, ground_* m/s^2 m/s m, energy J). An exception raised by fn
        stops the run and is raised again by the call that was stepping."""
        if not callable(fn):
            raise TypeError("rockdem: add_callback expects a callable f(sim, sample)")
        every = count_arg("every", every, 1, 2 ** 31 - 1)
        self._rec.callbacks.append([fn, every, 0])
        return self

    # --- stepping ------------------------------------------------------------------------
    def _call(self, fn: Callable[[], int]) -> int:
        """fn() (a C call that may run long); from the main thread it runs in a worker thread so
        that Ctrl-C reaches Python: the run is then stopped at its next step, finished (its file
        complete, status interrupted) and KeyboardInterrupt raised."""
        if threading.current_thread() is not threading.main_thread():
            return self._after(fn())
        box: Dict[str, Any] = {}

        def work() -> None:
            try:
                box["rc"] = fn()
            except BaseException as e:  # noqa: B902
                box["exc"] = e
        th = threading.Thread(target=work, name="rockdem-run", daemon=True)
        th.start()
        try:
            while th.is_alive():
                th.join(0.05)
        except KeyboardInterrupt:
            _lib.lib().rd_sim_stop(self._sim)
            th.join()
            self._over = True
            self.finish(raise_failed=False)
            raise
        if "exc" in box:
            raise box["exc"]
        return self._after(box["rc"])

    def _after(self, rc: int) -> int:
        if not rc:
            self._over = True
        if self._rec.error is not None:
            e, self._rec.error = self._rec.error, None
            self.finish(raise_failed=False)
            raise e
        return rc

    def _start(self) -> None:
        """Open the run file (if any) and settle: the first step() or run_until() does it, so a
        Simulation closed unstarted writes nothing and settles nothing."""
        if not self._started:
            sim = self._handle()
            if self.output is not None:
                err = _lib.Error()
                check(_lib.lib().rd_sim_write_hdf5(sim, os.fsencode(self.output),
                                                   ctypes.byref(err)), err)
            self._started = True
            self._call(lambda: _lib.lib().rd_sim_start(sim))

    def step(self, n: int = 1) -> "Simulation":
        """Take n shaking steps (settling the scene first, the first time), fewer if the run
        ends. n: 0 to 1e9 steps."""
        n = count_arg("n", n, 0, STEP_BUDGET)
        self._start()
        if n and not self._over:
            sim = self._handle()
            self._call(lambda: _lib.lib().rd_sim_advance(sim, n, math.inf))
        return self

    def run_until(self, t: float) -> "Simulation":
        """Shake until the time reaches t (s since the start of shaking, to within half a
        step) or the run ends; settles the scene first, the first time."""
        t = time_arg("t", t)
        self._start()
        if not self._over:
            sim = self._handle()
            self._call(lambda: _lib.lib().rd_sim_advance(sim, -1, t))
        return self

    def stop(self) -> None:
        """Ask the run to stop at its next step (safe from a callback or another thread)."""
        _lib.lib().rd_sim_stop(self._handle())

    def run(self) -> Run:
        """Run to the end and finish (see finish)."""
        self.run_until(math.inf)
        return self.finish()

    def finish(self, raise_failed: bool = True) -> Run:
        """Summarise and end the run (the HDF5 file, if any, is complete); a run finished before
        its end is 'interrupted'. Returns the Run (summary, events, in-memory histories);
        raises RockdemError for a failed run (unstable, penetrated, lost, untrusted, I/O or
        memory error) unless raise_failed is False. Later calls return the same Run."""
        if self._finished is None:
            self._start()  # an unstarted run settles first (rd_sim_finish would too)
            lib = _lib.lib()
            sim = self._handle()
            status = STATUS[lib.rd_sim_finish(sim)]
            self._over = True
            summ = _lib.Summary()
            lib.rd_sim_summary(sim, ctypes.byref(summ))
            summary = summary_dict(summ)
            n = ctypes.c_int(0)
            ev = lib.rd_sim_events(sim, ctypes.byref(n))
            events = [(ev[k].time, ev[k].body, ev[k].type.decode(), ev[k].value)
                      for k in range(n.value)]
            message = (lib.rd_sim_error(sim) or b"").decode("utf-8", "replace")
            free = [b.name for b in self.bodies if not b.fixed]
            self._finished = Run(self.output, summary, events, samples=self._rec.samples,
                                 body_names=free, joints=[j.state() for j in self.joints],
                                 message=message,
                                 precariousness={b.name: b.precariousness for b in self.bodies
                                                 if not b.fixed})
            if isinstance(self._rec.progress, _Bar):
                self._rec.progress.done()
        if raise_failed and self._finished.status in FAILED:
            raise RockdemError("%s: %s" % (self.scenario.name, self._finished.message))
        return self._finished

    def close(self) -> None:
        """Free the C simulation; a started run is finished first, so its file is complete
        (status interrupted if it had not reached its end)."""
        if self._sim:
            if self._finished is None and self._started:
                self.finish(raise_failed=False)
            sim, self._sim = self._sim, None
            _lib.lib().rd_sim_free(sim)

    def __enter__(self) -> "Simulation":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:  # noqa: BLE001 (interpreter shutdown)
            pass

    def __copy__(self) -> "Simulation":
        raise TypeError("rockdem: a Simulation holds a running C state and cannot be copied; "
                        "build another one from its scenario: Simulation(sim.scenario)")

    def __deepcopy__(self, memo: dict) -> "Simulation":
        return self.__copy__()

    def __reduce__(self) -> Any:
        raise TypeError("rockdem: a Simulation cannot be pickled (it holds a running C state); "
                        "pickle its scenario (sim.scenario) or its result (a Run)")

    def __repr__(self) -> str:
        return "<rockdem.Simulation %s: t = %.4g s, %d bodies>" % (
            self.scenario.name, self.t if self._sim else float("nan"), len(self.bodies))


def _as_scenario(x: Any) -> Scenario:
    """A private copy of x: a Scenario, a Scene (built) or a path to a scenario file."""
    if isinstance(x, Scenario):
        return x.copy()
    if hasattr(x, "build") and hasattr(x, "lines"):
        return x.build()
    if isinstance(x, (str, os.PathLike)):
        return Scenario.load(x)
    raise TypeError("rockdem: a Simulation is built from a Scenario, a Scene or a scenario file "
                    "path, got %s" % type(x).__name__)


class _Bar:
    """t / t_end with an ETA on stderr, at most twice a second."""

    def __init__(self) -> None:
        self.t0 = time.monotonic()
        self.last = 0.0

    def __call__(self, t: float, end: float) -> None:
        now = time.monotonic()
        if now - self.last < 0.5 or not end > 0:
            return
        self.last = now
        f = min(max(t / end, 0.0), 1.0)
        eta = (now - self.t0) * (1 - f) / f if f > 0 else float("nan")
        sys.stderr.write("\r  t = %.3g / %.3g s  %3.0f %%  ETA %.0f s " % (t, end, 100 * f, eta))
        sys.stderr.flush()

    def done(self) -> None:
        if self.last:
            sys.stderr.write("\n")
