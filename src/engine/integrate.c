/* rockdem — rigid-body time integration: explicit central differences (leapfrog).
 *
 * Translation: v(n+1/2) = v(n-1/2) + F(n)/m dt,  x(n+1) = x(n) + v(n+1/2) dt.
 * Rotation: the angular momentum L (ground frame, about the centre of mass) is kicked by the
 * torque, L(n+1/2) = L(n-1/2) + T(n) dt, which is exact for torque-free motion; the orientation
 * follows dq/dt = 1/2 w q with w = R I^-1 R^T L evaluated at the mid-step orientation (one
 * fixed-point iteration of the implicit midpoint rule, second order, as Omelyan's leapfrog).
 * This solves Euler's equations with the full inertia tensor, gyroscopic terms included.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "engine/workers.h"
#include "base/assert.h"
#include "base/vec.h"

/* w = R diag(1/I) R^T L */
static void omega_from(const double R[9], const double I[3], const double L[3], double w[3])
{
    double lb[3];
    rd_mat_tvec(R, L, lb);
    lb[0] /= I[0];
    lb[1] /= I[1];
    lb[2] /= I[2];
    rd_mat_vec(R, lb, w);
}

/* Rotation matrix, world vertices and world face planes of body i (rd_body_refresh; static, so
 * that its two copies stay in this file: RD_HOT). */
RD_HOT static void body_geometry(rd_sim *s, int i)
{
    rd_quat_to_mat(s->q[i], s->R[i]);
    const rd_poly *p = &s->poly[i];
    double R[9], x[3]; /* in locals: the stores below cannot alias them */
    for (int k = 0; k < 9; k++) R[k] = s->R[i][k];
    rd_copy3(s->x[i], x);
    double(*wv)[3] = s->wv + s->vert0[i], (*wn)[3] = s->wn + s->face0[i], *wd = s->wd + s->face0[i];
    for (int k = 0; k < p->nv; k++) {
        rd_mat_vec(R, p->v[k], wv[k]);
        rd_axpy(1.0, x, wv[k]);
    }
    for (int f = 0; f < p->nf; f++) {
        rd_mat_vec(R, p->fn[f], wn[f]);
        wd[f] = p->fd[f] + rd_dot(wn[f], x);
    }
}

void rd_body_refresh(rd_sim *s, int i) { body_geometry(s, i); }

/* n points' ground-frame coordinates: w[c][k] = R's row c . (bx, by, bz)[k] + x[c], rd_mat_vec's
 * rows then rd_axpy's 1.0 * x (the same expressions: the same bits); over contiguous coordinates
 * the loop vectorises, and each body-frame coordinate is loaded once for the three rows. */
RD_HOT static void transform_points(int n, const double *restrict bx, const double *restrict by,
                                    const double *restrict bz, const double R[9], const double x[3],
                                    double *restrict wx, double *restrict wy, double *restrict wz)
{
    const double r0 = R[0], r1 = R[1], r2 = R[2], r3 = R[3], r4 = R[4], r5 = R[5], r6 = R[6],
                 r7 = R[7], r8 = R[8];
    const double x0 = x[0], x1 = x[1], x2 = x[2];
    for (int k = 0; k < n; k++) {
        const double b0 = bx[k], b1 = by[k], b2 = bz[k];
        wx[k] = r0 * b0 + r1 * b1 + r2 * b2 + 1.0 * x0;
        wy[k] = r3 * b0 + r4 * b1 + r5 * b2 + 1.0 * x1;
        wz[k] = r6 * b0 + r7 * b1 + r8 * b2 + 1.0 * x2;
    }
}

/* What a step needs of non-convex body i: its rotation and candidate-face vertices (a scanned
 * rock: a few hundred of its thousands of vertices), from their contiguous body-frame
 * coordinates (rd_sim.cv_body) into their contiguous ground-frame ones (rd_sim.cv_world, which
 * the contact reads: contact.c, vertex_distances). It is never a contact target, so its face
 * planes are not needed; the contact finds a candidate face's normal from the rotation when a
 * point needs it (contact.c: owner_normal), and the broad phase transforms the hull vertices
 * only when it rebuilds the body's box (pairs.c). Its world vertices (rd_sim.wv) are left as
 * rd_bodies_refresh found them. */
static void body_refresh_contact(rd_sim *s, int i)
{
    rd_quat_to_mat(s->q[i], s->R[i]);
    const double *R = s->R[i], *x = s->x[i];
    const int k0 = s->cv0[i], n = s->cv0[i + 1] - k0, ncv = s->cv0[s->nb];
    const double *bx = s->cv_body + k0, *by = bx + ncv, *bz = by + ncv;
    double *wx = s->cv_world + k0, *wy = wx + ncv, *wz = wy + ncv;
    transform_points(n, bx, by, bz, R, x, wx, wy, wz);
}

/* World geometry of every free body (fixed bodies never move in the ground frame), a
 * non-convex one's candidate vertices into rd_sim.cv_world too (the same expressions). */
void rd_bodies_refresh(rd_sim *s)
{
    for (int i = 0; i < s->nb; i++) {
        if (s->fixed[i]) continue;
        rd_body_refresh(s, i);
        if (!s->convex[i]) body_refresh_contact(s, i);
    }
}

/* The body loops below touch body i alone, so they run on the run's threads (workers.h) where
 * the scene has enough bodies, with the same bits. */

static void refresh_step_body(rd_sim *s, int i)
{
    if (!s->fixed[i]) s->convex[i] ? rd_body_refresh(s, i) : body_refresh_contact(s, i);
}

/* World geometry of every free body for one step. */
void rd_bodies_refresh_step(rd_sim *s)
{
    const int n = rd_threads_for(s, s->nb);
    if (n > 1) {
        RD_OMP(omp parallel for schedule(static) num_threads(n))
        for (int i = 0; i < s->nb; i++) refresh_step_body(s, i);
    } else {
        for (int i = 0; i < s->nb; i++) refresh_step_body(s, i);
    }
}

static void kick_body(rd_sim *s, int i)
{
    if (s->fixed[i]) return;
    RD_ASSERT(s->mass[i] > 0.0);
    double im = 1.0 / s->mass[i];
    rd_copy3(s->v[i], s->v_old[i]);
    rd_copy3(s->L[i], s->L_old[i]);
    rd_axpy(im * s->dt, s->f[i], s->v[i]);
    rd_axpy(s->dt, s->tq[i], s->L[i]);
}

void rd_integrate_kick(rd_sim *s)
{
    const int n = rd_threads_for(s, s->nb);
    if (n > 1) {
        RD_OMP(omp parallel for schedule(static) num_threads(n))
        for (int i = 0; i < s->nb; i++) kick_body(s, i);
    } else {
        for (int i = 0; i < s->nb; i++) kick_body(s, i);
    }
}

static void drift_body(rd_sim *s, int i)
{
    const double dt = s->dt;
    if (s->fixed[i]) return;
    rd_axpy(dt, s->v[i], s->x[i]);
    double w[3], dq[4], qh[4], Rh[9], phi[3];
    omega_from(s->R[i], s->inertia[i], s->L[i], w);
    for (int k = 0; k < 3; k++) phi[k] = 0.5 * dt * w[k];
    rd_quat_from_rotvec(phi, dq);
    rd_quat_mul(dq, s->q[i], qh);
    rd_quat_to_mat(qh, Rh);
    omega_from(Rh, s->inertia[i], s->L[i], s->w[i]); /* w at n+1/2 */
    for (int k = 0; k < 3; k++) phi[k] = dt * s->w[i][k];
    rd_quat_from_rotvec(phi, dq);
    rd_quat_mul(dq, s->q[i], qh);
    rd_quat_normalize(qh);
    RD_ASSERT(fabs(qh[0] * qh[0] + qh[1] * qh[1] + qh[2] * qh[2] + qh[3] * qh[3] - 1.0) < 1e-12);
    for (int k = 0; k < 4; k++) s->q[i][k] = qh[k];
}

void rd_integrate_drift(rd_sim *s)
{
    const int n = rd_threads_for(s, s->nb);
    if (n > 1) {
        RD_OMP(omp parallel for schedule(static) num_threads(n))
        for (int i = 0; i < s->nb; i++) drift_body(s, i);
    } else {
        for (int i = 0; i < s->nb; i++) drift_body(s, i);
    }
}

void rd_body_set_angular_velocity(rd_sim *s, int i, const double w[3])
{
    double R[9], wb[3];
    rd_quat_to_mat(s->q[i], R);
    rd_mat_tvec(R, w, wb);
    for (int k = 0; k < 3; k++) wb[k] *= s->inertia[i][k];
    rd_mat_vec(R, wb, s->L[i]);
    rd_copy3(w, s->w[i]);
}
