/* rockdem — the free-vibration tail: `model solve time T tail D` shakes for T s (or to the end
 * of the motion, whichever is later), then runs on until every free body is at rest, for at
 * most D s more. "At rest" means, for every free body, no uplift (the monitor's contact-area
 * test) and kinetic energy below RD_REST_KE times m g r (r: its bounding radius), held for
 * RD_REST_HOLD s so that one quiet instant of a rocking or ringing body does not count.
 * `model solve until rest time-limit T` (docs/RUNOUT.md) is the same test from the end of the
 * motion on, through overturning, with T the longest run.
 * In the ground frame after the motion ends the ground velocity is constant (zero after
 * baseline correction), so this frame is inertial and the kinetic energy is the physical one.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "base/vec.h"

#define RD_REST_KE 1e-7 /* kinetic energy / (m g r): about 1 mm/s for r = 0.5 m */

/* Time after which the tail may stop the run, s: with `until rest`, the end of the motion. */
static double tail_start(const rd_sim *s)
{
    double end = rd_motion_end(&s->sc.motion);
    return s->sc.runout.until_rest ? fmin(end, s->sc.duration) : fmax(s->sc.duration, end);
}

double rd_run_length(const rd_sim *s)
{
    return s->sc.tail > 0 ? tail_start(s) + s->sc.tail : s->sc.duration;
}

double rd_rest_end(rd_sim *s)
{
    s->rest_since = -1.0;
    return rd_run_length(s);
}

/* At rest; with `until rest` a body that left the domain or fell out of the scene is out of
 * the run, and the uplift test (against the contact area of its first rest) is not made: a body
 * that toppled rests on another face, and the kinetic-energy test held for RD_REST_HOLD s
 * tells a rocking or flying body from one at rest. */
static int body_at_rest(const rd_sim *s, int k)
{
    int i = s->free_body[k], until = s->sc.runout.until_rest;
    if (until && (s->run[k].left || s->watch[k].lost)) return 1;
    double ke =
        0.5 * s->mass[i] * rd_dot(s->v[i], s->v[i]) + 0.5 * rd_dot(s->w[i], s->L[i]); /* J */
    return (until || !s->watch[k].uplifted) &&
           ke <= RD_REST_KE * s->mass[i] * s->sc.gravity * s->poly[i].radius;
}

int rd_rest_reached(rd_sim *s)
{
    int until = s->sc.runout.until_rest;
    if ((!(s->sc.tail > 0) && !until) || s->t < tail_start(s)) return 0;
    for (int k = 0; k < s->nfree; k++)
        if (!body_at_rest(s, k)) {
            s->rest_since = -1.0;
            return 0;
        }
    if (s->rest_since < 0) s->rest_since = s->t;
    s->at_rest = s->t - s->rest_since >= RD_REST_HOLD;
    return s->at_rest;
}
