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
 * A second kind of scene holds the objects' bounding balls (accel_balls), for the effect
 * plan's conservative questions (plan.c: can anything block a light from an object?), so
 * that the plan costs a query per object instead of a test per pair of objects.
 *
 * PUBLIC FUNCTIONS
 *   accel_build      the Embree scene of an array of objects (geom.h)
 *   accel_intersect  closest hit along a ray
 *   accel_intersect_from  closest hits of many rays from one point (camera rays): a stream
 *   accel_occluded   any hit along a segment (shadow rays), optionally ignoring one triangle
 *                    or one object
 *   accel_bytes      memory Embree holds for the scene
 *   accel_release    free it
 *   accel_balls_build    the bounding balls of an accel's objects, each grown by a radius
 *   accel_balls_capsule  does some ball meet a capsule around a segment or a ray?
 *   accel_balls_release  free them
 */
#ifndef ABRDF_ACCEL_H
#define ABRDF_ACCEL_H

#include <stddef.h>
#include "geom.h"

typedef struct accel accel;

typedef struct accel_hit {
    int object;    /* index into the objects, -1 for no hit */
    int triangle;  /* meshes: the triangle; analytic primitives: -1 */
    double t;      /* ray parameter (d need not be unit) */
    double n[3];   /* world shading normal, unit (meshes: interpolated when smooth, facing
                      the ray's side) */
    double ng[3];  /* world geometric normal, unit (analytic primitives: n) */
    double b1, b2; /* meshes: barycentric weights of corners 1 and 2 */
} accel_hit;

/* Build and commit. objects must outlive the accel. reach bounds the distance from the
 * world origin of every ray origin the queries will use (e.g. the camera) and of the scene:
 * user-geometry bounds are padded by 1e-6 of it, far above the float rounding of the ray
 * Embree traverses with (6e-8 of it), so the exact double-precision hit is never culled.
 * threads: Embree's build threads (0: every core). Returns 0, or -1 with a message. */
int accel_build(const geom_object *objects, int count, double reach, int threads, accel **out,
                char *err, size_t err_size);
void accel_release(accel *a);

/* Closest hit of o + t d, t in (tmin, tmax). Returns 1 (hit filled) or 0 (hit->object = -1).
 * tests (may be NULL) is increased by the exact intersector calls made on analytic objects. */
int accel_intersect(const accel *a, const double o[3], const double d[3], double tmin, double tmax,
                    accel_hit *hit, unsigned long long *tests);
/* accel_intersect for n rays o + t (dx[k], dy[k], dz[k]), handed to Embree as coherent
 * streams of ACCEL_STREAM (rtcIntersect1M: it traverses them in packets). The hits are those
 * accel_intersect finds for each ray on its own, to the rounding noted at accel_hit's
 * neighbouring triangles. */
#define ACCEL_STREAM 64
void accel_intersect_from(const accel *a, const double o[3], int n, const double *dx,
                          const double *dy, const double *dz, double tmin, double tmax,
                          accel_hit *hits, unsigned long long *tests);
/* Is o + t d blocked for some t in (tmin, tmax)? skip_object >= 0 with skip_triangle < 0
 * ignores that whole object (a convex solid cannot shadow its own lit side); with
 * skip_triangle >= 0 only that triangle of it (the one a shadow ray leaves). */
int accel_occluded(const accel *a, const double o[3], const double d[3], double tmin, double tmax,
                   int skip_object, int skip_triangle, unsigned long long *tests);

/* Bytes Embree allocated for the scene (BVH and buffers), from its memory monitor. */
size_t accel_bytes(const accel *a);

/* The bounding balls (geom_object center, bound) of a's objects, each grown by `grow`, in a
 * scene of their own on a's device (a must outlive it). 0, or -1 (no memory, Embree error). */
typedef struct accel_balls accel_balls;
int accel_balls_build(const accel *a, double grow, accel_balls **out);
void accel_balls_release(accel_balls *b);
/* Does the ball of some object j != skip meet the capsule of radius r (r <= grow) around
 * c + s d, s in [0, tmax] (tmax may be infinite: a half-infinite capsule)? Exact in double
 * (geom_segment_distance(center_j, c, d, tmax) <= r + bound_j); Embree finds the candidates
 * as the balls whose grown box the axis crosses. */
int accel_balls_capsule(const accel_balls *b, const double c[3], const double d[3], double tmax,
                        double r, int skip);

#endif
