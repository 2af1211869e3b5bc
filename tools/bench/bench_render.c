/* bench_render.c - robot renders for `abrdf bench` (bench.h): the per-model image errors
 * and the renderer-level comparison of full Disney against the adaptive selection. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "bench_scene.h"
#include "cli_args.h"
#include "metrics.h"
#include "render.h"
#include "robot_scene.h"
#include "scene_select.h"

int bench_robot_parse(scene *s, char *err, size_t err_size)
{
    return scene_parse_text("robot.scene", abrdf_robot_scene_text, strlen(abrdf_robot_scene_text),
                            s, err, err_size);
}

int bench_robot_lobes(scene *s, int size, int threads, abrdf_model diffuse, abrdf_model specular,
                      const abrdf_params *p, float *rgb, double *seconds, char *err,
                      size_t err_size)
{
    char msg[256];
    abrdf_model lobes[2] = {diffuse, specular};
    for (int l = 0; l < 2; ++l)
        if (lobes[l] != ABRDF_MODEL_NONE &&
            abrdf_params_check(lobes[l], p, msg, sizeof msg) != ABRDF_OK) {
            snprintf(err, err_size, "%s: %s", abrdf_model_get(lobes[l])->name, msg);
            return -1;
        }
    for (int c = 0; c < 3; ++c) s->ambient[c] = 0;
    for (int i = 0; i < s->material_count; ++i) {
        scene_material *m = &s->materials[i];
        m->kind = SCENE_MAT_MODELS;
        m->params = *p;
        for (int c = 0; c < 3; ++c) m->ka[c] = 0;
        m->lobe_count = 0;
        for (int l = 0; l < 2; ++l)
            if (lobes[l] != ABRDF_MODEL_NONE) m->lobes[m->lobe_count++] = lobes[l];
    }
    render_options ro = {.width = size, .height = size, .spp = 1, .threads = threads};
    return bench_render_timed(s, &ro, rgb, seconds, err, err_size);
}

/* ---- `abrdf bench --render` ----------------------------------------------------------- */

/* V_PERF_EXACT is V_PERFORMANCE with each Table-1 approximation replaced by the Blinn-Phong
 * lobe it approximates (same parameters): it splits (c)'s error into the approximation's
 * (c vs d) and the Blinn-Phong family's against the microfacet reference (d vs a). */
enum { V_DISNEY, V_PHOTOREAL, V_PERFORMANCE, V_PERF_EXACT, V_COUNT };
static const char *const variant_name[V_COUNT] = {"full_disney", "adaptive_photoreal",
                                                  "adaptive_performance", "performance_exact_bp"};

static int is_table1(abrdf_model m)
{
    return m == ABRDF_F2 || m == ABRDF_F4 || m == ABRDF_F8 || m == ABRDF_F16 || m == ABRDF_FS ||
           m == ABRDF_FKV || m == ABRDF_FKUB;
}

/* The robot with its materials as variant v makes them. */
static int variant_scene(int v, scene *s, char *err, size_t err_size)
{
    if (bench_robot_parse(s, err, err_size)) return -1;
    if (v == V_DISNEY) {
        for (int i = 0; i < s->material_count; ++i) {
            scene_material *m = &s->materials[i];
            m->lobe_count = 2;
            m->lobes[0] = ABRDF_DISNEY_DIFFUSE;
            m->lobes[1] = ABRDF_DISNEY_SPECULAR;
        }
        return 0;
    }
    scene_selection how = SCENE_SELECTION_INIT;
    how.forced = 1;
    how.all.goal = v == V_PHOTOREAL ? ABRDF_GOAL_PHOTOREAL : ABRDF_GOAL_PERFORMANCE;
    if (scene_select(s, "robot.scene", &how, NULL, NULL, err, err_size)) {
        scene_free(s);
        return -1;
    }
    if (v == V_PERF_EXACT)
        for (int i = 0; i < s->material_count; ++i)
            for (int l = 0; l < s->materials[i].lobe_count; ++l)
                if (is_table1(s->materials[i].lobes[l]))
                    s->materials[i].lobes[l] = ABRDF_BLINN_PHONG;
    return 0;
}

/* Mask of the pixels material mi covers: only its ambient term is non-zero. */
static int material_mask(int mi, int w, int h, int threads, float *rgb, char *err, size_t err_size)
{
    scene s;
    if (bench_robot_parse(&s, err, err_size)) return -1;
    for (int c = 0; c < 3; ++c) s.ambient[c] = 1;
    for (int i = 0; i < s.material_count; ++i) {
        scene_material *m = &s.materials[i];
        m->kind = SCENE_MAT_MODELS;
        m->lobe_count = 1;
        m->lobes[0] = ABRDF_LAMBERT;
        for (int c = 0; c < 3; ++c) m->params.kd[c] = 0, m->ka[c] = i == mi ? 1 : 0;
    }
    render_options ro = {.width = w, .height = h, .spp = 1, .threads = threads};
    int rc = bench_render_timed(&s, &ro, rgb, NULL, err, err_size);
    scene_free(&s);
    return rc;
}

/* NMSE of img vs ref over the pixels where mask > 0.5 (all pixels if mask is NULL). */
static double masked_nmse(const float *img, const float *ref, const float *mask, size_t pixels)
{
    double num, den;
    bench_masked_sums(img, ref, mask, pixels, &num, &den);
    return den > 0 ? num / den : NAN;
}

static void lobe_names(const scene_material *m, char *buf, size_t n)
{
    buf[0] = 0;
    for (int l = 0; l < m->lobe_count; ++l) {
        size_t len = strlen(buf);
        snprintf(buf + len, n - len, "%s%s", l ? " + " : "", abrdf_model_get(m->lobes[l])->name);
    }
}

#define MAX_MATERIALS 16

int bench_render_report(FILE *out, int json, int size, int reps, int threads, int lobe_size,
                        int quick)
{
    char err[512];
    scene sv[V_COUNT];
    int parsed = 0, rc = 1;
    float *img[V_COUNT] = {NULL}, *mask = NULL;
    double sec[V_COUNT] = {0};
    for (; parsed < V_COUNT; ++parsed)
        if (variant_scene(parsed, &sv[parsed], err, sizeof err)) goto out;
    int w = size > 0 ? size : sv[0].camera.width, h = size > 0 ? size : sv[0].camera.height;
    size_t pixels = (size_t)w * (size_t)h;
    int nm = sv[0].material_count < MAX_MATERIALS ? sv[0].material_count : MAX_MATERIALS;
    mask = malloc(pixels * 3 * sizeof *mask);
    for (int v = 0; v < V_COUNT; ++v)
        if (!(img[v] = malloc(pixels * 3 * sizeof *img[v]))) goto oom;
    if (!mask) goto oom;
    /* the median per variant of interleaved repetitions */
    render_options ro = {.width = w, .height = h, .spp = 1, .threads = threads};
    if (bench_render_medians(sv, V_COUNT, &ro, reps, img, sec, err, sizeof err)) goto out;

    double nmse[V_COUNT][MAX_MATERIALS], whole[V_COUNT], approx[MAX_MATERIALS];
    for (int v = 0; v < V_COUNT; ++v) whole[v] = masked_nmse(img[v], img[V_DISNEY], NULL, pixels);
    double approx_whole = masked_nmse(img[V_PERFORMANCE], img[V_PERF_EXACT], NULL, pixels);
    for (int i = 0; i < nm; ++i) {
        if (material_mask(i, w, h, threads, mask, err, sizeof err)) goto out;
        for (int v = 0; v < V_COUNT; ++v)
            nmse[v][i] = masked_nmse(img[v], img[V_DISNEY], mask, pixels);
        approx[i] = masked_nmse(img[V_PERFORMANCE], img[V_PERF_EXACT], mask, pixels);
    }

    char lb[128];
    if (json) {
        fprintf(
            out,
            "{\"scene\": \"robot\", \"width\": %d, \"height\": %d, \"spp\": 1, \"threads\": %d, "
            "\"reps\": %d, \"reference\": \"full_disney\", \"variants\": [",
            w, h, threads, reps);
        for (int v = 0; v < V_COUNT; ++v) {
            fprintf(out,
                    "%s\n  {\"name\": \"%s\", \"time_ratio\": %.6g, \"image_nmse\": %.6g, "
                    "\"materials\": [",
                    v ? "," : "", variant_name[v], sec[v] / sec[V_DISNEY], whole[v]);
            for (int i = 0; i < nm; ++i) {
                lobe_names(&sv[v].materials[i], lb, sizeof lb);
                bench_material_json(out, i, sv[v].materials[i].name, lb, nmse[v][i]);
            }
            fprintf(out, "]}");
        }
        fprintf(out, "\n], \"performance_vs_exact_bp\": {\"image_nmse\": %.6g, \"materials\": [",
                approx_whole);
        for (int i = 0; i < nm; ++i) {
            fprintf(out, "%s{\"material\": ", i ? ", " : "");
            cli_json_string(out, sv[0].materials[i].name);
            fprintf(out, ", \"nmse\": %.6g}", isfinite(approx[i]) ? approx[i] : -1.0);
        }
        fprintf(out, "]},\n\"lobe_costs\": ");
        if (bench_lobe_report(out, 1, lobe_size, reps, quick)) goto out;
        fprintf(out, ",\n\"light_sampling\": ");
        if (bench_lights_report(out, 1, reps, threads, quick)) goto out;
        fprintf(out, "}\n");
    } else {
        fprintf(out,
                "Robot %dx%d, 1 spp, %d thread(s), median of %d renders per variant.\n"
                "Reference (a): every material disney_diffuse + disney_specular. "
                "performance_exact_bp:\n"
                "adaptive_performance with each Table-1 approximation replaced by Blinn-Phong.\n\n",
                w, h, threads, reps);
        fprintf(out, "%-22s %10s %12s %10s\n", "variant", "time/(a)", "image NMSE", "class");
        for (int v = 0; v < V_COUNT; ++v)
            fprintf(out, "%-22s %10.3f %12.3g %10s\n", variant_name[v], sec[v] / sec[V_DISNEY],
                    whole[v], v ? abrdf_nmse_class(whole[v]) : "-");
        fprintf(out, "\n%-8s %-22s %-36s %12s\n", "material", "variant", "models", "NMSE vs (a)");
        for (int i = 0; i < nm; ++i)
            for (int v = 0; v < V_COUNT; ++v) {
                lobe_names(&sv[v].materials[i], lb, sizeof lb);
                fprintf(out, "%-8s %-22s %-36s %12.3g\n", sv[v].materials[i].name, variant_name[v],
                        lb, nmse[v][i]);
            }
        fprintf(out,
                "\nadaptive_performance vs performance_exact_bp (the approximation's own error):\n"
                "  image %.3g",
                approx_whole);
        for (int i = 0; i < nm; ++i) fprintf(out, ", %s %.3g", sv[0].materials[i].name, approx[i]);
        fprintf(out, "\n");
        if (bench_lobe_report(out, 0, lobe_size, reps, quick)) goto out;
        if (bench_lights_report(out, 0, reps, threads, quick)) goto out;
    }
    rc = 0;
    goto out;
oom:
    snprintf(err, sizeof err, "out of memory");
out:
    if (rc) fprintf(stderr, "abrdf bench: %s\n", err);
    for (int v = 0; v < parsed; ++v) scene_free(&sv[v]);
    for (int v = 0; v < V_COUNT; ++v) free(img[v]);
    free(mask);
    return rc;
}
