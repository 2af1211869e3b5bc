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

#if ABRDF__KERNEL_FLOAT ? !defined(ABRDF_K_DIFFUSE_H_F) : !defined(ABRDF_K_DIFFUSE_H_D)
#if ABRDF__KERNEL_FLOAT
#define ABRDF_K_DIFFUSE_H_F
#else
#define ABRDF_K_DIFFUSE_H_D
#endif

static inline void ABRDF__FN(k_lambert)(const ABRDF__KP *p, const ABRDF__GEO *g, ABRDF__REAL f[3])
{
    (void)g;
    for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * ABRDF__K(ABRDF__INV_PI); /* Eq. 1 */
}

static inline void ABRDF__FN(k_lambert_fresnel)(const ABRDF__KP *p, const ABRDF__GEO *g,
                                                ABRDF__REAL f[3])
{
    for (int c = 0; c < 3; ++c)
        f[c] = p->kd[c] * ABRDF__K(ABRDF__INV_PI) *
               (ABRDF__K(1) - ABRDF__FN(f_schlick)(p->f0[c], g->cd)); /* Eq. 2 */
}

static inline void ABRDF__FN(k_disney_diffuse)(const ABRDF__KP *p, const ABRDF__GEO *g,
                                               ABRDF__REAL f[3])
{
    ABRDF__REAL fd90 = ABRDF__K(0.5) + ABRDF__K(2) * p->r * g->cd * g->cd;
    ABRDF__REAL mi = ABRDF__K(1) - g->ci, mo = ABRDF__K(1) - g->co;
    ABRDF__REAL mi5 = mi * mi * mi * mi * mi, mo5 = mo * mo * mo * mo * mo;
    ABRDF__REAL s = (ABRDF__K(1) + (fd90 - ABRDF__K(1)) * mi5) *
                    (ABRDF__K(1) + (fd90 - ABRDF__K(1)) * mo5); /* Eq. 3 */
    for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * ABRDF__K(ABRDF__INV_PI) * ABRDF__FN(pos)(s);
}

/* Oren-Nayar's A and B from the slope deviation sigma, in double. */
static inline void ABRDF__FN(k_oren_nayar_setup)(ABRDF__KP *k, const abrdf_params *p)
{
    ABRDF__FN(kp_base)(k, p);
    double s2 = p->sigma * p->sigma;
    k->on_a = (ABRDF__REAL)(1.0 - 0.5 * s2 / (s2 + 0.33));
    k->on_b = (ABRDF__REAL)(0.45 * s2 / (s2 + 0.09));
}

static inline void ABRDF__FN(k_oren_nayar)(const ABRDF__KP *p, const ABRDF__GEO *g,
                                           ABRDF__REAL f[3])
{
    ABRDF__REAL s = g->ix * g->ox + g->iy * g->oy + g->iz * g->oz - g->ci * g->co;
    ABRDF__REAL t = g->ci > g->co ? g->ci : g->co;
    ABRDF__REAL term = p->on_a + p->on_b * ABRDF__FN(safe_div)(ABRDF__FN(pos)(s), t);
    for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * ABRDF__K(ABRDF__INV_PI) * term;
}

#endif /* per-precision guard */
