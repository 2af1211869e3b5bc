/* accel.h - the scene's ray queries through Intel Embree 3 (Wald et al., "Embree: A Kernel
 * Framework for Efficient CPU Ray Tracing", ACM TOG 33(4), 2014), the kernel Cycles uses on
 * the CPU. One Embree scene holds every object, committed once:
 *
 *   analytic primitives (sphere, cylinder, capsule, box) are user geometry: Embree's BVH
 *     finds the candidates and the callbacks run geom.c's exact intersectors on the query's
 *     double-precision ray, so hits and normals are bit for bit those of geom_intersect;
 *   meshes are Embree triangle geometry (float vertices in world space); every triangle hit
 *     Embree reports is recomputed in double on the object-space ray (geom.c), which gives
 *     the distance, the barycentric weights and the interpolated normal.
 *
 * Results do not depend on the BVH or on the order Embree visits candidates: the closest hit
 * is the smallest (t, object, triangle) in that order, as a loop over the objects in file
 * order and their triangles in file order with a strict `t < best` finds it.
 *
 * PUBLIC FUNCTIONS
 *   accel_build      the Embree scene of an array of objects (geom.h)
 *   accel_intersect  closest hit along a ray
 *   accel_occluded   any hit along a segment (shadow rays), optionally ignoring one triangle
 *                    or one object
 *   accel_bytes      memory Embree holds for the scene
 *   accel_release    free it
 */
#ifndef ABRDF_ACCEL_H
#define ABRDF_ACCEL_H

#include <stddef.h>
#include "geom.h"

typedef struct accel accel;

typedef struct accel_hit {
    int object;   /* index into the objects, -1 for no hit */
    int triangle; /* meshes: the triangle; analytic primitives: -1 */
    double t;     /* ray parameter (d need not be unit) */
    double n
        [3]; /* world shading normal, unit (meshes: interpolated when smooth, facing the ray's side) */
    double ng[3];  /* world geometric normal, unit (analytic primitives: n) */
    double b1, b2; /* meshes: barycentric weights of corners 1 and 2 */
} accel_hit;

/* Build and commit. objects must outlive the accel. reach bounds the distance from the
 * world origin of every ray origin the queries will use (e.g. the camera) and of the scene:
 * user-geometry bounds are padded by 1e-6 of it, far above the float rounding of the ray
 * Embree traverses with (6e-8 of it), so the exact double-precision hit is never culled.
 * Returns 0, or -1 with a message. */
int accel_build(const geom_object *objects, int count, double reach, accel **out, char *err,
                size_t err_size);
void accel_release(accel *a);

/* Closest hit of o + t d, t in (tmin, tmax). Returns 1 (hit filled) or 0 (hit->object = -1).
 * tests (may be NULL) is increased by the exact intersector calls made on analytic objects. */
int accel_intersect(const accel *a, const double o[3], const double d[3], double tmin, double tmax,
                    accel_hit *hit, unsigned long long *tests);
/* Is o + t d blocked for some t in (tmin, tmax)? skip_object >= 0 with skip_triangle < 0
 * ignores that whole object (a convex solid cannot shadow its own lit side); with
 * skip_triangle >= 0 only that triangle of it (the one a shadow ray leaves). */
int accel_occluded(const accel *a, const double o[3], const double d[3], double tmin, double tmax,
                   int skip_object, int skip_triangle, unsigned long long *tests);

/* Bytes Embree allocated for the scene (BVH and buffers), from its memory monitor. */
size_t accel_bytes(const accel *a);

#endif
