/* bench_lobes.c - `abrdf bench --render`, second part (bench.h): does the renderer show what a
 * lobe costs? On the shading-bound robot (scenes/robot16.scene, 16 point lights), one
 * thread, the render time of lambert + X minus that of lambert alone is X's cost in the
 * render; its ratio to disney_specular's is set beside the ratio of their costs per
 * evaluation on the batch path (abrdf_eval_batch, measure.c). A renderer that shows the cost
 * of accuracy has the two ratios close (goal: within 1.5x). A render that does all its
 * shading work but calls no BRDF (render_options.free_brdf) gives the share of the BRDFs in
 * the render time. Times are the calling thread's CPU clock (a one-thread render runs on
 * it), so other jobs on the machine add little. A lobe's cost is a small difference of two
 * renders, so each repetition renders lambert alone right before each variant and keeps the
 * difference (the pair shares the machine's state); the median difference is reported. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "measure.h"
#include "render.h"
#include "robot_scene.h"

static double thread_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The specular lobes compared with disney_specular (first: the reference of the ratios). */
static const abrdf_model lobes[] = {ABRDF_DISNEY_SPECULAR,
                                    ABRDF_COOK_TORRANCE,
                                    ABRDF_BLINN_PHONG,
                                    ABRDF_PHONG,
                                    ABRDF_F2,
                                    ABRDF_F4,
                                    ABRDF_F8,
                                    ABRDF_F16,
                                    ABRDF_FS,
                                    ABRDF_FKV,
                                    ABRDF_FKUB,
                                    ABRDF_F_2E,
                                    ABRDF_F_16E,
                                    ABRDF_F_BE,
                                    ABRDF_DISNEY_CLEARCOAT};
#define NLOBES ((int)(sizeof lobes / sizeof lobes[0]))
/* Variants: 0 = free (lambert's shading work, no BRDF call), 1 = lambert, 2 + k = lambert +
 * lobes[k], and last = full Disney (disney_diffuse + disney_specular). */
#define V_FREE 0
#define V_LAMBERT 1
#define V_FULL (2 + NLOBES)
#define NVAR (3 + NLOBES)

/* The parameters of variant v: the lobe's defaults with lambert's kd = 0.5. */
static void variant_params(int v, abrdf_params *p)
{
    abrdf_model m = v >= 2 && v < V_FULL ? lobes[v - 2] : ABRDF_DISNEY_SPECULAR;
    abrdf_params_init(m, p);
    p->kd[0] = p->kd[1] = p->kd[2] = 0.5;
}

static int variant_scene(int v, scene *s, char *err, size_t err_size)
{
    if (scene_parse_text("robot16.scene", abrdf_robot16_scene_text,
                         strlen(abrdf_robot16_scene_text), s, err, err_size))
        return -1;
    abrdf_params p;
    variant_params(v, &p);
    for (int i = 0; i < s->material_count; ++i) {
        scene_material *m = &s->materials[i];
        m->kind = SCENE_MAT_MODELS;
        m->params = p;
        m->lobe_count = 1;
        m->lobes[0] = v == V_FULL ? ABRDF_DISNEY_DIFFUSE : ABRDF_LAMBERT;
        if (v >= 2) m->lobes[m->lobe_count++] = v == V_FULL ? ABRDF_DISNEY_SPECULAR : lobes[v - 2];
    }
    return 0;
}

int bench_lobe_report(FILE *out, int json, int size, int reps, int quick)
{
    reps = 3 * reps; /* renders of ~20 ms: more repetitions, a steadier median */
    char err[512];
    scene sv[NVAR];
    render_scene rs[NVAR];
    int parsed = 0, prepared = 0, rc = 1;
    double *t = NULL, *dt = NULL, sec[NVAR], diff[NVAR], eval_ns[NLOBES], unit_ns = 0;
    float *rgb = NULL;
    measure_set *ms = NULL;
    render_options ro = {.width = size, .height = size, .spp = 1, .threads = 1};
    for (; parsed < NVAR; ++parsed)
        if (variant_scene(parsed, &sv[parsed], err, sizeof err)) goto out;
    if (size <= 0) ro.width = ro.height = size = sv[0].camera.width;
    for (; prepared < NVAR; ++prepared)
        if (render_prepare(&sv[prepared], &ro, &rs[prepared], err, sizeof err)) goto out;
    rgb = malloc((size_t)size * (size_t)size * 3 * sizeof *rgb);
    t = malloc(sizeof(double) * (size_t)(reps * NVAR));
    dt = malloc(sizeof(double) * (size_t)(reps * NVAR));
    if (!rgb || !t || !dt) goto oom;
    render_stats st;
    unsigned long long lit_pairs = 0;
    for (int r = -1; r < reps; ++r) /* r = -1: untimed warm-up */
        for (int v = 0; v < NVAR; ++v) {
            double tv[2];
            for (int pass = 0; pass < 2; ++pass) { /* lambert alone, then variant v */
                int u = pass ? v : V_LAMBERT;
                render_options o = ro;
                o.free_brdf = u == V_FREE;
                double t0 = thread_seconds();
                if (render_image(&rs[u], &o, rgb, &st)) {
                    snprintf(err, sizeof err, "cannot render");
                    goto out;
                }
                tv[pass] = thread_seconds() - t0;
                if (u == V_LAMBERT) lit_pairs = st.brdf_evals;
            }
            if (r >= 0) t[v * reps + r] = tv[1], dt[v * reps + r] = tv[1] - tv[0];
        }
    for (int v = 0; v < NVAR; ++v) {
        qsort(t + v * reps, (size_t)reps, sizeof(double), cmp_double);
        qsort(dt + v * reps, (size_t)reps, sizeof(double), cmp_double);
        sec[v] = t[v * reps + reps / 2];
        diff[v] = dt[v * reps + reps / 2]; /* median of (v - lambert) */
    }
    /* Per-evaluation costs of the same lobes with the same parameters, batch path. */
    measure_opts mo;
    measure_defaults(&mo, quick);
    if (!(ms = measure_set_new(mo.pairs))) goto oom;
    unit_ns = measure_unit_ns(ms, &mo);
    for (int k = 0; k < NLOBES; ++k) {
        abrdf_params p;
        variant_params(2 + k, &p);
        eval_ns[k] = measure_model_params_ns(ms, lobes[k], &p, 0, &mo);
        if (!(eval_ns[k] > 0)) {
            snprintf(err, sizeof err, "cannot time %s", abrdf_model_get(lobes[k])->name);
            goto out;
        }
    }
    double ds_render = diff[2], ds_eval = eval_ns[0];
    double share = (diff[V_FULL] - diff[V_FREE]) / sec[V_FULL]; /* the BRDFs' share */
    int within = 0;
    if (json)
        fprintf(out,
                "{\"scene\": \"robot16\", \"width\": %d, \"height\": %d, \"spp\": 1, "
                "\"threads\": 1, \"reps\": %d, \"lit_pairs\": %llu, \"unit_ns\": %.6g, "
                "\"free_seconds\": %.6g, \"lambert_seconds\": %.6g, \"full_disney_seconds\": "
                "%.6g, \"brdf_share_full_disney\": %.6g, \"lobes\": [",
                size, size, reps, lit_pairs, unit_ns, sec[V_FREE], sec[V_LAMBERT], sec[V_FULL],
                share);
    else
        fprintf(
            out,
            "\nLobe costs in the render: robot16 (16 point lights) %dx%d, 1 spp, 1 thread, "
            "float shading,\nmedian of %d paired renders per variant (thread CPU time), %llu lit "
            "(hit, light) pairs.\nrender = time(lambert + X) - time(lambert), rendered one after "
            "the other; eval = batch "
            "ns/eval; both relative to disney_specular.\n\n%-22s %10s %10s %10s %8s\n",
            size, size, reps, lit_pairs, "lobe X", "render ms", "render/ds", "eval/ds", "ratio");
    for (int k = 0; k < NLOBES; ++k) {
        double cost = diff[2 + k];
        double rr = cost / ds_render, er = eval_ns[k] / ds_eval;
        double q = rr > 0 ? (rr > er ? rr / er : er / rr) : INFINITY;
        within += q <= 1.5;
        if (json)
            fprintf(out,
                    "%s\n  {\"lobe\": \"%s\", \"render_seconds\": %.6g, \"render_ratio\": %.6g, "
                    "\"eval_ns\": %.6g, \"eval_ratio\": %.6g}",
                    k ? "," : "", abrdf_model_get(lobes[k])->name, cost, rr, eval_ns[k], er);
        else
            fprintf(out, "%-22s %10.2f %10.3f %10.3f %8.2f%s\n", abrdf_model_get(lobes[k])->name,
                    1e3 * cost, rr, er, q, q <= 1.5 ? "" : "  (> 1.5x)");
    }
    if (json)
        fprintf(out, "\n], \"within_1_5x\": %d, \"lobe_count\": %d}\n", within, NLOBES);
    else
        fprintf(out,
                "\n%d of %d lobes have render/ds within 1.5x of eval/ds (goal: all).\n"
                "Render times: free BRDF %.1f ms, lambert %.1f ms, full Disney %.1f ms: the BRDFs "
                "are %.0f %% of the full-Disney render\n(time - free) / time; shading also "
                "casts 16 shadow rays per hit, which the free variant keeps.\n",
                within, NLOBES, 1e3 * sec[V_FREE], 1e3 * sec[V_LAMBERT], 1e3 * sec[V_FULL],
                100.0 * share);
    rc = 0;
    goto out;
oom:
    snprintf(err, sizeof err, "out of memory");
out:
    if (rc) fprintf(stderr, "abrdf bench: %s\n", err);
    measure_set_free(ms);
    for (int v = 0; v < prepared; ++v) render_release(&rs[v]);
    for (int v = 0; v < parsed; ++v) scene_free(&sv[v]);
    free(rgb);
    free(t);
    free(dt);
    return rc;
}
