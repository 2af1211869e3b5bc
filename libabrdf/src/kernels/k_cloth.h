/* k_cloth.h - the cloth models, setup beside kernel (both precisions via kernel.h).
 *
 * Neubelt-Pettineo (Eq. 10): D. Neubelt, M. Pettineo, "Crafting a Next-Gen Material
 *   Pipeline for The Order: 1886", SIGGRAPH 2013 course notes, built on the inverted-
 *   Gaussian velvet distribution of M. Ashikhmin, S. Premoze, "Distribution-based BRDFs",
 *   2007 tech. report (MODELS.md B6.1):
 *     D = [1 + k_amp exp(-cot^2(theta_h)/alpha^2) / sin^4(theta_h)] / (pi (1 + k_amp alpha^2))
 *     f = (1 - F) kd/pi + ks F D / (4 (cos_i + cos_o - cos_i cos_o))
 *   The paper prints (1 - N.m)^2 in the last denominator; Ashikhmin-Premoze have
 *   sin^4 = (1 - (N.m)^2)^2, which is what makes D integrate to 1 (followed here).
 *   alpha: the width of the inverted Gaussian is the microfacet roughness alpha_g = r^2 of
 *   the library's single convention (as Filament, which passes perceptual roughness
 *   squared); F is Schlick's (Eq. 8) at L.H with f0; ks (default 1) scales the sheen lobe.
 *   Reciprocal (F at L.H = V.H, symmetric denominator); not energy-conserving in general.
 *   D and V are d_velvet and v_neubelt in k_terms.h.
 *
 * Kajiya-Kay (Eq. 11): J. T. Kajiya, T. L. Kay, "Rendering fur with three dimensional
 *   textures", SIGGRAPH 1989, in the sign-correct form for L pointing toward the light
 *   (MODELS.md B6.4; the paper's garbled print, cos.cos + sin.sin, holds only for L along
 *   the light's propagation and misplaces the highlight):
 *     f = kd sin(T,L) + ks [max(0, sin(T,L) sin(T,V) - (T.L)(T.V))]^n
 *   T is the local +x axis (the frame's tangent). Kajiya-Kay's terms are radiance-like
 *   "intensity" lobes; following the library's convention for the raw empirical lobes
 *   (abrdf.h), they are returned as f_r unchanged, so shading multiplies them by N.L.
 *   A caller wanting the fur convention (no N.L) divides by N.L. Not normalised, so not
 *   energy-conserving; not reciprocal (the diffuse term depends on L only; the specular
 *   bracket is symmetric in L and V). Nothing to precompute: its setup is kp_base. */
#include "kernel.h"
#include "k_terms.h"

#ifndef ABRDF_K_CLOTH_H
#define ABRDF_K_CLOTH_H

/* alpha_g = r^2 and the velvet normalisation 1/(pi (1 + k_amp alpha_g^2)) (Ashikhmin-
 * Premoze), the latter from alpha_g as the kernel holds it. */
static inline void k_neubelt_pettineo_setup(abrdf__kp *k, const abrdf_params *p)
{
    kp_base(k, p);
    k->ag = kp_alpha(p->r * p->r);
    k->k_amp = (abrdf__real)p->k_amp;
    double a = (double)k->ag;
    k->norm = (abrdf__real)(1.0 / (ABRDF__PI * (1.0 + p->k_amp * a * a)));
}

static inline void k_neubelt_pettineo(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    abrdf__real dv = d_velvet(g->ch, g->sh2, p->ag, p->k_amp, p->norm) * v_neubelt(g->ci, g->co);
    for (int c = 0; c < 3; ++c) {
        abrdf__real F = f_schlick(p->f0[c], g->cd);
        f[c] =
            (ABRDF__K(1) - F) * p->kd[c] * ABRDF__K(ABRDF__INV_PI) + p->ks[c] * F * dv; /* Eq. 10 */
    }
}

static inline void k_kajiya_kay(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    abrdf__real tl = clampr(g->ix, ABRDF__K(-1), ABRDF__K(1));
    abrdf__real tv = clampr(g->ox, ABRDF__K(-1), ABRDF__K(1));
    /* sin(T, w) = |T x w| = sqrt(w_y^2 + w_z^2) for T = +x: unlike sqrt(1 - (T.w)^2) it does
     * not cancel when w is close to the fibre (float lost 1% of sin there). */
    const abrdf__real zero = ABRDF__K(0), one = ABRDF__K(1);
    abrdf__real sl = clampr(sqrt(g->iy * g->iy + g->iz * g->iz), zero, one);
    abrdf__real sv = clampr(sqrt(g->oy * g->oy + g->oz * g->oz), zero, one);
    abrdf__real spec = pow_pos(sl * sv - tl * tv, p->n); /* cosine to the mirror cone */
    for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * sl + p->ks[c] * spec; /* Eq. 11 */
}

#endif /* ABRDF_K_CLOTH_H */
