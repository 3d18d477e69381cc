/* rockdem — the scenario parser: a 3DEC-flavoured command language into rd_scenario.
 *
 * One command per line, `noun verb keyword value ...`, keywords in any order after the verb
 * (case-insensitive); `;` starts a comment; a `&` as the last token of a line continues the
 * command on the next line; strings in single or double quotes. Angles in the file are degrees,
 * accelerations may carry a `g` suffix (times standard gravity); everything stored is SI.
 * Every error is one line "file:line:col: message" pointing at the offending token.
 */
#include "rockdem/scenario.h"
#include "rockdem/motion.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#if defined(__GNUC__)
#define RD_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define RD_PRINTF(f, a)
#endif

#define MAX_TOKENS 1024 /* tokens in one command, continuation lines included */

static const double DEG = 3.14159265358979323846 / 180.0; /* rad per degree */
static const double G0 = 9.80665;                         /* standard gravity, m/s^2 */

/* ---- values: numbers, ranges, units (shared by the parser and rd_scenario_set) ---- */

typedef enum range {
    R_ANY,    /* any finite number */
    R_POS,    /* > 0 */
    R_NONNEG, /* >= 0 */
    R_FRAC,   /* (0, 1] */
    R_DAMP,   /* (0, 10]: a viscous damping ratio (above 1: over-critical contact dashpots) */
    R_OPEN01, /* (0, 1) */
    R_ANGLE,  /* [0, 90) degrees */
    R_TURN    /* (0, 180] degrees */
} range;

typedef enum unit {
    U_PLAIN, /* stored as written */
    U_DEG,   /* written in degrees, stored in rad */
    U_ACCEL  /* m/s^2, or a number with a `g` suffix times G0 */
} unit;

/* Parses s[0..len) as a C floating-point number; with accel a trailing 'g' multiplies by G0.
 * Returns 0, or -1 when it is not a whole finite number. */
static int parse_number(const char *s, size_t len, int accel, double *v)
{
    char buf[64], *end;
    if (len == 0 || len >= sizeof buf || isspace((unsigned char)s[0]))
        return -1;
    memcpy(buf, s, len);
    buf[len] = '\0';
    double x = strtod(buf, &end);
    if (end == buf)
        return -1;
    if (accel && end[0] == 'g' && end[1] == '\0') {
        x *= G0;
        end++;
    }
    if (*end != '\0' || !isfinite(x))
        return -1;
    *v = x;
    return 0;
}

/* NULL when v (as written: degrees for angles) lies in r, else what it must be. */
static const char *range_error(double v, range r)
{
    switch (r) {
    case R_ANY: return NULL;
    case R_POS: return v > 0 ? NULL : "must be > 0";
    case R_NONNEG: return v >= 0 ? NULL : "must be >= 0";
    case R_FRAC: return v > 0 && v <= 1 ? NULL : "must be in (0, 1]";
    case R_DAMP: return v > 0 && v <= 10 ? NULL : "must be in (0, 10]";
    case R_OPEN01: return v > 0 && v < 1 ? NULL : "must be in (0, 1)";
    case R_ANGLE: return v >= 0 && v < 90 ? NULL : "must be in [0, 90) degrees";
    case R_TURN: return v > 0 && v <= 180 ? NULL : "must be in (0, 180] degrees";
    }
    return NULL;
}

static double unit_scale(unit u) { return u == U_DEG ? DEG : 1.0; }

static int is_periodic(rd_pulse_kind k)
{
    return k == RD_PULSE_ONE_SINE || k == RD_PULSE_ONE_COSINE || k == RD_PULSE_HARMONIC;
}

/* Duration of a pulse, s: one period (cycles periods for harmonic) for the periodic shapes;
 * 1/frequency or the given duration for rectangular and triangle. */
static double pulse_duration(const rd_pulse_def *p)
{
    if (p->kind == RD_PULSE_HARMONIC)
        return p->cycles / p->frequency;
    if (is_periodic(p->kind) || p->frequency > 0)
        return 1.0 / p->frequency;
    return p->duration;
}

/* Block names double as override keys (block.<name>.density): letters, digits, '_' and '-'. */
static int valid_name(const char *s, size_t len)
{
    if (len == 0 || len >= RD_NAME_MAX)
        return 0;
    for (size_t i = 0; i < len; i++)
        if (!isalnum((unsigned char)s[i]) && s[i] != '_' && s[i] != '-')
            return 0;
    return 1;
}

static int find_body(const rd_scenario *sc, const char *name, size_t len)
{
    for (int i = 0; i < sc->nbodies; i++)
        if (strlen(sc->bodies[i].name) == len && memcmp(sc->bodies[i].name, name, len) == 0)
            return i;
    return -1;
}

/* Appends ", word" (or "word" to an empty buf), truncating quietly. */
static void append(char *buf, size_t size, const char *word)
{
    size_t n = strlen(buf);
    if (n + 1 < size)
        snprintf(buf + n, size - n, "%s%s", n ? ", " : "", word);
}

/* ---- lexer ---- */

typedef struct token {
    const char *s; /* text, quotes stripped; not NUL-terminated */
    int len;
    int line, col; /* 1-based position of the first character (the quote for strings) */
    int quoted;
} token;

typedef struct parser {
    rd_scenario *sc;
    rd_error *err;
    const char *name;       /* file name for messages */
    const char *p;          /* next character */
    const char *bol;        /* first character of the current line */
    int line;               /* current line, 1-based */
    token tok[MAX_TOKENS];  /* the current command */
    int n;                  /* its tokens */
    int cur;                /* next token to take */
    char ctx[64];           /* "noun verb", for messages */
    int motion_line[3];     /* lines that set the records' direction, scale, baseline (0: none) */
} parser;

static int perr(const parser *P, const token *t, const char *fmt, ...) RD_PRINTF(3, 4);

static int perr(const parser *P, const token *t, const char *fmt, ...)
{
    char msg[RD_ERROR_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return rd_error_set(P->err, "%s:%d:%d: %s", P->name, t->line, t->col, msg);
}

static int is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

static int ends_word(char c) { return c == '\0' || c == '\n' || c == ';' || is_blank(c); }

/* Scans the token at P->p into *t: a quoted string (to the matching quote on the same line)
 * or a word (to the next blank, ';' or end of line). Returns 0 or -1. */
static int lex_token(parser *P, token *t)
{
    const char *s = P->p, *e = s + 1;
    *t = (token){s, 0, P->line, (int)(s - P->bol) + 1, *s == '\'' || *s == '"'};
    if (!t->quoted) {
        while (!ends_word(*P->p))
            P->p++;
        t->len = (int)(P->p - s);
        return 0;
    }
    while (*e && *e != '\n' && *e != *s)
        e++;
    if (*e != *s)
        return perr(P, t, "unterminated string (missing closing %c)", *s);
    t->s = s + 1;
    t->len = (int)(e - s - 1);
    P->p = e + 1;
    if (!ends_word(*P->p)) {
        token g = {P->p, 1, P->line, (int)(P->p - P->bol) + 1, 0};
        return perr(P, &g, "expected a space after the closing quote");
    }
    return 0;
}

/* Reads the next command (one line, or several joined by '&') into P->tok.
 * Returns 1 when a command was read, 0 at the end of the text, -1 on error. */
static int lex_command(parser *P)
{
    token amp = {0}, t; /* amp.s: a pending '&' on the current line */
    P->n = P->cur = 0;
    for (;;) {
        char c = *P->p;
        if (c == '\0' && amp.s)
            return perr(P, &amp, "'&' continuation at end of file");
        if (c == '\0')
            return P->n > 0;
        if (c == '\n') {
            P->p++;
            P->line++;
            P->bol = P->p;
            if (amp.s && *P->p == '\0')
                return perr(P, &amp, "'&' continuation at end of file");
            if (!amp.s && P->n > 0)
                return 1;
            amp.s = NULL;
        } else if (is_blank(c)) {
            P->p++;
        } else if (c == ';') {
            while (*P->p && *P->p != '\n')
                P->p++;
        } else {
            if (lex_token(P, &t))
                return -1;
            if (amp.s)
                return perr(P, &amp, "'&' must be the last token on its line");
            if (!t.quoted && t.len == 1 && t.s[0] == '&')
                amp = t;
            else if (P->n == MAX_TOKENS)
                return perr(P, &t, "too many tokens in one command (at most %d)", MAX_TOKENS);
            else
                P->tok[P->n++] = t;
        }
    }
}

/* ---- token helpers ---- */

static const token *take(parser *P) { return P->cur < P->n ? &P->tok[P->cur++] : NULL; }

static const token *verb_token(const parser *P) { return &P->tok[1]; }

static int tok_is(const token *t, const char *word)
{
    return (size_t)t->len == strlen(word) && strncasecmp(t->s, word, (size_t)t->len) == 0;
}

static int find_word(const token *t, const char *const *names)
{
    for (int i = 0; names[i]; i++)
        if (tok_is(t, names[i]))
            return i;
    return -1;
}

static void join(char *buf, size_t size, const char *const *names)
{
    buf[0] = '\0';
    for (int i = 0; names[i]; i++)
        append(buf, size, names[i]);
}

enum { KW_ERR = -1, KW_END = -2 };

/* Takes the next keyword of the command: its index in names (NULL-terminated), KW_END after
 * the last token, or KW_ERR for an unknown or repeated keyword. *seen collects the indices. */
static int next_keyword(parser *P, const char *const *names, unsigned *seen, const token **kw)
{
    char list[256];
    const token *t = take(P);
    if (!t)
        return KW_END;
    int k = find_word(t, names);
    if (k < 0) {
        join(list, sizeof list, names);
        return perr(P, t, "unknown keyword '%.*s' for '%s' (expected %s)", t->len, t->s, P->ctx,
                    list);
    }
    if (*seen & (1u << k))
        return perr(P, t, "keyword '%.*s' given twice", t->len, t->s);
    *seen |= 1u << k;
    *kw = t;
    return k;
}

/* Error for a command that needs at least one of its keywords. */
static int missing_keyword(parser *P, const char *const *names)
{
    char list[256];
    join(list, sizeof list, names);
    return perr(P, verb_token(P), "missing keyword after '%s' (expected %s)", P->ctx, list);
}

/* Keywords that exclude each other: remembers the first in *prev, refuses a second. */
static int exclusive(parser *P, const token **prev, const token *kw)
{
    if (*prev)
        return perr(P, kw, "'%.*s' cannot be combined with '%.*s'", kw->len, kw->s, (*prev)->len,
                    (*prev)->s);
    *prev = kw;
    return 0;
}

static int expect_end(parser *P)
{
    const token *t = take(P);
    if (t)
        return perr(P, t, "unexpected '%.*s' after '%s'", t->len, t->s, P->ctx);
    return 0;
}

/* Reads n numbers after keyword kw, each checked against r (as written) and converted to SI. */
static int read_values(parser *P, const token *kw, int n, range r, unit u, double *v)
{
    for (int i = 0; i < n; i++) {
        const token *t = take(P);
        if (!t)
            return perr(P, kw, "expected a number after '%.*s'", kw->len, kw->s);
        if (parse_number(t->s, (size_t)t->len, u == U_ACCEL, &v[i]))
            return perr(P, t, "expected a number after '%.*s', got '%.*s'", kw->len, kw->s,
                        t->len, t->s);
        const char *bad = range_error(v[i], r);
        if (bad)
            return perr(P, t, "'%.*s' %s, got %.*s", kw->len, kw->s, bad, t->len, t->s);
        v[i] *= unit_scale(u);
    }
    return 0;
}

static int read_value(parser *P, const token *kw, range r, unit u, double *v)
{
    return read_values(P, kw, 1, r, u, v);
}

static int read_switch(parser *P, const token *kw, int *on)
{
    const token *t = take(P);
    if (!t)
        return perr(P, kw, "expected on or off after '%.*s'", kw->len, kw->s);
    if (!tok_is(t, "on") && !tok_is(t, "off"))
        return perr(P, t, "expected on or off after '%.*s', got '%.*s'", kw->len, kw->s, t->len,
                    t->s);
    *on = tok_is(t, "on");
    return 0;
}

/* Reads a block name after kw into dst (RD_NAME_MAX); *name keeps its token for messages. */
static int read_name(parser *P, const token *kw, const token **name, char *dst)
{
    const token *t = take(P);
    if (!t)
        return perr(P, kw, "expected a name after '%.*s'", kw->len, kw->s);
    if (!valid_name(t->s, (size_t)t->len))
        return perr(P, t, "invalid block name '%.*s' (1 to %d letters, digits, '_' or '-')",
                    t->len, t->s, RD_NAME_MAX - 1);
    memcpy(dst, t->s, (size_t)t->len);
    dst[t->len] = '\0';
    *name = t;
    return 0;
}

/* Reads a text token (title, path) into dst of the given size; what names it in messages. */
static int read_text(parser *P, const char *what, char *dst, size_t size)
{
    const token *t = take(P);
    if (!t)
        return perr(P, verb_token(P), "expected %s after '%s'", what, P->ctx);
    if (t->len == 0)
        return perr(P, t, "empty %s", what);
    if ((size_t)t->len >= size)
        return perr(P, t, "%s longer than %zu characters", what, size - 1);
    memcpy(dst, t->s, (size_t)t->len);
    dst[t->len] = '\0';
    return 0;
}

/* ---- model ---- */

static int model_title(parser *P)
{
    if (read_text(P, "a title", P->sc->title, sizeof P->sc->title))
        return -1;
    return expect_end(P);
}

static int model_gravity(parser *P)
{
    if (read_value(P, verb_token(P), R_NONNEG, U_ACCEL, &P->sc->gravity))
        return -1;
    return expect_end(P);
}

static int model_density(parser *P)
{
    if (read_value(P, verb_token(P), R_POS, U_PLAIN, &P->sc->density))
        return -1;
    return expect_end(P);
}

static int model_damping(parser *P)
{
    static const char *const names[] = {"none", "viscous", "local", NULL};
    static const range ranges[] = {R_ANY, R_DAMP, R_OPEN01};
    rd_damping_def *d = &P->sc->damping;
    const token *kw, *prev = NULL;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        if (exclusive(P, &prev, kw))
            return -1;
        d->kind = (rd_damping_kind)k;
        d->value = 0;
        if (k > 0 && read_value(P, kw, ranges[k], U_PLAIN, &d->value))
            return -1;
    }
    if (k == KW_ERR)
        return -1;
    return prev ? 0 : missing_keyword(P, names);
}

static int model_timestep(parser *P)
{
    static const char *const names[] = {"auto", "fixed", "safety", NULL};
    rd_timestep_def *ts = &P->sc->timestep;
    const token *kw, *prev = NULL, *safety = NULL;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        if (k == 2) {
            safety = kw;
            if (read_value(P, kw, R_FRAC, U_PLAIN, &ts->safety))
                return -1;
            continue;
        }
        if (exclusive(P, &prev, kw))
            return -1;
        ts->kind = k == 0 ? RD_TIMESTEP_AUTO : RD_TIMESTEP_FIXED;
        if (k == 1 && read_value(P, kw, R_POS, U_PLAIN, &ts->dt))
            return -1;
    }
    if (k == KW_ERR)
        return -1;
    if (!prev)
        return perr(P, verb_token(P), "expected auto or fixed after 'model timestep'");
    if (safety && ts->kind == RD_TIMESTEP_FIXED)
        return perr(P, safety, "'safety' applies only to 'model timestep auto'");
    return 0;
}

static int model_settle(parser *P)
{
    static const char *const names[] = {"on", "off", "ratio", "time-limit", NULL};
    rd_settle_def *st = &P->sc->settle;
    const token *kw, *prev = NULL;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        int rc = 0;
        if (k < 2) {
            rc = exclusive(P, &prev, kw);
            st->enabled = k == 0;
        } else {
            rc = read_value(P, kw, R_POS, U_PLAIN, k == 2 ? &st->ratio : &st->max_time);
        }
        if (rc)
            return -1;
    }
    if (k == KW_ERR)
        return -1;
    return seen ? 0 : missing_keyword(P, names);
}

static int model_solve(parser *P)
{
    static const char *const names[] = {"time", "tail", NULL};
    const token *kw;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0)
        if (read_value(P, kw, R_POS, U_PLAIN, k == 0 ? &P->sc->duration : &P->sc->tail))
            return -1;
    if (k == KW_ERR)
        return -1;
    return seen ? 0 : missing_keyword(P, names);
}

static int model_overturn(parser *P)
{
    static const char *const names[] = {"tilt-ratio", "angle", "height", "off-pedestal", "stop", NULL};
    static const range ranges[] = {R_POS, R_TURN, R_OPEN01, R_NONNEG};
    static const unit units[] = {U_PLAIN, U_DEG, U_PLAIN, U_PLAIN};
    rd_overturn_def *ov = &P->sc->overturn;
    const token *kw, *prev = NULL;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        if (k == 4) {
            if (read_switch(P, kw, &ov->stop))
                return -1;
            continue;
        }
        if (exclusive(P, &prev, kw) || read_value(P, kw, ranges[k], units[k], &ov->value))
            return -1;
        ov->kind = (rd_overturn_kind)k;
    }
    if (k == KW_ERR)
        return -1;
    return seen ? 0 : missing_keyword(P, names);
}

/* `model reference restitution e`: the rigid reference solvers' impact restitution. */
static int model_reference(parser *P)
{
    static const char *const names[] = {"restitution", NULL};
    const token *kw;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0)
        if (read_value(P, kw, R_FRAC, U_PLAIN, &P->sc->ref_restitution))
            return -1;
    if (k == KW_ERR)
        return -1;
    return seen ? 0 : missing_keyword(P, names);
}

/* ---- block ---- */

static int resolve_path(const char *base, const char *file, char *dst, size_t size);

/* Keywords every single-body command accepts, after its shape's own. */
static const char *const body_common[] = {"position", "seat-on", "at",   "rotation",
                                          "density",  "mass",    "name", "fixed"};
#define NCOMMON 8

typedef struct body_cmd {
    rd_body_def b;
    const token *name, *dm, *place; /* name token; density/mass and position/seat-on given */
    unsigned seen;                  /* keywords seen, bit k for names[k] */
} body_cmd;

/* Reads "seat-on NAME": the body must exist (seated bodies stack in definition order). */
static int read_seat(parser *P, const token *kw, rd_body_def *b)
{
    const token *t;
    if (read_name(P, kw, &t, b->seat_on))
        return -1;
    int j = find_body(P->sc, b->seat_on, strlen(b->seat_on));
    if (j < 0)
        return perr(P, t, "unknown block '%s' (seat-on needs a block created before this line)",
                    b->seat_on);
    b->position[0] = P->sc->bodies[j].position[0]; /* default: above the seat's centre */
    b->position[1] = P->sc->bodies[j].position[1];
    return 0;
}

static int common_body_keyword(parser *P, int k, const token *kw, body_cmd *c)
{
    rd_body_def *b = &c->b;
    switch (k) {
    case 0: return exclusive(P, &c->place, kw) || read_values(P, kw, 3, R_ANY, U_PLAIN, b->position);
    case 1: return exclusive(P, &c->place, kw) || read_seat(P, kw, b);
    case 2: return read_values(P, kw, 2, R_ANY, U_PLAIN, b->position);
    case 3: return read_values(P, kw, 3, R_ANY, U_DEG, b->rotation);
    case 4: return exclusive(P, &c->dm, kw) || read_value(P, kw, R_POS, U_PLAIN, &b->density);
    case 5: return exclusive(P, &c->dm, kw) || read_value(P, kw, R_POS, U_PLAIN, &b->mass);
    case 6: return read_name(P, kw, &c->name, b->name);
    default: b->fixed = 1; return 0;
    }
}

/* Reads "vertices x y z x y z ...": every number up to the next keyword (at least 4 points). */
static int read_vertices(parser *P, const token *kw, rd_body_def *b)
{
    int n = 0;
    while (P->cur + n < P->n && parse_number(P->tok[P->cur + n].s, (size_t)P->tok[P->cur + n].len, 0,
                                             &(double){0}) == 0)
        n++;
    if (n < 12 || n % 3)
        return perr(P, kw, "'vertices' needs x y z triples of at least 4 points, got %d numbers", n);
    double *v = malloc((size_t)n * sizeof *v);
    if (!v)
        return perr(P, kw, "out of memory");
    if (read_values(P, kw, n, R_ANY, U_PLAIN, v)) {
        free(v);
        return -1;
    }
    free(b->verts);
    b->verts = v;
    b->nverts = n / 3;
    return 0;
}

/* Shape keywords: brick {size}, prism {sides, radius, radius-top, height}, polyhedron
 * {vertices}, mesh {} (the file is read before the keywords). */
static int shape_keyword(parser *P, int k, const token *kw, rd_body_def *b)
{
    double sides;
    switch (b->shape) {
    case RD_SHAPE_BRICK: return read_values(P, kw, 3, R_POS, U_PLAIN, b->size);
    case RD_SHAPE_PRISM:
        if (k == 0) {
            if (read_value(P, kw, R_POS, U_PLAIN, &sides))
                return -1;
            if (sides < 3 || sides > 128 || sides != (int)sides)
                return perr(P, kw, "'sides' must be a whole number from 3 to 128");
            b->sides = (int)sides;
            return 0;
        }
        return read_value(P, kw, R_POS, U_PLAIN, k == 1 ? &b->radius : k == 2 ? &b->radius_top : &b->size[2]);
    case RD_SHAPE_HULL: return read_vertices(P, kw, b);
    case RD_SHAPE_MESH: break;
    }
    return 0;
}

/* The shape's own keywords (required ones flagged by bits in need) + body_common. */
typedef struct shape_syntax {
    const char *word;
    rd_shape_kind kind;
    const char *names[NCOMMON + 5];
    int nown;
    unsigned need;
} shape_syntax;

static const shape_syntax shapes[] = {
    {"brick", RD_SHAPE_BRICK, {"size"}, 1, 1u},
    {"prism", RD_SHAPE_PRISM, {"sides", "radius", "radius-top", "height"}, 4, 1u | 2u | 8u},
    {"polyhedron", RD_SHAPE_HULL, {"vertices"}, 1, 1u},
    {"mesh", RD_SHAPE_MESH, {NULL}, 0, 0u},
};

static int body_command(parser *P, const shape_syntax *sh, body_cmd *c)
{
    const char *names[NCOMMON + 6];
    int n = 0;
    for (; n < sh->nown; n++) names[n] = sh->names[n];
    for (int i = 0; i < NCOMMON; i++) names[n + i] = body_common[i];
    names[n + NCOMMON] = NULL;
    const token *kw;
    int k;
    while ((k = next_keyword(P, names, &c->seen, &kw)) >= 0)
        if (k < n ? shape_keyword(P, k, kw, &c->b) : common_body_keyword(P, k - n, kw, c))
            return -1;
    if (k == KW_ERR)
        return -1;
    for (int i = 0; i < sh->nown; i++)
        if ((sh->need >> i & 1u) && !(c->seen >> i & 1u))
            return perr(P, &P->tok[2], "missing '%s' for '%s %s'", names[i], P->ctx, sh->word);
    if (!c->place)
        return perr(P, &P->tok[2], "missing 'position' or 'seat-on' for '%s %s'", P->ctx, sh->word);
    if ((c->seen >> (n + 2) & 1u) && !c->b.seat_on[0])
        return perr(P, &P->tok[2], "'at' applies only with 'seat-on'");
    if (c->b.shape == RD_SHAPE_PRISM && !(c->seen & 4u))
        c->b.radius_top = c->b.radius;
    return 0;
}

/* Appends b, naming it "block<k>" when unnamed; refuses duplicates and overflow. */
static int add_body(parser *P, const rd_body_def *b, const token *name, const token *at)
{
    rd_scenario *sc = P->sc;
    if (sc->nbodies == RD_MAX_BODIES)
        return perr(P, verb_token(P), "too many blocks (at most %d)", RD_MAX_BODIES);
    rd_body_def d = *b;
    d.line = P->tok[0].line;
    if (!d.name[0])
        snprintf(d.name, sizeof d.name, "block%d", sc->nbodies + 1);
    int dup = find_body(sc, d.name, strlen(d.name));
    if (dup >= 0 && name)
        return perr(P, name, "duplicate block name '%s' (first created on line %d)", d.name,
                    sc->bodies[dup].line);
    if (dup >= 0)
        return perr(P, at, "default name '%s' is already taken (line %d); give this block a name",
                    d.name, sc->bodies[dup].line);
    sc->bodies[sc->nbodies++] = d;
    return 0;
}

static int single_body(parser *P, const shape_syntax *sh, const token *at)
{
    body_cmd c = {.b = {.shape = sh->kind}};
    if (sh->kind == RD_SHAPE_MESH) {
        char file[RD_PATH_MAX];
        if (read_text(P, "a mesh file", file, sizeof file))
            return -1;
        if (resolve_path(P->name, file, c.b.mesh, sizeof c.b.mesh))
            return perr(P, at, "mesh path too long");
    }
    if (body_command(P, sh, &c) == 0 && add_body(P, &c.b, c.name, at) == 0)
        return 0;
    free(c.b.verts);
    return -1;
}

/* Builder helpers: a named member of an assembly seated on `seat`. */
static int add_member(parser *P, const body_cmd *c, const char *prefix, const char *suffix,
                      const char *seat, rd_body_def *b, const token *at)
{
    b->density = c->b.density;
    b->mass = 0;
    b->position[0] = c->b.position[0];
    b->position[1] = c->b.position[1];
    if ((size_t)snprintf(b->name, sizeof b->name, "%s-%s", prefix, suffix) >= sizeof b->name)
        return perr(P, at, "block name '%s-%s' is too long", prefix, suffix);
    snprintf(b->seat_on, sizeof b->seat_on, "%s", seat);
    return add_body(P, b, NULL, at);
}

static int read_count(parser *P, const token *kw, int lo, int hi, int *n)
{
    double v;
    if (read_value(P, kw, R_POS, U_PLAIN, &v))
        return -1;
    if (v < lo || v > hi || v != (int)v)
        return perr(P, kw, "'%.*s' must be a whole number from %d to %d", kw->len, kw->s, lo, hi);
    *n = (int)v;
    return 0;
}

/* block create column drums N diameter D height H [sides S] [taper T] [plinth W H]
 *                     [capital H] [abacus W H] seat-on NAME [at X Y] [name P] [density RHO]
 * A classical column: plinth (brick), N drums (prisms whose radius shrinks linearly from D/2
 * to T D/2 up the shaft), an echinus capital (frustum widening by 30 %), an abacus (brick). */
static int block_column(parser *P, const token *at)
{
    static const char *const names[] = {"drums", "diameter", "height", "sides", "taper", "plinth",
                                        "capital", "abacus", "seat-on", "at", "name", "density", NULL};
    body_cmd c = {.b = {.shape = RD_SHAPE_PRISM}};
    int ndrums = 0, sides = 20;
    double d = 0, h = 0, taper = 1, plinth[2] = {0}, cap = 0, abacus[2] = {0};
    const token *kw;
    int k;
    while ((k = next_keyword(P, names, &c.seen, &kw)) >= 0) {
        int rc = 0;
        switch (k) {
        case 0: rc = read_count(P, kw, 1, 100, &ndrums); break;
        case 1: rc = read_value(P, kw, R_POS, U_PLAIN, &d); break;
        case 2: rc = read_value(P, kw, R_POS, U_PLAIN, &h); break;
        case 3: rc = read_count(P, kw, 3, 128, &sides); break;
        case 4: rc = read_value(P, kw, R_FRAC, U_PLAIN, &taper); break;
        case 5: rc = read_values(P, kw, 2, R_POS, U_PLAIN, plinth); break;
        case 6: rc = read_value(P, kw, R_POS, U_PLAIN, &cap); break;
        case 7: rc = read_values(P, kw, 2, R_POS, U_PLAIN, abacus); break;
        case 8: rc = read_seat(P, kw, &c.b); c.place = kw; break;
        case 9: rc = read_values(P, kw, 2, R_ANY, U_PLAIN, c.b.position); break;
        case 10: rc = read_name(P, kw, &c.name, c.b.name); break;
        default: rc = read_value(P, kw, R_POS, U_PLAIN, &c.b.density); break;
        }
        if (rc)
            return -1;
    }
    if (k == KW_ERR)
        return -1;
    for (int i = 0; i < 3; i++)
        if (!(c.seen >> i & 1u))
            return perr(P, &P->tok[2], "missing '%s' for 'block create column'", names[i]);
    if (!c.place)
        return perr(P, &P->tok[2], "missing 'seat-on' for 'block create column'");
    const char *prefix = c.b.name[0] ? c.b.name : "column";
    char below[RD_NAME_MAX];
    snprintf(below, sizeof below, "%s", c.b.seat_on);
    if (plinth[0] > 0) {
        rd_body_def b = {.shape = RD_SHAPE_BRICK, .size = {plinth[0], plinth[0], plinth[1]}};
        if (add_member(P, &c, prefix, "plinth", below, &b, at)) return -1;
        memcpy(below, P->sc->bodies[P->sc->nbodies - 1].name, sizeof below);
    }
    double r0 = d / 2, r = r0;
    for (int i = 1; i <= ndrums; i++) {
        char suffix[16];
        snprintf(suffix, sizeof suffix, "d%d", i);
        double top = r0 * (1 - (1 - taper) * i / ndrums);
        rd_body_def b = {.shape = RD_SHAPE_PRISM, .sides = sides, .radius = r, .radius_top = top, .size = {0, 0, h}};
        if (add_member(P, &c, prefix, suffix, below, &b, at)) return -1;
        memcpy(below, P->sc->bodies[P->sc->nbodies - 1].name, sizeof below);
        r = top;
    }
    if (cap > 0) {
        rd_body_def b = {.shape = RD_SHAPE_PRISM, .sides = sides, .radius = r, .radius_top = 1.3 * r, .size = {0, 0, cap}};
        if (add_member(P, &c, prefix, "capital", below, &b, at)) return -1;
        memcpy(below, P->sc->bodies[P->sc->nbodies - 1].name, sizeof below);
    }
    if (abacus[0] > 0) {
        rd_body_def b = {.shape = RD_SHAPE_BRICK, .size = {abacus[0], abacus[0], abacus[1]}};
        if (add_member(P, &c, prefix, "abacus", below, &b, at)) return -1;
    }
    return 0;
}

/* block create stack lower LX LY LZ upper UX UY UZ seat-on NAME [at X Y] [name P] [density RHO]
 * A two-block assembly (a statue on its pedestal): P-lower on NAME, P-upper on P-lower. */
static int block_stack(parser *P, const token *at)
{
    static const char *const names[] = {"lower", "upper", "seat-on", "at", "name", "density", NULL};
    body_cmd c = {.b = {.shape = RD_SHAPE_BRICK}};
    double lo[3], up[3];
    const token *kw;
    int k;
    while ((k = next_keyword(P, names, &c.seen, &kw)) >= 0) {
        int rc = 0;
        switch (k) {
        case 0: rc = read_values(P, kw, 3, R_POS, U_PLAIN, lo); break;
        case 1: rc = read_values(P, kw, 3, R_POS, U_PLAIN, up); break;
        case 2: rc = read_seat(P, kw, &c.b); c.place = kw; break;
        case 3: rc = read_values(P, kw, 2, R_ANY, U_PLAIN, c.b.position); break;
        case 4: rc = read_name(P, kw, &c.name, c.b.name); break;
        default: rc = read_value(P, kw, R_POS, U_PLAIN, &c.b.density); break;
        }
        if (rc)
            return -1;
    }
    if (k == KW_ERR)
        return -1;
    if ((c.seen & 3u) != 3u)
        return perr(P, &P->tok[2], "missing '%s' for 'block create stack'", c.seen & 1u ? "upper" : "lower");
    if (!c.place)
        return perr(P, &P->tok[2], "missing 'seat-on' for 'block create stack'");
    const char *prefix = c.b.name[0] ? c.b.name : "stack";
    char lower[RD_NAME_MAX];
    rd_body_def b1 = {.shape = RD_SHAPE_BRICK, .size = {lo[0], lo[1], lo[2]}};
    rd_body_def b2 = {.shape = RD_SHAPE_BRICK, .size = {up[0], up[1], up[2]}};
    if (add_member(P, &c, prefix, "lower", c.b.seat_on, &b1, at)) return -1;
    memcpy(lower, P->sc->bodies[P->sc->nbodies - 1].name, sizeof lower);
    return add_member(P, &c, prefix, "upper", lower, &b2, at);
}

static int block_create(parser *P)
{
    const token *shape = take(P);
    static const char *expected = "brick, prism, polyhedron, column or stack";
    if (!shape)
        return perr(P, verb_token(P), "expected a shape after 'block create' (expected %s)", expected);
    if (tok_is(shape, "column"))
        return block_column(P, shape);
    if (tok_is(shape, "stack"))
        return block_stack(P, shape);
    for (size_t i = 0; i + 1 < sizeof shapes / sizeof shapes[0]; i++)
        if (tok_is(shape, shapes[i].word))
            return single_body(P, &shapes[i], shape);
    return perr(P, shape, "unknown shape '%.*s' for 'block create' (expected %s)", shape->len,
                shape->s, expected);
}

/* block import mesh 'rock.obj' (position X Y Z | seat-on NAME [at X Y]) [rotation ...] ... */
static int block_import(parser *P)
{
    const token *what = take(P);
    if (!what || !tok_is(what, "mesh"))
        return perr(P, what ? what : verb_token(P), "expected 'mesh' after 'block import'");
    return single_body(P, &shapes[3], what);
}

static int block_initial(parser *P)
{
    static const char *const names[] = {"name", "tilt", "direction", "velocity",
                                        "angular-velocity", NULL};
    const token *kw, *name = NULL;
    char id[RD_NAME_MAX];
    double tilt = 0, dir = 0, v[3] = {0}, w[3] = {0};
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        int rc = 0;
        switch (k) {
        case 0: rc = read_name(P, kw, &name, id); break;
        case 1: rc = read_value(P, kw, R_ANGLE, U_DEG, &tilt); break;
        case 2: rc = read_value(P, kw, R_ANY, U_DEG, &dir); break;
        case 3: rc = read_values(P, kw, 3, R_ANY, U_PLAIN, v); break;
        default: rc = read_values(P, kw, 3, R_ANY, U_PLAIN, w); break;
        }
        if (rc)
            return -1;
    }
    if (k == KW_ERR)
        return -1;
    if (!name)
        return perr(P, verb_token(P), "missing 'name' for 'block initial'");
    int i = find_body(P->sc, id, strlen(id));
    if (i < 0)
        return perr(P, name, "unknown block '%s' (no 'block create ... name %s' before this line)",
                    id, id);
    rd_body_def *b = &P->sc->bodies[i];
    if (b->fixed)
        return perr(P, name, "block '%s' is fixed; 'block initial' applies only to free blocks",
                    id);
    if (seen & 2u)
        b->tilt = tilt;
    if (seen & 4u)
        b->tilt_direction = dir;
    if (seen & 8u)
        memcpy(b->velocity, v, sizeof v);
    if (seen & 16u)
        memcpy(b->angular_velocity, w, sizeof w);
    return 0;
}

/* ---- contact ---- */

static int read_spacing(parser *P, const token *kw, double *v)
{
    const token *t = take(P);
    if (!t)
        return perr(P, kw, "expected a number, auto or vertices after 'spacing'");
    if (tok_is(t, "auto") || tok_is(t, "vertices")) {
        *v = tok_is(t, "auto") ? -1.0 : 0.0;
        return 0;
    }
    if (parse_number(t->s, (size_t)t->len, 0, v))
        return perr(P, t, "expected a number, auto or vertices after 'spacing', got '%.*s'",
                    t->len, t->s);
    if (*v < 0)
        return perr(P, t, "'spacing' must be >= 0, got %.*s", t->len, t->s);
    return 0;
}

static int contact_property(parser *P)
{
    static const char *const names[] = {"stiffness-normal", "stiffness-shear", "friction",
                                        "cohesion",         "tension",         "spacing", NULL};
    rd_contact_def *c = &P->sc->contact;
    const token *kw;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        int rc = 0;
        switch (k) {
        case 0: rc = read_value(P, kw, R_POS, U_PLAIN, &c->kn); break;
        case 1: rc = read_value(P, kw, R_POS, U_PLAIN, &c->ks); break;
        case 2: rc = read_value(P, kw, R_ANGLE, U_DEG, &c->friction); break;
        case 3: rc = read_value(P, kw, R_NONNEG, U_PLAIN, &c->cohesion); break;
        case 4: rc = read_value(P, kw, R_NONNEG, U_PLAIN, &c->tension); break;
        default: rc = read_spacing(P, kw, &c->spacing); break;
        }
        if (rc)
            return -1;
    }
    return k == KW_ERR ? -1 : 0;
}

/* contact interface-perturbation seed S remove F raise H raise-fraction P scatter C
 * keep-corners on|off (src/perturb.c) */
static int contact_perturbation(parser *P)
{
    static const char *const names[] = {"seed", "remove", "raise", "raise-fraction", "scatter",
                                        "keep-corners", NULL};
    rd_perturb_def *d = &P->sc->contact.perturb;
    const token *kw;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        double *v[] = {&d->seed, &d->remove, &d->raise, &d->raise_fraction, &d->scatter};
        if (k == 5 ? read_switch(P, kw, &d->keep_corners) : read_value(P, kw, R_NONNEG, U_PLAIN, v[k]))
            return -1;
        if ((k == 0 && d->seed != floor(d->seed)) || (k == 1 && d->remove >= 1) || (k == 3 && d->raise_fraction > 1))
            return perr(P, kw, "'%s' must be %s", names[k], k == 0 ? "a whole number" : k == 1 ? "below 1" : "at most 1");
    }
    return k == KW_ERR ? -1 : 0;
}

/* ---- ground motion ---- */

enum { PK_AMPLITUDE, PK_FREQUENCY, PK_DURATION, PK_CYCLES, PK_START, PK_DIRECTION, PK_VERTICAL,
       PK_COUNT };

/* Which keywords each pulse shape takes; tk holds the keyword tokens given (NULL if absent). */
static int pulse_check(parser *P, const token *shape, rd_pulse_kind kind, const token *const *tk)
{
    int periodic = is_periodic(kind);
    if (!tk[PK_AMPLITUDE])
        return perr(P, shape, "missing 'amplitude' for 'ground-motion pulse'");
    if (tk[PK_CYCLES] && kind != RD_PULSE_HARMONIC)
        return perr(P, tk[PK_CYCLES], "'cycles' applies only to harmonic pulses");
    if (tk[PK_DIRECTION] && tk[PK_VERTICAL])
        return perr(P, tk[PK_DIRECTION], "'direction' does not apply to a vertical pulse");
    if (periodic && tk[PK_DURATION])
        return perr(P, tk[PK_DURATION],
                    "'duration' does not apply to a %.*s pulse (set 'frequency')",
                    shape->len, shape->s);
    if (periodic && !tk[PK_FREQUENCY])
        return perr(P, shape, "a %.*s pulse needs 'frequency'", shape->len, shape->s);
    if (!periodic && tk[PK_FREQUENCY] && tk[PK_DURATION])
        return perr(P, tk[PK_DURATION], "'duration' cannot be combined with 'frequency'");
    if (!periodic && !tk[PK_FREQUENCY] && !tk[PK_DURATION])
        return perr(P, shape, "a %.*s pulse needs 'duration' (or 'frequency')", shape->len,
                    shape->s);
    return 0;
}

static int pulse_keywords(parser *P, rd_pulse_def *p, const token **tk)
{
    static const char *const names[] = {"amplitude", "frequency", "duration", "cycles",
                                        "start",     "direction", "vertical", NULL};
    const token *kw;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        int rc = 0;
        tk[k] = kw;
        switch (k) {
        case PK_AMPLITUDE: rc = read_value(P, kw, R_ANY, U_ACCEL, &p->amplitude); break;
        case PK_FREQUENCY: rc = read_value(P, kw, R_POS, U_PLAIN, &p->frequency); break;
        case PK_DURATION: rc = read_value(P, kw, R_POS, U_PLAIN, &p->duration); break;
        case PK_CYCLES: rc = read_value(P, kw, R_POS, U_PLAIN, &p->cycles); break;
        case PK_START: rc = read_value(P, kw, R_NONNEG, U_PLAIN, &p->start); break;
        case PK_DIRECTION: rc = read_value(P, kw, R_ANY, U_DEG, &p->direction); break;
        default: break;
        }
        if (rc)
            return -1;
    }
    return k == KW_ERR ? -1 : 0;
}

static int motion_pulse(parser *P)
{
    static const char *const shapes[] = {"one-sine", "one-cosine", "rectangular", "triangle",
                                         "harmonic", NULL};
    char list[128];
    const token *shape = take(P), *tk[PK_COUNT] = {0};
    join(list, sizeof list, shapes);
    if (!shape)
        return perr(P, verb_token(P), "expected a shape after 'ground-motion pulse' (expected %s)",
                    list);
    int s = find_word(shape, shapes);
    if (s < 0)
        return perr(P, shape, "unknown pulse shape '%.*s' (expected %s)", shape->len, shape->s,
                    list);
    rd_pulse_def p = {.kind = (rd_pulse_kind)(s + 1), .cycles = 1, .line = P->tok[0].line};
    if (pulse_keywords(P, &p, tk) || pulse_check(P, shape, p.kind, tk))
        return -1;
    const char *which = tk[PK_VERTICAL] ? "vertical" : "horizontal";
    rd_pulse_def *slot = tk[PK_VERTICAL] ? &P->sc->motion.vertical : &P->sc->motion.horizontal;
    if (slot->kind != RD_PULSE_NONE)
        return perr(P, &P->tok[0], "a %s pulse is already defined (line %d)", which, slot->line);
    for (int c = tk[PK_VERTICAL] ? RD_VERTICAL : RD_H1; c <= (tk[PK_VERTICAL] ? RD_VERTICAL : RD_H2); c++)
        if (P->sc->motion.record[c].source != RD_SOURCE_NONE)
            return perr(P, &P->tok[0], "a %s record is already defined (line %d); use a pulse or a record",
                        rd_motion_component_name(c), P->sc->motion.record[c].line);
    p.duration = pulse_duration(&p);
    *slot = p;
    return 0;
}

/* ---- ground motion: records (`ground-motion import`, `ground-motion stochastic`) ---- */

/* Keywords shared by import and stochastic (first in both keyword lists). */
enum { MK_COMPONENT, MK_DIRECTION, MK_SCALE, MK_SCALE_PGA, MK_SCALE_PGV, MK_BASELINE, MK_COMMON };

/* What one record command says about the motion as a whole. */
typedef struct motion_cmd {
    const token *tk[MK_COMMON]; /* keyword tokens given (NULL if absent) */
    const token *comp;          /* the component's value token */
    const token *scale;         /* the scale keyword given, if any */
    double direction;           /* rad */
    double scale_value;         /* factor, m/s^2 or m/s */
    int baseline;               /* 0 (off) or the degree */
} motion_cmd;

/* `baseline <degree>|off`: degree an integer in 2..8 (rd_record_baseline). */
static int read_baseline(parser *P, const token *kw, int *degree)
{
    const token *t = take(P);
    double v;
    if (!t)
        return perr(P, kw, "expected a degree (2 to 8) or off after 'baseline'");
    if (tok_is(t, "off")) {
        *degree = 0;
        return 0;
    }
    if (parse_number(t->s, (size_t)t->len, 0, &v) || v != floor(v) || v < 2 || v > 8)
        return perr(P, t, "expected a degree (2 to 8) or off after 'baseline', got '%.*s'", t->len,
                    t->s);
    *degree = (int)v;
    return 0;
}

/* Reads the value of common keyword k into mc. */
static int common_keyword(parser *P, int k, const token *kw, motion_cmd *mc)
{
    mc->tk[k] = kw;
    switch (k) {
    case MK_COMPONENT:
        if (!(mc->comp = take(P)))
            return perr(P, kw, "expected a component after 'component'");
        return 0;
    case MK_DIRECTION: return read_value(P, kw, R_ANY, U_DEG, &mc->direction);
    case MK_BASELINE: return read_baseline(P, kw, &mc->baseline);
    default: break;
    }
    if (exclusive(P, &mc->scale, kw))
        return -1;
    return read_value(P, kw, R_POS, k == MK_SCALE_PGA ? U_ACCEL : U_PLAIN, &mc->scale_value);
}

/* Motion-wide settings may be given once, on any record line. */
static int once(parser *P, const token *kw, int *line)
{
    if (*line)
        return perr(P, kw, "'%.*s' already given on line %d (it applies to the whole ground motion)",
                    kw->len, kw->s, *line);
    *line = kw->line;
    return 0;
}

static int apply_common(parser *P, const motion_cmd *mc)
{
    static const rd_scale_kind kinds[] = {RD_SCALE_FACTOR, RD_SCALE_PGA, RD_SCALE_PGV};
    rd_motion_def *m = &P->sc->motion;
    if (mc->tk[MK_DIRECTION] && once(P, mc->tk[MK_DIRECTION], &P->motion_line[0]))
        return -1;
    if (mc->scale && once(P, mc->scale, &P->motion_line[1]))
        return -1;
    if (mc->tk[MK_BASELINE] && once(P, mc->tk[MK_BASELINE], &P->motion_line[2]))
        return -1;
    if (mc->tk[MK_DIRECTION])
        m->direction = mc->direction;
    if (mc->scale) {
        m->scale = kinds[find_word(mc->scale, (const char *const[]){"scale", "scale-pga", "scale-pgv", NULL})];
        m->scale_value = mc->scale_value;
    }
    if (mc->tk[MK_BASELINE])
        m->baseline = mc->baseline;
    return 0;
}

/* The slot of the command's component: h1 (default), h2 or vertical; a FEMA set names its
 * horizontal components a (into h1) and b (into h2). */
static int component_slot(parser *P, const motion_cmd *mc, int fema, int *slot)
{
    static const char *const plain[] = {"h1", "h2", "vertical", NULL};
    static const char *const ab[] = {"a", "b", NULL};
    *slot = RD_H1;
    if (!mc->comp)
        return 0;
    *slot = find_word(mc->comp, fema ? ab : plain);
    if (*slot < 0)
        return perr(P, mc->comp, "unknown component '%.*s' (expected %s)", mc->comp->len, mc->comp->s,
                    fema ? "a or b for a FEMA P695 set" : "h1, h2 or vertical");
    return 0;
}

/* Stores d in its slot and reads or generates its samples; errors point at `at`. */
static int define_component(parser *P, int slot, const rd_component_def *d, const token *at)
{
    rd_motion_def *m = &P->sc->motion;
    rd_error e;
    if (m->record[slot].source != RD_SOURCE_NONE)
        return perr(P, &P->tok[0], "a %s record is already defined (line %d)%s",
                    rd_motion_component_name(slot), m->record[slot].line,
                    slot == RD_H1 ? "; add 'component h2' for the second horizontal component" : "");
    if ((slot == RD_VERTICAL ? m->vertical.kind : m->horizontal.kind) != RD_PULSE_NONE)
        return perr(P, &P->tok[0], "a %s pulse is already defined (line %d); use a pulse or a record",
                    slot == RD_VERTICAL ? "vertical" : "horizontal",
                    slot == RD_VERTICAL ? m->vertical.line : m->horizontal.line);
    m->record[slot] = *d;
    m->record[slot].line = P->tok[0].line;
    if (rd_motion_load(m, slot, &e)) {
        m->record[slot].source = RD_SOURCE_NONE;
        return perr(P, at, "%s", e.msg);
    }
    return 0;
}

/* Resolves a file name relative to the directory of the scenario file `base` into dst. */
static int resolve_path(const char *base, const char *file, char *dst, size_t size)
{
    const char *slash = strrchr(base, '/');
    int dir = file[0] != '/' && slash ? (int)(slash - base) + 1 : 0;
    int n = snprintf(dst, size, "%.*s%s", dir, base, file);
    return n >= 0 && (size_t)n < size ? 0 : -1;
}

/* Format from the file's extension: .at2, .h5/.hdf5 (FEMA P695 set), else text. */
static rd_record_source source_of(const char *file)
{
    const char *dot = strrchr(file, '.');
    if (dot && strcasecmp(dot, ".at2") == 0)
        return RD_SOURCE_AT2;
    if (dot && (strcasecmp(dot, ".h5") == 0 || strcasecmp(dot, ".hdf5") == 0))
        return RD_SOURCE_FEMA;
    return RD_SOURCE_TEXT;
}

/* Format from the `format` token, else from the file's extension. */
static int record_format(parser *P, const token *fmt, const char *file, rd_record_source *src)
{
    static const char *const names[] = {"at2", "csv", "text", "fema", NULL};
    static const rd_record_source kinds[] = {RD_SOURCE_AT2, RD_SOURCE_TEXT, RD_SOURCE_TEXT,
                                             RD_SOURCE_FEMA};
    int k = fmt ? find_word(fmt, names) : -1;
    if (fmt && k < 0)
        return perr(P, fmt, "unknown format '%.*s' (expected at2, csv, text or fema)", fmt->len,
                    fmt->s);
    *src = fmt ? kinds[k] : source_of(file);
    return 0;
}

static int read_units(parser *P, const token *kw, double *unit)
{
    static const char *const names[] = {"g", "m/s2", "cm/s2", NULL};
    static const double factor[] = {9.80665, 1.0, 0.01}; /* m/s^2 per unit */
    const token *t = take(P);
    int k = t ? find_word(t, names) : -1;
    if (!t)
        return perr(P, kw, "expected g, m/s2 or cm/s2 after 'units'");
    if (k < 0)
        return perr(P, t, "unknown units '%.*s' (expected g, m/s2 or cm/s2)", t->len, t->s);
    *unit = factor[k];
    return 0;
}

enum { IK_FORMAT = MK_COMMON, IK_UNITS, IK_DT, IK_RECORD };

/* Checks which import keywords fit the format. */
static int import_check(parser *P, rd_record_source src, const token *const *tk)
{
    if (src == RD_SOURCE_FEMA && !tk[IK_RECORD])
        return perr(P, verb_token(P), "a FEMA P695 set needs 'record <id>'");
    if (src != RD_SOURCE_FEMA && tk[IK_RECORD])
        return perr(P, tk[IK_RECORD], "'record' applies only to FEMA P695 sets (format fema)");
    if (src != RD_SOURCE_TEXT && tk[IK_UNITS])
        return perr(P, tk[IK_UNITS], "'units' applies only to text/CSV records (AT2 and FEMA are in g)");
    if (src != RD_SOURCE_TEXT && tk[IK_DT])
        return perr(P, tk[IK_DT], "'dt' applies only to text/CSV records");
    return 0;
}

static int motion_import(parser *P)
{
    static const char *const names[] = {"component", "direction", "scale", "scale-pga", "scale-pgv",
                                        "baseline", "format", "units", "dt", "record", NULL};
    rd_component_def d = {.unit = 9.80665};
    motion_cmd mc = {0};
    const token *kw, *tk[IK_RECORD + 1] = {0}, *file = P->cur < P->n ? &P->tok[P->cur] : NULL, *id = NULL;
    char name[RD_PATH_MAX];
    unsigned seen = 0;
    int k, slot;
    if (read_text(P, "a file name", name, sizeof name))
        return -1;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        int rc = 0;
        tk[k] = kw;
        switch (k) {
        case IK_FORMAT:
            rc = (tk[k] = take(P)) ? 0 : perr(P, kw, "expected at2, csv, text or fema after 'format'");
            break;
        case IK_UNITS: rc = read_units(P, kw, &d.unit); break;
        case IK_DT: rc = read_value(P, kw, R_POS, U_PLAIN, &d.dt); break;
        case IK_RECORD:
            id = P->cur < P->n ? &P->tok[P->cur] : NULL;
            rc = read_text(P, "a record id", d.record, sizeof d.record);
            break;
        default: rc = common_keyword(P, k, kw, &mc); break;
        }
        if (rc)
            return -1;
    }
    if (k == KW_ERR || record_format(P, tk[IK_FORMAT], name, &d.source) ||
        import_check(P, d.source, tk) || component_slot(P, &mc, d.source == RD_SOURCE_FEMA, &slot))
        return -1;
    if (resolve_path(P->name, name, d.path, sizeof d.path))
        return perr(P, file, "file name too long with the scenario's directory");
    FILE *f = fopen(d.path, "rb");
    if (!f)
        return perr(P, file, "%s: cannot open: %s", d.path, strerror(errno));
    fclose(f);
    d.fema_b = d.source == RD_SOURCE_FEMA && slot == RD_H2;
    /* the file opens: a FEMA reader error is about the record id, any other about the file */
    return apply_common(P, &mc) || define_component(P, slot, &d, id ? id : file);
}

enum { SK_SEED = MK_COMMON, SK_PGA, SK_DURATION, SK_DT, SK_FREQUENCY, SK_DAMPING, SK_HIGHPASS,
       SK_HIGHPASS_DAMPING, SK_PEAK_TIME, SK_END_LEVEL };

/* Reads one Kanai-Tajimi parameter (keyword k) into def. */
static int stochastic_value(parser *P, int k, const token *kw, rd_stochastic_def *def)
{
    double seed;
    switch (k) {
    case SK_SEED:
        if (read_value(P, kw, R_NONNEG, U_PLAIN, &seed))
            return -1;
        if (seed != floor(seed) || seed > 4294967295.0)
            return perr(P, &P->tok[P->cur - 1], "'seed' must be a whole number in [0, 2^32)");
        def->seed = (unsigned long)seed;
        return 0;
    case SK_PGA: return read_value(P, kw, R_POS, U_ACCEL, &def->pga);
    case SK_DURATION: return read_value(P, kw, R_POS, U_PLAIN, &def->duration);
    case SK_DT: return read_value(P, kw, R_POS, U_PLAIN, &def->dt);
    case SK_FREQUENCY: return read_value(P, kw, R_POS, U_PLAIN, &def->frequency);
    case SK_DAMPING: return read_value(P, kw, R_OPEN01, U_PLAIN, &def->damping);
    case SK_HIGHPASS: return read_value(P, kw, R_NONNEG, U_PLAIN, &def->highpass);
    case SK_HIGHPASS_DAMPING: return read_value(P, kw, R_OPEN01, U_PLAIN, &def->highpass_damping);
    case SK_PEAK_TIME: return read_value(P, kw, R_OPEN01, U_PLAIN, &def->peak_time);
    default: return read_value(P, kw, R_OPEN01, U_PLAIN, &def->end_level);
    }
}

static int motion_stochastic(parser *P)
{
    static const char *const names[] = {
        "component", "direction", "scale",    "scale-pga", "scale-pgv",        "baseline",
        "seed",      "pga",       "duration", "dt",        "frequency",        "damping",
        "highpass",  "highpass-damping",      "peak-time", "end-level",        NULL};
    rd_component_def d = {.source = RD_SOURCE_STOCHASTIC};
    motion_cmd mc = {0};
    const token *kw;
    unsigned seen = 0;
    int k, slot;
    rd_stochastic_defaults(&d.stochastic);
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0)
        if (k < MK_COMMON ? common_keyword(P, k, kw, &mc) : stochastic_value(P, k, kw, &d.stochastic))
            return -1;
    if (k == KW_ERR)
        return -1;
    static const int needed[] = {SK_SEED, SK_PGA, SK_DURATION};
    for (int i = 0; i < 3; i++)
        if (!(seen & (1u << needed[i])))
            return perr(P, verb_token(P), "missing '%s' for 'ground-motion stochastic'", names[needed[i]]);
    if (d.stochastic.dt >= d.stochastic.duration)
        return perr(P, verb_token(P), "'dt' must be shorter than 'duration'");
    if (component_slot(P, &mc, 0, &slot))
        return -1;
    return apply_common(P, &mc) || define_component(P, slot, &d, verb_token(P));
}

/* ---- output ---- */

static int output_hdf5(parser *P)
{
    static const char *const names[] = {"interval", NULL};
    rd_output_def *o = &P->sc->output;
    const token *kw;
    unsigned seen = 0;
    int k;
    if (read_text(P, "a file name", o->path, sizeof o->path))
        return -1;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0)
        if (read_value(P, kw, R_POS, U_PLAIN, &o->interval))
            return -1;
    return k == KW_ERR ? -1 : 0;
}

/* ---- commands ---- */

typedef int (*command_fn)(parser *P);

static const struct command {
    const char *noun, *verb;
    command_fn fn;
} commands[] = {
    {"model", "title", model_title},
    {"model", "gravity", model_gravity},
    {"model", "density", model_density},
    {"model", "damping", model_damping},
    {"model", "timestep", model_timestep},
    {"model", "settle", model_settle},
    {"model", "solve", model_solve},
    {"model", "overturn", model_overturn},
    {"model", "reference", model_reference},
    {"block", "create", block_create},
    {"block", "import", block_import},
    {"block", "initial", block_initial},
    {"contact", "property", contact_property},
    {"contact", "interface-perturbation", contact_perturbation},
    {"ground-motion", "pulse", motion_pulse},
    {"ground-motion", "import", motion_import},
    {"ground-motion", "stochastic", motion_stochastic},
    {"output", "hdf5", output_hdf5},
};

#define NCOMMANDS (sizeof commands / sizeof commands[0])

/* The nouns (noun == NULL) or the verbs of one noun, comma-separated. */
static void command_list(char *buf, size_t size, const token *noun)
{
    buf[0] = '\0';
    for (size_t i = 0; i < NCOMMANDS; i++) {
        if (!noun && (i == 0 || strcmp(commands[i].noun, commands[i - 1].noun) != 0))
            append(buf, size, commands[i].noun);
        if (noun && tok_is(noun, commands[i].noun))
            append(buf, size, commands[i].verb);
    }
}

static int run_command(parser *P)
{
    const token *noun = &P->tok[0], *verb = P->n > 1 ? &P->tok[1] : NULL;
    char list[256];
    int known = 0;
    for (size_t i = 0; i < NCOMMANDS; i++) {
        if (!tok_is(noun, commands[i].noun))
            continue;
        known = 1;
        if (verb && tok_is(verb, commands[i].verb)) {
            snprintf(P->ctx, sizeof P->ctx, "%s %s", commands[i].noun, commands[i].verb);
            P->cur = 2;
            return commands[i].fn(P);
        }
    }
    command_list(list, sizeof list, known ? noun : NULL);
    if (!known)
        return perr(P, noun, "unknown command '%.*s' (expected %s)", noun->len, noun->s, list);
    if (!verb)
        return perr(P, noun, "missing verb after '%.*s' (expected %s)", noun->len, noun->s, list);
    return perr(P, verb, "unknown verb '%.*s' for '%.*s' (expected %s)", verb->len, verb->s,
                noun->len, noun->s, list);
}

/* ---- public: defaults, parse, load, free ---- */

void rd_scenario_defaults(rd_scenario *sc)
{
    memset(sc, 0, sizeof *sc);
    sc->gravity = 9.81;
    sc->density = 2700.0;
    sc->contact = (rd_contact_def){.kn = 1e10, .ks = 1e9, .friction = 40.0 * DEG, .spacing = -1.0,
                                   .perturb.raise_fraction = 0.5};
    sc->damping = (rd_damping_def){RD_DAMPING_NONE, 0.0};
    sc->motion.horizontal.cycles = 1.0;
    sc->motion.vertical.cycles = 1.0;
    sc->motion.baseline = 4;
    sc->motion.factor = 1.0;
    sc->timestep = (rd_timestep_def){RD_TIMESTEP_AUTO, 0.2, 0.0};
    sc->settle = (rd_settle_def){1, 1e-6, 5.0};
    sc->overturn = (rd_overturn_def){RD_OVERTURN_TILT_RATIO, 1.5, 1};
    sc->ref_restitution = -1.0;
    snprintf(sc->output.path, sizeof sc->output.path, "%s", "rockdem.h5");
    sc->output.interval = 0.005;
}

/* Baseline-corrects and scales the records once all of them are read; errors "name: ...". */
static int prepare_records(rd_scenario *sc, const char *name, rd_error *err)
{
    rd_error e;
    if (!rd_motion_has_records(&sc->motion) || rd_motion_prepare(&sc->motion, &e) == 0)
        return 0;
    return rd_error_set(err, "%s: %s", name, e.msg);
}

int rd_scenario_parse(rd_scenario *sc, const char *name, const char *text, rd_error *err)
{
    size_t len = strlen(text);
    int rc;
    rd_scenario_defaults(sc);
    snprintf(sc->file, sizeof sc->file, "%s", name);
    sc->text = malloc(len + 1);
    if (!sc->text)
        return rd_error_set(err, "%s: out of memory", name);
    memcpy(sc->text, text, len + 1);
    parser P = {.sc = sc, .err = err, .name = name, .p = sc->text, .bol = sc->text, .line = 1};
    while ((rc = lex_command(&P)) > 0)
        if (run_command(&P)) {
            rc = -1;
            break;
        }
    if (rc >= 0 && prepare_records(sc, name, err))
        rc = -1;
    if (rc < 0) {
        rd_scenario_free(sc);
        return -1;
    }
    return 0;
}

/* Reads all of f into a NUL-terminated malloc'ed buffer; NULL when out of memory. */
static char *slurp(FILE *f, size_t *len)
{
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    while (buf && !feof(f) && !ferror(f)) {
        if (n + 1 == cap) {
            char *grown = realloc(buf, cap * 2);
            if (!grown)
                free(buf);
            buf = grown;
            cap *= 2;
            continue;
        }
        n += fread(buf + n, 1, cap - n - 1, f);
    }
    if (buf)
        buf[n] = '\0';
    *len = n;
    return buf;
}

static int read_file(const char *path, char **out, size_t *len, rd_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return rd_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    errno = 0;
    *out = slurp(f, len);
    int bad = ferror(f), e = errno;
    fclose(f);
    if (*out && bad) {
        free(*out);
        *out = NULL;
        return rd_error_set(err, "%s: cannot read: %s", path, strerror(e));
    }
    if (!*out)
        return rd_error_set(err, "%s: out of memory", path);
    return 0;
}

int rd_scenario_load(rd_scenario *sc, const char *path, rd_error *err)
{
    char *text = NULL;
    size_t len = 0;
    rd_scenario_defaults(sc);
    if (read_file(path, &text, &len, err))
        return -1;
    if (strlen(text) != len) {
        free(text);
        return rd_error_set(err, "%s: contains a NUL byte (not a text file?)", path);
    }
    int rc = rd_scenario_parse(sc, path, text, err);
    free(text);
    return rc;
}

void rd_scenario_free(rd_scenario *sc)
{
    rd_motion_release(&sc->motion);
    for (int i = 0; i < sc->nbodies; i++) {
        free(sc->bodies[i].verts);
        sc->bodies[i].verts = NULL;
    }
    free(sc->text);
    sc->text = NULL;
}

/* ---- public: command-line overrides ---- */

typedef enum set_kind {
    S_NUMBER, /* a double at set_key.off */
    S_PULSE,  /* a double in the pulse, duration re-derived */
    S_SPACING,
    S_DAMPING,
    S_TIMESTEP,
    S_SETTLE,
    S_FILE,
    S_RECORD  /* a record setting: the records are re-read and/or re-processed */
} set_kind;

typedef struct set_key {
    const char *key;
    set_kind kind;
    size_t off; /* S_NUMBER: offset of the double in rd_scenario (rd_body_def for block keys);
                   S_PULSE: in rd_pulse_def */
    range range;
    unit unit;
} set_key;

static const set_key set_keys[] = {
    {"contact.stiffness-normal", S_NUMBER, offsetof(rd_scenario, contact.kn), R_POS, U_PLAIN},
    {"contact.stiffness-shear", S_NUMBER, offsetof(rd_scenario, contact.ks), R_POS, U_PLAIN},
    {"contact.friction", S_NUMBER, offsetof(rd_scenario, contact.friction), R_ANGLE, U_DEG},
    {"contact.cohesion", S_NUMBER, offsetof(rd_scenario, contact.cohesion), R_NONNEG, U_PLAIN},
    {"contact.tension", S_NUMBER, offsetof(rd_scenario, contact.tension), R_NONNEG, U_PLAIN},
    {"contact.spacing", S_SPACING, 0, R_NONNEG, U_PLAIN},
    {"contact.interface-seed", S_NUMBER, offsetof(rd_scenario, contact.perturb.seed), R_NONNEG, U_PLAIN},
    {"contact.interface-remove", S_NUMBER, offsetof(rd_scenario, contact.perturb.remove), R_NONNEG, U_PLAIN},
    {"contact.interface-raise", S_NUMBER, offsetof(rd_scenario, contact.perturb.raise), R_NONNEG, U_PLAIN},
    {"contact.interface-scatter", S_NUMBER, offsetof(rd_scenario, contact.perturb.scatter), R_NONNEG, U_PLAIN},
    {"model.gravity", S_NUMBER, offsetof(rd_scenario, gravity), R_NONNEG, U_ACCEL},
    {"model.density", S_NUMBER, offsetof(rd_scenario, density), R_POS, U_PLAIN},
    {"model.duration", S_NUMBER, offsetof(rd_scenario, duration), R_POS, U_PLAIN},
    {"model.damping", S_DAMPING, 0, R_ANY, U_PLAIN},
    {"model.timestep", S_TIMESTEP, 0, R_POS, U_PLAIN},
    {"model.safety", S_NUMBER, offsetof(rd_scenario, timestep.safety), R_FRAC, U_PLAIN},
    {"model.settle", S_SETTLE, 0, R_ANY, U_PLAIN},
    {"motion.amplitude", S_PULSE, offsetof(rd_pulse_def, amplitude), R_ANY, U_ACCEL},
    {"motion.frequency", S_PULSE, offsetof(rd_pulse_def, frequency), R_POS, U_PLAIN},
    {"motion.duration", S_PULSE, offsetof(rd_pulse_def, duration), R_POS, U_PLAIN},
    {"motion.direction", S_RECORD, offsetof(rd_pulse_def, direction), R_ANY, U_DEG},
    {"motion.cycles", S_PULSE, offsetof(rd_pulse_def, cycles), R_POS, U_PLAIN},
    {"motion.start", S_PULSE, offsetof(rd_pulse_def, start), R_NONNEG, U_PLAIN},
    {"motion.vertical-amplitude", S_PULSE, offsetof(rd_pulse_def, amplitude), R_ANY, U_ACCEL},
    {"motion.scale", S_RECORD, 0, R_POS, U_PLAIN},
    {"motion.scale-pga", S_RECORD, 0, R_POS, U_ACCEL},
    {"motion.scale-pgv", S_RECORD, 0, R_POS, U_PLAIN},
    {"motion.baseline", S_RECORD, 0, R_ANY, U_PLAIN},
    {"motion.file", S_RECORD, 0, R_ANY, U_PLAIN},
    {"motion.record", S_RECORD, 0, R_ANY, U_PLAIN},
    {"motion.seed", S_RECORD, 0, R_NONNEG, U_PLAIN},
    {"model.tail", S_NUMBER, offsetof(rd_scenario, tail), R_NONNEG, U_PLAIN},
    {"output.file", S_FILE, 0, R_ANY, U_PLAIN},
    {"output.interval", S_NUMBER, offsetof(rd_scenario, output.interval), R_POS, U_PLAIN},
    {"reference.restitution", S_NUMBER, offsetof(rd_scenario, ref_restitution), R_FRAC, U_PLAIN},
};

static const set_key body_keys[] = {
    {"density", S_NUMBER, offsetof(rd_body_def, density), R_POS, U_PLAIN},
    {"mass", S_NUMBER, offsetof(rd_body_def, mass), R_POS, U_PLAIN},
    {"tilt", S_NUMBER, offsetof(rd_body_def, tilt), R_ANGLE, U_DEG},
    {"direction", S_NUMBER, offsetof(rd_body_def, tilt_direction), R_ANY, U_DEG},
};

#define NSET_KEYS (sizeof set_keys / sizeof set_keys[0])
#define NBODY_KEYS (sizeof body_keys / sizeof body_keys[0])

typedef struct setter {
    rd_scenario *sc;
    rd_error *err;
    const char *a;     /* the whole assignment, for messages */
    const char *value; /* after the '=' */
} setter;

static int serr(const setter *S, const char *fmt, ...) RD_PRINTF(2, 3);

static int serr(const setter *S, const char *fmt, ...)
{
    char msg[RD_ERROR_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return rd_error_set(S->err, "--set %s: %s", S->a, msg);
}

static int same_key(const char *key, const char *s, size_t len)
{
    return strlen(key) == len && strncasecmp(key, s, len) == 0;
}

/* Parses text as a number in range r (as written) and converts it to SI. */
static int set_parse(const setter *S, const char *text, range r, unit u, double *v)
{
    if (parse_number(text, strlen(text), u == U_ACCEL, v))
        return serr(S, "expected a number, got '%s'", text);
    const char *bad = range_error(*v, r);
    if (bad)
        return serr(S, "value %s", bad);
    *v *= unit_scale(u);
    return 0;
}

static double *field(void *base, size_t off) { return (double *)((char *)base + off); }

static int set_pulse(const setter *S, const set_key *k)
{
    int vertical = strcmp(k->key, "motion.vertical-amplitude") == 0;
    rd_pulse_def *p = vertical ? &S->sc->motion.vertical : &S->sc->motion.horizontal;
    double v;
    if (p->kind == RD_PULSE_NONE)
        return serr(S, "the scenario has no %s ground-motion pulse",
                    vertical ? "vertical" : "horizontal");
    if (k->off == offsetof(rd_pulse_def, duration) && is_periodic(p->kind))
        return serr(S, "motion.duration applies only to rectangular and triangle pulses "
                       "(set motion.frequency)");
    if (k->off == offsetof(rd_pulse_def, cycles) && p->kind != RD_PULSE_HARMONIC)
        return serr(S, "motion.cycles applies only to harmonic pulses");
    if (set_parse(S, S->value, k->range, k->unit, &v))
        return -1;
    *field(p, k->off) = v;
    if (k->off == offsetof(rd_pulse_def, duration))
        p->frequency = 0.0;
    p->duration = pulse_duration(p);
    return 0;
}

static int set_spacing(const setter *S)
{
    double v;
    if (strcasecmp(S->value, "auto") == 0 || strcasecmp(S->value, "vertices") == 0) {
        S->sc->contact.spacing = strcasecmp(S->value, "auto") == 0 ? -1.0 : 0.0;
        return 0;
    }
    if (parse_number(S->value, strlen(S->value), 0, &v))
        return serr(S, "expected a number, auto or vertices, got '%s'", S->value);
    if (v < 0)
        return serr(S, "value must be >= 0");
    S->sc->contact.spacing = v;
    return 0;
}

/* "none", "viscous <ratio>" or "local <alpha>". */
static int set_damping(const setter *S)
{
    const char *v = S->value;
    size_t wl = strcspn(v, " \t");
    const char *arg = v + wl + strspn(v + wl, " \t");
    rd_damping_def *d = &S->sc->damping;
    double x = 0.0;
    if (same_key("none", v, wl) && *arg == '\0')
        d->kind = RD_DAMPING_NONE;
    else if (same_key("viscous", v, wl) && *arg)
        d->kind = RD_DAMPING_VISCOUS;
    else if (same_key("local", v, wl) && *arg)
        d->kind = RD_DAMPING_LOCAL;
    else
        return serr(S, "expected none, viscous <ratio> or local <alpha>, got '%s'", v);
    if (d->kind != RD_DAMPING_NONE &&
        set_parse(S, arg, d->kind == RD_DAMPING_VISCOUS ? R_DAMP : R_OPEN01, U_PLAIN, &x))
        return -1;
    d->value = x;
    return 0;
}

static int set_timestep(const setter *S)
{
    rd_timestep_def *ts = &S->sc->timestep;
    double dt;
    if (strcasecmp(S->value, "auto") == 0) {
        ts->kind = RD_TIMESTEP_AUTO;
        return 0;
    }
    if (parse_number(S->value, strlen(S->value), 0, &dt))
        return serr(S, "expected auto or a time step in s, got '%s'", S->value);
    if (!(dt > 0))
        return serr(S, "value must be > 0");
    ts->kind = RD_TIMESTEP_FIXED;
    ts->dt = dt;
    return 0;
}

static int set_settle(const setter *S)
{
    if (strcasecmp(S->value, "on") != 0 && strcasecmp(S->value, "off") != 0)
        return serr(S, "expected on or off, got '%s'", S->value);
    S->sc->settle.enabled = strcasecmp(S->value, "on") == 0;
    return 0;
}

static int set_file(const setter *S)
{
    size_t len = strlen(S->value);
    if (len == 0)
        return serr(S, "empty file name");
    if (len >= RD_PATH_MAX)
        return serr(S, "file name longer than %d characters", RD_PATH_MAX - 1);
    memcpy(S->sc->output.path, S->value, len + 1);
    return 0;
}

/* The text of a --set value into dst (size), refusing empty or too long ones. */
static int set_text(const setter *S, char *dst, size_t size)
{
    size_t len = strlen(S->value);
    if (len == 0 || len >= size)
        return serr(S, "expected 1 to %zu characters", size - 1);
    memcpy(dst, S->value, len + 1);
    return 0;
}

/* motion.file (h1's file, relative to the scenario's directory), motion.seed (h1's generator),
 * motion.record (every FEMA component): change the source and re-read it. */
static int set_record_source(const setter *S, const char *key)
{
    rd_motion_def *m = &S->sc->motion;
    rd_component_def *h1 = &m->record[RD_H1];
    rd_error e;
    double seed;
    int n = 0;
    if (strcmp(key, "motion.record") == 0) {
        for (int c = 0; c < RD_NCOMPONENTS; c++) {
            if (m->record[c].source != RD_SOURCE_FEMA)
                continue;
            if (set_text(S, m->record[c].record, sizeof m->record[c].record))
                return -1;
            if (rd_motion_load(m, c, &e))
                return serr(S, "%s", e.msg);
            n++;
        }
        return n ? 0 : serr(S, "no ground-motion record comes from a FEMA P695 set");
    }
    if (strcmp(key, "motion.seed") == 0) {
        if (h1->source != RD_SOURCE_STOCHASTIC)
            return serr(S, "the h1 ground motion is not 'ground-motion stochastic'");
        if (set_parse(S, S->value, R_NONNEG, U_PLAIN, &seed))
            return -1;
        if (seed != floor(seed) || seed > 4294967295.0)
            return serr(S, "expected a whole number in [0, 2^32)");
        h1->stochastic.seed = (unsigned long)seed;
    } else if (h1->source == RD_SOURCE_NONE || h1->source == RD_SOURCE_STOCHASTIC) {
        return serr(S, "the h1 ground motion is not 'ground-motion import'");
    } else if (!S->value[0] || resolve_path(S->sc->file, S->value, h1->path, sizeof h1->path)) {
        return serr(S, "expected a file name of at most %d characters", RD_PATH_MAX - 1);
    } else if ((h1->source == RD_SOURCE_FEMA) != (source_of(S->value) == RD_SOURCE_FEMA)) {
        return serr(S, "motion.file keeps the kind of file: a FEMA P695 set (.h5) or a record");
    } else {
        h1->source = source_of(S->value); /* the extension picks AT2 or text */
    }
    return rd_motion_load(m, RD_H1, &e) ? serr(S, "%s", e.msg) : 0;
}

/* motion.baseline: a degree 2..8 or off. */
static int set_baseline(const setter *S, int *degree)
{
    double v;
    if (strcasecmp(S->value, "off") == 0) {
        *degree = 0;
        return 0;
    }
    if (parse_number(S->value, strlen(S->value), 0, &v) || v != floor(v) || v < 2 || v > 8)
        return serr(S, "expected a degree (2 to 8) or off, got '%s'", S->value);
    *degree = (int)v;
    return 0;
}

/* Record settings: re-read (file, record, seed) and re-process (every key) the records. */
static int set_record(const setter *S, const set_key *k)
{
    static const char *const scales[] = {"motion.scale", "motion.scale-pga", "motion.scale-pgv", NULL};
    static const rd_scale_kind kinds[] = {RD_SCALE_FACTOR, RD_SCALE_PGA, RD_SCALE_PGV};
    rd_motion_def *m = &S->sc->motion;
    rd_error e;
    int rc = 0;
    if (!rd_motion_has_records(m)) {
        if (strcmp(k->key, "motion.direction") == 0)
            return set_pulse(S, k);
        return serr(S, "the scenario has no ground-motion record (ground-motion import or stochastic)");
    }
    if (strcmp(k->key, "motion.direction") == 0) {
        double v;
        if (set_parse(S, S->value, k->range, k->unit, &v))
            return -1;
        m->direction = v;
        return 0;
    }
    for (int i = 0; scales[i]; i++) {
        double v;
        if (strcmp(k->key, scales[i]) != 0)
            continue;
        if (set_parse(S, S->value, k->range, k->unit, &v))
            return -1;
        m->scale = kinds[i];
        m->scale_value = v;
    }
    if (strcmp(k->key, "motion.baseline") == 0)
        rc = set_baseline(S, &m->baseline);
    else if (strncmp(k->key, "motion.scale", 12) != 0)
        rc = set_record_source(S, k->key);
    if (rc)
        return -1;
    return rd_motion_prepare(m, &e) ? serr(S, "%s", e.msg) : 0;
}

static int set_apply(const setter *S, const set_key *k)
{
    double v;
    switch (k->kind) {
    case S_NUMBER:
        if (set_parse(S, S->value, k->range, k->unit, &v))
            return -1;
        *field(S->sc, k->off) = v;
        return 0;
    case S_PULSE: return set_pulse(S, k);
    case S_SPACING: return set_spacing(S);
    case S_DAMPING: return set_damping(S);
    case S_TIMESTEP: return set_timestep(S);
    case S_SETTLE: return set_settle(S);
    case S_FILE: return set_file(S);
    case S_RECORD: return set_record(S, k);
    }
    return 0;
}

/* Unknown key: lists the keys of its section, or the sections. */
static int unknown_key(const setter *S, const char *key, size_t len)
{
    char list[RD_ERROR_MAX / 2] = "";
    size_t sect = strcspn(key, ".=") + 1; /* section length with its dot */
    for (size_t i = 0; i < NSET_KEYS; i++)
        if (sect <= len && strncasecmp(set_keys[i].key, key, sect) == 0)
            append(list, sizeof list, set_keys[i].key);
    if (list[0] == '\0')
        snprintf(list, sizeof list, "a key in contact, model, motion, output or block.<name>");
    return serr(S, "unknown key '%.*s' (expected %s)", (int)len, key, list);
}

/* key = "<name>.<field>" after "block." */
static int set_body(const setter *S, const char *key, size_t len)
{
    size_t nlen = len;
    while (nlen > 0 && key[nlen - 1] != '.')
        nlen--;
    if (nlen < 2)
        return serr(S, "expected block.<name>.<field>");
    int i = find_body(S->sc, key, nlen - 1);
    if (i < 0)
        return serr(S, "unknown block '%.*s'", (int)(nlen - 1), key);
    rd_body_def *b = &S->sc->bodies[i];
    const char *f = key + nlen;
    size_t flen = len - nlen;
    for (size_t j = 0; j < NBODY_KEYS; j++) {
        const set_key *k = &body_keys[j];
        double v;
        if (!same_key(k->key, f, flen))
            continue;
        if (b->fixed && k->unit == U_DEG)
            return serr(S, "block '%s' is fixed; %s applies only to free blocks", b->name, k->key);
        if (set_parse(S, S->value, k->range, k->unit, &v))
            return -1;
        *field(b, k->off) = v;
        if (k->off == offsetof(rd_body_def, density))
            b->mass = 0.0;
        if (k->off == offsetof(rd_body_def, mass))
            b->density = 0.0;
        return 0;
    }
    return serr(S, "unknown key '%.*s' (expected block.%s.density, mass, tilt or direction)",
                (int)flen, f, b->name);
}

/* Records the override in sc->text as a comment line "; --set <assignment>". */
static int append_override(rd_scenario *sc, const char *a, rd_error *err)
{
    size_t old = sc->text ? strlen(sc->text) : 0;
    int nl = old > 0 && sc->text[old - 1] != '\n';
    char *t = realloc(sc->text, old + (size_t)nl + strlen(a) + sizeof "; --set \n");
    if (!t)
        return rd_error_set(err, "--set %s: out of memory", a);
    sprintf(t + old, "%s; --set %s\n", nl ? "\n" : "", a);
    sc->text = t;
    return 0;
}

/* Length of a "block." or "body." prefix of key, else 0. */
static size_t body_prefix(const char *key, size_t len)
{
    if (len > 6 && strncasecmp(key, "block.", 6) == 0)
        return 6;
    if (len > 5 && strncasecmp(key, "body.", 5) == 0)
        return 5;
    return 0;
}

static int set_key_value(const setter *S, const char *key, size_t len)
{
    size_t pre = body_prefix(key, len);
    if (pre)
        return set_body(S, key + pre, len - pre);
    for (size_t i = 0; i < NSET_KEYS; i++)
        if (same_key(set_keys[i].key, key, len))
            return set_apply(S, &set_keys[i]);
    return unknown_key(S, key, len);
}

int rd_scenario_set(rd_scenario *sc, const char *assignment, rd_error *err)
{
    setter S = {sc, err, assignment, NULL};
    const char *eq = strchr(assignment, '=');
    if (strchr(assignment, '\n'))
        return serr(&S, "contains a line break");
    if (!eq || eq == assignment)
        return serr(&S, "expected section.key=value");
    S.value = eq + 1;
    if (set_key_value(&S, assignment, (size_t)(eq - assignment)))
        return -1;
    return append_override(sc, assignment, err);
}

/* ---- public: validation ---- */

/* NULL, or what is wrong with the scenario-wide settings. */
static const char *model_problem(const rd_scenario *sc)
{
    const rd_contact_def *c = &sc->contact;
    const rd_damping_def *d = &sc->damping;
    const double right = 90.0 * DEG;
    if (sc->nbodies < 0 || sc->nbodies > RD_MAX_BODIES)
        return "too many blocks";
    if (!(sc->gravity >= 0))
        return "gravity must be >= 0";
    if (!(sc->density > 0))
        return "density must be > 0";
    if (!(c->kn > 0) || !(c->ks > 0))
        return "contact stiffness-normal and stiffness-shear must be > 0";
    if (!(c->friction >= 0 && c->friction < right))
        return "contact friction must be in [0, 90) degrees";
    if (!(c->cohesion >= 0) || !(c->tension >= 0))
        return "contact cohesion and tension must be >= 0";
    if (!isfinite(c->spacing))
        return "contact spacing must be a number";
    if (d->kind == RD_DAMPING_VISCOUS && !(d->value > 0 && d->value <= 10))
        return "viscous damping ratio must be in (0, 10]";
    if (d->kind == RD_DAMPING_LOCAL && !(d->value > 0 && d->value < 1))
        return "local damping alpha must be in (0, 1)";
    if (sc->timestep.kind == RD_TIMESTEP_AUTO &&
        !(sc->timestep.safety > 0 && sc->timestep.safety <= 1))
        return "timestep safety must be in (0, 1]";
    if (sc->timestep.kind == RD_TIMESTEP_FIXED && !(sc->timestep.dt > 0))
        return "fixed timestep must be > 0";
    if (sc->settle.enabled && !(sc->settle.ratio > 0 && sc->settle.max_time > 0))
        return "settle ratio and time-limit must be > 0";
    if (!(sc->overturn.value > 0) && !(sc->overturn.kind == RD_OVERTURN_OFF && sc->overturn.value == 0))
        return "overturn criterion must be > 0 (off-pedestal: >= 0)";
    if (sc->output.path[0] == '\0' || !(sc->output.interval > 0))
        return "output needs a file name and an interval > 0";
    return NULL;
}

static const char *body_problem(const rd_scenario *sc, int i)
{
    const rd_body_def *b = &sc->bodies[i];
    if (b->shape == RD_SHAPE_BRICK && !(b->size[0] > 0 && b->size[1] > 0 && b->size[2] > 0))
        return "size must be > 0";
    if (b->shape == RD_SHAPE_PRISM && !(b->sides >= 3 && b->radius > 0 && b->radius_top > 0 && b->size[2] > 0))
        return "a prism needs sides >= 3, radii > 0 and height > 0";
    if (b->shape == RD_SHAPE_HULL && !(b->nverts >= 4 && b->verts))
        return "a polyhedron needs at least 4 vertices";
    if (b->shape == RD_SHAPE_MESH && b->mesh[0] == '\0')
        return "a mesh needs a file";
    if (!(b->mass >= 0))
        return "mass must be > 0 (or 0 to use the density)";
    if (!(b->tilt >= 0 && b->tilt < 90.0 * DEG))
        return "tilt must be in [0, 90) degrees";
    if (find_body(sc, b->name, strlen(b->name)) != i)
        return "name used by an earlier block";
    if (!valid_name(b->name, strlen(b->name)))
        return "invalid name";
    return NULL;
}

static const char *pulse_problem(const rd_pulse_def *p)
{
    if (p->kind == RD_PULSE_NONE)
        return NULL;
    if (!isfinite(p->amplitude) || !(p->start >= 0))
        return "amplitude must be a number and start >= 0";
    if (is_periodic(p->kind) && !(p->frequency > 0))
        return "frequency must be > 0";
    if (p->kind == RD_PULSE_HARMONIC && !(p->cycles > 0))
        return "cycles must be > 0";
    if (!(p->duration > 0))
        return "duration must be > 0";
    return NULL;
}

static const char *records_problem(const rd_motion_def *m)
{
    for (int c = 0; c < RD_NCOMPONENTS; c++)
        if (m->record[c].source != RD_SOURCE_NONE && !m->record[c].applied)
            return "a ground-motion record is defined but not loaded";
    if (m->baseline != 0 && (m->baseline < 2 || m->baseline > 8))
        return "record baseline degree must be 2 to 8 (or off)";
    if (m->scale != RD_SCALE_NONE && !(m->scale_value > 0))
        return "record scale must be > 0";
    if (!isfinite(m->direction))
        return "record direction must be a number";
    return NULL;
}

int rd_scenario_validate(const rd_scenario *sc, rd_error *err)
{
    const char *f = sc->file, *bad;
    int nfree = 0;
    for (int i = 0; i < sc->nbodies && i < RD_MAX_BODIES; i++)
        nfree += !sc->bodies[i].fixed;
    if (nfree == 0)
        return rd_error_set(err,
                            "%s: no free block (add 'block create brick ...' without 'fixed')", f);
    if (!(sc->duration > 0))
        return rd_error_set(err, "%s: no duration (add 'model solve time <s>')", f);
    if ((bad = model_problem(sc)))
        return rd_error_set(err, "%s: %s", f, bad);
    for (int i = 0; i < sc->nbodies; i++)
        if ((bad = body_problem(sc, i)))
            return rd_error_set(err, "%s:%d: block '%s': %s", f, sc->bodies[i].line,
                                sc->bodies[i].name, bad);
    if ((bad = pulse_problem(&sc->motion.horizontal)))
        return rd_error_set(err, "%s:%d: horizontal pulse: %s", f, sc->motion.horizontal.line, bad);
    if ((bad = pulse_problem(&sc->motion.vertical)))
        return rd_error_set(err, "%s:%d: vertical pulse: %s", f, sc->motion.vertical.line, bad);
    if ((bad = records_problem(&sc->motion)))
        return rd_error_set(err, "%s: %s", f, bad);
    if (!(sc->tail >= 0))
        return rd_error_set(err, "%s: solve tail must be >= 0", f);
    return 0;
}
