/* rockdem (private) — the bodies of a scenario by name (name_index.c): a hash table of indices
 * into sc->bodies, so that a parse or a validation of n bodies looks names up in O(n), where
 * find_body's scan made a 10,000-brick wall's parse quadratic (about 1e8 name comparisons).
 * The index follows the bodies as they are appended (it takes in any new ones at each lookup);
 * a name given twice keeps its first body, as find_body does.
 * Folder scenario/ owns the text language; it may call base/, records/ and geometry/.
 */
#ifndef RD_SCENARIO_NAME_INDEX_H
#define RD_SCENARIO_NAME_INDEX_H

#include "rockdem/scenario.h"

#include <stddef.h>

typedef struct rd_name_index {
    int *slot;   /* [cap]: body index + 1, 0 = empty (open addressing, linear probing) */
    int cap;     /* a power of two, at least twice the bodies indexed */
    int indexed; /* sc->bodies[0 .. indexed) are in the table */
} rd_name_index;

/* Index of the body named name[0..len) in sc, or -1; -2 when out of memory (the caller may
 * fall back on find_body). */
int rd_name_index_find(rd_name_index *x, const rd_scenario *sc, const char *name, size_t len);
void rd_name_index_free(rd_name_index *x);

#endif
