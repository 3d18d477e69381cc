/* rockdem-mpi — `mpirun -n N rockdem-mpi sweep ...` (make mpi): the sweep of cli_sweep.c with
 * its cases spread over MPI ranks. Every rank parses the same command line into the same plan;
 * rank 0 is the coordinator (it alone opens and writes the table, resumes, shows progress) and
 * ranks 1..N-1 are workers that receive case indices (-1 = stop) and send back one
 * rd_sweep_result each, as raw bytes (all ranks run the same binary on the same kind of
 * machine). With one rank it falls back to the fork pool (-j).
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

typedef struct mpi_ctx {
    int size;
} mpi_ctx;

static int mpi_send(void *ctx, int w, long k)
{
    (void)ctx;
    return MPI_Send(&k, 1, MPI_LONG, w + 1, TAG_CASE, MPI_COMM_WORLD) == MPI_SUCCESS ? 0 : -1;
}

/* Polls for a result every millisecond up to wait_ms. */
static int mpi_recv(void *ctx, int wait_ms, int *worker, rd_sweep_result *r)
{
    (void)ctx;
    struct timespec ms = {0, 1000000};
    for (int t = 0; t <= wait_ms; t++) {
        int flag = 0;
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, TAG_RESULT, MPI_COMM_WORLD, &flag, &st);
        if (flag) {
            MPI_Recv(r, (int)sizeof *r, MPI_BYTE, st.MPI_SOURCE, TAG_RESULT, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            *worker = st.MPI_SOURCE - 1;
            return 1;
        }
        nanosleep(&ms, NULL);
    }
    return 0;
}

/* Ctrl-C reaches the ranks through mpirun; nothing to pass on. */
static void mpi_interrupt(void *ctx) { (void)ctx; }

static void mpi_finish(void *ctx)
{
    mpi_ctx *c = ctx;
    for (int w = 1; w < c->size; w++) mpi_send(c, w - 1, -1);
    free(c);
}

static int mpi_open(const rd_sweep_plan *p, rd_sweep_pool *pool)
{
    (void)p;
    mpi_ctx *c = malloc(sizeof *c);
    if (!c) return -1;
    MPI_Comm_size(MPI_COMM_WORLD, &c->size);
    *pool = (rd_sweep_pool){.nworkers = c->size - 1, .ctx = c, .send = mpi_send, .recv = mpi_recv,
                            .interrupt = mpi_interrupt, .finish = mpi_finish};
    return 0;
}

/* A worker rank: cases until -1. */
static int mpi_serve(const rd_sweep_plan *p)
{
    long k;
    rd_sweep_result *r = malloc(sizeof *r);
    if (!r) return 3;
    while (MPI_Recv(&k, 1, MPI_LONG, 0, TAG_CASE, MPI_COMM_WORLD, MPI_STATUS_IGNORE) == MPI_SUCCESS && k >= 0) {
        rd_sweep_run_case(p, k, r);
        MPI_Send(r, (int)sizeof *r, MPI_BYTE, 0, TAG_RESULT, MPI_COMM_WORLD);
    }
    free(r);
    return 0;
}

int main(int argc, char **argv)
{
    MPI_Init(&argc, &argv);
    rd_sweep_backend b = {.serve = mpi_serve, .open = mpi_open};
    MPI_Comm_rank(MPI_COMM_WORLD, &b.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &b.size);
    int rc;
    if (argc >= 3 && !strcmp(argv[1], "sweep") && rd_cli_permute(argc, argv) == 0) {
        rc = rd_cli_sweep_with(argc, argv, &b);
    } else {
        if (b.rank == 0) fprintf(stderr, "usage: mpirun -n N rockdem-mpi sweep FILE ... (see rockdem --help)\n");
        rc = 2;
    }
    MPI_Finalize();
    return rc;
}
