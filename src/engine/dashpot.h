/* rockdem (private) — the surface model's normal dashpot, integrated implicitly (dashpot.c;
 * docs/CONTACT.md section 8.6).
 *
 * A patch's dashpot is a pressure c dd/dt over its compressed region, and dd/dt is affine in the
 * plane's coordinates (x, y) and linear in the two bodies' velocities: dd/dt = -(g0 + x g1 + y
 * g2) . xi, xi = (v_a, w_a, v_b, w_b). Its generalized force is then -D xi with the damping
 * matrix D = c B M B^T (B = [g0 g1 g2], 12 x 3; M the region's area moments in the basis 1, x,
 * y): symmetric and positive semi-definite, from the same moments as the spring's force.
 * Folder engine/ owns the simulation; it may call base/, contact/, geometry/, records/ and
 * scenario/, never io/ or cli/.
 */
#ifndef RD_DASHPOT_H
#define RD_DASHPOT_H

#include "engine/sim.h"

/* One patch's dashpot: bodies a (the integration body) and b (the reference body, -1 when
 * fixed), c (Pa s/m), the region's moments (a, sx, sy, sxx, sxy, syy; m^2 .. m^4) and the
 * normal-rate basis g[body][k] (k = 0, 1, 2 for 1, x, y; per body the six components of the
 * generalized velocity: linear, then angular), so that u . v_rel(x, y) = sum over the two
 * bodies of (g[.][0] + x g[.][1] + y g[.][2]) . xi. */
typedef struct rd_dashpot {
    int a, b;
    double c;
    double m[6];
    double g[2][3][6];
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

/* Room for one more dashpot (NULL when out of memory). */
rd_dashpot *rd_dashpot_new(rd_dashpots *d);

/* The mean velocities over the step of the bodies the dashpots of this step join, from the
 * implicit midpoint rule (M + dt D / 2) xi = M xi(n-1/2) + dt F / 2, F the forces and torques
 * found so far (s->f, s->tq), M the mass and ground-frame inertia at t(n): the dashpots' forces
 * -D xi are added to s->f and s->tq, so that the kick that follows is that implicit step, and
 * their work to s->e_damp (the mean of this step's and the last step's forces on the velocity
 * at n - 1/2, as the kinetic energy of energy.c counts it). Exact in one solve for a body on fixed ones; a stack is solved
 * by block Gauss-Seidel sweeps (a symmetric positive definite system: they converge). Clears
 * the list. Returns 0, -1 when out of memory. */
int rd_dashpot_solve(rd_sim *s, rd_dashpots *d);

void rd_dashpots_free(rd_dashpots *d);

#endif
