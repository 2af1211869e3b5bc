/* plan.c - the effect plan: before rendering, decide which work the scene needs (shadow
 * rays per light and receiver, tangent frames, Fresnel, layers, integration, ambient) and
 * explain why. The renderer does only what is planned (render.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "render.h"

static void sub3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[0] - b[0], o[1] = a[1] - b[1], o[2] = a[2] - b[2];
}

/* Distance from point c to the segment a + s (b - a), s in [0, 1] (or the ray s >= 0 with
 * direction d if b is NULL). */
static double dist_to_segment(const double c[3], const double a[3], const double *b, const double *d)
{
    double ab[3], ac[3];
    if (b) sub3(b, a, ab);
    else memcpy(ab, d, sizeof ab);
    sub3(c, a, ac);
    double l2 = geom_dot(ab, ab);
    double s = l2 > 0 ? geom_dot(ac, ab) / l2 : 0;
    if (s < 0) s = 0;
    if (b && s > 1) s = 1;
    double q[3] = {ac[0] - s * ab[0], ac[1] - s * ab[1], ac[2] - s * ab[2]};
    return sqrt(geom_dot(q, q));
}

/* Can object j block light l from any point of object i? Conservative: every segment from
 * a point of i's bounding ball to a point light lies in the capsule of radius r_i around the
 * segment (c_i, light); for a directional light, the half-infinite capsule along the
 * direction. j can block only if its ball meets that capsule. A convex object never blocks
 * light from itself: a lit point (N.wi > 0) sees the light through the supporting
 * half-space, which the solid does not enter. */
static int may_occlude(const render_scene *rs, const render_light *l, int i, int j)
{
    const geom_object *a = &rs->objects[i], *b = &rs->objects[j];
    if (i == j) return !a->convex;
    double d = l->kind == SCENE_LIGHT_POINT ? dist_to_segment(b->center, a->center, l->position, NULL)
                                            : dist_to_segment(b->center, a->center, NULL, l->direction);
    return d <= a->bound + b->bound;
}

int abrdf__render_plan_shadows(render_scene *rs);

/* Build occ_start/occ; returns 0 or -1 on allocation failure. */
int abrdf__render_plan_shadows(render_scene *rs)
{
    int n = rs->object_count, nl = rs->light_count;
    rs->occ_start = calloc((size_t)nl * (size_t)n + 1, sizeof *rs->occ_start);
    if (!rs->occ_start) return -1;
    size_t cap = 16, len = 0;
    rs->occ = malloc(cap * sizeof *rs->occ);
    if (!rs->occ) return -1;
    for (int l = 0; l < nl; ++l) {
        render_light *lt = &rs->lights[l];
        lt->shadow_receivers = 0;
        for (int i = 0; i < n; ++i) {
            rs->occ_start[l * n + i] = (int)len;
            int any = 0;
            /* A light with no energy lights nothing; nothing to shadow. */
            int dark = !(lt->e[0] > 0 || lt->e[1] > 0 || lt->e[2] > 0);
            size_t first = len;
            for (int j = 0; j < n && !dark; ++j) {
                if (!may_occlude(rs, lt, i, j)) continue;
                /* A long list is no cheaper than testing everything: store "all" (-1) and
                 * keep the plan's memory linear in lights x objects. */
                if (len - first == RENDER_OCC_LIST_MAX) {
                    len = first;
                    rs->occ[len++] = -1;
                    any = 1;
                    break;
                }
                if (len == cap) {
                    int *g = realloc(rs->occ, 2 * cap * sizeof *g);
                    if (!g) return -1;
                    rs->occ = g;
                    cap *= 2;
                }
                rs->occ[len++] = j;
                any = 1;
            }
            lt->shadow_receivers += any;
        }
    }
    rs->occ_start[nl * n] = (int)len;
    return 0;
}

/* Material part of the plan. */
void abrdf__render_plan_material(render_material *m, const double ia[3], const double ka[3]);

void abrdf__render_plan_material(render_material *m, const double ia[3], const double ka[3])
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
    fprintf(f, "effect plan: %d objects, %d lights, %d materials, %dx%d, %d spp, %d threads\n",
            n, rs->light_count, rs->material_count, rs->width, rs->height, opt->spp, opt->threads);
    fprintf(f, "shadows:\n");
    for (int l = 0; l < rs->light_count; ++l) {
        const render_light *lt = &rs->lights[l];
        int pairs = 0;
        for (int i = 0; i < n; ++i) {
            int a = rs->occ_start[l * n + i], b = rs->occ_start[l * n + i + 1];
            pairs += b - a == 1 && rs->occ[a] < 0 ? n : b - a;
        }
        fprintf(f, "  light %d (%s, line %d): ", l, lt->kind == SCENE_LIGHT_POINT ? "point" : "directional",
                s->lights[l].line);
        if (!(lt->e[0] > 0 || lt->e[1] > 0 || lt->e[2] > 0))
            fprintf(f, "OFF - zero intensity, lights nothing\n");
        else if (lt->shadow_receivers == 0)
            fprintf(f, "no shadow rays - no object can block it from any object (%s)\n",
                    n == 1 ? "a single convex solid cannot shadow itself"
                           : "bounding capsules toward the light are disjoint from every other object");
        else
            fprintf(f, "shadow rays for %d of %d receivers, %d occluder candidates in all "
                       "(bounding capsule toward the light meets another object)\n",
                    lt->shadow_receivers, n, pairs);
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
                : (m->needs & ABRDF_NEEDS_TANGENT) ? "no - anisotropic = 0 makes the lobe isotropic"
                                                   : "no - every lobe is isotropic (local frame from N and the view)");
        fprintf(f, "    fresnel: %s\n", (m->needs & ABRDF_NEEDS_FRESNEL) ? "yes - evaluated inside the lobe"
                                                                         : "no - no lobe has a Fresnel term");
        fprintf(f, "    layers: %s\n", (m->needs & ABRDF_NEEDS_LAYERS) ? "yes - layer stack evaluated" : "no");
        fprintf(f, "    numerical integration: %s\n", (m->needs & ABRDF_NEEDS_INTEGRATION) ? "yes (slow lobe)" : "no");
        fprintf(f, "    ambient: %s\n", m->use_ambient ? "yes - ka * Ia > 0" : "no - ka * Ia = 0");
    }
}
