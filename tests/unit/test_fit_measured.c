/* test_fit_measured.c - the fit and the prediction against a prepared reference (abrdf_fit.h:
 * abrdf_fit_to, abrdf_predict_nmse_to): a measured table written from an analytic BRDF gives
 * back its parameters; a prepared closed-form reference gives abrdf_fit's bits; the exact
 * log and cube-root errors vanish for an exact fit; bad arguments are refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf_fit.h"
#include "measured_cases.h"
#include "test_util.h"

/* The fit of diffuse + specular to a prepared reference, by the L2 metric. */
typedef struct fit_out {
    int status;
    abrdf_params p;
    abrdf_fit_result r;
} fit_out;

static fit_out fit_to(const abrdf_prepared *ref, abrdf_model diffuse, abrdf_model specular)
{
    fit_out o;
    abrdf_fit_options opt;
    abrdf_fit_options_init(&opt);
    size_t ws = abrdf_fit_workspace_size(&opt, NULL);
    void *work = malloc(ws);
    ck_assert_ptr_nonnull(work);
    abrdf_params_init(specular, &o.p);
    abrdf_fit_result_init(&o.r);
    o.status = abrdf_fit_to(ref, diffuse, specular, &o.p, &opt, &o.r, work, ws);
    free(work);
    return o;
}

/* A table of lambert kd + spec (r, the model's ks and f0 defaults), fitted by lambert + spec:
 * r, kd, ks and f0 come back within the bounds asserted (the table's linear interpolation
 * costs about 1 % in relative L2, docs/MEASURED.md). */
static void recovers(abrdf_model spec, double r, double kd, double tol_r, double tol_kd,
                     double tol_ks, double tol_f0)
{
    abrdf_params g;
    abrdf_params_init(spec, &g);
    g.r = r;
    for (int c = 0; c < 3; ++c) g.kd[c] = kd;
    mc_table t;
    mc_table_of(&t, 90, 90, 180, ABRDF_LAMBERT, spec, &g);
    abrdf_prepared ref;
    ck_assert_int_eq(abrdf_prepare_measured(&t.desc, &ref), ABRDF_OK);
    fit_out o = fit_to(&ref, ABRDF_LAMBERT, spec);
    ck_assert_msg(o.status == ABRDF_OK, "%s", o.r.message);
    printf("%s: r %.4f (%.2f), kd %.4f (%.2f), ks %.4f (%.2f), f0 %.4f (%.3f); rel L2 %.3g, "
           "log %.3g, cbrt %.3g, NMSE %.3g\n",
           abrdf_model_get(spec)->name, o.p.r, r, o.p.kd[0], kd, o.p.ks[0], g.ks[0], o.p.f0[0],
           g.f0[0], o.r.rel_l2, o.r.rel_log, o.r.rel_cbrt, o.r.nmse_pred);
    ck_assert_double_le(fabs(o.p.r - r), tol_r);
    for (int c = 0; c < 3; ++c) {
        ck_assert_double_le(fabs(o.p.kd[c] - kd), tol_kd);
        ck_assert_double_le(fabs(o.p.ks[c] - g.ks[c]), tol_ks);
        ck_assert_double_le(fabs(o.p.f0[c] - g.f0[c]), tol_f0);
    }
    ck_assert(isfinite(o.r.rel_log) && o.r.rel_log >= 0.0);
    ck_assert(isfinite(o.r.rel_cbrt) && o.r.rel_cbrt >= 0.0);
    ck_assert_double_lt(o.r.nmse_pred, 2.5e-4); /* "slight" of Table 8 at most */
    free(t.data);
}

START_TEST(disney_specular_recovered)
{
    /* fitted: r 0.2992, kd 0.5003, ks 1.0000, f0 0.0398 */
    recovers(ABRDF_DISNEY_SPECULAR, 0.3, 0.5, 0.01, 0.01, 0.02, 0.005);
}
END_TEST

START_TEST(cook_torrance_recovered)
{
    /* fitted: r 0.2988, kd 0.4999, ks 1.0000, f0 0.0403 */
    recovers(ABRDF_COOK_TORRANCE, 0.3, 0.5, 0.01, 0.01, 0.02, 0.005);
}
END_TEST

/* A closed-form model prepared is the reference abrdf_fit has with (none, model): the same
 * bits, fit and prediction. */
START_TEST(prepared_analytic_is_abrdf_fit)
{
    static const struct {
        abrdf_model ref, cd, cs;
        const char *param;
        double v;
    } cases[] = {
        {ABRDF_DISNEY_SPECULAR, ABRDF_LAMBERT, ABRDF_F_GE, "r", 0.4},
        {ABRDF_DISNEY_SPECULAR, ABRDF_MODEL_NONE, ABRDF_COOK_TORRANCE, "r", 0.25},
        {ABRDF_BLINN_PHONG, ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, "n", 80.0},
        {ABRDF_OREN_NAYAR, ABRDF_MODEL_NONE, ABRDF_DISNEY_DIFFUSE, "sigma", 0.4},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        abrdf_params g;
        abrdf_params_init(cases[i].ref, &g);
        int id;
        ck_assert_int_eq(abrdf_param_find(cases[i].param, &id), ABRDF_OK);
        ck_assert_int_eq(abrdf_param_set(&g, id, &cases[i].v, 1), ABRDF_OK);
        abrdf_prepared ref;
        ck_assert_int_eq(abrdf_prepare(cases[i].ref, &g, &ref), ABRDF_OK);
        fit_out a = fit_to(&ref, cases[i].cd, cases[i].cs);
        ck_assert_msg(a.status == ABRDF_OK, "%s", a.r.message);
        abrdf_fit_options opt;
        abrdf_fit_options_init(&opt);
        size_t ws = abrdf_fit_workspace_size(&opt, NULL);
        void *work = malloc(ws);
        ck_assert_ptr_nonnull(work);
        fit_out b;
        abrdf_params_init(cases[i].cs, &b.p);
        abrdf_fit_result_init(&b.r);
        b.status = abrdf_fit(ABRDF_MODEL_NONE, cases[i].ref, &g, cases[i].cd, cases[i].cs, &b.p,
                             &opt, &b.r, work, ws);
        ck_assert_int_eq(b.status, ABRDF_OK);
        ck_assert_mem_eq(&a.p, &b.p, sizeof a.p);
        ck_assert_mem_eq(&a.r, &b.r, sizeof a.r);
        double n1, n2;
        ck_assert_int_eq(
            abrdf_predict_nmse_to(&ref, cases[i].cd, cases[i].cs, &a.p, NULL, &n1, work, ws),
            ABRDF_OK);
        ck_assert_int_eq(abrdf_predict_nmse(ABRDF_MODEL_NONE, cases[i].ref, &g, cases[i].cd,
                                            cases[i].cs, &a.p, NULL, &n2, work, ws),
                         ABRDF_OK);
        ck_assert_mem_eq(&n1, &n2, sizeof n1);
        ck_assert_mem_eq(&n1, &a.r.nmse_pred, sizeof n1);
        free(work);
    }
}
END_TEST

/* The exact log and cube-root errors: 0 for a candidate equal to the reference, positive and
 * ordered as the metrics compress for one that is not. */
START_TEST(exact_metrics)
{
    abrdf_params g;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &g);
    g.r = 0.3;
    abrdf_prepared ref;
    ck_assert_int_eq(abrdf_prepare(ABRDF_DISNEY_SPECULAR, &g, &ref), ABRDF_OK);
    fit_out same = fit_to(&ref, ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR); /* kept: exact */
    ck_assert_int_eq(same.status, ABRDF_OK);
    ck_assert_double_eq(same.r.rel_l2, 0.0);
    ck_assert_double_eq(same.r.rel_log, 0.0);
    ck_assert_double_eq(same.r.rel_cbrt, 0.0);
    fit_out other = fit_to(&ref, ABRDF_MODEL_NONE, ABRDF_F2);
    ck_assert_int_eq(other.status, ABRDF_OK);
    ck_assert(other.r.rel_l2 > 0.0 && other.r.rel_log > 0.0 && other.r.rel_cbrt > 0.0);
    ck_assert(isfinite(other.r.rel_log) && isfinite(other.r.rel_cbrt));
}
END_TEST

START_TEST(bad_arguments_refused)
{
    abrdf_params g, p;
    abrdf_params_init(ABRDF_LAMBERT, &g);
    mc_table t;
    mc_table_of(&t, 90, 90, 180, ABRDF_LAMBERT, ABRDF_MODEL_NONE, &g);
    abrdf_prepared ref, blank;
    memset(&blank, 0, sizeof blank);
    ck_assert_int_eq(abrdf_prepare_measured(&t.desc, &ref), ABRDF_OK);
    abrdf_fit_options opt;
    abrdf_fit_options_init(&opt);
    size_t ws = abrdf_fit_workspace_size(&opt, NULL);
    void *work = malloc(ws);
    ck_assert_ptr_nonnull(work);
    abrdf_fit_result r;
    abrdf_fit_result_init(&r);
    abrdf_params_init(ABRDF_LAMBERT, &p);
    ck_assert_int_eq(abrdf_fit_to(NULL, ABRDF_MODEL_NONE, ABRDF_LAMBERT, &p, &opt, &r, work, ws),
                     ABRDF_E_NULL);
    ck_assert(r.message[0]);
    ck_assert_int_eq(abrdf_fit_to(&blank, ABRDF_MODEL_NONE, ABRDF_LAMBERT, &p, &opt, &r, work, ws),
                     ABRDF_E_MODEL);
    ck_assert_int_eq(abrdf_fit_to(&ref, ABRDF_MODEL_NONE, ABRDF_MEASURED, &p, &opt, &r, work, ws),
                     ABRDF_E_MODEL);
    ck_assert_int_eq(abrdf_fit_to(&ref, ABRDF_MODEL_NONE, ABRDF_MODEL_NONE, &p, &opt, &r, work, ws),
                     ABRDF_E_MODEL);
    ck_assert_int_eq(abrdf_fit_to(&ref, ABRDF_MODEL_NONE, ABRDF_LAMBERT, NULL, &opt, &r, work, ws),
                     ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_fit_to(&ref, ABRDF_MODEL_NONE, ABRDF_LAMBERT, &p, &opt, &r, work, 64),
                     ABRDF_E_SIZE);
    /* without a table the measured model cannot be a reference */
    ck_assert_int_eq(abrdf_fit(ABRDF_MODEL_NONE, ABRDF_MEASURED, &g, ABRDF_MODEL_NONE,
                               ABRDF_LAMBERT, &p, &opt, &r, work, ws),
                     ABRDF_E_TABLE);
    double nmse;
    ck_assert_int_eq(
        abrdf_predict_nmse_to(NULL, ABRDF_MODEL_NONE, ABRDF_LAMBERT, &p, NULL, &nmse, work, ws),
        ABRDF_E_NULL);
    ck_assert_double_eq(nmse, -1.0);
    ck_assert_int_eq(
        abrdf_predict_nmse_to(&blank, ABRDF_MODEL_NONE, ABRDF_LAMBERT, &p, NULL, &nmse, work, ws),
        ABRDF_E_MODEL);
    /* a Lambert table fitted by Lambert: kd back to float rounding and the interpolation */
    abrdf_fit_result_init(&r);
    ck_assert_int_eq(abrdf_fit_to(&ref, ABRDF_MODEL_NONE, ABRDF_LAMBERT, &p, &opt, &r, work, ws),
                     ABRDF_OK);
    ck_assert_double_le(fabs(p.kd[0] - g.kd[0]), 1e-6);
    ck_assert_int_eq(
        abrdf_predict_nmse_to(&ref, ABRDF_MODEL_NONE, ABRDF_LAMBERT, &p, NULL, &nmse, work, ws),
        ABRDF_OK);
    ck_assert_double_le(nmse, 1e-10);
    free(work);
    free(t.data);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("fit_measured");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, disney_specular_recovered);
    tcase_add_test(tc, cook_torrance_recovered);
    tcase_add_test(tc, prepared_analytic_is_abrdf_fit);
    tcase_add_test(tc, exact_metrics);
    tcase_add_test(tc, bad_arguments_refused);
    suite_add_tcase(s, tc);
    return tu_run(s);
}
