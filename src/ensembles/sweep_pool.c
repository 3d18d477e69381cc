/* rockdem — the fork pool of `rockdem sweep` (include/rockdem/sweep.h): n worker processes, each
 * with a task pipe (case indices in, -1 = stop) and a result pipe (one rd_sweep_result per case
 * out). Workers are forked before the coordinator opens the HDF5 table and leave with _exit, so
 * they share no HDF5 state with it. A worker that dies closes its result pipe: the coordinator
 * sees end-of-file, loses that worker's case (a resume runs it again) and goes on with the rest.
 * Folder ensembles/ owns many-run studies (threshold, restitution, sweeps); it may call the public
 * API (engine, scenario, reference) and io/.
 */
#define _GNU_SOURCE
#include "rockdem/sweep.h"
#include "ensembles/pipe_io.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

typedef struct pool_ctx {
    int n;
    pid_t *pid;
    int *task;   /* write end of each worker's task pipe (-1 once closed) */
    int *result; /* read end of each worker's result pipe (-1 once closed) */
} pool_ctx;

static void on_stop(int sig)
{
    (void)sig;
    rd_sweep_request_stop();
}

/* The worker: cases in, results out, until -1 or end of file. Never returns. */
static void worker(const rd_sweep_plan *p, int in, int out)
{
    long k;
    rd_sweep_result *r = malloc(sizeof *r);
    signal(SIGINT, on_stop);
    signal(SIGTERM, on_stop);
    signal(SIGHUP, on_stop);
    while (r && rd_pipe_read(in, &k, sizeof k) == 0 && k >= 0) {
        rd_sweep_run_case(p, k, r);
        if (rd_pipe_write(out, r, sizeof *r)) break;
    }
    _exit(r ? 0 : 3);
}

static int pool_send(void *ctx, int w, long k)
{
    pool_ctx *c = ctx;
    return c->task[w] >= 0 && rd_pipe_write(c->task[w], &k, sizeof k) == 0 ? 0 : -1;
}

static int pool_recv(void *ctx, int wait_ms, int *worker, rd_sweep_result *r)
{
    pool_ctx *c = ctx;
    struct pollfd fds[c->n];
    for (int w = 0; w < c->n; w++) fds[w] = (struct pollfd){ .fd = c->result[w], .events = POLLIN };
    int rc = poll(fds, (nfds_t)c->n, wait_ms);
    if (rc <= 0) return 0; /* timeout, or a signal: the caller looks at its flags and waits again */
    for (int w = 0; w < c->n; w++) {
        if (!(fds[w].revents & (POLLIN | POLLHUP | POLLERR))) continue;
        *worker = w;
        if (rd_pipe_read(c->result[w], r, sizeof *r) == 0) return 1;
        close(c->result[w]);
        c->result[w] = -1;
        return -1;
    }
    return 0;
}

static void pool_interrupt(void *ctx)
{
    pool_ctx *c = ctx;
    for (int w = 0; w < c->n; w++)
        if (c->pid[w] > 0) kill(c->pid[w], SIGINT);
}

static void pool_finish(void *ctx)
{
    pool_ctx *c = ctx;
    for (int w = 0; w < c->n; w++)
        if (c->task[w] >= 0) close(c->task[w]); /* end of file: the worker leaves */
    for (int w = 0; w < c->n; w++) {
        if (c->result[w] >= 0) close(c->result[w]);
        if (c->pid[w] > 0) waitpid(c->pid[w], NULL, 0);
    }
    free(c->pid);
    free(c->task);
    free(c->result);
    free(c);
}

int rd_sweep_pool_fork(const rd_sweep_plan *p, int n, rd_sweep_pool *pool, rd_error *err)
{
    pool_ctx *c = calloc(1, sizeof *c);
    if (!c || !(c->pid = calloc((size_t)n, sizeof *c->pid)) ||
        !(c->task = malloc((size_t)n * sizeof(int))) ||
        !(c->result = malloc((size_t)n * sizeof(int)))) {
        if (c) {
            free(c->pid);
            free(c->task);
            free(c);
        }
        return rd_error_set(err, "rockdem sweep: out of memory");
    }
    *pool = (rd_sweep_pool){ .nworkers = n,
                             .ctx = c,
                             .send = pool_send,
                             .recv = pool_recv,
                             .interrupt = pool_interrupt,
                             .finish = pool_finish };
    fflush(NULL);
    pid_t coordinator = getpid();
    for (int w = 0; w < n; w++) {
        int tp[2], rp[2];
        c->task[w] = c->result[w] = -1;
        if (pipe2(tp, O_CLOEXEC) || pipe2(rp, O_CLOEXEC)) break;
        c->pid[w] = fork();
        if (c->pid[w] == 0) {
            /* the worker dies with its coordinator (even one killed by SIGKILL): SIGTERM stops
               its case; then the closed pipe ends it. The check closes the race with a
               coordinator that died before prctl. */
            if (prctl(PR_SET_PDEATHSIG, SIGTERM) || getppid() != coordinator) _exit(3);
            for (int v = 0; v < w; v++) {
                close(c->task[v]);
                close(c->result[v]);
            }
            close(tp[1]);
            close(rp[0]);
            worker(p, tp[0], rp[1]);
        }
        close(tp[0]);
        close(rp[1]);
        c->task[w] = tp[1];
        c->result[w] = rp[0];
        c->n = w + 1;
        if (c->pid[w] < 0) break;
    }
    if (c->n < n || c->pid[n - 1] < 0) {
        pool_finish(c);
        return rd_error_set(err, "rockdem sweep: cannot start %d worker processes: %s", n,
                            strerror(errno));
    }
    return 0;
}
