// abrdf_osl_select.h - the model-selection flowchart of Zavalniuk & Romanyuk 2024 (Fig. 2) in
// OSL: the same decisions as libabrdf's abrdf_select (libabrdf/src/selection/select.c) and
// `abrdf advise` (docs/SELECTION.md). Every threshold, model choice and candidate cost comes
// from abrdf_meta.h (ABRDF_SELECT_*, generated from `abrdf advise --rules --json` and
// `abrdf models --json`); the error analysis of the Table-1 approximations is
// libabrdf/src/selection/approx_error.c in float, on the Table-1 lobes written in t = 1 - c.
// Included by abrdf_osl.h after the models.
//
//   int abrdf_select(goal, surface, n, r, anisotropic, max_rel_pct, max_abs,
//                    output diffuse, output specular, output n_out)
//     goal "performance" or "photoreal"; surface one of ABRDF_SELECT_SURFACE_OPTIONS;
//     n in [0, 1e6] and r in [0, 1], a negative value: derive it from the other (as the C
//     material's "unset"); anisotropic in [0, 1]; max_rel_pct, max_abs the performance
//     tolerances (>= 0; 1e30 or more: no limit). Returns 1 and the model names ("" for no
//     diffuse lobe) and the exponent the chosen model reads, or 0 and empty names when the
//     C library returns ABRDF_E_RANGE for the same input.
#ifndef ABRDF_OSL_SELECT_H
#define ABRDF_OSL_SELECT_H

#include "abrdf_osl_kernels.h" // the guards, abrdf_meta.h (rules, defaults), the fkub lobe

// approx_error.c's sampling constants, same values and reasons.
#define ABRDF_ERR_SAMPLES 2048
#define ABRDF_ERR_SAMPLES_1 2049 // array sizes must be literals in OSL
#define ABRDF_ERR_REFINE_TOP 4
#define ABRDF_ERR_PEAK_WINDOW 64.0
#define ABRDF_ERR_GOLDEN_STEPS 80

// The analysis runs in t = 1 - c (c = N.H at mirror geometry wi = wo): near the peak, where
// every lobe of a large exponent lives (width ~ 1/n), a float resolves c only to 6e-8, but t
// to its full relative precision. So the lobes are written here in t, algebraically equal to
// the port's model functions (abrdf_osl_kernels.h) at mirror geometry, and cos^n as exp(n log(1 - t))
// with the series of log(1 - t) for small t: the float analysis then follows the C one
// (double) to ~1e-6 at every n (tests/ports/test_osl_select.py measures it).

// log(1 - t), t in [0, 1): the series below 1e-2 (remainder < t^8 / 8 < 1e-16).
float abrdf_log1m(float t)
{
    if (t >= 1e-2) return log(1.0 - t);
    return -t * (1.0 + t * (0.5 + t * (1.0 / 3.0 + t * (0.25 + t * (0.2 + t * (1.0 / 6.0 +
                 t / 7.0))))));
}
// 1 - exp(-x), x >= 0: the series below 1e-3.
float abrdf_one_minus_exp(float x)
{
    if (x >= 1e-3) return 1.0 - exp(-x);
    return x * (1.0 - x * (0.5 - x * (1.0 / 6.0 - x / 24.0)));
}

// A Table-1 approximation (ks = 1) at t = 1 - c; 0 unless c > 0 (abrdf_geo_front).
float abrdf_table1_t(string model, float n, float t)
{
    if (!(t < 1.0)) return 0.0;
    float c = 1.0 - t;
    if (model == "f2") return abrdf_pow2k(1.0 - (n / 2.0) * t, 1);
    if (model == "f4") return abrdf_pow2k(1.0 - (n / 4.0) * t, 2);
    if (model == "f8") return abrdf_pow2k(1.0 - (n / 8.0) * t, 3);
    if (model == "f16") return abrdf_pow2k(1.0 - (n / 16.0) * t, 4);
    if (model == "fs") return abrdf_safe_div(c, n * t + c);         // c / (n - n c + c)
    if (model == "fkv") return abrdf_pos(c * (1.0 - 0.786 * n * t)); // 0.786 n c^2 + (1 - 0.786 n) c
    if (model == "fkub") {
        float a, b, d, x0;
        abrdf_fkub_coeffs(n, a, b, d, x0);
        // c >= x0 = 0.1^(1/n)  <=>  t <= 1 - 0.1^(1/n)
        float v = 1.0 + t * (a + t * (b + t * d));
        return t <= abrdf_one_minus_exp(log(10.0) / n) ? abrdf_clampr(v, 0.0, 1.0) : 0.0;
    }
    return 0.0;
}
// Blinn-Phong (ks = 1) at t: c^n.
float abrdf_blinn_phong_t(float n, float t)
{
    if (!(t < 1.0)) return 0.0;
    if (t <= 0.0) return 1.0;
    return exp(n * abrdf_log1m(t));
}

// Error at t = 1 - c.
float abrdf_err_at(string model, float n, int relative, float t0)
{
    float t = clamp(t0, 0.0, 1.0);
    float f = abrdf_table1_t(model, n, t);
    float g = abrdf_blinn_phong_t(n, t);
    float d = fabs(f - g);
    if (!relative) return d;
    return g > 0.0 ? d / g : 0.0;
}

// Golden-section maximisation of the error on the c-interval [a, b], given as ta = 1 - a
// >= tb = 1 - b; the same steps as in c (x1 = b - r (b - a) is tb + r (ta - tb)).
float abrdf_err_refine(string model, float n, int relative, float ta0, float tb0)
{
    float r = 0.6180339887498949;
    float ta = ta0, tb = tb0;
    float x1 = tb + r * (ta - tb), x2 = ta - r * (ta - tb);
    float f1 = abrdf_err_at(model, n, relative, x1), f2 = abrdf_err_at(model, n, relative, x2);
    float best = max(f1, f2);
    for (int i = 0; i < ABRDF_ERR_GOLDEN_STEPS && ta - tb > 0.0; ++i) {
        if (f1 >= f2) {
            tb = x2; x2 = x1; f2 = f1;
            x1 = tb + r * (ta - tb); f1 = abrdf_err_at(model, n, relative, x1);
        } else {
            ta = x1; x1 = x2; f1 = f2;
            x2 = ta - r * (ta - tb); f2 = abrdf_err_at(model, n, relative, x2);
        }
        best = max(best, max(f1, f2));
    }
    return best;
}

// Maximum over the c-interval [lo, hi], given as tlo = 1 - lo >= thi = 1 - hi: uniform
// samples, then the largest sampled local maxima refined between their neighbours.
float abrdf_err_maximise(string model, float n, int relative, float tlo, float thi)
{
    float v[ABRDF_ERR_SAMPLES_1];
    float h = (tlo - thi) / ABRDF_ERR_SAMPLES;
    for (int i = 0; i <= ABRDF_ERR_SAMPLES; ++i)
        v[i] = abrdf_err_at(model, n, relative, i == ABRDF_ERR_SAMPLES ? thi : tlo - h * i);
    int top[ABRDF_ERR_REFINE_TOP]; // indices of the largest sampled local maxima
    int ntop = 0;
    for (int i = 0; i <= ABRDF_ERR_SAMPLES; ++i) {
        int peak = (i == 0 || v[i] >= v[i - 1]) && (i == ABRDF_ERR_SAMPLES || v[i] >= v[i + 1]);
        if (!peak) continue;
        if (ntop == ABRDF_ERR_REFINE_TOP && v[i] <= v[top[ntop - 1]]) continue;
        int k = ntop < ABRDF_ERR_REFINE_TOP ? ntop : ntop - 1;
        if (ntop < ABRDF_ERR_REFINE_TOP) ntop += 1;
        while (k > 0 && v[top[k - 1]] < v[i]) {
            top[k] = top[k - 1];
            k -= 1;
        }
        top[k] = i;
    }
    float best = 0.0;
    for (int i = 0; i <= ABRDF_ERR_SAMPLES; ++i) best = max(best, v[i]);
    for (int k = 0; k < ntop; ++k) {
        int i = top[k];
        float a = i > 0 ? tlo - h * (i - 1) : tlo;
        float b = i < ABRDF_ERR_SAMPLES ? tlo - h * (i + 1) : thi;
        best = max(best, abrdf_err_refine(model, n, relative, a, b));
    }
    return best;
}

// abrdf_approx_error_eval: max relative error (%) in the highlight zone and max absolute
// error over [0, 1] of a Table-1 approximation against Blinn-Phong at exponent n. Returns
// 0 (C: ABRDF_E_MODEL / ABRDF_E_RANGE) for another model or an n outside its range.
int abrdf_approx_error(string model, float n, output float rel_pct, output float abs_err)
{
    rel_pct = 0.0;
    abs_err = 0.0;
    if (!(model == "f2" || model == "f4" || model == "f8" || model == "f16" || model == "fs" ||
          model == "fkv" || model == "fkub"))
        return 0;
    if (!(n >= ABRDF_P_N_MIN && n <= ABRDF_P_N_MAX)) return 0;
    // The highlight zone c >= max(0.5^(1/n), sqrt(1 - 1/n)) (abrdf__highlight_zone_cos), in t:
    // 1 - 0.5^(1/n) and 1 - sqrt(1 - 1/n) = (1/n) / (1 + sqrt(1 - 1/n)).
    float t_half = n > 0.0 ? abrdf_one_minus_exp(log(2.0) / n) : 1.0; // cos^n = 1/2
    float t_infl = n > 1.0 ? (1.0 / n) / (1.0 + sqrt(1.0 - 1.0 / n)) : 1.0; // sin^2 = 1/n
    float rel = abrdf_err_maximise(model, n, 1, min(t_half, t_infl), 0.0);
    abs_err = abrdf_err_maximise(model, n, 0, 1.0, 0.0);
    if (n > ABRDF_ERR_PEAK_WINDOW)
        abs_err = max(abs_err, abrdf_err_maximise(model, n, 0, ABRDF_ERR_PEAK_WINDOW / n, 0.0));
    rel_pct = 100.0 * rel;
    return 1;
}

// The converters of libabrdf/src/core/api.c (Walter et al. 2007's n <-> alpha_g, alpha_g = r^2).
float abrdf_sel_alpha_g_to_n(float alpha_g)
{
    float a = max(alpha_g, ABRDF_ALPHA_G_MIN);
    if (!(a < 1.0)) return 0.0;
    return 2.0 / (a * a) - 2.0;
}
float abrdf_sel_n_to_alpha_g(float n0)
{
    float n = n0 >= 0.0 ? n0 : 0.0;
    return sqrt(2.0 / (n + 2.0));
}

// The range check abrdf_select ends with (abrdf_params_check of each chosen model) on the
// values the selection fills in: n, r and anisotropic; the rest of the block is what C
// fills for a material with the library's defaults (kd 0.8, ks 1, f0 0.04, melanin 0.3,
// redness 0; the model's own defaults otherwise), all inside every range.
int abrdf_sel_params_ok(string model, float n, float r, float anisotropic)
{
    if (model == "") return 1;
    float l_eta[4] = {1.5, 1.5, 1.5, 1.5};
    float l_kappa[4] = {0.0, 0.0, 0.0, 0.0};
    float l_r[4] = {0.1, 0.1, 0.1, 0.1};
    color l_sigma_a[4] = {color(0), color(0), color(0), color(0)};
    float l_depth[4] = {0.0, 0.0, 0.0, 0.0};
    return abrdf_params_valid(model, color(0.8), color(1), color(0.04), n, r, anisotropic,
                              ABRDF_OREN_NAYAR_SIGMA_DEFAULT,
                              ABRDF_DISNEY_CLEARCOAT_CLEARCOAT_GLOSS_DEFAULT,
                              ABRDF_NEUBELT_PETTINEO_K_AMP_DEFAULT, 2, l_eta, l_kappa, l_r,
                              l_sigma_a, l_depth, ABRDF_HUANG_ETA_DEFAULT, 0.3, 0.0,
                              ABRDF_HUANG_CUTICLE_TILT_DEFAULT, ABRDF_HUANG_ASPECT_RATIO_DEFAULT,
                              ABRDF_HUANG_ENTRY_GRID_DEFAULT, ABRDF_HUANG_INTERNAL_GRID_DEFAULT);
}

// The special model of a surface class ("" for general, "?" for an unknown class).
string abrdf_sel_special(string surface)
{
    if (surface == "general") return "";
    if (surface == "cloth_rough") return ABRDF_SELECT_SPECIAL_CLOTH_ROUGH;
    if (surface == "cloth_shiny") return ABRDF_SELECT_SPECIAL_CLOTH_SHINY;
    if (surface == "hair") return ABRDF_SELECT_SPECIAL_HAIR;
    if (surface == "layered_plastic") return ABRDF_SELECT_SPECIAL_LAYERED_PLASTIC;
    if (surface == "layered_plate") return ABRDF_SELECT_SPECIAL_LAYERED_PLATE;
    if (surface == "layered_metal") return ABRDF_SELECT_SPECIAL_LAYERED_METAL;
    return "?";
}

int abrdf_select(string goal, string surface, float n, float r, float anisotropic,
                 float max_rel_pct, float max_abs, output string diffuse,
                 output string specular, output float n_out)
{
    diffuse = "";
    specular = "";
    n_out = 0.0;
    // check_material / check_tolerance: what C rejects with ABRDF_E_RANGE.
    if (goal != "performance" && goal != "photoreal") return 0;
    string special = abrdf_sel_special(surface);
    if (special == "?") return 0;
    if (!(n < 0.0) && !(n >= 0.0 && n <= ABRDF_P_N_MAX)) return 0;
    if (!(r < 0.0) && !(r >= 0.0 && r <= 1.0)) return 0;
    if (n < 0.0 && r < 0.0) return 0;
    if (!(anisotropic >= 0.0 && anisotropic <= 1.0)) return 0;
    if (!(max_rel_pct >= 0.0) || !(max_abs >= 0.0)) return 0;

    // n and r: the given one, the other derived; a derived n is clamped to [0, n_max].
    int n_given = n >= 0.0;
    float n_raw = n_given ? n : abrdf_sel_alpha_g_to_n(clamp(r, 0.0, 1.0) * clamp(r, 0.0, 1.0));
    float nn = n_given ? n_raw : clamp(n_raw, 0.0, ABRDF_SELECT_N_MAX);
    float rr = r >= 0.0 ? r : sqrt(clamp(abrdf_sel_n_to_alpha_g(n), 0.0, 1.0));
    n_out = nn;

    if (goal == "performance") {
        // Lambert + the cheapest Table-1 approximation within both tolerances (equal cost:
        // smaller relative, then absolute error); none: Blinn-Phong. The class is not used.
        string cand[ABRDF_SELECT_CANDIDATE_COUNT] = ABRDF_SELECT_CANDIDATE_LIST;
        float cost[ABRDF_SELECT_CANDIDATE_COUNT] = ABRDF_SELECT_CANDIDATE_COSTS;
        int best = -1;
        float best_cost = 0.0, best_rel = 0.0, best_abs = 0.0;
        for (int i = 0; i < ABRDF_SELECT_CANDIDATE_COUNT; ++i) {
            float rel, ab;
            if (!abrdf_approx_error(cand[i], nn, rel, ab)) continue;
            if (!(rel <= max_rel_pct && ab <= max_abs && cost[i] >= 0.0)) continue;
            if (best < 0 || cost[i] < best_cost ||
                (cost[i] == best_cost && (rel < best_rel || (rel == best_rel && ab < best_abs)))) {
                best = i;
                best_cost = cost[i];
                best_rel = rel;
                best_abs = ab;
            }
        }
        diffuse = ABRDF_SELECT_PERF_DIFFUSE;
        specular = best >= 0 ? cand[best] : ABRDF_SELECT_PERF_FALLBACK;
    } else if (special != "") {
        // A special surface: its model is the whole reflectance (no diffuse lobe).
        specular = special;
    } else if (rr <= ABRDF_SELECT_SMOOTH_R_MAX) {
        // Smooth: f_2e reads the given or derived n, clamped (unclamped before) to its range.
        diffuse = ABRDF_SELECT_SMOOTH_DIFFUSE;
        specular = ABRDF_SELECT_SMOOTH_SPECULAR;
        n_out = clamp(n_raw, ABRDF_SELECT_N_MIN, ABRDF_SELECT_N_MAX);
    } else {
        diffuse = ABRDF_SELECT_ROUGH_DIFFUSE;
        specular = anisotropic > ABRDF_SELECT_ANISO_MIN ? ABRDF_SELECT_ROUGH_SPECULAR_ANISO
                                                       : ABRDF_SELECT_ROUGH_SPECULAR;
    }
    // abrdf_params_check of the chosen models (e.g. huang needs r >= 0.05).
    if (!abrdf_sel_params_ok(diffuse, n_out, rr, anisotropic) ||
        !abrdf_sel_params_ok(specular, n_out, rr, anisotropic)) {
        diffuse = "";
        specular = "";
        n_out = 0.0;
        return 0;
    }
    return 1;
}

#endif // ABRDF_OSL_SELECT_H
