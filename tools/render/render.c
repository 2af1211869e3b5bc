/* render.c - the built-in ray tracer: camera rays, closest hits, direct lighting with the
 * library's scalar reference BRDFs, shadow rays where the effect plan (plan.c) lists an
 * occluder, box-filtered stratified supersampling, rows shared by pthreads. Each pixel is a
 * pure function of the scene and its coordinates, so the image is bit-identical for any
 * number of threads. */
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "plan.h"

static const double DEG = 3.14159265358979323846 / 180.0;

static void normalize(double v[3])
{
    double l = sqrt(geom_dot(v, v));
    if (l > 0) v[0] /= l, v[1] /= l, v[2] /= l;
}

static void cross(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

void render_release(render_scene *rs)
{
    free(rs->objects);
    free(rs->materials);
    free(rs->lights);
    free(rs->occ_start);
    free(rs->occ);
    free(rs->vis_start);
    free(rs->vis);
    free(rs->vis_cols);
    memset(rs, 0, sizeof *rs);
}

int render_prepare(const scene *s, const render_options *opt, render_scene *rs, char *err,
                   size_t err_size)
{
    memset(rs, 0, sizeof *rs);
    rs->src = s;
    for (int i = 0; i < s->material_count; ++i) {
        const scene_material *m = &s->materials[i];
        if (m->kind == SCENE_MAT_TABLE || m->kind == SCENE_MAT_ADAPTIVE) {
            snprintf(err, err_size,
                     "material '%s' (line %d) is %s and not resolved to models "
                     "(scene_select_materials)",
                     m->name, m->line,
                     m->kind == SCENE_MAT_TABLE ? "a material-table entry" : "adaptive");
            return -1;
        }
    }
    rs->width = opt->width > 0 ? opt->width : s->camera.width;
    rs->height = opt->height > 0 ? opt->height : s->camera.height;
    rs->object_count = s->object_count;
    rs->light_count = s->light_count;
    rs->material_count = s->material_count;
    rs->objects = calloc((size_t)s->object_count, sizeof *rs->objects);
    rs->materials = calloc((size_t)s->material_count + 1, sizeof *rs->materials);
    rs->lights = calloc((size_t)s->light_count + 1, sizeof *rs->lights);
    if (!rs->objects || !rs->materials || !rs->lights) goto oom;

    /* Camera: right and up scaled so that raster corners land on the plane's corners. */
    const scene_camera *c = &s->camera;
    memcpy(rs->eye, c->position, sizeof rs->eye);
    for (int k = 0; k < 3; ++k) rs->forward[k] = c->look_at[k] - c->position[k];
    normalize(rs->forward);
    cross(rs->forward, c->up, rs->right);
    normalize(rs->right);
    cross(rs->right, rs->forward, rs->up);
    double h = tan(0.5 * c->fov_deg * DEG), a = (double)rs->width / rs->height;
    for (int k = 0; k < 3; ++k) rs->right[k] *= a * h, rs->up[k] *= h;

    double extent = sqrt(geom_dot(c->position, c->position));
    for (int i = 0; i < s->object_count; ++i) {
        geom_object_make(&s->objects[i], &rs->objects[i]);
        const geom_object *g = &rs->objects[i];
        extent = fmax(extent, sqrt(geom_dot(g->center, g->center)) + g->bound);
        rs->materials[s->objects[i].material].used = 1;
    }
    /* 1e-9 of the scene's size: far above double rounding of hit points, far below any
     * feature of a scene. */
    rs->eps = 1e-9 * fmax(extent, 1.0);
    for (int i = 0; i < s->material_count; ++i) {
        const scene_material *sm = &s->materials[i];
        render_material *m = &rs->materials[i];
        m->lobe_count = sm->lobe_count;
        memcpy(m->lobes, sm->lobes, sizeof m->lobes);
        m->params = sm->params;
        plan_material(m, s->ambient, sm->ka);
    }
    for (int l = 0; l < s->light_count; ++l) {
        const scene_light *sl = &s->lights[l];
        render_light *rl = &rs->lights[l];
        rl->kind = sl->kind;
        memcpy(rl->position, sl->position, sizeof rl->position);
        memcpy(rl->direction, sl->direction, sizeof rl->direction);
        for (int k = 0; k < 3; ++k) rl->e[k] = sl->color[k] * sl->intensity;
    }
    if (plan_shadows(rs) || plan_visibility(rs, 1)) goto oom;
    return 0;
oom:
    render_release(rs);
    snprintf(err, err_size, "out of memory");
    return -1;
}

int render_plan_ignore(render_scene *rs)
{
    int n = rs->object_count, pairs = rs->light_count * n;
    if (plan_visibility(rs, 0)) return -1;
    int *all = malloc(((size_t)pairs + 1) * sizeof *all);
    if (!all) return -1;
    for (int k = 0; k < pairs; ++k) all[k] = -1; /* -1: test every object */
    for (int k = 0; k <= pairs; ++k) rs->occ_start[k] = k;
    free(rs->occ);
    rs->occ = all;
    for (int i = 0; i < rs->material_count; ++i) rs->materials[i].full = 1;
    rs->full = 1;
    return 0;
}

int render_set_model(scene *s, abrdf_model model, char *err, size_t err_size)
{
    const abrdf_model_info *mi = abrdf_model_get(model);
    if (!mi) {
        snprintf(err, err_size, "unknown model id %d", (int)model);
        return -1;
    }
    for (int i = 0; i < s->material_count; ++i) {
        scene_material *m = &s->materials[i];
        abrdf_params p;
        abrdf_params_init(model, &p);
        for (int k = 0; k < mi->param_count; ++k) {
            int id = mi->params[k].id, shared = 0;
            for (int l = 0; l < m->lobe_count; ++l) {
                const abrdf_model_info *old = abrdf_model_get(m->lobes[l]);
                for (int q = 0; q < old->param_count; ++q) shared |= old->params[q].id == id;
            }
            double v[3];
            int cnt;
            if (shared && (cnt = abrdf_param_read(&m->params, id, v)) > 0)
                abrdf_param_set(&p, id, v, cnt); /* out of the new model's range: keep default */
        }
        char msg[256];
        if (abrdf_params_check(model, &p, msg, sizeof msg) != ABRDF_OK) {
            snprintf(err, err_size, "material '%s' as %s: %s", m->name, mi->name, msg);
            return -1;
        }
        m->kind = SCENE_MAT_MODELS;
        m->lobe_count = 1;
        m->lobes[0] = model;
        m->params = p;
    }
    return 0;
}

/* ---- tracing ----------------------------------------------------------------------- */

typedef struct worker {
    const render_scene *rs;
    const render_options *opt;
    float *rgb;
    render_stats stats;
    pthread_mutex_t *lock;
    int *next_row, *rows_done;
} worker;

/* Closest hit of a camera ray through pixel (i, j): only the objects the plan lists for
 * row j and whose column range holds i. */
static int closest_hit(const render_scene *rs, int i, int j, const double o[3], const double d[3],
                       double *t, double n[3], render_stats *st)
{
    int best = -1;
    double tmax = INFINITY;
    for (int q = rs->vis_start[j]; q < rs->vis_start[j + 1]; ++q) {
        int k = rs->vis[q];
        if (i < rs->vis_cols[2 * k] || i > rs->vis_cols[2 * k + 1]) continue;
        double ti, ni[3];
        ++st->primary_tests;
        if (geom_intersect(&rs->objects[k], o, d, 0.0, tmax, &ti, ni)) {
            tmax = ti;
            best = k;
            memcpy(n, ni, sizeof ni);
        }
    }
    *t = tmax;
    return best;
}

/* Is the segment o + t d, t in (0, tmax), blocked by one of the listed occluders? */
static int occluded(const render_scene *rs, const int *occ, int count, const double o[3],
                    const double d[3], double tmax, render_stats *st)
{
    int all = count == 1 && occ[0] < 0;
    if (all) count = rs->object_count;
    for (int k = 0; k < count; ++k) {
        double t;
        ++st->occluder_tests;
        if (geom_intersect(&rs->objects[all ? k : occ[k]], o, d, 0.0, tmax, &t, NULL)) return 1;
    }
    return 0;
}

/* Local-frame directions for an isotropic lobe: only the polar angles and the azimuth
 * difference matter, so the x axis is put along the view's tangential part. */
static void iso_local(const double n[3], const double wi[3], const double wo[3], double li[3],
                      double lo[3])
{
    double co = geom_dot(n, wo), ci = geom_dot(n, wi);
    double ot[3] = {wo[0] - co * n[0], wo[1] - co * n[1], wo[2] - co * n[2]};
    double it[3] = {wi[0] - ci * n[0], wi[1] - ci * n[1], wi[2] - ci * n[2]};
    double so = sqrt(geom_dot(ot, ot)), si2 = geom_dot(it, it);
    /* 1e-12: below this wo is along N and its azimuth is undefined. */
    if (so > 1e-12) {
        double x = geom_dot(it, ot) / so;
        lo[0] = so, lo[1] = 0, lo[2] = co;
        li[0] = x, li[1] = sqrt(fmax(0.0, si2 - x * x)), li[2] = ci;
    } else {
        lo[0] = 0, lo[1] = 0, lo[2] = 1;
        li[0] = sqrt(si2), li[1] = 0, li[2] = ci;
    }
}

static void shade(const render_scene *rs, int obj, const double p[3], const double n[3],
                  const double wo[3], double out[3], render_stats *st)
{
    const scene_object *so = &rs->src->objects[obj];
    const render_material *m = &rs->materials[so->material];
    out[0] = out[1] = out[2] = 0;
    int tangent = m->use_tangent || m->full;
    if (m->use_ambient || m->full) {
        for (int c = 0; c < 3; ++c) out[c] = m->ambient[c];
        ++st->ambient_terms;
    }
    if (!(geom_dot(n, wo) > 0)) return; /* seen from behind: no direct light reaches the eye */
    double o[3] = {p[0] + rs->eps * n[0], p[1] + rs->eps * n[1], p[2] + rs->eps * n[2]};
    abrdf_frame frame;
    int have_frame = 0;
    int no = rs->object_count;
    for (int l = 0; l < rs->light_count; ++l) {
        const render_light *lt = &rs->lights[l];
        double wi[3], d[3], tmax, falloff = 1.0;
        if (lt->kind == SCENE_LIGHT_POINT) {
            for (int k = 0; k < 3; ++k) d[k] = lt->position[k] - o[k];
            double d2 = geom_dot(d, d);
            if (!(d2 > 0)) continue;
            falloff = 1.0 / d2;
            memcpy(wi, d, sizeof wi);
            normalize(wi);
            tmax = 1.0; /* d spans the whole segment to the light */
        } else {
            memcpy(wi, lt->direction, sizeof wi);
            memcpy(d, wi, sizeof d);
            tmax = INFINITY;
        }
        double ci = geom_dot(n, wi);
        if (!(ci > 0)) continue;
        int a = rs->occ_start[l * no + obj], b = rs->occ_start[l * no + obj + 1];
        if (b > a) {
            ++st->shadow_rays;
            if (occluded(rs, rs->occ + a, b - a, o, d, tmax, st)) continue;
        } else {
            ++st->shadow_rays_skipped;
        }
        double f[3] = {0, 0, 0}, fl[3], li[3], lo[3];
        if (tangent && !have_frame) {
            double t[3];
            geom_tangent(so, &rs->objects[obj].xf, p, t);
            abrdf_frame_make(n, t, &frame);
            have_frame = 1;
            ++st->tangent_frames;
        }
        if (!tangent) iso_local(n, wi, wo, li, lo);
        for (int k = 0; k < m->lobe_count; ++k) {
            if (tangent)
                abrdf_eval(m->lobes[k], &m->params, &frame, wi, wo, fl);
            else
                abrdf_eval(m->lobes[k], &m->params, NULL, li, lo, fl);
            unsigned needs = abrdf_model_get(m->lobes[k])->needs;
            ++st->brdf_evals;
            st->fresnel_evals += (needs & ABRDF_NEEDS_FRESNEL) != 0;
            st->layer_evals += (needs & ABRDF_NEEDS_LAYERS) != 0;
            st->integration_evals += (needs & ABRDF_NEEDS_INTEGRATION) != 0;
            for (int c = 0; c < 3; ++c) f[c] += fl[c];
        }
        for (int c = 0; c < 3; ++c) out[c] += lt->e[c] * falloff * ci * f[c];
    }
}

/* Deterministic hash of (pixel, sample, dimension) -> [0, 1), for jittered strata. */
static double hash01(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    x ^= x >> 31;
    return (double)(x >> 11) * (1.0 / 9007199254740992.0);
}

static void render_row(const render_scene *rs, const render_options *opt, int j, float *row,
                       render_stats *st)
{
    int k = (int)lround(sqrt((double)opt->spp));
    for (int i = 0; i < rs->width; ++i) {
        double sum[3] = {0, 0, 0};
        for (int sy = 0; sy < k; ++sy)
            for (int sx = 0; sx < k; ++sx) {
                double u = 0.5, v = 0.5;
                if (opt->jitter) {
                    uint64_t id =
                        ((uint64_t)j * (uint64_t)rs->width + (uint64_t)i) * (uint64_t)opt->spp +
                        (uint64_t)(sy * k + sx);
                    u = hash01(2 * id), v = hash01(2 * id + 1);
                }
                double x = i + (sx + u) / k, y = j + (sy + v) / k;
                double px = 2.0 * x / rs->width - 1.0, py = 1.0 - 2.0 * y / rs->height;
                double d[3];
                for (int c = 0; c < 3; ++c)
                    d[c] = rs->forward[c] + px * rs->right[c] + py * rs->up[c];
                normalize(d);
                ++st->primary_rays;
                double t, n[3];
                int obj = closest_hit(rs, i, j, rs->eye, d, &t, n, st);
                if (obj < 0) continue; /* background is black */
                ++st->hits;
                double p[3], wo[3] = {-d[0], -d[1], -d[2]}, L[3];
                for (int c = 0; c < 3; ++c) p[c] = rs->eye[c] + t * d[c];
                shade(rs, obj, p, n, wo, L, st);
                for (int c = 0; c < 3; ++c) sum[c] += L[c];
            }
        /* A point light on a surface is an infinite irradiance: keep the file finite. */
        for (int c = 0; c < 3; ++c) row[3 * i + c] = (float)fmin(sum[c] / opt->spp, FLT_MAX);
    }
}

static void progress(int done, int total)
{
    int w = 40, f = (int)((long long)done * w / total);
    fprintf(stderr, "\r[%.*s%*s] %3d%%", f, "========================================", w - f, "",
            (int)((long long)done * 100 / total));
    if (done == total) fputc('\n', stderr);
    fflush(stderr);
}

static void *work(void *arg)
{
    worker *w = arg;
    const render_scene *rs = w->rs;
    for (;;) {
        pthread_mutex_lock(w->lock);
        int j = (*w->next_row)++;
        pthread_mutex_unlock(w->lock);
        if (j >= rs->height) break;
        render_row(rs, w->opt, j, w->rgb + (size_t)j * (size_t)rs->width * 3, &w->stats);
        if (w->opt->progress) {
            pthread_mutex_lock(w->lock);
            progress(++*w->rows_done, rs->height);
            pthread_mutex_unlock(w->lock);
        }
    }
    return NULL;
}

static void add_stats(render_stats *a, const render_stats *b)
{
    a->primary_rays += b->primary_rays;
    a->primary_tests += b->primary_tests;
    a->hits += b->hits;
    a->shadow_rays += b->shadow_rays;
    a->shadow_rays_skipped += b->shadow_rays_skipped;
    a->occluder_tests += b->occluder_tests;
    a->tangent_frames += b->tangent_frames;
    a->brdf_evals += b->brdf_evals;
    a->fresnel_evals += b->fresnel_evals;
    a->layer_evals += b->layer_evals;
    a->integration_evals += b->integration_evals;
    a->ambient_terms += b->ambient_terms;
}

int render_image(const render_scene *rs, const render_options *opt, float *rgb, render_stats *stats)
{
    long k = lround(sqrt((double)opt->spp));
    if (opt->spp < 1 || k * k != opt->spp) return -1; /* strata form a k x k grid */
    int nt = opt->threads < 1 ? 1 : opt->threads > 64 ? 64 : opt->threads;
    worker w[64];
    pthread_t th[64];
    pthread_mutex_t lock;
    int next_row = 0, rows_done = 0, started = 0;
    if (pthread_mutex_init(&lock, NULL)) return -1;
    for (int t = 0; t < nt; ++t) {
        w[t] = (worker){rs, opt, rgb, {0}, &lock, &next_row, &rows_done};
        if (t > 0 && pthread_create(&th[t], NULL, work, &w[t])) break;
        started = t + 1;
    }
    work(&w[0]); /* the calling thread works too; rows left by failed starts are done here */
    for (int t = 1; t < started; ++t) pthread_join(th[t], NULL);
    pthread_mutex_destroy(&lock);
    if (stats) {
        memset(stats, 0, sizeof *stats);
        for (int t = 0; t < started; ++t) add_stats(stats, &w[t].stats);
    }
    return 0;
}

void render_stats_print(const render_stats *s, FILE *f)
{
    fprintf(f,
            "counters:\n"
            "  primary rays        %llu\n  primary tests       %llu\n  hits                %llu\n"
            "  shadow rays         %llu\n  shadow rays skipped %llu (plan: unoccludable)\n"
            "  occluder tests      %llu\n  tangent frames      %llu\n"
            "  brdf evals          %llu\n  fresnel evals       %llu\n"
            "  layer evals         %llu\n  integration evals   %llu\n  ambient terms       %llu\n",
            s->primary_rays, s->primary_tests, s->hits, s->shadow_rays, s->shadow_rays_skipped,
            s->occluder_tests, s->tangent_frames, s->brdf_evals, s->fresnel_evals, s->layer_evals,
            s->integration_evals, s->ambient_terms);
}
