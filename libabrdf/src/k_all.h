/* k_all.h - every closed-form model kernel in one precision, their parameter preparation
 * and the list that maps model ids to kernels. Included by eval_double.c and eval_float.c
 * after they define ABRDF_REAL and ABRDF_SFX. */
#include "kernel.h"
#include "k_diffuse.h"
#include "k_empirical.h"
#include "k_energy.h"
#include "k_microfacet.h"
#include "k_cloth.h"

/* Model id -> kernel, for every model evaluated in closed form. */
#define ABRDF__KERNEL_MODELS(X)                                  \
    X(ABRDF_LAMBERT, k_lambert)                                  \
    X(ABRDF_LAMBERT_FRESNEL, k_lambert_fresnel)                  \
    X(ABRDF_DISNEY_DIFFUSE, k_disney_diffuse)                    \
    X(ABRDF_OREN_NAYAR, k_oren_nayar)                            \
    X(ABRDF_PHONG, k_phong)                                      \
    X(ABRDF_BLINN_PHONG, k_blinn_phong)                          \
    X(ABRDF_F2, k_f2)                                            \
    X(ABRDF_F4, k_f4)                                            \
    X(ABRDF_F8, k_f8)                                            \
    X(ABRDF_F16, k_f16)                                          \
    X(ABRDF_FS, k_fs)                                            \
    X(ABRDF_FKV, k_fkv)                                          \
    X(ABRDF_FKUB, k_fkub)                                        \
    X(ABRDF_F_PHE, k_f_phe)                                      \
    X(ABRDF_F_BE, k_f_be)                                        \
    X(ABRDF_F_2E, k_f_2e)                                        \
    X(ABRDF_F_16E, k_f_16e)                                      \
    X(ABRDF_F_GE, k_f_ge)                                        \
    X(ABRDF_F_CTPHE, k_f_ctphe)                                  \
    X(ABRDF_F_CT2E, k_f_ct2e)                                    \
    X(ABRDF_F_CT16E, k_f_ct16e)                                  \
    X(ABRDF_COOK_TORRANCE, k_cook_torrance)                      \
    X(ABRDF_DISNEY_SPECULAR, k_disney_specular)                  \
    X(ABRDF_DISNEY_SPECULAR_ANISO, k_disney_specular_aniso)      \
    X(ABRDF_DISNEY_CLEARCOAT, k_disney_clearcoat)                \
    ABRDF__CLOTH_MODELS(X)

/* Convert and precompute the parameters a kernel reads (Cycles' "setup" step). */
static void FN(kp_make)(kp *k, abrdf_model model, const abrdf_params *p)
{
    for (int c = 0; c < 3; ++c) {
        k->kd[c] = (R)p->kd[c];
        k->ks[c] = (R)p->ks[c];
        k->f0[c] = (R)p->f0[c];
    }
    k->n = (R)p->n;
    k->r = (R)p->r;
    double ag = p->r * p->r;
    k->ag = (R)(ag > ABRDF__ALPHA_G_MIN ? ag : ABRDF__ALPHA_G_MIN);
    double aspect = sqrt(1.0 - 0.9 * p->anisotropic);
    double ax = ag / aspect, ay = ag * aspect;
    k->ax = (R)(ax > ABRDF__ALPHA_G_MIN ? ax : ABRDF__ALPHA_G_MIN);
    k->ay = (R)(ay > ABRDF__ALPHA_G_MIN ? ay : ABRDF__ALPHA_G_MIN);
    double s2 = p->sigma * p->sigma; /* Oren-Nayar 1994, qualitative model */
    k->on_a = (R)(1.0 - 0.5 * s2 / (s2 + 0.33));
    k->on_b = (R)(0.45 * s2 / (s2 + 0.09));
    k->cc_alpha = (R)(0.1 + (0.001 - 0.1) * p->clearcoat_gloss);
    k->k_amp = (R)p->k_amp;
    k->norm = K(1);
    k->fkub[0] = k->fkub[1] = k->fkub[2] = K(0);
    k->fkub_x0 = K(1);
    switch (model) {
    case ABRDF_F_PHE: case ABRDF_F_CTPHE: k->norm = FN(norm_phe)(k->n); break;
    case ABRDF_F_BE: k->norm = FN(norm_be)(k->n); break;
    case ABRDF_F_2E: case ABRDF_F_CT2E: k->norm = FN(norm_2e)(k->n); break;
    case ABRDF_F_16E: case ABRDF_F_CT16E: k->norm = FN(norm_16e)(k->n); break;
    case ABRDF_F_GE: k->norm = FN(norm_ge)(k->n); break;
    case ABRDF_FKUB: {
        double abc[3], x0;
        abrdf__fkub_coeffs(p->n, abc, &x0);
        for (int c = 0; c < 3; ++c) k->fkub[c] = (R)abc[c];
        k->fkub_x0 = (R)x0;
        break;
    }
    default: break;
    }
    FN(kp_make_cloth)(k, model, p);
}
