/* layered_ww.c - Weidlich-Wilkie layered model (Eq. 15), an arbitrary stack of rough
 * interfaces over a Lambertian base.
 *
 * A. Weidlich, A. Wilkie, "Arbitrarily layered micro-facet surfaces", GRAPHITE 2007; the
 * reading of I. Kabel, "Rendering layered materials: Weidlich-Wilkie layered model" (2018)
 * for the points the paper leaves open (MODELS.md B8.1). Per interface k (top to bottom):
 *   f_k(L, V) = f_top,k(L, V) + T12 f_{k+1}(L', V') a t                       (Eq. 15)
 *   f_top,k   = F(L.H) D_GGX(H) G(L, V) / (4 cos_i cos_o), exact Fresnel of eta_k + i kappa_k
 *   T12 = T21 = 1 - F(L.H)      (dielectric Fresnel transmission, in and out)
 *   L', V'    = L and V refracted by Snell's law at the top microfacet normal H (the
 *               original's single refraction point; Kabel suggests N instead). Because
 *               L.H = V.H, the entry and exit transmissions are equal and the model is
 *               reciprocal; the paper's T12 / T21 naming ambiguity (B8.1) is moot.
 *   a = exp(-sigma_a d (1/|N.L'| + 1/|N.V'|))  (absorption in the medium below)
 *   t = (1 - G) + T21 G, G = G1(L) G1(V) the interface's separable Smith term (as printed;
 *       the paper does not explain it).
 * Recursion: f_{k+1} is the same formula for the next interface in the medium below, with
 * the refracted directions. An interface with kappa > 0 is a conductor: opaque, it ends the
 * stack. Below the last dielectric interface lies a Lambertian base kd/pi.
 * Total internal reflection: refraction into a less dense layer (eta < 1) beyond the
 * critical angle transmits nothing (F = 1 and the refraction fails), so that path is 0.
 * Not done, as in the original: the solid-angle compression (the 1/eta^2 radiance factor
 * and the cos'/cos Jacobian), multiple inter-reflection between layers. With refraction at
 * H, L' + V' stays parallel to H, so a glossy base keeps its half-vector lobe (no solid-
 * angle gain). The model is not energy-conserving: at grazing incidence the coat's lobe and
 * the transmitted base overlap (albedo up to 1.15 over a white Lambert base, measured in
 * docs/MODELS.md, "Weidlich-Wilkie"); elsewhere it loses the inter-reflected light. */
#include <float.h>
#include <math.h>

#include "fmath.h"
#include "isa.h"
#include "layered.h"
#include "layered_optics.h"
#include "vec.h"

void abrdf__ww_setup(const abrdf_params *p, abrdf__ww *w)
{
    int count = p->layer_count < ABRDF_MAX_LAYERS ? p->layer_count : ABRDF_MAX_LAYERS;
    w->count = count < 0 ? 0 : count;
    for (int k = 0; k < ABRDF_MAX_LAYERS; ++k) {
        const abrdf_layer *ly = &p->layers[k];
        double ag = ly->r * ly->r;
        ag = ag > ABRDF__ALPHA_G_MIN ? ag : ABRDF__ALPHA_G_MIN;
        w->a2[k] = ag * ag;
        w->eta[k] = ly->eta;
        w->kappa[k] = ly->kappa;
        w->eta2[k] = ly->eta * ly->eta;
        w->inv_eta[k] = 1.0 / ly->eta;
        w->kind[k] = ly->kappa > 0.0  ? ABRDF__WW_CONDUCTOR
                     : ly->eta == 1.0 ? ABRDF__WW_MATCHED /* no interface at all */
                                      : ABRDF__WW_DIELECTRIC;
        for (int c = 0; c < 3; ++c) w->sd[k][c] = ly->sigma_a[c] * ly->depth;
        w->absorbs[k] = w->sd[k][0] > 0.0 || w->sd[k][1] > 0.0 || w->sd[k][2] > 0.0;
        w->grey[k] = w->sd[k][0] == w->sd[k][1] && w->sd[k][0] == w->sd[k][2];
    }
    for (int k = 0; k < w->count; ++k)
        if (w->kind[k] == ABRDF__WW_CONDUCTOR) w->count = k + 1;       /* opaque: ends the stack */
    for (int c = 0; c < 3; ++c) w->base[c] = p->kd[c] * ABRDF__INV_PI; /* Lambert base, Eq. 1 */
}

/* The exact dielectric Fresnel reflectance (layered_optics.h at kappa = 0) as a fraction
 * *num / *den, so that the caller folds its division into its own: with g^2 = eta^2 - sin^2,
 *   F = 1/2 (g - c)^2 / (g + c)^2 (1 + (c g - s^2)^2 / (c g + s^2)^2)
 *     = (g - c)^2 (c^2 g^2 + s^4) / ((g + c)^2 (c g + s^2)^2),
 * one root where the complex formula takes two and two divisions. No g (g^2 <= 0): total
 * internal reflection, F = 1 and 0 is returned. c is in [0, 1], c2 = c^2 (known without c's
 * root, so that g's root need not wait for it). Returns g^2 where light is transmitted (> 0),
 * else 0, and g in *g: the refracted cosine is g / eta (Snell: 1 - (1 - c^2) / eta^2 =
 * g^2 / eta^2), no root of its own. Selects, no branch: the double path calls it per pair,
 * the batch path inside its vectorised loop over a block's lanes. */
static inline double ww_dielectric(double c, double c2, double eta2, double *num, double *den,
                                   double *g)
{
    double s2 = 1.0 - c2, g2 = eta2 - s2;
    double gg = sqrt(g2 > 0.0 ? g2 : 0.0), cg = c * gg, gm = gg - c, dp = (gg + c) * (cg + s2);
    double n = gm * gm * (cg * cg + s2 * s2), d = dp * dp;
    double ok = g2 > 0.0 ? 1.0 : 0.0;
    ok = d > 0.0 ? ok : 0.0; /* d is 0 only at g = c = 0, eta = 1 */
    *num = ok > 0.0 ? n : 1.0;
    *den = ok > 0.0 ? d : 1.0;
    *g = gg;
    return ok > 0.0 ? g2 : 0.0;
}

/* Interface k's Fresnel term as ww_dielectric's fraction: F over 1 for the matched (0) and
 * conductor interfaces, which transmit along the cosine itself (g = c, g^2 = c2). */
static inline double ww_fresnel(const abrdf__ww *w, int k, double c, double c2, double *num,
                                double *den, double *g)
{
    if (w->kind[k] == ABRDF__WW_DIELECTRIC) return ww_dielectric(c, c2, w->eta2[k], num, den, g);
    *num = 0.0, *den = 1.0, *g = c;
    if (w->kind[k] == ABRDF__WW_CONDUCTOR) *num = abrdf__fresnel_exact(c, w->eta[k], w->kappa[k]);
    return c2;
}

#if defined(__GNUC__)
#define ABRDF__WW_INLINE __attribute__((always_inline)) /* one specialised copy per variant */
#else
#define ABRDF__WW_INLINE
#endif

/* What the recursion carries from one interface to the next. */
typedef struct ww_state {
    double ci, co, cd, cd2; /* N.L, N.V, L.H and (L.H)^2 at the interface */
    double sxy, z;          /* |N x H|^2 and N.H, up to the scale of ww_interface's u */
    double wt[3], f[3];     /* the product of the weights W above; the sum so far */
} ww_state;

/* Interface k: its top term added to st->f, then (return 1) the state below it, or 0 where
 * nothing goes through (a conductor, total internal reflection, refraction below the
 * horizon). D's t = |N x H|^2 + a2 (N.H)^2 is (sxy + a2 z^2) u: on the top interface sxy and
 * z are those of the unnormalised sum L + V (u = 1 / len2) and m = len folds 1 / len into
 * the interface's division; below it H is unit (u = m = 1, a constant in that call). */
static inline ABRDF__WW_INLINE int ww_interface(const abrdf__ww *w, int k, ww_state *st, double u,
                                                double m)
{
    const double ci = st->ci, co = st->co, cd = st->cd, a2 = w->a2[k];
    double nf, df, g;
    double g2 = ww_fresnel(w, k, cd, st->cd2, &nf, &df, &g);
    /* Smith visibility V1(c) = 1 / (c + sqrt(a2 + (1 - a2) c^2)) (Eq. 9), GGX D (Eq. 6)
     * a2 / (pi t^2): top = F D V1(ci) V1(co) */
    double vd = (ci + sqrt(a2 + (1.0 - a2) * ci * ci)) * (co + sqrt(a2 + (1.0 - a2) * co * co));
    double tn = st->sxy + a2 * st->z * st->z, tnm = tn * tn * m, pd = vd * tnm;
    double r = 1.0 / (df * pd); /* pd df m = 1 / r */
    double top = (nf * ((a2 * ABRDF__INV_PI) * (u * u) * m)) * r;
    for (int c = 0; c < 3; ++c) st->f[c] += st->wt[c] * top;
    if (w->kind[k] == ABRDF__WW_CONDUCTOR) return 0;    /* nothing below is seen */
    double fr = nf * pd, gr = 4.0 * ci * co * df * tnm; /* F / r, G / r */
    double F = fr * r, T = 1.0 - F, GF = (fr * gr) * (r * r);
    double im = (df * vd * tn * tn) * r, hz = st->z * im; /* 1 / m, N.H */
    if (!(T > 0.0 && g2 > 0.0)) return 0;                 /* total internal reflection */
    /* abrdf__lo_refract of L and V at H (L.H = V.H = cd) */
    double ie = w->inv_eta[k], ct = g * ie, kk = cd * ie - ct;
    double li = ci * ie - kk * hz, vi = co * ie - kk * hz;
    if (!(li > 0.0 && vi > 0.0)) return 0; /* refracted below the base's horizon */
    /* the next interface's half vector L' + V' has length 2 ct */
    if (k + 1 < w->count && !(4.0 * ct * ct > ABRDF__HALF_LEN2_MIN)) return 0;
    double tw = T * (1.0 - GF); /* T t, t = (1 - G) + T G = 1 - G F */
    if (!w->absorbs[k]) {
        for (int c = 0; c < 3; ++c) st->wt[c] *= tw; /* Eq. 15, a = 1 */
    } else {
        double path = (li + vi) / (li * vi); /* 1 / li + 1 / vi */
        double a = exp(-w->sd[k][0] * path); /* one exp when the channels absorb alike */
        for (int c = 0; c < 3; ++c) {
            double sd = w->sd[k][c];
            double ac = w->grey[k] ? a : sd > 0.0 ? exp(-sd * path) : 1.0;
            st->wt[c] *= tw * ac; /* Eq. 15 */
        }
    }
    st->ci = li, st->co = vi, st->cd = ct, st->cd2 = g2 * (ie * ie);
    st->sxy *= im * im, st->z = hz;
    return 1;
}

/* Eq. 15 from the top down: f = top_0 + W_1 (top_1 + W_2 (... + base)), each interface's
 * weight W = T a t taken into the product of those above it. Refraction at H keeps H the
 * half vector of every pair below (L' + V' = 2 cos_t H, cos_t the refracted cosine, which is
 * L'.H = V'.H), so H, D's arguments and the next incidence cosine need no renormalisation:
 * only the z components of L' and V' are followed. L.H = |L + V| / 2 for unit L and V. Per
 * interface: F (one root, which gives the refraction too), the two Smith terms (two roots)
 * and one division for F, D and V together (on the top interface for 1 / |L + V| as well);
 * the absorption's exp and division only below an absorbing layer. The products are grouped
 * so that little waits for the roots and the division: a renderer's call is one such chain. */
void abrdf__eval_weidlich_wilkie(const abrdf__ww *w, const double wi[3], const double wo[3],
                                 double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    double ci = wi[2], co = wo[2];
    if (!(ci > 0.0 && co > 0.0)) return;
    double sx = wi[0] + wo[0], sy = wi[1] + wo[1], sz = wi[2] + wo[2];
    double len2 = sx * sx + sy * sy + sz * sz;
    if (!(len2 > ABRDF__HALF_LEN2_MIN)) return;
    double len = sqrt(len2), cd = 0.5 * len, cd2 = 0.25 * len2;
    cd = cd < 1.0 ? cd : 1.0; /* > 0: ci, co > 0 */
    cd2 = cd2 < 1.0 ? cd2 : 1.0;
    ww_state st = {ci, co, cd, cd2, sx * sx + sy * sy, sz, {1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}};
    int k = 0, through = w->count > 0 ? ww_interface(w, 0, &st, len2, len) : 1;
    while (through && ++k < w->count) through = ww_interface(w, k, &st, 1.0, 1.0);
    for (int c = 0; c < 3; ++c) f[c] = st.f[c] + (through ? st.wt[c] * w->base[c] : 0.0);
}

/* THE BATCH PATH, vectorised over the pairs in blocks of WW_BLOCK: the layer loop outside,
 * one loop over the block's lanes per interface, so that the compiler vectorises each (in
 * double, as the double path computes) and the per-interface choices (kind, absorption) are
 * made once per block, not per pair. A lane that the double path stops (back-facing, total
 * internal reflection, refracted below the horizon) has its weight set to 0 and its state to
 * harmless values (cosines 1), so that the lanes need no branch and no NaN arises. The
 * absorption uses abrdf__expf (float, 2 ulp; its argument rounded to float: a relative error
 * below 6e-6 for arguments down to -88, where it is 0), inside the batch path's float
 * tolerance. Lanes whose float directions are far from unit length (|w|^2 outside
 * [0.25, 4], NaN) are evaluated again by the double path. */
#define WW_BLOCK 64

typedef struct ww_lanes {
    double ci[WW_BLOCK], co[WW_BLOCK], cd[WW_BLOCK]; /* N.L, N.V, L.H at the interface */
    double cd2[WW_BLOCK];                            /* (L.H)^2, as the double path has it */
    double hz[WW_BLOCK], sh2[WW_BLOCK];              /* N.H, |N x H|^2 */
    double wt[3][WW_BLOCK];                          /* the weight above, 0 once stopped */
    double f[3][WW_BLOCK];                           /* the sum so far */
} ww_lanes;

/* The squared length of a float direction if the vector path takes it, else 1 (the lane is
 * evaluated again by ww_batch_rest). A NaN fails both compares. */
static inline double ww_len2(double d)
{
    double x = d >= 0.25 ? d : 1.0;
    return x <= 4.0 ? x : 1.0;
}

/* The block's directions normalised in double (as abrdf__batch_special did), its half
 * vectors and the state above the top interface. */
static inline ABRDF__WW_INLINE void ww_start(int n, const float *restrict ix,
                                             const float *restrict iy, const float *restrict iz,
                                             const float *restrict ox, const float *restrict oy,
                                             const float *restrict oz, ww_lanes *restrict s)
{
    for (int j = 0; j < n; ++j) {
        double ax = ix[j], ay = iy[j], az = iz[j], bx = ox[j], by = oy[j], bz = oz[j];
        double ia = 1.0 / sqrt(ww_len2(ax * ax + ay * ay + az * az));
        double ib = 1.0 / sqrt(ww_len2(bx * bx + by * by + bz * bz));
        ax *= ia, ay *= ia, az *= ia, bx *= ib, by *= ib, bz *= ib;
        double hx = ax + bx, hy = ay + by, hz = az + bz, len2 = hx * hx + hy * hy + hz * hz;
        double live = az > 0.0 ? 1.0 : 0.0;
        live = bz > 0.0 ? live : 0.0;
        live = len2 > ABRDF__HALF_LEN2_MIN ? live : 0.0;
        len2 = live > 0.0 ? len2 : 1.0;
        double len = sqrt(len2), il = 1.0 / len, cd = 0.5 * len, cd2 = 0.25 * len2;
        hx *= il, hy *= il, hz *= il;
        cd = cd < 1.0 ? cd : 1.0;
        cd2 = cd2 < 1.0 ? cd2 : 1.0;
        s->ci[j] = live > 0.0 ? az : 1.0;
        s->co[j] = live > 0.0 ? bz : 1.0;
        s->cd[j] = live > 0.0 ? cd : 1.0;
        s->cd2[j] = live > 0.0 ? cd2 : 1.0;
        s->hz[j] = live > 0.0 ? hz : 1.0;
        s->sh2[j] = live > 0.0 ? hx * hx + hy * hy : 0.0;
        for (int c = 0; c < 3; ++c) s->wt[c][j] = live, s->f[c][j] = 0.0;
    }
}

/* Interface k of kind KIND (a constant in every call) over the block: its top term added,
 * then the weight through it, as abrdf__eval_weidlich_wilkie. LAST: no interface below. */
static inline ABRDF__WW_INLINE void ww_layer(const abrdf__ww *restrict w, int k, int kind,
                                             int absorbs, int last, int n, ww_lanes *restrict s)
{
    const double a2 = w->a2[k], eta2 = w->eta2[k], ie = w->inv_eta[k], a2pi = a2 * ABRDF__INV_PI;
    const double eta = w->eta[k], kappa = w->kappa[k];
    const double sd0 = w->sd[k][0], sd1 = w->sd[k][1], sd2 = w->sd[k][2];
    const double min4 = last ? -1.0 : ABRDF__HALF_LEN2_MIN; /* the next half vector's length */
    for (int j = 0; j < n; ++j) {
        double ci = s->ci[j], co = s->co[j], cd = s->cd[j], cd2 = s->cd2[j], hz = s->hz[j];
        double nf = 0.0, df = 1.0, g = cd, g2 = cd2, through = 1.0;
        if (kind == ABRDF__WW_DIELECTRIC) {
            g2 = ww_dielectric(cd, cd2, eta2, &nf, &df, &g);
            through = g2 > 0.0 ? 1.0 : 0.0;
        } else if (kind == ABRDF__WW_CONDUCTOR) {
            nf = abrdf__fresnel_exact(cd, eta, kappa);
        }
        double vd = (ci + sqrt(a2 + (1.0 - a2) * ci * ci)) * (co + sqrt(a2 + (1.0 - a2) * co * co));
        double t = s->sh2[j] + a2 * hz * hz, tt = t * t;
        double r = 1.0 / (df * vd * tt);
        double top = nf * a2pi * r;
        for (int c = 0; c < 3; ++c) s->f[c][j] += s->wt[c][j] * top;
        if (kind == ABRDF__WW_CONDUCTOR) continue; /* the caller adds no base */
        double F = nf * (vd * tt) * r, vv = df * tt * r, T = 1.0 - F;
        double ok = T > 0.0 ? through : 0.0;
        double ct = ok > 0.0 ? g * ie : 1.0, kk = cd * ie - ct;
        double li = ci * ie - kk * hz, vi = co * ie - kk * hz;
        ok = li > 0.0 ? ok : 0.0;
        ok = vi > 0.0 ? ok : 0.0;
        ok = 4.0 * ct * ct > min4 ? ok : 0.0;
        li = ok > 0.0 ? li : 1.0;
        vi = ok > 0.0 ? vi : 1.0;
        double G = 4.0 * ci * co * vv;
        double tw = ok > 0.0 ? T * (1.0 - G * F) : 0.0;
        double a0 = 1.0, a1 = 1.0, a2c = 1.0;
        if (absorbs) { /* exponents below -100 (-inf too) give 0 like -100: in float's range */
            double path = (li + vi) / (li * vi), y0 = -sd0 * path, y1 = -sd1 * path;
            double y2 = -sd2 * path;
            a0 = abrdf__expf((float)(y0 > -100.0 ? y0 : -100.0));
            a1 = abrdf__expf((float)(y1 > -100.0 ? y1 : -100.0));
            a2c = abrdf__expf((float)(y2 > -100.0 ? y2 : -100.0));
        }
        s->wt[0][j] *= tw * a0;
        s->wt[1][j] *= tw * a1;
        s->wt[2][j] *= tw * a2c;
        s->ci[j] = li;
        s->co[j] = vi;
        s->cd[j] = ok > 0.0 ? ct : 1.0;
        s->cd2[j] = ok > 0.0 ? g2 * (ie * ie) : 1.0;
    }
}

/* The base under the stack (none under a conductor), and the store: a finite value >= 0
 * within float's range, else 0 (abrdf__eval_float.c's rule). */
static inline ABRDF__WW_INLINE void ww_finish(const abrdf__ww *restrict w, int base, int n,
                                              const ww_lanes *restrict s, float *restrict fr,
                                              float *restrict fg, float *restrict fb)
{
    const double b0 = base ? w->base[0] : 0.0, b1 = base ? w->base[1] : 0.0;
    const double b2 = base ? w->base[2] : 0.0;
    for (int j = 0; j < n; ++j) {
        double v0 = s->f[0][j] + s->wt[0][j] * b0, v1 = s->f[1][j] + s->wt[1][j] * b1;
        double v2 = s->f[2][j] + s->wt[2][j] * b2;
        v0 = v0 >= 0.0 ? v0 : 0.0, v1 = v1 >= 0.0 ? v1 : 0.0, v2 = v2 >= 0.0 ? v2 : 0.0;
        fr[j] = (float)(v0 <= FLT_MAX ? v0 : 0.0);
        fg[j] = (float)(v1 <= FLT_MAX ? v1 : 0.0);
        fb[j] = (float)(v2 <= FLT_MAX ? v2 : 0.0);
    }
}

#define ABRDF__WW_BATCH_ARGS                                                                       \
    const abrdf__ww *restrict w, size_t n, const float *restrict ix, const float *restrict iy,     \
        const float *restrict iz, const float *restrict ox, const float *restrict oy,              \
        const float *restrict oz, float *restrict fr, float *restrict fg, float *restrict fb

/* ww_batch_<L>: the block loop at instruction-set level L (isa.h), each interface's loop
 * specialised for its kind and absorption. */
#define WW_BATCH(L)                                                                                \
    ABRDF__NOINLINE ABRDF__ISA_ATTR_##L static void ww_batch_##L(ABRDF__WW_BATCH_ARGS)             \
    {                                                                                              \
        ww_lanes s;                                                                                \
        for (size_t i = 0; i < n; i += WW_BLOCK) {                                                 \
            int m = n - i < WW_BLOCK ? (int)(n - i) : WW_BLOCK, base = 1;                          \
            ww_start(m, ix + i, iy + i, iz + i, ox + i, oy + i, oz + i, &s);                       \
            for (int k = 0; k < w->count; ++k) {                                                   \
                int last = k + 1 == w->count;                                                      \
                if (w->kind[k] == ABRDF__WW_CONDUCTOR) {                                           \
                    ww_layer(w, k, ABRDF__WW_CONDUCTOR, 0, 1, m, &s);                              \
                    base = 0;                                                                      \
                } else if (w->kind[k] == ABRDF__WW_MATCHED) {                                      \
                    if (w->absorbs[k])                                                             \
                        ww_layer(w, k, ABRDF__WW_MATCHED, 1, last, m, &s);                         \
                    else                                                                           \
                        ww_layer(w, k, ABRDF__WW_MATCHED, 0, last, m, &s);                         \
                } else if (w->absorbs[k]) {                                                        \
                    ww_layer(w, k, ABRDF__WW_DIELECTRIC, 1, last, m, &s);                          \
                } else {                                                                           \
                    ww_layer(w, k, ABRDF__WW_DIELECTRIC, 0, last, m, &s);                          \
                }                                                                                  \
            }                                                                                      \
            ww_finish(w, base, m, &s, fr + i, fg + i, fb + i);                                     \
        }                                                                                          \
    }
ABRDF__ISA_LEVELS(WW_BATCH)

typedef void (*ww_batch_fn)(ABRDF__WW_BATCH_ARGS);
#define WW_BATCH_ENTRY(L) ww_batch_##L,

/* The pairs the vector loop left to the double path: float directions far from unit length,
 * normalised as abrdf__batch_special does (vec.h), or degenerate (0). */
static void ww_batch_rest(const abrdf__ww *w, const abrdf_batch *b)
{
    for (size_t i = 0; i < b->count; ++i) {
        double wi[3] = {b->wi_x[i], b->wi_y[i], b->wi_z[i]};
        double wo[3] = {b->wo_x[i], b->wo_y[i], b->wo_z[i]};
        double di = abrdf__dot3(wi, wi), dn = abrdf__dot3(wo, wo);
        if (di >= 0.25 && di <= 4.0 && dn >= 0.25 && dn <= 4.0) continue;
        double ui[3], uo[3], f[3] = {0.0, 0.0, 0.0};
        if (abrdf__normalise3_unit(wi, ui) && abrdf__normalise3_unit(wo, uo))
            abrdf__eval_weidlich_wilkie(w, ui, uo, f);
        float *out[3] = {b->f_r, b->f_g, b->f_b};
        for (int c = 0; c < 3; ++c) out[c][i] = f[c] >= 0.0 && f[c] <= FLT_MAX ? (float)f[c] : 0.0f;
    }
}

void abrdf__ww_batch(const abrdf__ww *w, const abrdf_batch *b, int level)
{
    static const ww_batch_fn fns[] = {ABRDF__ISA_LEVELS(WW_BATCH_ENTRY)};
    const int nl = (int)(sizeof fns / sizeof fns[0]);
    fns[level < 0    ? 0
        : level < nl ? level
                     : nl - 1](w, b->count, b->wi_x, b->wi_y, b->wi_z, b->wo_x, b->wo_y, b->wo_z,
                               b->f_r, b->f_g, b->f_b);
    ww_batch_rest(w, b);
}
