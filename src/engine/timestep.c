/* rockdem — the critical time step of the explicit scheme.
 *
 * For springs k_p acting at points r_p of rigid bodies, the largest eigenvalue of M^-1 K is at
 * most sum_p k_p * mobility_p, where a point's mobility on body i is at most
 * G_i = 1/m_i + r_i^2 / I_min,i (translation plus rotation about the stiffest-to-turn axis;
 * r_i = distance of the farthest vertex). Per body, its own subcontacts all closed at once bound
 * w_max^2; dt_crit = 2 / w_max, reduced by sqrt(1 + l^2) - l for a normal dashpot of damping
 * ratio l. A body's own points cover its joints (weight 1 on pedestals; two half-weight sets on
 * a shared face), so the bound holds as contacts come and go. Each body takes the stiffest joint
 * it can form with any other body (joint.c: per-range contact properties).
 *
 * Per pair: a spring between bodies i and j moves both, so body i's bound is
 * k (A_i G_i + sum_j A_ij G_j), A_ij the part of i's bearing area A_i that bears on j. A_ij is at
 * most j's own bearing area A_j (the points of i inside convex j lie on the contact patch, which
 * j presses with), and sum_j A_ij <= A_i. Which bodies i meets is not known in advance, so A_i
 * goes to the most mobile other bodies first, each up to its A_j, the rest to fixed bodies
 * (G = 0). With one mobility for every partner (the most mobile other body's, as before), a 2 m
 * cube under a 5 cm cube took the small cube's mobility over its whole 4 m^2 bed: a step 46x
 * shorter than the small cube's own; now the small cube's 25 cm^2 only.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static double mobility(const rd_sim *s, int i)
{
    if (s->fixed[i]) return 0.0;
    double imin = fmin(s->inertia[i][0], fmin(s->inertia[i][1], s->inertia[i][2]));
    double r = s->poly[i].radius;
    return 1.0 / s->mass[i] + r * r / imin;
}

/* Body i's bearing area, m^2: its own subcontacts at full weight (where two free bodies meet,
 * the two half-weight sets together carry about the shared area): every bed face at once, or,
 * once it has toppled, the largest face that touches only later with the edge it shares with a
 * bed face (at most half of that face's points). */
static double bearing_area(const rd_sim *s, int i)
{
    if (s->surf) return rd_surface_contact_area(s, i); /* the surface model's own bound */
    double bed = 0, bed_max = 0, late = 0;
    for (int c = s->cf0[i]; c < s->cf0[i + 1]; c++) {
        double a = 0;
        for (int j = s->cf_pt0[c]; j < s->cf_pt0[c + 1]; j++) a += s->pa[j];
        if (s->cf_facing[c])
            late = fmax(late, a);
        else {
            bed += a;
            bed_max = fmax(bed_max, a);
        }
    }
    return fmax(bed, late + 0.5 * bed_max);
}

/* The free bodies that carry points, most mobile first, with prefix sums of their bearing
 * areas (area[k] = sum of the first k) and of area times mobility (ag[k]). */
typedef struct partners {
    int n;
    int *body;         /* [n] */
    double *g, *a;     /* [n] mobility, bearing area */
    double *area, *ag; /* [n + 1] prefix sums */
    int *rank;         /* [nb] position of a body in the list, or -1 */
} partners;

static const double *sort_g; /* qsort has no context argument: the mobilities it sorts by */

static int by_mobility(const void *x, const void *y)
{
    double a = sort_g[*(const int *)x], b = sort_g[*(const int *)y];
    return (a < b) - (a > b);
}

static int partners_make(const rd_sim *s, partners *p, double *g_all)
{
    p->body = malloc((size_t)(s->nb > 0 ? s->nb : 1) * sizeof *p->body);
    p->rank = malloc((size_t)(s->nb > 0 ? s->nb : 1) * sizeof *p->rank);
    p->g = malloc((size_t)(s->nb + 1) * sizeof *p->g);
    p->a = malloc((size_t)(s->nb + 1) * sizeof *p->a);
    p->area = malloc((size_t)(s->nb + 1) * sizeof *p->area);
    p->ag = malloc((size_t)(s->nb + 1) * sizeof *p->ag);
    if (!p->body || !p->rank || !p->g || !p->a || !p->area || !p->ag) return -1;
    p->n = 0;
    for (int j = 0; j < s->nb; j++) {
        p->rank[j] = -1;
        g_all[j] = mobility(s, j);
        if (s->pt0[j + 1] > s->pt0[j] && g_all[j] > 0) p->body[p->n++] = j;
    }
    sort_g = g_all;
    qsort(p->body, (size_t)p->n, sizeof *p->body, by_mobility);
    p->area[0] = p->ag[0] = 0;
    for (int k = 0; k < p->n; k++) {
        int j = p->body[k];
        p->rank[j] = k;
        p->g[k] = g_all[j];
        p->a[k] = bearing_area(s, j);
        p->area[k + 1] = p->area[k] + p->a[k];
        p->ag[k + 1] = p->ag[k] + p->a[k] * p->g[k];
    }
    return 0;
}

static void partners_free(partners *p)
{
    free(p->body);
    free(p->rank);
    free(p->g);
    free(p->a);
    free(p->area);
    free(p->ag);
}

/* Sums over the first k partners with body i left out (skip: i's place, or -1): their bearing
 * area and area times mobility. */
static void first_k(const partners *p, int skip, int k, double *area, double *ag)
{
    if (skip < 0 || k <= skip) {
        *area = p->area[k];
        *ag = p->ag[k];
        return;
    }
    *area = p->area[k + 1] - p->a[skip];
    *ag = p->ag[k + 1] - p->a[skip] * p->g[skip];
}

/* The k-th partner (0-based) with i left out. */
static int kth(int skip, int k) { return skip >= 0 && k >= skip ? k + 1 : k; }

/* The mean mobility of the bodies body i (bearing area a > 0) bears on, sum_j A_ij G_j / a: a
 * spread over the most mobile other bodies, each up to its own bearing area (a binary search on
 * the prefix sums), the rest on fixed bodies (G = 0). Where the most mobile one takes all of a
 * (bodies of one size), it is that body's mobility itself, as the bound had it before pairs.
 * *first: the most mobile other body, -1 when there is none. */
static double partner_mobility(const partners *p, int i, double a, int *first)
{
    int skip = p->rank[i], n = p->n - (skip >= 0);
    double area, ag;
    *first = n > 0 && a > 0 ? p->body[kth(skip, 0)] : -1;
    if (*first < 0) return 0.0;
    if (p->a[kth(skip, 0)] >= a) return p->g[kth(skip, 0)];
    first_k(p, skip, n, &area, &ag);
    if (area < a) return ag / a; /* every partner full, the rest on fixed bodies */
    int lo = 1, hi = n;          /* the least k whose first k take a */
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        first_k(p, skip, mid, &area, &ag);
        if (area >= a)
            hi = mid;
        else
            lo = mid + 1;
    }
    first_k(p, skip, lo - 1, &area, &ag);
    return (ag + (a - area) * p->g[kth(skip, lo - 1)]) / a;
}

double rd_timestep_critical(const rd_sim *s, int pair[2])
{
    double w2max = 0, lmax = 0;
    pair[0] = pair[1] = -1;
    partners p = { 0 };
    double *g = malloc((size_t)(s->nb > 0 ? s->nb : 1) * sizeof *g);
    if (!g || partners_make(s, &p, g)) {
        partners_free(&p);
        free(g);
        return NAN; /* out of memory */
    }
    for (int i = 0; i < s->nb; i++) {
        if (s->fixed[i]) continue;
        double k, zeta; /* the stiffest joint body i can form, and its largest dashpot ratio */
        rd_joint_body_limits(s, i, &k, &zeta);
        double area = bearing_area(s, i);
        int partner;
        double w2 = k * area * (g[i] + partner_mobility(&p, i, area, &partner));
        if (w2 > w2max) {
            w2max = w2;
            pair[0] = i;
            pair[1] = partner;
        }
        double l = zeta * sqrt(s->mass[i] * g[i]);
        if (l > lmax && !s->surf) lmax = l; /* the surface model's dashpot is implicit */
    }
    partners_free(&p);
    free(g);
    if (w2max <= 0) return INFINITY;
    return 2.0 / sqrt(w2max) * (sqrt(1.0 + lmax * lmax) - lmax);
}

void rd_timestep_pair_text(const rd_sim *s, char *buf, size_t n)
{
    int i = s->dt_pair[0], j = s->dt_pair[1];
    if (i < 0)
        snprintf(buf, n, "%s", "");
    else if (j < 0)
        snprintf(buf, n, " set by block '%s' bearing on fixed bodies", s->sc.bodies[i].name);
    else
        snprintf(buf, n, " set by block '%s' bearing on '%s'", s->sc.bodies[i].name,
                 s->sc.bodies[j].name);
}
