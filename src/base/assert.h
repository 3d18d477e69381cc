/* rockdem — RD_ASSERT: internal invariants, checked in debug and sanitizer builds.
 *
 * An invariant is a fact the code relies on that no input can break (a pair index within its
 * table, a unit quaternion after normalising, a body mass above zero once built). Bad input is
 * never an assertion: it gets an rd_error line and a non-zero exit. With RD_DEBUG defined
 * (`make asan`, `make debug`), a failed assertion prints the condition, file and line on stderr
 * and aborts; otherwise the condition is not evaluated (it must have no side effects), and
 * sizeof keeps its variables "used" so -Wunused stays quiet.
 */
#ifndef RD_BASE_ASSERT_H
#define RD_BASE_ASSERT_H

#ifdef RD_DEBUG
void rd_assert_fail(const char *cond, const char *file, int line);
#define RD_ASSERT(c) ((c) ? (void)0 : rd_assert_fail(#c, __FILE__, __LINE__))
#else
#define RD_ASSERT(c) ((void)sizeof(!(c)))
#endif

#endif
