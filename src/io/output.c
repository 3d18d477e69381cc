/* rockdem — the HDF5 file of a run as an observer (include/rockdem/output.h): created with the
 * scenario and bodies when attached, then samples, events, precariousness and the summary as
 * the run reports them (layout in io_hdf5.h).
 * Folder io/ owns the HDF5 output file; it may call base/ and the public headers, never engine/
 * internals or cli/.
 */
#include "rockdem/output.h"
#include "rockdem/observer.h"
#include "base/path.h"
#include "io/io_hdf5.h"
#include "io/io_bodies.h"
#include "io/output_scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *damping_text(const rd_damping_def *d, char *buf, size_t n)
{
    if (d->kind == RD_DAMPING_VISCOUS)
        snprintf(buf, n, "viscous %g", d->value);
    else if (d->kind == RD_DAMPING_LOCAL)
        snprintf(buf, n, "local %g", d->value);
    else
        snprintf(buf, n, "none");
    return buf;
}

static const char *overturn_text(const rd_overturn_def *o, char *buf, size_t n)
{
    static const char *kind[] = { "tilt-ratio", "angle", "height", "off-pedestal" };
    double v = o->kind == RD_OVERTURN_ANGLE ? o->value * 180.0 / M_PI : o->value;
    snprintf(buf, n, "%s %g%s", kind[o->kind], v, o->kind == RD_OVERTURN_ANGLE ? " deg" : "");
    return buf;
}

/* The scene is at rest: each free body's precariousness table and size (alpha comes with the
 * summary, from the same support polygon). */
static int on_begin(void *user, rd_sim *sim, rd_error *err)
{
    int n = rd_sim_body_count(sim, NULL);
    rd_h5_rest_body *b = malloc(sizeof *b * (size_t)(n > 0 ? n : 1));
    if (!b) return rd_error_set(err, "out of memory");
    for (int k = 0; k < n; k++) {
        rd_body_info info;
        rd_sim_body_info(sim, k, &info);
        b[k] = (rd_h5_rest_body){ .nprec = info.nprec, .precariousness = info.precariousness };
        memcpy(b[k].size, info.size, sizeof b[k].size);
    }
    int rc = rd_h5_bodies_rest(user, b, n, err);
    free(b);
    return rc;
}

static int on_sample(void *user, rd_sim *sim, const rd_sample *s, rd_error *err)
{
    (void)sim;
    rd_h5_sample smp = { .time = s->time,
                         .position = s->position,
                         .quaternion = s->quaternion,
                         .velocity = s->velocity,
                         .angular_velocity = s->angular_velocity,
                         .tilt = s->tilt,
                         .rotation = s->rotation };
    for (int j = 0; j < 3; j++) {
        smp.ground_acc[j] = s->ground_acc[j];
        smp.ground_vel[j] = s->ground_vel[j];
        smp.ground_disp[j] = s->ground_disp[j];
    }
    for (int j = 0; j < RD_NENERGY; j++) smp.energy[j] = s->energy[j];
    return rd_h5_append(user, &smp, err);
}

static int on_event(void *user, rd_sim *sim, const rd_event *e, rd_error *err)
{
    (void)sim;
    return rd_h5_event(user, e->time, e->body, e->type, e->value, err);
}

static int on_end(void *user, rd_sim *sim, const rd_summary *s, rd_error *err)
{
    /* the time series first, then the tables of histories, joints and outcomes (flushed when
       the file closes) */
    int ok = s->status == RD_STATUS_DONE || s->status == RD_STATUS_OVERTURNED;
    return rd_h5_summary(user, s, err) || rd_h5_flush(user, err) ||
                   rd_h5_scene_tables(user, sim, s, err) || rd_h5_commit(user, ok, err)
               ? -1
               : 0;
}

static void on_release(void *user) { rd_h5_close(user); }

/* Body k as the writer describes it. */
static rd_h5_body h5_body(rd_sim *sim, int k)
{
    rd_body_info b;
    rd_sim_body_info(sim, k, &b);
    rd_h5_body h = { .name = b.name,
                     .mass = b.mass,
                     .alpha = b.alpha,
                     .nvert = b.nvert,
                     .vertices = b.vertices,
                     .ntri = b.ntri,
                     .triangles = b.triangles,
                     .fixed = b.fixed };
    memcpy(h.inertia, b.inertia, sizeof h.inertia);
    memcpy(h.size, b.size, sizeof h.size);
    memcpy(h.position, b.position, sizeof h.position);
    memcpy(h.quaternion, b.quaternion, sizeof h.quaternion);
    return h;
}

/* Creates the file with the scenario, the contact law and the bodies as built (at path; or at
 * the temporary tmp, renamed to path when the run succeeds, where tmp is not NULL). */
static rd_h5 *open_file(rd_sim *sim, const char *path, const char *tmp, rd_error *err)
{
    const rd_scenario *sc = rd_sim_scenario(sim);
    int nfixed, nfree = rd_sim_body_count(sim, &nfixed);
    rd_h5_body *hb = calloc((size_t)(nfree + nfixed) + 1, sizeof *hb);
    if (!hb) {
        rd_error_set(err, "out of memory");
        return NULL;
    }
    for (int k = 0; k < nfree + nfixed; k++) hb[k] = h5_body(sim, k);
    rd_summary sum;
    rd_sim_summary(sim, &sum);
    char dbuf[64], obuf[64];
    const rd_contact_def *c = &sc->contact;
    rd_h5_meta meta = { .scenario_text = sc->text ? sc->text : "",
                        .scenario_file = sc->file,
                        .title = sc->title,
                        .dt = rd_sim_dt(sim),
                        .dt_critical = sum.dt_critical,
                        .damping = damping_text(&sc->damping, dbuf, sizeof dbuf),
                        .overturn_criterion = overturn_text(&sc->overturn, obuf, sizeof obuf),
                        .kn = c->kn,
                        .ks = c->ks,
                        .friction = c->friction,
                        .cohesion = c->cohesion,
                        .tension = c->tension,
                        .spacing = c->spacing,
                        .nbodies = nfree,
                        .bodies = hb,
                        .nfixed = nfixed,
                        .fixed_bodies = hb + nfree,
                        .target = tmp ? path : NULL };
    rd_h5 *h = rd_h5_open(tmp ? tmp : path, &meta, err);
    free(hb);
    return h;
}

int rd_sim_write_hdf5(rd_sim *sim, const char *path, rd_error *err)
{
    const rd_scenario *sc = rd_sim_scenario(sim);
    char why[RD_ERROR_MAX];
    const char *bad =
        rd_path_output_conflict(sc, path, sc->save_path, RD_OUTPUT_RUN, why, sizeof why);
    if (bad) return rd_error_set(err, "%s: cannot write the output there: %s", path, bad);
    char tmp[RD_PATH_MAX];
    int staged = rd_output_staging(path, sc->overwrite, tmp, sizeof tmp);
    rd_h5 *h = open_file(sim, path, staged ? tmp : NULL, err);
    if (!h) return -1;
    rd_observer o = { .user = h,
                      .begin = on_begin,
                      .sample = on_sample,
                      .event = on_event,
                      .end = on_end,
                      .release = on_release };
    if (rd_h5_ground_im(h, &rd_sim_scenario(sim)->motion, err) ||
        rd_sim_add_observer(sim, &o, err)) {
        rd_h5_close(h);
        return -1;
    }
    return 0;
}

int rd_output_staging(const char *path, int overwrite, char *buf, size_t n)
{
    struct stat st;
    snprintf(buf, n, "%s.tmp-%ld", path, (long)getpid());
    return !overwrite && stat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0;
}
