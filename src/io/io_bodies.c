/* rockdem — the /bodies group of a run file as whole tables (io_bodies.h).
 *
 * Layout 2 gave every body a group of its own (about 15 attributes, vertex and triangle tables,
 * a precariousness table and four dimension scales: 9 HDF5 objects per body), which was most
 * of a 10,000-brick wall's setup. Here every per-body quantity is one row of a table over the
 * `block` axis and the vertices, triangles and precariousness rows of all bodies are
 * concatenated in block order, each with a count per block (the CF conventions' contiguous
 * ragged array: the count variable names its `sample_dimension`): about 20 objects whatever
 * the bodies. Triangle indices stay local to their body, so a body's slice reads as before.
 * Folder io/ owns the HDF5 output file; it may call base/ and the public headers, never engine/
 * internals or cli/.
 */
#include "io/io_bodies.h"
#include "io/io_table.h"
#include "io/h5_quiet.h"

#include <stdlib.h>
#include <string.h>

/* Bytes a dataset's object header, its units, long_name and dimension-scale attributes take,
 * generously (as io/output_scene.c's RD_TABLE_HEADER), and the datasets of /bodies. */
#define RD_BODY_HEADER 4096
#define RD_BODY_TABLES 24
/* Bytes of one body's row in the per-block tables: its name in the global heap (with the
 * heap object's header), 19 numbers and 3 counts, generously. */
#define RD_BODY_ROW    (2 * RD_NAME_MAX + 256)

static const char prec_labels[] = "lean_direction,alpha,tip_acceleration";
static const char prec_units[] = "rad,rad,m/s^2";

static const rd_h5_body *body_of(const rd_h5_meta *m, int i)
{
    return i < m->nbodies ? &m->bodies[i] : &m->fixed_bodies[i - m->nbodies];
}

size_t rd_h5_bodies_bytes(const rd_h5_meta *m)
{
    size_t raw = RD_BODY_HEADER * RD_BODY_TABLES;
    for (int i = 0; i < m->nbodies + m->nfixed; i++) {
        const rd_h5_body *b = body_of(m, i);
        /* a vertex: 3 doubles and its index scale's int; a triangle: 3 ints and its index */
        raw += RD_BODY_ROW + (3 * sizeof(double) + sizeof(int)) * (size_t)b->nvert +
               4 * sizeof(int) * (size_t)b->ntri;
    }
    return raw + raw / 8;
}

/* The per-block columns and the concatenated vertex and triangle tables of m. */
typedef struct block_tables {
    int n;
    long nv, nf;
    const char **name;
    double *mass, *alpha, *inertia, *size, *position, *quaternion; /* [n], [n][3], [n][4] */
    int *fixed, *vcount, *fcount;                                  /* [n] */
    double *vertices;                                              /* [nv][3] */
    int *faces;                                                    /* [nf][3] */
} block_tables;

static void tables_free(block_tables *t)
{
    free(t->name);
    free(t->mass);
    free(t->vertices);
    free(t->faces);
    free(t->fixed);
}

/* One allocation for the doubles per block, one for the ints. 0 or -1. */
static int tables_alloc(block_tables *t, int n)
{
    size_t nn = (size_t)n + 1;
    t->n = n;
    t->name = calloc(nn, sizeof *t->name);
    t->mass = calloc(nn * 15, sizeof *t->mass); /* mass, alpha, inertia, size, position, q */
    t->fixed = calloc(nn * 3, sizeof *t->fixed);
    t->vertices = calloc((size_t)t->nv * 3 + 1, sizeof *t->vertices);
    t->faces = calloc((size_t)t->nf * 3 + 1, sizeof *t->faces);
    if (!t->name || !t->mass || !t->fixed || !t->vertices || !t->faces) return -1;
    t->alpha = t->mass + nn;
    t->inertia = t->alpha + nn;
    t->size = t->inertia + 3 * nn;
    t->position = t->size + 3 * nn;
    t->quaternion = t->position + 3 * nn;
    t->vcount = t->fixed + nn;
    t->fcount = t->vcount + nn;
    return 0;
}

static int tables_fill(block_tables *t, const rd_h5_meta *m)
{
    int n = m->nbodies + m->nfixed;
    t->nv = t->nf = 0;
    for (int i = 0; i < n; i++) {
        t->nv += body_of(m, i)->nvert;
        t->nf += body_of(m, i)->ntri;
    }
    if (tables_alloc(t, n)) return -1;
    long v = 0, f = 0;
    for (int i = 0; i < n; i++) {
        const rd_h5_body *b = body_of(m, i);
        t->name[i] = b->name;
        t->mass[i] = b->mass;
        t->alpha[i] = b->alpha;
        t->fixed[i] = b->fixed;
        t->vcount[i] = b->nvert;
        t->fcount[i] = b->ntri;
        memcpy(t->inertia + 3 * i, b->inertia, sizeof b->inertia);
        memcpy(t->size + 3 * i, b->size, sizeof b->size);
        memcpy(t->position + 3 * i, b->position, sizeof b->position);
        memcpy(t->quaternion + 4 * i, b->quaternion, sizeof b->quaternion);
        memcpy(t->vertices + 3 * v, b->vertices, 3 * sizeof(double) * (size_t)b->nvert);
        memcpy(t->faces + 3 * f, b->triangles, 3 * sizeof(int) * (size_t)b->ntri);
        v += b->nvert;
        f += b->ntri;
    }
    return 0;
}

/* A per-block column (cols 0) or table over (block, inner). */
static int per_block(long long g, const char *name, rd_h5t_type type, const void *data,
                     const block_tables *t, int cols, const char *inner, const char *units,
                     const char *long_name, rd_error *err)
{
    rd_h5t_axes ax = { { "block", inner }, { NULL, NULL } };
    return rd_h5t_write(g, name, type, data, t->n, cols, units, long_name, &ax, err);
}

/* A ragged table's count per block, naming the dimension it counts rows of. */
static int counts(long long g, const char *name, const int *count, int n, const char *dim,
                  const char *long_name, rd_error *err)
{
    rd_h5t_axes ax = { { "block", NULL }, { NULL, NULL } };
    return rd_h5t_write(g, name, RD_H5T_INT, count, n, 0, NULL, long_name, &ax, err) ||
                   rd_h5t_attr(g, name, "sample_dimension", dim, err)
               ? -1
               : 0;
}

static int write_columns(long long g, const block_tables *t, rd_error *err)
{
    return per_block(g, "fixed", RD_H5T_INT, t->fixed, t, 0, NULL, NULL,
                     "1: a fixed body (pedestal, footing), not in the time series", err) ||
                   per_block(g, "mass", RD_H5T_DOUBLE, t->mass, t, 0, NULL, "kg", "mass", err) ||
                   per_block(g, "inertia_principal", RD_H5T_DOUBLE, t->inertia, t, 3, "/xyz",
                             "kg m^2", "principal moments of inertia (body frame)", err) ||
                   per_block(g, "size", RD_H5T_DOUBLE, t->size, t, 3, "/xyz", "m",
                             "extents along ground x, y, z (of a free body: at rest)", err) ||
                   per_block(g, "alpha", RD_H5T_DOUBLE, t->alpha, t, 0, NULL, "rad",
                             "static tipping angle about the edge of the support polygon at "
                             "rest, least of the +-x, +-y leans (0: fixed)",
                             err) ||
                   per_block(g, "position", RD_H5T_DOUBLE, t->position, t, 3, "/xyz", "m",
                             "centre of mass as placed, ground frame (a fixed body's for good)",
                             err) ||
                   per_block(g, "quaternion", RD_H5T_DOUBLE, t->quaternion, t, 4, "/wxyz", "1",
                             "orientation as placed, body to ground frame", err)
               ? -1
               : 0;
}

static int write_geometry(long long g, const block_tables *t, rd_error *err)
{
    rd_h5t_axes va = { { "vertex", "/xyz" }, { NULL, NULL } };
    rd_h5t_axes fa = { { "face", "/corner" }, { NULL, NULL } };
    return counts(g, "vertex_count", t->vcount, t->n, "vertex",
                  "vertices of each body: rows of vertices in block order", err) ||
                   counts(g, "face_count", t->fcount, t->n, "face",
                          "triangles of each body: rows of faces in block order", err) ||
                   rd_h5t_write(g, "vertices", RD_H5T_DOUBLE, t->vertices, t->nv, 3, "m",
                                "vertex, body frame, about the centre of mass (each body's "
                                "vertex_count rows in turn)",
                                &va, err) ||
                   rd_h5t_write(g, "faces", RD_H5T_INT, t->faces, t->nf, 3, NULL,
                                "triangle, indices into its own body's vertices (outward "
                                "normal by the right-hand rule; face_count rows per body)",
                                &fa, err)
               ? -1
               : 0;
}

int rd_h5_bodies_write(long long file, const rd_h5_meta *m, rd_error *err)
{
    block_tables t = { 0 };
    if (tables_fill(&t, m)) {
        tables_free(&t);
        return rd_error_set(err, "out of memory for the bodies' tables");
    }
    long long g = rd_h5t_group(file, "bodies", err);
    int rc = g < 0 ||
             rd_h5t_strings(g, "block", t.name, t.n,
                            "every body: the free bodies in /body order, then the fixed ones",
                            "block", err) ||
             rd_h5t_strings(g, "names", t.name, m->nbodies, "free bodies, in output order", "/body",
                            err) ||
             write_columns(g, &t, err) || write_geometry(g, &t, err);
    rd_h5t_close_group(g);
    tables_free(&t);
    return rc ? -1 : 0;
}

/* Rows of the bodies at rest: sizes [n][3], the precariousness rows concatenated, the count
 * per block (0 for the fixed ones). */
static int rest_tables(long long g, const rd_h5_rest_body *b, int n, long nblock, rd_error *err)
{
    long rows = 0;
    for (int i = 0; i < n; i++) rows += b[i].nprec;
    double *size = malloc(3 * sizeof *size * (size_t)(n + 1));
    double *prec = malloc(3 * sizeof *prec * (size_t)(rows + 1));
    int *count = calloc((size_t)nblock + 1, sizeof *count);
    int rc = size && prec && count ? 0 : rd_error_set(err, "out of memory");
    for (long i = 0, r = 0; !rc && i < n; r += b[i].nprec, i++) {
        memcpy(size + 3 * i, b[i].size, sizeof b[i].size);
        memcpy(prec + 3 * r, b[i].precariousness, 3 * sizeof *prec * (size_t)b[i].nprec);
        count[i] = b[i].nprec;
    }
    rd_h5t_axes ax = { { "lean", "quantity" }, { NULL, prec_labels } };
    if (!rc)
        rc = rd_h5t_write_rows(g, "size", RD_H5T_DOUBLE, size, 0, n, err) ||
             rd_h5t_write(g, "precariousness", RD_H5T_DOUBLE, prec, rows, 3, prec_units,
                          "per lean direction of each free body (lean_count rows per body): "
                          "the direction it tips towards (rad from +x), its static tipping "
                          "angle alpha (rad), the quasi-static tipping acceleration "
                          "g tan(alpha) (m/s^2)",
                          &ax, err) ||
             counts(g, "lean_count", count, (int)nblock, "lean",
                    "lean directions of each body: rows of precariousness in block order", err);
    free(count);
    free(prec);
    free(size);
    return rc ? -1 : 0;
}

int rd_h5_bodies_rest(rd_h5 *h, const rd_h5_rest_body *b, int n, rd_error *err)
{
    size_t bytes = RD_BODY_HEADER * 4;
    for (int i = 0; i < n; i++)
        bytes += 3 * sizeof(double) + (3 * sizeof(double) + sizeof(int)) * (size_t)b[i].nprec;
    if (rd_h5_reserve(h, bytes + bytes / 8, err)) return -1;
    rd_h5_quiet q = rd_h5_quiet_begin();
    long long f = rd_h5_file_id(h);
    long nblock = rd_h5t_count(f, "bodies/block");
    long long g = nblock >= n ? rd_h5t_group(f, "bodies", err) : -1;
    int rc = g < 0 || rest_tables(g, b, n, nblock, err);
    rd_h5t_close_group(g);
    rd_h5_quiet_end(q);
    return rc ? rd_h5_fail(h, "cannot write the bodies at rest", err) : 0;
}

int rd_h5_bodies_alpha(long long file, const double *alpha, int n, rd_error *err)
{
    long nblock = rd_h5t_count(file, "bodies/alpha");
    if (nblock < n) return rd_error_set(err, "/bodies/alpha: %ld rows for %d bodies", nblock, n);
    double *a = malloc(sizeof *a * (size_t)(nblock + 1));
    int rc = a ? rd_h5t_read(file, "bodies/alpha", RD_H5T_DOUBLE, a, nblock, err)
               : rd_error_set(err, "out of memory");
    for (int i = 0; !rc && i < n; i++)
        if (alpha[i] > 0) a[i] = alpha[i];
    if (!rc) rc = rd_h5t_write_rows(file, "bodies/alpha", RD_H5T_DOUBLE, a, 0, n, err);
    free(a);
    return rc ? -1 : 0;
}
