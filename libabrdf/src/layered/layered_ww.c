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

void abrdf__ww_setup(const abrdf_params *p, abrdf__ww *w)
{
    w->count = p->layer_count < ABRDF_MAX_LAYERS ? p->layer_count : ABRDF_MAX_LAYERS;
    for (int k = 0; k < ABRDF_MAX_LAYERS; ++k) {
        const abrdf_layer *ly = &p->layers[k];
        double ag = ly->r * ly->r;
        w->ag[k] = ag > ABRDF__ALPHA_G_MIN ? ag : ABRDF__ALPHA_G_MIN;
        w->inv_eta[k] = 1.0 / ly->eta;
        for (int c = 0; c < 3; ++c) w->sd[k][c] = ly->sigma_a[c] * ly->depth;
        w->grey[k] = w->sd[k][0] == w->sd[k][1] && w->sd[k][0] == w->sd[k][2];
    }
    for (int c = 0; c < 3; ++c) w->base[c] = p->kd[c] * ABRDF__INV_PI; /* Lambert base, Eq. 1 */
}

/* Eq. 15 from the top down: f = top_0 + W_1 (top_1 + W_2 (... + base)), each interface's
 * weight W = T a t taken into the product of those above it. Refraction at H keeps H the
 * half vector of every pair below (L' + V' = 2 cos_t H, cos_t the refracted cosine, which is
 * L'.H = V'.H), so H, D's arguments and the next incidence cosine need no renormalisation:
 * only the z components of L' and V' are followed. */
void abrdf__eval_weidlich_wilkie(const abrdf__ww *w, const abrdf_params *p, const double wi[3],
                                 const double wo[3], double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    double ci = wi[2], co = wo[2];
    if (!(ci > 0.0 && co > 0.0)) return;
    double h[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double len2 = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
    if (!(len2 > ABRDF__HALF_LEN2_MIN)) return;
    double inv = 1.0 / sqrt(len2);
    for (int c = 0; c < 3; ++c) h[c] *= inv;
    double cd = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2], sh2 = h[0] * h[0] + h[1] * h[1];
    double wt[3] = {1.0, 1.0, 1.0}; /* the product of the weights W above this interface */
    for (int k = 0; k < w->count; ++k) {
        const abrdf_layer *ly = &p->layers[k];
        double ag = w->ag[k];
        double F = abrdf__fresnel_exact(cd, ly->eta, ly->kappa);
        double vv = abrdf__lo_v1(ci, ag) * abrdf__lo_v1(co, ag);
        double top = F * abrdf__lo_d_ggx(h[2], sh2, ag) * vv;
        for (int c = 0; c < 3; ++c) f[c] += wt[c] * top;
        if (ly->kappa > 0.0) return; /* conductor: nothing below is seen */
        double T = 1.0 - F;
        /* abrdf__lo_refract of L and V at H (L.H = V.H = cd) */
        double ie = w->inv_eta[k], s2t = (1.0 - cd * cd) * (ie * ie);
        if (!(T > 0.0 && cd > 0.0 && s2t < 1.0)) return; /* total internal reflection */
        double ct = sqrt(1.0 - s2t), kk = cd * ie - ct;
        double li = ci * ie - kk * h[2], vi = co * ie - kk * h[2];
        if (!(li > 0.0 && vi > 0.0)) return; /* refracted below the base's horizon */
        /* the next interface's half vector L' + V' has length 2 ct */
        if (k + 1 < w->count && !(4.0 * ct * ct > ABRDF__HALF_LEN2_MIN)) return;
        double G = 4.0 * ci * co * vv;
        double t = (1.0 - G) + T * G;
        double path = (li + vi) / (li * vi); /* 1 / li + 1 / vi */
        if (w->grey[k]) {                    /* one exp for the three channels */
            double sd = w->sd[k][0];
            double a = sd > 0.0 ? exp(-sd * path) : 1.0;
            for (int c = 0; c < 3; ++c) wt[c] *= T * a * t;
        } else {
            for (int c = 0; c < 3; ++c) {
                double sd = w->sd[k][c];
                double a = sd > 0.0 ? exp(-sd * path) : 1.0;
                wt[c] *= T * a * t; /* Eq. 15 */
            }
        }
        ci = li;
        co = vi;
        cd = ct;
    }
    for (int c = 0; c < 3; ++c) f[c] += wt[c] * w->base[c];
}
