/* rockdem — `rockdem restitution SCENARIO [--target r] [--theta0 rad] [--set k=v]...`:
 * the DEM's effective restitution in free rocking (src/restitution.c) for KN from 1e8 to
 * 1e11 Pa/m and damping ratios 0 .. 1, then the damping ratio that reaches the target
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
    double target; /* < 0: Housner's r */
    double theta0; /* < 0: half of alpha */
} restitution_args;

static int restitution_option(void *ctx, int argc, char **argv, int *i)
{
    restitution_args *a = ctx;
    if (*i + 1 >= argc) return 1;
    double *dst = !strcmp(argv[*i], "--target") ? &a->target : !strcmp(argv[*i], "--theta0") ? &a->theta0 : NULL;
    if (!dst) return 1;
    if (rd_cli_number(argv[*i], argv[*i + 1], 0, dst)) return -1;
    (*i)++;
    return 0;
}

static void print_table(rd_scenario *sc, double theta0)
{
    static const double kn[] = {1e8, 1e9, 1e10, 1e11}, zeta[] = {0, 0.1, 0.3, 0.6, 1.0};
    rd_scenario copy = *sc;
    printf("effective restitution r (free rocking from %.4g rad; r = w_after / w_before, mean of "
           "the first 3 impacts)\n%-10s", theta0, "KN \\ zeta");
    for (size_t j = 0; j < sizeof zeta / sizeof *zeta; j++) printf(" %7.2f", zeta[j]);
    printf("\n");
    for (size_t i = 0; i < sizeof kn / sizeof *kn; i++) {
        printf("%-10.0e", kn[i]);
        for (size_t j = 0; j < sizeof zeta / sizeof *zeta; j++) {
            copy.contact.kn = kn[i];
            copy.contact.ks = kn[i] * sc->contact.ks / sc->contact.kn;
            copy.damping = (rd_damping_def){zeta[j] > 0 ? RD_DAMPING_VISCOUS : RD_DAMPING_NONE, zeta[j]};
            rd_restitution m;
            rd_error err;
            if (rd_restitution_measure(&copy, theta0, &m, &err) || m.r < 0) printf(" %7s", "-");
            else printf(" %7.3f", m.r);
        }
        rd_cli_progress_clear(); /* the row replaces the progress line */
        printf("\n");
    }
}

int rd_cli_restitution(int argc, char **argv)
{
    rd_scenario sc;
    restitution_args a = {-1, -1};
    if (rd_cli_scenario(&sc, argc, argv, restitution_option, &a, NULL)) { rd_scenario_free(&sc); return 2; }
    rd_error err;
    rd_refscene rs;
    if (rd_refscene_map(&sc, &rs, &err) || rs.model != RD_REFMODEL_HOUSNER) {
        fprintf(stderr, "%s\n", rs.model == RD_REFMODEL_KOUNADIS ? "restitution: needs one free "
                "block on a fixed base (this is a stack)" : err.msg);
        rd_scenario_free(&sc);
        return 2;
    }
    double theta0 = a.theta0 > 0 ? a.theta0 : 0.5 * rs.alpha;
    double target = a.target > 0 ? a.target : rd_housner_r(rs.alpha);
    /* 4 x 5 table runs, then up to RD_CAL_ITER + 2 calibration runs (restitution.c) */
    rd_cli_progress_start("restitution", 36);
    print_table(&sc, theta0);
    double zeta, reached;
    int rc = rd_restitution_calibrate(&sc, theta0, target, &zeta, &reached, &err);
    rd_cli_progress_stop();
    if (rc < 0) {
        fprintf(stderr, "%s\n", err.msg);
    } else if (rc == 0) {
        printf("calibrated: model damping viscous %.4f gives r = %.4f (target %.4f%s) at KN %.3g Pa/m\n",
               zeta, reached, target, a.target > 0 ? "" : ", Housner's r", sc.contact.kn);
    } else {
        const char *why = zeta == 0 ? "even without damping the contact loses more energy than asked"
                        : sc.contact.spacing != 0 ? "a bed of many subcontacts rolls the pivot across the "
                          "base and saturates near 0.82-0.85; use corner subcontacts (contact property "
                          "spacing vertices)"
                        : "the strongest damping accepted (ratio 10) cannot remove more at impact";
        printf("UNREACHABLE: target r = %.4f; the closest this contact gets is r = %.4f at damping "
               "ratio %g: %s\n", target, reached, zeta, why);
    }
    rd_scenario_free(&sc);
    return rc < 0 ? 3 : rc ? 4 : 0;
}
