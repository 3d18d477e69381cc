/* rockdem — what `rockdem check` finds in a scene before it runs: the time step and its limit,
 * each body's mass, volume, tipping angle, subcontacts and what it rests on, the cost of a
 * simulated second, and the mistakes it can see (rd_check_scene). */
#ifndef ROCKDEM_CHECK_H
#define ROCKDEM_CHECK_H

#include "rockdem/api.h"
#include "rockdem/scenario.h"

typedef struct rd_check_body {
    char name[RD_NAME_MAX];
    char group[RD_NAME_MAX];
    int fixed;
    double mass;          /* kg */
    double volume;        /* m^3 */
    double alpha_min;     /* least static tipping angle over all lean directions, rad (free) */
    double alpha;         /* tipping angle about its base edges (least of +-x, +-y), rad (free) */
    int npoints;          /* its subcontact points */
    int rests_on;         /* index of the body it rests on as placed, -1: none */
    int below;            /* index of the nearest body under it, -1: nothing under it */
    double gap;           /* its lowest point above the top of `below`, m (< 0: inside it) */
    double overlap;       /* deepest overlap with another body as placed (a vertex of one inside the other), m */
    int overlaps;         /* index of the body it penetrates most, -1: none */
} rd_check_body;

typedef struct rd_check_report {
    int nbodies;
    rd_check_body *body;  /* [nbodies] (owned; rd_check_free) */
    int npoints;          /* subcontact points, all bodies */
    int njoints;          /* distinct joint property sets */
    double dt;            /* the step the run will use, s */
    double dt_critical;   /* its stability limit, s */
    double output_interval; /* s */
    double duration;      /* requested shaking time, s */
    double motion_end;    /* end of the ground motion, s (0: none) */
    int has_records;      /* 1 when the motion comes from records */
    double wall_per_sim_s;/* measured: wall seconds per simulated second (trial steps) */
    int trial_steps;      /* steps timed for it */
    int dt_body;          /* the body whose bound sets dt_critical (-1: none) */
    int dt_partner;       /* the most mobile body it may bear on (-1: fixed bodies only) */
} rd_check_report;

/* Build the scene (no output file), place it, time a few steps. 0, or -1 with err set. */
RD_API int rd_check_scene(const rd_scenario *sc, rd_check_report *rep, rd_error *err);
RD_API void rd_check_free(rd_check_report *rep);

#endif
