/* abrdf.h - surface reflectance models (BRDFs): the public ABI for evaluation.
 *
 * Reference implementations of every reflectance model of Zavalniuk & Romanyuk, "Adaptive
 * selection of the surface reflectance model for rendering tasks", Sci. Papers of DonNTU,
 * series Informatics, Cybernetics and Computer Engineering, 2(39), 2024, pp. 18-30,
 * DOI 10.31474/1996-1588-2024-2-39-18-30. Formula numbers ("Eq. N") are the paper's;
 * docs/MODELS.md maps them to the code.
 *
 * This header holds what a renderer needs: models, parameters, frames, evaluation and the
 * roughness converters. The paper's selection flowchart (choosing the models for a
 * material), its error analysis and cost model are in abrdf_select.h, which includes this
 * header; this header does not include it.
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
 * STABLE LAYOUTS: what a program compiled against this header can rely on when it runs
 *   with a later libabrdf of the same SOVERSION (CHANGELOG.md lists every change).
 *   - Enum values never change. New models (surfaces, ...) are added just before the
 *     *_COUNT terminator, so a *_COUNT is the count of the header you compiled against:
 *     size your own arrays with it, ask abrdf_model_count() at run time, and never pass a
 *     *_COUNT to the library. "No model" is ABRDF_MODEL_NONE (-1).
 *   - A struct you allocate that can grow starts with `size_t struct_size` (here
 *     abrdf_params, abrdf_sample_result and abrdf_measured; in abrdf_select.h the material, tolerance and
 *     selection). Its _init function is a static inline that passes your sizeof to the
 *     library's _init_sized function, which fills the defaults and sets struct_size. New
 *     fields are only ever appended. The library reads and writes only the first
 *     struct_size bytes; a field beyond them takes its default. struct_size 0 (a block
 *     never initialised) or below the struct's first published layout (0.2.0; the sample
 *     result's and the measured table's first layouts are the ones here) is rejected with ABRDF_E_SIZE; copying an
 *     initialised struct copies struct_size with it.
 *   - A struct the library owns and hands out by pointer (abrdf_model_info,
 *     abrdf_param_info, abrdf_sampler_info; abrdf_select_rules and abrdf_select_step) only
 *     grows at its end:
 *     read the fields your header declares.
 *   - Every other struct (abrdf_layer, abrdf_model_param, abrdf_frame, abrdf_batch,
 *     abrdf_prepared (ABRDF_PREPARED_SIZE opaque bytes); in
 *     abrdf_select.h abrdf_approx_error and abrdf_costs) is frozen: new data would come as
 *     a new struct or function. So is ABRDF_MAX_LAYERS.
 *   No public struct is sized by a count that grows. tests/unit/test_abi.c holds the
 *   layouts to these rules, and test_abi_old_caller.c runs a caller compiled against the
 *   0.2.0 headers (tests/data) with this library and with one grown by a model and a field.
 *
 * PUBLIC FUNCTIONS
 *   abrdf_version            runtime version string ("MAJOR.MINOR.PATCH")
 *   abrdf_strerror           message for a status code
 *   abrdf_model_count        number of model ids in the library (its ABRDF_MODEL_COUNT)
 *   abrdf_model_get          metadata of a model (name, formula, citation, params, needs, cost)
 *   abrdf_model_find         model id from its stable lower-case name
 *   abrdf_param_count        number of parameters known to the library
 *   abrdf_param_get          metadata of a parameter (name, unit, range, default)
 *   abrdf_param_find         parameter id from its name
 *   abrdf_params_init        fill a parameter block with a model's defaults (static inline)
 *   abrdf_params_init_sized  the same for a block of struct_size bytes (what the inline calls)
 *   abrdf_param_set          set one parameter by id (validated)
 *   abrdf_param_read         read one parameter by id
 *   abrdf_params_check       validate a parameter block for a model, with a message
 *   abrdf_frame_make         orthonormal shading frame from a normal and optional tangent
 *   abrdf_eval               double-precision scalar reference: f_r for world directions,
 *                            or local-frame directions with frame = NULL
 *   abrdf_eval_batch         float structure-of-arrays batch evaluation, local frame
 *   abrdf_prepare            validate a model's parameters once and precompute its constants
 *   abrdf_prepared_model     the model of a prepared object (ABRDF_MODEL_NONE if not prepared)
 *   abrdf_prepared_params    the validated parameters a prepared object holds
 *   abrdf_eval_prepared      abrdf_eval of a prepared model (double, scalar)
 *   abrdf_eval_prepared_unit the same for unit local-frame directions: a renderer's
 *                            per-sample call, with nothing to normalise
 *   abrdf_eval_prepared_batch  abrdf_eval_batch of a prepared model (float, structure of arrays)
 *   abrdf_eval_prepared_rows   the same over interleaved (x, y, z) rows in, (r, g, b) rows out
 *   abrdf_eval_prepared_float  one pair on that float path (a renderer's per-sample call)
 *   abrdf_prepared_ggx_float, abrdf_ggx_float_eval (abrdf_inline.h)  disney_specular's lobe
 *                            as an inline function: no call per sample, unit directions
 *   abrdf_measured_init      fill a measured-table descriptor, set its struct_size (static inline)
 *   abrdf_measured_init_sized  the same for a block of struct_size bytes
 *   abrdf_prepare_measured   prepare the `measured` model on a caller's table of measured f_r
 *   abrdf_huang_table_size, abrdf_huang_table_build, abrdf_prepare_huang_table
 *                            huang with its residual lobes tabulated once per material
 *   abrdf_shade              the paper's pixel intensity I = ka Ia + Il cos (f_d + f_s)
 *   abrdf_sample             importance sampling: a direction wi for wo, its pdf and the
 *                            weight f_r cos / pdf (double reference)
 *   abrdf_pdf                the density with which abrdf_sample returns wi
 *   abrdf_sample_prepared    abrdf_sample of a prepared model (no validation per sample)
 *   abrdf_pdf_prepared       abrdf_pdf of a prepared model
 *   abrdf_sample_result_init fill a sample result block, set its struct_size (static inline)
 *   abrdf_sample_result_init_sized  the same for a block of struct_size bytes
 *   abrdf_model_sampler      which sampler a model has (stable name, method, citation)
 *   abrdf_r_to_alpha_g, abrdf_alpha_g_to_r, abrdf_alpha_g_to_n, abrdf_n_to_alpha_g,
 *   abrdf_n_to_pov_roughness, abrdf_pov_roughness_to_n   roughness converters
 */
#ifndef ABRDF_H
#define ABRDF_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define ABRDF_VERSION_MAJOR 0
#define ABRDF_VERSION_MINOR 2
#define ABRDF_VERSION_PATCH 0
#define ABRDF_VERSION_STRING "0.2.0"

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
    ABRDF_E_NULL = -1,     /* a required pointer argument is NULL */
    ABRDF_E_MODEL = -2,    /* unknown model id or name */
    ABRDF_E_PARAM = -3,    /* unknown parameter id or name */
    ABRDF_E_RANGE = -4,    /* parameter value outside its range, or NaN */
    ABRDF_E_GEOMETRY = -5, /* degenerate vector (zero length, NaN, Inf) */
    ABRDF_E_UNUSED = -6,   /* parameter exists but the model does not use it */
    ABRDF_E_TABLE = -7,    /* a data table is missing or malformed */
    ABRDF_E_SIZE = -8      /* a struct's struct_size is 0 or below its 0.2.0 layout (or too
                               small for the parameter asked for): set it with its _init */
} abrdf_status;

ABRDF_API const char *abrdf_version(void);
ABRDF_API const char *abrdf_strerror(int status);

/* ---- models: stable ids and stable lower-case names (shared by C, CLI, OSL, POV-Ray) -- */
typedef enum abrdf_model {
    ABRDF_MODEL_NONE = -1, /* no model: an empty slot (abrdf_shade, a selection) */
    /* diffuse */
    ABRDF_LAMBERT = 0,     /* "lambert"               Eq. 1 */
    ABRDF_LAMBERT_FRESNEL, /* "lambert_fresnel"       Eq. 2 */
    ABRDF_DISNEY_DIFFUSE,  /* "disney_diffuse"        Eq. 3 */
    ABRDF_OREN_NAYAR,      /* "oren_nayar"            (named in the paper) */
    /* empirical specular lobes */
    ABRDF_PHONG,       /* "phong"                 cos(gamma)^n */
    ABRDF_BLINN_PHONG, /* "blinn_phong"           Eq. 4 */
    ABRDF_F2,          /* "f2"                    Table 1 */
    ABRDF_F4,          /* "f4"                    Table 1 */
    ABRDF_F8,          /* "f8"                    Table 1 */
    ABRDF_F16,         /* "f16"                   Table 1 */
    ABRDF_FS,          /* "fs"     Schlick        Table 1 */
    ABRDF_FKV,         /* "fkv"    quadratic      Table 1 */
    ABRDF_FKUB,        /* "fkub"   cubic          Table 1 */
    /* energy-conserving lobes of Table 5 */
    ABRDF_F_PHE,   /* "f_phe"                 Table 5 */
    ABRDF_F_BE,    /* "f_be"                  Table 5 */
    ABRDF_F_2E,    /* "f_2e"                  Table 5 */
    ABRDF_F_16E,   /* "f_16e"                 Table 5 */
    ABRDF_F_GE,    /* "f_ge"   Gotanda        Table 5 */
    ABRDF_F_CTPHE, /* "f_ctphe"               Table 5 */
    ABRDF_F_CT2E,  /* "f_ct2e"                Table 5 */
    ABRDF_F_CT16E, /* "f_ct16e"               Table 5 */
    /* microfacet */
    ABRDF_COOK_TORRANCE,         /* "cook_torrance"         Eq. 5 with Beckmann D */
    ABRDF_DISNEY_SPECULAR,       /* "disney_specular"       Eqs. 5, 6, 8, 9 */
    ABRDF_DISNEY_SPECULAR_ANISO, /* "disney_specular_aniso" Eqs. 5, 7, 8, 9 */
    ABRDF_DISNEY_CLEARCOAT,      /* "disney_clearcoat"      GTR1 clearcoat lobe */
    /* special surfaces */
    ABRDF_NEUBELT_PETTINEO, /* "neubelt_pettineo"      Eq. 10 */
    ABRDF_KAJIYA_KAY,       /* "kajiya_kay"            Eq. 11 */
    ABRDF_MARSCHNER,        /* "marschner"             R/TT/TRT hair */
    ABRDF_HUANG,            /* "huang"                 Eqs. 12-14 */
    ABRDF_WEIDLICH_WILKIE,  /* "weidlich_wilkie"       Eq. 15 */
    ABRDF_BELCOUR,          /* "belcour"               Eq. 16 */
    /* measured data (added after 0.2.0) */
    ABRDF_MEASURED,   /* "measured"              a caller's table (abrdf_prepare_measured) */
    ABRDF_MODEL_COUNT /* ids in this header; grows with every model (never "none") */
} abrdf_model;

/* ---- hair models (marschner, huang) ----
 * The fibre runs along the tangent T (local +x), on a "ribbon" with normal N, as BRDF
 * Explorer evaluates hair over a tangent field. With S the fibre scattering function in
 * pbrt-v4's convention (a lossless fibre has integral S dwi = 1 over the sphere), the
 * models return f_r = S / |N.wi| for wi, wo above the ribbon, 0 otherwise, so that
 * f_r * N.wi = S. Absorption comes from melanin/redness (Cycles' mapping). Hair f_r is not
 * reciprocal; docs/MODELS.md, "Hair models", gives the measured asymmetry. */

/* What a model needs from the caller or the renderer (bit flags of abrdf_model_info.needs). */
#define ABRDF_NEEDS_TANGENT 0x01u     /* uses T and B (anisotropy, fibres) */
#define ABRDF_NEEDS_FRESNEL 0x02u     /* evaluates a Fresnel term */
#define ABRDF_NEEDS_LAYERS 0x04u      /* uses the layer stack */
#define ABRDF_NEEDS_INTEGRATION 0x08u /* numerical integration inside eval (slow) */
#define ABRDF_NEEDS_TABLE                                                                          \
    0x10u /* evaluates a caller's table: abrdf_prepare_measured only
                                         (abrdf_eval, abrdf_prepare: ABRDF_E_TABLE) */

/* Physical properties (bit flags of abrdf_model_info.props). */
#define ABRDF_PROP_RECIPROCAL 0x01u        /* f_r(wi, wo) == f_r(wo, wi) */
#define ABRDF_PROP_ENERGY_CONSERVING 0x02u /* directional albedo <= 1 for unit weights */
#define ABRDF_PROP_DIFFUSE 0x04u           /* a diffuse lobe (uses kd) */
#define ABRDF_PROP_SPECULAR 0x08u          /* a specular lobe (uses ks) */

/* ---- parameters --------------------------------------------------------------------- */
#define ABRDF_MAX_LAYERS 4 /* frozen: part of the 0.2.0 layouts of abrdf_params, abrdf_material */

/* One interface of a layer stack with the medium below it (layered models). */
typedef struct abrdf_layer {
    double eta;        /* relative index of refraction of the interface, [0.25, 4] */
    double kappa;      /* extinction coefficient (conductor if > 0), [0, 10] */
    double r;          /* perceptual roughness of the interface, [0, 1] */
    double sigma_a[3]; /* absorption of the medium below, 1/unit depth, [0, 1e4] */
    double depth;      /* thickness of the medium below, [0, 100] */
} abrdf_layer;

/* One flat parameter block for every model; each model reads only the fields it lists in
 * its metadata. Colours are linear RGB. abrdf_params_init() fills the defaults and sets
 * struct_size; a parameter added by a later release is appended, and a block of an older
 * caller evaluates with that parameter at the model's default (STABLE LAYOUTS above). */
typedef struct abrdf_params {
    size_t struct_size;     /* bytes of this struct as the caller compiled it; set by _init */
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
    int layer_count;        /* number of used entries of layers, [0, ABRDF_MAX_LAYERS] */
    abrdf_layer layers[ABRDF_MAX_LAYERS]; /* top (index 0) to bottom */
    /* appended in 0.3.0 (a 0.2.0 block evaluates with their defaults): */
    int entry_grid;    /* huang: quadrature of the entry microfacet, an n x n midpoint grid of
                          the VNDF square, [1, 32], default 6 */
    int internal_grid; /* huang: the same for TRT's internal reflection, [1, 32], default 3
                          (docs/MODELS.md, "Convergence on an image": image error and
                          work of each grid; smoother fibres, r < 0.3, need denser grids
                          for the same error, "What a converged reference costs") */
} abrdf_params;

typedef enum abrdf_param_kind {
    ABRDF_PARAM_SCALAR = 0, /* one double */
    ABRDF_PARAM_RGB = 1,    /* three doubles */
    ABRDF_PARAM_INT = 2     /* an int stored as a whole number */
} abrdf_param_kind;

typedef struct abrdf_param_info {
    const char *name;      /* stable lower-case name, e.g. "r", "kd", "layer0_eta" */
    const char *help;      /* one-line description with the unit */
    abrdf_param_kind kind; /* scalar, RGB triple or integer */
    double min, max;       /* inclusive range of every component */
    double def;            /* library-wide default of every component */
} abrdf_param_info;

/* One parameter as a model uses it: the parameter id, this model's default and range (the
 * range may be narrower than the parameter's own, e.g. f_2e needs n >= 1). */
typedef struct abrdf_model_param {
    int id;          /* index for abrdf_param_get() */
    double def;      /* this model's default (every component) */
    double min, max; /* this model's inclusive range (every component) */
} abrdf_model_param;

typedef struct abrdf_model_info {
    abrdf_model id;       /* this model's id, [0, abrdf_model_count()) */
    const char *name;     /* stable lower-case name, e.g. "blinn_phong" */
    const char *title;    /* human-readable name */
    const char *equation; /* the paper's formula reference, e.g. "Eq. 4", "Table 1" */
    const char *citation; /* original publication */
    unsigned needs;       /* ABRDF_NEEDS_* */
    unsigned props;       /* ABRDF_PROP_* */
    int paper_cycles;     /* cost in cycles from the paper's Table 4, or -1 if not given */
    int param_count;      /* entries of params, [0, abrdf_param_count()] */
    const abrdf_model_param *params; /* the parameters this model reads */
} abrdf_model_info;

ABRDF_API int abrdf_model_count(void);
ABRDF_API const abrdf_model_info *abrdf_model_get(abrdf_model model); /* NULL if unknown */
ABRDF_API int abrdf_model_find(const char *name, abrdf_model *out);
ABRDF_API int abrdf_param_count(void);
ABRDF_API const abrdf_param_info *abrdf_param_get(int param); /* NULL if unknown */
ABRDF_API int abrdf_param_find(const char *name, int *out);

/* Defaults of `model` (library-wide defaults for fields the model does not use, and for
 * every field with ABRDF_MODEL_NONE) in a block of struct_size bytes; sets
 * params->struct_size. ABRDF_E_MODEL for an unknown model (the block still holds the
 * library-wide defaults); ABRDF_E_SIZE, writing nothing, if struct_size is below the
 * 0.2.0 layout. Call it through abrdf_params_init, which passes sizeof(abrdf_params). */
ABRDF_API int abrdf_params_init_sized(abrdf_model model, abrdf_params *params, size_t struct_size);
static inline int abrdf_params_init(abrdf_model model, abrdf_params *params)
{
    return abrdf_params_init_sized(model, params, sizeof(abrdf_params));
}
/* Set parameter `param` to `values` (1 or 3 values as its kind says); range-checked.
 * ABRDF_E_SIZE if the parameter lies beyond the block's struct_size. */
ABRDF_API int abrdf_param_set(abrdf_params *params, int param, const double *values, int count);
/* Read parameter `param` into values[0..2]; returns the number of components or < 0. */
ABRDF_API int abrdf_param_read(const abrdf_params *params, int param, double values[3]);
/* Validate every parameter `model` uses (and struct_size: ABRDF_E_SIZE). On failure writes
 * a one-line message into msg (if msg != NULL and msg_size > 0) naming the parameter, its
 * value and its range. */
ABRDF_API int abrdf_params_check(abrdf_model model, const abrdf_params *params, char *msg,
                                 size_t msg_size);

/* ---- geometry ----------------------------------------------------------------------- */
typedef struct abrdf_frame {
    double n[3]; /* unit normal N */
    double t[3]; /* unit tangent T, orthogonal to N */
    double b[3]; /* unit bitangent B = N x T */
} abrdf_frame;

/* Orthonormal frame from normal n and optional tangent t (NULL or parallel to n: an
 * arbitrary but deterministic tangent is chosen). Returns ABRDF_E_GEOMETRY for a zero or
 * non-finite normal; the frame is then the identity frame. */
ABRDF_API int abrdf_frame_make(const double n[3], const double t[3], abrdf_frame *frame);

/* ---- evaluation --------------------------------------------------------------------- */
/* Double-precision scalar reference. wi, wo in world space (normalised here; zero or
 * non-finite vectors give f = 0). frame NULL means the local frame (N = +z): wi, wo are
 * then local-frame directions. f receives f_r per RGB channel. Returns ABRDF_OK or an
 * error from abrdf_params_check (f = 0). */
ABRDF_API int abrdf_eval(abrdf_model model, const abrdf_params *params, const abrdf_frame *frame,
                         const double wi[3], const double wo[3], double f[3]);

/* Float structure-of-arrays batch: `count` direction pairs in the local frame, unit
 * length (not renormalised). Output arrays may not alias inputs. */
typedef struct abrdf_batch {
    size_t count;                    /* number of direction pairs */
    const float *wi_x, *wi_y, *wi_z; /* toward the light, local frame, unit length */
    const float *wo_x, *wo_y, *wo_z; /* toward the viewer, local frame, unit length */
    float *f_r, *f_g, *f_b;          /* out: f_r per channel, 1/sr, >= 0 */
} abrdf_batch;

ABRDF_API int abrdf_eval_batch(abrdf_model model, const abrdf_params *params,
                               const abrdf_batch *batch);

/* ---- prepared evaluation ------------------------------------------------------------- *
 * What a renderer does per material, as Cycles' closure setup and pbrt-v4's BxDF built per
 * hit do it: validate the parameters and precompute everything that depends only on them
 * (normalisations, alpha_g, Oren-Nayar's A and B, the fkub cubic, a hair model's absorption
 * and lobe constants) ONCE, then evaluate per direction pair with no check and no setup.
 * abrdf_eval and abrdf_eval_batch are exactly abrdf_prepare followed by these calls, so a
 * prepared evaluation returns the same bits as the unprepared one.
 *
 *   abrdf_prepared mat;
 *   if (abrdf_prepare(ABRDF_DISNEY_SPECULAR, &params, &mat) != ABRDF_OK) ...;  // once
 *   abrdf_eval_prepared(&mat, &frame, wi, wo, f);                             // per sample
 *
 * LIFETIME AND SHARING. abrdf_prepared is plain data of a fixed size, owned by the caller
 * (stack, array, heap) and valid as long as that memory is: it holds a copy of the
 * parameters (the block passed to abrdf_prepare may change or go away afterwards) and no
 * pointer, so a copy (assignment, memcpy) is a prepared object too. The one exception is the
 * `measured` model (abrdf_prepare_measured below), which points at the caller's table. Nothing is allocated
 * and nothing needs releasing. A prepared object is never modified by an evaluation, so
 * any number of threads may evaluate one concurrently. It is valid only for the library
 * that prepared it (the same process); do not store it in files. A block that
 * abrdf_prepare did not fill (or filled after a failure) is "not prepared": evaluating it
 * returns ABRDF_E_MODEL with f = 0. The struct is frozen (STABLE LAYOUTS): a later
 * release keeps ABRDF_PREPARED_SIZE and its alignment. */
#define ABRDF_PREPARED_SIZE 2048 /* frozen: bytes of abrdf_prepared */

typedef struct abrdf_prepared {
    union {
        unsigned char bytes[ABRDF_PREPARED_SIZE]; /* opaque: read through the functions below */
        double align_double;                      /* alignment of the library's layout */
        void *align_pointer;
    } opaque;
} abrdf_prepared;

/* Validate `params` for `model` (as abrdf_params_check, which gives the message) and
 * precompute. On success the object holds the model, a copy of the parameters in this
 * library's layout (fields beyond an older caller's struct_size at the model's defaults) and
 * the constants of both the scalar and the batch path. On failure (ABRDF_E_NULL,
 * ABRDF_E_MODEL, ABRDF_E_SIZE, ABRDF_E_RANGE, ...) *prepared is "not prepared". */
ABRDF_API int abrdf_prepare(abrdf_model model, const abrdf_params *params,
                            abrdf_prepared *prepared);
/* The model prepared, or ABRDF_MODEL_NONE for NULL or a block that is not prepared. */
ABRDF_API abrdf_model abrdf_prepared_model(const abrdf_prepared *prepared);
/* The validated parameters held by the object (this library's layout: read the fields your
 * header declares), or NULL if it is not prepared. Valid as long as the object is. */
ABRDF_API const abrdf_params *abrdf_prepared_params(const abrdf_prepared *prepared);
/* abrdf_eval of the prepared model: world directions with a frame, or local-frame
 * directions with frame = NULL (normalised here; degenerate vectors give f = 0). */
ABRDF_API int abrdf_eval_prepared(const abrdf_prepared *prepared, const abrdf_frame *frame,
                                  const double wi[3], const double wo[3], double f[3]);
/* abrdf_eval_prepared with frame = NULL for directions that are already unit vectors in the
 * local frame (N = +z, T = +x), as a renderer holds them at a shading point: a closed-form
 * model uses them as given when their squared lengths are within 1e-14 of 1 (vectors
 * normalised in double precision), skipping the normalisation that is most of
 * abrdf_eval_prepared's cost; any other vector (one normalised in float, say) and every
 * direction of the hair and layered models is normalised as abrdf_eval_prepared does. So
 * the result is abrdf_eval_prepared's up to rounding (relative differences of a few 1e-16
 * times the model's exponent n where it has one; hair and layered models: bit for bit).
 * Same status codes (ABRDF_E_NULL, ABRDF_E_MODEL with f = 0). Added after 0.2.0
 * (CHANGELOG). */
ABRDF_API int abrdf_eval_prepared_unit(const abrdf_prepared *prepared, const double wi[3],
                                       const double wo[3], double f[3]);
/* abrdf_eval_batch of the prepared model. The loops run the best instruction set this CPU
 * supports (AVX2 + FMA, AVX-512 on x86-64), chosen per call from the CPU alone; results
 * agree with the double path within the batch path's float tolerance (docs/MODELS.md). */
ABRDF_API int abrdf_eval_prepared_batch(const abrdf_prepared *prepared, const abrdf_batch *batch);
/* abrdf_eval_prepared_batch over interleaved rows: wi, wo hold `count` rows (x, y, z) of
 * local-frame directions of any length, f receives `count` rows (r, g, b) of f_r; f may not
 * overlap wi or wo. Each row is made unit first: a row whose squared length (computed in
 * double) is within 1e-6 of 1 (a vector normalised in float: a few roundings off) is used as
 * given, any other is scaled by 1 / sqrt(squared length) in double and rounded to float, and
 * a pair with a zero or non-finite row gets f = 0. The rule gives the same directions at
 * every instruction-set level. The result is abrdf_eval_prepared_batch's, bit for bit, on the
 * directions so made unit, without laying them out as a structure of arrays first: the rows
 * are read by the models' loops themselves, and unit rows cost only a test in those loops;
 * the 256 pairs around a row that is not unit take a general path that costs about 3-4 times
 * as much (docs/BENCHMARKS.md, section 4). Same status codes (ABRDF_E_NULL;
 * ABRDF_E_MODEL with f = 0). Added after 0.2.0 (CHANGELOG); rows of any length since the
 * change listed there. */
ABRDF_API int abrdf_eval_prepared_rows(const abrdf_prepared *prepared, size_t count,
                                       const float *wi, const float *wo, float *f);
/* One pair on the float batch path, for a renderer that shades one sample at a time in float:
 * abrdf_eval_prepared_rows with count 1, bit for bit, without its loops' set-up: the model's
 * float kernel at the instruction set the batch path runs, on local-frame directions made
 * unit by the rows rule (a zero or non-finite one gives f = 0); f may not overlap wi or wo.
 * A measured table and the hair and layered models take their batch path for the pair
 * (abrdf_eval_prepared_unit is their cheaper per-sample call). Same status codes
 * (ABRDF_E_NULL; ABRDF_E_MODEL with f = 0). Added after 0.2.0 (CHANGELOG). */
ABRDF_API int abrdf_eval_prepared_float(const abrdf_prepared *prepared, const float wi[3],
                                        const float wo[3], float f[3]);

/* ---- measured materials (added after 0.2.0) -------------------------------------------- *
 * The `measured` model (ABRDF_MEASURED) evaluates a table of measured f_r that the caller
 * owns, on the isotropic half/difference grid of the MERL database (Rusinkiewicz, EGWR 1998;
 * Matusik et al., SIGGRAPH 2003). Cell (ih, id, ip) holds f_r (1/sr, linear RGB, without the
 * cosine) at
 *   theta_h = (ih / n_theta_h)^2 pi/2,  theta_d = id / n_theta_d pi/2,  phi_d = ip / n_phi_d pi
 * (phi_h = 0; phi_d and phi_d + pi are one cell: reciprocity) in
 *   data[((ih * n_theta_d + id) * n_phi_d + ip) * 3 + channel].
 * A negative, NaN or infinite value means "not measured". Evaluation interpolates trilinearly in
 * (the square-root theta_h index, theta_d, phi_d), periodic in phi_d and held at the last
 * cell beyond the grid's end; a channel's unmeasured corners drop out and the others'
 * weights are renormalised (none measured: 0). The parametrisation makes the model
 * reciprocal, and every path takes the pair in one order, so f(wi, wo) == f(wo, wi) exactly. docs/MEASURED.md states it with its error on analytic tables.
 *
 * LIFETIME. abrdf_prepare_measured does not copy the table: the prepared object points at
 * `data`, which must stay valid and unchanged while the object (or any copy of it) is
 * evaluated or sampled; the descriptor itself may go away. The library never writes the
 * table. Everything else of abrdf_prepared holds (plain data, thread-safe, no allocation).
 * abrdf_eval, abrdf_eval_batch, abrdf_prepare, abrdf_sample and abrdf_pdf have no table to
 * read and return ABRDF_E_TABLE for ABRDF_MEASURED; the prepared forms all work.
 *
 * SAMPLING. abrdf_sample_prepared draws from a cosine lobe and a GGX visible-normal lobe
 * whose roughness and share abrdf_prepare_measured fits to the table (docs/MEASURED.md), with
 * one-sample MIS: the pdf is exact whatever the fit. */
typedef struct abrdf_measured {
    size_t struct_size; /* bytes of this struct as the caller compiled it; set by _init */
    int n_theta_h;      /* cells along theta_h, [2, 1024]; MERL: 90 */
    int n_theta_d;      /* cells along theta_d, [2, 1024]; MERL: 90 */
    int n_phi_d;        /* cells along phi_d over [0, pi), [2, 1024]; MERL: 180 */
    const float *data;  /* 3 * n_theta_h * n_theta_d * n_phi_d values (above), caller-owned */
} abrdf_measured;

/* Sets struct_size and clears the block (ABRDF_E_SIZE, writing nothing, below the first
 * layout). Call it through abrdf_measured_init. */
ABRDF_API int abrdf_measured_init_sized(abrdf_measured *table, size_t struct_size);
static inline int abrdf_measured_init(abrdf_measured *table)
{
    return abrdf_measured_init_sized(table, sizeof(abrdf_measured));
}
/* Prepare ABRDF_MEASURED on `table` (LIFETIME above). ABRDF_E_NULL (table, data or prepared
 * NULL), ABRDF_E_SIZE (struct_size not set by abrdf_measured_init), ABRDF_E_TABLE (a grid
 * size outside [2, 1024], or more than 2^26 cells in all); *prepared is then "not prepared". The prepared object's
 * parameters (abrdf_prepared_params) are the model's defaults: it reads none. */
ABRDF_API int abrdf_prepare_measured(const abrdf_measured *table, abrdf_prepared *prepared);

/* ---- huang tabulated (added after 0.2.0) -------------------------------------------- *
 * huang integrates its fibre by quadrature at every call: thousands of VNDF nodes, about
 * 0.2 ms, and its error on an image is spread over the rule's shifts like noise
 * (docs/MODELS.md, "What a converged reference costs"). For a material that many shading
 * points share, the residual lobes (TT, TRT, TRRT+) can be computed once on a grid of
 * directions, each node with a denser rule than a call affords (the mean of `sets` rotations
 * of the material's own entry and internal grids), and read back by cubic interpolation; R
 * keeps the quadrature. docs/MODELS.md, "A tabulated huang", measures what it costs to build
 * and to evaluate and how near the converged model it is.
 *
 *   int sizes[4] = ABRDF_HUANG_TABLE_SIZES;   // theta nodes, view azimuths, light azimuths, sets
 *   long n; int rows;
 *   abrdf_huang_table_size(&params, sizes, &n, &rows);
 *   double *v = malloc(n * sizeof *v);
 *   abrdf_huang_table_build(&params, sizes, 0, rows, v);     // rows: split them over threads
 *   abrdf_prepare_huang_table(&params, sizes, v, &prepared);  // then evaluate as any huang
 *
 * THE GRID. The fibre runs along T; theta is a direction's angle to the normal plane of the
 * fibre, phi its azimuth about it (0 along N). sizes[0] theta nodes (the view's and the
 * light's, at the centres of equal cells of (-90, 90) degrees), sizes[1] azimuths of the view
 * on [0, 90] degrees (the elliptical section's mirror symmetries give the rest; 1 only for a
 * round fibre, aspect_ratio 1), sizes[2] azimuths of the light relative to the view's
 * (periodic), each node the mean of sizes[3] shift sets (at the view azimuths 0 and 90
 * degrees, the mirror lines, the mean at the light azimuths d and -d). The values are the
 * table's own format, native doubles: a header of 8 (a mark, the format 1, the four sizes,
 * and two 32-bit keys of the material's parameters and of the revision of the library's quadrature
 * and table build), then the nodes. A table is valid only for the parameters and the
 * library it was built by: abrdf_prepare_huang_table compares the header and returns
 * ABRDF_E_TABLE for another material, other sizes, a table kept in a file by a library of
 * another revision, memory with no header, or a value no build gives (NaN, infinite,
 * negative). It
 * cannot tell rows that were never built from built ones: build them all first.
 *
 * LIFETIME as abrdf_prepare_measured: the prepared object points at `values`, which must
 * stay valid and unchanged while it (or a copy) is evaluated or sampled. Every prepared path
 * reads the table (eval, batch, sample weights); abrdf_eval and abrdf_prepare of ABRDF_HUANG
 * keep the quadrature, and so does the POV-Ray port; the OSL port reads the tables that
 * `abrdf export --cycles --hair-table` writes (docs/OSL.md, "huang from a table"). */
/* clang-format off */
#define ABRDF_HUANG_TABLE_SIZES {24, 9, 32, 16} /* the sizes docs/MODELS.md measures */
/* clang-format on */

/* The number of doubles of the table (header included) and its rows (one per view node: the
 * unit abrdf_huang_table_build fills). ABRDF_E_NULL, an error of abrdf_params_check for
 * ABRDF_HUANG, or ABRDF_E_TABLE (sizes out of range: theta nodes [4, 256], view azimuths
 * [2, 256] or 1 for a round fibre, light azimuths [4, 256], sets [1, 64], and at most 2^28
 * values in all). */
ABRDF_API int abrdf_huang_table_size(const abrdf_params *params, const int sizes[4], long *values,
                                     int *rows);
/* Fill rows [row0, row1) of the table (and its header when row0 is 0: rows [0, 0) write the
 * header alone, whose keys, values[6] and values[7], a caller that keeps tables in files can
 * name them by). Calls with
 * disjoint rows may run at once on one table; the rows' values do not depend on how they are
 * split. A row has sizes[0] sizes[2] nodes, each about 22 us per shift set on one core at
 * the default grids (about a minute for the default sizes). A call takes about 128 KiB of
 * stack: on threads of your own, give them at least 256 KiB (musl's default, 128 KiB, is
 * too little; glibc's is 8 MiB). The errors of
 * abrdf_huang_table_size, and ABRDF_E_RANGE for rows outside [0, rows]. */
ABRDF_API int abrdf_huang_table_build(const abrdf_params *params, const int sizes[4], int row0,
                                      int row1, double *values);
/* Prepare ABRDF_HUANG at params with its residual read from the table (LIFETIME above): the
 * errors of abrdf_prepare and abrdf_huang_table_size, ABRDF_E_NULL for values, and
 * ABRDF_E_TABLE if the table's header does not match params, sizes and this library, or a
 * value is not finite and >= 0 (THE GRID). *prepared is then "not prepared". */
ABRDF_API int abrdf_prepare_huang_table(const abrdf_params *params, const int sizes[4],
                                        const double *values, abrdf_prepared *prepared);

/* The paper's pixel intensity (Sec. 1), physically based convention (MODELS.md B1):
 *   I = ka*Ia + Il * max(0, N.wi) * (f_diffuse + f_specular)
 * where the diffuse model carries kd and the specular model carries ks. Either model may
 * be ABRDF_MODEL_NONE to omit that term. ambient = ka*Ia, light = Il (RGB). */
ABRDF_API int abrdf_shade(abrdf_model diffuse, abrdf_model specular, const abrdf_params *params,
                          const abrdf_frame *frame, const double wi[3], const double wo[3],
                          const double light[3], const double ambient[3], double out[3]);

/* ---- roughness converters (their errors: docs/MODELS.md, "Roughness converters") ----- */
ABRDF_API double abrdf_r_to_alpha_g(double r);           /* alpha_g = r^2 */
ABRDF_API double abrdf_alpha_g_to_r(double alpha_g);     /* r = sqrt(alpha_g) */
ABRDF_API double abrdf_alpha_g_to_n(double alpha_g);     /* Blinn-Phong n = 2/alpha_g^2 - 2 */
ABRDF_API double abrdf_n_to_alpha_g(double n);           /* alpha_g = sqrt(2/(n + 2)) */
ABRDF_API double abrdf_n_to_pov_roughness(double n);     /* POV-Ray roughness = 1/n; n = 0 -> 0 */
ABRDF_API double abrdf_pov_roughness_to_n(double rough); /* n = 1/rough; rough = 0 -> 0 */

/* ---- sampling ----------------------------------------------------------------------- *
 * What a path tracer needs beside evaluation (pbrt-v4's Sample_f/PDF, Mitsuba's
 * sample/pdf): for the viewer direction wo, a light direction wi drawn with a density close
 * to f_r(wi, wo) |N.wi|, its density and the weight f_r |N.wi| / pdf. docs/RENDERER.md,
 * "Importance sampling", lists the sampler of every model with its citation
 * (abrdf_model_sampler names it).
 *   - pdf is per unit solid angle (1/sr), over the whole sphere of directions: a sampler
 *     may return wi below the surface (N.wi <= 0), where f_r = 0, so its weight is 0. Such
 *     samples are part of the distribution (count them, do not redraw).
 *   - weight = f_r(wi, wo) max(0, N.wi) / pdf exactly, per channel: for a model with
 *     several lobes one lobe is chosen at random and pdf is the density of the whole
 *     mixture at wi (one-sample MIS), never the chosen lobe's alone.
 *   - Random numbers: u1, u2 in [0, 1]. Where a lobe must be chosen, u1 chooses it and is
 *     reused, rescaled, for the direction (as pbrt-v4 does); no third number is needed.
 *   - wo below or on the surface, or degenerate: no sample, reported as pdf = 0 (wi = N,
 *     weight 0) with ABRDF_OK, as abrdf_eval reports f = 0.
 *   - Deterministic: the same inputs give the same sample. No allocation, thread-safe. */
typedef struct abrdf_sample_result {
    size_t struct_size; /* bytes of this struct as the caller compiled it; set by _init */
    double wi[3];       /* sampled direction toward the light, unit; world frame, or local
                           if frame is NULL */
    double pdf;         /* density of wi, 1/sr, >= 0; 0 = no sample */
    double weight[3];   /* f_r(wi, wo) max(0, N.wi) / pdf per channel, finite, >= 0 */
} abrdf_sample_result;

/* Sets struct_size and clears the block (ABRDF_E_SIZE, writing nothing, below the first
 * layout). Call it once through abrdf_sample_result_init; a block can be reused. */
ABRDF_API int abrdf_sample_result_init_sized(abrdf_sample_result *result, size_t struct_size);
static inline int abrdf_sample_result_init(abrdf_sample_result *result)
{
    return abrdf_sample_result_init_sized(result, sizeof(abrdf_sample_result));
}

/* Sample wi for wo (world, normalised here; frame NULL: local-frame directions as in
 * abrdf_eval). Returns ABRDF_OK, an error of abrdf_params_check, ABRDF_E_NULL,
 * ABRDF_E_SIZE (result not initialised) or ABRDF_E_RANGE (u1 or u2 outside [0, 1] or NaN);
 * on error the result holds no sample. Double precision, the reference of any later
 * batch form. */
ABRDF_API int abrdf_sample(abrdf_model model, const abrdf_params *params, const abrdf_frame *frame,
                           const double wo[3], double u1, double u2, abrdf_sample_result *result);

/* The density (1/sr) with which abrdf_sample returns wi for wo, for the same model,
 * parameters and frame: what MIS needs for a direction another strategy (a light) drew.
 * Degenerate vectors or wo below the surface give 0. Returns ABRDF_OK or an error as
 * abrdf_sample (then *pdf = 0). */
ABRDF_API int abrdf_pdf(abrdf_model model, const abrdf_params *params, const abrdf_frame *frame,
                        const double wi[3], const double wo[3], double *pdf);

/* The same on a prepared model (abrdf_prepare): what a renderer calls per sample, with no
 * validation and no setup beyond the one that depends on wo. abrdf_sample and abrdf_pdf are
 * exactly abrdf_prepare followed by these calls, so the prepared forms return the same bits
 * (tests/unit/test_sample.c). A block that is not prepared: ABRDF_E_MODEL, no sample,
 * *pdf = 0. Thread-safe on a shared prepared object, which they do not modify. */
ABRDF_API int abrdf_sample_prepared(const abrdf_prepared *prepared, const abrdf_frame *frame,
                                    const double wo[3], double u1, double u2,
                                    abrdf_sample_result *result);
ABRDF_API int abrdf_pdf_prepared(const abrdf_prepared *prepared, const abrdf_frame *frame,
                                 const double wi[3], const double wo[3], double *pdf);

/* Which sampler a model has (bit flags of abrdf_sampler_info.flags). */
#define ABRDF_SAMPLER_MIXTURE 0x01u /* several components, one chosen per sample (MIS) */
#define ABRDF_SAMPLER_BELOW 0x02u   /* may return wi below the surface (with weight 0) */

typedef struct abrdf_sampler_info {
    const char *name;     /* stable lower-case name, e.g. "cosine", "ggx_vndf" */
    const char *method;   /* one line: the components and what each draws */
    const char *citation; /* where the sampling method is published */
    unsigned flags;       /* ABRDF_SAMPLER_* */
} abrdf_sampler_info;

/* The sampler of `model`; NULL for an unknown model. Owned by the library. */
ABRDF_API const abrdf_sampler_info *abrdf_model_sampler(abrdf_model model);

#ifdef __cplusplus
}
#endif

#endif /* ABRDF_H */
