/* rockdem (private) — the /bodies group of a run file (io_bodies.c): every body's mass,
 * geometry and precariousness as whole tables over the `block` axis (layout 3,
 * docs/HDF5-LAYOUT.md), so a file holds a fixed number of HDF5 objects whatever the bodies.
 * Folder io/ owns the HDF5 output file; it may call base/ and the public headers, never engine/
 * internals or cli/.
 */
#ifndef RD_IO_BODIES_H
#define RD_IO_BODIES_H

#include "io/io_hdf5.h"

#include <stddef.h>

/* What a body brings once the scene rests on its supports. */
typedef struct rd_h5_rest_body {
    double size[3];               /* extents at rest along ground x, y, z, m */
    int nprec;                    /* rows of precariousness */
    const double *precariousness; /* [nprec][3]: lean direction (rad from +x), alpha (rad),
                                     g tan(alpha) (m/s^2) */
} rd_h5_rest_body;

/* Bytes the tables rd_h5_bodies_write adds take in the file, at most. */
size_t rd_h5_bodies_bytes(const rd_h5_meta *m);
/* /bodies/names and the per-block tables of every body of m (free bodies in /body order, then
 * the fixed ones) under the existing group /bodies of file; the root scales /body, /xyz,
 * /wxyz and /corner must exist. 0, or -1 with err. */
int rd_h5_bodies_write(long long file, const rd_h5_meta *m, rd_error *err);
/* The free bodies at rest, b[0..n-1] in /body order: their sizes replace those given at
 * open, their precariousness tables become /bodies/precariousness with lean_count (0 for the
 * fixed bodies). Called once; the space is reserved first. 0, or -1 (the file marked
 * io_error). */
int rd_h5_bodies_rest(rd_h5 *h, const rd_h5_rest_body *b, int n, rd_error *err);
/* The support-polygon alpha of the n free bodies (rad; 0 or less: unknown, the value given at
 * open is kept) into /bodies/alpha. 0, or -1 with err. */
int rd_h5_bodies_alpha(long long file, const double *alpha, int n, rd_error *err);

#endif
