"""Closed-form (and closed-form-integrated) answers the validation ladder checks rockdem against.

Every function here is independent of rockdem's code: it is written from the equations in
docs/ROCKING-EQUATIONS.md (Housner 1963; Newmark 1965) and integrated with scipy when the answer
has no elementary expression. Units: SI (m, s, rad, kg).
"""
import math

import numpy as np
from scipy.integrate import solve_ivp

G0 = 9.80665  # m/s^2, standard gravity: the scenario unit `g` (amplitudes such as 0.6g)
SCENE_G = 9.81  # m/s^2, the scenes' gravity without `model gravity`: RD_GRAVITY_DEFAULT (tests/cli/validation.sh)


def housner_r(alpha):
    """Housner's angular-velocity ratio across a plastic impact of a rectangular block whose
    diagonal makes alpha with the vertical (angular momentum about the new corner conserved):
    r = 1 - 1.5 sin^2(alpha). For h/b = 2 (alpha = atan 0.5) r = 0.70 exactly."""
    return 1.0 - 1.5 * math.sin(alpha) ** 2


def restitution_from_amplitudes(alpha, th_before, th_after):
    """Angular-velocity ratio r implied by two successive rocking amplitudes of a rigid block
    (energy conserved between impacts: 0.5 I0 w^2 = m g R (cos(alpha - th) - cos(alpha)) at
    th = 0), so r^2 = (1 - cos(alpha - th_after)... written as ratios of (cos(a - th) - cos a)."""
    num = math.cos(alpha - th_after) - math.cos(alpha)
    den = math.cos(alpha - th_before) - math.cos(alpha)
    return math.sqrt(num / den)


def newmark_slide(mu, amp, freq, g, t_end=None):
    """Rigid-plastic (Newmark 1965) sliding of a block on a level base with friction
    coefficient mu under a one-sine ground pulse a_g = amp sin(2 pi f t), 0 <= t <= 1/f.
    g is the scene's gravity (m/s^2), which sets the friction limit mu g; amp is in m/s^2.
    Returns (max |u|, final u) of the slip u relative to the base (m). Integrated exactly in
    the sense of an ODE with events (rtol 1e-11): the block sticks while |a_g| <= mu g and its
    relative velocity is 0; while sliding, u'' = -a_g - mu g sign(u')."""
    T = 1.0 / freq
    t_end = t_end or 3 * T

    def ag(t):
        return amp * math.sin(2 * math.pi * freq * t) if t <= T else 0.0

    t, u, v, umax = 0.0, 0.0, 0.0, 0.0
    dt_scan = T / 20000.0
    while t < t_end:
        if v == 0.0:  # sticking: advance to the first time |a_g| > mu g (scanned, then refined)
            while t < t_end and abs(ag(t)) <= mu * g:
                t += dt_scan
            if t >= t_end:
                break
            lo = t - dt_scan
            for _ in range(60):
                mid = 0.5 * (lo + t)
                if abs(ag(mid)) > mu * g:
                    t = mid
                else:
                    lo = mid
            s = -math.copysign(1.0, ag(t))  # slides opposite to the ground acceleration
        else:
            s = math.copysign(1.0, v)

        def rhs(tt, y, s=s):
            return [y[1], -ag(tt) - mu * g * s]

        def stop(tt, y, s=s):
            return y[1] * s
        stop.terminal, stop.direction = True, -1
        sol = solve_ivp(rhs, [t, t_end], [u, v if v else 0.0], events=stop, rtol=1e-11, atol=1e-14,
                        max_step=T / 400)
        umax = max(umax, float(np.max(np.abs(sol.y[0]))))
        u, t = float(sol.y[0, -1]), float(sol.t[-1])
        v = 0.0
        if not sol.t_events[0].size:
            break
        t += 1e-12
    return umax, u


def winkler_inset_first_impact(b, h, depth, mass, kn, theta0, g):
    """First impact time of a block released from theta0 whose pivot lies inside the edge by the
    centroid of a Winkler bed's overlap wedge (YADE's volumetric law puts the normal force
    there): contact width c = sqrt(2 m g / (KN L theta)), inset c/3 (triangular pressure),
    capped at b. Returns (t_inset, t_edge): the same rigid ODE with the pivot at b - c/3 and on
    the edge. Their difference is the closed-form estimate of the volumetric law's delay."""
    def t1(inset):
        def rhs(t, y):
            th = max(y[0], 1e-9)
            bb = b - inset(th)
            R, al = math.hypot(bb, h), math.atan2(bb, h)
            I0 = mass * ((2 * b) ** 2 + (2 * h) ** 2) / 12 + mass * R * R
            return [y[1], -mass * g * R * math.sin(al - y[0]) / I0]

        def ev(t, y):
            return y[0] - 1e-7
        ev.terminal, ev.direction = True, -1
        s = solve_ivp(rhs, [0, 10], [theta0, 0.0], events=ev, rtol=1e-10, atol=1e-13, max_step=1e-3)
        return float(s.t_events[0][0])
    wedge = lambda th: min(math.sqrt(2 * mass * g / (kn * depth * th)) / 3, b)
    return t1(wedge), t1(lambda th: 0.0)


def stack_rocking_omega(blocks, kn, density, g):
    """Lowest angular frequency (rad/s) of an elastic two-block stack rocking before uplift:
    blocks = [(b1, h1), (b2, h2)] half-widths and half-heights (m) of square-based bricks, lower
    first; each joint a Winkler bed of stiffness kn (Pa/m) over the smaller face, rotational
    stiffness K = kn A b^2 (A = (2b)^2, b the smaller half-width). Small rotations theta_i of
    each block about its own base centre (shear held: KS >> KN), gravity's overturning moment
    included. Solves K v = omega^2 M v for the 2x2 system."""
    (b1, h1), (b2, h2) = blocks
    m1, m2 = (density * (2 * b) ** 2 * 2 * h for b, h in blocks)
    i1, i2 = m1 * (b1 ** 2 + h1 ** 2) / 3, m2 * (b2 ** 2 + h2 ** 2) / 3   # about the centroids
    bi = min(b1, b2)
    k1, k2 = kn * (2 * b1) ** 2 * b1 ** 2, kn * (2 * bi) ** 2 * bi ** 2
    M = np.array([[i1 + m1 * h1 ** 2 + m2 * 4 * h1 ** 2, m2 * 2 * h1 * h2],
                  [m2 * 2 * h1 * h2, i2 + m2 * h2 ** 2]])
    K = np.array([[k1 + k2 - (m1 + 2 * m2) * g * h1, -k2],
                  [-k2, k2 - m2 * g * h2]])
    w2 = np.linalg.eigvals(np.linalg.solve(M, K)).real
    return math.sqrt(w2.min())


def pulse_onset_lag(omega, freq, t):
    """Largest time (s) by which an undamped oscillator of angular frequency omega, at rest when
    a one-sine ground pulse a(t) = A sin(2 pi freq t) starts, lags or leads its quasi-static
    response at time t: the onset's jerk A 2 pi freq leaves a free vibration of amplitude
    (jerk / omega) in acceleration units, which the forcing's current slope A 2 pi freq
    cos(2 pi freq t) converts into time: 1 / (omega cos(2 pi freq t))."""
    return 1.0 / (omega * math.cos(2 * math.pi * freq * t))
