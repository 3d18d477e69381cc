#!/usr/bin/python3
"""Translate a rockdem scenario into a YADE (2023.02a) script, run it, and store the result in
rockdem's HDF5 layout (docs/HDF5-LAYOUT.md) so tools/yade/compare.py reads both codes' files.

    /usr/bin/python3 tools/yade/translate.py SCENARIO.dat [-o OUT.h5] [--script OUT.py]
        [--dt DT] [--set key=value]... [--no-hook] [--lift M] [--no-run] [-q]

Bodies: `block create brick`, `block create prism sides N radius R [radius-top RT] height H`
(an N-sided drum, position = centre of its mid-height section, as rd_poly_prism) with
`seat-on NAME` (z from NAME's top), and `block create polyhedron vertices x y z ...` (convex hull
of the points, relative to `position`). `fixed` bodies are pedestals. Contact: KN, KS (Pa/m),
friction; pulses: one-sine, one-cosine, harmonic, rectangular, triangle with direction/vertical/
start; `block initial` tilt/direction/velocity/angular-velocity; `model settle`, `model solve
time`, `model overturn`, `model timestep fixed`, `model damping local A` (YADE's Cundall damping;
`viscous` has no polyhedra counterpart in YADE and is refused unless --allow-viscous, which
drops it); `output hdf5 'f' interval DT`. Overrides: motion.amplitude, motion.frequency,
motion.direction, model.duration, model.timestep, contact.*, output.file, output.interval.

YADE mapping (docs/YADE.md): young = 2*KN; ks of a pair = KS * contact area of the pair (N/m,
area = the smaller of the touching faces: upper body's bottom, lower body's top); per-contact
shear restored by a PyRunner hook (default on; --no-hook shows YADE's shared shear variable);
fixed step (default: the scenario's fixed step, else 5e-5 s); no damping unless `local`.
The generated script is self-contained: yade -n -j1 -x SCRIPT OUT.npz.
"""
import argparse
import json
import math
import os
import re
import shlex
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
G0 = 9.80665


class TranslateError(Exception):
    pass


# ---------------------------------------------------------------- scenario parsing (subset)
def logical_lines(text):
    """(line number, [tokens]) per command: ';' comments, '&' continuation, quoted strings."""
    out, buf, start = [], [], None
    for n, raw in enumerate(text.splitlines(), 1):
        line, q = "", None
        for ch in raw:  # strip a ';' comment outside quotes
            if q:
                q = None if ch == q else q
            elif ch in "'\"":
                q = ch
            elif ch == ";":
                break
            line += ch
        line = line.rstrip()
        cont = line.endswith("&")
        if cont:
            line = line[:-1]
        if start is None and line.strip():
            start = n
        buf.append(line)
        if not cont:
            toks = shlex.split(" ".join(buf), posix=True)
            if toks:
                out.append((start, toks))
            buf, start = [], None
    return out


def num(tok, where, g=G0):
    t = tok.strip()
    try:
        if t.lower().endswith("g") and not t.lower().endswith("e"):
            return float(t[:-1]) * g
        return float(t)
    except ValueError:
        raise TranslateError("%s: expected a number, got '%s'" % (where, tok))


class Scenario:
    def __init__(self):
        self.gravity = 9.81
        self.density = 2700.0
        self.damping = ("none", 0.0)
        self.dt = None
        self.settle = True
        self.settle_ratio = 1e-6
        self.settle_limit = 5.0
        self.duration = None
        self.overturn = {"kind": "tilt-ratio", "value": 1.5, "stop": True}
        self.kn, self.ks, self.friction = 1e10, 1e9, math.radians(35.0)
        self.pulses = []
        self.bodies = []
        self.output = None
        self.interval = 0.01
        self.title = ""
        self.text = ""


KEYWORDS = {"size", "position", "rotation", "density", "mass", "name", "fixed", "sides", "radius",
            "radius-top", "height", "seat-on", "at", "vertices"}


def parse(text, path="scenario"):
    sc = Scenario()
    sc.text = text
    for ln, t in logical_lines(text):
        where = "%s:%d" % (path, ln)
        noun, verb, rest = t[0], (t[1] if len(t) > 1 else ""), t[2:]
        key = (noun, verb)
        if key == ("model", "title"):
            sc.title = " ".join(rest)
        elif key == ("model", "gravity"):
            sc.gravity = num(rest[0], where)
        elif key == ("model", "density"):
            sc.density = num(rest[0], where)
        elif key == ("model", "damping"):
            sc.damping = (rest[0], num(rest[1], where) if len(rest) > 1 else 0.0)
        elif key == ("model", "timestep"):
            if rest and rest[0] == "fixed":
                sc.dt = num(rest[1], where)
        elif key == ("model", "settle"):
            i = 0
            while i < len(rest):
                if rest[i] in ("on", "off"):
                    sc.settle = rest[i] == "on"; i += 1
                elif rest[i] == "ratio":
                    sc.settle_ratio = num(rest[i + 1], where); i += 2
                elif rest[i] == "time-limit":
                    sc.settle_limit = num(rest[i + 1], where); i += 2
                else:
                    raise TranslateError("%s: unknown settle keyword '%s'" % (where, rest[i]))
        elif key == ("model", "solve"):
            for i in range(0, len(rest) - 1, 2):
                if rest[i] == "time":
                    sc.duration = num(rest[i + 1], where)
        elif key == ("model", "overturn"):
            i = 0
            while i < len(rest):
                k = rest[i]
                if k == "stop":
                    sc.overturn["stop"] = rest[i + 1] == "on"
                elif k in ("tilt-ratio", "height"):
                    sc.overturn.update(kind=k, value=num(rest[i + 1], where))
                elif k == "angle":
                    sc.overturn.update(kind=k, value=math.radians(num(rest[i + 1], where)))
                i += 2
        elif key == ("model", "reference"):
            pass
        elif key == ("block", "create"):
            sc.bodies.append(parse_block(rest, where, sc))
        elif key == ("block", "initial"):
            d = dict(zip(rest[0::1], rest[1::1]))
            name = d.get("name")
            b = next((b for b in sc.bodies if b["name"] == name), None)
            if b is None:
                raise TranslateError("%s: no block named '%s'" % (where, name))
            i = 0
            while i < len(rest):
                k = rest[i]
                if k == "name":
                    i += 2
                elif k == "tilt":
                    b["tilt"] = math.radians(num(rest[i + 1], where)); i += 2
                elif k == "direction":
                    b["tilt_direction"] = math.radians(num(rest[i + 1], where)); i += 2
                elif k in ("velocity", "angular-velocity"):
                    b[k.replace("-", "_")] = [num(x, where) for x in rest[i + 1:i + 4]]; i += 4
                else:
                    raise TranslateError("%s: unknown 'block initial' keyword '%s'" % (where, k))
        elif key == ("contact", "property"):
            i = 0
            while i < len(rest):
                k = rest[i]
                if k == "stiffness-normal":
                    sc.kn = num(rest[i + 1], where)
                elif k == "stiffness-shear":
                    sc.ks = num(rest[i + 1], where)
                elif k == "friction":
                    sc.friction = math.radians(num(rest[i + 1], where))
                elif k in ("cohesion", "tension"):
                    if num(rest[i + 1], where) != 0:
                        raise TranslateError("%s: YADE's volumetric law has no %s" % (where, k))
                elif k == "spacing":
                    pass  # rockdem's subcontact spacing: no YADE counterpart (volumetric law)
                elif k == "restitution":
                    # YADE's polyhedra law is elastic (no impact loss): only restitution 1 matches
                    if num(rest[i + 1], where) != 1:
                        raise TranslateError("%s: YADE's polyhedra law is elastic: only restitution 1 "
                                             "has a YADE counterpart" % where)
                else:
                    raise TranslateError("%s: unknown contact keyword '%s'" % (where, k))
                i += 2
        elif key == ("ground-motion", "pulse"):
            p = {"kind": rest[0], "amplitude": 0.0, "frequency": 1.0, "duration": None,
                 "cycles": 1.0, "start": 0.0, "direction": 0.0, "vertical": False}
            i = 1
            while i < len(rest):
                k = rest[i]
                if k == "vertical":
                    p["vertical"] = True; i += 1; continue
                v = rest[i + 1]
                if k == "amplitude":
                    p["amplitude"] = num(v, where)
                elif k == "direction":
                    p["direction"] = math.radians(num(v, where))
                elif k in ("frequency", "duration", "cycles", "start"):
                    p[k] = num(v, where)
                else:
                    raise TranslateError("%s: unknown pulse keyword '%s'" % (where, k))
                i += 2
            if p["kind"] not in ("one-sine", "one-cosine", "harmonic", "rectangular", "triangle"):
                raise TranslateError("%s: pulse '%s' not translated" % (where, p["kind"]))
            if p["duration"] is None:
                p["duration"] = 1.0 / p["frequency"]
            sc.pulses.append(p)
        elif key == ("output", "hdf5"):
            sc.output = rest[0]
            if "interval" in rest:
                sc.interval = num(rest[rest.index("interval") + 1], where)
        elif noun == "ground-motion":
            raise TranslateError("%s: ground-motion %s is not translated (pulses only)" % (where, verb))
        else:
            raise TranslateError("%s: '%s %s' is not translated" % (where, noun, verb))
    if not sc.bodies:
        raise TranslateError("%s: no blocks" % path)
    return sc


def parse_block(rest, where, sc):
    shape = rest[0]
    b = {"shape": shape, "fixed": False, "rotation": [0.0, 0.0, 0.0], "density": None, "mass": None,
         "name": "block%d" % (len(sc.bodies) + 1), "tilt": 0.0, "tilt_direction": 0.0,
         "velocity": [0.0, 0.0, 0.0], "angular_velocity": [0.0, 0.0, 0.0], "seat_on": None,
         "radius_top": None}
    i = 1
    while i < len(rest):
        k = rest[i]
        if k == "fixed":
            b["fixed"] = True; i += 1
        elif k in ("size", "position", "rotation"):
            b[k] = [num(x, where) for x in rest[i + 1:i + 4]]; i += 4
        elif k in ("density", "mass", "radius", "radius-top", "height"):
            b[k.replace("-", "_")] = num(rest[i + 1], where); i += 2
        elif k == "sides":
            b["sides"] = int(rest[i + 1]); i += 2
        elif k in ("name", "seat-on"):
            b[k.replace("-", "_")] = rest[i + 1]; i += 2
        elif k == "at":  # seat-on NAME at X Y: the centre of mass above (X, Y)
            b["seat_at"] = [num(x, where) for x in rest[i + 1:i + 3]]; i += 3
        elif k == "vertices":
            j = i + 1
            vals = []
            while j < len(rest) and rest[j] not in KEYWORDS:
                vals.append(num(rest[j], where)); j += 1
            if len(vals) < 12 or len(vals) % 3:
                raise TranslateError("%s: 'vertices' needs x y z triples (at least 4)" % where)
            b["local_vertices"] = np.array(vals).reshape(-1, 3)
            i = j
        else:
            raise TranslateError("%s: unknown block keyword '%s'" % (where, k))
    if "position" in b and b["seat_on"]:
        raise TranslateError("%s: 'position' and 'seat-on' are exclusive" % where)
    if b.get("seat_at") and not b["seat_on"]:
        raise TranslateError("%s: 'at' needs 'seat-on'" % where)
    if "position" not in b:
        b["position"] = [0.0, 0.0, 0.0]
    else:
        b["position_given"] = True
    if shape == "brick":
        lx, ly, lz = b["size"]
        b["local_vertices"] = np.array([[i * lx / 2, j * ly / 2, k * lz / 2]
                                        for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)])
    elif shape == "prism":
        n, r, h = b["sides"], b["radius"], b["height"]
        rt = b["radius_top"] or r
        v = [[r * math.cos(2 * math.pi * k / n), r * math.sin(2 * math.pi * k / n), -h / 2] for k in range(n)]
        v += [[rt * math.cos(2 * math.pi * k / n), rt * math.sin(2 * math.pi * k / n), h / 2] for k in range(n)]
        # rockdem's position is the centre of mass: a frustum's lies (h/4)(r²+2r·rt+3rt²)/(r²+r·rt+rt²)
        # above the bottom, below mid-height when tapered
        zc = h * (r * r + 2 * r * rt + 3 * rt * rt) / (4 * (r * r + r * rt + rt * rt)) - h / 2
        b["local_vertices"] = np.array(v) - np.array([0.0, 0.0, zc])
    elif shape in ("polyhedron", "hull"):
        if "local_vertices" not in b:
            raise TranslateError("%s: 'block create %s' needs 'vertices'" % (where, shape))
    else:
        raise TranslateError("%s: shape '%s' is not translated" % (where, shape))
    return b


def apply_set(sc, kv):
    k, _, v = kv.partition("=")
    w = "--set " + kv
    if k == "motion.amplitude":
        for p in sc.pulses:
            p["amplitude"] = num(v, w)
    elif k in ("motion.frequency", "motion.cycles", "motion.start"):
        for p in sc.pulses:
            p[k.split(".")[1]] = num(v, w)
            if k == "motion.frequency":
                p["duration"] = 1.0 / p["frequency"]
    elif k == "motion.direction":
        for p in sc.pulses:
            p["direction"] = math.radians(num(v, w))
    elif k == "model.duration":
        sc.duration = num(v, w)
    elif k == "model.timestep":
        sc.dt = num(v.replace("fixed", "").strip(), w)
    elif k == "contact.stiffness-normal":
        sc.kn = num(v, w)
    elif k == "contact.stiffness-shear":
        sc.ks = num(v, w)
    elif k == "contact.friction":
        sc.friction = math.radians(num(v, w))
    elif k == "contact.spacing":
        pass
    elif k == "output.file":
        sc.output = v
    elif k == "output.interval":
        sc.interval = num(v, w)
    else:
        raise TranslateError("%s: key not translated" % w)
    sc.text += "\n; --set %s" % kv


# ---------------------------------------------------------------- geometry
def rot_matrix(rdeg):
    rx, ry, rz = (math.radians(a) for a in rdeg)
    cx, sx, cy, sy, cz, sz = math.cos(rx), math.sin(rx), math.cos(ry), math.sin(ry), math.cos(rz), math.sin(rz)
    Rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    Ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    Rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return Rz @ Ry @ Rx  # about x, then y, then z (extrinsic), as src/engine/setup.c


def hull(points):
    from scipy.spatial import ConvexHull
    return ConvexHull(points)


def face_area(points, normal_sign):
    """Area of the lowest (normal_sign=-1) or highest (+1) face of the convex body."""
    z = points[:, 2]
    zt = z.min() if normal_sign < 0 else z.max()
    h = z.max() - z.min()
    sel = points[np.abs(z - zt) < 1e-6 * max(h, 1e-9)][:, :2]
    if len(sel) < 3:
        return 0.0
    from scipy.spatial import ConvexHull
    try:
        return ConvexHull(sel).volume  # 2-D hull: 'volume' is the area
    except Exception:
        return 0.0


def build_geometry(sc, lift):
    by_name = {}
    for b in sc.bodies:
        R = rot_matrix(b["rotation"])
        local = b["local_vertices"] @ R.T
        pos = np.array(b["position"], float)
        if b["seat_on"]:
            base = by_name.get(b["seat_on"])
            if base is None:
                raise TranslateError("block '%s': seat-on '%s' must name an earlier block" % (b["name"], b["seat_on"]))
            if b.get("seat_at"):
                pos[0], pos[1] = b["seat_at"]
            elif "position_given" not in b:  # default: above the base's centre
                pos[0], pos[1] = base["position_xy"]
            pos[2] = base["world"][:, 2].max() - local[:, 2].min()
        b["position_xy"] = [float(pos[0]), float(pos[1])]
        w = local + pos
        if not b["fixed"]:
            w = w + np.array([0, 0, 0.0])
        b["world"] = w
        h = hull(w)
        b["volume"] = h.volume
        b["bottom_area"] = face_area(w, -1)
        b["top_area"] = face_area(w, +1)
        by_name[b["name"]] = b
    # pairs that touch at rest: a body whose bottom lies on another's top, overlapping in plan
    pairs = []
    for i, a in enumerate(sc.bodies):
        for j, c in enumerate(sc.bodies):
            if i == j or c["fixed"]:
                continue
            if abs(a["world"][:, 2].max() - c["world"][:, 2].min()) < 1e-6:
                area = min(c["bottom_area"], a["top_area"]) if a["top_area"] > 0 else c["bottom_area"]
                pairs.append((i, j, area))
    return pairs


def scene_dict(sc, dt, hook, lift):
    pairs = build_geometry(sc, lift)
    free = [b for b in sc.bodies if not b["fixed"]]
    if not free:
        raise TranslateError("no free block")
    bodies = []
    for b in sc.bodies:
        rho = b["density"] or sc.density
        bodies.append({"name": b["name"], "fixed": b["fixed"], "vertices": b["world"].tolist(),
                       "density": b["density"], "mass": b["mass"], "mass_geom": rho * b["volume"],
                       "bottom_area": b["bottom_area"], "tilt": b["tilt"],
                       "tilt_direction": b["tilt_direction"], "velocity": b["velocity"],
                       "angular_velocity": b["angular_velocity"]})
    areas = sorted(set(round(p[2], 12) for p in pairs))
    ref_area = pairs[0][2] if pairs else free[0]["bottom_area"]
    kind, val = sc.damping
    if kind == "viscous" and val > 0:
        raise TranslateError("model damping viscous: YADE's polyhedra law has no contact dashpot "
                             "(use --allow-viscous to drop it, or damping local)")
    duration = sc.duration if sc.duration is not None else 10.0
    return {
        "gravity": sc.gravity, "density": sc.density, "kn": sc.kn, "ks": sc.ks,
        "friction_rad": sc.friction, "dt": dt, "ref_area": ref_area,
        "pair_areas": [list(p) for p in pairs], "multi_ks": len(areas) > 1,
        "shear_hook": bool(hook) and len([b for b in sc.bodies]) > 2,
        "bodies": bodies, "pulses": sc.pulses,
        "local_damping": val if kind == "local" else 0.0,
        "settle": sc.settle, "settle_ratio": sc.settle_ratio,
        "settle_time_limit": min(sc.settle_limit, 1.0),
        "duration": duration, "interval": sc.interval, "overturn": sc.overturn, "lift": lift,
    }


def write_script(scene, path):
    with open(os.path.join(HERE, "yade_runtime.py")) as f:
        body = f.read()
    with open(path, "w") as f:
        f.write("# Generated by tools/yade/translate.py from a rockdem scenario; run:\n")
        f.write("#   yade -n -j1 -x %s OUT.npz\n" % os.path.basename(path))
        f.write("import json\nSCENE = json.loads(%r)\n" % json.dumps(scene))
        f.write(body)


# ---------------------------------------------------------------- HDF5 in rockdem's layout
def write_h5(path, sc, scene, r, script_text):
    import h5py
    from scipy.spatial import ConvexHull
    names = [str(n) for n in r["names"]]
    with h5py.File(path, "w") as f:
        f.attrs["program"] = "yade"
        f.attrs["layout"] = "rockdem"
        f.attrs["version"] = yade_version()
        f.attrs["scenario"] = sc.text
        f.attrs["title"] = sc.title
        f.attrs["dt"] = scene["dt"]
        f.attrs["damping"] = "local %g" % scene["local_damping"] if scene["local_damping"] else "none"
        ov = scene["overturn"]
        f.attrs["overturn_criterion"] = "%s %g" % (ov["kind"], math.degrees(ov["value"]) if ov["kind"] == "angle" else ov["value"])
        f.attrs["kn"], f.attrs["ks"], f.attrs["friction_deg"] = sc.kn, sc.ks, math.degrees(sc.friction)
        f.attrs["contact_law"] = "YADE Polyhedra volumetric (kn = young/2 = KN), ks = KS * pair area"
        f.attrs["shear_hook"] = int(scene["shear_hook"])
        f.attrs["yade_script"] = script_text
        dt = h5py.string_dtype()
        f.create_dataset("bodies/names", data=np.array(names, dtype=object), dtype=dt)
        free = [b for b in sc.bodies if not b["fixed"]]
        for k, b in enumerate(free):
            g = f.create_group("bodies/" + b["name"])
            g.attrs["mass"] = float(r["mass"][k])
            g.attrs["inertia_principal"] = r["inertia"][k]
            ext = b["world"].max(0) - b["world"].min(0)
            g.attrs["size"] = ext
            g.attrs["alpha"] = float(r["sum_alpha"][k])
            g.attrs["fixed"] = 0
            w = b["world"]
            c = w.mean(0)
            hh = ConvexHull(w)
            g.create_dataset("vertices", data=w - c)
            g.create_dataset("faces", data=hh.simplices.astype(np.int32))
        comp = dict(compression="gzip", compression_opts=6, shuffle=True)
        f.create_dataset("time", data=r["time"], **comp)
        for key in ("position", "quaternion", "velocity", "angular_velocity", "tilt"):
            f.create_dataset(key, data=r[key], **comp)
        f.create_dataset("rotation", data=rotation_from(r, scene), **comp)
        f.create_dataset("ground/acceleration", data=r["ground_acc"], **comp)
        f.create_dataset("energy/kinetic", data=r["kinetic"], **comp)
        f.create_dataset("energy/gravitational", data=r["gravitational"], **comp)
        ev = events_from(r, scene)
        evt = np.dtype([("time", "f8"), ("body", "i4"), ("type", "S16"), ("value", "f8")])
        f.create_dataset("events", data=np.array(ev, dtype=evt))
        s = f.create_group("summary")
        s.attrs["status"] = str(r["status"])
        s.attrs["any_overturned"] = int(np.any(r["sum_overturned"]))
        s.attrs["end_time"] = float(r["time"][-1])
        s.attrs["dt"] = scene["dt"]
        s.attrs["steps"] = int(r["steps"])
        s.attrs["settle_time"] = float(r["settle_time"])
        s.attrs["wall_seconds"] = float(r["wall"])
        for key in ("overturned", "overturn_time", "max_tilt", "max_tilt_ratio", "max_slide", "final_slide", "alpha"):
            a = r["sum_" + key]
            s.attrs[key] = a.astype(np.int32) if key == "overturned" else a.astype(float)


def signed_rocking(quat, tilt):
    """Signed tilt about the first rocking axis (sign from the horizontal lean), [N]."""
    w, x, y, z = quat[:, 0], quat[:, 1], quat[:, 2], quat[:, 3]
    # image of e_z under the rotation from rest
    zx = 2 * (x * z + w * y)
    zy = 2 * (y * z - w * x)
    k = np.argmax(np.hypot(zx, zy) > 1e-3 * max(np.max(np.hypot(zx, zy)), 1e-30))
    ax = np.array([zx[k], zy[k]])
    n = np.linalg.norm(ax)
    if n == 0:
        return tilt.copy()
    ax /= n
    return np.sign(zx * ax[0] + zy * ax[1]) * tilt


def rotation_from(r, scene):
    """/rotation [N][nb][3]: in-plane rocking (about the horizontal axis normal to the motion
    direction d, + tips towards d), out-of-plane rocking (+ towards z x d), twist (0: not
    computed), from the rotation since rest: atan2 of the rest vertical's lean components."""
    d = scene["pulses"][0]["direction"] if scene["pulses"] else 0.0
    c, s_ = math.cos(d), math.sin(d)
    q = r["quaternion"]
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    zx, zy, zz = 2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)
    out = np.zeros(q.shape[:-1] + (3,))
    out[..., 0] = np.arctan2(zx * c + zy * s_, zz)
    out[..., 1] = np.arctan2(-zx * s_ + zy * c, zz)
    return out


def events_from(r, scene):
    """impact (sign change of the rocking angle, linear interpolation) and overturn, per body."""
    ev = []
    t = r["time"]
    for k in range(r["tilt"].shape[1]):
        s = rotation_from(r, scene)[:, k, 0]
        for i in range(1, len(s)):
            if s[i - 1] * s[i] < 0:
                f = s[i - 1] / (s[i - 1] - s[i])
                ev.append((t[i - 1] + f * (t[i] - t[i - 1]), k, b"impact", 0.0))
        if r["sum_overturned"][k]:
            ev.append((float(r["sum_overturn_time"][k]), k, b"overturn", float(r["sum_max_tilt"][k])))
    ev.sort()
    return ev


def yade_version():
    return "YADE 2023.02a (Polyhedra, Law2_PolyhedraGeom_PolyhedraPhys_Volumetric)"


# ---------------------------------------------------------------- driver
def translate_and_run(scenario, out=None, dt=None, sets=(), hook=True, lift=1e-6, script=None,
                      run=True, quiet=False, allow_viscous=False, yade="yade"):
    with open(scenario) as f:
        text = f.read()
    sc = parse(text, scenario)
    for kv in sets:
        apply_set(sc, kv)
    if allow_viscous and sc.damping[0] == "viscous":
        sc.damping = ("none", 0.0)
    step = dt or sc.dt or 5e-5
    scene = scene_dict(sc, step, hook, lift)
    tmp = tempfile.mkdtemp(prefix="rd_yade_")
    script = script or os.path.join(tmp, "scene_yade.py")
    write_script(scene, script)
    if not run:
        return None
    npz = os.path.join(tmp, "out.npz")
    p = subprocess.run([yade, "-n", "-j1", "-x", script, npz], stdin=subprocess.DEVNULL,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    lines = [ln for ln in p.stdout.splitlines() if ln.startswith("yade-")]
    if p.returncode != 0 or not os.path.exists(npz):
        sys.stderr.write(p.stdout[-3000:])
        raise TranslateError("YADE run failed (rc %d): %s" % (p.returncode, script))
    if not quiet:
        print("\n".join(lines))
    r = dict(np.load(npz, allow_pickle=False))
    out = out or (os.path.splitext(os.path.basename(scenario))[0] + "-yade.h5")
    with open(script) as f:
        write_h5(out, sc, scene, r, f.read())
    return out, r, lines


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenario")
    ap.add_argument("-o", "--out", help="HDF5 output (default: <scenario>-yade.h5)")
    ap.add_argument("--script", help="also keep the generated YADE script here")
    ap.add_argument("--dt", type=float, help="YADE's fixed step, s (default: scenario's, else 5e-5)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    ap.add_argument("--no-hook", action="store_true", help="leave YADE's shared shear variable alone")
    ap.add_argument("--lift", type=float, default=1e-6, help="gap under a tilted block, m (default 1e-6)")
    ap.add_argument("--no-run", action="store_true", help="only write the script (needs --script)")
    ap.add_argument("--allow-viscous", action="store_true", help="drop 'model damping viscous'")
    ap.add_argument("-q", "--quiet", action="store_true")
    a = ap.parse_args(argv)
    try:
        res = translate_and_run(a.scenario, a.out, a.dt, a.set, not a.no_hook, a.lift, a.script,
                                not a.no_run, a.quiet, a.allow_viscous)
    except TranslateError as e:
        sys.exit("translate: %s" % e)
    if res and not a.quiet:
        print("wrote %s" % res[0])


if __name__ == "__main__":
    main()
