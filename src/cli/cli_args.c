/* rockdem — shared argument handling of the validation subcommands (src/cli.h).
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"
#include "base/constants.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int rd_cli_number(const char *name, const char *text, int accel, double *v)
{
    char *end;
    double x = strtod(text, &end);
    if (accel && *end == 'g') { x *= RD_G_STANDARD; end++; }
    if (end == text || *end || !isfinite(x) || strpbrk(text, RD_NOT_DECIMAL)) {
        fprintf(stderr, "rockdem: %s expects a number%s, got '%s'\n", name,
                accel ? " (m/s^2, or with a g suffix)" : "", text);
        return -1;
    }
    *v = x;
    return 0;
}

int rd_cli_option(int argc, char **argv, int i, const char *const *names, const char **v)
{
    while (*names && strcmp(argv[i], *names)) names++;
    if (!*names) return 1;
    if (i + 1 >= argc) {
        fprintf(stderr, "rockdem: %s needs a value (see rockdem %s --help)\n", argv[i], argv[1]);
        return -1;
    }
    *v = argv[i + 1];
    return 0;
}

/* --set KEY=VALUE (help: print the keys and stop); 0, or -1 after printing why not. */
static int set_key(rd_scenario *sc, const char *kv)
{
    rd_error err;
    if (!strcmp(kv, "help")) {
        rd_cli_keys(0);
        exit(0);
    }
    if (rd_scenario_set(sc, kv, &err)) { fprintf(stderr, "%s\n", err.msg); return -1; }
    return 0;
}

/* argv[*i] is -q, --set KEY=VALUE, --set=KEY=VALUE or (when out is not NULL) -o OUT: consume
 * it; 1 when it is none of them, -1 when its value is missing or bad (after printing why). */
static int common_option(rd_scenario *sc, int argc, char **argv, int *i, const char **out)
{
    static const char *const set_name[] = {"--set", NULL}, *const out_name[] = {"-o", NULL};
    const char *v;
    if (!strcmp(argv[*i], "-q")) {
        rd_cli_quiet = 1;
        return 0;
    }
    if (!strncmp(argv[*i], "--set=", 6)) return set_key(sc, argv[*i] + 6);
    int rc = rd_cli_option(argc, argv, *i, set_name, &v);
    if (rc == 0) {
        (*i)++;
        return set_key(sc, v);
    }
    if (rc < 0 || !out) return rc;
    rc = rd_cli_option(argc, argv, *i, out_name, &v);
    if (rc == 0) {
        (*i)++;
        *out = v;
    }
    return rc;
}

int rd_cli_scenario(rd_scenario *sc, int argc, char **argv, rd_cli_option_fn opt, void *ctx,
                    const char **out)
{
    rd_error err;
    if (rd_scenario_load(sc, argv[2], &err)) { fprintf(stderr, "%s\n", err.msg); return -1; }
    for (int i = 3; i < argc; i++) {
        int rc = common_option(sc, argc, argv, &i, out);
        if (rc > 0) rc = opt ? opt(ctx, argc, argv, &i) : 1;
        if (rc > 0)
            fprintf(stderr, "rockdem: unknown option '%s' for '%s' (see rockdem %s --help)\n",
                    argv[i], argv[1], argv[1]);
        if (rc) return -1;
    }
    if (out && *out) snprintf(sc->output.path, sizeof sc->output.path, "%s", *out);
    if (rd_scenario_validate(sc, &err)) { fprintf(stderr, "%s\n", err.msg); return -1; }
    return 0;
}
