/* rockdem — progress of running simulations (rd_set_progress in rockdem.h): one callback for
 * the process, called by rd_sim_run every RD_PROGRESS_STEPS steps and when the run ends, so a
 * command-line bar or a Python binding can show how far a run (or an ensemble of runs) is.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"

static rd_progress_fn progress_fn;
static void *progress_ctx;

void rd_set_progress(rd_progress_fn fn, void *ctx)
{
    progress_fn = fn;
    progress_ctx = ctx;
}

void rd_progress_report(double t, double t_end)
{
    if (progress_fn) progress_fn(progress_ctx, t, t_end);
}
