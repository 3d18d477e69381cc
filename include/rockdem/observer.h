/* rockdem — watching a simulation: observers (REBOUND's heartbeat, Box2D's event arrays).
 *
 * The engine writes no file. It samples the scene every `model output interval` seconds of
 * shaking (the monitors' cadence: tilt, rotation split and energies are evaluated there) and
 * hands each sample, each event and the final summary to the observers registered on it.
 * The HDF5 file of `rockdem run` is one such observer (rd_sim_write_hdf5, rockdem/output.h);
 * a progress bar, a plot or a Python callback is another. A simulation with no observer runs
 * and summarises exactly the same, without touching the file system.
 *
 * Order of calls inside rd_sim_run: begin (after settling, the scene at rest: support polygons,
 * alpha and precariousness known; before the initial tilt/velocities), then per sample first
 * the events since the previous one, then sample; at the end the last events, a final sample
 * and end. A callback returning non-zero stops the run with RD_STATUS_IO_ERROR and its err as
 * rd_sim_error(). Callbacks may call rd_sim_stop(sim) and any const accessor.
 */
#ifndef ROCKDEM_OBSERVER_H
#define ROCKDEM_OBSERVER_H

#include "rockdem/api.h"
#include "rockdem/rockdem.h"

/* Energies of a sample, in this order: kinetic, gravitational, elastic, friction, damping,
 * ground_work, residual (balance residual), J. */
#define RD_NENERGY 7

/* One sampled state of the free bodies (arrays in output order, valid during the call). */
typedef struct rd_sample {
    double time;                    /* s since the start of shaking */
    int nbodies;                    /* free bodies */
    const double *position;         /* [nbodies][3] centre of mass, ground frame, m */
    const double *quaternion;       /* [nbodies][4] w, x, y, z (body -> ground frame) */
    const double *velocity;         /* [nbodies][3] m/s, relative to the ground */
    const double *angular_velocity; /* [nbodies][3] rad/s, ground frame */
    const double *tilt;             /* [nbodies] angle of the rest vertical from vertical, rad */
    const double *rotation;         /* [nbodies][3] in-plane rocking, out-of-plane rocking,
                                       twist (unwrapped), rad */
    double ground_acc[3], ground_vel[3], ground_disp[3]; /* m/s^2, m/s, m */
    double energy[RD_NENERGY];                           /* J */
} rd_sample;

typedef struct rd_observer {
    void *user; /* handed back to every callback */
    int every;  /* receive every n-th sample (0 or 1: each one) */
    int (*begin)(void *user, rd_sim *sim, rd_error *err);
    int (*sample)(void *user, rd_sim *sim, const rd_sample *s, rd_error *err);
    int (*event)(void *user, rd_sim *sim, const rd_event *e, rd_error *err);
    int (*end)(void *user, rd_sim *sim, const rd_summary *s, rd_error *err);
    void (*release)(void *user); /* called by rd_sim_free (may be NULL) */
} rd_observer;

/* Register an observer (copied; any callback may be NULL). 0, or -1 with err. */
RD_API int rd_sim_add_observer(rd_sim *sim, const rd_observer *obs, rd_error *err);

/* A body as observers see it. */
typedef struct rd_body_info {
    const char *name;
    int fixed;            /* 1: a fixed body (pedestal), not in the samples */
    double position[3];   /* centre of mass now, ground frame, m (a fixed body's never moves) */
    double quaternion[4]; /* orientation now (w, x, y, z), body -> ground frame */
    double mass;          /* kg */
    double inertia[3];    /* principal moments, kg m^2 */
    double size[3];       /* extents of the body at rest along ground x, y, z, m (a brick
                                placed without rotation: its edge lengths) */
    double alpha;         /* static tipping angle about the edge of its support polygon at
                                rest, least of the +-x, +-y leans, rad (0 before the run and for
                                fixed bodies) */
    int nvert;
    const double *vertices; /* [nvert][3] body frame (centre of mass, principal axes), m */
    int ntri;
    const int *triangles;         /* [ntri][3] vertex indices, outward */
    int nprec;                    /* rows of precariousness (0 before the run) */
    const double *precariousness; /* [nprec][3]: lean direction (rad from +x), alpha (rad),
                                     quasi-static tipping acceleration g tan(alpha) (m/s^2) */
} rd_body_info;

/* Free bodies (the index of rd_sample's arrays and of rd_event.body); *nfixed (if not NULL):
 * fixed bodies. */
RD_API int rd_sim_body_count(const rd_sim *sim, int *nfixed);

/* Body k: free body k for 0 <= k < nfree, then the fixed bodies in scenario order for
 * nfree <= k < nfree + nfixed. Pointers stay valid until rd_sim_free. */
RD_API void rd_sim_body_info(const rd_sim *sim, int k, rd_body_info *out);

/* The simulation's own copy of its scenario (valid until rd_sim_free). */
RD_API const rd_scenario *rd_sim_scenario(const rd_sim *sim);

#endif
