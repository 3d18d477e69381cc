/* rockdem (private) — convex polyhedra: vertices, polygonal faces with outward planes, a
 * triangulation, mass properties from the closed surface, and subcontact points (points on
 * faces with tributary areas). Coordinates are in the body frame: origin at the centre of
 * mass, axes along the principal axes of inertia. */
#ifndef RD_GEOM_H
#define RD_GEOM_H

#include "rockdem/error.h"

typedef struct rd_poly {
    int nv;
    double (*v)[3];   /* vertices, m */
    int nf;
    int *fstart;      /* face f uses fidx[fstart[f] .. fstart[f]+flen[f]-1], counter-clockwise seen
                         from outside */
    int *flen;
    int *fidx;
    double (*fn)[3];  /* outward unit normal of each face */
    double *fd;       /* plane offset: points x on face f satisfy fn[f].x = fd[f], m */
    int ntri;
    int (*tri)[3];    /* fan triangulation of the faces (for output and mass properties) */
    double radius;    /* max vertex distance from the origin, m */
} rd_poly;

/* Mass properties of a closed polyhedron of uniform density (divergence theorem). */
typedef struct rd_mass {
    double volume;       /* m^3 */
    double centroid[3];  /* in the frame the polyhedron was given in, m */
    double inertia[9];   /* inertia tensor per unit density about the centroid, m^5 (row-major) */
    double principal[3]; /* principal moments per unit density, ascending, m^5 */
    double axes[9];      /* rotation matrix whose columns are the principal axes (det +1) */
} rd_mass;

/* Brick with edge lengths size[0..2], centred at the origin. 0 or -1. */
int rd_poly_brick(rd_poly *p, const double size[3], rd_error *err);

/* Volume, centroid, inertia tensor, principal axes (GSL eigen solver). 0 or -1. */
int rd_poly_mass(const rd_poly *p, rd_mass *m, rd_error *err);

/* Move the polyhedron into its principal frame: x' = axes^T (x - centroid); recompute planes. */
void rd_poly_to_frame(rd_poly *p, const rd_mass *m);

/* Recompute face planes, triangulation and radius from vertices and faces. */
void rd_poly_update(rd_poly *p);

void rd_poly_free(rd_poly *p);

/* Subcontact points on face f: spacing <= 0 gives the face's own vertices (3DEC's fewest-
 * triangle default); spacing > 0 refines the face so no edge exceeds it. Parallelogram faces
 * get a structured grid whose nodes take a quarter of each cell around them (symmetric);
 * other faces subdivide their fan triangles and each point takes one third of the area of
 * the triangles around it (3DEC's rule). Either way the areas sum to the face area.
 * Writes at most `cap` points into xyz[][3] and area[]; returns the count, or -1 if cap is too
 * small (call with cap = 0 to learn the count). */
int rd_poly_face_points(const rd_poly *p, int f, double spacing, double (*xyz)[3], double *area, int cap);

/* Area of face f, m^2. */
double rd_poly_face_area(const rd_poly *p, int f);

#endif
