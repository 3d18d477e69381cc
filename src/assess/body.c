/* rockdem — the rigid body of the assessment: half-width to the pivot b, height of the centre
 * of mass h, mass and moment of inertia about the pivot (seed 001 Table 1), for a box and for
 * a regular prism or cylinder rocking on its rim.
 * Folder assess/ owns the seismic assessment of unanchored bodies; it may call base/,
 * records/, scenario/, engine/ and io/.
 */
#include "rockdem/assess.h"

#include <math.h>

void rd_assess_body_brick(rd_assess_body *b, double width, double height, double mass, double mu)
{
    b->b = 0.5 * width;
    b->h = 0.5 * height;
    b->mass = mass;
    /* seed 001 Table 1: I0 = m (b^2 + h^2) / 3 for the box, I = I0 + m R^2 about the corner */
    double R2 = b->b * b->b + b->h * b->h;
    b->inertia = mass * R2 / 3.0 + mass * R2;
    b->mu = mu;
}

void rd_assess_body_prism(rd_assess_body *b, int sides, double radius, double height, double mass,
                          double mu)
{
    double c = sides >= 3 ? cos(M_PI / sides) : 1.0;
    /* centroidal in-plane moment of area of the regular n-gon: R^2 (1 + 2 cos^2(pi/n)) / 12
       per unit area (half its polar moment); R^2 / 4 for the circle (the limit n -> inf) */
    double k2 = radius * radius * (sides >= 3 ? (1.0 + 2.0 * c * c) / 12.0 : 0.25);
    b->b = radius * c;
    b->h = 0.5 * height;
    b->mass = mass;
    b->inertia = mass * (k2 + height * height / 12.0) + mass * (b->b * b->b + b->h * b->h);
    b->mu = mu;
}

double rd_assess_alpha(const rd_assess_body *b) { return atan2(b->b, b->h); }
