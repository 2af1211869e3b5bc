/* test_approx_error.c - abrdf_approx_error_eval (the paper's Tables 2-3) against closed
 * forms: exact cases, a hand-solved absolute maximum, large-n limits, the zone definition,
 * the default cost model, and argument checking. */
#include <math.h>
#include "abrdf_internal.h"
#include "abrdf_select.h"
#include "test_util.h"

static abrdf_approx_error err(abrdf_model m, double n)
{
    abrdf_approx_error e;
    ck_assert_int_eq(abrdf_approx_error_eval(m, n, &e), ABRDF_OK);
    ck_assert(isfinite(e.max_rel_pct) && e.max_rel_pct >= 0.0);
    ck_assert(isfinite(e.max_abs) && e.max_abs >= 0.0);
    return e;
}

/* ((n/m)(c - 1) + 1)^m is c^n itself when n = m: no error anywhere. */
START_TEST(power_form_exact_at_n_equal_m)
{
    const abrdf_model m[] = {ABRDF_F2, ABRDF_F4, ABRDF_F8, ABRDF_F16};
    for (int i = 0; i < 4; ++i) {
        abrdf_approx_error e = err(m[i], (double)(2 << i));
        ck_assert_msg(e.max_rel_pct < 1e-9 && e.max_abs < 1e-12, "f%d at n=%d: %g %% %g", 2 << i,
                      2 << i, e.max_rel_pct, e.max_abs);
    }
}
END_TEST

/* Schlick's c / (n - n c + c) is exact at c = 0 and c = 1 (and everywhere for n = 1). */
START_TEST(schlick_exact_at_the_ends)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_FS, &p);
    p.ks[0] = p.ks[1] = p.ks[2] = 1.0;
    for (double n = 0.5; n <= 1000.0; n *= 3.0) {
        p.n = n;
        double up[3] = {0, 0, 1}, grazing[3] = {1.0, 0, 1e-12};
        ck_assert(tu_close(tu_eval1(ABRDF_FS, &p, up, up), 1.0, 1e-15, 0.0));
        ck_assert(tu_eval1(ABRDF_FS, &p, grazing, grazing) < 1e-11);
    }
    abrdf_approx_error e = err(ABRDF_FS, 1.0);
    ck_assert(e.max_rel_pct < 1e-9 && e.max_abs < 1e-12);
}
END_TEST

/* f2 at n = 4 is max(0, 2c - 1)^2. c^4 - (2c - 1)^2 = (c - 1)^2 (c^2 + 2c - 1) >= 0 on
 * [1/2, 1], largest where c^3 - 2c + 1 = 0, c = (sqrt 5 - 1)/2, value (5 sqrt 5 - 11)/2;
 * below c = 1/2 the error is c^4 <= 1/16, smaller. The relative error h/c^4 falls with c,
 * so its maximum is at the zone start c0 = sqrt(3)/2 (the inflection point). */
START_TEST(f2_at_n4_by_hand)
{
    abrdf_approx_error e = err(ABRDF_F2, 4.0);
    ck_assert_msg(tu_close(e.max_abs, (5.0 * sqrt(5.0) - 11.0) / 2.0, 1e-10, 0.0), "abs %.15g",
                  e.max_abs);
    double c0 = sqrt(3.0) / 2.0;
    double rel = 100.0 * (1 - c0) * (1 - c0) * (c0 * c0 + 2 * c0 - 1) / pow(c0, 4);
    ck_assert(tu_close(e.zone_cos, c0, 1e-15, 0.0));
    ck_assert_msg(tu_close(e.max_rel_pct, rel, 1e-9, 0.0), "rel %.15g vs %.15g", e.max_rel_pct,
                  rel);
}
END_TEST

/* As n -> inf, c^n -> e^-x and f_m -> (1 - x/m)^m with x = n(1 - c); the zone ends at
 * x = 1/2 and every relative error grows with x, so the limits are 1 - (1 - 1/(2m))^m e^(1/2)
 * and, for Schlick, e^(1/2)/(3/2) - 1. The absolute limit is the maximum over x >= 0 of
 * e^-x - max(0, 1 - x/m)^m, found here by an independent dense scan. */
START_TEST(large_n_limits)
{
    const abrdf_model m[] = {ABRDF_F2, ABRDF_F4, ABRDF_F8, ABRDF_F16};
    for (int i = 0; i < 4; ++i) {
        double mm = (double)(2 << i);
        double lim_rel = 100.0 * (1.0 - pow(1.0 - 0.5 / mm, mm) * exp(0.5));
        double lim_abs = 0.0;
        for (int k = 0; k <= 400000; ++k) {
            double x = k * 1e-4, b = fmax(0.0, 1.0 - x / mm);
            lim_abs = fmax(lim_abs, fabs(exp(-x) - pow(b, mm)));
        }
        abrdf_approx_error e = err(m[i], 1e6);
        ck_assert_msg(fabs(e.max_rel_pct - lim_rel) < 1e-3, "f%d rel %g vs %g", 2 << i,
                      e.max_rel_pct, lim_rel);
        ck_assert_msg(fabs(e.max_abs - lim_abs) < 1e-5, "f%d abs %g vs %g", 2 << i, e.max_abs,
                      lim_abs);
    }
    abrdf_approx_error e = err(ABRDF_FS, 1e6);
    ck_assert(fabs(e.max_rel_pct - 100.0 * (exp(0.5) / 1.5 - 1.0)) < 1e-3);
}
END_TEST

/* For n >= 2 the f2, f4 and Schlick errors grow with n towards their limits; higher-degree
 * forms are best near n = m. */
START_TEST(monotone_in_n)
{
    const abrdf_model m[] = {ABRDF_F2, ABRDF_F4, ABRDF_FS};
    for (int i = 0; i < 3; ++i) {
        double prev_rel = -1.0, prev_abs = -1.0;
        for (double n = 4.0; n <= 4096.0; n *= 2.0) {
            abrdf_approx_error e = err(m[i], n);
            ck_assert_msg(e.max_rel_pct >= prev_rel - 1e-9 && e.max_abs >= prev_abs - 1e-12,
                          "model %d not monotone at n = %g", (int)m[i], n);
            prev_rel = e.max_rel_pct;
            prev_abs = e.max_abs;
        }
    }
    ck_assert(err(ABRDF_F16, 16.0).max_rel_pct < err(ABRDF_F16, 5.0).max_rel_pct);
    ck_assert(err(ABRDF_F16, 16.0).max_rel_pct < err(ABRDF_F16, 100.0).max_rel_pct);
}
END_TEST

/* The zone: concave core of cos^n (sin^2 = 1/n) within the half-maximum cone. */
START_TEST(zone_definition)
{
    ck_assert(tu_close(abrdf__highlight_zone_cos(2.0), sqrt(0.5), 1e-15, 0.0));
    ck_assert(tu_close(abrdf__highlight_zone_cos(100.0), sqrt(0.99), 1e-15, 0.0));
    ck_assert(tu_close(abrdf__highlight_zone_cos(1.0), 0.5, 1e-15, 0.0));
    ck_assert(tu_close(abrdf__highlight_zone_cos(1.5), pow(0.5, 1 / 1.5), 1e-15, 0.0));
    ck_assert(abrdf__highlight_zone_cos(0.0) == 0.0);
    for (double n = 2.0; n < 1e6; n *= 1.7) /* the half-maximum cone contains the core */
        ck_assert(pow(abrdf__highlight_zone_cos(n), n) >= 0.5 - 1e-12);
}
END_TEST

START_TEST(every_model_every_n_is_finite)
{
    const double ns[] = {0.0, 0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 37.5, 1e3, 1e5, 1e6};
    for (int m = ABRDF_F2; m <= ABRDF_FKUB; ++m)
        for (int i = 0; i < (int)(sizeof ns / sizeof ns[0]); ++i) {
            abrdf_approx_error e = err((abrdf_model)m, ns[i]);
            ck_assert(e.zone_cos >= 0.0 && e.zone_cos <= 1.0);
            ck_assert(e.max_abs <= 1.0 + 1e-12);
        }
}
END_TEST

START_TEST(rejects_bad_arguments)
{
    abrdf_approx_error e;
    ck_assert_int_eq(abrdf_approx_error_eval(ABRDF_F2, 10.0, NULL), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_approx_error_eval(ABRDF_BLINN_PHONG, 10.0, &e), ABRDF_E_MODEL);
    ck_assert_int_eq(abrdf_approx_error_eval(ABRDF_MODEL_COUNT, 10.0, &e), ABRDF_E_MODEL);
    ck_assert_int_eq(abrdf_approx_error_eval(ABRDF_MODEL_NONE, 10.0, &e), ABRDF_E_MODEL);
    ck_assert_int_eq(abrdf_approx_error_eval(ABRDF_F2, -1.0, &e), ABRDF_E_RANGE);
    ck_assert_int_eq(abrdf_approx_error_eval(ABRDF_F2, NAN, &e), ABRDF_E_RANGE);
    ck_assert_int_eq(abrdf_approx_error_eval(ABRDF_F2, INFINITY, &e), ABRDF_E_RANGE);
    ck_assert(e.max_rel_pct == 0.0 && e.max_abs == 0.0);
}
END_TEST

/* The default cost model is the paper's Table 4. */
START_TEST(costs_paper_is_table4)
{
    abrdf_costs c;
    ck_assert_int_eq(abrdf_costs_paper(NULL), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_costs_paper(&c), ABRDF_OK);
    ck_assert(c.unit != NULL);
    ck_assert(abrdf_costs_get(&c, ABRDF_F2) == 8 && abrdf_costs_get(&c, ABRDF_F4) == 11);
    ck_assert(abrdf_costs_get(&c, ABRDF_F8) == 14 && abrdf_costs_get(&c, ABRDF_F16) == 17);
    ck_assert(abrdf_costs_get(&c, ABRDF_FKUB) == 17 && abrdf_costs_get(&c, ABRDF_FKV) == 14);
    ck_assert(abrdf_costs_get(&c, ABRDF_FS) == 15);
    ck_assert(abrdf_costs_get(&c, ABRDF_BLINN_PHONG) < 0);
    ck_assert(abrdf_costs_get(&c, ABRDF_DISNEY_SPECULAR) < 0);
}
END_TEST

/* The cost table's accessors: every id inside its frozen capacity, nothing outside. */
START_TEST(costs_accessors_stay_inside_the_table)
{
    abrdf_costs c;
    ck_assert_int_eq(abrdf_costs_init(NULL, "x"), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_costs_init(&c, "ns/eval"), ABRDF_OK);
    ck_assert_str_eq(c.unit, "ns/eval");
    for (int i = 0; i < ABRDF_COSTS_CAPACITY; ++i)
        ck_assert(abrdf_costs_get(&c, (abrdf_model)i) == -1.0);
    ck_assert_int_eq(abrdf_costs_set(&c, ABRDF_F8, 2.5), ABRDF_OK);
    ck_assert(abrdf_costs_get(&c, ABRDF_F8) == 2.5);
    ck_assert_int_eq(abrdf_costs_set(&c, ABRDF_F8, -3.0), ABRDF_OK); /* unknown again */
    ck_assert(abrdf_costs_get(&c, ABRDF_F8) == -1.0);
    ck_assert_int_eq(abrdf_costs_set(&c, ABRDF_F8, NAN), ABRDF_E_RANGE);
    ck_assert_int_eq(abrdf_costs_set(&c, ABRDF_F8, INFINITY), ABRDF_E_RANGE);
    ck_assert_int_eq(abrdf_costs_set(&c, ABRDF_MODEL_NONE, 1.0), ABRDF_E_MODEL);
    ck_assert_int_eq(abrdf_costs_set(&c, (abrdf_model)ABRDF_COSTS_CAPACITY, 1.0), ABRDF_E_MODEL);
    ck_assert_int_eq(abrdf_costs_set(NULL, ABRDF_F8, 1.0), ABRDF_E_NULL);
    ck_assert(abrdf_costs_get(&c, ABRDF_MODEL_NONE) == -1.0);
    ck_assert(abrdf_costs_get(&c, (abrdf_model)ABRDF_COSTS_CAPACITY) == -1.0);
    ck_assert(abrdf_costs_get(NULL, ABRDF_F8) == -1.0);
    /* Every model of this build has a slot. */
    ck_assert_int_le(abrdf_model_count(), ABRDF_COSTS_CAPACITY);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("approx_error");
    TCase *tc = tcase_create("closed_forms");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, power_form_exact_at_n_equal_m);
    tcase_add_test(tc, schlick_exact_at_the_ends);
    tcase_add_test(tc, f2_at_n4_by_hand);
    tcase_add_test(tc, large_n_limits);
    tcase_add_test(tc, monotone_in_n);
    tcase_add_test(tc, zone_definition);
    tcase_add_test(tc, every_model_every_n_is_finite);
    tcase_add_test(tc, rejects_bad_arguments);
    tcase_add_test(tc, costs_paper_is_table4);
    tcase_add_test(tc, costs_accessors_stay_inside_the_table);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) { return tu_run(suite()); }
