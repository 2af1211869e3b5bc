/* test_render.c - the renderer against closed forms (one pixel), determinism across thread
 * counts, and the effect plan proved by the work counters. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render.h"
#include "scene_points.h"
#include "scene_select.h"
#include "test_util.h"

static const double PI = 3.14159265358979323846;

typedef struct result {
    int w, h;
    float *rgb;
    render_stats st;
} result;

/* The precision the "values" tests render in: each runs once per precision (a loop test whose
 * index is the render_precision), the plan tests in the default (float). */
static int precision = RENDER_FLOAT;
/* Closed-form tolerance of a pixel: the double path is exact to rounding; the float path
 * evaluates the BRDF in float (abrdf.h: the batch path's tolerance). */
static double pixel_tol(void) { return precision == RENDER_DOUBLE ? 1e-6 : 2e-5; }

/* Render scene text at its own resolution (size 0) or size x size. */
static result render_text_at(const char *text, int spp, int threads, int size, int full)
{
    scene s;
    char err[512];
    ck_assert_msg(scene_parse_text("t", text, strlen(text), &s, err, sizeof err) == 0, "%s", err);
    render_options opt = {size, size, spp, 0, threads, 0, precision, 0, 0, 0, 0, NULL};
    render_scene rs;
    ck_assert_msg(render_prepare(&s, &opt, &rs, err, sizeof err) == 0, "%s", err);
    if (full) ck_assert_int_eq(render_plan_ignore(&rs), 0);
    result r = {rs.width, rs.height, malloc((size_t)rs.width * rs.height * 3 * sizeof(float)), {0}};
    ck_assert_ptr_nonnull(r.rgb);
    ck_assert_int_eq(render_image(&rs, &opt, r.rgb, &r.st), 0);
    render_release(&rs);
    scene_free(&s);
    return r;
}

static result render_text(const char *text, int spp, int threads)
{
    return render_text_at(text, spp, threads, 0, 0);
}

static const float *pixel(const result *r, int i, int j)
{
    return r->rgb + 3 * ((size_t)j * r->w + i);
}

/* Unit sphere at the origin, camera on +z: the centre pixel of an odd-sized image with one
 * sample sees (0, 0, 1) with N = +z and wo = +z. */
START_TEST(lambert_centre_pixel_directional)
{
    precision = _i;
    const char *text = "camera position=0,0,4 look_at=0,0,0 fov=30 resolution=33,33\n"
                       "light directional direction=0,0.5,0.8660254037844386 intensity=3\n"
                       "ambient 0.1\n"
                       "material m model=lambert kd=0.5,0.25,0.125\n"
                       "sphere material=m radius=1\n";
    result r = render_text(text, 1, 1);
    const float *p = pixel(&r, 16, 16);
    double kd[3] = {0.5, 0.25, 0.125};
    for (int c = 0; c < 3; ++c) {
        double want = kd[c] * 0.1 + 3.0 * kd[c] / PI * cos(PI / 6); /* ka*Ia + E kd/pi cos */
        ck_assert_msg(tu_close(p[c], want, pixel_tol(), 0), "c%d %.9g vs %.9g", c, p[c], want);
    }
    /* The corner sees no object: black background. */
    ck_assert(pixel(&r, 0, 0)[0] == 0.0f);
    free(r.rgb);
}
END_TEST

/* A diffuse + specular pair is the paper's I = ka Ia + Il cos (f_d + f_s): the centre pixel
 * equals abrdf_shade for the same directions. */
START_TEST(pair_matches_abrdf_shade)
{
    precision = _i;
    const char *text =
        "camera position=0,0,4 look_at=0,0,0 fov=30 resolution=33,33\n"
        "light directional direction=0.3,0.4,0.8660254037844386 color=1,0.8,0.6 intensity=2\n"
        "ambient 0.05\n"
        "material m diffuse=disney_diffuse specular=disney_specular kd=0.4,0.3,0.2 r=0.35 f0=0.9\n"
        "sphere material=m radius=1\n";
    result r = render_text(text, 1, 2);
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_DIFFUSE, &p);
    p.kd[0] = 0.4, p.kd[1] = 0.3, p.kd[2] = 0.2;
    p.r = 0.35;
    p.f0[0] = p.f0[1] = p.f0[2] = 0.9;
    double wi[3] = {0.3, 0.4, 0.8660254037844386}, wo[3] = {0, 0, 1}, light[3] = {2, 1.6, 1.2};
    double l = sqrt(wi[0] * wi[0] + wi[1] * wi[1] + wi[2] * wi[2]);
    for (int c = 0; c < 3; ++c) wi[c] /= l;
    double ambient[3] = {0.4 * 0.05, 0.3 * 0.05, 0.2 * 0.05}, want[3];
    ck_assert_int_eq(abrdf_shade(ABRDF_DISNEY_DIFFUSE, ABRDF_DISNEY_SPECULAR, &p, NULL, wi, wo,
                                 light, ambient, want),
                     ABRDF_OK);
    for (int c = 0; c < 3; ++c)
        ck_assert_msg(tu_close(pixel(&r, 16, 16)[c], want[c], pixel_tol(), 0), "c%d %.9g vs %.9g",
                      c, pixel(&r, 16, 16)[c], want[c]);
    free(r.rgb);
}
END_TEST

START_TEST(point_light_falls_off_with_distance_squared)
{
    precision = _i;
    const char *text = "camera position=0,0,4 look_at=0,0,0 fov=30 resolution=33,33\n"
                       "light point position=0,0,3 intensity=8\n"
                       "material m model=lambert kd=0.5\n"
                       "sphere material=m radius=1\n";
    result r = render_text(text, 1, 1);
    double want = 8.0 / 4.0 * 0.5 / PI; /* d = 2, cos = 1 */
    ck_assert_msg(tu_close(pixel(&r, 16, 16)[0], want, pixel_tol(), 0), "%.9g vs %.9g",
                  pixel(&r, 16, 16)[0], want);
    free(r.rgb);
}
END_TEST

/* A box filter over the pixel: with 4 x 4 samples the centre pixel is the mean of 16
 * radiance samples, each computed in closed form here from the same camera model. */
START_TEST(box_filter_matches_camera_model)
{
    precision = _i;
    const char *text = "camera position=0,0,4 look_at=0,0,0 fov=30 resolution=9,9\n"
                       "light directional direction=0,0,1 intensity=1\n"
                       "material m model=lambert kd=1\n"
                       "sphere material=m radius=1\n";
    result r = render_text(text, 16, 2);
    double h = tan(PI / 12), sum = 0;
    for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
            double x = 4 + (sx + 0.5) / 4, y = 4 + (sy + 0.5) / 4;
            double d[3] = {(2 * x / 9 - 1) * h, (1 - 2 * y / 9) * h, -1};
            double l = sqrt(d[0] * d[0] + d[1] * d[1] + 1);
            for (int c = 0; c < 3; ++c) d[c] /= l;
            /* |o + t d| = 1 with o = (0, 0, 4) */
            double b = 4 * d[2], t = -b - sqrt(b * b - 15);
            double nz = 4 + t * d[2];
            sum += nz / PI; /* E = 1, light along +z: cos = N.z */
        }
    ck_assert_msg(tu_close(pixel(&r, 4, 4)[0], sum / 16, pixel_tol(), 0), "%.9g vs %.9g",
                  pixel(&r, 4, 4)[0], sum / 16);
    free(r.rgb);
}
END_TEST

/* The pixel footprint as other renderers can reproduce it: k x k strata centres of a W x H
 * image are the pixel centres of a kW x kH image, so averaging k x k blocks of the larger
 * one-sample image gives the supersampled image. */
START_TEST(strata_centres_equal_block_average_of_larger_image)
{
    precision = _i;
    const char *text = "camera position=0.3,0.2,4 look_at=0,0,0 fov=30 resolution=7,5\n"
                       "light directional direction=1,1,1\n"
                       "material m diffuse=lambert specular=disney_specular kd=0.5 r=0.3\n"
                       "sphere material=m radius=1\n";
    scene s;
    char err[256];
    ck_assert(scene_parse_text("t", text, strlen(text), &s, err, sizeof err) == 0);
    render_options small = {7, 5, 9, 0, 2, 0, precision, 0, 0, 0, 0, NULL},
                   big = {21, 15, 1, 0, 2, 0, precision, 0, 0, 0, 0, NULL};
    float a[7 * 5 * 3], b[21 * 15 * 3];
    render_scene rs;
    ck_assert(render_prepare(&s, &small, &rs, err, sizeof err) == 0);
    ck_assert(render_image(&rs, &small, a, NULL) == 0);
    render_release(&rs);
    ck_assert(render_prepare(&s, &big, &rs, err, sizeof err) == 0);
    ck_assert(render_image(&rs, &big, b, NULL) == 0);
    render_release(&rs);
    int nonzero = 0;
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 7; ++i)
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                for (int y = 0; y < 3; ++y)
                    for (int x = 0; x < 3; ++x) sum += b[3 * ((3 * j + y) * 21 + 3 * i + x) + c];
                float v = a[3 * (j * 7 + i) + c];
                nonzero += v > 0;
                ck_assert_msg(tu_close(v, sum / 9, pixel_tol(), 1e-12), "(%d,%d) %.9g vs %.9g", i,
                              j, v, sum / 9);
            }
    ck_assert(nonzero > 10);
    scene_free(&s);
}
END_TEST

static char *read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    ck_assert_msg(f != NULL, "cannot open %s", path);
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return buf;
}

static char robot[1 << 16];

static void load_robot(void) { strcpy(robot, read_file(SCENES_DIR "/robot.scene")); }

START_TEST(bit_identical_for_any_thread_count)
{
    precision = _i;
    load_robot();
    scene s;
    char err[256];
    ck_assert(scene_parse_text("robot", robot, strlen(robot), &s, err, sizeof err) == 0);
    float *img[3];
    render_stats st[3];
    int threads[3] = {1, 2, 2};
    for (int k = 0; k < 3; ++k) {
        render_options opt = {64, 64, 4, k == 2, threads[k], 0, precision, 0, 0, 0, 0, NULL};
        render_scene rs;
        ck_assert(render_prepare(&s, &opt, &rs, err, sizeof err) == 0);
        img[k] = malloc(64 * 64 * 3 * sizeof(float));
        ck_assert_int_eq(render_image(&rs, &opt, img[k], &st[k]), 0);
        render_release(&rs);
    }
    ck_assert_msg(memcmp(img[0], img[1], 64 * 64 * 3 * sizeof(float)) == 0,
                  "1 vs 2 threads differ");
    ck_assert(memcmp(&st[0], &st[1], sizeof st[0]) == 0);
    /* jitter moves samples: a different image, so the test above could have failed */
    ck_assert(memcmp(img[0], img[2], 64 * 64 * 3 * sizeof(float)) != 0);
    for (int k = 0; k < 3; ++k) free(img[k]);
    scene_free(&s);
}
END_TEST

/* The fast path against the double reference: every model, both shipped scenes, within
 * NMSE 1e-8 (sum (F - D)^2 / sum D^2, the paper's metric). Small images: the models that
 * integrate inside eval cost ~1e5 times more per evaluation. */
static double nmse_fast_vs_double(const scene *s, int size)
{
    float *img[2];
    for (int k = 0; k < 2; ++k) {
        render_options opt = {size, size, 1, 0, 2,   0, k ? RENDER_DOUBLE : RENDER_FLOAT,
                              0,    0,    0, 0, NULL};
        render_scene rs;
        char err[512];
        ck_assert_msg(render_prepare(s, &opt, &rs, err, sizeof err) == 0, "%s", err);
        img[k] = malloc((size_t)size * size * 3 * sizeof(float));
        ck_assert_int_eq(render_image(&rs, &opt, img[k], NULL), 0);
        render_release(&rs);
    }
    double num = 0, den = 0;
    for (int q = 0; q < size * size * 3; ++q) {
        double d = (double)img[0][q] - img[1][q];
        num += d * d, den += (double)img[1][q] * img[1][q];
    }
    free(img[0]), free(img[1]);
    ck_assert(den > 0);
    return num / den;
}

START_TEST(fast_path_within_nmse_1e8_of_double)
{
    const char *scenes[2] = {SCENES_DIR "/sphere.scene", SCENES_DIR "/robot.scene"};
    double worst = 0;
    for (int sc = 0; sc < 2; ++sc) {
        char *text = read_file(scenes[sc]);
        for (int mi = -1; mi < abrdf_model_count(); ++mi) { /* -1: the scene's own materials */
            scene s;
            char err[512];
            ck_assert(scene_parse_text("t", text, strlen(text), &s, err, sizeof err) == 0);
            const abrdf_model_info *m = mi < 0 ? NULL : tu_param_model(mi);
            if (mi >= 0 && !m) {
                scene_free(&s);
                continue; /* the measured model renders a table (test_measured.c) */
            }
            if (m) ck_assert_msg(scene_replace_models(&s, m->id, err, sizeof err) == 0, "%s", err);
            int size = m && (m->needs & ABRDF_NEEDS_INTEGRATION) ? 12 : 40;
            double e = nmse_fast_vs_double(&s, size);
            worst = e > worst ? e : worst;
            printf("fast vs double %-6s %-22s NMSE %.3g\n", sc ? "robot" : "sphere",
                   m ? m->name : "(scene)", e);
            ck_assert_msg(e <= 1e-8, "%s on %s: NMSE %.3g > 1e-8", m ? m->name : "scene",
                          scenes[sc], e);
            scene_free(&s);
        }
    }
    printf("fast vs double: largest NMSE %.3g (limit 1e-8)\n", worst);
}
END_TEST

/* ---- the effect plan, proved by counters ------------------------------------------- */

START_TEST(single_sphere_casts_no_shadow_rays)
{
    result r = render_text(read_file(SCENES_DIR "/sphere.scene"), 1, 2);
    ck_assert(r.st.hits > 0 && r.st.brdf_evals > 0);
    ck_assert_uint_eq(r.st.shadow_rays, 0);
    ck_assert_uint_eq(r.st.occluder_tests, 0);
    ck_assert(r.st.shadow_rays_skipped > 0);
    ck_assert_uint_eq(r.st.tangent_frames, 0); /* isotropic lobes */
    ck_assert_uint_eq(r.st.ambient_terms, 0);  /* ambient 0 */
    free(r.rgb);
}
END_TEST

START_TEST(robot_casts_shadow_rays_and_shadows_darken)
{
    load_robot();
    result r = render_text_at(robot, 1, 2, 128, 0);
    ck_assert(r.st.shadow_rays > 0 && r.st.occluder_tests > 0);
    /* Rays run the exact intersector only on the few objects Embree's BVH offers them: a
     * camera ray fewer than 35/4 of the 35, a shadow ray (which also skips its own convex
     * object) fewer than 2. */
    ck_assert(r.st.primary_tests * 4 < r.st.primary_rays * 35);
    ck_assert(r.st.occluder_tests < 2 * r.st.shadow_rays);
    ck_assert_uint_eq(r.st.tangent_frames, 0);
    ck_assert_uint_eq(r.st.ambient_terms, r.st.hits);
    /* Some lit samples are blocked: fewer BRDF evaluations than lit samples would need. */
    ck_assert(r.st.brdf_evals < 2 * (r.st.shadow_rays + r.st.shadow_rays_skipped));
    free(r.rgb);
}
END_TEST

/* The plan skips only work that cannot change the image: rendering with every effect
 * everywhere (shadow rays toward every object, tangent frames, ambient) gives the same
 * pixels up to rounding, while doing more work. A shadow the plan wrongly skipped would
 * differ by the whole direct light. */
static void expect_plan_is_exact(const char *text, int size)
{
    result a = render_text_at(text, 1, 2, size, 0), b = render_text_at(text, 1, 2, size, 1);
    double worst = 0;
    for (size_t k = 0; k < (size_t)a.w * a.h * 3; ++k)
        worst = fmax(worst, fabs(a.rgb[k] - b.rgb[k]) / fmax(1e-3, fabs(b.rgb[k])));
    ck_assert_msg(worst < 1e-5, "planned vs full render: rel diff %g", worst);
    ck_assert_uint_eq(a.st.hits, b.st.hits); /* primary visibility is exact */
    ck_assert(b.st.primary_tests >= a.st.primary_tests);
    ck_assert(b.st.occluder_tests >= a.st.occluder_tests);
    ck_assert(b.st.tangent_frames >= a.st.tangent_frames);
    free(a.rgb);
    free(b.rgb);
}

START_TEST(plan_changes_no_pixel)
{
    load_robot();
    expect_plan_is_exact(robot, 96);
    expect_plan_is_exact(read_file(SCENES_DIR "/sphere.scene"), 64);
    expect_plan_is_exact(read_file(FUZZ_CORPUS "/shapes.scene"), 64);
    /* Culling at the image edges and behind the eye: a wide view from inside a ring of
     * objects, one of them around the eye, one straddling the image plane's side. */
    expect_plan_is_exact(
        "camera position=0,0,0 look_at=0,0,-1 fov=150 resolution=40,30\n"
        "light point position=0,3,0 intensity=20\n"
        "ambient 0.1\n"
        "material m diffuse=lambert specular=disney_specular_aniso r=0.3 anisotropic=0.5\n"
        "sphere material=m radius=1 translate=0,0,-3\n"
        "sphere material=m radius=1 translate=0,0,3\n"
        "box material=m size=1,1,1 translate=4,0,-0.2\n"
        "capsule material=m radius=0.5 height=4 rotate=0,0,90 translate=-3,-1,0.4\n"
        "cylinder material=m radius=0.3 height=1 translate=0,5,-0.5\n"
        "box material=m size=20,20,20 translate=0,0,0\n",
        40);
}
END_TEST

START_TEST(separated_objects_need_no_shadow_rays)
{
    /* Two spheres side by side, light from the camera: neither bounding capsule toward the
     * light meets the other sphere. Move the light sideways and they can shadow each other. */
    const char *fmt = "camera position=0,0,10 look_at=0,0,0 resolution=32,32\n"
                      "light directional direction=%s\n"
                      "material m model=lambert\n"
                      "sphere material=m radius=1 translate=-2,0,0\n"
                      "sphere material=m radius=1 translate=2,0,0\n";
    char text[512];
    snprintf(text, sizeof text, fmt, "0,0,1");
    result a = render_text(text, 1, 1);
    ck_assert_uint_eq(a.st.shadow_rays, 0);
    ck_assert(a.st.shadow_rays_skipped > 0);
    snprintf(text, sizeof text, fmt, "1,0,0");
    result b = render_text(text, 1, 1);
    ck_assert(b.st.shadow_rays > 0);
    free(a.rgb);
    free(b.rgb);
}
END_TEST

static const char *ANISO = "camera position=0,0,4 look_at=0,0,0 resolution=24,24\n"
                           "light directional direction=1,1,1\n"
                           "material m model=%s %s\n"
                           "sphere material=m radius=1 tangent=u\n";

START_TEST(tangent_frames_only_for_anisotropic_materials)
{
    char text[512];
    snprintf(text, sizeof text, ANISO, "disney_specular_aniso", "r=0.4 anisotropic=0.8");
    result an = render_text(text, 1, 1);
    ck_assert(an.st.tangent_frames > 0);
    ck_assert(an.st.tangent_frames <= an.st.hits);
    snprintf(text, sizeof text, ANISO, "disney_specular_aniso", "r=0.4 anisotropic=0");
    result a0 = render_text(text, 1, 1);
    ck_assert_uint_eq(a0.st.tangent_frames, 0);
    /* The isotropic shortcut gives the frame path's value: a barely anisotropic lobe (with a
     * frame) against the isotropic lobe (without). */
    snprintf(text, sizeof text, ANISO, "disney_specular_aniso", "r=0.4 anisotropic=1e-9");
    result eps = render_text(text, 1, 1);
    snprintf(text, sizeof text, ANISO, "disney_specular", "r=0.4");
    result iso = render_text(text, 1, 1);
    ck_assert(eps.st.tangent_frames > 0);
    ck_assert_uint_eq(iso.st.tangent_frames, 0);
    double worst = 0;
    for (int k = 0; k < 24 * 24 * 3; ++k) {
        worst = fmax(worst, fabs(eps.rgb[k] - iso.rgb[k]) / fmax(1e-3, fabs(iso.rgb[k])));
        ck_assert(a0.rgb[k] == a0.rgb[k]);
    }
    ck_assert_msg(worst < 1e-5, "frame path vs isotropic path: rel diff %g", worst);
    free(an.rgb);
    free(a0.rgb);
    free(eps.rgb);
    free(iso.rgb);
}
END_TEST

START_TEST(fresnel_counted_only_where_a_lobe_has_it)
{
    char text[512];
    snprintf(text, sizeof text, ANISO, "lambert", "kd=0.5");
    result l = render_text(text, 1, 1);
    ck_assert(l.st.brdf_evals > 0);
    ck_assert_uint_eq(l.st.fresnel_evals, 0);
    snprintf(text, sizeof text, ANISO, "disney_specular", "r=0.4");
    result g = render_text(text, 1, 1);
    ck_assert_uint_eq(g.st.fresnel_evals, g.st.brdf_evals);
    free(l.rgb);
    free(g.rgb);
}
END_TEST

START_TEST(unresolvable_materials_are_refused)
{
    const char *text = "camera position=0,0,4 look_at=0,0,0\n"
                       "material m adaptive goal=photoreal\n"
                       "sphere material=m radius=1\n";
    scene s;
    char err[512];
    ck_assert(scene_parse_text("t", text, strlen(text), &s, err, sizeof err) == 0);
    render_options opt = {8, 8, 1, 0, 1, 0, RENDER_FLOAT, 0, 0, 0, 0, NULL};
    render_scene rs;
    ck_assert_int_eq(render_prepare(&s, &opt, &rs, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "adaptive"));
    /* spp must be a square: 3 samples cannot form a k x k grid of strata. */
    s.materials[0].kind = SCENE_MAT_MODELS;
    s.materials[0].lobe_count = 1;
    s.materials[0].lobes[0] = ABRDF_LAMBERT;
    abrdf_params_init(ABRDF_LAMBERT, &s.materials[0].params);
    ck_assert_int_eq(render_prepare(&s, &opt, &rs, err, sizeof err), 0);
    float rgb[8 * 8 * 3];
    opt.spp = 3;
    ck_assert_int_eq(render_image(&rs, &opt, rgb, NULL), -1);
    opt.spp = 4;
    ck_assert_int_eq(render_image(&rs, &opt, rgb, NULL), 0);
    render_release(&rs);
    scene_free(&s);
}
END_TEST

/* A scene's shading points (scene_points.h) are the render's: the prediction on them of a
 * candidate against a reference is the NMSE of their two renders over the material's
 * pixels (those whose centre sees it, as budget_points measures), shadows and tangents
 * included (a single material, no ambient term: nothing the
 * terms leave out). The occluder above the sphere, outside the camera's view, shadows part
 * of it from the point light. */
static const char *points_scene(const char *material)
{
    static char text[1024];
    snprintf(text, sizeof text,
             "camera position=0,0,6 look_at=0,0,0 fov=25 resolution=24,24\n"
             "ambient 0\n"
             "light directional direction=-1,0.5,1 intensity=2\n"
             "light point position=0.3,6,0.5 intensity=40\n"
             "material m %s\n"
             "material o model=lambert kd=0.5\n"
             "sphere material=m radius=1\n"
             "box material=o size=1,0.1,1 translate=0,3,0\n",
             material);
    return text;
}

START_TEST(scene_points_predict_the_render)
{
    precision = RENDER_DOUBLE;
    const char *ref = "diffuse=disney_diffuse specular=disney_specular_aniso kd=0.4,0.3,0.2 "
                      "ks=1 f0=0.04 r=0.35 anisotropic=0.7";
    const char *cand = "diffuse=lambert specular=blinn_phong kd=0.45,0.3,0.2 ks=0.05 n=40";
    result a = render_text(points_scene(ref), 4, 1), b = render_text(points_scene(cand), 4, 1);
    scene s;
    char err[512];
    const char *text = points_scene(ref);
    ck_assert_msg(scene_parse_text("t", text, strlen(text), &s, err, sizeof err) == 0, "%s", err);
    scene_points p;
    ck_assert_msg(scene_points_trace(&s, 4, &p, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(p.width, 24);
    ck_assert_int_eq(p.spp, 4);
    ck_assert_int_eq(p.stride[0], 1);
    ck_assert_int_eq(p.pixels[1], 0); /* the occluder is out of view */
    double num = 0, den = 0;
    int covered = 0;
    for (int q = 0; q < 24 * 24; ++q) {
        if (p.pixel_material[q] != 0) continue; /* the material's pixels: their centre sees it */
        ++covered;
        for (int c = 0; c < 3; ++c) {
            double d = (double)b.rgb[3 * q + c] - a.rgb[3 * q + c];
            num += d * d, den += (double)a.rgb[3 * q + c] * a.rgb[3 * q + c];
        }
    }
    ck_assert_int_eq(covered, p.pixels[0]);
    int shadowed = 0;
    for (int k = 0; k < p.term_count[0]; ++k) {
        const abrdf_view_term *t = &p.terms[0][k];
        ck_assert(fabs(geom_dot(t->n, t->t)) < 1e-12);
        ck_assert(t->sample >= 0 && t->sample < p.samples[0]);
        shadowed += t->wi[1] > 0.9; /* the point light, above */
    }
    ck_assert_int_lt(shadowed, p.term_count[0] / 2);
    abrdf_view v;
    ck_assert(scene_points_view(&p, 0, &v));
    abrdf_params pr, pc;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR_ANISO, &pr);
    pr.kd[0] = 0.4, pr.kd[1] = 0.3, pr.kd[2] = 0.2, pr.r = 0.35, pr.anisotropic = 0.7;
    for (int c = 0; c < 3; ++c) pr.ks[c] = 1, pr.f0[c] = 0.04;
    abrdf_params_init(ABRDF_BLINN_PHONG, &pc);
    pc.kd[0] = 0.45, pc.kd[1] = 0.3, pc.kd[2] = 0.2, pc.n = 40;
    for (int c = 0; c < 3; ++c) pc.ks[c] = 0.05;
    size_t size = abrdf_fit_workspace_size(NULL, &v);
    void *work = malloc(size);
    double nmse = -1;
    ck_assert_int_eq(abrdf_predict_nmse(ABRDF_DISNEY_DIFFUSE, ABRDF_DISNEY_SPECULAR_ANISO, &pr,
                                        ABRDF_LAMBERT, ABRDF_BLINN_PHONG, &pc, &v, &nmse, work,
                                        size),
                     ABRDF_OK);
    ck_assert_msg(nmse > 1e-3, "the candidate must differ: %g", nmse);
    /* the images are stored in float: 1e-5 of relative rounding */
    ck_assert_msg(fabs(nmse - num / den) < 1e-5 * (num / den), "points %.9g, image %.9g", nmse,
                  num / den);
    free(work);
    scene_points_free(&p);
    scene_free(&s);
    free(a.rgb);
    free(b.rgb);
}
END_TEST

/* A material covering more pixels than SCENE_POINTS_MAX_TERMS allows is sampled on every
 * k^2-th of its pixels; each term carries the light's irradiance over the samples per pixel. */
START_TEST(scene_points_keep_a_bounded_sample)
{
    const char *text = "camera position=0,0,3 look_at=0,0,0 fov=50 resolution=200,200\n"
                       "light directional direction=0,0,1 intensity=2\n"
                       "material m diffuse=lambert specular=disney_specular r=0.4\n"
                       "sphere material=m radius=1\n";
    scene s;
    char err[512];
    ck_assert_msg(scene_parse_text("t", text, strlen(text), &s, err, sizeof err) == 0, "%s", err);
    scene_points p;
    ck_assert_msg(scene_points_trace(&s, 4, &p, err, sizeof err) == 0, "%s", err);
    ck_assert_int_gt(p.stride[0], 1);
    double per = (double)p.pixels[0] / ((double)p.stride[0] * p.stride[0]);
    ck_assert_msg(p.samples[0] > 0.9 * per && p.samples[0] < 1.1 * per + 8, "%d of %g",
                  p.samples[0], per);
    ck_assert_int_le(p.term_count[0], SCENE_POINTS_MAX_TERMS * 11 / 10);
    for (int k = 0; k < p.term_count[0]; ++k) {
        const abrdf_view_term *t = &p.terms[0][k];
        for (int c = 0; c < 3; ++c) ck_assert(fabs(t->e[c] - 0.5) < 1e-12);
        ck_assert(fabs(t->wi[2] - 1.0) < 1e-12);
    }
    scene_points_free(&p);
    scene_free(&s);
}
END_TEST

/* A material thinner than its stride keeps pixels: a bar one pixel row tall on an odd row,
 * sampled every stride^2-th pixel of its own, not on a grid of even rows and columns. */
START_TEST(scene_points_keep_a_thin_material)
{
    char text[2048];
    int n = snprintf(text, sizeof text,
                     "camera position=0,0,10 look_at=0,0,0 fov=40 resolution=200,120\n"
                     "material bar diffuse=lambert\n"
                     "box material=bar size=10.3,0.05,0.05 translate=0,-0.091,0\n");
    for (int l = 0; l < 16; ++l) /* 16 lights x 4 samples: 64 terms a pixel */
        n += snprintf(text + n, sizeof text - (size_t)n,
                      "light directional direction=%g,%g,1 intensity=0.1\n", -0.3 + 0.2 * (l % 4),
                      -0.3 + 0.2 * (l / 4));
    scene s;
    char err[512];
    ck_assert_msg(scene_parse_text("t", text, strlen(text), &s, err, sizeof err) == 0, "%s", err);
    scene_points p;
    ck_assert_msg(scene_points_trace(&s, 4, &p, err, sizeof err) == 0, "%s", err);
    for (int j = 0; j < p.height; ++j) /* the bar's pixels: all on row 61, off the even grid */
        for (int i = 0; i < p.width; ++i)
            ck_assert(p.pixel_material[(size_t)j * p.width + i] < 0 || j == 61);
    ck_assert_int_gt(p.pixels[0], 100);
    ck_assert_int_eq(p.stride[0], 2);
    ck_assert_int_eq(p.kept[0], (p.pixels[0] + 3) / 4);
    ck_assert_int_eq(p.hits[0], p.kept[0]);
    ck_assert_int_eq(p.samples[0], p.kept[0]);
    ck_assert_int_eq(p.term_count[0], p.kept[0] * 4 * 16);
    ck_assert_int_le(p.term_count[0], SCENE_POINTS_MAX_TERMS);
    scene_points_free(&p);
    /* a non-square spp is refused, as render_image refuses it */
    ck_assert_int_eq(scene_points_trace(&s, 2, &p, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "not a square") != NULL, "%s", err);
    scene_free(&s);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("render");
    TCase *tv = tcase_create("values");
    tcase_add_loop_test(tv, lambert_centre_pixel_directional, RENDER_FLOAT, RENDER_DOUBLE + 1);
    tcase_add_loop_test(tv, pair_matches_abrdf_shade, RENDER_FLOAT, RENDER_DOUBLE + 1);
    tcase_add_loop_test(tv, point_light_falls_off_with_distance_squared, RENDER_FLOAT,
                        RENDER_DOUBLE + 1);
    tcase_add_loop_test(tv, box_filter_matches_camera_model, RENDER_FLOAT, RENDER_DOUBLE + 1);
    tcase_add_loop_test(tv, bit_identical_for_any_thread_count, RENDER_FLOAT, RENDER_DOUBLE + 1);
    tcase_add_loop_test(tv, strata_centres_equal_block_average_of_larger_image, RENDER_FLOAT,
                        RENDER_DOUBLE + 1);
    tcase_add_test(tv, fast_path_within_nmse_1e8_of_double);
    tcase_add_test(tv, scene_points_predict_the_render);
    tcase_add_test(tv, scene_points_keep_a_bounded_sample);
    tcase_add_test(tv, scene_points_keep_a_thin_material);
    tcase_set_timeout(tv, 300);
    suite_add_tcase(s, tv);
    TCase *tp = tcase_create("plan");
    tcase_add_test(tp, single_sphere_casts_no_shadow_rays);
    tcase_add_test(tp, robot_casts_shadow_rays_and_shadows_darken);
    tcase_add_test(tp, separated_objects_need_no_shadow_rays);
    tcase_add_test(tp, plan_changes_no_pixel);
    tcase_add_test(tp, tangent_frames_only_for_anisotropic_materials);
    tcase_add_test(tp, fresnel_counted_only_where_a_lobe_has_it);
    tcase_add_test(tp, unresolvable_materials_are_refused);
    tcase_set_timeout(tp, 120);
    suite_add_tcase(s, tp);
    return s;
}

int main(void) { return tu_run(suite()); }
