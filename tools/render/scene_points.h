/* scene_points.h - a scene's own shading points, per material, for the budget mode's
 * prediction (docs/SELECTION.md, "2. The prediction"): a cheap pass traces the camera's
 * pixels and records, at each visible hit, one term per point or directional light that
 * lights it (normal, tangent, wi, wo, irradiance: abrdf_view_term, abrdf_fit.h), grouped by
 * pixel as the render's box filter groups its samples. The materials need not be resolved:
 * only geometry, normal maps (the normal a term carries is the one the render shades),
 * lights and shadows are traced, none of which depends on the BRDFs.
 *
 * PUBLIC FUNCTIONS
 *   scene_points_trace  trace the pass (every material of the scene)
 *   scene_points_view   one material's terms as an abrdf_view (0 if it has none)
 *   scene_points_free   release what the pass allocated
 */
#ifndef ABRDF_SCENE_POINTS_H
#define ABRDF_SCENE_POINTS_H

#include <stddef.h>
#include "abrdf_fit.h"
#include "scene.h"

/* Terms kept per material at most: a material covering more pixels is sampled on every
 * k^2-th of its pixels in scan order (its first included), k the smallest that keeps its terms
 * (ceil(pixels / k^2) x spp x lights) under this, or 1 pixel. 8192 terms cost about what the sphere's 24 x 24 grids under four lights cost
 * a numerically integrated lobe (hair, ~1 ms an evaluation). */
#define SCENE_POINTS_MAX_TERMS 8192

typedef struct scene_points {
    int material_count;
    int width, height;       /* the pass's raster: the scene's resolution */
    int spp;                 /* camera samples per pixel of the pass, a square */
    int *pixel_material;     /* width x height, top row first: the material at each pixel's
                                centre, -1 for the background */
    int *pixels;             /* per material: pixels whose centre sees it */
    int *stride;             /* per material: the k of SCENE_POINTS_MAX_TERMS */
    int *kept;               /* per material: pixels sampled, ceil(pixels / stride^2) */
    int *hits;               /* per material: of those, pixels a camera sample of which sees
                                its front */
    int *samples;            /* per material: pixels that gave terms */
    int *term_count;         /* per material */
    abrdf_view_term **terms; /* per material: term_count terms (NULL: none) */
    int sampled_lights;      /* sphere, rectangle and environment lights: left out */
    double seconds;          /* wall time of the pass */
} scene_points;

/* Trace s's camera at its resolution: the material of every pixel centre, then, for each
 * material, in every stride^2-th pixel whose centre sees it, the spp camera samples
 * (strata centres) that hit it, with one term per lighting point or directional light, its
 * irradiance divided by spp (the pixel's box filter); a hit on a material with a normal map
 * takes the mapped normal (render_hit_normal_map, the footprint of spp samples per pixel).
 * spp must be a square, as render_image asks. Returns 0, or -1 with one line in err (out is
 * then empty): a non-square spp, a scene render_prepare refuses, a normal map that cannot be
 * read. */
int scene_points_trace(const scene *s, int spp, scene_points *out, char *err, size_t err_size);

/* v (initialised here) as material m's terms: 1, or 0 if m has none (v is then the default
 * sphere). */
int scene_points_view(const scene_points *p, int m, abrdf_view *v);

void scene_points_free(scene_points *p);

#endif
