/* rockdem — spectral matching of an acceleration record to a target response spectrum by the
 * frequency-domain iteration of Gasparini & Vanmarcke (1976, SIMQKE, MIT R76-4): compute the
 * record's pseudo-spectral acceleration at the target periods, multiply each Fourier
 * coefficient (gsl_fft_real_radix2 over the record zero-padded to a power of two) by the ratio
 * target / record at its period (interpolated in log period, held at the band's ends), return
 * to time, remove the drift (rd_record_baseline, degree 4) and repeat until every ratio lies in
 * [lo, hi] or the iterations run out. The phases, and so the record's envelope, are kept.
 * Folder records/ owns ground motions (records, readers, stochastic generation, intensity
 * measures, SDOF, spectral matching); it may call base/ only.
 */
#include "rockdem/record.h"

#include <gsl/gsl_fft_halfcomplex.h>
#include <gsl/gsl_fft_real.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Degree of the drift removal after each correction (record_process.c: 4-6 is usual). */
#define MATCH_BASELINE_DEGREE 4

/* Ratio target / psa at period T: linear in log T between the target periods, the end values
 * outside them. */
static double ratio_at(const double *periods, const double *q, size_t n, double T)
{
    if (T <= periods[0]) return q[0];
    if (T >= periods[n - 1]) return q[n - 1];
    size_t i = 1;
    while (periods[i] < T) i++;
    double u = log(T / periods[i - 1]) / log(periods[i] / periods[i - 1]);
    return q[i - 1] + u * (q[i] - q[i - 1]);
}

/* The ratios q = target / psa and their range. */
static int ratios(const rd_record *r, const double *periods, const double *target, size_t n,
                  double zeta, double *q, double *qmin, double *qmax, rd_error *err)
{
    if (rd_im_psa(r, periods, n, zeta, q, err)) return -1;
    *qmin = INFINITY;
    *qmax = 0.0;
    for (size_t i = 0; i < n; i++) {
        q[i] = target[i] / q[i];
        *qmin = fmin(*qmin, q[i]);
        *qmax = fmax(*qmax, q[i]);
    }
    return 0;
}

/* One correction: every Fourier coefficient times the ratio at its period. */
static int correct(rd_record *r, double *buf, size_t N, const double *periods, const double *q,
                   size_t n, rd_error *err)
{
    memset(buf, 0, N * sizeof *buf);
    memcpy(buf, r->acc, r->npts * sizeof *buf);
    gsl_fft_real_radix2_transform(buf, 1, N);
    for (size_t k = 1; k <= N / 2; k++) {
        double c = ratio_at(periods, q, n, N * r->dt / (double)k);
        buf[k] *= c;                    /* real part of bin k (the Nyquist bin at N/2) */
        if (k < N / 2) buf[N - k] *= c; /* imaginary part */
    }
    gsl_fft_halfcomplex_radix2_inverse(buf, 1, N);
    memcpy(r->acc, buf, r->npts * sizeof *buf);
    return rd_record_baseline(r, MATCH_BASELINE_DEGREE, err);
}

int rd_record_match(rd_record *r, const double *periods, const double *target, size_t n,
                    double zeta, int iterations, double lo, double hi, double *qmin, double *qmax,
                    rd_error *err)
{
    if (n < 2 || !(periods[0] > 0) || !(lo > 0 && lo <= 1 && hi >= 1) || iterations < 0)
        return rd_error_set(
            err, "record %s: matching needs >= 2 positive periods and 0 < lo <= 1 <= hi", r->name);
    for (size_t i = 1; i < n; i++)
        if (!(periods[i] > periods[i - 1]) || !(target[i] > 0))
            return rd_error_set(
                err, "record %s: matching periods must increase, targets be positive", r->name);
    if (r->npts < (size_t)MATCH_BASELINE_DEGREE + 2)
        return rd_error_set(err, "record %s: %zu samples, too short to match", r->name, r->npts);
    size_t N = 1;
    while (N < r->npts) N *= 2;
    double *buf = malloc(N * sizeof *buf), *q = malloc(n * sizeof *q);
    int rc = buf && q ? 0 : rd_error_set(err, "record %s: out of memory for matching", r->name);
    for (int it = 0; rc == 0; it++) {
        if (ratios(r, periods, target, n, zeta, q, qmin, qmax, err)) {
            rc = -1;
            break;
        }
        /* the record's spectrum is within the band when every ratio target / Sa is */
        if (1.0 / *qmax >= lo && 1.0 / *qmin <= hi) break;
        if (it == iterations) {
            rc = 1;
            break;
        }
        if (correct(r, buf, N, periods, q, n, err)) rc = -1;
    }
    free(buf);
    free(q);
    return rc;
}
