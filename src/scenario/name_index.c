/* rockdem — the bodies of a scenario by name (name_index.h).
 * Folder scenario/ owns the text language; it may call base/, records/ and geometry/.
 */
#include "scenario/name_index.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define RD_INDEX_MIN_CAP 64

/* 32-bit FNV-1a of s[0..len). */
static uint32_t name_hash(const char *s, size_t len)
{
    uint32_t h = 2166136261u;
    for (size_t i = 0; i < len; i++) h = (h ^ (unsigned char)s[i]) * 16777619u;
    return h;
}

static int same(const char *body, const char *name, size_t len)
{
    return strlen(body) == len && memcmp(body, name, len) == 0;
}

/* The slot holding name, or the empty slot where it would go. */
static int probe(const rd_name_index *x, const rd_scenario *sc, const char *name, size_t len)
{
    int k = (int)(name_hash(name, len) & (uint32_t)(x->cap - 1));
    while (x->slot[k] && !same(sc->bodies[x->slot[k] - 1].name, name, len))
        k = (k + 1) & (x->cap - 1);
    return k;
}

static void insert(rd_name_index *x, const rd_scenario *sc, int i)
{
    const char *n = sc->bodies[i].name;
    int k = probe(x, sc, n, strlen(n));
    if (!x->slot[k]) x->slot[k] = i + 1; /* a repeated name keeps its first body */
}

/* Room for n bodies at a load of at most one half: the table rebuilt from sc. 0 or -1. */
static int reserve(rd_name_index *x, const rd_scenario *sc, int n)
{
    if (2 * n <= x->cap) return 0;
    int cap = x->cap ? x->cap : RD_INDEX_MIN_CAP;
    while (2 * n > cap) cap *= 2;
    int *slot = calloc((size_t)cap, sizeof *slot);
    if (!slot) return -1;
    free(x->slot);
    *x = (rd_name_index){ .slot = slot, .cap = cap, .indexed = x->indexed };
    for (int i = 0; i < x->indexed; i++) insert(x, sc, i);
    return 0;
}

int rd_name_index_find(rd_name_index *x, const rd_scenario *sc, const char *name, size_t len)
{
    if (reserve(x, sc, sc->nbodies)) return -2;
    for (; x->indexed < sc->nbodies; x->indexed++) insert(x, sc, x->indexed);
    if (!x->cap) return -1;
    int k = probe(x, sc, name, len);
    return x->slot[k] - 1;
}

void rd_name_index_free(rd_name_index *x)
{
    free(x->slot);
    *x = (rd_name_index){ 0 };
}
