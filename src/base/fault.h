/* rockdem (private) — fault points: named places inside a write where a test can kill the
 * program, so that "a kill at any instant leaves the old valid file or the new one" is tested
 * without a debugger. The environment variable RD_FAULT=point[@n] makes the n-th (default
 * first) pass through rd_fault_point("point") raise SIGKILL. Unset (every real run), a fault
 * point costs one getenv. The points and what a kill there must leave: docs/HDF5-LAYOUT.md ("Writing safely").
 * Folder base/ owns errors, vectors, named constants, path checks and fault points.
 */
#ifndef RD_FAULT_H
#define RD_FAULT_H

/* Kill the program here (SIGKILL) when RD_FAULT names this point and pass. */
void rd_fault_point(const char *point);

#endif
