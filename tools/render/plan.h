/* plan.h - the effect plan's steps, called by render_prepare (render.c); the plan is
 * described in docs/RENDERER.md and printed by render_explain (plan.c). */
#ifndef ABRDF_PLAN_H
#define ABRDF_PLAN_H

#include "render.h"

/* Occluder candidates per (light, receiver): rs->occ_start, rs->occ. 0 or -1 (no memory). */
int plan_shadows(render_scene *rs);
/* Objects camera rays can hit, per image row and column range; cull = 0 lists every object
 * for every pixel. 0 or -1 (no memory). */
int plan_visibility(render_scene *rs, int cull);
/* Tangent frames, Fresnel/layer/integration needs and the ambient term of a material. */
void plan_material(render_material *m, const double ia[3], const double ka[3]);

#endif
