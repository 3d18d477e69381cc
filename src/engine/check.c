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

#define RD_CHECK_STEPS    400  /* trial steps timed for the cost estimate */
#define RD_CHECK_WALL_MAX 1.0  /* ... or fewer, when they take longer than this, s */
#define RD_CHECK_PLAN_TOL 1e-9 /* overlap and level tolerance of the plan boxes, per m of size */

/* A list of bodies per body, in ascending order: body i's are member[start[i] .. start[i+1]). */
typedef struct body_lists {
    int *start; /* [nb + 1] */
    int *member;
} body_lists;

static void lists_free(body_lists *l)
{
    free(l->start);
    free(l->member);
}

/* Walks free body j's chain of supports at rest (what it rests on, what that rests on, ... to
 * a fixed body, nothing, or nb steps: a cycle), calling back each body once: the bodies j
 * stands on, directly or through the bodies under it. fill 0 counts into start, 1 appends. */
static void chain_visit(const rd_sim *s, int j, int *mark, body_lists *l, int fill)
{
    for (int n = 0, a = j; n < s->nb && a >= 0 && !s->fixed[a]; n++) {
        a = s->watch[s->free_of[a]].rests_on;
        if (a < 0 || mark[a] == j) continue;
        mark[a] = j;
        if (fill)
            l->member[l->start[a + 1]++] = j;
        else
            l->start[a + 1]++;
    }
}

/* Each body's tower: itself (free) and every free body that stands on it, ascending: one pass
 * over the chains, O(bodies x courses), where asking each pair was quadratic (a 10,000-brick
 * wall's check). The sums over a tower keep the order of a loop over all bodies. */
static int towers(const rd_sim *s, body_lists *l)
{
    l->start = calloc((size_t)s->nb + 1, sizeof *l->start);
    int *mark = malloc(sizeof *mark * (size_t)(s->nb + 1));
    l->member = NULL;
    if (!l->start || !mark) {
        free(mark);
        return -1;
    }
    for (int fill = 0; fill < 2; fill++) {
        for (int i = 0; i < s->nb; i++) mark[i] = -1;
        for (int j = 0; j < s->nb; j++) {
            if (s->fixed[j]) continue;
            mark[j] = j;
            if (fill)
                l->member[l->start[j + 1]++] = j;
            else
                l->start[j + 1]++;
            chain_visit(s, j, mark, l, fill);
        }
        if (fill) break;
        for (int i = 0; i < s->nb; i++) l->start[i + 1] += l->start[i];
        l->member = malloc(sizeof *l->member * (size_t)(l->start[s->nb] + 1));
        if (!l->member) break;
        for (int i = s->nb; i > 0; i--) l->start[i] = l->start[i - 1]; /* fill from each start */
        l->start[0] = 0;
    }
    free(mark);
    return l->member ? 0 : -1;
}

/* Each body's contact pairs, ascending. */
static int pair_lists(const rd_sim *s, body_lists *l)
{
    l->start = calloc((size_t)s->nb + 1, sizeof *l->start);
    l->member = malloc(sizeof *l->member * (size_t)(2 * s->npair + 1));
    if (!l->start || !l->member) return -1;
    for (int p = 0; p < s->npair; p++) {
        l->start[s->pair[p].a + 1]++;
        if (s->pair[p].b != s->pair[p].a) l->start[s->pair[p].b + 1]++;
    }
    for (int i = 0; i < s->nb; i++) l->start[i + 1] += l->start[i];
    int *next = malloc(sizeof *next * (size_t)(s->nb + 1));
    if (!next) return -1;
    memcpy(next, l->start, sizeof *next * (size_t)s->nb);
    for (int p = 0; p < s->npair; p++) {
        l->member[next[s->pair[p].a]++] = p;
        if (s->pair[p].b != s->pair[p].a) l->member[next[s->pair[p].b]++] = p;
    }
    free(next);
    return 0;
}

/* Housner's frequency parameter p = sqrt(m g R / I_O) of the bodies standing on i (and i),
 * total mass m, centre of mass com, rocking about the edge of i's support polygon towards
 * (dx, dy) (unit): the edge's point P lies below com at the tipping angle alpha, R = |com - P|;
 * I_O sums each body's inertia about the edge's axis a = (-dy, dx, 0) through its centre
 * (principal moments I_k times (a in body axes)_k^2) and m_j r_j^2 (r_j its distance to the
 * edge line). */
static double pivot_frequency(const rd_sim *s, const body_lists *tw, int i, const double com[3],
                              double m, double dx, double dy, double alpha, double *R)
{
    const double a[3] = { -dy, dx, 0 };
    const double *seat = s->watch[s->free_of[i]].seat; /* seat . x = seat[3] */
    double h = com[2] -
               (seat[3] - seat[0] * com[0] - seat[1] * com[1]) / seat[2]; /* height over the seat */
    double d = h * tan(alpha), P[3] = { com[0] + d * dx, com[1] + d * dy, com[2] - h }, io = 0;
    for (int t = tw->start[i]; t < tw->start[i + 1]; t++) {
        const int j = tw->member[t];
        double ab[3], r[3];
        rd_mat_tvec(s->R[j], a, ab);
        for (int k = 0; k < 3; k++) io += s->inertia[j][k] * ab[k] * ab[k];
        for (int k = 0; k < 3; k++) r[k] = s->x[j][k] - P[k];
        double along = rd_dot(r, a);
        rd_axpy(-along, a, r);
        io += s->mass[j] * rd_dot(r, r);
    }
    *R = hypot(d, h);
    return io > 0 ? sqrt(m * s->sc.gravity * *R / io) : 0.0;
}

/* Body i's tipping angles along +- the shaking direction: its own, and with everything that
 * stands on it as one rigid assembly (a drum column, a stack or a statue on its plinth tips
 * first as a whole, at a smaller angle than any one of its parts). */
static void shaking_alphas(const rd_sim *s, const body_lists *tw, int i, rd_check_body *cb)
{
    const double psi =
        s->sc.motion.horizontal.kind != RD_PULSE_NONE ? s->sc.motion.horizontal.direction : 0.0;
    const double dx = cos(psi), dy = sin(psi);
    double com[3] = { 0, 0, 0 }, m = 0;
    for (int t = tw->start[i]; t < tw->start[i + 1]; t++) {
        const int j = tw->member[t];
        rd_axpy(s->mass[j], s->x[j], com);
        m += s->mass[j];
    }
    for (int k = 0; k < 3; k++) com[k] /= m;
    int k = s->free_of[i];
    cb->alpha_shaking = fmin(rd_monitor_alpha_at(s, k, s->x[i], dx, dy),
                             rd_monitor_alpha_at(s, k, s->x[i], -dx, -dy));
    double ap = rd_monitor_alpha_at(s, k, com, dx, dy),
           an = rd_monitor_alpha_at(s, k, com, -dx, -dy);
    cb->alpha_tower = fmin(ap, an);
    double sgn = ap <= an ? 1.0 : -1.0; /* the side it tips to first */
    cb->p_tower =
        pivot_frequency(s, tw, i, com, m, sgn * dx, sgn * dy, cb->alpha_tower, &cb->R_tower);
    cb->lean_tower = atan2(sgn * dy, sgn * dx);
}

static double body_volume(const rd_sim *s, int i)
{
    rd_mass m;
    rd_error e;
    return rd_poly_mass(&s->poly[i], &m, &e) ? 0.0 : m.volume;
}

/* Lowest and highest corner of body i's box. */
static void extent(const rd_sim *s, int i, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (int v = s->vert0[i]; v < s->vert0[i + 1]; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], s->wv[v][k]);
            hi[k] = fmax(hi[k], s->wv[v][k]);
        }
}

/* Do the plan boxes a and b overlap by more than tol in x and in y? */
static int plan_overlap(const double *a, const double *b, double tol)
{
    return fmin(a[3], b[3]) - fmax(a[0], b[0]) > tol && fmin(a[4], b[4]) - fmax(a[1], b[1]) > tol;
}

/* The nearest body under body i (see the header comment) and the gap to it; box[j] holds
 * body j's lowest corner (0..2) and highest (3..5). When that body lies lower than i's base
 * (a gap), a body whose plan box overlaps i's and whose top is at or below i's base and higher
 * is taken instead: a brick in running bond has its centre over the joint of the two bricks it
 * rests on, and the body under its centre is the course below them. */
static int below(const rd_sim *s, const double (*box)[6], int i, double *gap)
{
    int best = -1;
    double top = -INFINITY;
    for (int j = 0; j < s->nb; j++) {
        if (j == i) continue;
        const double *l2 = box[j], *h2 = box[j] + 3;
        int covers = s->x[i][0] >= l2[0] && s->x[i][0] <= h2[0] && s->x[i][1] >= l2[1] &&
                     s->x[i][1] <= h2[1];
        if (covers && l2[2] < s->x[i][2] && h2[2] > top) {
            top = h2[2];
            best = j;
        }
    }
    const double lo = box[i][2], tol = RD_CHECK_PLAN_TOL * (1.0 + s->poly[i].radius);
    for (int j = 0; best >= 0 && lo - top > tol && j < s->nb; j++)
        if (j != i && plan_overlap(box[i], box[j], tol) && box[j][5] <= lo + tol &&
            box[j][5] > top) {
            top = box[j][5];
            best = j;
        }
    *gap = best >= 0 ? lo - top : INFINITY;
    return best;
}

/* What body i touches as placed: the lowest partner with active points, and the deepest
 * overlap with a body near it (overlap.c: a vertex of one inside the other). */
static void touching(const rd_sim *s, const body_lists *pairs, int i, rd_check_body *cb)
{
    cb->rests_on = -1;
    cb->overlaps = -1;
    cb->overlap = 0;
    for (int t = pairs->start[i]; t < pairs->start[i + 1]; t++) {
        const rd_pair *pr = &s->pair[pairs->member[t]];
        int other = pr->a == i ? pr->b : pr->a, active = 0;
        double depth = rd_overlap_depth(s, i, other);
        if (depth > cb->overlap) {
            cb->overlap = depth;
            cb->overlaps = other;
        }
        for (int q = 0; q < pr->nside; q++) {
            const rd_side *sd = &pr->side[q];
            int n = s->pt0[sd->owner + 1] - s->pt0[sd->owner];
            for (int st = sd->state0; st < sd->state0 + n && !active; st++)
                active = (s->pstate[st] & RD_PT_ACTIVE) != 0;
        }
        if (active && s->x[other][2] < s->x[i][2] &&
            (cb->rests_on < 0 || s->x[other][2] < s->x[cb->rests_on][2]))
            cb->rests_on = other;
    }
}

/* Area of body i's support polygon as placed (rd_watch.support, ground plan), m^2. */
static double support_area(const rd_sim *s, int i)
{
    const rd_watch *w = &s->watch[s->free_of[i]];
    double a = 0;
    for (int k = 0, l = w->nsupport - 1; k < w->nsupport; l = k++)
        a += w->support[l][0] * w->support[k][1] - w->support[k][0] * w->support[l][1];
    return 0.5 * fabs(a);
}

/* Each free body's static sink into the body it rests on (rd_check_body.sink): the weight of it
 * and every free body whose chain of rests_on reaches it, on its support area, over the joint's
 * KN. A run settles first and stops as penetrated past ten bands (overlap.c); check does not
 * settle, so it estimates the sink of a uniformly pressed joint, exact for a block on a flat
 * seat (tests/cli/joint_stiffness.sh). */
static void static_sinks(rd_sim *s, rd_check_report *rep)
{
    for (int i = 0; i < s->nb; i++) {
        rd_check_body *cb = &rep->body[i];
        cb->sink_load = s->fixed[i] ? 0 : s->mass[i] * s->sc.gravity;
    }
    for (int k = 0; k < s->nb; k++) { /* k's weight on each body below it in its chain */
        if (s->fixed[k]) continue;
        int j = rep->body[k].rests_on;
        for (int n = 0; n < s->nb && j >= 0 && !s->fixed[j]; n++, j = rep->body[j].rests_on) {
            rep->body[j].sink_load += s->mass[k] * s->sc.gravity;
            rep->body[j].sink_above++;
        }
    }
    for (int i = 0; i < s->nb; i++) {
        rd_check_body *cb = &rep->body[i];
        const int j = cb->rests_on;
        if (s->fixed[i] || j < 0) continue;
        const int jt = rd_joint_resolve(s, i, j);
        if (jt < 0) continue;
        cb->sink_kn = s->joint[jt].kn;
        cb->sink_area = support_area(s, i);
        cb->band = RD_CONTACT_BAND * fmin(s->poly[i].radius, s->poly[j].radius);
        cb->sink = cb->sink_area > 0 ? cb->sink_load / (cb->sink_kn * cb->sink_area) : 0;
    }
}

/* The scene as placed, its contacts found once (NULL with err). */
static rd_sim *placed(const rd_scenario *sc, rd_error *err)
{
    rd_sim *s = rd_sim_build_as_placed(sc, err);
    if (!s) return NULL;
    s->settling = 1;
    if (rd_contact_step(s)) {
        rd_sim_free(s);
        rd_error_set(err, "out of memory");
        return NULL;
    }
    if (s->status != RD_STATUS_DONE) { /* a pair the contact model cannot make (pairs.c) */
        rd_error_set(err, "%s: %s", sc->file, s->errmsg);
        rd_sim_free(s);
        return NULL;
    }
    s->settling = 0;
    return s;
}

/* The scene whose points tell what touches what as placed. Corner points (spacing 0, the
 * default) of a block placed into an aligned one below lie on that block's side faces, at
 * zero distance from them, so they show no penetration: the automatic bed's points, inside
 * the face, are used instead. Returns s itself when its own points serve, NULL with err. A
 * scene that its own points fit but the bed does not (past the point budget: a wall of some
 * 2,000 bricks, 121 points a face; or out of memory) is probed with its own points, as run
 * would build it, and *coarse is set: check then accepts what run accepts. */
static rd_sim *touch_probe(const rd_scenario *sc, rd_sim *s, int *coarse, rd_error *err)
{
    *coarse = 0;
    if (sc->contact.spacing != 0) return s;
    rd_scenario bed = *sc; /* shallow: rd_sim_build copies what it keeps */
    bed.contact.spacing = -1;
    rd_sim *probe = placed(&bed, err);
    if (probe) return probe;
    *coarse = 1;
    return s;
}

int rd_check_scene(const rd_scenario *sc, rd_check_report *rep, rd_error *err)
{
    memset(rep, 0, sizeof *rep);
    rd_sim *s = placed(sc, err);
    if (!s) return -1;
    int coarse;
    rd_sim *probe = touch_probe(sc, s, &coarse, err);
    if (!probe) {
        rd_sim_free(s);
        return -1;
    }
    rep->nbodies = s->nb;
    rep->coarse_probe = coarse;
    rep->body = calloc((size_t)s->nb, sizeof *rep->body);
    double(*box)[6] = malloc((size_t)s->nb * sizeof *box);
    if (!rep->body || !box) {
        if (probe != s) rd_sim_free(probe);
        rd_sim_free(s);
        free(box);
        return rd_error_set(err, "out of memory");
    }
    for (int i = 0; i < s->nb; i++) extent(s, i, box[i], box[i] + 3);
    s->sc.settle.enabled = 0; /* as placed: support polygons from the lowest vertices */
    rd_monitor_rest(s);
    body_lists tw = { 0 }, pairs = { 0 };
    if (towers(s, &tw) || pair_lists(probe, &pairs)) {
        lists_free(&tw);
        lists_free(&pairs);
        if (probe != s) rd_sim_free(probe);
        rd_sim_free(s);
        free(box);
        return rd_error_set(err, "out of memory");
    }
    for (int i = 0; i < s->nb; i++) {
        rd_check_body *cb = &rep->body[i];
        const rd_body_def *d = &s->sc.bodies[i];
        memcpy(cb->name, d->name, sizeof cb->name);
        memcpy(cb->group, d->group, sizeof cb->group);
        cb->fixed = s->fixed[i];
        cb->mass = s->mass[i];
        cb->volume = body_volume(s, i);
        double lo[3], hi[3];
        extent(s, i, lo, hi);
        for (int k = 0; k < 3; k++) cb->extent[k] = hi[k] - lo[k];
        cb->npoints = s->pt0[i + 1] - s->pt0[i];
        touching(probe, &pairs, i, cb);
        cb->below = s->fixed[i] ? -1 : below(s, (const double(*)[6])box, i, &cb->gap);
        if (cb->rests_on < 0 && cb->below >= 0 && fabs(cb->gap) <= 1e-9 * (1.0 + s->poly[i].radius))
            cb->rests_on = cb->below; /* placed exactly on it: a closed joint at zero force */
        if (!s->fixed[i]) {
            const rd_watch *w = &s->watch[s->free_of[i]];
            cb->alpha_min = w->sum->alpha_min;
            cb->alpha = w->sum->alpha;
            shaking_alphas(s, &tw, i, cb);
        }
    }
    lists_free(&tw);
    lists_free(&pairs);
    if (probe != s) rd_sim_free(probe);
    free(box);
    static_sinks(s, rep);
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
