/* k_dispatch.h - the closed-form models: every family header and the list that maps a
 * model id to its setup and kernel. Included by eval_double.c (double) and eval_float.c
 * (float, ABRDF__KERNEL_FLOAT). */
#include "k_diffuse.h"
#include "k_empirical.h"
#include "k_energy.h"
#include "k_microfacet.h"
#include "k_cloth.h"

#ifndef ABRDF_K_DISPATCH_H
#define ABRDF_K_DISPATCH_H
/* X(id, setup, kernel, form) for every model evaluated in closed form. The setup fills
 * abrdf__kp from abrdf_params once per call; the kernel gives f_r for one direction pair.
 * form RGB: the kernel writes the three channels; form LOBE: the model is ks times one
 * scalar lobe, kernel_lobe (k_terms.h, lobe_out), and ks is in [0, 1] (registry), so the
 * float batch loops guard the lobe once and scale it per channel (eval_float.c); form
 * SCHLICK: the same with ks F_Schlick(F0, cos_d) for ks (k_terms.h, schlick_out), in [0, 1]
 * as well (F0 in [0, 1], registry). Both are
 * defined in the family header named above them, except kp_base (kernel.h), the setup of
 * the models with nothing to precompute. The names are the functions' own, in either
 * precision (kernel.h, naming rule). */
#define ABRDF__KERNEL_MODELS(X)                                                                    \
    /* k_diffuse.h */                                                                              \
    X(ABRDF_LAMBERT, kp_base, k_lambert, RGB)                                                      \
    X(ABRDF_LAMBERT_FRESNEL, kp_base, k_lambert_fresnel, RGB)                                      \
    X(ABRDF_DISNEY_DIFFUSE, kp_base, k_disney_diffuse, RGB)                                        \
    X(ABRDF_OREN_NAYAR, k_oren_nayar_setup, k_oren_nayar, RGB)                                     \
    /* k_empirical.h */                                                                            \
    X(ABRDF_PHONG, kp_base, k_phong, LOBE)                                                         \
    X(ABRDF_BLINN_PHONG, kp_base, k_blinn_phong, LOBE)                                             \
    X(ABRDF_F2, kp_base, k_f2, LOBE)                                                               \
    X(ABRDF_F4, kp_base, k_f4, LOBE)                                                               \
    X(ABRDF_F8, kp_base, k_f8, LOBE)                                                               \
    X(ABRDF_F16, kp_base, k_f16, LOBE)                                                             \
    X(ABRDF_FS, kp_base, k_fs, LOBE)                                                               \
    X(ABRDF_FKV, kp_base, k_fkv, LOBE)                                                             \
    X(ABRDF_FKUB, k_fkub_setup, k_fkub, LOBE)                                                      \
    /* k_energy.h */                                                                               \
    X(ABRDF_F_PHE, k_f_phe_setup, k_f_phe, LOBE)                                                   \
    X(ABRDF_F_BE, k_f_be_setup, k_f_be, LOBE)                                                      \
    X(ABRDF_F_2E, k_f_2e_setup, k_f_2e, LOBE)                                                      \
    X(ABRDF_F_16E, k_f_16e_setup, k_f_16e, LOBE)                                                   \
    X(ABRDF_F_GE, k_f_ge_setup, k_f_ge, SCHLICK)                                                   \
    X(ABRDF_F_CTPHE, k_f_phe_setup, k_f_ctphe, SCHLICK)                                            \
    X(ABRDF_F_CT2E, k_f_2e_setup, k_f_ct2e, SCHLICK)                                               \
    X(ABRDF_F_CT16E, k_f_16e_setup, k_f_ct16e, SCHLICK)                                            \
    /* k_microfacet.h */                                                                           \
    X(ABRDF_COOK_TORRANCE, k_microfacet_setup, k_cook_torrance, SCHLICK)                           \
    X(ABRDF_DISNEY_SPECULAR, k_microfacet_setup, k_disney_specular, SCHLICK)                       \
    X(ABRDF_DISNEY_SPECULAR_ANISO, k_disney_specular_aniso_setup, k_disney_specular_aniso,         \
      SCHLICK)                                                                                     \
    X(ABRDF_DISNEY_CLEARCOAT, k_disney_clearcoat_setup, k_disney_clearcoat, RGB)                   \
    /* k_cloth.h */                                                                                \
    X(ABRDF_NEUBELT_PETTINEO, k_neubelt_pettineo_setup, k_neubelt_pettineo, RGB)                   \
    X(ABRDF_KAJIYA_KAY, kp_base, k_kajiya_kay, RGB)
#endif /* ABRDF_K_DISPATCH_H */
