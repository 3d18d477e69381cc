"""The Scene builder writes every command of the scenario language (README, "A scenario, line
by line") and the library parses what it writes; a built scene runs as its text does."""
import numpy as np
import pytest

import rockdem

CUBE_OBJ = "".join("v %g %g %g\n" % (x, y, z) for x in (-.2, .2) for y in (-.2, .2) for z in (0, .4)) + \
    "f 1 2 3\nf 2 4 3\nf 5 7 6\nf 6 7 8\nf 1 5 2\nf 2 5 6\nf 3 4 7\nf 4 8 7\nf 1 3 5\nf 3 7 5\nf 2 6 4\nf 4 6 8\n"


def full_scene(folder):
    """A scene using every builder method once (values inside their ranges)."""
    (folder / "cube.obj").write_text(CUBE_OBJ)
    t = np.arange(0, 1, 0.01)
    (folder / "rec.txt").write_text("\n".join("%g" % v for v in 0.1 * np.sin(2 * np.pi * 2 * t)) + "\n")
    return (rockdem.Scene("every command", folder=str(folder))
            .preset("3dec")
            .gravity(9.81).density(2600).damping("viscous", 0.05).timestep(safety=0.2)
            .settle(True, ratio=1e-5, time_limit=4).overturn("tilt-ratio", 1.0, stop=True)
            .brick("base", size=(12, 4, 0.5), position=(0, 0, -0.25), fixed=True, group="rock")
            .brick("block", size=(0.4, 0.4, 1.2), seat_on="base", at=(-4, 0), rotation=(0, 0, 10),
                   mass=500, group="blocks")
            .prism("drum", sides=12, radius=0.3, radius_top=0.27, height=0.5, seat_on="base",
                   at=(-2.5, 0), group="blocks")
            .polyhedron("wedge", [(0, 0, 0), (0.4, 0, 0), (0, 0.4, 0), (0, 0, 0.4)],
                        seat_on="base", at=(-1, 1), density=2500)
            .mesh("rock", "cube.obj", seat_on="base", density=2700)
            .column(drums=2, diameter=0.5, height=1.0, sides=12, taper=0.9, plinth=(0.8, 0.2),
                    capital=0.2, abacus=(0.8, 0.1), seat_on="base", at=(2, 0), name="c")
            .stack(lower=(0.6, 0.6, 0.4), upper=(0.3, 0.3, 0.6), seat_on="base", at=(4, 0),
                   name="statue")
            .initial("block", tilt=1, direction=0, velocity=(0, 0, 0), angular_velocity=(0, 0, 0))
            .contact(kn=1e9, ks=1e8, friction=35, spacing="vertices", cohesion=0, tension=0,
                     restitution=0)
            .contact(kn=5e8, ks=5e7, friction=30, damping=0, range=("rock", "blocks"))
            .history_interval(0.01).history_body("block", "all")
            .history_joint("base", "block", "normal-force", "slip").history_energy()
            .record("rec.txt", units="g", dt=0.01, direction=0, scale=1.0, baseline="off")
            .solve(0.5, tail=1).output("full.h5", 0.01)
            .save(str(folder / "settled.h5")).reference_restitution(0.9))


def test_every_command_parses_and_builds(tmp_path):
    scene = full_scene(tmp_path)
    assert len(scene.lines) == 27
    sc = scene.build()
    sc.validate()
    with rockdem.Simulation(sc) as sim:
        names = [b.name for b in sim.bodies]
        assert {"base", "block", "drum", "wedge", "rock", "c-plinth", "c-d1", "c-d2",
                "c-capital", "c-abacus", "statue-lower", "statue-upper"} == set(names)
        assert abs(sim.bodies["block"].mass - 500) < 1e-9 * 500 and sim.bodies["base"].fixed  # round-off of the mass scaling


def test_other_motions_and_restore(tmp_path):
    for extra in (lambda s: s.pulse("harmonic", "0.1g", frequency=2, cycles=2, start=0.1),
                  lambda s: s.pulse("rectangular", 0.5, duration=0.2, vertical=True),
                  lambda s: s.stochastic(seed=3, pga="0.1g", duration=2, dt=0.01)):
        s = (rockdem.Scene(folder=str(tmp_path)).timestep(fixed=1e-4).damping("none")
             .brick("pad", (2, 2, 0.5), (0, 0, -0.25), fixed=True).brick("b", (0.4, 0.4, 0.8), seat_on="pad")
             .solve(0.2))
        extra(s).build().validate()
    rockdem.Scene().brick("b", (1, 1, 1), (0, 0, 0.5)).restore("state.h5").build()


def test_builder_refuses_bad_arguments():
    s = rockdem.Scene()
    for bad in (lambda: s.brick("b", (1, 1), (0, 0, 0)), lambda: s.brick("b", (1, 1, 1)),
                lambda: s.brick("b", (1, 1, 1), (0, 0, 0), seat_on="x"),
                lambda: s.brick("b", (1, 1, 1), (0, 0, 0), density=1, mass=1),
                lambda: s.preset("soft"), lambda: s.damping("viscous"),
                lambda: s.title("it's"), lambda: s.contact(damping=0.1)):
        with pytest.raises((ValueError, TypeError)):
            bad()
    with pytest.raises(rockdem.RockdemError, match="scene.dat:1"):
        rockdem.Scene().brick("b", (-1, 1, 1), (0, 0, 0)).build()


def test_built_scene_runs_as_its_file(tmp_path, block_file):
    s = (rockdem.Scene("python test: a slender block on a pad", folder=str(tmp_path))
         .brick("pad", size=(4, 4, 0.5), position=(0, 0, -0.25), fixed=True)
         .brick("block", size=(0.4, 0.4, 1.6), position=(0, 0, 0.8))
         .contact(kn=1e9, ks=1e8, friction=40)
         .pulse("one-sine", amplitude="0.35g", frequency=2, direction=0)
         .solve(1).output("x.h5", 0.01))
    a = s.build().run(progress=False).histories()["tilt"]
    b = rockdem.Scenario.load(block_file).run(progress=False).histories()["tilt"]
    assert np.array_equal(a, b)
