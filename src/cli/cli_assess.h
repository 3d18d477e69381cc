/* rockdem (private) — `rockdem assess`: its options (cli_assess.c) and its tables and JSON
 * (cli_assess_report.c).
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#ifndef RD_CLI_ASSESS_H
#define RD_CLI_ASSESS_H

#include "rockdem/assess.h"

typedef struct assess_args {
    char spectrum[RD_PATH_MAX]; /* "en1998-1A" .. "en1998-2E" or a table file */
    double ag;                  /* EN: a_g, m/s^2 (0: not given) */
    double damping;             /* table: its damping ratio */
    double kv;                  /* vertical / horizontal */
    double mu;                  /* < 0: from the scene's friction angle */
    double limit;               /* allowable sliding distance, m (< 0: the pad's edge) */
    int codes[RD_NCODES];       /* 1: checked */
    int neglect;                /* EN: neglect a vertical PGA under 0.25 g */
    char body[RD_NAME_MAX];
    char out[RD_PATH_MAX];
    rd_evidence_def ev;
    double slide_damping;
} assess_args;

/* Compute every check for body `body` of sc, print the tables and write OUT/assess.json
 * (phi_scene: the friction angle mu came from, rad; < 0 when --mu gave it). Exit status: 0,
 * 2 bad input, 3 a run failed. */
int rd_cli_assess_report(const rd_scenario *sc, int body, const assess_args *a,
                         const rd_spectrum *h, const rd_assess_body *ab, double phi_scene);

#endif
