/* vec.c - the vector helpers of vec.h that are not inline. */
#include "vec.h"

int abrdf__normalise3(const double v[3], double out[3])
{
    /* The common case, a direction of about unit length (what a renderer passes): one square
     * root and one division, where the general path below divides six times (the divisions
     * were two thirds of a per-sample Lambert call). Squares of components in that range can
     * neither overflow nor underflow; NaN and Inf fail the test. */
    double d = abrdf__dot3(v, v);
    if (d >= 0.25 && d <= 4.0) {
        double inv = 1.0 / sqrt(d);
        for (int c = 0; c < 3; ++c) out[c] = v[c] * inv;
        return 1;
    }
    out[0] = out[1] = out[2] = 0.0;
    if (!abrdf__finite3(v)) return 0;
    /* Scale first so that squaring cannot overflow or underflow. */
    double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    if (!(m > 0.0)) return 0;
    double s[3] = {v[0] / m, v[1] / m, v[2] / m};
    double len = sqrt(abrdf__dot3(s, s));
    for (int c = 0; c < 3; ++c) out[c] = s[c] / len;
    return 1;
}
