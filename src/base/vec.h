/* rockdem (private) — 3-vectors and unit quaternions as plain double arrays.
 * Quaternions are (w, x, y, z) and rotate body-frame vectors into the ground frame.
 * Folder base/ owns errors, vectors and named constants; it calls nothing else in rockdem.
 */
#ifndef RD_VEC_H
#define RD_VEC_H

#include <math.h>

static inline double rd_min(double a, double b) { return a < b ? a : b; }
static inline double rd_max(double a, double b) { return a > b ? a : b; }

static inline double rd_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void rd_cross(const double a[3], const double b[3], double out[3])
{
    double c0 = a[1] * b[2] - a[2] * b[1];
    double c1 = a[2] * b[0] - a[0] * b[2];
    double c2 = a[0] * b[1] - a[1] * b[0];
    out[0] = c0;
    out[1] = c1;
    out[2] = c2;
}

static inline double rd_norm(const double a[3]) { return sqrt(rd_dot(a, a)); }

static inline void rd_axpy(double s, const double x[3], double y[3])
{
    y[0] += s * x[0];
    y[1] += s * x[1];
    y[2] += s * x[2];
}

static inline void rd_copy3(const double a[3], double out[3])
{
    out[0] = a[0];
    out[1] = a[1];
    out[2] = a[2];
}

/* Rotation matrix (row-major 3x3) of a unit quaternion. */
static inline void rd_quat_to_mat(const double q[4], double m[9])
{
    double w = q[0], x = q[1], y = q[2], z = q[3];
    m[0] = 1 - 2 * (y * y + z * z);
    m[1] = 2 * (x * y - w * z);
    m[2] = 2 * (x * z + w * y);
    m[3] = 2 * (x * y + w * z);
    m[4] = 1 - 2 * (x * x + z * z);
    m[5] = 2 * (y * z - w * x);
    m[6] = 2 * (x * z - w * y);
    m[7] = 2 * (y * z + w * x);
    m[8] = 1 - 2 * (x * x + y * y);
}

static inline void rd_mat_vec(const double m[9], const double v[3], double out[3])
{
    double o0 = m[0] * v[0] + m[1] * v[1] + m[2] * v[2];
    double o1 = m[3] * v[0] + m[4] * v[1] + m[5] * v[2];
    double o2 = m[6] * v[0] + m[7] * v[1] + m[8] * v[2];
    out[0] = o0;
    out[1] = o1;
    out[2] = o2;
}

/* out = m^T v (ground -> body frame for a rotation matrix m). */
static inline void rd_mat_tvec(const double m[9], const double v[3], double out[3])
{
    double o0 = m[0] * v[0] + m[3] * v[1] + m[6] * v[2];
    double o1 = m[1] * v[0] + m[4] * v[1] + m[7] * v[2];
    double o2 = m[2] * v[0] + m[5] * v[1] + m[8] * v[2];
    out[0] = o0;
    out[1] = o1;
    out[2] = o2;
}

/* Hamilton product out = a * b. */
static inline void rd_quat_mul(const double a[4], const double b[4], double out[4])
{
    double w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    double x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    double y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    double z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
    out[0] = w;
    out[1] = x;
    out[2] = y;
    out[3] = z;
}

static inline void rd_quat_normalize(double q[4])
{
    double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    q[0] /= n;
    q[1] /= n;
    q[2] /= n;
    q[3] /= n;
}

/* Quaternion of a rotation by vector phi (axis * angle, rad), exact exponential map. Small
 * angles (every time step) use the Taylor series of cos(a/2) and sin(a/2)/a to a^6, whose
 * truncation error (< 1e-19 for a < 1e-2) is below round-off. */
static inline void rd_quat_from_rotvec(const double phi[3], double q[4])
{
    double a2 = rd_dot(phi, phi), c, s;
    if (a2 < 1e-4) {
        c = 1 - a2 / 8 * (1 - a2 / 48 * (1 - a2 / 120));
        s = 0.5 * (1 - a2 / 24 * (1 - a2 / 80 * (1 - a2 / 168)));
    } else {
        double a = sqrt(a2);
        c = cos(0.5 * a);
        s = sin(0.5 * a) / a;
    }
    q[0] = c;
    q[1] = s * phi[0];
    q[2] = s * phi[1];
    q[3] = s * phi[2];
}

/* Rotate v by unit quaternion q. */
static inline void rd_quat_rotate(const double q[4], const double v[3], double out[3])
{
    double m[9];
    rd_quat_to_mat(q, m);
    rd_mat_vec(m, v, out);
}

/* Unit quaternion of a proper rotation matrix (row-major), Shepperd's method. */
static inline void rd_quat_from_mat(const double m[9], double q[4])
{
    double tr = m[0] + m[4] + m[8];
    if (tr > 0) {
        double s = 2.0 * sqrt(1.0 + tr);
        q[0] = 0.25 * s;
        q[1] = (m[7] - m[5]) / s;
        q[2] = (m[2] - m[6]) / s;
        q[3] = (m[3] - m[1]) / s;
    } else if (m[0] > m[4] && m[0] > m[8]) {
        double s = 2.0 * sqrt(1.0 + m[0] - m[4] - m[8]);
        q[0] = (m[7] - m[5]) / s;
        q[1] = 0.25 * s;
        q[2] = (m[1] + m[3]) / s;
        q[3] = (m[2] + m[6]) / s;
    } else if (m[4] > m[8]) {
        double s = 2.0 * sqrt(1.0 + m[4] - m[0] - m[8]);
        q[0] = (m[2] - m[6]) / s;
        q[1] = (m[1] + m[3]) / s;
        q[2] = 0.25 * s;
        q[3] = (m[5] + m[7]) / s;
    } else {
        double s = 2.0 * sqrt(1.0 + m[8] - m[0] - m[4]);
        q[0] = (m[3] - m[1]) / s;
        q[1] = (m[2] + m[6]) / s;
        q[2] = (m[5] + m[7]) / s;
        q[3] = 0.25 * s;
    }
    rd_quat_normalize(q);
}

#endif
