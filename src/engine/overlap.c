/* rockdem — bodies that overlap as placed.
 *
 * A scene whose bodies interpenetrate as placed cannot start: the contact springs, pressed by
 * the overlap's depth, throw the bodies apart (a 0.4 x 0.4 x 1.6 m block placed 0.1 m into its
 * pedestal was flung 130 m up, and the run ended `done`). The depth of an overlap between two
 * convex bodies is their penetration depth: the least overlap of their projections over the
 * separating axes (each one's face normals, the cross products of their edges; two blocks side
 * by side 0.1 m into each other overlap by 0.1 m though no vertex lies inside the other); with
 * a mesh, the deepest its vertices lie inside the convex other, m. A block seated on another lies at depth 0, or at its static
 * compression m g / (KN A) (micrometres) when placed pressed; an overlap deeper than
 * RD_OVERLAP_FRACTION of the smaller body's bounding radius is refused by `run` (the setup
 * finds the deepest among touching bodies, rd_setup_contacts) and told by `check`.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "base/vec.h"

#include <math.h>
#include <stdio.h>

double rd_overlap_point_depth(const rd_sim *s, int t, const double w[3], double stop)
{
    const double(*wn)[3] = s->wn + s->face0[t];
    const double *wd = s->wd + s->face0[t];
    double depth = INFINITY; /* below every plane of t by at least this */
    for (int f = 0; f < s->poly[t].nf && depth > stop; f++)
        depth = fmin(depth, wd[f] - rd_dot(wn[f], w));
    return depth;
}

/* The deepest vertex of body i inside convex body j, m (<= 0: none inside). */
static double vertex_depth(const rd_sim *s, int i, int j)
{
    double deepest = -INFINITY;
    for (int v = s->vert0[i]; v < s->vert0[i + 1]; v++)
        deepest = fmax(deepest, rd_overlap_point_depth(s, j, s->wv[v], deepest));
    return deepest;
}

/* How far the projections of bodies i and j on the unit axis n overlap, m (< 0: apart). */
static double axis_overlap(const rd_sim *s, int i, int j, const double n[3])
{
    double lo[2] = { INFINITY, INFINITY }, hi[2] = { -INFINITY, -INFINITY };
    const int body[2] = { i, j };
    for (int k = 0; k < 2; k++)
        for (int v = s->vert0[body[k]]; v < s->vert0[body[k] + 1]; v++) {
            double x = rd_dot(n, s->wv[v]);
            lo[k] = fmin(lo[k], x);
            hi[k] = fmax(hi[k], x);
        }
    return fmin(hi[0] - lo[1], hi[1] - lo[0]);
}

/* Body i's edge directions (ground frame, unit), parallel ones once, into dir; their count. */
static int edge_directions(const rd_sim *s, int i, double (*dir)[3], int cap)
{
    const rd_poly *p = &s->poly[i];
    const double(*v)[3] = s->wv + s->vert0[i];
    int n = 0;
    for (int f = 0; f < p->nf; f++)
        for (int k = 0; k < p->flen[f]; k++) {
            const int *ix = p->fidx + p->fstart[f];
            const double *a = v[ix[k]], *b = v[ix[(k + 1) % p->flen[f]]];
            double e[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, c[3], len = rd_norm(e);
            if (!(len > 0)) continue;
            for (int q = 0; q < 3; q++) e[q] /= len;
            int seen = 0;
            for (int m = 0; m < n && !seen; m++) {
                rd_cross(dir[m], e, c);
                seen = rd_norm(c) < RD_PARALLEL_SIN;
            }
            if (!seen && n < cap) rd_copy3(e, dir[n++]);
        }
    return n;
}

/* Convex bodies i and j: their penetration depth, the least overlap of their projections over
 * the separating axes (each body's face normals and the cross products of their edges), m;
 * stops once it is at most stop (the answer is then only known to be below stop). */
static double convex_depth(const rd_sim *s, int i, int j, double stop)
{
    double depth = INFINITY;
    const int body[2] = { i, j };
    for (int k = 0; k < 2 && depth > stop; k++)
        for (int f = 0; f < s->poly[body[k]].nf && depth > stop; f++)
            depth = fmin(depth, axis_overlap(s, i, j, s->wn[s->face0[body[k]] + f]));
    double di[RD_OVERLAP_EDGE_DIRS][3], dj[RD_OVERLAP_EDGE_DIRS][3];
    int ni = depth > stop ? edge_directions(s, i, di, RD_OVERLAP_EDGE_DIRS) : 0;
    int nj = ni ? edge_directions(s, j, dj, RD_OVERLAP_EDGE_DIRS) : 0;
    for (int a = 0; a < ni && depth > stop; a++)
        for (int b = 0; b < nj && depth > stop; b++) {
            double n[3];
            rd_cross(di[a], dj[b], n);
            double len = rd_norm(n);
            if (len < RD_PARALLEL_SIN) continue; /* parallel edges: a face normal covers them */
            for (int q = 0; q < 3; q++) n[q] /= len;
            depth = fmin(depth, axis_overlap(s, i, j, n));
        }
    return depth;
}

/* How deep bodies i and j overlap, m (0: apart or touching); for two convex bodies only known
 * to be at most stop once it is (convex_depth). */
static double depth_to(const rd_sim *s, int i, int j, double stop)
{
    if (s->convex[i] && s->convex[j]) return fmax(convex_depth(s, i, j, stop), 0.0);
    double d = 0; /* a mesh: its vertices inside the convex other */
    if (s->convex[j]) d = fmax(d, vertex_depth(s, i, j));
    if (s->convex[i]) d = fmax(d, vertex_depth(s, j, i));
    return d;
}

double rd_overlap_depth(const rd_sim *s, int i, int j) { return depth_to(s, i, j, 0.0); }

void rd_overlap_note(rd_sim *s, int i, int j)
{
    if (s->fixed[i] && s->fixed[j]) return; /* fixed bodies may be built into each other */
    const double least =
        fmax(RD_OVERLAP_FRACTION * fmin(s->poly[i].radius, s->poly[j].radius), s->overlap);
    double d = depth_to(s, i, j, least);
    if (d > least) {
        s->overlap = d;
        s->overlap_pair[0] = i;
        s->overlap_pair[1] = j;
    }
}

int rd_overlap_refuse(const rd_sim *s, rd_error *err)
{
    if (!(s->overlap > 0)) return 0;
    const rd_body_def *a = &s->sc.bodies[s->overlap_pair[0]],
                      *b = &s->sc.bodies[s->overlap_pair[1]];
    return rd_error_set(err,
                        "%s: blocks '%s' and '%s' overlap by %.4g m as placed: the contact springs "
                        "would throw them apart (place one on the other with seat-on, or move it)",
                        s->sc.file, a->name, b->name, s->overlap);
}

/* Deepest overlap at rest, as a fraction of the smaller body's radius, that a run accepts: ten
 * contact bands. A joint's closure m g / (KN A) is its elastic deformation (the cask at KN 1e8
 * settles 3 mm, 0.12 % of its radius; a 0.5 x 0.5 x 1 m block at KN 1e7, 0.44 %), but past 1 %
 * the lever arms the verdicts rest on (alpha = atan(b / h), the support polygon) are off by more
 * than 1 %. */
#define RD_REST_OVERLAP_FRACTION (10 * RD_CONTACT_BAND)

/* No silent wrong answer at rest: after settling, two bodies deeper into each other than
 * RD_REST_OVERLAP_FRACTION of the smaller radius bear their load on springs far too soft for
 * it (a stack with a mass ratio of 1e6 ran 61 mm into itself, silently). The run stops as
 * penetrated, naming the pair, the depth and how much stiffer the joint would have to be. 1
 * when it stops. */
int rd_overlap_at_rest(rd_sim *s)
{
    for (int k = 0; k < s->npair; k++) {
        int a = s->pair[k].a, b = s->pair[k].b;
        if (s->fixed[a] && s->fixed[b]) continue;
        double most = RD_REST_OVERLAP_FRACTION * fmin(s->poly[a].radius, s->poly[b].radius);
        double d = depth_to(s, a, b, most);
        if (!(d > most)) continue;
        snprintf(
            s->errmsg, sizeof s->errmsg,
            "at rest, blocks '%s' and '%s' interpenetrate by %.3g mm, more than "
            "%.3g mm (1 %% of the smaller radius): their joint is far too soft for the load on it "
            "(stiffness-normal about %.2g times stiffer would keep it within that), or they were placed "
            "into each other",
            s->sc.bodies[a].name, s->sc.bodies[b].name, 1e3 * d, 1e3 * most, d / most);
        s->status = RD_STATUS_PENETRATED;
        return 1;
    }
    return 0;
}
