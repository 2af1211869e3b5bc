/* test_light.c - the sampled lights (tools/render/light.c, envmap.c) and their estimators:
 *   - a Lambert point under a sphere light: kd L_e r^2 / d^2 (closed form) by every estimator;
 *   - the rectangle's sampler: 1 / pdf is the solid angle (Van Oosterom and Strackee's
 *     triangle formula), each sample lies on the rectangle where light_hit finds it with the
 *     same density, and the samples are uniform in solid angle (the share falling on each
 *     quarter of the rectangle is the quarter's solid angle, within 5 standard errors); the
 *     sphere's sampler the same against its cone;
 *   - the environment map: the sampled density is envmap_pdf's, integrates to 1, and the
 *     estimate of integral L dw matches the exact sum over the pixels;
 *   - MIS, light-only and BRDF-only estimates of one scene converge to one image: NMSE
 *     against a 1024-spp reference falls as 1/spp (slope of log NMSE in [-1.3, -0.7]) and
 *     the image means agree within 5 standard errors;
 *   - scenes with only point and directional lights: the estimator options change no bit and
 *     draw no sample. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_io.h"
#include "light.h"
#include "test_util.h"

static const double PI = 3.14159265358979323846;

#ifdef LIGHT_QUICK
#define QUICK 1
#else
#define QUICK 0
#endif

/* A scene and its prepared renderer state. */
typedef struct setup {
    scene s;
    render_scene rs;
} setup;

static void setup_text(setup *u, const char *name, const char *text, const render_options *opt)
{
    char err[512];
    ck_assert_msg(scene_parse_text(name, text, strlen(text), &u->s, err, sizeof err) == 0, "%s",
                  err);
    ck_assert_msg(render_prepare(&u->s, opt, &u->rs, err, sizeof err) == 0, "%s", err);
}

static void setup_free(setup *u)
{
    render_release(&u->rs);
    scene_free(&u->s);
}

static float *render(setup *u, const render_options *opt, render_stats *st)
{
    float *rgb = malloc((size_t)u->rs.width * u->rs.height * 3 * sizeof *rgb);
    ck_assert_ptr_nonnull(rgb);
    ck_assert_int_eq(render_image(&u->rs, opt, rgb, st), 0);
    return rgb;
}

static double rnd(unsigned long long *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

/* ---- a closed form --------------------------------------------------------------------- */

/* Unit sphere, camera on +z, one pixel: the hit (0, 0, 1), N = wo = +z. A sphere light of
 * radius r at distance d on the normal: E = pi L r^2 / d^2, so L_pixel = kd L r^2 / d^2. */
START_TEST(sphere_light_closed_form)
{
    const char *text = "camera position=0,0,4 look_at=0,0,0 fov=30 resolution=1,1\n"
                       "light sphere center=0.6,0.3,4.9 radius=0.8 color=1,0.5,0.25 intensity=2\n"
                       "material m model=lambert kd=0.5\n"
                       "sphere material=m radius=1\n";
    double c[3] = {0.6, 0.3, 4.9}, p[3] = {0, 0, 1}, d2 = 0, r = 0.8;
    for (int k = 0; k < 3; ++k) d2 += (c[k] - p[k]) * (c[k] - p[k]);
    double want = 0.5 * 2.0 * r * r / d2 * (4.9 - 1.0) / sqrt(d2); /* E = pi L r^2 cos / d^2 */
    for (int e = RENDER_EST_MIS; e <= RENDER_EST_BRDF; ++e) {
        render_options opt = {0, 0,   1, 0, 1, 0, RENDER_DOUBLE, 0, e, QUICK ? 16384 : 65536,
                              0, NULL};
        setup u;
        setup_text(&u, "t", text, &opt);
        render_stats st;
        float *rgb = render(&u, &opt, &st);
        /* BRDF-only is a Bernoulli trial of probability ~ sin^2: relative error
         * sqrt((1 - p) / (p N)) ~ 2.6e-2 at N = 16384; 5 such errors */
        double tol = e == RENDER_EST_BRDF ? (QUICK ? 0.13 : 0.07) : 2e-3;
        for (int ch = 0; ch < 3; ++ch) {
            double w = want * (ch == 0 ? 1.0 : ch == 1 ? 0.5 : 0.25);
            ck_assert_msg(fabs(rgb[ch] - w) <= tol * w, "estimator %d channel %d: %.6g, want %.6g",
                          e, ch, rgb[ch], w);
        }
        printf("sphere light, estimator %d: %.6f (closed form %.6f), %llu light + %llu brdf "
               "samples\n",
               e, rgb[0], want, st.light_samples, st.brdf_samples);
        free(rgb);
        setup_free(&u);
    }
}
END_TEST

/* Light sizes and intensities across the ranges the scene format accepts: every pixel is
 * finite and within what the light can give. Under a sphere light on the normal the one pixel
 * is kd L r^2 / d^2 (as above): a vanishing light gives a vanishing pixel, with every
 * estimator (a light whose density overflows the MIS weight once made every lit pixel
 * 3.4e38). Under any rect light the irradiance is at most pi L, so the pixel is at most kd L
 * (twice that allows for the noise of 64 samples). */
START_TEST(light_sizes_and_intensities_sweep)
{
    const double radii[] = {4.9e-324, 1e-300, 1e-160, 1e-78, 1e-20, 1e-3, 0.8, 9.9e5};
    const double edges[] = {1.1e-9, 1e-6, 1e-2, 1.0, 1e3, 1e6};
    const double intensities[] = {0.0, 1e-300, 1.0, 1e6};
    int renders = 0;
    for (size_t k = 0; k < sizeof radii / sizeof *radii + sizeof edges / sizeof *edges; ++k)
        for (size_t j = 0; j < sizeof intensities / sizeof *intensities; ++j) {
            int sphere = k < sizeof radii / sizeof *radii;
            double L = intensities[j],
                   size = sphere ? radii[k] : edges[k - sizeof radii / sizeof *radii];
            double z = sphere ? (size > 1.0 ? 1e6 : 4.9) : 4.9, d = z - 1.0;
            char text[512], light[160];
            if (sphere)
                snprintf(light, sizeof light,
                         "light sphere center=0,0,%.17g radius=%.17g "
                         "intensity=%.17g\n",
                         z, size, L);
            else
                snprintf(light, sizeof light,
                         "light rect center=0,0,%.17g u=%.17g,0,0 "
                         "v=0,-%.17g,0 intensity=%.17g\n",
                         z, size, size, L);
            snprintf(text, sizeof text,
                     "camera position=0,0,4 look_at=0,0,0 fov=30 resolution=1,1\n%s"
                     "material m model=lambert kd=0.5\nsphere material=m radius=1\n",
                     light);
            double want = sphere ? 0.5 * L * (size / d) * (size / d) : 0.0, bound = 0.5 * L;
            for (int e = RENDER_EST_MIS; e <= RENDER_EST_BRDF; ++e) {
                render_options opt = {0, 0, 1, 0, 1, 0, RENDER_DOUBLE, 0, e, 64, 0, NULL};
                setup u;
                setup_text(&u, "t", text, &opt);
                render_stats st;
                float *rgb = render(&u, &opt, &st);
                for (int ch = 0; ch < 3; ++ch) {
                    double v = rgb[ch];
                    ck_assert_msg(isfinite(v) && v >= 0.0 && v <= bound * 2.0 + 1e-30,
                                  "%sestimator %d: pixel %g (bound %g)", light, e, v, bound);
                    /* light sampling of a narrow cone on a Lambert point is exact (cos is 1
                     * across it); a wide cone and MIS's BRDF samples add noise */
                    double tol = e == RENDER_EST_LIGHT && size < 0.01 * d ? 1e-3 : 0.1;
                    if (sphere && e != RENDER_EST_BRDF)
                        ck_assert_msg(fabs(v - want) <= tol * want + 1e-37,
                                      "%sestimator %d: pixel %g, closed form %g", light, e, v,
                                      want);
                }
                free(rgb);
                setup_free(&u);
                ++renders;
            }
        }
    printf("light sweep: %d renders, every pixel finite and bounded\n", renders);
}
END_TEST

/* ---- the samplers ---------------------------------------------------------------------- */

/* Solid angle of triangle (a, b, c) seen from the origin (Van Oosterom and Strackee 1983). */
static double tri_solid_angle(const double a[3], const double b[3], const double c[3])
{
    double la = sqrt(geom_dot(a, a)), lb = sqrt(geom_dot(b, b)), lc = sqrt(geom_dot(c, c));
    double bc[3] = {b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2],
                    b[0] * c[1] - b[1] * c[0]};
    double num = fabs(geom_dot(a, bc));
    double den = la * lb * lc + geom_dot(a, b) * lc + geom_dot(a, c) * lb + geom_dot(b, c) * la;
    return 2.0 * atan2(num, den);
}

/* Solid angle from o of the part [s0, s1] x [t0, t1] (fractions of the edges) of a rect. */
static double rect_solid_angle(const render_light *lt, const double o[3], double s0, double s1,
                               double t0, double t1)
{
    double q[4][3];
    const double st[4][2] = {{s0, t0}, {s1, t0}, {s1, t1}, {s0, t1}};
    for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c)
            q[k][c] = lt->position[c] + (st[k][0] - 0.5) * lt->edge_u[c] +
                      (st[k][1] - 0.5) * lt->edge_v[c] - o[c];
    return tri_solid_angle(q[0], q[1], q[2]) + tri_solid_angle(q[0], q[2], q[3]);
}

START_TEST(rect_sampler_is_uniform_in_solid_angle)
{
    const char *text = "camera position=0,0,4 look_at=0,0,0 resolution=1,1\n"
                       "light rect center=0.4,2,0.3 u=1.5,0,0.2 v=-0.1,0,0.75 intensity=1\n"
                       "material m model=lambert\nsphere material=m radius=1\n";
    render_options opt = {0, 0, 1, 0, 1, 0, RENDER_DOUBLE, 0, 0, 0, 0, NULL};
    setup u;
    setup_text(&u, "t", text, &opt);
    const render_light *lt = &u.rs.lights[0];
    /* near (large solid angle), far, grazing, and one far enough for area sampling */
    const double pts[4][3] = {{0.1, 1.3, 0.2}, {-3, -6, 2}, {5, 1.95, 0.2}, {300, -4000, 100}};
    unsigned long long seed = 7;
    int n = QUICK ? 20000 : 100000;
    for (int i = 0; i < 4; ++i) {
        double S = rect_solid_angle(lt, pts[i], 0, 1, 0, 1), quarter[4] = {0, 0, 0, 0};
        for (int k = 0; k < n; ++k) {
            light_sample ls, lh;
            ck_assert(light_sample_dir(lt, pts[i], rnd(&seed), rnd(&seed), &ls));
            ck_assert(light_hit(lt, pts[i], ls.wi, &lh));
            ck_assert_msg(tu_close(lh.dist, ls.dist, 1e-7, 0) && tu_close(lh.pdf, ls.pdf, 1e-7, 0),
                          "point %d: hit at %.17g (pdf %.17g), sampled %.17g (pdf %.17g)", i,
                          lh.dist, lh.pdf, ls.dist, ls.pdf);
            if (S >= LIGHT_RECT_MIN_SOLID_ANGLE)
                ck_assert_msg(tu_close(1.0 / ls.pdf, S, 1e-6, 0), "point %d: 1/pdf %.17g, S %.17g",
                              i, 1.0 / ls.pdf, S);
            double h[3];
            for (int c = 0; c < 3; ++c) h[c] = pts[i][c] + ls.dist * ls.wi[c] - lt->position[c];
            int a = geom_dot(h, lt->edge_u) > 0, b = geom_dot(h, lt->edge_v) > 0;
            quarter[2 * a + b] += 1.0 / n;
        }
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b) {
                double want = S >= LIGHT_RECT_MIN_SOLID_ANGLE
                                  ? rect_solid_angle(lt, pts[i], 0.5 * a, 0.5 * a + 0.5, 0.5 * b,
                                                     0.5 * b + 0.5) /
                                        S
                                  : 0.25; /* area sampling: uniform by area */
                double se = sqrt(want * (1 - want) / n);
                ck_assert_msg(fabs(quarter[2 * a + b] - want) < 5 * se + 1e-12,
                              "point %d quarter %d%d: share %.5f, want %.5f", i, a, b,
                              quarter[2 * a + b], want);
            }
    }
    /* behind the rectangle: no sample, no hit */
    const double back[3] = {0.4, 3, 0.3}, down[3] = {0, -1, 0};
    light_sample ls;
    ck_assert(!light_sample_dir(lt, back, 0.5, 0.5, &ls));
    ck_assert(!light_hit(lt, back, down, &ls));
    setup_free(&u);
}
END_TEST

START_TEST(sphere_sampler_is_uniform_in_the_cone)
{
    const char *text = "camera position=0,0,4 look_at=0,0,0 resolution=1,1\n"
                       "light sphere center=1,2,-0.5 radius=0.7 intensity=1\n"
                       "material m model=lambert\nsphere material=m radius=1\n";
    render_options opt = {0, 0, 1, 0, 1, 0, RENDER_DOUBLE, 0, 0, 0, 0, NULL};
    setup u;
    setup_text(&u, "t", text, &opt);
    const render_light *lt = &u.rs.lights[0];
    const double o[3] = {0.2, 0.1, 0.3};
    double dc[3], d = 0;
    for (int c = 0; c < 3; ++c) dc[c] = lt->position[c] - o[c], d += dc[c] * dc[c];
    d = sqrt(d);
    double cmax = sqrt(1 - 0.49 / (d * d)), S = 2 * PI * (1 - cmax);
    double chalf = 0.5 * (1 + cmax); /* the inner cone of half the solid angle */
    unsigned long long seed = 11;
    int n = QUICK ? 20000 : 100000;
    double inner = 0;
    for (int k = 0; k < n; ++k) {
        light_sample ls, lh;
        ck_assert(light_sample_dir(lt, o, rnd(&seed), rnd(&seed), &ls));
        ck_assert(tu_close(1.0 / ls.pdf, S, 1e-9, 0));
        ck_assert(light_hit(lt, o, ls.wi, &lh) || 1 - geom_dot(ls.wi, dc) / d < 1e-9);
        double h[3], r2 = 0;
        for (int c = 0; c < 3; ++c) h[c] = o[c] + ls.dist * ls.wi[c] - lt->position[c];
        r2 = geom_dot(h, h);
        ck_assert_msg(fabs(sqrt(r2) - 0.7) < 1e-9, "sample %d off the sphere by %g", k,
                      sqrt(r2) - 0.7);
        inner += geom_dot(ls.wi, dc) / d > chalf ? 1.0 / n : 0;
    }
    ck_assert_msg(fabs(inner - 0.5) < 5 * sqrt(0.25 / n), "inner half-cone share %.5f", inner);
    light_sample ls; /* inside the sphere: nothing */
    ck_assert(!light_sample_dir(lt, lt->position, 0.5, 0.5, &ls));
    setup_free(&u);
}
END_TEST

/* An environment map with a bright patch and a gradient, written as EXR. */
static void write_env(const char *path, int W, int H)
{
    float *px = malloc((size_t)W * H * 3 * sizeof *px);
    ck_assert_ptr_nonnull(px);
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            float *p = px + 3 * ((size_t)j * W + i);
            double t = (j + 0.5) / H;
            p[0] = (float)(0.2 + 0.3 * t), p[1] = (float)(0.3 * (1 - t)),
            p[2] = (float)(0.6 - 0.5 * t);
            if (j >= H / 8 && j < H / 8 + 3 && i >= W / 3 && i < W / 3 + 4)
                p[0] = 40.0f, p[1] = 38.0f, p[2] = 30.0f;
            if (j == H - 1 && i == 0) p[0] = p[1] = p[2] = 0.0f; /* a black texel */
        }
    char err[512];
    abrdf_bytes bytes = {NULL, 0};
    ck_assert_msg(abrdf_image_encode_linear(path, W, H, px, &bytes, err, (int)sizeof err) == 0,
                  "%s", err);
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite(bytes.data, 1, bytes.size, f), bytes.size);
    ck_assert_int_eq(fclose(f), 0);
    abrdf_bytes_free(&bytes);
    free(px);
}

START_TEST(environment_density_and_integral)
{
    const char *path = "test_light_env.exr";
    int W = 48, H = 24;
    write_env(path, W, H);
    envmap env;
    char err[512];
    ck_assert_msg(envmap_load(path, &env, err, (int)sizeof err) == 0, "%s", err);
    /* exact integral of the piecewise-constant map's luminance, and the pdf's */
    double exact = 0;
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            const float *p = env.rgb + 3 * ((size_t)j * W + i);
            double dw = 2 * PI / W * (cos(PI * j / H) - cos(PI * (j + 1) / H));
            exact += (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) * dw;
        }
    double pint = 0; /* integral of envmap_pdf over the sphere, midpoint rule per texel */
    int sub = 8;
    for (int j = 0; j < H * sub; ++j)
        for (int i = 0; i < W * sub; ++i) {
            double th = PI * (j + 0.5) / (H * sub), ph = 2 * PI * ((i + 0.5) / (W * sub) - 0.5);
            double d[3] = {sin(th) * sin(ph), cos(th), -sin(th) * cos(ph)};
            pint += envmap_pdf(&env, d) * sin(th) * (PI / (H * sub)) * (2 * PI / (W * sub));
        }
    ck_assert_msg(fabs(pint - 1) < 2e-3, "pdf integrates to %.6f", pint);
    unsigned long long seed = 3;
    int n = QUICK ? 20000 : 200000;
    double sum = 0, sum2 = 0;
    for (int k = 0; k < n; ++k) {
        double d[3], rgb[3];
        double pdf = envmap_sample(&env, rnd(&seed), rnd(&seed), d);
        ck_assert(pdf > 0);
        ck_assert_msg(tu_close(envmap_pdf(&env, d), pdf, 1e-9, 0), "pdf %.17g, envmap_pdf %.17g",
                      pdf, envmap_pdf(&env, d));
        envmap_lookup(&env, d, rgb);
        double v = (0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]) / pdf;
        sum += v, sum2 += v * v;
    }
    double mean = sum / n, se = sqrt(fmax(0, sum2 / n - mean * mean) / n);
    printf("environment: integral of luminance %.6f by sampling (se %.2g), exact %.6f\n", mean, se,
           exact);
    ck_assert_msg(fabs(mean - exact) < 5 * se + 1e-9 * exact, "estimate %.6f, exact %.6f", mean,
                  exact);
    /* luminance sampling: luminance / pdf is nearly constant, so the error is small */
    ck_assert(se < 0.05 * exact);
    envmap_free(&env);
    remove(path);
}
END_TEST

/* ---- the estimators -------------------------------------------------------------------- */

static const char *AREA_SCENE =
    "camera position=0,0.6,5 look_at=0,-0.2,0 fov=40 resolution=16,12\n"
    "light sphere center=2,2.5,2 radius=0.5 color=1,0.95,0.9 intensity=6\n"
    "light rect center=-2,2,0.5 u=1,0,0 v=0,0,1.2 color=0.9,0.95,1 intensity=3\n"
    "light environment file=test_light_conv.exr intensity=0.5\n"
    "material plastic diffuse=lambert specular=disney_specular kd=0.18,0.30,0.60 ks=1 "
    "f0=0.04 r=0.35\n"
    "material floor model=oren_nayar kd=0.5 sigma=0.3\n"
    "sphere material=plastic radius=1\n"
    "box material=floor size=8,0.2,8 translate=0,-1.1,0\n";

static double nmse(const float *a, const float *ref, size_t n)
{
    double num = 0, den = 0;
    for (size_t k = 0; k < n; ++k)
        num += (a[k] - ref[k]) * (double)(a[k] - ref[k]), den += ref[k] * (double)ref[k];
    return num / den;
}

static double nmse_den(const float *ref, size_t n)
{
    double den = 0;
    for (size_t k = 0; k < n; ++k) den += ref[k] * (double)ref[k];
    return den;
}

static double mean(const float *a, size_t n)
{
    double s = 0;
    for (size_t k = 0; k < n; ++k) s += a[k];
    return s / n;
}

START_TEST(estimators_converge_to_one_image)
{
    write_env("test_light_conv.exr", 32, 16);
    render_options opt = {0, 0,   QUICK ? 256 : 1024, 1, 2, 0, RENDER_FLOAT, 0, RENDER_EST_MIS, 1,
                          0, NULL};
    setup u;
    setup_text(&u, "t", AREA_SCENE, &opt);
    size_t n = (size_t)u.rs.width * u.rs.height * 3;
    float *ref = render(&u, &opt, NULL);
    static const char *const names[] = {"mis", "light", "brdf"};
    for (int e = RENDER_EST_MIS; e <= RENDER_EST_BRDF; ++e) {
        static const int spps[3] = {4, 16, 64};
        double lx[3], ly[3];
        for (int k = 0; k < 3; ++k) {
            render_options o = opt;
            o.estimator = e, o.spp = spps[k];
            float *img = render(&u, &o, NULL);
            double q = nmse(img, ref, n);
            lx[k] = log((double)spps[k]), ly[k] = log(q);
            printf("estimator %-5s spp %3d: NMSE %.3e, mean %.5f (reference %.5f)\n", names[e],
                   spps[k], q, mean(img, n), mean(ref, n));
            /* the image means agree within 5 standard errors of the mean of the pixel errors */
            double se = sqrt(q * nmse_den(ref, n)) / (double)n;
            ck_assert_msg(fabs(mean(img, n) - mean(ref, n)) < 5 * se,
                          "%s spp %d: mean %.5f, reference %.5f (standard error %.2g)", names[e],
                          spps[k], mean(img, n), mean(ref, n), se);
            free(img);
        }
        double mx = (lx[0] + lx[1] + lx[2]) / 3, my = (ly[0] + ly[1] + ly[2]) / 3, sxy = 0, sxx = 0;
        for (int k = 0; k < 3; ++k)
            sxy += (lx[k] - mx) * (ly[k] - my), sxx += (lx[k] - mx) * (lx[k] - mx);
        double slope = sxy / sxx;
        printf("estimator %-5s: NMSE ~ spp^%.3f\n", names[e], slope);
        ck_assert_msg(slope > -1.3 && slope < -0.7, "%s: NMSE falls as spp^%.3f, not 1/spp",
                      names[e], slope);
    }
    free(ref);
    setup_free(&u);
    remove("test_light_conv.exr");
}
END_TEST

START_TEST(exact_lights_ignore_the_estimator)
{
    const char *text =
        "camera position=0,1,5 look_at=0,0,0 fov=40 resolution=24,18\n"
        "light point position=2,3,2 intensity=12\n"
        "light directional direction=-1,1,0.5 intensity=0.7\n"
        "material m diffuse=lambert specular=cook_torrance kd=0.3 ks=1 r=0.4\n"
        "sphere material=m radius=1\nbox material=m size=6,0.2,6 translate=0,-1.1,0\n";
    for (int prec = RENDER_FLOAT; prec <= RENDER_DOUBLE; ++prec) {
        render_options base = {0, 0, 4, 1, 2, 0, prec, 0, RENDER_EST_MIS, 1, 0, NULL};
        setup u;
        setup_text(&u, "t", text, &base);
        ck_assert_int_eq(u.rs.sampled_lights, 0);
        render_stats st0;
        float *a = render(&u, &base, &st0);
        size_t n = (size_t)u.rs.width * u.rs.height * 3;
        for (int e = RENDER_EST_MIS; e <= RENDER_EST_BRDF; ++e) {
            render_options o = base;
            o.estimator = e, o.light_samples = 7;
            render_stats st;
            float *b = render(&u, &o, &st);
            ck_assert_msg(!memcmp(a, b, n * sizeof *a), "estimator %d changed the image", e);
            ck_assert(st.light_samples == 0 && st.brdf_samples == 0);
            ck_assert(st.brdf_evals == st0.brdf_evals && st.shadow_rays == st0.shadow_rays);
            free(b);
        }
        free(a);
        setup_free(&u);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("light");
    TCase *tc = tcase_create("light");
    tcase_set_timeout(tc, 0);
    tcase_add_test(tc, exact_lights_ignore_the_estimator);
    tcase_add_test(tc, rect_sampler_is_uniform_in_solid_angle);
    tcase_add_test(tc, sphere_sampler_is_uniform_in_the_cone);
    tcase_add_test(tc, environment_density_and_integral);
    tcase_add_test(tc, sphere_light_closed_form);
    tcase_add_test(tc, light_sizes_and_intensities_sweep);
    tcase_add_test(tc, estimators_converge_to_one_image);
    suite_add_tcase(s, tc);
    return tu_run(s);
}
