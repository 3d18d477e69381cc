/* rockdem — fault points (base/fault.h). */
#include "base/fault.h"

#include <signal.h>
#include <stdlib.h>
#include <string.h>

void rd_fault_point(const char *point)
{
    const char *want = getenv("RD_FAULT");
    if (!want) return;
    size_t n = strlen(point);
    if (strncmp(want, point, n) || (want[n] && want[n] != '@')) return;
    static long passes; /* one fault per process: the test names one point */
    long at = want[n] == '@' ? strtol(want + n + 1, NULL, 10) : 1;
    if (++passes == at) raise(SIGKILL);
}
