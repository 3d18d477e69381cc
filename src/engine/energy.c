/* rockdem — energy bookkeeping, evaluated at integer steps t(n) during shaking.
 *
 * Velocities live at half steps. The kinetic energy at t(n) is the scheme's own:
 *   kinetic       sum 1/2 m v(n-1/2).v(n+1/2) + 1/2 L(n-1/2).w(n+1/2)   (ground frame,
 *                 w(n+1/2) = R(n) I^-1 R(n)^T L(n+1/2)). Central differences conserve this
 *                 form plus the potential exactly when the forces are linear (a joint whose
 *                 springs all stay closed; free fall). It is 1/2 m v(n).v(n) - |F(n) dt|^2 / 8m,
 *                 v(n) the mean of the half-step velocities: the mean's form put that term into
 *                 the residual, an oscillation of (omega dt)^2 / 4 of every joint vibration
 *                 (2e-5 J of the YADE stack's 7e-2 J as it settles onto its joints at 5e-5 s,
 *                 where this form closes to 1e-12 J). It can dip below 0, by at most that term,
 *                 when a velocity turns within a step.
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
 * every output sample, is the health figure reported in the summary. The kinetic and
 * gravitational terms are looked at every step for the largest (a few multiply-adds per body),
 * the others at the samples, so the scale does not hang on the output interval (the YADE stack
 * swings 7e-2 J between gravity and its joints every 2.4 ms; samples every 5 ms saw 3e-3 J).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "base/vec.h"

#include <math.h>

/* Work of the pseudo-force -m a_g over [t(n-1), t(n)] with mid-interval force and velocity,
 * and the energy scale's kinetic and gravitational part (the kinetic energy at t(n-1/2));
 * called every step (about 20 flops per body). */
void rd_energy_step(rd_sim *s)
{
    if (s->step == 0) return;
    double ke = 0, pe = 0;
    for (int k = 0; k < s->nfree; k++) {
        int i = s->free_body[k];
        for (int j = 0; j < 3; j++)
            s->e_work -= s->mass[i] * 0.5 * (s->ag[j] + s->ag_prev[j]) * s->v_old[i][j] * s->dt;
        ke += 0.5 * (s->mass[i] * rd_dot(s->v_old[i], s->v_old[i]) + rd_dot(s->w[i], s->L_old[i]));
        pe += s->mass[i] * s->sc.gravity * (s->x[i][2] - s->watch[k].x_ref[2]);
    }
    s->e_scale = fmax(s->e_scale, fmax(ke, fabs(pe)));
}

/* All energies at t(n) and the balance residual, with the positions `back` steps ahead of t(n)
 * (0 inside a step, before its drift; 1 at the end of the run, after the last drift). */
static void sample(rd_sim *s, double back, int account)
{
    double ke = 0, pe = 0;
    for (int k = 0; k < s->nfree; k++) {
        int i = s->free_body[k];
        double lb[3], w[3];
        rd_mat_tvec(s->R[i], s->L[i], lb);
        for (int j = 0; j < 3; j++) lb[j] /= s->inertia[i][j];
        rd_mat_vec(s->R[i], lb, w);
        ke += 0.5 * (s->mass[i] * rd_dot(s->v_old[i], s->v[i]) + rd_dot(s->L_old[i], w));
        double z = s->x[i][2] - back * s->dt * s->v[i][2]; /* the drift moved x by v(n+1/2) dt */
        pe += s->mass[i] * s->sc.gravity * (z - s->watch[k].x_ref[2]);
    }
    double *e = s->energy, el = rd_contact_elastic_energy(s);
    e[0] = ke;
    e[1] = pe;
    e[2] = el;
    e[3] = s->e_fric;
    e[4] = s->e_damp;
    e[5] = s->e_work;
    double total = ke + pe + el;
    if (s->step == 0) s->e0 = total + s->e_fric + s->e_damp - s->e_work;
    e[6] = total + s->e_fric + s->e_damp - s->e_work - s->e0;
    if (!account) return;
    for (int j = 0; j < 6; j++) s->e_scale = fmax(s->e_scale, fabs(e[j]));
    s->e_scale = fmax(s->e_scale, fabs(s->e0));
    if (s->e_scale > 0) s->resid_max = fmax(s->resid_max, fabs(e[6]) / s->e_scale);
    if (!s->untrusted && s->resid_max > RD_ENERGY_TRUST) {
        s->untrusted = 1;
        s->t_untrusted = s->t;
    }
}

/* A sample inside a step (output samples, histories): positions and velocities at t(n). */
void rd_energy_sample(rd_sim *s) { sample(s, 0, 1); }

/* The same energies for a history row, leaving the run's energy scale and largest residual
 * alone: they follow the output samples only, so asking for a history changes no result (the
 * energy at t = 0, e0, is the same whichever sample sets it). */
void rd_energy_peek(rd_sim *s) { sample(s, 0, 0); }

/* The sample at the end of the run, after the last step's drift: the energies of the step's
 * t(n) (its contact forces, its kick's mean velocity), with the height taken back to t(n); the
 * height at t(n+1) against the velocity at t(n) left m g vz dt in the balance of a body still
 * falling when the run ended (15 J in free fall at a 1e-4 s step). */
void rd_energy_sample_end(rd_sim *s) { sample(s, 1, 1); }
