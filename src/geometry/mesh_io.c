/* rockdem — closed surface meshes from OBJ, PLY (ASCII, binary little/big endian) and STL
 * (ASCII, binary), read in double precision, recentred on the bounding-box centre and checked
 * (closed, manifold, consistently oriented, outward) by rd_poly_check.
 * Folder geometry/ owns solids, their mass properties, subcontact points and assembly builders;
 * it may call base/ only.
 */
#include "geometry/geom.h"
#include "geometry/terrain.h"
#include "base/path.h"
#include "base/grow.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Vertices and faces as they are read. */
typedef struct mesh {
    const char *path;
    double (*v)[3];
    int nv, vcap;
    int *flen;
    int nf, fcap;
    int *fline;
    int flcap; /* source line of each face (0: a binary file, no lines) */
    int *idx;
    int ni, icap;
    int *tline;
    int nt, tcap;   /* ASCII STL: line of each facet's endfacet */
    double f32_max; /* largest |coordinate| read as float32 (binary STL, PLY float), m */
} mesh;

/* Largest |coordinate| accepted, m: map coordinates are ~1e7 m; beyond 1e9 m products of
 * coordinates (areas, volumes, inertia) lose all precision relative to a rock's size. */
#define MESH_COORD_MAX   1e9
/* A float32 mesh is refused when its coordinates' resolution (the float32 spacing at their
 * magnitude) exceeds this fraction of the mesh's radius (half its bounding-box diagonal): the
 * contact band, RD_CONTACT_BAND of engine/sim.h, within which a point counts as touching; a
 * coarser rounding moves contacts by more than the band. */
#define MESH_F32_REL_MAX 1e-3

/* Add vertex x read on `line` (0: a binary file; the message then names the vertex index). */
static int add_vertex(mesh *m, const double x[3], int line, rd_error *err)
{
    for (int k = 0; k < 3; k++)
        if (!(fabs(x[k]) <= MESH_COORD_MAX)) {
            char at[32] = "";
            if (line > 0) snprintf(at, sizeof at, ":%d", line);
            return rd_error_set(
                err, "%s%s: vertex %d: coordinate %c = %g %s", m->path, at, m->nv, 'x' + k, x[k],
                isfinite(x[k]) ? "m is beyond the 1e9 m accepted" : "is not a finite number");
        }
    if (rd_grow((void **)&m->v, &m->vcap, m->nv + 1, sizeof *m->v))
        return rd_error_set(err, "%s: out of memory", m->path);
    memcpy(m->v[m->nv++], x, sizeof *m->v);
    return 0;
}

static int add_index(mesh *m, int i, rd_error *err)
{
    if (rd_grow((void **)&m->idx, &m->icap, m->ni + 1, sizeof *m->idx))
        return rd_error_set(err, "%s: out of memory", m->path);
    m->idx[m->ni++] = i;
    return 0;
}

/* End a face of len vertices read on `line` (0: binary). */
static int end_face(mesh *m, int len, int line, rd_error *err)
{
    if (rd_grow((void **)&m->flen, &m->fcap, m->nf + 1, sizeof *m->flen) ||
        rd_grow((void **)&m->fline, &m->flcap, m->nf + 1, sizeof *m->fline))
        return rd_error_set(err, "%s: out of memory", m->path);
    m->fline[m->nf] = line;
    m->flen[m->nf++] = len;
    return 0;
}

static void mesh_free(mesh *m)
{
    free(m->v);
    free(m->flen);
    free(m->fline);
    free(m->idx);
    free(m->tline);
}

/* Whole file, NUL-terminated. */
static int read_all(const char *path, char **buf, size_t *len, rd_error *err)
{
    if (rd_path_special(path)) return rd_error_set(err, "%s: %s", path, RD_PATH_INPUT_NOT_FILE);
    FILE *f = fopen(path, "rb");
    if (!f) return rd_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    size_t cap = 1 << 16, n = 0;
    char *b = malloc(cap + 1);
    while (b) {
        n += fread(b + n, 1, cap - n, f);
        if (n < cap) break;
        char *nb = realloc(b, 2 * cap + 1);
        if (!nb) {
            free(b);
            b = NULL;
            break;
        }
        b = nb;
        cap *= 2;
    }
    int bad = ferror(f) ? errno : 0;
    fclose(f);
    if (!b) return rd_error_set(err, "%s: out of memory", path);
    if (bad) {
        free(b);
        return rd_error_set(err, "%s: read error: %s", path, strerror(bad));
    }
    b[n] = '\0';
    *buf = b;
    *len = n;
    return 0;
}

/* A text coordinate: the token at s (after blanks) up to the next blank or eol, read whole by
 * strtod as a decimal number ("1x", "1.5.5" and the hexadecimal "0x1" are not). 0 with *end after
 * it; -1 with [*tok, *end) the bad token (empty at the line's end). */
static int text_coord(const char *s, const char *eol, double *x, const char **tok, const char **end)
{
    while (s < eol && isspace((unsigned char)*s)) s++;
    const char *e = s;
    while (e < eol && !isspace((unsigned char)*e)) e++;
    *tok = s;
    *end = e;
    char *stop;
    *x = strtod(s, &stop);
    return e > s && stop == e && !memchr(s, 'x', (size_t)(e - s)) &&
                   !memchr(s, 'X', (size_t)(e - s))
               ? 0
               : -1;
}

/* ---- OBJ: "v x y z", "f a b c ..." with a/b/c tokens and negative (relative) indices ---- */

static int obj_face(mesh *m, const char *s, const char *eol, int line, rd_error *err)
{
    int len = 0;
    for (;;) {
        while (s < eol && isspace((unsigned char)*s)) s++;
        if (s >= eol) break;
        char *end;
        long i = strtol(s, &end, 10);
        if (end == s || (end < eol && *end != '/' && !isspace((unsigned char)*end)))
            return rd_error_set(err, "%s:%d: bad vertex index in face %d", m->path, line,
                                m->nf + 1);
        long k = i > 0 ? i - 1 : m->nv + i;
        if (i == 0 || k < 0 || k >= m->nv)
            return rd_error_set(err, "%s:%d: face %d uses vertex %ld but the file has %d vertices",
                                m->path, line, m->nf + 1, i, m->nv);
        if (add_index(m, (int)k, err)) return -1;
        len++;
        for (s = end; s < eol && !isspace((unsigned char)*s); s++) {}
    }
    if (len < 3)
        return rd_error_set(err, "%s:%d: face %d has %d vertices (at least 3 needed)", m->path,
                            line, m->nf + 1, len);
    return end_face(m, len, line, err);
}

static int obj_read(mesh *m, const char *buf, rd_error *err)
{
    int line = 1;
    for (const char *s = buf; *s; line++) {
        const char *eol = strchr(s, '\n');
        if (!eol) eol = s + strlen(s);
        while (s < eol && (*s == ' ' || *s == '\t')) s++;
        if (s[0] == 'v' && (s[1] == ' ' || s[1] == '\t')) {
            double x[3];
            const char *at = s + 1, *tok;
            for (int k = 0; k < 3; k++)
                if (text_coord(at, eol, &x[k], &tok, &at))
                    return tok == at ? rd_error_set(err, "%s:%d: expected 3 coordinates after 'v'",
                                                    m->path, line)
                                     : rd_error_set(err, "%s:%d: bad coordinate '%.*s' after 'v'",
                                                    m->path, line, (int)(at - tok), tok);
            if (add_vertex(m, x, line, err)) return -1;
        } else if (s[0] == 'f' && (s[1] == ' ' || s[1] == '\t')) {
            if (obj_face(m, s + 1, eol, line, err)) return -1;
        } /* vt, vn, g, o, s, usemtl, comments ...: not geometry */
        s = *eol ? eol + 1 : eol;
    }
    return 0;
}

/* ---- PLY ---- */

/* Header limits, and the longest list (a face's vertex count) an element may hold. */
enum { PLY_MAXEL = 16, PLY_MAXPROP = 32, PLY_MAXLIST = 1000000 };
typedef enum { T_BAD, T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64 } ply_type;
typedef struct ply_prop {
    char name[32];
    ply_type type, count_type;
    int is_list;
} ply_prop;
typedef struct ply_elem {
    char name[32];
    long count;
    int np;
    ply_prop p[PLY_MAXPROP];
} ply_elem;
typedef struct ply {
    int format; /* 0 ascii, 1 binary little endian, 2 binary big endian */
    int nel;
    ply_elem el[PLY_MAXEL];
    const char *s, *end; /* data cursor */
    int line;            /* current line (ASCII) */
} ply;

static ply_type ply_type_of(const char *t)
{
    static const struct {
        const char *name;
        ply_type type;
    } names[] = { { "char", T_I8 },    { "int8", T_I8 },     { "uchar", T_U8 },
                  { "uint8", T_U8 },   { "short", T_I16 },   { "int16", T_I16 },
                  { "ushort", T_U16 }, { "uint16", T_U16 },  { "int", T_I32 },
                  { "int32", T_I32 },  { "uint", T_U32 },    { "uint32", T_U32 },
                  { "float", T_F32 },  { "float32", T_F32 }, { "double", T_F64 },
                  { "float64", T_F64 } };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (!strcmp(t, names[i].name)) return names[i].type;
    return T_BAD;
}

static int ply_header_line(ply *h, const char *path, char *ln, int line, rd_error *err)
{
    char a[32] = "", b[32] = "", c[32] = "", d[32] = "";
    int n = sscanf(ln, "%31s %31s %31s %31s", a, b, c, d);
    if (n <= 0 || !strcmp(a, "comment") || !strcmp(a, "obj_info")) return 0;
    if (!strcmp(a, "format")) {
        if (!strcmp(b, "ascii"))
            h->format = 0;
        else if (!strcmp(b, "binary_little_endian"))
            h->format = 1;
        else if (!strcmp(b, "binary_big_endian"))
            h->format = 2;
        else
            return rd_error_set(err, "%s:%d: unknown PLY format '%s'", path, line, b);
        return 0;
    }
    if (!strcmp(a, "element") && n == 3) {
        if (h->nel == PLY_MAXEL)
            return rd_error_set(err, "%s:%d: too many PLY elements", path, line);
        ply_elem *e = &h->el[h->nel++];
        memset(e, 0, sizeof *e);
        snprintf(e->name, sizeof e->name, "%s", b);
        char *end;
        e->count = strtol(c, &end, 10);
        if (*end || e->count < 0 || e->count > INT32_MAX / 4)
            return rd_error_set(err, "%s:%d: bad element count '%s'", path, line, c);
        return 0;
    }
    if (!strcmp(a, "property") && h->nel > 0) {
        ply_elem *e = &h->el[h->nel - 1];
        if (e->np == PLY_MAXPROP)
            return rd_error_set(err, "%s:%d: too many PLY properties", path, line);
        ply_prop *p = &e->p[e->np++];
        p->is_list = !strcmp(b, "list");
        p->count_type = p->is_list ? ply_type_of(c) : T_BAD;
        p->type = ply_type_of(p->is_list ? d : b);
        int ok = p->is_list ? n == 4 && sscanf(ln, "%*s %*s %*s %*s %31s", p->name) == 1 &&
                                  p->count_type != T_BAD
                            : n == 3 && snprintf(p->name, sizeof p->name, "%s", c) > 0;
        if (!ok || p->type == T_BAD)
            return rd_error_set(err, "%s:%d: bad PLY property line", path, line);
        return 0;
    }
    return rd_error_set(err, "%s:%d: unexpected PLY header line '%s'", path, line, a);
}

/* Parse the header; leave the cursor at the first data byte. */
static int ply_header(ply *h, const char *path, const char *buf, size_t len, rd_error *err)
{
    memset(h, 0, sizeof *h);
    h->format = -1;
    if (strncmp(buf, "ply", 3) || (buf[3] != '\n' && buf[3] != '\r'))
        return rd_error_set(err, "%s:1: not a PLY file (no 'ply' magic)", path);
    const char *s = buf, *end = buf + len;
    for (int line = 1;; line++) {
        const char *eol = memchr(s, '\n', (size_t)(end - s));
        if (!eol) return rd_error_set(err, "%s: truncated PLY header (no end_header)", path);
        char ln[256];
        size_t n = (size_t)(eol - s) < sizeof ln - 1 ? (size_t)(eol - s) : sizeof ln - 1;
        memcpy(ln, s, n);
        ln[n] = '\0';
        if (n && ln[n - 1] == '\r') ln[n - 1] = '\0';
        s = eol + 1;
        if (line == 1) continue;
        if (!strcmp(ln, "end_header")) {
            h->line = line + 1;
            break;
        }
        if (ply_header_line(h, path, ln, line, err)) return -1;
    }
    if (h->format < 0) return rd_error_set(err, "%s: PLY header has no format line", path);
    h->s = s;
    h->end = end;
    while (h->format == 0 && h->s < h->end && isspace((unsigned char)*h->s))
        h->line += *h->s++ == '\n';
    return 0;
}

static int type_size(ply_type t)
{
    static const int size[] = { 0, 1, 1, 2, 2, 4, 4, 4, 8 };
    return size[t];
}

/* One value of type t at the cursor. 0, or -1 at the end of the data or (ASCII) at a token
 * that is not a whole decimal number (text_coord: '1.5.5', '1-2', '0x1'), the cursor left on
 * it for ply_short to name. */
static int ply_value(ply *h, ply_type t, double *out)
{
    if (h->format == 0) { /* one element instance per line: stop at its end */
        while (h->s < h->end && (*h->s == ' ' || *h->s == '\t' || *h->s == '\r')) h->s++;
        if (h->s >= h->end || *h->s == '\n') return -1;
        const char *eol = memchr(h->s, '\n', (size_t)(h->end - h->s)), *tok, *e;
        if (text_coord(h->s, eol ? eol : h->end, out, &tok, &e)) return -1;
        h->s = e;
        return 0;
    }
    int n = type_size(t);
    if (h->end - h->s < n) return -1;
    unsigned char b[8];
    static const uint16_t one = 1;
    int little_host = *(const unsigned char *)&one == 1;
    for (int i = 0; i < n; i++)
        b[i] = (unsigned char)h->s[(h->format == 1) == little_host ? i : n - 1 - i];
    h->s += n;
    union {
        int8_t i8;
        uint8_t u8;
        int16_t i16;
        uint16_t u16;
        int32_t i32;
        uint32_t u32;
        float f;
        double d;
    } u;
    memcpy(&u, b, (size_t)n);
    switch (t) {
    case T_I8: *out = u.i8; break;
    case T_U8: *out = u.u8; break;
    case T_I16: *out = u.i16; break;
    case T_U16: *out = u.u16; break;
    case T_I32: *out = u.i32; break;
    case T_U32: *out = u.u32; break;
    case T_F32: *out = u.f; break;
    default: *out = u.d; break;
    }
    return 0;
}

static int ply_short(const ply *h, const char *path, const ply_elem *e, long i, rd_error *err)
{
    if (h->format == 0 && h->s < h->end && *h->s != '\n' && !isspace((unsigned char)*h->s)) {
        size_t n = strcspn(h->s, " \t\r\n"), left = (size_t)(h->end - h->s);
        return rd_error_set(err, "%s:%d: bad number '%.*s' in %s %ld of %ld", path, h->line,
                            (int)(n < left ? n : left), h->s, e->name, i, e->count);
    }
    if (h->format == 0)
        return rd_error_set(
            err, "%s:%d: %s %ld of %ld has fewer values than the header's properties%s", path,
            h->line, e->name, i, e->count, h->s >= h->end ? " (file ends)" : "");
    return rd_error_set(err, "%s: truncated binary file (%s %ld of %ld)", path, e->name, i,
                        e->count);
}

/* One face list: count then indices, checked against the vertex count. */
static int ply_face(ply *h, mesh *m, const ply_elem *e, const ply_prop *p, long i, rd_error *err)
{
    double c;
    if (ply_value(h, p->count_type, &c)) return ply_short(h, m->path, e, i, err);
    if (!(c >= 3 && c <= PLY_MAXLIST) || c != floor(c))
        return rd_error_set(err, "%s: face %ld has %g vertices (3 to %d allowed)", m->path, i, c,
                            PLY_MAXLIST);
    for (int k = 0; k < (int)c; k++) {
        double x;
        if (ply_value(h, p->type, &x)) return ply_short(h, m->path, e, i, err);
        if (x < 0 || x >= m->nv || x != floor(x))
            return rd_error_set(err, "%s: face %ld uses vertex %g but the file has %d vertices",
                                m->path, i, x, m->nv);
        if (add_index(m, (int)x, err)) return -1;
    }
    return end_face(m, (int)c, h->format == 0 ? h->line : 0, err);
}

/* A list property this reader does not use (a face's texture coordinates, ...): count, then
 * that many values read past. */
static int ply_skip_list(ply *h, const char *path, const ply_elem *e, const ply_prop *p, long i,
                         rd_error *err)
{
    double cnt, val;
    if (ply_value(h, p->count_type, &cnt)) return ply_short(h, path, e, i, err);
    if (!(cnt >= 0 && cnt <= PLY_MAXLIST) || cnt != floor(cnt))
        return rd_error_set(err, "%s: %s %ld: list '%s' has %g entries (0 to %d allowed)", path,
                            e->name, i, p->name, cnt, PLY_MAXLIST);
    for (long k = 0; k < (long)cnt; k++)
        if (ply_value(h, p->type, &val)) return ply_short(h, path, e, i, err);
    return 0;
}

/* Read one element instance: vertex x/y/z, face vertex_indices, everything else skipped. */
static int ply_instance(ply *h, mesh *m, const ply_elem *e, long i, rd_error *err)
{
    int is_vertex = !strcmp(e->name, "vertex"), is_face = !strcmp(e->name, "face");
    double x[3] = { 0, 0, 0 };
    for (int j = 0; j < e->np; j++) {
        const ply_prop *p = &e->p[j];
        if (is_face && p->is_list &&
            (!strcmp(p->name, "vertex_indices") || !strcmp(p->name, "vertex_index"))) {
            if (ply_face(h, m, e, p, i, err)) return -1;
            continue;
        }
        if (p->is_list) {
            if (ply_skip_list(h, m->path, e, p, i, err)) return -1;
            continue;
        }
        double val;
        if (ply_value(h, p->type, &val)) return ply_short(h, m->path, e, i, err);
        if (is_vertex && p->name[0] >= 'x' && p->name[0] <= 'z' && !p->name[1]) {
            x[p->name[0] - 'x'] = val;
            if (p->type == T_F32) m->f32_max = fmax(m->f32_max, fabs(val));
        }
    }
    return is_vertex ? add_vertex(m, x, h->format == 0 ? h->line : 0, err) : 0;
}

/* ASCII: element instance i must end its line (a longer line means the header's counts or
 * properties do not match the data, e.g. fewer vertex lines than "element vertex N"); then
 * move to the next line. */
static int ply_end_line(ply *h, const char *path, const ply_elem *e, long i, rd_error *err)
{
    if (h->format != 0) return 0;
    while (h->s < h->end && (*h->s == ' ' || *h->s == '\t' || *h->s == '\r')) h->s++;
    if (h->s < h->end && *h->s != '\n')
        return rd_error_set(err,
                            "%s:%d: %s %ld of %ld has more values than the header's %d properties "
                            "(do the element counts match the data?)",
                            path, h->line, e->name, i, e->count, e->np);
    while (h->s < h->end && isspace((unsigned char)*h->s)) h->line += *h->s++ == '\n';
    return 0;
}

static int ply_read(mesh *m, const char *buf, size_t len, rd_error *err)
{
    ply h;
    if (ply_header(&h, m->path, buf, len, err)) return -1;
    int seen_v = 0, seen_f = 0;
    for (int k = 0; k < h.nel; k++) {
        const ply_elem *e = &h.el[k];
        if (!strcmp(e->name, "vertex")) {
            int xyz = 0;
            for (int j = 0; j < e->np; j++)
                if (!e->p[j].is_list && e->p[j].name[0] >= 'x' && e->p[j].name[0] <= 'z' &&
                    !e->p[j].name[1])
                    xyz |= 1 << (e->p[j].name[0] - 'x');
            if (xyz != 7)
                return rd_error_set(err, "%s: PLY vertex element lacks x, y or z", m->path);
            seen_v = 1;
        }
        if (!strcmp(e->name, "face")) {
            if (!seen_v)
                return rd_error_set(err, "%s: PLY face element comes before the vertices", m->path);
            seen_f = 1;
        }
        for (long i = 0; i < e->count; i++)
            if (ply_instance(&h, m, e, i, err) || ply_end_line(&h, m->path, e, i, err)) return -1;
    }
    if (!seen_v || !seen_f)
        return rd_error_set(err, "%s: PLY file has no %s element", m->path,
                            seen_v ? "face" : "vertex");
    return 0;
}

/* ---- STL: triangles with their own corners; corners merged by exact coordinates ---- */

static const double (*sort_base)[3]; /* qsort context (setup only, single-threaded) */

static int by_xyz(const void *a, const void *b)
{
    const double *x = sort_base[*(const int *)a], *y = sort_base[*(const int *)b];
    for (int k = 0; k < 3; k++)
        if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
    return 0;
}

/* m->v holds 3 corners per triangle: merge equal corners into vertices, make the faces. */
static int stl_merge(mesh *m, rd_error *err)
{
    int n = m->nv;
    int *order = malloc((size_t)n * sizeof *order);
    double(*u)[3] = malloc((size_t)n * sizeof *u);
    if (!order || !u) {
        free(order);
        free(u);
        return rd_error_set(err, "%s: out of memory", m->path);
    }
    for (int i = 0; i < n; i++) order[i] = i;
    sort_base = (const double(*)[3])m->v;
    qsort(order, (size_t)n, sizeof *order, by_xyz);
    int nu = 0, rc = 0;
    m->ni = 0;
    if (rd_grow((void **)&m->idx, &m->icap, n, sizeof *m->idx))
        rc = rd_error_set(err, "%s: out of memory", m->path);
    for (int i = 0; i < n && rc == 0; i++) {
        if (i == 0 || by_xyz(&order[i - 1], &order[i])) memcpy(u[nu++], m->v[order[i]], sizeof *u);
        m->idx[order[i]] = nu - 1;
    }
    for (int t = 0; t < n / 3 && rc == 0; t++)
        rc = end_face(m, 3, t < m->nt ? m->tline[t] : 0, err);
    m->ni = n;
    free(m->v);
    m->v = u;
    m->nv = nu;
    m->vcap = n;
    free(order);
    return rc;
}

static int stl_binary(mesh *m, const char *buf, size_t len, rd_error *err)
{
    if (len < 84)
        return rd_error_set(err, "%s: truncated binary STL (%zu bytes; the header alone has 84)",
                            m->path, len);
    const unsigned char *b = (const unsigned char *)buf;
    uint32_t nt =
        (uint32_t)b[80] | (uint32_t)b[81] << 8 | (uint32_t)b[82] << 16 | (uint32_t)b[83] << 24;
    if (84 + 50 * (uint64_t)nt != len)
        return rd_error_set(
            err,
            "%s: truncated binary STL: the header says %u triangles (%llu bytes) but "
            "the file has %zu bytes",
            m->path, nt, 84 + 50 * (unsigned long long)nt, len);
    for (uint32_t t = 0; t < nt; t++)
        for (int c = 0; c < 3; c++) {
            double x[3];
            for (int k = 0; k < 3; k++) {
                const unsigned char *q = b + 84 + 50 * (size_t)t + 12 + 12 * c + 4 * k;
                uint32_t w = (uint32_t)q[0] | (uint32_t)q[1] << 8 | (uint32_t)q[2] << 16 |
                             (uint32_t)q[3] << 24;
                float f;
                memcpy(&f, &w, sizeof f);
                x[k] = f;
                m->f32_max = fmax(m->f32_max, fabs(x[k]));
            }
            if (add_vertex(m, x, 0, err)) return -1;
        }
    return 0;
}

/* ASCII STL: "facet normal ... outer loop vertex x y z (x3) endloop endfacet"; normals ignored
 * (the corner order gives the orientation). */
static int stl_ascii(mesh *m, const char *buf, rd_error *err)
{
    int line = 1, corners = 0, facet = 0;
    for (const char *s = buf; *s;) {
        if (isspace((unsigned char)*s)) {
            line += *s++ == '\n';
            continue;
        }
        const char *w = s;
        while (*s && !isspace((unsigned char)*s)) s++;
        size_t n = (size_t)(s - w);
        if (n == 6 && !strncmp(w, "vertex", 6)) {
            double x[3];
            const char *eol = s + strcspn(s, "\n"), *tok;
            for (int k = 0; k < 3; k++)
                if (text_coord(s, eol, &x[k], &tok, &s))
                    return tok == s
                               ? rd_error_set(err, "%s:%d: expected 3 coordinates after 'vertex'",
                                              m->path, line)
                               : rd_error_set(err, "%s:%d: bad coordinate '%.*s' after 'vertex'",
                                              m->path, line, (int)(s - tok), tok);
            if (add_vertex(m, x, line, err)) return -1;
            corners++;
        } else if (n == 8 && !strncmp(w, "endfacet", 8)) {
            if (corners != 3)
                return rd_error_set(err, "%s:%d: facet %d has %d vertices (3 expected)", m->path,
                                    line, facet, corners);
            corners = 0;
            facet++;
            if (rd_grow((void **)&m->tline, &m->tcap, m->nt + 1, sizeof *m->tline))
                return rd_error_set(err, "%s: out of memory", m->path);
            m->tline[m->nt++] = line;
        }
    }
    if (corners)
        return rd_error_set(err, "%s:%d: truncated ASCII STL (facet without endfacet)", m->path,
                            line);
    return 0;
}

static int stl_read(mesh *m, const char *buf, size_t len, rd_error *err)
{
    const char *s = buf;
    while (isspace((unsigned char)*s)) s++;
    /* binary files may also start with "solid", but ASCII ones hold no NUL bytes */
    int binary = strncmp(s, "solid", 5) || memchr(buf, '\0', len);
    if (binary ? stl_binary(m, buf, len, err) : stl_ascii(m, buf, err)) return -1;
    return stl_merge(m, err);
}

/* ---- result ---- */

/* float32 spacing (unit in the last place) at magnitude x, m. */
static double f32_ulp(double x) { return x > 0 ? ldexp(1.0, ilogb(x) - 23) : 0.0; }

/* Refuse float32 coordinates whose resolution is coarse against the mesh size (a scan at map
 * coordinates: at y = 4e6 m, float32 resolves 0.5 m). 0 or -1. */
static int check_f32(const mesh *m, double size, rd_error *err)
{
    double ulp = f32_ulp(m->f32_max);
    double radius = 0.5 * size;
    if (m->f32_max == 0 || ulp <= MESH_F32_REL_MAX * radius) return 0;
    return rd_error_set(
        err,
        "%s: float32 coordinates up to %.3g m are resolved to %.3g m only, %.2g %% of the "
        "mesh's radius %.3g m, more than the contact band (%g %%): export the scan in a local "
        "frame (subtract an origin) or in double precision (PLY 'property double')",
        m->path, m->f32_max, ulp, 100 * ulp / radius, radius, 100 * MESH_F32_REL_MAX);
}

/* Turn "path: message" into "path:line: message". */
static void at_line(const mesh *m, int line, rd_error *err)
{
    size_t n = strlen(m->path);
    if (strncmp(err->msg, m->path, n) || strncmp(err->msg + n, ": ", 2)) return;
    char head[32];
    size_t k = (size_t)snprintf(head, sizeof head, ":%d: ", line), len = strlen(err->msg);
    if (len + k - 2 >= sizeof err->msg) return;
    memmove(err->msg + n + k, err->msg + n + 2, len - n - 1); /* the rest and its NUL */
    memcpy(err->msg + n, head, k);
}

/* A check failed on a float32 mesh: say how coarse its coordinates are (degenerate faces at
 * map coordinates come from rounding, not from the scan). */
static void f32_note(const mesh *m, double size, rd_error *err)
{
    if (strstr(err->msg, "float32")) return;
    size_t n = strlen(err->msg);
    snprintf(err->msg + n, sizeof err->msg - n,
             " (float32 coordinates up to %.3g m are resolved to %.3g m; "
             "the mesh is %.3g m across)",
             m->f32_max, f32_ulp(m->f32_max), size);
}

/* Drop unused vertices, subtract the bounding-box centre, check, fill p. */
static int mesh_finish(mesh *m, rd_poly *p, double offset[3], int base, rd_error *err)
{
    int *map = malloc((size_t)(m->nv ? m->nv : 1) * sizeof *map);
    if (!map) return rd_error_set(err, "%s: out of memory", m->path);
    for (int i = 0; i < m->nv; i++) map[i] = -1;
    for (int i = 0; i < m->ni; i++) map[m->idx[i]] = 0;
    int nv = 0;
    for (int i = 0; i < m->nv; i++)
        if (map[i] == 0) {
            map[i] = nv;
            memmove(m->v[nv++], m->v[i], sizeof *m->v);
        }
    for (int i = 0; i < m->ni; i++) m->idx[i] = map[m->idx[i]];
    free(map);
    m->nv = nv;
    if (nv == 0 || m->nf == 0)
        return rd_error_set(err, "%s: empty mesh (%d vertices, %d faces)", m->path, nv, m->nf);
    double lo[3], hi[3], c[3];
    memcpy(lo, m->v[0], sizeof lo);
    memcpy(hi, m->v[0], sizeof hi);
    for (int i = 1; i < nv; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m->v[i][k]);
            hi[k] = fmax(hi[k], m->v[i][k]);
        }
    for (int k = 0; k < 3; k++) c[k] = 0.5 * (lo[k] + hi[k]);
    for (int i = 0; i < nv; i++)
        for (int k = 0; k < 3; k++) m->v[i][k] -= c[k];
    if (offset) memcpy(offset, c, sizeof c);
    if (rd_poly_alloc(p, nv, m->nf, m->ni, err)) return -1;
    memcpy(p->v, m->v, (size_t)nv * sizeof *p->v);
    memcpy(p->fidx, m->idx, (size_t)m->ni * sizeof *p->fidx);
    for (int f = 0, at = 0; f < m->nf; f++) {
        p->fstart[f] = at;
        p->flen[f] = m->flen[f];
        at += m->flen[f];
    }
    double size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    int bad;
    if (rd_poly_check_at(p, m->path, base, &bad, err) || check_f32(m, size, err)) {
        if (bad >= 0 && m->fline[bad] > 0)
            at_line(m, m->fline[bad], err);
        else if (strstr(err->msg, "volume") &&
                 m->fline[0] > 0) { /* the whole surface is at fault */
            size_t n = strlen(err->msg);
            snprintf(err->msg + n, sizeof err->msg - n, " (its %d faces are on lines %d-%d)", m->nf,
                     m->fline[0], m->fline[m->nf - 1]);
        }
        if (m->f32_max > 0) f32_note(m, size, err);
        rd_poly_free(p);
        return -1;
    }
    rd_poly_update(p);
    return 0;
}

/* A height grid's closed solid (terrain.c) as the mesh m. */
static int grid_read(mesh *m, const char *buf, rd_error *err)
{
    rd_grid g;
    rd_grid_mesh gm = { 0 };
    if (rd_grid_read(m->path, buf, &g, err)) return -1;
    int rc = rd_grid_solid(&g, &gm, err);
    for (int k = 0; rc == 0 && k < gm.nv; k++) rc = add_vertex(m, gm.v[k], 0, err);
    for (int t = 0; rc == 0 && t < gm.ntri; t++)
        rc = add_index(m, gm.tri[t][0], err) || add_index(m, gm.tri[t][1], err) ||
             add_index(m, gm.tri[t][2], err) || end_face(m, 3, 0, err);
    rd_grid_free(&g);
    rd_grid_mesh_free(&gm);
    return rc;
}

int rd_mesh_read(rd_poly *p, const char *path, double offset[3], rd_error *err)
{
    const char *dot = strrchr(path, '.');
    const char *ext = dot && !strchr(dot, '/') ? dot + 1 : "";
    int kind = !strcasecmp(ext, "obj")   ? 1
               : !strcasecmp(ext, "ply") ? 2
               : !strcasecmp(ext, "stl") ? 3
                                         : 0;
    if (!kind)
        return rd_error_set(err, "%s: unknown mesh format '%s' (expected .obj, .ply or .stl)", path,
                            ext);
    char *buf = NULL;
    size_t len = 0;
    if (read_all(path, &buf, &len, err)) return -1;
    mesh m = { .path = path };
    int rc = kind == 1   ? obj_read(&m, buf, err)
             : kind == 2 ? ply_read(&m, buf, len, err)
                         : stl_read(&m, buf, len, err);
    free(buf);
    if (rc == 0) rc = mesh_finish(&m, p, offset, kind == 1, err);
    mesh_free(&m);
    return rc;
}

int rd_terrain_read(rd_poly *p, const char *path, double offset[3], rd_error *err)
{
    char *buf = NULL;
    size_t len = 0;
    if (read_all(path, &buf, &len, err)) return -1;
    mesh m = { .path = path };
    int rc = grid_read(&m, buf, err);
    free(buf);
    if (rc == 0) rc = mesh_finish(&m, p, offset, 0, err);
    mesh_free(&m);
    return rc;
}
