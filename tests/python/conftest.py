"""pytest fixtures for the Python binding (tools/rockdem): the repository's library (or
$ROCKDEM_LIB, which tests/cli/pytest.sh sets from RD_BUILD) and small scenes to run."""
import os
import subprocess
import sys
import tempfile
import textwrap

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TOOLS = os.path.join(REPO, "tools")
sys.path.insert(0, TOOLS)
os.environ.setdefault("ROCKDEM_LIB", os.path.join(REPO, "build", "librockdem.so"))
os.environ.setdefault("ROCKDEM_BIN", os.path.join(REPO, "bin", "rockdem"))

# A 0.4 x 0.4 x 1.6 m block (alpha = atan(0.25) = 0.245 rad) on a pad, soft joint (KN 1e9 Pa/m)
# so the step is 7.4e-5 s and 1 s of shaking takes about half a second of CPU.
BLOCK = """model title 'python test: a slender block on a pad'
block create brick size 4 4 0.5 position 0 0 -0.25 fixed name pad
block create brick size 0.4 0.4 1.6 position 0 0 0.8 name block
contact property stiffness-normal 1e9 stiffness-shear 1e8 friction 40
ground-motion pulse one-sine amplitude 0.35g frequency 2 direction 0
model solve time 1
output hdf5 'x.h5' interval 0.01
"""


@pytest.fixture
def block_file(tmp_path):
    p = tmp_path / "block.dat"
    p.write_text(BLOCK)
    return str(p)


def run_python(code, timeout=120, **kw):
    """code in a fresh /usr/bin/python3 (sys.executable) with tools/ on its path: a crash there
    (abort, segfault, hang) fails the test instead of killing pytest. CompletedProcess."""
    env = dict(os.environ, PYTHONPATH=TOOLS + os.pathsep + os.environ.get("PYTHONPATH", ""))
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as f:
        f.write(textwrap.dedent(code))  # a file, not -c: spawn's children import its functions
    try:
        return subprocess.run([sys.executable, f.name], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True, timeout=timeout, **kw)
    finally:
        os.unlink(f.name)
