/* rockdem — the files a run writes, checked before it writes them (base/path.h).
 * Folder base/ owns errors, vectors, named constants and these path checks; it calls nothing
 * else in rockdem.
 */
#include "base/path.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int rd_path_same(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    return strcmp(a, b) == 0;
}

int rd_path_creatable(const char *path, char dir[RD_PATH_MAX])
{
    snprintf(dir, RD_PATH_MAX, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash == dir)
        slash[1] = '\0';
    else if (slash)
        *slash = '\0';
    else
        snprintf(dir, RD_PATH_MAX, ".");
    if (access(dir, W_OK | X_OK)) return 1;
    return access(path, F_OK) == 0 && access(path, W_OK) ? 2 : 0;
}

int rd_path_special(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && !S_ISREG(st.st_mode);
}

/* The record component c of sc reads a file (AT2, text, FEMA set), not a generator. */
static int reads_record(const rd_scenario *sc, int c)
{
    rd_record_source s = sc->motion.record[c].source;
    return s == RD_SOURCE_AT2 || s == RD_SOURCE_TEXT || s == RD_SOURCE_FEMA;
}

/* Which file sc reads that `path` is, into buf; NULL when none. */
static const char *input_named(const rd_scenario *sc, const char *path, char *buf, size_t n)
{
    if (sc->file[0] && rd_path_same(path, sc->file)) {
        snprintf(buf, n, "it is the scenario file being read (%s)", sc->file);
        return buf;
    }
    if (sc->restore_path[0] && rd_path_same(path, sc->restore_path))
        return "it is the checkpoint the scenario restores (model restore)";
    for (int c = 0; c < RD_NCOMPONENTS; c++)
        if (reads_record(sc, c) && rd_path_same(path, sc->motion.record[c].path))
            return "it is a ground-motion record the scenario reads";
    for (int i = 0; i < sc->nbodies; i++)
        if (sc->bodies[i].shape == RD_SHAPE_MESH && rd_path_same(path, sc->bodies[i].mesh)) {
            snprintf(buf, n, "it is the mesh of block '%s'", sc->bodies[i].name);
            return buf;
        }
    return NULL;
}

/* Which of rockdem's files an HDF5 file is, from its root: 'r' run file, 'c' checkpoint, 's'
 * sweep table, 'l' locked (open for writing elsewhere: HDF5's file lock), 0 another program's
 * (or unreadable). */
static int hdf5_kind(const char *path)
{
    int kind = 0;
    H5E_BEGIN_TRY
    {
        errno = 0;
        hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
        if (f < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) kind = 'l';
        if (f >= 0) {
            if (H5Lexists(f, "sweep", H5P_DEFAULT) > 0)
                kind = 's';
            else if (H5Lexists(f, "state", H5P_DEFAULT) > 0)
                kind = 'c';
            else if (H5Aexists(f, "program") > 0 && H5Lexists(f, "bodies", H5P_DEFAULT) > 0)
                kind = 'r';
            H5Fclose(f);
        }
    }
    H5E_END_TRY;
    return kind;
}

const char *rd_path_replace_conflict(const char *path, rd_path_output kind)
{
    struct stat st;
    if (lstat(path, &st)) return NULL; /* nothing there */
    if (S_ISLNK(st.st_mode))
        return "it is a symbolic link (rockdem does not write through links: remove it or give the file's own path)";
    if (!S_ISREG(st.st_mode)) return RD_PATH_NOT_FILE;
    if (st.st_size == 0) return NULL;
    htri_t h5 = 0;
    H5E_BEGIN_TRY { h5 = H5Fis_hdf5(path); }
    H5E_END_TRY;
    if (h5 <= 0)
        return "it exists and is not an HDF5 file of rockdem (remove it or choose another path)";
    int k = hdf5_kind(path);
    if (k == 'l') return RD_PATH_LOCKED;
    if (k == 's') return "it is a sweep table (rockdem sweep): choose another path";
    if (k == 'r' && kind == RD_OUTPUT_RUN) return NULL;
    if (k == 'c' && kind == RD_OUTPUT_CHECKPOINT) return NULL;
    if (k == 'r') return "it is a run file of rockdem, not a checkpoint: choose another path";
    if (k == 'c') return "it is a checkpoint (model save), not a run file: choose another path";
    return "it is an HDF5 file rockdem did not write (remove it or choose another path)";
}

const char *rd_path_output_conflict(const rd_scenario *sc, const char *path, const char *save,
                                    rd_path_output kind, char *buf, size_t n)
{
    const char *in = input_named(sc, path, buf, n);
    if (in) return in;
    if (save && save[0] && rd_path_same(path, save))
        return "it is also the run's checkpoint (model save)";
    return rd_path_replace_conflict(path, kind);
}

int rd_path_check_save(const rd_scenario *sc, rd_error *err)
{
    char why[RD_ERROR_MAX], dir[RD_PATH_MAX];
    const char *save = sc->save_path;
    const char *bad =
        save[0] ? rd_path_output_conflict(sc, save, NULL, RD_OUTPUT_CHECKPOINT, why, sizeof why)
                : NULL;
    if (bad) return rd_error_set(err, "%s: model save '%s': %s", sc->file, save, bad);
    int no = save[0] ? rd_path_creatable(save, dir) : 0;
    if (no == 1)
        return rd_error_set(err, "%s: model save '%s': cannot create the file in %s: %s", sc->file,
                            save, dir, strerror(errno));
    if (no == 2)
        return rd_error_set(err, "%s: model save '%s': cannot overwrite the file: %s", sc->file,
                            save, strerror(errno));
    return 0;
}

int rd_path_check_output(const rd_scenario *sc, const char *path, const char *save, rd_error *err)
{
    char why[RD_ERROR_MAX], dir[RD_PATH_MAX];
    const char *bad = rd_path_output_conflict(sc, path, save, RD_OUTPUT_RUN, why, sizeof why);
    if (bad) return rd_error_set(err, "%s: cannot write the output there: %s", path, bad);
    int no = rd_path_creatable(path, dir);
    if (no == 1)
        return rd_error_set(err, "%s: cannot create the output file in %s: %s", path, dir,
                            strerror(errno));
    if (no == 2)
        return rd_error_set(err, "%s: cannot overwrite the output file: %s", path, strerror(errno));
    return 0;
}

int rd_path_temp(const char *path, char tmp[RD_PATH_MAX])
{
    if (snprintf(tmp, RD_PATH_MAX, "%s.tmp-XXXXXX", path) >= RD_PATH_MAX) {
        errno = ENAMETOOLONG;
        return -1;
    }
    int fd = mkstemp(tmp);
    if (fd < 0) return -1;
    mode_t mask = umask(0);
    umask(mask);
    if (fchmod(fd, 0666 & ~mask)) { /* mkstemp makes it 0600: an output is as open would make it */
        int e = errno;
        close(fd);
        unlink(tmp);
        errno = e;
        return -1;
    }
    return fd;
}

/* fsync the file or folder at path. 0 or -1 (errno). */
static int sync_path(const char *path, int flags)
{
    int fd = open(path, flags);
    if (fd < 0) return -1;
    int rc = fsync(fd);
    int e = errno;
    close(fd);
    errno = e;
    return rc;
}

int rd_path_commit(const char *tmp, const char *path)
{
    char dir[RD_PATH_MAX];
    if (sync_path(tmp, O_RDONLY) || rename(tmp, path)) return -1;
    rd_path_creatable(path, dir); /* only for its folder name */
    sync_path(dir,
              O_RDONLY | O_DIRECTORY); /* best effort: some file systems refuse a folder's fsync */
    return 0;
}
