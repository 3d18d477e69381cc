/* rockdem — energy bookkeeping, evaluated at integer steps t(n) during shaking.
 *
 * Velocities live at half steps, so v(n) = (v(n-1/2) + v(n+1/2)) / 2 (and L likewise).
 *   kinetic       sum 1/2 m v.v + 1/2 w.L                     (ground frame)
 *   gravitational sum m g (z - z_rest)
 *   elastic       sum over active subcontacts of Fel^2/(2 KN A) + |Fs|^2/(2 KS A), from the
 *                 stored spring state, at samples only (contact.c)
 *   friction      accumulated slip work Fs . dUs_plastic      (contact.c)
 *   damping       accumulated dashpot and local-damping work   (contact.c, sim.c)
 *   ground_work   accumulated work of the pseudo-force -m a_g, i.e. the energy the shaking
 *                 ground puts in
 *   residual      kinetic + gravitational + elastic + friction + damping - ground_work - E(0),
 *                 E(0) the same sum at the first sample (so the residual starts at 0): the first
 *                 step's contact bookings (a dashpot's work, a slip) are for the displacement
 *                 x(0) - x(-1) = v(-1/2) dt, before the run, as the ground work of that interval
 *                 (rd_energy_step skips it); leaving them out of E(0) kept them in every sample
 *                 (a block set moving into its dashpots: 12 J of 2.5 kJ, 4.9e-3)
 * The residual is the balance error of the scheme; |residual| / (largest term seen), taken at
 * every output sample, is the health figure reported in the summary.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "base/vec.h"

#include <math.h>

/* Work of the pseudo-force -m a_g over [t(n-1), t(n)] with mid-interval force and velocity;
 * called every step (3 multiply-adds per body). */
void rd_energy_step(rd_sim *s)
{
    if (s->step == 0) return;
    for (int k = 0; k < s->nfree; k++) {
        int i = s->free_body[k];
        for (int j = 0; j < 3; j++)
            s->e_work -= s->mass[i] * 0.5 * (s->ag[j] + s->ag_prev[j]) * s->v_old[i][j] * s->dt;
    }
}

/* All energies at t(n) and the balance residual, with the positions `back` steps ahead of t(n)
 * (0 inside a step, before its drift; 1 at the end of the run, after the last drift). */
static void sample(rd_sim *s, double back)
{
    double ke = 0, pe = 0;
    for (int k = 0; k < s->nfree; k++) {
        int i = s->free_body[k];
        double v[3], L[3], lb[3], w[3];
        for (int j = 0; j < 3; j++) {
            v[j] = 0.5 * (s->v[i][j] + s->v_old[i][j]);
            L[j] = 0.5 * (s->L[i][j] + s->L_old[i][j]);
        }
        rd_mat_tvec(s->R[i], L, lb);
        for (int j = 0; j < 3; j++) lb[j] /= s->inertia[i][j];
        rd_mat_vec(s->R[i], lb, w);
        ke += 0.5 * s->mass[i] * rd_dot(v, v) + 0.5 * rd_dot(w, L);
        double z = s->x[i][2] - back * s->dt * s->v[i][2]; /* the drift moved x by v(n+1/2) dt */
        pe += s->mass[i] * s->sc.gravity * (z - s->watch[k].x_ref[2]);
    }
    double *e = s->energy, el = rd_contact_elastic_energy(s);
    e[0] = ke; e[1] = pe; e[2] = el; e[3] = s->e_fric; e[4] = s->e_damp;
    e[5] = s->e_work;
    double total = ke + pe + el;
    if (s->step == 0) s->e0 = total + s->e_fric + s->e_damp - s->e_work;
    e[6] = total + s->e_fric + s->e_damp - s->e_work - s->e0;
    for (int j = 0; j < 6; j++) s->e_scale = fmax(s->e_scale, fabs(e[j]));
    s->e_scale = fmax(s->e_scale, fabs(s->e0));
    if (s->e_scale > 0) s->resid_max = fmax(s->resid_max, fabs(e[6]) / s->e_scale);
}

/* A sample inside a step (output samples, histories): positions and velocities at t(n). */
void rd_energy_sample(rd_sim *s) { sample(s, 0); }

/* The sample at the end of the run, after the last step's drift: the energies of the step's
 * t(n) (its contact forces, its kick's mean velocity), with the height taken back to t(n); the
 * height at t(n+1) against the velocity at t(n) left m g vz dt in the balance of a body still
 * falling when the run ended (15 J in free fall at a 1e-4 s step). */
void rd_energy_sample_end(rd_sim *s) { sample(s, 1); }
