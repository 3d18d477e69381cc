/* rockdem — the DEM's effective coefficient of restitution in free rocking, and the viscous
 * damping ratio that reaches a target value (include/rockdem/validate.h). Restitution is a
 * property of the discretised contact (DESIGN.md section 2): corner subcontacts with a normal
 * dashpot reach Housner's r; a bed of many points rolls the pivot across the base and saturates
 * near 0.82-0.85 however strong the damping, which the calibration reports as unreachable.
 * Folder ensembles/ owns many-run studies (threshold, restitution, sweeps); it may call the
 * public API (engine, scenario, reference) and io/.
 */
#include "rockdem/validate.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RD_CAL_RTOL 0.002 /* calibration stops when |r - target| < this (about the scatter of
                             r between impacts at stiff KN) */
#define RD_CAL_ITER 14    /* bisection steps on zeta in [0, 1]: resolution 6e-5 */

/* The free-rocking scene: no motion, the single block tilted by theta0 toward +x (a copy of
 * base the caller frees with rd_scenario_free, also on error). */
static int free_rocking_scene(const rd_scenario *base, double theta0, rd_scenario *sc,
                              double *p, rd_error *err)
{
    if (rd_scenario_copy(sc, base, err)) return -1;
    rd_motion_release(&sc->motion);
    memset(&sc->motion, 0, sizeof sc->motion);
    int k = -1, nfree = 0;
    for (int i = 0; i < sc->nbodies; i++)
        if (!sc->bodies[i].fixed) { k = i; nfree++; }
    if (nfree != 1)
        return rd_error_set(err, "%s: restitution: needs exactly one free block (found %d)",
                            base->file, nfree);
    sc->bodies[k].tilt = theta0;
    sc->bodies[k].tilt_direction = 0;
    rd_refscene *rs = malloc(sizeof *rs);
    if (!rs) return rd_error_set(err, "out of memory");
    int rc = rd_refscene_map(sc, rs, err);
    if (rc == 0 && !(theta0 > 0 && theta0 < rs->alpha))
        rc = rd_error_set(err, "restitution: release angle %g rad must be in (0, alpha = %g)",
                          theta0, rs->alpha);
    *p = rs->p;
    free(rs);
    /* four impacts from theta0 <= alpha take under 3 quarter periods of the first half-cycle
       (each later one is shorter); 8/p leaves margin */
    sc->duration = 8.0 / *p;
    sc->tail = 0;
    sc->overturn.stop = 1;
    sc->output.interval = fmax(sc->output.interval, 0.05);
    return rc;
}

int rd_restitution_measure(const rd_scenario *base, double theta0, rd_restitution *out,
                           rd_error *err)
{
    memset(out, 0, sizeof *out);
    out->r = -1;
    rd_scenario *sc = malloc(sizeof *sc);
    if (!sc) return rd_error_set(err, "out of memory");
    double p;
    int rc = free_rocking_scene(base, theta0, sc, &p, err);
    rd_sim *sim = rc ? NULL : rd_sim_create(sc, err); /* no file: the events are all it needs */
    if (!sim) { rd_scenario_free(sc); free(sc); return -1; }
    rd_status st = rd_sim_run(sim);
    if (st == RD_STATUS_UNSTABLE || st == RD_STATUS_IO_ERROR)
        rc = rd_error_set(err, "restitution: %s", rd_sim_error(sim));
    int n;
    const rd_event *ev = rd_sim_events(sim, &n);
    double w[4];
    for (int k = 0; k < n; k++) {
        if (strcmp(ev[k].type, "impact") || ev[k].body != 0) continue;
        if (out->nimpacts < 4) {
            w[out->nimpacts] = ev[k].value;
            out->t_impact[out->nimpacts] = ev[k].time;
        }
        out->nimpacts++;
    }
    out->n = out->nimpacts < 4 ? (out->nimpacts > 0 ? out->nimpacts - 1 : 0) : 3;
    double logsum = 0;
    for (int k = 0; k < out->n; k++) {
        out->ratio[k] = w[k + 1] / w[k];
        logsum += log(out->ratio[k]);
    }
    if (out->n > 0) out->r = exp(logsum / out->n);
    rd_sim_free(sim);
    rd_scenario_free(sc);
    free(sc);
    return rc;
}

/* r at damping ratio zeta (0: no damping). */
static int r_at(const rd_scenario *base, double theta0, double zeta, double *r, rd_error *err)
{
    rd_scenario *sc = malloc(sizeof *sc);
    if (!sc) return rd_error_set(err, "out of memory");
    *sc = *base;
    sc->damping = (rd_damping_def){zeta > 0 ? RD_DAMPING_VISCOUS : RD_DAMPING_NONE, zeta};
    rd_restitution m;
    int rc = rd_restitution_measure(sc, theta0, &m, err);
    free(sc);
    if (rc == 0 && m.r < 0)
        rc = rd_error_set(err, "restitution: fewer than two impacts at damping ratio %g "
                               "(the block does not rock freely)", zeta);
    *r = m.r;
    return rc;
}

int rd_restitution_calibrate(const rd_scenario *sc, double theta0, double target, double *zeta,
                             double *reached, rd_error *err)
{
    /* bracket [0, zmax]: critical damping first; over-critical dashpots (up to a ratio of 10,
       the scenario's limit) only when the target lies below r at ratio 1 — with corner
       subcontacts Housner's r needs about 4 (the time step shrinks by sqrt(1 + l^2) - l) */
    double r0, r1, zmax = 1.0;
    if (r_at(sc, theta0, 0.0, &r0, err) || r_at(sc, theta0, zmax, &r1, err)) return -1;
    while (target < r1 - RD_CAL_RTOL && zmax < 10.0) {
        zmax = fmin(10.0, 2.5 * zmax);
        if (r_at(sc, theta0, zmax, &r1, err)) return -1;
    }
    if (target >= r0 - RD_CAL_RTOL || target <= r1 + RD_CAL_RTOL) {
        int high = target >= r0 - RD_CAL_RTOL;
        *zeta = high ? 0.0 : zmax;
        *reached = high ? r0 : r1;
        return fabs(target - *reached) < RD_CAL_RTOL ? 0 : 1;
    }
    double lo = 0, hi = zmax, r = r0; /* r(lo) > target > r(hi) */
    for (int it = 0; it < RD_CAL_ITER; it++) {
        double mid = 0.5 * (lo + hi);
        if (r_at(sc, theta0, mid, &r, err)) return -1;
        *zeta = mid;
        *reached = r;
        if (fabs(r - target) < RD_CAL_RTOL) return 0;
        if (r > target) lo = mid;
        else hi = mid;
    }
    return 0;
}
