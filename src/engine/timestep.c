/* rockdem — the critical time step of the explicit scheme.
 *
 * For springs k_p acting at points r_p of rigid bodies, the largest eigenvalue of M^-1 K is at
 * most sum_p k_p * mobility_p, where a point's mobility on body i is at most
 * G_i = 1/m_i + r_i^2 / I_min,i (translation plus rotation about the stiffest-to-turn axis;
 * r_i = distance of the farthest vertex). Per body, its own subcontacts all closed at once,
 * each acting between it and the most mobile other body, bound w_max^2; dt_crit = 2 / w_max,
 * reduced by sqrt(1 + l^2) - l for a normal dashpot of damping ratio l. A body's own points
 * cover its joints (weight 1 on pedestals; two half-weight sets on a shared face), so the
 * bound holds as contacts come and go. Each body takes the stiffest joint it can form with
 * any other body (joint.c: per-range contact properties).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"

#include <math.h>

static double mobility(const rd_sim *s, int i)
{
    if (s->fixed[i]) return 0.0;
    double imin = fmin(s->inertia[i][0], fmin(s->inertia[i][1], s->inertia[i][2]));
    double r = s->poly[i].radius;
    return 1.0 / s->mass[i] + r * r / imin;
}

/* The two most mobile bodies that carry subcontact points: mobility and index of the first,
 * mobility of the second (0 where there is none). */
typedef struct mobile_top {
    double g1, g2;
    int i1;
} mobile_top;

static mobile_top most_mobile(const rd_sim *s)
{
    mobile_top t = {0, 0, -1};
    for (int j = 0; j < s->nb; j++) {
        if (s->pt0[j + 1] <= s->pt0[j]) continue;
        double g = mobility(s, j);
        if (g > t.g1) { t.g2 = t.g1; t.g1 = g; t.i1 = j; }
        else if (g > t.g2) t.g2 = g;
    }
    return t;
}

/* Largest mobility among the bodies with points other than i (0 when i can only meet
 * pedestals): from the two most mobile, so the bound costs O(n), not O(n^2) (5,000 bricks:
 * 0.14 s of CPU). */
static double other_mobility(const mobile_top *t, int i) { return i == t->i1 ? t->g2 : t->g1; }

double rd_timestep_critical(const rd_sim *s)
{
    double w2max = 0, lmax = 0;
    mobile_top top = most_mobile(s);
    for (int i = 0; i < s->nb; i++) {
        if (s->fixed[i]) continue;
        double k, zeta; /* the stiffest joint body i can form, and its largest dashpot ratio */
        rd_joint_body_limits(s, i, &k, &zeta);
        /* its own subcontacts at full weight (where two free bodies meet, the two half-weight
           sets together carry about the shared area): every bed face at once, or, once it has
           toppled, the largest face that touches only later with the edge it shares with a bed
           face (at most half of that face's points) */
        double bed = 0, bed_max = 0, late = 0;
        for (int c = s->cf0[i]; c < s->cf0[i + 1]; c++) {
            double a = 0;
            for (int j = s->cf_pt0[c]; j < s->cf_pt0[c + 1]; j++) a += s->pa[j];
            if (s->cf_facing[c]) late = fmax(late, a);
            else { bed += a; bed_max = fmax(bed_max, a); }
        }
        double area = s->surf ? rd_surface_contact_area(s, i) : fmax(bed, late + 0.5 * bed_max);
        double w2 = k * area * (mobility(s, i) + other_mobility(&top, i));
        if (w2 > w2max) w2max = w2;
        double l = zeta * sqrt(s->mass[i] * mobility(s, i));
        if (l > lmax) lmax = l;
    }
    if (w2max <= 0) return INFINITY;
    return 2.0 / sqrt(w2max) * (sqrt(1.0 + lmax * lmax) - lmax);
}
