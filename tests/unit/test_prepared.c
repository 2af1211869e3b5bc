/* test_prepared.c - the prepared-evaluation contract (abrdf.h, "prepared evaluation"): a
 * frozen plain-data object that owns a copy of its parameters, refuses what abrdf_eval
 * refuses, and a block that was never prepared evaluates to 0 with ABRDF_E_MODEL. That it
 * returns the unprepared results bit for bit is test_invariants' prepared_equals_unprepared;
 * the stability grid runs through it (test_stability). Also: the expensive reference models
 * still give the values their code gave before it was made faster
 * (tests/data/special_reference.txt, tools/gen/gen_special_reference.c). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf.h"
#include "test_util.h"

START_TEST(layout_is_frozen)
{
    ck_assert_uint_eq(sizeof(abrdf_prepared), ABRDF_PREPARED_SIZE);
    ck_assert_int_eq(ABRDF_PREPARED_SIZE, 2048);
}
END_TEST

START_TEST(owns_a_copy_of_its_parameters)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
    p.r = 0.3;
    abrdf_prepared a;
    ck_assert_int_eq(abrdf_prepare(ABRDF_DISNEY_SPECULAR, &p, &a), ABRDF_OK);
    const double wi[3] = {0.3, 0.0, 1.0}, wo[3] = {-0.2, 0.1, 1.0};
    double f0[3], f1[3], f2[3];
    ck_assert_int_eq(abrdf_eval(ABRDF_DISNEY_SPECULAR, &p, NULL, wi, wo, f0), ABRDF_OK);
    p.r = 0.9; /* the caller's block changes after prepare: the object keeps r = 0.3 */
    memset(&p.ks, 0, sizeof p.ks);
    ck_assert_int_eq(abrdf_eval_prepared(&a, NULL, wi, wo, f1), ABRDF_OK);
    ck_assert(memcmp(f0, f1, sizeof f0) == 0);
    ck_assert(f1[0] > 0.0);
    ck_assert_double_eq(abrdf_prepared_params(&a)->r, 0.3);
    ck_assert_uint_eq(abrdf_prepared_params(&a)->struct_size, sizeof(abrdf_params));
    /* a byte copy in other memory, the original overwritten: still the same object */
    unsigned char *heap = malloc(sizeof a);
    ck_assert_ptr_nonnull(heap);
    memcpy(heap, &a, sizeof a);
    memset(&a, 0xff, sizeof a);
    abrdf_prepared b;
    memcpy(&b, heap, sizeof b);
    free(heap);
    ck_assert_int_eq(abrdf_prepared_model(&b), ABRDF_DISNEY_SPECULAR);
    ck_assert_int_eq(abrdf_eval_prepared(&b, NULL, wi, wo, f2), ABRDF_OK);
    ck_assert(memcmp(f0, f2, sizeof f0) == 0);
}
END_TEST

START_TEST(not_prepared_evaluates_to_zero)
{
    const double wi[3] = {0, 0, 1}, wo[3] = {0, 0, 1};
    float x[1] = {0}, y[1] = {0}, z[1] = {1}, fr[1] = {NAN}, fg[1] = {NAN}, fb[1] = {NAN};
    abrdf_batch b = {1, x, y, z, x, y, z, fr, fg, fb};
    abrdf_prepared zero, junk;
    memset(&zero, 0, sizeof zero);
    memset(&junk, 0x5a, sizeof junk);
    const abrdf_prepared *blocks[2] = {&zero, &junk};
    for (int k = 0; k < 2; ++k) {
        double f[3] = {NAN, NAN, NAN};
        ck_assert_int_eq(abrdf_eval_prepared(blocks[k], NULL, wi, wo, f), ABRDF_E_MODEL);
        ck_assert(f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0);
        ck_assert_int_eq(abrdf_eval_prepared_batch(blocks[k], &b), ABRDF_E_MODEL);
        ck_assert(fr[0] == 0.0f && fg[0] == 0.0f && fb[0] == 0.0f);
        ck_assert_int_eq(abrdf_prepared_model(blocks[k]), ABRDF_MODEL_NONE);
        ck_assert_ptr_null(abrdf_prepared_params(blocks[k]));
    }
    /* NULLs and an unknown model */
    abrdf_params p;
    abrdf_params_init(ABRDF_LAMBERT, &p);
    abrdf_prepared a;
    double f[3];
    ck_assert_int_eq(abrdf_prepare(ABRDF_LAMBERT, NULL, &a), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_prepared_model(&a), ABRDF_MODEL_NONE);
    ck_assert_int_eq(abrdf_prepare(ABRDF_LAMBERT, &p, NULL), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_prepare(ABRDF_MODEL_COUNT, &p, &a), ABRDF_E_MODEL);
    ck_assert_int_eq(abrdf_prepare(ABRDF_MODEL_NONE, &p, &a), ABRDF_E_MODEL);
    ck_assert_int_eq(abrdf_eval_prepared(&a, NULL, wi, wo, f), ABRDF_E_MODEL);
    ck_assert_int_eq(abrdf_prepared_model(NULL), ABRDF_MODEL_NONE);
    ck_assert_int_eq(abrdf_eval_prepared(NULL, NULL, wi, wo, f), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_eval_prepared_batch(NULL, &b), ABRDF_E_NULL);
    p.struct_size = 0; /* never initialised */
    ck_assert_int_eq(abrdf_prepare(ABRDF_LAMBERT, &p, &a), ABRDF_E_SIZE);
    ck_assert_int_eq(abrdf_prepared_model(&a), ABRDF_MODEL_NONE);
}
END_TEST

/* ---- the expensive references keep their values ---------------------------------------- */

/* A prepared object is plain data that names its model: objects of every model,
 * byte-copied in reverse order into other memory with the originals overwritten, evaluate
 * as abrdf_eval of their own model (abrdf_eval_prepared bit for bit, the unit entry up to
 * rounding), and give 0 for a back-facing pair. */
START_TEST(copies_keep_their_model)
{
    enum { N = ABRDF_MODEL_COUNT };
    abrdf_prepared *orig = malloc(N * sizeof *orig), *copy = malloc(N * sizeof *copy);
    abrdf_params *par = malloc(N * sizeof *par);
    ck_assert(orig && copy && par);
    int ids[N], n = 0;
    for (int mi = 0; mi < abrdf_model_count() && mi < N; ++mi) {
        if (!tu_param_model(mi)) continue;
        abrdf_params_init((abrdf_model)mi, &par[n]);
        ck_assert_int_eq(abrdf_prepare((abrdf_model)mi, &par[n], &orig[n]), ABRDF_OK);
        ids[n++] = mi;
    }
    ck_assert_int_gt(n, 20);
    for (int k = 0; k < n; ++k) memcpy(&copy[n - 1 - k], &orig[k], sizeof orig[k]);
    memset(orig, 0xff, (size_t)n * sizeof *orig);
    const double s = 1.0 / sqrt(3.0);
    const double wi[3] = {0.6, 0.0, 0.8}, wo[3] = {-s, s, s}, back[3] = {0.0, 0.6, -0.8};
    for (int k = 0; k < n; ++k) {
        const abrdf_prepared *c = &copy[n - 1 - k];
        ck_assert_int_eq(abrdf_prepared_model(c), ids[k]);
        double want[3], got[3], got_u[3], zero[3];
        ck_assert_int_eq(abrdf_eval((abrdf_model)ids[k], &par[k], NULL, wi, wo, want), ABRDF_OK);
        ck_assert_int_eq(abrdf_eval_prepared(c, NULL, wi, wo, got), ABRDF_OK);
        ck_assert_int_eq(abrdf_eval_prepared_unit(c, wi, wo, got_u), ABRDF_OK);
        ck_assert_msg(memcmp(want, got, sizeof want) == 0, "%s", abrdf_model_get(ids[k])->name);
        for (int ch = 0; ch < 3; ++ch) /* the unit entry: up to rounding (abrdf.h) */
            ck_assert_msg(fabs(got_u[ch] - want[ch]) <= 1e-12 * want[ch], "%s",
                          abrdf_model_get(ids[k])->name);
        ck_assert_int_eq(abrdf_eval_prepared_unit(c, back, wo, zero), ABRDF_OK);
        ck_assert(zero[0] == 0.0 && zero[1] == 0.0 && zero[2] == 0.0);
    }
    free(orig);
    free(copy);
    free(par);
}
END_TEST

/* A block whose head (the library's mark and model id, its first 8 bytes) is a prepared
 * object's and whose rest is stale never makes the library jump or read outside it: it
 * evaluates to a finite f >= 0, and a model id beyond the library's is "not prepared". */
START_TEST(stale_blocks_are_safe)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_LAMBERT, &p);
    abrdf_prepared good, stale;
    ck_assert_int_eq(abrdf_prepare(ABRDF_LAMBERT, &p, &good), ABRDF_OK);
    const double wi[3] = {0.0, 0.6, 0.8}, wo[3] = {0.6, 0.0, 0.8};
    double f[3];
    memset(&stale, 0x41, sizeof stale);
    memcpy(&stale, &good, 8);
    ck_assert_int_eq(abrdf_prepared_model(&stale), ABRDF_LAMBERT);
    ck_assert_int_eq(abrdf_eval_prepared_unit(&stale, wi, wo, f), ABRDF_OK);
    ck_assert_int_eq(abrdf_eval_prepared(&stale, NULL, wi, wo, f), ABRDF_OK);
    for (int c = 0; c < 3; ++c) ck_assert(isfinite(f[c]) && f[c] >= 0.0);
    memset(&stale, 0x41, sizeof stale);
    memcpy(&stale, &good, 4); /* the mark, then an id of no model */
    ck_assert_int_eq(abrdf_prepared_model(&stale), ABRDF_MODEL_NONE);
    ck_assert_int_eq(abrdf_eval_prepared_unit(&stale, wi, wo, f), ABRDF_E_MODEL);
    ck_assert(f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0);
}
END_TEST

/* abrdf_eval_prepared_unit against abrdf_eval_prepared for model m with parameters p on
 * wi, wo: within rel (hair and layered models: the same bits). Counts same-bit results. */
static void unit_vs_prepared(abrdf_model m, const abrdf_params *p, const double wi[3],
                             const double wo[3], double rel, long *compared, long *exact)
{
    abrdf_prepared prep;
    ck_assert_int_eq(abrdf_prepare(m, p, &prep), ABRDF_OK);
    double want[3], got[3];
    ck_assert_int_eq(abrdf_eval_prepared(&prep, NULL, wi, wo, want), ABRDF_OK);
    ck_assert_int_eq(abrdf_eval_prepared_unit(&prep, wi, wo, got), ABRDF_OK);
    int special = m == ABRDF_MARSCHNER || m == ABRDF_HUANG || m == ABRDF_WEIDLICH_WILKIE ||
                  m == ABRDF_BELCOUR; /* always the checked path */
    for (int c = 0; c < 3; ++c) {
        ck_assert(isfinite(got[c]) && got[c] >= 0.0);
        if (special)
            ck_assert_msg(got[c] == want[c], "%s: %.17g vs %.17g", abrdf_model_get(m)->name, got[c],
                          want[c]);
        else
            ck_assert_msg(fabs(got[c] - want[c]) <= rel * fabs(want[c]) + 1e-300,
                          "%s: %.17g vs %.17g", abrdf_model_get(m)->name, got[c], want[c]);
        *exact += got[c] == want[c];
        ++*compared;
    }
}

/* abrdf_eval_prepared_unit: every model on unit directions (above, below, grazing), on
 * vectors normalised in float (taken to the checked path), a non-unit, a tiny and a
 * non-finite one: abrdf_eval_prepared's value up to rounding; the exponent models at n = 1e4
 * too; the status codes. */
START_TEST(unit_entry_is_the_prepared_value)
{
    const double dirs[][3] = {{0.3, -0.2, 0.93},     {-0.5, 0.4, 0.3}, {0.0, 0.0, 1.0},
                              {0.99, 0.0, 0.01},     {0.2, 0.3, -0.9}, {2.0, 1.0, 3.0},
                              {1e-200, 0.0, 1e-200}, {NAN, 0.0, 1.0}};
    const int nd = (int)(sizeof dirs / sizeof dirs[0]);
    double v[8][3];
    for (int i = 0; i < nd; ++i) { /* unit in double, except the last three */
        double l =
            sqrt(dirs[i][0] * dirs[i][0] + dirs[i][1] * dirs[i][1] + dirs[i][2] * dirs[i][2]);
        for (int c = 0; c < 3; ++c) v[i][c] = i < nd - 3 ? dirs[i][c] / l : dirs[i][c];
    }
    for (int c = 0; c < 3; ++c) v[3][c] *= 1.0 + 4e-7; /* as a float normalisation leaves it */
    long compared = 0, exact = 0;
    for (int mi = 0; mi < abrdf_model_count(); ++mi) {
        if (!tu_param_model(mi)) continue;
        abrdf_model m = (abrdf_model)mi;
        abrdf_params p;
        abrdf_params_init(m, &p);
        for (int i = 0; i < nd; ++i)
            for (int o = 0; o < nd; ++o)
                unit_vs_prepared(m, &p, v[i], v[o], 1e-12, &compared, &exact);
    }
    const abrdf_model sharp[] = {ABRDF_PHONG, ABRDF_BLINN_PHONG, ABRDF_F_2E, ABRDF_F_GE};
    for (int k = 0; k < 4; ++k) {
        abrdf_params p;
        abrdf_params_init(sharp[k], &p);
        p.n = 1e4;
        for (int i = 0; i < 3; ++i) /* near the mirror direction, where cos^n is large */
            unit_vs_prepared(sharp[k], &p, v[i], (double[3]){-v[i][0], -v[i][1], v[i][2]}, 1e-11,
                             &compared, &exact);
    }
    ck_assert_int_gt(exact, compared / 2); /* most are the same bits */
    abrdf_prepared none;
    memset(&none, 0, sizeof none);
    double u[3] = {0, 0, 1}, f[3] = {1, 1, 1};
    ck_assert_int_eq(abrdf_eval_prepared_unit(&none, u, u, f), ABRDF_E_MODEL);
    ck_assert(f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0);
    abrdf_prepared prep;
    abrdf_params p;
    abrdf_params_init(ABRDF_LAMBERT, &p);
    ck_assert_int_eq(abrdf_prepare(ABRDF_LAMBERT, &p, &prep), ABRDF_OK);
    f[0] = 1.0;
    ck_assert_int_eq(abrdf_eval_prepared_unit(&prep, NULL, u, f), ABRDF_E_NULL);
    ck_assert(f[0] == 0.0);
    ck_assert_int_eq(abrdf_eval_prepared_unit(&prep, u, u, NULL), ABRDF_E_NULL);
}
END_TEST

START_TEST(special_models_keep_their_values)
{
    FILE *in = fopen(ABRDF_TEST_SPECIAL_REFERENCE, "r");
    ck_assert_msg(in != NULL, "cannot read %s", ABRDF_TEST_SPECIAL_REFERENCE);
    char line[1024];
    long n = 0, bad = 0;
    double worst = 0.0;
    while (fgets(line, sizeof line, in)) {
        if (line[0] == '#') continue;
        char name[64];
        int set, k;
        double wi[3], wo[3], want[3], got[3];
        ck_assert_int_eq(sscanf(line, "%63s %d %d %lf %lf %lf %lf %lf %lf %lf %lf %lf", name, &set,
                                &k, &wi[0], &wi[1], &wi[2], &wo[0], &wo[1], &wo[2], &want[0],
                                &want[1], &want[2]),
                         12);
        abrdf_model m;
        ck_assert_int_eq(abrdf_model_find(name, &m), ABRDF_OK);
        /* the file names the parameter sets in its header; re-read them from there */
        static abrdf_params sets[64];
        static int have[64];
        ck_assert(set >= 0 && set < 64);
        if (!have[set]) {
            FILE *h = fopen(ABRDF_TEST_SPECIAL_REFERENCE, "r");
            char hl[1024];
            abrdf_params_init(m, &sets[set]);
            while (fgets(hl, sizeof hl, h) && hl[0] == '#') {
                int s;
                char rest[900];
                if (sscanf(hl, "#   %d %*[^:]: %899[^\n]", &s, rest) != 2 || s != set) continue;
                for (char *tok = strtok(rest, " "); tok; tok = strtok(NULL, " ")) {
                    char pn[64];
                    double v;
                    int id;
                    if (!strcmp(tok, "defaults")) continue;
                    ck_assert_int_eq(sscanf(tok, "%63[^=]=%lf", pn, &v), 2);
                    ck_assert_int_eq(abrdf_param_find(pn, &id), ABRDF_OK);
                    double vv[3] = {v, v, v};
                    int cnt = abrdf_param_get(id)->kind == ABRDF_PARAM_RGB ? 3 : 1;
                    ck_assert_int_eq(abrdf_param_set(&sets[set], id, vv, cnt), ABRDF_OK);
                }
            }
            fclose(h);
            have[set] = 1;
        }
        abrdf_prepared prep;
        ck_assert_int_eq(abrdf_prepare(m, &sets[set], &prep), ABRDF_OK);
        ck_assert_int_eq(abrdf_eval_prepared(&prep, NULL, wi, wo, got), ABRDF_OK);
        for (int c = 0; c < 3; ++c) {
            double d = fabs(got[c] - want[c]) / fmax(fabs(want[c]), 1e-300);
            if (got[c] == want[c]) d = 0.0;
            worst = fmax(worst, d);
            if (d > 1e-10 && bad++ < 8)
                printf("CHANGED %s set %d pair %d channel %d: %.17g, was %.17g\n", name, set, k, c,
                       got[c], want[c]);
        }
        ++n;
    }
    fclose(in);
    printf("special references: %ld pairs, largest relative change %.3g (tolerance 1e-10)\n", n,
           worst);
    ck_assert_int_eq(n, 480);
    ck_assert_msg(bad == 0, "%ld values moved by more than 1e-10 relative", bad);
}
END_TEST

/* The float batch of marschner and belcour normalises a block's directions in one loop with
 * abrdf__normalise3_unit's arithmetic (eval_float.c): every pair's float result is the one it
 * gets alone (a batch of one pair takes the one-by-one path), bit for bit, in full blocks, in
 * the tail, for rows of length 0.5-2 (the block's), outside it, zero and NaN. (A change of
 * 1e-6 in the block's normalisation fails it; one of a few ulp of double does not reach the
 * float results.) */
START_TEST(special_batch_blocks_equal_single_pairs)
{
    enum { N = 150 }; /* two blocks of 64 and a tail of 22 */
    static const double len[] = {1.0, 1.0 + 1e-7, 0.6, 1.9, 0.45, 2.2, 1.0, 0.0};
    float d[6][N], f[3][N], g[3];
    unsigned s = 12345u;
    for (int i = 0; i < N; ++i)
        for (int v = 0; v < 2; ++v) {
            double th = 1.5 * (double)((s = s * 1103515245u + 12345u) >> 8) / 16777216.0;
            double ph = 6.2831853 * (double)((s = s * 1103515245u + 12345u) >> 8) / 16777216.0;
            double l = len[(i + v) % 8];
            d[3 * v][i] = (float)(l * sin(th) * cos(ph));
            d[3 * v + 1][i] = (float)(l * sin(th) * sin(ph));
            d[3 * v + 2][i] = (float)(l * cos(th));
        }
    d[0][77] = NAN;
    d[5][130] = -0.5f; /* below the surface */
    static const abrdf_model models[] = {ABRDF_MARSCHNER, ABRDF_BELCOUR};
    for (int k = 0; k < 2; ++k) {
        abrdf_params p;
        abrdf_params_init(models[k], &p);
        abrdf_batch b = {N, d[0], d[1], d[2], d[3], d[4], d[5], f[0], f[1], f[2]};
        ck_assert_int_eq(abrdf_eval_batch(models[k], &p, &b), ABRDF_OK);
        int nonzero = 0;
        for (int i = 0; i < N; ++i) {
            abrdf_batch one = {1,        d[0] + i, d[1] + i, d[2] + i, d[3] + i,
                               d[4] + i, d[5] + i, g,        g + 1,    g + 2};
            ck_assert_int_eq(abrdf_eval_batch(models[k], &p, &one), ABRDF_OK);
            for (int c = 0; c < 3; ++c)
                ck_assert_msg(memcmp(&f[c][i], &g[c], sizeof g[c]) == 0,
                              "model %d pair %d channel %d: %.9g in the batch, %.9g alone",
                              (int)models[k], i, c, f[c][i], g[c]);
            nonzero += f[0][i] > 0.0f;
        }
        ck_assert_int_gt(nonzero, N / 2);
    }
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("prepared");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, layout_is_frozen);
    tcase_add_test(tc, owns_a_copy_of_its_parameters);
    tcase_add_test(tc, copies_keep_their_model);
    tcase_add_test(tc, stale_blocks_are_safe);
    tcase_add_test(tc, not_prepared_evaluates_to_zero);
    tcase_add_test(tc, unit_entry_is_the_prepared_value);
    tcase_add_test(tc, special_models_keep_their_values);
    tcase_add_test(tc, special_batch_blocks_equal_single_pairs);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) { return tu_run(suite()); }
