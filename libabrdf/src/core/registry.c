/* registry.c - the single table of parameters and models that the library, the CLI, the
 * docs, the ports' metadata and the tests read. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "abrdf_internal.h"
#include "hair.h" /* the Huang quadrature defaults and bounds */

/* ---- parameters -------------------------------------------------------------------- */

#define PI_2 1.5707963267948966

/* Where each parameter lives in abrdf_params. */
typedef struct abrdf__param_slot {
    abrdf_param_info info;
    size_t offset;
} abrdf__param_slot;

/* The registry is a table laid out by hand, one entry per line. */
/* clang-format off */
#define SCALAR(field, help, lo, hi, def) \
    {{#field, help, ABRDF_PARAM_SCALAR, lo, hi, def}, offsetof(abrdf_params, field)}
#define RGB(field, help, lo, hi, def) \
    {{#field, help, ABRDF_PARAM_RGB, lo, hi, def}, offsetof(abrdf_params, field)}
#define LAYER(k)                                                                            \
    {{"layer" #k "_eta", "layer " #k ": relative index of refraction of the interface",     \
      ABRDF_PARAM_SCALAR, 0.25, 4.0, 1.5}, offsetof(abrdf_params, layers[k].eta)},          \
    {{"layer" #k "_kappa", "layer " #k ": extinction coefficient (conductor if > 0)",       \
      ABRDF_PARAM_SCALAR, 0.0, 10.0, 0.0}, offsetof(abrdf_params, layers[k].kappa)},        \
    {{"layer" #k "_r", "layer " #k ": perceptual roughness of the interface",               \
      ABRDF_PARAM_SCALAR, 0.0, 1.0, 0.1}, offsetof(abrdf_params, layers[k].r)},             \
    {{"layer" #k "_sigma_a", "layer " #k ": absorption of the medium below, 1/depth unit", \
      ABRDF_PARAM_RGB, 0.0, 1e4, 0.0}, offsetof(abrdf_params, layers[k].sigma_a)},         \
    {{"layer" #k "_depth", "layer " #k ": thickness of the medium below",                   \
      ABRDF_PARAM_SCALAR, 0.0, 100.0, 0.0}, offsetof(abrdf_params, layers[k].depth)}

static const abrdf__param_slot params_table[] = {
    RGB(kd, "diffuse reflectance (albedo), linear RGB", 0.0, 1.0, 1.0),
    RGB(ks, "specular lobe weight, linear RGB", 0.0, 1.0, 1.0),
    RGB(f0, "Fresnel reflectance at normal incidence, linear RGB", 0.0, 1.0, 0.04),
    SCALAR(n, "Phong / Blinn-Phong exponent (shininess)", 0.0, 1e6, 100.0),
    SCALAR(r, "perceptual roughness (the paper's alpha); alpha_g = r^2", 0.0, 1.0, 0.5),
    SCALAR(anisotropic, "Disney anisotropy; 0 = isotropic", 0.0, 1.0, 0.0),
    SCALAR(sigma, "Oren-Nayar slope deviation, radians", 0.0, PI_2, 0.3),
    SCALAR(clearcoat_gloss, "Disney clearcoat gloss; alpha = mix(0.1, 0.001, gloss)", 0.0, 1.0, 1.0),
    SCALAR(k_amp, "Neubelt-Pettineo inverted-Gaussian amplitude", 0.0, 100.0, 4.0),
    SCALAR(eta, "index of refraction of the hair fibre", 1.0, 4.0, 1.55),
    SCALAR(melanin, "hair melanin concentration", 0.0, 1.0, 0.3),
    SCALAR(redness, "hair pheomelanin fraction of the melanin", 0.0, 1.0, 0.0),
    SCALAR(cuticle_tilt, "hair cuticle tilt, degrees", -10.0, 10.0, 2.0),
    SCALAR(aspect_ratio, "hair cross-section minor/major axis ratio", 0.01, 1.0, 0.85),
    {{"layer_count", "number of layers of the stack", ABRDF_PARAM_INT, 0.0, ABRDF_MAX_LAYERS, 1.0},
     offsetof(abrdf_params, layer_count)},
    LAYER(0), LAYER(1), LAYER(2), LAYER(3),
    {{"entry_grid", "huang: entry microfacet quadrature, n x n VNDF midpoint nodes",
      ABRDF_PARAM_INT, 1.0, ABRDF__HUANG_GRID_MAX, ABRDF__HUANG_N1},
     offsetof(abrdf_params, entry_grid)},
    {{"internal_grid", "huang: TRT internal-reflection quadrature, n x n VNDF midpoint nodes",
      ABRDF_PARAM_INT, 1.0, ABRDF__HUANG_GRID_MAX, ABRDF__HUANG_N2},
     offsetof(abrdf_params, internal_grid)},
};

#define PARAM_COUNT ((int)(sizeof params_table / sizeof params_table[0]))

/* Parameter ids, for the model table below (their order in params_table). */
enum {
    P_KD, P_KS, P_F0, P_N, P_R, P_ANISOTROPIC, P_SIGMA, P_CLEARCOAT_GLOSS, P_K_AMP, P_ETA,
    P_MELANIN, P_REDNESS, P_CUTICLE_TILT, P_ASPECT_RATIO, P_LAYER_COUNT, P_LAYER0,
    P_ENTRY_GRID = P_LAYER0 + 5 * ABRDF_MAX_LAYERS, P_INTERNAL_GRID
};

/* ---- models ------------------------------------------------------------------------ */

#define REC ABRDF_PROP_RECIPROCAL
#define EC ABRDF_PROP_ENERGY_CONSERVING
#define DIF ABRDF_PROP_DIFFUSE
#define SPE ABRDF_PROP_SPECULAR

/* {id, default, min, max} per model; ranges repeat the parameter's own unless narrower. */
#define KD {P_KD, 1.0, 0.0, 1.0}
#define KS {P_KS, 1.0, 0.0, 1.0}
#define F0 {P_F0, 0.04, 0.0, 1.0}
#define N_ANY {P_N, 100.0, 0.0, 1e6}
#define N_GE1 {P_N, 100.0, 1.0, 1e6} /* 0.111/n in the f_2e normalisation, fitted for n >= 1 */
#define R_ANY {P_R, 0.5, 0.0, 1.0}
static const abrdf_model_param mp_kd[] = {KD};
static const abrdf_model_param mp_kd_f0[] = {KD, F0};
static const abrdf_model_param mp_kd_r[] = {KD, R_ANY};
static const abrdf_model_param mp_kd_sigma[] = {KD, {P_SIGMA, 0.3, 0.0, PI_2}};
static const abrdf_model_param mp_ks_n[] = {KS, N_ANY};
static const abrdf_model_param mp_ks_n1[] = {KS, N_GE1};
static const abrdf_model_param mp_ks_n_f0[] = {KS, N_ANY, F0};
static const abrdf_model_param mp_ks_n1_f0[] = {KS, N_GE1, F0};
static const abrdf_model_param mp_ks_r_f0[] = {KS, R_ANY, F0};
static const abrdf_model_param mp_aniso[] = {KS, R_ANY, {P_ANISOTROPIC, 0.5, 0.0, 1.0}, F0};
static const abrdf_model_param mp_clearcoat[] = {KS, {P_CLEARCOAT_GLOSS, 1.0, 0.0, 1.0}};

#define PARAMS(a) (int)(sizeof a / sizeof a[0]), a

#define KD_AT(d) {P_KD, d, 0.0, 1.0}
#define KS_AT(d) {P_KS, d, 0.0, 1.0}
/* The five parameters of layer k with this model's defaults (ranges are the parameters'). */
#define LAYER_MP(k, eta, kappa, r)                                                          \
    {P_LAYER0 + 5 * (k), eta, 0.25, 4.0}, {P_LAYER0 + 5 * (k) + 1, kappa, 0.0, 10.0},      \
    {P_LAYER0 + 5 * (k) + 2, r, 0.0, 1.0}, {P_LAYER0 + 5 * (k) + 3, 0.0, 0.0, 1e4},        \
    {P_LAYER0 + 5 * (k) + 4, 0.0, 0.0, 100.0}
/* Neubelt-Pettineo: kd, sheen weight ks, f0, r (alpha_g = r^2 is the velvet width), k_amp. */
static const abrdf_model_param mp_neubelt[] = {KD_AT(0.5), KS_AT(1.0), F0, {P_R, 0.7, 0.0, 1.0},
                                               {P_K_AMP, 4.0, 0.0, 100.0}};
/* Kajiya-Kay: kd, ks, exponent n. */
static const abrdf_model_param mp_kajiya[] = {KD_AT(0.25), KS_AT(0.25), {P_N, 40.0, 0.0, 1e6}};
/* Weidlich-Wilkie: coated plastic, a clear rough coat (eta 1.5, r 0.2) over Lambert kd. */
static const abrdf_model_param mp_ww[] = {KD_AT(0.5), {P_LAYER_COUNT, 1.0, 0.0, ABRDF_MAX_LAYERS},
    LAYER_MP(0, 1.5, 0.0, 0.2), LAYER_MP(1, 1.5, 0.0, 0.1), LAYER_MP(2, 1.5, 0.0, 0.1),
    LAYER_MP(3, 1.5, 0.0, 0.1)};
/* Belcour: coated metal, a smooth clear coat (eta 1.5, r 0.1) over a rough conductor with
 * aluminium's index (1.2 + 7.0i at 550 nm) relative to the coat: eta 0.8, kappa 4.7, r 0.4. */
static const abrdf_model_param mp_belcour[] = {{P_LAYER_COUNT, 2.0, 1.0, ABRDF_MAX_LAYERS},
    LAYER_MP(0, 1.5, 0.0, 0.1), LAYER_MP(1, 0.8, 4.7, 0.4), LAYER_MP(2, 1.5, 0.0, 0.1),
    LAYER_MP(3, 1.5, 0.0, 0.1)};
#define CIT_NEUBELT "D. Neubelt, M. Pettineo, Crafting a next-gen material pipeline for The Order: 1886, SIGGRAPH 2013 course; M. Ashikhmin, S. Premoze, Distribution-based BRDFs, 2007"
#define CIT_KAJIYA "J. T. Kajiya, T. L. Kay, Rendering fur with three dimensional textures, SIGGRAPH 1989"
#define CIT_WW "A. Weidlich, A. Wilkie, Arbitrarily layered micro-facet surfaces, GRAPHITE 2007"
#define CIT_BELCOUR "L. Belcour, Efficient rendering of layered materials using an atomic decomposition with statistical operators, ACM TOG 37(4), 2018"

#define CIT_LAMBERT "J. H. Lambert, Photometria, 1760"
#define CIT_BURLEY "B. Burley, Physically-Based Shading at Disney, SIGGRAPH 2012 course notes"
#define CIT_ON "M. Oren, S. K. Nayar, Generalization of Lambert's reflectance model, SIGGRAPH 1994"
#define CIT_PHONG "B. T. Phong, Illumination for computer generated pictures, CACM 18(6), 1975"
#define CIT_BLINN "J. F. Blinn, Models of light reflection for computer synthesized pictures, SIGGRAPH 1977"
#define CIT_TABLE1 "Zavalniuk, Romanyuk 2024, Table 1 (power form after Lyon 1993)"
#define CIT_SCHLICK "C. Schlick, A fast alternative to Phong's specular model, Graphics Gems IV, 1994"
#define CIT_ROMANYUK "O. N. Romanyuk et al., IAPGOS 13(3), 2023 (coefficients fitted by abrdf)"
#define CIT_LAFORTUNE "E. Lafortune, Y. Willems, Using the modified Phong reflectance model, KU Leuven TR CW197, 1994"
#define CIT_GIESEN "F. Giesen, The Blinn-Phong normalization zoo, 2009"
#define CIT_PAPER "Zavalniuk, Romanyuk 2024, Table 5 (fitted normalisation)"
#define CIT_GOTANDA "Y. Gotanda, Beyond a simple physically based Blinn-Phong model in real-time, SIGGRAPH 2012 course"
#define CIT_CT "R. L. Cook, K. E. Torrance, A reflectance model for computer graphics, ACM TOG 1(1), 1982"
#define CIT_WALTER "B. Walter et al., Microfacet models for refraction through rough surfaces, EGSR 2007; " CIT_BURLEY

/* Hair (hair.h). Defaults: brown hair with Cycles' Principled Hair defaults (melanin 0.8, redness 1.0),
 * eta 1.55 (keratin). Marschner: r is the longitudinal width beta_R in radians (the paper's
 * 5-10 deg -> 0.13 rad), the axis ratio a in [0.75, 1] where its eccentricity trick keeps
 * eta* >= 1 (it needs a^2 >= 1/2). */
static const abrdf_model_param mp_marschner[] = {
    {P_ETA, 1.55, 1.0, 4.0}, {P_MELANIN, 0.8, 0.0, 1.0}, {P_REDNESS, 1.0, 0.0, 1.0},
    {P_CUTICLE_TILT, 3.0, -10.0, 10.0}, {P_ASPECT_RATIO, 0.9, 0.75, 1.0},
    {P_R, 0.13, 0.01, 1.0}};
#define CIT_MARSCHNER "S. R. Marschner, H. W. Jensen, M. Cammarano, S. Worley, P. Hanrahan, " \
    "Light scattering from human hair fibers, ACM TOG 22(3), 2003"
/* Huang: Cycles' Principled Hair (Huang) defaults: r = GGX alpha 0.3 (not squared, clamped
 * to >= 0.001 as Cycles does), offset 2 deg, aspect ratio 0.85; r >= 0.05 bounds the cost
 * (the h step is 0.7 r). The quadrature grids (entry 6, internal 3) are the defaults the
 * model always had; coarser entry grids are its cheaper neighbours (docs/MODELS.md,
 * "Convergence on an image"). */
static const abrdf_model_param mp_huang[] = {
    {P_ETA, 1.55, 1.0, 4.0}, {P_MELANIN, 0.8, 0.0, 1.0}, {P_REDNESS, 1.0, 0.0, 1.0},
    {P_CUTICLE_TILT, 2.0, -10.0, 10.0}, {P_ASPECT_RATIO, 0.85, 0.01, 1.0},
    {P_R, 0.3, 0.05, 1.0}, {P_ENTRY_GRID, ABRDF__HUANG_N1, 1.0, ABRDF__HUANG_GRID_MAX},
    {P_INTERNAL_GRID, ABRDF__HUANG_N2, 1.0, ABRDF__HUANG_GRID_MAX}};
#define CIT_HUANG "W. Huang, M. B. Hullin, J. Hanika, A microfacet-based hair scattering model, " \
    "Computer Graphics Forum 41(4), 2022"
#define CIT_MERL "W. Matusik, H. Pfister, M. Brand, L. McMillan, A data-driven reflectance " \
    "model, ACM TOG 22(3), 2003; S. Rusinkiewicz, A new change of variables for efficient " \
    "BRDF representation, EGWR 1998"
#define HAIR_NEEDS (ABRDF_NEEDS_TANGENT | ABRDF_NEEDS_INTEGRATION | ABRDF_NEEDS_FRESNEL)

static const abrdf_model_info models_table[ABRDF_MODEL_COUNT] = {
    [ABRDF_LAMBERT] = {ABRDF_LAMBERT, "lambert", "Lambert", "Eq. 1", CIT_LAMBERT,
        0, REC | EC | DIF, -1, PARAMS(mp_kd)},
    [ABRDF_LAMBERT_FRESNEL] = {ABRDF_LAMBERT_FRESNEL, "lambert_fresnel", "Lambert * (1 - F)",
        "Eq. 2", CIT_LAMBERT "; Schlick Fresnel", ABRDF_NEEDS_FRESNEL, REC | EC | DIF, -1,
        PARAMS(mp_kd_f0)},
    [ABRDF_DISNEY_DIFFUSE] = {ABRDF_DISNEY_DIFFUSE, "disney_diffuse", "Disney (Burley) diffuse",
        "Eq. 3", CIT_BURLEY, 0, REC | DIF, -1, PARAMS(mp_kd_r)},
    [ABRDF_OREN_NAYAR] = {ABRDF_OREN_NAYAR, "oren_nayar", "Oren-Nayar (qualitative)",
        "Sec. 2 (named)", CIT_ON, 0, REC | DIF, -1, PARAMS(mp_kd_sigma)},
    [ABRDF_PHONG] = {ABRDF_PHONG, "phong", "Phong", "Sec. 2", CIT_PHONG,
        0, REC | SPE, -1, PARAMS(mp_ks_n)},
    [ABRDF_BLINN_PHONG] = {ABRDF_BLINN_PHONG, "blinn_phong", "Blinn-Phong", "Eq. 4", CIT_BLINN,
        0, REC | SPE, -1, PARAMS(mp_ks_n)},
    [ABRDF_F2] = {ABRDF_F2, "f2", "cosine-power approximation, degree 2", "Table 1", CIT_TABLE1,
        0, REC | SPE, 8, PARAMS(mp_ks_n)},
    [ABRDF_F4] = {ABRDF_F4, "f4", "cosine-power approximation, degree 4", "Table 1", CIT_TABLE1,
        0, REC | SPE, 11, PARAMS(mp_ks_n)},
    [ABRDF_F8] = {ABRDF_F8, "f8", "cosine-power approximation, degree 8", "Table 1", CIT_TABLE1,
        0, REC | SPE, 14, PARAMS(mp_ks_n)},
    [ABRDF_F16] = {ABRDF_F16, "f16", "cosine-power approximation, degree 16", "Table 1",
        CIT_TABLE1, 0, REC | SPE, 17, PARAMS(mp_ks_n)},
    [ABRDF_FS] = {ABRDF_FS, "fs", "Schlick's rational approximation", "Table 1", CIT_SCHLICK,
        0, REC | SPE, 15, PARAMS(mp_ks_n)},
    [ABRDF_FKV] = {ABRDF_FKV, "fkv", "quadratic approximation", "Table 1", CIT_TABLE1,
        0, REC | SPE, 14, PARAMS(mp_ks_n)},
    [ABRDF_FKUB] = {ABRDF_FKUB, "fkub", "cubic approximation (fitted)", "Table 1", CIT_ROMANYUK,
        0, REC | SPE, 17, PARAMS(mp_ks_n)},
    [ABRDF_F_PHE] = {ABRDF_F_PHE, "f_phe", "energy-conserving Phong", "Table 5", CIT_LAFORTUNE,
        0, REC | EC | SPE, -1, PARAMS(mp_ks_n)},
    [ABRDF_F_BE] = {ABRDF_F_BE, "f_be", "energy-conserving Blinn-Phong", "Table 5", CIT_GIESEN,
        0, REC | EC | SPE, -1, PARAMS(mp_ks_n)},
    [ABRDF_F_2E] = {ABRDF_F_2E, "f_2e", "energy-conserving cosine-quadratic", "Table 5",
        CIT_PAPER, 0, REC | EC | SPE, -1, PARAMS(mp_ks_n1)},
    [ABRDF_F_16E] = {ABRDF_F_16E, "f_16e", "energy-conserving cosine-power 16", "Table 5",
        CIT_PAPER, 0, REC | EC | SPE, -1, PARAMS(mp_ks_n)},
    [ABRDF_F_GE] = {ABRDF_F_GE, "f_ge", "Gotanda normalised Blinn-Phong with Fresnel", "Table 5",
        CIT_GOTANDA, ABRDF_NEEDS_FRESNEL, REC | EC | SPE, -1, PARAMS(mp_ks_n_f0)},
    [ABRDF_F_CTPHE] = {ABRDF_F_CTPHE, "f_ctphe", "Cook-Torrance, D = normalised Blinn-Phong, G = 1",
        "Table 5", CIT_CT, ABRDF_NEEDS_FRESNEL, REC | SPE, -1, PARAMS(mp_ks_n_f0)},
    [ABRDF_F_CT2E] = {ABRDF_F_CT2E, "f_ct2e", "Cook-Torrance, D = f_2e lobe, G = 1", "Table 5",
        CIT_CT, ABRDF_NEEDS_FRESNEL, REC | SPE, -1, PARAMS(mp_ks_n1_f0)},
    [ABRDF_F_CT16E] = {ABRDF_F_CT16E, "f_ct16e", "Cook-Torrance, D = f_16e lobe, G = 1",
        "Table 5", CIT_CT, ABRDF_NEEDS_FRESNEL, REC | SPE, -1, PARAMS(mp_ks_n_f0)},
    [ABRDF_COOK_TORRANCE] = {ABRDF_COOK_TORRANCE, "cook_torrance", "Cook-Torrance (Beckmann)",
        "Eq. 5", CIT_CT, ABRDF_NEEDS_FRESNEL, REC | EC | SPE, -1, PARAMS(mp_ks_r_f0)},
    [ABRDF_DISNEY_SPECULAR] = {ABRDF_DISNEY_SPECULAR, "disney_specular",
        "Disney specular (GGX, Smith, Schlick)", "Eqs. 5, 6, 8, 9", CIT_WALTER,
        ABRDF_NEEDS_FRESNEL, REC | EC | SPE, -1, PARAMS(mp_ks_r_f0)},
    [ABRDF_DISNEY_SPECULAR_ANISO] = {ABRDF_DISNEY_SPECULAR_ANISO, "disney_specular_aniso",
        "Disney specular, anisotropic GGX", "Eqs. 5, 7, 8, 9", CIT_WALTER,
        ABRDF_NEEDS_FRESNEL | ABRDF_NEEDS_TANGENT, REC | EC | SPE, -1, PARAMS(mp_aniso)},
    [ABRDF_DISNEY_CLEARCOAT] = {ABRDF_DISNEY_CLEARCOAT, "disney_clearcoat",
        "Disney clearcoat (GTR1)", "Sec. 3 (named)", CIT_BURLEY, ABRDF_NEEDS_FRESNEL,
        REC | EC | SPE, -1, PARAMS(mp_clearcoat)},
    /* hair */
    [ABRDF_MARSCHNER] = {ABRDF_MARSCHNER, "marschner", "Marschner hair (R, TT, TRT)",
        "special surfaces (named)", CIT_MARSCHNER, HAIR_NEEDS, 0, -1, PARAMS(mp_marschner)},
    [ABRDF_HUANG] = {ABRDF_HUANG, "huang", "Huang-Hullin-Hanika microfacet hair (far field)",
        "Eqs. 12-14", CIT_HUANG, HAIR_NEEDS, 0, -1, PARAMS(mp_huang)},
    /* cloth */
    [ABRDF_NEUBELT_PETTINEO] = {ABRDF_NEUBELT_PETTINEO, "neubelt_pettineo",
        "Neubelt-Pettineo cloth (Ashikhmin-Premoze velvet)", "Eq. 10", CIT_NEUBELT,
        ABRDF_NEEDS_FRESNEL, REC | DIF | SPE, -1, PARAMS(mp_neubelt)},
    [ABRDF_KAJIYA_KAY] = {ABRDF_KAJIYA_KAY, "kajiya_kay", "Kajiya-Kay fibre lobes", "Eq. 11",
        CIT_KAJIYA, ABRDF_NEEDS_TANGENT, DIF | SPE, -1, PARAMS(mp_kajiya)},
    /* layered */
    [ABRDF_WEIDLICH_WILKIE] = {ABRDF_WEIDLICH_WILKIE, "weidlich_wilkie",
        "Weidlich-Wilkie layered (GGX interfaces over Lambert)", "Eq. 15", CIT_WW,
        ABRDF_NEEDS_FRESNEL | ABRDF_NEEDS_LAYERS, REC | DIF | SPE, -1, PARAMS(mp_ww)},
    [ABRDF_BELCOUR] = {ABRDF_BELCOUR, "belcour", "Belcour layered (atomic decomposition)",
        "Eq. 16", CIT_BELCOUR, ABRDF_NEEDS_FRESNEL | ABRDF_NEEDS_LAYERS, REC | EC | SPE, -1,
        PARAMS(mp_belcour)},
    /* measured data: reads no parameter, only the caller's table */
    [ABRDF_MEASURED] = {ABRDF_MEASURED, "measured", "measured table (MERL half/difference grid)",
        "measured data (docs/MEASURED.md)", CIT_MERL, ABRDF_NEEDS_TABLE, REC | DIF | SPE, -1, 0,
        NULL},
};
/* clang-format on */

/* ---- lookups ----------------------------------------------------------------------- */

const char *abrdf_version(void) { return ABRDF_VERSION_STRING; }

const char *abrdf_strerror(int status)
{
    switch (status) {
    case ABRDF_OK: return "ok";
    case ABRDF_E_NULL: return "a required argument is NULL";
    case ABRDF_E_MODEL: return "unknown model";
    case ABRDF_E_PARAM: return "unknown parameter";
    case ABRDF_E_RANGE: return "parameter value out of range";
    case ABRDF_E_GEOMETRY: return "degenerate vector (zero length, NaN or Inf)";
    case ABRDF_E_UNUSED: return "parameter not used by this model";
    case ABRDF_E_TABLE: return "data table missing or malformed";
    case ABRDF_E_SIZE:
        return "struct_size is 0 or too small (initialise the struct with its _init function)";
    default: return "unknown status";
    }
}

int abrdf_model_count(void) { return ABRDF_MODEL_COUNT; }

const abrdf_model_info *abrdf_model_get(abrdf_model model)
{
    if ((int)model < 0 || model >= ABRDF_MODEL_COUNT) return NULL;
    const abrdf_model_info *m = &models_table[model];
    return m->name ? m : NULL; /* ids reserved for models not built in have no entry */
}

int abrdf_model_find(const char *name, abrdf_model *out)
{
    if (!name || !out) return ABRDF_E_NULL;
    for (int i = 0; i < ABRDF_MODEL_COUNT; ++i)
        if (models_table[i].name && strcmp(models_table[i].name, name) == 0) {
            *out = (abrdf_model)i;
            return ABRDF_OK;
        }
    return ABRDF_E_MODEL;
}

int abrdf_param_count(void) { return PARAM_COUNT; }

const abrdf_param_info *abrdf_param_get(int param)
{
    return (param >= 0 && param < PARAM_COUNT) ? &params_table[param].info : NULL;
}

int abrdf_param_find(const char *name, int *out)
{
    if (!name || !out) return ABRDF_E_NULL;
    for (int i = 0; i < PARAM_COUNT; ++i)
        if (strcmp(params_table[i].info.name, name) == 0) {
            *out = i;
            return ABRDF_OK;
        }
    return ABRDF_E_PARAM;
}

static int param_components(const abrdf_param_info *pi)
{
    return pi->kind == ABRDF_PARAM_RGB ? 3 : 1;
}

/* ---- struct_size of a parameter block (abrdf.h, STABLE LAYOUTS) ---- */

/* The first published layout (0.2.0) ends with layers[]; later parameters are appended. */
#define PARAMS_SIZE_0_2 (offsetof(abrdf_params, layers) + sizeof(((abrdf_params *)0)->layers))

static int params_size_ok(const abrdf_params *p) { return p->struct_size >= PARAMS_SIZE_0_2; }

/* 1 if parameter `param` lies inside the caller's block. */
static int param_in_block(const abrdf_params *p, int param);

const abrdf_params *abrdf__params_view(abrdf_model model, const abrdf_params *p,
                                       abrdf_params *scratch)
{
    if (!params_size_ok(p)) return NULL;
    if (p->struct_size >= sizeof *p) return p;
    abrdf_params_init_sized(model, scratch, sizeof *scratch); /* defaults of the tail */
    memcpy(scratch, p, p->struct_size);
    scratch->struct_size = sizeof *scratch;
    return scratch;
}

/* Write value v into every component of parameter `param` (no range check). */
static void param_store(abrdf_params *p, int param, const double *v, int count)
{
    const abrdf__param_slot *s = &params_table[param];
    char *base = (char *)p + s->offset;
    if (s->info.kind == ABRDF_PARAM_INT) {
        *(int *)(void *)base = (int)v[0];
        return;
    }
    double *d = (double *)(void *)base;
    for (int c = 0; c < param_components(&s->info); ++c) d[c] = v[count == 3 ? c : 0];
}

int abrdf_param_read(const abrdf_params *p, int param, double values[3])
{
    if (!p || !values) return ABRDF_E_NULL;
    const abrdf_param_info *pi = abrdf_param_get(param);
    if (!pi) return ABRDF_E_PARAM;
    if (!params_size_ok(p) || !param_in_block(p, param)) return ABRDF_E_SIZE;
    const char *base = (const char *)p + params_table[param].offset;
    if (pi->kind == ABRDF_PARAM_INT) {
        values[0] = *(const int *)(const void *)base;
        return 1;
    }
    const double *d = (const double *)(const void *)base;
    int n = param_components(pi);
    for (int c = 0; c < n; ++c) values[c] = d[c];
    return n;
}

static int param_in_block(const abrdf_params *p, int param)
{
    const abrdf__param_slot *s = &params_table[param];
    size_t size = s->info.kind == ABRDF_PARAM_INT
                      ? sizeof(int)
                      : (size_t)param_components(&s->info) * sizeof(double);
    return s->offset + size <= p->struct_size;
}

int abrdf_params_init_sized(abrdf_model model, abrdf_params *p, size_t struct_size)
{
    if (!p) return ABRDF_E_NULL;
    if (struct_size < PARAMS_SIZE_0_2) return ABRDF_E_SIZE;
    abrdf_params d; /* this library's layout, copied into the caller's struct_size bytes */
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    int st = ABRDF_OK;
    for (int i = 0; i < PARAM_COUNT; ++i) param_store(&d, i, &params_table[i].info.def, 1);
    const abrdf_model_info *m = abrdf_model_get(model);
    if (m) {
        for (int i = 0; i < m->param_count; ++i)
            param_store(&d, m->params[i].id, &m->params[i].def, 1);
    } else if (model != ABRDF_MODEL_NONE) {
        st = ABRDF_E_MODEL;
    }
    memset(p, 0, struct_size);
    memcpy(p, &d, struct_size < sizeof d ? struct_size : sizeof d);
    p->struct_size = struct_size;
    return st;
}

int abrdf_param_set(abrdf_params *p, int param, const double *values, int count)
{
    if (!p || !values) return ABRDF_E_NULL;
    const abrdf_param_info *pi = abrdf_param_get(param);
    if (!pi) return ABRDF_E_PARAM;
    if (!params_size_ok(p) || !param_in_block(p, param)) return ABRDF_E_SIZE;
    if (count != 1 && !(count == 3 && pi->kind == ABRDF_PARAM_RGB)) return ABRDF_E_RANGE;
    for (int c = 0; c < count; ++c) {
        if (!(values[c] >= pi->min && values[c] <= pi->max)) return ABRDF_E_RANGE;
        if (pi->kind == ABRDF_PARAM_INT && values[c] != floor(values[c])) return ABRDF_E_RANGE;
    }
    param_store(p, param, values, count);
    return ABRDF_OK;
}

int abrdf_params_check(abrdf_model model, const abrdf_params *p, char *msg, size_t msg_size)
{
    if (msg && msg_size) msg[0] = '\0';
    if (!p) return ABRDF_E_NULL;
    abrdf_params full;
    const abrdf_params *v = abrdf__params_view(model, p, &full);
    if (!v) {
        if (msg && msg_size)
            snprintf(msg, msg_size,
                     "abrdf_params: struct_size %zu is below the %zu bytes of "
                     "the 0.2.0 layout: initialise the block with abrdf_params_init",
                     p->struct_size, (size_t)PARAMS_SIZE_0_2);
        return ABRDF_E_SIZE;
    }
    p = v;
    const abrdf_model_info *m = abrdf_model_get(model);
    if (!m) {
        if (msg && msg_size) snprintf(msg, msg_size, "unknown model id %d", (int)model);
        return ABRDF_E_MODEL;
    }
    if (m->needs & ABRDF_NEEDS_TABLE) {
        if (msg && msg_size)
            snprintf(msg, msg_size,
                     "%s: evaluates a caller's table: prepare it with "
                     "abrdf_prepare_measured",
                     m->name);
        return ABRDF_E_TABLE;
    }
    for (int i = 0; i < m->param_count; ++i) {
        int id = m->params[i].id;
        const abrdf_param_info *pi = abrdf_param_get(id);
        double v[3], lo = m->params[i].min, hi = m->params[i].max;
        int n = abrdf_param_read(p, id, v);
        for (int c = 0; c < n; ++c)
            if (!(v[c] >= lo && v[c] <= hi)) {
                if (msg && msg_size)
                    snprintf(msg, msg_size, "%s: %s = %g is outside [%g, %g]", m->name, pi->name,
                             v[c], lo, hi);
                return ABRDF_E_RANGE;
            }
    }
    return ABRDF_OK;
}
