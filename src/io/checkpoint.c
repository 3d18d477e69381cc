/* rockdem — checkpoint files: `model save 'state.h5'` writes the settled state, `model restore
 * 'state.h5'` (in a scenario with the same blocks) starts from it instead of settling; and
 * rd_sim_create, which wires both to a scenario: the engine's rd_sim_build, then the restore
 * read at once, or the save as an observer whose begin (the scene at rest, before the initial
 * conditions) writes the file. What the state holds is the engine's (engine/state.h); this
 * file stores it.
 *
 * The file is HDF5: readable datasets for the bodies (/bodies/names, position, quaternion,
 * velocity, angular_momentum, and as built: fixed, vertex_count, mass, inertia, vertices) and
 * the engine's contact tables under /state (pairs and joints as raw records with their record
 * size, checked on restore, so a checkpoint is tied to the rockdem build that wrote it, like
 * 3DEC's save files). Restore refuses a scene whose blocks differ from the saved ones in name,
 * shape, mass, moments of inertia or, for fixed blocks, pose (to RD_STATE_BUILD_RTOL).
 * Folder io/ owns the HDF5 files; it may call base/, records/, the engine's public API and its
 * state image (engine/state.h), never cli/.
 */
#include "base/fault.h"
#include "base/path.h"
#include "engine/state.h"
#include "io/io_table.h"
#include "rockdem/observer.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static rd_h5t_type h5t_type(rd_state_type t)
{
    return t == RD_STATE_INT ? RD_H5T_INT : t == RD_STATE_BYTE ? RD_H5T_BYTE : RD_H5T_DOUBLE;
}

/* The blocks as built (engine/state.h: rd_state_build), for restore to check. 0 or -1. */
static int write_build(rd_sim *s, long long f, rd_error *err)
{
    rd_state_build b;
    if (rd_state_build_of(s, &b)) return rd_error_set(err, "out of memory");
    rd_state_array a[RD_STATE_ARRAYS];
    int na = rd_state_build_arrays(&b, a), rc = 0;
    for (int k = 0; k < na && !rc; k++)
        rc = rd_h5t_write(f, a[k].name, h5t_type(a[k].type), a[k].data, a[k].n, 0, NULL, NULL, NULL,
                          err);
    rd_state_build_free(&b);
    return rc;
}

static int write_image(rd_sim *s, long long f, rd_error *err)
{
    const rd_scenario *sc = rd_sim_scenario(s);
    long h[RD_STATE_HEADER];
    double fig[2];
    rd_state_capture(s, h, fig);
    const char **names = malloc((size_t)sc->nbodies * sizeof *names);
    int rc = names ? 0 : rd_error_set(err, "out of memory");
    for (int i = 0; names && i < sc->nbodies; i++) names[i] = sc->bodies[i].name;
    if (!rc) rc = rd_h5t_strings(f, "bodies/names", names, sc->nbodies, "block names", NULL, err);
    free(names);
    if (!rc)
        rc = rd_h5t_write(f, "state/header", RD_H5T_LONG, h, RD_STATE_HEADER, 0, NULL,
                          RD_STATE_HEADER_NAMES, NULL, err);
    if (!rc)
        rc = rd_h5t_write(f, "state/settle", RD_H5T_DOUBLE, fig, 2, 0, NULL,
                          "settle time (s), unbalanced-force ratio reached", NULL, err);
    rd_state_array a[RD_STATE_ARRAYS];
    int na = rd_state_arrays(s, a);
    for (int k = 0; k < na && !rc; k++)
        rc = rd_h5t_write(f, a[k].name, h5t_type(a[k].type), a[k].data, a[k].n, 0, NULL, NULL, NULL,
                          err);
    return rc ? rc : write_build(s, f, err);
}

/* The observer's begin: the scene has settled; write it to the path (user), atomically: to a
 * temporary beside it, renamed over it once whole (a kill leaves the earlier checkpoint or the
 * new one, never a part). */
static int save_at_rest(void *user, rd_sim *s, rd_error *err)
{
    const char *path = user;
    char tmp[RD_PATH_MAX];
    int fd = rd_path_temp(path, tmp);
    if (fd < 0)
        return rd_error_set(err, "%s: model save: cannot create a temporary file beside it: %s",
                            path, strerror(errno));
    close(fd);
    long long f = rd_h5t_create(tmp, err);
    int rc = f < 0 ? -1 : write_image(s, f, err);
    if (f >= 0) rd_h5t_close(f);
    rd_fault_point("checkpoint-rename");
    if (!rc && rd_path_commit(tmp, path))
        rc = rd_error_set(err, "cannot rename the new checkpoint into place: %s", strerror(errno));
    if (rc) unlink(tmp);
    if (rc) {
        char m[RD_ERROR_MAX];
        snprintf(m, sizeof m, "%s", err->msg);
        rd_error_set(err, "%s: model save: %s", path, m);
    }
    return rc;
}

/* The checkpoint's block names, when it holds as many as the scene (else NULL). */
static char **read_names(long long f, long nb, rd_error *err)
{
    char **names = calloc((size_t)nb + 1, sizeof *names);
    for (long i = 0; names && i < nb; i++) {
        names[i] = malloc(RD_NAME_MAX);
        if (!names[i] || rd_h5t_string(f, "bodies/names", (int)i, names[i], RD_NAME_MAX, err)) {
            for (long j = 0; j <= i; j++) free(names[j]);
            free(names);
            return NULL;
        }
    }
    return names;
}

/* The checkpoint's blocks as built (nb of them) into b, which the caller frees: 0, or -1 (err). */
static int read_build(long long f, int nb, rd_state_build *b, rd_error *err)
{
    long n = rd_h5t_count(f, "bodies/vertices"), sum = 0;
    if (n < 0 || n % 3)
        return rd_error_set(err, "dataset 'bodies/vertices': %s", n < 0 ? "missing" : "wrong size");
    if (rd_state_build_alloc(b, nb, n / 3)) return rd_error_set(err, "out of memory");
    rd_state_array a[RD_STATE_ARRAYS];
    int na = rd_state_build_arrays(b, a);
    for (int k = 0; k < na; k++)
        if (rd_h5t_read(f, a[k].name, h5t_type(a[k].type), a[k].data, a[k].n, err)) return -1;
    if (rd_h5t_read(f, "bodies/position", RD_H5T_DOUBLE, b->x, 3L * nb, err) ||
        rd_h5t_read(f, "bodies/quaternion", RD_H5T_DOUBLE, b->q, 4L * nb, err))
        return -1;
    for (int i = 0; i < nb && sum >= 0; i++) sum = b->nv[i] < 0 ? -1 : sum + b->nv[i];
    if (sum != b->nvert)
        return rd_error_set(
            err, "dataset 'bodies/vertex_count' does not count the %ld of bodies/vertices",
            b->nvert);
    return 0;
}

/* Does the image fit s (the same blocks, by name, shape, mass and fixed pose)? NULL, or what
 * is wrong (in buf, err's message or a constant). */
static const char *image_mismatch(rd_sim *s, long long f, const long h[RD_STATE_HEADER], char *buf,
                                  size_t n, rd_error *err)
{
    int nb = rd_sim_scenario(s)->nbodies;
    int same = h[RD_STATE_H_VERSION] == RD_STATE_VERSION && h[RD_STATE_H_NB] == nb;
    char **names = same ? read_names(f, nb, err) : NULL;
    rd_state_build there = { 0 };
    const char *bad =
        same && !names ? "no block names"
        : same && read_build(f, nb, &there, err)
            ? err->msg
            : rd_state_mismatch(s, h, (const char *const *)names, same ? &there : NULL, buf, n);
    for (int i = 0; names && i < nb; i++) free(names[i]);
    free(names);
    rd_state_build_free(&there);
    return bad;
}

/* NULL when the image was read into s, else what is wrong (in buf, err's message or a constant). */
static const char *read_image(rd_sim *s, long long f, char *buf, size_t n, rd_error *err)
{
    long h[RD_STATE_HEADER];
    double fig[2];
    if (rd_h5t_read(f, "state/header", RD_H5T_LONG, h, RD_STATE_HEADER, err) ||
        rd_h5t_read(f, "state/settle", RD_H5T_DOUBLE, fig, 2, err))
        return "not a rockdem checkpoint (no /state/header)";
    const char *bad = image_mismatch(s, f, h, buf, n, err);
    if (!bad && rd_state_reserve(s, h)) bad = "out of memory";
    rd_state_array a[RD_STATE_ARRAYS];
    int na = bad ? 0 : rd_state_arrays(s, a);
    for (int k = 0; k < na && !bad; k++)
        if (rd_h5t_read(f, a[k].name, h5t_type(a[k].type), a[k].data, a[k].n, err)) bad = err->msg;
    if (!bad) rd_state_restored(s, fig);
    return bad;
}

static int restore(rd_sim *s, const char *path, rd_error *err)
{
    const char *file = rd_sim_scenario(s)->file;
    if (rd_path_special(path))
        return rd_error_set(err, "%s: model restore '%s': %s", file, path, RD_PATH_INPUT_NOT_FILE);
    long long f = rd_h5t_open(path, err);
    if (f < 0)
        return rd_error_set(err, "%s: model restore: cannot open '%s' as a checkpoint", file, path);
    char buf[RD_ERROR_MAX]; /* what differs: block names, numbers and the words around them */
    const char *bad = read_image(s, f, buf, sizeof buf, err);
    rd_h5t_close(f);
    if (!bad) return 0;
    char msg[RD_ERROR_MAX];
    snprintf(msg, sizeof msg, "%s", bad);
    return rd_error_set(err, "%s: model restore '%s': %s", file, path, msg);
}

rd_sim *rd_sim_create(const rd_scenario *sc, rd_error *err)
{
    rd_sim *s = rd_sim_build(sc, err);
    if (!s) return NULL;
    const rd_scenario *own = rd_sim_scenario(s); /* its paths live as long as s */
    const rd_observer save = { .user = (void *)own->save_path, .begin = save_at_rest };
    int rc = own->restore_path[0] ? restore(s, own->restore_path, err)
             : own->save_path[0]
                 ? rd_path_check_save(own, err) || rd_sim_add_observer(s, &save, err)
                 : 0;
    if (rc) {
        rd_sim_free(s);
        return NULL;
    }
    return s;
}
