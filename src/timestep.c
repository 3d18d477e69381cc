/* rockdem — the critical time step of the explicit scheme.
 *
 * For springs k_p acting at points r_p of rigid bodies, the largest eigenvalue of M^-1 K is at
 * most sum_p k_p * mobility_p, where a point's mobility on body i is at most
 * G_i = 1/m_i + r_i^2 / I_min,i (translation plus rotation about the stiffest-to-turn axis;
 * r_i = distance of the farthest vertex). Per body, summing over every subcontact that can
 * touch it (all candidate points closed at once) bounds w_max^2; dt_crit = 2 / w_max, reduced
 * by sqrt(1 + l^2) - l for a normal dashpot of damping ratio l. The bound is rigorous (never
 * above the true limit), so a fixed step below it is stable. */
#include "sim.h"

#include <math.h>

static double mobility(const rd_sim *s, int i)
{
    if (s->fixed[i]) return 0.0;
    double imin = fmin(s->inertia[i][0], fmin(s->inertia[i][1], s->inertia[i][2]));
    double r = s->poly[i].radius;
    return 1.0 / s->mass[i] + r * r / imin;
}

double rd_timestep_critical(const rd_sim *s)
{
    double k = fmax(s->sc.contact.kn, s->sc.contact.ks), w2max = 0, lmax = 0;
    for (int i = 0; i < s->nb; i++) {
        if (s->fixed[i]) continue;
        double w2 = 0;
        for (int p = 0; p < s->npair; p++) {
            const rd_pair *pr = &s->pair[p];
            if (pr->a != i && pr->b != i) continue;
            double K = 0;
            for (int q = 0; q < pr->nside; q++) {
                const rd_side *sd = &pr->side[q];
                for (int j = s->pt0[sd->owner]; j < s->pt0[sd->owner + 1]; j++) K += k * sd->weight * s->pa[j];
            }
            w2 += K * (mobility(s, pr->a) + mobility(s, pr->b));
        }
        if (w2 > w2max) w2max = w2;
        double l = s->sc.damping.kind == RD_DAMPING_VISCOUS
                       ? s->sc.damping.value * sqrt(s->mass[i] * mobility(s, i)) : 0.0;
        if (l > lmax) lmax = l;
    }
    if (w2max <= 0) return INFINITY;
    return 2.0 / sqrt(w2max) * (sqrt(1.0 + lmax * lmax) - lmax);
}
