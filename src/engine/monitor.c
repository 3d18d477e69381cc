/* rockdem — watching the bodies: tilt, static tipping angle, slide, events and overturning.
 *
 * Tilt is the angle between the body's vertical axis at rest and its current one (rad); its
 * lean direction is where that axis points. The static tipping angle alpha in the lean
 * direction is atan(d / h): d is the horizontal distance from the centre of mass at rest to the
 * edge of the support polygon along the lean direction, h the height of the centre of mass
 * above the support plane at that edge (rd_watch.seat: level, or the inclined face of a
 * pedestal). Events (per free body):
 *   uplift   the area of the joints that support it (with bodies below it) drops below 60 % of
 *            its value at rest (rocking starts; with corner subcontacts, losing one edge halves it)
 *   impact   the signed rocking angle about the axis of the first rocking crosses zero
 *   peak     logged with each impact: the largest rocking angle since the last one (rad), the
 *            amplitude of the half-cycle that ends in this impact
 *   slip     every active subcontact of the body is at its Coulomb limit (sliding as a whole)
 *   overturn the overturn criterion is first met; recover if the body comes back
 * The rotation from rest is split (swing-twist) into a twist about the vertical and a swing
 * about a horizontal axis; the swing's rotation vector gives in-plane rocking (about z x d,
 * d = the motion's horizontal direction) and out-of-plane rocking (about -d), as in seed 002
 * Figs. 9-10. Twist is unwrapped sample to sample, so accumulated spins exceed pi.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "base/constants.h"
#include "base/vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RD_FALLEN_TILT     (85.0 * M_PI / 180.0)  /* past this, a run may stop: the body is down */
#define RD_UNSEEN_FRACTION (10 * RD_CONTACT_BAND) /* of the smaller radius: overlap.c's limit */
#define RD_ROCK_MIN                                                                                \
    1e-3 /* rocking amplitudes below this fraction of alpha are noise, not impacts */

void rd_event_add(rd_sim *s, double time, int body, const char *type, double value)
{
    if (s->nevent == s->cap_event) {
        int cap = s->cap_event ? 2 * s->cap_event : 256;
        rd_event *e = realloc(s->event, (size_t)cap * sizeof *e);
        if (!e) return; /* events are diagnostics; losing one is not fatal */
        s->event = e;
        s->cap_event = cap;
    }
    rd_event *e = &s->event[s->nevent++];
    e->time = time;
    e->body = body;
    e->value = value;
    snprintf(e->type, sizeof e->type, "%s", type);
}

static int lex_less(const double *a, const double *b)
{
    return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]);
}

static int cmp_xy(const void *a, const void *b)
{
    return lex_less(a, b) ? -1 : lex_less(b, a) ? 1 : 0;
}

/* Convex hull (monotone chain) of n 2-D points, counter-clockwise, written over p; returns its
 * size, or -1 without memory. */
static int hull2d(double (*p)[2], int n)
{
    if (n < 3) return n;
    qsort(p, (size_t)n, sizeof p[0], cmp_xy);
    double(*h)[2] = malloc((size_t)(2 * n + 1) * sizeof *h);
    if (!h) return -1;
    int k = 0;
    for (int pass = 0; pass < 2; pass++) {
        int start = k;
        for (int c = 0; c < n; c++) {
            int i = pass ? n - 1 - c : c;
            while (k >= start + 2 &&
                   (h[k - 1][0] - h[k - 2][0]) * (p[i][1] - h[k - 2][1]) -
                           (h[k - 1][1] - h[k - 2][1]) * (p[i][0] - h[k - 2][0]) <=
                       0)
                k--;
            h[k][0] = p[i][0];
            h[k][1] = p[i][1];
            k++;
        }
        k--;
    }
    memcpy(p, h, (size_t)k * sizeof *h);
    free(h);
    return k;
}

/* Distance from (cx, cy) to the polygon boundary along direction (dx, dy). */
static double ray_to_edge(const rd_watch *w, double cx, double cy, double dx, double dy)
{
    double best = INFINITY;
    for (int i = 0; i < w->nsupport; i++) {
        const double *a = w->support[i], *b = w->support[(i + 1) % w->nsupport];
        double ex = b[0] - a[0], ey = b[1] - a[1];
        double den = dx * ey - dy * ex;
        if (fabs(den) < 1e-15) continue;
        double t = ((a[0] - cx) * ey - (a[1] - cy) * ex) / den;
        double u = ((a[0] - cx) * dy - (a[1] - cy) * dx) / den;
        if (t >= 0 && u >= -1e-9 && u <= 1 + 1e-9 && t < best) best = t;
    }
    return isfinite(best) ? best : 0.0;
}

/* Height z (m) of the support plane at rest (rd_watch.seat) at ground (x, y). */
static double seat_z(const rd_watch *w, double x, double y)
{
    return (w->seat[3] - w->seat[0] * x - w->seat[1] * y) / w->seat[2];
}

/* Static tipping angle towards (dx, dy): atan(d / h), d the distance from the centre of mass's
 * plan position to the support polygon's edge along (dx, dy), h its height above the support
 * plane there (on an inclined seat the downhill edge lies lower than the uphill one). */
static double alpha_toward(const rd_watch *w, double dx, double dy)
{
    double n = hypot(dx, dy);
    if (n == 0) {
        dx = 1;
        dy = 0;
    } else {
        dx /= n;
        dy /= n;
    }
    double d = ray_to_edge(w, w->x_ref[0], w->x_ref[1], dx, dy);
    return atan2(d, w->x_ref[2] - seat_z(w, w->x_ref[0] + d * dx, w->x_ref[1] + d * dy));
}

double rd_monitor_alpha_at(const rd_sim *s, int k, const double com[3], double dx, double dy)
{
    const rd_watch *w = &s->watch[k];
    double n = hypot(dx, dy);
    if (n == 0) {
        dx = 1;
        dy = 0;
    } else {
        dx /= n;
        dy /= n;
    }
    double d = ray_to_edge(w, com[0], com[1], dx, dy);
    return atan2(d, com[2] - seat_z(w, com[0] + d * dx, com[1] + d * dy));
}

/* The live pairs of each body, in the order of s->live_prev (so every search below meets them
 * in the same order as a scan of all live pairs, and finds the same body): body i's are
 * list[first[i]] .. list[first[i + 1] - 1], indices into live_prev. Without memory (first NULL)
 * each body scans them all. Built once per rd_monitor_rest: a scan of all pairs per body made
 * the rest state of a 10,000-brick wall quadratic (2.7 CPU-s). */
typedef struct live_index {
    int *first, *list;
} live_index;

static void live_index_build(const rd_sim *s, live_index *ix)
{
    ix->first = calloc((size_t)s->nb + 1, sizeof *ix->first);
    ix->list = malloc((size_t)(2 * s->nlive_prev + 1) * sizeof *ix->list);
    if (!ix->first || !ix->list) {
        free(ix->first);
        free(ix->list);
        ix->first = ix->list = NULL;
        return;
    }
    for (int k = 0; k < s->nlive_prev; k++) {
        const rd_pair *pr = &s->pair[s->live_prev[k]];
        ix->first[pr->a + 1]++;
        if (pr->b != pr->a) ix->first[pr->b + 1]++;
    }
    for (int i = 0; i < s->nb; i++) ix->first[i + 1] += ix->first[i];
    int *fill = malloc((size_t)s->nb * sizeof *fill);
    if (!fill) {
        free(ix->first);
        free(ix->list);
        ix->first = ix->list = NULL;
        return;
    }
    memcpy(fill, ix->first, (size_t)s->nb * sizeof *fill);
    for (int k = 0; k < s->nlive_prev; k++) {
        const rd_pair *pr = &s->pair[s->live_prev[k]];
        ix->list[fill[pr->a]++] = k;
        if (pr->b != pr->a) ix->list[fill[pr->b]++] = k;
    }
    free(fill);
}

static void live_index_free(live_index *ix)
{
    free(ix->first);
    free(ix->list);
}

/* How many live pairs body i has in the index (all of them without one), and the m-th. */
static int live_count(const rd_sim *s, const live_index *ix, int i)
{
    return ix->first ? ix->first[i + 1] - ix->first[i] : s->nlive_prev;
}

static const rd_pair *live_pair(const rd_sim *s, const live_index *ix, int i, int m)
{
    return &s->pair[s->live_prev[ix->first ? ix->list[ix->first[i] + m] : m]];
}

/* Ground-frame xy of the subcontact points pressed between body i and the body `below` it
 * at rest (either side's points); returns the count written into a malloc'ed *out, or -1. */
static int contact_points(const rd_sim *s, const live_index *ix, int i, int below,
                          double (**out)[2])
{
    int cap = 64, n = 0;
    double(*p)[2] = malloc((size_t)cap * sizeof *p);
    if (!p) return -1;
    for (int k = 0; k < live_count(s, ix, i); k++) {
        const rd_pair *pr = live_pair(s, ix, i, k);
        if (!((pr->a == i && pr->b == below) || (pr->b == i && pr->a == below))) continue;
        for (int q = 0; q < pr->nside; q++) {
            const rd_side *sd = &pr->side[q];
            for (int j = s->pt0[sd->owner]; j < s->pt0[sd->owner + 1]; j++) {
                if (!(s->pstate[sd->state0 + j - s->pt0[sd->owner]] & RD_PT_ACTIVE)) continue;
                if (n == cap) {
                    double(*t)[2] = realloc(p, (size_t)(cap *= 2) * sizeof *p);
                    if (!t) {
                        free(p);
                        return -1;
                    }
                    p = t;
                }
                double x[3];
                rd_mat_vec(s->R[sd->owner], s->pl[j], x);
                p[n][0] = x[0] + s->x[sd->owner][0];
                p[n][1] = x[1] + s->x[sd->owner][1];
                n++;
            }
        }
    }
    *out = p;
    return n;
}

/* The body that body i rests on: among its contact partners at rest, the one whose centre is
 * lowest (-1 if it touches nothing). */
static int resting_on(const rd_sim *s, const live_index *ix, int i)
{
    int best = -1;
    for (int k = 0; k < live_count(s, ix, i); k++) {
        const rd_pair *pr = live_pair(s, ix, i, k);
        int other = pr->a == i ? pr->b : pr->b == i ? pr->a : -1;
        if (other >= 0 && s->x[other][2] < s->x[i][2] &&
            (best < 0 || s->x[other][2] < s->x[best][2]))
            best = other;
    }
    return best;
}

/* The highest point of body j, m. */
static double top_of(const rd_sim *s, int j)
{
    double z = -INFINITY;
    for (int v = s->vert0[j]; v < s->vert0[j + 1]; v++) z = fmax(z, s->wv[v][2]);
    return z;
}

/* Ground-frame xy hull of body j's vertices (its plan shadow, counter-clockwise), malloc'ed
 * into *out; returns its size, or -1 without memory. */
static int shadow(const rd_sim *s, int j, double (**out)[2])
{
    int n = s->vert0[j + 1] - s->vert0[j];
    double(*p)[2] = malloc((size_t)(n > 0 ? n : 1) * sizeof *p);
    if (!p) return -1;
    for (int v = 0; v < n; v++) {
        p[v][0] = s->wv[s->vert0[j] + v][0];
        p[v][1] = s->wv[s->vert0[j] + v][1];
    }
    n = hull2d(p, n);
    if (n < 0) {
        free(p);
        return -1;
    }
    *out = p;
    return n;
}

static double cross_at(const double *a, const double *b, const double *p)
{
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}

/* Clip polygon p (n points) by the convex counter-clockwise polygon c (m >= 3 points)
 * (Sutherland-Hodgman): the part of p inside c, into out (room for n + m points at each
 * stage, scratch tmp the same size); returns its size. */
static int clip_convex(const double (*p)[2], int n, const double (*c)[2], int m, double (*out)[2],
                       double (*tmp)[2])
{
    memcpy(out, p, (size_t)n * sizeof *out);
    for (int e = 0; e < m && n > 0; e++) {
        const double *a = c[e], *b = c[(e + 1) % m];
        memcpy(tmp, out, (size_t)n * sizeof *tmp);
        int k = 0;
        for (int i = 0; i < n; i++) {
            const double *u = tmp[i], *v = tmp[(i + 1) % n];
            double du = cross_at(a, b, u), dv = cross_at(a, b, v);
            if (du >= 0) {
                out[k][0] = u[0];
                out[k][1] = u[1];
                k++;
            }
            if ((du >= 0) != (dv >= 0)) {
                double t = du / (du - dv);
                out[k][0] = u[0] + t * (v[0] - u[0]);
                out[k][1] = u[1] + t * (v[1] - u[1]);
                k++;
            }
        }
        n = k;
    }
    return n;
}

/* Does body j hold body i up at rest: a contact partner whose highest point is level with
 * i's base (within RD_SUPPORT_BAND of i's lowest point zmin)? */
static int supports(const rd_sim *s, int j, double zmin)
{
    return fabs(top_of(s, j) - zmin) <= RD_SUPPORT_BAND;
}

/* Append to pts (n used) the base polygon clipped by the plan shadow of supporting body j,
 * and, after settling, the points pressed against j. Returns the new count (-1 without memory). */
static int add_support(rd_sim *s, const live_index *ix, int i, int j, const double (*base)[2],
                       int nb, double (**pts)[2], int n)
{
    double(*c)[2] = NULL, (*q)[2] = NULL;
    int m = shadow(s, j, &c);
    if (m < 0) return -1;
    int cap = n + 2 * (nb + m) + 1;
    double(*all)[2] = realloc(*pts, (size_t)cap * sizeof *all);
    if (!all || !(q = malloc((size_t)(nb + m + 1) * sizeof *q))) {
        free(c);
        if (all) *pts = all;
        return -1;
    }
    *pts = all;
    if (m >= 3) n += clip_convex(base, nb, (const double(*)[2])c, m, all + n, q);
    free(c);
    free(q);
    if (!(s->sc.settle.enabled || s->restored)) return n;
    double(*pr)[2] = NULL;
    int np = contact_points(s, ix, i, j, &pr);
    if (np < 0) return -1;
    all = realloc(*pts, (size_t)(n + np + 1) * sizeof *all);
    if (!all) {
        free(pr);
        return -1;
    }
    *pts = all;
    memcpy(all + n, pr, (size_t)np * sizeof *pr);
    free(pr);
    return n + np;
}

/* Support polygon at rest: a property of the body's geometry and pose, not of the contact
 * stiffness. Its base is the hull of the body's vertices within RD_SUPPORT_BAND of the support
 * plane (rd_watch.seat: level, or the inclined face it rests on); the support is the union,
 * over the bodies that hold it up (their tops level with that base: a brick in running bond
 * rests on two), of the base clipped to each one's plan (an overhanging block is supported only
 * where the body below is), together with the points pressed against them after settling
 * (which carry an inclined seat). With no body level with the base, the body it rests on (the
 * lowest partner) holds it. The pressed points alone depended on KN: a stiff contact presses
 * only the few asperity points of a scanned base (a 20 degree rock read 3 degrees at KN 1e11). */
static void support_polygon(rd_sim *s, const live_index *ix, int k, double zmin)
{
    int i = s->free_body[k], nv = s->vert0[i + 1] - s->vert0[i], n = 0, nbase = 0, nsup = 0;
    rd_watch *w = &s->watch[k];
    double(*pts)[2] = NULL, (*base)[2] = malloc((size_t)(nv > 0 ? nv : 1) * sizeof *base);
    for (int v = s->vert0[i]; base && v < s->vert0[i + 1]; v++)
        if (rd_dot(w->seat, s->wv[v]) <= w->seat[3] + RD_SUPPORT_BAND) {
            base[nbase][0] = s->wv[v][0];
            base[nbase][1] = s->wv[v][1];
            nbase++;
        }
    if (base) nbase = hull2d(base, nbase);
    for (int l = 0; base && nbase > 0 && n >= 0 && l < live_count(s, ix, i); l++) {
        const rd_pair *pr = live_pair(s, ix, i, l);
        int j = pr->a == i ? pr->b : pr->b == i ? pr->a : -1;
        if (j >= 0 && supports(s, j, zmin)) {
            n = add_support(s, ix, i, j, (const double(*)[2])base, nbase, &pts, n);
            nsup++;
        }
    }
    if (base && nbase > 0 && n >= 0 && !nsup && w->rests_on >= 0)
        n = add_support(s, ix, i, w->rests_on, (const double(*)[2])base, nbase, &pts, n);
    else if (base && nbase > 0 && n >= 0 && !nsup) {
        pts = realloc(pts, (size_t)nbase * sizeof *pts);
        if (pts) {
            memcpy(pts, base, (size_t)nbase * sizeof *pts);
            n = nbase;
        }
    }
    free(base);
    free(w->support);
    w->nsupport = pts && n > 0 ? hull2d(pts, n) : 0;
    if (w->nsupport < 0) w->nsupport = 0;
    w->support = pts;
}

/* Inradius of convex body i about its centre of mass, m: the distance to its nearest face plane
 * (body frame: the origin is the centre of mass, face f is fn[f] . x = fd[f]). A centre of mass
 * that passes through the body's middle travels at least twice this inside it. */
double rd_monitor_inradius(const rd_sim *s, int i)
{
    double r = INFINITY;
    for (int f = 0; f < s->poly[i].nf; f++) r = fmin(r, s->poly[i].fd[f]);
    return r;
}

/* The scene's floor: the lowest vertex of the fixed bodies; and the escape checks' reach: half
 * the smallest inradius of a convex body (the bodies a centre of mass is tested against), so a
 * centre that crosses one through its middle is inside it at a check (after setup). */
void rd_monitor_scene(rd_sim *s)
{
    s->floor_z = -INFINITY;
    double z = INFINITY, reach = INFINITY;
    for (int i = 0; i < s->nb; i++) {
        for (int v = s->vert0[i]; s->fixed[i] && v < s->vert0[i + 1]; v++) z = fmin(z, s->wv[v][2]);
        if (s->convex[i]) reach = fmin(reach, 0.5 * rd_monitor_inradius(s, i));
    }
    if (isfinite(z)) s->floor_z = z;
    s->escape_reach = reach;
}

/* Is point c strictly inside convex body j (behind every face plane)? */
static int inside_convex(const rd_sim *s, int j, const double c[3])
{
    for (int f = s->face0[j]; f < s->face0[j + 1]; f++)
        if (rd_dot(s->wn[f], c) >= s->wd[f]) return 0;
    return 1;
}

/* Body k overturned and is now falling out of the scene (or through an edge), or it fell off
 * the support it rested on: it failed, and that is its verdict (overturned), even if it passed
 * upright again tumbling down (a "recover" that is no recovery). */
static void fell_over(rd_sim *s, int k)
{
    s->watch[k].over = 1;
    s->watch[k].sum->overturned = 1;
}

/* No silent wrong answers: a free body whose centre of mass is inside another (convex) body
 * has passed through its support, and one whose centre of mass has fallen below the scene's
 * floor by more than its own size has left the scene; either ends the run (status
 * RD_STATUS_PENETRATED or RD_STATUS_LOST, the cause in s->errmsg). A body that overturned
 * (by the scenario's criterion) before it fell off, or that bore on a support when the shaking
 * began (a capital thrown off a collapsing column falls flat, never tilting past its criterion;
 * a block slides off its pad), is a result, not an error: it failed (overturned, at the time it
 * left if it never met the criterion), gets a "lost" event, and the run goes on. Only a body
 * that never bore on anything (placed beside its pad) or that left while settling stops the
 * run. Called every few steps, while settling too. Returns 1 when the run must stop. */
/* The usual causes of a body passing into another, for passed_into's message. */
static const char *const RD_SOFT_OR_EDGES =
    "the contact stiffness is far too soft for the load, or the bodies crossed edge to edge "
    "between subcontact points (give their faces a finer spacing)";

/* Body i has passed into convex body j (how: the evidence, cause: its likely causes, for the
 * message): one error, 1. */
static int passed_into(rd_sim *s, int i, int j, const char *stage, const char *how,
                       const char *cause)
{
    int k = s->free_of[i];
    if (k >= 0 && s->watch[k].over_once) {
        fell_over(s, k);
        /* it had overturned (the verdict stands) and, falling, crossed the other body edge to
           edge where no subcontact point guards (a documented limit): the run ends there */
        rd_event_add(s, s->t, k, "lost", 0.0);
        snprintf(s->errmsg, sizeof s->errmsg,
                 "body '%s' overturned, then fell through body '%s' "
                 "at t = %.6g s (edges crossing between subcontact points): the run stops there",
                 s->sc.bodies[i].name, s->sc.bodies[j].name, s->t);
        s->status = RD_STATUS_OVERTURNED;
        return 1;
    }
    snprintf(s->errmsg, sizeof s->errmsg,
             "body '%s' passed into body '%s'%s at t = %.6g s (step %ld): %s (stiffness-normal %g "
             "Pa/m): %s",
             s->sc.bodies[i].name, s->sc.bodies[j].name, stage, s->t, s->nsteps_all, how,
             s->sc.contact.kn, cause);
    s->status = RD_STATUS_PENETRATED;
    return 1;
}

/* Body i's centre of mass inside convex body j: one error, 1. Only bodies whose boxes overlap
 * (the broad phase's live pairs) can hold each other's centre, so only those are tested: the
 * check costs O(bodies), not O(bodies^2). */
static int penetrated(rd_sim *s, int i, int j, const char *stage)
{
    if (s->fixed[i] || !s->convex[j] || !inside_convex(s, j, s->x[i])) return 0;
    return passed_into(s, i, j, stage, "its centre of mass is inside it", RD_SOFT_OR_EDGES);
}

/* A bearing subcontact point of side sd deeper in the other (convex) body than that body's
 * inradius has passed its middle (an idle point's depth is from an entrance face it may have
 * slid far past, a late face's corner on a pedestal's side plane: not evidence): the bodies have
 * passed into each other though neither centre of mass lies in the other (a 354 kg scanned rock
 * on a 0.3 m pedestal at KN 1e6 Pa/m sank 0.2 m into it while settling, on through it, and hung
 * in its side below its top: the run ended "done", the rock "FELL FREELY"). Any stiffness that
 * holds the load keeps the depth far below: the rock's is 0.04 mm at KN 1e10. One error, 1. */
static int sunk(rd_sim *s, const rd_side *sd, const char *stage)
{
    const int o = sd->owner, t = sd->other;
    double deepest = 0;
    for (int pt = s->pt0[o], st = sd->state0; pt < s->pt0[o + 1]; pt++, st++)
        if (s->pstate[st] & RD_PT_ACTIVE)
            deepest = fmax(deepest, -s->pj[st][1]); /* pj[1]: minus the depth */
    double r = rd_monitor_inradius(s, t);
    if (!(deepest > r)) return 0;
    char how[RD_NAME_MAX + 160];
    snprintf(how, sizeof how,
             "a subcontact point of '%s' is %.3g m deep in it, past its middle (%.3g m from its "
             "centre of mass to its nearest face)",
             s->sc.bodies[o].name, deepest, r);
    return passed_into(s, o, t, stage, how, RD_SOFT_OR_EDGES);
}

/* The deepest hull vertex of body o inside convex body t, m (<= 0: none inside), from o's pose
 * (a free mesh's stored hull positions may be a step old: pairs.c). */
static double hull_depth(const rd_sim *s, int o, int t)
{
    double deepest = -INFINITY;
    for (int e = s->hv0[o]; e < s->hv0[o + 1]; e++) {
        double w[3];
        rd_mat_vec(s->R[o], s->poly[o].v[s->hv[e] - s->vert0[o]], w);
        rd_axpy(1.0, s->x[o], w);
        deepest = fmax(deepest, rd_overlap_point_depth(s, t, w, deepest));
    }
    return deepest;
}

/* A mesh's face that carries no subcontact points (its points lie on the faces that touch at
 * the start or face down near its base: setup.c face_role) meets a convex body unseen: a
 * scanned rock tipped towards a wall passed 422 of its 1,986 vertices into it, and the run
 * ended "OVERTURNED". A hull vertex of mesh o deeper in convex t than 1 % of the smaller
 * radius (the depth a run accepts at rest, overlap.c) and than every bearing point of the side
 * by more than the contact band is not held by the law: one error, 1. */
static int unseen(rd_sim *s, const rd_side *sd, const char *stage)
{
    const int o = sd->owner, t = sd->other;
    if (s->surf || s->convex[o] || !s->convex[t]) return 0; /* (the surface model: every face) */
    double bearing = 0; /* the side's deepest bearing point, m */
    for (int pt = s->pt0[o], st = sd->state0; pt < s->pt0[o + 1]; pt++, st++)
        if (s->pstate[st] & RD_PT_ACTIVE) bearing = fmax(bearing, -s->pj[st][1]);
    const double r = fmin(s->poly[o].radius, s->poly[t].radius);
    const double most = fmax(RD_UNSEEN_FRACTION * r, bearing + RD_CONTACT_BAND * r);
    const double deepest = hull_depth(s, o, t);
    if (!(deepest > most)) return 0;
    char how[RD_NAME_MAX + 160];
    snprintf(how, sizeof how,
             "a vertex of '%s' is %.3g m deep in it, deeper than its bearing points (%.3g m)",
             s->sc.bodies[o].name, deepest, bearing);
    return passed_into(s, o, t, stage, how,
                       "a face of the mesh that carries no subcontact points met it (the vertex "
                       "model puts points on the faces that touch at the start or face down near "
                       "the base): give 'contact model surface'");
}

int rd_monitor_escape(rd_sim *s)
{
    const char *stage = s->settling ? " while settling" : "";
    for (int k = 0; k < s->nfree; k++) {
        int i = s->free_body[k];
        const double *c = s->x[i];
        rd_watch *w = &s->watch[k];
        if (s->run && s->run[k].left) continue; /* out of the domain: out of the run */
        if (c[2] < s->floor_z - s->poly[i].radius && !s->settling &&
            (w->over_once || w->rest_area > 0)) {
            if (!w->lost) {
                rd_event_add(s, s->t, k, "lost", s->floor_z - c[2]);
                if (!w->over_once) w->sum->overturn_time = s->t; /* fell off its support */
            }
            w->lost = 1;
            fell_over(s, k);
        } else if (c[2] < s->floor_z - s->poly[i].radius) {
            snprintf(s->errmsg, sizeof s->errmsg,
                     "body '%s' left the scene%s at t = %.6g s (step %ld): its centre of "
                     "mass is %.3g m below the lowest fixed body (nothing holds it)",
                     s->sc.bodies[i].name, stage, s->t, s->nsteps_all, s->floor_z - c[2]);
            s->status = RD_STATUS_LOST;
            return 1;
        }
    }
    for (int l = 0; l < s->nlive; l++) {
        const rd_pair *p = &s->pair[s->live[l]];
        if (penetrated(s, p->a, p->b, stage) || penetrated(s, p->b, p->a, stage)) return 1;
        for (int q = 0; q < p->nside; q++)
            if (sunk(s, &p->side[q], stage) || unseen(s, &p->side[q], stage)) return 1;
    }
    return 0;
}

/* The support plane of body i at rest (rd_watch.seat) into seat: the face of the body j it
 * rests on (-1: none) that faces up (normal within 60 degrees of the vertical) and lies
 * nearest i's lowest vertex low, through i's lowest point along its normal; level (e_z, through
 * i's lowest point) when j has no such face. An inclined pedestal's top face gives an inclined
 * base: its lowest point alone is not the base. */
static void seat_plane(const rd_sim *s, int i, int j, const double low[3], double seat[4])
{
    const double up[3] = { 0, 0, 1 };
    const double *n = up;
    double best = INFINITY;
    for (int f = j >= 0 ? s->face0[j] : 0; j >= 0 && f < s->face0[j + 1]; f++) {
        double gap = fabs(rd_dot(s->wn[f], low) - s->wd[f]);
        if (s->wn[f][2] >= 0.5 && gap < best) {
            best = gap;
            n = s->wn[f];
        }
    }
    rd_copy3(n, seat);
    seat[3] = INFINITY;
    for (int v = s->vert0[i]; v < s->vert0[i + 1]; v++)
        seat[3] = fmin(seat[3], rd_dot(n, s->wv[v]));
}

/* Rest state of body k: support polygon, height of the centre of mass, tipping angles. */
static void watch_init(rd_sim *s, const live_index *ix, int k)
{
    int i = s->free_body[k];
    rd_watch *w = &s->watch[k];
    memcpy(w->q_ref, s->q[i], sizeof w->q_ref);
    rd_copy3(s->x[i], w->x_ref);
    const double *low = s->wv[s->vert0[i]]; /* the lowest vertex */
    for (int v = s->vert0[i]; v < s->vert0[i + 1]; v++)
        if (s->wv[v][2] < low[2]) low = s->wv[v];
    const double zmin = low[2];
    w->rests_on = resting_on(s, ix, i);
    seat_plane(s, i, w->rests_on, low, w->seat);
    support_polygon(s, ix, k, zmin);
    const double zs = seat_z(w, s->x[i][0], s->x[i][1]);
    double b[3] = { s->x[i][0], s->x[i][1], zs }, d[3] = { 0, 0, zs - s->x[i][2] };
    rd_copy3(b, w->base_ref);
    rd_mat_tvec(s->R[i], d, w->base_local);
    w->rest_area = w->area;
    rd_mat_tvec(s->R[i], (double[3]){ 0, 0, 1 }, w->zb);
    snprintf(w->sum->name, sizeof w->sum->name, "%s", s->sc.bodies[i].name);
    w->sum->overturn_time = -1;
    double amin = M_PI / 2;
    for (int d = 0; d < RD_NPREC; d++) {
        double psi = 2 * M_PI * d / RD_NPREC, a = alpha_toward(w, cos(psi), sin(psi));
        w->prec[d][0] = psi;
        w->prec[d][1] = a;
        w->prec[d][2] = s->sc.gravity * tan(a);
        if (a < amin) {
            amin = a;
            w->sum->alpha_min_direction = psi;
        }
    }
    w->alpha_min = amin;
    w->sum->alpha_min = amin;
    w->sum->tip_accel_min = s->sc.gravity * tan(amin);
    w->sum->alpha = fmin(alpha_toward(w, 1, 0), alpha_toward(w, 0, 1));
    w->key_max = 0;
    w->key_ratio_gate = 0;
    const rd_overturn_def *o = &s->sc.overturn;
    w->cos_over_gate = o->kind == RD_OVERTURN_TILT_RATIO ? cos(fmin(o->value * amin, M_PI))
                       : o->kind == RD_OVERTURN_ANGLE    ? cos(o->value)
                                                         : -2;
}

/* Tilt (rad) of body k, its lean direction (unit, horizontal) and the tilt vector axis*angle. */
/* The body's rest vertical in the ground frame now (uses the step's rotation matrix). */
static void rest_vertical(const rd_sim *s, int k, double z[3])
{
    rd_mat_vec(s->R[s->free_body[k]], s->watch[k].zb, z);
}

/* Tilt (rad) from the rest vertical z, lean direction (unit, horizontal) and the tilt vector
 * axis * angle. */
static double tilt_of(const double z[3], double lean[2], double tv[3])
{
    double hz = hypot(z[0], z[1]);
    double tilt = atan2(hz, z[2]);
    lean[0] = hz > 0 ? z[0] / hz : 1;
    lean[1] = hz > 0 ? z[1] / hz : 0;
    tv[0] = -lean[1] * tilt;
    tv[1] = lean[0] * tilt;
    tv[2] = 0;
    return tilt;
}

void rd_monitor_rest(rd_sim *s)
{
    live_index ix;
    live_index_build(s, &ix);
    for (int k = 0; k < s->nfree; k++) watch_init(s, &ix, k);
    live_index_free(&ix);
}

void rd_monitor_start(rd_sim *s)
{
    for (int k = 0; k < s->nfree; k++) {
        rd_watch *w = &s->watch[k];
        double z[3];
        rest_vertical(s, k, z);
        double n = hypot(z[0], z[1]); /* sine of the initial tilt */
        int tilted = n > RD_ROCK_MIN * w->alpha_min;
        w->rock_axis[0] = tilted ? -z[1] / n : 0;
        w->rock_axis[1] = tilted ? z[0] / n : 1;
        w->rock_prev = -z[1] * w->rock_axis[0] + z[0] * w->rock_axis[1];
        w->rock_peak = fabs(w->rock_prev);
        w->uplifted = tilted;
        w->sum->uplifted = tilted;
    }
}

/* The watch that books the contact of a side (owner's points against other): a joint counts
 * for the body it supports, the one of the pair whose centre of mass is higher (a stack's lower
 * block rocks on its base joint, not on the joint under the upper block); NULL when that body
 * is fixed or neither is higher. */
rd_watch *rd_monitor_contact_watch(rd_sim *s, int owner, int other)
{
    for (int b = 0; b < 2; b++) {
        int me = b ? other : owner, below = b ? owner : other, k = s->free_of[me];
        if (k >= 0 && s->x[below][2] < s->x[me][2]) return &s->watch[k];
    }
    return NULL;
}

static int criterion_met(const rd_sim *s, int k, const double z[3])
{
    const rd_overturn_def *o = &s->sc.overturn;
    const rd_watch *w = &s->watch[k];
    int i = s->free_body[k];
    if (o->kind == RD_OVERTURN_HEIGHT)
        return s->x[i][2] - w->base_ref[2] < o->value * (w->x_ref[2] - w->base_ref[2]);
    if (o->kind == RD_OVERTURN_OFF) {
        if (w->rests_on < 0) return 0;
        double b[6]; /* grown by the broad-phase margin */
        rd_pairs_box_now(s, w->rests_on, b);
        double grow = o->value * s->poly[i].radius;
        return s->x[i][0] < b[0] - grow || s->x[i][0] > b[3] + grow || s->x[i][1] < b[1] - grow ||
               s->x[i][1] > b[4] + grow;
    }
    if (z[2] >= w->cos_over_gate) return 0; /* below the smallest possible threshold */
    if (o->kind == RD_OVERTURN_ANGLE) return 1;
    double lean[2], tv[3], tilt = tilt_of(z, lean, tv);
    return tilt >= o->value * alpha_toward(w, lean[0], lean[1]);
}

/* A number that grows with the tilt over [0, pi] and resolves small tilts to round-off: the
 * squared horizontal part of the rest vertical, mirrored past 90 degrees. */
static double tilt_key(const double z[3])
{
    double h2 = z[0] * z[0] + z[1] * z[1];
    return z[2] >= 0 ? h2 : 2 - h2;
}

static double key_of_angle(double a)
{
    return a <= M_PI / 2 ? sin(a) * sin(a) : 2 - sin(a) * sin(a);
}

/* Extremes of tilt, tilt / alpha and slide. The angles cost an atan2 and a ray cast, so they
 * are evaluated only when the tilt passes a gate that a new extreme must pass. */
static void track_extremes(rd_sim *s, int k, const double z[3])
{
    rd_watch *w = &s->watch[k];
    rd_body_summary *sum = w->sum;
    int i = s->free_body[k];
    double key = tilt_key(z);
    if (key > w->key_max || key > w->key_ratio_gate) {
        double lean[2], tv[3], tilt = tilt_of(z, lean, tv);
        if (key > w->key_max) {
            sum->max_tilt = tilt;
            w->key_max = key;
        }
        double ratio = tilt / alpha_toward(w, lean[0], lean[1]);
        if (ratio > sum->max_tilt_ratio) {
            sum->max_tilt_ratio = ratio;
            w->key_ratio_gate = key_of_angle(rd_min(ratio * w->alpha_min, M_PI));
        }
    }
    double b[3];
    rd_mat_vec(s->R[i], w->base_local, b);
    rd_axpy(1.0, s->x[i], b);
    double dx = b[0] - w->base_ref[0], dy = b[1] - w->base_ref[1], d2 = dx * dx + dy * dy;
    if (d2 > sum->max_slide * sum->max_slide) sum->max_slide = sqrt(d2);
}

static void watch_step(rd_sim *s, int k)
{
    rd_watch *w = &s->watch[k];
    rd_body_summary *sum = w->sum;
    int i = s->free_body[k];
    double z[3];
    if (w->lost) { /* it overturned and fell out of the scene: the verdict is final (a body
                      tumbling in free fall passes upright again, which is no recovery) */
        w->down = 1;
        return;
    }
    rest_vertical(s, k, z);
    track_extremes(s, k, z);
    w->down = z[2] < cos(RD_FALLEN_TILT);

    if (w->rest_area > 0 && !w->uplifted && w->area < RD_UPLIFT_AREA_ON * w->rest_area) {
        w->uplifted = 1;
        sum->uplifted = 1;
        double lean[2], tv[3], tilt = tilt_of(z, lean, tv);
        rd_event_add(s, s->t, k, "uplift", tilt);
        if (w->rock_peak < RD_ROCK_MIN * w->alpha_min &&
            rd_norm(tv) > 0) { /* first rocking: its axis */
            double n = rd_norm(tv);
            w->rock_axis[0] = tv[0] / n;
            w->rock_axis[1] = tv[1] / n;
        }
    } else if (w->uplifted && w->area >= RD_UPLIFT_AREA_OFF * w->rest_area &&
               1 - z[2] < 5e-7 * w->alpha_min * w->alpha_min) {
        w->uplifted = 0;
    }
    /* signed rocking about the first rocking axis, sine-scaled: (z x e_z) . axis */
    double r = -z[1] * w->rock_axis[0] + z[0] * w->rock_axis[1];
    if (r * w->rock_prev < 0 && w->rock_peak >= RD_ROCK_MIN * w->alpha_min) {
        double f = w->rock_prev / (w->rock_prev - r); /* linear interpolation of the crossing */
        rd_event_add(s, s->t - s->dt + f * s->dt, k, "peak", asin(rd_min(w->rock_peak, 1.0)));
        rd_event_add(s, s->t - s->dt + f * s->dt, k, "impact", rd_norm(s->w[i]));
        w->rock_peak = 0;
    }
    w->rock_peak = rd_max(w->rock_peak, fabs(r));
    w->rock_prev = r;

    int sliding = w->nactive > 0 && w->nslip == w->nactive;
    if (sliding && !w->sliding) {
        rd_event_add(s, s->t, k, "slip", sum->max_slide);
        sum->slid = 1;
    }
    w->sliding = sliding;

    int over = criterion_met(s, k, z);
    if (over) w->over_once = 1;
    if (over != w->over) {
        double lean[2], tv[3], tilt = tilt_of(z, lean, tv);
        rd_event_add(s, s->t, k, over ? "overturn" : "recover", tilt);
        if (over) sum->overturn_time = s->t;
    }
    w->over = over;
    sum->overturned = over;
}

void rd_monitor_step(rd_sim *s)
{
    for (int k = 0; k < s->nfree; k++) watch_step(s, k);
}

/* Body k lies down: tilted past RD_FALLEN_TILT or fallen out of the scene, or, for the height
 * and off-pedestal criteria, meeting them. */
static int fallen(const rd_sim *s, int k)
{
    rd_overturn_kind kind = s->sc.overturn.kind;
    return s->watch[k].down ||
           ((kind == RD_OVERTURN_HEIGHT || kind == RD_OVERTURN_OFF) && s->watch[k].over);
}

int rd_monitor_all_fallen(const rd_sim *s)
{
    for (int k = 0; k < s->nfree; k++)
        if (!fallen(s, k)) return 0;
    return s->nfree > 0;
}

int rd_monitor_any_fallen(const rd_sim *s)
{
    for (int k = 0; k < s->nfree; k++)
        if (s->watch[k].over && fallen(s, k)) return 1;
    return 0;
}

void rd_monitor_finish(rd_sim *s)
{
    for (int k = 0; k < s->nfree; k++) {
        rd_watch *w = &s->watch[k];
        int i = s->free_body[k];
        double b[3];
        rd_mat_vec(s->R[i], w->base_local, b);
        rd_axpy(1.0, s->x[i], b);
        w->sum->final_slide = hypot(b[0] - w->base_ref[0], b[1] - w->base_ref[1]);
        /* where it ended up: a body that never touched anything fell freely */
        w->sum->unsupported = w->rest_area <= 0 && !w->touched;
        rd_copy3(s->x[i], w->sum->final_position);
        w->sum->travel = hypot(s->x[i][0] - w->x_ref[0], s->x[i][1] - w->x_ref[1]);
        w->sum->drop = w->z_start - s->x[i][2];
        if (!w->sum->overturned) w->sum->overturn_time = -1;
    }
}

/* Rotation of body k from rest: in-plane rocking, out-of-plane rocking, twist (rad), the twist
 * unwrapped against prev (rad: the caller's last twist), without touching the monitor
 * (histories read it this way, so that measuring changes no result). */
void rd_monitor_rotation_peek(const rd_sim *s, int k, double prev, double out[3])
{
    const rd_watch *w = &s->watch[k];
    int i = s->free_body[k];
    double qc[4] = { w->q_ref[0], -w->q_ref[1], -w->q_ref[2], -w->q_ref[3] }, dq[4];
    rd_quat_mul(s->q[i], qc, dq); /* rotation since rest, ground frame */
    double tn = hypot(dq[0], dq[3]);
    double qt[4] = { tn > 0 ? dq[0] / tn : 1, 0, 0, tn > 0 ? dq[3] / tn : 0 };
    double qti[4] = { qt[0], 0, 0, -qt[3] }, qs[4];
    rd_quat_mul(dq, qti, qs); /* swing = rotation * twist^-1 */
    if (qs[0] < 0)
        for (int j = 0; j < 4; j++) qs[j] = -qs[j];
    double sn = sqrt(qs[1] * qs[1] + qs[2] * qs[2] + qs[3] * qs[3]);
    double ang = 2 * atan2(sn, qs[0]), f = sn > 0 ? ang / sn : 2.0;
    double phi[2] = { f * qs[1], f * qs[2] }; /* horizontal swing rotation vector */
    double dir = s->sc.motion.horizontal.direction, d[2] = { cos(dir), sin(dir) };
    out[0] = -phi[0] * d[1] + phi[1] * d[0];   /* about z x d */
    out[1] = -(phi[0] * d[0] + phi[1] * d[1]); /* about -d */
    double tw = 2 * atan2(qt[3], qt[0]);       /* in (-2 pi, 2 pi] */
    while (tw - prev > M_PI) tw -= 2 * M_PI;
    while (tw - prev < -M_PI) tw += 2 * M_PI;
    out[2] = tw;
}

/* rd_monitor_rotation_peek, then the unwrapping's reference and the summary's maxima follow it.
 * Called at output samples (twist unwrapping assumes less than half a turn between samples). */
void rd_monitor_rotation(rd_sim *s, int k, double out[3])
{
    rd_watch *w = &s->watch[k];
    rd_monitor_rotation_peek(s, k, w->twist_prev, out);
    const double tw = out[2];
    w->twist_prev = tw;
    rd_body_summary *sum = w->sum;
    sum->max_rocking_in = rd_max(sum->max_rocking_in, fabs(out[0]));
    sum->max_rocking_out = rd_max(sum->max_rocking_out, fabs(out[1]));
    sum->max_twist = rd_max(sum->max_twist, fabs(tw));
    sum->final_twist = tw;
}
