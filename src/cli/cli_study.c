/* rockdem — `rockdem study SCENARIO [--set k=v]...`: what accuracy the scenario's settings buy.
 * The scene runs at KN x {0.1, 1, 10} and time-step safety x {2, 1, 0.5} (capped at 1); the
 * finest of them (KN x 10, safety x 0.5) is the yardstick. For each run the table gives the wall
 * time and the differences from the yardstick: max tilt (relative), first impact time (s),
 * overturning (same or not). A user reads off which settings reach a given accuracy and what
 * they cost; the rigid-block references (rockdem reference, make study) check the yardstick.
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct study_run {
    double kn, safety; /* Pa/m, fraction of the critical step */
    double dt;         /* s */
    double wall;       /* s, shaking stage */
    double max_tilt;   /* rad, largest over the free bodies */
    double t_impact;   /* s, first impact of any body, -1 if none */
    int overturned;
    int status;
} study_run;

static int run_one(const rd_scenario *base, double kn, double safety, study_run *r, rd_error *err)
{
    rd_scenario *sc = malloc(sizeof *sc);
    if (!sc) return rd_error_set(err, "out of memory");
    *sc = *base;
    sc->contact.ks *= kn / sc->contact.kn; /* keep KS / KN */
    sc->contact.kn = kn;
    sc->timestep = (rd_timestep_def){ RD_TIMESTEP_AUTO, safety, 0 };
    *r = (study_run){ .kn = kn, .safety = safety, .t_impact = -1 };
    rd_sim *sim = rd_sim_create(sc, err);
    int rc = -1;
    if (sim) {
        r->status = rd_sim_run(sim);
        rd_summary s;
        rd_sim_summary(sim, &s);
        r->dt = s.dt;
        r->wall = s.wall_seconds;
        r->overturned = s.any_overturned;
        for (int k = 0; k < s.nbodies; k++) r->max_tilt = fmax(r->max_tilt, s.body[k].max_tilt);
        int n;
        const rd_event *ev = rd_sim_events(sim, &n);
        for (int k = 0; k < n && r->t_impact < 0; k++)
            if (!strcmp(ev[k].type, "impact")) r->t_impact = ev[k].time;
        rd_sim_free(sim);
        rc = 0;
    }
    free(sc);
    return rc;
}

static void print_row(const study_run *r, const study_run *ref)
{
    printf("%9.2e %6.3f %9.2e %8.3f %10.4g %10.2e", r->kn, r->safety, r->dt, r->wall, r->max_tilt,
           ref->max_tilt > 0 ? fabs(r->max_tilt - ref->max_tilt) / ref->max_tilt : 0.0);
    if (r->t_impact >= 0 && ref->t_impact >= 0)
        printf(" %10.2e", fabs(r->t_impact - ref->t_impact));
    else
        printf(" %10s", r->t_impact < 0 && ref->t_impact < 0 ? "none" : "missing");
    printf(" %5s %s\n", r->overturned == ref->overturned ? "same" : "DIFF",
           rd_status_name((rd_status)r->status));
}

/* The study's KN factors (the largest is the yardstick's) and step safety factors. */
static const double kf[] = { 0.1, 1, 10 }, sf[] = { 2, 1, 0.5 };

/* Are the study's stiffnesses KN x 0.1 .. KN x 10 within the scenario limits of KN
 * (docs/LIMITS.md)? 0, or -1 with err: a yardstick above 1e15 Pa/m ran for minutes at a step
 * below 1e-9 s before any row was printed. */
static int kn_range_ok(const rd_scenario *sc, rd_error *err)
{
    double lo, hi, kn = sc->contact.kn;
    rd_scenario_limit("stiffness-normal", &lo, &hi);
    if (kf[0] * kn < lo || kf[2] * kn > hi)
        return rd_error_set(
            err,
            "rockdem study: %s: the study runs KN x %g to x %g (%.3g to %.3g Pa/m), outside "
            "stiffness-normal's range [%g, %g] Pa/m; give KN from %g to %g",
            sc->file, kf[0], kf[2], kf[0] * kn, kf[2] * kn, lo, hi, lo / kf[0], hi / kf[2]);
    return 0;
}

int rd_cli_study(int argc, char **argv)
{
    rd_scenario sc;
    rd_error err;
    if (rd_cli_scenario(&sc, argc, argv, NULL, NULL, NULL)) {
        rd_scenario_free(&sc);
        return 2;
    }
    if (kn_range_ok(&sc, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        rd_scenario_free(&sc);
        return 2;
    }
    double kn = sc.contact.kn, safety = sc.timestep.safety;
    study_run ref, runs[9];
    rd_cli_progress_start("study", 10); /* the yardstick and 3 x 3 settings */
    int rc = run_one(&sc, 10 * kn, 0.5 * safety, &ref, &err);
    for (int i = 0; rc == 0 && i < 3; i++)
        for (int j = 0; rc == 0 && j < 3; j++)
            rc = run_one(&sc, kf[i] * kn, fmin(1.0, sf[j] * safety), &runs[3 * i + j], &err);
    rd_cli_progress_stop();
    if (rc) {
        fprintf(stderr, "%s\n", err.msg);
        rd_scenario_free(&sc);
        return 3;
    }
    printf(
        "study of %s: yardstick KN %.3g Pa/m, safety %.3g (max tilt %.6g rad, first impact %.6g s, %s)\n",
        sc.file, ref.kn, ref.safety, ref.max_tilt, ref.t_impact,
        ref.overturned ? "overturned" : "stood");
    printf("%9s %6s %9s %8s %10s %10s %10s %5s %s\n", "KN", "safety", "dt_s", "wall_s", "max_tilt",
           "tilt_err", "impact_dt", "fall", "status");
    for (int k = 0; k < 9; k++) print_row(&runs[k], &ref);
    printf("tilt_err: |max tilt - yardstick| / yardstick; impact_dt: |first impact time - "
           "yardstick| (s); fall: same overturning verdict as the yardstick\n");
    rd_scenario_free(&sc);
    return 0;
}
