/* measured.c - the `measured` model: trilinear interpolation in a caller's table on the MERL
 * half/difference grid, and the lobe its sampler draws from (measured.h).
 *
 * Rusinkiewicz, EGWR 1998, Sec. 3 (the half vector h and the difference vector d, the light
 * direction seen in h's frame); Matusik et al., SIGGRAPH 2003 (the grid). Cell (ih, id, ip)
 * holds f_r at theta_h = (ih/n_h)^2 pi/2, theta_d = id/n_d pi/2, phi_d = ip/n_p pi. */
#include "measured.h"

#include "isa.h"

#include <float.h>
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
    /* a NaN coordinate (h underflowing to 0 for directions a few 1e-160 above the horizon)
     * reads nothing */
    return u[0] >= 0.0 && u[1] >= 0.0 && u[2] >= 0.0 && u[2] <= m->n_p;
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
                    if (v[k] >= 0.0f && v[k] <= FLT_MAX) acc[k] += w * v[k], wsum[k] += w;
            }
    for (int k = 0; k < 3; ++k) f[k] = wsum[k] > 0.0 ? acc[k] / wsum[k] : 0.0;
}

/* 1 if (a, b) comes after (b, a) in the order the lookup takes its pair in: the larger
 * cosine first (then x, then y), so that f(wi, wo) and f(wo, wi) are one computation and
 * reciprocity holds to the bit, not to rounding. */
static int after(const double a[3], const double b[3])
{
    if (a[2] != b[2]) return a[2] < b[2];
    if (a[0] != b[0]) return a[0] < b[0];
    return a[1] < b[1];
}

void abrdf__measured_eval(const abrdf__measured *m, const double wi[3], const double wo[3],
                          double f[3])
{
    double u[3];
    f[0] = f[1] = f[2] = 0.0;
    if (after(wi, wo)) {
        const double *t = wi;
        wi = wo, wo = t;
    }
    if (grid_coords(m, wi, wo, u)) lookup(m, u, f);
}

/* ---- the float batch: the same lookup in float, on the vector unit ----------------------
 * The loop below has no call and no branch, so the compiler vectorises it at every
 * instruction-set level (isa.h): the angles come from atan_01, the table's corners are
 * gathered by 32-bit indices (abrdf_prepare_measured bounds a table below 2^31 values), and
 * every coordinate is clamped into the grid before it becomes an index, so no input (NaN,
 * a direction below the surface) can read outside the table. */

/* atan(a) for a in [0, 1]: a P(a^2), P of degree 7 fitted here to the relative error
 * (iterated weighted least squares on Chebyshev nodes); 2.3e-7 relative at most in float,
 * measured on 2e5 points (docs/MEASURED.md). */
static inline float atan_01(float a)
{
    const float t = a * a;
    float p = -0.004693686f;
    p = p * t + 0.024253951f;
    p = p * t - 0.059488732f;
    p = p * t + 0.099144727f;
    p = p * t - 0.140195549f;
    p = p * t + 0.199697390f;
    p = p * t - 0.333319932f;
    p = p * t + 0.999999881f;
    return a * p;
}

/* The angle of (x, y) with x, y >= 0, in [0, pi/2]; 0 for (0, 0). */
static inline float atan2_q1(float y, float x)
{
    float hi = x > y ? x : y, lo = x > y ? y : x;
    float r = atan_01(hi > 0.0f ? lo / hi : 0.0f);
    return y > x ? (float)HALF_PI - r : r;
}

/* Cell pair and weight of a clamped axis, u in [0, last + 1]. */
static inline void axis_f(float u, float last, int *i0, int *i1, float *t)
{
    float v = u < last ? u : last; /* held at the last cell */
    /* floorf before each conversion, and the selects in float: without them GCC does not
     * if-convert the loop at the AVX2 and AVX-512 levels (a select feeding a conversion) */
    float fl = floorf(v);
    *i0 = (int)fl;
    *t = v - fl;
    *i1 = (int)(v < last ? fl + 1.0f : fl);
}

/* A coordinate into [0, hi]: NaN (a degenerate input) gives 0. */
static inline float into(float u, float hi) { return u >= 0.0f ? (u < hi ? u : hi) : 0.0f; }

#define MEASURED_BATCH_ARGS                                                                        \
    const float *restrict data, int nh, int nd, int np, size_t n, const float *restrict ix,        \
        const float *restrict iy, const float *restrict iz, const float *restrict ox,              \
        const float *restrict oy, const float *restrict oz, float *restrict fr,                    \
        float *restrict fg, float *restrict fb

/* One level's loop: batch_measured_L. */
#define MEASURED_BATCH_LOOP(L)                                                                     \
    ABRDF__NOINLINE ABRDF__ISA_ATTR_##L static void batch_measured_##L(MEASURED_BATCH_ARGS)        \
    {                                                                                              \
        const float sh = (float)nh, sd = (float)nd, sp = (float)np;                                \
        for (size_t i = 0; i < n; ++i) {                                                           \
            /* the pair in the double path's order (after): exactly reciprocal */                  \
            float ax = ix[i], ay = iy[i], az = iz[i], bx = ox[i], by = oy[i], bz = oz[i];          \
            float sw = ay < by ? 1.0f : 0.0f;                                                      \
            sw = ax != bx ? (ax < bx ? 1.0f : 0.0f) : sw;                                          \
            sw = az != bz ? (az < bz ? 1.0f : 0.0f) : sw;                                          \
            float wx = sw > 0.0f ? bx : ax, wy = sw > 0.0f ? by : ay, wz = sw > 0.0f ? bz : az;    \
            float hx = ax + bx, hy = ay + by, hz = az + bz;                                        \
            /* h unnormalised: theta_h and theta_d are atan2 of two numbers of the same      \
             * degree in h, so |h| cancels; phi_d's (d_x, d_y) are taken times s |h| > 0     \
             * (four divisions fewer than normalising h and its azimuth) */     \
            float s2 = hx * hx + hy * hy, s = sqrtf(s2), hn = sqrtf(s2 + hz * hz);                 \
            float theta_h = atan2_q1(s, hz);                                                       \
            float x0 = wy * hz - wz * hy, x1 = wz * hx - wx * hz, x2 = wx * hy - wy * hx;          \
            float cd = wx * hx + wy * hy + wz * hz;                                                \
            float theta_d = atan2_q1(sqrtf(x0 * x0 + x1 * x1 + x2 * x2), cd > 0.0f ? cd : 0.0f);   \
            /* phi_h = 0 where h is the normal (AZIMUTH_MIN in float): d = (wx hz - wz s, wy) */   \
            float azim = s > 1e-6f * hn ? 1.0f : 0.0f;                                             \
            float dx = azim > 0.0f ? (wx * hx + wy * hy) * hz - wz * s2 : wx * hz - wz * s;        \
            float dy = (azim > 0.0f ? wy * hx - wx * hy : wy) * hn;                                \
            float flip = dy < 0.0f ? -1.0f : 1.0f; /* phi_d + pi: the same cell */                 \
            dx *= flip, dy *= flip;                                                                \
            float a_d = atan2_q1(dy, fabsf(dx));                                                   \
            float phi_d = dx >= 0.0f ? a_d : (float)PI - a_d;                                      \
            float uh = into(sqrtf(theta_h * (float)(1.0 / HALF_PI)) * sh, sh);                     \
            float ud = into(theta_d * (float)(1.0 / HALF_PI) * sd, sd);                            \
            float up = into(phi_d * (float)(1.0 / PI) * sp, sp);                                   \
            int h0, h1, d0, d1, p0, p1;                                                            \
            float th, td, tp;                                                                      \
            axis_f(uh, sh - 1.0f, &h0, &h1, &th);                                                  \
            axis_f(ud, sd - 1.0f, &d0, &d1, &td);                                                  \
            float q = up < sp ? up : 0.0f; /* phi_d = pi is phi_d = 0 */                           \
            float fq = floorf(q);                                                                  \
            p0 = (int)fq;                                                                          \
            tp = q - fq;                                                                           \
            p1 = (int)(fq + 1.0f < sp ? fq + 1.0f : 0.0f);                                         \
            float acc[3] = {0.0f, 0.0f, 0.0f}, ws[3] = {0.0f, 0.0f, 0.0f};                         \
            CORNER(h0, d0, p0, (1.0f - th) * (1.0f - td) * (1.0f - tp));                           \
            CORNER(h0, d0, p1, (1.0f - th) * (1.0f - td) * tp);                                    \
            CORNER(h0, d1, p0, (1.0f - th) * td * (1.0f - tp));                                    \
            CORNER(h0, d1, p1, (1.0f - th) * td * tp);                                             \
            CORNER(h1, d0, p0, th *(1.0f - td) * (1.0f - tp));                                     \
            CORNER(h1, d0, p1, th *(1.0f - td) * tp);                                              \
            CORNER(h1, d1, p0, th *td *(1.0f - tp));                                               \
            CORNER(h1, d1, p1, th *td *tp);                                                        \
            float front = az > 0.0f ? 1.0f : 0.0f;                                                 \
            front = bz > 0.0f ? front : 0.0f;                                                      \
            fr[i] = keep_f(ws[0] > 0.0f ? acc[0] / ws[0] : 0.0f) * front;                          \
            fg[i] = keep_f(ws[1] > 0.0f ? acc[1] / ws[1] : 0.0f) * front;                          \
            fb[i] = keep_f(ws[2] > 0.0f ? acc[2] / ws[2] : 0.0f) * front;                          \
        }                                                                                          \
    }
/* A corner's channels with weight W: a channel not measured (negative) or NaN drops out. */
#define CORNER(H, D, P, W)                                                                         \
    do {                                                                                           \
        const float w_ = (W);                                                                      \
        const int c_ = 3 * (((H)*nd + (D)) * np + (P));                                            \
        for (int k_ = 0; k_ < 3; ++k_) {                                                           \
            float v_ = data[c_ + k_];                                                              \
            float ok_ = v_ >= 0.0f ? 1.0f : 0.0f; /* not measured (< 0, NaN) or Inf: out */        \
            ok_ = v_ <= 3.4028234e38f ? ok_ : 0.0f;                                                \
            acc[k_] += ok_ > 0.0f ? w_ * v_ : 0.0f;                                                \
            ws[k_] += ok_ > 0.0f ? w_ : 0.0f;                                                      \
        }                                                                                          \
    } while (0)

static float keep_f(float x) { return x >= 0.0f && x <= 3.4028234e38f ? x : 0.0f; }

ABRDF__ISA_LEVELS(MEASURED_BATCH_LOOP)

#define MEASURED_BATCH_CASE(L)                                                                     \
    case L:                                                                                        \
        batch_measured_##L(m->data, m->n_h, m->n_d, m->n_p, b->count, b->wi_x, b->wi_y, b->wi_z,   \
                           b->wo_x, b->wo_y, b->wo_z, b->f_r, b->f_g, b->f_b);                     \
        break;

void abrdf__measured_batch(const abrdf__measured *m, const abrdf_batch *b, int level)
{
    switch (level) {
        ABRDF__ISA_LEVELS(MEASURED_BATCH_CASE)
    default: break;
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
