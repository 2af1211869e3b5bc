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

/* The same, faster for a direction of about unit length (what a renderer passes per sample):
 * one square root and one division where abrdf__normalise3 divides six times (two thirds of a
 * per-sample Lambert call); other vectors go through abrdf__normalise3. The result can differ
 * from abrdf__normalise3's in the last bit: every path uses it except huang's, which keeps
 * abrdf__normalise3 (its quadrature moves by 3e-8 for a one-ulp change of its directions, and
 * its reference values are kept to 1e-10: test_prepared); marschner, weidlich_wilkie and
 * belcour, whose values move by ~1e-14, take directions within 1e-14 of unit length as given
 * (api.c). */
static inline int abrdf__normalise3_unit(const double v[3], double out[3])
{
    double d = abrdf__dot3(v, v);
    if (d >= 0.25 && d <= 4.0) { /* squares can neither overflow nor underflow; NaN fails */
        double inv = 1.0 / sqrt(d);
        for (int c = 0; c < 3; ++c) out[c] = v[c] * inv;
        return 1;
    }
    return abrdf__normalise3(v, out);
}

#endif /* ABRDF_VEC_H */
