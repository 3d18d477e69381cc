/* rockdem — error reporting shared by every fallible call.
 *
 * Every fallible function returns an int status (0 = success, non-zero = failure, as in
 * SUNDIALS/GSL) and fills an rd_error with one line of text. Scenario errors read
 * "file:line:col: message"; other errors name the file or object concerned.
 */
#ifndef ROCKDEM_ERROR_H
#define ROCKDEM_ERROR_H

#include "rockdem/api.h"

#include <stddef.h>

#define RD_ERROR_MAX 512

typedef struct rd_error {
    char msg[RD_ERROR_MAX]; /* one line, no trailing newline; empty when no error */
} rd_error;

/* printf-style setter; always returns -1 so callers can write `return rd_error_set(...)`. */
RD_API int rd_error_set(rd_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

#endif
