/* rockdem — a reference solution written in the DEM's HDF5 layout (src/io/io_hdf5.h), so one tool
 * reads both. Each block is a rigid body rotating in the vertical plane of the rocking direction
 * d about its active pivot: the ground pivot O = (s1 b1 d, base) for block 1, the corner
 * P = (s2 b2 d, top of block 1) of block 1 for block 2. The rotation axis is a = (-d_y, d_x, 0)
 * (a positive angle tips the top toward +d). Energies: kinetic and gravitational (from rest);
 * the rigid model has no springs, friction or dashpots, so the others are written as zero.
 * Folder reference/ owns the rigid CVODE reference solvers (Housner, Kounadis); it may call
 * base/, records/, io/ and the public API.
 */
#include "rockdem/validate.h"
#include "rockdem/output.h"
#include "base/path.h"
#include "io/io_hdf5.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Rotate r about unit axis a by angle th (Rodrigues), into out. */
static void rotate(const double a[3], double th, const double r[3], double out[3])
{
    double c = cos(th), s = sin(th), ad = a[0] * r[0] + a[1] * r[1] + a[2] * r[2];
    double x[3] = { a[1] * r[2] - a[2] * r[1], a[2] * r[0] - a[0] * r[2],
                    a[0] * r[1] - a[1] * r[0] };
    for (int k = 0; k < 3; k++) out[k] = r[k] * c + x[k] * s + a[k] * ad * (1 - c);
}

/* out = w a x r (velocity of a point at r from the pivot, rotating at w about a). */
static void spin(const double a[3], double w, const double r[3], double out[3])
{
    out[0] = w * (a[1] * r[2] - a[2] * r[1]);
    out[1] = w * (a[2] * r[0] - a[0] * r[2]);
    out[2] = w * (a[0] * r[1] - a[1] * r[0]);
}

typedef struct pose {
    double x[2][3], v[2][3]; /* centre of mass and its velocity, m, m/s */
} pose;

static double sgn(double v) { return (v > 0) - (v < 0); }

/* Poses of the blocks for one sample. The pivot sides come from the signs of the angles (the
 * pattern in force), which also hold on a sample exactly at an impact. */
static void sample_pose(const rd_refscene *rs, const rd_ref_sample *sm, pose *ps)
{
    const double a[3] = { -rs->dir[1], rs->dir[0], 0 };
    double s1 = sgn(sm->theta[0]), s2 = sgn(sm->theta[1] - sm->theta[0]);
    double O[3] = { rs->origin[0] + s1 * rs->b[0] * rs->dir[0],
                    rs->origin[1] + s1 * rs->b[0] * rs->dir[1], rs->base_z };
    double c1[3] = { rs->origin[0], rs->origin[1], rs->base_z + rs->h[0] }, r[3], rr[3];
    for (int k = 0; k < 3; k++) r[k] = c1[k] - O[k];
    rotate(a, sm->theta[0], r, rr);
    for (int k = 0; k < 3; k++) ps->x[0][k] = O[k] + rr[k];
    spin(a, sm->omega[0], rr, ps->v[0]);
    if (rs->nblock < 2) return;
    double P[3] = { rs->origin[0] + s2 * rs->b[1] * rs->dir[0],
                    rs->origin[1] + s2 * rs->b[1] * rs->dir[1], rs->base_z + 2 * rs->h[0] },
           Pw[3], vP[3];
    for (int k = 0; k < 3; k++) r[k] = P[k] - O[k];
    rotate(a, sm->theta[0], r, rr);
    spin(a, sm->omega[0], rr, vP);
    for (int k = 0; k < 3; k++) Pw[k] = O[k] + rr[k];
    double c2[3] = { rs->origin[0], rs->origin[1], rs->base_z + 2 * rs->h[0] + rs->h[1] };
    for (int k = 0; k < 3; k++) r[k] = c2[k] - P[k];
    rotate(a, sm->theta[1], r, rr);
    spin(a, sm->omega[1], rr, ps->v[1]);
    for (int k = 0; k < 3; k++) {
        ps->x[1][k] = Pw[k] + rr[k];
        ps->v[1][k] += vP[k];
    }
}

/* Box vertices about its centre and its 12 triangles (outward). */
static const int box_tri[12][3] = { { 0, 2, 1 }, { 0, 3, 2 }, { 4, 5, 6 }, { 4, 6, 7 },
                                    { 0, 1, 5 }, { 0, 5, 4 }, { 1, 2, 6 }, { 1, 6, 5 },
                                    { 2, 3, 7 }, { 2, 7, 6 }, { 3, 0, 4 }, { 3, 4, 7 } };

static void box_vertices(const double size[3], double v[8][3])
{
    static const int sx[8] = { -1, 1, 1, -1, -1, 1, 1, -1 }, sy[8] = { -1, -1, 1, 1, -1, -1, 1, 1 };
    for (int i = 0; i < 8; i++) {
        v[i][0] = 0.5 * sx[i] * size[0];
        v[i][1] = 0.5 * sy[i] * size[1];
        v[i][2] = 0.5 * (i < 4 ? -1 : 1) * size[2];
    }
}

static rd_h5 *open_file(const rd_scenario *sc, const rd_refscene *rs, const char *path,
                        double verts[2][8][3], rd_error *err)
{
    rd_h5_body hb[2];
    for (int k = 0; k < rs->nblock; k++) {
        const double *s = rs->size[k];
        double m = rs->mass[k];
        box_vertices(s, verts[k]);
        hb[rs->out[k]] = (rd_h5_body){ .name = sc->bodies[rs->body[k]].name,
                                       .mass = m,
                                       .inertia = { m * (s[1] * s[1] + s[2] * s[2]) / 12,
                                                    m * (s[0] * s[0] + s[2] * s[2]) / 12,
                                                    m * (s[0] * s[0] + s[1] * s[1]) / 12 },
                                       .size = { s[0], s[1], s[2] },
                                       .alpha = atan2(rs->b[k], rs->h[k]),
                                       .nvert = 8,
                                       .vertices = &verts[k][0][0],
                                       .ntri = 12,
                                       .triangles = &box_tri[0][0] };
    }
    char damping[160];
    if (rs->model == RD_REFMODEL_HOUSNER)
        snprintf(damping, sizeof damping,
                 "rigid reference (Housner), impact restitution e = %.4g%s",
                 rs->housner.e >= 0 ? rs->housner.e : rd_housner_r(rs->alpha),
                 rs->housner.e >= 0 ? "" : " (Housner's r)");
    else if (rs->kounadis.r > 0.0)
        snprintf(damping, sizeof damping,
                 "rigid reference (Kounadis), impacts keep %.4g x the plastic "
                 "rates (lower block's e = %.4g)",
                 rs->kounadis.r / rd_housner_r(rs->alpha), rs->kounadis.r);
    else
        snprintf(damping, sizeof damping,
                 "rigid reference (Kounadis), plastic impacts "
                 "(angular momentum conserved)");
    rd_h5_meta meta = { .scenario_text = sc->text ? sc->text : "",
                        .scenario_file = sc->file,
                        .title = sc->title,
                        .damping = damping,
                        .overturn_criterion =
                            "rigid: certain fall (energy above the saddle moving outward)",
                        .nbodies = rs->nblock,
                        .bodies = hb };
    char tmp[RD_PATH_MAX]; /* an earlier file at path is replaced once this one is whole */
    int staged = rd_output_staging(path, sc->overwrite, tmp, sizeof tmp);
    meta.target = staged ? path : NULL;
    return rd_h5_open(staged ? tmp : path, &meta, err);
}

static int write_samples(const rd_scenario *sc, const rd_refscene *rs, const rd_ref_result *res,
                         rd_h5 *h5, rd_body_summary *body, rd_error *err)
{
    const double a[3] = { -rs->dir[1], rs->dir[0], 0 };
    for (size_t i = 0; i < res->nsamples; i++) {
        const rd_ref_sample *sm = &res->samples[i];
        pose ps;
        sample_pose(rs, sm, &ps);
        double pos[6], quat[8], vel[6], ang[6], tilt[2], rot[6] = { 0 };
        rd_h5_sample out = { .time = sm->t,
                             .position = pos,
                             .quaternion = quat,
                             .velocity = vel,
                             .angular_velocity = ang,
                             .tilt = tilt,
                             .rotation = rot };
        rd_motion_eval(&rs->motion, sm->t, out.ground_acc, out.ground_vel, out.ground_disp);
        for (int k = 0; k < rs->nblock; k++) {
            int o = rs->out[k];
            double th = sm->theta[k], m = rs->mass[k];
            double Ic = m * (rs->b[k] * rs->b[k] + rs->h[k] * rs->h[k]) / 3; /* about the centre */
            memcpy(pos + 3 * o, ps.x[k], sizeof ps.x[k]);
            memcpy(vel + 3 * o, ps.v[k], sizeof ps.v[k]);
            quat[4 * o] = cos(0.5 * th);
            for (int j = 0; j < 3; j++) {
                quat[4 * o + 1 + j] = a[j] * sin(0.5 * th);
                ang[3 * o + j] = a[j] * sm->omega[k];
            }
            tilt[o] = fabs(th);
            rot[3 * o] = th; /* planar: all in-plane rocking (about a), no out-of-plane, no twist */
            double v2 = ps.v[k][0] * ps.v[k][0] + ps.v[k][1] * ps.v[k][1] + ps.v[k][2] * ps.v[k][2];
            out.energy[0] += 0.5 * m * v2 + 0.5 * Ic * sm->omega[k] * sm->omega[k];
            double z0 = rs->base_z + (k ? 2 * rs->h[0] : 0) + rs->h[k];
            out.energy[1] += m * sc->gravity * (ps.x[k][2] - z0);
            if (fabs(th) > body[o].max_tilt) body[o].max_tilt = fabs(th);
            body[o].uplifted |= th != 0;
        }
        if (rd_h5_append(h5, &out, err)) return -1;
    }
    return 0;
}

static int write_events(const rd_refscene *rs, const rd_ref_result *res, rd_h5 *h5, rd_error *err)
{
    static const char *names[] = {
        "uplift", "impact", NULL, "rest", "lock", "overturn", "liftoff"
    };
    for (size_t i = 0; i < res->nevents; i++) {
        const rd_ref_event *e = &res->events[i];
        if (!names[e->kind]) continue; /* turning points are not DEM events */
        int j = e->joint ? 1 : 0, body = rs->out[rs->nblock > 1 ? j : 0];
        double value = e->kind == RD_REF_IMPACT ? fabs(e->omega_pre[j]) : fabs(e->theta[j]);
        if (rd_h5_event(h5, e->t, body, names[e->kind], value, err)) return -1;
    }
    return 0;
}

static void fill_summary(const rd_scenario *sc, const rd_refscene *rs, const rd_ref_result *res,
                         rd_summary *sum, rd_body_summary *body)
{
    const rd_ref_summary *r = &res->summary;
    sum->nbodies = rs->nblock;
    sum->body = body;
    sum->end_time = r->t_stop;
    sum->status = r->overturned ? RD_STATUS_OVERTURNED : RD_STATUS_DONE;
    sum->any_overturned = r->overturned;
    for (int k = 0; k < rs->nblock; k++) {
        rd_body_summary *b = &body[rs->out[k]];
        snprintf(b->name, sizeof b->name, "%s", sc->bodies[rs->body[k]].name);
        b->alpha = atan2(rs->b[k], rs->h[k]);
        b->max_tilt_ratio = r->max_ratio[k];
        /* the lower block carries the upper one down with it */
        b->overturned = r->overturned && (r->overturn_joint == 0 || r->overturn_joint == k);
        b->overturn_time = b->overturned ? r->t_overturn : -1;
    }
}

int rd_refscene_check_output(const rd_scenario *sc, const char *path, rd_error *err)
{
    return rd_path_check_output(sc, path, NULL, err);
}

int rd_refscene_write(const rd_scenario *sc, const rd_refscene *rs, const rd_ref_result *res,
                      const char *path, rd_summary *sum, rd_body_summary body[RD_REF_BLOCKS],
                      rd_error *err)
{
    char why[RD_ERROR_MAX];
    const char *bad = rd_path_output_conflict(sc, path, NULL, RD_OUTPUT_RUN, why, sizeof why);
    if (bad) return rd_error_set(err, "%s: cannot write the output there: %s", path, bad);
    double verts[2][8][3];
    rd_summary s = { 0 };
    rd_body_summary bs[RD_REF_BLOCKS] = { 0 };
    rd_h5 *h5 = open_file(sc, rs, path, verts, err);
    if (!h5) return -1;
    fill_summary(sc, rs, res, &s, bs);
    int rc = write_samples(sc, rs, res, h5, bs, err) || write_events(rs, res, h5, err) ||
             rd_h5_summary(h5, &s, err) || rd_h5_flush(h5, err) || rd_h5_commit(h5, 1, err);
    rd_h5_close(h5);
    if (sum) {
        memcpy(body, bs, sizeof bs);
        *sum = s;
        sum->body = body;
    }
    return rc ? -1 : 0;
}
