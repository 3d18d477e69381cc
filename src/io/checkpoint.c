/* rockdem — checkpoint files: `model save 'state.h5'` writes the settled state, `model restore
 * 'state.h5'` (in a scenario with the same blocks) starts from it instead of settling; and
 * rd_sim_create, which wires both to a scenario: the engine's rd_sim_build, then the restore
 * read at once, or the save as an observer whose begin (the scene at rest, before the initial
 * conditions) writes the file. What the state holds is the engine's (engine/state.h); this
 * file stores it.
 *
 * The file is HDF5: readable datasets for the bodies (/bodies/names, position, quaternion,
 * velocity, angular_momentum) and the engine's contact tables under /state (pairs and joints
 * as raw records with their record size, checked on restore, so a checkpoint is tied to the
 * rockdem build that wrote it, like 3DEC's save files).
 * Folder io/ owns the HDF5 files; it may call base/, records/, the engine's public API and its
 * state image (engine/state.h), never cli/.
 */
#include "engine/state.h"
#include "io/io_table.h"
#include "rockdem/observer.h"

#include <stdio.h>
#include <stdlib.h>

static rd_h5t_type h5t_type(rd_state_type t)
{
    return t == RD_STATE_INT ? RD_H5T_INT : t == RD_STATE_BYTE ? RD_H5T_BYTE : RD_H5T_DOUBLE;
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
    if (!rc) rc = rd_h5t_write(f, "state/header", RD_H5T_LONG, h, RD_STATE_HEADER, 0, NULL,
                               RD_STATE_HEADER_NAMES, NULL, err);
    if (!rc) rc = rd_h5t_write(f, "state/settle", RD_H5T_DOUBLE, fig, 2, 0, NULL,
                               "settle time (s), unbalanced-force ratio reached", NULL, err);
    rd_state_array a[RD_STATE_ARRAYS];
    int na = rd_state_arrays(s, a);
    for (int k = 0; k < na && !rc; k++)
        rc = rd_h5t_write(f, a[k].name, h5t_type(a[k].type), a[k].data, a[k].n, 0, NULL, NULL, NULL, err);
    return rc;
}

/* The observer's begin: the scene has settled; write it to the path (user). */
static int save_at_rest(void *user, rd_sim *s, rd_error *err)
{
    const char *path = user;
    long long f = rd_h5t_create(path, err);
    int rc = f < 0 ? -1 : write_image(s, f, err);
    if (f >= 0) rd_h5t_close(f);
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

/* NULL when the image was read into s, else what is wrong (in buf, err's message or a constant). */
static const char *read_image(rd_sim *s, long long f, char *buf, size_t n, rd_error *err)
{
    long h[RD_STATE_HEADER];
    double fig[2];
    if (rd_h5t_read(f, "state/header", RD_H5T_LONG, h, RD_STATE_HEADER, err) ||
        rd_h5t_read(f, "state/settle", RD_H5T_DOUBLE, fig, 2, err))
        return "not a rockdem checkpoint (no /state/header)";
    int nb = rd_sim_scenario(s)->nbodies;
    char **names = h[RD_STATE_H_NB] == nb ? read_names(f, nb, err) : NULL;
    if (h[RD_STATE_H_NB] == nb && !names) return "no block names";
    const char *bad = rd_state_mismatch(s, h, (const char *const *)names, buf, n);
    for (int i = 0; names && i < nb; i++) free(names[i]);
    free(names);
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
    long long f = rd_h5t_open(path, err);
    if (f < 0) return rd_error_set(err, "%s: model restore: cannot open '%s' as a checkpoint", file, path);
    char buf[2 * RD_NAME_MAX + 64]; /* two block names and the words around them */
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
    const rd_observer save = {.user = (void *)own->save_path, .begin = save_at_rest};
    if (own->restore_path[0] ? restore(s, own->restore_path, err)
                             : own->save_path[0] && rd_sim_add_observer(s, &save, err)) {
        rd_sim_free(s);
        return NULL;
    }
    return s;
}
