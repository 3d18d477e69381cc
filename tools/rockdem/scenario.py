"""A parsed scenario (the C rd_scenario) that copies, pickles and crosses processes safely.

A Scenario keeps what made it: the scenario text, the name that anchors its relative paths
(mesh files, records) and the overrides applied since, in order. A copy, a deep copy or an
unpickled Scenario (multiprocessing with spawn or forkserver) parses that text again into a C
scenario of its own and replays the overrides: nothing of the C side is ever shared, so a
setting on a copy never reaches the original and each handle is freed exactly once."""
from __future__ import annotations

import ctypes
import os
import threading
from typing import Any, Iterable, Mapping, Optional, Tuple, Union

from . import _lib

PathLike = Union[str, "os.PathLike[str]"]
Value = Union[str, int, float]


class RockdemError(RuntimeError):
    """A one-line error from the library (file:line: problem) or from the rockdem program."""


def check(rc: int, err: _lib.Error) -> None:
    """Raise RockdemError with the library's message when rc is not 0."""
    if rc != 0:
        raise RockdemError(err.text or "rockdem: failed")


def _text_arg(what: str, text: str) -> bytes:
    """text as the C side reads it (UTF-8, NUL-terminated): a NUL inside would cut it short."""
    if not isinstance(text, str):
        raise TypeError("rockdem: %s must be a str, got %s" % (what, type(text).__name__))
    if "\0" in text:
        raise RockdemError("rockdem: %s contains a NUL byte at offset %d (the scenario language "
                           "is text)" % (what, text.index("\0")))
    return text.encode("utf-8")


def _value_text(key: str, value: Value) -> str:
    """An override's value as the scenario language writes it (numbers exactly: repr)."""
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise TypeError("rockdem: the value of %s must be a str or a number, got %s"
                    % (key, type(value).__name__))


class Scenario:
    """A parsed scenario. Build with Scenario.load(path), Scenario.from_text(text) or
    Scene(...).build(); change it with set(); run it with run() or Simulation(scenario).

    Attributes: text (the scenario text), name (its file name: relative paths inside it are
    taken from its folder), overrides (the "key=value" assignments applied, in order)."""

    def __init__(self, text: str, name: str = "scenario.dat",
                 overrides: Iterable[str] = ()) -> None:
        """Parse text (a whole scenario) named name, then apply the overrides in order."""
        self.text = text
        self.name = os.fspath(name)
        self.overrides: list = []
        self._lock = threading.Lock()  # one C call at a time on this handle
        self._h = None
        h = _lib.lib().rd_scenario_new()
        if not h:
            raise MemoryError("rockdem: cannot allocate a scenario")
        self._h = h
        err = _lib.Error()
        check(_lib.lib().rd_scenario_parse(self._h, os.fsencode(self.name),
                                           _text_arg(self.name, text), ctypes.byref(err)), err)
        for o in overrides:
            self.set(o)

    @property
    def source(self) -> str:
        """The scenario's file name (as messages name it)."""
        return self.name

    @classmethod
    def load(cls, path: PathLike) -> "Scenario":
        """Parse a scenario file (relative paths inside it: from its folder). A file that cannot
        be read, is not UTF-8 or holds a NUL byte raises RockdemError naming it."""
        path = os.fspath(path)
        try:
            with open(path, "rb") as f:
                raw = f.read()
        except OSError as e:
            raise RockdemError("%s: cannot read: %s" % (path, e.strerror or e)) from None
        if b"\0" in raw:
            raise RockdemError("%s: contains a NUL byte (not a text file?)" % path)
        try:
            text = raw.decode("utf-8")
        except UnicodeDecodeError as e:
            raise RockdemError("%s: not UTF-8 text (byte %d)" % (path, e.start)) from None
        return cls(text, path)

    @classmethod
    def from_text(cls, text: str, name: str = "scenario.dat") -> "Scenario":
        """Parse scenario text; name names it in messages and its folder anchors relative
        paths (mesh files, records)."""
        return cls(text, name)

    def set(self, key: str, value: Optional[Value] = None) -> "Scenario":
        """Override one key: set("motion.amplitude", "0.4g") or set("motion.amplitude=0.4g").
        The keys and their units are those of `rockdem keys` (rockdem.keys(); --set on the
        command line); every value is range-checked by the library as on the command line."""
        if not isinstance(key, str):
            raise TypeError("rockdem: a key must be a str, got %s" % type(key).__name__)
        assignment = key if value is None else "%s=%s" % (key, _value_text(key, value))
        err = _lib.Error()
        with self._lock:
            check(_lib.lib().rd_scenario_set(self._h, _text_arg("override", assignment),
                                             ctypes.byref(err)), err)
        self.overrides.append(assignment)
        return self

    def update(self, overrides: Union[Mapping[str, Value], Iterable[str]]) -> "Scenario":
        """set() every item of a dict, or of an iterable of "key=value" strings."""
        items = overrides.items() if isinstance(overrides, Mapping) else ((o, None) for o in overrides)
        for k, v in items:
            self.set(k, v)
        return self

    def validate(self) -> None:
        """Check the whole scenario as `rockdem check` does before building (RockdemError)."""
        err = _lib.Error()
        with self._lock:
            check(_lib.lib().rd_scenario_validate(self._h, ctypes.byref(err)), err)

    def copy(self) -> "Scenario":
        """A real copy: the text parsed again, the overrides replayed (its own C scenario)."""
        return Scenario(self.text, self.name, self.overrides)

    __copy__ = copy

    def __deepcopy__(self, memo: dict) -> "Scenario":
        return self.copy()

    def __reduce__(self) -> Tuple[Any, ...]:
        """Pickle as what made it (text, name, overrides): unpickling parses it again."""
        return (Scenario, (self.text, self.name, list(self.overrides)))

    def run(self, output: Optional[PathLike] = None, progress: Any = None, every: int = 1,
            callback: Any = None) -> "Run":  # noqa: F821 (results.Run)
        """Settle and shake in this process (rockdem.Simulation); with output, write the HDF5
        run file there as `rockdem run -o` does. Returns a Run: summary, events, histories (in
        memory when there is no file). progress: None (a bar on a terminal), False, or a
        callable f(t, t_end) (s). Ctrl-C stops the run at its next step, completes the file
        and raises KeyboardInterrupt. A failed run (unstable, penetrated, lost, untrusted,
        I/O or memory error) raises RockdemError with its cause."""
        from .simulation import Simulation
        sim = Simulation(self, output=output, progress=progress)
        try:
            if callback is not None:
                sim.add_callback(callback, every=every)
            return sim.run()
        finally:
            sim.close()

    def __del__(self) -> None:
        h, self._h = getattr(self, "_h", None), None
        if h:
            _lib.lib().rd_scenario_delete(h)

    def __repr__(self) -> str:
        return "<rockdem.Scenario %s%s>" % (self.name, (" + %d overrides" % len(self.overrides))
                                            if self.overrides else "")
