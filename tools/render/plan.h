/* plan.h - the effect plan's steps, called by render_prepare (render.c); the plan is
 * described in docs/RENDERER.md and printed by render_explain (plan.c). */
#ifndef ABRDF_PLAN_H
#define ABRDF_PLAN_H

#include "render.h"

/* Which (light, receiver) pairs need shadow rays: rs->shadow, lights' shadow_receivers
 * (needs rs->accel). 0 or -1 (no memory, Embree error). */
int plan_shadows(render_scene *rs);
/* Tangent frames, Fresnel/layer/integration needs and the ambient term of a material. */
void plan_material(render_material *m, const double ia[3], const double ka[3]);

#endif
