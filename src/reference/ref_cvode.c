/* rockdem — hybrid ODE driver on SUNDIALS CVODE (Adams–Moulton, Newton with a dense linear
 * solver) for the reference solvers, plus the result bookkeeping they share.
 * Every SUNDIALS 6.x / 7.x difference is kept in this file.
 * Folder reference/ owns the rigid CVODE reference solvers (Housner, Kounadis); it may call
 * base/, records/, io/ and the public API.
 */
#include "reference/ref_cvode.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#if SUNDIALS_VERSION_MAJOR >= 7
#define RD_SUN_COMM_NULL SUN_COMM_NULL
#else
#define RD_SUN_COMM_NULL NULL
#endif

/* Restarts at one instant before the driver calls the model's switching chattering. */
#define RD_HYB_MAX_SAME_T 200

/* Events kept per run; a rigid stack settles (Zeno threshold) long before this. */
#define RD_REF_MAX_EVENTS 10000000

rd_ref_opts rd_ref_opts_default(void)
{
    rd_ref_opts o;
    memset(&o, 0, sizeof o);
    o.t_end = 5.0;
    o.dt_out = 1e-3;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.rest_factor = 1e-4;
    return o;
}

void rd_ref_result_init(rd_ref_result *res)
{
    memset(res, 0, sizeof *res);
    res->summary.overturn_joint = -1;
    res->summary.t_overturn = -1.0;
}

void rd_ref_result_free(rd_ref_result *res)
{
    if (!res) return;
    free(res->samples);
    free(res->events);
    res->samples = NULL;
    res->events = NULL;
    res->nsamples = res->cap_samples = 0;
    res->nevents = res->cap_events = 0;
}

/* Grow *arr (elements of size sz) so that one more fits. */
static int grow(void **arr, size_t *cap, size_t n, size_t sz, rd_error *err)
{
    if (n < *cap) return 0;
    size_t ncap = *cap ? 2 * *cap : 256;
    void *p = realloc(*arr, ncap * sz);
    if (!p) return rd_error_set(err, "reference solver: out of memory (%zu records)", ncap);
    *arr = p;
    *cap = ncap;
    return 0;
}

int rd_ref_push_sample(rd_ref_result *res, const rd_ref_sample *s, rd_error *err)
{
    void *p = res->samples;
    if (grow(&p, &res->cap_samples, res->nsamples, sizeof *s, err)) return -1;
    res->samples = p;
    res->samples[res->nsamples++] = *s;
    return 0;
}

int rd_ref_push_event(rd_ref_result *res, const rd_ref_event *e, rd_error *err)
{
    if (res->nevents >= RD_REF_MAX_EVENTS) /* a runaway event sequence, not physics */
        return rd_error_set(err, "reference solver: more than %d events by t = %.9g s",
                            RD_REF_MAX_EVENTS, e->t);
    void *p = res->events;
    if (grow(&p, &res->cap_events, res->nevents, sizeof *e, err)) return -1;
    res->events = p;
    res->events[res->nevents++] = *e;
    return 0;
}

int rd_ground_check(const rd_ground *gm, rd_error *err)
{
    if (gm->fn && !(gm->t_quiet > 0.0))
        return rd_error_set(err,
                            "ground motion: t_quiet must be > 0 (INFINITY if the motion "
                            "never ends), got %g",
                            gm->t_quiet);
    if (gm->nbreaks && !gm->breaks)
        return rd_error_set(err, "ground motion: %zu breaks but no array", gm->nbreaks);
    return 0;
}

void rd_ground_eval(const rd_ground *gm, double t, double *ug, double *vg)
{
    *ug = 0.0;
    *vg = 0.0;
    if (gm && gm->fn && !(t >= gm->t_quiet)) gm->fn(gm->ctx, t, ug, vg);
}

/* ---- CVODE session ------------------------------------------------------------------- */

typedef struct cv_session {
    SUNContext ctx;
    N_Vector y;
    SUNMatrix a;
    SUNLinearSolver ls;
    void *mem;
    const rd_hybrid *h;
    int cb_failed; /* a model callback returned -1 (message already in h->err) */
} cv_session;

static int cv_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *user)
{
    cv_session *s = user;
    if (s->h->rhs(s->h->sys, t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot))) {
        s->cb_failed = 1;
        return -1;
    }
    return 0;
}

static int cv_roots(sunrealtype t, N_Vector y, sunrealtype *g, void *user)
{
    cv_session *s = user;
    if (s->h->roots(s->h->sys, t, N_VGetArrayPointer(y), g)) {
        s->cb_failed = 1;
        return -1;
    }
    return 0;
}

#if SUNDIALS_VERSION_MAJOR < 7
/* Keep CVODE quiet: its messages come back through the return flag and rd_error. */
static void cv_silent(int code, const char *module, const char *fn, char *msg, void *data)
{
    (void)code, (void)module, (void)fn, (void)msg, (void)data;
}
#endif

static void cv_free(cv_session *s)
{
    if (s->mem) CVodeFree(&s->mem);
    if (s->ls) SUNLinSolFree(s->ls);
    if (s->a) SUNMatDestroy(s->a);
    if (s->y) N_VDestroy(s->y);
    if (s->ctx) SUNContext_Free(&s->ctx);
}

static int cv_create(cv_session *s, const rd_hybrid *h, const rd_ref_opts *o, rd_error *err)
{
    memset(s, 0, sizeof *s);
    s->h = h;
    if (SUNContext_Create(RD_SUN_COMM_NULL, &s->ctx))
        return rd_error_set(err, "CVODE: cannot create a SUNDIALS context");
    s->y = N_VNew_Serial(h->n, s->ctx);
    s->a = s->y ? SUNDenseMatrix(h->n, h->n, s->ctx) : NULL;
    s->ls = s->a ? SUNLinSol_Dense(s->y, s->a, s->ctx) : NULL;
    s->mem = s->ls ? CVodeCreate(CV_ADAMS, s->ctx) : NULL;
    if (!s->mem) return rd_error_set(err, "CVODE: cannot allocate the integrator (n = %d)", h->n);
    N_VConst(0.0, s->y);
    int f = CVodeInit(s->mem, cv_rhs, 0.0, s->y);
    f = f ? f : CVodeSetUserData(s->mem, s);
    f = f ? f : CVodeSStolerances(s->mem, o->rtol, o->atol);
    f = f ? f : CVodeSetLinearSolver(s->mem, s->ls, s->a);
    f = f ? f : CVodeSetMaxNumSteps(s->mem, 1000000L);
    f = f ? f : CVodeSetMaxStep(s->mem, h->hmax);
#if SUNDIALS_VERSION_MAJOR < 7
    f = f ? f : CVodeSetErrHandlerFn(s->mem, cv_silent, NULL);
#endif
    if (f) return rd_error_set(err, "CVODE: setup failed (flag %d)", f);
    return 0;
}

/* Restart at (t, y) with the current mode's root functions and a stop time. */
static int cv_restart(cv_session *s, double t, const double *y, double tstop, rd_error *err)
{
    int dirs[RD_HYB_MAXROOTS];
    int nr = s->h->nroots(s->h->sys, dirs);
    memcpy(N_VGetArrayPointer(s->y), y, (size_t)s->h->n * sizeof *y);
    int f = CVodeReInit(s->mem, t, s->y);
    f = f ? f : CVodeRootInit(s->mem, nr, nr ? cv_roots : NULL);
    if (!f && nr) {
        f = CVodeSetRootDirection(s->mem, dirs);
        f = f ? f : CVodeSetNoInactiveRootWarn(s->mem);
    }
    f = f ? f : CVodeSetStopTime(s->mem, tstop);
    f = f ? f : CVodeSetMaxStep(s->mem, s->h->hmax);
    if (f) return rd_error_set(err, "CVODE: restart at t = %.9g s failed (flag %d)", t, f);
    return 0;
}

/* ---- driver ---------------------------------------------------------------------------- */

/* First break strictly after t (with a relative guard), else t_end. */
static double next_break(const rd_ground *gm, double t, double t_end)
{
    double tb = t_end;
    double guard = 1e-13 * (1.0 + fabs(t));
    if (!gm) return tb;
    for (size_t i = 0; i < gm->nbreaks; i++)
        if (gm->breaks[i] > t + guard && gm->breaks[i] < tb) tb = gm->breaks[i];
    if (isfinite(gm->t_quiet) && gm->t_quiet > t + guard && gm->t_quiet < tb) tb = gm->t_quiet;
    return tb;
}

typedef struct drive {
    const rd_hybrid *h;
    const rd_ground *gm;
    cv_session cv;
    double t, t_end, dt_out;
    long k_out;  /* index of the next output time k * dt_out */
    int sampled; /* the last sample was taken at t */
} drive;

static double next_out(const drive *d)
{
    return d->dt_out > 0.0 ? (double)d->k_out * d->dt_out : INFINITY;
}

/* Output every pending time <= t (they coincide with t: called at output times only). */
static int emit_due(drive *d, double *y)
{
    while (next_out(d) <= d->t * (1.0 + 1e-15) + 1e-300) {
        if (d->h->sample(d->h->sys, d->t, y)) return -1;
        d->k_out++;
        d->sampled = 1;
    }
    return 0;
}

/* Integrate one smooth stretch up to tstop; returns an RD_HYB_* code or -1. */
static int run_stretch(drive *d, double tstop, double *y, rd_error *err)
{
    const rd_hybrid *h = d->h;
    int found[RD_HYB_MAXROOTS];
    for (;;) {
        double tout = fmin(next_out(d), tstop);
        sunrealtype tret;
        int f = CVode(d->cv.mem, tout, d->cv.y, &tret, CV_NORMAL);
        memcpy(y, N_VGetArrayPointer(d->cv.y), (size_t)h->n * sizeof *y);
        if (d->cv.cb_failed) return -1;
        if (f < 0)
            return rd_error_set(err, "CVODE failed at t = %.9g s (flag %d)", (double)tret, f);
        d->t = tret;
        d->sampled = 0;
        if (f == CV_ROOT_RETURN) {
            if (CVodeGetRootInfo(d->cv.mem, found))
                return rd_error_set(err, "CVODE: no root information at t = %.9g s", d->t);
            int rc = h->event(h->sys, d->t, y, found);
            if (rc != RD_HYB_GO) return rc;
            continue;
        }
        if (d->t >= tout && emit_due(d, y)) return -1;
        if (d->t >= tstop) return RD_HYB_RESTART;
    }
}

static int drive_loop(drive *d, double *y, rd_error *err)
{
    const rd_hybrid *h = d->h;
    double t_last = -1.0;
    int same = 0;
    for (;;) {
        int rc = h->settle(h->sys, d->t, y);
        if (rc < 0 || rc == RD_HYB_STOP) return rc;
        if (emit_due(d, y)) return -1;
        if (d->t >= d->t_end) return RD_HYB_STOP;
        same = d->t <= t_last + 1e-13 * (1.0 + fabs(d->t)) ? same + 1 : 0;
        if (same > RD_HYB_MAX_SAME_T)
            return rd_error_set(err, "reference solver: mode switching chatters at t = %.9g s",
                                d->t);
        t_last = d->t;
        double tstop = next_break(d->gm, d->t, d->t_end);
        if (cv_restart(&d->cv, d->t, y, tstop, err)) return -1;
        rc = run_stretch(d, tstop, y, err);
        if (rc < 0 || rc == RD_HYB_STOP) return rc;
    }
}

int rd_hybrid_run(const rd_hybrid *h, const rd_ground *gm, const rd_ref_opts *opts, double *y,
                  double *t_stop, rd_error *err)
{
    if (!(opts->t_end > 0.0) || !(opts->rtol > 0.0) || !(opts->atol > 0.0))
        return rd_error_set(err, "reference solver: t_end, rtol and atol must be > 0");
    if (h->n < 1 || h->n > 4)
        return rd_error_set(err, "reference solver: state length %d not in 1..4", h->n);
    drive d;
    memset(&d, 0, sizeof d);
    d.h = h;
    d.gm = gm;
    d.t_end = opts->t_end;
    d.dt_out = opts->dt_out;
    int rc = cv_create(&d.cv, h, opts, err);
    if (!rc) {
        rc = drive_loop(&d, y, err);
        if (rc >= 0 && !d.sampled && h->sample(h->sys, d.t, y)) /* final state, off the grid */
            rc = -1;
    }
    cv_free(&d.cv);
    *t_stop = d.t;
    return rc < 0 ? -1 : 0;
}
