/* rockdem — contact from the touching surfaces (`contact model surface`; docs/CONTACT.md
 * section 8).
 *
 * For each live pair, the reference body r is a convex one (the fixed one when both are), the
 * integration body the other. A point p of the integration body's surface is inside r when it
 * lies behind every face plane of r, and its depth is its distance below the nearest one,
 * min over g of d_g(p) = dR_g - u_g . p: for convex r the exact depth, continuous across faces.
 * For a plane P of the integration body (its coplanar faces together) and a face g of r, the
 * patch is the part of P's faces where g is the nearest plane and p is behind it: each face's
 * polygon clipped first by d_h >= 0 for every face h of r (inside r: once per plane and step),
 * then by the half-planes d_h - d_g >= 0 (every other face h), all affine in P's coordinates. No facing rule: the penetration energy (KN / 2) integral of d^2
 * over the whole surface is then a continuous function of the pose (a rule that admitted a
 * block's side face once it faced the floor within 80 deg gave it, at that tilt, the wedge
 * already below the floor at once: 6.5 J created in one step of a rocking block under a 0.78 g
 * pulse). The Winkler pressure KN d_g over that region gives the force and both moments
 * exactly from its area moments (contact/patch.c), and its twisting lever in closed form about
 * the region's centroid. State (shear spring, twisting spring) is kept per patch, keyed by the
 * pair, P and g (Box2D keeps a manifold's impulses by feature ids): it persists while the patch
 * moves, grows and shrinks, and follows its region's area (rd_patch_spring_resize).
 * The normal force at each material point of the integration body is KN d_g u_g, the gradient
 * of the energy (KN / 2) d^2 of that point (the limit of a bed of vertex subcontacts as its
 * spacing goes to zero), and its reaction acts on r at the same point: the normal law is
 * conservative but for the edges of the integration faces that pass inside r with depth (a
 * base sliding over a pedestal's edge), where the energy KN d^2 / 2 of the material that
 * crosses is released, a fraction d / L of the stored energy.
 * Impact loss: the joint's normal dashpot (`model damping viscous` or a joint's damping), a
 * pressure c_a dd/dt with c_a = 2 zeta KN sqrt(m_eff / K_active), integrated implicitly
 * (engine/dashpot.c: it does not shorten the step); the permanent set of the vertex model
 * (`restitution` < 1) has no patch form and is refused, as are cohesion and tension, and two
 * non-convex bodies that may touch.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * contact/, geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "engine/law.h"
#include "engine/dashpot.h"
#include "contact/contact.h"
#include "base/vec.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Faces of one body lie in one plane when their normals' dot product exceeds 1 - this and
 * their offsets differ by at most RD_FACE_TOL (1 m + the body's radius). */
#define RD_SURF_COPLANAR  1e-9
/* A face wholly deeper than this fraction of the smaller bounding radius behind a plane of r is
 * taken as not touching it (a mesh's far side): such a depth ends the run as penetrated
 * (monitor.c) long before a touching face gets there. */
#define RD_SURF_DEPTH_CAP 0.25

/* The planes of one body, body frame. */
typedef struct surf_body {
    int nplane;
    int *plane_f0;         /* [nplane + 1] first entry of each plane's faces in plane_face */
    int *plane_face;       /* face indices, grouped by plane */
    double (*frame)[4][3]; /* per plane: origin o, axes e1, e2, outward normal n = e1 x e2, m */
    int *f2_0;             /* [nf + 1] first vertex of face f in f2 */
    double (*f2)[2];       /* the faces' polygons in their plane's coordinates, counter-clockwise */
    double (*box)[4];      /* per plane: the bounding box of its faces in its coordinates, m (x
                               min, y min, x max, y max): an affine depth's bounds over the plane
                               are at its corners */
} surf_body;

/* The state of one patch, keyed by (pair, plane of the integration body, face of r). */
typedef struct surf_state {
    uint64_t key;
    rd_patch_spring sp;
    double e2;  /* integral of d^2 over the compressed region at the last step, m^4 */
    double kn;  /* KN, Pa/m (its normal energy is kn e2 / 2) */
    double ks;  /* KS, Pa/m */
    long stamp; /* the surface step that last loaded it */
} surf_state;

/* A pair's joint measures from its patches at one step (rd_surface_joint_measure). */
typedef struct surf_meas {
    double fn, fs_b[3], cop[3], wsum, area;
} surf_meas;

struct rd_surface {
    surf_body *body; /* [nb] */
    surf_state *st;  /* patches met so far */
    int nst, cap_st;
    int *hash, hcap;      /* key -> index into st, -1 empty; hcap a power of 2 */
    int *on, non, cap_on; /* patches loaded at the last step */
    int *on_next, non_next, cap_on_next;
    rd_poly2 *comp; /* scratch: one patch's compressed pieces */
    int cap_comp;
    rd_poly2 *ins; /* scratch: the parts of one plane's faces inside r */
    int cap_ins;
    double (*pl)[4];  /* scratch: r's planes in the integration body's frame (u, d) */
    double (*uw)[3];  /* scratch: r's outward normals, ground frame */
    double (*dep)[3]; /* scratch: depth below each plane of r, affine in a plane's coords */
    int cap_pl;
    rd_patch_scratch tsc; /* scratch of rd_patch_torsion_set */
    rd_dashpots dp;       /* this step's patch dashpots, solved implicitly (dashpot.c) */
    surf_meas *meas;      /* per pair, its joint's measures at the last step it was live */
    int cap_meas;
    long stamp; /* surface steps taken */
};

static int grow(void **arr, int *cap, int n, size_t size)
{
    if (n <= *cap) return 0;
    int c = *cap ? *cap : 16;
    while (c < n) c *= 2;
    void *p = realloc(*arr, (size_t)c * size);
    if (!p) return -1;
    *arr = p;
    *cap = c;
    return 0;
}

static uint64_t state_key(int pair, int plane, int face)
{
    return ((uint64_t)pair << 42) | ((uint64_t)plane << 21) | (uint64_t)face;
}

static unsigned key_hash(uint64_t k)
{
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    return (unsigned)k;
}

static int rehash(struct rd_surface *S, int hcap)
{
    int *h = malloc((size_t)hcap * sizeof *h);
    if (!h) return -1;
    for (int k = 0; k < hcap; k++) h[k] = -1;
    for (int i = 0; i < S->nst; i++) {
        unsigned m = (unsigned)hcap - 1, q = key_hash(S->st[i].key) & m;
        while (h[q] >= 0) q = (q + 1) & m;
        h[q] = i;
    }
    free(S->hash);
    S->hash = h;
    S->hcap = hcap;
    return 0;
}

/* The patch of key k, created unloaded when first met; NULL when out of memory. */
static surf_state *state_of(struct rd_surface *S, uint64_t k)
{
    unsigned m = (unsigned)S->hcap - 1, q = key_hash(k) & m;
    for (; S->hash[q] >= 0; q = (q + 1) & m)
        if (S->st[S->hash[q]].key == k) return &S->st[S->hash[q]];
    if (2 * (S->nst + 1) > S->hcap) {
        if (rehash(S, 2 * S->hcap)) return NULL;
        return state_of(S, k);
    }
    if (grow((void **)&S->st, &S->cap_st, S->nst + 1, sizeof *S->st)) return NULL;
    surf_state *st = &S->st[S->nst];
    memset(st, 0, sizeof *st);
    st->key = k;
    st->stamp = -1;
    S->hash[q] = S->nst++;
    return st;
}

/* Body i's faces grouped by plane, each plane's frame, the faces' polygons in it. */
static int body_planes(const rd_poly *P, surf_body *B, rd_error *err, const char *name)
{
    int nf = P->nf, nv2 = 0;
    for (int f = 0; f < nf; f++) {
        if (P->flen[f] > RD_PATCH_FACE_MAX) {
            rd_error_set(err,
                         "contact model surface: body '%s' has a face of %d vertices (at most %d)",
                         name, P->flen[f], RD_PATCH_FACE_MAX);
            return -1;
        }
        nv2 += P->flen[f];
    }
    int *plane_of = malloc((size_t)nf * sizeof *plane_of);
    B->frame = malloc((size_t)(nf ? nf : 1) * sizeof *B->frame);
    B->plane_f0 = calloc((size_t)nf + 1, sizeof *B->plane_f0);
    B->plane_face = malloc((size_t)(nf ? nf : 1) * sizeof *B->plane_face);
    B->f2_0 = malloc(((size_t)nf + 1) * sizeof *B->f2_0);
    B->f2 = malloc((size_t)(nv2 ? nv2 : 1) * sizeof *B->f2);
    double *pd = malloc((size_t)(nf ? nf : 1) * sizeof *pd);
    if (!plane_of || !B->frame || !B->plane_f0 || !B->plane_face || !B->f2_0 || !B->f2 || !pd) {
        free(plane_of);
        free(pd);
        rd_error_set(err, "out of memory");
        return -1;
    }
    const double tol = RD_FACE_TOL * (1.0 + P->radius);
    B->nplane = 0;
    for (int f = 0; f < nf; f++) {
        int k = 0;
        for (; k < B->nplane; k++)
            if (rd_dot(B->frame[k][3], P->fn[f]) > 1 - RD_SURF_COPLANAR &&
                fabs(pd[k] - P->fd[f]) <= tol)
                break;
        if (k == B->nplane) { /* a new plane: its frame from the face's first vertex and edge */
            const double *v0 = P->v[P->fidx[P->fstart[f]]], *v1 = P->v[P->fidx[P->fstart[f] + 1]];
            double *o = B->frame[k][0], *e1 = B->frame[k][1], *e2 = B->frame[k][2],
                   *n = B->frame[k][3];
            rd_copy3(P->fn[f], n);
            rd_copy3(v0, o);
            double e[3] = { v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2] };
            rd_axpy(-rd_dot(e, n), n, e);
            double le = rd_norm(e);
            for (int c = 0; c < 3; c++) e1[c] = e[c] / le;
            rd_cross(n, e1, e2);
            pd[k] = P->fd[f];
            B->nplane++;
        }
        plane_of[f] = k;
        B->plane_f0[k + 1]++;
    }
    for (int k = 0; k < B->nplane; k++) B->plane_f0[k + 1] += B->plane_f0[k];
    int *fill = calloc((size_t)B->nplane + 1, sizeof *fill);
    if (!fill) {
        free(plane_of);
        free(pd);
        rd_error_set(err, "out of memory");
        return -1;
    }
    for (int f = 0; f < nf; f++) B->plane_face[B->plane_f0[plane_of[f]] + fill[plane_of[f]]++] = f;
    int w = 0;
    for (int f = 0; f < nf; f++) {
        const double(*fr)[3] = B->frame[plane_of[f]];
        B->f2_0[f] = w;
        for (int j = 0; j < P->flen[f]; j++) {
            const double *v = P->v[P->fidx[P->fstart[f] + j]];
            double d[3] = { v[0] - fr[0][0], v[1] - fr[0][1], v[2] - fr[0][2] };
            B->f2[w][0] = rd_dot(d, fr[1]);
            B->f2[w][1] = rd_dot(d, fr[2]);
            w++;
        }
    }
    B->f2_0[nf] = w;
    B->box = malloc((size_t)(B->nplane ? B->nplane : 1) * sizeof *B->box);
    if (!B->box) {
        free(fill);
        free(plane_of);
        free(pd);
        rd_error_set(err, "out of memory");
        return -1;
    }
    for (int k = 0; k < B->nplane; k++) {
        double *bx = B->box[k];
        bx[0] = bx[1] = DBL_MAX;
        bx[2] = bx[3] = -DBL_MAX;
        for (int e = B->plane_f0[k]; e < B->plane_f0[k + 1]; e++)
            for (int q = B->f2_0[B->plane_face[e]]; q < B->f2_0[B->plane_face[e] + 1]; q++)
                for (int c = 0; c < 2; c++) {
                    bx[c] = rd_min(bx[c], B->f2[q][c]);
                    bx[c + 2] = rd_max(bx[c + 2], B->f2[q][c]);
                }
    }
    free(fill);
    free(plane_of);
    free(pd);
    return 0;
}

int rd_surface_init(rd_sim *s, rd_error *err)
{
    s->surf = NULL;
    if (s->sc.contact.model != RD_CONTACT_SURFACE) return 0;
    for (int j = 0; j < s->njoint; j++) {
        const rd_joint *jt = &s->joint[j];
        if (jt->restitution < 1) {
            rd_error_set(
                err,
                "contact model surface: restitution %g is not modelled (its impact loss is the "
                "joint's dashpot, 'model damping viscous'); give 'contact property restitution 1'",
                jt->restitution);
            return -1;
        }
        if (jt->cohesion > 0 || jt->tension > 0) {
            rd_error_set(
                err,
                "contact model surface: cohesion and tension are not modelled; give them as 0");
            return -1;
        }
    }
    if (s->sc.save_path[0] || s->sc.restore_path[0]) {
        rd_error_set(err,
                     "contact model surface: 'model %s' is not supported yet (a checkpoint "
                     "holds the vertex subcontacts' state, not the patches')",
                     s->sc.save_path[0] ? "save" : "restore");
        return -1;
    }
    for (int a = 0; a < s->nb; a++)
        for (int b = a + 1; b < s->nb; b++)
            if (!s->convex[a] && !s->convex[b] && !(s->fixed[a] && s->fixed[b])) {
                rd_error_set(
                    err,
                    "contact model surface: bodies '%s' and '%s' are both non-convex: a patch needs "
                    "a convex body on one side",
                    s->sc.bodies[a].name, s->sc.bodies[b].name);
                return -1;
            }
    struct rd_surface *S = calloc(1, sizeof *S);
    if (!S) {
        rd_error_set(err, "out of memory");
        return -1;
    }
    s->surf = S;
    S->body = calloc((size_t)s->nb, sizeof *S->body);
    if (!S->body || rehash(S, 64)) {
        rd_error_set(err, "out of memory");
        return -1;
    }
    int most = 0;
    for (int i = 0; i < s->nb; i++) {
        if (body_planes(&s->poly[i], &S->body[i], err, s->sc.bodies[i].name)) return -1;
        if (s->poly[i].nf > most) most = s->poly[i].nf;
    }
    if (grow((void **)&S->pl, &S->cap_pl, most, sizeof *S->pl)) {
        rd_error_set(err, "out of memory");
        return -1;
    }
    S->uw = malloc((size_t)S->cap_pl * sizeof *S->uw);
    S->dep = malloc((size_t)S->cap_pl * sizeof *S->dep);
    if (!S->uw || !S->dep) {
        rd_error_set(err, "out of memory");
        return -1;
    }
    return 0;
}

/* The largest area body i can press on one body at once, m^2, for the critical step
 * (timestep.c): its largest plane, and half its second one (toppled onto an edge, the two faces
 * around it each bear a part: the rule of the vertex model's late faces). */
double rd_surface_contact_area(const rd_sim *s, int i)
{
    const surf_body *B = &s->surf->body[i];
    const rd_poly *P = &s->poly[i];
    double a1 = 0, a2 = 0;
    for (int k = 0; k < B->nplane; k++) {
        double a = 0;
        for (int e = B->plane_f0[k]; e < B->plane_f0[k + 1]; e++) {
            const int f = B->plane_face[e];
            rd_poly2 p = { P->flen[f], { { 0 } } };
            memcpy(p.p, B->f2 + B->f2_0[f], (size_t)p.n * sizeof p.p[0]);
            rd_moments m;
            rd_patch_moments(&p, &m);
            a += m.a;
        }
        if (a > a1) {
            a2 = a1;
            a1 = a;
        } else if (a > a2)
            a2 = a;
    }
    return a1 + 0.5 * a2;
}

void rd_surface_free(rd_sim *s)
{
    struct rd_surface *S = s->surf;
    if (!S) return;
    for (int i = 0; S->body && i < s->nb; i++) {
        surf_body *B = &S->body[i];
        free(B->plane_f0);
        free(B->plane_face);
        free(B->frame);
        free(B->f2_0);
        free(B->f2);
        free(B->box);
    }
    free(S->body);
    free(S->st);
    free(S->hash);
    free(S->on);
    free(S->on_next);
    free(S->comp);
    free(S->ins);
    free(S->pl);
    free(S->uw);
    free(S->dep);
    free(S->tsc.slot);
    free(S->tsc.count);
    free(S->tsc.ends);
    rd_dashpots_free(&S->dp);
    free(S->meas);
    free(S);
    s->surf = NULL;
}

/* What one side of a pair gathers over its patches (ground frame): force and torque on the
 * integration body (about its centre), the normal force along a -> b, stiffness and area. */
typedef struct surf_sums {
    double f[3], tq[3], nsum[3];
    double k_active, area;
    int nact, nslip;
    double fn, fs_b[3], cop[3], wsum; /* the joint's measures (rd_surface_joint_measure): normal
                                         force (N), shear force on the pair's second body (N),
                                         |fn|-weighted sum of the patches' centres of pressure
                                         (N m) and its weight (N) */
} surf_sums;

/* The dashpot of one patch (c_a, Pa s/m; region moments m; the plane's origin O from i's centre
 * and axes E1, E2, r's outward normal u, ground frame) into the step's implicit solve
 * (dashpot.c): u . vrel at (x, y) of the plane is (g0 + x g1 + y g2) . xi over the two bodies,
 * g0 = (u, O x u) and gk = (0, Ek x u) for i, their negatives for r with O + x_i - x_r. */
static int patch_dashpot(rd_sim *s, int i, int r, double c_a, const rd_moments *m,
                         const double O[3], const double E1[3], const double E2[3],
                         const double u[3])
{
    rd_dashpot *e = rd_dashpot_new(&s->surf->dp);
    if (!e) return -1;
    e->a = s->fixed[i] ? -1 : i;
    e->b = s->fixed[r] ? -1 : r;
    e->c = c_a;
    const double mm[6] = { m->a, m->sx, m->sy, m->sxx, m->sxy, m->syy };
    memcpy(e->m, mm, sizeof mm);
    double Or[3];
    for (int k = 0; k < 3; k++) Or[k] = O[k] + s->x[i][k] - s->x[r][k];
    const double *lever[2][3] = { { O, E1, E2 }, { Or, E1, E2 } };
    for (int sd = 0; sd < 2; sd++) {
        const double sg = sd ? -1.0 : 1.0;
        for (int k = 0; k < 3; k++) {
            double t[3];
            rd_cross(lever[sd][k], u, t);
            for (int p = 0; p < 3; p++) {
                e->g[sd][k][p] = k == 0 ? sg * u[p] : 0.0;
                e->g[sd][k][3 + p] = sg * t[p];
            }
        }
    }
    return 0;
}

/* One patch (plane P of body i against face g of r) with the compressed region's moments m,
 * its load ld (depth coefficients dep, plane frame fr) and twisting lever tors: the law, its
 * forces into the sums. */
static int patch_apply(rd_sim *s, rd_pair *pr, int pair, int i, int r, int P, int g,
                       const rd_moments *m, const rd_patch_load *ld, double tors,
                       const double fr[4][3], const double dep[3], double c_a, surf_sums *sum)
{
    struct rd_surface *S = s->surf;
    const rd_joint *j = &s->joint[pr->joint];
    surf_state *st = state_of(S, state_key(pair, P, g));
    if (!st) return -1;
    const double *uw = S->uw[g], *Ri = s->R[i], *xi = s->x[i], *xr = s->x[r];
    const int r_free = !s->fixed[r];
    double O[3], E1[3], E2[3]; /* the plane's origin (from i's centre) and axes, ground frame */
    rd_mat_vec(Ri, fr[0], O);
    rd_mat_vec(Ri, fr[1], E1);
    rd_mat_vec(Ri, fr[2], E2);
    double wrel[3] = { s->w[i][0], s->w[i][1], s->w[i][2] };
    if (r_free) rd_axpy(-1.0, s->w[r], wrel);
    double rt[3];
    if (c_a > 0 && patch_dashpot(s, i, r, c_a, m, O, E1, E2, uw)) return -1;
    /* the normal pressure KN d, affine, integrated over the region */
    double q[3];
    for (int k = 0; k < 3; k++) q[k] = j->kn * dep[k];
    double fn = q[0] * m->a + q[1] * m->sx + q[2] * m->sy;
    double mx = q[0] * m->sx + q[1] * m->sxx + q[2] * m->sxy;
    double my = q[0] * m->sy + q[1] * m->sxy + q[2] * m->syy;
    double F[3], tq[3], tmp[3];
    for (int k = 0; k < 3; k++) F[k] = fn * uw[k];
    rd_cross(O, uw, tq);
    for (int k = 0; k < 3; k++) tq[k] *= fn;
    rd_cross(E1, uw, tmp);
    rd_axpy(mx, tmp, tq);
    rd_cross(E2, uw, tmp);
    rd_axpy(my, tmp, tq);
    /* shear and twist at the region's centroid */
    double C[3];
    for (int k = 0; k < 3; k++) C[k] = O[k] + ld->cx * E1[k] + ld->cy * E2[k];
    for (int k = 0; k < 3; k++) rt[k] = xi[k] + C[k] - xr[k];
    double vr[3];
    rd_law_relative_velocity_of(s->v[i], s->w[i], s->v[r], s->w[r], r_free, C, rt, vr);
    double vn = rd_dot(vr, uw), spin = rd_dot(wrel, uw);
    rd_patch_spring *sp = &st->sp;
    s->e_fric += rd_patch_spring_resize(sp, j->ks, ld->area, ld->polar);
    rd_law_shear_turn(sp->fs, uw);
    const double f0[3] = { sp->fs[0], sp->fs[1], sp->fs[2] }, m0 = sp->mt;
    const double kA = j->ks * ld->area, kJ = j->ks * ld->polar;
    rd_law_shear_load(sp->fs, uw, vr, vn, kA, s->dt);
    sp->mt -= kJ * spin * s->dt;
    double flim = j->tan_phi * rd_max(fn, 0.0), mlim = ld->f > 0 ? flim * tors / ld->f : 0.0;
    int slip = rd_patch_spring_cap(sp, f0, m0, kA, kJ, flim, mlim, &s->e_fric);
    rd_axpy(1.0, sp->fs, F);
    rd_cross(C, sp->fs, tmp);
    rd_axpy(1.0, tmp, tq);
    rd_axpy(sp->mt, uw, tq);
    rd_axpy(1.0, F, sum->f);
    rd_axpy(1.0, tq, sum->tq);
    rd_axpy(r == pr->a ? fn : -fn, uw, sum->nsum);
    /* the joint's measures: the spring's normal force, its centre of pressure (mx, my) / fn in
       the plane, the shear springs on the pair's second body */
    const double sg = fn < 0 ? -1.0 : 1.0;
    for (int k = 0; k < 3; k++) {
        sum->cop[k] += sg * (fn * (xi[k] + O[k]) + mx * E1[k] + my * E2[k]);
        sum->fs_b[k] += (i == pr->b ? 1.0 : -1.0) * sp->fs[k];
    }
    sum->fn += fn;
    sum->wsum += fabs(fn);
    sum->k_active += j->kn * ld->area;
    sum->area += ld->area;
    sum->nact++;
    sum->nslip += slip;
    st->e2 = ld->e2;
    st->kn = j->kn;
    st->ks = j->ks;
    if (st->stamp != S->stamp) {
        if (grow((void **)&S->on_next, &S->cap_on_next, S->non_next + 1, sizeof *S->on_next))
            return -1;
        S->on_next[S->non_next++] = (int)(st - S->st);
        st->stamp = S->stamp;
    }
    return 0;
}

/* Copy polygon b's vertices into a (a polygon holds RD_PATCH_MAX: only the used ones move). */
static void poly_copy(rd_poly2 *a, const rd_poly2 *b)
{
    a->n = b->n;
    memcpy(a->p, b->p, (size_t)b->n * sizeof b->p[0]);
}

/* The parts of plane P's faces (body i) inside r, behind every plane of r (d_h >= 0), into
 * S->ins: found once per plane and step, so a plane that does not reach r costs one pass, and
 * each face g then clips only what is inside. A face whose every vertex lies deeper than cap
 * below the nearest plane is left out (a mesh's far side). Returns the count, -1 when out of
 * memory. */
static int plane_inside(rd_sim *s, const surf_body *B, int i, int P, int nr, double cap)
{
    struct rd_surface *S = s->surf;
    const rd_poly *Pi = &s->poly[i];
    const double *bx = B->box[P];
    for (int h = 0; h < nr; h++) { /* the whole plane in front of one plane of r: outside it */
        const double *dh = S->dep[h];
        double hi =
            dh[0] + rd_max(dh[1] * bx[0], dh[1] * bx[2]) + rd_max(dh[2] * bx[1], dh[2] * bx[3]);
        if (hi <= 0) return 0;
    }
    int n = 0;
    for (int e = B->plane_f0[P]; e < B->plane_f0[P + 1]; e++) {
        const int f = B->plane_face[e], nv = Pi->flen[f];
        const double(*v2)[2] = B->f2 + B->f2_0[f];
        if (grow((void **)&S->ins, &S->cap_ins, n + 2, sizeof *S->ins)) return -1;
        rd_poly2 *a = &S->ins[n], *b = &S->ins[n + 1];
        a->n = nv;
        memcpy(a->p, v2, (size_t)nv * sizeof *v2);
        int alive = 1;
        double deep =
            DBL_MAX; /* the least, over the face's vertices, of their nearest-plane depth */
        for (int k = 0; k < nv; k++) {
            double dmin = DBL_MAX;
            for (int h = 0; h < nr; h++)
                dmin =
                    rd_min(dmin, S->dep[h][0] + S->dep[h][1] * v2[k][0] + S->dep[h][2] * v2[k][1]);
            deep = rd_min(deep, dmin);
        }
        if (deep > cap) continue;
        for (int h = 0; h < nr && alive; h++) {
            const double *dh = S->dep[h];
            int cut = 0;
            for (int k = 0; k < a->n && !cut; k++)
                cut = dh[0] + dh[1] * a->p[k][0] + dh[2] * a->p[k][1] < 0;
            if (!cut) continue;
            alive = rd_patch_clip_half(a, dh[1], dh[2], dh[0], b) > 0;
            rd_poly2 *t = a;
            a = b;
            b = t;
        }
        if (!alive) continue;
        if (a != &S->ins[n]) poly_copy(&S->ins[n], a);
        n++;
    }
    return n;
}

/* The parts of the inside pieces S->ins[0 .. nin) where face g of r is the nearest plane (d_h -
 * d_g >= 0 for every other face h): into S->comp, their moments summed into *m. Returns the
 * piece count, -1 when out of memory. */
static int nearest_pieces(struct rd_surface *S, int nin, int g, int nr, rd_moments *m)
{
    const double *dg = S->dep[g];
    int n = 0;
    *m = (rd_moments){ 0, 0, 0, 0, 0, 0 };
    for (int e = 0; e < nin; e++) {
        if (grow((void **)&S->comp, &S->cap_comp, n + 2, sizeof *S->comp)) return -1;
        rd_poly2 *a = &S->comp[n], *b = &S->comp[n + 1];
        poly_copy(a, &S->ins[e]);
        int alive = 1;
        for (int h = 0; h < nr && alive; h++) {
            if (h == g) continue;
            const double *dh = S->dep[h];
            double c0 = dh[0] - dg[0], cx = dh[1] - dg[1], cy = dh[2] - dg[2];
            int cut = 0;
            for (int k = 0; k < a->n && !cut; k++) cut = c0 + cx * a->p[k][0] + cy * a->p[k][1] < 0;
            if (!cut) continue;
            alive = rd_patch_clip_half(a, cx, cy, c0, b) > 0;
            rd_poly2 *t = a;
            a = b;
            b = t;
        }
        if (!alive) continue;
        if (a != &S->comp[n]) poly_copy(&S->comp[n], a);
        rd_moments pm;
        rd_patch_moments(&S->comp[n], &pm);
        if (!(pm.a > 0)) continue;
        m->a += pm.a;
        m->sx += pm.sx;
        m->sy += pm.sy;
        m->sxx += pm.sxx;
        m->sxy += pm.sxy;
        m->syy += pm.syy;
        n++;
    }
    return n;
}

/* Pair number pair's joint measures from this step's sums. 0, -1 when out of memory. */
static int measure_store(rd_sim *s, int pair, const surf_sums *sum)
{
    struct rd_surface *S = s->surf;
    if (pair >= S->cap_meas) {
        int c = S->cap_meas ? S->cap_meas : 16;
        while (c <= pair) c *= 2;
        surf_meas *m = realloc(S->meas, (size_t)c * sizeof *m);
        if (!m) return -1;
        memset(m + S->cap_meas, 0, (size_t)(c - S->cap_meas) * sizeof *m);
        S->meas = m;
        S->cap_meas = c;
    }
    surf_meas *m = &S->meas[pair];
    m->fn = sum->fn;
    m->wsum = sum->wsum;
    m->area = sum->area;
    rd_copy3(sum->fs_b, m->fs_b);
    rd_copy3(sum->cop, m->cop);
    return 0;
}

/* Every patch of live pair number pair. */
static int pair_step(rd_sim *s, int pair)
{
    struct rd_surface *S = s->surf;
    rd_pair *pr = &s->pair[pair];
    const int a = pr->a, b = pr->b;
    if (s->fixed[a] && s->fixed[b]) return 0;
    int r = (s->convex[a] && s->convex[b]) ? (s->fixed[b] ? b : a) : s->convex[a] ? a : b;
    int i = r == a ? b : a;
    const rd_poly *Pr = &s->poly[r];
    const surf_body *B = &S->body[i];
    const rd_joint *j = &s->joint[pr->joint];
    const int nr = Pr->nf;
    for (int g = 0; g < nr; g++) { /* r's planes, ground frame and i's frame */
        double *uw = S->uw[g], *pl = S->pl[g];
        rd_mat_vec(s->R[r], Pr->fn[g], uw);
        double dw = Pr->fd[g] + rd_dot(uw, s->x[r]);
        rd_mat_tvec(s->R[i], uw, pl);
        pl[3] = dw - rd_dot(uw, s->x[i]);
    }
    const double cap = RD_SURF_DEPTH_CAP * rd_min(Pr->radius, s->poly[i].radius);
    const double c_a = (j->damping > 0 && pr->k_active > 0)
                           ? 2 * j->damping * j->kn * sqrt(pr->m_eff / pr->k_active)
                           : 0.0;
    surf_sums sum = { .nact = 0 }; /* all zero */
    for (int P = 0; P < B->nplane; P++) {
        const double(*fr)[3] = B->frame[P];
        for (int h = 0; h < nr; h++) { /* depth below plane h of r, in P's coordinates */
            const double *pl = S->pl[h];
            S->dep[h][0] = pl[3] - rd_dot(pl, fr[0]);
            S->dep[h][1] = -rd_dot(pl, fr[1]);
            S->dep[h][2] = -rd_dot(pl, fr[2]);
        }
        const int nin = plane_inside(s, B, i, P, nr, cap);
        if (nin < 0) return -1;
        for (int g = 0; g < nr && nin > 0; g++) {
            rd_moments m;
            int n = nearest_pieces(S, nin, g, nr, &m);
            if (n < 0) return -1;
            if (n == 0) continue;
            rd_patch_load ld;
            const double *dg = S->dep[g];
            rd_patch_load_from(&m, dg[0], dg[1], dg[2], &ld);
            if (!(ld.area > 0)) continue;
            const double c[2] = { ld.cx, ld.cy };
            double tors = rd_patch_torsion_set(S->comp, n, c, dg[0], dg[1], dg[2], &S->tsc);
            if (patch_apply(s, pr, pair, i, r, P, g, &m, &ld, tors, fr, dg, c_a, &sum)) return -1;
        }
    }
    /* i takes the sums; r (when free) -F at each point: -(sum tq) - (x_i - x_r) x sum F */
    rd_axpy(1.0, sum.f, s->f[i]);
    rd_axpy(1.0, sum.tq, s->tq[i]);
    if (!s->fixed[r]) {
        double d[3] = { s->x[i][0] - s->x[r][0], s->x[i][1] - s->x[r][1], s->x[i][2] - s->x[r][2] },
               t[3];
        rd_cross(d, sum.f, t);
        rd_axpy(-1.0, sum.f, s->f[r]);
        for (int k = 0; k < 3; k++) s->tq[r][k] -= sum.tq[k] + t[k];
    }
    pr->k_active = sum.k_active;
    double nn = rd_norm(sum.nsum);
    if (nn > 0)
        for (int k = 0; k < 3; k++) pr->n[k] = sum.nsum[k] / nn;
    rd_watch *w = rd_monitor_contact_watch(s, i, r);
    if (w) {
        w->area += sum.area;
        w->nactive += sum.nact;
        w->nslip += sum.nslip;
        if (sum.area > 0 && !s->settling) w->touched = 1;
    }
    if (!s->settling) s->active_point_steps += sum.nact;
    return measure_store(s, pair, &sum);
}

/* The stored energy of a patch, J. */
static double state_energy(const surf_state *st)
{
    const rd_patch_spring *sp = &st->sp;
    double e = 0.5 * st->kn * st->e2;
    if (sp->area > 0) e += rd_dot(sp->fs, sp->fs) / (2 * st->ks * sp->area);
    if (sp->polar > 0) e += sp->mt * sp->mt / (2 * st->ks * sp->polar);
    return e;
}

void rd_surface_step(rd_sim *s)
{
    struct rd_surface *S = s->surf;
    S->stamp++;
    S->non_next = 0;
    for (int k = 0; k < s->nlive; k++)
        if (pair_step(s, s->live[k])) {
            s->status = RD_STATUS_ERROR;
            snprintf(s->errmsg, sizeof s->errmsg, "out of memory (contact patches)");
            return;
        }
    if (rd_dashpot_solve(s, &S->dp)) {
        s->status = RD_STATUS_ERROR;
        snprintf(s->errmsg, sizeof s->errmsg, "out of memory (contact patches)");
        return;
    }
    /* patches loaded last step and not now open: their springs let go (booked as friction) */
    for (int k = 0; k < S->non; k++) {
        surf_state *st = &S->st[S->on[k]];
        if (st->stamp == S->stamp) continue;
        s->e_fric += state_energy(st);
        st->e2 = 0;
        st->sp = (rd_patch_spring){ { 0, 0, 0 }, 0, 0, 0 };
    }
    int *t = S->on;
    S->on = S->on_next;
    S->on_next = t;
    int c = S->cap_on;
    S->cap_on = S->cap_on_next;
    S->cap_on_next = c;
    S->non = S->non_next;
}

double rd_surface_elastic_energy(const rd_sim *s)
{
    const struct rd_surface *S = s->surf;
    double e = 0;
    for (int k = 0; k < S->non; k++) e += state_energy(&S->st[S->on[k]]);
    return e;
}

void rd_surface_reset(rd_sim *s, int body)
{
    struct rd_surface *S = s->surf;
    for (int k = 0; k < S->nst; k++) {
        const rd_pair *pr = &s->pair[S->st[k].key >> 42];
        if (pr->a != body && pr->b != body) continue;
        S->st[k].e2 = 0;
        S->st[k].sp = (rd_patch_spring){ { 0, 0, 0 }, 0, 0, 0 };
    }
}

void rd_surface_joint_measure(const rd_sim *s, const rd_pair *pr, rd_joint_state *m, double *wsum)
{
    const struct rd_surface *S = s->surf;
    const int pair = (int)(pr - s->pair);
    if (pair >= S->cap_meas) return;
    const surf_meas *q = &S->meas[pair];
    m->fn = q->fn;
    m->area = q->area;
    rd_copy3(q->fs_b, m->fs);
    rd_copy3(q->cop, m->cop);
    *wsum = q->wsum;
}
