/* test_measured.c - the `measured` model (abrdf.h, "measured materials"): the API contract
 * (no table: ABRDF_E_TABLE; bad descriptors refused), exact values at the grid's cells,
 * tables written from analytic models read back within the grid's interpolation error, and
 * the shared invariants (finite, non-negative, reciprocal, albedo bound, scalar == batch,
 * sampling by chi-square and pdf integration) on tables with holes, NaN and Inf cells. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf.h"
#include "prepared.h"
#include "measured_cases.h"
#include "sample_stats.h"
#include "test_grid.h"
#include "test_util.h"

#define PI 3.14159265358979323846

static void prepare(const mc_table *t, abrdf_prepared *pr)
{
    ck_assert_int_eq(abrdf_prepare_measured(&t->desc, pr), ABRDF_OK);
}

START_TEST(needs_a_table)
{
    abrdf_params p;
    ck_assert_int_eq(abrdf_params_init(ABRDF_MEASURED, &p), ABRDF_OK);
    const abrdf_model_info *m = abrdf_model_get(ABRDF_MEASURED);
    ck_assert_ptr_nonnull(m);
    ck_assert_str_eq(m->name, "measured");
    ck_assert(m->needs & ABRDF_NEEDS_TABLE);
    ck_assert(m->props & ABRDF_PROP_RECIPROCAL);
    ck_assert_int_eq(m->param_count, 0);
    abrdf_model found;
    ck_assert_int_eq(abrdf_model_find("measured", &found), ABRDF_OK);
    ck_assert_int_eq(found, ABRDF_MEASURED);
    ck_assert_ptr_nonnull(abrdf_model_sampler(ABRDF_MEASURED));
    char msg[256];
    ck_assert_int_eq(abrdf_params_check(ABRDF_MEASURED, &p, msg, sizeof msg), ABRDF_E_TABLE);
    ck_assert(strstr(msg, "abrdf_prepare_measured") != NULL);
    const double wi[3] = {0, 0, 1}, wo[3] = {0, 0, 1};
    double f[3] = {1, 1, 1}, pdf = 1;
    ck_assert_int_eq(abrdf_eval(ABRDF_MEASURED, &p, NULL, wi, wo, f), ABRDF_E_TABLE);
    ck_assert(f[0] == 0 && f[1] == 0 && f[2] == 0);
    abrdf_prepared pr;
    ck_assert_int_eq(abrdf_prepare(ABRDF_MEASURED, &p, &pr), ABRDF_E_TABLE);
    ck_assert_int_eq(abrdf_prepared_model(&pr), ABRDF_MODEL_NONE);
    abrdf_sample_result r;
    abrdf_sample_result_init(&r);
    ck_assert_int_eq(abrdf_sample(ABRDF_MEASURED, &p, NULL, wo, 0.5, 0.5, &r), ABRDF_E_TABLE);
    ck_assert_int_eq(abrdf_pdf(ABRDF_MEASURED, &p, NULL, wi, wo, &pdf), ABRDF_E_TABLE);
    ck_assert(pdf == 0.0);
}
END_TEST

START_TEST(bad_descriptors_are_refused)
{
    float data[2 * 2 * 2 * 3] = {0};
    abrdf_measured t;
    abrdf_prepared pr;
    memset(&t, 0, sizeof t);
    t.n_theta_h = t.n_theta_d = t.n_phi_d = 2;
    t.data = data;
    ck_assert_int_eq(abrdf_prepare_measured(&t, &pr), ABRDF_E_SIZE); /* never initialised */
    ck_assert_int_eq(abrdf_measured_init_sized(&t, sizeof t - 1), ABRDF_E_SIZE);
    ck_assert_int_eq(abrdf_measured_init(NULL), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_measured_init(&t), ABRDF_OK);
    ck_assert_ptr_null(t.data);
    t.n_theta_h = t.n_theta_d = t.n_phi_d = 2;
    ck_assert_int_eq(abrdf_prepare_measured(&t, &pr), ABRDF_E_NULL); /* no data */
    t.data = data;
    ck_assert_int_eq(abrdf_prepare_measured(NULL, &pr), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_prepare_measured(&t, NULL), ABRDF_E_NULL);
    const int bad[] = {-1, 0, 1, 1025, 1 << 30};
    for (int k = 0; k < 3; ++k)
        for (size_t b = 0; b < sizeof bad / sizeof bad[0]; ++b) {
            abrdf_measured u = t;
            (&u.n_theta_h)[k] = bad[b];
            ck_assert_int_eq(abrdf_prepare_measured(&u, &pr), ABRDF_E_TABLE);
            ck_assert_int_eq(abrdf_prepared_model(&pr), ABRDF_MODEL_NONE);
        }
    ck_assert_int_eq(abrdf_prepare_measured(&t, &pr), ABRDF_OK);
    ck_assert_int_eq(abrdf_prepared_model(&pr), ABRDF_MEASURED);
    ck_assert_ptr_nonnull(abrdf_prepared_params(&pr));
}
END_TEST

/* At a cell's own directions the interpolation returns the cell (in float: the table's
 * precision), away from the grid's clamped end and the horizon. */
START_TEST(cells_are_exact)
{
    mc_table t;
    abrdf_measured_init(&t.desc);
    t.desc.n_theta_h = 12, t.desc.n_theta_d = 10, t.desc.n_phi_d = 16;
    size_t n = (size_t)12 * 10 * 16 * 3;
    t.data = malloc(n * sizeof *t.data);
    t.desc.data = t.data;
    for (size_t i = 0; i < n; ++i) t.data[i] = (float)(0.1 + (i * 7919 % 1000) / 250.0);
    abrdf_prepared pr;
    prepare(&t, &pr);
    int checked = 0;
    for (int ih = 1; ih < 11; ++ih) /* theta_d = 0 is one direction pair for every phi_d */
        for (int id = 1; id < 9; ++id)
            for (int ip = 0; ip < 16; ++ip) {
                double wi[3], wo[3], f[3];
                mc_cell_dirs(&t.desc, ih, id, ip, wi, wo);
                if (!(wi[2] > 1e-3 && wo[2] > 1e-3)) continue;
                ck_assert_int_eq(abrdf_eval_prepared(&pr, NULL, wi, wo, f), ABRDF_OK);
                const float *v = t.data + mc_cell(&t.desc, ih, id, ip);
                for (int c = 0; c < 3; ++c)
                    if (!tu_close(f[c], v[c], 1e-9, 1e-12))
                        ck_abort_msg("cell (%d,%d,%d) c%d: %.17g, table %.9g", ih, id, ip, c, f[c],
                                     v[c]);
                ++checked;
            }
    ck_assert_int_gt(checked, 500);
    free(t.data);
}
END_TEST

/* Relative cosine-weighted L2 error of the table's BRDF against the analytic one over
 * random direction pairs above the horizon, and the largest pointwise error relative to the
 * BRDF's peak over the set. */
static void table_error(const mc_table *t, abrdf_model diffuse, abrdf_model specular,
                        const abrdf_params *p, double *rel_l2, double *max_rel)
{
    abrdf_prepared pr;
    prepare(t, &pr);
    tg_rng rng = {12345};
    double num = 0, den = 0, peak = 0, worst = 0;
    for (int i = 0; i < 20000; ++i) {
        double wi[3], wo[3], f[3], fd[3] = {0, 0, 0}, fs[3] = {0, 0, 0};
        tg_hemisphere(&rng, wi);
        tg_hemisphere(&rng, wo);
        abrdf_eval_prepared(&pr, NULL, wi, wo, f);
        if (diffuse != ABRDF_MODEL_NONE) abrdf_eval(diffuse, p, NULL, wi, wo, fd);
        if (specular != ABRDF_MODEL_NONE) abrdf_eval(specular, p, NULL, wi, wo, fs);
        for (int c = 0; c < 3; ++c) {
            double ref = fd[c] + fs[c], w = wi[2] * wi[2];
            num += w * (f[c] - ref) * (f[c] - ref);
            den += w * ref * ref;
            peak = fmax(peak, ref * wi[2]);
            worst = fmax(worst, fabs(f[c] - ref) * wi[2]);
        }
    }
    *rel_l2 = sqrt(num / den);
    *max_rel = worst / peak;
}

/* Tables of MERL's grid written from analytic models read back within the grid's
 * interpolation error (docs/MEASURED.md quotes these numbers). */
START_TEST(analytic_tables_read_back)
{
    static const struct {
        abrdf_model d, s;
        double r, bound_l2, bound_max;
    } cases[] = {
        {ABRDF_LAMBERT, ABRDF_MODEL_NONE, 0.5, 1e-6, 1e-6},
        {ABRDF_LAMBERT, ABRDF_DISNEY_SPECULAR, 0.3, 0.02, 0.05},
        {ABRDF_MODEL_NONE, ABRDF_COOK_TORRANCE, 0.3, 0.02, 0.05},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        abrdf_params p;
        abrdf_params_init(cases[k].s != ABRDF_MODEL_NONE ? cases[k].s : cases[k].d, &p);
        p.r = cases[k].r;
        for (int c = 0; c < 3; ++c) p.kd[c] = 0.5, p.ks[c] = 1.0, p.f0[c] = 0.04 + 0.3 * c;
        mc_table t;
        mc_table_of(&t, 90, 90, 180, cases[k].d, cases[k].s, &p);
        double l2, mx;
        table_error(&t, cases[k].d, cases[k].s, &p, &l2, &mx);
        printf("measured %s + %s r=%.2f: rel L2 %.3g, max %.3g of the peak\n",
               cases[k].d == ABRDF_MODEL_NONE ? "none" : abrdf_model_get(cases[k].d)->name,
               cases[k].s == ABRDF_MODEL_NONE ? "none" : abrdf_model_get(cases[k].s)->name,
               cases[k].r, l2, mx);
        ck_assert_msg(l2 < cases[k].bound_l2 && mx < cases[k].bound_max, "case %zu: %g %g", k, l2,
                      mx);
        free(t.data);
    }
}
END_TEST

/* A table with holes, NaN, Inf and huge cells, on a coarse grid. */
static void hostile_table(mc_table *t)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
    p.r = 0.2;
    mc_table_of(t, 16, 12, 24, ABRDF_LAMBERT, ABRDF_DISNEY_SPECULAR, &p);
    size_t n = (size_t)16 * 12 * 24 * 3;
    for (size_t i = 0; i < n; i += 37) t->data[i] = -1.0f;
    t->data[5] = NAN;
    t->data[300] = INFINITY;
    t->data[301] = 3e38f;
}

START_TEST(invariants)
{
    mc_table t;
    hostile_table(&t);
    abrdf_prepared pr;
    prepare(&t, &pr);
    tg_rng rng = {777};
    enum { N = 4096 };
    static float ix[N], iy[N], iz[N], ox[N], oy[N], oz[N], fr[N], fg[N], fb[N];
    static double ref[N][3];
    long bad = 0, recip = 0;
    for (int i = 0; i < N; ++i) {
        double wi[3], wo[3], f[3], g[3];
        tg_sphere(&rng, wi);
        tg_sphere(&rng, wo);
        if (i % 7 == 0) wo[0] = -wi[0], wo[1] = -wi[1], wo[2] = wi[2]; /* mirror */
        if (i % 11 == 0) memcpy(wo, wi, sizeof wo);                    /* retro */
        if (i % 13 == 0) wi[2] = 0.0;                                  /* horizon */
        abrdf_eval_prepared(&pr, NULL, wi, wo, f);
        abrdf_eval_prepared(&pr, NULL, wo, wi, g);
        for (int c = 0; c < 3; ++c) {
            bad += !(f[c] >= 0.0 && isfinite(f[c]));
            recip += f[c] != g[c]; /* one order of the pair in every path: the same bits */
        }
        double li = sqrt(wi[0] * wi[0] + wi[1] * wi[1] + wi[2] * wi[2]);
        double lo = sqrt(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2]);
        ix[i] = (float)(wi[0] / li), iy[i] = (float)(wi[1] / li), iz[i] = (float)(wi[2] / li);
        ox[i] = (float)(wo[0] / lo), oy[i] = (float)(wo[1] / lo), oz[i] = (float)(wo[2] / lo);
        memcpy(ref[i], f, sizeof f);
    }
    ck_assert_int_eq(bad, 0);
    ck_assert_int_eq(recip, 0);
    abrdf_batch b = {N, ix, iy, iz, ox, oy, oz, fr, fg, fb};
    ck_assert_int_eq(abrdf_eval_prepared_batch(&pr, &b), ABRDF_OK);
    /* float == double at every instruction-set level this CPU runs: the grid coordinates in
     * float (atan by a polynomial of 2.3e-7 relative error) move a lookup by ~1e-6 of a
     * cell, so the difference is bounded by that times the table's steepest step */
    for (int level = 0; level <= abrdf__isa_best(); ++level) {
        memset(fr, 0xff, sizeof fr); /* NaN: every output must be written */
        ck_assert_int_eq(abrdf__eval_prepared_f_isa(abrdf__prep_of(&pr), &b, level), 0);
        long off = 0;
        double worst = 0;
        for (int i = 0; i < N; ++i) {
            float v[3] = {fr[i], fg[i], fb[i]};
            for (int c = 0; c < 3; ++c) {
                ck_assert(v[c] >= 0.0f && isfinite(v[c]));
                off += !tu_close(v[c], ref[i][c], 2e-4, 1e-5);
                if (ref[i][c] > 1e-3) worst = fmax(worst, fabs(v[c] - ref[i][c]) / ref[i][c]);
            }
        }
        printf("measured batch, level %s: largest relative difference to double %.3g\n",
               abrdf__isa_name(level), worst);
        ck_assert_msg(off == 0, "level %d: %ld values of the batch differ from the double path",
                      level, off);
        /* and the batch is reciprocal to the bit too */
        abrdf_batch sw = {N, ox, oy, oz, ix, iy, iz, fg, fb, fr};
        static float keep[N];
        memcpy(keep, fr, sizeof keep);
        ck_assert_int_eq(abrdf__eval_prepared_f_isa(abrdf__prep_of(&pr), &sw, level), 0);
        ck_assert(memcmp(keep, fg, sizeof keep) == 0);
    }
    free(t.data);
}
END_TEST

/* Albedo of a table written from an energy-conserving BRDF stays within 1 (white furnace by
 * a midpoint quadrature over wi, the table's own interpolation error added). */
START_TEST(albedo_bound)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
    p.r = 0.5;
    for (int c = 0; c < 3; ++c) p.ks[c] = 1.0, p.f0[c] = 1.0;
    mc_table t;
    mc_table_of(&t, 45, 45, 90, ABRDF_MODEL_NONE, ABRDF_DISNEY_SPECULAR, &p);
    abrdf_prepared pr;
    prepare(&t, &pr);
    for (int k = 0; k < 6; ++k) {
        double to = k * 15.0 * PI / 180, wo[3] = {sin(to), 0, cos(to)}, a = 0;
        const int nt = 256, np = 128;
        for (int i = 0; i < nt; ++i)
            for (int j = 0; j < np; ++j) {
                double t1 = (i + 0.5) / nt * PI / 2, p1 = (j + 0.5) / np * 2 * PI, f[3];
                double wi[3] = {sin(t1) * cos(p1), sin(t1) * sin(p1), cos(t1)};
                abrdf_eval_prepared(&pr, NULL, wi, wo, f);
                a += f[0] * cos(t1) * sin(t1) * (PI / 2 / nt) * (2 * PI / np);
            }
        ck_assert_msg(a <= 1.0 + 1e-3, "theta_o %d deg: albedo %g", k * 15, a);
        ck_assert_msg(a > 0.5, "theta_o %d deg: albedo %g", k * 15, a);
    }
    free(t.data);
}
END_TEST

/* An infinite cell counts as not measured in both paths, also where its weight is 0 (a
 * direction pair on a grid node, where 0 * Inf would be NaN). */
START_TEST(infinite_cells)
{
    mc_table t;
    abrdf_measured_init(&t.desc);
    t.desc.n_theta_h = 8, t.desc.n_theta_d = 8, t.desc.n_phi_d = 16;
    size_t n = (size_t)8 * 8 * 16 * 3;
    t.data = malloc(n * sizeof *t.data);
    t.desc.data = t.data;
    for (size_t i = 0; i < n; ++i) t.data[i] = 0.1f;
    t.data[mc_cell(&t.desc, 0, 1, 0)] = INFINITY;
    abrdf_prepared pr;
    prepare(&t, &pr);
    const double z[3] = {0, 0, 1};
    double f[3];
    abrdf_eval_prepared(&pr, NULL, z, z, f);
    float x[1] = {0}, y[1] = {0}, one[1] = {1}, fr[1], fg[1], fb[1];
    abrdf_batch b = {1, x, y, one, x, y, one, fr, fg, fb};
    abrdf_eval_prepared_batch(&pr, &b);
    for (int c = 0; c < 3; ++c) ck_assert(tu_close(f[c], 0.1, 1e-7, 0));
    ck_assert(tu_close(fr[0], 0.1, 1e-6, 0) && tu_close(fg[0], 0.1, 1e-6, 0));
    free(t.data);
}
END_TEST

/* Holes are filled from the measured neighbours; a region with none gives 0. */
START_TEST(holes)
{
    mc_table t;
    abrdf_measured_init(&t.desc);
    t.desc.n_theta_h = t.desc.n_theta_d = 4, t.desc.n_phi_d = 8;
    size_t n = (size_t)4 * 4 * 8 * 3;
    t.data = malloc(n * sizeof *t.data);
    t.desc.data = t.data;
    for (size_t i = 0; i < n; ++i) t.data[i] = 0.25f;
    t.data[mc_cell(&t.desc, 1, 1, 2) + 1] = -1.0f; /* green of one cell not measured */
    abrdf_prepared pr;
    prepare(&t, &pr);
    double wi[3], wo[3], f[3];
    mc_cell_dirs(&t.desc, 1, 1, 2, wi, wo);
    abrdf_eval_prepared(&pr, NULL, wi, wo, f);
    ck_assert(tu_close(f[0], 0.25, 1e-12, 0) && tu_close(f[1], 0.25, 1e-12, 0));
    for (size_t i = 0; i < n; ++i) t.data[i] = -1.0f;
    prepare(&t, &pr);
    abrdf_eval_prepared(&pr, NULL, wi, wo, f);
    ck_assert(f[0] == 0 && f[1] == 0 && f[2] == 0);
    free(t.data);
}
END_TEST

/* ---- sampling ----------------------------------------------------------------------- */

typedef struct pdf_ctx {
    const abrdf_prepared *pr;
    const double *wo;
} pdf_ctx;

static double pdf_fn(void *ctx, const double w[3])
{
    const pdf_ctx *c = ctx;
    double p = 0;
    abrdf_pdf_prepared(c->pr, NULL, w, c->wo, &p);
    return p;
}

/* abrdf_sample_prepared draws what abrdf_pdf_prepared says (chi-square on a sphere grid
 * about the normal), the pdf integrates to 1, and the weight is f cos / pdf. */
START_TEST(sampling)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
    p.r = 0.3;
    mc_table t;
    mc_table_of(&t, 45, 45, 90, ABRDF_LAMBERT, ABRDF_DISNEY_SPECULAR, &p);
    abrdf_prepared pr;
    prepare(&t, &pr);
    enum { NT = 24, NP = 48 };
    const double pole[3] = {0, 0, 1};
    const double thetas[2] = {20.0, 65.0};
    for (int k = 0; k < 2; ++k) {
        double wo[3];
        tu_dir(thetas[k], 30.0, wo);
        pdf_ctx ctx = {&pr, wo};
        ss_grid g;
        ss_grid_make(&g, pole, NT, NP, 1.0);
        static double expected[NT * NP], observed[NT * NP];
        double total = ss_integrate(&g, pdf_fn, &ctx, 1e-8, 1e-5, 4, expected, NULL);
        ck_assert_msg(fabs(total - 1.0) < 1e-3, "pdf integrates to %g", total);
        memset(observed, 0, sizeof observed);
        tg_rng rng = {4242 + k};
        const long n = 100000;
        abrdf_sample_result r;
        abrdf_sample_result_init(&r);
        for (long i = 0; i < n; ++i) {
            ck_assert_int_eq(
                abrdf_sample_prepared(&pr, NULL, wo, tg_uniform(&rng), tg_uniform(&rng), &r),
                ABRDF_OK);
            if (!(r.pdf > 0)) continue;
            observed[ss_cell(&g, r.wi)] += 1.0;
            if (i % 97 == 0) {
                double f[3], q;
                abrdf_eval_prepared(&pr, NULL, r.wi, wo, f);
                abrdf_pdf_prepared(&pr, NULL, r.wi, wo, &q);
                ck_assert(tu_close(q, r.pdf, 1e-12, 0));
                for (int c = 0; c < 3; ++c)
                    ck_assert(tu_close(r.weight[c], f[c] * fmax(r.wi[2], 0) / r.pdf, 1e-12, 1e-15));
            }
        }
        for (int i = 0; i < NT * NP; ++i) expected[i] *= n;
        double pv;
        int dof;
        double chi2 = ss_chi2(observed, expected, NT * NP, 5.0, &pv, &dof);
        ck_assert_msg(pv > 1e-3, "theta_o %g: chi2 %g dof %d p %g", thetas[k], chi2, dof, pv);
    }
    free(t.data);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("measured");
    TCase *tc = tcase_create("measured");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, needs_a_table);
    tcase_add_test(tc, bad_descriptors_are_refused);
    tcase_add_test(tc, cells_are_exact);
    tcase_add_test(tc, analytic_tables_read_back);
    tcase_add_test(tc, invariants);
    tcase_add_test(tc, albedo_bound);
    tcase_add_test(tc, holes);
    tcase_add_test(tc, infinite_cells);
    tcase_add_test(tc, sampling);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) { return tu_run(suite()); }
