/* k_empirical.h - the empirical specular lobes: Phong, Blinn-Phong (Eq. 4) and the
 * approximations of Blinn-Phong of the paper's Table 1, setup beside kernel (both
 * precisions via kernel.h). Each returns ks * lobe, an unnormalised lobe used as a BRDF
 * (abrdf.h, direction convention).
 *
 * Phong: B. T. Phong, "Illumination for computer generated pictures", CACM 18(6), 1975:
 *   cos(gamma)^n, gamma = angle(R, V).
 * Blinn-Phong (Eq. 4): J. F. Blinn, "Models of light reflection for computer synthesized
 *   pictures", SIGGRAPH 1977: cos(theta_h)^n.
 * f2, f4, f8, f16 (Table 1): ((n/m)(c - 1) + 1)^m, the limit form of (1 + x/m)^m, usually
 *   attributed to Lyon 1993 (Apple TR 43); lobe_fm in k_terms.h.
 * fs (Table 1): C. Schlick, "A fast alternative to Phong's specular model", Graphics Gems IV,
 *   1994: c / (n - n c + c).
 * fkv (Table 1): the paper's quadratic 0.786 n c^2 + (1 - 0.786 n) c, clamped at 0 because
 *   it is negative on (0, 1 - 1/(0.786 n)) (MODELS.md B3).
 * fkub (Table 1): a cubic A c^3 + B c^2 + C c (Romanyuk et al., IAPGOS 13(3), 2023) whose
 *   coefficients the paper does not give; the project fits them (tools/gen/fit_fkub.c, table
 *   in fkub_table.c), evaluates the same cubic written about c = 1 (stable in float for
 *   large n), zeroes it below the fitted zone start x0 and clamps it to [0, 1].
 * All lobes take c = N.H (they approximate Blinn-Phong), Phong takes c = R.V. Every model
 * here but fkub has nothing to precompute: its setup is kp_base (kernel.h). */
#include "kernel.h"
#include "k_terms.h"

#ifndef ABRDF_K_EMPIRICAL_H
#define ABRDF_K_EMPIRICAL_H

static inline abrdf__real k_phong_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return pow_pos(g->rv, p->n);
}
static inline void k_phong(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_phong_lobe(p, g), f);
}

static inline abrdf__real k_blinn_phong_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return pow_ch(g, p->n); /* Eq. 4 */
}
static inline void k_blinn_phong(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_blinn_phong_lobe(p, g), f);
}

static inline abrdf__real k_f2_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return lobe_fm(p->n, g->ch, 1);
}
static inline void k_f2(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_f2_lobe(p, g), f);
}
static inline abrdf__real k_f4_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return lobe_fm(p->n, g->ch, 2);
}
static inline void k_f4(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_f4_lobe(p, g), f);
}
static inline abrdf__real k_f8_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return lobe_fm(p->n, g->ch, 3);
}
static inline void k_f8(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_f8_lobe(p, g), f);
}
static inline abrdf__real k_f16_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return lobe_fm(p->n, g->ch, 4);
}
static inline void k_f16(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_f16_lobe(p, g), f);
}

static inline abrdf__real k_fs_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    abrdf__real c = pos(g->ch);
    /* n(1 - c) + c >= min(1, n) c-independent lower bound; 0 only at n = 0, c = 0. */
    return safe_div(c, p->n - p->n * c + c);
}
static inline void k_fs(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_fs_lobe(p, g), f);
}

static inline abrdf__real k_fkv_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    abrdf__real c = pos(g->ch);
    abrdf__real a = ABRDF__K(0.786) * p->n;
    return pos(a * c * c + (ABRDF__K(1) - a) * c);
}
static inline void k_fkv(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_fkv_lobe(p, g), f);
}

/* The fitted cubic for this n (fkub_table.c) and the start of its zone. */
static inline void k_fkub_setup(abrdf__kp *k, const abrdf_params *p)
{
    kp_base(k, p);
    double abd[3], x0;
    abrdf__fkub_coeffs(p->n, abd, &x0);
    for (int c = 0; c < 3; ++c) k->fkub[c] = (abrdf__real)abd[c];
    k->fkub_x0 = (abrdf__real)x0;
}

static inline abrdf__real k_fkub_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    abrdf__real c = pos(g->ch);
    abrdf__real t = ABRDF__K(1) - c; /* the cubic written about c = 1 (fkub_table.c) */
    abrdf__real v = ABRDF__K(1) + t * (p->fkub[0] + t * (p->fkub[1] + t * p->fkub[2]));
    /* zero below the zone, then clamp to [0, 1]: the same values as clamping inside the
     * zone (NaN -> 0), written as selects with a zero arm, which vectorise to compare+and */
    v = c >= p->fkub_x0 ? v : ABRDF__K(0);
    v = v > ABRDF__K(0) ? v : ABRDF__K(0);
    return v < ABRDF__K(1) ? v : ABRDF__K(1);
}
static inline void k_fkub(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_fkub_lobe(p, g), f);
}

#endif /* ABRDF_K_EMPIRICAL_H */
