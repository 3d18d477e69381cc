/* rockdem — the HDF5 file of a run, as an observer (rockdem/observer.h). Its layout is in
 * src/io/io_hdf5.h and docs/ARCHITECTURE.md. */
#ifndef ROCKDEM_OUTPUT_H
#define ROCKDEM_OUTPUT_H

#include "rockdem/api.h"
#include "rockdem/rockdem.h"

/* Write the run's HDF5 file at path: the file is created (truncated) now, with the scenario
 * and the bodies; samples, events and the summary follow during rd_sim_run; rd_sim_free closes
 * it. Call after rd_sim_create, before rd_sim_run. 0, or -1 with err (the file cannot be
 * created). */
RD_API int rd_sim_write_hdf5(rd_sim *sim, const char *path, rd_error *err);

#endif
