/* rockdem — the quiet end of a sweep or threshold case (sc.quiet_stop): once every free body
 * is at rest relative to the ground (no uplift, kinetic energy below RD_QUIET_KE of its tipping
 * barrier, held RD_REST_HOLD s) and what is left of the motion can neither lift nor slide it,
 * the rest of the run cannot change its answer, and it ends there (status done; the time is
 * rd_sim_quiet_end). While the ground still shakes a standing body rings on its joint's springs
 * (the PBR at 0.02 g: about 2 mm/s), above the free-vibration tail's rest level (rest.c); what
 * matters is that this energy cannot tip it: all of it spent rocking about the pivot, at
 * R from the centre of mass, would raise the tilt by KE / (m g R sin alpha), and the limit
 * RD_QUIET_KE m g r (1 - cos alpha) (r >= R: the bounding radius) keeps that below
 * RD_QUIET_KE (r/R) / 2 of alpha for small alpha, under the sweep's rocking resolution
 * RD_MODE_TILT_MIN (1e-3 of alpha) for r/R < 2.
 * In the ground frame a body at rest feels its weight m (g - a_v) and the pseudo-force -m a_h.
 * A rigid body on its support stays seated while |a_h| <= (g - a_v) tan(alpha) (the static
 * uplift acceleration about its most precarious pivot, alpha = rd_watch.alpha_min) and does
 * not slide while |a_h| <= tan(phi) (g - a_v) (phi: the least friction angle of the scene's
 * joints, cohesion ignored). The test takes the peaks of the whole remaining record, a_h the
 * horizontal magnitude bound sqrt(max|h1|^2 + max|h2|^2) and a_v the largest |vertical| taken
 * downward, against RD_QUIET_MARGIN times both limits. The margin is not the rigid limit's
 * factor of safety but what keeps the answer unchanged on elastic joints: a base of many
 * bearing points begins to open once the resultant leaves its kern, at about 1/4 of the rigid
 * limit (the kern's inradius over the base's: 1/4 for a disc and a triangle, 0.24 for a
 * square), and the joint's rocking and bearing modes may amplify the ground's acceleration by
 * the spectral amplification of a record, about 2.5 (5 %-damped median-to-84th-percentile,
 * Newmark and Hall); 1/4 / 2.5 = 0.1. Measured on the shipped PBR (scenarios/pbr_fragility.dat,
 * least tipping angle 12.7 deg, g tan alpha = 0.225 g): full 20 s runs at 0.02 g (0.09 of the
 * limit) stay at rest, max tilt / alpha <= 1.8e-4 (seeds 1-2, directions 0 and 90), against
 * the sweep's rocking resolution RD_MODE_TILT_MIN 1e-3; at 0.1 g (0.44) one uplifts to 1.1e-3.
 * Analytic pulses are not bounded this way: while one lasts the case runs on.
 * A body standing on another free body (a stack) is tipped at a lower acceleration than its
 * own: such scenes are never ended early.
 * Folder engine/ owns the simulation; it may call base/, geometry/, records/ and scenario/.
 */
#include "engine/sim.h"
#include "base/vec.h"
#include "rockdem/motion.h"

#include <math.h>
#include <stdlib.h>

#define RD_QUIET_MARGIN 0.1  /* of the static uplift and slide accelerations (see above) */
#define RD_QUIET_KE     1e-3 /* of the tipping barrier m g r (1 - cos alpha) (see above) */

typedef struct rd_quiet {
    double *peak[RD_NCOMPONENTS]; /* [n] largest |applied acc| from sample i on, m/s^2 */
    size_t n[RD_NCOMPONENTS];
    double dt[RD_NCOMPONENTS]; /* sample step, s */
    double pulse_end;          /* every analytic pulse is over after this time, s */
    double tan_alpha;          /* least tan(alpha_min) over the free bodies */
    double tan_phi;            /* least tan(friction) over the joints */
    double since;              /* time since which the bodies have been at rest, s (-1) */
    double at;                 /* time the run ended quietly, s (-1: it did not) */
} rd_quiet;

/* Largest |acc| of a record from each sample on into a new array (NULL: no memory). */
static double *suffix_peaks(const rd_record *r)
{
    double *p = malloc(r->npts * sizeof *p);
    if (!p) return NULL;
    double m = 0.0;
    for (size_t i = r->npts; i-- > 0;) p[i] = m = fmax(m, fabs(r->acc[i]));
    return p;
}

/* Free body k at rest relative to the ground, its kinetic energy unable to tip it (above). */
static int body_quiet(const rd_sim *s, int k)
{
    int i = s->free_body[k];
    double ke =
        0.5 * s->mass[i] * rd_dot(s->v[i], s->v[i]) + 0.5 * rd_dot(s->w[i], s->L[i]); /* J */
    double barrier =
        s->mass[i] * s->sc.gravity * s->poly[i].radius * (1.0 - cos(s->watch[k].alpha_min)); /* J */
    return !s->watch[k].uplifted && ke <= RD_QUIET_KE * barrier;
}

/* Every free body stands on a fixed body (no stacks). */
static int on_fixed_supports(const rd_sim *s)
{
    for (int k = 0; k < s->nfree; k++) {
        int j = s->watch[k].rests_on;
        if (j < 0 || !s->fixed[j]) return 0;
    }
    return 1;
}

int rd_quiet_begin(rd_sim *s)
{
    if (!s->sc.quiet_stop || !on_fixed_supports(s)) return 0;
    rd_quiet *q = calloc(1, sizeof *q);
    if (!q) return -1;
    s->quiet = q;
    q->since = q->at = -1.0;
    q->pulse_end =
        fmax(rd_pulse_end(&s->sc.motion.horizontal), rd_pulse_end(&s->sc.motion.vertical));
    for (int c = 0; c < RD_NCOMPONENTS; c++) {
        const rd_record *r = s->sc.motion.record[c].applied;
        if (!r) continue;
        if (!(q->peak[c] = suffix_peaks(r))) return -1;
        q->n[c] = r->npts;
        q->dt[c] = r->dt;
    }
    q->tan_alpha = INFINITY;
    for (int k = 0; k < s->nfree; k++)
        q->tan_alpha = fmin(q->tan_alpha, tan(s->watch[k].alpha_min));
    q->tan_phi = INFINITY;
    for (int j = 0; j < s->njoint; j++) q->tan_phi = fmin(q->tan_phi, s->joint[j].tan_phi);
    return 0;
}

/* Largest |acc| of component c from time t on, m/s^2 (the sample at or before t on: the motion
 * between samples is their linear interpolation). */
static double peak_after(const rd_quiet *q, int c, double t)
{
    if (!q->peak[c]) return 0.0;
    size_t i = (size_t)fmax(floor(t / q->dt[c]), 0.0);
    return i < q->n[c] ? q->peak[c][i] : 0.0;
}

/* What is left of the motion after t cannot lift or slide a body at rest. */
static int motion_spent(const rd_sim *s, const rd_quiet *q, double t)
{
    if (t < q->pulse_end) return 0;
    double h1 = peak_after(q, RD_H1, t), h2 = peak_after(q, RD_H2, t);
    double a_h = sqrt(h1 * h1 + h2 * h2);                        /* m/s^2 */
    double hold = s->sc.gravity - peak_after(q, RD_VERTICAL, t); /* least g - a_v, m/s^2 */
    return hold > 0 && a_h <= RD_QUIET_MARGIN * hold * fmin(q->tan_alpha, q->tan_phi);
}

int rd_quiet_reached(rd_sim *s)
{
    rd_quiet *q = s->quiet;
    if (!q) return 0;
    for (int k = 0; k < s->nfree; k++)
        if (!body_quiet(s, k)) {
            q->since = -1.0;
            return 0;
        }
    if (q->since < 0) q->since = s->t;
    if (s->t - q->since < RD_REST_HOLD || !motion_spent(s, q, s->t)) return 0;
    q->at = s->t;
    return 1;
}

void rd_quiet_free(rd_sim *s)
{
    if (!s->quiet) return;
    for (int c = 0; c < RD_NCOMPONENTS; c++) free(s->quiet->peak[c]);
    free(s->quiet);
    s->quiet = NULL;
}

double rd_sim_quiet_end(const rd_sim *s) { return s->quiet ? s->quiet->at : -1.0; }
