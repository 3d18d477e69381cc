/* rockdem — the scene-control tables of a run file, written when the run ends (after the
 * time series' last flush, so small files stay small while the series are written):
 *   /history/time, /history/<series>     the `history` table (rockdem/history.h), every series
 *                                        on the /history/time axis, its columns on a scale
 *   /joints/joint, body_a, body_b         every pair of bodies that came near each other
 *   /joints/properties [joint][property]  kn, ks, friction, cohesion, tension, damping_ratio
 *   /joints/outcomes [joint][outcome]     max_opening, max_slip, final_slip, closed
 *   /outcomes/bodies [body][quantity]     x, y, z at the end, travel, drop, unsupported
 *   /runout/bodies [body][quantity]       runout, direction, path, speed, bounce, orientation,
 *                                         domain exit and fence crossing (docs/RUNOUT.md)
 *   /runout/fence [point][plan]           the first fence's polyline, when one is given
 *   /runout/fences/<name>/points, bodies  every fence's polyline and each body's crossings
 * docs/HDF5-LAYOUT.md describes them with the rest of the file.
 * Folder io/ owns the HDF5 output file; it may call base/ and the public headers, never engine/
 * internals or cli/.
 */
#include "io/output_scene.h"
#include "io/h5_quiet.h"
#include "io/io_table.h"
#include "rockdem/history.h"
#include "rockdem/observer.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int history(long long f, const rd_sim *sim, rd_error *err)
{
    int ns = rd_sim_history_count(sim), cols;
    long rows;
    const double *tab = rd_sim_history_table(sim, &rows, &cols);
    if (ns == 0) return 0;
    double *buf = malloc((size_t)(rows ? rows : 1) * (size_t)cols * sizeof *buf);
    if (!buf) return rd_error_set(err, "out of memory");
    for (long r = 0; r < rows; r++) buf[r] = tab[r * cols];
    int rc = rd_h5t_write(f, "history/time", RD_H5T_DOUBLE, buf, rows, 0, "s",
                          "time of the history samples since the shaking started", NULL, err) ||
             rd_h5t_make_scale(f, "history/time", err);
    for (int k = 0; k < ns && !rc; k++) {
        rd_history_series se;
        rd_sim_history_series(sim, k, &se);
        for (long r = 0; r < rows; r++)
            for (int c = 0; c < se.ncol; c++) buf[r * se.ncol + c] = tab[r * cols + se.col + c];
        char path[sizeof se.path + 16], dim[sizeof se.path + 64];
        snprintf(path, sizeof path, "history/%s", se.path);
        const char *slash = strrchr(path, '/');
        if (se.dim && se.dim[0] != '/') /* a scale of the series' own group */
            snprintf(dim, sizeof dim, "%.*s/%s", (int)(slash - path), path, se.dim);
        else
            snprintf(dim, sizeof dim, "%s", se.dim ? se.dim : "");
        rd_h5t_axes ax = { { "/history/time", se.ncol > 1 ? dim : NULL }, { NULL, se.labels } };
        rc = rd_h5t_write(f, path, RD_H5T_DOUBLE, buf, rows, se.ncol > 1 ? se.ncol : 0, se.units,
                          se.long_name, &ax, err);
    }
    free(buf);
    return rc ? -1 : 0;
}

enum { NPROP = 6, NOUT = 4, NBODY = 6, NRUN = 19, NHIT = 8 };

static int joints(long long f, const rd_sim *sim, rd_error *err)
{
    int n = rd_sim_joint_count(sim), rc = 0;
    rd_joint_summary *j = malloc((size_t)(n + 1) * sizeof *j);
    char(*label)[2 * RD_NAME_MAX + 2] = malloc((size_t)(n + 1) * sizeof *label);
    const char **lab = malloc((size_t)(n + 1) * 3 * sizeof *lab);
    double *prop = malloc((size_t)(n + 1) * NPROP * sizeof *prop),
           *out = malloc((size_t)(n + 1) * NOUT * sizeof *out);
    if (!j || !label || !lab || !prop || !out) rc = rd_error_set(err, "out of memory");
    const char **a = lab + n, **b = lab + 2 * n;
    for (int p = 0; !rc && p < n; p++) {
        rd_sim_joint(sim, p, &j[p]);
        snprintf(label[p], sizeof label[p], "%s-%s", j[p].a, j[p].b);
        lab[p] = label[p];
        a[p] = j[p].a;
        b[p] = j[p].b;
        double v[NPROP] = { j[p].kn,       j[p].ks,      j[p].friction,
                            j[p].cohesion, j[p].tension, j[p].damping };
        double o[NOUT] = { j[p].max_opening, j[p].max_slip, j[p].final_slip, j[p].closed };
        memcpy(prop + NPROP * p, v, sizeof v);
        memcpy(out + NOUT * p, o, sizeof o);
    }
    rd_h5t_axes pax = { { "joint", "property" },
                        { NULL, "kn,ks,friction,cohesion,tension,damping_ratio" } };
    rd_h5t_axes oax = { { "joint", "outcome" },
                        { NULL, "max_opening,max_slip,final_slip,closed" } };
    if (!rc)
        rc = rd_h5t_strings(f, "joints/joint", lab, n, "joint: its two bodies", "joints/joint",
                            err) ||
             rd_h5t_strings(f, "joints/body_a", a, n, "first body of the joint", "/joints/joint",
                            err) ||
             rd_h5t_strings(f, "joints/body_b", b, n, "second body of the joint", "/joints/joint",
                            err);
    long long g = rc ? -1 : rd_h5t_group(f, "joints", err);
    if (g >= 0) {
        rc = rd_h5t_write(
                 g, "properties", RD_H5T_DOUBLE, prop, n, NPROP, "Pa/m,Pa/m,rad,Pa,Pa,1",
                 "joint properties: kn, ks (per unit area), friction angle, cohesion, tensile "
                 "strength, normal dashpot ratio",
                 &pax, err) ||
             rd_h5t_write(
                 g, "outcomes", RD_H5T_DOUBLE, out, n, NOUT, "m,m,m,1",
                 "largest opening and slip while shaking, final slip (slip of the second body "
                 "against the first at the centre of pressure, elastic shear removed), 1 if it "
                 "carried load",
                 &oax, err);
        rd_h5t_close_group(g);
    } else {
        rc = -1;
    }
    free(j);
    free(label);
    free(lab);
    free(prop);
    free(out);
    return rc ? -1 : 0;
}

static int outcomes(long long f, const rd_summary *s, rd_error *err)
{
    int nf = s->nbodies;
    double *v = malloc((size_t)(nf + 1) * NBODY * sizeof *v);
    if (!v) return rd_error_set(err, "out of memory");
    for (int k = 0; k < nf; k++) {
        const rd_body_summary *b = &s->body[k];
        double row[NBODY] = {
            b->final_position[0], b->final_position[1], b->final_position[2], b->travel, b->drop,
            b->unsupported
        };
        memcpy(v + NBODY * k, row, sizeof row);
    }
    rd_h5t_axes ax = { { "/body", "quantity" }, { NULL, "x,y,z,travel,drop,unsupported" } };
    long long g = rd_h5t_group(f, "outcomes", err);
    int rc =
        g < 0 || rd_h5t_write(g, "bodies", RD_H5T_DOUBLE, v, nf, NBODY, "m,m,m,m,m,1",
                              "where each free body ended up: centre of mass x, y, z at the end, "
                              "horizontal travel from rest, drop from placement, 1 if it touched "
                              "nothing (fell freely)",
                              &ax, err);
    rd_h5t_close_group(g);
    free(v);
    return rc ? -1 : 0;
}

static const char run_labels[] =
    "runout,direction,path_length,max_speed,max_energy,max_bounce,qw,qx,qy,qz,left_time,fence_crossings,"
    "fence_time,fence_energy,fence_speed,fence_height,fence_x,fence_y,fence_z";
static const char run_units[] = "m,rad,m,m/s,J,m,1,1,1,1,s,1,s,J,m/s,m,m,m,m";

static const char hit_labels[] = "crossings,time,energy,speed,height,x,y,z";
static const char hit_units[] = "1,s,J,m/s,m,m,m,m";

/* /runout/fences/<name>/points and bodies: fence f's polyline and each body's crossings. */
static int fence_tables(long long g, const rd_summary *s, const rd_fence_def *fe, int f,
                        rd_error *err)
{
    int nf = s->nbodies;
    double *v = malloc((size_t)(nf + 1) * NHIT * sizeof *v);
    if (!v) return rd_error_set(err, "out of memory");
    for (int k = 0; k < nf; k++) {
        const rd_fence_hit *h = &s->body[k].fence[f];
        double row[NHIT] = { h->crossings, h->time,     h->energy,   h->speed,
                             h->height,    h->point[0], h->point[1], h->point[2] };
        memcpy(v + NHIT * k, row, sizeof row);
    }
    rd_h5t_axes pax = { { "point", "plan" }, { NULL, "x,y" } };
    rd_h5t_axes bax = { { "/body", "quantity" }, { NULL, hit_labels } };
    long long fg = rd_h5t_group(g, fe->name, err);
    int rc =
        fg < 0 ||
        rd_h5t_write(fg, "points", RD_H5T_DOUBLE, fe->point, fe->npoint, 2, "m",
                     "the fence polyline in plan (a vertical fence standing on it)", &pax, err) ||
        rd_h5t_write(fg, "bodies", RD_H5T_DOUBLE, v, nf, NHIT, hit_units,
                     "each free body's crossings of this fence and, at the first, its time "
                     "(-1: none), kinetic energy, speed, centre height above the surface "
                     "and place",
                     &bax, err);
    rd_h5t_close_group(fg);
    free(v);
    return rc ? -1 : 0;
}

/* /runout/fence (the first fence's polyline, as before several were allowed) and
 * /runout/fences/<name>/ for every fence. */
static int fences(long long g, const rd_summary *s, const rd_scenario *sc, rd_error *err)
{
    const rd_runout_def *r = &sc->runout;
    if (r->nfences == 0) return 0;
    rd_h5t_axes ax = { { "point", "plan" }, { NULL, "x,y" } };
    if (rd_h5t_write(g, "fence", RD_H5T_DOUBLE, r->fence[0].point, r->fence[0].npoint, 2, "m",
                     "the first fence's polyline in plan (all of them: /runout/fences)", &ax, err))
        return -1;
    long long fg = rd_h5t_group(g, "fences", err);
    int rc = fg < 0;
    for (int f = 0; f < r->nfences && !rc; f++) rc = fence_tables(fg, s, &r->fence[f], f, err);
    rd_h5t_close_group(fg);
    return rc ? -1 : 0;
}

static int runout(long long f, const rd_sim *sim, const rd_summary *s, rd_error *err)
{
    int nf = s->nbodies;
    double *v = malloc((size_t)(nf + 1) * NRUN * sizeof *v);
    if (!v) return rd_error_set(err, "out of memory");
    for (int k = 0; k < nf; k++) {
        const rd_body_summary *b = &s->body[k];
        double row[NRUN] = { b->travel,
                             b->runout_direction,
                             b->path_length,
                             b->max_speed,
                             b->max_energy,
                             b->max_bounce,
                             b->final_quaternion[0],
                             b->final_quaternion[1],
                             b->final_quaternion[2],
                             b->final_quaternion[3],
                             b->left_time,
                             b->fence[0].crossings,
                             b->fence[0].time,
                             b->fence[0].energy,
                             b->fence[0].speed,
                             b->fence[0].height,
                             b->fence[0].point[0],
                             b->fence[0].point[1],
                             b->fence[0].point[2] };
        memcpy(v + NRUN * k, row, sizeof row);
    }
    rd_h5t_axes ax = { { "/body", "quantity" }, { NULL, run_labels } };
    long long g = rd_h5t_group(f, "runout", err);
    int rc =
        g < 0 ||
        rd_h5t_write(
            g, "bodies", RD_H5T_DOUBLE, v, nf, NRUN, run_units,
            "the runout of each free body's centre of mass (docs/RUNOUT.md): "
            "horizontal distance and direction from rest, path length, largest "
            "speed, kinetic energy and bounce, final orientation, time it left the domain (-1: "
            "never), the first fence's crossings and, at the first, its time (-1: none), "
            "kinetic energy, speed, height above the surface and place (every fence: "
            "/runout/fences)",
            &ax, err) ||
        fences(g, s, rd_sim_scenario(sim), err);
    rd_h5t_close_group(g);
    free(v);
    return rc ? -1 : 0;
}

/* Bytes the tables take in the file, at most: their doubles (contiguous, uncompressed), each
 * joint's three name strings in the global heap, and RD_TABLE_HEADER per dataset (its object
 * header, units, long_name and dimension-scale attributes), plus an eighth for HDF5's
 * allocation slack as for the series (io_hdf5.c h5_flush). */
#define RD_TABLE_HEADER 4096
static size_t scene_bytes(const rd_sim *sim, const rd_summary *s)
{
    long rows;
    const int nfence = rd_sim_scenario(sim)->runout.nfences;
    int cols, nj = rd_sim_joint_count(sim), nd = rd_sim_history_count(sim) + 10 + 3 * nfence;
    rd_sim_history_table(sim, &rows, &cols);
    size_t label = 2 * RD_NAME_MAX + 2 + 16; /* a joint's label and its heap object's header */
    size_t raw = sizeof(double) * ((size_t)rows * (size_t)cols + (size_t)nj * (NPROP + NOUT) +
                                   (size_t)s->nbodies * (NBODY + NRUN + NHIT * (size_t)nfence) +
                                   2 * RD_MAX_FENCE_POINTS * (size_t)(nfence + 1)) +
                 3 * label * (size_t)nj + RD_TABLE_HEADER * (size_t)nd;
    return raw + raw / 8;
}

/* The space is reserved first: HDF5 writing past a full disk or a size limit left a file that
 * no reader opens (its superblock's end of file beyond the file's end), and the run's samples
 * with it. A failure marks the file io_error: its status had read the run's, "done". */
int rd_h5_scene_tables(rd_h5 *h, const rd_sim *sim, const rd_summary *s, rd_error *err)
{
    if (rd_h5_reserve(h, scene_bytes(sim, s), err)) return -1;
    long long f = rd_h5_file_id(h);
    rd_h5_quiet q = rd_h5_quiet_begin();
    int rc = history(f, sim, err) || joints(f, sim, err) || outcomes(f, s, err) ||
             runout(f, sim, s, err) ||
             (rd_h5t_count(f, "history/time") >= 0 && rd_h5t_link_scales(f, "history", err)) ||
             rd_h5t_link_scales(f, "joints", err) || rd_h5t_link_scales(f, "outcomes", err) ||
             rd_h5t_link_scales(f, "runout", err);
    rd_h5_quiet_end(q);
    return rc ? rd_h5_fail(h, "cannot write the end-of-run tables", err) : 0;
}
