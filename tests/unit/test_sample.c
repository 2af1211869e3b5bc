/* test_sample.c - abrdf_sample and abrdf_pdf for every model (loop over the registry):
 *   - every model names its sampler (abrdf_model_sampler);
 *   - the weight is f_r max(0, N.wi) / pdf, the pdf returned is abrdf_pdf's, and the
 *     direction is the internal sampler's (the one test_sample_chi2 tests) bit for bit;
 *   - a frame rotates the sample and changes neither pdf nor weight;
 *   - the albedo estimated by sampling, mean(weight), matches the albedo by adaptive
 *     quadrature of f_r max(0, N.wi) over the sphere within 5 standard errors;
 *   - closed forms: lambert's weight is kd, phong's 2 pi ks cos_i / (n + 1), disney
 *     specular's F G1(wi) with G1 from Smith's Lambda; the cosine and GGX visible-normal
 *     densities from independent formulas;
 *   - the prepared forms (abrdf_sample_prepared, abrdf_pdf_prepared) return the unprepared
 *     calls' bits for every model and parameter set, in the local frame and with a frame;
 *   - bad calls: one status, no sample.
 * Sample counts per model are in the table of albedo_by_sampling_matches_quadrature; the
 * hair models get fewer (huang's f_r integrates numerically, ~2.5 ms per call) and the
 * sanitizer build fewer still (SAMPLE_QUICK). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sample.h"
#include "sample_cases.h"
#include "vec.h"
#include "sample_stats.h"
#include "test_grid.h"
#include "test_util.h"

#define PI 3.14159265358979323846

#ifdef SAMPLE_QUICK
#define QUICK 1
#else
#define QUICK 0
#endif

static int is_model(const char *name, abrdf_model m)
{
    return !strcmp(abrdf_model_get(m)->name, name);
}

/* Samples per consistency case: huang's eval costs milliseconds. */
static int consistency_count(abrdf_model m)
{
    if (is_model("huang", m)) return QUICK ? 1 : 4;
    if (is_model("marschner", m)) return QUICK ? 8 : 40;
    return QUICK ? 50 : 200;
}

START_TEST(every_model_names_its_sampler)
{
    for (int i = 0; i < abrdf_model_count(); ++i) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        if (!m) continue;
        const abrdf_sampler_info *s = abrdf_model_sampler((abrdf_model)i);
        ck_assert_msg(s != NULL, "%s has no sampler", m->name);
        ck_assert_msg(s->name && *s->name && s->method && *s->method && s->citation && *s->citation,
                      "%s: sampler metadata incomplete", m->name);
        for (const char *c = s->name; *c; ++c)
            ck_assert_msg((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '_',
                          "%s: sampler name '%s' is not a stable lower-case name", m->name,
                          s->name);
    }
    ck_assert_ptr_null(abrdf_model_sampler(ABRDF_MODEL_NONE));
    ck_assert_ptr_null(abrdf_model_sampler((abrdf_model)abrdf_model_count()));
}
END_TEST

START_TEST(weight_is_f_cos_over_pdf)
{
    abrdf_model model = (abrdf_model)_i;
    if (!tu_param_model(model)) return;
    const char *name = abrdf_model_get(model)->name;
    static sc_set sets[SC_MAX_SETS];
    int nsets = sc_param_sets(model, sets), count = consistency_count(model);
    static const double thetas[3] = {10.0, 45.0, 80.0};
    tg_rng rng = {0x5eed0000ull + (unsigned long long)model};
    long checked = 0, below = 0;
    for (int s = 0; s < nsets; ++s)
        for (int t = 0; t < 3; ++t) {
            double d[3], wo[3];
            tu_dir(thetas[t], 20.0 + 70.0 * t, d);
            abrdf__normalise3(d, wo); /* as abrdf_sample does: the same bits on both sides */
            abrdf__mixture mx;
            abrdf__mixture_setup(model, &sets[s].p, wo, &mx);
            for (int i = 0; i < count; ++i) {
                double u1 = tg_uniform(&rng), u2 = tg_uniform(&rng), wi[3];
                abrdf_sample_result r;
                abrdf_sample_result_init(&r);
                ck_assert_int_eq(abrdf_sample(model, &sets[s].p, NULL, wo, u1, u2, &r), ABRDF_OK);
                abrdf__mixture_sample(&mx, u1, u2, wi);
                ck_assert_msg(r.pdf == 0.0 ||
                                  (fabs(wi[0] - r.wi[0]) < 1e-12 && fabs(wi[1] - r.wi[1]) < 1e-12 &&
                                   fabs(wi[2] - r.wi[2]) < 1e-12),
                              "%s %s: abrdf_sample's wi is not the internal sampler's", name,
                              sets[s].label);
                if (r.pdf == 0.0) continue;
                double pdf, f[3];
                ck_assert_int_eq(abrdf_pdf(model, &sets[s].p, NULL, r.wi, wo, &pdf), ABRDF_OK);
                ck_assert_msg(tu_close(pdf, r.pdf, 1e-9, 0.0),
                              "%s %s: pdf %.17g != abrdf_pdf %.17g", name, sets[s].label, r.pdf,
                              pdf);
                ck_assert_int_eq(abrdf_eval(model, &sets[s].p, NULL, r.wi, wo, f), ABRDF_OK);
                for (int c = 0; c < 3; ++c) {
                    double want = f[c] * fmax(r.wi[2], 0.0) / r.pdf;
                    ck_assert_msg(tu_close(r.weight[c], want, 1e-10, 1e-300),
                                  "%s %s: weight %.17g, f cos / pdf %.17g", name, sets[s].label,
                                  r.weight[c], want);
                }
                below += r.wi[2] <= 0.0;
                ++checked;
            }
        }
    printf("%-22s %ld samples checked (%ld below the surface)\n", name, checked, below);
    ck_assert_int_gt(checked, 0);
}
END_TEST

START_TEST(frame_rotates_the_sample)
{
    abrdf_model model = (abrdf_model)_i;
    if (!tu_param_model(model)) return;
    abrdf_params p;
    abrdf_params_init(model, &p);
    double n[3] = {0.3, -0.5, 0.8}, t[3] = {1.0, 0.2, 0.1};
    abrdf_frame fr;
    ck_assert_int_eq(abrdf_frame_make(n, t, &fr), ABRDF_OK);
    tg_rng rng = {42};
    int count = is_model("huang", model) ? 2 : 20;
    for (int i = 0; i < count; ++i) {
        double lo[3], wo[3];
        tu_dir(15.0 + 60.0 * tg_uniform(&rng), 360.0 * tg_uniform(&rng), lo);
        for (int c = 0; c < 3; ++c) wo[c] = lo[0] * fr.t[c] + lo[1] * fr.b[c] + lo[2] * fr.n[c];
        double u1 = tg_uniform(&rng), u2 = tg_uniform(&rng);
        abrdf_sample_result a, b;
        abrdf_sample_result_init(&a);
        abrdf_sample_result_init(&b);
        ck_assert_int_eq(abrdf_sample(model, &p, NULL, lo, u1, u2, &a), ABRDF_OK);
        ck_assert_int_eq(abrdf_sample(model, &p, &fr, wo, u1, u2, &b), ABRDF_OK);
        ck_assert(tu_close(a.pdf, b.pdf, 1e-8, 0.0));
        for (int c = 0; c < 3; ++c) {
            double w = a.wi[0] * fr.t[c] + a.wi[1] * fr.b[c] + a.wi[2] * fr.n[c];
            ck_assert_msg(fabs(w - b.wi[c]) < 1e-10, "%s: world wi off by %g",
                          abrdf_model_get(model)->name, fabs(w - b.wi[c]));
            ck_assert(tu_close(a.weight[c], b.weight[c], 1e-7, 1e-12));
        }
        double pw;
        ck_assert_int_eq(abrdf_pdf(model, &p, &fr, b.wi, wo, &pw), ABRDF_OK);
        ck_assert(tu_close(pw, b.pdf, 1e-8, 0.0));
    }
}
END_TEST

/* ---- albedo: sampling against quadrature ------------------------------------------------ */

typedef struct eval_ctx {
    abrdf_model model;
    const abrdf_params *p;
    const double *wo;
    int channel;
} eval_ctx;

static double f_cos(void *ctx, const double w[3])
{
    const eval_ctx *e = ctx;
    if (!(w[2] > 0.0)) return 0.0;
    double f[3];
    abrdf_eval(e->model, e->p, NULL, w, e->wo, f);
    return f[e->channel] * w[2];
}

START_TEST(albedo_by_sampling_matches_quadrature)
{
    abrdf_model model = (abrdf_model)_i;
    if (!tu_param_model(model)) return;
    const char *name = abrdf_model_get(model)->name;
    int huang = is_model("huang", model), hair = huang || is_model("marschner", model);
    if (huang && QUICK) return; /* seconds per evaluation under the sanitizers */
    /* samples and grid per model: huang's f_r costs ~2.5 ms, so 600 samples and a fixed
     * 8 x 16 grid of 4 x 4 Gauss-Legendre cells (2048 evaluations, about 1% accurate:
     * tolerance 2%); marschner (~35 us) 2e4 samples, a 12 x 24 grid; every other model 1e5
     * samples against adaptive quadrature on 24 x 48 cells. The sets' colours are grey:
     * channel 0 stands for the three. */
    long n = huang ? 600 : hair ? 20000 : (QUICK ? 20000 : 100000);
    static sc_set sets[SC_MAX_SETS];
    int nsets = sc_param_sets(model, sets);
    if (hair || QUICK) nsets = 1; /* the sanitizer build: the defaults only */
    static const double thetas[2] = {30.0, 70.0};
    for (int s = 0; s < nsets; ++s)
        for (int t = 0; t < (huang ? 1 : 2); ++t) {
            double wo[3];
            tu_dir(thetas[t], 35.0 + 100.0 * t, wo);
            tg_rng rng = {0xa1bed0ull + (unsigned long long)(model * 100 + s * 10 + t)};
            double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
            abrdf_sample_result r;
            abrdf_sample_result_init(&r);
            for (long i = 0; i < n; ++i) {
                double u1 = tg_uniform(&rng), u2 = tg_uniform(&rng);
                abrdf_sample(model, &sets[s].p, NULL, wo, u1, u2, &r);
                for (int c = 0; c < 3; ++c) {
                    sum[c] += r.weight[c];
                    sum2[c] += r.weight[c] * r.weight[c];
                }
            }
            double pole[3], warp;
            sc_pole(model, wo, pole, &warp);
            ss_grid g;
            int nt = huang ? 8 : hair ? 12 : 24;
            ss_grid_make(&g, pole, nt, 2 * nt, warp);
            for (int c = 0; c < 1; ++c) {
                eval_ctx e = {model, &sets[s].p, wo, c};
                double quad = huang ? ss_integrate(&g, f_cos, &e, 1e300, 1.0, 0, NULL, NULL)
                                    : ss_integrate(&g, f_cos, &e, 1e-9, 1e-7, 4, NULL, NULL);
                double mean = sum[c] / n, var = fmax(0.0, sum2[c] / n - mean * mean);
                double se = sqrt(var / n);
                double tol = 5.0 * se + (huang ? 0.02 : 2e-3) * fmax(quad, 0.01);
                int ok = fabs(mean - quad) <= tol;
                if (!ok || getenv("ABRDF_TEST_VERBOSE"))
                    printf("%-22s %-18s theta_o %2.0f ch %d: sampled %.6f +- %.6f, quadrature "
                           "%.6f, rel. second moment %.3g%s\n",
                           name, sets[s].label, thetas[t], c, mean, se, quad,
                           mean > 0.0 ? sum2[c] / n / (mean * mean) : 0.0, ok ? "" : "  FAIL");
                ck_assert_msg(ok, "%s %s: albedo by sampling %.6f, by quadrature %.6f", name,
                              sets[s].label, mean, quad);
            }
        }
}
END_TEST

/* ---- closed forms ----------------------------------------------------------------------- */

START_TEST(closed_form_weights_and_densities)
{
    tg_rng rng = {7};
    abrdf_sample_result r;
    abrdf_sample_result_init(&r);
    for (int i = 0; i < 2000; ++i) {
        double wo[3], u1 = tg_uniform(&rng), u2 = tg_uniform(&rng), pdf;
        tu_dir(85.0 * tg_uniform(&rng), 360.0 * tg_uniform(&rng), wo);
        /* lambert: pdf cos/pi, weight kd */
        abrdf_params p;
        abrdf_params_init(ABRDF_LAMBERT, &p);
        double kd[3] = {0.2, 0.5, 0.9};
        abrdf_param_set(&p, 0, kd, 3);
        ck_assert_int_eq(abrdf_sample(ABRDF_LAMBERT, &p, NULL, wo, u1, u2, &r), ABRDF_OK);
        ck_assert(tu_close(r.pdf, r.wi[2] / PI, 1e-13, 0.0));
        for (int c = 0; c < 3; ++c) ck_assert(tu_close(r.weight[c], kd[c], 1e-13, 0.0));
        /* phong, n = 30: weight 2 pi ks cos_i / (n + 1) above the surface */
        abrdf_params_init(ABRDF_PHONG, &p);
        p.n = 30.0;
        ck_assert_int_eq(abrdf_sample(ABRDF_PHONG, &p, NULL, wo, u1, u2, &r), ABRDF_OK);
        if (r.wi[2] > 0.0) ck_assert(tu_close(r.weight[0], 2.0 * PI * r.wi[2] / 31.0, 1e-10, 0.0));
        /* disney_specular: pdf D G1(wo) / (4 cos_o), weight F G1(wi), with G1 = 1/(1 + Lambda),
         * Lambda = (sqrt(1 + alpha^2 tan^2) - 1)/2 (Heitz 2014), D Eq. 6, F Eq. 8 */
        abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
        p.r = 0.6;
        ck_assert_int_eq(abrdf_sample(ABRDF_DISNEY_SPECULAR, &p, NULL, wo, u1, u2, &r), ABRDF_OK);
        double a = 0.36, a2 = a * a, h[3];
        for (int c = 0; c < 3; ++c) h[c] = r.wi[c] + wo[c];
        double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        for (int c = 0; c < 3; ++c) h[c] /= hl;
        double ch = h[2], dd = ch * ch * (a2 - 1.0) + 1.0, D = a2 / (PI * dd * dd);
        double to2 = (1.0 - wo[2] * wo[2]) / (wo[2] * wo[2]);
        double g1o = 1.0 / (1.0 + 0.5 * (sqrt(1.0 + a2 * to2) - 1.0));
        ck_assert(tu_close(r.pdf, D * g1o / (4.0 * wo[2]), 1e-10, 0.0));
        if (r.wi[2] > 0.0) {
            double ti2 = (1.0 - r.wi[2] * r.wi[2]) / (r.wi[2] * r.wi[2]);
            double g1i = 1.0 / (1.0 + 0.5 * (sqrt(1.0 + a2 * ti2) - 1.0));
            double cd = r.wi[0] * h[0] + r.wi[1] * h[1] + r.wi[2] * h[2];
            double F = 0.04 + 0.96 * pow(1.0 - cd, 5.0);
            ck_assert(tu_close(r.weight[0], F * g1i, 1e-9, 0.0));
        } else {
            ck_assert(r.weight[0] == 0.0);
        }
        /* the density of a direction below the surface is the sampler's, not 0 */
        double below[3] = {-wo[0], -wo[1], -wo[2] * 0.1};
        ck_assert_int_eq(abrdf_pdf(ABRDF_PHONG, &p, NULL, below, wo, &pdf), ABRDF_OK);
        ck_assert(pdf >= 0.0 && isfinite(pdf));
    }
}
END_TEST

/* ---- bad calls ------------------------------------------------------------------------- */

START_TEST(bad_calls_give_a_status_and_no_sample)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
    double wo[3] = {0.3, 0.1, 0.9}, wi[3] = {-0.2, 0.0, 1.0}, pdf = 7.0;
    abrdf_sample_result r;
    ck_assert_int_eq(abrdf_sample_result_init_sized(NULL, sizeof r), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_sample_result_init_sized(&r, sizeof r - 1), ABRDF_E_SIZE);
    ck_assert_int_eq(abrdf_sample_result_init(&r), ABRDF_OK);
    ck_assert_uint_eq(r.struct_size, sizeof r);
    ck_assert_int_eq(abrdf_sample(ABRDF_DISNEY_SPECULAR, &p, NULL, wo, 0.5, 0.5, NULL),
                     ABRDF_E_NULL);
    abrdf_sample_result zero;
    memset(&zero, 0, sizeof zero);
    ck_assert_int_eq(abrdf_sample(ABRDF_DISNEY_SPECULAR, &p, NULL, wo, 0.5, 0.5, &zero),
                     ABRDF_E_SIZE);
    const double bad_u[] = {-1e-9, 1.0 + 1e-9, NAN, INFINITY};
    for (size_t i = 0; i < sizeof bad_u / sizeof *bad_u; ++i) {
        ck_assert_int_eq(abrdf_sample(ABRDF_DISNEY_SPECULAR, &p, NULL, wo, bad_u[i], 0.5, &r),
                         ABRDF_E_RANGE);
        ck_assert(r.pdf == 0.0 && r.weight[0] == 0.0);
        ck_assert_int_eq(abrdf_sample(ABRDF_DISNEY_SPECULAR, &p, NULL, wo, 0.5, bad_u[i], &r),
                         ABRDF_E_RANGE);
    }
    ck_assert_int_eq(abrdf_sample(ABRDF_DISNEY_SPECULAR, NULL, NULL, wo, 0.5, 0.5, &r),
                     ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_sample(ABRDF_DISNEY_SPECULAR, &p, NULL, NULL, 0.5, 0.5, &r),
                     ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_sample((abrdf_model)abrdf_model_count(), &p, NULL, wo, 0.5, 0.5, &r),
                     ABRDF_E_MODEL);
    abrdf_params bad = p;
    bad.r = 2.0;
    ck_assert_int_eq(abrdf_sample(ABRDF_DISNEY_SPECULAR, &bad, NULL, wo, 0.5, 0.5, &r),
                     ABRDF_E_RANGE);
    ck_assert_int_eq(abrdf_pdf(ABRDF_DISNEY_SPECULAR, &bad, NULL, wi, wo, &pdf), ABRDF_E_RANGE);
    ck_assert(pdf == 0.0);
    ck_assert_int_eq(abrdf_pdf(ABRDF_DISNEY_SPECULAR, &p, NULL, wi, wo, NULL), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_pdf(ABRDF_DISNEY_SPECULAR, &p, NULL, NULL, wo, &pdf), ABRDF_E_NULL);
    /* geometry the API accepts, with no sample: below the surface, degenerate, NaN */
    const double no_wo[][3] = {
        {0.3, 0.0, -0.9}, {1.0, 0.0, 0.0}, {0, 0, 0}, {NAN, 0, 1}, {0, 0, INFINITY}};
    for (size_t i = 0; i < sizeof no_wo / sizeof *no_wo; ++i) {
        ck_assert_int_eq(abrdf_sample(ABRDF_DISNEY_SPECULAR, &p, NULL, no_wo[i], 0.5, 0.5, &r),
                         ABRDF_OK);
        ck_assert(r.pdf == 0.0 && r.weight[0] == 0.0 && r.wi[2] == 1.0);
        ck_assert_int_eq(abrdf_pdf(ABRDF_DISNEY_SPECULAR, &p, NULL, wi, no_wo[i], &pdf), ABRDF_OK);
        ck_assert(pdf == 0.0);
    }
    /* with a frame, "no sample" is wi = N */
    double n[3] = {0.0, 1.0, 0.0};
    abrdf_frame fr;
    abrdf_frame_make(n, NULL, &fr);
    double under[3] = {0.0, -1.0, 0.2};
    abrdf_params_init(ABRDF_LAMBERT, &p);
    ck_assert_int_eq(abrdf_sample(ABRDF_LAMBERT, &p, &fr, under, 0.5, 0.5, &r), ABRDF_OK);
    ck_assert(r.pdf == 0.0 && r.wi[1] == 1.0);
    /* u = 0 and u = 1 are valid */
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            ck_assert_int_eq(abrdf_sample(ABRDF_LAMBERT, &p, NULL, wo, a, b, &r), ABRDF_OK);
            ck_assert(isfinite(r.pdf) && r.pdf >= 0.0);
        }
}
END_TEST

/* ---- the prepared forms ------------------------------------------------------------------ */

START_TEST(prepared_equals_unprepared)
{
    abrdf_model model = (abrdf_model)_i;
    if (!tu_param_model(model)) return;
    const char *name = abrdf_model_get(model)->name;
    static sc_set sets[SC_MAX_SETS];
    int nsets = sc_param_sets(model, sets), count = consistency_count(model) / 4 + 1;
    double n[3] = {0.2, 0.9, -0.3}, t[3] = {0.0, 0.3, 1.0};
    abrdf_frame fr;
    ck_assert_int_eq(abrdf_frame_make(n, t, &fr), ABRDF_OK);
    tg_rng rng = {0x9e9a0000ull + (unsigned long long)model};
    long checked = 0;
    for (int s = 0; s < nsets; ++s) {
        abrdf_prepared prep;
        ck_assert_int_eq(abrdf_prepare(model, &sets[s].p, &prep), ABRDF_OK);
        for (int i = 0; i < 3 * count; ++i) {
            const abrdf_frame *f = (i & 1) ? &fr : NULL;
            double lo[3], wo[3];
            tu_dir(5.0 + 80.0 * tg_uniform(&rng), 360.0 * tg_uniform(&rng), lo);
            for (int c = 0; c < 3; ++c)
                wo[c] = f ? lo[0] * fr.t[c] + lo[1] * fr.b[c] + lo[2] * fr.n[c] : lo[c];
            double u1 = tg_uniform(&rng), u2 = tg_uniform(&rng);
            if (i % 7 == 3) u1 = 1.0, u2 = 0.0; /* the ends of the range */
            abrdf_sample_result a, b;
            abrdf_sample_result_init(&a);
            abrdf_sample_result_init(&b);
            ck_assert_int_eq(abrdf_sample(model, &sets[s].p, f, wo, u1, u2, &a), ABRDF_OK);
            ck_assert_int_eq(abrdf_sample_prepared(&prep, f, wo, u1, u2, &b), ABRDF_OK);
            ck_assert_msg(!memcmp(a.wi, b.wi, sizeof a.wi) &&
                              !memcmp(&a.pdf, &b.pdf, sizeof a.pdf) &&
                              !memcmp(a.weight, b.weight, sizeof a.weight),
                          "%s %s: prepared sample differs (pdf %.17g vs %.17g)", name,
                          sets[s].label, a.pdf, b.pdf);
            /* the density of the sample and of an unrelated direction */
            double other[3] = {wo[1], -wo[0] + 0.1, wo[2] * 0.5 + 0.2};
            const double *wis[2] = {a.wi, other};
            for (int k = 0; k < 2; ++k) {
                double pa = -1.0, pb = -2.0;
                ck_assert_int_eq(abrdf_pdf(model, &sets[s].p, f, wis[k], wo, &pa), ABRDF_OK);
                ck_assert_int_eq(abrdf_pdf_prepared(&prep, f, wis[k], wo, &pb), ABRDF_OK);
                ck_assert_msg(!memcmp(&pa, &pb, sizeof pa), "%s %s: pdf %.17g, prepared %.17g",
                              name, sets[s].label, pa, pb);
            }
            ++checked;
        }
    }
    ck_assert_int_gt(checked, 0);
}
END_TEST

START_TEST(prepared_bad_calls)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_LAMBERT, &p);
    abrdf_prepared prep, never;
    memset(&never, 0, sizeof never);
    ck_assert_int_eq(abrdf_prepare(ABRDF_LAMBERT, &p, &prep), ABRDF_OK);
    double wo[3] = {0.3, 0.1, 0.9}, wi[3] = {-0.2, 0.0, 1.0}, pdf = 7.0;
    abrdf_sample_result r, zero;
    abrdf_sample_result_init(&r);
    memset(&zero, 0, sizeof zero);
    ck_assert_int_eq(abrdf_sample_prepared(&never, NULL, wo, 0.5, 0.5, &r), ABRDF_E_MODEL);
    ck_assert(r.pdf == 0.0 && r.weight[0] == 0.0 && r.wi[2] == 1.0);
    ck_assert_int_eq(abrdf_sample_prepared(NULL, NULL, wo, 0.5, 0.5, &r), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_sample_prepared(&prep, NULL, NULL, 0.5, 0.5, &r), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_sample_prepared(&prep, NULL, wo, 0.5, 0.5, NULL), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_sample_prepared(&prep, NULL, wo, 0.5, 0.5, &zero), ABRDF_E_SIZE);
    ck_assert_int_eq(abrdf_sample_prepared(&prep, NULL, wo, NAN, 0.5, &r), ABRDF_E_RANGE);
    ck_assert(r.pdf == 0.0);
    ck_assert_int_eq(abrdf_pdf_prepared(&never, NULL, wi, wo, &pdf), ABRDF_E_MODEL);
    ck_assert(pdf == 0.0);
    ck_assert_int_eq(abrdf_pdf_prepared(&prep, NULL, NULL, wo, &pdf), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_pdf_prepared(&prep, NULL, wi, wo, NULL), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_pdf_prepared(&prep, NULL, wi, wo, &pdf), ABRDF_OK);
    ck_assert(pdf > 0.0);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sample");
    TCase *tc = tcase_create("sample");
    tcase_set_timeout(tc, 0);
    tcase_add_test(tc, every_model_names_its_sampler);
    tcase_add_test(tc, closed_form_weights_and_densities);
    tcase_add_test(tc, bad_calls_give_a_status_and_no_sample);
    tcase_add_loop_test(tc, weight_is_f_cos_over_pdf, 0, abrdf_model_count());
    tcase_add_loop_test(tc, frame_rotates_the_sample, 0, abrdf_model_count());
    tcase_add_test(tc, prepared_bad_calls);
    tcase_add_loop_test(tc, prepared_equals_unprepared, 0, abrdf_model_count());
    tcase_add_loop_test(tc, albedo_by_sampling_matches_quadrature, 0, abrdf_model_count());
    suite_add_tcase(s, tc);
    return tu_run(s);
}
