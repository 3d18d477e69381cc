/* rockdem — command-line program.
 *   rockdem run FILE [--set key=value]... [-o OUT.h5] [-q]   settle, shake, write HDF5, summarise
 *   rockdem check FILE [--set key=value]...                  parse and validate only
 *   rockdem keys [--tsv]                                     every --set key, units, default
 *   rockdem --version | --help | SUB --help | help SUB       (cli_help.c)
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "rockdem/observer.h"
#include "rockdem/output.h"
#include "rockdem/rockdem.h"
#include "cli/cli.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

static void on_signal(int sig)
{
    (void)sig;
    rd_sim_request_stop();
}

/* Free body k left the scene (event "lost") without having met the overturn criterion: it fell
 * off its support, and the engine counts that as overturned (engine/monitor.c). */
static int fell_off(const rd_sim *sim, int k)
{
    int n;
    const rd_event *ev = rd_sim_events(sim, &n);
    for (int e = 0; e < n; e++) {
        if (ev[e].body != k) continue;
        if (!strcmp(ev[e].type, "overturn")) return 0;
        if (!strcmp(ev[e].type, "lost")) return 1;
    }
    return 0;
}

/* The scene's settling stopped before the unbalanced-force ratio fell to the one asked (event
 * "unsettled"): 1 with the ratio reached, else 0. */
static int settle_gave_up(const rd_sim *sim, double *ratio)
{
    int n;
    const rd_event *ev = rd_sim_events(sim, &n);
    for (int k = 0; k < n; k++)
        if (!strcmp(ev[k].type, "unsettled")) {
            *ratio = ev[k].value;
            return 1;
        }
    return 0;
}

static void print_summary(const rd_sim *sim, const rd_summary *s, int quiet)
{
    int invalid = s->status == RD_STATUS_PENETRATED || s->status == RD_STATUS_LOST;
    for (int k = 0; k < s->nbodies; k++) {
        const rd_body_summary *b = &s->body[k];
        if (invalid) { /* the motion is not physical: no verdict (the cause follows on stderr) */
            printf("%s: no verdict: the run stopped, %s\n", b->name,
                   s->status == RD_STATUS_LOST ? "a body left the scene"
                                               : "a body passed into another");
            continue;
        }
        if (b->unsupported) {
            printf(
                "%s: FELL FREELY: it touched nothing (no support under it); fell %.4g m, ended at "
                "(%.4g, %.4g, %.4g) m\n",
                b->name, b->drop, b->final_position[0], b->final_position[1], b->final_position[2]);
            continue;
        }
        const char *what =
            b->overturned
                ? (fell_off(sim, k) ? "OVERTURNED (fell off its support, out of the scene)"
                                    : "OVERTURNED")
            : b->uplifted ? "rocked"
            : b->slid     ? "slid"
                          : "stayed seated";
        printf("%s: %s", b->name, what);
        if (b->overturned) printf(" at t = %.3f s", b->overturn_time);
        printf(
            "; max tilt %.4g rad = %.3g alpha; max sway of its base centre %.3g mm (rocking and sliding "
            "together; the slip at its joints is on the joint lines)%s%s\n",
            b->max_tilt, b->max_tilt_ratio, 1e3 * b->max_slide,
            b->slid ? "; all its bearing points slipped at once" : "",
            b->uplifted && !b->overturned ? "; uplifted" : "");
        if (b->overturned)
            printf("%s: ended at (%.4g, %.4g, %.4g) m: %.4g m from where it stood, %.4g m lower\n",
                   b->name, b->final_position[0], b->final_position[1], b->final_position[2],
                   b->travel, b->drop);
        if (!quiet)
            printf("%s: precariousness: least tipping angle %.4g deg leaning towards %.0f deg "
                   "(quasi-static tipping acceleration %.3g g); twist at end %.3g deg\n",
                   b->name, b->alpha_min * 180 / M_PI, b->alpha_min_direction * 180 / M_PI,
                   b->tip_accel_min / RD_G_STANDARD, b->final_twist * 180 / M_PI);
    }
    for (int k = 0; k < rd_sim_joint_count(sim); k++) {
        rd_joint_summary j;
        rd_sim_joint(sim, k, &j);
        if (!j.closed) continue;
        char opening[64] = "never opened";
        if (j.max_opening > 0)
            snprintf(opening, sizeof opening, "max opening %.4g mm", 1e3 * j.max_opening);
        printf(
            "joint %s-%s: max slip %.4g mm, final slip %.4g mm (relative sliding at the joint), %s "
            "(KN %.3g, KS %.3g Pa/m, friction %.3g deg)\n",
            j.a, j.b, 1e3 * j.max_slip, 1e3 * j.final_slip, opening, j.kn, j.ks,
            j.friction * 180 / M_PI);
    }
    if (quiet) return;
    double sim_s = s->steps * s->dt;
    long aps = rd_sim_active_point_steps(sim);
    printf("run: status %s, t = %.4g s, dt = %.3g s (limit %.3g s), %ld steps, settle %.3g s, "
           "energy residual %.2e\n",
           rd_status_name(s->status), s->end_time, s->dt, s->dt_critical, s->steps, s->settle_time,
           s->energy_residual_max);
    printf("perf: steps=%ld wall_s=%.6f steps_per_s=%.6g ns_per_subcontact_step=%.4g "
           "mean_active_subcontacts=%.4g threads=%d wall_per_sim_s=%.6g\n",
           s->steps, s->wall_seconds, s->wall_seconds > 0 ? s->steps / s->wall_seconds : 0.0,
           aps > 0 ? 1e9 * s->wall_seconds / (double)aps : 0.0,
           s->steps > 0 ? (double)aps / (double)s->steps : 0.0, rd_sim_threads(sim),
           sim_s > 0 ? s->wall_seconds / sim_s : 0.0);
}

/* --force (run past the step budget) of run and check, --overwrite (write over an earlier run
 * file in place) of run, --strict (warnings fail) of check; -q is common (rd_cli_quiet). */
typedef struct run_flags {
    int check_only, force, overwrite, strict;
} run_flags;

static int run_option(void *ctx, int argc, char **argv, int *i)
{
    run_flags *f = ctx;
    (void)argc;
    if (!strcmp(argv[*i], "--force"))
        f->force = 1;
    else if (!f->check_only && !strcmp(argv[*i], "--overwrite"))
        f->overwrite = 1;
    else if (f->check_only && !strcmp(argv[*i], "--strict"))
        f->strict = 1;
    else
        return 1;
    return 0;
}

/* The run's header: every dimensional input with its units, each free body's size and mass. */
static void print_inputs(const rd_sim *sim)
{
    const rd_scenario *sc = rd_sim_scenario(sim);
    rd_cli_echo_inputs(sc);
    int nfree = rd_sim_body_count(sim, NULL);
    for (int k = 0; k < nfree; k++) {
        rd_body_info b;
        rd_sim_body_info(sim, k, &b);
        int mesh = 0;
        for (int i = 0; i < sc->nbodies; i++)
            if (!strcmp(sc->bodies[i].name, b.name)) mesh = sc->bodies[i].shape == RD_SHAPE_MESH;
        rd_cli_echo_body(b.name, mesh, b.mass, b.size);
    }
}

/* rockdem check: everything run would read and build (meshes, records with their IMs,
 * perturbed subcontact points, time step and step budget, output folder), nothing written. */
static int cmd_run(int argc, char **argv, int check_only)
{
    rd_scenario sc;
    const char *out = NULL;
    run_flags f = { .check_only = check_only };
    if (rd_cli_scenario(&sc, argc, argv, run_option, &f, &out)) {
        rd_scenario_free(&sc);
        return 2;
    }
    int quiet = rd_cli_quiet;
    if (f.force) sc.force = 1;
    sc.overwrite = f.overwrite;
    if (check_only) {
        int rc = rd_cli_check(&sc, quiet, f.strict);
        rd_scenario_free(&sc);
        return rc;
    }
    rd_error err;
    if (!quiet && rd_cli_print_motion(&sc.motion)) {
        rd_scenario_free(&sc);
        return 2;
    }
    rd_sim *sim = rd_sim_create(&sc, &err);
    char staged[RD_PATH_MAX]; /* where this run writes while an earlier file is at the output */
    int replacing = rd_output_staging(sc.output.path, sc.overwrite, staged, sizeof staged);
    if (!sim || rd_sim_write_hdf5(sim, sc.output.path, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        rd_sim_free(sim);
        rd_scenario_free(&sc);
        return 2;
    }
    if (!quiet) print_inputs(sim);
    /* Ctrl-C, kill (SIGTERM) and a closed terminal or session (SIGHUP) all stop the run at the
       next step; the file is closed with status interrupted */
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
    signal(SIGHUP, on_signal);
    rd_cli_progress_start("run", 1);
    rd_status st = rd_sim_run(sim);
    rd_cli_progress_stop();
    rd_summary s;
    rd_sim_summary(sim, &s);
    print_summary(sim, &s, quiet);
    char unsettled[96] = ""; /* settling gave up short of its force ratio: said once, below */
    double ratio;
    if (settle_gave_up(sim, &ratio))
        snprintf(unsettled, sizeof unsettled, "settling stopped at force ratio %.3g (asked %.3g)",
                 ratio, sc.settle.ratio);
    int rc = 0;
    /* a run that did not succeed leaves an earlier file at the output as it was */
    char kept[RD_PATH_MAX + 64] = "";
    if (replacing && (rd_status_failed(st) || st == RD_STATUS_INTERRUPTED))
        snprintf(kept, sizeof kept, " (%s keeps the earlier run)", sc.output.path);
    const char *written = kept[0] ? staged : sc.output.path;
    if (rd_status_failed(st)) { /* one line: the failure, with the settling that preceded it */
        fprintf(stderr, "%s: %s%s%s%s%s%s\n", sc.file, rd_sim_error(sim), unsettled[0] ? "; " : "",
                unsettled, kept[0] ? "; this run's output is in " : "", kept[0] ? staged : "",
                kept);
        rc = 3;
    } else if (st == RD_STATUS_INTERRUPTED) {
        fprintf(stderr, "rockdem: interrupted at t = %.4g s; %s holds everything so far%s\n",
                s.end_time, written, kept);
        rc = 130;
    } else if (unsettled[0]) {
        fprintf(stderr, "rockdem: warning: %s\n", unsettled);
    }
    if (!quiet) printf("output: %s\n", written);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
    return rc;
}

/* One line for a first argument that is no subcommand; exit status 2. */
static int unknown_subcommand(const char *name)
{
    fprintf(stderr, "rockdem: unknown subcommand '%s' (rockdem help lists them)\n", name);
    return 2;
}

int main(int argc, char **argv)
{
    /* past a file-size limit (ulimit -f) write() then fails with EFBIG and the writer reports
       it, instead of the process dying of SIGXFSZ with nothing said */
    signal(SIGXFSZ, SIG_IGN);
    if (argc >= 2 && (!strcmp(argv[1], "--version") || !strcmp(argv[1], "version"))) {
        printf("rockdem %s\n", RD_VERSION);
        return 0;
    }
    if (argc >= 2 && !strcmp(argv[1], "help")) {
        if (rd_cli_help(argc >= 3 ? argv[2] : NULL, stdout) == 0) return 0;
        fprintf(stderr, "rockdem: unknown help topic '%s' (rockdem help lists the subcommands)\n",
                argv[2]);
        return 2;
    }
    for (int i = 1; i < argc; i++) /* rockdem --help, rockdem SUB [...] --help */
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            if (rd_cli_help(i >= 2 ? argv[1] : NULL, stdout) == 0) return 0;
            return unknown_subcommand(argv[1]);
        }
    if (argc >= 2 && !strcmp(argv[1], "keys")) {
        if (argc > 3 || (argc == 3 && strcmp(argv[2], "--tsv"))) {
            fprintf(stderr, "rockdem: keys takes only --tsv (see rockdem keys --help)\n");
            return 2;
        }
        rd_cli_keys(argc == 3);
        return 0;
    }
    if (argc >= 3 && rd_cli_is_subcommand(argv[1]) && rd_cli_permute(argc, argv)) {
        fprintf(stderr, "rockdem %s: missing FILE (see rockdem %s --help)\n", argv[1], argv[1]);
        return 2;
    }
    if (argc >= 3 && !strcmp(argv[1], "run")) return cmd_run(argc, argv, 0);
    if (argc >= 3 && !strcmp(argv[1], "check")) return cmd_run(argc, argv, 1);
    if (argc >= 3 && !strcmp(argv[1], "reference")) return rd_cli_reference(argc, argv);
    if (argc >= 3 && !strcmp(argv[1], "threshold")) return rd_cli_threshold(argc, argv);
    if (argc >= 3 && !strcmp(argv[1], "restitution")) return rd_cli_restitution(argc, argv);
    if (argc >= 3 && !strcmp(argv[1], "study")) return rd_cli_study(argc, argv);
    if (argc >= 3 && !strcmp(argv[1], "sweep")) return rd_cli_sweep(argc, argv);
    if (argc >= 3 && !strcmp(argv[1], "assess")) return rd_cli_assess(argc, argv);
    if (argc == 1) { /* no subcommand: the usage */
        rd_cli_help(NULL, stderr);
        return 2;
    }
    if (!rd_cli_is_subcommand(argv[1])) return unknown_subcommand(argv[1]);
    fprintf(stderr, "rockdem %s: missing FILE (see rockdem %s --help)\n", argv[1], argv[1]);
    return 2;
}
