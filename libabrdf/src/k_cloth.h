/* k_cloth.h - cloth models (both precisions via kernel.h).
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
 *   bracket is symmetric in L and V). */

/* Ashikhmin-Premoze inverted-Gaussian velvet D with offset 1 and amplitude k_amp; the
 * normalisation norm = 1/(pi (1 + k_amp alpha^2)) comes from kp. */
static inline R FN(d_velvet)(R ch, R sh2, R alpha, R k_amp, R norm)
{
    R g = K(0);
    if (sh2 > K(ABRDF__VELVET_SIN2_MIN) && ch > K(0))
        g = exp(-(ch * ch) / (sh2 * alpha * alpha)) / (sh2 * sh2);
    return norm * (K(1) + k_amp * g); /* Eq. 10 (D) */
}

/* Neubelt-Pettineo's "smooth" visibility 1/(4 (cos_i + cos_o - cos_i cos_o)). */
static inline R FN(v_neubelt)(R ci, R co)
{
    return FN(safe_div)(K(1), K(4) * (ci + co - ci * co));
}

static inline void FN(k_neubelt_pettineo)(const kp *p, const geo *g, R f[3])
{
    R dv = FN(d_velvet)(g->ch, g->sh2, p->ag, p->k_amp, p->norm) * FN(v_neubelt)(g->ci, g->co);
    for (int c = 0; c < 3; ++c) {
        R F = FN(f_schlick)(p->f0[c], g->cd);
        f[c] = (K(1) - F) * p->kd[c] * K(ABRDF__INV_PI) + p->ks[c] * F * dv; /* Eq. 10 */
    }
}

static inline void FN(k_kajiya_kay)(const kp *p, const geo *g, R f[3])
{
    R tl = FN(clampr)(g->ix, K(-1), K(1)), tv = FN(clampr)(g->ox, K(-1), K(1));
    /* sin(T, w) = |T x w| = sqrt(w_y^2 + w_z^2) for T = +x: unlike sqrt(1 - (T.w)^2) it does
     * not cancel when w is close to the fibre (float lost 1% of sin there). */
    R sl = FN(clampr)(sqrt(g->iy * g->iy + g->iz * g->iz), K(0), K(1));
    R sv = FN(clampr)(sqrt(g->oy * g->oy + g->oz * g->oz), K(0), K(1));
    R spec = FN(pow_pos)(sl * sv - tl * tv, p->n); /* cosine to the mirror cone */
    for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * sl + p->ks[c] * spec; /* Eq. 11 */
}

#define ABRDF__CLOTH_MODELS(X)                   \
    X(ABRDF_NEUBELT_PETTINEO, k_neubelt_pettineo) \
    X(ABRDF_KAJIYA_KAY, k_kajiya_kay)

static inline void FN(kp_make_cloth)(kp *k, abrdf_model model, const abrdf_params *p)
{
    if (model == ABRDF_NEUBELT_PETTINEO) {
        double a = (double)k->ag;
        k->norm = (R)(1.0 / (ABRDF__PI * (1.0 + p->k_amp * a * a))); /* Ashikhmin-Premoze */
    }
}
