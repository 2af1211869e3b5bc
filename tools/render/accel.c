/* accel.c - the Embree scene (accel.h). Embree traverses with a float copy of the ray; the
 * query's double-precision ray travels in the intersect context, which every callback
 * reads, and the callbacks keep the closest hit in double there. Embree's own ray.tfar only
 * prunes the traversal: it is kept at or just above the best distance found. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <embree3/rtcore.h>

#include "accel.h"

struct accel {
    RTCDevice device;
    RTCScene scene;
    const geom_object *objects;
    int count;
    long long bytes; /* Embree's allocations now (memory monitor) */
    char error[256]; /* Embree's first error message */
};

/* One query: Embree passes a pointer to ctx to every callback, so ctx comes first. */
typedef struct query {
    struct RTCIntersectContext ctx;
    const accel *a;
    double o[3], d[3], tmin, tmax;
    int skip_object, skip_triangle;
    int best_object, best_triangle; /* closest so far (-1: none) */
    double best_t, b1, b2;
    double n[3]; /* analytic winner: its world normal */
    unsigned long long tests;
} query;

static void on_error(void *user, enum RTCError code, const char *msg)
{
    accel *a = user;
    if (!a->error[0]) snprintf(a->error, sizeof a->error, "Embree error %d: %s", (int)code, msg);
}

static bool on_memory(void *user, ssize_t bytes, bool post)
{
    accel *a = user;
    (void)post;
    __atomic_add_fetch(&a->bytes, (long long)bytes, __ATOMIC_RELAXED);
    return true;
}

/* (t, object, triangle) before the best so far? */
static int better(const query *q, double t, int object, int triangle)
{
    if (q->best_object < 0) return 1;
    if (t != q->best_t) return t < q->best_t;
    if (object != q->best_object) return object < q->best_object;
    return triangle < q->best_triangle;
}

/* The smallest float not below x: Embree's tfar must never cut a hit at distance x. */
static float float_up(double x)
{
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

static float float_down(double x)
{
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

/* ---- analytic primitives: user geometry ----------------------------------------------- */

static void user_bounds(const struct RTCBoundsFunctionArguments *args)
{
    const float *box = args->geometryUserPtr; /* lower x, y, z, upper x, y, z */
    struct RTCBounds *b = args->bounds_o;
    b->lower_x = box[0], b->lower_y = box[1], b->lower_z = box[2];
    b->upper_x = box[3], b->upper_y = box[4], b->upper_z = box[5];
}

static void user_intersect(const struct RTCIntersectFunctionNArguments *args)
{
    query *q = (query *)args->context;
    if (args->N != 1 || !args->valid[0]) return;
    int id = (int)args->geomID;
    const geom_object *g = &q->a->objects[id];
    ++q->tests;
    /* Up to the best distance; an equal distance still wins for an earlier object. */
    double limit = q->best_object < 0    ? q->tmax
                   : id < q->best_object ? nextafter(q->best_t, INFINITY)
                                         : q->best_t;
    double t, n[3];
    if (!geom_intersect(g, q->o, q->d, q->tmin, limit, &t, n) || !better(q, t, id, -1)) return;
    q->best_object = id, q->best_triangle = -1, q->best_t = t;
    memcpy(q->n, n, sizeof n);
    struct RTCRayHit *rh = (struct RTCRayHit *)args->rayhit; /* N = 1: the plain layout */
    rh->ray.tfar = float_up(t);
    rh->hit.geomID = (unsigned)id;
    rh->hit.primID = 0;
    rh->hit.u = rh->hit.v = 0;
    rh->hit.Ng_x = (float)n[0], rh->hit.Ng_y = (float)n[1], rh->hit.Ng_z = (float)n[2];
    rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

static void user_occluded(const struct RTCOccludedFunctionNArguments *args)
{
    query *q = (query *)args->context;
    if (args->N != 1 || !args->valid[0]) return;
    int id = (int)args->geomID;
    if (id == q->skip_object && q->skip_triangle < 0) return;
    ++q->tests;
    double t;
    if (geom_intersect(&q->a->objects[id], q->o, q->d, q->tmin, q->tmax, &t, NULL))
        ((struct RTCRay *)args->ray)->tfar = -INFINITY; /* N = 1; Embree's mark of occlusion */
}

/* ---- meshes: triangle geometry, hits recomputed in double ------------------------------ */

/* Distance and barycentric weights of the double ray on triangle k of object id, given that
 * Embree's float ray hit it. If the double ray passes just outside the triangle (it runs
 * within float rounding of an edge Embree's ray crossed), the weights are clamped onto the
 * triangle and the distance is that of its plane: a crack never opens between triangles. */
static double refine(const query *q, int id, int k, double *b1, double *b2)
{
    const geom_object *g = &q->a->objects[id];
    double lo[3], ld[3], t;
    geom_xform_point(g->xf.inv, q->o, lo);
    geom_xform_vector(g->xf.inv, q->d, ld);
    if (geom_triangle_intersect(g, k, lo, ld, -INFINITY, INFINITY, &t, b1, b2)) return t;
    const mesh *m = g->mesh;
    double p[3][3], e1[3], e2[3], s[3], nrm[3];
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 3; ++i)
            p[c][i] = m->position[3 * (size_t)m->tri[3 * (size_t)k + c] + i];
    for (int i = 0; i < 3; ++i) e1[i] = p[1][i] - p[0][i], e2[i] = p[2][i] - p[0][i];
    nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
    nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
    nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double den = geom_dot(nrm, ld);
    if (den == 0) return NAN;
    for (int i = 0; i < 3; ++i) s[i] = p[0][i] - lo[i];
    t = geom_dot(nrm, s) / den;
    /* weights of the plane point by areas, then clamped onto the triangle */
    double x[3], c1[3], c2[3], nn = geom_dot(nrm, nrm);
    for (int i = 0; i < 3; ++i) x[i] = lo[i] + t * ld[i] - p[0][i];
    c1[0] = x[1] * e2[2] - x[2] * e2[1];
    c1[1] = x[2] * e2[0] - x[0] * e2[2];
    c1[2] = x[0] * e2[1] - x[1] * e2[0];
    c2[0] = e1[1] * x[2] - e1[2] * x[1];
    c2[1] = e1[2] * x[0] - e1[0] * x[2];
    c2[2] = e1[0] * x[1] - e1[1] * x[0];
    double u = fmax(0.0, geom_dot(c1, nrm) / nn), v = fmax(0.0, geom_dot(c2, nrm) / nn);
    if (u + v > 1) u /= u + v, v = 1 - u;
    *b1 = u, *b2 = v;
    return t;
}

static void mesh_filter_intersect(const struct RTCFilterFunctionNArguments *args)
{
    query *q = (query *)args->context;
    if (args->N != 1 || !args->valid[0]) return;
    const struct RTCHit *h = (const struct RTCHit *)args->hit; /* N = 1: the plain layout */
    int id = (int)h->geomID, k = (int)h->primID;
    double b1, b2, t = refine(q, id, k, &b1, &b2);
    if (!(t > q->tmin && t < q->tmax) || !better(q, t, id, k)) {
        args->valid[0] = 0;
        return;
    }
    q->best_object = id, q->best_triangle = k, q->best_t = t, q->b1 = b1, q->b2 = b2;
    /* Embree sets tfar to its own float distance; it may sit a rounding below t, which only
     * prunes candidates that could not win by more than that rounding. */
}

static void mesh_filter_occluded(const struct RTCFilterFunctionNArguments *args)
{
    query *q = (query *)args->context;
    if (args->N != 1 || !args->valid[0]) return;
    const struct RTCHit *h = (const struct RTCHit *)args->hit; /* N = 1: the plain layout */
    int id = (int)h->geomID, k = (int)h->primID;
    if (id == q->skip_object && (q->skip_triangle < 0 || k == q->skip_triangle)) {
        args->valid[0] = 0;
        return;
    }
    double b1, b2, t = refine(q, id, k, &b1, &b2);
    if (!(t > q->tmin && t < q->tmax)) args->valid[0] = 0;
}

/* ---- building ---------------------------------------------------------------------------- */

static int add_user(accel *a, int id, float *box, double reach)
{
    const geom_object *g = &a->objects[id];
    double pad = 1e-6 * fmax(reach, sqrt(geom_dot(g->center, g->center)) + g->bound);
    for (int c = 0; c < 3; ++c) {
        box[c] = float_down(g->center[c] - g->bound - pad);
        box[3 + c] = float_up(g->center[c] + g->bound + pad);
    }
    RTCGeometry geo = rtcNewGeometry(a->device, RTC_GEOMETRY_TYPE_USER);
    if (!geo) return -1;
    rtcSetGeometryUserPrimitiveCount(geo, 1);
    rtcSetGeometryUserData(geo, box);
    rtcSetGeometryBoundsFunction(geo, user_bounds, NULL);
    rtcSetGeometryIntersectFunction(geo, user_intersect);
    rtcSetGeometryOccludedFunction(geo, user_occluded);
    rtcCommitGeometry(geo);
    rtcAttachGeometryByID(a->scene, geo, (unsigned)id);
    rtcReleaseGeometry(geo);
    return 0;
}

static int add_mesh(accel *a, int id)
{
    const geom_object *g = &a->objects[id];
    const mesh *m = g->mesh;
    RTCGeometry geo = rtcNewGeometry(a->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!geo) return -1;
    float *v = rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), (size_t)m->vertex_count);
    /* The file's triangles as they are (non-negative indices): shared, not copied. */
    rtcSetSharedGeometryBuffer(geo, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m->tri, 0,
                               3 * sizeof(unsigned), (size_t)m->triangle_count);
    if (!v) {
        rtcReleaseGeometry(geo);
        return -1;
    }
    for (size_t i = 0; i < (size_t)m->vertex_count; ++i) {
        double p[3] = {m->position[3 * i], m->position[3 * i + 1], m->position[3 * i + 2]}, w[3];
        geom_xform_point(g->xf.m, p, w);
        v[3 * i] = (float)w[0], v[3 * i + 1] = (float)w[1], v[3 * i + 2] = (float)w[2];
    }
    rtcSetGeometryIntersectFilterFunction(geo, mesh_filter_intersect);
    rtcSetGeometryOccludedFilterFunction(geo, mesh_filter_occluded);
    rtcCommitGeometry(geo);
    rtcAttachGeometryByID(a->scene, geo, (unsigned)id);
    rtcReleaseGeometry(geo);
    return 0;
}

void accel_release(accel *a)
{
    if (!a) return;
    if (a->scene) rtcReleaseScene(a->scene);
    if (a->device) rtcReleaseDevice(a->device);
    free(a);
}

int accel_build(const geom_object *objects, int count, double reach, accel **out, char *err,
                size_t err_size)
{
    *out = NULL;
    /* the accel, then one float box per analytic object (the bounds callback's data) */
    accel *a = calloc(1, sizeof *a + 6 * sizeof(float) * (size_t)(count > 0 ? count : 1));
    if (!a) {
        snprintf(err, err_size, "out of memory");
        return -1;
    }
    float *boxes = (float *)(a + 1);
    a->objects = objects;
    a->count = count;
    a->device = rtcNewDevice(NULL);
    if (!a->device) {
        snprintf(err, err_size, "Embree: cannot create a device (error %d)",
                 (int)rtcGetDeviceError(NULL));
        free(a);
        return -1;
    }
    rtcSetDeviceErrorFunction(a->device, on_error, a);
    rtcSetDeviceMemoryMonitorFunction(a->device, on_memory, a);
    a->scene = rtcNewScene(a->device);
    if (a->scene) {
        /* robust: no traversal shortcut that could let a ray slip between triangles */
        rtcSetSceneFlags(a->scene, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(a->scene, RTC_BUILD_QUALITY_HIGH);
        for (int i = 0; i < count && !a->error[0]; ++i) {
            int st = objects[i].shape == SCENE_MESH ? add_mesh(a, i)
                                                    : add_user(a, i, boxes + 6 * (size_t)i, reach);
            if (st && !a->error[0]) snprintf(a->error, sizeof a->error, "Embree: out of memory");
        }
        if (!a->error[0]) rtcCommitScene(a->scene);
    }
    if (a->error[0] || !a->scene) {
        snprintf(err, err_size, "%s", a->error[0] ? a->error : "Embree: cannot create a scene");
        accel_release(a);
        return -1;
    }
    *out = a;
    return 0;
}

static void query_init(query *q, const accel *a, const double o[3], const double d[3], double tmin,
                       double tmax)
{
    rtcInitIntersectContext(&q->ctx);
    q->a = a;
    memcpy(q->o, o, sizeof q->o);
    memcpy(q->d, d, sizeof q->d);
    q->tmin = tmin, q->tmax = tmax;
    q->skip_object = q->skip_triangle = -1;
    q->best_object = q->best_triangle = -1;
    q->best_t = tmax, q->b1 = q->b2 = 0;
    q->tests = 0;
}

static void float_ray(const query *q, struct RTCRay *r)
{
    r->org_x = (float)q->o[0], r->org_y = (float)q->o[1], r->org_z = (float)q->o[2];
    r->dir_x = (float)q->d[0], r->dir_y = (float)q->d[1], r->dir_z = (float)q->d[2];
    /* the float interval holds the double one */
    r->tnear = q->tmin > 0 ? float_down(q->tmin) : 0.0f;
    r->tfar = isinf(q->tmax) ? INFINITY : float_up(q->tmax);
    r->time = 0;
    r->mask = 0xffffffffu;
    r->id = 0;
    r->flags = 0;
}

int accel_intersect(const accel *a, const double o[3], const double d[3], double tmin, double tmax,
                    accel_hit *hit, unsigned long long *tests)
{
    query q;
    query_init(&q, a, o, d, tmin, tmax);
    struct RTCRayHit rh;
    float_ray(&q, &rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(a->scene, &q.ctx, &rh);
    if (tests) *tests += q.tests;
    memset(hit, 0, sizeof *hit);
    hit->object = q.best_object;
    hit->triangle = q.best_triangle;
    if (q.best_object < 0) return 0;
    hit->t = q.best_t;
    if (q.best_triangle < 0) {
        memcpy(hit->n, q.n, sizeof hit->n);
        memcpy(hit->ng, q.n, sizeof hit->ng);
        return 1;
    }
    const geom_object *g = &a->objects[q.best_object];
    double ld[3];
    geom_mesh_hit mh;
    geom_xform_vector(g->xf.inv, d, ld);
    geom_triangle_normals(g, q.best_triangle, q.b1, q.b2, ld, &mh);
    geom_xform_normal(&g->xf, mh.n, hit->n);
    geom_xform_normal(&g->xf, mh.ng, hit->ng);
    hit->b1 = q.b1, hit->b2 = q.b2;
    return 1;
}

int accel_occluded(const accel *a, const double o[3], const double d[3], double tmin, double tmax,
                   int skip_object, int skip_triangle, unsigned long long *tests)
{
    query q;
    query_init(&q, a, o, d, tmin, tmax);
    q.skip_object = skip_object;
    q.skip_triangle = skip_object >= 0 ? skip_triangle : -1;
    struct RTCRay r;
    float_ray(&q, &r);
    rtcOccluded1(a->scene, &q.ctx, &r);
    if (tests) *tests += q.tests;
    return r.tfar == -INFINITY;
}

size_t accel_bytes(const accel *a)
{
    long long b = __atomic_load_n(&a->bytes, __ATOMIC_RELAXED);
    return b > 0 ? (size_t)b : 0;
}
