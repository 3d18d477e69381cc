/* rockdem — distinct-element simulation of freestanding rigid blocks under ground motion.
 *
 * Usage (REBOUND-style: one simulation object, a status enum from the run call):
 *     rd_scenario sc; rd_error err;
 *     if (rd_scenario_load(&sc, "run.dat", &err)) { fprintf(stderr, "%s\n", err.msg); ... }
 *     rd_sim *sim = rd_sim_create(&sc, &err);
 *     rd_status st = rd_sim_run(sim);
 *     rd_sim_summary(sim, &summary);
 *     rd_sim_free(sim); rd_scenario_free(&sc);
 */
#ifndef ROCKDEM_H
#define ROCKDEM_H

#include "rockdem/api.h"
#include "rockdem/error.h"
#include "rockdem/scenario.h"
#include "rockdem/motion.h"

#define RD_VERSION "0.1.0"

typedef enum rd_status {
    RD_STATUS_DONE = 0,        /* ran for the requested duration */
    RD_STATUS_OVERTURNED = 1,  /* stopped early: every free body overturned (criterion met) */
    RD_STATUS_INTERRUPTED = 2, /* stopped by a signal (Ctrl-C); output holds everything so far */
    RD_STATUS_UNSTABLE = 3,    /* NaN/Inf or runaway velocity: stopped, cause in rd_sim_error() */
    RD_STATUS_IO_ERROR = 4,    /* the output file could not be written */
    RD_STATUS_ERROR = 5,       /* out of memory during the run: stopped, cause in rd_sim_error() */
    RD_STATUS_PENETRATED = 6,  /* a body passed into another (its centre of mass inside it: the
                                  contact is far too soft for the load); cause in rd_sim_error() */
    RD_STATUS_LOST = 7,        /* a body fell out of the scene (below the lowest fixed body by
                                  more than its own size); cause in rd_sim_error() */
    RD_STATUS_UNTRUSTED = 8    /* ran to the end, but the energy balance residual exceeded
                                  RD_ENERGY_TRUST: the answer is not to be trusted (smaller step,
                                  stiffer or differently discretised contact), cause in
                                  rd_sim_error() */
} rd_status;

/* Largest energy-balance residual (fraction of the run's energy scale) a trusted run may
 * reach. Rocking amplitudes follow energy (0.5 I w^2 against m g R (1 - cos)), so a balance
 * error of 1 % moves amplitudes by about 1 %: a third of the 3 % the validation ladder asks of
 * the DEM against rigid theory. */
#define RD_ENERGY_TRUST 1e-2

/* "done", "overturned", "interrupted", "unstable", "io_error", "error", "untrusted". */
RD_API const char *rd_status_name(rd_status st);

/* A status that means the run's answer is not an outcome (unstable, I/O or memory error,
 * untrusted energy balance): ensembles count such runs as errors. */
RD_API int rd_status_failed(rd_status st);

/* A body's crossings of one fence (docs/RUNOUT.md): its centre's plan path against the fence's
 * polyline, the first crossing interpolated within its step. */
typedef struct rd_fence_hit {
    int crossings;   /* times the centre's plan path crossed the fence line */
    double time;     /* s of the first crossing (-1: none) */
    double energy;   /* kinetic energy at it, translation and rotation, J */
    double speed;    /* speed of the centre at it, m/s */
    double height;   /* height of the centre above the fixed surface below it, m (-1: no
                        crossing; NaN: no surface below it there) */
    double point[3]; /* where the centre crossed, m */
} rd_fence_hit;

/* What a run found, per free body and overall (written as HDF5 summary attributes). */
typedef struct rd_body_summary {
    char name[RD_NAME_MAX];
    int overturned;       /* 1 if the overturn criterion was met */
    double overturn_time; /* s, -1 if never */
    double max_tilt;      /* max angle between the body's initial and current vertical axis, rad */
    double alpha;         /* static tipping angle about its base edge (least of +-x, +-y), rad */
    double alpha_min;     /* least static tipping angle over all lean directions, rad */
    double alpha_min_direction; /* lean direction of alpha_min, rad from +x */
    double tip_accel_min;       /* quasi-static tipping acceleration g tan(alpha_min), m/s^2 */
    double max_tilt_ratio;      /* max_tilt / alpha */
    double max_slide;       /* max horizontal displacement of the base centre from its start, m */
    double final_slide;     /* same, at the end, m */
    int uplifted;           /* 1 if the body ever lost contact over part of its base */
    int slid;               /* 1 if the body slid as a whole (every active subcontact slipping) */
    double max_rocking_in;  /* max |in-plane rocking| (about the axis normal to the motion), rad */
    double max_rocking_out; /* max |out-of-plane rocking| (about the motion direction), rad */
    double max_twist;       /* max |twist about the vertical|, rad */
    double final_twist;     /* twist at the end (residual), rad */
    int unsupported;        /* 1 if it touched nothing at rest or during the run: it fell freely */
    double final_position[3]; /* centre of mass at the end, ground frame, m */
    double travel;            /* horizontal distance of the centre of mass from its rest position at
                              the end, m (where an overturned or falling body ended up) */
    double drop; /* fall of the centre of mass from where it was placed to the end, m */
    /* runout (docs/RUNOUT.md): the centre of mass's path after rest, ground frame */
    double runout_direction;    /* direction of the travel (the runout), rad from +x (0: none) */
    double path_length;         /* length of the centre's path, m */
    double max_speed;           /* largest speed of the centre relative to the ground, m/s */
    double max_energy;          /* largest kinetic energy, translation and rotation, J */
    double max_bounce;          /* largest gap between the body and the fixed surface below
                                   it (its lowest hull vertex's clearance), m */
    double final_quaternion[4]; /* orientation at the end, body to ground frame (w, x, y, z) */
    double left_time;           /* s the centre left the domain box (-1: never, or no box) */
    int nfences;                /* fences of the scenario (rd_runout_def.fence) */
    rd_fence_hit fence[RD_MAX_FENCES]; /* the body at each, in the scenario's order */
} rd_body_summary;

/* What one joint (pair of bodies that came into contact) had and did. */
typedef struct rd_joint_summary {
    char a[RD_NAME_MAX], b[RD_NAME_MAX]; /* its two bodies */
    double kn, ks;                       /* Pa/m */
    double friction;                     /* rad */
    double cohesion, tension;            /* Pa */
    double damping;                      /* viscous ratio of its normal dashpot */
    int closed;                          /* 1 if it carried load while shaking */
    double max_opening; /* largest opening while shaking beyond the gaps it had when it first
                             closed and beyond its springs' static compression (0: it never
                             opened), every step, m */
    double max_slip;    /* largest relative slip of b against a at the joint's centre of
                             pressure (not a body's sway), every step, m */
    double final_slip;  /* slip at the end, m */
} rd_joint_summary;

/* What a run found. body[] is borrowed, as rd_sim_events' array is: it points into the
 * simulation that filled the summary and is valid until rd_sim_free (copy what must outlive it;
 * rd_sim_body_summary copies one body). */
typedef struct rd_summary {
    int nbodies;                 /* free bodies, all of them (output order) */
    const rd_body_summary *body; /* [nbodies] */
    int any_overturned;
    double end_time;            /* simulated time reached, s */
    double dt;                  /* time step used, s */
    double dt_critical;         /* estimated critical step, s */
    long steps;                 /* steps taken in the shaking stage */
    double settle_time;         /* simulated settling time, s */
    double energy_residual_max; /* max |balance residual| / energy scale */
    double wall_seconds;        /* wall-clock time of the shaking stage, s */
    int at_rest;                /* `model solve until rest`: 1 if the run ended with every body
                                   at rest or out of the domain, 0 at the time limit */
    rd_status status;
} rd_summary;

/* Something that happened during the run (also written to /events in the HDF5 file). */
typedef struct rd_event {
    double time;   /* s */
    int body;      /* index among the free bodies (output order), -1 for the whole scene */
    char type[16]; /* uplift, impact, peak, slip, overturn, recover, unstable, unsettled */
    double value;  /* uplift/overturn/recover: tilt (rad); impact: angular speed before (rad/s);
                      peak: rocking amplitude of the half-cycle that ended in the impact (rad);
                      slip: slide so far (m); unsettled: force ratio reached */
} rd_event;

typedef struct rd_sim rd_sim;

/* Most steps a run may take unless forced (`model solve ... force on`, rockdem run --force):
 * 1e9 steps is hours to days of wall time even for one block; beyond it a scene is almost
 * always mis-specified (a stiffness or a time in the wrong unit). */
#define RD_STEP_BUDGET 1e9

/* Most subcontact points a scene may create (all bodies): a scene is refused, before its faces
 * are meshed, when its points would exceed it. The shipped scenes and tests use at most 4307
 * (scenarios/column.dat); 1e6 points (a 0.4 m square base at spacing 0.4 mm) cost about 20 ms
 * a step (45 min per simulated second at dt 7.4e-6 s) and 200 MB, and past them a spacing is
 * almost always in the wrong unit. */
#define RD_POINT_BUDGET 1e6

/* What rd_sim_check found. */
typedef struct rd_check_info {
    double dt;          /* the time step the run would take, s */
    double dt_critical; /* its stable limit, s */
    double steps;       /* estimated steps: (settle max time + duration + tail) / dt */
    int npoints;        /* subcontact points */
} rd_check_info;

/* Everything rd_sim_create checks, without writing: meshes read and checked, bodies seated,
 * subcontact points and their perturbation built, the time step and the step count against
 * RD_STEP_BUDGET; and, for the run file rd_sim_write_hdf5 would write, that it can be created
 * (its folder exists and is writable). info may be NULL. 0, or -1 with err ("file:line: ..."
 * where a line applies). */
RD_API int rd_sim_check(const rd_scenario *sc, rd_check_info *info, rd_error *err);

/* Build the simulation (geometry, subcontact points, time step; the state of `model restore`,
 * or the observer that writes `model save`'s checkpoint). It opens no run file: that is
 * rd_sim_write_hdf5's (rockdem/output.h). NULL on error. */
RD_API rd_sim *rd_sim_create(const rd_scenario *sc, rd_error *err);

/* Settle (if asked), then shake for the scenario's duration. The engine writes no file: its
 * observers are told at the start, at each output sample and at the end (the run file's writer,
 * rd_sim_write_hdf5 of rockdem/output.h, is one of them; rockdem/observer.h). */
RD_API rd_status rd_sim_run(rd_sim *sim);

/* rd_sim_run in three stages, for a caller that steps a run itself (the Python binding's
 * step(n) and run_until(t)): rd_sim_start settles (or restores) the scene, begins the observers
 * and applies the initial conditions; rd_sim_advance takes shaking steps until nsteps are taken
 * (nsteps < 0: no count), the time reaches t_until (s since the start of shaking; INFINITY: no
 * time) or the run is over (its duration, a stop, every body overturned, a failure, rest in the
 * tail); rd_sim_finish summarises and ends the observers (the file is complete), once, at any
 * stage (an unstarted run is started first; one finished while shaking could go on is INTERRUPTED).
 * rd_sim_start and rd_sim_advance return 1 while shaking can go on, 0 once it is over. */
RD_API int rd_sim_start(rd_sim *sim);
RD_API int rd_sim_advance(rd_sim *sim, long nsteps, double t_until);
RD_API rd_status rd_sim_finish(rd_sim *sim);

/* Simulated time since the start of shaking (s), and the time the shaking stage ends at (s;
 * NaN before rd_sim_start). */
RD_API double rd_sim_time(const rd_sim *sim);
RD_API double rd_sim_end_time(const rd_sim *sim);

/* Time at which a run with sc.quiet_stop ended because every free body was at rest and the
 * motion left could no longer lift or slide it, s; -1 when it did not end so. */
RD_API double rd_sim_quiet_end(const rd_sim *sim);

/* Fill the summary (valid after rd_sim_run, also after an early stop; out->body borrowed). */
RD_API void rd_sim_summary(const rd_sim *sim, rd_summary *out);

/* What the run found for free body k (0 <= k < rd_sim_body_count), any scene size. */
RD_API void rd_sim_body_summary(const rd_sim *sim, int k, rd_body_summary *out);

/* The message for an UNSTABLE or IO_ERROR status ("" otherwise). */
RD_API const char *rd_sim_error(const rd_sim *sim);

/* Ask every running simulation of the process to stop at its next step (async-signal-safe: the
 * one call a signal handler may make). rd_sim_run clears it when it starts. */
RD_API void rd_sim_request_stop(void);

/* Ask this simulation to stop at its next step; rd_sim_run then returns RD_STATUS_INTERRUPTED
 * (RD_STATUS_INTERRUPTED at once if called before rd_sim_run). Safe from another thread and
 * from an observer's callback; other simulations run on. */
RD_API void rd_sim_stop(rd_sim *sim);

/* Progress of running simulations, for a progress bar: fn(ctx, t, t_end) is called by
 * rd_sim_run every RD_PROGRESS_STEPS steps of the shaking stage and once when it ends, with the
 * simulated time reached and the time the run ends at (s). One callback for the process, so the
 * ensembles (threshold, restitution, study) report every run they make; NULL turns it off. */
#define RD_PROGRESS_STEPS 2048
typedef void (*rd_progress_fn)(void *ctx, double t, double t_end);
RD_API void rd_set_progress(rd_progress_fn fn, void *ctx);
/* Pass (t, t_end) to the process's callback, as rd_sim_run does: for an ensemble that runs its
 * simulations in worker processes and relays their progress (threshold -j). A callback counts a
 * new run where t falls back. */
RD_API void rd_progress_report(double t, double t_end);

/* Events so far (n receives the count); valid until the next run call or rd_sim_free. */
RD_API const rd_event *rd_sim_events(const rd_sim *sim, int *n);

/* State of free body k (output order): centre of mass x (m), orientation q (w,x,y,z),
 * velocity v (m/s) and angular velocity w (rad/s), ground frame. Any pointer may be NULL. */
RD_API void rd_sim_body_state(const rd_sim *sim, int k, double x[3], double q[4], double v[3],
                              double w[3]);

/* Energies of the last step, J, in the order kinetic, gravitational, elastic, friction,
 * damping, ground_work, residual. */
RD_API void rd_sim_energy(const rd_sim *sim, double e[7]);

/* Number of subcontact points (all bodies) and the time step in use (s). */
RD_API int rd_sim_point_count(const rd_sim *sim);
RD_API double rd_sim_dt(const rd_sim *sim);

/* Sum over the shaking steps of the active subcontacts (for ns per subcontact-step). */
RD_API long rd_sim_active_point_steps(const rd_sim *sim);

/* The most threads one step of the run has run on so far (1: every step serial): the run asks
 * for rd_scenario.threads (or OMP_NUM_THREADS), and a step uses them where the scene has enough
 * pairs or bodies to share out (engine/workers.c). The results are the same for any count. */
RD_API int rd_sim_threads(const rd_sim *sim);

/* Joints (pairs of bodies that came near each other) and what each did; k < count. */
RD_API int rd_sim_joint_count(const rd_sim *sim);
RD_API void rd_sim_joint(const rd_sim *sim, int k, rd_joint_summary *out);

RD_API void rd_sim_free(rd_sim *sim);

#endif
