/* rockdem (private) — whole-message reads and writes on the pipes between a many-run study's
 * coordinator and its forked workers (`rockdem threshold`'s scan, `rockdem sweep`'s pool). A pipe
 * may return less than asked, or be interrupted by a signal (EINTR: the sweep's stop handler);
 * these loop until the whole message has passed.
 */
#ifndef RD_PIPE_IO_H
#define RD_PIPE_IO_H

#include <stddef.h>

/* Write all n bytes of buf to fd: 0, or -1 on an error (a closed pipe). */
int rd_pipe_write(int fd, const void *buf, size_t n);

/* Read exactly n bytes from fd into buf: 0; 1 when the pipe is at end-of-file before any byte
 * (the writer closed it between messages); -1 on an error or a message cut short. */
int rd_pipe_read(int fd, void *buf, size_t n);

#endif
