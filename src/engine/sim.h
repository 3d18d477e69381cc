/* rockdem (private) — the simulation object. One struct, every field commented (REBOUND
 * style); per-body and per-point data are flat arrays (structs of arrays) indexed by body or
 * point, so the contact loop streams through memory and never allocates.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#ifndef RD_SIM_H
#define RD_SIM_H

#include "rockdem/observer.h"
#include "rockdem/rockdem.h"
#include "engine/state.h"
#include "records/motion_axes.h"
#include "geometry/geom.h"

#include <signal.h>
#include <stdatomic.h>
#include <stdint.h>

/* The step's hot functions (contact.c: side_step, with the laws it inlines, subcontact and
 * vertex_distances; integrate.c: body_geometry and transform_points) are compiled twice, for the
 * build's target (the Makefile's x86-64-v2) and with AVX2, and the AVX2 copy runs where the CPU
 * has it (a GNU ifunc, chosen once at load; GCC 6+ with glibc on x86-64). AVX2 without FMA: each
 * operation is the x86-64-v2 copy's on the same operands in the same order (VEX's three-operand
 * forms need no register copies, and the distance and transform loops run four lanes, not two),
 * so both copies give the same bits on every machine (tests/cli/determinism.sh). Static
 * functions only, so the copies stay private to their file. Clang (14 exports its resolvers from
 * the shared library: tests/cli/symbols.sh), other systems and -DRD_NO_CLONES build the one
 * copy. */
#if defined(__x86_64__) && defined(__GLIBC__) && defined(__GNUC__) && !defined(__clang__) &&       \
    __GNUC__ >= 6 && !defined(RD_NO_CLONES)
#define RD_HOT __attribute__((target_clones("avx2", "default")))
#else
#define RD_HOT
#endif

#define RD_EDGE_SLOTS                                                                              \
    2 /* spring slots per edge subcontact: its deepest point, or the two ends of
                           its part inside the other body (edge.c) */
#define RD_FAR_WORDS                                                                               \
    3 /* 64-bit words of rd_side.far: a fixed body's planes past the first 64 RD_FAR_WORDS are
         measured at every step (contact.c) */
#define RD_NPREC 72 /* directions of the precariousness table (every 5 degrees) */
#define RD_SUPPORT_BAND                                                                            \
    1e-3 /* m: vertices this close to a body's lowest point form its base (support polygon) */
/* Contact band as a fraction of the smaller body's bounding radius (3DEC keeps a contact while
 * its gap is below a tolerance of the order of 0.1 % of the model's dimension) (contact.c, joint.c). */
#define RD_CONTACT_BAND 1e-3
/* Two faces lie on each other within this distance per metre of (1 m + the body's radius) (setup.c:
 * which faces carry a bed; pairs.c: which side of a joint covers it). */
#define RD_FACE_TOL     1e-6
#define RD_ANTIPARALLEL                                                                            \
    0.999 /* two faces whose normals' dot product is below minus this face each other */
#define RD_ESCAPE_EVERY                                                                            \
    64 /* steps between checks that no body passed into another or left, at most
                              (power of 2); fewer where bodies move fast (rd_sim.escape_reach) */

/* Per-subcontact state bits (rd_sim.pstate). */
enum {
    RD_PT_ACTIVE = 1,  /* carries force this step */
    RD_PT_BONDED = 2,  /* cohesion and tension intact */
    RD_PT_SLIP = 4,    /* at the Coulomb limit this step */
    RD_PT_INSIDE = 8,  /* inside the other body; rd_sim.pface holds its entrance face */
    RD_PT_VIRGIN = 16, /* new contact not yet unloaded: the impact loss is still to come */
    RD_PT_STRUCK = 32, /* bearing, and pressed while one of its bodies takes a new impact: the
                          impact loss is still to come (contact.c) */
    RD_PT_IMPACT = 64  /* with RD_PT_VIRGIN: the touch was an impact, not a settling (contact.c) */
};

/* The resolved properties of one joint (joint.c): the default or a per-range override. Pairs
 * with equal properties share one entry of rd_sim.joint. */
typedef struct rd_joint {
    double kn, ks;      /* normal and shear stiffness per unit area, Pa/m */
    double friction;    /* rad */
    double tan_phi;     /* tan(friction) */
    double cohesion;    /* Pa */
    double tension;     /* Pa */
    double damping;     /* viscous ratio of the normal dashpot (0 = none) */
    double restitution; /* impact loss of a subcontact, [0, 1] (contact.c) */
} rd_joint;

/* Joint measures of one pair at one instant (joint.c: rd_joint_measure). */
typedef struct rd_joint_state {
    double fn;      /* normal force (compression), N */
    double fs[3];   /* shear force on the pair's second body, ground frame, N */
    double area;    /* active contact area, m^2 */
    double cop[3];  /* centre of pressure, ground frame, m (the pair's midpoint when no load) */
    double opening; /* largest gap among its evaluated subcontacts (>= 0), m */
    double slip[3]; /* relative tangential displacement of the second body at the joint's
                          reference point, elastic shear removed, m */
} rd_joint_state;

/* One side of a contact pair: the owner's subcontact points tested against the other body's
 * surface. Contact history is keyed by (pair, side, point index on the owner): a stable key,
 * because subcontact points are fixed on their body for the whole run. */
typedef struct rd_side {
    int owner, other; /* body indices */
    double weight;    /* 1, or 1/2 when both bodies carry points (3DEC averaging of both sets) */
    int state0;       /* index of the owner's first point in rd_sim.fs / rd_sim.pstate */
    int face0;        /* index of the owner's first candidate face in rd_sim.face_nactive */
    int edge0, nedge; /* the other body's edges as edge subcontacts (edge.c): first slot in
                         rd_sim.efs / edepth / eon, count (0: none) */
    double edge_area; /* tributary area of an edge subcontact: the owner's mean point area, m^2 */
    uint64_t far[RD_FAR_WORDS]; /* planes of a fixed other body that the owner's candidate
                                    vertices clear (contact.c: vertex_distances skips them) */
    double far_clear;           /* their least clearance below reach when measured, m (0: none) */
    double far_pose[7];         /* the owner's position and quaternion then */
    uint64_t edges_clear;       /* the owner's box build (rd_sim.box_builds) + 1 at which every
                                    edge of a fixed other body lay beyond one side of the owner's
                                    loose box (edge.c skips the side while it stands); 0: none */
} rd_side;

/* A pair of bodies that may touch: one or two sides, each the points of one body tested
 * against the other (contact.c). */
typedef struct rd_pair {
    int a, b;  /* body indices, a < b */
    int nside; /* 1 (one body carries points) or 2 */
    rd_side side[2];
    double m_eff;       /* reduced mass of the pair, kg (for viscous damping) */
    long seen;          /* broad-phase stamp of the last step its boxes overlapped */
    double k_active;    /* sum of KN*A over points active last step, N/m (viscous damping) */
    int joint;          /* index of its properties in rd_sim.joint */
    double n[3];        /* the joint's normal, unit, from a towards b: its subcontacts' normals
                          weighted by their normal forces (the last loaded step's) */
    int ref_set;        /* 1 while the joint carried load at its last measure */
    double ref[2][3];   /* its centre of pressure then, in the frames of a and b, m */
    double slip_acc[3]; /* accumulated tangential displacement of b against a at the centre of
                          pressure while loaded (elastic shear included), m */
    double open_max;    /* largest opening while shaking beyond its gaps when it first closed
                          (open_rest), every step, m; 0 while it never opened */
    double open_rest;   /* its largest gap when it first closed while shaking (a seated mesh's
                          base has gaps where it does not touch), m */
    double comp_rest;   /* its springs' mean static compression then, fn / (KN A), m: an opening
                          below it is the springs' breathing, not the joint opening */
    int rest_set;       /* 1 once open_rest and comp_rest are set */
    double slip_max;    /* largest |slip| while shaking, every step, m */
    double slip_end[3]; /* slip at the last step, m */
    int closed;         /* 1 if the joint ever carried load while shaking */
} rd_pair;

/* Monitoring state of one free body (events, overturning, summary). */
typedef struct rd_watch {
    double q_ref[4];       /* orientation at rest (after settling, before initial conditions) */
    double x_ref[3];       /* centre of mass at rest, m */
    double base_local[3];  /* point of the support plane below the centre of mass, body frame, m */
    double base_ref[3];    /* same point in the ground frame at rest, m */
    double seat[4];        /* the support plane at rest, seat . (x, y, z) = seat[3] (m): its upward
                            unit normal (the face of the body it rests on that faces up and holds
                            its lowest point; e_z when it rests on nothing) and the body's lowest
                            point along it */
    double zb[3];          /* the rest vertical in the body frame */
    double alpha_min;      /* smallest static tipping angle over all lean directions, rad */
    double key_max;        /* tilt key (monitor.c: tilt_key) of the max tilt so far */
    double key_ratio_gate; /* key of max tilt ratio * alpha_min: a new max ratio must exceed it */
    double cos_over_gate;  /* cos of the smallest tilt that can meet the overturn criterion */
    int down;              /* tilted past 85 degrees: lying down */
    int rests_on;          /* body it rested on at rest (off-pedestal criterion), -1 none */
    double twist_prev;     /* unwrapped twist at the last sample, rad */
    int nsupport;          /* support polygon at rest (ground xy, counter-clockwise), for alpha: the
                            base over the bodies that hold it up (monitor.c: support_polygon) */
    double (*support)[2];
    double prec[RD_NPREC][3]; /* precariousness: lean direction (rad), alpha (rad), g tan(alpha) */
    double rest_area;         /* contact area at rest, m^2 */
    double area;              /* contact area this step, m^2 */
    int nslip, nactive;       /* slipping / active subcontacts this step */
    int uplifted;             /* currently rocking (contact area < 60 % of the area at rest) */
    double rock_axis[3]; /* horizontal unit axis of the rocking that started at the last uplift */
    double rock_prev;    /* signed rocking angle about rock_axis at the previous step, rad */
    double rock_peak;    /* largest |rocking angle| since the last impact, rad */
    int sliding;    /* currently sliding as a whole (every active point at the Coulomb limit) */
    int over;       /* currently beyond the overturn criterion */
    int over_once;  /* has met it since shaking began: a body that overturned keeps that
                            verdict when it then leaves the scene, even if, tumbling as it falls,
                            it passes upright again (monitor.c: rd_monitor_escape) */
    int touched;    /* 1 once it had contact area while shaking */
    double z_start; /* height of the centre of mass as placed, m */
    rd_body_summary *sum; /* what the run found: &rd_sim.body_sum[k] */
    int lost;             /* fell out of the scene after overturning, or after resting on a
                            support (event "lost" written): the verdict is final */
} rd_watch;

/* Runout state of one free body (runout.c). */
typedef struct rd_runout_body {
    double x_prev[3]; /* centre of mass at the previous step, m */
    int left;         /* 1 once its centre left the domain box: out of the run */
} rd_runout_body;

/* The fixed surface seen from above (runout.c): the upward-facing triangles of the fixed
 * bodies, binned on a plan grid, for the height of the ground below a point. */
typedef struct rd_ground {
    int ntri;
    double (*tri)[3][3]; /* ground frame, m */
    double lo[2], cell;  /* grid origin and cell size, m */
    int nx, ny;
    int *cell0; /* [nx ny + 1] first entry of each cell in item */
    int *item;  /* triangle indices */
} rd_ground;

struct rd_sim {
    rd_scenario sc; /* deep copy of the scenario (owned: the caller's may be freed) */
    int nb;         /* bodies, fixed and free, in scenario order */
    int nfree;      /* free bodies */
    int *free_body; /* [nfree] body index of each free body (output order) */
    int *free_of;   /* [nb] index among free bodies, -1 for fixed bodies */
    rd_poly *poly;  /* [nb] shape in the body frame (centre of mass, principal axes) */

    /* body state (ground frame: the frame moving with the ground) */
    double (*x)[3];       /* centre of mass, m */
    double (*q)[4];       /* orientation, body -> ground */
    double (*v)[3];       /* velocity at the half step, m/s */
    double (*L)[3];       /* angular momentum about the centre of mass at the half step, kg m^2/s */
    double (*w)[3];       /* angular velocity at the half step, rad/s */
    double (*R)[9];       /* rotation matrix of q, refreshed each step */
    double *mass;         /* kg */
    double (*inertia)[3]; /* principal moments, kg m^2 */
    int *fixed;           /* 1 for pedestals (move with the ground: at rest in this frame) */
    unsigned char *impacting;      /* [nb] 1: at the last contact step a point of one of the body's
                                      contacts was in its first compression (a new impact) */
    unsigned char *impacting_next; /* [nb] the same, found during this contact step */
    int *convex;                   /* 1 for convex bodies: only they can be contact targets */
    double (*f)[3];                /* force accumulator, N */
    double (*tq)[3];               /* torque accumulator about the centre of mass, N m */
    double (*v_old)[3];            /* previous half-step velocity (energy at integer steps) */
    double (*L_old)[3];
    double (*df_local)[6]; /* local damping's force (0-2, N) and torque (3-5, N m) at the last
                              shaking step: its work is booked by the trapezoid rule */

    /* world geometry, refreshed each step for free bodies */
    int *vert0;         /* [nb+1] first world vertex of each body */
    double (*wv)[3];    /* world vertices, m */
    int *face0;         /* [nb+1] first world face of each body */
    double (*wn)[3];    /* world face normals */
    double *wd;         /* world face offsets, m */
    double (*wt)[2][3]; /* a fixed body's world face tangents t1, t2 (t1 x t2 = the face's
                              normal), the axes of contact.c's face law; unset for free bodies */
    int *hv0;           /* [nb+1] first entry of each body's hull vertices in hv */
    int *hv;            /* hull vertices (world index): a body's box is theirs. A convex body's
                              step (rd_bodies_refresh_step) transforms all its vertices; a
                              non-convex one's only its candidate-face vertices (cv, into
                              cv_world), its hull when the broad phase rebuilds its box
                              (pairs.c), the rest only in rd_bodies_refresh (setup, start of
                              shaking) */
    int *cv0;           /* [nb+1] first entry of each body's candidate-face vertices in cv
                              (faces share vertices, so contact.c finds each vertex's plane
                              distances once per side and step) */
    int *cv;            /* world vertex indices */
    int *cv_slot;       /* [vertices] position of a vertex in its body's cv list, -1 if absent */
    int *edge_v0;       /* [bodies + 1] first entry of a body's edges in edge_v (edge.c) */
    int (*edge_v)[2];   /* each edge of every body once: its vertices (body-local, a < b) */
    double *cv_body;    /* [3][cv entries, all bodies] the cv vertices' body-frame coordinates,
                              x, y, z each contiguous (integrate.c: a mesh's step transform) */
    double *cv_world;   /* [3][cv entries, all bodies] their ground-frame coordinates, x, y, z
                              each contiguous: a non-convex body's step transforms only these
                              (integrate.c), and the contact reads them there (contact.c:
                              vertex_distances); a convex body's are read from wv */
    double *cv_dist;    /* scratch: [cv entries of one body][planes of the other body] signed
                              distances, m */
    uint64_t *cv_mask;  /* scratch: [cv entries of one body][2][nw] plane bits, nw = (planes of
                              the other body + 63) / 64 words a set (contact.c: vertex_distances) */
    int np_max;         /* the most faces of a convex body: the most planes a contact target has */
    struct rd_plane_scratch *plane_scratch; /* contact.c's per-side arrays over the other body's
                                               planes, np_max of each (rd_contact_scratch) */
    struct rd_edge_scratch *edge_scratch;   /* edge.c's arrays over a side's planes, vertices and
                                             edges (rd_edge_init) */

    /* subcontact points, grouped by body, then by candidate face */
    int npts;
    double (*pl)[3];  /* point in the body frame, m */
    double *pa;       /* tributary area, m^2 (a merged point's: its places' sum, merge.c) */
    double (*pn)[3];  /* the point's own outward normal, body frame: its face's, or a merged
                              point's area-weighted mean over its faces (entrance tie-break) */
    int *pmult;       /* points before merging that the point stands for (1: not merged) */
    int *pkin;        /* [npts] the point's kinematics slot on its body: the index (from the
                              body's first point) of the first point at the same place. A mesh
                              face carries its vertices, so a vertex is a point of every face
                              around it (5 on average); contact.c finds its motion once */
    double (*kin)[6]; /* scratch: [most points of a body] one side's ro, vr per slot
                              (contact.c: point_kinematics) */
    long *kin_stamp;  /* scratch: [most points of a body] the side step that filled kin */
    long kin_epoch;   /* side steps taken (stamps kin) */
    int *pt0;         /* [nb+1] first point of each body */
    int ncf;          /* candidate faces (faces that carry points), all bodies */
    int *cf0;         /* [nb+1] first candidate face of each body */
    int *cf_face;     /* [ncf] face index on its body */
    int *cf_pt0;      /* [ncf+1] first point of each candidate face */
    char *cf_facing;  /* [ncf] 1: a face that touches only later (its vertices act only
                              while it faces the other body's entrance face) */
    int *cf_v0;       /* [ncf+1] first entry of each candidate face's vertices in cf_v */
    int *cf_v;        /* the candidate faces' vertices, in face order, as the offsets of
                              their plane masks in cv_mask (their positions in their body's cv
                              list, cv_slot, times 2: times the side's words a set, nw): contact.c's face test reads
                              each mask word with one load */

    /* broad phase (pairs.c) */
    double (*aabb)[6];     /* per body: min xyz, max xyz of its hull vertices, grown by
                              `margin`, m, when the box was last built (at box_pose) */
    double (*box_pose)[7]; /* per body: position (3) and quaternion (4) at the last box build;
                              NaN: never built */
    double *box_rho;       /* per body: largest distance of a hull vertex from its centre, m */
    double *box_drift;     /* per body: bound on how far any hull vertex moved since the box was
                              built, this step (0: the box is exact), m */
    uint64_t *box_builds;  /* per body: boxes built so far (a box's generation) */
    double margin;         /* m */
    int *order;            /* bodies sorted by box minimum along sweep_axis */
    int sweep_axis;
    long stamp; /* broad-phase step counter */
    int *hkey;  /* hash map (a, b) -> pair index, -1 empty; hcap a power of 2 */
    int hcap;
    int *live, nlive, cap_live; /* pairs whose boxes overlap this step */
    int *live_prev, nlive_prev, cap_live_prev;
    struct rd_sweep_part *sweep_part; /* [RD_THREADS_MAX] a threaded sweep's per-thread finds
                                         (pairs.c), made at the first one */

    /* contact pairs and their per-point history (grown when two bodies first meet) */
    int npair, cap_pair;
    rd_pair *pair;
    int nstate, cap_state, cap_state_flags;
    double (*fs)[3];       /* shear force on the owner, ground frame, N */
    unsigned char *pstate; /* RD_PT_* bits */
    int *pface;            /* entrance face (index on the other body) while RD_PT_INSIDE */
    double *pset;          /* permanent set of the normal spring after the impact loss, m */
    double *pstrike;       /* a struck point's stretch (depth - set) when it was struck, m */
    int cap_pface, cap_pset, cap_pstrike;
    int nface_state, cap_face_state;
    int *face_nactive; /* active points per (side, candidate face) last step */
    int bonds;         /* 1 when cohesion or tension is set */
    int shaking;       /* 1 once the shaking stage has started */
    int njoint, cap_joint;
    rd_joint *joint; /* distinct joint property sets; 0 = the default */
    double (*pj)[2]; /* per subcontact state: normal force (N, 0 when open) and last gap
                              (m; faces skipped as wholly open get their lower bound) */
    int cap_state_joint;
    /* edge subcontacts (edge.c), grown with the pairs */
    int nedge_state, cap_efs, cap_edepth, cap_eon;
    double (*efs)[3];    /* shear force on the owner, ground frame, N */
    double (*edepth)[3]; /* while bearing: elastic stretch (depth less the set) and the set
                              taken at the contact's onset, m; the spring's place along its
                              edge (0 to 1, from its first vertex; joint.c's measures) */
    unsigned char *eon;  /* non-zero while bearing or holding its set (edge.c's RD_EDGE_ bits) */

    /* time */
    double t;           /* s, 0 at the start of shaking */
    double dt;          /* s */
    double dt_crit;     /* estimated critical step, s */
    int dt_pair[2];     /* the bodies that set it (timestep.c; -1: a fixed body) */
    long step;          /* steps taken while shaking */
    int settling;       /* 1 during the settle stage */
    double settle_time; /* s */

    /* ground motion this step (m/s^2, m/s, m) */
    double ag[3], vg[3], dg[3];
    double ag_prev[3]; /* ground acceleration at the previous step, m/s^2 */
    int ground_const;  /* 1: the motion has no pulse and no record, the same at every t */
    int ground_still;  /* 1: ag, vg, dg hold such a motion (evaluated at the first step that
                              shakes) */
    rd_motion_axes ground_axes; /* the motion's directions' cosines and sines, found once */

    /* energy bookkeeping, J */
    double e_fric, e_damp, e_work; /* accumulated friction, damping dissipation, ground work */
    /* [2] while rd_contact_pair steps a pair: its friction and damping energy this step, added
       to e_fric, e_damp once per pair; else NULL */
    double *e_pair;
    double e0;                 /* total mechanical energy at the start of shaking */
    double e_scale;            /* largest energy term seen (to normalise the residual) */
    double resid_max;          /* max |residual| / e_scale */
    double t_untrusted;        /* s: first sample whose residual passed RD_ENERGY_TRUST
                                      (its time only where untrusted is 1) */
    int untrusted;             /* 1: a sample's residual has passed RD_ENERGY_TRUST */
    double energy[RD_NENERGY]; /* last sample */

    /* monitoring and output */
    rd_watch *watch;           /* [nfree] */
    rd_body_summary *body_sum; /* [nfree] what the run found per free body, contiguous:
                              rd_summary.body points here */
    int rested;                /* 1 once rd_monitor_rest has run: support polygons, alpha and
                              precariousness known */
    int nevent, cap_event;
    rd_event *event;
    int nevent_written; /* events already handed to the observers */
    rd_observer *obs;   /* [nobs] registered observers (observe.c) */
    int nobs, cap_obs;
    long nsample;            /* samples taken so far */
    double next_out;         /* time of the next sample, s */
    double *obuf;            /* [nfree * 17] staging buffer for one sample */
    long active_point_steps; /* sum over steps of active subcontacts (performance figure) */
    int nthreads; /* threads a step may run on: rd_scenario.threads resolved (workers.c) */
    int team;     /* the most threads one step of this run ran on (1: all serial) */
    struct rd_workers *workers; /* the threads' views of the simulation and their tapes
                                   (workers.c), made at the first step run in parallel */
    struct rd_tape *tape;       /* NULL in the simulation itself; in a thread's view of it
                                   (workers.c), where the contact loop records each addition to
                                   a sum that other pairs share (engine/workers.h: rd_book) */
    size_t ndist, nmask;        /* entries of cv_dist and cv_mask (setup.c: side_sizes) */
    int nkin;                   /* entries of kin and kin_stamp: the most points of a body */
    double wall;                /* wall seconds of the shaking stage */
    double settle_ratio;        /* unbalanced-force ratio reached by the settle stage */
    double overlap;         /* deepest overlap of two bodies as placed beyond RD_OVERLAP_FRACTION, m
                              (0: none; overlap.c) */
    int overlap_pair[2];    /* the two bodies of that overlap */
    double rest_since;      /* tail: time since which every free body has been at rest, s
                              (-1 while something moves) */
    int at_rest;            /* until rest: 1 once the run ended at rest (rd_summary.at_rest) */
    rd_runout_body *run;    /* [nfree] runout state (runout.c) */
    rd_ground ground;       /* the fixed surface from above (runout.c) */
    struct rd_quiet *quiet; /* sc.quiet_stop: the motion's remaining peaks (quiet_end.c) */
    /* histories (history.c) */
    int nhist_col;  /* columns per history sample (time first) */
    int *hist_pair; /* [nhistories] pair index of a joint history, -1 before it exists */
    int *hist_body; /* [nhistories][2] body indices */
    double *hist;   /* [nhist_rows][nhist_col] */
    long nhist_rows, cap_hist_rows;
    double next_hist; /* time of the next history sample, s */
    int restored;     /* 1: the state came from `model restore` (no settling) */
    double
        *rest_area; /* [nfree] state image (state.c) staging: each free body's contact area, m^2 */
    rd_status status;
    int phase;       /* rd_sim_phase: where rd_sim_start / advance / finish have got to */
    double end;      /* time the shaking stage ends at (rd_rest_end at its start), s */
    atomic_int stop; /* rd_sim_stop: 1 = stop at the next step */
    char errmsg[RD_ERROR_MAX];
    double floor_z;  /* lowest point of the fixed bodies, m (-INFINITY without any) */
    long nsteps_all; /* steps taken, settling included (escape checks every RD_ESCAPE_EVERY) */
    struct rd_surface *surf; /* `contact model surface`: the bodies' planes and the patches'
                              state (surface.c); NULL with vertex subcontacts */
    double escape_reach;  /* travel of a centre of mass against another body between escape checks,
                              at most, m: half the smallest inradius of a convex body (monitor.c) */
    double escape_travel; /* bound on that travel since the last escape check, m */
};

/* The stages of a run (rd_sim_start, rd_sim_advance, rd_sim_finish in rockdem.h). */
typedef enum rd_sim_phase {
    RD_PHASE_CREATED = 0, /* built, not settled */
    RD_PHASE_SHAKING = 1, /* at rest, observers begun, shaking under way */
    RD_PHASE_OVER = 2,    /* the shaking stage ended (duration, stop, overturn, failure, rest) */
    RD_PHASE_FINISHED = 3 /* summarised, observers ended */
} rd_sim_phase;

/* sim.c: n settle-mode steps from the current state (returns the wall seconds they took);
 * rd_sim_build (the simulation without a checkpoint) is in engine/state.h */
double rd_sim_trial_steps(rd_sim *s, int n);

/* joint.c */
int rd_joints_init(rd_sim *s, rd_error *err);
int rd_joint_resolve(rd_sim *s, int a, int b);
void rd_joint_body_limits(const rd_sim *s, int i, double *k, double *zeta);
void rd_joint_face_open(rd_sim *s, const rd_side *sd, int cf, double gap);
void rd_joint_measure(rd_sim *s, rd_pair *pr, rd_joint_state *m);
void rd_joints_sample(rd_sim *s);
int rd_pair_find(const rd_sim *s, int a, int b);

/* history.c */
int rd_history_init(rd_sim *s, rd_error *err);
void rd_history_step(rd_sim *s);

/* pairs.c */
int rd_pairs_init(rd_sim *s, rd_error *err);
int rd_pairs_update(rd_sim *s);
void rd_pairs_free(rd_sim *s);
void rd_pairs_box_now(const rd_sim *s, int i, double box[6]);
void rd_pairs_box_loose(const rd_sim *s, int i, double box[6]);
double rd_pairs_drift(const rd_sim *s, int i, const double pose[7]);

/* contact.c */
int rd_contact_step(rd_sim *s);
/* One live pair's subcontact and edge forces (rd_contact_step's loop body; workers.c runs it on
 * a thread's view of s). */
void rd_contact_pair(rd_sim *s, rd_pair *pr);
/* A side's plane scratch for np_max planes (rd_sim.plane_scratch; workers.c: one per thread),
 * or NULL (memory); free() frees it. */
struct rd_plane_scratch *rd_contact_scratch(const rd_sim *s);
void rd_contact_reset_body(rd_sim *s, int body);
void rd_contact_seat(rd_sim *s);
void rd_contact_find_impacts(rd_sim *s);
double rd_contact_elastic_energy(const rd_sim *s);

/* surface.c: contact from the touching surfaces (`contact model surface`) */
int rd_surface_init(rd_sim *s, rd_error *err);
void rd_surface_step(rd_sim *s);
double rd_surface_elastic_energy(const rd_sim *s);
double rd_surface_contact_area(const rd_sim *s, int i);
void rd_surface_reset(rd_sim *s, int body);
/* Pair pr's joint measures from its patches at the last step (fn, fs, area; cop left as the
 * |fn|-weighted sum, its weight into *wsum); left alone when it never touched. */
void rd_surface_joint_measure(const rd_sim *s, const rd_pair *pr, rd_joint_state *m, double *wsum);
void rd_surface_free(rd_sim *s);

/* edge.c */
int rd_edge_count(const rd_poly *p);
int rd_edge_init(rd_sim *s, rd_error *err);
/* edge.c's scratch (rd_sim.edge_scratch; workers.c: one per thread), or NULL (memory). */
struct rd_edge_scratch *rd_edge_scratch_new(const rd_sim *s);
void rd_edge_side(rd_sim *s, const rd_pair *pr, rd_side *sd, const double *dist,
                  const uint64_t *mask);
void rd_edge_reset(rd_sim *s, const rd_side *sd);
double rd_edge_slot_area(const rd_sim *s, const rd_side *sd, int e);
void rd_edge_seat(rd_sim *s); /* settled: the bearing edges' onsets are no impacts */
double rd_edge_elastic_energy(const rd_sim *s, const rd_pair *pr, const rd_side *sd);

/* integrate.c */
void rd_body_refresh(rd_sim *s, int i);
void rd_bodies_refresh(rd_sim *s);
void rd_bodies_refresh_step(rd_sim *s);
void rd_integrate_kick(rd_sim *s);
void rd_integrate_drift(rd_sim *s);
void rd_body_set_angular_velocity(rd_sim *s, int i, const double w[3]);

/* timestep.c */
/* The stable step bound, s (INFINITY: no contact; NAN: out of memory); pair: the body whose
 * bound is the least and the most mobile other body it may bear on (-1: fixed bodies only). */
double rd_timestep_critical(const rd_sim *s, int pair[2]);
/* " set by block 'a' bearing on 'b'" (or "... on fixed bodies") for s->dt_pair, into buf; "" when none. */
void rd_timestep_pair_text(const rd_sim *s, char *buf, size_t n);

/* energy.c */
void rd_energy_step(rd_sim *s);
void rd_energy_sample(rd_sim *s);
void rd_energy_sample_end(rd_sim *s);

/* rest.c: the free-vibration tail (`model solve time T tail D`) */
#define RD_REST_HOLD 0.1 /* s a rest must last (the tail's and quiet_end.c's) */
/* Longest the shaking stage runs, s: the duration; with a tail, the later of the duration and
 * the motion's end, plus the tail. */
double rd_run_length(const rd_sim *s);
/* rd_run_length, with the tail's rest watch reset: the run's end time. */
double rd_rest_end(rd_sim *s);
int rd_rest_reached(rd_sim *s);

/* quiet_end.c: a sweep or threshold case ends once nothing left of the motion can move it */
/* Prepare the remaining-peak tables (sc.quiet_stop; after rd_monitor_rest). 0, or -1 (memory). */
int rd_quiet_begin(rd_sim *s);
/* 1 once every free body has been at rest RD_REST_HOLD s and the motion left cannot lift or
 * slide any of them (the time is kept: rd_sim_quiet_end). */
int rd_quiet_reached(rd_sim *s);
void rd_quiet_free(rd_sim *s);

/* monitor.c */
void rd_monitor_rest(rd_sim *s);
void rd_monitor_scene(rd_sim *s);
double rd_monitor_inradius(const rd_sim *s, int i);
/* Static tipping angle (rad) of free body k's support polygon at rest (after rd_monitor_rest)
 * with a centre of mass at com (ground frame, m), leaning towards the horizontal (dx, dy):
 * atan(d / h) as for the body's own alpha. com is the body's own, or that of the body and
 * everything standing on it (the assembly tipping as one about this body's base). */
double rd_monitor_alpha_at(const rd_sim *s, int k, const double com[3], double dx, double dy);
int rd_monitor_escape(rd_sim *s);
void rd_monitor_start(rd_sim *s);
void rd_monitor_step(rd_sim *s);
rd_watch *rd_monitor_contact_watch(rd_sim *s, int owner, int other);

int rd_monitor_all_fallen(const rd_sim *s);
/* 1 once any free body has overturned and lies down (RD_OVERTURN_STOP_ANY). */
int rd_monitor_any_fallen(const rd_sim *s);
void rd_monitor_finish(rd_sim *s);
void rd_monitor_rotation(rd_sim *s, int k, double out[3]);
void rd_monitor_rotation_peek(const rd_sim *s, int k, double prev, double out[3]);
void rd_energy_peek(rd_sim *s); /* energy.c: s->energy at t(n), the run's residual untouched */
void rd_event_add(rd_sim *s, double time, int body, const char *type, double value);

/* runout.c: trajectories, fence and domain (docs/RUNOUT.md) */
int rd_runout_begin(rd_sim *s);   /* at the start of shaking; -1 out of memory */
void rd_runout_step(rd_sim *s);   /* every shaking step, after the monitor */
void rd_runout_finish(rd_sim *s); /* at the end: direction, orientation */
void rd_runout_free(rd_sim *s);
/* Height of the fixed surface below (x, y), at most z_top, m (-INFINITY: none). */
double rd_ground_below(const rd_sim *s, double x, double y, double z_top);

/* observe.c: samples, events and the summary handed to the observers */
void rd_observe_begin(rd_sim *s);
int rd_observe_sample(rd_sim *s);
void rd_observe_end(rd_sim *s);
void rd_observe_release(rd_sim *s);

/* setup.c */
int rd_setup_bodies(rd_sim *s, rd_error *err);
int rd_setup_contacts(rd_sim *s, rd_error *err);
/* Face f of body i lies on face g of body j: antiparallel normals, every vertex of f within tol
 * of g's plane (setup.c: the faces that carry a bed; pairs.c: which side covers a joint). */
int rd_face_lies_on(const rd_sim *s, int i, int f, int j, int g, double tol);

/* rd_sim_build without refusing bodies that overlap as placed (check.c reports them). */
rd_sim *rd_sim_build_as_placed(const rd_scenario *sc, rd_error *err);

/* Bodies overlapping as placed (overlap.c). */
#define RD_OVERLAP_FRACTION                                                                        \
    1e-3 /* an overlap deeper than this fraction of the smaller body's
                                    bounding radius cannot be a placement: refused */
#define RD_OVERLAP_EDGE_DIRS                                                                       \
    256 /* edge directions of a body taken as separating axes (a 128-sided drum: 129) */
#define RD_PARALLEL_SIN 1e-9 /* two unit directions closer than this sine are parallel */
/* How deep bodies i and j overlap as placed, m (0: apart or touching). */
double rd_overlap_depth(const rd_sim *s, int i, int j);
/* How far point w (ground frame, m) lies below every face plane of convex body t, m (<= 0:
 * outside), known only to be at most stop once it is (engine/overlap.c). */
double rd_overlap_point_depth(const rd_sim *s, int t, const double w[3], double stop);
/* Note the overlap of touching bodies i and j as placed, if deeper than any noted before. */
void rd_overlap_note(rd_sim *s, int i, int j);
/* -1 with err naming the deepest overlap noted, else 0. */
int rd_overlap_refuse(const rd_sim *s, rd_error *err);
/* After settling: a pair deeper into each other than 1 % of the smaller radius (ten contact
 * bands) stops the run as penetrated, the cause in s->errmsg. 1 when it does. */
int rd_overlap_at_rest(rd_sim *s);

/* merge.c: co-located points on faces that always act merged into one (summed area); faces left
 * without a point dropped from the candidates. Allocates pn and pmult. 0 or -1. */
int rd_merge_points(rd_sim *s, rd_error *err);

#endif
