/* light.h - the sampled lights of the built-in renderer: sphere and rectangle area lights of
 * uniform radiance, sampled by solid angle, and the environment light (a lat-long map,
 * sampled by luminance: envmap.h). Each is estimated per hit by light sampling, BRDF sampling
 * (abrdf_sample_prepared) or both combined by multiple importance sampling, as
 * render_options.estimator says (docs/RENDERER.md, "Area and environment lights"):
 *
 *   light sample  wi ~ p_L:  f(wi, wo) cos_i L_e(wi) V / p_L(wi)  * w_L
 *   BRDF sample   wi ~ p_B:  f(wi, wo) cos_i L_e(wi) V / p_B(wi)  * w_B   (if wi reaches it)
 *   MIS (power heuristic, E. Veach, "Robust Monte Carlo methods for light transport
 *   simulation", PhD thesis, Stanford 1997, Ch. 9): w_L = p_L^2 / (p_L^2 + p_B^2),
 *   w_B = p_B^2 / (p_L^2 + p_B^2); light-only: w_L = 1, no BRDF sample; BRDF-only: w_B = 1.
 *
 * Samplers:
 *   sphere     uniform in the cone the sphere subtends, p_L = 1 / (2 pi (1 - cos theta_max))
 *              (P. Shirley, C. Wang, K. Zimmerman, "Monte Carlo techniques for direct
 *              lighting calculations", ACM TOG 15(1), 1996)
 *   rectangle  uniform in the solid angle S it subtends, p_L = 1 / S, by the area-preserving
 *              parametrisation of spherical rectangles (C. Urena, M. Fajardo, A. King, "An
 *              area-preserving parametrization for spherical rectangles", Computer Graphics
 *              Forum 32(4), 2013); below S = LIGHT_RECT_MIN_SOLID_ANGLE (a far or
 *              tiny light, where S's formula cancels) uniform by area, p_L = d^2 / (A cos_l)
 *   environment  envmap_sample (luminance x sin(theta) per pixel)
 * The random numbers of a hit are a hash of its point and view direction, so that shading
 * stays a pure function of the hit (render_shade_hits' contract).
 *
 * PUBLIC FUNCTIONS
 *   light_setup          a scene light's sampling data (render_prepare)
 *   light_sample_dir     a direction toward a light from a point, with L_e, distance, p_L
 *   light_hit            where a ray from a point meets a light: L_e, distance, p_L
 *   light_shade_sampled  the sampled lights' part of a hit's radiance
 *   light_kind_name      "point", "directional", "sphere", "rect", "environment"
 */
#ifndef ABRDF_LIGHT_H
#define ABRDF_LIGHT_H

#include "render.h"

/* sr: rectangles subtending less are sampled by area (see above). */
#define LIGHT_RECT_MIN_SOLID_ANGLE 1e-6

typedef struct light_sample {
    double wi[3]; /* unit, from the point toward the light */
    double dist;  /* distance along wi to the light (INFINITY: the environment) */
    double le[3]; /* radiance arriving along -wi */
    double pdf;   /* p_L(wi), solid angle; 0: no sample */
} light_sample;

void light_setup(const scene_light *sl, render_light *rl);
/* 1 and *s for a sample from u1, u2 in [0, 1); 0 if the light cannot light o (inside a
 * sphere, behind a rectangle, a black map). */
int light_sample_dir(const render_light *lt, const double o[3], double u1, double u2,
                     light_sample *s);
/* 1 and *s (wi copied) if the ray o + t wi, t > 0, reaches the light; p_L is light_sample_dir's
 * density for that direction. */
int light_hit(const render_light *lt, const double o[3], const double wi[3], light_sample *s);

/* render.c's visibility test (whatever it is): 1 if the segment o + t d, t in (0, tmax), is
 * blocked for light l seen from hit h (counting its work in st). */
typedef int (*light_blocked_fn)(const render_scene *rs, int l, const render_hit *h,
                                const double o[3], const double d[3], double tmax,
                                render_stats *st);

/* Add to L the sampled lights' radiance at hit h (seen from the front; o the shadow-ray
 * origin; frame the material's tangent frame, or NULL to build one from the normal). */
void light_shade_sampled(const render_scene *rs, const render_options *opt,
                         const render_material *m, const render_hit *h, const double o[3],
                         const abrdf_frame *frame, light_blocked_fn blocked, double L[3],
                         render_stats *st);

const char *light_kind_name(scene_light_kind kind);

#endif
