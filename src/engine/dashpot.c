/* rockdem — the surface model's normal dashpot, integrated implicitly (dashpot.h).
 *
 * Explicitly (the pressure from the last half step's velocities) a dashpot of ratio zeta
 * shortens the stable step by sqrt(1 + zeta^2) - zeta, and a patch's dashpot that makes a
 * rocking block's landing edge plastic (zeta near 3: Housner's restitution) took a step 19
 * times shorter. Taken at the step's mean velocity (Crank-Nicolson in the damping, leapfrog in
 * the springs) the scheme is stable for omega dt < 2 whatever the damping (the one-degree-of-
 * freedom amplification matrix has spectral radius 1 at most), and the dashpots' work is the
 * quadratic form dt xi . D xi, xi the velocities the kick's mean gives (booked in the
 * kinetic energy's own convention: work(), below).
 * Folder engine/ owns the simulation; it may call base/, contact/, geometry/, records/ and
 * scenario/, never io/ or cli/.
 */
#include "engine/dashpot.h"
#include "base/vec.h"
#include "base/grow.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A new patch's dashpot is merged into one of the pair's last this many (same direction and
 * ratio): a few directions a pair (a convex body's faces), and a bounded search where each
 * patch has its own (terrain's faces against a rock). */
#define RD_DASHPOT_SCAN   8
#define RD_DASHPOT_SWEEPS 200 /* most Gauss-Seidel sweeps of a stack's solve */
#define RD_DASHPOT_TOL                                                                             \
    1e-14 /* a sweep that moves no body's velocity by more than this
                                   fraction of its size (|v| + |w| radius) ends the solve */

rd_dashpot *rd_dashpot_of(const rd_sim *s, rd_dashpots *d, int first, int i, int r, double c,
                          const double u[3])
{
    const int a = s->fixed[i] ? -1 : i, b = s->fixed[r] ? -1 : r;
    const int k0 = d->n - RD_DASHPOT_SCAN > first ? d->n - RD_DASHPOT_SCAN : first;
    for (int k = k0; k < d->n; k++) {
        rd_dashpot *e = &d->e[k];
        if (e->a == a && e->b == b && e->c == c && e->u[0] == u[0] && e->u[1] == u[1] &&
            e->u[2] == u[2])
            return e;
    }
    if (rd_grow((void **)&d->e, &d->cap, d->n + 1, sizeof *d->e)) return NULL;
    rd_dashpot *e = &d->e[d->n++];
    memset(e, 0, sizeof *e);
    e->a = a;
    e->b = b;
    e->c = c;
    rd_copy3(u, e->u);
    /* body i: (u, 0) for 1, (0, e_l x u) for p_l; body r the negatives, its lever p + x_i - x_r */
    double lever[3], t[3];
    for (int k = 0; k < 3; k++) lever[k] = s->x[i][k] - s->x[r][k];
    for (int sd = 0; sd < 2; sd++) {
        const double sg = sd ? -1.0 : 1.0;
        for (int p = 0; p < 3; p++) e->g[sd][0][p] = sg * u[p];
        if (sd) {
            rd_cross(lever, u, t);
            for (int p = 0; p < 3; p++) e->g[sd][0][3 + p] = -t[p];
        }
        for (int l = 0; l < 3; l++) {
            const double el[3] = { l == 0, l == 1, l == 2 };
            rd_cross(el, u, t);
            for (int p = 0; p < 3; p++) e->g[sd][1 + l][3 + p] = sg * t[p];
        }
    }
    return e;
}

void rd_dashpot_add_region(rd_dashpot *e, const double m2[6], const double O[3], const double E1[3],
                           const double E2[3])
{
    const double a = m2[0], sx = m2[1], sy = m2[2], sxx = m2[3], sxy = m2[4], syy = m2[5];
    double *m = e->m;
    m[0] += a;
    for (int k = 0; k < 3; k++) m[1 + k] += a * O[k] + sx * E1[k] + sy * E2[k];
    int q = 4;
    for (int k = 0; k < 3; k++)
        for (int l = k; l < 3; l++)
            m[q++] += a * O[k] * O[l] + sx * (O[k] * E1[l] + E1[k] * O[l]) +
                      sy * (O[k] * E2[l] + E2[k] * O[l]) + sxx * E1[k] * E1[l] +
                      sxy * (E1[k] * E2[l] + E2[k] * E1[l]) + syy * E2[k] * E2[l];
}

void rd_dashpots_free(rd_dashpots *d)
{
    free(d->e);
    free(d->first);
    free(d->list);
    free(d->xi);
    free(d->rhs);
    free(d->chol);
    free(d->fd);
    free(d->fd_prev);
    memset(d, 0, sizeof *d);
}

/* The moments as the symmetric 4 x 4 matrix of the basis (1, p_x, p_y, p_z). */
static void moment_matrix(const double m[RD_DASHPOT_MOMENTS], double M[4][4])
{
    int q = 0;
    for (int k = 0; k < RD_DASHPOT_BASIS; k++)
        for (int l = k; l < RD_DASHPOT_BASIS; l++) M[k][l] = M[l][k] = m[q++];
}

/* The rates w_k = sum over the free sides of g[side][k] . xi (k: 1, p_x, p_y, p_z), m/s. */
static void rates(const rd_dashpot *e, double (*xi)[6], double w[RD_DASHPOT_BASIS])
{
    const int body[2] = { e->a, e->b };
    for (int k = 0; k < RD_DASHPOT_BASIS; k++) {
        w[k] = 0;
        for (int sd = 0; sd < 2; sd++)
            if (body[sd] >= 0)
                for (int p = 0; p < 6; p++) w[k] += e->g[sd][k][p] * xi[body[sd]][p];
    }
}

/* Cholesky factor, packed lower triangle by rows (21 entries), of the symmetric positive
 * definite 6 x 6 matrix A (row-major). */
static void chol6(const double A[36], double L[21])
{
    for (int i = 0; i < 6; i++)
        for (int j = 0; j <= i; j++) {
            double sum = A[6 * i + j];
            for (int k = 0; k < j; k++) sum -= L[i * (i + 1) / 2 + k] * L[j * (j + 1) / 2 + k];
            L[i * (i + 1) / 2 + j] = i == j ? sqrt(sum) : sum / L[j * (j + 1) / 2 + j];
        }
}

/* x = A^-1 b from the packed Cholesky factor L. */
static void chol6_solve(const double L[21], const double b[6], double x[6])
{
    double y[6];
    for (int i = 0; i < 6; i++) {
        double sum = b[i];
        for (int k = 0; k < i; k++) sum -= L[i * (i + 1) / 2 + k] * y[k];
        y[i] = sum / L[i * (i + 1) / 2 + i];
    }
    for (int i = 5; i >= 0; i--) {
        double sum = y[i];
        for (int k = i + 1; k < 6; k++) sum -= L[k * (k + 1) / 2 + i] * x[k];
        x[i] = sum / L[i * (i + 1) / 2 + i];
    }
}

int rd_dashpots_reserve(const rd_sim *s, rd_dashpots *d)
{
    if (s->nb <= d->cap_x) return 0;
    void *xi = realloc(d->xi, (size_t)s->nb * sizeof *d->xi);
    if (xi) d->xi = xi;
    void *rhs = realloc(d->rhs, (size_t)s->nb * sizeof *d->rhs);
    if (rhs) d->rhs = rhs;
    void *ch = realloc(d->chol, (size_t)s->nb * sizeof *d->chol);
    if (ch) d->chol = ch;
    void *fd = realloc(d->fd, (size_t)s->nb * sizeof *d->fd);
    if (fd) d->fd = fd;
    void *fp = realloc(d->fd_prev, (size_t)s->nb * sizeof *d->fd_prev);
    if (fp) {
        d->fd_prev = fp;
        memset(d->fd_prev + d->cap_x, 0, (size_t)(s->nb - d->cap_x) * sizeof *d->fd_prev);
    }
    if (!xi || !rhs || !ch || !fd || !fp) return -1;
    d->cap_x = s->nb;
    return 0;
}

/* Per body, the dashpots it takes part in (CSR; list[2 n ..) is the fill scratch). */
static int body_lists(const rd_sim *s, rd_dashpots *d)
{
    if (rd_grow((void **)&d->first, &d->cap_b, s->nb + 1, sizeof *d->first) ||
        rd_grow((void **)&d->list, &d->cap_l, 2 * d->n + s->nb, sizeof *d->list) ||
        rd_dashpots_reserve(s, d))
        return -1;
    memset(d->first, 0, (size_t)(s->nb + 1) * sizeof *d->first);
    for (int k = 0; k < d->n; k++) {
        if (d->e[k].a >= 0) d->first[d->e[k].a + 1]++;
        if (d->e[k].b >= 0) d->first[d->e[k].b + 1]++;
    }
    for (int i = 0; i < s->nb; i++) d->first[i + 1] += d->first[i];
    int *fill = d->list + 2 * d->n;
    for (int i = 0; i < s->nb; i++) fill[i] = d->first[i];
    for (int k = 0; k < d->n; k++) {
        if (d->e[k].a >= 0) d->list[fill[d->e[k].a]++] = k;
        if (d->e[k].b >= 0) d->list[fill[d->e[k].b]++] = k;
    }
    return 0;
}

/* Body i's system: rhs = M xi(n-1/2) + dt F / 2 and the factor of M + dt D_ii / 2; xi starts at
 * the velocities the kick would give without the dashpots' forces (their mean). */
static void body_system(rd_sim *s, rd_dashpots *d, int i)
{
    const double dt = s->dt, m = s->mass[i], *R = s->R[i], *I = s->inertia[i];
    double A[36] = { 0 };
    for (int k = 0; k < 3; k++) {
        A[6 * k + k] = m;
        d->rhs[i][k] = m * s->v[i][k] + 0.5 * dt * s->f[i][k];
        d->rhs[i][3 + k] = s->L[i][k] + 0.5 * dt * s->tq[i][k];
        for (int l = 0; l < 3; l++) /* ground-frame inertia R diag(I) R^T */
            A[6 * (3 + k) + 3 + l] = R[3 * k] * I[0] * R[3 * l] +
                                     R[3 * k + 1] * I[1] * R[3 * l + 1] +
                                     R[3 * k + 2] * I[2] * R[3 * l + 2];
    }
    for (int q = d->first[i]; q < d->first[i + 1]; q++) {
        const rd_dashpot *e = &d->e[d->list[q]];
        const int sd = e->a == i ? 0 : 1;
        double M[RD_DASHPOT_BASIS][RD_DASHPOT_BASIS], H[RD_DASHPOT_BASIS][6];
        moment_matrix(e->m, M);
        for (int k = 0; k < RD_DASHPOT_BASIS; k++)
            for (int p = 0; p < 6; p++) {
                H[k][p] = 0;
                for (int l = 0; l < RD_DASHPOT_BASIS; l++) H[k][p] += M[k][l] * e->g[sd][l][p];
            }
        for (int p = 0; p < 6; p++)
            for (int r = 0; r < 6; r++) {
                double gh = 0;
                for (int k = 0; k < RD_DASHPOT_BASIS; k++) gh += e->g[sd][k][p] * H[k][r];
                A[6 * p + r] += 0.5 * dt * e->c * gh;
            }
    }
    chol6(A, d->chol[i]);
    chol6_solve(d->chol[i], d->rhs[i], d->xi[i]);
}

/* One Gauss-Seidel update of body i: its own block solved against the others' current xi.
 * Returns the change relative to the velocity's size. */
static double body_update(rd_sim *s, rd_dashpots *d, int i)
{
    double b[6], x[6];
    memcpy(b, d->rhs[i], sizeof b);
    for (int q = d->first[i]; q < d->first[i + 1]; q++) {
        const rd_dashpot *e = &d->e[d->list[q]];
        const int sd = e->a == i ? 0 : 1, o = sd ? e->a : e->b;
        if (o < 0) continue;
        double w[RD_DASHPOT_BASIS] = { 0, 0, 0, 0 }, M[RD_DASHPOT_BASIS][RD_DASHPOT_BASIS];
        for (int k = 0; k < RD_DASHPOT_BASIS; k++)
            for (int p = 0; p < 6; p++) w[k] += e->g[1 - sd][k][p] * d->xi[o][p];
        moment_matrix(e->m, M);
        for (int k = 0; k < RD_DASHPOT_BASIS; k++) {
            const double h = M[k][0] * w[0] + M[k][1] * w[1] + M[k][2] * w[2] + M[k][3] * w[3];
            for (int p = 0; p < 6; p++) b[p] -= 0.5 * s->dt * e->c * e->g[sd][k][p] * h;
        }
    }
    chol6_solve(d->chol[i], b, x);
    const double r = s->poly[i].radius;
    double dv = 0, size = 0;
    for (int k = 0; k < 3; k++) {
        dv = fmax(dv, fabs(x[k] - d->xi[i][k]) + r * fabs(x[3 + k] - d->xi[i][3 + k]));
        size = fmax(size, fabs(x[k]) + r * fabs(x[3 + k]));
    }
    memcpy(d->xi[i], x, sizeof x);
    return size > 0 ? dv / size : dv;
}

/* w = R diag(1/I) R^T x: the ground-frame inverse inertia of body i at t(n) times x. */
static void inverse_inertia(const rd_sim *s, int i, const double x[3], double w[3])
{
    double b[3];
    rd_mat_tvec(s->R[i], x, b);
    for (int k = 0; k < 3; k++) b[k] /= s->inertia[i][k];
    rd_mat_vec(s->R[i], b, w);
}

/* The dashpots' work on body i over [t(n-1), t(n)], J, as the kinetic energy of energy.c counts
 * it (the product of the two half steps' momenta and velocities, with the inertia at t(n)): the
 * force at t(n) on v(n-1/2) and the torque on I(n)^-1 L(n-1/2), halved, plus the same halves
 * of the last step's force and torque (fd_prev keeps that torque as I(n-1)^-1 T(n-1));
 * engine/law.h rd_law_dashpot_work for one subcontact. The quadratic form dt xi . D xi at the
 * mean velocity is the same work summed over the run but for half of the last step's, a
 * first-order error at each sample (4 % of a dropped block's energy at zeta 1); the half-step
 * angular velocity s->w (the inertia at t(n-1/2)) in place of I(n)^-1 L left 7e-4 of a
 * rocking block's energy over three impacts at zeta 3.3. Keeps this step's halves in fd_prev. */
static double work(const rd_sim *s, rd_dashpots *d, int i)
{
    double wt[3];
    inverse_inertia(s, i, d->fd[i] + 3, wt);
    double e = 0;
    for (int p = 0; p < 3; p++)
        e -= 0.5 * s->dt *
             ((d->fd_prev[i][p] + d->fd[i][p]) * s->v[i][p] +
              (d->fd_prev[i][3 + p] + wt[p]) * s->L[i][p]);
    for (int p = 0; p < 3; p++) {
        d->fd_prev[i][p] = d->fd[i][p];
        d->fd_prev[i][3 + p] = wt[p];
    }
    return e;
}

int rd_dashpot_solve(rd_sim *s, rd_dashpots *d)
{
    if (d->n == 0 && !d->acted) return 0;
    if (body_lists(s, d)) return -1;
    int coupled = 0;
    for (int k = 0; k < d->n; k++) coupled |= d->e[k].a >= 0 && d->e[k].b >= 0;
    for (int i = 0; i < s->nb; i++)
        if (d->first[i + 1] > d->first[i]) body_system(s, d, i);
    for (int sweep = 0; coupled && sweep < RD_DASHPOT_SWEEPS; sweep++) {
        double change = 0;
        for (int i = 0; i < s->nb; i++)
            if (d->first[i + 1] > d->first[i]) change = fmax(change, body_update(s, d, i));
        if (change <= RD_DASHPOT_TOL) break;
    }
    memset(d->fd, 0, (size_t)s->nb * sizeof *d->fd);
    for (int k = 0; k < d->n; k++) { /* the generalized forces -D xi */
        const rd_dashpot *e = &d->e[k];
        double w[RD_DASHPOT_BASIS], M[RD_DASHPOT_BASIS][RD_DASHPOT_BASIS], h[RD_DASHPOT_BASIS];
        rates(e, d->xi, w);
        moment_matrix(e->m, M);
        for (int l = 0; l < RD_DASHPOT_BASIS; l++)
            h[l] = M[l][0] * w[0] + M[l][1] * w[1] + M[l][2] * w[2] + M[l][3] * w[3];
        const int body[2] = { e->a, e->b };
        for (int sd = 0; sd < 2; sd++) {
            if (body[sd] < 0) continue;
            for (int p = 0; p < 6; p++)
                d->fd[body[sd]][p] -= e->c * (e->g[sd][0][p] * h[0] + e->g[sd][1][p] * h[1] +
                                              e->g[sd][2][p] * h[2] + e->g[sd][3][p] * h[3]);
        }
    }
    for (int i = 0; i < s->nb; i++) {
        if (s->fixed[i]) continue;
        s->e_damp += work(s, d, i);
        for (int p = 0; p < 3; p++) {
            s->f[i][p] += d->fd[i][p];
            s->tq[i][p] += d->fd[i][3 + p];
        }
    }
    d->acted = d->n > 0;
    d->n = 0;
    return 0;
}
