/* rockdem — building a simulation from a scenario: bodies (shape, mass properties, pose),
 * subcontact points on the faces that can touch, and the contact pairs with their history.
 *
 * Leave out what the scene does not need: a face carries subcontact points only if it faces
 * down at the start (it may land on what is below) or lies on another body's face (a stack
 * joint). Fixed pedestals carry no points: a free body's own points already integrate the
 * joint over its footprint (weight 1); where two free bodies meet, both point sets carry half
 * the stiffness (3DEC's averaging of the two faces' subcontacts). Pairs are made by the broad
 * phase (pairs.c) when two bodies first come near each other.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "engine/perturb.h"
#include "base/vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ALLOC(ptr, n) ((ptr) = calloc((size_t)(n) > 0 ? (size_t)(n) : 1, sizeof *(ptr)))

/* Orientation from rotations about x, then y, then z (extrinsic, rad), times the principal axes. */
static void initial_orientation(const double rot[3], const double axes[9], double q[4])
{
    double qx[4], qy[4], qz[4], qa[4], t1[4], t2[4];
    double ex[3] = { rot[0], 0, 0 }, ey[3] = { 0, rot[1], 0 }, ez[3] = { 0, 0, rot[2] };
    rd_quat_from_rotvec(ex, qx);
    rd_quat_from_rotvec(ey, qy);
    rd_quat_from_rotvec(ez, qz);
    rd_quat_from_mat(axes, qa);
    rd_quat_mul(qy, qx, t1);
    rd_quat_mul(qz, t1, t2);
    rd_quat_mul(t2, qa, q);
}

/* A mesh in the scene's frame: read (path resolved by the parser), scaled to metres by its
 * declared units and turned z-up when the file is y-up (+90 deg about x: (x, y, z) ->
 * (x, -z, y)); the bounding-box centre stays at the origin. */
static int mesh_shape(const rd_body_def *d, rd_poly *p, double offset[3], rd_error *err)
{
    if ((d->terrain ? rd_terrain_read : rd_mesh_read)(p, d->mesh, offset, err)) return -1;
    double s = d->mesh_unit > 0 ? d->mesh_unit : 1.0;
    if (s == 1.0 && d->mesh_up != 1) return 0;
    for (int i = 0; i < p->nv; i++) {
        double x = p->v[i][0], y = p->v[i][1], z = p->v[i][2];
        p->v[i][0] = s * x;
        p->v[i][1] = s * (d->mesh_up == 1 ? -z : y);
        p->v[i][2] = s * (d->mesh_up == 1 ? y : z);
    }
    rd_poly_update(p);
    return 0;
}

/* offset: where the shape's origin lies in its file's coordinates (meshes), m. */
static int build_shape(const rd_body_def *d, rd_poly *p, double offset[3], rd_error *err)
{
    switch (d->shape) {
    case RD_SHAPE_BRICK: return rd_poly_brick(p, d->size, err);
    case RD_SHAPE_PRISM:
        return rd_poly_prism(p, d->sides, d->radius, d->radius_top, d->size[2], err);
    case RD_SHAPE_HULL: return rd_poly_hull(p, (const double(*)[3])d->verts, d->nverts, err);
    case RD_SHAPE_MESH: return mesh_shape(d, p, offset, err);
    }
    return rd_error_set(err, "unknown shape");
}

/* Convex to this tolerance, m, for a body of radius r (m): only convex bodies can be contact
 * targets (a point's gap is measured against their face planes); round-off of the face planes
 * is ~1e-16 r. */
#define RD_CONVEX_TOL(r) (1e-9 * (1.0 + (r)))
#define RD_SURFACE_CONVEX_FACES                                                                    \
    130 /* the surface model (surface.c) takes a convex body of more faces as a mesh: the
           integration side of its pairs, against a convex partner */

static int build_body(rd_sim *s, int i, rd_error *err)
{
    const rd_body_def *d = &s->sc.bodies[i];
    rd_mass m;
    double offset[3] = { 0, 0, 0 };
    if (build_shape(d, &s->poly[i], offset, err) || rd_poly_mass(&s->poly[i], &m, err)) {
        char msg[RD_ERROR_MAX];
        snprintf(msg, sizeof msg, "%s", err->msg);
        return rd_error_set(err, "%s:%d: block '%s': %s", s->sc.file, d->line, d->name, msg);
    }
    rd_poly_to_frame(&s->poly[i], &m);
    double density =
        d->mass > 0 ? d->mass / m.volume : (d->density > 0 ? d->density : s->sc.density);
    s->mass[i] = density * m.volume;
    for (int k = 0; k < 3; k++) s->inertia[i][k] = density * m.principal[k];
    initial_orientation(d->rotation, m.axes, s->q[i]);
    rd_copy3(d->position, s->x[i]); /* the centre of mass */
    if (d->terrain)                 /* a terrain stays at its file's coordinates */
        for (int k = 0; k < 3; k++) s->x[i][k] = offset[k] + m.centroid[k];
    s->fixed[i] = d->fixed;
    if (rd_poly_convex(&s->poly[i], RD_CONVEX_TOL(s->poly[i].radius), &s->convex[i], err)) {
        char msg[RD_ERROR_MAX];
        snprintf(msg, sizeof msg, "%s", err->msg);
        return rd_error_set(err, "%s:%d: block '%s': %s", s->sc.file, d->line, d->name, msg);
    }
    /* the surface model takes a convex body of many faces as a mesh (surface.c: it is then the
       integration side of its pairs, against a convex partner) */
    if (s->convex[i] && s->poly[i].nf > RD_SURFACE_CONVEX_FACES &&
        s->sc.contact.model == RD_CONTACT_SURFACE)
        s->convex[i] = 0;
    return 0;
}

/* Place body i so its lowest vertex rests on the highest point of the body it is seated on,
 * centre of mass above position[0..1] (a rock on its pedestal, a drum on the drum below). */
static int seat_body(rd_sim *s, int i, rd_error *err)
{
    const rd_body_def *d = &s->sc.bodies[i];
    int j = -1;
    for (int k = 0; k < i && j < 0; k++)
        if (!strcmp(s->sc.bodies[k].name, d->seat_on)) j = k;
    if (j < 0)
        return rd_error_set(err, "%s:%d: block '%s' sits on '%s', which is not defined before it",
                            s->sc.file, d->line, d->name, d->seat_on);
    double top = -INFINITY, low = INFINITY;
    for (int v = s->vert0[j]; v < s->vert0[j + 1]; v++) top = fmax(top, s->wv[v][2]);
    for (int v = s->vert0[i]; v < s->vert0[i + 1]; v++) low = fmin(low, s->wv[v][2]);
    s->x[i][2] += top - low;
    rd_body_refresh(s, i);
    return 0;
}

/* Tangents t1, t2 of a face of outward unit normal u, ground frame, t1 x t2 = u: t1 along
 * e_a x u for the axis e_a least along u, t2 = u x t1 (a level face's are exact: -e_y and e_x). */
static void face_tangents(const double u[3], double t[2][3])
{
    const double a0 = fabs(u[0]), a1 = fabs(u[1]), a2 = fabs(u[2]);
    const int a = a0 <= a1 && a0 <= a2 ? 0 : a1 <= a2 ? 1 : 2;
    double e[3] = { 0, 0, 0 };
    e[a] = 1;
    rd_cross(e, u, t[0]);
    double n = rd_norm(t[0]);
    for (int k = 0; k < 3; k++) t[0][k] /= n;
    rd_cross(u, t[0], t[1]);
}

int rd_setup_bodies(rd_sim *s, rd_error *err)
{
    int nb = s->nb = s->sc.nbodies;
    if (!ALLOC(s->poly, nb) || !ALLOC(s->x, nb) || !ALLOC(s->q, nb) || !ALLOC(s->v, nb) ||
        !ALLOC(s->L, nb) || !ALLOC(s->w, nb) || !ALLOC(s->R, nb) || !ALLOC(s->mass, nb) ||
        !ALLOC(s->inertia, nb) || !ALLOC(s->fixed, nb) || !ALLOC(s->f, nb) || !ALLOC(s->tq, nb) ||
        !ALLOC(s->v_old, nb) || !ALLOC(s->L_old, nb) || !ALLOC(s->df_local, nb) ||
        !ALLOC(s->free_body, nb) || !ALLOC(s->free_of, nb) || !ALLOC(s->vert0, nb + 1) ||
        !ALLOC(s->face0, nb + 1) || !ALLOC(s->convex, nb) || !ALLOC(s->impacting, nb) ||
        !ALLOC(s->impacting_next, nb))
        return rd_error_set(err, "out of memory");
    for (int i = 0; i < nb; i++) {
        if (build_body(s, i, err)) return -1;
        s->free_of[i] = s->fixed[i] ? -1 : s->nfree;
        if (!s->fixed[i]) s->free_body[s->nfree++] = i;
        s->vert0[i + 1] = s->vert0[i] + s->poly[i].nv;
        s->face0[i + 1] = s->face0[i] + s->poly[i].nf;
    }
    if (!ALLOC(s->wv, s->vert0[nb]) || !ALLOC(s->wn, s->face0[nb]) || !ALLOC(s->wd, s->face0[nb]) ||
        !ALLOC(s->wt, s->face0[nb]))
        return rd_error_set(err, "out of memory");
    /* world geometry of every body, once here (fixed bodies never change), in order, so a
       body can be seated on one defined before it */
    for (int i = 0; i < nb; i++) {
        rd_body_refresh(s, i);
        if (s->sc.bodies[i].seat_on[0] && seat_body(s, i, err)) return -1;
    }
    /* a fixed body's face tangents, the axes of contact.c's face law (placed: it never moves) */
    for (int i = 0; i < nb; i++)
        for (int f = s->face0[i]; s->fixed[i] && f < s->face0[i + 1]; f++)
            face_tangents(s->wn[f], s->wt[f]);
    return 0;
}

/* Bounding box of face f of body i (world), grown by tol: lo[3], hi[3]. */
static void face_box(const rd_sim *s, int i, int f, double tol, double lo[3], double hi[3])
{
    const rd_poly *p = &s->poly[i];
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (int k = 0; k < p->flen[f]; k++) {
        const double *v = s->wv[s->vert0[i] + p->fidx[p->fstart[f] + k]];
        for (int c = 0; c < 3; c++) {
            lo[c] = fmin(lo[c], v[c] - tol);
            hi[c] = fmax(hi[c], v[c] + tol);
        }
    }
}

/* The bodies near each body: those whose boxes (world vertices grown by tol) overlap its own,
 * body i's in list[start[i]] .. list[start[i + 1] - 1]. */
typedef struct neighbours {
    int *start; /* [nb + 1] */
    int *list;
} neighbours;

typedef struct box_key {
    double lo; /* lowest x of the box, m */
    int body;
} box_key;

static int by_lo(const void *a, const void *b)
{
    double x = ((const box_key *)a)->lo, y = ((const box_key *)b)->lo;
    return (x > y) - (x < y);
}

static int boxes_meet(const double *p, const double *q)
{
    return p[0] <= q[3] && q[0] <= p[3] && p[1] <= q[4] && q[1] <= p[4] && p[2] <= q[5] &&
           q[2] <= p[5];
}

/* Sort and sweep along x, O(n log n + pairs): testing each face against every other body's
 * faces made setup quadratic in the bodies (bench/wall.py's 5,000 bricks: rd_sim_create took
 * 1.36 s of CPU, 0.19 s with this). */
static int find_neighbours(const rd_sim *s, double tol, neighbours *nb)
{
    int n = s->nb;
    double(*box)[6] = malloc((size_t)n * sizeof *box);
    box_key *key = malloc((size_t)n * sizeof *key);
    int *fill = calloc((size_t)n + 1, sizeof *fill);
    nb->start = calloc((size_t)n + 1, sizeof *nb->start);
    nb->list = NULL;
    int rc = box && key && fill && nb->start ? 0 : -1;
    for (int i = 0; !rc && i < n; i++) {
        for (int k = 0; k < 3; k++) {
            box[i][k] = INFINITY;
            box[i][k + 3] = -INFINITY;
        }
        for (int v = s->vert0[i]; v < s->vert0[i + 1]; v++)
            for (int k = 0; k < 3; k++) {
                box[i][k] = fmin(box[i][k], s->wv[v][k] - tol);
                box[i][k + 3] = fmax(box[i][k + 3], s->wv[v][k] + tol);
            }
        key[i] = (box_key){ box[i][0], i };
    }
    if (!rc) qsort(key, (size_t)n, sizeof *key, by_lo);
    for (int pass = 0; !rc && pass < 2; pass++) { /* count, then fill */
        for (int a = 0; a < n; a++)
            for (int b = a + 1; b < n && key[b].lo <= box[key[a].body][3]; b++) {
                int i = key[a].body, j = key[b].body;
                if (!boxes_meet(box[i], box[j])) continue;
                if (pass) {
                    nb->list[fill[i]++] = j;
                    nb->list[fill[j]++] = i;
                } else {
                    nb->start[i + 1]++;
                    nb->start[j + 1]++;
                }
            }
        if (pass) break;
        for (int i = 0; i < n; i++) nb->start[i + 1] += nb->start[i];
        memcpy(fill, nb->start, (size_t)n * sizeof *fill);
        nb->list = malloc((size_t)nb->start[n] * sizeof *nb->list + 1);
        if (!nb->list) rc = -1;
    }
    free(box);
    free(key);
    free(fill);
    return rc;
}

int rd_face_lies_on(const rd_sim *s, int i, int f, int j, int g, double tol)
{
    const rd_poly *p = &s->poly[i];
    const double *m = s->wn[s->face0[j] + g], dg = s->wd[s->face0[j] + g];
    if (rd_dot(s->wn[s->face0[i] + f], m) > -RD_ANTIPARALLEL) return 0;
    for (int k = 0; k < p->flen[f]; k++)
        if (!(fabs(rd_dot(m, s->wv[s->vert0[i] + p->fidx[p->fstart[f] + k]]) - dg) < tol)) return 0;
    return 1;
}

/* Does face f of body i lie on a face of a neighbouring body (antiparallel normals, coplanar)? */
static int face_touches(const rd_sim *s, const neighbours *nb, int i, int f, double tol)
{
    double lo[3], hi[3], lo2[3], hi2[3];
    face_box(s, i, f, tol, lo, hi);
    for (int m = nb->start[i]; m < nb->start[i + 1]; m++) {
        int j = nb->list[m];
        for (int g = 0; g < s->poly[j].nf; g++) {
            if (!rd_face_lies_on(s, i, f, j, g, tol)) continue;
            face_box(s, j, g, tol, lo2, hi2); /* coplanar: do the two faces overlap? */
            if (lo[0] <= hi2[0] && lo2[0] <= hi[0] && lo[1] <= hi2[1] && lo2[1] <= hi[1] &&
                lo[2] <= hi2[2] && lo2[2] <= hi[2])
                return 1;
        }
    }
    return 0;
}

/* What a face carries: RD_FACE_BED (a point bed at the body's spacing) if it lies on another
 * body's face, or faces down in the lowest fifth of the body (a rock's base region, not its
 * overhangs); RD_FACE_LATE (its vertices only, acting while the face looks at the other body)
 * for the other faces of a convex free body, which touch only later (a toppled block's side, a
 * drum's side against the rim below); RD_FACE_NONE otherwise. zr is the body's height range
 * (world z, m: lowest, highest vertex). */
enum { RD_FACE_NONE = 0, RD_FACE_BED = 1, RD_FACE_LATE = 2 };

static int face_role(const rd_sim *s, const neighbours *nb, int i, int f, const double zr[2])
{
    if (s->fixed[i]) return RD_FACE_NONE;
    const rd_poly *p = &s->poly[i];
    const double *n = s->wn[s->face0[i] + f];
    int late = s->convex[i] ? RD_FACE_LATE : RD_FACE_NONE;
    if (face_touches(s, nb, i, f, RD_FACE_TOL * (1.0 + p->radius))) return RD_FACE_BED;
    if (n[2] >= -0.5) return late;
    double fmin_z = INFINITY;
    for (int k = 0; k < p->flen[f]; k++)
        fmin_z = fmin(fmin_z, s->wv[s->vert0[i] + p->fidx[p->fstart[f] + k]][2]);
    return fmin_z <= zr[0] + 0.2 * (zr[1] - zr[0]) ? RD_FACE_BED : late;
}

/* Lowest and highest world z of body i's vertices, m (once per body: a per-face scan made
 * setup quadratic in the triangles of a scanned mesh, 39 s for 160k triangles). */
static void body_z_range(const rd_sim *s, int i, double zr[2])
{
    zr[0] = INFINITY;
    zr[1] = -INFINITY;
    for (int v = s->vert0[i]; v < s->vert0[i + 1]; v++) {
        zr[0] = fmin(zr[0], s->wv[v][2]);
        zr[1] = fmax(zr[1], s->wv[v][2]);
    }
}

/* Width of face f: the smallest, over its edges, of the farthest vertex from that edge's line
 * (a rectangle: its short side; a regular polygon: about its diameter). */
static double face_width(const rd_poly *p, int f)
{
    const int *ix = p->fidx + p->fstart[f];
    int n = p->flen[f];
    double w = INFINITY;
    for (int k = 0; k < n; k++) {
        const double *a = p->v[ix[k]], *b = p->v[ix[(k + 1) % n]];
        double e[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, len = rd_norm(e), far = 0;
        for (int j = 0; j < n; j++) {
            double d[3] = { p->v[ix[j]][0] - a[0], p->v[ix[j]][1] - a[1], p->v[ix[j]][2] - a[2] },
                   c[3];
            rd_cross(e, d, c);
            far = fmax(far, rd_norm(c) / len);
        }
        w = fmin(w, far);
    }
    return w;
}

/* Subcontact spacing of body i: the scenario's, or automatically a tenth of the narrowest
 * candidate face (an 11 x 11 bed on a square base); a mesh's own vertices already sample its
 * surface, so automatic spacing uses them. */
static double body_spacing(const rd_sim *s, int i, const char *cand)
{
    if (s->sc.contact.spacing >= 0) return s->sc.contact.spacing;
    if (s->sc.bodies[i].shape == RD_SHAPE_MESH) return 0;
    double w = INFINITY;
    for (int f = 0; f < s->poly[i].nf; f++)
        if (cand[s->face0[i] + f] == RD_FACE_BED) w = fmin(w, face_width(&s->poly[i], f));
    return isfinite(w) ? w / 10.0 : 0.0;
}

/* Count the points of every candidate face (pass 0), then mesh them into place (pass 1).
 * cand[face0[i] + f] is each face's RD_FACE_* role; spacing[i] is body i's bed spacing. */
static int mesh_candidates(rd_sim *s, const char *cand, const double *spacing, rd_error *err)
{
    int nb = s->nb, npts = 0, ncf = 0;
    for (int pass = 0; pass < 2; pass++) {
        npts = ncf = 0;
        for (int i = 0; i < nb; i++) {
            s->pt0[i] = npts;
            s->cf0[i] = ncf;
            for (int f = 0; f < s->poly[i].nf; f++) {
                int role = cand[s->face0[i] + f];
                if (role == RD_FACE_NONE) continue;
                double h = role == RD_FACE_BED ? spacing[i] : 0.0;
                int n = pass ? rd_poly_face_points(&s->poly[i], f, h, s->pl + npts, s->pa + npts,
                                                   s->npts - npts)
                             : rd_poly_face_points(&s->poly[i], f, h, NULL, NULL, 0);
                if (n < 0)
                    return rd_error_set(err, "cannot mesh face %d of body '%s'", f,
                                        s->sc.bodies[i].name);
                if (pass) {
                    s->cf_face[ncf] = f;
                    s->cf_pt0[ncf] = npts;
                    s->cf_facing[ncf] = role == RD_FACE_LATE;
                }
                npts += n;
                ncf++;
            }
        }
        s->pt0[nb] = npts;
        s->cf0[nb] = ncf;
        if (!pass) {
            s->npts = npts;
            s->ncf = ncf;
            if (!ALLOC(s->pl, npts) || !ALLOC(s->pa, npts) || !ALLOC(s->cf_face, ncf) ||
                !ALLOC(s->cf_pt0, ncf + 1) || !ALLOC(s->cf_facing, ncf))
                return rd_error_set(err, "out of memory");
        }
    }
    s->cf_pt0[ncf] = npts;
    return 0;
}

/* Refuse a scene whose subcontact points would exceed RD_POINT_BUDGET, naming the body with
 * the most (the bound counts before meshing: a spacing far below the faces' size would take
 * minutes to mesh and gigabytes to hold). */
static int check_point_budget(const rd_sim *s, const char *cand, const double *spacing,
                              rd_error *err)
{
    double total = 0, most = -1;
    int big = 0;
    for (int i = 0; i < s->nb; i++) {
        double n = 0;
        for (int f = 0; f < s->poly[i].nf; f++) {
            int role = cand[s->face0[i] + f];
            if (role != RD_FACE_NONE)
                n += rd_poly_face_points_bound(&s->poly[i], f,
                                               role == RD_FACE_BED ? spacing[i] : 0.0);
        }
        total += n;
        if (n > most) {
            most = n;
            big = i;
        }
    }
    if (!(total > RD_POINT_BUDGET)) return 0;
    const rd_body_def *b = &s->sc.bodies[big];
    char at[48] = "on its faces' corners";
    if (spacing[big] > 0) snprintf(at, sizeof at, "at spacing %g m", spacing[big]);
    return rd_error_set(
        err,
        "%s:%d: body '%s' would carry about %.3g subcontact points %s (the scene %.3g), "
        "more than the budget of %.0e; give a coarser 'contact property spacing', or "
        "auto or vertices",
        s->sc.file, b->line, b->name, most, at, total, RD_POINT_BUDGET);
}

/* Subcontact points of every body, on its candidate faces (each face judged once). */
static int build_points(rd_sim *s, rd_error *err)
{
    char *cand = calloc((size_t)s->face0[s->nb] + 1, 1);
    double *spacing = calloc((size_t)s->nb + 1, sizeof *spacing);
    double rmax = 0;
    for (int i = 0; i < s->nb; i++) rmax = fmax(rmax, s->poly[i].radius);
    neighbours nb;
    int rc = -1;
    if (find_neighbours(s, RD_FACE_TOL * (1.0 + rmax), &nb) || !cand || !spacing ||
        !ALLOC(s->pt0, s->nb + 1) || !ALLOC(s->cf0, s->nb + 1)) {
        rd_error_set(err, "out of memory");
    } else {
        for (int i = 0; i < s->nb; i++) {
            double zr[2];
            body_z_range(s, i, zr);
            for (int f = 0; f < s->poly[i].nf; f++)
                cand[s->face0[i] + f] = (char)face_role(s, &nb, i, f, zr);
        }
        for (int i = 0; i < s->nb; i++) spacing[i] = body_spacing(s, i, cand);
        for (int i = 0; i < s->nb; i++)
            for (int m = nb.start[i]; m < nb.start[i + 1]; m++)
                if (nb.list[m] > i) rd_overlap_note(s, i, nb.list[m]);
        rc = check_point_budget(s, cand, spacing, err) || mesh_candidates(s, cand, spacing, err)
                 ? -1
                 : 0;
    }
    free(nb.start);
    free(nb.list);
    free(cand);
    free(spacing);
    return rc;
}

/* Mark (use[v] = 1) the vertices of body i's candidate faces. */
static void mark_candidate_vertices(const rd_sim *s, int i, char *use)
{
    const rd_poly *p = &s->poly[i];
    for (int cf = s->cf0[i]; cf < s->cf0[i + 1]; cf++) {
        int f = s->cf_face[cf];
        for (int k = 0; k < p->flen[f]; k++) use[p->fidx[p->fstart[f] + k]] = 1;
    }
}

/* The listed vertices (use[v] = 1) of every body, in order, into list with offsets first[nb+1]
 * (allocated here). 0 or -1. */
static int list_vertices(const rd_sim *s, const char *use, int **first, int **list)
{
    int n = 0;
    for (int v = 0; v < s->vert0[s->nb]; v++) n += use[v];
    if (!ALLOC(*first, s->nb + 1) || !ALLOC(*list, n)) return -1;
    n = 0;
    for (int i = 0; i < s->nb; i++) {
        (*first)[i] = n;
        for (int v = s->vert0[i]; v < s->vert0[i + 1]; v++)
            if (use[v]) (*list)[n++] = v;
    }
    (*first)[s->nb] = n;
    return 0;
}

/* The sizes of a side's scratch (rd_sim.cv_dist, cv_mask) over every pair of bodies: the owner's
 * candidate vertices times the other body's planes, doubles (*ndist), and times two sets of
 * (planes + 63) / 64 words, uint64 (*nmask). The other body is convex (only a convex body is a
 * contact target) and never the owner itself: a body's partner with the most planes is the convex
 * body with the most, or, for that body, the one with the next most. */
static void side_sizes(const rd_sim *s, size_t *ndist, size_t *nmask)
{
    int top = -1, np1 = 0, np2 = 0; /* the most planes (body top) and the next most */
    for (int i = 0; i < s->nb; i++) {
        if (!s->convex[i]) continue;
        const int np = s->poly[i].nf;
        if (np > np1) {
            np2 = np1;
            np1 = np;
            top = i;
        } else if (np > np2) {
            np2 = np;
        }
    }
    *ndist = *nmask = 0;
    for (int i = 0; i < s->nb; i++) {
        const size_t ncv = (size_t)(s->cv0[i + 1] - s->cv0[i]), np = (size_t)(i == top ? np2 : np1);
        if (ncv * np > *ndist) *ndist = ncv * np;
        if (ncv * 2 * ((np + 63) / 64) > *nmask) *nmask = ncv * 2 * ((np + 63) / 64);
    }
}

/* Hull vertices of every body (rd_sim.hv: its bounding box in any pose; a hull that qhull
 * cannot make keeps every vertex), then every body's candidate-face vertices (rd_sim.cv: what a
 * non-convex body's step transforms, their body-frame coordinates in rd_sim.cv_body) and the
 * scratch of their world coordinates, plane distances and masks. */
static int build_step_vertices(rd_sim *s, rd_error *err)
{
    int nv = s->vert0[s->nb], np_max = 0;
    char *use = calloc((size_t)nv + 1, 1);
    int rc = !use;
    for (int i = 0; i < s->nb && !rc; i++) {
        char *u = use + s->vert0[i];
        rd_error e;
        if (s->convex[i] || rd_poly_hull_marks(&s->poly[i], u, &e))
            memset(u, 1, (size_t)s->poly[i].nv);
    }
    rc = rc || list_vertices(s, use, &s->hv0, &s->hv);
    if (!rc) memset(use, 0, (size_t)nv);
    for (int i = 0; i < s->nb && !rc; i++) {
        if (s->convex[i]) np_max = s->poly[i].nf > np_max ? s->poly[i].nf : np_max;
        mark_candidate_vertices(s, i, use + s->vert0[i]);
    }
    rc = rc || list_vertices(s, use, &s->cv0, &s->cv) || !ALLOC(s->cv_slot, nv);
    for (int i = 0; i < s->nb && !rc; i++) {
        for (int v = s->vert0[i]; v < s->vert0[i + 1]; v++) s->cv_slot[v] = -1;
        for (int k = s->cv0[i]; k < s->cv0[i + 1]; k++) s->cv_slot[s->cv[k]] = k - s->cv0[i];
    }
    int ncv = rc ? 0 : s->cv0[s->nb];
    s->np_max = np_max;
    size_t ndist = 0, nmask = 0;
    if (!rc) side_sizes(s, &ndist, &nmask);
    s->ndist = ndist;
    s->nmask = nmask;
    rc = rc || !ALLOC(s->cv_dist, ndist) || !ALLOC(s->cv_mask, nmask) ||
         !(s->plane_scratch = rd_contact_scratch(s)) || !ALLOC(s->cv_body, 3 * (size_t)ncv) ||
         !ALLOC(s->cv_world, 3 * (size_t)ncv);
    for (int i = 0; i < s->nb && !rc; i++)
        for (int k = s->cv0[i]; k < s->cv0[i + 1]; k++)
            for (int d = 0; d < 3; d++) {
                s->cv_body[d * ncv + k] = s->poly[i].v[s->cv[k] - s->vert0[i]][d];
                s->cv_world[d * ncv + k] = s->wv[s->cv[k]][d]; /* as placed (rd_setup_bodies) */
            }
    free(use);
    return rc ? rd_error_set(err, "out of memory") : 0;
}

/* A point's place (its coordinates) and index, sorted by place (bitwise: equal only when
 * identical), then index. No shared qsort context: builds may run in threads. */
typedef struct place_key {
    double x[3];
    int idx;
} place_key;
static int by_place(const void *a, const void *b)
{
    const place_key *p = a, *q = b;
    int c = memcmp(p->x, q->x, sizeof p->x);
    return c ? c : (p->idx > q->idx) - (p->idx < q->idx);
}

/* Each point's kinematics slot (rd_sim.pkin): points at the same place on a body share one, the
 * first such point's, so the contact finds their motion once. Then the slots' scratch. */
static int share_points(rd_sim *s, rd_error *err)
{
    int nmax = 1;
    for (int i = 0; i < s->nb; i++)
        if (s->pt0[i + 1] - s->pt0[i] > nmax) nmax = s->pt0[i + 1] - s->pt0[i];
    s->nkin = nmax;
    place_key *key = malloc((size_t)nmax * sizeof *key);
    if (!key || !ALLOC(s->pkin, s->npts) || !ALLOC(s->kin, nmax) || !ALLOC(s->kin_stamp, nmax)) {
        free(key);
        return rd_error_set(err, "out of memory");
    }
    for (int i = 0; i < s->nb; i++) {
        int p0 = s->pt0[i], n = s->pt0[i + 1] - p0;
        for (int k = 0; k < n; k++) {
            memcpy(key[k].x, s->pl[p0 + k], sizeof key[k].x);
            key[k].idx = p0 + k;
        }
        qsort(key, (size_t)n, sizeof *key, by_place);
        for (int k = 0; k < n; k++) /* sorted by place, then index: a run's first is its least */
            s->pkin[key[k].idx] = k > 0 && !memcmp(key[k].x, key[k - 1].x, sizeof key[k].x)
                                      ? s->pkin[key[k - 1].idx]
                                      : key[k].idx - p0;
    }
    free(key);
    return 0;
}

/* Each candidate face's vertices as the offsets of their cv_mask entries (rd_sim.cf_v), once the
 * faces are final (after merging). */
static int face_vertices(rd_sim *s, rd_error *err)
{
    int n = 0;
    for (int i = 0; i < s->nb; i++)
        for (int cf = s->cf0[i]; cf < s->cf0[i + 1]; cf++) n += s->poly[i].flen[s->cf_face[cf]];
    if (!ALLOC(s->cf_v0, s->ncf + 1) || !ALLOC(s->cf_v, n))
        return rd_error_set(err, "out of memory");
    n = 0;
    for (int i = 0; i < s->nb; i++) {
        const rd_poly *p = &s->poly[i];
        for (int cf = s->cf0[i]; cf < s->cf0[i + 1]; cf++) {
            int f = s->cf_face[cf];
            s->cf_v0[cf] = n;
            for (int k = 0; k < p->flen[f]; k++)
                s->cf_v[n++] = 2 * s->cv_slot[s->vert0[i] + p->fidx[p->fstart[f] + k]];
        }
    }
    s->cf_v0[s->ncf] = n;
    return 0;
}

int rd_setup_contacts(rd_sim *s, rd_error *err)
{
    if (rd_joints_init(s, err)) return -1;
    if (build_points(s, err) || build_step_vertices(s, err) || rd_edge_init(s, err) ||
        rd_perturb_points(s, err) || rd_merge_points(s, err) || face_vertices(s, err) ||
        share_points(s, err) || rd_pairs_init(s, err) || rd_surface_init(s, err))
        return -1;
    return 0;
}
