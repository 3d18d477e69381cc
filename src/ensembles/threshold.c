/* rockdem — minimum overturning amplitude of a scenario's horizontal pulse, with the DEM or the
 * rigid reference (include/rockdem/validate.h explains what the search finds). The coarse scan
 * runs its amplitudes in batches of opts->jobs worker processes (fork, one pipe each); the
 * outcomes are read in scan order, so the bracket is the serial scan's. The workers send their
 * progress on the same pipes, and the scan relays the batch's sum to the process's progress
 * callback as runs' worth done (see relay_progress), so a progress bar follows the whole scan.
 * Folder ensembles/ owns many-run studies (threshold, restitution, sweeps); it may call the
 * public API (engine, scenario, reference) and io/.
 */
#include "rockdem/validate.h"
#include "rockdem/check.h"
#include "ensembles/pipe_io.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

rd_threshold_opts rd_threshold_opts_default(void)
{
    return (rd_threshold_opts){ .lo = 0, .hi = 0, .nscan = 24, .jobs = 0, .rtol = 0.005 };
}

/* DEM run (no file: only the summary is needed); *over = any free body overturned. The run
 * stops once one has for good (RD_OVERTURN_STOP_ANY): the answer is then known, and the energy
 * balance is judged over the run that gave it. */
static int dem_overturns(const rd_scenario *base, double amplitude, int *over, rd_error *err)
{
    rd_scenario *sc = malloc(sizeof *sc);
    if (!sc) return rd_error_set(err, "out of memory");
    *sc = *base;
    sc->motion.horizontal.amplitude = amplitude;
    sc->output.interval = fmax(sc->output.interval, 0.05); /* a coarse sampling: no history kept */
    sc->overturn.stop = RD_OVERTURN_STOP_ANY;
    sc->quiet_stop = 1; /* ends once at rest after the pulse (engine/quiet_end.c) */
    sc->threads = 1;    /* the levels already run one per core (processes) */
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
    rd_ref_result res = { 0 };
    int rc = -1;
    if (!sc || !rs) {
        rd_error_set(err, "out of memory");
        goto done;
    }
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

/* ---- the coarse scan on several cores ------------------------------------------------------ */

/* One scan run's outcome, from its worker process to the scan (one write on a pipe). */
typedef struct scan_outcome {
    int rc, over;
    char msg[RD_ERROR_MAX];
} scan_outcome;

/* A message on a worker's pipe: its progress (t of t_end, s), then once its outcome (done). */
typedef struct scan_message {
    int done;
    double t, t_end;
    scan_outcome o;
} scan_message;

#define RD_SCAN_REPORTS 200 /* progress messages per worker run, at most (one per 0.5 % of it) */

#define RD_SCAN_MAX_JOBS                                                                           \
    256 /* worker processes at once, at most (each batch's state is on the stack) */

/* Worker processes for the scan: opts->jobs, or every online core when it is <= 0. */
static int scan_jobs(const rd_threshold_opts *opts)
{
    long n = opts->jobs > 0 ? opts->jobs : sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > RD_SCAN_MAX_JOBS ? RD_SCAN_MAX_JOBS : (int)n;
}

/* A worker's progress callback: its run's progress on its pipe, each 1 / RD_SCAN_REPORTS of the
   run at most (the scan reads it while it waits, so the pipe never fills). */
typedef struct worker_pipe {
    int fd;
    double sent, t_end;
} worker_pipe;
static void worker_progress(void *ctx, double t, double t_end)
{
    worker_pipe *w = ctx;
    double f = t_end > 0 ? t / t_end : 1.0;
    w->t_end = t_end;
    if (f - w->sent < 1.0 / RD_SCAN_REPORTS && f < 1.0) return;
    w->sent = f;
    scan_message m = { .done = 0, .t = t, .t_end = t_end };
    if (rd_pipe_write(w->fd, &m, sizeof m)) _exit(3);
}

/* The worker: one run, its progress and outcome on fd, never returns. */
static void scan_worker(const rd_scenario *sc, rd_engine engine, double amplitude, int fd)
{
    scan_message m = { .done = 1 };
    rd_error err = { { 0 } };
    worker_pipe w = { fd, -1.0, 0.0 };
    rd_set_progress(worker_progress, &w);
    m.o.rc = rd_overturns(sc, engine, amplitude, &m.o.over, &err);
    m.t = m.t_end = w.t_end;
    memcpy(m.o.msg, err.msg, sizeof m.o.msg);
    _exit(rd_pipe_write(fd, &m, sizeof m) ? 3 : 0);
}

/* The batch's progress to the process's callback: base runs finished before the batch plus each
   worker's fraction (f[k], 1 once done) make `done` runs' worth, told as rd_sim_run would tell
   that many runs one after the other (a run's t from 0 to t_end, then the next one's from 0), so
   a bar that counts runs where t falls back and shows the current one's t follows the whole
   scan. *told: runs' worth told so far in this scan (0: none; the first report starts a run). */
static void relay_progress(double base, const double *f, int n, double t_end, double *told)
{
    double done = base;
    for (int k = 0; k < n; k++) done += f[k];
    if (!(done > *told) || !(t_end > 0)) return;
    if (*told == 0) rd_progress_report(0, t_end); /* the scan's first run starts */
    int run = *told > 0 ? (int)ceil(*told) : 1;   /* the run the callback is in */
    int last = done > floor(done) ? (int)floor(done) + 1 : (int)done; /* the one done ends in */
    for (; run < last; run++) {
        rd_progress_report(t_end, t_end); /* it is complete, the next starts */
        rd_progress_report(0, t_end);
    }
    rd_progress_report(done < last ? (done - floor(done)) * t_end : t_end, t_end);
    *told = done;
}

/* Runs amplitudes a[0..n) at once, one worker process each; out[k] their outcomes (a worker
   that dies leaves rc -1 and says so). Their progress is relayed as it arrives, after `base`
   runs of the scan (relay_progress). -1 only when no worker could be started. */
static int scan_batch(const rd_scenario *sc, rd_engine engine, const double *a, int n, double base,
                      double *told, scan_outcome *out, rd_error *err)
{
    pid_t pid[n];
    int fd[n], started = 0;
    pid_t parent = getpid();
    fflush(NULL); /* nothing buffered is written twice */
    for (; started < n; started++) {
        int p[2];
        if (pipe(p)) break;
        pid[started] = fork();
        if (pid[started] < 0) {
            close(p[0]);
            close(p[1]);
            break;
        }
        if (pid[started] == 0) {
            /* the worker dies with the scan; the check closes the race with a parent gone first */
            if (prctl(PR_SET_PDEATHSIG, SIGKILL) || getppid() != parent) _exit(3);
            for (int k = 0; k < started; k++) close(fd[k]);
            close(p[0]);
            scan_worker(sc, engine, a[started], p[1]);
        }
        close(p[1]);
        fd[started] = p[0];
    }
    double f[n], t_end = 0;
    struct pollfd pfd[n];
    for (int k = 0; k < started; k++) {
        f[k] = 0;
        pfd[k] = (struct pollfd){ .fd = fd[k], .events = POLLIN };
    }
    for (int open = started, waiting = 1; open > 0;) {
        if (waiting && poll(pfd, (nfds_t)started, -1) < 0) {
            if (errno == EINTR) continue;
            waiting = 0;
        }
        for (int k = 0; k < started; k++) { /* (without poll: blocking reads, in order) */
            if (pfd[k].fd < 0 || (waiting && !pfd[k].revents)) continue;
            scan_message m;
            int lost = rd_pipe_read(fd[k], &m, sizeof m);
            if (!lost && m.t_end > 0) t_end = m.t_end;
            if (!lost && !m.done) { /* progress */
                f[k] = m.t_end > 0 ? fmin(fmax(m.t / m.t_end, 0), 1) : 0;
                continue;
            }
            if (lost) { /* the pipe closed with no outcome: the worker died */
                m.o = (scan_outcome){ .rc = -1 };
                snprintf(m.o.msg, sizeof m.o.msg, "threshold: the worker for %.4g m/s^2 died",
                         a[k]);
            }
            out[k] = m.o;
            f[k] = 1;
            pfd[k].fd = -1;
            open--;
        }
        relay_progress(base, f, started, t_end, told);
    }
    for (int k = 0; k < started; k++) {
        close(fd[k]);
        waitpid(pid[k], NULL, 0);
    }
    if (started == n) return 0;
    return rd_error_set(err, "threshold: cannot start %d worker processes: %s", n, strerror(errno));
}

/* The coarse scan up from lo in n steps: the first amplitude that overturns closes the first
   bracket (*above < 0: none did; *below: the last one below it). jobs runs at a time; the
   outcomes are taken in scan order, so the bracket is the serial scan's. */
static int coarse_scan(const rd_scenario *sc, rd_engine engine, double lo, double hi, int n,
                       int jobs, double *below, double *above, rd_threshold_result *out,
                       rd_error *err)
{
    double told = 0; /* runs' worth told to the progress callback (relay_progress) */
    *below = lo;
    *above = -1;
    for (int k0 = 0; k0 <= n && *above < 0; k0 += jobs) {
        int m = n + 1 - k0 < jobs ? n + 1 - k0 : jobs;
        double a[m];
        scan_outcome o[m];
        for (int i = 0; i < m; i++) a[i] = lo + (hi - lo) * (k0 + i) / n;
        if (m == 1) { /* one run: in this process */
            o[0].rc = rd_overturns(sc, engine, a[0], &o[0].over, err);
            if (o[0].rc) return -1;
        } else if (scan_batch(sc, engine, a, m, k0, &told, o, err)) {
            return -1;
        }
        out->runs += m;
        for (int i = 0; i < m && *above < 0; i++) {
            if (o[i].rc) return rd_error_set(err, "%s", o[i].msg);
            if (o[i].over) {
                *above = a[i];
                out->lifted_off = o[i].over == RD_LIFTS_OFF;
            } else
                *below = a[i];
        }
    }
    return 0;
}

/* The scene's own scales where no rigid reference maps it (meshes, prisms, drum columns,
 * several bodies): the least static tipping acceleration g tan(alpha) along +- the pulse's
 * direction over every free body, alone or with everything standing on it (rd_check_scene:
 * each body's support polygon and centre of mass as placed), and w/p of that assembly. */
static int own_scales(const rd_scenario *sc, rd_threshold_result *out, rd_error *err)
{
    rd_check_report rep;
    if (rd_check_scene(sc, &rep, err)) return -1;
    double alpha = INFINITY, p = 0;
    for (int i = 0; i < rep.nbodies; i++) {
        const rd_check_body *b = &rep.body[i];
        if (b->fixed) continue;
        double a =
            fmin(b->alpha_shaking, b->alpha_tower); /* (p: the assembly's, or its own alone) */
        if (a < alpha) {
            alpha = a;
            p = b->p_tower;
        }
    }
    rd_check_free(&rep);
    if (!(alpha > 0 && alpha < M_PI / 2))
        return rd_error_set(
            err,
            "%s: threshold: no free body stands on a support that can tip it (static "
            "tipping angle %.3g deg); give --lo and --hi",
            sc->file, alpha * 180 / M_PI);
    out->static_amp = sc->gravity * tan(alpha);
    out->w_over_p = p > 0 ? 2 * M_PI * sc->motion.horizontal.frequency / p : 0;
    out->own_scale = 1;
    return 0;
}

/* Static uplift threshold (m/s^2) and w/p of the scene's lower block: from the rigid reference
 * where it maps the scene (bricks: Housner, a two-block stack: Kounadis), else the scene's own. */
static int scene_scales(const rd_scenario *sc, rd_threshold_result *out, rd_error *err)
{
    rd_refscene *rs = malloc(sizeof *rs);
    if (!rs) return rd_error_set(err, "out of memory");
    rd_error ref_err;
    int rc = rd_refscene_map(sc, rs, &ref_err);
    if (rc)
        rc = own_scales(sc, out, err);
    else {
        out->static_amp = sc->gravity * tan(rs->alpha);
        if (rs->model == RD_REFMODEL_KOUNADIS) {
            double stack, upper;
            rd_kounadis_uplift_thresholds(&rs->kounadis, &stack, &upper);
            out->static_amp = sc->gravity * fmin(stack, upper);
        }
        out->w_over_p = 2 * M_PI * sc->motion.horizontal.frequency / rs->p;
        out->own_scale = rs->equivalent;
    }
    free(rs);
    return rc;
}

/* rd_threshold_range with the scene's scales into out (static uplift, w/p). */
static int search_range(const rd_scenario *sc, const rd_threshold_opts *opts, double *lo,
                        double *hi, rd_threshold_result *out, rd_error *err)
{
    if (sc->motion.horizontal.kind == RD_PULSE_NONE)
        return rd_error_set(err, "%s: threshold: the scenario has no horizontal pulse to scale",
                            sc->file);
    if (!(opts->rtol >= RD_THRESHOLD_RTOL_MIN && opts->rtol <= RD_THRESHOLD_RTOL_MAX))
        return rd_error_set(err,
                            "threshold: --rtol %g is outside its range [%g, %g] (the bisection's "
                            "relative bracket)",
                            opts->rtol, RD_THRESHOLD_RTOL_MIN, RD_THRESHOLD_RTOL_MAX);
    if (opts->nscan > RD_THRESHOLD_SCAN_MAX)
        return rd_error_set(err,
                            "threshold: --steps %d is above its cap %d (coarse scan steps, one "
                            "run each)",
                            opts->nscan, RD_THRESHOLD_SCAN_MAX);
    if (scene_scales(sc, out, err)) return -1;
    *lo = opts->lo > 0 ? opts->lo : 0.9 * out->static_amp;
    *hi = opts->hi > 0 ? opts->hi : 10 * out->static_amp;
    if (!(*lo > 0 && *hi > *lo))
        return rd_error_set(err,
                            "%s: threshold: --lo %.5g m/s^2 is not below --hi %.5g m/s^2 (their "
                            "defaults: 0.9 and 10 times the static uplift threshold %.5g m/s^2)",
                            sc->file, *lo, *hi, out->static_amp);
    return 0;
}

int rd_threshold_range(const rd_scenario *sc, const rd_threshold_opts *opts, double *lo, double *hi,
                       rd_error *err)
{
    rd_threshold_result scales = { 0 };
    return search_range(sc, opts, lo, hi, &scales, err);
}

int rd_threshold(const rd_scenario *sc, rd_engine engine, const rd_threshold_opts *opts,
                 rd_threshold_result *out, rd_error *err)
{
    memset(out, 0, sizeof *out);
    double lo = 0, hi = 0, below, above;
    if (search_range(sc, opts, &lo, &hi, out, err)) return -1;
    int n = opts->nscan > 0 ? opts->nscan : 24, over = 0;
    /* (a reference run that lifts off ends the search like an overturning one: the bracket then
       closes on the onset of jumping, reported as such) */
    if (coarse_scan(sc, engine, lo, hi, n, scan_jobs(opts), &below, &above, out, err)) return -1;
    if (above < 0) return 0;
    if (above == lo) {
        out->found = 1;
        out->amplitude = out->below = lo;
        return 0;
    }
    while ((above - below) / above > opts->rtol) {
        double mid = 0.5 * (below + above);
        if (rd_overturns(sc, engine, mid, &over, err)) return -1;
        out->runs++;
        if (over) {
            above = mid;
            out->lifted_off = over == RD_LIFTS_OFF;
        } else
            below = mid;
    }
    out->found = 1;
    out->amplitude = above;
    out->below = below;
    return 0;
}
