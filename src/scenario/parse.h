/* rockdem (private) — what the scenario files share: value ranges and units, the lexer's tokens
 * and parser state, the keyword readers and the command handlers.
 *
 * Folder scenario/ owns the text language (parse, `--set` overrides, validation) and fills the
 * public rd_scenario (include/rockdem/scenario.h). It may call base/, records/ (reading and
 * generating ground motions) and geometry/ (assembly builders); never engine/, io/ or cli/.
 */
#ifndef RD_SCENARIO_PARSE_H
#define RD_SCENARIO_PARSE_H

#include "base/constants.h"
#include "rockdem/motion.h"
#include "rockdem/record.h"
#include "rockdem/scenario.h"
#include "scenario/name_index.h"

#include <stddef.h>

#if defined(__GNUC__)
#define RD_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define RD_PRINTF(f, a)
#endif

#define MAX_TOKENS 1024 /* tokens in one command, continuation lines included */

/* ---- values (values.c): numbers, ranges, units; shared by the parser and rd_scenario_set ---- */

typedef enum range {
    R_ANY,    /* any finite number */
    R_POS,    /* > 0 */
    R_NONNEG, /* >= 0 */
    R_FRAC,   /* (0, 1] */
    R_DAMP,   /* (0, 10]: a viscous damping ratio (above 1: over-critical contact dashpots) */
    R_OPEN01, /* (0, 1) */
    R_UNIT,   /* [0, 1] */
    R_ANGLE,  /* [0, 90) degrees */
    R_TURN    /* (0, 180] degrees */
} range;

typedef enum unit {
    U_PLAIN, /* stored as written */
    U_DEG,   /* written in degrees, stored in rad */
    U_ACCEL, /* m/s^2, or a number with a `g` suffix times RD_G_STANDARD */
    U_MU     /* a friction coefficient mu = tan(phi), stored as the angle phi = atan(mu), rad */
} unit;

/* Parses s[0..len) as a C floating-point number; with accel a trailing 'g' multiplies by
 * RD_G_STANDARD. Returns 0, or -1 when it is not a whole finite number. */
int parse_number(const char *s, size_t len, int accel, double *v);
/* NULL when v (as written: degrees for angles) lies in r, else what it must be. */
const char *range_error(double v, range r);
/* NULL when v (as written) lies in keyword kw[0..len)'s valid range (values.c's table,
 * docs/LIMITS.md), else the message, written into buf. */
const char *limit_error(const char *kw, size_t len, double v, char *buf, size_t size);
/* NULL when a subcontact spacing (m) is valid, else why not: 0, or outside its limits. */
const char *spacing_error(double v, char *buf, size_t size);
/* A number v as written in unit u, in SI (degrees to rad, a friction coefficient to its angle). */
double unit_si(double v, unit u);
int is_periodic(rd_pulse_kind k);
/* Duration of a pulse, s (one period, cycles periods, 1/frequency or the given duration). */
double pulse_duration(const rd_pulse_def *p);
/* Block names double as override keys (block.<name>.density): letters, digits, '_' and '-'. */
int valid_name(const char *s, size_t len);
/* Index of the body named name[0..len), or -1. */
int find_body(const rd_scenario *sc, const char *name, size_t len);
/* Room for one more body in sc->bodies (scenario.c). 0, or -1 without memory. */
int rd_scenario_grow(rd_scenario *sc);
/* Appends ", word" (or "word" to an empty buf), truncating quietly. */
void append(char *buf, size_t size, const char *word);
/* Resolves a file name relative to the directory of the scenario file `base` into dst. */
int resolve_path(const char *base, const char *file, char *dst, size_t size);
/* Format from the file's extension: .at2, .h5/.hdf5 (FEMA P695 set), else text. */
rd_record_source source_of(const char *file);

/* ---- lexer (lexer.c) ---- */

typedef struct token {
    const char *s; /* text, quotes stripped; not NUL-terminated */
    int len;
    int line, col; /* 1-based position of the first character (the quote for strings) */
    int quoted;
} token;

/* A single-valued setting given in the scenario ('model gravity', 'friction' of 'contact
 * property', ...) and the line that gave it: a second one is refused (setting_once). */
typedef struct setting {
    char what[2 * RD_NAME_MAX + 96]; /* as the message names it; also the key */
    int line;
} setting;

typedef struct parser {
    rd_scenario *sc;
    rd_error *err;
    const char *name;      /* file name for messages */
    const char *p;         /* next character */
    const char *bol;       /* first character of the current line */
    int line;              /* current line, 1-based */
    token tok[MAX_TOKENS]; /* the current command */
    int n;                 /* its tokens */
    int cur;               /* next token to take */
    char ctx[64];          /* "noun verb", for messages */
    int motion_line[3];    /* lines that set the records' direction, scale, baseline (0: none) */
    setting *settings;     /* single-valued settings given so far (malloc'ed; freed by the parse) */
    int nsettings, settings_cap;
    rd_name_index names; /* the bodies so far by name (freed by the parse) */
} parser;

enum { KW_ERR = -1, KW_END = -2 };

/* Index of the body named name[0..len) created so far, or -1 (find_body through P->names). */
int parse_find_body(parser *P, const char *name, size_t len);

/* Sets err to "file:line:col: message" at token t; returns -1. */
int perr(const parser *P, const token *t, const char *fmt, ...) RD_PRINTF(3, 4);
/* Reads the next command's tokens into P->tok: 1 (a command), 0 (end of text) or -1. */
int lex_command(parser *P);
const token *take(parser *P);
const token *verb_token(const parser *P);
int tok_is(const token *t, const char *word);
int find_word(const token *t, const char *const *names);
void join(char *buf, size_t size, const char *const *names);
/* The next keyword of the command: its index in names (NULL-terminated), KW_END after the last
 * token, or KW_ERR for an unknown or repeated keyword. *seen collects the indices. */
int next_keyword(parser *P, const char *const *names, unsigned *seen, const token **kw);
int missing_keyword(parser *P, const char *const *names);
/* The end of a keyword loop that stopped at k: -1 after an error (KW_ERR), else 0 when a
 * keyword was found, else the missing-keyword error. */
int keywords_end(parser *P, int k, int found, const char *const *names);
int exclusive(parser *P, const token **prev, const token *kw);
/* A command of exactly one of names (NULL-terminated) and nothing after it: its index, or -1
 * (err set: missing, unknown or a second keyword). */
int one_keyword(parser *P, const char *const *names);
int expect_end(parser *P);
/* The line that gave the setting `what` (setting_once's name), or 0 when none has. */
int setting_line(const parser *P, const char *what);
/* A single-valued setting `what` ("'model gravity'", "'friction' of 'contact property'") given
 * at token t: 0 the first time (its line kept), else -1 with err "file:line:col: WHAT already
 * given on line N ..." (a repeat silently replaced the first before). */
int setting_once(parser *P, const token *t, const char *what);
/* setting_once for keyword `name` of the current command (P->ctx): "'name' of 'noun verb'". */
int keyword_once(parser *P, const token *kw, const char *name);
/* setting_once for the whole current command: "'noun verb'". */
int command_once(parser *P);
int read_values(parser *P, const token *kw, int n, range r, unit u, double *v);
int read_value(parser *P, const token *kw, range r, unit u, double *v);
int read_switch(parser *P, const token *kw, int *on);
int read_name(parser *P, const token *kw, const token **name, char *dst);
int read_text(parser *P, const char *what, char *dst, size_t size);

/* ---- command handlers: P->cur at the first token after the verb; 0 or -1 ---- */

int model_title(parser *P); /* parse_model.c */
int model_gravity(parser *P);
int model_density(parser *P);
int model_damping(parser *P);
int model_timestep(parser *P);
int model_settle(parser *P);
int model_solve(parser *P);
int model_overturn(parser *P);
int model_reference(parser *P);
int model_domain(parser *P); /* parse_runout.c */
int model_fence(parser *P);
int contact_property(parser *P);
int contact_perturbation(parser *P);
int contact_preset(parser *P);
int contact_model(parser *P);
int output_hdf5(parser *P);
int block_create(parser *P); /* parse_block.c */
int block_import(parser *P);
int block_initial(parser *P);
int motion_pulse(parser *P); /* parse_motion.c */
int motion_import(parser *P);
int motion_stochastic(parser *P);
int contact_is_range(const parser *P); /* parse_scene.c: `contact property ... range ...` */
int contact_joint(parser *P);
int history_interval(parser *P);
int history_body(parser *P);
int history_joint(parser *P);
int history_energy(parser *P);
int model_save(parser *P);
int model_restore(parser *P);

#endif
