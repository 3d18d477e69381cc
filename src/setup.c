/* rockdem — building a simulation from a scenario: bodies (shape, mass properties, pose),
 * subcontact points on the faces that can touch, and the contact pairs with their history.
 *
 * Leave out what the scene does not need: a face carries subcontact points only if it faces
 * down at the start (it may land on what is below) or lies on another body's face (a stack
 * joint). Fixed pedestals carry no points: a free body's own points already integrate the
 * joint over its footprint (weight 1); where two free bodies meet, both point sets carry half
 * the stiffness (3DEC's averaging of the two faces' subcontacts). Pairs are made by the broad
 * phase (pairs.c) when two bodies first come near each other. */
#include "sim.h"
#include "vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define ALLOC(ptr, n) ((ptr) = calloc((size_t)(n) > 0 ? (size_t)(n) : 1, sizeof *(ptr)))

/* Orientation from rotations about x, then y, then z (extrinsic, rad), times the principal axes. */
static void initial_orientation(const double rot[3], const double axes[9], double q[4])
{
    double qx[4], qy[4], qz[4], qa[4], t1[4], t2[4];
    double ex[3] = {rot[0], 0, 0}, ey[3] = {0, rot[1], 0}, ez[3] = {0, 0, rot[2]};
    rd_quat_from_rotvec(ex, qx);
    rd_quat_from_rotvec(ey, qy);
    rd_quat_from_rotvec(ez, qz);
    rd_quat_from_mat(axes, qa);
    rd_quat_mul(qy, qx, t1);
    rd_quat_mul(qz, t1, t2);
    rd_quat_mul(t2, qa, q);
}

static int build_body(rd_sim *s, int i, rd_error *err)
{
    const rd_body_def *d = &s->sc.bodies[i];
    rd_mass m;
    if (rd_poly_brick(&s->poly[i], d->size, err)) return -1;
    if (rd_poly_mass(&s->poly[i], &m, err)) return -1;
    rd_poly_to_frame(&s->poly[i], &m);
    double density = d->mass > 0 ? d->mass / m.volume : (d->density > 0 ? d->density : s->sc.density);
    s->mass[i] = density * m.volume;
    for (int k = 0; k < 3; k++) s->inertia[i][k] = density * m.principal[k];
    initial_orientation(d->rotation, m.axes, s->q[i]);
    /* the centroid given in the file is the brick's centre; its mass centre is the same point */
    rd_copy3(d->position, s->x[i]);
    s->fixed[i] = d->fixed;
    return 0;
}

int rd_setup_bodies(rd_sim *s, rd_error *err)
{
    int nb = s->nb = s->sc.nbodies;
    if (!ALLOC(s->poly, nb) || !ALLOC(s->x, nb) || !ALLOC(s->q, nb) || !ALLOC(s->v, nb) ||
        !ALLOC(s->L, nb) || !ALLOC(s->w, nb) || !ALLOC(s->R, nb) || !ALLOC(s->mass, nb) ||
        !ALLOC(s->inertia, nb) || !ALLOC(s->fixed, nb) || !ALLOC(s->f, nb) || !ALLOC(s->tq, nb) ||
        !ALLOC(s->v_old, nb) || !ALLOC(s->L_old, nb) || !ALLOC(s->free_body, nb) ||
        !ALLOC(s->free_of, nb) || !ALLOC(s->vert0, nb + 1) || !ALLOC(s->face0, nb + 1))
        return rd_error_set(err, "out of memory");
    for (int i = 0; i < nb; i++) {
        if (build_body(s, i, err)) return -1;
        if (s->poly[i].nf > RD_MAX_PLANES)
            return rd_error_set(err, "%s:%d: body '%s' has %d faces; at most %d are supported",
                                s->sc.file, s->sc.bodies[i].line, s->sc.bodies[i].name,
                                s->poly[i].nf, RD_MAX_PLANES);
        s->free_of[i] = s->fixed[i] ? -1 : s->nfree;
        if (!s->fixed[i]) s->free_body[s->nfree++] = i;
        s->vert0[i + 1] = s->vert0[i] + s->poly[i].nv;
        s->face0[i + 1] = s->face0[i] + s->poly[i].nf;
    }
    if (!ALLOC(s->wv, s->vert0[nb]) || !ALLOC(s->wn, s->face0[nb]) || !ALLOC(s->wd, s->face0[nb]))
        return rd_error_set(err, "out of memory");
    /* world geometry of every body, once (fixed bodies never change) */
    for (int i = 0; i < nb; i++) {
        int fx = s->fixed[i];
        s->fixed[i] = 0;
        rd_bodies_refresh(s);
        s->fixed[i] = fx;
    }
    for (int i = 0; i < nb; i++) rd_quat_to_mat(s->q[i], s->R[i]);
    return 0;
}

/* Does face f of body i lie on a face of another body (antiparallel normals, coplanar)? */
static int face_touches(const rd_sim *s, int i, int f, double tol)
{
    const double *n = s->wn[s->face0[i] + f];
    const rd_poly *p = &s->poly[i];
    for (int j = 0; j < s->nb; j++) {
        if (j == i) continue;
        for (int g = 0; g < s->poly[j].nf; g++) {
            const double *m = s->wn[s->face0[j] + g];
            double dg = s->wd[s->face0[j] + g];
            if (rd_dot(n, m) > -0.999) continue;
            int on = 1;
            for (int k = 0; k < p->flen[f] && on; k++)
                on = fabs(rd_dot(m, s->wv[s->vert0[i] + p->fidx[p->fstart[f] + k]]) - dg) < tol;
            if (on) return 1;
        }
    }
    return 0;
}

static int is_candidate(const rd_sim *s, int i, int f)
{
    if (s->fixed[i]) return 0;
    const double *n = s->wn[s->face0[i] + f];
    return n[2] < -0.5 || face_touches(s, i, f, 1e-6 * (1.0 + s->poly[i].radius));
}

/* Automatic spacing: a tenth of the shortest edge of the candidate faces. */
static double auto_spacing(const rd_sim *s)
{
    double emin = INFINITY;
    for (int i = 0; i < s->nb; i++) {
        const rd_poly *p = &s->poly[i];
        for (int f = 0; f < p->nf; f++) {
            if (!is_candidate(s, i, f)) continue;
            for (int k = 0; k < p->flen[f]; k++) {
                const double *a = p->v[p->fidx[p->fstart[f] + k]];
                const double *b = p->v[p->fidx[p->fstart[f] + (k + 1) % p->flen[f]]];
                double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
                emin = fmin(emin, rd_norm(e));
            }
        }
    }
    return isfinite(emin) ? emin / 10.0 : 0.0;
}

static int build_points(rd_sim *s, double spacing, rd_error *err)
{
    int nb = s->nb, npts = 0, ncf = 0;
    if (!ALLOC(s->pt0, nb + 1) || !ALLOC(s->cf0, nb + 1)) return rd_error_set(err, "out of memory");
    for (int pass = 0; pass < 2; pass++) {
        npts = ncf = 0;
        for (int i = 0; i < nb; i++) {
            s->pt0[i] = npts; s->cf0[i] = ncf;
            for (int f = 0; f < s->poly[i].nf; f++) {
                if (!is_candidate(s, i, f)) continue;
                int n = pass ? rd_poly_face_points(&s->poly[i], f, spacing, s->pl + npts, s->pa + npts, s->npts - npts)
                             : rd_poly_face_points(&s->poly[i], f, spacing, NULL, NULL, 0);
                if (n < 0) return rd_error_set(err, "cannot mesh face %d of body '%s'", f, s->sc.bodies[i].name);
                if (pass) { s->cf_face[ncf] = f; s->cf_pt0[ncf] = npts; }
                npts += n; ncf++;
            }
        }
        s->pt0[nb] = npts; s->cf0[nb] = ncf;
        if (!pass) {
            s->npts = npts; s->ncf = ncf;
            if (!ALLOC(s->pl, npts) || !ALLOC(s->pa, npts) || !ALLOC(s->cf_face, ncf) || !ALLOC(s->cf_pt0, ncf + 1))
                return rd_error_set(err, "out of memory");
        }
    }
    s->cf_pt0[ncf] = npts;
    return 0;
}

int rd_setup_contacts(rd_sim *s, rd_error *err)
{
    double spacing = s->sc.contact.spacing < 0 ? auto_spacing(s) : s->sc.contact.spacing;
    s->sc.contact.spacing = spacing;
    s->tan_phi = tan(s->sc.contact.friction);
    s->bonds = s->sc.contact.tension > 0 || s->sc.contact.cohesion > 0;
    s->can_cull = !s->bonds;
    if (build_points(s, spacing, err) || rd_pairs_init(s, err)) return -1;
    return 0;
}
