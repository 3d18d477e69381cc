/* rockdem — the valid range of a read record's steps and samples, shared by the readers
 * (record.c: AT2 and text; record_fema.c: FEMA P695 sets) so that each refuses the same
 * inputs with its own "file[:line]: " prefix. Folder records/ owns ground motions; it may call
 * base/ only.
 */
#ifndef RD_RECORDS_RECORD_LIMITS_H
#define RD_RECORDS_RECORD_LIMITS_H

#include "rockdem/record.h"

/* Valid sample steps, s: strong-motion records are sampled at 1 Hz to 1 MHz; a step outside
 * this range is a misread header (or a unit error), not a record. */
#define RD_RECORD_DT_MIN   1e-6
#define RD_RECORD_DT_MAX   1.0
/* Most samples a record may hold: 1e9 (8 GB of doubles), far beyond any real record. */
#define RD_RECORD_NPTS_MAX 1e9
/* Largest |acceleration| a sample may have, m/s^2: the pulse amplitude's cap (scenario/values.c,
 * docs/LIMITS.md); earthquakes stay below 10 g, so a larger sample is a unit or format error. */
#define RD_RECORD_ACC_MAX  1e6

/* NULL when the sample step dt (s) lies in [RD_RECORD_DT_MIN, RD_RECORD_DT_MAX], else why not
 * (in buf). */
const char *rd_record_step_error(double dt, char *buf, size_t size);

/* NULL when a sample x, in a unit of `unit` m/s^2, is finite with |x unit| <= RD_RECORD_ACC_MAX,
 * else why not (in buf). */
const char *rd_record_sample_error(double x, double unit, char *buf, size_t size);

/* rd_record_read_text for a scenario's `units`: the values stay as written (the caller scales
 * them by unit, m/s^2 per file unit, afterwards) but are checked as accelerations in that unit. */
int rd_record_read_text_as(rd_record *r, const char *path, double unit, double dt, rd_error *err);

#endif
