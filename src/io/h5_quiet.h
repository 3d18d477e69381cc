/* rockdem (private) — HDF5's automatic error printing, switched off around rockdem's own HDF5
 * calls only: rockdem reports each failure itself in one line (rd_error), and a program that
 * embeds librockdem and uses HDF5 too keeps whatever error handler it had set.
 * Folder io/ owns the HDF5 output file; it may call base/ and the public headers, never engine/
 * internals or cli/.
 */
#ifndef RD_H5_QUIET_H
#define RD_H5_QUIET_H

#include <hdf5.h>

typedef struct rd_h5_quiet {
    H5E_auto2_t fn; /* the error handler in force before (NULL: none) */
    void *data;
} rd_h5_quiet;

/* Saves the default error stack's handler and switches it off. The first call, before HDF5
 * is initialised, also drops HDF5's exit hook (H5dont_atexit has no effect once the library is
 * up): rockdem closes every file it opens itself, and the hook crashed on a file whose close
 * had failed. */
static inline rd_h5_quiet rd_h5_quiet_begin(void)
{
    H5dont_atexit();
    rd_h5_quiet q = { NULL, NULL };
    H5Eget_auto2(H5E_DEFAULT, &q.fn, &q.data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    return q;
}

/* Restores the handler saved by rd_h5_quiet_begin. */
static inline void rd_h5_quiet_end(rd_h5_quiet q) { H5Eset_auto2(H5E_DEFAULT, q.fn, q.data); }

/* The whole body of an entry point: returns `call` (of type `type`), evaluated with HDF5's
 * error printing off. */
#define RD_H5_QUIETLY(type, call)                                                                  \
    do {                                                                                           \
        rd_h5_quiet q_ = rd_h5_quiet_begin();                                                      \
        type r_ = (call);                                                                          \
        rd_h5_quiet_end(q_);                                                                       \
        return r_;                                                                                 \
    } while (0)

#endif
