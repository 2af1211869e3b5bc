/* plan.c - the effect plan: before rendering, decide which work the scene needs (shadow rays
 * per light and receiver, tangent frames, Fresnel, layers, integration, ambient) and explain
 * why. The renderer does only what is planned (render.c). */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf_fit.h"
#include "light.h"
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
 * its direction; for a sphere or rectangle light (light.h), every segment from i's ball to
 * the light's ball (radius bound) lies within r_i + bound of the segment between the
 * centres. Object j can block only if its ball meets that capsule. An environment light
 * comes from every direction: any other object may block it. A convex object never blocks
 * light from itself: a lit point (N.wi > 0) sees the light through the supporting
 * half-space, which the solid does not enter; a mesh may shadow itself.
 *
 * Each (light, receiver) pair asks Embree once (accel_balls_capsule: the balls grown by the
 * capsule's radius class, the capsule's axis as a ray, the exact test on the candidates), so
 * the plan costs about n log n per light, not the n^2 of testing every pair. */
int plan_shadows(render_scene *rs)
{
    int n = rs->object_count, nl = rs->light_count;
    size_t pairs = (size_t)nl * (size_t)n;
    rs->shadow = calloc(pairs + 1, 1);
    if (!rs->shadow) return -1;
    for (int l = 0; l < nl; ++l) rs->lights[l].shadow_receivers = 0;
    if (pairs == 0) return 0;
    /* cls[l * n + i]: the radius class of the pair's capsule; INT_MIN: no query (a light
     * with no energy lights nothing, an environment needs none) */
    int *cls = malloc(pairs * sizeof *cls);
    if (!cls) return -1;
    int lo = 0, hi = 0, queries = 0;
    for (int l = 0; l < nl; ++l) {
        render_light *lt = &rs->lights[l];
        int dark = !(lt->e[0] > 0 || lt->e[1] > 0 || lt->e[2] > 0);
        for (int i = 0; i < n; ++i) {
            const geom_object *g = &rs->objects[i];
            size_t k = (size_t)l * n + i;
            cls[k] = INT_MIN;
            if (dark) continue;
            if (lt->kind == SCENE_LIGHT_ENVIRONMENT) {
                if (n > 1 || !g->convex) {
                    rs->shadow[k] = 1;
                    ++lt->shadow_receivers;
                }
                continue;
            }
            double r = g->bound + (SCENE_LIGHT_SAMPLED(lt->kind) ? lt->bound : 0.0);
            cls[k] = radius_class(r);
            if (queries == 0 || cls[k] < lo) lo = cls[k];
            if (queries == 0 || cls[k] > hi) hi = cls[k];
            ++queries;
        }
    }
    int status = 0;
    for (int c = lo; c <= hi && queries > 0 && !status; ++c) {
        int any = 0;
        for (size_t k = 0; k < pairs && !any; ++k) any = cls[k] == c;
        if (!any) continue;
        accel_balls *balls;
        if (accel_balls_build(rs->accel, ldexp(1.0, c), &balls)) {
            status = -1;
            break;
        }
        for (int l = 0; l < nl; ++l) {
            render_light *lt = &rs->lights[l];
            for (int i = 0; i < n; ++i) {
                size_t k = (size_t)l * n + i;
                if (cls[k] != c) continue;
                const geom_object *g = &rs->objects[i];
                double d[3], tmax = 1.0, r = g->bound;
                if (lt->kind == SCENE_LIGHT_DIRECTIONAL) {
                    memcpy(d, lt->direction, sizeof d);
                    tmax = INFINITY;
                } else {
                    for (int q = 0; q < 3; ++q) d[q] = lt->position[q] - g->center[q];
                    if (SCENE_LIGHT_SAMPLED(lt->kind)) r += lt->bound;
                }
                if (!accel_balls_capsule(balls, g->center, d, tmax, r, g->convex ? i : -1))
                    continue;
                rs->shadow[k] = 1;
                ++lt->shadow_receivers;
            }
        }
        accel_balls_release(balls);
    }
    free(cls);
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

/* Which lights are sampled, with which estimator (light.h); "off" for exact lights only. */
/* What a measured lobe reads and costs: its table, and the built-in cost of a lookup beside
 * the analytic pair it most often stands for. */
static void explain_measured(FILE *f, const scene_measured *sm)
{
    const measured_table *t = &sm->table;
    size_t cells = (size_t)t->n_theta_h * (size_t)t->n_theta_d * (size_t)t->n_phi_d;
    fprintf(f,
            "    measured table: %s (%s, %d x %d x %d cells, %.1f %% not measured, %.1f MB of "
            "floats): one trilinear lookup per evaluation (docs/MEASURED.md)\n",
            sm->path, sm->format, t->n_theta_h, t->n_theta_d, t->n_phi_d,
            100.0 * (double)t->unmeasured / (double)cells, 12.0 * (double)cells / 1e6);
    abrdf_costs c;
    abrdf_costs_builtin(&c);
    double lookup = abrdf_costs_get(&c, ABRDF_MEASURED),
           pair = abrdf_costs_get(&c, ABRDF_LAMBERT) + abrdf_costs_get(&c, ABRDF_DISNEY_SPECULAR);
    if (lookup > 0 && pair > 0)
        fprintf(f,
                "    cost: %.3g ns per evaluation (built-in cost table), %.2gx lambert + "
                "disney_specular's %.3g ns\n",
                lookup, lookup / pair, pair);
}

static void explain_sampling(const render_scene *rs, const render_options *opt, FILE *f)
{
    int count[SCENE_LIGHT_ENVIRONMENT + 1] = {0};
    for (int l = 0; l < rs->light_count; ++l) ++count[rs->lights[l].kind];
    if (!rs->sampled_lights) {
        fprintf(f, "light sampling: off - no area or environment light (point and directional "
                   "lights are exact: no samples, no noise)\n");
        return;
    }
    int ns = opt->light_samples > 1 ? opt->light_samples : 1;
    fprintf(f,
            "light sampling: on - %d sphere, %d rect, %d environment light(s) integrated by "
            "Monte Carlo, %d sample(s) per hit, light and strategy\n",
            count[SCENE_LIGHT_SPHERE], count[SCENE_LIGHT_RECT], count[SCENE_LIGHT_ENVIRONMENT], ns);
    if (count[SCENE_LIGHT_SPHERE])
        fprintf(f, "  sphere: uniform in the subtended cone (Shirley, Wang, Zimmerman 1996)\n");
    if (count[SCENE_LIGHT_RECT])
        fprintf(f, "  rect: uniform in the subtended spherical rectangle (Urena et al. 2013)\n");
    if (count[SCENE_LIGHT_ENVIRONMENT])
        fprintf(f, "  environment: per pixel by luminance x sin(theta), a 2-D piecewise-constant "
                   "distribution\n");
    static const char *const est[] = {
        "MIS - one light sample and one BRDF sample (abrdf_sample_prepared), power heuristic "
        "(Veach 1997)",
        "light - light samples only (--estimator light)",
        "brdf - BRDF samples only, those reaching the light count (--estimator brdf)"};
    int e =
        opt->estimator >= RENDER_EST_MIS && opt->estimator <= RENDER_EST_BRDF ? opt->estimator : 0;
    fprintf(f, "  estimator: %s; shaded in double per hit in both precisions\n", est[e]);
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
    explain_sampling(rs, opt, f);
    if (rs->textures) {
        int nt = 0;
        for (int i = 0; i < rs->material_count; ++i) nt += rs->materials[i].textured;
        fprintf(f,
                "textures: %d textured materials; a hit on one reads its maps (OpenImageIO "
                "TextureSystem: filtered, mip-mapped, the camera ray's footprint) and prepares "
                "its lobes for that hit; tile cache bounded by %g MB (--texture-cache, default "
                "%g)\n",
                nt, rs->texture_cache_mb, TEXTURE_CACHE_MB_DEFAULT);
    }
    fprintf(f, "shadows:\n");
    for (int l = 0; l < rs->light_count; ++l) {
        const render_light *lt = &rs->lights[l];
        fprintf(f, "  light %d (%s, line %d): ", l, light_kind_name(lt->kind), s->lights[l].line);
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
        if (m->tabulated)
            fprintf(f,
                    "    numerical integration: huang's R only; TT, TRT and TRRT+ read from its "
                    "table (%d theta, %d view azimuth and %d light azimuth nodes, %d shift "
                    "sets)\n",
                    opt->hair_tables->sizes[0], opt->hair_tables->sizes[1],
                    opt->hair_tables->sizes[2], opt->hair_tables->sizes[3]);
        else
            fprintf(f, "    numerical integration: %s\n",
                    (m->needs & ABRDF_NEEDS_INTEGRATION) ? "yes (slow lobe)" : "no");
        fprintf(f, "    ambient: %s\n", m->use_ambient ? "yes - ka * Ia > 0" : "no - ka * Ia = 0");
        if (s->materials[i].measured >= 0)
            explain_measured(f, &s->measured[s->materials[i].measured]);
    }
}
