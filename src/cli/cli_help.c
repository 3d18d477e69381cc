/* rockdem — `rockdem --help`, `rockdem help SUB` and `rockdem SUB --help`: the global usage and
 * one page per subcommand listing every option it takes, with units and defaults.
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"

#include <stdio.h>
#include <string.h>

static const char *const global_usage =
    "usage: rockdem SUBCOMMAND FILE [options]      (rockdem SUBCOMMAND --help for its options)\n"
    "  run FILE          settle, shake, write the HDF5 run file, print a summary\n"
    "  check FILE        read and build everything run would, write nothing\n"
    "  reference FILE    the rigid Housner (1 block) / Kounadis (2 blocks) solution, same output\n"
    "  threshold FILE    minimum overturning amplitude of the pulse (a curve with --frequencies)\n"
    "  restitution FILE  measure the DEM's restitution in free rocking and calibrate damping\n"
    "  study FILE        error against run time of your KN and time-step settings\n"
    "  sweep FILE        parallel, resumable fragility sweep into an HDF5 table\n"
    "  assess FILE       code checks (ASCE 7, EN 1998, KTA, ASCE 43-05) and time histories\n"
    "  keys              every --set key with its units and default\n"
    "  --version         print the version\n"
    "Options common to the subcommands that read FILE:\n"
    "  --set KEY=VALUE   override one setting (repeatable; `rockdem keys` lists them;\n"
    "                    --set help prints the list)\n"
    "  -q                quiet: no progress line, shorter output (progress shows only on a\n"
    "                    terminal)\n";

typedef struct sub_help {
    const char *name;
    const char *text;
} sub_help;

static const sub_help pages[] = {
    { "assess",
      "usage: rockdem assess FILE [--spectrum en1998-TG|TABLE] [--ag A] [--damping Z]\n"
      "                 [--vertical KV] [--mu MU] [--slide-limit M] [--code LIST]\n"
      "                 [--neglect-vertical] [--records N] [--seed S] [--duration S]\n"
      "                 [--slide-damping Z] [--body NAME] [--out DIR] [--set KEY=VALUE]... [-q]\n"
      "Seismic assessment of the scene's unanchored body on its pad (docs/ASSESS.md): the\n"
      "static rocking and sliding checks of ASCE/SEI 7-10, EN 1990/1998 and KTA 2201 (seed\n"
      "001 Table 2), ASCE/SEI 43-05 A.2 rocking angle and A.1 sliding distance (SF 2.0), the\n"
      "allowable PGA of each, and N spectrum-compatible records through the DEM (mean and\n"
      "sd of the peak tilt and slide, SF 3.0 on sliding). Writes DIR/assess.json, the\n"
      "records (CSV) and runs (HDF5); tools/rdassess.py DIR writes the report.\n"
      "  --spectrum S      en1998-TG: EN 1998-1 type T (1, 2), ground G (A-E) (default\n"
      "                    en1998-1A); else a table file: period (s), Sa (g), from T = 0\n"
      "  --ag A            EN: design ground acceleration a_g, m/s^2 or with g (required)\n"
      "  --damping Z       table: its damping ratio (default 0.05)\n"
      "  --vertical KV     vertical = KV x horizontal (default 2/3: seed 001 Fig. 29)\n"
      "  --mu MU           friction coefficient (default tan of the pad joint's angle)\n"
      "  --slide-limit M   allowable sliding distance, m (default: to the pad's edge)\n"
      "  --code LIST       static checks: asce7,en1998,kta (default all)\n"
      "  --neglect-vertical  EN: drop a vertical PGA below 0.25 g (EN 1998-1 4.3.3.5.2)\n"
      "  --records N       time histories: 0 (none) or 5 to 32 (default 5)\n"
      "  --seed S          first generator seed (default 1)\n"
      "  --duration S      record length, s (default 20)\n"
      "  --slide-damping Z A.1 secant damping (default 2/pi, a friction loop's)\n"
      "  --body NAME       the body to assess (default: the only free one)\n"
      "  --out DIR         report folder (default: FILE's stem + _assess)\n"
      "Exit status: 0 assessed (verdicts in the output), 2 bad input, 3 a run failed.\n" },
    { "run",
      "usage: rockdem run FILE [--set KEY=VALUE]... [-o OUT.h5] [-q] [--force] [--overwrite]\n"
      "Settle the scene under gravity, shake it for the scenario's duration and write the\n"
      "HDF5 run file (docs/HDF5-LAYOUT.md); print one verdict line per free body.\n"
      "  -o OUT.h5         output file (default: the scenario's `output hdf5`, else rockdem.h5);\n"
      "                    an earlier run file there is replaced once this run ends done or\n"
      "                    overturned (--overwrite: in place); a link or any other file is\n"
      "                    refused\n"
      "  --set KEY=VALUE   override a setting, e.g. --set motion.amplitude=0.4g (rockdem keys)\n"
      "  -q                no progress line, no intensity-measure or performance lines\n"
      "  --force           run even when the estimated step count exceeds 1e9 (docs/LIMITS.md)\n"
      "  --overwrite       write over an earlier run file at the output in place (a failed or\n"
      "                    killed run then leaves its own part there, not the earlier file)\n"
      "Exit status: 0 done or overturned, 2 bad input, 3 unstable, I/O error (disk full, file\n"
      "size limit, file removed: one line names the file and the reason), a body passed into\n"
      "another (penetrated) or fell out of the scene (lost); 130 Ctrl-C, SIGTERM or SIGHUP\n"
      "(the file then holds everything so far).\n" },
    { "check",
      "usage: rockdem check FILE [--set KEY=VALUE]... [-o OUT.h5] [-q] [--force] [--strict]\n"
      "Read and build everything run would, writing nothing: the scenario (every number\n"
      "within its range, docs/LIMITS.md), meshes (read and checked), records (read; their\n"
      "intensity measures printed unless -q), the perturbed subcontact points, the time\n"
      "step and the step budget (1e9 steps; --force lifts it), the output folder. Then\n"
      "reports the time step and its limit, every block (mass, volume, tipping angle,\n"
      "subcontacts, what it rests on), the joints and the measured cost of a simulated\n"
      "second, and warns of a block with nothing under it, a block placed above its\n"
      "support, overlapping blocks, a joint whose static sink W / (KN A) at rest exceeds\n"
      "the contact band, a step far below the output interval and a record shorter than\n"
      "the run; echoes every dimensional input with its units ('inputs:'\n"
      "lines) and warns of values that look like a unit mistake, with the likely intent\n"
      "(friction in degrees under 1.5, gravity off the Earth's, an amplitude under 1 m/s^2\n"
      "without g, a PGA above 5 g, a body over 100 m across, a mesh tipping under 0.5 deg).\n"
      "The last line is 'FILE: ok (...)' or 'FILE: N warnings (...)'. Exit status 0 when\n"
      "valid (warnings included; 1 with --strict when it warns), 2 with one line naming\n"
      "file, line and problem. Options may come before or after FILE.\n" },
    { "reference",
      "usage: rockdem reference FILE [--set KEY=VALUE]... [-o OUT.h5]\n"
      "Solve the scene as rigid blocks with CVODE: Housner's equation for one free brick\n"
      "on a fixed base, Kounadis' two-block equations for a stack of two. Same HDF5\n"
      "layout as run. Restitution: `model reference restitution e` (default Housner's r).\n"
      "  -o OUT.h5         output file\n"
      "  --set KEY=VALUE   override a setting (rockdem keys)\n" },
    { "threshold",
      "usage: rockdem threshold FILE [--engine dem|reference] [--lo A] [--hi A] [--rtol R]\n"
      "                 [--steps N] [--frequencies F1,F2,...] [-j N] [--set KEY=VALUE]... [-q]\n"
      "Minimum amplitude of the scenario's horizontal pulse that overturns the scene:\n"
      "a coarse scan from --lo to --hi, then bisection. Prints it in m/s^2, in g and as\n"
      "a / (g tan alpha), with w / p.\n"
      "  --engine dem|reference  the DEM (default) or the rigid reference solver\n"
      "  --lo A, --hi A    amplitude range, m/s^2 or with a g suffix (default 0.9 and 10\n"
      "                    times the static uplift threshold g tan alpha), lo < hi <= 1e6\n"
      "  --rtol R          bisection stops when (hi - lo) / hi < R, 1e-6 to 1 (default\n"
      "                    0.005; 1: no bisection)\n"
      "  --steps N         coarse scan steps from lo to hi, 1 to 1000 (default 24)\n"
      "  --frequencies F1,F2,...  one threshold per pulse frequency (Hz): the\n"
      "                    minimum-overturning curve a / (g tan alpha) against w / p\n"
      "  -j N              coarse-scan runs at once, one worker process each (default:\n"
      "                    the number of cores); the result does not depend on it\n"
      "  --set KEY=VALUE   override a setting (rockdem keys)\n"
      "  -q                no progress line\n" },
    { "restitution",
      "usage: rockdem restitution FILE [--target R] [--rtol R] [--theta0 RAD] [--body NAME]\n"
      "       [--set KEY=VALUE]... [-q]\n"
      "Free rocking of the scene's single block: the DEM's effective restitution\n"
      "r = w_after / w_before (mean of the first 3 impacts) for KN 1e8..1e11 Pa/m and\n"
      "contact restitution 0..1, then the contact restitution that reaches the target\n"
      "at the scenario's KN (to 0.002, or --rtol), checked by the second measure.\n"
      "r is measured twice: by amplitude decay (the energy left after each whole\n"
      "half-cycle) and, in brackets, from the speeds at equal |theta| before and\n"
      "after each impact (a quarter to three quarters of the smaller amplitude), both\n"
      "carried to theta = 0 by energy. They agree to 0.5 % when each impact is over\n"
      "within that band; a larger bracket means the block still bounces on its new\n"
      "pivot after impact.\n"
      "Under contact model surface (no permanent set) the impact loss is the joint's\n"
      "dashpot: restitution 1, and the dashpot's ratio (model damping viscous) is\n"
      "scanned over 0.05..5 and calibrated instead.\n"
      "  --target R        restitution to reach, in (0, 1] (default Housner's r = 1 - 1.5 sin^2 alpha)\n"
      "  --rtol R          stop the calibration at |r - target| < R, 1e-4 to 0.002 (default 0.002)\n"
      "  --theta0 RAD      initial tilt, rad, in (0, alpha) (default alpha / 2)\n"
      "  --body NAME       in a scene of several free bodies (a stack, a column, a statue\n"
      "                    on a pedestal): NAME's free rocking on what holds it up, held\n"
      "                    fixed, the bodies above it removed: calibrates the joint under it\n"
      "  --set KEY=VALUE   override a setting (rockdem keys)\n"
      "  -q                no progress line\n"
      "Exit status 4 when the target cannot be reached (the closest r is printed).\n" },
    { "study",
      "usage: rockdem study FILE [--set KEY=VALUE]... [-q]\n"
      "Runs the scene at KN x {0.1, 1, 10} and time-step safety x {2, 1, 0.5}; the finest\n"
      "is the yardstick. For each run: wall time and the differences from the yardstick in\n"
      "max tilt (relative), first impact time (s) and overturning.\n"
      "  --set KEY=VALUE   override a setting (rockdem keys)\n"
      "  -q                no progress line\n" },
    { "sweep",
      "usage: rockdem sweep FILE [--set KEY=VALUE]... [--axis KEY=V1,V2,...]... [--records F1,F2,...]\n"
      "             [--scales S1,S2,...] [--directions D1,D2,...] [-j N] [--keep-runs DIR] [--full]\n"
      "             [-q] -o TABLE.h5\n"
      "Every combination of the axes (the last varies fastest) is one DEM run; results go\n"
      "to the HDF5 table /sweep as they finish. Running the same command again resumes it.\n"
      "  --axis KEY=V1,V2  a --set key and its values (repeatable); interface=K sweeps K\n"
      "                    seeded interface perturbations\n"
      "  --records F1,F2   record files (h1) to apply in turn\n"
      "  --scales S1,S2    0.3g = scale each record to that PGA (m/s^2 or g); 2 = a factor\n"
      "  --directions D1,D2  motion direction, degrees from +x\n"
      "  -j N              worker processes (default: the number of cores)\n"
      "  --keep-runs DIR   keep every case's run file in DIR (default: deleted)\n"
      "  --full            run every case to its end (default: a case ends once at rest\n"
      "                    and the motion left cannot lift or slide it; column quiet_end)\n"
      "  -o TABLE.h5       the table (required); docs/FRAGILITY.md, docs/HDF5-LAYOUT.md\n"
      "  -q                no progress line\n" },
    { "keys",
      "usage: rockdem keys [--tsv]\n"
      "Every key --set accepts, with its units, default and meaning (--tsv: tab-separated,\n"
      "one header line). block.<name>.<field> keys apply to the named block.\n" },
};

/* The help page of subcommand sub, or NULL when rockdem has no such subcommand. */
static const char *page_of(const char *sub)
{
    for (size_t i = 0; i < sizeof pages / sizeof pages[0]; i++)
        if (!strcmp(sub, pages[i].name)) return pages[i].text;
    return NULL;
}

int rd_cli_is_subcommand(const char *sub) { return page_of(sub) != NULL; }

int rd_cli_help(const char *sub, FILE *out)
{
    const char *text = sub ? page_of(sub) : global_usage;
    if (!text) return -1;
    fputs(text, out);
    return 0;
}
