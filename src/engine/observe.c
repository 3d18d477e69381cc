/* rockdem — observers (include/rockdem/observer.h): the scene is sampled every output
 * interval of shaking, and each sample, event and the summary go to whoever registered. The
 * engine itself writes nothing; the HDF5 file is io/output.c's observer.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "base/vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int rd_sim_add_observer(rd_sim *s, const rd_observer *obs, rd_error *err)
{
    if (s->nobs == s->cap_obs) {
        int cap = s->cap_obs ? 2 * s->cap_obs : 4;
        rd_observer *o = realloc(s->obs, (size_t)cap * sizeof *o);
        if (!o) return rd_error_set(err, "out of memory adding an observer");
        s->obs = o;
        s->cap_obs = cap;
    }
    s->obs[s->nobs++] = *obs;
    return 0;
}

/* An observer's callback failed: the run stops with its message (the first failure wins). */
static void failed(rd_sim *s, const rd_error *err)
{
    if (s->status == RD_STATUS_IO_ERROR) return;
    snprintf(s->errmsg, sizeof s->errmsg, "%s", err->msg);
    s->status = RD_STATUS_IO_ERROR;
}

void rd_observe_begin(rd_sim *s)
{
    rd_error err;
    for (int k = 0; k < s->nobs && s->status == RD_STATUS_DONE; k++)
        if (s->obs[k].begin && s->obs[k].begin(s->obs[k].user, s, &err)) failed(s, &err);
}

/* The free bodies' state now into s->obuf; also advances the monitors' rotation split (its
 * unwrapped twist and rocking extremes are sampled here, observers or not). */
static void take_sample(rd_sim *s, rd_sample *smp)
{
    int nf = s->nfree;
    double *pos = s->obuf, *quat = pos + 3 * nf, *vel = quat + 4 * nf, *ang = vel + 3 * nf,
           *tilt = ang + 3 * nf, *rot = tilt + nf;
    for (int k = 0; k < nf; k++) {
        int i = s->free_body[k];
        double Lm[3], lb[3];
        for (int j = 0; j < 3; j++) {
            pos[3 * k + j] = s->x[i][j];
            vel[3 * k + j] = 0.5 * (s->v[i][j] + s->v_old[i][j]);
            Lm[j] = 0.5 * (s->L[i][j] + s->L_old[i][j]);
        }
        rd_mat_tvec(s->R[i], Lm, lb);
        for (int j = 0; j < 3; j++) lb[j] /= s->inertia[i][j];
        rd_mat_vec(s->R[i], lb, ang + 3 * k);
        memcpy(quat + 4 * k, s->q[i], 4 * sizeof(double));
        double qc[4] = { s->watch[k].q_ref[0], -s->watch[k].q_ref[1], -s->watch[k].q_ref[2],
                         -s->watch[k].q_ref[3] },
               dq[4], z[3];
        rd_quat_mul(s->q[i], qc, dq);
        rd_quat_rotate(dq, (double[3]){ 0, 0, 1 }, z);
        tilt[k] = atan2(hypot(z[0], z[1]), z[2]);
        rd_monitor_rotation(s, k, rot + 3 * k);
    }
    *smp = (rd_sample){ .time = s->t,
                        .nbodies = nf,
                        .position = pos,
                        .quaternion = quat,
                        .velocity = vel,
                        .angular_velocity = ang,
                        .tilt = tilt,
                        .rotation = rot };
    memcpy(smp->ground_acc, s->ag, sizeof s->ag);
    memcpy(smp->ground_vel, s->vg, sizeof s->vg);
    memcpy(smp->ground_disp, s->dg, sizeof s->dg);
    memcpy(smp->energy, s->energy, sizeof s->energy);
}

int rd_observe_sample(rd_sim *s)
{
    rd_sample smp;
    rd_error err;
    int rc = 0;
    take_sample(s, &smp);
    for (; rc == 0 && s->nevent_written < s->nevent; s->nevent_written++)
        for (int k = 0; k < s->nobs && rc == 0; k++)
            if (s->obs[k].event)
                rc = s->obs[k].event(s->obs[k].user, s, &s->event[s->nevent_written], &err);
    for (int k = 0; k < s->nobs && rc == 0; k++) {
        const rd_observer *o = &s->obs[k];
        if (o->sample && (o->every <= 1 || s->nsample % o->every == 0))
            rc = o->sample(o->user, s, &smp, &err);
    }
    s->nsample++;
    if (rc) failed(s, &err);
    return rc;
}

void rd_observe_end(rd_sim *s)
{
    rd_summary sum;
    rd_error err;
    /* the final state, which also completes the rotation extremes; should an observer fail
       on it, the others still end (a run file keeps its summary, status io-error) */
    rd_observe_sample(s);
    rd_sim_summary(s, &sum);
    for (int k = 0; k < s->nobs; k++)
        if (s->obs[k].end && s->obs[k].end(s->obs[k].user, s, &sum, &err)) {
            failed(s, &err);
            return;
        }
}

void rd_observe_release(rd_sim *s)
{
    for (int k = 0; k < s->nobs; k++)
        if (s->obs[k].release) s->obs[k].release(s->obs[k].user);
    free(s->obs);
}

/* ---- what observers may ask ---- */

int rd_sim_body_count(const rd_sim *s, int *nfixed)
{
    if (nfixed) *nfixed = s->nb - s->nfree;
    return s->nfree;
}

const rd_scenario *rd_sim_scenario(const rd_sim *s) { return &s->sc; }

/* Extents of body i along ground x, y, z in orientation q. */
static void extents(const rd_poly *p, const double q[4], double size[3])
{
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int v = 0; v < p->nv; v++) {
        double r[3];
        rd_quat_rotate(q, p->v[v], r);
        for (int j = 0; j < 3; j++) {
            lo[j] = rd_min(lo[j], r[j]);
            hi[j] = rd_max(hi[j], r[j]);
        }
    }
    for (int j = 0; j < 3; j++) size[j] = p->nv ? hi[j] - lo[j] : 0;
}

/* Body index of info index k (free bodies first, then fixed ones in scenario order). */
static int body_of(const rd_sim *s, int k)
{
    if (k < s->nfree) return s->free_body[k];
    for (int i = 0, n = s->nfree; i < s->nb; i++)
        if (s->fixed[i] && n++ == k) return i;
    return -1;
}

void rd_sim_body_info(const rd_sim *s, int k, rd_body_info *out)
{
    int i = body_of(s, k);
    const rd_poly *p = &s->poly[i];
    const rd_watch *w = k < s->nfree ? &s->watch[k] : NULL;
    int rested = w && s->rested;
    *out = (rd_body_info){ .name = s->sc.bodies[i].name,
                           .fixed = s->fixed[i],
                           .mass = s->mass[i],
                           .alpha = rested ? w->sum->alpha : 0,
                           .nvert = p->nv,
                           .vertices = &p->v[0][0],
                           .ntri = p->ntri,
                           .triangles = &p->tri[0][0],
                           .nprec = rested ? RD_NPREC : 0,
                           .precariousness = w ? &w->prec[0][0] : NULL };
    memcpy(out->position, s->x[i], sizeof out->position);
    memcpy(out->quaternion, s->q[i], sizeof out->quaternion);
    memcpy(out->inertia, s->inertia[i], sizeof out->inertia);
    extents(p, rested ? w->q_ref : s->q[i], out->size); /* at rest: before any initial tilt */
}
