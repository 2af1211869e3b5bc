/* fmath.h - the float transcendentals of the batch path: 2^y, log2(x), x^e and e^y as plain
 * C (float arithmetic, integer operations on the bits), with no branch and no call, so that
 * the batch loops that use them vectorise at every instruction-set level the dispatcher
 * compiles (eval_float.c). C's expf/powf are calls into the math library that no loop can
 * vectorise: one such call per pair made the models that use them 10-90x dearer than their
 * arithmetic. These are the library's own polynomials (no run-time dependency: libabrdf
 * stays "C99 and the C math library"; docs/BENCHMARKS.md compares them with SLEEF and glibc's
 * vector math, tools/bench/vmath_choice.c).
 *
 *   abrdf__exp2f(y)       2^y; y < -126 gives 0 (no subnormal results), y >= 128 +Inf, NaN 0
 *   abrdf__log2f(x)       log2(x) for x > 0 (subnormals included); the caller excludes x <= 0
 *   abrdf__log2f_normal(x, s)  log2(x) - s for a normal x and an integer-valued s: the core
 *                         of abrdf__log2f and abrdf__powf_pos
 *   abrdf__powf_pos(x, e) max(0, x)^e for e >= 0, with 0^0 = 1 and 0^e = 0 (C's pow); a
 *                         subnormal x is taken as FLT_MIN
 *   abrdf__expf(y)        e^y; y < -87.34 gives 0, y > 88.375 +Inf, NaN 0
 *
 * Errors, measured over every float of the domain by test_fmath (which prints them):
 * abrdf__exp2f within 1.6 ulp of the exact result, abrdf__log2f and abrdf__log2f_normal
 * (s = 0, normal x: the same values) within 2.8 ulp (near x = 1 as well: the polynomial is
 * in t = (m - 1)/(m + 1), so its relative error stays small where log2 vanishes),
 * abrdf__expf within 2 ulp. x^e adds the rounding of y = e log2(x), which
 * 2^y turns into a relative error of about ln 2 (|y| 2^-24 + e 2.8 ulp(log2 x)): for results
 * down to 1e-6 (|y| < 20) a few 1e-6 at most, inside the batch path's float tolerance (2e-5
 * relative, test_invariants), and the order of the rounding of x itself amplified by e that
 * any float x^e has. */
#ifndef ABRDF_FMATH_H
#define ABRDF_FMATH_H
#include <stdint.h>
#include <string.h>

static inline uint32_t abrdf__fbits(float x)
{
    uint32_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}
static inline float abrdf__bitsf(uint32_t u)
{
    float x;
    memcpy(&x, &u, sizeof x);
    return x;
}

/* 2^y = 2^k 2^f with k = floor(y) (up to a tie: f = y - k in [0, 1]): 2^f by its degree-6
 * Chebyshev interpolant on [0, 1] (relative error 2.6e-9 before rounding; its constant term
 * is 1 in float, so 2^0 = 1 exactly), 2^k written into the exponent field. y is clamped to
 * [-126.5, 128] first (a NaN fails both compares and becomes -126.5), so k is in [-127, 128]:
 * k = -127 writes a zero exponent field, i.e. 0; k <= 127 for every y < 128, so only
 * y >= 128 overflows to +Inf. */
static inline float abrdf__exp2f(float y)
{
    y = y > -126.5f ? y : -126.5f;
    y = y < 128.0f ? y : 128.0f;
    /* round y - 1/2 to the nearest integer: adding 1.5 * 2^23 leaves no fraction bits */
    const float shift = 12582912.0f;
    float k = ((y - 0.5f) + shift) - shift;
    float f = y - k; /* exact */
    float p = 2.1877505e-4f;
    p = p * f + 1.2387821e-3f;
    p = p * f + 9.6845805e-3f;
    p = p * f + 5.5480426e-2f;
    p = p * f + 2.4023050e-1f;
    p = p * f + 6.9314693e-1f;
    p = p * f + 1.0f;
    int32_t e = (int32_t)k + 127; /* 0 .. 255 */
    return p * abrdf__bitsf((uint32_t)e << 23);
}

/* log2(x) - s for a normal x (FLT_MIN <= x < Inf) and an integer-valued s: j + log2(m) - s
 * with x = 2^j m, m in [sqrt(1/2), sqrt(2)), log2(m) = t Q(t^2), t = (m - 1)/(m + 1),
 * |t| <= 0.1716, Q the degree-3 Chebyshev interpolant (relative error 1.2e-9 before
 * rounding). j and m come from the bits by integer arithmetic alone, with no compare: adding
 * 0x004AFB0C carries into the exponent field exactly when the mantissa is at least that of
 * the smallest float above sqrt(2) (0x3504F4), and the mantissa plus 0x3F3504F4 is then
 * 0.5 (1.mantissa), else 1.mantissa. A select here made GCC's vectoriser evaluate the
 * polynomial, division included, once per arm. */
static inline float abrdf__log2f_normal(float x, float s)
{
    uint32_t v = abrdf__fbits(x) + 0x004AFB0Cu;
    float j = (float)(int32_t)(v >> 23) - (127.0f + s);
    float m = abrdf__bitsf((v & 0x007FFFFFu) + 0x3F3504F4u);
    float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
    float q = 0.43173302f;
    q = q * t2 + 0.57671451f;
    q = q * t2 + 0.96179885f;
    q = q * t2 + 2.88539008f;
    return j + t * q;
}

/* log2(x) for x > 0, subnormals included: a subnormal x is scaled by 2^24 first. */
static inline float abrdf__log2f(float x)
{
    /* every select on a float compare with float arms: GCC's vectoriser rejects masks that
     * mix float compares with integer selects */
    float tiny = x < 1.17549435e-38f ? 1.0f : 0.0f;
    x = tiny > 0.0f ? x * 16777216.0f : x;
    return abrdf__log2f_normal(x, 24.0f * tiny);
}

/* max(0, x)^e, e >= 0: 2^(e log2 x); x <= 0 (or NaN) gives 0^e: 1 for e = 0, else 0. A
 * subnormal x is raised as FLT_MIN = 2^-126 (so log2 needs no scaling): x^e is then off by
 * less than 2^-126e, nothing for e >= 1 (the lobes' exponents), and for e < 1 the lobe was
 * already discontinuous at x = 0. */
static inline float abrdf__powf_pos(float x, float e)
{
    const float flt_min = 1.17549435e-38f;
    float y = e * abrdf__log2f_normal(x > flt_min ? x : flt_min, 0.0f);
    float r = abrdf__exp2f(y);
    float at_zero = e == 0.0f ? 1.0f : 0.0f;
    return x > 0.0f ? r : at_zero;
}

/* e^y = 2^k e^r with k = round(y log2 e) and r = y - k ln 2 in [-ln2/2, ln2/2], taken in two
 * steps (Cody and Waite: ln 2 = LN2_HI + LN2_LO, LN2_HI with 16 significant bits, so k LN2_HI
 * is exact) so that r keeps its digits where y is large; e^r by its degree-6 Chebyshev
 * interpolant (relative error 2.6e-9 before rounding). y is clamped to [-88, 88.375]: below
 * -87.34 (k = -127) the result is 0, like abrdf__exp2f; above 88.375 it is +Inf. */
static inline float abrdf__expf(float y)
{
    y = y > -88.0f ? y : -88.0f;
    y = y < 88.375f ? y : 88.375f;
    const float shift = 12582912.0f;
    float k = (y * 1.44269504f + shift) - shift;
    float r = (y - k * 0.693145751953125f) - k * 1.42860677e-6f;
    float p = 1.3948581e-3f;
    p = p * r + 8.3751289e-3f;
    p = p * r + 4.1666218e-2f;
    p = p * r + 1.6666415e-1f;
    p = p * r + 5.0000001e-1f;
    p = p * r + 1.0000000f;
    p = p * r + 1.0f;
    int32_t e = (int32_t)k + 127; /* 0 .. 255 */
    return p * abrdf__bitsf((uint32_t)e << 23);
}

#endif /* ABRDF_FMATH_H */
