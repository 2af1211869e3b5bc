/* plan.c - the effect plan: before rendering, decide which work the scene needs (objects
 * per pixel, shadow rays per light and receiver, tangent frames, Fresnel, layers,
 * integration, ambient) and explain why. The renderer does only what is planned (render.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plan.h"

static void sub3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[0] - b[0], o[1] = a[1] - b[1], o[2] = a[2] - b[2];
}

/* Distance from point c to the segment a + s (b - a), s in [0, 1] (or the ray s >= 0 with
 * direction d if b is NULL). */
static double dist_to_segment(const double c[3], const double a[3], const double *b,
                              const double *d)
{
    double ab[3], ac[3];
    if (b)
        sub3(b, a, ab);
    else
        memcpy(ab, d, sizeof ab);
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
    double d = l->kind == SCENE_LIGHT_POINT
                   ? dist_to_segment(b->center, a->center, l->position, NULL)
                   : dist_to_segment(b->center, a->center, NULL, l->direction);
    return d <= a->bound + b->bound;
}

/* Build occ_start/occ; returns 0 or -1 on allocation failure. */
int plan_shadows(render_scene *rs)
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

/* Conservative range [lo, hi] of raster coordinate (along an image axis) that can see a
 * ball: its centre in camera coordinates has lateral offset c and depth z; slope = c/z of
 * the tangents from the eye, in the plane of that axis and the view direction (the ball
 * projects onto that plane as a disc of the same radius). `scale` is the plane's half-size
 * (a h or h), `size` the image size in pixels, `flip` for y (raster y grows downward).
 * Returns 0 if no ray in front of the eye can reach the ball. */
static int raster_range(double c, double z, double r, double scale, int size, int flip, int *lo,
                        int *hi)
{
    const double HALF_PI = 1.5707963267948966;
    double d = sqrt(c * c + z * z);
    *lo = 0, *hi = size - 1;
    if (d <= r) return 1; /* the eye is inside the ball's projection: every pixel */
    double th = atan2(c, z), del = asin(r / d);
    double a0 = th - del, a1 = th + del;
    if (a0 >= HALF_PI || a1 <= -HALF_PI) return 0; /* behind the eye */
    /* Plane coordinate p = tan(angle)/scale in [-1, 1] across the image; +-1e6 is "beyond". */
    double p0 = a0 <= -HALF_PI ? -1e6 : fmax(-1e6, tan(a0) / scale);
    double p1 = a1 >= HALF_PI ? 1e6 : fmin(1e6, tan(a1) / scale);
    if (flip) {
        double t = -p0;
        p0 = -p1, p1 = t;
    }
    /* raster x = (p + 1) size / 2; one pixel of margin for rounding. */
    double x0 = floor((p0 + 1.0) * 0.5 * size) - 1.0, x1 = floor((p1 + 1.0) * 0.5 * size) + 1.0;
    if (x1 < 0 || x0 > size - 1) return 0;
    *lo = x0 < 0 ? 0 : (int)x0;
    *hi = x1 > size - 1 ? size - 1 : (int)x1;
    return 1;
}

/* Per-row lists of the objects primary rays can hit; cull = 0 lists every object
 * everywhere (render_plan_ignore). Returns 0 or -1 on allocation failure. */
int plan_visibility(render_scene *rs, int cull)
{
    int n = rs->object_count, H = rs->height, W = rs->width;
    int *rows = malloc(2 * (size_t)n * sizeof *rows);
    int *cols = malloc(2 * (size_t)n * sizeof *cols + 1);
    int *start = calloc((size_t)H + 1, sizeof *start);
    if (!rows || !cols || !start) {
        free(rows), free(cols), free(start);
        return -1;
    }
    double a = (double)W / H, h = sqrt(geom_dot(rs->up, rs->up));
    double rhat[3], uhat[3];
    for (int c = 0; c < 3; ++c) rhat[c] = rs->right[c] / (a * h), uhat[c] = rs->up[c] / h;
    size_t total = 0;
    for (int k = 0; k < n; ++k) {
        const geom_object *g = &rs->objects[k];
        double v[3];
        sub3(g->center, rs->eye, v);
        double z = geom_dot(v, rs->forward);
        int seen = 1;
        rows[2 * k] = 0, rows[2 * k + 1] = H - 1, cols[2 * k] = 0, cols[2 * k + 1] = W - 1;
        if (cull)
            seen = raster_range(geom_dot(v, uhat), z, g->bound, h, H, 1, &rows[2 * k],
                                &rows[2 * k + 1]) &&
                   raster_range(geom_dot(v, rhat), z, g->bound, a * h, W, 0, &cols[2 * k],
                                &cols[2 * k + 1]);
        if (!seen) rows[2 * k] = 1, rows[2 * k + 1] = 0; /* empty */
        for (int j = rows[2 * k]; j <= rows[2 * k + 1]; ++j) ++start[j + 1], ++total;
    }
    for (int j = 0; j < H; ++j) start[j + 1] += start[j];
    int *list = malloc((total ? total : 1) * sizeof *list),
        *fill = malloc(((size_t)H + 1) * sizeof *fill);
    if (!list || !fill) {
        free(rows), free(cols), free(start), free(list), free(fill);
        return -1;
    }
    memcpy(fill, start, ((size_t)H + 1) * sizeof *fill);
    for (int k = 0; k < n; ++k) /* object order within each row: ties resolve as without culling */
        for (int j = rows[2 * k]; j <= rows[2 * k + 1]; ++j) list[fill[j]++] = k;
    free(fill);
    free(rows);
    free(rs->vis_start), free(rs->vis), free(rs->vis_cols);
    rs->vis_start = start, rs->vis = list, rs->vis_cols = cols;
    return 0;
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
        fprintf(f, "--full: the plan below is ignored; camera and shadow rays test every object, "
                   "every material builds tangent frames and adds the ambient term\n");
    }
    if (opt->precision == RENDER_DOUBLE)
        fprintf(f, "shading: double - the scalar reference, every lobe per hit and light "
                   "(abrdf_eval_prepared)\n");
    else
        fprintf(f, "shading: float - the fast path, each material's lobes over a tile's lit hits "
                   "(abrdf_eval_prepared_batch); within NMSE 1e-8 of --precision double\n");
    fprintf(f, "primary rays: %s\n",
            rs->full ? "every object tested for every pixel"
                     : "a pixel tests only the objects whose bounding sphere projects onto it");
    if (!rs->full) {
        long long covered = 0;
        for (int j = 0; j < rs->height; ++j)
            for (int q = rs->vis_start[j]; q < rs->vis_start[j + 1]; ++q) {
                int k = rs->vis[q];
                covered += rs->vis_cols[2 * k + 1] - rs->vis_cols[2 * k] + 1;
            }
        fprintf(f, "  %.2f of %d objects per pixel on average\n",
                (double)covered / ((double)rs->width * rs->height), n);
    }
    fprintf(f, "shadows:\n");
    for (int l = 0; l < rs->light_count; ++l) {
        const render_light *lt = &rs->lights[l];
        int pairs = 0;
        for (int i = 0; i < n; ++i) {
            int a = rs->occ_start[l * n + i], b = rs->occ_start[l * n + i + 1];
            pairs += b - a == 1 && rs->occ[a] < 0 ? n : b - a;
        }
        fprintf(f, "  light %d (%s, line %d): ", l,
                lt->kind == SCENE_LIGHT_POINT ? "point" : "directional", s->lights[l].line);
        if (!(lt->e[0] > 0 || lt->e[1] > 0 || lt->e[2] > 0))
            fprintf(f, "OFF - zero intensity, lights nothing\n");
        else if (lt->shadow_receivers == 0)
            fprintf(
                f, "no shadow rays - no object can block it from any object (%s)\n",
                n == 1 ? "a single convex solid cannot shadow itself"
                       : "bounding capsules toward the light are disjoint from every other object");
        else
            fprintf(f,
                    "shadow rays for %d of %d receivers, %d occluder candidates in all "
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
