/* rockdem — horizontal elastic response spectra for the assessment: EN 1998-1:2004 3.2.2.2
 * (eqs. 3.2-3.5, Tables 3.2 and 3.3, damping correction 3.6) and tabulated user spectra.
 * Folder assess/ owns the seismic assessment of unanchored bodies (spectra, code checks, ASCE
 * 43-05 Appendix A, time-history evidence); it may call base/, records/, scenario/, engine/
 * and io/.
 */
#include "rockdem/assess.h"
#include "rockdem/record.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* EN 1998-1 (3.6): eta >= 0.55; xi in percent. */
#define EN_ETA_MIN 0.55
/* Plateau amplification of the horizontal elastic spectrum, EN 1998-1 (3.3). */
#define EN_PLATEAU 2.5

/* S, TB, TC, TD (s) for ground types A..E: EN 1998-1 Table 3.2 (type 1) and 3.3 (type 2). */
static const double en_table[2][5][4] = {
    { { 1.00, 0.15, 0.4, 2.0 },
      { 1.20, 0.15, 0.5, 2.0 },
      { 1.15, 0.20, 0.6, 2.0 },
      { 1.35, 0.20, 0.8, 2.0 },
      { 1.40, 0.15, 0.5, 2.0 } },
    { { 1.00, 0.05, 0.25, 1.2 },
      { 1.35, 0.05, 0.25, 1.2 },
      { 1.50, 0.10, 0.25, 1.2 },
      { 1.80, 0.10, 0.30, 1.2 },
      { 1.60, 0.05, 0.25, 1.2 } },
};

int rd_spectrum_en1998(rd_spectrum *s, int type, char ground, double ag, rd_error *err)
{
    int g = toupper((unsigned char)ground) - 'A';
    if (type != 1 && type != 2)
        return rd_error_set(err, "EN 1998 spectrum: type %d, expected 1 or 2", type);
    if (g < 0 || g > 4)
        return rd_error_set(err, "EN 1998 spectrum: ground type '%c', expected A, B, C, D or E",
                            ground);
    if (!(ag > 0) || !isfinite(ag))
        return rd_error_set(err, "EN 1998 spectrum: a_g %g m/s^2 must be positive", ag);
    memset(s, 0, sizeof *s);
    s->kind = RD_SPECTRUM_EN1998;
    s->type = type;
    s->ground = (char)('A' + g);
    s->ag = ag;
    s->S = en_table[type - 1][g][0];
    s->TB = en_table[type - 1][g][1];
    s->TC = en_table[type - 1][g][2];
    s->TD = en_table[type - 1][g][3];
    s->damping = 0.05;
    s->scale = 1.0;
    return 0;
}

int rd_spectrum_table(rd_spectrum *s, const double *T, const double *sa, int n, double damping,
                      rd_error *err)
{
    if (n < 2 || n > RD_SPECTRUM_MAX)
        return rd_error_set(err, "spectrum table: %d points, expected 2 to %d", n, RD_SPECTRUM_MAX);
    if (T[0] != 0.0)
        return rd_error_set(
            err, "spectrum table: the first period is %g s, expected 0 (its Sa is the PGA)", T[0]);
    for (int i = 0; i < n; i++) {
        if (i > 0 && !(T[i] > T[i - 1]))
            return rd_error_set(err, "spectrum table: period %g s at point %d does not increase",
                                T[i], i + 1);
        if (!(sa[i] > 0) || !isfinite(sa[i]) || !isfinite(T[i]))
            return rd_error_set(err, "spectrum table: Sa %g at point %d must be positive", sa[i],
                                i + 1);
    }
    if (!(damping > 0 && damping < 1))
        return rd_error_set(err, "spectrum table: damping %g must be a ratio in (0, 1)", damping);
    memset(s, 0, sizeof *s);
    s->kind = RD_SPECTRUM_TABLE;
    s->n = n;
    memcpy(s->T, T, (size_t)n * sizeof *T);
    memcpy(s->sa, sa, (size_t)n * sizeof *sa);
    s->damping = damping;
    s->scale = 1.0;
    return 0;
}

/* Next number of a table line (blanks or commas between), or -1 at the end, -2 on junk. */
static int next_number(char **p, double *v)
{
    while (**p == ' ' || **p == '\t' || **p == ',' || **p == ';' || **p == '\r' || **p == '\n')
        (*p)++;
    if (!**p) return -1;
    char *end;
    errno = 0;
    *v = strtod(*p, &end);
    if (end == *p || errno || !isfinite(*v) || strpbrk(*p, "xXpP") == *p + 1) return -2;
    *p = end;
    return 0;
}

int rd_spectrum_read(rd_spectrum *s, const char *path, double damping, rd_error *err)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return rd_error_set(err, "%s: cannot open the spectrum table: %s", path, strerror(errno));
    double T[RD_SPECTRUM_MAX], sa[RD_SPECTRUM_MAX];
    char line[512];
    int n = 0, lineno = 0, rc = 0;
    while (rc == 0 && fgets(line, sizeof line, f)) {
        lineno++;
        char *p = strchr(line, '#');
        if (p) *p = 0;
        p = line;
        double v[3];
        int k = 0, got;
        while (k < 3 && (got = next_number(&p, &v[k])) == 0) k++;
        if (k == 0 && got == -1) continue;
        if (got == -2 || k != 2 || next_number(&p, &v[2]) != -1)
            rc = rd_error_set(err, "%s:%d: expected two numbers, period (s) and Sa (g)", path,
                              lineno);
        else if (n == RD_SPECTRUM_MAX)
            rc = rd_error_set(err, "%s:%d: more than %d points", path, lineno, RD_SPECTRUM_MAX);
        else if (n > 0 && !(v[0] > T[n - 1]))
            rc = rd_error_set(err, "%s:%d: period %g s does not increase", path, lineno, v[0]);
        else if (!(v[1] > 0))
            rc = rd_error_set(err, "%s:%d: Sa %g g must be positive", path, lineno, v[1]);
        else if (n == 0 && v[0] != 0.0)
            rc =
                rd_error_set(err, "%s:%d: the first period is %g s, expected 0 (its Sa is the PGA)",
                             path, lineno, v[0]);
        else {
            T[n] = v[0];
            sa[n++] = v[1] * RD_G_STANDARD;
        }
    }
    fclose(f);
    if (rc) return rc;
    if (n < 2)
        return rd_error_set(err, "%s: %d points, a spectrum table needs at least 2", path, n);
    if (rd_spectrum_table(s, T, sa, n, damping, err)) {
        char msg[RD_ERROR_MAX];
        snprintf(msg, sizeof msg, "%s", err->msg);
        return rd_error_set(err, "%s: %s", path, msg);
    }
    return 0;
}

double rd_spectrum_eta(double zeta) { return fmax(sqrt(10.0 / (5.0 + 100.0 * zeta)), EN_ETA_MIN); }

/* EN 1998-1 eqs. (3.2)-(3.5) at period T with correction eta. */
static double en_sa(const rd_spectrum *s, double T, double eta)
{
    double a = s->ag * s->S;
    if (T <= s->TB) return a * (1.0 + T / s->TB * (EN_PLATEAU * eta - 1.0));
    if (T <= s->TC) return a * eta * EN_PLATEAU;
    if (T <= s->TD) return a * eta * EN_PLATEAU * s->TC / T;
    return a * eta * EN_PLATEAU * s->TC * s->TD / (T * T);
}

/* Table at period T, its own damping: linear in T; constant displacement past the end. */
static double table_sa(const rd_spectrum *s, double T)
{
    int n = s->n;
    if (T >= s->T[n - 1]) return s->sa[n - 1] * (s->T[n - 1] / T) * (s->T[n - 1] / T);
    int i = 1;
    while (s->T[i] < T) i++;
    double u = (T - s->T[i - 1]) / (s->T[i] - s->T[i - 1]);
    return s->sa[i - 1] + u * (s->sa[i] - s->sa[i - 1]);
}

double rd_spectrum_sa(const rd_spectrum *s, double T, double zeta)
{
    if (s->kind == RD_SPECTRUM_EN1998) return s->scale * en_sa(s, T, rd_spectrum_eta(zeta));
    if (T <= 0.0) return s->scale * s->sa[0];
    /* EN's branches are all proportional to eta from TB on and its (3.2) blends linearly from
       1 at T = 0: the table's correction does the same over its first interval */
    double ratio = rd_spectrum_eta(zeta) / rd_spectrum_eta(s->damping);
    double u = fmin(T / s->T[1], 1.0);
    return s->scale * table_sa(s, T) * (1.0 + u * (ratio - 1.0));
}

double rd_spectrum_pga(const rd_spectrum *s) { return rd_spectrum_sa(s, 0.0, s->damping); }
