/* rockdem (private) — convex polyhedra: vertices, polygonal faces with outward planes, a
 * triangulation, mass properties from the closed surface, and subcontact points (points on
 * faces with tributary areas). Coordinates are in the body frame: origin at the centre of
 * mass, axes along the principal axes of inertia.
 * Folder geometry/ owns solids, their mass properties, subcontact points and assembly builders;
 * it may call base/ only.
 */
#ifndef RD_GEOM_H
#define RD_GEOM_H

#include "rockdem/error.h"

typedef struct rd_poly {
    int nv;
    double (*v)[3]; /* vertices, m */
    int nf;
    int *fstart; /* face f uses fidx[fstart[f] .. fstart[f]+flen[f]-1], counter-clockwise seen
                         from outside */
    int *flen;
    int *fidx;
    double (*fn)[3]; /* outward unit normal of each face */
    double *fd;      /* plane offset: points x on face f satisfy fn[f].x = fd[f], m */
    int ntri;
    int (*tri)[3]; /* fan triangulation of the faces (for output and mass properties) */
    double radius; /* max vertex distance from the origin, m */
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
 * other faces are split into triangles from their centroid, refined, each point taking one
 * third of the area of the triangles around it (3DEC's rule); in vertex mode each vertex
 * takes half of the two centroid triangles beside it. The areas sum to the face area.
 * Writes at most `cap` points into xyz[][3] and area[]; returns the count, or -1 if cap is too
 * small (call with cap = 0 to learn the count). */
int rd_poly_face_points(const rd_poly *p, int f, double spacing, double (*xyz)[3], double *area,
                        int cap);

/* At least as many points as rd_poly_face_points makes on face f at this spacing, cheaply
 * (nothing is meshed), as a double: what a spacing far below the face's size would ask for. */
double rd_poly_face_points_bound(const rd_poly *p, int f, double spacing);

/* Area of face f, m^2. */
double rd_poly_face_area(const rd_poly *p, int f);

/* Allocate (zeroed) arrays for nv vertices and nf faces using nidx face-vertex indices in
 * total; the caller fills v, fstart, flen, fidx and calls rd_poly_update. 0 or -1. */
int rd_poly_alloc(rd_poly *p, int nv, int nf, int nidx, rd_error *err);

/* --- shapes.c: more solids, all closed with outward counter-clockwise polygonal faces --- */

/* Right prism or frustum with nsides >= 3 sides (a drum: a cylinder approximated by N sides,
 * optionally tapered). Axis along z, base (a regular n-gon of circumradius radius_bottom, m)
 * at z = -height/2, top (circumradius radius_top, m) at z = +height/2, first vertex of each
 * ring on +x; the centroid is at the origin only for a prism (call rd_poly_mass and
 * rd_poly_to_frame). Vertices 0..n-1 form the base ring, n..2n-1 the top ring; face 0 is the
 * base (one n-gon), face 1 the top, faces 2.. the quadrilateral sides. 0 or -1. */
int rd_poly_prism(rd_poly *p, int nsides, double radius_bottom, double radius_top, double height,
                  rd_error *err);

/* Convex hull of n >= 4 points pts[n][3] (m) by qhull, coplanar triangles merged into one
 * polygonal face; only hull vertices are kept. Fails on fewer than 4 or coplanar points. */
int rd_poly_hull(rd_poly *p, const double (*pts)[3], int n, rd_error *err);

/* Mark (on_hull[v] = 1) the vertices of p that are vertices of its convex hull (qhull; points
 * on a hull face are not). 0 or -1. */
int rd_poly_hull_marks(const rd_poly *p, char *on_hull, rd_error *err);

/* Is the closed, outward polyhedron p convex to within tol (m)? *convex = 1 when every edge is
 * convex (each face's far side lies behind its neighbour's plane across the edge, within tol)
 * and p fills its convex hull (qhull's volume, to tol times the hull's area): a closed surface
 * convex at every edge and embedded is the boundary of a convex body. O(n log n) (the edge sort
 * and qhull) where testing every vertex against every face plane was O(n^2): 85 s for a
 * 1M-triangle sphere. 0, or -1 with err (out of memory, qhull failed). */
int rd_poly_convex(const rd_poly *p, double tol, int *convex, rd_error *err);

/* Polyhedron from explicit faces: face f uses idx[face_start[f] .. + face_len[f] - 1], counter-
 * clockwise seen from outside. Checked by rd_poly_check (named "faces"). 0 or -1. */
int rd_poly_from_faces(rd_poly *p, const double (*v)[3], int nv, const int *face_start,
                       const int *face_len, const int *idx, int nf, rd_error *err);

/* Check a polyhedron (non-convex allowed): every vertex used; faces of >= 3 vertices, not
 * degenerate (area > 1e-12 L^2, L the bounding-box diagonal), planar (within 1e-6 L) and
 * convex; every edge shared by exactly two faces that traverse it in opposite directions
 * (closed, manifold, consistently oriented); positive volume (outward). Messages start with
 * `what` (a file name) and count faces and vertices from `base` (1 for OBJ, else 0). */
int rd_poly_check(const rd_poly *p, const char *what, int base, rd_error *err);
/* The same; *bad is the index (from 0) of the face the error is about, or -1 (a vertex, the
 * volume): readers turn it into the file's line. */
int rd_poly_check_at(const rd_poly *p, const char *what, int base, int *bad, rd_error *err);

/* --- mesh_io.c --- */

/* Read a closed triangle/polygon mesh from OBJ, PLY (ASCII or binary) or STL (ASCII or
 * binary), chosen by the file extension, in double precision. The bounding-box centre is
 * subtracted from every vertex (map coordinates ~1e6 m keep their precision) and returned in
 * offset (m; may be NULL): file coordinates = vertex + offset. STL vertices are merged by
 * exact coordinate match; unused vertices are dropped. The result passes rd_poly_check. */
int rd_mesh_read(rd_poly *p, const char *path, double offset[3], rd_error *err);
/* The closed solid of a height grid (geometry/terrain.c: .asc an ESRI ASCII grid, else gridded
 * XYZ points), as rd_mesh_read gives a mesh. */
int rd_terrain_read(rd_poly *p, const char *path, double offset[3], rd_error *err);

#endif
