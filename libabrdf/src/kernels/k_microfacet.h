/* k_microfacet.h - the microfacet models, setup beside kernel (both precisions via
 * kernel.h), composed of the D, G and F of k_terms.h in the Walter et al. 2007
 * normalisation f = F D G / (4 cos_i cos_o) (Eq. 5), G taken as the visibility
 * V = G / (4 cos_i cos_o) so no cosine is divided by at grazing.
 *
 * Cook-Torrance (Eq. 5): R. L. Cook, K. E. Torrance, "A reflectance model for computer
 *   graphics", ACM TOG 1(1), 1982, with the normalised Beckmann D (P. Beckmann,
 *   A. Spizzichino 1963) and the V-cavity G = min(1, 2 NH NV / VH, 2 NH NL / VH). The 1982
 *   paper's pi in the denominator and unnormalised D combine to 4x this form (MODELS.md B5.1).
 * Disney specular (Eqs. 5, 6, 8, 9): B. Burley, "Physically-Based Shading at Disney",
 *   SIGGRAPH 2012 course notes: GGX D (B. Walter et al., "Microfacet models for refraction
 *   through rough surfaces", EGSR 2007) with alpha_g = r^2, Schlick F, separable Smith G
 *   with the same alpha_g as D (the post-2017 reference code; MODELS.md B5.4).
 * Anisotropic (Eq. 7): aspect = sqrt(1 - 0.9 anisotropic), alpha_x = r^2 / aspect,
 *   alpha_y = r^2 aspect (Burley 2012), both >= ABRDF__ALPHA_G_MIN.
 * Disney clearcoat: Burley 2012, 0.25 ks F(0.04) D_GTR1(alpha) G(0.25) / (4 cos_i cos_o),
 *   alpha = mix(0.1, 0.001, clearcoat_gloss), alpha not squared. ks is the clearcoat amount. */
#include "kernel.h"
#include "k_terms.h"

#ifndef ABRDF_K_MICROFACET_H
#define ABRDF_K_MICROFACET_H

/* The setup of cook_torrance and disney_specular: alpha_g = r^2, floored. */
static inline void k_microfacet_setup(abrdf__kp *k, const abrdf_params *p)
{
    kp_base(k, p);
    k->ag = kp_alpha(p->r * p->r);
}

static inline abrdf__real k_cook_torrance_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    abrdf__real dg = d_beckmann(g->ch, g->sh2, p->ag) * g_cook_torrance(g);
    return safe_div(dg, ABRDF__K(4) * g->ci * g->co); /* Eq. 5 */
}
static inline void k_cook_torrance(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    schlick_out(p, g, k_cook_torrance_lobe(p, g), f);
}

/* D V_i V_o (Eq. 5 with Eqs. 6 and 9) over one denominator: with h = wi + wo unnormalised,
 * GGX's t = sin^2 + a2 cos^2 of theta_h is (hxy2 + a2 hz2) / |h|^2, so
 *   D V_i V_o = a2 |h|^4 / (pi (hxy2 + a2 hz2)^2 (c_i + s_i) (c_o + s_o)),
 * s_u = sqrt(a2 + (1 - a2) c_u^2) as in v1_smith_ggx: one division and no normalised H
 * where the three terms took four (a per-sample call's cost is its divisions and square
 * roots; docs/BENCHMARKS.md, "The per-sample call"). vi vo is one product, so swapping wi
 * and wo gives the same bits. Both sides are scaled by 2^100 (exact): near the mirror at
 * grazing angles with a2 at its floor, the denominator goes as a2^2 cos^6 and would underflow
 * in float (to 0, and safe_div to f = 0, from cos ~ 1e-4 at r = 1e-3; sooner with flush to
 * zero) while the value is large and finite; scaled, neither side leaves float's range (the
 * numerator stays below 2^100 16, the denominator below pi 2^100 64). */
#define ABRDF__GGX_SCALE 0x1p100
static inline abrdf__real k_disney_specular_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    abrdf__real a2 = p->ag * p->ag, b2 = ABRDF__K(1) - a2;
    abrdf__real t = g->hxy2 + a2 * g->hz2;
    abrdf__real vi = g->ci + sqrt(a2 + b2 * g->ci * g->ci);
    abrdf__real vo = g->co + sqrt(a2 + b2 * g->co * g->co);
    abrdf__real num = a2 * ABRDF__K(ABRDF__GGX_SCALE) * g->hl2 * g->hl2;
    return safe_div(num, ABRDF__K(ABRDF__PI * ABRDF__GGX_SCALE) * t * t * (vi * vo));
}
static inline void k_disney_specular(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    schlick_out(p, g, k_disney_specular_lobe(p, g), f);
}

/* alpha_x = r^2 / aspect, alpha_y = r^2 aspect (Eq. 7), each floored. */
static inline void k_disney_specular_aniso_setup(abrdf__kp *k, const abrdf_params *p)
{
    kp_base(k, p);
    double ag = p->r * p->r;
    double aspect = sqrt(1.0 - 0.9 * p->anisotropic);
    k->ax = kp_alpha(ag / aspect);
    k->ay = kp_alpha(ag * aspect);
}

static inline abrdf__real k_disney_specular_aniso_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    /* Eq. 5 with Eqs. 7 and 9; the two visibility terms multiplied first, so swapping wi and
     * wo gives the same bits */
    return d_ggx_aniso(g->hx, g->hy, g->hz, p->ax, p->ay) *
           (v1_smith_ggx_aniso(g->ix, g->iy, g->ci, p->ax, p->ay) *
            v1_smith_ggx_aniso(g->ox, g->oy, g->co, p->ax, p->ay));
}
static inline void k_disney_specular_aniso(const abrdf__kp *p, const abrdf__geo *g,
                                           abrdf__real f[3])
{
    schlick_out(p, g, k_disney_specular_aniso_lobe(p, g), f);
}

/* GTR1 alpha = mix(0.1, 0.001, clearcoat_gloss). */
static inline void k_disney_clearcoat_setup(abrdf__kp *k, const abrdf_params *p)
{
    kp_base(k, p);
    k->cc_alpha = (abrdf__real)(0.1 + (0.001 - 0.1) * p->clearcoat_gloss);
}

static inline void k_disney_clearcoat(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    abrdf__real dv = d_gtr1(g->ch, g->sh2, p->cc_alpha) *
                     (v1_smith_ggx(g->ci, ABRDF__K(0.25)) * v1_smith_ggx(g->co, ABRDF__K(0.25)));
    abrdf__real v = ABRDF__K(0.25) * f_schlick(ABRDF__K(0.04), g->cd) * dv;
    for (int c = 0; c < 3; ++c) f[c] = p->ks[c] * v;
}

#endif /* ABRDF_K_MICROFACET_H */
