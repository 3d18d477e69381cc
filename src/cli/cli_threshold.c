/* rockdem — `rockdem threshold SCENARIO --engine dem|reference [--lo A] [--hi A] [--rtol r]
 * [--steps n] [--frequencies f1,f2,...] [-j N] [--set k=v]...`: minimum overturning amplitude
 * of the scenario's horizontal pulse (src/ensembles/threshold.c), printed in m/s^2, g and
 * a / (g tan alpha), with w / p; with --frequencies, one row per pulse frequency: the
 * minimum-overturning curve a / (g tan alpha) against w / p. -j: coarse-scan runs at once
 * (default: the number of online cores).
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"
#include "rockdem/validate.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define RD_MAX_FREQS 64
#define RD_MAX_JOBS  256 /* -j: the scan's own cap (src/ensembles/threshold.c) */

typedef struct threshold_args {
    rd_engine engine;
    rd_threshold_opts opts;
    int nfreq;
    double freq[RD_MAX_FREQS]; /* Hz */
} threshold_args;

/* "f1,f2,..." into a->freq (Hz, each positive, none empty); 0, or -1 with a message. */
static int read_frequencies(threshold_args *a, const char *v)
{
    for (const char *tok = v;; tok++) {
        size_t len = strcspn(tok, ",");
        char item[64];
        if (len == 0 || len >= sizeof item) {
            fprintf(stderr,
                    "rockdem: --frequencies expects positive numbers (Hz) separated by "
                    "commas, got '%s' (%s item)\n",
                    v, len ? "an overlong" : "an empty");
            return -1;
        }
        if (a->nfreq == RD_MAX_FREQS) {
            fprintf(stderr, "rockdem: --frequencies: at most %d values\n", RD_MAX_FREQS);
            return -1;
        }
        snprintf(item, sizeof item, "%.*s", (int)len, tok);
        double *f = &a->freq[a->nfreq++];
        if (rd_cli_number("--frequencies", item, 0, f)) return -1;
        double lo, hi; /* Hz: a pulse frequency's range */
        rd_scenario_limit("frequency", &lo, &hi);
        if (!(*f > 0)) {
            fprintf(stderr, "rockdem: --frequencies expects positive frequencies (Hz), got '%s'\n",
                    item);
            return -1;
        }
        if (!(*f >= lo && *f <= hi)) {
            fprintf(stderr,
                    "rockdem: --frequencies expects frequencies from %g to %g Hz (docs/LIMITS.md), "
                    "got '%s'\n",
                    lo, hi, item);
            return -1;
        }
        tok += len;
        if (!*tok) return 0;
    }
}

/* --lo / --hi A: an amplitude above zero, at most a pulse amplitude's cap (m/s^2, or with a g
 * suffix); 0, or -1 with a message. */
static int read_amplitude(const char *o, const char *v, double *a)
{
    double lo, hi; /* m/s^2: a pulse amplitude's range */
    rd_scenario_limit("amplitude", &lo, &hi);
    if (rd_cli_number(o, v, 1, a)) return -1;
    if (*a > hi) {
        fprintf(stderr,
                "rockdem: %s expects an amplitude of at most %g m/s^2 (docs/LIMITS.md), got '%s'\n",
                o, hi, v);
        return -1;
    }
    if (*a > 0) return 0;
    fprintf(stderr,
            "rockdem: %s expects an amplitude above 0 (m/s^2, or with a g suffix), got '%s'\n", o,
            v);
    return -1;
}

/* --rtol r: the bisection's relative bracket in [RD_THRESHOLD_RTOL_MIN, RD_THRESHOLD_RTOL_MAX];
 * 0, or -1 with a message. */
static int read_rtol(const char *v, double *rtol)
{
    if (rd_cli_number("--rtol", v, 0, rtol)) return -1;
    if (*rtol >= RD_THRESHOLD_RTOL_MIN && *rtol <= RD_THRESHOLD_RTOL_MAX) return 0;
    fprintf(stderr, "rockdem: --rtol expects a relative bracket from %g to %g, got '%s'\n",
            RD_THRESHOLD_RTOL_MIN, RD_THRESHOLD_RTOL_MAX, v);
    return -1;
}

/* A whole number from 1 to max for option o; 0, or -1 with a message naming what it counts. */
static int read_count(const char *o, const char *v, int max, const char *what, int *n)
{
    double x;
    if (rd_cli_number(o, v, 0, &x)) return -1;
    if (!(x >= 1 && x <= max) || x != floor(x)) {
        fprintf(stderr, "rockdem: %s expects a number of %s (1 to %d), got '%s'\n", o, what, max,
                v);
        return -1;
    }
    *n = (int)x;
    return 0;
}

static int threshold_option(void *ctx, int argc, char **argv, int *i)
{
    static const char *const names[] = { "--engine",      "--lo",    "--hi", "--rtol",
                                         "--frequencies", "--steps", "-j",   NULL };
    threshold_args *a = ctx;
    const char *o = argv[*i], *v;
    int rc = rd_cli_option(argc, argv, *i, names, &v);
    if (rc) return rc;
    if (!strcmp(o, "--engine")) {
        if (strcmp(v, "dem") && strcmp(v, "reference")) {
            fprintf(stderr, "rockdem: --engine expects dem or reference, got '%s'\n", v);
            return -1;
        }
        a->engine = strcmp(v, "dem") ? RD_ENGINE_REFERENCE : RD_ENGINE_DEM;
    } else if (!strcmp(o, "--lo") || !strcmp(o, "--hi")) {
        rc = read_amplitude(o, v, o[2] == 'l' ? &a->opts.lo : &a->opts.hi);
    } else if (!strcmp(o, "--rtol")) {
        rc = read_rtol(v, &a->opts.rtol);
    } else if (!strcmp(o, "--frequencies")) {
        rc = read_frequencies(a, v);
    } else if (!strcmp(o, "--steps")) {
        rc = read_count(o, v, RD_THRESHOLD_SCAN_MAX, "coarse scan steps", &a->opts.nscan);
    } else {
        rc = read_count(o, v, RD_MAX_JOBS, "worker processes", &a->opts.jobs);
    }
    (*i)++;
    return rc;
}

/* One row of the minimum-overturning curve at pulse frequency f (Hz). */
static int curve_row(rd_scenario *sc, const threshold_args *a, double f)
{
    char set[64];
    rd_error err;
    rd_threshold_result r;
    snprintf(set, sizeof set, "motion.frequency=%.17g", f);
    if (rd_scenario_set(sc, set, &err) || rd_threshold(sc, a->engine, &a->opts, &r, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return -1;
    }
    rd_cli_progress_clear(); /* the row on a clean line; the bar comes back with the next run */
    if (r.found)
        printf("%10.4g %10.4f %14.4f %12.4f %6d%s\n", f, r.w_over_p, r.amplitude / r.static_amp,
               r.amplitude / RD_G_STANDARD, r.runs,
               r.lifted_off ? "  lift-off (jumps), not overturning" : "");
    else
        printf("%10.4g %10.4f %14s %12s %6d\n", f, r.w_over_p, "none", "-", r.runs);
    return 0;
}

static void print_single(const rd_scenario *sc, const threshold_args *a,
                         const rd_threshold_result *r)
{
    if (!r->found) {
        printf("no overturning up to the top of the range (%d runs); raise --hi\n", r->runs);
        return;
    }
    if (r->lifted_off) {
        printf("lift-off: the pivot lifts off (the block jumps) before it overturns; the rigid "
               "model stops at %.5g m/s^2 = %.4f g (a / a_uplift = %.4f); below it nothing "
               "overturned\n",
               r->amplitude, r->amplitude / RD_G_STANDARD, r->amplitude / r->static_amp);
        return;
    }
    printf("engine %s: minimum overturning amplitude %.5g m/s^2 = %.4f g "
           "(bracket %.5g .. %.5g m/s^2, %d runs)\n",
           a->engine == RD_ENGINE_DEM ? "dem" : "reference", r->amplitude,
           r->amplitude / RD_G_STANDARD, r->below, r->amplitude, r->runs);
    if (r->own_scale)
        printf(
            "a / a_uplift = %.4f   (static uplift a_uplift = %.4g m/s^2: g tan alpha of the scene itself, "
            "the least along the shaking over its free bodies and the assemblies standing on them)   w / p = %.4f (p of that body or assembly about its pivot edge)\n",
            r->amplitude / r->static_amp, r->static_amp, r->w_over_p);
    else
        printf("a / a_uplift = %.4f   (static uplift a_uplift = %.4g m/s^2; g tan alpha for one "
               "block)   w / p = %.4f\n",
               r->amplitude / r->static_amp, r->static_amp, r->w_over_p);
    if (r->amplitude == r->below)
        printf(
            "note: the lowest amplitude tried (%.4g m/s^2 = %.4f g) already overturns; lower --lo\n",
            r->amplitude, r->amplitude / sc->gravity);
}

int rd_cli_threshold(int argc, char **argv)
{
    rd_scenario sc;
    threshold_args a = { RD_ENGINE_DEM, rd_threshold_opts_default(), 0, { 0 } };
    rd_error err;
    double lo, hi; /* m/s^2: the range searched, refused here (exit 2) before any run */
    if (rd_cli_scenario(&sc, argc, argv, threshold_option, &a, NULL)) {
        rd_scenario_free(&sc);
        return 2;
    }
    if (rd_threshold_range(&sc, &a.opts, &lo, &hi, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        rd_scenario_free(&sc);
        return 2;
    }
    int rc = 0;
    /* runs: about half the coarse scan, then bisection from its step down to rtol */
    int per = a.opts.nscan / 2 + 2 + (int)ceil(log2(1.0 / fmax(a.opts.rtol * a.opts.nscan, 1e-6)));
    rd_cli_progress_start("threshold", (a.nfreq > 0 ? a.nfreq : 1) * (per > 1 ? per : 2));
    if (a.nfreq > 0) {
        printf("engine %s: minimum-overturning curve\n%10s %10s %14s %12s %6s\n",
               a.engine == RD_ENGINE_DEM ? "dem" : "reference", "f (Hz)", "w/p", "a/a_uplift",
               "a (g)", "runs");
        for (int k = 0; k < a.nfreq && rc == 0; k++) rc = curve_row(&sc, &a, a.freq[k]);
    } else {
        rd_threshold_result r;
        rc = rd_threshold(&sc, a.engine, &a.opts, &r, &err);
        rd_cli_progress_stop();
        if (rc)
            fprintf(stderr, "%s\n", err.msg);
        else
            print_single(&sc, &a, &r);
    }
    rd_cli_progress_stop();
    rd_scenario_free(&sc);
    return rc ? 3 : 0;
}
