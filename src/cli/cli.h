/* rockdem (private) — subcommands of the command-line program beyond run/check (src/cli/main.c
 * dispatches to these). Each returns the process exit status: 0 ok, 2 bad input, 3 failure.
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#ifndef RD_CLI_H
#define RD_CLI_H

#include "rockdem/rockdem.h"
#include "rockdem/sweep.h"

#include <stdio.h>

/* Option handler of one subcommand: consume argv[*i] (and its value, advancing *i) and return
 * 0; return 1 when the option is not its own, -1 when its value is bad (after printing why). */
typedef int (*rd_cli_option_fn)(void *ctx, int argc, char **argv, int *i);

/* Load argv[2] as a scenario, apply --set k=v overrides and -o OUT (when out is not NULL),
 * hand every other option to `opt` (may be NULL), then validate. Prints one line and returns
 * -1 on error. */
int rd_cli_scenario(rd_scenario *sc, int argc, char **argv, rd_cli_option_fn opt, void *ctx,
                    const char **out);

/* Options anywhere (getopt's order): moves the subcommand's FILE, the first argument from
 * argv[2] on that is neither an option nor an option's value, to argv[2]; options that take no
 * value are -q, --force, --strict and --tsv, every other one takes the next argument unless
 * written --opt=V. 0, or -1 when there is no FILE. */
int rd_cli_permute(int argc, char **argv);

/* Is argv[i] one of the options `names` (NULL-terminated) that take a value? 1 when it is not
 * one of them; -1 when the value is missing (after printing which option needs one); 0 with
 * *v = argv[i + 1]. */
int rd_cli_option(int argc, char **argv, int i, const char *const *names, const char **v);

/* Is option argv[i] one of the earlier options argv[seen[0]], ..., argv[seen[n - 1]]: the same
 * name (up to an '=', for --opt=V), or for --set and --axis, whose values are KEY=..., the same
 * option and key? Then -1 with err's one line naming both (the last one no longer wins
 * silently); else 0. */
int rd_cli_repeated(int argc, char **argv, const int *seen, int n, int i, rd_error *err);

/* Parse a number (optionally with a 'g' suffix: times RD_G_STANDARD = 9.80665 m/s^2) for option `name`. */
int rd_cli_number(const char *name, const char *text, int accel, double *v);

int rd_cli_reference(int argc, char **argv);   /* rockdem reference SCENARIO ... */
int rd_cli_threshold(int argc, char **argv);   /* rockdem threshold SCENARIO ... */
int rd_cli_restitution(int argc, char **argv); /* rockdem restitution SCENARIO ... */
int rd_cli_study(int argc, char **argv);       /* rockdem study SCENARIO ... */
int rd_cli_sweep(int argc, char **argv);       /* rockdem sweep SCENARIO ... (cli_sweep.c) */
int rd_cli_assess(int argc, char **argv);      /* rockdem assess SCENARIO ... (cli_assess.c) */
/* rockdem check: report and warnings (cli_check.c); strict: exit 1 when it warns. */
int rd_cli_check(rd_scenario *sc, int quiet, int strict);

/* cli_units.c: every dimensional input of the scene with its units ("inputs: ..." lines). */
void rd_cli_echo_inputs(const rd_scenario *sc);
/* One "inputs: block ..." line: its size along ground x, y, z (m) and mass (kg). */
void rd_cli_echo_body(const char *name, int mesh, double mass, const double size[3]);
/* "warning:" lines for scene values that look like a unit mistake, each with the likely
 * intent (friction in degrees below 1.5, gravity off the Earth's, a pulse amplitude under
 * 1 m/s^2 without a g suffix, a PGA above 5 g); returns how many. */
int rd_cli_unit_warnings(const rd_scenario *sc);
/* The same for body d as built: larger than 100 m across (a mesh in mm?), a mesh tipping at
 * under 0.5 deg (y-up?); alpha < 0 when unknown. Returns how many. */
int rd_cli_body_warnings(const rd_body_def *d, double mass, const double size[3], double alpha);

/* -q given (rd_cli_scenario takes it for every subcommand): no progress line, shorter output. */
extern int rd_cli_quiet;

/* cli_progress.c: a progress line on stderr (simulated time, runs, elapsed, ETA) while the
 * library runs simulations; only when stderr is a terminal and not -q. runs_expected: 1 for one
 * run, an estimate for an ensemble. Stop erases the line. */
void rd_cli_progress_start(const char *what, int runs_expected);
void rd_cli_progress_stop(void);
void rd_cli_progress_clear(void); /* erase the line (before printing a result); keeps counting */

/* cli_help.c: the page of subcommand `sub` (NULL: the global usage) on out; 0, or -1 (nothing
 * printed) for an unknown subcommand. */
int rd_cli_help(const char *sub, FILE *out);
/* cli_help.c: 1 when sub names a subcommand (one with a help page), else 0. */
int rd_cli_is_subcommand(const char *sub);

/* cli_keys.c: every --set key with units, default and meaning (tsv: tab-separated). */
void rd_cli_keys(int tsv);

/* One line of intensity measures per applied record component (cli_motion.c). 0 or -1. */
int rd_cli_print_motion(const rd_motion_def *m);

/* --- cli_sweep.c ----------------------------------------------------------------------------- */

/* A distributed backend (bin/rockdem-mpi): rank > 0 serves cases; rank 0 opens a pool. */
typedef struct rd_sweep_backend {
    int rank;
    int size;
    int (*serve)(const rd_sweep_plan *p);                     /* worker ranks: exit status */
    int (*open)(const rd_sweep_plan *p, rd_sweep_pool *pool); /* coordinator: 0 or -1 */
} rd_sweep_backend;

/* rockdem sweep with the given backend (NULL: the fork pool). Returns the exit status. */
int rd_cli_sweep_with(int argc, char **argv, const rd_sweep_backend *b);

#endif
