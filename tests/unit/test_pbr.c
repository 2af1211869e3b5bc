/* test_pbr.c - glTF metallic-roughness materials as abrdf lobes and as the flowchart's
 * material (abrdf_pbr.h): closed-form values of the mapping, the exactness of its specular
 * Fresnel against the glTF mix computed term by term, the anisotropy match, range errors. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "abrdf_pbr.h"
#include "test_util.h"

static double schlick(double f0, double f90, double c) { return f0 + (f90 - f0) * pow(1 - c, 5); }

START_TEST(defaults_are_gltf_defaults)
{
    abrdf_pbr p;
    ck_assert_int_eq(abrdf_pbr_init(&p), ABRDF_OK);
    ck_assert(p.struct_size == sizeof p);
    ck_assert(p.base_color[0] == 1 && p.metallic == 1 && p.roughness == 1);
    ck_assert(p.ior == 1.5 && p.specular == 1 && p.specular_color[2] == 1);
    ck_assert(p.clearcoat == 0 && p.sheen_color[0] == 0 && p.transmission == 0);
    ck_assert_int_eq(abrdf_pbr_init_sized(&p, 8), ABRDF_E_SIZE);
    ck_assert_int_eq(abrdf_pbr_init(NULL), ABRDF_E_NULL);
}
END_TEST

START_TEST(dielectric_and_metal_in_closed_form)
{
    abrdf_pbr p;
    abrdf_pbr_init(&p);
    double base[3] = {0.8, 0.4, 0.2};
    memcpy(p.base_color, base, sizeof base);
    p.metallic = 0, p.roughness = 0.3;
    abrdf_model lobes[ABRDF_PBR_MAX_LOBES];
    int n = 0;
    abrdf_params q;
    abrdf_params_init(ABRDF_LAMBERT, &q);
    ck_assert_int_eq(abrdf_pbr_lobes(&p, lobes, &n, &q), ABRDF_OK);
    ck_assert_int_eq(n, 2);
    ck_assert_int_eq(lobes[0], ABRDF_LAMBERT_FRESNEL);
    ck_assert_int_eq(lobes[1], ABRDF_DISNEY_SPECULAR);
    for (int c = 0; c < 3; ++c) {
        ck_assert_double_eq_tol(q.kd[c], base[c], 1e-15);
        ck_assert_double_eq_tol(q.ks[c], 1, 1e-15);
        ck_assert_double_eq_tol(q.f0[c], 0.04, 1e-15); /* ((1.5-1)/(1.5+1))^2 */
    }
    ck_assert_double_eq(q.r, 0.3);
    p.metallic = 1;
    ck_assert_int_eq(abrdf_pbr_lobes(&p, lobes, &n, &q), ABRDF_OK);
    for (int c = 0; c < 3; ++c) {
        ck_assert_double_eq(q.kd[c], 0);
        ck_assert_double_eq_tol(q.f0[c], base[c], 1e-15);
    }
    /* ior 2.0: f0 = 1/9; transmission halves the diffuse */
    p.metallic = 0, p.ior = 2, p.transmission = 0.5;
    ck_assert_int_eq(abrdf_pbr_lobes(&p, lobes, &n, &q), ABRDF_OK);
    ck_assert_double_eq_tol(q.f0[1], 1.0 / 9, 1e-15);
    ck_assert_double_eq_tol(q.kd[0], 0.4, 1e-15);
}
END_TEST

/* ks * Schlick(f0, 1) equals the glTF mix (1-m) w Schlick(f0_d, 1) + m Schlick(base, 1) at
 * every angle, for metallic and specular inside (0, 1) and a coloured, clamped f0_d. */
START_TEST(specular_fresnel_is_the_gltf_mix_exactly)
{
    abrdf_pbr p;
    abrdf_pbr_init(&p);
    double base[3] = {0.9, 0.6, 0.1}, sc[3] = {1, 3, 40};
    memcpy(p.base_color, base, sizeof base);
    memcpy(p.specular_color, sc, sizeof sc);
    p.ior = 1.8, p.specular = 0.7, p.metallic = 0.35;
    abrdf_model lobes[ABRDF_PBR_MAX_LOBES];
    int n;
    abrdf_params q;
    abrdf_params_init(ABRDF_LAMBERT, &q);
    ck_assert_int_eq(abrdf_pbr_lobes(&p, lobes, &n, &q), ABRDF_OK);
    double e = (1.8 - 1) / (1.8 + 1);
    for (int c = 0; c < 3; ++c) {
        double f0d = fmin(e * e * sc[c], 1);
        for (double cos_d = 0; cos_d <= 1; cos_d += 0.125) {
            double want =
                (1 - 0.35) * 0.7 * schlick(f0d, 1, cos_d) + 0.35 * schlick(base[c], 1, cos_d);
            double got = q.ks[c] * schlick(q.f0[c], 1, cos_d);
            ck_assert_msg(fabs(got - want) < 1e-14, "c %d cos %g: %.17g vs %.17g", c, cos_d, got,
                          want);
        }
    }
}
END_TEST

/* With specular weight 1 the diffuse lobe (lambert_fresnel: kd / pi (1 - Schlick(f0))) equals
 * glTF's (1 - m)(1 - t) base / pi (1 - max_c Schlick(f0_d)) at every angle, for a metallic
 * mix and a coloured f0_d. */
START_TEST(diffuse_is_the_gltf_diffuse_exactly)
{
    abrdf_pbr p;
    abrdf_pbr_init(&p);
    double base[3] = {0.8, 0.3, 0.2}, sc[3] = {2, 1, 0.5};
    memcpy(p.base_color, base, sizeof base);
    memcpy(p.specular_color, sc, sizeof sc);
    p.metallic = 0.5, p.transmission = 0.25;
    abrdf_model lobes[ABRDF_PBR_MAX_LOBES];
    int n;
    abrdf_params q;
    abrdf_params_init(ABRDF_LAMBERT, &q);
    ck_assert_int_eq(abrdf_pbr_lobes(&p, lobes, &n, &q), ABRDF_OK);
    double f0d_max = 0.04 * 2; /* the largest of 0.04 * specular_color */
    for (int c = 0; c < 3; ++c)
        for (double cos_d = 0; cos_d <= 1; cos_d += 0.125) {
            double want = 0.5 * 0.75 * base[c] * (1 - schlick(f0d_max, 1, cos_d));
            double got = q.kd[c] * (1 - schlick(q.f0[c], 1, cos_d));
            ck_assert_msg(fabs(got - want) < 1e-14, "c %d cos %g: %.17g vs %.17g", c, cos_d, got,
                          want);
        }
}
END_TEST

/* Disney's alpha_x alpha_y and alpha_x / alpha_y equal glTF's alpha_t alpha_b and
 * alpha_t / alpha_b while the ratio is within reach (aspect^2 >= 0.1). */
START_TEST(anisotropy_matches_area_and_ratio)
{
    abrdf_pbr p;
    abrdf_pbr_init(&p);
    p.roughness = 0.5, p.anisotropy = 0.4;
    abrdf_model lobes[ABRDF_PBR_MAX_LOBES];
    int n;
    abrdf_params q;
    abrdf_params_init(ABRDF_LAMBERT, &q);
    ck_assert_int_eq(abrdf_pbr_lobes(&p, lobes, &n, &q), ABRDF_OK);
    ck_assert_int_eq(lobes[1], ABRDF_DISNEY_SPECULAR_ANISO);
    double a = 0.25, at = a + (1 - a) * 0.16, ab = a;
    double aspect = sqrt(1 - 0.9 * q.anisotropic);
    double ax = q.r * q.r / aspect, ay = q.r * q.r * aspect;
    ck_assert_double_eq_tol(ax * ay, at * ab, 1e-14);
    ck_assert_double_eq_tol(ax / ay, at / ab, 1e-12);
    /* out of reach: strength 1 at roughness 0.1 clamps anisotropic to 1, area kept */
    p.roughness = 0.1, p.anisotropy = 1;
    ck_assert_int_eq(abrdf_pbr_lobes(&p, lobes, &n, &q), ABRDF_OK);
    ck_assert_double_eq(q.anisotropic, 1);
    ck_assert_double_eq_tol(pow(q.r, 4), 1.0 * 0.01, 1e-15);
}
END_TEST

START_TEST(flowchart_material_classes)
{
    abrdf_pbr p;
    abrdf_pbr_init(&p);
    abrdf_material m;
    abrdf_material_init(&m);
    p.metallic = 0, p.roughness = 0.02;
    ck_assert_int_eq(abrdf_pbr_material(&p, &m), ABRDF_OK);
    ck_assert_int_eq(m.type, ABRDF_SURFACE_GENERAL);
    ck_assert_double_eq(m.r, 0.02);
    ck_assert(m.n < 0);
    ck_assert(m.struct_size == sizeof m);
    p.clearcoat = 1, p.clearcoat_roughness = 0.05;
    ck_assert_int_eq(abrdf_pbr_material(&p, &m), ABRDF_OK);
    ck_assert_int_eq(m.type, ABRDF_SURFACE_LAYERED_PLASTIC);
    ck_assert_int_eq(m.layer_count, 1);
    ck_assert_double_eq(m.layers[0].eta, 1.5);
    ck_assert_double_eq(m.layers[0].r, 0.05);
    p.metallic = 1;
    ck_assert_int_eq(abrdf_pbr_material(&p, &m), ABRDF_OK);
    ck_assert_int_eq(m.type, ABRDF_SURFACE_LAYERED_METAL);
    ck_assert_int_eq(m.layer_count, 2);
    p.clearcoat = 0, p.metallic = 0, p.sheen_color[1] = 0.5, p.sheen_roughness = 0.7;
    ck_assert_int_eq(abrdf_pbr_material(&p, &m), ABRDF_OK);
    ck_assert_int_eq(m.type, ABRDF_SURFACE_CLOTH_ROUGH);
    p.sheen_roughness = 0.2;
    ck_assert_int_eq(abrdf_pbr_material(&p, &m), ABRDF_OK);
    ck_assert_int_eq(m.type, ABRDF_SURFACE_CLOTH_SHINY);
    /* every mapped material is one the selection accepts */
    abrdf_selection s;
    abrdf_selection_init(&s);
    ck_assert_int_eq(abrdf_select(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &s, NULL, NULL, NULL),
                     ABRDF_OK);
}
END_TEST

START_TEST(out_of_range_fields_are_named)
{
    abrdf_pbr p;
    abrdf_pbr_init(&p);
    char msg[128];
    ck_assert_int_eq(abrdf_pbr_check(&p, msg, sizeof msg), ABRDF_OK);
    p.roughness = 1.5;
    ck_assert_int_eq(abrdf_pbr_check(&p, msg, sizeof msg), ABRDF_E_RANGE);
    ck_assert_str_eq(msg, "roughness = 1.5 is outside [0, 1]");
    p.roughness = 0.5, p.base_color[2] = NAN;
    ck_assert_int_eq(abrdf_pbr_check(&p, msg, sizeof msg), ABRDF_E_RANGE);
    ck_assert_str_eq(msg, "base_color[2] = nan is not finite");
    abrdf_model lobes[2];
    int n = -1;
    abrdf_params q;
    abrdf_params_init(ABRDF_LAMBERT, &q);
    ck_assert_int_eq(abrdf_pbr_lobes(&p, lobes, &n, &q), ABRDF_E_RANGE);
    ck_assert_int_eq(n, -1); /* nothing written */
    ck_assert_int_eq(abrdf_pbr_lobes(NULL, lobes, &n, &q), ABRDF_E_NULL);
    p.base_color[2] = 0.5, p.struct_size = 4;
    ck_assert_int_eq(abrdf_pbr_check(&p, msg, sizeof msg), ABRDF_E_SIZE);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("pbr");
    TCase *tc = tcase_create("mapping");
    tcase_add_test(tc, defaults_are_gltf_defaults);
    tcase_add_test(tc, dielectric_and_metal_in_closed_form);
    tcase_add_test(tc, specular_fresnel_is_the_gltf_mix_exactly);
    tcase_add_test(tc, diffuse_is_the_gltf_diffuse_exactly);
    tcase_add_test(tc, anisotropy_matches_area_and_ratio);
    tcase_add_test(tc, flowchart_material_classes);
    tcase_add_test(tc, out_of_range_fields_are_named);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) { return tu_run(suite()); }
