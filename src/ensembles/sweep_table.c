/* rockdem — the sweep table (include/rockdem/sweep.h, layout in docs/FRAGILITY.md): group /sweep
 * of equal-length 1-D datasets, one row per finished case (the form tools/rdtools/fraginput.py
 * reads), plus 2-D per-body datasets body_* [rows][free bodies]. A row is appended column by
 * column and committed by the `case` column, written last, then the file is flushed: a file
 * left by a killed sweep is trimmed back to its committed rows when it is opened again.
 * Self-describing like a run file (docs/HDF5-LAYOUT.md): `case` is the dimension scale of the
 * rows and `body` of the per-body axis, every column has units and long_name, status is an
 * HDF5 enum, strings are UTF-8 and the case count is a number.
 *
 * Before a row is written the file is extended (posix_fallocate) by more than the row needs,
 * so a full disk or a file-size limit fails before HDF5 writes anything; HDF5 never meets a
 * failed write mid-row. Trailing rows whose case/hash do not match the plan (a partial row
 * left by older versions, or by an I/O error inside HDF5) are dropped and reported.
 *
 * Folder ensembles/ owns many-run studies (threshold, restitution, sweeps); it may call the
 * public API (engine, scenario, reference) and io/.
 */
#include "rockdem/sweep.h"
#include "base/fault.h"
#include "base/path.h"
#include "io/h5_quiet.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define RD_SWEEP_CHUNK 64 /* rows per chunk */
#define RD_SWEEP_LAYOUT                                                                            \
    5 /* /sweep layout_version: 2 = scales, status enum, numeric ncases;
                            3 = Sa, max twist, joint slip, response modes; 4 = runout;
                            5 = per-fence columns on the fence axis */
/* Space reserved before a row: a new chunk for every column when the row starts one (chunks
 * are allocated whole), plus 32 KiB for chunk-index (B-tree) nodes and object-header updates. */
#define RD_SWEEP_RESERVE_FIXED (32 << 10)

typedef enum col_type { C_I32, C_I64, C_U64, C_F64, C_STR, C_STATUS } col_type;

typedef struct col_spec {
    const char *name;
    col_type type;
    size_t off;   /* in rd_sweep_result */
    int per_body; /* 1: [rows][nbodies]; PER_FENCE: [rows][nfences] */
    const char *units;
    const char *long_name;
} col_spec;

#define PER_FENCE 2
#define R(f)      offsetof(rd_sweep_result, f)
static const col_spec outcome_cols[] = {
    { "pga", C_F64, R(im[RD_IM_PGA]), 0, "m/s^2", "peak ground acceleration" },
    { "pgv", C_F64, R(im[RD_IM_PGV]), 0, "m/s", "peak ground velocity" },
    { "pgd", C_F64, R(im[RD_IM_PGD]), 0, "m", "peak ground displacement" },
    { "pgv_pga", C_F64, R(im[RD_IM_PGV_PGA]), 0, "s", "PGV / PGA" },
    { "arias", C_F64, R(im[RD_IM_ARIAS]), 0, "m/s", "Arias intensity" },
    { "d5_95", C_F64, R(im[RD_IM_D5_95]), 0, "s", "significant duration D5-95" },
    { "sa_0_2", C_F64, R(im[RD_IM_SA_0_2]), 0, "m/s^2",
      "pseudo-spectral acceleration, 5 % damping, T = 0.2 s" },
    { "sa_1", C_F64, R(im[RD_IM_SA_1]), 0, "m/s^2",
      "pseudo-spectral acceleration, 5 % damping, T = 1 s" },
    { "overturned", C_I32, R(overturned), 0, "1", "1 if any free body overturned" },
    { "overturn_time", C_F64, R(overturn_time), 0, "s", "time of the first overturn (-1: none)" },
    { "max_tilt_ratio", C_F64, R(max_tilt_ratio), 0, "1",
      "largest max tilt / alpha over the free bodies" },
    { "max_slide", C_F64, R(max_slide), 0, "m", "largest max slide over the free bodies" },
    { "final_twist", C_F64, R(final_twist), 0, "rad",
      "largest |twist at the end| over the free bodies (signed)" },
    { "max_twist", C_F64, R(max_twist), 0, "rad",
      "largest max |twist about the vertical| over the free bodies" },
    { "max_slip", C_F64, R(max_slip), 0, "m",
      "largest joint slip of a free body (not its centre's sway)" },
    { "mode", C_STR, R(mode), 0, "",
      "response mode, most severe over the bodies: rest, slide, rock, "
      "rock-slide, rock-twist, overturn (docs/FRAGILITY.md)" },
    { "status", C_STATUS, R(status), 0, "", "how the run ended" },
    { "energy_residual", C_F64, R(energy_residual), 0, "1",
      "max |energy balance residual| / energy scale" },
    { "end_time", C_F64, R(end_time), 0, "s", "simulated time reached" },
    { "quiet_end", C_F64, R(quiet_end), 0, "s",
      "the case ended here: every body at rest, the motion left unable to lift or slide it "
      "(-1: ran to its end; rockdem sweep --full)" },
    { "wall_seconds", C_F64, R(wall_seconds), 0, "s", "wall time of the case (setup and run)" },
    { "hash", C_U64, R(hash), 0, "", "FNV-1a 64 hash of the case overrides" },
    { "body_overturned", C_I32, R(b_overturned), 1, "1", "1 if the body overturned" },
    { "body_overturn_time", C_F64, R(b_overturn_time), 1, "s",
      "time the body overturned (-1: never)" },
    { "body_max_tilt_ratio", C_F64, R(b_max_tilt_ratio), 1, "1", "max tilt / alpha of the body" },
    { "body_max_slide", C_F64, R(b_max_slide), 1, "m", "max slide of the body" },
    { "body_final_twist", C_F64, R(b_final_twist), 1, "rad", "twist of the body at the end" },
    { "body_max_twist", C_F64, R(b_max_twist), 1, "rad",
      "max |twist about the vertical| of the body" },
    { "body_max_slip", C_F64, R(b_max_slip), 1, "m", "largest slip of the body's joints" },
    { "body_mode", C_I32, R(b_mode), 1, "",
      "response mode: 0 rest, 1 slide, 2 rock, 3 rock-slide, "
      "4 rock-twist, 5 overturn (docs/FRAGILITY.md)" },
    { "runout", C_F64, R(runout), 0, "m",
      "largest runout (horizontal travel of the centre from rest) over the free bodies" },
    { "fence_energy", C_F64, R(fence_energy), 0, "J",
      "largest kinetic energy at a fence crossing over the free bodies (0: none crossed)" },
    { "at_rest", C_I32, R(at_rest), 0, "1",
      "model solve until rest: 1 if every body came to rest or left the domain" },
    { "body_runout", C_F64, R(b_runout), 1, "m", "runout of the body from rest" },
    { "body_runout_direction", C_F64, R(b_runout_direction), 1, "rad",
      "direction of the body's runout from +x" },
    { "body_max_speed", C_F64, R(b_max_speed), 1, "m/s", "largest speed of the body's centre" },
    { "body_max_energy", C_F64, R(b_max_energy), 1, "J",
      "largest kinetic energy of the body (translation and rotation)" },
    { "body_max_bounce", C_F64, R(b_max_bounce), 1, "m",
      "largest gap between the body and the fixed surface below it" },
    { "body_fence_time", C_F64, R(b_fence_time), 1, "s",
      "time the body first crossed the first fence (-1: never)" },
    { "body_fence_energy", C_F64, R(b_fence_energy), 1, "J",
      "kinetic energy of the body at its first crossing of the first fence (0: none)" },
    { "body_fence_height", C_F64, R(b_fence_height), 1, "m",
      "height of the body's centre above the surface at its first crossing of the first fence "
      "(-1: none)" },
    { "fence_max_energy", C_F64, R(f_energy), PER_FENCE, "J",
      "largest kinetic energy at a first crossing of the fence over the free bodies (0: none)" },
    { "fence_max_height", C_F64, R(f_height), PER_FENCE, "m",
      "largest centre height above the surface at a first crossing of the fence (-1: none)" },
    { "fence_crossed", C_I32, R(f_crossed), PER_FENCE, "1", "free bodies that crossed the fence" },
    { "case", C_I64, R(index), 0, "",
      "case index in the sweep plan" }, /* last: writing it commits the row */
};
#define NOUT (int)(sizeof outcome_cols / sizeof outcome_cols[0])

typedef struct column {
    char name[RD_NAME_MAX];
    hid_t dset;
    hid_t mtype; /* memory type of one element */
    size_t size; /* bytes of one element */
    int width;   /* elements per row */
    int axis;    /* axis index, or -1 */
    const col_spec *spec;
} column;

struct rd_sweep_table {
    char path[RD_PATH_MAX];
    hid_t file, group, str; /* str: fixed-length UTF-8 text cells */
    hid_t vstr;             /* variable-length UTF-8 string (attributes, the body scale) */
    hid_t status_t;         /* enum of the run statuses (rd_status_name) */
    const rd_sweep_plan *plan;
    int ncols;
    column col[RD_SWEEP_MAX_AXES + NOUT];
    long rows;
    long dropped; /* partial trailing rows dropped at open */
    int fd;       /* the file's descriptor (sec2 driver), for reserve() */
};

static void col_init(rd_sweep_table *t, column *c, const char *name, col_type ty, int width)
{
    snprintf(c->name, sizeof c->name, "%s", name);
    c->width = width;
    c->axis = -1;
    c->dset = -1;
    c->mtype = ty == C_I32      ? H5T_NATIVE_INT
               : ty == C_I64    ? H5T_NATIVE_LONG
               : ty == C_U64    ? H5T_NATIVE_ULLONG
               : ty == C_F64    ? H5T_NATIVE_DOUBLE
               : ty == C_STATUS ? t->status_t
                                : t->str;
    c->size = H5Tget_size(c->mtype);
}

/* Elements per row of a column on axis per_body (0: one; at least one: no free body). */
static int axis_width(const rd_sweep_plan *p, int per_body)
{
    int n = per_body == PER_FENCE ? p->nfences : per_body ? p->nbodies : 1;
    return n > 0 ? n : 1;
}

static void layout(rd_sweep_table *t)
{
    const rd_sweep_plan *p = t->plan;
    t->ncols = 0;
    for (int a = 0; a < p->naxes; a++) {
        column *c = &t->col[t->ncols++];
        col_init(t, c, p->axis[a].key, p->axis[a].number ? C_F64 : C_STR, 1);
        c->axis = a;
    }
    for (int i = 0; i < NOUT; i++) {
        const col_spec *s = &outcome_cols[i];
        if (s->per_body == PER_FENCE && p->nfences == 0) continue; /* no fence, no fence axis */
        column *c = &t->col[t->ncols++];
        col_init(t, c, s->name, s->type, axis_width(p, s->per_body));
        c->spec = s;
    }
}

static int h5fail(rd_sweep_table *t, rd_error *err, const char *what)
{
    return rd_error_set(err, "rockdem sweep: %s: %s", t->path, what);
}

/* A variable-length UTF-8 string attribute. */
static int attr_text(const rd_sweep_table *t, hid_t obj, const char *name, const char *text)
{
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(obj, name, t->vstr, sp, H5P_DEFAULT, H5P_DEFAULT);
    int rc = a >= 0 && H5Awrite(a, t->vstr, &text) >= 0 ? 0 : -1;
    if (a >= 0) H5Aclose(a);
    H5Sclose(sp);
    return rc;
}

static int attr_number(hid_t obj, const char *name, hid_t type, const void *v)
{
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(obj, name, type, sp, H5P_DEFAULT, H5P_DEFAULT);
    int rc = a >= 0 && H5Awrite(a, type, v) >= 0 ? 0 : -1;
    if (a >= 0) H5Aclose(a);
    H5Sclose(sp);
    return rc;
}

/* A string attribute (variable or fixed length) as a malloc'd text, or NULL. */
static char *attr_read(hid_t obj, const char *name)
{
    if (H5Aexists(obj, name) <= 0) return NULL;
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT), ty = H5Aget_type(a);
    char *s = NULL;
    if (H5Tget_class(ty) == H5T_STRING && H5Tis_variable_str(ty) > 0) {
        char *v = NULL;
        if (H5Aread(a, ty, &v) >= 0 && v) s = strdup(v);
        H5free_memory(v);
    } else if (H5Tget_class(ty) == H5T_STRING) {
        size_t n = H5Tget_size(ty);
        if ((s = calloc(n + 1, 1)) && H5Aread(a, ty, s) < 0) {
            free(s);
            s = NULL;
        }
    }
    H5Tclose(ty);
    H5Aclose(a);
    return s;
}

static int create_column(rd_sweep_table *t, column *c)
{
    int rank = c->width > 1 || (c->spec && c->spec->per_body) ? 2 : 1;
    hsize_t dims[2] = { 0, (hsize_t)c->width }, maxd[2] = { H5S_UNLIMITED, (hsize_t)c->width };
    hsize_t chunk[2] = { RD_SWEEP_CHUNK, (hsize_t)c->width };
    hid_t sp = H5Screate_simple(rank, dims, maxd), dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, rank, chunk);
    c->dset = H5Dcreate2(t->group, c->name, c->mtype, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    H5Pclose(dcpl);
    H5Sclose(sp);
    if (c->dset < 0) return -1;
    const char *units = c->axis >= 0 ? t->plan->axis[c->axis].units : c->spec->units;
    const char *lname = c->axis >= 0 ? "swept value" : c->spec->long_name;
    return (units[0] && attr_text(t, c->dset, "units", units)) ||
                   attr_text(t, c->dset, "long_name", lname)
               ? -1
               : 0;
}

/* A 1-D dataset of n names (at least one, "" for none) under /sweep, made a dimension scale.
 * Its id, or -1. */
static hid_t name_scale(rd_sweep_table *t, const char *name, const char (*names)[RD_NAME_MAX],
                        int n, const char *long_name)
{
    const char *v[RD_SWEEP_BODIES];
    hsize_t nn = (hsize_t)(n > 0 ? n : 1);
    for (int k = 0; k < (int)nn; k++) v[k] = k < n ? names[k] : "";
    hid_t sp = H5Screate_simple(1, &nn, NULL);
    hid_t d = H5Dcreate2(t->group, name, t->vstr, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Sclose(sp);
    if (d >= 0 && H5Dwrite(d, t->vstr, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0 &&
        H5DSset_scale(d, name) >= 0 && !attr_text(t, d, "long_name", long_name))
        return d;
    if (d >= 0) H5Dclose(d);
    return -1;
}

/* `case` becomes the scale of every column's rows, /sweep/body that of the per-body axis,
 * /sweep/fence that of the per-fence one (made only when the scenario has fences, as are the
 * per-fence columns). */
static int attach_scales(rd_sweep_table *t)
{
    const rd_sweep_plan *p = t->plan;
    hid_t b = name_scale(t, "body", p->body, p->nbodies, "free body");
    hid_t fe = p->nfences ? name_scale(t, "fence", p->fence, p->nfences, "fence (model fence)") : 0;
    hid_t ck = t->col[t->ncols - 1].dset;
    int rc = b >= 0 && fe >= 0 && H5DSset_scale(ck, "case") >= 0 ? 0 : -1;
    for (int i = 0; !rc && i < t->ncols - 1; i++) {
        const column *c = &t->col[i];
        const int ax = c->spec ? c->spec->per_body : 0;
        if (H5DSattach_scale(c->dset, ck, 0) < 0 ||
            (ax && H5DSattach_scale(c->dset, ax == PER_FENCE ? fe : b, 1) < 0))
            rc = -1;
    }
    if (b >= 0) H5Dclose(b);
    if (fe > 0) H5Dclose(fe);
    return rc;
}

static int write_meta(rd_sweep_table *t)
{
    const rd_sweep_plan *p = t->plan;
    const char *bodies[RD_SWEEP_BODIES];
    for (int k = 0; k < p->nbodies; k++) bodies[k] = p->body[k];
    hsize_t nb = (hsize_t)p->nbodies;
    hid_t sp = H5Screate_simple(1, &nb, NULL);
    hid_t a = nb ? H5Acreate2(t->group, "bodies", t->vstr, sp, H5P_DEFAULT, H5P_DEFAULT) : 0;
    int bad = a < 0 || (nb && H5Awrite(a, t->vstr, bodies) < 0);
    if (a > 0) H5Aclose(a);
    H5Sclose(sp);
    long ncases = p->ncases;
    int layout = RD_SWEEP_LAYOUT;
    return bad || attr_text(t, t->file, "Conventions", "rockdem-2") ||
                   attr_text(t, t->file, "scenario", p->text) ||
                   attr_text(t, t->file, "scenario_file", p->path) ||
                   attr_text(t, t->file, "axes", p->axes_text) ||
                   attr_text(t, t->file, "program", "rockdem " RD_VERSION) ||
                   attr_number(t->group, "layout_version", H5T_NATIVE_INT, &layout) ||
                   attr_number(t->group, "ncases", H5T_NATIVE_LONG, &ncases) ||
                   attr_text(t, t->group, "im_source",
                             p->pulse ? "pulse: sampled along its direction"
                                      : "records: max over horizontal components")
               ? -1
               : 0;
}

/* The descriptor behind t->file. 0 or -1. */
static int get_fd(rd_sweep_table *t, rd_error *err)
{
    int *fdp = NULL;
    if (H5Fget_vfd_handle(t->file, H5P_DEFAULT, (void **)&fdp) < 0 || !fdp)
        return h5fail(t, err, "cannot get the file descriptor");
    t->fd = *fdp;
    return 0;
}

/* Make room for `bytes` more past HDF5's allocated end of file. 0, or -1 with the reason. */
static int reserve(rd_sweep_table *t, size_t bytes, rd_error *err)
{
    hsize_t used = 0;
    if (H5Fget_filesize(t->file, &used) < 0) return h5fail(t, err, "cannot get the file size");
    int e;
    do e = posix_fallocate(t->fd, (off_t)used, (off_t)(bytes + RD_SWEEP_RESERVE_FIXED));
    while (e == EINTR);
    if (e)
        return rd_error_set(
            err, "rockdem sweep: %s: cannot extend the table by %zu bytes for row %ld: %s", t->path,
            bytes + RD_SWEEP_RESERVE_FIXED, t->rows, strerror(e));
    return 0;
}

/* Flush and give the unused reserve back. 0 or -1 (errno set). */
static int flush_table(rd_sweep_table *t)
{
    hsize_t used = 0;
    errno = 0;
    if (H5Fflush(t->file, H5F_SCOPE_GLOBAL) < 0 || H5Fget_filesize(t->file, &used) < 0) return -1;
    return ftruncate(t->fd, (off_t)used) ? -1 : 0;
}

/* "cannot <what>: <errno text>" for an HDF5 failure that follows a failed system call. */
static int h5fail_errno(rd_sweep_table *t, rd_error *err, const char *what)
{
    int e = errno;
    return rd_error_set(err, "rockdem sweep: %s: %s: %s", t->path, what,
                        e ? strerror(e)
                          : "HDF5 library error (the file may be damaged: check it with h5dump, "
                            "or choose another -o)");
}

/* A new, empty table at t->path; `excl`: the path must not exist yet (else it is a temporary
 * made for it). 0 or -1. */
static int create_table(rd_sweep_table *t, int excl, rd_error *err)
{
    int fd = excl ? open(t->path, O_WRONLY | O_CREAT | O_EXCL, 0666)
                  : 0; /* the system's reason, if any */
    if (fd < 0) return h5fail_errno(t, err, "cannot create the table");
    if (excl) close(fd);
    t->file = H5Fcreate(t->path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (t->file < 0 || get_fd(t, err)) return h5fail_errno(t, err, "cannot create the table");
    if (reserve(t, 0, err)) return -1;
    t->group = H5Gcreate2(t->file, "sweep", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (t->group < 0 || write_meta(t)) return h5fail(t, err, "cannot write the table header");
    for (int i = 0; i < t->ncols; i++)
        if (create_column(t, &t->col[i])) return h5fail(t, err, "cannot create a column");
    if (attach_scales(t)) return h5fail(t, err, "cannot write the dimension scales");
    return flush_table(t) ? h5fail_errno(t, err, "cannot flush") : 0;
}

/* The rows committed (length of `case`); other columns are trimmed to it. */
static int trim(rd_sweep_table *t, rd_error *err)
{
    hsize_t dims[2];
    hid_t sp = H5Dget_space(t->col[t->ncols - 1].dset);
    H5Sget_simple_extent_dims(sp, dims, NULL);
    H5Sclose(sp);
    t->rows = (long)dims[0];
    for (int i = 0; i < t->ncols; i++) {
        hsize_t d[2] = { dims[0], (hsize_t)t->col[i].width };
        if (H5Dset_extent(t->col[i].dset, d) < 0) return h5fail(t, err, "cannot trim a column");
    }
    return 0;
}

/* Lines of text as one line in buf (n bytes): joined by "; ", the last newline dropped. */
static const char *one_line(const char *text, char *buf, size_t n)
{
    size_t k = 0;
    for (const char *c = text; *c && k + 3 < n; c++) {
        if (*c != '\n')
            buf[k++] = *c;
        else if (c[1]) {
            buf[k++] = ';';
            buf[k++] = ' ';
        }
    }
    buf[k] = '\0';
    return buf;
}

/* The table's root attribute `attr` must read `now`. `what` says what differs: the axes and
 * overrides (quoted from the table in the message), or NULL for the scenario text (too long to
 * quote). */
static int check_same(rd_sweep_table *t, const char *attr, const char *now, const char *what,
                      rd_error *err)
{
    char *was = attr_read(t->file, attr);
    int same = was && !strcmp(was, now);
    char had[RD_ERROR_MAX / 2];
    if (!same && !was)
        rd_error_set(err,
                     "rockdem sweep: %s: not a sweep table of rockdem (no '%s' attribute); "
                     "choose another -o",
                     t->path, attr);
    else if (!same && what)
        rd_error_set(err,
                     "rockdem sweep: %s holds a sweep with other %s (it has: %s); re-run with "
                     "the same ones or choose another -o",
                     t->path, what, one_line(was, had, sizeof had));
    else if (!same)
        rd_error_set(err,
                     "rockdem sweep: %s holds a sweep of another scenario text; re-run with the "
                     "scenario it was made with or choose another -o",
                     t->path);
    free(was);
    return same ? 0 : -1;
}

static const column *find_col(const rd_sweep_table *t, const char *name)
{
    for (int i = 0; i < t->ncols; i++)
        if (t->col[i].axis < 0 && !strcmp(t->col[i].name, name)) return &t->col[i];
    return NULL;
}

/* Shorten every column to t->rows. */
static int set_rows(rd_sweep_table *t, rd_error *err)
{
    for (int i = 0; i < t->ncols; i++) {
        hsize_t d[2] = { (hsize_t)t->rows, (hsize_t)t->col[i].width };
        if (H5Dset_extent(t->col[i].dset, d) < 0) return h5fail(t, err, "cannot trim a column");
    }
    return 0;
}

/* Every committed row's swept values must be its case's values in the plan: a row whose
 * values belong to another case (a table reordered in place by an older rockdem and killed
 * mid-way, or edited) is damage, refused with one line. k: the rows' cases. 0 or -1. */
static int verify_axes(rd_sweep_table *t, const long *k, long n, rd_error *err)
{
    for (int i = 0; i < t->ncols; i++) {
        const column *c = &t->col[i];
        if (c->axis < 0 || n == 0) continue;
        const rd_sweep_axis *a = &t->plan->axis[c->axis];
        char *v = malloc(c->size * (size_t)n);
        if (!v || H5Dread(c->dset, c->mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) {
            free(v);
            return h5fail(t, err, "cannot read a swept-value column");
        }
        long bad = -1;
        for (long r = 0; r < n && bad < 0; r++) {
            int x = rd_sweep_value_index(t->plan, k[r], c->axis);
            const char *cellv = v + c->size * (size_t)r;
            double num;
            if (a->number) memcpy(&num, cellv, sizeof num);
            if (a->number ? num != a->number[x]
                          : strncmp(cellv, a->value[x], RD_SWEEP_TEXT - 1) != 0)
                bad = r;
        }
        free(v);
        if (bad >= 0)
            return rd_error_set(
                err,
                "rockdem sweep: %s is damaged: row %ld (case %ld) holds a '%s' value of another "
                "case; choose another -o (the table cannot be resumed)",
                t->path, bad, k[bad], c->name);
    }
    return 0;
}

/* Mark done[] from the committed rows, checking each case's hash. Trailing rows that do not
 * match (partially written) are dropped; a mismatch before a good row is another sweep's. */
static int read_done(rd_sweep_table *t, char *done, rd_error *err)
{
    const column *ck = find_col(t, "case"), *ch = find_col(t, "hash");
    long n = t->rows;
    long *k = malloc((size_t)(n > 0 ? n : 1) * sizeof *k);
    unsigned long long *h = malloc((size_t)(n > 0 ? n : 1) * sizeof *h);
    int rc = !k || !h ? h5fail(t, err, "out of memory") : 0;
    if (!rc && n > 0 &&
        (H5Dread(ck->dset, ck->mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, k) < 0 ||
         H5Dread(ch->dset, ch->mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, h) < 0))
        rc = h5fail(t, err, "cannot read the case and hash columns");
    while (!rc && n > 0 &&
           (k[n - 1] < 0 || k[n - 1] >= t->plan->ncases ||
            h[n - 1] != rd_sweep_hash(t->plan, k[n - 1])))
        n--, t->dropped++;
    if (!rc && t->dropped) {
        t->rows = n;
        rc = set_rows(t, err) || flush_table(t)
                 ? h5fail_errno(t, err, "cannot drop the partially written rows")
                 : 0;
    }
    for (long i = 0; !rc && i < n; i++) {
        if (k[i] < 0 || k[i] >= t->plan->ncases || h[i] != rd_sweep_hash(t->plan, k[i]))
            rc = rd_error_set(err,
                              "rockdem sweep: %s: row %ld (case %ld) does not match this sweep's "
                              "overrides; choose another -o",
                              t->path, i, k[i]);
        else if (done[k[i]])
            rc = rd_error_set(err,
                              "rockdem sweep: %s is damaged: case %ld is in two rows; choose "
                              "another -o (the table cannot be resumed)",
                              t->path, k[i]);
        else
            done[k[i]] = 1;
    }
    if (!rc) rc = verify_axes(t, k, n, err);
    free(k);
    free(h);
    return rc;
}

static int open_table(rd_sweep_table *t, char *done, rd_error *err)
{
    htri_t is = H5Fis_hdf5(t->path);
    if (is <= 0) return h5fail(t, err, "exists and is not an HDF5 file; choose another -o");
    errno = 0;
    t->file = H5Fopen(t->path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (t->file < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
        return rd_error_set(err, "rockdem sweep: %s: cannot resume it: %s", t->path,
                            RD_PATH_LOCKED);
    if (t->file < 0 || get_fd(t, err)) return h5fail_errno(t, err, "cannot open for writing");
    if (check_same(t, "axes", t->plan->axes_text, "axes or --set overrides", err) ||
        check_same(t, "scenario", t->plan->text, NULL, err))
        return -1;
    if ((t->group = H5Gopen2(t->file, "sweep", H5P_DEFAULT)) < 0)
        return h5fail(t, err, "no /sweep group");
    int layout = 0;
    if (H5Aexists(t->group, "layout_version") <= 0 ||
        H5LTget_attribute_int(t->group, ".", "layout_version", &layout) < 0 ||
        layout != RD_SWEEP_LAYOUT)
        return h5fail(t, err,
                      "was written by an older rockdem (another table layout); choose another -o");
    for (int i = 0; i < t->ncols; i++)
        if ((t->col[i].dset = H5Dopen2(t->group, t->col[i].name, H5P_DEFAULT)) < 0)
            return h5fail(t, err, "a column of /sweep is missing");
    return trim(t, err) || read_done(t, done, err) ? -1 : 0;
}

/* A table handle for plan p at path, with its types and column layout; no file yet. */
static rd_sweep_table *new_table(const char *path, const rd_sweep_plan *p)
{
    rd_sweep_table *t = calloc(1, sizeof *t);
    if (!t) return NULL;
    snprintf(t->path, sizeof t->path, "%s", path);
    t->plan = p;
    t->file = t->group = t->fd = -1;
    t->str = H5Tcopy(H5T_C_S1);
    H5Tset_size(t->str, RD_SWEEP_TEXT);
    H5Tset_cset(t->str, H5T_CSET_UTF8);
    t->vstr = H5Tcopy(H5T_C_S1);
    H5Tset_size(t->vstr, H5T_VARIABLE);
    H5Tset_cset(t->vstr, H5T_CSET_UTF8);
    t->status_t = H5Tenum_create(H5T_NATIVE_UCHAR);
    for (unsigned char v = 0; v <= RD_STATUS_UNTRUSTED; v++)
        H5Tenum_insert(t->status_t, rd_status_name((rd_status)v), &v);
    layout(t);
    return t;
}

static void sweep_table_close(rd_sweep_table *t);

static rd_sweep_table *sweep_table_open(const char *path, const rd_sweep_plan *p, char *done,
                                        rd_error *err)
{
    if (rd_path_same(path, p->path)) {
        rd_error_set(err, "%s: cannot write the table there: it is the scenario file being read",
                     path);
        return NULL;
    }
    struct stat st;
    if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode)) {
        rd_error_set(
            err,
            "%s: cannot write the table there: it is a symbolic link (rockdem does not write "
            "through links: remove it or give the file's own path)",
            path);
        return NULL;
    }
    if (rd_path_special(path)) {
        rd_error_set(err, "%s: cannot write the table there: " RD_PATH_NOT_FILE, path);
        return NULL;
    }
    rd_sweep_table *t = new_table(path, p);
    if (!t) {
        rd_error_set(err, "rockdem sweep: out of memory");
        return NULL;
    }
    FILE *f = fopen(path, "rb");
    int rc = f ? open_table(t, done, err) : create_table(t, 1, err);
    if (f) fclose(f);
    if (rc) {
        rd_sweep_table_close(t);
        return NULL;
    }
    return t;
}

/* Bytes of one row of column c from result r. */
static void cell(const rd_sweep_table *t, const column *c, const rd_sweep_result *r, char *buf)
{
    memset(buf, 0, c->size * (size_t)c->width);
    if (c->axis >= 0) {
        const rd_sweep_axis *a = &t->plan->axis[c->axis];
        int v = rd_sweep_value_index(t->plan, r->index, c->axis);
        if (a->number)
            memcpy(buf, &a->number[v], sizeof(double));
        else
            snprintf(buf, RD_SWEEP_TEXT, "%s", a->value[v]);
    } else if (c->spec->type == C_STATUS) {
        buf[0] = (char)(r->status >= 0 && r->status <= RD_STATUS_UNTRUSTED ? r->status
                                                                           : RD_STATUS_ERROR);
    } else {
        size_t n = c->spec->per_body == PER_FENCE ? (size_t)t->plan->nfences
                   : c->spec->per_body            ? (size_t)t->plan->nbodies
                                                  : 1;
        memcpy(buf, (const char *)r + c->spec->off, n * c->size);
    }
}

/* A write failed inside HDF5 (past the reserve): shrink every column back to the committed
 * rows, so that no partial row stays, and report the system's reason. Returns -1. */
static int undo_row(rd_sweep_table *t, rd_error *err, const char *what)
{
    h5fail_errno(t, err, what);
    rd_error ignored;
    if (set_rows(t, &ignored) == 0) flush_table(t);
    return -1;
}

static int sweep_table_append(rd_sweep_table *t, const rd_sweep_result *r, rd_error *err)
{
    char buf[RD_SWEEP_BODIES * sizeof(double) + RD_SWEEP_TEXT];
    size_t chunks = 0; /* bytes of one new chunk of every column, when this row starts one */
    for (int i = 0; i < t->ncols && t->rows % RD_SWEEP_CHUNK == 0; i++)
        chunks += RD_SWEEP_CHUNK * t->col[i].size * (size_t)t->col[i].width;
    if (reserve(t, chunks, err)) return -1;
    errno = 0;
    for (int i = 0; i < t->ncols; i++) {
        column *c = &t->col[i];
        hsize_t d[2] = { (hsize_t)t->rows + 1, (hsize_t)c->width },
                start[2] = { (hsize_t)t->rows, 0 };
        hsize_t count[2] = { 1, (hsize_t)c->width };
        int rank = c->spec && c->spec->per_body ? 2 : 1;
        cell(t, c, r, buf);
        if (H5Dset_extent(c->dset, d) < 0) return undo_row(t, err, "cannot extend a column");
        hid_t fs = H5Dget_space(c->dset), ms = H5Screate_simple(rank, count, NULL);
        H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL);
        herr_t w = H5Dwrite(c->dset, c->mtype, ms, fs, H5P_DEFAULT, buf);
        H5Sclose(ms);
        H5Sclose(fs);
        if (w < 0) return undo_row(t, err, "cannot write a row");
    }
    if (flush_table(t)) return undo_row(t, err, "cannot flush");
    t->rows++;
    return 0;
}

long rd_sweep_table_rows(const rd_sweep_table *t) { return t->rows; }

long rd_sweep_table_dropped(const rd_sweep_table *t) { return t->dropped; }

static int cmp_key(const void *a, const void *b)
{
    const long *x = a, *y = b;
    return (x[0] > y[0]) - (x[0] < y[0]);
}

/* Copy every column of t into the new table u, row i of u = row perm[i] of t. 0 or -1. */
static int copy_sorted(rd_sweep_table *t, rd_sweep_table *u, const long *perm, rd_error *err)
{
    size_t bytes = 0;
    for (int i = 0; i < t->ncols; i++)
        bytes += t->col[i].size * (size_t)t->col[i].width * (size_t)t->rows;
    if (reserve(u, 2 * bytes, err))
        return -1; /* the data and its chunk rounding, before HDF5 writes */
    for (int i = 0; i < t->ncols; i++) {
        column *c = &t->col[i];
        size_t row = c->size * (size_t)c->width;
        hsize_t d[2] = { (hsize_t)t->rows, (hsize_t)c->width };
        char *a = malloc(row * (size_t)t->rows), *b = malloc(row * (size_t)t->rows);
        int rc =
            a && b && H5Dread(c->dset, c->mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, a) >= 0 ? 0 : -1;
        for (long r = 0; !rc && r < t->rows; r++)
            memcpy(b + (size_t)r * row, a + (size_t)perm[r] * row, row);
        errno = 0;
        if (!rc && (H5Dset_extent(u->col[i].dset, d) < 0 ||
                    H5Dwrite(u->col[i].dset, c->mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, b) < 0))
            rc = -1;
        free(a);
        free(b);
        if (rc) return h5fail_errno(u, err, "cannot write the sorted rows");
        rd_fault_point("sweep-sort-column");
    }
    return flush_table(u) ? h5fail_errno(u, err, "cannot flush") : 0;
}

/* Reorder the rows by perm (new row i = old row perm[i]) out of place: the sorted table is
 * written whole to a temporary beside t->path and renamed over it, so a kill or a fault at any
 * instant leaves the unsorted table (every row whole; resume sorts it) or the sorted one. In
 * place, a kill between two columns left rows whose swept values belonged to other cases. */
static int permute(rd_sweep_table *t, const long *perm, rd_error *err)
{
    char tmp[RD_PATH_MAX];
    int fd = rd_path_temp(t->path, tmp);
    if (fd < 0)
        return h5fail_errno(t, err, "cannot create a temporary file beside it to sort the rows");
    close(fd);
    rd_sweep_table *u = new_table(tmp, t->plan);
    int rc = !u ? h5fail(t, err, "out of memory")
                : create_table(u, 0, err) || copy_sorted(t, u, perm, err);
    sweep_table_close(u);
    rd_fault_point("sweep-sort-rename");
    if (!rc && rd_path_commit(tmp, t->path))
        rc = h5fail_errno(t, err, "cannot rename the sorted table into place");
    if (rc) {
        unlink(tmp);
        char why[RD_ERROR_MAX];
        snprintf(why, sizeof why, "%s", err->msg);
        return rd_error_set(
            err, "%s (the table keeps its rows unsorted; the same command sorts them)", why);
    }
    rd_fault_point("sweep-sort-renamed");
    return 0;
}

static int sweep_table_sort(rd_sweep_table *t, rd_error *err)
{
    const column *ck = &t->col[t->ncols - 1];
    long n = t->rows, *k = malloc((size_t)(n > 0 ? n : 1) * sizeof *k),
         *kv = malloc((size_t)(n > 0 ? n : 1) * 2 * sizeof *kv);
    int rc =
        k && kv && (n == 0 || H5Dread(ck->dset, ck->mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, k) >= 0)
            ? 0
            : -1;
    int sorted = 1;
    for (long i = 0; !rc && i < n; i++) {
        kv[2 * i] = k[i];
        kv[2 * i + 1] = i;
        if (i && k[i] < k[i - 1]) sorted = 0;
    }
    if (!rc && !sorted) {
        qsort(kv, (size_t)n, 2 * sizeof *kv, cmp_key);
        for (long i = 0; i < n; i++) k[i] = kv[2 * i + 1];
        rc = permute(t, k, err);
    } else if (rc) {
        h5fail(t, err, "cannot read the case column");
    }
    free(k);
    free(kv);
    return rc;
}

static void sweep_table_close(rd_sweep_table *t)
{
    if (!t) return;
    for (int i = 0; i < t->ncols; i++)
        if (t->col[i].dset >= 0) H5Dclose(t->col[i].dset);
    if (t->group >= 0) H5Gclose(t->group);
    if (t->file >= 0) H5Fclose(t->file);
    H5Tclose(t->str);
    H5Tclose(t->vstr);
    H5Tclose(t->status_t);
    free(t);
}

/* ---- the entry points: HDF5 error printing off around each (io/h5_quiet.h) ---- */

rd_sweep_table *rd_sweep_table_open(const char *path, const rd_sweep_plan *p, char *done,
                                    rd_error *err)
{
    RD_H5_QUIETLY(rd_sweep_table *, sweep_table_open(path, p, done, err));
}

int rd_sweep_table_append(rd_sweep_table *t, const rd_sweep_result *r, rd_error *err)
{
    RD_H5_QUIETLY(int, sweep_table_append(t, r, err));
}

int rd_sweep_table_sort(rd_sweep_table *t, rd_error *err)
{
    RD_H5_QUIETLY(int, sweep_table_sort(t, err));
}

void rd_sweep_table_close(rd_sweep_table *t)
{
    rd_h5_quiet q = rd_h5_quiet_begin();
    sweep_table_close(t);
    rd_h5_quiet_end(q);
}
