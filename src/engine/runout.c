/* rockdem — the runout after the topple (docs/RUNOUT.md): where each free body's centre of mass
 * goes once the shaking has set it moving, every step in the ground frame:
 *   - its path length, largest speed and kinetic energy, and largest bounce (the gap between its
 *     lowest hull vertex and the fixed surface below it, in flight: while it touches, 0);
 *   - the first crossing of its plan path with each fence's polyline (`model fence points`):
 *     time, kinetic energy (translation and rotation), speed, the centre's height above the
 *     surface below it there, by linear interpolation within the step;
 *   - leaving the domain box (`model domain box`): event "left", and out of the run (rest.c
 *     no longer waits for it; the escape checks no longer watch it).
 * The surface below a point is the highest upward-facing triangle of a fixed body under it,
 * found on a plan grid of the triangles (built once: fixed bodies do not move in this frame).
 * Folder engine/ owns the simulation; it may call base/ and geometry/.
 */
#include "engine/sim.h"
#include "base/vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RD_GROUND_UP       1e-6 /* a triangle faces up when its normal's z exceeds this */
#define RD_GROUND_MAX_GRID 512  /* cells along a side of the plan grid, at most */
#define RD_BOUNCE_EVERY    8    /* steps between bounce measurements (a flight lasts many) */

static double rd_dist2(const double a[3], const double b[3])
{
    double d[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    return rd_dot(d, d);
}

/* ---- the fixed surface from above ---- */

static int count_up(const rd_sim *s, double (*out)[3][3])
{
    int n = 0;
    for (int i = 0; i < s->nb; i++) {
        const rd_poly *p = &s->poly[i];
        for (int t = 0; s->fixed[i] && t < p->ntri; t++) {
            const double *a = s->wv[s->vert0[i] + p->tri[t][0]];
            const double *b = s->wv[s->vert0[i] + p->tri[t][1]];
            const double *c = s->wv[s->vert0[i] + p->tri[t][2]];
            double nz = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            if (!(nz > RD_GROUND_UP * (rd_dist2(a, b) + rd_dist2(a, c)))) continue;
            if (out) {
                rd_copy3(a, out[n][0]);
                rd_copy3(b, out[n][1]);
                rd_copy3(c, out[n][2]);
            }
            n++;
        }
    }
    return n;
}

static void tri_box(const double t[3][3], double lo[2], double hi[2])
{
    for (int k = 0; k < 2; k++) {
        lo[k] = fmin(t[0][k], fmin(t[1][k], t[2][k]));
        hi[k] = fmax(t[0][k], fmax(t[1][k], t[2][k]));
    }
}

static int cell_of(const rd_ground *g, double x, int axis)
{
    int n = axis ? g->ny : g->nx, c = (int)floor((x - g->lo[axis]) / g->cell);
    return c < 0 ? 0 : c >= n ? n - 1 : c;
}

/* Visit triangle t's cells: count (fill 0) or fill (fill 1) them. */
static void bin_tri(rd_ground *g, int t, int *next, int fill)
{
    double lo[2], hi[2];
    tri_box(g->tri[t], lo, hi);
    for (int cy = cell_of(g, lo[1], 1); cy <= cell_of(g, hi[1], 1); cy++)
        for (int cx = cell_of(g, lo[0], 0); cx <= cell_of(g, hi[0], 0); cx++) {
            int c = cy * g->nx + cx;
            if (fill)
                g->item[next[c]++] = t;
            else
                g->cell0[c + 1]++;
        }
}

static int ground_build(rd_sim *s)
{
    rd_ground *g = &s->ground;
    g->ntri = count_up(s, NULL);
    if (g->ntri == 0) return 0;
    g->tri = malloc((size_t)g->ntri * sizeof *g->tri);
    if (!g->tri) return -1;
    count_up(s, g->tri);
    double lo[2] = { INFINITY, INFINITY }, hi[2] = { -INFINITY, -INFINITY };
    for (int t = 0; t < g->ntri; t++) {
        double a[2], b[2];
        tri_box(g->tri[t], a, b);
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], a[k]);
            hi[k] = fmax(hi[k], b[k]);
        }
    }
    double span = fmax(fmax(hi[0] - lo[0], hi[1] - lo[1]), 1e-9);
    int side = (int)fmin(RD_GROUND_MAX_GRID, ceil(sqrt((double)g->ntri)));
    g->cell = span / side;
    memcpy(g->lo, lo, sizeof lo);
    g->nx = (int)fmin(side, floor((hi[0] - lo[0]) / g->cell) + 1);
    g->ny = (int)fmin(side, floor((hi[1] - lo[1]) / g->cell) + 1);
    g->cell0 = calloc((size_t)g->nx * g->ny + 1, sizeof *g->cell0);
    if (!g->cell0) return -1;
    for (int t = 0; t < g->ntri; t++) bin_tri(g, t, NULL, 0);
    for (int c = 0; c < g->nx * g->ny; c++) g->cell0[c + 1] += g->cell0[c];
    int *next = malloc((size_t)g->nx * g->ny * sizeof *next);
    g->item = malloc((size_t)(g->cell0[g->nx * g->ny] + 1) * sizeof *g->item);
    if (!next || !g->item) {
        free(next);
        return -1;
    }
    memcpy(next, g->cell0, (size_t)g->nx * g->ny * sizeof *next);
    for (int t = 0; t < g->ntri; t++) bin_tri(g, t, next, 1);
    free(next);
    return 0;
}

/* Height of triangle t at (x, y) if (x, y) lies over it (barycentric, edges included). */
static int tri_height(const double t[3][3], double x, double y, double *z)
{
    double d =
        (t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[1][1] - t[0][1]) * (t[2][0] - t[0][0]);
    double u = ((x - t[0][0]) * (t[2][1] - t[0][1]) - (y - t[0][1]) * (t[2][0] - t[0][0])) / d;
    double v = ((t[1][0] - t[0][0]) * (y - t[0][1]) - (t[1][1] - t[0][1]) * (x - t[0][0])) / d;
    const double eps = 1e-12;
    if (u < -eps || v < -eps || u + v > 1 + eps) return 0;
    *z = t[0][2] + u * (t[1][2] - t[0][2]) + v * (t[2][2] - t[0][2]);
    return 1;
}

double rd_ground_below(const rd_sim *s, double x, double y, double z_top)
{
    const rd_ground *g = &s->ground;
    if (g->ntri == 0 || x < g->lo[0] || y < g->lo[1] || x > g->lo[0] + g->nx * g->cell ||
        y > g->lo[1] + g->ny * g->cell)
        return -INFINITY;
    int c = cell_of(g, y, 1) * g->nx + cell_of(g, x, 0);
    double best = -INFINITY, z;
    for (int e = g->cell0[c]; e < g->cell0[c + 1]; e++)
        if (tri_height(g->tri[g->item[e]], x, y, &z) && z <= z_top && z > best) best = z;
    return best;
}

/* ---- per body ---- */

/* Gap between body i's lowest hull vertex (over the surface) and the surface below it, m;
 * -INFINITY when no vertex is over the surface. A vertex pressed into the surface finds it up
 * to the body's radius above it (its gap is then negative): with a band of RD_CONTACT_BAND r
 * the corners of a block landing flat, pressed 1 mm in, missed the surface, and its upper
 * corners' 0.4 m was taken for a bounce. */
static double clearance(const rd_sim *s, int i)
{
    double gap = INFINITY, band = s->poly[i].radius;
    int over = 0;
    for (int e = s->hv0[i]; e < s->hv0[i + 1]; e++) {
        double p[3];
        rd_mat_vec(s->R[i], s->poly[i].v[s->hv[e] - s->vert0[i]], p);
        rd_axpy(1.0, s->x[i], p);
        double zg = rd_ground_below(s, p[0], p[1], p[2] + band);
        if (zg == -INFINITY) continue;
        over = 1;
        gap = fmin(gap, p[2] - zg);
    }
    return over ? gap : -INFINITY;
}

/* Does plan segment a-b cross segment p-q? Then u: the fraction along a-b. */
static int crosses(const double a[2], const double b[2], const double p[2], const double q[2],
                   double *u)
{
    double r[2] = { b[0] - a[0], b[1] - a[1] }, sv[2] = { q[0] - p[0], q[1] - p[1] };
    double den = r[0] * sv[1] - r[1] * sv[0];
    if (den == 0) return 0;
    double ap[2] = { p[0] - a[0], p[1] - a[1] };
    double t = (ap[0] * sv[1] - ap[1] * sv[0]) / den, w = (ap[0] * r[1] - ap[1] * r[0]) / den;
    if (t < 0 || t >= 1 || w < 0 || w > 1) return 0;
    *u = t;
    return 1;
}

static double kinetic(const rd_sim *s, int i)
{
    return 0.5 * s->mass[i] * rd_dot(s->v[i], s->v[i]) + 0.5 * rd_dot(s->w[i], s->L[i]);
}

/* The body's centre moved from x_prev to x this step: a crossing of fence fe's line? */
static void fence_step(rd_sim *s, int k, const rd_fence_def *fe, rd_fence_hit *h)
{
    int i = s->free_body[k];
    const double *a = s->run[k].x_prev, *c = s->x[i];
    for (int f = 0; f + 1 < fe->npoint; f++) {
        double u;
        if (!crosses(a, c, fe->point[f], fe->point[f + 1], &u)) continue;
        if (h->crossings++ == 0) {
            double p[3];
            for (int m = 0; m < 3; m++) p[m] = a[m] + u * (c[m] - a[m]);
            rd_copy3(p, h->point);
            h->time = s->t - s->dt + u * s->dt;
            h->energy = kinetic(s, i);
            h->speed = rd_norm(s->v[i]);
            double zg = rd_ground_below(s, p[0], p[1], p[2]);
            h->height = zg == -INFINITY ? NAN : p[2] - zg;
            rd_event_add(s, h->time, k, "fence", h->energy);
        }
    }
}

static int outside(const rd_runout_def *r, const double x[3])
{
    for (int m = 0; m < 3; m++)
        if (x[m] < r->lo[m] || x[m] > r->hi[m]) return 1;
    return 0;
}

int rd_runout_begin(rd_sim *s)
{
    s->run = calloc((size_t)s->nfree + 1, sizeof *s->run);
    if (!s->run || ground_build(s)) return -1;
    for (int k = 0; k < s->nfree; k++) {
        rd_body_summary *b = &s->body_sum[k];
        rd_copy3(s->x[s->free_body[k]], s->run[k].x_prev);
        b->left_time = -1;
        b->nfences = s->sc.runout.nfences;
        for (int f = 0; f < RD_MAX_FENCES; f++) b->fence[f].time = b->fence[f].height = -1;
        b->max_bounce = 0;
    }
    return 0;
}

void rd_runout_step(rd_sim *s)
{
    const rd_runout_def *r = &s->sc.runout;
    int bounce = s->step % RD_BOUNCE_EVERY == 0 && s->ground.ntri > 0;
    for (int k = 0; k < s->nfree; k++) {
        int i = s->free_body[k];
        rd_runout_body *run = &s->run[k];
        rd_body_summary *b = &s->body_sum[k];
        if (run->left) continue;
        b->path_length += sqrt(rd_dist2(run->x_prev, s->x[i]));
        b->max_speed = fmax(b->max_speed, rd_norm(s->v[i]));
        b->max_energy = fmax(b->max_energy, kinetic(s, i));
        /* a body touching something has no gap to find (its lowest vertex bears): only in
           flight is the surface searched (the PBR's rocking cost 5.6 % more instructions) */
        if (bounce && !(s->watch[k].area > 0)) b->max_bounce = fmax(b->max_bounce, clearance(s, i));
        for (int f = 0; f < r->nfences; f++) fence_step(s, k, &r->fence[f], &b->fence[f]);
        rd_copy3(s->x[i], run->x_prev);
        if (r->domain && outside(r, s->x[i])) {
            run->left = 1;
            b->left_time = s->t;
            rd_event_add(s, s->t, k, "left", rd_norm(s->v[i]));
        }
    }
}

void rd_runout_finish(rd_sim *s)
{
    for (int k = 0; s->run && k < s->nfree; k++) {
        int i = s->free_body[k];
        rd_body_summary *b = &s->body_sum[k];
        const double *x0 = s->watch[k].x_ref;
        double dx = s->x[i][0] - x0[0], dy = s->x[i][1] - x0[1];
        b->runout_direction = dx == 0 && dy == 0 ? 0 : atan2(dy, dx);
        memcpy(b->final_quaternion, s->q[i], sizeof b->final_quaternion);
    }
}

void rd_runout_free(rd_sim *s)
{
    free(s->run);
    free(s->ground.tri);
    free(s->ground.cell0);
    free(s->ground.item);
    s->run = NULL;
    memset(&s->ground, 0, sizeof s->ground);
}
