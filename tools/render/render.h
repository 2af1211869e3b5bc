/* render.h - the built-in ray tracer: direct lighting of analytic primitives and triangle
 * meshes with the library's BRDFs, visibility through one Embree scene (accel.h), and the
 * effect plan that decides which work a scene needs.
 *
 * Camera model and pixel footprint (docs/RENDERER.md): pinhole at camera.position looking at
 * look_at; the image plane at distance 1 spans [-a*h, a*h] x [-h, h] with h = tan(fov/2),
 * a = width/height (square pixels). Pixel (i, j), column i from the left, row j from the
 * top, covers x in [i, i+1], y in [j, j+1] of the raster; raster (x, y) maps to the plane
 * point ((2x/W - 1) a h, (1 - 2y/H) h). A pixel is the box-filtered mean over its square:
 * spp = k*k samples at the centres of a k x k grid of strata (or jittered inside them).
 *
 * Radiance at a hit: L = ka*Ia + sum over lights of E_l * max(0, N.wi) * sum of lobes f_r,
 * E_l = color*intensity (directional) or color*intensity/d^2 (point), zero if occluded; plus,
 * for each sphere, rectangle or environment light, the Monte Carlo estimate of
 * integral L_e(wi) f_r max(0, N.wi) dwi that render_options.estimator names (light.h).
 *
 * PUBLIC FUNCTIONS
 *   render_prepare      scene -> ray-casting data + effect plan (fails on unresolvable materials)
 *   render_explain      print the effect plan and the reason for every decision
 *   render_image        render linear RGB into a caller's buffer (threads, deterministic)
 *   render_shade_hits   the radiance of a batch of camera-ray hits (direct light, both precisions)
 *   render_hit_light    one point or directional light as a hit sees it (direction, irradiance)
 *   render_hit_tangent  the tangent of a hit by its object's tangent rule
 *   render_hit_normal_map  a hit's shading normal under its material's normal map
 *   render_precision_name  "double" / "float" for --explain
 *   render_stats_print  print the work counters
 *   render_textures_print  the texture system's statistics (nothing without textures)
 *   render_texture_error   a texture that failed during the render (a truncated file)
 *   render_plan_ignore  do every effect everywhere (to measure the plan against)
 *   render_release      free what render_prepare allocated
 *
 * Textures (`pbr` materials with maps, scene.h; docs/GLTF.md, "Textures"): render_prepare
 * opens every map of a used material in one texture system (texture.h), whose cache holds
 * at most render_options.texture_cache_mb; each thread looks up through its own scratch. At
 * a hit on a textured material the maps are read at the hit's texture coordinates with the
 * derivatives of the camera ray's footprint, the material's parameters are made from its
 * factors times the texels (scene_pbr_params) and its lobes prepared for that hit; every
 * light is then evaluated with them in the precision asked for (the float path evaluates
 * the hit's lights as one batch per lobe instead of joining the tile's sorted batches).
 */
#ifndef ABRDF_RENDER_H
#define ABRDF_RENDER_H

#include <stdio.h>
#include "accel.h"
#include "envmap.h"
#include "geom.h"
#include "hair_store.h"
#include "texture.h"

/* Work counters: what the renderer actually did. A "test" is one exact double-precision
 * intersection on a candidate Embree's BVH offers (accel.h): an analytic object's
 * intersector, or the refinement of a mesh triangle Embree's float ray hit. */
typedef struct render_stats {
    unsigned long long primary_rays;
    unsigned long long primary_tests; /* exact tests made by primary rays */
    unsigned long long hits;
    unsigned long long shadow_rays;         /* cast: the plan says something may block */
    unsigned long long shadow_rays_skipped; /* lit samples the plan proved unoccludable */
    unsigned long long occluder_tests;      /* exact tests made by shadow rays */
    unsigned long long tangent_frames;      /* frames built from a tangent field rule */
    unsigned long long brdf_evals;          /* lobe evaluations */
    unsigned long long fresnel_evals;       /* ... of lobes with a Fresnel term */
    unsigned long long layer_evals;         /* ... of layered lobes */
    unsigned long long integration_evals;   /* ... of lobes integrated numerically (hair) */
    unsigned long long ambient_terms;       /* hits that added ka*Ia */
    unsigned long long light_samples;       /* directions drawn on sampled lights */
    unsigned long long brdf_samples;        /* directions drawn from the BRDFs for them */
    unsigned long long textured_hits;       /* hits whose lobes were prepared from texels */
    unsigned long long texture_lookups;     /* filtered lookups made for them */
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
    int tabulated; /* a huang lobe is prepared on its table (render_options.hair_tables) */
    unsigned lobe_needs[SCENE_MAX_LOBES]; /* ABRDF_NEEDS_* of each lobe (counters) */
    abrdf_params params;
    double ambient[3]; /* ka * Ia */
    int use_ambient;   /* ka * Ia is non-zero */
    int use_tangent;   /* some lobe needs a tangent frame (and is not isotropic here) */
    unsigned needs;    /* union of the lobes' ABRDF_NEEDS_* */
    int used;          /* some object uses it */
    int full;          /* render_plan_ignore: frames and ambient regardless of the plan */
    /* Textured `pbr` materials: each map's file (NULL: no map), resolved at prepare. */
    int textured;
    texture_file *maps[SCENE_MAP_COUNT];
    int map_channels[SCENE_MAP_COUNT]; /* channels the map's file holds */
} render_material;

typedef struct render_light {
    scene_light_kind kind;
    double position[3], direction[3]; /* point / sphere / rectangle: position (centre) */
    double e[3];          /* color * intensity: E (point, directional) or radiance (sampled) */
    int shadow_receivers; /* objects for which some occluder is possible */
    /* Sampled lights (light.h): sphere, rectangle, environment. */
    double radius;               /* sphere */
    double edge_u[3], edge_v[3]; /* rectangle: its full edges */
    double normal[3];            /* rectangle: unit edge_u x edge_v, the side it lights */
    double bound;                /* sphere, rectangle: a ball about position holding it */
    const envmap *env;           /* environment: the map (owned by the scene) */
} render_light;

typedef struct render_scene {
    const scene *src;
    int width, height;
    double eye[3], right[3], up[3], forward[3]; /* right, up scaled to the plane half-size */
    double eps;                                 /* ray offset, proportional to the scene's size */
    int object_count, light_count, material_count;
    long long triangle_count;
    geom_object *objects;
    render_material *materials;
    render_light *lights;
    accel *accel; /* every object in one Embree scene: camera and shadow rays */
    /* shadow[l * object_count + i]: light l needs shadow rays at object i (plan_shadows) */
    unsigned char *shadow;
    int full;                 /* render_plan_ignore was applied */
    int sampled_lights;       /* lights with SCENE_LIGHT_SAMPLED kinds (light.h) */
    texture_system *textures; /* the maps of textured materials; NULL if none is used */
    double texture_cache_mb;  /* its cache bound */
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
    int estimator;     /* render_estimator: how sampled (area, environment) lights are estimated */
    int light_samples; /* per hit, sampled light and strategy; < 1 means 1 */
    double texture_cache_mb; /* textures' cache bound, MB; 0: TEXTURE_CACHE_MB_DEFAULT */
    /* Not NULL: every huang lobe of a material without texture maps has its residual
     * tabulated at the store's sizes (hair_store_get: a table the store holds already, e.g.
     * the one the budget mode predicted against, else the cache's, else built over the
     * store's threads) and is prepared on it (abrdf_prepare_huang_table); the tables stay the
     * store's. NULL: huang integrates per call. */
    hair_store *hair_tables;
} render_options;

/* Estimators of the sampled lights (sphere, rectangle, environment; light.h). Point and
 * directional lights are exact and never sampled, whatever this says.
 *   RENDER_EST_MIS    one light sample and one BRDF sample per hit and light, combined by
 *                     the power heuristic (Veach 1997): the default
 *   RENDER_EST_LIGHT  light samples only (solid angle / luminance)
 *   RENDER_EST_BRDF   BRDF samples only (abrdf_sample_prepared), counting those that reach
 *                     the light */
typedef enum render_estimator {
    RENDER_EST_MIS = 0,
    RENDER_EST_LIGHT = 1,
    RENDER_EST_BRDF = 2
} render_estimator;

/* A camera-ray hit to shade: object (and mesh triangle, -1 on analytic objects), point,
 * unit shading normal and unit direction to the viewer; on a mesh, the barycentric weights
 * of the triangle's corners 1 and 2 (texture coordinates). The hit must be a camera ray's:
 * a textured material's lookups take their footprint from the camera (render.c). */
typedef struct render_hit {
    int obj, triangle;
    double p[3], n[3], wo[3];
    double b1, b2;
} render_hit;

/* Work memory of render_shade_hits for up to `capacity` hits (one per thread). */
typedef struct render_shade_scratch render_shade_scratch;
render_shade_scratch *render_shade_scratch_new(const render_scene *rs, int capacity);
void render_shade_scratch_free(render_shade_scratch *sc);

/* Builds the Embree scene with opt->threads threads (0: every core). Opens the textures of
 * used materials: a file that cannot be read, a channel it lacks, or a textured material on
 * an object without texture coordinates fails here with one line, before any work. */
int render_prepare(const scene *s, const render_options *opt, render_scene *rs, char *err,
                   size_t err_size);
void render_release(render_scene *rs);
/* Ignore the effect plan: every lit point casts a shadow ray that tests every object (its
 * own too), every material builds tangent frames and adds the ambient term (`--full`, to
 * measure what the plan saves). Returns 0. */
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
/* Point or directional light l as render_shade_hits lights camera-ray hit h: 1 with the unit
 * direction wi toward it and e, its irradiance on a surface facing it (E, over d^2 for a
 * point light; the cosine left out), if it lights h (in front, not shadowed as the plan
 * says); 0 otherwise and for a sampled light. */
int render_hit_light(const render_scene *rs, int l, const render_hit *h, double wi[3], double e[3],
                     render_stats *st);
/* The tangent of hit h by its object's tangent rule (not orthogonalised against h->n). */
void render_hit_tangent(const render_scene *rs, const render_hit *h, double t[3]);
/* Camera-ray hit h with h->n replaced by the normal render_shade_hits shades it with under
 * its material's normal map: the same lookup (texture coordinates, the footprint of
 * opt->spp samples per pixel, the map's transform and scale). th: the caller's texture
 * thread (texture_thread_new(rs->textures)). 1, or 0 (h unchanged) if the material has no
 * normal map. */
int render_hit_normal_map(const render_scene *rs, const render_options *opt, texture_thread *th,
                          render_hit *h, render_stats *st);
const char *render_precision_name(int precision);
void render_stats_print(const render_stats *st, FILE *f);
/* The texture cache's bound and use (OpenImageIO's statistics: peak and current tile memory,
 * peak tiles, lookups, bytes read); prints nothing for a scene without textures. */
void render_textures_print(const render_scene *rs, FILE *f);
/* 0, or -1 with "FILE: problem" if a texture lookup failed during render_image (its texels
 * read as 0): the image is then not what the scene describes. */
int render_texture_error(const render_scene *rs, char *err, size_t err_size);

#endif
