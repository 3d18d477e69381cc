/* rockdem — ground motion with its directions' cosines and sines found once (records/motion.c):
 * rd_motion_eval finds them at every call; a run whose motion stays fixed keeps them.
 * Folder records/ owns ground motions; it may call base/ only.
 */
#ifndef RD_RECORDS_MOTION_AXES_H
#define RD_RECORDS_MOTION_AXES_H

#include "rockdem/motion.h"

/* (cos, sin) of the pulse's direction and of the records' h1 direction, rad */
typedef struct rd_motion_axes {
    double pulse[2];
    double record[2];
} rd_motion_axes;

void rd_motion_axes_of(const rd_motion_def *m, rd_motion_axes *ax);

/* rd_motion_eval with m's axes already found (rd_motion_axes_of): the same values. */
void rd_motion_eval_axes(const rd_motion_def *m, const rd_motion_axes *ax, double t, double acc[3],
                         double vel[3], double disp[3]);

#endif
