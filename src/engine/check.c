/* rockdem — looking at a scene before running it (include/rockdem/check.h).
 *
 * The scene is built as a run would build it (shapes, subcontacts, joints, time step), one
 * contact pass finds what each body touches as placed, and a short stretch of settle-mode
 * steps is timed. Under each free body the nearest body is the one whose box covers its centre
 * of mass in plan and whose top lies highest below the body's lowest point.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "rockdem/check.h"
#include "engine/sim.h"
#include "base/vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RD_CHECK_STEPS 400     /* trial steps timed for the cost estimate */
#define RD_CHECK_WALL_MAX 1.0  /* ... or fewer, when they take longer than this, s */

static double body_volume(const rd_sim *s, int i)
{
    rd_mass m;
    rd_error e;
    return rd_poly_mass(&s->poly[i], &m, &e) ? 0.0 : m.volume;
}

/* Lowest and highest z of body i and its plan box. */
static void extent(const rd_sim *s, int i, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) { lo[k] = INFINITY; hi[k] = -INFINITY; }
    for (int v = s->vert0[i]; v < s->vert0[i + 1]; v++)
        for (int k = 0; k < 3; k++) { lo[k] = fmin(lo[k], s->wv[v][k]); hi[k] = fmax(hi[k], s->wv[v][k]); }
}

/* The nearest body under body i (see the header comment) and the gap to it. */
static int below(const rd_sim *s, int i, double *gap)
{
    double lo[3], hi[3], l2[3], h2[3];
    extent(s, i, lo, hi);
    int best = -1;
    double top = -INFINITY;
    for (int j = 0; j < s->nb; j++) {
        if (j == i) continue;
        extent(s, j, l2, h2);
        int covers = s->x[i][0] >= l2[0] && s->x[i][0] <= h2[0] && s->x[i][1] >= l2[1] && s->x[i][1] <= h2[1];
        if (covers && l2[2] < s->x[i][2] && h2[2] > top) { top = h2[2]; best = j; }
    }
    *gap = best >= 0 ? lo[2] - top : INFINITY;
    return best;
}

/* What body i touches as placed: the lowest partner with active points, and the deepest
 * overlap with a body near it (overlap.c: a vertex of one inside the other). */
static void touching(const rd_sim *s, int i, rd_check_body *cb)
{
    cb->rests_on = -1; cb->overlaps = -1; cb->overlap = 0;
    for (int p = 0; p < s->npair; p++) {
        const rd_pair *pr = &s->pair[p];
        if (pr->a != i && pr->b != i) continue;
        int other = pr->a == i ? pr->b : pr->a, active = 0;
        double depth = rd_overlap_depth(s, i, other);
        if (depth > cb->overlap) { cb->overlap = depth; cb->overlaps = other; }
        for (int q = 0; q < pr->nside; q++) {
            const rd_side *sd = &pr->side[q];
            int n = s->pt0[sd->owner + 1] - s->pt0[sd->owner];
            for (int st = sd->state0; st < sd->state0 + n && !active; st++) active = (s->pstate[st] & RD_PT_ACTIVE) != 0;
        }
        if (active && s->x[other][2] < s->x[i][2] && (cb->rests_on < 0 || s->x[other][2] < s->x[cb->rests_on][2]))
            cb->rests_on = other;
    }
}

/* The scene as placed, its contacts found once (NULL with err). */
static rd_sim *placed(const rd_scenario *sc, rd_error *err)
{
    rd_sim *s = rd_sim_build_as_placed(sc, err);
    if (!s) return NULL;
    s->settling = 1;
    if (rd_contact_step(s)) { rd_sim_free(s); rd_error_set(err, "out of memory"); return NULL; }
    s->settling = 0;
    return s;
}

/* The scene whose points tell what touches what as placed. Corner points (spacing 0, the
 * default) of a block placed into an aligned one below lie on that block's side faces, at
 * zero distance from them, so they show no penetration: the automatic bed's points, inside
 * the face, are used instead. Returns s itself when its own points serve, NULL with err. */
static rd_sim *touch_probe(const rd_scenario *sc, rd_sim *s, rd_error *err)
{
    if (sc->contact.spacing != 0) return s;
    rd_scenario bed = *sc; /* shallow: rd_sim_build copies what it keeps */
    bed.contact.spacing = -1;
    return placed(&bed, err);
}

int rd_check_scene(const rd_scenario *sc, rd_check_report *rep, rd_error *err)
{
    memset(rep, 0, sizeof *rep);
    rd_sim *s = placed(sc, err);
    if (!s) return -1;
    rd_sim *probe = touch_probe(sc, s, err);
    if (!probe) { rd_sim_free(s); return -1; }
    rep->nbodies = s->nb;
    rep->body = calloc((size_t)s->nb, sizeof *rep->body);
    if (!rep->body) {
        if (probe != s) rd_sim_free(probe);
        rd_sim_free(s);
        return rd_error_set(err, "out of memory");
    }
    s->sc.settle.enabled = 0; /* as placed: support polygons from the lowest vertices */
    rd_monitor_rest(s);
    for (int i = 0; i < s->nb; i++) {
        rd_check_body *cb = &rep->body[i];
        const rd_body_def *d = &s->sc.bodies[i];
        memcpy(cb->name, d->name, sizeof cb->name);
        memcpy(cb->group, d->group, sizeof cb->group);
        cb->fixed = s->fixed[i];
        cb->mass = s->mass[i];
        cb->volume = body_volume(s, i);
        cb->npoints = s->pt0[i + 1] - s->pt0[i];
        touching(probe, i, cb);
        cb->below = s->fixed[i] ? -1 : below(s, i, &cb->gap);
        if (cb->rests_on < 0 && cb->below >= 0 && fabs(cb->gap) <= 1e-9 * (1.0 + s->poly[i].radius))
            cb->rests_on = cb->below; /* placed exactly on it: a closed joint at zero force */
        if (!s->fixed[i]) {
            const rd_watch *w = &s->watch[s->free_of[i]];
            cb->alpha_min = w->sum->alpha_min;
            cb->alpha = w->sum->alpha;
        }
    }
    if (probe != s) rd_sim_free(probe);
    rep->npoints = s->npts;
    rep->njoints = s->njoint;
    rep->dt = s->dt;
    rep->dt_critical = s->dt_crit;
    rep->dt_body = s->dt_pair[0];
    rep->dt_partner = s->dt_pair[1];
    rep->output_interval = s->sc.output.interval;
    rep->duration = s->sc.duration;
    rep->has_records = rd_motion_has_records(&s->sc.motion);
    rep->motion_end = rd_motion_end(&s->sc.motion);
    int n = 0;
    double wall = 0;
    while (n < RD_CHECK_STEPS && wall < RD_CHECK_WALL_MAX && s->status == RD_STATUS_DONE) {
        wall += rd_sim_trial_steps(s, 50);
        n += 50;
    }
    rep->trial_steps = n;
    rep->wall_per_sim_s = n > 0 ? wall / (n * s->dt) : 0;
    rd_sim_free(s);
    return 0;
}

void rd_check_free(rd_check_report *rep)
{
    free(rep->body);
    rep->body = NULL;
}
