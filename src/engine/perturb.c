/* rockdem — an uncertain interface (`contact interface-perturbation`, seed 002): the
 * subcontact points of every free body are perturbed once, as they are built, by a
 * gsl_rng_mt19937 stream seeded with `seed` and read in a fixed order (bodies, then points),
 * three numbers per point whatever the settings, so a seed names one interface:
 *   remove F  floor(F n) of the body's n points are dropped (a partial Fisher-Yates shuffle of
 *             the removable ones; with keep-corners the corners of each face are kept);
 *   raise H   a fraction raise-fraction of the kept points moves into the body along its face's
 *             inward normal by U(0, H) m, so it touches only after that much closure;
 *   scatter C each kept point's area (so its KN A and KS A) is multiplied by a lognormal factor
 *             of mean 1 and coefficient of variation C: exp(sigma z - sigma^2/2),
 *             sigma^2 = ln(1 + C^2); C = 0 gives exactly 1.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/perturb.h"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>

static int check(const rd_perturb_def *d, rd_error *err)
{
    const char *bad = d->seed != floor(d->seed) || d->seed < 0 || d->seed > 4294967295.0
                          ? "seed must be a whole number in [0, 2^32)"
                      : !(d->remove >= 0 && d->remove < 1) ? "remove must be in [0, 1)"
                      : !(d->raise >= 0)                   ? "raise must be >= 0"
                      : !(d->raise_fraction >= 0 && d->raise_fraction <= 1)
                          ? "raise-fraction must be in [0, 1]"
                      : !(d->scatter >= 0) ? "scatter must be >= 0"
                                           : NULL;
    return bad ? rd_error_set(err, "contact interface-perturbation: %s", bad) : 0;
}

/* Is point j (body frame) a corner of face f of polyhedron p? */
static int is_corner(const rd_poly *p, int f, const double x[3])
{
    double tol = 1e-9 * (1.0 + p->radius);
    for (int k = 0; k < p->flen[f]; k++) {
        const double *v = p->v[p->fidx[p->fstart[f] + k]];
        if (fabs(v[0] - x[0]) < tol && fabs(v[1] - x[1]) < tol && fabs(v[2] - x[2]) < tol) return 1;
    }
    return 0;
}

/* Mark the removed points of body i (keep[j] = 0). */
static int choose_removed(rd_sim *s, int i, gsl_rng *r, char *keep, int *idx, rd_error *err)
{
    const rd_perturb_def *d = &s->sc.contact.perturb;
    int n = s->pt0[i + 1] - s->pt0[i], m = 0;
    for (int c = s->cf0[i]; c < s->cf0[i + 1]; c++)
        for (int j = s->cf_pt0[c]; j < s->cf_pt0[c + 1]; j++)
            if (!d->keep_corners || !is_corner(&s->poly[i], s->cf_face[c], s->pl[j])) idx[m++] = j;
    int nrem = (int)floor(d->remove * n);
    if (nrem > m) nrem = m;
    for (int k = 0; k < nrem; k++) { /* partial Fisher-Yates: idx[0..nrem) are removed */
        int t = k + (int)gsl_rng_uniform_int(r, (unsigned long)(m - k)), u = idx[k];
        idx[k] = idx[t];
        idx[t] = u;
        keep[idx[k]] = 0;
    }
    if (n >= 3 && n - nrem < 3)
        return rd_error_set(err,
                            "contact interface-perturbation: remove %g leaves %d subcontact points "
                            "on block '%s' (at least 3 needed)",
                            d->remove, n - nrem, s->sc.bodies[i].name);
    return 0;
}

/* Raise and scatter the points of body i (three draws per point, kept or not). */
static void shift_points(rd_sim *s, int i, gsl_rng *r, const char *keep)
{
    const rd_perturb_def *d = &s->sc.contact.perturb;
    double sigma = sqrt(log1p(d->scatter * d->scatter));
    for (int c = s->cf0[i]; c < s->cf0[i + 1]; c++) {
        const double *n = s->poly[i].fn[s->cf_face[c]]; /* outward, body frame */
        for (int j = s->cf_pt0[c]; j < s->cf_pt0[c + 1]; j++) {
            double u = gsl_rng_uniform(r), h = d->raise * gsl_rng_uniform(r),
                   z = gsl_ran_ugaussian(r);
            if (!keep[j]) continue;
            if (u < d->raise_fraction)
                for (int k = 0; k < 3; k++) s->pl[j][k] -= h * n[k];
            if (d->scatter > 0) s->pa[j] *= exp(sigma * z - 0.5 * sigma * sigma);
        }
    }
}

/* Drop the removed points, keeping the grouping by body and candidate face. */
static void compact(rd_sim *s, const char *keep)
{
    int out = 0;
    for (int i = 0; i < s->nb; i++) {
        s->pt0[i] = out;
        for (int c = s->cf0[i]; c < s->cf0[i + 1]; c++) {
            int first = s->cf_pt0[c], last = s->cf_pt0[c + 1];
            s->cf_pt0[c] = out;
            for (int j = first; j < last; j++) {
                if (!keep[j]) continue;
                for (int k = 0; k < 3; k++) s->pl[out][k] = s->pl[j][k];
                s->pa[out++] = s->pa[j];
            }
        }
    }
    s->pt0[s->nb] = s->cf_pt0[s->ncf] = s->npts = out;
}

int rd_perturb_points(rd_sim *s, rd_error *err)
{
    const rd_perturb_def *d = &s->sc.contact.perturb;
    if (check(d, err)) return -1;
    if (d->seed == 0 || (d->remove == 0 && d->raise == 0 && d->scatter == 0)) return 0;
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    char *keep = malloc((size_t)s->npts + 1);
    int *idx = malloc(((size_t)s->npts + 1) * sizeof *idx), rc = 0;
    if (!r || !keep || !idx)
        rc = rd_error_set(err, "out of memory");
    else {
        gsl_rng_set(r, (unsigned long)d->seed);
        for (int j = 0; j < s->npts; j++) keep[j] = 1;
        for (int i = 0; i < s->nb && !rc; i++) {
            if (s->fixed[i] || s->pt0[i + 1] == s->pt0[i]) continue;
            rc = choose_removed(s, i, r, keep, idx, err);
            shift_points(s, i, r, keep);
        }
        if (!rc) compact(s, keep);
    }
    if (r) gsl_rng_free(r);
    free(keep);
    free(idx);
    return rc;
}
