/* k_energy.h - the energy-conserving lobes of the paper's Table 5.
 *
 * Which angle each lobe uses (the paper mixes gamma and theta_h between rows; MODELS.md
 * Table 5 note and B4):
 *   f_phe, f_2e, f_16e   Phong-style lobes on cos(gamma) = R.V. Their constants are
 *                        normalisations of a lobe about R (f_2e's and f_16e's are fits to
 *                        the exact NDF constant K_m); on N.H they would overshoot ~4x.
 *                        The paper prints f_16e on theta_h; we follow B4 and use gamma.
 *   f_be, f_ge           Blinn-Phong on cos(theta_h) = N.H (their constants are derived
 *                        for N.H).
 *   f_ctphe, f_ct2e, f_ct16e  the same lobes used as the distribution D of Cook-Torrance
 *                        D F G / (4 cos_i cos_o) with G = 1, hence on N.H (an NDF). The
 *                        cosines are clamped at ABRDF__COS_MIN_NO_G.
 *
 * f_phe: E. Lafortune, Y. Willems, "Using the modified Phong reflectance model for physically
 *   based rendering", TR CW197, KU Leuven 1994: (n + 2)/(2 pi) cos^n(gamma).
 * f_be: F. Giesen, "The Blinn-Phong normalization zoo", 2009:
 *   (n + 2)(n + 4) / (8 pi (2^(-n/2) + n)) cos^n(theta_h).
 * f_2e, f_16e: the paper's fitted constants 0.111/n + 0.238(0.481 + n) and (1.063 n + 1)/(2 pi).
 * f_ge: Y. Gotanda, "Beyond a simple physically based Blinn-Phong model in real-time",
 *   SIGGRAPH 2012 course, eq. 1 with the closed-form constant (MODELS.md B4):
 *   (n + 2) / (4 pi (2 - 2^(-n/2))) F cos^n(theta_h) / max(cos_i, cos_o).
 * f_ctphe, f_ct2e, f_ct16e: R. L. Cook, K. E. Torrance, "A reflectance model for computer
 *   graphics", ACM TOG 1(1), 1982 (Eq. 5) in the Walter et al. 2007 normalisation. */

static inline R FN(norm_phe)(R n) { return (n + K(2)) / K(2 * ABRDF__PI); }
static inline R FN(norm_be)(R n)
{
    return (n + K(2)) * (n + K(4)) / (K(8 * ABRDF__PI) * (pow(K(2), -n / K(2)) + n));
}
static inline R FN(norm_2e)(R n) { return K(0.111) / n + K(0.238) * (K(0.481) + n); }
static inline R FN(norm_16e)(R n) { return (K(1.063) * n + K(1)) / K(2 * ABRDF__PI); }
static inline R FN(norm_ge)(R n)
{
    return (n + K(2)) / (K(4 * ABRDF__PI) * (K(2) - pow(K(2), -n / K(2))));
}

static inline void FN(k_f_phe)(const kp *p, const geo *g, R f[3])
{
    FN(lobe_out)(p, p->norm * FN(pow_pos)(g->rv, p->n), f);
}

static inline void FN(k_f_be)(const kp *p, const geo *g, R f[3])
{
    FN(lobe_out)(p, p->norm * FN(pow_pos)(g->ch, p->n), f);
}

static inline void FN(k_f_2e)(const kp *p, const geo *g, R f[3])
{
    FN(lobe_out)(p, p->norm * FN(lobe_fm)(p->n, g->rv, 1), f);
}

static inline void FN(k_f_16e)(const kp *p, const geo *g, R f[3])
{
    FN(lobe_out)(p, p->norm * FN(lobe_fm)(p->n, g->rv, 4), f);
}

static inline void FN(k_f_ge)(const kp *p, const geo *g, R f[3])
{
    R lobe = p->norm * FN(pow_pos)(g->ch, p->n) / (g->ci > g->co ? g->ci : g->co);
    for (int c = 0; c < 3; ++c) f[c] = p->ks[c] * FN(f_schlick)(p->f0[c], g->cd) * lobe;
}

/* D F / (4 cos_i cos_o) with G = 1 and clamped cosines. */
static inline void FN(ct_no_g)(const kp *p, const geo *g, R d, R f[3])
{
    R ci = g->ci > K(ABRDF__COS_MIN_NO_G) ? g->ci : K(ABRDF__COS_MIN_NO_G);
    R co = g->co > K(ABRDF__COS_MIN_NO_G) ? g->co : K(ABRDF__COS_MIN_NO_G);
    R v = d / (K(4) * ci * co); /* Eq. 5 with G = 1 */
    for (int c = 0; c < 3; ++c) f[c] = p->ks[c] * FN(f_schlick)(p->f0[c], g->cd) * v;
}

static inline void FN(k_f_ctphe)(const kp *p, const geo *g, R f[3])
{
    FN(ct_no_g)(p, g, p->norm * FN(pow_pos)(g->ch, p->n), f);
}
static inline void FN(k_f_ct2e)(const kp *p, const geo *g, R f[3])
{
    FN(ct_no_g)(p, g, p->norm * FN(lobe_fm)(p->n, g->ch, 1), f);
}
static inline void FN(k_f_ct16e)(const kp *p, const geo *g, R f[3])
{
    FN(ct_no_g)(p, g, p->norm * FN(lobe_fm)(p->n, g->ch, 4), f);
}
