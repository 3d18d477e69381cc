/* rockdem — seismic assessment of an unanchored rigid body on its pad (issue 43; seed 001
 * section 4, docs/ASSESS.md): design response spectra, the static rocking and sliding checks of
 * ASCE/SEI 7-10, EN 1990/1998-1 and KTA 2201.1/2201.4 with the load factors of seed 001 Table 2,
 * the simplified methods of ASCE/SEI 43-05 Appendix A (A.1 sliding, A.2 rocking), allowable
 * peak ground accelerations, and the time-history evidence run through the DEM.
 *
 * Files: spectrum.c (EN 1998-1 and tabulated spectra), static_check.c (Table 2),
 * asce43.c (Appendix A), evidence.c (spectrum-compatible records through the DEM).
 * SI units: m, kg, s, rad, m/s^2; damping as a ratio of critical (0.05 = 5 %).
 */
#ifndef ROCKDEM_ASSESS_H
#define ROCKDEM_ASSESS_H

#include "rockdem/api.h"
#include "rockdem/error.h"
#include "rockdem/scenario.h"

/* ---- spectrum.c: horizontal elastic response spectra ------------------------------------- */

#define RD_SPECTRUM_MAX 1024 /* points of a tabulated spectrum */

typedef enum rd_spectrum_kind {
    RD_SPECTRUM_EN1998 = 0, /* EN 1998-1:2004 3.2.2.2, eqs. (3.2)-(3.5), Tables 3.2 / 3.3 */
    RD_SPECTRUM_TABLE = 1   /* user table of (period, Sa) at its own damping */
} rd_spectrum_kind;

typedef struct rd_spectrum {
    rd_spectrum_kind kind;
    int type;             /* EN: spectrum type 1 (Ms > 5.5) or 2 */
    char ground;          /* EN: ground type 'A'..'E' */
    double ag;            /* EN: design ground acceleration on type A ground, m/s^2 */
    double S, TB, TC, TD; /* EN: soil factor and corner periods (s) of Table 3.2 / 3.3 */
    int n;                /* table: number of points (>= 2), periods strictly increasing from 0 */
    double T[RD_SPECTRUM_MAX];  /* table: periods, s */
    double sa[RD_SPECTRUM_MAX]; /* table: spectral accelerations, m/s^2 */
    double damping;             /* damping ratio the ordinates are given at (EN: 0.05) */
    double scale; /* every ordinate is multiplied by this (1 as built; the allowable-PGA
                        searches scale the spectrum's shape) */
} rd_spectrum;

/* EN 1998-1 type 1 or 2 elastic spectrum for ground type 'A'..'E' and a_g (m/s^2, > 0).
 * 0, or -1 with err naming the bad value. */
RD_API int rd_spectrum_en1998(rd_spectrum *s, int type, char ground, double ag, rd_error *err);

/* A tabulated spectrum: n points (T_i s, Sa_i m/s^2), T_0 = 0 (its Sa is the PGA), periods
 * strictly increasing, Sa > 0, given at damping ratio `damping` in (0, 1). 0 or -1. */
RD_API int rd_spectrum_table(rd_spectrum *s, const double *T, const double *sa, int n,
                             double damping, rd_error *err);

/* Read a table file: two columns, period (s) and Sa (in g), blanks or commas, '#' comments.
 * Errors read "file:line: problem". 0 or -1. */
RD_API int rd_spectrum_read(rd_spectrum *s, const char *path, double damping, rd_error *err);

/* EN 1998-1 (3.6): damping correction eta = sqrt(10 / (5 + xi)) >= 0.55, xi in percent
 * (eta = 1 at 5 %). */
RD_API double rd_spectrum_eta(double zeta);

/* Spectral acceleration (m/s^2) at period T (s, >= 0) and damping ratio zeta: EN's
 * eqs. (3.2)-(3.5) with eta(zeta) (beyond 4 s the 1/T^2 branch (3.5) continues); a table is
 * interpolated linearly in period, held at constant spectral displacement beyond its last
 * period, and corrected from its damping by eta(zeta) / eta(damping), blended in linearly over
 * its first interval as EN's (3.2) does up to TB (the PGA at T = 0 does not depend on damping).
 * Every value is times s->scale. */
RD_API double rd_spectrum_sa(const rd_spectrum *s, double T, double zeta);

/* Peak ground acceleration the spectrum implies (Sa at T = 0; EN: a_g S), m/s^2. */
RD_API double rd_spectrum_pga(const rd_spectrum *s);

/* ---- the body ---------------------------------------------------------------------------- */

typedef struct rd_assess_body {
    double b;       /* horizontal distance from the centre of mass to the rocking pivot, m */
    double h;       /* height of the centre of mass above the base, m */
    double mass;    /* kg */
    double inertia; /* moment of inertia about the pivot, kg m^2 (seed 001 Table 1: I) */
    double mu;      /* available friction coefficient (A.1: the 95 % exceedance value) */
} rd_assess_body;

/* Rigid box 2b x 2h, homogeneous (seed 001 Table 1: I0 = m (b^2 + h^2) / 3, I = I0 + m R^2). */
RD_API void rd_assess_body_brick(rd_assess_body *b, double width, double height, double mass,
                                 double mu);

/* Regular n-gon prism (n >= 3, circumradius R) or, for n = 0, a circular cylinder of radius R,
 * height H, homogeneous, rocking on its rim about the least stable axis: b = R cos(pi / n)
 * (the apothem: it rocks about an edge), R for the cylinder; I0 about a horizontal centroidal
 * axis = m (R^2 (1 + 2 cos^2(pi / n)) / 12 + H^2 / 12) (m (R^2 / 4 + H^2 / 12) for n = 0). */
RD_API void rd_assess_body_prism(rd_assess_body *b, int sides, double radius, double height,
                                 double mass, double mu);

/* Critical angle alpha = atan(b / h), rad. */
RD_API double rd_assess_alpha(const rd_assess_body *b);

/* ---- static_check.c: the codes' static checks (seed 001 Table 2) -------------------------- */

typedef enum rd_code {
    RD_CODE_ASCE7 = 0,
    RD_CODE_EN1998 = 1,
    RD_CODE_KTA = 2,
    RD_NCODES = 3
} rd_code;

/* One code's load factors, as seed 001 Table 2 gives them: the dead load is multiplied by
 * `dead`; the upward seismic acceleration is up_h a_h + up_v a_v. */
typedef struct rd_code_factors {
    const char *name; /* "ASCE/SEI 7-10", "EN 1990/1998-1", "KTA 2201.1/2201.4" */
    double dead;      /* factor on the dead load: 0.9, 1.0, 0.95 */
    double up_h;      /* share of the horizontal acceleration acting upwards: 2/3, 0, 0 */
    double up_v;      /* share of the vertical acceleration acting upwards: 0, 0.3, 0.3 */
    double neglect_v; /* the vertical may be neglected below this vertical PGA, m/s^2 per g
                            (EN: 0.25; 0: never) */
} rd_code_factors;

RD_API void rd_code_get(rd_code c, rd_code_factors *f);

/* A static check: overturning moment m a_h h against the resisting moment
 * (dead g - upward) m b; required friction coefficient a_h / (dead g - upward). */
typedef struct rd_static_check {
    double a_up;         /* upward seismic acceleration, m/s^2 */
    double m_over;       /* overturning moment, N m */
    double m_resist;     /* resisting moment, N m */
    double rock_margin;  /* m_resist / m_over (>= 1 passes; inf without horizontal load) */
    double mu_required;  /* a_h / (dead g - a_up) (inf when nothing holds the body down) */
    double slide_margin; /* mu / mu_required */
    double pga_rock;     /* allowable PGA against rocking, m/s^2 (a_v = kv a_h) */
    double pga_slide;    /* allowable PGA against sliding, m/s^2 */
} rd_static_check;

/* The check of code c for horizontal acceleration a_h and vertical a_v (m/s^2, >= 0) on the
 * body: a rigid body on its pad feels the PGA (the spectrum's T = 0 value). kv = a_v / a_h
 * for the allowable PGAs; neglect = 1 uses EN's permission to drop a vertical PGA below
 * 0.25 g. g: gravity, m/s^2. */
RD_API void rd_assess_static(const rd_assess_body *b, rd_code c, double a_h, double a_v, double kv,
                             int neglect, double g, rd_static_check *out);

/* ---- asce43.c: ASCE/SEI 43-05 Appendix A ------------------------------------------------- */

#define RD_ASCE43_SF_SLIDE 2.0 /* A.1: safety factor on the best-estimate sliding distance */
#define RD_ASCE43_SF_ROCK  2.0 /* A.2: safety factor on the best-estimate rocking angle */
#define RD_TH_SF_SLIDE     3.0 /* time histories (mean of >= 5 records): factor on sliding */
#define RD_TH_MIN_RECORDS  5   /* time histories: at least five records */

/* Housner's restitution of the body, seed 001 eq. (5): r = 1 - (2 m R^2 / I) sin^2 alpha. */
RD_API double rd_assess_restitution(const rd_assess_body *b);

/* Equivalent viscous damping ratio of the linearised rocking oscillator whose energy loss per
 * cycle equals the rocking body's two impacts (seed 001 section 4): r^4 = exp(-4 pi D /
 * sqrt(1 - D^2)), so D = -ln r / sqrt(pi^2 + ln^2 r); 11.3 % for r = 0.7 (h/b = 2). */
RD_API double rd_assess_rocking_damping(double r);

/* Seed 001 eq. (13): K_t = 2 m g h / phi^2 (cos phi + (b/h) sin phi - 1), N m / rad. */
RD_API double rd_assess_rocking_stiffness(const rd_assess_body *b, double phi, double g);

typedef struct rd_rocking {
    double phi;          /* best-estimate rocking angle, rad (0: no rocking; alpha: overturns) */
    int overturns;       /* 1: no angle up to alpha balances the spectrum (the body tips over) */
    double freq;         /* f = sqrt(K_t / I) / (2 pi) at phi, Hz */
    double damping;      /* D from the restitution */
    double sa_h, sa_v;   /* spectral accelerations at f and D, m/s^2 */
    double phi_h, phi_v; /* angles from each component (m h Sa_h / K_t, m b Sa_v / K_t), rad */
    double alpha;        /* critical angle, rad */
    double margin;       /* alpha / (SF phi): >= 1 passes */
} rd_rocking;

/* A.2: the largest angle phi in (0, alpha] at which SRSS(phi_h, phi_v) = phi on the
 * horizontal spectrum h and the vertical spectrum v (may be NULL: none). 0 or -1. */
RD_API int rd_assess_rocking(const rd_assess_body *b, const rd_spectrum *h, const rd_spectrum *v,
                             double g, rd_rocking *out, rd_error *err);

typedef struct rd_sliding {
    double mu_e;     /* effective friction coefficient mu (1 - 0.4 a_v / g) */
    double damping;  /* damping of the secant oscillator */
    double freq;     /* f_e at which Sa(f_e, damping) = mu_e g on the long-period side, Hz */
    double distance; /* best-estimate sliding distance mu_e g / (2 pi f_e)^2, m (0: none) */
    double limit;    /* allowable distance, m */
    double margin;   /* limit / (SF distance): >= 1 passes */
} rd_sliding;

/* Secant damping of a rigid-plastic friction loop, 2 / pi (energy per cycle 4 F d over
 * 4 pi times the secant's strain energy F d / 2). */
#define RD_ASCE43_SLIDE_DAMPING (2.0 / 3.14159265358979323846)

/* A.1: sliding distance on spectrum h with vertical PGA a_v (m/s^2) and damping ratio zeta
 * for the secant oscillator (RD_ASCE43_SLIDE_DAMPING); limit: allowable distance, m. */
RD_API int rd_assess_sliding(const rd_assess_body *b, const rd_spectrum *h, double a_v, double zeta,
                             double limit, double g, rd_sliding *out, rd_error *err);

/* Allowable PGA (m/s^2) of A.2 (SF on the angle below alpha) and of A.1 (SF on the distance
 * below limit): the spectrum's shape scaled, the vertical spectrum kv times the horizontal.
 * 0 or -1. */
RD_API int rd_assess_pga_rocking(const rd_assess_body *b, const rd_spectrum *h, double kv, double g,
                                 double *pga, rd_error *err);
RD_API int rd_assess_pga_sliding(const rd_assess_body *b, const rd_spectrum *h, double kv,
                                 double zeta, double limit, double g, double *pga, rd_error *err);

/* ---- evidence.c: spectrum-compatible records through the DEM ------------------------------ */

#define RD_EVIDENCE_MAX      32
/* Periods at which each record is matched and checked: log-spaced over the band, 200 over
 * 0.05-4 s are 2.2 % apart (at 48, 10 % apart, a record's spectrum dipped to 0.83 of the
 * target between two of them). */
#define RD_EVIDENCE_NPERIODS 200

typedef struct rd_evidence_def {
    int nrecords;          /* >= RD_TH_MIN_RECORDS (default 5) */
    double duration;       /* record length, s (default 20) */
    double dt;             /* record step, s (default 0.005) */
    unsigned long seed;    /* first generator seed (default 1; record k uses seed + k) */
    double tmin, tmax;     /* matching band, s (default 0.05 .. 4: EN 1998-1's period range) */
    double lo, hi;         /* each record's 5 % spectrum within [lo, hi] x target in the band
                            (default 0.9 .. 1.3: US NRC SRP 3.7.1 option 1 approach 2) */
    int iterations;        /* most matching iterations (default 60) */
    double kv;             /* vertical record matched to kv x the horizontal spectrum (0: none) */
    char dir[RD_PATH_MAX]; /* where records (CSV) and runs (HDF5) go; "" = nowhere */
} rd_evidence_def;

typedef struct rd_evidence {
    int n;                             /* records run */
    double ratio_min[RD_EVIDENCE_MAX]; /* least Sa / target in the band, horizontal record */
    double ratio_max[RD_EVIDENCE_MAX]; /* largest */
    int in_band[RD_EVIDENCE_MAX];      /* 1: both components within [lo, hi] */
    double pga[RD_EVIDENCE_MAX];       /* horizontal record's PGA, m/s^2 */
    double tilt[RD_EVIDENCE_MAX];      /* peak tilt, rad */
    double slide[RD_EVIDENCE_MAX];     /* peak slide of the base centre on its pad, m */
    int overturned[RD_EVIDENCE_MAX];
    double tilt_mean, tilt_sd, slide_mean, slide_sd; /* over the records (sample sd) */
} rd_evidence;

RD_API void rd_evidence_defaults(rd_evidence_def *d);

/* Generate d->nrecords Kanai-Tajimi records (stochastic.c), match each to the spectrum h at its
 * damping (records/match.c), run the scene with each (body `body`, index into sc->bodies)
 * and collect the peaks. 0, or -1 with err (a failed run names its record). */
RD_API int rd_assess_evidence(const rd_scenario *sc, int body, const rd_spectrum *h,
                              const rd_evidence_def *d, rd_evidence *out, rd_error *err);

#endif
