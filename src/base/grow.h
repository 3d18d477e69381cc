/* rockdem (private) — a growable array's capacity.
 * Folder base/ holds what every other folder may use; it calls nothing of the project. */
#ifndef RD_GROW_H
#define RD_GROW_H

#include <stdlib.h>

/* Make the array *arr (elements of size bytes, *cap of them allocated) hold at least n: the
 * capacity doubles from 16, so n appends cost O(n). Returns 0, -1 when out of memory (*arr and
 * *cap are then unchanged). */
static inline int rd_grow(void **arr, int *cap, int n, size_t size)
{
    if (n <= *cap) return 0;
    int c = *cap ? *cap : 16;
    while (c < n) c *= 2;
    void *p = realloc(*arr, (size_t)c * size);
    if (!p) return -1;
    *arr = p;
    *cap = c;
    return 0;
}

#endif
