"""Every public function and method of the binding has a docstring and type hints on its
parameters and return (the API reference, `make python-docs`, is built from them)."""
import inspect

import rockdem

PUBLIC = [rockdem.Scenario, rockdem.Scene, rockdem.Simulation, rockdem.Body, rockdem.Joint,
          rockdem.Run, rockdem.threshold, rockdem.sweep, rockdem.keys, rockdem.program,
          rockdem.open_run, rockdem.open_sweep, rockdem.event_table]


def _functions():
    for obj in PUBLIC:
        if inspect.isclass(obj):
            for name, f in vars(obj).items():
                if name.startswith("_") and name != "__init__":
                    continue
                f = f.fget if isinstance(f, property) else getattr(f, "__func__", f)
                if inspect.isfunction(f):
                    yield "%s.%s" % (obj.__name__, name), f
        else:
            yield obj.__name__, obj


def test_docstrings_and_hints():
    missing = []
    for name, f in _functions():
        sig = inspect.signature(f)
        params = [p for p in sig.parameters.values() if p.name not in ("self", "cls")
                  and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
        if not inspect.getdoc(f) and not name.endswith("__init__"):
            missing.append(name + ": no docstring")
        if any(p.annotation is p.empty for p in params):
            missing.append(name + ": a parameter without a type hint")
        if sig.return_annotation is sig.empty:
            missing.append(name + ": no return type hint")
    assert not missing, missing
