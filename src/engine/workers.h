/* rockdem (private) — one run on several threads (workers.c): the contact loop's live pairs
 * shared out in chunks, each chunk run on a thread's view of the simulation (its own scratch)
 * and recording, on the chunk's tape, every addition it makes to a sum that other pairs share
 * (the bodies' force and torque, the friction and damping energies, a monitored body's contact
 * area). After the loop the tapes are played back in chunk order, so each sum takes the same
 * terms in the same order as the serial loop: the same bits for any number of threads.
 * Folder engine/ owns the simulation; it may call base/, geometry/, records/ and scenario/.
 */
#ifndef RD_WORKERS_H
#define RD_WORKERS_H

#include "engine/sim.h"
#include "base/vec.h"

#include <stddef.h>

/* An OpenMP pragma, left out of a build without OpenMP (`make OPENMP=`: every loop serial,
 * rd_threads_for is then 1). */
#ifdef _OPENMP
#define RD_OMP(directive) _Pragma(#directive)
#else
#define RD_OMP(directive)
#endif

/* One recorded addition: *to += v. */
typedef struct rd_tape_entry {
    double *to;
    double v;
} rd_tape_entry;

/* Bytes of a cache line: what one core's write takes from another's cache. */
#define RD_CACHE_LINE 64

/* The additions of one chunk of live pairs, in the order the serial loop makes them. Each tape
 * fills whole cache lines of its own (workers.c allocates them aligned): the chunks running at
 * once are mostly neighbours, and their counts, written at every addition, sharing a line made
 * the two cores pass it back and forth. */
typedef struct rd_tape {
    _Alignas(RD_CACHE_LINE) rd_tape_entry *e;
    size_t n, cap;
    int failed;  /* 1: out of memory growing it (rd_contact_step fails) */
    rd_sim *sim; /* the simulation (the energies' sums: rd_book_fric, rd_book_damp) */
} rd_tape;

void rd_tape_grow(rd_tape *t); /* room for one more entry, or failed set */

static inline void rd_tape_add(rd_tape *t, double *to, double v)
{
    if (t->n == t->cap) {
        rd_tape_grow(t);
        if (t->failed) return;
    }
    t->e[t->n].to = to;
    t->e[t->n].v = v;
    t->n++;
}

/* *to += v, or, on a thread's view (s->tape set), recorded for the play-back. */
static inline void rd_book(rd_sim *s, double *to, double v)
{
    if (s->tape)
        rd_tape_add(s->tape, to, v);
    else
        *to += v;
}

/* Friction and damping energy, J (rd_sim.e_fric, e_damp of the simulation, not of the view). */
static inline void rd_book_fric(rd_sim *s, double v)
{
    if (s->tape)
        rd_tape_add(s->tape, &s->tape->sim->e_fric, v);
    else
        s->e_fric += v;
}
static inline void rd_book_damp(rd_sim *s, double v)
{
    if (s->tape)
        rd_tape_add(s->tape, &s->tape->sim->e_damp, v);
    else
        s->e_damp += v;
}

/* Whole-number tallies (a watch's active and slipping points): order does not matter, so a
 * view adds atomically. */
static inline void rd_count(rd_sim *s, int *to, int v)
{
    if (s->tape)
        __atomic_fetch_add(to, v, __ATOMIC_RELAXED);
    else
        *to += v;
}

/* law.h's rd_law_apply (F at ro on the owner o, -F at rt on t when t_free) with each addition
 * booked: the same expressions, so the same terms (1.0 * x is x, -1.0 * x is -x exactly). */
static inline void rd_book_apply(rd_sim *s, const double F[3], const double ro[3],
                                 const double rt[3], int o, int t_free, int t)
{
    double tmp[3];
    rd_cross(ro, F, tmp);
    for (int k = 0; k < 3; k++) rd_book(s, &s->f[o][k], F[k]);
    for (int k = 0; k < 3; k++) rd_book(s, &s->tq[o][k], tmp[k]);
    if (t_free) {
        rd_cross(rt, F, tmp);
        for (int k = 0; k < 3; k++) rd_book(s, &s->f[t][k], -F[k]);
        for (int k = 0; k < 3; k++) rd_book(s, &s->tq[t][k], -tmp[k]);
    }
}

/* The threads a run asks for: sc->threads, or where 0 OMP_NUM_THREADS's first number, else 1;
 * at most RD_THREADS_MAX. */
int rd_threads_of(const rd_scenario *sc);

/* Threads a loop over n items runs on: 1, or s->nthreads once each thread has at least
 * RD_ITEMS_PER_THREAD of them (fewer are not worth the thread team's start). */
int rd_threads_for(const rd_sim *s, long n);

/* rd_contact_step's loop over the live pairs on s->nthreads threads: 1 when it ran them, 0 when
 * they are too few (the caller runs them serially), -1 when out of memory. */
int rd_workers_contact(rd_sim *s);

void rd_workers_free(rd_sim *s);

#endif
