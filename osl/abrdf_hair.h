// abrdf_hair.h - the OSL twins of the hair fibre models, 1:1 with libabrdf/src/hair/hair.h,
// hair_common.c, hair_marschner.c and hair_huang.c: the same names, the same parameters in
// the registry's order, the same guards, thresholds, node counts and loop structure, in
// float. Included by abrdf_osl.h. The conventions, formulas and every deliberate choice are in
// docs/MODELS.md, "Hair models"; only what the float transliteration changes is explained
// here.
//
// FIBRE ON A SURFACE: the fibre runs along the local +x axis (the frame's tangent T), the
// surface normal N = +z is the normal of the ribbon carrying it. Each model computes the
// fibre scattering function S(wi, wo) and returns f_r = S / N.wi for wi, wo above the ribbon.
//
//   abrdf_marschner(wi, wo, eta, melanin, redness, cuticle_tilt, aspect_ratio, r)
//   abrdf_huang(wi, wo, eta, melanin, redness, cuticle_tilt, aspect_ratio, r, entry_grid,
//               internal_grid)
#ifndef ABRDF_HAIR_OSL_H
#define ABRDF_HAIR_OSL_H

#include "abrdf_osl_guards.h"
#include "abrdf_hair_tables.h"

// ---- named thresholds (libabrdf/src/hair/hair.h, same values, same reasons) -------------------
// Floor of cos(theta_d) (Marschner) and cos(theta) (Huang): both vanish only along the fibre.
#define ABRDF_HAIR_COS_MIN 1e-6
// |dPhi/dh| below this is a stationary point of the azimuthal map: a root there is clamped.
#define ABRDF_HAIR_DPHI_MIN 1e-9
// Azimuthal intervals narrower than this in Phi carry no root worth solving.
#define ABRDF_HAIR_FLAT_PHI 1e-12
#define ABRDF_HAIR_DEG (ABRDF_PI / 180.0)
// Floor of E in the compensation 1/E (below the tables' smallest entry, 0.0224).
#define ABRDF_HAIR_E_MIN 0.02
// |v|^2 below this: a half vector of two opposite directions (eta = 1), undefined.
#define ABRDF_HUANG_HALF_LEN2_MIN 1e-20
// GGX Lambda of a grazing direction (fully shadowed). The C code returns 1e300; float
// overflows that to Inf, and (1 + Inf) / (1 + Inf + lo) in the masking ratio is NaN. 1e30
// is as "infinite" for every use (1 / (1 + 1e30) is 0 against the other terms) and finite.
#define ABRDF_HUANG_LAMBDA_GRAZING 1e30
// Marschner's glint smoothing constants (hair_marschner.c).
#define ABRDF_MARSCHNER_GLINT_KG 0.5
#define ABRDF_MARSCHNER_GLINT_WC (15.0 * ABRDF_HAIR_DEG)
#define ABRDF_MARSCHNER_GLINT_DETA 0.3
#define ABRDF_MARSCHNER_GLINT_DHM 0.3
// Bisection steps for the roots of the azimuthal map (double precision in C; in float the
// interval stops shrinking after ~25 steps and the rest are no-ops).
#define ABRDF_MARSCHNER_BISECT_STEPS 60

// ---- shared helpers (hair_common.c) ------------------------------------------------------
// Melanin -> absorption sigma_a per unit radius, Cycles' mapping (MODELS.md B7.2).
color abrdf_hair_sigma_a(float melanin, float redness)
{
    float m = -log(max(1.0 - melanin, 1e-4));
    float ce = m * (1.0 - redness), cp = m * redness;
    return ce * color(0.506, 0.841, 1.653) + cp * color(0.343, 0.733, 1.924);
}

// Cosine of the refracted angle for relative index n, or -1 for total internal reflection.
float abrdf_hair_cos_refracted(float n, float c)
{
    float s2 = max(0.0, 1.0 - c * c) / (n * n);
    return s2 >= 1.0 ? -1.0 : sqrt(1.0 - s2);
}

float abrdf_hair_fresnel_s(float n, float c_in)
{
    float c = min(max(c_in, 0.0), 1.0);
    float ct = abrdf_hair_cos_refracted(n, c);
    if (ct < 0.0) return 1.0;
    float den = c + n * ct;
    if (!(den > 0.0)) return 1.0;
    float r = (c - n * ct) / den;
    return r * r;
}

float abrdf_hair_fresnel_p(float n, float c_in)
{
    float c = min(max(c_in, 0.0), 1.0);
    float ct = abrdf_hair_cos_refracted(n, c);
    if (ct < 0.0) return 1.0;
    float den = n * c + ct;
    if (!(den > 0.0)) return 1.0;
    float r = (n * c - ct) / den;
    return r * r;
}

float abrdf_hair_fresnel_dielectric(float n, float c)
{
    return 0.5 * (abrdf_hair_fresnel_s(n, c) + abrdf_hair_fresnel_p(n, c));
}

float abrdf_hair_gauss(float x, float sd)
{
    return exp(-0.5 * (x * x) / (sd * sd)) / (sd * 2.5066282746310002); // sqrt(2 pi)
}

// Wrap an angle into (-pi, pi] (fmod is C's: truncated).
float abrdf_hair_wrap_pi(float a_in)
{
    float a = fmod(a_in, 2.0 * ABRDF_PI);
    if (a > ABRDF_PI) a -= 2.0 * ABRDF_PI;
    else if (a <= -ABRDF_PI) a += 2.0 * ABRDF_PI;
    return a;
}

void abrdf_hair_fibre_angles(vector w, output float sin_t, output float cos_t, output float phi)
{
    sin_t = min(max(w[0], -1.0), 1.0);
    cos_t = sqrt(w[1] * w[1] + w[2] * w[2]);
    phi = atan2(w[2], w[1]);
}

// ---- Marschner et al. 2003 (hair_marschner.c) -------------------------------------------
// Longitudinal shift and width of lobe p from the parameters (abrdf__marschner_setup).
float abrdf_marschner_alpha(float cuticle_tilt, int p)
{
    float a_r = -2.0 * cuticle_tilt * ABRDF_HAIR_DEG;
    return p == 0 ? a_r : (p == 1 ? -a_r / 2.0 : -3.0 * a_r / 2.0);
}
float abrdf_marschner_beta(float r, int p) { return p == 0 ? r : (p == 1 ? r / 2.0 : 2.0 * r); }

float abrdf_marschner_mp(float cuticle_tilt, float r, int p, float theta_h)
{
    return 0.5 * abrdf_hair_gauss(theta_h - abrdf_marschner_alpha(cuticle_tilt, p),
                                  abrdf_marschner_beta(r, p));
}

float abrdf_marschner_phi_of(int p, float h, float eta1)
{
    return 2.0 * p * asin(h / eta1) - 2.0 * asin(h) + p * ABRDF_PI;
}

float abrdf_marschner_dphi_dh(int p, float h, float eta1)
{
    return 2.0 * p / sqrt(eta1 * eta1 - h * h) - 2.0 / sqrt(1.0 - h * h);
}

float abrdf_marschner_d2phi_dh2(int p, float h, float eta1)
{
    return 2.0 * p * h / pow(eta1 * eta1 - h * h, 1.5) - 2.0 * h / pow(1.0 - h * h, 1.5);
}

color abrdf_marschner_ap(color sigma_a, int p, float h, float eta1, float eta2, float cos_theta_t)
{
    float cos_gi = sqrt(max(0.0, 1.0 - h * h));
    float fi = 0.5 * (abrdf_hair_fresnel_s(eta1, cos_gi) + abrdf_hair_fresnel_p(eta2, cos_gi));
    if (p == 0) return color(fi); // A_0
    float st = h / eta1;
    float cos_gt = sqrt(max(0.0, 1.0 - st * st));
    float fo = 0.5 * (abrdf_hair_fresnel_s(1.0 / eta1, cos_gt) +
                      abrdf_hair_fresnel_p(1.0 / eta2, cos_gt));
    float tr = (1.0 - fi) * (1.0 - fo) * pow(fo, p - 1);
    color a = color(0);
    for (int c = 0; c < 3; ++c) {
        // sigma_a = 0 must give T = 1 even where cos_theta_t -> 0 (no 0/0).
        float tau = sigma_a[c] > 0.0
            ? 2.0 * sigma_a[c] * cos_gt / max(cos_theta_t, ABRDF_HAIR_COS_MIN) : 0.0;
        a[c] = tr * exp(-tau * p); // T^p
    }
    return a;
}

// Bravais indices for index eta at theta_d, and the refracted longitudinal cosine.
void abrdf_marschner_bravais(float eta, float sin_d, float cos_d, output float eta1,
                             output float eta2, output float cos_t)
{
    float q = sqrt(max(eta * eta - sin_d * sin_d, 0.0));
    eta1 = max(q / cos_d, 1.0);
    eta2 = eta * eta * cos_d / max(q, ABRDF_HAIR_COS_MIN);
    float st = sin_d / eta;
    cos_t = sqrt(max(0.0, 1.0 - st * st));
}

// Marschner's eccentricity trick for TRT: the effective index for an elliptical section.
float abrdf_marschner_eta_star(float eta, float a, float cos_phi_sum)
{
    float e1 = 2.0 * (eta - 1.0) * a * a - eta + 2.0;
    float e2 = 2.0 * (eta - 1.0) / (a * a) - eta + 2.0;
    return max(1.0, 0.5 * ((e1 + e2) + cos_phi_sum * (e1 - e2)));
}

// Bare root sum: over roots h of Phi(p, h) = phi (mod 2 pi) of A_p(h) / |2 Phi'(h)|.
color abrdf_marschner_root_sum(color sigma_a, int p, float phi, float eta1, float eta2,
                               float cos_t)
{
    color n = color(0);
    float cuts[4] = {-1.0, 1.0, 0.0, 0.0};
    int ncut = 2;
    if (p >= 2 && eta1 < p) {
        float hc = sqrt((p * p - eta1 * eta1) / (p * p - 1.0));
        cuts[0] = -1.0; cuts[1] = -hc; cuts[2] = hc; cuts[3] = 1.0;
        ncut = 4;
    }
    for (int k = 0; k + 1 < ncut; ++k) {
        float a = cuts[k], b = cuts[k + 1];
        float pa = abrdf_marschner_phi_of(p, a, eta1), pb = abrdf_marschner_phi_of(p, b, eta1);
        if (fabs(pb - pa) < ABRDF_HAIR_FLAT_PHI) continue;
        float lo = min(pa, pb), hi = max(pa, pb);
        int inc = pb > pa;
        // Every branch phi + 2 pi j inside [lo, hi] has exactly one root here.
        float j0 = ceil((lo - phi) / (2.0 * ABRDF_PI)), j1 = floor((hi - phi) / (2.0 * ABRDF_PI));
        for (float j = j0; j <= j1; j += 1.0) {
            float target = phi + 2.0 * ABRDF_PI * j;
            float x0 = a, x1 = b;
            for (int it = 0; it < ABRDF_MARSCHNER_BISECT_STEPS; ++it) {
                float xm = 0.5 * (x0 + x1);
                float g = abrdf_marschner_phi_of(p, xm, eta1) - target;
                if ((g < 0.0) == inc) x0 = xm; else x1 = xm;
            }
            float h = 0.5 * (x0 + x1);
            if (!(fabs(h) < 1.0)) continue; // |dPhi/dh| is infinite at |h| = 1: N = 0
            float d = max(fabs(abrdf_marschner_dphi_dh(p, h, eta1)), ABRDF_HAIR_DPHI_MIN);
            n += abrdf_marschner_ap(sigma_a, p, h, eta1, eta2, cos_t) / (2.0 * d);
        }
    }
    return n;
}

color abrdf_marschner_np(float eta_in, float aspect, color sigma_a, int p, float phi_in,
                         float theta_d, float cos_phi_sum, int glint)
{
    float sin_d = sin(theta_d), cos_d = max(cos(theta_d), ABRDF_HAIR_COS_MIN);
    float eta = p == 2 ? abrdf_marschner_eta_star(eta_in, aspect, cos_phi_sum) : eta_in;
    float eta1, eta2, cos_t;
    abrdf_marschner_bravais(eta, sin_d, cos_d, eta1, eta2, cos_t);
    float phi = abrdf_hair_wrap_pi(phi_in);
    color n = abrdf_marschner_root_sum(sigma_a, p, phi, eta1, eta2, cos_t);
    if (p != 2 || !glint) return n;

    // TRT glint smoothing (paper Sec. 4.4), as hair_marschner.c.
    float hc, dh, t;
    if (eta1 < 2.0) {
        hc = sqrt((4.0 - eta1 * eta1) / 3.0);
        float d2 = fabs(abrdf_marschner_d2phi_dh2(2, hc, eta1));
        dh = d2 > 0.0 ? min(ABRDF_MARSCHNER_GLINT_DHM, 2.0 * sqrt(2.0 * ABRDF_MARSCHNER_GLINT_WC / d2))
                      : ABRDF_MARSCHNER_GLINT_DHM;
        t = 1.0;
    } else {
        hc = 0.0;
        dh = ABRDF_MARSCHNER_GLINT_DHM;
        float x = min(1.0, (eta1 - 2.0) / ABRDF_MARSCHNER_GLINT_DETA);
        t = 1.0 - x * x * (3.0 - 2.0 * x);
    }
    if (!(t > 0.0)) return n;
    float phic = abrdf_hair_wrap_pi(abrdf_marschner_phi_of(2, hc, eta1));
    float g0 = abrdf_hair_gauss(0.0, ABRDF_MARSCHNER_GLINT_WC);
    float gm = abrdf_hair_gauss(abrdf_hair_wrap_pi(phi - phic), ABRDF_MARSCHNER_GLINT_WC);
    float gp = abrdf_hair_gauss(abrdf_hair_wrap_pi(phi + phic), ABRDF_MARSCHNER_GLINT_WC);
    float notch = (1.0 - t * gm / g0) * (1.0 - t * gp / g0);
    color ac = abrdf_marschner_ap(sigma_a, 2, hc, eta1, eta2, cos_t);
    return n * notch + t * ABRDF_MARSCHNER_GLINT_KG * ac * dh * (gm + gp);
}

// The fibre scattering function S (all three lobes) for local wi, wo anywhere.
color abrdf_marschner_fibre(vector wi, vector wo, float eta, float melanin, float redness,
                            float cuticle_tilt, float aspect_ratio, float r)
{
    color sigma_a = abrdf_hair_sigma_a(melanin, redness);
    float si, ci, pi_, so, co, po;
    abrdf_hair_fibre_angles(wi, si, ci, pi_);
    abrdf_hair_fibre_angles(wo, so, co, po);
    float ti = asin(si), to = asin(so);
    float th = 0.5 * (ti + to), td = 0.5 * (to - ti);
    float cd = max(cos(td), ABRDF_HAIR_COS_MIN);
    float phi = po - pi_;
    float cps = cos(pi_ + po); // cos(2 phi_h)
    color s = color(0);
    for (int p = 0; p < 3; ++p) {
        color n = abrdf_marschner_np(eta, aspect_ratio, sigma_a, p, phi, td, cps, 1);
        float w = abrdf_marschner_mp(cuticle_tilt, r, p, th) / (cd * cd) * ci; // S = S_M cos
        s += w * n;
    }
    return s;
}

// Marschner, Jensen, Cammarano, Worley, Hanrahan 2003, practical model (its Sec. 4):
// S = sum_p M_p(theta_h) N_p(phi) / cos^2(theta_d) cos(theta_i), f_r = S / N.wi.
color abrdf_marschner(vector wi, vector wo, float eta, float melanin, float redness,
                      float cuticle_tilt, float aspect_ratio, float r)
{
    if (!(wi[2] > 0.0 && wo[2] > 0.0)) return color(0);
    color s = abrdf_marschner_fibre(wi, wo, eta, melanin, redness, cuticle_tilt, aspect_ratio, r);
    return s / wi[2]; // f_r = S / |N.wi|
}

// ---- Huang, Hullin, Hanika 2022 (hair_huang.c) ------------------------------------------
// Cycles' local frame inside: y along the fibre (hair_huang.c maps (x, y, z) -> (y, x, z)).
struct abrdf_huang_m {
    float eta;       // index of refraction
    float alpha;     // GGX roughness (not squared), [0.001, 1]
    float tilt;      // cuticle tilt of the mesonormals (rad), = -cuticle_tilt
    float b;         // minor/major axis ratio, (0, 1]
    color sigma_a;   // absorption per unit (major) radius
    int refine;      // Simpson step divisor (1 = Cycles' steps)
    int n1;          // entry VNDF grid per dimension
    int n2;          // internal-reflection VNDF grid per dimension
    int compensate;  // 1: divide each interaction by the glass albedo E (Cycles)
};

float abrdf_huang_sin_theta(vector w) { return w[1]; }
float abrdf_huang_cos_theta(vector w) { return sqrt(w[0] * w[0] + w[2] * w[2]); }
float abrdf_huang_dir_phi(vector w) { return atan2(w[0], w[2]); }
float abrdf_huang_to_phi(float gamma, float b) { return atan2(b * sin(gamma), cos(gamma)); }
float abrdf_huang_to_gamma(float phi, float b) { return atan2(sin(phi), b * cos(phi)); }

float abrdf_huang_phi_to_h(float phi, float b, float sp_i, float cp_i)
{
    float g = abrdf_huang_to_gamma(phi, b);
    return -cp_i * sin(g) + b * sp_i * cos(g);
}

float abrdf_huang_h_to_gamma(float h_div_r, float b, vector wi)
{
    return atan2(wi[2], -b * wi[0]) - acos(min(max(-h_div_r, -1.0), 1.0));
}

vector abrdf_huang_to_point(float gamma, float b) { return vector(sin(gamma), 0.0, b * cos(gamma)); }

// Unit (meso)normal at ellipse parameter gamma, tilted by theta along the fibre.
vector abrdf_huang_sphg_dir(float theta, float gamma, float b)
{
    float st = sin(theta), ct = cos(theta), sg = sin(gamma), cg = cos(gamma);
    float sp = sg, cp = cg;
    if (b != 1.0) { // (b sin gamma, cos gamma) over its length, >= b
        float n = sqrt(b * b * sg * sg + cg * cg);
        sp = b * sg / n;
        cp = cg / n;
    }
    return vector(sp * ct, st, cp * ct);
}

float abrdf_huang_arc_length(float e2, float gamma)
{
    float s = sin(gamma);
    return sqrt(max(0.0, 1.0 - e2 * s * s));
}

float abrdf_huang_ggx_d_sq(float alpha2, float c2)
{
    float k = 1.0 + (alpha2 - 1.0) * c2;
    return alpha2 / (ABRDF_PI * k * k);
}

float abrdf_huang_ggx_d(float alpha2, float c)
{
    return c > 0.0 ? abrdf_huang_ggx_d_sq(alpha2, c * c) : 0.0;
}

float abrdf_huang_ggx_lambda(float alpha2, float c)
{
    float c2 = c * c;
    if (!(c2 > 0.0)) return ABRDF_HUANG_LAMBDA_GRAZING;
    return 0.5 * (sqrt(1.0 + alpha2 * (1.0 - c2) / c2) - 1.0);
}

float abrdf_huang_ggx_g(float alpha2, float ci, float co)
{
    return 1.0 / (1.0 + abrdf_huang_ggx_lambda(alpha2, ci) + abrdf_huang_ggx_lambda(alpha2, co));
}

float abrdf_huang_ggx_go(float alpha2, float ci, float co)
{
    float li = abrdf_huang_ggx_lambda(alpha2, ci), lo = abrdf_huang_ggx_lambda(alpha2, co);
    return (1.0 + li) / (1.0 + li + lo);
}

// The shift of VNDF grid k (hair_huang.c grid_shift): the k-th point of the R2 sequence minus
// 1/2, its steps in units of 2^-16 and k modulo 2^15, so that 32-bit integers give the C
// library's values exactly.
void abrdf_huang_grid_shift(int k, output float d1, output float d2)
{
    int kk = k % 32768;
    d1 = float((32768 + kk * 49472) % 65536) / 65536.0 - 0.5;
    d2 = float((32768 + kk * 37345) % 65536) / 65536.0 - 0.5;
}

// Heitz 2018's VNDF sampling map as a change of variables (hair_huang.c vndf_map).
vector abrdf_huang_vndf_map(float alpha, vector wi, vector wm, float u1, float u2)
{
    float sg = wm[2] >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sg + wm[2]), bb = wm[0] * wm[1] * a;
    vector s = vector(1.0 + sg * wm[0] * wm[0] * a, sg * bb, -sg * wm[0]);
    vector t = vector(bb, sg + wm[1] * wm[1] * a, -wm[1]);
    vector l = vector(dot(wi, s), dot(wi, t), dot(wi, wm));
    vector vh = vector(alpha * l[0], alpha * l[1], l[2]);
    vh = vh / length(vh);
    float lensq = vh[0] * vh[0] + vh[1] * vh[1];
    vector t1 = lensq > 0.0 ? vector(-vh[1], vh[0], 0.0) / sqrt(lensq) : vector(1, 0, 0);
    vector t2 = cross(vh, t1);
    float r = sqrt(u1), ph = 2.0 * ABRDF_PI * u2;
    float p1 = r * cos(ph), p2 = r * sin(ph);
    float sh = 0.5 * (1.0 + vh[2]);
    p2 = (1.0 - sh) * sqrt(max(0.0, 1.0 - p1 * p1)) + sh * p2;
    float p3 = sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2));
    vector nh = t1 * p1 + t2 * p2 + vh * p3;
    vector ne = vector(alpha * nh[0], alpha * nh[1], max(0.0, nh[2]));
    ne = ne / length(ne);
    return s * ne[0] + t * ne[1] + wm * ne[2];
}

// Fresnel for unpolarised light at cosine c (sign ignored); cos_t: the refracted cosine
// (negative: on the other side), 0 on total internal reflection.
float abrdf_huang_fresnel(float c_in, float eta, output float cos_t)
{
    float c = fabs(c_in);
    float q = eta * eta - (1.0 - c * c);
    if (q <= 0.0) {
        cos_t = 0.0;
        return 1.0;
    }
    cos_t = -sqrt(q) / eta;
    return abrdf_hair_fresnel_dielectric(eta, c);
}

vector abrdf_huang_refract_dir(vector wi, vector n, float cos_t, float inv_eta)
{
    return n * (inv_eta * dot(n, wi) + cos_t) - wi * inv_eta;
}

vector abrdf_huang_reflect_dir(vector i, vector n) { return i - n * (2.0 * dot(i, n)); }

int abrdf_huang_visible1(vector v, vector m, vector h) { return dot(v, h) > 0.0 && dot(v, m) > 0.0; }
int abrdf_huang_visible2(vector a, vector b, vector m, vector h)
{
    return abrdf_huang_visible1(a, m, h) && abrdf_huang_visible1(b, m, h);
}

// Chiang et al. 2016's longitudinal function, for TRRT+.
float abrdf_huang_bessel_i0(float x)
{
    float x2 = 0.25 * x * x, term = 1.0, sum = 1.0;
    for (int k = 1; k < 200 && term > 1e-17 * sum; ++k) {
        term *= x2 / (float(k) * k);
        sum += term;
    }
    return sum;
}

float abrdf_huang_log_bessel_i0(float x)
{
    if (x > 12.0) return x + 0.5 * (1.0 / (8.0 * x) - log(2.0 * ABRDF_PI) - log(x));
    return log(abrdf_huang_bessel_i0(x));
}

float abrdf_huang_longitudinal_m(float si, float ci, float so, float co, float v)
{
    float a = ci * co / v, bsin = si * so / v;
    if (v <= 0.1)
        return exp(abrdf_huang_log_bessel_i0(a) - bsin - 1.0 / v + log(2.0) + log(0.5 / v));
    return exp(-bsin) * abrdf_huang_bessel_i0(a) / (sinh(1.0 / v) * 2.0 * v);
}

// Cycles' TRRT+ estimate: the geometric series of further internal bounces.
float abrdf_huang_trrt(float t1, float r2, float a)
{
    float tavg = max(1.0 - r2, 1e-5);
    return t1 * r2 * r2 * tavg * a * a * a / (1.0 - a * (1.0 - tavg));
}

// Trilinear lookup with Cycles' conventions (nodes at k/(N - 1), coordinates clamped).
float abrdf_huang_table_read(float t[], float x, float y, float z)
{
    int n = ABRDF_HAIR_E_N;
    float c[3] = {x, y, z};
    int i0[3], i1[3];
    float f[3];
    for (int k = 0; k < 3; ++k) {
        float u = min(max(c[k], 0.0), 1.0) * (n - 1);
        i0[k] = int(u) < n - 1 ? int(u) : n - 1;
        i1[k] = i0[k] + 1 < n ? i0[k] + 1 : n - 1;
        f[k] = u - i0[k];
    }
    float v = 0.0;
    for (int k = 0; k < 8; ++k) {
        int ix = (k & 1) ? i1[0] : i0[0], iy = (k & 2) ? i1[1] : i0[1], iz = (k & 4) ? i1[2] : i0[2];
        float w = ((k & 1) ? f[0] : 1 - f[0]) * ((k & 2) ? f[1] : 1 - f[1]) *
                  ((k & 4) ? f[2] : 1 - f[2]);
        v += w * t[(iz * n + iy) * n + ix];
    }
    return v;
}

// 1/E, Cycles' bsdf_hair_huang_energy_scale; 1 when compensation is off.
float abrdf_huang_energy_scale(abrdf_huang_m m, float te[], float tie[], float mu, float eta)
{
    if (!m.compensate) return 1.0;
    float z = sqrt(fabs((eta - 1.0) / (eta + 1.0)));
    float e = eta < 1.0 ? abrdf_huang_table_read(tie, sqrt(m.alpha), mu, z)
                        : abrdf_huang_table_read(te, sqrt(m.alpha), mu, z);
    return 1.0 / max(e, ABRDF_HAIR_E_MIN);
}

// entry_grid x entry_grid VNDF nodes for the entry microfacet, internal_grid x internal_grid
// for TRT's internal reflection (the library's entry_grid and internal_grid parameters).
abrdf_huang_m abrdf_huang_setup(float eta, float melanin, float redness, float cuticle_tilt,
                                float aspect_ratio, float r, int entry_grid, int internal_grid)
{
    abrdf_huang_m m;
    m.eta = eta;
    m.alpha = min(max(r, 0.001), 1.0);
    m.tilt = -cuticle_tilt * ABRDF_HAIR_DEG;
    m.b = min(aspect_ratio, 1.0);
    m.sigma_a = abrdf_hair_sigma_a(melanin, redness);
    m.refine = 1;
    m.n1 = entry_grid;
    m.n2 = internal_grid;
    m.compensate = 1;
    return m;
}

// Simpson intervals (even), the count of the largest range pi (hair_huang.c explains).
int abrdf_huang_simpson_intervals(float res, int refine)
{
    return 2 * int(ceil(ABRDF_PI / res * 0.5)) * refine;
}

// Composite Simpson of Eq. 12's integrand over [lo, hi] with the fixed count n.
float abrdf_huang_simpson_r(abrdf_huang_m m, float te[], float tie[], vector wi, vector wo,
                            vector wh, float lo, float hi, int n)
{
    float b = m.b, a2 = m.alpha * m.alpha, e2 = 1.0 - b * b;
    float res = (hi - lo) / n, sum = 0.0;
    for (int i = 0; i <= n; ++i) {
        float gm = lo + i * res;
        vector wm = abrdf_huang_sphg_dir(m.tilt, gm, b);
        float w = (i == 0 || i == n) ? 0.5 : (i % 2 + 1);
        float c = dot(wm, wh);
        sum += w * abrdf_huang_ggx_d_sq(a2, c * c) * abrdf_huang_ggx_g(a2, dot(wm, wi), dot(wm, wo)) *
               abrdf_huang_arc_length(e2, gm) * abrdf_huang_energy_scale(m, te, tie, dot(wm, wi), m.eta);
    }
    return sum * 2.0 / 3.0 * res;
}

// Eq. 12 over [g0, g0 + gr], cut on the range where the mesonormal faces wo and wm.wh >= 0.
float abrdf_huang_lobe_r(abrdf_huang_m m, float te[], float tie[], vector wi, vector wo,
                         float g0, float gr)
{
    float pi = ABRDF_PI, b = m.b;
    vector wh = wi + wo;
    float l = length(wh);
    if (!(l > 0.0)) return 0.0;
    wh = wh / l;
    float gc = atan2(wi[2], -b * wi[0]) - 0.5 * pi;
    float go = gc + abrdf_hair_wrap_pi(atan2(b * wo[0], wo[2]) - gc);
    float lo = max(g0, go - 0.5 * pi), hi = min(g0 + gr, go + 0.5 * pi);
    if (!(hi > lo)) return 0.0;
    float hxz = sqrt(wh[0] * wh[0] + wh[2] * wh[2]), ct = cos(m.tilt), st = sin(m.tilt);
    float num = -st * wh[1], den = ct * hxz;
    float arc_lo = lo - 1.0, arc_hi = hi + 1.0; // default: the arc covers the range
    if (num >= den) return 0.0;                 // wm.wh <= 0 everywhere
    if (num > -den) {
        float ph = atan2(wh[0], wh[2]), a = acos(num / den), gh = abrdf_huang_to_gamma(ph, b);
        float d1 = abrdf_hair_wrap_pi(gh - abrdf_huang_to_gamma(ph - a, b));
        float d2 = abrdf_hair_wrap_pi(abrdf_huang_to_gamma(ph + a, b) - gh);
        if (d1 < 0.0) d1 = a > 0.5 * pi ? d1 + 2.0 * pi : 0.0;
        if (d2 < 0.0) d2 = a > 0.5 * pi ? d2 + 2.0 * pi : 0.0;
        arc_lo = gh - d1;
        arc_hi = gh + d2;
        float k = floor((lo - arc_hi) / (2.0 * pi)); // first shift reaching the range
        arc_lo += 2.0 * pi * k;
        arc_hi += 2.0 * pi * k;
    }
    int n = abrdf_huang_simpson_intervals(0.7 * m.alpha, m.refine);
    float sum = 0.0;
    for (int k = 0; k < 3 && arc_lo <= hi; ++k) {
        float p0 = max(lo, arc_lo), p1 = min(hi, arc_hi);
        if (p1 > p0) sum += abrdf_huang_simpson_r(m, te, tie, wi, wo, wh, p0, p1, n);
        arc_lo += 2.0 * pi;
        arc_hi += 2.0 * pi;
    }
    float unused;
    return 0.25 * abrdf_huang_fresnel(dot(wi, wh), m.eta, unused) * sum; // Eq. 12
}

// TT + TRT + TRRT+ (RGB): Simpson over gamma, nested shifted grids over the VNDF squares.
color abrdf_huang_lobes_residual(abrdf_huang_m m, float te[], float tie[], vector wi, vector wo,
                                 float g0, float gr, float sp_i, float cp_i)
{
    float b = m.b, eta = m.eta, inv_eta = 1.0 / eta, al = m.alpha;
    float a2 = al * al, e2 = 1.0 - b * b;
    int n1 = m.n1, n2 = m.n2;
    float w1 = 1.0 / (n1 * n1), w2 = 1.0 / (n2 * n2);
    color s_tt = color(0), s_trt = color(0), s_trrt = color(0);
    int n = abrdf_huang_simpson_intervals(0.8 * al, m.refine);
    float res = gr / n;
    float unused;
    for (int i = 0; i <= n; ++i) {
        float gmi = g0 + i * res;
        vector wmi = abrdf_huang_sphg_dir(m.tilt, gmi, b), wmi_ = abrdf_huang_sphg_dir(0.0, gmi, b);
        float cos_mi1 = max(dot(wi, wmi), 0.0);
        float weight = (i == 0 || i == n) ? 0.5 : (i % 2 + 1);
        // projected width of this element seen from wi: the light TRRT+ receives here
        float proj = fabs(cp_i * cos(gmi) + b * sp_i * sin(gmi)) * abrdf_huang_cos_theta(wi);
        float e1, e2s; // the entry grid's shift: grid i
        abrdf_huang_grid_shift(i, e1, e2s);
        for (int j1 = 0; j1 < n1 * n1; ++j1) {
            vector wh1 = abrdf_huang_vndf_map(al, wi, wmi, (j1 / n1 + 0.5 + e1) / n1,
                                              (j1 % n1 + 0.5 + e2s) / n1);
            float cos_hi1 = dot(wi, wh1);
            if (!(cos_hi1 > 0.0)) continue;
            float cos_t1;
            float t1 = 1.0 - abrdf_huang_fresnel(cos_hi1, eta, cos_t1);
            float scale1 = abrdf_huang_energy_scale(m, te, tie, cos_mi1, eta);
            vector wt = abrdf_huang_refract_dir(wi, wh1, cos_t1, inv_eta);
            float phi_t = abrdf_huang_dir_phi(wt);
            float gmt = 2.0 * abrdf_huang_to_phi(phi_t, b) - gmi;
            vector wmt = abrdf_huang_sphg_dir(-m.tilt, gmt, b), wmt_ = abrdf_huang_sphg_dir(0.0, gmt, b);
            float cos_mo1 = dot(-wt, wmi), cos_mi2 = dot(-wt, wmt);
            if (!(dot(-wt, wh1) > 0.0 && dot(-wt, wmi) > 0.0 && dot(-wt, wmi_) > 0.0))
                continue;
            float g1o = abrdf_huang_ggx_go(a2, cos_mi1, cos_mo1);
            float scale2 = abrdf_huang_energy_scale(m, te, tie, cos_mi2, inv_eta);
            float ct_t = max(abrdf_huang_cos_theta(wt), ABRDF_HAIR_COS_MIN);
            float chord = length(abrdf_huang_to_point(gmi, b) - abrdf_huang_to_point(gmt + ABRDF_PI, b));
            color at = color(1);
            for (int c = 0; c < 3; ++c)
                at[c] = m.sigma_a[c] > 0.0 ? exp(-m.sigma_a[c] / ct_t * chord) : 1.0;
            float wgt = weight * w1;

            // TT: exit through the microfacet with generalised half vector wh2 (Eq. 13)
            if (dot(wo, wt) >= inv_eta - 1e-5) {
                vector wh2 = -wt + wo * inv_eta;
                float l2 = dot(wh2, wh2);
                if (l2 > ABRDF_HUANG_HALF_LEN2_MIN) {
                    float rn = 1.0 / sqrt(l2);
                    wh2 = wh2 * rn;
                    float cos_mh2 = dot(wmt, wh2), cos_ho2 = dot(-wo, wh2);
                    // cos_ho2 = wo.wt - 1/eta <= 0 within the tolerance above: no exit
                    if (cos_mh2 > 0.0 && cos_ho2 > 0.0) {
                        float cos_hi2 = dot(-wt, wh2);
                        float t2 = (1.0 - abrdf_huang_fresnel(cos_hi2, inv_eta, unused)) * scale2;
                        float v = wgt * t1 * scale1 * t2 * abrdf_huang_ggx_d(a2, cos_mh2) * g1o *
                                  abrdf_huang_ggx_g(a2, cos_mi2, dot(-wo, wmt)) / cos_mo1 * cos_mi1 *
                                  cos_hi2 * cos_ho2 * rn * rn * abrdf_huang_arc_length(e2, gmt);
                        if (isfinite(v)) s_tt += v * at; // Eq. 13
                    }
                }
            }
            if (!(cos_mi2 > 0.0)) continue;

            // TRT: internal reflection at wh2 (n2 x n2 VNDF nodes, grid i n1^2 + j1), exit at
            // wh3 (Eq. 14)
            float d1, d2;
            abrdf_huang_grid_shift(i * n1 * n1 + j1, d1, d2);
            for (int j2 = 0; j2 < n2 * n2; ++j2) {
                vector wh2 = abrdf_huang_vndf_map(al, -wt, wmt, (j2 / n2 + 0.5 + d1) / n2,
                                                  (j2 % n2 + 0.5 + d2) / n2);
                float cos_hi2 = dot(-wt, wh2);
                if (!(cos_hi2 > 0.0)) continue;
                float r2f = abrdf_huang_fresnel(cos_hi2, inv_eta, unused), r2 = r2f * scale2;
                float wgt2 = wgt * w2;
                vector wtr = -abrdf_huang_reflect_dir(wt, wh2);
                color rr = color(0);
                for (int c = 0; c < 3; ++c) rr[c] = wgt2 * proj * abrdf_huang_trrt(t1, r2f, at[c]);
                if (dot(-wtr, wo) < inv_eta - 1e-5) { // total internal reflection
                    s_trrt += rr;
                    continue;
                }
                if (!abrdf_huang_visible2(-wt, -wtr, wmt, wh2) ||
                    !abrdf_huang_visible2(-wt, -wtr, wmt_, wh2))
                    continue;
                float phi_tr = abrdf_huang_dir_phi(wtr);
                float gmtr = gmi - 2.0 * (abrdf_huang_to_phi(phi_t, b) - abrdf_huang_to_phi(phi_tr, b)) +
                             ABRDF_PI;
                vector wmtr = abrdf_huang_sphg_dir(-m.tilt, gmtr, b), wmtr_ = abrdf_huang_sphg_dir(0.0, gmtr, b);
                vector wh3 = wtr + wo * inv_eta;
                float l3 = dot(wh3, wh3);
                if (!(l3 > ABRDF_HUANG_HALF_LEN2_MIN)) continue;
                float rn3 = 1.0 / sqrt(l3);
                wh3 = wh3 * rn3;
                float cos_mh3 = dot(wmtr, wh3);
                if (!(cos_mh3 > 0.0) || !abrdf_huang_visible2(wtr, -wo, wmtr, wh3) ||
                    !abrdf_huang_visible2(wtr, -wo, wmtr_, wh3)) {
                    s_trrt += rr;
                    continue;
                }
                float cos_hi3 = dot(wh3, wtr), cos_ho3 = dot(wh3, -wo);
                float cos_mi3 = dot(wmtr, wtr), cos_mo2 = dot(wmt, -wtr);
                float t3 = (1.0 - abrdf_huang_fresnel(cos_hi3, inv_eta, unused)) *
                           abrdf_huang_energy_scale(m, te, tie, cos_mi3, inv_eta);
                float ct_tr = max(abrdf_huang_cos_theta(wtr), ABRDF_HAIR_COS_MIN);
                float chord2 = length(abrdf_huang_to_point(gmtr, b) - abrdf_huang_to_point(gmt, b));
                float v = wgt2 * t1 * scale1 * r2 * t3 * abrdf_huang_ggx_d(a2, cos_mh3) * g1o *
                          abrdf_huang_ggx_go(a2, cos_mi2, cos_mo2) *
                          abrdf_huang_ggx_g(a2, cos_mi3, dot(wmtr, -wo)) / (cos_mo1 * cos_mo2) *
                          cos_mi1 * cos_mi2 * cos_hi3 * cos_ho3 * rn3 * rn3 *
                          abrdf_huang_arc_length(e2, gmtr);
                if (isfinite(v))
                    for (int c = 0; c < 3; ++c) {
                        float atr = m.sigma_a[c] > 0.0 ? exp(-m.sigma_a[c] / ct_tr * chord2) : 1.0;
                        s_trt[c] += v * at[c] * atr; // Eq. 14
                    }
                s_trrt += rr;
            }
        }
    }
    float mlong = abrdf_huang_longitudinal_m(abrdf_huang_sin_theta(wi), abrdf_huang_cos_theta(wi),
                                             abrdf_huang_sin_theta(wo), abrdf_huang_cos_theta(wo),
                                             4.0 * al);
    float k = 2.0 / 3.0 * res;
    return ((s_tt + s_trt) * inv_eta * inv_eta + s_trrt * mlong / (2.0 * ABRDF_PI)) * k;
}

// The fibre function S for local wi, wo (hair.h convention): R, plus TT + TRT + TRRT+ when
// residual is 1.
color abrdf_huang_fibre_lobes(abrdf_huang_m m, vector wi_, vector wo_, int residual)
{
    // Cycles' convention: its "wi" is the viewer (our wo), its "wo" the light (our wi).
    vector wi = vector(wo_[1], wo_[0], wo_[2]), wo = vector(wi_[1], wi_[0], wi_[2]);
    float ci = abrdf_huang_cos_theta(wi);
    if (!(ci > ABRDF_HAIR_COS_MIN) || !(abrdf_huang_cos_theta(wo) > 0.0)) return color(0);
    float b = m.b, e2 = 1.0 - b * b;
    float tan_tilt = tan(m.tilt);
    if (tan_tilt * abrdf_huang_sin_theta(wo) / abrdf_huang_cos_theta(wo) < -1.0)
        return color(0); // exit mesonormal hidden
    float x = -tan_tilt * abrdf_huang_sin_theta(wi) / ci;
    if (x > 1.0) return color(0); // entry mesonormal hidden
    float half_span = acos(max(x, 0.0));
    float sp_i = wi[0] / ci, cp_i = wi[2] / ci;
    float radius = sqrt(max(1e-12, 1.0 - e2 * sp_i * sp_i));
    float phi_i = abrdf_huang_dir_phi(wi);
    float hmin = abrdf_huang_phi_to_h(phi_i + half_span, b, sp_i, cp_i) / radius;
    float hmax = abrdf_huang_phi_to_h(phi_i - half_span, b, sp_i, cp_i) / radius;
    hmin = max(hmin, -1.0);
    hmax = min(hmax, 1.0);
    if (!(hmax > hmin)) return color(0);
    float g0 = abrdf_huang_h_to_gamma(hmax, b, wi), g1 = abrdf_huang_h_to_gamma(hmin, b, wi);
    if (!(g1 > g0)) return color(0);
    float area = ci * 2.0 * radius;
    float te[ABRDF_HAIR_E_N3] = ABRDF_HAIR_GLASS_E;
    float tie[ABRDF_HAIR_E_N3] = ABRDF_HAIR_GLASS_INV_E;
    float r = abrdf_huang_lobe_r(m, te, tie, wi, wo, g0, g1 - g0);
    if (!residual) return color(r / area);
    color res = abrdf_huang_lobes_residual(m, te, tie, wi, wo, g0, g1 - g0, sp_i, cp_i);
    return (r + res) / area;
}

// The fibre function S (all lobes) for local wi, wo (hair.h convention).
color abrdf_huang_fibre(abrdf_huang_m m, vector wi_, vector wo_)
{
    return abrdf_huang_fibre_lobes(m, wi_, wo_, 1);
}

// Huang, Hullin, Hanika 2022, far field (Eqs. 12-14) with Cycles' TRRT+ and energy
// compensation, integrated deterministically (docs/MODELS.md, "Hair models"). f_r = S / N.wi.
color abrdf_huang(vector wi, vector wo, float eta, float melanin, float redness,
                  float cuticle_tilt, float aspect_ratio, float r, int entry_grid,
                  int internal_grid)
{
    if (!(wi[2] > 0.0 && wo[2] > 0.0)) return color(0);
    abrdf_huang_m m = abrdf_huang_setup(eta, melanin, redness, cuticle_tilt, aspect_ratio, r,
                                        entry_grid, internal_grid);
    color s = abrdf_huang_fibre(m, wi, wo);
    return s / wi[2]; // f_r = S / |N.wi|
}

// ---- huang tabulated (hair_huang_table.c) -------------------------------------------------
// The residual lobes (TT + TRT + TRRT+) read from a table the library built
// (abrdf_huang_table_build) and `abrdf export --cycles --hair-table` wrote as a float RGB image:
// the values after the header in their own order, nt * np texels wide (light theta node, light
// azimuth node) and nt * nv high (view theta node, view azimuth node), the first row at the
// top. Read texel by texel (no filtering) and interpolated as the library does: Catmull-Rom
// along the lobes' ridges in theta, blended into the read along the theta axes near their
// ends, and in each azimuth (hair_huang_table.c, theta_stencil and residual, says why). R
// keeps the quadrature. Local directions, hair.h convention: the fibre along +x.

void abrdf_huang_table_cr(float t, output float w[4])
{
    float t2 = t * t, t3 = t2 * t;
    w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
    w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
    w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
    w[3] = 0.5 * (t3 - t2);
}

int abrdf_huang_table_clamp(int j, int n) { return j < 0 ? 0 : (j > n - 1 ? n - 1 : j); }

// The two theta axes' stencil (hair_huang_table.c, theta_stencil): up to 32 (view node, light
// node, weight) triples; returns their count.
int abrdf_huang_table_theta(int nt, float tv, float tl, output int iv[32], output int il[32],
                            output float w[32])
{
    float xv = (tv + 0.5 * ABRDF_PI) * nt / ABRDF_PI - 0.5;
    float xl = (tl + 0.5 * ABRDF_PI) * nt / ABRDF_PI - 0.5, xj = xv + xl;
    float fv = floor(xv), fl = floor(xl), fj = floor(xj);
    float wv[4], wl[4], wj[4];
    abrdf_huang_table_cr(xv - fv, wv);
    abrdf_huang_table_cr(xl - fl, wl);
    abrdf_huang_table_cr(xj - fj, wj);
    float e = min(min(xv, nt - 1 - xv), min(xl, nt - 1 - xl)); // nodes from an end
    float s = min(max(0.5 * (e - 2.0), 0.0), 1.0);             // the ridge read's share
    int n = 0;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            int v = (int)fv - 1 + a;
            if (s > 0.0) {
                iv[n] = abrdf_huang_table_clamp(v, nt);
                il[n] = abrdf_huang_table_clamp((int)fj - 1 + b - v, nt);
                w[n] = s * wv[a] * wj[b];
                n += 1;
            }
            if (s < 1.0) {
                iv[n] = abrdf_huang_table_clamp(v, nt);
                il[n] = abrdf_huang_table_clamp((int)fl - 1 + b, nt);
                w[n] = (1.0 - s) * wv[a] * wl[b];
                n += 1;
            }
        }
    return n;
}

// A host may take asin and atan2 from fast approximations (Cycles does: measured errors up to
// 4.5e-5 and 9e-6 rad), which the read across the table's sharp ridges turns into errors of
// 1e-4 of the value. One Newton step on each, with sin and cos, brings them to float rounding
// (measured: 2.6e-7 rad).
float abrdf_huang_table_asin(float x_in)
{
    float x = clamp(x_in, -1.0, 1.0), t = asin(x), c = cos(t);
    return c > 1e-3 ? t - (sin(t) - x) / c : t;
}

float abrdf_huang_table_atan2(float y, float x)
{
    float a = atan2(y, x), c = cos(a), s = sin(a), r = x * c + y * s;
    return r > 0.0 ? a + (y * c - x * s) / r : a;
}

// The residual S of one light wi seen from wo, from the table.
color abrdf_huang_table_residual(string table, int nt, int nv, int np, vector wi, vector wo)
{
    float cv = sqrt(max(1.0 - wo[0] * wo[0], 0.0));
    if (!(cv > ABRDF_HAIR_COS_MIN)) return color(0);
    float tv = abrdf_huang_table_asin(wo[0]), tl = abrdf_huang_table_asin(wi[0]);
    float pv = abrdf_huang_table_atan2(wo[1], wo[2]);
    float d = abrdf_huang_table_atan2(wi[1], wi[2]) - pv;
    d -= 2.0 * ABRDF_PI * round(d / (2.0 * ABRDF_PI));
    if (pv < 0.0) { // y -> -y
        pv = -pv;
        d = -d;
    }
    if (pv > 0.5 * ABRDF_PI) { // z -> -z
        pv = ABRDF_PI - pv;
        d = -d;
    }
    pv = clamp(pv, 0.0, 0.5 * ABRDF_PI); // the steps may cross pi by a rounding
    int iv[32], il[32];
    float wt[32], wp[4] = {0.0, 1.0, 0.0, 0.0};
    int nth = abrdf_huang_table_theta(nt, tv, tl, iv, il, wt);
    int ip = 0;
    if (nv > 1) {
        float x = pv * (nv - 1) / (0.5 * ABRDF_PI);
        ip = min((int)floor(x), nv - 2);
        abrdf_huang_table_cr(x - ip, wp);
    }
    float width = nt * np, height = nt * nv;
    color acc = color(0);
    for (int q = 0; q < 4; ++q) {
        if (wp[q] == 0.0) continue;
        int jv = nv > 1 ? ip - 1 + q : 0;
        float dd = d;
        if (jv < 0) { // across phi_v = 0
            jv = -jv;
            dd = -dd;
        }
        if (jv > nv - 1) { // across phi_v = pi/2
            jv = 2 * (nv - 1) - jv;
            dd = -dd;
        }
        float x = (dd + ABRDF_PI) * np / (2.0 * ABRDF_PI), f = floor(x);
        float wd[4];
        abrdf_huang_table_cr(x - f, wd);
        for (int a = 0; a < nth; ++a) {
            float t = (iv[a] * nv + jv + 0.5) / height;
            for (int k = 0; k < 4; ++k) {
                int kd = (((int)f - 1 + k) % np + np) % np;
                color c = texture(table, (il[a] * np + kd + 0.5) / width, t, 0, 0, 0, 0, "interp",
                                  "closest", "wrap", "clamp");
                acc += wp[q] * wt[a] * wd[k] * c;
            }
        }
    }
    color s = color(0);
    for (int c = 0; c < 3; ++c) s[c] = acc[c] > 0.0 ? acc[c] / cv : 0.0;
    return s;
}

// huang with its residual read from a table (the texture `table`, nt theta nodes, nv view
// azimuths, np light azimuths, as abrdf_huang_table_size gives them): the library's prepared
// huang on abrdf_prepare_huang_table. A table whose resolution is not (nt np, nt nv) is an
// error, and the lobe is 0.
color abrdf_huang_tabulated(vector wi, vector wo, float eta, float melanin, float redness,
                            float cuticle_tilt, float aspect_ratio, float r, int entry_grid,
                            int internal_grid, string table, int nt, int nv, int np)
{
    if (!(wi[2] > 0.0 && wo[2] > 0.0)) return color(0);
    int res[2] = {0, 0};
    if (!gettextureinfo(table, "resolution", res) || res[0] != nt * np || res[1] != nt * nv) {
        error("abrdf: huang table %s: %d x %d texels, not %d x %d", table, res[0], res[1], nt * np,
              nt * nv);
        return color(0);
    }
    abrdf_huang_m m = abrdf_huang_setup(eta, melanin, redness, cuticle_tilt, aspect_ratio, r,
                                        entry_grid, internal_grid);
    // where S is 0 whatever the table: the view along the fibre, or a mesonormal the cuticle
    // tilt hides from the view or the light (hair_huang_table.c, view_lit and light_lit)
    float tan_tilt = tan(m.tilt);
    float c_o = sqrt(wo[1] * wo[1] + wo[2] * wo[2]), c_i = sqrt(wi[1] * wi[1] + wi[2] * wi[2]);
    if (!(c_o > ABRDF_HAIR_COS_MIN) || -tan_tilt * wo[0] / c_o > 1.0) return color(0);
    color s = abrdf_huang_fibre_lobes(m, wi, wo, 0);
    if (c_i > 0.0 && !(tan_tilt * wi[0] / c_i < -1.0))
        s += abrdf_huang_table_residual(table, nt, nv, np, wi, wo);
    return s / wi[2]; // f_r = S / |N.wi|
}

#endif // ABRDF_HAIR_OSL_H
