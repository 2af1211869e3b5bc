// abrdf_osl_guards.h - the named thresholds and the guards of the OSL port, the same values
// and reasons as libabrdf's internal header: the only place where sqrt, division and pow are
// made safe. Included by every header of the port that computes.
#ifndef ABRDF_OSL_GUARDS_H
#define ABRDF_OSL_GUARDS_H

// ---- named thresholds (libabrdf/src/base/abrdf_internal.h, same values, same reasons) ----------
// Smallest microfacet roughness alpha_g: the GGX peak 1/(pi alpha_g^2) stays finite in float.
#define ABRDF_ALPHA_G_MIN 1e-6
// |wi + wo|^2 below this: the half vector is undefined (wi ~ -wo, both grazing, f = 0).
#define ABRDF_HALF_LEN2_MIN 1e-12
// G = 1 models divide by cos_i cos_o; each cosine is clamped here (bounds 1/(ci co) by 2.5e7).
#define ABRDF_COS_MIN_NO_G 1e-4
// Disney clearcoat GTR1 at alpha = 1 is 0/0; within this distance of 1 use its limit 1/pi.
#define ABRDF_GTR1_ALPHA_ONE 1e-7
#define ABRDF_PI 3.14159265358979323846
#define ABRDF_INV_PI 0.31830988618379067154

// ---- guards (the only place where sqrt/division/pow are made safe) ----------------------
// Two plain selects, as the C kernel: NaN -> lo.
float abrdf_clampr(float x, float lo, float hi)
{
    float y = x > lo ? x : lo;
    return y < hi ? y : hi;
}
float abrdf_pos(float x) { return x > 0.0 ? x : 0.0; } // NaN -> 0 as well
float abrdf_safe_sqrt(float x) { return sqrt(abrdf_pos(x)); }
float abrdf_safe_div(float a, float b) { return b != 0.0 ? a / b : 0.0; }
// pow with the base clamped to >= 0 (pow of a negative base is NaN or a spurious lobe).
float abrdf_pow_pos(float x, float e) { return pow(abrdf_pos(x), e); }
// x^(2^k) by k squarings of max(0, x): the Table-1 forms.
float abrdf_pow2k(float x, int k)
{
    float y = abrdf_pos(x);
    for (int i = 0; i < k; ++i) y *= y;
    return y;
}
// Every channel of an RGB parameter inside [lo, hi] (NaN fails).
int abrdf_in_range(color v, float lo, float hi)
{
    return v[0] >= lo && v[0] <= hi && v[1] >= lo && v[1] <= hi && v[2] >= lo && v[2] <= hi;
}

#endif // ABRDF_OSL_GUARDS_H
