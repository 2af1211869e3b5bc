// abrdf_trace.h - the scene format's analytic primitives in OSL (tools/render/geom.c of the
// built-in renderer, same conventions): exact ray intersections and normals of sphere,
// cylinder, capsule and box in object space, affine transforms, tangent field rules.
// Scene shaders written by `abrdf export --cycles` use it to re-trace the pixel-centre
// camera ray and the shadow rays against the exact shapes, so the host's tessellation
// never changes a pixel.
//
// Transforms are 3x4 affine maps stored in the upper rows of an OSL matrix and applied as
// M * p with M[row][col] (not OSL's transform(), which multiplies row vectors).
#ifndef ABRDF_TRACE_H
#define ABRDF_TRACE_H

#include "abrdf_osl.h"

#define ABRDF_SHAPE_SPHERE 0
#define ABRDF_SHAPE_CYLINDER 1
#define ABRDF_SHAPE_CAPSULE 2
#define ABRDF_SHAPE_BOX 3
#define ABRDF_SHAPE_MESH 4 // triangles the host traces (abrdf_hit_object never hits them)

#define ABRDF_TANGENT_U 0
#define ABRDF_TANGENT_V 1
#define ABRDF_TANGENT_RADIAL 2
#define ABRDF_TANGENT_AXIS 3

#define ABRDF_T_INF 1e30

point abrdf_xform_point(matrix m, point p)
{
    return point(m[0][0] * p[0] + m[0][1] * p[1] + m[0][2] * p[2] + m[0][3],
                 m[1][0] * p[0] + m[1][1] * p[1] + m[1][2] * p[2] + m[1][3],
                 m[2][0] * p[0] + m[2][1] * p[1] + m[2][2] * p[2] + m[2][3]);
}
vector abrdf_xform_vector(matrix m, vector v)
{
    return vector(m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
                  m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
                  m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]);
}
// World normal from an object normal: the inverse transpose, normalised.
vector abrdf_xform_normal(matrix inv, vector n)
{
    return normalize(vector(inv[0][0] * n[0] + inv[1][0] * n[1] + inv[2][0] * n[2],
                            inv[0][1] * n[0] + inv[1][1] * n[1] + inv[2][1] * n[2],
                            inv[0][2] * n[0] + inv[1][2] * n[1] + inv[2][2] * n[2]));
}

// Roots of a t^2 + 2 b t + c = 0, the numerically stable pair, sorted.
int abrdf_quad_roots(float a, float b, float c, output float r0, output float r1)
{
    if (!(a > 0.0)) return 0;
    float disc = b * b - a * c;
    if (!(disc >= 0.0)) return 0;
    float sq = sqrt(disc);
    float q = -(b + (b >= 0.0 ? sq : -sq));
    float t0 = q / a, t1 = q != 0.0 ? c / q : t0;
    r0 = min(t0, t1);
    r1 = max(t0, t1);
    return 1;
}

// One Newton step on the quadric q(t) = |P(t)|^2 - R^2 from a root found from far away.
// In float, a ray from a camera at distance D to a shape of size R loses about D^2/R^2 of
// the discriminant to cancellation (1e-3 of the root for the robot's antenna ball seen
// from 10 units, a visible shift of a sharp highlight); q evaluated at the near-surface
// point has no such cancellation. Skipped at grazing incidence, where the step diverges.
float abrdf_root_refine(float t, float q, float dq, float R, float dlen)
{
    if (!(fabs(dq) > 0.0)) return t;
    float step = q / dq;
    return fabs(step) * dlen < R ? t - step : t;
}

// Sphere of radius R centred at (0, cy, 0); side +1 keeps y >= cy, -1 y <= cy, 0 all.
int abrdf_hit_sphere(float R, float cy, point o, vector d, float tmin, output float best,
                     output vector n, int side)
{
    vector oc = vector(o[0], o[1] - cy, o[2]);
    float r[2];
    if (!abrdf_quad_roots(dot(d, d), dot(oc, d), dot(oc, oc) - R * R, r[0], r[1])) return 0;
    for (int k = 0; k < 2; ++k) {
        vector pk = oc + r[k] * d;
        r[k] = abrdf_root_refine(r[k], dot(pk, pk) - R * R, 2.0 * dot(pk, d), R, length(d));
        if (!(r[k] > tmin && r[k] < best)) continue;
        vector p = oc + r[k] * d;
        if (side * p[1] < 0.0) continue;
        best = r[k];
        n = p;
        return 1;
    }
    return 0;
}

// Side of the cylinder x^2 + z^2 = R^2, |y| <= hh.
int abrdf_hit_tube(float R, float hh, point o, vector d, float tmin, output float best,
                   output vector n)
{
    float r[2];
    if (!abrdf_quad_roots(d[0] * d[0] + d[2] * d[2], o[0] * d[0] + o[2] * d[2],
                          o[0] * o[0] + o[2] * o[2] - R * R, r[0], r[1]))
        return 0;
    for (int k = 0; k < 2; ++k) {
        float px = o[0] + r[k] * d[0], pz = o[2] + r[k] * d[2];
        r[k] = abrdf_root_refine(r[k], px * px + pz * pz - R * R,
                                 2.0 * (px * d[0] + pz * d[2]), R, length(d));
        if (!(r[k] > tmin && r[k] < best)) continue;
        float y = o[1] + r[k] * d[1];
        if (fabs(y) > hh) continue;
        best = r[k];
        n = vector(o[0] + r[k] * d[0], 0, o[2] + r[k] * d[2]);
        return 1;
    }
    return 0;
}

int abrdf_hit_caps(float R, float hh, point o, vector d, float tmin, output float best,
                   output vector n)
{
    if (d[1] == 0.0) return 0;
    int hit = 0;
    for (int s = -1; s <= 1; s += 2) {
        float t = (s * hh - o[1]) / d[1];
        if (!(t > tmin && t < best)) continue;
        float x = o[0] + t * d[0], z = o[2] + t * d[2];
        if (x * x + z * z > R * R) continue;
        best = t;
        n = vector(0, s, 0);
        hit = 1;
    }
    return hit;
}

// Box of half extents h: slabs, entry face first, exit face if the entry is behind tmin.
int abrdf_hit_box(vector h, point o, vector d, float tmin, output float best, output vector n)
{
    float t0 = -ABRDF_T_INF, t1 = ABRDF_T_INF;
    int a0 = -1, a1 = -1;
    float s0 = 0.0, s1 = 0.0;
    for (int c = 0; c < 3; ++c) {
        if (d[c] == 0.0) {
            if (fabs(o[c]) > h[c]) return 0;
            continue;
        }
        float inv = 1.0 / d[c];
        float ta = (-h[c] - o[c]) * inv, tb = (h[c] - o[c]) * inv;
        float sa = -1.0, sb = 1.0;
        if (ta > tb) {
            float x = ta;
            ta = tb;
            tb = x;
            sa = 1.0;
            sb = -1.0;
        }
        if (ta > t0) { t0 = ta; a0 = c; s0 = sa; }
        if (tb < t1) { t1 = tb; a1 = c; s1 = sb; }
    }
    if (!(t0 <= t1)) return 0;
    if (a0 >= 0 && t0 > tmin && t0 < best) {
        best = t0;
        n = vector(0);
        n[a0] = s0;
        return 1;
    }
    if (a1 >= 0 && t1 > tmin && t1 < best) {
        best = t1;
        n = vector(0);
        n[a1] = s1;
        return 1;
    }
    return 0;
}

// World-space ray o + t d against one object; on a closer hit than `best` updates best and
// the world normal. The object-space ray keeps the world parameter t.
int abrdf_hit_object(int shape, float radius, float height, vector half, matrix inv, point o,
                     vector d, float tmin, output float best, output vector n_world)
{
    point lo = abrdf_xform_point(inv, o);
    vector ld = abrdf_xform_vector(inv, d);
    vector ln = vector(0);
    int hit = 0;
    if (shape == ABRDF_SHAPE_SPHERE) {
        hit = abrdf_hit_sphere(radius, 0.0, lo, ld, tmin, best, ln, 0);
    } else if (shape == ABRDF_SHAPE_CYLINDER) {
        hit = abrdf_hit_tube(radius, 0.5 * height, lo, ld, tmin, best, ln);
        hit |= abrdf_hit_caps(radius, 0.5 * height, lo, ld, tmin, best, ln);
    } else if (shape == ABRDF_SHAPE_CAPSULE) {
        hit = abrdf_hit_tube(radius, 0.5 * height, lo, ld, tmin, best, ln);
        hit |= abrdf_hit_sphere(radius, 0.5 * height, lo, ld, tmin, best, ln, 1);
        hit |= abrdf_hit_sphere(radius, -0.5 * height, lo, ld, tmin, best, ln, -1);
    } else if (shape == ABRDF_SHAPE_BOX) {
        hit = abrdf_hit_box(half, lo, ld, tmin, best, ln);
    }
    if (hit) n_world = abrdf_xform_normal(inv, ln);
    return hit;
}

// The tangent field rule at world point p, in world space (not normalised).
vector abrdf_tangent_rule(int rule, vector axis, matrix m, matrix inv, point p_world)
{
    point p = abrdf_xform_point(inv, p_world);
    vector t = vector(0);
    if (rule == ABRDF_TANGENT_U) t = vector(-p[2], 0, p[0]);
    else if (rule == ABRDF_TANGENT_V) t = vector(0, 1, 0);
    else if (rule == ABRDF_TANGENT_RADIAL) t = vector(p[0], 0, p[2]);
    else t = axis;
    return abrdf_xform_vector(m, t);
}

// Pixel-centre camera ray of the pixel that the host's camera ray through P falls in:
// the built-in renderer's camera (tools/render/render.h) with forward unit, right and up scaled to
// the image plane's half sizes. Every sample of a pixel gets the same ray, so the host's
// pixel filter and sample count cannot change the result. Returns 0 outside the image.
int abrdf_pixel_ray(point eye, vector fwd, vector right, vector up, int width, int height,
                    point P, output vector d)
{
    vector v = P - eye;
    float z = dot(v, fwd);
    if (!(z > 0.0)) return 0;
    float px = dot(v, right) / (z * dot(right, right));
    float py = dot(v, up) / (z * dot(up, up));
    float x = floor((px + 1.0) * 0.5 * width), y = floor((1.0 - py) * 0.5 * height);
    x = clamp(x, 0.0, width - 1.0);
    y = clamp(y, 0.0, height - 1.0);
    float cx = 2.0 * (x + 0.5) / width - 1.0, cy = 1.0 - 2.0 * (y + 0.5) / height;
    d = normalize(fwd + cx * right + cy * up);
    return 1;
}

#endif // ABRDF_TRACE_H
