/* test_rows.c - abrdf_eval_prepared_rows (interleaved rows) against abrdf_eval_prepared_batch
 * (structure of arrays): the same values bit for bit on the directions made unit by the rows
 * entry's rule (abrdf.h; written out again here as unit_rule), for every model (a measured
 * table too), at every instruction-set level this CPU runs, for counts around the loops' block
 * sizes (32 pairs a vector block, 256 a stack block); degenerate, non-finite and not quite
 * unit rows (on both sides of the rule's tolerance) included, which give f = 0 or their unit
 * row's value; one pair at a time (abrdf_eval_prepared_float) gives the rows' values bit for
 * bit; the status codes of bad calls. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf.h"
#include "abrdf_inline.h"
#include "abrdf_internal.h"
#include "measured_cases.h"
#include "prepared.h"
#include "test_grid.h"
#include "test_util.h"

#define MAXN 600 /* more than two stack blocks */

static float wi[3 * MAXN], wo[3 * MAXN], rows[3 * MAXN + 3]; /* one row more: untouched */
static float ix[MAXN], iy[MAXN], iz[MAXN], ox[MAXN], oy[MAXN], oz[MAXN], fr[MAXN], fg[MAXN],
    fb[MAXN];
static int bad[MAXN];           /* pairs with a zero or non-finite direction: f = 0 */
static int n_between, n_scaled; /* boundary rows kept though the loops' test fails, and scaled */

/* The rule of abrdf.h: a squared length (in double) within 1e-6 of 1 is kept, a zero or
 * non-finite vector is bad (returns 1), any other is scaled by 1 / sqrt(len2) in double and
 * rounded to float. */
static int unit_rule(float *x, float *y, float *z)
{
    double v[3] = {*x, *y, *z};
    double len2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (fabs(len2 - 1.0) <= 1e-6) return 0;
    if (!(len2 > 0.0) || !isfinite(len2)) {
        *x = *y = *z = 0.0f;
        return 1;
    }
    double s = 1.0 / sqrt(len2);
    *x = (float)(v[0] * s), *y = (float)(v[1] * s), *z = (float)(v[2] * s);
    return 0;
}

static double len2_of(const float *v)
{
    return (double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2];
}

/* n pairs: unit directions over the whole sphere (a third below the horizon), runs of pairs
 * sharing wo (the lights of one shading point, which huang groups) that straddle the block
 * edges, and a few degenerate rows: zero, NaN, Inf, tiny, not unit. */
static void make_pairs(int n)
{
    tg_rng rng = {777};
    double o[3] = {0, 0, 1};
    for (int k = 0; k < n; ++k) {
        double i[3];
        tg_sphere(&rng, i);
        if (k % 5 == 0) tg_hemisphere(&rng, o); /* a new view every 5 pairs */
        for (int c = 0; c < 3; ++c) wi[3 * k + c] = (float)i[c], wo[3 * k + c] = (float)o[c];
    }
    static const float odd[][3] = {{0, 0, 0},         {NAN, 0, 1},        {0, INFINITY, 1},
                                   {0, 0, 1e-30f},    {0.3f, 0.2f, 2.0f}, {0, 0, -1},
                                   {1e30f, 0, 1e30f}, {0, -1e-40f, 0}};
    int n_odd = (int)(sizeof odd / sizeof odd[0]);
    for (int j = 0; j < n_odd && 7 * j + 3 < n; ++j) {
        memcpy(wi + 3 * (7 * j + 3), odd[j], sizeof odd[j]);
        memcpy(wo + 3 * (7 * j + 5 < n ? 7 * j + 5 : 7 * j + 3), odd[n_odd - 1 - j], sizeof odd[j]);
    }
    /* the same odd rows again past the first stack block, on a block's edge and in the last
     * pairs (the tail the vector loops leave) */
    const int later[] = {300, 511, 512, n - 40, n - 5};
    for (int j = 0; j < (int)(sizeof later / sizeof later[0]); ++j)
        if (later[j] > 256 && later[j] < n)
            memcpy((j % 2 ? wo : wi) + 3 * later[j], odd[j % n_odd], sizeof odd[0]);
    /* squared lengths 1 + t around the loops' float test (8e-7) and the rule's 1e-6: rows the
     * test cannot pass that the rule keeps, and rows the rule scales (counted; the test
     * rows_make_the_boundary_cases checks that both kinds occur) */
    static const double t[] = {5e-7, -5e-7, 9e-7, -9e-7, 9.5e-7, -9.5e-7, 1.1e-6, -1.1e-6, 3e-6};
    n_between = n_scaled = 0;
    for (int j = 0; j < (int)(sizeof t / sizeof t[0]) && 11 * j + 2 < n; ++j) {
        float *v = (j % 2 ? wo : wi) + 3 * (11 * j + 2);
        double u[3] = {v[0], v[1], v[2]}, r = sqrt((1.0 + t[j]) / len2_of(v));
        for (int c = 0; c < 3; ++c) v[c] = (float)(u[c] * r);
        double d = fabs(len2_of(v) - 1.0);
        n_between += d > 8e-7 + 1.8e-7 - 1e-12 && d <= 1e-6; /* the float test fails them */
        n_scaled += d > 1e-6;
    }
    for (int k = 0; k < n; ++k) {
        ix[k] = wi[3 * k], iy[k] = wi[3 * k + 1], iz[k] = wi[3 * k + 2];
        ox[k] = wo[3 * k], oy[k] = wo[3 * k + 1], oz[k] = wo[3 * k + 2];
        bad[k] = unit_rule(&ix[k], &iy[k], &iz[k]) | unit_rule(&ox[k], &oy[k], &oz[k]);
    }
}

/* rows against batch (on the directions made unit by the rule; f = 0 where one is bad) for a
 * prepared model at every level, for every count; returns the number of differing values (0
 * expected). */
static long compare(const abrdf_prepared *pr, const char *name)
{
    static const int counts[] = {0, 1, 31, 32, 33, 64, 255, 256, 257, 300, 513, MAXN};
    const abrdf__prep *p = abrdf__prep_of(pr);
    ck_assert_ptr_nonnull(p);
    long differ = 0;
    for (int level = 0; level <= abrdf__isa_best(); ++level) {
        for (size_t c = 0; c < sizeof counts / sizeof counts[0]; ++c) {
            int n = counts[c];
            make_pairs(n);
            abrdf_batch b = {(size_t)n, ix, iy, iz, ox, oy, oz, fr, fg, fb};
            ck_assert_int_eq(abrdf__eval_prepared_f_isa(p, &b, level), 0);
            memset(rows, 0xff, sizeof rows); /* NaN: every value must be written */
            ck_assert_int_eq(abrdf__eval_prepared_rows_isa(p, (size_t)n, wi, wo, rows, level), 0);
            for (int k = 0; k < n; ++k) {
                float want[3] = {fr[k], fg[k], fb[k]};
                if (bad[k]) want[0] = want[1] = want[2] = 0.0f;
                if (memcmp(want, rows + 3 * k, sizeof want) == 0) continue;
                if (differ++ < 5)
                    printf("ROWS %s (%s) n=%d pair %d: rows (%.9g %.9g %.9g) batch (%.9g %.9g "
                           "%.9g)\n",
                           name, abrdf__isa_name(level), n, k, rows[3 * k], rows[3 * k + 1],
                           rows[3 * k + 2], want[0], want[1], want[2]);
            }
            ck_assert(isnan(rows[3 * n])); /* nothing written past the last row */
            /* one pair at a time (abrdf_eval_prepared_float's path): the rows' values */
            for (int k = 0; k < n; ++k) {
                float one[3] = {NAN, NAN, NAN};
                ck_assert_int_eq(abrdf__eval_prepared_one_f(p, wi + 3 * k, wo + 3 * k, one, level),
                                 0);
                if (memcmp(one, rows + 3 * k, sizeof one) == 0) continue;
                if (differ++ < 5)
                    printf("ONE %s (%s) pair %d: one (%.9g %.9g %.9g) rows (%.9g %.9g %.9g)\n",
                           name, abrdf__isa_name(level), k, one[0], one[1], one[2], rows[3 * k],
                           rows[3 * k + 1], rows[3 * k + 2]);
            }
        }
    }
    float one[3];
    ck_assert_int_eq(abrdf__eval_prepared_one_f(p, wi, wo, one, abrdf__isa_best() + 1), -1);
    return differ;
}

START_TEST(rows_make_the_boundary_cases)
{
    make_pairs(MAXN);
    printf("boundary rows: %d kept where the float test fails, %d scaled\n", n_between, n_scaled);
    ck_assert_int_ge(n_between, 1);
    ck_assert_int_ge(n_scaled, 2);
}
END_TEST

START_TEST(rows_equal_batch_every_model)
{
    static tg_set sets[2];
    long differ = 0;
    int models = 0;
    for (int mi = 0; mi < abrdf_model_count(); ++mi) {
        const abrdf_model_info *m = tu_param_model(mi);
        if (!m) continue;
        int ns = tg_param_sets(m->id, TG_TYPICAL, sets, 2);
        for (int s = 0; s < ns; ++s) {
            abrdf_prepared pr;
            ck_assert_int_eq(abrdf_prepare(m->id, &sets[s].p, &pr), ABRDF_OK);
            differ += compare(&pr, m->name);
        }
        ++models;
    }
    printf("rows == batch: %d models, %ld values differ\n", models, differ);
    ck_assert_msg(differ == 0, "%ld values of abrdf_eval_prepared_rows differ from the batch",
                  differ);
}
END_TEST

START_TEST(rows_equal_batch_measured)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
    p.r = 0.3;
    mc_table t;
    mc_table_of(&t, 16, 12, 24, ABRDF_LAMBERT, ABRDF_DISNEY_SPECULAR, &p);
    abrdf_prepared pr;
    ck_assert_int_eq(abrdf_prepare_measured(&t.desc, &pr), ABRDF_OK);
    ck_assert_int_eq(compare(&pr, "measured"), 0);
    free(t.data);
}
END_TEST

/* The public call runs the best level: the batch's values, and its status codes. */
START_TEST(rows_public_call)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
    abrdf_prepared pr;
    ck_assert_int_eq(abrdf_prepare(ABRDF_DISNEY_SPECULAR, &p, &pr), ABRDF_OK);
    make_pairs(MAXN);
    abrdf_batch b = {MAXN, ix, iy, iz, ox, oy, oz, fr, fg, fb};
    ck_assert_int_eq(abrdf_eval_prepared_batch(&pr, &b), ABRDF_OK);
    ck_assert_int_eq(abrdf_eval_prepared_rows(&pr, MAXN, wi, wo, rows), ABRDF_OK);
    int n_bad = 0;
    for (int k = 0; k < MAXN; ++k) {
        float want[3] = {fr[k], fg[k], fb[k]};
        if (bad[k]) want[0] = want[1] = want[2] = 0.0f, ++n_bad;
        ck_assert(memcmp(want, rows + 3 * k, sizeof want) == 0);
    }
    ck_assert_int_ge(n_bad, 9); /* zero, NaN and Inf on either side, early and late */
    ck_assert_int_eq(abrdf_eval_prepared_rows(NULL, 1, wi, wo, rows), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_eval_prepared_rows(&pr, 1, NULL, wo, rows), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_eval_prepared_rows(&pr, 1, wi, NULL, rows), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_eval_prepared_rows(&pr, 1, wi, wo, NULL), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_eval_prepared_rows(&pr, 0, NULL, NULL, NULL), ABRDF_OK);
    /* one pair: the rows' value, bit for bit (the best level); its status codes */
    for (int k = 0; k < MAXN; ++k) {
        float one[3];
        ck_assert_int_eq(abrdf_eval_prepared_float(&pr, wi + 3 * k, wo + 3 * k, one), ABRDF_OK);
        ck_assert(memcmp(one, rows + 3 * k, sizeof one) == 0);
    }
    float one[3] = {1, 1, 1};
    ck_assert_int_eq(abrdf_eval_prepared_float(NULL, wi, wo, one), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_eval_prepared_float(&pr, NULL, wo, one), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_eval_prepared_float(&pr, wi, NULL, one), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_eval_prepared_float(&pr, wi, wo, NULL), ABRDF_E_NULL);
    /* an object abrdf_prepare never filled: ABRDF_E_MODEL and f = 0 */
    abrdf_prepared junk;
    memset(&junk, 0xa5, sizeof junk);
    rows[0] = rows[1] = rows[2] = 1.0f;
    ck_assert_int_eq(abrdf_eval_prepared_rows(&junk, 1, wi, wo, rows), ABRDF_E_MODEL);
    ck_assert(rows[0] == 0.0f && rows[1] == 0.0f && rows[2] == 0.0f);
    ck_assert_int_eq(abrdf_eval_prepared_float(&junk, wi, wo, one), ABRDF_E_MODEL);
    ck_assert(one[0] == 0.0f && one[1] == 0.0f && one[2] == 0.0f);
}
END_TEST

/* abrdf_inline.h: the inlined GGX lobe is abrdf_eval_prepared_float's value, bit for bit, on
 * unit directions (this file is compiled without FMA contraction, as the library): random
 * pairs, back-facing ones, wi = -wo, the mirror at grazing angles, at the roughness floor and
 * in between, colours of F0; and its status codes. */
START_TEST(inline_ggx_equals_the_float_call)
{
    static const double rs[] = {0.0, 1e-3, 0.05, 0.3, 0.7, 1.0};
    unsigned s = 777u;
    long same = 0, nonzero = 0;
    for (int ri = 0; ri < 6; ++ri) {
        abrdf_params p;
        abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
        p.r = rs[ri];
        p.ks[0] = 0.9, p.ks[1] = 0.5, p.ks[2] = 0.2;
        p.f0[0] = 0.04, p.f0[1] = 0.5, p.f0[2] = 1.0;
        abrdf_prepared pr;
        ck_assert_int_eq(abrdf_prepare(ABRDF_DISNEY_SPECULAR, &p, &pr), ABRDF_OK);
        abrdf_ggx_float lobe;
        ck_assert_int_eq(abrdf_prepared_ggx_float(&pr, &lobe), ABRDF_OK);
        for (int k = 0; k < 20000; ++k) {
            float w[2][3];
            for (int v = 0; v < 2; ++v) {
                double u1 = (double)((s = s * 1103515245u + 12345u) >> 8) / 16777216.0;
                double u2 = (double)((s = s * 1103515245u + 12345u) >> 8) / 16777216.0;
                double z = 1.9 * u1 - 0.9, q = sqrt(1.0 - z * z);
                w[v][0] = (float)(q * cos(6.283185307179586 * u2));
                w[v][1] = (float)(q * sin(6.283185307179586 * u2));
                w[v][2] = (float)z;
            }
            if (k % 5 == 0) { /* the mirror pair, down to grazing */
                double c = pow(10.0, -6.0 * (double)((k / 5) % 100) / 99.0);
                w[0][0] = (float)sqrt(1.0 - c * c), w[0][1] = 0.0f, w[0][2] = (float)c;
                w[1][0] = -w[0][0], w[1][1] = 0.0f, w[1][2] = w[0][2];
            }
            if (k % 97 == 0) /* wi = -wo */
                w[1][0] = -w[0][0], w[1][1] = -w[0][1], w[1][2] = -w[0][2];
            float want[3], got[3];
            ck_assert_int_eq(abrdf_eval_prepared_float(&pr, w[0], w[1], want), ABRDF_OK);
            abrdf_ggx_float_eval(&lobe, w[0], w[1], got);
            if (memcmp(want, got, sizeof got) != 0)
                ck_abort_msg("r %g pair %d: inline (%.9g, %.9g, %.9g), float call (%.9g, %.9g, "
                             "%.9g)",
                             rs[ri], k, got[0], got[1], got[2], want[0], want[1], want[2]);
            ++same;
            nonzero += got[0] > 0.0f;
        }
    }
    ck_assert_int_gt(nonzero, same / 4);
    abrdf_ggx_float lobe;
    abrdf_prepared pr;
    lobe.ks_f0[0] = 1.0f;
    ck_assert_int_eq(abrdf_prepared_ggx_float(NULL, &lobe), ABRDF_E_NULL);
    ck_assert(lobe.ks_f0[0] == 0.0f && lobe.alpha_g == 0.0f); /* zeroed on every failure */
    abrdf_params p;
    abrdf_params_init(ABRDF_COOK_TORRANCE, &p);
    ck_assert_int_eq(abrdf_prepare(ABRDF_COOK_TORRANCE, &p, &pr), ABRDF_OK);
    ck_assert_int_eq(abrdf_prepared_ggx_float(&pr, NULL), ABRDF_E_NULL);
    lobe.ks_f0[0] = 1.0f;
    ck_assert_int_eq(abrdf_prepared_ggx_float(&pr, &lobe), ABRDF_E_MODEL);
    const float up[3] = {0.0f, 0.0f, 1.0f};
    float f[3];
    abrdf_ggx_float_eval(&lobe, up, up, f); /* a zeroed lobe evaluates to 0 */
    ck_assert(f[0] == 0.0f && f[1] == 0.0f && f[2] == 0.0f);
    memset(&pr, 0xa5, sizeof pr);
    ck_assert_int_eq(abrdf_prepared_ggx_float(&pr, &lobe), ABRDF_E_MODEL);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("rows");
    TCase *tc = tcase_create("rows");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, rows_make_the_boundary_cases);
    tcase_add_test(tc, rows_equal_batch_every_model);
    tcase_add_test(tc, rows_equal_batch_measured);
    tcase_add_test(tc, rows_public_call);
    tcase_add_test(tc, inline_ggx_equals_the_float_call);
    suite_add_tcase(s, tc);
    return tu_run(s);
}
