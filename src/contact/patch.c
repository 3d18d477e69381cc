/* rockdem — the geometry of a contact patch: clipping of convex polygons, exact polygon
 * moments, the torsion integral, the load of an affine depth (contact/contact.h).
 * Folder contact/ holds the patch geometry and its law; it may call base/ and geometry/, and is
 * called by engine/.
 */
#include "contact/contact.h"
#include "base/vec.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* A fan triangle whose doubled area is below this fraction of its squared size is taken as a
 * line (rd_patch_torsion). */
#define RD_PATCH_THIN        1e-13
/* rd_patch_torsion_bound is lowered by this fraction: far above its round-off, far below the
 * bound's own slack (it is 0.62 of the integral on a square, 0.75 on a disc) */
#define RD_PATCH_BOUND_SLACK 1e-9

int rd_patch_clip_half(const rd_poly2 *in, double a, double b, double c, rd_poly2 *out)
{
    out->n = 0;
    double f[RD_PATCH_MAX]; /* the line's function at each vertex */
    for (int i = 0; i < in->n; i++) f[i] = a * in->p[i][0] + b * in->p[i][1] + c;
    for (int i = 0; i < in->n; i++) {
        const int j = i + 1 == in->n ? 0 : i + 1;
        const double *p = in->p[i], *q = in->p[j];
        const double fp = f[i], fq = f[j];
        if (fp >= 0) {
            if (out->n == RD_PATCH_MAX) return out->n = 0;
            out->p[out->n][0] = p[0];
            out->p[out->n][1] = p[1];
            out->n++;
        }
        if ((fp >= 0) != (fq >= 0)) { /* the edge crosses the line: its crossing point */
            if (out->n == RD_PATCH_MAX) return out->n = 0;
            double t = fp / (fp - fq);
            out->p[out->n][0] = p[0] + t * (q[0] - p[0]);
            out->p[out->n][1] = p[1] + t * (q[1] - p[1]);
            out->n++;
        }
    }
    if (out->n < 3) out->n = 0;
    return out->n;
}

int rd_patch_clip(const rd_poly2 *subj, const rd_poly2 *clip, rd_poly2 *out)
{
    rd_poly2 buf[2];
    const rd_poly2 *cur = subj;
    for (int i = 0; i < clip->n; i++) {
        const double *p = clip->p[i], *q = clip->p[(i + 1) % clip->n];
        /* inside: left of the edge p -> q, ex (y - py) - ey (x - px) >= 0 */
        double ex = q[0] - p[0], ey = q[1] - p[1];
        rd_poly2 *dst = (i == clip->n - 1) ? out : &buf[i & 1];
        if (!rd_patch_clip_half(cur, -ey, ex, ey * p[0] - ex * p[1], dst)) return out->n = 0;
        cur = dst;
    }
    if (clip->n == 0) out->n = 0;
    return out->n;
}

void rd_patch_moments(const rd_poly2 *p, rd_moments *m)
{
    *m = (rd_moments){ 0, 0, 0, 0, 0, 0 };
    if (p->n < 3) return;
    /* about the first vertex (round-off relative to the polygon's size), then shifted */
    const double x0 = p->p[0][0], y0 = p->p[0][1];
    double a = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (int i = 0; i < p->n; i++) {
        const double *u = p->p[i], *v = p->p[i + 1 == p->n ? 0 : i + 1];
        double xi = u[0] - x0, yi = u[1] - y0, xj = v[0] - x0, yj = v[1] - y0;
        double cr = xi * yj - xj * yi;
        a += cr;
        sx += (xi + xj) * cr;
        sy += (yi + yj) * cr;
        sxx += (xi * xi + xi * xj + xj * xj) * cr;
        syy += (yi * yi + yi * yj + yj * yj) * cr;
        sxy += (xi * yj + 2 * xi * yi + 2 * xj * yj + xj * yi) * cr;
    }
    a /= 2;
    sx /= 6;
    sy /= 6;
    sxx /= 12;
    syy /= 12;
    sxy /= 24;
    m->a = a;
    m->sx = sx + a * x0;
    m->sy = sy + a * y0;
    m->sxx = sxx + 2 * x0 * sx + a * x0 * x0;
    m->syy = syy + 2 * y0 * sy + a * y0 * y0;
    m->sxy = sxy + x0 * sy + y0 * sx + a * x0 * y0;
}

/* The integrals over t in [0, 1] of sqrt(q) and t sqrt(q), q = alpha t^2 + beta t + gamma =
 * |a + t e|^2 (alpha = |e|^2 > 0, disc = 4 alpha gamma - beta^2 = 4 (a x e)^2 > 0). */
static void edge_root_integrals(double alpha, double beta, double gamma, double disc, double *j0,
                                double *j1)
{
    const double sd = sqrt(disc), q0 = sqrt(gamma), q1 = sqrt(alpha + beta + gamma);
    const double k = disc / (8.0 * alpha * sqrt(alpha));
    double f1 = (2 * alpha + beta) * q1 / (4 * alpha) + k * asinh((2 * alpha + beta) / sd);
    double f0 = beta * q0 / (4 * alpha) + k * asinh(beta / sd);
    *j0 = f1 - f0;
    *j1 = ((2.0 / 3.0) * (q1 * q1 * q1 - q0 * q0 * q0) - beta * *j0) / (2 * alpha);
}

/* The share of fan triangle (c, c + a, c + a + e) in the integral of (dc + g . (r - c)) |r - c|:
 * as c + s (a + t e), s, t in [0, 1], dA = s (a x e) ds dt, |r - c| = s |w|, w = a + t e, and
 * the depth dc + s g . w, so (a x e) [(dc / 3 + g . a / 4) J0 + (g . e / 4) J1], J0 and J1 the
 * integrals of |w| and t |w| over t. */
static double fan_share(const double a[2], const double e[2], double dc, double gx, double gy)
{
    double cr = a[0] * e[1] - a[1] * e[0];
    double alpha = e[0] * e[0] + e[1] * e[1], gamma = a[0] * a[0] + a[1] * a[1];
    /* a fan triangle of no area (c on the edge's line: c at a vertex, or on an edge of a face
       cut into triangles), whose share is below the round-off of the others' */
    if (!(fabs(cr) > RD_PATCH_THIN * (alpha + gamma))) return 0.0;
    double j0, j1;
    edge_root_integrals(alpha, 2 * (a[0] * e[0] + a[1] * e[1]), gamma, 4 * cr * cr, &j0, &j1);
    double ga = gx * a[0] + gy * a[1], ge = gx * e[0] + gy * e[1];
    return cr * ((dc / 3 + ga / 4) * j0 + (ge / 4) * j1);
}

double rd_patch_torsion(const rd_poly2 *p, const double c[2], double d0, double gx, double gy)
{
    const double dc = d0 + gx * c[0] + gy * c[1];
    double sum = 0;
    for (int i = 0; i < p->n; i++) {
        const double *u = p->p[i], *v = p->p[i + 1 == p->n ? 0 : i + 1];
        const double a[2] = { u[0] - c[0], u[1] - c[1] }, e[2] = { v[0] - u[0], v[1] - u[1] };
        sum += fan_share(a, e, dc, gx, gy);
    }
    return sum;
}

static unsigned edge_hash(const double *lo, const double *hi)
{
    uint64_t h = 1469598103934665603ULL, w[4];
    memcpy(w, lo, 2 * sizeof *lo);
    memcpy(w + 2, hi, 2 * sizeof *hi);
    for (int k = 0; k < 4; k++) {
        h ^= w[k];
        h *= 1099511628211ULL;
        h ^= h >> 29;
    }
    return (unsigned)h;
}

/* Is (x0, y0) before (x1, y1) in lexicographic order? */
static int before(const double *p, const double *q)
{
    return p[0] < q[0] || (p[0] == q[0] && p[1] < q[1]);
}

double rd_patch_torsion_set(const rd_poly2 *pieces, int n, const double c[2], double d0, double gx,
                            double gy, rd_patch_scratch *sc)
{
    int ne = 0;
    for (int k = 0; k < n; k++) ne += pieces[k].n;
    int hcap = 16;
    while (hcap < 2 * ne) hcap *= 2;
    if (hcap > sc->cap) {
        int *slot = realloc(sc->slot, (size_t)hcap * sizeof *slot);
        int *cnt = slot ? realloc(sc->count, (size_t)hcap * sizeof *cnt) : NULL;
        const double(**ends)[2] = cnt ? realloc(sc->ends, (size_t)hcap * 2 * sizeof *ends) : NULL;
        if (slot) sc->slot = slot;
        if (cnt) sc->count = cnt;
        if (ends) sc->ends = ends;
        if (!ends) { /* no room: each piece on its own (the same integral, more work) */
            double sum = 0;
            for (int k = 0; k < n; k++) sum += rd_patch_torsion(&pieces[k], c, d0, gx, gy);
            return sum;
        }
        sc->cap = hcap;
    }
    for (int k = 0; k < hcap; k++) sc->slot[k] = -1;
    /* each edge once, as (lo, hi) in lexicographic order, with its direction count: an edge
       two pieces share runs both ways, and their fan triangles cancel exactly */
    int nu = 0;
    unsigned m = (unsigned)hcap - 1;
    for (int k = 0; k < n; k++)
        for (int i = 0; i < pieces[k].n; i++) {
            const double *u = pieces[k].p[i], *v = pieces[k].p[i + 1 == pieces[k].n ? 0 : i + 1];
            int fwd = before(u, v);
            const double *lo = fwd ? u : v, *hi = fwd ? v : u;
            unsigned q = edge_hash(lo, hi) & m;
            for (;; q = (q + 1) & m) {
                int e = sc->slot[q];
                if (e < 0) {
                    sc->slot[q] = nu;
                    sc->ends[2 * nu] = (const double(*)[2])lo;
                    sc->ends[2 * nu + 1] = (const double(*)[2])hi;
                    sc->count[nu++] = fwd ? 1 : -1;
                    break;
                }
                const double *elo = *sc->ends[2 * e], *ehi = *sc->ends[2 * e + 1];
                if (elo[0] == lo[0] && elo[1] == lo[1] && ehi[0] == hi[0] && ehi[1] == hi[1]) {
                    sc->count[e] += fwd ? 1 : -1;
                    break;
                }
            }
        }
    const double dc = d0 + gx * c[0] + gy * c[1];
    double sum = 0;
    for (int e = 0; e < nu; e++) {
        if (sc->count[e] == 0) continue;
        const double *lo = *sc->ends[2 * e], *hi = *sc->ends[2 * e + 1];
        const double a[2] = { lo[0] - c[0], lo[1] - c[1] }, d[2] = { hi[0] - lo[0], hi[1] - lo[1] };
        sum += sc->count[e] * fan_share(a, d, dc, gx, gy);
    }
    return sum;
}

/* The integral of (dc + gx X + gy Y)(X^2 + Y^2) over a counter-clockwise polygon, X, Y about
 * c (Green's theorem: the second and third area moments about c), and the largest |r - c| of
 * its vertices into *rmax. */
static double weighted_polar(const rd_poly2 *p, const double c[2], double dc, double gx, double gy,
                             double *rmax)
{
    double i2 = 0, x3 = 0, y3 = 0, x2y = 0, xy2 = 0;
    for (int i = 0; i < p->n; i++) {
        const double *u = p->p[i], *v = p->p[i + 1 == p->n ? 0 : i + 1];
        const double xi = u[0] - c[0], yi = u[1] - c[1], xj = v[0] - c[0], yj = v[1] - c[1];
        const double cr = xi * yj - xj * yi;
        *rmax = rd_max(*rmax, xi * xi + yi * yi);
        i2 += (xi * xi + xi * xj + xj * xj + yi * yi + yi * yj + yj * yj) * cr;
        x3 += (xi * xi * xi + xi * xi * xj + xi * xj * xj + xj * xj * xj) * cr;
        y3 += (yi * yi * yi + yi * yi * yj + yi * yj * yj + yj * yj * yj) * cr;
        x2y += (xi * xi * (3 * yi + yj) + 2 * xi * xj * (yi + yj) + xj * xj * (yi + 3 * yj)) * cr;
        xy2 += (yi * yi * (3 * xi + xj) + 2 * yi * yj * (xi + xj) + yj * yj * (xi + 3 * xj)) * cr;
    }
    return dc * i2 / 12 + gx * (x3 / 20 + xy2 / 60) + gy * (x2y / 60 + y3 / 20);
}

double rd_patch_torsion_bound(const rd_poly2 *pieces, int n, const double c[2], double d0,
                              double gx, double gy)
{
    const double dc = d0 + gx * c[0] + gy * c[1];
    double w = 0, r2 = 0;
    for (int k = 0; k < n; k++) w += weighted_polar(&pieces[k], c, dc, gx, gy, &r2);
    return r2 > 0 && w > 0 ? (1 - RD_PATCH_BOUND_SLACK) * w / sqrt(r2) : 0.0;
}

double rd_patch_torsion_disc(const rd_poly2 *pieces, int n, double f, double d0, double gx,
                             double gy)
{
    double dmax = 0;
    for (int k = 0; k < n; k++)
        for (int i = 0; i < pieces[k].n; i++)
            dmax = rd_max(dmax, d0 + gx * pieces[k].p[i][0] + gy * pieces[k].p[i][1]);
    return rd_patch_torsion_disc_of(f, dmax);
}

double rd_patch_torsion_disc_of(double f, double dmax)
{
    if (!(f > 0 && dmax > 0)) return 0.0;
    const double q = sqrt(f / (3 * M_PI * dmax));
    return (1 - RD_PATCH_BOUND_SLACK) * (2.0 / 3.0) * q * f;
}

void rd_patch_load_from(const rd_moments *m, double d0, double gx, double gy, rd_patch_load *out)
{
    *out = (rd_patch_load){ 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    if (!(m->a > 0)) return;
    out->area = m->a;
    out->cx = m->sx / m->a;
    out->cy = m->sy / m->a;
    out->polar = m->sxx + m->syy - m->a * (out->cx * out->cx + out->cy * out->cy);
    out->f = d0 * m->a + gx * m->sx + gy * m->sy;
    out->mx = d0 * m->sx + gx * m->sxx + gy * m->sxy;
    out->my = d0 * m->sy + gx * m->sxy + gy * m->syy;
    out->e2 = d0 * d0 * m->a + 2 * d0 * (gx * m->sx + gy * m->sy) + gx * gx * m->sxx +
              2 * gx * gy * m->sxy + gy * gy * m->syy;
}

void rd_patch_load_of(const rd_poly2 *p, double d0, double gx, double gy, rd_patch_load *out,
                      rd_poly2 *comp)
{
    *out = (rd_patch_load){ 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    rd_poly2 buf, *q = comp ? comp : &buf;
    if (!rd_patch_clip_half(p, gx, gy, d0, q)) return;
    rd_moments m;
    rd_patch_moments(q, &m);
    rd_patch_load_from(&m, d0, gx, gy, out);
    if (!(out->area > 0)) return;
    const double c[2] = { out->cx, out->cy };
    out->tors = rd_patch_torsion(q, c, d0, gx, gy);
}

int rd_patch_faces(const double o[3], const double e1[3], const double e2[3], const double n[3],
                   const rd_poly2 *s, const double (*rv)[3], int nr, const double u[3], double dR,
                   rd_poly2 *patch, double dep[3])
{
    patch->n = 0;
    const double nu = rd_dot(n, u);
    if (!(nu < 0) || nr > RD_PATCH_MAX || nr < 3) return 0;
    /* R's vertices projected along u onto S's plane n . x = n . o: q + lambda u, lambda = n . (o -
       q) / (n . u); R runs counter-clockwise about u, so clockwise about n: taken in reverse */
    rd_poly2 r;
    r.n = nr;
    for (int i = 0; i < nr; i++) {
        const double *q = rv[nr - 1 - i];
        double dq[3] = { q[0] - o[0], q[1] - o[1], q[2] - o[2] };
        double lambda = -rd_dot(n, dq) / nu;
        for (int k = 0; k < 3; k++) dq[k] += lambda * u[k];
        r.p[i][0] = rd_dot(dq, e1);
        r.p[i][1] = rd_dot(dq, e2);
    }
    /* the depth of S's point o + x e1 + y e2 behind R's plane: dR - u . o - x u . e1 - y u . e2 */
    dep[0] = dR - rd_dot(u, o);
    dep[1] = -rd_dot(u, e1);
    dep[2] = -rd_dot(u, e2);
    return rd_patch_clip(s, &r, patch);
}
