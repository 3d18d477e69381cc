/* rockdem — checkpoints: `model save 'state.h5'` writes the settled state, `model restore
 * 'state.h5'` (in a scenario with the same blocks) starts from it instead of settling.
 *
 * A checkpoint holds everything the shaking stage reads that settling produced: every body's
 * pose and momenta (also the previous half step's), the broad phase (boxes, sweep order,
 * step stamp, pair hash map, the pairs live at the last step), every contact pair with its
 * per-subcontact history (shear forces, state bits, normal force and gap) and the joint
 * table, the settle stage's figures and events, and each free body's contact area at rest
 * (the monitor's reference for uplift). Numbers are stored as they are in memory
 * (doubles bit for bit), so a restored run continues exactly as the uninterrupted one would:
 * tests/cli/checkpoint.sh compares the final states of both for equality.
 *
 * The file is HDF5: readable datasets for the bodies (/bodies/names, position, quaternion,
 * velocity, angular_momentum) and the engine's contact tables under /state (pairs and joints
 * as raw records with their record size, checked on restore, so a checkpoint is tied to the
 * rockdem build that wrote it, like 3DEC's save files).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/. This file is
 * the one exception left: it reads and writes its checkpoint through io/io_table.c
 * (docs/ARCHITECTURE.md).
 */
#include "engine/sim.h"
#include "io/io_table.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RD_CHECKPOINT_VERSION 1

typedef struct blob {
    const char *name;
    rd_h5t_type type;
    void *data;
    long n;
} blob;

/* The arrays of a checkpoint (sizes from the sim as built, or as read). */
static int blobs(rd_sim *s, blob *b)
{
    int n = 0, nb = s->nb;
    b[n++] = (blob){"bodies/position", RD_H5T_DOUBLE, s->x, 3L * nb};
    b[n++] = (blob){"bodies/quaternion", RD_H5T_DOUBLE, s->q, 4L * nb};
    b[n++] = (blob){"bodies/velocity", RD_H5T_DOUBLE, s->v, 3L * nb};
    b[n++] = (blob){"bodies/angular_momentum", RD_H5T_DOUBLE, s->L, 3L * nb};
    b[n++] = (blob){"state/angular_velocity", RD_H5T_DOUBLE, s->w, 3L * nb};
    b[n++] = (blob){"state/velocity_old", RD_H5T_DOUBLE, s->v_old, 3L * nb};
    b[n++] = (blob){"state/angular_momentum_old", RD_H5T_DOUBLE, s->L_old, 3L * nb};
    b[n++] = (blob){"state/aabb", RD_H5T_DOUBLE, s->aabb, 6L * nb};
    b[n++] = (blob){"state/order", RD_H5T_INT, s->order, nb};
    b[n++] = (blob){"state/hash", RD_H5T_INT, s->hkey, s->hcap};
    b[n++] = (blob){"state/live", RD_H5T_INT, s->live_prev, s->nlive_prev};
    b[n++] = (blob){"state/pairs", RD_H5T_BYTE, s->pair, (long)(s->npair * sizeof *s->pair)};
    b[n++] = (blob){"state/joints", RD_H5T_BYTE, s->joint, (long)(s->njoint * sizeof *s->joint)};
    b[n++] = (blob){"state/shear_force", RD_H5T_DOUBLE, s->fs, 3L * s->nstate};
    b[n++] = (blob){"state/point_state", RD_H5T_BYTE, s->pstate, s->nstate};
    b[n++] = (blob){"state/point_force_gap", RD_H5T_DOUBLE, s->pj, 2L * s->nstate};
    b[n++] = (blob){"state/entrance_face", RD_H5T_BYTE, s->pface, (long)(s->nstate * sizeof *s->pface)};
    b[n++] = (blob){"state/permanent_set", RD_H5T_DOUBLE, s->pset, s->nstate};
    b[n++] = (blob){"state/face_active", RD_H5T_INT, s->face_nactive, s->nface_state};
    b[n++] = (blob){"state/events", RD_H5T_BYTE, s->event, (long)(s->nevent * sizeof *s->event)};
    b[n++] = (blob){"state/rest_area", RD_H5T_DOUBLE, s->rest_area, s->nfree};
    return n;
}

/* Sizes and figures: version, nb, npts, npair, njoint, nstate, nface_state, hcap, nlive_prev,
 * nevent, stamp, sweep_axis, record sizes of rd_pair, rd_joint, rd_event. */
enum { H_VERSION, H_NB, H_NPTS, H_NPAIR, H_NJOINT, H_NSTATE, H_NFACE, H_HCAP, H_NLIVE, H_NEVENT,
       H_STAMP, H_AXIS, H_PAIR_SIZE, H_JOINT_SIZE, H_EVENT_SIZE, H_COUNT };

int rd_checkpoint_save(const rd_sim *cs, const char *path, rd_error *err)
{
    rd_sim *s = (rd_sim *)cs; /* blobs() lists pointers; nothing is modified */
    long h[H_COUNT] = {RD_CHECKPOINT_VERSION, s->nb, s->npts, s->npair, s->njoint, s->nstate,
                       s->nface_state, s->hcap, s->nlive_prev, s->nevent, s->stamp, s->sweep_axis,
                       (long)sizeof(rd_pair), (long)sizeof(rd_joint), (long)sizeof(rd_event)};
    double fig[2] = {s->settle_time, s->settle_ratio};
    long long f = rd_h5t_create(path, err);
    if (f < 0) return -1;
    const char **names = malloc((size_t)s->nb * sizeof *names);
    int rc = names ? 0 : rd_error_set(err, "out of memory");
    for (int i = 0; names && i < s->nb; i++) names[i] = s->sc.bodies[i].name;
    if (!rc) rc = rd_h5t_strings(f, "bodies/names", names, s->nb, "block names", NULL, err);
    if (!rc) rc = rd_h5t_write(f, "state/header", RD_H5T_LONG, h, H_COUNT, 0, NULL,
                               "version,nb,npts,npair,njoint,nstate,nface_state,hcap,nlive,nevent,"
                               "stamp,sweep_axis,pair_size,joint_size,event_size", NULL, err);
    if (!rc) rc = rd_h5t_write(f, "state/settle", RD_H5T_DOUBLE, fig, 2, 0, NULL,
                               "settle time (s), unbalanced-force ratio reached", NULL, err);
    blob b[32];
    for (int k = 0; k < s->nfree; k++) s->rest_area[k] = s->watch[k].area;
    int nbl = blobs(s, b);
    for (int k = 0; k < nbl && !rc; k++)
        rc = rd_h5t_write(f, b[k].name, b[k].type, b[k].data, b[k].n, 0, NULL, NULL, NULL, err);
    free(names);
    rd_h5t_close(f);
    if (rc) {
        char m[RD_ERROR_MAX];
        snprintf(m, sizeof m, "%s", err->msg);
        rd_error_set(err, "%s: model save: %s", path, m);
    }
    return rc;
}

/* Grow the sim's arrays to the checkpoint's sizes. */
static int make_room(rd_sim *s, const long *h)
{
    void **p[] = {(void **)&s->hkey, (void **)&s->live_prev, (void **)&s->pair, (void **)&s->joint,
                  (void **)&s->fs, (void **)&s->pstate, (void **)&s->pj, (void **)&s->face_nactive,
                  (void **)&s->event, (void **)&s->pface, (void **)&s->pset};
    size_t sz[] = {sizeof *s->hkey * (size_t)h[H_HCAP], sizeof *s->live_prev * (size_t)h[H_NLIVE],
                   sizeof *s->pair * (size_t)h[H_NPAIR], sizeof *s->joint * (size_t)h[H_NJOINT],
                   sizeof *s->fs * (size_t)h[H_NSTATE], sizeof *s->pstate * (size_t)h[H_NSTATE],
                   sizeof *s->pj * (size_t)h[H_NSTATE], sizeof *s->face_nactive * (size_t)h[H_NFACE],
                   sizeof *s->event * (size_t)h[H_NEVENT], sizeof *s->pface * (size_t)h[H_NSTATE],
                   sizeof *s->pset * (size_t)h[H_NSTATE]};
    for (size_t k = 0; k < sizeof sz / sizeof sz[0]; k++) {
        void *t = realloc(*p[k], sz[k] ? sz[k] : 1);
        if (!t) return -1;
        *p[k] = t;
    }
    s->hcap = (int)h[H_HCAP];
    s->nlive_prev = (int)h[H_NLIVE]; s->cap_live_prev = s->nlive_prev;
    s->npair = s->cap_pair = (int)h[H_NPAIR];
    s->njoint = s->cap_joint = (int)h[H_NJOINT];
    s->nstate = s->cap_state = s->cap_state_flags = s->cap_state_joint = (int)h[H_NSTATE];
    s->cap_pface = s->cap_pset = (int)h[H_NSTATE];
    s->nface_state = s->cap_face_state = (int)h[H_NFACE];
    s->nevent = s->cap_event = (int)h[H_NEVENT];
    s->stamp = h[H_STAMP];
    s->sweep_axis = (int)h[H_AXIS];
    return 0;
}

/* Does the checkpoint's scene match this one (same build, same blocks)? NULL or the problem. */
static const char *mismatch(const rd_sim *s, long long f, const long *h, char *buf, size_t n, rd_error *err)
{
    if (h[H_VERSION] != RD_CHECKPOINT_VERSION || h[H_PAIR_SIZE] != (long)sizeof(rd_pair) ||
        h[H_JOINT_SIZE] != (long)sizeof(rd_joint) || h[H_EVENT_SIZE] != (long)sizeof(rd_event))
        return "written by another rockdem build (checkpoint layout differs)";
    if (h[H_NB] != s->nb) {
        snprintf(buf, n, "it holds %ld blocks, this scenario %d", h[H_NB], s->nb);
        return buf;
    }
    for (int i = 0; i < s->nb; i++) {
        char name[RD_NAME_MAX];
        if (rd_h5t_string(f, "bodies/names", i, name, sizeof name, err)) return "no block names";
        if (strcmp(name, s->sc.bodies[i].name)) {
            snprintf(buf, n, "block %d is '%s' there, '%s' here", i + 1, name, s->sc.bodies[i].name);
            return buf;
        }
    }
    if (h[H_NPTS] != s->npts) {
        snprintf(buf, n, "it has %ld subcontacts, this scenario %d (other shapes or spacing)", h[H_NPTS], s->npts);
        return buf;
    }
    return NULL;
}

int rd_checkpoint_restore(rd_sim *s, const char *path, rd_error *err)
{
    long h[H_COUNT];
    double fig[2];
    char buf[2 * RD_NAME_MAX + 64]; /* two block names and the words around them */
    const char *bad = NULL;
    long long f = rd_h5t_open(path, err);
    if (f < 0) return rd_error_set(err, "%s: model restore: cannot open '%s' as a checkpoint", s->sc.file, path);
    if (rd_h5t_read(f, "state/header", RD_H5T_LONG, h, H_COUNT, err) ||
        rd_h5t_read(f, "state/settle", RD_H5T_DOUBLE, fig, 2, err))
        bad = "not a rockdem checkpoint (no /state/header)";
    if (!bad) bad = mismatch(s, f, h, buf, sizeof buf, err);
    if (!bad && make_room(s, h)) bad = "out of memory";
    blob b[32];
    int nbl = bad ? 0 : blobs(s, b);
    for (int k = 0; k < nbl && !bad; k++)
        if (rd_h5t_read(f, b[k].name, b[k].type, b[k].data, b[k].n, err)) bad = err->msg;
    rd_h5t_close(f);
    if (bad) {
        char msg[RD_ERROR_MAX];
        snprintf(msg, sizeof msg, "%s", bad);
        return rd_error_set(err, "%s: model restore '%s': %s", s->sc.file, path, msg);
    }
    for (int k = 0; k < s->nfree; k++) s->watch[k].area = s->rest_area[k]; /* contact area at rest */
    s->settle_time = fig[0];
    s->settle_ratio = fig[1];
    s->restored = 1;
    return 0;
}
