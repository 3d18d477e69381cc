/* rockdem — shared argument handling of the validation subcommands (src/cli/cli.h).
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
    if (accel && *end == 'g') {
        x *= RD_G_STANDARD;
        end++;
    }
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

/* Length of an option's name or a value's key: up to its '=' (or all of it). */
static size_t name_len(const char *a)
{
    const char *e = strchr(a, '=');
    return e ? (size_t)(e - a) : strlen(a);
}

/* The KEY=... value of argv[i] when it is --set or --axis (either form), else NULL; *opt_len
 * the option name's length. */
static const char *keyed_value(int argc, char **argv, int i, size_t *opt_len)
{
    static const char *const keyed[] = { "--set", "--axis", NULL };
    for (const char *const *k = keyed; *k; k++) {
        size_t n = strlen(*k);
        if (strncmp(argv[i], *k, n)) continue;
        *opt_len = n;
        if (argv[i][n] == '=') return argv[i] + n + 1;
        if (!argv[i][n]) return i + 1 < argc ? argv[i + 1] : NULL;
    }
    return NULL;
}

int rd_cli_repeated(int argc, char **argv, const int *seen, int n, int i, rd_error *err)
{
    size_t li = 0, lj = 0;
    const char *a = keyed_value(argc, argv, i, &li);
    for (int k = 0; k < n; k++) {
        int j = seen[k];
        const char *b = keyed_value(argc, argv, j, &lj);
        int same = a || b ? a && b && li == lj && !strncmp(argv[i], argv[j], li) &&
                                name_len(a) == name_len(b) && !strncmp(a, b, name_len(a))
                          : name_len(argv[i]) == name_len(argv[j]) &&
                                !strncmp(argv[i], argv[j], name_len(argv[i]));
        if (!same) continue;
        if (a)
            return rd_error_set(
                err,
                "rockdem %s: %.*s '%.*s' given twice (arguments %d and %d); give each key once",
                argv[1], (int)li, argv[i], (int)name_len(a), a, j, i);
        return rd_error_set(
            err,
            "rockdem %s: option '%.*s' given twice (arguments %d and %d); give each option once",
            argv[1], (int)name_len(argv[i]), argv[i], j, i);
    }
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
    if (rd_scenario_set(sc, kv, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return -1;
    }
    return 0;
}

/* argv[*i] is -q, --set KEY=VALUE, --set=KEY=VALUE or (when out is not NULL) -o OUT: consume
 * it; 1 when it is none of them, -1 when its value is missing or bad (after printing why). */
static int common_option(rd_scenario *sc, int argc, char **argv, int *i, const char **out)
{
    static const char *const set_name[] = { "--set", NULL }, *const out_name[] = { "-o", NULL };
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

/* Options of any subcommand that take no value (every other '-' argument without '=' takes the
 * next one). */
static int is_flag(const char *a)
{
    static const char *const flags[] = {
        "-q", "--force", "--overwrite", "--strict", "--tsv", NULL
    };
    for (const char *const *f = flags; *f; f++)
        if (!strcmp(a, *f)) return 1;
    return 0;
}

int rd_cli_permute(int argc, char **argv)
{
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] != '-' ||
            !a[1]) { /* the operand: moved to argv[2], the options keep their order */
            char *file = argv[i];
            memmove(argv + 3, argv + 2, (size_t)(i - 2) * sizeof *argv);
            argv[2] = file;
            return 0;
        }
        if (!is_flag(a) && !strchr(a, '=')) i++; /* its value */
    }
    return -1;
}

int rd_cli_scenario(rd_scenario *sc, int argc, char **argv, rd_cli_option_fn opt, void *ctx,
                    const char **out)
{
    rd_error err;
    if (rd_scenario_load(sc, argv[2], &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return -1;
    }
    int seen[argc], nseen = 0; /* the options' places, for rd_cli_repeated */
    for (int i = 3; i < argc; i++) {
        if (rd_cli_repeated(argc, argv, seen, nseen, i, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            return -1;
        }
        seen[nseen++] = i;
        int rc = common_option(sc, argc, argv, &i, out);
        if (rc > 0) rc = opt ? opt(ctx, argc, argv, &i) : 1;
        if (rc > 0)
            fprintf(stderr, "rockdem: unknown option '%s' for '%s' (see rockdem %s --help)\n",
                    argv[i], argv[1], argv[1]);
        if (rc) return -1;
    }
    if (out && *out) snprintf(sc->output.path, sizeof sc->output.path, "%s", *out);
    if (rd_scenario_validate(sc, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return -1;
    }
    return 0;
}
