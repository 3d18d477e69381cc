# %% [markdown]
# # A PBR study from Python
#
# Jupyter-style (cells marked `# %%`: open it with Jupyter + jupytext or VS Code, or run it as
# a script). It loads the shipped precariously balanced rock (`scenarios/pbr.dat`), runs it over
# pulse amplitudes and frequencies in a pool of worker processes (each Scenario pickled to its
# worker and parsed again there), gathers the summaries in a table, steps one run from Python
# with a callback and reads its bodies, joints and events, reads a run's time histories as an
# xarray Dataset, and asks the library for the minimum overturning amplitude of a block built
# in code.
#
# From the repository: `make python` (builds build/librockdem.so), then
# `/usr/bin/python3 docs/examples/pbr_study.py`. From a virtual environment:
# `python3 -m venv --system-site-packages venv && venv/bin/pip install --no-deps ./tools`.

# %%
import concurrent.futures
import multiprocessing
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "tools"))  # not needed once pip-installed
import numpy as np
import rockdem

QUICK = os.environ.get("ROCKDEM_EXAMPLE_QUICK") == "1"  # the test suite runs a shorter loop
out = tempfile.mkdtemp(prefix="pbr_study_")

# %% [markdown]
# ## The study: amplitude x frequency of a one-sine pulse

# %%
amplitudes_g = [0.25, 0.45] if QUICK else [0.2, 0.3, 0.4, 0.5, 0.6]
frequencies = [2.0] if QUICK else [1.0, 2.0]


def one_run(job):
    """One case, in a worker process: the Scenario arrives pickled (its text and overrides)."""
    sc, path = job
    run = sc.run(path, progress=False)
    rock = run.summary["bodies"]["rock"]
    return (rock["max_tilt_ratio"], rock["overturned"], 1e3 * rock["max_slide"],
            run.summary["wall_seconds"], path)


jobs, cases = [], []
for f in frequencies:
    for a in amplitudes_g:
        sc = rockdem.Scenario.load(os.path.join(REPO, "scenarios", "pbr.dat"))
        sc.update({"motion.amplitude": "%gg" % a, "motion.frequency": f,
                   "model.duration": 1.5 if QUICK else 4})
        jobs.append((sc, os.path.join(out, "pbr_%gg_%gHz.h5" % (a, f))))
        cases.append((f, a))
if __name__ == "__main__":
    spawn = multiprocessing.get_context("spawn")  # fork works as well; spawn is the strictest
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=spawn) as pool:
        results = list(pool.map(one_run, jobs))

    print("%6s %6s %14s %10s %14s %8s" % ("f (Hz)", "a (g)", "max tilt/alpha", "overturned",
                                           "max slide (mm)", "wall (s)"))
    for (f, a), (r, o, s, w, _) in zip(cases, results):
        print("%6.1f %6.2f %14.3f %10s %14.3f %8.2f" % (f, a, r, "yes" if o else "no", s, w))
    last_file = results[-1][4]

# %% [markdown]
# ## Stepping a run from Python: bodies, joints, a callback, events

# %%
if __name__ == "__main__":
    sc = rockdem.Scenario.load(os.path.join(REPO, "scenarios", "pbr.dat"))
    sc.update({"motion.amplitude": "0.5g", "motion.frequency": 1.0,
               "model.duration": 1.5 if QUICK else 4})
    peaks = []                                   # the rock's tilt every 20 samples (0.1 s)
    with rockdem.Simulation(sc) as sim:          # no file: results in memory
        sim.add_callback(lambda s, d: peaks.append((d["time"], d["tilt"][0])), every=20)
        rock = sim.bodies["rock"]
        print("rock: %.0f kg, %.3f m tall; pedestal fixed: %s"
              % (rock.mass, rock.size[2], sim.bodies["pedestal"].fixed))
        sim.run_until(0.5)                        # settles, then shakes to t = 0.5 s
        print("t = %.3f s: rock at z = %.4f m, alpha = %.2f deg, speed %.4f m/s"
              % (sim.t, rock.position[2], np.degrees(rock.alpha), np.linalg.norm(rock.velocity)))
        run = sim.run()                           # on to the end
    (joint,) = run.joints                         # the Run keeps what the joints did
    print("tilt every 0.1 s (mrad):", " ".join("%.1f" % (1e3 * t) for _, t in peaks[:12]))
    print("joint %s-%s: max slip %.2f mm, max opening %.2f mm"
          % (joint["a"], joint["b"], 1e3 * joint["max_slip"], 1e3 * joint["max_opening"]))
    print(run.events.groupby("type").size().to_string())

# %% [markdown]
# ## One run's time histories: numpy arrays and an xarray Dataset

# %%
if __name__ == "__main__":
    h = run.histories()                           # in memory: the same arrays as a run file's
    print("samples:", h["time"].shape[0], "; tilt / alpha peaks at %.3f (t = %.2f s)"
          % (np.nanmax(h["tilt_ratio"][:, 0]), h["time"][np.nanargmax(h["tilt_ratio"][:, 0])]))
    ds = rockdem.open_run(last_file)              # a run file of the pool, as a Dataset
    print(ds["tilt"].sel(body="rock").to_series().describe()[["count", "max"]].to_string())
    print("dimensions:", dict(ds.sizes))
    gr = rockdem.open_run(last_file, "ground")
    print("/ground coordinates:", {k: gr[k].attrs.get("units", "") for k in gr.coords})

# %% [markdown]
# ## A block built in code, and its minimum overturning amplitude (rigid reference engine)

# %%
if __name__ == "__main__":
    block = (rockdem.Scene("a 0.4 x 0.4 x 1.6 m block on a pad")
             .brick("pad", size=(4, 4, 0.5), position=(0, 0, -0.25), fixed=True)
             .brick("block", size=(0.4, 0.4, 1.6), position=(0, 0, 0.8))
             .contact(kn=1e10, ks=1e9, friction=40)
             .pulse("one-sine", amplitude="0.3g", frequency=2)
             .solve(3)).build(os.path.join(out, "block.dat"))
    th = rockdem.threshold(block, engine="reference")
    print("block: minimum overturning amplitude %.3f g = %.3f x g tan(alpha) (w/p = %.2f, %d runs)"
          % (th["amplitude"] / 9.80665, th["ratio"], th["w_over_p"], th["runs"]))
