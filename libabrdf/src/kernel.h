/* kernel.h - the precision prelude of the closed-form model kernels.
 *
 * The kernels are written once, against ABRDF__REAL and <tgmath.h>'s type-generic math (so
 * sqrt/pow/exp resolve to the float versions in float), and compiled twice: eval_double.c
 * in double (the scalar reference), eval_float.c in float (the batch path). A translation
 * unit asks for float by defining ABRDF__KERNEL_FLOAT to 1 before it includes a kernel
 * header; otherwise the kernels are double. Every k_*.h includes this prelude and the other
 * headers it uses, and is guarded once per precision.
 *
 * NAMING RULE: ABRDF__FN(name) is name_d in double and name_f in float; grep the stem.
 *   ABRDF__FN(k_f8)            k_f8_d, k_f8_f                the kernel of model f8
 *   ABRDF__FN(k_fkub_setup)    k_fkub_setup_d, _f            a model's setup
 *   ABRDF__FN(d_ggx)           d_ggx_d, d_ggx_f              a term (k_terms.h)
 *   ABRDF__KP                  abrdf__kp_d, abrdf__kp_f      the prepared parameters
 *   ABRDF__GEO                 abrdf__geo_d, abrdf__geo_f    the local-frame geometry
 *   batch loop of k_f8         batch_k_f8_f                  (eval_float.c)
 *
 * Provides, per precision:
 *   ABRDF__REAL, ABRDF__K(x)  the real type and the constant x in it
 *   guards                    clampr, pos, safe_sqrt, safe_div, clampg, pow_pos, pow2k,
 *                             finite_or_zero: the kernels' only guarded sqrt, division, pow
 *   ABRDF__KP, kp_base        the prepared parameters and the conversion every setup starts
 *                             with (Cycles' "setup" step; each model's setup is beside its
 *                             kernel, k_dispatch.h lists them)
 *   ABRDF__GEO, geo_make      the geometry every kernel reads (cosines, H, R.V)
 * The thresholds are named in guards.h. */
#include <float.h>
#include <tgmath.h>

#include "abrdf_internal.h"
#include "prepared.h"

#undef ABRDF__REAL
#undef ABRDF__REAL_MAX
#undef ABRDF__SFX
#if ABRDF__KERNEL_FLOAT
#define ABRDF__REAL float
#define ABRDF__REAL_MAX FLT_MAX
#define ABRDF__SFX f
#else
#define ABRDF__REAL double
#define ABRDF__REAL_MAX DBL_MAX
#define ABRDF__SFX d
#endif

#ifndef ABRDF_KERNEL_H
#define ABRDF_KERNEL_H
#define ABRDF__CAT2(a, b) a##_##b
#define ABRDF__CAT(a, b) ABRDF__CAT2(a, b)
#define ABRDF__FN(name) ABRDF__CAT(name, ABRDF__SFX)
#define ABRDF__K(x) ((ABRDF__REAL)(x))
#define ABRDF__KP ABRDF__FN(abrdf__kp)
#define ABRDF__GEO ABRDF__FN(abrdf__geo)
#endif

#if ABRDF__KERNEL_FLOAT ? !defined(ABRDF_KERNEL_H_F) : !defined(ABRDF_KERNEL_H_D)
#if ABRDF__KERNEL_FLOAT
#define ABRDF_KERNEL_H_F
#else
#define ABRDF_KERNEL_H_D
#endif

/* ---- guards ---------------------------------------------------------------------- */
/* Two plain selects (no nested or unordered compares) so batch loops vectorise; NaN -> lo. */
static inline ABRDF__REAL ABRDF__FN(clampr)(ABRDF__REAL x, ABRDF__REAL lo, ABRDF__REAL hi)
{
    ABRDF__REAL y = x > lo ? x : lo;
    return y < hi ? y : hi;
}
static inline ABRDF__REAL ABRDF__FN(pos)(ABRDF__REAL x)
{
    return x > ABRDF__K(0) ? x : ABRDF__K(0); /* NaN -> 0 as well */
}
static inline ABRDF__REAL ABRDF__FN(safe_sqrt)(ABRDF__REAL x) { return sqrt(ABRDF__FN(pos)(x)); }
static inline ABRDF__REAL ABRDF__FN(safe_div)(ABRDF__REAL a, ABRDF__REAL b)
{
    return b != ABRDF__K(0) ? a / b : ABRDF__K(0);
}
/* Clamp of a geometric quantity (cosines, sin^2) that is in range up to rounding for unit
 * inputs. The double path clamps (it is the reference). The float batch path does not:
 * there the clamps cost more than half of a Table-1 approximation's time (GCC expands each
 * select pair into compare/and/or mask sequences under IEEE semantics), every kernel
 * tolerates a 1-ulp excursion, and a NaN still ends as 0 (it fails the front-facing test or
 * finite_or_zero). */
static inline ABRDF__REAL ABRDF__FN(clampg)(ABRDF__REAL x, ABRDF__REAL lo, ABRDF__REAL hi)
{
#if ABRDF__KERNEL_FLOAT
    (void)lo;
    (void)hi;
    return x;
#else
    return ABRDF__FN(clampr)(x, lo, hi);
#endif
}
/* pow with the base clamped to >= 0: C's pow(negative, non-integer) is NaN, and an even
 * power of a negative base would give a spurious lobe (MODELS.md B0). */
static inline ABRDF__REAL ABRDF__FN(pow_pos)(ABRDF__REAL x, ABRDF__REAL e)
{
    return pow(ABRDF__FN(pos)(x), e);
}
/* x^(2^k) by k squarings of max(0, x): the Table-1 forms (MODELS.md B3). */
static inline ABRDF__REAL ABRDF__FN(pow2k)(ABRDF__REAL x, int k)
{
    ABRDF__REAL y = ABRDF__FN(pos)(x);
    for (int i = 0; i < k; ++i) y *= y;
    return y;
}
/* The last line of defence of every eval path (abrdf.h: never NaN, Inf or negative): x if
 * it is a finite number >= 0, else 0. Two selects with a zero arm, each one compare and one
 * AND when vectorised; NaN fails both compares. */
static inline ABRDF__REAL ABRDF__FN(finite_or_zero)(ABRDF__REAL x)
{
    ABRDF__REAL y = x >= ABRDF__K(0) ? x : ABRDF__K(0);
    return y <= ABRDF__REAL_MAX ? y : ABRDF__K(0);
}

/* ---- parameters in the kernel's precision ------------------------------------------ */
/* One struct for every model (abrdf__kp_d, abrdf__kp_f, defined in prepared.h so that a
 * prepared object holds both); a model's setup fills the fields its kernel reads. */

/* The colours and scalars most kernels read, converted: the first step of every setup and
 * the whole setup of the models with nothing to precompute. */
static inline void ABRDF__FN(kp_base)(ABRDF__KP *k, const abrdf_params *p)
{
    for (int c = 0; c < 3; ++c) {
        k->kd[c] = (ABRDF__REAL)p->kd[c];
        k->ks[c] = (ABRDF__REAL)p->ks[c];
        k->f0[c] = (ABRDF__REAL)p->f0[c];
    }
    k->n = (ABRDF__REAL)p->n;
    k->r = (ABRDF__REAL)p->r;
}

/* A microfacet alpha, computed in double, floored at ABRDF__ALPHA_G_MIN and converted. */
static inline ABRDF__REAL ABRDF__FN(kp_alpha)(double a)
{
    return (ABRDF__REAL)(a > ABRDF__ALPHA_G_MIN ? a : ABRDF__ALPHA_G_MIN);
}

/* ---- local-frame geometry ----------------------------------------------------------- */
typedef struct ABRDF__FN(abrdf__geo) {
    ABRDF__REAL ix, iy, iz; /* wi */
    ABRDF__REAL ox, oy, oz; /* wo */
    ABRDF__REAL ci, co;     /* cos_i = N.wi, cos_o = N.wo, clamped to [-1, 1] (clampg) */
    ABRDF__REAL hx, hy, hz; /* H; +z when wi ~ -wo (then the pair is rejected as back-facing) */
    ABRDF__REAL ch;         /* N.H */
    ABRDF__REAL sh2;        /* |N x H|^2 = sin^2(theta_h), without the cancellation of 1 - ch^2 */
    ABRDF__REAL cd;         /* wi.H = wo.H = |wi + wo|/2 in [0, 1] */
    ABRDF__REAL rv;         /* R.wo, R the mirror of wi: cos(gamma) of Phong */
} ABRDF__GEO;

static inline void ABRDF__FN(geo_make)(ABRDF__GEO *g, ABRDF__REAL ix, ABRDF__REAL iy,
                                       ABRDF__REAL iz, ABRDF__REAL ox, ABRDF__REAL oy,
                                       ABRDF__REAL oz)
{
    g->ix = ix;
    g->iy = iy;
    g->iz = iz;
    g->ox = ox;
    g->oy = oy;
    g->oz = oz;
    g->ci = ABRDF__FN(clampg)(iz, ABRDF__K(-1), ABRDF__K(1));
    g->co = ABRDF__FN(clampg)(oz, ABRDF__K(-1), ABRDF__K(1));
    ABRDF__REAL hx = ix + ox, hy = iy + oy, hz = iz + oz;
    ABRDF__REAL len2 = hx * hx + hy * hy + hz * hz;
    /* Every select tests a float compare directly (no int flag): GCC's vectoriser cannot
     * mix an int mask with float compares ("relevant stmt not supported"). */
    const ABRDF__REAL min2 = ABRDF__K(ABRDF__HALF_LEN2_MIN);
    ABRDF__REAL len = sqrt(len2 > min2 ? len2 : ABRDF__K(1));
    ABRDF__REAL inv = len2 > min2 ? ABRDF__K(1) / len : ABRDF__K(0);
    g->hx = len2 > min2 ? hx * inv : ABRDF__K(0);
    g->hy = len2 > min2 ? hy * inv : ABRDF__K(0);
    g->hz = len2 > min2 ? hz * inv : ABRDF__K(1);
    g->ch = ABRDF__FN(clampg)(g->hz, ABRDF__K(-1), ABRDF__K(1));
    g->sh2 = ABRDF__FN(clampg)(g->hx * g->hx + g->hy * g->hy, ABRDF__K(0), ABRDF__K(1));
    /* cos(theta_d) = wi.H = |wi + wo| / 2 for unit vectors. The norm form is bitwise
     * symmetric in wi and wo (reciprocity to the last bit), and it does not cancel when
     * wi ~ -wo: wi.H there loses ~1e-4 relative in float for inputs that are unit only to
     * float precision. */
    g->cd = len2 > min2 ? ABRDF__FN(clampg)(ABRDF__K(0.5) * len, ABRDF__K(0), ABRDF__K(1))
                        : ABRDF__K(0);
    g->rv = ABRDF__FN(clampg)(-ix * ox - iy * oy + iz * oz, ABRDF__K(-1), ABRDF__K(1));
}

/* Both directions strictly above the surface: the only pairs with a non-zero BRDF. */
static inline int ABRDF__FN(geo_front)(const ABRDF__GEO *g)
{
    return g->ci > ABRDF__K(0) && g->co > ABRDF__K(0);
}

#endif /* per-precision guard */
