/* rockdem — the surface model's part of the state image (engine/state.h): what `model save`
 * must keep of `contact model surface` for `model restore` to continue the run bit for bit.
 *
 * The patches met so far (their keys, shear and twisting springs, the energy figures and the
 * step that last loaded each, as raw records whose size the header carries) with their hash map
 * as it is, the patches loaded at the last step (their springs let go when they open), the mesh
 * pairs' face pairs that bore and when, each pair's joint measures, the surface step count, the
 * plane the last front test used, and the dashpot's last forces per body (the trapezoid of its
 * work spans the step: dashpot.c). The bodies' planes, cells and trees are rebuilt from the
 * shapes at setup, and the scratch holds nothing from one step to the next.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * contact/, geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/state.h"
#include "engine/surface.h"

#include <stdio.h>
#include <stdlib.h>

void rd_surface_state_capture(const rd_sim *s, long h[RD_STATE_HEADER])
{
    for (int k = RD_STATE_H_MODEL; k < RD_STATE_HEADER; k++) h[k] = 0;
    const struct rd_surface *S = s->surf;
    if (!S) return;
    h[RD_STATE_H_MODEL] = 1;
    h[RD_STATE_H_NPATCH] = S->nst;
    h[RD_STATE_H_PATCH_HCAP] = S->hcap;
    h[RD_STATE_H_NON] = S->non;
    h[RD_STATE_H_FCAP] = S->fcap;
    h[RD_STATE_H_NFK] = S->nfk;
    h[RD_STATE_H_NMEAS] = S->cap_meas;
    h[RD_STATE_H_SURF_STAMP] = S->stamp;
    h[RD_STATE_H_FRONT] = S->front;
    h[RD_STATE_H_PATCH_SIZE] = (long)sizeof(surf_state);
    /* the dashpot's arrays exist once a dashpot acted: before that its last forces are 0 */
    h[RD_STATE_H_DP_N] = S->dp.cap_x >= s->nb ? s->nb : 0;
    h[RD_STATE_H_DP_ACTED] = S->dp.acted;
}

int rd_surface_state_arrays(rd_sim *s, rd_state_array *a, int n)
{
    struct rd_surface *S = s->surf;
    if (!S) return n;
    a[n++] = (rd_state_array){ "surface/patches", RD_STATE_BYTE, S->st,
                               (long)((size_t)S->nst * sizeof *S->st) };
    a[n++] = (rd_state_array){ "surface/patch_hash", RD_STATE_INT, S->hash, S->hcap };
    a[n++] = (rd_state_array){ "surface/loaded", RD_STATE_INT, S->on, S->non };
    a[n++] = (rd_state_array){ "surface/face_pairs", RD_STATE_BYTE, S->fkey,
                               (long)((size_t)S->fcap * sizeof *S->fkey) };
    a[n++] = (rd_state_array){ "surface/face_pair_steps", RD_STATE_BYTE, S->fstamp,
                               (long)((size_t)S->fcap * sizeof *S->fstamp) };
    a[n++] = (rd_state_array){ "surface/measures", RD_STATE_BYTE, S->meas,
                               (long)((size_t)S->cap_meas * sizeof *S->meas) };
    const long ndp = S->dp.cap_x >= s->nb ? s->nb : 0;
    a[n++] = (rd_state_array){ "surface/dashpot_last", RD_STATE_DOUBLE, S->dp.fd_prev, 6 * ndp };
    return n;
}

const char *rd_surface_state_mismatch(const rd_sim *s, const long h[RD_STATE_HEADER], char *buf,
                                      size_t n)
{
    const long here = s->surf != NULL;
    if (h[RD_STATE_H_MODEL] != here) {
        snprintf(buf, n, "saved under contact model %s, this scenario uses contact model %s",
                 h[RD_STATE_H_MODEL] ? "surface" : "vertex", here ? "surface" : "vertex");
        return buf;
    }
    if (here && h[RD_STATE_H_PATCH_SIZE] != (long)sizeof(surf_state))
        return "written by another rockdem build (checkpoint layout differs)";
    return NULL;
}

/* *p resized to n elements of size sz (at least one byte); 0 or -1. */
static int resize(void **p, long n, size_t sz)
{
    void *t = realloc(*p, n > 0 ? (size_t)n * sz : 1);
    if (!t) return -1;
    *p = t;
    return 0;
}

int rd_surface_state_reserve(rd_sim *s, const long h[RD_STATE_HEADER])
{
    struct rd_surface *S = s->surf;
    if (!S) return 0;
    const long nst = h[RD_STATE_H_NPATCH], hcap = h[RD_STATE_H_PATCH_HCAP];
    const long non = h[RD_STATE_H_NON], fcap = h[RD_STATE_H_FCAP];
    const long nmeas = h[RD_STATE_H_NMEAS];
    if (resize((void **)&S->st, nst, sizeof *S->st) ||
        resize((void **)&S->hash, hcap, sizeof *S->hash) ||
        resize((void **)&S->on, non, sizeof *S->on) ||
        resize((void **)&S->on_next, non, sizeof *S->on_next) ||
        resize((void **)&S->fkey, fcap, sizeof *S->fkey) ||
        resize((void **)&S->fstamp, fcap, sizeof *S->fstamp) ||
        resize((void **)&S->meas, nmeas, sizeof *S->meas))
        return -1;
    if (h[RD_STATE_H_DP_N] > 0 && rd_dashpots_reserve(s, &S->dp)) return -1;
    S->nst = S->cap_st = (int)nst;
    S->hcap = (int)hcap;
    S->non = S->cap_on = S->cap_on_next = (int)non;
    S->fcap = (int)fcap;
    S->nfk = (int)h[RD_STATE_H_NFK];
    S->cap_meas = (int)nmeas;
    S->stamp = h[RD_STATE_H_SURF_STAMP];
    S->front = (int)h[RD_STATE_H_FRONT];
    S->dp.acted = (int)h[RD_STATE_H_DP_ACTED];
    return 0;
}
