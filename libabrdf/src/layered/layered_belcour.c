/* layered_belcour.c - Belcour's layered model (Eq. 16): the adding-doubling statistics of
 * a stack of rough interfaces and absorbing media, evaluated as a sum of GGX lobes.
 *
 * L. Belcour, "Efficient rendering of layered materials using an atomic decomposition with
 * statistical operators", ACM TOG 37(4) (SIGGRAPH 2018), Secs. 4-6 and its supplemental
 * reference code, as documented in MODELS.md B8.2:
 *   f(L, V) = sum_k e_k D_GGX(H; alpha_k) G(L, V; alpha_k) / (4 cos_i cos_o)     (Eq. 16)
 * e_k and alpha_k come from one pass top -> bottom over the stack at the cosine of the mean
 * direction, carrying energies (R0i, T0i, Ri0, Ti0, RGB), variances (s_*), Jacobians J.
 * Per interface k (relative index eta_k + i kappa_k, alpha_g = r_k^2):
 *   s(a) = a^1.1 / (1 - a^1.1),  a(s) = (s / (1 + s))^(1/1.1)       (variance <-> roughness)
 *   R12 = FGD(cos, a(s_T0i + s(alpha)), eta, kappa), T12 = 1 - R12 (0 for a conductor)
 *   s_T12 = s(alpha |eta - 1| / (2 eta)), s_T21 = s(alpha |1/eta - 1| eta / 2), with the
 *     reference code's cosine factors set to 1 (the paper has cos ratios; MODELS.md B8.2)
 *   j12 = eta cos_t / cos, j21 = 1 / j12, cos_t by Snell's law of the mean direction
 *   TIR at the interface above (decoupling approximation): tau = TIR(cos, a(.), 1/eta_{k-1}),
 *     Ri0 += (1 - tau) Ti0, Ti0 *= tau
 *   adding: D = 1 - Ri0 R12, e_k = T0i R12 Ti0 / D, R0i += e_k, T0i = T0i T12 / D,
 *     Ri0 = R21 + T21 Ri0 T12 / D, Ti0 = T21 Ti0 / D, and the variances as in the code
 *     (averaged energies), alpha_k = a(s_Ti0 + J0i (s_T0i + s_R12 + Rr (s_R12 + s_Ri0)))
 * Per medium (depth d > 0 below a dielectric interface): T = exp(-sigma_a d / cos), R = 0,
 *   no scattering (the ABI has no sigma_s), so the variances are unchanged.
 * Choices (documented in docs/MODELS.md, "Belcour 2018"):
 *   - cos = |H.L| as in the evaluation of the Photon-v2 port (sampling there uses N.V);
 *     because H.L = H.V the model is then reciprocal.
 *   - G is the separable Smith G of Eq. 9; the FGD table is computed with the same G, so a
 *     single interface gives exactly FGD(H.L) D G / (4 cos_i cos_o).
 *   - A conductor (kappa > 0) or a refraction that fails (TIR of the mean) ends the stack;
 *     a dielectric bottom lets the transmitted light leave (no base below it).
 *   - TIR uses the index ratio of the interface above even when a medium lies between (the
 *     Photon-v2 port skips it then, an artefact of storing media as layers).
 *   - eta and kappa are scalars in the ABI: Fresnel is grey; colour comes from sigma_a. */
#include <math.h>

#include "belcour_tables.h"
#include "layered.h"
#include "layered_optics.h"

static double var_of_alpha(double a)
{
    a = a < 0.0 ? 0.0 : (a > ABRDF__BELCOUR_ALPHA_MAX ? ABRDF__BELCOUR_ALPHA_MAX : a);
    double p = pow(a, 1.1);
    return p / (1.0 - p);
}

/* (s / (1 + s))^(1/1.1) as exp2(log2(q) / 1.1), q in (0, 1): log2's rounding is carried
 * into the result as ln 2 |log2(q)| / 1.1 ulp, 4e-16 relative measured on (0.05, 0.95) and
 * ~1.5e-15 where alpha is at its floor (1e-6); glibc's exp2 and log2 take 0.75x pow's time,
 * and this is the one transcendental of an evaluation through two interfaces. */
static double alpha_of_var(double s)
{
    return s > 0.0 ? exp2(log2(s / (1.0 + s)) * (1.0 / 1.1)) : 0.0;
}

/* Split a continuous index into a clamped cell and a weight. */
static void cell(double x, int n, int *i, double *t)
{
    if (!(x > 0.0)) x = 0.0;
    if (x > n - 1) x = n - 1;
    int k = (int)x;
    if (k > n - 2) k = n - 2;
    *i = k;
    *t = x - k;
}

static abrdf__belcour_cell cell_of(double x, int n)
{
    abrdf__belcour_cell c;
    cell(x, n, &c.i, &c.t);
    return c;
}

/* FGD's eta and kappa corners for one interface (weights of exactly 0 left out). */
static abrdf__belcour_mix fgd_mix(double eta, double kappa)
{
    abrdf__belcour_cell e = cell_of(abrdf__bt_x_fgd_eta(eta), ABRDF__FGD_NETA);
    abrdf__belcour_cell k = cell_of(abrdf__bt_x_fgd_kappa(kappa), ABRDF__FGD_NKAPPA);
    abrdf__belcour_mix m = {0, {0, 0, 0, 0}, {0.0, 0.0, 0.0, 0.0}};
    for (int hk = 0; hk < 2; ++hk)
        for (int he = 0; he < 2; ++he) {
            double w = (he ? e.t : 1.0 - e.t) * (hk ? k.t : 1.0 - k.t);
            if (w == 0.0) continue;
            m.off[m.n] = (e.i + he) * ABRDF__FGD_NKAPPA + k.i + hk;
            m.w[m.n++] = w;
        }
    return m;
}

/* TIR's eta corners for the index ratio eta < 1. */
static abrdf__belcour_mix tir_mix(double eta)
{
    abrdf__belcour_cell e = cell_of(abrdf__bt_x_tir_eta(eta), ABRDF__TIR_NETA);
    abrdf__belcour_mix m = {0, {0, 0, 0, 0}, {0.0, 0.0, 0.0, 0.0}};
    for (int he = 0; he < 2; ++he) {
        double w = he ? e.t : 1.0 - e.t;
        if (w == 0.0) continue;
        m.off[m.n] = e.i + he;
        m.w[m.n++] = w;
    }
    return m;
}

static double clamp01(double v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

/* A table laid out [cos][alpha][trailing axes] at cos node ic, interpolated in the cell a
 * (alpha) and the premixed trailing corners m; s0 and s1 are the strides of cos and alpha. */
static double mix_node(const float *table, int s0, int s1, int ic, abrdf__belcour_cell a,
                       const abrdf__belcour_mix *m)
{
    double v = 0.0;
    for (int ha = 0; ha < 2; ++ha) {
        double w = ha ? a.t : 1.0 - a.t;
        if (w == 0.0) continue;
        const float *row = table + ic * s0 + (a.i + ha) * s1;
        double r = 0.0;
        for (int k = 0; k < m->n; ++k) r += m->w[k] * row[m->off[k]];
        v += w * r;
    }
    return v;
}

/* The value at cos between the two nodes of cell c whose values are v0 and v1. */
static double cos_lerp(abrdf__belcour_cell c, double v0, double v1)
{
    return clamp01((1.0 - c.t) * v0 + c.t * v1);
}

/* Multilinear interpolation of such a table: in alpha and the trailing axes at the two cos
 * nodes of the cell c, then in cos. */
static double mix_interp(const float *table, int s0, int s1, abrdf__belcour_cell c,
                         abrdf__belcour_cell a, const abrdf__belcour_mix *m)
{
    return cos_lerp(c, mix_node(table, s0, s1, c.i, a, m), mix_node(table, s0, s1, c.i + 1, a, m));
}

/* The same from a table's values at every cos node (n of them, from mix_node): the same
 * arithmetic, so the same bits. */
static double node_interp(const double *v, int n, double c)
{
    abrdf__belcour_cell cc = cell_of(abrdf__bt_x_cos(c, n), n);
    return cos_lerp(cc, v[cc.i], v[cc.i + 1]);
}

enum {
    FGD_S0 = ABRDF__FGD_NALPHA * ABRDF__FGD_NETA * ABRDF__FGD_NKAPPA,
    FGD_S1 = ABRDF__FGD_NETA * ABRDF__FGD_NKAPPA,
    TIR_S0 = ABRDF__TIR_NALPHA * ABRDF__TIR_NETA,
    TIR_S1 = ABRDF__TIR_NETA
};

static double fgd_at(double c, abrdf__belcour_cell a, const abrdf__belcour_mix *m)
{
    abrdf__belcour_cell cc = cell_of(abrdf__bt_x_cos(c, ABRDF__FGD_NCOS), ABRDF__FGD_NCOS);
    return mix_interp(abrdf__fgd_table, FGD_S0, FGD_S1, cc, a, m);
}

static abrdf__belcour_cell fgd_alpha_cell(double a)
{
    return cell_of(abrdf__bt_x_alpha(a, ABRDF__FGD_NALPHA), ABRDF__FGD_NALPHA);
}

static abrdf__belcour_cell tir_alpha_cell(double a)
{
    return cell_of(abrdf__bt_x_alpha(a, ABRDF__TIR_NALPHA), ABRDF__TIR_NALPHA);
}

static double tir_at(double c, abrdf__belcour_cell ca, const abrdf__belcour_mix *m)
{
    abrdf__belcour_cell cc = cell_of(abrdf__bt_x_cos(c, ABRDF__TIR_NCOS), ABRDF__TIR_NCOS);
    return mix_interp(abrdf__tir_table, TIR_S0, TIR_S1, cc, ca, m);
}

double abrdf__belcour_fgd(double c, double a, double eta, double kappa)
{
    abrdf__belcour_mix m = fgd_mix(eta, kappa);
    return fgd_at(c, fgd_alpha_cell(a), &m);
}

double abrdf__belcour_tir(double c, double a, double eta)
{
    if (eta >= 1.0) return 1.0; /* from the less dense side nothing is totally reflected */
    abrdf__belcour_mix m = tir_mix(eta);
    return tir_at(c, tir_alpha_cell(a), &m);
}

/* The mean of the nc (1 or 3) channels carried. */
static double avg(const double v[3], int nc) { return nc == 1 ? v[0] : (v[0] + v[1] + v[2]) / 3.0; }

/* The statistics carried from the top of the stack down to the current medium. */
typedef struct stack_stats {
    double R0i[3], T0i[3], Ri0[3], Ti0[3];
    double sR0i, sT0i, sRi0, sTi0;
    double J0i, Ji0;
    double cos; /* cosine of the mean direction in the current medium */
} stack_stats;

/* abrdf__belcour_setup without the tables along cos (tops = 0). */
static void setup_stack(const abrdf_params *p, abrdf__belcour *b)
{
    int n = p->layer_count < ABRDF_MAX_LAYERS ? p->layer_count : ABRDF_MAX_LAYERS;
    b->channels = 1;
    for (int k = 0; k < ABRDF_MAX_LAYERS; ++k) {
        const abrdf_layer *ly = &p->layers[k];
        if (k < n && ly->depth > 0.0 &&
            !(ly->sigma_a[0] == ly->sigma_a[1] && ly->sigma_a[0] == ly->sigma_a[2]))
            b->channels = 3;
        double eta = ly->eta, alpha = ly->r * ly->r;
        int used = k < n, transmits = used && !(ly->kappa > 0.0); /* what add_interface reads */
        b->s_r12[k] = used ? var_of_alpha(alpha) : 0.0;
        b->inv_eta2[k] = 1.0 / (eta * eta);
        b->s_t12[k] = transmits ? var_of_alpha(alpha * 0.5 * fabs(eta - 1.0) / eta) : 0.0;
        b->s_t21[k] = transmits ? var_of_alpha(alpha * 0.5 * fabs(1.0 / eta - 1.0) * eta) : 0.0;
        b->fgd[k] = fgd_mix(eta, ly->kappa);
        double eta_up = k > 0 ? 1.0 / p->layers[k - 1].eta : 1.0; /* abrdf__belcour_tir's */
        b->tir_dense[k] = k > 0 && !(eta_up >= 1.0);
        b->tir[k] = tir_mix(b->tir_dense[k] ? eta_up : 1.0);
    }
    /* add_interface's a_top = a(s_T0i + s_R12) at k = 0 and 1, s_T0i being 0 and s_T12 */
    b->alpha_top0 = alpha_of_var(0.0 + b->s_r12[0]);
    b->tops = 0;
}

void abrdf__belcour_setup(const abrdf_params *p, abrdf__belcour *b, int tables)
{
    setup_stack(p, b);
    if (!tables) return;
    double alpha_top1 = alpha_of_var(b->s_t12[0] + b->s_r12[1]);
    abrdf__belcour_cell f0 = fgd_alpha_cell(b->alpha_top0), f1 = fgd_alpha_cell(alpha_top1);
    abrdf__belcour_cell t1 = tir_alpha_cell(alpha_top1);
    for (int i = 0; i < ABRDF__FGD_NCOS; ++i) {
        b->fgd_top[0][i] = mix_node(abrdf__fgd_table, FGD_S0, FGD_S1, i, f0, &b->fgd[0]);
        b->fgd_top[1][i] = mix_node(abrdf__fgd_table, FGD_S0, FGD_S1, i, f1, &b->fgd[1]);
    }
    for (int i = 0; i < ABRDF__TIR_NCOS; ++i)
        b->tir_top1[i] = mix_node(abrdf__tir_table, TIR_S0, TIR_S1, i, t1, &b->tir[1]);
    b->tops = 1;
}

/* D_GGX(H) G(L, V) / (4 cos_i cos_o) with the separable Smith G (Eq. 9), that is
 * abrdf__lo_d_ggx(ch, sh2, ag) abrdf__lo_v1(ci, ag) abrdf__lo_v1(co, ag) with one division
 * and H unnormalised: h = wi + wo, hxy2 = h_x^2 + h_y^2, hz2 = h_z^2, hl2 = |h|^2, so that
 * sin^2 + a2 cos^2 of theta_h is (hxy2 + a2 hz2) / hl2 (as k_disney_specular_lobe). */
static double ggx_lobe(double hxy2, double hz2, double hl2, double ci, double co, double ag)
{
    double a2 = ag * ag, t = hxy2 + a2 * hz2;
    if (!(t > 0.0)) return 0.0;
    double vi = ci + sqrt(a2 + (1.0 - a2) * ci * ci), vo = co + sqrt(a2 + (1.0 - a2) * co * co);
    return a2 * hl2 * hl2 / (ABRDF__LO_PI * t * t * (vi * vo));
}

/* Adds interface k to the stack; writes its lobe (energy e, roughness alpha). Returns 1 if
 * light continues below it. */
static int add_interface(stack_stats *st, const abrdf__belcour *bp, const abrdf_params *p, int k,
                         double e[3], double *alpha_k)
{
    const abrdf_layer *ly = &p->layers[k];
    double eta = ly->eta;
    int conductor = ly->kappa > 0.0;
    double c = st->cos;
    double sin_t2 = (1.0 - c * c) * bp->inv_eta2[k];
    int has_t = !conductor && sin_t2 < 1.0;
    double cos_t = has_t ? sqrt(1.0 - sin_t2) : 0.0;
    if (cos_t < ABRDF__BELCOUR_COS_MIN) has_t = 0;
    double sR12 = bp->s_r12[k], sT12 = 0.0, sT21 = 0.0, j12 = 1.0, j21 = 1.0;
    if (has_t) {
        sT12 = bp->s_t12[k];
        sT21 = bp->s_t21[k];
        j12 = eta * cos_t / c;
        j21 = c / (eta * cos_t); /* 1 / j12, not waiting for it */
    }
    /* roughness seen through the stack above (k < 2: fixed, the setup's tables along cos) */
    int top = k < 2 && bp->tops;
    double a_top = top ? 0.0 : alpha_of_var(st->sT0i + sR12);
    /* abrdf__belcour_fgd(c, a_top, eta, kappa) */
    double R12 = top ? node_interp(bp->fgd_top[k], ABRDF__FGD_NCOS, c)
                     : fgd_at(c, fgd_alpha_cell(a_top), &bp->fgd[k]);
    double T12 = has_t ? 1.0 - R12 : 0.0, R21 = has_t ? R12 : 0.0, T21 = T12;
    int nc = bp->channels;
    if (k == 0) {
        /* Under the empty stack (R = 0, T = 1, no variance, J = 1) the adding step below
         * reduces to the interface itself: e = R12, alpha = a_top, and the normalised
         * variances s R / R are s_R12. */
        for (int ch = 0; ch < 3; ++ch) e[ch] = R12 > 0.0 ? R12 : 0.0;
        *alpha_k = R12 > 0.0 ? bp->alpha_top0 : 0.0;
        for (int ch = 0; ch < nc; ++ch) {
            st->R0i[ch] = R12;
            st->T0i[ch] = T12;
            st->Ri0[ch] = R21;
            st->Ti0[ch] = T21;
        }
        st->sR0i = R12 > 0.0 ? sR12 : 0.0;
        st->sT0i = sT12;
        st->sRi0 = R21 > 0.0 ? sR12 : 0.0;
        st->sTi0 = sT21;
        st->J0i = j12;
        st->Ji0 = j21;
        st->cos = cos_t;
        return has_t;
    }
    if (bp->tir_dense[k]) { /* TIR at the interface above, seen from this medium */
        /* abrdf__belcour_tir(c, a_top, 1 / eta_{k-1}) */
        double tau = top ? node_interp(bp->tir_top1, ABRDF__TIR_NCOS, c)
                         : tir_at(c, tir_alpha_cell(a_top), &bp->tir[k]);
        for (int ch = 0; ch < nc; ++ch) {
            double ri = st->Ri0[ch] + (1.0 - tau) * st->Ti0[ch];
            st->Ri0[ch] = ri < 1.0 ? ri : 1.0; /* fmin(1, ri), inline */
            st->Ti0[ch] *= tau;
        }
    }
    double r0i_prev = avg(st->R0i, nc), eterm[3], riterm[3], rr[3];
    for (int ch = 0; ch < nc; ++ch) { /* the adding step, in place */
        double ri = st->Ri0[ch], ti = st->Ti0[ch], t0 = st->T0i[ch];
        double den = 1.0 - ri * R12;
        double inv = den > 0.0 ? 1.0 / den : 0.0; /* 0: the terms below are 0 */
        eterm[ch] = t0 * R12 * ti * inv;
        riterm[ch] = T21 * ri * T12 * inv;
        rr[ch] = ri * R12 * inv;
        st->R0i[ch] += eterm[ch];
        st->T0i[ch] = t0 * T12 * inv;
        st->Ri0[ch] = R21 + riterm[ch];
        st->Ti0[ch] = T21 * ti * inv;
    }
    double e_avg = avg(eterm, nc), ri_avg = avg(riterm, nc), rr_avg = avg(rr, nc);
    double sR0i = r0i_prev * st->sR0i +
                  e_avg * (st->sTi0 + st->J0i * (st->sT0i + sR12 + rr_avg * (sR12 + st->sRi0)));
    double sT0i = j12 * st->sT0i + sT12 + j12 * (sR12 + st->sRi0) * rr_avg;
    double sRi0 =
        R21 * sR12 + ri_avg * (sT12 + j12 * (sT21 + st->sRi0 + rr_avg * (sR12 + st->sRi0)));
    double sTi0 = st->Ji0 * sT21 + st->sTi0 + st->Ji0 * (sR12 + st->sRi0) * rr_avg;
    double r0i_avg = avg(st->R0i, nc), ri0_avg = avg(st->Ri0, nc);
    *alpha_k =
        e_avg > 0.0
            ? alpha_of_var(st->sTi0 + st->J0i * (st->sT0i + sR12 + rr_avg * (sR12 + st->sRi0)))
            : 0.0;
    for (int ch = 0; ch < 3; ++ch) e[ch] = e_avg > 0.0 ? eterm[nc == 1 ? 0 : ch] : 0.0;
    st->sR0i = r0i_avg > 0.0 ? sR0i / r0i_avg : 0.0;
    st->sT0i = sT0i;
    st->sRi0 = ri0_avg > 0.0 ? sRi0 / ri0_avg : 0.0;
    st->sTi0 = sTi0;
    st->J0i *= j12;
    st->Ji0 *= j21;
    st->cos = cos_t;
    return has_t;
}

/* The absorbing medium below interface k: transmittance exp(-sigma_a d / cos) each way. */
static void add_medium(stack_stats *st, const abrdf_layer *ly, int nc)
{
    for (int ch = 0; ch < nc; ++ch) {
        double sd = ly->sigma_a[ch] * ly->depth;
        double T = sd > 0.0 ? exp(-sd / st->cos) : 1.0;
        st->T0i[ch] *= T;
        st->Ti0[ch] *= T;
        st->Ri0[ch] *= T * T;
    }
}

void abrdf__eval_belcour(const abrdf__belcour *bp, const abrdf_params *p, const double wi[3],
                         const double wo[3], double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    double ci = wi[2], co = wo[2];
    if (!(ci > 0.0 && co > 0.0)) return;
    double h[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double hxy2 = h[0] * h[0] + h[1] * h[1], hz2 = h[2] * h[2], len2 = hxy2 + hz2;
    if (!(len2 > ABRDF__HALF_LEN2_MIN)) return;
    double cd = 0.5 * sqrt(len2); /* wi.H = |wi + wo| / 2 for unit directions */
    if (!(cd > ABRDF__BELCOUR_COS_MIN)) return;
    stack_stats st = {{0, 0, 0}, {1, 1, 1}, {0, 0, 0}, {1, 1, 1},          0, 0, 0,
                      0,         1,         1,         cd < 1.0 ? cd : 1.0};
    int n = p->layer_count < ABRDF_MAX_LAYERS ? p->layer_count : ABRDF_MAX_LAYERS;
    for (int k = 0; k < n; ++k) {
        double e[3], ak;
        int below = add_interface(&st, bp, p, k, e, &ak);
        double ag = ak > ABRDF__ALPHA_G_MIN ? ak : ABRDF__ALPHA_G_MIN; /* fmax, inline */
        double lobe = ggx_lobe(hxy2, hz2, len2, ci, co, ag);
        for (int c = 0; c < 3; ++c) f[c] += e[c] * lobe; /* Eq. 16 */
        if (!below) break;
        if (p->layers[k].depth > 0.0) add_medium(&st, &p->layers[k], bp->channels);
    }
}

int abrdf__belcour_lobes(const abrdf_params *p, double cos_theta, double e[][3], double alpha[])
{
    stack_stats st = {{0, 0, 0},
                      {1, 1, 1},
                      {0, 0, 0},
                      {1, 1, 1},
                      0,
                      0,
                      0,
                      0,
                      1,
                      1,
                      fmin(fmax(cos_theta, ABRDF__BELCOUR_COS_MIN), 1.0)};
    abrdf__belcour bp;
    setup_stack(p, &bp);
    int n = p->layer_count < ABRDF_MAX_LAYERS ? p->layer_count : ABRDF_MAX_LAYERS, count = 0;
    for (int k = 0; k < n; ++k) {
        double ak;
        int below = add_interface(&st, &bp, p, k, e[count], &ak);
        alpha[count++] = fmax(ak, ABRDF__ALPHA_G_MIN);
        if (!below) break;
        if (p->layers[k].depth > 0.0) add_medium(&st, &p->layers[k], bp.channels);
    }
    return count;
}
