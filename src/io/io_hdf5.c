/* rockdem — HDF5 writer (layout in io_hdf5.h).
 *
 * Every per-sample series is a chunked, shuffle + deflate compressed dataset whose first
 * dimension is unlimited. Samples and events are buffered (RD_H5_BUF rows) and, when a buffer
 * fills or on rd_h5_flush, appended with H5Dset_extent + H5Dwrite and followed by H5Fflush, so
 * the file on disk is valid and holds every flushed sample even if the process dies. The file
 * uses the default (earliest) format, which has no "open for writing" flag to clear afterwards.
 *
 * Folder io/ owns the HDF5 output file; it may call base/ and the public headers, never engine/
 * internals or cli/.
 */
#include "io/io_hdf5.h"
#include "io/h5_quiet.h"

#include <hdf5.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RD_H5_BUF 256     /* rows buffered between writes; also the chunk length in time */
#define RD_H5_DEFLATE 4   /* deflate level */
#define RD_H5_EVTYPE 16   /* bytes of an event type word, NUL included */
#define RD_H5_SERNAME 48  /* bytes of a series path */

const char *const rd_energy_names[RD_NENERGY] = {
    "kinetic", "gravitational", "elastic", "friction", "damping", "ground_work", "residual"};

/* Per-sample series, in rd_h5_sample order; energies follow. */
enum {
    SER_TIME, SER_POSITION, SER_QUATERNION, SER_VELOCITY, SER_ANGULAR_VELOCITY, SER_TILT,
    SER_ROTATION, SER_GROUND_ACC, SER_GROUND_VEL, SER_GROUND_DISP, SER_ENERGY,
    SER_COUNT = SER_ENERGY + RD_NENERGY
};

typedef struct rd_h5_series_spec {
    const char *name;
    int per_body;  /* 1: one row per free body */
    hsize_t inner; /* components per body or sample, 0 for a scalar */
    const char *units;
} rd_h5_series_spec;

static const rd_h5_series_spec series_spec[SER_ENERGY] = {
    {"time", 0, 0, "s"},
    {"position", 1, 3, "m"},
    {"quaternion", 1, 4, "1"},
    {"velocity", 1, 3, "m/s"},
    {"angular_velocity", 1, 3, "rad/s"},
    {"tilt", 1, 0, "rad"},
    {"rotation", 1, 3, "rad"}, /* in-plane rocking, out-of-plane rocking, twist */
    {"ground/acceleration", 0, 3, "m/s^2"},
    {"ground/velocity", 0, 3, "m/s"},
    {"ground/displacement", 0, 3, "m"},
};

typedef struct rd_h5_series {
    char name[RD_H5_SERNAME];
    hid_t dset;
    int rank;
    hsize_t dims[3]; /* dims[0]: samples on disk; the rest: shape of one sample */
    size_t width;    /* doubles per sample */
    double *buf;     /* [RD_H5_BUF][width] */
} rd_h5_series;

typedef struct rd_h5_event_row {
    double time; /* s */
    int body;    /* index into /bodies/names, -1 = none */
    char type[RD_H5_EVTYPE];
    double value;
} rd_h5_event_row;

struct rd_h5 {
    char *path;
    hid_t file;
    hid_t str_type; /* variable-length UTF-8 string, for attributes */
    int nb;
    char (*names)[RD_NAME_MAX]; /* [nb] free bodies in output order */
    rd_h5_series ser[SER_COUNT];
    int nbuf; /* samples buffered */
    hid_t ev_dset, ev_mem_type;
    hsize_t ev_written;
    int nev; /* events buffered */
    rd_h5_event_row ev[RD_H5_BUF];
};

static const char *const status_names[] = {"done", "overturned", "interrupted", "unstable",
                                           "io_error", "error"};

/* ---- attributes ---- */

/* Create (or replace) attribute name on loc: scalar if n == 0, else a 1-D array of n. */
static int attr_write(const rd_h5 *h, hid_t loc, const char *name, hid_t type, hsize_t n,
                      const void *data, rd_error *err)
{
    hid_t space = n ? H5Screate_simple(1, &n, NULL) : H5Screate(H5S_SCALAR);
    hid_t a = H5I_INVALID_HID;
    int ok = space >= 0;
    if (ok && H5Aexists(loc, name) > 0) ok = H5Adelete(loc, name) >= 0;
    if (ok) a = H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    ok = ok && a >= 0 && H5Awrite(a, type, data) >= 0;
    if (a >= 0) H5Aclose(a);
    if (space >= 0) H5Sclose(space);
    return ok ? 0 : rd_error_set(err, "%s: cannot write attribute '%s'", h->path, name);
}

static int attr_str(const rd_h5 *h, hid_t loc, const char *name, const char *value,
                    rd_error *err)
{
    const char *v = value ? value : "";
    return attr_write(h, loc, name, h->str_type, 0, &v, err);
}

static int attr_double(const rd_h5 *h, hid_t loc, const char *name, double value, rd_error *err)
{
    return attr_write(h, loc, name, H5T_NATIVE_DOUBLE, 0, &value, err);
}

static int attr_int(const rd_h5 *h, hid_t loc, const char *name, int value, rd_error *err)
{
    return attr_write(h, loc, name, H5T_NATIVE_INT, 0, &value, err);
}

/* ---- file creation ---- */

static int make_group(const rd_h5 *h, const char *name, rd_error *err)
{
    hid_t g = H5Gcreate2(h->file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) return rd_error_set(err, "%s: cannot create group '%s'", h->path, name);
    H5Gclose(g);
    return 0;
}

static int write_root_attrs(const rd_h5 *h, const rd_h5_meta *m, rd_error *err)
{
    hid_t r = h->file;
    const double deg = 180.0 / 3.14159265358979323846; /* degrees per radian */
    return attr_str(h, r, "program", "rockdem", err) ||
           attr_str(h, r, "version", RD_VERSION, err) ||
           attr_str(h, r, "scenario", m->scenario_text, err) ||
           attr_str(h, r, "scenario_file", m->scenario_file, err) ||
           attr_str(h, r, "title", m->title, err) ||
           attr_double(h, r, "dt", m->dt, err) ||
           attr_double(h, r, "dt_critical", m->dt_critical, err) ||
           attr_str(h, r, "damping", m->damping, err) ||
           attr_str(h, r, "overturn_criterion", m->overturn_criterion, err) ||
           attr_double(h, r, "kn", m->kn, err) ||
           attr_double(h, r, "ks", m->ks, err) ||
           attr_double(h, r, "friction_deg", m->friction * deg, err) ||
           attr_double(h, r, "cohesion", m->cohesion, err) ||
           attr_double(h, r, "tension", m->tension, err) ||
           attr_double(h, r, "spacing", m->spacing, err) ? -1 : 0;
}

/* Small contiguous [n][3] dataset under loc (n may be 0). */
static int write_table3(const rd_h5 *h, hid_t loc, const char *name, hid_t ftype, hid_t mtype,
                        int n, const void *data, const char *units, rd_error *err)
{
    hsize_t dims[2] = {(hsize_t)n, 3};
    hid_t space = H5Screate_simple(2, dims, NULL);
    hid_t d = space >= 0 ? H5Dcreate2(loc, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT,
                                      H5P_DEFAULT)
                         : H5I_INVALID_HID;
    int ok = d >= 0 && (n == 0 || H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0);
    if (space >= 0) H5Sclose(space);
    if (!ok) {
        if (d >= 0) H5Dclose(d);
        return rd_error_set(err, "%s: cannot write dataset '%s'", h->path, name);
    }
    int rc = units ? attr_str(h, d, "units", units, err) : 0;
    H5Dclose(d);
    return rc;
}

static int write_body(const rd_h5 *h, const rd_h5_body *b, rd_error *err)
{
    char path[RD_NAME_MAX + 16];
    snprintf(path, sizeof path, "/bodies/%s", b->name);
    hid_t g = H5Gcreate2(h->file, path, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) return rd_error_set(err, "%s: cannot create group '%s'", h->path, path);
    int rc = attr_double(h, g, "mass", b->mass, err) ||
             attr_write(h, g, "inertia_principal", H5T_NATIVE_DOUBLE, 3, b->inertia, err) ||
             attr_write(h, g, "size", H5T_NATIVE_DOUBLE, 3, b->size, err) ||
             attr_double(h, g, "alpha", b->alpha, err) ||
             attr_int(h, g, "fixed", 0, err) ||
             write_table3(h, g, "vertices", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, b->nvert,
                          b->vertices, "m", err) ||
             write_table3(h, g, "faces", H5T_STD_I32LE, H5T_NATIVE_INT, b->ntri, b->triangles,
                          NULL, err) ? -1 : 0;
    H5Gclose(g);
    return rc;
}

/* 1..RD_MAX_BODIES bodies, named as HDF5 groups can be and short enough for rd_body_summary. */
static int check_names(const char *path, const rd_h5_meta *m, rd_error *err)
{
    if (m->nbodies < 1 || m->nbodies > RD_MAX_BODIES)
        return rd_error_set(err, "%s: %d free bodies (1 to %d can be written)", path,
                            m->nbodies, RD_MAX_BODIES);
    for (int i = 0; i < m->nbodies; i++) {
        const char *n = m->bodies[i].name;
        if (!n || !n[0] || strlen(n) >= RD_NAME_MAX || strchr(n, '/') || !strcmp(n, ".") ||
            !strcmp(n, ".."))
            return rd_error_set(err, "%s: invalid body name '%s'", path, n ? n : "");
    }
    return 0;
}

static int write_bodies(rd_h5 *h, const rd_h5_meta *m, rd_error *err)
{
    if (make_group(h, "/bodies", err)) return -1;
    for (int i = 0; i < h->nb; i++) {
        strncpy(h->names[i], m->bodies[i].name, RD_NAME_MAX);
        if (write_body(h, &m->bodies[i], err)) return -1;
    }
    hsize_t n = (hsize_t)h->nb;
    hid_t t = H5Tcopy(H5T_C_S1);
    hid_t space = H5Screate_simple(1, &n, NULL);
    hid_t d = H5I_INVALID_HID;
    int ok = t >= 0 && space >= 0 && H5Tset_size(t, RD_NAME_MAX) >= 0;
    if (ok) d = H5Dcreate2(h->file, "/bodies/names", t, space, H5P_DEFAULT, H5P_DEFAULT,
                           H5P_DEFAULT);
    ok = ok && d >= 0 && H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, h->names) >= 0;
    if (d >= 0) H5Dclose(d);
    if (space >= 0) H5Sclose(space);
    if (t >= 0) H5Tclose(t);
    return ok ? 0 : rd_error_set(err, "%s: cannot write /bodies/names", h->path);
}

static int series_create(rd_h5 *h, rd_h5_series *s, const rd_h5_series_spec *sp,
                         rd_error *err)
{
    hsize_t maxd[3] = {H5S_UNLIMITED, 0, 0}, chunk[3] = {RD_H5_BUF, 0, 0};
    int r = 1;
    if (sp->per_body) s->dims[r++] = (hsize_t)h->nb;
    if (sp->inner) s->dims[r++] = sp->inner;
    s->rank = r;
    s->width = 1;
    for (int k = 1; k < r; k++) {
        maxd[k] = chunk[k] = s->dims[k];
        s->width *= (size_t)s->dims[k];
    }
    snprintf(s->name, sizeof s->name, "%s", sp->name);
    s->buf = malloc(RD_H5_BUF * s->width * sizeof *s->buf);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    hid_t space = H5Screate_simple(r, s->dims, maxd);
    int ok = s->buf && dcpl >= 0 && space >= 0 && H5Pset_chunk(dcpl, r, chunk) >= 0 &&
             H5Pset_shuffle(dcpl) >= 0 && H5Pset_deflate(dcpl, RD_H5_DEFLATE) >= 0;
    if (ok) s->dset = H5Dcreate2(h->file, s->name, H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl,
                                 H5P_DEFAULT);
    if (space >= 0) H5Sclose(space);
    if (dcpl >= 0) H5Pclose(dcpl);
    if (!ok || s->dset < 0)
        return rd_error_set(err, "%s: cannot create dataset '%s'", h->path, s->name);
    return attr_str(h, s->dset, "units", sp->units, err);
}

static int create_series(rd_h5 *h, rd_error *err)
{
    if (make_group(h, "/ground", err) || make_group(h, "/energy", err)) return -1;
    for (int i = 0; i < SER_COUNT; i++) {
        char name[RD_H5_SERNAME];
        rd_h5_series_spec sp = {name, 0, 0, "J"};
        if (i < SER_ENERGY) sp = series_spec[i];
        else snprintf(name, sizeof name, "energy/%s", rd_energy_names[i - SER_ENERGY]);
        if (series_create(h, &h->ser[i], &sp, err)) return -1;
    }
    return 0;
}

static int create_events(rd_h5 *h, rd_error *err)
{
    hsize_t dims = 0, maxd = H5S_UNLIMITED, chunk = RD_H5_BUF;
    hid_t str = H5Tcopy(H5T_C_S1);
    hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(rd_h5_event_row));
    int ok = str >= 0 && t >= 0 && H5Tset_size(str, RD_H5_EVTYPE) >= 0 &&
             H5Tinsert(t, "time", offsetof(rd_h5_event_row, time), H5T_NATIVE_DOUBLE) >= 0 &&
             H5Tinsert(t, "body", offsetof(rd_h5_event_row, body), H5T_NATIVE_INT) >= 0 &&
             H5Tinsert(t, "type", offsetof(rd_h5_event_row, type), str) >= 0 &&
             H5Tinsert(t, "value", offsetof(rd_h5_event_row, value), H5T_NATIVE_DOUBLE) >= 0;
    h->ev_mem_type = t;
    hid_t ft = ok ? H5Tcopy(t) : H5I_INVALID_HID; /* on disk: same fields, no padding */
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    hid_t space = H5Screate_simple(1, &dims, &maxd);
    ok = ok && ft >= 0 && H5Tpack(ft) >= 0 && dcpl >= 0 && space >= 0 &&
         H5Pset_chunk(dcpl, 1, &chunk) >= 0 && H5Pset_shuffle(dcpl) >= 0 &&
         H5Pset_deflate(dcpl, RD_H5_DEFLATE) >= 0;
    if (ok) h->ev_dset = H5Dcreate2(h->file, "/events", ft, space, H5P_DEFAULT, dcpl,
                                    H5P_DEFAULT);
    if (space >= 0) H5Sclose(space);
    if (dcpl >= 0) H5Pclose(dcpl);
    if (ft >= 0) H5Tclose(ft);
    if (str >= 0) H5Tclose(str);
    if (!ok || h->ev_dset < 0) return rd_error_set(err, "%s: cannot create /events", h->path);
    return attr_str(h, h->ev_dset, "units", "time: s; value: depends on type", err);
}

/* Release everything without writing. */
static void destroy(rd_h5 *h)
{
    for (int i = 0; i < SER_COUNT; i++) {
        if (h->ser[i].dset >= 0) H5Dclose(h->ser[i].dset);
        free(h->ser[i].buf);
    }
    if (h->ev_dset >= 0) H5Dclose(h->ev_dset);
    if (h->ev_mem_type >= 0) H5Tclose(h->ev_mem_type);
    if (h->str_type >= 0) H5Tclose(h->str_type);
    if (h->file >= 0) H5Fclose(h->file);
    free(h->names);
    free(h->path);
    free(h);
}

static rd_h5 *alloc_handle(const char *path, int nb)
{
    rd_h5 *h = calloc(1, sizeof *h);
    if (!h) return NULL;
    h->file = h->str_type = h->ev_dset = h->ev_mem_type = H5I_INVALID_HID;
    for (int i = 0; i < SER_COUNT; i++) h->ser[i].dset = H5I_INVALID_HID;
    h->nb = nb;
    h->path = strdup(path);
    h->names = calloc((size_t)nb, sizeof *h->names);
    if (h->path && h->names) return h;
    destroy(h);
    return NULL;
}

static rd_h5 *h5_open(const char *path, const rd_h5_meta *meta, rd_error *err)
{
    if (check_names(path, meta, err)) return NULL;
    rd_h5 *h = alloc_handle(path, meta->nbodies);
    if (!h) {
        rd_error_set(err, "%s: out of memory", path);
        return NULL;
    }
    h->file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (h->file < 0) {
        rd_error_set(err, "%s: cannot create file", path);
        destroy(h);
        return NULL;
    }
    h->str_type = H5Tcopy(H5T_C_S1);
    if (h->str_type < 0 || H5Tset_size(h->str_type, H5T_VARIABLE) < 0 ||
        H5Tset_cset(h->str_type, H5T_CSET_UTF8) < 0) {
        rd_error_set(err, "%s: cannot create string type", path);
        destroy(h);
        return NULL;
    }
    if (write_root_attrs(h, meta, err) || write_bodies(h, meta, err) || create_series(h, err) ||
        create_events(h, err) || rd_h5_flush(h, err)) {
        destroy(h);
        return NULL;
    }
    return h;
}

/* ---- appending ---- */

/* Copy one sample's values into row nbuf of a series buffer; a NULL source writes NaN. */
static void put(rd_h5_series *s, int row, const double *src)
{
    double *dst = s->buf + (size_t)row * s->width;
    if (src) {
        memcpy(dst, src, s->width * sizeof *dst);
        return;
    }
    for (size_t k = 0; k < s->width; k++) dst[k] = NAN;
}

static int h5_append(rd_h5 *h, const rd_h5_sample *s, rd_error *err)
{
    int r = h->nbuf;
    put(&h->ser[SER_TIME], r, &s->time);
    put(&h->ser[SER_POSITION], r, s->position);
    put(&h->ser[SER_QUATERNION], r, s->quaternion);
    put(&h->ser[SER_VELOCITY], r, s->velocity);
    put(&h->ser[SER_ANGULAR_VELOCITY], r, s->angular_velocity);
    put(&h->ser[SER_TILT], r, s->tilt);
    put(&h->ser[SER_ROTATION], r, s->rotation);
    put(&h->ser[SER_GROUND_ACC], r, s->ground_acc);
    put(&h->ser[SER_GROUND_VEL], r, s->ground_vel);
    put(&h->ser[SER_GROUND_DISP], r, s->ground_disp);
    for (int e = 0; e < RD_NENERGY; e++) put(&h->ser[SER_ENERGY + e], r, &s->energy[e]);
    h->nbuf++;
    return h->nbuf == RD_H5_BUF ? rd_h5_flush(h, err) : 0;
}

static int h5_event(rd_h5 *h, double time, int body, const char *type, double value, rd_error *err)
{
    if (body < -1 || body >= h->nb)
        return rd_error_set(err, "%s: event body index %d out of range", h->path, body);
    rd_h5_event_row *e = &h->ev[h->nev++];
    memset(e, 0, sizeof *e);
    e->time = time;
    e->body = body;
    snprintf(e->type, sizeof e->type, "%s", type ? type : "");
    e->value = value;
    return h->nev == RD_H5_BUF ? rd_h5_flush(h, err) : 0;
}

/* Append n rows from buf to an extendible dataset whose first dimension is *written. */
static int extend_write(hid_t d, hid_t mtype, int rank, hsize_t *dims, hsize_t n,
                        const void *buf)
{
    hsize_t start[3] = {dims[0], 0, 0}, count[3] = {n, 0, 0}, grown[3] = {dims[0] + n, 0, 0};
    for (int k = 1; k < rank; k++) count[k] = grown[k] = dims[k];
    if (H5Dset_extent(d, grown) < 0) return -1;
    hid_t fs = H5Dget_space(d);
    hid_t ms = H5Screate_simple(rank, count, NULL);
    int ok = fs >= 0 && ms >= 0 &&
             H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 &&
             H5Dwrite(d, mtype, ms, fs, H5P_DEFAULT, buf) >= 0;
    if (ms >= 0) H5Sclose(ms);
    if (fs >= 0) H5Sclose(fs);
    if (ok) dims[0] += n;
    return ok ? 0 : -1;
}

static int h5_flush(rd_h5 *h, rd_error *err)
{
    int n = h->nbuf, nev = h->nev;
    h->nbuf = h->nev = 0; /* a failed write is not retried: it would duplicate rows */
    for (int i = 0; n > 0 && i < SER_COUNT; i++) {
        rd_h5_series *s = &h->ser[i];
        if (extend_write(s->dset, H5T_NATIVE_DOUBLE, s->rank, s->dims, (hsize_t)n, s->buf))
            return rd_error_set(err, "%s: cannot write '%s'", h->path, s->name);
    }
    if (nev > 0 && extend_write(h->ev_dset, h->ev_mem_type, 1, &h->ev_written, (hsize_t)nev,
                                h->ev))
        return rd_error_set(err, "%s: cannot write /events", h->path);
    if (H5Fflush(h->file, H5F_SCOPE_GLOBAL) < 0)
        return rd_error_set(err, "%s: cannot flush file", h->path);
    return 0;
}

/* ---- summary ---- */

typedef struct rd_h5_body_field {
    const char *name;
    size_t offset; /* in rd_body_summary */
    int is_int;
} rd_h5_body_field;

static const rd_h5_body_field body_fields[] = {
    {"overturned", offsetof(rd_body_summary, overturned), 1},
    {"overturn_time", offsetof(rd_body_summary, overturn_time), 0},
    {"max_tilt", offsetof(rd_body_summary, max_tilt), 0},
    {"alpha", offsetof(rd_body_summary, alpha), 0},
    {"max_tilt_ratio", offsetof(rd_body_summary, max_tilt_ratio), 0},
    {"max_slide", offsetof(rd_body_summary, max_slide), 0},
    {"final_slide", offsetof(rd_body_summary, final_slide), 0},
    {"uplifted", offsetof(rd_body_summary, uplifted), 1},
    {"slid", offsetof(rd_body_summary, slid), 1},
    {"max_rocking_in_plane", offsetof(rd_body_summary, max_rocking_in), 0},
    {"max_rocking_out_of_plane", offsetof(rd_body_summary, max_rocking_out), 0},
    {"max_twist", offsetof(rd_body_summary, max_twist), 0},
    {"final_twist", offsetof(rd_body_summary, final_twist), 0},
    {"alpha_min", offsetof(rd_body_summary, alpha_min), 0},
    {"alpha_min_direction", offsetof(rd_body_summary, alpha_min_direction), 0},
    {"tip_accel_min", offsetof(rd_body_summary, tip_accel_min), 0},
};

static int h5_precariousness(rd_h5 *h, const char *body, const double *table, int n, rd_error *err)
{
    char path[RD_NAME_MAX + 16];
    snprintf(path, sizeof path, "/bodies/%s", body);
    hid_t g = H5Gopen2(h->file, path, H5P_DEFAULT);
    if (g < 0) return rd_error_set(err, "%s: no group '%s'", h->path, path);
    if (H5Lexists(g, "precariousness", H5P_DEFAULT) > 0) H5Ldelete(g, "precariousness", H5P_DEFAULT);
    int rc = write_table3(h, g, "precariousness", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, n, table,
                          "rad, rad, m/s^2", err);
    H5Gclose(g);
    return rc;
}

/* order[i] = index in s->body of the body written as /bodies/names[i]. */
static int summary_order(const rd_h5 *h, const rd_summary *s, int *order, rd_error *err)
{
    if (s->nbodies != h->nb)
        return rd_error_set(err, "%s: summary has %d bodies, file has %d", h->path, s->nbodies,
                            h->nb);
    for (int i = 0; i < h->nb; i++) {
        order[i] = -1;
        for (int j = 0; j < s->nbodies && order[i] < 0; j++)
            if (!strncmp(s->body[j].name, h->names[i], RD_NAME_MAX)) order[i] = j;
        if (order[i] < 0)
            return rd_error_set(err, "%s: summary lacks body '%s'", h->path, h->names[i]);
    }
    return 0;
}

static int write_body_fields(const rd_h5 *h, hid_t g, const rd_summary *s, const int *order,
                             rd_error *err)
{
    double d[RD_MAX_BODIES];
    int n[RD_MAX_BODIES];
    size_t nf = sizeof body_fields / sizeof body_fields[0];
    for (size_t f = 0; f < nf; f++) {
        const rd_h5_body_field *bf = &body_fields[f];
        for (int i = 0; i < h->nb; i++) {
            const char *p = (const char *)&s->body[order[i]] + bf->offset;
            if (bf->is_int) memcpy(&n[i], p, sizeof n[i]);
            else memcpy(&d[i], p, sizeof d[i]);
        }
        if (attr_write(h, g, bf->name, bf->is_int ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE,
                       (hsize_t)h->nb, bf->is_int ? (const void *)n : (const void *)d, err))
            return -1;
    }
    return 0;
}

static int write_summary_attrs(const rd_h5 *h, hid_t g, const rd_summary *s, rd_error *err)
{
    unsigned st = (unsigned)s->status;
    const char *status = st < sizeof status_names / sizeof status_names[0] ? status_names[st]
                                                                            : "unknown";
    long steps = s->steps;
    return attr_str(h, g, "status", status, err) ||
           attr_int(h, g, "any_overturned", s->any_overturned, err) ||
           attr_double(h, g, "end_time", s->end_time, err) ||
           attr_double(h, g, "dt", s->dt, err) ||
           attr_double(h, g, "dt_critical", s->dt_critical, err) ||
           attr_write(h, g, "steps", H5T_NATIVE_LONG, 0, &steps, err) ||
           attr_double(h, g, "settle_time", s->settle_time, err) ||
           attr_double(h, g, "energy_residual_max", s->energy_residual_max, err) ||
           attr_double(h, g, "wall_seconds", s->wall_seconds, err) ? -1 : 0;
}

static int h5_summary(rd_h5 *h, const rd_summary *s, rd_error *err)
{
    int order[RD_MAX_BODIES];
    if (summary_order(h, s, order, err)) return -1;
    htri_t exists = H5Lexists(h->file, "/summary", H5P_DEFAULT);
    hid_t g = exists > 0 ? H5Gopen2(h->file, "/summary", H5P_DEFAULT)
                         : H5Gcreate2(h->file, "/summary", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) return rd_error_set(err, "%s: cannot create group '/summary'", h->path);
    int rc = write_summary_attrs(h, g, s, err) || write_body_fields(h, g, s, order, err) ? -1 : 0;
    H5Gclose(g);
    if (!rc && H5Fflush(h->file, H5F_SCOPE_GLOBAL) < 0)
        rc = rd_error_set(err, "%s: cannot flush file", h->path);
    return rc;
}

static void h5_close(rd_h5 *h)
{
    if (!h) return;
    rd_error ignored;
    rd_h5_flush(h, &ignored);
    destroy(h);
}

/* ---- intensity measures of the applied ground motion ---- */

/* Attributes "<c>_pga", ... of one applied component c on the open group g. */
static int write_component_im(const rd_h5 *h, hid_t g, const rd_motion_def *m, int c, rd_error *err)
{
    const char *cn = rd_motion_component_name(c);
    const rd_record *r = m->record[c].applied;
    rd_im im;
    double sa[2];
    if (rd_motion_im(m, c, &im, sa, err)) return -1;
    const struct { const char *key; double v; } f[] = {
        {"pga", im.pga}, {"pgv", im.pgv}, {"pgd", im.pgd}, {"pgv_pga", im.pgv_pga},
        {"arias", im.arias}, {"d5_95", im.d5_95}, {"sa_0.2s", sa[0]}, {"sa_1s", sa[1]},
        {"dt", r->dt}, {"duration", rd_record_duration(r)}};
    char name[64];
    for (size_t i = 0; i < sizeof f / sizeof f[0]; i++) {
        snprintf(name, sizeof name, "%s_%s", cn, f[i].key);
        if (attr_double(h, g, name, f[i].v, err)) return -1;
    }
    snprintf(name, sizeof name, "%s_record", cn);
    if (attr_str(h, g, name, r->name, err)) return -1;
    snprintf(name, sizeof name, "%s_source", cn);
    return attr_str(h, g, name, r->source, err);
}

static int h5_ground_im(rd_h5 *h, const rd_motion_def *m, rd_error *err)
{
    if (!rd_motion_has_records(m)) return 0;
    hid_t g = H5Gopen2(h->file, "/ground", H5P_DEFAULT);
    if (g < 0) return rd_error_set(err, "%s: cannot open group '/ground'", h->path);
    int rc = attr_double(h, g, "direction", m->direction, err) ||
             attr_double(h, g, "scale_factor", m->factor, err) ||
             attr_int(h, g, "baseline_degree", m->baseline, err) ? -1 : 0;
    for (int c = 0; c < RD_NCOMPONENTS && !rc; c++)
        if (m->record[c].applied) rc = write_component_im(h, g, m, c, err);
    H5Gclose(g);
    return rc;
}

/* ---- the entry points: HDF5 error printing off around each (io/h5_quiet.h) ---- */

rd_h5 *rd_h5_open(const char *path, const rd_h5_meta *meta, rd_error *err)
{
    rd_h5_quiet q = rd_h5_quiet_begin();
    rd_h5 *r = h5_open(path, meta, err);
    rd_h5_quiet_end(q);
    return r;
}

int rd_h5_append(rd_h5 *h, const rd_h5_sample *s, rd_error *err)
{
    rd_h5_quiet q = rd_h5_quiet_begin();
    int r = h5_append(h, s, err);
    rd_h5_quiet_end(q);
    return r;
}

int rd_h5_event(rd_h5 *h, double time, int body, const char *type, double value, rd_error *err)
{
    rd_h5_quiet q = rd_h5_quiet_begin();
    int r = h5_event(h, time, body, type, value, err);
    rd_h5_quiet_end(q);
    return r;
}

int rd_h5_flush(rd_h5 *h, rd_error *err)
{
    rd_h5_quiet q = rd_h5_quiet_begin();
    int r = h5_flush(h, err);
    rd_h5_quiet_end(q);
    return r;
}

int rd_h5_precariousness(rd_h5 *h, const char *body, const double *table, int n, rd_error *err)
{
    rd_h5_quiet q = rd_h5_quiet_begin();
    int r = h5_precariousness(h, body, table, n, err);
    rd_h5_quiet_end(q);
    return r;
}

int rd_h5_summary(rd_h5 *h, const rd_summary *s, rd_error *err)
{
    rd_h5_quiet q = rd_h5_quiet_begin();
    int r = h5_summary(h, s, err);
    rd_h5_quiet_end(q);
    return r;
}

void rd_h5_close(rd_h5 *h)
{
    rd_h5_quiet q = rd_h5_quiet_begin();
    h5_close(h);
    rd_h5_quiet_end(q);
}

int rd_h5_ground_im(rd_h5 *h, const rd_motion_def *m, rd_error *err)
{
    rd_h5_quiet q = rd_h5_quiet_begin();
    int r = h5_ground_im(h, m, err);
    rd_h5_quiet_end(q);
    return r;
}
