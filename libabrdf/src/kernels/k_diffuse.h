/* k_diffuse.h - the diffuse models, setup beside kernel (both precisions via kernel.h).
 *
 * Lambert (Eq. 1): J. H. Lambert, Photometria, 1760.
 * Lambert with Fresnel (Eq. 2): the diffuse lobe loses the energy the surface reflects
 *   specularly, f = (kd/pi)(1 - F(H.L)); MODELS.md B2.2. Reciprocal because H.L = H.V.
 * Disney diffuse (Eq. 3): B. Burley, "Physically-Based Shading at Disney", SIGGRAPH 2012
 *   course notes, with the cos^2 correction of the published notes (MODELS.md B2.3):
 *   F_D90 = 0.5 + 2 r (H.L)^2, r the perceptual roughness.
 * Oren-Nayar: M. Oren, S. K. Nayar, "Generalization of Lambert's reflectance model",
 *   SIGGRAPH 1994, the qualitative model (their Eq. 30), written without trigonometry:
 *   max(0, cos phi) sin(alpha) tan(beta) = max(0, s) / max(cos_i, cos_o) with
 *   s = L.V - (N.L)(N.V) (MODELS.md B2.4).
 * Lambert, Lambert with Fresnel and Disney diffuse have nothing to precompute: their setup
 * is kp_base (kernel.h). */
#include "kernel.h"
#include "k_terms.h"

#ifndef ABRDF_K_DIFFUSE_H
#define ABRDF_K_DIFFUSE_H

static inline void k_lambert(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    (void)g;
    for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * ABRDF__K(ABRDF__INV_PI); /* Eq. 1 */
}

static inline void k_lambert_fresnel(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    for (int c = 0; c < 3; ++c)
        f[c] = p->kd[c] * ABRDF__K(ABRDF__INV_PI) *
               (ABRDF__K(1) - f_schlick(p->f0[c], g->cd)); /* Eq. 2 */
}

static inline void k_disney_diffuse(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    /* 2 r cos_d^2 = r |wi + wo|^2 / 2: no square root (cos_d = |wi + wo| / 2); the clamp
     * keeps it <= 2 r (cos_d <= 1) where rounding puts |wi + wo|^2 above 4 */
    abrdf__real cd2 = ABRDF__K(0.25) * g->hl2;
    cd2 = cd2 < ABRDF__K(1) ? cd2 : ABRDF__K(1);
    abrdf__real fd90 = ABRDF__K(0.5) + ABRDF__K(2) * p->r * cd2;
    abrdf__real mi = ABRDF__K(1) - g->ci, mo = ABRDF__K(1) - g->co;
    abrdf__real mi5 = mi * mi * mi * mi * mi, mo5 = mo * mo * mo * mo * mo;
    abrdf__real s = (ABRDF__K(1) + (fd90 - ABRDF__K(1)) * mi5) *
                    (ABRDF__K(1) + (fd90 - ABRDF__K(1)) * mo5); /* Eq. 3 */
    for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * ABRDF__K(ABRDF__INV_PI) * pos(s);
}

/* Oren-Nayar's A and B from the slope deviation sigma, in double. */
static inline void k_oren_nayar_setup(abrdf__kp *k, const abrdf_params *p)
{
    kp_base(k, p);
    double s2 = p->sigma * p->sigma;
    k->on_a = (abrdf__real)(1.0 - 0.5 * s2 / (s2 + 0.33));
    k->on_b = (abrdf__real)(0.45 * s2 / (s2 + 0.09));
}

static inline void k_oren_nayar(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    abrdf__real s = g->ix * g->ox + g->iy * g->oy + g->iz * g->oz - g->ci * g->co;
    abrdf__real t = g->ci > g->co ? g->ci : g->co;
    abrdf__real term = p->on_a + p->on_b * safe_div(pos(s), t);
    for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * ABRDF__K(ABRDF__INV_PI) * term;
}

#endif /* ABRDF_K_DIFFUSE_H */
