/* budget_points.c - the budget mode's prediction on the sphere against the prediction on the
 * scene's own shading points, each against the NMSE measured in the image (docs/SELECTION.md,
 * "2. The prediction"). For one scene it chooses every material by the budget (--adaptive, as
 * `abrdf render --adaptive --budget B` does) twice: predicted on the sphere
 * (scene_budget_view) and on the scene's shading points (scene_points.h); renders the
 * reference (the flowchart's photoreal choice) and both choices; and prints, for each material
 * and each choice, the choice's NMSE predicted on the sphere, predicted on the points, and
 * measured over the material's own pixels (those whose centre sees it). Times: the pass over
 * the scene's points and each selection.
 *
 *   budget_points SCENE [--budget CLASS|NMSE] [--spp K] [--threads T] [--check FACTOR]
 *
 * K is a square (1, 4, 9, ..., 64): the render's strata form a k x k grid.
 *
 * --check exits 1 unless, for every material the points see, the points' prediction of the
 * points' choice is within FACTOR of the measurement (values under 1e-8 compared as 1e-8). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "budget_run.h"
#include "cli_args.h"
#include "data_path.h"
#include "materials.h"
#include "render.h"
#include "scene_points.h"
#include "scene_select.h"

/* Values below this are compared as this in --check: far below the class "none" (1e-4). */
#define NMSE_FLOOR 1e-8

enum { V_REF, V_SPHERE, V_POINTS, V_COUNT };
static const char *const variant_name[V_COUNT] = {"photoreal", "sphere", "points"};

static double wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The scene at path with every material chosen as variant v asks; *sec: the selection's
 * wall time. 0, or -1 with the message on stderr. */
static int variant(const char *path, const mat_table *table, int v, double max_nmse, int spp,
                   scene *s, double *sec)
{
    char err[1024];
    if (scene_parse_file(path, s, err, sizeof err)) {
        fprintf(stderr, "budget_points: %s\n", err);
        return -1;
    }
    scene_selection how = SCENE_SELECTION_INIT;
    how.forced = 1;
    how.spp = spp;
    if (v != V_REF) how.all.by_budget = 1, how.all.max_nmse = max_nmse;
    how.points = v == V_POINTS;
    double t0 = wall_seconds();
    if (scene_select(s, path, &how, table, NULL, err, sizeof err)) {
        fprintf(stderr, "budget_points: %s\n", err);
        scene_free(s);
        return -1;
    }
    *sec = wall_seconds() - t0;
    return 0;
}

static float *render(const scene *s, int spp, int threads)
{
    render_options ro = {.spp = spp, .threads = threads, .precision = RENDER_DOUBLE};
    render_scene rs;
    char err[512];
    if (render_prepare(s, &ro, &rs, err, sizeof err)) {
        fprintf(stderr, "budget_points: %s\n", err);
        return NULL;
    }
    float *rgb = malloc((size_t)rs.width * (size_t)rs.height * 3 * sizeof *rgb);
    if (!rgb)
        fprintf(stderr, "budget_points: out of memory for the image\n");
    else if (render_image(&rs, &ro, rgb, NULL)) {
        /* spp is a square (checked with the arguments): the lock could not be made */
        fprintf(stderr,
                "budget_points: the image cannot be rendered (render_image refused "
                "%d samples per pixel or could not make its lock)\n",
                spp);
        free(rgb);
        rgb = NULL;
    }
    render_release(&rs);
    return rgb;
}

/* NMSE of img against ref over the pixels whose centre sees material m. */
static double measured(const float *img, const float *ref, const scene_points *p, int m)
{
    double num = 0.0, den = 0.0;
    for (size_t q = 0; q < (size_t)p->width * (size_t)p->height; ++q) {
        if (p->pixel_material[q] != m) continue;
        for (int c = 0; c < 3; ++c) {
            double d = (double)img[3 * q + c] - ref[3 * q + c];
            num += d * d, den += (double)ref[3 * q + c] * ref[3 * q + c];
        }
    }
    return den > 0.0 ? num / den : (num > 0.0 ? INFINITY : 0.0);
}

static void lobes_of(const scene_material *m, abrdf_model *d, abrdf_model *sp)
{
    *d = m->lobe_count == 2 ? m->lobes[0] : ABRDF_MODEL_NONE;
    *sp = m->lobes[m->lobe_count - 1];
}

/* The predicted NMSE of material c against the same material ref on view, into *nmse (NaN if
 * abrdf_predict_nmse refuses the pair). 0, or -1 out of memory, with the message on stderr. */
static int predicted(const scene_material *ref, const scene_material *c, const abrdf_view *view,
                     double *nmse)
{
    abrdf_model rd, rs, cd, cs;
    lobes_of(ref, &rd, &rs);
    lobes_of(c, &cd, &cs);
    size_t size = abrdf_fit_workspace_size(NULL, view);
    void *work = malloc(size);
    if (!work) {
        fprintf(stderr, "budget_points: %s: out of memory for the prediction's workspace\n",
                c->name);
        return -1;
    }
    if (abrdf_predict_nmse(rd, rs, &ref->params, cd, cs, &c->params, view, nmse, work, size) !=
        ABRDF_OK)
        *nmse = NAN; /* a pair the prediction does not cover: NaN in the table */
    free(work);
    return 0;
}

static double floored(double x) { return x > NMSE_FLOOR ? x : NMSE_FLOOR; }

int main(int argc, char **argv)
{
    const char *path = NULL, *budget = "slight";
    long spp = 4, threads = 2;
    double factor = 0.0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--budget") && i + 1 < argc)
            budget = argv[++i];
        else if (!strcmp(a, "--spp") && i + 1 < argc && cli_parse_int(argv[i + 1], 1, 64, &spp)) {
            long k = lround(sqrt((double)spp));
            if (k * k != spp) {
                fprintf(stderr, "budget_points: --spp %ld: not a square (1, 4, 9, ..., 64)\n", spp);
                return 2;
            }
            ++i;
        } else if (!strcmp(a, "--threads") && i + 1 < argc &&
                   cli_parse_int(argv[i + 1], 1, 64, &threads))
            ++i;
        else if (!strcmp(a, "--check") && i + 1 < argc && cli_parse_double(argv[i + 1], &factor) &&
                 factor > 1.0)
            ++i;
        else if (a[0] != '-' && !path)
            path = a;
        else {
            fprintf(stderr,
                    "budget_points: bad argument '%s'; usage: budget_points SCENE [--budget "
                    "CLASS|NMSE] [--spp K (a square, 1-64)] [--threads T (1-64)] [--check FACTOR "
                    "(> 1)]\n",
                    a);
            return 2;
        }
    }
    double max_nmse;
    char err[1024];
    if (!path) {
        fprintf(stderr, "budget_points: no scene; usage: budget_points SCENE [options]\n");
        return 2;
    }
    if (budget_parse(budget, &max_nmse, err, sizeof err)) {
        fprintf(stderr, "budget_points: --budget: %s\n", err);
        return 2;
    }
    char tpath[4096];
    mat_table table = {NULL, 0, 0};
    /* not found: tpath is the source tree's path, and the loader says what is wrong with it */
    data_path_find("materials.csv", tpath, sizeof tpath);
    if (mat_table_load(&table, tpath, err, sizeof err)) {
        fprintf(stderr, "budget_points: the material table: %s\n", err);
        return 1;
    }
    scene sv[V_COUNT], base;
    double sel[V_COUNT] = {0};
    float *img[V_COUNT] = {NULL};
    int made = 0, rc = 1;
    scene_points pts;
    memset(&pts, 0, sizeof pts);
    for (; made < V_COUNT; ++made)
        if (variant(path, &table, made, max_nmse, (int)spp, &sv[made], &sel[made])) goto out;
    if (scene_parse_file(path, &base, err, sizeof err)) {
        fprintf(stderr, "budget_points: %s\n", err);
        goto out;
    }
    int traced = !scene_points_trace(&base, (int)spp, &pts, err, sizeof err);
    abrdf_light_dir lights[SCENE_MAX_LIGHTS];
    abrdf_view sphere;
    scene_budget_view(&base, (int)spp, &sphere, lights);
    scene_free(&base);
    if (!traced) {
        fprintf(stderr, "budget_points: %s\n", err);
        goto out;
    }
    for (int v = 0; v < V_COUNT; ++v)
        if (!(img[v] = render(&sv[v], (int)spp, (int)threads))) goto out;
    printf("%s, budget NMSE < %g, %d x %d, %d spp: predicted on the sphere (scene_budget_view) "
           "and on the scene's shading points, measured over each material's pixels\n",
           path, max_nmse, pts.width, pts.height, pts.spp);
    printf("pass over the shading points %.3f s; selection on the sphere %.2f s, on the points "
           "%.2f s (the pass included)\n\n",
           pts.seconds, sel[V_SPHERE], sel[V_POINTS]);
    printf("%-10s %-7s %-46s %11s %11s %11s %7s\n", "material", "chosen", "models", "pred sphere",
           "pred points", "measured", "terms");
    int off = 0;
    for (int m = 0; m < pts.material_count; ++m) {
        abrdf_view own;
        int seen = scene_points_view(&pts, m, &own);
        for (int v = V_SPHERE; v < V_COUNT; ++v) {
            const scene_material *c = &sv[v].materials[m], *r = &sv[V_REF].materials[m];
            abrdf_model d, sp;
            lobes_of(c, &d, &sp);
            char name[128];
            budget_pair_name(d, sp, &c->params, name, sizeof name);
            double ps, pp = NAN;
            if (predicted(r, c, &sphere, &ps) || (seen && predicted(r, c, &own, &pp))) {
                rc = 1;
                goto out;
            }
            double me = measured(img[v], img[V_REF], &pts, m);
            printf("%-10s %-7s %-46s %11.3g %11.3g %11.3g %7d\n", c->name, variant_name[v], name,
                   ps, pp, me, pts.term_count[m]);
            if (factor > 0 && v == V_POINTS && seen && pts.pixels[m] > 0) {
                double ratio = floored(pp) / floored(me);
                if (!(ratio <= factor && ratio >= 1.0 / factor)) {
                    printf("check: %s: predicted on the points %.3g, measured %.3g: not within "
                           "%gx\n",
                           c->name, pp, me, factor);
                    ++off;
                }
            }
        }
    }
    if (factor > 0)
        printf("\ncheck: %d material(s) predicted on the points more than %gx off the "
               "measurement\n",
               off, factor);
    rc = off ? 1 : 0;
out:
    for (int v = 0; v < V_COUNT; ++v) free(img[v]);
    for (int v = 0; v < made; ++v) scene_free(&sv[v]);
    scene_points_free(&pts);
    mat_table_free(&table);
    return rc;
}
