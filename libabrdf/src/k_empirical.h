/* k_empirical.h - the empirical specular lobes: Phong, Blinn-Phong (Eq. 4) and the
 * approximations of Blinn-Phong of the paper's Table 1. Each returns ks * lobe, an
 * unnormalised lobe used as a BRDF (abrdf.h, direction convention).
 *
 * Phong: B. T. Phong, "Illumination for computer generated pictures", CACM 18(6), 1975:
 *   cos(gamma)^n, gamma = angle(R, V).
 * Blinn-Phong (Eq. 4): J. F. Blinn, "Models of light reflection for computer synthesized
 *   pictures", SIGGRAPH 1977: cos(theta_h)^n.
 * f2, f4, f8, f16 (Table 1): ((n/m)(c - 1) + 1)^m, the limit form of (1 + x/m)^m, usually
 *   attributed to Lyon 1993 (Apple TR 43). The base is clamped at 0 (the paper's Table 4
 *   note "the point after which the function must be zeroed"); evaluated by log2(m)
 *   squarings.
 * fs (Table 1): C. Schlick, "A fast alternative to Phong's specular model", Graphics Gems IV,
 *   1994: c / (n - n c + c).
 * fkv (Table 1): the paper's quadratic 0.786 n c^2 + (1 - 0.786 n) c, clamped at 0 because
 *   it is negative on (0, 1 - 1/(0.786 n)) (MODELS.md B3).
 * fkub (Table 1): a cubic A c^3 + B c^2 + C c (Romanyuk et al., IAPGOS 13(3), 2023) whose
 *   coefficients the paper does not give; the project fits them (tools/gen/fit_fkub.c, table
 *   in fkub_table.c), evaluates the same cubic written about c = 1 (stable in float for
 *   large n), zeroes it below the fitted zone start x0 and clamps it to [0, 1].
 * All lobes take c = N.H (they approximate Blinn-Phong), Phong takes c = R.V. */

static inline void FN(lobe_out)(const kp *p, R lobe, R f[3])
{
    for (int c = 0; c < 3; ++c) f[c] = p->ks[c] * lobe;
}

static inline void FN(k_phong)(const kp *p, const geo *g, R f[3])
{
    FN(lobe_out)(p, FN(pow_pos)(g->rv, p->n), f);
}

static inline void FN(k_blinn_phong)(const kp *p, const geo *g, R f[3])
{
    FN(lobe_out)(p, FN(pow_pos)(g->ch, p->n), f); /* Eq. 4 */
}

/* ((n/m)(c - 1) + 1)^m with m = 2^k, Table 1. */
static inline R FN(lobe_fm)(R n, R c, int k)
{
    R m = (R)(1 << k);
    return FN(pow2k)((n / m) * (c - K(1)) + K(1), k);
}

static inline void FN(k_f2)(const kp *p, const geo *g, R f[3])
{
    FN(lobe_out)(p, FN(lobe_fm)(p->n, g->ch, 1), f);
}
static inline void FN(k_f4)(const kp *p, const geo *g, R f[3])
{
    FN(lobe_out)(p, FN(lobe_fm)(p->n, g->ch, 2), f);
}
static inline void FN(k_f8)(const kp *p, const geo *g, R f[3])
{
    FN(lobe_out)(p, FN(lobe_fm)(p->n, g->ch, 3), f);
}
static inline void FN(k_f16)(const kp *p, const geo *g, R f[3])
{
    FN(lobe_out)(p, FN(lobe_fm)(p->n, g->ch, 4), f);
}

static inline void FN(k_fs)(const kp *p, const geo *g, R f[3])
{
    R c = FN(pos)(g->ch);
    /* n(1 - c) + c >= min(1, n) c-independent lower bound; 0 only at n = 0, c = 0. */
    FN(lobe_out)(p, FN(safe_div)(c, p->n - p->n * c + c), f);
}

static inline void FN(k_fkv)(const kp *p, const geo *g, R f[3])
{
    R c = FN(pos)(g->ch);
    R a = K(0.786) * p->n;
    FN(lobe_out)(p, FN(pos)(a * c * c + (K(1) - a) * c), f);
}

static inline void FN(k_fkub)(const kp *p, const geo *g, R f[3])
{
    R c = FN(pos)(g->ch);
    R t = K(1) - c; /* the cubic written about c = 1 (fkub_table.c) */
    R v = K(1) + t * (p->fkub[0] + t * (p->fkub[1] + t * p->fkub[2]));
    /* zero below the zone, then clamp to [0, 1]: the same values as clamping inside the
     * zone (NaN -> 0), written as selects with a zero arm, which vectorise to compare+and */
    v = c >= p->fkub_x0 ? v : K(0);
    v = v > K(0) ? v : K(0);
    v = v < K(1) ? v : K(1);
    FN(lobe_out)(p, v, f);
}
