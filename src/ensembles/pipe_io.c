/* rockdem — whole-message pipe reads and writes for the forked workers of threshold and sweep
 * (src/ensembles/pipe_io.h).
 * Folder ensembles/ owns many-run studies (threshold, restitution, sweeps); it may call the
 * public API (engine, scenario, reference) and io/.
 */
#include "ensembles/pipe_io.h"

#include <errno.h>
#include <unistd.h>

int rd_pipe_write(int fd, const void *buf, size_t n)
{
    const char *p = buf;
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return -1;
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

int rd_pipe_read(int fd, void *buf, size_t n)
{
    char *p = buf;
    size_t got = 0;
    while (got < n) {
        ssize_t r = read(fd, p + got, n - got);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return r == 0 && got == 0 ? 1 : -1;
        got += (size_t)r;
    }
    return 0;
}
