/* kernel.h - the precision prelude of the model kernels. Included (with everything that
 * follows it) once per precision: the includer defines ABRDF_REAL (double or float) and
 * ABRDF_SFX (d or f). Provides
 *   R, K(x), FN(name)     the real type, a constant of that type, a suffixed name
 *   safe_* guards         the only place where sqrt/acos/division/pow are made safe
 *   kp                    model parameters converted to R, with per-model precomputation
 *   geo                   the local-frame geometry every model reads (cosines, H, R.V)
 * Math functions come from <tgmath.h>, so sqrt/pow/exp resolve to the float versions in
 * the float instantiation. */
#include <tgmath.h>
#include "abrdf_internal.h"

#define ABRDF__CAT2(a, b) a##_##b
#define ABRDF__CAT(a, b) ABRDF__CAT2(a, b)
#define R ABRDF_REAL
#define K(x) ((R)(x))
#define FN(name) ABRDF__CAT(name, ABRDF_SFX)

/* ---- guards ---------------------------------------------------------------------- */
/* Two plain selects (no nested or unordered compares) so batch loops vectorise; NaN -> lo. */
static inline R FN(clampr)(R x, R lo, R hi)
{
    R y = x > lo ? x : lo;
    return y < hi ? y : hi;
}
static inline R FN(pos)(R x) { return x > K(0) ? x : K(0); }  /* NaN -> 0 as well */
static inline R FN(safe_sqrt)(R x) { return sqrt(FN(pos)(x)); }
static inline R FN(safe_div)(R a, R b) { return b != K(0) ? a / b : K(0); }
/* pow with the base clamped to >= 0: C's pow(negative, non-integer) is NaN, and an even
 * power of a negative base would give a spurious lobe (MODELS.md B0). */
static inline R FN(pow_pos)(R x, R e) { return pow(FN(pos)(x), e); }
/* x^(2^k) by k squarings of max(0, x): the Table-1 forms (MODELS.md B3). */
static inline R FN(pow2k)(R x, int k)
{
    R y = FN(pos)(x);
    for (int i = 0; i < k; ++i) y *= y;
    return y;
}

/* ---- parameters in the kernel's precision ------------------------------------------ */
typedef struct FN(abrdf__kp) {
    R kd[3], ks[3], f0[3];
    R n;          /* exponent */
    R r;          /* perceptual roughness */
    R ag;         /* alpha_g = max(r^2, ABRDF__ALPHA_G_MIN) */
    R ax, ay;     /* anisotropic alpha_g along T and B */
    R on_a, on_b; /* Oren-Nayar A and B */
    R cc_alpha;   /* clearcoat GTR1 alpha */
    R k_amp;
    R norm;       /* the model's normalisation constant (Table 5), 1 where none */
    R fkub[3];    /* a, b, d of the cubic approximation about c = 1 for this n */
    R fkub_x0;    /* below this cosine the cubic is zero */
} FN(abrdf__kp);
#define kp FN(abrdf__kp)

/* ---- local-frame geometry ----------------------------------------------------------- */
typedef struct FN(abrdf__geo) {
    R ix, iy, iz;   /* wi */
    R ox, oy, oz;   /* wo */
    R ci, co;       /* cos_i = N.wi, cos_o = N.wo, clamped to [-1, 1] */
    R hx, hy, hz;   /* H; +z when wi ~ -wo (then the pair is rejected as back-facing) */
    R ch;           /* N.H */
    R sh2;          /* |N x H|^2 = sin^2(theta_h), without the cancellation of 1 - ch^2 */
    R cd;           /* wi.H = wo.H = |wi + wo|/2 in [0, 1] */
    R rv;           /* R.wo, R the mirror of wi: cos(gamma) of Phong */
} FN(abrdf__geo);
#define geo FN(abrdf__geo)

static inline void FN(geo_make)(geo *g, R ix, R iy, R iz, R ox, R oy, R oz)
{
    g->ix = ix; g->iy = iy; g->iz = iz;
    g->ox = ox; g->oy = oy; g->oz = oz;
    g->ci = FN(clampr)(iz, K(-1), K(1));
    g->co = FN(clampr)(oz, K(-1), K(1));
    R hx = ix + ox, hy = iy + oy, hz = iz + oz;
    R len2 = hx * hx + hy * hy + hz * hz;
    int ok = len2 > K(ABRDF__HALF_LEN2_MIN);
    R len = sqrt(ok ? len2 : K(1));
    R inv = ok ? K(1) / len : K(0);
    g->hx = ok ? hx * inv : K(0);
    g->hy = ok ? hy * inv : K(0);
    g->hz = ok ? hz * inv : K(1);
    g->ch = FN(clampr)(g->hz, K(-1), K(1));
    g->sh2 = FN(clampr)(g->hx * g->hx + g->hy * g->hy, K(0), K(1));
    /* cos(theta_d) = wi.H = |wi + wo| / 2 for unit vectors. The norm form is bitwise
     * symmetric in wi and wo (reciprocity to the last bit), and it does not cancel when
     * wi ~ -wo: wi.H there loses ~1e-4 relative in float for inputs that are unit only to
     * float precision. */
    g->cd = ok ? FN(clampr)(K(0.5) * len, K(0), K(1)) : K(0);
    g->rv = FN(clampr)(-ix * ox - iy * oy + iz * oz, K(-1), K(1));
}

/* Both directions strictly above the surface: the only pairs with a non-zero BRDF. */
static inline int FN(geo_front)(const geo *g) { return g->ci > K(0) && g->co > K(0); }

/* Schlick's Fresnel, Eq. 8: F0 + (1 - F0)(1 - cos_d)^5, cos_d clamped to [0, 1]. */
static inline R FN(f_schlick)(R f0, R cos_d)
{
    R m = K(1) - FN(clampr)(cos_d, K(0), K(1));
    R m2 = m * m;
    return f0 + (K(1) - f0) * (m2 * m2 * m); /* Eq. 8 */
}
