// abrdf_osl.h - the OSL port of libabrdf's closed-form models, 1:1 with the C kernels
// (libabrdf/src/kernels/k_*.h): the same names abrdf_<model>, the same parameters in the same
// order, the same guards and thresholds. Formulas and sources: docs/MODELS.md of the C
// library; each function names its equation.
//
// Direction convention (as libabrdf/include/abrdf.h): in the local frame z is the normal
// N, x the tangent T, y the bitangent B = N x T; wi points toward the light, wo toward the
// viewer, both away from the surface. Every abrdf_<model> returns f_r WITHOUT the cosine,
// and 0 unless both directions are strictly above the surface.
//
// FUNCTIONS
//   abrdf_<model>(wi, wo, ...)      one per model (list: abrdf_meta.h, ABRDF_MODEL_NAMES)
//   abrdf_eval(model, wi, wo, ...)  dispatch by the model's stable name; invalid -> 0
//   abrdf_params_valid(model, ...)  the C library's per-model range check (abrdf_meta.h)
//   abrdf_to_local(v, T, B, N)      world -> local frame
//   abrdf_frame_make(N, T, T_out, B_out)  the C library's abrdf_frame_make
//   abrdf_d_ggx, abrdf_d_ggx_aniso, abrdf_d_beckmann, abrdf_d_gtr1, abrdf_v1_smith_ggx,
//   abrdf_g1_smith_ggx, abrdf_f_schlick, abrdf_norm_*       the split terms
#ifndef ABRDF_OSL_H
#define ABRDF_OSL_H

#include "abrdf_osl_guards.h"
#include "abrdf_meta.h"
#include "abrdf_osl_kernels.h"

// ---- hair fibres (integrated in the loops of abrdf_hair.h) -------------------------------
#include "abrdf_hair.h"

// ---- dispatch by name ----------------------------------------------------------------------
// Every parameter of the library's flat parameter block; each model reads its own. Returns
// 0 for an unknown model or parameters outside the model's ranges (the C library returns
// an error code there), and never a negative or non-finite value.
color abrdf_eval(string model, vector wi, vector wo, color kd, color ks, color f0, float n,
                 float r, float anisotropic, float sigma, float clearcoat_gloss, float k_amp,
                 int layer_count, float layer_eta[4], float layer_kappa[4], float layer_r[4],
                 color layer_sigma_a[4], float layer_depth[4], float eta, float melanin,
                 float redness, float cuticle_tilt, float aspect_ratio, int entry_grid,
                 int internal_grid)
{
    if (!abrdf_params_valid(model, kd, ks, f0, n, r, anisotropic, sigma, clearcoat_gloss, k_amp,
                            layer_count, layer_eta, layer_kappa, layer_r, layer_sigma_a,
                            layer_depth, eta, melanin, redness, cuticle_tilt, aspect_ratio,
                            entry_grid, internal_grid))
        return color(0);
    color f = color(0);
    if (model == "lambert") f = abrdf_lambert(wi, wo, kd);
    else if (model == "lambert_fresnel") f = abrdf_lambert_fresnel(wi, wo, kd, f0);
    else if (model == "disney_diffuse") f = abrdf_disney_diffuse(wi, wo, kd, r);
    else if (model == "oren_nayar") f = abrdf_oren_nayar(wi, wo, kd, sigma);
    else if (model == "phong") f = abrdf_phong(wi, wo, ks, n);
    else if (model == "blinn_phong") f = abrdf_blinn_phong(wi, wo, ks, n);
    else if (model == "f2") f = abrdf_f2(wi, wo, ks, n);
    else if (model == "f4") f = abrdf_f4(wi, wo, ks, n);
    else if (model == "f8") f = abrdf_f8(wi, wo, ks, n);
    else if (model == "f16") f = abrdf_f16(wi, wo, ks, n);
    else if (model == "fs") f = abrdf_fs(wi, wo, ks, n);
    else if (model == "fkv") f = abrdf_fkv(wi, wo, ks, n);
    else if (model == "fkub") f = abrdf_fkub(wi, wo, ks, n);
    else if (model == "f_phe") f = abrdf_f_phe(wi, wo, ks, n);
    else if (model == "f_be") f = abrdf_f_be(wi, wo, ks, n);
    else if (model == "f_2e") f = abrdf_f_2e(wi, wo, ks, n);
    else if (model == "f_16e") f = abrdf_f_16e(wi, wo, ks, n);
    else if (model == "f_ge") f = abrdf_f_ge(wi, wo, ks, n, f0);
    else if (model == "f_ctphe") f = abrdf_f_ctphe(wi, wo, ks, n, f0);
    else if (model == "f_ct2e") f = abrdf_f_ct2e(wi, wo, ks, n, f0);
    else if (model == "f_ct16e") f = abrdf_f_ct16e(wi, wo, ks, n, f0);
    else if (model == "cook_torrance") f = abrdf_cook_torrance(wi, wo, ks, r, f0);
    else if (model == "disney_specular") f = abrdf_disney_specular(wi, wo, ks, r, f0);
    else if (model == "disney_specular_aniso")
        f = abrdf_disney_specular_aniso(wi, wo, ks, r, anisotropic, f0);
    else if (model == "disney_clearcoat") f = abrdf_disney_clearcoat(wi, wo, ks, clearcoat_gloss);
    else if (model == "neubelt_pettineo") f = abrdf_neubelt_pettineo(wi, wo, kd, ks, f0, r, k_amp);
    else if (model == "kajiya_kay") f = abrdf_kajiya_kay(wi, wo, kd, ks, n);
    else if (model == "marschner")
        f = abrdf_marschner(wi, wo, eta, melanin, redness, cuticle_tilt, aspect_ratio, r);
    else if (model == "huang")
        f = abrdf_huang(wi, wo, eta, melanin, redness, cuticle_tilt, aspect_ratio, r, entry_grid,
                        internal_grid);
    else if (model == "weidlich_wilkie")
        f = abrdf_weidlich_wilkie(wi, wo, kd, layer_count, layer_eta, layer_kappa, layer_r,
                                  layer_sigma_a, layer_depth);
    else if (model == "belcour")
        f = abrdf_belcour(wi, wo, layer_count, layer_eta, layer_kappa, layer_r, layer_sigma_a,
                          layer_depth);
    // Last line of defence, as in the C library: never NaN, Inf or negative.
    for (int c = 0; c < 3; ++c)
        if (!(f[c] >= 0.0 && f[c] <= 3.4e38)) f[c] = 0.0;
    return f;
}

// ---- shader parameters ----------------------------------------------------------------
// One interface of the layer stack as the library's layerK_* shader parameters, with the
// library's help and ranges (abrdf_eval.osl and abrdf_material.osl declare four).
#define ABRDF_LAYER(k)                                                                      \
    float layer##k##_eta = ABRDF_WEIDLICH_WILKIE_LAYER##k##_ETA_DEFAULT [[                 \
        string help = ABRDF_P_LAYER##k##_ETA_HELP, string label = "layer" #k "_eta",        \
        string page = "Layer " #k, float min = ABRDF_P_LAYER##k##_ETA_MIN,                 \
        float max = ABRDF_P_LAYER##k##_ETA_MAX ]],                                         \
    float layer##k##_kappa = ABRDF_WEIDLICH_WILKIE_LAYER##k##_KAPPA_DEFAULT [[             \
        string help = ABRDF_P_LAYER##k##_KAPPA_HELP, string label = "layer" #k "_kappa",    \
        string page = "Layer " #k, float min = ABRDF_P_LAYER##k##_KAPPA_MIN,               \
        float max = ABRDF_P_LAYER##k##_KAPPA_MAX ]],                                       \
    float layer##k##_r = ABRDF_WEIDLICH_WILKIE_LAYER##k##_R_DEFAULT [[                     \
        string help = ABRDF_P_LAYER##k##_R_HELP, string label = "layer" #k "_r",            \
        string page = "Layer " #k, float min = ABRDF_P_LAYER##k##_R_MIN,                   \
        float max = ABRDF_P_LAYER##k##_R_MAX ]],                                           \
    color layer##k##_sigma_a = color(ABRDF_WEIDLICH_WILKIE_LAYER##k##_SIGMA_A_DEFAULT) [[  \
        string help = ABRDF_P_LAYER##k##_SIGMA_A_HELP, string label = "layer" #k "_sigma_a",\
        string page = "Layer " #k, float min = ABRDF_P_LAYER##k##_SIGMA_A_MIN,             \
        float max = ABRDF_P_LAYER##k##_SIGMA_A_MAX ]],                                     \
    float layer##k##_depth = ABRDF_WEIDLICH_WILKIE_LAYER##k##_DEPTH_DEFAULT [[             \
        string help = ABRDF_P_LAYER##k##_DEPTH_HELP, string label = "layer" #k "_depth",    \
        string page = "Layer " #k, float min = ABRDF_P_LAYER##k##_DEPTH_MIN,               \
        float max = ABRDF_P_LAYER##k##_DEPTH_MAX ]]

// ---- the selection flowchart (Fig. 2), abrdf_select() ------------------------------------
#include "abrdf_osl_select.h"

#endif // ABRDF_OSL_H
