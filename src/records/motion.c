/* rockdem — built-in ground-motion pulses and their exact integrals.
 *
 * Each pulse is an acceleration history a(tau), tau = t - start (s), that is zero before the
 * start and after the pulse ends. Velocity v (m/s) and displacement d (m) are the closed-form
 * integrals of a from rest; after the end a = 0, v keeps its end value and d grows linearly
 * with it (a pulse that leaves a net velocity, such as the rectangular one, keeps the ground
 * moving: the engine runs in the ground frame, so only a matters for the bodies).
 *
 * Folder records/ owns ground motions (records, readers, stochastic generation, intensity
 * measures, SDOF); it may call base/ only.
 */
#include "rockdem/motion.h"
#include "rockdem/record.h"
#include "records/motion_axes.h"

#include <math.h>

/* Length of the pulse, s (from its start). */
static double pulse_length(const rd_pulse_def *p)
{
    switch (p->kind) {
    case RD_PULSE_ONE_SINE:
    case RD_PULSE_ONE_COSINE: return 1.0 / p->frequency;
    case RD_PULSE_HARMONIC: return p->cycles / p->frequency;
    case RD_PULSE_RECTANGULAR:
    case RD_PULSE_TRIANGLE: return p->duration;
    case RD_PULSE_NONE: break;
    }
    return 0.0;
}

/* a sin(w tau): v = a/w (1 - cos w tau), d = a/w (tau - sin(w tau)/w). */
static void eval_sine(double amp, double w, double tau, double *a, double *v, double *d)
{
    double sn = sin(w * tau); /* once: libm's sin may set errno, so gcc calls it at each use */
    *a = amp * sn;
    *v = amp / w * (1.0 - cos(w * tau));
    *d = amp / w * (tau - sn / w);
}

/* a cos(w tau): v = a/w sin(w tau), d = a/w^2 (1 - cos w tau). */
static void eval_cosine(double amp, double w, double tau, double *a, double *v, double *d)
{
    double cs = cos(w * tau); /* once, as eval_sine's sin */
    *a = amp * cs;
    *v = amp / w * sin(w * tau);
    *d = amp / (w * w) * (1.0 - cs);
}

/* Triangle of height amp and base T: a = 2 amp tau/T up to T/2, then 2 amp (T - tau)/T.
 * Rising half: v = amp tau^2/T, d = amp tau^3/(3T). Falling half (u = T - tau):
 * v = amp T/2 - amp u^2/T, d = amp T^2/24 + amp T/2 (tau - T/2) + amp (u^3 - T^3/8)/(3T). */
static void eval_triangle(double amp, double T, double tau, double *a, double *v, double *d)
{
    if (tau <= 0.5 * T) {
        *a = 2.0 * amp * tau / T;
        *v = amp * tau * tau / T;
        *d = amp * tau * tau * tau / (3.0 * T);
        return;
    }
    double u = T - tau;
    *a = 2.0 * amp * u / T;
    *v = 0.5 * amp * T - amp * u * u / T;
    *d = amp * T * T / 24.0 + 0.5 * amp * T * (tau - 0.5 * T) +
         amp * (u * u * u - T * T * T / 8.0) / (3.0 * T);
}

/* The pulse at 0 <= tau <= its length. */
static void eval_inside(const rd_pulse_def *p, double tau, double *a, double *v, double *d)
{
    double w = 2.0 * M_PI * p->frequency; /* rad/s */
    switch (p->kind) {
    case RD_PULSE_ONE_SINE:
    case RD_PULSE_HARMONIC: eval_sine(p->amplitude, w, tau, a, v, d); return;
    case RD_PULSE_ONE_COSINE: eval_cosine(p->amplitude, w, tau, a, v, d); return;
    case RD_PULSE_RECTANGULAR:
        *a = p->amplitude;
        *v = p->amplitude * tau;
        *d = 0.5 * p->amplitude * tau * tau;
        return;
    case RD_PULSE_TRIANGLE: eval_triangle(p->amplitude, p->duration, tau, a, v, d); return;
    case RD_PULSE_NONE: break;
    }
    *a = *v = *d = 0.0;
}

void rd_pulse_eval(const rd_pulse_def *p, double t, double *a, double *v, double *d)
{
    double tau = t - p->start;
    double len = pulse_length(p);
    *a = *v = *d = 0.0;
    if (p->kind == RD_PULSE_NONE || tau <= 0.0) return;
    if (tau < len) {
        eval_inside(p, tau, a, v, d);
        return;
    }
    /* After the end: coast with the end velocity. */
    double a_end;
    eval_inside(p, len, &a_end, v, d);
    *d += *v * (tau - len);
}

double rd_pulse_end(const rd_pulse_def *p)
{
    if (p->kind == RD_PULSE_NONE) return 0.0;
    return p->start + pulse_length(p);
}

void rd_motion_axes_of(const rd_motion_def *m, rd_motion_axes *ax)
{
    ax->pulse[0] = cos(m->horizontal.direction);
    ax->pulse[1] = sin(m->horizontal.direction);
    ax->record[0] = cos(m->direction);
    ax->record[1] = sin(m->direction);
}

/* Adds the applied records at t: h1 along (cos, sin) of m->direction (ax->record), h2 along
 * (-sin, cos), vertical along z. Absent components cost nothing. */
static void add_records(const rd_motion_def *m, const rd_motion_axes *ax, double t, double acc[3],
                        double vel[3], double disp[3])
{
    if (!m->record[RD_H1].applied && !m->record[RD_H2].applied && !m->record[RD_VERTICAL].applied)
        return;
    double c = ax->record[0], s = ax->record[1];
    const double axis[RD_NCOMPONENTS][3] = { { c, s, 0 }, { -s, c, 0 }, { 0, 0, 1 } };
    for (int k = 0; k < RD_NCOMPONENTS; k++) {
        const rd_record *r = m->record[k].applied;
        double a, v, d;
        if (!r) continue;
        rd_record_eval(r, t, &a, &v, &d);
        for (int j = 0; j < 3; j++) {
            acc[j] += a * axis[k][j];
            vel[j] += v * axis[k][j];
            disp[j] += d * axis[k][j];
        }
    }
}

void rd_motion_eval_axes(const rd_motion_def *m, const rd_motion_axes *ax, double t, double acc[3],
                         double vel[3], double disp[3])
{
    double ah, vh, dh, az, vz, dz;
    rd_pulse_eval(&m->horizontal, t, &ah, &vh, &dh);
    rd_pulse_eval(&m->vertical, t, &az, &vz, &dz);
    double c = ax->pulse[0], s = ax->pulse[1];
    acc[0] = ah * c, acc[1] = ah * s, acc[2] = az;
    vel[0] = vh * c, vel[1] = vh * s, vel[2] = vz;
    disp[0] = dh * c, disp[1] = dh * s, disp[2] = dz;
    add_records(m, ax, t, acc, vel, disp);
}

void rd_motion_eval(const rd_motion_def *m, double t, double acc[3], double vel[3], double disp[3])
{
    rd_motion_axes ax;
    rd_motion_axes_of(m, &ax);
    rd_motion_eval_axes(m, &ax, t, acc, vel, disp);
}

double rd_motion_end(const rd_motion_def *m)
{
    double end = fmax(rd_pulse_end(&m->horizontal), rd_pulse_end(&m->vertical));
    for (int k = 0; k < RD_NCOMPONENTS; k++)
        if (m->record[k].applied) end = fmax(end, rd_record_duration(m->record[k].applied));
    return end;
}
