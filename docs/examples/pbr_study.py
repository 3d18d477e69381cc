# %% [markdown]
# # A PBR study from Python
#
# Jupyter-style (cells marked `# %%`: open it with Jupyter + jupytext or VS Code, or run it as
# a script). It loads the shipped precariously balanced rock (`scenarios/pbr.dat`), runs it in a
# loop over pulse amplitudes and frequencies with the library in this process, gathers the
# summaries in a table, reads one run's time histories as an xarray Dataset, and asks the
# library for the minimum overturning amplitude of a block built in code.
#
# From the repository: `make python` (builds build/librockdem.so), then
# `/usr/bin/python3 docs/examples/pbr_study.py`. From a virtual environment:
# `python3 -m venv --system-site-packages venv && venv/bin/pip install ./tools`.

# %%
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
rows = []
for f in frequencies:
    for a in amplitudes_g:
        sc = rockdem.Scenario.load(os.path.join(REPO, "scenarios", "pbr.dat"))
        sc.update({"motion.amplitude": "%gg" % a, "motion.frequency": f,
                   "model.duration": 1.5 if QUICK else 4})
        run = sc.run(os.path.join(out, "pbr_%gg_%gHz.h5" % (a, f)), progress=False)
        rock = run.summary["bodies"]["rock"]
        rows.append((f, a, rock["max_tilt_ratio"], rock["overturned"], 1e3 * rock["max_slide"],
                     run.summary["wall_seconds"]))

print("%6s %6s %14s %10s %14s %8s" % ("f (Hz)", "a (g)", "max tilt/alpha", "overturned",
                                       "max slide (mm)", "wall (s)"))
for f, a, r, o, s, w in rows:
    print("%6.1f %6.2f %14.3f %10s %14.3f %8.2f" % (f, a, r, "yes" if o else "no", s, w))

# %% [markdown]
# ## One run's time histories: numpy arrays and an xarray Dataset

# %%
h = run.histories()
print("samples:", h["time"].shape[0], "; tilt / alpha peaks at %.3f (t = %.2f s)"
      % (np.nanmax(h["tilt_ratio"][:, 0]), h["time"][np.nanargmax(h["tilt_ratio"][:, 0])]))
ds = run.dataset()
print(ds["tilt"].sel(body="rock").to_series().describe()[["count", "max"]].to_string())
print("dimensions:", dict(ds.sizes))
ev = rockdem.open_run(run.path, "events")
print("events:", ", ".join("%s %s" % (n, t) for n, t in
                           zip(*np.unique(ev["type"].values.astype(str), return_counts=True))))

# %% [markdown]
# ## A block built in code, and its minimum overturning amplitude (rigid reference engine)

# %%
block = (rockdem.Scene("a 0.4 x 0.4 x 1.6 m block on a pad")
         .brick("pad", size=(4, 4, 0.5), position=(0, 0, -0.25), fixed=True)
         .brick("block", size=(0.4, 0.4, 1.6), position=(0, 0, 0.8))
         .contact(kn=1e10, ks=1e9, friction=40)
         .pulse("one-sine", amplitude="0.3g", frequency=2)
         .solve(3)).build(os.path.join(out, "block.dat"))
th = rockdem.threshold(block, engine="reference")
print("block: minimum overturning amplitude %.3f g = %.3f x g tan(alpha) (w/p = %.2f, %d runs)"
      % (th["amplitude"] / 9.80665, th["ratio"], th["w_over_p"], th["runs"]))
