/* Replay of the fuzzing inputs (tests/fuzz/): every stored regression input (a crash, hang or
 * sanitizer report found by `make fuzz`, since fixed) and every seed of the corpus is fed to
 * its reader again. Each must be read or refused without a crash; under `make asan` also
 * without a sanitizer report. Run from the repository root (make test does). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tests/fuzz/fuzz_target.c"

/* Feed every file in dir to reader `target`; returns how many there were. */
static int replay_dir(int target, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.') continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        FILE *f = fopen(path, "rb");
        assert_non_null(f);
        static uint8_t buf[1 << 20];
        size_t len = fread(buf, 1, sizeof buf, f);
        fclose(f);
        rd_fuzz_run(target, buf, len);
        n++;
    }
    closedir(d);
    return n;
}

static void test_replay(void **state)
{
    (void)state;
    int regress = 0, seeds = 0;
    for (int t = 0; t < RD_FUZZ_NTARGETS; t++) {
        char dir[256];
        snprintf(dir, sizeof dir, "tests/fuzz/regress/%s", rd_fuzz_targets[t].name);
        regress += replay_dir(t, dir);
        snprintf(dir, sizeof dir, "tests/fuzz/corpus/%s", rd_fuzz_targets[t].name);
        int s = replay_dir(t, dir);
        if (s == 0) fail_msg("no seed inputs in %s (run from the repository root)", dir);
        seeds += s;
    }
    printf("replayed %d regression inputs and %d seeds\n", regress, seeds);
}

int main(void)
{
    const struct CMUnitTest tests[] = { cmocka_unit_test(test_replay) };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
