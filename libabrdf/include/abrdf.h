/* abrdf.h - adaptive selection of surface reflectance models (BRDFs): the public ABI.
 *
 * Reference implementations of every reflectance model of Zavalniuk & Romanyuk, "Adaptive
 * selection of the surface reflectance model for rendering tasks", Sci. Papers of DonNTU,
 * series Informatics, Cybernetics and Computer Engineering, 2(39), 2024, pp. 18-30,
 * DOI 10.31474/1996-1588-2024-2-39-18-30, plus the paper's selection flowchart.
 * Formula numbers ("Eq. N") are the paper's; docs/MODELS.md maps them to the code.
 *
 * DIRECTION CONVENTION (stated once, used everywhere)
 *   wi  unit vector from the surface point toward the LIGHT      (the paper's L)
 *   wo  unit vector from the surface point toward the VIEWER     (the paper's V)
 *   Both point away from the surface. N is the shading normal, T the tangent (the paper's X),
 *   B = N x T the bitangent (the paper's Y), H = (wi + wo)/|wi + wo|, R = 2(wi.N)N - wi.
 *   A model returns the BRDF f_r(wi, wo) in 1/sr WITHOUT the cosine factor: the radiance
 *   reflected from a point light of irradiance E is f_r * E * max(0, N.wi).
 *   The raw empirical lobes (phong, blinn_phong and the Table-1 approximations) are
 *   unnormalised lobes used as BRDFs, cos^n * ks; the legacy "intensity lobe" convention
 *   differs from this by a factor N.wi (MODELS.md B1).
 *   Local frame: N = +z, T = +x, B = +y. Batch evaluation takes local-frame directions.
 *
 * ROUGHNESS: one convention everywhere. `r` is perceptual roughness (the paper's alpha), the
 *   microfacet roughness is alpha_g = r^2. Converters: abrdf_r_to_alpha_g() and friends.
 *
 * ERRORS: functions return ABRDF_OK (0) or a negative abrdf_status. Invalid parameters are
 *   rejected; degenerate geometry (zero/NaN vectors, back-facing directions) gives f_r = 0.
 *   No evaluation ever returns NaN, Inf or a negative value. No function allocates memory,
 *   and the library has no global mutable state: every function is thread-safe.
 *
 * PUBLIC FUNCTIONS
 *   abrdf_version            runtime version string ("MAJOR.MINOR.PATCH")
 *   abrdf_strerror           message for a status code
 *   abrdf_model_count        number of models in the registry
 *   abrdf_model_get          metadata of a model (name, formula, citation, params, needs, cost)
 *   abrdf_model_find         model id from its stable lower-case name
 *   abrdf_param_count        number of parameters known to the library
 *   abrdf_param_get          metadata of a parameter (name, unit, range, default)
 *   abrdf_param_find         parameter id from its name
 *   abrdf_params_init        fill a parameter block with a model's defaults
 *   abrdf_param_set          set one parameter by id (validated)
 *   abrdf_param_read         read one parameter by id
 *   abrdf_params_check       validate a parameter block for a model, with a message
 *   abrdf_frame_make         orthonormal shading frame from a normal and optional tangent
 *   abrdf_eval               double-precision scalar reference: f_r for world directions
 *   abrdf_eval_local         the same, directions already in the local frame
 *   abrdf_eval_batch         float structure-of-arrays batch evaluation, local frame
 *   abrdf_shade              the paper's pixel intensity I = ka Ia + Il cos (f_d + f_s)
 *   abrdf_approx_error_eval  errors of a Table-1 approximation vs Blinn-Phong (Tables 2-3)
 *   abrdf_costs_paper        the paper's Table 4 cycle counts as a cost model
 *   abrdf_r_to_alpha_g, abrdf_alpha_g_to_r, abrdf_alpha_g_to_n, abrdf_n_to_alpha_g,
 *   abrdf_n_to_pov_roughness, abrdf_pov_roughness_to_n   roughness converters
 *   abrdf_surface_name, abrdf_surface_find, abrdf_goal_name, abrdf_goal_find   selection names
 *   abrdf_material_init      a material with every field unset or at its default
 *   abrdf_select_rules_get   the flowchart's thresholds and model choices (one table)
 *   abrdf_select             the paper's flowchart (Fig. 2): models, parameters, error, cost, trace
 *   abrdf_select_model_name  stable name of any model id, registered in this build or not
 */
#ifndef ABRDF_H
#define ABRDF_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define ABRDF_VERSION_MAJOR 0
#define ABRDF_VERSION_MINOR 1
#define ABRDF_VERSION_PATCH 0
#define ABRDF_VERSION_STRING "0.1.0"

#if defined(_WIN32) && defined(ABRDF_SHARED_BUILD)
#define ABRDF_API __declspec(dllexport)
#elif defined(__GNUC__)
#define ABRDF_API __attribute__((visibility("default")))
#else
#define ABRDF_API
#endif

/* ---- status codes ------------------------------------------------------------------- */
typedef enum abrdf_status {
    ABRDF_OK = 0,
    ABRDF_E_NULL = -1,      /* a required pointer argument is NULL */
    ABRDF_E_MODEL = -2,     /* unknown model id or name */
    ABRDF_E_PARAM = -3,     /* unknown parameter id or name */
    ABRDF_E_RANGE = -4,     /* parameter value outside its range, or NaN */
    ABRDF_E_GEOMETRY = -5,  /* degenerate vector (zero length, NaN, Inf) */
    ABRDF_E_UNUSED = -6,    /* parameter exists but the model does not use it */
    ABRDF_E_TABLE = -7      /* a data table is missing or malformed */
} abrdf_status;

ABRDF_API const char *abrdf_version(void);
ABRDF_API const char *abrdf_strerror(int status);

/* ---- models: stable ids and stable lower-case names (shared by C, CLI, OSL, POV-Ray) -- */
typedef enum abrdf_model {
    /* diffuse */
    ABRDF_LAMBERT = 0,            /* "lambert"               Eq. 1 */
    ABRDF_LAMBERT_FRESNEL,        /* "lambert_fresnel"       Eq. 2 */
    ABRDF_DISNEY_DIFFUSE,         /* "disney_diffuse"        Eq. 3 */
    ABRDF_OREN_NAYAR,             /* "oren_nayar"            (named in the paper) */
    /* empirical specular lobes */
    ABRDF_PHONG,                  /* "phong"                 cos(gamma)^n */
    ABRDF_BLINN_PHONG,            /* "blinn_phong"           Eq. 4 */
    ABRDF_F2,                     /* "f2"                    Table 1 */
    ABRDF_F4,                     /* "f4"                    Table 1 */
    ABRDF_F8,                     /* "f8"                    Table 1 */
    ABRDF_F16,                    /* "f16"                   Table 1 */
    ABRDF_FS,                     /* "fs"     Schlick        Table 1 */
    ABRDF_FKV,                    /* "fkv"    quadratic      Table 1 */
    ABRDF_FKUB,                   /* "fkub"   cubic          Table 1 */
    /* energy-conserving lobes of Table 5 */
    ABRDF_F_PHE,                  /* "f_phe"                 Table 5 */
    ABRDF_F_BE,                   /* "f_be"                  Table 5 */
    ABRDF_F_2E,                   /* "f_2e"                  Table 5 */
    ABRDF_F_16E,                  /* "f_16e"                 Table 5 */
    ABRDF_F_GE,                   /* "f_ge"   Gotanda        Table 5 */
    ABRDF_F_CTPHE,                /* "f_ctphe"               Table 5 */
    ABRDF_F_CT2E,                 /* "f_ct2e"                Table 5 */
    ABRDF_F_CT16E,                /* "f_ct16e"               Table 5 */
    /* microfacet */
    ABRDF_COOK_TORRANCE,          /* "cook_torrance"         Eq. 5 with Beckmann D */
    ABRDF_DISNEY_SPECULAR,        /* "disney_specular"       Eqs. 5, 6, 8, 9 */
    ABRDF_DISNEY_SPECULAR_ANISO,  /* "disney_specular_aniso" Eqs. 5, 7, 8, 9 */
    ABRDF_DISNEY_CLEARCOAT,       /* "disney_clearcoat"      GTR1 clearcoat lobe */
    /* special surfaces */
    ABRDF_NEUBELT_PETTINEO,       /* "neubelt_pettineo"      Eq. 10 */
    ABRDF_KAJIYA_KAY,             /* "kajiya_kay"            Eq. 11 */
    ABRDF_MARSCHNER,              /* "marschner"             R/TT/TRT hair */
    ABRDF_HUANG,                  /* "huang"                 Eqs. 12-14 */
    ABRDF_WEIDLICH_WILKIE,        /* "weidlich_wilkie"       Eq. 15 */
    ABRDF_BELCOUR,                /* "belcour"               Eq. 16 */
    ABRDF_MODEL_COUNT
} abrdf_model;

/* ---- hair models (marschner, huang) ----
 * The fibre runs along the tangent T (local +x), on a "ribbon" with normal N, as BRDF
 * Explorer evaluates hair over a tangent field. With S the fibre scattering function in
 * pbrt-v4's convention (a lossless fibre has integral S dwi = 1 over the sphere), the
 * models return f_r = S / |N.wi| for wi, wo above the ribbon, 0 otherwise, so that
 * f_r * N.wi = S. Absorption comes from melanin/redness (Cycles' mapping). Hair f_r is not
 * reciprocal; docs/SPECIAL_HAIR.md gives the measured asymmetry. */

/* What a model needs from the caller or the renderer (bit flags of abrdf_model_info.needs). */
#define ABRDF_NEEDS_TANGENT     0x01u  /* uses T and B (anisotropy, fibres) */
#define ABRDF_NEEDS_FRESNEL     0x02u  /* evaluates a Fresnel term */
#define ABRDF_NEEDS_LAYERS      0x04u  /* uses the layer stack */
#define ABRDF_NEEDS_INTEGRATION 0x08u  /* numerical integration inside eval (slow) */

/* Physical properties (bit flags of abrdf_model_info.props). */
#define ABRDF_PROP_RECIPROCAL   0x01u  /* f_r(wi, wo) == f_r(wo, wi) */
#define ABRDF_PROP_ENERGY_CONSERVING 0x02u /* directional albedo <= 1 for unit weights */
#define ABRDF_PROP_DIFFUSE      0x04u  /* a diffuse lobe (uses kd) */
#define ABRDF_PROP_SPECULAR     0x08u  /* a specular lobe (uses ks) */

/* ---- parameters --------------------------------------------------------------------- */
#define ABRDF_MAX_LAYERS 4

/* One interface of a layer stack with the medium below it (layered models). */
typedef struct abrdf_layer {
    double eta;        /* relative index of refraction of the interface, [0.25, 4] */
    double kappa;      /* extinction coefficient (conductor if > 0), [0, 10] */
    double r;          /* perceptual roughness of the interface, [0, 1] */
    double sigma_a[3]; /* absorption of the medium below, 1/unit depth, [0, 1e4] */
    double depth;      /* thickness of the medium below, [0, 100] */
} abrdf_layer;

/* One flat parameter block for every model; each model reads only the fields it lists in
 * its metadata. Colours are linear RGB. abrdf_params_init() fills the defaults. */
typedef struct abrdf_params {
    double kd[3];           /* diffuse reflectance (albedo) per channel, [0, 1] */
    double ks[3];           /* specular lobe weight per channel, [0, 1] */
    double f0[3];           /* Fresnel reflectance at normal incidence, [0, 1] */
    double n;               /* Phong / Blinn-Phong exponent (shininess), [0, 1e6] */
    double r;               /* perceptual roughness (the paper's alpha), [0, 1] */
    double anisotropic;     /* Disney anisotropy, [0, 1]; 0 = isotropic */
    double sigma;           /* Oren-Nayar slope deviation in radians, [0, pi/2] */
    double clearcoat_gloss; /* Disney clearcoat gloss, [0, 1] */
    double k_amp;           /* Neubelt-Pettineo inverted-Gaussian amplitude, [0, 100] */
    double eta;             /* index of refraction (hair fibre), [1, 4] */
    double melanin;         /* hair melanin concentration, [0, 1] */
    double redness;         /* hair pheomelanin fraction, [0, 1] */
    double cuticle_tilt;    /* hair cuticle tilt in degrees, [-10, 10] */
    double aspect_ratio;    /* hair cross-section minor/major axis ratio, (0, 1] */
    int    layer_count;     /* number of used entries of layers, [0, ABRDF_MAX_LAYERS] */
    abrdf_layer layers[ABRDF_MAX_LAYERS]; /* top (index 0) to bottom */
} abrdf_params;

typedef enum abrdf_param_kind {
    ABRDF_PARAM_SCALAR = 0,  /* one double */
    ABRDF_PARAM_RGB = 1,     /* three doubles */
    ABRDF_PARAM_INT = 2      /* an int stored as a whole number */
} abrdf_param_kind;

typedef struct abrdf_param_info {
    const char *name;       /* stable lower-case name, e.g. "r", "kd", "layer0_eta" */
    const char *help;       /* one-line description with the unit */
    abrdf_param_kind kind;
    double min, max;        /* inclusive range of every component */
    double def;             /* library-wide default of every component */
} abrdf_param_info;

/* One parameter as a model uses it: the parameter id, this model's default and range (the
 * range may be narrower than the parameter's own, e.g. f_2e needs n >= 1). */
typedef struct abrdf_model_param {
    int id;                 /* index for abrdf_param_get() */
    double def;             /* this model's default (every component) */
    double min, max;        /* this model's inclusive range (every component) */
} abrdf_model_param;

typedef struct abrdf_model_info {
    abrdf_model id;
    const char *name;        /* stable lower-case name, e.g. "blinn_phong" */
    const char *title;       /* human-readable name */
    const char *equation;    /* the paper's formula reference, e.g. "Eq. 4", "Table 1" */
    const char *citation;    /* original publication */
    unsigned needs;          /* ABRDF_NEEDS_* */
    unsigned props;          /* ABRDF_PROP_* */
    int paper_cycles;        /* cost in cycles from the paper's Table 4, or -1 if not given */
    int param_count;
    const abrdf_model_param *params;
} abrdf_model_info;

ABRDF_API int abrdf_model_count(void);
ABRDF_API const abrdf_model_info *abrdf_model_get(abrdf_model model); /* NULL if unknown */
ABRDF_API int abrdf_model_find(const char *name, abrdf_model *out);
ABRDF_API int abrdf_param_count(void);
ABRDF_API const abrdf_param_info *abrdf_param_get(int param);          /* NULL if unknown */
ABRDF_API int abrdf_param_find(const char *name, int *out);

/* Defaults of `model` (library-wide defaults for fields the model does not use). */
ABRDF_API int abrdf_params_init(abrdf_model model, abrdf_params *params);
/* Set parameter `param` to `values` (1 or 3 values as its kind says); range-checked. */
ABRDF_API int abrdf_param_set(abrdf_params *params, int param, const double *values, int count);
/* Read parameter `param` into values[0..2]; returns the number of components or < 0. */
ABRDF_API int abrdf_param_read(const abrdf_params *params, int param, double values[3]);
/* Validate every parameter `model` uses. On failure writes a one-line message into msg
 * (if msg != NULL and msg_size > 0) naming the parameter, its value and its range. */
ABRDF_API int abrdf_params_check(abrdf_model model, const abrdf_params *params,
                                 char *msg, size_t msg_size);

/* ---- geometry ----------------------------------------------------------------------- */
typedef struct abrdf_frame {
    double n[3];  /* unit normal N */
    double t[3];  /* unit tangent T, orthogonal to N */
    double b[3];  /* unit bitangent B = N x T */
} abrdf_frame;

/* Orthonormal frame from normal n and optional tangent t (NULL or parallel to n: an
 * arbitrary but deterministic tangent is chosen). Returns ABRDF_E_GEOMETRY for a zero or
 * non-finite normal; the frame is then the identity frame. */
ABRDF_API int abrdf_frame_make(const double n[3], const double t[3], abrdf_frame *frame);

/* ---- evaluation --------------------------------------------------------------------- */
/* Double-precision scalar reference. wi, wo in world space (normalised here; zero or
 * non-finite vectors give f = 0). frame NULL means the local frame (N = +z). f receives
 * f_r per RGB channel. Returns ABRDF_OK or an error from abrdf_params_check (f = 0). */
ABRDF_API int abrdf_eval(abrdf_model model, const abrdf_params *params,
                         const abrdf_frame *frame, const double wi[3], const double wo[3],
                         double f[3]);
ABRDF_API int abrdf_eval_local(abrdf_model model, const abrdf_params *params,
                               const double wi[3], const double wo[3], double f[3]);

/* Float structure-of-arrays batch: `count` direction pairs in the local frame, unit
 * length (not renormalised). Output arrays may not alias inputs. */
typedef struct abrdf_batch {
    size_t count;
    const float *wi_x, *wi_y, *wi_z;
    const float *wo_x, *wo_y, *wo_z;
    float *f_r, *f_g, *f_b;
} abrdf_batch;

ABRDF_API int abrdf_eval_batch(abrdf_model model, const abrdf_params *params,
                               const abrdf_batch *batch);

/* The paper's pixel intensity (Sec. 1), physically based convention (MODELS.md B1):
 *   I = ka*Ia + Il * max(0, N.wi) * (f_diffuse + f_specular)
 * where the diffuse model carries kd and the specular model carries ks. Either model may
 * be ABRDF_MODEL_COUNT to omit that term. ambient = ka*Ia, light = Il (RGB). */
ABRDF_API int abrdf_shade(abrdf_model diffuse, abrdf_model specular,
                          const abrdf_params *params, const abrdf_frame *frame,
                          const double wi[3], const double wo[3],
                          const double light[3], const double ambient[3], double out[3]);

/* ---- error analysis of the Table-1 approximations (the paper's Tables 2 and 3) ----------- */
/* Maximum relative error (percent) in the highlight zone and maximum absolute error over
 * [0, 1] of approximation `approx` (ABRDF_F2 ... ABRDF_FKUB) against Blinn-Phong cos^n,
 * computed from first principles (docs/TABLES.md defines the highlight zone). */
typedef struct abrdf_approx_error {
    double max_rel_pct;  /* max |f - c^n| / c^n * 100 over the highlight zone */
    double max_abs;      /* max |f - c^n| over c in [0, 1] */
    double zone_cos;     /* the highlight zone is c in [zone_cos, 1] */
} abrdf_approx_error;

ABRDF_API int abrdf_approx_error_eval(abrdf_model approx, double n, abrdf_approx_error *out);

/* ---- cost model (the paper's Table 4, or a calibration measured on the host) ------------- */
typedef struct abrdf_costs {
    double cost[ABRDF_MODEL_COUNT]; /* cost of one evaluation per model; < 0 = unknown */
    const char *unit;               /* "cycles (paper Table 4, AMD Zen 4)" or "ns/eval" */
} abrdf_costs;

/* The paper's Table 4 cycle counts (models the table does not list are < 0). */
ABRDF_API int abrdf_costs_paper(abrdf_costs *out);

/* ---- roughness converters (documented with their error in docs/CONVERTERS.md) -------- */
ABRDF_API double abrdf_r_to_alpha_g(double r);         /* alpha_g = r^2 */
ABRDF_API double abrdf_alpha_g_to_r(double alpha_g);   /* r = sqrt(alpha_g) */
ABRDF_API double abrdf_alpha_g_to_n(double alpha_g);   /* Blinn-Phong n = 2/alpha_g^2 - 2 */
ABRDF_API double abrdf_n_to_alpha_g(double n);         /* alpha_g = sqrt(2/(n + 2)) */
ABRDF_API double abrdf_n_to_pov_roughness(double n);   /* POV-Ray roughness = 1/n; n = 0 -> 0 */
ABRDF_API double abrdf_pov_roughness_to_n(double rough); /* n = 1/rough; rough = 0 -> 0 */

/* ---- adaptive selection: the paper's flowchart (Fig. 2), docs/SELECTION.md ------------ */

/* Surface classes of the flowchart; stable lower-case names as in the comments. */
typedef enum abrdf_surface {
    ABRDF_SURFACE_GENERAL = 0,      /* "general"          metals, dielectrics, plastics, ... */
    ABRDF_SURFACE_CLOTH_ROUGH,      /* "cloth_rough"      wool, cotton, denim */
    ABRDF_SURFACE_CLOTH_SHINY,      /* "cloth_shiny"      silk, satin, velvet */
    ABRDF_SURFACE_HAIR,             /* "hair" */
    ABRDF_SURFACE_LAYERED_PLASTIC,  /* "layered_plastic"  clear coat over a diffuse base */
    ABRDF_SURFACE_LAYERED_PLATE,    /* "layered_plate"    transparent plate over a base */
    ABRDF_SURFACE_LAYERED_METAL,    /* "layered_metal"    coat over a metal */
    ABRDF_SURFACE_COUNT
} abrdf_surface;

typedef enum abrdf_goal {
    ABRDF_GOAL_PERFORMANCE = 0,     /* "performance": hard time/hardware limits */
    ABRDF_GOAL_PHOTOREAL = 1,       /* "photoreal": resources allow microstructure */
    ABRDF_GOAL_COUNT
} abrdf_goal;

ABRDF_API const char *abrdf_surface_name(abrdf_surface s);  /* NULL if unknown */
ABRDF_API int abrdf_surface_find(const char *name, abrdf_surface *out);
ABRDF_API const char *abrdf_goal_name(abrdf_goal g);        /* NULL if unknown */
ABRDF_API int abrdf_goal_find(const char *name, abrdf_goal *out);

/* A material as the flowchart reads it (a row of data/materials.csv, or explicit values).
 * Either n or r may be unset (< 0); abrdf_select derives it from the other. */
typedef struct abrdf_material {
    const char *name;        /* for the trace; may be NULL */
    abrdf_surface type;
    double n;                /* Blinn-Phong exponent, [0, 1e6]; < 0 = derive from r */
    double r;                /* perceptual roughness (the paper's alpha), [0, 1]; < 0 = derive from n */
    double kd[3];            /* diffuse albedo, linear RGB, [0, 1] */
    double ks[3];            /* specular weight, linear RGB, [0, 1] */
    double f0[3];            /* Fresnel reflectance at normal incidence, [0, 1]; used if eta <= 0 */
    double eta;              /* index of refraction of a dielectric or hair fibre, [1, 4];
                                > 0 replaces f0 by ((eta - 1)/(eta + 1))^2; <= 0 = unset */
    double anisotropy;       /* Disney anisotropy, [0, 1] */
    double melanin;          /* hair melanin concentration, [0, 1] */
    double redness;          /* hair pheomelanin fraction, [0, 1] */
    int layer_count;         /* layered types: interfaces top (0) to bottom, [0, ABRDF_MAX_LAYERS] */
    abrdf_layer layers[ABRDF_MAX_LAYERS]; /* eta/kappa relative to the medium above */
} abrdf_material;

/* Tolerances of the performance branch. INFINITY = no limit; negative or NaN is invalid. */
typedef struct abrdf_tolerance {
    double max_rel_pct;      /* max relative error in the highlight zone, percent */
    double max_abs;          /* max absolute error over [0, 1] */
} abrdf_tolerance;

/* Every threshold, constant and model choice of the flowchart, in one table
 * (libabrdf/src/select.c). The OSL and POV-Ray ports are generated from or tested against it. */
#define ABRDF_SELECT_MAX_CANDIDATES 8
#define ABRDF_SELECT_NMSE_ROWS 18
typedef struct abrdf_select_rules {
    double smooth_r_max;          /* r <= this is smooth (the paper: alpha <= 0.03) */
    double aniso_min;             /* anisotropy > this selects the anisotropic lobe */
    double default_max_rel_pct;   /* tolerances when the caller gives none (abrdf's choice) */
    double default_max_abs;
    double n_min, n_max;          /* range of an exponent derived from r (f_2e needs n >= 1) */
    abrdf_model perf_diffuse;     /* performance: Lambert (Eq. 1) */
    abrdf_model perf_fallback;    /* performance, nothing passes: Blinn-Phong (Eq. 4) */
    int candidate_count;          /* Table-1 approximations tried by the performance branch */
    abrdf_model candidates[ABRDF_SELECT_MAX_CANDIDATES];
    abrdf_model rough_diffuse;    /* photoreal, rough: Disney diffuse (Eq. 3) */
    abrdf_model rough_specular;   /* photoreal, rough: Disney specular (Eqs. 5, 6, 8, 9) */
    abrdf_model rough_specular_aniso; /* photoreal, rough, anisotropic (Eq. 7) */
    abrdf_model smooth_diffuse;   /* photoreal, smooth: Lambert * (1 - F) (Eq. 2) */
    abrdf_model smooth_specular;  /* photoreal, smooth: f_2E (Table 5) */
    abrdf_model special[ABRDF_SURFACE_COUNT]; /* photoreal model per surface class;
                                                 ABRDF_MODEL_COUNT for "general" */
    const char *special_reason[ABRDF_SURFACE_COUNT]; /* why, for the trace */
    double nmse_class_max[3];     /* the paper's Table 8: NMSE below [0] no visible difference,
                                     [1] slight, [2] noticeable, else significant; [a, b) */
    int nmse_rows;                /* the paper's Table 6, f_2E column: min NMSE vs the GGX lobe */
    double nmse_alpha_g[ABRDF_SELECT_NMSE_ROWS];
    double nmse_f2e[ABRDF_SELECT_NMSE_ROWS];
} abrdf_select_rules;

ABRDF_API const abrdf_select_rules *abrdf_select_rules_get(void);

/* What a trace step decided (abrdf_select_step.kind). */
typedef enum abrdf_step_kind {
    ABRDF_STEP_INPUT = 0,   /* the material's n and r, given or derived */
    ABRDF_STEP_GOAL,        /* the goal and what it asks for */
    ABRDF_STEP_DIFFUSE,     /* the diffuse model */
    ABRDF_STEP_CANDIDATE,   /* one Table-1 approximation against the tolerances */
    ABRDF_STEP_CHEAPEST,    /* the cheapest candidate that passes */
    ABRDF_STEP_FALLBACK,    /* no candidate passes: Blinn-Phong */
    ABRDF_STEP_SURFACE,     /* the surface class */
    ABRDF_STEP_ROUGHNESS,   /* r against the smooth threshold */
    ABRDF_STEP_ANISOTROPY,  /* anisotropy against its threshold */
    ABRDF_STEP_EXPONENT,    /* the exponent n given to f_2e */
    ABRDF_STEP_SPECIAL,     /* the special-surface model */
    ABRDF_STEP_AVAILABLE,   /* whether the chosen models are built into this library */
    ABRDF_STEP_KIND_COUNT
} abrdf_step_kind;

#define ABRDF_SELECT_MAX_STEPS 24
#define ABRDF_SELECT_TEXT 256

typedef struct abrdf_select_step {
    abrdf_step_kind kind;
    abrdf_model model;       /* the model the step is about; ABRDF_MODEL_COUNT if none */
    double value;            /* the number that decided it (r, relative error %, ...); -1 if none */
    double threshold;        /* what value was compared with; INFINITY = no limit; -1 if none */
    double value2;           /* second criterion (absolute error) or -1 */
    double threshold2;
    double cost;             /* cost of `model` in the cost unit; < 0 = unknown */
    int passed;              /* 1 if the comparison held (or the step chose something) */
    char text[ABRDF_SELECT_TEXT]; /* one human-readable line with the deciding numbers */
} abrdf_select_step;

typedef struct abrdf_selection {
    abrdf_goal goal;
    abrdf_surface type;
    abrdf_model diffuse;     /* ABRDF_MODEL_COUNT: none (the special model has its own) */
    abrdf_model specular;    /* the specular lobe, or the whole special-surface model */
    abrdf_params params;     /* one block for both models (abrdf_shade), filled from the material */
    double n, r;             /* the exponent and roughness used (given or derived) */
    double err_rel_pct;      /* predicted max relative error vs Blinn-Phong, %; < 0 = n/a */
    double err_abs;          /* predicted max absolute error vs Blinn-Phong; < 0 = n/a */
    double err_nmse;         /* smooth branch: the paper's Table 6 NMSE of f_2E; < 0 = n/a */
    double cost_diffuse, cost_specular, cost_total; /* in cost_unit; < 0 = unknown */
    const char *cost_unit;
    int available;           /* 1 if every chosen model is registered in this library build */
    int step_count;
    abrdf_select_step steps[ABRDF_SELECT_MAX_STEPS];
    char message[ABRDF_SELECT_TEXT]; /* why abrdf_select failed, empty on success */
} abrdf_selection;

/* Defaults: general surface, n = r = -1 (unset), kd 0.8, ks 1, f0 0.04, eta unset, no
 * anisotropy, melanin 0.3, redness 0, no layers. */
ABRDF_API void abrdf_material_init(abrdf_material *m);

/* The paper's flowchart. tol NULL = the rules' defaults; costs NULL = the paper's Table 4.
 * Returns ABRDF_OK, or ABRDF_E_RANGE / ABRDF_E_NULL with out->message naming the bad field. */
ABRDF_API int abrdf_select(const abrdf_material *m, abrdf_goal goal, const abrdf_tolerance *tol,
                           const abrdf_costs *costs, abrdf_selection *out);

/* Stable lower-case name of any model id (also ids reserved for models not built into this
 * library, e.g. "huang"); NULL for an invalid id. */
ABRDF_API const char *abrdf_select_model_name(abrdf_model model);

#ifdef __cplusplus
}
#endif

#endif /* ABRDF_H */
