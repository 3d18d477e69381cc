/* rockdem — `rockdem keys` (and `--set help`): every key --set accepts (src/scenario/
 * overrides.c), with its units, its default and what it sets. tests/cli/help_keys_progress.sh
 * checks this list against the keys the parser accepts, both ways.
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"

#include <stdio.h>
#include <string.h>

typedef struct key_doc {
    const char *key;
    const char *units;
    const char *def;
    const char *meaning;
} key_doc;

static const key_doc keys[] = {
    { "model.gravity", "m/s^2 or g", "9.81", "gravity, along -z" },
    { "model.density", "kg/m^3", "2700", "default block density" },
    { "model.duration", "s", "scenario",
      "shaking + free motion after settling (model solve time)" },
    { "model.tail", "s", "0",
      "free-vibration tail: run on until every body rests, at most this long" },
    { "model.damping", "none | viscous R | local A", "none",
      "contact damping (ratio of critical; Cundall alpha)" },
    { "model.timestep", "auto | s", "auto",
      "time step: a fraction of the critical step, or fixed" },
    { "model.safety", "1", "0.2", "auto time step: fraction of the critical step, (0, 1]" },
    { "model.settle", "on | off", "on", "settle under gravity before shaking" },
    { "model.threads", "1", "OMP_NUM_THREADS, else 1",
      "threads one run steps on (the same results for any count)" },
    { "contact.stiffness-normal", "Pa/m", "1e10", "KN, normal stiffness per unit area" },
    { "contact.stiffness-shear", "Pa/m", "1e11",
      "KS, shear stiffness per unit area (default 10 KN: see docs/CONTACT.md)" },
    { "contact.friction", "degree", "40", "friction angle" },
    { "contact.friction-coefficient", "1", "0.839",
      "friction as a coefficient mu = tan(friction angle)" },
    { "contact.cohesion", "Pa", "0", "peak cohesion (lost at the first slip)" },
    { "contact.tension", "Pa", "0", "peak tensile strength (lost at the first opening)" },
    { "contact.spacing", "m | auto | vertices", "vertices",
      "subcontact spacing (vertices: face corners; auto: a tenth of the narrowest face)" },
    { "contact.restitution", "1", "0",
      "impact loss: fraction of a new subcontact's stretch kept when it first unloads, [0, 1] (0 plastic, 1 elastic)" },
    { "contact.interface-seed", "1", "0", "seed of the interface perturbation (0: off)" },
    { "contact.interface-remove", "1", "0", "fraction of subcontacts removed, [0, 1)" },
    { "contact.interface-raise", "m", "0",
      "a raised subcontact moves up to this far into its body" },
    { "contact.interface-scatter", "1", "0",
      "c.o.v. of the lognormal factor on each subcontact's area" },
    { "contact.model", "vertex | surface", "vertex",
      "contact model: vertex subcontacts or patches from the touching faces" },
    { "motion.amplitude", "m/s^2 or g", "scenario", "horizontal pulse amplitude" },
    { "motion.frequency", "Hz", "scenario", "pulse frequency (sine, cosine, harmonic)" },
    { "motion.duration", "s", "scenario", "pulse duration (rectangular, triangle)" },
    { "motion.direction", "degree", "0",
      "direction of +acceleration (pulses) or of +h1 (records)" },
    { "motion.cycles", "1", "1", "harmonic pulse: number of cycles" },
    { "motion.start", "s", "0", "time the pulse starts" },
    { "motion.vertical-amplitude", "m/s^2 or g", "scenario", "vertical pulse amplitude (+ up)" },
    { "motion.scale", "1", "1", "records: one factor for every component" },
    { "motion.scale-pga", "m/s^2 or g", "none",
      "records: scale to this PGA (geometric mean of h1, h2)" },
    { "motion.scale-pgv", "m/s", "none", "records: scale to this PGV" },
    { "motion.baseline", "degree | off", "4", "records: polynomial baseline correction" },
    { "motion.file", "path", "scenario", "records: the h1 file (AT2, text/CSV)" },
    { "motion.record", "id", "scenario", "records: FEMA P695 record id (every component)" },
    { "motion.seed", "1", "1", "records: seed of the stochastic h1 generator" },
    { "output.file", "path", "rockdem.h5", "HDF5 run file (also -o)" },
    { "output.interval", "s", "0.005", "time between samples" },
    { "reference.restitution", "1", "Housner's r",
      "rigid reference solvers: impact restitution e, (0, 1]; a stack's impacts keep e / r_H1 x the plastic rates" },
    { "block.<name>.density", "kg/m^3", "model.density", "density of the named block" },
    { "block.<name>.mass", "kg", "from density", "mass of the named block (overrides density)" },
    { "block.<name>.tilt", "degree", "0", "initial tilt about its base edge" },
    { "block.<name>.direction", "degree", "0", "direction the initial tilt leans towards" },
};

void rd_cli_keys(int tsv)
{
    size_t n = sizeof keys / sizeof keys[0];
    if (tsv)
        printf("key\tunits\tdefault\tmeaning\n");
    else
        printf("%-27s %-22s %-14s %s\n", "key (--set KEY=VALUE)", "units", "default", "meaning");
    for (size_t i = 0; i < n; i++) {
        const key_doc *k = &keys[i];
        if (tsv)
            printf("%s\t%s\t%s\t%s\n", k->key, k->units, k->def, k->meaning);
        else
            printf("%-27s %-22s %-14s %s\n", k->key, k->units, k->def, k->meaning);
    }
    if (!tsv)
        printf(
            "'scenario': no default, the scenario file sets it. Numbers accept SI units only;\n"
            "accelerations also a g suffix (0.3g). Example: rockdem run pbr.dat --set motion.amplitude=0.4g\n");
}
