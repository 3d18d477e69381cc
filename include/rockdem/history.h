/* rockdem — the histories of a run (`history body|joint|energy ...`, rd_scenario.history): a
 * table sampled every `history interval` seconds of shaking, column 0 the time (s), and the
 * series that name its columns. Observers write it (the HDF5 file: /history); a script reads
 * it after rd_sim_run. */
#ifndef ROCKDEM_HISTORY_H
#define ROCKDEM_HISTORY_H

#include "rockdem/api.h"
#include "rockdem/rockdem.h"

/* One recorded quantity: columns [col, col + ncol) of the table. */
typedef struct rd_history_series {
    char path[3 * RD_NAME_MAX + 40]; /* its place under /history: "body/<name>/position",
                                        "joint/<a>-<b>/slip", "energy" */
    const char *units;               /* e.g. "m", "N", "J" */
    const char *long_name;           /* what it is */
    const char *dim;                 /* its columns' axis: a root scale ("/xyz"), a name local to
                                        its group ("xyz_magnitude"), or NULL for one column */
    const char *labels;              /* the columns' names, comma-separated (NULL: one column) */
    int col, ncol;
} rd_history_series;

/* Series recorded (0 without `history` commands). */
RD_API int rd_sim_history_count(const rd_sim *sim);
RD_API void rd_sim_history_series(const rd_sim *sim, int k, rd_history_series *out);

/* The table: rows x cols doubles, row-major (valid until the next step or rd_sim_free). */
RD_API const double *rd_sim_history_table(const rd_sim *sim, long *rows, int *cols);

#endif
