/* rockdem (private) — the surface model's state (`contact model surface`; surface.c builds and
 * steps it, surface_state.c lists it for a checkpoint; docs/CONTACT.md section 8).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * contact/, geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#ifndef RD_SURFACE_H
#define RD_SURFACE_H

#include "engine/sim.h"
#include "engine/dashpot.h"
#include "contact/contact.h"

#include <stdint.h>

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
    double (*rect)[6];     /* per plane: the body-frame box (x, y, z min, then max; m) of the
                               corners of its coordinate box (keep_planes) */
    int *plane_of;         /* [nf] the plane of each face */
    int *plane_c0;         /* [nplane + 1] first cell of each plane (the convex path) */
    int *c2_0;             /* [ncell + 1] first vertex of cell c in c2 */
    double (*c2)[2];       /* the cells: each plane's faces merged into convex polygons
                               (rd_patch_cells), its coordinates, counter-clockwise */
    rd_bvh tree;           /* the faces' boxes, body frame (contact/bvh.c) */
    int *seen;             /* [nplane] stamp: plane taken this step (the convex path) */
    int *plane_key;        /* [nplane] the tree position of its first face (near_planes' order) */
} surf_body;

/* A pair's planes near the other body, kept with the pose they were found at (near_planes). */
typedef struct surf_near {
    double rot[9], tr[3]; /* i's frame into r's then */
    double box[6];        /* the box around the planes' coordinate boxes, i's frame (lo, hi), m */
    int *plane, n, cap;
    int valid;
} surf_near;

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
    rd_poly2 *ins; /* scratch: the parts of one plane's cells inside r */
    int cap_ins;
    double inbox[4];    /* their bounding box, the plane's coordinates (x, y min, x, y max), m */
    double (*pl)[4];    /* scratch: r's planes in the integration body's frame (u, d) */
    double (*uw)[3];    /* scratch: r's outward normals, ground frame */
    double (*dep)[3];   /* scratch: depth below each plane of r, affine in a plane's coords */
    int *hcut;          /* scratch: the planes of r that may cut a piece */
    int *keep, nkeep;   /* scratch: the planes of r that may reach this pair (keep_planes) */
    int *pkeep, npkeep; /* scratch: of those, the ones that may reach one plane of i */
    double *klo;        /* scratch: keep_over's depth bounds */
    double keep_m;      /* keep_over's margin for this pair, m */
    surf_near *near;    /* per pair (the convex path), its kept near planes */
    double ubox[6];     /* the present pair's surf_near.box */
    double (*qpl)[4];   /* mesh pairs: r's planes in i's frame (u, dR), found at the epoch of */
    unsigned *qstamp;   /* qstamp (plane_in) */
    unsigned qepoch;
    int cap_q;
    int cap_near;
    int front; /* the plane of r that last put a whole plane in front of it */
    int cap_pl;
    rd_patch_scratch tsc;   /* scratch of rd_patch_torsion_set */
    rd_bvh_pairs cand;      /* scratch: candidate faces, or face pairs, from the trees */
    int *pkey, cap_pkey;    /* scratch (mesh pairs): each piece's group, plane P and plane Q */
    struct mesh_side *side; /* scratch (mesh pairs): one face's candidates' regions */
    int cap_side;
    double (*hpl)[3]; /* scratch (mesh pairs): their sides' half-planes */
    int cap_hpl;
    int *cnt, cap_cnt; /* scratch (mesh pairs): the candidates' counting sort */
    int *ord, cap_ord; /* scratch: an ordering */
    int seen_stamp;    /* stamp of surf_body.seen */
    uint64_t *fkey;    /* mesh pairs: face pairs (pair, face of i, plane of r) that bore */
    long *fstamp;      /* the surface step each last bore */
    int nfk, fcap;     /* entries, capacity (a power of 2, 0 before the first) */
    rd_dashpots dp;    /* this step's patch dashpots, solved implicitly (dashpot.c) */
    surf_meas *meas;   /* per pair, its joint's measures at the last step it was live */
    int cap_meas;
    long stamp; /* surface steps taken */
};

#endif
