/* rockdem (private) — the joint law's kinematics, Coulomb shear and force sums, shared by the vertex
 * subcontacts (contact.c) and the edge subcontacts (edge.c).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#ifndef RD_LAW_H
#define RD_LAW_H

#include "engine/sim.h"
#include "base/vec.h"

#include <math.h>

/* Velocity, m/s, of a point at offsets ro (from the owner's centre) and rt (from the other
 * body's centre) of an owner moving with (vo, wo) against another body moving with (vt, wt),
 * ground frame: vo + wo x ro - (vt + wt x rt), the other's part left out unless t_free. */
static inline void rd_law_relative_velocity_of(const double vo[3], const double wo[3],
                                               const double vt[3], const double wt[3], int t_free,
                                               const double ro[3], const double rt[3], double vr[3])
{
    double tmp[3];
    rd_cross(wo, ro, vr);
    rd_axpy(1.0, vo, vr);
    if (t_free) {
        rd_cross(wt, rt, tmp);
        rd_axpy(-1.0, tmp, vr);
        rd_axpy(-1.0, vt, vr);
    }
}

/* rd_law_relative_velocity_of for owner body o against body t of the simulation. */
static inline void rd_law_relative_velocity(const rd_sim *s, int o, int t, const double ro[3],
                                            const double rt[3], double vr[3])
{
    rd_law_relative_velocity_of(s->v[o], s->w[o], s->v[t], s->w[t], !s->fixed[t], ro, rt, vr);
}

/* Approach speed above which a new touch of pair pr is an impact, m/s: g sqrt(m_eff / K_active),
 * the speed the pair's weight reaches settling onto its bearing springs from rest (0 while none
 * bore last step: any touch then is an impact). Found only at a subcontact's first bearing
 * step (contact.c, edge.c). */
static inline double rd_law_touch_speed(const rd_sim *s, const rd_pair *pr)
{
    return pr->k_active > 0 ? s->sc.gravity * sqrt(pr->m_eff / pr->k_active) : 0.0;
}

/* Force F (N) of a subcontact at offsets ro (from owner o's centre) and rt (from the other body
 * t's centre), m: F and ro x F added to o's force and torque sums (f_o, tq_o), -F and -(rt x F)
 * to t's (f_t, tq_t) when t is free (t_free; a fixed body takes no force). */
static inline void rd_law_apply(const double F[3], const double ro[3], const double rt[3],
                                double f_o[3], double tq_o[3], int t_free, double f_t[3],
                                double tq_t[3])
{
    double tmp[3];
    rd_axpy(1.0, F, f_o);
    rd_cross(ro, F, tmp);
    rd_axpy(1.0, tmp, tq_o);
    if (t_free) {
        rd_axpy(-1.0, F, f_t);
        rd_cross(rt, F, tmp);
        rd_axpy(-1.0, tmp, tq_t);
    }
}

/* The shear spring fs (N) kept in the plane of unit normal n: last step's force is turned with
 * the plane, its magnitude (and so its stored energy) kept. */
static inline void rd_law_shear_turn(double fs[3], const double n[3])
{
    double fu = rd_dot(fs, n);
    if (fu != 0) {
        double prev2 = rd_dot(fs, fs);
        for (int k = 0; k < 3; k++) fs[k] -= fu * n[k];
        double now2 = rd_dot(fs, fs);
        double r = now2 > 0 ? sqrt(prev2 / now2) : 0.0;
        fs[0] *= r;
        fs[1] *= r;
        fs[2] *= r;
    }
}

/* The elastic increment -KS A' dUs of the tangential relative velocity vr - vn n over dt
 * (sA = KS A', N/m) added to the turned shear spring fs. */
static inline void rd_law_shear_load(double fs[3], const double n[3], const double vr[3], double vn,
                                     double sA, double dt)
{
    for (int k = 0; k < 3; k++) fs[k] -= sA * (vr[k] - vn * n[k]) * dt;
}

/* The trial step of the incremental Coulomb shear spring fs (N) on the plane of unit normal n:
 * turned (rd_law_shear_turn), then loaded (rd_law_shear_load). */
static inline void rd_law_shear_trial(double fs[3], const double n[3], const double vr[3],
                                      double vn, double sA, double dt)
{
    rd_law_shear_turn(fs, n);
    rd_law_shear_load(fs, n, vr, vn, sA, dt);
}

/* The Coulomb cap on the trial force fs (N; f0: last step's force turned into the plane) : scaled
 * back to lim (N) when it exceeds it. The slip's dissipated energy is added to *e_fric (J): the
 * work the scheme does on the spring over the step, -(f0 + f).dUs / 2 with f the capped force
 * (leapfrog's kinetic energy changes by the mean of a force's values at the step's two ends
 * times the step's displacement), less the spring's energy change (f.f - f0.f0) / (2 KS A'),
 * which is (|F_trial| - F_lim) (F_lim + f0 . F_trial / |F_trial|) / (2 KS A'): lim*d when
 * sliding steadily, the released spring energy when the limit drops, and nothing when
 * frictionless. Negative only when one step's displacement reverses the force through zero
 * and past the limit (the mean force is then not the force along the path): booked as 0, as
 * slip never gives energy back. Returns 1 on slip. */
static inline int rd_law_shear_cap(double fs[3], const double f0[3], double sA, double lim,
                                   double *e_fric)
{
    double mag2 = rd_dot(fs, fs);
    if (mag2 <= lim * lim) return 0;
    double mag = sqrt(mag2), r = lim / mag;
    *e_fric += fmax((mag - lim) * (lim + rd_dot(f0, fs) / mag) / (2.0 * sA), 0.0);
    fs[0] *= r;
    fs[1] *= r;
    fs[2] *= r;
    return 1;
}

/* One step of the incremental Coulomb shear spring fs: the trial step, then the cap (above).
 * Returns 1 on slip. */
static inline int rd_law_shear(double fs[3], const double n[3], const double vr[3], double vn,
                               double sA, double dt, double lim, double *e_fric)
{
    rd_law_shear_turn(fs, n);
    const double f0[3] = { fs[0], fs[1], fs[2] };
    rd_law_shear_load(fs, n, vr, vn, sA, dt);
    return rd_law_shear_cap(fs, f0, sA, lim, e_fric);
}

/* The mean stretch, m, of a compression-only spring over the step around t(n), given its stretch
 * sn at t(n) (> 0: compressed) and the stretch w (m) it moves through in one step (|vn| dt, vn
 * its rate over the last step), when the spring switches on or off within that step (|sn| < w /
 * 2). Leapfrog gives the bodies F(n) dt as the impulse over [t(n) - dt/2, t(n) + dt/2]; the
 * spring's impulse over that interval, with the stretch moving linearly through sn, is KN A'
 * times the mean of max(stretch, 0), (sn + w/2)^2 / (2 w): it joins the linear spring at sn =
 * w/2 and zero at sn = -w/2. With KN A' sn instead (the spring on from t(n) - dt/2 or not at
 * all), an impact's rebound gained or lost up to (omega dt)^2 / 4 of its kinetic energy with
 * where the touch fell in the step (omega dt = 0.2: +-0.9 %); with the mean, 0.01 % (a point
 * mass on a spring, touches spread over the step; docs/CONTACT.md section 6). */
static inline double rd_law_switch_stretch(double sn, double w)
{
    double a = sn + 0.5 * w;
    return a * a / (2.0 * w);
}

/* Work, J, dissipated over a step by the non-elastic part of a normal force (a dashpot, a
 * tension cap): fd_prev and fd (N, along the entrance face's outward normal) at the step's two
 * ends, vn (m/s) the normal relative velocity over the step. Leapfrog's kinetic energy changes
 * by the mean of a force's values at the step's two ends times the step's displacement, so the
 * work is the trapezoid rule's -(fd_prev + fd) vn dt / 2; fd vn dt (the force at the step's end
 * only) missed (fd_prev - fd) vn dt / 2 a step, a first-order error wherever the dashpot force
 * changes fast (an impact). A subcontact that stops bearing books its last half step with
 * fd = 0. */
static inline double rd_law_dashpot_work(double fd_prev, double fd, double vn, double dt)
{
    return -0.5 * (fd_prev + fd) * vn * dt;
}

/* Energy, J, that a subcontact's springs give up when it stops bearing at step n (its force
 * F(n-1) acted last). Leapfrog gives the bodies the work of F(n-1) over the first half of the
 * step only (the step's kinetic energy change is the mean of F(n-1) and F(n) = 0 times the
 * displacement), so the springs let go at mid-step: booking their energy at step n-1 (or at
 * n) left F(n-1) dU / 2 per release in the balance, a first-order error (the 4-drum YADE column
 * at 0.5 g: 0.93 J of its 1.06 J residual).
 *  - normal (kA = KN A', N/m): the stretch midway between the last bearing step's s_prev and
 *    this step's s_now (m), while both are compressions, or both tensions of a spring that may
 *    pull (pulls: a bond); nothing otherwise: a spring that opens by itself stores nothing as it
 *    lets go (the scheme's error at that switch is of order dt^2), and an unbonded spring in
 *    tension holds nothing (an unbonded point idles below its permanent set: contact.c);
 *  - shear: the spring fs (N) turned into the plane n and taken through half the step's
 *    tangential displacement (vr, vn: the point's relative velocity and its normal part, m/s)
 *    under its last Coulomb limit lim (N): its energy then, plus what slips in that half step
 *    (rd_law_shear_cap). Without the cap a stiff shear spring (KS A' dU >> lim) was credited
 *    (KS A' dU)^2 / 8 it could never hold (the YADE stack at KS 2e10 Pa/m: a residual floor of
 *    7e-4 at 2.5e-5 and 1.25e-5 s). */
static inline double rd_law_release_energy(double kA, double s_prev, double s_now, int pulls,
                                           const double fs[3], const double n[3],
                                           const double vr[3], double vn, double sA, double lim,
                                           double dt)
{
    int held = s_prev * s_now > 0 && (s_prev > 0 || pulls);
    double sm = held ? 0.5 * (s_prev + s_now) : 0.0, f[3] = { fs[0], fs[1], fs[2] }, e = 0;
    rd_law_shear(f, n, vr, vn, sA, 0.5 * dt, lim, &e);
    return e + 0.5 * (kA * sm * sm + rd_dot(f, f) / sA);
}

#endif
