/* rockdem — the engine's state image (engine/state.h): everything the shaking stage reads that
 * settling produced, for `model save 'state.h5'` / `model restore 'state.h5'` (io/checkpoint.c
 * writes and reads the file).
 *
 * The image holds every body's pose and momenta (also the previous half step's), the broad
 * phase (boxes, sweep order, step stamp, pair hash map, the pairs live at the last step), every
 * contact pair with its per-subcontact history (shear forces, state bits, normal force and gap)
 * and the joint table, the settle stage's figures and events, and each free body's contact area
 * at rest (the monitor's reference for uplift); under `contact model surface` its patches
 * (surface_state.c). Arrays are listed as they are in memory
 * (doubles bit for bit, pairs and joints as raw records whose sizes the header carries), so a
 * restored run continues exactly as the uninterrupted one would: tests/cli/checkpoint.sh
 * compares the final states of both for equality.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/state.h"
#include "engine/sim.h"
#include "base/vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void rd_state_capture(rd_sim *s, long h[RD_STATE_HEADER], double settle[2])
{
    const long v[RD_STATE_HEADER] = { RD_STATE_VERSION,
                                      s->nb,
                                      s->npts,
                                      s->npair,
                                      s->njoint,
                                      s->nstate,
                                      s->nface_state,
                                      s->hcap,
                                      s->nlive_prev,
                                      s->nevent,
                                      s->stamp,
                                      s->sweep_axis,
                                      (long)sizeof(rd_pair),
                                      (long)sizeof(rd_joint),
                                      (long)sizeof(rd_event),
                                      s->nedge_state };
    memcpy(h, v, sizeof v);
    rd_surface_state_capture(s, h);
    settle[0] = s->settle_time;
    settle[1] = s->settle_ratio;
    for (int k = 0; k < s->nfree; k++) s->rest_area[k] = s->watch[k].area;
}

int rd_state_arrays(rd_sim *s, rd_state_array a[RD_STATE_ARRAYS])
{
    int n = 0, nb = s->nb;
    a[n++] = (rd_state_array){ "bodies/position", RD_STATE_DOUBLE, s->x, 3L * nb };
    a[n++] = (rd_state_array){ "bodies/quaternion", RD_STATE_DOUBLE, s->q, 4L * nb };
    a[n++] = (rd_state_array){ "bodies/velocity", RD_STATE_DOUBLE, s->v, 3L * nb };
    a[n++] = (rd_state_array){ "bodies/angular_momentum", RD_STATE_DOUBLE, s->L, 3L * nb };
    a[n++] = (rd_state_array){ "state/angular_velocity", RD_STATE_DOUBLE, s->w, 3L * nb };
    a[n++] = (rd_state_array){ "state/velocity_old", RD_STATE_DOUBLE, s->v_old, 3L * nb };
    a[n++] = (rd_state_array){ "state/angular_momentum_old", RD_STATE_DOUBLE, s->L_old, 3L * nb };
    a[n++] = (rd_state_array){ "state/aabb", RD_STATE_DOUBLE, s->aabb, 6L * nb };
    a[n++] = (rd_state_array){ "state/order", RD_STATE_INT, s->order, nb };
    a[n++] = (rd_state_array){ "state/hash", RD_STATE_INT, s->hkey, s->hcap };
    a[n++] = (rd_state_array){ "state/live", RD_STATE_INT, s->live_prev, s->nlive_prev };
    a[n++] = (rd_state_array){ "state/pairs", RD_STATE_BYTE, s->pair,
                               (long)(s->npair * sizeof *s->pair) };
    a[n++] = (rd_state_array){ "state/joints", RD_STATE_BYTE, s->joint,
                               (long)(s->njoint * sizeof *s->joint) };
    a[n++] = (rd_state_array){ "state/shear_force", RD_STATE_DOUBLE, s->fs, 3L * s->nstate };
    a[n++] = (rd_state_array){ "state/point_state", RD_STATE_BYTE, s->pstate, s->nstate };
    a[n++] = (rd_state_array){ "state/point_force_gap", RD_STATE_DOUBLE, s->pj, 2L * s->nstate };
    a[n++] = (rd_state_array){ "state/entrance_face", RD_STATE_BYTE, s->pface,
                               (long)(s->nstate * sizeof *s->pface) };
    a[n++] = (rd_state_array){ "state/permanent_set", RD_STATE_DOUBLE, s->pset, s->nstate };
    a[n++] = (rd_state_array){ "state/struck_stretch", RD_STATE_DOUBLE, s->pstrike, s->nstate };
    a[n++] = (rd_state_array){ "state/face_active", RD_STATE_INT, s->face_nactive, s->nface_state };
    a[n++] = (rd_state_array){ "state/events", RD_STATE_BYTE, s->event,
                               (long)(s->nevent * sizeof *s->event) };
    a[n++] = (rd_state_array){ "state/rest_area", RD_STATE_DOUBLE, s->rest_area, s->nfree };
    a[n++] =
        (rd_state_array){ "state/edge_shear_force", RD_STATE_DOUBLE, s->efs, 3L * s->nedge_state };
    a[n++] =
        (rd_state_array){ "state/edge_depth", RD_STATE_DOUBLE, s->edepth, 3L * s->nedge_state };
    a[n++] = (rd_state_array){ "state/edge_bearing", RD_STATE_BYTE, s->eon, s->nedge_state };
    return rd_surface_state_arrays(s, a, n);
}

/* Do the k values at a and b agree to RD_STATE_BUILD_RTOL of scale? */
static int agree(const double *a, const double *b, int k, double scale)
{
    for (int j = 0; j < k; j++)
        if (!(fabs(a[j] - b[j]) <= RD_STATE_BUILD_RTOL * scale)) return 0;
    return 1;
}

/* Body i's shape against the saved one (its vertices there at v): NULL, or why not (in buf). */
static const char *shape_mismatch(const rd_sim *s, int i, const rd_state_build *there,
                                  const double *v, char *buf, size_t n)
{
    const char *name = s->sc.bodies[i].name;
    const rd_poly *p = &s->poly[i];
    if (there->nv[i] != p->nv) {
        snprintf(buf, n, "block '%s' has another shape (%d vertices there, %d here)", name,
                 there->nv[i], p->nv);
        return buf;
    }
    for (int k = 0; k < p->nv; k++)
        if (!agree(&v[3 * k], p->v[k], 3, p->radius)) {
            snprintf(buf, n,
                     "block '%s' has another shape (vertex %d at (%.9g, %.9g, %.9g) m there, "
                     "(%.9g, %.9g, %.9g) m here, in its principal frame)",
                     name, k + 1, v[3 * k], v[3 * k + 1], v[3 * k + 2], p->v[k][0], p->v[k][1],
                     p->v[k][2]);
            return buf;
        }
    return NULL;
}

/* Body i's mass and principal moments against the saved ones: NULL, or why not (in buf). */
static const char *mass_mismatch(const rd_sim *s, int i, const rd_state_build *there, char *buf,
                                 size_t n)
{
    const char *name = s->sc.bodies[i].name;
    const double *m = &there->inertia[3 * i], *h = s->inertia[i];
    if (!agree(&there->mass[i], &s->mass[i], 1, s->mass[i])) {
        snprintf(buf, n, "block '%s' has another mass (%.9g kg there, %.9g kg here)", name,
                 there->mass[i], s->mass[i]);
        return buf;
    }
    if (agree(m, h, 3, fmax(fmax(h[0], h[1]), h[2]))) return NULL;
    snprintf(buf, n,
             "block '%s' has other principal moments of inertia (%.6g, %.6g, %.6g kg m^2 there, "
             "%.6g, %.6g, %.6g here)",
             name, m[0], m[1], m[2], h[0], h[1], h[2]);
    return buf;
}

/* Fixed body i's pose as built against the saved one: NULL, or why not (in buf). */
static const char *pose_mismatch(const rd_sim *s, int i, const rd_state_build *there, char *buf,
                                 size_t n)
{
    const char *name = s->sc.bodies[i].name;
    const double *x = &there->x[3 * i], *q = &there->q[4 * i], *h = s->q[i];
    const double minus_q[4] = { -q[0], -q[1], -q[2], -q[3] }; /* q and -q: the same orientation */
    if (!agree(x, s->x[i], 3, rd_norm(s->x[i]) + s->poly[i].radius)) {
        snprintf(buf, n,
                 "fixed block '%s' stands elsewhere (centre of mass at (%.9g, %.9g, %.9g) m there, "
                 "(%.9g, %.9g, %.9g) m here)",
                 name, x[0], x[1], x[2], s->x[i][0], s->x[i][1], s->x[i][2]);
        return buf;
    }
    if (agree(q, h, 4, 1) || agree(minus_q, h, 4, 1)) return NULL;
    snprintf(buf, n,
             "fixed block '%s' is turned otherwise (quaternion (%.6g, %.6g, %.6g, %.6g) there, "
             "(%.6g, %.6g, %.6g, %.6g) here)",
             name, q[0], q[1], q[2], q[3], h[0], h[1], h[2], h[3]);
    return buf;
}

/* Are the saved blocks (there) this simulation's as built, to RD_STATE_BUILD_RTOL? NULL, or the
 * first difference naming its block (in buf). Before the image is read. */
static const char *build_mismatch(const rd_sim *s, const rd_state_build *there, char *buf, size_t n)
{
    const double *v = there->vertices;
    for (int i = 0; i < s->nb; i++) {
        if (there->fixed[i] != s->fixed[i]) {
            snprintf(buf, n, "block '%s' is %s there, %s here", s->sc.bodies[i].name,
                     there->fixed[i] ? "fixed" : "free", s->fixed[i] ? "fixed" : "free");
            return buf;
        }
        const char *bad = shape_mismatch(s, i, there, v, buf, n);
        if (!bad) bad = mass_mismatch(s, i, there, buf, n);
        if (!bad && s->fixed[i]) bad = pose_mismatch(s, i, there, buf, n);
        if (bad) return bad;
        v += 3 * there->nv[i];
    }
    return NULL;
}

const char *rd_state_mismatch(const rd_sim *s, const long h[RD_STATE_HEADER],
                              const char *const *names, const rd_state_build *there, char *buf,
                              size_t n)
{
    if (h[RD_STATE_H_VERSION] != RD_STATE_VERSION) {
        snprintf(
            buf, n,
            "checkpoint version %ld, this rockdem reads version %d (save it again with this build)",
            h[RD_STATE_H_VERSION], RD_STATE_VERSION);
        return buf;
    }
    if (h[RD_STATE_H_PAIR_SIZE] != (long)sizeof(rd_pair) ||
        h[RD_STATE_H_JOINT_SIZE] != (long)sizeof(rd_joint) ||
        h[RD_STATE_H_EVENT_SIZE] != (long)sizeof(rd_event))
        return "written by another rockdem build (checkpoint layout differs)";
    const char *model = rd_surface_state_mismatch(s, h, buf, n);
    if (model) return model;
    if (h[RD_STATE_H_NB] != s->nb || !names || !there) {
        snprintf(buf, n, "it holds %ld blocks, this scenario %d", h[RD_STATE_H_NB], s->nb);
        return buf;
    }
    for (int i = 0; i < s->nb; i++)
        if (strcmp(names[i], s->sc.bodies[i].name)) {
            snprintf(buf, n, "block %d is '%s' there, '%s' here", i + 1, names[i],
                     s->sc.bodies[i].name);
            return buf;
        }
    const char *bad = build_mismatch(s, there, buf, n);
    if (bad) return bad;
    if (h[RD_STATE_H_NPTS] != s->npts) {
        snprintf(buf, n, "it has %ld subcontacts, this scenario %d (other shapes or spacing)",
                 h[RD_STATE_H_NPTS], s->npts);
        return buf;
    }
    return NULL;
}

int rd_state_reserve(rd_sim *s, const long h[RD_STATE_HEADER])
{
    long nstate = h[RD_STATE_H_NSTATE];
    void **p[] = { (void **)&s->hkey,  (void **)&s->live_prev,    (void **)&s->pair,
                   (void **)&s->joint, (void **)&s->fs,           (void **)&s->pstate,
                   (void **)&s->pj,    (void **)&s->face_nactive, (void **)&s->event,
                   (void **)&s->pface, (void **)&s->pset,         (void **)&s->pstrike,
                   (void **)&s->efs,   (void **)&s->edepth,       (void **)&s->eon };
    size_t sz[] = { sizeof *s->hkey * (size_t)h[RD_STATE_H_HCAP],
                    sizeof *s->live_prev * (size_t)h[RD_STATE_H_NLIVE],
                    sizeof *s->pair * (size_t)h[RD_STATE_H_NPAIR],
                    sizeof *s->joint * (size_t)h[RD_STATE_H_NJOINT],
                    sizeof *s->fs * (size_t)nstate,
                    sizeof *s->pstate * (size_t)nstate,
                    sizeof *s->pj * (size_t)nstate,
                    sizeof *s->face_nactive * (size_t)h[RD_STATE_H_NFACE],
                    sizeof *s->event * (size_t)h[RD_STATE_H_NEVENT],
                    sizeof *s->pface * (size_t)nstate,
                    sizeof *s->pset * (size_t)nstate,
                    sizeof *s->pstrike * (size_t)nstate,
                    sizeof *s->efs * (size_t)h[RD_STATE_H_NEDGE],
                    sizeof *s->edepth * (size_t)h[RD_STATE_H_NEDGE],
                    sizeof *s->eon * (size_t)h[RD_STATE_H_NEDGE] };
    for (size_t k = 0; k < sizeof sz / sizeof sz[0]; k++) {
        void *t = realloc(*p[k], sz[k] ? sz[k] : 1);
        if (!t) return -1;
        *p[k] = t;
    }
    s->hcap = (int)h[RD_STATE_H_HCAP];
    s->nlive_prev = s->cap_live_prev = (int)h[RD_STATE_H_NLIVE];
    s->npair = s->cap_pair = (int)h[RD_STATE_H_NPAIR];
    s->njoint = s->cap_joint = (int)h[RD_STATE_H_NJOINT];
    s->nstate = s->cap_state = s->cap_state_flags = s->cap_state_joint = (int)nstate;
    s->cap_pface = s->cap_pset = s->cap_pstrike = (int)nstate;
    s->nface_state = s->cap_face_state = (int)h[RD_STATE_H_NFACE];
    s->nevent = s->cap_event = (int)h[RD_STATE_H_NEVENT];
    s->nedge_state = s->cap_efs = s->cap_edepth = s->cap_eon = (int)h[RD_STATE_H_NEDGE];
    s->stamp = h[RD_STATE_H_STAMP];
    s->sweep_axis = (int)h[RD_STATE_H_AXIS];
    return rd_surface_state_reserve(s, h);
}

void rd_state_restored(rd_sim *s, const double settle[2])
{
    for (int k = 0; k < s->nfree; k++)
        s->watch[k].area = s->rest_area[k]; /* contact area at rest */
    /* an edge side's skip holds for the saving run's box builds (rd_sim.box_builds, not in the
       image: this run counts its own) */
    for (int p = 0; p < s->npair; p++)
        for (int q = 0; q < s->pair[p].nside; q++) s->pair[p].side[q].edges_clear = 0;
    rd_contact_find_impacts(s); /* the bodies taking a new impact, from the points' state */
    s->settle_time = settle[0];
    s->settle_ratio = settle[1];
    s->restored = 1;
}

int rd_state_build_alloc(rd_state_build *b, int nb, long nvert)
{
    *b = (rd_state_build){ .nb = nb,
                           .nvert = nvert }; /* each array one longer: never a 0-byte calloc */
    b->fixed = calloc((size_t)nb + 1, sizeof *b->fixed);
    b->nv = calloc((size_t)nb + 1, sizeof *b->nv);
    b->mass = calloc((size_t)nb + 1, sizeof *b->mass);
    b->inertia = calloc(3 * (size_t)nb + 1, sizeof *b->inertia);
    b->x = calloc(3 * (size_t)nb + 1, sizeof *b->x);
    b->q = calloc(4 * (size_t)nb + 1, sizeof *b->q);
    b->vertices = calloc(3 * (size_t)nvert + 1, sizeof *b->vertices);
    if (b->fixed && b->nv && b->mass && b->inertia && b->x && b->q && b->vertices) return 0;
    rd_state_build_free(b);
    return -1;
}

void rd_state_build_free(rd_state_build *b)
{
    free(b->fixed);
    free(b->nv);
    free(b->mass);
    free(b->inertia);
    free(b->x);
    free(b->q);
    free(b->vertices);
    *b = (rd_state_build){ 0 };
}

int rd_state_build_of(const rd_sim *s, rd_state_build *b)
{
    long nvert = 0;
    for (int i = 0; i < s->nb; i++) nvert += s->poly[i].nv;
    if (rd_state_build_alloc(b, s->nb, nvert)) return -1;
    double *v = b->vertices;
    for (int i = 0; i < s->nb; i++) {
        b->fixed[i] = s->fixed[i];
        b->nv[i] = s->poly[i].nv;
        b->mass[i] = s->mass[i];
        memcpy(&b->inertia[3 * i], s->inertia[i], sizeof s->inertia[i]);
        memcpy(&b->x[3 * i], s->x[i], sizeof s->x[i]);
        memcpy(&b->q[4 * i], s->q[i], sizeof s->q[i]);
        memcpy(v, s->poly[i].v, 3 * sizeof *v * (size_t)s->poly[i].nv);
        v += 3 * s->poly[i].nv;
    }
    return 0;
}

int rd_state_build_arrays(rd_state_build *b, rd_state_array a[RD_STATE_ARRAYS])
{
    int n = 0;
    a[n++] = (rd_state_array){ "bodies/fixed", RD_STATE_INT, b->fixed, b->nb };
    a[n++] = (rd_state_array){ "bodies/vertex_count", RD_STATE_INT, b->nv, b->nb };
    a[n++] = (rd_state_array){ "bodies/mass", RD_STATE_DOUBLE, b->mass, b->nb };
    a[n++] = (rd_state_array){ "bodies/inertia", RD_STATE_DOUBLE, b->inertia, 3L * b->nb };
    a[n++] = (rd_state_array){ "bodies/vertices", RD_STATE_DOUBLE, b->vertices, 3 * b->nvert };
    return n;
}
