/* rockdem — minimum overturning amplitude of a scenario's horizontal pulse, with the DEM or the
 * rigid reference (include/rockdem/validate.h explains what the search finds).
 * Folder ensembles/ owns many-run studies (threshold, restitution, sweeps); it may call the
 * public API (engine, scenario, reference) and io/.
 */
#include "rockdem/validate.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

rd_threshold_opts rd_threshold_opts_default(void)
{
    return (rd_threshold_opts){.lo = 0, .hi = 0, .nscan = 24, .rtol = 0.005};
}

/* DEM run (no file: only the summary is needed); *over = any free body overturned. */
static int dem_overturns(const rd_scenario *base, double amplitude, int *over, rd_error *err)
{
    rd_scenario *sc = malloc(sizeof *sc);
    if (!sc) return rd_error_set(err, "out of memory");
    *sc = *base;
    sc->motion.horizontal.amplitude = amplitude;
    sc->output.interval = fmax(sc->output.interval, 0.05); /* a coarse sampling: no history kept */
    rd_sim *sim = rd_sim_create(sc, err);
    int rc = -1;
    if (sim) {
        rd_status st = rd_sim_run(sim);
        rd_summary sum;
        rd_sim_summary(sim, &sum);
        *over = sum.any_overturned;
        rc = 0;
        if (rd_status_failed(st)) /* no outcome: unstable, or an untrusted energy balance */
            rc = rd_error_set(err, "run at %.4g m/s^2: %s", amplitude, rd_sim_error(sim));
        rd_sim_free(sim);
    }
    free(sc);
    return rc;
}

static int ref_overturns(const rd_scenario *base, double amplitude, int *over, rd_error *err)
{
    rd_scenario *sc = malloc(sizeof *sc);
    rd_refscene *rs = malloc(sizeof *rs);
    rd_ref_result res = {0};
    int rc = -1;
    if (!sc || !rs) { rd_error_set(err, "out of memory"); goto done; }
    *sc = *base;
    sc->motion.horizontal.amplitude = amplitude;
    sc->output.interval = sc->duration; /* no history needed */
    if (rd_refscene_map(sc, rs, err)) goto done;
    rc = rd_refscene_solve(sc, rs, &res, err);
    /* a pivot that lifts off (the block jumps) ends the rigid model: its own outcome */
    *over = res.summary.lifted_off ? RD_LIFTS_OFF : res.summary.overturned;
done:
    rd_ref_result_free(&res);
    free(sc);
    free(rs);
    return rc;
}

int rd_overturns(const rd_scenario *sc, rd_engine engine, double amplitude, int *over,
                 rd_error *err)
{
    return engine == RD_ENGINE_DEM ? dem_overturns(sc, amplitude, over, err)
                                   : ref_overturns(sc, amplitude, over, err);
}

/* Static uplift threshold (m/s^2) and w/p of the scene's lower block. */
static int scene_scales(const rd_scenario *sc, rd_threshold_result *out, rd_error *err)
{
    rd_refscene *rs = malloc(sizeof *rs);
    if (!rs) return rd_error_set(err, "out of memory");
    int rc = rd_refscene_map(sc, rs, err);
    if (rc == 0) {
        out->static_amp = sc->gravity * tan(rs->alpha);
        if (rs->model == RD_REFMODEL_KOUNADIS) {
            double stack, upper;
            rd_kounadis_uplift_thresholds(&rs->kounadis, &stack, &upper);
            out->static_amp = sc->gravity * fmin(stack, upper);
        }
        out->w_over_p = 2 * M_PI * sc->motion.horizontal.frequency / rs->p;
    }
    free(rs);
    return rc;
}

int rd_threshold(const rd_scenario *sc, rd_engine engine, const rd_threshold_opts *opts,
                 rd_threshold_result *out, rd_error *err)
{
    memset(out, 0, sizeof *out);
    if (sc->motion.horizontal.kind == RD_PULSE_NONE)
        return rd_error_set(err, "%s: threshold: the scenario has no horizontal pulse to scale",
                            sc->file);
    if (scene_scales(sc, out, err)) return -1;
    double lo = opts->lo > 0 ? opts->lo : 0.9 * out->static_amp;
    double hi = opts->hi > 0 ? opts->hi : 10 * out->static_amp;
    int n = opts->nscan > 0 ? opts->nscan : 24, over = 0;
    if (!(hi > lo) || !(opts->rtol > 0))
        return rd_error_set(err, "threshold: need 0 < lo < hi and rtol > 0 (got lo %g, hi %g, "
                                 "rtol %g)", lo, hi, opts->rtol);
    /* coarse scan up from lo: the first amplitude that overturns closes the first bracket */
    double below = lo, above = -1;
    /* (a reference run that lifts off ends the search like an overturning one: the bracket then
       closes on the onset of jumping, reported as such) */
    for (int k = 0; k <= n && above < 0; k++) {
        double a = lo + (hi - lo) * k / n;
        if (rd_overturns(sc, engine, a, &over, err)) return -1;
        out->runs++;
        if (over) { above = a; out->lifted_off = over == RD_LIFTS_OFF; }
        else below = a;
    }
    if (above < 0) return 0;
    if (above == lo) { out->found = 1; out->amplitude = out->below = lo; return 0; }
    while ((above - below) / above > opts->rtol) {
        double mid = 0.5 * (below + above);
        if (rd_overturns(sc, engine, mid, &over, err)) return -1;
        out->runs++;
        if (over) { above = mid; out->lifted_off = over == RD_LIFTS_OFF; }
        else below = mid;
    }
    out->found = 1;
    out->amplitude = above;
    out->below = below;
    return 0;
}
