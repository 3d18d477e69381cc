/* rockdem — `rockdem run` prints one line of intensity measures per applied record component
 * (the same values rd_h5_ground_im writes as attributes of /ground).
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"

#include <stdio.h>

int rd_cli_print_motion(const rd_motion_def *m)
{
    const double g = RD_G_STANDARD; /* accelerations printed in g */
    for (int c = 0; c < RD_NCOMPONENTS; c++) {
        const rd_record *r = m->record[c].applied;
        rd_im im;
        double sa[2];
        rd_error err;
        if (!r) continue;
        if (rd_motion_im(m, c, &im, sa, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            return -1;
        }
        printf(
            "motion %s: %s; PGA %.6g g, PGV %.4g m/s, PGD %.4g m, PGV/PGA %.4g s, Arias %.4g m/s, "
            "D5-95 %.4g s, Sa(0.2 s) %.4g g, Sa(1 s) %.4g g (5 %%); scale %.6g\n",
            rd_motion_component_name(c), r->name, im.pga / g, im.pgv, im.pgd, im.pgv_pga, im.arias,
            im.d5_95, sa[0] / g, sa[1] / g, m->factor);
    }
    return 0;
}
