/* rockdem — `rockdem check FILE [--set key=value]...`: parse, build and look at the scene
 * without running it. Prints the time step and its limit, every body (mass, volume, tipping
 * angle, subcontacts, what it rests on), the joints and the cost of a simulated second, then
 * one "warning:" line per mistake it can see:
 *   - a free body with nothing under it (it would fall freely for the whole run)
 *   - a free body that starts above what is under it (it drops before it rests)
 *   - bodies that overlap as placed (the contact springs would throw them apart)
 *   - a time step far below the output interval (many steps per sample: a slow run)
 *   - a ground-motion record that ends before the requested duration
 *   - a joint whose static sink at rest, W / (KN A), exceeds the contact band
 * It first does everything a run would refuse (rd_sim_check: meshes, the step budget, the
 * output file; the checkpoint it restores, read and compared as run does). Exit status: 2 when a
 * run would be refused (bad input), 1 with --strict when it warned, else 0; the last line
 * is "FILE: ok (...)" without warnings, "FILE: N warnings (...)" with them.
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "rockdem/check.h"
#include "cli/cli.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define RD_GAP_TOL              1e-4 /* a gap below this fraction of the body's height is contact */
#define RD_OVERLAP_TOL          1e-3 /* penetration above this fraction of the body's height: overlap */
#define RD_STEPS_PER_SAMPLE_MAX 2000 /* more steps than this per output sample: warn (slow run) */

static const double DEG = 180.0 / 3.14159265358979323846; /* degrees per radian */

static void print_body(const rd_check_report *r, const rd_check_body *b)
{
    printf("  %-12s %s mass %.6g kg, volume %.4g m^3", b->name, b->fixed ? "fixed" : "free ",
           b->mass, b->volume);
    if (b->group[0]) printf(", group '%s'", b->group);
    if (!b->fixed)
        printf(", tipping angle %.3g deg (least %.3g deg), %d subcontacts", b->alpha * DEG,
               b->alpha_min * DEG, b->npoints);
    if (!b->fixed && b->rests_on >= 0)
        printf(", rests on '%s'", r->body[b->rests_on].name);
    else if (!b->fixed && b->below >= 0)
        printf(", %.4g m above '%s'", b->gap, r->body[b->below].name);
    else if (!b->fixed)
        printf(", nothing under it");
    printf("; size %.4g x %.4g x %.4g m (x, y, z)\n", b->extent[0], b->extent[1], b->extent[2]);
}

/* Height of a body from its volume and mass are not enough: use the cube root of its volume as
 * its size for the tolerances. */
static double size_of(const rd_check_body *b) { return cbrt(b->volume); }

/* Body b's joint with what it rests on closes at rest by more than the contact band: its
 * subcontacts then bear from deeper than the band the contact is built for, and the run, which
 * settles first, stops as penetrated past ten bands (overlap.c). One warning, 1; else 0. */
static int sink_warning(const rd_check_report *r, const rd_check_body *b)
{
    if (b->fixed || b->rests_on < 0 || !(b->sink > b->band)) return 0;
    char above[64] = "";
    if (b->sink_above)
        snprintf(above, sizeof above, " and the %d free bod%s above it", b->sink_above,
                 b->sink_above == 1 ? "y" : "ies");
    printf("warning: block '%s' on '%s' sinks about %.3g mm at rest, W / (KN A) = %.3g N (its "
           "weight%s) / (%.3g Pa/m x %.3g m^2), more than the contact band %.3g mm: "
           "stiffness-normal about %.2g times higher keeps it within the band%s\n",
           b->name, r->body[b->rests_on].name, 1e3 * b->sink, b->sink_load, above, b->sink_kn,
           b->sink_area, 1e3 * b->band, b->sink / b->band,
           b->sink > 10 * b->band ? " (past ten bands a run stops as penetrated)" : "");
    return 1;
}

static int warnings(const rd_scenario *sc, const rd_check_report *r)
{
    int n = 0;
    for (int i = 0; i < r->nbodies; i++) {
        const rd_check_body *b = &r->body[i];
        const rd_body_def *d = &sc->bodies[i];
        int moving = fabs(d->velocity[0]) + fabs(d->velocity[1]) + fabs(d->velocity[2]) > 0;
        if (b->fixed) continue;
        if (b->rests_on < 0 && b->below < 0) {
            printf("warning: block '%s' has nothing under it: it falls freely for the whole run "
                   "(place it on a block, e.g. seat-on NAME, or add a fixed base)\n",
                   b->name);
            n++;
        } else if (b->rests_on < 0 && b->gap > RD_GAP_TOL * size_of(b) && !moving) {
            printf("warning: block '%s' starts %.4g m above '%s': it drops before it rests "
                   "(use seat-on '%s' to place it on top)\n",
                   b->name, b->gap, r->body[b->below].name, r->body[b->below].name);
            n++;
        }
        int twice = b->overlaps >= 0 && b->overlaps < i && !r->body[b->overlaps].fixed &&
                    r->body[b->overlaps].overlaps == i; /* told with the free body before it */
        if (b->overlap > RD_OVERLAP_TOL * size_of(b) && !twice) {
            printf("warning: block '%s' overlaps '%s' by %.4g m as placed: the contact springs "
                   "will throw them apart\n",
                   b->name, r->body[b->overlaps].name, b->overlap);
            n++;
        }
    }
    for (int i = 0; i < r->nbodies; i++) n += sink_warning(r, &r->body[i]);
    n += rd_cli_unit_warnings(sc);
    for (int i = 0; i < r->nbodies; i++)
        n += rd_cli_body_warnings(&sc->bodies[i], r->body[i].mass, r->body[i].extent,
                                  r->body[i].alpha_min);
    double per_sample = r->output_interval / r->dt;
    if (per_sample > RD_STEPS_PER_SAMPLE_MAX) {
        char by[2 * RD_NAME_MAX + 64] = "";
        if (r->dt_body >= 0)
            snprintf(by, sizeof by, ", set by block '%s' bearing on %s%s%s",
                     r->body[r->dt_body].name, r->dt_partner >= 0 ? "'" : "fixed bodies",
                     r->dt_partner >= 0 ? r->body[r->dt_partner].name : "",
                     r->dt_partner >= 0 ? "'" : "");
        printf(
            "warning: the time step %.3g s (limit %.3g s%s) is %.0f times shorter than the output "
            "interval %.3g s: each simulated second costs about %.3g s of wall time; check the "
            "contact stiffness and the smallest block\n",
            r->dt, r->dt_critical, by, per_sample, r->output_interval, r->wall_per_sim_s);
        n++;
    }
    if (r->has_records && r->motion_end < r->duration - 1e-9) {
        printf("warning: the ground-motion record ends at %.4g s but the run asks for %.4g s: the "
               "last %.4g s are free motion on still ground\n",
               r->motion_end, r->duration, r->duration - r->motion_end);
        n++;
    }
    return n;
}

/* A restored run reads its checkpoint first and compares its blocks (rd_sim_create): check
 * does the same, so a missing or mismatched checkpoint is refused here, not only by run. */
static int check_restore(const rd_scenario *sc, rd_error *err)
{
    if (!sc->restore_path[0]) return 0;
    rd_sim *sim = rd_sim_create(sc, err);
    rd_sim_free(sim);
    return sim ? 0 : -1;
}

int rd_cli_check(rd_scenario *sc, int quiet, int strict)
{
    rd_check_report r;
    rd_check_info info;
    rd_error err;
    if (!quiet && rd_cli_print_motion(&sc->motion)) return 2;
    /* what a run would refuse (meshes, budget, output file), then the report */
    if (rd_sim_check(sc, &info, &err) || check_restore(sc, &err) || rd_check_scene(sc, &r, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 2;
    }
    printf("%s: %d blocks, %d subcontacts, %d joint propert%s, duration %.4g s\n", sc->file,
           r.nbodies, r.npoints, r.njoints, r.njoints == 1 ? "y set" : "y sets", r.duration);
    printf("time step %.4g s (stability limit %.4g s), %.0f steps per output sample (%.3g s)\n",
           r.dt, r.dt_critical, r.output_interval / r.dt, r.output_interval);
    rd_cli_echo_inputs(sc);
    for (int i = 0; i < r.nbodies; i++) print_body(&r, &r.body[i]);
    printf("cost: %.3g s of wall time per simulated second (%d steps timed), about %.3g s for "
           "the run\n",
           r.wall_per_sim_s, r.trial_steps, r.wall_per_sim_s * r.duration);
    if (r.coarse_probe)
        printf(
            "note: what each body rests on and overlaps was found from its own subcontact points: "
            "the finer probe (an automatic bed) is past the point budget of %.0e; a block sunk into "
            "an aligned one below may go unseen\n",
            RD_POINT_BUDGET);
    int n = warnings(sc, &r);
    if (n)
        printf(
            "%s: %d warning%s (%d bodies, %d subcontact points, %.4g s; dt %.3g s, about %.3g steps; "
            "output %s)\n",
            sc->file, n, n == 1 ? "" : "s", sc->nbodies, info.npoints, sc->duration, info.dt,
            info.steps, sc->output.path);
    else
        printf(
            "%s: ok (%d bodies, %d subcontact points, %.4g s; dt %.3g s, about %.3g steps; output %s)\n",
            sc->file, sc->nbodies, info.npoints, sc->duration, info.dt, info.steps,
            sc->output.path);
    rd_check_free(&r);
    /* warnings are advice: the exit status says whether a run would be refused, unless --strict */
    return strict && n ? 1 : 0;
}
