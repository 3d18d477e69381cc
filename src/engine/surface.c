/* rockdem — contact from the touching surfaces (`contact model surface`; docs/CONTACT.md
 * section 8).
 *
 * For each live pair, the reference body r is a convex one (the fixed one when both are), the
 * integration body the other. A point p of the integration body's surface is inside r when it
 * lies behind every face plane of r, and its depth is its distance below the nearest one,
 * min over g of d_g(p) = dR_g - u_g . p: for convex r the exact depth, continuous across faces.
 * For a plane P of the integration body (its coplanar faces together) and a face g of r, the
 * patch is the part of P's faces where g is the nearest plane and p is behind it: each of P's
 * convex cells (its faces merged at setup, contact/cells.c) clipped first by d_h >= 0 for every
 * face h of r (inside r: once per plane and step),
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
 * (`restitution` < 1) has no patch form and is refused, as are cohesion, tension and the
 * interface perturbation of the vertex model's points (rd_surface_init).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * contact/, geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/surface.h"
#include "engine/law.h"
#include "base/vec.h"
#include "base/grow.h"

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
/* A bound on an affine function over a box taken as negative only below minus this fraction of
 * its terms' size: far beyond round-off, so a rejection never drops a piece the clip keeps. */
#define RD_SURF_ROUNDOFF  1e-12
/* keep_planes leaves a plane of r out only when it is behind the nearest one by more than this
 * fraction of the scene's size (the bodies' radii and distances): a thousand times the
 * round-off margin of box_bounds, so its per-plane tests would have left it out too. */
#define RD_SURF_KEEP      1e-9
/* The skin of a pair's kept near planes, in contact bands (near_planes): a seated rock's planes
 * are found once, a rocking one's every few steps. */
#define RD_SURF_SKIN      1.0

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
    if (rd_grow((void **)&S->st, &S->cap_st, S->nst + 1, sizeof *S->st)) return NULL;
    surf_state *st = &S->st[S->nst];
    memset(st, 0, sizeof *st);
    st->key = k;
    st->stamp = -1;
    S->hash[q] = S->nst++;
    return st;
}

/* Each plane's faces merged into convex cells (rd_patch_cells), once: the convex path clips a
 * cell where it clipped each face (a flat base cut into 535 triangles is a few cells). 0, -1
 * when out of memory. */
static int plane_cells(const rd_poly *P, surf_body *B)
{
    const int nf = P->nf, nv2 = B->f2_0[nf];
    int *f0 = malloc(((size_t)nf + 1) * sizeof *f0),
        *vid = malloc((size_t)(nv2 ? nv2 : 1) * sizeof *vid);
    int *slot = malloc((size_t)(nv2 ? nv2 : 1) * sizeof *slot),
        *c0 = malloc(((size_t)nf + 1) * sizeof *c0);
    double(*xy)[2] = malloc((size_t)(nv2 ? nv2 : 1) * sizeof *xy);
    B->plane_c0 = malloc(((size_t)B->nplane + 1) * sizeof *B->plane_c0);
    B->c2_0 = malloc(((size_t)nf + 1) * sizeof *B->c2_0);
    B->c2 = malloc((size_t)(nv2 ? nv2 : 1) * sizeof *B->c2);
    int bad = !f0 || !vid || !slot || !c0 || !xy || !B->plane_c0 || !B->c2_0 || !B->c2;
    int nc = 0, w = 0;
    for (int k = 0; k < B->nplane && !bad; k++) {
        int nface = 0, m = 0;
        for (int e = B->plane_f0[k]; e < B->plane_f0[k + 1]; e++) {
            const int f = B->plane_face[e];
            f0[nface++] = m;
            for (int j = 0; j < P->flen[f]; j++, m++) {
                vid[m] = P->fidx[P->fstart[f] + j];
                xy[m][0] = B->f2[B->f2_0[f] + j][0];
                xy[m][1] = B->f2[B->f2_0[f] + j][1];
            }
        }
        f0[nface] = m;
        const int n =
            rd_patch_cells(nface, f0, vid, (const double(*)[2])xy, RD_PATCH_CELL_MAX, c0, slot);
        if (n < 0) bad = 1;
        B->plane_c0[k] = nc;
        for (int c = 0; c < n; c++, nc++) {
            B->c2_0[nc] = w;
            for (int q = c0[c]; q < c0[c + 1]; q++, w++) {
                B->c2[w][0] = xy[slot[q]][0];
                B->c2[w][1] = xy[slot[q]][1];
            }
        }
    }
    if (!bad) {
        B->plane_c0[B->nplane] = nc;
        B->c2_0[nc] = w;
    }
    free(f0);
    free(vid);
    free(slot);
    free(c0);
    free(xy);
    return bad ? -1 : 0;
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
    if (!plane_of || !B->frame || !B->plane_f0 || !B->plane_face || !B->f2_0 || !B->f2) {
        free(plane_of);
        rd_error_set(err, "out of memory");
        return -1;
    }
    const double tol = RD_FACE_TOL * (1.0 + P->radius);
    int *first = malloc((size_t)(nf ? nf : 1) * sizeof *first);
    B->nplane = first ? rd_plane_group(nf, (const double(*)[3])P->fn, P->fd, RD_SURF_COPLANAR, tol,
                                       plane_of, first)
                      : -1;
    if (B->nplane < 0) {
        free(first);
        free(plane_of);
        rd_error_set(err, "out of memory");
        return -1;
    }
    for (int k = 0; k < B->nplane; k++) { /* its frame from the first face's vertex and edge */
        const int f = first[k];
        const double *v0 = P->v[P->fidx[P->fstart[f]]], *v1 = P->v[P->fidx[P->fstart[f] + 1]];
        double *o = B->frame[k][0], *e1 = B->frame[k][1], *e2 = B->frame[k][2], *n = B->frame[k][3];
        rd_copy3(P->fn[f], n);
        rd_copy3(v0, o);
        double e[3] = { v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2] };
        rd_axpy(-rd_dot(e, n), n, e);
        double le = rd_norm(e);
        for (int c = 0; c < 3; c++) e1[c] = e[c] / le;
        rd_cross(n, e1, e2);
    }
    free(first);
    for (int f = 0; f < nf; f++) B->plane_f0[plane_of[f] + 1]++;
    for (int k = 0; k < B->nplane; k++) B->plane_f0[k + 1] += B->plane_f0[k];
    int *fill = calloc((size_t)B->nplane + 1, sizeof *fill);
    if (!fill) {
        free(plane_of);
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
    B->plane_of = plane_of;
    B->rect = malloc((size_t)(B->nplane > 0 ? B->nplane : 1) * sizeof *B->rect);
    if (!B->rect) {
        rd_error_set(err, "out of memory");
        return -1;
    }
    for (int k = 0; k < B->nplane; k++) { /* the corners o + x e1 + y e2 of the box, body frame */
        const double *bx = B->box[k], (*fr)[3] = B->frame[k];
        double *b = B->rect[k];
        for (int c = 0; c < 3; c++) {
            b[c] = DBL_MAX;
            b[c + 3] = -DBL_MAX;
        }
        for (int q = 0; q < 4; q++) {
            const double x = bx[q & 1 ? 2 : 0], y = bx[q & 2 ? 3 : 1];
            for (int c = 0; c < 3; c++) {
                const double v = fr[0][c] + x * fr[1][c] + y * fr[2][c];
                b[c] = rd_min(b[c], v);
                b[c + 3] = rd_max(b[c + 3], v);
            }
        }
    }
    if (plane_cells(P, B)) {
        rd_error_set(err, "out of memory");
        return -1;
    }
    B->seen = calloc((size_t)(B->nplane ? B->nplane : 1), sizeof *B->seen);
    double(*lo)[3] = malloc((size_t)(nf ? nf : 1) * sizeof *lo);
    double(*hi)[3] = malloc((size_t)(nf ? nf : 1) * sizeof *hi);
    int bad = !B->seen || !lo || !hi;
    for (int f = 0; f < nf && !bad; f++) { /* each face's box, body frame */
        for (int c = 0; c < 3; c++) {
            lo[f][c] = DBL_MAX;
            hi[f][c] = -DBL_MAX;
        }
        for (int q = P->fstart[f]; q < P->fstart[f] + P->flen[f]; q++)
            for (int c = 0; c < 3; c++) {
                lo[f][c] = rd_min(lo[f][c], P->v[P->fidx[q]][c]);
                hi[f][c] = rd_max(hi[f][c], P->v[P->fidx[q]][c]);
            }
    }
    if (!bad) bad = rd_bvh_build(&B->tree, nf, (const double(*)[3])lo, (const double(*)[3])hi);
    free(lo);
    free(hi);
    B->plane_key = bad ? NULL : malloc((size_t)(B->nplane > 0 ? B->nplane : 1) * sizeof(int));
    bad = bad || !B->plane_key;
    for (int k = 0; !bad && k < B->nplane; k++) B->plane_key[k] = nf;
    for (int q = 0; !bad && q < nf; q++) { /* its first face in the tree's item order */
        int *key = &B->plane_key[B->plane_of[B->tree.item[q]]];
        if (q < *key) *key = q;
    }
    if (bad) {
        rd_error_set(err, "out of memory");
        return -1;
    }
    return 0;
}

/* A scenario place for messages: "file:line", or "file (--set KEY)" for line 0. */
static void scene_where(const rd_scenario *sc, int line, const char *key, char *buf, size_t n)
{
    if (line > 0)
        snprintf(buf, n, "%s:%d", sc->file, line);
    else
        snprintf(buf, n, "%s (--set %s)", sc->file, key);
}

/* What the surface model does not model, refused with one line naming where the scene asks for
 * it and where it chose the model: the permanent set (restitution < 1), cohesion and tension of
 * the scene's joints and of the range overrides (whose joints form later, with their pairs), and
 * the interface perturbation of the vertex model's points. */
static int refuse_unmodelled(const rd_sim *s, rd_error *err)
{
    const rd_scenario *sc = &s->sc;
    char where[RD_PATH_MAX + 48], at[RD_PATH_MAX + 48];
    scene_where(sc, sc->contact.model_line, "contact.model=surface", where, sizeof where);
    for (int j = 0; j < s->njoint; j++) {
        const rd_joint *jt = &s->joint[j];
        if (jt->restitution < 1)
            return rd_error_set(err,
                                "%s: contact model surface: restitution %g is not modelled (its "
                                "impact loss is the joint's dashpot, 'model damping viscous'); "
                                "give 'contact property restitution 1'",
                                where, jt->restitution);
        if (jt->cohesion > 0 || jt->tension > 0)
            return rd_error_set(err,
                                "%s: contact model surface: cohesion and tension are not "
                                "modelled; give them as 0",
                                where);
    }
    const rd_perturb_def *pd = &sc->contact.perturb;
    if (pd->seed != 0 && (pd->remove > 0 || pd->raise > 0 || pd->scatter > 0)) {
        scene_where(sc, pd->line, "contact.interface-*", at, sizeof at);
        return rd_error_set(err,
                            "%s: contact model surface (%s): contact interface-perturbation is not "
                            "modelled (it perturbs the vertex model's subcontact points); leave it "
                            "out or give 'contact model vertex'",
                            at, where);
    }
    for (int k = 0; k < sc->njoints; k++) {
        const rd_joint_def *jd = &sc->joint[k];
        if ((jd->set & RD_JOINT_RESTITUTION) && jd->restitution < 1)
            return rd_error_set(err,
                                "%s:%d: contact model surface (%s): restitution %g is not "
                                "modelled (its impact loss is the joint's dashpot, 'damping'); "
                                "give 'restitution 1'",
                                sc->file, jd->line, where, jd->restitution);
        if (((jd->set & RD_JOINT_COHESION) && jd->cohesion > 0) ||
            ((jd->set & RD_JOINT_TENSION) && jd->tension > 0))
            return rd_error_set(err,
                                "%s:%d: contact model surface (%s): cohesion and tension are not "
                                "modelled; give them as 0",
                                sc->file, jd->line, where);
    }
    return 0;
}

int rd_surface_init(rd_sim *s, rd_error *err)
{
    s->surf = NULL;
    if (s->sc.contact.model != RD_CONTACT_SURFACE) return 0;
    if (refuse_unmodelled(s, err)) return -1;
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
    int most = 0, most_planes = 1;
    for (int i = 0; i < s->nb; i++) {
        if (body_planes(&s->poly[i], &S->body[i], err, s->sc.bodies[i].name)) return -1;
        if (s->poly[i].nf > most) most = s->poly[i].nf;
        if (S->body[i].nplane > most_planes) most_planes = S->body[i].nplane;
    }
    S->cap_q = most_planes;
    S->qpl = malloc((size_t)most_planes * sizeof *S->qpl);
    S->qstamp = calloc((size_t)most_planes, sizeof *S->qstamp);
    if (!S->qpl || !S->qstamp) {
        rd_error_set(err, "out of memory");
        return -1;
    }
    if (rd_grow((void **)&S->pl, &S->cap_pl, most, sizeof *S->pl)) {
        rd_error_set(err, "out of memory");
        return -1;
    }
    S->uw = malloc((size_t)S->cap_pl * sizeof *S->uw);
    S->dep = malloc((size_t)S->cap_pl * sizeof *S->dep);
    S->hcut = malloc((size_t)S->cap_pl * sizeof *S->hcut);
    S->keep = malloc((size_t)S->cap_pl * sizeof *S->keep);
    S->pkeep = malloc((size_t)S->cap_pl * sizeof *S->pkeep);
    S->klo = malloc((size_t)S->cap_pl * sizeof *S->klo);
    if (!S->uw || !S->dep || !S->hcut || !S->keep || !S->pkeep || !S->klo) {
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
        free(B->rect);
        free(B->plane_of);
        free(B->plane_c0);
        free(B->c2_0);
        free(B->c2);
        free(B->seen);
        free(B->plane_key);
        rd_bvh_free(&B->tree);
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
    free(S->hcut);
    free(S->keep);
    free(S->pkeep);
    free(S->klo);
    free(S->qpl);
    free(S->qstamp);
    for (int k = 0; k < S->cap_near; k++) free(S->near[k].plane);
    free(S->near);
    free(S->tsc.slot);
    free(S->tsc.count);
    free(S->tsc.ends);
    free(S->cand.ab);
    free(S->pkey);
    free(S->side);
    free(S->hpl);
    free(S->cnt);
    free(S->ord);
    free(S->fkey);
    free(S->fstamp);
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
    int dp0;                          /* the pair's first dashpot (S->dp) */
} surf_sums;

/* The twisting lever of a patch (the integral of d |r - c| about its centroid c), found only
 * when the Coulomb test needs it: from the pieces pc[0 .. n) (the convex path) or pc[ix[0 ..
 * n)] (the mesh path, one patch's pieces among the pair's). */
typedef struct surf_twist {
    const rd_poly2 *pc; /* the compressed pieces; NULL: tors is found */
    const int *ix;      /* NULL, or the patch's pieces in pc */
    int n;
    const double *c, *dep; /* the centroid, the depth's coefficients (plane coordinates) */
    rd_patch_scratch *sc;
    double tors; /* m^4 */
} surf_twist;

/* The lever itself (once). */
static double twist_exact(surf_twist *tw)
{
    if (tw->pc && tw->ix) {
        const double *d = tw->dep;
        tw->tors = 0;
        for (int q = 0; q < tw->n; q++)
            tw->tors += rd_patch_torsion(&tw->pc[tw->ix[q]], tw->c, d[0], d[1], d[2]);
        tw->pc = NULL;
    } else if (tw->pc) {
        const double *d = tw->dep;
        tw->tors = tw->n == 1
                       ? rd_patch_torsion(tw->pc, tw->c, d[0], d[1], d[2])
                       : rd_patch_torsion_set(tw->pc, tw->n, tw->c, d[0], d[1], d[2], tw->sc);
        tw->pc = NULL;
    }
    return tw->tors;
}

/* A weaker lower bound from the patch's integral of depth f (m^3) and its deepest vertex, in one
 * pass over the vertices (rd_patch_torsion_disc): tried first. */
static double twist_disc(const surf_twist *tw, double f)
{
    const double *d = tw->dep;
    if (!tw->pc) return tw->tors;
    if (!tw->ix) return rd_patch_torsion_disc(tw->pc, tw->n, f, d[0], d[1], d[2]);
    double dmax = 0;
    for (int q = 0; q < tw->n; q++) {
        const rd_poly2 *p = &tw->pc[tw->ix[q]];
        for (int v = 0; v < p->n; v++)
            dmax = rd_max(dmax, d[0] + d[1] * p->p[v][0] + d[2] * p->p[v][1]);
    }
    return rd_patch_torsion_disc_of(f, dmax);
}

/* A lower bound of it: the Coulomb test with this lever finds most sticking patches inside the
 * limit surface at a third of the cost (rd_patch_spring_s2). */
static double twist_lower(const surf_twist *tw, double f)
{
    const double *d = tw->dep;
    if (tw->pc && tw->ix)
        return twist_disc(tw, f); /* (no third-moment bound of scattered pieces) */
    return tw->pc ? rd_patch_torsion_bound(tw->pc, tw->n, tw->c, d[0], d[1], d[2]) : tw->tors;
}

/* The direction of a patch's dashpot (ground frame): the fixed body's surface normal, pointing
 * into the integration body i. r's outward normal uw when r is fixed or both are free, minus
 * i's plane normal when i is fixed (terrain against a convex rock). A dashpot damps the bodies'
 * approach; along the free rock's own face normal it also saw a steady slide: a rock pitched by
 * theta (the friction moment) sliding at v over terrain material changes each point's depth at
 * v theta (and at v where terrain enters through the rock's leading face, the nearest-plane
 * sliver), a dashpot force of c_a A v theta that the Coulomb limit does not see: 0.25 J lost
 * and a slide 2.2 mm (0.22 %) short on a triangulated slope at zeta 0.1. Along the terrain's
 * normal a slide has no rate and an impact is damped along the surface it strikes, as the
 * vertex model's point-on-face contact is. */
static void dashpot_normal(const rd_sim *s, int i, const double fr[4][3], const double uw[3],
                           double un[3])
{
    if (!s->fixed[i]) {
        rd_copy3(uw, un);
        return;
    }
    rd_mat_vec(s->R[i], fr[3], un);
    for (int k = 0; k < 3; k++) un[k] = -un[k];
}

/* One patch (plane P of body i against face g of r) with the compressed region's moments m,
 * its load ld (depth coefficients dep, plane frame fr) and twisting lever tw: the law, its
 * forces into the sums. */
static int patch_apply(rd_sim *s, rd_pair *pr, int pair, int i, int r, int P, int g,
                       const rd_moments *m, const rd_patch_load *ld, surf_twist *tw,
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
    if (c_a > 0) { /* into the pair's dashpot along un (dashpot.h) */
        double un[3];
        dashpot_normal(s, i, fr, uw, un);
        rd_dashpot *e = rd_dashpot_of(s, &S->dp, sum->dp0, i, r, c_a, un);
        if (!e) return -1;
        const double m2[6] = { m->a, m->sx, m->sy, m->sxx, m->sxy, m->syy };
        rd_dashpot_add_region(e, m2, O, E1, E2);
    }
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
    double fp[3] = { sp->fs[0], sp->fs[1], sp->fs[2] }; /* last step's springs, turned */
    const double mp = sp->mt;
    rd_law_shear_turn(fp, uw);
    s->e_fric += rd_patch_spring_resize(sp, j->ks, ld->area, ld->polar);
    rd_law_shear_turn(sp->fs, uw);
    const double f0[3] = { sp->fs[0], sp->fs[1], sp->fs[2] }, m0 = sp->mt;
    const double kA = j->ks * ld->area, kJ = j->ks * ld->polar;
    rd_law_shear_load(sp->fs, uw, vr, vn, kA, s->dt);
    sp->mt -= kJ * spin * s->dt;
    s->e_fric += rd_patch_resize_work(sp, fp, mp, f0, m0, kA, kJ);
    double flim = j->tan_phi * rd_max(fn, 0.0),
           mlim = ld->f > 0 ? flim * twist_disc(tw, ld->f) / ld->f : 0.0;
    /* the bounds, weakest first, prove most sticking springs inside; else the lever itself */
    if (!(rd_patch_spring_s2(sp, flim, mlim) <= 1) && ld->f > 0)
        mlim = flim * twist_lower(tw, ld->f) / ld->f;
    if (!(rd_patch_spring_s2(sp, flim, mlim) <= 1))
        mlim = ld->f > 0 ? flim * twist_exact(tw) / ld->f : 0.0;
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
        if (rd_grow((void **)&S->on_next, &S->cap_on_next, S->non_next + 1, sizeof *S->on_next))
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

/* The bounds of the affine d = c[0] + c[1] x + c[2] y over the box bx (x min, y min, x max, y
 * max; at its corners), and the round-off margin tol within which a vertex inside the box may
 * exceed them when evaluated on its own. */
static void box_bounds(const double c[3], const double bx[4], double *lo, double *hi, double *tol)
{
    const double x0 = c[1] * bx[0], x1 = c[1] * bx[2], y0 = c[2] * bx[1], y1 = c[2] * bx[3];
    *lo = c[0] + rd_min(x0, x1) + rd_min(y0, y1);
    *hi = c[0] + rd_max(x0, x1) + rd_max(y0, y1);
    *tol =
        RD_SURF_ROUNDOFF * (fabs(c[0]) + rd_max(fabs(x0), fabs(x1)) + rd_max(fabs(y0), fabs(y1)));
}

/* The parts of plane P's cells (body i; its faces merged, plane_cells) inside r, behind every
 * plane of r (d_h >= 0), into S->ins, and their bounding box into S->inbox: found once per plane
 * and step, so a plane that does not reach r costs one pass, and each face g then clips only
 * what is inside. A cell whose every vertex lies deeper than cap below the nearest plane is
 * left out (a mesh's far side). Returns the count, -1 when out of memory. */
static int plane_inside(rd_sim *s, const surf_body *B, int P, double cap)
{
    struct rd_surface *S = s->surf;
    const double *bx = B->box[P];
    const int nk = S->npkeep, *keep = S->pkeep;
    int ncut = 0, *cut_by = S->hcut; /* the planes of r that may cut a cell */
    double least_hi = DBL_MAX, least_tol = 0;
    for (int kh = 0; kh < nk; kh++) { /* the whole plane in front of one plane of r: outside */
        const int h = keep[kh];
        double lo, hi, tol;
        box_bounds(S->dep[h], bx, &lo, &hi, &tol);
        if (hi <= 0) {
            S->front = h;
            return 0;
        }
        if (!(lo > tol)) cut_by[ncut++] = h;
        if (hi < least_hi) {
            least_hi = hi;
            least_tol = tol;
        }
    }
    /* a plane of r with every point of the box within cap: no cell is a far side */
    const int far_test = !(least_hi < cap - least_tol);
    int n = 0;
    double *ib = S->inbox;
    ib[0] = ib[1] = DBL_MAX;
    ib[2] = ib[3] = -DBL_MAX;
    for (int c = B->plane_c0[P]; c < B->plane_c0[P + 1]; c++) {
        const int nv = B->c2_0[c + 1] - B->c2_0[c];
        const double(*v2)[2] = B->c2 + B->c2_0[c];
        if (rd_grow((void **)&S->ins, &S->cap_ins, n + 2, sizeof *S->ins)) return -1;
        rd_poly2 *a = &S->ins[n], *b = &S->ins[n + 1];
        a->n = nv;
        memcpy(a->p, v2, (size_t)nv * sizeof *v2);
        int alive = 1;
        double deep =
            -DBL_MAX; /* the least, over the cell's vertices, of their nearest-plane depth */
        for (int k = 0; k < nv && far_test; k++) {
            double dmin = DBL_MAX;
            for (int kh = 0; kh < nk; kh++) {
                const double *dh = S->dep[keep[kh]];
                dmin = rd_min(dmin, dh[0] + dh[1] * v2[k][0] + dh[2] * v2[k][1]);
            }
            deep = k ? rd_min(deep, dmin) : dmin;
        }
        if (deep > cap) continue;
        for (int e = 0; e < ncut && alive; e++) {
            const double *dh = S->dep[cut_by[e]];
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
        for (int k = 0; k < a->n; k++)
            for (int q = 0; q < 2; q++) {
                ib[q] = rd_min(ib[q], a->p[k][q]);
                ib[q + 2] = rd_max(ib[q + 2], a->p[k][q]);
            }
        n++;
    }
    return n;
}

/* Can face g of r be the nearest plane anywhere in the inside pieces' box S->inbox? Not when
 * for some other face h the affine d_h - d_g is negative all over the box (every piece would
 * clip to nothing). Otherwise the faces h whose d_h - d_g may be negative somewhere in the box
 * (those that may cut a piece) into S->hcut; returns their count + 1, 0 when g cannot be. */
static int nearest_possible(struct rd_surface *S, int g)
{
    const double *dg = S->dep[g];
    int n = 0;
    for (int kh = 0; kh < S->npkeep; kh++) {
        const int h = S->pkeep[kh];
        if (h == g) continue;
        const double *dh = S->dep[h];
        const double c[3] = { dh[0] - dg[0], dh[1] - dg[1], dh[2] - dg[2] };
        double lo, hi, tol;
        box_bounds(c, S->inbox, &lo, &hi, &tol);
        if (hi < -tol) return 0;
        if (!(lo > tol)) S->hcut[n++] = h;
    }
    return n + 1;
}

/* The parts of the inside pieces S->ins[0 .. nin) where face g of r is the nearest plane (d_h -
 * d_g >= 0 for the nh faces h of S->hcut, the others hold it over the pieces' box): into
 * S->comp (*pc), their moments summed into *m. When no face cuts (nh = 0) and every inside
 * piece has an area, they are the inside pieces themselves (*pc = S->ins, nothing copied).
 * Returns the piece count, -1 when out of memory. */
static int nearest_pieces(struct rd_surface *S, int nin, int g, int nh, rd_moments *m,
                          const rd_poly2 **pc)
{
    const double *dg = S->dep[g];
    int n = 0;
    *m = (rd_moments){ 0, 0, 0, 0, 0, 0 };
    if (nh == 0) {
        for (; n < nin; n++) {
            rd_moments pm;
            rd_patch_moments(&S->ins[n], &pm);
            if (!(pm.a > 0)) break;
            rd_moments_add(m, &pm);
        }
        if (n == nin) {
            *pc = S->ins;
            return n;
        }
        n = 0; /* a piece with no area: the pieces that have one, copied */
        *m = (rd_moments){ 0, 0, 0, 0, 0, 0 };
    }
    for (int e = 0; e < nin; e++) {
        if (rd_grow((void **)&S->comp, &S->cap_comp, n + 2, sizeof *S->comp)) return -1;
        rd_poly2 *a = &S->comp[n], *b = &S->comp[n + 1];
        poly_copy(a, &S->ins[e]);
        int alive = 1;
        for (int q = 0; q < nh && alive; q++) {
            const double *dh = S->dep[S->hcut[q]];
            double c0 = dh[0] - dg[0], cx = dh[1] - dg[1], cy = dh[2] - dg[2];
            int cut = 0, kept = 0; /* a vertex outside, a vertex inside */
            for (int k = 0; k < a->n; k++) {
                if (c0 + cx * a->p[k][0] + cy * a->p[k][1] < 0)
                    cut = 1;
                else
                    kept = 1;
            }
            if (!cut) continue;
            alive = kept && rd_patch_clip_half(a, cx, cy, c0, b) > 0;
            rd_poly2 *t = a;
            a = b;
            b = t;
        }
        if (!alive) continue;
        if (a != &S->comp[n]) poly_copy(&S->comp[n], a);
        rd_moments pm;
        rd_patch_moments(&S->comp[n], &pm);
        if (!(pm.a > 0)) continue;
        rd_moments_add(m, &pm);
        n++;
    }
    *pc = S->comp; /* (after its growth) */
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

/* The pose of body r in body i's frame: x_i-frame = rot x_r-frame + tr (rot row-major). */
static void rel_pose(const rd_sim *s, int i, int r, double rot[9], double tr[3])
{
    const double *Ri = s->R[i], *Rr = s->R[r];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            rot[3 * a + b] = Ri[a] * Rr[b] + Ri[3 + a] * Rr[3 + b] + Ri[6 + a] * Rr[6 + b];
    const double d[3] = { s->x[r][0] - s->x[i][0], s->x[r][1] - s->x[i][1],
                          s->x[r][2] - s->x[i][2] };
    rd_mat_tvec(Ri, d, tr);
}

/* The sums of a pair's patches onto its bodies, and the pair's and monitor's records: i takes
 * them; r (when free) -F at each point: -(sum tq) - (x_i - x_r) x sum F. */
static int pair_finish(rd_sim *s, int pair, rd_pair *pr, int i, int r, const surf_sums *sum)
{
    rd_axpy(1.0, sum->f, s->f[i]);
    rd_axpy(1.0, sum->tq, s->tq[i]);
    if (!s->fixed[r]) {
        double d[3] = { s->x[i][0] - s->x[r][0], s->x[i][1] - s->x[r][1], s->x[i][2] - s->x[r][2] },
               t[3];
        rd_cross(d, sum->f, t);
        rd_axpy(-1.0, sum->f, s->f[r]);
        for (int k = 0; k < 3; k++) s->tq[r][k] -= sum->tq[k] + t[k];
    }
    pr->k_active = sum->k_active;
    double nn = rd_norm(sum->nsum);
    if (nn > 0)
        for (int k = 0; k < 3; k++) pr->n[k] = sum->nsum[k] / nn;
    rd_watch *w = rd_monitor_contact_watch(s, i, r);
    if (w) {
        w->area += sum->area;
        w->nactive += sum->nact;
        w->nslip += sum->nslip;
        if (sum->area > 0 && !s->settling) w->touched = 1;
    }
    if (!s->settling) s->active_point_steps += sum->nact;
    return measure_store(s, pair, sum);
}

/* How far, at most, any node box of i's tree (carried into r's frame as the box around its
 * turned box: rd_bvh_query_carried) has moved between the poses (rot0, tr0) and (rot, tr): each
 * box's centre c and half-widths h move by at most |d tr| + |d rot| (|c| + |h|) per axis (|d
 * rot| the Frobenius norm, above the spectral one), and |c| + |h| <= 2 rc, rc the farthest
 * corner of the root box from i's centre. m. */
static double carried_shift(const rd_bvh *t, const double rot0[9], const double tr0[3],
                            const double rot[9], const double tr[3])
{
    double dr = 0, dt = 0, rc = 0;
    for (int k = 0; k < 9; k++) dr += (rot[k] - rot0[k]) * (rot[k] - rot0[k]);
    for (int k = 0; k < 3; k++) {
        dt += (tr[k] - tr0[k]) * (tr[k] - tr0[k]);
        const double c = rd_max(fabs(t->lo[0][k]), fabs(t->hi[0][k]));
        rc += c * c;
    }
    return sqrt(dt) + 2 * sqrt(dr) * sqrt(rc);
}

/* The planes of body i (its tree) that may reach into body r (pair number pair): those with a
 * face whose box, carried into r's frame, meets r's box there grown by margin (m); into S->ord,
 * in the order of their first face in the tree (surf_body.plane_key). The tree is queried with
 * margin + RD_SURF_SKIN margin and the list kept with the pose (Verlet's skin): while no box has
 * moved by more than the skin since (carried_shift), every plane the query with margin would
 * find is in the kept list, and the others find no patch (no point of theirs lies within
 * margin of r's box), so the patches, in their order, are the same. Returns the count, -1 when
 * out of memory. */
static int near_planes(rd_sim *s, int pair, int i, int r, double margin)
{
    struct rd_surface *S = s->surf;
    surf_body *B = &S->body[i];
    const rd_bvh *tr_r = &S->body[r].tree;
    if (tr_r->nnode == 0) return 0;
    double rot[9], tr[3];
    rel_pose(s, r, i, rot, tr);
    if (pair >= S->cap_near) {
        const int old = S->cap_near;
        if (rd_grow((void **)&S->near, &S->cap_near, pair + 1, sizeof *S->near)) return -1;
        memset(S->near + old, 0, (size_t)(S->cap_near - old) * sizeof *S->near);
    }
    surf_near *kn = &S->near[pair];
    const double skin = RD_SURF_SKIN * margin;
    if (kn->valid && carried_shift(&B->tree, kn->rot, kn->tr, rot, tr) <= skin) {
        if (rd_grow((void **)&S->ord, &S->cap_ord, kn->n, sizeof *S->ord)) return -1;
        if (kn->n > 0) memcpy(S->ord, kn->plane, (size_t)kn->n * sizeof *S->ord);
        memcpy(S->ubox, kn->box, sizeof S->ubox);
        return kn->n;
    }
    S->cand.n = 0;
    if (rd_bvh_query_carried(&B->tree, rot, tr, tr_r->lo[0], tr_r->hi[0], margin + skin, &S->cand))
        return -1;
    if (++S->seen_stamp == 0) { /* the stamp wrapped: start the marks again */
        for (int b = 0; b < s->nb; b++)
            memset(S->body[b].seen, 0, (size_t)S->body[b].nplane * sizeof(int));
        S->seen_stamp = 1;
    }
    int n = 0;
    if (rd_grow((void **)&S->ord, &S->cap_ord, S->cand.n, sizeof *S->ord)) return -1;
    for (int k = 0; k < S->cand.n; k++) {
        const int P = B->plane_of[S->cand.ab[k][0]];
        if (B->seen[P] == S->seen_stamp) continue;
        B->seen[P] = S->seen_stamp;
        int k1 = n++; /* insertion by key: the faces come in tree order, so planes seldom move */
        for (; k1 > 0 && B->plane_key[S->ord[k1 - 1]] > B->plane_key[P]; k1--)
            S->ord[k1] = S->ord[k1 - 1];
        S->ord[k1] = P;
    }
    if (rd_grow((void **)&kn->plane, &kn->cap, n, sizeof *kn->plane)) return -1;
    if (n > 0) memcpy(kn->plane, S->ord, (size_t)n * sizeof *kn->plane);
    memcpy(kn->rot, rot, sizeof kn->rot);
    memcpy(kn->tr, tr, sizeof kn->tr);
    double *bx = kn->box; /* the box around the planes' coordinate boxes (keep_planes) */
    for (int c = 0; c < 3; c++) {
        bx[c] = DBL_MAX;
        bx[c + 3] = -DBL_MAX;
    }
    for (int k = 0; k < n; k++)
        for (int c = 0; c < 3; c++) {
            bx[c] = rd_min(bx[c], B->rect[S->ord[k]][c]);
            bx[c + 3] = rd_max(bx[c + 3], B->rect[S->ord[k]][c + 3]);
        }
    memcpy(S->ubox, bx, sizeof S->ubox);
    kn->n = n;
    kn->valid = 1;
    return n;
}

/* The depth below plane h of r over plane frame fr, affine in its coordinates, into S->dep[h]. */
static void plane_depth(struct rd_surface *S, const double fr[4][3], int h)
{
    const double *pl = S->pl[h];
    S->dep[h][0] = pl[3] - rd_dot(pl, fr[0]);
    S->dep[h][1] = -rd_dot(pl, fr[1]);
    S->dep[h][2] = -rd_dot(pl, fr[2]);
}

/* Is plane P of body B wholly in front of plane h of r (over its box)? */
static int in_front(struct rd_surface *S, const surf_body *B, int P, int h)
{
    double lo, hi, tol;
    plane_depth(S, B->frame[P], h);
    box_bounds(S->dep[h], B->box[P], &lo, &hi, &tol);
    return hi <= 0;
}

/* The first face of face g's plane (body B): a plane of r gives one patch per plane of i, keyed
 * by that face. Coplanar faces of a convex r (a triangulated box, a terrain grid's plane) have
 * the same depth but for round-off, and the nearest-plane clip between them broke the tie at
 * random: each face that survived it bore the whole region (4 of a grid plane's 30 triangles
 * under a brick: 4 times KN, a quarter of its static depth). */
static int plane_lead(const surf_body *B, int g)
{
    return B->plane_face[B->plane_f0[B->plane_of[g]]];
}

/* Of the planes from[0 .. n) of r, those that may cut or be nearest anywhere in the box b (body
 * i's frame: x, y, z min, then max) into to, in their order; returns their count. Over b each
 * plane h has depth bounds lo_h .. hi_h; with H the least hi_h, a plane with lo_h above H and
 * above 0 by m is behind the plane that gives H, and behind r's surface, at every point of b:
 * it cuts no cell there, is never the nearest plane, and each region it would bound is bounded
 * by that plane already, so plane_inside, nearest_possible and nearest_pieces find the same
 * regions without it (the order of the clips can move a vertex at round-off). */
static int keep_over(struct rd_surface *S, const double b[6], const int *from, int n, double m,
                     int *to)
{
    double mid[3], half[3], least = DBL_MAX;
    for (int c = 0; c < 3; c++) {
        mid[c] = 0.5 * (b[c] + b[c + 3]);
        half[c] = 0.5 * (b[c + 3] - b[c]);
    }
    for (int k = 0; k < n; k++) { /* d_h(p) = pl[3] - u . p over b: centre -+ spread */
        const double *pl = S->pl[from[k]];
        const double dc = pl[3] - rd_dot(pl, mid);
        const double w = fabs(pl[0]) * half[0] + fabs(pl[1]) * half[1] + fabs(pl[2]) * half[2];
        S->klo[k] = dc - w;
        least = rd_min(least, dc + w);
    }
    int nk = 0;
    for (int k = 0; k < n; k++)
        if (!(S->klo[k] > least + m && S->klo[k] > m)) to[nk++] = from[k];
    return nk;
}

/* The planes of r that may reach the near planes of i (S->ord) into S->keep (keep_over, over
 * the box U of their coordinate boxes, S->ubox: a rock on a pedestal's top keeps the top), with
 * the margin RD_SURF_KEEP of the scene's size into S->keep_m; each near plane P then keeps
 * those that may reach its own box (surf_body.rect: a drum's side face, the two or three
 * planes of the drum below at its edge, not all 26). */
static void keep_planes(rd_sim *s, int i, int r)
{
    struct rd_surface *S = s->surf;
    const int nr = s->poly[r].nf;
    double size = s->poly[i].radius + s->poly[r].radius;
    for (int c = 0; c < 3; c++) size += fabs(S->ubox[c]) + fabs(S->ubox[c + 3]);
    for (int h = 0; h < nr; h++) {
        size = rd_max(size, fabs(S->pl[h][3]));
        S->pkeep[h] = h;
    }
    S->keep_m = RD_SURF_KEEP * size;
    S->nkeep = keep_over(S, S->ubox, S->pkeep, nr, S->keep_m, S->keep);
}

/* Every patch of live pair number pair whose body r is convex (section 8.1): the planes of i
 * near r (near_planes) against the planes of r that may reach them (keep_planes) by the
 * nearest-plane clip. */
static int pair_convex(rd_sim *s, int pair, int i, int r)
{
    struct rd_surface *S = s->surf;
    rd_pair *pr = &s->pair[pair];
    const rd_poly *Pr = &s->poly[r];
    const surf_body *B = &S->body[i];
    const rd_joint *j = &s->joint[pr->joint];
    const int nr = Pr->nf;
    const double band = RD_CONTACT_BAND * rd_min(Pr->radius, s->poly[i].radius);
    const int np = near_planes(s, pair, i, r, band);
    if (np <= 0) {
        pr->k_active = 0;
        return np;
    }
    const surf_body *Br = &S->body[r];
    for (int g = 0; g < nr; g++) { /* r's planes, ground frame and i's frame */
        double *uw = S->uw[g], *pl = S->pl[g];
        const int lead = plane_lead(Br, g);
        if (lead != g) { /* a coplanar face: its plane's, exactly (the clips see no tie) */
            rd_copy3(S->uw[lead], uw);
            memcpy(pl, S->pl[lead], sizeof S->pl[0]);
            continue;
        }
        rd_mat_vec(s->R[r], Pr->fn[g], uw);
        double dw = Pr->fd[g] + rd_dot(uw, s->x[r]);
        rd_mat_tvec(s->R[i], uw, pl);
        pl[3] = dw - rd_dot(uw, s->x[i]);
    }
    keep_planes(s, i, r);
    const double cap = RD_SURF_DEPTH_CAP * rd_min(Pr->radius, s->poly[i].radius);
    const double c_a = (j->damping > 0 && pr->k_active > 0)
                           ? 2 * j->damping * j->kn * sqrt(pr->m_eff / pr->k_active)
                           : 0.0;
    surf_sums sum = { .dp0 = S->dp.n }; /* all zero but the pair's first dashpot */
    for (int kp = 0; kp < np; kp++) {
        const int P = S->ord[kp];
        const double(*fr)[3] = B->frame[P];
        /* the plane of r that put the last plane wholly in front usually does it again: one
           depth and one box test reject most candidates (plane_inside's own first test) */
        const int f0 = S->front < nr ? S->front : 0;
        if (in_front(S, B, P, f0)) continue;
        S->npkeep = keep_over(S, B->rect[P], S->keep, S->nkeep, S->keep_m, S->pkeep);
        for (int kh = 0; kh < S->npkeep; kh++) /* (in_front found f0's) */
            if (S->pkeep[kh] != f0) plane_depth(S, fr, S->pkeep[kh]);
        const int nin = plane_inside(s, B, P, cap);
        if (nin < 0) return -1;
        for (int kg = 0; kg < S->npkeep && nin > 0; kg++) {
            const int g = S->pkeep[kg];
            if (plane_lead(Br, g) != g) continue; /* its plane's patch is its lead's */
            const int nh = nearest_possible(S, g) - 1;
            if (nh < 0) continue;
            rd_moments m;
            const rd_poly2 *pieces;
            int n = nearest_pieces(S, nin, g, nh, &m, &pieces);
            if (n < 0) return -1;
            if (n == 0) continue;
            rd_patch_load ld;
            const double *dg = S->dep[g];
            rd_patch_load_from(&m, dg[0], dg[1], dg[2], &ld);
            if (!(ld.area > 0)) continue;
            const double c[2] = { ld.cx, ld.cy };
            surf_twist tw = { pieces, NULL, n, c, dg, &S->tsc, 0.0 };
            if (patch_apply(s, pr, pair, i, r, P, g, &m, &ld, &tw, fr, dg, c_a, &sum)) return -1;
        }
    }
    return pair_finish(s, pair, pr, i, r, &sum);
}

/* ---- Mesh against mesh (neither body convex; section 8.5) ----
 * For a face S of i (plane P) and a face R of r (plane Q) facing each other (n_S . u_R <
 * -RD_SURF_FACING) the patch is the part of S whose projection along u_R falls in R, behind R's
 * plane by a depth 0 < d_R(p) < band (rd_patch_faces, then the two depth clips): the depth is
 * local, from R's plane. A point of S behind several facing faces of r within the band (near a
 * convex edge of r) takes the nearest one: S's piece for R is split where another candidate
 * face H is nearer, 0 < d_H < d_R, into its parts d_H <= 0 and d_H >= d_R (two convex pieces),
 * so no point is counted twice; for convex r this is the nearest-plane rule of section 8.1. */
/* The depth window of a mesh pair, as a fraction of the smaller bounding radius: deeper, a face
 * is a far side, or (when it passes through the face or bore on it) has sunk, and the run ends
 * penetrated. Not the contact band (1e-3): a rough scan's spike bears on a face through a
 * cone of slope about 0.3, whose Winkler load KN pi d^3 / (3 0.09) holds a 350 kg rock at KN
 * 1e10 Pa/m only at d = 3 mm (the scanned rock on a scanned pedestal of docs/CONTACT.md
 * section 8.5 stopped at 0.47 mm with the band). */
#define RD_SURF_MESH_DEPTH 0.02
#define RD_SURF_FACING     1e-3 /* faces facing each other: n_S . u_R below minus this (89.94 deg) */
/* A piece of less than this fraction of its face's area, left by the subtraction along an edge
 * two faces of r share, is round-off (a sliver of 1e-16 m width), not a piece */
#define RD_SURF_SLIVER     1e-12
#define RD_SURF_PIECES     32 /* most convex pieces of one face pair after the nearest-face rule */

/* A candidate face pair of a mesh pair, after the facing and depth tests. */
typedef struct mesh_cand {
    int fi, Q, fr;
    int facing; /* 1: the faces face each other (a patch); 0: R only rules points out */
    int behind; /* 1: part of S may lie behind R's plane (a patch's source); 0: S is wholly in
                   front, beyond round-off, and R only rules its prism out for the others */
} mesh_cand;

/* The region a candidate face H of r takes out of another candidate's pieces on face S of i
 * (face_pieces), S's plane coordinates: where d_R - d_H > 0 (that side depends on R) and
 * inside the half-planes hpl[h0 .. h0 + nh) (a x + b y + c >= 0): H's edges projected along
 * its normal (facing H), or d_H > 0 (S behind H). Built once per face S and step. */
typedef struct mesh_side {
    double e[3]; /* d_H = e0 + e1 x + e2 y, m */
    int h0, nh;  /* its half-planes; nh 0: H is skipped (its projection cannot be made) */
} mesh_side;

/* The candidates sorted by (fi, Q, fr), each key unique: three stable counting sorts (least
 * significant first), linear in the candidates and the faces (a comparison sort of the 4,400
 * candidates of a rock on a scanned rock took a quarter of its step). mc's room is 2 nc;
 * the result is in mc[0 .. nc). 0, -1 when out of memory. */
static int sort_cand(struct rd_surface *S, mesh_cand *mc, int nc, int nfi, int nqr, int nfr)
{
    const int most = (nfi > nqr ? (nfi > nfr ? nfi : nfr) : (nqr > nfr ? nqr : nfr)) + 1;
    if (rd_grow((void **)&S->cnt, &S->cap_cnt, most, sizeof *S->cnt)) return -1;
    mesh_cand *a = mc, *b = mc + nc;
    for (int pass = 0; pass < 3; pass++) {
        const int nk = pass == 0 ? nfr : pass == 1 ? nqr : nfi;
        int *cnt = S->cnt;
        memset(cnt, 0, ((size_t)nk + 1) * sizeof *cnt);
        for (int k = 0; k < nc; k++) {
            const int key = pass == 0 ? a[k].fr : pass == 1 ? a[k].Q : a[k].fi;
            cnt[key + 1]++;
        }
        for (int q = 0; q < nk; q++) cnt[q + 1] += cnt[q];
        for (int k = 0; k < nc; k++) {
            const int key = pass == 0 ? a[k].fr : pass == 1 ? a[k].Q : a[k].fi;
            b[cnt[key]++] = a[k];
        }
        mesh_cand *t = a;
        a = b;
        b = t;
    }
    if (a != mc) memcpy(mc, a, (size_t)nc * sizeof *mc);
    return 0;
}

/* Plane Q of r in i's frame: outward normal u and offset dR (u . x = dR), found once per pair and
 * step (the candidates share their planes: S->qpl, stamped with pair_mesh's epoch). */
static void plane_in(struct rd_surface *S, const surf_body *Br, int Q, const double rot[9],
                     const double tr[3], double u[3], double *dR)
{
    double *q = S->qpl[Q];
    if (S->qstamp[Q] != S->qepoch) { /* once per pair and step (pair_mesh's epoch) */
        const double(*fq)[3] = Br->frame[Q];
        rd_mat_vec(rot, fq[3], q);
        q[3] = rd_dot(fq[3], fq[0]) + rd_dot(q, tr);
        S->qstamp[Q] = S->qepoch;
    }
    rd_copy3(q, u);
    *dR = q[3];
}

/* One piece (a convex polygon of plane P's coordinates) into the pieces store, group (P, Q). */
static int keep_piece(struct rd_surface *S, int *n, const rd_poly2 *p, int P, int Q)
{
    if (rd_grow((void **)&S->comp, &S->cap_comp, *n + 2, sizeof *S->comp) ||
        rd_grow((void **)&S->pkey, &S->cap_pkey, 2 * (*n + 1), sizeof *S->pkey))
        return -1;
    poly_copy(&S->comp[*n], p);
    S->pkey[2 * *n] = P;
    S->pkey[2 * *n + 1] = Q;
    (*n)++;
    return 0;
}

/* Body i passed into body r (a face through a face deeper than the depth window): the run ends. */
static int mesh_penetrated(rd_sim *s, int i, int r, int fi, int fr, double depth, double band)
{
    snprintf(
        s->errmsg, sizeof s->errmsg,
        "body '%s' passed into body '%s' at t = %.6g s (step %ld): its face %d is %.3g m "
        "deep behind face %d, more than a mesh pair's depth window (%.3g m): the contact stiffness "
        "(stiffness-normal %g Pa/m) is far too soft for the load",
        s->sc.bodies[i].name, s->sc.bodies[r].name, s->t, s->nsteps_all, fi, depth, fr, band,
        s->sc.contact.kn);
    s->status = RD_STATUS_PENETRATED;
    return 1;
}

/* A face pair split into more pieces than the scratch holds: the run stops (never a piece
 * dropped silently). */
static int too_many_pieces(rd_sim *s, int i, int r, int fi)
{
    snprintf(s->errmsg, sizeof s->errmsg,
             "contact model surface: face %d of body '%s' splits into more than %d pieces against "
             "body '%s' at t = %.6g s (the nearest-face rule over many faces of it): not modelled",
             fi, s->sc.bodies[i].name, RD_SURF_PIECES, s->sc.bodies[r].name, s->t);
    s->status = RD_STATUS_ERROR;
    return 1;
}

/* The area of a counter-clockwise polygon, m^2 (shoelace). */
static double poly_area(const rd_poly2 *p)
{
    double a = 0;
    for (int k = 0; k < p->n; k++) {
        const double *u = p->p[k], *v = p->p[(k + 1) % p->n];
        a += u[0] * v[1] - v[0] * u[1];
    }
    return 0.5 * a;
}

/* Face fh of r projected along u (i's frame) onto the plane of frame fr, as the half-planes of
 * its edges (a x + b y + c >= 0 inside) appended to hp from index *nh. 0 when it cannot be. */
static int project_face(const double fr[4][3], const rd_poly *Pr, int fh, const double rot[9],
                        const double tr[3], const double u[3], double (*hp)[3], int *nh)
{
    const int nr = Pr->flen[fh];
    const double nu = rd_dot(fr[3], u);
    if (!(nu < 0) || nr > RD_PATCH_FACE_MAX) return 0;
    double p2[RD_PATCH_FACE_MAX][2];
    for (int k = 0; k < nr; k++) { /* reversed: counter-clockwise about the plane's normal */
        double q[3];
        rd_mat_vec(rot, Pr->v[Pr->fidx[Pr->fstart[fh] + nr - 1 - k]], q);
        rd_axpy(1.0, tr, q);
        double dq[3] = { q[0] - fr[0][0], q[1] - fr[0][1], q[2] - fr[0][2] };
        rd_axpy(-rd_dot(fr[3], dq) / nu, u, dq);
        p2[k][0] = rd_dot(dq, fr[1]);
        p2[k][1] = rd_dot(dq, fr[2]);
    }
    int n = 0;
    for (int k = 0; k < nr; k++) {
        const double *p = p2[k], *q = p2[(k + 1) % nr];
        double ex = q[0] - p[0], ey = q[1] - p[1];
        hp[n][0] = -ey;
        hp[n][1] = ex;
        hp[n][2] = ey * p[0] - ex * p[1];
        n++;
    }
    *nh += n;
    return 1;
}

/* The face-pair table of mesh pairs: the slot of key k (its key 0 when empty; keys are never 0:
 * they carry pair + 1). */
static int face_slot(const struct rd_surface *S, uint64_t k)
{
    unsigned m = (unsigned)S->fcap - 1, q = key_hash(k) & m;
    while (S->fkey[q] != 0 && S->fkey[q] != k) q = (q + 1) & m;
    return (int)q;
}

/* Face pair k bore this step. 0, or -1 when out of memory. */
static int face_bore(struct rd_surface *S, uint64_t k)
{
    if (2 * (S->nfk + 1) > S->fcap) {
        int cap = S->fcap ? 2 * S->fcap : 256;
        uint64_t *ok = S->fkey;
        long *os = S->fstamp;
        const int ocap = S->fcap;
        S->fkey = calloc((size_t)cap, sizeof *S->fkey);
        S->fstamp = calloc((size_t)cap, sizeof *S->fstamp);
        if (!S->fkey || !S->fstamp) return -1;
        S->fcap = cap;
        for (int j = 0; j < ocap; j++)
            if (ok[j]) {
                int q = face_slot(S, ok[j]);
                S->fkey[q] = ok[j];
                S->fstamp[q] = os[j];
            }
        free(ok);
        free(os);
    }
    int q = face_slot(S, k);
    if (S->fkey[q] == 0) {
        S->fkey[q] = k;
        S->nfk++;
    }
    S->fstamp[q] = S->stamp;
    return 0;
}

/* Did face pair k bear at the last step? */
static int face_bore_last(const struct rd_surface *S, uint64_t k)
{
    if (S->fcap == 0) return 0;
    int q = face_slot(S, k);
    return S->fkey[q] == k && S->fstamp[q] == S->stamp - 1;
}

/* The regions of the candidates cand[0 .. nc) of one face of i (plane frame fr) into S->side
 * and S->hpl: what depends on H alone, once, not once per piece source. 0, -1 when out of
 * memory. */
static int face_sides(struct rd_surface *S, const rd_poly *Pr, const surf_body *Br,
                      const double fr[4][3], const mesh_cand *cand, int nc, const double rot[9],
                      const double tr[3])
{
    int nhp = 0;
    for (int k = 0; k < nc; k++) nhp += cand[k].facing ? Pr->flen[cand[k].fr] : 1;
    if (rd_grow((void **)&S->side, &S->cap_side, nc, sizeof *S->side) ||
        rd_grow((void **)&S->hpl, &S->cap_hpl, nhp, sizeof *S->hpl))
        return -1;
    int nh = 0;
    for (int k = 0; k < nc; k++) {
        mesh_side *sd = &S->side[k];
        double uh[3], dh;
        plane_in(S, Br, cand[k].Q, rot, tr, uh, &dh);
        sd->e[0] = dh - rd_dot(uh, fr[0]);
        sd->e[1] = -rd_dot(uh, fr[1]);
        sd->e[2] = -rd_dot(uh, fr[2]);
        sd->h0 = nh;
        if (!cand[k].facing) { /* only where S is behind H: 0 < d_H < d_R */
            S->hpl[nh][0] = sd->e[1];
            S->hpl[nh][1] = sd->e[2];
            S->hpl[nh++][2] = sd->e[0];
        } else
            project_face(fr, Pr, cand[k].fr, rot, tr, uh, S->hpl + nh, &nh);
        sd->nh = nh - sd->h0;
    }
    return 0;
}

/* Does convex polygon p meet the inside of the nh half-planes hp (a x + b y + c > 0)? Not when
 * all its vertices lie on or outside one of them: then the subtraction would only cut p into
 * pieces whose union is p (a test per half-plane instead of two clips). */
static int meets_region(const rd_poly2 *p, const double (*hp)[3], int nh)
{
    for (int h = 0; h < nh; h++) {
        int in = 0;
        for (int v = 0; v < p->n && !in; v++)
            in = hp[h][0] * p->p[v][0] + hp[h][1] * p->p[v][1] + hp[h][2] > 0;
        if (!in) return 0;
    }
    return 1;
}

/* The pieces of face c->fi of i (the candidates cand[0 .. nc), all of that face) into the pieces
 * store. Returns 0, 1 when the bodies passed into each other, -1 when out of memory. */
static int face_pieces(rd_sim *s, int pair, int i, int r, const mesh_cand *cand, int nc,
                       const double rot[9], const double tr[3], double band, int *npc)
{
    struct rd_surface *S = s->surf;
    const surf_body *B = &S->body[i], *Br = &S->body[r];
    const rd_poly *Pi = &s->poly[i], *Pr = &s->poly[r];
    const int fi = cand[0].fi, P = B->plane_of[fi];
    const double(*fr)[3] = B->frame[P];
    rd_poly2 sp, pieces[2][RD_SURF_PIECES], patch, cut;
    sp.n = Pi->flen[fi];
    memcpy(sp.p, B->f2 + B->f2_0[fi], (size_t)sp.n * sizeof sp.p[0]);
    const double sliver = RD_SURF_SLIVER * poly_area(&sp);
    int sides = 0; /* face_sides built: on the first piece source (most faces have none) */
    double rv[RD_PATCH_FACE_MAX][3];
    for (int k = 0; k < nc; k++) {
        if (!cand[k].facing || !cand[k].behind) continue;
        const int fr_ = cand[k].fr, Q = cand[k].Q, nr = Pr->flen[fr_];
        double u[3], dR, dep[3];
        plane_in(S, Br, Q, rot, tr, u, &dR);
        for (int v = 0; v < nr; v++) {
            rd_mat_vec(rot, Pr->v[Pr->fidx[Pr->fstart[fr_] + v]], rv[v]);
            rd_axpy(1.0, tr, rv[v]);
        }
        if (!rd_patch_faces(fr[0], fr[1], fr[2], fr[3], &sp, (const double(*)[3])rv, nr, u, dR,
                            &patch, dep))
            continue;
        if (!rd_patch_clip_half(&patch, dep[1], dep[2], dep[0], &cut)) continue;
        poly_copy(&patch, &cut);
        if (!sides && face_sides(S, Pr, Br, fr, cand, nc, rot, tr)) return -1;
        sides = 1;
        const mesh_side *side = S->side;
        /* the nearest face over each point: the part of the piece that lies in the prism of
           another candidate face H (of another plane) with d_H < d_R (nearer, or in front of
           H: outside r there) is taken out, piece minus a convex region, in convex parts */
        int cur = 0, np = 1;
        poly_copy(&pieces[0][0], &patch);
        for (int k2 = 0; k2 < nc && np > 0; k2++) {
            if (cand[k2].Q == Q || side[k2].nh == 0) continue;
            /* the region's sides, inside >= 0: d_R - d_H > 0, then H's (side[k2]) */
            const double *e = side[k2].e;
            double hp[RD_PATCH_FACE_MAX + 1][3];
            int nh = 1 + side[k2].nh;
            hp[0][0] = dep[1] - e[1];
            hp[0][1] = dep[2] - e[2];
            hp[0][2] = dep[0] - e[0];
            memcpy(hp + 1, S->hpl + side[k2].h0, (size_t)side[k2].nh * sizeof hp[0]);
            int nn = 0;
            for (int q = 0; q < np; q++) {
                const rd_poly2 *pc = &pieces[cur][q];
                if (!meets_region(pc, (const double(*)[3])hp, nh)) {
                    if (nn == RD_SURF_PIECES) return too_many_pieces(s, i, r, fi);
                    poly_copy(&pieces[!cur][nn++], pc);
                    continue;
                }
                rd_poly2 rest, nxt;
                poly_copy(&rest, pc);
                for (int h = 0; h < nh && rest.n; h++) {
                    /* a sliver of round-off along an edge two faces of r share is no piece */
                    if (rd_patch_clip_half(&rest, -hp[h][0], -hp[h][1], -hp[h][2], &cut) &&
                        poly_area(&cut) > sliver) {
                        if (nn == RD_SURF_PIECES) return too_many_pieces(s, i, r, fi);
                        poly_copy(&pieces[!cur][nn++], &cut);
                    }
                    if (!rd_patch_clip_half(&rest, hp[h][0], hp[h][1], hp[h][2], &nxt)) break;
                    poly_copy(&rest, &nxt);
                }
            }
            cur = !cur;
            np = nn;
        }
        /* where R is the nearest, a plane that bore on Q at the last step has gone deeper than
           the window: the bodies are inside each other (a face merely behind R's plane, in its
           prism, beyond a notch of r, is no evidence: it never bore) */
        double deepest = 0;
        for (int q = 0; q < np; q++)
            for (int v = 0; v < pieces[cur][q].n; v++)
                deepest = rd_max(deepest, dep[0] + dep[1] * pieces[cur][q].p[v][0] +
                                              dep[2] * pieces[cur][q].p[v][1]);
        if (deepest > band && face_bore_last(S, state_key(pair + 1, fi, Q)))
            return mesh_penetrated(s, i, r, fi, fr_, deepest, band);
        int bore = 0;
        for (int q = 0; q < np; q++)
            if (rd_patch_clip_half(&pieces[cur][q], -dep[1], -dep[2], band - dep[0], &cut)) {
                if (keep_piece(S, npc, &cut, P, Q)) return -1;
                bore = 1;
            }
        if (bore && face_bore(S, state_key(pair + 1, fi, Q))) return -1;
    }
    return 0;
}

static const int *g_pkey; /* the pieces' keys, for cmp_piece (qsort has no user pointer) */

static int cmp_piece(const void *a, const void *b)
{
    const int x = *(const int *)a, y = *(const int *)b;
    for (int k = 0; k < 2; k++)
        if (g_pkey[2 * x + k] != g_pkey[2 * y + k])
            return (g_pkey[2 * x + k] > g_pkey[2 * y + k]) -
                   (g_pkey[2 * x + k] < g_pkey[2 * y + k]);
    return (x > y) - (x < y);
}

/* Every patch of live pair number pair when neither body is convex: the face pairs that the two
 * trees give, their pieces (face_pieces), summed per (plane P of i, plane Q of r): one patch,
 * one state, per pair of planes. 0, 1 when the run must stop, -1 when out of memory. */
static int pair_mesh(rd_sim *s, int pair, int i, int r)
{
    struct rd_surface *S = s->surf;
    rd_pair *pr = &s->pair[pair];
    const rd_poly *Pi = &s->poly[i], *Pr = &s->poly[r];
    const surf_body *B = &S->body[i], *Br = &S->body[r];
    const rd_joint *j = &s->joint[pr->joint];
    const double band = RD_SURF_MESH_DEPTH * rd_min(Pr->radius, Pi->radius);
    double rot[9], tr[3];
    rel_pose(s, i, r, rot, tr);
    if (++S->qepoch == 0) { /* the epoch wrapped: start the stamps again */
        memset(S->qstamp, 0, (size_t)S->cap_q * sizeof *S->qstamp);
        S->qepoch = 1;
    }
    S->cand.n = 0;
    if (rd_bvh_overlaps(&B->tree, &Br->tree, rot, tr, band, &S->cand)) return -1;
    /* the facing and depth tests; the survivors in place, as mesh_cand */
    mesh_cand *mc = (mesh_cand *)S->ord;
    if (rd_grow((void **)&S->ord, &S->cap_ord,
                (int)(sizeof(mesh_cand) / sizeof(int)) * 2 * (S->cand.n + 1), sizeof *S->ord))
        return -1;
    mc = (mesh_cand *)S->ord;
    /* S wholly in front of R by more than the round-off of the depths (their terms' size) */
    const double front_tol = RD_SURF_ROUNDOFF * (Pi->radius + Pr->radius + rd_norm(tr));
    int nc = 0;
    for (int k = 0; k < S->cand.n; k++) {
        const int fi = S->cand.ab[k][0], fr_ = S->cand.ab[k][1], Q = Br->plane_of[fr_];
        double u[3], dR;
        plane_in(S, Br, Q, rot, tr, u, &dR);
        const int facing = rd_dot(Pi->fn[fi], u) < -RD_SURF_FACING;
        double dlo = DBL_MAX, dhi = -DBL_MAX;
        for (int q = Pi->fstart[fi]; q < Pi->fstart[fi] + Pi->flen[fi]; q++) {
            double d = dR - rd_dot(u, Pi->v[Pi->fidx[q]]);
            dlo = rd_min(dlo, d);
            dhi = rd_max(dhi, d);
        }
        /* a face wholly deeper than the band is a far side (not touching), unless its plane
           bore on Q at the last step: then it has sunk (face_pieces stops the run) */
        if (dlo >= band && !face_bore_last(S, state_key(pair + 1, fi, Q))) continue;
        /* a facing R wholly in front still rules its prism out for the others; a face that
           does not face S counts only where S is behind it */
        if (!facing && !(dhi > 0 && dlo < band)) continue;
        mc[nc++] = (mesh_cand){ fi, Q, fr_, facing, dhi > -front_tol };
    }
    if (sort_cand(S, mc, nc, Pi->nf, Br->nplane, Pr->nf)) return -1;
    int npc = 0;
    for (int k = 0; k < nc;) {
        int e = k;
        while (e < nc && mc[e].fi == mc[k].fi) e++;
        int rc = face_pieces(s, pair, i, r, mc + k, e - k, rot, tr, band, &npc);
        if (rc) return rc;
        k = e;
    }
    /* the pieces by (P, Q): each group one patch */
    int *ix = malloc((size_t)(npc ? npc : 1) * sizeof *ix);
    if (!ix) return -1;
    for (int k = 0; k < npc; k++) ix[k] = k;
    g_pkey = S->pkey;
    qsort(ix, (size_t)npc, sizeof *ix, cmp_piece);
    const double c_a = (j->damping > 0 && pr->k_active > 0)
                           ? 2 * j->damping * j->kn * sqrt(pr->m_eff / pr->k_active)
                           : 0.0;
    surf_sums sum = { .dp0 = S->dp.n }; /* all zero but the pair's first dashpot */
    int rc = 0;
    for (int k = 0; k < npc && !rc;) {
        const int P = S->pkey[2 * ix[k]], Q = S->pkey[2 * ix[k] + 1];
        int e = k;
        rd_moments m = { 0, 0, 0, 0, 0, 0 };
        for (; e < npc && S->pkey[2 * ix[e]] == P && S->pkey[2 * ix[e] + 1] == Q; e++) {
            rd_moments pm;
            rd_patch_moments(&S->comp[ix[e]], &pm);
            rd_moments_add(&m, &pm);
        }
        const double(*fr)[3] = B->frame[P];
        double u[3], dR, dep[3];
        plane_in(S, Br, Q, rot, tr, u, &dR);
        dep[0] = dR - rd_dot(u, fr[0]);
        dep[1] = -rd_dot(u, fr[1]);
        dep[2] = -rd_dot(u, fr[2]);
        rd_patch_load ld;
        rd_patch_load_from(&m, dep[0], dep[1], dep[2], &ld);
        if (ld.area > 0) {
            const double c[2] = { ld.cx, ld.cy };
            rd_mat_vec(s->R[r], Br->frame[Q][3], S->uw[Q]);
            surf_twist tw = { S->comp, ix + k, e - k, c, dep, NULL, 0.0 };
            rc = patch_apply(s, pr, pair, i, r, P, Q, &m, &ld, &tw, fr, dep, c_a, &sum);
        }
        k = e;
    }
    free(ix);
    if (rc) return rc;
    return pair_finish(s, pair, pr, i, r, &sum);
}

/* Every patch of live pair number pair: r is the convex body (the fixed one when both are), or,
 * when neither is convex, the fixed one (the larger when both are free). */
static int pair_step(rd_sim *s, int pair)
{
    const rd_pair *pr = &s->pair[pair];
    const int a = pr->a, b = pr->b;
    if (s->fixed[a] && s->fixed[b]) return 0;
    if (s->convex[a] || s->convex[b]) {
        int r = (s->convex[a] && s->convex[b]) ? (s->fixed[b] ? b : a) : s->convex[a] ? a : b;
        return pair_convex(s, pair, r == a ? b : a, r);
    }
    int r = s->fixed[a] ? a : s->fixed[b] ? b : s->poly[a].radius >= s->poly[b].radius ? a : b;
    return pair_mesh(s, pair, r == a ? b : a, r);
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
    for (int k = 0; k < s->nlive; k++) {
        int rc = pair_step(s, s->live[k]);
        if (rc > 0) return; /* the run stops (s->status and s->errmsg set) */
        if (rc < 0) {
            s->status = RD_STATUS_ERROR;
            snprintf(s->errmsg, sizeof s->errmsg, "out of memory (contact patches)");
            return;
        }
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
