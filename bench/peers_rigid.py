"""The rigid-body peers of bench/peers.py: PyBullet and MuJoCo on its scenes (the block and the
two-block stack of the validation ladder, tools/validate/ladder.py; the 4-drum column of
tests/data/yade/column.dat), run in the virtual
environment bench/peers.sh makes (pip: pybullet, mujoco). One task per call, its result as one
JSON line on stdout:

    python peers_rigid.py CODE DT free                   first impact of the block released from 10 deg
    python peers_rigid.py CODE DT threshold SCENE FREQ STATIC   minimum overturning one-sine
                                                         amplitude, scanned from 0.9 x STATIC (m/s^2)
    python peers_rigid.py CODE DT history SCENE AMP_G T  max tilt per body under a one-sine pulse

CODE: pybullet or mujoco; DT: the code's fixed step (s); SCENE: block, stack or column.
Options before CODE: --ground plane|box (the fixed base: an infinite plane, or a 20 x 20 x 1 m
box whose top is z = 0; default plane), --friction DEG (every contact's friction angle,
default 80). bench/peers.py searches both, as it searches the step.
Each code is used as a user would: its own contact model and solver defaults, the step the one
setting varied (MuJoCo's contact time constant follows it at 2 dt, the stiffest its
documentation recommends). Ground motion: the pulse enters as the inertial force -m ug''(t)
along +x on every body (the ground frame; rockdem's and YADE's moving base is the same motion).
Overturning: any body's tilt beyond 1.5 times its alpha (the scenes' `model overturn tilt-ratio
1.5`). The search is rd_threshold's: 24 coarse steps from 0.9 to 10 times STATIC (rockdem's
static uplift threshold of the scene), then bisection to a relative bracket of 0.005. Units SI.
"""
import json
import math
import sys
import time

G = 9.81                  # m/s^2, the scenes' gravity
DENSITY = 2700.0          # kg/m^3
FRICTION_DEG = 80.0       # default friction angle of every contact, deg (--friction)
GROUND_HALF = (10.0, 10.0, 0.5)  # m: the box ground's half extents (--ground box), top at z = 0
OVER_RATIO = 1.5          # tilt / alpha that counts as overturned
SETTLE = 0.2              # s at rest on the ground before the pulse (contact transients)
NSCAN, RTOL = 24, 0.005   # rd_threshold's defaults


def box(hx, hy, hz, z, name):
    return {"kind": "box", "half": (hx, hy, hz), "pos": (0.0, 0.0, z), "name": name,
            "mass": DENSITY * 8 * hx * hy * hz, "alpha": math.atan(min(hx, hy) / hz)}


def prism(sides, radius, height, z, name):
    """An N-sided drum (circumradius, height), as rd_poly_prism: a vertex on +x."""
    verts = []
    for zz in (-height / 2, height / 2):
        for k in range(sides):
            a = 2 * math.pi * k / sides
            verts.append((radius * math.cos(a), radius * math.sin(a), zz))
    apothem = radius * math.cos(math.pi / sides)
    area = 0.5 * sides * radius * radius * math.sin(2 * math.pi / sides)
    return {"kind": "mesh", "verts": verts, "pos": (0.0, 0.0, z), "name": name,
            "mass": DENSITY * area * height, "alpha": math.atan(apothem / (height / 2))}


def scene(name, friction_deg=FRICTION_DEG):
    """Free bodies of the scene (the fixed base: the plane z = 0): the ladder's 0.5 x 0.5 x 1.0 m
    block, its stack (a 0.4 x 0.4 x 0.8 m block on it), tests/data/yade/column.dat's drums."""
    mu = math.tan(math.radians(friction_deg))
    if name == "block":
        return [box(0.25, 0.25, 0.5, 0.5, "block")], mu
    if name == "stack":
        return [box(0.25, 0.25, 0.5, 0.5, "lower"), box(0.2, 0.2, 0.4, 1.4, "upper")], mu
    if name == "column":
        return [prism(12, 0.3, 0.6, 0.3 + 0.6 * k, "d%d" % (k + 1)) for k in range(4)], mu
    raise SystemExit("peers_rigid: unknown scene %r" % name)


def one_sine(amp, freq):
    """ug''(t) of a one-sine pulse starting at t = 0 (m/s^2)."""
    w = 2 * math.pi * freq
    return lambda t: amp * math.sin(w * t) if 0 <= t <= 1 / freq else 0.0


# ---- PyBullet ------------------------------------------------------------------------------------
class Bullet:
    def __init__(self, bodies, mu, dt, tilt0=0.0, ground="plane"):
        import pybullet as p
        self.p = p
        self.cid = p.connect(p.DIRECT)
        p.setGravity(0, 0, -G, physicsClientId=self.cid)
        p.setPhysicsEngineParameter(fixedTimeStep=dt, physicsClientId=self.cid)
        if ground == "box":
            plane = p.createMultiBody(0, p.createCollisionShape(p.GEOM_BOX, halfExtents=GROUND_HALF,
                                                                physicsClientId=self.cid),
                                      basePosition=(0, 0, -GROUND_HALF[2]), physicsClientId=self.cid)
        else:
            plane = p.createMultiBody(0, p.createCollisionShape(p.GEOM_PLANE, physicsClientId=self.cid),
                                      physicsClientId=self.cid)
        # Bullet multiplies the two friction and restitution coefficients of a pair
        p.changeDynamics(plane, -1, lateralFriction=1.0, restitution=0.0, physicsClientId=self.cid)
        self.ids, self.mass = [], []
        for b in bodies:
            if b["kind"] == "box":
                shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=b["half"], physicsClientId=self.cid)
            else:
                shape = p.createCollisionShape(p.GEOM_MESH, vertices=b["verts"], physicsClientId=self.cid)
            pos, q = placed(b, tilt0)
            bid = p.createMultiBody(b["mass"], shape, basePosition=pos, baseOrientation=(q[1], q[2], q[3], q[0]),
                                    physicsClientId=self.cid)
            p.changeDynamics(bid, -1, lateralFriction=mu, restitution=0.0, physicsClientId=self.cid)
            self.ids.append(bid)
            self.mass.append(b["mass"])

    def step(self, ag):
        p = self.p
        for bid, m in zip(self.ids, self.mass):
            pos, _ = p.getBasePositionAndOrientation(bid, physicsClientId=self.cid)
            p.applyExternalForce(bid, -1, (-m * ag, 0, 0), pos, p.WORLD_FRAME, physicsClientId=self.cid)
        p.stepSimulation(physicsClientId=self.cid)

    def axes(self):
        """Each body's rest-vertical axis in the world (x, z components)."""
        out = []
        for bid in self.ids:
            _, q = self.p.getBasePositionAndOrientation(bid, physicsClientId=self.cid)
            m = self.p.getMatrixFromQuaternion(q)
            out.append((m[2], m[8]))
        return out

    def close(self):
        self.p.disconnect(physicsClientId=self.cid)


# ---- MuJoCo --------------------------------------------------------------------------------------
class Mujoco:
    def __init__(self, bodies, mu, dt, tilt0=0.0, ground="plane"):
        import mujoco
        import numpy as np
        self.mj, self.np = mujoco, np
        tc = 2 * dt  # contact time constant, s: the stiffest MuJoCo recommends (>= 2 steps)
        assets, world = [], []
        for k, b in enumerate(bodies):
            pos, q = placed(b, tilt0)
            if b["kind"] == "box":
                geom = '<geom type="box" size="%g %g %g"/>' % b["half"]
            else:
                assets.append('<mesh name="m%d" vertex="%s"/>' % (k, " ".join("%.9g" % c for v in b["verts"] for c in v)))
                geom = '<geom type="mesh" mesh="m%d"/>' % k
            world.append('<body name="%s" pos="%.12g %.12g %.12g" quat="%.12g %.12g %.12g %.12g"><freejoint/>%s</body>'
                         % ((b["name"],) + tuple(pos) + tuple(q) + (geom,)))
        floor = ('<geom type="box" size="%g %g %g" pos="0 0 %g"/>' % (GROUND_HALF + (-GROUND_HALF[2],))
                 if ground == "box" else '<geom type="plane" size="10 10 0.1"/>')
        xml = ('<mujoco><option timestep="%g" gravity="0 0 %g"/>'
               '<default><geom density="%g" friction="%g 0.005 0.0001" solref="%g 1"/></default>'
               '<asset>%s</asset><worldbody>%s%s</worldbody></mujoco>'
               % (dt, -G, DENSITY, mu, tc, "".join(assets), floor, "".join(world)))
        self.model = mujoco.MjModel.from_xml_string(xml)
        self.data = mujoco.MjData(self.model)
        self.bid = [self.model.body(b["name"]).id for b in bodies]
        self.mass = [float(self.model.body_mass[i]) for i in self.bid]

    def step(self, ag):
        for i, m in zip(self.bid, self.mass):
            self.data.xfrc_applied[i, 0] = -m * ag
        self.mj.mj_step(self.model, self.data)

    def axes(self):
        return [(float(self.data.xmat[i][2]), float(self.data.xmat[i][8])) for i in self.bid]

    def close(self):
        pass


def placed(b, tilt0):
    """Position and quaternion (w, x, y, z) of body b, tilted by tilt0 (rad) about y on its +x
    bottom edge (that edge stays on the ground)."""
    x, y, z = b["pos"]
    if tilt0 == 0.0:
        return (x, y, z), (1.0, 0.0, 0.0, 0.0)
    hx, _, hz = b["half"]
    c, s = math.cos(tilt0), math.sin(tilt0)
    # the edge (hx, -hz) goes to (hx c - hz s, -hx s - hz c): keep it at (hx, 0)
    return (x + hx - (hx * c - hz * s), y, hx * s + hz * c), (math.cos(tilt0 / 2), 0.0, math.sin(tilt0 / 2), 0.0)


OPTS = {"ground": "plane", "friction": FRICTION_DEG}  # set by main from --ground, --friction


def make(code, bodies, mu, dt, tilt0=0.0):
    return (Bullet if code == "pybullet" else Mujoco)(bodies, mu, dt, tilt0, OPTS["ground"])


class Clock:
    """Wall time spent stepping and the simulated time it covered."""
    def __init__(self):
        self.wall, self.sim = 0.0, 0.0


def run_pulse(code, name, dt, amp, freq, T, clock, stop_on_over=True):
    """(overturned, max tilt per body, rad) under a one-sine pulse of amp (m/s^2)."""
    bodies, mu = scene(name, OPTS["friction"])
    sim = make(code, bodies, mu, dt)
    ag = one_sine(amp, freq)
    nset, n = int(round(SETTLE / dt)), int(round(T / dt))
    alpha = [b["alpha"] for b in bodies]
    peak = [0.0] * len(bodies)
    over = False
    t0 = time.perf_counter()
    steps = 0
    for k in range(nset + n):
        sim.step(ag((k - nset) * dt) if k >= nset else 0.0)
        steps += 1
        if k % 10 == 0 or k == nset + n - 1:
            for i, (ax, az) in enumerate(sim.axes()):
                th = math.acos(max(-1.0, min(1.0, az)))
                peak[i] = max(peak[i], th)
                if th > OVER_RATIO * alpha[i]:
                    over = True
            if over and stop_on_over:
                break
    clock.wall += time.perf_counter() - t0
    clock.sim += steps * dt
    sim.close()
    return over, peak


def task_free(code, dt):
    """First impact time (s) of the block released from rest at 10 deg (tests/data/yade/free.dat):
    the first zero of its signed tilt, by linear interpolation between steps."""
    bodies, mu = scene("block", OPTS["friction"])
    sim = make(code, bodies, mu, dt, math.radians(10))
    clock = Clock()
    prev, t_imp = None, None
    t0 = time.perf_counter()
    k = 0
    while k * dt < 1.5:
        sim.step(0.0)
        k += 1
        ax, az = sim.axes()[0]
        th = math.atan2(ax, az)
        if prev is not None and prev > 0 >= th:
            t_imp = (k - 1) * dt + dt * prev / (prev - th)
            break
        prev = th
    clock.wall, clock.sim = time.perf_counter() - t0, k * dt
    sim.close()
    return {"impact_time": t_imp, "wall_s": clock.wall, "sim_s": clock.sim}


def task_threshold(code, dt, name, freq, static):
    lo, hi = 0.9 * static, 10 * static
    clock = Clock()
    t_run = 3.0
    runs = 0
    t0 = time.perf_counter()
    below, above = lo, None
    for k in range(NSCAN + 1):
        a = lo + (hi - lo) * k / NSCAN
        runs += 1
        if run_pulse(code, name, dt, a, freq, t_run, clock)[0]:
            above = a
            break
        below = a
    if above is not None and above > lo:
        while (above - below) / above > RTOL:
            mid = 0.5 * (below + above)
            runs += 1
            if run_pulse(code, name, dt, mid, freq, t_run, clock)[0]:
                above = mid
            else:
                below = mid
    return {"threshold": above, "below": below, "runs": runs, "search_wall_s": time.perf_counter() - t0,
            "wall_s": clock.wall, "sim_s": clock.sim}


def task_history(code, dt, name, amp_g, T):
    clock = Clock()
    over, peak = run_pulse(code, name, dt, amp_g * 9.80665, 2.0, T, clock, stop_on_over=False)
    return {"overturned": over, "max_tilt": peak, "wall_s": clock.wall, "sim_s": clock.sim}


def main(argv):
    argv = list(argv)
    while len(argv) > 2 and argv[1] in ("--ground", "--friction"):
        if argv[1] == "--ground":
            if argv[2] not in ("plane", "box"):
                raise SystemExit("peers_rigid: --ground expects plane or box, got %r" % argv[2])
            OPTS["ground"] = argv[2]
        else:
            OPTS["friction"] = float(argv[2])
        del argv[1:3]
    if len(argv) < 4 or argv[1] not in ("pybullet", "mujoco"):
        raise SystemExit(__doc__)
    code, dt, task = argv[1], float(argv[2]), argv[3]
    if task == "free":
        out = task_free(code, dt)
    elif task == "threshold":
        out = task_threshold(code, dt, argv[4], float(argv[5]), float(argv[6]))
    elif task == "history":
        out = task_history(code, dt, argv[4], float(argv[5]), float(argv[6]))
    else:
        raise SystemExit(__doc__)
    print(json.dumps(out))


if __name__ == "__main__":
    main(sys.argv)
