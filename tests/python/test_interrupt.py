"""Ctrl-C during a run raises KeyboardInterrupt at the next step and leaves a valid run file
(status 'interrupted', every sample so far). Before, SIGINT only set the library's stop flag from
a Python handler that could not run until the C call returned: Ctrl-C was ignored."""
import os
import signal
import subprocess
import sys

import h5py

from conftest import TOOLS


def test_ctrl_c_raises_and_keeps_the_file(tmp_path, block_file):
    out = str(tmp_path / "int.h5")
    code = (
        "import sys, rockdem\n"
        "sc = rockdem.Scenario.load(%r).set('model.duration', 1000)\n"  # 1000 s: minutes of CPU
        "def ready(sim, s):\n"
        "    if s['time'] >= 0.05: print('running', flush=True); sim.add_callback(lambda *a: 0)\n"
        "try:\n"
        "    sc.run(%r, progress=False, callback=ready, every=5)\n"
        "except KeyboardInterrupt:\n"
        "    print('KeyboardInterrupt', flush=True); sys.exit(130)\n" % (block_file, out))
    env = dict(os.environ, PYTHONPATH=TOOLS)
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, env=env)
    line = p.stdout.readline()
    assert line.strip() == "running", p.stderr.read()
    p.send_signal(signal.SIGINT)
    try:
        rest, err = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        p.kill()
        raise AssertionError("Ctrl-C ignored: the run went on for 30 s")
    assert p.returncode == 130 and "KeyboardInterrupt" in rest, err
    with h5py.File(out, "r") as f:
        assert "summary" in f, "no /summary in %s: %s; stderr: %s" % (out, list(f), err)
        status = f["summary"].attrs["status"]
        names = {int(v): k for k, v in h5py.check_enum_dtype(f["summary"].attrs.get_id("status").dtype).items()}
        assert names[int(status)] == "interrupted", dict(f["summary"].attrs)
        assert f["time"].shape[0] >= 5 and f["time"][-1] < 1000
