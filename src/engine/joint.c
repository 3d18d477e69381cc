/* rockdem — joints: per-range contact properties and what each joint does.
 *
 * Properties (3DEC `block contact property ... range group A group B`): every pair of bodies
 * starts from the default joint (`contact property` without a range, and the model's viscous
 * damping ratio), then takes each override whose range holds the pair, in file order, so a
 * later override wins where two set the same property. A pair is resolved once, when the broad
 * phase first creates it; pairs with equal properties share one rd_joint.
 *
 * Measures (rd_joint_measure), from the contact law's per-subcontact state:
 *   normal force   sum of the normal forces of the joint's active subcontacts, N
 *   shear force    vector sum of their shear forces, on the pair's second body, N
 *   area           active contact area, m^2 (half-weight sets summed where both bodies carry
 *                  points); these, the centre of pressure and the slip count the bearing edge
 *                  springs too (edge.c)
 *   centre of pressure   normal-force weighted mean of their positions, m
 *   opening        the largest gap among the subcontacts evaluated this step on the faces
 *                  turned towards the other body and lying over the other body's face (within
 *                  its side walls, to the contact band: a brick's overhang beside the brick
 *                  below is not an opening of their joint), m; NaN with the surface model
 *                  (its patches hold only the compressed region), whose force, area, centre
 *                  of pressure and shear come from its patches (surface.c)
 *   slip           tangential displacement of the second body against the first, summed
 *                  measure to measure while the joint carries load, of the material points
 *                  at the centre of pressure of the previous measure, minus the elastic shear
 *                  sum(Fs) / (KS A): the joint's own slip, not the sway of a rocking stack (a
 *                  joint that rocks as one with its neighbours does not move) nor the roll of
 *                  a block tipping about its edge (the pivot stays put). Measures are taken
 *                  at output and history samples.
 *
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "engine/workers.h"
#include "base/vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Does body i belong to range r? */
static int in_range(const rd_sim *s, const rd_range_def *r, int i)
{
    const rd_body_def *d = &s->sc.bodies[i];
    switch (r->kind) {
    case RD_RANGE_ANY: return 1;
    case RD_RANGE_GROUP: return strcmp(d->group, r->name) == 0;
    case RD_RANGE_BLOCK: return strcmp(d->name, r->name) == 0;
    }
    return 0;
}

static int applies(const rd_sim *s, const rd_joint_def *j, int a, int b)
{
    return (in_range(s, &j->range[0], a) && in_range(s, &j->range[1], b)) ||
           (in_range(s, &j->range[0], b) && in_range(s, &j->range[1], a));
}

static void override(rd_joint *p, const rd_joint_def *j)
{
    if (j->set & RD_JOINT_KN) p->kn = j->kn;
    if (j->set & RD_JOINT_KS) p->ks = j->ks;
    if (j->set & RD_JOINT_FRICTION) p->friction = j->friction;
    if (j->set & RD_JOINT_COHESION) p->cohesion = j->cohesion;
    if (j->set & RD_JOINT_TENSION) p->tension = j->tension;
    if (j->set & RD_JOINT_DAMPING) p->damping = j->damping;
    if (j->set & RD_JOINT_RESTITUTION) p->restitution = j->restitution;
    p->tan_phi = tan(p->friction);
}

/* Properties of the joint between bodies a and b (no table entry). */
static rd_joint joint_of(const rd_sim *s, int a, int b)
{
    rd_joint p = s->joint[0];
    for (int k = 0; k < s->sc.njoints; k++)
        if (applies(s, &s->sc.joint[k], a, b)) override(&p, &s->sc.joint[k]);
    return p;
}

/* Index of properties p in the table, appending them when new; -1 without memory. */
static int intern(rd_sim *s, const rd_joint *p)
{
    for (int k = 0; k < s->njoint; k++)
        if (!memcmp(&s->joint[k], p, sizeof *p)) return k;
    if (s->njoint == s->cap_joint) {
        int cap = s->cap_joint ? 2 * s->cap_joint : 8;
        rd_joint *t = realloc(s->joint, (size_t)cap * sizeof *t);
        if (!t) return -1;
        s->joint = t;
        s->cap_joint = cap;
    }
    s->joint[s->njoint] = *p;
    return s->njoint++;
}

int rd_joint_resolve(rd_sim *s, int a, int b)
{
    rd_joint p = joint_of(s, a, b);
    return intern(s, &p);
}

/* Is range r's name known (a group some body carries, or a body)? */
static int range_known(const rd_sim *s, const rd_range_def *r)
{
    if (r->kind == RD_RANGE_ANY) return 1;
    for (int i = 0; i < s->nb; i++)
        if (!strcmp(r->kind == RD_RANGE_GROUP ? s->sc.bodies[i].group : s->sc.bodies[i].name,
                    r->name))
            return 1;
    return 0;
}

int rd_joints_init(rd_sim *s, rd_error *err)
{
    const rd_contact_def *c = &s->sc.contact;
    rd_joint def = { .kn = c->kn,
                     .ks = c->ks,
                     .friction = c->friction,
                     .tan_phi = tan(c->friction),
                     .cohesion = c->cohesion,
                     .tension = c->tension,
                     .restitution = c->restitution,
                     .damping =
                         s->sc.damping.kind == RD_DAMPING_VISCOUS ? s->sc.damping.value : 0.0 };
    s->njoint = 0;
    if (intern(s, &def) < 0) return rd_error_set(err, "out of memory");
    s->bonds = def.cohesion > 0 || def.tension > 0;
    for (int k = 0; k < s->sc.njoints; k++) {
        const rd_joint_def *j = &s->sc.joint[k];
        for (int e = 0; e < 2; e++)
            if (!range_known(s, &j->range[e]))
                return rd_error_set(err, "%s:%d: contact property range: no block %s '%s'",
                                    s->sc.file, j->line,
                                    j->range[e].kind == RD_RANGE_GROUP ? "is in group" : "is named",
                                    j->range[e].name);
        if (((j->set & RD_JOINT_COHESION) && j->cohesion > 0) ||
            ((j->set & RD_JOINT_TENSION) && j->tension > 0))
            s->bonds = 1;
    }
    return 0;
}

/* Stiffest joint stiffness max(KN, KS) and largest dashpot ratio of the joints body i can form
 * (with every other body), for the critical time step. */
void rd_joint_body_limits(const rd_sim *s, int i, double *k, double *zeta)
{
    const rd_joint *d = &s->joint[0];
    *k = fmax(d->kn, d->ks);
    *zeta = d->damping;
    if (s->sc.njoints == 0) return;
    *k = 0;
    *zeta = 0;
    for (int j = 0; j < s->nb; j++) {
        if (j == i) continue;
        rd_joint p = joint_of(s, i, j);
        *k = fmax(*k, fmax(p.kn, p.ks));
        *zeta = fmax(*zeta, p.damping);
    }
}

/* A face skipped as wholly clear of the other body: its points' gaps are at least `gap`. */
void rd_joint_face_open(rd_sim *s, const rd_side *sd, int cf, double gap)
{
    int first = sd->state0 + (s->cf_pt0[cf] - s->pt0[sd->owner]);
    int n = s->cf_pt0[cf + 1] - s->cf_pt0[cf];
    for (int j = 0; j < n; j++) {
        s->pj[first + j][0] = 0;
        s->pj[first + j][1] = gap;
    }
}

int rd_pair_find(const rd_sim *s, int a, int b)
{
    if (a > b) {
        int t = a;
        a = b;
        b = t;
    }
    for (int p = 0; p < s->npair; p++)
        if (s->pair[p].a == a && s->pair[p].b == b) return p;
    return -1;
}

/* World position of point j of body o. */
static void point_world(const rd_sim *s, int o, int j, double out[3])
{
    rd_mat_vec(s->R[o], s->pl[j], out);
    rd_axpy(1.0, s->x[o], out);
}

/* Does point p lie over the face of convex body t that meets the joint (normal n): inside every
 * side wall of t (a face within 60 deg of perpendicular to n), to the contact band tol (m)? */
static int over_face(const rd_sim *s, int t, const double n[3], const double p[3], double tol)
{
    for (int f = s->face0[t]; f < s->face0[t + 1]; f++)
        if (fabs(rd_dot(s->wn[f], n)) < 0.5 && rd_dot(s->wn[f], p) - s->wd[f] > tol) return 0;
    return 1;
}

/* The bearing edge springs of side sd (edge.c; kn: the joint's KN, Pa/m) into m's normal force
 * and area, the centre of pressure's sums (cop, fsum) and the shear on the second body (fs_b;
 * sign: +1 where the owner is the second body, as the points'). A spring lies at its place
 * along its edge of the other body t. */
static void edge_measure(const rd_sim *s, const rd_side *sd, int t, double kn, double sign,
                         rd_joint_state *m, double *fsum, double fs_b[3])
{
    const int(*ev)[2] = s->edge_v + s->edge_v0[t];
    for (int i = 0; i < sd->nedge; i++)
        for (int k = 0; k < RD_EDGE_SLOTS; k++) {
            int e = sd->edge0 + RD_EDGE_SLOTS * i + k;
            if (!s->eon[e] || !(s->edepth[e][0] > 0)) continue;
            const double *a = s->wv[s->vert0[t] + ev[i][0]], *b = s->wv[s->vert0[t] + ev[i][1]];
            double A = rd_edge_slot_area(s, sd, e), fn = kn * A * s->edepth[e][0],
                   u = s->edepth[e][2];
            m->fn += fn;
            m->area += A;
            *fsum += fn;
            for (int c = 0; c < 3; c++) {
                m->cop[c] += fn * (a[c] + u * (b[c] - a[c]));
                fs_b[c] += sign * s->efs[e][c];
            }
        }
}

/* Side q of pair pr: its owner o, the other body t, the contact band tol (m) and the joint's
 * normal in the owner's frame nb. */
static void side_frame(const rd_sim *s, const rd_pair *pr, int q, int *o, int *t, double *tol,
                       double nb[3])
{
    *o = pr->side[q].owner;
    *t = *o == pr->a ? pr->b : pr->a;
    *tol = RD_CONTACT_BAND * fmin(s->poly[*o].radius, s->poly[*t].radius);
    rd_mat_tvec(s->R[*o], pr->n, nb);
}

/* Does face cf of body o turn towards the other body (joint normal nb in o's frame, to_other
 * its sign)? Only such faces measure the joint's opening (the face's normal in the body frame:
 * a mesh body's step leaves its world face normals alone). */
static int face_turned(const rd_sim *s, int o, int cf, const double nb[3], double to_other)
{
    return to_other * rd_dot(s->poly[o].fn[s->cf_face[cf]], nb) > 0.5;
}

/* The joint's opening (m): the largest gap of a point on a face turned towards the other body
 * and, against a convex body, lying over its face that meets the joint. */
static double opening_scan(const rd_sim *s, const rd_pair *pr)
{
    double open = 0;
    for (int q = 0; q < pr->nside; q++) {
        const rd_side *sd = &pr->side[q];
        int o, t;
        double tol, nb[3], to_other = sd->owner == pr->a ? 1.0 : -1.0;
        side_frame(s, pr, q, &o, &t, &tol, nb);
        for (int cf = s->cf0[o]; cf < s->cf0[o + 1]; cf++) {
            if (s->cf_pt0[cf + 1] == s->cf_pt0[cf] || !face_turned(s, o, cf, nb, to_other))
                continue;
            for (int j = s->cf_pt0[cf]; j < s->cf_pt0[cf + 1]; j++) {
                int st = sd->state0 + (j - s->pt0[o]);
                if (!(s->pj[st][1] < 1e300 && s->pj[st][1] > open)) continue;
                double p[3];
                point_world(s, o, j, p);
                if (!s->convex[t] || over_face(s, t, pr->n, p, tol)) open = s->pj[st][1];
            }
        }
    }
    return open;
}

/* Face cf of body o that holds point j (cf_pt0 is ascending over the body's faces). */
static int point_face(const rd_sim *s, int o, int j)
{
    int lo = s->cf0[o], hi = s->cf0[o + 1] - 1; /* cf_pt0[lo] <= j < cf_pt0[hi + 1] */
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (s->cf_pt0[mid] <= j)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

/* The largest gap (m) of side sd's points on owner o's faces turned towards the other body,
 * above *best (first such point in point order); *best_j its point, left alone when none beats
 * it. */
static void turned_gap(const rd_sim *s, const rd_side *sd, int o, const double nb[3],
                       double to_other, double *best, int *best_j)
{
    for (int cf = s->cf0[o]; cf < s->cf0[o + 1]; cf++) {
        int facing = -1; /* asked once per face, and only when a point of it could count */
        for (int j = s->cf_pt0[cf]; j < s->cf_pt0[cf + 1]; j++) {
            double g = s->pj[sd->state0 + (j - s->pt0[o])][1];
            if (!(g < 1e300 && g > *best)) continue;
            if (facing < 0) facing = face_turned(s, o, cf, nb, to_other);
            if (!facing) break;
            *best = g;
            *best_j = j;
        }
    }
}

/* Side sd's active points (owner o) into m's normal force and area and the centre of
 * pressure's sums (cop: the |fn|-weighted sum of their positions, fsum: of |fn|), the shear on
 * the second body into fs_b (sign as edge_measure's); and the largest gap of any of its points
 * and that point (gap, gap_j; gap_j -1 when none is above 0). One pass in point order, the
 * positions summed in the body frame and turned once: sum |fn| (R p + x) = R sum |fn| p + x
 * sum |fn|. The weight is 1 or 1/2, so w sum A = sum w A exactly. */
static void side_measure(const rd_sim *s, const rd_side *sd, int o, double sign, rd_joint_state *m,
                         double *fsum, double fs_b[3], double *gap, int *gap_j)
{
    const int j0 = s->pt0[o], n = s->pt0[o + 1] - j0;
    const unsigned char *ps = s->pstate + sd->state0;
    const double(*pj)[2] = (const double(*)[2])(s->pj + sd->state0);
    const double(*fs)[3] = (const double(*)[3])(s->fs + sd->state0);
    const double(*pl)[3] = (const double(*)[3])(s->pl + j0);
    const double *pa = s->pa + j0;
    double fn_sum = 0, area = 0, wsum = 0, cop_b[3] = { 0, 0, 0 }, shear[3] = { 0, 0, 0 };
    double best = 0;
    int best_i = -1;
    for (int i = 0; i < n; i++) {
        double g = pj[i][1];
        if (g < 1e300 && g > best) {
            best = g;
            best_i = i;
        }
        if (!(ps[i] & RD_PT_ACTIVE)) continue;
        double fn = pj[i][0], w = fabs(fn);
        fn_sum += fn;
        area += pa[i];
        wsum += w;
        for (int k = 0; k < 3; k++) {
            cop_b[k] += w * pl[i][k];
            shear[k] += fs[i][k];
        }
    }
    double cop[3];
    rd_mat_vec(s->R[o], cop_b, cop);
    m->fn += fn_sum;
    m->area += sd->weight * area;
    *fsum += wsum;
    for (int k = 0; k < 3; k++) {
        m->cop[k] += cop[k] + wsum * s->x[o][k];
        fs_b[k] += sign * shear[k];
    }
    *gap = best;
    *gap_j = best_i < 0 ? -1 : j0 + best_i;
}

void rd_joint_measure(rd_sim *s, rd_pair *pr, rd_joint_state *m)
{
    memset(m, 0, sizeof *m);
    const rd_joint *jt = &s->joint[pr->joint];
    double fs_b[3] = { 0, 0, 0 }, fsum = 0, open = 0;
    int live = pr->seen == s->stamp;       /* a pair whose boxes parted holds no contact */
    int normal = rd_dot(pr->n, pr->n) > 0; /* the joint has borne load */
    /* The opening is the largest gap of the points that may measure it (on a face turned
       towards the other body): this runs every step, so the deepest point of the side is found
       in the forces' pass and its face asked alone; only where that face is not turned are the
       turned faces scanned (the same point: the first largest of a subset that holds the first
       largest of the whole). That point is then tested alone against the face it must lie
       over; only when it lies off that face does opening_scan look at them all. */
    double best_gap = 0;
    int best_q = -1, best_j = -1;
    if (s->surf && live) { /* the surface model's patches (surface.c); no opening measured */
        rd_surface_joint_measure(s, pr, m, &fsum);
        rd_copy3(m->fs, fs_b);
        open = NAN;
    }
    for (int q = 0; q < pr->nside && live && !s->surf; q++) {
        const rd_side *sd = &pr->side[q];
        int o, t, gap_j;
        double tol, nb[3], gap;
        side_frame(s, pr, q, &o, &t, &tol, nb);
        double sign = o == pr->b ? 1.0 : -1.0;     /* stored forces act on the owner */
        double to_other = o == pr->a ? 1.0 : -1.0; /* pr->n points from a towards b */
        side_measure(s, sd, o, sign, m, &fsum, fs_b, &gap, &gap_j);
        if (normal && gap > best_gap) {
            if (face_turned(s, o, point_face(s, o, gap_j), nb, to_other)) {
                best_gap = gap;
                best_j = gap_j;
                best_q = q;
            } else {
                int j = -1;
                turned_gap(s, sd, o, nb, to_other, &best_gap, &j);
                if (j >= 0) {
                    best_j = j;
                    best_q = q;
                }
            }
        }
        edge_measure(s, sd, t, jt->kn, sign, m, &fsum, fs_b);
    }
    if (best_q >= 0) {
        int o, t;
        double tol, nb[3], p[3];
        side_frame(s, pr, best_q, &o, &t, &tol, nb);
        point_world(s, o, best_j, p);
        open = !s->convex[t] || over_face(s, t, pr->n, p, tol) ? best_gap : opening_scan(s, pr);
    }
    m->opening = live ? open : INFINITY;
    rd_copy3(fs_b, m->fs);
    for (int k = 0; k < 3; k++) {
        m->cop[k] = fsum > 0 ? m->cop[k] / fsum : 0.5 * (s->x[pr->a][k] + s->x[pr->b][k]);
    }
    int loaded = m->area > 0 && s->shaking;
    if (pr->ref_set && loaded) { /* the material points at the last centre of pressure */
        double pa[3], pb[3], d[3];
        rd_mat_vec(s->R[pr->a], pr->ref[0], pa);
        rd_mat_vec(s->R[pr->b], pr->ref[1], pb);
        for (int k = 0; k < 3; k++) d[k] = (pb[k] + s->x[pr->b][k]) - (pa[k] + s->x[pr->a][k]);
        double dn = rd_dot(d, pr->n);
        for (int k = 0; k < 3; k++) pr->slip_acc[k] += d[k] - dn * pr->n[k];
    }
    pr->ref_set = loaded;
    for (int e = 0; loaded && e < 2; e++) {
        int i = e ? pr->b : pr->a;
        double d[3] = { m->cop[0] - s->x[i][0], m->cop[1] - s->x[i][1], m->cop[2] - s->x[i][2] };
        rd_mat_tvec(s->R[i], d, pr->ref[e]);
    }
    for (int k = 0; k < 3; k++) {
        /* elastic shear of the second body: its shear force is -KS A times its displacement */
        double el = m->area > 0 ? -fs_b[k] / (jt->ks * m->area) : 0.0;
        m->slip[k] = pr->slip_acc[k] - el;
    }
}

/* Outcomes of every joint while shaking, called every step (the slip accumulates between
 * measures along the centre of pressure's path, so a coarser call misses slip, and maxima
 * between samples): largest opening beyond the gaps it had when it first closed, largest slip,
 * final slip. */
static void joint_sample(rd_sim *s, rd_pair *pr)
{
    if (pr->seen != s->stamp) return; /* parted: keeps what it had */
    rd_joint_state m;
    rd_joint_measure(s, pr, &m);
    if (m.area > 0) pr->closed = 1;
    if (!pr->closed) return;
    if (!pr->rest_set && m.area > 0 && isfinite(m.opening)) {
        const rd_joint *jt = &s->joint[pr->joint];
        pr->open_rest = m.opening;
        pr->comp_rest = m.fn / (jt->kn * m.area);
        pr->rest_set = 1;
    }
    double opened = m.opening - pr->open_rest;
    if (pr->rest_set && isfinite(m.opening) && opened > pr->comp_rest)
        pr->open_max = fmax(pr->open_max, opened);
    pr->slip_max = fmax(pr->slip_max, rd_norm(m.slip));
    rd_copy3(m.slip, pr->slip_end);
}

/* Each pair's measure reads the bodies and its own points and writes its own fields only, so
 * the pairs run on the run's threads (workers.h) where there are enough, with the same bits,
 * each thread one stretch of the pairs (made in the sweep's order, so about the pairs of its
 * block of the contact loop, in its core's cache); the surface model's measures (surface.c)
 * stay serial. */
void rd_joints_sample(rd_sim *s)
{
    const int n = s->surf ? 1 : rd_threads_for_pairs(s, NULL, s->npair);
    if (n > 1) {
        RD_OMP(omp parallel for schedule(static) num_threads(n))
        for (int p = 0; p < s->npair; p++) joint_sample(s, &s->pair[p]);
    } else {
        for (int p = 0; p < s->npair; p++) joint_sample(s, &s->pair[p]);
    }
}
