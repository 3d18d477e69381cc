/* rockdem (private) — the surface model's normal dashpot, integrated implicitly (dashpot.c;
 * docs/CONTACT.md section 8.6).
 *
 * A patch's dashpot is a pressure c dd/dt over its compressed region, and dd/dt is affine in the
 * point p (ground frame, from the integration body's centre) and linear in the two bodies'
 * velocities: dd/dt = -(g0 + p_x g1 + p_y g2 + p_z g3) . xi, xi = (v_a, w_a, v_b, w_b), for the
 * rate along one direction u. Its generalized force is then -D xi with the damping matrix D = c
 * B M B^T (B = [g0 .. g3], 12 x 4; M the region's area moments in the basis 1, p_x, p_y, p_z):
 * symmetric and positive semi-definite, from the same moments as the spring's force. The
 * patches of one pair along one u share B, so their regions are one dashpot: the moments of
 * their union are the sums of theirs (on a scanned rock, some hundred patches a pair, one u).
 * Folder engine/ owns the simulation; it may call base/, contact/, geometry/, records/ and
 * scenario/, never io/ or cli/.
 */
#ifndef RD_DASHPOT_H
#define RD_DASHPOT_H

#include "engine/sim.h"

/* The functions of p in the basis of a dashpot's rate: 1, p_x, p_y, p_z. */
#define RD_DASHPOT_BASIS   4
/* The distinct entries of the symmetric 4 x 4 moment matrix. */
#define RD_DASHPOT_MOMENTS 10

/* The dashpot of one pair's regions along one direction: bodies a (the integration body, -1
 * when fixed) and b (the reference body, -1 when fixed), c (Pa s/m), the rate's direction u
 * (unit, ground frame), the regions' moments m (packed upper triangle of the integral of phi
 * phi^T over them, phi = (1, p_x, p_y, p_z), p from the integration body's centre, ground
 * frame; m^2 .. m^4) and the normal-rate basis g[body][k] (per body the six components of the
 * generalized velocity: linear, then angular), so that u . v_rel(p) = sum over the two bodies
 * of sum_k phi_k(p) g[.][k] . xi. */
typedef struct rd_dashpot {
    int a, b;
    double c;
    double u[3];
    double m[RD_DASHPOT_MOMENTS];
    double g[2][RD_DASHPOT_BASIS][6];
} rd_dashpot;

/* The dashpots of one step and the solve's scratch. */
typedef struct rd_dashpots {
    rd_dashpot *e;
    int n, cap;
    int *first, *list, cap_b, cap_l; /* per body, its dashpots (CSR: first[nb + 1], list) */
    double (*xi)[6], (*rhs)[6], (*chol)[21];
    double (*fd)[6];      /* per body, the dashpots' force (N) and torque (N m) at this step,
                             ground frame */
    double (*fd_prev)[6]; /* per body, last step's force (N) and its torque times that step's
                             inverse inertia (1/s^2), for the work's second half */
    int cap_x;
    int acted; /* some dashpot acted at the last step (its force's work is still due) */
} rd_dashpots;

/* The dashpot along u with ratio c of integration body i against reference body r (either
 * may be fixed; points are taken from i's centre), among those made since entry first (the
 * pair's first): the one that matches, else a new one with no region. NULL when out of memory. */
rd_dashpot *rd_dashpot_of(const rd_sim *s, rd_dashpots *d, int first, int i, int r, double c,
                          const double u[3]);

/* Add to e's regions a plane region of moments m2 = (a, sx, sy, sxx, sxy, syy) about origin O
 * (from body i's centre) along axes E1, E2 (ground frame): p = O + x E1 + y E2. */
void rd_dashpot_add_region(rd_dashpot *e, const double m2[6], const double O[3], const double E1[3],
                           const double E2[3]);

/* The mean velocities over the step of the bodies the dashpots of this step join, from the
 * implicit midpoint rule (M + dt D / 2) xi = M xi(n-1/2) + dt F / 2, F the forces and torques
 * found so far (s->f, s->tq), M the mass and ground-frame inertia at t(n): the dashpots' forces
 * -D xi are added to s->f and s->tq, so that the kick that follows is that implicit step, and
 * their work to s->e_damp (the mean of this step's and the last step's forces on the velocity
 * at n - 1/2, as the kinetic energy of energy.c counts it). Exact in one solve for a body on fixed ones; a stack is solved
 * by block Gauss-Seidel sweeps (a symmetric positive definite system: they converge). Clears
 * the list. Returns 0, -1 when out of memory. */
int rd_dashpot_solve(rd_sim *s, rd_dashpots *d);

/* Room for the per-body arrays of every body (last step's forces zeroed where new). 0 or -1. */
int rd_dashpots_reserve(const rd_sim *s, rd_dashpots *d);

void rd_dashpots_free(rd_dashpots *d);

#endif
