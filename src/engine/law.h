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

/* Velocity, m/s, of a point of owner body o against body t at offsets ro (from o's centre) and
 * rt (from t's centre), ground frame: v_o + w_o x ro - (v_t + w_t x rt), t's part left out when
 * t is fixed. */
static inline void rd_law_relative_velocity(const rd_sim *s, int o, int t, const double ro[3],
                                            const double rt[3], double vr[3])
{
    double tmp[3];
    rd_cross(s->w[o], ro, vr);
    rd_axpy(1.0, s->v[o], vr);
    if (!s->fixed[t]) {
        rd_cross(s->w[t], rt, tmp);
        rd_axpy(-1.0, tmp, vr);
        rd_axpy(-1.0, s->v[t], vr);
    }
}

/* Force F (N) of a subcontact at offsets ro (from owner o's centre) and rt (from the other body
 * t's centre), m: F and ro x F added to o's force and torque sums (f_o, tq_o), -F and -(rt x F)
 * to t's (f_t, tq_t) when t is free (t_free; a fixed body takes no force). */
static inline void rd_law_apply(const double F[3], const double ro[3], const double rt[3], double f_o[3],
                                double tq_o[3], int t_free, double f_t[3], double tq_t[3])
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

/* The trial step of the incremental Coulomb shear spring fs (N) on the plane of unit normal n:
 * last step's force is kept in the plane (turned with it, its magnitude kept) and the elastic
 * increment -KS A' dUs of the tangential relative velocity vr - vn n over dt is added (sA = KS A',
 * N/m). */
static inline void rd_law_shear_trial(double fs[3], const double n[3], const double vr[3], double vn,
                                      double sA, double dt)
{
    double fu = rd_dot(fs, n);
    if (fu != 0) {
        double prev2 = rd_dot(fs, fs);
        for (int k = 0; k < 3; k++) fs[k] -= fu * n[k];
        double now2 = rd_dot(fs, fs);
        double r = now2 > 0 ? sqrt(prev2 / now2) : 0.0;
        fs[0] *= r; fs[1] *= r; fs[2] *= r;
    }
    for (int k = 0; k < 3; k++) fs[k] -= sA * (vr[k] - vn * n[k]) * dt;
}

/* The Coulomb cap on the trial force fs (N; f0: last step's force): scaled back to lim (N) when
 * it exceeds it. The slip's dissipated energy is added to *e_fric (J): slip
 * d = (|F_trial| - F_lim) / (KS A') happens at a force between F_lim and the smaller of |F_prev|,
 * |F_trial|, which books lim*d when sliding steadily, the released spring energy when the limit
 * drops, and nothing when frictionless. Returns 1 on slip. */
static inline int rd_law_shear_cap(double fs[3], const double f0[3], double sA, double lim,
                                   double *e_fric)
{
    double mag2 = rd_dot(fs, fs);
    if (mag2 <= lim * lim) return 0;
    double mag = sqrt(mag2), r = lim / mag;
    *e_fric += (mag - lim) * (lim + fmin(sqrt(rd_dot(f0, f0)), mag)) / (2.0 * sA);
    fs[0] *= r; fs[1] *= r; fs[2] *= r;
    return 1;
}

/* One step of the incremental Coulomb shear spring fs: the trial step, then the cap (above).
 * Returns 1 on slip. */
static inline int rd_law_shear(double fs[3], const double n[3], const double vr[3], double vn,
                               double sA, double dt, double lim, double *e_fric)
{
    const double f0[3] = {fs[0], fs[1], fs[2]};
    rd_law_shear_trial(fs, n, vr, vn, sA, dt);
    return rd_law_shear_cap(fs, f0, sA, lim, e_fric);
}

#endif
