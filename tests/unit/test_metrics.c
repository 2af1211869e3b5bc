/* test_metrics.c - NMSE and companions on small hand-computed images; the Table-8 class
 * boundaries (half-open intervals); undefined and non-finite cases. */
#include <math.h>

#include "metrics.h"
#include "test_util.h"

START_TEST(nmse_by_hand)
{
    /* 2x1 RGB. sum R^2 = 1+4+9+16+25+36 = 91; differences 0.5 (R of pixel 0), -1 (B of
     * pixel 1): sse = 1.25, NMSE = 1.25/91, MSE = 1.25/6. */
    float ref[6] = {1, 2, 3, 4, 5, 6};
    float test[6] = {1.5f, 2, 3, 4, 5, 5};
    abrdf_metrics m;
    ck_assert_int_eq(abrdf_metrics_compute(test, ref, 2, 1, 3, &m), ABRDF_METRICS_OK);
    ck_assert(m.nmse_defined);
    ck_assert(tu_close(m.nmse, 1.25 / 91, 1e-15, 0));
    ck_assert(tu_close(m.mse, 1.25 / 6, 1e-15, 0));
    ck_assert(tu_close(m.peak, 6, 0, 0));
    ck_assert(tu_close(m.psnr, 10 * log10(36 * 6 / 1.25), 1e-12, 0));
    ck_assert(tu_close(m.max_abs, 1, 0, 0));
    ck_assert_int_eq(m.max_x, 1);
    ck_assert_int_eq(m.max_y, 0);
    ck_assert_int_eq(m.max_c, 2);
}
END_TEST

START_TEST(nmse_is_not_symmetric)
{
    float a[3] = {1, 1, 1}, b[3] = {2, 2, 2};
    abrdf_metrics ab, ba;
    abrdf_metrics_compute(b, a, 1, 1, 3, &ab); /* reference a */
    abrdf_metrics_compute(a, b, 1, 1, 3, &ba); /* reference b */
    ck_assert(tu_close(ab.nmse, 1.0, 1e-15, 0));
    ck_assert(tu_close(ba.nmse, 0.25, 1e-15, 0));
}
END_TEST

START_TEST(max_pixel_row_and_column)
{
    float ref[4 * 3 * 3] = {0}, test[4 * 3 * 3] = {0};
    ref[0] = 0.5f;
    test[3 * (2 * 4 + 3) + 1] = -0.75f; /* x = 3, y = 2, G */
    abrdf_metrics m;
    ck_assert_int_eq(abrdf_metrics_compute(test, ref, 4, 3, 3, &m), ABRDF_METRICS_OK);
    ck_assert_int_eq(m.max_x, 3);
    ck_assert_int_eq(m.max_y, 2);
    ck_assert_int_eq(m.max_c, 1);
    ck_assert(tu_close(m.max_abs, 0.75, 0, 0));
}
END_TEST

START_TEST(identical_and_black)
{
    float a[3] = {0.3f, 0.2f, 0.1f}, z[3] = {0, 0, 0};
    abrdf_metrics m;
    ck_assert_int_eq(abrdf_metrics_compute(a, a, 1, 1, 3, &m), ABRDF_METRICS_OK);
    ck_assert(m.nmse_defined && m.nmse == 0 && isinf(m.psnr) && m.max_abs == 0);
    ck_assert_str_eq(abrdf_nmse_class(m.nmse), "none");
    ck_assert_int_eq(abrdf_metrics_compute(a, z, 1, 1, 3, &m), ABRDF_METRICS_OK);
    ck_assert(!m.nmse_defined);
    ck_assert(m.nmse == 0);
}
END_TEST

START_TEST(nonfinite_and_bad_args)
{
    float a[6] = {1, 1, 1, 1, 1, 1}, b[6] = {1, 1, 1, 1, NAN, 1};
    abrdf_metrics m;
    ck_assert_int_eq(abrdf_metrics_compute(b, a, 2, 1, 3, &m), ABRDF_METRICS_NONFINITE);
    ck_assert_int_eq(m.max_x, 1);
    ck_assert_int_eq(m.max_c, 1);
    b[4] = INFINITY;
    ck_assert_int_eq(abrdf_metrics_compute(a, b, 2, 1, 3, &m), ABRDF_METRICS_NONFINITE);
    ck_assert_int_eq(abrdf_metrics_compute(a, a, 0, 1, 3, &m), ABRDF_METRICS_BAD_ARGS);
    ck_assert_int_eq(abrdf_metrics_compute(NULL, a, 1, 1, 3, &m), ABRDF_METRICS_BAD_ARGS);
    ck_assert_int_eq(abrdf_metrics_compute(a, a, 1, 1, 3, NULL), ABRDF_METRICS_BAD_ARGS);
}
END_TEST

START_TEST(table8_classes_half_open)
{
    ck_assert_str_eq(abrdf_nmse_class(0), "none");
    ck_assert_str_eq(abrdf_nmse_class(nextafter(1e-4, 0)), "none");
    ck_assert_str_eq(abrdf_nmse_class(1e-4), "slight");
    ck_assert_str_eq(abrdf_nmse_class(nextafter(2.5e-4, 0)), "slight");
    ck_assert_str_eq(abrdf_nmse_class(2.5e-4), "noticeable");
    ck_assert_str_eq(abrdf_nmse_class(nextafter(1e-3, 0)), "noticeable");
    ck_assert_str_eq(abrdf_nmse_class(1e-3), "significant");
    ck_assert_str_eq(abrdf_nmse_class(5), "significant");
    ck_assert_str_eq(abrdf_nmse_class(-1e-9), "undefined");
    ck_assert_str_eq(abrdf_nmse_class(NAN), "undefined");
    ck_assert_str_eq(abrdf_nmse_class_description(2e-4), "slight difference");
    ck_assert_str_eq(abrdf_nmse_class_description(5e-5), "no visible difference");
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("metrics");
    TCase *t = tcase_create("nmse");
    tcase_add_test(t, nmse_by_hand);
    tcase_add_test(t, nmse_is_not_symmetric);
    tcase_add_test(t, max_pixel_row_and_column);
    tcase_add_test(t, identical_and_black);
    tcase_add_test(t, nonfinite_and_bad_args);
    tcase_add_test(t, table8_classes_half_open);
    suite_add_tcase(s, t);
    return s;
}

int main(void) { return tu_run(suite()); }
