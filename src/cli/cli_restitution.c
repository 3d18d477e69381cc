/* rockdem — `rockdem restitution SCENARIO [--target r] [--theta0 rad] [--set k=v]...`:
 * the DEM's effective restitution in free rocking (src/ensembles/restitution.c) for KN from
 * 1e8 to 1e11 Pa/m and the impact-loss parameter's grid (contact restitution 0 .. 1; under the
 * surface model the joint dashpot's ratio 0.05 .. 5), then the value that reaches the target
 * (default Housner's r = 1 - 1.5 sin^2 alpha) at the scenario's own KN.
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"
#include "rockdem/validate.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct restitution_args {
    double target;    /* 0: Housner's r */
    double rtol;      /* the calibration's stop on |r - target| */
    double theta0;    /* rad; 0: half of alpha */
    const char *body; /* --body NAME: that body alone on what holds it up; NULL: the scene */
} restitution_args;

static int restitution_option(void *ctx, int argc, char **argv, int *i)
{
    static const char *const names[] = { "--target", "--theta0", "--body", "--rtol", NULL };
    restitution_args *a = ctx;
    const char *o = argv[*i], *v;
    int rc = rd_cli_option(argc, argv, *i, names, &v);
    if (rc) return rc;
    if (!strcmp(o, "--body")) {
        a->body = v;
        (*i)++;
        return 0;
    }
    int target = !strcmp(o, "--target");
    double x;
    if (rd_cli_number(o, v, 0, &x)) return -1;
    if (!strcmp(o, "--rtol")) {
        if (!(x >= RD_CAL_RTOL_MIN && x <= RD_CAL_RTOL)) {
            fprintf(stderr, "rockdem: --rtol expects a tolerance on r from %g to %g, got '%s'\n",
                    RD_CAL_RTOL_MIN, RD_CAL_RTOL, v);
            return -1;
        }
        a->rtol = x;
        (*i)++;
        return 0;
    }
    if (!(x > 0) || (target && x > 1)) {
        fprintf(stderr, "rockdem: %s expects %s, got '%s'\n", o,
                target ? "a restitution above 0, at most 1" : "an initial tilt above 0 (rad)", v);
        return -1;
    }
    *(target ? &a->target : &a->theta0) = x;
    (*i)++;
    return 0;
}

/* r by amplitude decay (and, in brackets, from the speeds at equal |theta|) for KN
 * 1e8 .. 1e11 Pa/m (KS scaled with it) and the loss parameter rd_restitution_loss_at(k), the
 * calibration's scan. Returns 1 with grid[] filled when the scenario's own KN is a row (the
 * calibration then reuses it), else 0. */
static int print_table(rd_scenario *sc, double theta0, rd_restitution grid[RD_CAL_GRID + 1])
{
    static const double kn[] = { 1e8, 1e9, 1e10, 1e11 };
    rd_scenario copy = *sc;
    int have = 0;
    printf(
        "block restitution r (free rocking from %.4g rad, mean of the first 3 impacts; amplitude "
        "decay [speeds at equal |theta| either side])\n%-10s",
        theta0, rd_restitution_by_dashpot(sc) ? "KN \\ zeta" : "KN \\ e");
    for (int j = 0; j <= RD_CAL_GRID; j++) printf(" %15.2f", rd_restitution_loss_at(sc, j));
    printf("\n");
    for (size_t i = 0; i < sizeof kn / sizeof *kn; i++) {
        int own = kn[i] == sc->contact.kn;
        printf("%-10.0e", kn[i]);
        for (int j = 0; j <= RD_CAL_GRID; j++) {
            copy.contact.kn = kn[i];
            copy.contact.ks = own ? sc->contact.ks : kn[i] * sc->contact.ks / sc->contact.kn;
            rd_restitution_set_loss(&copy, rd_restitution_loss_at(sc, j));
            rd_restitution m;
            rd_error err;
            int bad = rd_restitution_measure(&copy, theta0, &m, &err);
            if (own) grid[j] = m;
            have |= own && !bad;
            if (bad || m.r < 0)
                printf(" %15s", "-");
            else
                printf("   %.3f [%.3f]", m.r, m.r_speed);
        }
        rd_cli_progress_clear(); /* the row replaces the progress line */
        printf("\n");
        fflush(stdout);
    }
    return have;
}

/* The calibrated run (m) measured by the speeds as well: agreement to RD_CHECK_RTOL says each
 * impact is complete within the band. */
static void print_check(const rd_restitution *m)
{
    double d = fabs(m->r_speed / m->r - 1);
    printf(
        "check: the speeds either side of each impact give r = %.4f, %.2f %% from the amplitude "
        "decay: %s\n",
        m->r_speed, 100 * d,
        d <= RD_CHECK_RTOL
            ? "the impacts are complete, agreed"
            : "DISAGREE (over 0.5 %): the block still bounces on its new pivot after each impact, "
              "losing energy later than rigid theory's instantaneous impact");
}

/* Why the calibration cannot reach its target (rc 2: r too uneven in a bracket; else r stays
 * above it (high) or below it), for the vertex model's restitution or the dashpot's ratio. */
static const char *unreachable_why(int rc, int high, int dashpot)
{
    if (rc == 2)
        return dashpot ? "r crosses the target between two scanned ratios but is too uneven "
                         "there to reach it to --rtol (the block slides or bounces: see the "
                         "table)"
                       : "r(e) crosses the target between two scanned values of e but is too "
                         "uneven there to reach it to --rtol (the block slides or bounces on "
                         "its new edge: see the table)";
    if (dashpot)
        return high ? "no dashpot ratio up to 5 loses enough; a lower r needs sliding at the "
                      "pivot"
                    : "no dashpot ratio down to 0.05 keeps enough: a continuous base reverses "
                      "the block's fall on the compressed wedge under its landing edge, which "
                      "bounds r (0.913 for h/b = 2, docs/CONTACT.md section 8.6); below 0.05 "
                      "the block's vibration on its joint is not damped out between impacts";
    return high ? "no restitution in [0, 1] loses enough: perfectly plastic point impacts "
                  "already keep more than asked; a lower r needs sliding at the pivot or "
                  "contact dashpots (model damping viscous)"
                : "no restitution in [0, 1] keeps enough: a point that rebounds makes the block "
                  "bounce on its new edge, and a corner impact without bouncing keeps at most "
                  "Housner's r; more needs the impact shared with the base's interior (spacing, "
                  "docs/CONTACT.md section 2)";
}

int rd_cli_restitution(int argc, char **argv)
{
    rd_scenario sc;
    restitution_args a = { .target = 0, .rtol = RD_CAL_RTOL, .theta0 = 0, .body = NULL };
    if (rd_cli_scenario(&sc, argc, argv, restitution_option, &a, NULL)) {
        rd_scenario_free(&sc);
        return 2;
    }
    rd_error err;
    rd_rocking_scales rs;
    if (a.body) { /* that body's free rocking on what holds it up */
        rd_scenario one;
        int bad = rd_restitution_isolate(&sc, a.body, &one, &err);
        rd_scenario_free(&sc);
        if (bad) {
            fprintf(stderr, "%s\n", err.msg);
            return 2;
        }
        sc = one;
        printf("body '%s': its free rocking on what holds it up (held fixed), the bodies above it "
               "removed: the joint under it is calibrated\n",
               a.body);
    }
    if (rd_rocking_scales_of(&sc, &rs, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        rd_scenario_free(&sc);
        return 2;
    }
    if (a.theta0 >= rs.alpha) {
        fprintf(stderr,
                "rockdem: --theta0 expects an initial tilt below the block's alpha = %.6g rad, "
                "got %g\n",
                rs.alpha, a.theta0);
        rd_scenario_free(&sc);
        return 2;
    }
    double theta0 = a.theta0 > 0 ? a.theta0 : 0.5 * rs.alpha;
    const int dashpot = rd_restitution_by_dashpot(&sc);
    if (dashpot)
        printf("contact model surface: the impact loss is the joint's dashpot (no permanent "
               "set): restitution 1, and the dashpot's ratio (model damping viscous) is the "
               "calibrated parameter\n");
    double rigid = rs.housner ? rd_housner_r(rs.alpha) : rd_rigid_restitution(&rs, sc.gravity);
    double target = a.target > 0 ? a.target : rigid;
    if (!rs.housner)
        printf(
            "body: no Housner block (not a brick); its own rocking: alpha %.4g rad, R %.4g m, p %.4g rad/s, "
            "leaning towards %.0f deg; rigid impact about the opposite edge r = 1 - 2 p^2 R sin^2(alpha) / g "
            "= %.4f (exact for a body symmetric about its rocking plane's vertical, approximate for an "
            "irregular one)%s\n",
            rs.alpha, rs.R, rs.p, rs.lean * 180 / M_PI, rigid, a.target > 0 ? "" : ": the target");
    if (tan(rs.alpha) > tan(sc.contact.friction)) /* Shenton: rocking alone needs mu > tan alpha */
        printf("note: tan alpha = %.3g exceeds the joint's friction coefficient %.3g (%.4g deg): "
               "the body slides as it rocks, so rigid theory's impact (no slip at the new pivot) "
               "and its r do not apply; a calibration to it is not meaningful\n",
               tan(rs.alpha), tan(sc.contact.friction), sc.contact.friction * 180 / M_PI);
    fflush(stdout); /* before the runs (minutes on a column's drum) */
    /* 4 x 5 table runs, then up to RD_CAL_ITER calibration runs (restitution.c; its scan is
       the table's row at the scenario's KN when there is one, else 5 more runs); the check is
       the calibration's last run */
    rd_cli_progress_start("restitution", 37);
    rd_restitution grid[RD_CAL_GRID + 1], at;
    int have = print_table(&sc, theta0, grid);
    double e, reached;
    int rc = rd_restitution_calibrate_grid(&sc, theta0, target, a.rtol, have ? grid : NULL, &e,
                                           &reached, &at, &err);
    rd_cli_progress_stop();
    if (rc < 0) {
        fprintf(stderr, "%s\n", err.msg);
    } else if (rc == 0) {
        printf("calibrated: %s %.4f gives r = %.4f (target %.4f%s, |error| < %g) at KN %.3g "
               "Pa/m\n",
               dashpot ? "model damping viscous" : "contact property restitution", e, reached,
               target,
               a.target > 0 ? ""
               : rs.housner ? ", Housner's r"
                            : ", the rigid impact's r",
               a.rtol, sc.contact.kn);
        print_check(&at);
    } else {
        printf("UNREACHABLE: target r = %.4f (--rtol %g); the closest this contact gets is "
               "r = %.4f at %s %g: %s\n",
               target, a.rtol, reached, dashpot ? "dashpot ratio" : "restitution", e,
               unreachable_why(rc, reached > target, dashpot));
    }
    rd_scenario_free(&sc);
    return rc < 0 ? 3 : rc ? 4 : 0;
}
