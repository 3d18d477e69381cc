/* rockdem — the terminal progress line of the long subcommands (run, threshold, restitution,
 * study; sweep has its own): simulated time of the current run, runs so far for the ensembles,
 * elapsed time and an ETA, redrawn on stderr at most RD_PROGRESS_HZ times a second. Silent when
 * stderr is not a terminal or with -q (rd_cli_quiet), so logs and pipes stay clean.
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"

#include <math.h>
#include <stdio.h>
#include <time.h>
#include <unistd.h>

#define RD_PROGRESS_HZ 4.0 /* redraws per second, at most */

int rd_cli_quiet;

typedef struct rd_cli_progress {
    const char *what;  /* subcommand name */
    int runs_expected; /* 1 for run; an estimate for the ensembles (shown as ~N) */
    int run;           /* runs started so far */
    double t_prev;     /* simulated time at the last report, s */
    double wall0;      /* monotonic start, s */
    double drawn;      /* monotonic time of the last redraw, s */
} rd_cli_progress;

static rd_cli_progress bar;

static double mono(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* "1h02m", "3m05s" or "12s" */
static void hms(double s, char *buf, size_t n)
{
    if (!isfinite(s) || s < 0) {
        snprintf(buf, n, "?");
        return;
    }
    long k = lround(s);
    if (k >= 3600)
        snprintf(buf, n, "%ldh%02ldm", k / 3600, k / 60 % 60);
    else if (k >= 60)
        snprintf(buf, n, "%ldm%02lds", k / 60, k % 60);
    else
        snprintf(buf, n, "%lds", k);
}

static void draw(void *ctx, double t, double t_end)
{
    rd_cli_progress *p = ctx;
    if (t < p->t_prev || p->run == 0) p->run++; /* a new run starts at t = 0 */
    p->t_prev = t;
    double now = mono();
    if (now - p->drawn < 1.0 / RD_PROGRESS_HZ) return;
    p->drawn = now;
    double f = t_end > 0 ? fmin(fmax(t / t_end, 0), 1) : 0; /* of this run */
    int total = p->runs_expected > p->run ? p->runs_expected : p->run;
    double done = (double)(p->run - 1) + f; /* runs' worth finished */
    char el[48], eta[48];
    hms(now - p->wall0, el, sizeof el);
    hms(done > 0 ? (now - p->wall0) * ((double)total - done) / done : NAN, eta, sizeof eta);
    if (p->runs_expected > 1)
        fprintf(stderr, "\r%s: run %d of ~%d, t = %.3g / %.3g s, %s elapsed, ETA ~%s   ", p->what,
                p->run, total, t, t_end, el, eta);
    else
        fprintf(stderr, "\r%s: t = %.3g / %.3g s (%.0f %%), %s elapsed, ETA %s   ", p->what, t,
                t_end, 100 * f, el, eta);
    fflush(stderr);
}

void rd_cli_progress_start(const char *what, int runs_expected)
{
    if (rd_cli_quiet || !isatty(2)) return;
    bar = (rd_cli_progress){ what, runs_expected, 0, 0, mono(), 0 };
    rd_set_progress(draw, &bar);
}

void rd_cli_progress_stop(void)
{
    rd_set_progress(NULL, NULL);
    /* erase the line (a bar drawn by a worker process of the threshold scan too) */
    if (bar.what) fprintf(stderr, "\r\033[K");
    bar = (rd_cli_progress){ 0 };
}

void rd_cli_progress_clear(void)
{
    if (bar.what) fprintf(stderr, "\r\033[K");
    fflush(stderr);
}
