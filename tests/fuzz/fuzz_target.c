/* rockdem — fuzzing entry points for the readers of untrusted input: the scenario parser (with
 * its validation), the OBJ/PLY/STL mesh readers and the AT2/CSV record readers.
 *
 * rd_fuzz_run(target, data, size) feeds one input to one reader. Built with -DRD_FUZZ_TARGET=
 * "<name>" (Makefile `fuzz`, clang -fsanitize=fuzzer) this file is a libFuzzer target; included
 * by tests/test_fuzz_regress.c it replays the stored regression inputs in `make test`. The file
 * readers take a path, so an input is written to a private file in /dev/shm (a RAM file system;
 * $TMPDIR when /dev/shm is absent) under the extension that selects the reader. A reader may
 * refuse an input; it must never crash, leak, hang or invoke undefined behaviour (ASan/UBSan
 * abort on those). */
#include "geometry/geom.h"
#include "rockdem/record.h"
#include "rockdem/scenario.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Target names, each with the file extension its reader is chosen by ("" : in memory). */
static const struct {
    const char *name, *ext;
} rd_fuzz_targets[] = { { "scenario", "" }, { "obj", ".obj" }, { "ply", ".ply" },
                        { "stl", ".stl" },  { "at2", ".AT2" }, { "csv", ".csv" } };
enum { RD_FUZZ_NTARGETS = sizeof rd_fuzz_targets / sizeof rd_fuzz_targets[0] };

/* The input as a file named *ext; returns its path (static storage) or NULL. */
static const char *rd_fuzz_file(const uint8_t *data, size_t size, const char *ext)
{
    static char path[256];
    const char *dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/rdfuzz-%ld%s", dir ? dir : "/tmp", (long)getpid(), ext);
    FILE *f = fopen(path, "wb");
    if (!f) return NULL;
    size_t n = fwrite(data, 1, size, f);
    if (fclose(f) || n != size) return NULL;
    return path;
}

static void rd_fuzz_scenario(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return;
    memcpy(text, data, size);
    text[size] = '\0';
    static rd_scenario sc; /* large: keep it off the stack */
    rd_error err = { { 0 } };
    if (rd_scenario_parse(&sc, "fuzz.dat", text, &err) == 0) rd_scenario_validate(&sc, &err);
    rd_scenario_free(&sc);
    free(text);
}

/* Feed one input to reader `target` (an index into rd_fuzz_targets). */
static void rd_fuzz_run(int target, const uint8_t *data, size_t size)
{
    if (target == 0) {
        rd_fuzz_scenario(data, size);
        return;
    }
    const char *path = rd_fuzz_file(data, size, rd_fuzz_targets[target].ext);
    if (!path) return;
    rd_error err = { { 0 } };
    rd_record r = { 0 };
    rd_poly p = { 0 };
    double offset[3];
    if (target == 4)
        rd_record_read_at2(&r, path, &err);
    else if (target == 5)
        rd_record_read_text(&r, path, RD_UNIT_G, 0.01, &err);
    else if (rd_mesh_read(&p, path, offset, &err) == 0)
        rd_poly_free(&p);
    rd_record_free(&r);
    unlink(path);
}

#ifdef RD_FUZZ_TARGET
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int target = -1;
    for (int i = 0; target < 0 && i < RD_FUZZ_NTARGETS; i++)
        if (!strcmp(rd_fuzz_targets[i].name, RD_FUZZ_TARGET)) target = i;
    if (target < 0) abort(); /* a build error: unknown RD_FUZZ_TARGET */
    rd_fuzz_run(target, data, size);
    return 0;
}
#endif
