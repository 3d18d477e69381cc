/* rockdem (private) — the files a run writes, checked before it writes them: never a device,
 * folder or pipe (HDF5 cannot close such a file cleanly, and a pipe blocks the open), never a
 * file the scenario reads (the scenario itself, a record, a mesh, the checkpoint it restores)
 * nor one of its other outputs.
 * Folder base/ owns errors, vectors, named constants and these path checks; it calls nothing
 * else in rockdem (it reads the public rd_scenario struct only).
 */
#ifndef RD_PATH_H
#define RD_PATH_H

#include "rockdem/scenario.h"

#include <stddef.h>

/* 1 when a and b name the same file: the same device and inode where both exist, else the same
 * text. */
int rd_path_same(const char *a, const char *b);

/* Can a file be created at path? 0; 1 when its folder (into dir) is missing or not writable,
 * 2 when it exists and is not writable (errno says why in both). */
int rd_path_creatable(const char *path, char dir[RD_PATH_MAX]);

/* Why an output cannot go to an existing path that is not a regular file. */
#define RD_PATH_NOT_FILE                                                                           \
    "not a regular file (a device, folder or pipe): rockdem writes its outputs to files"

/* Why a file cannot be opened while HDF5's file lock is held by another process (EAGAIN from
 * the lock, "Resource temporarily unavailable"), and what to do. */
#define RD_PATH_LOCKED                                                                             \
    "it is open for writing in another program (HDF5's file lock: another rockdem, or "            \
    "h5py or HDFView with the file open): close it there or wait for that run to end, "            \
    "or choose another path"

/* 1 when path exists and is not a regular file (a device such as /dev/null, a folder, a pipe). */
int rd_path_special(const char *path);

/* Why a file a scenario reads (a mesh, a record, a checkpoint) cannot be one that rd_path_special
 * finds: a device such as /dev/zero never ends (the reader grew until memory ran out) and
 * opening a pipe without a writer blocks for ever. The readers check before they open. */
#define RD_PATH_INPUT_NOT_FILE                                                                     \
    "not a regular file (a device, folder or pipe): rockdem reads meshes, "                        \
    "records and checkpoints from files"

/* What an output may replace: a run file (`rockdem run`, `rockdem reference`: root attribute
 * program "rockdem" and a /bodies group, no /sweep) or a checkpoint (`model save`: /state). */
typedef enum rd_path_output { RD_OUTPUT_RUN, RD_OUTPUT_CHECKPOINT } rd_path_output;

/* Why an existing file at path must not be replaced by an output of kind `kind`: a symbolic link
 * (rockdem never writes through one: its target may be any file), a file that is not HDF5, an
 * HDF5 file rockdem did not write, a sweep table, or a file of the other kind; NULL when it
 * may be (no file, an empty file, or one of that kind). The reason is one line, a constant. */
const char *rd_path_replace_conflict(const char *path, rd_path_output kind);

/* Why `path` must not be written as an output of scenario sc (its HDF5 output, its `model save`
 * checkpoint, `kind`): "not a regular file ...", "it is the scenario file being read", a file
 * rd_path_replace_conflict refuses, ...; NULL when it may be. `save` is the run's `model save`
 * checkpoint ("" or NULL: none), which the HDF5 output must not be either. The reason is one
 * line, in buf (n bytes) or a constant. */
const char *rd_path_output_conflict(const rd_scenario *sc, const char *path, const char *save,
                                    rd_path_output kind, char *buf, size_t n);

/* The `model save` checkpoint of sc (none: 0) may be written: no conflict (above) and its
 * folder writable. 0, or -1 with err (one line naming the scenario and the checkpoint). */
int rd_path_check_save(const rd_scenario *sc, rd_error *err);

/* The HDF5 output of sc may be written at path, checked before any work: no conflict (above,
 * with the checkpoint `save`, "" or NULL: none) and its folder writable. 0, or -1 with err
 * (one line naming the output). Used by check (engine/sim.c) and reference. */
int rd_path_check_output(const rd_scenario *sc, const char *path, const char *save, rd_error *err);

/* Atomic replacement: write the new content to rd_path_temp's file, then rd_path_commit renames
 * it over the target, so a kill at any instant leaves the old file or the new one, never a mix.
 * rd_path_temp creates "<path>.tmp-XXXXXX" in path's folder (rename cannot cross file systems)
 * and returns its open descriptor (mode 0666 less the umask, as open would give), the name in tmp;
 * -1 with errno. */
int rd_path_temp(const char *path, char tmp[RD_PATH_MAX]);

/* Make the finished temporary tmp durable (fsync) and rename it to path, then sync path's folder
 * so the new name survives a crash. 0, or -1 with errno (tmp is left; the caller removes it). */
int rd_path_commit(const char *tmp, const char *path);

#endif
