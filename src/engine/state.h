/* rockdem (private) — the engine's state image: what `model save` must keep for `model
 * restore` to continue a run bit for bit. The engine lists its arrays and sizes here and
 * applies a restored image; io/checkpoint.c stores and reads them (the engine opens no file).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/. This header is
 * the one engine interface below the public API that io/ may call.
 */
#ifndef RD_STATE_H
#define RD_STATE_H

#include "rockdem/rockdem.h"

#include <stddef.h>

#define RD_STATE_VERSION 5 /* bump when the image's arrays or their meaning change */
#define RD_STATE_ARRAYS 32 /* room for the arrays of an image */

typedef enum rd_state_type { RD_STATE_DOUBLE = 0, RD_STATE_INT = 1, RD_STATE_BYTE = 2 } rd_state_type;

/* One array of the image: n elements of type at data (the simulation's own memory). */
typedef struct rd_state_array {
    const char *name; /* its path in the checkpoint file, e.g. "bodies/position" */
    rd_state_type type;
    void *data;
    long n;
} rd_state_array;

/* The image's sizes and figures, in this order (stored as one array of longs): version, nb,
 * npts, npair, njoint, nstate, nface_state, hcap, nlive_prev, nevent, stamp, sweep_axis, and
 * the record sizes of rd_pair, rd_joint, rd_event (a checkpoint is tied to the build), and the
 * edge subcontacts' count (edge.c). */
enum { RD_STATE_H_VERSION, RD_STATE_H_NB, RD_STATE_H_NPTS, RD_STATE_H_NPAIR, RD_STATE_H_NJOINT,
       RD_STATE_H_NSTATE, RD_STATE_H_NFACE, RD_STATE_H_HCAP, RD_STATE_H_NLIVE, RD_STATE_H_NEVENT,
       RD_STATE_H_STAMP, RD_STATE_H_AXIS, RD_STATE_H_PAIR_SIZE, RD_STATE_H_JOINT_SIZE,
       RD_STATE_H_EVENT_SIZE, RD_STATE_H_NEDGE, RD_STATE_HEADER };
#define RD_STATE_HEADER_NAMES "version,nb,npts,npair,njoint,nstate,nface_state,hcap,nlive,nevent," \
                              "stamp,sweep_axis,pair_size,joint_size,event_size,nedge"

/* sim.c: the simulation built from a scenario (rd_sim_create without the checkpoint) */
rd_sim *rd_sim_build(const rd_scenario *sc, rd_error *err);

/* state.c. Saving, at rest (settled, before the initial conditions): capture fills the header
 * and the settle figures (time, s; unbalanced-force ratio reached) and stages what is not kept
 * in an array (each free body's contact area); then rd_state_arrays lists the arrays. */
void rd_state_capture(rd_sim *s, long h[RD_STATE_HEADER], double settle[2]);
/* The arrays of the image, as sized now (after capture, or after rd_state_reserve): count. */
int rd_state_arrays(rd_sim *s, rd_state_array a[RD_STATE_ARRAYS]);

/* Restoring: does an image of header h and block names (NULL when h's nb differs) fit this
 * simulation? NULL, or the difference (in buf, or a constant). */
const char *rd_state_mismatch(const rd_sim *s, const long h[RD_STATE_HEADER], const char *const *names,
                              char *buf, size_t n);
/* Size the arrays for the image (then rd_state_arrays lists where to read them). 0 or -1. */
int rd_state_reserve(rd_sim *s, const long h[RD_STATE_HEADER]);
/* The arrays are read: the run starts from them instead of settling. */
void rd_state_restored(rd_sim *s, const double settle[2]);

#endif
