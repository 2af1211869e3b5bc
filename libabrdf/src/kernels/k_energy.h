/* k_energy.h - the energy-conserving lobes of the paper's Table 5, setup beside kernel (both
 * precisions via kernel.h). Each setup computes the lobe's normalisation constant (defined
 * and cited in k_terms.h) once, in the kernel's precision.
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
 *                        cosines are clamped at ABRDF__COS_MIN_NO_G. They share the setup
 *                        of the lobe they use (f_phe, f_2e, f_16e).
 *
 * f_phe: Lafortune, Willems 1994, (n + 2)/(2 pi) cos^n(gamma).
 * f_be: Giesen 2009, (n + 2)(n + 4) / (8 pi (2^(-n/2) + n)) cos^n(theta_h).
 * f_2e, f_16e: the paper's fitted constants times the Table-1 lobes f2, f16 on gamma.
 * f_ge: Gotanda 2012, (n + 2) / (4 pi (2 - 2^(-n/2))) F cos^n(theta_h) / max(cos_i, cos_o).
 * f_ctphe, f_ct2e, f_ct16e: R. L. Cook, K. E. Torrance, "A reflectance model for computer
 *   graphics", ACM TOG 1(1), 1982 (Eq. 5) in the Walter et al. 2007 normalisation. */
#include "kernel.h"
#include "k_terms.h"

#ifndef ABRDF_K_ENERGY_H
#define ABRDF_K_ENERGY_H

static inline void k_f_phe_setup(abrdf__kp *k, const abrdf_params *p)
{
    kp_base(k, p);
    k->norm = norm_phe(k->n);
}

static inline abrdf__real k_f_phe_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return p->norm * pow_pos(g->rv, p->n);
}
static inline void k_f_phe(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_f_phe_lobe(p, g), f);
}

static inline void k_f_be_setup(abrdf__kp *k, const abrdf_params *p)
{
    kp_base(k, p);
    k->norm = norm_be(k->n);
}

static inline abrdf__real k_f_be_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return p->norm * pow_ch(g, p->n);
}
static inline void k_f_be(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_f_be_lobe(p, g), f);
}

static inline void k_f_2e_setup(abrdf__kp *k, const abrdf_params *p)
{
    kp_base(k, p);
    k->norm = norm_2e(k->n);
}

static inline abrdf__real k_f_2e_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return p->norm * lobe_fm(p->n, g->rv, 1);
}
static inline void k_f_2e(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_f_2e_lobe(p, g), f);
}

static inline void k_f_16e_setup(abrdf__kp *k, const abrdf_params *p)
{
    kp_base(k, p);
    k->norm = norm_16e(k->n);
}

static inline abrdf__real k_f_16e_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return p->norm * lobe_fm(p->n, g->rv, 4);
}
static inline void k_f_16e(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    lobe_out(p, k_f_16e_lobe(p, g), f);
}

static inline void k_f_ge_setup(abrdf__kp *k, const abrdf_params *p)
{
    kp_base(k, p);
    k->norm = norm_ge(k->n);
}

static inline abrdf__real k_f_ge_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return p->norm * pow_ch(g, p->n) / (g->ci > g->co ? g->ci : g->co);
}
static inline void k_f_ge(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    schlick_out(p, g, k_f_ge_lobe(p, g), f);
}

/* D / (4 cos_i cos_o) with G = 1 and clamped cosines; times ks F in schlick_out. */
static inline abrdf__real ct_no_g(const abrdf__geo *g, abrdf__real d)
{
    const abrdf__real cmin = ABRDF__K(ABRDF__COS_MIN_NO_G);
    abrdf__real ci = g->ci > cmin ? g->ci : cmin;
    abrdf__real co = g->co > cmin ? g->co : cmin;
    return d / (ABRDF__K(4) * ci * co); /* Eq. 5 with G = 1 */
}

static inline abrdf__real k_f_ctphe_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return ct_no_g(g, p->norm * pow_ch(g, p->n));
}
static inline void k_f_ctphe(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    schlick_out(p, g, k_f_ctphe_lobe(p, g), f);
}
static inline abrdf__real k_f_ct2e_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return ct_no_g(g, p->norm * lobe_fm(p->n, g->ch, 1));
}
static inline void k_f_ct2e(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    schlick_out(p, g, k_f_ct2e_lobe(p, g), f);
}
static inline abrdf__real k_f_ct16e_lobe(const abrdf__kp *p, const abrdf__geo *g)
{
    return ct_no_g(g, p->norm * lobe_fm(p->n, g->ch, 4));
}
static inline void k_f_ct16e(const abrdf__kp *p, const abrdf__geo *g, abrdf__real f[3])
{
    schlick_out(p, g, k_f_ct16e_lobe(p, g), f);
}

#endif /* ABRDF_K_ENERGY_H */
