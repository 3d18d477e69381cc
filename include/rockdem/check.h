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
    double extent[3];     /* its bounding box in the ground frame as placed (x, y, z), m */
    double alpha_min;     /* least static tipping angle over all lean directions, rad (free) */
    double alpha;         /* tipping angle about its base edges (least of +-x, +-y), rad (free) */
    double alpha_shaking; /* tipping angle leaning along +- the horizontal pulse's direction
                             (x without a pulse), rad (free) */
    double alpha_tower;   /* the same for the body and every free body standing on it, tipping
                             as one about this body's base (its own alpha_shaking when nothing
                             stands on it), rad (free) */
    double p_tower;       /* frequency parameter sqrt(m g R / I_O) of that assembly rocking
                             about its pivot edge on the side of alpha_tower (I_O its moment of
                             inertia about the edge, R the distance to it): Housner's p for a
                             rigid body of this mass, R and pivot inertia, rad/s (free) */
    double R_tower;    /* that assembly's distance from its centre of mass to the pivot edge, m */
    double lean_tower; /* the direction it tips to first (the pulse's or the opposite), rad
                             from +x */
    int npoints;       /* its subcontact points */
    int rests_on;      /* index of the body it rests on as placed, -1: none */
    int below;         /* index of the nearest body under it, -1: nothing under it */
    double gap;        /* its lowest point above the top of `below`, m (< 0: inside it) */
    double
        overlap; /* deepest overlap with another body as placed (a vertex of one inside the other), m */
    int overlaps; /* index of the body it penetrates most, -1: none */
    /* the static sink at rest into the body it rests on (free, rests_on >= 0; check does not
       settle): its joint closes by W / (KN A) under the weight W of the body and every free body
       standing on it, on the area A of its support polygon as placed */
    double sink;      /* W / (KN A), m (0: no estimate: no support area) */
    double sink_load; /* W, N */
    double sink_area; /* A, m^2 */
    double sink_kn;   /* KN of the joint, Pa/m */
    int sink_above;   /* free bodies standing on it, whose weight W includes */
    double band;      /* the joint's contact band, RD_CONTACT_BAND of the smaller radius, m */
} rd_check_body;

typedef struct rd_check_report {
    int nbodies;
    rd_check_body *body;    /* [nbodies] (owned; rd_check_free) */
    int npoints;            /* subcontact points, all bodies */
    int njoints;            /* distinct joint property sets */
    double dt;              /* the step the run will use, s */
    double dt_critical;     /* its stability limit, s */
    double output_interval; /* s */
    double duration;        /* requested shaking time, s */
    double motion_end;      /* end of the ground motion, s (0: none) */
    int has_records;        /* 1 when the motion comes from records */
    double wall_per_sim_s;  /* measured: wall seconds per simulated second (trial steps) */
    int trial_steps;        /* steps timed for it */
    int coarse_probe;       /* 1: what each body touches was found from its own corner points, the
                             automatic bed used for it (check.c, touch_probe) being past the
                             point budget or memory */
    int dt_body;            /* the body whose bound sets dt_critical (-1: none) */
    int dt_partner;         /* the most mobile body it may bear on (-1: fixed bodies only) */
} rd_check_report;

/* Build the scene (no output file), place it, time a few steps. 0, or -1 with err set. */
RD_API int rd_check_scene(const rd_scenario *sc, rd_check_report *rep, rd_error *err);
RD_API void rd_check_free(rd_check_report *rep);

#endif
