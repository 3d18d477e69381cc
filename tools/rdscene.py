#!/usr/bin/python3
"""rdscene — a picture of a rockdem scene: every body of a run file drawn in 3-D at one output
sample (fixed bodies grey, free bodies in colour; axes x, y, z in metres, equal scales)."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rdtools import cli  # noqa: E402


def main():
    p = cli.Parser(prog="rdscene", description=cli.describe(__doc__))
    p.add_argument("run", metavar="RUN.h5", help="HDF5 file written by 'rockdem run'")
    p.add_argument("-o", "--output", metavar="OUT.png", help="PNG or PDF to write (default RUN.scene.png)")
    p.add_argument("--sample", type=int, default=0, help="output sample to draw (default 0: at rest)")
    p.add_argument("--title", help="title (default: the scenario's title and the time)")
    p.add_argument("--dpi", type=int, default=300, help="resolution (default 300)")
    a = p.parse_args()
    from rdtools.scene import draw_scene
    from rdtools.runfile import Run
    out = a.output or os.path.splitext(a.run)[0] + ".scene.png"
    cli.ensure_writable(out)
    with Run(a.run) as run:
        n = run.nsamples()
    if not -n <= a.sample < n:
        raise cli.RDError("%s: --sample %d: the file has %d samples" % (a.run, a.sample, n))
    draw_scene(a.run, out, sample=a.sample, title=a.title, dpi=a.dpi)
    print("wrote %s" % out)


if __name__ == "__main__":
    sys.exit(cli.run(main, "rdscene"))
