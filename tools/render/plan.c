/* plan.c - the effect plan: before rendering, decide which work the scene needs (shadow rays
 * per light and receiver, tangent frames, Fresnel, layers, integration, ambient) and explain
 * why. The renderer does only what is planned (render.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plan.h"

/* The radius class of a bounding ball: the smallest power of two >= bound (bounds below
 * 2^-40 share one class). Receivers of one class query one ball scene grown by that power. */
static int radius_class(double bound)
{
    int e;
    double m = frexp(bound, &e); /* bound = m 2^e, m in [0.5, 1) */
    if (m == 0.5) --e;           /* an exact power of two is its own class */
    return e < -40 ? -40 : e;
}

/* Can some object block light l from some point of object i? Conservative: every segment
 * from a point of i's bounding ball to a point light lies in the capsule of radius r_i
 * around the segment (c_i, light); for a directional light, the half-infinite capsule along
 * its direction. Object j can block only if its ball meets that capsule. A convex object
 * never blocks light from itself: a lit point (N.wi > 0) sees the light through the
 * supporting half-space, which the solid does not enter; a mesh may shadow itself.
 *
 * Each receiver asks Embree once (accel_balls_capsule: the balls grown by the receiver's
 * radius class, the capsule's axis as a ray, the exact test on the candidates), so the plan
 * costs about n log n, not the n^2 of testing every pair. */
int plan_shadows(render_scene *rs)
{
    int n = rs->object_count, nl = rs->light_count;
    rs->shadow = calloc((size_t)nl * (size_t)n + 1, 1);
    if (!rs->shadow) return -1;
    for (int l = 0; l < nl; ++l) rs->lights[l].shadow_receivers = 0;
    int lit = 0; /* a light with no energy lights nothing: nothing to shadow */
    for (int l = 0; l < nl; ++l) {
        const double *e = rs->lights[l].e;
        lit += e[0] > 0 || e[1] > 0 || e[2] > 0;
    }
    if (!lit || n == 0) return 0;
    int *cls = malloc((size_t)n * sizeof *cls), *order = malloc((size_t)n * sizeof *order);
    if (!cls || !order) {
        free(cls), free(order);
        return -1;
    }
    int lo = 0, hi = 0;
    for (int i = 0; i < n; ++i) {
        cls[i] = radius_class(rs->objects[i].bound);
        if (i == 0 || cls[i] < lo) lo = cls[i];
        if (i == 0 || cls[i] > hi) hi = cls[i];
    }
    int status = 0;
    for (int c = lo; c <= hi && !status; ++c) {
        int m = 0;
        for (int i = 0; i < n; ++i)
            if (cls[i] == c) order[m++] = i;
        if (m == 0) continue;
        accel_balls *balls;
        if (accel_balls_build(rs->accel, ldexp(1.0, c), &balls)) {
            status = -1;
            break;
        }
        for (int l = 0; l < nl; ++l) {
            render_light *lt = &rs->lights[l];
            if (!(lt->e[0] > 0 || lt->e[1] > 0 || lt->e[2] > 0)) continue;
            for (int k = 0; k < m; ++k) {
                int i = order[k];
                const geom_object *g = &rs->objects[i];
                double d[3], tmax = 1.0;
                if (lt->kind == SCENE_LIGHT_POINT) {
                    for (int q = 0; q < 3; ++q) d[q] = lt->position[q] - g->center[q];
                } else {
                    memcpy(d, lt->direction, sizeof d);
                    tmax = INFINITY;
                }
                if (!accel_balls_capsule(balls, g->center, d, tmax, g->bound, g->convex ? i : -1))
                    continue;
                rs->shadow[(size_t)l * n + i] = 1;
                ++lt->shadow_receivers;
            }
        }
        accel_balls_release(balls);
    }
    free(cls), free(order);
    return status;
}

/* Material part of the plan. */
void plan_material(render_material *m, const double ia[3], const double ka[3])
{
    m->needs = 0;
    m->use_tangent = 0;
    for (int k = 0; k < m->lobe_count; ++k) {
        const abrdf_model_info *mi = abrdf_model_get(m->lobes[k]);
        m->needs |= mi->needs;
        /* The anisotropic lobe at anisotropic = 0 has alpha_x = alpha_y: rotation invariant
         * about N, so the tangent cannot change its value. */
        int iso = m->lobes[k] == ABRDF_DISNEY_SPECULAR_ANISO && m->params.anisotropic == 0;
        if ((mi->needs & ABRDF_NEEDS_TANGENT) && !iso) m->use_tangent = 1;
    }
    m->use_ambient = 0;
    for (int c = 0; c < 3; ++c) {
        m->ambient[c] = ka[c] * ia[c];
        if (m->ambient[c] > 0) m->use_ambient = 1;
    }
}

static void lobe_names(const render_material *m, char *buf, size_t size)
{
    buf[0] = '\0';
    for (int k = 0; k < m->lobe_count; ++k) {
        size_t len = strlen(buf);
        snprintf(buf + len, size - len, "%s%s", k ? " + " : "", abrdf_model_get(m->lobes[k])->name);
    }
}

void render_explain(const render_scene *rs, const render_options *opt, FILE *f)
{
    const scene *s = rs->src;
    int n = rs->object_count;
    fprintf(f, "effect plan: %d objects, %d lights, %d materials, %dx%d, %d spp, %d threads\n", n,
            rs->light_count, rs->material_count, rs->width, rs->height, opt->spp, opt->threads);
    if (rs->full) {
        fprintf(f, "--full: the plan below is ignored; every lit point casts a shadow ray that "
                   "tests every object, every material builds tangent frames and adds the "
                   "ambient term\n");
    }
    if (opt->precision == RENDER_DOUBLE)
        fprintf(f, "shading: double - the scalar reference, every lobe per hit and light "
                   "(abrdf_eval_prepared)\n");
    else
        fprintf(f, "shading: float - the fast path, each material's lobes over a tile's lit hits "
                   "(abrdf_eval_prepared_batch); within NMSE 1e-8 of --precision double\n");
    fprintf(f,
            "primary rays: one Embree BVH over the %d objects (%lld triangles); a ray runs the "
            "exact intersector only on what its boxes let through\n",
            n, rs->triangle_count);
    fprintf(f, "shadows:\n");
    for (int l = 0; l < rs->light_count; ++l) {
        const render_light *lt = &rs->lights[l];
        fprintf(f, "  light %d (%s, line %d): ", l,
                lt->kind == SCENE_LIGHT_POINT ? "point" : "directional", s->lights[l].line);
        if (!(lt->e[0] > 0 || lt->e[1] > 0 || lt->e[2] > 0))
            fprintf(f, "OFF - zero intensity, lights nothing\n");
        else if (rs->full)
            fprintf(f, "shadow rays everywhere (--full)\n");
        else if (lt->shadow_receivers == 0)
            fprintf(
                f, "no shadow rays - no object can block it from any object (%s)\n",
                n == 1 ? "a single convex solid cannot shadow itself"
                       : "bounding capsules toward the light are disjoint from every other object");
        else
            fprintf(f,
                    "shadow rays for %d of %d receivers (bounding capsule toward the light meets "
                    "another object, or a mesh may shadow itself); an occlusion query each\n",
                    lt->shadow_receivers, n);
    }
    fprintf(f, "materials:\n");
    for (int i = 0; i < rs->material_count; ++i) {
        const render_material *m = &rs->materials[i];
        char names[128];
        lobe_names(m, names, sizeof names);
        fprintf(f, "  %s (line %d): %s%s\n", s->materials[i].name, s->materials[i].line, names,
                m->used ? "" : "  [unused by any object: never evaluated]");
        if (!m->used) continue;
        fprintf(f, "    tangent frames: %s\n",
                m->use_tangent ? "yes - an anisotropic/fibre lobe reads T and B"
                : (m->needs & ABRDF_NEEDS_TANGENT)
                    ? "no - anisotropic = 0 makes the lobe isotropic"
                    : "no - every lobe is isotropic (local frame from N and the view)");
        fprintf(f, "    fresnel: %s\n",
                (m->needs & ABRDF_NEEDS_FRESNEL) ? "yes - evaluated inside the lobe"
                                                 : "no - no lobe has a Fresnel term");
        fprintf(f, "    layers: %s\n",
                (m->needs & ABRDF_NEEDS_LAYERS) ? "yes - layer stack evaluated" : "no");
        fprintf(f, "    numerical integration: %s\n",
                (m->needs & ABRDF_NEEDS_INTEGRATION) ? "yes (slow lobe)" : "no");
        fprintf(f, "    ambient: %s\n", m->use_ambient ? "yes - ka * Ia > 0" : "no - ka * Ia = 0");
    }
}
