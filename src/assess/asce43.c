/* rockdem — ASCE/SEI 43-05 Appendix A as seed 001 section 4 sets it out.
 *
 * A.2 rocking: the body rocking about its corner is replaced by a linear oscillator whose
 * torsion spring K_t (seed eq. 13) stores at the rocking angle phi the potential energy the
 * tilted body gains, with inertia I about the pivot (eq. 12) and the viscous damping D whose
 * energy loss per cycle equals the two impacts' loss by Housner's restitution (eq. 5). The
 * horizontal component drives the moment m h a_h, the vertical m b a_v; each angle is the
 * oscillator's spectral displacement times m h / I (or m b / I), phi = m h Sa / K_t, and the
 * two are combined by SRSS. phi and f = sqrt(K_t / I) / (2 pi) depend on each other: the
 * result is the largest phi in (0, alpha] that reproduces itself (the conservative fixed point
 * of the standard's iteration), and no such phi (the balance still short at alpha) means the
 * body tips over. The best estimate is multiplied by 2.0 and compared with alpha.
 *
 * A.1 sliding: seed 001 states its inputs (the spectrum and the 95 % exceedance friction
 * coefficient) and its factor 2.0; the rest is the same equivalent linearisation: a secant
 * spring that carries the friction force mu_e m g at the sliding distance d, so Sa(f_e) = mu_e g
 * and d = mu_e g / (2 pi f_e)^2, on the long-period side of the spectrum, with the
 * rigid-plastic loop's secant damping 2/pi (EN's eta floor of 0.55 limits what a spectrum
 * gives for it) and mu_e = mu (1 - 0.4 a_v / g), the vertical taken at 40 % (the 100-40-40
 * combination of ASCE 4-98 3.2.7.1.1, which ASCE 43-05 cites). docs/ASSESS.md states which
 * parts are the seed's and which are this reading.
 * Folder assess/ owns the seismic assessment of unanchored bodies; it may call base/,
 * records/, scenario/, engine/ and io/.
 */
#include "rockdem/assess.h"

#include <math.h>
#include <string.h>

/* The angle scan of A.2: log-spaced from alpha * PHI_SCAN_MIN to alpha. */
#define PHI_SCAN_N           4000
#define PHI_SCAN_MIN         1e-6
/* Bisection steps (each halves the bracket: 60 reach round-off from any bracket). */
#define BISECT_STEPS         60
/* Period scan of A.1 (s): log-spaced over [SLIDE_T_MIN, SLIDE_T_MAX]. */
#define SLIDE_T_N            4000
#define SLIDE_T_MIN          1e-3
#define SLIDE_T_MAX          100.0
/* Share of the vertical acceleration that lightens the body in A.1 (100-40-40 rule). */
#define SLIDE_VERTICAL_SHARE 0.4

double rd_assess_restitution(const rd_assess_body *b)
{
    double R2 = b->b * b->b + b->h * b->h, s = sin(rd_assess_alpha(b));
    return 1.0 - 2.0 * b->mass * R2 / b->inertia * s * s;
}

double rd_assess_rocking_damping(double r)
{
    double L = -log(r);
    return L / sqrt(M_PI * M_PI + L * L);
}

double rd_assess_rocking_stiffness(const rd_assess_body *b, double phi, double g)
{
    /* cos phi - 1 = -2 sin^2(phi/2) keeps the small-angle difference exact */
    double s = sin(0.5 * phi);
    return 2.0 * b->mass * g * b->h / (phi * phi) * (b->b / b->h * sin(phi) - 2.0 * s * s);
}

/* The oscillator at angle phi: frequency, spectral accelerations and the angles they give. */
static void rocking_at(const rd_assess_body *b, const rd_spectrum *h, const rd_spectrum *v,
                       double g, double D, double phi, rd_rocking *o)
{
    double K = rd_assess_rocking_stiffness(b, phi, g);
    double w = sqrt(K / b->inertia);
    o->freq = w / (2.0 * M_PI);
    o->sa_h = rd_spectrum_sa(h, 2.0 * M_PI / w, D);
    o->sa_v = v ? rd_spectrum_sa(v, 2.0 * M_PI / w, D) : 0.0;
    o->phi_h = b->mass * b->h * o->sa_h / K;
    o->phi_v = b->mass * b->b * o->sa_v / K;
}

/* SRSS angle over the trial angle: 1 at a consistent angle. */
static double rocking_ratio(const rd_assess_body *b, const rd_spectrum *h, const rd_spectrum *v,
                            double g, double D, double phi)
{
    rd_rocking o;
    rocking_at(b, h, v, g, D, phi, &o);
    return hypot(o.phi_h, o.phi_v) / phi;
}

static double scan_phi(double alpha, int k)
{
    return alpha * pow(PHI_SCAN_MIN, 1.0 - (double)k / (PHI_SCAN_N - 1));
}

static int check_body(const rd_assess_body *b, rd_error *err)
{
    if (!(b->b > 0 && b->h > 0 && b->mass > 0 && b->inertia > 0) || !(b->mu >= 0))
        return rd_error_set(
            err,
            "assess: body b %g m, h %g m, mass %g kg, inertia %g kg m^2 must be positive and "
            "mu %g >= 0",
            b->b, b->h, b->mass, b->inertia, b->mu);
    return 0;
}

int rd_assess_rocking(const rd_assess_body *b, const rd_spectrum *h, const rd_spectrum *v, double g,
                      rd_rocking *out, rd_error *err)
{
    if (check_body(b, err)) return -1;
    double r = rd_assess_restitution(b);
    if (!(r > 0))
        return rd_error_set(err,
                            "assess: the body's restitution r = %.3g <= 0 (too squat to rock: "
                            "b/h >= sqrt 2 for a box, seed 001 section 2)",
                            r);
    memset(out, 0, sizeof *out);
    double D = rd_assess_rocking_damping(r), alpha = rd_assess_alpha(b);
    out->damping = D;
    out->alpha = alpha;
    double lo = 0.0, hi = 0.0;
    if (rocking_ratio(b, h, v, g, D, alpha) >= 1.0) {
        out->overturns = 1;
        out->phi = alpha;
    } else {
        for (int k = PHI_SCAN_N - 2; k >= 0 && hi == 0.0; k--)
            if (rocking_ratio(b, h, v, g, D, scan_phi(alpha, k)) >= 1.0) {
                lo = scan_phi(alpha, k);
                hi = scan_phi(alpha, k + 1);
            }
        for (int i = 0; i < BISECT_STEPS && hi > 0.0; i++) {
            double m = 0.5 * (lo + hi);
            *(rocking_ratio(b, h, v, g, D, m) >= 1.0 ? &lo : &hi) = m;
        }
        out->phi = lo;
    }
    rocking_at(b, h, v, g, D, out->phi > 0 ? out->phi : scan_phi(alpha, 0), out);
    out->margin = out->phi > 0 ? alpha / (RD_ASCE43_SF_ROCK * out->phi) : INFINITY;
    return 0;
}

int rd_assess_pga_rocking(const rd_assess_body *b, const rd_spectrum *h, double kv, double g,
                          double *pga, rd_error *err)
{
    if (check_body(b, err)) return -1;
    double r = rd_assess_restitution(b);
    if (!(r > 0))
        return rd_error_set(err, "assess: the body's restitution r = %.3g <= 0: it does not rock",
                            r);
    rd_spectrum hs = *h, vs = *h;
    hs.scale = 1.0;
    vs.scale = kv;
    double D = rd_assess_rocking_damping(r), alpha = rd_assess_alpha(b);
    /* the ratio scales with the spectrum: the largest consistent angle reaches
       phi* = alpha / SF once scale x max over [phi*, alpha] of the ratio reaches 1 */
    double phi0 = alpha / RD_ASCE43_SF_ROCK, best = 0.0;
    for (int k = 0; k < PHI_SCAN_N; k++) {
        double phi = phi0 + (alpha - phi0) * k / (PHI_SCAN_N - 1);
        best = fmax(best, rocking_ratio(b, &hs, kv > 0 ? &vs : NULL, g, D, phi));
    }
    *pga = rd_spectrum_pga(&hs) / best;
    return 0;
}

/* A.1 at the spectrum as given: fills out, returns 0. */
static void sliding_at(const rd_assess_body *b, const rd_spectrum *h, double a_v, double zeta,
                       double g, rd_sliding *out)
{
    out->mu_e = b->mu * (1.0 - SLIDE_VERTICAL_SHARE * a_v / g);
    out->damping = zeta;
    out->freq = 0.0;
    out->distance = 0.0;
    double target = out->mu_e * g; /* m/s^2 */
    if (!(target > 0)) {
        out->distance = INFINITY;
        return;
    }
    if (rd_spectrum_sa(h, 0.0, zeta) <= target) return; /* the pad holds it: no sliding */
    /* the last period of the scan at which Sa still reaches mu_e g; the crossing after it */
    double lo = 0.0, hi = 0.0;
    for (int k = SLIDE_T_N - 1; k >= 0 && hi == 0.0; k--) {
        double T = SLIDE_T_MIN * pow(SLIDE_T_MAX / SLIDE_T_MIN, (double)k / (SLIDE_T_N - 1));
        if (rd_spectrum_sa(h, T, zeta) >= target) {
            if (k == SLIDE_T_N - 1) {
                out->distance = INFINITY;
                return;
            }
            lo = T;
            hi = SLIDE_T_MIN * pow(SLIDE_T_MAX / SLIDE_T_MIN, (double)(k + 1) / (SLIDE_T_N - 1));
        }
    }
    if (hi == 0.0) return; /* Sa below mu_e g at every period but T = 0: the PGA is a spike */
    for (int i = 0; i < BISECT_STEPS; i++) {
        double m = 0.5 * (lo + hi);
        *(rd_spectrum_sa(h, m, zeta) >= target ? &lo : &hi) = m;
    }
    out->freq = 1.0 / lo;
    out->distance = target * lo * lo / (4.0 * M_PI * M_PI);
}

int rd_assess_sliding(const rd_assess_body *b, const rd_spectrum *h, double a_v, double zeta,
                      double limit, double g, rd_sliding *out, rd_error *err)
{
    if (check_body(b, err)) return -1;
    if (!(zeta > 0 && zeta < 1))
        return rd_error_set(err, "assess: sliding damping %g must be in (0, 1)", zeta);
    if (!(limit > 0))
        return rd_error_set(err, "assess: allowable sliding distance %g m must be positive", limit);
    sliding_at(b, h, a_v, zeta, g, out);
    out->limit = limit;
    out->margin = out->distance > 0 ? limit / (RD_ASCE43_SF_SLIDE * out->distance) : INFINITY;
    return 0;
}

int rd_assess_pga_sliding(const rd_assess_body *b, const rd_spectrum *h, double kv, double zeta,
                          double limit, double g, double *pga, rd_error *err)
{
    rd_sliding o;
    if (rd_assess_sliding(b, h, 0.0, zeta, limit, g, &o, err)) return -1;
    rd_spectrum s = *h;
    double lo = 0.0, hi = 1.0, pga1;
    s.scale = 1.0;
    pga1 = rd_spectrum_pga(&s);
    /* the factored distance grows with the scale (Sa up, mu_e down): bracket, then bisect */
    for (int i = 0; i < 200; i++) {
        s.scale = hi;
        sliding_at(b, &s, kv * hi * pga1, zeta, g, &o);
        if (RD_ASCE43_SF_SLIDE * o.distance > limit) break;
        lo = hi;
        hi *= 2.0;
    }
    for (int i = 0; i < BISECT_STEPS; i++) {
        double m = 0.5 * (lo + hi);
        s.scale = m;
        sliding_at(b, &s, kv * m * pga1, zeta, g, &o);
        *(RD_ASCE43_SF_SLIDE * o.distance > limit ? &hi : &lo) = m;
    }
    *pga = lo * pga1;
    return 0;
}
