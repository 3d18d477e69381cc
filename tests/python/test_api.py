"""The object API: a Simulation stepped from Python gives the command line's answer bit for
bit (the engine is deterministic), its bodies and joints read the C state, callbacks come every
k samples, results stay in memory without a file, events come as a table."""
import math
import os
import subprocess

import h5py
import numpy as np
import pytest

import rockdem


@pytest.fixture(scope="module")
def cli(tmp_path_factory):
    """`rockdem run` of the block scene at 0.3 g: its run file."""
    from conftest import BLOCK
    d = tmp_path_factory.mktemp("cli")
    (d / "block.dat").write_text(BLOCK)
    out = str(d / "cli.h5")
    subprocess.run([rockdem.program(), "run", str(d / "block.dat"), "--set",
                    "motion.amplitude=0.3g", "-q", "-o", out], check=True, stdout=subprocess.DEVNULL)
    return out


def test_stepped_run_equals_the_cli(block_file, cli, tmp_path):
    sc = rockdem.Scenario.load(block_file).set("motion.amplitude", "0.3g")
    sim = rockdem.Simulation(sc, output=str(tmp_path / "py.h5"))
    sim.step(1000)                      # settle, then 1000 shaking steps
    assert abs(sim.t - 1000 * sim.dt) < 1e-9
    sim.run_until(0.5)
    assert abs(sim.t - 0.5) <= 0.5 * sim.dt
    run = sim.run()
    with h5py.File(cli, "r") as c, h5py.File(run.path, "r") as p:
        assert np.array_equal(c["tilt"][()], p["tilt"][()])
        assert c["summary"].attrs["max_tilt"][0] == run.summary["bodies"]["block"]["max_tilt"]
    h = run.histories()                 # in memory: the same samples as the file
    with h5py.File(cli, "r") as c:
        assert np.array_equal(h["tilt"], c["tilt"][()]) and np.array_equal(h["time"], c["time"][()])
        assert np.array_equal(h["energy_kinetic"], c["energy/kinetic"][()])
    sim.close()


def test_histories_from_the_file_equal_those_in_memory(block_file, tmp_path):
    sim = rockdem.Simulation(rockdem.Scenario.load(block_file), output=str(tmp_path / "r.h5"))
    run = sim.run()
    sim.close()
    mem = run.histories()
    disk = rockdem.Run(run.path, run.summary, run.event_list, body_names=run.names).histories()
    # the same names: the dimension scales linked into /ground and /energy (time, xyz) for
    # xarray are no histories
    assert sorted(disk) == sorted(mem)
    for k in mem:
        assert np.array_equal(disk[k], mem[k]), k


def test_results_in_memory_without_a_file(block_file, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    before = sorted(os.listdir(tmp_path))
    run = rockdem.Scenario.load(block_file).run(progress=False)
    assert run.path is None and sorted(os.listdir(tmp_path)) == before    # nothing written
    ds = run.dataset()
    assert ds["tilt"].dims == ("time", "body") and list(ds["body"].values) == ["block"]
    assert float(ds["max_tilt"].sel(body="block")) == run.summary["bodies"]["block"]["max_tilt"]
    # the in-memory tilt ratio peaks where the summary's does (sampled vs every step: 5 %)
    assert abs(np.nanmax(run.histories()["tilt_ratio"]) - run.summary["bodies"]["block"]["max_tilt_ratio"]) \
        < 0.05 * run.summary["bodies"]["block"]["max_tilt_ratio"]


def test_bodies_and_joints(block_file):
    with rockdem.Simulation(block_file) as sim:
        block, pad = sim.bodies["block"], sim.bodies["pad"]
        assert not block.fixed and pad.fixed and [b.name for b in sim.bodies] == ["block", "pad"]
        assert abs(block.mass - 0.4 * 0.4 * 1.6 * 2700) < 1e-9 * block.mass   # default density
        assert np.allclose(block.size, (0.4, 0.4, 1.6)) and block.alpha == 0   # before settling
        z0 = block.position[2]
        sim.run_until(0.05)
        assert abs(block.alpha - math.atan(0.25)) < 1e-3 * math.atan(0.25)   # b/h of the block
        # settled onto its joint: the centre sinks by the spring's static compression, m g / (KN A)
        sink = block.mass * 9.81 / (1e9 * 0.16)
        assert abs((z0 - block.position[2]) - sink) < 0.2 * sink
        (j,) = sim.joints
        assert (j.a, j.b) == ("pad", "block") and j.kn == 1e9 and j.closed
        assert np.allclose(pad.position, (0, 0, -0.25)) and np.all(pad.velocity == 0)
        assert set(sim.energy) >= {"kinetic", "elastic", "residual"}


def test_callbacks_every_k_samples_and_stop(block_file):
    seen = []
    with rockdem.Simulation(block_file) as sim:
        sim.add_callback(lambda s, d: seen.append(d["time"]), every=10)
        sim.add_callback(lambda s, d: s.stop() if d["time"] >= 0.3 else None)
        run = sim.run()
    assert run.status == "interrupted" and 0.3 <= run.summary["end_time"] < 0.32
    assert np.allclose(np.diff(seen), 0.1, atol=1e-3)      # output interval 0.01 s x 10


def test_callback_exception_propagates(block_file, tmp_path):
    def boom(sim, d):
        if d["time"] > 0.1:
            raise ZeroDivisionError("in the callback")
    out = str(tmp_path / "boom.h5")
    with pytest.raises(ZeroDivisionError, match="in the callback"):
        rockdem.Scenario.load(block_file).run(out, progress=False, callback=boom)
    with h5py.File(out, "r") as f:            # the file is finished and readable
        assert f["time"].shape[0] >= 10


def test_events_table(block_file):
    run = rockdem.Scenario.load(block_file).run(progress=False)
    ev = run.events
    assert list(ev.columns) == ["time", "body", "body_name", "type", "value"]
    assert "uplift" in set(ev["type"]) and set(ev["body_name"]) <= {"block", ""}
    arr = rockdem.event_table(run.event_list, run.names)
    assert len(arr) == len(ev)


def test_failed_run_raises(tmp_path):
    untrusted = ("block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base\n"
                 "block create brick size 0.5 0.5 1.0 position 0 0 0.6 name b\n"
                 "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40 restitution 1 spacing vertices\n"
                 "model timestep fixed 1.9e-4\nmodel settle off\nblock initial name b velocity 0 0 -5\n"
                 "model solve time 0.5\noutput hdf5 'x.h5' interval 0.01\n")
    with pytest.raises(rockdem.RockdemError, match="energy balance"):
        rockdem.Scenario.from_text(untrusted).run(progress=False)


def test_threshold_equals_the_cli(block_file):
    p = subprocess.run([rockdem.program(), "threshold", block_file, "--engine", "reference", "-q"],
                       stdout=subprocess.PIPE, text=True, check=True)
    cli_amp = float(p.stdout.split("amplitude ")[1].split()[0])
    th = rockdem.threshold(rockdem.Scenario.load(block_file), engine="reference")
    assert th["found"] and abs(th["amplitude"] - cli_amp) <= 1e-4 * cli_amp


def test_fragility_sweep(block_file, tmp_path):
    """A sweep at half and twice the rigid threshold: the block stands, then overturns (the DEM's
    threshold lies within a few per cent of the reference's for this slender block)."""
    th = rockdem.threshold(rockdem.Scenario.load(block_file), engine="reference")
    a = th["amplitude"] / 9.80665
    tab = rockdem.sweep(block_file, str(tmp_path / "sw.h5"),
                        scales=["%.4gg" % (0.5 * a), "%.4gg" % (2 * a)], jobs=2,
                        overrides={"model.duration": 3})
    assert tab.sizes["case"] == 2 and list(tab["overturned"].values) == [0, 1]


def test_checkpoint_restores_bit_for_bit(tmp_path):
    """`model save` after settling, then a run from `model restore`: the same shaking, to the
    bit (the checkpoint holds the settled state; tests/cli/checkpoint.sh for the CLI)."""
    state = str(tmp_path / "settled.h5")

    def scene():
        return (rockdem.Scene("checkpoint", folder=str(tmp_path))
                .brick("pad", (4, 4, 0.5), (0, 0, -0.25), fixed=True)
                .brick("block", (0.4, 0.4, 1.6), (0, 0, 0.8))
                .contact(kn=1e9, ks=1e8, friction=40).pulse("one-sine", "0.35g", 2).solve(0.5)
                .output("x.h5", 0.01))
    a = rockdem.Simulation(scene().save(state)).run()
    assert os.path.exists(state)
    sim = rockdem.Simulation(scene().restore(state))
    # before any step: the settled state, sunk by m g / (KN A) = 4.2e-5 m, not the 0.8 m placed
    sink = sim.bodies["block"].mass * 9.81 / (1e9 * 0.16)
    assert abs(0.8 - sim.bodies["block"].position[2] - sink) < 0.2 * sink
    b = sim.run()
    assert np.array_equal(a.histories()["tilt"], b.histories()["tilt"])
    assert b.summary["steps"] == a.summary["steps"]
