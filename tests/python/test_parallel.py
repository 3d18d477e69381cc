"""Scenarios and runs under multiprocessing (spawn, forkserver, fork) and in a thread pool give
the serial answer bit for bit (the engine is deterministic). Before, a Scenario sent to a spawn
Pool carried its C pointer: the child segfaulted and Pool.map never returned."""
import concurrent.futures
import multiprocessing as mp

import pytest

import rockdem
from conftest import run_python

AMPS = ["0.3g", "0.35g", "0.4g"]


def _tilt(sc):
    return sc.run(progress=False).summary["bodies"]["block"]["max_tilt_ratio"]


def _serial(block_file):
    return [_tilt(rockdem.Scenario.load(block_file).set("motion.amplitude", a)) for a in AMPS]


@pytest.mark.parametrize("method", ["spawn", "forkserver", "fork"])
def test_pool(block_file, method):
    code = """
        import multiprocessing as mp, os, rockdem
        def tilt(job):
            sc, out = job  # a file each: the test also runs against the binding before the fix
            return sc.run(out, progress=False).summary["bodies"]["block"]["max_tilt_ratio"]
        if __name__ == "__main__":
            scs = [(rockdem.Scenario.load(%r).set("motion.amplitude", a),
                    os.path.join(os.path.dirname(%r), "%%s-%%d.h5" %% (%r, k)))
                   for k, a in enumerate(%r)]
            with mp.get_context(%r).Pool(2) as p:
                print(repr(p.map_async(tilt, scs).get(100)))
    """ % (block_file, block_file, method, AMPS, method)
    p = run_python(code, timeout=150)
    assert p.returncode == 0, p.stderr[-2000:]
    assert eval(p.stdout.strip().splitlines()[-1]) == _serial(block_file)


def test_thread_pool(block_file):
    scs = [rockdem.Scenario.load(block_file).set("motion.amplitude", a) for a in AMPS]
    with concurrent.futures.ThreadPoolExecutor(3) as ex:
        got = list(ex.map(_tilt, scs))
    assert got == _serial(block_file)


def test_one_scenario_shared_by_threads(block_file):
    sc = rockdem.Scenario.load(block_file)
    with concurrent.futures.ThreadPoolExecutor(2) as ex:
        got = list(ex.map(lambda _: _tilt(sc), range(2)))
    assert got[0] == got[1] == _tilt(sc)
