/* rockdem — one run on several threads (engine/workers.h): the contact loop's live pairs in
 * chunks on an OpenMP team, each thread on its own view of the simulation, the shared sums
 * recorded on the chunks' tapes and played back in chunk order.
 *
 * What the contact loop writes besides each pair's own state (its points' springs, flags and
 * measures, its sides' caches): the bodies' force and torque sums, the friction and damping
 * energies and a monitored body's contact area, each a sum over pairs whose round-off depends
 * on the order of its terms (booked: workers.h); a monitored body's active and slipping counts
 * (whole numbers: added atomically); the impact flags (set atomically); the active
 * point-steps (each view's own, added after); and its scratch (the plane arrays, the vertex
 * distances and masks, the point kinematics cache, edge.c's arrays: one set per thread). The
 * chunks are fixed by the live pairs alone, and the tapes played back in chunk order give every
 * sum the serial loop's terms in the serial loop's order: the bits of one thread for any
 * number (tests/cli/threads.sh).
 * Folder engine/ owns the simulation; it may call base/, geometry/, records/ and scenario/.
 */
#include "engine/workers.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* Live pairs per thread below which the contact loop stays serial, and bodies or joints per
 * thread below which their loops do: fewer do not pay for the team's start (a few us). The
 * test build $(BUILD)/tests/rockdem-threads sets 0, so that small scenes of every kind of
 * contact (edges, impacts, dashpots, slip: tests/cli/threads.sh) run threaded too. */
#ifndef RD_ITEMS_PER_THREAD
#define RD_ITEMS_PER_THREAD 32
#endif
/* Subcontact points per thread above which a loop over fewer pairs than RD_ITEMS_PER_THREAD
 * per thread runs threaded: 32 of a wall's bricks' pairs carry about 500 (8 corner points
 * a side, two sides), so the same work. */
#ifndef RD_POINTS_PER_THREAD
#define RD_POINTS_PER_THREAD 512
#endif
/* Chunks of live pairs per thread: thread t runs the chunks of its own block (the t-th of the
 * live list's n equal blocks) first, then takes the chunks left in the others' blocks, so a
 * block of costly pairs (a wall's end on its footing) does not hold the others back. */
#define RD_CHUNKS_PER_THREAD 16
#define RD_TAPE_MIN          2048 /* words of a tape's first block */

/* One thread's view of the simulation: a copy of rd_sim with the thread's own scratch. */
typedef struct rd_worker {
    rd_sim *view;
    struct rd_plane_scratch *plane_scratch;
    struct rd_edge_scratch *edge_scratch;
    double *cv_dist;
    uint64_t *cv_mask;
    double (*kin)[6];
    long *kin_stamp;
    long kin_epoch; /* the view's kin_epoch, kept from step to step (its stamps are its own) */
    long active_point_steps; /* the view's this step */
} rd_worker;

/* The chunks of one block taken so far, on a cache line of its own (every thread may take). */
typedef struct rd_block {
    _Alignas(RD_CACHE_LINE) int taken;
} rd_block;

typedef struct rd_workers {
    int n;          /* threads */
    rd_worker *w;   /* [n] */
    rd_block *next; /* [n] */
    int ntape;      /* n * RD_CHUNKS_PER_THREAD */
    rd_tape *tape;  /* [ntape] */
} rd_workers;

int rd_threads_of(const rd_scenario *sc)
{
    long n = sc->threads;
    const char *env = getenv("OMP_NUM_THREADS");
    if (n <= 0 && env && *env) {
        char *end;
        errno = 0;
        n = strtol(env, &end, 10); /* a list "4,2" asks for 4 at the outer level */
        if (errno || end == env || (*end && *end != ',')) n = 1;
    }
    if (n < 1) n = 1;
    return n > RD_THREADS_MAX ? RD_THREADS_MAX : (int)n;
}

int rd_threads_for(const rd_sim *s, long n)
{
#ifdef _OPENMP
    if (s->nthreads > 1 && n >= (long)RD_ITEMS_PER_THREAD * s->nthreads) return s->nthreads;
#endif
    (void)s;
    (void)n;
    return 1;
}

int rd_threads_for_pairs(const rd_sim *s, const int *list, int n)
{
    const int t = rd_threads_for(s, n);
#ifdef _OPENMP
    if (t == 1 && s->nthreads > 1 && n >= 2 * s->nthreads) {
        long points = 0; /* n is small here: fewer than RD_ITEMS_PER_THREAD pairs per thread */
        for (int k = 0; k < n; k++) {
            const rd_pair *pr = &s->pair[list ? list[k] : k];
            for (int q = 0; q < pr->nside; q++)
                points += s->pt0[pr->side[q].owner + 1] - s->pt0[pr->side[q].owner];
        }
        if (points >= (long)RD_POINTS_PER_THREAD * s->nthreads) return s->nthreads;
    }
#endif
    (void)list;
    return t;
}

void rd_tape_grow(rd_tape *t, size_t k)
{
    size_t cap = t->cap ? 2 * t->cap : RD_TAPE_MIN;
    while (cap < t->n + k) cap *= 2;
    rd_tape_word *w = realloc(t->w, cap * sizeof *w);
    if (!w) {
        t->failed = 1;
        return;
    }
    t->w = w;
    t->cap = cap;
}

void rd_workers_free(rd_sim *s)
{
    rd_workers *W = s->workers;
    if (!W) return;
    for (int i = 0; W->w && i < W->n; i++) {
        rd_worker *w = &W->w[i];
        free(w->view);
        free(w->plane_scratch);
        free(w->edge_scratch);
        free(w->cv_dist);
        free(w->cv_mask);
        free(w->kin);
        free(w->kin_stamp);
    }
    for (int c = 0; W->tape && c < W->ntape; c++) free(W->tape[c].w);
    free(W->w);
    free(W->next);
    free(W->tape);
    free(W);
    s->workers = NULL;
}

#ifdef _OPENMP
/* The threads' views and scratch, and the tapes: 0, or -1 (memory). */
static int workers_new(rd_sim *s)
{
    rd_workers *W = calloc(1, sizeof *W);
    if (!W) return -1;
    s->workers = W;
    W->n = s->nthreads;
    W->ntape = W->n * RD_CHUNKS_PER_THREAD;
    W->w = calloc((size_t)W->n, sizeof *W->w);
    W->next = aligned_alloc(RD_CACHE_LINE, (size_t)W->n * sizeof *W->next);
    W->tape = aligned_alloc(RD_CACHE_LINE, (size_t)W->ntape * sizeof *W->tape);
    if (!W->w || !W->next || !W->tape) return -1;
    memset(W->tape, 0, (size_t)W->ntape * sizeof *W->tape);
    const size_t nd = s->ndist ? s->ndist : 1, nm = s->nmask ? s->nmask : 1,
                 nk = s->nkin > 0 ? (size_t)s->nkin : 1;
    for (int i = 0; i < W->n; i++) {
        rd_worker *w = &W->w[i];
        w->view = malloc(sizeof *w->view);
        w->plane_scratch = rd_contact_scratch(s);
        w->edge_scratch = rd_edge_scratch_new(s);
        w->cv_dist = calloc(nd, sizeof *w->cv_dist);
        w->cv_mask = calloc(nm, sizeof *w->cv_mask);
        w->kin = calloc(nk, sizeof *w->kin);
        w->kin_stamp = calloc(nk, sizeof *w->kin_stamp); /* 0: no side step yet (epochs from 1) */
        if (!w->view || !w->plane_scratch || !w->edge_scratch || !w->cv_dist || !w->cv_mask ||
            !w->kin || !w->kin_stamp)
            return -1;
    }
    return 0;
}

/* Thread i's view of s for this step: every field as s has it now, its own scratch and tape. */
static void view_of(rd_sim *s, rd_worker *w)
{
    rd_sim *v = w->view;
    memcpy(v, s, sizeof *v);
    v->plane_scratch = w->plane_scratch;
    v->edge_scratch = w->edge_scratch;
    v->cv_dist = w->cv_dist;
    v->cv_mask = w->cv_mask;
    v->kin = w->kin;
    v->kin_stamp = w->kin_stamp;
    v->kin_epoch = w->kin_epoch;
    v->active_point_steps = 0;
    v->workers = NULL;
}

/* The next chunk for thread t of a team of nt: its own block's next, else the next left in
 * the following threads' blocks; -1 when every chunk is taken. Block b holds chunks
 * [nchunk b / nt, nchunk (b + 1) / nt). Which thread runs a chunk changes no result (each
 * chunk books on its own tape), only which core's cache holds its pairs: with each thread on
 * its own block, the same pairs from step to step, their state stays in one core's cache,
 * where chunks taken in turn by whichever thread was free moved about half of it between the
 * cores every step. */
static int chunk_next(rd_workers *W, int t, int nt, int nchunk)
{
    for (int k = 0; k < nt; k++) {
        const int b = (t + k) % nt, lo = (int)((long)nchunk * b / nt),
                  hi = (int)((long)nchunk * (b + 1) / nt);
        if (__atomic_load_n(&W->next[b].taken, __ATOMIC_RELAXED) >= hi - lo) continue;
        const int c = lo + __atomic_fetch_add(&W->next[b].taken, 1, __ATOMIC_RELAXED);
        if (c < hi) return c;
    }
    return -1;
}

/* Plays one tape back into s (workers.h: the records). */
static void play_tape(rd_sim *s, const rd_tape *t)
{
    const rd_tape_word *w = t->w;
    for (size_t k = 0, n = t->n; k < n;) {
        const uintptr_t h = w[k].tag;
        if (!(h & 1u)) {
            *w[k].to += w[k + 1].v;
            k += 2;
            continue;
        }
        const int o = (int)(h >> 3);
        if ((h & 7u) == RD_TAPE_BODY) {
            for (int c = 0; c < 3; c++) {
                s->f[o][c] += w[k + 1 + c].v;
                s->tq[o][c] += w[k + 4 + c].v;
            }
            k += 7;
            continue;
        }
        const int ot = (int)w[k + 1].tag;
        for (int c = 0; c < 3; c++) {
            s->f[o][c] += w[k + 2 + c].v;
            s->tq[o][c] += w[k + 5 + c].v;
            s->f[ot][c] += -w[k + 2 + c].v;
            s->tq[ot][c] += w[k + 8 + c].v;
        }
        k += 11;
    }
}

/* Plays the tapes back in chunk order: every shared sum takes its terms as the serial loop
 * gives them. 0, or -1 when a tape ran out of memory. */
static int play_back(rd_sim *s, rd_workers *W, int nchunk)
{
    for (int c = 0; c < nchunk; c++)
        if (W->tape[c].failed) return -1;
    for (int c = 0; c < nchunk; c++) play_tape(s, &W->tape[c]);
    return 0;
}
#endif

int rd_workers_contact(rd_sim *s)
{
#ifdef _OPENMP
    const int n = rd_threads_for_pairs(s, s->live, s->nlive);
    if (n < 2) return 0;
    if (!s->workers && workers_new(s)) {
        rd_workers_free(s);
        return -1;
    }
    rd_workers *W = s->workers;
    const int nchunk = s->nlive < W->ntape ? s->nlive : W->ntape;
    for (int c = 0; c < nchunk; c++) {
        W->tape[c].n = 0;
        W->tape[c].failed = 0;
        W->tape[c].sim = s;
    }
    const int nlive = s->nlive;
    const int *live = s->live;
    rd_pair *pair = s->pair;
    for (int t = 0; t < n; t++) W->next[t].taken = 0;
    int team = 1; /* the threads the team has (OpenMP may give fewer than asked) */
#pragma omp parallel num_threads(n)
    {
        const int t = omp_get_thread_num(), nt = omp_get_num_threads();
#pragma omp master
        team = nt;
        rd_worker *w = &W->w[t];
        view_of(s, w);
        rd_sim *v = w->view;
        /* chunk c: live pairs [nlive c / nchunk, nlive (c + 1) / nchunk), on any thread */
        for (int c; (c = chunk_next(W, t, nt, nchunk)) >= 0;) {
            v->tape = &W->tape[c];
            const int k1 = (int)((long)nlive * (c + 1) / nchunk);
            for (int k = (int)((long)nlive * c / nchunk); k < k1; k++)
                rd_contact_pair(v, &pair[live[k]]);
        }
        w->kin_epoch = v->kin_epoch;
        w->active_point_steps = v->active_point_steps;
    }
    for (int i = 0; i < team; i++) s->active_point_steps += W->w[i].active_point_steps;
    if (team > s->team) s->team = team;
    return play_back(s, W, nchunk) ? -1 : 1;
#else
    (void)s;
    return 0;
#endif
}
