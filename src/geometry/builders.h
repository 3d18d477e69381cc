/* rockdem (private) — assembly builders: the member shapes of a multi-block assembly (a classical
 * column, a statue on its pedestal), bottom to top, each seated on the one below. The scenario
 * commands `block create column|stack` read the keywords and add the members.
 *
 * Folder geometry/: solids (polyhedra, prisms, hulls, meshes), their mass properties and
 * subcontact points, perturbations and assemblies; it may call base/ only.
 */
#ifndef RD_BUILDERS_H
#define RD_BUILDERS_H

#include "rockdem/scenario.h"

/* A classical column (`block create column`): a square plinth (brick, skipped when
 * plinth[0] = 0), `drums` prisms whose radius shrinks linearly from diameter/2 to
 * taper diameter/2 up the shaft, an echinus capital (a frustum widening by
 * RD_CAPITAL_FLARE, skipped when capital = 0) and a square abacus (skipped when abacus[0] = 0). */
typedef struct rd_column_spec {
    int drums, sides; /* number of drums (>= 1), sides of each drum's polygon (>= 3) */
    double diameter;  /* shaft diameter at the base, m */
    double height;    /* height of one drum, m */
    double taper;     /* top-to-base diameter ratio of the shaft, (0, 1] */
    double plinth[2]; /* plinth width and height, m */
    double capital;   /* capital height, m */
    double abacus[2]; /* abacus width and height, m */
} rd_column_spec;

/* The largest number of members a column can have: plinth, drums, capital, abacus. */
int rd_column_members(const rd_column_spec *c);

/* Fills out[0 ..) with the column's members bottom to top (shape and dimensions only) and
 * suffix[k] with each one's name suffix (plinth, d1 .. dN, capital, abacus); returns the count
 * (at most rd_column_members(c)). */
int rd_build_column(const rd_column_spec *c, rd_body_def *out, char (*suffix)[16]);

/* A two-brick stack (`block create stack`): out[0] the lower block (suffix "lower"), out[1] the
 * upper one ("upper"), edge lengths in m. */
void rd_build_stack(const double lower[3], const double upper[3], rd_body_def out[2],
                    char suffix[2][16]);

#endif
