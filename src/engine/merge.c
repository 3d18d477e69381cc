/* rockdem — one subcontact per place: the co-located points of a body merged at setup.
 *
 * A mesh face carries its vertices as points, so a vertex is a point of every face around it
 * (5.3 on average: the shipped PBR's 1,956 points sit at 366 places). The joint law is linear in
 * the tributary area A: Fn = KN A (depth - set), the shear increment KS A dUs, the Coulomb cap
 * tan(phi) Fn + c A, the dashpot and the tension cap scale with A, and the permanent set
 * (1 - e) depth_peak does not depend on A. Points at one place move together, so while they
 * share their state (entrance face, inside / active / slip / bond flags, set) one point with the
 * summed area bears exactly their summed force, to round-off. The merged point's state can
 * differ from the separate points' only where theirs would differ from each other:
 *  - the entrance face's tie-break among planes equally shallow within the contact band, for a
 *    contact made at rest (no approach), looks at the point's own face normal; a merged point
 *    uses the area-weighted mean normal of its faces (rd_sim.pn: the surface's normal at the
 *    vertex), where separate points could split one vertex's area over two entrance faces;
 *  - faces that touch only later (rd_sim.cf_facing) act only while they face the entrance face,
 *    a per-face test: their points are never merged;
 *  - the other faces' points bear only on faces they look at (contact.c, RD_BASE_FACING_COS),
 *    tested with the merged normal: faces more than 60 deg apart keep their own points (below).
 * The merged point belongs to the first of its faces (per-face counts, joint openings); faces
 * left with no point are no longer candidates (their vertices still bear through the points
 * that took them over, and a face's cull against the other body is the same test as its
 * vertices' exit test, see contact.c). rd_sim.pmult keeps how many points each one stands for
 * (the edge subcontacts' area is the mean area of the points before merging).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "base/vec.h"

#include <stdlib.h>
#include <string.h>

/* A point's place (its coordinates, bitwise) and index: sorted by place, then index. */
typedef struct merge_key {
    double x[3];
    int idx;
} merge_key;
static int by_place(const void *a, const void *b)
{
    const merge_key *p = a, *q = b;
    int c = memcmp(p->x, q->x, sizeof p->x);
    return c ? c : (p->idx > q->idx) - (p->idx < q->idx);
}

/* Co-located points merge only when their faces' normals lie within 60 deg of each other (of
 * the leading face's; the spread of a rock's base region, whose faces look down within 60 deg,
 * setup.c): a scanned surface's faces around a vertex share a point (the shipped PBR: 370
 * points, 366 with any faces merged),
 * while the faces of a sharp edge (a brick's base and its side placed on a neighbour's) bear on
 * different faces (contact.c, RD_BASE_FACING_COS) and keep their own points. Merged, the corner
 * of a brick placed against a neighbour carried its side's area on the floor too (and its base's
 * on the neighbour): the floor joint sank 0.75 of m g / (KN A). */
#define RD_MERGE_COS 0.5

/* Merge body i's co-located points on faces that always act: each run of equal places is taken
 * in index order, each point not yet merged leading a group of the later ones whose normals lie
 * within RD_MERGE_COS of its own; the leader takes its group's areas (summed in index order) and
 * the area-weighted mean of their normals; keep[j] = 0 for the others. */
static void merge_body(rd_sim *s, int i, merge_key *key, char *keep)
{
    int n = 0;
    for (int c = s->cf0[i]; c < s->cf0[i + 1]; c++) {
        if (s->cf_facing[c]) continue;
        for (int j = s->cf_pt0[c]; j < s->cf_pt0[c + 1]; j++) {
            memcpy(key[n].x, s->pl[j], sizeof key[n].x);
            key[n++].idx = j;
        }
    }
    qsort(key, (size_t)n, sizeof *key, by_place);
    for (int a = 0, b; a < n; a = b) {
        for (b = a + 1; b < n && !memcmp(key[b].x, key[a].x, sizeof key[a].x); b++) continue;
        for (int l = a; l < b; l++) {
            int p = key[l].idx, members = 1;
            if (!keep[p]) continue;
            double lead[3], area = s->pa[p], nrm[3] = { 0, 0, 0 };
            rd_copy3(s->pn[p], lead);
            rd_axpy(s->pa[p], s->pn[p], nrm);
            for (int k = l + 1; k < b; k++) {
                int j = key[k].idx;
                if (!keep[j] || rd_dot(s->pn[j], lead) < RD_MERGE_COS) continue;
                area += s->pa[j];
                rd_axpy(s->pa[j], s->pn[j], nrm);
                s->pmult[p] += s->pmult[j];
                keep[j] = 0;
                members++;
            }
            if (members == 1) continue;
            double len = rd_norm(nrm); /* 0: faces that cancel; the first face's normal stays */
            if (len > 0)
                for (int k = 0; k < 3; k++) s->pn[p][k] = nrm[k] / len;
            s->pa[p] = area;
        }
    }
}

/* Drop the merged points and the candidate faces left without a point, keeping the grouping by
 * body and candidate face. */
static void compact(rd_sim *s, const char *keep)
{
    int out = 0, ncf = 0;
    for (int i = 0; i < s->nb; i++) {
        int c0 = s->cf0[i], c1 = s->cf0[i + 1];
        s->pt0[i] = out;
        s->cf0[i] = ncf;
        for (int c = c0; c < c1; c++) {
            int first = s->cf_pt0[c], last = s->cf_pt0[c + 1], start = out;
            for (int j = first; j < last; j++) {
                if (!keep[j]) continue;
                memmove(s->pl[out], s->pl[j], sizeof s->pl[j]);
                memmove(s->pn[out], s->pn[j], sizeof s->pn[j]);
                s->pa[out] = s->pa[j];
                s->pmult[out++] = s->pmult[j];
            }
            if (out == start) continue;
            s->cf_face[ncf] = s->cf_face[c];
            s->cf_facing[ncf] = s->cf_facing[c];
            s->cf_pt0[ncf++] = start;
        }
    }
    s->pt0[s->nb] = s->cf_pt0[ncf] = s->npts = out;
    s->cf0[s->nb] = s->ncf = ncf;
}

int rd_merge_points(rd_sim *s, rd_error *err)
{
    s->pn = calloc((size_t)s->npts + 1, sizeof *s->pn);
    s->pmult = calloc((size_t)s->npts + 1, sizeof *s->pmult);
    merge_key *key = malloc(((size_t)s->npts + 1) * sizeof *key);
    char *keep = malloc((size_t)s->npts + 1);
    if (!s->pn || !s->pmult || !key || !keep) {
        free(key);
        free(keep);
        return rd_error_set(err, "out of memory");
    }
    for (int i = 0; i < s->nb; i++)
        for (int c = s->cf0[i]; c < s->cf0[i + 1]; c++)
            for (int j = s->cf_pt0[c]; j < s->cf_pt0[c + 1]; j++) {
                rd_copy3(s->poly[i].fn[s->cf_face[c]], s->pn[j]);
                s->pmult[j] = 1;
                keep[j] = 1;
            }
    for (int i = 0; i < s->nb; i++) merge_body(s, i, key, keep);
    compact(s, keep);
    free(key);
    free(keep);
    return 0;
}
