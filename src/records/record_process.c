/* rockdem — the acceleration record: allocation, integration, units, scaling, resampling,
 * padding, baseline correction and evaluation at any time. Folder records/: ground motions
 * (records, their readers, stochastic generation, intensity measures, the SDOF oscillator);
 * it may call base/ only. The readers (record.c, record_fema.c) call this file, never back.
 *
 * The acceleration is piecewise linear between samples. On a step h from sample i to i+1
 * the exact integrals from rest are
 *   v_{i+1} = v_i + h (a_i + a_{i+1}) / 2
 *   d_{i+1} = d_i + h v_i + h^2 (2 a_i + a_{i+1}) / 6,
 * so acc, vel and disp always describe one consistent motion.
 */
#include "records/record_limits.h"

#include <gsl/gsl_interp.h>
#include <gsl/gsl_multifit.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *rd_record_step_error(double dt, char *buf, size_t size)
{
    if (dt >= RD_RECORD_DT_MIN && dt <= RD_RECORD_DT_MAX) return NULL;
    snprintf(buf, size, "time step %g s is outside [%g, %g] s", dt, RD_RECORD_DT_MIN,
             RD_RECORD_DT_MAX);
    return buf;
}

const char *rd_record_sample_error(double x, double unit, char *buf, size_t size)
{
    if (fabs(x * unit) <= RD_RECORD_ACC_MAX) return NULL;
    if (!isfinite(x))
        snprintf(buf, size, "is not a finite number");
    else
        snprintf(buf, size,
                 "is outside the valid |acceleration| <= %g m/s^2 (%.4g g; docs/LIMITS.md)",
                 RD_RECORD_ACC_MAX, RD_RECORD_ACC_MAX / RD_G_STANDARD);
    return buf;
}

int rd_record_alloc(rd_record *r, size_t npts, double dt, rd_error *err)
{
    memset(r, 0, sizeof *r);
    if (npts == 0) return rd_error_set(err, "record: no samples");
    if (!(dt > 0.0) || !isfinite(dt))
        return rd_error_set(err, "record: time step %g s must be positive", dt);
    r->acc = calloc(npts, sizeof *r->acc);
    r->vel = calloc(npts, sizeof *r->vel);
    r->disp = calloc(npts, sizeof *r->disp);
    if (!r->acc || !r->vel || !r->disp) {
        rd_record_free(r);
        return rd_error_set(err, "record: out of memory for %zu samples", npts);
    }
    r->npts = npts;
    r->dt = dt;
    return 0;
}

void rd_record_free(rd_record *r)
{
    free(r->acc);
    free(r->vel);
    free(r->disp);
    memset(r, 0, sizeof *r);
}

double rd_accel_unit_factor(rd_accel_unit unit)
{
    switch (unit) {
    case RD_UNIT_G: return RD_G_STANDARD;
    case RD_UNIT_CM_S2: return 0.01;
    case RD_UNIT_M_S2: break;
    }
    return 1.0;
}

/* Exact integrals of the piecewise-linear a (n samples, step h) from rest into v and d. */
static void integrate_series(const double *a, size_t n, double h, double *v, double *d)
{
    v[0] = 0.0;
    d[0] = 0.0;
    for (size_t i = 0; i + 1 < n; i++) {
        v[i + 1] = v[i] + 0.5 * h * (a[i] + a[i + 1]);
        d[i + 1] = d[i] + h * v[i] + h * h * (2.0 * a[i] + a[i + 1]) / 6.0;
    }
}

void rd_record_integrate(rd_record *r)
{
    integrate_series(r->acc, r->npts, r->dt, r->vel, r->disp);
}

double rd_record_duration(const rd_record *r)
{
    return r->npts ? (double)(r->npts - 1) * r->dt : 0.0;
}

void rd_record_scale(rd_record *r, double factor)
{
    for (size_t i = 0; i < r->npts; i++) {
        r->acc[i] *= factor;
        r->vel[i] *= factor;
        r->disp[i] *= factor;
    }
}

static double peak_abs(const double *x, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs(x[i]));
    return m;
}

/* Scale so that the peak of |series| becomes target. */
static int scale_peak(rd_record *r, const double *series, double target, const char *what,
                      rd_error *err)
{
    double peak = peak_abs(series, r->npts);
    if (!(peak > 0.0))
        return rd_error_set(err, "record %s: cannot scale to a target %s: the record is zero",
                            r->name, what);
    if (!(target >= 0.0) || !isfinite(target))
        return rd_error_set(err, "record %s: target %s %g must be finite and >= 0", r->name, what,
                            target);
    rd_record_scale(r, target / peak);
    return 0;
}

int rd_record_scale_to_pga(rd_record *r, double pga, rd_error *err)
{
    return scale_peak(r, r->acc, pga, "PGA", err);
}

int rd_record_scale_to_pgv(rd_record *r, double pgv, rd_error *err)
{
    return scale_peak(r, r->vel, pgv, "PGV", err);
}

/* Replace r's arrays by a fresh record (keeping name and source). */
static void adopt(rd_record *r, rd_record *fresh)
{
    memcpy(fresh->name, r->name, sizeof r->name);
    memcpy(fresh->source, r->source, sizeof r->source);
    rd_record_free(r);
    *r = *fresh;
}

/* out->acc at out's step from r's samples by gsl_interp_linear (r->npts >= 2). */
static int interpolate(const rd_record *r, rd_record *out)
{
    double *t = malloc(r->npts * sizeof *t);
    gsl_interp *lin = gsl_interp_alloc(gsl_interp_linear, r->npts);
    gsl_interp_accel *acc = gsl_interp_accel_alloc();
    int status = (t && lin && acc) ? 0 : -1;
    if (status == 0) {
        for (size_t i = 0; i < r->npts; i++) t[i] = (double)i * r->dt;
        gsl_interp_init(lin, t, r->acc, r->npts);
        for (size_t k = 0; k < out->npts; k++) /* clamp: k*dt may pass the last time by rounding */
            out->acc[k] =
                gsl_interp_eval(lin, t, r->acc, fmin((double)k * out->dt, t[r->npts - 1]), acc);
    }
    free(t);
    gsl_interp_free(lin);
    gsl_interp_accel_free(acc);
    return status;
}

int rd_record_resample(rd_record *r, double dt, rd_error *err)
{
    if (!(dt > 0.0) || !isfinite(dt))
        return rd_error_set(err, "record %s: resampling step %g s must be positive", r->name, dt);
    size_t n =
        (size_t)floor(rd_record_duration(r) / dt * (1.0 + 1e-12)) + 1; /* samples within [0, T] */
    rd_record out;
    if (rd_record_alloc(&out, n, dt, err)) return -1;
    if (r->npts < 2)
        out.acc[0] = r->acc[0];
    else if (interpolate(r, &out)) {
        rd_record_free(&out);
        return rd_error_set(err, "record %s: out of memory while resampling", r->name);
    }
    rd_record_integrate(&out);
    adopt(r, &out);
    return 0;
}

int rd_record_pad(rd_record *r, double duration, rd_error *err)
{
    if (!(duration >= 0.0) || !isfinite(duration))
        return rd_error_set(err, "record %s: padding %g s must be finite and >= 0", r->name,
                            duration);
    size_t extra = (size_t)ceil(duration / r->dt * (1.0 - 1e-12));
    rd_record out;
    if (rd_record_alloc(&out, r->npts + extra, r->dt, err)) return -1;
    memcpy(out.acc, r->acc, r->npts * sizeof *r->acc);
    rd_record_integrate(&out);
    adopt(r, &out);
    return 0;
}

/* Basis accelerations for displacement t^k, k = 2..degree, in normalised time tau = t/T:
 * column k-2 of `a` holds tau^(k-2); `d` gets its exact piecewise-linear double integral
 * and `vend` the end velocity of each. Returns -1 on allocation failure. */
static int baseline_basis(const rd_record *r, int degree, gsl_matrix *d, gsl_vector *vend)
{
    size_t n = r->npts;
    double T = rd_record_duration(r);
    double *a = malloc(3 * n * sizeof *a);
    if (!a) return -1;
    double *v = a + n, *x = a + 2 * n;
    for (int k = 2; k <= degree; k++) {
        for (size_t i = 0; i < n; i++) a[i] = pow((double)i * r->dt / T, k - 2);
        integrate_series(a, n, r->dt, v, x);
        for (size_t i = 0; i < n; i++) gsl_matrix_set(d, i, (size_t)(k - 2), x[i]);
        gsl_vector_set(vend, (size_t)(k - 2), v[n - 1]);
    }
    free(a);
    return 0;
}

/* Least-squares coefficients c of the basis displacements fitting r->disp subject to
 * sum c_k vend_k = v(T). The constraint is solved for the constant-acceleration term
 * c_0 (vend_0 = T exactly), the others come from gsl_multifit_linear on the rest. */
static int baseline_fit(const rd_record *r, const gsl_matrix *d, const gsl_vector *vend,
                        gsl_vector *c)
{
    size_t n = r->npts, m = c->size;
    double vT = r->vel[n - 1], v0 = gsl_vector_get(vend, 0);
    gsl_vector_set_zero(c);
    if (m == 1) {
        gsl_vector_set(c, 0, vT / v0);
        return 0;
    }
    gsl_matrix *X = gsl_matrix_alloc(n, m - 1);
    gsl_vector *y = gsl_vector_alloc(n), *cr = gsl_vector_alloc(m - 1);
    gsl_matrix *cov = gsl_matrix_alloc(m - 1, m - 1);
    gsl_multifit_linear_workspace *w = gsl_multifit_linear_alloc(n, m - 1);
    int status = (X && y && cr && cov && w) ? 0 : -1;
    if (status == 0) {
        for (size_t i = 0; i < n; i++) {
            double d0 = gsl_matrix_get(d, i, 0);
            gsl_vector_set(y, i, r->disp[i] - vT / v0 * d0);
            for (size_t k = 1; k < m; k++)
                gsl_matrix_set(X, i, k - 1,
                               gsl_matrix_get(d, i, k) - gsl_vector_get(vend, k) / v0 * d0);
        }
        double chisq;
        status = gsl_multifit_linear(X, y, cr, cov, &chisq, w) ? -1 : 0;
        double rest = 0.0;
        for (size_t k = 1; k < m; k++) {
            gsl_vector_set(c, k, gsl_vector_get(cr, k - 1));
            rest += gsl_vector_get(cr, k - 1) * gsl_vector_get(vend, k);
        }
        gsl_vector_set(c, 0, (vT - rest) / v0);
    }
    gsl_matrix_free(X);
    gsl_vector_free(y);
    gsl_vector_free(cr);
    gsl_matrix_free(cov);
    gsl_multifit_linear_free(w);
    return status;
}

int rd_record_baseline(rd_record *r, int degree, rd_error *err)
{
    if (degree < 2 || degree > 8)
        return rd_error_set(err, "record %s: baseline polynomial degree %d outside [2, 8]", r->name,
                            degree);
    if (r->npts < (size_t)degree + 1)
        return rd_error_set(err, "record %s: %zu samples are too few for a degree-%d baseline",
                            r->name, r->npts, degree);
    size_t m = (size_t)degree - 1;
    gsl_matrix *d = gsl_matrix_alloc(r->npts, m);
    gsl_vector *vend = gsl_vector_alloc(m), *c = gsl_vector_alloc(m);
    int status = (d && vend && c && baseline_basis(r, degree, d, vend) == 0)
                     ? baseline_fit(r, d, vend, c)
                     : -1;
    if (status == 0) {
        double T = rd_record_duration(r);
        for (size_t i = 0; i < r->npts; i++)
            for (size_t k = 0; k < m; k++)
                r->acc[i] -= gsl_vector_get(c, k) * pow((double)i * r->dt / T, (double)k);
        rd_record_integrate(r);
    }
    gsl_matrix_free(d);
    gsl_vector_free(vend);
    gsl_vector_free(c);
    return status ? rd_error_set(err, "record %s: baseline fit failed", r->name) : 0;
}

void rd_record_eval(const rd_record *r, double t, double *a, double *v, double *d)
{
    *a = *v = *d = 0.0;
    if (t < 0.0 || r->npts == 0) return;
    size_t last = r->npts - 1;
    double T = rd_record_duration(r);
    if (t >= T) {
        *a = (t == T) ? r->acc[last] : 0.0;
        *v = r->vel[last];
        *d = r->disp[last] + r->vel[last] * (t - T);
        return;
    }
    size_t i = (size_t)(t / r->dt);
    if (i >= last) i = last - 1;
    double s = t - (double)i * r->dt, h = r->dt;
    double a0 = r->acc[i], slope = (r->acc[i + 1] - a0) / h; /* m/s^3 */
    *a = a0 + slope * s;
    *v = r->vel[i] + a0 * s + 0.5 * slope * s * s;
    *d = r->disp[i] + r->vel[i] * s + 0.5 * a0 * s * s + slope * s * s * s / 6.0;
}
