/* guards.h - every threshold of the evaluation code, each with the reason for its value, and
 * the guards of the double-only models (hair, layered). The closed-form kernels use the
 * same thresholds through their own guards, in the kernels' precision (kernel.h: pos,
 * safe_sqrt, safe_div, clampr, finite_or_zero). */
#ifndef ABRDF_GUARDS_H
#define ABRDF_GUARDS_H
#include <math.h>

/* ---- geometry and roughness, every model ---------------------------------------------- */

/* Smallest microfacet roughness alpha_g. The paper's Table 6 goes down to alpha_g = 1e-5;
 * at 1e-6 the GGX peak 1/(pi alpha_g^2) = 3.2e11 is still far inside float's range and
 * alpha_g^4 = 1e-24 stays a normal float, so D never overflows or divides by zero. */
#define ABRDF__ALPHA_G_MIN 1e-6

/* |wi + wo|^2 below this means wi ~ -wo: the half vector is undefined. Both directions then
 * lie at grazing (they cannot both be above the surface), where every model returns 0. */
#define ABRDF__HALF_LEN2_MIN 1e-12

/* ---- closed-form kernels ---------------------------------------------------------------- */

/* Models with G = 1 (Table 5's Cook-Torrance forms) divide by cos_i cos_o with nothing to
 * cancel it. Clamping each cosine at 1e-4 bounds that factor by 2.5e7 (MODELS.md B4), so
 * grazing rims stay finite in float as well as double. */
#define ABRDF__COS_MIN_NO_G 1e-4

/* Disney clearcoat GTR1 at alpha = 1 is 0/0; within this distance of 1 use its limit 1/pi. */
#define ABRDF__GTR1_ALPHA_ONE 1e-7

/* Below this sin^2(theta_h) the inverted-Gaussian velvet term exp(-cot^2/alpha^2)/sin^4 is
 * taken at its limit 0 (0/0 at theta_h = 0). For every alpha <= 1 its value at the threshold
 * is below exp(-0.9999e4) * 1e8, i.e. exactly 0 in double, so the cut changes nothing; it
 * only keeps 0 * Inf out of float. (Filament's 2^-7 clamp is an fp16 guard, not copied.) */
#define ABRDF__VELVET_SIN2_MIN 1e-4

/* ---- hair (hair_*.c) ------------------------------------------------------------------- */
/* Where the OSL twin (osl/abrdf_hair.h) names a threshold, it is this name with one
 * underscore. */

/* Floor of cos(theta_d) (Marschner) and cos(theta) (Huang): both vanish only when a
 * direction runs along the fibre. 1e-6 keeps eta' = sqrt(eta^2 - sin^2)/cos <= 4e6 and
 * 1/cos^2 <= 1e12, finite, while changing no direction farther than 0.06 deg from T. */
#define ABRDF__HAIR_COS_MIN 1e-6

/* |dPhi/dh| below this is a stationary point of the azimuthal map (a caustic, or eta' = 1
 * where TT is a Dirac delta): a root there is clamped to it, which bounds one root's
 * A/|2 dPhi/dh| by 5e8 * A. Such roots only occur where the glint smoothing multiplies
 * them by ~0 (TRT) or on a set of measure zero (TT at eta = 1). */
#define ABRDF__HAIR_DPHI_MIN 1e-9

/* Azimuthal intervals narrower than this in Phi carry no root worth solving (Phi constant:
 * TT at eta' = 1 is a delta in phi, zero almost everywhere). */
#define ABRDF__HAIR_FLAT_PHI 1e-12

/* Floor of 1 - melanin in the melanin -> concentration map -ln(1 - melanin): Cycles' value,
 * with which melanin = 1 maps to the finite concentration 9.2. */
#define ABRDF__HAIR_MELANIN_REST_MIN 1e-4

/* Floor of E in the Huang energy compensation 1/E, a guard only: it lies below the tables'
 * smallest entry (0.0224, printed in hair_tables.c; grazing light inside a fibre of high
 * index), so it never changes a tabulated value, and it bounds 1/E at 50. */
#define ABRDF__HAIR_E_MIN 0.02

/* Huang's generalised half vectors -wt + wo/eta and wtr + wo/eta: |.|^2 below this only at
 * eta = 1 with the two directions aligned, where the lobe is a delta and the half vector
 * 0/0. Lower than ABRDF__HALF_LEN2_MIN because a short generalised half vector (eta near
 * 1) is a valid configuration, not a pair at grazing. */
#define ABRDF__HUANG_HALF_LEN2_MIN 1e-20

/* Smith's Lambda at a grazing cosine (infinite): a finite stand-in so that G = 1/(1 +
 * Lambda_i + Lambda_o) is 0 without Inf/Inf. */
#define ABRDF__HUANG_LAMBDA_GRAZING 1e300

/* Tolerance of the critical-angle test for leaving the fibre (wo.wt >= 1/eta - tol):
 * Cycles' value, which keeps the exit at the critical angle itself. */
#define ABRDF__HUANG_CRITICAL_TOL 1e-5

/* Floor of the average transmission in Huang's TRRT+ geometric series
 * 1/(1 - a (1 - T)): keeps it finite for a lossless fibre (a = 1) with T -> 0. */
#define ABRDF__HUANG_TAVG_MIN 1e-5

/* Cycles' clip of h (units of the projected radius) before its Simpson over h, where
 * dgamma/dh is singular at +-1; used only by the tests' Cycles quadrature (cycles_nodes in
 * hair.h): the model integrates over gamma and needs no clip. */
#define ABRDF__HUANG_CYCLES_H_CLIP 0.999

/* Floor of the squared projected radius 1 - e^2 sin^2(phi_i) of the elliptical section;
 * it is >= b^2 >= 1e-4 for the registry's aspect ratios, so this only keeps 1/0 out. */
#define ABRDF__HUANG_RADIUS2_MIN 1e-12

/* Bessel I0 by its power series: stop when a term falls below this fraction of the sum
 * (under double's 1.1e-16), after at most ABRDF__HUANG_I0_TERMS terms. */
#define ABRDF__HUANG_I0_REL_TOL 1e-17
#define ABRDF__HUANG_I0_TERMS 200

/* Past this argument log I0(x) uses its asymptotic expansion: the series' terms would
 * overflow their exponent long before it converges. */
#define ABRDF__HUANG_I0_ASYMPTOTIC 12.0

/* Chiang's longitudinal variance v at or below which M is evaluated in log form:
 * sinh(1/v) overflows for small v. */
#define ABRDF__HUANG_M_LOG_V 0.1

/* Smallest Huang GGX roughness alpha (Cycles' clamp): the quadrature step is 0.7 alpha. */
#define ABRDF__HUANG_ALPHA_MIN 0.001

/* ---- layered (layered_*.c) ---------------------------------------------------------------- */

/* Roughness near 1 makes Belcour's variance s(alpha) = alpha^1.1 / (1 - alpha^1.1) diverge;
 * the reference code clamps alpha at 0.9999. */
#define ABRDF__BELCOUR_ALPHA_MAX 0.9999

/* Below this cosine of the mean direction Belcour's statistics are degenerate (the Jacobian
 * eta cos_t / cos blows up): such a direction only occurs for L ~ -V, both grazing, or at
 * the critical angle of a less dense layer, and carries no energy. */
#define ABRDF__BELCOUR_COS_MIN 1e-6

/* ---- sampling (sample_*.c) -------------------------------------------------------------- */

/* A power-form or Schlick lobe whose value varies by less than this relative amount over its
 * support (n t_max / m for ((n/m)(c - 1) + 1)^m, n for 1/(1 + n t)) is sampled uniformly:
 * its own inverse CDF would take 1 - x^(1/(m+1)) of an x within 1e-8 of 1 and lose half
 * the digits, while the uniform density is within 1e-8 of the lobe's. */
#define ABRDF__SAMPLE_FLAT 1e-8

/* The largest uniform number a sampler uses: abrdf_sample accepts u = 1, which every
 * inverse CDF here maps to the end of its support (log(1 - u) = -Inf); 1 - 2^-53 is the
 * largest double below 1. */
#define ABRDF__SAMPLE_U_MAX (1.0 - 1.1102230246251565e-16)

/* ---- guards of the double-only models --------------------------------------------------- */

/* sqrt of a quantity that is >= 0 up to rounding (1 - c^2, a sum of squares minus one). */
static inline double abrdf__safe_sqrt(double x) { return x > 0.0 ? sqrt(x) : 0.0; }

/* x clamped to [lo, hi]; NaN gives lo. Compares, not fmin/fmax: without -ffinite-math-only
 * those are library calls on x86-64 (their NaN rules), and the double paths call this in
 * their inner loops. */
static inline double abrdf__clamp(double x, double lo, double hi)
{
    return x > lo ? (x < hi ? x : hi) : lo;
}

#endif /* ABRDF_GUARDS_H */
