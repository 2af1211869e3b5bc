/* scene_points.c - a scene's own shading points per material (scene_points.h). The pass
 * renders nothing: it casts the camera's rays and the shadow rays of render.c
 * (render_hit_light), on a copy of the scene whose materials are all a black Lambert, so that
 * adaptive and table materials need no resolving first. The copy keeps the normal maps: a
 * hit's normal is the one the render shades (render_hit_normal_map, at the render's
 * footprint), so the terms' frames, the side they face and the lights that reach them are
 * the render's. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scene_points.h"
#include "render.h"

static double wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void scene_points_free(scene_points *p)
{
    if (p->terms)
        for (int m = 0; m < p->material_count; ++m) free(p->terms[m]);
    free(p->terms);
    free(p->term_count);
    free(p->samples);
    free(p->stride);
    free(p->kept);
    free(p->hits);
    free(p->pixels);
    free(p->pixel_material);
    memset(p, 0, sizeof *p);
}

int scene_points_view(const scene_points *p, int m, abrdf_view *v)
{
    abrdf_view_init(v);
    if (m < 0 || m >= p->material_count || p->term_count[m] == 0) return 0;
    v->term_count = p->term_count[m];
    v->terms = p->terms[m];
    return 1;
}

/* The unit camera ray through raster point (x, y) (render.h: the plane at distance 1). */
static void camera_ray(const render_scene *rs, double x, double y, double d[3])
{
    double px = 2.0 * x / rs->width - 1.0, py = 1.0 - 2.0 * y / rs->height, len = 0.0;
    for (int k = 0; k < 3; ++k) {
        d[k] = rs->forward[k] + px * rs->right[k] + py * rs->up[k];
        len += d[k] * d[k];
    }
    len = sqrt(len);
    for (int k = 0; k < 3; ++k) d[k] /= len;
}

/* Append term t to material m's list, growing it. 0, or -1 out of memory. */
static int push(scene_points *p, int *cap, int m, const abrdf_view_term *t)
{
    if (p->term_count[m] == cap[m]) {
        int n = cap[m] ? 2 * cap[m] : 256;
        abrdf_view_term *g = realloc(p->terms[m], (size_t)n * sizeof *g);
        if (!g) return -1;
        p->terms[m] = g, cap[m] = n;
    }
    p->terms[m][p->term_count[m]++] = *t;
    return 0;
}

/* The camera sample through (x, y) if it hits material m: its terms, into sample *sample
 * (taken from p->samples[m] at the first term); *hit set if it sees m's front. 0, or -1 out
 * of memory. */
static int sample_terms(scene_points *p, int *cap, const render_scene *rs, const render_options *ro,
                        texture_thread *th, int m, double x, double y, double weight, int *sample,
                        int *hit, render_stats *st)
{
    double d[3];
    camera_ray(rs, x, y, d);
    accel_hit ah;
    accel_intersect(rs->accel, rs->eye, d, 0.0, INFINITY, &ah, &st->primary_tests);
    if (ah.object < 0 || rs->src->objects[ah.object].material != m) return 0;
    render_hit h;
    h.obj = ah.object, h.triangle = ah.triangle, h.b1 = ah.b1, h.b2 = ah.b2;
    memcpy(h.n, ah.n, sizeof h.n);
    for (int k = 0; k < 3; ++k) h.p[k] = rs->eye[k] + ah.t * d[k], h.wo[k] = -d[k];
    render_hit_normal_map(rs, ro, th, &h, st);
    if (!(geom_dot(h.n, h.wo) > 0)) return 0; /* seen from behind: unlit, as render.c has it */
    *hit = 1;
    abrdf_view_term t;
    memcpy(t.n, h.n, sizeof t.n);
    memcpy(t.wo, h.wo, sizeof t.wo);
    render_hit_tangent(rs, &h, t.t);
    double tn = geom_dot(t.t, h.n); /* the term's tangent must be orthogonal to n */
    for (int k = 0; k < 3; ++k) t.t[k] -= tn * h.n[k];
    for (int l = 0; l < rs->light_count; ++l) {
        if (!render_hit_light(rs, l, &h, t.wi, t.e, st)) continue;
        for (int c = 0; c < 3; ++c) t.e[c] *= weight;
        if (*sample < 0) *sample = p->samples[m]++;
        t.sample = *sample;
        if (push(p, cap, m, &t)) return -1;
    }
    return 0;
}

/* The copy of s the pass traces: every material a black Lambert (no table or measured file
 * to read) with s's normal map, if any (its only texture); the rest is s's, shared.
 * materials: room for s's materials. */
static void black_copy(const scene *s, scene *t, scene_material *materials)
{
    *t = *s;
    t->materials = materials;
    for (int i = 0; i < s->material_count; ++i) {
        scene_material *m = &materials[i];
        *m = s->materials[i];
        m->kind = SCENE_MAT_MODELS;
        m->lobe_count = 1;
        m->lobes[0] = ABRDF_LAMBERT;
        abrdf_params_init(ABRDF_LAMBERT, &m->params);
        for (int c = 0; c < 3; ++c) m->params.kd[c] = 0.0;
        m->measured = -1;
        m->pbr = 0, m->fit_count = 0;
        memset(m->maps, 0, sizeof m->maps);
        m->maps[SCENE_MAP_NORMAL] = s->materials[i].maps[SCENE_MAP_NORMAL];
        m->textured = m->maps[SCENE_MAP_NORMAL].path != NULL;
    }
}

int scene_points_trace(const scene *s, int spp, scene_points *out, char *err, size_t err_size)
{
    double t0 = wall_seconds();
    memset(out, 0, sizeof *out);
    int k = (int)lround(sqrt(spp > 0 ? (double)spp : 1.0));
    if (spp < 1 || k * k != spp) { /* the render's strata form a k x k grid */
        snprintf(err, err_size, "%d samples per pixel: not a square (1, 4, 9, ...)", spp);
        return -1;
    }
    int nm = s->material_count, rc = -1, *cap = NULL, *seen = NULL; /* seen: per material, its
                                                                      pixels scanned so far */
    texture_thread *th = NULL;
    scene copy;
    scene_material *mats = calloc((size_t)nm + 1, sizeof *mats);
    render_scene rs;
    memset(&rs, 0, sizeof rs);
    render_stats st;
    memset(&st, 0, sizeof st);
    if (!mats) goto oom;
    black_copy(s, &copy, mats);
    render_options ro;
    memset(&ro, 0, sizeof ro);
    ro.spp = k * k, ro.threads = 1; /* spp: a normal map's footprint is the render's */
    if (render_prepare(&copy, &ro, &rs, err, err_size)) {
        free(mats);
        return -1;
    }
    out->material_count = nm;
    out->width = rs.width, out->height = rs.height, out->spp = k * k;
    size_t npx = (size_t)rs.width * (size_t)rs.height;
    out->pixel_material = malloc(npx * sizeof *out->pixel_material);
    out->pixels = calloc((size_t)nm + 1, sizeof *out->pixels);
    out->stride = calloc((size_t)nm + 1, sizeof *out->stride);
    out->samples = calloc((size_t)nm + 1, sizeof *out->samples);
    out->term_count = calloc((size_t)nm + 1, sizeof *out->term_count);
    out->terms = calloc((size_t)nm + 1, sizeof *out->terms);
    out->kept = calloc((size_t)nm + 1, sizeof *out->kept);
    out->hits = calloc((size_t)nm + 1, sizeof *out->hits);
    cap = calloc((size_t)nm + 1, sizeof *cap);
    seen = calloc((size_t)nm + 1, sizeof *seen);
    if (!out->pixel_material || !out->pixels || !out->stride || !out->samples || !out->term_count ||
        !out->terms || !out->kept || !out->hits || !cap || !seen)
        goto oom;
    if (rs.textures && !(th = texture_thread_new(rs.textures))) goto oom;
    /* the material at every pixel centre */
    for (int j = 0; j < rs.height; ++j)
        for (int i = 0; i < rs.width; ++i) {
            double d[3];
            camera_ray(&rs, i + 0.5, j + 0.5, d);
            accel_hit ah;
            accel_intersect(rs.accel, rs.eye, d, 0.0, INFINITY, &ah, &st.primary_tests);
            int m = ah.object >= 0 ? s->objects[ah.object].material : -1;
            out->pixel_material[(size_t)j * rs.width + i] = m;
            if (m >= 0) ++out->pixels[m];
        }
    int lights = 0;
    for (int l = 0; l < s->light_count; ++l) {
        int sampled = SCENE_LIGHT_SAMPLED(s->lights[l].kind);
        out->sampled_lights += sampled;
        lights += !sampled;
    }
    for (int m = 0; m < nm; ++m) {
        int st_m = 1;
        double per_pixel = (double)out->spp * (lights > 0 ? lights : 1);
        while ((double)st_m * st_m < out->pixels[m] &&
               ceil(out->pixels[m] / ((double)st_m * st_m)) * per_pixel > SCENE_POINTS_MAX_TERMS)
            ++st_m;
        out->stride[m] = st_m;
    }
    /* each material's terms: every stride^2-th of its pixels in scan order, its first
     * included, so that a material thinner than the stride keeps pixels too */
    double inv_k = 1.0 / k, weight = 1.0 / (k * k);
    for (int j = 0; j < rs.height; ++j)
        for (int i = 0; i < rs.width; ++i) {
            int m = out->pixel_material[(size_t)j * rs.width + i];
            if (m < 0 || seen[m]++ % (out->stride[m] * out->stride[m])) continue;
            ++out->kept[m];
            int sample = -1, hit = 0;
            for (int sy = 0; sy < k; ++sy)
                for (int sx = 0; sx < k; ++sx)
                    if (sample_terms(out, cap, &rs, &ro, th, m, i + (sx + 0.5) * inv_k,
                                     j + (sy + 0.5) * inv_k, weight, &sample, &hit, &st))
                        goto oom;
            out->hits[m] += hit;
        }
    if (render_texture_error(&rs, err, err_size)) { /* a normal map read as 0: not the render's */
        scene_points_free(out);
        goto done;
    }
    out->seconds = wall_seconds() - t0;
    rc = 0;
    goto done;
oom:
    snprintf(err, err_size, "out of memory for the scene's shading points");
    scene_points_free(out);
done:
    free(cap);
    free(seen);
    texture_thread_free(rs.textures, th);
    render_release(&rs);
    free(mats);
    return rc;
}
