/* geom.h - ray geometry of the built-in renderer: affine transforms, the analytic primitives
 * of the scene format (exact intersections and normals in object space), triangle meshes
 * (intersection of one triangle, interpolated normals, tangents from texture coordinates),
 * bounding spheres and the tangent field rules. Everything in double precision.
 *
 * Meshes: a triangle is hit from either side (two-sided, as POV-Ray and Cycles shade them);
 * the normals a hit reports face the side the ray came from. The shading normal of a smooth
 * mesh is the barycentric mix of its corners' unit normals, in object space, then
 * transformed like any normal and normalised: the interpolation POV-Ray's mesh2
 * (Smooth_Mesh_Normal) and Cycles' smooth triangles perform. A flat mesh (smooth=off) uses
 * the face normal. */
#ifndef ABRDF_GEOM_H
#define ABRDF_GEOM_H

#include "scene.h"

typedef struct geom_xform {
    double m[3][4];   /* object -> world (affine) */
    double inv[3][4]; /* world -> object */
} geom_xform;

/* A scene object ready for ray casting. */
typedef struct geom_object {
    scene_shape shape;
    double radius, height, half[3]; /* object-space dimensions (box: half extents) */
    const mesh *mesh;               /* SCENE_MESH: the triangles (object space) */
    int smooth;                     /* SCENE_MESH: interpolated vertex normals */
    geom_xform xf;
    double center[3], bound; /* world-space bounding sphere */
    int convex;              /* a convex solid cannot shadow itself */
} geom_object;

/* A ray's hit on a mesh triangle, in object space. */
typedef struct geom_mesh_hit {
    int triangle;
    double t;      /* ray parameter */
    double b1, b2; /* barycentric weights of corners 1 and 2 (corner 0: 1 - b1 - b2) */
    double n[3];   /* shading normal (not normalised), on the ray's side */
    double ng[3];  /* face normal (not normalised), on the ray's side */
} geom_mesh_hit;

/* Ray epsilon: hits closer than GEOM_T_MIN * scene scale are the surface the ray left. */
#define GEOM_T_MIN 1e-9

static inline double geom_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void geom_xform_make(const scene_object *o, geom_xform *xf);
void geom_object_make(const scene_object *o, geom_object *g);
/* p_out = M p (point) or M v (vector, no translation). */
void geom_xform_point(const double m[3][4], const double p[3], double out[3]);
void geom_xform_vector(const double m[3][4], const double v[3], double out[3]);
/* World normal from an object normal: inverse transpose, normalised. */
void geom_xform_normal(const geom_xform *xf, const double n[3], double out[3]);

/* Closest hit of the object-space ray o + t d with t in (tmin, tmax) (d need not be unit).
 * Returns 1 and sets *t and the outward object-space normal n (not normalised), else 0. */
int geom_intersect_local(const geom_object *g, const double o[3], const double d[3], double tmin,
                         double tmax, double *t, double n[3]);
/* World-space ray against object: bounding sphere test first, then the exact shape. */
int geom_intersect(const geom_object *g, const double o[3], const double d[3], double tmin,
                   double tmax, double *t, double n_world[3]);
/* What every ray from one origin o shares against one object (the camera's rays): o
 * relative to the bounding ball and o in object space. */
typedef struct geom_origin {
    double oc[3];    /* o - centre of the bounding ball */
    double c;        /* |oc|^2 - bound^2 */
    double local[3]; /* o in object space */
} geom_origin;
void geom_origin_make(const geom_object *g, const double o[3], geom_origin *go);
/* geom_intersect for a ray from the origin go was made for, without the per-ray work that
 * depends on the origin only; n_local receives the OBJECT-space normal (not normalised:
 * geom_xform_normal gives the world one, so a closest-hit search transforms only the last). */
int geom_intersect_from(const geom_object *g, const geom_origin *go, const double d[3], double tmin,
                        double tmax, double *t, double n_local[3]);
/* Ray against the bounding sphere only (any overlap of the segment with the ball). */
int geom_hits_bound(const geom_object *g, const double o[3], const double d[3], double tmin,
                    double tmax);

/* Tangent of the object's field rule at world point p, in world space (not normalised;
 * the frame construction projects it onto the tangent plane). The uv rule needs the hit
 * triangle: geom_tangent_uv. */
void geom_tangent(const scene_object *o, const geom_xform *xf, const double p_world[3],
                  double t_world[3]);

/* ---- meshes ------------------------------------------------------------------------- */

/* Ray o + t d, t in (tmin, tmax), against triangle k of the object's mesh (object space),
 * in double precision (Moller and Trumbore 1997). Returns 1 and sets t, b1, b2. */
int geom_triangle_intersect(const geom_object *g, int k, const double o[3], const double d[3],
                            double tmin, double tmax, double *t, double *b1, double *b2);
/* Normals of a hit on triangle k at (b1, b2) seen along direction d (object space). */
void geom_triangle_normals(const geom_object *g, int k, double b1, double b2, const double d[3],
                           geom_mesh_hit *h);
/* Closest hit over every triangle (no acceleration structure: the reference the Embree
 * scene is tested against, accel.h). Object space; returns 1 and fills h. */
int geom_mesh_intersect_local(const geom_object *g, const double o[3], const double d[3],
                              double tmin, double tmax, geom_mesh_hit *h);
/* The uv tangent of triangle k: the direction of increasing u of its texture coordinates
 * (dP/du, constant over the triangle), in world space; zero where the coordinates are
 * degenerate (the frame construction then falls back, abrdf_frame_make). */
void geom_tangent_uv(const geom_object *g, int k, double t_world[3]);

#endif
