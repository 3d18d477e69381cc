/* rockdem — the response mode of a body in one sweep case (docs/FRAGILITY.md "Response
 * modes"): rest, slide, rock, rock-slide, rock-twist, overturn, from the run's summary (uplift,
 * max tilt / alpha, max |twist about the vertical|, overturned) and the largest slip of the
 * body's joints (tangential displacement at the centre of pressure, elastic shear removed; not
 * the sway of the body's centre, which rocking alone produces).
 *
 * Folder ensembles/ owns many-run studies; it may call the public API.
 */
#include "rockdem/sweep.h"

#include <math.h>

rd_sweep_mode rd_sweep_mode_of(const rd_body_summary *b, double max_slip)
{
    if (b->overturned) return RD_MODE_OVERTURN;
    int rock = b->uplifted && b->max_tilt_ratio >= RD_MODE_TILT_MIN;
    int slide = max_slip >= RD_MODE_SLIP_MIN;
    if (rock && fabs(b->max_twist) >= RD_MODE_TWIST_MIN) return RD_MODE_ROCK_TWIST;
    if (rock) return slide ? RD_MODE_ROCK_SLIDE : RD_MODE_ROCK;
    return slide ? RD_MODE_SLIDE : RD_MODE_REST;
}

const char *rd_sweep_mode_name(rd_sweep_mode m)
{
    static const char *const names[RD_MODE_COUNT] = { "rest",       "slide",      "rock",
                                                      "rock-slide", "rock-twist", "overturn" };
    return m >= 0 && m < RD_MODE_COUNT ? names[m] : "unknown";
}
