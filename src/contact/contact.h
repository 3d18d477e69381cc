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

#define RD_PATCH_MAX 72 /* most vertices of a patch polygon: a face of a convex body has at most
                           RD_MAX_PLANES - 2 = 128 edges, but the patch of two faces has at most
                           the sum of their edges; callers clip by faces of at most 64 + 4 (a
                           128-sided drum's caps are split in two by the caller) */

/* A convex polygon in a plane's coordinates, counter-clockwise, m. */
typedef struct rd_poly2 {
    int n;
    double p[RD_PATCH_MAX][2];
} rd_poly2;

/* Area moments of a polygon, m^2 .. m^4: integrals of 1, x, y, x^2, x y, y^2 over it. */
typedef struct rd_moments {
    double a, sx, sy, sxx, sxy, syy;
} rd_moments;

/* What the pressure KN d of an affine depth d = d0 + gx x + gy y does over a patch, per unit KN
 * (the caller multiplies by KN): the compressed region (d > 0) only. */
typedef struct rd_patch_load {
    double area;      /* compressed area, m^2 */
    double cx, cy;    /* its centroid, m (0, 0 when area is 0) */
    double polar;     /* its polar moment about the centroid, integral of |r - c|^2, m^4 */
    double f;         /* integral of d, m^3 (the normal force / KN) */
    double mx, my;    /* integrals of x d and y d, m^4 (the force's moments / KN) */
    double e2;        /* integral of d^2, m^4 (twice the spring energy / KN) */
    double tors;      /* integral of d |r - c|, m^4, c the centroid (the twisting friction's
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

/* The load of the affine depth d0 + gx x + gy y over patch p: p clipped by d > 0 (into *comp
 * when comp is not NULL), then its moments (rd_patch_load; its torsion about its own centroid).
 * Every field but tors is additive over pieces of a patch; tors is about the piece's own
 * centroid, so the pieces of one plane (a face cut into triangles) take rd_patch_torsion about
 * their common centroid instead. */
void rd_patch_load_of(const rd_poly2 *p, double d0, double gx, double gy, rd_patch_load *out, rd_poly2 *comp);

/* The patch of face S against face R, in S's plane frame: origin o, axes e1, e2 and outward
 * normal n = e1 x e2 (unit), S's polygon s (counter-clockwise about n, in that frame); R's nr
 * vertices rv (ground frame, counter-clockwise about its outward normal u) and its plane
 * u . q = dR. R is projected along u onto S's plane and clipped against s. Fills the patch
 * polygon and the depth's affine coefficients (d0, gx, gy: d = d0 + gx x + gy y, m). Returns the
 * patch's vertex count (0: no overlap, or faces that do not face each other, n . u >= 0). */
int rd_patch_faces(const double o[3], const double e1[3], const double e2[3], const double n[3], const rd_poly2 *s,
                   const double (*rv)[3], int nr, const double u[3], double dR, rd_poly2 *patch, double dep[3]);

#endif
