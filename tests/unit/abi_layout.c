/* abi_layout.c - the table of abi_layout.h for the headers this file is compiled against:
 * ABI_HEADER names abrdf_select.h (or its 0.2.0 snapshot), ABI_TABLE the table's name.
 * The lists below are the 0.2.0 ABI, field by field: like the snapshot, they never change;
 * a later release appends what it adds. */
#include ABI_HEADER
#include "abi_layout.h"

#define STRUCT(t) {ABI_STRUCT, #t, NULL, 0, sizeof(t)},
#define FIELD(t, f) {ABI_FIELD, #t, #f, offsetof(t, f), sizeof(((t *)0)->f)},
#define VALUE(v) {ABI_VALUE, #v, NULL, (size_t)((long)(v) + ABI_VALUE_BIAS), 0},

const abi_entry ABI_TABLE[] = {
    /* abrdf.h */
    STRUCT(abrdf_layer) FIELD(abrdf_layer, eta) FIELD(abrdf_layer, kappa) FIELD(
        abrdf_layer, r) FIELD(abrdf_layer, sigma_a) FIELD(abrdf_layer, depth) STRUCT(abrdf_params)
        FIELD(abrdf_params, struct_size) FIELD(abrdf_params, kd) FIELD(abrdf_params, ks) FIELD(
            abrdf_params, f0) FIELD(abrdf_params, n) FIELD(abrdf_params, r)
            FIELD(abrdf_params, anisotropic) FIELD(abrdf_params, sigma) FIELD(
                abrdf_params, clearcoat_gloss) FIELD(abrdf_params, k_amp) FIELD(abrdf_params, eta)
                FIELD(abrdf_params, melanin) FIELD(abrdf_params, redness) FIELD(abrdf_params,
                                                                                cuticle_tilt)
                    FIELD(abrdf_params, aspect_ratio) FIELD(abrdf_params, layer_count) FIELD(
                        abrdf_params, layers) STRUCT(abrdf_param_info) FIELD(abrdf_param_info, name)
                        FIELD(abrdf_param_info, help) FIELD(abrdf_param_info, kind) FIELD(
                            abrdf_param_info,
                            min) FIELD(abrdf_param_info, max)
                            FIELD(abrdf_param_info, def) STRUCT(abrdf_model_param) FIELD(
                                abrdf_model_param, id) FIELD(abrdf_model_param, def)
                                FIELD(abrdf_model_param, min) FIELD(abrdf_model_param, max) STRUCT(
                                    abrdf_model_info) FIELD(abrdf_model_info, id)
                                    FIELD(abrdf_model_info, name) FIELD(abrdf_model_info, title)
                                        FIELD(abrdf_model_info, equation) FIELD(
                                            abrdf_model_info,
                                            citation) FIELD(abrdf_model_info, needs)
                                            FIELD(abrdf_model_info, props) FIELD(
                                                abrdf_model_info,
                                                paper_cycles) FIELD(abrdf_model_info, param_count)
                                                FIELD(abrdf_model_info, params) STRUCT(
                                                    abrdf_frame) FIELD(abrdf_frame,
                                                                       n) FIELD(abrdf_frame, t)
                                                    FIELD(abrdf_frame, b) STRUCT(abrdf_batch) FIELD(
                                                        abrdf_batch, count) FIELD(abrdf_batch, wi_x)
                                                        FIELD(abrdf_batch, wi_y) FIELD(abrdf_batch,
                                                                                       wi_z)
                                                            FIELD(abrdf_batch,
                                                                  wo_x) FIELD(abrdf_batch, wo_y)
                                                                FIELD(abrdf_batch, wo_z)
                                                                    FIELD(abrdf_batch, f_r)
                                                                        FIELD(abrdf_batch, f_g)
                                                                            FIELD(abrdf_batch, f_b)
    /* abrdf_select.h */
    STRUCT(abrdf_approx_error) FIELD(abrdf_approx_error, max_rel_pct) FIELD(
        abrdf_approx_error, max_abs) FIELD(abrdf_approx_error, zone_cos) STRUCT(abrdf_costs)
        FIELD(abrdf_costs, unit) FIELD(abrdf_costs, cost) STRUCT(abrdf_material) FIELD(
            abrdf_material, struct_size) FIELD(abrdf_material,
                                               name) FIELD(abrdf_material,
                                                           type) FIELD(abrdf_material,
                                                                       n) FIELD(abrdf_material, r)
            FIELD(abrdf_material, kd) FIELD(abrdf_material, ks) FIELD(abrdf_material, f0) FIELD(
                abrdf_material,
                eta) FIELD(abrdf_material,
                           anisotropy) FIELD(abrdf_material,
                                             melanin) FIELD(abrdf_material, redness)
                FIELD(abrdf_material, layer_count) FIELD(abrdf_material, layers) STRUCT(
                    abrdf_tolerance) FIELD(abrdf_tolerance,
                                           struct_size) FIELD(abrdf_tolerance, max_rel_pct)
                    FIELD(abrdf_tolerance,
                          max_abs) STRUCT(abrdf_select_rules) FIELD(abrdf_select_rules, smooth_r_max)
                        FIELD(abrdf_select_rules, aniso_min) FIELD(
                            abrdf_select_rules,
                            default_max_rel_pct) FIELD(abrdf_select_rules, default_max_abs)
                            FIELD(abrdf_select_rules, n_min) FIELD(
                                abrdf_select_rules,
                                n_max) FIELD(abrdf_select_rules,
                                             perf_diffuse) FIELD(abrdf_select_rules,
                                                                 perf_fallback) FIELD(abrdf_select_rules,
                                                                                      candidate_count)
                                FIELD(abrdf_select_rules, candidates) FIELD(
                                    abrdf_select_rules,
                                    rough_diffuse) FIELD(abrdf_select_rules, rough_specular)
                                    FIELD(abrdf_select_rules, rough_specular_aniso) FIELD(
                                        abrdf_select_rules,
                                        smooth_diffuse) FIELD(abrdf_select_rules, smooth_specular)
                                        FIELD(abrdf_select_rules, surface_count) FIELD(
                                            abrdf_select_rules,
                                            special) FIELD(abrdf_select_rules,
                                                           special_reason) FIELD(abrdf_select_rules,
                                                                                 nmse_class_max)
                                            STRUCT(abrdf_select_step) FIELD(abrdf_select_step, kind) FIELD(
                                                abrdf_select_step,
                                                model) FIELD(abrdf_select_step,
                                                             value) FIELD(abrdf_select_step, threshold)
                                                FIELD(abrdf_select_step, value2) FIELD(
                                                    abrdf_select_step,
                                                    threshold2) FIELD(abrdf_select_step, cost)
                                                    FIELD(abrdf_select_step, passed) FIELD(
                                                        abrdf_select_step,
                                                        text) STRUCT(abrdf_selection)
                                                        FIELD(abrdf_selection, struct_size) FIELD(
                                                            abrdf_selection,
                                                            goal) FIELD(abrdf_selection, type)
                                                            FIELD(abrdf_selection, diffuse) FIELD(
                                                                abrdf_selection,
                                                                specular) FIELD(abrdf_selection, n)
                                                                FIELD(abrdf_selection, r) FIELD(
                                                                    abrdf_selection,
                                                                    err_rel_pct) FIELD(abrdf_selection,
                                                                                       err_abs)
                                                                    FIELD(abrdf_selection, err_nmse) FIELD(
                                                                        abrdf_selection,
                                                                        cost_diffuse)
                                                                        FIELD(abrdf_selection,
                                                                              cost_specular)
                                                                            FIELD(abrdf_selection,
                                                                                  cost_total)
                                                                                FIELD(
                                                                                    abrdf_selection,
                                                                                    cost_unit)
                                                                                    FIELD(
                                                                                        abrdf_selection,
                                                                                        step_count)
                                                                                        FIELD(
                                                                                            abrdf_selection,
                                                                                            message)

    /* Values that never change: statuses, ids, flags and frozen sizes. */
    VALUE(ABRDF_OK) VALUE(ABRDF_E_NULL) VALUE(ABRDF_E_MODEL) VALUE(ABRDF_E_PARAM) VALUE(
        ABRDF_E_RANGE) VALUE(ABRDF_E_GEOMETRY) VALUE(ABRDF_E_UNUSED) VALUE(ABRDF_E_TABLE)
        VALUE(ABRDF_E_SIZE) VALUE(ABRDF_MODEL_NONE) VALUE(ABRDF_LAMBERT) VALUE(
            ABRDF_LAMBERT_FRESNEL) VALUE(ABRDF_DISNEY_DIFFUSE) VALUE(ABRDF_OREN_NAYAR)
            VALUE(ABRDF_PHONG) VALUE(ABRDF_BLINN_PHONG) VALUE(ABRDF_F2) VALUE(ABRDF_F4) VALUE(
                ABRDF_F8)
                VALUE(ABRDF_F16) VALUE(ABRDF_FS) VALUE(ABRDF_FKV) VALUE(ABRDF_FKUB) VALUE(
                    ABRDF_F_PHE) VALUE(ABRDF_F_BE) VALUE(ABRDF_F_2E) VALUE(ABRDF_F_16E)
                    VALUE(ABRDF_F_GE) VALUE(ABRDF_F_CTPHE) VALUE(ABRDF_F_CT2E) VALUE(
                        ABRDF_F_CT16E) VALUE(ABRDF_COOK_TORRANCE) VALUE(ABRDF_DISNEY_SPECULAR)
                        VALUE(ABRDF_DISNEY_SPECULAR_ANISO) VALUE(ABRDF_DISNEY_CLEARCOAT) VALUE(
                            ABRDF_NEUBELT_PETTINEO) VALUE(ABRDF_KAJIYA_KAY) VALUE(ABRDF_MARSCHNER)
                            VALUE(ABRDF_HUANG) VALUE(ABRDF_WEIDLICH_WILKIE) VALUE(ABRDF_BELCOUR) VALUE(
                                ABRDF_NEEDS_TANGENT) VALUE(ABRDF_NEEDS_FRESNEL) VALUE(ABRDF_NEEDS_LAYERS)
                                VALUE(ABRDF_NEEDS_INTEGRATION) VALUE(ABRDF_PROP_RECIPROCAL) VALUE(
                                    ABRDF_PROP_ENERGY_CONSERVING) VALUE(ABRDF_PROP_DIFFUSE)
                                    VALUE(ABRDF_PROP_SPECULAR) VALUE(ABRDF_MAX_LAYERS) VALUE(
                                        ABRDF_PARAM_SCALAR) VALUE(ABRDF_PARAM_RGB)
                                        VALUE(ABRDF_PARAM_INT) VALUE(ABRDF_COSTS_CAPACITY) VALUE(
                                            ABRDF_SELECT_MESSAGE_MAX) VALUE(ABRDF_SURFACE_GENERAL)
                                            VALUE(ABRDF_SURFACE_CLOTH_ROUGH) VALUE(
                                                ABRDF_SURFACE_CLOTH_SHINY) VALUE(ABRDF_SURFACE_HAIR)
                                                VALUE(ABRDF_SURFACE_LAYERED_PLASTIC) VALUE(
                                                    ABRDF_SURFACE_LAYERED_PLATE)
                                                    VALUE(ABRDF_SURFACE_LAYERED_METAL) VALUE(
                                                        ABRDF_GOAL_PERFORMANCE)
                                                        VALUE(ABRDF_GOAL_PHOTOREAL) VALUE(
                                                            ABRDF_STEP_INPUT) VALUE(ABRDF_STEP_GOAL)
                                                            VALUE(ABRDF_STEP_DIFFUSE) VALUE(
                                                                ABRDF_STEP_CANDIDATE)
                                                                VALUE(ABRDF_STEP_CHEAPEST) VALUE(
                                                                    ABRDF_STEP_FALLBACK)
                                                                    VALUE(ABRDF_STEP_SURFACE) VALUE(
                                                                        ABRDF_STEP_ROUGHNESS)
                                                                        VALUE(ABRDF_STEP_ANISOTROPY)
                                                                            VALUE(
                                                                                ABRDF_STEP_EXPONENT)
                                                                                VALUE(
                                                                                    ABRDF_STEP_SPECIAL){
                                                                                    ABI_STRUCT,
                                                                                    NULL, NULL, 0,
                                                                                    0}};
