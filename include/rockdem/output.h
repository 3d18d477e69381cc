/* rockdem — the HDF5 file of a run, as an observer (rockdem/observer.h). Its layout is in
 * src/io/io_hdf5.h and docs/ARCHITECTURE.md. */
#ifndef ROCKDEM_OUTPUT_H
#define ROCKDEM_OUTPUT_H

#include "rockdem/api.h"
#include "rockdem/rockdem.h"

#include <stddef.h>

/* Write the run's HDF5 file at path: the file is created now, with the scenario and the
 * bodies; samples, events and the summary follow during rd_sim_run (flushed as they go, so a
 * killed run leaves a valid file with what it had); rd_sim_free closes it. Where path already
 * holds a file (an earlier run's: any other file is refused) and the scenario has no `force`,
 * the run writes rd_output_staging's temporary beside it instead and renames it over path once
 * the run ends done or overturned; a run that fails, is interrupted or killed leaves path as it
 * was and its own output in the temporary. Call after rd_sim_create, before rd_sim_run. 0, or
 * -1 with err (the file cannot be created, or path is a link, a sweep table, not rockdem's). */
RD_API int rd_sim_write_hdf5(rd_sim *sim, const char *path, rd_error *err);

/* The temporary a run writes while path holds an earlier file: "<path>.tmp-<process id>", into
 * buf (n bytes). 1 when path holds a non-empty file and `overwrite` (rd_scenario.overwrite) is 0
 * (the run will write the temporary), else 0 (it writes path itself). Ask before
 * rd_sim_write_hdf5 creates the file. */
RD_API int rd_output_staging(const char *path, int overwrite, char *buf, size_t n);

#endif
