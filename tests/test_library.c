/* The library as an embedding program sees it (issue 14): a run with no file at all, observers
 * (samples, events, summary), the HDF5 file as one observer, a per-simulation stop beside the
 * process-wide one, a run stepped in pieces, HDF5's error printing left as the program set it, and the progress of a
 * threshold scan run on several worker processes. Only the public headers are used. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "rockdem/observer.h"
#include "rockdem/output.h"
#include "rockdem/rockdem.h"
#include "rockdem/validate.h"

#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "tmpdir.h"

/* A 0.4 x 0.4 x 1.6 m block on a base, shaken by a sine pulse for 0.5 s. */
static const char *scene =
    "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n"
    "block create brick size 0.4 0.4 1.6 position 0 0 0.8 name b\n"
    "contact property stiffness-normal 1e9 stiffness-shear 1e8 friction 40 spacing vertices\n"
    "ground-motion pulse one-sine amplitude 1 frequency 2\n"
    "model solve time 0.5\n"
    "output hdf5 'x.h5' interval 0.01\n";

static rd_sim *create(rd_scenario *sc, const char *file)
{
    rd_error err;
    char set[160];
    assert_int_equal(rd_scenario_parse(sc, "lib.dat", scene, &err), 0);
    snprintf(set, sizeof set, "output.file=%s/%s", tmpdir, file);
    assert_int_equal(rd_scenario_set(sc, set, &err), 0);
    rd_sim *sim = rd_sim_create(sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    return sim;
}

/* rd_sim_stop stops its own simulation at once (no step taken) and no other. */
static void test_stop_one_simulation(void **state)
{
    (void)state;
    rd_scenario sa, sb;
    rd_sim *a = create(&sa, "a.h5"), *b = create(&sb, "b.h5");
    rd_sim_stop(a);
    assert_int_equal(rd_sim_run(a), RD_STATUS_INTERRUPTED);
    assert_int_equal(rd_sim_run(b), RD_STATUS_DONE);
    rd_summary ra, rb;
    rd_sim_summary(a, &ra);
    rd_sim_summary(b, &rb);
    assert_int_equal(ra.steps, 0);
    assert_true(rb.end_time >= 0.5 - rd_sim_dt(b)); /* ran its whole 0.5 s */
    rd_sim_free(a);
    rd_sim_free(b);
    rd_scenario_free(&sa);
    rd_scenario_free(&sb);
}

/* rd_sim_start / rd_sim_advance / rd_sim_finish: a run stepped in pieces (100 steps, to 0.2 s,
 * then to the end) ends in the same state, bit for bit, as rd_sim_run (the same loop); each
 * piece stops where it was asked to, to within half a step; a run finished before its end is
 * interrupted, and further calls change nothing. */
static void test_stepped_run(void **state)
{
    (void)state;
    rd_scenario sa, sb, sc;
    rd_sim *a = create(&sa, "whole.h5"), *b = create(&sb, "stepped.h5"),
           *c = create(&sc, "early.h5");
    assert_true(isnan(rd_sim_end_time(b)));
    assert_int_equal(rd_sim_run(a), RD_STATUS_DONE);
    assert_int_equal(rd_sim_start(b), 1);
    assert_true(fabs(rd_sim_end_time(b) - 0.5) < 1e-12);
    assert_int_equal(rd_sim_advance(b, 100, INFINITY), 1);
    assert_true(fabs(rd_sim_time(b) - 100 * rd_sim_dt(b)) < 1e-12);
    assert_int_equal(rd_sim_advance(b, -1, 0.2), 1);
    assert_true(fabs(rd_sim_time(b) - 0.2) <= 0.5 * rd_sim_dt(b));
    assert_int_equal(rd_sim_advance(b, -1, INFINITY), 0);
    assert_int_equal(rd_sim_finish(b), RD_STATUS_DONE);
    rd_summary ra, rb;
    rd_sim_summary(a, &ra);
    rd_sim_summary(b, &rb);
    assert_int_equal(ra.steps, rb.steps);
    assert_true(ra.body[0].max_tilt == rb.body[0].max_tilt);
    double xa[3], xb[3], qa[4], qb[4];
    rd_sim_body_state(a, 0, xa, qa, NULL, NULL);
    rd_sim_body_state(b, 0, xb, qb, NULL, NULL);
    assert_memory_equal(xa, xb, sizeof xa);
    assert_memory_equal(qa, qb, sizeof qa);
    assert_int_equal(rd_sim_start(c), 1);
    assert_int_equal(rd_sim_advance(c, 10, INFINITY), 1);
    assert_int_equal(rd_sim_finish(c), RD_STATUS_INTERRUPTED);
    assert_int_equal(rd_sim_advance(c, 10, INFINITY), 0);
    assert_int_equal(rd_sim_finish(c), RD_STATUS_INTERRUPTED);
    rd_summary rc;
    rd_sim_summary(c, &rc);
    assert_int_equal(rc.steps, 10);
    rd_sim_free(a);
    rd_sim_free(b);
    rd_sim_free(c);
    rd_scenario_free(&sa);
    rd_scenario_free(&sb);
    rd_scenario_free(&sc);
}

static int printed;
static herr_t count_errors(hid_t stack, void *data)
{
    (void)stack;
    (void)data;
    printed++;
    return 0;
}

/* An embedding program's HDF5 error handler is neither replaced nor called by rockdem's own
 * failing HDF5 calls (an output file in a folder that does not exist), and still works after. */
static void test_hdf5_error_handler_kept(void **state)
{
    (void)state;
    H5Eset_auto2(H5E_DEFAULT, count_errors, NULL);
    rd_scenario sc;
    rd_error err;
    assert_int_equal(rd_scenario_parse(&sc, "lib.dat", scene, &err), 0);
    char set[160];
    snprintf(set, sizeof set, "output.file=%s/no/such/dir/x.h5", tmpdir);
    assert_int_equal(rd_scenario_set(&sc, set, &err), 0);
    rd_sim *sim = rd_sim_create(&sc, &err);
    assert_non_null(sim);
    assert_int_equal(rd_sim_write_hdf5(sim, sc.output.path, &err), -1);
    rd_sim_free(sim);
    assert_non_null(strstr(err.msg, "cannot create file"));
    assert_int_equal(printed, 0);
    H5E_auto2_t fn = NULL;
    void *data = NULL;
    H5Eget_auto2(H5E_DEFAULT, &fn, &data);
    assert_ptr_equal(fn, count_errors);
    H5Fopen("/nonexistent/rockdem.h5", H5F_ACC_RDONLY, H5P_DEFAULT); /* the program's own call */
    assert_true(printed > 0);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    rd_scenario_free(&sc);
}

/* What a counting observer saw. */
typedef struct seen {
    int begins, samples, events, ends, released;
    double last_time, first_alpha;
    long steps;
} seen;

static int count_begin(void *u, rd_sim *sim, rd_error *err)
{
    (void)err;
    seen *s = u;
    rd_body_info b;
    rd_sim_body_info(sim, 0, &b);
    s->first_alpha = b.alpha;
    s->begins++;
    return 0;
}

static int count_sample(void *u, rd_sim *sim, const rd_sample *smp, rd_error *err)
{
    (void)sim;
    (void)err;
    seen *s = u;
    s->samples++;
    s->last_time = smp->time;
    return 0;
}

static int count_event(void *u, rd_sim *sim, const rd_event *e, rd_error *err)
{
    (void)sim;
    (void)e;
    (void)err;
    ((seen *)u)->events++;
    return 0;
}

static int count_end(void *u, rd_sim *sim, const rd_summary *sum, rd_error *err)
{
    (void)sim;
    (void)err;
    seen *s = u;
    s->ends++;
    s->steps = sum->steps;
    return 0;
}

static void count_release(void *u) { ((seen *)u)->released++; }

/* No observer: the run creates no file (the scenario names one) and summarises as with one.
 * Observers get begin once (the bodies at rest: alpha of the 0.4 x 1.6 m block is
 * atan(0.2 / 0.8)), every sample (a second one every 5th: 0.5 s at 0.01 s gives 51 samples
 * with the final one, so ceil(51 / 5) = 11), every event, end once and release once. */
static void test_observers_no_file(void **state)
{
    (void)state;
    rd_scenario sc;
    rd_error err;
    assert_int_equal(rd_scenario_parse(&sc, "lib.dat", scene, &err), 0);
    char path[160];
    snprintf(path, sizeof path, "%s/none.h5", tmpdir);
    snprintf(sc.output.path, sizeof sc.output.path, "%s", path);
    rd_sim *sim = rd_sim_create(&sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    seen all = { 0 }, fifth = { 0 };
    rd_observer a = { .user = &all,
                      .begin = count_begin,
                      .sample = count_sample,
                      .event = count_event,
                      .end = count_end,
                      .release = count_release };
    rd_observer b = { .user = &fifth, .every = 5, .sample = count_sample };
    assert_int_equal(rd_sim_add_observer(sim, &a, &err), 0);
    assert_int_equal(rd_sim_add_observer(sim, &b, &err), 0);
    assert_int_equal(rd_sim_run(sim), RD_STATUS_DONE);
    assert_int_equal(access(path, F_OK), -1);
    int nev;
    rd_sim_events(sim, &nev);
    rd_summary sum;
    rd_sim_summary(sim, &sum);
    assert_int_equal(all.begins, 1);
    assert_int_equal(all.ends, 1);
    assert_int_equal(all.events, nev);
    assert_int_equal(all.samples, 51);
    assert_int_equal(fifth.samples, 11);
    assert_true(fabs(all.last_time - sum.end_time) < 1e-12);
    assert_int_equal(all.steps, sum.steps);
    assert_true(fabs(all.first_alpha - atan(0.25)) < 1e-6); /* rest tilt of a few micro-rad */
    rd_sim_free(sim);
    assert_int_equal(all.released, 1);
    rd_scenario_free(&sc);
}

/* Ownership: rd_sim_create copies what it needs (records, hull vertices, text), so the scenario
 * may be freed before rd_sim_run. A stochastic record (samples on the heap) drives a hull block;
 * the freed scenario's memory is then reused and scribbled over. The run must equal one whose
 * scenario stayed alive, bit for bit (same code path, same inputs); `valgrind
 * build/tests/test_library` reports no invalid read. */
static const char *owned_scene =
    "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n"
    "block create polyhedron vertices -0.2 -0.2 0  0.2 -0.2 0  0.2 0.2 0  -0.2 0.2 0 &\n"
    "    -0.2 -0.2 1.2  0.2 -0.2 1.2  0.2 0.2 1.2  -0.2 0.2 1.2 position 0 0 0.6 name b\n"
    "contact property stiffness-normal 1e9 stiffness-shear 1e8 friction 40 spacing vertices\n"
    "ground-motion stochastic seed 7 pga 0.4g duration 1 dt 0.01\n"
    "model solve time 1\n";

/* Run the owned scene, the scenario freed (and its memory reused) before rd_sim_run when
 * free_first; *body receives the free body's summary, kept past rd_sim_free. */
static void owned_run(int free_first, rd_summary *sum, rd_body_summary *body)
{
    rd_scenario sc;
    rd_error err;
    assert_int_equal(rd_scenario_parse(&sc, "own.dat", owned_scene, &err), 0);
    rd_sim *sim = rd_sim_create(&sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    void *scribble[64] = { 0 };
    if (free_first) {
        rd_scenario_free(&sc);
        memset(&sc, 0xab, sizeof sc);
        for (int k = 0; k < 64; k++) /* reuse the freed blocks */
            if ((scribble[k] = malloc(4096))) memset(scribble[k], 0xcd, 4096);
    }
    assert_int_equal(rd_sim_run(sim), RD_STATUS_DONE);
    for (int k = 0; k < 64; k++) free(scribble[k]);
    rd_sim_summary(sim, sum);
    assert_int_equal(sum->nbodies, 1);
    *body = sum->body[0];
    sum->body = body;
    assert_string_equal(rd_sim_scenario(sim)->bodies[1].name, "b");
    rd_sim_free(sim);
    if (!free_first) rd_scenario_free(&sc);
}

static void test_free_scenario_before_run(void **state)
{
    (void)state;
    rd_summary kept, freed;
    rd_body_summary kept_body, freed_body;
    owned_run(0, &kept, &kept_body);
    owned_run(1, &freed, &freed_body);
    assert_true(kept.body[0].max_tilt > 0);
    assert_true(kept.body[0].max_tilt == freed.body[0].max_tilt);
    assert_true(kept.body[0].max_slide == freed.body[0].max_slide);
    assert_int_equal(kept.steps, freed.steps);
}

/* Progress as a bar reads it (cli_progress.c's rule): a new run where t falls back; runs' worth
 * done = runs before this one + t / t_end of it. */
typedef struct progress_seen {
    int runs, calls, backwards;
    double t_prev, done;
} progress_seen;
static void count_progress(void *ctx, double t, double t_end)
{
    progress_seen *p = ctx;
    if (t < p->t_prev || p->runs == 0) p->runs++;
    p->t_prev = t;
    double done = p->runs - 1 + (t_end > 0 ? fmin(t / t_end, 1.0) : 0.0);
    p->backwards += done < p->done;
    p->done = done;
    p->calls++;
}

/* rd_threshold with jobs 2 runs its coarse scan in worker processes; the progress callback of
 * the calling process must follow the whole scan: one run counted per run made (the scan's and
 * the bisection's), never going back. (Before, only the first worker of each batch drew, in its
 * own process: the caller saw the bisection runs alone.) */
static void test_threshold_progress_jobs(void **state)
{
    (void)state;
    rd_scenario sc;
    rd_error err;
    if (rd_scenario_load(&sc, "tests/cli/data/sweep_brick.dat", &err)) fail_msg("%s", err.msg);
    char set[160];
    snprintf(set, sizeof set, "output.file=%s/threshold.h5", tmpdir);
    assert_int_equal(rd_scenario_set(&sc, set, &err), 0);
    rd_threshold_opts o = rd_threshold_opts_default();
    o.lo = 3.5;
    o.hi = 7;
    o.nscan = 12;
    o.jobs = 2;
    o.rtol = 0.01; /* bisection runs follow the scan */
    progress_seen seen = { 0 };
    rd_set_progress(count_progress, &seen);
    rd_threshold_result r;
    int rc = rd_threshold(&sc, RD_ENGINE_DEM, &o, &r, &err);
    rd_set_progress(NULL, NULL);
    rd_scenario_free(&sc);
    if (rc) fail_msg("%s", err.msg);
    print_message("threshold -j 2: %d runs, %d counted from %d reports\n", r.runs, seen.runs,
                  seen.calls);
    assert_true(r.found && r.runs > o.jobs);
    assert_int_equal(seen.runs, r.runs);
    assert_int_equal(seen.backwards, 0);
}

/* A slender block that overturns beside a squat one that never does: a run stops when every
 * free body lies down (stop 1: this one runs its whole 3 s), or, with RD_OVERTURN_STOP_ANY (the
 * threshold's runs, whose question is only whether anything overturns), once the slender block
 * lies down, its verdict overturned and the squat one's not. Before, a threshold run went on
 * through the rest of a collapse and its energy balance was judged there (the six-drum column
 * at 0.574 g: untrusted at 3.4 s, after col-d6 had overturned at 2.28 s; exit 3). */
static const char *two_blocks =
    "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n"
    "block create brick size 0.2 0.2 1.2 position -1 0 0.6 name slender\n"
    "block create brick size 1 1 0.3 position 1 0 0.15 name squat\n"
    "contact property stiffness-normal 1e9 stiffness-shear 1e10 friction 60 spacing vertices\n"
    "ground-motion pulse one-sine amplitude 1g frequency 2\n"
    "model overturn tilt-ratio 1.0\n"
    "model solve time 3\n";

/* sum->body belongs to the simulation: its first body's overturn time is copied to *fall_time
 * (s) before the simulation is freed. */
static void run_two_blocks(int stop, rd_summary *sum, double *dt, double *fall_time)
{
    rd_scenario sc;
    rd_error err;
    assert_int_equal(rd_scenario_parse(&sc, "two.dat", two_blocks, &err), 0);
    sc.overturn.stop = stop;
    rd_sim *sim = rd_sim_create(&sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    rd_sim_run(sim);
    rd_sim_summary(sim, sum);
    *dt = rd_sim_dt(sim);
    rd_body_summary b[2] = { sum->body[0], sum->body[1] };
    print_message("stop %d: status %s at t = %.4g s; slender overturned %d at %.4g s, squat %d\n",
                  stop, rd_status_name(sum->status), sum->end_time, b[0].overturned,
                  b[0].overturn_time, b[1].overturned);
    assert_true(b[0].overturned && !b[1].overturned);
    *fall_time = b[0].overturn_time;
    sum->body = NULL;
    rd_sim_free(sim);
    rd_scenario_free(&sc);
}

static void test_stop_at_first_fall(void **state)
{
    (void)state;
    rd_summary every, any;
    double dt, fall;
    run_two_blocks(1, &every, &dt, &fall);
    assert_int_equal(every.status, RD_STATUS_DONE);
    assert_true(every.end_time >= 3 - dt); /* the squat block never lies down */
    run_two_blocks(RD_OVERTURN_STOP_ANY, &any, &dt, &fall);
    assert_int_equal(any.status, RD_STATUS_OVERTURNED);
    assert_true(any.end_time < 3 - dt);
    assert_true(any.end_time >= fall); /* stopped once it lay down */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stop_one_simulation),
        cmocka_unit_test(test_stepped_run),
        cmocka_unit_test(test_hdf5_error_handler_kept),
        cmocka_unit_test(test_observers_no_file),
        cmocka_unit_test(test_free_scenario_before_run),
        cmocka_unit_test(test_threshold_progress_jobs),
        cmocka_unit_test(test_stop_at_first_fall),
    };
    return cmocka_run_group_tests(tests, setup_dir, remove_dir);
}
