/* k_diffuse.h - diffuse models (one family, both precisions via kernel.h).
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
 *   s = L.V - (N.L)(N.V) (MODELS.md B2.4). */

static inline void FN(k_lambert)(const kp *p, const geo *g, R f[3])
{
    (void)g;
    for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * K(ABRDF__INV_PI); /* Eq. 1 */
}

static inline void FN(k_lambert_fresnel)(const kp *p, const geo *g, R f[3])
{
    for (int c = 0; c < 3; ++c)
        f[c] = p->kd[c] * K(ABRDF__INV_PI) * (K(1) - FN(f_schlick)(p->f0[c], g->cd)); /* Eq. 2 */
}

static inline void FN(k_disney_diffuse)(const kp *p, const geo *g, R f[3])
{
    R fd90 = K(0.5) + K(2) * p->r * g->cd * g->cd;
    R mi = K(1) - g->ci, mo = K(1) - g->co;
    R mi5 = mi * mi * mi * mi * mi, mo5 = mo * mo * mo * mo * mo;
    R s = (K(1) + (fd90 - K(1)) * mi5) * (K(1) + (fd90 - K(1)) * mo5); /* Eq. 3 */
    for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * K(ABRDF__INV_PI) * FN(pos)(s);
}

static inline void FN(k_oren_nayar)(const kp *p, const geo *g, R f[3])
{
    R s = g->ix * g->ox + g->iy * g->oy + g->iz * g->oz - g->ci * g->co;
    R t = g->ci > g->co ? g->ci : g->co;
    R term = p->on_a + p->on_b * FN(safe_div)(FN(pos)(s), t);
    for (int c = 0; c < 3; ++c) f[c] = p->kd[c] * K(ABRDF__INV_PI) * term;
}
