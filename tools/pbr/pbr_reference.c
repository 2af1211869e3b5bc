/* pbr_reference.c - the glTF 2.0 metallic-roughness BRDF with its KHR material extensions, as
 * the specification writes it (pbr_reference.h names the sections). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pbr_reference.h"
#include "quad.h"

static const double PI = 3.14159265358979323846;

static double sq(double x) { return x * x; }
static double max3(const double v[3]) { return fmax(v[0], fmax(v[1], v[2])); }

/* Appendix B.3.2: F = f0 + (f90 - f0)(1 - |V.H|)^5. */
double pbr_ref_f_schlick(double f0, double f90, double cos_vh)
{
    double m = 1 - fabs(cos_vh);
    return f0 + (f90 - f0) * m * m * m * m * m;
}

/* Appendix B.3.3: D = alpha^2 chi(N.H) / (pi ((N.H)^2 (alpha^2 - 1) + 1)^2). */
double pbr_ref_d_ggx(double alpha, double cos_h)
{
    if (!(cos_h > 0)) return 0;
    double a2 = alpha * alpha, k = cos_h * cos_h * (a2 - 1) + 1;
    return a2 / (PI * k * k);
}

/* KHR_materials_anisotropy: D = 1 / (pi at ab ((T.H/at)^2 + (B.H/ab)^2 + (N.H)^2)^2). */
double pbr_ref_d_ggx_aniso(double at, double ab, const double h[3])
{
    if (!(h[2] > 0)) return 0;
    double k = sq(h[0] / at) + sq(h[1] / ab) + h[2] * h[2];
    return 1 / (PI * at * ab * k * k);
}

/* Appendix B.3.3: the height-correlated Smith term over 4 |N.L| |N.V|,
 * V = 0.5 / (|N.L| sqrt(a2 + (1 - a2)(N.V)^2) + |N.V| sqrt(a2 + (1 - a2)(N.L)^2)), a2 = alpha^2,
 * which is G2 = 1 / (1 + Lambda(V) + Lambda(L)) divided by 4 |N.L| |N.V|. */
double pbr_ref_v_ggx(double alpha, double cos_l, double cos_v)
{
    if (!(cos_l > 0 && cos_v > 0)) return 0;
    double a2 = alpha * alpha;
    double gv = cos_l * sqrt(a2 + (1 - a2) * cos_v * cos_v);
    double gl = cos_v * sqrt(a2 + (1 - a2) * cos_l * cos_l);
    return 0.5 / (gv + gl);
}

/* KHR_materials_anisotropy: the same with |(at T.X, ab B.X, N.X)| in place of the square
 * roots. */
double pbr_ref_v_ggx_aniso(double at, double ab, const double l[3], const double v[3])
{
    if (!(l[2] > 0 && v[2] > 0)) return 0;
    double gv = l[2] * sqrt(sq(at * v[0]) + sq(ab * v[1]) + v[2] * v[2]);
    double gl = v[2] * sqrt(sq(at * l[0]) + sq(ab * l[1]) + l[2] * l[2]);
    return 0.5 / (gv + gl);
}

/* KHR_materials_sheen, "Sheen distribution" (Estevez & Kulla 2017):
 * D = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi). */
double pbr_ref_d_charlie(double alpha, double cos_h)
{
    if (!(cos_h > 0)) return 0;
    double sin2 = fmax(1 - cos_h * cos_h, 0.0), inv = 1 / alpha;
    return (2 + inv) * pow(sin2, 0.5 * inv) / (2 * PI);
}

/* KHR_materials_sheen, "Sheen visibility": the fitted l(x) of Estevez & Kulla, its five
 * coefficients interpolated by (1 - alpha)^2 between their alpha = 1 and alpha = 0 values. */
static double charlie_l(double x, double alpha)
{
    double t = sq(1 - alpha);
    double a = 21.5473 + (25.3245 - 21.5473) * t;
    double b = 3.82987 + (3.32435 - 3.82987) * t;
    double c = 0.19823 + (0.16801 - 0.19823) * t;
    double d = -1.97760 + (-1.27393 + 1.97760) * t;
    double e = -4.32054 + (-4.85967 + 4.32054) * t;
    return a / (1 + b * pow(x, c)) + d * x + e;
}

double pbr_ref_lambda_charlie(double alpha, double cos_theta)
{
    double c = fabs(cos_theta);
    return c < 0.5 ? exp(charlie_l(c, alpha))
                   : exp(2 * charlie_l(0.5, alpha) - charlie_l(1 - c, alpha));
}

/* V = 1 / ((1 + Lambda(N.V) + Lambda(N.L)) 4 N.V N.L). */
double pbr_ref_v_charlie(double alpha, double cos_l, double cos_v)
{
    if (!(cos_l > 0 && cos_v > 0)) return 0;
    double g = 1 + pbr_ref_lambda_charlie(alpha, cos_v) + pbr_ref_lambda_charlie(alpha, cos_l);
    return 1 / (g * 4 * cos_v * cos_l);
}

/* Nodes of the sheen albedo integral: Gauss-Legendre in cos(theta_l), midpoints in the
 * azimuth over [0, pi] (the lobe is symmetric about the plane of V). The Charlie lobe is
 * smooth in L for the widths a material uses; docs/GLTF.md states the integral's error. */
#define SHEEN_MU_NODES 64
#define SHEEN_PHI_NODES 128

static double sheen_albedo_at(double alpha, double cos_v)
{
    double x[SHEEN_MU_NODES], w[SHEEN_MU_NODES];
    quad_gauss_legendre01(SHEEN_MU_NODES, x, w);
    double sv = sqrt(fmax(1 - cos_v * cos_v, 0.0)), sum = 0;
    for (int i = 0; i < SHEEN_MU_NODES; ++i) {
        double cl = x[i], sl = sqrt(fmax(1 - cl * cl, 0.0));
        for (int j = 0; j < SHEEN_PHI_NODES; ++j) {
            double phi = PI * (j + 0.5) / SHEEN_PHI_NODES;
            double h[3] = {sl * cos(phi) + sv, sl * sin(phi), cl + cos_v};
            double len = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            double f =
                pbr_ref_d_charlie(alpha, h[2] / len) * pbr_ref_v_charlie(alpha, cl, cos_v) * cl;
            sum += f * w[i] * (2 * PI / SHEEN_PHI_NODES); /* both halves of the azimuth */
        }
    }
    return sum;
}

double pbr_ref_sheen_e(const pbr_ref *r, double cos_theta)
{
    double u = fmin(fmax(cos_theta, 0.0), 1.0) * (PBR_REF_SHEEN_N - 1);
    int i = (int)u;
    if (i >= PBR_REF_SHEEN_N - 1) return r->sheen_e[PBR_REF_SHEEN_N - 1];
    double t = u - i;
    return r->sheen_e[i] + t * (r->sheen_e[i + 1] - r->sheen_e[i]);
}

int pbr_ref_prepare(const abrdf_pbr *p, pbr_ref *out, char *msg, size_t msg_size)
{
    int st = abrdf_pbr_check(p, msg, msg_size);
    if (st != ABRDF_OK) return st;
    pbr_ref r;
    memset(&r, 0, sizeof r);
    double e2 = sq((p->ior - 1) / (p->ior + 1)); /* KHR_materials_ior */
    for (int c = 0; c < 3; ++c) {
        r.base[c] = p->base_color[c];
        r.f0d[c] = fmin(e2 * p->specular_color[c], 1.0); /* KHR_materials_specular */
        r.sheen[c] = p->sheen_color[c];
    }
    r.metallic = p->metallic;
    r.spec_w = p->specular;
    r.transmission = p->transmission;
    double alpha = fmax(sq(p->roughness), PBR_REF_ALPHA_MIN);
    r.alpha_b = alpha;
    r.alpha_t = alpha + (1 - alpha) * sq(p->anisotropy); /* mix(alpha, 1, strength^2) */
    r.clearcoat = p->clearcoat;
    r.coat_alpha = fmax(sq(p->clearcoat_roughness), PBR_REF_ALPHA_MIN);
    r.sheen_max = max3(r.sheen);
    r.sheen_alpha = fmax(sq(p->sheen_roughness), PBR_REF_ALPHA_MIN);
    if (r.sheen_max > 0)
        for (int i = 0; i < PBR_REF_SHEEN_N; ++i)
            r.sheen_e[i] = sheen_albedo_at(r.sheen_alpha, i / (double)(PBR_REF_SHEEN_N - 1));
    *out = r;
    return ABRDF_OK;
}

void pbr_ref_eval(const pbr_ref *r, const double wi[3], const double wo[3], double f[3])
{
    f[0] = f[1] = f[2] = 0;
    double cl = wi[2], cv = wo[2];
    if (!(cl > 0 && cv > 0)) return;
    double h[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double len = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    if (!(len > 0)) return;
    for (int c = 0; c < 3; ++c) h[c] /= len;
    double vh = wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2];
    /* B.3.3 (or KHR_materials_anisotropy): the specular lobe without Fresnel */
    double s = r->alpha_t == r->alpha_b
                   ? pbr_ref_d_ggx(r->alpha_t, h[2]) * pbr_ref_v_ggx(r->alpha_t, cl, cv)
                   : pbr_ref_d_ggx_aniso(r->alpha_t, r->alpha_b, h) *
                         pbr_ref_v_ggx_aniso(r->alpha_t, r->alpha_b, wi, wo);
    /* B.2.1 fresnel_mix with KHR_materials_specular's weight and colour: the diffuse is
     * weighted by the largest channel of the dielectric Fresnel */
    double fd[3];
    for (int c = 0; c < 3; ++c) fd[c] = pbr_ref_f_schlick(r->f0d[c], 1, vh);
    double keep = 1 - r->spec_w * max3(fd);
    for (int c = 0; c < 3; ++c) {
        double diffuse = (1 - r->transmission) * r->base[c] / PI; /* B.3.4, transmission mix */
        double dielectric = keep * diffuse + r->spec_w * fd[c] * s;
        double metal = pbr_ref_f_schlick(r->base[c], 1, vh) * s; /* conductor_fresnel */
        f[c] = (1 - r->metallic) * dielectric + r->metallic * metal;
    }
    if (r->sheen_max > 0) { /* KHR_materials_sheen, "Albedo-scaling technique" */
        double ds =
            pbr_ref_d_charlie(r->sheen_alpha, h[2]) * pbr_ref_v_charlie(r->sheen_alpha, cl, cv);
        double scale = fmin(1 - r->sheen_max * pbr_ref_sheen_e(r, cv),
                            1 - r->sheen_max * pbr_ref_sheen_e(r, cl));
        for (int c = 0; c < 3; ++c) f[c] = r->sheen[c] * ds + f[c] * scale;
    }
    if (r->clearcoat > 0) { /* KHR_materials_clearcoat, fresnel_coat over everything below */
        double fc = r->clearcoat * pbr_ref_f_schlick(0.04, 1, cv);
        double coat = pbr_ref_d_ggx(r->coat_alpha, h[2]) * pbr_ref_v_ggx(r->coat_alpha, cl, cv);
        for (int c = 0; c < 3; ++c) f[c] = f[c] * (1 - fc) + fc * coat;
    }
}
