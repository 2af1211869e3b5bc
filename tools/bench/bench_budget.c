/* bench_budget.c - `abrdf bench --budget`: the payoff of the selection's budget mode on the
 * mixed scene (scenes/mixed.scene: the robot beside hair, cloth, a coated metal and a layered
 * plate, four lights). In one run it resolves the scene's materials by the flowchart's
 * photoreal choice and by the budget mode for each Table-8 class, renders every variant
 * (repetitions interleaved, median time), and reports per class the render time relative to
 * photoreal, the image NMSE against the photoreal render and the NMSE of every material over
 * its own pixels. Goal (docs/BENCHMARKS.md): --budget slight at least 5x faster than
 * photoreal with every material's NMSE within slight. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_budget.h"
#include "bench_scene.h"
#include "budget_run.h"
#include "cli_args.h"
#include "data_path.h"
#include "metrics.h"
#include "mixed_scene.h"
#include "render.h"
#include "scene_select.h"

/* With huang tables (bench_budget_report's tables), photoreal renders its hair from them (the
 * converged model, the reference of every NMSE) and B_PER_CALL renders the photoreal choice
 * with huang's per-call quadrature, what photoreal is without tables. */
enum { B_PHOTO, B_NONE, B_SLIGHT, B_NOTICEABLE, B_PER_CALL, B_COUNT };
static const char *const variant_name[B_COUNT] = {"photoreal", "budget none", "budget slight",
                                                  "budget noticeable", "photoreal per call"};

#define MAX_MATERIALS 16

static int parse_mixed(scene *s, char *err, size_t err_size)
{
    return scene_parse_text("mixed.scene", abrdf_mixed_scene_text, strlen(abrdf_mixed_scene_text),
                            s, err, err_size);
}

/* The mixed scene with its materials chosen as variant v makes them, a budget's hair against
 * its table from `tables` (NULL: against the per-call quadrature); *select_s receives the
 * selection's wall time. */
static int variant_scene(int v, int spp, hair_store *tables, scene *s, double *select_s, char *err,
                         size_t err_size)
{
    if (parse_mixed(s, err, err_size)) return -1;
    char path[1024];
    mat_table table = {NULL, 0, 0};
    if (data_path_find("materials.csv", path, sizeof path)) {
        snprintf(err, err_size, "the material table is missing (set ABRDF_DATA_DIR)");
        scene_free(s);
        return -1;
    }
    if (mat_table_load(&table, path, err, err_size)) {
        scene_free(s);
        return -1;
    }
    double t0 = bench_wall_seconds();
    scene_selection how = SCENE_SELECTION_INIT;
    how.forced = 1;
    how.spp = spp;
    how.points = 1; /* predicted as abrdf render --adaptive --budget predicts */
    how.hair_tables = tables;
    if (v != B_PHOTO && v != B_PER_CALL) {
        how.all.by_budget = 1;
        how.all.max_nmse = abrdf_select_rules_get()->nmse_class_max[v - 1];
    }
    int rc = scene_select(s, "mixed.scene", &how, &table, NULL, err, err_size);
    *select_s = bench_wall_seconds() - t0;
    for (int i = 0; i < s->material_count && v == B_PER_CALL; ++i)
        s->materials[i].huang_per_call = 1;
    mat_table_free(&table);
    if (rc) scene_free(s);
    return rc;
}

/* Pixels where material mi is the closest hit: only its ambient term is non-zero. */
static int mask_of(int mi, const render_options *ro, float *rgb, char *err, size_t err_size)
{
    scene s;
    if (parse_mixed(&s, err, err_size)) return -1;
    for (int c = 0; c < 3; ++c) s.ambient[c] = 1;
    s.light_count = 0;
    for (int i = 0; i < s.material_count; ++i) {
        scene_material *m = &s.materials[i];
        m->kind = SCENE_MAT_MODELS;
        m->lobe_count = 1;
        m->lobes[0] = ABRDF_LAMBERT;
        abrdf_params_init(ABRDF_LAMBERT, &m->params);
        for (int c = 0; c < 3; ++c) m->params.kd[c] = 0, m->ka[c] = i == mi ? 1 : 0;
        m->ka_given = 1;
    }
    render_options one = *ro;
    one.spp = 1;
    int rc = bench_render_timed(&s, &one, rgb, NULL, err, err_size);
    scene_free(&s);
    return rc;
}

static double masked_nmse(const float *img, const float *ref, const float *mask, size_t pixels)
{
    double num, den;
    bench_masked_sums(img, ref, mask, pixels, &num, &den);
    return den > 0 ? num / den : (num > 0 ? INFINITY : 0.0);
}

static void lobe_names(const scene_material *m, char *buf, size_t n)
{
    budget_pair_name(m->lobe_count == 2 ? m->lobes[0] : ABRDF_MODEL_NONE,
                     m->lobes[m->lobe_count - 1], &m->params, buf, n);
}

int bench_budget_report(FILE *out, int json, int size, int spp, int reps, int threads,
                        hair_store *tables)
{
    const int nv = tables ? B_COUNT : B_PER_CALL; /* the variants of this run */
    char err[512] = "";
    scene sv[B_COUNT];
    double select_s[B_COUNT] = {0}, sec[B_COUNT] = {0};
    int parsed = 0, rc = 1;
    float *img[B_COUNT] = {NULL}, *mask = NULL;
    for (; parsed < nv; ++parsed)
        if (variant_scene(parsed, spp, tables, &sv[parsed], &select_s[parsed], err, sizeof err))
            goto out;
    int w = size > 0 ? size : sv[0].camera.width;
    int h = size > 0 ? size * sv[0].camera.height / sv[0].camera.width : sv[0].camera.height;
    size_t pixels = (size_t)w * (size_t)h;
    int nm = sv[0].material_count < MAX_MATERIALS ? sv[0].material_count : MAX_MATERIALS;
    mask = malloc(pixels * 3 * sizeof *mask);
    for (int v = 0; v < nv; ++v)
        if (!(img[v] = malloc(pixels * 3 * sizeof *img[v]))) goto oom;
    if (!mask) goto oom;
    render_options ro = {.width = w, .height = h, .spp = spp, .threads = threads};
    ro.hair_tables = tables;
    /* the median per variant of interleaved repetitions */
    if (bench_render_medians(sv, nv, &ro, reps, img, sec, err, sizeof err)) goto out;
    double nmse[B_COUNT][MAX_MATERIALS], whole[B_COUNT];
    for (int v = 0; v < nv; ++v) whole[v] = masked_nmse(img[v], img[B_PHOTO], NULL, pixels);
    for (int i = 0; i < nm; ++i) {
        if (mask_of(i, &ro, mask, err, sizeof err)) goto out;
        for (int v = 0; v < nv; ++v) nmse[v][i] = masked_nmse(img[v], img[B_PHOTO], mask, pixels);
    }
    /* the goal: slight >= 5x faster with every material within slight */
    double slight = abrdf_select_rules_get()->nmse_class_max[1];
    int over = 0;
    for (int i = 0; i < nm; ++i) over += !(nmse[B_SLIGHT][i] < slight);
    double speedup = sec[B_SLIGHT] > 0 ? sec[B_PHOTO] / sec[B_SLIGHT] : 0;
    double per_call = tables && sec[B_SLIGHT] > 0 ? sec[B_PER_CALL] / sec[B_SLIGHT] : 0;
    /* what the models cost at all: photoreal's rays and effect plan with every BRDF free (a
     * choice of models that also drops tangent frames could save slightly more) */
    render_options free_ro = ro;
    free_ro.free_brdf = 1;
    double free_s = 0;
    if (bench_render_medians(&sv[B_PHOTO], 1, &free_ro, reps, &mask, &free_s, err, sizeof err))
        goto out;
    double bound = free_s > 0 ? sec[B_PHOTO] / free_s : 0;
    char lb[128];
    if (json) {
        fprintf(out,
                "{\"scene\": \"mixed\", \"width\": %d, \"height\": %d, \"spp\": %d, \"threads\": "
                "%d, \"reps\": %d, \"reference\": \"%s\", \"variants\": [",
                w, h, spp, threads, reps, tables ? "photoreal, huang from its table" : "photoreal");
        for (int v = 0; v < nv; ++v) {
            fprintf(out,
                    "%s\n  {\"name\": \"%s\", \"seconds\": %.6g, \"time_ratio\": %.6g, "
                    "\"select_seconds\": %.4g, \"image_nmse\": %.6g, \"materials\": [",
                    v ? "," : "", variant_name[v], sec[v], sec[v] / sec[B_PHOTO], select_s[v],
                    whole[v]);
            for (int i = 0; i < nm; ++i) {
                lobe_names(&sv[v].materials[i], lb, sizeof lb);
                bench_material_json(out, i, sv[v].materials[i].name, lb, nmse[v][i]);
            }
            fprintf(out, "]}");
        }
        fprintf(out, "\n]");
        if (tables)
            fprintf(out,
                    ", \"hair_tables\": {\"sizes\": [%d, %d, %d, %d], \"built\": %d, "
                    "\"build_seconds\": %.4g, \"read\": %d}, \"speedup_slight_per_call\": %.6g",
                    tables->sizes[0], tables->sizes[1], tables->sizes[2], tables->sizes[3],
                    tables->built, tables->build_seconds, tables->read, per_call);
        fprintf(out,
                ", \"brdf_free_seconds\": %.6g, \"speedup_bound\": %.6g, \"goal\": "
                "{\"speedup_slight\": %.6g, \"materials_over_slight\": %d, \"met\": %s}}\n",
                free_s, bound, speedup, over, speedup >= 5.0 && over == 0 ? "true" : "false");
    } else {
        fprintf(out,
                "Mixed scene %dx%d, %d spp, %d thread(s), median of %d renders per variant "
                "(interleaved).\nReference: every material by the flowchart's photoreal choice%s; "
                "budget: abrdf_select_budget per material,\npredicted on its own shading points in "
                "the scene (scene_points.h), as abrdf render predicts%s.\n",
                w, h, spp, threads, reps, tables ? ", huang from its table" : "",
                tables ? ", huang's against its table" : "");
        if (tables)
            fprintf(out,
                    "Huang tables %d,%d,%d,%d: %d built in %.1f s wall (before the renders, not "
                    "in their times), %d read from the cache.\n",
                    tables->sizes[0], tables->sizes[1], tables->sizes[2], tables->sizes[3],
                    tables->built, tables->build_seconds, tables->read);
        fprintf(out, "\n");
        fprintf(out, "%-20s %10s %10s %12s %-12s %10s\n", "variant", "render s", "time/photo",
                "image NMSE", "class", "select s");
        for (int v = 0; v < nv; ++v)
            fprintf(out, "%-20s %10.3f %10.3f %12.3g %-12s %10.2f\n", variant_name[v], sec[v],
                    sec[v] / sec[B_PHOTO], whole[v], v ? abrdf_nmse_class(whole[v]) : "-",
                    select_s[v]);
        fprintf(out, "\n%-8s %-20s %-40s %12s\n", "material", "variant", "models", "NMSE");
        for (int i = 0; i < nm; ++i)
            for (int v = 0; v < nv; ++v) {
                lobe_names(&sv[v].materials[i], lb, sizeof lb);
                fprintf(out, "%-8s %-20s %-40s %12.3g\n", sv[v].materials[i].name, variant_name[v],
                        lb, nmse[v][i]);
            }
        fprintf(out,
                "\ngoal: --budget slight >= 5x faster than photoreal with every material within "
                "slight: %.2fx, %d material(s) over slight: %s\n",
                speedup, over, speedup >= 5.0 && over == 0 ? "met" : "missed");
        if (tables)
            fprintf(out,
                    "--budget slight against photoreal with huang per call (no tables): %.2fx\n",
                    per_call);
        fprintf(out,
                "photoreal with every BRDF free (f_r = 0, the same rays and effect plan): %.3f s, "
                "%.2fx faster: what replacing its models could save at most\n",
                free_s, bound);
    }
    rc = 0;
    goto out;
oom:
    snprintf(err, sizeof err, "out of memory");
out:
    if (rc) fprintf(stderr, "abrdf bench: %s\n", err);
    for (int v = 0; v < parsed; ++v) scene_free(&sv[v]);
    for (int v = 0; v < nv; ++v) free(img[v]);
    free(mask);
    return rc;
}
