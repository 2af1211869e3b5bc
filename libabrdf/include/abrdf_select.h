/* abrdf_select.h - adaptive selection of the reflectance model: the paper's flowchart
 * (Fig. 2), with the error analysis (Tables 2-3) and the cost model (Table 4) it ranks by.
 *
 * Zavalniuk & Romanyuk 2024 (abrdf.h gives the reference). For a material and a rendering
 * goal (performance or photorealism) abrdf_select chooses the diffuse and specular models,
 * fills their parameters, predicts the error and the cost, and reports every decision with
 * the number behind it. docs/SELECTION.md walks the flowchart.
 *
 * This header includes abrdf.h (models, parameters, evaluation); abrdf.h does not include
 * it, so a renderer that only evaluates sees the small header.
 *
 * STABLE LAYOUTS (the rules of abrdf.h): abrdf_material, abrdf_tolerance and
 * abrdf_selection start with struct_size, set by their _init function (a static inline that
 * passes your sizeof); the library reads and writes only that many bytes. abrdf_select_rules
 * and abrdf_select_step belong to the library and grow only at their end. abrdf_approx_error
 * and abrdf_costs are frozen; a cost table holds ABRDF_COSTS_CAPACITY model ids, read and
 * written through abrdf_costs_get/abrdf_costs_set.
 *
 * PUBLIC FUNCTIONS
 *   abrdf_approx_error_eval     errors of a Table-1 approximation vs Blinn-Phong (Tables 2-3)
 *   abrdf_costs_init            a cost table with every cost unknown, in a given unit
 *   abrdf_costs_set             set the cost of one model
 *   abrdf_costs_get             the cost of one model (< 0 = unknown)
 *   abrdf_costs_paper           the paper's Table 4 cycle counts as a cost table
 *   abrdf_surface_name, abrdf_surface_find   surface class: id <-> stable name
 *   abrdf_goal_name, abrdf_goal_find         goal: id <-> stable name
 *   abrdf_step_name             stable name of a trace step kind ("candidate", ...)
 *   abrdf_material_init         a material with every field unset or at its default (inline)
 *   abrdf_material_init_sized   the same for a struct of struct_size bytes
 *   abrdf_tolerance_init        the flowchart's default tolerances (inline)
 *   abrdf_tolerance_init_sized  the same for a struct of struct_size bytes
 *   abrdf_selection_init        an empty selection result (inline)
 *   abrdf_selection_init_sized  the same for a struct of struct_size bytes
 *   abrdf_select_rules_get      the flowchart's thresholds and model choices (one table)
 *   abrdf_select_table6         one row of the paper's Table 6 (f_2E's NMSE vs the GGX lobe)
 *   abrdf_select                the flowchart: models, parameters, predicted error, cost, trace
 *
 * The selection's error-budget mode (fitted candidates, predicted image error, the cheapest
 * within a Table-8 class) is declared in abrdf_fit.h, which includes this header.
 */
#ifndef ABRDF_SELECT_H
#define ABRDF_SELECT_H

#include "abrdf.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- error analysis of the Table-1 approximations (the paper's Tables 2 and 3) ---------- */
/* Maximum relative error (percent) in the highlight zone and maximum absolute error over
 * [0, 1] of approximation `approx` (ABRDF_F2 ... ABRDF_FKUB) against Blinn-Phong cos^n,
 * computed from first principles (docs/TABLES.md defines the highlight zone). */
typedef struct abrdf_approx_error {
    double max_rel_pct; /* max |f - c^n| / c^n * 100 over the highlight zone, >= 0 */
    double max_abs;     /* max |f - c^n| over c in [0, 1], >= 0 */
    double zone_cos;    /* the highlight zone is c in [zone_cos, 1], [0, 1] */
} abrdf_approx_error;

ABRDF_API int abrdf_approx_error_eval(abrdf_model approx, double n, abrdf_approx_error *out);

/* ---- cost model (the paper's Table 4, or a calibration measured on the host) ------------- */
/* Room for this many model ids; frozen, so adding a model does not change the layout. */
#define ABRDF_COSTS_CAPACITY 128

typedef struct abrdf_costs {
    const char *unit; /* e.g. "cycles (paper Table 4, AMD Zen 4)" or "ns/eval"; not copied */
    double cost[ABRDF_COSTS_CAPACITY]; /* per model id, in unit; < 0 = unknown; use
                                          abrdf_costs_get/abrdf_costs_set */
} abrdf_costs;

/* Every cost unknown (-1), unit as given (the string must outlive the table). */
ABRDF_API int abrdf_costs_init(abrdf_costs *costs, const char *unit);
/* Cost of one evaluation of `model`: >= 0, or < 0 for unknown. ABRDF_E_MODEL for an id
 * outside [0, ABRDF_COSTS_CAPACITY), ABRDF_E_RANGE for NaN or Inf. */
ABRDF_API int abrdf_costs_set(abrdf_costs *costs, abrdf_model model, double cost);
/* The cost of `model`; -1 (unknown) for NULL or an id outside the table. */
ABRDF_API double abrdf_costs_get(const abrdf_costs *costs, abrdf_model model);
/* The paper's Table 4 cycle counts (models the table does not list are < 0). */
ABRDF_API int abrdf_costs_paper(abrdf_costs *out);

/* ---- surfaces and goals ------------------------------------------------------------- */

/* Surface classes of the flowchart; stable lower-case names as in the comments. */
typedef enum abrdf_surface {
    ABRDF_SURFACE_GENERAL = 0,     /* "general"          metals, dielectrics, plastics, ... */
    ABRDF_SURFACE_CLOTH_ROUGH,     /* "cloth_rough"      wool, cotton, denim */
    ABRDF_SURFACE_CLOTH_SHINY,     /* "cloth_shiny"      silk, satin, velvet */
    ABRDF_SURFACE_HAIR,            /* "hair" */
    ABRDF_SURFACE_LAYERED_PLASTIC, /* "layered_plastic"  clear coat over a diffuse base */
    ABRDF_SURFACE_LAYERED_PLATE,   /* "layered_plate"    transparent plate over a base */
    ABRDF_SURFACE_LAYERED_METAL,   /* "layered_metal"    coat over a metal */
    ABRDF_SURFACE_COUNT            /* classes in this header; grows */
} abrdf_surface;

typedef enum abrdf_goal {
    ABRDF_GOAL_PERFORMANCE = 0, /* "performance": hard time/hardware limits */
    ABRDF_GOAL_PHOTOREAL = 1,   /* "photoreal": resources allow microstructure */
    ABRDF_GOAL_COUNT            /* goals in this header; grows */
} abrdf_goal;

ABRDF_API const char *abrdf_surface_name(abrdf_surface s); /* NULL if unknown */
ABRDF_API int abrdf_surface_find(const char *name, abrdf_surface *out);
ABRDF_API const char *abrdf_goal_name(abrdf_goal g); /* NULL if unknown */
ABRDF_API int abrdf_goal_find(const char *name, abrdf_goal *out);

/* ---- inputs: the material and the tolerances ------------------------------------------ */

/* A material as the flowchart reads it (a row of data/materials.csv, or explicit values).
 * Either n or r may be unset (< 0); abrdf_select derives it from the other. */
typedef struct abrdf_material {
    size_t struct_size; /* bytes of this struct as the caller compiled it; set by _init */
    const char *name;   /* for the trace; may be NULL */
    abrdf_surface type; /* surface class, [0, ABRDF_SURFACE_COUNT) */
    double n;           /* Blinn-Phong exponent, [0, 1e6]; < 0 = derive from r */
    double r;           /* perceptual roughness (the paper's alpha), [0, 1]; < 0 = derive from n */
    double kd[3];       /* diffuse albedo, linear RGB, [0, 1] */
    double ks[3];       /* specular weight, linear RGB, [0, 1] */
    double f0[3];       /* Fresnel reflectance at normal incidence, [0, 1]; used if eta <= 0 */
    double eta;         /* index of refraction of a dielectric or hair fibre, [1, 4];
                                > 0 replaces f0 by ((eta - 1)/(eta + 1))^2; <= 0 = unset */
    double anisotropy;  /* Disney anisotropy, [0, 1] */
    double melanin;     /* hair melanin concentration, [0, 1] */
    double redness;     /* hair pheomelanin fraction, [0, 1] */
    int layer_count;    /* layered types: interfaces top (0) to bottom, [0, ABRDF_MAX_LAYERS] */
    abrdf_layer layers[ABRDF_MAX_LAYERS]; /* eta/kappa relative to the medium above */
} abrdf_material;

/* Defaults: general surface, n = r = -1 (unset), kd 0.8, ks 1, f0 0.04, eta unset, no
 * anisotropy, melanin 0.3, redness 0, no layers; sets struct_size. ABRDF_E_SIZE, writing
 * nothing, if struct_size is below the 0.2.0 layout. */
ABRDF_API int abrdf_material_init_sized(abrdf_material *m, size_t struct_size);
static inline int abrdf_material_init(abrdf_material *m)
{
    return abrdf_material_init_sized(m, sizeof(abrdf_material));
}

/* Tolerances of the performance branch. INFINITY = no limit; negative or NaN is invalid. */
typedef struct abrdf_tolerance {
    size_t struct_size; /* bytes of this struct as the caller compiled it; set by _init */
    double max_rel_pct; /* max relative error in the highlight zone, percent, >= 0 */
    double max_abs;     /* max absolute error over [0, 1], >= 0 */
} abrdf_tolerance;

/* The rules' default tolerances (abrdf_select_rules); sets struct_size. */
ABRDF_API int abrdf_tolerance_init_sized(abrdf_tolerance *t, size_t struct_size);
static inline int abrdf_tolerance_init(abrdf_tolerance *t)
{
    return abrdf_tolerance_init_sized(t, sizeof(abrdf_tolerance));
}

/* ---- the flowchart's rules: one table (libabrdf/src/selection/select.c) ---------------- */
/* Every threshold, constant and model choice of the flowchart. The CLI prints it
 * (abrdf advise --rules --json); the OSL and POV-Ray ports are generated from that. */
typedef struct abrdf_select_rules {
    double smooth_r_max;           /* r <= this is smooth (the paper: alpha <= 0.03), [0, 1] */
    double aniso_min;              /* anisotropy > this selects the anisotropic lobe, [0, 1] */
    double default_max_rel_pct;    /* tolerances when the caller gives none (abrdf's choice), % */
    double default_max_abs;        /* the same for the absolute error */
    double n_min, n_max;           /* range of an exponent derived from r (f_2e needs n >= 1) */
    abrdf_model perf_diffuse;      /* performance: Lambert (Eq. 1) */
    abrdf_model perf_fallback;     /* performance, nothing passes: Blinn-Phong (Eq. 4) */
    int candidate_count;           /* entries of candidates */
    const abrdf_model *candidates; /* Table-1 approximations tried by the performance branch */
    abrdf_model rough_diffuse;     /* photoreal, rough: Disney diffuse (Eq. 3) */
    abrdf_model rough_specular;    /* photoreal, rough: Disney specular (Eqs. 5, 6, 8, 9) */
    abrdf_model rough_specular_aniso;  /* photoreal, rough, anisotropic (Eq. 7) */
    abrdf_model smooth_diffuse;        /* photoreal, smooth: Lambert * (1 - F) (Eq. 2) */
    abrdf_model smooth_specular;       /* photoreal, smooth: f_2E (Table 5) */
    int surface_count;                 /* entries of special and special_reason (the library's
                                     ABRDF_SURFACE_COUNT) */
    const abrdf_model *special;        /* photoreal model per surface class; ABRDF_MODEL_NONE for
                                     "general" */
    const char *const *special_reason; /* per surface class: why, for the trace */
    double nmse_class_max[3];          /* the paper's Table 8: NMSE below [0] no visible difference,
                                     [1] slight, [2] noticeable, else significant; [a, b) */
} abrdf_select_rules;

ABRDF_API const abrdf_select_rules *abrdf_select_rules_get(void);

/* Row `row` (0 = roughest) of the paper's Table 6, f_2E column: the minimum NMSE of f_2E
 * against the GGX lobe at microfacet roughness alpha_g, which the smooth branch quotes.
 * ABRDF_E_RANGE past the last row (alpha_g decreases row by row). */
ABRDF_API int abrdf_select_table6(int row, double *alpha_g, double *nmse_f2e);

/* ---- the trace: every decision with the number behind it --------------------------------- */

/* What a trace step decided (abrdf_select_step.kind). */
typedef enum abrdf_step_kind {
    ABRDF_STEP_INPUT = 0,  /* "input"       the material's n and r, given or derived */
    ABRDF_STEP_GOAL,       /* "goal"        the goal and what it asks for */
    ABRDF_STEP_DIFFUSE,    /* "diffuse"     the diffuse model */
    ABRDF_STEP_CANDIDATE,  /* "candidate"   one Table-1 approximation against the tolerances */
    ABRDF_STEP_CHEAPEST,   /* "cheapest"    the cheapest candidate that passes */
    ABRDF_STEP_FALLBACK,   /* "fallback"    no candidate passes: Blinn-Phong */
    ABRDF_STEP_SURFACE,    /* "surface"     the surface class */
    ABRDF_STEP_ROUGHNESS,  /* "roughness"   r against the smooth threshold */
    ABRDF_STEP_ANISOTROPY, /* "anisotropy"  anisotropy against its threshold */
    ABRDF_STEP_EXPONENT,   /* "exponent"    the exponent n given to f_2e */
    ABRDF_STEP_SPECIAL,    /* "special"     the special-surface model */
    ABRDF_STEP_REFERENCE,  /* "reference"   budget mode: the reference (the photoreal choice) */
    ABRDF_STEP_FIT,        /* "fit"         budget mode: one fitted candidate and its error */
    ABRDF_STEP_BUDGET,     /* "budget"      budget mode: the winner and why */
    ABRDF_STEP_KIND_COUNT  /* kinds in this header; grows */
} abrdf_step_kind;

ABRDF_API const char *abrdf_step_name(abrdf_step_kind kind); /* NULL if unknown */

/* One decision, handed to the trace callback (the library's memory, valid during the call). */
typedef struct abrdf_select_step {
    abrdf_step_kind kind; /* what was decided */
    abrdf_model model;    /* the model the step is about; ABRDF_MODEL_NONE if none */
    double value;         /* the number that decided it (r, relative error %, ...); -1 if none */
    double threshold;     /* what value was compared with; INFINITY = no limit; -1 if none */
    double value2;        /* second criterion (absolute error); -1 if none */
    double threshold2;    /* its limit; INFINITY = no limit; -1 if none */
    double cost;          /* cost of `model` in the cost unit; < 0 = unknown */
    int passed;           /* 1 if the comparison held (or the step chose something) */
    const char *text;     /* one human-readable line with the deciding numbers; copy it
                                to keep it */
    /* since 0.3.0 (budget mode, abrdf_fit.h; otherwise ABRDF_MODEL_NONE and NULL): */
    abrdf_model diffuse;        /* the diffuse lobe paired with `model` */
    const abrdf_params *params; /* the fitted parameter block of the pair; copy it to keep it */
} abrdf_select_step;

/* Called once per decision, in order; `user` is abrdf_select's trace_user. */
typedef void (*abrdf_select_trace_fn)(void *user, const abrdf_select_step *step);

/* ---- the result and the flowchart ---------------------------------------------------- */

#define ABRDF_SELECT_MESSAGE_MAX 256 /* bytes of abrdf_selection.message; frozen */

typedef struct abrdf_selection {
    size_t struct_size;    /* bytes of this struct as the caller compiled it; set by _init */
    abrdf_goal goal;       /* the goal asked for */
    abrdf_surface type;    /* the material's surface class */
    abrdf_model diffuse;   /* ABRDF_MODEL_NONE: none (a special model has its own) */
    abrdf_model specular;  /* the specular lobe, or the whole special-surface model */
    double n;              /* Blinn-Phong exponent used (given or derived), [0, 1e6] */
    double r;              /* perceptual roughness used (given or derived), [0, 1] */
    double err_rel_pct;    /* predicted max relative error vs Blinn-Phong (budget mode: vs
                              the reference, abrdf_fit_result.max_rel_pct), %; < 0 = n/a */
    double err_abs;        /* predicted max absolute error vs Blinn-Phong (budget mode: vs
                              the reference, abrdf_fit_result.max_abs); < 0 = n/a */
    double err_nmse;       /* smooth branch: the paper's Table 6 NMSE of f_2E (budget mode:
                              the predicted image NMSE); < 0 = n/a */
    double cost_diffuse;   /* cost of the diffuse model in cost_unit; 0 if none; < 0 = unknown */
    double cost_specular;  /* cost of the specular model in cost_unit; < 0 = unknown */
    double cost_total;     /* their sum; < 0 = unknown */
    const char *cost_unit; /* the cost table's unit string (not a copy) */
    int step_count;        /* decisions made (each reported to the trace callback) */
    char message[ABRDF_SELECT_MESSAGE_MAX]; /* why abrdf_select failed; empty on success */
} abrdf_selection;

/* An empty result (no models, every number n/a); sets struct_size. */
ABRDF_API int abrdf_selection_init_sized(abrdf_selection *s, size_t struct_size);
static inline int abrdf_selection_init(abrdf_selection *s)
{
    return abrdf_selection_init_sized(s, sizeof(abrdf_selection));
}

/* The paper's flowchart (Fig. 2) for material m (initialised by abrdf_material_init) and a
 * goal. tol NULL = the rules' defaults; costs NULL = the paper's Table 4. out (initialised by
 * abrdf_selection_init) receives the choice. params, if not NULL (initialised by
 * abrdf_params_init, any model), receives one block for both chosen models, as abrdf_shade
 * takes it, filled from the material. trace, if not NULL, is called with trace_user once per
 * decision, in order. Returns ABRDF_OK; ABRDF_E_NULL, ABRDF_E_SIZE or ABRDF_E_RANGE with
 * out->message naming the problem (out itself NULL or too small: nothing is written). A cost
 * table holding a NaN or an infinity (written to cost[] directly) is ABRDF_E_RANGE. */
ABRDF_API int abrdf_select(const abrdf_material *m, abrdf_goal goal, const abrdf_tolerance *tol,
                           const abrdf_costs *costs, abrdf_selection *out, abrdf_params *params,
                           abrdf_select_trace_fn trace, void *trace_user);

#ifdef __cplusplus
}
#endif

#endif /* ABRDF_SELECT_H */
