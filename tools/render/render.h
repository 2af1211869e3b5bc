/* render.h - the built-in ray tracer: direct lighting of analytic primitives with the
 * library's BRDFs, and the effect plan that decides which work a scene needs.
 *
 * Camera model and pixel footprint (docs/RENDERER.md): pinhole at camera.position looking at
 * look_at; the image plane at distance 1 spans [-a*h, a*h] x [-h, h] with h = tan(fov/2),
 * a = width/height (square pixels). Pixel (i, j), column i from the left, row j from the
 * top, covers x in [i, i+1], y in [j, j+1] of the raster; raster (x, y) maps to the plane
 * point ((2x/W - 1) a h, (1 - 2y/H) h). A pixel is the box-filtered mean over its square:
 * spp = k*k samples at the centres of a k x k grid of strata (or jittered inside them).
 *
 * Radiance at a hit: L = ka*Ia + sum over lights of E_l * max(0, N.wi) * sum of lobes f_r,
 * E_l = color*intensity (directional) or color*intensity/d^2 (point), zero if occluded.
 *
 * PUBLIC FUNCTIONS
 *   render_prepare      scene -> ray-casting data + effect plan (fails on unresolvable materials)
 *   render_explain      print the effect plan and the reason for every decision
 *   render_image        render linear RGB into a caller's buffer (threads, deterministic)
 *   render_shade_hits   the radiance of a batch of camera-ray hits (direct light, both precisions)
 *   render_precision_name  "double" / "float" for --explain
 *   render_stats_print  print the work counters
 *   render_set_model    replace every material's models by one model (CLI --model)
 *   render_plan_ignore  do every effect everywhere (to measure the plan against)
 *   render_release      free what render_prepare allocated
 */
#ifndef ABRDF_RENDER_H
#define ABRDF_RENDER_H

#include <stdio.h>
#include "geom.h"

/* Work counters: what the renderer actually did. */
typedef struct render_stats {
    unsigned long long primary_rays;
    unsigned long long primary_tests; /* ray/object tests made by primary rays */
    unsigned long long hits;
    unsigned long long shadow_rays;         /* cast: the plan lists an occluder */
    unsigned long long shadow_rays_skipped; /* lit samples the plan proved unoccludable */
    unsigned long long occluder_tests;      /* ray/object tests made by shadow rays */
    unsigned long long tangent_frames;      /* frames built from a tangent field rule */
    unsigned long long brdf_evals;          /* lobe evaluations */
    unsigned long long fresnel_evals;       /* ... of lobes with a Fresnel term */
    unsigned long long layer_evals;         /* ... of layered lobes */
    unsigned long long integration_evals;   /* ... of lobes integrated numerically (hair) */
    unsigned long long ambient_terms;       /* hits that added ka*Ia */
} render_stats;

/* Which BRDF path shades (render_options.precision).
 *   RENDER_FLOAT   the fast path (default): the hits of a tile are gathered per material and
 *                  each lobe is evaluated over them with abrdf_eval_prepared_batch (float,
 *                  structure of arrays, the best instruction set of the CPU); rays, shadow
 *                  tests, light weights and pixel sums stay in double. Within NMSE 1e-8 of
 *                  the double reference for every model on the shipped scenes (test_render).
 *   RENDER_DOUBLE  the reference: every lobe per hit and light with abrdf_eval_prepared
 *                  (double, scalar). The port cross-checks compare against this path. */
typedef enum render_precision { RENDER_FLOAT = 0, RENDER_DOUBLE = 1 } render_precision;

/* A material as the renderer evaluates it, with its part of the plan. */
typedef struct render_material {
    int lobe_count;
    abrdf_model lobes[SCENE_MAX_LOBES];
    abrdf_prepared prepared[SCENE_MAX_LOBES]; /* each lobe validated and precomputed at load */
    unsigned lobe_needs[SCENE_MAX_LOBES];     /* ABRDF_NEEDS_* of each lobe (counters) */
    abrdf_params params;
    double ambient[3]; /* ka * Ia */
    int use_ambient;   /* ka * Ia is non-zero */
    int use_tangent;   /* some lobe needs a tangent frame (and is not isotropic here) */
    unsigned needs;    /* union of the lobes' ABRDF_NEEDS_* */
    int used;          /* some object uses it */
    int full;          /* render_plan_ignore: frames and ambient regardless of the plan */
} render_material;

typedef struct render_light {
    scene_light_kind kind;
    double position[3], direction[3];
    double e[3];          /* color * intensity */
    int shadow_receivers; /* objects for which some occluder is possible */
} render_light;

#define RENDER_OCC_LIST_MAX 64

typedef struct render_scene {
    const scene *src;
    int width, height;
    double eye[3], right[3], up[3], forward[3]; /* right, up scaled to the plane half-size */
    double eps;                                 /* ray offset, proportional to the scene's size */
    int object_count, light_count, material_count;
    geom_object *objects;
    render_material *materials;
    render_light *lights;
    /* Occluder candidates of (light l, receiver i): occ[occ_start[l*N+i] .. occ_start[l*N+i+1]);
     * a single -1 means every object (more than RENDER_OCC_LIST_MAX candidates). */
    int *occ_start, *occ;
    /* Primary visibility: the objects whose bounding sphere projects onto image row j are
     * vis[vis_start[j] .. vis_start[j+1]), in object order; object k covers columns
     * [vis_cols[2k], vis_cols[2k+1]]. */
    int *vis_start, *vis, *vis_cols;
    geom_origin *eye_origin; /* per object: what every camera ray shares against it */
    int full;                /* render_plan_ignore was applied */
} render_scene;

typedef struct render_options {
    int width, height; /* 0: the scene's resolution */
    int spp;           /* samples per pixel, a square k*k >= 1 */
    int jitter;        /* jitter inside the strata (deterministic hash) */
    int threads;       /* >= 1 */
    int progress;      /* draw a progress bar on stderr */
    int precision;     /* render_precision: RENDER_FLOAT (0, the default) or RENDER_DOUBLE */
    int free_brdf;     /* benchmarks only: do all the shading work but call no BRDF (f_r = 0),
                          so that time minus this render's is the BRDFs' (abrdf bench --render) */
} render_options;

/* A camera-ray hit to shade: object, point, unit normal and unit direction to the viewer. */
typedef struct render_hit {
    int obj;
    double p[3], n[3], wo[3];
} render_hit;

/* Work memory of render_shade_hits for up to `capacity` hits (one per thread). */
typedef struct render_shade_scratch render_shade_scratch;
render_shade_scratch *render_shade_scratch_new(const render_scene *rs, int capacity);
void render_shade_scratch_free(render_shade_scratch *sc);

int render_prepare(const scene *s, const render_options *opt, render_scene *rs, char *err,
                   size_t err_size);
void render_release(render_scene *rs);
/* Ignore the effect plan: every light shadow-tests every object, every material builds
 * tangent frames and adds the ambient term (`--full`, to measure what the plan saves).
 * Returns 0 or -1 (out of memory; rs unchanged). */
int render_plan_ignore(render_scene *rs);
void render_explain(const render_scene *rs, const render_options *opt, FILE *f);
/* rgb: width*height*3 floats, top row first. Returns 0, or -1 if spp is not a square
 * k*k >= 1 or no mutex can be made (nothing rendered). Threads that cannot start leave their rows to the caller's
 * thread, so the image is always complete. */
int render_image(const render_scene *rs, const render_options *opt, float *rgb,
                 render_stats *stats);
/* Radiance L (ambient + direct light of every light, shadows as planned) of count <= the
 * scratch's capacity hits, in the precision opt->precision asks for. Deterministic: the same
 * batch gives the same bits (render_image batches by image row, so the image does not depend
 * on the thread count). Separate from ray casting: whatever finds the hits can shade them. */
void render_shade_hits(const render_scene *rs, const render_options *opt, const render_hit *hits,
                       int count, double (*L)[3], render_shade_scratch *sc, render_stats *st);
const char *render_precision_name(int precision);
void render_stats_print(const render_stats *st, FILE *f);
/* Every material becomes the single model `model`, keeping parameter values it shares
 * with the old models (kd, ks, f0, r, n, ...). Returns 0 or -1 with a message. */
int render_set_model(scene *s, abrdf_model model, char *err, size_t err_size);

#endif
