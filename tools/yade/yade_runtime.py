# rockdem -> YADE runtime. tools/yade/translate.py prepends `SCENE = {...}` (the translated
# scenario as a dict) and writes the result as one self-contained YADE script, run as
#   yade -n -j1 -x SCRIPT OUT.npz
# It builds the scene with Polyhedra and the volumetric law, applies rockdem's initial conditions
# (settle, tilt), shakes the free bodies by the pseudo-acceleration -a_g(t) (rockdem's moving
# frame: NewtonIntegrator.gravity is updated every step), samples the free bodies every output
# interval and saves arrays to OUT.npz (translate.py turns them into rockdem's HDF5 layout).
#
# YADE traits handled here (docs/YADE.md):
# - normal: force = kn * overlap volume; Ip2 gives kn = young/2, so young = 2*KN (Pa/m).
# - shear stiffness is absolute (N/m): ks of a pair = KS * (contact area of the pair), set per
#   interaction every step (pair areas come from the translator).
# - Law2_PolyhedraGeom_PolyhedraPhys_Volumetric keeps the elastic shear force in ONE member
#   variable shared by every interaction, so with several contacts each contact starts its update
#   from the previous contact's force. With SCENE['shear_hook'] on, a PyRunner placed after the
#   InteractionLoop recomputes each contact's shear force from its own stored value (key: id
#   pair), applies the difference to the two bodies (force and torque at the contact point) and
#   stores it in phys.shearForce: per-contact shear, as in rockdem.
# - the time step is fixed (YADE's automatic steppers misread polyhedra stiffness).
import math
import sys
import time

import numpy as np
from yade import log, utils

log.setLevel("Default", log.ERROR)  # Polyhedra_support warns on degenerate intersections

S = SCENE  # noqa: F821 (prepended by translate.py)
out_path = sys.argv[1] if len(sys.argv) > 1 else "yade_out.npz"
G = S["gravity"]
KN, KS, TANPHI = S["kn"], S["ks"], math.tan(S["friction_rad"])
DT = S["dt"]
young = 2.0 * KN
poisson = KS * S["ref_area"] / KN  # ks = young*poisson/2 = KS*ref_area for equal materials

O.reset()
mat = O.materials.append(PolyhedraMat(young=young, poisson=poisson, density=S["density"],
                                      frictionAngle=S["friction_rad"], IsSplitable=False))
ids = []
for b in S["bodies"]:
    verts = [Vector3(*v) for v in b["vertices"]]  # world frame, rest pose
    body = utils.polyhedron(verts, fixed=b["fixed"], material=mat)
    if not b["fixed"]:
        if b.get("mass"):
            body.state.mass = b["mass"]
            body.state.inertia = Vector3(*[b["mass"] / b["mass_geom"] * x for x in body.state.inertia])
        elif b.get("density"):
            k = b["density"] / S["density"]
            body.state.mass *= k
            body.state.inertia = Vector3(*[k * x for x in body.state.inertia])
    ids.append(O.bodies.append(body))
name_of = {ids[k]: S["bodies"][k]["name"] for k in range(len(ids))}
free = [ids[k] for k, b in enumerate(S["bodies"]) if not b["fixed"]]
pair_area = {}
for a, b, area in S["pair_areas"]:
    ia, ib = ids[a], ids[b]
    pair_area[(min(ia, ib), max(ia, ib))] = area
bottom_area = {ids[k]: b["bottom_area"] for k, b in enumerate(S["bodies"])}


def pair_ks(i1, i2):
    a = pair_area.get((min(i1, i2), max(i1, i2)))
    if a is None:
        cand = [bottom_area[i] for i in (i1, i2) if O.bodies[i].dynamic]
        a = min(cand) if cand else S["ref_area"]
    return KS * a


# ---- ground motion: rockdem's pulses (src/records/motion.c), acceleration only ----
def pulse_acc(p, t):
    tau = t - p["start"]
    if tau <= 0:
        return 0.0
    kind, A = p["kind"], p["amplitude"]
    if kind in ("one-sine", "one-cosine"):
        L = 1.0 / p["frequency"]
    elif kind == "harmonic":
        L = p["cycles"] / p["frequency"]
    else:
        L = p["duration"]
    if tau >= L:
        return 0.0
    w = 2 * math.pi * p.get("frequency", 0.0)
    if kind in ("one-sine", "harmonic"):
        return A * math.sin(w * tau)
    if kind == "one-cosine":
        return A * math.cos(w * tau)
    if kind == "rectangular":
        return A
    if kind == "triangle":
        return 2 * A * tau / L if tau <= 0.5 * L else 2 * A * (L - tau) / L
    return 0.0


def ground_acc(t):
    a = [0.0, 0.0, 0.0]
    for p in S["pulses"]:
        v = pulse_acc(p, t)
        if p["vertical"]:
            a[2] += v
        else:
            a[0] += v * math.cos(p["direction"])
            a[1] += v * math.sin(p["direction"])
    return a


t0 = [0.0]  # simulated time at the end of settling (rockdem's t = 0)
shaking = [False]
store = {}
hook_stats = {"calls": 0, "corrected": 0}


def control():
    """Every step, after the InteractionLoop: per-pair ks, per-contact shear, pseudo-force."""
    global store
    if S["shear_hook"]:
        new = {}
        for i in O.interactions:
            if not i.isReal:
                continue
            g, p = i.geom, i.phys
            key = (i.id1, i.id2)
            ks = pair_ks(i.id1, i.id2)
            p.ks = ks
            if not (g.penetrationVolume > 0 and g.equivalentPenetrationDepth > 1e-18):
                continue  # the law applied nothing and zeroed the phys
            n = g.normal
            prev = store.get(key)
            if prev is None:
                fs = Vector3(0, 0, 0)
            else:  # turn the stored force into the current contact plane, keeping its size
                fs = prev - n * n.dot(prev)
                m1 = fs.norm()
                if m1 > 0:
                    fs *= prev.norm() / m1
            fs = fs - ks * g.shearInc
            lim = p.normalForce.norm() * TANPHI
            m = fs.norm()
            if m > lim:
                fs *= (lim / m) if m > 0 else 0.0
            d = fs - p.shearForce
            if d.squaredNorm() > 0:
                cp = g.contactPoint
                O.forces.addF(i.id1, -d)
                O.forces.addF(i.id2, d)
                O.forces.addT(i.id1, (O.bodies[i.id1].state.pos - cp).cross(d))
                O.forces.addT(i.id2, (cp - O.bodies[i.id2].state.pos).cross(d))
                hook_stats["corrected"] += 1
            p.shearForce = fs
            new[key] = fs
        store = new
        hook_stats["calls"] += 1
    elif S["multi_ks"]:
        for i in O.interactions:
            if i.isReal:
                i.phys.ks = pair_ks(i.id1, i.id2)
    if shaking[0]:
        a = ground_acc(O.time - t0[0])
        newton.gravity = Vector3(-a[0], -a[1], -G - a[2])


engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Polyhedra_Aabb()]),
    InteractionLoop([Ig2_Polyhedra_Polyhedra_PolyhedraGeom()],
                    [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                    [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric(label="law")]),
]
need_runner = S["shear_hook"] or S["multi_ks"] or bool(S["pulses"])
if need_runner:
    engines.append(PyRunner(command="control()", iterPeriod=1, label="ctl"))
engines.append(NewtonIntegrator(damping=S["local_damping"], gravity=(0, 0, -G), label="newton"))
O.engines = engines
O.dt = DT

# ---- settle (rockdem: local damping 0.8, no shaking, until unbalanced/weight < ratio) ----
settle_time = 0.0
if S["settle"] and free:
    newton.damping = 0.8
    limit = S["settle_time_limit"]
    chunk = max(1, int(round(0.01 / DT)))
    while O.time < limit:
        O.run(chunk, True)
        if utils.unbalancedForce() < max(S["settle_ratio"], 1e-4):
            break
    for i in free:
        O.bodies[i].state.vel = Vector3(0, 0, 0)
        O.bodies[i].state.angVel = Vector3(0, 0, 0)
    newton.damping = S["local_damping"]
    settle_time = O.time
t0[0] = O.time


# ---- rest reference of each free body (after settling, before the tilt) ----
def world_vertices(bid):
    b = O.bodies[bid]
    return [b.state.pos + b.state.ori * v for v in b.shape.v]


EZ = Vector3(0, 0, 1)
ref = {}
for bid in free:
    st = O.bodies[bid].state
    wv = world_vertices(bid)
    zmin = min(v[2] for v in wv)
    h = max(v[2] for v in wv) - zmin
    sup = [(v[0] - st.pos[0], v[1] - st.pos[1]) for v in wv if v[2] < zmin + 1e-3 * h]
    base_w = Vector3(st.pos[0], st.pos[1], zmin)
    ref[bid] = {
        "ori": Quaternion(st.ori), "up_body": st.ori.conjugate() * EZ, "support": sup,
        "hcom": st.pos[2] - zmin, "zmin": zmin, "z0": st.pos[2],
        "base_local": st.ori.conjugate() * (base_w - st.pos), "base_ref": base_w,
    }


def ray_exit(poly, d):
    """Distance from the origin to the convex hull of the 2-D points poly along unit d."""
    pts = sorted(set(poly))
    if len(pts) < 3:
        return max(0.0, max(p[0] * d[0] + p[1] * d[1] for p in pts))

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    lo, hi = [], []
    for p in pts:
        while len(lo) >= 2 and cross(lo[-2], lo[-1], p) <= 0:
            lo.pop()
        lo.append(p)
    for p in reversed(pts):
        while len(hi) >= 2 and cross(hi[-2], hi[-1], p) <= 0:
            hi.pop()
        hi.append(p)
    hull = lo[:-1] + hi[:-1]
    best = 0.0
    for k in range(len(hull)):
        a, b = hull[k], hull[(k + 1) % len(hull)]
        ex, ey = b[0] - a[0], b[1] - a[1]
        den = d[0] * ey - d[1] * ex
        if abs(den) < 1e-15:
            continue
        t = (a[0] * ey - a[1] * ex) / den
        u = (a[0] * d[1] - a[1] * d[0]) / den
        if t > 0 and -1e-9 <= u <= 1 + 1e-9:
            best = max(best, t)
    return best


def alpha_toward(bid, lx, ly):
    r = ref[bid]
    n = math.hypot(lx, ly)
    d = (1.0, 0.0) if n == 0 else (lx / n, ly / n)
    return math.atan2(ray_exit(r["support"], d), r["hcom"])


def alpha_min(bid):
    return min(alpha_toward(bid, math.cos(a), math.sin(a)) for a in np.linspace(0, 2 * math.pi, 73))


# ---- initial conditions (rockdem's apply_tilt: about the support edge on the lean side) ----
for k, b in enumerate(S["bodies"]):
    bid = ids[k]
    if b["fixed"]:
        continue
    st = O.bodies[bid].state
    if b["tilt"] > 0:
        d = (math.cos(b["tilt_direction"]), math.sin(b["tilt_direction"]))
        sup = ref[bid]["support"]
        best = max(p[0] * d[0] + p[1] * d[1] for p in sup)
        sel = [p for p in sup if p[0] * d[0] + p[1] * d[1] > best - 1e-9 * (1 + abs(best))]
        piv = Vector3(st.pos[0] + sum(p[0] for p in sel) / len(sel),
                      st.pos[1] + sum(p[1] for p in sel) / len(sel), ref[bid]["zmin"])
        Q = Quaternion(Vector3(-d[1], d[0], 0), b["tilt"])
        st.pos = piv + Q * (st.pos - piv) + Vector3(0, 0, S["lift"])
        st.ori = Q * st.ori
    st.vel = Vector3(*b["velocity"])
    st.angVel = Vector3(*b["angular_velocity"])

# ---- sampling ----
crit = S["overturn"]
amin = {bid: alpha_min(bid) for bid in free}
T, POS, QUAT, VEL, ANG, TILT, GACC, KE, PE = [], [], [], [], [], [], [], [], []
summ = {bid: {"max_tilt": 0.0, "max_tilt_ratio": 0.0, "max_slide": 0.0, "overturned": 0,
              "overturn_time": -1.0} for bid in free}


def sample():
    t = O.time - t0[0]
    T.append(t)
    pos, quat, vel, ang, tilt = [], [], [], [], []
    ke = pe = 0.0
    for bid in free:
        st = O.bodies[bid].state
        r = ref[bid]
        rel = st.ori * r["ori"].conjugate()  # rotation from the rest pose
        ax, an = rel.toAxisAngle()
        w, s = math.cos(an / 2), math.sin(an / 2)
        quat.append([w, s * ax[0], s * ax[1], s * ax[2]])
        pos.append([st.pos[0], st.pos[1], st.pos[2]])
        vel.append([st.vel[0], st.vel[1], st.vel[2]])
        ang.append([st.angVel[0], st.angVel[1], st.angVel[2]])
        z = st.ori * r["up_body"]
        th = math.atan2(math.hypot(z[0], z[1]), z[2])
        tilt.append(th)
        sm = summ[bid]
        sm["max_tilt"] = max(sm["max_tilt"], th)
        ratio = th / alpha_toward(bid, z[0], z[1]) if th > 0 else 0.0
        sm["max_tilt_ratio"] = max(sm["max_tilt_ratio"], ratio)
        bw = st.pos + st.ori * r["base_local"]
        sm["max_slide"] = max(sm["max_slide"], math.hypot(bw[0] - r["base_ref"][0], bw[1] - r["base_ref"][1]))
        if crit["kind"] == "tilt-ratio":
            over = ratio >= crit["value"]
        elif crit["kind"] == "angle":
            over = th >= crit["value"]
        else:
            over = st.pos[2] - r["zmin"] < crit["value"] * (r["z0"] - r["zmin"])
        if over and not sm["overturned"]:
            sm["overturn_time"] = t
        sm["overturned"] = int(over)
        sm["final_slide"] = math.hypot(bw[0] - r["base_ref"][0], bw[1] - r["base_ref"][1])
        sm["final_tilt"] = th
        m = O.bodies[bid].state.mass
        I = O.bodies[bid].state.inertia
        wl = st.ori.conjugate() * st.angVel
        ke += 0.5 * m * st.vel.squaredNorm() + 0.5 * sum(I[j] * wl[j] ** 2 for j in range(3))
        pe += m * G * st.pos[2]
    POS.append(pos); QUAT.append(quat); VEL.append(vel); ANG.append(ang); TILT.append(tilt)
    GACC.append(ground_acc(t) if shaking[0] else [0.0, 0.0, 0.0])
    KE.append(ke); PE.append(pe)
    return all(x > math.radians(85) for x in tilt)


per = max(1, int(round(S["interval"] / DT)))
nsteps = int(round(S["duration"] / DT))
shaking[0] = bool(S["pulses"])
status = ["done"]


def sampler():
    """PyRunner every `per` steps (one O.run for the whole window: each O.run call costs a
    wait-poll of tens of ms in YADE)."""
    down = sample()
    if not all(math.isfinite(x) for row in POS[-1] for x in row):
        status[0] = "unstable"
        O.pause()
    elif crit["stop"] and down:
        status[0] = "all-overturned"
        O.pause()


sample()
O.engines = O.engines + [PyRunner(command="sampler()", iterPeriod=per, initRun=False, label="smp")]
it0 = O.iter
wall0 = time.perf_counter()
O.run(nsteps, True)
done = O.iter - it0
wall = time.perf_counter() - wall0

names = [name_of[b] for b in free]
res = dict(time=np.array(T), position=np.array(POS), quaternion=np.array(QUAT),
           velocity=np.array(VEL), angular_velocity=np.array(ANG), tilt=np.array(TILT),
           ground_acc=np.array(GACC), kinetic=np.array(KE), gravitational=np.array(PE),
           names=np.array(names), wall=wall, steps=done, settle_time=settle_time, status=status[0],
           hook_calls=hook_stats["calls"], hook_corrected=hook_stats["corrected"])
for key in ("max_tilt", "max_tilt_ratio", "max_slide", "final_slide", "overturned", "overturn_time"):
    res["sum_" + key] = np.array([summ[b].get(key, 0.0) for b in free])
res["sum_alpha"] = np.array([amin[b] for b in free])
res["mass"] = np.array([O.bodies[b].state.mass for b in free])
res["inertia"] = np.array([[O.bodies[b].state.inertia[j] for j in range(3)] for b in free])
np.savez(out_path, **res)
print("yade-run: steps=%d wall_s=%.3f wall_per_sim_s=%.4f status=%s hook=%s" % (
    done, wall, wall / max(done * DT, 1e-30), status[0], "on" if S["shear_hook"] else "off"))
for k, b in enumerate(free):
    sm = summ[b]
    print("yade-body: %s max_tilt=%.5g max_tilt_ratio=%.4g overturned=%d max_slide=%.4g" % (
        names[k], sm["max_tilt"], sm["max_tilt_ratio"], sm["overturned"], sm["max_slide"]))
sys.stdout.flush()
