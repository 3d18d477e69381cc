/* rockdem (private) — named physical and tuning constants, with their units and the reason for
 * each value. Folder base/: errors, vectors and constants; it calls nothing else in rockdem.
 * The contact model's own constants live beside it in engine/contact.c.
 */
#ifndef RD_CONSTANTS_H
#define RD_CONSTANTS_H

/* rad per degree: scenario files and --set values give angles in degrees, rockdem stores rad. */
#define RD_DEG (3.14159265358979323846 / 180.0)

/* Standard gravity, m/s^2, is RD_G_STANDARD (public: include/rockdem/record.h): the unit `g` of
 * records, of the `g` suffix on accelerations, and of printed accelerations. The default
 * gravity of a scene, RD_GRAVITY_DEFAULT, is the rounded 9.81 m/s^2 of the rocking literature
 * (Housner 1963, Makris & Konstantinidis 2003), so closed-form references compare directly. */
#define RD_GRAVITY_DEFAULT 9.81

/* Characters no decimal number of a scenario or option holds, though strtod reads them: the
 * hexadecimal prefix and binary exponent (0x10 is 16, 0x1p1 is 2). */
#define RD_NOT_DECIMAL "xXpP"

/* ---- monitors (engine/monitor.c) ---- */

/* Uplift hysteresis on the contact area, as fractions of the area at rest: a body is "uplifted"
 * when its base contact area falls below RD_UPLIFT_AREA_ON of its rest area, and seated again
 * only when it is back above RD_UPLIFT_AREA_OFF (and nearly upright). Two thresholds, not one,
 * so that the area's small step-to-step noise under full contact (subcontact points flickering
 * at zero overlap) does not fire an uplift event every step. */
#define RD_UPLIFT_AREA_ON  0.6
#define RD_UPLIFT_AREA_OFF 0.9

/* ---- stepping (engine/sim.c) ---- */

/* A body moving faster than this, in (m/s)^2 of v^2 + (w r)^2, has run away: no rigid block
 * under earthquake shaking gets near 1000 m/s, so such a speed means the explicit step went
 * unstable (a time step above the contact's critical one) and the run stops with an error. */
#define RD_RUNAWAY_V2 1e6

/* Local (non-viscous) damping ratio while settling the scene under gravity before the shaking,
 * 3DEC's default 0.8 for static solutions: it removes most kinetic energy each cycle so the
 * stack comes to rest within a few hundred steps; the dynamic run uses the scenario's damping. */
#define RD_SETTLE_DAMPING 0.8

/* ---- broad phase (engine/pairs.c) ---- */

/* Bounding boxes are inflated by this fraction of the smallest body's bounding radius, so a
 * pair enters the contact cache a few steps before the bodies touch (no contact is missed
 * between two broad-phase updates); 5 % keeps false pairs few. */
#define RD_BROAD_MARGIN 0.05

/* ---- subcontact candidate faces (engine/setup.c) ---- */

/* A face "faces down" when its outward normal's z component is below this (normal more than
 * 60 degrees from horizontal, cos 120 deg = -0.5): a rock's base, not its flanks. */
#define RD_FACE_DOWN_NZ (-0.5)

/* A face lies in a body's base region when its lowest vertex is within this fraction of the
 * body's height above the body's lowest point (the lowest fifth: a boulder's flattened base,
 * not an overhang higher up). */
#define RD_BASE_FRACTION 0.2

#endif
