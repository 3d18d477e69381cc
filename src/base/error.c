/* rockdem — rd_error: one line of text describing the last failure.
 * Folder base/ owns errors, vectors and named constants; it calls nothing else in rockdem.
 */
#include "rockdem/error.h"
#include "base/assert.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

int rd_error_set(rd_error *err, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
    }
    return -1;
}

#ifdef RD_DEBUG
void rd_assert_fail(const char *cond, const char *file, int line)
{
    fprintf(stderr, "rockdem: internal invariant broken at %s:%d: %s\n", file, line, cond);
    abort();
}
#endif
