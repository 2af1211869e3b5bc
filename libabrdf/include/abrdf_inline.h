/* abrdf_inline.h - the GGX specular lobe (disney_specular) as an inline function, for a
 * renderer that shades one sample at a time in float and wants no call per sample.
 *
 *   abrdf_prepared disney;                       once per material
 *   abrdf_prepare(ABRDF_DISNEY_SPECULAR, &params, &disney);
 *   abrdf_ggx_float lobe;
 *   abrdf_prepared_ggx_float(&disney, &lobe);    ABRDF_OK for disney_specular only
 *   ...
 *   abrdf_ggx_float_eval(&lobe, wi, wo, f);      per sample: inlined, no call, no check
 *
 * The lobe is disney_specular's float kernel (libabrdf/src/kernels/k_microfacet.h: GGX D,
 * separable Smith visibility with the same alpha_g, Schlick's Fresnel; Burley 2012, the
 * paper's Eqs. 5, 6, 8, 9), with the library's guards: f = 0 unless both directions are
 * above the surface, and a value that is not finite gives 0. What abrdf_eval_prepared_float
 * does besides (the rows rule's test of both directions, normalising those that fail it,
 * choosing the instruction set, one indirect call) is left out, so:
 *   - wi and wo must be unit vectors in the local frame (z = normal): squared lengths within
 *     8e-7 of 1, which a direction normalised in float or in double and stored in float
 *     meets. Anything else gives a value, but not the model's;
 *   - for such directions the result is abrdf_eval_prepared_float's, bit for bit, where the
 *     caller's compiler does not contract a * b + c into a fused multiply-add: GCC's ISO C
 *     modes (-std=c99, c11, ...) imply -ffp-contract=off; its GNU C modes and g++ (ISO C++
 *     modes too) contract when the target has FMA (-march=native, AArch64), and then values
 *     differ by up to ~11 ulp (7.6e-7 relative measured), never between zero and non-zero;
 *     pass -ffp-contract=off for the same bits. test_rows holds the bits (the library and
 *     the test are compiled with -ffp-contract=off);
 *   - -ffast-math, -fassociative-math or -Ofast are not supported in a caller of this
 *     function: reassociating the products undoes the scaling that keeps the denominator
 *     from underflowing, and the lobe then gives 0 (or errors of tens of percent) near the
 *     mirror at grazing angles and low roughness, where its value is large.
 * Cost on the machine of docs/BENCHMARKS.md: "The per-sample call", fifth pass.
 *
 * It calls sqrtf: link the C math library (`pkg-config --libs abrdf` and the CMake target
 * abrdf::abrdf bring -lm). abrdf_ggx_float is frozen (abrdf.h, STABLE LAYOUTS): a lobe of
 * another form would come as a new struct. */
#ifndef ABRDF_INLINE_H
#define ABRDF_INLINE_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "abrdf.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct abrdf_ggx_float {
    float alpha_g;  /* GGX alpha_g = r^2, at least 1e-6 */
    float ks_f0[3]; /* ks F0 per channel */
    float ks_f1[3]; /* ks (1 - F0) per channel: ks F = ks_f0 + ks_f1 (1 - cos_d)^5 */
} abrdf_ggx_float;

/* The lobe of a prepared disney_specular: ABRDF_OK; ABRDF_E_NULL for a NULL argument;
 * ABRDF_E_MODEL for an object not prepared or prepared for another model. On every failure
 * a non-NULL lobe is zeroed: it evaluates to 0. */
ABRDF_API int abrdf_prepared_ggx_float(const abrdf_prepared *prepared, abrdf_ggx_float *lobe);

/* f_r (1/sr, three channels) of the lobe for unit local-frame directions wi, wo (above). f
 * may not overlap wi or wo. */
static inline void abrdf_ggx_float_eval(const abrdf_ggx_float *lobe, const float wi[3],
                                        const float wo[3], float f[3])
{
    const float ci = wi[2], co = wo[2];
    const float hx = wi[0] + wo[0], hy = wi[1] + wo[1], hz = wi[2] + wo[2];
    const float len2 = hx * hx + hy * hy + hz * hz;
    const int open = len2 > (float)1e-12; /* wi ~ -wo: H taken as the normal */
    const float hl2 = open ? len2 : 1.0f, hxy2 = open ? hx * hx + hy * hy : 0.0f;
    const float hz2 = open ? hz * hz : 1.0f, cd = open ? 0.5f * sqrtf(len2) : 0.0f;
    /* D V_i V_o over one denominator, both sides scaled by 2^100 (k_microfacet.h says why;
     * written in decimal, exact, for C++ before C++17) */
    const float a2 = lobe->alpha_g * lobe->alpha_g, b2 = 1.0f - a2;
    const float t = hxy2 + a2 * hz2;
    const float vi = ci + sqrtf(a2 + b2 * ci * ci), vo = co + sqrtf(a2 + b2 * co * co);
    const float num = a2 * 1267650600228229401496703205376.0f * hl2 * hl2;
    const float den =
        (float)(3.14159265358979323846 * 1267650600228229401496703205376.0) * t * t * (vi * vo);
    float w = den > 0.0f || den < 0.0f ? num / den : 0.0f; /* NaN: 0 as well, after the guard */
    uint32_t bits;
    memcpy(&bits, &w, sizeof bits);
    w = bits <= 0x7F7FFFFFu ? w : 0.0f; /* NaN, infinite or negative: 0 */
    w *= co > 0.0f ? (ci > 0.0f ? 1.0f : 0.0f) : 0.0f;
    const float c = cd > 0.0f ? (cd < 1.0f ? cd : 1.0f) : 0.0f, m = 1.0f - c, m2 = m * m;
    const float m5 = m2 * m2 * m;
    f[0] = (lobe->ks_f0[0] + lobe->ks_f1[0] * m5) * w;
    f[1] = (lobe->ks_f0[1] + lobe->ks_f1[1] * m5) * w;
    f[2] = (lobe->ks_f0[2] + lobe->ks_f1[2] * m5) * w;
}

#ifdef __cplusplus
}
#endif

#endif /* ABRDF_INLINE_H */
