/* rockdem — `rockdem reference SCENARIO [--set k=v]... [-o out.h5]`: run the scene through the
 * rigid reference solver it maps to (Housner or Kounadis, src/reference/ref_scene.c) and write
 * the DEM's HDF5 layout, so one tool reads both. Other scenes are refused with the reason.
 * Folder cli/ owns the rockdem program (not part of librockdem); it may call the public API and
 * ensembles/.
 */
#include "cli/cli.h"
#include "rockdem/validate.h"

#include <stdio.h>

int rd_cli_reference(int argc, char **argv)
{
    rd_scenario sc;
    const char *out = NULL;
    if (rd_cli_scenario(&sc, argc, argv, NULL, NULL, &out)) {
        rd_scenario_free(&sc);
        return 2;
    }
    rd_error err;
    rd_refscene rs;
    if (rd_refscene_map(&sc, &rs, &err) || rd_refscene_check_output(&sc, sc.output.path, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        rd_scenario_free(&sc);
        return 2;
    }
    rd_ref_result res = { 0 };
    rd_summary sum;
    rd_body_summary body[RD_REF_BLOCKS];
    int rc = rd_refscene_solve(&sc, &rs, &res, &err);
    if (rc == 0) rc = rd_refscene_write(&sc, &rs, &res, sc.output.path, &sum, body, &err);
    if (rc) {
        fprintf(stderr, "%s: %s\n", sc.file, err.msg);
    } else {
        if (rs.equivalent)
            printf(
                "reference: APPROXIMATE: body '%s' is no brick; Housner's one-block equation with its own "
                "alpha, R = %.4g m and pivot inertia along the shaking (the lesser side), as the block "
                "b = %.4g m, h = %.4g m of the same alpha and p; its impacts keep r = 1 - 2 p^2 R sin^2(alpha) "
                "/ g (exact only for a body symmetric about the rocking plane's vertical)\n",
                sc.bodies[rs.body[0]].name, rs.R_own, rs.b[0], rs.h[0]);
        printf("reference: %s, alpha = %.4g rad, p = %.4g 1/s",
               rs.model == RD_REFMODEL_HOUSNER ? "Housner (one block)"
                                               : "Kounadis (two-block stack)",
               rs.alpha, rs.p);
        if (rs.model == RD_REFMODEL_HOUSNER)
            printf(", e = %.4g", rs.housner.e >= 0 ? rs.housner.e : rd_housner_r(rs.alpha));
        printf("\n");
        for (int k = 0; k < sum.nbodies; k++) {
            const rd_body_summary *b = &sum.body[k];
            printf("%s: %s", b->name,
                   b->overturned ? "OVERTURNED"
                   : b->uplifted ? "rocked"
                                 : "stayed seated");
            if (b->overturned) printf(" at t = %.4f s", b->overturn_time);
            printf("; max tilt %.4g rad = %.3g alpha\n", b->max_tilt, b->max_tilt_ratio);
        }
        printf("run: t = %.4g s, %zu impacts%s\noutput: %s\n", res.summary.t_stop,
               res.summary.nimpacts,
               res.summary.lifted_off ? ", stopped at a lift-off (jumping)" : "", sc.output.path);
    }
    rd_ref_result_free(&res);
    rd_scenario_free(&sc);
    return rc ? 3 : 0;
}
