/* rockdem (private) — HDF5 writer. The file is written incrementally: samples are buffered and
 * appended to chunked, deflate-compressed, extendible datasets, then H5Fflush'ed, so a run that
 * stops early (Ctrl-C, NaN, error) leaves a valid file with everything written so far.
 *
 * Layout (all SI; docs/HDF5-LAYOUT.md is the full description, layout_version 3). Every
 * dataset has `units` (where it has any) and `long_name`; every attribute with units has a
 * companion `<name>_units`; every axis has an HDF5 dimension scale (netCDF-4 style); strings are
 * variable-length UTF-8; status, event type and spacing rule are HDF5 enums.
 *   /                      attributes: Conventions, layout_version, program, version, scenario
 *                          (full text), scenario_file, title, dt, dt_critical, damping,
 *                          overturn_criterion, kn, ks, friction_deg, cohesion, tension,
 *                          spacing_rule (enum auto|vertices|fixed), spacing (fixed only)
 *   /time /body /xyz /wxyz /rotation_part /corner     dimension scales (body: free body names)
 *   /bodies/names          [body] free bodies in output order
 *   /bodies/               every body, fixed ones too, one row each over the axis `block`
 *                          (io_bodies.h): block (names), fixed, mass, inertia_principal[3],
 *                          size[3] (extents at rest along x, y, z), alpha (static tipping angle
 *                          about the edge of the support polygon at rest, least of the +-x, +-y
 *                          leans; 0 for fixed bodies), position[3], quaternion[4] (as placed);
 *                          vertices [vertex][xyz] (body frame, about the centre of mass), faces
 *                          [face][corner] and precariousness [lean][quantity] of all bodies in
 *                          block order with vertex_count, face_count, lean_count per block
 *   /position              [time][body][xyz]   centre of mass, ground frame, m
 *   /quaternion            [time][body][wxyz]  body -> ground frame
 *   /velocity              [time][body][xyz]   m/s, relative to the ground
 *   /angular_velocity      [time][body][xyz]   rad/s, ground frame
 *   /tilt                  [time][body]        angle of the rest vertical axis from vertical, rad
 *   /rotation              [time][body][rotation_part]  rotation from rest split into in-plane
 *                          rocking (about the horizontal axis normal to the motion direction d,
 *                          + tips towards d), out-of-plane rocking (about d, + tips towards
 *                          z x d) and twist about the vertical (unwrapped), rad
 *   /ground/acceleration, velocity, displacement  [time][xyz]  m/s^2, m/s, m
 *   /ground                attributes (records only): intensity measures, see rd_h5_ground_im
 *   /energy/<name>         [time] J: kinetic, gravitational, elastic, friction, damping,
 *                          ground_work, residual (balance residual, J)
 *   /events/               columns [event]: time (s), body (name, "" = the whole scene),
 *                          body_index (-1 = none), type (enum: uplift, impact, ...), value
 *   /summary               group, attributes from rd_summary (status enum, overturned,
 *                          overturn_time, max_tilt, max_tilt_ratio, ... per body as arrays)
 *
 * Folder io/ owns the HDF5 output file; it may call base/ and the public headers, never engine/
 * internals or cli/.
 */
#ifndef RD_IO_HDF5_H
#define RD_IO_HDF5_H

#include "rockdem/observer.h"
#include "rockdem/rockdem.h"

extern const char *const rd_energy_names[RD_NENERGY]; /* order of rd_h5_sample.energy */

typedef struct rd_h5_body {
    const char *name;
    double mass;       /* kg */
    double inertia[3]; /* principal moments, kg m^2 */
    double size[3];    /* m (brick) */
    double alpha;      /* static tipping angle, rad */
    int nvert;
    const double *vertices; /* [nvert][3], body frame, m */
    int ntri;
    const int *triangles; /* [ntri][3] */
    int fixed;            /* 1: a fixed body (pedestal), drawn but not in the time series */
    double position[3];   /* centre of mass as placed, ground frame, m */
    double quaternion[4]; /* orientation as placed (w, x, y, z), body -> ground frame */
} rd_h5_body;

typedef struct rd_h5_meta {
    const char *scenario_text;
    const char *scenario_file;
    const char *title;
    double dt, dt_critical;
    const char *damping;            /* e.g. "none", "viscous 0.05", "local 0.8" */
    const char *overturn_criterion; /* e.g. "tilt-ratio 1.5" */
    double kn, ks, friction, cohesion, tension, spacing; /* contact law, SI (friction in rad) */
    int nbodies;                                         /* free bodies written per sample */
    const rd_h5_body *bodies;
    int nfixed; /* fixed bodies (geometry only; may be 0) */
    const rd_h5_body *fixed_bodies;
    const char *target; /* NULL: the file is written at its path; else the path is a
                                       temporary, renamed to target by rd_h5_commit */
} rd_h5_meta;

typedef struct rd_h5_sample {
    double time;
    const double *position;         /* [nb][3] */
    const double *quaternion;       /* [nb][4] */
    const double *velocity;         /* [nb][3] */
    const double *angular_velocity; /* [nb][3] */
    const double *tilt;             /* [nb] */
    const double *rotation;         /* [nb][3] in-plane rocking, out-of-plane rocking, twist */
    double ground_acc[3], ground_vel[3], ground_disp[3];
    double energy[RD_NENERGY];
} rd_h5_sample;

typedef struct rd_h5 rd_h5;

/* Create (truncate) the file and write the metadata. NULL with err filled on failure. */
rd_h5 *rd_h5_open(const char *path, const rd_h5_meta *meta, rd_error *err);
/* Append one sample (buffered; written and flushed every few hundred samples). 0 or -1. */
int rd_h5_append(rd_h5 *h, const rd_h5_sample *s, rd_error *err);
/* Append one event row (written at the next flush). type is one of uplift, impact, slip,
 * overturn, recover, unstable, unsettled, rest, lock, liftoff (-1 otherwise). 0 or -1. */
int rd_h5_event(rd_h5 *h, double time, int body, const char *type, double value, rd_error *err);
/* Attributes of /ground describing the applied records (none for pulses): direction (rad),
 * scale_factor, baseline_degree, and per component c in h1, h2, vertical: c_pga (m/s^2), c_pgv
 * (m/s), c_pgd (m), c_pgv_pga (s), c_arias (m/s), c_d5_95 (s), c_sa_0.2s and c_sa_1s (5 %
 * damped PSA, m/s^2), c_dt (s), c_duration (s), c_record, c_source. 0 or -1. */
int rd_h5_ground_im(rd_h5 *h, const rd_motion_def *m, rd_error *err);
/* Write buffered samples and events, then H5Fflush. 0 or -1. */
int rd_h5_flush(rd_h5 *h, rd_error *err);
/* Write the /summary group (may be called more than once; last call wins). 0 or -1. */
int rd_h5_summary(rd_h5 *h, const rd_summary *s, rd_error *err);
/* The run has ended (`ok`: done or overturned): a file written to a temporary (meta.target) is
 * flushed, closed and renamed over its target, so the earlier file there is replaced only by a
 * whole, successful run; with !ok, or written in place, nothing happens. 0, or -1 with err (the
 * rename failed: the temporary stays, named in err). */
int rd_h5_commit(rd_h5 *h, int ok, rd_error *err);
/* Flush and close; safe on NULL. */
void rd_h5_close(rd_h5 *h);
/* The open file's HDF5 id, for the table writer (io_table.h): /history, /joints. */
long long rd_h5_file_id(const rd_h5 *h);
/* Make room for `bytes` of tables the table writer is about to add (posix_fallocate, as before
 * every batch of samples: a full disk or a file-size limit fails here, before HDF5 writes
 * anything). 0, or -1 with the file's status io_error. */
int rd_h5_reserve(rd_h5 *h, size_t bytes, rd_error *err);
/* The table writer failed (err holds why): the file's status becomes io_error with
 * "<path>: <what>: <why>", also put in err. Returns -1. */
int rd_h5_fail(rd_h5 *h, const char *what, rd_error *err);

#endif
