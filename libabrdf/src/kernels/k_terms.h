/* k_terms.h - the split terms the closed-form models are composed of: Fresnel F,
 * distributions D, shadowing G and visibility V, the Table-1 lobe and the Table-5
 * normalisations. Both precisions via kernel.h; the models are in the family headers.
 *
 * F: C. Schlick, "An inexpensive BRDF model for physically-based rendering", Computer
 *   Graphics Forum 13(3), 1994 (Eq. 8).
 * D: GGX / Trowbridge-Reitz (Eq. 6) and its anisotropic form (Eq. 7), B. Walter et al.,
 *   "Microfacet models for refraction through rough surfaces", EGSR 2007; the normalised
 *   Beckmann D (P. Beckmann, A. Spizzichino 1963); Disney's GTR1 (B. Burley, "Physically-
 *   Based Shading at Disney", SIGGRAPH 2012 course notes, App. B); the inverted-Gaussian
 *   velvet D (M. Ashikhmin, S. Premoze, "Distribution-based BRDFs", 2007 tech. report).
 * G, V: separable Smith for GGX (Eq. 9), computed as the visibility
 *   G1(u)/(2 cos_u) = 1/(cos_u + sqrt(alpha^2 + (1 - alpha^2) cos_u^2)), so no cosine is
 *   divided by at grazing; Cook-Torrance's V-cavity G (R. L. Cook, K. E. Torrance, ACM TOG
 *   1(1), 1982); Neubelt-Pettineo's smooth visibility (SIGGRAPH 2013 course notes).
 * Lobes: the Table-1 power form ((n/m)(c - 1) + 1)^m (after Lyon 1993, Apple TR 43) and the
 *   Table-5 normalisation constants, cited where each is defined. */
#include "kernel.h"

#ifndef ABRDF_K_TERMS_H
#define ABRDF_K_TERMS_H

/* ---- Fresnel ------------------------------------------------------------------------ */

/* (1 - cos_d)^5, cos_d clamped to [0, 1]: Schlick's weight, in [0, 1] (NaN -> 1). */
static inline abrdf__real schlick_m5(abrdf__real cos_d)
{
    abrdf__real m = ABRDF__K(1) - clampr(cos_d, ABRDF__K(0), ABRDF__K(1));
    abrdf__real m2 = m * m;
    return m2 * m2 * m;
}

/* Schlick's Fresnel, Eq. 8: F0 + (1 - F0)(1 - cos_d)^5, cos_d clamped to [0, 1]. */
static inline abrdf__real f_schlick(abrdf__real f0, abrdf__real cos_d)
{
    return f0 + (ABRDF__K(1) - f0) * schlick_m5(cos_d); /* Eq. 8 */
}

/* ---- distributions D ------------------------------------------------------------------ */

/* GGX / Trowbridge-Reitz D, Eq. 6, with sin^2 from |N x H|^2 instead of 1 - cos^2. */
static inline abrdf__real d_ggx(abrdf__real ch, abrdf__real sh2, abrdf__real ag)
{
    abrdf__real a2 = ag * ag;
    abrdf__real t = sh2 + a2 * ch * ch;               /* = 1 + (a2 - 1) ch^2 */
    return safe_div(a2, ABRDF__K(ABRDF__PI) * t * t); /* Eq. 6 */
}

/* Anisotropic GGX D, Eq. 7; H in the local frame (x along T, y along B). */
static inline abrdf__real d_ggx_aniso(abrdf__real hx, abrdf__real hy, abrdf__real hz,
                                      abrdf__real ax, abrdf__real ay)
{
    abrdf__real u = hx / ax, v = hy / ay;
    abrdf__real t = u * u + v * v + hz * hz;
    return safe_div(ABRDF__K(1), ABRDF__K(ABRDF__PI) * ax * ay * t * t); /* Eq. 7 */
}

/* Normalised Beckmann D: exp(-tan^2/alpha^2) / (pi alpha^2 cos^4). */
static inline abrdf__real d_beckmann(abrdf__real ch, abrdf__real sh2, abrdf__real ag)
{
    if (!(ch > ABRDF__K(0))) return ABRDF__K(0);
    abrdf__real c2 = ch * ch;
    return safe_div(exp_r(-sh2 / (c2 * ag * ag)), ABRDF__K(ABRDF__PI) * ag * ag * c2 * c2);
}

/* Disney clearcoat GTR1 (Burley 2012, App. B); alpha not squared. */
static inline abrdf__real d_gtr1(abrdf__real ch, abrdf__real sh2, abrdf__real alpha)
{
    abrdf__real a2 = alpha * alpha;
    if (ABRDF__K(1) - a2 < ABRDF__K(ABRDF__GTR1_ALPHA_ONE)) return ABRDF__K(ABRDF__INV_PI);
    return (a2 - ABRDF__K(1)) / (ABRDF__K(ABRDF__PI) * log(a2) * (sh2 + a2 * ch * ch));
}

/* Ashikhmin-Premoze inverted-Gaussian velvet D with offset 1 and amplitude k_amp:
 *   [1 + k_amp exp(-cot^2(theta_h)/alpha^2) / sin^4(theta_h)] norm,
 * norm = 1/(pi (1 + k_amp alpha^2)) from the setup (k_neubelt_pettineo_setup). */
static inline abrdf__real d_velvet(abrdf__real ch, abrdf__real sh2, abrdf__real alpha,
                                   abrdf__real k_amp, abrdf__real norm)
{
    /* no branch, so that batch loops vectorise: the term is computed with a sin^2 that is
     * never below the cut (1 where it is) and then selected; the same values as testing first */
    int on = sh2 > ABRDF__K(ABRDF__VELVET_SIN2_MIN);
    abrdf__real s = on ? sh2 : ABRDF__K(1);
    abrdf__real g = exp_r(-(ch * ch) / (s * alpha * alpha)) / (s * s);
    g = on ? g : ABRDF__K(0);
    g = ch > ABRDF__K(0) ? g : ABRDF__K(0);
    return norm * (ABRDF__K(1) + k_amp * g); /* Eq. 10 (D) */
}

/* ---- shadowing G and visibility V = G / (4 cos_i cos_o) --------------------------------- */

/* Half of Smith's separable G1 for GGX over the cosine, Eq. 9:
 * G1(u) / (2 cos_u) = 1 / (cos_u + sqrt(alpha^2 + (1 - alpha^2) cos_u^2)). */
static inline abrdf__real v1_smith_ggx(abrdf__real cu, abrdf__real ag)
{
    abrdf__real a2 = ag * ag;
    return ABRDF__K(1) / (cu + sqrt(a2 + (ABRDF__K(1) - a2) * cu * cu));
}

/* Smith G1 for GGX itself (Eq. 9), for callers that want G rather than visibility. */
static inline abrdf__real g1_smith_ggx(abrdf__real cu, abrdf__real ag)
{
    abrdf__real c = pos(cu);
    return ABRDF__K(2) * c * v1_smith_ggx(c, ag); /* Eq. 9 */
}

/* Anisotropic version: sqrt((u_x a_x)^2 + (u_y a_y)^2 + u_z^2). */
static inline abrdf__real v1_smith_ggx_aniso(abrdf__real ux, abrdf__real uy, abrdf__real uz,
                                             abrdf__real ax, abrdf__real ay)
{
    abrdf__real a = ux * ax, b = uy * ay;
    return ABRDF__K(1) / (uz + sqrt(a * a + b * b + uz * uz));
}

/* Cook-Torrance V-cavity G = min(1, 2 NH NV / VH, 2 NH NL / VH). */
static inline abrdf__real g_cook_torrance(const abrdf__geo *g)
{
    abrdf__real k = safe_div(ABRDF__K(2) * g->ch, g->cd);
    abrdf__real gi = k * g->ci, go = k * g->co;
    abrdf__real m = gi < go ? gi : go;
    return m < ABRDF__K(1) ? pos(m) : ABRDF__K(1);
}

/* Neubelt-Pettineo's "smooth" visibility 1/(4 (cos_i + cos_o - cos_i cos_o)). */
static inline abrdf__real v_neubelt(abrdf__real ci, abrdf__real co)
{
    return safe_div(ABRDF__K(1), ABRDF__K(4) * (ci + co - ci * co));
}

/* ---- lobes ------------------------------------------------------------------------------ */

/* f = ks * lobe: an unnormalised lobe used as a BRDF (abrdf.h, direction convention). The
 * kernel of a model whose value is ks times one scalar lobe (form LOBE in k_dispatch.h), k_f8
 * say, is lobe_out of its k_f8_lobe, both defined in the family header. The float batch loops
 * call the _lobe function and apply the guards once per pair instead of once per channel
 * (eval_float.c). */
static inline void lobe_out(const abrdf__kp *p, abrdf__real lobe, abrdf__real f[3])
{
    for (int c = 0; c < 3; ++c) f[c] = p->ks[c] * lobe;
}

/* f = ks F_Schlick(F0, cos_d) * lobe, per channel: the kernel of a model whose value is that
 * (form SCHLICK in k_dispatch.h), k_f_ge say, is schlick_out of its k_f_ge_lobe. The float
 * batch loops call the _lobe function, guard it once per pair and write ks F as
 * ks_f0 + ks_f1 (1 - cos_d)^5 (kp_base), which is in [0, ks] for F0 in [0, 1] (eval_float.c). */
static inline void schlick_out(const abrdf__kp *p, const abrdf__geo *g, abrdf__real lobe,
                               abrdf__real f[3])
{
    for (int c = 0; c < 3; ++c) f[c] = p->ks[c] * f_schlick(p->f0[c], g->cd) * lobe;
}

/* ((n/m)(c - 1) + 1)^m with m = 2^k, Table 1: the limit form of (1 + x/m)^m, the base
 * clamped at 0 (the paper's Table 4 note "the point after which the function must be
 * zeroed"), evaluated by k squarings. */
static inline abrdf__real lobe_fm(abrdf__real n, abrdf__real c, int k)
{
    abrdf__real m = (abrdf__real)(1 << k);
    return pow2k((n / m) * (c - ABRDF__K(1)) + ABRDF__K(1), k);
}

/* ---- Table-5 normalisations (the models are in k_energy.h) ----------------------------- */

/* f_phe: E. Lafortune, Y. Willems, "Using the modified Phong reflectance model for
 * physically based rendering", TR CW197, KU Leuven 1994: (n + 2)/(2 pi). */
static inline abrdf__real norm_phe(abrdf__real n)
{
    return (n + ABRDF__K(2)) / ABRDF__K(2 * ABRDF__PI);
}
/* f_be: F. Giesen, "The Blinn-Phong normalization zoo", 2009:
 * (n + 2)(n + 4) / (8 pi (2^(-n/2) + n)). */
static inline abrdf__real norm_be(abrdf__real n)
{
    return (n + ABRDF__K(2)) * (n + ABRDF__K(4)) /
           (ABRDF__K(8 * ABRDF__PI) * (pow(ABRDF__K(2), -n / ABRDF__K(2)) + n));
}
/* f_2e, f_16e: the paper's fitted constants 0.111/n + 0.238(0.481 + n) and
 * (1.063 n + 1)/(2 pi), fits to the exact NDF constant of the lobe. */
static inline abrdf__real norm_2e(abrdf__real n)
{
    return ABRDF__K(0.111) / n + ABRDF__K(0.238) * (ABRDF__K(0.481) + n);
}
static inline abrdf__real norm_16e(abrdf__real n)
{
    return (ABRDF__K(1.063) * n + ABRDF__K(1)) / ABRDF__K(2 * ABRDF__PI);
}
/* f_ge: Y. Gotanda, "Beyond a simple physically based Blinn-Phong model in real-time",
 * SIGGRAPH 2012 course, eq. 1 with the closed-form constant (MODELS.md B4):
 * (n + 2) / (4 pi (2 - 2^(-n/2))). */
static inline abrdf__real norm_ge(abrdf__real n)
{
    return (n + ABRDF__K(2)) /
           (ABRDF__K(4 * ABRDF__PI) * (ABRDF__K(2) - pow(ABRDF__K(2), -n / ABRDF__K(2))));
}

#endif /* ABRDF_K_TERMS_H */
