/* geom.h - ray geometry of the built-in renderer: affine transforms, the analytic primitives
 * of the scene format (exact intersections and normals in object space), bounding spheres
 * and the tangent field rules. Everything in double precision. */
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
    geom_xform xf;
    double center[3], bound; /* world-space bounding sphere */
    int convex;              /* a convex solid cannot shadow itself */
} geom_object;

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
 * the frame construction projects it onto the tangent plane). */
void geom_tangent(const scene_object *o, const geom_xform *xf, const double p_world[3],
                  double t_world[3]);

#endif
