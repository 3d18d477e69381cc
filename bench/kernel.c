/* rockdem bench — the reference point kernel (issue 13, item 4): the least work a point-contact
 * DEM step can do, written twice in plain C, to measure rockdem's contact against.
 *
 * One rigid 0.5 x 0.5 x 1.0 m granite block stands on the plane z = 0 on N subcontact points
 * (a grid over its base, each carrying an equal share of the base area) under a 2 Hz harmonic
 * ground acceleration. Each step, for every point: its world offset r = R q from the centre of
 * mass, its gap z, a compression-only normal spring fn = KN A max(-z, 0), an incremental shear
 * spring us += v_t dt with the Coulomb cap |fs| <= tan(phi) fn (slip: the spring is cut back to
 * the cap), and the force and torque r x f summed over the points. Then the body moves
 * (semi-implicit Euler, the rotation as a unit quaternion). No broad phase, no energy, no output.
 *
 *   scalar: array of structs, a branch per point (no contact: reset and skip; slip or stick).
 *   soa:    structure of arrays padded to a multiple of RD_LANES points: a branch-free map
 *           (contact and slip as 0/1 factors and selects, restrict arrays, per-point force and
 *           torque out), then the sums in RD_LANES partial sums. GCC 12 vectorises the map at
 *           -O3 -march=native -fno-math-errno (sqrt without errno); at rockdem's default
 *           -O2 -march=x86-64-v2 it does not (no if-conversion, sqrt may set errno), so the
 *           Makefile builds this file both ways (build/bench/kernel, build/bench/kernel-native).
 *
 * Each run restarts the block every EPISODE steps (a 2 s window, as bench/block.dat), so long
 * timing runs stay on the same physics.
 *
 *   kernel N STEPS      runs both variants on N points for STEPS steps of 5e-5 s, prints
 *                       "kernel: variant=scalar n=N steps=S ns_per_point_step=X" per variant and
 *                       fails (exit 1) if the two final states differ by more than round-off.
 *
 * Units: SI (m, s, kg, N, Pa/m).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define RD_LANES     8   /* points per SoA block (the inner loop width) */
#define BLOCK_X      0.5 /* block size, m */
#define BLOCK_Y      0.5
#define BLOCK_Z      1.0
#define DENSITY      2700.0 /* kg/m^3 */
#define KN           1e10   /* normal stiffness, Pa/m (bench/block.dat) */
#define KS           1e9    /* shear stiffness, Pa/m */
#define FRICTION_DEG 40.0
#define GRAVITY      9.81 /* m/s^2 */
#define DT           5e-5 /* s (bench/block.dat) */
#define GROUND_AMP                                                                                 \
    (0.3 * GRAVITY)        /* m/s^2: below sliding (tan 40 g) and rigid uplift (b/h g = 0.5 g) */
#define GROUND_FREQ 2.0    /* Hz */
#define EPISODE     40000L /* steps (2 s, bench/block.dat's window): then the block starts over */
/* two variants agree to this (m): both sum the same forces in another order, a relative
   round-off of ~1e-16 per step; over 1e6 steps of a stable oscillation this stays far below a nm */
#define AGREE_TOL   1e-9

typedef struct body {
    double x[3], v[3];  /* centre of mass position (m), velocity (m/s) */
    double q[4];        /* orientation quaternion (w, x, y, z) */
    double L[3];        /* angular momentum, world frame (kg m^2/s) */
    double R[9];        /* rotation matrix from q, row major */
    double w[3];        /* angular velocity, world frame (rad/s) */
    double mass, ib[3]; /* kg; principal moments, kg m^2 */
} body;

typedef struct point { /* scalar variant: array of structs */
    double q[3];       /* body-frame offset from the centre of mass, m */
    double us[2];      /* shear displacement, m */
    double area;       /* m^2 */
} point;

typedef struct soa { /* vectorised variant: one array per coordinate, padded */
    int n, npad;
    double *qx, *qy, *qz, *usx, *usy, *kn, *ks; /* per point: offset (m), shear (m), K A (N/m) */
    double *out[6]; /* per point: force (N), then torque (N m), world frame */
} soa;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void body_rotation(body *b)
{
    const double w = b->q[0], x = b->q[1], y = b->q[2], z = b->q[3];
    double *R = b->R;
    R[0] = 1 - 2 * (y * y + z * z);
    R[1] = 2 * (x * y - w * z);
    R[2] = 2 * (x * z + w * y);
    R[3] = 2 * (x * y + w * z);
    R[4] = 1 - 2 * (x * x + z * z);
    R[5] = 2 * (y * z - w * x);
    R[6] = 2 * (x * z - w * y);
    R[7] = 2 * (y * z + w * x);
    R[8] = 1 - 2 * (x * x + y * y);
    /* w = R Ib^-1 R^T L */
    double lb[3];
    for (int i = 0; i < 3; i++)
        lb[i] = (R[i] * b->L[0] + R[3 + i] * b->L[1] + R[6 + i] * b->L[2]) / b->ib[i];
    for (int i = 0; i < 3; i++)
        b->w[i] = R[3 * i] * lb[0] + R[3 * i + 1] * lb[1] + R[3 * i + 2] * lb[2];
}

/* The block at rest on its springs, tilted by a hair so the rotation is not trivial. */
static void body_init(body *b)
{
    memset(b, 0, sizeof *b);
    b->mass = DENSITY * BLOCK_X * BLOCK_Y * BLOCK_Z;
    b->ib[0] = b->mass * (BLOCK_Y * BLOCK_Y + BLOCK_Z * BLOCK_Z) / 12;
    b->ib[1] = b->mass * (BLOCK_X * BLOCK_X + BLOCK_Z * BLOCK_Z) / 12;
    b->ib[2] = b->mass * (BLOCK_X * BLOCK_X + BLOCK_Y * BLOCK_Y) / 12;
    double sink = b->mass * GRAVITY / (KN * BLOCK_X * BLOCK_Y); /* static spring compression, m */
    b->x[2] = 0.5 * BLOCK_Z - sink;
    double tilt = 1e-5; /* rad, about y */
    b->q[0] = cos(0.5 * tilt);
    b->q[2] = sin(0.5 * tilt);
    body_rotation(b);
}

/* Advance the body one step under the contact force f and torque t (world frame). */
static void body_step(body *b, const double f[3], const double t[3], long step)
{
    double ag = GROUND_AMP * sin(2 * M_PI * GROUND_FREQ * (double)step * DT);
    double acc[3] = { f[0] / b->mass - ag, f[1] / b->mass, f[2] / b->mass - GRAVITY };
    for (int i = 0; i < 3; i++) {
        b->v[i] += acc[i] * DT;
        b->x[i] += b->v[i] * DT;
        b->L[i] += t[i] * DT;
    }
    body_rotation(b); /* w from the new L */
    const double *w = b->w, *q = b->q;
    double dq[4] = { -w[0] * q[1] - w[1] * q[2] - w[2] * q[3],
                     w[0] * q[0] + w[1] * q[3] - w[2] * q[2],
                     w[1] * q[0] + w[2] * q[1] - w[0] * q[3],
                     w[2] * q[0] + w[0] * q[2] - w[1] * q[1] };
    double norm = 0;
    for (int i = 0; i < 4; i++) {
        b->q[i] += 0.5 * DT * dq[i];
        norm += b->q[i] * b->q[i];
    }
    norm = 1 / sqrt(norm);
    for (int i = 0; i < 4; i++) b->q[i] *= norm;
    body_rotation(b);
}

/* Body-frame offset of point k of a side x side grid spanning the base, edges included (side 2:
   the four corners, as rockdem's vertex subcontacts; side 1: the base's centre). */
static void grid_point(int k, int side, double q[3])
{
    int i = k % side, j = k / side;
    double step = side > 1 ? 1.0 / (side - 1) : 0, off = side > 1 ? 0.5 : 0;
    q[0] = BLOCK_X * (i * step - off);
    q[1] = BLOCK_Y * (j * step - off);
    q[2] = -0.5 * BLOCK_Z;
}

/* ---- scalar: array of structs with branches ----------------------------------------------- */
static void scalar_forces(const body *b, point *p, int n, double f[3], double t[3])
{
    const double mu = tan(FRICTION_DEG * M_PI / 180);
    const double *R = b->R, *v = b->v, *w = b->w;
    f[0] = f[1] = f[2] = t[0] = t[1] = t[2] = 0;
    for (int k = 0; k < n; k++) {
        point *pk = &p[k];
        double r[3];
        for (int i = 0; i < 3; i++)
            r[i] = R[3 * i] * pk->q[0] + R[3 * i + 1] * pk->q[1] + R[3 * i + 2] * pk->q[2];
        double gap = b->x[2] + r[2];
        if (gap >= 0) {
            pk->us[0] = pk->us[1] = 0;
            continue;
        }
        double vx = v[0] + w[1] * r[2] - w[2] * r[1], vy = v[1] + w[2] * r[0] - w[0] * r[2];
        pk->us[0] += vx * DT;
        pk->us[1] += vy * DT;
        double fn = -KN * pk->area * gap;
        double fs[2] = { -KS * pk->area * pk->us[0], -KS * pk->area * pk->us[1] };
        double mag = sqrt(fs[0] * fs[0] + fs[1] * fs[1]), cap = mu * fn;
        if (mag > cap) { /* slip: the spring cut back to the Coulomb cap */
            double s = cap / mag;
            fs[0] *= s;
            fs[1] *= s;
            pk->us[0] *= s;
            pk->us[1] *= s;
        }
        double fk[3] = { fs[0], fs[1], fn };
        for (int i = 0; i < 3; i++) f[i] += fk[i];
        t[0] += r[1] * fk[2] - r[2] * fk[1];
        t[1] += r[2] * fk[0] - r[0] * fk[2];
        t[2] += r[0] * fk[1] - r[1] * fk[0];
    }
}

/* ---- soa: a branch-free map over the points, then a reduction in RD_LANES partial sums ----- */
typedef struct frame { /* the body's state the point map reads, by value (no aliasing) */
    double R[9], z, vx, vy, wx, wy, wz, mu;
} frame;

/* Per point k: new shear (ux, uy), force (ox, oy, oz) and torque (mx, my, mz) about the centre. */
static void soa_map(frame fr, int n, const double *restrict px, const double *restrict py,
                    const double *restrict pz, const double *restrict kn, const double *restrict ks,
                    double *restrict ux, double *restrict uy, double *restrict ox,
                    double *restrict oy, double *restrict oz, double *restrict mx,
                    double *restrict my, double *restrict mz)
{
    const double tiny = 1e-300; /* N: keeps 0 / 0 (no contact) at 0 */
    const double *R = fr.R;
    for (int k = 0; k < n; k++) {
        double rx = R[0] * px[k] + R[1] * py[k] + R[2] * pz[k],
               ry = R[3] * px[k] + R[4] * py[k] + R[5] * pz[k],
               rz = R[6] * px[k] + R[7] * py[k] + R[8] * pz[k];
        double gap = fr.z + rz;
        double on = gap < 0 ? 1.0 : 0.0;
        double vx = fr.vx + fr.wy * rz - fr.wz * ry, vy = fr.vy + fr.wz * rx - fr.wx * rz;
        double usx = on * (ux[k] + vx * DT), usy = on * (uy[k] + vy * DT);
        double fn = on * -kn[k] * gap;
        double fsx = -ks[k] * usx, fsy = -ks[k] * usy;
        double mag = sqrt(fsx * fsx + fsy * fsy) + tiny;
        double ratio = fr.mu * fn / mag,
               sc = ratio < 1.0 ? ratio : 1.0; /* slip: cut back to the cap */
        fsx *= sc;
        fsy *= sc;
        ux[k] = usx * sc;
        uy[k] = usy * sc;
        ox[k] = fsx;
        oy[k] = fsy;
        oz[k] = fn;
        mx[k] = ry * fn - rz * fsy;
        my[k] = rz * fsx - rx * fn;
        mz[k] = rx * fsy - ry * fsx;
    }
}

/* Sum of o[0..n) (n a multiple of RD_LANES) in RD_LANES partial sums. */
static double lane_sum(int n, const double *restrict o)
{
    double lane[RD_LANES] = { 0 }, sum = 0;
    for (int k0 = 0; k0 < n; k0 += RD_LANES)
        for (int l = 0; l < RD_LANES; l++) lane[l] += o[k0 + l];
    for (int l = 0; l < RD_LANES; l++) sum += lane[l];
    return sum;
}

static void soa_forces(const body *b, soa *s, double f[3], double t[3])
{
    frame fr = { .z = b->x[2],
                 .vx = b->v[0],
                 .vy = b->v[1],
                 .wx = b->w[0],
                 .wy = b->w[1],
                 .wz = b->w[2],
                 .mu = tan(FRICTION_DEG * M_PI / 180) };
    memcpy(fr.R, b->R, sizeof fr.R);
    soa_map(fr, s->npad, s->qx, s->qy, s->qz, s->kn, s->ks, s->usx, s->usy, s->out[0], s->out[1],
            s->out[2], s->out[3], s->out[4], s->out[5]);
    for (int c = 0; c < 3; c++) {
        f[c] = lane_sum(s->npad, s->out[c]);
        t[c] = lane_sum(s->npad, s->out[3 + c]);
    }
}

static void *xcalloc(size_t n, size_t size)
{
    void *p = calloc(n, size);
    if (!p) {
        fprintf(stderr, "kernel: out of memory\n");
        exit(2);
    }
    return p;
}

/* Runs the scalar variant; returns ns per point-step, final body in *b. */
static double run_scalar(int n, int side, long steps, body *b)
{
    point *p = xcalloc((size_t)n, sizeof *p);
    for (int k = 0; k < n; k++) {
        grid_point(k, side, p[k].q);
        p[k].area = BLOCK_X * BLOCK_Y / n;
    }
    double f[3], t[3], t0 = now();
    for (long s = 0; s < steps; s++) {
        if (s % EPISODE == 0) {
            body_init(b);
            for (int k = 0; k < n; k++) p[k].us[0] = p[k].us[1] = 0;
        }
        scalar_forces(b, p, n, f, t);
        body_step(b, f, t, s % EPISODE);
    }
    double ns = 1e9 * (now() - t0) / ((double)steps * n);
    free(p);
    return ns;
}

/* Runs the SoA variant; padding points sit far above the plane (never in contact). */
static double run_soa(int n, int side, long steps, body *b)
{
    soa s = { .n = n, .npad = (n + RD_LANES - 1) / RD_LANES * RD_LANES };
    double **arr[] = { &s.qx,     &s.qy,     &s.qz,     &s.usx,    &s.usy,    &s.kn,    &s.ks,
                       &s.out[0], &s.out[1], &s.out[2], &s.out[3], &s.out[4], &s.out[5] };
    for (size_t i = 0; i < sizeof arr / sizeof *arr; i++)
        *arr[i] = xcalloc((size_t)s.npad, sizeof(double));
    for (int k = 0; k < s.npad; k++) {
        double q[3] = { 0, 0, BLOCK_Z }; /* padding: the top face's centre */
        if (k < n) grid_point(k, side, q);
        s.qx[k] = q[0];
        s.qy[k] = q[1];
        s.qz[k] = q[2];
        s.kn[k] = KN * BLOCK_X * BLOCK_Y / n;
        s.ks[k] = KS * BLOCK_X * BLOCK_Y / n;
    }
    double f[3], t[3], t0 = now();
    for (long st = 0; st < steps; st++) {
        if (st % EPISODE == 0) {
            body_init(b);
            memset(s.usx, 0, (size_t)s.npad * sizeof(double));
            memset(s.usy, 0, (size_t)s.npad * sizeof(double));
        }
        soa_forces(b, &s, f, t);
        body_step(b, f, t, st % EPISODE);
    }
    double ns = 1e9 * (now() - t0) / ((double)steps * n);
    for (size_t i = 0; i < sizeof arr / sizeof *arr; i++) free(*arr[i]);
    return ns;
}

/* An integer argument in min..max, or exit 2 with one line. */
static long arg_count(const char *what, const char *v, long min, long max)
{
    char *end;
    long x = strtol(v, &end, 10);
    if (*v == '\0' || *end != '\0' || x < min || x > max) {
        fprintf(stderr, "kernel: %s must be an integer %ld..%ld, got '%s'\n", what, min, max, v);
        exit(2);
    }
    return x;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(
            stderr,
            "usage: kernel N STEPS   (N >= 4 points on a square grid: rounded up to a square)\n");
        return 2;
    }
    int want = (int)arg_count("N", argv[1], 4, 1000000); /* 4: the block needs its corners */
    long steps = arg_count("STEPS", argv[2], 1, 1000000000L);
    int side = (int)ceil(sqrt((double)want) - 1e-9), n = side * side;
    body bs, bv;
    double ns_s = run_scalar(n, side, steps, &bs);
    double ns_v = run_soa(n, side, steps, &bv);
    double dx = 0;
    for (int i = 0; i < 3; i++) dx = fmax(dx, fabs(bs.x[i] - bv.x[i]));
    printf("kernel: variant=scalar n=%d steps=%ld ns_per_point_step=%.4g\n", n, steps, ns_s);
    printf("kernel: variant=soa n=%d steps=%ld ns_per_point_step=%.4g\n", n, steps, ns_v);
    printf("kernel: final z=%.9f m, variants differ by %.3g m\n", bs.x[2], dx);
    if (!(dx <= AGREE_TOL)) {
        fprintf(stderr, "kernel: the scalar and soa variants disagree by %.3g m (> %.0e m)\n", dx,
                AGREE_TOL);
        return 1;
    }
    return 0;
}
