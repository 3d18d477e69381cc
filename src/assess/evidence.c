/* rockdem — the time-history evidence of an assessment: spectrum-compatible records run
 * through the DEM with the scene's body on its pad (seed 001 section 4: the mean of at least
 * five time histories, safety factor 3.0 on sliding).
 *
 * Each record is a Kanai-Tajimi record (records/stochastic.c, Clough-Penzien high-pass, its
 * ground frequency at the spectrum's peak) matched to the design spectrum at its damping over
 * the band [tmin, tmax] (records/match.c) until each ordinate lies within [lo, hi] of the
 * target; the vertical one, when kv > 0, is matched to kv times the horizontal spectrum. The
 * records are written as CSV (time s, acceleration m/s^2) into the report folder and the scene
 * reads them as `ground-motion import` would, its own motion replaced; each run writes its
 * HDF5 file beside them.
 * Folder assess/ owns the seismic assessment of unanchored bodies; it may call base/,
 * records/, scenario/, engine/ and io/.
 */
#include "rockdem/assess.h"
#include "rockdem/motion.h"
#include "rockdem/output.h"
#include "rockdem/record.h"
#include "rockdem/rockdem.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Seconds of free motion after the record ends (the body comes to rest or keeps rocking). */
#define EVIDENCE_TAIL        2.0
/* Seed offset of the vertical records (independent of the horizontal ones). */
#define VERTICAL_SEED_OFFSET 1000
/* Period scan for the spectrum's peak (s). */
#define PEAK_T_MIN           0.02
#define PEAK_T_MAX           4.0
#define PEAK_T_N             400

void rd_evidence_defaults(rd_evidence_def *d)
{
    memset(d, 0, sizeof *d);
    d->nrecords = RD_TH_MIN_RECORDS;
    d->duration = 20.0;
    d->dt = 0.005;
    d->seed = 1;
    d->tmin = 0.05;
    d->tmax = 4.0;
    d->lo = 0.9;
    d->hi = 1.3;
    d->iterations = 60;
    d->kv = 2.0 / 3.0;
}

static double peak_period(const rd_spectrum *h)
{
    double best = 0.0, Tb = PEAK_T_MIN;
    for (int k = 0; k < PEAK_T_N; k++) {
        double T = PEAK_T_MIN * pow(PEAK_T_MAX / PEAK_T_MIN, (double)k / (PEAK_T_N - 1));
        double sa = rd_spectrum_sa(h, T, h->damping);
        if (sa > best) {
            best = sa;
            Tb = T;
        }
    }
    return Tb;
}

/* Generate, match and write one component; 0, 1 (out of band) or -1. */
static int make_record(const rd_spectrum *h, const rd_evidence_def *d, unsigned long seed,
                       double kv, const char *path, double *qmin, double *qmax, double *pga,
                       rd_error *err)
{
    double T[RD_EVIDENCE_NPERIODS], target[RD_EVIDENCE_NPERIODS];
    for (int i = 0; i < RD_EVIDENCE_NPERIODS; i++) {
        T[i] = d->tmin * pow(d->tmax / d->tmin, (double)i / (RD_EVIDENCE_NPERIODS - 1));
        target[i] = kv * rd_spectrum_sa(h, T[i], h->damping);
    }
    rd_stochastic_def sd;
    rd_stochastic_defaults(&sd);
    sd.duration = d->duration;
    sd.dt = d->dt;
    sd.seed = seed;
    sd.frequency = 1.0 / peak_period(h);
    sd.highpass = 0.1 * sd.frequency; /* stochastic.c's default ratio f_f = f_g / 10 */
    sd.pga = kv * rd_spectrum_pga(h);
    rd_record r;
    memset(&r, 0, sizeof r);
    if (rd_record_stochastic(&r, &sd, err)) return -1;
    int rc = rd_record_match(&r, T, target, RD_EVIDENCE_NPERIODS, h->damping, d->iterations, d->lo,
                             d->hi, qmin, qmax, err);
    rd_im im;
    rd_im_compute(&r, &im);
    *pga = im.pga;
    FILE *f = rc < 0 ? NULL : fopen(path, "w");
    if (rc >= 0 && !f) rc = rd_error_set(err, "%s: cannot write the record", path);
    if (f) {
        fprintf(
            f,
            "# time (s), acceleration (m/s^2): Kanai-Tajimi seed %lu matched to %.4g x the design spectrum "
            "at %.3g damping over %.3g-%.3g s\ntime,acc\n",
            seed, kv, h->damping, d->tmin, d->tmax);
        for (size_t i = 0; i < r.npts; i++) fprintf(f, "%.6f,%.9g\n", (double)i * r.dt, r.acc[i]);
        if (fclose(f)) rc = rd_error_set(err, "%s: cannot write the record", path);
    }
    rd_record_free(&r);
    return rc;
}

/* The scene with its motion replaced by the record files; 0 or -1. */
static int scene_with(rd_scenario *c, const rd_scenario *sc, const char *hpath, const char *vpath,
                      double duration, const char *out, rd_error *err)
{
    if (rd_scenario_copy(c, sc, err)) return -1;
    rd_motion_release(&c->motion);
    rd_motion_def *m = &c->motion;
    m->horizontal.kind = RD_PULSE_NONE;
    m->vertical.kind = RD_PULSE_NONE;
    memset(m->record, 0, sizeof m->record);
    m->scale = RD_SCALE_NONE;
    m->baseline = 4;
    const char *paths[RD_NCOMPONENTS] = { hpath, NULL, vpath };
    for (int k = 0; k < RD_NCOMPONENTS; k++) {
        if (!paths[k]) continue;
        m->record[k].source = RD_SOURCE_TEXT;
        snprintf(m->record[k].path, sizeof m->record[k].path, "%s", paths[k]);
        m->record[k].unit = 1.0; /* m/s^2 */
        if (rd_motion_load(m, k, err)) return -1;
    }
    if (rd_motion_prepare(m, err)) return -1;
    c->duration = duration + EVIDENCE_TAIL;
    snprintf(c->output.path, sizeof c->output.path, "%s", out);
    return 0;
}

/* Run one record; fills the peaks of `body`. 0 or -1. */
static int run_one(const rd_scenario *sc, int body, const char *hpath, const char *vpath,
                   double duration, const char *out, double *tilt, double *slide, int *overturned,
                   rd_error *err)
{
    rd_scenario c;
    memset(&c, 0, sizeof c);
    int rc = scene_with(&c, sc, hpath, vpath, duration, out, err);
    rd_sim *sim = rc ? NULL : rd_sim_create(&c, err);
    if (!rc && (!sim || rd_sim_write_hdf5(sim, out, err))) rc = -1;
    if (!rc) {
        rd_status st = rd_sim_run(sim);
        if (rd_status_failed(st))
            rc = rd_error_set(err, "%s: the run failed (%s): %s", hpath, rd_status_name(st),
                              rd_sim_error(sim));
    }
    if (!rc) {
        rd_summary s;
        rd_sim_summary(sim, &s);
        rc = -1;
        for (int k = 0; k < s.nbodies; k++)
            if (!strcmp(s.body[k].name, sc->bodies[body].name)) {
                *tilt = s.body[k].max_tilt;
                *slide = s.body[k].max_slide;
                *overturned = s.body[k].overturned;
                rc = 0;
            }
        if (rc)
            rd_error_set(err, "%s: body '%s' is not among the run's free bodies", hpath,
                         sc->bodies[body].name);
    }
    rd_sim_free(sim);
    rd_scenario_free(&c);
    return rc;
}

static void mean_sd(const double *x, int n, double *mean, double *sd)
{
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; i++) s += x[i];
    *mean = s / n;
    for (int i = 0; i < n; i++) s2 += (x[i] - *mean) * (x[i] - *mean);
    *sd = n > 1 ? sqrt(s2 / (n - 1)) : 0.0;
}

int rd_assess_evidence(const rd_scenario *sc, int body, const rd_spectrum *h,
                       const rd_evidence_def *d, rd_evidence *out, rd_error *err)
{
    if (d->nrecords < RD_TH_MIN_RECORDS || d->nrecords > RD_EVIDENCE_MAX)
        return rd_error_set(err, "assess: %d records; the time-history evidence needs %d to %d",
                            d->nrecords, RD_TH_MIN_RECORDS, RD_EVIDENCE_MAX);
    if (!d->dir[0])
        return rd_error_set(err,
                            "assess: the time-history evidence needs a folder for its records");
    if (!(d->tmin > 0 && d->tmax > d->tmin))
        return rd_error_set(err, "assess: matching band %g-%g s", d->tmin, d->tmax);
    memset(out, 0, sizeof *out);
    for (int k = 0; k < d->nrecords; k++) {
        char hp[RD_PATH_MAX + 32], vp[RD_PATH_MAX + 32], run[RD_PATH_MAX + 32];
        snprintf(hp, sizeof hp, "%s/record%d_h.csv", d->dir, k + 1);
        snprintf(vp, sizeof vp, "%s/record%d_v.csv", d->dir, k + 1);
        snprintf(run, sizeof run, "%s/run%d.h5", d->dir, k + 1);
        double qmin, qmax, vmin, vmax, vpga;
        int rh =
            make_record(h, d, d->seed + (unsigned long)k, 1.0, hp, &qmin, &qmax, &out->pga[k], err);
        if (rh < 0) return -1;
        int rv = 0;
        if (d->kv > 0) {
            rv = make_record(h, d, d->seed + VERTICAL_SEED_OFFSET + (unsigned long)k, d->kv, vp,
                             &vmin, &vmax, &vpga, err);
            if (rv < 0) return -1;
        }
        out->ratio_min[k] = 1.0 / qmax; /* Sa / target */
        out->ratio_max[k] = 1.0 / qmin;
        out->in_band[k] = rh == 0 && rv == 0;
        if (run_one(sc, body, hp, d->kv > 0 ? vp : NULL, d->duration, run, &out->tilt[k],
                    &out->slide[k], &out->overturned[k], err))
            return -1;
        out->n = k + 1;
    }
    mean_sd(out->tilt, out->n, &out->tilt_mean, &out->tilt_sd);
    mean_sd(out->slide, out->n, &out->slide_mean, &out->slide_sd);
    return 0;
}
