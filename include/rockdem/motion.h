/* rockdem — ground motion: the acceleration, velocity and displacement of the ground (and so of
 * every fixed body) as functions of time. The engine runs in the ground frame and applies the
 * ground acceleration as a pseudo-force -m a_g to every free body (exact for a translating frame).
 * Axes: x, y horizontal, z up; SI units.
 */
#ifndef ROCKDEM_MOTION_H
#define ROCKDEM_MOTION_H

#include "rockdem/api.h"
#include "rockdem/record.h"
#include "rockdem/scenario.h"

/* One pulse at time t: acceleration a (m/s^2), velocity v (m/s) and displacement d (m), the
 * exact integrals of a from the pulse start with zero initial velocity and displacement. */
RD_API void rd_pulse_eval(const rd_pulse_def *p, double t, double *a, double *v, double *d);

/* Time at which the pulse ends (start + its duration), s; 0 for RD_PULSE_NONE. */
RD_API double rd_pulse_end(const rd_pulse_def *p);

/* The whole ground motion at time t as 3-vectors (x, y, z): the horizontal pulse along its
 * direction plus the applied records (h1 along m->direction, h2 at +90 deg, vertical up).
 * Records cost O(1) per call (the sample index is t / dt). */
RD_API void rd_motion_eval(const rd_motion_def *m, double t, double acc[3], double vel[3],
                           double disp[3]);

/* Time at which all motion has ended, s (0 when there is none). */
RD_API double rd_motion_end(const rd_motion_def *m);

/* --- motion_record.c: recorded and synthetic components ---------------------------------- */

/* Read (or generate) component c (RD_H1, RD_H2, RD_VERTICAL) from its definition into its raw
 * record, replacing any earlier one. Errors name the file: "path: message". */
RD_API int rd_motion_load(rd_motion_def *m, int c, rd_error *err);

/* Build every applied record from its raw one: baseline correction (m->baseline), then one
 * scale factor for all components (m->scale; stored in m->factor). 0 or -1. */
RD_API int rd_motion_prepare(rd_motion_def *m, rd_error *err);

/* 1 when any record component is defined. */
RD_API int rd_motion_has_records(const rd_motion_def *m);

/* Free the records of every component (the definitions stay). */
RD_API void rd_motion_release(rd_motion_def *m);

/* Deep copy of src's records into dst (the rest of dst is src's by value): dst owns its
 * records (rd_motion_release). 0, or -1 with err (dst then holds no records). */
RD_API int rd_motion_copy(rd_motion_def *dst, const rd_motion_def *src, rd_error *err);

/* Intensity measures of one applied component: peaks, Arias, D5-95 (im) and the 5 %-damped
 * pseudo-spectral accelerations at 0.2 s and 1 s (sa[0], sa[1], m/s^2; the record is padded with
 * 2 s of rest so long-period oscillators reach their peak). 0, or -1 (no record, no memory). */
RD_API int rd_motion_im(const rd_motion_def *m, int c, struct rd_im *im, double sa[2],
                        rd_error *err);

/* Short name of component c: "h1", "h2", "vertical". */
RD_API const char *rd_motion_component_name(int c);

#endif
