/* rockdem — scenario validation: rd_scenario_validate (a scenario built in code, not parsed,
 * gets the same checks as a parsed one).
 * Folder scenario/ owns the scenario language (parse, --set overrides, validation); it may call
 * base/, records/ and geometry/, never engine/, io/ or cli/.
 */
#include "scenario/parse.h"
#include "scenario/name_index.h"

#include <math.h>
#include <string.h>

/* ---- public: validation ---- */

/* NULL, or what is wrong with the scenario-wide settings. */
static const char *model_problem(const rd_scenario *sc)
{
    const rd_contact_def *c = &sc->contact;
    const rd_damping_def *d = &sc->damping;
    const double right = 90.0 * RD_DEG;
    if (sc->nbodies < 0 || (sc->nbodies > 0 && !sc->bodies)) return "block list missing";
    if (!(sc->gravity >= 0)) return "gravity must be >= 0";
    if (!(sc->density > 0)) return "density must be > 0";
    if (!(c->kn > 0) || !(c->ks > 0))
        return "contact stiffness-normal and stiffness-shear must be > 0";
    if (!(c->friction >= 0 && c->friction < right))
        return "contact friction must be in [0, 90) degrees";
    if (!(c->cohesion >= 0) || !(c->tension >= 0))
        return "contact cohesion and tension must be >= 0";
    if (!isfinite(c->spacing)) return "contact spacing must be a number";
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
    if (!(sc->overturn.value > 0) &&
        !(sc->overturn.kind == RD_OVERTURN_OFF && sc->overturn.value == 0))
        return "overturn criterion must be > 0 (off-pedestal: >= 0)";
    if (sc->output.path[0] == '\0' || !(sc->output.interval > 0))
        return "output needs a file name and an interval > 0";
    return NULL;
}

static const char *body_problem(const rd_scenario *sc, int i, rd_name_index *names)
{
    const rd_body_def *b = &sc->bodies[i];
    if (b->shape == RD_SHAPE_BRICK && !(b->size[0] > 0 && b->size[1] > 0 && b->size[2] > 0))
        return "size must be > 0";
    if (b->shape == RD_SHAPE_PRISM &&
        !(b->sides >= 3 && b->radius > 0 && b->radius_top > 0 && b->size[2] > 0))
        return "a prism needs sides >= 3, radii > 0 and height > 0";
    if (b->shape == RD_SHAPE_HULL && !(b->nverts >= 4 && b->verts))
        return "a polyhedron needs at least 4 vertices";
    if (b->shape == RD_SHAPE_MESH && b->mesh[0] == '\0') return "a mesh needs a file";
    if (!(b->mass >= 0)) return "mass must be > 0 (or 0 to use the density)";
    if (!(b->tilt >= 0 && b->tilt < 90.0 * RD_DEG)) return "tilt must be in [0, 90) degrees";
    int first = rd_name_index_find(names, sc, b->name, strlen(b->name));
    if ((first == -2 ? find_body(sc, b->name, strlen(b->name)) : first) != i)
        return "name used by an earlier block";
    if (!valid_name(b->name, strlen(b->name))) return "invalid name";
    return NULL;
}

static const char *pulse_problem(const rd_pulse_def *p)
{
    if (p->kind == RD_PULSE_NONE) return NULL;
    if (!isfinite(p->amplitude) || !(p->start >= 0))
        return "amplitude must be a number and start >= 0";
    if (is_periodic(p->kind) && !(p->frequency > 0)) return "frequency must be > 0";
    if (p->kind == RD_PULSE_HARMONIC && !(p->cycles > 0)) return "cycles must be > 0";
    if (!(p->duration > 0)) return "duration must be > 0";
    return NULL;
}

static const char *records_problem(const rd_motion_def *m)
{
    for (int c = 0; c < RD_NCOMPONENTS; c++)
        if (m->record[c].source != RD_SOURCE_NONE && !m->record[c].applied)
            return "a ground-motion record is defined but not loaded";
    if (m->baseline != 0 && (m->baseline < 2 || m->baseline > 8))
        return "record baseline degree must be 2 to 8 (or off)";
    if (m->scale != RD_SCALE_NONE && !(m->scale_value > 0)) return "record scale must be > 0";
    if (!isfinite(m->direction)) return "record direction must be a number";
    return NULL;
}

int rd_scenario_validate(const rd_scenario *sc, rd_error *err)
{
    const char *f = sc->file, *bad;
    int nfree = 0;
    for (int i = 0; i < sc->nbodies && sc->bodies; i++) nfree += !sc->bodies[i].fixed;
    if (nfree == 0)
        return rd_error_set(err, "%s: no free block (add 'block create brick ...' without 'fixed')",
                            f);
    if (!(sc->duration > 0))
        return rd_error_set(err, "%s: no duration (add 'model solve time <s>')", f);
    if ((bad = model_problem(sc))) return rd_error_set(err, "%s: %s", f, bad);
    rd_name_index names = { 0 };
    for (int i = 0; i < sc->nbodies; i++)
        if ((bad = body_problem(sc, i, &names))) {
            rd_name_index_free(&names);
            return rd_error_set(err, "%s:%d: block '%s': %s", f, sc->bodies[i].line,
                                sc->bodies[i].name, bad);
        }
    rd_name_index_free(&names);
    if ((bad = pulse_problem(&sc->motion.horizontal)))
        return rd_error_set(err, "%s:%d: horizontal pulse: %s", f, sc->motion.horizontal.line, bad);
    if ((bad = pulse_problem(&sc->motion.vertical)))
        return rd_error_set(err, "%s:%d: vertical pulse: %s", f, sc->motion.vertical.line, bad);
    if ((bad = records_problem(&sc->motion))) return rd_error_set(err, "%s: %s", f, bad);
    if (!(sc->tail >= 0)) return rd_error_set(err, "%s: solve tail must be >= 0", f);
    return 0;
}
