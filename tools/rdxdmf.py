#!/usr/bin/python3
"""rdxdmf — an XDMF sidecar so ParaView animates the bodies of a rockdem run: RUN.xmf (one grid
per output step in a temporal collection: the bodies' triangles from /bodies/faces) and
its companion RUN.vis.h5 holding the world vertex coordinates of every step (/step_<k>/xyz),
computed as position + R(quaternion) * body-frame vertices. Open RUN.xmf in ParaView."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rdtools import cli  # noqa: E402


def main():
    p = cli.Parser(prog="rdxdmf", description=cli.describe(__doc__))
    p.add_argument("run", metavar="RUN.h5", help="HDF5 file written by 'rockdem run'")
    p.add_argument("-o", "--output", metavar="OUT.xmf",
                   help="XDMF file to write (default RUN.xmf); the companion is OUT.vis.h5 beside it")
    p.add_argument("--every", "--stride", dest="stride", type=int, default=1, metavar="K",
                   help="write only every K-th output step (the last one is always kept)")
    p.add_argument("--frame", choices=("ground", "absolute"), default="ground",
                   help="ground: positions as written (pedestal frame, default); absolute: add "
                        "/ground/displacement")
    p.add_argument("--float64", action="store_true",
                   help="store coordinates in double precision (default single: 0.1 um at 1 m)")
    a = p.parse_args()
    from rdtools.xdmf import write_sidecar
    out = a.output or os.path.splitext(a.run)[0] + ".xmf"
    if not out.endswith(".xmf"):
        p.error("the output name must end in .xmf")
    cli.ensure_writable(out)
    xmf, vis, ns, nv, nt, nf = write_sidecar(a.run, out, a.stride, a.frame, not a.float64)
    print("wrote %s and %s: %d steps, %d vertices, %d triangles, %d fixed bodies"
          % (xmf, vis, ns, nv, nt, nf))


if __name__ == "__main__":
    sys.exit(cli.run(main, "rdxdmf"))
