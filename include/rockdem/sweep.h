/* rockdem — parameter sweeps for fragility (`rockdem sweep`, docs/FRAGILITY.md).
 *
 * A plan is the cartesian product of its axes (records x scales x directions x --axis lists,
 * the last axis varying fastest); case k is one DEM run of the scenario with the base --set
 * overrides and then one value of every axis applied by rd_scenario_set on a fresh parse.
 * Workers (forked processes, or MPI ranks in bin/rockdem-mpi) run cases and send back one
 * fixed-size rd_sweep_result each; the coordinator appends it to the HDF5 table (/sweep).
 * The implementation is src/ensembles/sweep*.c; `rockdem sweep` (src/cli/cli_sweep.c) and
 * bin/rockdem-mpi drive it.
 */
#ifndef ROCKDEM_SWEEP_H
#define ROCKDEM_SWEEP_H

#include "rockdem/api.h"
#include "rockdem/rockdem.h"

#define RD_SWEEP_MAX_AXES 16
#define RD_SWEEP_TEXT     128 /* bytes of a text column value (record names, text axis values) */
#define RD_SWEEP_MSG      200 /* bytes of a case's error message */
/* Free bodies a sweep tabulates per case: a case's result travels as one fixed-size record
 * (pipe or MPI), so its per-body columns are arrays of this length (about 10 kB a result). */
#define RD_SWEEP_BODIES   256

typedef enum rd_axis_kind {
    RD_AXIS_SET = 0,   /* --axis section.key=v1,v2: rd_scenario_set("section.key=v") */
    RD_AXIS_RECORD,    /* --records: motion.file (path as given, relative to the current dir) */
    RD_AXIS_SCALE,     /* --scales: "0.3g" = target PGA, "2" = factor (see rd_sweep_assignment) */
    RD_AXIS_DIRECTION, /* --directions: motion.direction, degrees */
    RD_AXIS_INTERFACE  /* --axis interface=K: contact.interface-seed = 1..K */
} rd_axis_kind;

typedef struct rd_sweep_axis {
    rd_axis_kind kind;
    char key[RD_NAME_MAX]; /* column name: the --set key, or record, scale, direction, interface */
    int n;                 /* number of values (>= 1) */
    char **value;          /* the values as written (owned) */
    double *number;        /* numeric value of each (SI: scales in m/s^2 or factors); NULL for a
                              text axis (owned) */
    const char *units;     /* of the numeric column ("" if none) */
} rd_sweep_axis;

typedef struct rd_sweep_plan {
    const char *path; /* scenario file */
    char *text;       /* the scenario file as read (owned) */
    int nsets;
    char **sets; /* base --set assignments (argv strings) */
    int naxes;
    rd_sweep_axis axis[RD_SWEEP_MAX_AXES];
    long ncases;     /* product of the axis lengths */
    char *axes_text; /* canonical "key=v1,v2\n" per axis, then "--set a\n" (owned) */
    int nbodies;     /* free bodies */
    char body[RD_SWEEP_BODIES][RD_NAME_MAX];
    int nfences; /* fences of the scenario (`model fence`) */
    char fence[RD_MAX_FENCES][RD_NAME_MAX];
    int pulse;        /* 1: the scenario's horizontal motion is a pulse (no records) */
    double amplitude; /* the pulse's amplitude as parsed, m/s^2 (factor scales) */
    int perturbed;    /* 1: the scenario's interface perturbation removes, raises or scatters */
    int surface;      /* 1: the scenario's `contact model surface` (it has no points to perturb) */
    const char *keep_dir; /* --keep-runs DIR: each case's HDF5 file there; NULL: no file */
    int full;             /* --full: every case runs to its end (no quiet end: sc.quiet_stop 0) */
} rd_sweep_plan;

enum {
    RD_IM_PGA,
    RD_IM_PGV,
    RD_IM_PGD,
    RD_IM_PGV_PGA,
    RD_IM_ARIAS,
    RD_IM_D5_95,
    RD_IM_SA_0_2,
    RD_IM_SA_1,
    RD_SWEEP_NIM
};

/* Response mode of a free body in one run (docs/FRAGILITY.md "Response modes"), most severe
 * last; a run's mode is the most severe over its bodies. */
typedef enum rd_sweep_mode {
    RD_MODE_REST = 0,   /* neither rocked nor slid */
    RD_MODE_SLIDE,      /* joint slip >= RD_MODE_SLIP_MIN, no rocking (twist by slip included) */
    RD_MODE_ROCK,       /* uplifted and max tilt >= RD_MODE_TILT_MIN x alpha */
    RD_MODE_ROCK_SLIDE, /* rock and slide, twist below RD_MODE_TWIST_MIN */
    RD_MODE_ROCK_TWIST, /* rock with max |twist| >= RD_MODE_TWIST_MIN (slid or not) */
    RD_MODE_OVERTURN,   /* the overturn criterion was met */
    RD_MODE_COUNT
} rd_sweep_mode;

/* Thresholds of the modes (justified in docs/FRAGILITY.md). */
#define RD_MODE_TILT_MIN                                                                           \
    1e-3                       /* max tilt / alpha (with uplift): rocking; the brick of
                                  tests/cli/data/sweep_brick.dat reaches 5.4e-4 at 0.38 g, below its
                                  tipping 0.4 g, and 2.7e-3 at 0.42 g */
#define RD_MODE_SLIP_MIN  1e-3 /* m of joint slip: sliding (seed 002's mm displacement resolution) */
#define RD_MODE_TWIST_MIN 0.05 /* rad of max |twist|: rock-twist (2.9 deg) */

/* What one case found: sent through a pipe or MPI as raw bytes (a homogeneous machine set). */
typedef struct rd_sweep_result {
    long index;              /* case index */
    unsigned long long hash; /* rd_sweep_hash of the case */
    int status;              /* rd_status; -1: the case could not be set up (message) */
    char message[RD_SWEEP_MSG];
    double im[RD_SWEEP_NIM];  /* pga m/s^2, pgv m/s, pgd m, pgv/pga s, arias m/s, d5-95 s,
                                    5 %-damped Sa(0.2 s), Sa(1 s) m/s^2 */
    int overturned;           /* 1 if any free body overturned */
    double overturn_time;     /* first overturn, s (-1 if none) */
    double max_tilt_ratio;    /* max over bodies of max tilt / alpha */
    double max_slide;         /* max over bodies, m */
    double final_twist;       /* the largest |twist at the end| over bodies, signed, rad */
    double max_twist;         /* max over bodies of max |twist about the vertical|, rad */
    double max_slip;          /* max over joints of a free body of its joint slip, m */
    char mode[RD_SWEEP_TEXT]; /* rd_sweep_mode_name of the most severe body mode */
    double energy_residual;   /* max |balance residual| / energy scale */
    double end_time;          /* simulated time reached, s */
    double quiet_end;         /* the case ended here, at rest with the motion left unable to
                                 lift or slide it (rd_sim_quiet_end), s; -1: it did not */
    double wall_seconds;      /* wall time of the whole case (setup + run), s */
    int nbodies;
    int b_overturned[RD_SWEEP_BODIES];
    double b_overturn_time[RD_SWEEP_BODIES], b_max_tilt_ratio[RD_SWEEP_BODIES];
    double b_max_slide[RD_SWEEP_BODIES], b_final_twist[RD_SWEEP_BODIES];
    double b_max_twist[RD_SWEEP_BODIES], b_max_slip[RD_SWEEP_BODIES];
    int b_mode[RD_SWEEP_BODIES]; /* rd_sweep_mode */
    /* runout (docs/RUNOUT.md) */
    double runout;       /* largest runout (travel from rest) over the bodies, m */
    double fence_energy; /* largest kinetic energy at a crossing over the bodies and fences, J
                            (0: none crossed) */
    int at_rest;         /* `until rest`: 1 if the run ended at rest, 0 at its time limit */
    double b_runout[RD_SWEEP_BODIES], b_runout_direction[RD_SWEEP_BODIES];
    double b_max_speed[RD_SWEEP_BODIES], b_max_bounce[RD_SWEEP_BODIES];
    double b_max_energy[RD_SWEEP_BODIES];
    double b_fence_time[RD_SWEEP_BODIES], b_fence_energy[RD_SWEEP_BODIES]; /* the first fence */
    double b_fence_height[RD_SWEEP_BODIES];
    /* per fence, over the bodies: the largest kinetic energy at a first crossing (J; 0: none),
       the largest centre height above the surface there (m; -1: none), the bodies that crossed */
    double f_energy[RD_MAX_FENCES], f_height[RD_MAX_FENCES];
    int f_crossed[RD_MAX_FENCES];
} rd_sweep_result;

/* --- sweep_mode.c ---------------------------------------------------------------------------- */

/* Mode of one body from its summary and the largest slip of its joints (m). */
RD_API rd_sweep_mode rd_sweep_mode_of(const rd_body_summary *b, double max_slip);

/* "rest", "slide", "rock", "rock-slide", "rock-twist", "overturn". */
RD_API const char *rd_sweep_mode_name(rd_sweep_mode m);

/* --- sweep.c ----------------------------------------------------------------------------- */

/* Add an axis from "KEY=V1,V2,..." (--axis) or a list (kind RECORD, SCALE, DIRECTION). Prints
 * nothing; -1 with err = "rockdem sweep: ...". */
RD_API int rd_sweep_add_axis(rd_sweep_plan *p, rd_axis_kind kind, const char *spec, rd_error *err);

/* Read the scenario, check every axis value once on a fresh parse, count the cases, and make
 * axes_text. -1 with err. */
RD_API int rd_sweep_plan_finish(rd_sweep_plan *p, rd_error *err);

RD_API void rd_sweep_plan_free(rd_sweep_plan *p);

/* Value index of axis a in case k. */
RD_API int rd_sweep_value_index(const rd_sweep_plan *p, long k, int a);

/* FNV-1a 64 of the case's overrides as written (base --set, then "key=value" per axis). */
RD_API unsigned long long rd_sweep_hash(const rd_sweep_plan *p, long k);

/* Run case k (fresh scenario, overrides, DEM run; with keep_dir its HDF5 file is written there,
 * else no file at all). Always fills r (status -1 and message on a setup error). */
RD_API void rd_sweep_run_case(const rd_sweep_plan *p, long k, rd_sweep_result *r);

/* Ask the case running in this process to stop (async-signal-safe); later cases are skipped. */
RD_API void rd_sweep_request_stop(void);

/* --- sweep_pool.c: fork + pipes ------------------------------------------------------------ */

/* How the coordinator talks to its workers (fork pool, MPI). */
typedef struct rd_sweep_pool {
    int nworkers;
    void *ctx;
    int (*send)(void *ctx, int worker, long index); /* index -1: stop; 0 or -1 */
    /* Wait up to wait_ms for a result: 1 (r, *worker set), 0 (none yet), -1 (worker *worker
       died; its case is lost) */
    int (*recv)(void *ctx, int wait_ms, int *worker, rd_sweep_result *r);
    void (*interrupt)(void *ctx); /* pass Ctrl-C on to the workers */
    void (*finish)(void *ctx);    /* stop and reap the workers, free ctx */
} rd_sweep_pool;

/* Fork n workers. -1 with err. */
RD_API int rd_sweep_pool_fork(const rd_sweep_plan *p, int n, rd_sweep_pool *pool, rd_error *err);

/* --- sweep_table.c: the HDF5 table --------------------------------------------------------- */

typedef struct rd_sweep_table rd_sweep_table;

/* Create the table, or open an existing one for the same scenario and axes (done[k] = 1 for
 * cases already in it; done has ncases entries). NULL with err. */
RD_API rd_sweep_table *rd_sweep_table_open(const char *path, const rd_sweep_plan *p, char *done,
                                           rd_error *err);

/* Append one result row and flush the file. Atomic: the space is reserved first
 * (posix_fallocate), so a full disk or a file-size limit fails before anything is written and
 * the table keeps exactly its earlier rows. -1 with err (the file and the system's reason). */
RD_API int rd_sweep_table_append(rd_sweep_table *t, const rd_sweep_result *r, rd_error *err);

/* Rows on disk. */
RD_API long rd_sweep_table_rows(const rd_sweep_table *t);

/* Trailing rows found partially written when the table was opened (an append cut short by a
 * fault, e.g. a full disk, before this version made appends atomic); they were dropped and
 * their cases are run again. */
RD_API long rd_sweep_table_dropped(const rd_sweep_table *t);

/* Reorder the rows by case index (a complete sweep reads the same whatever -j). -1 with err. */
RD_API int rd_sweep_table_sort(rd_sweep_table *t, rd_error *err);

RD_API void rd_sweep_table_close(rd_sweep_table *t);

#endif
