/* Embedding rockdem: a scene built in memory, run with no file at all, watched by an observer.
 *
 *   cc -std=c11 -Iinclude docs/examples/embed.c build/librockdem.so -o embed   (or `make examples`)
 *   ./embed              the built-in scene: a granite block on a pedestal, a one-sine pulse
 *   ./embed SCENE.dat    any scenario file (its `output hdf5` line is ignored: nothing is written)
 *
 * Prints each body's peak tilt, the events, and the cost per step (bench/scale.sh uses it).
 */
#include "rockdem/observer.h"
#include "rockdem/rockdem.h"

#include <stdio.h>
#include <time.h>

static const char *scene =
    "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n"
    "block create brick size 0.4 0.4 1.6 position 0 0 0.8 name statue\n"
    "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40\n"
    "ground-motion pulse one-sine amplitude 0.3g frequency 2\n"
    "model solve time 2\n";

/* An observer: the largest tilt of body 0 over the samples it is shown. */
static int watch(void *user, rd_sim *sim, const rd_sample *s, rd_error *err)
{
    (void)sim;
    (void)err;
    double *peak = user;
    if (s->tilt[0] > *peak) *peak = s->tilt[0];
    return 0;
}

int main(int argc, char **argv)
{
    rd_scenario sc;
    rd_error err;
    int rc = argc > 1 ? rd_scenario_load(&sc, argv[1], &err)
                      : rd_scenario_parse(&sc, "built-in", scene, &err);
    rd_sim *sim = rc ? NULL : rd_sim_create(&sc, &err);
    if (!rc) rd_scenario_free(&sc); /* the simulation owns a copy of everything it needs */
    if (!sim) {
        fprintf(stderr, "%s\n", err.msg);
        return 2;
    }
    double peak = 0;
    rd_observer obs = { .user = &peak, .sample = watch };
    rd_sim_add_observer(sim, &obs, &err);
    clock_t c0 = clock();
    rd_status st = rd_sim_run(sim);
    double cpu = (double)(clock() - c0) / CLOCKS_PER_SEC; /* CPU s: steady on a busy machine */
    rd_summary s;
    rd_sim_summary(sim, &s);
    int nev, nfixed, nfree = rd_sim_body_count(sim, &nfixed);
    rd_sim_events(sim, &nev);
    printf("status %d: %d free + %d fixed bodies, %ld steps of %.3g s, %d events\n", (int)st, nfree,
           nfixed, s.steps, s.dt, nev);
    printf("body 0: peak tilt %.4g rad (observer), %.4g rad (summary), alpha %.4g rad\n", peak,
           s.body[0].max_tilt, s.body[0].alpha);
    double all = s.steps + s.settle_time / s.dt; /* settling steps too */
    printf("cost: %.4g s wall for %ld shaking steps (%.4g us per step); %.4g s CPU for %.0f "
           "settling + shaking steps: %.4g us per step\n",
           s.wall_seconds, s.steps, s.steps ? 1e6 * s.wall_seconds / s.steps : 0, cpu, all,
           all > 0 ? 1e6 * cpu / all : 0);
    rd_sim_free(sim);
    return st == RD_STATUS_DONE || st == RD_STATUS_OVERTURNED ? 0 : 3;
}
