/* rockdem — rigid-block reference solvers (SUNDIALS CVODE with root finding).
 *
 * Two models from docs/ROCKING-EQUATIONS.md, both planar, rigid, no sliding:
 *   - Housner: one block 2b x 2h rocking on a moving ground (1 DOF, impacts with restitution e);
 *   - Kounadis: two stacked blocks (2 DOF), eight configuration patterns (s1, s2) plus rest,
 *     switched by root functions; impacts conserve angular momentum (perfectly plastic).
 * Sign convention: theta > 0 tips toward +x about the right corner (clockwise positive);
 * a ground acceleration ug'' > 0 drives theta negative. Angles in rad, time in s, SI elsewhere.
 * The DEM engine never uses these solvers; they exist to check it.
 */
#ifndef ROCKDEM_REFERENCE_H
#define ROCKDEM_REFERENCE_H

#include "rockdem/api.h"
#include <stddef.h>

#include "rockdem/error.h"

/* Ground acceleration at time t: horizontal ug'' and vertical vg'' (m/s^2, vertical up). */
typedef void (*rd_ground_fn)(void *ctx, double t, double *ug_dd, double *vg_dd);

typedef struct rd_ground {
    rd_ground_fn fn;      /* NULL: the ground does not move */
    void *ctx;            /* passed to fn */
    const double *breaks; /* s, times where the input is non-smooth (pulse start/end); any order */
    size_t nbreaks;
    double t_quiet; /* s, ug'' = vg'' = 0 for all t >= t_quiet (free motion); INFINITY if never */
} rd_ground;

/* Run options shared by both solvers; start from rd_ref_opts_default(). */
typedef struct rd_ref_opts {
    double t_end;       /* s, the run covers [0, t_end]; default 5 */
    double dt_out;      /* s, time-history interval; <= 0: no history; default 0.001 */
    double rtol;        /* CVODE relative tolerance; default 1e-10 */
    double atol;        /* CVODE absolute tolerance, rad and rad/s; default 1e-12 */
    double rest_factor; /* a joint closes (rest, lock) when its post-impact opening rate is below
                           rest_factor * p, p = sqrt(3 g / 4 R) of the (lower) block; default 1e-4 */
    double theta0[2];   /* initial angles, rad (Kounadis: theta1, theta2 absolute); default 0 */
    double omega0[2];   /* initial rates, rad/s; default 0 */
} rd_ref_opts;

RD_API rd_ref_opts rd_ref_opts_default(void);

typedef enum rd_ref_event_kind {
    RD_REF_UPLIFT,   /* a closed joint opens (rocking starts) */
    RD_REF_IMPACT,   /* a joint angle returns to 0; omega_pre/omega_post hold the jump */
    RD_REF_PEAK,     /* turning point of theta[joint] (rate 0): an amplitude */
    RD_REF_REST,     /* the ground joint closes: the (lower) block rests flat on the ground */
    RD_REF_LOCK,     /* the interface closes: the upper block rests flat on the lower one */
    RD_REF_OVERTURN, /* overturning is certain (criterion in rd_housner_falls / pi/2 tilt) */
    RD_REF_LIFTOFF   /* a pivot's normal force turned negative (jumping): the run stops */
} rd_ref_event_kind;

typedef struct rd_ref_event {
    double t; /* s */
    rd_ref_event_kind kind;
    int joint;            /* 0: ground joint / lower block, 1: interface / upper block */
    int s1, s2;           /* configuration after the event (Housner: s1 only, s2 = 0) */
    double theta[2];      /* rad, at the event */
    double omega_pre[2];  /* rad/s, before a jump (equal to omega_post otherwise) */
    double omega_post[2]; /* rad/s, after */
} rd_ref_event;

typedef struct rd_ref_sample {
    double t;        /* s */
    double theta[2]; /* rad (Housner: theta[1] = 0) */
    double omega[2]; /* rad/s */
    int s1, s2;      /* configuration pattern in force */
} rd_ref_sample;

typedef struct rd_ref_summary {
    int overturned;      /* 1 when overturning became certain */
    int overturn_joint;  /* 0 lower block / stack / single block, 1 upper block; -1 if none */
    double t_overturn;   /* s, when it became certain; -1 if never */
    int lifted_off;      /* 1 when a pivot lifted off (run stopped, model invalid beyond) */
    double t_stop;       /* s, time reached */
    double max_ratio[2]; /* max |theta_i| / alpha_i over the run */
    size_t nimpacts;     /* impacts at either joint */
} rd_ref_summary;

/* Output of a solve: a time history at dt_out (plus the final state), events, summary. */
typedef struct rd_ref_result {
    rd_ref_sample *samples;
    size_t nsamples, cap_samples;
    rd_ref_event *events;
    size_t nevents, cap_events;
    rd_ref_summary summary;
} rd_ref_result;

/* Release the arrays of a result filled by a solver (the struct itself is the caller's). */
RD_API void rd_ref_result_free(rd_ref_result *res);

/* ---- Housner: one block ---------------------------------------------------------------- */

typedef struct rd_housner_def {
    double b; /* half-width, m; default 0.25 */
    double h; /* half-height, m; default 0.5 */
    double g; /* gravity, m/s^2; default 9.81 */
    double e; /* angular-velocity restitution at impact, 0..1; < 0 means Housner's r; default -1 */
} rd_housner_def;

RD_API rd_housner_def rd_housner_def_default(void);

/* Slenderness alpha = atan(b/h), rad. */
RD_API double rd_housner_alpha(double b, double h);

/* Frequency parameter p = sqrt(3 g / (4 R)), R = sqrt(b^2 + h^2), 1/s. */
RD_API double rd_housner_p(double b, double h, double g);

/* Housner's restitution from angular momentum: r = 1 - 1.5 sin^2(alpha). */
RD_API double rd_housner_r(double alpha);

/* Free-motion overturning test for a block rocking about a corner with slenderness alpha and
 * frequency p (works for any rigid body about a fixed pivot with saddle angle alpha): 1 when the
 * fall is certain — beyond alpha moving outward, energy 0.5 omega^2 + p^2 cos(alpha - |theta|)
 * >= p^2 while moving outward, or beyond alpha moving inward without the energy to return. */
RD_API int rd_housner_falls(double theta, double omega, double alpha, double p);

/* Exact time (s) of free rocking from rest at theta0 (0 < theta0 < alpha) to theta = 0:
 * t = integral_0^theta0 dtheta / sqrt(2 p^2 (cos(alpha - theta0) - cos(alpha - theta))),
 * evaluated with GSL after theta = theta0 - u^2 removes the endpoint singularity. */
RD_API int rd_housner_free_time(double alpha, double p, double theta0, double *t, rd_error *err);

/* Integrate one block from opts->theta0[0], omega0[0] (rest when both are 0). */
RD_API int rd_housner_solve(const rd_housner_def *def, const rd_ground *gm, const rd_ref_opts *opts,
                            rd_ref_result *res, rd_error *err);

/* ---- Kounadis: two stacked blocks ------------------------------------------------------- */

typedef struct rd_kounadis_def {
    double b1, h1, m1; /* lower block half-width, half-height (m), mass (kg); default 0.25 0.5 1 */
    double b2, h2, m2; /* upper block, centred, b2 <= b1; default 0.25 0.5 1 */
    double g;          /* gravity, m/s^2; default 9.81 */
    double r;          /* impact restitution as the lower block alone would have it (Housner's e:
                          post- over pre-impact rate); every impact keeps r / r_H1 times the
                          plastic law's post-impact rates (r_H1 the lower block's Housner r);
                          <= 0: the plastic law (default). An impact that would gain energy is
                          an error. */
} rd_kounadis_def;

RD_API rd_kounadis_def rd_kounadis_def_default(void);

/* M(theta) and rest(theta, theta', ug'', vg'') of the 2-DOF pattern (s1, s2), s1, s2 = +-1,
 * exactly as in ROCKING-EQUATIONS.md section 2: M theta'' + rest = 0. */
RD_API void rd_kounadis_matrix(const rd_kounadis_def *d, int s1, int s2, const double th[2],
                               const double om[2], double ug, double vg, double m[2][2],
                               double rest[2]);

/* Accelerations and contact forces of pattern (s1, s2), s in {-1, 0, 1}; (0, 0) is rest. */
typedef struct rd_kounadis_eval {
    double acc[2];    /* theta1'', theta2'' (rad/s^2); locked: equal; lower at rest: acc[0] = 0 */
    double ground[2]; /* closed: corner forces (left, right), N; pivot: normal force (N) and the
                         moment about the pivot (N m, zero up to round-off: a consistency check) */
    double iface[2];  /* the same for the interface (normal = top face of the lower block) */
} rd_kounadis_eval;

RD_API int rd_kounadis_eval_mode(const rd_kounadis_def *d, int s1, int s2, const double th[2],
                                 const double om[2], double ug, double vg, rd_kounadis_eval *out,
                                 rd_error *err);

/* Static uplift thresholds |ug''|/g from rest: whole stack and upper block alone. */
RD_API void rd_kounadis_uplift_thresholds(const rd_kounadis_def *d, double *stack, double *upper);

/* Integrate the stack from opts->theta0, omega0 (pattern inferred from signs; rest when all 0).
 * A lift-off is reported (event, summary) and ends the run with status 0. */
RD_API int rd_kounadis_solve(const rd_kounadis_def *def, const rd_ground *gm,
                             const rd_ref_opts *opts, rd_ref_result *res, rd_error *err);

#endif
