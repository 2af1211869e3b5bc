/* test_sample_chi2.c - every model's sampler draws what its pdf says: Pearson's chi-square
 * goodness of fit of sampled directions against the pdf integrated over the cells of a
 * (theta, phi) grid of the whole sphere (as pbrt-v4's and Mitsuba 3's sampling tests do),
 * per model, for the sets of sample_cases.c and two view directions; and the pdf integrates
 * to 1 over the sphere (directions below the surface included: a sampler may return them,
 * with weight 0, and they are counted like the others).
 *
 * The directions come from the library's internal sampler (abrdf__mixture_sample), the
 * directions abrdf_sample returns (test_sample.c proves they are the same), without the
 * evaluation of f_r that abrdf_sample adds for the weight: so the slow hair models afford
 * as many samples as the others. Deterministic seeds; significance 1% over all the tests
 * of the suite together (Bonferroni: each test at 0.01 / SC_TESTS_BOUND). Cells expecting
 * fewer than 5 samples are pooled into one. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sample.h"
#include "sample_cases.h"
#include "sample_stats.h"
#include "test_grid.h"
#include "test_util.h"

#define NTHETA 24
#define NPHI 48
#ifndef SC_SAMPLES
#define SC_SAMPLES 100000 /* per test; the sanitizer build sets fewer (CMakeLists.txt) */
#endif
#define SC_TESTS_BOUND 400 /* >= the number of chi-square tests (checked) */
#define SC_ALPHA 0.01

static int tests_run;

static double pdf_fn(void *ctx, const double w[3])
{
    return abrdf__mixture_pdf((const abrdf__mixture *)ctx, w);
}

/* One chi-square test; returns 1 if it passes. */
static int chi2_case(abrdf_model model, const sc_set *set, const double wo[3], unsigned long seed)
{
    const char *name = abrdf_model_get(model)->name;
    abrdf__mixture mx;
    abrdf__mixture_setup(model, &set->p, wo, &mx);
    ss_grid g;
    double pole[3], warp;
    sc_pole(model, wo, pole, &warp);
    ss_grid_make(&g, pole, NTHETA, NPHI, warp);
    static double expected[NTHETA * NPHI], observed[NTHETA * NPHI];
    long evals = 0;
    double total = ss_integrate(&g, pdf_fn, &mx, 1e-8, 1e-5, 4, expected, &evals);
    memset(observed, 0, sizeof observed);
    tg_rng rng = {0x2545f4914f6cdd1dull ^ seed};
    long below = 0;
    for (long i = 0; i < SC_SAMPLES; ++i) {
        double wi[3], u1 = tg_uniform(&rng), u2 = tg_uniform(&rng);
        abrdf__mixture_sample(&mx, u1, u2, wi);
        observed[ss_cell(&g, wi)] += 1.0;
        below += wi[2] <= 0.0;
    }
    for (int i = 0; i < NTHETA * NPHI; ++i) expected[i] *= SC_SAMPLES;
    double p;
    int dof;
    double chi2 = ss_chi2(observed, expected, NTHETA * NPHI, 5.0, &p, &dof);
    ++tests_run;
    int ok = p >= SC_ALPHA / SC_TESTS_BOUND && fabs(total - 1.0) < 1e-3;
    if (!ok || getenv("ABRDF_TEST_VERBOSE"))
        printf("%-22s %-20s wo=(%.3f,%.3f,%.3f) integral %.6f chi2 %.1f dof %d p %.3g "
               "below %.4f evals %ld%s\n",
               name, set->label, wo[0], wo[1], wo[2], total, chi2, dof, p,
               (double)below / SC_SAMPLES, evals, ok ? "" : "  FAIL");
    return ok;
}

/* 1 if the sampler of set b draws what the sampler of set a draws for these wo (the same
 * density at 64 directions and for both view directions): a parameter the sampler does not
 * read (kd of a cosine, f0 of a lobe), whose chi-square test would repeat a's. */
static int same_sampler(abrdf_model model, const sc_set *a, const sc_set *b, double wos[2][3])
{
    tg_rng rng = {99};
    for (int w = 0; w < 2; ++w) {
        abrdf__mixture ma, mb;
        abrdf__mixture_setup(model, &a->p, wos[w], &ma);
        abrdf__mixture_setup(model, &b->p, wos[w], &mb);
        for (int i = 0; i < 64; ++i) {
            double d[3];
            tg_sphere(&rng, d);
            if (abrdf__mixture_pdf(&ma, d) != abrdf__mixture_pdf(&mb, d)) return 0;
        }
    }
    return 1;
}

START_TEST(chi2_every_model)
{
    abrdf_model model = (abrdf_model)_i;
    if (!tu_param_model(model)) return;
    static sc_set sets[SC_MAX_SETS];
    int n = sc_param_sets(model, sets);
    double wos[2][3];
    tu_dir(30.0, 40.0, wos[0]);
    tu_dir(75.0, 200.0, wos[1]);
    int failed = 0;
    for (int s = 0; s < n; ++s) {
        if (s > 0 && same_sampler(model, &sets[0], &sets[s], wos)) continue;
        for (int w = 0; w < 2; ++w)
            failed +=
                !chi2_case(model, &sets[s], wos[w], (unsigned long)(model * 1000 + s * 10 + w));
    }
    ck_assert_msg(failed == 0, "%s: %d chi-square test(s) failed (lines above)",
                  abrdf_model_get(model)->name, failed);
    ck_assert_int_le(tests_run, SC_TESTS_BOUND);
}
END_TEST

/* The test can fail: a sampler drawing from a density 10% wider than its pdf says. */
static double wider_pdf(void *ctx, const double w[3])
{
    (void)ctx;
    return w[2] > 0.0 ? w[2] / 3.14159265358979323846 : 0.0;
}

START_TEST(chi2_rejects_a_wrong_density)
{
    /* draws cos^1.2 / normalisation, tested against cos/pi */
    ss_grid g;
    double pole[3] = {0, 0, 1};
    ss_grid_make(&g, pole, NTHETA, NPHI, 1.0);
    static double expected[NTHETA * NPHI], observed[NTHETA * NPHI];
    ss_integrate(&g, wider_pdf, NULL, 1e-10, 1e-7, 4, expected, NULL);
    memset(observed, 0, sizeof observed);
    tg_rng rng = {12345};
    const long n = 100000; /* fixed: the sanitizer build's SC_SAMPLES has too little power */
    for (long i = 0; i < n; ++i) {
        double c = pow(1.0 - tg_uniform(&rng), 1.0 / 2.2), s = sqrt(1.0 - c * c);
        double ph = 2.0 * 3.14159265358979323846 * tg_uniform(&rng);
        double w[3] = {s * cos(ph), s * sin(ph), c};
        observed[ss_cell(&g, w)] += 1.0;
    }
    for (int i = 0; i < NTHETA * NPHI; ++i) expected[i] *= n;
    double p;
    int dof;
    ss_chi2(observed, expected, NTHETA * NPHI, 5.0, &p, &dof);
    ck_assert_msg(p < SC_ALPHA / SC_TESTS_BOUND, "a wrong density passed: p = %g", p);
}
END_TEST

START_TEST(gamma_q_matches_known_values)
{
    /* chi-square survival function: Q(k/2, x/2) */
    ck_assert(tu_close(ss_gamma_q(0.5, 0.5 * 3.841458820694124), 0.05, 1e-9, 0.0));
    ck_assert(tu_close(ss_gamma_q(5.0, 0.5 * 23.20925115551), 0.01, 1e-8, 0.0));
    ck_assert(tu_close(ss_gamma_q(500.0, 500.0), 0.4940533, 1e-5, 0.0));
    ck_assert(tu_close(ss_gamma_q(1.0, 2.0), exp(-2.0), 1e-12, 0.0));
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sample_chi2");
    TCase *tc = tcase_create("chi2");
    tcase_set_timeout(tc, 0);
    tcase_add_test(tc, gamma_q_matches_known_values);
    tcase_add_test(tc, chi2_rejects_a_wrong_density);
    tcase_add_loop_test(tc, chi2_every_model, 0, abrdf_model_count());
    suite_add_tcase(s, tc);
    return tu_run(s);
}
