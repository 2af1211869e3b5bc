/* render.c - the built-in ray tracer: camera rays and their closest hits through the Embree
 * scene (accel.h), direct lighting with the library's prepared BRDFs (the float batch path
 * by default, the double scalar reference on request: render.h, render_precision), shadow
 * rays as occlusion queries where the effect plan (plan.c) says something may block,
 * box-filtered stratified supersampling, rows shared by pthreads. A row is traced
 * and shaded as one batch of hits (in chunks of RENDER_TILE samples), so each pixel is a
 * pure function of the scene and its row: the image is bit-identical for any number of
 * threads, in each precision. */
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "light.h"
#include "map_range.h"
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

static int textures_open(const scene *s, const render_options *opt, render_scene *rs, char *err,
                         size_t err_size);

void render_release(render_scene *rs)
{
    texture_system_free(rs->textures);
    free(rs->objects);
    free(rs->materials);
    free(rs->lights);
    free(rs->shadow);
    accel_release(rs->accel);
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
                     "(scene_select)",
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
    rs->triangle_count = s->triangle_count;
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
        /* Validate and precompute each lobe once: shading then evaluates with no check. */
        for (int k = 0; k < m->lobe_count; ++k) {
            int st;
            if (m->lobes[k] == ABRDF_MEASURED && sm->measured < 0) {
                snprintf(err, err_size, "material '%s' (line %d): a measured lobe without a table",
                         sm->name, sm->line);
                render_release(rs);
                return -1;
            }
            if (m->lobes[k] == ABRDF_MEASURED) { /* the scene's table, alive as long as it */
                const measured_table *t = &s->measured[sm->measured].table;
                abrdf_measured desc;
                abrdf_measured_init(&desc);
                desc.n_theta_h = t->n_theta_h, desc.n_theta_d = t->n_theta_d;
                desc.n_phi_d = t->n_phi_d, desc.data = t->data;
                st = abrdf_prepare_measured(&desc, &m->prepared[k]);
            } else {
                st = abrdf_prepare(m->lobes[k], &m->params, &m->prepared[k]);
            }
            if (st != ABRDF_OK) {
                char msg[256];
                abrdf_params_check(m->lobes[k], &m->params, msg, sizeof msg);
                snprintf(err, err_size, "material '%s' (line %d): %s", sm->name, sm->line, msg);
                render_release(rs);
                return -1;
            }
            m->lobe_needs[k] = abrdf_model_get(m->lobes[k])->needs;
            if (m->lobes[k] == ABRDF_HUANG && opt->hair_tables && m->used && !sm->textured &&
                !sm->huang_per_call) {
                char what[160];
                snprintf(what, sizeof what, "material '%s' (line %d)", sm->name, sm->line);
                if (hair_store_get(opt->hair_tables, &m->params, what, &m->prepared[k], err,
                                   err_size)) {
                    render_release(rs);
                    return -1;
                }
                m->tabulated = 1;
            }
        }
        plan_material(m, s->ambient, sm->ka);
    }
    if (textures_open(s, opt, rs, err, err_size)) {
        render_release(rs);
        return -1;
    }
    for (int l = 0; l < s->light_count; ++l) {
        const scene_light *sl = &s->lights[l];
        render_light *rl = &rs->lights[l];
        rl->kind = sl->kind;
        memcpy(rl->position, sl->position, sizeof rl->position);
        memcpy(rl->direction, sl->direction, sizeof rl->direction);
        for (int k = 0; k < 3; ++k) rl->e[k] = sl->color[k] * sl->intensity;
        light_setup(sl, rl);
        rs->sampled_lights += SCENE_LIGHT_SAMPLED(sl->kind);
    }
    /* reach: the camera and every object lie within `extent` of the origin */
    if (accel_build(rs->objects, rs->object_count, extent, opt->threads, &rs->accel, err,
                    err_size)) {
        render_release(rs);
        return -1;
    }
    if (plan_shadows(rs)) goto oom;
    return 0;
oom:
    render_release(rs);
    snprintf(err, err_size, "out of memory");
    return -1;
}

int render_plan_ignore(render_scene *rs)
{
    memset(rs->shadow, 1, (size_t)rs->light_count * (size_t)rs->object_count);
    for (int l = 0; l < rs->light_count; ++l) rs->lights[l].shadow_receivers = rs->object_count;
    for (int i = 0; i < rs->material_count; ++i) rs->materials[i].full = 1;
    rs->full = 1;
    return 0;
}

/* ---- textures (texture.h) ---------------------------------------------------------- */

/* Open the maps of the used textured materials into one texture system and check that every
 * object with such a material has texture coordinates. 0, or -1 with one line in err. */
static int textures_open(const scene *s, const render_options *opt, render_scene *rs, char *err,
                         size_t err_size)
{
    for (int i = 0; i < s->object_count; ++i) {
        const scene_object *o = &s->objects[i];
        const scene_material *sm = &s->materials[o->material];
        if (!sm->textured) continue;
        if (o->shape != SCENE_MESH || !o->mesh_data->tri_uv) {
            snprintf(err, err_size,
                     "material '%s' (line %d) has textures, but the %s at line %d has no "
                     "texture coordinates (a mesh with vt)",
                     sm->name, sm->line, scene_shape_name(o->shape), o->line);
            return -1;
        }
        for (int k = 0; k < SCENE_MAP_COUNT; ++k)
            if (sm->maps[k].path && sm->maps[k].uv_set != 0) {
                snprintf(err, err_size,
                         "material '%s' (line %d): the %s map reads texture coordinates %d, but "
                         "a mesh has one set (0)",
                         sm->name, sm->line, scene_map_name((scene_map_slot)k), sm->maps[k].uv_set);
                return -1;
            }
    }
    rs->texture_cache_mb =
        opt->texture_cache_mb > 0 ? opt->texture_cache_mb : TEXTURE_CACHE_MB_DEFAULT;
    for (int i = 0; i < s->material_count; ++i) {
        const scene_material *sm = &s->materials[i];
        render_material *m = &rs->materials[i];
        if (!sm->textured || !m->used) continue;
        if (!rs->textures &&
            !(rs->textures = texture_system_new(rs->texture_cache_mb, err, err_size)))
            return -1;
        m->textured = 1;
        for (int k = 0; k < SCENE_MAP_COUNT; ++k) {
            const scene_map *mp = &sm->maps[k];
            if (!mp->path) continue;
            texture_info info;
            if (map_open(rs->textures, mp, &m->maps[k], &info, err, err_size)) return -1;
            m->map_channels[k] = info.channels;
            int one = k != SCENE_MAP_BASE_COLOR && k != SCENE_MAP_NORMAL;
            if (one && mp->channel >= info.channels) {
                snprintf(err, err_size,
                         "%s: no channel %d (it has %d) for %s_channel of material "
                         "'%s' (line %d)",
                         mp->path, mp->channel, info.channels, scene_map_name((scene_map_slot)k),
                         sm->name, sm->line);
                return -1;
            }
            if (k == SCENE_MAP_NORMAL && info.channels < 3) {
                snprintf(err, err_size, "%s: a normal map needs 3 channels (it has %d)", mp->path,
                         info.channels);
                return -1;
            }
        }
    }
    return 0;
}

/* A textured material at one hit: its lobes prepared from the texels there (m, whose
 * `ambient` also carries the occlusion), and the hit with the normal map's normal (h). */
typedef struct tex_point {
    render_material m;
    render_hit h;
} tex_point;

static void sub3(const double a[3], const double b[3], double o[3])
{
    for (int k = 0; k < 3; ++k) o[k] = a[k] - b[k];
}

/* Texture coordinates (glTF's: s right, t down; an OBJ mesh's v is up, t = 1 - v; a glTF
 * mesh's v is t) of a hit,
 * and their derivatives across one sample's footprint (a stratum: the pixel / k for k x k
 * samples). The footprint is the camera ray's differential (Igehy 1999): the rays through
 * the stratum's neighbours in x and y meet the triangle's plane at p + dp/dx, p + dp/dy,
 * and s, t are linear on the triangle. */
static void hit_uv(const render_scene *rs, const render_options *opt, const render_hit *h,
                   double st[2], double dx[2], double dy[2], double dpdu[3], double dpdv[3])
{
    const geom_object *g = &rs->objects[h->obj];
    const mesh *me = g->mesh;
    const int *ti = me->tri + 3 * (size_t)h->triangle, *tu = me->tri_uv + 3 * (size_t)h->triangle;
    double P[3][3], uv[3][2];
    for (int c = 0; c < 3; ++c) {
        const float *q = me->position + 3 * (size_t)ti[c];
        double po[3] = {q[0], q[1], q[2]};
        geom_xform_point(g->xf.m, po, P[c]);
        uv[c][0] = me->uv[2 * (size_t)tu[c]];
        uv[c][1] = me->uv[2 * (size_t)tu[c] + 1];
    }
    double b0 = 1.0 - h->b1 - h->b2;
    double u = b0 * uv[0][0] + h->b1 * uv[1][0] + h->b2 * uv[2][0];
    double v = b0 * uv[0][1] + h->b1 * uv[1][1] + h->b2 * uv[2][1];
    double e1[3], e2[3], n[3], g1[3], g2[3];
    sub3(P[1], P[0], e1);
    sub3(P[2], P[0], e2);
    cross(e1, e2, n);
    double nn = geom_dot(n, n);
    cross(e2, n, g1); /* the duals of e1, e2 in the plane: gi . ej = (i == j) */
    cross(n, e1, g2);
    for (int k = 0; k < 3; ++k) g1[k] /= nn, g2[k] /= nn;
    double du1 = uv[1][0] - uv[0][0], du2 = uv[2][0] - uv[0][0];
    double dv1 = uv[1][1] - uv[0][1], dv2 = uv[2][1] - uv[0][1];
    /* dP/du, dP/dv: the triangle's uv tangent frame (the normal map's) */
    double det = du1 * dv2 - du2 * dv1, inv = det != 0 ? 1.0 / det : 0.0;
    /* dpdv points up the image (the normal map's +y) for both: a glTF mesh's v runs down */
    double up = me->uv_origin_top ? -1.0 : 1.0;
    for (int k = 0; k < 3; ++k) {
        dpdu[k] = (dv2 * e1[k] - dv1 * e2[k]) * inv;
        dpdv[k] = up * (du1 * e2[k] - du2 * e1[k]) * inv;
    }
    /* the unnormalised camera direction D (forward . D = 1) and its change per stratum */
    double fd = -geom_dot(h->wo, rs->forward), D[3], lam, pe[3];
    for (int k = 0; k < 3; ++k) D[k] = -h->wo[k] / fd;
    sub3(h->p, rs->eye, pe);
    lam = geom_dot(pe, rs->forward);
    double kk = sqrt((double)opt->spp), nD = geom_dot(n, D);
    double sx = 2.0 / (rs->width * kk), sy = -2.0 / (rs->height * kk);
    double *out[2] = {dx, dy};
    for (int a = 0; a < 2; ++a) {
        double dD[3], dp[3];
        for (int k = 0; k < 3; ++k) dD[k] = a == 0 ? rs->right[k] * sx : rs->up[k] * sy;
        double r = nD != 0 ? geom_dot(n, dD) / nD : 0.0;
        for (int k = 0; k < 3; ++k) dp[k] = lam * (dD[k] - D[k] * r);
        double db1 = geom_dot(g1, dp), db2 = geom_dot(g2, dp);
        out[a][0] = du1 * db1 + du2 * db2;
        /* t = 1 - v for an OBJ mesh (v up); t = v for a glTF one (mesh.h, uv_origin_top) */
        out[a][1] = (me->uv_origin_top ? 1 : -1) * (dv1 * db1 + dv2 * db2);
    }
    st[0] = u, st[1] = me->uv_origin_top ? v : 1.0 - v;
}

/* KHR_texture_transform: x' = offset + R(rotation) (scale * x), R counter-clockwise. */
static void map_transform(const scene_map *mp, const double in[2], double out[2], int linear)
{
    double c = mp->rotation ? cos(mp->rotation) : 1.0, s = mp->rotation ? sin(mp->rotation) : 0.0;
    double x = mp->scale[0] * in[0], y = mp->scale[1] * in[1];
    out[0] = c * x - s * y + (linear ? 0 : mp->offset[0]);
    out[1] = s * x + c * y + (linear ? 0 : mp->offset[1]);
}

static double clamp01(double v) { return v > 0 ? (v < 1 ? v : 1) : 0; /* NaN -> 0 */ }

/* The filtered texels of map mp (its file f, channels first to first + n - 1) at texture
 * coordinates uv with footprint derivatives dx, dy (hit_uv), through mp's transform. */
static void map_texel(const render_scene *rs, texture_thread *th, const scene_map *mp,
                      texture_file *f, int first, int n, const double uv[2], const double dx[2],
                      const double dy[2], float v[4], render_stats *st)
{
    double q[2], qx[2], qy[2];
    map_transform(mp, uv, q, 0);
    map_transform(mp, dx, qx, 1);
    map_transform(mp, dy, qy, 1);
    texture_lookup(rs->textures, th, f, first, n, q[0], q[1], qx[0], qx[1], qy[0], qy[1], v);
    ++st->texture_lookups;
}

/* The shading normal of hit h under its material's normal map, into n (which may be h->n):
 * the map's texel at uv (footprint dx, dy; hit_uv) in glTF's tangent space, x along dP/du,
 * y along dP/dv (the image's up), z the normal; h->n where the map's normal or the tangent
 * degenerates. */
static void normal_map_at(const render_scene *rs, const render_hit *h, const double uv[2],
                          const double dx[2], const double dy[2], const double dpdu[3],
                          const double dpdv[3], texture_thread *th, double n[3], render_stats *st)
{
    int mi = rs->src->objects[h->obj].material;
    const scene_map *mp = &rs->src->materials[mi].maps[SCENE_MAP_NORMAL];
    float texel[4];
    map_texel(rs, th, mp, rs->materials[mi].maps[SCENE_MAP_NORMAL], 0, 3, uv, dx, dy, texel, st);
    const double *hn = h->n;
    double s = mp->strength, t[3], b[3], nb[3];
    double x = (2.0 * texel[0] - 1.0) * s;
    double y = (2.0 * texel[1] - 1.0) * s;
    double z = 2.0 * texel[2] - 1.0;
    double tn = geom_dot(dpdu, hn);
    for (int k = 0; k < 3; ++k) t[k] = dpdu[k] - tn * hn[k];
    normalize(t);
    cross(hn, t, b);
    if (geom_dot(b, dpdv) < 0) /* mirrored texture coordinates */
        for (int k = 0; k < 3; ++k) b[k] = -b[k];
    for (int k = 0; k < 3; ++k) nb[k] = x * t[k] + y * b[k] + z * hn[k];
    if (geom_dot(nb, nb) > 0 && geom_dot(t, t) > 0) {
        normalize(nb);
        memcpy(n, nb, sizeof nb);
    }
}

/* Prepare the textured material of hit h (tp->m and tp->h); the texture thread th is the
 * caller's. */
static void texture_point(const render_scene *rs, const render_options *opt, const render_hit *h,
                          texture_thread *th, tex_point *tp, render_stats *st)
{
    const scene_material *sm = &rs->src->materials[rs->src->objects[h->obj].material];
    const render_material *base = &rs->materials[rs->src->objects[h->obj].material];
    double uv[2], dx[2], dy[2], dpdu[3], dpdv[3];
    hit_uv(rs, opt, h, uv, dx, dy, dpdu, dpdv);
    float texel[SCENE_MAP_COUNT][4] = {{0}};
    /* glTF packs metallic and roughness in one file: one lookup reads both channels (a
     * channel's filtered value does not depend on the others looked up with it) */
    const scene_map *mm = &sm->maps[SCENE_MAP_METALLIC], *mr = &sm->maps[SCENE_MAP_ROUGHNESS];
    int packed = base->maps[SCENE_MAP_METALLIC] &&
                 base->maps[SCENE_MAP_METALLIC] == base->maps[SCENE_MAP_ROUGHNESS] &&
                 mm->offset[0] == mr->offset[0] && mm->offset[1] == mr->offset[1] &&
                 mm->scale[0] == mr->scale[0] && mm->scale[1] == mr->scale[1] &&
                 mm->rotation == mr->rotation;
    for (int k = 0; k < SCENE_MAP_COUNT; ++k) {
        const scene_map *mp = &sm->maps[k];
        if (!base->maps[k] || (packed && k == SCENE_MAP_ROUGHNESS)) continue;
        if (k == SCENE_MAP_NORMAL) continue; /* normal_map_at, below (the last slot: same order) */
        int rgb = k == SCENE_MAP_BASE_COLOR;
        int first = rgb ? 0 : mp->channel;
        int n = rgb ? (base->map_channels[k] < 3 ? 1 : 3) : 1;
        if (packed && k == SCENE_MAP_METALLIC) {
            first = mm->channel < mr->channel ? mm->channel : mr->channel;
            n = abs(mm->channel - mr->channel) + 1;
        }
        float v[4];
        map_texel(rs, th, mp, base->maps[k], first, n, uv, dx, dy, v, st);
        if (packed && k == SCENE_MAP_METALLIC) {
            texel[SCENE_MAP_METALLIC][0] = v[mm->channel - first];
            texel[SCENE_MAP_ROUGHNESS][0] = v[mr->channel - first];
        } else {
            for (int c = 0; c < 3; ++c) texel[k][c] = v[n == 1 ? 0 : c]; /* grey: every channel */
        }
    }
    ++st->textured_hits;
    abrdf_pbr q = sm->pbr_in;
    if (base->maps[SCENE_MAP_BASE_COLOR])
        for (int c = 0; c < 3; ++c) {
            double t = clamp01(texel[SCENE_MAP_BASE_COLOR][c]);
            q.base_color[c] *= sm->maps[SCENE_MAP_BASE_COLOR].srgb ? texture_srgb_decode(t) : t;
        }
    if (base->maps[SCENE_MAP_METALLIC]) q.metallic *= clamp01(texel[SCENE_MAP_METALLIC][0]);
    if (base->maps[SCENE_MAP_ROUGHNESS]) q.roughness *= clamp01(texel[SCENE_MAP_ROUGHNESS][0]);
    tp->m = *base;
    scene_pbr_params(sm, &q, &tp->m.params); /* q is in range: factors times [0, 1] */
    for (int k = 0; k < tp->m.lobe_count; ++k)
        abrdf_prepare(tp->m.lobes[k], &tp->m.params, &tp->m.prepared[k]);
    /* ambient: ka * Ia (ka follows the hit's kd unless given), times the occlusion */
    double occ = 1.0;
    if (base->maps[SCENE_MAP_OCCLUSION])
        occ = 1.0 + sm->maps[SCENE_MAP_OCCLUSION].strength *
                        (clamp01(texel[SCENE_MAP_OCCLUSION][0]) - 1.0);
    for (int c = 0; c < 3; ++c)
        tp->m.ambient[c] =
            (sm->ka_given ? sm->ka[c] : tp->m.params.kd[c]) * rs->src->ambient[c] * occ;
    tp->m.use_ambient = tp->m.ambient[0] > 0 || tp->m.ambient[1] > 0 || tp->m.ambient[2] > 0;
    tp->h = *h;
    if (base->maps[SCENE_MAP_NORMAL]) normal_map_at(rs, h, uv, dx, dy, dpdu, dpdv, th, tp->h.n, st);
}

int render_hit_normal_map(const render_scene *rs, const render_options *opt, texture_thread *th,
                          render_hit *h, render_stats *st)
{
    if (!rs->materials[rs->src->objects[h->obj].material].maps[SCENE_MAP_NORMAL]) return 0;
    double uv[2], dx[2], dy[2], dpdu[3], dpdv[3];
    hit_uv(rs, opt, h, uv, dx, dy, dpdu, dpdv);
    normal_map_at(rs, h, uv, dx, dy, dpdu, dpdv, th, h->n, st);
    return 1;
}

/* ---- shading ----------------------------------------------------------------------- */

const char *render_precision_name(int precision)
{
    return precision == RENDER_DOUBLE ? "double" : "float";
}

/* Is the segment o + t d, t in (0, tmax), from hit h toward a light blocked? An occlusion
 * query that ignores the triangle the ray leaves, and a convex receiver as a whole (it
 * cannot shadow its own lit side; --full tests it too). */
static int occluded(const render_scene *rs, const render_hit *h, const double o[3],
                    const double d[3], double tmax, render_stats *st)
{
    int skip = h->triangle >= 0 || (!rs->full && rs->objects[h->obj].convex) ? h->obj : -1;
    return accel_occluded(rs->accel, o, d, 0.0, tmax, skip, h->triangle, &st->occluder_tests);
}

/* Local-frame directions for an isotropic lobe: only the polar angles and the azimuth
 * difference matter, so the x axis is put along the view's tangential part. The view's part
 * (iso_view) is computed once per hit, the light's (iso_local) per light. */
typedef struct iso_view {
    double co, ot[3];  /* N.wo and wo's tangential part */
    double so, inv_so; /* |ot| and 1/|ot| */
} iso_view;

static void iso_view_make(const double n[3], const double wo[3], iso_view *v)
{
    v->co = geom_dot(n, wo);
    for (int k = 0; k < 3; ++k) v->ot[k] = wo[k] - v->co * n[k];
    v->so = sqrt(geom_dot(v->ot, v->ot));
    v->inv_so = v->so > 1e-12 ? 1.0 / v->so : 0.0;
}

static void iso_local(const double n[3], const iso_view *v, const double wi[3], double li[3],
                      double lo[3])
{
    double ci = geom_dot(n, wi);
    double it[3] = {wi[0] - ci * n[0], wi[1] - ci * n[1], wi[2] - ci * n[2]};
    double si2 = geom_dot(it, it);
    /* 1e-12: below this wo is along N and its azimuth is undefined. */
    if (v->so > 1e-12) {
        double x = geom_dot(it, v->ot) * v->inv_so;
        lo[0] = v->so, lo[1] = 0, lo[2] = v->co;
        double y2 = si2 - x * x;
        li[0] = x, li[1] = sqrt(y2 > 0.0 ? y2 : 0.0), li[2] = ci;
    } else {
        lo[0] = 0, lo[1] = 0, lo[2] = 1;
        li[0] = sqrt(si2), li[1] = 0, li[2] = ci;
    }
}

static void to_local(const abrdf_frame *fr, const double v[3], double out[3])
{
    out[0] = geom_dot(v, fr->t);
    out[1] = geom_dot(v, fr->b);
    out[2] = geom_dot(v, fr->n);
}

/* Is the segment o + t d, t in (0, tmax), from hit h toward light l blocked? Only where the
 * plan says something may block (plan_shadows) is a shadow ray cast (light.h calls this
 * through a pointer). */
static int shadow_blocked(const render_scene *rs, int l, const render_hit *h, const double o[3],
                          const double d[3], double tmax, render_stats *st)
{
    if (rs->shadow[(size_t)l * (size_t)rs->object_count + (size_t)h->obj]) {
        ++st->shadow_rays;
        return occluded(rs, h, o, d, tmax, st);
    }
    ++st->shadow_rays_skipped;
    return 0;
}

/* One light as seen from a hit: the direction to it, the irradiance factor E falloff cos_i,
 * and whether it lights the point (in front, not shadowed as the plan says). Sampled lights
 * (light.h) are not this function's: 0. */
static int light_at(const render_scene *rs, int l, const render_hit *h, const double o[3],
                    double wi[3], double w[3], render_stats *st)
{
    const render_light *lt = &rs->lights[l];
    double d[3], tmax, falloff = 1.0;
    if (SCENE_LIGHT_SAMPLED(lt->kind)) return 0;
    if (lt->kind == SCENE_LIGHT_POINT) {
        for (int k = 0; k < 3; ++k) d[k] = lt->position[k] - o[k];
        double d2 = geom_dot(d, d);
        if (!(d2 > 0)) return 0;
        double inv = 1.0 / sqrt(d2); /* one divide for both */
        falloff = inv * inv;
        for (int k = 0; k < 3; ++k) wi[k] = d[k] * inv;
        tmax = 1.0; /* d spans the whole segment to the light */
    } else {
        memcpy(wi, lt->direction, 3 * sizeof *wi);
        memcpy(d, wi, sizeof d);
        tmax = INFINITY;
    }
    double ci = geom_dot(h->n, wi);
    if (!(ci > 0)) return 0;
    if (shadow_blocked(rs, l, h, o, d, tmax, st)) return 0;
    for (int c = 0; c < 3; ++c) w[c] = lt->e[c] * falloff * ci;
    return 1;
}

int render_hit_light(const render_scene *rs, int l, const render_hit *h, double wi[3], double e[3],
                     render_stats *st)
{
    double o[3], w[3];
    for (int c = 0; c < 3; ++c) o[c] = h->p[c] + rs->eps * h->n[c];
    if (!light_at(rs, l, h, o, wi, w, st)) return 0;
    double ci = geom_dot(h->n, wi); /* > 0: light_at lit the point */
    for (int c = 0; c < 3; ++c) e[c] = w[c] / ci;
    return 1;
}

void render_hit_tangent(const render_scene *rs, const render_hit *h, double t[3])
{
    const scene_object *so = &rs->src->objects[h->obj];
    if (so->tangent == SCENE_TANGENT_UV && h->triangle >= 0)
        geom_tangent_uv(&rs->objects[h->obj], h->triangle, t);
    else
        geom_tangent(so, &rs->objects[h->obj].xf, h->p, t);
}

/* The ambient term, the shadow-ray origin and (for a material with a tangent rule) the
 * shading frame of a hit with material m; 0 if the hit is seen from behind (no direct
 * light). */
static int hit_begin(const render_scene *rs, const render_material *m, const render_hit *h,
                     double L[3], double o[3], abrdf_frame *frame, render_stats *st)
{
    L[0] = L[1] = L[2] = 0;
    if (m->use_ambient || m->full) {
        for (int c = 0; c < 3; ++c) L[c] = m->ambient[c];
        ++st->ambient_terms;
    }
    if (!(geom_dot(h->n, h->wo) > 0)) return 0; /* seen from behind: no light reaches the eye */
    for (int c = 0; c < 3; ++c) o[c] = h->p[c] + rs->eps * h->n[c];
    if (m->use_tangent || m->full) {
        double t[3];
        render_hit_tangent(rs, h, t);
        abrdf_frame_make(h->n, t, frame);
        ++st->tangent_frames;
    }
    return 1;
}

static void count_evals(const render_material *m, unsigned long long pairs, render_stats *st)
{
    for (int k = 0; k < m->lobe_count; ++k) {
        unsigned needs = m->lobe_needs[k];
        st->brdf_evals += pairs;
        st->fresnel_evals += (needs & ABRDF_NEEDS_FRESNEL) ? pairs : 0;
        st->layer_evals += (needs & ABRDF_NEEDS_LAYERS) ? pairs : 0;
        st->integration_evals += (needs & ABRDF_NEEDS_INTEGRATION) ? pairs : 0;
    }
}

/* The double reference: every lobe of material m per hit and light, abrdf_eval_prepared. */
static void shade_double(const render_scene *rs, const render_options *opt,
                         const render_material *m, const render_hit *h, double out[3],
                         render_stats *st)
{
    double o[3];
    abrdf_frame frame;
    if (!hit_begin(rs, m, h, out, o, &frame, st)) return;
    int tangent = m->use_tangent || m->full;
    iso_view view;
    if (!tangent) iso_view_make(h->n, h->wo, &view);
    for (int l = 0; l < rs->light_count; ++l) {
        double wi[3], w[3], f[3] = {0, 0, 0}, fl[3], li[3], lo[3];
        if (!light_at(rs, l, h, o, wi, w, st)) continue;
        if (!tangent) iso_local(h->n, &view, wi, li, lo);
        for (int k = 0; k < m->lobe_count && !opt->free_brdf; ++k) {
            if (tangent)
                abrdf_eval_prepared(&m->prepared[k], &frame, wi, h->wo, fl);
            else
                abrdf_eval_prepared(&m->prepared[k], NULL, li, lo, fl);
            for (int c = 0; c < 3; ++c) f[c] += fl[c];
        }
        count_evals(m, 1, st);
        for (int c = 0; c < 3; ++c) out[c] += w[c] * f[c];
    }
    if (rs->sampled_lights)
        light_shade_sampled(rs, opt, m, h, o, tangent ? &frame : NULL, shadow_blocked, out, st);
}

/* The float path for one hit of a textured material (its own prepared lobes, tp): the hit's
 * lit lights as one batch per lobe (abrdf_eval_prepared_batch). */
static void shade_float_hit(const render_scene *rs, const render_options *opt,
                            const render_material *m, const render_hit *h, double out[3],
                            render_stats *st)
{
    double o[3], w[SCENE_MAX_LIGHTS][3];
    abrdf_frame frame;
    float in[6][SCENE_MAX_LIGHTS], f[3][SCENE_MAX_LIGHTS];
    if (!hit_begin(rs, m, h, out, o, &frame, st)) return;
    int tangent = m->use_tangent || m->full, n = 0;
    if (rs->sampled_lights)
        light_shade_sampled(rs, opt, m, h, o, tangent ? &frame : NULL, shadow_blocked, out, st);
    iso_view view;
    if (!tangent) iso_view_make(h->n, h->wo, &view);
    for (int l = 0; l < rs->light_count; ++l) {
        double wi[3], li[3], lo[3];
        if (!light_at(rs, l, h, o, wi, w[n], st)) continue;
        if (tangent) {
            to_local(&frame, wi, li);
            to_local(&frame, h->wo, lo);
        } else {
            iso_local(h->n, &view, wi, li, lo);
        }
        for (int c = 0; c < 3; ++c) in[c][n] = (float)li[c], in[3 + c][n] = (float)lo[c];
        ++n;
    }
    if (!n) return;
    count_evals(m, (unsigned long long)n, st);
    double sum[SCENE_MAX_LIGHTS][3] = {{0}};
    for (int k = 0; k < m->lobe_count && !opt->free_brdf; ++k) {
        abrdf_batch b = {(size_t)n, in[0], in[1], in[2], in[3], in[4], in[5], f[0], f[1], f[2]};
        abrdf_eval_prepared_batch(&m->prepared[k], &b);
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) sum[i][c] += f[c][i];
    }
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) out[c] += w[i][c] * sum[i][c];
}

/* Lit (hit, light) pairs gathered for the float path, at most this many per batch. */
#define RENDER_PAIRS_MAX 16384
#define RENDER_CHUNK 256 /* pairs per lobe call: inputs and outputs stay in L1 */

struct render_shade_scratch {
    int pair_cap;                       /* pairs per batch */
    int *hit, *mat;                     /* per pair in gathering order: hit, material */
    int *shit;                          /* per sorted slot: the pair's hit */
    double *sw;                         /* per sorted slot: the pair's w (3) */
    double *w;                          /* per pair: E falloff cos_i (3) */
    float *li, *lo;                     /* per pair: local directions (3 each), gathering order */
    float *ix, *iy, *iz, *ox, *oy, *oz; /* sorted by material: the batch inputs */
    float *f[SCENE_MAX_LOBES][3];       /* each lobe's f_r over a chunk of sorted slots */
    int *start;                         /* per material: first sorted slot (material_count + 1) */
    texture_system *textures;           /* the scene's (NULL: no textured material) */
    texture_thread *tex;                /* ... and this thread's lookup state */
};

void render_shade_scratch_free(render_shade_scratch *sc)
{
    if (!sc) return;
    free(sc->hit), free(sc->mat), free(sc->shit), free(sc->sw), free(sc->w), free(sc->li);
    free(sc->lo);
    free(sc->ix), free(sc->iy), free(sc->iz), free(sc->ox), free(sc->oy), free(sc->oz);
    for (int k = 0; k < SCENE_MAX_LOBES; ++k)
        for (int c = 0; c < 3; ++c) free(sc->f[k][c]);
    free(sc->start);
    texture_thread_free(sc->textures, sc->tex);
    free(sc);
}

render_shade_scratch *render_shade_scratch_new(const render_scene *rs, int capacity)
{
    render_shade_scratch *sc = calloc(1, sizeof *sc);
    if (!sc) return NULL;
    long want = (long)(capacity > 0 ? capacity : 1) * (rs->light_count > 0 ? rs->light_count : 1);
    long lights = rs->light_count > 0 ? rs->light_count : 1;
    if (want > RENDER_PAIRS_MAX) want = RENDER_PAIRS_MAX > lights ? RENDER_PAIRS_MAX : lights;
    size_t n = (size_t)want;
    sc->pair_cap = (int)want;
    sc->hit = malloc(n * sizeof *sc->hit), sc->mat = malloc(n * sizeof *sc->mat);
    sc->shit = malloc(n * sizeof *sc->shit), sc->sw = malloc(3 * n * sizeof *sc->sw);
    sc->w = malloc(3 * n * sizeof *sc->w);
    sc->li = malloc(3 * n * sizeof *sc->li), sc->lo = malloc(3 * n * sizeof *sc->lo);
    sc->ix = malloc(n * sizeof(float)), sc->iy = malloc(n * sizeof(float));
    sc->iz = malloc(n * sizeof(float)), sc->ox = malloc(n * sizeof(float));
    sc->oy = malloc(n * sizeof(float)), sc->oz = malloc(n * sizeof(float));
    int ok = sc->hit && sc->mat && sc->shit && sc->sw && sc->w && sc->li && sc->lo && sc->ix &&
             sc->iy && sc->iz && sc->ox && sc->oy && sc->oz;
    for (int k = 0; k < SCENE_MAX_LOBES; ++k)
        for (int c = 0; c < 3; ++c) ok = (sc->f[k][c] = malloc(RENDER_CHUNK * sizeof(float))) && ok;
    sc->start = calloc((size_t)rs->material_count + 2, sizeof *sc->start);
    sc->textures = rs->textures;
    if (rs->textures) ok = (sc->tex = texture_thread_new(rs->textures)) && ok;
    if (!ok || !sc->start) {
        render_shade_scratch_free(sc);
        return NULL;
    }
    return sc;
}

/* Evaluate the gathered pairs: sort them by material (stable), run each lobe of a material
 * over its pairs with the batch API (into its own arrays: no pass that adds the lobes), and
 * add w * (sum of the lobes) to each pair's hit. */
static void flush_pairs(const render_scene *rs, const render_options *opt, int np, double (*L)[3],
                        render_shade_scratch *sc, render_stats *st)
{
    int nm = rs->material_count;
    int *start = sc->start;
    memset(start, 0, ((size_t)nm + 2) * sizeof *start);
    for (int q = 0; q < np; ++q) ++start[sc->mat[q] + 2];
    for (int m = 0; m < nm; ++m) start[m + 2] += start[m + 1];
    for (int q = 0; q < np; ++q) { /* start[m + 1] is material m's next free slot */
        int s = start[sc->mat[q] + 1]++;
        sc->shit[s] = sc->hit[q];
        for (int c = 0; c < 3; ++c) sc->sw[3 * s + c] = sc->w[3 * q + c];
        sc->ix[s] = sc->li[3 * q], sc->iy[s] = sc->li[3 * q + 1], sc->iz[s] = sc->li[3 * q + 2];
        sc->ox[s] = sc->lo[3 * q], sc->oy[s] = sc->lo[3 * q + 1], sc->oz[s] = sc->lo[3 * q + 2];
    }
    /* now start[m] is material m's first slot and start[m + 1] its end. Each material's pairs
     * go through its lobes and back to their hits RENDER_CHUNK at a time, so that a lobe's
     * inputs and outputs are still in the L1 cache when the next lobe and the sum read them:
     * a lobe then costs what its evaluation costs, not the traffic of its output arrays. */
    for (int m = 0; m < nm; ++m) {
        const render_material *mat = &rs->materials[m];
        count_evals(mat, (unsigned long long)(start[m + 1] - start[m]), st);
        for (int a = start[m]; a < start[m + 1]; a += RENDER_CHUNK) {
            int n = start[m + 1] - a < RENDER_CHUNK ? start[m + 1] - a : RENDER_CHUNK;
            for (int k = 0; k < mat->lobe_count; ++k) {
                float **out = sc->f[k];
                abrdf_batch b = {(size_t)n,  sc->ix + a, sc->iy + a, sc->iz + a, sc->ox + a,
                                 sc->oy + a, sc->oz + a, out[0],     out[1],     out[2]};
                if (opt->free_brdf)
                    for (int c = 0; c < 3; ++c) memset(out[c], 0, (size_t)n * sizeof(float));
                else
                    abrdf_eval_prepared_batch(&mat->prepared[k], &b);
            }
            /* Sorted order keeps gathering order within a material, and a hit has one
             * material: each hit gets its lights in light order. */
            for (int i = 0; i < n; ++i) {
                double *out = L[sc->shit[a + i]];
                for (int c = 0; c < 3; ++c) {
                    float f = mat->lobe_count > 0 ? sc->f[0][c][i] : 0.0f;
                    for (int k = 1; k < mat->lobe_count; ++k) f += sc->f[k][c][i];
                    out[c] += sc->sw[3 * (a + i) + c] * (double)f;
                }
            }
        }
    }
}

/* The float path: lit pairs gathered over the batch, evaluated per material and lobe. */
static void shade_float(const render_scene *rs, const render_options *opt, const render_hit *hits,
                        int count, double (*L)[3], render_shade_scratch *sc, render_stats *st)
{
    int np = 0;
    for (int h = 0; h < count; ++h) {
        const render_hit *hit = &hits[h];
        int mi = rs->src->objects[hit->obj].material;
        const render_material *m = &rs->materials[mi];
        double o[3];
        abrdf_frame frame;
        if (m->textured) { /* lobes of its own: shaded now, per hit */
            tex_point tp;
            texture_point(rs, opt, hit, sc->tex, &tp, st);
            shade_float_hit(rs, opt, &tp.m, &tp.h, L[h], st);
            continue;
        }
        if (!hit_begin(rs, m, hit, L[h], o, &frame, st)) continue;
        if (np + rs->light_count > sc->pair_cap) { /* full: evaluate what is gathered */
            flush_pairs(rs, opt, np, L, sc, st);
            np = 0;
        }
        int tangent = m->use_tangent || m->full;
        /* sampled lights: double, scalar, per hit (light.h), in both precisions */
        if (rs->sampled_lights)
            light_shade_sampled(rs, opt, m, hit, o, tangent ? &frame : NULL, shadow_blocked, L[h],
                                st);
        iso_view view;
        if (!tangent) iso_view_make(hit->n, hit->wo, &view);
        for (int l = 0; l < rs->light_count; ++l) {
            double wi[3], li[3], lo[3];
            if (!light_at(rs, l, hit, o, wi, sc->w + 3 * np, st)) continue;
            if (tangent) {
                to_local(&frame, wi, li);
                to_local(&frame, hit->wo, lo);
            } else {
                iso_local(hit->n, &view, wi, li, lo);
            }
            for (int c = 0; c < 3; ++c) {
                sc->li[3 * np + c] = (float)li[c];
                sc->lo[3 * np + c] = (float)lo[c];
            }
            sc->hit[np] = h;
            sc->mat[np] = mi;
            ++np;
        }
    }
    if (np) flush_pairs(rs, opt, np, L, sc, st);
}

void render_shade_hits(const render_scene *rs, const render_options *opt, const render_hit *hits,
                       int count, double (*L)[3], render_shade_scratch *sc, render_stats *st)
{
    if (opt->precision == RENDER_DOUBLE) {
        for (int h = 0; h < count; ++h) {
            const render_material *m = &rs->materials[rs->src->objects[hits[h].obj].material];
            if (m->textured) {
                tex_point tp;
                texture_point(rs, opt, &hits[h], sc->tex, &tp, st);
                shade_double(rs, opt, &tp.m, &tp.h, L[h], st);
            } else {
                shade_double(rs, opt, m, &hits[h], L[h], st);
            }
        }
    } else {
        shade_float(rs, opt, hits, count, L, sc, st);
    }
}

/* ---- tracing ----------------------------------------------------------------------- */

#define RENDER_TILE 1024 /* hits shaded as one batch */
#define RENDER_RAYS 256  /* camera rays generated as one batch */
#define RENDER_BAND 8    /* image rows per work item (a thread's unit) */

typedef struct worker {
    const render_scene *rs;
    const render_options *opt;
    float *rgb;
    render_stats stats;
    pthread_mutex_t *lock;
    int *next_row, *rows_done;
    render_shade_scratch *scratch;
    render_hit *hits;
    int *hit_pixel;   /* per hit: pixel column */
    double (*L)[3];   /* per hit: radiance */
    double *sum;      /* per pixel of a band: 3 sums */
    double *ray;      /* RENDER_RAYS camera rays: plane x, y, then direction x, y, z */
    int *ray_pixel;   /* per camera ray: pixel index within the band */
    accel_hit *ahits; /* per camera ray: its closest hit */
} worker;

/* Deterministic hash of (pixel, sample, dimension) -> [0, 1), for jittered strata. */
static double hash01(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    x ^= x >> 31;
    return (double)(x >> 11) * (1.0 / 9007199254740992.0);
}

/* Shade the hits gathered so far and add each to its pixel's sum. */
static void flush_hits(worker *w, int nh)
{
    render_shade_hits(w->rs, w->opt, w->hits, nh, w->L, w->scratch, &w->stats);
    for (int h = 0; h < nh; ++h)
        for (int c = 0; c < 3; ++c) w->sum[3 * w->hit_pixel[h] + c] += w->L[h][c];
}

/* Unit directions of camera rays through plane points (px[s], py[s]): one loop over SoA
 * arrays that the compiler vectorises (sqrt and divide in packed form). */
static void camera_dirs(const render_scene *rs, int n, const double *restrict px,
                        const double *restrict py, double *restrict dx, double *restrict dy,
                        double *restrict dz)
{
    const double f0 = rs->forward[0], f1 = rs->forward[1], f2 = rs->forward[2];
    const double r0 = rs->right[0], r1 = rs->right[1], r2 = rs->right[2];
    const double u0 = rs->up[0], u1 = rs->up[1], u2 = rs->up[2];
    for (int s = 0; s < n; ++s) {
        double x = f0 + px[s] * r0 + py[s] * u0;
        double y = f1 + px[s] * r1 + py[s] * u1;
        double z = f2 + px[s] * r2 + py[s] * u2;
        double inv = 1.0 / sqrt(x * x + y * y + z * z);
        dx[s] = x * inv, dy[s] = y * inv, dz[s] = z * inv;
    }
}

/* Trace the nr camera rays generated so far (one coherent stream from the eye); hits go to
 * the shading batch. */
static void trace_rays(worker *w, int nr, int *nh)
{
    const render_scene *rs = w->rs;
    render_stats *st = &w->stats;
    double *px = w->ray, *py = px + RENDER_RAYS, *dx = py + RENDER_RAYS, *dy = dx + RENDER_RAYS,
           *dz = dy + RENDER_RAYS;
    camera_dirs(rs, nr, px, py, dx, dy, dz);
    accel_intersect_from(rs->accel, rs->eye, nr, dx, dy, dz, 0.0, INFINITY, w->ahits,
                         &st->primary_tests);
    st->primary_rays += (unsigned long long)nr;
    for (int r = 0; r < nr; ++r) {
        const accel_hit *ah = &w->ahits[r];
        if (ah->object < 0) continue; /* background is black */
        ++st->hits;
        render_hit *h = &w->hits[*nh];
        h->obj = ah->object, h->triangle = ah->triangle;
        h->b1 = ah->b1, h->b2 = ah->b2;
        memcpy(h->n, ah->n, sizeof h->n);
        h->p[0] = rs->eye[0] + ah->t * dx[r], h->wo[0] = -dx[r];
        h->p[1] = rs->eye[1] + ah->t * dy[r], h->wo[1] = -dy[r];
        h->p[2] = rs->eye[2] + ah->t * dz[r], h->wo[2] = -dz[r];
        w->hit_pixel[(*nh)++] = w->ray_pixel[r];
        if (*nh == RENDER_TILE) flush_hits(w, *nh), *nh = 0;
    }
}

/* Rows [j0, j1), a band: camera samples in pixel order (row, column, then stratum row and
 * column), generated RENDER_RAYS at a time, traced, and shaded RENDER_TILE hits at a time (a
 * band gathers more hits per material than a row); each pixel sums its samples in that
 * order. Bands are fixed by the image, so the result does not depend on the threads. */
static void render_band(worker *w, int j0, int j1, float *rows)
{
    const render_scene *rs = w->rs;
    const render_options *opt = w->opt;
    int k = (int)lround(sqrt((double)opt->spp)), nh = 0, nr = 0, W = rs->width;
    double inv_k = 1.0 / k, sx2 = 2.0 / W, sy2 = 2.0 / rs->height;
    double *px = w->ray, *py = px + RENDER_RAYS;
    memset(w->sum, 0, (size_t)W * (size_t)(j1 - j0) * 3 * sizeof *w->sum);
    for (int j = j0; j < j1; ++j)
        for (int i = 0; i < W; ++i)
            for (int sy = 0, q = 0; sy < k; ++sy)
                for (int sx = 0; sx < k; ++sx, ++q) {
                    double u = 0.5, v = 0.5;
                    if (opt->jitter) {
                        uint64_t id =
                            ((uint64_t)j * (uint64_t)W + (uint64_t)i) * (uint64_t)opt->spp +
                            (uint64_t)q;
                        u = hash01(2 * id), v = hash01(2 * id + 1);
                    }
                    double x = i + (sx + u) * inv_k, y = j + (sy + v) * inv_k;
                    px[nr] = x * sx2 - 1.0, py[nr] = 1.0 - y * sy2;
                    w->ray_pixel[nr++] = (j - j0) * W + i;
                    if (nr == RENDER_RAYS) trace_rays(w, nr, &nh), nr = 0;
                }
    if (nr) trace_rays(w, nr, &nh);
    if (nh) flush_hits(w, nh);
    /* A point light on a surface is an infinite irradiance: keep the file finite. */
    for (size_t p = 0; p < (size_t)W * (size_t)(j1 - j0) * 3; ++p)
        rows[p] = (float)fmin(w->sum[p] / opt->spp, FLT_MAX);
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
        int j = *w->next_row;
        *w->next_row += RENDER_BAND;
        pthread_mutex_unlock(w->lock);
        if (j >= rs->height) break;
        int j1 = j + RENDER_BAND < rs->height ? j + RENDER_BAND : rs->height;
        render_band(w, j, j1, w->rgb + (size_t)j * (size_t)rs->width * 3);
        if (w->opt->progress) {
            pthread_mutex_lock(w->lock);
            *w->rows_done += j1 - j;
            progress(*w->rows_done, rs->height);
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
    a->light_samples += b->light_samples;
    a->brdf_samples += b->brdf_samples;
    a->textured_hits += b->textured_hits;
    a->texture_lookups += b->texture_lookups;
}

static void worker_free(worker *w)
{
    render_shade_scratch_free(w->scratch);
    free(w->hits), free(w->hit_pixel), free(w->L), free(w->sum), free(w->ray), free(w->ray_pixel);
    free(w->ahits);
}

/* The per-thread memory of a worker; 0 or -1 (out of memory, nothing left allocated). */
static int worker_alloc(worker *w)
{
    w->scratch = render_shade_scratch_new(w->rs, RENDER_TILE);
    w->hits = malloc(RENDER_TILE * sizeof *w->hits);
    w->hit_pixel = malloc(RENDER_TILE * sizeof *w->hit_pixel);
    w->L = malloc(RENDER_TILE * sizeof *w->L);
    w->sum = malloc((size_t)w->rs->width * RENDER_BAND * 3 * sizeof *w->sum);
    w->ray = malloc(5 * RENDER_RAYS * sizeof *w->ray);
    w->ray_pixel = malloc(RENDER_RAYS * sizeof *w->ray_pixel);
    w->ahits = malloc(RENDER_RAYS * sizeof *w->ahits);
    if (w->scratch && w->hits && w->hit_pixel && w->L && w->sum && w->ray && w->ray_pixel &&
        w->ahits)
        return 0;
    worker_free(w);
    return -1;
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
        w[t] = (worker){.rs = rs,
                        .opt = opt,
                        .rgb = rgb,
                        .lock = &lock,
                        .next_row = &next_row,
                        .rows_done = &rows_done};
        if (worker_alloc(&w[t])) {
            if (t == 0) {
                pthread_mutex_destroy(&lock);
                return -1;
            }
            break;
        }
        if (t > 0 && pthread_create(&th[t], NULL, work, &w[t])) {
            worker_free(&w[t]);
            break;
        }
        started = t + 1;
    }
    work(&w[0]); /* the calling thread works too; rows left by failed starts are done here */
    for (int t = 1; t < started; ++t) pthread_join(th[t], NULL);
    pthread_mutex_destroy(&lock);
    if (stats) {
        memset(stats, 0, sizeof *stats);
        for (int t = 0; t < started; ++t) add_stats(stats, &w[t].stats);
    }
    for (int t = 0; t < started; ++t) worker_free(&w[t]);
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
    if (s->light_samples || s->brdf_samples) /* sampled lights only: other scenes print as before */
        fprintf(f, "  light samples       %llu\n  brdf samples        %llu\n", s->light_samples,
                s->brdf_samples);
    if (s->textured_hits) /* textured materials only */
        fprintf(f, "  textured hits       %llu\n  texture lookups     %llu\n", s->textured_hits,
                s->texture_lookups);
}

void render_textures_print(const render_scene *rs, FILE *f)
{
    if (!rs->textures) return;
    texture_stats t;
    texture_stats_get(rs->textures, &t);
    fprintf(f,
            "textures: %d files, cache bound %g MB: peak %.3f MB, now %lld bytes, peak %d tiles; "
            "%llu lookups, %llu bytes read\n",
            t.files, rs->texture_cache_mb, t.peak_memory_mb, t.memory_used, t.tiles_peak, t.lookups,
            t.bytes_read);
}

int render_texture_error(const render_scene *rs, char *err, size_t err_size)
{
    return rs->textures ? texture_error(rs->textures, err, err_size) : 0;
}
