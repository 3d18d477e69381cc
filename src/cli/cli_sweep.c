/* rockdem sweep SCENARIO [--set k=v]... --axis KEY=V1,V2 [--axis ...] [--records F1,F2]
 *     [--scales S1,S2] [--directions D1,D2] [-j N] [--keep-runs DIR] [-q] -o TABLE.h5
 * The coordinator: builds the plan, starts the workers (fork pool, or MPI ranks through a
 * backend), skips the cases already in the table, hands out the rest one at a time, appends
 * each result as it arrives and shows progress on stderr (docs/FRAGILITY.md).
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static volatile sig_atomic_t interrupted;

static void on_signal(int sig)
{
    (void)sig;
    interrupted = 1;
}

typedef struct sweep_args {
    const char *out, *records, *scales, *directions;
    int njobs, quiet;
    int naxes;
    const char *axis[RD_SWEEP_MAX_AXES];
} sweep_args;

/* The value of option argv[*i] ("--opt V" or "--opt=V"), or NULL when argv[*i] is not opt. */
static const char *opt_value(int argc, char **argv, int *i, const char *opt)
{
    size_t n = strlen(opt);
    if (strncmp(argv[*i], opt, n)) return NULL;
    if (argv[*i][n] == '=') return argv[*i] + n + 1;
    if (argv[*i][n] || *i + 1 >= argc) return NULL;
    return argv[++*i];
}

/* --keep-runs DIR: a folder the runs can be written into, made when missing; 0, or -1 with err.
 * An existing file there was taken, and every case then failed to write (exit 3, a line each). */
static int keep_dir_ok(const char *dir, rd_error *err)
{
    struct stat st;
    if (mkdir(dir, 0777) && errno != EEXIST)
        return rd_error_set(err, "rockdem sweep: --keep-runs %s: %s", dir, strerror(errno));
    if (stat(dir, &st) || !S_ISDIR(st.st_mode))
        return rd_error_set(err, "rockdem sweep: --keep-runs %s: not a folder", dir);
    if (access(dir, W_OK | X_OK))
        return rd_error_set(err, "rockdem sweep: --keep-runs %s: %s", dir, strerror(errno));
    return 0;
}

static int parse_args(int argc, char **argv, sweep_args *a, rd_sweep_plan *p, rd_error *err)
{
    int seen[argc], nseen = 0; /* the options' places, for rd_cli_repeated */
    for (int i = 3; i < argc; i++) {
        const char *v;
        if (rd_cli_repeated(argc, argv, seen, nseen, i, err)) return -1;
        seen[nseen++] = i;
        if ((v = opt_value(argc, argv, &i, "--set"))) {
            char **s = realloc(p->sets, (size_t)(p->nsets + 1) * sizeof *s);
            if (!s) return rd_error_set(err, "rockdem sweep: out of memory");
            (p->sets = s)[p->nsets++] = (char *)v;
        } else if ((v = opt_value(argc, argv, &i, "--axis"))) {
            if (a->naxes == RD_SWEEP_MAX_AXES)
                return rd_error_set(err, "rockdem sweep: too many --axis");
            a->axis[a->naxes++] = v;
        } else if ((v = opt_value(argc, argv, &i, "--records")))
            a->records = v;
        else if ((v = opt_value(argc, argv, &i, "--scales")))
            a->scales = v;
        else if ((v = opt_value(argc, argv, &i, "--directions")))
            a->directions = v;
        else if ((v = opt_value(argc, argv, &i, "--keep-runs")))
            p->keep_dir = v;
        else if ((v = opt_value(argc, argv, &i, "-o")))
            a->out = v;
        else if ((v = opt_value(argc, argv, &i, "-j"))) {
            char *end;
            long n = strtol(v, &end, 10);
            if (*end || end == v || n < 1 || n > 4096)
                return rd_error_set(
                    err, "rockdem sweep: -j expects a number of workers (1 to 4096), got '%s'", v);
            a->njobs = (int)n;
        } else if (!strcmp(argv[i], "-q"))
            a->quiet = 1;
        else if (!strcmp(argv[i], "--full"))
            p->full = 1;
        else
            return rd_error_set(
                err, "rockdem sweep: unknown option or missing value '%s' (see rockdem --help)",
                argv[i]);
    }
    if (!a->out) return rd_error_set(err, "rockdem sweep: missing -o TABLE.h5");
    if ((a->records && rd_sweep_add_axis(p, RD_AXIS_RECORD, a->records, err)) ||
        (a->scales && rd_sweep_add_axis(p, RD_AXIS_SCALE, a->scales, err)) ||
        (a->directions && rd_sweep_add_axis(p, RD_AXIS_DIRECTION, a->directions, err)))
        return -1;
    for (int k = 0; k < a->naxes; k++)
        if (rd_sweep_add_axis(p, RD_AXIS_SET, a->axis[k], err)) return -1;
    if (p->naxes == 0)
        return rd_error_set(
            err,
            "rockdem sweep: nothing to sweep: give --axis, --records, --scales or --directions");
    return p->keep_dir ? keep_dir_ok(p->keep_dir, err) : 0;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void hms(double s, char *buf, size_t n)
{
    long t = (long)(s + 0.5);
    if (t >= 3600)
        snprintf(buf, n, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
    else
        snprintf(buf, n, "%ld:%02ld", t / 60, t % 60);
}

typedef struct progress {
    long total, before, done, running; /* cases: all, in the table at the start, finished now */
    double t0, shown;
    int tty, quiet;
} progress;

/* The progress line on stderr: redrawn at most 4 times a second on a terminal; elsewhere (a
 * log, a pipe) only the final line. */
static void show(progress *g, int final)
{
    double t = now();
    if (g->quiet || (!final && (!g->tty || t - g->shown < 0.25))) return;
    g->shown = t;
    char el[32], eta[32] = "?";
    hms(t - g->t0, el, sizeof el);
    long left = g->total - g->before - g->done;
    if (g->done > 0) hms((t - g->t0) / (double)g->done * (double)left, eta, sizeof eta);
    fprintf(stderr, "%ssweep: %ld/%ld done, %ld running, %s elapsed, ETA %s%s", g->tty ? "\r" : "",
            g->before + g->done, g->total, g->running, el, eta, g->tty && !final ? "  " : "\n");
    fflush(stderr);
}

typedef struct driver {
    rd_sweep_pool *pool;
    rd_sweep_table *table;
    const rd_sweep_plan *plan;
    long *todo, ntodo, next;
    long failed, lost, overturned;
    int write_error;
    progress g;
} driver;

/* Give worker w its next case, if any and not stopping. */
static void hand_out(driver *d, int w)
{
    if (interrupted || d->write_error || d->next >= d->ntodo) return;
    if (d->pool->send(d->pool->ctx, w, d->todo[d->next]) == 0) {
        d->next++;
        d->g.running++;
    }
}

static void take(driver *d, const rd_sweep_result *r)
{
    rd_error err;
    if (r->status == RD_STATUS_INTERRUPTED) {
        d->lost++;
        return;
    }
    if (r->status < 0 ||
        r->status == RD_STATUS_IO_ERROR) { /* not a result: a resume runs it again */
        fprintf(stderr, "%s%s\n", d->g.tty ? "\n" : "", r->message);
        d->failed++;
        return;
    }
    if (r->message[0])
        fprintf(stderr, "%srockdem sweep: case %ld: %s\n", d->g.tty ? "\n" : "", r->index,
                r->message);
    if (d->write_error) return;
    if (rd_sweep_table_append(d->table, r, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        d->write_error = 1;
        return;
    }
    d->g.done++;
    d->overturned += r->overturned;
}

static void drive(driver *d)
{
    rd_sweep_result *r = malloc(sizeof *r);
    int forwarded = 0;
    if (!r) {
        d->write_error = 1;
        return;
    }
    for (int w = 0; w < d->pool->nworkers; w++) hand_out(d, w);
    while (d->g.running > 0) {
        if (interrupted && !forwarded) {
            d->pool->interrupt(d->pool->ctx);
            forwarded = 1;
        }
        int w, rc = d->pool->recv(d->pool->ctx, 250, &w, r);
        if (rc != 0) d->g.running--;
        if (rc > 0) take(d, r);
        if (rc < 0) {
            fprintf(
                stderr,
                "%srockdem sweep: worker %d died; its case is not in the table (run again to retry)\n",
                d->g.tty ? "\n" : "", w);
            d->failed++;
        }
        if (rc > 0) hand_out(d, w);
        show(&d->g, 0);
    }
    free(r);
}

/* Coordinator: table, pool, cases; returns the exit status. */
static int coordinate(const rd_sweep_plan *p, const sweep_args *a, rd_sweep_pool *pool)
{
    rd_error err;
    char *done = calloc((size_t)p->ncases, 1);
    driver d = { .pool = pool, .plan = p, .todo = malloc((size_t)p->ncases * sizeof(long)) };
    d.table = done && d.todo ? rd_sweep_table_open(a->out, p, done, &err) : NULL;
    if (!d.table) {
        fprintf(stderr, "%s\n", done && d.todo ? err.msg : "rockdem sweep: out of memory");
        pool->finish(pool->ctx);
        free(done);
        free(d.todo);
        return 2;
    }
    for (long k = 0; k < p->ncases; k++)
        if (!done[k]) d.todo[d.ntodo++] = k;
    if (rd_sweep_table_dropped(d.table))
        fprintf(
            stderr,
            "rockdem sweep: %s: dropped %ld partially written row(s) at its end (a write was cut "
            "short); their cases run again\n",
            a->out, rd_sweep_table_dropped(d.table));
    d.g = (progress){ .total = p->ncases,
                      .before = p->ncases - d.ntodo,
                      .t0 = now(),
                      .tty = isatty(2),
                      .quiet = a->quiet };
    drive(&d);
    pool->finish(pool->ctx);
    show(&d.g, 1);
    int complete = d.g.before + d.g.done == p->ncases;
    if (complete && !d.write_error && rd_sweep_table_sort(d.table, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        d.write_error = 1;
    }
    if (!a->quiet)
        printf(
            "sweep: %ld cases (%ld run now, %ld already in the table), %ld overturned now; %s%s\n",
            p->ncases, d.g.done, d.g.before, d.overturned, a->out, complete ? "" : " (incomplete)");
    rd_sweep_table_close(d.table);
    free(done);
    free(d.todo);
    if (interrupted) {
        fprintf(stderr,
                "rockdem sweep: interrupted; %s holds every finished case; run the same command "
                "to resume\n",
                a->out);
        return 130;
    }
    if (!complete)
        fprintf(
            stderr,
            "rockdem sweep: %s is incomplete: %ld of %ld cases%s; run the same command to resume\n",
            a->out, d.g.before + d.g.done, p->ncases,
            d.write_error ? " (a write failed, see above)" : "");
    return d.write_error || d.failed || !complete ? 3 : 0;
}

int rd_cli_sweep_with(int argc, char **argv, const rd_sweep_backend *b)
{
    rd_sweep_plan p = { .path = argv[2] };
    sweep_args a = { .njobs = (int)sysconf(_SC_NPROCESSORS_ONLN) };
    rd_error err;
    int rank = b ? b->rank : 0, rc;
    if (parse_args(argc, argv, &a, &p, &err) || rd_sweep_plan_finish(&p, &err)) {
        if (rank == 0) fprintf(stderr, "%s\n", err.msg);
        rd_sweep_plan_free(&p);
        free(p.sets);
        return 2;
    }
    rd_sweep_pool pool;
    if (b && b->size > 1 && rank > 0) {
        rc = b->serve(&p);
    } else {
        signal(SIGINT, on_signal);
        signal(SIGTERM, on_signal);
        signal(SIGHUP, on_signal);
        signal(SIGPIPE, SIG_IGN);
        int n = a.njobs < p.ncases ? a.njobs : (int)p.ncases;
        if (b && b->size > 1 ? b->open(&p, &pool)
                             : rd_sweep_pool_fork(&p, n < 1 ? 1 : n, &pool, &err)) {
            fprintf(stderr, "%s\n",
                    b && b->size > 1 ? "rockdem sweep: cannot start the MPI workers" : err.msg);
            rc = 3;
        } else {
            rc = coordinate(&p, &a, &pool);
        }
    }
    rd_sweep_plan_free(&p);
    free(p.sets);
    return rc;
}

int rd_cli_sweep(int argc, char **argv) { return rd_cli_sweep_with(argc, argv, NULL); }
