#!/usr/bin/env bash
# Runout after the topple (docs/RUNOUT.md), against closed forms:
#  1. Coulomb slide down a 20 deg slope (friction 30 deg) from v0 = 2 m/s: it stops after
#     s = v0^2 / (2 g (mu cos psi - sin psi)) along the slope; `model solve until rest` ends the
#     run RD_REST_HOLD = 0.1 s after it stops. The same on a slope read from an ESRI grid.
#  2. A fence across the slope 0.5 m (plan) below the start: kinetic energy there
#     1/2 m (v0^2 - 2 a s), s = 0.5 / cos psi; the centre's height above the slope 0.1 / cos psi.
#     Two named fences (0.3 m and 0.6 m, the second a bent polyline): each from the same form,
#     and the sweep table's per-fence columns equal to the run file's.
#  3. A domain box ending 0.3 m (plan) below the start: the block leaves it when
#     v0 t - a t^2 / 2 = 0.3 / cos psi.
#  4. A 0.6 x 0.6 x 1.0 m block toppling from 1 deg past balance onto its side (friction 80 deg:
#     the pivot holds to the landing, N > 0.07 m g and |H| < mu N all the way by the rigid
#     model): kinetic energy at landing m g (z0 - b), speed of its centre omega R with
#     omega^2 = 2 m g (z0 - b) / I_O, I_O = 4/3 m R^2.
# Tolerances: the run's own change when the step is halved (its discretisation error), plus,
# for the slide, the shear spring's elastic stretch mu m g cos psi / (KS A) at the stop (a rigid
# block has none), and for the landing twice the friction booked before it (the pivot's slip).
#  5. The same slide on a non-convex terrain mesh (a slope, then level): the vertex model has no
#     contact there (check and run refuse the pair); the surface model holds it and stops it where the
#     Coulomb closed form does (its dashpot along the terrain's normal: docs/CONTACT.md 8.8).
#  6. A cube landing flat on a soil joint with a dashpot (surface model): its restitution
#     against the linear spring-dashpot let go at zero force.
#  7. tools/rdrunout.py draws a plan view of several runs (one path each) and the sweep's
#     exceedance curves, and refuses bad input with one line and exit 2.
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/runout; rm -rf "$T"; mkdir -p "$T"
PY=/usr/bin/python3
fails=0
run() { # NAME FILE ARGS...
    local name=$1 file=$2; shift 2
    "$BIN" run "$file" -q -o "$T/$name.h5" "$@" > "$T/$name.log" 2>&1 ||
        { echo "FAIL $name: exit $? ($(tail -1 "$T/$name.log"))"; fails=$((fails + 1)); }
}
$PY - "$T" <<'PY'
import math, sys
T = sys.argv[1]
psi = math.radians(20); d = (math.cos(psi), 0, -math.sin(psi)); n = (math.sin(psi), 0, math.cos(psi))
c = [(0.25 + 0.1) * n[k] - 2.0 * d[k] for k in range(3)]
block = f"""block create brick size 0.4 0.4 0.2 position {c[0]:.12f} 0 {c[2]:.12f} rotation 0 20 0 name b
block initial name b velocity {2 * d[0]:.12f} 0 {2 * d[2]:.12f}
contact property friction 30
model solve until rest time-limit 5
"""
slope = "block create brick size 6 2 0.5 position 0 0 0 rotation 0 20 0 fixed name slope\n"
open(f"{T}/slide.dat", "w").write(slope + block)
fx = c[0] + 0.5
open(f"{T}/fence.dat", "w").write(slope + block + f"model fence points {fx:.12f} -3 {fx:.12f} 3\n")
# two named fences, 0.3 m and 0.6 m (plan) below the start; the lower one a bent polyline
fu, fl = c[0] + 0.3, c[0] + 0.6
open(f"{T}/fences.dat", "w").write(slope + block +
    f"model fence points {fu:.12f} -3 {fu:.12f} 3 name upper\n"
    f"model fence points {fl:.12f} -3 {fl:.12f} 0.05 {fl:.12f} 3 name lower\n")
open(f"{T}/domain.dat", "w").write(slope + block +
    f"model domain box -10 {c[0] + 0.3:.12f} -10 10 -10 10\n")
# the same slope as an ESRI ASCII grid (heights at the cell centres), the block on its plane
rows = [" ".join("%.12f" % (-math.tan(psi) * (i + 0.5)) for i in range(5)) for r in range(3)]
open(f"{T}/slope.asc", "w").write("ncols 5\nnrows 3\nxllcorner 0\nyllcorner 1\ncellsize 1\n"
                                  "NODATA_value -9999\n" + "\n".join(rows) + "\n")
x0 = 1.5; cc = [x0 + 0.1 * n[0], 2.5, -math.tan(psi) * x0 + 0.1 * n[2]]
tb = block.replace(f"position {c[0]:.12f} 0 {c[2]:.12f}", f"position {cc[0]:.12f} 2.5 {cc[2]:.12f}")
open(f"{T}/terrain.dat", "w").write("block import terrain 'slope.asc' name ground\n" + tb)
# the same grid as XYZ points, shuffled, comma-separated
import random
pts = [(i + 0.5, 1 + j + 0.5, -math.tan(psi) * (i + 0.5)) for i in range(5) for j in range(3)]
random.Random(1).shuffle(pts)
open(f"{T}/slope.xyz", "w").write("# x, y, z (m)\n" + "".join("%.12f,%.12f,%.12f\n" % p for p in pts))
open(f"{T}/terrain_xyz.dat", "w").write("block import terrain 'slope.xyz' name ground\n" + tb)
# a non-convex terrain: the slope, then a level runout beyond x = 9 m
rows = [" ".join("%.12f" % (-math.tan(psi) * min(i + 0.5, 9.0)) for i in range(13)) for r in range(5)]
open(f"{T}/kink.asc", "w").write("ncols 13\nnrows 5\nxllcorner 0\nyllcorner 0\ncellsize 1\n" +
                                 "\n".join(rows) + "\n")
open(f"{T}/kink.dat", "w").write("block import terrain 'kink.asc' name ground\n" +
    tb.replace("until rest time-limit 5", "time 0.3"))
open(f"{T}/kink_surface.dat", "w").write("block import terrain 'kink.asc' name ground\n" + tb +
    "contact model surface\ncontact property restitution 1\nmodel damping viscous 0.1\n")
# a 64-sided prism (R 0.3 m) lying on a 10 deg incline, a face down, released from rest
N, Rw, pw = 64, 0.3, math.radians(10)
dw, nw = (math.cos(pw), 0, -math.sin(pw)), (math.sin(pw), 0, math.cos(pw))
cw = [(0.25 + Rw * math.cos(math.pi / N)) * nw[k] - 2.5 * dw[k] for k in range(3)]
open(f"{T}/roll.dat", "w").write(f"""block create brick size 8 2 0.5 position 0 0 0 rotation 0 10 0 fixed name slope
block create prism sides {N} radius {Rw} height 0.3 position {cw[0]:.12f} 0 {cw[2]:.12f} rotation 90 {10 + 180 / N:.10f} 0 name w
contact property friction 60
model settle off
model overturn tilt-ratio 1.5 stop off
model solve time 0.8
""")
# a brick thrown straight up at 1 m/s off a floor: its bounce (lowest corner's height) v^2 / 2g
open(f"{T}/hop.dat", "w").write("""block create brick size 2 2 0.5 position 0 0 -0.25 fixed name floor
block create brick size 0.4 0.4 0.2 seat-on floor name b
block initial name b velocity 0 0 1
contact property friction 30
model solve time 0.15
""")
open(f"{T}/topple.dat", "w").write("""block create brick size 4 2 0.5 position 0 0 -0.25 fixed name floor
block create brick size 0.6 0.6 1.0 seat-on floor name b
block initial name b tilt 31.96375653207352 direction 0
contact property friction 80
model overturn tilt-ratio 1.5 stop off
model solve time 1.6
""")
PY
half() { sed 's/^contact property friction \([0-9]*\)$/contact property friction \1\nmodel timestep auto safety 0.1/' "$1" > "${1%.dat}_h.dat"; }
for s in slide fence fences domain terrain topple roll hop; do half "$T/$s.dat"; run $s "$T/$s.dat"; run ${s}_h "$T/${s}_h.dat"; done
"$BIN" run "$T/kink.dat" -q -o "$T/kink.h5" > "$T/kink.log" 2>&1 # refused: exit 3
run kink_surface "$T/kink_surface.dat"
# the XYZ points give the ESRI grid's solid: the same volume and centre of mass
vol() { "$BIN" check "$1" 2>&1 | awk '/^  ground/ { for (i = 1; i < NF; i++) if ($i == "volume") print $(i + 1) }'; }
va=$(vol "$T/terrain.dat"); vx=$(vol "$T/terrain_xyz.dat")
if [ -n "$va" ] && [ "$va" = "$vx" ]; then echo "CHECK terrain from XYZ points: volume $vx m^3 as from the ESRI grid"
else echo "FAIL terrain from XYZ points: volume '$vx' against '$va'"; fails=$((fails + 1)); fi

$PY - "$T" <<'PY' || fails=$((fails + 1))
import h5py, math, sys
T = sys.argv[1]
g, psi, mu, v0 = 9.81, math.radians(20), math.tan(math.radians(30)), 2.0
a = g * (mu * math.cos(psi) - math.sin(psi))
def rec(name):
    f = h5py.File(f"{T}/{name}.h5", "r")
    q = [x.decode() if isinstance(x, bytes) else x for x in f["runout/quantity"][:]]
    return dict(zip(q, f["runout/bodies"][0])), f
bad = 0
def check(what, got, want, tol):
    global bad
    gap = abs(got - want); ok = gap <= tol
    print(("CHECK" if ok else "FAIL") + f" {what}: {got:.7g} against {want:.7g}, gap={gap:.3g} tol={tol:.3g}")
    bad += not ok
m = 0.4 * 0.4 * 0.2 * 2700; A = 0.4 * 0.4; stretch = mu * m * g * math.cos(psi) / (1e11 * A)
s_stop = v0 ** 2 / (2 * a)
for name in ("slide", "terrain"):
    r, f = rec(name); rh, fh = rec(name + "_h")
    check(f"{name}: Coulomb stop distance along the slope (m)", r["path_length"], s_stop,
          abs(r["path_length"] - rh["path_length"]) + stretch)
r, f = rec("slide"); rh, fh = rec("slide_h")
end, endh = f["summary"].attrs["end_time"], fh["summary"].attrs["end_time"]
# the rest test (kinetic energy below 1e-7 m g r, r its bounding radius) passes when the speed
# falls below sqrt(2e-7 g r), that long before the exact stop
r_b = math.sqrt(0.2 ** 2 + 0.2 ** 2 + 0.1 ** 2); early = math.sqrt(2e-7 * g * r_b) / a
check("until rest: run ends 0.1 s after the stop (s)", end, v0 / a + 0.1,
      abs(end - endh) + 2 * f["summary"].attrs["dt"] + early)
check("until rest: at_rest", f["summary"].attrs["at_rest"], 1, 0)
r, f = rec("fence"); rh, fh = rec("fence_h")
s = 0.5 / math.cos(psi); ke = 0.5 * m * (v0 ** 2 - 2 * a * s)
# the crossing's energy is its step's (leapfrog's half-step velocity): within m v a dt of the
# crossing instant's
dt = f["summary"].attrs["dt"]; within = m * math.sqrt(2 * ke / m) * a * dt
check("fence: kinetic energy at the crossing (J)", r["fence_energy"], ke,
      abs(r["fence_energy"] - rh["fence_energy"]) + ke * 2 * stretch / s + within)
check("fence: centre height above the slope (m)", r["fence_height"], 0.1 / math.cos(psi), abs(r["fence_height"] - rh["fence_height"]) + 1e-6)
check("fence: crossings", r["fence_crossings"], 1, 0)
# several fences: each its own crossing, from the same closed form; the first also in
# /runout/bodies
f, fh = (h5py.File(f"{T}/{n}.h5", "r") for n in ("fences", "fences_h"))
names = list(f["runout/fences"].keys())
check("fences: both written", sorted(names) == ["lower", "upper"], 1, 0)
r0, f0 = rec("fences")
for name, plan in (("upper", 0.3), ("lower", 0.6)):
    q = [x.decode() if isinstance(x, bytes) else x for x in f[f"runout/fences/{name}/quantity"][:]]
    h, hh = (dict(zip(q, g[f"runout/fences/{name}/bodies"][0])) for g in (f, fh))
    s = plan / math.cos(psi); ke = 0.5 * m * (v0 ** 2 - 2 * a * s)
    within = m * math.sqrt(2 * ke / m) * a * dt
    check(f"fence '{name}' {plan} m below: kinetic energy (J)", h["energy"], ke,
          abs(h["energy"] - hh["energy"]) + ke * 2 * stretch / s + within)
    check(f"fence '{name}': crossings", h["crossings"], 1, 0)
    if name == "upper":
        check("fences: /runout/bodies holds the first", r0["fence_energy"], h["energy"], 0)
r, f = rec("domain"); rh, fh = rec("domain_h")
s = 0.3 / math.cos(psi); t_left = (v0 - math.sqrt(v0 ** 2 - 2 * a * s)) / a
check("domain: time the block leaves the box (s)", r["left_time"], t_left, abs(r["left_time"] - rh["left_time"]) + 2 * f["summary"].attrs["dt"])
check("domain: at rest once every body is out", f["summary"].attrs["at_rest"], 1, 0)
r, f = rec("topple"); rh, fh = rec("topple_h")
b, h = 0.3, 0.5; R = math.hypot(b, h); mt = 0.6 * 0.6 * 1.0 * 2700
z0 = f["position"][0, 0, 2]; ke = mt * g * (z0 - b); v = math.sqrt(2 * g * (z0 - b) / (4 / 3 * R * R)) * R
# dissipation before the landing: friction and damping booked at the last sample before it (the
# one of largest kinetic energy), doubled for the part of a sample interval left to the landing
kes = f["energy/kinetic"][:]; i = int(kes.argmax())
fric = 2 * (f["energy/friction"][i] + f["energy/damping"][i])
check("topple: kinetic energy at landing (J)", r["max_energy"], ke, abs(r["max_energy"] - rh["max_energy"]) + fric)
check("topple: landing speed of the centre (m/s)", r["max_speed"], v, abs(r["max_speed"] - rh["max_speed"]) + v * fric / ke)
r, f = rec("hop"); rh, fh = rec("hop_h"); dt = f["summary"].attrs["dt"]
check("bounce of a brick thrown up at 1 m/s (m)", r["max_bounce"], 1 / (2 * g),
      abs(r["max_bounce"] - rh["max_bounce"]) + g * (8 * dt) ** 2 / 8 + 1.0 * dt / 2)
# (measured every 8 steps: g (8 dt)^2 / 8; the initial velocity is leapfrog's half-step one, a
# launch half a step early or late: v0 dt / 2)
r, f = rec("kink_surface")
check("surface model on a non-convex terrain mesh: held, at rest", f["summary"].attrs["at_rest"], 1, 0)
# the slide check's tolerance on the ESRI slope (its step change plus the spring's stretch)
check("surface model on a triangulated terrain: Coulomb stop distance (m)", r["path_length"],
      s_stop, 1.6e-5)
# the rolling prism: the cylinder's s = a t^2 / 2, a = g sin psi / (1 + I / (m R^2)) (R the
# rolling radius R sin(pi/N) / (pi/N)), is the limit of many sides; a polygon pivots about a
# corner between plastic corner impacts (the rigid rimless wheel: omega+ = eta omega-,
# eta = 1 - (m R^2 / I_O)(1 - cos 2 pi / N)), which keeps it 8 % behind the cylinder at 0.79 s.
# The prism is placed unseated (settle off: it cannot rest on the incline), drops into its
# springs and rolls 29 % ahead of the rimless wheel in the first 0.02 s, so the wheel starts
# from rockdem's state at t1 = 0.1 s (its corner angle and spin) and the distances from t1 to
# 0.79 s are compared. Tolerance: the rimless wheel with eta times 0.997 and 1.001, the default
# contact's measured per-impact range of Housner's r (docs/GUIDE.md `contact property`), plus
# the step change.
from scipy.integrate import solve_ivp
import numpy as np
def rimless(N, R, psi, t, T, phi, w, fac=1.0):
    I = R * R * (1 + 2 * math.cos(math.pi / N) ** 2) / 6; IO = I + R * R
    eta = fac * (1 - (R * R / IO) * (1 - math.cos(2 * math.pi / N)))
    L, k, s0, ts, ss = 2 * R * math.sin(math.pi / N), 0, R * math.sin(phi), [t], [0.0]
    hit = lambda t, y: y[0] - math.pi / N
    hit.terminal, hit.direction = True, 1
    while t < T:
        sol = solve_ivp(lambda t, y: [y[1], g * R * math.sin(y[0] + psi) / IO], (t, T), [phi, w],
                        events=hit, rtol=1e-11, atol=1e-13, dense_output=True)
        tt = np.linspace(t, sol.t[-1], 200)
        ts += list(tt[1:]); ss += list(k * L + R * np.sin(sol.sol(tt[1:])[0]) - s0)
        t = sol.t[-1]
        if sol.status == 1: phi, w, k = -math.pi / N, eta * sol.y[1][-1], k + 1
    return np.array(ts), np.array(ss), I
def qmul(a, b):
    w1, x1, y1, z1 = a; w2, x2, y2, z2 = b
    return [w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2]
Nw, Rw, pw, t1, t2 = 64, 0.3, math.radians(10), 0.1, 0.79
def rolled(name):
    f = h5py.File(f"{T}/{name}.h5", "r"); t = f["time"][:]; x = f["position"][:, 0]
    sl = (x - x[0]) @ np.array([math.cos(pw), 0, -math.sin(pw)])
    i = int(np.searchsorted(t, t1)); q0 = f["quaternion"][0, 0]
    qr = qmul(f["quaternion"][i, 0], [q0[0], -q0[1], -q0[2], -q0[3]])
    th = 2 * math.atan2(qr[2], qr[0]); step = 2 * math.pi / Nw
    phi = -math.pi / Nw + th - math.floor(th / step) * step  # from the pivot's normal
    return float(np.interp(t2, t, sl)) - sl[i], t[i], phi, f["angular_velocity"][i, 0, 1]
got, ti, phi1, w1 = rolled("roll"); goth = rolled("roll_h")[0]
ref = {fac: float(np.interp(t2, *rimless(Nw, Rw, pw, ti, 0.8, phi1, w1, fac)[:2]))
       for fac in (0.997, 1.0, 1.001)}
Iw = rimless(Nw, Rw, pw, 0, 1e-3, 0, 0)[2]; Reff = Rw * math.sin(math.pi / Nw) / (math.pi / Nw)
acyl = g * math.sin(pw) / (1 + Iw / Reff ** 2)
gap = got - ref[1.0]; lo, hi = ref[0.997] - ref[1.0] - abs(got - goth), ref[1.001] - ref[1.0] + abs(got - goth)
ok = lo <= gap <= hi
print(("CHECK" if ok else "FAIL") + f" rolling 64-sided prism, distance from {t1} to {t2} s (m): "
      f"{got:.6g} against the rimless wheel {ref[1.0]:.6g} gap={gap:.3g} tol=[{lo:.3g},{hi:.3g}] "
      f"(cylinder from rest to {t2} s: {0.5 * acyl * t2 * t2:.5g} m, a = {acyl:.5g} m/s^2)")
bad += not ok
check("topple: energy residual below 1e-3", f["summary"].attrs["energy_residual_max"], 0, 1e-3)
sys.exit(1 if bad else 0)
PY
# the sweep table: per-fence columns on the fence axis, the same figures as the run files
"$BIN" sweep "$T/fences.dat" --axis contact.friction=30,32 -j 1 -q -o "$T/fences_sweep.h5" > "$T/sweep.log" 2>&1 ||
    { echo "FAIL fences sweep: $(tail -1 "$T/sweep.log")"; fails=$((fails + 1)); }
$PY - "$T" <<'PY' || fails=$((fails + 1))
import h5py, sys
T = sys.argv[1]
t = h5py.File(f"{T}/fences_sweep.h5", "r")["sweep"]
names = [x.decode() if isinstance(x, bytes) else x for x in t["fence"][:]]
e = t["fence_max_energy"][:]; n = t["fence_crossed"][:]; fr = t["contact.friction"][:]
f = h5py.File(f"{T}/fences.h5", "r")
want = {k: f[f"runout/fences/{k}/bodies"][0, 2] for k in names}
row = [i for i in range(len(fr)) if fr[i] == 30][0]
ok = names == ["upper", "lower"] and e.shape == (2, 2) and (n == 1).all() and \
    all(abs(e[row, j] - want[k]) <= 1e-9 * want[k] for j, k in enumerate(names)) and \
    abs(t["fence_energy"][row] - max(want.values())) <= 1e-9 * max(want.values())
print(("CHECK" if ok else "FAIL") + f" sweep per-fence columns: fence {names}, fence_max_energy "
      f"{e.tolist()} against the run's {want}, fence_crossed {n.tolist()}")
sys.exit(0 if ok else 1)
PY
# impact loss on soil under the surface model: the soil joint's dashpot (ratio 0.3) on a cube
# landing flat at 1 m/s; its restitution against the linear spring-dashpot's, m x'' + c x' + k x
# = m g (k = KN A, c = 2 zeta sqrt(k m)), let go at zero force (Schwager and Poeschel 2007: 0.451
# without gravity), integrated here; tolerance the run's change when the step is halved
cat > "$T/soil_drop.dat" <<'EOF'
block create brick size 2 2 1 position 0 0 -0.5 fixed name floor group 'soil'
block create brick size 0.5 0.5 0.5 position 0 0 0.251 name b
block initial name b velocity 0 0 -1
contact model surface
contact property restitution 1
contact property friction 35 damping 0.3 restitution 1 range group 'soil'
model settle off
model solve time 0.01
output hdf5 'soil_drop.h5' interval 1e-5
EOF
sed 's/^model settle off$/&\nmodel timestep auto safety 0.1/' "$T/soil_drop.dat" > "$T/soil_drop_h.dat"
run soil_drop "$T/soil_drop.dat"; run soil_drop_h "$T/soil_drop_h.dat"
$PY - "$T" <<'PY' || fails=$((fails + 1))
import math, sys, h5py, numpy as np
from scipy.integrate import solve_ivp
T = sys.argv[1]
def rebound(name):
    v = h5py.File(f"{T}/{name}.h5", "r")["velocity"][:, -1, 2]
    k = int(np.argmin(v))                  # the last sample before the push turns it
    return v[k], v[k:].max()
vin, vout = rebound("soil_drop"); _, vout_h = rebound("soil_drop_h")
m, k, g, zeta = 2700 * 0.125, 1e10 * 0.25, 9.81, 0.3
c = 2 * zeta * math.sqrt(k * m)
def let_go(t, y):                          # the contact force, compression x > 0
    return k * y[0] + c * y[1]
let_go.terminal, let_go.direction = True, -1
sol = solve_ivp(lambda t, y: [y[1], g - (k * y[0] + c * y[1]) / m], (0, 0.01), [0, -vin],
                events=let_go, rtol=1e-11, atol=1e-14, max_step=1e-6)
e_ref = sol.y_events[0][0][1] / vin
e, e_h = vout / -vin, vout_h / -vin
tol = abs(e - e_h)
# the half step's run must meet it; the default step's is reported (its leapfrog dashpot keeps
# a few per cent more of the speed: an expected failure with its gap when outside)
ok = abs(e_h - e_ref) <= tol
print(("CHECK" if ok else "FAIL") + f" soil impact restitution at the half step (dashpot 0.3, surface model): "
      f"{e_h:.5f} against {e_ref:.5f}, gap={abs(e_h - e_ref):.3g} tol={tol:.3g}")
print(("CHECK" if abs(e - e_ref) <= tol else "XFAIL:") + f" soil impact restitution at the default step: "
      f"{e:.5f} against {e_ref:.5f}, gap={abs(e - e_ref):.3g} tol={tol:.3g}")
sys.exit(0 if ok else 1)
PY
# tools/rdrunout.py: the plan view of two runs over the ESRI grid (a path each), the sweep's
# exceedance curves (a PNG), and bad input as one line with exit 2
png_ok() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' ')" = 89504e470d0a1a0a ] && [ "$(stat -c %s "$1")" -gt 10000 ]; }
tool() { # NAME EXPECT ARGS...: the tool's output must hold EXPECT
    local name=$1 want=$2; shift 2
    if $PY tools/rdrunout.py "$@" > "$T/tool.log" 2>&1 && grep -q "$want" "$T/tool.log"; then
        echo "CHECK rdrunout $name: $(tail -1 "$T/tool.log")"
    else echo "FAIL rdrunout $name: $(tail -1 "$T/tool.log")"; fails=$((fails + 1)); fi
}
tool "plan of two runs" ": 2 paths from 2 run files" plan "$T/terrain.h5" "$T/terrain_h.h5" --labels dt,half \
    --terrain "$T/slope.asc" -o "$T/plan.png" --dpi 100
png_ok "$T/plan.png" || { echo "FAIL rdrunout plan: no PNG"; fails=$((fails + 1)); }
tool "exceedance" "exceed.png" exceedance "$T/fences_sweep.h5" -o "$T/exceed.png" --dpi 100
png_ok "$T/exceed.png" || { echo "FAIL rdrunout exceedance: no PNG"; fails=$((fails + 1)); }
bad_tool() { # NAME EXPECT ARGS...: one line holding EXPECT, exit 2
    local name=$1 want=$2 rc=0; shift 2
    $PY tools/rdrunout.py "$@" > "$T/tool.log" 2>&1 || rc=$?
    if [ "$rc" = 2 ] && [ "$(wc -l < "$T/tool.log")" = 1 ] && grep -q -- "$want" "$T/tool.log"; then
        echo "CHECK rdrunout $name: $(cat "$T/tool.log")"
    else echo "FAIL rdrunout $name: exit $rc, $(head -3 "$T/tool.log")"; fails=$((fails + 1)); fi
}
bad_tool "labels that do not match" "1 labels for 2 run files" plan "$T/terrain.h5" "$T/terrain_h.h5" --labels a -o "$T/p2.png"
bad_tool "two sweep tables" "one sweep table" exceedance "$T/fences_sweep.h5" "$T/fences_sweep.h5" -o "$T/e2.png"
bad_tool "a missing run file" "nothing.h5: no such file" plan "$T/nothing.h5" -o "$T/p3.png"
# a convex rock on a non-convex terrain mesh: no contact in the vertex model (only a convex
# body is a contact target, and the terrain carries no points): it fell through; now check and
# run refuse the pair with one line naming it
cant="blocks 'ground' and 'b' are within reach of each other at t = 0 s, and the vertex contact model cannot touch them"
rc=0; "$BIN" check "$T/kink.dat" > /dev/null 2> "$T/kink_check.err" || rc=$?
if [ "$rc" = 2 ] && [ "$(wc -l < "$T/kink_check.err")" = 1 ] && grep -qF "$cant" "$T/kink_check.err" &&
    grep -qF "$cant" "$T/kink.log" && ! grep -q "left the scene" "$T/kink.log"; then
    echo "CHECK vertex model on a non-convex terrain mesh: refused by check and run"
else echo "FAIL vertex model on a non-convex terrain mesh: check exit $rc, $(cat "$T/kink_check.err"); run: $(tail -n 2 "$T/kink.log")"; fails=$((fails + 1)); fi
# bad input: one line naming the file and line
bad_input() { # WHAT EXPECT TEXT
    printf '%s\n' "block create brick size 1 1 1 position 0 0 0.5 name b" "$3" "${4:-}" > "$T/bad.dat"
    if "$BIN" check "$T/bad.dat" > "$T/bad.log" 2>&1 || ! grep -q "$2" "$T/bad.log"; then
        grep -q "$2" "$T/bad.log" && "$BIN" check "$T/bad.dat" >/dev/null 2>&1 && { echo "FAIL $1: accepted"; fails=$((fails + 1)); return; }
        grep -q "$2" "$T/bad.log" || { echo "FAIL $1: $(cat "$T/bad.log")"; fails=$((fails + 1)); return; }
    fi
    echo "CHECK $1: $(head -1 "$T/bad.log")"
}
bad_input "until rest needs a time limit" "needs 'time-limit" "model solve until rest"
bad_input "time-limit needs until rest" "cannot be combined" "model solve time 1 time-limit 3"
bad_input "a fence of one point" "x y pairs" "model fence points 0 0"
bad_input "a domain box inside out" "must be below" "model domain box 1 0 0 1 0 1"
bad_input "a fence name given twice" "fence 'road' given twice" "model fence points 0 0 1 1 name road" "model fence points 0 1 1 2 name road"
printf 'ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n1 2\n-9999 3\n' > "$T/hole.asc"
bad_input "a NODATA terrain cell" "hole.asc:8: a NODATA cell" "block import terrain '$T/hole.asc'" "model solve time 1"
printf '0 0 1\n1 0 1\n0 1 1\n1 1 1\n2 2 1\n' > "$T/three.xyz"
bad_input "XYZ points not on a grid" "not one point per node" "block import terrain '$T/three.xyz'" "model solve time 1"
[ "$fails" -eq 0 ]
