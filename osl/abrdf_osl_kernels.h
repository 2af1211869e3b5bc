// abrdf_osl_kernels.h - the closed-form and layered models of the OSL port, 1:1 with the C
// kernels (libabrdf/src/kernels/k_*.h, libabrdf/src/layered/layered_*.c): the local-frame
// geometry, frames, the split terms and one function abrdf_<model>(wi, wo, ...) per model. Included by abrdf_osl.h.
#ifndef ABRDF_OSL_KERNELS_H
#define ABRDF_OSL_KERNELS_H

#include "abrdf_osl_guards.h"
#include "abrdf_meta.h"
#include "abrdf_fkub.h"
#include "abrdf_belcour_tables.h"

// ---- local-frame geometry (kernel.h geo_make) --------------------------------------------
struct abrdf_geo {
    vector i;   // wi
    vector o;   // wo
    float ci;   // N.wi clamped to [-1, 1]
    float co;   // N.wo clamped to [-1, 1]
    vector h;   // H; +z when wi ~ -wo
    float ch;   // N.H
    float sh2;  // |N x H|^2 = sin^2(theta_h)
    float cd;   // wi.H = |wi + wo| / 2 in [0, 1]
    float rv;   // R.wo, R the mirror of wi
};

abrdf_geo abrdf_geo_make(vector wi, vector wo)
{
    abrdf_geo g;
    g.i = wi;
    g.o = wo;
    g.ci = abrdf_clampr(wi[2], -1.0, 1.0);
    g.co = abrdf_clampr(wo[2], -1.0, 1.0);
    vector h = wi + wo;
    float len2 = dot(h, h);
    int ok = len2 > ABRDF_HALF_LEN2_MIN;
    float len = sqrt(ok ? len2 : 1.0);
    g.h = ok ? h / len : vector(0, 0, 1);
    g.ch = abrdf_clampr(g.h[2], -1.0, 1.0);
    g.sh2 = abrdf_clampr(g.h[0] * g.h[0] + g.h[1] * g.h[1], 0.0, 1.0);
    // |wi + wo| / 2: symmetric in wi, wo and free of cancellation when wi ~ -wo.
    g.cd = ok ? abrdf_clampr(0.5 * len, 0.0, 1.0) : 0.0;
    g.rv = abrdf_clampr(-wi[0] * wo[0] - wi[1] * wo[1] + wi[2] * wo[2], -1.0, 1.0);
    return g;
}

// Both directions strictly above the surface: the only pairs with a non-zero BRDF.
int abrdf_geo_front(abrdf_geo g) { return g.ci > 0.0 && g.co > 0.0; }

// Schlick's Fresnel, Eq. 8, cos_d clamped to [0, 1].
float abrdf_f_schlick(float f0, float cos_d)
{
    float m = 1.0 - abrdf_clampr(cos_d, 0.0, 1.0);
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m); // Eq. 8
}
color abrdf_f_schlick(color f0, float cos_d)
{
    return color(abrdf_f_schlick(f0[0], cos_d), abrdf_f_schlick(f0[1], cos_d),
                 abrdf_f_schlick(f0[2], cos_d));
}

// ---- frames -------------------------------------------------------------------------------
vector abrdf_to_local(vector v, vector T, vector B, vector N)
{
    return vector(dot(v, T), dot(v, B), dot(v, N));
}

// Below this |T_perp| (T and N unit) the tangent is taken as parallel to N. The C library
// uses 1e-6 in double; in float, T and N computed through transforms carry errors of
// ~1e-7 each, so a T that is exactly parallel to N (the radial rule on a cylinder's side)
// leaves |T_perp| ~ 1e-6 of noise, and normalising that noise would give a random frame.
// 1e-4 keeps such T on the deterministic fallback, as the double-precision C code does.
#define ABRDF_FRAME_T_PERP_MIN 1e-4

// libabrdf's abrdf_frame_make: T by Gram-Schmidt against N; if T is (nearly) parallel to N,
// the world axis least aligned with N. A second Gram-Schmidt pass keeps T orthogonal to N
// to float precision.
void abrdf_frame_make(vector N, vector T, output vector T_out, output vector B_out)
{
    vector n = normalize(N);
    vector tt = vector(0);
    int have_t = 0;
    float tl = length(T);
    if (tl > 0.0) {
        vector tn = T / tl;
        tt = tn - dot(tn, n) * n;
        have_t = length(tt) > ABRDF_FRAME_T_PERP_MIN;
    }
    if (!have_t) {
        vector ax = vector(0);
        float a0 = fabs(n[0]), a1 = fabs(n[1]), a2 = fabs(n[2]);
        int k = a0 <= a1 ? (a0 <= a2 ? 0 : 2) : (a1 <= a2 ? 1 : 2);
        ax[k] = 1.0;
        tt = ax - dot(ax, n) * n;
    }
    tt = normalize(tt);
    T_out = normalize(tt - dot(tt, n) * n);
    B_out = cross(n, T_out);
}

// The scene format's tangent field rules (docs/RENDERER.md, "Tangent field") in the host's
// object space: "u" around the object's y axis, "v" along it, "radial" away from it, "axis"
// the fixed object-space direction `axis`; any other rule returns `fallback` (e.g. dPdu).
vector abrdf_tangent_field(string rule, vector axis, point Pw, vector fallback)
{
    point p = transform("common", "object", Pw);
    vector t = vector(0);
    if (rule == "u") t = vector(-p[2], 0, p[0]);
    else if (rule == "v") t = vector(0, 1, 0);
    else if (rule == "radial") t = vector(p[0], 0, p[2]);
    else if (rule == "axis") t = axis;
    else return fallback;
    return transform("object", "common", t);
}

// ---- diffuse (k_diffuse.h) ----------------------------------------------------------------
// Lambert, Eq. 1 (Lambert 1760).
color abrdf_lambert(vector wi, vector wo, color kd)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return kd * ABRDF_INV_PI; // Eq. 1
}

// Lambert * (1 - F(H.L)), Eq. 2.
color abrdf_lambert_fresnel(vector wi, vector wo, color kd, color f0)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return kd * ABRDF_INV_PI * (color(1) - abrdf_f_schlick(f0, g.cd)); // Eq. 2
}

// Disney diffuse, Eq. 3 (Burley 2012): F_D90 = 0.5 + 2 r (H.L)^2.
color abrdf_disney_diffuse(vector wi, vector wo, color kd, float r)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float fd90 = 0.5 + 2.0 * r * g.cd * g.cd;
    float mi = 1.0 - g.ci, mo = 1.0 - g.co;
    float mi5 = mi * mi * mi * mi * mi, mo5 = mo * mo * mo * mo * mo;
    float s = (1.0 + (fd90 - 1.0) * mi5) * (1.0 + (fd90 - 1.0) * mo5); // Eq. 3
    return kd * ABRDF_INV_PI * abrdf_pos(s);
}

// Oren-Nayar 1994, qualitative model, without trigonometry:
// max(0, cos phi) sin(alpha) tan(beta) = max(0, L.V - (N.L)(N.V)) / max(cos_i, cos_o).
color abrdf_oren_nayar(vector wi, vector wo, color kd, float sigma)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float s2 = sigma * sigma;
    float a = 1.0 - 0.5 * s2 / (s2 + 0.33);
    float b = 0.45 * s2 / (s2 + 0.09);
    float s = dot(g.i, g.o) - g.ci * g.co;
    float t = g.ci > g.co ? g.ci : g.co;
    return kd * ABRDF_INV_PI * (a + b * abrdf_safe_div(abrdf_pos(s), t));
}

// ---- empirical lobes (k_empirical.h): ks * lobe ------------------------------------------
// ((n/m)(c - 1) + 1)^m with m = 2^k, Table 1.
float abrdf_lobe_fm(float n, float c, int k)
{
    float m = float(1 << k);
    return abrdf_pow2k((n / m) * (c - 1.0) + 1.0, k);
}

// Phong 1975: cos(gamma)^n, gamma = angle(R, V).
color abrdf_phong(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return ks * abrdf_pow_pos(g.rv, n);
}

// Blinn-Phong, Eq. 4 (Blinn 1977): cos(theta_h)^n.
color abrdf_blinn_phong(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return ks * abrdf_pow_pos(g.ch, n); // Eq. 4
}

// Table 1: ((n/m)(c - 1) + 1)^m, m = 2, 4, 8, 16 (power form after Lyon 1993).
color abrdf_f2(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return ks * abrdf_lobe_fm(n, g.ch, 1);
}
color abrdf_f4(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return ks * abrdf_lobe_fm(n, g.ch, 2);
}
color abrdf_f8(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return ks * abrdf_lobe_fm(n, g.ch, 3);
}
color abrdf_f16(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return ks * abrdf_lobe_fm(n, g.ch, 4);
}

// Table 1, Schlick 1994: c / (n - n c + c).
color abrdf_fs(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float c = abrdf_pos(g.ch);
    return ks * abrdf_safe_div(c, n - n * c + c);
}

// Table 1: 0.786 n c^2 + (1 - 0.786 n) c, clamped at 0.
color abrdf_fkv(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float c = abrdf_pos(g.ch);
    float a = 0.786 * n;
    return ks * abrdf_pos(a * c * c + (1.0 - a) * c);
}

// Table 1 (Romanyuk et al. 2023), the fitted cubic about c = 1, zero below x0, in [0, 1].
color abrdf_fkub(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float a, b, d, x0;
    abrdf_fkub_coeffs(n, a, b, d, x0);
    float c = abrdf_pos(g.ch);
    float t = 1.0 - c;
    float v = 1.0 + t * (a + t * (b + t * d));
    v = c >= x0 ? abrdf_clampr(v, 0.0, 1.0) : 0.0;
    return ks * v;
}

// ---- energy-conserving lobes (k_energy.h), Table 5 ----------------------------------------
float abrdf_norm_phe(float n) { return (n + 2.0) / (2.0 * ABRDF_PI); }
float abrdf_norm_be(float n)
{
    return (n + 2.0) * (n + 4.0) / (8.0 * ABRDF_PI * (pow(2.0, -n / 2.0) + n));
}
float abrdf_norm_2e(float n) { return 0.111 / n + 0.238 * (0.481 + n); }
float abrdf_norm_16e(float n) { return (1.063 * n + 1.0) / (2.0 * ABRDF_PI); }
float abrdf_norm_ge(float n) { return (n + 2.0) / (4.0 * ABRDF_PI * (2.0 - pow(2.0, -n / 2.0))); }

// Lafortune-Willems 1994: (n + 2)/(2 pi) cos^n(gamma).
color abrdf_f_phe(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return ks * (abrdf_norm_phe(n) * abrdf_pow_pos(g.rv, n));
}

// Giesen 2009: normalised Blinn-Phong on N.H.
color abrdf_f_be(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return ks * (abrdf_norm_be(n) * abrdf_pow_pos(g.ch, n));
}

// The paper's fitted f_2E on cos(gamma) (MODELS.md B4).
color abrdf_f_2e(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return ks * (abrdf_norm_2e(n) * abrdf_lobe_fm(n, g.rv, 1));
}

// The paper's fitted f_16E on cos(gamma) (MODELS.md B4).
color abrdf_f_16e(vector wi, vector wo, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return ks * (abrdf_norm_16e(n) * abrdf_lobe_fm(n, g.rv, 4));
}

// Gotanda 2012: F cos^n(theta_h) (n + 2) / (4 pi (2 - 2^(-n/2)) max(cos_i, cos_o)).
color abrdf_f_ge(vector wi, vector wo, color ks, float n, color f0)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float lobe = abrdf_norm_ge(n) * abrdf_pow_pos(g.ch, n) / (g.ci > g.co ? g.ci : g.co);
    return ks * abrdf_f_schlick(f0, g.cd) * lobe;
}

// D F / (4 cos_i cos_o) with G = 1 and clamped cosines (Eq. 5 with G = 1).
color abrdf_ct_no_g(abrdf_geo g, color ks, color f0, float d)
{
    float ci = g.ci > ABRDF_COS_MIN_NO_G ? g.ci : ABRDF_COS_MIN_NO_G;
    float co = g.co > ABRDF_COS_MIN_NO_G ? g.co : ABRDF_COS_MIN_NO_G;
    float v = d / (4.0 * ci * co); // Eq. 5 with G = 1
    return ks * abrdf_f_schlick(f0, g.cd) * v;
}

// Cook-Torrance 1982 with D = the normalised lobes of Table 5 on N.H, G = 1.
color abrdf_f_ctphe(vector wi, vector wo, color ks, float n, color f0)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return abrdf_ct_no_g(g, ks, f0, abrdf_norm_phe(n) * abrdf_pow_pos(g.ch, n));
}
color abrdf_f_ct2e(vector wi, vector wo, color ks, float n, color f0)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return abrdf_ct_no_g(g, ks, f0, abrdf_norm_2e(n) * abrdf_lobe_fm(n, g.ch, 1));
}
color abrdf_f_ct16e(vector wi, vector wo, color ks, float n, color f0)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    return abrdf_ct_no_g(g, ks, f0, abrdf_norm_16e(n) * abrdf_lobe_fm(n, g.ch, 4));
}

// ---- microfacet split terms and models (k_microfacet.h), Walter et al. 2007 form ---------
// GGX D, Eq. 6, with sin^2 from |N x H|^2.
float abrdf_d_ggx(float ch, float sh2, float ag)
{
    float a2 = ag * ag;
    float t = sh2 + a2 * ch * ch;
    return abrdf_safe_div(a2, ABRDF_PI * t * t); // Eq. 6
}

// Anisotropic GGX D, Eq. 7; H in the local frame.
float abrdf_d_ggx_aniso(vector h, float ax, float ay)
{
    float u = h[0] / ax, v = h[1] / ay;
    float t = u * u + v * v + h[2] * h[2];
    return abrdf_safe_div(1.0, ABRDF_PI * ax * ay * t * t); // Eq. 7
}

// Normalised Beckmann D.
float abrdf_d_beckmann(float ch, float sh2, float ag)
{
    if (!(ch > 0.0)) return 0.0;
    float c2 = ch * ch;
    return abrdf_safe_div(exp(-sh2 / (c2 * ag * ag)), ABRDF_PI * ag * ag * c2 * c2);
}

// Disney clearcoat GTR1 (Burley 2012, App. B); alpha not squared.
float abrdf_d_gtr1(float ch, float sh2, float alpha)
{
    float a2 = alpha * alpha;
    if (1.0 - a2 < ABRDF_GTR1_ALPHA_ONE) return ABRDF_INV_PI;
    return (a2 - 1.0) / (ABRDF_PI * log(a2) * (sh2 + a2 * ch * ch));
}

// G1(u) / (2 cos_u) = 1 / (cos_u + sqrt(alpha^2 + (1 - alpha^2) cos_u^2)), Eq. 9.
float abrdf_v1_smith_ggx(float cu, float ag)
{
    float a2 = ag * ag;
    return 1.0 / (cu + sqrt(a2 + (1.0 - a2) * cu * cu));
}
float abrdf_g1_smith_ggx(float cu, float ag)
{
    return 2.0 * abrdf_pos(cu) * abrdf_v1_smith_ggx(abrdf_pos(cu), ag); // Eq. 9
}
float abrdf_v1_smith_ggx_aniso(vector u, float ax, float ay)
{
    float a = u[0] * ax, b = u[1] * ay;
    return 1.0 / (u[2] + sqrt(a * a + b * b + u[2] * u[2]));
}

// Cook-Torrance V-cavity G.
float abrdf_g_cook_torrance(abrdf_geo g)
{
    float k = abrdf_safe_div(2.0 * g.ch, g.cd);
    float gi = k * g.ci, go = k * g.co;
    float m = gi < go ? gi : go;
    return m < 1.0 ? abrdf_pos(m) : 1.0;
}

// alpha_g = max(r^2, ABRDF_ALPHA_G_MIN).
float abrdf_alpha_g(float r) { return max(r * r, ABRDF_ALPHA_G_MIN); }

// Cook-Torrance 1982 (Eq. 5) with the normalised Beckmann D and the V-cavity G.
color abrdf_cook_torrance(vector wi, vector wo, color ks, float r, color f0)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float dg = abrdf_d_beckmann(g.ch, g.sh2, abrdf_alpha_g(r)) * abrdf_g_cook_torrance(g);
    float v = abrdf_safe_div(dg, 4.0 * g.ci * g.co); // Eq. 5
    return ks * abrdf_f_schlick(f0, g.cd) * v;
}

// Disney specular (Eqs. 5, 6, 8, 9): GGX D, separable Smith G, Schlick F.
color abrdf_disney_specular(vector wi, vector wo, color ks, float r, color f0)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float ag = abrdf_alpha_g(r);
    float dv = abrdf_d_ggx(g.ch, g.sh2, ag) * abrdf_v1_smith_ggx(g.ci, ag) *
               abrdf_v1_smith_ggx(g.co, ag); // Eq. 5 with Eqs. 6 and 9
    return ks * abrdf_f_schlick(f0, g.cd) * dv;
}

// Disney anisotropic specular (Eqs. 5, 7, 8, 9): aspect = sqrt(1 - 0.9 anisotropic).
color abrdf_disney_specular_aniso(vector wi, vector wo, color ks, float r, float anisotropic,
                                  color f0)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float ag = r * r;
    float aspect = sqrt(1.0 - 0.9 * anisotropic);
    float ax = max(ag / aspect, ABRDF_ALPHA_G_MIN), ay = max(ag * aspect, ABRDF_ALPHA_G_MIN);
    float dv = abrdf_d_ggx_aniso(g.h, ax, ay) * abrdf_v1_smith_ggx_aniso(g.i, ax, ay) *
               abrdf_v1_smith_ggx_aniso(g.o, ax, ay); // Eqs. 5, 7, 9
    return ks * abrdf_f_schlick(f0, g.cd) * dv;
}

// Disney clearcoat: 0.25 ks F(0.04) D_GTR1 G(0.25) / (4 cos_i cos_o),
// alpha = mix(0.1, 0.001, clearcoat_gloss).
color abrdf_disney_clearcoat(vector wi, vector wo, color ks, float clearcoat_gloss)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float alpha = 0.1 + (0.001 - 0.1) * clearcoat_gloss;
    float dv = abrdf_d_gtr1(g.ch, g.sh2, alpha) * abrdf_v1_smith_ggx(g.ci, 0.25) *
               abrdf_v1_smith_ggx(g.co, 0.25);
    return ks * (0.25 * abrdf_f_schlick(0.04, g.cd) * dv);
}

// ---- cloth (k_cloth.h) ------------------------------------------------------------------
// Below this sin^2(theta_h) the inverted-Gaussian term is at its limit 0 (keeps 0 * Inf out).
#define ABRDF_VELVET_SIN2_MIN 1e-4

// Ashikhmin-Premoze inverted-Gaussian velvet D, offset 1, amplitude k_amp.
float abrdf_d_velvet(float ch, float sh2, float alpha, float k_amp)
{
    float g = 0.0;
    if (sh2 > ABRDF_VELVET_SIN2_MIN && ch > 0.0)
        g = exp(-(ch * ch) / (sh2 * alpha * alpha)) / (sh2 * sh2);
    return (1.0 + k_amp * g) / (ABRDF_PI * (1.0 + k_amp * alpha * alpha)); // Eq. 10 (D)
}

// Neubelt-Pettineo 2013, Eq. 10: (1 - F) kd/pi + ks F D / (4 (cos_i + cos_o - cos_i cos_o)).
color abrdf_neubelt_pettineo(vector wi, vector wo, color kd, color ks, color f0, float r,
                             float k_amp)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float dv = abrdf_d_velvet(g.ch, g.sh2, abrdf_alpha_g(r), k_amp) *
               abrdf_safe_div(1.0, 4.0 * (g.ci + g.co - g.ci * g.co));
    color F = abrdf_f_schlick(f0, g.cd);
    return (color(1) - F) * kd * ABRDF_INV_PI + ks * F * dv; // Eq. 10
}

// Kajiya-Kay 1989, Eq. 11 (sign-correct form): kd sin(T,L) + ks [sin sin - cos cos]^n,
// T = local +x.
color abrdf_kajiya_kay(vector wi, vector wo, color kd, color ks, float n)
{
    abrdf_geo g = abrdf_geo_make(wi, wo);
    if (!abrdf_geo_front(g)) return color(0);
    float tl = abrdf_clampr(g.i[0], -1.0, 1.0), tv = abrdf_clampr(g.o[0], -1.0, 1.0);
    float sl = abrdf_clampr(sqrt(g.i[1] * g.i[1] + g.i[2] * g.i[2]), 0.0, 1.0);
    float sv = abrdf_clampr(sqrt(g.o[1] * g.o[1] + g.o[2] * g.o[2]), 0.0, 1.0);
    float spec = abrdf_pow_pos(sl * sv - tl * tv, n);
    return kd * sl + ks * spec; // Eq. 11
}

// ---- layered (layered_ww.c, layered_optics.h) ------------------------------------------
#define ABRDF_MAX_LAYERS 4

// Exact Fresnel reflectance of an interface of relative index eta + i kappa at incidence
// cosine c (Born & Wolf Sec. 14.2); kappa = 0 is the dielectric, incl. total internal
// reflection (F = 1).
float abrdf_fresnel_exact(float c_in, float eta, float kappa)
{
    if (eta == 1.0 && kappa == 0.0) return 0.0; // index-matched: no interface at all
    float c = c_in < 0.0 ? 0.0 : (c_in > 1.0 ? 1.0 : c_in);
    float c2 = c * c, s2 = 1.0 - c2;
    float t0 = eta * eta - kappa * kappa - s2;
    float a2pb2 = sqrt(t0 * t0 + 4.0 * eta * eta * kappa * kappa);
    float a = sqrt(max(0.0, 0.5 * (a2pb2 + t0)));
    float t1 = a2pb2 + c2, t2 = 2.0 * c * a;
    if (!(t1 + t2 > 0.0)) return 1.0; // grazing incidence
    float rs = (t1 - t2) / (t1 + t2);
    float t3 = c2 * a2pb2 + s2 * s2, t4 = t2 * s2;
    float rp = (t3 + t4 > 0.0) ? rs * (t3 - t4) / (t3 + t4) : rs;
    float f = 0.5 * (rs + rp);
    return f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
}

// GGX D of the layered models (layered_optics.h: 0 below the horizon of H).
float abrdf_lo_d_ggx(float ch, float sh2, float ag)
{
    if (!(ch > 0.0)) return 0.0;
    float a2 = ag * ag, t = sh2 + a2 * ch * ch;
    return t > 0.0 ? a2 / (ABRDF_PI * t * t) : 0.0;
}

// Refract the upward unit direction w through the upward unit normal m into the medium
// below (relative index eta) and return the refracted ray reversed (pointing up from
// below); 0 on total internal reflection or if w is behind m.
int abrdf_lo_refract(vector w, vector m, float eta, output vector out)
{
    float ci = dot(w, m);
    if (!(ci > 0.0)) return 0;
    float s2t = (1.0 - ci * ci) / (eta * eta);
    if (!(s2t < 1.0)) return 0;
    float ct = sqrt(1.0 - s2t);
    float k = ci / eta - ct;
    out = w / eta - k * m;
    return 1;
}

// Weidlich-Wilkie layered, Eq. 15 (Weidlich & Wilkie 2007): per interface k, top to bottom,
// f_k = F D G / (4 cos_i cos_o) + T f_{k+1}(L', V') a t, with L', V' refracted at H; a
// conductor (kappa > 0) ends the stack, below the last interface a Lambert base kd/pi.
// OSL cannot recurse: the linear recursion is unrolled into a loop carrying the product
// w of the factors T a t of the interfaces above.
color abrdf_weidlich_wilkie(vector wi, vector wo, color kd, int layer_count,
                            float layer_eta[4], float layer_kappa[4], float layer_r[4],
                            color layer_sigma_a[4], float layer_depth[4])
{
    color f = color(0), w = color(1);
    vector L = wi, V = wo;
    for (int k = 0; k <= ABRDF_MAX_LAYERS; ++k) {
        float ci = L[2], co = V[2];
        if (!(ci > 0.0 && co > 0.0)) break;
        if (k >= layer_count || k >= ABRDF_MAX_LAYERS) {
            f += w * kd * ABRDF_INV_PI; // Lambert base, Eq. 1
            break;
        }
        vector h = L + V;
        float len2 = dot(h, h);
        if (!(len2 > ABRDF_HALF_LEN2_MIN)) break;
        h *= 1.0 / sqrt(len2);
        float cd = dot(L, h);
        float ag = max(layer_r[k] * layer_r[k], ABRDF_ALPHA_G_MIN);
        float F = abrdf_fresnel_exact(cd, layer_eta[k], layer_kappa[k]);
        float vv = abrdf_v1_smith_ggx(ci, ag) * abrdf_v1_smith_ggx(co, ag);
        float top = F * abrdf_lo_d_ggx(h[2], h[0] * h[0] + h[1] * h[1], ag) * vv;
        f += w * top;
        if (layer_kappa[k] > 0.0) break; // conductor: nothing below is seen
        float T = 1.0 - F;
        vector Li, Vi;
        if (!(T > 0.0) || !abrdf_lo_refract(L, h, layer_eta[k], Li) ||
            !abrdf_lo_refract(V, h, layer_eta[k], Vi))
            break; // total internal reflection
        if (!(Li[2] > 0.0 && Vi[2] > 0.0)) break; // refracted below the base's horizon
        float G = 4.0 * ci * co * vv;
        float t = (1.0 - G) + T * G;
        color sd = layer_sigma_a[k] * layer_depth[k];
        color a = color(1);
        for (int c = 0; c < 3; ++c)
            if (sd[c] > 0.0) a[c] = exp(-sd[c] * (1.0 / Li[2] + 1.0 / Vi[2]));
        w *= T * a * t; // Eq. 15
        L = Li;
        V = Vi;
    }
    return f;
}

// ---- Belcour layered (layered_belcour.c, belcour_tables.h) ---------------------------------
// Belcour 2018, Eq. 16: f = sum_k e_k D_GGX(H; alpha_k) G(L, V; alpha_k) / (4 cos_i cos_o),
// e_k and alpha_k from one pass top -> bottom over the stack at the cosine of the mean
// direction (adding-doubling of energies, variances and Jacobians). The same choices as
// the C code (docs/MODELS.md, "Belcour 2018"): cos = |H.L|, separable Smith G, a conductor
// or a failed refraction of the mean ends the stack, TIR with the index of the interface
// above. The FGD and TIR tables are the library's (abrdf_belcour_tables.h, generated).

// Roughness near 1 makes s(alpha) diverge; the reference code clamps alpha at 0.9999.
#define ABRDF_BELCOUR_ALPHA_MAX 0.9999
// Below this cosine of the mean direction the statistics are degenerate (the Jacobian
// eta cos_t / cos blows up); such directions carry no energy.
#define ABRDF_BELCOUR_COS_MIN 1e-6

float abrdf_belcour_var_of_alpha(float a_in)
{
    float a = a_in < 0.0 ? 0.0 : (a_in > ABRDF_BELCOUR_ALPHA_MAX ? ABRDF_BELCOUR_ALPHA_MAX : a_in);
    float p = pow(a, 1.1);
    return p / (1.0 - p);
}

float abrdf_belcour_alpha_of_var(float s)
{
    return s > 0.0 ? pow(s / (1.0 + s), 1.0 / 1.1) : 0.0;
}

// Split a continuous index into a clamped cell (returned) and a weight t.
int abrdf_belcour_cell(float x_in, int n, output float t)
{
    float x = x_in;
    if (!(x > 0.0)) x = 0.0;
    if (x > n - 1) x = n - 1;
    int k = (int)x;
    if (k > n - 2) k = n - 2;
    t = x - k;
    return k;
}

// Continuous index of a value on each axis (belcour_tables.h, abrdf__bt_x_*).
float abrdf_bt_x_cos(float c, int n) { return c * n - 0.5; }
float abrdf_bt_x_alpha(float a, int n) { return a * (n - 1); }
float abrdf_bt_x_fgd_eta(float eta)
{
    return log(eta / ABRDF_FGD_ETA_MIN) / log(ABRDF_FGD_ETA_MAX / ABRDF_FGD_ETA_MIN) *
           (ABRDF_FGD_NETA - 1);
}
float abrdf_bt_x_fgd_kappa(float k)
{
    return sqrt(k > 0.0 ? k / ABRDF_FGD_KAPPA_MAX : 0.0) * (ABRDF_FGD_NKAPPA - 1);
}
float abrdf_bt_x_tir_eta(float eta)
{
    return (eta - ABRDF_TIR_ETA_MIN) / (1.0 - ABRDF_TIR_ETA_MIN) * (ABRDF_TIR_NETA - 1);
}

// Directional albedo of one rough interface, quadrilinear in the FGD table, in [0, 1].
float abrdf_belcour_fgd(float c, float a, float eta, float kappa)
{
    int i[4];
    float t[4];
    float tw;
    i[0] = abrdf_belcour_cell(abrdf_bt_x_cos(c, ABRDF_FGD_NCOS), ABRDF_FGD_NCOS, tw);
    t[0] = tw;
    i[1] = abrdf_belcour_cell(abrdf_bt_x_alpha(a, ABRDF_FGD_NALPHA), ABRDF_FGD_NALPHA, tw);
    t[1] = tw;
    i[2] = abrdf_belcour_cell(abrdf_bt_x_fgd_eta(eta), ABRDF_FGD_NETA, tw);
    t[2] = tw;
    i[3] = abrdf_belcour_cell(abrdf_bt_x_fgd_kappa(kappa), ABRDF_FGD_NKAPPA, tw);
    t[3] = tw;
    float v = abrdf_bt_fgd_sum(i, t);
    return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
}

// Fraction of light leaving the dense side (eta = n_outside / n_inside), trilinear in TIR.
float abrdf_belcour_tir(float c, float a, float eta)
{
    if (eta >= 1.0) return 1.0; // from the less dense side nothing is totally reflected
    int i[3];
    float t[3];
    float tw;
    i[0] = abrdf_belcour_cell(abrdf_bt_x_cos(c, ABRDF_TIR_NCOS), ABRDF_TIR_NCOS, tw);
    t[0] = tw;
    i[1] = abrdf_belcour_cell(abrdf_bt_x_alpha(a, ABRDF_TIR_NALPHA), ABRDF_TIR_NALPHA, tw);
    t[1] = tw;
    i[2] = abrdf_belcour_cell(abrdf_bt_x_tir_eta(eta), ABRDF_TIR_NETA, tw);
    t[2] = tw;
    float v = abrdf_bt_tir_sum(i, t);
    return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
}

float abrdf_avg3(color v) { return (v[0] + v[1] + v[2]) / 3.0; }

// The statistics carried from the top of the stack down to the current medium.
struct abrdf_belcour_stack {
    color R0i; color T0i; color Ri0; color Ti0;
    float sR0i; float sT0i; float sRi0; float sTi0;
    float J0i; float Ji0;
    float cosm; // cosine of the mean direction in the current medium
};

// Adds interface k to the stack; writes its lobe (energy e, roughness alpha_k). Returns 1
// if light continues below it.
int abrdf_belcour_add_interface(output abrdf_belcour_stack st, int k, float layer_eta[4],
                                float layer_kappa[4], float layer_r[4], output color e,
                                output float alpha_k)
{
    float eta = layer_eta[k], alpha = layer_r[k] * layer_r[k];
    int conductor = layer_kappa[k] > 0.0;
    float c = st.cosm;
    float sin_t2 = (1.0 - c * c) / (eta * eta);
    int has_t = !conductor && sin_t2 < 1.0;
    float cos_t = has_t ? sqrt(1.0 - sin_t2) : 0.0;
    if (cos_t < ABRDF_BELCOUR_COS_MIN) has_t = 0;
    float sR12 = abrdf_belcour_var_of_alpha(alpha), sT12 = 0.0, sT21 = 0.0, j12 = 1.0, j21 = 1.0;
    if (has_t) {
        sT12 = abrdf_belcour_var_of_alpha(alpha * 0.5 * abs(eta - 1.0) / eta);
        sT21 = abrdf_belcour_var_of_alpha(alpha * 0.5 * abs(1.0 / eta - 1.0) * eta);
        j12 = eta * cos_t / c;
        j21 = 1.0 / j12;
    }
    float a_top = abrdf_belcour_alpha_of_var(st.sT0i + sR12); // roughness through the stack above
    float R12 = abrdf_belcour_fgd(c, a_top, eta, layer_kappa[k]);
    float T12 = has_t ? 1.0 - R12 : 0.0, R21 = has_t ? R12 : 0.0, T21 = T12;
    if (k > 0) { // TIR at the interface above, seen from this medium
        float tau = abrdf_belcour_tir(c, a_top, 1.0 / layer_eta[k - 1]);
        color ri = st.Ri0 + (1.0 - tau) * st.Ti0;
        for (int ch = 0; ch < 3; ++ch) ri[ch] = min(1.0, ri[ch]);
        st.Ri0 = ri;
        st.Ti0 *= tau;
    }
    color R0i, T0i, Ri0, Ti0, eterm, riterm, rr;
    for (int ch = 0; ch < 3; ++ch) {
        float den = 1.0 - st.Ri0[ch] * R12;
        int ok = den > 0.0;
        eterm[ch] = ok ? st.T0i[ch] * R12 * st.Ti0[ch] / den : 0.0;
        riterm[ch] = ok ? T21 * st.Ri0[ch] * T12 / den : 0.0;
        rr[ch] = ok ? st.Ri0[ch] * R12 / den : 0.0;
        R0i[ch] = st.R0i[ch] + eterm[ch];
        T0i[ch] = ok ? st.T0i[ch] * T12 / den : 0.0;
        Ri0[ch] = R21 + riterm[ch];
        Ti0[ch] = ok ? T21 * st.Ti0[ch] / den : 0.0;
    }
    float e_avg = abrdf_avg3(eterm), ri_avg = abrdf_avg3(riterm), rr_avg = abrdf_avg3(rr);
    float sR0i = abrdf_avg3(st.R0i) * st.sR0i +
                 e_avg * (st.sTi0 + st.J0i * (st.sT0i + sR12 + rr_avg * (sR12 + st.sRi0)));
    float sT0i = j12 * st.sT0i + sT12 + j12 * (sR12 + st.sRi0) * rr_avg;
    float sRi0 = R21 * sR12 + ri_avg * (sT12 + j12 * (sT21 + st.sRi0 + rr_avg * (sR12 + st.sRi0)));
    float sTi0 = st.Ji0 * sT21 + st.sTi0 + st.Ji0 * (sR12 + st.sRi0) * rr_avg;
    float r0i_avg = abrdf_avg3(R0i), ri0_avg = abrdf_avg3(Ri0);
    alpha_k = e_avg > 0.0
                  ? abrdf_belcour_alpha_of_var(st.sTi0 + st.J0i * (st.sT0i + sR12 +
                                                                   rr_avg * (sR12 + st.sRi0)))
                  : 0.0;
    e = e_avg > 0.0 ? eterm : color(0);
    st.R0i = R0i;
    st.T0i = T0i;
    st.Ri0 = Ri0;
    st.Ti0 = Ti0;
    st.sR0i = r0i_avg > 0.0 ? sR0i / r0i_avg : 0.0;
    st.sT0i = sT0i;
    st.sRi0 = ri0_avg > 0.0 ? sRi0 / ri0_avg : 0.0;
    st.sTi0 = sTi0;
    st.J0i *= j12;
    st.Ji0 *= j21;
    st.cosm = cos_t;
    return has_t;
}

// The absorbing medium below an interface: transmittance exp(-sigma_a d / cos) each way.
void abrdf_belcour_add_medium(output abrdf_belcour_stack st, color sigma_a, float depth)
{
    for (int ch = 0; ch < 3; ++ch) {
        float sd = sigma_a[ch] * depth;
        float T = sd > 0.0 ? exp(-sd / st.cosm) : 1.0;
        st.T0i[ch] *= T;
        st.Ti0[ch] *= T;
        st.Ri0[ch] *= T * T;
    }
}

color abrdf_belcour(vector wi, vector wo, int layer_count, float layer_eta[4],
                    float layer_kappa[4], float layer_r[4], color layer_sigma_a[4],
                    float layer_depth[4])
{
    color f = color(0);
    float ci = wi[2], co = wo[2];
    if (!(ci > 0.0 && co > 0.0)) return f;
    vector h = wi + wo;
    float len2 = dot(h, h);
    if (!(len2 > ABRDF_HALF_LEN2_MIN)) return f;
    h *= 1.0 / sqrt(len2);
    float cd = dot(wi, h);
    if (!(cd > ABRDF_BELCOUR_COS_MIN)) return f;
    float sh2 = h[0] * h[0] + h[1] * h[1];
    abrdf_belcour_stack st;
    st.R0i = color(0);
    st.T0i = color(1);
    st.Ri0 = color(0);
    st.Ti0 = color(1);
    st.sR0i = 0.0;
    st.sT0i = 0.0;
    st.sRi0 = 0.0;
    st.sTi0 = 0.0;
    st.J0i = 1.0;
    st.Ji0 = 1.0;
    st.cosm = min(cd, 1.0);
    int n = layer_count < ABRDF_MAX_LAYERS ? layer_count : ABRDF_MAX_LAYERS;
    for (int k = 0; k < n; ++k) {
        color e;
        float ak;
        int below = abrdf_belcour_add_interface(st, k, layer_eta, layer_kappa, layer_r, e, ak);
        float ag = max(ak, ABRDF_ALPHA_G_MIN);
        float lobe = abrdf_lo_d_ggx(h[2], sh2, ag) * abrdf_v1_smith_ggx(ci, ag) *
                     abrdf_v1_smith_ggx(co, ag);
        f += e * lobe; // Eq. 16
        if (!below) break;
        if (layer_depth[k] > 0.0) abrdf_belcour_add_medium(st, layer_sigma_a[k], layer_depth[k]);
    }
    return f;
}

#endif // ABRDF_OSL_KERNELS_H
