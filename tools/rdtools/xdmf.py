"""XDMF sidecar for ParaView: the bodies' triangles, animated, with the fixed bodies (pedestals)
drawn in place.

XDMF cannot rotate a mesh by a quaternion, so the world vertex coordinates of every free body
are computed here for each written step and stored in the sidecar's companion HDF5 file
(shuffle + deflate compressed; tilt and tilt ratio are constant per body and compress to almost
nothing):

  <stem>.vis.h5   /topology        [ntri][3] int32  triangles of the free bodies, global vertex ids
                  /body            [ntri]    int32  body index (output order) of each triangle
                  /step_<k>/xyz    [nv][3]          world vertices of the free bodies at step k
                  /step_<k>/tilt   [ntri]           tilt of the triangle's body, rad
                  /step_<k>/tilt_ratio [ntri]       tilt / alpha of the triangle's body, alpha
                                                    towards the side it leans to (Run.tilt_ratio)
                  /fixed/topology, /fixed/xyz       the fixed bodies (static), if any; their
                                                    tilt is NaN (drawn in the NaN colour), body -1
  <stem>.xmf      Xdmf 2 XML: a Temporal collection of one Spatial collection per written step,
                  each holding the grid "bodies" (its own /step_<k>/...) and the grid "fixed"
                  (the same static datasets every step).

The HDF5 file is named in the XML as "./<name>" — a path relative to the .xmf's folder that the
XDMF Reader and both Xdmf3 readers of ParaView resolve, wherever ParaView was started (a bare
name is looked up in the current folder by some of them).

World frame: rockdem writes positions in the ground (pedestal) frame; frame='absolute' adds
/ground/displacement so the bodies and the pedestal move with the shaking table."""
import os
from xml.sax.saxutils import escape

import numpy as np

from . import RDError
from .rotation import quat_to_matrix, world_vertices
from .runfile import Run, h5py

COMPRESS = dict(compression="gzip", compression_opts=4, shuffle=True)


def _fixed_bodies(r, free):
    """[(name, world vertices, faces)] of the fixed bodies (fixed = 1 in /bodies)."""
    out = []
    b = r.bodies()
    for nm in b.fixed_names():
        if nm in free:
            continue
        v, fc = r.body_geometry(nm)
        pos = np.asarray(b.attr(nm, "position", np.zeros(3)), float)
        q = np.asarray(b.attr(nm, "quaternion", [1.0, 0, 0, 0]), float)
        out.append((nm, world_vertices(pos, q, v), fc))
    return out


def _ratio(r, k, name, tilt):
    """tilt / alpha toward the lean of body k (Run.tilt_ratio); NaN when alpha is unknown."""
    x = r.tilt_ratio(k, name)
    return x if x is not None else np.full(len(tilt), np.nan)


def write_sidecar(run_path, xmf_path, stride=1, frame="ground", float32=False):
    if stride < 1:
        raise RDError("--every must be >= 1")
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
        fixed = _fixed_bodies(r, set(names))
        ratio = np.column_stack([_ratio(r, k, nm, tilt[:, k]) for k, nm in enumerate(names)])
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

    fv = np.cumsum([0] + [len(v) for _, v, _ in fixed])
    with h5py.File(vis_path, "w") as h:
        h.attrs["program"] = "rdxdmf"
        h.attrs["source"] = os.path.abspath(run_path)
        h.attrs["frame"] = frame
        h.create_dataset("topology", data=topo, **COMPRESS)
        h.create_dataset("body", data=body_of_tri, **COMPRESS)
        h.create_dataset("time", data=t[steps])
        if fixed:
            h.create_dataset("fixed/topology", data=np.concatenate(
                [f + fv[i] for i, (_, _, f) in enumerate(fixed)]).astype(np.int32))
            h.create_dataset("fixed/xyz", data=np.concatenate([v for _, v, _ in fixed]).astype(dtype))
            ntf_ = sum(len(f) for _, _, f in fixed)  # no tilt: NaN (ParaView's NaN colour)
            h.create_dataset("fixed/tilt", data=np.full(ntf_, np.nan, dtype))
            h.create_dataset("fixed/body", data=np.full(ntf_, -1, np.int32))
        for k in steps:
            xyz = np.empty((nv, 3))
            for b, (v, _) in enumerate(geo):
                xyz[voff[b]:voff[b + 1]] = pos[k, b] + shift[k] + v @ R[k, b].T
            g = h.create_group("step_%d" % k)
            g.create_dataset("xyz", data=xyz.astype(dtype), **COMPRESS)
            g.create_dataset("tilt", data=tilt[k, body_of_tri].astype(dtype), **COMPRESS)
            g.create_dataset("tilt_ratio", data=ratio[k, body_of_tri].astype(dtype), **COMPRESS)
            if fixed and frame == "absolute":
                g.create_dataset("fixed_xyz", data=(h["fixed/xyz"][()] + shift[k]).astype(dtype),
                                 **COMPRESS)

    rel = "./" + os.path.relpath(vis_path, os.path.dirname(os.path.abspath(xmf_path)) or ".")
    prec = 4 if float32 else 8
    L = ['<?xml version="1.0" ?>', '<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>',
         '<Xdmf Version="2.0">', ' <Domain>',
         '  <!-- rdxdmf: %s, %d free bodies (%s), %d fixed, frame %s -->' % (
             escape(os.path.basename(run_path)).replace("--", "- -"), len(names),
             escape(", ".join(names)).replace("--", "- -"), len(fixed), frame),
         '  <Grid Name="run" GridType="Collection" CollectionType="Temporal">']

    def item(dims, ntype, p, path):
        return ('<DataItem Dimensions="%s" NumberType="%s" Precision="%d" Format="HDF">%s:%s'
                '</DataItem>' % (dims, ntype, p, escape(rel), path))

    def cell_attr(name, path, count, ntype="Float", p=prec):
        return ['     <Attribute Name="%s" AttributeType="Scalar" Center="Cell">' % name,
                '      ' + item("%d" % count, ntype, p, path), '     </Attribute>']

    ntf = int(sum(len(f) for _, _, f in fixed))
    for k in steps:
        L += ['   <Grid Name="step_%d" GridType="Collection" CollectionType="Spatial">' % k,
              '    <Time Value="%.17g"/>' % t[k],
              '    <Grid Name="bodies" GridType="Uniform">',
              '     <Topology TopologyType="Triangle" NumberOfElements="%d">' % nt,
              '      ' + item("%d 3" % nt, "Int", 4, "/topology"),
              '     </Topology>',
              '     <Geometry GeometryType="XYZ">',
              '      ' + item("%d 3" % nv, "Float", prec, "/step_%d/xyz" % k),
              '     </Geometry>']
        L += cell_attr("body", "/body", nt, "Int", 4)
        L += cell_attr("tilt", "/step_%d/tilt" % k, nt)
        L += cell_attr("tilt_ratio", "/step_%d/tilt_ratio" % k, nt)
        L += ['    </Grid>']
        if fixed:
            xyz = "/step_%d/fixed_xyz" % k if frame == "absolute" else "/fixed/xyz"
            L += ['    <Grid Name="fixed" GridType="Uniform">',
                  '     <Topology TopologyType="Triangle" NumberOfElements="%d">' % ntf,
                  '      ' + item("%d 3" % ntf, "Int", 4, "/fixed/topology"),
                  '     </Topology>',
                  '     <Geometry GeometryType="XYZ">',
                  '      ' + item("%d 3" % int(fv[-1]), "Float", prec, xyz),
                  '     </Geometry>']
            L += cell_attr("body", "/fixed/body", ntf, "Int", 4)
            L += cell_attr("tilt", "/fixed/tilt", ntf)
            L += cell_attr("tilt_ratio", "/fixed/tilt", ntf)
            L += ['    </Grid>']
        L += ['   </Grid>']
    L += ['  </Grid>', ' </Domain>', '</Xdmf>', '']
    with open(xmf_path, "w") as fh:
        fh.write("\n".join(L))
    return xmf_path, vis_path, len(steps), nv, nt, len(fixed)
