/* measured.c - the `measured` model: trilinear interpolation in a caller's table on the MERL
 * half/difference grid, and the lobe its sampler draws from (measured.h).
 *
 * Rusinkiewicz, EGWR 1998, Sec. 3 (the half vector h and the difference vector d, the light
 * direction seen in h's frame); Matusik et al., SIGGRAPH 2003 (the grid). Cell (ih, id, ip)
 * holds f_r at theta_h = (ih/n_h)^2 pi/2, theta_d = id/n_d pi/2, phi_d = ip/n_p pi. */
#include "measured.h"

#include <math.h>
#include <stddef.h>

#define PI 3.14159265358979323846
#define HALF_PI 1.57079632679489661923

/* Below this sin(theta_h) the half vector is the normal for phi_h: phi_h = 0, as the grid's
 * cells are laid out (a 1e-12 offset moves phi_d by at most 1e-12 / sin). */
#define AZIMUTH_MIN 1e-12

/* Fractional grid coordinates of (wi, wo): u[0] along theta_h (square-root index), u[1]
 * along theta_d, u[2] along phi_d in [0, n_p]. 0 if either direction is not above the
 * surface. */
static int grid_coords(const abrdf__measured *m, const double wi[3], const double wo[3],
                       double u[3])
{
    if (!(wi[2] > 0.0 && wo[2] > 0.0)) return 0;
    double h[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double inv = 1.0 / sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]); /* h.z > 0: no zero */
    for (int c = 0; c < 3; ++c) h[c] *= inv;
    double s = sqrt(h[0] * h[0] + h[1] * h[1]);
    double theta_h = atan2(s, h[2]);
    /* theta_d: the angle between wi and h, by atan2 of |wi x h| and wi.h (exact near 0) */
    double x0 = wi[1] * h[2] - wi[2] * h[1], x1 = wi[2] * h[0] - wi[0] * h[2];
    double x2 = wi[0] * h[1] - wi[1] * h[0];
    double theta_d =
        atan2(sqrt(x0 * x0 + x1 * x1 + x2 * x2), wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]);
    /* phi_d: d = Ry(-theta_h) Rz(-phi_h) wi, its azimuth (Sec. 3) */
    double cp = 1.0, sp = 0.0;
    if (s > AZIMUTH_MIN) cp = h[0] / s, sp = h[1] / s;
    double dx = (wi[0] * cp + wi[1] * sp) * h[2] - wi[2] * s;
    double dy = wi[1] * cp - wi[0] * sp;
    double phi_d = atan2(dy, dx);
    if (phi_d < 0.0) phi_d += PI; /* phi_d and phi_d + pi: the same cell (reciprocity) */
    u[0] = sqrt(theta_h / HALF_PI) * m->n_h;
    u[1] = theta_d / HALF_PI * m->n_d;
    u[2] = phi_d / PI * m->n_p;
    return 1;
}

/* The two cells of an axis around coordinate u and the weight of the second: clamped to the
 * last cell (held beyond it), or periodic (phi_d). */
static void axis_cells(double u, int n, int periodic, int i[2], double *t)
{
    double fl = floor(u);
    if (periodic) {
        int k = (int)fl % n;
        i[0] = k < 0 ? k + n : k;
        i[1] = i[0] + 1 < n ? i[0] + 1 : 0;
        *t = u - fl;
    } else if (!(u > 0.0)) {
        i[0] = i[1] = 0;
        *t = 0.0;
    } else if (fl >= n - 1) {
        i[0] = i[1] = n - 1;
        *t = 0.0;
    } else {
        i[0] = (int)fl;
        i[1] = i[0] + 1;
        *t = u - fl;
    }
}

/* Trilinear interpolation over the measured corners: a channel whose value is negative (not
 * measured) or NaN drops out and the other corners' weights are renormalised; no measured
 * corner gives 0. */
static void lookup(const abrdf__measured *m, const double u[3], double f[3])
{
    int ih[2], id[2], ip[2];
    double th, td, tp;
    axis_cells(u[0], m->n_h, 0, ih, &th);
    axis_cells(u[1], m->n_d, 0, id, &td);
    axis_cells(u[2], m->n_p, 1, ip, &tp);
    double acc[3] = {0.0, 0.0, 0.0}, wsum[3] = {0.0, 0.0, 0.0};
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (int c = 0; c < 2; ++c) {
                double w = (a ? th : 1.0 - th) * (b ? td : 1.0 - td) * (c ? tp : 1.0 - tp);
                if (!(w > 0.0)) continue;
                size_t cell = ((size_t)ih[a] * (size_t)m->n_d + (size_t)id[b]) * (size_t)m->n_p +
                              (size_t)ip[c];
                const float *v = m->data + 3 * cell;
                for (int k = 0; k < 3; ++k)
                    if (v[k] >= 0.0f) acc[k] += w * v[k], wsum[k] += w;
            }
    for (int k = 0; k < 3; ++k) f[k] = wsum[k] > 0.0 ? acc[k] / wsum[k] : 0.0;
}

void abrdf__measured_eval(const abrdf__measured *m, const double wi[3], const double wo[3],
                          double f[3])
{
    double u[3];
    f[0] = f[1] = f[2] = 0.0;
    if (grid_coords(m, wi, wo, u)) lookup(m, u, f);
}

/* ---- the float batch: the same lookup in float ---------------------------------------- */

static float keep_f(float x) { return x >= 0.0f && x <= 3.4028234e38f ? x : 0.0f; }

void abrdf__measured_batch(const abrdf__measured *m, const abrdf_batch *b)
{
    const float nh = (float)m->n_h, nd = (float)m->n_d, np = (float)m->n_p;
    for (size_t i = 0; i < b->count; ++i) {
        float ix = b->wi_x[i], iy = b->wi_y[i], iz = b->wi_z[i];
        float ox = b->wo_x[i], oy = b->wo_y[i], oz = b->wo_z[i];
        b->f_r[i] = b->f_g[i] = b->f_b[i] = 0.0f;
        if (!(iz > 0.0f && oz > 0.0f)) continue;
        float hx = ix + ox, hy = iy + oy, hz = iz + oz;
        float inv = 1.0f / sqrtf(hx * hx + hy * hy + hz * hz);
        hx *= inv, hy *= inv, hz *= inv;
        float s = sqrtf(hx * hx + hy * hy);
        float theta_h = atan2f(s, hz);
        float x0 = iy * hz - iz * hy, x1 = iz * hx - ix * hz, x2 = ix * hy - iy * hx;
        float theta_d = atan2f(sqrtf(x0 * x0 + x1 * x1 + x2 * x2), ix * hx + iy * hy + iz * hz);
        float cp = 1.0f, sp = 0.0f;
        if (s > 1e-6f) cp = hx / s, sp = hy / s; /* AZIMUTH_MIN in float */
        float phi_d = atan2f(iy * cp - ix * sp, (ix * cp + iy * sp) * hz - iz * s);
        if (phi_d < 0.0f) phi_d += (float)PI;
        double u[3] = {sqrtf(theta_h / (float)HALF_PI) * nh, theta_d / (float)HALF_PI * nd,
                       phi_d / (float)PI * np};
        if (!(u[0] == u[0] && u[1] == u[1] && u[2] == u[2])) continue; /* NaN input */
        double f[3];
        lookup(m, u, f);
        b->f_r[i] = keep_f((float)f[0]);
        b->f_g[i] = keep_f((float)f[1]);
        b->f_b[i] = keep_f((float)f[2]);
    }
}

/* ---- the sampling lobe, fitted at prepare ------------------------------------------------
 * With the viewer on the normal (wo = N), the light at angle theta from it has theta_h =
 * theta_d = theta/2 and phi_d = 0: one line of the table holds the whole lobe. Its floor is
 * taken as the diffuse part (pi floor its albedo); what rises above it as a microfacet lobe
 * D(theta_h), whose second moment of tan(theta_h) under D cos sin is alpha^2 for Beckmann
 * (Walter et al., EGSR 2007, Eq. 33), used as the GGX alpha_g of the proposal. The lobe's
 * share of the draws is its share of the albedo at normal incidence. Only the efficiency of
 * the sampler depends on this: its pdf is exact whatever the fit (sample.h). */
#define LOBE_STEPS 128
#define LOBE_ALPHA_MIN 0.02 /* below this the proposal is narrower than the grid's cells */
#define LOBE_SHARE_MIN 0.1  /* each component keeps some draws: neither can starve */

/* A value the lobe fit can use: finite and >= 0 (a NaN or Inf cell gives 0, as evaluation
 * does). */
static double usable(double x) { return x >= 0.0 && x <= 1.7976931348623157e308 ? x : 0.0; }

static double luminance(const double f[3]) { return 0.2126 * f[0] + 0.7152 * f[1] + 0.0722 * f[2]; }

void abrdf__measured_setup(const abrdf_measured *table, abrdf__measured *m)
{
    m->data = table->data;
    m->n_h = table->n_theta_h;
    m->n_d = table->n_theta_d;
    m->n_p = table->n_phi_d;
    double lum[LOBE_STEPS], floor_v = INFINITY;
    const double wo[3] = {0.0, 0.0, 1.0};
    for (int k = 0; k < LOBE_STEPS; ++k) {
        double theta = (k + 0.5) / LOBE_STEPS * HALF_PI, f[3];
        double wi[3] = {sin(theta), 0.0, cos(theta)};
        abrdf__measured_eval(m, wi, wo, f);
        for (int c = 0; c < 3; ++c) f[c] = usable(f[c]);
        lum[k] = luminance(f);
        if (lum[k] < floor_v) floor_v = lum[k];
    }
    double m0 = 0.0, m2 = 0.0, lobe_albedo = 0.0, dtheta = HALF_PI / LOBE_STEPS;
    for (int k = 0; k < LOBE_STEPS; ++k) {
        double theta = (k + 0.5) * dtheta, th = 0.5 * theta, spec = lum[k] - floor_v;
        double w = spec * cos(th) * sin(th), t = tan(th);
        m0 += w;
        m2 += w * t * t;
        lobe_albedo += 2.0 * PI * spec * cos(theta) * sin(theta) * dtheta;
    }
    double alpha = m0 > 0.0 ? sqrt(m2 / m0) : 1.0;
    m->alpha = alpha > LOBE_ALPHA_MIN ? (alpha < 1.0 ? alpha : 1.0) : LOBE_ALPHA_MIN;
    double diffuse_albedo = PI * floor_v, total = lobe_albedo + diffuse_albedo;
    double share = total > 0.0 ? lobe_albedo / total : 0.5;
    m->p_lobe = share > LOBE_SHARE_MIN
                    ? (share < 1.0 - LOBE_SHARE_MIN ? share : 1.0 - LOBE_SHARE_MIN)
                    : LOBE_SHARE_MIN;
}
