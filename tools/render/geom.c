/* geom.c - transforms, exact ray/primitive intersections and normals, mesh triangles,
 * tangent fields. */
#include <math.h>
#include <string.h>

#include "geom.h"

static const double DEG = 3.14159265358979323846 / 180.0;

static void mat_mul(const double a[3][4], const double b[3][4], double out[3][4])
{
    double r[3][4];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
            if (j == 3) r[i][j] += a[i][3];
        }
    memcpy(out, r, sizeof r);
}

static void rot(int axis, double deg, double out[3][4])
{
    double c = cos(deg * DEG), s = sin(deg * DEG);
    memset(out, 0, sizeof(double[3][4]));
    int a = (axis + 1) % 3, b = (axis + 2) % 3;
    out[axis][axis] = 1.0;
    out[a][a] = c, out[a][b] = -s;
    out[b][a] = s, out[b][b] = c;
}

void geom_xform_make(const scene_object *o, geom_xform *xf)
{
    double s[3][4] = {{o->scale[0], 0, 0, 0}, {0, o->scale[1], 0, 0}, {0, 0, o->scale[2], 0}};
    double r[3][4];
    for (int ax = 0; ax < 3; ++ax) { /* x first, then y, then z */
        rot(ax, o->rotate_deg[ax], r);
        mat_mul(r, s, s);
    }
    for (int i = 0; i < 3; ++i) s[i][3] += o->translate[i];
    memcpy(xf->m, s, sizeof s);
    /* Inverse: S^-1 R^T (p - T); rotations are orthonormal, so no general inversion. */
    double rt[3][3];
    double lin[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    for (int ax = 0; ax < 3; ++ax) {
        rot(ax, o->rotate_deg[ax], r);
        mat_mul(r, lin, lin);
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) rt[i][j] = lin[j][i] / o->scale[i];
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) xf->inv[i][j] = rt[i][j];
        xf->inv[i][3] =
            -(rt[i][0] * o->translate[0] + rt[i][1] * o->translate[1] + rt[i][2] * o->translate[2]);
    }
}

void geom_xform_point(const double m[3][4], const double p[3], double out[3])
{
    for (int i = 0; i < 3; ++i) out[i] = m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3];
}

void geom_xform_vector(const double m[3][4], const double v[3], double out[3])
{
    for (int i = 0; i < 3; ++i) out[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
}

void geom_xform_normal(const geom_xform *xf, const double n[3], double out[3])
{
    for (int i = 0; i < 3; ++i)
        out[i] = xf->inv[0][i] * n[0] + xf->inv[1][i] * n[1] + xf->inv[2][i] * n[2];
    double l2 = geom_dot(out, out);
    if (l2 > 0) { /* one divide, not three */
        double inv = 1.0 / sqrt(l2);
        out[0] *= inv, out[1] *= inv, out[2] *= inv;
    }
}

void geom_object_make(const scene_object *o, geom_object *g)
{
    memset(g, 0, sizeof *g);
    g->shape = o->shape;
    g->radius = o->radius;
    g->height = o->height;
    double local_bound = 0;
    switch (o->shape) {
    case SCENE_SPHERE: local_bound = o->radius; break;
    case SCENE_CYLINDER:
        local_bound = sqrt(o->radius * o->radius + 0.25 * o->height * o->height);
        break;
    case SCENE_CAPSULE: local_bound = o->radius + 0.5 * o->height; break;
    case SCENE_BOX:
        for (int c = 0; c < 3; ++c) g->half[c] = 0.5 * o->size[c];
        local_bound = sqrt(geom_dot(g->half, g->half));
        break;
    case SCENE_MESH:
        g->mesh = o->mesh_data;
        g->smooth = o->smooth;
        local_bound = g->mesh ? g->mesh->radius : 0.0;
        break;
    default: break;
    }
    /* Every analytic shape of the format is a convex solid; a mesh can shadow itself. */
    g->convex = o->shape != SCENE_MESH;
    geom_xform_make(o, &g->xf);
    double smax = fmax(o->scale[0], fmax(o->scale[1], o->scale[2]));
    double local_center[3] = {0, 0, 0};
    if (o->shape == SCENE_MESH && g->mesh)
        memcpy(local_center, g->mesh->center, sizeof local_center);
    geom_xform_point(g->xf.m, local_center, g->center);
    /* 1 + 1e-9: rounding of the transform must not push a surface point outside. */
    g->bound = local_bound * smax * (1.0 + 1e-9);
}

/* Smallest root of a t^2 + 2 b t + c = 0 inside (tmin, tmax) whose hit passes accept(). */
typedef int (*accept_fn)(const double o[3], const double d[3], double t, const geom_object *g);

static int quad_roots(double a, double b, double c, double r[2])
{
    if (!(a > 0)) return 0;
    double disc = b * b - a * c;
    if (!(disc >= 0)) return 0;
    double sq = sqrt(disc);
    /* Numerically stable pair: q = -(b + sign(b) sq). */
    double q = -(b + (b >= 0 ? sq : -sq));
    double t0 = q / a, t1 = q != 0 ? c / q : t0;
    r[0] = t0 < t1 ? t0 : t1; /* finite here: plain selects, not libm's fmin/fmax calls */
    r[1] = t0 < t1 ? t1 : t0;
    return 1;
}

static int better(double t, double tmin, double best) { return t > tmin && t < best; }

static int hit_sphere(double R, double cy, const double o[3], const double d[3], double tmin,
                      double *best, double n[3], int side /* 0: any, +1: y > cy, -1: y < cy */)
{
    double oc[3] = {o[0], o[1] - cy, o[2]};
    double r[2];
    if (!quad_roots(geom_dot(d, d), geom_dot(oc, d), geom_dot(oc, oc) - R * R, r)) return 0;
    int hit = 0;
    for (int k = 0; k < 2; ++k) {
        if (!better(r[k], tmin, *best)) continue;
        double p[3] = {oc[0] + r[k] * d[0], oc[1] + r[k] * d[1], oc[2] + r[k] * d[2]};
        if (side * p[1] < 0) continue;
        *best = r[k];
        n[0] = p[0], n[1] = p[1], n[2] = p[2];
        hit = 1;
        break;
    }
    return hit;
}

/* Side of the infinite cylinder x^2 + z^2 = R^2 limited to |y| <= hh. */
static int hit_tube(double R, double hh, const double o[3], const double d[3], double tmin,
                    double *best, double n[3])
{
    double r[2];
    if (!quad_roots(d[0] * d[0] + d[2] * d[2], o[0] * d[0] + o[2] * d[2],
                    o[0] * o[0] + o[2] * o[2] - R * R, r))
        return 0;
    for (int k = 0; k < 2; ++k) {
        if (!better(r[k], tmin, *best)) continue;
        double y = o[1] + r[k] * d[1];
        if (fabs(y) > hh) continue;
        *best = r[k];
        n[0] = o[0] + r[k] * d[0], n[1] = 0, n[2] = o[2] + r[k] * d[2];
        return 1;
    }
    return 0;
}

static int hit_caps(double R, double hh, const double o[3], const double d[3], double tmin,
                    double *best, double n[3])
{
    if (d[1] == 0) return 0;
    int hit = 0;
    for (int s = -1; s <= 1; s += 2) {
        double t = (s * hh - o[1]) / d[1];
        if (!better(t, tmin, *best)) continue;
        double x = o[0] + t * d[0], z = o[2] + t * d[2];
        if (x * x + z * z > R * R) continue;
        *best = t;
        n[0] = 0, n[1] = s, n[2] = 0;
        hit = 1;
    }
    return hit;
}

static int hit_box(const double h[3], const double o[3], const double d[3], double tmin,
                   double *best, double n[3])
{
    double t0 = -INFINITY, t1 = INFINITY;
    int a0 = -1, a1 = -1;
    double s0 = 0, s1 = 0;
    for (int c = 0; c < 3; ++c) {
        if (d[c] == 0) {
            if (fabs(o[c]) > h[c]) return 0;
            continue;
        }
        double inv = 1.0 / d[c];
        double ta = (-h[c] - o[c]) * inv, tb = (h[c] - o[c]) * inv;
        double sa = -1, sb = 1; /* face sign where the ray crosses at ta, tb */
        if (ta > tb) {
            double x = ta;
            ta = tb;
            tb = x;
            sa = 1, sb = -1;
        }
        if (ta > t0) t0 = ta, a0 = c, s0 = sa;
        if (tb < t1) t1 = tb, a1 = c, s1 = sb;
    }
    if (!(t0 <= t1)) return 0;
    if (a0 >= 0 && better(t0, tmin, *best)) {
        *best = t0;
        n[0] = n[1] = n[2] = 0;
        n[a0] = s0;
        return 1;
    }
    if (a1 >= 0 && better(t1, tmin, *best)) {
        *best = t1;
        n[0] = n[1] = n[2] = 0;
        n[a1] = s1;
        return 1;
    }
    return 0;
}

int geom_intersect_local(const geom_object *g, const double o[3], const double d[3], double tmin,
                         double tmax, double *t, double n[3])
{
    double best = tmax;
    int hit = 0;
    switch (g->shape) {
    case SCENE_SPHERE: hit = hit_sphere(g->radius, 0, o, d, tmin, &best, n, 0); break;
    case SCENE_CYLINDER:
        hit = hit_tube(g->radius, 0.5 * g->height, o, d, tmin, &best, n);
        hit |= hit_caps(g->radius, 0.5 * g->height, o, d, tmin, &best, n);
        break;
    case SCENE_CAPSULE:
        hit = hit_tube(g->radius, 0.5 * g->height, o, d, tmin, &best, n);
        hit |= hit_sphere(g->radius, 0.5 * g->height, o, d, tmin, &best, n, 1);
        hit |= hit_sphere(g->radius, -0.5 * g->height, o, d, tmin, &best, n, -1);
        break;
    case SCENE_BOX: hit = hit_box(g->half, o, d, tmin, &best, n); break;
    case SCENE_MESH: {
        geom_mesh_hit h;
        hit = geom_mesh_intersect_local(g, o, d, tmin, tmax, &h);
        if (hit) best = h.t, memcpy(n, h.n, sizeof h.n);
        break;
    }
    default: break;
    }
    if (hit) *t = best;
    return hit;
}

/* The bounding-ball test of a ray o + t d, given oc = o - centre and c = |oc|^2 - bound^2:
 * the roots (-b -+ sq)/a compared with tmin and tmax as -b -+ sq against tmin a and tmax a
 * (a > 0), so no division. */
static int bound_test(const double oc[3], double c, const double d[3], double tmin, double tmax)
{
    double a = geom_dot(d, d), b = geom_dot(oc, d);
    double disc = b * b - a * c;
    if (disc < 0 || !(a > 0)) return 0;
    double sq = sqrt(disc);
    return -b + sq > tmin * a && -b - sq < tmax * a;
}

int geom_hits_bound(const geom_object *g, const double o[3], const double d[3], double tmin,
                    double tmax)
{
    double oc[3] = {o[0] - g->center[0], o[1] - g->center[1], o[2] - g->center[2]};
    return bound_test(oc, geom_dot(oc, oc) - g->bound * g->bound, d, tmin, tmax);
}

void geom_origin_make(const geom_object *g, const double o[3], geom_origin *go)
{
    for (int k = 0; k < 3; ++k) go->oc[k] = o[k] - g->center[k];
    go->c = geom_dot(go->oc, go->oc) - g->bound * g->bound;
    geom_xform_point(g->xf.inv, o, go->local);
}

int geom_intersect_from(const geom_object *g, const geom_origin *go, const double d[3], double tmin,
                        double tmax, double *t, double n_local[3])
{
    /* A sphere is its own bounding ball: its exact test is the cheaper rejection. */
    if (g->shape != SCENE_SPHERE && !bound_test(go->oc, go->c, d, tmin, tmax)) return 0;
    double ld[3];
    geom_xform_vector(g->xf.inv, d, ld);
    return geom_intersect_local(g, go->local, ld, tmin, tmax, t, n_local);
}

int geom_intersect(const geom_object *g, const double o[3], const double d[3], double tmin,
                   double tmax, double *t, double n_world[3])
{
    if (!geom_hits_bound(g, o, d, tmin, tmax)) return 0;
    double lo[3], ld[3], ln[3];
    geom_xform_point(g->xf.inv, o, lo);
    geom_xform_vector(g->xf.inv, d, ld);
    if (!geom_intersect_local(g, lo, ld, tmin, tmax, t, ln)) return 0;
    if (n_world) geom_xform_normal(&g->xf, ln, n_world);
    return 1;
}

void geom_tangent(const scene_object *o, const geom_xform *xf, const double p_world[3],
                  double t_world[3])
{
    double p[3], t[3] = {0, 0, 0};
    geom_xform_point(xf->inv, p_world, p);
    switch (o->tangent) {
    case SCENE_TANGENT_U: t[0] = -p[2], t[2] = p[0]; break;
    case SCENE_TANGENT_V: t[1] = 1; break;
    case SCENE_TANGENT_RADIAL: t[0] = p[0], t[2] = p[2]; break;
    case SCENE_TANGENT_AXIS: memcpy(t, o->tangent_axis, sizeof t); break;
    case SCENE_TANGENT_UV: break; /* per triangle: geom_tangent_uv */
    }
    geom_xform_vector(xf->m, t, t_world);
}

/* ---- meshes ------------------------------------------------------------------------- */

static void corner(const mesh *m, int k, int c, double p[3])
{
    const float *v = m->position + 3 * (size_t)m->tri[3 * (size_t)k + (size_t)c];
    p[0] = v[0], p[1] = v[1], p[2] = v[2];
}

int geom_triangle_intersect(const geom_object *g, int k, const double o[3], const double d[3],
                            double tmin, double tmax, double *t, double *b1, double *b2)
{
    double a[3], b[3], c[3], e1[3], e2[3], pv[3], tv[3], qv[3];
    corner(g->mesh, k, 0, a);
    corner(g->mesh, k, 1, b);
    corner(g->mesh, k, 2, c);
    for (int i = 0; i < 3; ++i) e1[i] = b[i] - a[i], e2[i] = c[i] - a[i], tv[i] = o[i] - a[i];
    pv[0] = d[1] * e2[2] - d[2] * e2[1];
    pv[1] = d[2] * e2[0] - d[0] * e2[2];
    pv[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = geom_dot(e1, pv);
    if (det == 0 || !isfinite(det)) return 0; /* parallel or degenerate */
    double inv = 1.0 / det, u = geom_dot(tv, pv) * inv;
    if (!(u >= 0 && u <= 1)) return 0;
    qv[0] = tv[1] * e1[2] - tv[2] * e1[1];
    qv[1] = tv[2] * e1[0] - tv[0] * e1[2];
    qv[2] = tv[0] * e1[1] - tv[1] * e1[0];
    double v = geom_dot(d, qv) * inv;
    if (!(v >= 0 && u + v <= 1)) return 0;
    double tt = geom_dot(e2, qv) * inv;
    if (!(tt > tmin && tt < tmax)) return 0;
    *t = tt, *b1 = u, *b2 = v;
    return 1;
}

void geom_triangle_normals(const geom_object *g, int k, double b1, double b2, const double d[3],
                           geom_mesh_hit *h)
{
    const mesh *m = g->mesh;
    double a[3], b[3], c[3], e1[3], e2[3];
    corner(m, k, 0, a);
    corner(m, k, 1, b);
    corner(m, k, 2, c);
    for (int i = 0; i < 3; ++i) e1[i] = b[i] - a[i], e2[i] = c[i] - a[i];
    h->ng[0] = e1[1] * e2[2] - e1[2] * e2[1];
    h->ng[1] = e1[2] * e2[0] - e1[0] * e2[2];
    h->ng[2] = e1[0] * e2[1] - e1[1] * e2[0];
    if (g->smooth) {
        double w[3] = {1.0 - b1 - b2, b1, b2};
        h->n[0] = h->n[1] = h->n[2] = 0;
        for (int q = 0; q < 3; ++q) {
            const float *nv = m->normal + 3 * (size_t)m->tri_normal[3 * (size_t)k + (size_t)q];
            for (int i = 0; i < 3; ++i) h->n[i] += w[q] * nv[i];
        }
    } else {
        memcpy(h->n, h->ng, sizeof h->n);
    }
    /* Two-sided: seen from behind the face, both normals turn toward the viewer. */
    if (geom_dot(h->ng, d) > 0)
        for (int i = 0; i < 3; ++i) h->n[i] = -h->n[i], h->ng[i] = -h->ng[i];
    h->triangle = k;
    h->b1 = b1, h->b2 = b2;
}

int geom_mesh_intersect_local(const geom_object *g, const double o[3], const double d[3],
                              double tmin, double tmax, geom_mesh_hit *h)
{
    if (!g->mesh) return 0;
    int best = -1;
    double bt = tmax, bb1 = 0, bb2 = 0;
    for (int k = 0; k < g->mesh->triangle_count; ++k) {
        double t, b1, b2;
        /* strict <: of two triangles at the same distance the first in the file wins */
        if (geom_triangle_intersect(g, k, o, d, tmin, bt, &t, &b1, &b2))
            best = k, bt = t, bb1 = b1, bb2 = b2;
    }
    if (best < 0) return 0;
    geom_triangle_normals(g, best, bb1, bb2, d, h);
    h->t = bt;
    return 1;
}

void geom_tangent_uv(const geom_object *g, int k, double t_world[3])
{
    const mesh *m = g->mesh;
    double t[3] = {0, 0, 0};
    if (m && m->tri_uv) {
        double a[3], b[3], c[3], uv[3][2];
        corner(m, k, 0, a);
        corner(m, k, 1, b);
        corner(m, k, 2, c);
        for (int q = 0; q < 3; ++q) {
            const float *x = m->uv + 2 * (size_t)m->tri_uv[3 * (size_t)k + (size_t)q];
            uv[q][0] = x[0], uv[q][1] = x[1];
        }
        double du1 = uv[1][0] - uv[0][0], dv1 = uv[1][1] - uv[0][1];
        double du2 = uv[2][0] - uv[0][0], dv2 = uv[2][1] - uv[0][1];
        double det = du1 * dv2 - du2 * dv1;
        /* P - P0 = (u - u0) dP/du + (v - v0) dP/dv on the triangle: solve for dP/du. */
        if (det != 0)
            for (int i = 0; i < 3; ++i) t[i] = (dv2 * (b[i] - a[i]) - dv1 * (c[i] - a[i])) / det;
    }
    geom_xform_vector(g->xf.m, t, t_world);
}
