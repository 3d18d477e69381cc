/* rockdem — the DEM's effective coefficient of restitution in free rocking, and the contact
 * restitution (impact loss, contact.c) that reaches a target value (include/rockdem/
 * validate.h). Restitution of the block is a property of the discretised contact: perfectly
 * plastic point impacts (e = 0) at corner subcontacts give Housner's r (the rigid impact keeps
 * the angular momentum about the new pivot); e > 0 lets the pivot rebound and raises r.
 * Folder ensembles/ owns many-run studies (threshold, restitution, sweeps); it may call the
 * public API (engine, scenario, reference) and io/.
 */
#include "rockdem/validate.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RD_CAL_ITER 12 /* secant steps on e in [0, 1] */

/* The free-rocking scene: no motion, the single block tilted by theta0 toward +x (a copy of
 * base the caller frees with rd_scenario_free, also on error). */
static int free_rocking_scene(const rd_scenario *base, double theta0, rd_scenario *sc,
                              double *p, double *alpha, rd_error *err)
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
    *alpha = rs->alpha;
    free(rs);
    /* four impacts from theta0 <= alpha take under 3 quarter periods of the first half-cycle
       (each later one is shorter); 8/p leaves margin */
    sc->duration = 8.0 / *p;
    sc->tail = 0;
    sc->overturn.stop = 1;
    sc->output.interval = fmax(sc->output.interval, 0.05);
    return rc;
}

/* Restitution of one impact from the amplitudes before (a0) and after (a1) it, rad. */
static double decay_ratio(double alpha, double a0, double a1)
{
    double e0 = cos(alpha - a0) - cos(alpha), e1 = cos(alpha - a1) - cos(alpha);
    return e0 > 0 && e1 >= 0 ? sqrt(e1 / e0) : -1.0;
}

int rd_restitution_measure(const rd_scenario *base, double theta0, rd_restitution *out,
                           rd_error *err)
{
    memset(out, 0, sizeof *out);
    out->r = out->r_speed = -1;
    rd_scenario *sc = malloc(sizeof *sc);
    if (!sc) return rd_error_set(err, "out of memory");
    double p = 0, alpha = 0;
    int rc = free_rocking_scene(base, theta0, sc, &p, &alpha, err);
    rd_sim *sim = rc ? NULL : rd_sim_create(sc, err); /* no file: the events are all it needs */
    if (!sim) { rd_scenario_free(sc); free(sc); return -1; }
    rd_status st = rd_sim_run(sim);
    if (st != RD_STATUS_DONE && st != RD_STATUS_OVERTURNED)
        rc = rd_error_set(err, "restitution: %s", rd_sim_error(sim));
    int n, npeak = 0;
    const rd_event *ev = rd_sim_events(sim, &n);
    double w[4];
    for (int k = 0; k < n; k++) {
        if (ev[k].body != 0) continue;
        if (!strcmp(ev[k].type, "peak") && npeak < 4) out->amplitude[npeak++] = ev[k].value;
        if (strcmp(ev[k].type, "impact")) continue;
        if (out->nimpacts < 4) {
            w[out->nimpacts] = ev[k].value;
            out->t_impact[out->nimpacts] = ev[k].time;
        }
        out->nimpacts++;
    }
    out->n = npeak - 1 < 3 ? (npeak > 1 ? npeak - 1 : 0) : 3;
    out->n = out->n < out->nimpacts - 1 ? out->n : (out->nimpacts > 1 ? out->nimpacts - 1 : 0);
    double logsum = 0, logspeed = 0;
    for (int k = 0; k < out->n; k++) {
        out->ratio[k] = decay_ratio(alpha, out->amplitude[k], out->amplitude[k + 1]);
        out->speed_ratio[k] = w[k + 1] / w[k];
        if (out->ratio[k] <= 0) { out->n = k; break; }
        logsum += log(out->ratio[k]);
        logspeed += log(out->speed_ratio[k]);
    }
    if (out->n > 0) {
        out->r = exp(logsum / out->n);
        out->r_speed = exp(logspeed / out->n);
    }
    rd_sim_free(sim);
    rd_scenario_free(sc);
    free(sc);
    return rc;
}

/* r at contact restitution e. */
static int r_at(const rd_scenario *base, double theta0, double e, double *r, rd_error *err)
{
    rd_scenario *sc = malloc(sizeof *sc);
    if (!sc) return rd_error_set(err, "out of memory");
    *sc = *base;
    sc->contact.restitution = e;
    rd_restitution m;
    int rc = rd_restitution_measure(sc, theta0, &m, err);
    free(sc);
    if (rc == 0 && m.r < 0)
        rc = rd_error_set(err, "restitution: fewer than two impacts at contact restitution %g "
                               "(the block does not rock freely)", e);
    *r = m.r;
    return rc;
}

int rd_restitution_calibrate(const rd_scenario *sc, double theta0, double target, double *e,
                             double *reached, rd_error *err)
{
    double r0, r1;
    if (r_at(sc, theta0, 0.0, &r0, err)) return -1;
    if (r_at(sc, theta0, 1.0, &r1, err)) return -1;
    if (target <= r0 + RD_CAL_RTOL || target >= r1 - RD_CAL_RTOL) {
        int low = target <= r0 + RD_CAL_RTOL;
        *e = low ? 0.0 : 1.0;
        *reached = low ? r0 : r1;
        return fabs(target - *reached) < RD_CAL_RTOL ? 0 : 1;
    }
    /* r(e) is smooth and monotonic: secant steps kept inside the bracket (regula falsi,
       Illinois variant), then bisection if it stalls */
    double lo = 0, hi = 1, flo = r0 - target, fhi = r1 - target;
    for (int it = 0; it < RD_CAL_ITER; it++) {
        double mid = (lo * fhi - hi * flo) / (fhi - flo);
        if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
        double r;
        if (r_at(sc, theta0, mid, &r, err)) return -1;
        *e = mid;
        *reached = r;
        if (fabs(r - target) < RD_CAL_RTOL) return 0;
        if ((r - target) * flo > 0) { lo = mid; flo = r - target; fhi *= 0.5; }
        else { hi = mid; fhi = r - target; flo *= 0.5; }
    }
    return 1;
}
