/* test_pbr_reference.c - the glTF BRDF as specified (tools/pbr/pbr_reference.h) against closed
 * forms, and the measurement of the mapping (pbr_error.h): its quadrature's convergence and
 * its sphere, held to abrdf_predict_nmse's on libabrdf BRDFs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf_fit.h"
#include "pbr_error.h"
#include "pbr_reference.h"
#include "quad.h"
#include "test_util.h"

static const double PI = 3.14159265358979323846;

/* int_0^(pi/2) g(theta) dtheta by Gauss-Legendre on [0, split] and [split, pi/2]. */
static double theta_integral(double (*g)(double, const double *), const double *arg, double split)
{
    enum { N = 512 };
    double x[N], w[N], sum = 0;
    quad_gauss_legendre01(N, x, w);
    double lo[2] = {0, split}, hi[2] = {split, PI / 2};
    for (int s = 0; s < 2; ++s)
        for (int i = 0; i < N; ++i)
            sum += w[i] * (hi[s] - lo[s]) * g(lo[s] + (hi[s] - lo[s]) * x[i], arg);
    return sum;
}

static double ggx_projected(double t, const double *a)
{
    return 2 * PI * pbr_ref_d_ggx(a[0], cos(t)) * cos(t) * sin(t);
}

static double charlie_projected(double t, const double *a)
{
    return 2 * PI * pbr_ref_d_charlie(a[0], cos(t)) * cos(t) * sin(t);
}

/* The azimuthal integral of the anisotropic D at polar angle t. */
static double ggx_aniso_projected(double t, const double *a)
{
    enum { NPHI = 2048 };
    double sum = 0;
    for (int j = 0; j < NPHI; ++j) {
        double p = 2 * PI * (j + 0.5) / NPHI;
        double h[3] = {sin(t) * cos(p), sin(t) * sin(p), cos(t)};
        sum += pbr_ref_d_ggx_aniso(a[0], a[1], h) * cos(t) * sin(t) * (2 * PI / NPHI);
    }
    return sum;
}

START_TEST(distributions_integrate_to_one_over_the_projected_hemisphere)
{
    const double alphas[] = {0.01, 0.09, 0.3, 1};
    for (int k = 0; k < 4; ++k) {
        double a = alphas[k];
        double g = theta_integral(ggx_projected, &a, fmin(atan(a) * 8, 1.5));
        ck_assert_msg(fabs(g - 1) < 1e-9, "GGX alpha %g: %.12g", a, g);
        double c = theta_integral(charlie_projected, &a, 1.0);
        ck_assert_msg(fabs(c - 1) < 1e-9, "Charlie alpha %g: %.12g", a, c);
    }
    const double an[2] = {0.37, 0.16};
    double g = theta_integral(ggx_aniso_projected, an, 1.0);
    ck_assert_msg(fabs(g - 1) < 1e-7, "anisotropic GGX: %.12g", g);
    double h[3] = {0.3, -0.2, 0};
    h[2] = sqrt(1 - 0.13);
    ck_assert(tu_close(pbr_ref_d_ggx_aniso(0.2, 0.2, h), pbr_ref_d_ggx(0.2, h[2]), 1e-13, 0));
}
END_TEST

/* Smith's Lambda for GGX, Lambda(w) = (-1 + sqrt(1 + (at^2 x^2 + ab^2 y^2) / z^2)) / 2, and
 * the height-correlated G2 = 1 / (1 + Lambda(L) + Lambda(V)) over 4 |N.L| |N.V|. */
static double lambda_ggx(double at, double ab, const double w[3])
{
    return 0.5 * (-1 + sqrt(1 + (at * at * w[0] * w[0] + ab * ab * w[1] * w[1]) / (w[2] * w[2])));
}

START_TEST(visibility_is_smith_height_correlated)
{
    const double alphas[][2] = {{0.05, 0.05}, {0.3, 0.3}, {1, 1}, {0.5, 0.1}, {0.2, 0.9}};
    for (int k = 0; k < 5; ++k)
        for (double ti = 5; ti < 90; ti += 14)
            for (double to = 3; to < 90; to += 17)
                for (double ph = 0; ph < 360; ph += 75) {
                    double l[3], v[3];
                    tu_dir(ti, 20, l);
                    tu_dir(to, 20 + ph, v);
                    double at = alphas[k][0], ab = alphas[k][1];
                    double g2 = 1 / (1 + lambda_ggx(at, ab, l) + lambda_ggx(at, ab, v));
                    double want = g2 / (4 * l[2] * v[2]);
                    double got = pbr_ref_v_ggx_aniso(at, ab, l, v);
                    ck_assert_msg(tu_close(got, want, 1e-12, 0), "aniso %g %g: %.15g vs %.15g", at,
                                  ab, got, want);
                    if (at == ab)
                        ck_assert(tu_close(pbr_ref_v_ggx(at, l[2], v[2]), want, 1e-12, 0));
                }
    ck_assert(pbr_ref_v_ggx(0.3, 0, 0.5) == 0 && pbr_ref_v_ggx(0.3, 0.5, -0.1) == 0);
}
END_TEST

START_TEST(charlie_visibility_and_schlick_in_closed_form)
{
    /* Lambda(cos) below 0.5 is exp(l(cos)), l(x) = a / (1 + b x^c) + d x + e; at alpha = 1
     * the coefficients are the first of each pair */
    double x = 0.3, l = 21.5473 / (1 + 3.82987 * pow(x, 0.19823)) - 1.97760 * x - 4.32054;
    ck_assert(tu_close(pbr_ref_lambda_charlie(1, x), exp(l), 1e-14, 0));
    double l5 = 21.5473 / (1 + 3.82987 * pow(0.5, 0.19823)) - 1.97760 * 0.5 - 4.32054;
    double l2 = 21.5473 / (1 + 3.82987 * pow(0.2, 0.19823)) - 1.97760 * 0.2 - 4.32054;
    ck_assert(tu_close(pbr_ref_lambda_charlie(1, 0.8), exp(2 * l5 - l2), 1e-14, 0));
    double want = 1 / ((1 + exp(l) + exp(2 * l5 - l2)) * 4 * 0.3 * 0.8);
    ck_assert(tu_close(pbr_ref_v_charlie(1, 0.3, 0.8), want, 1e-14, 0));
    ck_assert(pbr_ref_f_schlick(0.04, 1, 1) == 0.04);
    ck_assert(tu_close(pbr_ref_f_schlick(0.04, 1, 0.5), 0.04 + 0.96 / 32, 1e-15, 0));
    ck_assert(pbr_ref_f_schlick(0.2, 1, 0) == 1);
}
END_TEST

static double albedo_of(const pbr_ref *r, double theta_deg, double width, int order, int c)
{
    double wo[3], rho[3], widths[1] = {width};
    tu_dir(theta_deg, 0, wo);
    pbr_albedo(pbr_ref_brdf, r, wo, widths, 1, order, rho);
    return rho[c];
}

START_TEST(limits_lambert_mirror_and_transmission)
{
    abrdf_pbr p;
    abrdf_pbr_init(&p);
    pbr_ref r;
    char msg[128];
    /* specular 0: the diffuse alone, whose albedo is the base colour; transmission scales it */
    p.metallic = 0, p.specular = 0, p.base_color[1] = 0.6, p.transmission = 0.25;
    ck_assert_int_eq(pbr_ref_prepare(&p, &r, msg, sizeof msg), ABRDF_OK);
    for (double t = 0; t < 80; t += 25) {
        double rho = albedo_of(&r, t, 0.16, 96, 1);
        ck_assert_msg(fabs(rho - 0.6 * 0.75) < 1e-5, "lambert at %g: %.9g", t, rho);
    }
    double wi[3], wo[3], f[3];
    tu_dir(30, 0, wi), tu_dir(50, 120, wo);
    pbr_ref_eval(&r, wi, wo, f);
    ck_assert(tu_close(f[1], 0.6 * 0.75 / PI, 1e-15, 0));
    /* metallic 1 and roughness 0.02 (alpha 4e-4): a mirror of reflectance Schlick(base, cos) */
    abrdf_pbr_init(&p);
    p.roughness = 0.02, p.base_color[0] = 0.3;
    ck_assert_int_eq(pbr_ref_prepare(&p, &r, msg, sizeof msg), ABRDF_OK);
    for (double t = 0; t < 80; t += 25) {
        double rho = albedo_of(&r, t, 4e-4, 96, 0);
        double want = pbr_ref_f_schlick(0.3, 1, cos(t * PI / 180));
        ck_assert_msg(fabs(rho - want) < 2e-3, "mirror at %g: %.9g vs %.9g", t, rho, want);
    }
    /* a bad material is refused with abrdf_pbr_check's message */
    p.ior = 0.5;
    ck_assert_int_eq(pbr_ref_prepare(&p, &r, msg, sizeof msg), ABRDF_E_RANGE);
    ck_assert(strstr(msg, "ior") != NULL);
}
END_TEST

/* E(cos_v) = int f_sheen(l, v) cos_l dl (sheen colour 1) by a midpoint rule over the light's
 * polar angle and azimuth, independent of the prepare step's Gauss-Legendre rule. */
static double sheen_albedo_midpoint(double alpha, double cv)
{
    enum { NT = 1200, NP = 600 };
    double v[3] = {sqrt(1 - cv * cv), 0, cv}, sum = 0;
    for (int i = 0; i < NT; ++i) {
        double t = (PI / 2) * (i + 0.5) / NT;
        for (int j = 0; j < NP; ++j) {
            double p = PI * (j + 0.5) / NP;
            double l[3] = {sin(t) * cos(p), sin(t) * sin(p), cos(t)};
            double h[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]};
            double n = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            double f = pbr_ref_d_charlie(alpha, h[2] / n) * pbr_ref_v_charlie(alpha, l[2], cv);
            sum += f * l[2] * sin(t) * (PI / 2 / NT) * (2 * PI / NP);
        }
    }
    return sum;
}

START_TEST(sheen_albedo_table)
{
    abrdf_pbr p;
    abrdf_pbr_init(&p);
    pbr_ref r;
    char msg[128];
    p.metallic = 0, p.specular = 0, p.sheen_roughness = 0.5;
    p.sheen_color[0] = p.sheen_color[1] = p.sheen_color[2] = 1;
    ck_assert_int_eq(pbr_ref_prepare(&p, &r, msg, sizeof msg), ABRDF_OK);
    for (int i = 0; i < PBR_REF_SHEEN_N; ++i)
        ck_assert_msg(r.sheen_e[i] >= 0 && r.sheen_e[i] <= 1, "E[%d] = %g", i, r.sheen_e[i]);
    const double cosines[] = {0.13, 0.5, 0.77, 0.995};
    for (int k = 0; k < 4; ++k) {
        double want = sheen_albedo_midpoint(0.25, cosines[k]);
        double got = pbr_ref_sheen_e(&r, cosines[k]);
        ck_assert_msg(fabs(got - want) < 2e-3, "E(%g): %.6f vs %.6f", cosines[k], got, want);
    }
    /* a white Lambert base under a white sheen: its albedo is E(v) plus the base scaled by
     * 1 - max(E(v), E(l)), 2 int (1 - max(E(v), E(mu))) mu dmu, and stays below 1 */
    for (double t = 0; t < 80; t += 25) {
        double cv = cos(t * PI / 180), want = pbr_ref_sheen_e(&r, cv);
        enum { NM = 20000 };
        for (int i = 0; i < NM; ++i) {
            double mu = (i + 0.5) / NM;
            want += 2 * (1 - fmax(pbr_ref_sheen_e(&r, cv), pbr_ref_sheen_e(&r, mu))) * mu / NM;
        }
        double rho = albedo_of(&r, t, 1, 96, 0);
        ck_assert_msg(fabs(rho - want) < 2e-3 && rho < 1, "furnace at %g: %.6f vs %.6f", t, rho,
                      want);
    }
}
END_TEST

/* The table's albedo order (96) against twice it, on every row (every third in a sanitizer
 * build, several times slower): the error the table prints (mapped - reference) moves
 * by less than 1e-4, each albedo by less than 1e-3. */
#ifdef PBR_REFERENCE_QUICK
#define TEST_ROW_STEP 3
#else
#define TEST_ROW_STEP 1
#endif
START_TEST(albedo_quadrature_converges)
{
    int n;
    const pbr_error_row *rows = pbr_error_rows(&n);
    ck_assert_int_ge(n, 11);
    for (int k = 0; k < n; k += TEST_ROW_STEP) {
        pbr_ref r;
        pbr_mapped m;
        char msg[128];
        ck_assert_int_eq(pbr_ref_prepare(&rows[k].material, &r, msg, sizeof msg), ABRDF_OK);
        ck_assert_int_eq(pbr_mapped_make(&rows[k].material, &m), ABRDF_OK);
        double widths[3] = {r.alpha_b, r.alpha_t, r.coat_alpha};
        for (double t = 0; t < 80; t += 37.5) {
            double wo[3], lo[3], hi[3], mlo[3], mhi[3];
            tu_dir(t, 30, wo);
            pbr_albedo(pbr_ref_brdf, &r, wo, widths, 3, 96, lo);
            pbr_albedo(pbr_ref_brdf, &r, wo, widths, 3, 192, hi);
            pbr_albedo(pbr_mapped_eval, &m, wo, widths, 3, 96, mlo);
            pbr_albedo(pbr_mapped_eval, &m, wo, widths, 3, 192, mhi);
            for (int c = 0; c < 3; ++c) {
                ck_assert_msg(fabs(lo[c] - hi[c]) < 1e-3, "%s at %g: %.8f vs %.8f", rows[k].name, t,
                              lo[c], hi[c]);
                double d = (mlo[c] - lo[c]) - (mhi[c] - hi[c]);
                ck_assert_msg(fabs(d) < 1e-4, "%s at %g: error moves by %.3g", rows[k].name, t, d);
            }
        }
    }
}
END_TEST

/* The sphere of pbr_sphere_nmse is abrdf_predict_nmse's default view: the same NMSE for a
 * pair of libabrdf BRDFs (an anisotropic one, so the tangent's direction counts too). */
START_TEST(sphere_is_the_predictions_view)
{
    abrdf_pbr a, b;
    abrdf_pbr_init(&a);
    abrdf_pbr_init(&b);
    a.metallic = 0.3, a.roughness = 0.35, a.anisotropy = 0.6, a.base_color[2] = 0.2;
    b.metallic = 0.3, b.roughness = 0.5, b.base_color[2] = 0.2;
    pbr_mapped ma, mb;
    ck_assert_int_eq(pbr_mapped_make(&a, &ma), ABRDF_OK);
    ck_assert_int_eq(pbr_mapped_make(&b, &mb), ABRDF_OK);
    size_t ws = abrdf_fit_workspace_size(NULL, NULL);
    void *w = malloc(ws);
    ck_assert_ptr_nonnull(w);
    double want, got;
    ck_assert_int_eq(abrdf_predict_nmse(ma.lobes[0], ma.lobes[1], &ma.params, mb.lobes[0],
                                        mb.lobes[1], &mb.params, NULL, &want, w, ws),
                     ABRDF_OK);
    free(w);
    ck_assert_int_eq(pbr_sphere_nmse(pbr_mapped_eval, &mb, pbr_mapped_eval, &ma, 0, &got),
                     ABRDF_OK);
    ck_assert_msg(want > 1e-3 && tu_close(got, want, 1e-9, 0), "%.12g vs %.12g", got, want);
    ck_assert_int_eq(pbr_sphere_nmse(pbr_mapped_eval, &mb, pbr_mapped_eval, &ma, 2000, &got),
                     ABRDF_E_RANGE);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("pbr_reference");
    TCase *t = tcase_create("core");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, distributions_integrate_to_one_over_the_projected_hemisphere);
    tcase_add_test(t, visibility_is_smith_height_correlated);
    tcase_add_test(t, charlie_visibility_and_schlick_in_closed_form);
    tcase_add_test(t, limits_lambert_mirror_and_transmission);
    tcase_add_test(t, sheen_albedo_table);
    tcase_add_test(t, albedo_quadrature_converges);
    tcase_add_test(t, sphere_is_the_predictions_view);
    suite_add_tcase(s, t);
    return tu_run(s);
}
