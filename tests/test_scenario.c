/* rockdem — tests of the scenario parser: the language, units, defaults, every error message
 * (file:line:col), command-line overrides and validation. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rockdem/scenario.h"

#define DEG (3.14159265358979323846 / 180.0)
#define G0  9.80665
#define EPS 1e-12

static rd_scenario *sc; /* one on the heap for all tests */

static int group_setup(void **state)
{
    (void)state;
    sc = calloc(1, sizeof *sc);
    return sc ? 0 : -1;
}

static int group_teardown(void **state)
{
    (void)state;
    free(sc);
    return 0;
}

static int test_teardown(void **state)
{
    (void)state;
    rd_scenario_free(sc);
    return 0;
}

/* A small valid scenario the override and validation tests start from. */
static const char *BASE = "model solve time 3\n"
                          "block create brick size 1 1 2 position 0 0 1 name cask\n"
                          "block create brick size 3 3 1 position 0 0 -0.5 name base fixed\n"
                          "ground-motion pulse one-sine amplitude 0.2g frequency 2\n";

static void parse_ok(const char *text)
{
    rd_error err = { "" };
    int rc = rd_scenario_parse(sc, "run.dat", text, &err);
    if (rc != 0) print_error("unexpected error: %s\n", err.msg);
    assert_int_equal(rc, 0);
}

/* text must fail to parse with exactly msg; nothing stays allocated. */
static void parse_fails(const char *text, const char *msg)
{
    rd_error err = { "" };
    assert_int_equal(rd_scenario_parse(sc, "run.dat", text, &err), -1);
    assert_string_equal(err.msg, msg);
    assert_null(sc->text);
}

/* A text with a NUL byte given with its length (Python's bytes): refused with the offset, where
 * a C string would have ended at the NUL and the rest (here the ground motion) been lost. The
 * same text without the NUL parses. */
static void test_parse_n_nul(void **state)
{
    (void)state;
    rd_error err = { "" };
    char text[512];
    size_t n = (size_t)snprintf(text, sizeof text, "%s", BASE);
    size_t at = strstr(text, "ground-motion") - text;
    text[at - 1] = '\0';
    assert_int_equal(rd_scenario_parse_n(sc, "run.dat", text, n, &err), -1);
    char want[128];
    snprintf(want, sizeof want, "run.dat: contains a NUL byte at offset %zu of %zu (not a text?)",
             at - 1, n);
    assert_string_equal(err.msg, want);
    assert_null(sc->text);
    text[at - 1] = '\n';
    assert_int_equal(rd_scenario_parse_n(sc, "run.dat", text, n, &err), 0);
    assert_non_null(strstr(sc->text, "ground-motion"));
}

static void set_fails(const char *assignment, const char *msg)
{
    rd_error err = { "" };
    assert_int_equal(rd_scenario_set(sc, assignment, &err), -1);
    assert_string_equal(err.msg, msg);
}

static void set_ok(const char *assignment)
{
    rd_error err = { "" };
    int rc = rd_scenario_set(sc, assignment, &err);
    if (rc != 0) print_error("unexpected error: %s\n", err.msg);
    assert_int_equal(rc, 0);
}

static void validate_fails(const char *msg)
{
    rd_error err = { "" };
    assert_int_equal(rd_scenario_validate(sc, &err), -1);
    assert_string_equal(err.msg, msg);
}

/* Writes len bytes of data to a fresh temporary file; its name goes to path. */
static void write_temp(char *path, const char *data, size_t len)
{
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, data, len), (ssize_t)len);
    close(fd);
}

/* ---- good input ---- */

static void test_defaults(void **state)
{
    (void)state;
    rd_scenario_defaults(sc);
    assert_int_equal(sc->nbodies, 0);
    assert_null(sc->text);
    assert_float_equal(sc->gravity, 9.81, EPS);
    assert_float_equal(sc->density, 2700.0, EPS);
    assert_float_equal(sc->contact.kn, 1e10, 1.0);
    assert_float_equal(sc->contact.ks, 1e11, 1.0);
    assert_float_equal(sc->contact.friction, 40.0 * DEG, EPS);
    assert_float_equal(sc->contact.cohesion, 0.0, EPS);
    assert_float_equal(sc->contact.tension, 0.0, EPS);
    assert_float_equal(sc->contact.spacing, 0.0, EPS);
    assert_int_equal(sc->damping.kind, RD_DAMPING_NONE);
    assert_int_equal(sc->timestep.kind, RD_TIMESTEP_AUTO);
    assert_float_equal(sc->timestep.safety, 0.2, EPS);
    assert_int_equal(sc->settle.enabled, 1);
    assert_float_equal(sc->settle.ratio, 1e-6, 1e-18);
    assert_float_equal(sc->settle.max_time, 5.0, EPS);
    assert_int_equal(sc->overturn.kind, RD_OVERTURN_TILT_RATIO);
    assert_float_equal(sc->overturn.value, 1.5, EPS);
    assert_int_equal(sc->overturn.stop, 1);
    assert_string_equal(sc->output.path, "rockdem.h5");
    assert_float_equal(sc->output.interval, 0.005, EPS);
    assert_float_equal(sc->duration, 0.0, EPS);
    assert_int_equal(sc->motion.horizontal.kind, RD_PULSE_NONE);
    assert_int_equal(sc->motion.vertical.kind, RD_PULSE_NONE);
    assert_float_equal(sc->motion.horizontal.cycles, 1.0, EPS);
    assert_string_equal(sc->title, "");
}

static const char *FULL =
    "; rockdem test scenario\n"
    "model title 'Two \"blocks\" on a pedestal'   ; a comment after a string\n"
    "model gravity 9.80665\n"
    "model density 2500\n"
    "model damping viscous 0.05\n"
    "model timestep auto safety 0.3\n"
    "model settle on ratio 1e-5 time-limit 2\n"
    "model solve time 12.5\n"
    "model overturn angle 30 stop off\n"
    "block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base\n"
    "block create brick name cask size 0.5 0.6 1.5 &   ; continued\n"
    "    position 0.1 -0.2 0.75 rotation 0 0 90 mass 1200\n"
    "block create brick size 0.4 0.4 1.0 position 1 1 0.5 density 2400\n"
    "block initial name cask tilt 2 direction 45 velocity 0.1 0 0 angular-velocity 0 0.5 0\n"
    "contact property friction 35 stiffness-normal 2e9 stiffness-shear 5e8 cohesion 1e3 &\n"
    "  tension 2e3 spacing 0.05\n"
    "ground-motion pulse one-sine amplitude 0.3g frequency 2 direction 90 start 0.5\n"
    "ground-motion pulse harmonic amplitude -1.5 frequency 4 cycles 3 vertical\n"
    "output hdf5 \"out dir/run.h5\" interval 0.01";

static void test_full_scenario_model(void **state)
{
    (void)state;
    parse_ok(FULL);
    assert_string_equal(sc->file, "run.dat");
    assert_string_equal(sc->text, FULL);
    assert_string_equal(sc->title, "Two \"blocks\" on a pedestal");
    assert_float_equal(sc->gravity, 9.80665, EPS);
    assert_float_equal(sc->density, 2500.0, EPS);
    assert_int_equal(sc->damping.kind, RD_DAMPING_VISCOUS);
    assert_float_equal(sc->damping.value, 0.05, EPS);
    assert_int_equal(sc->timestep.kind, RD_TIMESTEP_AUTO);
    assert_float_equal(sc->timestep.safety, 0.3, EPS);
    assert_int_equal(sc->settle.enabled, 1);
    assert_float_equal(sc->settle.ratio, 1e-5, 1e-18);
    assert_float_equal(sc->settle.max_time, 2.0, EPS);
    assert_float_equal(sc->duration, 12.5, EPS);
    assert_int_equal(sc->overturn.kind, RD_OVERTURN_ANGLE);
    assert_float_equal(sc->overturn.value, 30.0 * DEG, EPS);
    assert_int_equal(sc->overturn.stop, 0);
    assert_string_equal(sc->output.path, "out dir/run.h5");
    assert_float_equal(sc->output.interval, 0.01, EPS);
}

static void test_full_scenario_blocks(void **state)
{
    (void)state;
    parse_ok(FULL);
    assert_int_equal(sc->nbodies, 3);
    const rd_body_def *base = &sc->bodies[0], *cask = &sc->bodies[1], *third = &sc->bodies[2];
    assert_string_equal(base->name, "base");
    assert_int_equal(base->fixed, 1);
    assert_int_equal(base->line, 10);
    assert_float_equal(base->position[2], -0.25, EPS);
    assert_string_equal(cask->name, "cask");
    assert_int_equal(cask->shape, RD_SHAPE_BRICK);
    assert_int_equal(cask->fixed, 0);
    assert_int_equal(cask->line, 11);
    assert_float_equal(cask->size[0], 0.5, EPS);
    assert_float_equal(cask->size[1], 0.6, EPS);
    assert_float_equal(cask->size[2], 1.5, EPS);
    assert_float_equal(cask->position[0], 0.1, EPS);
    assert_float_equal(cask->position[1], -0.2, EPS);
    assert_float_equal(cask->position[2], 0.75, EPS);
    assert_float_equal(cask->rotation[0], 0.0, EPS);
    assert_float_equal(cask->rotation[2], 90.0 * DEG, EPS);
    assert_float_equal(cask->mass, 1200.0, EPS);
    assert_float_equal(cask->density, 0.0, EPS);
    assert_float_equal(cask->tilt, 2.0 * DEG, EPS);
    assert_float_equal(cask->tilt_direction, 45.0 * DEG, EPS);
    assert_float_equal(cask->velocity[0], 0.1, EPS);
    assert_float_equal(cask->angular_velocity[1], 0.5, EPS);
    assert_string_equal(third->name, "block3");
    assert_int_equal(third->line, 13);
    assert_float_equal(third->density, 2400.0, EPS);
    assert_float_equal(third->tilt, 0.0, EPS);
}

static void test_full_scenario_contact_and_motion(void **state)
{
    (void)state;
    parse_ok(FULL);
    assert_float_equal(sc->contact.friction, 35.0 * DEG, EPS);
    assert_float_equal(sc->contact.kn, 2e9, 1e-3);
    assert_float_equal(sc->contact.ks, 5e8, 1e-3);
    assert_float_equal(sc->contact.cohesion, 1e3, EPS);
    assert_float_equal(sc->contact.tension, 2e3, EPS);
    assert_float_equal(sc->contact.spacing, 0.05, EPS);
    const rd_pulse_def *h = &sc->motion.horizontal, *v = &sc->motion.vertical;
    assert_int_equal(h->kind, RD_PULSE_ONE_SINE);
    assert_float_equal(h->amplitude, 0.3 * G0, EPS);
    assert_float_equal(h->frequency, 2.0, EPS);
    assert_float_equal(h->duration, 0.5, EPS);
    assert_float_equal(h->direction, 90.0 * DEG, EPS);
    assert_float_equal(h->start, 0.5, EPS);
    assert_int_equal(h->line, 17);
    assert_int_equal(v->kind, RD_PULSE_HARMONIC);
    assert_float_equal(v->amplitude, -1.5, EPS);
    assert_float_equal(v->cycles, 3.0, EPS);
    assert_float_equal(v->duration, 0.75, EPS);
    assert_int_equal(v->line, 18);
}

static void test_case_order_crlf_and_blank_lines(void **state)
{
    (void)state;
    parse_ok("\r\n   \n; only a comment\r\n"
             "MODEL Solve TIME 2\r\n"
             "block create brick position 0 0 0.5 fixed size 1 1 1\r\n"
             "\tblock create brick position 0 0 1.5 size 1 1 1 ; comment & ignored 'x\r\n"
             "model damping local 0.8\n"
             "model timestep fixed 1e-5\n"
             "model settle off\n"
             "model overturn height 0.5\n");
    assert_float_equal(sc->duration, 2.0, EPS);
    assert_int_equal(sc->nbodies, 2);
    assert_string_equal(sc->bodies[0].name, "block1");
    assert_int_equal(sc->bodies[0].fixed, 1);
    assert_string_equal(sc->bodies[1].name, "block2");
    assert_int_equal(sc->bodies[1].line, 6);
    assert_int_equal(sc->damping.kind, RD_DAMPING_LOCAL);
    assert_float_equal(sc->damping.value, 0.8, EPS);
    assert_int_equal(sc->timestep.kind, RD_TIMESTEP_FIXED);
    assert_float_equal(sc->timestep.dt, 1e-5, 1e-18);
    assert_int_equal(sc->settle.enabled, 0);
    assert_int_equal(sc->overturn.kind, RD_OVERTURN_HEIGHT);
    assert_float_equal(sc->overturn.value, 0.5, EPS);
}

static void test_spacing_words(void **state)
{
    (void)state;
    parse_ok("contact property spacing vertices\n");
    assert_float_equal(sc->contact.spacing, 0.0, EPS);
    rd_scenario_free(sc);
    parse_ok("contact property spacing auto\n");
    assert_float_equal(sc->contact.spacing, -1.0, EPS);
}

static void test_pulse_durations(void **state)
{
    (void)state;
    parse_ok("ground-motion pulse rectangular amplitude 2 frequency 4\n"
             "ground-motion pulse triangle amplitude 1g duration 0.3 vertical\n");
    assert_int_equal(sc->motion.horizontal.kind, RD_PULSE_RECTANGULAR);
    assert_float_equal(sc->motion.horizontal.duration, 0.25, EPS);
    assert_int_equal(sc->motion.vertical.kind, RD_PULSE_TRIANGLE);
    assert_float_equal(sc->motion.vertical.amplitude, G0, EPS);
    assert_float_equal(sc->motion.vertical.duration, 0.3, EPS);
    rd_scenario_free(sc);
    parse_ok("ground-motion pulse one-cosine amplitude -0.5g frequency 5\n");
    assert_int_equal(sc->motion.horizontal.kind, RD_PULSE_ONE_COSINE);
    assert_float_equal(sc->motion.horizontal.amplitude, -0.5 * G0, EPS);
    assert_float_equal(sc->motion.horizontal.duration, 0.2, EPS);
    assert_float_equal(sc->motion.horizontal.cycles, 1.0, EPS);
}

static void test_empty_text_parses(void **state)
{
    (void)state;
    parse_ok("");
    assert_int_equal(sc->nbodies, 0);
    assert_string_equal(sc->text, "");
}

static void test_load_file(void **state)
{
    (void)state;
    char path[] = "/tmp/rd_scenario_XXXXXX";
    write_temp(path, BASE, strlen(BASE));
    rd_error err = { "" };
    int rc = rd_scenario_load(sc, path, &err);
    unlink(path);
    assert_int_equal(rc, 0);
    assert_string_equal(sc->file, path);
    assert_string_equal(sc->text, BASE);
    assert_int_equal(sc->nbodies, 2);
}

static void test_load_missing_file(void **state)
{
    (void)state;
    rd_error err = { "" };
    assert_int_equal(rd_scenario_load(sc, "/nonexistent/run.dat", &err), -1);
    assert_string_equal(err.msg, "/nonexistent/run.dat: cannot open: No such file or directory");
    assert_null(sc->text);
}

static void test_load_reports_line_and_col(void **state)
{
    (void)state;
    char path[] = "/tmp/rd_scenario_XXXXXX";
    write_temp(path, "model solve time 1\nmodel solve tme 1\n", 37);
    rd_error err = { "" }, want = { "" };
    assert_int_equal(rd_scenario_load(sc, path, &err), -1);
    unlink(path);
    snprintf(
        want.msg, sizeof want.msg,
        "%s:2:13: unknown keyword 'tme' for 'model solve' (expected time, tail, force, until, time-limit)",
        path);
    assert_string_equal(err.msg, want.msg);
}

static void test_load_large_file(void **state)
{
    (void)state;
    char path[] = "/tmp/rd_scenario_XXXXXX";
    static const char comment[] = "; a long comment line to make the file span several buffers\n";
    size_t n = 200, clen = strlen(comment), blen = strlen(BASE);
    char *text = malloc(n * clen + blen + 1);
    assert_non_null(text);
    for (size_t i = 0; i < n; i++) memcpy(text + i * clen, comment, clen);
    memcpy(text + n * clen, BASE, blen + 1);
    write_temp(path, text, n * clen + blen);
    rd_error err = { "" };
    int rc = rd_scenario_load(sc, path, &err);
    unlink(path);
    assert_int_equal(rc, 0);
    assert_string_equal(sc->text, text);
    free(text);
    assert_int_equal(sc->nbodies, 2);
    assert_int_equal(sc->bodies[1].line, 203);
}

static void test_load_unreadable(void **state)
{
    (void)state;
    char path[] = "/tmp/rd_scenario_XXXXXX", want[RD_ERROR_MAX];
    rd_error err = { "" };
    assert_int_equal(rd_scenario_load(sc, "/tmp", &err), -1);
    assert_string_equal(err.msg, "/tmp: cannot read: Is a directory");
    write_temp(path, "model solve time 1\n\0\n", 21);
    assert_int_equal(rd_scenario_load(sc, path, &err), -1);
    unlink(path);
    snprintf(want, sizeof want, "%s: contains a NUL byte (not a text file?)", path);
    assert_string_equal(err.msg, want);
    assert_null(sc->text);
}

/* ---- lexical errors ---- */

static void test_error_unterminated_string(void **state)
{
    (void)state;
    parse_fails("model solve time 1\nmodel title 'open end\n",
                "run.dat:2:13: unterminated string (missing closing ')");
}

static void test_error_text_after_quote(void **state)
{
    (void)state;
    parse_fails("output hdf5 'a.h5'x\n", "run.dat:1:19: expected a space after the closing quote");
}

static void test_error_continuation_at_eof(void **state)
{
    (void)state;
    parse_fails("model solve time 1\nmodel gravity &\n",
                "run.dat:2:15: '&' continuation at end of file");
    parse_fails("model gravity &", "run.dat:1:15: '&' continuation at end of file");
}

static void test_error_ampersand_not_last(void **state)
{
    (void)state;
    parse_fails("model gravity & 9.81\n", "run.dat:1:15: '&' must be the last token on its line");
}

static void test_error_position_on_continuation_line(void **state)
{
    (void)state;
    parse_fails("block create brick size 1 1 1 &\n"
                "  position 0 0 x\n",
                "run.dat:2:16: expected a number after 'position', got 'x'");
}

/* ---- command and keyword errors ---- */

static void test_error_unknown_command(void **state)
{
    (void)state;
    parse_fails("modle solve time 1\n",
                "run.dat:1:1: unknown command 'modle' (expected model, block, contact, "
                "ground-motion, history, output)");
}

static void test_error_unknown_and_missing_verb(void **state)
{
    (void)state;
    parse_fails("  block crate brick\n",
                "run.dat:1:9: unknown verb 'crate' for 'block' (expected create, import, initial)");
    parse_fails(
        "contact\n",
        "run.dat:1:1: missing verb after 'contact' (expected property, interface-perturbation, preset, model)");
}

static void test_error_unknown_keyword(void **state)
{
    (void)state;
    parse_fails(
        "model solve time 1\n\n\n\n\n\n"
        "   contact property frction 30\n",
        "run.dat:7:21: unknown keyword 'frction' for 'contact property' (expected "
        "stiffness-normal, stiffness-shear, friction, cohesion, tension, spacing, restitution, friction-coefficient)");
}

static void test_error_duplicate_keyword(void **state)
{
    (void)state;
    parse_fails("contact property friction 30 friction 35\n",
                "run.dat:1:30: keyword 'friction' given twice");
}

/* A single-valued setting given twice: the last one silently won (KN, friction, the step,
 * the title, the output, a block's initial tilt, a joint range's property). Refused at the
 * repeat with the line of the first; settings that add up (histories, bodies, contact
 * property lines of different keys, overlapping joint ranges) stay allowed. */
static void test_error_repeated_setting(void **state)
{
    (void)state;
    parse_fails(
        "contact property stiffness-normal 1e10\ncontact property stiffness-normal 2e10\n",
        "run.dat:2:18: 'stiffness-normal' of 'contact property' already given on line 1; give each "
        "setting once");
    parse_fails(
        "contact property friction 30 spacing 0.1\n; comment\ncontact property friction 35\n",
        "run.dat:3:18: 'friction' of 'contact property' already given on line 1; give each setting once");
    parse_fails("model timestep fixed 1e-5\nmodel timestep auto safety 0.1\n",
                "run.dat:2:1: 'model timestep' already given on line 1; give each setting once");
    parse_fails(
        "model solve time 1\nmodel solve time 2 tail 1\n",
        "run.dat:2:13: 'time' of 'model solve' already given on line 1; give each setting once");
    parse_fails("model gravity 9.81\nmodel gravity 1.62\n",
                "run.dat:2:1: 'model gravity' already given on line 1; give each setting once");
    parse_fails("model title 'a'\nmodel title 'b'\n",
                "run.dat:2:1: 'model title' already given on line 1; "
                "give each setting once");
    parse_fails("model damping viscous 0.1\nmodel damping none\n",
                "run.dat:2:1: 'model damping' already given on line 1; give each setting once");
    parse_fails(
        "model settle off\nmodel settle on ratio 1e-5\n",
        "run.dat:2:14: 'on|off' of 'model settle' already given on line 1; give each setting once");
    parse_fails(
        "model overturn angle 30\nmodel overturn tilt-ratio 1\n",
        "run.dat:2:16: 'tilt-ratio|angle|height|off-pedestal' of 'model overturn' already given on line "
        "1; give each setting once");
    parse_fails("output hdf5 'a.h5'\noutput hdf5 'b.h5' interval 0.01\n",
                "run.dat:2:1: 'output hdf5' already given on line 1; give each setting once");
    parse_fails("history interval 0.01\nhistory interval 0.02\n",
                "run.dat:2:1: 'history interval' already given on line 1; give each setting once");
    parse_fails(
        "contact interface-perturbation seed 1 raise 0.001\ncontact interface-perturbation seed 2\n",
        "run.dat:2:32: 'seed' of 'contact interface-perturbation' already given on line 1; give each "
        "setting once");
    parse_fails(
        "model reference restitution 0.5\nmodel reference restitution 0.6\n",
        "run.dat:2:17: 'restitution' of 'model reference' already given on line 1; give each setting once");
    parse_fails(
        "block create brick size 1 1 1 position 0 0 0.5 name b\nblock initial name b tilt 1\n"
        "block initial name b velocity 1 0 0 tilt 2\n",
        "run.dat:3:37: 'tilt' of 'block initial name b' already given on line 2; give each setting once");
    parse_fails(
        "block create brick size 1 1 1 position 0 0 0.5 name a\nblock create brick size 1 1 1 "
        "position 0 0 1.5 name b\ncontact property friction 30 range block 'a' block 'b'\n"
        "contact property friction 20 damping 0 range block 'b' block 'a'\n",
        "run.dat:4:18: 'friction' of 'contact property ... range block 'a' block 'b'' already given on "
        "line 3; give each setting once");
    parse_fails("contact preset rigid\ncontact preset 3dec\n",
                "run.dat:2:1: 'contact preset' already given on line 1; give each setting once");
    /* a preset replaces the whole contact and the damping: one after them dropped them */
    parse_fails(
        "contact property friction 30\ncontact preset rigid\n",
        "run.dat:2:1: 'contact preset' would replace 'friction' of 'contact property' given on line 1; "
        "give the preset first");
    parse_fails(
        "model damping viscous 0.1\ncontact preset rigid\n",
        "run.dat:2:1: 'contact preset' would replace 'model damping' given on line 1; give the preset first");
    /* allowed: different keys on separate lines, a preset then single values, overlapping ranges,
       histories that add up, another block's initial conditions */
    parse_ok(
        "block create brick size 1 1 1 position 0 0 0.5 name a group 'g'\n"
        "block create brick size 1 1 1 position 0 0 1.5 name b\n"
        "contact preset rigid\ncontact property friction 30\ncontact property stiffness-normal 2e10\n"
        "model damping viscous 0.1\nmodel settle off\nmodel settle time-limit 2\n"
        "model overturn angle 30\nmodel overturn stop off\n"
        "contact property friction 20 range group 'g'\ncontact property friction 25 range block 'a' block 'b'\n"
        "contact property stiffness-normal 1e9 range block 'b' block 'a'\n"
        "block initial name a tilt 1\nblock initial name b tilt 2\nblock initial name a velocity 1 0 0\n"
        "history body 'a' position\nhistory body 'a' velocity\nmodel solve time 1\nmodel solve tail 2\n");
    assert_float_equal(sc->contact.friction, 30 * M_PI / 180, EPS);
    assert_float_equal(sc->contact.kn, 2e10, EPS);
    assert_int_equal(sc->njoints, 3);
}

static void test_error_missing_value(void **state)
{
    (void)state;
    parse_fails("block create brick position 0 0 0 size\n",
                "run.dat:1:35: expected a number after 'size'");
    parse_fails("block create brick size 1 2 position 0 0 0\n",
                "run.dat:1:29: expected a number after 'size', got 'position'");
    parse_fails("model gravity\n", "run.dat:1:7: expected a number after 'gravity'");
}

static void test_error_not_a_number(void **state)
{
    (void)state;
    parse_fails("contact property stiffness-normal 1e10x\n",
                "run.dat:1:35: expected a number after 'stiffness-normal', got '1e10x'");
    parse_fails("ground-motion pulse one-sine amplitude 1 frequency 2g\n",
                "run.dat:1:52: expected a number after 'frequency', got '2g'");
    parse_fails("model density nan\n",
                "run.dat:1:15: expected a number after 'density', got 'nan'");
}

static void test_error_out_of_range(void **state)
{
    (void)state;
    parse_fails("contact property stiffness-normal 0\n",
                "run.dat:1:35: 'stiffness-normal' must be > 0, got 0");
    parse_fails("contact property friction 90\n",
                "run.dat:1:27: 'friction' must be in [0, 90) degrees, got 90");
    parse_fails("contact property friction -1\n",
                "run.dat:1:27: 'friction' must be in [0, 90) degrees, got -1");
    parse_fails("block create brick size 1 -2 1 position 0 0 0\n",
                "run.dat:1:27: 'size' must be > 0, got -2");
    parse_fails("model timestep auto safety 1.5\n",
                "run.dat:1:28: 'safety' must be in (0, 1], got 1.5");
    parse_fails("model damping viscous 0\n", "run.dat:1:23: 'viscous' must be in (0, 10], got 0");
    parse_fails("model damping local 1\n", "run.dat:1:21: 'local' must be in (0, 1), got 1");
    parse_fails("output hdf5 x.h5 interval 0\n", "run.dat:1:27: 'interval' must be > 0, got 0");
    parse_fails(
        "contact property spacing -0.1\n",
        "run.dat:1:26: 'spacing' -0.1 is outside its valid range [1e-06, 10000] m (docs/LIMITS.md)");
}

static void test_error_unexpected_token(void **state)
{
    (void)state;
    parse_fails("model gravity 9.81 5\n", "run.dat:1:20: unexpected '5' after 'model gravity'");
    parse_fails("model title My rocks\n", "run.dat:1:16: unexpected 'rocks' after 'model title'");
}

static void test_error_exclusive_keywords(void **state)
{
    (void)state;
    parse_fails("model damping none local 0.5\n",
                "run.dat:1:20: 'local' cannot be combined with 'none'");
    parse_fails("block create brick size 1 1 1 position 0 0 0 mass 10 density 2000\n",
                "run.dat:1:54: 'density' cannot be combined with 'mass'");
    parse_fails("model timestep fixed 1e-5 safety 0.5\n",
                "run.dat:1:27: 'safety' applies only to 'model timestep auto'");
    parse_fails(
        "model damping\n",
        "run.dat:1:7: missing keyword after 'model damping' (expected none, viscous, local)");
}

static void test_error_switch(void **state)
{
    (void)state;
    parse_fails("model overturn stop maybe\n",
                "run.dat:1:21: expected on or off after 'stop', got 'maybe'");
}

/* ---- block errors ---- */

static void test_error_block_shape_and_required(void **state)
{
    (void)state;
    parse_fails(
        "block create sphere size 1\n",
        "run.dat:1:14: unknown shape 'sphere' for 'block create' (expected brick, prism, polyhedron, column or stack)");
    parse_fails("block create brick position 0 0 0\n",
                "run.dat:1:14: missing 'size' for 'block create brick'");
    parse_fails("block create brick size 1 1 1\n",
                "run.dat:1:14: missing 'position' or 'seat-on' for 'block create brick'");
}

static void test_error_duplicate_block_name(void **state)
{
    (void)state;
    parse_fails("block create brick size 1 1 1 position 0 0 0 name a\n"
                "block create brick size 1 1 1 position 0 0 2 name a\n",
                "run.dat:2:51: duplicate block name 'a' (first created on line 1)");
    parse_fails("block create brick size 1 1 1 position 0 0 0 name block2\n"
                "block create brick size 1 1 1 position 0 0 2\n",
                "run.dat:2:14: default name 'block2' is already taken (line 1); give this block "
                "a name");
}

static void test_error_invalid_block_name(void **state)
{
    (void)state;
    parse_fails("block create brick size 1 1 1 position 0 0 0 name a.b\n",
                "run.dat:1:51: invalid block name 'a.b' (1 to 63 letters, digits, '_' or '-')");
}

/* No cap on the number of blocks (issue 14): 5,000 load, named block1 .. block5000. */
static void test_many_blocks(void **state)
{
    (void)state;
    static const char line[] = "block create brick size 1 1 1 position 0 0 0\n";
    size_t n = 5000, len = strlen(line);
    char *text = malloc(n * len + 1);
    assert_non_null(text);
    for (size_t i = 0; i < n; i++) memcpy(text + i * len, line, len);
    text[n * len] = '\0';
    rd_error err = { "" };
    int rc = rd_scenario_parse(sc, "run.dat", text, &err);
    free(text);
    if (rc) fail_msg("%s", err.msg);
    assert_int_equal(sc->nbodies, 5000);
    assert_string_equal(sc->bodies[4999].name, "block5000");
}

static void test_error_block_initial(void **state)
{
    (void)state;
    parse_fails("block initial name cask tilt 5\n"
                "block create brick size 1 1 1 position 0 0 0 name cask\n",
                "run.dat:1:20: unknown block 'cask' (no 'block create ... name cask' before this "
                "line)");
    parse_fails("block create brick size 1 1 1 position 0 0 0 name base fixed\n"
                "block initial tilt 5 name base\n",
                "run.dat:2:27: block 'base' is fixed; 'block initial' applies only to free blocks");
    parse_fails("block initial tilt 5\n", "run.dat:1:7: missing 'name' for 'block initial'");
    parse_fails(
        "block create brick size 1 1 1 position 0 0 0 name a\nblock initial name a tilt 90\n",
        "run.dat:2:27: 'tilt' must be in [0, 90) degrees, got 90");
}

/* ---- ground-motion errors ---- */

static void test_error_pulse(void **state)
{
    (void)state;
    parse_fails("ground-motion pulse one-sin amplitude 1\n",
                "run.dat:1:21: unknown pulse shape 'one-sin' (expected one-sine, one-cosine, "
                "rectangular, triangle, harmonic)");
    parse_fails("ground-motion pulse one-sine frequency 2\n",
                "run.dat:1:21: missing 'amplitude' for 'ground-motion pulse'");
    parse_fails("ground-motion pulse one-sine amplitude 0.3g\n",
                "run.dat:1:21: a one-sine pulse needs 'frequency'");
    parse_fails("ground-motion pulse harmonic amplitude 1 frequency 2 duration 1\n",
                "run.dat:1:54: 'duration' does not apply to a harmonic pulse (set 'frequency')");
    parse_fails("ground-motion pulse rectangular amplitude 1 duration 1 cycles 2\n",
                "run.dat:1:56: 'cycles' applies only to harmonic pulses");
    parse_fails("ground-motion pulse triangle amplitude 1\n",
                "run.dat:1:21: a triangle pulse needs 'duration' (or 'frequency')");
    parse_fails("ground-motion pulse triangle amplitude 1 frequency 2 duration 0.5\n",
                "run.dat:1:54: 'duration' cannot be combined with 'frequency'");
    parse_fails("ground-motion pulse triangle amplitude 1 duration 1 direction 30 vertical\n",
                "run.dat:1:53: 'direction' does not apply to a vertical pulse");
}

static void test_error_second_pulse(void **state)
{
    (void)state;
    parse_fails("ground-motion pulse one-sine amplitude 1 frequency 1\n"
                "ground-motion pulse one-sine amplitude 1 frequency 1 vertical\n"
                "ground-motion pulse one-sine amplitude 1 frequency 2\n",
                "run.dat:3:1: a horizontal pulse is already defined (line 1)");
}

/* ---- overrides ---- */

static void test_set_good(void **state)
{
    (void)state;
    parse_ok(BASE);
    set_ok("contact.stiffness-normal=5e9");
    set_ok("contact.friction=30");
    set_ok("contact.spacing=vertices");
    set_ok("model.damping=viscous 0.05");
    set_ok("model.timestep=2e-6");
    set_ok("model.settle=off");
    set_ok("contact.model=surface");
    set_ok("model.gravity=1g");
    set_ok("motion.amplitude=0.4g");
    set_ok("motion.direction=45");
    set_ok("output.file=sweep/a.h5");
    set_ok("block.cask.mass=900");
    set_ok("block.cask.tilt=3");
    set_ok("body.base.density=2600");
    assert_float_equal(sc->contact.kn, 5e9, 1e-3);
    assert_float_equal(sc->contact.friction, 30.0 * DEG, EPS);
    assert_float_equal(sc->contact.spacing, 0.0, EPS);
    assert_int_equal(sc->damping.kind, RD_DAMPING_VISCOUS);
    assert_float_equal(sc->damping.value, 0.05, EPS);
    assert_int_equal(sc->timestep.kind, RD_TIMESTEP_FIXED);
    assert_float_equal(sc->timestep.dt, 2e-6, 1e-18);
    assert_int_equal(sc->settle.enabled, 0);
    assert_int_equal(sc->contact.model, RD_CONTACT_SURFACE);
    assert_float_equal(sc->gravity, G0, EPS);
    assert_float_equal(sc->motion.horizontal.amplitude, 0.4 * G0, EPS);
    assert_float_equal(sc->motion.horizontal.direction, 45.0 * DEG, EPS);
    assert_string_equal(sc->output.path, "sweep/a.h5");
    assert_float_equal(sc->bodies[0].mass, 900.0, EPS);
    assert_float_equal(sc->bodies[0].density, 0.0, EPS);
    assert_float_equal(sc->bodies[0].tilt, 3.0 * DEG, EPS);
    assert_float_equal(sc->bodies[1].density, 2600.0, EPS);
}

static void test_set_without_parse(void **state)
{
    (void)state;
    rd_scenario_defaults(sc);
    set_ok("model.safety=0.5");
    set_ok("contact.spacing=auto");
    assert_float_equal(sc->timestep.safety, 0.5, EPS);
    assert_float_equal(sc->contact.spacing, -1.0, EPS);
    assert_string_equal(sc->text, "; --set model.safety=0.5\n; --set contact.spacing=auto\n");
}

static void test_set_records_in_text(void **state)
{
    (void)state;
    parse_ok("model solve time 1"); /* no final newline */
    set_ok("model.duration=4");
    set_ok("model.damping=none");
    assert_float_equal(sc->duration, 4.0, EPS);
    assert_string_equal(
        sc->text, "model solve time 1\n; --set model.duration=4\n; --set model.damping=none\n");
}

static void test_set_pulse_rederives_duration(void **state)
{
    (void)state;
    parse_ok(BASE);
    set_ok("motion.frequency=4");
    assert_float_equal(sc->motion.horizontal.duration, 0.25, EPS);
    rd_scenario_free(sc);
    parse_ok("ground-motion pulse rectangular amplitude 1 frequency 2\n"
             "ground-motion pulse harmonic amplitude 1 frequency 2 vertical\n");
    set_ok("motion.duration=0.3");
    assert_float_equal(sc->motion.horizontal.duration, 0.3, EPS);
    assert_float_equal(sc->motion.horizontal.frequency, 0.0, EPS);
    set_ok("motion.vertical-amplitude=-0.1g");
    assert_float_equal(sc->motion.vertical.amplitude, -0.1 * G0, EPS);
}

static void test_set_bad_key(void **state)
{
    (void)state;
    parse_ok(BASE);
    set_fails(
        "contact.frction=30",
        "--set contact.frction=30: unknown key 'contact.frction' (expected "
        "contact.stiffness-normal, contact.stiffness-shear, contact.friction, contact.friction-coefficient, "
        "contact.cohesion, contact.tension, contact.spacing, contact.restitution, contact.interface-seed, "
        "contact.interface-remove, contact.interface-raise, contact.interface-scatter, contact.model)");
    set_fails("solver.dt=1", "--set solver.dt=1: unknown key 'solver.dt' (expected a key in "
                             "contact, model, motion, output or block.<name>)");
    set_fails("model.gravity", "--set model.gravity: expected section.key=value");
    set_fails("block.rock.mass=1", "--set block.rock.mass=1: unknown block 'rock'");
    set_fails("block.cask.volume=1",
              "--set block.cask.volume=1: unknown key 'volume' (expected block.cask.density, "
              "mass, tilt or direction)");
    set_fails("block.base.tilt=2",
              "--set block.base.tilt=2: block 'base' is fixed; tilt applies only to free blocks");
    assert_string_equal(sc->text, BASE); /* failures record nothing */
}

static void test_set_bad_value(void **state)
{
    (void)state;
    parse_ok(BASE);
    set_fails("contact.stiffness-normal=-1",
              "--set contact.stiffness-normal=-1: value must be > 0");
    set_fails("contact.friction=abc", "--set contact.friction=abc: expected a number, got 'abc'");
    set_fails("contact.spacing=some",
              "--set contact.spacing=some: expected a number, auto or vertices, got 'some'");
    set_fails("model.damping=viscous 12",
              "--set model.damping=viscous 12: value must be in (0, 10]");
    set_fails("contact.model=mortar",
              "--set contact.model=mortar: expected vertex or surface, got 'mortar'");
    set_fails("model.damping=sticky",
              "--set model.damping=sticky: expected none, viscous <ratio> or local <alpha>, got "
              "'sticky'");
    set_fails("model.timestep=soon",
              "--set model.timestep=soon: expected auto or a time step in s, got 'soon'");
    set_fails("model.settle=yes", "--set model.settle=yes: expected on or off, got 'yes'");
    set_fails("output.interval=0", "--set output.interval=0: value must be > 0");
    set_fails("output.file=", "--set output.file=: empty file name");
    set_fails("motion.duration=1",
              "--set motion.duration=1: motion.duration applies only to rectangular and triangle "
              "pulses (set motion.frequency)");
    set_fails("motion.cycles=2",
              "--set motion.cycles=2: motion.cycles applies only to harmonic pulses");
    set_fails(
        "motion.vertical-amplitude=1g",
        "--set motion.vertical-amplitude=1g: the scenario has no vertical ground-motion pulse");
    assert_float_equal(sc->contact.kn, 1e10, 1.0);
}

/* ---- validation ---- */

static void test_validate_ok(void **state)
{
    (void)state;
    parse_ok(BASE);
    rd_error err = { "" };
    assert_int_equal(rd_scenario_validate(sc, &err), 0);
    rd_scenario_free(sc);
    parse_ok(FULL);
    assert_int_equal(rd_scenario_validate(sc, &err), 0);
}

static void test_validate_no_free_block(void **state)
{
    (void)state;
    parse_ok("");
    validate_fails("run.dat: no free block (add 'block create brick ...' without 'fixed')");
    rd_scenario_free(sc);
    parse_ok("model solve time 1\nblock create brick size 1 1 1 position 0 0 0 fixed\n");
    validate_fails("run.dat: no free block (add 'block create brick ...' without 'fixed')");
}

static void test_validate_no_duration(void **state)
{
    (void)state;
    parse_ok("block create brick size 1 1 1 position 0 0 0.5\n");
    validate_fails("run.dat: no duration (add 'model solve time <s>')");
}

static void test_validate_fields_set_by_hand(void **state)
{
    (void)state;
    parse_ok(BASE);
    sc->bodies[0].size[1] = 0.0;
    validate_fails("run.dat:2: block 'cask': size must be > 0");
    sc->bodies[0].size[1] = 1.0;
    strcpy(sc->bodies[1].name, "cask");
    validate_fails("run.dat:3: block 'cask': name used by an earlier block");
    strcpy(sc->bodies[1].name, "base");
    sc->contact.ks = 0.0;
    validate_fails("run.dat: contact stiffness-normal and stiffness-shear must be > 0");
    sc->contact.ks = 1e9;
    sc->motion.horizontal.frequency = 0.0;
    validate_fails("run.dat:4: horizontal pulse: frequency must be > 0");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_defaults, test_teardown),
        cmocka_unit_test_teardown(test_parse_n_nul, test_teardown),
        cmocka_unit_test_teardown(test_full_scenario_model, test_teardown),
        cmocka_unit_test_teardown(test_full_scenario_blocks, test_teardown),
        cmocka_unit_test_teardown(test_full_scenario_contact_and_motion, test_teardown),
        cmocka_unit_test_teardown(test_case_order_crlf_and_blank_lines, test_teardown),
        cmocka_unit_test_teardown(test_spacing_words, test_teardown),
        cmocka_unit_test_teardown(test_pulse_durations, test_teardown),
        cmocka_unit_test_teardown(test_empty_text_parses, test_teardown),
        cmocka_unit_test_teardown(test_load_file, test_teardown),
        cmocka_unit_test_teardown(test_load_missing_file, test_teardown),
        cmocka_unit_test_teardown(test_load_reports_line_and_col, test_teardown),
        cmocka_unit_test_teardown(test_load_large_file, test_teardown),
        cmocka_unit_test_teardown(test_load_unreadable, test_teardown),
        cmocka_unit_test_teardown(test_error_unterminated_string, test_teardown),
        cmocka_unit_test_teardown(test_error_text_after_quote, test_teardown),
        cmocka_unit_test_teardown(test_error_continuation_at_eof, test_teardown),
        cmocka_unit_test_teardown(test_error_ampersand_not_last, test_teardown),
        cmocka_unit_test_teardown(test_error_position_on_continuation_line, test_teardown),
        cmocka_unit_test_teardown(test_error_unknown_command, test_teardown),
        cmocka_unit_test_teardown(test_error_unknown_and_missing_verb, test_teardown),
        cmocka_unit_test_teardown(test_error_unknown_keyword, test_teardown),
        cmocka_unit_test_teardown(test_error_duplicate_keyword, test_teardown),
        cmocka_unit_test_teardown(test_error_repeated_setting, test_teardown),
        cmocka_unit_test_teardown(test_error_missing_value, test_teardown),
        cmocka_unit_test_teardown(test_error_not_a_number, test_teardown),
        cmocka_unit_test_teardown(test_error_out_of_range, test_teardown),
        cmocka_unit_test_teardown(test_error_unexpected_token, test_teardown),
        cmocka_unit_test_teardown(test_error_exclusive_keywords, test_teardown),
        cmocka_unit_test_teardown(test_error_switch, test_teardown),
        cmocka_unit_test_teardown(test_error_block_shape_and_required, test_teardown),
        cmocka_unit_test_teardown(test_error_duplicate_block_name, test_teardown),
        cmocka_unit_test_teardown(test_error_invalid_block_name, test_teardown),
        cmocka_unit_test_teardown(test_many_blocks, test_teardown),
        cmocka_unit_test_teardown(test_error_block_initial, test_teardown),
        cmocka_unit_test_teardown(test_error_pulse, test_teardown),
        cmocka_unit_test_teardown(test_error_second_pulse, test_teardown),
        cmocka_unit_test_teardown(test_set_good, test_teardown),
        cmocka_unit_test_teardown(test_set_records_in_text, test_teardown),
        cmocka_unit_test_teardown(test_set_without_parse, test_teardown),
        cmocka_unit_test_teardown(test_set_pulse_rederives_duration, test_teardown),
        cmocka_unit_test_teardown(test_set_bad_key, test_teardown),
        cmocka_unit_test_teardown(test_set_bad_value, test_teardown),
        cmocka_unit_test_teardown(test_validate_ok, test_teardown),
        cmocka_unit_test_teardown(test_validate_no_free_block, test_teardown),
        cmocka_unit_test_teardown(test_validate_no_duration, test_teardown),
        cmocka_unit_test_teardown(test_validate_fields_set_by_hand, test_teardown),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
