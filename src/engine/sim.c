/* rockdem — the simulation: create, settle, shake, stop, summarise.
 *
 * One step (the table of contents of the engine):
 *   ground motion at t  ->  world geometry  ->  gravity and ground pseudo-force
 *   ->  contacts (common plane, subcontact law)  ->  damping  ->  kick velocities
 *   ->  energies, monitoring, output at t  ->  drift positions  ->  health check
 * The frame of reference moves with the ground, so pedestals are at rest and every free body
 * feels the pseudo-force -m a_g(t) (exact for a translating frame).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "engine/workers.h"
#include "base/constants.h"
#include "base/path.h"
#include "base/vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* rd_sim_request_stop: every running simulation stops (async-signal-safe, for handlers). */
static volatile sig_atomic_t stop_requested;

void rd_sim_request_stop(void) { stop_requested = 1; }

void rd_sim_stop(rd_sim *s) { atomic_store(&s->stop, 1); }

/* This simulation was asked to stop, by rd_sim_stop or by rd_sim_request_stop. */
static int stopping(rd_sim *s) { return stop_requested || atomic_load(&s->stop); }

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Gravity and the ground pseudo-force on every free body; clears the accumulators. */
static void forces_external(rd_sim *s)
{
    for (int i = 0; i < s->nb; i++) {
        s->tq[i][0] = s->tq[i][1] = s->tq[i][2] = 0;
        double m = s->mass[i];
        s->f[i][0] = -m * s->ag[0];
        s->f[i][1] = -m * s->ag[1];
        s->f[i][2] = -m * (s->sc.gravity + s->ag[2]);
    }
    for (int k = 0; k < s->nfree; k++) {
        rd_watch *w = &s->watch[k];
        w->area = 0;
        w->nactive = 0;
        w->nslip = 0;
    }
}

/* Cundall local damping: each force/torque component is reduced by alpha |F| against the
 * velocity component (velocity-proportional terms are absent: it does not resist steady
 * motion and leaves free rocking periods unchanged). */
static void damping_local(rd_sim *s, double alpha, int account)
{
    for (int i = 0; i < s->nb; i++) {
        if (s->fixed[i]) continue;
        double *prev = s->df_local[i];
        for (int k = 0; k < 3; k++) {
            double df = -alpha * fabs(s->f[i][k]) *
                        (s->v[i][k] > 0   ? 1.0
                         : s->v[i][k] < 0 ? -1.0
                                          : 0.0);
            double dm = -alpha * fabs(s->tq[i][k]) *
                        (s->w[i][k] > 0   ? 1.0
                         : s->w[i][k] < 0 ? -1.0
                                          : 0.0);
            s->f[i][k] += df;
            s->tq[i][k] += dm;
            if (!account) continue;
            /* work over [t(n-1), t(n)]: the mean of the two steps' forces over v(n-1/2) dt, as
             * the kinetic energy sees it (energy.c); the force flips with the velocity, so the
             * step's own force alone left an error of first order */
            s->e_damp -=
                0.5 * ((prev[k] + df) * s->v[i][k] + (prev[3 + k] + dm) * s->w[i][k]) * s->dt;
            prev[k] = df;
            prev[3 + k] = dm;
        }
    }
}

/* Largest unbalanced force / weight and torque / (weight * size) over the free bodies. */
static double unbalance(const rd_sim *s)
{
    double r = 0;
    for (int i = 0; i < s->nb; i++) {
        if (s->fixed[i]) continue;
        double wgt = s->mass[i] * s->sc.gravity;
        r = fmax(r, rd_norm(s->f[i]) / wgt);
        r = fmax(r, rd_norm(s->tq[i]) / (wgt * s->poly[i].radius));
    }
    return r;
}

static int healthy(rd_sim *s)
{
    for (int k = 0; k < s->nfree; k++) {
        int i = s->free_body[k];
        double r = s->poly[i].radius;
        double v2 = rd_dot(s->v[i], s->v[i]) + rd_dot(s->w[i], s->w[i]) * r * r;
        double sum = s->x[i][0] + s->x[i][1] + s->x[i][2] + s->q[i][0] + s->q[i][1] + s->q[i][2] +
                     s->q[i][3] + v2; /* NaN or Inf anywhere makes the sum non-finite */
        if (isfinite(sum) && v2 <= RD_RUNAWAY_V2) continue;
        const char *cause = NULL;
        double speed = sqrt(v2);
        if (!isfinite(sum)) cause = "has a non-finite state (NaN/Inf)";
        char buf[96];
        if (!cause) {
            snprintf(buf, sizeof buf, "moves at %.3g m/s (runaway)", speed);
            cause = buf;
        }
        if (cause) {
            snprintf(s->errmsg, sizeof s->errmsg,
                     "unstable at step %ld (t = %.6g s): body '%s' %s; contact forces blew up — "
                     "time step %.3g s, estimated stable limit %.3g s",
                     s->step, s->t, s->sc.bodies[i].name, cause, s->dt, s->dt_crit);
            rd_event_add(s, s->t, k, "unstable", speed);
            s->status = RD_STATUS_UNSTABLE;
            return 0;
        }
    }
    return 1;
}

/* Whether the scene's ground motion depends on time: a pulse or an applied record (with
 * neither, rd_motion_eval gives the same values at every t). */
static int ground_varies(const rd_motion_def *m)
{
    int varies = m->horizontal.kind != RD_PULSE_NONE || m->vertical.kind != RD_PULSE_NONE;
    for (int k = 0; k < RD_NCOMPONENTS; k++) varies |= m->record[k].applied != NULL;
    return varies;
}

/* The escape checks (rd_monitor_escape: a centre of mass inside another body, a body out of the
 * scene) every RD_ESCAPE_EVERY steps, and sooner once a centre of mass may have moved half the
 * smallest inradius against another body (rd_sim.escape_reach): a point moves at most
 * u = |v| + |w| r <= sqrt(2 (v^2 + w^2 r^2)) (r: the body's radius), so a centre moves against
 * another body's material within that body's radius at most 2 u_max per second. A 0.5 m block
 * at 30 m/s on a 0.2 m wall at KN 1e6 (2.2 ms steps: 6.7 cm a step, 4.3 m between checks of
 * every 64 steps) passed through it and the run ended done. */
static void escape_watch(rd_sim *s)
{
    double u2 = 0;
    for (int k = 0; k < s->nfree; k++) {
        int i = s->free_body[k];
        double r = s->poly[i].radius;
        u2 = fmax(u2, rd_dot(s->v[i], s->v[i]) + rd_dot(s->w[i], s->w[i]) * r * r);
    }
    s->escape_travel += 2.0 * sqrt(2.0 * u2) * s->dt;
    if ((++s->nsteps_all & (RD_ESCAPE_EVERY - 1)) != 0 && s->escape_travel < s->escape_reach)
        return;
    s->escape_travel = 0;
    rd_monitor_escape(s);
}

/* One explicit step from t to t + dt. */
static void step_once(rd_sim *s)
{
    if (!s->settling && !s->ground_still) {
        rd_motion_eval_axes(&s->sc.motion, &s->ground_axes, s->t, s->ag, s->vg, s->dg);
        s->ground_still = s->ground_const;
    }
    rd_bodies_refresh_step(s);
    forces_external(s);
    if (rd_contact_step(s)) {
        snprintf(s->errmsg, sizeof s->errmsg,
                 "out of memory growing the contact-pair cache at t = %g s", s->t);
        s->status = RD_STATUS_ERROR;
        return;
    }
    if (s->settling) {
        s->settle_ratio = unbalance(s);
        damping_local(s, RD_SETTLE_DAMPING, 0);
    } else if (s->sc.damping.kind == RD_DAMPING_LOCAL) {
        damping_local(s, s->sc.damping.value, 1);
    }
    rd_integrate_kick(s);
    if (!s->settling) {
        rd_energy_step(s);
        rd_monitor_step(s);
        rd_runout_step(s);
        if (s->t >= s->next_out - 1e-9 * s->dt) {
            rd_energy_sample(s);
            rd_observe_sample(s);
            s->next_out += s->sc.output.interval;
        }
        rd_joints_sample(
            s); /* every step: slip accumulates along the path, maxima between samples */
        rd_history_step(s);
    }
    rd_integrate_drift(s);
    memcpy(s->ag_prev, s->ag, sizeof s->ag);
    s->t += s->dt;
    escape_watch(s);
}

/* Bring the scene to rest under gravity (local damping RD_SETTLE_DAMPING, no shaking), like
 * 3DEC's solve to a force ratio; then clear velocities. Contacts keep their history. */
static void settle(rd_sim *s)
{
    s->settling = 1;
    s->t = 0;
    memset(s->ag, 0, sizeof s->ag);
    s->ground_still = 0;
    s->settle_ratio = INFINITY;
    while (s->t < s->sc.settle.max_time && !stopping(s) && s->status == RD_STATUS_DONE) {
        step_once(s);
        if (s->settle_ratio < s->sc.settle.ratio) break;
    }
    s->settle_time = s->t;
    for (int i = 0; i < s->nb; i++) {
        memset(s->v[i], 0, sizeof s->v[i]);
        memset(s->L[i], 0, sizeof s->L[i]);
        memset(s->w[i], 0, sizeof s->w[i]);
    }
    if (s->settle_ratio >= s->sc.settle.ratio) rd_event_add(s, 0, -1, "unsettled", s->settle_ratio);
    rd_contact_seat(s);
    s->settling = 0;
    s->t = 0;
    /* bonds exist only where the joint is closed at rest: a re-created contact starts from zero */
    for (int k = 0; k < s->nstate; k++)
        if (!(s->pstate[k] & RD_PT_ACTIVE)) s->pstate[k] &= (unsigned char)~RD_PT_BONDED;
}

/* The state at rest: from a checkpoint (`model restore`, read by rd_sim_create in
 * io/checkpoint.c), or by settling, or as placed. `model save` is an observer there: its begin
 * writes this state. As placed, one contact step finds the contact areas at rest for the
 * monitor, and the contacts it finds pressed are seated, as settling seats its own: a body
 * placed pressed into its support is not landing on it, and a new contact's impact loss at its
 * first unloading turned its whole compression into a permanent set at the first round-off
 * unloading (a cube placed at its static compression dropped to twice it). */
static void restore_or_settle(rd_sim *s)
{
    if (s->restored) return;
    if (s->sc.settle.enabled)
        settle(s);
    else if (rd_contact_step(s))
        s->status = RD_STATUS_ERROR;
    else
        rd_contact_seat(s);
}

/* Rotate body k about the edge of its support on the side it leans to. */
static void apply_tilt(rd_sim *s, int k, double tilt, double dir)
{
    const rd_watch *w = &s->watch[k];
    int i = s->free_body[k];
    double d[2] = { cos(dir), sin(dir) }, best = -INFINITY, piv[3] = { 0, 0, w->base_ref[2] };
    int n = 0;
    for (int j = 0; j < w->nsupport; j++)
        best = fmax(best, d[0] * w->support[j][0] + d[1] * w->support[j][1]);
    for (int j = 0; j < w->nsupport; j++)
        if (d[0] * w->support[j][0] + d[1] * w->support[j][1] > best - 1e-9 * (1 + fabs(best))) {
            piv[0] += w->support[j][0];
            piv[1] += w->support[j][1];
            n++;
        }
    piv[0] /= n;
    piv[1] /= n;
    double axis[3] = { -d[1] * tilt, d[0] * tilt, 0 }, Q[4], r[3], qn[4];
    rd_quat_from_rotvec(axis, Q);
    double rel[3] = { s->x[i][0] - piv[0], s->x[i][1] - piv[1], s->x[i][2] - piv[2] };
    rd_quat_rotate(Q, rel, r);
    for (int j = 0; j < 3; j++) s->x[i][j] = piv[j] + r[j];
    rd_quat_mul(Q, s->q[i], qn);
    memcpy(s->q[i], qn, sizeof qn);
}

static void apply_initial_conditions(rd_sim *s)
{
    for (int k = 0; k < s->nfree; k++) {
        int i = s->free_body[k];
        const rd_body_def *d = &s->sc.bodies[i];
        if (d->tilt > 0) {
            apply_tilt(s, k, d->tilt, d->tilt_direction);
            rd_contact_reset_body(s, i);
        }
        rd_copy3(d->velocity, s->v[i]);
        rd_body_set_angular_velocity(s, i, d->angular_velocity);
    }
    rd_bodies_refresh(s);
}

static int choose_timestep(rd_sim *s, rd_error *err)
{
    s->dt_crit = rd_timestep_critical(s, s->dt_pair);
    if (isnan(s->dt_crit))
        return rd_error_set(err, "%s: out of memory for the time step bound", s->sc.file);
    const rd_timestep_def *ts = &s->sc.timestep;
    if (ts->kind == RD_TIMESTEP_FIXED) {
        if (ts->dt > s->dt_crit)
            return rd_error_set(err,
                                "%s: fixed time step %g s is above the stable limit %.4g s "
                                "(from mass, inertia and contact stiffness); use at most %.4g s "
                                "or 'model timestep auto'",
                                s->sc.file, ts->dt, s->dt_crit, s->dt_crit);
        s->dt = ts->dt;
    } else {
        s->dt = isfinite(s->dt_crit) ? ts->safety * s->dt_crit : s->sc.output.interval / 10.0;
    }
    return 0;
}

/* Refuse initial conditions that are already a runaway (healthy: v^2 + (w r)^2 above
 * RD_RUNAWAY_V2, r the body's radius): `block initial` accepts up to 1e3 m/s and 1e4 rad/s
 * (docs/LIMITS.md), and a 0.5 x 0.5 x 1 m block spun at 3000 rad/s (1840 m/s at its corners)
 * stopped at step 1 as "unstable ... contact forces blew up", blaming the time step. */
static int check_initial_speeds(const rd_sim *s, rd_error *err)
{
    for (int k = 0; k < s->nfree; k++) {
        int i = s->free_body[k];
        const rd_body_def *d = &s->sc.bodies[i];
        double r = s->poly[i].radius, v = rd_norm(d->velocity), w = rd_norm(d->angular_velocity);
        if (v * v + w * w * r * r <= RD_RUNAWAY_V2) continue;
        return rd_error_set(
            err,
            "%s:%d: block '%s' starts at %.3g m/s (velocity %.3g m/s, angular velocity "
            "%.3g rad/s at its radius %.3g m), above the %g m/s at which a run stops as a "
            "runaway (docs/LIMITS.md)",
            s->sc.file, d->initial_line, d->name, sqrt(v * v + w * w * r * r), v, w, r,
            sqrt(RD_RUNAWAY_V2));
    }
    return 0;
}

/* Estimated steps of the whole run: settling (at most its time limit; none when the run starts
 * from a checkpoint), shaking and tail as the run takes them (rd_run_length). The motion's end
 * counts only with a tail: without one the run stops at its duration, and a 10 s run at KN
 * 1e14 under a 600 s record (3.6e7 steps) was refused as 1.46e9. */
static double step_estimate(const rd_sim *s)
{
    const rd_scenario *sc = &s->sc;
    const int settles = sc->settle.enabled && !sc->restore_path[0];
    return ((settles ? sc->settle.max_time : 0.0) + rd_run_length(s)) / s->dt;
}

/* Refuse a run whose step count exceeds RD_STEP_BUDGET unless forced, and one shorter than a
 * single step (it ends before the first step: a 1e-6 s run of a seated cask reported that the
 * cask fell freely). */
static int check_budget(const rd_sim *s, rd_error *err)
{
    char at[16] = "";
    if (s->sc.solve_line > 0) snprintf(at, sizeof at, ":%d", s->sc.solve_line);
    if (s->sc.duration < s->dt)
        return rd_error_set(
            err,
            "%s%s: the run of %.3g s is shorter than one time step (%.3g s): nothing would "
            "be computed; give a longer 'model solve time'",
            s->sc.file, at, s->sc.duration, s->dt);
    double n = step_estimate(s);
    if (!(n > RD_STEP_BUDGET) || s->sc.force) return 0;
    char by[2 * RD_NAME_MAX + 64];
    rd_timestep_pair_text(s, by, sizeof by);
    return rd_error_set(
        err,
        "%s%s: the run would take about %.3g steps (dt %.3g s%s, over %.4g s of settling, "
        "shaking and tail), more than the budget of %.0e; check the contact stiffness, "
        "masses and times, or force it ('model solve ... force on', or --force)",
        s->sc.file, at, n, s->dt, by, n * s->dt, RD_STEP_BUDGET);
}

/* Geometry, subcontact points, time step and budget: everything but the output file. */
static rd_sim *sim_build(const rd_scenario *sc, rd_error *err)
{
    if (rd_scenario_validate(sc, err)) return NULL;
    rd_sim *s = calloc(1, sizeof *s);
    if (!s) {
        rd_error_set(err, "out of memory");
        return NULL;
    }
    if (rd_scenario_copy(&s->sc, sc, err) || rd_setup_bodies(s, err) || rd_setup_contacts(s, err) ||
        check_initial_speeds(s, err) || choose_timestep(s, err) || check_budget(s, err) ||
        rd_history_init(s, err)) {
        rd_sim_free(s);
        return NULL;
    }
    rd_monitor_scene(s);
    s->nthreads = rd_threads_of(&s->sc);
    s->team = 1;
    rd_motion_axes_of(&s->sc.motion, &s->ground_axes);
    s->ground_const = !ground_varies(&s->sc.motion);
    return s;
}

int rd_sim_check(const rd_scenario *sc, rd_check_info *info, rd_error *err)
{
    rd_sim *s = sim_build(sc, err);
    if (!s) return -1;
    if (info)
        *info = (rd_check_info){
            .dt = s->dt, .dt_critical = s->dt_crit, .steps = step_estimate(s), .npoints = s->npts
        };
    int rc = rd_path_check_output(&s->sc, s->sc.output.path, s->sc.save_path, err) ||
                     rd_path_check_save(&s->sc, err)
                 ? -1
                 : 0;
    rd_sim_free(s);
    return rc;
}

rd_sim *rd_sim_build(const rd_scenario *sc, rd_error *err)
{
    rd_sim *s = rd_sim_build_as_placed(sc, err);
    if (s && !sc->restore_path[0] &&
        rd_overlap_refuse(s, err)) { /* a checkpoint's state replaces the placement */
        rd_sim_free(s);
        return NULL;
    }
    return s;
}

rd_sim *rd_sim_build_as_placed(const rd_scenario *sc, rd_error *err)
{
    rd_sim *s = sim_build(sc, err);
    if (!s) return NULL;
    s->watch = calloc((size_t)s->nfree, sizeof *s->watch);
    s->body_sum = calloc((size_t)s->nfree + 1, sizeof *s->body_sum);
    s->obuf = calloc((size_t)s->nfree * 17 + 1, sizeof *s->obuf);
    s->rest_area = calloc((size_t)s->nfree + 1, sizeof *s->rest_area);
    if (!s->watch || !s->body_sum || !s->obuf || !s->rest_area) {
        rd_error_set(err, "out of memory");
        goto fail;
    }
    for (int k = 0; k < s->nfree; k++) {
        s->watch[k].z_start = s->x[s->free_body[k]][2];
        s->watch[k].sum = &s->body_sum[k];
    }
    return s;
fail:
    rd_sim_free(s);
    return NULL;
}

/* The first "overturn" event (its index; -1: none). */
static int first_overturn(const rd_sim *s)
{
    for (int k = 0; k < s->nevent; k++)
        if (!strcmp(s->event[k].type, "overturn")) return k;
    return -1;
}

/* A run that ended normally but whose energy balance drifted past RD_ENERGY_TRUST: the message
 * says when it first did, and when the first body met the overturn criterion, before or after. */
static void judge_energy(rd_sim *s)
{
    if ((s->status != RD_STATUS_DONE && s->status != RD_STATUS_OVERTURNED) ||
        !(s->resid_max > RD_ENERGY_TRUST))
        return;
    char when[RD_NAME_MAX + 96] = "";
    int o = first_overturn(s);
    if (o >= 0)
        snprintf(when, sizeof when, "; body '%s' first met the overturn criterion at t = %.4g s",
                 s->sc.bodies[s->free_body[s->event[o].body]].name, s->event[o].time);
    snprintf(s->errmsg, sizeof s->errmsg,
             "energy balance residual %.3g of the energy scale exceeds %g (first at t = %.4g s%s): "
             "the answer is not to be trusted (reduce the time step with 'model timestep auto "
             "safety ...', or check the contact stiffness and discretisation)",
             s->resid_max, RD_ENERGY_TRUST, s->t_untrusted, when);
    s->status = RD_STATUS_UNTRUSTED;
}

double rd_sim_trial_steps(rd_sim *s, int n)
{
    s->settling = 1;
    double t0 = wall_now();
    for (int k = 0; k < n && s->status == RD_STATUS_DONE; k++) step_once(s);
    s->settling = 0;
    return wall_now() - t0;
}

int rd_sim_start(rd_sim *s)
{
    if (s->phase != RD_PHASE_CREATED) return s->phase == RD_PHASE_SHAKING;
    stop_requested = 0;
    s->status = RD_STATUS_DONE;
    restore_or_settle(s);
    rd_bodies_refresh(s);
    if (s->status == RD_STATUS_DONE) rd_overlap_at_rest(s);
    rd_monitor_rest(s);
    s->rested = 1;
    rd_observe_begin(s);
    apply_initial_conditions(s);
    rd_monitor_start(s);
    if (rd_runout_begin(s)) {
        snprintf(s->errmsg, sizeof s->errmsg, "out of memory for the runout state");
        s->status = RD_STATUS_ERROR;
    }
    s->shaking = 1;
    s->e_fric = s->e_damp = s->e_work = 0;
    s->end = rd_rest_end(s);
    if (rd_quiet_begin(s)) {
        snprintf(s->errmsg, sizeof s->errmsg, "out of memory (the quiet end's record peaks)");
        s->status = RD_STATUS_ERROR;
    }
    s->phase = s->status == RD_STATUS_DONE ? RD_PHASE_SHAKING : RD_PHASE_OVER;
    return s->phase == RD_PHASE_SHAKING;
}

/* One shaking step and the checks after it; 1 while the run goes on, 0 once it is over. */
static int shake_once(rd_sim *s)
{
    if (s->t >= s->end - 0.5 * s->dt) return 0;
    if (stopping(s)) {
        s->status = RD_STATUS_INTERRUPTED;
        return 0;
    }
    step_once(s);
    s->step++;
    if (s->step % RD_PROGRESS_STEPS == 0) rd_progress_report(s->t, s->end);
    if (s->status != RD_STATUS_DONE || !healthy(s)) return 0;
    if ((s->sc.overturn.stop == RD_OVERTURN_STOP_ANY && rd_monitor_any_fallen(s)) ||
        (s->sc.overturn.stop && !s->sc.runout.until_rest && rd_monitor_all_fallen(s))) {
        s->status = RD_STATUS_OVERTURNED;
        return 0;
    }
    /* free-vibration tail, or a case whose remaining motion cannot move it: everything at rest */
    return !rd_rest_reached(s) && !rd_quiet_reached(s);
}

int rd_sim_advance(rd_sim *s, long nsteps, double t_until)
{
    if (s->phase != RD_PHASE_SHAKING) return 0;
    double t0 = wall_now();
    for (long k = 0; (nsteps < 0 || k < nsteps) && s->t < t_until - 0.5 * s->dt; k++)
        if (!shake_once(s)) {
            s->phase = RD_PHASE_OVER;
            break;
        }
    s->wall += wall_now() - t0;
    return s->phase == RD_PHASE_SHAKING;
}

rd_status rd_sim_finish(rd_sim *s)
{
    if (s->phase == RD_PHASE_FINISHED) return s->status;
    if (s->phase == RD_PHASE_CREATED) rd_sim_start(s);
    if (s->phase == RD_PHASE_SHAKING) s->status = RD_STATUS_INTERRUPTED; /* ended before its end */
    s->phase = RD_PHASE_FINISHED;
    rd_progress_report(s->t, s->end);
    rd_monitor_finish(s);
    rd_runout_finish(s);
    rd_joints_sample(s);
    rd_energy_sample_end(s);
    judge_energy(s);
    rd_observe_end(s);
    return s->status;
}

rd_status rd_sim_run(rd_sim *s)
{
    if (rd_sim_start(s)) rd_sim_advance(s, -1, INFINITY);
    return rd_sim_finish(s);
}

double rd_sim_time(const rd_sim *s) { return s->t; }

double rd_sim_end_time(const rd_sim *s) { return s->phase == RD_PHASE_CREATED ? NAN : s->end; }

void rd_sim_summary(const rd_sim *s, rd_summary *out)
{
    memset(out, 0, sizeof *out);
    out->nbodies = s->nfree;
    out->body = s->body_sum;
    for (int k = 0; k < s->nfree; k++) out->any_overturned |= s->body_sum[k].overturned;
    out->end_time = s->t;
    out->dt = s->dt;
    out->dt_critical = s->dt_crit;
    out->steps = s->step;
    out->settle_time = s->settle_time;
    out->energy_residual_max = s->resid_max;
    out->wall_seconds = s->wall;
    out->at_rest = s->at_rest;
    out->status = s->status;
}

void rd_sim_body_summary(const rd_sim *s, int k, rd_body_summary *out) { *out = s->body_sum[k]; }

const char *rd_sim_error(const rd_sim *s) { return s->errmsg; }

const char *rd_status_name(rd_status st)
{
    static const char *const names[] = { "done",       "overturned", "interrupted",
                                         "unstable",   "io_error",   "error",
                                         "penetrated", "lost",       "untrusted" };
    return (unsigned)st < sizeof names / sizeof names[0] ? names[st] : "unknown";
}

int rd_status_failed(rd_status st)
{
    return st == RD_STATUS_UNSTABLE || st == RD_STATUS_IO_ERROR || st == RD_STATUS_ERROR ||
           st == RD_STATUS_PENETRATED || st == RD_STATUS_LOST || st == RD_STATUS_UNTRUSTED;
}

const rd_event *rd_sim_events(const rd_sim *s, int *n)
{
    *n = s->nevent;
    return s->event;
}

void rd_sim_body_state(const rd_sim *s, int k, double x[3], double q[4], double v[3], double w[3])
{
    int i = s->free_body[k];
    if (x) memcpy(x, s->x[i], 3 * sizeof(double));
    if (q) memcpy(q, s->q[i], 4 * sizeof(double));
    if (v) memcpy(v, s->v[i], 3 * sizeof(double));
    if (w) memcpy(w, s->w[i], 3 * sizeof(double));
}

void rd_sim_energy(const rd_sim *s, double e[7]) { memcpy(e, s->energy, 7 * sizeof(double)); }

int rd_sim_point_count(const rd_sim *s) { return s->npts; }

double rd_sim_dt(const rd_sim *s) { return s->dt; }

long rd_sim_active_point_steps(const rd_sim *s) { return s->active_point_steps; }

int rd_sim_threads(const rd_sim *s) { return s->team; }

int rd_sim_joint_count(const rd_sim *s) { return s->npair; }

void rd_sim_joint(const rd_sim *s, int k, rd_joint_summary *out)
{
    const rd_pair *pr = &s->pair[k];
    const rd_joint *j = &s->joint[pr->joint];
    memset(out, 0, sizeof *out);
    snprintf(out->a, sizeof out->a, "%s", s->sc.bodies[pr->a].name);
    snprintf(out->b, sizeof out->b, "%s", s->sc.bodies[pr->b].name);
    out->kn = j->kn;
    out->ks = j->ks;
    out->friction = j->friction;
    out->cohesion = j->cohesion;
    out->tension = j->tension;
    out->damping = j->damping;
    out->closed = pr->closed;
    out->max_opening = pr->open_max;
    out->max_slip = pr->slip_max;
    out->final_slip = sqrt(pr->slip_end[0] * pr->slip_end[0] + pr->slip_end[1] * pr->slip_end[1] +
                           pr->slip_end[2] * pr->slip_end[2]);
}

void rd_sim_free(rd_sim *s)
{
    if (!s) return;
    rd_observe_release(s);
    rd_surface_free(s);
    rd_quiet_free(s);
    rd_scenario_free(&s->sc);
    for (int i = 0; s->poly && i < s->nb; i++) rd_poly_free(&s->poly[i]);
    for (int k = 0; s->watch && k < s->nfree; k++) free(s->watch[k].support);
    rd_runout_free(s);
    rd_workers_free(s);
    rd_pairs_free(s);
    void *arrays[] = { s->poly,
                       s->x,
                       s->q,
                       s->v,
                       s->L,
                       s->w,
                       s->R,
                       s->mass,
                       s->inertia,
                       s->fixed,
                       s->convex,
                       s->impacting,
                       s->impacting_next,
                       s->f,
                       s->tq,
                       s->v_old,
                       s->L_old,
                       s->df_local,
                       s->free_body,
                       s->free_of,
                       s->vert0,
                       s->face0,
                       s->wv,
                       s->wn,
                       s->wd,
                       s->wt,
                       s->hv0,
                       s->hv,
                       s->cv0,
                       s->cv,
                       s->cv_slot,
                       s->edge_v0,
                       s->edge_v,
                       s->cv_dist,
                       s->cv_mask,
                       s->plane_scratch,
                       s->edge_scratch,
                       s->cv_body,
                       s->cv_world,
                       s->pl,
                       s->pa,
                       s->pn,
                       s->pmult,
                       s->pkin,
                       s->kin,
                       s->kin_stamp,
                       s->pt0,
                       s->cf0,
                       s->cf_face,
                       s->cf_pt0,
                       s->cf_v0,
                       s->cf_v,
                       s->pair,
                       s->fs,
                       s->pstate,
                       s->pface,
                       s->pset,
                       s->pstrike,
                       s->efs,
                       s->edepth,
                       s->eon,
                       s->cf_facing,
                       s->face_nactive,
                       s->watch,
                       s->body_sum,
                       s->event,
                       s->obuf,
                       s->aabb,
                       s->box_pose,
                       s->box_rho,
                       s->box_drift,
                       s->box_builds,
                       s->order,
                       s->hkey,
                       s->live,
                       s->live_prev,
                       s->joint,
                       s->pj,
                       s->hist_pair,
                       s->hist_body,
                       s->hist,
                       s->rest_area };
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++) free(arrays[k]);
    free(s);
}
