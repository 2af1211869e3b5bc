/* test_fit.c - abrdf_fit and abrdf_predict_nmse (abrdf_fit.h) by property: a model fitted
 * to itself from other starting values recovers its parameters; a fit beats the paper's
 * converter where the converter only approximates; fitted parameters stay in their ranges;
 * the prediction is the NMSE of the rendered images (exact for a scaled copy); results are
 * deterministic; bad input is rejected with a message. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf_fit.h"
#include "fit_internal.h"
#include "test_util.h"

typedef struct fit_out {
    abrdf_params p;
    abrdf_fit_result r;
    int status;
} fit_out;

/* keep: abrdf_fit_options.keep_shared (a lobe of the reference's model keeps its parameters) */
static fit_out fit_keep(abrdf_model rd, abrdf_model rs, const abrdf_params *rp, abrdf_model cd,
                        abrdf_model cs, abrdf_fit_metric metric, int keep)
{
    fit_out o;
    abrdf_fit_options opt;
    abrdf_fit_options_init(&opt);
    opt.metric = metric;
    opt.keep_shared = keep;
    size_t ws = abrdf_fit_workspace_size(&opt, NULL);
    ck_assert_uint_gt(ws, 0);
    void *w = malloc(ws);
    ck_assert_ptr_nonnull(w);
    abrdf_params_init(cs, &o.p);
    abrdf_fit_result_init(&o.r);
    o.status = abrdf_fit(rd, rs, rp, cd, cs, &o.p, &opt, &o.r, w, ws);
    free(w);
    return o;
}

static fit_out fit(abrdf_model rd, abrdf_model rs, const abrdf_params *rp, abrdf_model cd,
                   abrdf_model cs, abrdf_fit_metric metric)
{
    return fit_keep(rd, rs, rp, cd, cs, metric, 1);
}

static abrdf_params block(abrdf_model m)
{
    abrdf_params p;
    abrdf_params_init(m, &p);
    return p;
}

/* The reference's own model refitted: the linear weights come out of the closed-form solve,
 * the searched parameters out of the search, both to the reference's values. */
START_TEST(self_fit_recovers_parameters)
{
    abrdf_params g = block(ABRDF_DISNEY_SPECULAR);
    g.r = 0.33;
    double ks[3] = {0.9, 0.7, 0.5}, f0[3] = {0.95, 0.6, 0.3};
    memcpy(g.ks, ks, sizeof ks);
    memcpy(g.f0, f0, sizeof f0);
    for (int c = 0; c < 3; ++c) g.kd[c] = 0.4;
    fit_out o = fit_keep(ABRDF_LAMBERT, ABRDF_DISNEY_SPECULAR, &g, ABRDF_LAMBERT,
                         ABRDF_DISNEY_SPECULAR, ABRDF_FIT_L2, 0);
    ck_assert_int_eq(o.status, ABRDF_OK);
    ck_assert_str_eq(o.r.message, "");
    ck_assert_msg(fabs(o.p.r - 0.33) < 1e-3, "r %g", o.p.r);
    for (int c = 0; c < 3; ++c) {
        ck_assert_msg(fabs(o.p.ks[c] - ks[c]) < 2e-3, "ks[%d] %g", c, o.p.ks[c]);
        ck_assert_msg(fabs(o.p.f0[c] - f0[c]) < 2e-3, "f0[%d] %g", c, o.p.f0[c]);
        ck_assert_msg(fabs(o.p.kd[c] - 0.4) < 1e-3, "kd[%d] %g", c, o.p.kd[c]);
    }
    ck_assert_double_lt(o.r.rel_l2, 1e-3);
    ck_assert_double_lt(o.r.nmse_pred, 1e-6);
    ck_assert_int_eq(o.r.fitted, 3 * 3 + 1);
    ck_assert_int_gt(o.r.directions, 500);
}
END_TEST

/* Every model the fit searches, refitted to itself at non-default values: exact up to the
 * search's tolerance. This also holds every model to the linearity in kd, ks (and ks f0)
 * that the closed-form solve assumes: a model not linear in them could not be matched. */
START_TEST(self_fit_every_fast_model)
{
    static const abrdf_model models[] = {ABRDF_OREN_NAYAR,
                                         ABRDF_BLINN_PHONG,
                                         ABRDF_F8,
                                         ABRDF_FKUB,
                                         ABRDF_F_2E,
                                         ABRDF_F_GE,
                                         ABRDF_F_CT16E,
                                         ABRDF_COOK_TORRANCE,
                                         ABRDF_KAJIYA_KAY,
                                         ABRDF_NEUBELT_PETTINEO,
                                         ABRDF_DISNEY_CLEARCOAT};
    for (size_t i = 0; i < sizeof models / sizeof models[0]; ++i) {
        abrdf_model m = models[i];
        abrdf_params p = block(m);
        for (int c = 0; c < 3; ++c) p.kd[c] = 0.3 + 0.1 * c, p.ks[c] = 0.8 - 0.2 * c;
        p.n = 60.0;
        p.r = 0.45;
        p.sigma = 0.6;
        p.f0[0] = 0.5;
        p.clearcoat_gloss = 0.4;
        p.k_amp = 3.0;
        fit_out o = fit_keep(ABRDF_MODEL_NONE, m, &p, ABRDF_MODEL_NONE, m, ABRDF_FIT_L2, 0);
        ck_assert_int_eq(o.status, ABRDF_OK);
        ck_assert_msg(o.r.rel_l2 < 2e-3, "%s: rel L2 %g", abrdf_model_get(m)->name, o.r.rel_l2);
        ck_assert_msg(o.r.nmse_pred < 1e-5, "%s: NMSE %g", abrdf_model_get(m)->name, o.r.nmse_pred);
    }
}
END_TEST

/* Blinn-Phong n from the converter n = 2/alpha_g^2 - 2 (Walter et al. 2007) with ks = 1,
 * against a fitted n and ks: the fit is closer to a rough dielectric GGX lobe in every error
 * measure it reports, and its parameters stay in Blinn-Phong's ranges. */
START_TEST(fit_beats_the_converter)
{
    abrdf_params g = block(ABRDF_DISNEY_SPECULAR);
    g.r = 0.5;
    fit_out o = fit(ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g, ABRDF_MODEL_NONE,
                    ABRDF_BLINN_PHONG, ABRDF_FIT_L2);
    ck_assert_int_eq(o.status, ABRDF_OK);
    abrdf_params conv = block(ABRDF_BLINN_PHONG);
    conv.n = abrdf_alpha_g_to_n(abrdf_r_to_alpha_g(g.r));
    conv.ks[0] = conv.ks[1] = conv.ks[2] = 1.0;
    size_t ws = abrdf_fit_workspace_size(NULL, NULL);
    void *w = malloc(ws);
    double e_conv, e_fit;
    ck_assert_int_eq(abrdf_predict_nmse(ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g,
                                        ABRDF_MODEL_NONE, ABRDF_BLINN_PHONG, &conv, NULL, &e_conv,
                                        w, ws),
                     ABRDF_OK);
    ck_assert_int_eq(abrdf_predict_nmse(ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g,
                                        ABRDF_MODEL_NONE, ABRDF_BLINN_PHONG, &o.p, NULL, &e_fit, w,
                                        ws),
                     ABRDF_OK);
    free(w);
    ck_assert_double_eq_tol(e_fit, o.r.nmse_pred, 1e-12);
    ck_assert_msg(e_fit < 0.5 * e_conv, "fit %g vs converter %g", e_fit, e_conv);
    const abrdf_model_info *mi = abrdf_model_get(ABRDF_BLINN_PHONG);
    for (int k = 0; k < mi->param_count; ++k) {
        double v[3];
        int n = abrdf_param_read(&o.p, mi->params[k].id, v);
        for (int c = 0; c < n; ++c)
            ck_assert(v[c] >= mi->params[k].min && v[c] <= mi->params[k].max);
    }
    ck_assert_int_eq(abrdf_params_check(ABRDF_BLINN_PHONG, &o.p, NULL, 0), ABRDF_OK);
}
END_TEST

/* The fit is a minimum of its objective under the parameters' bounds: with the L2 metric the
 * objective is rel_l2^2 times a constant, and no feasible step of a fitted weight (ks, f0 per
 * channel; against gold some sit on their bounds) or of n lowers rel_l2 on the fit's own
 * direction set (fit_internal.h). */
START_TEST(fit_is_a_constrained_minimum)
{
    abrdf_params g = block(ABRDF_DISNEY_SPECULAR);
    g.r = 0.2;
    g.f0[0] = 0.957, g.f0[1] = 0.792, g.f0[2] = 0.408;
    fit_out o = fit(ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g, ABRDF_MODEL_NONE, ABRDF_F_GE,
                    ABRDF_FIT_L2);
    ck_assert_int_eq(o.status, ABRDF_OK);
    char msg[256];
    abrdf__brdf ref, cand;
    ck_assert_int_eq(
        abrdf__brdf_make(&ref, ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g, msg, sizeof msg),
        ABRDF_OK);
    size_t ws = abrdf_fit_workspace_size(NULL, NULL);
    void *w = malloc(ws);
    abrdf__arena a;
    abrdf__arena_init(&a, w, ws);
    abrdf__fit_set set;
    ck_assert_int_eq(abrdf__fit_set_make(&set, &ref, 0, 0, abrdf__fit_level(0, 0), &a), ABRDF_OK);
    ck_assert_int_eq(set.n, o.r.directions);
    ck_assert_int_eq(abrdf__brdf_make(&cand, ABRDF_MODEL_NONE, ABRDF_F_GE, &o.p, msg, sizeof msg),
                     ABRDF_OK);
    abrdf_fit_result base;
    abrdf_fit_result_init(&base);
    abrdf__fit_errors(&set, &cand, &base);
    ck_assert_double_eq_tol(base.rel_l2, o.r.rel_l2, 1e-12);
    int steps = 0;
    for (int k = 0; k < 7; ++k)
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            abrdf__brdf c = cand;
            double h = 1e-3 * sgn;
            if (k < 3)
                c.p.ks[k] += h;
            else if (k < 6)
                c.p.f0[k - 3] += h;
            else
                c.p.n *= 1.0 + 10.0 * h;
            if (abrdf_params_check(ABRDF_F_GE, &c.p, NULL, 0) != ABRDF_OK) continue;
            abrdf_fit_result r;
            abrdf_fit_result_init(&r);
            abrdf__fit_errors(&set, &c, &r);
            ck_assert_msg(r.rel_l2 >= base.rel_l2 * (1.0 - 1e-9),
                          "step %d (%+g) lowers rel L2 from %.12g to %.12g", k, h, base.rel_l2,
                          r.rel_l2);
            ++steps;
        }
    ck_assert_int_ge(steps, 7); /* at least one feasible direction per parameter */
    free(w);
}
END_TEST

/* Blinn-Phong's peak is ks <= 1: against a glossy metal (peak ~ 50) the fit stays in range
 * (ks at its bound) and says how far off it is. */
START_TEST(fit_stays_in_range)
{
    abrdf_params g = block(ABRDF_DISNEY_SPECULAR);
    g.r = 0.2;
    g.f0[0] = 0.957, g.f0[1] = 0.792, g.f0[2] = 0.408;
    fit_out o = fit(ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g, ABRDF_MODEL_NONE,
                    ABRDF_BLINN_PHONG, ABRDF_FIT_AUTO);
    ck_assert_int_eq(o.status, ABRDF_OK);
    for (int c = 0; c < 3; ++c) ck_assert_double_le(o.p.ks[c], 1.0);
    ck_assert_double_ge(o.p.n, 1.0);
    ck_assert_double_le(o.p.n, 1e6);
    ck_assert_double_gt(o.r.nmse_pred, 1e-3); /* a significant difference, reported */
    ck_assert_double_gt(o.r.rel_l2, 0.5);
}
END_TEST

/* The prediction is the NMSE of rendered images: a copy with every weight scaled by s
 * renders s times the reference, NMSE (1 - s)^2 whatever the view; identical BRDFs give 0. */
START_TEST(prediction_is_image_nmse)
{
    abrdf_params g = block(ABRDF_DISNEY_SPECULAR), h;
    g.r = 0.3;
    for (int c = 0; c < 3; ++c) g.kd[c] = 0.5;
    h = g;
    for (int c = 0; c < 3; ++c) h.kd[c] *= 0.9, h.ks[c] *= 0.9;
    abrdf_light_dir lights[2] = {{{0, 1, 1}, {2, 2, 2}}, {{1, 0, 0.2}, {1, 0.5, 0.2}}};
    abrdf_view v;
    abrdf_view_init(&v);
    v.view_dir[0] = 0.3;
    v.light_count = 2;
    v.lights = lights;
    v.resolution = 40;
    size_t ws = abrdf_fit_workspace_size(NULL, NULL); /* the default view is the larger */
    ck_assert_uint_ge(ws, abrdf_fit_workspace_size(NULL, &v));
    void *w = malloc(ws);
    double e;
    ck_assert_int_eq(abrdf_predict_nmse(ABRDF_DISNEY_DIFFUSE, ABRDF_DISNEY_SPECULAR, &g,
                                        ABRDF_DISNEY_DIFFUSE, ABRDF_DISNEY_SPECULAR, &h, &v, &e, w,
                                        ws),
                     ABRDF_OK);
    ck_assert_double_eq_tol(e, 0.01, 1e-12);
    ck_assert_int_eq(abrdf_predict_nmse(ABRDF_DISNEY_DIFFUSE, ABRDF_DISNEY_SPECULAR, &g,
                                        ABRDF_DISNEY_DIFFUSE, ABRDF_DISNEY_SPECULAR, &g, NULL, &e,
                                        w, ws),
                     ABRDF_OK);
    ck_assert_double_eq(e, 0.0);
    /* the caller's terms: one sample lit by one light */
    abrdf_view_term t = {0, {0, 0, 1}, {1, 0, 0}, {0, 0.6, 0.8}, {0.6, 0, 0.8}, {1, 1, 1}};
    abrdf_view vt;
    abrdf_view_init(&vt);
    vt.term_count = 1;
    vt.terms = &t;
    ck_assert_int_eq(abrdf_predict_nmse(ABRDF_DISNEY_DIFFUSE, ABRDF_DISNEY_SPECULAR, &g,
                                        ABRDF_DISNEY_DIFFUSE, ABRDF_DISNEY_SPECULAR, &h, &vt, &e, w,
                                        ws),
                     ABRDF_OK);
    ck_assert_double_eq_tol(e, 0.01, 1e-12);
    free(w);
}
END_TEST

START_TEST(deterministic)
{
    abrdf_params g = block(ABRDF_DISNEY_SPECULAR);
    g.r = 0.25;
    for (int c = 0; c < 3; ++c) g.kd[c] = 0.3;
    fit_out a = fit(ABRDF_DISNEY_DIFFUSE, ABRDF_DISNEY_SPECULAR, &g, ABRDF_LAMBERT, ABRDF_F_GE,
                    ABRDF_FIT_AUTO);
    fit_out b = fit(ABRDF_DISNEY_DIFFUSE, ABRDF_DISNEY_SPECULAR, &g, ABRDF_LAMBERT, ABRDF_F_GE,
                    ABRDF_FIT_AUTO);
    ck_assert_int_eq(a.status, ABRDF_OK);
    ck_assert_mem_eq(&a.p, &b.p, sizeof a.p);
    ck_assert_double_eq(a.r.nmse_pred, b.r.nmse_pred);
    ck_assert_int_eq(a.r.evals, b.r.evals);
}
END_TEST

START_TEST(bad_input)
{
    abrdf_params g = block(ABRDF_DISNEY_SPECULAR), c = block(ABRDF_BLINN_PHONG);
    abrdf_fit_result r;
    abrdf_fit_result_init(&r);
    char small[64];
    ck_assert_int_eq(abrdf_fit(ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g, ABRDF_MODEL_NONE,
                               ABRDF_BLINN_PHONG, &c, NULL, &r, small, sizeof small),
                     ABRDF_E_SIZE);
    ck_assert_ptr_nonnull(strstr(r.message, "workspace"));
    size_t ws = abrdf_fit_workspace_size(NULL, NULL);
    void *w = malloc(ws);
    ck_assert_int_eq(abrdf_fit(ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g, ABRDF_MODEL_NONE,
                               ABRDF_MODEL_NONE, &c, NULL, &r, w, ws),
                     ABRDF_E_MODEL);
    ck_assert_ptr_nonnull(strstr(r.message, "no model"));
    g.r = NAN;
    ck_assert_int_eq(abrdf_fit(ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g, ABRDF_MODEL_NONE,
                               ABRDF_BLINN_PHONG, &c, NULL, &r, w, ws),
                     ABRDF_E_RANGE);
    ck_assert_ptr_nonnull(strstr(r.message, "r = nan"));
    g.r = 0.3;
    abrdf_fit_options o;
    abrdf_fit_options_init(&o);
    o.metric = (abrdf_fit_metric)99;
    ck_assert_int_eq(abrdf_fit(ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g, ABRDF_MODEL_NONE,
                               ABRDF_BLINN_PHONG, &c, &o, &r, w, ws),
                     ABRDF_E_RANGE);
    o.struct_size = 0;
    ck_assert_int_eq(abrdf_fit(ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g, ABRDF_MODEL_NONE,
                               ABRDF_BLINN_PHONG, &c, &o, &r, w, ws),
                     ABRDF_E_SIZE);
    abrdf_view v;
    abrdf_view_init(&v);
    v.up[0] = 0, v.up[1] = 0, v.up[2] = 2; /* parallel to view_dir */
    double e;
    ck_assert_int_eq(abrdf_predict_nmse(ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &g,
                                        ABRDF_MODEL_NONE, ABRDF_BLINN_PHONG, &c, &v, &e, w, ws),
                     ABRDF_E_GEOMETRY);
    ck_assert_uint_eq(abrdf_fit_workspace_size(NULL, &v), 0);
    free(w);
    abrdf_fit_metric m;
    ck_assert_int_eq(abrdf_fit_metric_find("cbrt", &m), ABRDF_OK);
    ck_assert_int_eq(m, ABRDF_FIT_CBRT);
    ck_assert_str_eq(abrdf_fit_metric_name(ABRDF_FIT_AUTO), "auto");
    ck_assert_int_eq(abrdf_fit_metric_find("l1", &m), ABRDF_E_RANGE);
}
END_TEST

/* keep_shared: the candidate's lobe of the reference's model is the reference's, exactly;
 * only the other lobe is fitted. */
START_TEST(shared_lobe_is_kept)
{
    abrdf_params g = block(ABRDF_DISNEY_SPECULAR);
    g.r = 0.05;
    g.f0[0] = 0.2;
    for (int c = 0; c < 3; ++c) g.kd[c] = 0.6;
    fit_out o = fit(ABRDF_DISNEY_DIFFUSE, ABRDF_DISNEY_SPECULAR, &g, ABRDF_LAMBERT,
                    ABRDF_DISNEY_SPECULAR, ABRDF_FIT_AUTO);
    ck_assert_int_eq(o.status, ABRDF_OK);
    ck_assert_double_eq(o.p.r, g.r);
    ck_assert_mem_eq(o.p.ks, g.ks, sizeof g.ks);
    ck_assert_mem_eq(o.p.f0, g.f0, sizeof g.f0);
    ck_assert_int_eq(o.r.fitted, 3); /* kd per channel */
    ck_assert_double_ne(o.p.kd[0], g.kd[0]);
}
END_TEST

/* A lobe at the end of its range: against cotton's Neubelt-Pettineo sheen (the material table's
 * parameters), Oren-Nayar plus a GGX lobe at r = 1 with a small ks fits better than Oren-Nayar
 * alone. The search's grid has no point at a range's end, and where the solve switches the
 * lobe off (ks = 0) r is flat for Nelder-Mead; the scan of each parameter from the best point
 * (fit.c, search) finds the lobe. Both the L2 and the log metric. */
START_TEST(fit_finds_a_lobe_at_the_range_end)
{
    abrdf_params np = block(ABRDF_NEUBELT_PETTINEO);
    np.kd[0] = np.kd[1] = 0.7, np.kd[2] = 0.68;
    np.ks[0] = np.ks[1] = np.ks[2] = 1.0;
    np.f0[0] = np.f0[1] = np.f0[2] = 0.04652056901;
    np.r = 0.8, np.k_amp = 4.0;
    const abrdf_fit_metric metrics[] = {ABRDF_FIT_L2, ABRDF_FIT_LOG};
    for (int k = 0; k < 2; ++k) {
        fit_out alone = fit(ABRDF_MODEL_NONE, ABRDF_NEUBELT_PETTINEO, &np, ABRDF_MODEL_NONE,
                            ABRDF_OREN_NAYAR, metrics[k]);
        fit_out both = fit(ABRDF_MODEL_NONE, ABRDF_NEUBELT_PETTINEO, &np, ABRDF_OREN_NAYAR,
                           ABRDF_DISNEY_SPECULAR, metrics[k]);
        ck_assert_int_eq(alone.status, ABRDF_OK);
        ck_assert_int_eq(both.status, ABRDF_OK);
        ck_assert_msg(both.p.r > 0.99 && both.p.ks[0] > 0.01,
                      "metric %d: r %g, ks %g (the lobe at r = 1 not found)", k, both.p.r,
                      both.p.ks[0]);
        ck_assert_msg(both.r.objective < 0.99 * alone.r.objective,
                      "metric %d: objective %.9g with the lobe, %.9g without", k, both.r.objective,
                      alone.r.objective);
    }
}
END_TEST

/* Every registered model has a built-in cost (the budget ranks every candidate by it; the
 * measured model's is a lookup in a MERL-size table, what `abrdf calibrate` times). */
START_TEST(builtin_costs_cover_every_model)
{
    abrdf_costs c;
    ck_assert_int_eq(abrdf_costs_builtin(&c), ABRDF_OK);
    for (int i = 0; i < abrdf_model_count(); ++i)
        ck_assert_msg(abrdf_costs_get(&c, (abrdf_model)i) > 0.0, "no built-in cost for %s",
                      abrdf_model_get((abrdf_model)i)->name);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("fit");
    TCase *tc = tcase_create("fit");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, self_fit_recovers_parameters);
    tcase_add_test(tc, self_fit_every_fast_model);
    tcase_add_test(tc, fit_beats_the_converter);
    tcase_add_test(tc, fit_stays_in_range);
    tcase_add_test(tc, fit_is_a_constrained_minimum);
    tcase_add_test(tc, prediction_is_image_nmse);
    tcase_add_test(tc, deterministic);
    tcase_add_test(tc, bad_input);
    tcase_add_test(tc, shared_lobe_is_kept);
    tcase_add_test(tc, fit_finds_a_lobe_at_the_range_end);
    tcase_add_test(tc, builtin_costs_cover_every_model);
    suite_add_tcase(s, tc);
    return tu_run(s);
}
