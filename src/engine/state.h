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

#define RD_STATE_VERSION                                                                           \
    8 /* bump when the image's arrays or their meaning change (8: the surface model's patches) */
#define RD_STATE_ARRAYS 40 /* room for the arrays of an image */
#define RD_STATE_BUILD_RTOL                                                                        \
    1e-9 /* a restored block's shape, mass and fixed pose must be the saved
                                    one's to this relative tolerance (round-off, not a change) */

typedef enum rd_state_type {
    RD_STATE_DOUBLE = 0,
    RD_STATE_INT = 1,
    RD_STATE_BYTE = 2
} rd_state_type;

/* One array of the image: n elements of type at data (the simulation's own memory). */
typedef struct rd_state_array {
    const char *name; /* its path in the checkpoint file, e.g. "bodies/position" */
    rd_state_type type;
    void *data;
    long n;
} rd_state_array;

/* The image's sizes and figures, in this order (stored as one array of longs): version, nb,
 * npts, npair, njoint, nstate, nface_state, hcap, nlive_prev, nevent, stamp, sweep_axis, and
 * the record sizes of rd_pair, rd_joint, rd_event (a checkpoint is tied to the build), the
 * edge subcontacts' count (edge.c), then the contact model (0 vertex, 1 surface) and the
 * surface model's sizes and figures (surface_state.c; 0 under the vertex model): patches,
 * their hash map's capacity, patches loaded at the last step, the mesh pairs' face-pair table
 * capacity and entries, pairs measured, surface steps, the last front plane, the patch record's
 * size, bodies with a dashpot force kept and whether a dashpot acted at the last step. */
enum {
    RD_STATE_H_VERSION,
    RD_STATE_H_NB,
    RD_STATE_H_NPTS,
    RD_STATE_H_NPAIR,
    RD_STATE_H_NJOINT,
    RD_STATE_H_NSTATE,
    RD_STATE_H_NFACE,
    RD_STATE_H_HCAP,
    RD_STATE_H_NLIVE,
    RD_STATE_H_NEVENT,
    RD_STATE_H_STAMP,
    RD_STATE_H_AXIS,
    RD_STATE_H_PAIR_SIZE,
    RD_STATE_H_JOINT_SIZE,
    RD_STATE_H_EVENT_SIZE,
    RD_STATE_H_NEDGE,
    RD_STATE_H_MODEL,
    RD_STATE_H_NPATCH,
    RD_STATE_H_PATCH_HCAP,
    RD_STATE_H_NON,
    RD_STATE_H_FCAP,
    RD_STATE_H_NFK,
    RD_STATE_H_NMEAS,
    RD_STATE_H_SURF_STAMP,
    RD_STATE_H_FRONT,
    RD_STATE_H_PATCH_SIZE,
    RD_STATE_H_DP_N,
    RD_STATE_H_DP_ACTED,
    RD_STATE_HEADER
};
#define RD_STATE_HEADER_NAMES                                                                      \
    "version,nb,npts,npair,njoint,nstate,nface_state,hcap,nlive,nevent,"                           \
    "stamp,sweep_axis,pair_size,joint_size,event_size,nedge,model,npatch,patch_hcap,non,"          \
    "face_cap,nface_pair,nmeasure,surface_stamp,front,patch_size,dashpot_bodies,dashpot_acted"

/* sim.c: the simulation built from a scenario (rd_sim_create without the checkpoint) */
rd_sim *rd_sim_build(const rd_scenario *sc, rd_error *err);

/* state.c. Saving, at rest (settled, before the initial conditions): capture fills the header
 * and the settle figures (time, s; unbalanced-force ratio reached) and stages what is not kept
 * in an array (each free body's contact area); then rd_state_arrays lists the arrays. */
void rd_state_capture(rd_sim *s, long h[RD_STATE_HEADER], double settle[2]);
/* The arrays of the image, as sized now (after capture, or after rd_state_reserve): count. */
int rd_state_arrays(rd_sim *s, rd_state_array a[RD_STATE_ARRAYS]);

/* The blocks as built, stored beside the image so that a restore is refused unless the scene's
 * blocks are the same: per body, fixed (1) or free, vertex count, mass (kg) and principal
 * moments (kg m^2), and every body's vertices in its own frame (centre of mass, principal axes;
 * m), in body order. A fixed body's pose is the image's bodies/position and bodies/quaternion
 * (it never moves). */
typedef struct rd_state_build {
    int nb;
    long nvert;       /* vertices of all bodies */
    int *fixed;       /* [nb] */
    int *nv;          /* [nb] */
    double *mass;     /* [nb] kg */
    double *inertia;  /* [3 nb] kg m^2 */
    double *x;        /* [3 nb] centre of mass, m */
    double *q;        /* [4 nb] orientation, body -> ground */
    double *vertices; /* [3 nvert] m */
} rd_state_build;

/* Room for nb bodies and nvert vertices (zeroed); 0 or -1. rd_state_build_free releases it. */
int rd_state_build_alloc(rd_state_build *b, int nb, long nvert);
void rd_state_build_free(rd_state_build *b);
/* The simulation's blocks (fixed bodies at their pose as built). 0 or -1. */
int rd_state_build_of(const rd_sim *s, rd_state_build *b);
/* The arrays of b that a checkpoint stores (not x and q: the image's): count. */
int rd_state_build_arrays(rd_state_build *b, rd_state_array a[RD_STATE_ARRAYS]);

/* Restoring, before the image is read: does an image of header h, block names and blocks as
 * built (both NULL when h's version or nb differs) fit this simulation (the same blocks, to
 * RD_STATE_BUILD_RTOL)? NULL, or the difference, naming the block (in buf, or a constant). */
const char *rd_state_mismatch(const rd_sim *s, const long h[RD_STATE_HEADER],
                              const char *const *names, const rd_state_build *there, char *buf,
                              size_t n);
/* Size the arrays for the image (then rd_state_arrays lists where to read them). 0 or -1. */
int rd_state_reserve(rd_sim *s, const long h[RD_STATE_HEADER]);
/* The arrays are read: the run starts from them instead of settling. */
void rd_state_restored(rd_sim *s, const double settle[2]);

/* surface_state.c: the surface model's part of the image (nothing under the vertex model).
 * Its header entries (RD_STATE_H_MODEL on; 0 under the vertex model). */
void rd_surface_state_capture(const rd_sim *s, long h[RD_STATE_HEADER]);
/* Its arrays appended at a[n ..): the count after them. */
int rd_surface_state_arrays(rd_sim *s, rd_state_array *a, int n);
/* Does the image's model fit this simulation's? NULL, or the difference (in buf). */
const char *rd_surface_state_mismatch(const rd_sim *s, const long h[RD_STATE_HEADER], char *buf,
                                      size_t n);
/* Its arrays sized for the image of header h. 0 or -1. */
int rd_surface_state_reserve(rd_sim *s, const long h[RD_STATE_HEADER]);

#endif
