/* vec.c - the vector helpers of vec.h that are not inline. */
#include "vec.h"

int abrdf__normalise3(const double v[3], double out[3])
{
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
