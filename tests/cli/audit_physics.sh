#!/usr/bin/env bash
# Closed-form checks a 3DEC user or a cask analyst would run first (physics audit, 2026-11):
#  1. vertical + horizontal base motion: a block sliding under a rectangular horizontal pulse
#     while the base also accelerates vertically (+ up: the pseudo-force adds to gravity, so the
#     Coulomb limit is mu m (g + a_v)). Reference: the same block with two degrees of freedom, a
#     vertical spring KN A (the step of a_v sets it vibrating, undamped, between m g and
#     m (g + 2 a_v)) and an elastic-perfectly-plastic shear spring KS A capped at mu times its
#     force, integrated here at two steps (its own error is their difference). A wrong sign of
#     the vertical pseudo-force, or a friction cap from the weight alone, moves the slide by
#     0.2-0.6 m.
#  2. slide or rock (Shenton 1996): a 0.4 x 0.4 x 0.8 m block (b/h = 0.5) under a ramp of base
#     acceleration r = g/2 per second. mu = 0.3 < b/h: it slides from a = mu g, its velocity
#     relative to the base r (t - t_s)^2 / 2, and never rocks (tilt at its elastic level) though the
#     ramp passes g b/h. mu = 0.7 > b/h: it does not slide, and tips at a = g b/h.
#  3. a block dropped flat: the elastic contact lasts (pi + 2 asin(x_s / X)) / omega (gravity's
#     static compression x_s = g / omega^2 shifts the oscillation, X its amplitude); with
#     restitution e the rebound speed is sqrt(e^2 v0^2 - 2 g d (1 - e^2)) (d the deepest
#     compression: the set (1 - e) d, the spring gives back e^2 of 1/2 K d^2, gravity takes m g d).
#  4. two equal free blocks colliding face to face on a frictionless base, elastic: they exchange
#     velocities. The striking faces' base corners used to bear on the struck side face too (bed
#     point and side point at one place), so the joint's pressure centre lay at h/3 and the
#     striker kept 0.0236 m/s; a base point now bears only on a face it looks at (contact.c,
#     RD_BASE_FACING_COS).
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/audit_physics; rm -rf "$T"; mkdir -p "$T"
fails=0
run() { # NAME FILE ARGS...: run quietly, fail the test on a non-zero exit
    local name=$1 file=$2; shift 2
    "$BIN" run "$file" -q -o "$T/$name.h5" "$@" > "$T/$name.log" 2>&1 ||
        { echo "FAIL audit/$name: run failed"; cat "$T/$name.log"; fails=$((fails + 1)); return 1; }
}
# report: reads "what gap tol ok" lines (ok 1 met, 0 missed; mode as the 5th field, default
# strict); a met strict check prints a "CHECK" line (tests/run.sh counts each)
report() {
    while read -r what gap tol ok mode; do
        if [ "$ok" = 1 ] && [ "${mode:-strict}" = strict ]; then echo "CHECK audit/$what: gap $gap tol $tol"
        else echo "audit/$what: gap $gap tol $tol"; fi
        verdict "audit/$what" "$ok" "$gap" "$tol" "${mode:-strict}" || fails=$((fails + 1))
    done
}
# pycheck ARGS... <<'PY' (the checker on stdin): runs it, then reports its lines; a checker that
# fails or prints nothing fails the test
pycheck() {
    /usr/bin/python3 - "$@" > "$T/report" && [ -s "$T/report" ] ||
        { echo "FAIL audit: checker failed ($*)"; fails=$((fails + 1)); }
    report < "$T/report"
}

# ---- 1. vertical + horizontal base motion ----------------------------------------------------
cat > "$T/vslide.dat" <<'EOF'
model gravity 9.81
block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base
block create brick size 1 1 0.25 position 0 0 0.125 density 2700 name block
contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 20 restitution 1
model settle on
ground-motion pulse rectangular amplitude 6 duration 0.5 start 0.1 direction 0
ground-motion pulse rectangular amplitude 3 duration 0.5 start 0.1 vertical
model solve time 1.2
output hdf5 'vslide.h5' interval 0.001
EOF
for c in "6 3" "6 -3" "4.5 0"; do
    read -r ah av <<< "$c"
    run "vslide_${ah}_${av}" "$T/vslide.dat" --set motion.amplitude="$ah" --set motion.vertical-amplitude="$av" || continue
    pycheck "$T/vslide_${ah}_${av}.h5" "$ah" "$av" <<'PY'
import sys, h5py, numpy as np
G, MU, KN, KS, M, A, T0, D, TEND = 9.81, np.tan(np.radians(20)), 1e10, 1e9, 675.0, 1.0, 0.1, 0.5, 1.2
f = h5py.File(sys.argv[1], "r"); ah, av = float(sys.argv[2]), float(sys.argv[3])
x = f["position"][:, 0, 0]; u = x - x[0]; dt = float(f.attrs["dt"])

def ep2dof(h):
    """Relative slide (min u, m) of the block with a vertical spring KN A (N = KN A x its
    compression, from rest under m g) and a shear spring KS A, elastic-perfectly plastic at
    mu N; semi-implicit Euler at step h."""
    k, kn, uu, v, F, umin = KS * A, KN * A, 0.0, 0.0, 0.0, 0.0
    z, vz = -M * G / kn, 0.0
    for i in range(int(round(TEND / h))):
        on = T0 < (i + 0.5) * h < T0 + D
        N = max(-kn * z, 0.0)
        vz += (-(G + (av if on else 0.0)) + N / M) * h; z += vz * h
        v += (-(ah if on else 0.0) + F / M) * h
        uu += v * h; F -= k * v * h
        if abs(F) > MU * N: F = np.copysign(MU * N, F)
        umin = min(umin, uu)
    return umin

r1, r2 = ep2dof(4e-6), ep2dof(2e-6)
# Tolerance: the pulse's start and end each fall within one step of the DEM: a velocity error of
# at most a_h dt each, kept over the pulse and the stop that follows (D + v1 / (mu g), v1 the
# rigid slide speed at the pulse's end); plus the reference's own step error, |r1 - r2|. Left
# out of the reference: the block's pitching on its corner springs (the pulse's step sets it
# going; the corners' normal forces then swing about their mean, their caps with them).
a1 = max(ah - MU * (G + av), 0.0)
span = D + a1 * D / (MU * G)
tol = 2 * ah * dt * span + abs(r1 - r2)
gap = abs(u.min() - r2)
print("vslide(ah=%g,av=%g,slide=%.6g,2dof=%.6g,rigid=%.6g,m)" % (ah, av, -u.min(), -r2, a1 * D * D / 2 * (1 + a1 / (MU * G))),
      "%.3g" % gap, "%.3g" % tol, int(gap <= tol))
PY
done

# ---- 2. slide or rock ------------------------------------------------------------------------
cat > "$T/sr.dat" <<'EOF'
model gravity 9.81
block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.4 0.8 position 0 0 0.4 density 2700 name b
contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 16.69924423
model settle on
ground-motion pulse triangle amplitude 9.81 duration 4 direction 0
model solve time 1.4
output hdf5 'sr.h5' interval 0.001
EOF
for mu in 0.3 0.7; do
    phi=$(/usr/bin/python3 -c "import math; print('%.10g' % math.degrees(math.atan($mu)))")
    run "sr_$mu" "$T/sr.dat" --set contact.friction="$phi" || continue
    pycheck "$T/sr_$mu.h5" "$mu" <<'PY'
import sys, h5py, numpy as np
G, KN, KS, RHO, B, H = 9.81, 1e10, 1e11, 2700.0, 0.4, 0.8
f = h5py.File(sys.argv[1], "r"); mu = float(sys.argv[2])
t = f["time"][()]; v = f["velocity"][:, 0, 0]; tilt = f["tilt"][:, 0]; dt = float(f.attrs["dt"])
M, A, r = RHO * B * B * H, B * B, G / 2            # kg, m^2, m/s^3 (the ramp)
krot = KN * A * B * B / 4                          # N m/rad: four corners of A/4 at +-b/2
at = lambda tt: np.argmin(abs(t - tt))
if mu < B / H:
    # slides from t_s = mu g / r; relative velocity -r (t - t_s)^2 / 2. Tolerance: the onset within
    # one step, r (t - t_s) dt, plus what the shear springs can give as they let go, at most the
    # speed of their whole energy at the cap: s_cap omega_s = mu m g / sqrt(KS A m)
    ts, k = mu * G / r, at(1.0)
    ref = -r * (t[k] - ts) ** 2 / 2
    tol = r * (t[k] - ts) * dt + mu * M * G / np.sqrt(KS * A * M)
    print("slide(mu=%g,v(1s)=%.7g,ref=%.7g,m/s)" % (mu, v[k], ref), "%.3g" % abs(v[k] - ref), "%.3g" % tol, int(abs(v[k] - ref) <= tol))
    # never rocks: the tilt stays within twice (a suddenly applied moment's overshoot) the
    # elastic tilt under the friction's moment mu m g h/2, though a reaches 0.7 g > g b/h
    el = mu * M * G * H / 2 / krot
    print("slide-no-rock(mu=%g,max-tilt,rad)" % mu, "%.3g" % tilt.max(), "%.3g" % (2 * el), int(tilt.max() <= 2 * el))
else:
    # no slide: the joint's slip (elastic shear removed) under the elastic scale mu m g / (KS A)
    # (1.3e-7 m) times 100, while a rigid-plastic slide would reach metres
    slip = float(f["joints/outcomes"][0, 1])
    cap = 100 * mu * M * G / (KS * A)
    print("rock-no-slide(mu=%g,joint-slip,m)" % mu, "%.3g" % slip, "%.3g" % cap, int(slip <= cap))
    # tips at a = g b/h (t = 1 s): 2 % before, the tilt is at most the elastic tilt of the
    # moment m a h/2 at the threshold; 5 % after, it is 10 times that (a rigid block tips from
    # t = 1 s, 0.05 s later its tilt is ~1e-4 rad against 1.1e-5 rad elastic)
    el = M * G * B / H * H / 2 / krot
    k0, k1 = at(0.98), at(1.05)
    print("rock-onset(mu=%g,tilt@0.98s,rad)" % mu, "%.3g" % tilt[k0], "%.3g" % el, int(tilt[k0] <= el))
    print("rock-onset(mu=%g,tilt@1.05s>10x-elastic,rad)" % mu, "%.3g" % tilt[k1], "%.3g" % (10 * el), int(tilt[k1] >= 10 * el))
PY
done

# ---- 3. a block dropped flat ------------------------------------------------------------------
cat > "$T/drop.dat" <<'EOF'
block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.4 0.8 position 0 0 0.405 density 2700 name blk
contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40 restitution 1 spacing vertices
model settle off
model solve time 0.04
output hdf5 'drop.h5' interval 0.00001
EOF
run drop_elastic "$T/drop.dat" && run drop_e05 "$T/drop.dat" --set contact.restitution=0.5 \
    --set model.timestep=5e-6 --set output.interval=5e-6 &&
pycheck "$T/drop_elastic.h5" "$T/drop_e05.h5" <<'PY'
import sys, h5py, numpy as np
G, KN, M, H0 = 9.81, 1e10, 0.4 * 0.4 * 0.8 * 2700, 0.005
K = KN * 0.16                                   # four corners of 0.04 m^2, N/m
w, v0 = np.sqrt(K / M), np.sqrt(2 * G * H0)     # rad/s, m/s
xs = G / w ** 2                                 # static compression, m
X = np.hypot(xs, v0 / w)                        # amplitude about it, m
d = xs + X                                      # deepest compression, m

def pass_below(f):
    """times (interpolated) the base crosses z = 0 down and up, and the z(t) arrays"""
    t, z = f["time"][()], f["position"][:, 0, 2] - 0.4
    i0 = np.argmax(z < 0); i1 = i0 + np.argmax(z[i0:] >= 0)
    cross = lambda i: t[i - 1] + (t[i] - t[i - 1]) * (0 - z[i - 1]) / (z[i] - z[i - 1])
    return cross(i0), cross(i1), i1, t, z

f = h5py.File(sys.argv[1], "r"); dt = float(f.attrs["dt"])
ta, tb, _, _, _ = pass_below(f)
ref = (np.pi + 2 * np.arcsin(xs / X)) / w
# each crossing is found between two samples of a step's length: within dt
print("drop-elastic-contact(s=%.6g,ref=%.6g)" % (tb - ta, ref), "%.3g" % abs(tb - ta - ref), "%.3g" % dt, int(abs(tb - ta - ref) <= dt))

f = h5py.File(sys.argv[2], "r"); dt, e = float(f.attrs["dt"]), 0.5
_, _, i1, t, z = pass_below(f)
post = np.arange(i1 + 2, i1 + 400)              # ballistic after the bounce: z + g t^2/2 is linear
c1, c0 = np.polyfit(t[post], z[post] + 0.5 * G * t[post] ** 2, 1)
rts = np.roots([-0.5 * G, c1, c0]); tr = rts[np.argmin(abs(rts - t[i1]))]
ratio = (c1 - G * tr) / v0
refr = np.sqrt(e * e - 2 * G * d * (1 - e * e) / v0 ** 2)
# Tolerance: the set is taken at the first step that unloads, within 1.5 steps of the deepest
# point, so from a stretch short of d by at most (1.5 w dt)^2 / 2 of it: e grows by (1 - e) that;
# the spring switching on and off at t(n) moves each end's energy by (w dt)^2 / 4
q = w * dt
de = (1 - e) * (1.5 * q) ** 2 / 2
tol = e * de / refr + refr * (q * q / 4) * (1 + 1 / refr ** 2) / 2
print("drop-restitution(e=0.5,ratio=%.6g,ref=%.6g)" % (ratio, refr), "%.3g" % abs(ratio - refr), "%.3g" % tol, int(abs(ratio - refr) <= tol))
PY

# ---- 4. two equal blocks colliding -------------------------------------------------------------
cat > "$T/coll.dat" <<'EOF'
model gravity 9.81
block create brick size 6 2 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.4 0.4 0.4 position -0.5 0 0.2 density 2700 name a
block create brick size 0.4 0.4 0.4 position 0.5 0 0.2 density 2700 name b
contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 0 restitution 1
model settle on
block initial name a velocity 1 0 0
model solve time 0.7
output hdf5 'coll.h5' interval 0.001
EOF
run coll "$T/coll.dat" && pycheck "$T/coll.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r"); v = f["velocity"][-1]
# Equal masses, frictionless, elastic springs: they exchange velocities (a at rest, b at 1 m/s).
# Tolerance: elastic_bounce.sh's bound for an elastic spring switching within a step, 1e-4 of the
# impact's energy at omega dt 0.2, as a velocity 1e-4 of the impact speed; twice for the two sides
gap = abs(v[0, 0])
print("collision-exchange(va=%.4g,vb=%.4g,m/s)" % (v[0, 0], v[1, 0]), "%.3g" % gap, "2e-4", int(gap <= 2e-4))
PY

[ "$fails" = 0 ] || exit 1
