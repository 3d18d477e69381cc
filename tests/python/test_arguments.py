"""Every argument is range-checked as the command line checks it: a bad value raises one clear
error at once, never a hang (threshold(steps=10**9) ran a billion-step scan before), a crash or a
silent default."""
import math

import pytest

import rockdem


@pytest.fixture
def sc(block_file):
    return rockdem.Scenario.load(block_file)


@pytest.mark.parametrize("kw, err", [
    ({"steps": 10 ** 9}, ValueError), ({"steps": 0}, ValueError), ({"steps": 2.5}, TypeError),
    ({"jobs": 0}, ValueError), ({"jobs": 257}, ValueError), ({"rtol": 0.0}, ValueError),
    ({"rtol": 2.0}, ValueError), ({"lo": -1.0}, ValueError), ({"hi": 1e12}, ValueError),
    ({"lo": "fast"}, ValueError), ({"engine": "rigid"}, ValueError),
    ({"frequencies": [-1.0]}, ValueError), ({"frequencies": []}, ValueError),
    ({"steps": True}, TypeError),
])
def test_threshold_refuses(sc, kw, err):
    with pytest.raises(err):
        rockdem.threshold(sc, **kw)


def test_threshold_c_side_refuses_a_huge_scan(sc):
    """The library's own bound (a C caller, or the CLI), not only Python's."""
    import ctypes
    from rockdem import _lib
    lib = _lib.lib()
    opts = lib.rd_threshold_opts_default()
    opts.nscan = 10 ** 9
    res, err = _lib.ThresholdResult(), _lib.Error()
    assert lib.rd_threshold(sc._h, 1, ctypes.byref(opts), ctypes.byref(res), ctypes.byref(err)) != 0
    assert "1000" in err.text


def test_cli_refuses_a_huge_scan(block_file):
    import subprocess
    p = subprocess.run([rockdem.program(), "threshold", block_file, "--steps", "1000000000"],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=30)
    assert p.returncode != 0 and "1 to 1000" in p.stderr


@pytest.mark.parametrize("call, err", [
    (lambda s: s.step(-1), ValueError), (lambda s: s.step(10 ** 10), ValueError),
    (lambda s: s.step(1.5), TypeError), (lambda s: s.run_until(-1.0), ValueError),
    (lambda s: s.run_until(math.nan), ValueError), (lambda s: s.run_until("1"), TypeError),
    (lambda s: s.add_callback(print, every=0), ValueError),
    (lambda s: s.add_callback(3), TypeError),
])
def test_simulation_refuses(block_file, call, err):
    with rockdem.Simulation(block_file) as sim:
        with pytest.raises(err):
            call(sim)


@pytest.mark.parametrize("bad, want", [
    ("motion.nonsense=1", "unknown key"), ("motion.frequency=0", "motion.frequency"),
    ("model.duration=1e99", "model.duration"),
])
def test_set_refuses(sc, bad, want):
    with pytest.raises(rockdem.RockdemError, match=want):
        sc.set(bad)
    assert sc.overrides == []


def test_nul_byte_refused():
    with pytest.raises(rockdem.RockdemError, match="NUL byte at offset 11"):
        rockdem.Scenario.from_text("model title\0 'x'\n")


def test_set_value_types(sc):
    with pytest.raises(TypeError):
        sc.set("motion.amplitude", [1, 2])
    with pytest.raises(TypeError):
        sc.set(3, 4)


def test_errors_are_one_line(tmp_path):
    for bad, want in ((lambda: rockdem.Scenario.from_text("block create brick size -1 1 1\n"),
                       "scenario.dat:1"),
                      (lambda: rockdem.Scenario.load(str(tmp_path / "nope.dat")), "nope.dat")):
        with pytest.raises(rockdem.RockdemError) as e:
            bad()
        assert want in str(e.value) and "\n" not in str(e.value)


def test_simulation_from_wrong_type():
    with pytest.raises(TypeError, match="Scenario"):
        rockdem.Simulation(42)
