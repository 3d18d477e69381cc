/* rockdem — HDF5 writer (layout in io_hdf5.h and docs/HDF5-LAYOUT.md).
 *
 * Every per-sample series is a chunked, shuffle + deflate compressed dataset whose first
 * dimension is unlimited. Samples and events are buffered (RD_H5_BUF rows) and, when a buffer
 * fills or on rd_h5_flush, appended with H5Dset_extent + H5Dwrite and followed by H5Fflush, so
 * the file on disk is valid and holds every flushed sample even if the process dies. The file
 * uses the default (earliest) format, which has no "open for writing" flag to clear afterwards.
 *
 * Faults (disk full, a file-size limit, the file or its directory removed): before each batch
 * of writes the file is extended by posix_fallocate by more than the batch can need (reserve),
 * so running out of space fails there, before HDF5 has written anything; after each flush the
 * file is truncated back to the end of HDF5's allocation (flush_file). On such a failure the writer stops writing: the
 * root attributes `status` and `status_message`, created at open at their largest, are
 * overwritten in place ("io_error" and the reason with the system's errno text), which needs
 * no new space, and the file keeps every sample flushed before the fault. Until a run ends the
 * root `status` reads "running" (a file left by a killed process says so).
 *
 * Folder io/ owns the HDF5 output file; it may call base/ and the public headers, never engine/
 * internals or cli/.
 *
 * The file describes itself the netCDF-4 way (so xarray and h5netcdf read it with named
 * dimensions): every axis of a dataset has an HDF5 dimension scale (H5DS, hdf5_hl) — /time,
 * /body, /xyz, ... —, every dataset carries `units` (where it has any) and `long_name`, every
 * attribute with units has a companion `<name>_units` attribute, strings are variable-length
 * UTF-8 and enumerations (run status, event type, spacing rule) are HDF5 enums.
 */
#include "io/io_hdf5.h"
#include "io/io_bodies.h"
#include "io/io_table.h"
#include "io/h5_quiet.h"
#include "base/fault.h"
#include "base/path.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define RD_H5_BUF           256 /* rows buffered between writes; also the chunk length in time */
#define RD_H5_DEFLATE       4   /* deflate level */
#define RD_H5_SERNAME       48  /* bytes of a series path */
/* layout_version: 3 = /bodies as tables over `block`; 2 = dimension scales, enums, /events */
#define RD_H5_LAYOUT        3
#define RD_H5_STATUS        16  /* bytes of the root `status` attribute, NUL included */
#define RD_H5_STATUS_MSG    512 /* bytes of the root `status_message` attribute */
/* Space reserved before each batch of writes: the batch's raw size plus an eighth (shuffle keeps
 * the size; deflate expands incompressible data by at most 0.03 % + 13 bytes per chunk, zlib's
 * deflateBound) plus 64 KiB for metadata (attributes, chunk-index B-tree nodes of every
 * dataset, object-header and heap updates). */
#define RD_H5_RESERVE_FIXED (64 << 10)
/* Bytes one event can take on disk (its columns, 25 bytes, and its body name in the global
 * heap of variable-length strings, with the heap's per-object overhead), generously. */
#define RD_H5_EVENT_BYTES   128

const char *const rd_energy_names[RD_NENERGY] = { "kinetic", "gravitational", "elastic", "friction",
                                                  "damping", "ground_work",   "residual" };

static const char *const energy_long_names[RD_NENERGY] = {
    "kinetic energy (ground frame), leapfrog's 1/2 m v(n-1/2).v(n+1/2)",
    "gravitational potential energy",
    "elastic energy stored in the contact springs",
    "energy dissipated by friction (cumulative)",
    "energy dissipated by damping (cumulative)",
    "work done by the ground motion (cumulative)",
    "energy balance residual"
};

/* Event types, in the order of the HDF5 enum /events/type (value = index). */
static const char *const event_types[] = { "uplift",   "impact",    "slip", "overturn", "recover",
                                           "unstable", "unsettled", "rest", "lock",     "liftoff",
                                           "lost",     "peak",      "left", "fence" };
#define RD_H5_NEVTYPES ((int)(sizeof event_types / sizeof event_types[0]))

#define RD_H5_NSTATUS (RD_STATUS_UNTRUSTED + 1) /* run statuses, named by rd_status_name */

/* How subcontact points were spaced (root attribute spacing_rule). */
static const char *const spacing_rules[] = { "auto", "vertices", "fixed" };

/* Dimension scales at the root: name, labels, long name. /time and /body are made elsewhere. */
typedef enum { DIM_NONE = -1, DIM_XYZ, DIM_WXYZ, DIM_ROTATION, DIM_CORNER, DIM_COUNT } rd_h5_dim;

typedef struct rd_h5_dim_spec {
    const char *name;
    int n;
    const char *labels[4];
    const char *long_name;
} rd_h5_dim_spec;

static const rd_h5_dim_spec dim_spec[DIM_COUNT] = {
    { "xyz", 3, { "x", "y", "z" }, "Cartesian component, ground frame (z up)" },
    { "wxyz", 4, { "w", "x", "y", "z" }, "quaternion component (scalar first)" },
    { "rotation_part",
      3,
      { "in_plane", "out_of_plane", "twist" },
      "part of the rotation from rest: in-plane rocking, out-of-plane rocking, twist" },
    { "corner", 3, { "0", "1", "2" }, "corner of a triangle" },
};

/* Per-sample series, in rd_h5_sample order; energies follow. */
enum {
    SER_TIME,
    SER_POSITION,
    SER_QUATERNION,
    SER_VELOCITY,
    SER_ANGULAR_VELOCITY,
    SER_TILT,
    SER_ROTATION,
    SER_GROUND_ACC,
    SER_GROUND_VEL,
    SER_GROUND_DISP,
    SER_ENERGY,
    SER_COUNT = SER_ENERGY + RD_NENERGY
};

typedef struct rd_h5_series_spec {
    const char *name;
    int per_body;    /* 1: one row per free body */
    rd_h5_dim inner; /* dimension of the components per body or sample, DIM_NONE for a scalar */
    const char *units;
    const char *long_name;
} rd_h5_series_spec;

static const rd_h5_series_spec series_spec[SER_ENERGY] = {
    { "time", 0, DIM_NONE, "s", "time since the shaking started" },
    { "position", 1, DIM_XYZ, "m", "centre of mass, ground frame" },
    { "quaternion", 1, DIM_WXYZ, "1", "orientation, body to ground frame" },
    { "velocity", 1, DIM_XYZ, "m/s", "velocity of the centre of mass relative to the ground" },
    { "angular_velocity", 1, DIM_XYZ, "rad/s", "angular velocity, ground frame" },
    { "tilt", 1, DIM_NONE, "rad", "angle of the body's rest vertical axis from the vertical" },
    { "rotation", 1, DIM_ROTATION, "rad",
      "rotation from rest: in-plane rocking, out-of-plane "
      "rocking, twist about the vertical (unwrapped)" },
    { "ground/acceleration", 0, DIM_XYZ, "m/s^2", "ground acceleration as applied" },
    { "ground/velocity", 0, DIM_XYZ, "m/s", "ground velocity" },
    { "ground/displacement", 0, DIM_XYZ, "m", "ground displacement" },
};

typedef struct rd_h5_series {
    char name[RD_H5_SERNAME];
    hid_t dset;
    int rank;
    hsize_t dims[3]; /* dims[0]: samples on disk; the rest: shape of one sample */
    size_t width;    /* doubles per sample */
    double *buf;     /* [RD_H5_BUF][width] */
} rd_h5_series;

/* /events columns, in the order of the datasets of the group. */
enum { EV_INDEX, EV_TIME, EV_BODY, EV_BODY_INDEX, EV_TYPE, EV_VALUE, EV_COUNT };

typedef struct rd_h5_event_buf {
    int index[RD_H5_BUF];
    double time[RD_H5_BUF];        /* s */
    const char *body[RD_H5_BUF];   /* body name ("" for the whole scene) */
    int body_index[RD_H5_BUF];     /* index into /body, -1 = the whole scene */
    unsigned char type[RD_H5_BUF]; /* index into event_types */
    double value[RD_H5_BUF];
} rd_h5_event_buf;

struct rd_h5 {
    char *path;   /* the file written: the output, or a temporary beside target */
    char *target; /* NULL, or the output the temporary replaces at rd_h5_commit */
    hid_t file;
    hid_t str_type;    /* variable-length UTF-8 string */
    hid_t status_type; /* enum of the run statuses */
    hid_t event_type;  /* enum of event_types */
    int nb;
    char (*names)[RD_NAME_MAX]; /* [nb] free bodies in output order */
    const char **name_list;     /* [nb] pointers to names[i], as HDF5 writes a string array */
    rd_h5_series ser[SER_COUNT];
    hid_t dims[DIM_COUNT]; /* root dimension scales */
    hid_t body_dim;        /* /body */
    int nbuf;              /* samples buffered */
    hid_t ev[EV_COUNT];
    hsize_t ev_written;
    int nev; /* events buffered */
    rd_h5_event_buf evb;
    int fd;         /* the file's descriptor (sec2 driver), for reserve() */
    struct stat id; /* device and inode of the file at open: is it still at path? */
    int broken;     /* a write failed: nothing more is written; fault holds why */
    char fault[RD_ERROR_MAX];
};

/* ---- types ---- */

/* An 8-bit HDF5 enum with members names[0..n-1] = 0..n-1. */
static hid_t enum_type(const char *const *names, int n)
{
    hid_t t = H5Tenum_create(H5T_NATIVE_UCHAR);
    for (int i = 0; t >= 0 && i < n; i++) {
        unsigned char v = (unsigned char)i;
        if (H5Tenum_insert(t, names[i], &v) < 0) {
            H5Tclose(t);
            return H5I_INVALID_HID;
        }
    }
    return t;
}

/* ---- faults ---- */

/* Overwrite the root string attribute `name` in place (variable-length UTF-8, value cut to
 * n - 1 bytes). Its global-heap space was reserved when it was created (reserve_status). */
static int overwrite_status(const rd_h5 *h, const char *name, size_t n, const char *value)
{
    char buf[RD_H5_STATUS_MSG] = { 0 };
    snprintf(buf, n < sizeof buf ? n : sizeof buf, "%s", value);
    const char *v = buf;
    hid_t a = H5Aopen(h->file, name, H5P_DEFAULT);
    int ok = a >= 0 && H5Awrite(a, h->str_type, &v) >= 0;
    if (a >= 0) H5Aclose(a);
    return ok ? 0 : -1;
}

/* Flush, then give the unused reserve back (the file ends where HDF5's allocation ends). */
static int flush_file(const rd_h5 *h)
{
    hsize_t used = 0;
    if (H5Fflush(h->file, H5F_SCOPE_GLOBAL) < 0 || H5Fget_filesize(h->file, &used) < 0) return -1;
    return ftruncate(h->fd, (off_t)used) ? -1 : 0;
}

/* Root `status` and `status_message`, written in place and flushed. 0 or -1. */
static int write_status(const rd_h5 *h, const char *status, const char *message)
{
    if (overwrite_status(h, "status", RD_H5_STATUS, status) ||
        overwrite_status(h, "status_message", RD_H5_STATUS_MSG, message))
        return -1;
    return flush_file(h);
}

/* A write failed: "path: what: reason" into err and h->fault; stop writing; record the fault
 * in the file's status. `reason` is the system's text (strerror). Returns -1. */
static int fault(rd_h5 *h, rd_error *err, const char *what, const char *reason)
{
    if (!h->broken) {
        snprintf(h->fault, sizeof h->fault, "%s: %s: %s", h->path, what, reason);
        h->broken = 1;
        write_status(h, "io_error", h->fault);
    }
    return rd_error_set(err, "%s", h->fault);
}

/* An HDF5 write failed: its reason is the errno left by the failed system call (HDF5's sec2
 * driver does not change it afterwards); the caller cleared errno before the writes. */
static int fault_h5(rd_h5 *h, rd_error *err, const char *what)
{
    int e = errno;
    return fault(h, err, what, e ? strerror(e) : "HDF5 library error (no system error)");
}

/* Before a batch of writes of up to `bytes` bytes: the file must still be at its path, and the
 * space must exist (posix_fallocate past the current end). 0, or -1 after fault(). */
static int reserve(rd_h5 *h, size_t bytes, rd_error *err)
{
    if (h->broken) return rd_error_set(err, "%s", h->fault);
    struct stat now;
    if (stat(h->path, &now))
        return fault(h, err, "the file was removed during the run", strerror(errno));
    if (now.st_dev != h->id.st_dev || now.st_ino != h->id.st_ino)
        return fault(h, err, "the file was replaced during the run", "another file is at its path");
    hsize_t used = 0; /* HDF5's end of allocated space: the file beyond it is our reserve */
    if (H5Fget_filesize(h->file, &used) < 0) return fault_h5(h, err, "cannot get the file size");
    int e;
    do e = posix_fallocate(h->fd, (off_t)used, (off_t)(bytes + RD_H5_RESERVE_FIXED));
    while (e == EINTR);
    if (e) {
        char what[96];
        snprintf(what, sizeof what, "cannot extend the file by %zu bytes at %llu bytes",
                 bytes + RD_H5_RESERVE_FIXED, (unsigned long long)used);
        return fault(h, err, what, strerror(e));
    }
    errno = 0;
    return 0;
}

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

static int attr_str(const rd_h5 *h, hid_t loc, const char *name, const char *value, rd_error *err)
{
    const char *v = value ? value : "";
    return attr_write(h, loc, name, h->str_type, 0, &v, err);
}

/* The companion attribute "<name>_units" (none when units is NULL). */
static int attr_units(const rd_h5 *h, hid_t loc, const char *name, const char *units, rd_error *err)
{
    if (!units) return 0;
    char un[96];
    snprintf(un, sizeof un, "%s_units", name);
    return attr_str(h, loc, un, units, err);
}

/* A double attribute and its units ("1" for a ratio, NULL for none). */
static int attr_double(const rd_h5 *h, hid_t loc, const char *name, double value, const char *units,
                       rd_error *err)
{
    return attr_write(h, loc, name, H5T_NATIVE_DOUBLE, 0, &value, err) ||
                   attr_units(h, loc, name, units, err)
               ? -1
               : 0;
}

static int attr_int(const rd_h5 *h, hid_t loc, const char *name, int value, rd_error *err)
{
    return attr_write(h, loc, name, H5T_NATIVE_INT, 0, &value, err);
}

static int attr_enum(const rd_h5 *h, hid_t loc, const char *name, hid_t type, int value,
                     rd_error *err)
{
    unsigned char v = (unsigned char)value;
    return attr_write(h, loc, name, type, 0, &v, err);
}

/* units (may be NULL) and long_name of a dataset. */
static int describe(const rd_h5 *h, hid_t d, const char *units, const char *long_name,
                    rd_error *err)
{
    return (units && attr_str(h, d, "units", units, err)) ||
                   attr_str(h, d, "long_name", long_name, err)
               ? -1
               : 0;
}

/* ---- dimension scales ---- */

/* A 1-D contiguous dataset of n values of type (strings: const char *[n]) made a dimension
 * scale named as the dataset. Returns the open dataset or H5I_INVALID_HID. */
static hid_t scale_create(const rd_h5 *h, hid_t loc, const char *name, hid_t type, hsize_t n,
                          const void *data, const char *long_name, rd_error *err)
{
    hid_t space = H5Screate_simple(1, &n, NULL);
    hid_t d = space >= 0 ? H5Dcreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)
                         : H5I_INVALID_HID;
    int ok = d >= 0 && (n == 0 || H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0) &&
             H5DSset_scale(d, name) >= 0;
    if (space >= 0) H5Sclose(space);
    if (ok && !describe(h, d, NULL, long_name, err)) return d;
    if (d >= 0) H5Dclose(d);
    rd_error_set(err, "%s: cannot write dimension scale '%s'", h->path, name);
    return H5I_INVALID_HID;
}

/* Attach scales[k] to axis k of d (rank axes). */
static int attach(const rd_h5 *h, hid_t d, const hid_t *scales, int rank, const char *what,
                  rd_error *err)
{
    for (int k = 0; k < rank; k++)
        if (H5DSattach_scale(d, scales[k], (unsigned)k) < 0)
            return rd_error_set(err, "%s: cannot attach dimension %d of '%s'", h->path, k, what);
    return 0;
}

static int create_dims(rd_h5 *h, rd_error *err)
{
    for (int i = 0; i < DIM_COUNT; i++) {
        const rd_h5_dim_spec *ds = &dim_spec[i];
        h->dims[i] = scale_create(h, h->file, ds->name, h->str_type, (hsize_t)ds->n, ds->labels,
                                  ds->long_name, err);
        if (h->dims[i] < 0) return -1;
    }
    h->body_dim = scale_create(h, h->file, "body", h->str_type, (hsize_t)h->nb, h->name_list,
                               "free body, in output order", err);
    return h->body_dim < 0 ? -1 : 0;
}

/* ---- file creation ---- */

static int make_group(const rd_h5 *h, const char *name, const char *long_name, rd_error *err)
{
    hid_t g = H5Gcreate2(h->file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) return rd_error_set(err, "%s: cannot create group '%s'", h->path, name);
    int rc = attr_str(h, g, "long_name", long_name, err);
    H5Gclose(g);
    return rc;
}

/* The groups' outside dimension scales (/time, /xyz, /corner, ...) hard-linked into them, so
 * each group opens in a netCDF reader (xarray) with its coordinates (io_table.h). */
static int link_scales(const rd_h5 *h, rd_error *err)
{
    static const char *const groups[] = { "/bodies", "/ground", "/energy" };
    for (size_t k = 0; k < sizeof groups / sizeof groups[0]; k++)
        if (rd_h5t_link_scales(h->file, groups[k], err))
            return rd_error_set(err, "%s: cannot link the dimension scales of %s", h->path,
                                groups[k]);
    return 0;
}

/* spacing < 0: automatic; 0: face vertices only; > 0: a fixed spacing, m. */
static int write_spacing(const rd_h5 *h, double spacing, rd_error *err)
{
    int rule = spacing < 0 ? 0 : spacing == 0 ? 1 : 2;
    hid_t t = enum_type(spacing_rules, 3);
    if (t < 0) return rd_error_set(err, "%s: cannot create enum type", h->path);
    int rc = attr_enum(h, h->file, "spacing_rule", t, rule, err);
    H5Tclose(t);
    if (rc || rule != 2) return rc;
    return attr_double(h, h->file, "spacing", spacing, "m", err);
}

static int write_root_attrs(const rd_h5 *h, const rd_h5_meta *m, rd_error *err)
{
    hid_t r = h->file;
    const double deg = 180.0 / 3.14159265358979323846; /* degrees per radian */
    return attr_str(h, r, "Conventions", "rockdem-3", err) ||
                   attr_int(h, r, "layout_version", RD_H5_LAYOUT, err) ||
                   attr_str(h, r, "program", "rockdem", err) ||
                   attr_str(h, r, "version", RD_VERSION, err) ||
                   attr_str(h, r, "scenario", m->scenario_text, err) ||
                   attr_str(h, r, "scenario_file", m->scenario_file, err) ||
                   attr_str(h, r, "title", m->title, err) ||
                   attr_double(h, r, "dt", m->dt, "s", err) ||
                   attr_double(h, r, "dt_critical", m->dt_critical, "s", err) ||
                   attr_str(h, r, "damping", m->damping, err) ||
                   attr_str(h, r, "overturn_criterion", m->overturn_criterion, err) ||
                   attr_double(h, r, "kn", m->kn, "Pa/m", err) ||
                   attr_double(h, r, "ks", m->ks, "Pa/m", err) ||
                   attr_double(h, r, "friction_deg", m->friction * deg, "degree", err) ||
                   attr_double(h, r, "cohesion", m->cohesion, "Pa", err) ||
                   attr_double(h, r, "tension", m->tension, "Pa", err) ||
                   write_spacing(h, m->spacing, err)
               ? -1
               : 0;
}

static int name_order(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* No two bodies share a name (the rows of /bodies/block are told apart by it): sorted, then
 * neighbours compared, O(n log n) for a 10,000-brick wall. */
static int check_unique(const char *path, const rd_h5_meta *m, rd_error *err)
{
    const size_t nb = (size_t)m->nbodies, n = nb + (size_t)m->nfixed; /* both >= 0: check_names */
    if (n < 2) return 0;
    const char **s = malloc(sizeof *s * n);
    if (!s) return rd_error_set(err, "%s: out of memory", path);
    for (size_t i = 0; i < n; i++) s[i] = i < nb ? m->bodies[i].name : m->fixed_bodies[i - nb].name;
    qsort(s, n, sizeof *s, name_order);
    int rc = 0;
    for (size_t i = 1; i < n && !rc; i++)
        if (!strcmp(s[i - 1], s[i]))
            rc = rd_error_set(err, "%s: two bodies are named '%s'", path, s[i]);
    free(s);
    return rc;
}

/* At least one free body, each named as HDF5 groups can be (/history/body/<name>), short
 * enough for rd_body_summary, and no two alike. */
static int check_names(const char *path, const rd_h5_meta *m, rd_error *err)
{
    if (m->nbodies < 1)
        return rd_error_set(err, "%s: %d free bodies (at least 1 is written)", path, m->nbodies);
    if (m->nfixed < 0) return rd_error_set(err, "%s: %d fixed bodies", path, m->nfixed);
    for (int i = 0; i < m->nbodies + m->nfixed; i++) {
        const char *n = i < m->nbodies ? m->bodies[i].name : m->fixed_bodies[i - m->nbodies].name;
        if (!n || !n[0] || strlen(n) >= RD_NAME_MAX || strchr(n, '/') || !strcmp(n, ".") ||
            !strcmp(n, ".."))
            return rd_error_set(err, "%s: invalid body name '%s'", path, n ? n : "");
    }
    return check_unique(path, m, err);
}

static int write_bodies(const rd_h5 *h, const rd_h5_meta *m, rd_error *err)
{
    return rd_h5_bodies_write(h->file, m, err) ? rd_error_set(err, "%s: %s", h->path, err->msg) : 0;
}

static int series_create(rd_h5 *h, rd_h5_series *s, const rd_h5_series_spec *sp, rd_error *err)
{
    hsize_t maxd[3] = { H5S_UNLIMITED, 0, 0 }, chunk[3] = { RD_H5_BUF, 0, 0 };
    hid_t scales[3] = { h->ser[SER_TIME].dset, 0, 0 };
    int r = 1;
    s->dims[0] = 0;
    if (sp->per_body) {
        scales[r] = h->body_dim;
        s->dims[r++] = (hsize_t)h->nb;
    }
    if (sp->inner != DIM_NONE) {
        scales[r] = h->dims[sp->inner];
        s->dims[r++] = (hsize_t)dim_spec[sp->inner].n;
    }
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
    if (ok)
        s->dset =
            H5Dcreate2(h->file, s->name, H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    if (space >= 0) H5Sclose(space);
    if (dcpl >= 0) H5Pclose(dcpl);
    if (!ok || s->dset < 0)
        return rd_error_set(err, "%s: cannot create dataset '%s'", h->path, s->name);
    if (describe(h, s->dset, sp->units, sp->long_name, err)) return -1;
    if (s == &h->ser[SER_TIME]) /* /time is the time axis of every series */
        return H5DSset_scale(s->dset, "time") < 0
                   ? rd_error_set(err, "%s: cannot make /time a dimension scale", h->path)
                   : 0;
    return attach(h, s->dset, scales, r, s->name, err);
}

static int create_series(rd_h5 *h, rd_error *err)
{
    if (make_group(h, "/ground", "motion of the ground (the shaking table)", err) ||
        make_group(h, "/energy", "energy balance of the free bodies", err))
        return -1;
    for (int i = 0; i < SER_COUNT; i++) {
        char name[RD_H5_SERNAME];
        rd_h5_series_spec sp = { name, 0, DIM_NONE, "J", NULL };
        if (i < SER_ENERGY) {
            sp = series_spec[i];
        } else {
            snprintf(name, sizeof name, "energy/%s", rd_energy_names[i - SER_ENERGY]);
            sp.long_name = energy_long_names[i - SER_ENERGY];
        }
        if (series_create(h, &h->ser[i], &sp, err)) return -1;
    }
    return 0;
}

/* One extendible, chunked 1-D column of /events. */
static hid_t event_column(const rd_h5 *h, hid_t g, const char *name, hid_t type, const char *units,
                          const char *long_name, rd_error *err)
{
    hsize_t dims = 0, maxd = H5S_UNLIMITED, chunk = RD_H5_BUF;
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    hid_t space = H5Screate_simple(1, &dims, &maxd);
    hid_t d = H5I_INVALID_HID;
    if (dcpl >= 0 && space >= 0 && H5Pset_chunk(dcpl, 1, &chunk) >= 0)
        d = H5Dcreate2(g, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    if (space >= 0) H5Sclose(space);
    if (dcpl >= 0) H5Pclose(dcpl);
    if (d >= 0 && !describe(h, d, units, long_name, err)) return d;
    if (d >= 0) H5Dclose(d);
    rd_error_set(err, "%s: cannot create /events/%s", h->path, name);
    return H5I_INVALID_HID;
}

static int create_events(rd_h5 *h, rd_error *err)
{
    if (make_group(h, "/events", "what happened during the run, in time order", err)) return -1;
    hid_t g = H5Gopen2(h->file, "/events", H5P_DEFAULT);
    if (g < 0) return rd_error_set(err, "%s: cannot open /events", h->path);
    static const struct {
        const char *name, *units, *long_name;
    } col[EV_COUNT] = { { "event", NULL, "event number" },
                        { "time", "s", "time of the event" },
                        { "body", NULL, "free body concerned (empty: the whole scene)" },
                        { "body_index", NULL, "index of the body in /body (-1: the whole scene)" },
                        { "type", NULL, "kind of event" },
                        { "value", NULL,
                          "uplift, overturn, recover: tilt (rad); impact: angular speed before "
                          "(rad/s); slip: slide so far (m); unstable: speed (m/s); unsettled: "
                          "force ratio reached (1)" } };
    const hid_t type[EV_COUNT] = { H5T_NATIVE_INT, H5T_IEEE_F64LE, h->str_type,
                                   H5T_NATIVE_INT, h->event_type,  H5T_IEEE_F64LE };
    int rc = 0;
    for (int c = 0; c < EV_COUNT && !rc; c++) {
        h->ev[c] = event_column(h, g, col[c].name, type[c], col[c].units, col[c].long_name, err);
        rc = h->ev[c] < 0 ? -1 : 0;
    }
    if (!rc && H5DSset_scale(h->ev[EV_INDEX], "event") < 0)
        rc = rd_error_set(err, "%s: cannot make /events/event a dimension scale", h->path);
    for (int c = 1; c < EV_COUNT && !rc; c++)
        rc = attach(h, h->ev[c], &h->ev[EV_INDEX], 1, "/events", err);
    H5Gclose(g);
    return rc;
}

/* Close every HDF5 object and the file, without writing. */
static void close_file(rd_h5 *h)
{
    for (int i = 0; i < SER_COUNT; i++)
        if (h->ser[i].dset >= 0) H5Dclose(h->ser[i].dset);
    for (int i = 0; i < EV_COUNT; i++)
        if (h->ev[i] >= 0) H5Dclose(h->ev[i]);
    for (int i = 0; i < DIM_COUNT; i++)
        if (h->dims[i] >= 0) H5Dclose(h->dims[i]);
    if (h->body_dim >= 0) H5Dclose(h->body_dim);
    if (h->event_type >= 0) H5Tclose(h->event_type);
    if (h->status_type >= 0) H5Tclose(h->status_type);
    if (h->str_type >= 0) H5Tclose(h->str_type);
    if (h->file >= 0) H5Fclose(h->file);
    h->file = h->str_type = h->status_type = h->event_type = h->body_dim = H5I_INVALID_HID;
    for (int i = 0; i < SER_COUNT; i++) {
        h->ser[i].dset = H5I_INVALID_HID;
        free(h->ser[i].buf);
        h->ser[i].buf = NULL;
    }
    for (int i = 0; i < EV_COUNT; i++) h->ev[i] = H5I_INVALID_HID;
    for (int i = 0; i < DIM_COUNT; i++) h->dims[i] = H5I_INVALID_HID;
}

/* Release everything without writing. */
static void destroy(rd_h5 *h)
{
    close_file(h);
    free(h->target);
    free(h->names);
    free(h->name_list);
    free(h->path);
    free(h);
}

static rd_h5 *alloc_handle(const char *path, const rd_h5_meta *m)
{
    rd_h5 *h = calloc(1, sizeof *h);
    if (!h) return NULL;
    h->file = h->str_type = h->status_type = h->event_type = h->body_dim = H5I_INVALID_HID;
    for (int i = 0; i < SER_COUNT; i++) h->ser[i].dset = H5I_INVALID_HID;
    for (int i = 0; i < EV_COUNT; i++) h->ev[i] = H5I_INVALID_HID;
    for (int i = 0; i < DIM_COUNT; i++) h->dims[i] = H5I_INVALID_HID;
    h->nb = m->nbodies;
    h->path = strdup(path);
    h->target = m->target ? strdup(m->target) : NULL;
    h->names = calloc((size_t)h->nb, sizeof *h->names);
    h->name_list = calloc((size_t)h->nb, sizeof *h->name_list);
    if (!h->path || !h->names || !h->name_list || (m->target && !h->target)) {
        destroy(h);
        return NULL;
    }
    for (int i = 0; i < h->nb; i++) {
        snprintf(h->names[i], RD_NAME_MAX, "%s", m->bodies[i].name);
        h->name_list[i] = h->names[i];
    }
    return h;
}

/* The string and enum types every writer uses. 0 or -1. */
static int make_types(rd_h5 *h)
{
    h->str_type = H5Tcopy(H5T_C_S1);
    const char *status_names[RD_H5_NSTATUS];
    for (int i = 0; i < RD_H5_NSTATUS; i++) status_names[i] = rd_status_name((rd_status)i);
    h->status_type = enum_type(status_names, RD_H5_NSTATUS);
    h->event_type = enum_type(event_types, RD_H5_NEVTYPES);
    return h->str_type >= 0 && H5Tset_size(h->str_type, H5T_VARIABLE) >= 0 &&
                   H5Tset_cset(h->str_type, H5T_CSET_UTF8) >= 0 && h->status_type >= 0 &&
                   h->event_type >= 0
               ? 0
               : -1;
}

/* Root `status` ("running" until the run ends) and `status_message` (""), variable-length
 * UTF-8 strings. Each is first written at its largest (RD_H5_STATUS, RD_H5_STATUS_MSG bytes),
 * then overwritten with its value: HDF5 frees the larger heap object on the overwrite, so the
 * file's global heap keeps room for a fault's status and message without growing. */
static int write_status_attrs(const rd_h5 *h, rd_error *err)
{
    char big[RD_H5_STATUS_MSG];
    memset(big, '-', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    const char *st = big + sizeof big - RD_H5_STATUS, *msg = big;
    if (attr_write(h, h->file, "status", h->str_type, 0, &st, err) ||
        attr_write(h, h->file, "status_message", h->str_type, 0, &msg, err))
        return -1;
    if (overwrite_status(h, "status", RD_H5_STATUS, "running") ||
        overwrite_status(h, "status_message", RD_H5_STATUS_MSG, ""))
        return rd_error_set(err, "%s: cannot write the root status", h->path);
    return 0;
}

static rd_h5 *h5_open(const char *path, const rd_h5_meta *meta, rd_error *err)
{
    if (check_names(path, meta, err)) return NULL;
    rd_h5 *h = alloc_handle(path, meta);
    if (!h) {
        rd_error_set(err, "%s: out of memory", path);
        return NULL;
    }
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0666); /* the system's reason, if any */
    if (fd < 0 || close(fd)) {
        rd_error_set(err, "%s: cannot create file: %s", path, strerror(errno));
        destroy(h);
        return NULL;
    }
    errno = 0;
    /* the 1.8 file format at least: it stores an attribute over 64 KiB (the per-body /summary
       arrays of more than 8,000 bodies) densely, where the 1.6 format refuses it */
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    if (fapl >= 0 && H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST) >= 0)
        h->file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    if (fapl >= 0) H5Pclose(fapl);
    int *fdp = NULL;
    if (h->file < 0 || H5Fget_vfd_handle(h->file, H5P_DEFAULT, (void **)&fdp) < 0 || !fdp ||
        fstat(*fdp, &h->id)) {
        rd_error_set(err, "%s: cannot create file: %s", path,
                     errno == EAGAIN || errno == EWOULDBLOCK ? RD_PATH_LOCKED
                     : errno
                         ? strerror(errno)
                         : "HDF5 library error (no system error: check the folder with df and ls)");
        destroy(h);
        return NULL;
    }
    h->fd = *fdp;
    /* bytes of the bodies' tables (the free bodies' tables alone left a 31-body scene 73 KB
       short once, so HDF5 wrote past a full disk or size limit and left a file no reader opens) */
    size_t tables = rd_h5_bodies_bytes(meta);
    if (make_types(h)) {
        rd_error_set(err, "%s: cannot create the string and enum types", path);
        destroy(h);
        return NULL;
    }
    if (reserve(h, tables, err) || write_root_attrs(h, meta, err) || write_status_attrs(h, err) ||
        create_dims(h, err) || make_group(h, "/bodies", "geometry and mass of every body", err) ||
        write_bodies(h, meta, err) || create_series(h, err) || create_events(h, err) ||
        link_scales(h, err) || rd_h5_flush(h, err)) {
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

static int event_type_index(const char *type)
{
    for (int i = 0; type && i < RD_H5_NEVTYPES; i++)
        if (!strcmp(type, event_types[i])) return i;
    return -1;
}

static int h5_event(rd_h5 *h, double time, int body, const char *type, double value, rd_error *err)
{
    if (body < -1 || body >= h->nb)
        return rd_error_set(err, "%s: event body index %d out of range", h->path, body);
    int ty = event_type_index(type);
    if (ty < 0) return rd_error_set(err, "%s: unknown event type '%s'", h->path, type ? type : "");
    rd_h5_event_buf *b = &h->evb;
    int r = h->nev++;
    b->index[r] = (int)h->ev_written + r;
    b->time[r] = time;
    b->body[r] = body >= 0 ? h->names[body] : "";
    b->body_index[r] = body;
    b->type[r] = (unsigned char)ty;
    b->value[r] = value;
    return h->nev == RD_H5_BUF ? rd_h5_flush(h, err) : 0;
}

/* Append n rows from buf to an extendible dataset whose first dimension is *written. */
static int extend_write(hid_t d, hid_t mtype, int rank, hsize_t *dims, hsize_t n, const void *buf)
{
    hsize_t start[3] = { dims[0], 0, 0 }, count[3] = { n, 0, 0 }, grown[3] = { dims[0] + n, 0, 0 };
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

/* Append the buffered events (n rows) to every /events column. 0 or -1. */
static int write_events(rd_h5 *h, int n)
{
    const rd_h5_event_buf *b = &h->evb;
    const void *src[EV_COUNT] = { b->index, b->time, b->body, b->body_index, b->type, b->value };
    const hid_t mt[EV_COUNT] = { H5T_NATIVE_INT, H5T_NATIVE_DOUBLE, h->str_type,
                                 H5T_NATIVE_INT, h->event_type,     H5T_NATIVE_DOUBLE };
    for (int c = 0; c < EV_COUNT; c++) {
        hsize_t written = h->ev_written;
        if (extend_write(h->ev[c], mt[c], 1, &written, (hsize_t)n, src[c])) return -1;
    }
    h->ev_written += (hsize_t)n;
    return 0;
}

static int h5_flush(rd_h5 *h, rd_error *err)
{
    int n = h->nbuf, nev = h->nev;
    h->nbuf = h->nev = 0; /* a failed write is not retried: it would duplicate rows */
    size_t width = 0;     /* doubles per sample, all series */
    for (int i = 0; i < SER_COUNT; i++) width += h->ser[i].width;
    size_t raw = sizeof(double) * width * (size_t)n + RD_H5_EVENT_BYTES * (size_t)nev;
    if (reserve(h, raw + raw / 8, err)) return -1;
    char what[RD_H5_SERNAME + 32];
    for (int i = 0; n > 0 && i < SER_COUNT; i++) {
        rd_h5_series *s = &h->ser[i];
        snprintf(what, sizeof what, "cannot write '%s'", s->name);
        if (extend_write(s->dset, H5T_NATIVE_DOUBLE, s->rank, s->dims, (hsize_t)n, s->buf))
            return fault_h5(h, err, what);
    }
    if (nev > 0 && write_events(h, nev)) return fault_h5(h, err, "cannot write /events");
    if (flush_file(h)) return fault_h5(h, err, "cannot flush file");
    rd_fault_point("run-flush");
    return 0;
}

/* ---- summary ---- */

/* The per-body /summary attributes: rd_body_summary's members, grouped by kind. */
typedef struct rd_h5_body_field {
    const char *name;  /* attribute */
    size_t offset;     /* of the member in rd_body_summary */
    const char *units; /* NULL: a 0/1 flag (an int member); else a double in these units */
} rd_h5_body_field;

#define RD_FIELD(attr, member, units)                                                              \
    {                                                                                              \
        attr, offsetof(rd_body_summary, member), units                                             \
    }
static const rd_h5_body_field body_fields[] = {
    RD_FIELD("overturned", overturned, NULL),
    RD_FIELD("uplifted", uplifted, NULL),
    RD_FIELD("slid", slid, NULL),
    RD_FIELD("overturn_time", overturn_time, "s"),
    RD_FIELD("max_tilt_ratio", max_tilt_ratio, "1"),
    RD_FIELD("tip_accel_min", tip_accel_min, "m/s^2"),
    RD_FIELD("max_slide", max_slide, "m"),
    RD_FIELD("final_slide", final_slide, "m"),
    RD_FIELD("max_tilt", max_tilt, "rad"),
    RD_FIELD("alpha", alpha, "rad"),
    RD_FIELD("max_rocking_in_plane", max_rocking_in, "rad"),
    RD_FIELD("max_rocking_out_of_plane", max_rocking_out, "rad"),
    RD_FIELD("max_twist", max_twist, "rad"),
    RD_FIELD("final_twist", final_twist, "rad"),
    RD_FIELD("alpha_min", alpha_min, "rad"),
    RD_FIELD("alpha_min_direction", alpha_min_direction, "rad"),
};
#undef RD_FIELD

/* order[i] = index in s->body of the body written as /bodies/names[i] (i itself when the
 * orders agree, as the engine's do: no search). */
static int summary_order(const rd_h5 *h, const rd_summary *s, int *order, rd_error *err)
{
    if (s->nbodies != h->nb)
        return rd_error_set(err, "%s: summary has %d bodies, file has %d", h->path, s->nbodies,
                            h->nb);
    for (int i = 0; i < h->nb; i++) {
        order[i] = strncmp(s->body[i].name, h->names[i], RD_NAME_MAX) ? -1 : i;
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
    double *d = malloc((size_t)h->nb * sizeof *d);
    int *n = malloc((size_t)h->nb * sizeof *n);
    size_t nf = sizeof body_fields / sizeof body_fields[0];
    int rc = d && n ? 0 : rd_error_set(err, "%s: out of memory", h->path);
    for (size_t f = 0; f < nf && !rc; f++) {
        const rd_h5_body_field *bf = &body_fields[f];
        for (int i = 0; i < h->nb; i++) {
            const char *p = (const char *)&s->body[order[i]] + bf->offset;
            if (!bf->units)
                memcpy(&n[i], p, sizeof n[i]);
            else
                memcpy(&d[i], p, sizeof d[i]);
        }
        rc = attr_write(h, g, bf->name, bf->units ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT,
                        (hsize_t)h->nb, bf->units ? (const void *)d : (const void *)n, err) ||
                     attr_units(h, g, bf->name, bf->units, err)
                 ? -1
                 : 0;
    }
    free(d);
    free(n);
    return rc;
}

/* The support-polygon alpha found at rest replaces the brick estimate in /bodies/alpha. */
static int body_alpha(const rd_h5 *h, const rd_summary *s, const int *order, rd_error *err)
{
    double *a = malloc(sizeof *a * (size_t)h->nb);
    if (!a) return rd_error_set(err, "%s: out of memory", h->path);
    for (int i = 0; i < h->nb; i++) a[i] = s->body[order[i]].alpha;
    int rc = rd_h5_bodies_alpha(h->file, a, h->nb, err);
    free(a);
    return rc ? rd_error_set(err, "%s: %s", h->path, err->msg) : 0;
}

static int write_summary_attrs(const rd_h5 *h, hid_t g, const rd_summary *s, rd_error *err)
{
    int st = (int)s->status;
    if (st < 0 || st >= RD_H5_NSTATUS)
        return rd_error_set(err, "%s: unknown run status %d", h->path, st);
    long steps = s->steps;
    return attr_enum(h, g, "status", h->status_type, st, err) ||
                   attr_int(h, g, "any_overturned", s->any_overturned, err) ||
                   attr_double(h, g, "end_time", s->end_time, "s", err) ||
                   attr_double(h, g, "dt", s->dt, "s", err) ||
                   attr_double(h, g, "dt_critical", s->dt_critical, "s", err) ||
                   attr_write(h, g, "steps", H5T_NATIVE_LONG, 0, &steps, err) ||
                   attr_double(h, g, "settle_time", s->settle_time, "s", err) ||
                   attr_double(h, g, "energy_residual_max", s->energy_residual_max, "1", err) ||
                   attr_double(h, g, "wall_seconds", s->wall_seconds, "s", err) ||
                   attr_int(h, g, "at_rest", s->at_rest, err)
               ? -1
               : 0;
}

/* /summary: the run's attributes and the per-body arrays. 0, -1 (err set), or 1: a write
 * failed (the caller records the fault). */
static int summary_group(rd_h5 *h, const rd_summary *s, const int *order, rd_error *err)
{
    htri_t exists = H5Lexists(h->file, "/summary", H5P_DEFAULT);
    if (exists <= 0 && make_group(h, "/summary",
                                  "what the run found (per-body attributes in "
                                  "/body order)",
                                  err))
        return -1;
    hid_t g = H5Gopen2(h->file, "/summary", H5P_DEFAULT);
    if (g < 0) return rd_error_set(err, "%s: cannot create group '/summary'", h->path);
    int rc = write_summary_attrs(h, g, s, err) || write_body_fields(h, g, s, order, err) ||
             body_alpha(h, s, order, err);
    H5Gclose(g);
    return rc;
}

static int h5_summary(rd_h5 *h, const rd_summary *s, rd_error *err)
{
    if (reserve(h, 0, err)) return -1;
    int *order = malloc((size_t)h->nb * sizeof *order);
    if (!order) return rd_error_set(err, "%s: out of memory", h->path);
    if (summary_order(h, s, order, err)) {
        free(order);
        return -1;
    }
    int rc = summary_group(h, s, order, err);
    free(order);
    if (rc < 0) return -1;
    if (rc) return fault_h5(h, err, "cannot write /summary");
    unsigned st = (unsigned)s->status;
    if (write_status(h, rd_status_name((rd_status)st), ""))
        return fault_h5(h, err, "cannot write the status");
    return 0;
}

long long rd_h5_file_id(const rd_h5 *h) { return (long long)h->file; }

static int h5_commit(rd_h5 *h, int ok, rd_error *err)
{
    if (!h->target || !ok || h->broken) return 0;
    if (h5_flush(h, err)) return -1;
    close_file(h);
    rd_fault_point("run-rename");
    if (rd_path_commit(h->path, h->target))
        return rd_error_set(
            err, "%s: cannot rename the finished run over %s: %s; the run's output is in %s",
            h->target, h->target, strerror(errno), h->path);
    free(h->target);
    h->target = NULL;
    return 0;
}

static void h5_close(rd_h5 *h)
{
    if (!h) return;
    rd_error ignored;
    if (!h->broken && h->file >= 0) rd_h5_flush(h, &ignored);
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
    const struct {
        const char *key;
        double v;
        const char *units;
    } f[] = { { "pga", im.pga, "m/s^2" },    { "pgv", im.pgv, "m/s" },
              { "pgd", im.pgd, "m" },        { "pgv_pga", im.pgv_pga, "s" },
              { "arias", im.arias, "m/s" },  { "d5_95", im.d5_95, "s" },
              { "sa_0.2s", sa[0], "m/s^2" }, { "sa_1s", sa[1], "m/s^2" },
              { "dt", r->dt, "s" },          { "duration", rd_record_duration(r), "s" } };
    char name[64];
    for (size_t i = 0; i < sizeof f / sizeof f[0]; i++) {
        snprintf(name, sizeof name, "%s_%s", cn, f[i].key);
        if (attr_double(h, g, name, f[i].v, f[i].units, err)) return -1;
    }
    snprintf(name, sizeof name, "%s_record", cn);
    if (attr_str(h, g, name, r->name, err)) return -1;
    snprintf(name, sizeof name, "%s_source", cn);
    return attr_str(h, g, name, r->source, err);
}

static int h5_ground_im(rd_h5 *h, const rd_motion_def *m, rd_error *err)
{
    if (!rd_motion_has_records(m)) return 0;
    if (reserve(h, 0, err)) return -1;
    hid_t g = H5Gopen2(h->file, "/ground", H5P_DEFAULT);
    if (g < 0) return rd_error_set(err, "%s: cannot open group '/ground'", h->path);
    int rc = attr_double(h, g, "direction", m->direction, "rad", err) ||
                     attr_double(h, g, "scale_factor", m->factor, "1", err) ||
                     attr_int(h, g, "baseline_degree", m->baseline, err)
                 ? -1
                 : 0;
    for (int c = 0; c < RD_NCOMPONENTS && !rc; c++)
        if (m->record[c].applied) rc = write_component_im(h, g, m, c, err);
    H5Gclose(g);
    return rc;
}

/* ---- the entry points: HDF5 error printing off around each (io/h5_quiet.h) ---- */

rd_h5 *rd_h5_open(const char *path, const rd_h5_meta *meta, rd_error *err)
{
    RD_H5_QUIETLY(rd_h5 *, h5_open(path, meta, err));
}

int rd_h5_append(rd_h5 *h, const rd_h5_sample *s, rd_error *err)
{
    RD_H5_QUIETLY(int, h5_append(h, s, err));
}

int rd_h5_event(rd_h5 *h, double time, int body, const char *type, double value, rd_error *err)
{
    RD_H5_QUIETLY(int, h5_event(h, time, body, type, value, err));
}

int rd_h5_flush(rd_h5 *h, rd_error *err) { RD_H5_QUIETLY(int, h5_flush(h, err)); }

int rd_h5_summary(rd_h5 *h, const rd_summary *s, rd_error *err)
{
    RD_H5_QUIETLY(int, h5_summary(h, s, err));
}

int rd_h5_reserve(rd_h5 *h, size_t bytes, rd_error *err)
{
    RD_H5_QUIETLY(int, reserve(h, bytes, err));
}

int rd_h5_fail(rd_h5 *h, const char *what, rd_error *err)
{
    char why[RD_ERROR_MAX];
    snprintf(why, sizeof why, "%s", err->msg);
    RD_H5_QUIETLY(int, fault(h, err, what, why));
}

int rd_h5_commit(rd_h5 *h, int ok, rd_error *err) { RD_H5_QUIETLY(int, h5_commit(h, ok, err)); }

void rd_h5_close(rd_h5 *h)
{
    rd_h5_quiet q = rd_h5_quiet_begin();
    h5_close(h);
    rd_h5_quiet_end(q);
}

int rd_h5_ground_im(rd_h5 *h, const rd_motion_def *m, rd_error *err)
{
    RD_H5_QUIETLY(int, h5_ground_im(h, m, err));
}
