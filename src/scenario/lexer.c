/* rockdem — scenario lexer: tokens of one command (continuation lines, quotes, comments)
 * and the keyword readers every command uses; errors are "file:line:col: message".
 * Folder scenario/ owns the scenario language (parse, --set overrides, validation); it may call
 * base/, records/ and geometry/, never engine/, io/ or cli/.
 */
#include "scenario/parse.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int perr(const parser *P, const token *t, const char *fmt, ...)
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
    *t = (token){ s, 0, P->line, (int)(s - P->bol) + 1, *s == '\'' || *s == '"' };
    if (!t->quoted) {
        while (!ends_word(*P->p)) P->p++;
        t->len = (int)(P->p - s);
        return 0;
    }
    while (*e && *e != '\n' && *e != *s) e++;
    if (*e != *s) return perr(P, t, "unterminated string (missing closing %c)", *s);
    t->s = s + 1;
    t->len = (int)(e - s - 1);
    P->p = e + 1;
    if (!ends_word(*P->p)) {
        token g = { P->p, 1, P->line, (int)(P->p - P->bol) + 1, 0 };
        return perr(P, &g, "expected a space after the closing quote");
    }
    return 0;
}

/* Reads the next command (one line, or several joined by '&') into P->tok.
 * Returns 1 when a command was read, 0 at the end of the text, -1 on error. */
int lex_command(parser *P)
{
    token amp = { 0 }, t; /* amp.s: a pending '&' on the current line */
    P->n = P->cur = 0;
    for (;;) {
        char c = *P->p;
        if (c == '\0' && amp.s) return perr(P, &amp, "'&' continuation at end of file");
        if (c == '\0') return P->n > 0;
        if (c == '\n') {
            P->p++;
            P->line++;
            P->bol = P->p;
            if (amp.s && *P->p == '\0') return perr(P, &amp, "'&' continuation at end of file");
            if (!amp.s && P->n > 0) return 1;
            amp.s = NULL;
        } else if (is_blank(c)) {
            P->p++;
        } else if (c == ';') {
            while (*P->p && *P->p != '\n') P->p++;
        } else {
            if (lex_token(P, &t)) return -1;
            if (amp.s) return perr(P, &amp, "'&' must be the last token on its line");
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

const token *take(parser *P) { return P->cur < P->n ? &P->tok[P->cur++] : NULL; }

const token *verb_token(const parser *P) { return &P->tok[1]; }

int tok_is(const token *t, const char *word)
{
    return (size_t)t->len == strlen(word) && strncasecmp(t->s, word, (size_t)t->len) == 0;
}

int find_word(const token *t, const char *const *names)
{
    for (int i = 0; names[i]; i++)
        if (tok_is(t, names[i])) return i;
    return -1;
}

void join(char *buf, size_t size, const char *const *names)
{
    buf[0] = '\0';
    for (int i = 0; names[i]; i++) append(buf, size, names[i]);
}

/* Takes the next keyword of the command: its index in names (NULL-terminated), KW_END after
 * the last token, or KW_ERR for an unknown or repeated keyword. *seen collects the indices. */
int next_keyword(parser *P, const char *const *names, unsigned *seen, const token **kw)
{
    char list[256];
    const token *t = take(P);
    if (!t) return KW_END;
    int k = find_word(t, names);
    if (k < 0) {
        join(list, sizeof list, names);
        return perr(P, t, "unknown keyword '%.*s' for '%s' (expected %s)", t->len, t->s, P->ctx,
                    list);
    }
    if (*seen & (1u << k)) return perr(P, t, "keyword '%.*s' given twice", t->len, t->s);
    *seen |= 1u << k;
    *kw = t;
    return k;
}

/* Error for a command that needs at least one of its keywords. */
int missing_keyword(parser *P, const char *const *names)
{
    char list[256];
    join(list, sizeof list, names);
    return perr(P, verb_token(P), "missing keyword after '%s' (expected %s)", P->ctx, list);
}

int keywords_end(parser *P, int k, int found, const char *const *names)
{
    if (k == KW_ERR) return -1;
    return found ? 0 : missing_keyword(P, names);
}

/* Keywords that exclude each other: remembers the first in *prev, refuses a second. */
int exclusive(parser *P, const token **prev, const token *kw)
{
    if (*prev)
        return perr(P, kw, "'%.*s' cannot be combined with '%.*s'", kw->len, kw->s, (*prev)->len,
                    (*prev)->s);
    *prev = kw;
    return 0;
}

int one_keyword(parser *P, const char *const *names)
{
    const token *kw, *prev = NULL;
    unsigned seen = 0;
    int k, found = -1;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        if (exclusive(P, &prev, kw)) return -1;
        found = k;
    }
    return keywords_end(P, k, prev != NULL, names) ? -1 : found;
}

int expect_end(parser *P)
{
    const token *t = take(P);
    if (t) return perr(P, t, "unexpected '%.*s' after '%s'", t->len, t->s, P->ctx);
    return 0;
}

/* Reads n numbers after keyword kw, each checked against r (as written) and converted to SI. */
int read_values(parser *P, const token *kw, int n, range r, unit u, double *v)
{
    for (int i = 0; i < n; i++) {
        const token *t = take(P);
        if (!t) return perr(P, kw, "expected a number after '%.*s'", kw->len, kw->s);
        if (parse_number(t->s, (size_t)t->len, u == U_ACCEL, &v[i]))
            return perr(P, t, "expected a number after '%.*s', got '%.*s'", kw->len, kw->s, t->len,
                        t->s);
        const char *bad = range_error(v[i], r);
        if (bad) return perr(P, t, "'%.*s' %s, got %.*s", kw->len, kw->s, bad, t->len, t->s);
        char why[128];
        if ((bad = limit_error(kw->s, (size_t)kw->len, v[i], why, sizeof why)))
            return perr(P, t, "'%.*s' %.*s %s", kw->len, kw->s, t->len, t->s, bad);
        v[i] = unit_si(v[i], u);
    }
    return 0;
}

int read_value(parser *P, const token *kw, range r, unit u, double *v)
{
    return read_values(P, kw, 1, r, u, v);
}

int read_switch(parser *P, const token *kw, int *on)
{
    const token *t = take(P);
    if (!t) return perr(P, kw, "expected on or off after '%.*s'", kw->len, kw->s);
    if (!tok_is(t, "on") && !tok_is(t, "off"))
        return perr(P, t, "expected on or off after '%.*s', got '%.*s'", kw->len, kw->s, t->len,
                    t->s);
    *on = tok_is(t, "on");
    return 0;
}

/* Reads a block name after kw into dst (RD_NAME_MAX); *name keeps its token for messages. */
int read_name(parser *P, const token *kw, const token **name, char *dst)
{
    const token *t = take(P);
    if (!t) return perr(P, kw, "expected a name after '%.*s'", kw->len, kw->s);
    if (!valid_name(t->s, (size_t)t->len))
        return perr(P, t, "invalid block name '%.*s' (1 to %d letters, digits, '_' or '-')", t->len,
                    t->s, RD_NAME_MAX - 1);
    memcpy(dst, t->s, (size_t)t->len);
    dst[t->len] = '\0';
    *name = t;
    return 0;
}

/* Reads a text token (title, path) into dst of the given size; what names it in messages. */
int read_text(parser *P, const char *what, char *dst, size_t size)
{
    const token *t = take(P);
    if (!t) return perr(P, verb_token(P), "expected %s after '%s'", what, P->ctx);
    if (t->len == 0) return perr(P, t, "empty %s", what);
    if ((size_t)t->len >= size) return perr(P, t, "%s longer than %zu characters", what, size - 1);
    memcpy(dst, t->s, (size_t)t->len);
    dst[t->len] = '\0';
    return 0;
}

/* ---- settings given once ---- */

int setting_line(const parser *P, const char *what)
{
    for (int i = 0; i < P->nsettings; i++)
        if (!strcmp(P->settings[i].what, what)) return P->settings[i].line;
    return 0;
}

int setting_once(parser *P, const token *t, const char *what)
{
    int first = setting_line(P, what);
    if (first)
        return perr(P, t, "%s already given on line %d; give each setting once", what, first);
    if (P->nsettings == P->settings_cap) {
        int cap = P->settings_cap ? 2 * P->settings_cap : 32;
        setting *grown = realloc(P->settings, (size_t)cap * sizeof *grown);
        if (!grown) return perr(P, t, "out of memory");
        P->settings = grown;
        P->settings_cap = cap;
    }
    setting *s = &P->settings[P->nsettings++];
    snprintf(s->what, sizeof s->what, "%s", what);
    s->line = t->line;
    return 0;
}

int keyword_once(parser *P, const token *kw, const char *name)
{
    char what[sizeof((setting *)0)->what];
    snprintf(what, sizeof what, "'%s' of '%s'", name, P->ctx);
    return setting_once(P, kw, what);
}

int command_once(parser *P)
{
    char what[sizeof((setting *)0)->what];
    snprintf(what, sizeof what, "'%s'", P->ctx);
    return setting_once(P, &P->tok[0], what);
}
