#!/usr/bin/python3
"""rdplot — one rockdem run on one PNG: tilt/alpha and base slide per body, ground acceleration
and velocity, energies (kinetic, gravitational, elastic, friction, damping, ground_work, residual)
against time, with the events (uplift, impact, slip, overturn) marked."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rdtools import cli  # noqa: E402


def main():
    p = cli.Parser(prog="rdplot", description=cli.describe(__doc__))
    p.add_argument("run", metavar="RUN.h5", help="HDF5 file written by 'rockdem run'")
    p.add_argument("-o", "--output", metavar="OUT.png",
                   help="PNG to write (default: RUN.png next to the run file)")
    p.add_argument("--dpi", type=int, default=300,
                   help="resolution (default 300, print quality: 2160 px across the 7.2 in page width)")
    a = p.parse_args()
    from rdtools.plot import plot_run
    out = a.output or os.path.splitext(a.run)[0] + ".png"
    cli.ensure_writable(out)
    plot_run(a.run, out, dpi=a.dpi)
    print("wrote %s" % out)


if __name__ == "__main__":
    sys.exit(cli.run(main, "rdplot"))
