/* rockdem — the validation ladder: run a scenario through the rigid reference solvers, find
 * overturning thresholds, measure and calibrate the DEM's coefficient of restitution, and
 * measure the DEM's error against run time (the validation ladder of docs/validation.md).
 *
 * Mapping a scene to a reference model (rd_refscene_map):
 *   - one fixed body (the base) and one free brick standing on it       -> Housner (1 DOF);
 *   - one fixed base and two free bricks, the upper centred on the lower -> Kounadis (2 DOF).
 * Bricks must be axis-aligned and rock in the vertical plane of the horizontal pulse, whose
 * direction must be a multiple of 90 degrees (otherwise the block rocks in 3-D). theta > 0 tips
 * toward +direction; the reference feels ug'' = a_g . direction and vg'' = a_g,z.
 * SI units throughout. */
#ifndef ROCKDEM_VALIDATE_H
#define ROCKDEM_VALIDATE_H

#include "rockdem/api.h"
#include "rockdem/reference.h"
#include "rockdem/rockdem.h"

typedef enum rd_refmodel { RD_REFMODEL_HOUSNER = 1, RD_REFMODEL_KOUNADIS = 2 } rd_refmodel;

#define RD_REF_BLOCKS 2 /* most blocks a reference model has (Kounadis' stack) */

typedef struct rd_refscene {
    rd_refmodel model;
    rd_housner_def housner;   /* HOUSNER: the block (e from the scenario's reference restitution) */
    rd_kounadis_def kounadis; /* KOUNADIS: lower block 1, upper block 2 */
    int nblock;               /* 1 or RD_REF_BLOCKS */
    int body[2];              /* scenario body index of block 1 (lower) and block 2 (upper) */
    int out[2];               /* index of each block among the free bodies (output order) */
    double mass[2];           /* kg */
    double b[2], h[2];        /* half-width along the rocking direction and half-height, m */
    double size[2][3];        /* brick edge lengths, m */
    double dir[2];            /* horizontal unit vector: theta > 0 tips toward +dir */
    double origin[2];         /* x, y of the blocks' centres, m */
    double base_z;            /* top of the fixed base, m */
    double theta0;            /* initial tilt of a single block, rad (signed) */
    double alpha, p;          /* slenderness (rad) and p = sqrt(3 g / 4 R) (1/s) of block 1 */
    int equivalent;           /* 1: block 1 is the rigid-rocking equivalent of a body that is no
                                 brick (a mesh, a prism, a hull): Housner's equation with that
                                 body's own alpha (the lesser of its two sides along the shaking)
                                 and p = sqrt(m g R / I_O) (R and pivot inertia I_O from its mass
                                 properties), written as the rectangle of the same alpha and p;
                                 its impact keeps r = 1 - 2 p^2 R sin^2(alpha) / g (an
                                 approximation for an irregular body) */
    double R_own;             /* equivalent: the body's own distance to its pivot edge, m */
    rd_motion_def motion;     /* the scenario's ground motion */
    double breaks[4];         /* pulse starts and ends, s */
    rd_ground ground;         /* ground acceleration for the solvers (ctx = this struct) */
} rd_refscene;

/* Map the scenario to a reference model, or -1 with a one-line reason. The rd_refscene must
 * not be moved after this call (its ground callback points at it). */
RD_API int rd_refscene_map(const rd_scenario *sc, rd_refscene *rs, rd_error *err);

/* Solve the mapped model over [0, sc->duration] with samples every output interval. */
RD_API int rd_refscene_solve(const rd_scenario *sc, const rd_refscene *rs, rd_ref_result *res,
                             rd_error *err);

/* Write a solution in the DEM's HDF5 layout (src/io/io_hdf5.h) to path: poses from the rigid
 * rotation about the active pivot, tilt, ground, events, summary; energies kinetic and
 * gravitational (the others zero). When sum is not NULL, fills it and body[0..nblock), the
 * caller's storage that sum->body then points at. */
RD_API int rd_refscene_write(const rd_scenario *sc, const rd_refscene *rs, const rd_ref_result *res,
                             const char *path, rd_summary *sum, rd_body_summary body[RD_REF_BLOCKS],
                             rd_error *err);

/* Can rd_refscene_write write path? The checks `rockdem run` makes of its output before any
 * work (never a device, folder or pipe, nor a file the scene reads; its folder writable), for
 * a caller to make before the solve. 0, or -1 with err (one line naming the output). */
RD_API int rd_refscene_check_output(const rd_scenario *sc, const char *path, rd_error *err);

/* ---- overturning thresholds ------------------------------------------------------------- */

typedef enum rd_engine { RD_ENGINE_DEM = 0, RD_ENGINE_REFERENCE = 1 } rd_engine;

typedef struct rd_threshold_opts {
    double lo, hi; /* amplitude range searched, m/s^2; <= 0: defaults 0.9 and 10 times the
                      static uplift threshold g tan(alpha) (stack: the lower of item 2) */
    int nscan;   /* coarse steps from lo to hi (<= 0: default 24; at most RD_THRESHOLD_SCAN_MAX) */
    int jobs;    /* runs of the coarse scan at once, each in a worker process (fork); <= 0
                      (default): the number of online cores; 1: all in the calling process.
                      The result is the serial scan's whatever the number (runs may be more) */
    double rtol; /* bisection stops when (hi - lo) / hi < rtol (default 0.005), in
                      [RD_THRESHOLD_RTOL_MIN, RD_THRESHOLD_RTOL_MAX] */
} rd_threshold_opts;

/* The bisection's relative bracket rtol: below 1e-6 the bracket reaches round-off before it
 * closes (1e-300 bisected for ever); 1 bisects nothing (the coarse scan's bracket), and a
 * relative bracket (hi - lo) / hi never exceeds 1. */
#define RD_THRESHOLD_RTOL_MIN 1e-6
#define RD_THRESHOLD_RTOL_MAX 1.0

/* Coarse scan steps, at most: each is one run (the default 24 brackets a threshold to 1/24 of
 * the range before bisection); 1000 runs of even a 1 s scene are hours, past which a count is
 * almost always a slip (10**9 would run for years). */
#define RD_THRESHOLD_SCAN_MAX 1000

RD_API rd_threshold_opts rd_threshold_opts_default(void);

/* The amplitude range (m/s^2) rd_threshold searches for this scenario and these options: lo
 * and hi with their defaults resolved. 0, or -1 with err (one line) when the options or the
 * scene cannot be searched: no horizontal pulse, no free body that can tip, rtol outside its
 * range, nscan above RD_THRESHOLD_SCAN_MAX, lo not below hi. Runs nothing: bad input is told
 * before any run. */
RD_API int rd_threshold_range(const rd_scenario *sc, const rd_threshold_opts *opts, double *lo,
                              double *hi, rd_error *err);

typedef struct rd_threshold_result {
    int found;         /* 0: nothing in [lo, hi] overturned */
    double amplitude;  /* m/s^2, upper end of the final bracket (overturns) */
    double below;      /* m/s^2, lower end (does not overturn) */
    double static_amp; /* m/s^2, static uplift threshold g tan(alpha) of block 1 (or stack) */
    double w_over_p;   /* 2 pi f / p of block 1 (0 without a frequency) */
    int runs;          /* simulations made (a parallel scan may run up to jobs - 1 past the
                           first bracket) */
    int lifted_off;    /* reference only: 1 when the upper end of the bracket is the onset of
                           pivot lift-off (the block jumps; the rigid model stops there), not
                           of overturning */
    int own_scale;     /* 1: static_amp and w_over_p are the scene's own (no brick or stack the
                           rigid reference maps exactly): the least g tan(alpha) along the shaking
                           over its free bodies and the assemblies standing on them, p of that
                           one's rocking (last: tools/rockdem/_lib.py mirrors the layout) */
} rd_threshold_result;

/* rd_overturns' *over for a reference run whose pivot lifts off (the block jumps). */
#define RD_LIFTS_OFF 2

/* Does the scene overturn at this horizontal pulse amplitude (m/s^2)? DEM: the scenario's
 * criterion; reference: certain overturning of either block, or RD_LIFTS_OFF when a pivot
 * lifts off first. The DEM writes no file. */
RD_API int rd_overturns(const rd_scenario *sc, rd_engine engine, double amplitude, int *over,
                        rd_error *err);

/* Minimum overturning amplitude of the scenario's horizontal pulse. Overturning is not
 * monotonic in amplitude in general (a stronger pulse can throw the block back before it
 * falls, leaving "safe islands" above the first overturning amplitude); the search scans up
 * from lo in nscan coarse steps to the first amplitude that overturns, then bisects inside
 * that first bracket. It finds the lowest overturning amplitude of that bracket, not a global
 * minimum below an island narrower than one coarse step. */
RD_API int rd_threshold(const rd_scenario *sc, rd_engine engine, const rd_threshold_opts *opts,
                        rd_threshold_result *out, rd_error *err);

/* ---- restitution of the discretised contact --------------------------------------------- */

/* Free rocking of the scenario's single free block released from rest at theta0 (rad, about
 * the corner along +x; the scenario's motion is removed), the way rocking theory defines
 * restitution (Housner 1963): the ratio of the angular velocities just after and just before
 * an impact, once the impact is complete. Between impacts free rocking conserves
 * 0.5 w^2 + p^2 cos(alpha - |theta|), so the speed leaving impact k follows from the amplitude
 * theta_{k+1} of the next half-cycle and the speed arriving from theta_k:
 *     r_k^2 = (cos(alpha - theta_{k+1}) - cos alpha) / (cos(alpha - theta_k) - cos alpha)
 * (amplitude decay: whole half-cycles, so the compliant impact is complete). Measured
 * independently from the speeds (`speed_ratio`): w^2 + 2 p^2 (cos(alpha - |theta|) - cos alpha),
 * the squared speed carried to theta = 0 (rigid theory's instant of impact), averaged over the
 * same band of |theta| before and after the impact (a quarter to three quarters of the smaller
 * amplitude: outside the compliant impact). The two agree when the impact is over within the
 * band; a block that still bounces on its new pivot after it (contact restitution > 0 at
 * corners) loses energy later and shows a speed ratio above the amplitude decay. r is the
 * geometric mean of the first n ratios. */
typedef struct rd_restitution {
    int nimpacts;          /* impacts seen */
    int n;                 /* ratios averaged (<= 3) */
    double ratio[3];       /* r_1 .. r_n from the amplitude decay */
    double speed_ratio[3]; /* r_1 .. r_n from the speeds either side, carried to theta = 0 */
    double amplitude[4];   /* rad: release angle, then the amplitude after each impact */
    double r;              /* geometric mean of ratio[], or -1 when fewer than 2 impacts */
    double r_speed;        /* geometric mean of speed_ratio[] */
    double t_impact[4];    /* s, first impact times */
} rd_restitution;

/* The rigid-body scales of a scene's free rocking: one free body's tipping angle alpha (rad)
 * and frequency parameter p = sqrt(m g R / I_O) (rad/s) on the side it tips to first along the
 * pulse's direction (x without a pulse), the distance R (m) from its centre of mass to that
 * pivot edge, and that lean direction (rad from +x). From Housner's block where the reference
 * maps the scene (housner = 1: a brick), else from the body itself (a mesh, a prism: its own
 * support polygon, R and pivot inertia; housner = 0). 0, or -1 with err (not one free body). */
typedef struct rd_rocking_scales {
    double alpha, p, R, lean;
    int housner;
} rd_rocking_scales;
RD_API int rd_rocking_scales_of(const rd_scenario *sc, rd_rocking_scales *out, rd_error *err);

/* The scene reduced to one free body, `name`, for its free rocking (a stack's, a column's or a
 * statue's joint calibrated on the body above it): the bodies it rests on as placed, down to the
 * fixed base, become fixed, every other free body (those above it) is removed, histories are
 * dropped, and no joint override sets a restitution (the calibrated one is the joint's). out is
 * a copy the caller frees with rd_scenario_free. 0, or -1 with err (no such body, or fixed). */
RD_API int rd_restitution_isolate(const rd_scenario *sc, const char *name, rd_scenario *out,
                                  rd_error *err);

/* Rigid theory's restitution of an impact onto the opposite pivot edge, angular momentum
 * about the new pivot conserved: r = 1 - 2 m R^2 sin^2(alpha) / I_O = 1 - 2 p^2 R sin^2(alpha)
 * / g (a uniform rectangular block, I_O = 4/3 m R^2: Housner's 1 - 1.5 sin^2 alpha). Exact for
 * a body symmetric about its rocking plane's vertical; an approximation for an irregular one. */
RD_API double rd_rigid_restitution(const rd_rocking_scales *s, double gravity);

RD_API int rd_restitution_measure(const rd_scenario *sc, double theta0, rd_restitution *out,
                                  rd_error *err);

/* The impact-loss parameter that gives the block restitution `target` in free rocking to
 * |r - target| < RD_CAL_RTOL: the vertex model's contact restitution e (`contact property
 * restitution e`, the impact loss of contact.c), or under the surface model, which has no
 * permanent set, its joint dashpot's ratio of critical damping zeta (`model damping viscous
 * zeta`, its impact loss; the joint's restitution is taken as 1): rd_restitution_loss_at. A scan
 * of the grid (e = 0, 0.25, ..., 1; zeta = 0.05, 0.3, 1, 2.5, 5) finds the first interval
 * where r crosses the target (r need not grow with e at a multi-point base; it falls with
 * zeta), then secant steps inside it. Returns 0 with *e set when reached; 1 when no scanned
 * interval crosses the target (below r(e = 0) at corners the impacts are already perfectly
 * plastic: less needs sliding or dashpots; above r(e = 1) the contact is elastic; above
 * r(zeta = 0.05) no steady loss keeps more); 2 when one does but RD_CAL_ITER steps inside it do
 * not reach the target (r too uneven there: the block slides or bounces, e.g. the `3dec`
 * preset's KS = KN / 10). Not reached, *e and *reached are the closest parameter and r
 * measured. */
RD_API int rd_restitution_calibrate(const rd_scenario *sc, double theta0, double target, double *e,
                                    double *reached, rd_error *err);

/* Intervals of the calibration's first scan (e in [0, 1], or zeta in [0.05, 5]). */
#define RD_CAL_GRID 4
/* 1 when the scenario's impact loss is its joint dashpot (the surface model), not the contact
 * restitution; then the calibration varies the dashpot's ratio. */
RD_API int rd_restitution_by_dashpot(const rd_scenario *sc);
/* The calibration's k-th scanned loss parameter (k = 0 .. RD_CAL_GRID): e = k / RD_CAL_GRID, or
 * the surface model's dashpot ratio. */
RD_API double rd_restitution_loss_at(const rd_scenario *sc, int k);
/* Set the loss parameter x on sc: its contact restitution, or (surface model) restitution 1 and
 * `model damping viscous x`. */
RD_API void rd_restitution_set_loss(rd_scenario *sc, double x);
/* rd_restitution_calibrate to |r - target| < rtol, with the scan's runs already made: grid[k]
 * (k = 0 .. RD_CAL_GRID) is the measurement of the scenario at loss parameter
 * rd_restitution_loss_at(k) (a row of `rockdem restitution`'s table), or NULL to run them. *at
 * (may be NULL) receives the measurement at the returned e, so a caller reads its speed check
 * without running it again. */
RD_API int rd_restitution_calibrate_grid(const rd_scenario *sc, double theta0, double target,
                                         double rtol, const rd_restitution *grid, double *e,
                                         double *reached, rd_restitution *at, rd_error *err);

/* |r - target| at which the calibration stops (the specification, issue 11), and the least a
 * caller may ask (`rockdem restitution --rtol`): the last digit the calibration prints r to. */
#define RD_CAL_RTOL     0.002
#define RD_CAL_RTOL_MIN 1e-4
/* Relative difference up to which the amplitude-decay and speed measures of one run agree when
 * its impacts are complete (the specification, issue 11; measured 0.04 % on the rigid preset
 * and on the 11 x 11 bed, 0.00 % on the defaults, docs/CONTACT.md). */
#define RD_CHECK_RTOL   0.005

#endif
