/* rockdem (private) — seeded perturbation of the subcontact points (perturb.c).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#ifndef RD_PERTURB_H
#define RD_PERTURB_H

#include "engine/sim.h"

/* Apply sc.contact.perturb to the points built by setup.c (a no-op when its seed is 0 or it
 * asks for nothing): remove, raise and scatter, then compact the point arrays. 0 or -1. */
int rd_perturb_points(rd_sim *s, rd_error *err);

#endif
