/* rockdem — a body's faces grouped into planes, once at setup (contact/contact.h).
 * The grouping is first fit: face f joins the first plane (in the order they were opened) whose
 * opening face's normal m and offset d' satisfy n . m > 1 - ntol and |d - d'| <= dtol, or opens a
 * new one. Scanning every plane for every face is quadratic (a 500,000-triangle scanned rock
 * has nearly as many planes as faces); here each plane is filed in a hash under its cell of a
 * grid over (n, d), and a face looks only in the cells that its tolerance box meets. A plane
 * within tolerance lies in that box: |n_c - m_c| <= |n - m| = sqrt(2 (1 - n . m)) <
 * sqrt(2 ntol) for unit normals, |d - d'| <= dtol; the box's half-widths are these bounds times
 * a margin (round-off in the normals and the divisions) and the cells are twice as wide, so the
 * box meets one or two cells per component (16 at most, about 5 on average). None is missed
 * and the lowest-numbered match found is the scan's: the same planes, in the same order.
 * Folder contact/ holds the patch geometry and its law; it may call base/ and geometry/, and is
 * called by engine/.
 */
#include "contact/contact.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

/* The tolerance box's half-widths over the tolerances' bounds: far above round-off. */
#define RD_PLANE_MARGIN 1.5

typedef struct plane_grid {
    double bn, bd; /* the tolerance box's half-widths: normal components (1), offset (m) */
    double hn, hd; /* cell widths, twice the half-widths */
    int *head;     /* [nbucket] first plane of each bucket's chain, -1 none */
    int *next;     /* [nf] next plane in its chain */
    unsigned mask; /* nbucket - 1 (a power of two) */
} plane_grid;

static void cell_of(const plane_grid *g, const double n[3], double d, int64_t c[4])
{
    for (int k = 0; k < 3; k++) c[k] = (int64_t)floor(n[k] / g->hn);
    c[3] = (int64_t)floor(d / g->hd);
}

static unsigned cell_bucket(const plane_grid *g, const int64_t c[4])
{
    uint64_t h = 0x9E3779B97F4A7C15ULL;
    for (int k = 0; k < 4; k++) {
        h ^= (uint64_t)c[k] + 0x9E3779B97F4A7C15ULL + (h << 6) + (h >> 2);
        h *= 0xff51afd7ed558ccdULL;
    }
    return (unsigned)(h ^ (h >> 32)) & g->mask;
}

/* Does face f lie in the plane opened by face r? */
static int same_plane(const double (*fn)[3], const double *fd, int f, int r, double ntol,
                      double dtol)
{
    const double dot = fn[f][0] * fn[r][0] + fn[f][1] * fn[r][1] + fn[f][2] * fn[r][2];
    return dot > 1 - ntol && fabs(fd[r] - fd[f]) <= dtol;
}

/* The lowest-numbered plane that face f lies in, searched over the cells its tolerance box
 * meets; -1 none. */
static int first_match(const plane_grid *g, const double (*fn)[3], const double *fd,
                       const int *first, int f, double ntol, double dtol)
{
    const double lo[4] = { fn[f][0] - g->bn, fn[f][1] - g->bn, fn[f][2] - g->bn, fd[f] - g->bd };
    const double hi[4] = { fn[f][0] + g->bn, fn[f][1] + g->bn, fn[f][2] + g->bn, fd[f] + g->bd };
    int64_t c0[4], c1[4], q[4];
    cell_of(g, lo, lo[3], c0);
    cell_of(g, hi, hi[3], c1);
    int best = -1;
    for (int m = 0; m < 16; m++) {
        int skip = 0;
        for (int k = 0; k < 4; k++) {
            q[k] = (m >> k & 1) ? c1[k] : c0[k];
            skip |= (m >> k & 1) && c1[k] == c0[k]; /* that component meets one cell */
        }
        if (skip) continue;
        for (int k = g->head[cell_bucket(g, q)]; k >= 0; k = g->next[k])
            if ((best < 0 || k < best) && same_plane(fn, fd, f, first[k], ntol, dtol)) best = k;
    }
    return best;
}

int rd_plane_group(int nf, const double (*fn)[3], const double *fd, double ntol, double dtol,
                   int *plane_of, int *first)
{
    plane_grid g;
    g.bn = RD_PLANE_MARGIN * sqrt(2 * ntol);
    g.bd = RD_PLANE_MARGIN * dtol;
    g.hn = 2 * g.bn;
    g.hd = 2 * g.bd;
    unsigned nbucket = 16;
    while (nbucket < 2u * (unsigned)nf) nbucket *= 2;
    g.mask = nbucket - 1;
    g.head = malloc(nbucket * sizeof *g.head);
    g.next = malloc((size_t)(nf ? nf : 1) * sizeof *g.next);
    if (!g.head || !g.next) {
        free(g.head);
        free(g.next);
        return -1;
    }
    for (unsigned b = 0; b < nbucket; b++) g.head[b] = -1;
    int np = 0;
    for (int f = 0; f < nf; f++) {
        int k = first_match(&g, fn, fd, first, f, ntol, dtol);
        if (k < 0) { /* a new plane, filed under its opening face's cell */
            int64_t c[4];
            cell_of(&g, fn[f], fd[f], c);
            const unsigned b = cell_bucket(&g, c);
            k = np++;
            first[k] = f;
            g.next[k] = g.head[b];
            g.head[b] = k;
        }
        plane_of[f] = k;
    }
    free(g.head);
    free(g.next);
    return np;
}
