/* rockdem — a scenario as a rigid reference model (Housner or Kounadis): mapping and solving.
 * See include/rockdem/validate.h for the rules; every refusal names what does not fit.
 * Folder reference/ owns the rigid CVODE reference solvers (Housner, Kounadis); it may call
 * base/, records/, io/ and the public API (rd_check_scene of engine/check.c: a body that is no
 * brick, for its Housner equivalent).
 */
#include "rockdem/validate.h"
#include "rockdem/check.h"

#include <math.h>
#include <string.h>

#define RD_FIT_TOL 1e-6 /* relative tolerance on positions (blocks resting on each other), - */

/* Ground acceleration along the rocking direction and vertical, m/s^2. */
static void refscene_ground(void *ctx, double t, double *ug, double *vg)
{
    const rd_refscene *rs = ctx;
    double a[3], v[3], d[3];
    rd_motion_eval(&rs->motion, t, a, v, d);
    *ug = a[0] * rs->dir[0] + a[1] * rs->dir[1];
    *vg = a[2];
}

static double body_mass(const rd_scenario *sc, const rd_body_def *b)
{
    double vol = b->size[0] * b->size[1] * b->size[2];
    return b->mass > 0 ? b->mass : (b->density > 0 ? b->density : sc->density) * vol;
}

/* Unit direction (multiple of 90 degrees) from an angle, or -1 when it is oblique. */
static int axis_direction(double ang, double dir[2])
{
    double c = cos(ang), s = sin(ang);
    if (fabs(c) > 1 - 1e-9) {
        dir[0] = c > 0 ? 1 : -1;
        dir[1] = 0;
        return 0;
    }
    if (fabs(s) > 1 - 1e-9) {
        dir[0] = 0;
        dir[1] = s > 0 ? 1 : -1;
        return 0;
    }
    return -1;
}

/* What a body is, for the sentence that refuses a shape the planar models cannot describe. */
static const char *shape_words(rd_shape_kind k)
{
    switch (k) {
    case RD_SHAPE_PRISM: return "a prism (a drum)";
    case RD_SHAPE_HULL: return "a convex hull of points";
    case RD_SHAPE_MESH: return "a triangle mesh";
    default: return "a brick";
    }
}

/* The planar models know rectangular blocks only: each body's width and height come from its
 * brick size, the base's top from its height. */
static int check_shape(const rd_scenario *sc, const rd_body_def *b, rd_error *err)
{
    if (b->shape == RD_SHAPE_BRICK) return 0;
    return rd_error_set(err,
                        "%s:%d: reference: body '%s' is %s; the Housner and Kounadis models "
                        "describe rectangular bricks only (`block create brick`, `block "
                        "create stack`)",
                        sc->file, b->line, b->name, shape_words(b->shape));
}

static int check_brick(const rd_scenario *sc, const rd_body_def *b, rd_error *err)
{
    if (check_shape(sc, b, err)) return -1;
    if (b->rotation[0] != 0 || b->rotation[1] != 0 || b->rotation[2] != 0)
        return rd_error_set(err,
                            "%s:%d: reference: body '%s' is rotated; the reference solvers "
                            "need axis-aligned bricks",
                            sc->file, b->line, b->name);
    for (int k = 0; k < 3; k++)
        if (b->velocity[k] != 0 || b->angular_velocity[k] != 0)
            return rd_error_set(err,
                                "%s:%d: reference: body '%s' has an initial velocity; the "
                                "reference solvers start from rest or a tilt",
                                sc->file, b->line, b->name);
    return 0;
}

/* Rocking direction: the horizontal pulse's, else the tilt's, else +x. */
static int choose_direction(const rd_scenario *sc, const rd_body_def *blk, rd_refscene *rs,
                            rd_error *err)
{
    const rd_pulse_def *hp = &sc->motion.horizontal;
    double ang = hp->kind != RD_PULSE_NONE ? hp->direction
                 : blk->tilt > 0           ? blk->tilt_direction
                                           : 0;
    if (axis_direction(ang, rs->dir))
        return rd_error_set(err,
                            "%s: reference: the rocking direction %.4g deg is oblique to the "
                            "bricks; the planar reference needs 0, 90, 180 or 270 deg",
                            sc->file, ang * 180 / M_PI);
    rs->theta0 = 0;
    if (blk->tilt > 0) {
        double c = cos(blk->tilt_direction) * rs->dir[0] + sin(blk->tilt_direction) * rs->dir[1];
        if (fabs(fabs(c) - 1) > 1e-9)
            return rd_error_set(err,
                                "%s:%d: reference: body '%s' is tilted out of the rocking "
                                "plane",
                                sc->file, blk->line, blk->name);
        rs->theta0 = c > 0 ? blk->tilt : -blk->tilt;
    }
    return 0;
}

/* Half-width along dir and half-height of brick k; position of its base, m. */
static void block_dims(rd_refscene *rs, int k, const rd_body_def *b)
{
    memcpy(rs->size[k], b->size, sizeof b->size);
    rs->b[k] = 0.5 * (rs->dir[0] != 0 ? b->size[0] : b->size[1]);
    rs->h[k] = 0.5 * b->size[2];
}

/* Height of a brick's base, m: seated bodies (`seat-on`, `block create stack`) are placed by
 * the engine with their base on the top of their support (at z = top). */
static double brick_bottom(const rd_body_def *blk, const rd_body_def *base, double top)
{
    if (blk->seat_on[0] && !strcmp(blk->seat_on, base->name)) return top;
    return blk->position[2] - 0.5 * blk->size[2];
}

static int check_support(const rd_scenario *sc, const rd_body_def *base, const rd_body_def *blk,
                         double top, double scale, rd_error *err)
{
    double bottom = brick_bottom(blk, base, top);
    if (fabs(bottom - top) > RD_FIT_TOL * scale)
        return rd_error_set(err,
                            "%s:%d: reference: body '%s' does not stand on '%s' (its base is "
                            "at z = %.6g m, the support at %.6g m)",
                            sc->file, blk->line, blk->name, base->name, bottom, top);
    for (int k = 0; k < 2; k++)
        if (fabs(blk->position[k] - base->position[k]) + 0.5 * blk->size[k] >
            0.5 * base->size[k] + RD_FIT_TOL * scale)
            return rd_error_set(err,
                                "%s:%d: reference: body '%s' overhangs '%s'; the reference "
                                "needs a support at least as wide",
                                sc->file, blk->line, blk->name, base->name);
    return 0;
}

static int count_bodies(const rd_scenario *sc, int *fixed, int free_idx[2], int *nfree,
                        rd_error *err)
{
    int nfix = 0;
    *nfree = 0;
    for (int i = 0; i < sc->nbodies; i++) {
        if (sc->bodies[i].fixed) {
            *fixed = i;
            nfix++;
        } else if (*nfree < 2)
            free_idx[(*nfree)++] = i;
        else
            (*nfree)++;
    }
    if (nfix != 1 || *nfree < 1 || *nfree > 2)
        return rd_error_set(err,
                            "%s: reference: this scene has %d fixed and %d free bodies; the "
                            "reference solvers take one fixed base with one free brick "
                            "(Housner) or two stacked free bricks (Kounadis)",
                            sc->file, nfix, *nfree);
    return 0;
}

/* Breaks of the pulses (starts and ends) and the ground's evaluation, for either model. */
static void ground_of(const rd_scenario *sc, rd_refscene *rs)
{
    size_t nb = 0;
    const rd_pulse_def *p[2] = { &sc->motion.horizontal, &sc->motion.vertical };
    rs->motion = sc->motion;
    for (int k = 0; k < 2; k++)
        if (p[k]->kind != RD_PULSE_NONE) {
            rs->breaks[nb++] = p[k]->start;
            rs->breaks[nb++] = rd_pulse_end(p[k]);
        }
    /* records (if any) enter through rd_motion_eval; the ground is quiet after all motion */
    double quiet = rd_motion_end(&rs->motion);
    rs->ground = (rd_ground){ .fn = quiet > 0 ? refscene_ground : NULL,
                              .ctx = rs,
                              .breaks = rs->breaks,
                              .nbreaks = nb,
                              .t_quiet = quiet };
}

/* One free body that is no brick, standing on the fixed base: Housner's equation with its own
 * alpha and p along the shaking (rd_check_scene: its support polygon, centre of mass, R and
 * pivot inertia as placed), as the rectangle b = R_eq sin(alpha), h = R_eq cos(alpha) of the
 * same alpha and p (R_eq = 3 g / 4 p^2: the rectangle's p = sqrt(3 g / 4 R)); its impacts keep
 * the rigid impact's r = 1 - 2 p^2 R sin^2(alpha) / g with its own R, unless the scenario sets
 * `model reference restitution`. */
static int map_equivalent(const rd_scenario *sc, int ibase, int ifree, rd_refscene *rs,
                          rd_error *err)
{
    const rd_body_def *blk = &sc->bodies[ifree], *base = &sc->bodies[ibase];
    if (check_shape(sc, base, err) || choose_direction(sc, blk, rs, err)) return -1;
    rd_check_report rep;
    if (rd_check_scene(sc, &rep, err)) return -1;
    const rd_check_body *cb = &rep.body[ifree];
    double alpha = cb->alpha_tower, p = cb->p_tower, R = cb->R_tower, m = cb->mass;
    int rests = cb->rests_on == ibase;
    rd_check_free(&rep);
    if (!rests)
        return rd_error_set(err,
                            "%s:%d: reference: body '%s' does not rest on the fixed base as placed",
                            sc->file, blk->line, blk->name);
    if (!(alpha > 0 && p > 0))
        return rd_error_set(
            err, "%s:%d: reference: body '%s' has no tipping angle along the shaking (%.3g deg)",
            sc->file, blk->line, blk->name, alpha * 180 / M_PI);
    double Req = 3 * sc->gravity / (4 * p * p);
    rs->equivalent = 1;
    rs->R_own = R;
    rs->nblock = 1;
    rs->body[0] = ifree;
    rs->out[0] = 0;
    rs->mass[0] = m;
    rs->b[0] = Req * sin(alpha);
    rs->h[0] = Req * cos(alpha);
    rs->size[0][0] = rs->size[0][1] = 2 * rs->b[0];
    rs->size[0][2] = 2 * rs->h[0];
    rs->origin[0] = blk->position[0];
    rs->origin[1] = blk->position[1];
    rs->base_z = base->position[2] + 0.5 * base->size[2];
    rs->alpha = alpha;
    rs->p = p;
    double sa = sin(alpha), r = 1 - 2 * p * p * R * sa * sa / sc->gravity;
    rs->model = RD_REFMODEL_HOUSNER;
    rs->housner = (rd_housner_def){ .b = rs->b[0],
                                    .h = rs->h[0],
                                    .g = sc->gravity,
                                    .e = sc->ref_restitution >= 0 ? sc->ref_restitution : r };
    ground_of(sc, rs);
    return 0;
}

int rd_refscene_map(const rd_scenario *sc, rd_refscene *rs, rd_error *err)
{
    memset(rs, 0, sizeof *rs);
    int ibase = -1, fr[2] = { 0, 0 }, nfree;
    if (count_bodies(sc, &ibase, fr, &nfree, err)) return -1;
    if (nfree == 1 && sc->bodies[fr[0]].shape != RD_SHAPE_BRICK)
        return map_equivalent(sc, ibase, fr[0], rs, err);
    const rd_body_def *base = &sc->bodies[ibase];
    if (check_shape(sc, base, err)) return -1;
    /* block 1 is the lower of the free bricks */
    if (nfree == 2 && sc->bodies[fr[1]].position[2] < sc->bodies[fr[0]].position[2]) {
        int t = fr[0];
        fr[0] = fr[1];
        fr[1] = t;
    }
    for (int k = 0; k < nfree; k++) {
        if (check_brick(sc, &sc->bodies[fr[k]], err)) return -1;
        rs->body[k] = fr[k];
        rs->out[k] = nfree == 2 && fr[k] > fr[1 - k]; /* free bodies keep scenario order */
        rs->mass[k] = body_mass(sc, &sc->bodies[fr[k]]);
    }
    const rd_body_def *b1 = &sc->bodies[fr[0]];
    if (choose_direction(sc, b1, rs, err)) return -1;
    double scale = b1->size[2];
    rs->base_z = base->position[2] + 0.5 * base->size[2];
    if (check_support(sc, base, b1, rs->base_z, scale, err)) return -1;
    rs->nblock = nfree;
    rs->origin[0] = b1->position[0];
    rs->origin[1] = b1->position[1];
    for (int k = 0; k < nfree; k++) block_dims(rs, k, &sc->bodies[fr[k]]);
    rs->motion = sc->motion;
    rs->alpha = rd_housner_alpha(rs->b[0], rs->h[0]);
    rs->p = rd_housner_p(rs->b[0], rs->h[0], sc->gravity);
    if (nfree == 1) {
        rs->model = RD_REFMODEL_HOUSNER;
        rs->housner = (rd_housner_def){
            .b = rs->b[0], .h = rs->h[0], .g = sc->gravity, .e = sc->ref_restitution
        };
    } else {
        const rd_body_def *b2 = &sc->bodies[fr[1]];
        if (b1->tilt > 0 || b2->tilt > 0)
            return rd_error_set(err,
                                "%s: reference: initial tilts of a stack are not supported; "
                                "start the stack from rest",
                                sc->file);
        double top1 = brick_bottom(b1, base, rs->base_z) + b1->size[2];
        if (check_support(sc, b1, b2, top1, scale, err)) return -1;
        if (fabs(b2->position[0] - b1->position[0]) + fabs(b2->position[1] - b1->position[1]) >
            RD_FIT_TOL * scale)
            return rd_error_set(err,
                                "%s:%d: reference: the upper block '%s' is not centred on the "
                                "lower one",
                                sc->file, b2->line, b2->name);
        rs->model = RD_REFMODEL_KOUNADIS;
        rs->kounadis = (rd_kounadis_def){ .b1 = rs->b[0],
                                          .h1 = rs->h[0],
                                          .m1 = rs->mass[0],
                                          .b2 = rs->b[1],
                                          .h2 = rs->h[1],
                                          .m2 = rs->mass[1],
                                          .g = sc->gravity,
                                          .r = sc->ref_restitution };
    }
    ground_of(sc, rs);
    return 0;
}

int rd_refscene_solve(const rd_scenario *sc, const rd_refscene *rs, rd_ref_result *res,
                      rd_error *err)
{
    rd_ref_opts o = rd_ref_opts_default();
    o.t_end = sc->duration;
    o.dt_out = sc->output.interval;
    o.theta0[0] = o.theta0[1] = rs->theta0;
    if (rs->model == RD_REFMODEL_HOUSNER)
        return rd_housner_solve(&rs->housner, &rs->ground, &o, res, err);
    return rd_kounadis_solve(&rs->kounadis, &rs->ground, &o, res, err);
}
