/* bench_lights.c - what light sampling costs and buys (`abrdf bench --render`, last part;
 * bench.h): the noise of MIS, light-only and BRDF-only estimates of the sampled lights, at
 * equal samples and at equal time, per model.
 *
 * Scenes: scenes/area.scene (spheres on a floor under a small sphere light and a rectangle
 * light) and the same objects under an environment light, a synthetic sky map made here (a
 * blue gradient over a grey ground, and a sun of 3 x 3 pixels, about 4 degrees wide, 40
 * degrees up). The two spheres get the model under test (with the scene's kd, ks = 1, f0 = 0.04),
 * the floor stays Lambertian.
 *
 * Every render casts one camera ray through each pixel centre, so that all the noise is the
 * lights' estimate: --light-samples TEST per hit, sampled light and strategy, against a
 * reference rendered with MIS at REF light samples (its own noise is TEST/REF of the MIS
 * image's, 1/64 by default). The NMSE of each estimator's image against it is the noise at
 * equal samples; NMSE x time (median render time) is the noise at equal time: its ratio to
 * MIS's is how much longer an estimator must run to be as clean as MIS.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "bench_scene.h"
#include "cli_args.h"
#include "render.h"
#include "robot_scene.h"

enum { SC_AREA, SC_ENV, SC_COUNT };
static const char *const scene_name[SC_COUNT] = {"area", "environment"};

enum { E_MIS, E_LIGHT, E_BRDF, E_COUNT };
static const char *const est_name[E_COUNT] = {"mis", "light", "brdf"};
static const int est_value[E_COUNT] = {RENDER_EST_MIS, RENDER_EST_LIGHT, RENDER_EST_BRDF};

/* The models on the spheres: Lambert alone, then Lambert + a specular lobe. Blinn-Phong's
 * n = 2 / alpha^2 - 2 with alpha = r^2 = 0.09 is the Beckmann-equivalent of r = 0.3. */
typedef struct bench_model {
    const char *label;
    abrdf_model specular; /* ABRDF_MODEL_NONE: Lambert alone */
    double r, n;
} bench_model;
static const bench_model models[] = {
    {"lambert", ABRDF_MODEL_NONE, 0, 0},
    {"lambert + disney_specular r=0.3", ABRDF_DISNEY_SPECULAR, 0.3, 0},
    {"lambert + blinn_phong n=245", ABRDF_BLINN_PHONG, 0, 245},
    {"lambert + disney_specular r=0.1", ABRDF_DISNEY_SPECULAR, 0.1, 0},
};
#define MODEL_COUNT ((int)(sizeof models / sizeof models[0]))

/* The sky: W x H lat-long radiance (envmap.h's mapping: row 0 the zenith). */
static float *sky_pixels(int W, int H)
{
    float *px = malloc((size_t)W * H * 3 * sizeof *px);
    if (!px) return NULL;
    const double pi = 3.14159265358979323846;
    const double sun_theta = 50.0 * pi / 180.0, sun_phi = -0.6; /* 40 degrees up */
    int si = (int)((0.5 + sun_phi / (2 * pi)) * W), sj = (int)(sun_theta / pi * H);
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            float *p = px + 3 * ((size_t)j * W + i);
            double t = (j + 0.5) / H; /* 0 zenith, 0.5 horizon, 1 nadir */
            if (t < 0.5) {
                double h = t / 0.5; /* deep blue up, pale at the horizon */
                p[0] = (float)(0.15 + 0.75 * h), p[1] = (float)(0.3 + 0.6 * h),
                p[2] = (float)(0.8 + 0.2 * h);
            } else {
                p[0] = p[1] = p[2] = 0.12f;
            }
            if (abs(i - si) <= 1 && abs(j - sj) <= 1)
                p[0] = 2500.0f, p[1] = 2300.0f, p[2] = 2000.0f;
        }
    return px;
}

/* scenes/area.scene, lit as variant sc, with model mi on the spheres. */
static int make_scene(int sc, int mi, scene *s, char *err, size_t err_size)
{
    if (scene_parse_text("area.scene", abrdf_area_scene_text, strlen(abrdf_area_scene_text), s, err,
                         err_size))
        return -1;
    const bench_model *bm = &models[mi];
    for (int i = 0; i < s->material_count; ++i) {
        scene_material *m = &s->materials[i];
        if (!strcmp(m->name, "floor")) continue;
        m->lobe_count = 1;
        m->lobes[0] = ABRDF_LAMBERT;
        if (bm->specular != ABRDF_MODEL_NONE) m->lobes[m->lobe_count++] = bm->specular;
        for (int c = 0; c < 3; ++c) m->params.ks[c] = 1.0, m->params.f0[c] = 0.04;
        if (bm->r > 0) m->params.r = bm->r;
        if (bm->n > 0) m->params.n = bm->n;
    }
    if (sc == SC_ENV) {
        const int W = 256, H = 128;
        float *px = sky_pixels(W, H);
        envmap *env = calloc(1, sizeof *env);
        if (!px || !env) {
            free(px), free(env), scene_free(s);
            snprintf(err, err_size, "out of memory");
            return -1;
        }
        char msg[256];
        if (envmap_from_pixels("sky", W, H, px, env, msg, (int)sizeof msg)) {
            free(env), scene_free(s);
            snprintf(err, err_size, "%s", msg);
            return -1;
        }
        scene_light *l = &s->lights[0];
        memset(l, 0, sizeof *l);
        l->kind = SCENE_LIGHT_ENVIRONMENT;
        l->color[0] = l->color[1] = l->color[2] = 1.0;
        l->intensity = 1.0;
        l->env = env;
        l->line = 0;
        s->light_count = 1; /* the rest of the array is dropped: it owns nothing */
    }
    return 0;
}

static int render_one(const scene *s, int w, int h, int threads, int est, int ns, float *rgb,
                      double *seconds, char *err, size_t err_size)
{
    render_options ro = {.width = w,
                         .height = h,
                         .spp = 1,
                         .threads = threads,
                         .estimator = est,
                         .light_samples = ns};
    return bench_render_timed(s, &ro, rgb, seconds, err, err_size);
}

static double nmse(const float *img, const float *ref, size_t n)
{
    double num = 0, den = 0;
    for (size_t k = 0; k < n; ++k) {
        double d = (double)img[k] - ref[k];
        num += d * d, den += (double)ref[k] * ref[k];
    }
    return den > 0 ? num / den : NAN;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int bench_lights_report(FILE *out, int json, int reps, int threads, int quick)
{
    const int w = quick ? 32 : 128, h = quick ? 24 : 96, test_ns = 4, ref_ns = quick ? 64 : 256;
    size_t n = (size_t)w * h * 3;
    float *ref = malloc(n * sizeof *ref), *img = malloc(n * sizeof *img);
    double err_eq[SC_COUNT][MODEL_COUNT][E_COUNT], sec[SC_COUNT][MODEL_COUNT][E_COUNT];
    char err[512] = "";
    int rc = -1;
    scene s[E_COUNT];
    int parsed = 0;
    if (!ref || !img) {
        snprintf(err, sizeof err, "out of memory");
        goto out;
    }
    for (int sc = 0; sc < SC_COUNT; ++sc)
        for (int mi = 0; mi < MODEL_COUNT; ++mi) {
            scene base;
            if (make_scene(sc, mi, &base, err, sizeof err)) goto out;
            int r = render_one(&base, w, h, threads, RENDER_EST_MIS, ref_ns, ref, NULL, err,
                               sizeof err);
            scene_free(&base);
            if (r) goto out;
            for (parsed = 0; parsed < E_COUNT; ++parsed)
                if (make_scene(sc, mi, &s[parsed], err, sizeof err)) goto out;
            /* The estimators' renders interleaved, repetition by repetition (a slow spell of
             * the machine hits all three); each render is deterministic, so the image of the
             * last repetition is every repetition's. */
            double t[E_COUNT][64];
            int nr = reps < 64 ? reps : 64;
            for (int rep = 0; rep < nr; ++rep)
                for (int e = 0; e < E_COUNT; ++e) {
                    if (render_one(&s[e], w, h, threads, est_value[e], test_ns, img, &t[e][rep],
                                   err, sizeof err))
                        goto out;
                    if (rep == nr - 1) err_eq[sc][mi][e] = nmse(img, ref, n);
                }
            for (int e = 0; e < E_COUNT; ++e) {
                qsort(t[e], (size_t)nr, sizeof t[e][0], cmp_double);
                sec[sc][mi][e] = t[e][nr / 2];
            }
            for (int e = 0; e < E_COUNT; ++e) scene_free(&s[e]);
            parsed = 0;
        }

    if (json) {
        fprintf(out,
                "{\"width\": %d, \"height\": %d, \"light_samples\": %d, \"reference_light_samples\""
                ": %d, \"threads\": %d, \"reps\": %d, \"rows\": [",
                w, h, test_ns, ref_ns, threads, reps);
        for (int sc = 0; sc < SC_COUNT; ++sc)
            for (int mi = 0; mi < MODEL_COUNT; ++mi) {
                fprintf(out, "%s\n  {\"scene\": \"%s\", \"model\": ", sc || mi ? "," : "",
                        scene_name[sc]);
                cli_json_string(out, models[mi].label);
                fprintf(out, ", \"estimators\": [");
                for (int e = 0; e < E_COUNT; ++e)
                    fprintf(out,
                            "%s{\"name\": \"%s\", \"nmse\": %.6g, \"seconds\": %.6g, "
                            "\"nmse_ratio\": %.6g, \"nmse_time_ratio\": %.6g}",
                            e ? ", " : "", est_name[e], err_eq[sc][mi][e], sec[sc][mi][e],
                            err_eq[sc][mi][e] / err_eq[sc][mi][E_MIS],
                            err_eq[sc][mi][e] * sec[sc][mi][e] /
                                (err_eq[sc][mi][E_MIS] * sec[sc][mi][E_MIS]));
                fprintf(out, "]}");
            }
        fprintf(out, "\n]}");
    } else {
        fprintf(out,
                "\nLight sampling: scenes/area.scene (a small sphere light and a rect light) and "
                "its objects under a\nsky map with a sun; %dx%d, one camera ray per pixel centre, "
                "%d light samples per hit,\nlight and strategy, %d thread(s), median of %d "
                "renders; NMSE against MIS at %d light samples.\n"
                "equal samples: NMSE / NMSE(mis); equal time: NMSE x time / (NMSE x time)(mis), "
                "the time an\nestimator needs for MIS's noise. NMSE x s: noise per unit of time "
                "(lower is better).\n\n",
                w, h, test_ns, threads, reps, ref_ns);
        fprintf(out, "%-12s %-32s %10s %9s | %-13s | %-13s | %-11s\n", "", "", "", "",
                "equal samples", "equal time", "NMSE x s");
        fprintf(out, "%-12s %-32s %10s %9s | %6s %6s | %6s %6s | %11s\n", "scene", "spheres",
                "NMSE mis", "s mis", "light", "brdf", "light", "brdf", "mis");
        for (int sc = 0; sc < SC_COUNT; ++sc)
            for (int mi = 0; mi < MODEL_COUNT; ++mi) {
                const double *q = err_eq[sc][mi], *t = sec[sc][mi];
                fprintf(out, "%-12s %-32s %10.3g %9.4f | %6.3g %6.3g | %6.3g %6.3g | %11.3g\n",
                        scene_name[sc], models[mi].label, q[E_MIS], t[E_MIS], q[E_LIGHT] / q[E_MIS],
                        q[E_BRDF] / q[E_MIS], q[E_LIGHT] * t[E_LIGHT] / (q[E_MIS] * t[E_MIS]),
                        q[E_BRDF] * t[E_BRDF] / (q[E_MIS] * t[E_MIS]), q[E_MIS] * t[E_MIS]);
            }
    }
    rc = 0;
out:
    if (rc) fprintf(stderr, "abrdf bench: %s\n", err);
    for (int e = 0; e < parsed; ++e) scene_free(&s[e]);
    free(ref), free(img);
    return rc;
}
