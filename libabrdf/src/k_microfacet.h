/* k_microfacet.h - microfacet models: the split terms D, G, F and the models built from them.
 * All models use the Walter et al. 2007 normalisation f = F D G / (4 cos_i cos_o) (Eq. 5).
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
 *   alpha = mix(0.1, 0.001, clearcoat_gloss), alpha not squared. ks is the clearcoat amount.
 *
 * The visibility form V = G / (4 cos_i cos_o) is computed directly, so no cosine is divided
 * by at grazing: G1(u)/(2 cos_u) = 1/(cos_u + sqrt(alpha^2 + (1 - alpha^2) cos_u^2)). */

/* GGX / Trowbridge-Reitz D, Eq. 6, with sin^2 from |N x H|^2 instead of 1 - cos^2. */
static inline R FN(d_ggx)(R ch, R sh2, R ag)
{
    R a2 = ag * ag;
    R t = sh2 + a2 * ch * ch; /* = 1 + (a2 - 1) ch^2 */
    return FN(safe_div)(a2, K(ABRDF__PI) * t * t); /* Eq. 6 */
}

/* Anisotropic GGX D, Eq. 7; H in the local frame (x along T, y along B). */
static inline R FN(d_ggx_aniso)(R hx, R hy, R hz, R ax, R ay)
{
    R u = hx / ax, v = hy / ay;
    R t = u * u + v * v + hz * hz;
    return FN(safe_div)(K(1), K(ABRDF__PI) * ax * ay * t * t); /* Eq. 7 */
}

/* Normalised Beckmann D: exp(-tan^2/alpha^2) / (pi alpha^2 cos^4). */
static inline R FN(d_beckmann)(R ch, R sh2, R ag)
{
    if (!(ch > K(0))) return K(0);
    R c2 = ch * ch;
    return FN(safe_div)(exp(-sh2 / (c2 * ag * ag)), K(ABRDF__PI) * ag * ag * c2 * c2);
}

/* Disney clearcoat GTR1 (Burley 2012, App. B); alpha not squared. */
static inline R FN(d_gtr1)(R ch, R sh2, R alpha)
{
    R a2 = alpha * alpha;
    if (K(1) - a2 < K(ABRDF__GTR1_ALPHA_ONE)) return K(ABRDF__INV_PI);
    return (a2 - K(1)) / (K(ABRDF__PI) * log(a2) * (sh2 + a2 * ch * ch));
}

/* Half of Smith's separable G1 for GGX over the cosine, Eq. 9:
 * G1(u) / (2 cos_u) = 1 / (cos_u + sqrt(alpha^2 + (1 - alpha^2) cos_u^2)). */
static inline R FN(v1_smith_ggx)(R cu, R ag)
{
    R a2 = ag * ag;
    return K(1) / (cu + sqrt(a2 + (K(1) - a2) * cu * cu));
}

/* Smith G1 for GGX itself (Eq. 9), for callers that want G rather than visibility. */
static inline R FN(g1_smith_ggx)(R cu, R ag)
{
    return K(2) * FN(pos)(cu) * FN(v1_smith_ggx)(FN(pos)(cu), ag); /* Eq. 9 */
}

/* Anisotropic version: sqrt((u_x a_x)^2 + (u_y a_y)^2 + u_z^2). */
static inline R FN(v1_smith_ggx_aniso)(R ux, R uy, R uz, R ax, R ay)
{
    R a = ux * ax, b = uy * ay;
    return K(1) / (uz + sqrt(a * a + b * b + uz * uz));
}

/* Cook-Torrance V-cavity G. */
static inline R FN(g_cook_torrance)(const geo *g)
{
    R k = FN(safe_div)(K(2) * g->ch, g->cd);
    R gi = k * g->ci, go = k * g->co;
    R m = gi < go ? gi : go;
    return m < K(1) ? FN(pos)(m) : K(1);
}

static inline void FN(k_cook_torrance)(const kp *p, const geo *g, R f[3])
{
    R dg = FN(d_beckmann)(g->ch, g->sh2, p->ag) * FN(g_cook_torrance)(g);
    R v = FN(safe_div)(dg, K(4) * g->ci * g->co); /* Eq. 5 */
    for (int c = 0; c < 3; ++c) f[c] = p->ks[c] * FN(f_schlick)(p->f0[c], g->cd) * v;
}

static inline void FN(k_disney_specular)(const kp *p, const geo *g, R f[3])
{
    R dv = FN(d_ggx)(g->ch, g->sh2, p->ag) * FN(v1_smith_ggx)(g->ci, p->ag) *
           FN(v1_smith_ggx)(g->co, p->ag); /* Eq. 5 with Eqs. 6 and 9 */
    for (int c = 0; c < 3; ++c) f[c] = p->ks[c] * FN(f_schlick)(p->f0[c], g->cd) * dv;
}

static inline void FN(k_disney_specular_aniso)(const kp *p, const geo *g, R f[3])
{
    R dv = FN(d_ggx_aniso)(g->hx, g->hy, g->hz, p->ax, p->ay) *
           FN(v1_smith_ggx_aniso)(g->ix, g->iy, g->ci, p->ax, p->ay) *
           FN(v1_smith_ggx_aniso)(g->ox, g->oy, g->co, p->ax, p->ay); /* Eqs. 5, 7, 9 */
    for (int c = 0; c < 3; ++c) f[c] = p->ks[c] * FN(f_schlick)(p->f0[c], g->cd) * dv;
}

static inline void FN(k_disney_clearcoat)(const kp *p, const geo *g, R f[3])
{
    R dv = FN(d_gtr1)(g->ch, g->sh2, p->cc_alpha) * FN(v1_smith_ggx)(g->ci, K(0.25)) *
           FN(v1_smith_ggx)(g->co, K(0.25));
    R v = K(0.25) * FN(f_schlick)(K(0.04), g->cd) * dv;
    for (int c = 0; c < 3; ++c) f[c] = p->ks[c] * v;
}
