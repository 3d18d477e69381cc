/* rockdem — histories (`history body|joint|energy ...`): chosen quantities sampled every
 * `history interval` seconds during shaking, kept in memory and written at the end of the run
 * by observers (the HDF5 file: /history, io/output_scene.c), each dataset with units:
 *   /history/time                            [N] s
 *   /history/body/<name>/position            [N][3] m        centre of mass
 *   /history/body/<name>/rotation            [N][3] rad      in-plane, out-of-plane, twist
 *   /history/body/<name>/velocity            [N][3] m/s
 *   /history/body/<name>/angular_velocity    [N][3] rad/s
 *   /history/joint/<a>-<b>/normal_force      [N] N           compression
 *   /history/joint/<a>-<b>/shear_force       [N][4] N        on <b>: x, y, z, magnitude
 *   /history/joint/<a>-<b>/opening           [N] m
 *   /history/joint/<a>-<b>/slip              [N][4] m        x, y, z, magnitude
 *   /history/joint/<a>-<b>/area              [N] m^2
 *   /history/joint/<a>-<b>/pressure_centre   [N][3] m
 *   /history/energy                          [N][7] J        as /energy
 * A joint's values are NaN while its two bodies are apart (no contact pair).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "base/vec.h"
#include "rockdem/history.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct series_kind {
    unsigned bit;
    const char *name, *units, *columns;
    int ncol;
    const char *dim; /* scale of the components: a root one (/xyz) or one of the group's */
    const char *long_name;
} series_kind;

static const series_kind body_series[] = {
    { RD_HB_POSITION, "position", "m", "x,y,z", 3, "/xyz", "centre of mass, ground frame" },
    { RD_HB_ROTATION, "rotation", "rad", "in_plane,out_of_plane,twist", 3, "/rotation_part",
      "rotation from rest: in-plane rocking, out-of-plane rocking, twist" },
    { RD_HB_VELOCITY, "velocity", "m/s", "x,y,z", 3, "/xyz", "velocity relative to the ground" },
    { RD_HB_ANGULAR_VELOCITY, "angular_velocity", "rad/s", "x,y,z", 3, "/xyz", "angular velocity" },
};
static const series_kind joint_series[] = {
    { RD_HJ_NORMAL_FORCE, "normal_force", "N", NULL, 1, NULL,
      "normal force of the joint (compression)" },
    { RD_HJ_SHEAR_FORCE, "shear_force", "N", "x,y,z,magnitude", 4, "xyz_magnitude",
      "shear force on the joint's second body" },
    { RD_HJ_OPENING, "opening", "m", NULL, 1, NULL, "largest gap of the joint's subcontacts" },
    { RD_HJ_SLIP, "slip", "m", "x,y,z,magnitude", 4, "xyz_magnitude",
      "slip of the second body against the first, elastic shear removed" },
    { RD_HJ_AREA, "area", "m^2", NULL, 1, NULL, "active contact area" },
    { RD_HJ_PRESSURE_CENTRE, "pressure_centre", "m", "x,y,z", 3, "/xyz", "centre of pressure" },
};
#define NBODY_SERIES  (int)(sizeof body_series / sizeof body_series[0])
#define NJOINT_SERIES (int)(sizeof joint_series / sizeof joint_series[0])

static int body_index(const rd_sim *s, const char *name)
{
    for (int i = 0; i < s->nb; i++)
        if (!strcmp(s->sc.bodies[i].name, name)) return i;
    return -1;
}

/* Columns of history h. */
static int history_columns(const rd_history_def *h)
{
    if (h->kind == RD_HISTORY_ENERGY) return RD_NENERGY;
    int n = 0;
    const series_kind *sk = h->kind == RD_HISTORY_BODY ? body_series : joint_series;
    int ns = h->kind == RD_HISTORY_BODY ? NBODY_SERIES : NJOINT_SERIES;
    for (int k = 0; k < ns; k++)
        if (h->what & sk[k].bit) n += sk[k].ncol;
    return n;
}

int rd_history_init(rd_sim *s, rd_error *err)
{
    int nh = s->sc.nhistories;
    s->nhist_col = 1;
    s->hist_pair = malloc((size_t)(nh ? nh : 1) * sizeof *s->hist_pair);
    s->hist_body = malloc((size_t)(nh ? 2 * nh : 1) * sizeof *s->hist_body);
    if (!s->hist_pair || !s->hist_body) return rd_error_set(err, "out of memory");
    for (int h = 0; h < nh; h++) {
        const rd_history_def *d = &s->sc.history[h];
        s->hist_pair[h] = -1;
        for (int e = 0; e < (d->kind == RD_HISTORY_JOINT  ? 2
                             : d->kind == RD_HISTORY_BODY ? 1
                                                          : 0);
             e++) {
            const char *name = e ? d->b : d->a;
            int i = body_index(s, name);
            if (i < 0)
                return rd_error_set(err, "%s:%d: history: no block named '%s'", s->sc.file, d->line,
                                    name);
            s->hist_body[2 * h + e] = i;
        }
        if (d->kind == RD_HISTORY_JOINT && s->hist_body[2 * h] == s->hist_body[2 * h + 1])
            return rd_error_set(err, "%s:%d: history joint: a joint needs two different blocks",
                                s->sc.file, d->line);
        s->nhist_col += history_columns(d);
    }
    s->next_hist = 0;
    return 0;
}

static void body_values(rd_sim *s, const rd_history_def *d, int i, double *row)
{
    int k = s->free_of[i];
    for (int q = 0; q < NBODY_SERIES; q++) {
        unsigned bit = body_series[q].bit;
        if (!(d->what & bit)) continue;
        double v[3] = { 0, 0, 0 };
        if (bit == RD_HB_POSITION)
            rd_copy3(s->x[i], v);
        else if (bit == RD_HB_ROTATION && k >= 0) /* twist unwrapped against the last row's */
            rd_monitor_rotation_peek(
                s, k, s->nhist_rows > 1 ? row[2 - s->nhist_col] : s->watch[k].twist_prev, v);
        else if (bit == RD_HB_VELOCITY)
            for (int j = 0; j < 3; j++) v[j] = 0.5 * (s->v[i][j] + s->v_old[i][j]);
        else if (bit == RD_HB_ANGULAR_VELOCITY)
            rd_copy3(s->w[i], v);
        memcpy(row, v, sizeof v);
        row += 3;
    }
}

static void joint_values(rd_sim *s, int h, const rd_history_def *d, double *row)
{
    int p = s->hist_pair[h];
    if (p < 0) p = s->hist_pair[h] = rd_pair_find(s, s->hist_body[2 * h], s->hist_body[2 * h + 1]);
    rd_joint_state m;
    int have = p >= 0 && s->pair[p].seen == s->stamp;
    if (have) rd_joint_measure(s, &s->pair[p], &m);
    for (int q = 0; q < NJOINT_SERIES; q++) {
        unsigned bit = joint_series[q].bit;
        if (!(d->what & bit)) continue;
        double v[4] = { NAN, NAN, NAN, NAN };
        if (have) {
            if (bit == RD_HJ_NORMAL_FORCE)
                v[0] = m.fn;
            else if (bit == RD_HJ_SHEAR_FORCE) {
                rd_copy3(m.fs, v);
                v[3] = rd_norm(m.fs);
            } else if (bit == RD_HJ_OPENING)
                v[0] = m.opening;
            else if (bit == RD_HJ_SLIP) {
                rd_copy3(m.slip, v);
                v[3] = rd_norm(m.slip);
            } else if (bit == RD_HJ_AREA)
                v[0] = m.area;
            else
                rd_copy3(m.cop, v);
        }
        memcpy(row, v, (size_t)joint_series[q].ncol * sizeof(double));
        row += joint_series[q].ncol;
    }
}

/* Take a sample when its time has come (called once per shaking step, after the kick). */
void rd_history_step(rd_sim *s)
{
    if (s->sc.nhistories == 0 || s->t < s->next_hist - 1e-9 * s->dt) return;
    s->next_hist += s->sc.history_interval;
    if (s->nhist_rows == s->cap_hist_rows) {
        long cap = s->cap_hist_rows ? 2 * s->cap_hist_rows : 1024;
        double *t = realloc(s->hist, (size_t)cap * (size_t)s->nhist_col * sizeof *t);
        if (!t) return; /* histories are diagnostics: stop recording, keep running */
        s->hist = t;
        s->cap_hist_rows = cap;
    }
    double *row = s->hist + s->nhist_rows++ * s->nhist_col;
    *row++ = s->t;
    for (int h = 0; h < s->sc.nhistories; h++) {
        const rd_history_def *d = &s->sc.history[h];
        if (d->kind == RD_HISTORY_BODY)
            body_values(s, d, s->hist_body[2 * h], row);
        else if (d->kind == RD_HISTORY_JOINT)
            joint_values(s, h, d, row);
        else {
            rd_energy_peek(s);
            memcpy(row, s->energy, RD_NENERGY * sizeof(double));
        }
        row += history_columns(d);
    }
}

/* The series of history h, appended to out from column *col on; returns how many. */
static int series_of(const rd_history_def *d, int *col, rd_history_series *out)
{
    int n = 0;
    if (d->kind == RD_HISTORY_ENERGY) {
        if (out) {
            rd_history_series *o = &out[n];
            memset(o, 0, sizeof *o);
            snprintf(o->path, sizeof o->path, "energy");
            o->units = "J";
            o->long_name = "energies (as /energy)";
            o->dim = "energy_term";
            o->labels = "kinetic,gravitational,elastic,friction,damping,ground_work,residual";
            o->col = *col;
            o->ncol = RD_NENERGY;
        }
        *col += RD_NENERGY;
        return 1;
    }
    const series_kind *sk = d->kind == RD_HISTORY_BODY ? body_series : joint_series;
    int ns = d->kind == RD_HISTORY_BODY ? NBODY_SERIES : NJOINT_SERIES;
    for (int q = 0; q < ns; q++) {
        if (!(d->what & sk[q].bit)) continue;
        if (out) {
            rd_history_series *o = &out[n];
            memset(o, 0, sizeof *o);
            if (d->kind == RD_HISTORY_BODY)
                snprintf(o->path, sizeof o->path, "body/%s/%s", d->a, sk[q].name);
            else
                snprintf(o->path, sizeof o->path, "joint/%s-%s/%s", d->a, d->b, sk[q].name);
            o->units = sk[q].units;
            o->long_name = sk[q].long_name;
            o->dim = sk[q].dim;
            o->labels = sk[q].columns;
            o->col = *col;
            o->ncol = sk[q].ncol;
        }
        *col += sk[q].ncol;
        n++;
    }
    return n;
}

int rd_sim_history_count(const rd_sim *s)
{
    int n = 0, col = 1;
    for (int h = 0; h < s->sc.nhistories; h++) n += series_of(&s->sc.history[h], &col, NULL);
    return n;
}

void rd_sim_history_series(const rd_sim *s, int k, rd_history_series *out)
{
    rd_history_series buf[8];
    int col = 1, n = 0;
    memset(out, 0, sizeof *out);
    for (int h = 0; h < s->sc.nhistories; h++) {
        int m = series_of(&s->sc.history[h], &col, NULL);
        if (k < n + m) {
            col -= history_columns(&s->sc.history[h]);
            series_of(&s->sc.history[h], &col, buf);
            *out = buf[k - n];
            return;
        }
        n += m;
    }
}

const double *rd_sim_history_table(const rd_sim *s, long *rows, int *cols)
{
    *rows = s->nhist_rows;
    *cols = s->nhist_col;
    return s->hist;
}
