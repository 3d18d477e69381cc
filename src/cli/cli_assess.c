/* rockdem — `rockdem assess FILE [options]`: the seismic assessment of the scene's unanchored
 * body on its pad (include/rockdem/assess.h, docs/ASSESS.md): the design spectrum, each code's
 * static rocking and sliding check (seed 001 Table 2), ASCE/SEI 43-05 A.1 and A.2 with their
 * safety factors, the allowable PGA of every method, and the time-history evidence (matched
 * records through the DEM). Prints the tables and writes DIR/assess.json, the records and
 * the runs; tools/rdassess.py turns the folder into the report (Markdown, figures, PDF).
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"
#include "cli/cli_assess.h"
#include "rockdem/assess.h"
#include "rockdem/record.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

static int set_codes(assess_args *a, const char *v)
{
    static const char *const names[RD_NCODES] = { "asce7", "en1998", "kta" };
    char buf[128];
    snprintf(buf, sizeof buf, "%s", v);
    memset(a->codes, 0, sizeof a->codes);
    for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
        int k = 0;
        while (k < RD_NCODES && strcmp(t, names[k])) k++;
        if (k == RD_NCODES) {
            fprintf(stderr, "rockdem: --code expects a list of asce7, en1998, kta, got '%s'\n", t);
            return -1;
        }
        a->codes[k] = 1;
    }
    return 0;
}

/* A number option within [lo, hi]. */
static int number_in(const char *o, const char *v, int accel, double lo, double hi, double *x)
{
    if (rd_cli_number(o, v, accel, x)) return -1;
    if (!(*x >= lo && *x <= hi)) {
        fprintf(stderr, "rockdem: %s expects a value in [%g, %g], got '%s'\n", o, lo, hi, v);
        return -1;
    }
    return 0;
}

static int assess_option(void *ctx, int argc, char **argv, int *i)
{
    static const char *const names[] = {
        "--spectrum", "--ag",  "--damping", "--vertical", "--mu",       "--slide-limit",   "--code",
        "--body",     "--out", "--records", "--seed",     "--duration", "--slide-damping", NULL
    };
    assess_args *a = ctx;
    const char *o = argv[*i], *v;
    if (!strcmp(o, "--neglect-vertical")) {
        a->neglect = 1;
        return 0;
    }
    int rc = rd_cli_option(argc, argv, *i, names, &v);
    if (rc) return rc;
    double x;
    (*i)++;
    if (!strcmp(o, "--spectrum")) {
        snprintf(a->spectrum, sizeof a->spectrum, "%s", v);
        return 0;
    }
    if (!strcmp(o, "--body")) {
        snprintf(a->body, sizeof a->body, "%s", v);
        return 0;
    }
    if (!strcmp(o, "--out")) {
        snprintf(a->out, sizeof a->out, "%s", v);
        return 0;
    }
    if (!strcmp(o, "--code")) return set_codes(a, v);
    if (!strcmp(o, "--ag")) return number_in(o, v, 1, 1e-6, 100.0 * RD_G_STANDARD, &a->ag);
    if (!strcmp(o, "--damping")) return number_in(o, v, 0, 1e-4, 0.99, &a->damping);
    if (!strcmp(o, "--slide-damping")) return number_in(o, v, 0, 1e-4, 0.99, &a->slide_damping);
    if (!strcmp(o, "--vertical")) return number_in(o, v, 0, 0.0, 10.0, &a->kv);
    if (!strcmp(o, "--mu")) return number_in(o, v, 0, 0.0, 10.0, &a->mu);
    if (!strcmp(o, "--slide-limit")) return number_in(o, v, 0, 1e-6, 1e3, &a->limit);
    if (!strcmp(o, "--duration")) return number_in(o, v, 0, 1.0, 600.0, &a->ev.duration);
    if (!strcmp(o, "--seed")) {
        if (number_in(o, v, 0, 1, 1e9, &x)) return -1;
        a->ev.seed = (unsigned long)x;
        return 0;
    }
    if (number_in(o, v, 0, 0, RD_EVIDENCE_MAX, &x)) return -1; /* --records */
    if (x != floor(x) || (x > 0 && x < RD_TH_MIN_RECORDS)) {
        fprintf(stderr,
                "rockdem: --records expects 0 (none) or a whole number from %d to %d, got '%s'\n",
                RD_TH_MIN_RECORDS, RD_EVIDENCE_MAX, v);
        return -1;
    }
    a->ev.nrecords = (int)x;
    return 0;
}

/* The design spectrum from --spectrum and --ag. */
static int make_spectrum(const assess_args *a, rd_spectrum *s)
{
    rd_error err;
    int type;
    char ground, extra;
    if (sscanf(a->spectrum, "en1998-%d%c%c", &type, &ground, &extra) == 2) {
        if (!(a->ag > 0)) {
            fprintf(
                stderr,
                "rockdem: assess: the EN 1998 spectrum needs --ag (design ground acceleration)\n");
            return -1;
        }
        if (rd_spectrum_en1998(s, type, ground, a->ag, &err)) {
            fprintf(stderr, "rockdem: --spectrum: %s\n", err.msg);
            return -1;
        }
        return 0;
    }
    if (!strncmp(a->spectrum, "en1998", 6)) {
        fprintf(
            stderr,
            "rockdem: --spectrum expects en1998-TG (type 1 or 2, ground A-E, e.g. en1998-1A) or a "
            "table file, got '%s'\n",
            a->spectrum);
        return -1;
    }
    if (rd_spectrum_read(s, a->spectrum, a->damping, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return -1;
    }
    return 0;
}

static int in_range(const rd_range_def *r, const rd_body_def *b)
{
    return r->kind == RD_RANGE_ANY ||
           !strcmp(r->name, r->kind == RD_RANGE_GROUP ? b->group : b->name);
}

/* Friction angle of the joint between bodies a and b: the default, then every override whose
 * range holds the pair, in file order (scenario.h, rd_joint_def). */
static double joint_friction(const rd_scenario *sc, const rd_body_def *a, const rd_body_def *b)
{
    double phi = sc->contact.friction;
    for (int k = 0; k < sc->njoints; k++) {
        const rd_joint_def *j = &sc->joint[k];
        if (!(j->set & RD_JOINT_FRICTION)) continue;
        if ((in_range(&j->range[0], a) && in_range(&j->range[1], b)) ||
            (in_range(&j->range[0], b) && in_range(&j->range[1], a)))
            phi = j->friction;
    }
    return phi;
}

/* The body to assess (named, or the only free one) and its support (what it is seated on, or
 * the only fixed body; -1: none known). */
static int find_bodies(const rd_scenario *sc, const char *name, int *body, int *support)
{
    int nfree = 0, nfixed = 0;
    *body = *support = -1;
    for (int k = 0; k < sc->nbodies; k++) {
        const rd_body_def *b = &sc->bodies[k];
        if (b->fixed) {
            nfixed++;
            if (nfixed == 1) *support = k;
            continue;
        }
        nfree++;
        if (name[0] ? !strcmp(b->name, name) : nfree == 1) *body = k;
    }
    if (name[0] && *body < 0) {
        fprintf(stderr, "%s: assess: no free body named '%s'\n", sc->file, name);
        return -1;
    }
    if (!name[0] && nfree != 1) {
        fprintf(stderr, "%s: assess: %d free bodies; name the one to assess with --body\n",
                sc->file, nfree);
        return -1;
    }
    const rd_body_def *b = &sc->bodies[*body];
    if (b->seat_on[0])
        for (int k = 0; k < sc->nbodies; k++)
            if (!strcmp(sc->bodies[k].name, b->seat_on)) *support = k;
    if (nfixed != 1 && !b->seat_on[0]) *support = -1;
    return 0;
}

/* Mass of body b: given, or density times volume. */
static double body_mass(const rd_scenario *sc, const rd_body_def *b, double volume)
{
    return b->mass > 0 ? b->mass : (b->density > 0 ? b->density : sc->density) * volume;
}

/* The rigid body of the assessment from the scene's body definition; -1 after one line. */
static int make_body(const rd_scenario *sc, int k, double mu, rd_assess_body *ab,
                     double *half_width)
{
    const rd_body_def *b = &sc->bodies[k];
    if (b->rotation[0] != 0 || b->rotation[1] != 0) {
        fprintf(stderr,
                "%s:%d: assess: block '%s' is not upright (rotated about a horizontal axis)\n",
                sc->file, b->line, b->name);
        return -1;
    }
    if (b->shape == RD_SHAPE_BRICK) {
        /* it rocks first across its narrower side */
        double w = fmin(b->size[0], b->size[1]);
        rd_assess_body_brick(ab, w, b->size[2],
                             body_mass(sc, b, b->size[0] * b->size[1] * b->size[2]), mu);
        *half_width = 0.5 * b->size[0];
        return 0;
    }
    if (b->shape == RD_SHAPE_PRISM && b->radius_top == b->radius) {
        double area = 0.5 * b->sides * b->radius * b->radius * sin(2.0 * M_PI / b->sides);
        rd_assess_body_prism(ab, b->sides, b->radius, b->size[2],
                             body_mass(sc, b, area * b->size[2]), mu);
        *half_width = b->radius;
        return 0;
    }
    fprintf(stderr,
            "%s:%d: assess: block '%s' is a %s; the simplified methods need a brick or a prism "
            "(a drum of equal radii)\n",
            sc->file, b->line, b->name,
            b->shape == RD_SHAPE_PRISM  ? "frustum"
            : b->shape == RD_SHAPE_HULL ? "hull"
                                        : "mesh");
    return -1;
}

/* Distance the body may slide before its base reaches the pad's edge along x, m (0: it
 * overhangs; -1: unknown, the support is no brick). */
static double pad_gap(const rd_scenario *sc, int body, int support, double half_width)
{
    if (support < 0 || sc->bodies[support].shape != RD_SHAPE_BRICK) return -1.0;
    const rd_body_def *p = &sc->bodies[support], *b = &sc->bodies[body];
    return fmax(0.5 * p->size[0] - fabs(b->position[0] - p->position[0]) - half_width, 0.0);
}

static int mkdir_p(const char *dir)
{
    char buf[RD_PATH_MAX];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            if (mkdir(buf, 0777) && errno != EEXIST) return -1;
            *p = '/';
        }
    return mkdir(buf, 0777) && errno != EEXIST ? -1 : 0;
}

int rd_cli_assess(int argc, char **argv)
{
    assess_args a;
    memset(&a, 0, sizeof a);
    snprintf(a.spectrum, sizeof a.spectrum, "en1998-1A");
    a.damping = 0.05;
    a.kv = 2.0 / 3.0;
    a.mu = -1;
    a.limit = -1;
    a.slide_damping = RD_ASCE43_SLIDE_DAMPING;
    for (int k = 0; k < RD_NCODES; k++) a.codes[k] = 1;
    rd_evidence_defaults(&a.ev);
    rd_scenario sc;
    if (rd_cli_scenario(&sc, argc, argv, assess_option, &a, NULL)) {
        rd_scenario_free(&sc);
        return 2;
    }
    int rc = 2, body, support;
    rd_spectrum h;
    rd_assess_body ab;
    double half, phi_mu = 0;
    if (make_spectrum(&a, &h) || find_bodies(&sc, a.body, &body, &support)) goto done;
    if (a.mu < 0)
        phi_mu = support >= 0 ? joint_friction(&sc, &sc.bodies[body], &sc.bodies[support])
                              : sc.contact.friction;
    if (make_body(&sc, body, a.mu >= 0 ? a.mu : tan(phi_mu), &ab, &half)) goto done;
    if (a.limit < 0 && (a.limit = pad_gap(&sc, body, support, half)) <= 0) {
        fprintf(stderr, "%s: assess: no allowable sliding distance: give --slide-limit (m); %s\n",
                sc.file,
                a.limit < 0 ? "the pad's edge is not known (its support is no brick)"
                            : "the body overhangs its pad");
        goto done;
    }
    if (!a.out[0]) {
        const char *base = strrchr(sc.file, '/');
        snprintf(a.out, sizeof a.out, "%.*s_assess", (int)strcspn(base ? base + 1 : sc.file, "."),
                 base ? base + 1 : sc.file);
    }
    if (mkdir_p(a.out)) {
        fprintf(stderr, "rockdem: assess: cannot create the report folder '%s': %s\n", a.out,
                strerror(errno));
        goto done;
    }
    snprintf(a.ev.dir, sizeof a.ev.dir, "%s", a.out);
    a.ev.kv = a.kv;
    rc = rd_cli_assess_report(&sc, body, &a, &h, &ab, a.mu < 0 ? phi_mu : -1.0);
done:
    rd_scenario_free(&sc);
    return rc;
}
