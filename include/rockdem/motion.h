/* rockdem — ground motion: the acceleration, velocity and displacement of the ground (and so of
 * every fixed body) as functions of time. The engine runs in the ground frame and applies the
 * ground acceleration as a pseudo-force -m a_g to every free body (exact for a translating frame).
 * Axes: x, y horizontal, z up; SI units.
 */
#ifndef ROCKDEM_MOTION_H
#define ROCKDEM_MOTION_H

#include "rockdem/scenario.h"

/* One pulse at time t: acceleration a (m/s^2), velocity v (m/s) and displacement d (m), the
 * exact integrals of a from the pulse start with zero initial velocity and displacement. */
void rd_pulse_eval(const rd_pulse_def *p, double t, double *a, double *v, double *d);

/* Time at which the pulse ends (start + its duration), s; 0 for RD_PULSE_NONE. */
double rd_pulse_end(const rd_pulse_def *p);

/* The whole ground motion at time t as 3-vectors (x, y, z), horizontal pulse along its direction. */
void rd_motion_eval(const rd_motion_def *m, double t, double acc[3], double vel[3], double disp[3]);

/* Time at which all motion has ended, s (0 when there is none). */
double rd_motion_end(const rd_motion_def *m);

#endif
