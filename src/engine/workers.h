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
#include <stdint.h>

/* An OpenMP pragma, left out of a build without OpenMP (`make OPENMP=`: every loop serial,
 * rd_threads_for is then 1). */
#ifdef _OPENMP
#define RD_OMP(directive) _Pragma(#directive)
#else
#define RD_OMP(directive)
#endif

/* A tape is a stream of 8-byte words holding records, each headed by a word whose lowest bits
 * tell its kind (a double's address has them 0):
 *   add    [to][v]                        *to += v
 *   body   [o << 3 | 1][F 3][T 3]         f[o] += F, tq[o] += T
 *   pair   [o << 3 | 3][t][F 3][To 3][Tt 3] f[o] += F, tq[o] += To, f[t] += -F, tq[t] += Tt
 * A body or pair record is what the serial loop adds to those sums at that point, in its order
 * for each sum (the sums of different components and bodies do not meet), in 7 or 11 words
 * instead of the 12 or 24 of one add per component. */
typedef union rd_tape_word {
    double *to;
    double v;
    uintptr_t tag;
} rd_tape_word;

#define RD_TAPE_BODY 1u /* record kinds: the header's low 3 bits */
#define RD_TAPE_PAIR 3u

/* Bytes of a cache line: what one core's write takes from another's cache. */
#define RD_CACHE_LINE 64

/* The additions of one chunk of live pairs, in the order the serial loop makes them. Each tape
 * fills whole cache lines of its own (workers.c allocates them aligned): the chunks running at
 * once are mostly neighbours, and their counts, written at every addition, sharing a line made
 * the two cores pass it back and forth. */
typedef struct rd_tape {
    _Alignas(RD_CACHE_LINE) rd_tape_word *w;
    size_t n, cap; /* words */
    int failed;    /* 1: out of memory growing it (rd_contact_step fails) */
    rd_sim *sim;   /* the simulation (the bodies' sums, the energies: rd_book_fric, rd_book_damp) */
} rd_tape;

void rd_tape_grow(rd_tape *t, size_t k); /* room for k more words, or failed set */

/* Room for k more words: 1, or 0 (failed set). */
static inline int rd_tape_room(rd_tape *t, size_t k)
{
    if (t->n + k > t->cap) rd_tape_grow(t, k);
    return !t->failed;
}

static inline void rd_tape_add(rd_tape *t, double *to, double v)
{
    if (!rd_tape_room(t, 2)) return;
    t->w[t->n].to = to;
    t->w[t->n + 1].v = v;
    t->n += 2;
}

/* f[o] += F, tq[o] += T (rd_sim.f, tq of the simulation). */
static inline void rd_tape_body(rd_tape *t, int o, const double F[3], const double T[3])
{
    if (!rd_tape_room(t, 7)) return;
    rd_tape_word *w = t->w + t->n;
    w[0].tag = (uintptr_t)o << 3 | RD_TAPE_BODY;
    for (int k = 0; k < 3; k++) {
        w[1 + k].v = F[k];
        w[4 + k].v = T[k];
    }
    t->n += 7;
}

/* f[o] += F, tq[o] += To, f[ot] += -F, tq[ot] += Tt. */
static inline void rd_tape_pair(rd_tape *t, int o, int ot, const double F[3], const double To[3],
                                const double Tt[3])
{
    if (!rd_tape_room(t, 11)) return;
    rd_tape_word *w = t->w + t->n;
    w[0].tag = (uintptr_t)o << 3 | RD_TAPE_PAIR;
    w[1].tag = (uintptr_t)ot;
    for (int k = 0; k < 3; k++) {
        w[2 + k].v = F[k];
        w[5 + k].v = To[k];
        w[8 + k].v = Tt[k];
    }
    t->n += 11;
}

/* *to += v, or, on a thread's view (s->tape set), recorded for the play-back. */
static inline void rd_book(rd_sim *s, double *to, double v)
{
    if (s->tape)
        rd_tape_add(s->tape, to, v);
    else
        *to += v;
}

/* Friction and damping energy, J, of the pair being stepped (rd_sim.e_pair: every contact and
 * edge law runs inside rd_contact_pair, which books the two sums once per pair). */
static inline void rd_book_fric(rd_sim *s, double v) { s->e_pair[0] += v; }
static inline void rd_book_damp(rd_sim *s, double v) { s->e_pair[1] += v; }

/* Whole-number tallies (a watch's active and slipping points): order does not matter, so a
 * view adds atomically. */
static inline void rd_count(rd_sim *s, int *to, int v)
{
    if (s->tape)
        __atomic_fetch_add(to, v, __ATOMIC_RELAXED);
    else
        *to += v;
}

/* law.h's rd_law_apply (F at ro on the owner o, -F at rt on t when t_free) booked on a thread's
 * view: the same expressions, so the same terms (1.0 * x is x, -1.0 * x is -x exactly). */
static inline void rd_book_apply(rd_sim *s, const double F[3], const double ro[3],
                                 const double rt[3], int o, int t_free, int t)
{
    double to[3], tt[3];
    rd_cross(ro, F, to);
    if (!t_free) {
        rd_tape_body(s->tape, o, F, to);
        return;
    }
    rd_cross(rt, F, tt);
    for (int k = 0; k < 3; k++) tt[k] = -tt[k];
    rd_tape_pair(s->tape, o, t, F, to, tt);
}

/* The threads a run asks for: sc->threads, or where 0 OMP_NUM_THREADS's first number, else 1;
 * at most RD_THREADS_MAX. */
int rd_threads_of(const rd_scenario *sc);

/* Threads a loop over n items runs on: 1, or s->nthreads once each thread has at least
 * RD_ITEMS_PER_THREAD of them (fewer are not worth the thread team's start). */
int rd_threads_for(const rd_sim *s, long n);

/* Threads a loop over the pairs list[0 .. n) (list NULL: pairs 0 .. n) runs on: as
 * rd_threads_for, or, where the pairs are fewer but carry many subcontact points (a column's
 * drum beds: some 90 points a side), s->nthreads once there are at least 2 pairs and
 * RD_POINTS_PER_THREAD points per thread. */
int rd_threads_for_pairs(const rd_sim *s, const int *list, int n);

/* rd_contact_step's loop over the live pairs on s->nthreads threads: 1 when it ran them, 0 when
 * they are too few (the caller runs them serially), -1 when out of memory. */
int rd_workers_contact(rd_sim *s);

void rd_workers_free(rd_sim *s);

#endif
