/* rockdem — acceleration records: the PEER .AT2 and text/CSV readers (the record itself is
 * allocated and processed by record_process.c, which calls nothing here).
 *
 * Readers report malformed input as "file:line: message" and leave the record zeroed on
 * failure. Values are converted to m/s^2 and integrated (rd_record_integrate) on success.
 *
 * Folder records/ owns ground motions (records, readers, stochastic generation, intensity
 * measures, SDOF); it may call base/ only.
 */
#include "records/record_limits.h"
#include "base/path.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define SEPARATORS " \t\r\n,;"
/* Two-column files: each time step may differ from the first by this fraction (times are
 * printed with a few digits; a real change of step is far larger). */
#define STEP_TOL   1e-3

/* --- helpers shared by both readers ------------------------------------------------------ */

/* A growable array of doubles. */
typedef struct values {
    double *v;
    size_t n, cap;
} values;

static int values_push(values *a, double x)
{
    if (a->n == a->cap) {
        size_t cap = a->cap ? 2 * a->cap : 1024;
        double *v = realloc(a->v, cap * sizeof *v);
        if (!v) return -1;
        a->v = v;
        a->cap = cap;
    }
    a->v[a->n++] = x;
    return 0;
}

/* A file being read line by line, with its name and the current line number for messages. */
typedef struct reader {
    const char *path;
    FILE *f;
    char *line;
    size_t cap;
    long lineno;
    int read_errno; /* a read failed (errno), 0 otherwise */
} reader;

static int reader_open(reader *rd, const char *path, rd_error *err)
{
    memset(rd, 0, sizeof *rd);
    rd->path = path;
    if (rd_path_special(path)) return rd_error_set(err, "%s: %s", path, RD_PATH_INPUT_NOT_FILE);
    rd->f = fopen(path, "r");
    if (!rd->f) return rd_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    return 0;
}

/* Next line (without its end-of-line characters), or NULL at the end of the file or on a read
 * error (rd->read_errno then holds the system's reason). */
static char *reader_next(reader *rd)
{
    errno = 0;
    ssize_t len = getline(&rd->line, &rd->cap, rd->f);
    if (len < 0) {
        if (ferror(rd->f)) rd->read_errno = errno ? errno : EIO;
        return NULL;
    }
    rd->lineno++;
    while (len > 0 && (rd->line[len - 1] == '\n' || rd->line[len - 1] == '\r'))
        rd->line[--len] = '\0';
    return rd->line;
}

/* A read error ends the file early: report it rather than what the truncated text looks like. */
static int reader_check(const reader *rd, rd_error *err)
{
    if (!rd->read_errno) return 0;
    return rd_error_set(err, "%s:%ld: read error: %s", rd->path, rd->lineno + 1,
                        strerror(rd->read_errno));
}

static void reader_close(reader *rd)
{
    if (rd->f) fclose(rd->f);
    free(rd->line);
}

/* "file:line: message" at the reader's current line. */
static int reader_fail(const reader *rd, rd_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int reader_fail(const reader *rd, rd_error *err, const char *fmt, ...)
{
    char msg[RD_ERROR_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return rd_error_set(err, "%s:%ld: %s", rd->path, rd->lineno, msg);
}

/* Parse a whole token as a finite number. */
static int parse_number(const char *tok, double *x)
{
    char *end;
    errno = 0;
    *x = strtod(tok, &end);
    return (end != tok && *end == '\0' && errno != ERANGE && isfinite(*x)) ? 0 : -1;
}

/* Record name: the file name without directories. */
static void set_name(rd_record *r, const char *path)
{
    const char *slash = strrchr(path, '/');
    snprintf(r->name, sizeof r->name, "%s", slash ? slash + 1 : path);
}

/* Move the samples into r (step dt), multiplied by scale (m/s^2 per unit of the values) and
 * integrated. */
static int finish(rd_record *r, const values *acc, double dt, double scale, const char *path,
                  rd_error *err)
{
    char source[RD_PATH_MAX];
    snprintf(source, sizeof source, "%s", r->source);
    rd_error alloc_err;
    if (rd_record_alloc(r, acc->n, dt, &alloc_err))
        return rd_error_set(err, "%s: %s", path, alloc_err.msg);
    memcpy(r->acc, acc->v, acc->n * sizeof *acc->v);
    memcpy(r->source, source, sizeof source);
    set_name(r, path);
    rd_record_scale(r, scale);
    rd_record_integrate(r);
    return 0;
}

/* --- PEER .AT2 ------------------------------------------------------------------------------ */

/* Case-insensitive search for `key` in s; NULL when absent. */
static const char *find_key(const char *s, const char *key)
{
    size_t n = strlen(key);
    for (; *s; s++)
        if (strncasecmp(s, key, n) == 0) return s;
    return NULL;
}

/* Where the value after "key=" starts (blanks allowed around '='); NULL without "key=". */
static const char *keyed_value(const char *line, const char *key)
{
    const char *p = find_key(line, key);
    if (!p) return NULL;
    p += strlen(key);
    while (isspace((unsigned char)*p)) p++;
    return *p == '=' ? p + 1 : NULL;
}

/* The header number at p into *x, *end after it: 0; -1 when p holds no number; -2 when it runs
 * on into other characters ("200x", ".0100x"; a number ends at a blank, ',' or the line's end),
 * with the whole token reported as "file:line: ...". */
static int header_number(const reader *rd, const char *p, const char *what, double *x,
                         const char **end, rd_error *err)
{
    char *e;
    *x = strtod(p, &e);
    *end = e;
    if (e == p) return -1;
    if (*e == '\0' || isspace((unsigned char)*e) || *e == ',') return 0;
    p += strspn(p, " \t");
    reader_fail(rd, err, "%s '%.*s' is not a number", what, (int)strcspn(p, " \t,"), p);
    return -2;
}

/* NPTS and DT from the 4th header line in either NGA-West2 form: 0, -1 when absent, -2 when one
 * is malformed (err filled). */
static int parse_npts_dt(const reader *rd, const char *line, double *npts, double *dt,
                         rd_error *err)
{
    const char *pn = keyed_value(line, "NPTS"), *pd = keyed_value(line, "DT"), *end1, *end2;
    int rc;
    if (pn && pd) {
        if ((rc = header_number(rd, pn, "NPTS", npts, &end1, err)) == -2) return rc;
        int rc_dt = header_number(rd, pd, "DT", dt, &end2, err);
        if (rc_dt == -2 || (rc == 0 && rc_dt == 0)) return rc_dt;
    }
    if ((rc = header_number(rd, line, "NPTS", npts, &end1, err)) ||
        (rc = header_number(rd, end1, "DT", dt, &end2, err)))
        return rc;
    return find_key(end2, "NPTS") ? 0 : -1;
}

/* The unit words a PEER header writes after "UNITS OF" (case-insensitive), and m/s^2 per unit.
 * NGA-West2 writes "ACCELERATION TIME SERIES IN UNITS OF G"; older PEER and converted files
 * write cm/s^2 and m/s^2 in several spellings. */
static const struct at2_unit {
    const char *word;
    double si;
} at2_units[] = {
    { "G", RD_G_STANDARD }, { "CM/SEC/SEC", 0.01 }, { "CM/S/S", 0.01 }, { "CM/SEC^2", 0.01 },
    { "CM/SEC2", 0.01 },    { "CM/S^2", 0.01 },     { "CM/S2", 0.01 },  { "GAL", 0.01 },
    { "M/SEC/SEC", 1.0 },   { "M/S/S", 1.0 },       { "M/SEC^2", 1.0 }, { "M/SEC2", 1.0 },
    { "M/S^2", 1.0 },       { "M/S2", 1.0 },
};

/* What header line `line` (number k) says of the file's quantity and units: -1 (err filled) for a
 * velocity or displacement file, or for units it names but rockdem does not know; else 0, with
 * *si set to m/s^2 per unit when the line says "UNITS OF <unit>" (left as is otherwise). */
static int at2_header_units(const reader *rd, const char *line, int k, double *si, rd_error *err)
{
    static const char *const quantity[] = { "VELOCITY", "DISPLACEMENT" };
    for (int q = 0; q < 2; q++)
        if (find_key(line, quantity[q]))
            return rd_error_set(
                err,
                "%s:%d: a PEER %s file (its header says \"%s\"): rockdem reads "
                "acceleration records; give the matching acceleration file (.AT2 whose "
                "header says ACCELERATION)",
                rd->path, k, quantity[q], line);
    const char *p = find_key(line, "UNITS OF");
    if (!p) return 0;
    p += strlen("UNITS OF");
    p += strspn(p, " \t");
    size_t n = strcspn(p, " \t,.;");
    for (size_t u = 0; u < sizeof at2_units / sizeof at2_units[0]; u++)
        if (strlen(at2_units[u].word) == n && !strncasecmp(p, at2_units[u].word, n)) {
            *si = at2_units[u].si;
            return 0;
        }
    return rd_error_set(
        err, "%s:%d: unknown units '%.*s' in the header (expected G, CM/SEC/SEC or M/SEC/SEC)",
        rd->path, k, (int)n, p);
}

/* Header (4 lines): keeps the event line in r->source, returns NPTS, DT and the values' units
 * (m/s^2 per unit: g unless a line says "UNITS OF ..."); refuses velocity and displacement files. */
static int read_at2_header(reader *rd, rd_record *r, size_t *npts, double *dt, double *si,
                           rd_error *err)
{
    char *line = NULL;
    *si = RD_G_STANDARD;
    for (int k = 1; k <= 4; k++) {
        line = reader_next(rd);
        if (!line && k == 1)
            return rd_error_set(err, "%s: empty file: expected 4 header lines and the values",
                                rd->path);
        if (!line)
            return reader_fail(rd, err,
                               "file ends in the header: expected 4 header lines, found %d", k - 1);
        if (k == 2) snprintf(r->source, sizeof r->source, "%s", line);
        if (k != 2 && k < 4 && at2_header_units(rd, line, k, si, err)) return -1;
    }
    double n;
    int rc = parse_npts_dt(rd, line, &n, dt, err);
    if (rc == -2) return -1;
    if (rc)
        return reader_fail(
            rd, err,
            "missing NPTS and DT: expected \"NPTS= <n>, DT= <s> SEC\" or \"<n> <s> NPTS, DT\", "
            "found \"%s\"",
            line);
    if (!(n >= 1.0) || n != floor(n) || n > RD_RECORD_NPTS_MAX)
        return reader_fail(rd, err, "NPTS must be a whole number in [1, %g], found %g",
                           RD_RECORD_NPTS_MAX, n);
    if (!(*dt >= RD_RECORD_DT_MIN && *dt <= RD_RECORD_DT_MAX))
        return reader_fail(rd, err, "DT must be in [%g, %g] s, found %g s", RD_RECORD_DT_MIN,
                           RD_RECORD_DT_MAX, *dt);
    *npts = (size_t)n;
    return 0;
}

/* Every value after the header, in the header's units (si m/s^2 each); checks the count
 * against NPTS. */
static int read_at2_values(reader *rd, size_t npts, double si, values *acc, rd_error *err)
{
    long surplus_line = 0;
    char *line, *save;
    while ((line = reader_next(rd))) {
        for (char *tok = strtok_r(line, SEPARATORS, &save); tok;
             tok = strtok_r(NULL, SEPARATORS, &save)) {
            double x;
            char why[128];
            if (parse_number(tok, &x)) return reader_fail(rd, err, "non-numeric value '%s'", tok);
            if (rd_record_sample_error(x, si, why, sizeof why))
                return reader_fail(rd, err, "acceleration '%s' %s %s", tok,
                                   si == RD_G_STANDARD ? "g"
                                   : si == 1.0         ? "m/s^2"
                                                       : "cm/s^2",
                                   why);
            if (values_push(acc, x)) return reader_fail(rd, err, "out of memory");
            if (acc->n == npts + 1) surplus_line = rd->lineno;
        }
    }
    if (acc->n != npts) {
        if (surplus_line) rd->lineno = surplus_line;
        return reader_fail(rd, err, "expected %zu values (NPTS), found %zu", npts, acc->n);
    }
    return 0;
}

int rd_record_read_at2(rd_record *r, const char *path, rd_error *err)
{
    reader rd;
    values acc = { 0 };
    size_t npts = 0;
    double dt = 0.0, si = RD_G_STANDARD;
    memset(r, 0, sizeof *r);
    if (reader_open(&rd, path, err)) return -1;
    int status = read_at2_header(&rd, r, &npts, &dt, &si, err);
    if (status == 0) status = read_at2_values(&rd, npts, si, &acc, err);
    if (rd.read_errno) status = reader_check(&rd, err);
    if (status == 0) status = finish(r, &acc, dt, si, path, err);
    reader_close(&rd);
    free(acc.v);
    if (status) memset(r, 0, sizeof *r);
    return status;
}

/* --- one- and two-column text -------------------------------------------------------------- */

/* State of a text read: columns seen, samples, time-step checks. */
typedef struct text_state {
    int ncol;            /* columns in the data (0 until the first data line) */
    long first_line;     /* line of the first data row */
    values t, acc;       /* time (two-column files) and acceleration */
    double step;         /* first time step, s (two-column files) */
    double unit;         /* m/s^2 per unit of the acceleration column (its samples' check) */
    int header_possible; /* the next content line may be a header */
    long header_line;    /* the line taken as a header (0: none) */
    int header_fields;   /* its fields, and whether all but the first are numbers */
    int header_numeric;
    char header_first[32]; /* its first field (for the message when it was a data row) */
} text_state;

/* Time column: steps must be positive and uniform. */
static int check_time(const reader *rd, text_state *st, double t, rd_error *err)
{
    if (st->t.n == 0) return 0;
    double prev = st->t.v[st->t.n - 1], h = t - prev;
    if (!(h > 0.0))
        return reader_fail(
            rd, err, "time %g s does not increase after %g s (time step %g s must be positive)", t,
            prev, h);
    if (st->t.n == 1)
        st->step = h;
    else if (fabs(h - st->step) > STEP_TOL * st->step)
        return reader_fail(rd, err,
                           "non-uniform time step: %g s here, %g s at the start (line %ld)", h,
                           st->step, st->first_line + 1);
    return 0;
}

/* One data row already split into numbers; acc is the acceleration's token. */
static int text_row(const reader *rd, text_state *st, const double *x, int n, const char *acc,
                    rd_error *err)
{
    char why[128];
    if (n > 2)
        return reader_fail(rd, err, "expected 1 or 2 columns (time, acceleration), found %d", n);
    if (st->ncol == 0 && st->header_numeric && st->header_fields == n)
        return rd_error_set(
            err, "%s:%ld: non-numeric value '%s' (a row of %d fields like line %ld, not a header)",
            rd->path, st->header_line, st->header_first, n, rd->lineno);
    if (st->ncol == 0) {
        st->ncol = n;
        st->first_line = rd->lineno;
    } else if (n != st->ncol) {
        return reader_fail(rd, err, "expected %d column%s as on line %ld, found %d", st->ncol,
                           st->ncol == 1 ? "" : "s", st->first_line, n);
    }
    if (rd_record_sample_error(x[n - 1], st->unit, why, sizeof why))
        return reader_fail(rd, err, "acceleration '%s' %s", acc, why);
    if (n == 2 && check_time(rd, st, x[0], err)) return -1;
    if ((n == 2 && values_push(&st->t, x[0])) || values_push(&st->acc, x[n - 1]))
        return reader_fail(rd, err, "out of memory");
    return 0;
}

/* A field that starts like a number (a digit, or a sign or '.' before one) is a mistyped
 * value ("0.1x"), never a header's first word. */
static int starts_like_number(const char *tok)
{
    tok += *tok == '+' || *tok == '-';
    tok += *tok == '.';
    return isdigit((unsigned char)*tok);
}

/* Keeps the first content line as a header whose first field is `first`; the rest of its
 * fields are counted, and if they are all numbers, a first data row with as many fields shows
 * that the line was a row with one bad value ("O 0.2"), refused by text_row. */
static void text_header(const reader *rd, text_state *st, const char *first, char **save)
{
    st->header_line = rd->lineno;
    st->header_fields = 1;
    st->header_numeric = 1;
    snprintf(st->header_first, sizeof st->header_first, "%s", first);
    for (char *tok = strtok_r(NULL, SEPARATORS, save); tok;
         tok = strtok_r(NULL, SEPARATORS, save)) {
        double v;
        st->header_fields++;
        st->header_numeric &= parse_number(tok, &v) == 0;
    }
    st->header_numeric &= st->header_fields > 1;
}

/* Split a content line; on the first content line, a first field that is no number and does
 * not start like one is a header. */
static int text_line(const reader *rd, text_state *st, char *line, rd_error *err)
{
    double x[3];
    int n = 0;
    char *save;
    const char *acc = NULL;
    int header = st->header_possible;
    st->header_possible = 0;
    for (char *tok = strtok_r(line, SEPARATORS, &save); tok;
         tok = strtok_r(NULL, SEPARATORS, &save), n++) {
        double v;
        if (parse_number(tok, &v)) {
            if (header && n == 0 && !starts_like_number(tok)) {
                text_header(rd, st, tok, &save);
                return 0;
            }
            return reader_fail(rd, err, "non-numeric value '%s'", tok);
        }
        if (n < 3) x[n] = v;
        acc = tok;
    }
    return text_row(rd, st, x, n, acc, err);
}

static int is_content(const char *line)
{
    line += strspn(line, SEPARATORS);
    return *line != '\0' && *line != '#';
}

/* Step of the samples: from the time column, or the given dt for one column. */
static int text_step(const reader *rd, const text_state *st, double dt, double *step, rd_error *err)
{
    if (st->acc.n == 0)
        return rd_error_set(err, "%s: no data (%ld line%s, none with numbers)", rd->path,
                            rd->lineno, rd->lineno == 1 ? "" : "s");
    if (st->ncol == 1) {
        if (!(dt > 0.0) || !isfinite(dt))
            return rd_error_set(
                err, "%s:%ld: one column of accelerations needs a time step dt > 0, got %g s",
                rd->path, st->first_line, dt);
        *step = dt;
    }
    if (st->t.n < 2 && !(dt > 0.0))
        return rd_error_set(err, "%s:%ld: one sample cannot define a time step", rd->path,
                            st->first_line);
    *step = st->t.n < 2 ? dt : (st->t.v[st->t.n - 1] - st->t.v[0]) / (double)(st->t.n - 1);
    if (dt > 0.0 && fabs(*step - dt) > STEP_TOL * dt)
        return rd_error_set(err, "%s:%ld: time step %g s in the file, %g s given", rd->path,
                            st->first_line, *step, dt);
    char why[128];
    if (rd_record_step_error(*step, why, sizeof why))
        return rd_error_set(err, "%s:%ld: %s", rd->path, st->first_line, why);
    return 0;
}

/* rd_record_read_text with the values scaled by `scale` into m/s^2 and checked as multiples of
 * `unit` m/s^2. */
static int read_text(rd_record *r, const char *path, double scale, double unit, double dt,
                     rd_error *err)
{
    reader rd;
    text_state st;
    memset(&st, 0, sizeof st);
    st.header_possible = 1;
    st.unit = unit;
    memset(r, 0, sizeof *r);
    if (reader_open(&rd, path, err)) return -1;
    int status = 0;
    char *line;
    while (status == 0 && (line = reader_next(&rd)))
        if (is_content(line)) status = text_line(&rd, &st, line, err);
    if (rd.read_errno) status = reader_check(&rd, err);
    double step = 0.0;
    if (status == 0) status = text_step(&rd, &st, dt, &step, err);
    if (status == 0) {
        snprintf(r->source, sizeof r->source, "%s", path);
        status = finish(r, &st.acc, step, scale, path, err);
    }
    reader_close(&rd);
    free(st.t.v);
    free(st.acc.v);
    if (status) memset(r, 0, sizeof *r);
    return status;
}

int rd_record_read_text(rd_record *r, const char *path, rd_accel_unit unit, double dt,
                        rd_error *err)
{
    double f = rd_accel_unit_factor(unit);
    return read_text(r, path, f, f, dt, err);
}

int rd_record_read_text_as(rd_record *r, const char *path, double unit, double dt, rd_error *err)
{
    return read_text(r, path, 1.0, unit, dt, err);
}
