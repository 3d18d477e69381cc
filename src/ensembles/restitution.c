/* rockdem — the DEM's effective coefficient of restitution in free rocking, and the contact
 * restitution (impact loss, contact.c) that reaches a target value (include/rockdem/
 * validate.h). Restitution of the block is a property of the discretised contact: perfectly
 * plastic point impacts (e = 0) at corner subcontacts give Housner's r (the rigid impact keeps
 * the angular momentum about the new pivot); e > 0 lets the pivot rebound and raises r.
 * Folder ensembles/ owns many-run studies (threshold, restitution, sweeps); it may call the
 * public API (engine, scenario, reference) and io/.
 */
#include "rockdem/validate.h"
#include "rockdem/observer.h"
#include "rockdem/check.h"
#include "base/vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RD_CAL_ITER          12 /* secant steps on the loss parameter inside one bracket */
/* The speeds either side of impact k are averaged over the band of |theta| from RD_BAND_LO to
 * RD_BAND_HI times the smaller of the two amplitudes around it, the same band on both sides:
 * outside the impact (the compliant impact turns the block through about 1e-5 rad at KN
 * 1e10), where the block rocks freely on one corner. The average over the band spans many
 * periods of the block's vibration on its contact springs (under 2 ms at KN >= 1e10 against
 * a band crossed in tens of ms), which would otherwise put about 1 % of scatter on one
 * sample. */
#define RD_BAND_LO           0.25
#define RD_BAND_HI           0.75
/* A swing (a run of one sign of theta) starts once |theta| exceeds this fraction of the
 * release angle: below it the block is in the impact, where the compliant contact lets theta
 * jitter about 0. */
#define RD_SWING_EPS         1e-3
#define RD_NRATIO            3         /* impacts whose restitution is averaged */
#define RD_LOG_STEP          (1 << 15) /* samples the speed log grows by */
#define RD_SAMPLE_EVERY_STEP 1e-12     /* s: output interval below any step: every step sampled */

/* Signed in-plane rocking and squared angular speed of the free block at every step, until
 * the swing after impact RD_NRATIO + 1 begins (the amplitudes of the ratios are then known). */
typedef struct speed_log {
    size_t n, cap;
    double *th, *w2;  /* rad, rad^2/s^2 */
    double eps;       /* rad: |theta| below which no swing begins (RD_SWING_EPS x release) */
    int sign, swings; /* sign of the current swing, swings begun */
    int done;         /* 1: the log is complete and the run was stopped */
} speed_log;

static int speed_log_sample(void *user, rd_sim *sim, const rd_sample *s, rd_error *err)
{
    speed_log *lg = user;
    if (lg->n == lg->cap) {
        size_t cap = lg->cap + RD_LOG_STEP;
        double *th = realloc(lg->th, cap * sizeof *th);
        if (th) lg->th = th;
        double *w2 = th ? realloc(lg->w2, cap * sizeof *w2) : NULL;
        if (!w2) return rd_error_set(err, "restitution: out of memory logging the speed");
        lg->w2 = w2;
        lg->cap = cap;
    }
    double th = s->rotation[0];
    lg->th[lg->n] = th;
    lg->w2[lg->n++] = rd_dot(s->angular_velocity, s->angular_velocity);
    int sg = th > lg->eps ? 1 : th < -lg->eps ? -1 : lg->sign;
    if (sg != lg->sign) {
        lg->sign = sg;
        lg->swings++;
    }
    if (lg->swings == RD_NRATIO + 2) {
        lg->done = 1;
        rd_sim_stop(sim);
    }
    return 0;
}

/* Squared angular speed the block would have upright (theta = 0), carried there from (theta,
 * w^2) by free rocking on the corner it leans over: 0.5 w^2 + p^2 cos(alpha - |theta|) is
 * conserved (rad^2/s^2). */
static double upright_w2(double p, double alpha, double th, double w2)
{
    return w2 + 2 * p * p * (cos(alpha - fabs(th)) - cos(alpha));
}

/* Mean of upright_w2 over the samples i0 .. i1 (step +1 or -1) whose |theta| lies in [lo, hi]. */
static double band_mean(const speed_log *lg, double p, double alpha, size_t i0, size_t i1,
                        double lo, double hi)
{
    double sum = 0;
    int n = 0;
    for (size_t i = i0;; i += i1 > i0 ? 1 : (size_t)-1) {
        double t = fabs(lg->th[i]);
        if (t >= lo && t <= hi) {
            sum += upright_w2(p, alpha, lg->th[i], lg->w2[i]);
            n++;
        }
        if (i == i1) break;
    }
    return n ? sum / n : -1;
}

/* Restitution of impacts 1 .. nmax from the speed log: the speed arriving through the band
 * of |theta| before the impact and leaving through the same band after it, both carried to
 * theta = 0 (rigid theory's instant of impact) by energy. Returns the number of ratios. */
static int speed_ratios(const speed_log *lg, double p, double alpha, double *ratio, int nmax)
{
    size_t start[5] = { 0 }, end[5] = { 0 }, top[5] = { 0 };
    double peak[5] = { 0 };
    int ns = 0, sign = 0;
    for (size_t i = 0; i < lg->n; i++) {
        double t = lg->th[i];
        if (fabs(t) <= lg->eps) continue;
        int sg = t > 0 ? 1 : -1;
        if (sg != sign) {
            if (ns == nmax + 2) break; /* swing nmax + 1 is complete */
            start[ns] = i;
            sign = sg;
            ns++;
        }
        end[ns - 1] = i;
        if (fabs(t) > peak[ns - 1]) {
            peak[ns - 1] = fabs(t);
            top[ns - 1] = i;
        }
    }
    int n = ns - 2 < nmax ? ns - 2 : nmax; /* impact k needs swing k + 1 complete */
    for (int k = 0; k < n; k++) {
        double amp = fmin(peak[k], peak[k + 1]), lo = RD_BAND_LO * amp, hi = RD_BAND_HI * amp;
        double before = band_mean(lg, p, alpha, top[k], end[k], lo, hi);
        double after = band_mean(lg, p, alpha, start[k + 1], top[k + 1], lo, hi);
        ratio[k] = before > 0 && after > 0 ? sqrt(after / before) : -1;
    }
    return n > 0 ? n : 0;
}

int rd_rocking_scales_of(const rd_scenario *sc, rd_rocking_scales *out, rd_error *err)
{
    memset(out, 0, sizeof *out);
    int nfree = 0;
    for (int i = 0; i < sc->nbodies; i++) nfree += !sc->bodies[i].fixed;
    if (nfree != 1)
        return rd_error_set(
            err,
            "%s: restitution: needs exactly one free body (found %d): an assembly's free "
            "rocking opens its joints each at its own time, no single sequence of impacts to "
            "measure; give --body NAME to calibrate the joint under NAME on NAME's own free "
            "rocking (what holds it up fixed, the bodies above it removed)",
            sc->file, nfree);
    rd_refscene *rs = malloc(sizeof *rs);
    if (!rs) return rd_error_set(err, "out of memory");
    rd_error ref_err;
    if (rd_refscene_map(sc, rs, &ref_err) == 0 && rs->model == RD_REFMODEL_HOUSNER &&
        !rs->equivalent) {
        *out = (rd_rocking_scales){
            .alpha = rs->alpha, .p = rs->p, .R = hypot(rs->b[0], rs->h[0]), .lean = 0, .housner = 1
        };
        free(rs);
        return 0;
    }
    free(rs);
    rd_check_report rep;
    if (rd_check_scene(sc, &rep, err)) return -1;
    for (int i = 0; i < rep.nbodies; i++)
        if (!rep.body[i].fixed)
            *out = (rd_rocking_scales){ .alpha = rep.body[i].alpha_tower,
                                        .p = rep.body[i].p_tower,
                                        .R = rep.body[i].R_tower,
                                        .lean = rep.body[i].lean_tower };
    rd_check_free(&rep);
    if (!(out->alpha > 0 && out->p > 0))
        return rd_error_set(
            err,
            "%s: restitution: the free body does not stand on a base it can rock on "
            "(tipping angle %.3g deg)",
            sc->file, out->alpha * 180 / M_PI);
    return 0;
}

/* keep[i] = 1 for body b, the chain of bodies it rests on as placed (rd_check_scene), and every
 * fixed body; 0 for every other body (those standing on b or beside its chain). */
static int support_chain(const rd_scenario *sc, int b, int *keep, rd_error *err)
{
    rd_check_report rep;
    if (rd_check_scene(sc, &rep, err)) return -1;
    for (int i = 0; i < sc->nbodies; i++) keep[i] = sc->bodies[i].fixed;
    for (int j = b; j >= 0 && !keep[j]; j = rep.body[j].rests_on) keep[j] = 1;
    keep[b] = 1;
    rd_check_free(&rep);
    return 0;
}

int rd_restitution_isolate(const rd_scenario *sc, const char *name, rd_scenario *out, rd_error *err)
{
    int b = -1;
    for (int i = 0; i < sc->nbodies && b < 0; i++)
        if (!strcmp(sc->bodies[i].name, name)) b = i;
    if (b < 0)
        return rd_error_set(err, "%s: restitution: --body: no body named '%s'", sc->file, name);
    if (sc->bodies[b].fixed)
        return rd_error_set(err, "%s: restitution: --body '%s' is fixed: it does not rock",
                            sc->file, name);
    int *keep = malloc((size_t)sc->nbodies * sizeof *keep);
    if (!keep) return rd_error_set(err, "out of memory");
    int rc = support_chain(sc, b, keep, err) || rd_scenario_copy(out, sc, err) ? -1 : 0;
    if (rc) {
        free(keep);
        return -1;
    }
    int n = 0;
    for (int i = 0; i < out->nbodies; i++) {
        if (!keep[i]) {
            free(out->bodies[i].verts);
            continue;
        }
        out->bodies[n] = out->bodies[i];
        out->bodies[n].fixed |= i != b; /* what holds b up does not move */
        n++;
    }
    out->nbodies = n;
    out->nhistories = 0; /* they may name removed bodies; the measurement keeps none */
    /* the calibrated loss (e, or the dashpot's ratio) acts on b's joint, whatever set it */
    const unsigned loss = rd_restitution_by_dashpot(sc) ? RD_JOINT_RESTITUTION | RD_JOINT_DAMPING
                                                        : RD_JOINT_RESTITUTION;
    for (int j = 0; j < out->njoints; j++) out->joint[j].set &= ~loss;
    free(keep);
    return 0;
}

double rd_rigid_restitution(const rd_rocking_scales *s, double gravity)
{
    double sa = sin(s->alpha);
    return 1 - 2 * s->p * s->p * s->R * sa * sa / gravity;
}

/* The surface model's scan of its dashpot ratio (validate.h): on the 0.5 x 0.5 x 1.0 m block
 * (h/b = 2) r falls from 0.913 at 0.05 through 0.850 at 0.3, 0.780 at 1 and 0.719 at 2.5 to
 * 0.656 at 5 (docs/CONTACT.md section 8.6), so the grid brackets every r from below Housner's
 * (0.70) to the highest steady one; below 0.05 the block's vibration on its joint is not damped
 * out between impacts and the ratios scatter. */
static const double CAL_ZETA[RD_CAL_GRID + 1] = { 0.05, 0.3, 1.0, 2.5, 5.0 };

int rd_restitution_by_dashpot(const rd_scenario *sc)
{
    return sc->contact.model == RD_CONTACT_SURFACE;
}

double rd_restitution_loss_at(const rd_scenario *sc, int k)
{
    return rd_restitution_by_dashpot(sc) ? CAL_ZETA[k] : (double)k / RD_CAL_GRID;
}

void rd_restitution_set_loss(rd_scenario *sc, double x)
{
    if (!rd_restitution_by_dashpot(sc)) {
        sc->contact.restitution = x;
        return;
    }
    sc->contact.restitution = 1; /* the surface model's joint: no permanent set */
    sc->damping.kind = RD_DAMPING_VISCOUS;
    sc->damping.value = x;
}

/* The free-rocking scene: no motion, the single body tilted by theta0 towards the side it tips
 * to first (rd_rocking_scales_of; +x for a brick), its in-plane rocking measured in that plane (a
 * copy of base the caller frees with rd_scenario_free, also on error). */
static int free_rocking_scene(const rd_scenario *base, double theta0, rd_scenario *sc, double *p,
                              double *alpha, rd_error *err)
{
    rd_rocking_scales rk;
    if (rd_scenario_copy(sc, base, err)) return -1;
    if (rd_rocking_scales_of(base, &rk, err)) return -1;
    rd_motion_release(&sc->motion);
    memset(&sc->motion, 0, sizeof sc->motion);
    sc->motion.horizontal.direction = rk.lean; /* no motion: the plane of in-plane rocking */
    for (int i = 0; i < sc->nbodies; i++)
        if (!sc->bodies[i].fixed) {
            sc->bodies[i].tilt = theta0;
            sc->bodies[i].tilt_direction = rk.lean;
        }
    int rc = 0;
    if (!(theta0 > 0 && theta0 < rk.alpha))
        rc = rd_error_set(err, "restitution: release angle %g rad must be in (0, alpha = %g)",
                          theta0, rk.alpha);
    *p = rk.p;
    *alpha = rk.alpha;
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
    sc->output.interval = RD_SAMPLE_EVERY_STEP;
    sc->threads = 1; /* one rocking block: nothing to share out (and a worker process's run) */
    rd_sim *sim = rc ? NULL : rd_sim_create(sc, err); /* no file: events and the speed log */
    speed_log lg = { .eps = RD_SWING_EPS * theta0 };
    rd_observer obs = { .user = &lg, .sample = speed_log_sample };
    if (sim && rd_sim_add_observer(sim, &obs, err)) {
        rd_sim_free(sim);
        sim = NULL;
    }
    if (!sim) {
        rd_scenario_free(sc);
        free(sc);
        return -1;
    }
    rd_status st = rd_sim_run(sim);
    if (st != RD_STATUS_DONE && st != RD_STATUS_OVERTURNED &&
        !(st == RD_STATUS_INTERRUPTED && lg.done))
        rc = rd_error_set(err, "restitution: %s", rd_sim_error(sim));
    int n, npeak = 0;
    const rd_event *ev = rd_sim_events(sim, &n);
    for (int k = 0; k < n; k++) {
        if (ev[k].body != 0) continue;
        if (!strcmp(ev[k].type, "peak") && npeak < 4) out->amplitude[npeak++] = ev[k].value;
        if (strcmp(ev[k].type, "impact")) continue;
        if (out->nimpacts < 4) out->t_impact[out->nimpacts] = ev[k].time;
        out->nimpacts++;
    }
    out->n = npeak - 1 < 3 ? (npeak > 1 ? npeak - 1 : 0) : 3;
    out->n = out->n < out->nimpacts - 1 ? out->n : (out->nimpacts > 1 ? out->nimpacts - 1 : 0);
    int nspeed = speed_ratios(&lg, p, alpha, out->speed_ratio, RD_NRATIO);
    out->n = out->n < nspeed ? out->n : nspeed;
    free(lg.th);
    free(lg.w2);
    double logsum = 0, logspeed = 0;
    for (int k = 0; k < out->n; k++) {
        out->ratio[k] = decay_ratio(alpha, out->amplitude[k], out->amplitude[k + 1]);
        if (out->ratio[k] <= 0 || out->speed_ratio[k] <= 0) {
            out->n = k;
            break;
        }
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

/* Fewer than two impacts: the block does not rock freely (an error for the calibration). */
static int too_few(const rd_scenario *sc, const rd_restitution *m, double x, rd_error *err)
{
    if (m->r >= 0) return 0;
    return rd_error_set(
        err, "restitution: fewer than two impacts at %s %g (the block does not rock freely)",
        rd_restitution_by_dashpot(sc) ? "dashpot ratio" : "contact restitution", x);
}

/* The measurement at loss parameter x (rd_restitution_set_loss). */
static int measure_at(const rd_scenario *base, double theta0, double x, rd_restitution *m,
                      rd_error *err)
{
    rd_scenario *sc = malloc(sizeof *sc);
    if (!sc) return rd_error_set(err, "out of memory");
    *sc = *base;
    rd_restitution_set_loss(sc, x);
    int rc = rd_restitution_measure(sc, theta0, m, err);
    free(sc);
    return rc ? rc : too_few(base, m, x, err);
}

/* Regula falsi (Illinois variant) for r(e) = target inside a bracket [lo, hi] where r - target
 * changes sign (flo, fhi); bisection when a step leaves it. *e, *reached and *at hold the
 * closest measurement so far (the caller's on entry) and are replaced by closer ones. Returns 0
 * once within rtol, 2 when RD_CAL_ITER steps do not get there (r(e) too uneven inside
 * the bracket: the block slides or bounces), -1 on error. */
static int refine(const rd_scenario *sc, double theta0, double target, double rtol, double lo,
                  double hi, double flo, double fhi, double *e, double *reached, rd_restitution *at,
                  rd_error *err)
{
    for (int it = 0; it < RD_CAL_ITER; it++) {
        double mid = (lo * fhi - hi * flo) / (fhi - flo);
        if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
        rd_restitution m;
        if (measure_at(sc, theta0, mid, &m, err)) return -1;
        double r = m.r;
        if (fabs(r - target) < fabs(*reached - target)) {
            *e = mid;
            *reached = r;
            *at = m;
        }
        if (fabs(r - target) < rtol) return 0;
        if ((r - target) * flo > 0) {
            lo = mid;
            flo = r - target;
            fhi *= 0.5;
        } else {
            hi = mid;
            fhi = r - target;
            flo *= 0.5;
        }
    }
    return 2;
}

int rd_restitution_calibrate(const rd_scenario *sc, double theta0, double target, double *e,
                             double *reached, rd_error *err)
{
    return rd_restitution_calibrate_grid(sc, theta0, target, RD_CAL_RTOL, NULL, e, reached, NULL,
                                         err);
}

int rd_restitution_calibrate_grid(const rd_scenario *sc, double theta0, double target, double rtol,
                                  const rd_restitution *grid, double *e, double *reached,
                                  rd_restitution *at, rd_error *err)
{
    /* r(e) grows with e at corner subcontacts but need not at a multi-point base (the
       mid-line layout of docs/CONTACT.md section 2 goes down and up again), and falls with the
       surface model's dashpot ratio: the grid (rd_restitution_loss_at) is scanned for the first
       interval where r crosses the target, which is then refined; with none, the grid point
       closest to it is returned */
    double eg[RD_CAL_GRID + 1], fg[RD_CAL_GRID + 1];
    rd_restitution mg[RD_CAL_GRID + 1], dummy;
    if (!at) at = &dummy;
    int best = 0;
    for (int k = 0; k <= RD_CAL_GRID; k++) {
        eg[k] = rd_restitution_loss_at(sc, k);
        if (grid) {
            mg[k] = grid[k];
            if (too_few(sc, &mg[k], eg[k], err)) return -1;
        } else if (measure_at(sc, theta0, eg[k], &mg[k], err)) {
            return -1;
        }
        fg[k] = mg[k].r - target;
        if (fabs(fg[k]) < fabs(fg[best])) best = k;
        if (fabs(fg[k]) < rtol) {
            *e = eg[k];
            *reached = mg[k].r;
            *at = mg[k];
            return 0;
        }
    }
    *e = eg[best];
    *reached = fg[best] + target;
    *at = mg[best];
    for (int k = 0; k < RD_CAL_GRID; k++)
        if (fg[k] * fg[k + 1] < 0)
            return refine(sc, theta0, target, rtol, eg[k], eg[k + 1], fg[k], fg[k + 1], e, reached,
                          at, err);
    return 1;
}
