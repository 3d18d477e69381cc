/* rockdem — `rockdem threshold SCENARIO --engine dem|reference [--lo A] [--hi A] [--rtol r]
 * [--steps n] [--set k=v]...`: minimum overturning amplitude of the scenario's horizontal
 * pulse (src/threshold.c), printed in m/s^2, g and a / (g tan alpha), with w / p. */
#include "cli.h"
#include "rockdem/validate.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct threshold_args {
    rd_engine engine;
    rd_threshold_opts opts;
} threshold_args;

static int threshold_option(void *ctx, int argc, char **argv, int *i)
{
    threshold_args *a = ctx;
    if (*i + 1 >= argc) return 1;
    const char *o = argv[*i], *v = argv[*i + 1];
    double x;
    if (!strcmp(o, "--engine")) {
        if (strcmp(v, "dem") && strcmp(v, "reference")) {
            fprintf(stderr, "rockdem: --engine expects dem or reference, got '%s'\n", v);
            return -1;
        }
        a->engine = strcmp(v, "dem") ? RD_ENGINE_REFERENCE : RD_ENGINE_DEM;
    } else if (!strcmp(o, "--lo") || !strcmp(o, "--hi")) {
        if (rd_cli_number(o, v, 1, &x)) return -1;
        *(o[2] == 'l' ? &a->opts.lo : &a->opts.hi) = x;
    } else if (!strcmp(o, "--rtol")) {
        if (rd_cli_number(o, v, 0, &a->opts.rtol)) return -1;
    } else if (!strcmp(o, "--steps")) {
        if (rd_cli_number(o, v, 0, &x)) return -1;
        a->opts.nscan = (int)x;
    } else {
        return 1;
    }
    (*i)++;
    return 0;
}

int rd_cli_threshold(int argc, char **argv)
{
    rd_scenario sc;
    threshold_args a = {RD_ENGINE_DEM, rd_threshold_opts_default()};
    if (rd_cli_scenario(&sc, argc, argv, threshold_option, &a, NULL)) { rd_scenario_free(&sc); return 2; }
    rd_error err;
    rd_threshold_result r;
    int rc = rd_threshold(&sc, a.engine, &a.opts, &r, &err);
    if (rc) {
        fprintf(stderr, "%s\n", err.msg);
    } else if (!r.found) {
        printf("no overturning up to the top of the range (%d runs); raise --hi\n", r.runs);
    } else {
        double g = sc.gravity;
        printf("engine %s: minimum overturning amplitude %.5g m/s^2 = %.4f g "
               "(bracket %.5g .. %.5g m/s^2, %d runs)\n", a.engine == RD_ENGINE_DEM ? "dem" : "reference",
               r.amplitude, r.amplitude / 9.80665, r.below, r.amplitude, r.runs);
        printf("a / a_uplift = %.4f   (static uplift a_uplift = %.4g m/s^2; g tan alpha for one "
               "block)   w / p = %.4f\n", r.amplitude / r.static_amp, r.static_amp, r.w_over_p);
        if (r.amplitude == r.below)
            printf("note: the lowest amplitude tried (%.4g m/s^2 = %.4f g) already overturns; lower --lo\n",
                   r.amplitude, r.amplitude / g);
    }
    rd_scenario_free(&sc);
    return rc ? 3 : 0;
}
