/* rockdem — shared argument handling of the validation subcommands (src/cli.h).
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int rd_cli_number(const char *name, const char *text, int accel, double *v)
{
    char *end;
    double x = strtod(text, &end);
    if (accel && *end == 'g') { x *= RD_G_STANDARD; end++; }
    if (end == text || *end || !isfinite(x)) {
        fprintf(stderr, "rockdem: %s expects a number%s, got '%s'\n", name,
                accel ? " (m/s^2, or with a g suffix)" : "", text);
        return -1;
    }
    *v = x;
    return 0;
}

int rd_cli_scenario(rd_scenario *sc, int argc, char **argv, rd_cli_option_fn opt, void *ctx,
                    const char **out)
{
    rd_error err;
    if (rd_scenario_load(sc, argv[2], &err)) { fprintf(stderr, "%s\n", err.msg); return -1; }
    for (int i = 3; i < argc; i++) {
        const char *set = !strcmp(argv[i], "--set") && i + 1 < argc ? argv[++i]
                        : !strncmp(argv[i], "--set=", 6) ? argv[i] + 6 : NULL;
        if (set && !strcmp(set, "help")) { /* --set help: the keys, then stop */
            rd_cli_keys(0);
            exit(0);
        } else if (set) {
            if (rd_scenario_set(sc, set, &err)) { fprintf(stderr, "%s\n", err.msg); return -1; }
        } else if (!strcmp(argv[i], "-q")) {
            rd_cli_quiet = 1;
        } else if (out && !strcmp(argv[i], "-o") && i + 1 < argc) {
            *out = argv[++i];
        } else {
            int rc = opt ? opt(ctx, argc, argv, &i) : 1;
            if (rc > 0)
                fprintf(stderr, "rockdem: unknown option '%s' for '%s' (see rockdem %s --help)\n",
                        argv[i], argv[1], argv[1]);
            if (rc) return -1;
        }
    }
    if (out && *out) snprintf(sc->output.path, sizeof sc->output.path, "%s", *out);
    if (rd_scenario_validate(sc, &err)) { fprintf(stderr, "%s\n", err.msg); return -1; }
    return 0;
}
