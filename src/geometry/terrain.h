/* rockdem — terrain from a height grid (terrain.c, docs/RUNOUT.md). */
#ifndef RD_GEOMETRY_TERRAIN_H
#define RD_GEOMETRY_TERRAIN_H

#include "rockdem/error.h"

/* Heights on a rectilinear grid: z[j nx + i] at (x[i], y[j]), x and y increasing, m. */
typedef struct rd_grid {
    int nx, ny;
    double *x, *y, *z;
} rd_grid;

/* A closed triangle mesh (counter-clockwise seen from outside). */
typedef struct rd_grid_mesh {
    int nv, ntri;
    double (*v)[3];
    int (*tri)[3];
} rd_grid_mesh;

/* Read path's text buf: .asc an ESRI ASCII grid, else gridded XYZ points. 0 or -1 (err:
 * "path:line: ..."). */
int rd_grid_read(const char *path, const char *buf, rd_grid *g, rd_error *err);
void rd_grid_free(rd_grid *g);
/* The grid as a closed solid: surface, side walls, flat base one (smallest) cell below its
 * lowest point. 0 or -1. */
int rd_grid_solid(const rd_grid *g, rd_grid_mesh *m, rd_error *err);
void rd_grid_mesh_free(rd_grid_mesh *m);

#endif
