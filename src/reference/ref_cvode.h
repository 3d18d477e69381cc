/* rockdem — private: a hybrid (piecewise-smooth) ODE driver on CVODE, shared by the Housner
 * and Kounadis reference solvers. All SUNDIALS calls live in ref_cvode.c.
 *
 * The driver integrates y' = f(t, y) of the current mode, restarts CVODE at every break of the
 * ground input, watches the mode's root functions and hands each root to the model, which may
 * change the mode and jump the state (impacts), continue, or stop.
 *
 * Folder reference/ owns the rigid CVODE reference solvers (Housner, Kounadis); it may call
 * base/, records/, io/ and the public API.
 */
#ifndef ROCKDEM_REF_CVODE_H
#define ROCKDEM_REF_CVODE_H

#include "rockdem/reference.h"

#define RD_HYB_MAXROOTS 16

enum {
    RD_HYB_GO = 0,      /* carry on integrating without a restart */
    RD_HYB_RESTART = 1, /* mode or state changed: settle and restart CVODE here */
    RD_HYB_STOP = 2     /* the run is over (overturn, lift-off) */
};

typedef struct rd_hybrid {
    int n;       /* state length (<= 4) */
    double hmax; /* s, largest CVODE step: keeps short excursions of a root function visible */
    void *sys;   /* the model */
    /* y' = f(t, y) in the current mode; 0 ok, non-zero: CVODE retries/fails */
    int (*rhs)(void *sys, double t, const double *y, double *ydot);
    /* number of root functions of the current mode; dirs[i]: +1 rising, -1 falling, 0 both */
    int (*nroots)(void *sys, int *dirs);
    int (*roots)(void *sys, double t, const double *y, double *g);
    /* make the mode consistent with (t, y) before each (re)start: RD_HYB_GO or RD_HYB_STOP */
    int (*settle)(void *sys, double t, double *y);
    /* roots found at t (found[i] != 0): RD_HYB_GO, RD_HYB_RESTART or RD_HYB_STOP */
    int (*event)(void *sys, double t, double *y, const int *found);
    /* record the state at an output time (may adjust y to the mode's constraints); 0 or -1 */
    int (*sample)(void *sys, double t, double *y);
} rd_hybrid;

/* Integrate from t = 0 (y holds the initial state) to opts->t_end or a stop. y ends as the
 * final state; *t_stop the time reached. A callback that returns -1 must have filled err (the
 * model keeps the same rd_error). */
int rd_hybrid_run(const rd_hybrid *h, const rd_ground *gm, const rd_ref_opts *opts, double *y,
                  double *t_stop, rd_error *err);

/* 0 when gm is usable: a callback needs t_quiet > 0 (INFINITY when the motion never ends). */
int rd_ground_check(const rd_ground *gm, rd_error *err);

/* Ground accelerations at t (zero without a callback or at t >= t_quiet). */
void rd_ground_eval(const rd_ground *gm, double t, double *ug, double *vg);

/* Append to a result; -1 (with err) when out of memory. */
int rd_ref_push_sample(rd_ref_result *res, const rd_ref_sample *s, rd_error *err);
int rd_ref_push_event(rd_ref_result *res, const rd_ref_event *e, rd_error *err);

/* Reset a result to empty with summary defaults (no overturn, ratios 0). */
void rd_ref_result_init(rd_ref_result *res);

#endif
