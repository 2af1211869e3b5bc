/* test_sample_hard.c - abrdf_sample and abrdf_pdf on the hard cases of every model: the
 * parameter extremes of test_grid.c (TG_HARD: r in {0, 1e-8, 1e-4, 1}, n in {0, 1, 1e4,
 * 1e6}, F0 in {0, 1}, every parameter's min and max), grazing and normal view directions,
 * and the ends of the unit interval for u1, u2 (0, 2^-53, 1 - 2^-53, 1) beside random
 * ones. Every pdf (abrdf_sample's and abrdf_pdf's) and weight is finite and non-negative,
 * every wi a unit vector. Samples per model: >= 10^6 for the closed-form
 * models, 4e5 for the layered ones (a layer pass per call), 2e4 for marschner, 300 for
 * huang (its f_r integrates numerically, ~2.5 ms per call); the sanitizer build a tenth.
 * Prints the counts. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_grid.h"
#include "test_util.h"

#define MAX_SETS 96
#ifdef SAMPLE_QUICK
#define SCALE 10
#else
#define SCALE 1
#endif

static long target(const char *name)
{
    if (!strcmp(name, "huang")) return 300 / SCALE;
    if (!strcmp(name, "marschner")) return 20000 / SCALE;
    if (!strcmp(name, "weidlich_wilkie") || !strcmp(name, "belcour")) return 400000 / SCALE;
    return 1000000 / SCALE;
}

START_TEST(hard_cases_stay_finite)
{
    abrdf_model model = (abrdf_model)_i;
    const abrdf_model_info *m = tu_param_model(model);
    if (!m) return;
    static tg_set sets[MAX_SETS];
    int nsets = tg_param_sets(model, TG_HARD, sets, MAX_SETS);
    /* view directions: normal, grazing at 1e-8 and 1e-4 above the surface, ordinary */
    static const double cz[] = {1.0, 1e-8, 1e-4, 0.02, 0.5, 0.9};
    static const double edge_u[] = {0.0, 1.1102230246251565e-16, 0.5, 1.0 - 1.1102230246251565e-16,
                                    1.0};
    const int nwo = (int)(sizeof cz / sizeof *cz), ne = (int)(sizeof edge_u / sizeof *edge_u);
    long want = target(m->name);
    long per = (want + (long)nsets * nwo - 1) / ((long)nsets * nwo);
    if (per < 1) per = 1;
    tg_rng rng = {0xbadc0ffeeull ^ (unsigned long long)model};
    tu_counts w = {0, 0, 0, 0}, pd = {0, 0, 0, 0};
    long samples = 0, none = 0, below = 0, failed = 0, not_unit = 0;
    abrdf_sample_result r;
    abrdf_sample_result_init(&r);
    for (int s = 0; s < nsets; ++s)
        for (int k = 0; k < nwo; ++k) {
            double z = cz[k], sxy = sqrt(1.0 - z * z),
                   ph = 2.0 * 3.14159265358979 * tg_uniform(&rng);
            double wo[3] = {sxy * cos(ph), sxy * sin(ph), z};
            for (long i = 0; i < per; ++i) {
                double u1 = i < ne * ne ? edge_u[i % ne] : tg_uniform(&rng);
                double u2 = i < ne * ne ? edge_u[i / ne] : tg_uniform(&rng);
                /* counters, asserted once below: Check records every passing assertion */
                failed += abrdf_sample(model, &sets[s].p, NULL, wo, u1, u2, &r) != ABRDF_OK;
                ++samples;
                double p3[3] = {r.pdf, r.pdf, r.pdf};
                tu_count(&w, r.weight);
                tu_count(&pd, p3);
                double len = sqrt(r.wi[0] * r.wi[0] + r.wi[1] * r.wi[1] + r.wi[2] * r.wi[2]);
                not_unit += !(fabs(len - 1.0) < 1e-12);
                if (r.pdf == 0.0) {
                    ++none;
                    continue;
                }
                below += r.wi[2] <= 0.0;
                if (i % 16 == 0) { /* abrdf_pdf is finite too (every 16th: it repeats the setup) */
                    double q[3];
                    abrdf_pdf(model, &sets[s].p, NULL, r.wi, wo, &q[0]);
                    q[1] = q[2] = q[0];
                    tu_count(&pd, q);
                }
            }
        }
    printf("%-22s %3d sets, %8ld samples: %ld without a sample, %ld below the surface; "
           "weights NaN %ld Inf %ld negative %ld; pdf NaN %ld Inf %ld negative %ld\n",
           m->name, nsets, samples, none, below, w.nan, w.inf, w.neg, pd.nan, pd.inf, pd.neg);
    ck_assert_msg(failed == 0, "%s: %ld calls failed", m->name, failed);
    ck_assert_msg(not_unit == 0, "%s: %ld directions are not unit vectors", m->name, not_unit);
    ck_assert_msg(w.nan + w.inf + w.neg + pd.nan + pd.inf + pd.neg == 0,
                  "%s: non-finite or negative results (counts above)", m->name);
    ck_assert_int_ge(samples, want);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sample_hard");
    TCase *tc = tcase_create("hard");
    tcase_set_timeout(tc, 0);
    tcase_add_loop_test(tc, hard_cases_stay_finite, 0, abrdf_model_count());
    suite_add_tcase(s, tc);
    return tu_run(s);
}
