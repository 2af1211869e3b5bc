/* pbr_error.c - the glTF mapping's measured error: furnace albedo and sphere image NMSE of
 * abrdf_pbr_lobes against the glTF BRDF as specified (pbr_error.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pbr_error.h"
#include "quad.h"

static const double PI = 3.14159265358979323846;

int pbr_mapped_make(const abrdf_pbr *p, pbr_mapped *m)
{
    memset(m, 0, sizeof *m);
    abrdf_params_init(ABRDF_LAMBERT, &m->params);
    return abrdf_pbr_lobes(p, m->lobes, &m->count, &m->params);
}

void pbr_mapped_eval(const void *ctx, const double wi[3], const double wo[3], double f[3])
{
    const pbr_mapped *m = ctx;
    f[0] = f[1] = f[2] = 0;
    for (int k = 0; k < m->count; ++k) {
        double g[3];
        abrdf_eval(m->lobes[k], &m->params, NULL, wi, wo, g);
        for (int c = 0; c < 3; ++c) f[c] += g[c];
    }
}

void pbr_ref_brdf(const void *ctx, const double wi[3], const double wo[3], double f[3])
{
    pbr_ref_eval(ctx, wi, wo, f);
}

/* ---- furnace albedo ------------------------------------------------------------------ */

/* Density over the solid angle of h of the half vectors pbr_albedo places for width a:
 * v uniform, u = 1 - (1 - v)^2, tan^2 theta_h = a^2 u / (1 - u), azimuth uniform, which is
 * a / (2 pi (a^2 + tan^2 theta_h)^(3/2) cos^3 theta_h) (it integrates to 1 over the
 * hemisphere; a = 1 is uniform). */
static double half_density(double a, double cos_h)
{
    double c2 = cos_h * cos_h, t = (1 - c2) / c2;
    return a / (2 * PI * pow(a * a + t, 1.5) * c2 * cos_h);
}

/* The smallest width the quadrature follows: narrower lobes than this are integrated as if
 * this wide (the nodes then miss part of the peak; no material row is that smooth). */
#define ALBEDO_WIDTH_MIN 1e-4

/* The sets' combined density at wi, each half-vector set's density (over the solid angle
 * of wi: dwi = 4 (wo.h) dwh) weighted by c = cos^2 / (cos^2 + ALBEDO_HORIZON^2), theta_i's cosine.
 * The weights make a partition of unity as the balance heuristic's do, but hand the
 * directions near the horizon to the cosine-weighted set: a half-vector set's nodes run
 * past the horizon, and its share there would end in a kink Gauss-Legendre converges on
 * slowly; weighted by c it ends smoothly. ALBEDO_HORIZON 0.3: of 1e-4, 0.05, 0.15 and 0.3,
 * the one whose albedos over the table's rows moved least from order 96 to 384 (1.2e-4).
 * *own receives this set's weighted density. */
#define ALBEDO_HORIZON 0.3
static double light_density(const double *a, int n, int set, const double wi[3], const double wo[3],
                            double *own)
{
    double h[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double len = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    double ch = h[2] / len, vh = (wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2]) / len;
    double p = wi[2] / PI, c2 = wi[2] * wi[2] / (wi[2] * wi[2] + ALBEDO_HORIZON * ALBEDO_HORIZON);
    *own = p;
    for (int m = 0; m < n; ++m) {
        double q = c2 * half_density(a[m], ch) / (4 * vh);
        p += q;
        if (m == set) *own = q;
    }
    return p;
}

void pbr_albedo(pbr_brdf_fn fn, const void *ctx, const double wo[3], const double *widths,
                int width_count, int order, double rho[3])
{
    double x[QUAD_ORDER_MAX], w[QUAD_ORDER_MAX], a[PBR_ALBEDO_WIDTHS_MAX];
    rho[0] = rho[1] = rho[2] = 0;
    if (order > QUAD_ORDER_MAX) order = QUAD_ORDER_MAX;
    if (width_count > PBR_ALBEDO_WIDTHS_MAX) width_count = PBR_ALBEDO_WIDTHS_MAX;
    for (int k = 0; k < width_count; ++k) a[k] = fmax(widths[k], ALBEDO_WIDTH_MIN);
    quad_gauss_legendre01(order, x, w);
    int nphi = 2 * order;
    /* set -1: wi cosine-weighted (sin^2 theta_i = v); set k: half vectors of width a[k] */
    for (int k = -1; k < width_count; ++k)
        for (int i = 0; i < order; ++i) {
            double ct, st;
            if (k < 0) {
                st = sqrt(x[i]), ct = sqrt(1 - x[i]);
            } else {
                double mv = 1 - x[i], u = 1 - mv * mv;
                double tn = a[k] * sqrt(u / (1 - u));
                ct = 1 / sqrt(1 + tn * tn), st = tn * ct;
            }
            for (int j = 0; j < nphi; ++j) {
                double phi = 2 * PI * (j + 0.5) / nphi;
                double d[3] = {st * cos(phi), st * sin(phi), ct}, wi[3];
                if (k < 0) {
                    memcpy(wi, d, sizeof wi);
                } else {
                    double vh = wo[0] * d[0] + wo[1] * d[1] + wo[2] * d[2];
                    if (!(vh > 0)) continue;
                    for (int c = 0; c < 3; ++c) wi[c] = 2 * vh * d[c] - wo[c];
                }
                if (!(wi[2] > 0)) continue;
                /* this set's share of wi over its own density (weighted as above) */
                double own, all = light_density(a, width_count, k, wi, wo, &own);
                double pk =
                    k < 0 ? own : own * (1 + ALBEDO_HORIZON * ALBEDO_HORIZON / (wi[2] * wi[2]));
                double q = w[i] / nphi * wi[2] * (own / all) / pk;
                double f[3];
                fn(ctx, wi, wo, f);
                for (int c = 0; c < 3; ++c) rho[c] += f[c] * q;
            }
        }
}

/* ---- the sphere ---------------------------------------------------------------------- */

/* abrdf_predict_nmse's default view (abrdf_fit.h, predict.c). */
#define SPHERE_RES_DEFAULT 128
#define SPHERE_RES_MAX 1024
#define SPHERE_GRIDS 4
static const double sphere_light_dir[2][3] = {{-1, 1, 1}, {1, 0.3, 0.5}};
static const double sphere_light_e[2] = {3, 1};

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void local(const abrdf_frame *fr, const double v[3], double o[3])
{
    o[0] = dot3(v, fr->t), o[1] = dot3(v, fr->b), o[2] = dot3(v, fr->n);
}

int pbr_sphere_nmse(pbr_brdf_fn test, const void *test_ctx, pbr_brdf_fn ref, const void *ref_ctx,
                    int resolution, double *nmse)
{
    *nmse = -1;
    if (resolution < 0 || resolution > SPHERE_RES_MAX) return ABRDF_E_RANGE;
    int res = resolution ? resolution : SPHERE_RES_DEFAULT;
    const double V[3] = {0, 0, 1}, up[3] = {0, 1, 0};
    double X[3], Y[3], L[2][3];
    cross3(up, V, X); /* screen right */
    cross3(V, X, Y);  /* screen up */
    for (int l = 0; l < 2; ++l) {
        double n = sqrt(dot3(sphere_light_dir[l], sphere_light_dir[l]));
        for (int c = 0; c < 3; ++c) L[l][c] = sphere_light_dir[l][c] / n;
    }
    static const double shift[SPHERE_GRIDS][2] = {{0, 0}, {0.5, 0}, {0, 0.5}, {0.5, 0.5}};
    double worst = 0;
    for (int g = 0; g < SPHERE_GRIDS; ++g) {
        double num = 0, den = 0;
        for (int j = 0; j < res; ++j)
            for (int i = 0; i < res; ++i) {
                double x = (2.0 * (i + shift[g][0]) + 1) / res - 1;
                double y = 1 - (2.0 * (j + shift[g][1]) + 1) / res;
                double z2 = 1 - x * x - y * y;
                if (!(z2 > 0)) continue; /* off the disk: black in both images */
                double z = sqrt(z2), N[3], T[3];
                for (int c = 0; c < 3; ++c) N[c] = x * X[c] + y * Y[c] + z * V[c];
                cross3(N, up, T); /* the tangent around the axis (the scene format's `u`) */
                abrdf_frame fr;
                abrdf_frame_make(N, T, &fr);
                double it[3] = {0, 0, 0}, ir[3] = {0, 0, 0}, wo[3];
                local(&fr, V, wo);
                for (int l = 0; l < 2; ++l) {
                    double ci = dot3(fr.n, L[l]);
                    if (!(ci > 0) || !(wo[2] > 0)) continue;
                    double wi[3], ft[3], fref[3];
                    local(&fr, L[l], wi);
                    test(test_ctx, wi, wo, ft);
                    ref(ref_ctx, wi, wo, fref);
                    for (int c = 0; c < 3; ++c) {
                        it[c] += sphere_light_e[l] * ci * ft[c];
                        ir[c] += sphere_light_e[l] * ci * fref[c];
                    }
                }
                for (int c = 0; c < 3; ++c)
                    num += (it[c] - ir[c]) * (it[c] - ir[c]), den += ir[c] * ir[c];
            }
        if (!(den > 0)) return ABRDF_E_RANGE;
        worst = fmax(worst, num / den);
    }
    *nmse = worst;
    return ABRDF_OK;
}

/* ---- the table's rows ---------------------------------------------------------------- */

const double pbr_error_angle_deg[PBR_ERROR_ANGLES] = {0, 45, 75};
const double pbr_error_azimuth_deg[PBR_ERROR_AZIMUTHS] = {0, 90};

#define ERROR_ROWS_MAX 16
static pbr_error_row rows[ERROR_ROWS_MAX];
static int row_count;

/* A dielectric of glTF's defaults but metallic 0, the base colour (0.8, 0.3, 0.2) and
 * roughness 0.4, which each row then changes. */
static abrdf_pbr *row(const char *name, const char *values, const char *exact, const char *approx)
{
    pbr_error_row *r = &rows[row_count++];
    r->name = name, r->values = values, r->exact = exact, r->approx = approx;
    abrdf_pbr_init(&r->material);
    r->material.base_color[0] = 0.8, r->material.base_color[1] = 0.3;
    r->material.base_color[2] = 0.2;
    r->material.metallic = 0;
    r->material.roughness = 0.4;
    return &r->material;
}

#define ROW_EXACT_D "GGX D (alpha = r^2)"
#define ROW_MASKING "masking: separable Smith vs height-correlated"

static void rows_make(void)
{
    abrdf_pbr *p;
    p = row("dielectric, rough", "base (0.8, 0.3, 0.2), r 0.7",
            ROW_EXACT_D ", Fresnel, diffuse 1 - F", ROW_MASKING);
    p->roughness = 0.7;
    p = row("dielectric, smooth", "base (0.8, 0.3, 0.2), r 0.1",
            ROW_EXACT_D ", Fresnel, diffuse 1 - F", ROW_MASKING);
    p->roughness = 0.1;
    p = row("metal", "metallic 1, base (0.95, 0.64, 0.54), r 0.3",
            ROW_EXACT_D ", Fresnel (f0 = base), no diffuse", ROW_MASKING);
    p->metallic = 1, p->roughness = 0.3;
    p->base_color[0] = 0.95, p->base_color[1] = 0.64, p->base_color[2] = 0.54;
    p = row("metallic 0.5", "metallic 0.5, r 0.4",
            ROW_EXACT_D ", specular Fresnel mix (ks Schlick(f0)), diffuse (kd scaled)",
            ROW_MASKING);
    p->metallic = 0.5;
    p = row("specular 0.5", "specular 0.5, r 0.4", ROW_EXACT_D ", specular Fresnel (ks = 0.5)",
            ROW_MASKING "; diffuse 1 - F, not 1 - 0.5 F");
    p->specular = 0.5;
    p = row("coloured specular", "specular_color (2, 1, 0.5), r 0.4",
            ROW_EXACT_D ", specular Fresnel per channel, diffuse 1 - max F (kd scaled)",
            ROW_MASKING);
    p->specular_color[0] = 2, p->specular_color[2] = 0.5;
    p = row("ior 2", "ior 2, r 0.4", ROW_EXACT_D ", Fresnel (f0 = 1/9), diffuse 1 - F",
            ROW_MASKING);
    p->ior = 2;
    p = row("anisotropy 0.5", "metallic 1, base 0.9, r 0.4, anisotropy 0.5",
            "alpha_t alpha_b and alpha_t / alpha_b (Disney aspect), Fresnel",
            ROW_MASKING " (anisotropic)");
    p->metallic = 1, p->anisotropy = 0.5;
    p->base_color[0] = p->base_color[1] = p->base_color[2] = 0.9;
    p = row("clearcoat 1", "clearcoat 1, clearcoat_roughness 0.1, r 0.4",
            "the base, as the dielectric rows",
            ROW_MASKING "; the coat left out: its lobe and the base's 1 - Fc");
    p->clearcoat = 1, p->clearcoat_roughness = 0.1;
    p = row("sheen", "sheen_color 0.8, sheen_roughness 0.5, r 0.7",
            "the base, as the dielectric rows",
            ROW_MASKING "; the sheen left out: its lobe and the base's albedo scaling");
    p->roughness = 0.7, p->sheen_roughness = 0.5;
    p->sheen_color[0] = p->sheen_color[1] = p->sheen_color[2] = 0.8;
    p = row("transmission 0.5", "transmission 0.5, r 0.4",
            "reflection: diffuse (1 - T) (1 - F), specular, Fresnel",
            ROW_MASKING "; the transmitted light is not carried");
    p->transmission = 0.5;
}

const pbr_error_row *pbr_error_rows(int *count)
{
    if (!row_count) rows_make();
    *count = row_count;
    return rows;
}

/* The quadrature order of the table's albedos: the unit test measures its convergence. */
#define ERROR_ALBEDO_ORDER 96

int pbr_error_measure(const abrdf_pbr *p, pbr_error_result *out, char *msg, size_t msg_size)
{
    pbr_ref ref;
    pbr_mapped map;
    int st = pbr_ref_prepare(p, &ref, msg, msg_size);
    if (st != ABRDF_OK) return st;
    st = pbr_mapped_make(p, &map);
    if (st != ABRDF_OK) return st;
    double widths[PBR_ALBEDO_WIDTHS_MAX];
    int nw = 0;
    widths[nw++] = ref.alpha_b;
    if (ref.alpha_t != ref.alpha_b) widths[nw++] = ref.alpha_t;
    if (ref.clearcoat > 0) widths[nw++] = ref.coat_alpha;
    memset(out, 0, sizeof *out);
    for (int k = 0; k < PBR_ERROR_ANGLES; ++k) {
        double t = pbr_error_angle_deg[k] * PI / 180;
        for (int z = 0; z < PBR_ERROR_AZIMUTHS; ++z) {
            double ph = pbr_error_azimuth_deg[z] * PI / 180;
            double wo[3] = {sin(t) * cos(ph), sin(t) * sin(ph), cos(t)}, rr[3], rm[3];
            pbr_albedo(pbr_ref_brdf, &ref, wo, widths, nw, ERROR_ALBEDO_ORDER, rr);
            pbr_albedo(pbr_mapped_eval, &map, wo, widths, nw, ERROR_ALBEDO_ORDER, rm);
            for (int c = 0; c < 3; ++c)
                if (fabs(rm[c] - rr[c]) > fabs(out->albedo_err[k]))
                    out->albedo_err[k] = rm[c] - rr[c];
        }
        out->albedo_max_abs = fmax(out->albedo_max_abs, fabs(out->albedo_err[k]));
    }
    return pbr_sphere_nmse(pbr_mapped_eval, &map, pbr_ref_brdf, &ref, 0, &out->nmse);
}
