/* rockdem — the tables of `rockdem assess` on stdout and the same numbers in OUT/assess.json
 * (read by tools/rdassess.py for the report): spectrum, static checks per code, ASCE 43-05
 * A.1 and A.2, allowable PGAs, time-history evidence and the verdicts side by side.
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"
#include "cli/cli_assess.h"
#include "rockdem/record.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Points of the spectrum curve written for the report's figure (log-spaced, s). */
#define CURVE_N     120
#define CURVE_T_MIN 0.01
#define CURVE_T_MAX 10.0

typedef struct results {
    double g, pga, av;
    rd_static_check st[RD_NCODES];
    rd_rocking rock;
    rd_sliding slide;
    double pga_rock, pga_slide;
    int have_ev;
    rd_evidence ev;
    int th_rock_ok, th_slide_ok;
} results;

/* A JSON number (null for inf / nan). */
static void jnum(FILE *f, const char *key, double x, int comma)
{
    if (isfinite(x))
        fprintf(f, "\"%s\": %.10g%s", key, x, comma ? ", " : "");
    else
        fprintf(f, "\"%s\": null%s", key, comma ? ", " : "");
}

/* A JSON string: quotes, backslashes and control characters escaped. */
static void jstr(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

static const char *verdict(double margin) { return margin >= 1.0 ? "pass" : "FAIL"; }

static void print_tables(const rd_scenario *sc, int body, const assess_args *a,
                         const rd_spectrum *h, const rd_assess_body *ab, double phi_scene,
                         const results *r)
{
    printf(
        "assess: body '%s' of %s: b %.4g m, h %.4g m, mass %.4g kg, I %.4g kg m^2 about the pivot, "
        "alpha %.4g deg, Housner r %.4f\n",
        sc->bodies[body].name, sc->file, ab->b, ab->h, ab->mass, ab->inertia,
        rd_assess_alpha(ab) * 180 / M_PI, rd_assess_restitution(ab));
    if (phi_scene >= 0)
        printf("friction: mu = tan(%.4g deg) = %.4g (the scene's joint)\n", phi_scene * 180 / M_PI,
               ab->mu);
    else
        printf("friction: mu = %.4g (--mu)\n", ab->mu);
    if (h->kind == RD_SPECTRUM_EN1998)
        printf(
            "spectrum: EN 1998-1 type %d, ground %c, a_g %.4g g, S %.3g, TB %.3g TC %.3g TD %.3g s, 5 %%; PGA %.4g g\n",
            h->type, h->ground, h->ag / RD_G_STANDARD, h->S, h->TB, h->TC, h->TD,
            r->pga / RD_G_STANDARD);
    else
        printf("spectrum: table %s (%d points, %.3g %% damping); PGA %.4g g\n", a->spectrum, h->n,
               100 * h->damping, r->pga / RD_G_STANDARD);
    printf("vertical: %.4g x horizontal (PGA %.4g g); allowable sliding distance %.4g m\n", a->kv,
           r->av / RD_G_STANDARD, a->limit);
    printf("static checks (seed 001 Table 2), a_h = PGA %.4g g:\n", r->pga / RD_G_STANDARD);
    printf("  %-18s %5s %7s %9s %9s %8s %8s %8s %10s %10s\n", "code", "dead", "a_up g", "M_over",
           "M_resist", "margin", "mu_req", "margin", "PGA_rock g", "PGA_slide g");
    for (int c = 0; c < RD_NCODES; c++) {
        if (!a->codes[c]) continue;
        rd_code_factors f;
        rd_code_get((rd_code)c, &f);
        const rd_static_check *s = &r->st[c];
        printf("  %-18s %5.3g %7.4f %9.4g %9.4g %6.3f %s %8.4f %6.3f %s %10.4f %10.4f\n", f.name,
               f.dead, s->a_up / RD_G_STANDARD, s->m_over, s->m_resist, s->rock_margin,
               verdict(s->rock_margin), s->mu_required, s->slide_margin, verdict(s->slide_margin),
               s->pga_rock / RD_G_STANDARD, s->pga_slide / RD_G_STANDARD);
    }
    const rd_rocking *k = &r->rock;
    printf(
        "ASCE 43-05 A.2 rocking: D %.2f %%, phi %.4g rad (%.4g deg) at f %.4g Hz (Sa_h %.4g g, Sa_v %.4g g; "
        "phi_h %.4g, phi_v %.4g rad); SF %.1f: %.4g rad vs alpha %.4g rad: margin %.3f %s%s; allowable PGA %.4f g\n",
        100 * k->damping, k->phi, k->phi * 180 / M_PI, k->freq, k->sa_h / RD_G_STANDARD,
        k->sa_v / RD_G_STANDARD, k->phi_h, k->phi_v, RD_ASCE43_SF_ROCK, RD_ASCE43_SF_ROCK * k->phi,
        k->alpha, k->margin, verdict(k->margin),
        k->overturns ? " (no angle balances: it tips over)" : "", r->pga_rock / RD_G_STANDARD);
    const rd_sliding *s = &r->slide;
    printf(
        "ASCE 43-05 A.1 sliding: mu_e %.4g, damping %.1f %%, f_e %.4g Hz, distance %.4g m; SF %.1f: %.4g m vs %.4g m: "
        "margin %.3f %s; allowable PGA %.4f g\n",
        s->mu_e, 100 * s->damping, s->freq, s->distance, RD_ASCE43_SF_SLIDE,
        RD_ASCE43_SF_SLIDE * s->distance, s->limit, s->margin, verdict(s->margin),
        r->pga_slide / RD_G_STANDARD);
    if (!r->have_ev) {
        printf("time histories: none (--records 0)\n");
        return;
    }
    const rd_evidence *e = &r->ev;
    printf(
        "time histories: %d records matched to the spectrum over %.3g-%.3g s within [%.2f, %.2f] x target:\n",
        e->n, a->ev.tmin, a->ev.tmax, a->ev.lo, a->ev.hi);
    for (int i = 0; i < e->n; i++)
        printf(
            "  record %d: PGA %.4g g, Sa/target %.3f-%.3f %s; peak tilt %.4g rad, peak slide %.4g mm%s\n",
            i + 1, e->pga[i] / RD_G_STANDARD, e->ratio_min[i], e->ratio_max[i],
            e->in_band[i] ? "in band" : "OUT OF BAND", e->tilt[i], 1e3 * e->slide[i],
            e->overturned[i] ? ", OVERTURNED" : "");
    printf("  mean peak tilt %.4g rad (sd %.3g), SF %.1f: %.4g vs alpha %.4g rad: %s\n",
           e->tilt_mean, e->tilt_sd, RD_ASCE43_SF_ROCK, RD_ASCE43_SF_ROCK * e->tilt_mean,
           rd_assess_alpha(ab), r->th_rock_ok ? "pass" : "FAIL");
    printf("  mean peak slide %.4g mm (sd %.3g), SF %.1f: %.4g m vs %.4g m: %s\n",
           1e3 * e->slide_mean, 1e3 * e->slide_sd, RD_TH_SF_SLIDE, RD_TH_SF_SLIDE * e->slide_mean,
           a->limit, r->th_slide_ok ? "pass" : "FAIL");
}

static void json_spectrum(FILE *f, const assess_args *a, const rd_spectrum *h, const rd_rocking *k)
{
    fprintf(f, "\"spectrum\": {\"kind\": \"%s\", ",
            h->kind == RD_SPECTRUM_EN1998 ? "en1998" : "table");
    if (h->kind == RD_SPECTRUM_EN1998)
        fprintf(
            f,
            "\"type\": %d, \"ground\": \"%c\", \"ag\": %.10g, \"S\": %g, \"TB\": %g, \"TC\": %g, \"TD\": %g, ",
            h->type, h->ground, h->ag, h->S, h->TB, h->TC, h->TD);
    else {
        fprintf(f, "\"file\": ");
        jstr(f, a->spectrum);
        fprintf(f, ", ");
    }
    jnum(f, "damping", h->damping, 1);
    fprintf(f, "\"T\": [");
    for (int i = 0; i < CURVE_N; i++)
        fprintf(f, "%s%.6g", i ? ", " : "",
                CURVE_T_MIN * pow(CURVE_T_MAX / CURVE_T_MIN, (double)i / (CURVE_N - 1)));
    fprintf(f, "], \"sa\": [");
    for (int i = 0; i < CURVE_N; i++)
        fprintf(f, "%s%.6g", i ? ", " : "",
                rd_spectrum_sa(
                    h, CURVE_T_MIN * pow(CURVE_T_MAX / CURVE_T_MIN, (double)i / (CURVE_N - 1)),
                    h->damping));
    fprintf(f, "], \"sa_rocking\": [");
    for (int i = 0; i < CURVE_N; i++)
        fprintf(f, "%s%.6g", i ? ", " : "",
                rd_spectrum_sa(
                    h, CURVE_T_MIN * pow(CURVE_T_MAX / CURVE_T_MIN, (double)i / (CURVE_N - 1)),
                    k->damping));
    fprintf(f, "]},\n");
}

static int write_json(const rd_scenario *sc, int body, const assess_args *a, const rd_spectrum *h,
                      const rd_assess_body *ab, double phi_scene, const results *r)
{
    char path[RD_PATH_MAX + 16];
    snprintf(path, sizeof path, "%s/assess.json", a->out);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "rockdem: assess: cannot write %s\n", path);
        return -1;
    }
    fprintf(f, "{\"scene\": ");
    jstr(f, sc->file);
    fprintf(f, ", \"title\": ");
    jstr(f, sc->title);
    fprintf(f, ", \"version\": \"%s\", \"g\": %.10g,\n\"body\": {\"name\": ", RD_VERSION, r->g);
    jstr(f, sc->bodies[body].name);
    fprintf(f, ", \"shape\": \"%s\", ",
            sc->bodies[body].shape == RD_SHAPE_BRICK ? "brick" : "prism");
    jnum(f, "b", ab->b, 1);
    jnum(f, "h", ab->h, 1);
    jnum(f, "mass", ab->mass, 1);
    jnum(f, "inertia", ab->inertia, 1);
    jnum(f, "alpha", rd_assess_alpha(ab), 1);
    jnum(f, "restitution", rd_assess_restitution(ab), 1);
    jnum(f, "mu", ab->mu, 1);
    jnum(f, "friction_angle", phi_scene, 0);
    fprintf(f, "},\n");
    json_spectrum(f, a, h, &r->rock);
    fprintf(f,
            "\"pga\": %.10g, \"kv\": %.10g, \"av\": %.10g, \"slide_limit\": %.10g,\n\"static\": [",
            r->pga, a->kv, r->av, a->limit);
    int first = 1;
    for (int c = 0; c < RD_NCODES; c++) {
        if (!a->codes[c]) continue;
        rd_code_factors cf;
        rd_code_get((rd_code)c, &cf);
        const rd_static_check *s = &r->st[c];
        fprintf(f, "%s\n {\"code\": \"%s\", ", first ? "" : ",", cf.name);
        first = 0;
        jnum(f, "dead", cf.dead, 1);
        jnum(f, "up_h", cf.up_h, 1);
        jnum(f, "up_v", cf.up_v, 1);
        jnum(f, "a_up", s->a_up, 1);
        jnum(f, "m_over", s->m_over, 1);
        jnum(f, "m_resist", s->m_resist, 1);
        jnum(f, "rock_margin", s->rock_margin, 1);
        jnum(f, "mu_required", s->mu_required, 1);
        jnum(f, "slide_margin", s->slide_margin, 1);
        jnum(f, "pga_rock", s->pga_rock, 1);
        jnum(f, "pga_slide", s->pga_slide, 0);
        fprintf(f, "}");
    }
    const rd_rocking *k = &r->rock;
    const rd_sliding *s = &r->slide;
    fprintf(f, "],\n\"rocking\": {");
    jnum(f, "phi", k->phi, 1);
    fprintf(f, "\"overturns\": %d, ", k->overturns);
    jnum(f, "freq", k->freq, 1);
    jnum(f, "damping", k->damping, 1);
    jnum(f, "sa_h", k->sa_h, 1);
    jnum(f, "sa_v", k->sa_v, 1);
    jnum(f, "phi_h", k->phi_h, 1);
    jnum(f, "phi_v", k->phi_v, 1);
    jnum(f, "sf", RD_ASCE43_SF_ROCK, 1);
    jnum(f, "margin", k->margin, 1);
    jnum(f, "pga_allow", r->pga_rock, 0);
    fprintf(f, "},\n\"sliding\": {");
    jnum(f, "mu_e", s->mu_e, 1);
    jnum(f, "damping", s->damping, 1);
    jnum(f, "freq", s->freq, 1);
    jnum(f, "distance", s->distance, 1);
    jnum(f, "sf", RD_ASCE43_SF_SLIDE, 1);
    jnum(f, "margin", s->margin, 1);
    jnum(f, "pga_allow", r->pga_slide, 0);
    fprintf(f, "},\n\"evidence\": ");
    if (!r->have_ev)
        fprintf(f, "null");
    else {
        const rd_evidence *e = &r->ev;
        fprintf(
            f,
            "{\"n\": %d, \"duration\": %g, \"dt\": %g, \"seed\": %lu, \"tmin\": %g, \"tmax\": %g, \"lo\": %g, "
            "\"hi\": %g, \"nperiods\": %d, \"sf_slide\": %g, \"sf_rock\": %g, ",
            e->n, a->ev.duration, a->ev.dt, a->ev.seed, a->ev.tmin, a->ev.tmax, a->ev.lo, a->ev.hi,
            RD_EVIDENCE_NPERIODS, RD_TH_SF_SLIDE, RD_ASCE43_SF_ROCK);
        jnum(f, "tilt_mean", e->tilt_mean, 1);
        jnum(f, "tilt_sd", e->tilt_sd, 1);
        jnum(f, "slide_mean", e->slide_mean, 1);
        jnum(f, "slide_sd", e->slide_sd, 1);
        fprintf(f, "\"rock_ok\": %d, \"slide_ok\": %d, \"records\": [", r->th_rock_ok,
                r->th_slide_ok);
        for (int i = 0; i < e->n; i++) {
            fprintf(f, "%s\n  {\"h\": \"record%d_h.csv\", \"run\": \"run%d.h5\", ", i ? "," : "",
                    i + 1, i + 1);
            if (a->kv > 0)
                fprintf(f, "\"v\": \"record%d_v.csv\", ", i + 1);
            else
                fprintf(f, "\"v\": null, ");
            jnum(f, "pga", e->pga[i], 1);
            jnum(f, "ratio_min", e->ratio_min[i], 1);
            jnum(f, "ratio_max", e->ratio_max[i], 1);
            fprintf(f, "\"in_band\": %d, \"overturned\": %d, ", e->in_band[i], e->overturned[i]);
            jnum(f, "tilt", e->tilt[i], 1);
            jnum(f, "slide", e->slide[i], 0);
            fprintf(f, "}");
        }
        fprintf(f, "]}");
    }
    fprintf(f, "\n}\n");
    if (fclose(f)) {
        fprintf(stderr, "rockdem: assess: cannot write %s\n", path);
        return -1;
    }
    printf("output: %s\n", path);
    return 0;
}

int rd_cli_assess_report(const rd_scenario *sc, int body, const assess_args *a,
                         const rd_spectrum *h, const rd_assess_body *ab, double phi_scene)
{
    results r;
    memset(&r, 0, sizeof r);
    rd_error err;
    r.g = sc->gravity;
    r.pga = rd_spectrum_pga(h);
    r.av = a->kv * r.pga;
    rd_spectrum v = *h;
    v.scale = a->kv;
    for (int c = 0; c < RD_NCODES; c++)
        if (a->codes[c])
            rd_assess_static(ab, (rd_code)c, r.pga, r.av, a->kv, a->neglect, r.g, &r.st[c]);
    if (rd_assess_rocking(ab, h, a->kv > 0 ? &v : NULL, r.g, &r.rock, &err) ||
        rd_assess_pga_rocking(ab, h, a->kv, r.g, &r.pga_rock, &err) ||
        rd_assess_sliding(ab, h, r.av, a->slide_damping, a->limit, r.g, &r.slide, &err) ||
        rd_assess_pga_sliding(ab, h, a->kv, a->slide_damping, a->limit, r.g, &r.pga_slide, &err)) {
        fprintf(stderr, "%s: %s\n", sc->file, err.msg);
        return 2;
    }
    if (a->ev.nrecords > 0) {
        rd_cli_progress_start("assess", a->ev.nrecords);
        int bad = rd_assess_evidence(sc, body, h, &a->ev, &r.ev, &err);
        rd_cli_progress_stop();
        if (bad) {
            fprintf(stderr, "%s: %s\n", sc->file, err.msg);
            return 3;
        }
        r.have_ev = 1;
        int over = 0;
        for (int i = 0; i < r.ev.n; i++) over |= r.ev.overturned[i];
        r.th_rock_ok = !over && RD_ASCE43_SF_ROCK * r.ev.tilt_mean <= rd_assess_alpha(ab);
        r.th_slide_ok = RD_TH_SF_SLIDE * r.ev.slide_mean <= a->limit;
    }
    print_tables(sc, body, a, h, ab, phi_scene, &r);
    return write_json(sc, body, a, h, ab, phi_scene, &r) ? 3 : 0;
}
