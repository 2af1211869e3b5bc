/* test_accel.c - the Embree scene (accel.h) against the loop it replaces: every object in
 * order, geom.c's exact intersectors, strict `t < best`. Analytic primitives must agree bit
 * for bit (object, distance, normal), and so must mesh hits on the same triangle (Embree
 * finds it in float, accel.c recomputes it in double as the loop does); a hit on the
 * neighbouring triangle across an edge is allowed to rounding, in at most 1 of 1000. Also: occlusion with and without the object or
 * triangle a shadow ray leaves, ties between coincident objects, rebuilds, memory. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel.h"
#include "test_util.h"

#define ABRDF_TEST_PI 3.14159265358979323846

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static double rnd(double lo, double hi)
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return lo + (hi - lo) * (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

/* Rays per check; the sanitizer build sets fewer (the loop it checks against is slow there). */
#ifndef TEST_ACCEL_RAYS
#define TEST_ACCEL_RAYS 8000
#endif

#define ANALYTIC 60
#define COUNT (ANALYTIC + 4) /* + a duplicate primitive, two teapots, a duplicate teapot */

static mesh teapot;
static scene_object so[COUNT];
static geom_object go[COUNT];

static void make_scene(void)
{
    char err[512];
    ck_assert_msg(
        mesh_load_file(SCENES_DIR "/teapot.obj", MESH_MAX_TRIANGLES, &teapot, err, sizeof err) == 0,
        "%s", err);
    for (int i = 0; i < COUNT; ++i) {
        scene_object *o = &so[i];
        memset(o, 0, sizeof *o);
        o->mesh = -1;
        o->shape = (scene_shape)(i % 4);
        o->radius = rnd(0.2, 0.8);
        o->height = o->shape == SCENE_CYLINDER ? rnd(0.2, 1.5) : rnd(0.0, 1.5);
        for (int c = 0; c < 3; ++c) {
            o->size[c] = rnd(0.3, 1.5);
            o->scale[c] = rnd(0.5, 1.6); /* non-uniform: normals use the inverse transpose */
            o->rotate_deg[c] = rnd(-180, 180);
            o->translate[c] = rnd(-5, 5);
        }
    }
    so[ANALYTIC] = so[7]; /* coincident with object 7: the earlier object wins ties */
    for (int i = ANALYTIC + 1; i < COUNT; ++i) {
        so[i].shape = SCENE_MESH;
        so[i].mesh = 0;
        so[i].mesh_data = &teapot;
        so[i].smooth = i != ANALYTIC + 2;
        so[i].scale[0] = so[i].scale[1] = so[i].scale[2] = 0.9;
    }
    so[ANALYTIC + 2].translate[0] = 2.5, so[ANALYTIC + 2].rotate_deg[1] = 40;
    so[ANALYTIC + 3] = so[ANALYTIC + 1]; /* coincident teapot */
    for (int i = 0; i < COUNT; ++i) geom_object_make(&so[i], &go[i]);
}

typedef struct ref_hit {
    int object, triangle;
    double t, n[3];
} ref_hit;

/* The loop over every object the Embree scene stands in for. */
static int brute_intersect(const double o[3], const double d[3], double tmin, ref_hit *h)
{
    h->object = -1;
    double best = INFINITY;
    for (int k = 0; k < COUNT; ++k) {
        const geom_object *g = &go[k];
        if (g->shape != SCENE_MESH) {
            double t, n[3];
            if (geom_intersect(g, o, d, tmin, best, &t, n)) {
                best = t, h->object = k, h->triangle = -1, h->t = t;
                memcpy(h->n, n, sizeof n);
            }
            continue;
        }
        double lo[3], ld[3];
        geom_xform_point(g->xf.inv, o, lo);
        geom_xform_vector(g->xf.inv, d, ld);
        geom_mesh_hit mh;
        if (geom_mesh_intersect_local(g, lo, ld, tmin, best, &mh)) {
            best = mh.t, h->object = k, h->triangle = mh.triangle, h->t = mh.t;
            geom_xform_normal(&g->xf, mh.n, h->n);
        }
    }
    return h->object >= 0;
}

static int brute_occluded(const double o[3], const double d[3], double tmax, int skip)
{
    for (int k = 0; k < COUNT; ++k) {
        double t;
        if (k != skip && geom_intersect(&go[k], o, d, 0.0, tmax, &t, NULL)) return 1;
    }
    return 0;
}

static void random_ray(double o[3], double d[3])
{
    if (rnd(0, 1) < 0.7) { /* from outside toward a point of the scene */
        double th = rnd(0, ABRDF_TEST_PI), ph = rnd(0, 2 * ABRDF_TEST_PI), p[3];
        o[0] = 20 * sin(th) * cos(ph), o[1] = 20 * cos(th), o[2] = 20 * sin(th) * sin(ph);
        for (int c = 0; c < 3; ++c) p[c] = rnd(-4, 4), d[c] = p[c] - o[c];
    } else { /* from inside the scene, any direction, not unit length */
        for (int c = 0; c < 3; ++c) o[c] = rnd(-5, 5), d[c] = rnd(-2, 2);
    }
}

START_TEST(closest_hits_match_the_loop)
{
    rng = 0x9e3779b97f4a7c15ull;
    make_scene();
    accel *a;
    char err[256];
    ck_assert_msg(accel_build(go, COUNT, 40.0, &a, err, sizeof err) == 0, "%s", err);
    int rays = TEST_ACCEL_RAYS, analytic = 0, meshes = 0, other_triangle = 0, ties = 0;
    unsigned long long tests = 0;
    for (int r = 0; r < rays; ++r) {
        double o[3], d[3];
        random_ray(o, d);
        ref_hit ref;
        accel_hit h;
        int hit_ref = brute_intersect(o, d, 0.0, &ref);
        int hit = accel_intersect(a, o, d, 0.0, INFINITY, &h, &tests);
        ck_assert_int_eq(hit, hit_ref);
        ck_assert_int_eq(h.object, ref.object);
        if (!hit) continue;
        ties += ref.object == 7 || ref.object == ANALYTIC + 1;
        if (ref.triangle < 0) {
            ++analytic; /* exact: the same intersector on the same double ray */
            ck_assert_msg(h.t == ref.t && h.triangle == -1, "ray %d: t %.17g vs %.17g", r, h.t,
                          ref.t);
            for (int c = 0; c < 3; ++c) ck_assert(h.n[c] == ref.n[c] && h.ng[c] == ref.n[c]);
            continue;
        }
        ++meshes;
        if (h.triangle == ref.triangle) { /* the same double-precision computation */
            ck_assert_msg(h.t == ref.t, "ray %d: t %.17g vs %.17g", r, h.t, ref.t);
            for (int c = 0; c < 3; ++c) ck_assert(h.n[c] == ref.n[c]);
            continue;
        }
        /* the neighbour across an edge: the same point to rounding */
        ++other_triangle;
        ck_assert_msg(fabs(h.t - ref.t) <= 1e-6 * ref.t, "ray %d: t %.17g vs %.17g", r, h.t, ref.t);
    }
    printf("accel: %d rays, %d analytic hits exact, %d mesh hits (%d on the neighbouring "
           "triangle), %d on a coincident pair, %llu exact tests (%.2f per ray against %d "
           "objects)\n",
           rays, analytic, meshes, other_triangle, ties, tests, (double)tests / rays, COUNT);
    ck_assert(analytic > rays / 5 && meshes > rays / 20 && ties > rays / 100);
    ck_assert(other_triangle <= meshes / 1000);
    /* the BVH prunes: far fewer exact tests than objects per ray */
    ck_assert(tests < (unsigned long long)rays * ANALYTIC / 4);
    ck_assert(accel_bytes(a) > 0);
    accel_release(a);
    mesh_free(&teapot);
}
END_TEST

START_TEST(occlusion_matches_the_loop)
{
    rng = 0x2545f4914f6cdd1dull;
    make_scene();
    accel *a;
    char err[256];
    ck_assert_msg(accel_build(go, COUNT, 40.0, &a, err, sizeof err) == 0, "%s", err);
    int differ = 0, blocked = 0, rays = TEST_ACCEL_RAYS;
    for (int r = 0; r < rays; ++r) {
        double o[3], d[3];
        random_ray(o, d);
        double tmax = rnd(0.2, 1.5);
        int skip = rnd(0, 1) < 0.5 ? (int)rnd(0, ANALYTIC) : -1;
        int ref = brute_occluded(o, d, tmax, skip);
        int got = accel_occluded(a, o, d, 0.0, tmax, skip, -1, NULL);
        blocked += ref;
        differ += ref != got;
    }
    printf("occlusion: %d segments, %d blocked, %d differ\n", rays, blocked, differ);
    ck_assert(blocked > rays / 10 && blocked < rays - rays / 10);
    ck_assert(differ <= rays / 2000); /* only where a float hit lies within rounding of an edge */
    /* A ray leaving a triangle of the teapot along its outward face normal, started just
     * behind it: that triangle blocks it unless it is the one skipped. */
    const geom_object *g = &go[ANALYTIC + 2]; /* the teapot without a double */
    int found = 0;
    for (int k = 0; k < teapot.triangle_count && !found; k += 7) {
        double p[3][3], e1[3], e2[3], fn[3], c[3], pw[3], nw[3], start[3], out[3];
        for (int q = 0; q < 3; ++q)
            for (int x = 0; x < 3; ++x) p[q][x] = teapot.position[3 * teapot.tri[3 * k + q] + x];
        for (int x = 0; x < 3; ++x)
            e1[x] = p[1][x] - p[0][x], e2[x] = p[2][x] - p[0][x],
            c[x] = (p[0][x] + p[1][x] + p[2][x]) / 3;
        fn[0] = e1[1] * e2[2] - e1[2] * e2[1];
        fn[1] = e1[2] * e2[0] - e1[0] * e2[2];
        fn[2] = e1[0] * e2[1] - e1[1] * e2[0];
        geom_xform_point(g->xf.m, c, pw);
        geom_xform_normal(&g->xf, fn, nw);
        for (int x = 0; x < 3; ++x) start[x] = pw[x] - 1e-6 * nw[x], out[x] = pw[x] + 1e-6 * nw[x];
        if (brute_occluded(out, nw, 1e3, -1)) continue; /* something else is in the way */
        found = 1;
        ck_assert(accel_occluded(a, start, nw, 0.0, 1e3, -1, -1, NULL));
        ck_assert(!accel_occluded(a, start, nw, 0.0, 1e3, ANALYTIC + 2, k, NULL));
        ck_assert(accel_occluded(a, start, nw, 0.0, 1e3, ANALYTIC + 2, k + 1, NULL));
    }
    ck_assert(found);
    accel_release(a);
    mesh_free(&teapot);
}
END_TEST

START_TEST(rebuilds_agree)
{
    rng = 0x1234567ull;
    make_scene();
    accel *a, *b;
    char err[256];
    ck_assert(accel_build(go, COUNT, 40.0, &a, err, sizeof err) == 0);
    ck_assert(accel_build(go, COUNT, 40.0, &b, err, sizeof err) == 0);
    for (int r = 0; r < TEST_ACCEL_RAYS / 2; ++r) {
        double o[3], d[3];
        random_ray(o, d);
        accel_hit x, y;
        accel_intersect(a, o, d, 0.0, INFINITY, &x, NULL);
        accel_intersect(b, o, d, 0.0, INFINITY, &y, NULL);
        ck_assert(!memcmp(&x, &y, sizeof x));
    }
    accel_release(a);
    accel_release(b);
    /* an empty scene has nothing to hit */
    ck_assert(accel_build(go, 0, 1.0, &a, err, sizeof err) == 0);
    double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
    accel_hit h;
    ck_assert(!accel_intersect(a, o, d, 0, INFINITY, &h, NULL) && h.object == -1);
    ck_assert(!accel_occluded(a, o, d, 0, INFINITY, -1, -1, NULL));
    accel_release(a);
    mesh_free(&teapot);
}
END_TEST

/* The dense teapot (gen_teapot --segments 128 at test time, argv[1]): over 10^6
 * triangles read, built into Embree and hit like the loop over all of them. */
static const char *dense_path;

START_TEST(dense_teapot)
{
    mesh m;
    char err[512];
    ck_assert_msg(mesh_load_file(dense_path, MESH_MAX_TRIANGLES, &m, err, sizeof err) == 0, "%s",
                  err);
    ck_assert_int_ge(m.triangle_count, 1000000);
    scene_object o;
    memset(&o, 0, sizeof o);
    o.shape = SCENE_MESH, o.mesh_data = &m, o.smooth = 1;
    o.scale[0] = o.scale[1] = o.scale[2] = 1;
    geom_object g;
    geom_object_make(&o, &g);
    accel *a;
    ck_assert_msg(accel_build(&g, 1, 40.0, &a, err, sizeof err) == 0, "%s", err);
    rng = 0x51ed2701ull;
    int hits = 0, same = 0;
    for (int r = 0; r < 64; ++r) {
        double org[3] = {rnd(-8, 8), rnd(-2, 8), 12}, d[3],
               p[3] = {rnd(-3, 3), rnd(0, 3), rnd(-2, 2)};
        for (int c = 0; c < 3; ++c) d[c] = p[c] - org[c];
        accel_hit h;
        geom_mesh_hit ref;
        int got = accel_intersect(a, org, d, 0.0, INFINITY, &h, NULL);
        int want = geom_mesh_intersect_local(&g, org, d, 0.0, INFINITY, &ref);
        ck_assert_int_eq(got, want);
        if (!got) continue;
        ++hits;
        same += h.triangle == ref.triangle;
        ck_assert_msg(fabs(h.t - ref.t) <= 1e-6 * ref.t, "t %.17g vs %.17g", h.t, ref.t);
    }
    printf("dense teapot: %d triangles, %d vertices; Embree %.1f bytes per triangle, the mesh "
           "%.1f; %d of 64 rays hit, %d on the loop's triangle\n",
           m.triangle_count, m.vertex_count, (double)accel_bytes(a) / m.triangle_count,
           (12.0 * m.vertex_count + 12.0 * m.normal_count + 8.0 * m.uv_count +
            36.0 * m.triangle_count) /
               m.triangle_count,
           hits, same);
    ck_assert(hits > 20 && same >= hits - 1);
    accel_release(a);
    mesh_free(&m);
}
END_TEST

int main(int argc, char **argv)
{
    Suite *s = suite_create("accel");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 300);
    if (argc > 1) { /* test_accel DENSE.obj: the dense teapot only */
        dense_path = argv[1];
        tcase_add_test(tc, dense_teapot);
    } else {
        tcase_add_test(tc, closest_hits_match_the_loop);
        tcase_add_test(tc, occlusion_matches_the_loop);
        tcase_add_test(tc, rebuilds_agree);
    }
    suite_add_tcase(s, tc);
    return tu_run(s);
}
