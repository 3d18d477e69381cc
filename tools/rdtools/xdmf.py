"""XDMF sidecar for ParaView: the bodies' triangles, animated.

XDMF cannot rotate a mesh by a quaternion, so the world vertex coordinates of every body are
computed here for each output step and written to the sidecar's own companion HDF5 file:

  <stem>.vis.h5   /topology      [ntri_total][3] int32  triangles of all bodies, global vertex ids
                  /body          [ntri_total]    int32  body index (output order) of each triangle
                  /step_<k>/xyz  [nv_total][3]          world vertices at output step k
                  /step_<k>/tilt [ntri_total]           tilt of the triangle's body, rad
  <stem>.xmf      Xdmf 2 XML: one Uniform Grid per written step inside a Temporal Collection,
                  each Grid referencing /topology and its own /step_<k>/xyz (one dataset per step
                  works in both ParaView XDMF readers: "XDMF Reader" and "Xdmf3 Reader").

World frame: rockdem writes positions in the ground (pedestal) frame; frame='absolute' adds
/ground/displacement so the bodies move with the shaking table as seen from outside."""
import os
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from . import RDError
from .rotation import quat_to_matrix
from .runfile import Run, h5py


def write_sidecar(run_path, xmf_path, stride=1, frame="ground", float32=False):
    if stride < 1:
        raise RDError("--stride must be >= 1")
    if frame not in ("ground", "absolute"):
        raise RDError("--frame must be ground or absolute")
    stem = xmf_path[:-4] if xmf_path.endswith(".xmf") else xmf_path
    vis_path = stem + ".vis.h5"
    if os.path.abspath(vis_path) == os.path.abspath(run_path):
        raise RDError("%s: the companion file would overwrite the run file" % vis_path)
    with Run(run_path) as r:
        names = r.body_names()
        t = r.time()
        pos = r.data("position")
        quat = r.data("quaternion")
        tilt = r.data("tilt") if r.has("tilt") else np.zeros((len(t), len(names)))
        n = len(t)
        if pos.shape[:2] != (n, len(names)) or quat.shape[:2] != (n, len(names)):
            raise RDError("%s: /position or /quaternion does not match /time and /bodies/names"
                          % run_path)
        shift = np.zeros((n, 3))
        if frame == "absolute":
            shift = r.data("ground/displacement")[:, :3]
        geo = [r.body_geometry(nm) for nm in names]
    if n == 0:
        raise RDError("%s: the run has no output samples" % run_path)

    voff = np.cumsum([0] + [len(v) for v, _ in geo])
    topo = np.concatenate([f + voff[b] for b, (_, f) in enumerate(geo)]).astype(np.int32)
    body_of_tri = np.concatenate([np.full(len(f), b, np.int32) for b, (_, f) in enumerate(geo)])
    nv, nt = int(voff[-1]), len(topo)
    steps = list(range(0, n, stride))
    if steps[-1] != n - 1:
        steps.append(n - 1)  # always show the final state
    dtype = np.float32 if float32 else np.float64
    R = quat_to_matrix(quat)  # [n, nb, 3, 3]

    with h5py.File(vis_path, "w") as h:
        h.attrs["program"] = "rdxdmf"
        h.attrs["source"] = os.path.abspath(run_path)
        h.attrs["frame"] = frame
        h.create_dataset("topology", data=topo)
        h.create_dataset("body", data=body_of_tri)
        h.create_dataset("time", data=t[steps])
        for k in steps:
            xyz = np.empty((nv, 3))
            for b, (v, _) in enumerate(geo):
                xyz[voff[b]:voff[b + 1]] = pos[k, b] + shift[k] + v @ R[k, b].T
            g = h.create_group("step_%d" % k)
            g.create_dataset("xyz", data=xyz.astype(dtype))
            g.create_dataset("tilt", data=tilt[k, body_of_tri].astype(dtype))

    rel = os.path.relpath(vis_path, os.path.dirname(os.path.abspath(xmf_path)) or ".")
    prec = 4 if float32 else 8
    L = ['<?xml version="1.0" ?>', '<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>',
         '<Xdmf Version="2.0">', ' <Domain>',
         '  <!-- rdxdmf: %s, %d bodies (%s), frame %s -->' % (
             escape(os.path.basename(run_path)).replace("--", "- -"), len(names),
             escape(", ".join(names)).replace("--", "- -"), frame),
         '  <Grid Name="bodies" GridType="Collection" CollectionType="Temporal">']

    def item(dims, ntype, p, path):
        return ('<DataItem Dimensions="%s" NumberType="%s" Precision="%d" Format="HDF">%s:%s'
                '</DataItem>' % (dims, ntype, p, escape(rel), path))

    for k in steps:
        L += ['   <Grid Name="step_%d" GridType="Uniform">' % k,
              '    <Time Value="%.17g"/>' % t[k],
              '    <Topology TopologyType="Triangle" NumberOfElements="%d">' % nt,
              '     ' + item("%d 3" % nt, "Int", 4, "/topology"),
              '    </Topology>',
              '    <Geometry GeometryType="XYZ">',
              '     ' + item("%d 3" % nv, "Float", prec, "/step_%d/xyz" % k),
              '    </Geometry>',
              '    <Attribute Name="body" AttributeType="Scalar" Center="Cell">',
              '     ' + item("%d" % nt, "Int", 4, "/body"),
              '    </Attribute>',
              '    <Attribute Name="tilt" AttributeType="Scalar" Center="Cell">',
              '     ' + item("%d" % nt, "Float", prec, "/step_%d/tilt" % k),
              '    </Attribute>',
              '   </Grid>']
    L += ['  </Grid>', ' </Domain>', '</Xdmf>', '']
    with open(xmf_path, "w") as fh:
        fh.write("\n".join(L))
    return xmf_path, vis_path, len(steps), nv, nt
