/* rockdem — every dimensional input echoed with its units, and the values that look like a
 * unit mistake, with the likely intent (`rockdem check`; the echo also heads `rockdem run`).
 *
 * The advice thresholds (named below) mark values no real rocking problem has; each warning
 * says what the value was read as and what it would be in the unit that was likely meant.
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"

#include <math.h>
#include <stdio.h>

static const double DEG = 180.0 / 3.14159265358979323846; /* degrees per radian */

/* A friction angle below this (deg) is nearly frictionless: more likely a coefficient mu
 * written where degrees are read (mu 0.6 = 31 deg); rock joints have 25-45 deg. */
#define FRICTION_DEG_SUSPECT  1.5
/* Standard gravity and the spread of g over the Earth's surface (9.78 at the equator to 9.83
 * m/s^2 at the poles): a gravity outside this band is no terrestrial value. */
#define GRAVITY_EARTH_TOL     0.03
/* A pulse amplitude below this, written without a g suffix (so read in m/s^2), is under 0.1 g:
 * more likely meant in g. */
#define AMPLITUDE_MS2_SUSPECT 1.0
/* Peak ground accelerations above this are not earthquakes (the largest recorded are ~4 g):
 * a record in cm/s^2 read as g, or an amplitude in m/s^2 written with a g suffix. */
#define PGA_G_SUSPECT         5.0
/* A free body larger than this across (m) is no precarious rock or museum object (the
 * tallest balanced rocks are ~30 m): a mesh drawn in mm or cm read as m. */
#define SIZE_M_SUSPECT        100.0
/* A free body tipping at less than this (deg) is on its side or on a point: a y-up mesh read
 * as z-up stands on its side. */
#define ALPHA_DEG_SUSPECT     0.5

static const char *pulse_name(rd_pulse_kind k)
{
    static const char *const names[] = { "none",     "one-sine", "one-cosine", "rectangular",
                                         "triangle", "harmonic", "ricker" };
    return (int)k >= 0 && (size_t)k < sizeof names / sizeof names[0] ? names[k] : "pulse";
}

static void echo_pulse(const char *which, const rd_pulse_def *p)
{
    if (p->kind == RD_PULSE_NONE) return;
    printf("inputs: %s pulse %s: amplitude %.4g m/s^2 = %.4g g (written in %s)", which,
           pulse_name(p->kind), p->amplitude, p->amplitude / RD_G_STANDARD,
           p->amplitude_in_g ? "g" : "m/s^2");
    if (p->frequency > 0) printf(", frequency %.4g Hz", p->frequency);
    if (p->duration > 0) printf(", duration %.4g s", p->duration);
    printf("\n");
}

static const char *record_units(const rd_component_def *c)
{
    if (c->source == RD_SOURCE_AT2)
        return "in the units its header states (UNITS OF G, CM/SEC/SEC or M/SEC/SEC)";
    if (c->source == RD_SOURCE_FEMA) return "in g (FEMA P695 sets)";
    if (c->source == RD_SOURCE_STOCHASTIC) return "generated in m/s^2";
    if (!c->unit_given) return "in g (no 'units' declared: g is the default)";
    return c->unit == 1.0    ? "in m/s^2 (declared)"
           : c->unit == 0.01 ? "in cm/s^2 (declared)"
                             : "in g (declared)";
}

void rd_cli_echo_inputs(const rd_scenario *sc)
{
    const rd_contact_def *c = &sc->contact;
    printf(
        "inputs: gravity %.5g m/s^2 (%.4g g); contact KN %.3g Pa/m, KS %.3g Pa/m (KS/KN %.3g), friction %.4g deg "
        "(mu %.4g)\n",
        sc->gravity, sc->gravity / RD_G_STANDARD, c->kn, c->ks, c->ks / c->kn, c->friction * DEG,
        tan(c->friction));
    for (int j = 0; j < sc->njoints; j++)
        if (sc->joint[j].set & RD_JOINT_FRICTION)
            printf("inputs: joint range (line %d): friction %.4g deg (mu %.4g)\n",
                   sc->joint[j].line, sc->joint[j].friction * DEG, tan(sc->joint[j].friction));
    echo_pulse("horizontal", &sc->motion.horizontal);
    echo_pulse("vertical", &sc->motion.vertical);
    for (int k = 0; k < RD_NCOMPONENTS; k++) {
        const rd_component_def *r = &sc->motion.record[k];
        if (r->source == RD_SOURCE_NONE || !r->applied) continue;
        double pga = 0;
        for (size_t i = 0; i < r->applied->npts; i++) pga = fmax(pga, fabs(r->applied->acc[i]));
        printf("inputs: %s record %s: values %s; applied PGA %.4g m/s^2 = %.4g g\n",
               rd_motion_component_name(k), r->applied->name, record_units(r), pga,
               pga / RD_G_STANDARD);
    }
}

void rd_cli_echo_body(const char *name, int mesh, double mass, const double size[3])
{
    printf("inputs: block %s%s: %.4g x %.4g x %.4g m (x, y, z), mass %.4g kg\n", name,
           mesh ? " (mesh)" : "", size[0], size[1], size[2], mass);
}

/* One "warning:" line; returns 1 (a count). */
#define WARN(...) (printf("warning: " __VA_ARGS__), printf("\n"), 1)

static int friction_warning(const char *where, double phi)
{
    double deg = phi * DEG;
    if (!(deg > 0 && deg < FRICTION_DEG_SUSPECT)) return 0;
    return WARN(
        "%sfriction %.3g deg (mu %.3g) is nearly frictionless: did you mean friction-coefficient %.3g "
        "(= %.3g deg)? 'friction' is an angle in degrees",
        where, deg, tan(phi), deg, atan(deg) * DEG);
}

static int pulse_warning(const char *which, const rd_pulse_def *p)
{
    double a = fabs(p->amplitude), g = a / RD_G_STANDARD;
    if (p->kind == RD_PULSE_NONE) return 0;
    if (!p->amplitude_in_g && a > 0 && a < AMPLITUDE_MS2_SUSPECT)
        return WARN(
            "%s pulse amplitude %.3g m/s^2 = %.3g g (a number without a g suffix is m/s^2): did you "
            "mean %.3gg = %.3g m/s^2?",
            which, p->amplitude, p->amplitude / RD_G_STANDARD, p->amplitude,
            p->amplitude * RD_G_STANDARD);
    if (g > PGA_G_SUSPECT)
        return WARN("%s pulse amplitude %.3g g (%.3g m/s^2) is above %g g, beyond any earthquake%s",
                    which, g, a, PGA_G_SUSPECT,
                    p->amplitude_in_g ? ": did you mean it in m/s^2 (drop the g suffix)?" : "");
    return 0;
}

static int record_warning(int k, const rd_component_def *r)
{
    if (r->source == RD_SOURCE_NONE || !r->applied) return 0;
    double pga = 0;
    for (size_t i = 0; i < r->applied->npts; i++) pga = fmax(pga, fabs(r->applied->acc[i]));
    if (pga / RD_G_STANDARD <= PGA_G_SUSPECT) return 0;
    const char *hint =
        r->source != RD_SOURCE_TEXT ? ": check the record's units and the scale"
        : !r->unit_given ? ": its values were read as g (no 'units' given); a record in cm/s^2 or "
                           "m/s^2 needs 'units cm/s2' or 'units m/s2' on its ground-motion import"
                         : ": check its declared 'units' and the scale";
    return WARN("%s record %s: PGA %.3g g (%.3g m/s^2) is above %g g, beyond any earthquake%s",
                rd_motion_component_name(k), r->applied->name, pga / RD_G_STANDARD, pga,
                PGA_G_SUSPECT, hint);
}

int rd_cli_unit_warnings(const rd_scenario *sc)
{
    int n = 0;
    if (fabs(sc->gravity - RD_G_STANDARD) > GRAVITY_EARTH_TOL)
        n += WARN(
            "gravity %.4g m/s^2 (%.3g g) is not the Earth's %.4g m/s^2: 'model gravity' is in m/s^2%s",
            sc->gravity, sc->gravity / RD_G_STANDARD, RD_G_STANDARD,
            fabs(sc->gravity - 1.0) < 1e-9 ? " (did you mean 1 g = 9.81?)" : "");
    n += friction_warning("contact ", sc->contact.friction);
    for (int j = 0; j < sc->njoints; j++)
        if (sc->joint[j].set & RD_JOINT_FRICTION) {
            char where[64];
            snprintf(where, sizeof where, "joint range (line %d): ", sc->joint[j].line);
            n += friction_warning(where, sc->joint[j].friction);
        }
    n += pulse_warning("horizontal", &sc->motion.horizontal);
    n += pulse_warning("vertical", &sc->motion.vertical);
    for (int k = 0; k < RD_NCOMPONENTS; k++) n += record_warning(k, &sc->motion.record[k]);
    return n;
}

int rd_cli_body_warnings(const rd_body_def *d, double mass, const double size[3], double alpha)
{
    int mesh = d->shape == RD_SHAPE_MESH, n = 0;
    double across = fmax(size[0], fmax(size[1], size[2]));
    if (d->fixed) return 0;
    if (across > SIZE_M_SUSPECT)
        n += WARN("block '%s' is %.3g m across and %.3g kg: %s", d->name, across, mass,
                  mesh ? (d->mesh_unit > 0
                              ? "check the mesh's declared 'units'"
                              : "mesh in mm? its coordinates are read as m: add 'units mm' (or cm) "
                                "to its block import")
                       : "scenario lengths are in m");
    if (mesh && !n && alpha >= 0 &&
        alpha * DEG < ALPHA_DEG_SUSPECT) /* (a mesh in mm: its size first) */
        n += WARN("block '%s' tips at %.3g deg: it stands on its side or on a point; %s", d->name,
                  alpha * DEG,
                  d->mesh_up == 1
                      ? "check its orientation ('rotation')"
                      : "a mesh drawn y-up is read z-up: add 'up y' to its block import");
    return n;
}
