/* kernel.h - the precision prelude of the closed-form model kernels.
 *
 * The kernels are written once, against abrdf__real and <tgmath.h>'s type-generic math (so
 * sqrt/pow/exp resolve to the float versions in float), and compiled twice: eval_double.c
 * in double (the scalar reference), eval_float.c in float (the batch path). A translation
 * unit asks for float by defining ABRDF__KERNEL_FLOAT to 1 before it includes a kernel
 * header; otherwise the kernels are double. Every k_*.h includes this prelude and the other
 * headers it uses, and is guarded once.
 *
 * NAMING RULE: every kernel, term and guard is defined under the plain name it is called by,
 * in both precisions. A translation unit includes the kernels in one precision only (double:
 * eval_double.c, sample_lobe.c, sample_mix.c, tests/unit/closed_form_terms.c; float:
 * eval_float.c; a later include asking for the other precision is an #error below), and
 * they are static inline, so the double and the float copies never meet.
 *   k_f8           the kernel of model f8 (k_empirical.h)
 *   k_f8_lobe      its scalar lobe (form LOBE, k_dispatch.h)
 *   k_fkub_setup   a model's setup
 *   d_ggx          a term (k_terms.h)
 *   abrdf__real    the real type: double, or float with ABRDF__KERNEL_FLOAT
 *   abrdf__kp      the prepared parameters: abrdf__kp_d or abrdf__kp_f (prepared.h)
 *   abrdf__geo     the local-frame geometry
 *   batch_k_f8_1   the batch loop of k_f8 at instruction-set level 1 (eval_float.c)
 *   scalar_k_f8    the double scalar evaluation of k_f8, one pair (eval_double.c)
 *
 * Provides, in the translation unit's precision:
 *   abrdf__real, ABRDF__K(x)  the real type and the constant x in it
 *   guards                    clampr, pos, safe_sqrt, safe_div, clampg, pow_pos, pow2k,
 *                             finite_or_zero: the kernels' only guarded sqrt, division, pow
 *   exp_r                     e^x (with pow_pos, the only transcendentals a batch loop calls:
 *                             float ones from fmath.h, which vectorise)
 *   abrdf__kp, kp_base        the prepared parameters and the conversion every setup starts
 *                             with (Cycles' "setup" step; each model's setup is beside its
 *                             kernel, k_dispatch.h lists them)
 *   abrdf__geo, geo_make      the geometry every kernel reads (cosines, H, R.V)
 *   pow_ch                    (N.H)^e, the lobe on N.H (in float without N.H's square root)
 * The thresholds are named in guards.h. */
#ifndef ABRDF_KERNEL_H
#define ABRDF_KERNEL_H
#include <float.h>
#include <tgmath.h>

#include "abrdf_internal.h"
#include "fmath.h"
#include "prepared.h"

/* The precision of this translation unit's kernels, fixed by its first include of kernel.h
 * (ABRDF__KERNEL_IS_FLOAT records it for the check at the end of this file). */
#if ABRDF__KERNEL_FLOAT
#define ABRDF__KERNEL_IS_FLOAT 1
typedef float abrdf__real;
typedef abrdf__kp_f abrdf__kp;
#define ABRDF__REAL_MAX FLT_MAX
#else
#define ABRDF__KERNEL_IS_FLOAT 0
typedef double abrdf__real;
typedef abrdf__kp_d abrdf__kp;
#define ABRDF__REAL_MAX DBL_MAX
#endif
/* The constant x in the kernels' real type. */
#define ABRDF__K(x) ((abrdf__real)(x))

/* ---- guards ---------------------------------------------------------------------- */
/* Two plain selects (no nested or unordered compares) so batch loops vectorise; NaN -> lo. */
static inline abrdf__real clampr(abrdf__real x, abrdf__real lo, abrdf__real hi)
{
    abrdf__real y = x > lo ? x : lo;
    return y < hi ? y : hi;
}
static inline abrdf__real pos(abrdf__real x)
{
    return x > ABRDF__K(0) ? x : ABRDF__K(0); /* NaN -> 0 as well */
}
static inline abrdf__real safe_sqrt(abrdf__real x) { return sqrt(pos(x)); }
static inline abrdf__real safe_div(abrdf__real a, abrdf__real b)
{
    return b != ABRDF__K(0) ? a / b : ABRDF__K(0);
}
/* Clamp of a geometric quantity (cosines, sin^2) that is in range up to rounding for unit
 * inputs. The double path clamps (it is the reference). The float batch path does not:
 * there the clamps cost more than half of a Table-1 approximation's time (GCC expands each
 * select pair into compare/and/or mask sequences under IEEE semantics), every kernel
 * tolerates a 1-ulp excursion, and a NaN still ends as 0 (it fails the front-facing test or
 * finite_or_zero). */
static inline abrdf__real clampg(abrdf__real x, abrdf__real lo, abrdf__real hi)
{
#if ABRDF__KERNEL_IS_FLOAT
    (void)lo;
    (void)hi;
    return x;
#else
    return clampr(x, lo, hi);
#endif
}
/* pow with the base clamped to >= 0: C's pow(negative, non-integer) is NaN, and an even
 * power of a negative base would give a spurious lobe (MODELS.md B0). e >= 0. In float, the
 * vectorisable polynomial form (fmath.h); in double, the C library's pow (the reference). */
static inline abrdf__real pow_pos(abrdf__real x, abrdf__real e)
{
#if ABRDF__KERNEL_IS_FLOAT
    return abrdf__powf_pos(x, e);
#else
    return pow(pos(x), e);
#endif
}
/* e^x: in float the vectorisable form (fmath.h), in double the C library's. */
static inline abrdf__real exp_r(abrdf__real x)
{
#if ABRDF__KERNEL_IS_FLOAT
    return abrdf__expf(x);
#else
    return exp(x);
#endif
}
/* x^(2^k) by k squarings of max(0, x): the Table-1 forms (MODELS.md B3). */
static inline abrdf__real pow2k(abrdf__real x, int k)
{
    abrdf__real y = pos(x);
    for (int i = 0; i < k; ++i) y *= y;
    return y;
}
/* The last line of defence of every eval path (abrdf.h: never NaN, Inf or negative): x if
 * it is a finite number >= 0, else 0. Two selects with a zero arm, each one compare and one
 * AND when vectorised; NaN fails both compares. */
static inline abrdf__real finite_or_zero(abrdf__real x)
{
    abrdf__real y = x >= ABRDF__K(0) ? x : ABRDF__K(0);
    return y <= ABRDF__REAL_MAX ? y : ABRDF__K(0);
}

/* ---- parameters in the kernel's precision ------------------------------------------ */
/* One struct for every model (abrdf__kp is abrdf__kp_d or abrdf__kp_f, defined in prepared.h
 * so that a prepared object holds both); a model's setup fills the fields its kernel reads. */

/* The colours and scalars most kernels read, converted: the first step of every setup and
 * the whole setup of the models with nothing to precompute. */
static inline void kp_base(abrdf__kp *k, const abrdf_params *p)
{
    for (int c = 0; c < 3; ++c) {
        k->kd[c] = (abrdf__real)p->kd[c];
        k->ks[c] = (abrdf__real)p->ks[c];
        k->f0[c] = (abrdf__real)p->f0[c];
        k->ks_f0[c] = (abrdf__real)(p->ks[c] * p->f0[c]);
        k->ks_f1[c] = (abrdf__real)(p->ks[c] * (1.0 - p->f0[c]));
    }
    k->n = (abrdf__real)p->n;
    k->r = (abrdf__real)p->r;
}

/* A microfacet alpha, computed in double, floored at ABRDF__ALPHA_G_MIN and converted. */
static inline abrdf__real kp_alpha(double a)
{
    return (abrdf__real)(a > ABRDF__ALPHA_G_MIN ? a : ABRDF__ALPHA_G_MIN);
}

/* ---- local-frame geometry ----------------------------------------------------------- */
typedef struct abrdf__geo {
    abrdf__real ix, iy, iz; /* wi */
    abrdf__real ox, oy, oz; /* wo */
    abrdf__real ci, co;     /* cos_i = N.wi, cos_o = N.wo, clamped to [-1, 1] (clampg) */
    abrdf__real hx, hy, hz; /* H; +z when wi ~ -wo (then the pair is rejected as back-facing) */
    abrdf__real ch;         /* N.H */
    abrdf__real ch2;        /* (N.H)^2 = max(0, h_z)^2 / |wi + wo|^2, no square root (pow_ch) */
    abrdf__real sh2;        /* |N x H|^2 = sin^2(theta_h), without the cancellation of 1 - ch^2 */
    abrdf__real cd;         /* wi.H = wo.H = |wi + wo|/2 in [0, 1] */
    abrdf__real rv;         /* R.wo, R the mirror of wi: cos(gamma) of Phong */
    /* wi + wo before normalising (0, 0, 1 when wi ~ -wo): |wi + wo|^2, its xy part squared and
     * h_z^2, so that a kernel can divide once by a product instead of normalising H
     * (k_disney_specular_lobe); sh2 = hxy2 / hl2 and ch^2 = hz2 / hl2 */
    abrdf__real hl2, hxy2, hz2;
} abrdf__geo;

/* Always inlined, so that each caller keeps only the fields its kernel reads (the scalar
 * path makes the geometry once per model case: eval_double.c). */
#if defined(__GNUC__)
#define ABRDF__ALWAYS_INLINE __attribute__((always_inline))
#else
#define ABRDF__ALWAYS_INLINE
#endif
static inline ABRDF__ALWAYS_INLINE void geo_make(abrdf__geo *g, abrdf__real ix, abrdf__real iy,
                                                 abrdf__real iz, abrdf__real ox, abrdf__real oy,
                                                 abrdf__real oz)
{
    g->ix = ix;
    g->iy = iy;
    g->iz = iz;
    g->ox = ox;
    g->oy = oy;
    g->oz = oz;
    g->ci = clampg(iz, ABRDF__K(-1), ABRDF__K(1));
    g->co = clampg(oz, ABRDF__K(-1), ABRDF__K(1));
    abrdf__real hx = ix + ox, hy = iy + oy, hz = iz + oz;
    abrdf__real len2 = hx * hx + hy * hy + hz * hz;
    /* Every select tests a float compare directly (no int flag): GCC's vectoriser cannot
     * mix an int mask with float compares ("relevant stmt not supported"). */
    const abrdf__real min2 = ABRDF__K(ABRDF__HALF_LEN2_MIN);
    abrdf__real len = sqrt(len2 > min2 ? len2 : ABRDF__K(1));
    abrdf__real inv = len2 > min2 ? ABRDF__K(1) / len : ABRDF__K(0);
    g->hx = len2 > min2 ? hx * inv : ABRDF__K(0);
    g->hy = len2 > min2 ? hy * inv : ABRDF__K(0);
    g->hz = len2 > min2 ? hz * inv : ABRDF__K(1);
    g->ch = clampg(g->hz, ABRDF__K(-1), ABRDF__K(1));
    abrdf__real hzp = pos(hz);
    g->ch2 = len2 > min2 ? hzp * hzp / len2 : ABRDF__K(1);
    g->sh2 = clampg(g->hx * g->hx + g->hy * g->hy, ABRDF__K(0), ABRDF__K(1));
    /* cos(theta_d) = wi.H = |wi + wo| / 2 for unit vectors. The norm form is bitwise
     * symmetric in wi and wo (reciprocity to the last bit), and it does not cancel when
     * wi ~ -wo: wi.H there loses ~1e-4 relative in float for inputs that are unit only to
     * float precision. */
    g->cd = len2 > min2 ? clampg(ABRDF__K(0.5) * len, ABRDF__K(0), ABRDF__K(1)) : ABRDF__K(0);
    g->rv = clampg(-ix * ox - iy * oy + iz * oz, ABRDF__K(-1), ABRDF__K(1));
    g->hl2 = len2 > min2 ? len2 : ABRDF__K(1);
    g->hxy2 = len2 > min2 ? hx * hx + hy * hy : ABRDF__K(0);
    g->hz2 = len2 > min2 ? hz * hz : ABRDF__K(1);
}

/* (N.H)^e, e >= 0: the Blinn-Phong lobe (Eq. 4) and every lobe on N.H, with N.H <= 0 giving
 * 0^e. In double, pow of the clamped cosine (the reference). In float, ch2^(e/2): N.H is
 * never formed, so a loop that needs nothing else of H does without the square root and
 * the reciprocal of |wi + wo| (one division by |wi + wo|^2 instead), and ch2 rounds twice
 * (the square, the division) where ch rounded three times (square root, reciprocal,
 * product). Where N.H < 2^-63, ch2 is subnormal or 0 (the square underflows), and
 * abrdf__powf_pos raises it as 2^-126 or gives 0^e: c^e is then off by less than 2^-63 e,
 * nothing next to the lobe's peak for e >= 1. */
static inline abrdf__real pow_ch(const abrdf__geo *g, abrdf__real e)
{
#if ABRDF__KERNEL_IS_FLOAT
    return abrdf__powf_pos(g->ch2, ABRDF__K(0.5) * e);
#else
    return pow(pos(g->ch), e);
#endif
}

/* Both directions strictly above the surface: the only pairs with a non-zero BRDF. The
 * clamped cosine ci is > 0 exactly when wi's z is (clampg keeps a positive z or lowers it to
 * 1; z <= 0 and NaN stay <= 0 or fail), so the test reads z and a model that reads no cosine
 * (lambert) is not made to clamp it. */
static inline int geo_front(const abrdf__geo *g)
{
    return g->iz > ABRDF__K(0) && g->oz > ABRDF__K(0);
}

#endif /* ABRDF_KERNEL_H */

/* Every later include asks for the precision of the first (each k_*.h includes this header
 * before its own guard, so every include of a kernel header is checked): kernels in the other
 * precision would have the same names. */
#if (ABRDF__KERNEL_FLOAT ? 1 : 0) != ABRDF__KERNEL_IS_FLOAT
#error "kernel.h: ABRDF__KERNEL_FLOAT differs from the first include in this translation unit"
#endif
