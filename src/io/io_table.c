/* rockdem — plain HDF5 tables (io_table.h).
 * Folder io/ owns the HDF5 output file; it may call base/ and the public headers, never engine/
 * internals or cli/.
 */
#include "io/io_table.h"

#include <hdf5.h>
#include <hdf5_hl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static hid_t mem_type(rd_h5t_type t)
{
    switch (t) {
    case RD_H5T_INT: return H5T_NATIVE_INT;
    case RD_H5T_BYTE: return H5T_NATIVE_UCHAR;
    case RD_H5T_LONG: return H5T_NATIVE_LONG;
    default: return H5T_NATIVE_DOUBLE;
    }
}

static hid_t utf8_type(void)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    H5Tset_cset(t, H5T_CSET_UTF8);
    return t;
}

long long rd_h5t_create(const char *path, rd_error *err)
{
    hid_t f = H5I_INVALID_HID;
    H5dont_atexit(); /* before HDF5 is up, if this is its first use (io/h5_quiet.h) */
    H5E_BEGIN_TRY { f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT); }
    H5E_END_TRY;
    if (f < 0) rd_error_set(err, "%s: cannot create the file", path);
    return f < 0 ? -1 : (long long)f;
}

long long rd_h5t_open(const char *path, rd_error *err)
{
    hid_t f = H5I_INVALID_HID;
    H5dont_atexit(); /* before HDF5 is up, if this is its first use (io/h5_quiet.h) */
    H5E_BEGIN_TRY { f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT); }
    H5E_END_TRY;
    if (f < 0) rd_error_set(err, "cannot open '%s'", path);
    return f < 0 ? -1 : (long long)f;
}

void rd_h5t_close(long long file)
{
    if (file >= 0) H5Fclose((hid_t)file);
}

/* A variable-length UTF-8 string attribute (as every string rockdem writes: h5py reads a str,
 * netCDF readers a string, never bytes). */
static int str_attr(hid_t d, const char *name, const char *value)
{
    hid_t t = utf8_type(), sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(d, name, t, sp, H5P_DEFAULT, H5P_DEFAULT);
    int ok = a >= 0 && H5Awrite(a, t, &value) >= 0;
    if (a >= 0) H5Aclose(a);
    H5Sclose(sp);
    H5Tclose(t);
    return ok ? 0 : -1;
}

/* Dataset creation with intermediate groups. */
static hid_t make(hid_t loc, const char *name, hid_t ftype, hid_t space)
{
    hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
    H5Pset_create_intermediate_group(lcpl, 1);
    hid_t d = H5Dcreate2(loc, name, ftype, space, lcpl, H5P_DEFAULT, H5P_DEFAULT);
    H5Pclose(lcpl);
    return d;
}

static int exists(hid_t loc, const char *name)
{
    htri_t r = 0;
    H5E_BEGIN_TRY { r = H5Oexists_by_name(loc, name, H5P_DEFAULT); }
    H5E_END_TRY;
    return r > 0;
}

/* Scale `dim` of n entries: opened when it exists, else created (labels or indices). */
static hid_t scale(hid_t loc, const char *dim, const char *labels, long n)
{
    if (exists(loc, dim)) return H5Dopen2(loc, dim, H5P_DEFAULT);
    hsize_t len = (hsize_t)n;
    hid_t sp = H5Screate_simple(1, &len, NULL), d = H5I_INVALID_HID;
    int ok = 0;
    if (labels) {
        char *buf = strdup(labels);
        const char **lab = malloc((size_t)(n > 0 ? n : 1) * sizeof *lab);
        long k = 0;
        for (char *p = buf, *save = NULL, *w = buf ? strtok_r(p, ",", &save) : NULL; w && k < n;
             w = strtok_r(NULL, ",", &save))
            lab[k++] = w;
        hid_t t = utf8_type();
        d = buf && lab && k == n ? make(loc, dim, t, sp) : H5I_INVALID_HID;
        ok = d >= 0 && (n == 0 || H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, lab) >= 0);
        H5Tclose(t);
        free(lab);
        free(buf);
    } else {
        int *ix = malloc((size_t)(n > 0 ? n : 1) * sizeof *ix);
        for (long k = 0; ix && k < n; k++) ix[k] = (int)k;
        d = ix ? make(loc, dim, H5T_NATIVE_INT, sp) : H5I_INVALID_HID;
        ok = d >= 0 &&
             (n == 0 || H5Dwrite(d, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, ix) >= 0);
        free(ix);
    }
    H5Sclose(sp);
    const char *base = strrchr(dim, '/');
    ok = ok && H5DSset_scale(d, base ? base + 1 : dim) >= 0 &&
         str_attr(d, "long_name", labels ? "component" : "index") == 0;
    if (!ok && d >= 0) {
        H5Dclose(d);
        d = H5I_INVALID_HID;
    }
    return d;
}

static int attach_axes(hid_t loc, hid_t d, const rd_h5t_axes *axes, const long *n, int rank)
{
    for (int k = 0; axes && k < rank; k++) {
        if (!axes->dim[k]) continue;
        hid_t sc = scale(loc, axes->dim[k], axes->labels[k], n[k]);
        int ok = sc >= 0 && H5DSattach_scale(d, sc, (unsigned)k) >= 0;
        if (sc >= 0) H5Dclose(sc);
        if (!ok) return -1;
    }
    return 0;
}

int rd_h5t_write(long long loc, const char *name, rd_h5t_type t, const void *data, long rows,
                 int cols, const char *units, const char *long_name, const rd_h5t_axes *axes,
                 rd_error *err)
{
    hsize_t dims[2] = { (hsize_t)rows, (hsize_t)cols };
    long n[2] = { rows, cols };
    int rank = cols > 0 ? 2 : 1;
    hid_t sp = H5Screate_simple(rank, dims, NULL);
    hid_t d = sp >= 0 ? make((hid_t)loc, name, mem_type(t), sp) : H5I_INVALID_HID;
    int ok =
        d >= 0 && (rows == 0 || H5Dwrite(d, mem_type(t), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0);
    if (ok && units) ok = str_attr(d, "units", units) == 0;
    if (ok && long_name) ok = str_attr(d, "long_name", long_name) == 0;
    if (ok) ok = attach_axes((hid_t)loc, d, axes, n, rank) == 0;
    if (d >= 0) H5Dclose(d);
    if (sp >= 0) H5Sclose(sp);
    return ok ? 0 : rd_error_set(err, "cannot write dataset '%s'", name);
}

int rd_h5t_write_rows(long long loc, const char *name, rd_h5t_type t, const void *data, long first,
                      long rows, rd_error *err)
{
    hid_t d = exists((hid_t)loc, name) ? H5Dopen2((hid_t)loc, name, H5P_DEFAULT) : H5I_INVALID_HID;
    hid_t fs = d >= 0 ? H5Dget_space(d) : H5I_INVALID_HID, ms = H5I_INVALID_HID;
    hsize_t dims[2] = { 0, 1 };
    int rank = fs >= 0 ? H5Sget_simple_extent_dims(fs, dims, NULL) : -1;
    int ok =
        (rank == 1 || rank == 2) && first >= 0 && rows >= 0 && (hsize_t)(first + rows) <= dims[0];
    if (ok && rows > 0) {
        hsize_t start[2] = { (hsize_t)first, 0 }, count[2] = { (hsize_t)rows, dims[1] };
        ms = H5Screate_simple(rank, count, NULL);
        ok = ms >= 0 && H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 &&
             H5Dwrite(d, mem_type(t), ms, fs, H5P_DEFAULT, data) >= 0;
    }
    if (ms >= 0) H5Sclose(ms);
    if (fs >= 0) H5Sclose(fs);
    if (d >= 0) H5Dclose(d);
    return ok ? 0
              : rd_error_set(err, "cannot write rows %ld..%ld of dataset '%s'", first,
                             first + rows - 1, name);
}

int rd_h5t_attr(long long loc, const char *name, const char *key, const char *value, rd_error *err)
{
    hid_t o = H5Oopen((hid_t)loc, name, H5P_DEFAULT);
    int ok = o >= 0 && (H5Aexists(o, key) <= 0 || H5Adelete(o, key) >= 0) &&
             str_attr(o, key, value) == 0;
    if (o >= 0) H5Oclose(o);
    return ok ? 0 : rd_error_set(err, "cannot write attribute '%s' of '%s'", key, name);
}

long long rd_h5t_group(long long loc, const char *name, rd_error *err)
{
    hid_t g = exists((hid_t)loc, name)
                  ? H5Gopen2((hid_t)loc, name, H5P_DEFAULT)
                  : H5Gcreate2((hid_t)loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) rd_error_set(err, "cannot create group '%s'", name);
    return g < 0 ? -1 : (long long)g;
}

void rd_h5t_close_group(long long g)
{
    if (g >= 0) H5Gclose((hid_t)g);
}

int rd_h5t_make_scale(long long loc, const char *name, rd_error *err)
{
    hid_t d = H5Dopen2((hid_t)loc, name, H5P_DEFAULT);
    const char *base = strrchr(name, '/');
    int ok = d >= 0 && H5DSset_scale(d, base ? base + 1 : name) >= 0;
    if (d >= 0) H5Dclose(d);
    return ok ? 0 : rd_error_set(err, "cannot make '%s' a dimension scale", name);
}

long rd_h5t_count(long long loc, const char *name)
{
    if (!exists((hid_t)loc, name)) return -1;
    hid_t d = H5Dopen2((hid_t)loc, name, H5P_DEFAULT);
    if (d < 0) return -1;
    hid_t sp = H5Dget_space(d);
    long n = (long)H5Sget_simple_extent_npoints(sp);
    H5Sclose(sp);
    H5Dclose(d);
    return n;
}

int rd_h5t_read(long long loc, const char *name, rd_h5t_type t, void *data, long n, rd_error *err)
{
    long have = rd_h5t_count(loc, name);
    if (have != n)
        return rd_error_set(err, "dataset '%s': %s", name, have < 0 ? "missing" : "wrong size");
    if (n == 0) return 0;
    hid_t d = H5Dopen2((hid_t)loc, name, H5P_DEFAULT);
    int ok = d >= 0 && H5Dread(d, mem_type(t), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0;
    if (d >= 0) H5Dclose(d);
    return ok ? 0 : rd_error_set(err, "cannot read dataset '%s'", name);
}

int rd_h5t_strings(long long loc, const char *name, const char *const *s, int n,
                   const char *long_name, const char *dim, rd_error *err)
{
    hsize_t len = (hsize_t)n;
    hid_t t = utf8_type(), sp = H5Screate_simple(1, &len, NULL);
    hid_t d = make((hid_t)loc, name, t, sp);
    int ok = d >= 0 && (n == 0 || H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, s) >= 0);
    if (ok && long_name) ok = str_attr(d, "long_name", long_name) == 0;
    if (ok && dim && !strcmp(dim, name)) {
        const char *base = strrchr(name, '/');
        ok = H5DSset_scale(d, base ? base + 1 : name) >= 0;
    } else if (ok && dim) {
        long nn[1] = { n };
        rd_h5t_axes ax = { { dim, NULL }, { NULL, NULL } };
        ok = attach_axes((hid_t)loc, d, &ax, nn, 1) == 0;
    }
    if (d >= 0) H5Dclose(d);
    H5Sclose(sp);
    H5Tclose(t);
    return ok ? 0 : rd_error_set(err, "cannot write dataset '%s'", name);
}

int rd_h5t_string(long long loc, const char *name, int k, char *out, int size, rd_error *err)
{
    long n = rd_h5t_count(loc, name);
    if (n < 0) return rd_error_set(err, "dataset '%s': missing", name);
    if (k < 0 || k >= n) return rd_error_set(err, "dataset '%s': no entry %d", name, k);
    hid_t d = H5Dopen2((hid_t)loc, name, H5P_DEFAULT);
    hid_t t = utf8_type(), sp = H5Dget_space(d);
    char **buf = calloc((size_t)n, sizeof *buf);
    int ok = buf && H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0;
    if (ok) {
        size_t len = strlen(buf[k]);
        if (len >= (size_t)size) len = (size_t)size - 1;
        memcpy(out, buf[k], len);
        out[len] = '\0';
        H5Dvlen_reclaim(t, sp, H5P_DEFAULT, buf);
    }
    free(buf);
    H5Sclose(sp);
    H5Tclose(t);
    H5Dclose(d);
    return ok ? 0 : rd_error_set(err, "cannot read dataset '%s'", name);
}

/* ---- scales linked into the groups that use them ---- */

/* LINK_MAX: distinct outside scales one group may use; MEMBER_MAX: members of a group whose
 * addresses are kept for the in-group test (more: the test falls back on names). */
enum { LINK_MAX = 32, MEMBER_MAX = 64 };

/* Paths of the outside scales resolved so far, by object address, shared by the whole visit:
 * H5Iget_name of a scale opened through a reference searches the file for it (O(file)), so
 * each distinct scale is named once, not once per dataset using it (a 10,000-body file has
 * 20,000 such uses of /xyz and /corner). */
typedef struct scale_names {
    int n;
    haddr_t addr[LINK_MAX];
    char path[LINK_MAX][256];
    char spare[256]; /* the path of a scale looked up when the cache is full */
} scale_names;

typedef struct link_ctx {
    hid_t group;        /* the group whose datasets are visited */
    scale_names *names; /* shared cache of resolved outside scales */
    int nmember;        /* addresses of the group's own members (-1: too many) */
    haddr_t member[MEMBER_MAX];
    int n, failed;
    char path[LINK_MAX][256]; /* the outside scales found, linked once the visit is over */
} link_ctx;

/* 1 when the object at address a is one of the group's own members (unknown: 0). */
static int is_member(const link_ctx *c, haddr_t a)
{
    for (int k = 0; k < c->nmember; k++)
        if (c->member[k] == a) return 1;
    return 0;
}

/* The path of scale sc (address a), from the cache or else looked up once. NULL when none. */
static const char *scale_path(scale_names *s, hid_t sc, haddr_t a)
{
    for (int k = 0; k < s->n; k++)
        if (s->addr[k] == a) return s->path[k];
    char *path = s->n < LINK_MAX ? s->path[s->n] : s->spare;
    if (H5Iget_name(sc, path, sizeof s->spare) <= 0) return NULL;
    if (s->n == LINK_MAX) return path;
    s->addr[s->n] = a;
    return s->path[s->n++];
}

/* H5DSiterate_scales callback: note scale `sc` unless it is already a member of ctx->group. */
static herr_t note_scale(hid_t did, unsigned dim, hid_t sc, void *op)
{
    (void)did;
    (void)dim;
    link_ctx *c = op;
    H5O_info_t oi;
    if (H5Oget_info2(sc, &oi, H5O_INFO_BASIC) < 0) return 0;
    if (c->nmember >= 0 && is_member(c, oi.addr)) return 0;
    const char *path = scale_path(c->names, sc, oi.addr);
    if (!path) {
        c->failed = 1;
        return 0;
    }
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    if (!base[0] || exists(c->group, base)) return 0;
    for (int k = 0; k < c->n; k++)
        if (!strcmp(c->path[k], path)) return 0;
    if (c->n == LINK_MAX) {
        c->failed = 1;
        return 0;
    }
    snprintf(c->path[c->n++], sizeof c->path[0], "%s", path);
    return 0;
}

static int link_group(hid_t g, scale_names *names);

/* H5Literate callback: the group's members' addresses (the in-group test of note_scale). */
static herr_t list_member(hid_t g, const char *name, const H5L_info_t *info, void *op)
{
    link_ctx *c = op;
    H5O_info_t oi;
    if (info->type != H5L_TYPE_HARD || c->nmember < 0 ||
        H5Oget_info_by_name2(g, name, &oi, H5O_INFO_BASIC, H5P_DEFAULT) < 0)
        return 0;
    if (c->nmember == MEMBER_MAX)
        c->nmember = -1; /* too many: fall back on names */
    else
        c->member[c->nmember++] = oi.addr;
    return 0;
}

/* H5Literate callback over a group's members: a dataset's outside scales are noted, a
 * subgroup is linked in turn. */
static herr_t visit_member(hid_t g, const char *name, const H5L_info_t *info, void *op)
{
    link_ctx *c = op;
    H5O_info_t oi;
    if (info->type != H5L_TYPE_HARD ||
        H5Oget_info_by_name2(g, name, &oi, H5O_INFO_BASIC, H5P_DEFAULT) < 0)
        return 0;
    if (oi.type == H5O_TYPE_GROUP) {
        hid_t sub = H5Gopen2(g, name, H5P_DEFAULT);
        if (sub < 0 || link_group(sub, c->names)) c->failed = 1;
        if (sub >= 0) H5Gclose(sub);
    } else if (oi.type == H5O_TYPE_DATASET) {
        hid_t d = H5Dopen2(g, name, H5P_DEFAULT), sp = d < 0 ? -1 : H5Dget_space(d);
        int rank = sp < 0 ? 0 : H5Sget_simple_extent_ndims(sp);
        for (int k = 0; k < rank; k++)
            if (H5DSget_num_scales(d, (unsigned)k) > 0)
                H5DSiterate_scales(d, (unsigned)k, NULL, note_scale, c);
        if (sp >= 0) H5Sclose(sp);
        if (d >= 0) H5Dclose(d);
    }
    return 0;
}

/* Link into group g the outside scales its datasets use, and do the same in its subgroups
 * (the links are made after the visit: a group is not changed while it is listed). */
static int link_group(hid_t g, scale_names *names)
{
    link_ctx *c = calloc(1, sizeof *c);
    if (!c) return -1;
    c->group = g;
    c->names = names;
    hsize_t idx = 0;
    int rc = H5Literate(g, H5_INDEX_NAME, H5_ITER_NATIVE, &idx, list_member, c) < 0;
    idx = 0;
    rc = rc || H5Literate(g, H5_INDEX_NAME, H5_ITER_NATIVE, &idx, visit_member, c) < 0 || c->failed;
    for (int k = 0; k < c->n && !rc; k++) {
        const char *base = strrchr(c->path[k], '/') + 1;
        rc = H5Lcreate_hard(g, c->path[k], g, base, H5P_DEFAULT, H5P_DEFAULT) < 0;
    }
    free(c);
    return rc ? -1 : 0;
}

int rd_h5t_link_scales(long long loc, const char *name, rd_error *err)
{
    hid_t g = H5Gopen2((hid_t)loc, name, H5P_DEFAULT);
    if (g < 0) return rd_error_set(err, "cannot open group '%s'", name);
    scale_names *names = calloc(1, sizeof *names);
    int rc = !names || link_group(g, names);
    free(names);
    H5Gclose(g);
    return rc ? rd_error_set(err, "cannot link the dimension scales of group '%s'", name) : 0;
}
