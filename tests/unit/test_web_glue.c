/* test_web_glue.c - the functions the browser explorer calls (tools/web/abrdf_web.h), built
 * for the host so the sanitizers watch them: values against libabrdf's double reference,
 * the lit sphere's closed form, the selection's JSON, and every refusal (bad names, values,
 * slots, sizes) with its one-line message and the slot unchanged. The same source compiled to
 * WebAssembly is tested in a browser by tests/web. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf.h"
#include "abrdf_web.h"
#include "test_util.h"

/* f_r of one pair through the slot. */
static void eval1(int slot, const float wi[3], const float wo[3], float f[3])
{
    ck_assert_int_eq(aw_eval(slot, wi, wo, 1, f), 0);
}

START_TEST(registry_and_table)
{
    const char *m = aw_models();
    ck_assert_ptr_nonnull(m);
    ck_assert_int_eq(m[0], '[');
    for (int i = 0; i < abrdf_model_count(); ++i) {
        char key[96];
        snprintf(key, sizeof key, "{\"name\": \"%s\"", abrdf_model_get((abrdf_model)i)->name);
        ck_assert_msg(strstr(m, key), "%s missing from aw_models", key);
    }
    ck_assert_ptr_nonnull(strstr(m, "\"closedForm\": false")); /* the integrating models */
    const char *t = aw_materials();
    ck_assert_ptr_nonnull(t);
    ck_assert_ptr_nonnull(strstr(t, "{\"name\": \"gold\", \"surface\": \"general\""));
    int rows = 0;
    for (const char *p = t; (p = strstr(p, "{\"name\": ")); ++p) ++rows;
    ck_assert_int_eq(rows, 64);
}
END_TEST

/* The float batch path through a slot equals the double reference (abrdf_eval with the same
 * parameters); directions need not be unit length. */
START_TEST(eval_matches_reference)
{
    static const struct {
        const char *model, *spec, *param;
        double v[3];
        int count;
    } cases[] = {
        {"lambert", "kd=0.5,0.4,0.3", "kd", {0.5, 0.4, 0.3}, 3},
        {"blinn_phong", "n=80", "n", {80}, 1},
        {"disney_specular", "r=0.3", "r", {0.3}, 1},
        {"disney_specular", "f0=0.9,0.6,0.3", "f0", {0.9, 0.6, 0.3}, 3},
        {"kajiya_kay", "", NULL, {0}, 0},
        {"f_2e", "n=300", "n", {300}, 1},
        {"neubelt_pettineo", "r=0.6", "r", {0.6}, 1},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        ck_assert_msg(aw_set_model(1, cases[k].model, cases[k].spec) == 0, "%s: %s", cases[k].model,
                      aw_error());
        abrdf_model id;
        abrdf_params p;
        int pid;
        ck_assert_int_eq(abrdf_model_find(cases[k].model, &id), ABRDF_OK);
        abrdf_params_init(id, &p);
        if (cases[k].param) {
            ck_assert_int_eq(abrdf_param_find(cases[k].param, &pid), ABRDF_OK);
            ck_assert_int_eq(abrdf_param_set(&p, pid, cases[k].v, cases[k].count), ABRDF_OK);
        }
        for (int i = 0; i < 20; ++i) {
            double wi[3], wo[3], f[3];
            tu_dir(2.0 + 4.3 * i, 11.0 * i, wi);
            tu_dir(85.0 - 4.1 * i, 200.0 - 9.0 * i, wo);
            ck_assert_int_eq(abrdf_eval(id, &p, NULL, wi, wo, f), ABRDF_OK);
            float a[3] = {(float)(3 * wi[0]), (float)(3 * wi[1]), (float)(3 * wi[2])};
            float b[3] = {(float)(wo[0] / 2), (float)(wo[1] / 2), (float)(wo[2] / 2)}, g[3];
            eval1(1, a, b, g);
            for (int c = 0; c < 3; ++c)
                ck_assert_msg(tu_close(g[c], f[c], 1e-3, 1e-6), "%s pair %d: %g vs %g",
                              cases[k].model, i, g[c], f[c]);
        }
    }
}
END_TEST

/* A diffuse + specular pair in one slot is the sum of the two lobes on one parameter block. */
START_TEST(pair_is_the_sum)
{
    ck_assert_int_eq(aw_set_model(0, "disney_diffuse", "kd=0.6,0.2,0.1;r=0.4"), 0);
    ck_assert_int_eq(aw_set_model(1, "disney_specular", "r=0.4;f0=0.04"), 0);
    ck_assert_int_eq(
        aw_set_pair(2, "disney_diffuse", "disney_specular", "kd=0.6,0.2,0.1;r=0.4;f0=0.04"), 0);
    for (int i = 0; i < 10; ++i) {
        double wi[3], wo[3];
        tu_dir(3.0 + 8.0 * i, 20.0 * i, wi);
        tu_dir(70.0 - 5.0 * i, 150.0 + 13.0 * i, wo);
        float a[3] = {(float)wi[0], (float)wi[1], (float)wi[2]};
        float b[3] = {(float)wo[0], (float)wo[1], (float)wo[2]}, fd[3], fs[3], f[3];
        eval1(0, a, b, fd);
        eval1(1, a, b, fs);
        eval1(2, a, b, f);
        for (int c = 0; c < 3; ++c) ck_assert(tu_close(f[c], fd[c] + fs[c], 1e-6, 1e-9));
    }
    /* the diffuse lobe's own parameters are checked too; the slot keeps its pair */
    ck_assert_int_eq(aw_set_pair(2, "oren_nayar", "disney_specular", "sigma=9"), -1);
    ck_assert_str_eq(aw_error_param(), "sigma");
    ck_assert_int_eq(aw_set_pair(2, "no_such_diffuse", "disney_specular", ""), -1);
    ck_assert_ptr_nonnull(strstr(aw_error(), "unknown model 'no_such_diffuse'"));
}
END_TEST

START_TEST(refusals_keep_the_slot)
{
    float wi[3] = {0.3f, 0.0f, 1.0f}, wo[3] = {-0.2f, 0.1f, 1.0f}, before[3], after[3];
    ck_assert_int_eq(aw_set_model(2, "blinn_phong", "n=50"), 0);
    eval1(2, wi, wo, before);
    static const struct {
        const char *model, *spec, *param, *words;
    } bad[] = {
        {"blinn_phong", "n=-5", "n", "n"},
        {"disney_specular", "r=7", "r", "[0, 1]"},
        {"disney_specular", "r=abc", "r", "not a"},
        {"disney_specular", "r=nan", "r", "finite"},
        {"disney_specular", "r=1e400", "r", "finite"},
        {"lambert", "kd=0.5,0.5", "kd", "one value or three"},
        {"lambert", "kd=0.5,0.5,0.5,0.5", "kd", "at most three"},
        {"lambert", "kd=0.5,0.5,1.5", "kd", "kd = 1.5 is outside [0, 1]"},
        {"disney_specular", "r=0.1,0.2", "r", "r takes one value"},
        {"disney_specular", "r=0x1", "r", "decimal"},
        {"disney_specular", "r= 0.5", "r", "decimal"},
        {"lambert", "r=0.3", "r", "not a parameter of lambert"},
        {"cook_torrance", "kd=0.1", "kd", "not a parameter of cook_torrance"},
        {"disney_specular", "roughness=0.3", "roughness", "unknown parameter"},
        {"disney_specular", "r", "", "NAME=VALUE"},
        {"no_such_model", "", "", "unknown model"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        ck_assert_int_eq(aw_set_model(2, bad[i].model, bad[i].spec), -1);
        ck_assert_msg(strstr(aw_error(), bad[i].words), "%s: '%s'", bad[i].spec, aw_error());
        ck_assert_msg(!strchr(aw_error(), '\n'), "%s", aw_error());
        ck_assert_str_eq(aw_error_param(), bad[i].param);
        eval1(2, wi, wo, after);
        ck_assert(memcmp(before, after, sizeof before) == 0);
    }
    char *big = malloc(5000);
    memset(big, 'r', 4999);
    big[4999] = '\0';
    ck_assert_int_eq(aw_set_model(2, "lambert", big), -1);
    free(big);
    ck_assert_int_eq(aw_set_model(AW_SLOTS, "lambert", ""), -1);
    ck_assert_int_eq(aw_set_model(-1, "lambert", ""), -1);
    float f[3];
    ck_assert_int_eq(aw_eval(3, wi, wo, 1, f), -1); /* never set */
    ck_assert_ptr_nonnull(strstr(aw_error(), "no model in slot 3"));
}
END_TEST

/* A white Lambert sphere: L = cos(n, l) where lit, 0 outside the disk and in the shadow; the
 * coarse steps fill their blocks; bands equal the whole image. */
START_TEST(sphere_closed_form)
{
    enum { S = 64 };
    ck_assert_int_eq(aw_set_model(0, "lambert", "kd=1"), 0);
    static float full[3 * S * S], band[3 * S * S], coarse[3 * S * S];
    unsigned char mask[S * S];
    double l[3] = {0.3, 0.5, 1.0}, ll = sqrt(0.09 + 0.25 + 1.0);
    ck_assert_int_eq(aw_sphere_rows(0, S, l[0], l[1], l[2], 0, S, 1, full), 0);
    aw_mask(S, mask);
    for (int y = 0; y < S; ++y)
        for (int x = 0; x < S; ++x) {
            double u = 2.0 * (x + 0.5) / S - 1.0, v = -(2.0 * (y + 0.5) / S - 1.0);
            double r2 = u * u + v * v;
            ck_assert_int_eq(mask[y * S + x], r2 < 1.0);
            double want = 0.0;
            if (r2 < 1.0) {
                double c = (u * l[0] + v * l[1] + sqrt(1.0 - r2) * l[2]) / ll;
                want = c > 0.0 ? c : 0.0;
            }
            for (int c = 0; c < 3; ++c)
                ck_assert_msg(fabs(full[3 * (y * S + x) + c] - want) < 1e-5, "(%d, %d): %g vs %g",
                              x, y, full[3 * (y * S + x) + c], want);
        }
    for (int y0 = 0; y0 < S; y0 += 24) {
        int y1 = y0 + 24 < S ? y0 + 24 : S;
        ck_assert_int_eq(aw_sphere_rows(0, S, l[0], l[1], l[2], y0, y1, 1, band), 0);
        ck_assert(memcmp(band, full + 3 * y0 * S, sizeof(float) * 3 * S * (y1 - y0)) == 0);
    }
    /* step 4 in bands that do not start on a block: every pixel equals its block's sample */
    for (int y0 = 0; y0 < S; y0 += 10) {
        int y1 = y0 + 10 < S ? y0 + 10 : S;
        ck_assert_int_eq(aw_sphere_rows(0, S, l[0], l[1], l[2], y0, y1, 4, coarse + 3 * y0 * S), 0);
    }
    for (int y = 0; y < S; ++y)
        for (int x = 0; x < S; ++x) {
            int cx = (x / 4) * 4 + 2, cy = (y / 4) * 4 + 2;
            float got = coarse[3 * (y * S + x)], want = full[3 * (cy * S + cx)];
            ck_assert_msg(got == want || (got == 0.0f && !mask[cy * S + cx]),
                          "(%d, %d): %g vs block %g", x, y, got, want);
        }
    /* a refusal says why, and never repeats an earlier call's message */
    ck_assert_int_eq(aw_set_model(1, "oren_nayar", "sigma=9"), -1);
    ck_assert_int_eq(aw_sphere_rows(0, S, 0, 0, 1, 0, S, 1000, full), -1);
    ck_assert_ptr_nonnull(strstr(aw_error(), "step 1000 is outside [1, 64]"));
    ck_assert_int_eq(aw_sphere_rows(0, 1 << 20, 0, 0, 1, 0, 1, 1, full), -1);
    ck_assert_ptr_nonnull(strstr(aw_error(), "size 1048576 is outside [1, 4096]"));
    ck_assert_int_eq(aw_sphere_rows(0, S, 0, 0, 0, 0, S, 1, full), -1);
    ck_assert_ptr_nonnull(strstr(aw_error(), "light direction"));
    ck_assert_int_eq(aw_sphere_rows(0, S, NAN, 0, 1, 0, S, 1, full), -1);
    ck_assert_int_eq(aw_sphere_rows(0, S, 0, 0, 1, 0, S + 1, 1, full), -1);
    ck_assert_int_eq(aw_sphere_rows(0, S, 0, 0, 1, 5, 5, 1, full), -1);
    ck_assert_int_eq(aw_sphere_rows(0, S, 0, 0, 1, 0, S, 0, full), -1);
    ck_assert_int_eq(aw_sphere_rows(0, 0, 0, 0, 1, 0, 0, 1, full), -1);
}
END_TEST

/* Every parameter of every model takes the ends of the range aw_models advertises (as text
 * read back from its JSON, as the page's sliders send them). */
START_TEST(advertised_ranges_are_taken)
{
    const char *m = aw_models();
    ck_assert_ptr_nonnull(m);
    char *json = malloc(strlen(m) + 1);
    ck_assert_ptr_nonnull(json);
    strcpy(json, m);
    int checked = 0;
    for (char *model = strstr(json, "{\"name\": \""); model;) {
        char name[64];
        ck_assert_int_eq(sscanf(model, "{\"name\": \"%63[^\"]\"", name), 1);
        char *next = strstr(model + 1, "\n{\"name\": \"");
        char *params = strstr(model, "\"params\": [");
        for (char *p = params ? strstr(params, "{\"name\": \"") : NULL; p && (!next || p < next);
             p = strstr(p + 1, "{\"name\": \"")) {
            char pname[64], lo[64], hi[64];
            ck_assert_int_eq(sscanf(p, "{\"name\": \"%63[^\"]\"", pname), 1);
            char *kmin = strstr(p, "\"min\": "), *kmax = strstr(p, "\"max\": ");
            ck_assert_int_eq(sscanf(kmin, "\"min\": %63[^,]", lo), 1);
            ck_assert_int_eq(sscanf(kmax, "\"max\": %63[^,]", hi), 1);
            if (!strcmp(name, "measured")) continue; /* needs a measured table */
            for (int end = 0; end < 2; ++end) {
                char spec[200];
                snprintf(spec, sizeof spec, "%s=%s", pname, end ? hi : lo);
                ck_assert_msg(aw_set_model(3, name, spec) == 0, "%s %s: %s", name, spec,
                              aw_error());
                ++checked;
            }
        }
        model = next ? next + 1 : NULL;
    }
    free(json);
    ck_assert_int_gt(checked, 100);
}
END_TEST

/* The sphere's shading frame: tangent around +y, view +z; a pixel of an anisotropic, a fibre
 * and a Fresnel lobe equals abrdf_eval with that frame in world space. */
START_TEST(sphere_frame)
{
    enum { S = 32 };
    static float img[3 * S * S];
    static const char *const models[] = {"disney_specular_aniso", "kajiya_kay", "cook_torrance"};
    double l[3] = {-0.4, 0.6, 0.7}, wo[3] = {0.0, 0.0, 1.0};
    for (int k = 0; k < 3; ++k) {
        abrdf_model id;
        abrdf_params p;
        ck_assert_int_eq(abrdf_model_find(models[k], &id), ABRDF_OK);
        abrdf_params_init(id, &p);
        ck_assert_int_eq(aw_set_model(0, models[k], ""), 0);
        ck_assert_int_eq(aw_sphere_rows(0, S, l[0], l[1], l[2], 0, S, 1, img), 0);
        int compared = 0;
        for (int y = 3; y < S; y += 5)
            for (int x = 2; x < S; x += 5) {
                double u = 2.0 * (x + 0.5) / S - 1.0, v = -(2.0 * (y + 0.5) / S - 1.0);
                if (u * u + v * v >= 0.95) continue;
                double n[3] = {u, v, sqrt(1.0 - u * u - v * v)};
                double ll = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
                double cosl = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / ll;
                if (cosl <= 0.05) continue;
                double t[3] = {n[2], 0.0, -n[0]}, f[3];
                abrdf_frame fr;
                ck_assert_int_eq(abrdf_frame_make(n, t, &fr), ABRDF_OK);
                ck_assert_int_eq(abrdf_eval(id, &p, &fr, l, wo, f), ABRDF_OK);
                for (int c = 0; c < 3; ++c) {
                    double want = f[c] * cosl * 3.14159265358979323846;
                    ck_assert_msg(tu_close(img[3 * (y * S + x) + c], want, 2e-3, 1e-6),
                                  "%s (%d, %d): %g vs %g", models[k], x, y,
                                  img[3 * (y * S + x) + c], want);
                }
                ++compared;
            }
        ck_assert_int_gt(compared, 10);
    }
}
END_TEST

START_TEST(plane_and_hemisphere)
{
    enum { N = 181 };
    double t[N];
    float f[3 * N], h[3 * 8 * 16];
    ck_assert_int_eq(aw_set_model(0, "blinn_phong", "n=200"), 0);
    ck_assert_int_eq(aw_plane(0, 30.0, N, t, f), 0);
    ck_assert(t[0] == -90.0 && t[N - 1] == 90.0);
    int peak = 0;
    for (int k = 1; k < N; ++k)
        if (f[3 * k] > f[3 * peak]) peak = k;
    ck_assert_msg(fabs(t[peak] + 30.0) < 1e-9, "peak at %g", t[peak]); /* the mirror */
    ck_assert_int_eq(aw_plane(0, 30.0, 1, t, f), -1);
    ck_assert_int_eq(aw_set_model(1, "oren_nayar", "sigma=9"), -1);
    ck_assert_int_eq(aw_plane(0, 30.0, 5000, t, f), -1);
    ck_assert_ptr_nonnull(strstr(aw_error(), "plane: 5000 samples is outside [2, 1024]"));
    ck_assert_int_eq(aw_plane(0, NAN, 5, t, f), -1);
    ck_assert_int_eq(aw_hemisphere(0, 30.0, 0.0, 70000, 70000, h), -1);
    ck_assert_ptr_nonnull(strstr(aw_error(), "hemisphere: a 70000 x 70000 grid"));
    ck_assert_int_eq(aw_hemisphere(0, 30.0, 0.0, 1024, 1025, h), -1);
    ck_assert_int_eq(aw_eval(0, NULL, NULL, -1, NULL), -1);
    ck_assert_ptr_nonnull(strstr(aw_error(), "-1 direction pairs"));
    unsigned char mk[1];
    ck_assert_int_eq(aw_mask(70000, mk), -1);
    ck_assert(isnan(aw_nmse(NULL, NULL, -4)));
    ck_assert_int_eq(aw_hemisphere(0, 30.0, 0.0, 8, 16, h), 0);
    for (int i = 0; i < 3 * 8 * 16; ++i) ck_assert(isfinite(h[i]) && h[i] >= 0.0f);
    ck_assert_int_eq(aw_hemisphere(0, 30.0, 0.0, 0, 16, h), -1);
}
END_TEST

START_TEST(nmse_and_classes)
{
    float a[4] = {1, 2, 3, 4}, b[4] = {1, 2, 3, 4}, z[4] = {0, 0, 0, 0};
    ck_assert(aw_nmse(a, b, 4) == 0.0);
    b[3] = 4.02f; /* (0.02)^2 / 30.16 = 1.3e-5 */
    ck_assert(tu_close(aw_nmse(a, b, 4), 0.0004 / (1 + 4 + 9 + 4.02 * 4.02), 1e-5, 0));
    ck_assert_str_eq(aw_nmse_class(aw_nmse(a, b, 4)), "none");
    ck_assert_str_eq(aw_nmse_class(2e-4), "slight");
    ck_assert_str_eq(aw_nmse_class(5e-4), "noticeable");
    ck_assert_str_eq(aw_nmse_class(0.5), "significant");
    ck_assert(aw_nmse(z, z, 4) == 0.0);
    ck_assert(isinf(aw_nmse(a, z, 4)));
}
END_TEST

START_TEST(selection_json)
{
    const char *s = aw_select("name=gold", "photoreal");
    ck_assert_msg(s != NULL, "%s", aw_error());
    ck_assert_ptr_nonnull(strstr(s, "{\"material\": \"gold\""));
    ck_assert_ptr_nonnull(strstr(s, "\"specular\": \"disney_specular\""));
    ck_assert_ptr_nonnull(strstr(s, "\"trace\": ["));
    s = aw_select("name=gold;r=0.01", "photoreal"); /* smooth: another branch */
    ck_assert_msg(s != NULL, "%s", aw_error());
    ck_assert_ptr_nonnull(strstr(s, "alpha 0.01"));
    s = aw_select("type=general;n=300;kd=0.5,0.4,0.3", "performance");
    ck_assert_msg(s != NULL, "%s", aw_error());
    ck_assert_ptr_nonnull(strstr(s, "\"material\": null"));
    static const struct {
        const char *spec, *goal, *param, *words;
    } bad[] = {
        {"name=unobtainium", "photoreal", "name", "unknown material 'unobtainium'"},
        {"name=gold", "beauty", "goal", "unknown goal 'beauty'"},
        {"name=gold;r=abc", "photoreal", "r", "not a finite number"},
        {"name=gold;kd=1,2", "photoreal", "kd", "three"},
        {"type=metal", "photoreal", "type", "unknown surface type 'metal'"},
        {"r=0.2;name=gold", "photoreal", "name", "before its values"},
        {"colour=red", "photoreal", "colour", "unknown material value"},
        {"name=gold;r=5", "photoreal", "r", "r = 5 is outside [0, 1]"},
        {"type=general;n=-5;r=-1", "photoreal", "n", "n = -5 is outside [0, 1e+06]"},
        {"name=gold;eta=0.5", "photoreal", "eta", "eta = 0.5 is outside [1, 4]"},
        {"name=gold;kd=0.5,0.5,2", "photoreal", "kd", "kd = 2 is outside [0, 1]"},
        {"name=gold;r=0x0.1", "photoreal", "r", "not a finite number"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        ck_assert_msg(aw_select(bad[i].spec, bad[i].goal) == NULL, "%s accepted", bad[i].spec);
        ck_assert_msg(strstr(aw_error(), bad[i].words), "%s: '%s'", bad[i].spec, aw_error());
        ck_assert_str_eq(aw_error_param(), bad[i].param);
    }
    ck_assert_ptr_null(aw_budget("name=gold", 0.0, 0));
    ck_assert_ptr_nonnull(strstr(aw_error(), "not in (0, 1]"));
    ck_assert_ptr_null(aw_budget("name=unobtainium", 2.5e-4, 0));
}
END_TEST

/* The budget mode's JSON: one material whose candidates fit fast (rough cloth has the fewest;
 * the command's tests hold the budget mode's values, tests/cli/test_cli_budget.py). */
START_TEST(budget_json)
{
    const char *s = aw_budget("type=cloth_rough;r=0.6", 2.5e-4, 0);
    ck_assert_msg(s != NULL, "%s", aw_error());
    ck_assert_ptr_nonnull(strstr(s, "\"budget\": {\"max_nmse\": 0.00025, \"class\": \"slight\"}"));
    ck_assert_ptr_nonnull(strstr(s, "\"candidates\": ["));
    ck_assert_ptr_nonnull(strstr(s, "\"pareto\": true"));
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("web_glue");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, registry_and_table);
    tcase_add_test(tc, eval_matches_reference);
    tcase_add_test(tc, pair_is_the_sum);
    tcase_add_test(tc, refusals_keep_the_slot);
    tcase_add_test(tc, sphere_closed_form);
    tcase_add_test(tc, advertised_ranges_are_taken);
    tcase_add_test(tc, sphere_frame);
    tcase_add_test(tc, plane_and_hemisphere);
    tcase_add_test(tc, nmse_and_classes);
    tcase_add_test(tc, selection_json);
    tcase_add_test(tc, budget_json);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) { return tu_run(suite()); }
