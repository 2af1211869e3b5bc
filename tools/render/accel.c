/* accel.c - the Embree scene (accel.h). Embree traverses with a float copy of the ray; the
 * query's double-precision ray travels in the intersect context, which every callback
 * reads, and the callbacks keep the closest hit in double there. Embree's own ray.tfar only
 * prunes the traversal: it is kept at or just above the best distance found.
 *
 * Layout: geometry 0 is one user geometry whose primitive k is the k-th analytic object (one
 * geometry for all of them: 10^5 objects cost one Embree object, not 10^5); geometry g >= 1
 * is the triangle geometry of one mesh object. Tables map both back to object indices. */
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
    int user_count;   /* analytic objects: primitives of geometry 0 */
    int *user_object; /* primitive k of geometry 0 -> object index */
    float *user_box;  /* its bounds: lower x, y, z, upper x, y, z */
    int *mesh_object; /* geometry g >= 1 -> object index (mesh_object[g]) */
    double reach;
    long long bytes; /* Embree's allocations now (memory monitor) */
    char error[256]; /* Embree's first error message */
};

/* One ray of a query, in double precision, with its closest hit so far. */
typedef struct lane {
    double o[3], d[3], tmin, tmax;
    int best_object, best_triangle; /* closest so far (-1: none) */
    double best_t, b1, b2;
    double n[3]; /* analytic winner: its object-space normal (transformed once, at the end) */
} lane;

/* One query of one ray or a stream of them. Embree passes a pointer to ctx to every
 * callback, so ctx comes first; a callback finds its ray's lane by the Embree ray's id. */
typedef struct query {
    struct RTCIntersectContext ctx;
    const accel *a;
    lane *lanes;
    int skip_object, skip_triangle; /* occlusion */
    unsigned long long tests;
} query;

/* Fields of lane i of N in Embree's structure-of-arrays rays and hits (rtcore_ray.h's
 * RTCRayN and RTCHitN layouts, which are C++ accessors there); N = 1 is RTCRay/RTCHit. */
#define ACCEL_RAY_TFAR(ray, N, i) (((float *)(ray))[8 * (N) + (i)])
#define ACCEL_RAY_ID(ray, N, i) (((const unsigned *)(ray))[10 * (N) + (i)])
#define ACCEL_HIT_PRIM(hit, N, i) (((const unsigned *)(hit))[5 * (N) + (i)])
#define ACCEL_HIT_GEOM(hit, N, i) (((const unsigned *)(hit))[6 * (N) + (i)])

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
static int better(const lane *q, double t, int object, int triangle)
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

/* Float box holding [lo, hi] grown by the padding that keeps a float ray's hit: 1e-6 of the
 * reach (or of `far`, the farthest point of the object from the origin, if larger), far
 * above the float rounding of a ray (6e-8 of it). */
static void float_box(const double lo[3], const double hi[3], double far, double reach,
                      float box[6])
{
    double pad = 1e-6 * fmax(reach, far);
    for (int k = 0; k < 3; ++k) {
        box[k] = float_down(lo[k] - pad);
        box[3 + k] = float_up(hi[k] + pad);
    }
}

static void box_bounds(const struct RTCBoundsFunctionArguments *args)
{
    const float *box = (const float *)args->geometryUserPtr + 6 * (size_t)args->primID;
    struct RTCBounds *b = args->bounds_o;
    b->lower_x = box[0], b->lower_y = box[1], b->lower_z = box[2];
    b->upper_x = box[3], b->upper_y = box[4], b->upper_z = box[5];
}

/* ---- analytic primitives: user geometry ----------------------------------------------- */

/* The exact intersector of analytic object g on a lane's ray, up to tmax: the bounding-ball
 * test, then the shape in object space (geom_intersect, but the normal stays in object
 * space: only the closest hit's is transformed). */
static int user_hit(const geom_object *g, const lane *q, double tmax, double *t, double n[3])
{
    if (!geom_hits_bound(g, q->o, q->d, q->tmin, tmax)) return 0;
    double lo[3], ld[3];
    geom_xform_point(g->xf.inv, q->o, lo);
    geom_xform_vector(g->xf.inv, q->d, ld);
    return geom_intersect_local(g, lo, ld, q->tmin, tmax, t, n);
}

static void user_intersect(const struct RTCIntersectFunctionNArguments *args)
{
    query *qu = (query *)args->context;
    unsigned N = args->N;
    int id = qu->a->user_object[args->primID];
    const geom_object *g = &qu->a->objects[id];
    float *ray = (float *)args->rayhit, *hit = ray + 12 * N; /* RTCRayHitN: rays, then hits */
    for (unsigned i = 0; i < N; ++i) {
        if (!args->valid[i]) continue;
        lane *q = &qu->lanes[ACCEL_RAY_ID(ray, N, i)];
        ++qu->tests;
        /* Up to the best distance; an equal distance still wins for an earlier object. */
        double limit = q->best_object < 0    ? q->tmax
                       : id < q->best_object ? nextafter(q->best_t, INFINITY)
                                             : q->best_t;
        double t, n[3];
        if (!user_hit(g, q, limit, &t, n) || !better(q, t, id, -1)) continue;
        q->best_object = id, q->best_triangle = -1, q->best_t = t;
        memcpy(q->n, n, sizeof n);
        ACCEL_RAY_TFAR(ray, N, i) = float_up(t);
        /* u, v, primID, geomID, instID (Ng unused): the hit lane of RTCHitN */
        hit[3 * N + i] = hit[4 * N + i] = 0;
        ((unsigned *)hit)[5 * N + i] = args->primID;
        ((unsigned *)hit)[6 * N + i] = args->geomID;
        ((unsigned *)hit)[7 * N + i] = RTC_INVALID_GEOMETRY_ID; /* instID */
    }
}

static void user_occluded(const struct RTCOccludedFunctionNArguments *args)
{
    query *qu = (query *)args->context;
    unsigned N = args->N;
    int id = qu->a->user_object[args->primID];
    if (id == qu->skip_object) return;
    for (unsigned i = 0; i < N; ++i) {
        if (!args->valid[i]) continue;
        const lane *q = &qu->lanes[ACCEL_RAY_ID(args->ray, N, i)];
        ++qu->tests;
        double t, n[3];
        if (user_hit(&qu->a->objects[id], q, q->tmax, &t, n))
            ACCEL_RAY_TFAR(args->ray, N, i) = -INFINITY; /* Embree's mark of occlusion */
    }
}

/* ---- meshes: triangle geometry, hits recomputed in double ------------------------------ */

/* Distance and barycentric weights of the double ray on triangle k of object id, given that
 * Embree's float ray hit it. If the double ray passes just outside the triangle (it runs
 * within float rounding of an edge Embree's ray crossed), the weights are clamped onto the
 * triangle and the distance is that of its plane: a crack never opens between triangles. */
static double refine(const accel *a, const lane *q, int id, int k, double *b1, double *b2)
{
    const geom_object *g = &a->objects[id];
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
    query *qu = (query *)args->context;
    unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (!args->valid[i]) continue;
        lane *q = &qu->lanes[ACCEL_RAY_ID(args->ray, N, i)];
        int id = qu->a->mesh_object[ACCEL_HIT_GEOM(args->hit, N, i)];
        int k = (int)ACCEL_HIT_PRIM(args->hit, N, i);
        ++qu->tests;
        double b1, b2, t = refine(qu->a, q, id, k, &b1, &b2);
        if (!(t > q->tmin && t < q->tmax) || !better(q, t, id, k)) {
            args->valid[i] = 0;
            continue;
        }
        q->best_object = id, q->best_triangle = k, q->best_t = t, q->b1 = b1, q->b2 = b2;
        /* Embree sets tfar to its own float distance; it may sit a rounding below t, which
         * only prunes candidates that could not win by more than that rounding. */
    }
}

static void mesh_filter_occluded(const struct RTCFilterFunctionNArguments *args)
{
    query *qu = (query *)args->context;
    unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (!args->valid[i]) continue;
        const lane *q = &qu->lanes[ACCEL_RAY_ID(args->ray, N, i)];
        int id = qu->a->mesh_object[ACCEL_HIT_GEOM(args->hit, N, i)];
        int k = (int)ACCEL_HIT_PRIM(args->hit, N, i);
        if (id == qu->skip_object && (qu->skip_triangle < 0 || k == qu->skip_triangle)) {
            args->valid[i] = 0;
            continue;
        }
        ++qu->tests;
        double b1, b2, t = refine(qu->a, q, id, k, &b1, &b2);
        if (!(t > q->tmin && t < q->tmax)) args->valid[i] = 0;
    }
}

/* ---- building ---------------------------------------------------------------------------- */

static int add_users(accel *a)
{
    if (a->user_count == 0) return 0;
    for (int k = 0; k < a->user_count; ++k) {
        const geom_object *g = &a->objects[a->user_object[k]];
        double lo[3], hi[3];
        geom_world_box(g, lo, hi);
        float_box(lo, hi, sqrt(geom_dot(g->center, g->center)) + g->bound, a->reach,
                  a->user_box + 6 * (size_t)k);
    }
    RTCGeometry geo = rtcNewGeometry(a->device, RTC_GEOMETRY_TYPE_USER);
    if (!geo) return -1;
    rtcSetGeometryUserPrimitiveCount(geo, (unsigned)a->user_count);
    rtcSetGeometryUserData(geo, a->user_box);
    rtcSetGeometryBoundsFunction(geo, box_bounds, NULL);
    rtcSetGeometryIntersectFunction(geo, user_intersect);
    rtcSetGeometryOccludedFunction(geo, user_occluded);
    rtcCommitGeometry(geo);
    rtcAttachGeometryByID(a->scene, geo, 0);
    rtcReleaseGeometry(geo);
    return 0;
}

static int add_mesh(accel *a, int id, unsigned geom_id)
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
    rtcAttachGeometryByID(a->scene, geo, geom_id);
    rtcReleaseGeometry(geo);
    return 0;
}

void accel_release(accel *a)
{
    if (!a) return;
    if (a->scene) rtcReleaseScene(a->scene);
    if (a->device) rtcReleaseDevice(a->device);
    free(a->user_object), free(a->user_box), free(a->mesh_object);
    free(a);
}

int accel_build(const geom_object *objects, int count, double reach, int threads, accel **out,
                char *err, size_t err_size)
{
    *out = NULL;
    accel *a = calloc(1, sizeof *a);
    size_t n = (size_t)(count > 0 ? count : 1);
    if (a) {
        a->user_object = malloc(n * sizeof *a->user_object);
        a->user_box = malloc(6 * n * sizeof *a->user_box);
        a->mesh_object = malloc((n + 1) * sizeof *a->mesh_object);
    }
    if (!a || !a->user_object || !a->user_box || !a->mesh_object) {
        accel_release(a);
        snprintf(err, err_size, "out of memory");
        return -1;
    }
    a->objects = objects;
    a->count = count;
    a->reach = reach;
    char config[64] = "";
    if (threads > 0) snprintf(config, sizeof config, "threads=%d", threads);
    a->device = rtcNewDevice(config);
    if (!a->device) {
        snprintf(err, err_size, "Embree: cannot create a device (error %d)",
                 (int)rtcGetDeviceError(NULL));
        accel_release(a);
        return -1;
    }
    rtcSetDeviceErrorFunction(a->device, on_error, a);
    rtcSetDeviceMemoryMonitorFunction(a->device, on_memory, a);
    a->scene = rtcNewScene(a->device);
    if (a->scene) {
        /* robust: no traversal shortcut that could let a ray slip between triangles */
        rtcSetSceneFlags(a->scene, RTC_SCENE_FLAG_ROBUST);
        unsigned meshes = 0;
        for (int i = 0; i < count; ++i)
            if (objects[i].shape != SCENE_MESH) a->user_object[a->user_count++] = i;
        a->mesh_object[0] = -1;
        if (add_users(a) && !a->error[0]) snprintf(a->error, sizeof a->error, "Embree: no memory");
        for (int i = 0; i < count && !a->error[0]; ++i) {
            if (objects[i].shape != SCENE_MESH) continue;
            a->mesh_object[++meshes] = i;
            if (add_mesh(a, i, meshes) && !a->error[0])
                snprintf(a->error, sizeof a->error, "Embree: out of memory");
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

static void lane_init(lane *q, const double o[3], const double d[3], double tmin, double tmax)
{
    memcpy(q->o, o, sizeof q->o);
    memcpy(q->d, d, sizeof q->d);
    q->tmin = tmin, q->tmax = tmax;
    q->best_object = q->best_triangle = -1;
    q->best_t = tmax, q->b1 = q->b2 = 0;
}

static void query_init(query *q, const accel *a, lane *lanes, int coherent)
{
    rtcInitIntersectContext(&q->ctx);
    if (coherent) q->ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    q->a = a;
    q->lanes = lanes;
    q->skip_object = q->skip_triangle = -1;
    q->tests = 0;
}

static void float_ray(const lane *q, unsigned id, struct RTCRay *r)
{
    r->org_x = (float)q->o[0], r->org_y = (float)q->o[1], r->org_z = (float)q->o[2];
    r->dir_x = (float)q->d[0], r->dir_y = (float)q->d[1], r->dir_z = (float)q->d[2];
    /* the float interval holds the double one */
    r->tnear = q->tmin > 0 ? float_down(q->tmin) : 0.0f;
    r->tfar = isinf(q->tmax) ? INFINITY : float_up(q->tmax);
    r->time = 0;
    r->mask = 0xffffffffu;
    r->id = id;
    r->flags = 0;
}

/* The hit of a lane whose query is done. */
static int lane_hit(const accel *a, const lane *q, accel_hit *hit)
{
    memset(hit, 0, sizeof *hit);
    hit->object = q->best_object;
    hit->triangle = q->best_triangle;
    if (q->best_object < 0) return 0;
    const geom_object *g = &a->objects[q->best_object];
    hit->t = q->best_t;
    if (q->best_triangle < 0) {
        geom_xform_normal(&g->xf, q->n, hit->n);
        memcpy(hit->ng, hit->n, sizeof hit->ng);
        return 1;
    }
    double ld[3];
    geom_mesh_hit mh;
    geom_xform_vector(g->xf.inv, q->d, ld);
    geom_triangle_normals(g, q->best_triangle, q->b1, q->b2, ld, &mh);
    geom_xform_normal(&g->xf, mh.n, hit->n);
    geom_xform_normal(&g->xf, mh.ng, hit->ng);
    hit->b1 = q->b1, hit->b2 = q->b2;
    return 1;
}

int accel_intersect(const accel *a, const double o[3], const double d[3], double tmin, double tmax,
                    accel_hit *hit, unsigned long long *tests)
{
    lane ln;
    query q;
    lane_init(&ln, o, d, tmin, tmax);
    query_init(&q, a, &ln, 0);
    struct RTCRayHit rh;
    float_ray(&ln, 0, &rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(a->scene, &q.ctx, &rh);
    if (tests) *tests += q.tests;
    return lane_hit(a, &ln, hit);
}

void accel_intersect_from(const accel *a, const double o[3], int n, const double *dx,
                          const double *dy, const double *dz, double tmin, double tmax,
                          accel_hit *hits, unsigned long long *tests)
{
    lane ln[ACCEL_STREAM];
    struct RTCRayHit rh[ACCEL_STREAM];
    for (int s = 0; s < n; s += ACCEL_STREAM) {
        int m = n - s < ACCEL_STREAM ? n - s : ACCEL_STREAM;
        query q;
        query_init(&q, a, ln, 1);
        for (int r = 0; r < m; ++r) {
            double d[3] = {dx[s + r], dy[s + r], dz[s + r]};
            lane_init(&ln[r], o, d, tmin, tmax);
            float_ray(&ln[r], (unsigned)r, &rh[r].ray);
            rh[r].hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh[r].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect1M(a->scene, &q.ctx, rh, (unsigned)m, sizeof rh[0]);
        if (tests) *tests += q.tests;
        for (int r = 0; r < m; ++r) lane_hit(a, &ln[r], &hits[s + r]);
    }
}

int accel_occluded(const accel *a, const double o[3], const double d[3], double tmin, double tmax,
                   int skip_object, int skip_triangle, unsigned long long *tests)
{
    lane ln;
    query q;
    lane_init(&ln, o, d, tmin, tmax);
    query_init(&q, a, &ln, 0);
    q.skip_object = skip_object;
    q.skip_triangle = skip_object >= 0 ? skip_triangle : -1;
    struct RTCRay r;
    float_ray(&ln, 0, &r);
    rtcOccluded1(a->scene, &q.ctx, &r);
    if (tests) *tests += q.tests;
    return r.tfar == -INFINITY;
}

size_t accel_bytes(const accel *a)
{
    long long b = __atomic_load_n(&a->bytes, __ATOMIC_RELAXED);
    return b > 0 ? (size_t)b : 0;
}

/* ---- the objects' bounding balls, for the effect plan's shadow decisions ----------------- */

struct accel_balls {
    const accel *a;
    RTCScene scene;
    double grow;
    float *box; /* per object: its ball grown by `grow`, as a float box */
};

/* One capsule query; ctx first (see query). */
typedef struct capsule_query {
    struct RTCIntersectContext ctx;
    const accel_balls *b;
    double c[3], d[3], tmax, r;
    int skip;
} capsule_query;

static void ball_occluded(const struct RTCOccludedFunctionNArguments *args)
{
    capsule_query *q = (capsule_query *)args->context;
    if (args->N != 1 || !args->valid[0]) return;
    int j = (int)args->primID;
    if (j == q->skip) return;
    const geom_object *g = &q->b->a->objects[j];
    if (geom_segment_distance(g->center, q->c, q->d, q->tmax) <= q->r + g->bound)
        ((struct RTCRay *)args->ray)->tfar = -INFINITY;
}

void accel_balls_release(accel_balls *b)
{
    if (!b) return;
    if (b->scene) rtcReleaseScene(b->scene);
    free(b->box);
    free(b);
}

int accel_balls_build(const accel *a, double grow, accel_balls **out)
{
    *out = NULL;
    accel_balls *b = calloc(1, sizeof *b);
    if (!b) return -1;
    b->a = a;
    b->grow = grow;
    b->box = malloc(6 * (size_t)(a->count > 0 ? a->count : 1) * sizeof *b->box);
    b->scene = rtcNewScene(a->device);
    if (!b->box || !b->scene) {
        accel_balls_release(b);
        return -1;
    }
    for (int j = 0; j < a->count; ++j) {
        const geom_object *g = &a->objects[j];
        double r = g->bound + grow, lo[3], hi[3];
        for (int k = 0; k < 3; ++k) lo[k] = g->center[k] - r, hi[k] = g->center[k] + r;
        float_box(lo, hi, sqrt(geom_dot(g->center, g->center)) + r, a->reach + grow,
                  b->box + 6 * (size_t)j);
    }
    if (a->count > 0) {
        RTCGeometry geo = rtcNewGeometry(a->device, RTC_GEOMETRY_TYPE_USER);
        if (!geo) {
            accel_balls_release(b);
            return -1;
        }
        rtcSetGeometryUserPrimitiveCount(geo, (unsigned)a->count);
        rtcSetGeometryUserData(geo, b->box);
        rtcSetGeometryBoundsFunction(geo, box_bounds, NULL);
        rtcSetGeometryOccludedFunction(geo, ball_occluded);
        rtcCommitGeometry(geo);
        rtcAttachGeometryByID(b->scene, geo, 0);
        rtcReleaseGeometry(geo);
    }
    rtcCommitScene(b->scene);
    if (rtcGetDeviceError(a->device) != RTC_ERROR_NONE) {
        accel_balls_release(b);
        return -1;
    }
    *out = b;
    return 0;
}

int accel_balls_capsule(const accel_balls *b, const double c[3], const double d[3], double tmax,
                        double r, int skip)
{
    capsule_query q;
    rtcInitIntersectContext(&q.ctx);
    q.b = b;
    memcpy(q.c, c, sizeof q.c);
    memcpy(q.d, d, sizeof q.d);
    q.tmax = tmax, q.r = r, q.skip = skip;
    struct RTCRay ray;
    lane ln;
    lane_init(&ln, c, d, 0.0, tmax);
    /* r <= grow: every ball the capsule meets has a grown box the axis crosses */
    float_ray(&ln, 0, &ray);
    rtcOccluded1(b->scene, &q.ctx, &ray);
    return ray.tfar == -INFINITY;
}
