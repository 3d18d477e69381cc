/* rockdem — contacts: vertex-face subcontacts with an entrance face, and the Coulomb-slip joint
 * law with an impact-loss model.
 *
 * Geometry. Each subcontact point p of the owner body (tributary area A) is tested against the
 * other body, which is convex: p is inside when it lies behind every face plane of the other
 * body. A point that enters is attached to the face it entered through — its entrance face,
 * found once per contact episode (as the entrance edge of Shi's DDA) — and for as long as it
 * stays inside, its penetration is measured below that face and its normal force acts along
 * that face's outward normal. The entrance face is the plane the point crossed last: for each
 * plane it approaches (relative velocity into the plane), the time since it crossed is
 * depth / approach speed, and the smallest wins. A point that slid off the other body's top
 * face and comes back from the side is therefore pushed out through the side it crosses, never
 * "re-entering buried" below the top face. A plane counts only if the point can have crossed it
 * within the last RD_ENTRY_STEPS steps (depth <= 2 approach dt): a corner skimming into the band
 * of a long base's top face, almost parallel to it, lies metres inside the base's trailing side,
 * which it approaches at its full speed, and taking that side gave it a spring metres deep (a
 * 4-drum column at 0.6 g gained 66 kJ in one step; tests/test_extreme.c test_grazing_landing).
 * A point that comes in level with a face its own face looks at (within the band of its plane)
 * while that rule picks a plane its face does not look at bears on the level face from where it
 * is (its depth taken as its set): a block sliding back over its pedestal's edge, its points
 * crossing the pedestal's side plane at the top face's level, was pushed back by that side
 * (tests/cli/edge_slide.sh).
 * With no plane crossed (contact made at rest, or that skim), the shallowest plane wins, and
 * among planes equally shallow within the contact band, one that the point's own face looks at
 * (a corner of two equal blocks bears on the top face, not on the side plane it also lies on).
 * Faces that touch only later (a brick's sides, once it topples) carry their vertices as
 * points that take part only while their face looks at the entrance face (outward normals at
 * more than 135 deg, RD_FACING_COS): a brick's corner belongs to its base while it rocks, and
 * its side's corners join once it has toppled past 45 deg. The points of the faces that always
 * act (a base, a face placed on another body's) bear only on a face they look at, within 80 deg
 * of facing it (RD_BASE_FACING_COS): a base's corner does not push on a side face that it meets
 * at right angles (two blocks sliding into each other), and one that crossed a side plane takes
 * the face it looks at instead (look_again).
 * With the entrance face fixed, the normal force is the gradient of (1/2) KN A' depth^2, a
 * potential of the relative pose: the normal law is conservative (no energy is created by
 * the choice of normal, unlike a common plane that switches between the faces of two blocks).
 *
 * Law (seed 002 eqs. 1-2, 3DEC Coulomb slip), per subcontact, with A' = weight * A:
 *     Fn = KN A' (depth - dp)         compression only (tension up to T A' while bonded)
 *     Fs <- proj(Fs) - KS A' dUs      incremental, kept in the plane of the entrance face
 *     |Fs| <= Fn tan(phi) + c A'      scaled back along its direction when exceeded
 * Impact loss (`contact property restitution e`): the first time a new subcontact unloads, its
 * spring keeps the fraction e of its stretch, dp = (1 - e) depth_peak (a permanent set), so a
 * point mass striking it rebounds with e times its speed (energy ratio e^2) while the
 * stiffness, and so the stable time step, stay KN A. e = 0 makes every impact perfectly
 * plastic at the point, which is the impact of rigid rocking theory (Housner; Kounadis):
 * no rebound at the new pivot, angular momentum kept about it. e = 1 (3DEC's elastic joint)
 * loses nothing.
 * A new impact is an event of its two bodies, not of the point alone: while a point of one of a
 * body's contacts is in its first compression, every bearing point of that body's contacts that
 * is pressed (approaches, vn < 0) is struck, and its next unloading takes the same loss. The
 * rigid theory resolves all the impulses of an impact at once, each contact plastic (Housner;
 * Kounadis: the ground corner and the interface of a stack together); without this, a bearing
 * point pressed by the impulse of another contact gives its compression back elastically, and a
 * stack hops at its impacts and walks (docs/CONTACT.md section 2). Found from the last contact
 * step (rd_sim.impacting), so the order of the pairs does not matter. A touch counts as an impact
 * when the point approaches faster than g sqrt(m_eff / K_active), the speed the pair's weight
 * reaches settling onto its bearing springs from rest: slower, it is a quasi-static touchdown,
 * like a scanned rock's points coming and going as it sways, and striking the bearing points at
 * each of those would sink the body step by step into its support.
 * On an elastic joint (e = 1) an unbonded spring that switches on or off within a step bears the
 * step's mean force, KN A' (s + w/2)^2 / (2 w) for a stretch s within w/2 = |vn| dt / 2 of zero
 * (law.h rd_law_switch_stretch): leapfrog's impulse F(n) dt is then the spring's own over the
 * step, and a bounce keeps its energy wherever the touch fell in the step (with KN A' s, up to
 * (omega dt)^2 / 4 of it was gained or lost). A joint with e < 1 takes the set at the first
 * unloading step, booked for the force at t(n), and keeps KN A' s.
 * The face law. Against a fixed body (a pedestal, a base), a point's law runs in the frame of its
 * entrance face: axes t1, t2 along the face (rd_sim.wt) and its outward normal u, t1 x t2 = u.
 * Its offset and relative velocity there are ro' = B ro and vr' = B vr (B: rows t1, t2, u), so
 * its normal speed is vr'_z, its tangential velocity (vr'_x, vr'_y) and its shear spring the
 * plane vector (t1 . fs, t2 . fs): the law of a point on the plane z = 0, as the reference
 * kernel's (bench/kernel.c), with no projection of vr and no turn of the spring (a fixed face
 * does not turn). The forces are summed per face in its frame and turned back once per side
 * step. It is the same law: results differ from the ground frame's at round-off (the stored
 * spring loses the round-off part along u that the turn kept), and a bearing point costs less
 * (docs/PERFORMANCE.md). Between two free bodies the entrance face turns, and the law runs in
 * the ground frame with the turn.
 * An exiting subcontact drops its forces; the first slip or opening breaks its bond (c, T -> 0).
 * Optional normal dashpot: Fd = -2 zeta KN A' sqrt(m_eff / K_active) vn.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "engine/law.h"
#include "engine/workers.h"
#include "base/vec.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A subcontact acts only while its face and the entrance face are within 45 deg of facing each
 * other (cos 135 deg = -RD_FACING_COS). */
#define RD_FACING_COS        0.70710678118654752
/* A point of a face that always acts (a base, a bed, a face placed on another body's) bears
 * only on an entrance face that its own face looks at: outward normals more than 100 deg apart
 * (cos 100 deg = -RD_BASE_FACING_COS; its normal: rd_sim.pn, the face's, or the mean of the
 * merged faces' at a vertex, merge.c). A face at right angles to another touches it along an
 * edge only, which the edge subcontacts carry: a block's base corner that met another block's
 * side face (the two sliding into each other) bore on it with the base's area as well as the
 * side face's own corner with the side's, 1.5 times the joint's KN A and its centre at h/3, not
 * h/2. 10 deg short of the right angle, so that a block striking a vertical face while tilted by
 * a few degrees is decided far from round-off, while a block rocking on its base keeps its pivot
 * up to 80 deg of tilt (past any block's overturning angle but the squattest, h/b < 0.18). */
#define RD_BASE_FACING_COS   0.17364817766693035
/* A plane counts as approached when the point moves into it faster than this fraction of its
 * relative speed (below, the motion is tangential: round-off must not pick a side face). */
#define RD_APPROACH_FRACTION 1e-3
/* A point found inside crossed a plane it approaches only if its depth below it is what it
 * moved through in this many steps at its approach speed (entrance_face). */
#define RD_ENTRY_STEPS       2.0
/* steady_point is a pure shortcut of subcontact. Built with -DRD_STEADY_PATH=0 every point takes
 * subcontact, and every output must be bit-identical: tests/cli/steady_path.sh checks that on
 * scenes that visit every branch (bed, corners, late faces, slip, bonds, dashpots, mesh, drums). */
#ifndef RD_STEADY_PATH
#define RD_STEADY_PATH 1
#endif

/* The motion of the owner relative to the other body this step, found once per side from
 * rd_sim's R, x, v, w (side_ctx.fr, and a local of side_faces that no store into rd_sim can
 * reach). A point at offset ro from the owner's centre moves against the other body's material
 * point at the same place with vr = v0 + wr x ro: with d = xo - xt, vo + wo x ro - vt - wt x
 * (ro + d) = (vo - vt - wt x d) + (wo - wt) x ro, one cross product a point (a fixed other body
 * has no motion: v0 = vo, wr = wo). */
typedef struct side_frame {
    double R[9];  /* owner rotation, body -> ground */
    double v0[3]; /* relative velocity of the owner's centre, m/s */
    double wr[3]; /* relative angular velocity, rad/s */
} side_frame;

/* A side's force sums: the force F (N) and torque ro x F (N m) on the owner summed over its
 * subcontacts, fn u summed (N), KN A' summed over active points (N/m), and the current face's
 * bearing area A' (m^2). A free other body takes -F at rt = ro + d each: -sum F and -(sum ro x F
 * + d x sum F), applied once per side (side_step). side_faces keeps them in a local that no
 * rd_sim store can reach (off the store-to-load chains of a struct behind a pointer). */
typedef struct side_sums {
    double f_o[3], tq_o[3];
    double nsum[3];
    double k_active;
    double area;
} side_sums;

/* A face of a fixed other body as the frame of the face law (see the header): axes t1, t2 along
 * the face (rd_sim.wt) and its outward normal u, t1 x t2 = u; B has rows t1, t2, u. Found when a
 * point first needs it in a side step (face_frame_at). */
typedef struct face_frame {
    const double (*t)[3]; /* t1, t2, ground frame (rd_sim.wt) */
    double r[2][3];       /* t1, t2 in the owner's frame: a point at p (owner frame) lies at
                           ro' = (r[0] . p, r[1] . p, its plane distance's u' . p) */
    double v0[3], wr[3];  /* side_frame's v0 (m/s) and wr (rad/s) in the face frame */
    double f[3], tq[3];   /* the face's points' force (N) and torque about the owner's centre (N m),
                           face frame */
    double fn;            /* their normal forces summed, N */
} face_frame;

/* A side's arrays over the other body's planes, np_max of each (rd_sim.np_max: sized by the
 * body with the most faces, so a convex body may have any number), in one block
 * (rd_contact_scratch); a side step uses the first np. */
struct rd_plane_scratch {
    face_frame *ff;            /* side_ctx.ff */
    double (*pl)[4];           /* side_ctx.pl */
    double *n0, *n1, *n2, *dq; /* distances_from's plane coefficients, one array each */
    double *dmax;              /* distances_from's largest distance to each plane, m */
    uint64_t *cross, *ff_used; /* [(np_max + 63) / 64] side_ctx.cross, ff_used */
};

/* The other body's face planes expressed in the owner's body frame, so a point's signed
 * distances need no transform: s_k(p) = n_k . p - d_k (> 0: outside plane k). */
typedef struct side_ctx {
    int o, t;              /* owner and other body */
    double wa;             /* weight */
    double damp_coef;      /* 2 zeta sqrt(m_eff / K_active), s (0 without viscous damping) */
    int damped;            /* the joint has a normal dashpot (damping > 0) */
    int struck;            /* one of the two bodies takes a new impact (rd_sim.impacting) and
                                   the joint loses energy at impacts: a bearing point pressed now
                                   is struck */
    int opens;             /* a point of this side is in its first compression after an
                                   impact (RD_PT_IMPACT) */
    int mean_switch;       /* an elastic joint (restitution 1): an unbonded spring that
                                   switches on or off within the step bears its mean force over
                                   the step (rd_law_switch_stretch) */
    const rd_pair *pr;     /* the pair (its m_eff and last K_active: rd_law_touch_speed) */
    side_frame fr;         /* the two bodies' pose and motion */
    double tol;            /* contact band: a point this far outside a plane still counts as
                                   inside, m */
    int np;                /* planes of the other body */
    const double (*wn)[3]; /* the other body's outward face normals, ground frame (rd_sim.wn) */
    double (*pl)[4];       /* [np] n (3), d: plane k, owner frame (rd_plane_scratch) */
    const double *dist;    /* the owner's candidate-face vertices' signed distances to the
                                   planes (rd_sim.cv_dist, [cv slot][plane], m) */
    const uint64_t *mask;  /* per vertex (rd_sim.cv_mask, [cv slot][2][nw]): bit q
                                   of word set 0 when the vertex lies beyond plane q by more than
                                   out_band (or its distance is NaN), of set 1 when it lies above
                                   reach */
    int nw;                /* mask words in use, (np + 63) / 64 */
    double out_band;       /* tol + bond slack + raise: a face wholly this far beyond one
                                   plane cannot touch, m */
    double reach;          /* tol / 2 - raise, m: when every vertex of a face lies below this
                                   distance from plane q, none of its points lies beyond q by more
                                   than the band tol (points lie in the hull of their face's
                                   vertices, raised inward by at most raise; tol / 2 is left for
                                   round-off), so their exit test skips q */
    double raise;          /* a raised point lies up to this far inside its face, m */
    uint64_t *cross;       /* [nw] bit q: some point of the current face may lie beyond
                                    plane q (rd_plane_scratch) */
    const double *m;       /* outward normal of the current owner face, ground frame, once
                                   found (owner_normal), else NULL; set, with mf, for late faces
                                   only (no other face's points ask for it) */
    int mf;                /* the current owner face (a late one) */
    double mbuf[3];
    int facing;               /* 1: the face's points act only while it faces the entrance face */
    int t_free;               /* the other body is free (a fixed one takes no force) */
    double to_b;              /* +1 when the owner is the pair's body b, -1 when it is a */
    int face_law;             /* the other body is fixed: its points take the face law
                                   (face_frame), in the frame of their entrance face */
    const double (*wt)[2][3]; /* the other body's face tangents (rd_sim.wt), when it is fixed */
    face_frame *ff;           /* [np] the other body's faces as frames, valid where ff_used */
    uint64_t *ff_used;        /* [nw] bit e: ff[e] found this side step (rd_plane_scratch) */
} side_ctx;

static inline double plane_dist(const double *pl, const double p[3])
{
    return pl[0] * p[0] + pl[1] * p[1] + pl[2] * p[2] - pl[3];
}

/* Point p's (owner frame) offset ro from the owner's centre (ground frame) and its relative
 * velocity vr = v0 + wr x ro, from the frame fr: k = (ro, vr), 6 values. */
static inline __attribute__((always_inline)) void frame_kinematics(const side_frame *fr,
                                                                   const double p[3], double k[6])
{
    rd_mat_vec(fr->R, p, k);
    rd_cross(fr->wr, k, k + 3);
    rd_axpy(1.0, fr->v0, k + 3);
}

/* Face e of the fixed other body as a frame (face_frame), from the side's frame; its sums start
 * at 0. */
static __attribute__((noinline)) void face_frame_find(side_ctx *c, int e)
{
    face_frame *ff = &c->ff[e];
    c->ff_used[e >> 6] |= (uint64_t)1 << (e & 63);
    const double *u = c->wn[e];
    ff->t = c->wt[e];
    rd_mat_tvec(c->fr.R, ff->t[0], ff->r[0]);
    rd_mat_tvec(c->fr.R, ff->t[1], ff->r[1]);
    const double *b[3] = { ff->t[0], ff->t[1], u };
    for (int k = 0; k < 3; k++) {
        ff->v0[k] = rd_dot(b[k], c->fr.v0);
        ff->wr[k] = rd_dot(b[k], c->fr.wr);
        ff->f[k] = ff->tq[k] = 0;
    }
    ff->fn = 0;
}

/* Face e's frame, found at its first use in this side step (face_frame_find). */
static inline __attribute__((always_inline)) face_frame *face_frame_at(side_ctx *c, int e)
{
    if (!(c->ff_used[e >> 6] & ((uint64_t)1 << (e & 63)))) face_frame_find(c, e);
    return &c->ff[e];
}

/* Point p's (owner frame) offset ro' and relative velocity vr' = v0' + wr' x ro' in face frame
 * ff, given ro'_z = dz (the first part of its plane distance): k = (ro', vr'), 6 values. */
static inline __attribute__((always_inline)) void
face_kinematics(const face_frame *ff, const double p[3], double dz, double k[6])
{
    k[0] = rd_dot(ff->r[0], p);
    k[1] = rd_dot(ff->r[1], p);
    k[2] = dz;
    rd_cross(ff->wr, k, k + 3);
    rd_axpy(1.0, ff->v0, k + 3);
}

/* The face law's trial shear spring (N): the stored spring fs (ground frame) in the face's plane,
 * f0 = (t1 . fs, t2 . fs, 0), loaded by -KS A' vr'_t dt (sA = KS A', N/m): into f. */
static inline __attribute__((always_inline)) void
face_shear_trial(const face_frame *ff, const double fs[3], const double vr[3], double sA, double dt,
                 double f0[3], double f[3])
{
    f0[0] = rd_dot(ff->t[0], fs);
    f0[1] = rd_dot(ff->t[1], fs);
    f0[2] = 0;
    f[0] = f0[0] - sA * vr[0] * dt;
    f[1] = f0[1] - sA * vr[1] * dt;
    f[2] = 0;
}

/* rd_sim's frame of the side's two bodies (side_frame); d receives xo - xt (0 when the other
 * body is fixed), m. */
static void side_frame_of(const rd_sim *s, int o, int t, side_frame *fr, double d[3])
{
    for (int k = 0; k < 9; k++) fr->R[k] = s->R[o][k];
    rd_copy3(s->v[o], fr->v0);
    rd_copy3(s->w[o], fr->wr);
    d[0] = d[1] = d[2] = 0;
    if (s->fixed[t]) return;
    double wd[3];
    for (int k = 0; k < 3; k++) d[k] = s->x[o][k] - s->x[t][k];
    rd_cross(s->w[t], d, wd);
    for (int k = 0; k < 3; k++) {
        fr->v0[k] -= s->v[t][k] + wd[k];
        fr->wr[k] -= s->w[t][k];
    }
}

/* Point pt's offset from the owner's centre and its relative velocity (ro, vr: 6 values into
 * k), found once per side step for the points that share its place
 * (rd_sim.pkin, kept in rd_sim.kin). k is the caller's local: a law that read them back from
 * kin right after these 8-byte stores would stall on store forwarding (16-byte loads).
 * Inlined at both of its calls in subcontact (gcc makes a call of it otherwise: 15 % slower). */
static inline __attribute__((always_inline)) void point_kinematics(rd_sim *s, const side_ctx *c,
                                                                   int pt, double k[6])
{
    int q = s->pkin[pt];
    double *sk = s->kin[q];
    if (s->kin_stamp[q] != s->kin_epoch) {
        frame_kinematics(&c->fr, s->pl[pt], k);
        for (int i = 0; i < 6; i++) sk[i] = k[i];
        s->kin_stamp[q] = s->kin_epoch;
    } else {
        for (int i = 0; i < 6; i++) k[i] = sk[i];
    }
}

/* The law's kinematics of point pt at p (owner frame) with entrance face e: under the face law
 * in that face's frame (dz: the point's ro'_z, face_kinematics), else in the ground frame
 * (point_kinematics): k = (ro, vr). */
static inline __attribute__((always_inline)) void
law_kinematics(rd_sim *s, side_ctx *c, int pt, int e, const double p[3], double dz, double k[6])
{
    if (c->face_law)
        face_kinematics(face_frame_at(c, e), p, dz, k);
    else
        point_kinematics(s, c, pt, k);
}

/* The normal relative velocity vr . u (m/s, < 0: approaching) of law_kinematics' vr: its z
 * under the face law. */
static inline double law_vn(const side_ctx *c, const double vr[3], const double u[3])
{
    return c->face_law ? vr[2] : rd_dot(vr, u);
}

/* A subcontact's last bearing step, as a release needs it: its elastic normal stretch s (m), the
 * non-elastic part of its normal force fd (dashpot, tension cap; N) and its Coulomb limit lim
 * (N). All 0 for a point that did not bear. */
typedef struct bore {
    double s, fd, lim;
    int bonded; /* it bore as a bond (it may hold tension) */
} bore;

static inline bore last_bore(const rd_sim *s, const rd_joint *j, int st, double A)
{
    bore b = { 0.0, 0.0, 0.0, 0 };
    unsigned char fl = s->pstate[st];
    if (!(fl & RD_PT_ACTIVE)) return b;
    b.bonded = (fl & RD_PT_BONDED) != 0;
    b.s = -s->pj[st][1] - s->pset[st]; /* pj: its last normal force and minus its depth */
    /* only a dashpot or a bond's tension cap makes a normal force other than the spring's: the
       difference is then exactly 0, not the round-off of -pj[1] - pset (an elastic joint's
       spring that switched within the step stored pj[1] = -(pset + its mean stretch)) */
    b.fd = j->damping > 0 || b.bonded ? s->pj[st][0] - j->kn * A * b.s : 0.0;
    b.lim = rd_max(s->pj[st][0], 0.0) * j->tan_phi + ((fl & RD_PT_BONDED) ? j->cohesion * A : 0.0);
    return b;
}

/* Spring energy released by subcontact st (point pt) that stops bearing at this step (it leaves
 * the contact, its face turns away, its bond breaks), last: its last bearing step, s_now: its
 * elastic normal stretch now (m): its springs at mid-step (rd_law_release_energy), booked as
 * friction (the joint model dissipates it: 3DEC drops the forces of an opening contact), and its
 * dashpot's last half step. */
static void release(rd_sim *s, const side_ctx *c, int pt, int st, double kA, double sA,
                    const bore *last, double s_now)
{
    if (!(s->pstate[st] & RD_PT_ACTIVE)) return;
    double kin[6];
    point_kinematics(s, c, pt, kin);
    const double *u = c->wn[s->pface[st]], *vr = kin + 3;
    double vn = rd_dot(vr, u);
    rd_book_fric(s, rd_law_release_energy(kA, last->s, s_now, last->bonded, s->fs[st], u, vr, vn,
                                          sA, last->lim, s->dt));
    if (last->fd != 0) rd_book_damp(s, rd_law_dashpot_work(last->fd, 0.0, vn, s->dt));
    s->fs[st][0] = s->fs[st][1] = s->fs[st][2] = 0;
}

/* The point leaves the contact (last, s_now: as release): forces drop, the contact episode
 * ends, and so does a bond. */
static void point_exit(rd_sim *s, const side_ctx *c, int pt, int st, double kA, double sA,
                       const bore *last, double s_now)
{
    unsigned char *fl = &s->pstate[st];
    release(s, c, pt, st, kA, sA, last, s_now);
    if (*fl & (RD_PT_ACTIVE | RD_PT_INSIDE)) *fl &= (unsigned char)~(RD_PT_BONDED);
    *fl &= (unsigned char)~(RD_PT_ACTIVE | RD_PT_SLIP | RD_PT_INSIDE | RD_PT_VIRGIN | RD_PT_STRUCK |
                            RD_PT_IMPACT);
    s->pset[st] = 0;
}

/* A point inside but not bearing (its face turned away, or lifted off its permanent set):
 * forces drop, the rest of its state is kept. */
static void point_idle(rd_sim *s, const side_ctx *c, int pt, int st, double kA, double sA,
                       const bore *last, double s_now)
{
    unsigned char *fl = &s->pstate[st];
    release(s, c, pt, st, kA, sA, last, s_now);
    *fl &= (unsigned char)~(RD_PT_ACTIVE | RD_PT_SLIP | RD_PT_BONDED | RD_PT_STRUCK);
}

/* Outward normal of the current owner face, ground frame, found once per face and side step
 * when a point needs it: a convex owner's rd_sim.wn (rd_body_refresh found it from the same
 * rotation, so the same bits); a mesh body's step leaves its face normals alone, so its normal
 * is found here (rd_body_refresh's expression). */
static const double *owner_normal(const rd_sim *s, side_ctx *c)
{
    if (!c->m && s->convex[c->o]) {
        c->m = s->wn[s->face0[c->o] + c->mf];
    } else if (!c->m) {
        rd_mat_vec(s->R[c->o], s->poly[c->o].fn[c->mf], c->mbuf);
        c->m = c->mbuf;
    }
    return c->m;
}

/* Does point pt, of a face that always acts, look at its entrance face e (RD_BASE_FACING_COS)?
 * Both normals in the owner's frame: its own (rd_sim.pn) and the plane's (side_ctx.pl). */
static inline __attribute__((always_inline)) int base_looks(const double pn[3], const double *plane)
{
    return rd_dot(pn, plane) <= -RD_BASE_FACING_COS;
}

/* A point of a face that always acts, inside the other body with an entrance face its face does
 * not look at (it crossed a side plane, or its face turned away): it takes the shallowest plane
 * its face looks at that lies within the contact band of it as its entrance face and bears on
 * it from where it is (its depth below it, if inside, as its set: the level rule of
 * entrance_face), from the next step; it idles on its face while no such plane is near. A drum's
 * base vertex within the band beyond the rim below had taken the rim's side face and, once not
 * pushed sideways by it, would have idled there for good. Only a near plane: the corner of a
 * brick's side face placed on a neighbour, lying on the floor, took the floor's far side 2 m away
 * and bore on it from there (tests/cli/joint_stiffness.sh, tests/cli/pass_through.sh). */
static void look_again(rd_sim *s, const side_ctx *c, int pt, int st, const double p[3])
{
    int g = -1;
    double dmin = DBL_MAX;
    for (int k = 0; k < c->np; k++) {
        double depth = -plane_dist(c->pl[k], p);
        if (base_looks(s->pn[pt], c->pl[k]) && depth <= c->tol && depth < dmin) {
            dmin = depth;
            g = k;
        }
    }
    if (g < 0) return;
    s->pface[st] = (short)g;
    s->pset[st] = fmax(dmin, 0.0);
}

/* The entrance face of point pt (at p, owner frame) that has just been found inside (see the
 * header); its own normal (rd_sim.pn: its face's, or a merged point's mean) breaks ties.
 * *set: the point's permanent set, m: its depth below the face when that is the level one its
 * face looks at, taken instead of a crossed plane it does not look at (it bears from where it
 * is), else 0. */
static int entrance_face(const rd_sim *s, const side_ctx *c, int pt, const double p[3],
                         const double vr[3], double *set)
{
    const double(*wn)[3] = s->wn + s->face0[c->t];
    double speed = rd_norm(vr), tmin = DBL_MAX, dmin = DBL_MAX, m[3];
    rd_mat_vec(s->R[c->o], s->pn[pt], m);
    int best = -1, shallow = -1, level = -1, best_looks = 0;
    double lmin = DBL_MAX;
    for (int k = 0; k < c->np; k++) {
        double depth = rd_max(-plane_dist(c->pl[k], p), 0.0);
        double approach = -rd_dot(vr, wn[k]);           /* > 0: moving into plane k */
        int looks = rd_dot(m, wn[k]) <= -RD_FACING_COS; /* the point's face looks at plane k */
        if (looks && depth <= c->tol && depth < lmin) {
            lmin = depth;
            level = k;
        }
        if (approach > RD_APPROACH_FRACTION * speed && approach > 0 && depth / approach < tmin &&
            depth <= RD_ENTRY_STEPS * approach * s->dt) {
            tmin = depth / approach;
            best = k;
            best_looks = looks;
        }
        /* the shallowest plane; within the contact band, one the point's face looks at */
        double rank = depth + (looks ? 0.0 : c->tol);
        if (rank < dmin) {
            dmin = rank;
            shallow = k;
        }
    }
    const int level_set = level >= 0 && best >= 0 && !best_looks;
    *set = level_set ? lmin : 0;
    return level_set ? level : best >= 0 ? best : shallow;
}

/* A bearing subcontact's results (A: its area A', m^2; fn: normal force, N; u: its entrance
 * face's outward normal; fs: its shear force, N; ro: its offset from the owner's centre, m): its
 * stored shear and normal force (into fsa and pj: rd_sim.fs and rd_sim.pj), the side's normal
 * and area sums, and the force F = fn u + fs with its torque ro x F on the owner (side_sums: a
 * free other body's share is the side's). */
static inline __attribute__((always_inline)) void bear(double (*fsa)[3], double (*pj)[2],
                                                       side_sums *a, int st, double A, double fn,
                                                       const double u[3], const double fs[3],
                                                       const double ro[3])
{
    rd_copy3(fs, fsa[st]);
    pj[st][0] = fn;
    double fu[3] = { fn * u[0], fn * u[1], fn * u[2] };
    for (int k = 0; k < 3; k++) a->nsum[k] += fu[k];
    a->area += A;

    double F[3] = { fu[0] + fs[0], fu[1] + fs[1], fu[2] + fs[2] };
    rd_law_apply(F, ro, NULL, a->f_o, a->tq_o, 0, NULL, NULL);
}

/* bear for the face law (face frame ff): fs = (fx, fy, 0) and ro in the face frame, the force
 * F' = (fx, fy, fn) and its torque ro' x F' summed in the frame (turned back by
 * fold_face_sums), the shear spring stored in the ground frame, fx t1 + fy t2. */
static inline __attribute__((always_inline)) void bear_face(double (*fsa)[3], double (*pj)[2],
                                                            side_sums *a, face_frame *ff, int st,
                                                            double A, double fn, const double fs[3],
                                                            const double ro[3])
{
    for (int k = 0; k < 3; k++) fsa[st][k] = ff->t[0][k] * fs[0] + ff->t[1][k] * fs[1];
    pj[st][0] = fn;
    ff->fn += fn;
    a->area += A;
    const double F[3] = { fs[0], fs[1], fn };
    double tq[3];
    rd_cross(ro, F, tq);
    for (int k = 0; k < 3; k++) {
        ff->f[k] += F[k];
        ff->tq[k] += tq[k];
    }
}

/* The face law's sums of each face used in this side step turned to the ground frame (B^T) and
 * added to the side's: force, torque and fn u. The side's force and torque run on from the
 * owner's (side_step); on a thread's view each face's share is booked to the owner's instead
 * (workers.h), the same additions in the same order. */
static void fold_face_sums(rd_sim *s, side_ctx *c, side_sums *a)
{
    for (int w = 0; w < c->nw; w++)
        for (uint64_t m = c->ff_used[w]; m; m &= m - 1) {
            const int e = 64 * w + __builtin_ctzll(m);
            const face_frame *ff = &c->ff[e];
            const double *u = c->wn[e];
            double f[3], tq[3];
            for (int k = 0; k < 3; k++) {
                f[k] = ff->t[0][k] * ff->f[0] + ff->t[1][k] * ff->f[1] + u[k] * ff->f[2];
                tq[k] = ff->t[0][k] * ff->tq[0] + ff->t[1][k] * ff->tq[1] + u[k] * ff->tq[2];
                a->nsum[k] += u[k] * ff->fn;
            }
            if (s->tape) {
                rd_tape_body(s->tape, c->o, f, tq);
                continue;
            }
            for (int k = 0; k < 3; k++) {
                a->f_o[k] += f[k];
                a->tq_o[k] += tq[k];
            }
        }
}

/* Force of one subcontact on the owner; returns 1 if it carries force. steady_point (below)
 * repeats this law's common cases expression for expression: a change here must be made there
 * too (tests/cli/steady_path.sh fails otherwise: see RD_STEADY_PATH). */
RD_HOT static __attribute__((noinline)) int subcontact(rd_sim *s, side_ctx *c, const rd_joint *j,
                                                       int pt, int st, side_sums *a)
{
    unsigned char *fl = &s->pstate[st];
    const double *p = s->pl[pt];
    double A = c->wa * s->pa[pt], kA = j->kn * A, sA = j->ks * A;
    double slack = (*fl & RD_PT_BONDED) ? j->tension / j->kn : 0.0; /* a bond holds across a gap */
    const bore last = last_bore(s, j, st, A);
    for (int w = 0; w < c->nw; w++)
        for (uint64_t m = c->cross[w]; m; m &= m - 1) {
            double out = plane_dist(c->pl[64 * w + __builtin_ctzll(m)], p);
            if (out > c->tol + slack) {
                s->pj[st][0] = 0;
                s->pj[st][1] = out;
                double stretch =
                    (*fl & RD_PT_INSIDE) ? -plane_dist(c->pl[s->pface[st]], p) - s->pset[st] : 0.0;
                point_exit(s, c, pt, st, kA, sA, &last, stretch);
                return 0;
            }
        }

    /* the point's motion (point_kinematics) is found only when the law needs it: a point that
       idles below needs only its depth */
    double kin[6];
    int moved = 0;
    if (!(*fl & RD_PT_INSIDE)) {
        point_kinematics(s, c, pt, kin);
        moved = !c->face_law; /* the face law's kinematics are in its entrance face's frame */
        s->pface[st] = (short)entrance_face(s, c, pt, p, kin + 3, &s->pset[st]);
        *fl |= RD_PT_INSIDE | RD_PT_VIRGIN;
    }
    int e = s->pface[st];
    const double *u = c->wn[e]; /* outward normal of the entrance face */
    const double dz = rd_dot(c->pl[e], p),
                 depth = -(dz - c->pl[e][3]); /* -plane_dist, to the bit */
    s->pj[st][0] = 0;
    s->pj[st][1] = -depth;
    if (c->facing && rd_dot(owner_normal(s, c), u) > -RD_FACING_COS) {
        point_idle(s, c, pt, st, kA, sA, &last, depth - s->pset[st]);
        return 0;
    }
    if (!c->facing && !base_looks(s->pn[pt], c->pl[e])) {
        point_idle(s, c, pt, st, kA, sA, &last, depth - s->pset[st]);
        look_again(s, c, pt, st, p);
        return 0;
    }
    /* w: the stretch an elastic joint's unbonded spring moves through in this step (|vn| dt,
       m); one within w / 2 of switching bears its mean force over the step (0: a plain switch) */
    double w = 0;
    if (c->mean_switch && !(*fl & RD_PT_BONDED)) {
        if (!moved) law_kinematics(s, c, pt, e, p, dz, kin);
        moved = 1;
        w = fabs(law_vn(c, kin + 3, u)) * s->dt;
    }
    if (depth <= 0 && !(*fl & RD_PT_BONDED)) { /* above its face, within the band: the next
                                                   touch is a new impact */
        if (!(depth > -0.5 * w)) {
            point_idle(s, c, pt, st, kA, sA, &last, depth - s->pset[st]);
            *fl |= RD_PT_VIRGIN;
            s->pset[st] = 0;
            return 0;
        }
        s->pset[st] = 0; /* it touches within this step */
    }
    if (c->facing && !(*fl & RD_PT_ACTIVE)) /* a face that has just turned towards the other
                                               body: its vertex bears from where it is now */
        s->pset[st] = fmax(s->pset[st], depth);
    if (!(*fl & RD_PT_BONDED) &&
        (*fl & (RD_PT_VIRGIN | RD_PT_ACTIVE)) != (RD_PT_VIRGIN | RD_PT_ACTIVE) &&
        kA * (depth - s->pset[st]) < 0 && !(depth - s->pset[st] > -0.5 * w)) {
        /* below its permanent set (by more than w / 2), no bond, no impact to book: the
           contact's surface is at the set, so neither spring nor dashpot acts (a dashpot pushing
           a spring held in tension had both springs' energy flicker in and out of the balance
           each step) */
        point_idle(s, c, pt, st, kA, sA, &last, depth - s->pset[st]);
        return 0;
    }
    if (!moved) law_kinematics(s, c, pt, e, p, dz, kin);
    const double *ro = kin, *vr = kin + 3;
    double vn = law_vn(c, vr, u);
    if (c->struck && (*fl & (RD_PT_VIRGIN | RD_PT_ACTIVE | RD_PT_STRUCK)) == RD_PT_ACTIVE &&
        vn < 0) {
        *fl |= RD_PT_STRUCK; /* a bearing point pressed during a new impact of one of its bodies: */
        s->pstrike[st] = depth - s->pset[st]; /* the impact's share is what it gains from here */
    }
    if ((*fl & RD_PT_ACTIVE) && (*fl & (RD_PT_VIRGIN | RD_PT_STRUCK)) && vn > 0 && !s->settling) {
        /* first unloading of a new or struck contact that bore force: the impact loss (set);
           settling seats the bodies quasi-statically, with no impacts. The energy lost is the
           drop of the scheme's own spring energy: leapfrog conserves sum 1/2 KN A' s(n) s(n+1)
           over a spring that bears throughout (not 1/2 KN A' s(n)^2), and s(n-1) = s(n) + vn dt,
           so the set takes 1/2 KN A' set (s(n-1) + s(n) - set). Booking 1/2 KN A' s(n)^2 left
           1/2 KN A' set vn dt per impact unbooked, an order-dt^2 loss (10-drum column: 2/3 of
           its residual at the default step) */
        double stretch = depth - s->pset[st];
        double set = (1.0 - j->restitution) *
                     ((*fl & RD_PT_VIRGIN) ? stretch : rd_max(stretch - s->pstrike[st], 0.0));
        if (stretch > 0) rd_book_damp(s, 0.5 * kA * set * (2.0 * stretch + vn * s->dt - set));
        s->pset[st] += set;
        *fl &= (unsigned char)~(RD_PT_VIRGIN | RD_PT_STRUCK | RD_PT_IMPACT);
    }
    double stretch = depth - s->pset[st];
    double fel = kA * stretch;                /* elastic normal force, N (< 0: tension) */
    double fn = fel - c->damp_coef * kA * vn; /* plus the dashpot */
    if (w > 0 && stretch < 0.5 * w) { /* it switches within the step: the spring's mean force;
                                         the dashpot acts while the point is pressed */
        double sm = rd_law_switch_stretch(stretch, w);
        fel = kA * sm;
        fn = stretch > 0 ? fel - c->damp_coef * kA * vn : fel;
        s->pj[st][1] = -(s->pset[st] + sm); /* the stretch the spring energy and the dashpot's
                                                share are read from (last_bore) */
    }
    if (fn < 0) {
        int bonded = (*fl & RD_PT_BONDED) && fel > -j->tension * A;
        if (!bonded) {
            *fl &= (unsigned char)~RD_PT_BONDED;
            if (stretch <= 0) { /* a breaking bond releases its tension */
                point_idle(s, c, pt, st, kA, sA, &last, stretch);
                return 0;
            }
        }
        fn = bonded ? fmax(fn, -j->tension * A) : 0.0;
    }
    if (fn != fel || last.fd != 0) /* dashpot or tension-cap work */
        rd_book_damp(s, rd_law_dashpot_work(last.fd, fn - fel, vn, s->dt));
    a->k_active += kA;

    /* shear: the incremental Coulomb spring on the plane of the entrance face (law.h; the face
       law's in the face's frame) */
    double cohesion = (*fl & RD_PT_BONDED) ? j->cohesion * A : 0.0;
    double lim = rd_max(fn, 0.0) * j->tan_phi + cohesion;
    if ((*fl & (RD_PT_VIRGIN | RD_PT_ACTIVE)) == RD_PT_VIRGIN) /* its first bearing step */
        *fl = (unsigned char)(-vn > rd_law_touch_speed(s, c->pr) ? *fl | RD_PT_IMPACT
                                                                 : *fl & ~RD_PT_IMPACT);
    *fl = (unsigned char)((*fl | RD_PT_ACTIVE) & ~RD_PT_SLIP);
    double fs[3]; /* in registers: stored once */
    face_frame *ff = c->face_law ? face_frame_at(c, e) : NULL;
    int slip;
    double *e_fric = &s->e_pair[0]; /* the slip's friction energy: the pair's sum */
    if (ff) {
        double f0[3];
        face_shear_trial(ff, s->fs[st], vr, sA, s->dt, f0, fs);
        slip = rd_law_shear_cap(fs, f0, sA, lim, e_fric);
    } else {
        rd_copy3(s->fs[st], fs);
        slip = rd_law_shear(fs, u, vr, vn, sA, s->dt, lim, e_fric);
    }
    if (slip) *fl = (unsigned char)((*fl | RD_PT_SLIP) & ~RD_PT_BONDED);
    if ((*fl & (RD_PT_VIRGIN | RD_PT_IMPACT)) == (RD_PT_VIRGIN | RD_PT_IMPACT)) c->opens = 1;
    if (ff)
        bear_face(s->fs, s->pj, a, ff, st, A, fn, fs, ro);
    else
        bear(s->fs, s->pj, a, st, A, fn, u, fs, ro);
    return 1;
}

/* What the face pass and the steady path read of rd_sim, the side and the joint: the candidate
 * faces' and the points' arrays and the constants, copied once per side into a local of
 * side_faces (steady_of), with the current face's plane bits and kind. The point's state bytes
 * that the path stores (unsigned char, which may alias any object) would otherwise have each
 * pointer and constant loaded again from rd_sim, side_ctx and rd_joint after every such store. */
typedef struct steady_ctx {
    const int *cf_v, *cf_v0; /* rd_sim.cf_v, cf_v0, cf_facing */
    const char *cf_facing;
    const uint64_t *mask; /* side_ctx.mask, dist (vertex_distances) */
    const double *dist;
    int np;                /* the other body's planes */
    const double (*pl)[3]; /* rd_sim.pl, pn, pa, pface, pset, fs, pj, pstate */
    const double (*pn)[3];
    const double *pa;
    const int *pface;
    double *pset;
    double (*fs)[3];
    double (*pj)[2];
    unsigned char *pstate;
    const double (*plane)[4]; /* side_ctx.pl, wn */
    const double (*wn)[3];
    uint64_t cross0;           /* word 0 of the current face's side_ctx.cross, in the context: the
                              state bytes the path stores may alias side_ctx.cross itself */
    const uint64_t *cross;     /* side_ctx.cross, read from word 1 on */
    int facing;                /* the current face is a late one (side_ctx.facing) */
    double tol, wa, damp_coef; /* side_ctx's */
    double kn, ks, tan_phi;    /* the joint's */
    double dt;
    int mean_switch, struck, damped, settling;
    int face_law; /* side_ctx's */
} steady_ctx;

/* The side's steady_ctx (k) from rd_sim, its side_ctx c (after vertex_distances) and joint j. */
static inline __attribute__((always_inline)) void steady_of(const rd_sim *s, const side_ctx *c,
                                                            const rd_joint *j, steady_ctx *k)
{
    k->cf_v = s->cf_v;
    k->cf_v0 = s->cf_v0;
    k->cf_facing = s->cf_facing;
    k->mask = c->mask;
    k->dist = c->dist;
    k->np = c->np;
    k->cross = c->cross;
    k->cross0 = 0;
    k->pl = (const double(*)[3])s->pl;
    k->pn = (const double(*)[3])s->pn;
    k->pa = s->pa;
    k->pface = s->pface;
    k->pset = s->pset;
    k->fs = s->fs;
    k->pj = s->pj;
    k->pstate = s->pstate;
    k->plane = (const double(*)[4])c->pl;
    k->wn = c->wn;
    k->tol = c->tol;
    k->wa = c->wa;
    k->damp_coef = c->damp_coef;
    k->kn = j->kn;
    k->ks = j->ks;
    k->tan_phi = j->tan_phi;
    k->dt = s->dt;
    k->mean_switch = c->mean_switch;
    k->struck = c->struck;
    k->damped = c->damped;
    k->settling = s->settling;
    k->face_law = c->face_law;
}

/* What steady_point found, with the point's state bits after it (face_points counts them from
 * this): NONE, the point needs subcontact (nothing stored); OUT, outside (not RD_PT_INSIDE);
 * IDLE, inside, not bearing; BEARS, inside, bearing, not slipping. */
enum { STEADY_NONE = -1, STEADY_OUT, STEADY_IDLE, STEADY_BEARS };

/* steady_point's point beyond the band (out: its distance beyond the plane, m, more than
 * subcontact's band unbonded, slack 0): one that was already out records its gap; STEADY_OUT,
 * or STEADY_NONE for subcontact. */
static inline __attribute__((always_inline)) int steady_out(const steady_ctx *k, int st,
                                                            unsigned fl, double out)
{
    if (fl & (RD_PT_ACTIVE | RD_PT_INSIDE | RD_PT_SLIP | RD_PT_VIRGIN)) return STEADY_NONE;
    k->pj[st][0] = 0;
    k->pj[st][1] = out;
    k->pset[st] = 0;
    return STEADY_OUT;
}

/* A steady point's kinematics k = (ro, vr) with entrance face e (dz: its ro'_z): under the face
 * law in that face's frame, returned; else in the ground frame from the side's frame fr (NULL). */
static inline __attribute__((always_inline)) face_frame *
steady_kinematics(side_ctx *c, const steady_ctx *k, const side_frame *fr, int e, const double p[3],
                  double dz, double kin[6])
{
    if (!k->face_law) {
        frame_kinematics(fr, p, kin);
        return NULL;
    }
    face_frame *ff = face_frame_at(c, e);
    face_kinematics(ff, p, dz, kin);
    return ff;
}

/* subcontact's common cases, with its arithmetic (the same expressions in the same order, so
 * the same bits) and none of its branches on rare state:
 * - a point beyond the band that was already out: only its gap is recorded;
 * - a point inside that was idle and stays so: above its face within the band, or (no dashpot)
 *   below its permanent set, or on a late face that looks away from its entrance face;
 * - a steady bearing point: inside, bearing last step, no bond, no impact loss this step (not
 *   new, or not unloading), its face not a late one, below its entrance face, compressed, and
 *   within the Coulomb limit;
 * on an elastic joint, none within w/2 of its spring's switch (subcontact's mean force).
 * plain (a constant at each call): the joint has no dashpot and loses energy at impacts (no mean
 * force at a switch), the bodies are not settling and the face is not a late one, so those tests
 * are left out (the bed: 4 % fewer instructions). Returns what it found (STEADY_OUT,
 * STEADY_IDLE, STEADY_BEARS), or STEADY_NONE (nothing stored) when the point needs subcontact. */
static inline __attribute__((always_inline)) int steady_point(rd_sim *s, side_ctx *c,
                                                              const steady_ctx *k, int pt, int st,
                                                              const side_frame *fr, side_sums *a,
                                                              const int nw, const int plain)
{
    const unsigned fl = k->pstate[st];
    const double *p = k->pl[pt];
    if (fl & RD_PT_BONDED) return STEADY_NONE;
    for (int w = 0; w < nw; w++)
        for (uint64_t m = w ? k->cross[w] : k->cross0; m; m &= m - 1) {
            double out = plane_dist(k->plane[64 * w + __builtin_ctzll(m)], p);
            if (out > k->tol + 0.0) return steady_out(k, st, fl, out);
        }
    if (!(fl & RD_PT_INSIDE)) return STEADY_NONE;
    int e = k->pface[st];
    const double dz = rd_dot(k->plane[e], p), depth = -(dz - k->plane[e][3]); /* subcontact's */
    double A = k->wa * k->pa[pt], kA = k->kn * A, sA = k->ks * A;
    const double *u = k->wn[e];
    if (!k->facing && !base_looks(k->pn[pt], k->plane[e]))
        return STEADY_NONE; /* turned away: subcontact */
    if (!plain &&
        k->facing) { /* a late face: only its points that stay idle facing away are common */
        if (fl & (RD_PT_ACTIVE | RD_PT_SLIP) || !(rd_dot(owner_normal(s, c), u) > -RD_FACING_COS))
            return STEADY_NONE;
        k->pj[st][0] = 0;
        k->pj[st][1] = -depth;
        return STEADY_IDLE;
    }
    if ((fl & ~(unsigned)(RD_PT_VIRGIN | RD_PT_IMPACT)) ==
        RD_PT_INSIDE) { /* idle last step (release: nothing) */
        if (!plain &&
            k->mean_switch) { /* an elastic joint's spring that touches within this step (as
                                 subcontact's w): subcontact */
            double kin[6];
            const face_frame *ff = steady_kinematics(c, k, fr, e, p, dz, kin);
            double reach = -0.5 * fabs(ff ? kin[5] : rd_dot(kin + 3, u)) * k->dt;
            if ((depth <= 0 ? depth : depth - k->pset[st]) > reach) return STEADY_NONE;
        }
        if (depth <= 0) { /* above its face, within the band */
            k->pstate[st] = (unsigned char)(fl | RD_PT_VIRGIN);
            k->pset[st] = 0;
        } else if (!(kA * (depth - k->pset[st]) < 0)) {
            return STEADY_NONE; /* touches: subcontact */
        }                       /* else below its permanent set: idle */
        k->pj[st][0] = 0;
        k->pj[st][1] = -depth;
        return STEADY_IDLE;
    }
    if ((fl & ~(unsigned)(RD_PT_SLIP | RD_PT_VIRGIN | RD_PT_IMPACT)) !=
            (RD_PT_INSIDE | RD_PT_ACTIVE) ||
        !(depth > 0))
        return STEADY_NONE;
    double kin[6], *ro = kin, *vr = kin + 3;
    face_frame *ff = steady_kinematics(c, k, fr, e, p, dz, kin);
    double vn = ff ? vr[2] : rd_dot(vr, u);
    if (fl & RD_PT_VIRGIN && vn > 0 && (plain || !k->settling))
        return STEADY_NONE; /* its impact loss: subcontact */
    if (k->struck && vn < 0 && !(fl & RD_PT_VIRGIN)) return STEADY_NONE; /* struck: subcontact */
    double stretch = depth - k->pset[st];
    if (!(stretch >= 0)) return STEADY_NONE; /* below its permanent set: subcontact idles it */
    if (!plain && k->mean_switch && !(stretch >= 0.5 * fabs(vn) * k->dt))
        return STEADY_NONE; /* it lets go within
                                                                                  this step */
    double fel = kA * stretch;
    double fn = fel - k->damp_coef * kA * vn;
    if (!(fn >= 0)) return STEADY_NONE;
    double fs[3] = { k->fs[st][0], k->fs[st][1], k->fs[st][2] };
    double lim = fn * k->tan_phi + 0.0; /* subcontact's, unbonded (no cohesion); fn >= 0, so
                                           rd_max(fn, 0.0) is fn but for -0, whose product + 0.0
                                           is +0 too */
    if (ff) {
        double f0[3];
        face_shear_trial(ff, k->fs[st], vr, sA, k->dt, f0, fs);
    } else {
        rd_law_shear_trial(fs, u, vr, vn, sA, k->dt);
    }
    if (!(rd_dot(fs, fs) <= lim * lim))
        return STEADY_NONE; /* slips: rd_law_shear_cap in subcontact */
    /* the dashpot's work, with last_bore's fd; without a dashpot there is none: fd is exactly 0
       (a bearing point's stored force pj[0] is then its elastic force kA * (depth - set), the
       product repeated here: the tension cap never holds a bearing point's force below it), and
       fn == fel (damp_coef is 0, and a NaN fn went to subcontact above) */
    if (!plain && k->damped) {
        double fd_prev = k->pj[st][0] - kA * (-k->pj[st][1] - k->pset[st]);
        if (fn != fel || fd_prev != 0)
            rd_book_damp(s, rd_law_dashpot_work(fd_prev, fn - fel, vn, k->dt));
    }
    a->k_active += kA;
    k->pstate[st] = (unsigned char)(fl & ~(unsigned)RD_PT_SLIP);
    if ((fl & (RD_PT_VIRGIN | RD_PT_IMPACT)) == (RD_PT_VIRGIN | RD_PT_IMPACT)) c->opens = 1;
    k->pj[st][1] = -depth;
    if (ff)
        bear_face(k->fs, k->pj, a, ff, st, A, fn, fs, ro);
    else
        bear(k->fs, k->pj, a, st, A, fn, u, fs, ro);
    return STEADY_BEARS;
}

/* Forget a pair's contact history (shear forces, entrance faces, sets); bonds are kept. */
static void reset_pair(rd_sim *s, rd_pair *pr)
{
    for (int k = 0; k < pr->nside; k++) {
        const rd_side *sd = &pr->side[k];
        int n = s->pt0[sd->owner + 1] - s->pt0[sd->owner];
        memset(s->fs + sd->state0, 0, (size_t)n * sizeof *s->fs);
        memset(s->pset + sd->state0, 0, (size_t)n * sizeof *s->pset);
        for (int j = 0; j < n; j++) s->pstate[sd->state0 + j] &= RD_PT_BONDED;
        int nf = s->cf0[sd->owner + 1] - s->cf0[sd->owner];
        memset(s->face_nactive + sd->face0, 0, (size_t)nf * sizeof(int));
        rd_edge_reset(s, sd);
    }
    pr->k_active = 0;
}

void rd_contact_reset_body(rd_sim *s, int body)
{
    if (s->surf) rd_surface_reset(s, body);
    for (int p = 0; p < s->npair; p++)
        if (s->pair[p].a == body || s->pair[p].b == body) reset_pair(s, &s->pair[p]);
}

/* Contacts made while settling are seated, not impacts: no impact loss when they first unload. */
void rd_contact_seat(rd_sim *s)
{
    for (int k = 0; k < s->nstate; k++)
        s->pstate[k] &= (unsigned char)~(RD_PT_VIRGIN | RD_PT_STRUCK | RD_PT_IMPACT);
    rd_edge_seat(s);
    memset(s->impacting, 0, (size_t)s->nb);
}

/* rd_sim.impacting from the points' state (a restored run: the image holds no flags of its own):
 * a body takes a new impact when a point of one of its contacts bore last step in the first
 * compression of an impact, as rd_contact_step finds it. */
void rd_contact_find_impacts(rd_sim *s)
{
    memset(s->impacting, 0, (size_t)s->nb);
    for (int p = 0; p < s->npair; p++)
        for (int q = 0; q < s->pair[p].nside; q++) {
            const rd_side *sd = &s->pair[p].side[q];
            int n = s->pt0[sd->owner + 1] - s->pt0[sd->owner];
            for (int k = 0; k < n; k++)
                if ((s->pstate[sd->state0 + k] & (RD_PT_VIRGIN | RD_PT_ACTIVE | RD_PT_IMPACT)) ==
                    (RD_PT_VIRGIN | RD_PT_ACTIVE | RD_PT_IMPACT))
                    s->impacting[sd->owner] = s->impacting[sd->other] = 1;
        }
}

/* Pairs that were live last step but whose boxes no longer overlap lose their history. */
static void reset_departed(rd_sim *s)
{
    for (int k = 0; k < s->nlive_prev; k++) {
        rd_pair *pr = &s->pair[s->live_prev[k]];
        if (pr->seen != s->stamp) reset_pair(s, pr);
    }
}

/* Every point of candidate face cf (k-th of its side) leaves the contact. A point can still be
 * below its entrance face when the whole face has passed beyond another plane of the other
 * body (a drum's rim sliding off the lower drum's edge): its normal spring is released too. */
static void clear_face(rd_sim *s, const side_ctx *c, const rd_side *sd, const rd_joint *j, int cf,
                       int k)
{
    int *na = &s->face_nactive[sd->face0 + k];
    if (*na == 0) return;
    int first = sd->state0 + (s->cf_pt0[cf] - s->pt0[sd->owner]);
    for (int pt = s->cf_pt0[cf], st = first; pt < s->cf_pt0[cf + 1]; pt++, st++) {
        double A = sd->weight * s->pa[pt];
        double stretch = (s->pstate[st] & RD_PT_INSIDE)
                             ? -plane_dist(c->pl[s->pface[st]], s->pl[pt]) - s->pset[st]
                             : 0.0;
        const bore last = last_bore(s, j, st, A);
        point_exit(s, c, pt, st, j->kn * A, j->ks * A, &last, stretch);
    }
    *na = 0;
}

/* The other body's planes in the owner frame (once per side and step). */
static void side_planes(const rd_sim *s, side_ctx *c)
{
    const double *R = s->R[c->o], *xo = s->x[c->o];
    c->np = s->poly[c->t].nf;
    c->wn = s->wn + s->face0[c->t];
    c->wt = (const double(*)[2][3])s->wt + s->face0[c->t];
    for (int k = 0; k < c->np; k++) {
        const double *n = s->wn[s->face0[c->t] + k];
        double *pl = c->pl[k];
        rd_mat_tvec(R, n, pl);
        pl[3] = s->wd[s->face0[c->t] + k] - rd_dot(n, xo);
    }
}

/* Signed distances of the owner's candidate-face vertices (rd_sim.cv) to the other body's
 * planes, each once per side and step (faces share their vertices), and each vertex's plane
 * masks (side_ctx.mask), so that face_planes needs one AND and one OR per vertex and word.
 * Far planes: against a fixed other body (a pedestal), a plane that every candidate vertex
 * cleared by more than RD_FAR_BANDS bands below reach when last measured (rd_side.far, the
 * least clearance far_clear, the owner's pose far_pose) is skipped while the owner's vertices
 * cannot have moved (rd_pairs_drift) more than far_clear - tol / 2 since: each vertex then still
 * lies below reach by tol / 2 (far more than round-off), so both of its bits for that plane are 0
 * (reach < out_band) as the full loop would make them, and no face is culled on that plane, so
 * face_planes never reads the distance left out. The shipped PBR computes 1 of its pedestal's 6
 * planes per vertex and step. Against a free other body (no far planes) the distances run
 * vertex by vertex (vertex_rows). */
#define RD_FAR_BANDS 2.0

/* The owner's candidate vertices in the ground frame: vertex k at (x[k], y[k], z[k]) for a
 * non-convex owner (soa: rd_sim.cv_world, the only vertices its step transforms, integrate.c),
 * else at wv[cv[k]] (rd_sim.wv). */
typedef struct cv_coords {
    const double *x, *y, *z;
    const double (*wv)[3];
    const int *cv;
} cv_coords;

/* Vertex k of v (soa: a constant at each call) into p. */
static inline __attribute__((always_inline)) void cv_vertex(const cv_coords *v, int k,
                                                            const int soa, double p[3])
{
    if (soa) {
        p[0] = v->x[k];
        p[1] = v->y[k];
        p[2] = v->z[k];
    } else {
        const double *w = v->wv[v->cv[k]];
        p[0] = w[0];
        p[1] = w[1];
        p[2] = w[2];
    }
}

/* One plane (n: normal and offset, ground frame) against the ncv candidate vertices v (soa, a
 * constant at each call: cv_vertex): each signed distance into row k of d (np planes a row, this
 * plane's column q), the plane's bit q in each vertex's masks (mk, vertex_distances: beyond
 * band[0] = out_band, above band[1] = reach; set: the plane is the first in its mask word, whose
 * bits it sets, else it adds its bit), and, when track (track and set: constants at each call, so
 * the loop without it carries no dependency chain), the largest distance (NaN sticks), else
 * -INFINITY. */
static inline __attribute__((always_inline)) double
plane_pass(const cv_coords *v, const int soa, int ncv, const double n[4], const double band[2],
           int np, int nw, int q, double *restrict d, uint64_t *restrict mk, int track,
           const int set)
{
    const double n0 = n[0], n1 = n[1], n2 = n[2], dq = n[3], out_band = band[0], reach = band[1];
    const uint64_t bit = (uint64_t)1 << (q & 63);
    uint64_t *mo = mk + (q >> 6), *mc = mk + nw + (q >> 6);
    const size_t stride = 2 * (size_t)nw;
    double hi = -INFINITY;
    for (int k = 0; k < ncv; k++) {
        double x[3];
        cv_vertex(v, k, soa, x);
        const double dl = n0 * x[0] + n1 * x[1] + n2 * x[2] - dq;
        d[k * np + q] = dl;
        if (set) { /* the word's first plane: its bits alone */
            mo[k * stride] = !(dl <= out_band) ? bit : 0;
            mc[k * stride] = dl > reach ? bit : 0;
        } else {
            if (!(dl <= out_band)) mo[k * stride] |= bit; /* NaN too: min skips it */
            if (dl > reach) mc[k * stride] |= bit;        /* NaN not: max skips it */
        }
        if (track && !(dl <= hi)) hi = dl; /* NaN sticks: never far */
    }
    return hi;
}

/* Against a free other body (no far planes to skip): vertex by vertex, each vertex's row of
 * distances to the np planes (coefficients n0, n1, n2, dq, one array each) and its nw mask
 * words in one pass over the planes, the words kept in registers and stored once; each bit is
 * selected from bit[], so the loop runs two planes a vector. The same expression as plane_pass's,
 * so the same bits. A drum-drum side (32 vertices, 18 planes) runs about 15 % faster than plane
 * by plane, whose read-modify-writes of the masks and gathered vertices do not vectorise. */
static inline __attribute__((always_inline)) void
vertex_rows(const cv_coords *v, const int soa, int ncv, const double *n0, const double *n1,
            const double *n2, const double *dq, int np, int nw, double out_band, double reach,
            double *restrict d, uint64_t *restrict mk)
{
    uint64_t bit[64]; /* bit q of a mask word, as a value a vector lane can select */
    for (int q = 0; q < 64 && q < np; q++) bit[q] = (uint64_t)1 << q;
    for (int k = 0; k < ncv; k++) {
        double x[3];
        cv_vertex(v, k, soa, x);
        const double x0 = x[0], x1 = x[1], x2 = x[2];
        double *restrict row = d + (size_t)k * np;
        uint64_t *m = mk + (size_t)k * 2 * (size_t)nw;
        for (int w = 0; w < nw; w++) {
            const int q0 = 64 * w, nq = np - q0 < 64 ? np - q0 : 64;
            uint64_t mo = 0, mc = 0;
            for (int q = 0; q < nq; q++) {
                const double dl = n0[q0 + q] * x0 + n1[q0 + q] * x1 + n2[q0 + q] * x2 - dq[q0 + q];
                row[q0 + q] = dl;
                mo |= !(dl <= out_band) ? bit[q] : 0; /* NaN too: min skips it */
                mc |= dl > reach ? bit[q] : 0;        /* NaN not: max skips it */
            }
            m[w] = mo;
            m[nw + w] = mc;
        }
    }
}

/* vertex_distances from the candidate vertices v (soa: a constant at each call, cv_vertex). */
static inline __attribute__((always_inline)) void
distances_from(const rd_sim *s, side_ctx *c, rd_side *sd, const cv_coords *v, const int soa)
{
    const double(*wn)[3] = s->wn + s->face0[c->t];
    const double *wd = s->wd + s->face0[c->t];
    const int np = c->np, fixed = s->fixed[c->t];
    const double out_band = c->out_band, reach = c->reach;
    const int reuse = fixed && sd->far_clear > 0 &&
                      rd_pairs_drift(s, c->o, sd->far_pose) <= sd->far_clear - 0.5 * c->tol;
    const int nw = (np + 63) / 64, ncv = s->cv0[c->o + 1] - s->cv0[c->o];
    struct rd_plane_scratch *ps = s->plane_scratch;
    double *restrict d = s->cv_dist;
    uint64_t *restrict mk = s->cv_mask;
    c->nw = nw;
    c->dist = s->cv_dist;
    c->mask = s->cv_mask;
    if (!fixed) {
        /* the coefficients of up to one mask word of planes on the stack, of more in scratch */
        double local[4][64];
        double *restrict n0 = nw == 1 ? local[0] : ps->n0,
                         *restrict n1 = nw == 1 ? local[1] : ps->n1,
                         *restrict n2 = nw == 1 ? local[2] : ps->n2,
                         *restrict dq = nw == 1 ? local[3] : ps->dq;
        for (int q = 0; q < np; q++) {
            n0[q] = wn[q][0];
            n1[q] = wn[q][1];
            n2[q] = wn[q][2];
            dq[q] = wd[q];
        }
        if (nw == 1) /* the usual one word, as a constant (the masks' stride) */
            vertex_rows(v, soa, ncv, n0, n1, n2, dq, np, 1, out_band, reach, d, mk);
        else
            vertex_rows(v, soa, ncv, n0, n1, n2, dq, np, nw, out_band, reach, d, mk);
        return;
    }
    /* with one mask word in use (face_planes and edge.c read no others), the first plane measured
       sets each vertex's two words; with more, they are cleared first */
    int set = nw == 1;
    if (!set) memset(mk, 0, (size_t)ncv * 2 * (size_t)nw * sizeof *mk);
    double *dmax = ps->dmax; /* the largest distance to each plane, wanted only to find the far
                                planes (a fixed other body, every plane measured) */
    const int track = fixed && !reuse;
    /* plane by plane (all, or the near ones), each a pass over the vertices: with few planes
       (a pedestal's one near plane) the loop is all vertices, none of its overhead per plane */
    for (int q = 0; q < np; q++) {
        dmax[q] = -INFINITY;
        if (reuse && q < 64 * RD_FAR_WORDS && ((sd->far[q >> 6] >> (q & 63)) & 1)) continue;
        const double n[4] = { wn[q][0], wn[q][1], wn[q][2], wd[q] }, band[2] = { out_band, reach };
        if (set)
            dmax[q] = track ? plane_pass(v, soa, ncv, n, band, np, nw, q, d, mk, 1, 1)
                            : plane_pass(v, soa, ncv, n, band, np, nw, q, d, mk, 0, 1);
        else
            dmax[q] = track ? plane_pass(v, soa, ncv, n, band, np, nw, q, d, mk, 1, 0)
                            : plane_pass(v, soa, ncv, n, band, np, nw, q, d, mk, 0, 0);
        set = 0;
    }
    if (set) /* no plane measured: no bits */
        for (int k = 0; k < ncv; k++) mk[k * 2 * nw] = mk[k * 2 * nw + nw] = 0;
    if (track) { /* every plane measured: the far ones, from this pose */
        sd->far_clear = INFINITY;
        for (int w = 0; w < RD_FAR_WORDS; w++) sd->far[w] = 0;
        for (int q = 0; q < np && q < 64 * RD_FAR_WORDS; q++) {
            double clear = reach - dmax[q];
            if (!(clear > RD_FAR_BANDS * c->tol)) continue;
            sd->far[q >> 6] |= (uint64_t)1 << (q & 63);
            sd->far_clear = rd_min(sd->far_clear, clear);
        }
        if (!isfinite(sd->far_clear)) sd->far_clear = 0; /* none far (or no vertex) */
        rd_copy3(s->x[c->o], sd->far_pose);
        for (int k = 0; k < 4; k++) sd->far_pose[3 + k] = s->q[c->o][k];
    }
}

/* The side's candidate-vertex distances and plane masks (see above RD_FAR_BANDS), a non-convex
 * owner's vertices read from rd_sim.cv_world, a convex one's from rd_sim.wv. */
RD_HOT static void vertex_distances(const rd_sim *s, side_ctx *c, rd_side *sd)
{
    const int k0 = s->cv0[c->o], ncv_all = s->cv0[s->nb];
    if (!s->convex[c->o]) {
        const double *x = s->cv_world + k0;
        const cv_coords v = { .x = x, .y = x + ncv_all, .z = x + 2 * ncv_all };
        distances_from(s, c, sd, &v, 1);
    } else {
        const cv_coords v = { .wv = s->wv, .cv = s->cv + k0 };
        distances_from(s, c, sd, &v, 0);
    }
}

/* Word w of candidate face cf's plane masks (its vertices' mask offsets, nv of them): the planes
 * every vertex lies beyond by more than out_band (*out), the planes some vertex lies above reach
 * (*cross). Out of line: the common triangle and quadrilateral are face_planes' own. */
static __attribute__((noinline)) void face_masks(const uint64_t *mask, const int *mo, int nv, int w,
                                                 int nw, uint64_t *out, uint64_t *cross)
{
    uint64_t o = ~(uint64_t)0, x = 0;
    for (int v = 0; v < nv; v++) {
        const uint64_t *mk = mask + (size_t)mo[v] * (size_t)nw;
        o &= mk[w];
        x |= mk[nw + w];
    }
    *out = o;
    *cross = x;
}

/* Planes that some point of candidate face cf may lie beyond by more than the band (some vertex
 * above reach: side_ctx.cross); 0, or 1 when the whole face lies outside one plane (no point can
 * touch), with *gap the face's clearance from the first such plane, m. As a loop over planes of
 * the least and largest vertex distance (NaN skipped) against the bands, from the vertices' plane
 * masks (rd_sim.cf_v: the offsets of the face's vertices' masks), read through k (steady_ctx);
 * the face's kind and plane bits into k and c: subcontact, out of line, reads c's (handed k, its
 * address would escape, and every state byte the steady path stores would load k's fields again). */
static inline int face_planes(const rd_sim *s, side_ctx *c, steady_ctx *k, int cf, double *gap,
                              const int nw)
{
    const int *mo = k->cf_v + k->cf_v0[cf], nv = k->cf_v0[cf + 1] - k->cf_v0[cf];
    k->facing = c->facing = k->cf_facing[cf];
    if (k->facing) { /* owner_normal: only a late face's points ask for the face's normal */
        c->m = NULL;
        c->mf = s->cf_face[cf];
    }
    for (int w = 0; w < nw; w++) {
        uint64_t out, cross;
        if (nv == 3) { /* a mesh's triangle */
            const uint64_t *m0 = k->mask + (size_t)mo[0] * (size_t)nw + w;
            const uint64_t *m1 = k->mask + (size_t)mo[1] * (size_t)nw + w;
            const uint64_t *m2 = k->mask + (size_t)mo[2] * (size_t)nw + w;
            out = m0[0] & m1[0] & m2[0];
            cross = m0[nw] | m1[nw] | m2[nw];
        } else if (nv == 4) { /* a brick's face */
            const uint64_t *m0 = k->mask + (size_t)mo[0] * (size_t)nw + w;
            const uint64_t *m1 = k->mask + (size_t)mo[1] * (size_t)nw + w;
            const uint64_t *m2 = k->mask + (size_t)mo[2] * (size_t)nw + w;
            const uint64_t *m3 = k->mask + (size_t)mo[3] * (size_t)nw + w;
            out = m0[0] & m1[0] & m2[0] & m3[0];
            cross = m0[nw] | m1[nw] | m2[nw] | m3[nw];
        } else {
            face_masks(k->mask, mo, nv, w, nw, &out, &cross);
        }
        if (out) { /* every vertex beyond plane q */
            int q = 64 * w + __builtin_ctzll(out);
            double emin = DBL_MAX;
            for (int v = 0; v < nv; v++)
                emin = rd_min(k->dist[(size_t)(mo[v] / 2) * (size_t)k->np + q], emin);
            *gap = emin - c->raise;
            return 1;
        }
        c->cross[w] = cross;
        if (!w) k->cross0 = cross;
    }
    return 0;
}

/* The points pt0 .. pt1 - 1 of a candidate face (point pt's subcontact: pt + dst), each by
 * steady_point (plain: its), else subcontact; their forces into *a, the side's bearing and
 * slipping counts into *na and *nslip. Returns the face's points inside. */
static inline __attribute__((always_inline)) int
face_points(rd_sim *s, side_ctx *c, const rd_joint *j, const steady_ctx *k, int pt0, int pt1,
            int dst, const side_frame *fr, side_sums *a, int *na, int *nslip, const int nw,
            const int plain)
{
    int nin = 0, nbear = 0, nsl = 0; /* counts in locals: no state byte store reaches them */
    for (int pt = pt0; pt < pt1; pt++) {
        const int st = pt + dst;
        const int found =
            RD_STEADY_PATH ? steady_point(s, c, k, pt, st, fr, a, nw, plain) : STEADY_NONE;
        if (found == STEADY_NONE) {
            if (subcontact(s, c, j, pt, st, a)) {
                ++nbear;
                nsl += (k->pstate[st] & RD_PT_SLIP) != 0;
            }
            nin += (k->pstate[st] & RD_PT_INSIDE) != 0;
        } else { /* its bits as steady_point left them */
            nbear += found == STEADY_BEARS;
            nin += found != STEADY_OUT;
        }
    }
    *na += nbear;
    *nslip += nsl;
    return nin;
}

/* The candidate faces of a side (side_step's context c), each tested against the other body
 * (face_planes), then its points (steady_point, else subcontact); their forces summed into
 * *sums, the contact tally into *tally and the active point-steps into *active_steps. The tally
 * takes each face's bearing area in face order (a face's own sum first, as the monitor's area
 * always was), its counts and whether it touched once for the side; area_to: NULL, or on a
 * thread's view (workers.h) the monitored body's area, to which each face's area is booked
 * instead. nw: the mask words in use (a constant at each call: 1 word for most bodies). */
static inline __attribute__((always_inline)) void side_faces(rd_sim *s, side_ctx *c, rd_side *sd,
                                                             const rd_joint *j, side_sums *sums,
                                                             rd_watch *tally, long *active_steps,
                                                             double *area_to, const int nw)
{
    const side_frame fr = c->fr; /* locals no store into rd_sim reaches */
    side_sums a = *sums;
    steady_ctx k;
    steady_of(s, c, j, &k);
    const int dst = sd->state0 - s->pt0[c->o]; /* a point's subcontact, less its index */
    int na = 0, nslip = 0, touch = 0;
    double area = tally->area;
    /* the loop's bounds and arrays in locals: rd_sim's fields are reloaded after every byte store */
    const int cf0 = s->cf0[c->o], ncf = s->cf0[c->o + 1] - cf0;
    const int *pt0 = s->cf_pt0 + cf0;
    int *nactive = s->face_nactive + sd->face0;
    const int plain =
        !k.mean_switch && !k.damped && !k.settling; /* steady_point's, but for late faces */
    for (int f = 0; f < ncf; f++) {
        const int cf = cf0 + f;
        double gap;
        if (face_planes(s, c, &k, cf, &gap, nw)) {
            clear_face(s, c, sd, j, cf, f);
            rd_joint_face_open(s, sd, cf, gap);
            continue;
        }
        a.area = 0;
        /* a mesh's face carries about one point: a copy of face_points for it, with no loop; and
           copies for plain faces (steady_point) */
        const int p0 = pt0[f], p1 = pt0[f + 1];
        if (plain && !k.facing)
            nactive[f] =
                p1 - p0 == 1
                    ? face_points(s, c, j, &k, p0, p0 + 1, dst, &fr, &a, &na, &nslip, nw, 1)
                    : face_points(s, c, j, &k, p0, p1, dst, &fr, &a, &na, &nslip, nw, 1);
        else
            nactive[f] =
                p1 - p0 == 1
                    ? face_points(s, c, j, &k, p0, p0 + 1, dst, &fr, &a, &na, &nslip, nw, 0)
                    : face_points(s, c, j, &k, p0, p1, dst, &fr, &a, &na, &nslip, nw, 0);
        if (!area_to)
            area += a.area;
        else if (a.area != 0) /* a thread's view: each face's area booked to the watch's */
            rd_tape_add(s->tape, area_to, a.area);
        touch |= a.area > 0;
    }
    if (c->face_law) fold_face_sums(s, c, &a);
    *sums = a;
    tally->area = area;
    tally->nactive += na;
    tally->nslip += nslip;
    if (touch && s->shaking) tally->touched = 1;
    *active_steps += na;
}

RD_HOT static void side_step(rd_sim *s, rd_pair *pr, rd_side *sd, double *k_active, double nsum[3])
{
    const rd_joint *j = &s->joint[pr->joint];
    side_ctx c;
    c.o = sd->owner;
    c.t = sd->other;
    c.wa = sd->weight;
    c.to_b = sd->owner == pr->b ? 1.0 : -1.0;
    c.damp_coef = 0;
    c.damped = j->damping > 0;
    c.struck = j->restitution < 1 && !s->settling && (s->impacting[c.o] || s->impacting[c.t]);
    c.opens = 0;
    c.mean_switch = j->restitution >= 1;
    c.pr = pr;
    /* the contact band (3DEC's contact tolerance, a fraction of the bodies' size): a point up
       to this far beyond the other body's edge still bears on it (the corners of two equal
       blocks lying on each other, twisted or slid by a hair), and one hovering this close
       above a face is already attached to it (with no force until it touches) */
    c.tol = RD_CONTACT_BAND * fmin(s->poly[c.o].radius, s->poly[c.t].radius);
    if (j->damping > 0 && !s->settling) {
        double K = pr->k_active > 0 ? pr->k_active : INFINITY; /* a new contact: undamped step */
        c.damp_coef = 2.0 * j->damping * sqrt(pr->m_eff / K);
    }
    double slack = s->bonds ? j->tension / j->kn : 0.0;
    c.raise = s->sc.contact.perturb.raise;
    c.out_band = c.tol + slack + c.raise;
    c.reach = 0.5 * c.tol - c.raise;
    c.t_free = !s->fixed[c.t];
    struct rd_plane_scratch *ps = s->plane_scratch;
    c.face_law = !c.t_free;
    c.ff = ps->ff; /* found as used (face_frame_at) */
    c.pl = ps->pl;
    c.cross = ps->cross;
    c.ff_used = ps->ff_used;
    c.nw = (s->poly[c.t].nf + 63) / 64;
    memset(c.ff_used, 0, (size_t)c.nw * sizeof *c.ff_used);
    /* against a fixed body the owner's sums run on from its force and torque so far; a free
       other body's share needs the side's own sums, which then start at 0 */
    side_sums sums = {
        .f_o = { 0, 0, 0 }, .tq_o = { 0, 0, 0 }, .nsum = { 0, 0, 0 }, .k_active = 0, .area = 0
    };
    if (!c.t_free && !s->tape) { /* (a thread's view books each face's share: fold_face_sums) */
        rd_copy3(s->f[c.o], sums.f_o);
        rd_copy3(s->tq[c.o], sums.tq_o);
    }
    double d[3]; /* xo - xt, m */
    side_frame_of(s, c.o, c.t, &c.fr, d);
    side_planes(s, &c);
    vertex_distances(s, &c, sd);
    s->kin_epoch++;
    /* the side's contact tally and its active point-steps, carried in locals and stored once */
    rd_watch *watch = rd_monitor_contact_watch(s, c.o, c.t);
    rd_watch tally = { 0 };
    double *area_to = watch && s->tape ? &watch->area : NULL; /* a thread's view: booked */
    if (watch && !s->tape) {
        tally.area = watch->area;
        tally.nactive = watch->nactive;
        tally.nslip = watch->nslip;
        tally.touched = watch->touched;
    }
    long active_steps = 0;
    if (c.nw == 1) /* the usual one word of planes (up to 64), as a constant */
        side_faces(s, &c, sd, j, &sums, &tally, &active_steps, area_to, 1);
    else
        side_faces(s, &c, sd, j, &sums, &tally, &active_steps, area_to, c.nw);
    if (watch && !s->tape) {
        watch->area = tally.area;
        watch->nactive = tally.nactive;
        watch->nslip = tally.nslip;
        watch->touched = tally.touched;
    } else if (watch) { /* a thread's view: the counts added, touched set, the area booked */
        rd_count(s, &watch->nactive, tally.nactive);
        rd_count(s, &watch->nslip, tally.nslip);
        if (tally.touched) __atomic_store_n(&watch->touched, 1, __ATOMIC_RELAXED);
    }
    if (c.opens && !s->settling) { /* (a flag other pairs may set too: stored atomically) */
        __atomic_store_n(&s->impacting_next[c.o], 1, __ATOMIC_RELAXED);
        __atomic_store_n(&s->impacting_next[c.t], 1, __ATOMIC_RELAXED);
    }
    if (!s->settling) s->active_point_steps += active_steps;
    if (c.t_free) { /* the owner takes the sums; the other -F at ro + d each:
                       -(sum ro x F) - d x sum F (a thread's view books the same additions) */
        double dt[3];
        rd_cross(d, sums.f_o, dt);
        if (s->tape) {
            double tt[3];
            for (int k = 0; k < 3; k++) tt[k] = -(sums.tq_o[k] + dt[k]);
            rd_tape_pair(s->tape, c.o, c.t, sums.f_o, sums.tq_o, tt);
        } else {
            rd_axpy(1.0, sums.f_o, s->f[c.o]);
            rd_axpy(1.0, sums.tq_o, s->tq[c.o]);
            rd_axpy(-1.0, sums.f_o, s->f[c.t]);
            for (int k = 0; k < 3; k++) s->tq[c.t][k] -= sums.tq_o[k] + dt[k];
        }
    } else if (!s->tape) {
        rd_copy3(sums.f_o, s->f[c.o]);
        rd_copy3(sums.tq_o, s->tq[c.o]);
    }
    *k_active += sums.k_active;
    rd_axpy(c.to_b, sums.nsum, nsum); /* to_b = +-1: +-(fn u) summed, exactly */
}

struct rd_plane_scratch *rd_contact_scratch(const rd_sim *s)
{
    const size_t np = s->np_max > 0 ? (size_t)s->np_max : 1, mw = (np + 63) / 64;
    struct rd_plane_scratch *ps =
        calloc(1, sizeof *ps + np * sizeof *ps->ff + np * (4 + 5) * sizeof(double) +
                      2 * mw * sizeof(uint64_t));
    if (!ps) return NULL;
    /* the struct, then its arrays: each a whole number of 8-byte words */
    ps->ff = (face_frame *)(ps + 1);
    ps->pl = (double(*)[4])(ps->ff + np);
    ps->n0 = (double *)(ps->pl + np);
    ps->n1 = ps->n0 + np;
    ps->n2 = ps->n1 + np;
    ps->dq = ps->n2 + np;
    ps->dmax = ps->dq + np;
    ps->cross = (uint64_t *)(ps->dmax + np);
    ps->ff_used = ps->cross + mw;
    return ps;
}

void rd_contact_pair(rd_sim *s, rd_pair *pr)
{
    double k_active = 0, nsum[3] = { 0, 0, 0 };
    double e_pair[2] = { 0, 0 }; /* the pair's friction and damping energy this step, J */
    s->e_pair = e_pair;
    for (int q = 0; q < pr->nside; q++) {
        side_step(s, pr, &pr->side[q], &k_active, nsum);
        /* edge subcontacts (edge.c): with two sides, this side's owner's edges against the
           other body, from the vertex distances side_step has just found */
        if (pr->nside == 2)
            rd_edge_side(s, pr, &pr->side[1 - q], s->cv_dist, s->cv_mask);
        else
            rd_edge_side(s, pr, &pr->side[q], NULL, NULL);
    }
    s->e_pair = NULL;
    rd_sim *sim = s->tape ? s->tape->sim : s; /* on a thread's view: the simulation's totals */
    if (e_pair[0] != 0) rd_book(s, &sim->e_fric, e_pair[0]);
    if (e_pair[1] != 0) rd_book(s, &sim->e_damp, e_pair[1]);
    pr->k_active = k_active;
    double nn = rd_norm(nsum);
    if (nn > 0)
        for (int k = 0; k < 3; k++) pr->n[k] = nsum[k] / nn;
}

/* Broad phase, then every live pair's subcontact forces. 0, or -1 when the broad phase ran out
 * of memory growing the pair cache, or the threads their tapes (workers.c). */
int rd_contact_step(rd_sim *s)
{
    if (rd_pairs_update(s)) return -1;
    if (s->surf)
        rd_surface_step(s); /* `contact model surface` */
    else
        reset_departed(s);
    /* the live pairs on the run's threads (workers.c), else here */
    const int threaded = s->surf ? 0 : rd_workers_contact(s);
    if (threaded < 0) return -1;
    for (int k = 0; !s->surf && !threaded && k < s->nlive; k++)
        rd_contact_pair(s, &s->pair[s->live[k]]);
    unsigned char *im = s->impacting; /* this step's new impacts, for the next step */
    s->impacting = s->impacting_next;
    s->impacting_next = im;
    memset(s->impacting_next, 0, (size_t)s->nb);
    int *t = s->live_prev;
    s->live_prev = s->live;
    s->live = t;
    int c = s->cap_live_prev;
    s->cap_live_prev = s->cap_live;
    s->cap_live = c;
    s->nlive_prev = s->nlive;
    return 0;
}

/* Spring energy of the subcontacts that bore force at the last contact step, J: over its live
 * pairs (rd_contact_step leaves them in live_prev), Fel^2 / (2 KN A') + |Fs|^2 / (2 KS A') with
 * Fel = KN A' (depth - set). Evaluated from the stored spring state only when an energy sample
 * is taken, so the contact loop carries no division. */
double rd_contact_elastic_energy(const rd_sim *s)
{
    if (s->surf) return rd_surface_elastic_energy(s);
    double e = 0;
    for (int k = 0; k < s->nlive_prev; k++) {
        const rd_pair *pr = &s->pair[s->live_prev[k]];
        const rd_joint *j = &s->joint[pr->joint];
        for (int q = 0; q < pr->nside; q++) {
            const rd_side *sd = &pr->side[q];
            e += rd_edge_elastic_energy(s, pr, sd);
            for (int pt = s->pt0[sd->owner], st = sd->state0; pt < s->pt0[sd->owner + 1];
                 pt++, st++) {
                if (!(s->pstate[st] & RD_PT_ACTIVE)) continue;
                double A = sd->weight * s->pa[pt], kA = j->kn * A, sA = j->ks * A;
                double stretch = -s->pj[st][1] - s->pset[st]; /* pj[1]: minus the depth */
                e += 0.5 * (kA * stretch * stretch + rd_dot(s->fs[st], s->fs[st]) / sA);
            }
        }
    }
    return e;
}
