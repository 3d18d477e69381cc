/* rockdem — scenario commands `block create|import|initial`: bodies into rd_scenario; the
 * column and stack assemblies come from geometry/builders.c.
 * Folder scenario/ owns the scenario language (parse, --set overrides, validation); it may call
 * base/, records/ and geometry/, never engine/, io/ or cli/.
 */
#include "scenario/parse.h"
#include "geometry/builders.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RD_COLUMN_MAX_DRUMS 100   /* drums of one `block create column` */
#define RD_PRISM_MAX_SIDES  10000 /* sides of a drum (values.c's bound on 'sides') */

/* ---- block ---- */

/* Keywords every single-body command accepts, after its shape's own. */
static const char *const body_common[] = { "position", "seat-on", "at",    "rotation", "density",
                                           "mass",     "name",    "fixed", "group" };
#define NCOMMON 9

typedef struct body_cmd {
    rd_body_def b;
    const token *name, *dm, *place; /* name token; density/mass and position/seat-on given */
    unsigned seen;                  /* keywords seen, bit k for names[k] */
} body_cmd;

/* Reads "seat-on NAME": the body must exist (seated bodies stack in definition order). */
static int read_seat(parser *P, const token *kw, rd_body_def *b)
{
    const token *t;
    if (read_name(P, kw, &t, b->seat_on)) return -1;
    int j = parse_find_body(P, b->seat_on, strlen(b->seat_on));
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
    case 0:
        return exclusive(P, &c->place, kw) || read_values(P, kw, 3, R_ANY, U_PLAIN, b->position);
    case 1: return exclusive(P, &c->place, kw) || read_seat(P, kw, b);
    case 2: return read_values(P, kw, 2, R_ANY, U_PLAIN, b->position);
    case 3: return read_values(P, kw, 3, R_ANY, U_DEG, b->rotation);
    case 4: return exclusive(P, &c->dm, kw) || read_value(P, kw, R_POS, U_PLAIN, &b->density);
    case 5: return exclusive(P, &c->dm, kw) || read_value(P, kw, R_POS, U_PLAIN, &b->mass);
    case 6: return read_name(P, kw, &c->name, b->name);
    case 7: b->fixed = 1; return 0;
    default: return read_name(P, kw, &(const token *){ NULL }, b->group); /* joint group */
    }
}

/* Reads "vertices x y z x y z ...": every number up to the next keyword (at least 4 points). */
static int read_vertices(parser *P, const token *kw, rd_body_def *b)
{
    int n = 0;
    while (P->cur + n < P->n && parse_number(P->tok[P->cur + n].s, (size_t)P->tok[P->cur + n].len,
                                             0, &(double){ 0 }) == 0)
        n++;
    if (n < 12 || n % 3)
        return perr(P, kw, "'vertices' needs x y z triples of at least 4 points, got %d numbers",
                    n);
    double *v = malloc((size_t)n * sizeof *v);
    if (!v) return perr(P, kw, "out of memory");
    if (read_values(P, kw, n, R_ANY, U_PLAIN, v)) {
        free(v);
        return -1;
    }
    free(b->verts);
    b->verts = v;
    b->nverts = n / 3;
    return 0;
}

/* `units mm|cm|m` of a mesh: metres per file unit (a scan exported in millimetres is common). */
static int read_mesh_units(parser *P, const token *kw, rd_body_def *b)
{
    static const char *const names[] = { "mm", "cm", "m", NULL };
    static const double metres[] = { 1e-3, 1e-2, 1.0 };
    const token *t = take(P);
    int k = t ? find_word(t, names) : -1;
    if (!t) return perr(P, kw, "expected mm, cm or m after 'units'");
    if (k < 0) return perr(P, t, "unknown mesh units '%.*s' (expected mm, cm or m)", t->len, t->s);
    b->mesh_unit = metres[k];
    return 0;
}

/* `up y|z` of a mesh: the file's vertical axis (many scanning and graphics tools write y up). */
static int read_mesh_up(parser *P, const token *kw, rd_body_def *b)
{
    static const char *const names[] = { "y", "z", NULL };
    const token *t = take(P);
    int k = t ? find_word(t, names) : -1;
    if (!t) return perr(P, kw, "expected y or z after 'up'");
    if (k < 0) return perr(P, t, "unknown up axis '%.*s' (expected y or z)", t->len, t->s);
    b->mesh_up = k == 0 ? 1 : 2;
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
            if (read_value(P, kw, R_POS, U_PLAIN, &sides)) return -1;
            if (sides < 3 || sides > RD_PRISM_MAX_SIDES || sides != (int)sides)
                return perr(P, kw, "'sides' must be a whole number from 3 to %d",
                            RD_PRISM_MAX_SIDES);
            b->sides = (int)sides;
            return 0;
        }
        return read_value(P, kw, R_POS, U_PLAIN,
                          k == 1   ? &b->radius
                          : k == 2 ? &b->radius_top
                                   : &b->size[2]);
    case RD_SHAPE_HULL: return read_vertices(P, kw, b);
    case RD_SHAPE_MESH: return k == 0 ? read_mesh_units(P, kw, b) : read_mesh_up(P, kw, b);
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
    { "brick", RD_SHAPE_BRICK, { "size" }, 1, 1u },
    { "prism", RD_SHAPE_PRISM, { "sides", "radius", "radius-top", "height" }, 4, 1u | 2u | 8u },
    { "polyhedron", RD_SHAPE_HULL, { "vertices" }, 1, 1u },
    { "mesh", RD_SHAPE_MESH, { "units", "up" }, 2, 0u },
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
    if (k == KW_ERR) return -1;
    for (int i = 0; i < sh->nown; i++)
        if ((sh->need >> i & 1u) && !(c->seen >> i & 1u))
            return perr(P, &P->tok[2], "missing '%s' for '%s %s'", names[i], P->ctx, sh->word);
    if (!c->place)
        return perr(P, &P->tok[2], "missing 'position' or 'seat-on' for '%s %s'", P->ctx, sh->word);
    if ((c->seen >> (n + 2) & 1u) && !c->b.seat_on[0])
        return perr(P, &P->tok[2], "'at' applies only with 'seat-on'");
    if (c->b.shape == RD_SHAPE_PRISM && !(c->seen & 4u)) c->b.radius_top = c->b.radius;
    return 0;
}

/* Appends b (taking over its vertices), naming it "block<k>" when unnamed; refuses
 * duplicates. */
static int add_body(parser *P, const rd_body_def *b, const token *name, const token *at)
{
    rd_scenario *sc = P->sc;
    if (rd_scenario_grow(sc))
        return perr(P, verb_token(P), "out of memory for block %d", sc->nbodies + 1);
    rd_body_def d = *b;
    d.line = P->tok[0].line;
    if (!d.name[0]) snprintf(d.name, sizeof d.name, "block%d", sc->nbodies + 1);
    int dup = parse_find_body(P, d.name, strlen(d.name));
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
    body_cmd c = { .b = { .shape = sh->kind, .mesh_up = 2 } };
    if (sh->kind == RD_SHAPE_MESH) {
        char file[RD_PATH_MAX];
        if (read_text(P, "a mesh file", file, sizeof file)) return -1;
        if (resolve_path(P->name, file, c.b.mesh, sizeof c.b.mesh))
            return perr(P, at, "mesh path too long");
    }
    if (body_command(P, sh, &c) == 0 && add_body(P, &c.b, c.name, at) == 0) return 0;
    free(c.b.verts);
    return -1;
}

/* Builder helpers: a named member of an assembly seated on `seat`. */
static int add_member(parser *P, const body_cmd *c, const char *prefix, const char *suffix,
                      const char *seat, rd_body_def *b, const token *at)
{
    b->density = c->b.density;
    b->mass = 0;
    memcpy(b->group, c->b.group, sizeof b->group); /* every member in the assembly's group */
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
    if (read_value(P, kw, R_POS, U_PLAIN, &v)) return -1;
    if (v < lo || v > hi || v != (int)v)
        return perr(P, kw, "'%.*s' must be a whole number from %d to %d", kw->len, kw->s, lo, hi);
    *n = (int)v;
    return 0;
}

/* Adds the n members of an assembly bottom to top, named "<prefix>-<suffix>", the first
 * seated on the command's seat-on block and each next one on the one before. */
static int add_chain(parser *P, const body_cmd *c, const char *prefix, rd_body_def *members,
                     char (*suffix)[16], int n, const token *at)
{
    char below[RD_NAME_MAX];
    snprintf(below, sizeof below, "%s", c->b.seat_on);
    for (int k = 0; k < n; k++) {
        if (add_member(P, c, prefix, suffix[k], below, &members[k], at)) return -1;
        memcpy(below, P->sc->bodies[P->sc->nbodies - 1].name, sizeof below);
    }
    return 0;
}

/* block create column drums N diameter D height H [sides S] [taper T] [plinth W H]
 *                     [capital H] [abacus W H] seat-on NAME [at X Y] [name P] [density RHO]
 * A classical column: plinth (brick), N drums (prisms whose radius shrinks linearly from D/2
 * to T D/2 up the shaft), an echinus capital (frustum widening by 30 %), an abacus (brick). */
static int block_column(parser *P, const token *at)
{
    static const char *const names[] = { "drums",  "diameter", "height", "sides",   "taper",
                                         "plinth", "capital",  "abacus", "seat-on", "at",
                                         "name",   "density",  "group",  NULL };
    body_cmd c = { .b = { .shape = RD_SHAPE_PRISM } };
    int ndrums = 0, sides = 20;
    double d = 0, h = 0, taper = 1, plinth[2] = { 0 }, cap = 0, abacus[2] = { 0 };
    const token *kw;
    int k;
    while ((k = next_keyword(P, names, &c.seen, &kw)) >= 0) {
        int rc = 0;
        switch (k) {
        case 0: rc = read_count(P, kw, 1, RD_COLUMN_MAX_DRUMS, &ndrums); break;
        case 1: rc = read_value(P, kw, R_POS, U_PLAIN, &d); break;
        case 2: rc = read_value(P, kw, R_POS, U_PLAIN, &h); break;
        case 3: rc = read_count(P, kw, 3, RD_PRISM_MAX_SIDES, &sides); break;
        case 4: rc = read_value(P, kw, R_FRAC, U_PLAIN, &taper); break;
        case 5: rc = read_values(P, kw, 2, R_POS, U_PLAIN, plinth); break;
        case 6: rc = read_value(P, kw, R_POS, U_PLAIN, &cap); break;
        case 7: rc = read_values(P, kw, 2, R_POS, U_PLAIN, abacus); break;
        case 8:
            rc = read_seat(P, kw, &c.b);
            c.place = kw;
            break;
        case 9: rc = read_values(P, kw, 2, R_ANY, U_PLAIN, c.b.position); break;
        case 10: rc = read_name(P, kw, &c.name, c.b.name); break;
        case 11: rc = read_value(P, kw, R_POS, U_PLAIN, &c.b.density); break;
        default: rc = read_name(P, kw, &(const token *){ NULL }, c.b.group); break;
        }
        if (rc) return -1;
    }
    if (k == KW_ERR) return -1;
    for (int i = 0; i < 3; i++)
        if (!(c.seen >> i & 1u))
            return perr(P, &P->tok[2], "missing '%s' for 'block create column'", names[i]);
    if (!c.place) return perr(P, &P->tok[2], "missing 'seat-on' for 'block create column'");
    rd_column_spec spec = {
        ndrums, sides, d, h, taper, { plinth[0], plinth[1] }, cap, { abacus[0], abacus[1] }
    };
    rd_body_def members[RD_COLUMN_MAX_DRUMS + 3];
    char suffix[RD_COLUMN_MAX_DRUMS + 3][16];
    int n = rd_build_column(&spec, members, suffix);
    return add_chain(P, &c, c.b.name[0] ? c.b.name : "column", members, suffix, n, at);
}

/* block create stack lower LX LY LZ upper UX UY UZ seat-on NAME [at X Y] [name P] [density RHO]
 * A two-block assembly (a statue on its pedestal): P-lower on NAME, P-upper on P-lower. */
static int block_stack(parser *P, const token *at)
{
    static const char *const names[] = { "lower", "upper",   "seat-on", "at",
                                         "name",  "density", "group",   NULL };
    body_cmd c = { .b = { .shape = RD_SHAPE_BRICK } };
    double lo[3], up[3];
    const token *kw;
    int k;
    while ((k = next_keyword(P, names, &c.seen, &kw)) >= 0) {
        int rc = 0;
        switch (k) {
        case 0: rc = read_values(P, kw, 3, R_POS, U_PLAIN, lo); break;
        case 1: rc = read_values(P, kw, 3, R_POS, U_PLAIN, up); break;
        case 2:
            rc = read_seat(P, kw, &c.b);
            c.place = kw;
            break;
        case 3: rc = read_values(P, kw, 2, R_ANY, U_PLAIN, c.b.position); break;
        case 4: rc = read_name(P, kw, &c.name, c.b.name); break;
        case 5: rc = read_value(P, kw, R_POS, U_PLAIN, &c.b.density); break;
        default: rc = read_name(P, kw, &(const token *){ NULL }, c.b.group); break;
        }
        if (rc) return -1;
    }
    if (k == KW_ERR) return -1;
    if ((c.seen & 3u) != 3u)
        return perr(P, &P->tok[2], "missing '%s' for 'block create stack'",
                    c.seen & 1u ? "upper" : "lower");
    if (!c.place) return perr(P, &P->tok[2], "missing 'seat-on' for 'block create stack'");
    rd_body_def members[2];
    char suffix[2][16];
    rd_build_stack(lo, up, members, suffix);
    return add_chain(P, &c, c.b.name[0] ? c.b.name : "stack", members, suffix, 2, at);
}

int block_create(parser *P)
{
    const token *shape = take(P);
    static const char *expected = "brick, prism, polyhedron, column or stack";
    if (!shape)
        return perr(P, verb_token(P), "expected a shape after 'block create' (expected %s)",
                    expected);
    if (tok_is(shape, "column")) return block_column(P, shape);
    if (tok_is(shape, "stack")) return block_stack(P, shape);
    for (size_t i = 0; i + 1 < sizeof shapes / sizeof shapes[0]; i++)
        if (tok_is(shape, shapes[i].word)) return single_body(P, &shapes[i], shape);
    return perr(P, shape, "unknown shape '%.*s' for 'block create' (expected %s)", shape->len,
                shape->s, expected);
}

/* block import terrain 'slope.asc' [name N] [group 'G']: a height grid (ESRI ASCII .asc or
 * gridded .xyz) as a fixed solid at the file's own coordinates (geometry/terrain.c). */
static int import_terrain(parser *P, const token *at)
{
    static const char *const names[] = { "name", "group", NULL };
    body_cmd c = { .b = { .shape = RD_SHAPE_MESH, .mesh_up = 2, .terrain = 1, .fixed = 1 } };
    char file[RD_PATH_MAX];
    if (read_text(P, "a terrain grid file (.asc or .xyz)", file, sizeof file)) return -1;
    if (resolve_path(P->name, file, c.b.mesh, sizeof c.b.mesh))
        return perr(P, at, "terrain path too long");
    const token *kw;
    int k;
    while ((k = next_keyword(P, names, &c.seen, &kw)) >= 0)
        if (k == 0 ? read_name(P, kw, &c.name, c.b.name)
                   : read_name(P, kw, &(const token *){ NULL }, c.b.group))
            return -1;
    if (k == KW_ERR) return -1;
    return add_body(P, &c.b, c.name, at);
}

/* block import mesh 'rock.obj' (position X Y Z | seat-on NAME [at X Y]) [rotation ...] ... */
int block_import(parser *P)
{
    const token *what = take(P);
    if (what && tok_is(what, "terrain")) return import_terrain(P, what);
    if (!what || !tok_is(what, "mesh"))
        return perr(P, what ? what : verb_token(P),
                    "expected 'mesh' or 'terrain' after 'block import'");
    return single_body(P, &shapes[3], what);
}

int block_initial(parser *P)
{
    static const char *const names[] = {
        "name", "tilt", "direction", "velocity", "angular-velocity", NULL
    };
    const token *kw, *name = NULL, *given[sizeof names / sizeof names[0]] = { NULL };
    char id[RD_NAME_MAX];
    double tilt = 0, dir = 0, v[3] = { 0 }, w[3] = { 0 };
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        int rc = 0;
        given[k] = kw;
        switch (k) {
        case 0: rc = read_name(P, kw, &name, id); break;
        case 1: rc = read_value(P, kw, R_ANGLE, U_DEG, &tilt); break;
        case 2: rc = read_value(P, kw, R_ANY, U_DEG, &dir); break;
        case 3: rc = read_values(P, kw, 3, R_ANY, U_PLAIN, v); break;
        default: rc = read_values(P, kw, 3, R_ANY, U_PLAIN, w); break;
        }
        if (rc) return -1;
    }
    if (k == KW_ERR) return -1;
    if (!name) return perr(P, verb_token(P), "missing 'name' for 'block initial'");
    int i = parse_find_body(P, id, strlen(id));
    if (i < 0)
        return perr(P, name, "unknown block '%s' (no 'block create ... name %s' before this line)",
                    id, id);
    rd_body_def *b = &P->sc->bodies[i];
    if (b->fixed)
        return perr(P, name, "block '%s' is fixed; 'block initial' applies only to free blocks",
                    id);
    for (k = 1; names[k]; k++) { /* each value once per block */
        char what[sizeof((setting *)0)->what];
        snprintf(what, sizeof what, "'%s' of 'block initial name %s'", names[k], id);
        if (given[k] && setting_once(P, given[k], what)) return -1;
    }
    if (seen & 2u) b->tilt = tilt;
    if (seen & 4u) b->tilt_direction = dir;
    if (seen & 8u) memcpy(b->velocity, v, sizeof v);
    if (seen & 16u) memcpy(b->angular_velocity, w, sizeof w);
    b->initial_line = verb_token(P)->line;
    return 0;
}
