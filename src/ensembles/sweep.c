/* rockdem — sweep plans and single cases (include/rockdem/sweep.h).
 * Folder ensembles/ owns many-run studies (threshold, restitution, sweeps); it may call the
 * public API (engine, scenario, reference) and io/.
 */
#include "rockdem/sweep.h"
#include "rockdem/output.h"

#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define RD_PULSE_SAMPLES 4000 /* samples of a pulse for its intensity measures */
#define RD_SA_PAD                                                                                  \
    2.0 /* s of rest after a pulse for its Sa: two periods of the longest oscillator */

static volatile sig_atomic_t stop_flag;

void rd_sweep_request_stop(void)
{
    stop_flag = 1;
    rd_sim_request_stop();
}

static int fail(rd_error *err, const char *fmt, ...)
{
    char msg[RD_ERROR_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return rd_error_set(err, "rockdem sweep: %s", msg);
}

static char *dup_text(const char *s, size_t n)
{
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

/* Full-string number (no suffix). */
static int plain_number(const char *s, double *v)
{
    char *end;
    *v = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*v);
}

/* Comma-separated values into a->value (none empty). */
static int split_values(rd_sweep_axis *a, const char *list, const char *opt, rd_error *err)
{
    int n = 1;
    for (const char *c = list; *c; c++) n += *c == ',';
    if (!(a->value = calloc((size_t)n, sizeof *a->value))) return fail(err, "out of memory");
    const char *s = list;
    for (int i = 0; i < n; i++) {
        size_t len = strcspn(s, ",");
        if (len == 0 || len >= RD_SWEEP_TEXT)
            return fail(err, "%s '%s': %s value %d", opt, list, len ? "too long" : "empty", i + 1);
        if (!(a->value[a->n++] = dup_text(s, len))) return fail(err, "out of memory");
        s += len + 1;
    }
    return 0;
}

/* Numeric values of a scale axis: all "Xg" (target PGA, m/s^2) or all factors. */
static int scale_numbers(rd_sweep_axis *a, rd_error *err)
{
    int ng = 0;
    for (int i = 0; i < a->n; i++) {
        char *end;
        double x = strtod(a->value[i], &end);
        int g = end != a->value[i] && (end[0] == 'g' || end[0] == 'G') && end[1] == '\0';
        if (!(g || (end != a->value[i] && *end == '\0')) || !(x > 0) || !isfinite(x))
            return fail(err,
                        "--scales: expected a positive factor or a PGA with a g suffix, got '%s'",
                        a->value[i]);
        a->number[i] = g ? x * RD_G_STANDARD : x;
        ng += g;
    }
    if (ng && ng != a->n)
        return fail(err, "--scales: give either PGA levels with a g suffix (0.3g,0.5g) or factors "
                         "(0.5,1,2), not both");
    a->units = ng ? "m/s^2" : "1";
    return 0;
}

static int axis_numbers(rd_sweep_axis *a, const char *opt, rd_error *err)
{
    if (!(a->number = calloc((size_t)a->n, sizeof *a->number))) return fail(err, "out of memory");
    if (a->kind == RD_AXIS_SCALE) return scale_numbers(a, err);
    a->units = a->kind == RD_AXIS_DIRECTION ? "deg" : "";
    for (int i = 0; i < a->n; i++) {
        if (plain_number(a->value[i], &a->number[i])) continue;
        if (a->kind == RD_AXIS_DIRECTION)
            return fail(err, "%s: expected a direction in degrees, got '%s'", opt, a->value[i]);
        free(a->number); /* a text axis */
        a->number = NULL;
        return 0;
    }
    return 0;
}

/* interface=K: seeds 1..K. */
static int interface_axis(rd_sweep_axis *a, const char *spec, rd_error *err)
{
    double k;
    if (a->n != 1 || !plain_number(a->value[0], &k) || k != floor(k) || k < 1 || k > 100000)
        return fail(err,
                    "--axis '%s': expected interface=K, K = number of seeded interface "
                    "perturbations (1 to 100000)",
                    spec);
    a->kind = RD_AXIS_INTERFACE;
    free(a->value[0]);
    free(a->value);
    a->n = 0;
    if (!(a->value = calloc((size_t)k, sizeof *a->value))) return fail(err, "out of memory");
    for (int i = 0; i < (int)k; i++) {
        char buf[16];
        snprintf(buf, sizeof buf, "%d", i + 1);
        if (!(a->value[a->n++] = dup_text(buf, strlen(buf)))) return fail(err, "out of memory");
    }
    return 0;
}

int rd_sweep_add_axis(rd_sweep_plan *p, rd_axis_kind kind, const char *spec, rd_error *err)
{
    static const char *const names[] = { "", "record", "scale", "direction", "interface" };
    static const char *const opts[] = { "--axis", "--records", "--scales", "--directions",
                                        "--axis" };
    if (p->naxes == RD_SWEEP_MAX_AXES)
        return fail(err, "too many axes (at most %d)", RD_SWEEP_MAX_AXES);
    rd_sweep_axis *a = &p->axis[p->naxes];
    *a = (rd_sweep_axis){ .kind = kind, .units = "" };
    const char *list = spec, *eq = strchr(spec, '=');
    if (kind == RD_AXIS_SET) {
        size_t klen = eq ? (size_t)(eq - spec) : 0;
        if (!eq || klen == 0 || klen >= RD_NAME_MAX || !eq[1] || strchr(eq + 1, '='))
            return fail(
                err,
                "--axis '%s': expected KEY=V1,V2,... (e.g. contact.stiffness-normal=5e9,1e10 "
                "or interface=10)",
                spec);
        memcpy(a->key, spec, klen);
        list = eq + 1;
    } else {
        snprintf(a->key, sizeof a->key, "%s", names[kind]);
    }
    for (int i = 0; i < p->naxes; i++)
        if (!strcmp(p->axis[i].key, a->key))
            return fail(err, "%s '%s': axis '%s' given twice", opts[kind], spec, a->key);
    if (split_values(a, list, opts[kind], err)) return -1;
    p->naxes++; /* owned from here: rd_sweep_plan_free releases it */
    if (kind == RD_AXIS_SET && !strcmp(a->key, "interface") && interface_axis(a, spec, err))
        return -1;
    return kind == RD_AXIS_RECORD ? 0 : axis_numbers(a, opts[a->kind], err);
}

int rd_sweep_value_index(const rd_sweep_plan *p, long k, int a)
{
    for (int i = p->naxes - 1; i > a; i--) k /= p->axis[i].n;
    return (int)(k % p->axis[a].n);
}

/* The rd_scenario_set assignment of value v of axis a. 0, or -1 (record not found). */
static int assignment(const rd_sweep_plan *p, int a, int v, char *buf, size_t size)
{
    const rd_sweep_axis *x = &p->axis[a];
    const char *s = x->value[v];
    char path[4096];
    switch (x->kind) {
    case RD_AXIS_RECORD:
        if (!realpath(s, path)) return -1; /* given relative to the current folder */
        snprintf(buf, size, "motion.file=%s", path);
        return 0;
    case RD_AXIS_SCALE:
        if (p->pulse && !strcmp(x->units, "1"))
            snprintf(buf, size, "motion.amplitude=%.17g", x->number[v] * p->amplitude);
        else if (p->pulse)
            snprintf(buf, size, "motion.amplitude=%s", s);
        else
            snprintf(buf, size, "motion.%s=%s", strcmp(x->units, "1") ? "scale-pga" : "scale", s);
        return 0;
    case RD_AXIS_DIRECTION: snprintf(buf, size, "motion.direction=%s", s); return 0;
    case RD_AXIS_INTERFACE: snprintf(buf, size, "contact.interface-seed=%s", s); return 0;
    case RD_AXIS_SET: snprintf(buf, size, "%s=%s", x->key, s); return 0;
    }
    return -1;
}

unsigned long long rd_sweep_hash(const rd_sweep_plan *p, long k)
{
    unsigned long long h = 1469598103934665603ULL;
    char line[RD_NAME_MAX + RD_SWEEP_TEXT + 16];
    for (int i = 0; i < p->nsets + p->naxes; i++) {
        if (i < p->nsets)
            snprintf(line, sizeof line, "--set %s\n", p->sets[i]);
        else {
            const rd_sweep_axis *a = &p->axis[i - p->nsets];
            snprintf(line, sizeof line, "%s=%s\n", a->key,
                     a->value[rd_sweep_value_index(p, k, i - p->nsets)]);
        }
        for (const char *c = line; *c; c++) h = (h ^ (unsigned char)*c) * 1099511628211ULL;
    }
    return h;
}

/* Fresh scenario: parse the text, base --set overrides. */
static int base_scenario(const rd_sweep_plan *p, rd_scenario *sc, rd_error *err)
{
    if (rd_scenario_parse(sc, p->path, p->text, err)) return -1;
    for (int i = 0; i < p->nsets; i++)
        if (rd_scenario_set(sc, p->sets[i], err)) return -1;
    return 0;
}

/* Case k's scenario (base + every axis value), its run file (if kept) in dir. */
static int case_scenario(const rd_sweep_plan *p, long k, const char *dir, rd_scenario *sc,
                         rd_error *err)
{
    char a[4096 + 64];
    if (base_scenario(p, sc, err)) return -1;
    for (int i = 0; i < p->naxes; i++) {
        int v = rd_sweep_value_index(p, k, i);
        if (assignment(p, i, v, a, sizeof a))
            return rd_error_set(err, "rockdem sweep: --records: cannot find '%s'",
                                p->axis[i].value[v]);
        if (rd_scenario_set(sc, a, err)) return -1;
    }
    sc->quiet_stop = !p->full; /* engine/quiet_end.c */
    sc->threads = 1;           /* the cases already run one per core (sweep_pool.c's processes) */
    if (dir) snprintf(sc->output.path, sizeof sc->output.path, "%s/case-%06ld.h5", dir, k);
    return rd_scenario_validate(sc, err);
}

static int read_text(rd_sweep_plan *p, rd_error *err)
{
    FILE *f = fopen(p->path, "rb");
    if (!f) return fail(err, "cannot open scenario '%s'", p->path);
    size_t cap = 4096, n = 0, got;
    char *t = malloc(cap);
    while (t && (got = fread(t + n, 1, cap - n - 1, f)) > 0) {
        n += got;
        char *g = n + 1 == cap ? realloc(t, cap *= 2) : t;
        if (!g) {
            free(t);
            t = NULL;
        } else
            t = g;
    }
    fclose(f);
    if (!t) return fail(err, "out of memory");
    t[n] = '\0';
    p->text = t;
    return 0;
}

/* The scenario as the base of every case: bodies, motion kind. */
static int inspect_base(rd_sweep_plan *p, rd_error *err)
{
    rd_scenario sc;
    int rc = base_scenario(p, &sc, err) || rd_scenario_validate(&sc, err) ? -1 : 0;
    for (int i = 0; !rc && i < sc.nbodies; i++)
        if (!sc.bodies[i].fixed && p->nbodies == RD_SWEEP_BODIES)
            rc = rd_error_set(err,
                              "rockdem sweep: more than %d free blocks (the table's per-block "
                              "columns hold %d)",
                              RD_SWEEP_BODIES, RD_SWEEP_BODIES);
        else if (!sc.bodies[i].fixed)
            snprintf(p->body[p->nbodies++], RD_NAME_MAX, "%s", sc.bodies[i].name);
    p->nfences = sc.runout.nfences;
    for (int f = 0; f < p->nfences; f++)
        snprintf(p->fence[f], RD_NAME_MAX, "%s", sc.runout.fence[f].name);
    p->pulse = !rd_motion_has_records(&sc.motion);
    p->amplitude = sc.motion.horizontal.amplitude;
    const rd_perturb_def *d = &sc.contact.perturb;
    p->perturbed = d->remove > 0 || d->raise > 0 || d->scatter > 0;
    p->surface = sc.contact.model == RD_CONTACT_SURFACE;
    rd_scenario_free(&sc);
    return rc;
}

/* Every axis value once on a fresh scenario: bad keys and values are found before any run. */
static int check_values(const rd_sweep_plan *p, rd_error *err)
{
    char a[4096 + 64];
    for (int i = 0; i < p->naxes; i++) {
        const rd_sweep_axis *x = &p->axis[i];
        if (x->kind == RD_AXIS_SCALE && p->pulse && !(p->amplitude != 0) && !strcmp(x->units, "1"))
            return fail(err, "--scales: factors need a pulse amplitude or a record to scale");
        if (x->kind == RD_AXIS_INTERFACE && !p->perturbed)
            return fail(err,
                        "--axis interface: the scenario has no 'contact interface-perturbation' "
                        "with remove, raise or scatter; every seed would be the same interface");
        if (x->kind == RD_AXIS_INTERFACE && p->surface)
            return fail(err, "--axis interface: the scenario's contact model surface has no "
                             "subcontact points to perturb (give 'contact model vertex')");
        for (int v = 0; v < x->n; v++) {
            rd_scenario sc;
            rd_error e;
            if (assignment(p, i, v, a, sizeof a))
                return fail(err, "--records: cannot find '%s'", x->value[v]);
            int rc = base_scenario(p, &sc, &e) || rd_scenario_set(&sc, a, &e) ||
                     rd_scenario_validate(&sc, &e);
            rd_scenario_free(&sc);
            if (rc) return fail(err, "axis %s=%s: %s", x->key, x->value[v], e.msg);
        }
    }
    return 0;
}

static int make_axes_text(rd_sweep_plan *p, rd_error *err)
{
    size_t n = 1;
    for (int i = 0; i < p->naxes; i++)
        for (int v = 0; v < p->axis[i].n; v++)
            n += strlen(p->axis[i].key) + strlen(p->axis[i].value[v]) + 2;
    for (int i = 0; i < p->nsets; i++) n += strlen(p->sets[i]) + 8;
    char *t = p->axes_text = calloc(n, 1);
    if (!t) return fail(err, "out of memory");
    for (int i = 0; i < p->naxes; i++) {
        t += sprintf(t, "%s=", p->axis[i].key);
        for (int v = 0; v < p->axis[i].n; v++)
            t += sprintf(t, "%s%c", p->axis[i].value[v], v + 1 < p->axis[i].n ? ',' : '\n');
    }
    for (int i = 0; i < p->nsets; i++) t += sprintf(t, "--set %s\n", p->sets[i]);
    return 0;
}

int rd_sweep_plan_finish(rd_sweep_plan *p, rd_error *err)
{
    if (read_text(p, err)) return -1;
    if (inspect_base(p, err)) return -1; /* the parser's "file:line:col: ..." as is */
    p->ncases = 1;
    for (int i = 0; i < p->naxes; i++) {
        if (p->ncases > 100000000L / p->axis[i].n) return fail(err, "more than 1e8 cases");
        p->ncases *= p->axis[i].n;
    }
    return check_values(p, err) || make_axes_text(p, err) ? -1 : 0;
}

void rd_sweep_plan_free(rd_sweep_plan *p)
{
    for (int i = 0; i < p->naxes; i++) {
        for (int v = 0; v < p->axis[i].n; v++) free(p->axis[i].value[v]);
        free(p->axis[i].value);
        free(p->axis[i].number);
    }
    free(p->text);
    free(p->axes_text);
    p->naxes = 0;
    p->text = p->axes_text = NULL;
}

/* Intensity measures of a pulse along its direction, from RD_PULSE_SAMPLES samples of the exact
 * acceleration, velocity and displacement over [0, end of the pulse]; its Sa(0.2 s), Sa(1 s)
 * (5 % damping) after RD_SA_PAD s of rest, as rd_motion_im pads records. */
static void pulse_im(const rd_pulse_def *h, double im[RD_SWEEP_NIM])
{
    static const double periods[2] = { 0.2, 1.0 }; /* s */
    double end = rd_pulse_end(h);
    rd_record r = { 0 };
    rd_error e;
    if (h->kind == RD_PULSE_NONE || !(end > 0) ||
        rd_record_alloc(&r, RD_PULSE_SAMPLES + 1, end / RD_PULSE_SAMPLES, &e))
        return;
    for (size_t i = 0; i < r.npts; i++)
        rd_pulse_eval(h, (double)i * r.dt, &r.acc[i], &r.vel[i], &r.disp[i]);
    rd_im m;
    double sa[2] = { 0, 0 };
    rd_im_compute(&r, &m);
    if (rd_record_pad(&r, RD_SA_PAD, &e) || rd_im_psa(&r, periods, 2, 0.05, sa, &e))
        sa[0] = sa[1] = NAN;
    rd_record_free(&r);
    double v[RD_SWEEP_NIM] = { m.pga, m.pgv, m.pgd, m.pgv_pga, m.arias, m.d5_95, sa[0], sa[1] };
    memcpy(im, v, sizeof v);
}

/* Records: per measure the larger of the horizontal components (the vertical one alone when
 * there is no horizontal record), as rdtable's max(h1, h2). */
static int record_im(const rd_motion_def *m, double im[RD_SWEEP_NIM], rd_error *err)
{
    int horiz = m->record[RD_H1].applied || m->record[RD_H2].applied;
    for (int c = 0; c < RD_NCOMPONENTS; c++) {
        rd_im x;
        double sa[2];
        if (!m->record[c].applied || (horiz && c == RD_VERTICAL)) continue;
        if (rd_motion_im(m, c, &x, sa, err)) return -1;
        double v[RD_SWEEP_NIM] = { x.pga, x.pgv, x.pgd, x.pgv_pga, x.arias, x.d5_95, sa[0], sa[1] };
        for (int i = 0; i < RD_SWEEP_NIM; i++) im[i] = fmax(im[i], v[i]);
    }
    return 0;
}

/* Largest slip of the joints of free body `name`, m (0 if it has none). */
static double body_slip(const rd_sim *sim, const char *name)
{
    double m = 0.0;
    for (int j = 0; j < rd_sim_joint_count(sim); j++) {
        rd_joint_summary js;
        rd_sim_joint(sim, j, &js);
        if (!strcmp(js.a, name) || !strcmp(js.b, name)) m = fmax(m, js.max_slip);
    }
    return m;
}

static void copy_summary(const rd_sim *sim, const rd_summary *s, rd_sweep_result *r)
{
    r->status = (int)s->status;
    r->overturned = s->any_overturned;
    r->energy_residual = s->energy_residual_max;
    r->end_time = s->end_time;
    r->at_rest = s->at_rest;
    r->nbodies =
        s->nbodies < RD_SWEEP_BODIES ? s->nbodies : RD_SWEEP_BODIES; /* inspect_base checked */
    r->overturn_time = -1;
    for (int f = 0; f < RD_MAX_FENCES; f++) r->f_height[f] = -1;
    rd_sweep_mode mode = RD_MODE_REST;
    for (int k = 0; k < r->nbodies; k++) {
        const rd_body_summary *b = &s->body[k];
        r->b_overturned[k] = b->overturned;
        r->b_overturn_time[k] = b->overturn_time;
        r->b_max_tilt_ratio[k] = b->max_tilt_ratio;
        r->b_max_slide[k] = b->max_slide;
        r->b_final_twist[k] = b->final_twist;
        r->b_max_twist[k] = fabs(b->max_twist);
        r->b_max_slip[k] = body_slip(sim, b->name);
        r->b_mode[k] = (int)rd_sweep_mode_of(b, r->b_max_slip[k]);
        r->b_runout[k] = b->travel;
        r->b_runout_direction[k] = b->runout_direction;
        r->b_max_speed[k] = b->max_speed;
        r->b_max_bounce[k] = b->max_bounce;
        r->b_max_energy[k] = b->max_energy;
        const rd_fence_hit *h0 = &b->fence[0];
        r->b_fence_time[k] = h0->time;
        r->b_fence_energy[k] = h0->crossings > 0 ? h0->energy : 0;
        r->b_fence_height[k] = h0->height;
        r->runout = fmax(r->runout, b->travel);
        for (int f = 0; f < b->nfences; f++) {
            const rd_fence_hit *h = &b->fence[f];
            if (h->crossings == 0) continue;
            r->f_crossed[f]++;
            r->f_energy[f] = fmax(r->f_energy[f], h->energy);
            r->f_height[f] = fmax(r->f_height[f], h->height);
            r->fence_energy = fmax(r->fence_energy, h->energy);
        }
        if (b->overturned && (r->overturn_time < 0 || b->overturn_time < r->overturn_time))
            r->overturn_time = b->overturn_time;
        r->max_tilt_ratio = fmax(r->max_tilt_ratio, b->max_tilt_ratio);
        r->max_slide = fmax(r->max_slide, b->max_slide);
        r->max_twist = fmax(r->max_twist, r->b_max_twist[k]);
        r->max_slip = fmax(r->max_slip, r->b_max_slip[k]);
        if (fabs(b->final_twist) > fabs(r->final_twist)) r->final_twist = b->final_twist;
        if (r->b_mode[k] > (int)mode) mode = (rd_sweep_mode)r->b_mode[k];
    }
    snprintf(r->mode, sizeof r->mode, "%s", rd_sweep_mode_name(mode));
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void rd_sweep_run_case(const rd_sweep_plan *p, long k, rd_sweep_result *r)
{
    double t0 = now();
    memset(r, 0, sizeof *r);
    r->index = k;
    r->hash = rd_sweep_hash(p, k);
    r->status = RD_STATUS_INTERRUPTED;
    if (stop_flag) return;
    rd_scenario sc;
    rd_error err;
    rd_sim *sim = NULL;
    if (case_scenario(p, k, p->keep_dir, &sc, &err) ||
        (rd_motion_has_records(&sc.motion) ? record_im(&sc.motion, r->im, &err)
                                           : (pulse_im(&sc.motion.horizontal, r->im), 0)) ||
        !(sim = rd_sim_create(&sc, &err)) ||
        (p->keep_dir && rd_sim_write_hdf5(sim, sc.output.path, &err))) {
        r->status = -1;
        snprintf(r->message, sizeof r->message, "%.199s", err.msg);
    } else {
        rd_status st = rd_sim_run(sim);
        rd_summary s;
        rd_sim_summary(sim, &s);
        copy_summary(sim, &s, r);
        r->quiet_end = rd_sim_quiet_end(sim);
        r->status = (int)st;
        if (rd_status_failed(st))
            snprintf(r->message, sizeof r->message, "%.199s", rd_sim_error(sim));
    }
    rd_sim_free(sim);
    rd_scenario_free(&sc);
    r->wall_seconds = now() - t0;
}
