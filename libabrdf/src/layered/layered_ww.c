/* layered_ww.c - Weidlich-Wilkie layered model (Eq. 15), an arbitrary stack of rough
 * interfaces over a Lambertian base.
 *
 * A. Weidlich, A. Wilkie, "Arbitrarily layered micro-facet surfaces", GRAPHITE 2007; the
 * reading of I. Kabel, "Rendering layered materials: Weidlich-Wilkie layered model" (2018)
 * for the points the paper leaves open (MODELS.md B8.1). Per interface k (top to bottom):
 *   f_k(L, V) = f_top,k(L, V) + T12 f_{k+1}(L', V') a t                       (Eq. 15)
 *   f_top,k   = F(L.H) D_GGX(H) G(L, V) / (4 cos_i cos_o), exact Fresnel of eta_k + i kappa_k
 *   T12 = T21 = 1 - F(L.H)      (dielectric Fresnel transmission, in and out)
 *   L', V'    = L and V refracted by Snell's law at the top microfacet normal H (the
 *               original's single refraction point; Kabel suggests N instead). Because
 *               L.H = V.H, the entry and exit transmissions are equal and the model is
 *               reciprocal; the paper's T12 / T21 naming ambiguity (B8.1) is moot.
 *   a = exp(-sigma_a d (1/|N.L'| + 1/|N.V'|))  (absorption in the medium below)
 *   t = (1 - G) + T21 G, G = G1(L) G1(V) the interface's separable Smith term (as printed;
 *       the paper does not explain it).
 * Recursion: f_{k+1} is the same formula for the next interface in the medium below, with
 * the refracted directions. An interface with kappa > 0 is a conductor: opaque, it ends the
 * stack. Below the last dielectric interface lies a Lambertian base kd/pi.
 * Total internal reflection: refraction into a less dense layer (eta < 1) beyond the
 * critical angle transmits nothing (F = 1 and the refraction fails), so that path is 0.
 * Not done, as in the original: the solid-angle compression (the 1/eta^2 radiance factor
 * and the cos'/cos Jacobian), multiple inter-reflection between layers. With refraction at
 * H, L' + V' stays parallel to H, so a glossy base keeps its half-vector lobe (no solid-
 * angle gain). The model is not energy-conserving: at grazing incidence the coat's lobe and
 * the transmitted base overlap (albedo up to 1.15 over a white Lambert base, measured in
 * docs/MODELS.md, "Weidlich-Wilkie"); elsewhere it loses the inter-reflected light. */
#include <math.h>

#include "layered.h"
#include "layered_optics.h"

static void ww_stack(const abrdf_params *p, int k, const double L[3], const double V[3],
                     double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    double ci = L[2], co = V[2];
    if (!(ci > 0.0 && co > 0.0)) return;
    if (k >= p->layer_count || k >= ABRDF_MAX_LAYERS) {
        for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * ABRDF__INV_PI; /* Lambert base, Eq. 1 */
        return;
    }
    const abrdf_layer *ly = &p->layers[k];
    double h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
    double len2 = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
    if (!(len2 > ABRDF__HALF_LEN2_MIN)) return;
    double inv = 1.0 / sqrt(len2);
    for (int c = 0; c < 3; ++c) h[c] *= inv;
    double cd = L[0] * h[0] + L[1] * h[1] + L[2] * h[2];
    double ag = fmax(ly->r * ly->r, ABRDF__ALPHA_G_MIN);
    double F = abrdf__fresnel_exact(cd, ly->eta, ly->kappa);
    double vv = abrdf__lo_v1(ci, ag) * abrdf__lo_v1(co, ag);
    double top = F * abrdf__lo_d_ggx(h[2], h[0] * h[0] + h[1] * h[1], ag) * vv;
    for (int c = 0; c < 3; ++c) f[c] = top;
    if (ly->kappa > 0.0) return; /* conductor: nothing below is seen */
    double T = 1.0 - F;
    double Li[3], Vi[3];
    if (!(T > 0.0) || !abrdf__lo_refract(L, h, ly->eta, Li) ||
        !abrdf__lo_refract(V, h, ly->eta, Vi))
        return;                                /* total internal reflection */
    if (!(Li[2] > 0.0 && Vi[2] > 0.0)) return; /* refracted below the base's horizon */
    double G = 4.0 * ci * co * vv;
    double t = (1.0 - G) + T * G;
    double sub[3];
    ww_stack(p, k + 1, Li, Vi, sub);
    for (int c = 0; c < 3; ++c) {
        double sd = ly->sigma_a[c] * ly->depth;
        double a = sd > 0.0 ? exp(-sd * (1.0 / Li[2] + 1.0 / Vi[2])) : 1.0;
        f[c] += T * sub[c] * a * t; /* Eq. 15 */
    }
}

void abrdf__eval_weidlich_wilkie(const abrdf_params *p, const double wi[3], const double wo[3],
                                 double f[3])
{
    ww_stack(p, 0, wi, wo, f);
}
