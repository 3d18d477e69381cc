/* rockdem — recorded and synthetic ground-motion components of a scenario.
 *
 * Each component (h1, h2, vertical) keeps two records: `raw`, as read from its file or made by
 * the generator (SI units), and `applied`, what the ground does: raw, baseline-corrected
 * (polynomial of degree m->baseline, so the ground velocity ends at zero), a generated record
 * scaled back to its own target PGA, then times one scale factor shared by all components (a
 * pair keeps its ratio). Scaling comes last, so a requested PGA is the applied one. Both are owned by the definition
 * and freed by rd_motion_release (called from rd_scenario_free).
 *
 * Folder records/ owns ground motions (records, readers, stochastic generation, intensity
 * measures, SDOF); it may call base/ only.
 */
#include "rockdem/motion.h"
#include "rockdem/record.h"
#include "records/record_limits.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const component_names[RD_NCOMPONENTS] = { "h1", "h2", "vertical" };

const char *rd_motion_component_name(int c)
{
    return c >= 0 && c < RD_NCOMPONENTS ? component_names[c] : "?";
}

static void record_destroy(rd_record **r)
{
    if (!*r) return;
    rd_record_free(*r);
    free(*r);
    *r = NULL;
}

void rd_motion_release(rd_motion_def *m)
{
    for (int c = 0; c < RD_NCOMPONENTS; c++) {
        record_destroy(&m->record[c].raw);
        record_destroy(&m->record[c].applied);
    }
}

/* A new record holding a copy of r's samples; NULL without memory. */
static rd_record *record_clone(const rd_record *r)
{
    rd_record *c = malloc(sizeof *c);
    rd_error e;
    if (!c || rd_record_alloc(c, r->npts, r->dt, &e)) {
        free(c);
        return NULL;
    }
    memcpy(c->name, r->name, sizeof c->name);
    memcpy(c->source, r->source, sizeof c->source);
    memcpy(c->acc, r->acc, r->npts * sizeof *r->acc);
    memcpy(c->vel, r->vel, r->npts * sizeof *r->vel);
    memcpy(c->disp, r->disp, r->npts * sizeof *r->disp);
    return c;
}

int rd_motion_copy(rd_motion_def *dst, const rd_motion_def *src, rd_error *err)
{
    *dst = *src;
    int ok = 1;
    for (int c = 0; c < RD_NCOMPONENTS; c++) {
        rd_component_def *d = &dst->record[c];
        d->raw = ok && src->record[c].raw ? record_clone(src->record[c].raw) : NULL;
        d->applied = ok && src->record[c].applied ? record_clone(src->record[c].applied) : NULL;
        ok = ok && (d->raw != NULL) == (src->record[c].raw != NULL) &&
             (d->applied != NULL) == (src->record[c].applied != NULL);
    }
    if (ok) return 0;
    rd_motion_release(dst);
    return rd_error_set(err, "out of memory copying the ground-motion records");
}

int rd_motion_has_records(const rd_motion_def *m)
{
    for (int c = 0; c < RD_NCOMPONENTS; c++)
        if (m->record[c].source != RD_SOURCE_NONE) return 1;
    return 0;
}

/* Reads or generates d's samples into r (SI units). */
static int read_source(const rd_component_def *d, rd_record *r, rd_error *err)
{
    switch (d->source) {
    case RD_SOURCE_AT2: return rd_record_read_at2(r, d->path, err);
    case RD_SOURCE_TEXT:
        if (rd_record_read_text_as(r, d->path, d->unit, d->dt, err)) return -1;
        rd_record_scale(r, d->unit);
        return 0;
    case RD_SOURCE_FEMA: return rd_record_read_fema(r, d->path, d->record, d->fema_b, err);
    case RD_SOURCE_STOCHASTIC: return rd_record_stochastic(r, &d->stochastic, err);
    case RD_SOURCE_NONE: break;
    }
    return rd_error_set(err, "ground motion: component has no source");
}

int rd_motion_load(rd_motion_def *m, int c, rd_error *err)
{
    rd_component_def *d = &m->record[c];
    rd_record *r = calloc(1, sizeof *r);
    if (!r) return rd_error_set(err, "ground motion: out of memory");
    if (read_source(d, r, err)) {
        rd_record_free(r);
        free(r);
        return -1;
    }
    record_destroy(&d->raw);
    record_destroy(&d->applied);
    d->raw = r;
    return 0;
}

/* A new record with the samples of src (vel and disp re-integrated). */
static rd_record *record_copy(const rd_record *src, rd_error *err)
{
    rd_record *r = calloc(1, sizeof *r);
    if (!r) {
        rd_error_set(err, "ground motion: out of memory");
        return NULL;
    }
    if (rd_record_alloc(r, src->npts, src->dt, err)) {
        free(r);
        return NULL;
    }
    memcpy(r->acc, src->acc, src->npts * sizeof *r->acc);
    memcpy(r->name, src->name, sizeof r->name);
    memcpy(r->source, src->source, sizeof r->source);
    rd_record_integrate(r);
    return r;
}

static double peak(const double *x, size_t n)
{
    double p = 0.0;
    for (size_t i = 0; i < n; i++) p = fmax(p, fabs(x[i]));
    return p;
}

/* Geometric mean of the peak |acc| (pgv = 0) or |vel| (pgv = 1) of the horizontal applied
 * records, or the vertical peak when there is no horizontal record. */
static double reference_peak(const rd_motion_def *m, int pgv)
{
    double logsum = 0.0;
    int n = 0;
    for (int c = 0; c < RD_NCOMPONENTS && (c < RD_VERTICAL || n == 0); c++) {
        const rd_record *r = m->record[c].applied;
        if (!r) continue;
        logsum += log(peak(pgv ? r->vel : r->acc, r->npts));
        n++;
    }
    return n ? exp(logsum / n) : 0.0;
}

/* The factor m->scale asks for, from the baseline-corrected records. */
static int scale_factor(rd_motion_def *m, rd_error *err)
{
    m->factor = 1.0;
    if (m->scale == RD_SCALE_FACTOR) m->factor = m->scale_value;
    if (m->scale != RD_SCALE_PGA && m->scale != RD_SCALE_PGV) return 0;
    double p = reference_peak(m, m->scale == RD_SCALE_PGV);
    if (!(p > 0.0) || !isfinite(p))
        return rd_error_set(err, "ground motion: cannot scale to a %s: a record is zero",
                            m->scale == RD_SCALE_PGV ? "PGV" : "PGA");
    m->factor = m->scale_value / p;
    return 0;
}

/* A record with fewer samples than the degree-`degree` baseline has coefficients cannot be
 * corrected: refused naming its file (or generator) and the count. */
static int too_short(const rd_component_def *d, int degree, rd_error *err)
{
    size_t need = (size_t)degree + 1, n = d->applied->npts;
    if (n >= need) return 0;
    return rd_error_set(
        err,
        "%s: %zu sample%s, too few for the degree-%d baseline (at least %zu, or 'baseline "
        "off')",
        d->path[0] ? d->path : d->applied->name, n, n == 1 ? "" : "s", degree, need);
}

/* A generated record's own target PGA holds for the record that drives the bodies: the
 * baseline correction moves its peak (0.3 g requested, 0.2955 g applied for seed 1 over 8 s
 * before this step), so the corrected record is scaled back to it. A shared PGA or PGV target
 * (m->scale) replaces it, and without a correction the generator's scaling already holds. */
static int generator_pga(const rd_motion_def *m, rd_component_def *d, rd_error *err)
{
    if (d->source != RD_SOURCE_STOCHASTIC || m->baseline == 0 || m->scale == RD_SCALE_PGA ||
        m->scale == RD_SCALE_PGV)
        return 0;
    return rd_record_scale_to_pga(d->applied, d->stochastic.pga, err);
}

int rd_motion_prepare(rd_motion_def *m, rd_error *err)
{
    for (int c = 0; c < RD_NCOMPONENTS; c++) {
        rd_component_def *d = &m->record[c];
        record_destroy(&d->applied);
        if (!d->raw) continue;
        d->applied = record_copy(d->raw, err);
        if (!d->applied) return -1;
        if (m->baseline > 0 && too_short(d, m->baseline, err)) return -1;
        if (m->baseline > 0 && rd_record_baseline(d->applied, m->baseline, err)) return -1;
        if (generator_pga(m, d, err)) return -1;
    }
    if (scale_factor(m, err)) return -1;
    for (int c = 0; c < RD_NCOMPONENTS; c++)
        if (m->record[c].applied) rd_record_scale(m->record[c].applied, m->factor);
    return 0;
}

int rd_motion_im(const rd_motion_def *m, int c, rd_im *im, double sa[2], rd_error *err)
{
    static const double periods[2] = { 0.2, 1.0 }; /* s */
    const double pad = 2.0; /* s of rest: two periods of the longest oscillator */
    const rd_record *r = m->record[c].applied;
    if (!r) return rd_error_set(err, "ground motion: no %s record", rd_motion_component_name(c));
    rd_im_compute(r, im);
    rd_record *p = record_copy(r, err);
    if (!p) return -1;
    int rc = rd_record_pad(p, pad, err) || rd_im_psa(p, periods, 2, 0.05, sa, err) ? -1 : 0;
    rd_record_free(p);
    free(p);
    return rc;
}
