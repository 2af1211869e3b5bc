/* light.c - sphere, rectangle and environment lights: sampling, ray hits and the per-hit
 * estimators (light.h). */
#include "light.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static void cross3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static double len3(const double v[3]) { return sqrt(geom_dot(v, v)); }

const char *light_kind_name(scene_light_kind kind)
{
    static const char *const names[] = {"point", "directional", "sphere", "rect", "environment"};
    return kind >= SCENE_LIGHT_POINT && kind <= SCENE_LIGHT_ENVIRONMENT ? names[kind] : "?";
}

void light_setup(const scene_light *sl, render_light *rl)
{
    rl->radius = sl->radius;
    memcpy(rl->edge_u, sl->edge_u, sizeof rl->edge_u);
    memcpy(rl->edge_v, sl->edge_v, sizeof rl->edge_v);
    memset(rl->normal, 0, sizeof rl->normal);
    rl->bound = 0;
    rl->env = sl->env;
    if (sl->kind == SCENE_LIGHT_SPHERE) rl->bound = sl->radius;
    if (sl->kind == SCENE_LIGHT_RECT) {
        cross3(sl->edge_u, sl->edge_v, rl->normal);
        double l = len3(rl->normal);
        for (int c = 0; c < 3; ++c) rl->normal[c] /= l;
        rl->bound = 0.5 * sqrt(geom_dot(sl->edge_u, sl->edge_u) + geom_dot(sl->edge_v, sl->edge_v));
    }
}

/* ---- sphere: uniform in the subtended cone ------------------------------------------- */

/* 1 - cos(theta_max) of the cone from o (d2 = |c - o|^2 > r^2), without cancellation. */
static double cone_width(double r2, double d2)
{
    double s2 = r2 / d2, cmax = sqrt(fmax(0.0, 1.0 - s2));
    return s2 / (1.0 + cmax);
}

/* Two unit vectors completing the unit w to an orthonormal basis. */
static void basis(const double w[3], double a[3], double b[3])
{
    double t[3] = {0, 0, 0};
    t[fabs(w[0]) < 0.5 ? 0 : fabs(w[1]) < 0.5 ? 1 : 2] = 1.0;
    cross3(w, t, a);
    double l = len3(a);
    for (int c = 0; c < 3; ++c) a[c] /= l;
    cross3(w, a, b);
}

static int sphere_sample(const render_light *lt, const double o[3], double u1, double u2,
                         light_sample *s)
{
    double dc[3] = {lt->position[0] - o[0], lt->position[1] - o[1], lt->position[2] - o[2]};
    double d2 = geom_dot(dc, dc), r2 = lt->radius * lt->radius;
    if (!(d2 > r2)) return 0; /* inside the light: it lights nothing there */
    double d = sqrt(d2), w[3] = {dc[0] / d, dc[1] / d, dc[2] / d}, a[3], b[3];
    double om = cone_width(r2, d2), t = u1 * om; /* t = 1 - cos(theta) */
    if (!(om > 0)) return 0; /* narrower than a double resolves: it lights nothing */
    double ct = 1.0 - t, st = sqrt(fmax(0.0, t * (2.0 - t))), phi = 2.0 * PI * u2;
    basis(w, a, b);
    double ca = cos(phi), sa = sin(phi);
    for (int c = 0; c < 3; ++c) s->wi[c] = ct * w[c] + st * (ca * a[c] + sa * b[c]);
    /* the near intersection; at the cone's edge the discriminant is 0 */
    s->dist = d * ct - sqrt(fmax(0.0, r2 - d2 * st * st));
    s->pdf = 1.0 / (2.0 * PI * om);
    memcpy(s->le, lt->e, sizeof s->le);
    return 1;
}

static int sphere_hit(const render_light *lt, const double o[3], const double wi[3],
                      light_sample *s)
{
    double dc[3] = {lt->position[0] - o[0], lt->position[1] - o[1], lt->position[2] - o[2]};
    double d2 = geom_dot(dc, dc), r2 = lt->radius * lt->radius;
    double b = geom_dot(wi, dc), c = d2 - r2, disc = b * b - c;
    if (!(c > 0) || !(b > 0) || !(disc >= 0)) return 0;
    double om = cone_width(r2, d2);
    if (!(om > 0)) return 0;
    s->dist = c / (b + sqrt(disc)); /* the near root, without cancellation */
    s->pdf = 1.0 / (2.0 * PI * om);
    memcpy(s->le, lt->e, sizeof s->le);
    return 1;
}

/* ---- rectangle: the spherical rectangle (Urena et al. 2013) ---------------------------- */

/* The rectangle seen from o, in its own frame: x along edge_u, y along edge_v, z its normal;
 * corner s = centre - u/2 - v/2 at (x0, y0, z0) from o, z0 < 0 (o in front). */
typedef struct sph_rect {
    double x[3], y[3], z[3];
    double x0, y0, z0, x1, y1;
    double b0, b1, k, S; /* S: solid angle */
    double area;
} sph_rect;

static int rect_setup(const render_light *lt, const double o[3], sph_rect *q)
{
    double eu = len3(lt->edge_u), ev = len3(lt->edge_v), d[3];
    for (int c = 0; c < 3; ++c) {
        q->x[c] = lt->edge_u[c] / eu, q->y[c] = lt->edge_v[c] / ev, q->z[c] = lt->normal[c];
        d[c] = lt->position[c] - 0.5 * lt->edge_u[c] - 0.5 * lt->edge_v[c] - o[c];
    }
    q->x0 = geom_dot(d, q->x), q->y0 = geom_dot(d, q->y), q->z0 = geom_dot(d, q->z);
    if (!(q->z0 < 0)) return 0; /* behind or in its plane: one-sided */
    q->x1 = q->x0 + eu, q->y1 = q->y0 + ev;
    q->area = eu * ev;
    double z0 = q->z0, z2 = z0 * z0;
    /* unit normals of the planes through o and each edge (closed forms of the cross products
     * of consecutive corners) */
    double n0[3] = {0, z0, -q->y0}, n1[3] = {-z0, 0, q->x1}, n2[3] = {0, -z0, q->y1},
           n3[3] = {z0, 0, -q->x0};
    double l0 = sqrt(z2 + q->y0 * q->y0), l1 = sqrt(z2 + q->x1 * q->x1),
           l2 = sqrt(z2 + q->y1 * q->y1), l3 = sqrt(z2 + q->x0 * q->x0);
    for (int c = 0; c < 3; ++c) n0[c] /= l0, n1[c] /= l1, n2[c] /= l2, n3[c] /= l3;
    double g0 = acos(fmax(-1.0, fmin(1.0, -geom_dot(n0, n1))));
    double g1 = acos(fmax(-1.0, fmin(1.0, -geom_dot(n1, n2))));
    double g2 = acos(fmax(-1.0, fmin(1.0, -geom_dot(n2, n3))));
    double g3 = acos(fmax(-1.0, fmin(1.0, -geom_dot(n3, n0))));
    q->b0 = n0[2], q->b1 = n2[2];
    q->k = 2.0 * PI - g2 - g3;
    q->S = g0 + g1 - q->k;
    return 1;
}

/* Area sampling's solid-angle density of the point at distance dist along wi. */
static double rect_area_pdf(const sph_rect *q, const double wi[3], double dist)
{
    double cl = -geom_dot(wi, q->z);
    return cl > 0 ? dist * dist / (q->area * cl) : 0.0;
}

static int rect_sample(const render_light *lt, const double o[3], double u1, double u2,
                       light_sample *s)
{
    sph_rect q;
    if (!rect_setup(lt, o, &q)) return 0;
    double p[3]; /* the point on the rectangle, relative to o */
    int by_area = !(q.S >= LIGHT_RECT_MIN_SOLID_ANGLE);
    if (by_area) {
        double xu = q.x0 + u1 * (q.x1 - q.x0), yv = q.y0 + u2 * (q.y1 - q.y0);
        for (int c = 0; c < 3; ++c) p[c] = xu * q.x[c] + yv * q.y[c] + q.z0 * q.z[c];
    } else {
        double au = u1 * q.S + q.k, sau = sin(au);
        double fu = sau != 0 ? (cos(au) * q.b0 - q.b1) / sau : (q.b0 > q.b1 ? INFINITY : -INFINITY);
        double cu = (fu > 0 ? 1.0 : -1.0) / sqrt(fu * fu + q.b0 * q.b0);
        cu = fmax(-1.0, fmin(1.0, cu));
        double sq = sqrt(fmax(1e-300, 1.0 - cu * cu));
        double xu = fmax(q.x0, fmin(q.x1, -(cu * q.z0) / sq));
        double dd = sqrt(xu * xu + q.z0 * q.z0);
        double h0 = q.y0 / sqrt(dd * dd + q.y0 * q.y0), h1 = q.y1 / sqrt(dd * dd + q.y1 * q.y1);
        double hv = h0 + u2 * (h1 - h0), hv2 = hv * hv;
        double yv = hv2 < 1.0 - 1e-12 ? hv * dd / sqrt(1.0 - hv2) : q.y1;
        yv = fmax(q.y0, fmin(q.y1, yv));
        for (int c = 0; c < 3; ++c) p[c] = xu * q.x[c] + yv * q.y[c] + q.z0 * q.z[c];
    }
    double dist = len3(p);
    if (!(dist > 0)) return 0;
    for (int c = 0; c < 3; ++c) s->wi[c] = p[c] / dist;
    s->dist = dist;
    s->pdf = by_area ? rect_area_pdf(&q, s->wi, dist) : 1.0 / q.S;
    memcpy(s->le, lt->e, sizeof s->le);
    return s->pdf > 0 && isfinite(s->pdf);
}

static int rect_hit(const render_light *lt, const double o[3], const double wi[3], light_sample *s)
{
    double den = geom_dot(wi, lt->normal);
    if (!(den < 0)) return 0; /* parallel, or toward its back */
    double dc[3] = {lt->position[0] - o[0], lt->position[1] - o[1], lt->position[2] - o[2]};
    double t = geom_dot(dc, lt->normal) / den;
    if (!(t > 0)) return 0;
    double a = 0, b = 0, eu2 = geom_dot(lt->edge_u, lt->edge_u),
           ev2 = geom_dot(lt->edge_v, lt->edge_v);
    for (int c = 0; c < 3; ++c) {
        double r = t * wi[c] - dc[c]; /* hit point - centre */
        a += r * lt->edge_u[c], b += r * lt->edge_v[c];
    }
    /* a = (hit - centre).u in units of |u|^2: inside if |a| <= |u|^2 / 2 */
    if (fabs(a) > 0.5 * eu2 || fabs(b) > 0.5 * ev2) return 0;
    sph_rect q;
    if (!rect_setup(lt, o, &q)) return 0;
    s->dist = t;
    s->pdf = q.S >= LIGHT_RECT_MIN_SOLID_ANGLE ? 1.0 / q.S : rect_area_pdf(&q, wi, t);
    memcpy(s->le, lt->e, sizeof s->le);
    return s->pdf > 0 && isfinite(s->pdf);
}

/* ---- environment --------------------------------------------------------------------- */

static void env_radiance(const render_light *lt, const double wi[3], double le[3])
{
    envmap_lookup(lt->env, wi, le);
    for (int c = 0; c < 3; ++c) le[c] *= lt->e[c];
}

int light_sample_dir(const render_light *lt, const double o[3], double u1, double u2,
                     light_sample *s)
{
    s->pdf = 0;
    switch (lt->kind) {
    case SCENE_LIGHT_SPHERE: return sphere_sample(lt, o, u1, u2, s);
    case SCENE_LIGHT_RECT: return rect_sample(lt, o, u1, u2, s);
    case SCENE_LIGHT_ENVIRONMENT:
        s->pdf = envmap_sample(lt->env, u1, u2, s->wi);
        if (!(s->pdf > 0)) return 0;
        s->dist = INFINITY;
        env_radiance(lt, s->wi, s->le);
        return 1;
    default: return 0;
    }
}

int light_hit(const render_light *lt, const double o[3], const double wi[3], light_sample *s)
{
    s->pdf = 0;
    memcpy(s->wi, wi, sizeof s->wi);
    switch (lt->kind) {
    case SCENE_LIGHT_SPHERE: return sphere_hit(lt, o, wi, s);
    case SCENE_LIGHT_RECT: return rect_hit(lt, o, wi, s);
    case SCENE_LIGHT_ENVIRONMENT:
        s->dist = INFINITY;
        s->pdf = envmap_pdf(lt->env, wi);
        env_radiance(lt, wi, s->le);
        return 1; /* p_L may be 0 (a black texel): then only BRDF sampling sees it */
    default: return 0;
    }
}

/* ---- the estimators ------------------------------------------------------------------ */

/* Veach's power heuristic (beta = 2) for a sample of density p against the other strategy's q,
 * as 1 / (1 + (q/p)^2): a light that subtends almost nothing has a density near DBL_MAX whose
 * square would overflow (inf / inf); the ratio only underflows, to the right weights 1 and 0. */
static double power_heuristic(double p, double q)
{
    double r = q / p;
    return 1.0 / (1.0 + r * r);
}

static uint64_t mix64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* Uniform in [0, 1) from the hit's seed and a dimension. */
static double rnd(uint64_t seed, uint64_t dim)
{
    return (double)(mix64(seed ^ mix64(dim)) >> 11) * (1.0 / 9007199254740992.0);
}

static uint64_t hit_seed(const render_hit *h)
{
    uint64_t s = 0x5a17ull;
    for (int c = 0; c < 3; ++c) {
        uint64_t a, b;
        memcpy(&a, &h->p[c], sizeof a);
        memcpy(&b, &h->wo[c], sizeof b);
        s = mix64(s ^ a) ^ mix64(s + b);
    }
    return s;
}

/* Sum of the material's lobes at (wi, wo). */
static void eval_lobes(const render_material *m, const abrdf_frame *fr, const double wi[3],
                       const double wo[3], int free_brdf, double f[3], render_stats *st)
{
    f[0] = f[1] = f[2] = 0;
    st->brdf_evals += (unsigned long long)m->lobe_count;
    if (free_brdf) return;
    for (int k = 0; k < m->lobe_count; ++k) {
        double fl[3];
        abrdf_eval_prepared(&m->prepared[k], fr, wi, wo, fl);
        for (int c = 0; c < 3; ++c) f[c] += fl[c];
    }
}

/* BRDF sampling's density: lobes chosen with equal probability (one-sample MIS). */
static double brdf_pdf(const render_material *m, const abrdf_frame *fr, const double wi[3],
                       const double wo[3])
{
    double p = 0;
    for (int k = 0; k < m->lobe_count; ++k) {
        double pk;
        abrdf_pdf_prepared(&m->prepared[k], fr, wi, wo, &pk);
        p += pk;
    }
    return m->lobe_count > 0 ? p / m->lobe_count : 0.0;
}

void light_shade_sampled(const render_scene *rs, const render_options *opt,
                         const render_material *m, const render_hit *h, const double o[3],
                         const abrdf_frame *frame, light_blocked_fn blocked, double L[3],
                         render_stats *st)
{
    abrdf_frame local;
    if (!frame) {
        abrdf_frame_make(h->n, NULL, &local); /* isotropic lobes: any tangent */
        frame = &local;
    }
    int est = opt->estimator, ns = opt->light_samples > 1 ? opt->light_samples : 1;
    int K = m->lobe_count;
    uint64_t seed = hit_seed(h);
    for (int l = 0; l < rs->light_count; ++l) {
        const render_light *lt = &rs->lights[l];
        if (!SCENE_LIGHT_SAMPLED(lt->kind) || !(lt->e[0] > 0 || lt->e[1] > 0 || lt->e[2] > 0))
            continue;
        if (lt->kind == SCENE_LIGHT_ENVIRONMENT && !(lt->env->total > 0)) continue;
        double acc[3] = {0, 0, 0};
        for (int s = 0; s < ns; ++s) {
            uint64_t dim = 4 * ((uint64_t)l * (uint64_t)ns + (uint64_t)s);
            light_sample ls;
            if (est != RENDER_EST_BRDF &&
                light_sample_dir(lt, o, rnd(seed, dim), rnd(seed, dim + 1), &ls)) {
                ++st->light_samples;
                double ci = geom_dot(h->n, ls.wi), f[3];
                if (ci > 0) {
                    eval_lobes(m, frame, ls.wi, h->wo, opt->free_brdf, f, st);
                    if ((f[0] > 0 || f[1] > 0 || f[2] > 0) &&
                        !blocked(rs, l, h, o, ls.wi, ls.dist, st)) {
                        double w = 1.0;
                        if (est == RENDER_EST_MIS)
                            w = power_heuristic(ls.pdf, brdf_pdf(m, frame, ls.wi, h->wo));
                        for (int c = 0; c < 3; ++c) acc[c] += f[c] * ci * ls.le[c] * w / ls.pdf;
                    }
                }
            }
            if (est == RENDER_EST_LIGHT || K == 0 || opt->free_brdf) continue;
            /* BRDF sample: a lobe chosen with u1, which is reused rescaled (abrdf.h) */
            double u1 = rnd(seed, dim + 2) * K, u2 = rnd(seed, dim + 3);
            int k = (int)u1 < K ? (int)u1 : K - 1;
            abrdf_sample_result r;
            abrdf_sample_result_init(&r);
            abrdf_sample_prepared(&m->prepared[k], frame, h->wo, fmin(1.0, u1 - k), u2, &r);
            ++st->brdf_samples;
            double ci = geom_dot(h->n, r.wi);
            if (!(r.pdf > 0) || !(ci > 0) || !light_hit(lt, o, r.wi, &ls)) continue;
            double pb = K == 1 ? r.pdf : brdf_pdf(m, frame, r.wi, h->wo), f[3];
            if (!(pb > 0)) continue;
            eval_lobes(m, frame, r.wi, h->wo, 0, f, st);
            if (!(f[0] > 0 || f[1] > 0 || f[2] > 0) || blocked(rs, l, h, o, r.wi, ls.dist, st))
                continue;
            double w = 1.0;
            if (est == RENDER_EST_MIS) w = power_heuristic(pb, ls.pdf);
            for (int c = 0; c < 3; ++c) acc[c] += f[c] * ci * ls.le[c] * w / pb;
        }
        for (int c = 0; c < 3; ++c) L[c] += acc[c] / ns;
    }
}
