/* rockdem — tests for the HDF5 writer: write known values, read them back with the HDF5 C API. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>

#include <dirent.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/io_hdf5.h"
#include "io/io_bodies.h"

#define NB       2
#define NSAMPLES 1000
#define SCENARIO                                                                                   \
    "; test scenario\nblock create brick size 1 1 2 name 'left'\n"                                 \
    "model solve time 30\n"

typedef struct fixture {
    char dir[64];
    char path[128];
} fixture;

static const double cube_vertices[8][3] = { { -0.5, -0.5, -1 }, { 0.5, -0.5, -1 }, { 0.5, 0.5, -1 },
                                            { -0.5, 0.5, -1 },  { -0.5, -0.5, 1 }, { 0.5, -0.5, 1 },
                                            { 0.5, 0.5, 1 },    { -0.5, 0.5, 1 } };
static const int cube_faces[12][3] = { { 0, 2, 1 }, { 0, 3, 2 }, { 4, 5, 6 }, { 4, 6, 7 },
                                       { 0, 1, 5 }, { 0, 5, 4 }, { 1, 2, 6 }, { 1, 6, 5 },
                                       { 2, 3, 7 }, { 2, 7, 6 }, { 3, 0, 4 }, { 3, 4, 7 } };

/* The value written for sample k, series s, body b, component c (exact in binary). */
static double val(int k, int s, int b, int c) { return k * 1024.0 + s * 64.0 + b * 8.0 + c + 0.25; }

static rd_h5_meta make_meta(rd_h5_body *bodies)
{
    static const char *names[NB] = { "left", "right" };
    for (int i = 0; i < NB; i++) {
        bodies[i] = (rd_h5_body){
            names[i], 2000.0 + i,           { 1, 2, 3 }, { 1, 1, 2 },       0.4636 + i,
            8,        &cube_vertices[0][0], 12,          &cube_faces[0][0], 0,
            { 0 },    { 1, 0, 0, 0 }
        };
    }
    return (rd_h5_meta){ SCENARIO,
                         "test.dat",
                         "writer test",
                         1e-5,
                         4e-5,
                         "viscous 0.05",
                         "tilt-ratio 1.5",
                         1e10,
                         1e9,
                         0.6981317007977318,
                         0,
                         0,
                         0.1,
                         NB,
                         bodies,
                         0,
                         NULL,
                         NULL };
}

static void append_range(rd_h5 *h, int from, int to)
{
    double pos[NB][3], quat[NB][4], vel[NB][3], om[NB][3], tilt[NB];
    rd_error err = { { 0 } };
    for (int k = from; k < to; k++) {
        rd_h5_sample s = { .time = k * 0.5,
                           .position = &pos[0][0],
                           .quaternion = &quat[0][0],
                           .velocity = &vel[0][0],
                           .angular_velocity = &om[0][0],
                           .tilt = tilt };
        for (int b = 0; b < NB; b++) {
            for (int c = 0; c < 4; c++) quat[b][c] = val(k, 1, b, c);
            for (int c = 0; c < 3; c++) {
                pos[b][c] = val(k, 0, b, c);
                vel[b][c] = val(k, 2, b, c);
                om[b][c] = val(k, 3, b, c);
            }
            tilt[b] = val(k, 4, b, 0);
        }
        for (int c = 0; c < 3; c++) {
            s.ground_acc[c] = val(k, 5, 0, c);
            s.ground_vel[c] = val(k, 6, 0, c);
            s.ground_disp[c] = val(k, 7, 0, c);
        }
        for (int e = 0; e < RD_NENERGY; e++) s.energy[e] = val(k, 8 + e, 0, 0);
        assert_int_equal(rd_h5_append(h, &s, &err), 0);
    }
}

/* A summary whose bodies are stored in body[] (the caller's). */
static rd_summary make_summary(double scale, rd_body_summary body[NB])
{
    rd_summary s;
    memset(&s, 0, sizeof s);
    memset(body, 0, NB * sizeof *body);
    s.nbodies = NB;
    s.body = body;
    /* listed in the opposite order to /bodies/names: the writer must reorder by name */
    for (int b = 0; b < NB; b++) {
        rd_body_summary *bs = &body[NB - 1 - b];
        snprintf(bs->name, sizeof bs->name, "%s", b == 0 ? "left" : "right");
        bs->overturned = b;
        bs->overturn_time = b ? 12.5 * scale : -1;
        bs->max_tilt = 0.1 * (b + 1) * scale;
        bs->alpha = 0.5 + b;
        bs->max_tilt_ratio = bs->max_tilt / bs->alpha;
        bs->max_slide = 0.01 * (b + 1) * scale;
        bs->final_slide = 0.005 * (b + 1);
        bs->uplifted = 1;
        bs->slid = b;
    }
    s.any_overturned = 1;
    s.end_time = 30 * scale;
    s.dt = 1e-5;
    s.dt_critical = 4e-5;
    s.steps = 3000000L;
    s.settle_time = 0.5;
    s.energy_residual_max = 1e-3;
    s.wall_seconds = 2.5 * scale;
    s.status = scale > 1 ? RD_STATUS_INTERRUPTED : RD_STATUS_OVERTURNED;
    return s;
}

/* ---- readers ---- */

static hsize_t read_all(hid_t f, const char *name, double **out, int rank_expected,
                        const hsize_t *inner)
{
    int rank = -1;
    assert_true(H5LTget_dataset_ndims(f, name, &rank) >= 0);
    assert_int_equal(rank, rank_expected);
    hsize_t dims[3] = { 0, 0, 0 };
    assert_true(H5LTget_dataset_info(f, name, dims, NULL, NULL) >= 0);
    size_t n = dims[0];
    for (int k = 1; k < rank; k++) {
        assert_int_equal(dims[k], inner[k - 1]);
        n *= dims[k];
    }
    *out = malloc((n ? n : 1) * sizeof **out);
    assert_non_null(*out);
    assert_true(H5LTread_dataset_double(f, name, *out) >= 0);
    return dims[0];
}

static void read_str_attr(hid_t loc, const char *obj, const char *name, char *buf, size_t size)
{
    hid_t a = H5Aopen_by_name(loc, obj, name, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(a >= 0);
    hid_t ft = H5Aget_type(a);
    assert_int_equal(H5Tget_class(ft), H5T_STRING);
    hid_t mt = H5Tcopy(ft); /* same character set */
    if (H5Tis_variable_str(ft) > 0) {
        char *s = NULL;
        assert_true(H5Aread(a, mt, &s) >= 0);
        snprintf(buf, size, "%s", s);
        H5free_memory(s);
    } else {
        size_t n = H5Tget_size(ft);
        assert_true(n < size);
        H5Tset_size(mt, n + 1);
        assert_true(H5Aread(a, mt, buf) >= 0);
    }
    H5Tclose(mt);
    H5Tclose(ft);
    H5Aclose(a);
}

static double attr_d(hid_t loc, const char *obj, const char *name)
{
    double v = 0;
    assert_true(H5LTget_attribute_double(loc, obj, name, &v) >= 0);
    return v;
}

static void check_str_attr(hid_t loc, const char *obj, const char *name, const char *want)
{
    char buf[1024];
    read_str_attr(loc, obj, name, buf, sizeof buf);
    assert_string_equal(buf, want);
}

/* Checks every series holds n samples, equal to those written by append_range. */
static void check_series(hid_t f, hsize_t n)
{
    static const char *names[] = { "/position", "/quaternion", "/velocity", "/angular_velocity" };
    static const int series[] = { 0, 1, 2, 3 }, width[] = { 3, 4, 3, 3 };
    double *d;
    assert_int_equal(read_all(f, "/time", &d, 1, NULL), n);
    for (hsize_t k = 0; k < n; k++) assert_true(d[k] == k * 0.5);
    free(d);
    for (int i = 0; i < 4; i++) {
        hsize_t inner[2] = { NB, (hsize_t)width[i] };
        assert_int_equal(read_all(f, names[i], &d, 3, inner), n);
        for (hsize_t k = 0; k < n; k++)
            for (int b = 0; b < NB; b++)
                for (int c = 0; c < width[i]; c++)
                    assert_true(d[(k * NB + b) * width[i] + c] == val(k, series[i], b, c));
        free(d);
    }
    hsize_t nb = NB, three = 3;
    assert_int_equal(read_all(f, "/tilt", &d, 2, &nb), n);
    for (hsize_t k = 0; k < n; k++)
        for (int b = 0; b < NB; b++) assert_true(d[k * NB + b] == val(k, 4, b, 0));
    free(d);
    const char *ground[3] = { "/ground/acceleration", "/ground/velocity", "/ground/displacement" };
    for (int g = 0; g < 3; g++) {
        assert_int_equal(read_all(f, ground[g], &d, 2, &three), n);
        for (hsize_t k = 0; k < n; k++)
            for (int c = 0; c < 3; c++) assert_true(d[k * 3 + c] == val(k, 5 + g, 0, c));
        free(d);
    }
    for (int e = 0; e < RD_NENERGY; e++) {
        char name[64];
        snprintf(name, sizeof name, "/energy/%s", rd_energy_names[e]);
        assert_int_equal(read_all(f, name, &d, 1, NULL), n);
        for (hsize_t k = 0; k < n; k++) assert_true(d[k] == val(k, 8 + e, 0, 0));
        free(d);
    }
}

typedef struct event_row {
    double time;
    int body;
    char name[RD_NAME_MAX]; /* body name, "" for the whole scene */
    char type[16];
    double value;
} event_row;

/* Column col of /events as doubles (n rows). */
static void read_event_column(hid_t f, const char *col, hid_t mtype, void *out)
{
    char path[64];
    snprintf(path, sizeof path, "/events/%s", col);
    hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
    assert_true(d >= 0);
    assert_true(H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) >= 0);
    H5Dclose(d);
}

/* The /events group's columns as rows; type read through the file's enum (names). */
static hsize_t read_events(hid_t f, event_row *rows, hsize_t max)
{
    hsize_t n = 0;
    assert_true(H5LTget_dataset_info(f, "/events/time", &n, NULL, NULL) >= 0);
    assert_true(n <= max);
    if (!n) return 0;
    double t[16], v[16];
    int b[16];
    char *names[16];
    unsigned char ty[16];
    assert_true(n <= 16);
    read_event_column(f, "time", H5T_NATIVE_DOUBLE, t);
    read_event_column(f, "value", H5T_NATIVE_DOUBLE, v);
    read_event_column(f, "body_index", H5T_NATIVE_INT, b);
    hid_t st = H5Tcopy(H5T_C_S1);
    H5Tset_size(st, H5T_VARIABLE);
    read_event_column(f, "body", st, names);
    hid_t d = H5Dopen2(f, "/events/type", H5P_DEFAULT);
    hid_t et = H5Dget_type(d);
    assert_int_equal(H5Tget_class(et), H5T_ENUM);
    assert_true(H5Dread(d, H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, ty) >= 0);
    for (hsize_t k = 0; k < n; k++) {
        rows[k].time = t[k];
        rows[k].value = v[k];
        rows[k].body = b[k];
        snprintf(rows[k].name, sizeof rows[k].name, "%s", names[k]);
        assert_true(H5Tenum_nameof(et, &ty[k], rows[k].type, sizeof rows[k].type) >= 0);
        H5free_memory(names[k]);
    }
    H5Tclose(et);
    H5Dclose(d);
    H5Tclose(st);
    return n;
}

/* The name of the enum attribute obj@name. */
static void check_enum_attr(hid_t f, const char *obj, const char *name, const char *want)
{
    hid_t a = H5Aopen_by_name(f, obj, name, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(a >= 0);
    hid_t t = H5Aget_type(a);
    assert_int_equal(H5Tget_class(t), H5T_ENUM);
    unsigned char v = 0;
    char buf[32];
    assert_true(H5Aread(a, H5T_NATIVE_UCHAR, &v) >= 0);
    assert_true(H5Tenum_nameof(t, &v, buf, sizeof buf) >= 0);
    assert_string_equal(buf, want);
    H5Tclose(t);
    H5Aclose(a);
}

static void check_summary(hid_t f, double scale)
{
    rd_body_summary wb[NB];
    rd_summary want = make_summary(scale, wb);
    check_enum_attr(f, "/summary", "status", scale > 1 ? "interrupted" : "overturned");
    check_str_attr(f, "/summary", "max_slide_units", "m");
    int i = 0;
    long steps = 0;
    assert_true(H5LTget_attribute_int(f, "/summary", "any_overturned", &i) >= 0);
    assert_int_equal(i, 1);
    assert_true(H5LTget_attribute_long(f, "/summary", "steps", &steps) >= 0);
    assert_int_equal(steps, want.steps);
    assert_true(attr_d(f, "/summary", "end_time") == want.end_time);
    assert_true(attr_d(f, "/summary", "dt") == want.dt);
    assert_true(attr_d(f, "/summary", "settle_time") == want.settle_time);
    assert_true(attr_d(f, "/summary", "energy_residual_max") == want.energy_residual_max);
    assert_true(attr_d(f, "/summary", "wall_seconds") == want.wall_seconds);
    double d[NB];
    int n[NB];
    /* /bodies/names is left, right; make_summary stores them as right, left */
    assert_true(H5LTget_attribute_double(f, "/summary", "max_tilt", d) >= 0);
    assert_true(d[0] == want.body[1].max_tilt && d[1] == want.body[0].max_tilt);
    assert_true(H5LTget_attribute_double(f, "/summary", "overturn_time", d) >= 0);
    assert_true(d[0] == -1 && d[1] == 12.5 * scale);
    assert_true(H5LTget_attribute_double(f, "/summary", "max_slide", d) >= 0);
    assert_true(d[0] == want.body[1].max_slide && d[1] == want.body[0].max_slide);
    assert_true(H5LTget_attribute_double(f, "/summary", "max_tilt_ratio", d) >= 0);
    assert_true(d[0] == want.body[1].max_tilt_ratio);
    assert_true(H5LTget_attribute_double(f, "/summary", "alpha", d) >= 0);
    assert_true(d[0] == 0.5 && d[1] == 1.5);
    assert_true(H5LTget_attribute_double(f, "/summary", "final_slide", d) >= 0);
    assert_true(d[0] == 0.005 && d[1] == 0.01);
    assert_true(H5LTget_attribute_int(f, "/summary", "overturned", n) >= 0);
    assert_true(n[0] == 0 && n[1] == 1);
    assert_true(H5LTget_attribute_int(f, "/summary", "uplifted", n) >= 0);
    assert_true(n[0] == 1 && n[1] == 1);
    assert_true(H5LTget_attribute_int(f, "/summary", "slid", n) >= 0);
    assert_true(n[0] == 0 && n[1] == 1);
}

static void check_root(hid_t f)
{
    check_str_attr(f, "/", "program", "rockdem");
    check_str_attr(f, "/", "version", RD_VERSION);
    check_str_attr(f, "/", "scenario", SCENARIO);
    check_str_attr(f, "/", "scenario_file", "test.dat");
    check_str_attr(f, "/", "title", "writer test");
    check_str_attr(f, "/", "damping", "viscous 0.05");
    check_str_attr(f, "/", "overturn_criterion", "tilt-ratio 1.5");
    assert_true(attr_d(f, "/", "dt") == 1e-5);
    assert_true(attr_d(f, "/", "dt_critical") == 4e-5);
    assert_true(attr_d(f, "/", "kn") == 1e10);
    assert_true(attr_d(f, "/", "ks") == 1e9);
    assert_true(fabs(attr_d(f, "/", "friction_deg") - 40.0) < 1e-12);
    assert_true(attr_d(f, "/", "cohesion") == 0);
    assert_true(attr_d(f, "/", "tension") == 0);
    assert_true(attr_d(f, "/", "spacing") == 0.1);
    check_enum_attr(f, "/", "spacing_rule", "fixed");
    check_str_attr(f, "/", "spacing_units", "m");
    check_str_attr(f, "/", "kn_units", "Pa/m");
    check_str_attr(f, "/", "Conventions", "rockdem-3");
    int layout = 0;
    assert_true(H5LTget_attribute_int(f, "/", "layout_version", &layout) >= 0);
    assert_int_equal(layout, 3);
    check_str_attr(f, "/time", "units", "s");
    check_str_attr(f, "/energy/kinetic", "units", "J");
    check_str_attr(f, "/position", "long_name", "centre of mass, ground frame");
}

static void check_bodies(hid_t f)
{
    char *names[NB];
    hid_t d = H5Dopen2(f, "/bodies/names", H5P_DEFAULT);
    hid_t ft = H5Dget_type(d);
    assert_true(H5Tis_variable_str(ft) > 0);
    assert_int_equal(H5Tget_cset(ft), H5T_CSET_UTF8);
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    assert_true(H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, names) >= 0);
    H5Tclose(t);
    H5Tclose(ft);
    H5Dclose(d);
    assert_string_equal(names[0], "left");
    assert_string_equal(names[1], "right");
    H5free_memory(names[0]);
    H5free_memory(names[1]);
    /* one row per block (left, right), the geometry concatenated in block order */
    double *v;
    hsize_t three = 3, four = 4;
    assert_int_equal(read_all(f, "/bodies/mass", &v, 1, NULL), NB);
    assert_true(v[0] == 2000.0 && v[1] == 2001.0);
    free(v);
    /* the summary's alpha (support polygon at rest) replaces the brick estimate 1.4636 */
    assert_int_equal(read_all(f, "/bodies/alpha", &v, 1, NULL), NB);
    assert_true(v[0] == 0.5 && v[1] == 1.5);
    free(v);
    assert_int_equal(read_all(f, "/bodies/inertia_principal", &v, 2, &three), NB);
    assert_true(v[3] == 1 && v[4] == 2 && v[5] == 3);
    free(v);
    /* the sizes at rest replace those given at open (1 1 2) */
    assert_int_equal(read_all(f, "/bodies/size", &v, 2, &three), NB);
    assert_true(v[0] == 1.5 && v[1] == 1.5 && v[2] == 2 && v[3] == 2.5);
    free(v);
    assert_int_equal(read_all(f, "/bodies/quaternion", &v, 2, &four), NB);
    assert_true(v[0] == 1 && v[4] == 1);
    free(v);
    int ints[2 * NB];
    assert_true(H5LTread_dataset_int(f, "/bodies/fixed", ints) >= 0);
    assert_true(ints[0] == 0 && ints[1] == 0);
    assert_true(H5LTread_dataset_int(f, "/bodies/vertex_count", ints) >= 0);
    assert_true(ints[0] == 8 && ints[1] == 8);
    check_str_attr(f, "/bodies/vertex_count", "sample_dimension", "vertex");
    assert_int_equal(read_all(f, "/bodies/vertices", &v, 2, &three), 2 * 8);
    assert_memory_equal(v, cube_vertices, sizeof cube_vertices);
    assert_memory_equal(v + 24, cube_vertices, sizeof cube_vertices);
    free(v);
    int faces[2 * 12][3];
    assert_true(H5LTread_dataset_int(f, "/bodies/faces", &faces[0][0]) >= 0);
    assert_memory_equal(faces[12], cube_faces, sizeof cube_faces); /* local indices */
    /* precariousness: left 2 rows, right 1 */
    assert_true(H5LTread_dataset_int(f, "/bodies/lean_count", ints) >= 0);
    assert_true(ints[0] == 2 && ints[1] == 1);
    check_str_attr(f, "/bodies/lean_count", "sample_dimension", "lean");
    assert_int_equal(read_all(f, "/bodies/precariousness", &v, 2, &three), 3);
    assert_true(v[0] == 0 && v[4] == 0.5 && v[6] == 3 && v[8] == 9.81);
    free(v);
}

/* /position must be chunked with shuffle and deflate and unlimited in time. */
static void check_layout(hid_t f)
{
    hid_t d = H5Dopen2(f, "/position", H5P_DEFAULT);
    hid_t p = H5Dget_create_plist(d);
    assert_int_equal(H5Pget_layout(p), H5D_CHUNKED);
    int nf = H5Pget_nfilters(p), shuffle = 0, deflate = 0;
    for (int i = 0; i < nf; i++) {
        unsigned flags, cd[4];
        size_t ncd = 4;
        H5Z_filter_t id = H5Pget_filter2(p, (unsigned)i, &flags, &ncd, cd, 0, NULL, NULL);
        shuffle |= id == H5Z_FILTER_SHUFFLE;
        if (id == H5Z_FILTER_DEFLATE) deflate = (int)cd[0];
    }
    assert_true(shuffle);
    assert_int_equal(deflate, 4);
    hid_t sp = H5Dget_space(d);
    hsize_t dims[3], maxd[3];
    H5Sget_simple_extent_dims(sp, dims, maxd);
    assert_true(maxd[0] == H5S_UNLIMITED);
    H5Sclose(sp);
    /* axes: /time, /body, /xyz dimension scales */
    const char *axis[3] = { "/time", "/body", "/xyz" };
    for (unsigned k = 0; k < 3; k++) {
        hid_t sc = H5Dopen2(f, axis[k], H5P_DEFAULT);
        assert_true(H5DSis_scale(sc) > 0);
        assert_true(H5DSis_attached(d, sc, k) > 0);
        H5Dclose(sc);
    }
    H5Pclose(p);
    H5Dclose(d);
}

static hid_t reopen(const char *path)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    return f;
}

/* ---- fixture ---- */

static int setup(void **state)
{
    fixture *fx = calloc(1, sizeof *fx);
    if (!fx) return -1;
    snprintf(fx->dir, sizeof fx->dir, "/tmp/rd_h5_XXXXXX");
    if (!mkdtemp(fx->dir)) return -1;
    snprintf(fx->path, sizeof fx->path, "%s/out.h5", fx->dir);
    *state = fx;
    return 0;
}

static int teardown(void **state)
{
    fixture *fx = *state;
    DIR *dir = opendir(fx->dir);
    struct dirent *e;
    while (dir && (e = readdir(dir))) {
        char p[512];
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        snprintf(p, sizeof p, "%s/%s", fx->dir, e->d_name);
        unlink(p);
    }
    if (dir) closedir(dir);
    int rc = rmdir(fx->dir);
    free(fx);
    return rc;
}

/* ---- tests ---- */

static void test_roundtrip(void **state)
{
    fixture *fx = *state;
    rd_h5_body bodies[NB];
    rd_h5_meta meta = make_meta(bodies);
    rd_error err = { { 0 } };
    rd_h5 *h = rd_h5_open(fx->path, &meta, &err);
    assert_non_null(h);
    static const double prec_left[2][3] = { { 0, 0.5, 5 }, { 3.14, 0.5, 5 } };
    static const double prec_right[1][3] = { { 3, 1, 9.81 } };
    rd_h5_rest_body rest[NB] = { { { 1.5, 1.5, 2 }, 2, &prec_left[0][0] },
                                 { { 2.5, 2.5, 2 }, 1, &prec_right[0][0] } };
    assert_int_equal(rd_h5_bodies_rest(h, rest, NB, &err), 0);
    append_range(h, 0, 400);
    assert_int_equal(rd_h5_event(h, 1.25, 0, "uplift", 0.001, &err), 0);
    assert_int_equal(rd_h5_event(h, 2.5, 1, "overturn", 1.6, &err), 0);
    append_range(h, 400, NSAMPLES);
    assert_int_equal(rd_h5_event(h, 3.0, -1, "unsettled", -2.0, &err), 0);
    assert_int_equal(rd_h5_event(h, 3.0, -1, "no-such-event", -2.0, &err), -1);
    assert_non_null(strstr(err.msg, "unknown event type 'no-such-event'"));
    rd_body_summary sb[NB];
    rd_summary s = make_summary(1, sb);
    assert_int_equal(rd_h5_summary(h, &s, &err), 0);
    rd_h5_close(h);

    hid_t f = reopen(fx->path);
    check_series(f, NSAMPLES);
    check_root(f);
    check_bodies(f);
    check_layout(f);
    check_summary(f, 1);
    event_row ev[8];
    assert_int_equal(read_events(f, ev, 8), 3);
    assert_true(ev[0].time == 1.25 && ev[0].body == 0 && ev[0].value == 0.001);
    assert_string_equal(ev[0].type, "uplift");
    assert_string_equal(ev[0].name, "left");
    assert_true(ev[1].time == 2.5 && ev[1].body == 1 && ev[1].value == 1.6);
    assert_string_equal(ev[1].type, "overturn");
    assert_string_equal(ev[1].name, "right");
    assert_true(ev[2].body == -1 && ev[2].value == -2.0);
    assert_string_equal(ev[2].name, "");
    assert_string_equal(ev[2].type, "unsettled");
    H5Fclose(f);
}

/* A child that dies without closing the file must leave every flushed sample readable. */
static void test_crash_keeps_flushed(void **state)
{
    fixture *fx = *state;
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        rd_h5_body bodies[NB];
        rd_h5_meta meta = make_meta(bodies);
        rd_error err = { { 0 } };
        rd_h5 *h = rd_h5_open(fx->path, &meta, &err);
        if (!h) _exit(2);
        append_range(h, 0, 600);
        if (rd_h5_event(h, 0.5, 1, "impact", 3.0, &err) || rd_h5_flush(h, &err)) _exit(3);
        append_range(h, 600, 610); /* buffered only: lost with the process */
        _exit(1);
    }
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 1);

    hid_t f = reopen(fx->path);
    hsize_t dims[3] = { 0 };
    assert_true(H5LTget_dataset_info(f, "/time", dims, NULL, NULL) >= 0);
    assert_int_equal(dims[0], 600); /* the 10 unflushed samples died with the child */
    check_series(f, 600);
    check_root(f);
    event_row ev[4];
    assert_int_equal(read_events(f, ev, 4), 1);
    assert_string_equal(ev[0].type, "impact");
    assert_int_equal(H5Lexists(f, "/summary", H5P_DEFAULT), 0);
    H5Fclose(f);
}

/* Explicit flushes of partial buffers keep the samples in order. */
static void test_partial_flushes(void **state)
{
    fixture *fx = *state;
    rd_h5_body bodies[NB];
    rd_h5_meta meta = make_meta(bodies);
    rd_error err = { { 0 } };
    rd_h5 *h = rd_h5_open(fx->path, &meta, &err);
    assert_non_null(h);
    append_range(h, 0, 10);
    assert_int_equal(rd_h5_flush(h, &err), 0);
    assert_int_equal(rd_h5_flush(h, &err), 0);
    append_range(h, 10, 300);
    assert_int_equal(rd_h5_flush(h, &err), 0);
    append_range(h, 300, 301);
    rd_h5_close(h);
    hid_t f = reopen(fx->path);
    check_series(f, 301);
    event_row ev[1];
    assert_int_equal(read_events(f, ev, 1), 0);
    H5Fclose(f);
}

static void test_summary_twice_keeps_last(void **state)
{
    fixture *fx = *state;
    rd_h5_body bodies[NB];
    rd_h5_meta meta = make_meta(bodies);
    rd_error err = { { 0 } };
    rd_h5 *h = rd_h5_open(fx->path, &meta, &err);
    assert_non_null(h);
    append_range(h, 0, 5);
    rd_body_summary b1[NB], b2[NB];
    rd_summary s1 = make_summary(1, b1), s2 = make_summary(2, b2);
    assert_int_equal(rd_h5_summary(h, &s1, &err), 0);
    assert_int_equal(rd_h5_summary(h, &s2, &err), 0);
    rd_h5_close(h);
    hid_t f = reopen(fx->path);
    check_summary(f, 2);
    H5Fclose(f);
}

static void test_summary_unknown_body(void **state)
{
    fixture *fx = *state;
    rd_h5_body bodies[NB];
    rd_h5_meta meta = make_meta(bodies);
    rd_error err = { { 0 } };
    rd_h5 *h = rd_h5_open(fx->path, &meta, &err);
    assert_non_null(h);
    rd_body_summary sb[NB];
    rd_summary s = make_summary(1, sb);
    snprintf(sb[0].name, sizeof sb[0].name, "ghost"); /* was "right" */
    assert_int_equal(rd_h5_summary(h, &s, &err), -1);
    assert_non_null(strstr(err.msg, fx->path));
    assert_non_null(strstr(err.msg, "right"));
    rd_h5_close(h);
}

static void test_bad_event_body(void **state)
{
    fixture *fx = *state;
    rd_h5_body bodies[NB];
    rd_h5_meta meta = make_meta(bodies);
    rd_error err = { { 0 } };
    rd_h5 *h = rd_h5_open(fx->path, &meta, &err);
    assert_non_null(h);
    assert_int_equal(rd_h5_event(h, 0, NB, "slip", 0, &err), -1);
    assert_non_null(strstr(err.msg, "out of range"));
    rd_h5_close(h);
}

static void test_unwritable_path(void **state)
{
    fixture *fx = *state;
    char path[256];
    snprintf(path, sizeof path, "%s/no/such/dir/out.h5", fx->dir);
    rd_h5_body bodies[NB];
    rd_h5_meta meta = make_meta(bodies);
    rd_error err = { { 0 } };
    assert_null(rd_h5_open(path, &meta, &err));
    assert_non_null(strstr(err.msg, path));
    assert_non_null(strstr(err.msg, "cannot create file"));
}

static void test_bad_body_name(void **state)
{
    fixture *fx = *state;
    rd_h5_body bodies[NB];
    rd_h5_meta meta = make_meta(bodies);
    bodies[1].name = "a/b";
    rd_error err = { { 0 } };
    assert_null(rd_h5_open(fx->path, &meta, &err));
    assert_non_null(strstr(err.msg, "a/b"));
    bodies[1].name = "left"; /* duplicate */
    assert_null(rd_h5_open(fx->path, &meta, &err));
    assert_non_null(strstr(err.msg, fx->path));
}

static void test_close_null(void **state)
{
    (void)state;
    rd_h5_close(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_roundtrip, setup, teardown),
        cmocka_unit_test_setup_teardown(test_crash_keeps_flushed, setup, teardown),
        cmocka_unit_test_setup_teardown(test_partial_flushes, setup, teardown),
        cmocka_unit_test_setup_teardown(test_summary_twice_keeps_last, setup, teardown),
        cmocka_unit_test_setup_teardown(test_summary_unknown_body, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_event_body, setup, teardown),
        cmocka_unit_test_setup_teardown(test_unwritable_path, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_body_name, setup, teardown),
        cmocka_unit_test(test_close_null),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
