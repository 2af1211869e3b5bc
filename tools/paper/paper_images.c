/* paper_images.c - Tables 6 and 7 of Zavalniuk & Romanyuk 2024 (Sec. 4, the image
 * experiment): the robot rendered with the Disney GGX specular (the reference) at each
 * alpha_g, each candidate lobe rendered at each exponent n; per alpha_g the minimum over n of
 * NMSE(candidate vs reference) (tools/image/metrics.h) and its argmin n, printed beside the
 * published values (data/paper_tables.csv). Set-up and discussion: docs/TABLES.md, "Tables 6
 * and 7". */
#define _POSIX_C_SOURCE 200809L
#include "paper_images.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "metrics.h"
#include "render.h"
#include "robot_scene.h"
#include "scene_load.h"

/* The paper's alpha_g values, as printed in Tables 6-7 (the rows of the published data). */
static const char *const alpha_g_label[PAPER_IMAGES_ROWS] = {
    "1.0", "0.9",  "0.8",  "0.7",   "0.6",   "0.5",    "0.4",    "0.3",     "0.2",
    "0.1", "0.05", "0.01", "0.005", "0.001", "0.0005", "0.0001", "0.00005", "0.00001"};
/* The exponents searched, as listed in the paper (Sec. 4). */
const double paper_images_exponents[PAPER_IMAGES_EXPONENTS] = {
    1, 5, 10, 20, 40, 60, 80, 100, 200, 300, 400, 500, 600, 700, 800, 900, 950, 1000};
static const char *const table_models[2][PAPER_IMAGES_MODELS] = {
    {"f_phe", "f_be", "f_2e", "f_16e"},      /* Table 6: no Fresnel factor */
    {"f_ge", "f_ctphe", "f_ct2e", "f_ct16e"} /* Table 7: with a Fresnel factor */
};

void paper_images_defaults(paper_images_options *o)
{
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    *o = (paper_images_options){128,  128, 1,    cpus > 0 ? (int)(cpus < 64 ? cpus : 64) : 1,
                                0.04, 0.5, NULL, 0};
}

/* Every material of s becomes Lambert(kd) (if kd > 0) + `model` with parameters p, and the
 * ambient term goes: one light only, as in the lit-object view. */
static int set_material(scene *s, abrdf_model model, const abrdf_params *p, double kd, char *err,
                        size_t err_size)
{
    abrdf_params q = *p;
    for (int c = 0; c < 3; ++c) q.kd[c] = kd, s->ambient[c] = 0;
    char msg[256];
    if (abrdf_params_check(model, &q, msg, sizeof msg) != ABRDF_OK ||
        (kd > 0 && abrdf_params_check(ABRDF_LAMBERT, &q, msg, sizeof msg) != ABRDF_OK)) {
        snprintf(err, err_size, "%s: %s", abrdf_model_get(model)->name, msg);
        return -1;
    }
    for (int i = 0; i < s->material_count; ++i) {
        scene_material *m = &s->materials[i];
        m->kind = SCENE_MAT_MODELS;
        m->params = q;
        for (int c = 0; c < 3; ++c) m->ka[c] = 0;
        m->lobe_count = 0;
        if (kd > 0) m->lobes[m->lobe_count++] = ABRDF_LAMBERT;
        m->lobes[m->lobe_count++] = model;
    }
    return 0;
}

static int render_with(scene *s, const paper_images_options *o, abrdf_model model,
                       const abrdf_params *p, float *rgb, char *err, size_t err_size)
{
    if (set_material(s, model, p, o->kd, err, err_size)) return -1;
    /* The double reference path: the experiment's NMSE reaches 1e-15, below the float path's
     * rounding, and its values must not depend on the instruction set the CPU offers. */
    render_options ro = {.width = o->width,
                         .height = o->height,
                         .spp = o->spp,
                         .threads = o->threads,
                         .precision = RENDER_DOUBLE};
    render_scene rs;
    if (render_prepare(s, &ro, &rs, err, err_size)) return -1;
    int rc = render_image(&rs, &ro, rgb, NULL);
    render_release(&rs);
    if (rc) snprintf(err, err_size, "cannot start render threads");
    return rc;
}

static void progress(const paper_images_options *o, int table, int done, int total)
{
    if (!o->progress) return;
    fprintf(stderr, "\rTable %d: %d/%d renders", table, done, total);
    if (done == total) fputc('\n', stderr);
}

int paper_images_compute(int table, const paper_images_options *o, paper_images_result *res,
                         char *err, size_t err_size)
{
    memset(res, 0, sizeof *res);
    if (table != 6 && table != 7) {
        snprintf(err, err_size, "table %d: the image experiments are Tables 6 and 7", table);
        return -1;
    }
    long k = lround(sqrt((double)o->spp));
    if (o->width < 1 || o->height < 1 || o->spp < 1 || k * k != o->spp || o->threads < 1 ||
        !(o->f0 >= 0 && o->f0 <= 1) || !(o->kd >= 0 && o->kd <= 1)) {
        snprintf(err, err_size,
                 "invalid options (size, square spp, threads >= 1, f0 and kd in [0, 1])");
        return -1;
    }
    const int t = table - 6;
    res->table = table;
    abrdf_model models[PAPER_IMAGES_MODELS];
    for (int m = 0; m < PAPER_IMAGES_MODELS; ++m) {
        res->model[m] = table_models[t][m];
        if (abrdf_model_find(res->model[m], &models[m]) != ABRDF_OK) {
            snprintf(err, err_size, "model %s is not in the library", res->model[m]);
            return -1;
        }
    }
    scene s;
    int parsed = o->scene_path
                     ? scene_load(o->scene_path, &s, err, err_size)
                     : scene_parse_text("robot.scene", abrdf_robot_scene_text,
                                        strlen(abrdf_robot_scene_text), &s, err, err_size);
    if (parsed) return -1;

    const int rows = PAPER_IMAGES_ROWS, total = rows + PAPER_IMAGES_MODELS * PAPER_IMAGES_EXPONENTS;
    size_t px = (size_t)o->width * (size_t)o->height * 3;
    float *ref = malloc((size_t)rows * px * sizeof *ref), *img = malloc(px * sizeof *img);
    int rc = -1;
    if (!ref || !img) {
        snprintf(err, err_size, "out of memory for %d images of %dx%d", rows + 1, o->width,
                 o->height);
        goto out;
    }
    /* Reference: Disney specular, ks = 1, F0 = f0, r = sqrt(alpha_g) (alpha_g = r^2). */
    for (int r = 0; r < rows; ++r) {
        res->label[r] = alpha_g_label[r];
        res->alpha_g[r] = strtod(alpha_g_label[r], NULL);
        abrdf_params p;
        abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
        for (int c = 0; c < 3; ++c) p.ks[c] = 1, p.f0[c] = o->f0;
        p.r = sqrt(res->alpha_g[r]);
        if (render_with(&s, o, ABRDF_DISNEY_SPECULAR, &p, ref + (size_t)r * px, err, err_size))
            goto out;
        for (int m = 0; m < PAPER_IMAGES_MODELS; ++m)
            res->nmse[r][m] = INFINITY, res->n[r][m] = NAN;
        progress(o, table, ++res->renders, total);
    }
    /* Candidates: lobes without a Fresnel factor get ks = f0 (the reference's reflectance at
     * normal incidence); lobes with one get ks = 1 and F0 = f0, like the reference. A
     * candidate image is compared with every reference, so each is rendered once. */
    for (int m = 0; m < PAPER_IMAGES_MODELS; ++m) {
        int fresnel = (abrdf_model_get(models[m])->needs & ABRDF_NEEDS_FRESNEL) != 0;
        for (int j = 0; j < PAPER_IMAGES_EXPONENTS; ++j) {
            abrdf_params p;
            abrdf_params_init(models[m], &p);
            for (int c = 0; c < 3; ++c) p.ks[c] = fresnel ? 1 : o->f0, p.f0[c] = o->f0;
            p.n = paper_images_exponents[j];
            if (render_with(&s, o, models[m], &p, img, err, err_size)) goto out;
            for (int r = 0; r < rows; ++r) {
                abrdf_metrics mt;
                if (abrdf_metrics_compute(img, ref + (size_t)r * px, o->width, o->height, 3, &mt) !=
                    ABRDF_METRICS_OK) {
                    snprintf(err, err_size, "non-finite pixel in a render of %s", res->model[m]);
                    goto out;
                }
                res->defined[r] = mt.nmse_defined;
                if (mt.nmse_defined && mt.nmse < res->nmse[r][m])
                    res->nmse[r][m] = mt.nmse, res->n[r][m] = paper_images_exponents[j];
            }
            progress(o, table, ++res->renders, total);
        }
    }
    for (int r = 0; r < rows; ++r)
        if (!res->defined[r])
            for (int m = 0; m < PAPER_IMAGES_MODELS; ++m) res->nmse[r][m] = NAN;
    rc = 0;
out:
    free(ref);
    free(img);
    scene_free(&s);
    return rc;
}
