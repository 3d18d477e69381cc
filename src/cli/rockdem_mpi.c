/* rockdem-mpi — `mpirun -n N rockdem-mpi sweep ...` (make mpi): the sweep of cli_sweep.c with
 * its cases spread over MPI ranks, every rank computing. Every rank parses the same command line
 * into the same plan. Rank 0 coordinates (it alone opens and writes the table, resumes, shows
 * progress) and runs cases too, in one forked local worker (the fork pool of sweep_pool.c with
 * one process: it shares no HDF5 state with the coordinator and never calls MPI); ranks
 * 1..N-1 receive case indices (-1 = stop) and send back one rd_sweep_result each, as raw bytes
 * (all ranks run the same binary on the same kind of machine). Worker 0 of the pool is the
 * local process, worker w >= 1 is rank w. With one rank it falls back to the fork pool (-j).
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"

#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { TAG_CASE = 1, TAG_RESULT = 2 };

/* the coordinator's poll period while it waits for results (ns): 1 ms */
#define POLL_NS 1000000L

typedef struct mpi_ctx {
    int size;            /* ranks */
    rd_sweep_pool local; /* rank 0's own worker process: pool worker 0 */
} mpi_ctx;

static int mpi_send(void *ctx, int w, long k)
{
    mpi_ctx *c = ctx;
    if (w == 0) return c->local.send(c->local.ctx, 0, k);
    return MPI_Send(&k, 1, MPI_LONG, w, TAG_CASE, MPI_COMM_WORLD) == MPI_SUCCESS ? 0 : -1;
}

/* Polls the local worker and the ranks every millisecond up to wait_ms. */
static int mpi_recv(void *ctx, int wait_ms, int *worker, rd_sweep_result *r)
{
    mpi_ctx *c = ctx;
    struct timespec ms = { 0, POLL_NS };
    for (int t = 0; t <= wait_ms; t++) {
        int flag = 0, rc = c->local.recv(c->local.ctx, 0, worker, r);
        if (rc != 0) return rc; /* *worker is 0 */
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, TAG_RESULT, MPI_COMM_WORLD, &flag, &st);
        if (flag) {
            MPI_Recv(r, (int)sizeof *r, MPI_BYTE, st.MPI_SOURCE, TAG_RESULT, MPI_COMM_WORLD,
                     MPI_STATUS_IGNORE);
            *worker = st.MPI_SOURCE;
            return 1;
        }
        nanosleep(&ms, NULL);
    }
    return 0;
}

/* Ctrl-C reaches the ranks through mpirun; the local worker gets it from the fork pool. */
static void mpi_interrupt(void *ctx)
{
    mpi_ctx *c = ctx;
    c->local.interrupt(c->local.ctx);
}

static void mpi_finish(void *ctx)
{
    mpi_ctx *c = ctx;
    for (int w = 1; w < c->size; w++) mpi_send(c, w, -1);
    c->local.finish(c->local.ctx);
    free(c);
}

static int mpi_open(const rd_sweep_plan *p, rd_sweep_pool *pool)
{
    rd_error err;
    mpi_ctx *c = malloc(sizeof *c);
    if (!c) return -1;
    MPI_Comm_size(MPI_COMM_WORLD, &c->size);
    if (rd_sweep_pool_fork(p, 1, &c->local, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        free(c);
        return -1;
    }
    *pool = (rd_sweep_pool){ .nworkers = c->size,
                             .ctx = c,
                             .send = mpi_send,
                             .recv = mpi_recv,
                             .interrupt = mpi_interrupt,
                             .finish = mpi_finish };
    return 0;
}

/* A worker rank: cases until -1. */
static int mpi_serve(const rd_sweep_plan *p)
{
    long k;
    rd_sweep_result *r = malloc(sizeof *r);
    if (!r) return 3;
    while (MPI_Recv(&k, 1, MPI_LONG, 0, TAG_CASE, MPI_COMM_WORLD, MPI_STATUS_IGNORE) ==
               MPI_SUCCESS &&
           k >= 0) {
        rd_sweep_run_case(p, k, r);
        MPI_Send(r, (int)sizeof *r, MPI_BYTE, 0, TAG_RESULT, MPI_COMM_WORLD);
    }
    free(r);
    return 0;
}

int main(int argc, char **argv)
{
    MPI_Init(&argc, &argv);
    rd_sweep_backend b = { .serve = mpi_serve, .open = mpi_open };
    MPI_Comm_rank(MPI_COMM_WORLD, &b.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &b.size);
    int rc;
    if (argc >= 3 && !strcmp(argv[1], "sweep") && rd_cli_permute(argc, argv) == 0) {
        rc = rd_cli_sweep_with(argc, argv, &b);
    } else {
        if (b.rank == 0)
            fprintf(stderr, "usage: mpirun -n N rockdem-mpi sweep FILE ... (see rockdem --help)\n");
        rc = 2;
    }
    MPI_Finalize();
    return rc;
}
