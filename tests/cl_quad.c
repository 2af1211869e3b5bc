/* cl_quad.c - random directions of the cloth and layered suites. */
#include <math.h>
#include "cl_quad.h"

static const double PI = 3.14159265358979323846;

double clq_rand(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (*s >> 8) / 16777216.0;
}

void clq_rand_dir(unsigned *s, double zmin, double out[3])
{
    double z = zmin + (1.0 - zmin) * clq_rand(s), phi = 2.0 * PI * clq_rand(s);
    double r = sqrt(fmax(0.0, 1.0 - z * z));
    out[0] = r * cos(phi);
    out[1] = r * sin(phi);
    out[2] = z;
}
