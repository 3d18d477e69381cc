/* rockdem (private) — the scene-control tables of a run file (output_scene.c).
 * Folder io/ owns the HDF5 output file; it may call base/ and the public headers, never engine/
 * internals or cli/.
 */
#ifndef RD_IO_OUTPUT_SCENE_H
#define RD_IO_OUTPUT_SCENE_H

#include "io/io_hdf5.h"

/* /history, /joints and /outcomes of a finished run. 0, or -1 with err. */
int rd_h5_scene_tables(rd_h5 *h, const rd_sim *sim, const rd_summary *s, rd_error *err);

#endif
