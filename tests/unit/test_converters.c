/* test_converters.c - the roughness converters: documented values (docs/MODELS.md,
 * "Roughness converters"),
 * round trips, the peak match of the Blinn-Phong NDF, clamping of bad input. */
#include <float.h>
#include <math.h>
#include "test_util.h"

static const double PI = 3.14159265358979323846;

START_TEST(documented_values)
{
    ck_assert(tu_close(abrdf_r_to_alpha_g(0.5), 0.25, 1e-15, 0.0));
    ck_assert(tu_close(abrdf_alpha_g_to_r(0.25), 0.5, 1e-15, 0.0));
    ck_assert(tu_close(abrdf_alpha_g_to_n(0.1), 198.0, 1e-13, 0.0)); /* 2/0.01 - 2 */
    ck_assert(tu_close(abrdf_n_to_alpha_g(198.0), 0.1, 1e-15, 0.0));
    ck_assert(tu_close(abrdf_alpha_g_to_n(0.5), 6.0, 1e-15, 0.0));
    ck_assert(abrdf_alpha_g_to_n(1.0) == 0.0);
    ck_assert(abrdf_n_to_alpha_g(0.0) == 1.0);
    /* POV-Ray 3.7's default finish: roughness 0.05 is exponent 20 on N.H. */
    ck_assert(tu_close(abrdf_pov_roughness_to_n(0.05), 20.0, 1e-15, 0.0));
    ck_assert(tu_close(abrdf_n_to_pov_roughness(20.0), 0.05, 1e-15, 0.0));
    /* POV-Ray reads roughness 0 as exponent 0. */
    ck_assert(abrdf_n_to_pov_roughness(0.0) == 0.0);
    ck_assert(abrdf_pov_roughness_to_n(0.0) == 0.0);
}
END_TEST

START_TEST(round_trips)
{
    for (int i = 0; i <= 1000; ++i) {
        double x = i / 1000.0;
        ck_assert(tu_close(abrdf_alpha_g_to_r(abrdf_r_to_alpha_g(x)), x, 1e-15, 0.0));
        double a = fmax(x, 1e-3);
        ck_assert_msg(tu_close(abrdf_n_to_alpha_g(abrdf_alpha_g_to_n(a)), a, 1e-14, 0.0),
                      "alpha_g %g", a);
        double n = pow(10.0, -3.0 + 9.0 * x);
        ck_assert_msg(tu_close(abrdf_alpha_g_to_n(abrdf_n_to_alpha_g(n)), n, 1e-11, 0.0), "n %g",
                      n);
        ck_assert_msg(
            tu_close(abrdf_pov_roughness_to_n(abrdf_n_to_pov_roughness(n)), n, 1e-15, 0.0), "n %g",
            n);
    }
}
END_TEST

/* The mapping n = 2/alpha_g^2 - 2 makes the normalised Blinn-Phong NDF (n + 2)/(2 pi) peak
 * exactly as high as GGX and Beckmann, 1/(pi alpha_g^2) (the "peak ratio" column of
 * docs/MODELS.md, "Roughness converters"). */
START_TEST(blinn_phong_peak_matches)
{
    for (double a = 1e-3; a <= 1.0; a *= 1.1) {
        double n = abrdf_alpha_g_to_n(a);
        ck_assert_msg(tu_close((n + 2.0) / (2.0 * PI), 1.0 / (PI * a * a), 1e-12, 0.0),
                      "alpha_g %g", a);
    }
}
END_TEST

START_TEST(bad_input_is_clamped)
{
    const double bad[] = {NAN, -1.0, -INFINITY, INFINITY, 0.0, 2.0, 1e-320, DBL_MAX};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        double x = bad[i];
        double out[] = {abrdf_r_to_alpha_g(x),       abrdf_alpha_g_to_r(x),
                        abrdf_alpha_g_to_n(x),       abrdf_n_to_alpha_g(x),
                        abrdf_n_to_pov_roughness(x), abrdf_pov_roughness_to_n(x)};
        for (size_t k = 0; k < sizeof out / sizeof out[0]; ++k)
            ck_assert_msg(isfinite(out[k]) && out[k] >= 0.0, "converter %zu of %g gave %g", k, x,
                          out[k]);
    }
    ck_assert(abrdf_r_to_alpha_g(2.0) == 1.0);
    ck_assert(abrdf_r_to_alpha_g(-1.0) == 0.0);
    ck_assert(abrdf_alpha_g_to_n(2.0) == 0.0);
    ck_assert(abrdf_n_to_alpha_g(INFINITY) == 0.0);
    /* POV-Ray holds roughness in single precision: never below FLT_MIN (it would read 0). */
    ck_assert(abrdf_n_to_pov_roughness(1e300) == FLT_MIN);
    ck_assert(abrdf_n_to_pov_roughness(INFINITY) == FLT_MIN);
    ck_assert(abrdf_n_to_pov_roughness(1e-300) == FLT_MAX);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("converters");
    TCase *tc = tcase_create("converters");
    tcase_add_test(tc, documented_values);
    tcase_add_test(tc, round_trips);
    tcase_add_test(tc, blinn_phong_peak_matches);
    tcase_add_test(tc, bad_input_is_clamped);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) { return tu_run(suite()); }
