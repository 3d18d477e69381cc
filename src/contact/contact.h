/* rockdem (private) — contact from the touching surfaces (docs/CONTACT.md section 8).
 *
 * Geometry of a contact patch. Two bodies touch where a face S of one (the integration face) and
 * a face R of the other (the reference face) face each other: outward normals nearly opposite,
 * the faces within the contact band. The patch is S's part whose projection along R's normal u
 * falls inside R: R's polygon projected along u onto S's plane, clipped against S's polygon
 * (Sutherland-Hodgman; both faces are convex: polyhedron faces, mesh triangles). Each material
 * point p of S inside the patch is a Winkler spring (KN per unit area) of depth
 *     d(p) = dR - u . p       (> 0: inside the other body, behind R's plane)
 * along u, the limit of a bed of vertex subcontacts as the bed's spacing goes to zero. d is
 * affine in S's plane coordinates (x, y): d = d0 + gx x + gy y. The compressed region, d > 0, is
 * the patch clipped by the zero-gap line, and over that convex polygon the force, both moments
 * and the spring energy of the pressure KN d are polynomial integrals, exact from the polygon's
 * moments (Green's theorem): the joint's stiffness is the patch's area whatever the faces' sizes.
 * The twisting friction of the patch needs the pressure-weighted mean distance from the torsion
 * centre, an integral of |r|: exact too, by fan triangles from the centre, polar in the radial
 * direction and the closed form of the integral of a square root of a quadratic along each edge
 * (rd_patch_load).
 * Folder contact/ holds the patch geometry and its law; it may call base/ and geometry/, and is
 * called by engine/.
 */
#ifndef RD_CONTACT_H
#define RD_CONTACT_H

#include <math.h>

#define RD_PATCH_MAX                                                                               \
    264                       /* most vertices of a patch polygon: the overlap of two convex faces
                            has at most the sum of their edges, and faces have at most
                            RD_PATCH_FACE_MAX (a 128-sided drum's cap): 256, and a few more for
                            the round-off of near-parallel clip lines */
#define RD_PATCH_FACE_MAX 128 /* most vertices of a face that takes part in a patch */

/* A convex polygon in a plane's coordinates, counter-clockwise, m. */
typedef struct rd_poly2 {
    int n;
    double p[RD_PATCH_MAX][2];
} rd_poly2;

/* Area moments of a polygon, m^2 .. m^4: integrals of 1, x, y, x^2, x y, y^2 over it. */
typedef struct rd_moments {
    double a, sx, sy, sxx, sxy, syy;
} rd_moments;

/* m += p: the moments of a region made of pieces are their sums. */
static inline void rd_moments_add(rd_moments *m, const rd_moments *p)
{
    m->a += p->a;
    m->sx += p->sx;
    m->sy += p->sy;
    m->sxx += p->sxx;
    m->sxy += p->sxy;
    m->syy += p->syy;
}

/* What the pressure KN d of an affine depth d = d0 + gx x + gy y does over a patch, per unit KN
 * (the caller multiplies by KN): the compressed region (d > 0) only. */
typedef struct rd_patch_load {
    double area;   /* compressed area, m^2 */
    double cx, cy; /* its centroid, m (0, 0 when area is 0) */
    double polar;  /* its polar moment about the centroid, integral of |r - c|^2, m^4 */
    double f;      /* integral of d, m^3 (the normal force / KN) */
    double mx, my; /* integrals of x d and y d, m^4 (the force's moments / KN) */
    double e2;     /* integral of d^2, m^4 (twice the spring energy / KN) */
    double tors;   /* integral of d |r - c|, m^4, c the centroid (the twisting friction's
                         lever: the limit torque is tan(phi) KN tors) */
} rd_patch_load;

/* The part of polygon in where a x + b y + c >= 0 (convex in, convex out). Returns out->n. */
int rd_patch_clip_half(const rd_poly2 *in, double a, double b, double c, rd_poly2 *out);

/* The part of polygon subj inside the convex counter-clockwise polygon clip (Sutherland-
 * Hodgman). Returns out->n; 0 when they do not overlap or when the result would exceed
 * RD_PATCH_MAX vertices (never for faces of at most RD_PATCH_MAX / 2 edges). */
int rd_patch_clip(const rd_poly2 *subj, const rd_poly2 *clip, rd_poly2 *out);

/* Area moments of a counter-clockwise polygon (Green's theorem; exact). Coordinates should be
 * taken from a point near the polygon (the caller's plane origin) to keep the round-off small. */
void rd_patch_moments(const rd_poly2 *p, rd_moments *m);

/* Integral of (d0 + gx x + gy y) |r - c| over a counter-clockwise convex polygon, m^4 (c: a
 * point inside it or on its boundary). Fan triangles from c: along each ray the integrand is a
 * polynomial of the radius, and along each edge the closed form of the integral of
 * sqrt(alpha t^2 + beta t + gamma) and of t times it. */
double rd_patch_torsion(const rd_poly2 *p, const double c[2], double d0, double gx, double gy);

/* A lower bound of rd_patch_torsion summed over n pieces about one centre c, cheap (no square
 * root of a quadratic): the integral of d |r - c|^2 over them divided by the largest |r - c| of
 * their vertices (|r - c| >= |r - c|^2 / rmax), from their third area moments. The pieces must
 * lie where d >= 0. 0 when it cannot bound (no area). */
double rd_patch_torsion_bound(const rd_poly2 *pieces, int n, const double c[2], double d0,
                              double gx, double gy);

/* A weaker lower bound, cheaper still (one pass over the vertices): with F the integral of d
 * over the pieces (m^3) and dmax the largest d at their vertices, the part of F within a disc
 * of radius q about any centre is at most pi q^2 dmax, so the integral of d |r - c| is at
 * least q (F - pi q^2 dmax), largest at q = sqrt(F / (3 pi dmax)): (2/3) q F. The pieces must
 * lie where d >= 0. 0 when it cannot bound. */
double rd_patch_torsion_disc(const rd_poly2 *pieces, int n, double f, double d0, double gx,
                             double gy);
/* The same bound from f and dmax (m, the largest d over the pieces, 0 or more) themselves. */
double rd_patch_torsion_disc_of(double f, double dmax);

/* Scratch of rd_patch_torsion_set (zero it before first use; free its arrays after). */
typedef struct rd_patch_scratch {
    int cap;
    int *slot, *count;
    const double (**ends)[2];
} rd_patch_scratch;

/* rd_patch_torsion summed over n pieces of one plane (a face cut into triangles), about one
 * centre c: an edge two pieces share (the same two vertices, to the bit) runs both ways and
 * its fan triangles cancel, so only the union's boundary is integrated (cost follows the
 * boundary, and the sum is the union's to round-off). */
double rd_patch_torsion_set(const rd_poly2 *pieces, int n, const double c[2], double d0, double gx,
                            double gy, rd_patch_scratch *sc);

/* The load of the affine depth d0 + gx x + gy y over patch p: p clipped by d > 0 (into *comp
 * when comp is not NULL), then its moments (rd_patch_load; its torsion about its own centroid).
 * Every field but tors is additive over pieces of a patch; tors is about the piece's own
 * centroid, so the pieces of one plane (a face cut into triangles) take rd_patch_torsion about
 * their common centroid instead. */
void rd_patch_load_of(const rd_poly2 *p, double d0, double gx, double gy, rd_patch_load *out,
                      rd_poly2 *comp);

/* The load of the depth d0 + gx x + gy y over a compressed region of moments m (the sum of its
 * pieces' moments), all fields but tors (left 0). */
void rd_patch_load_from(const rd_moments *m, double d0, double gx, double gy, rd_patch_load *out);

/* The patch of face S against face R, in S's plane frame: origin o, axes e1, e2 and outward
 * normal n = e1 x e2 (unit), S's polygon s (counter-clockwise about n, in that frame); R's nr
 * vertices rv (ground frame, counter-clockwise about its outward normal u) and its plane
 * u . q = dR. R is projected along u onto S's plane and clipped against s. Fills the patch
 * polygon and the depth's affine coefficients (d0, gx, gy: d = d0 + gx x + gy y, m). Returns the
 * patch's vertex count (0: no overlap, or faces that do not face each other, n . u >= 0). */
int rd_patch_faces(const double o[3], const double e1[3], const double e2[3], const double n[3],
                   const rd_poly2 *s, const double (*rv)[3], int nr, const double u[3], double dR,
                   rd_poly2 *patch, double dep[3]);

/* Most vertices of a cell of merged coplanar faces (rd_patch_cells): clipped by the planes of
 * a convex partner it stays well inside RD_PATCH_MAX. */
#define RD_PATCH_CELL_MAX 64

/* Coplanar faces merged into convex cells, once at setup (contact/cells.c): nface faces, face f
 * the slots f0[f] .. f0[f + 1) (counter-clockwise in the plane's coordinates), slot q its
 * vertex id vid[q] (equal ids: one vertex) at xy[q]. Two cells that share a chain of edges are
 * joined while the union stays convex (no right turn) and of at most maxv vertices; an
 * interior vertex that the join closes drops out, every other vertex is kept to the bit. The
 * cells (as slot lists, counter-clockwise) into c0 (room for nface + 1) and cslot (room for
 * f0[nface]). Returns the cell count, -1 when out of memory. */
int rd_patch_cells(int nface, const int *f0, const int *vid, const double (*xy)[2], int maxv,
                   int *c0, int *cslot);

/* A body's nf faces (unit outward normals fn, offsets fd: fn . x = fd on face f, m) grouped
 * into planes, once at setup (contact/planes.c): face f joins the first plane opened before it
 * whose opening face's normal m has fn[f] . m > 1 - ntol and whose offset is within dtol (m), or
 * opens the next one; ntol, dtol > 0. The same grouping as comparing each face with every
 * plane, in expected time linear in nf. Each face's plane into plane_of, each plane's opening
 * face into first (room for nf). Returns the plane count, -1 when out of memory. */
int rd_plane_group(int nf, const double (*fn)[3], const double *fd, double ntol, double dtol,
                   int *plane_of, int *first);

/* ---- The joint law of a patch (docs/CONTACT.md section 8), written once ----
 * Normal: the Winkler pressure KN d (+ a dashpot's c_a dd/dt, c_a in Pa s/m) integrated over the
 * compressed region exactly (rd_patch_load). Shear: one spring per patch, the resultant fs of the
 * shear stresses, stiffness KS A (A the compressed area), loaded by the tangential velocity of
 * the region's centroid, and a twisting spring mt about the normal, stiffness KS J (J the
 * region's polar moment about its centroid), loaded by the relative spin about the normal: a
 * uniform shear stress field's rigid in-plane motion, decoupled about the centroid. Coulomb:
 * the pair (fs, mt) stays inside the ellipsoidal limit surface
 *     (|fs| / F_lim)^2 + (mt / M_lim)^2 <= 1,  F_lim = tan(phi) Fn,  M_lim = rho F_lim,
 * rho = (integral of d |r - c|) / (integral of d), the pressure's mean lever about the centroid:
 * a pure slide gives Coulomb's F_lim and a pure spin the torque of a uniform friction stress,
 * tan(phi) times the pressure times |r| integrated, exactly; combined motions take the ellipse,
 * the standard approximation of a patch's limit surface (Goyal, Ruina and Papadopoulos 1991;
 * Howe and Cutkosky 1996). A trial pair outside is scaled back along its own direction. */
typedef struct rd_patch_spring {
    double fs[3]; /* shear force on the integration body, ground frame, N */
    double mt;    /* twisting moment on it about the normal u, N m */
    double area;  /* compressed area at the last step (0: open), m^2 */
    double polar; /* its polar moment about its centroid, m^4 */
} rd_patch_spring;

/* The springs follow a new compressed region (area, polar): where it shrank, fs and mt shrink
 * in proportion (the stress is kept: what left took its share, as the springs of a bed of
 * points do); where it grew they are kept (new material joins unstretched). Either way the
 * stored energy |fs|^2 / (2 KS A) + mt^2 / (2 KS J) can only fall, and what it loses is
 * returned, J (booked as friction: the joint drops it, as 3DEC drops an opening contact's
 * force). area 0: the patch opens and gives up all of it. */
static inline double rd_patch_spring_resize(rd_patch_spring *sp, double ks, double area,
                                            double polar)
{
    double e = 0;
    if (sp->area > 0) {
        double f2 = sp->fs[0] * sp->fs[0] + sp->fs[1] * sp->fs[1] + sp->fs[2] * sp->fs[2];
        double ra = area > 0 ? (area < sp->area ? area / sp->area : 1.0) : 0.0;
        e += f2 / (2 * ks * sp->area) - (area > 0 ? ra * ra * f2 / (2 * ks * area) : 0.0);
        for (int k = 0; k < 3; k++) sp->fs[k] *= ra;
        if (sp->polar > 0) {
            double rj = polar > 0 ? (polar < sp->polar ? polar / sp->polar : 1.0) : 0.0;
            e += sp->mt * sp->mt / (2 * ks * sp->polar) -
                 (polar > 0 ? rj * rj * sp->mt * sp->mt / (2 * ks * polar) : 0.0);
            sp->mt *= rj;
        } else {
            sp->mt = 0;
        }
    }
    sp->area = area;
    sp->polar = polar;
    return e > 0 ? e : 0.0;
}

/* The resize's share of the step's work, J, to add to the friction booked by
 * rd_patch_spring_resize. Leapfrog gives the bodies the mean of a force's values at the step's
 * two ends times the step's displacement: the springs of the last step, fp and mp (turned into
 * the new plane), at the start, not the resized f0 and m0 the trial is loaded from. The
 * displacement is the trial's load, -(fs - f0) / kA and -(mt - m0) / kJ (sp: the trial, before
 * the cap), so the springs' work is short of the bodies' by (fp - f0) . (fs - f0) / (2 kA) +
 * (mp - m0) (mt - m0) / (2 kJ). Booked at the step's end this was a first-order error: a soft
 * shear spring's region shrinking under a rocking block (the YADE overturn scene at 0.77 g,
 * KS 1e9 Pa/m) left residuals of 6.7e-3, 3.4e-3, 1.7e-3 at dt, dt/2, dt/4. */
static inline double rd_patch_resize_work(const rd_patch_spring *sp, const double fp[3], double mp,
                                          const double f0[3], double m0, double kA, double kJ)
{
    double e = 0;
    if (kA > 0)
        for (int k = 0; k < 3; k++) e += (fp[k] - f0[k]) * (sp->fs[k] - f0[k]) / (2 * kA);
    if (kJ > 0) e += (mp - m0) * (sp->mt - m0) / (2 * kJ);
    return e;
}

/* The Coulomb cap on the trial springs (fs, mt) of a patch, f0 and m0 their values before the
 * step's load, kA = KS A and kJ = KS J (N/m, N m/rad), flim and mlim the limits (N, N m). The
 * pair is scaled back by r onto the limit surface; each spring dissipates (1 - r) (x0 x_t +
 * r x_t^2) / (2 k) (the trapezoid work of the step less its energy change; engine/law.h
 * rd_law_shear_cap for one spring), added to *e_fric (J; never negative: slip gives no energy
 * back). Returns 1 on slip. */
/* (fs, mt) against the limit surface: (|fs| / flim)^2 + (mt / mlim)^2, infinite when a limit is
 * 0 and a spring is loaded. Never larger for a larger mlim: a lower bound of mlim that finds the
 * springs inside (<= 1) proves them inside, the twisting lever need not be computed. */
static inline double rd_patch_spring_s2(const rd_patch_spring *sp, double flim, double mlim)
{
    double ft2 = sp->fs[0] * sp->fs[0] + sp->fs[1] * sp->fs[1] + sp->fs[2] * sp->fs[2];
    if (flim > 0 && mlim > 0) return ft2 / (flim * flim) + sp->mt * sp->mt / (mlim * mlim);
    return (ft2 > 0 || sp->mt != 0) ? INFINITY : 0.0;
}

static inline int rd_patch_spring_cap(rd_patch_spring *sp, const double f0[3], double m0, double kA,
                                      double kJ, double flim, double mlim, double *e_fric)
{
    double ft2 = sp->fs[0] * sp->fs[0] + sp->fs[1] * sp->fs[1] + sp->fs[2] * sp->fs[2];
    double s2 = rd_patch_spring_s2(sp, flim, mlim);
    if (s2 <= 1) return 0;
    double r = isfinite(s2) ? 1 / sqrt(s2) : 0.0;
    double f0ft = f0[0] * sp->fs[0] + f0[1] * sp->fs[1] + f0[2] * sp->fs[2];
    double d = (1 - r) * (f0ft + r * ft2) / (2 * kA);
    if (kJ > 0) d += (1 - r) * (m0 * sp->mt + r * sp->mt * sp->mt) / (2 * kJ);
    *e_fric += d > 0 ? d : 0.0;
    for (int k = 0; k < 3; k++) sp->fs[k] *= r;
    sp->mt *= r;
    return 1;
}

/* ---- Bounding-volume hierarchy of a body's faces, in the body's frame (src/contact/bvh.c) ----
 * An axis-aligned box tree over items (a body's faces), built once: each node's box holds its
 * items' boxes; a leaf holds at most RD_BVH_LEAF items. Two bodies' trees are traversed
 * together under their relative pose, so a step's cost follows the boxes that overlap (the
 * touching patches), not the bodies' face counts. */
#define RD_BVH_LEAF 4

typedef struct rd_bvh {
    int nnode;
    double (*lo)[3], (*hi)[3]; /* node boxes, body frame, m */
    int *child;                /* first child (the second is child + 1), -1 for a leaf */
    int *first, *count;        /* a leaf's items: item[first .. first + count) */
    int *item;                 /* item indices, ordered by leaf */
} rd_bvh;

/* Builds the tree of n items of boxes lo[k] .. hi[k] (median split along the longest axis of
 * the items' centres). 0, or -1 when out of memory. */
int rd_bvh_build(rd_bvh *t, int n, const double (*lo)[3], const double (*hi)[3]);
void rd_bvh_free(rd_bvh *t);

/* A growable list of item pairs (a of the first tree, b of the second). */
typedef struct rd_bvh_pairs {
    int n, cap;
    int (*ab)[2];
} rd_bvh_pairs;

/* Every pair of leaf items of trees a and b whose boxes, grown by margin (m), overlap, b's
 * boxes carried into a's frame by x_a = rot x_b + tr (rot row-major). Appended to out. 0, or -1
 * when out of memory. */
int rd_bvh_overlaps(const rd_bvh *a, const rd_bvh *b, const double rot[9], const double tr[3],
                    double margin, rd_bvh_pairs *out);

/* The items of tree a whose boxes, carried into another frame by x' = rot x + tr (each node as
 * the box around its rotated box, so the looseness is a node's size times the rotation, small
 * at the leaves), meet the box lo .. hi of that frame grown by margin (m): appended to out as
 * (item, 0). A body's faces near a partner, tested in the partner's own frame, where its box is
 * tight. 0, or -1 when out of memory. */
int rd_bvh_query_carried(const rd_bvh *a, const double rot[9], const double tr[3],
                         const double lo[3], const double hi[3], double margin, rd_bvh_pairs *out);

#endif
