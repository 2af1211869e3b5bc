/* vec.h - the small double 3-vector helpers of the entry points and the batch path. */
#ifndef ABRDF_VEC_H
#define ABRDF_VEC_H
#include <math.h>

static inline double abrdf__dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline int abrdf__finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static inline void abrdf__cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Normalise v into out; returns 0 (and out = 0) for zero, tiny or non-finite vectors.
 * Scales by the largest component first, so squaring cannot overflow or underflow. */
int abrdf__normalise3(const double v[3], double out[3]);

#endif /* ABRDF_VEC_H */
