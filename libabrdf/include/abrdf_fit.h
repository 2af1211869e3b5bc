/* abrdf_fit.h - one reflectance model fitted to another, the image error it predicts, and the
 * selection's error-budget mode built on both.
 *
 * The paper's converters (abrdf.h: n <-> alpha_g, ...) map one model's parameters to
 * another's by a formula; abrdf_fit finds the candidate's parameters that make it closest to
 * a reference over the whole hemisphere, reports how close (the paper's error measures,
 * generalised), and predicts the NMSE the two would show in an image (the paper's Table 8
 * measure). abrdf_select_budget then chooses, for a material, the cheapest candidate whose
 * predicted image error is within a budget given as a Table-8 class or a number, with the
 * photoreal choice of the paper's flowchart (abrdf_select) as the reference.
 * docs/SELECTION.md, "The budget mode", documents the objective, the optimiser, the
 * prediction and their validation on rendered images.
 *
 * A "BRDF" below is what the selection hands out and abrdf_shade evaluates: one or two lobes
 * (diffuse, specular; either may be ABRDF_MODEL_NONE, not both) summed, sharing one
 * abrdf_params block.
 *
 * THE FIT (Lafortune et al. 1997; Ngan, Durand, Matusik, EGSR 2005): minimise over the
 *   candidate's parameters the cosine-weighted squared error
 *       E = sum_j q_j w_j sum_c (f_cand,c - f_ref,c)^2 cos^2(theta_i)
 *   over a deterministic direction set covering the hemisphere (incidence x outgoing
 *   directions, outgoing ones placed around the reference's highlight; with the tangent
 *   azimuth too when a lobe reads the tangent frame), q_j the set's solid-angle weights.
 *   w_j = 1 is the L2 metric; ABRDF_FIT_LOG and ABRDF_FIT_CBRT weight by the first-order
 *   expansion of the log metric of Low et al. (ACM TOG 2012) and of the cube-root metric of
 *   Fores, Ferwerda, Gu (CIC 2012) about the reference, so every metric stays a weighted
 *   least-squares problem. ABRDF_FIT_AUTO fits with each metric and keeps the fit whose
 *   predicted image error is smallest: candidates by BRDF error, the winner by rendered error
 *   (Bieron & Peers, EGSR 2020). Variable projection: the parameters the model is linear in
 *   (kd, ks per channel, and the Fresnel f0 of a Schlick lobe through ks*f0) are solved in
 *   closed form by bounded least squares for every trial of the others (n in log space, r,
 *   sigma, ...), which a coarse scan and golden-section search (one parameter) or bounded
 *   Nelder-Mead (several) explore from the converters' starting points. Every parameter
 *   stays inside the candidate's registry range. Deterministic; bounded work (a closed-form
 *   pair takes a few milliseconds; docs/SELECTION.md, "1. The fit", gives the hair and
 *   layered timings).
 *
 * THE PREDICTION: both BRDFs render a small image without ray tracing and the image NMSE
 *   (the paper's measure, MODELS.md B9) is the prediction. The image is an abrdf_view: by
 *   default an analytic sphere seen by an orthographic camera along view_dir, point-sampled
 *   like a renderer samples it, under the given directional lights (a documented default
 *   set if none); or the caller's own shading terms (abrdf_view_term), e.g. a renderer's
 *   samples of one material in a scene. A highlight narrower than the sampling misses every
 *   sample, as in a render at that rate: the prediction is for images sampled like the view.
 *
 * NO ALLOCATION: the fit, the prediction and the budget selection work in a caller-provided
 *   workspace; abrdf_fit_workspace_size tells its size (a few MiB).
 *
 * STABLE LAYOUTS (the rules of abrdf.h): abrdf_fit_options, abrdf_fit_result, abrdf_view and
 *   abrdf_budget start with struct_size, set by their _init function (a static inline that
 *   passes your sizeof); the library reads and writes only that many bytes. abrdf_light_dir
 *   and abrdf_view_term are frozen.
 *
 * PUBLIC FUNCTIONS
 *   abrdf_view_init, abrdf_view_init_sized                the default view (inline / sized)
 *   abrdf_fit_options_init, abrdf_fit_options_init_sized  default fit options
 *   abrdf_fit_result_init, abrdf_fit_result_init_sized    an empty fit result
 *   abrdf_budget_init, abrdf_budget_init_sized            a budget (default: slight)
 *   abrdf_fit_workspace_size    bytes of workspace abrdf_fit / abrdf_predict_nmse /
 *                               abrdf_select_budget (and the _to forms) need for the given
 *                               options and view
 *   abrdf_fit                   fit a candidate BRDF to a reference BRDF
 *   abrdf_fit_to                the same against a prepared reference (any model, a
 *                               measured table in particular)
 *   abrdf_predict_nmse          predicted image NMSE of a BRDF against a reference
 *   abrdf_predict_nmse_to       the same against a prepared reference
 *   abrdf_fit_metric_name, abrdf_fit_metric_find   metric: id <-> stable name
 *   abrdf_budget_class_find     a Table-8 class name ("none", "slight", "noticeable") -> NMSE
 *   abrdf_budget_candidate      the candidates the budget mode fits for a material, one by one
 *   abrdf_select_budget         the cheapest fitted candidate within an image-error budget
 *   abrdf_costs_builtin         the built-in cost table of every model (ns/eval, measured)
 */
#ifndef ABRDF_FIT_H
#define ABRDF_FIT_H

#include "abrdf_select.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the image the prediction renders ------------------------------------------------- */

/* A directional light of the default sphere view (frozen). */
typedef struct abrdf_light_dir {
    double dir[3]; /* toward the light, world space (normalised by the library), non-zero */
    double e[3];   /* irradiance on a surface facing the light, linear RGB, >= 0 */
} abrdf_light_dir;

/* One light's contribution to one image sample, as a renderer shades it (frozen):
 * sample value += e * max(0, n.wi) * f_r(wi, wo) in the frame (n, t). */
typedef struct abrdf_view_term {
    int sample;   /* image sample it adds to, [0, term count); terms of a sample are adjacent */
    double n[3];  /* unit shading normal */
    double t[3];  /* unit tangent orthogonal to n (read by anisotropic and fibre models) */
    double wi[3]; /* unit direction toward the light */
    double wo[3]; /* unit direction toward the viewer */
    double e[3];  /* irradiance from the light at the point (occlusion, falloff), RGB, >= 0 */
} abrdf_view_term;

/* The image of the prediction: the analytic sphere (term_count 0) or the caller's terms. */
typedef struct abrdf_view {
    size_t struct_size; /* bytes of this struct as the caller compiled it; set by _init */
    double view_dir[3]; /* sphere: toward the orthographic camera, world; (0, 0, 1) */
    double up[3];       /* sphere: its axis; the tangent runs around it (the scene
                                    format's `u` rule), not parallel to view_dir; (0, 1, 0) */
    int light_count;    /* sphere: entries of lights, [0, 64]; 0 = the default set */
    const abrdf_light_dir *lights; /* sphere: the lights (world space) */
    int resolution;                /* sphere: point samples across its diameter (a renderer's
                                    pixels x sqrt(spp)), [0, 1024]; 0 = default (128; 32 when
                                    a lobe integrates numerically) */
    int term_count;                /* > 0: render these terms instead of the sphere */
    const abrdf_view_term *terms;  /* the caller's shading terms */
} abrdf_view;

/* The default sphere: view along +z, axis +y, 128 samples across, the default lights
 * (docs/SELECTION.md, "2. The prediction": the key light of scenes/sphere.scene, from
 * (-1, 1, 1) with irradiance 3, and a fill light from (1, 0.3, 0.5) with irradiance 1). */
ABRDF_API int abrdf_view_init_sized(abrdf_view *v, size_t struct_size);
static inline int abrdf_view_init(abrdf_view *v) { return abrdf_view_init_sized(v, sizeof *v); }

/* ---- the fit -------------------------------------------------------------------------- */

/* Error metric of the fit (abrdf_fit_options.metric); stable names in the comments. */
typedef enum abrdf_fit_metric {
    ABRDF_FIT_L2 = 0,      /* "l2"    cosine-weighted L2 (Ngan et al. 2005) */
    ABRDF_FIT_LOG,         /* "log"   linearised log metric (Low et al. 2012) */
    ABRDF_FIT_CBRT,        /* "cbrt"  linearised cube-root metric (Fores et al. 2012) */
    ABRDF_FIT_AUTO,        /* "auto"  each of the above; the smallest predicted NMSE wins */
    ABRDF_FIT_METRIC_COUNT /* metrics in this header; grows */
} abrdf_fit_metric;

ABRDF_API const char *abrdf_fit_metric_name(abrdf_fit_metric m); /* NULL if unknown */
ABRDF_API int abrdf_fit_metric_find(const char *name, abrdf_fit_metric *out);

typedef struct abrdf_fit_options {
    size_t struct_size;      /* bytes of this struct as the caller compiled it; set by _init */
    abrdf_fit_metric metric; /* default ABRDF_FIT_L2 */
    int resolution;          /* direction-set density, [0, 5]: 1 (coarsest) to 5, each step
                                2-4 times the directions and the time; 0 = default (3) */
    const abrdf_view *view;  /* image of the prediction; NULL = the default sphere */
    int predict;             /* 1 (default): predict the image NMSE; 0: skip (nmse_pred < 0) */
    int keep_shared;         /* 1 (default): a candidate's lobe of the same model as a lobe of
                                the reference keeps the reference's parameters, and so does
                                every parameter it reads; only the other lobe is fitted.
                                0: every parameter is fitted */
} abrdf_fit_options;

ABRDF_API int abrdf_fit_options_init_sized(abrdf_fit_options *o, size_t struct_size);
static inline int abrdf_fit_options_init(abrdf_fit_options *o)
{
    return abrdf_fit_options_init_sized(o, sizeof *o);
}

#define ABRDF_FIT_MESSAGE_MAX 256 /* bytes of abrdf_fit_result.message; frozen */

typedef struct abrdf_fit_result {
    size_t struct_size;      /* bytes of this struct as the caller compiled it; set by _init */
    double rel_l2;           /* sqrt(sum q (f - f_ref)^2 cos^2 / sum q f_ref^2 cos^2), >= 0 */
    double max_rel_pct;      /* max |f - f_ref| / f_ref * 100 over the reference's highlight
                                zone (Table 2's measure; docs/SELECTION.md), >= 0 */
    double max_abs;          /* max |f - f_ref| cos over the set, divided by the largest
                                f_ref cos (Table 3's measure for a lobe of peak 1), >= 0 */
    double nmse_pred;        /* predicted image NMSE against the reference; < 0 = not asked */
    double objective;        /* the minimised E (in the metric used) */
    abrdf_fit_metric metric; /* the metric of the kept fit (AUTO: the winner) */
    int fitted;              /* parameters fitted: linear coefficients + searched ones */
    int evals;               /* objective evaluations made */
    int directions;          /* direction pairs of the set */
    char message[ABRDF_FIT_MESSAGE_MAX]; /* why abrdf_fit failed; empty on success */
    /* appended after 0.2.0 (CHANGELOG): the log and cube-root metrics of the kept fit,
     * computed exactly on the direction set (not linearised), relative as rel_l2 is:
     *   sqrt(sum a (g(f cos) - g(f_ref cos))^2 / sum a g(f_ref cos)^2), a the set's solid-angle
     *   weights times cos(theta_o) (rel_l2's q without its cos^2(theta_i)), g the metric */
    double rel_log;  /* g(y) = log(1 + y) (Low et al. 2012), >= 0; < 0 = not computed */
    double rel_cbrt; /* g(y) = y^(1/3) (Fores et al. 2012), >= 0; < 0 = not computed */
} abrdf_fit_result;

ABRDF_API int abrdf_fit_result_init_sized(abrdf_fit_result *r, size_t struct_size);
static inline int abrdf_fit_result_init(abrdf_fit_result *r)
{
    return abrdf_fit_result_init_sized(r, sizeof *r);
}

/* Bytes of workspace for abrdf_fit, abrdf_predict_nmse and abrdf_select_budget (and their _to
 * forms) with these options (NULL = defaults) and view (NULL = the default sphere); 0 if
 * either is invalid. */
ABRDF_API size_t abrdf_fit_workspace_size(const abrdf_fit_options *opt, const abrdf_view *view);

/* Fit the candidate (cand_diffuse + cand_specular) to the reference (ref_diffuse +
 * ref_specular with ref_params; a measured reference: abrdf_fit_to, below). cand_params
 * (initialised by abrdf_params_init) receives the fitted block: the parameters the candidate
 * reads that the reference also reads start from the reference's values (clamped into the
 * candidate's range), the rest from the candidate's defaults, then the fit sets kd, ks, f0
 * and the searched parameters (docs/SELECTION.md, "1. The fit", lists them per model).
 * work: abrdf_fit_workspace_size(opt, opt->view) bytes, aligned for double. Returns
 * ABRDF_OK, or ABRDF_E_NULL / ABRDF_E_MODEL / ABRDF_E_RANGE / ABRDF_E_SIZE with res->message
 * naming the problem (a candidate with no lobe, invalid reference parameters, a workspace
 * too small), or ABRDF_E_TABLE for a reference lobe that reads a table (ABRDF_MEASURED:
 * prepare it and call abrdf_fit_to). */
ABRDF_API int abrdf_fit(abrdf_model ref_diffuse, abrdf_model ref_specular,
                        const abrdf_params *ref_params, abrdf_model cand_diffuse,
                        abrdf_model cand_specular, abrdf_params *cand_params,
                        const abrdf_fit_options *opt, abrdf_fit_result *res, void *work,
                        size_t work_size);

/* abrdf_fit against a reference given as a prepared object (abrdf_prepare, or
 * abrdf_prepare_measured for a measured table; it must stay valid during the call), evaluated
 * as prepared (the double path) on the same direction set and view. For a closed-form model
 * the result is abrdf_fit's with (ABRDF_MODEL_NONE, that model, its prepared parameters) as
 * the reference. A reference with no parameter block (ABRDF_MEASURED) shares no parameter
 * with any candidate: the candidate starts from its defaults, except a searched roughness r
 * (or exponent n), which starts from the GGX alpha_g abrdf_prepare_measured fitted to the
 * table for its sampler (n through abrdf_alpha_g_to_n); the search scans the whole range
 * anyway (docs/SELECTION.md, "1. The fit"). keep_shared then keeps nothing. A candidate
 * lobe that reads a table (ABRDF_MEASURED) is refused (ABRDF_E_MODEL): it has nothing to fit.
 * Returns abrdf_fit's statuses; ABRDF_E_NULL for a NULL reference, ABRDF_E_MODEL for one
 * that is not prepared. */
ABRDF_API int abrdf_fit_to(const abrdf_prepared *reference, abrdf_model cand_diffuse,
                           abrdf_model cand_specular, abrdf_params *cand_params,
                           const abrdf_fit_options *opt, abrdf_fit_result *res, void *work,
                           size_t work_size);

/* Predicted image NMSE of the BRDF (diffuse + specular, params) against the reference:
 * both render `view` (NULL = the default sphere), NMSE = sum (I - R)^2 / sum R^2 over the
 * image's samples and channels. *nmse is 0 when both images are black, and the reference's
 * energy is then 0. Returns ABRDF_OK or an error (invalid parameters, too small a workspace:
 * abrdf_fit_workspace_size(NULL, view)). */
ABRDF_API int abrdf_predict_nmse(abrdf_model ref_diffuse, abrdf_model ref_specular,
                                 const abrdf_params *ref_params, abrdf_model diffuse,
                                 abrdf_model specular, const abrdf_params *params,
                                 const abrdf_view *view, double *nmse, void *work,
                                 size_t work_size);
/* abrdf_predict_nmse against a prepared reference (abrdf_fit_to says which); the same
 * workspace. ABRDF_E_NULL for a NULL reference, ABRDF_E_MODEL for one not prepared. */
ABRDF_API int abrdf_predict_nmse_to(const abrdf_prepared *reference, abrdf_model diffuse,
                                    abrdf_model specular, const abrdf_params *params,
                                    const abrdf_view *view, double *nmse, void *work,
                                    size_t work_size);

/* ---- the selection within an error budget --------------------------------------------- */

/* The largest NMSE of a Table-8 class: "none" 1e-4, "slight" 2.5e-4, "noticeable" 1e-3
 * (abrdf_select_rules()->nmse_class_max); ABRDF_E_RANGE for any other name. */
ABRDF_API int abrdf_budget_class_find(const char *name, double *max_nmse);

typedef struct abrdf_budget {
    size_t struct_size;      /* bytes of this struct as the caller compiled it; set by _init */
    double max_nmse;         /* a candidate passes if its predicted NMSE < max_nmse,
                                  (0, 1]; default: the class "slight" (2.5e-4) */
    abrdf_fit_metric metric; /* metric of the candidates' fits; default ABRDF_FIT_AUTO */
    int resolution;          /* direction-set density of the fits (abrdf_fit_options) */
    const abrdf_view *view;  /* image of the predictions; NULL = the default sphere */
    /* (added after 0.2.0) The reference as the caller evaluates it, or NULL: a prepared object of
     * the photoreal choice's one model with the photoreal choice's parameters (ABRDF_E_MODEL
     * otherwise, with a message naming the difference), e.g. huang tabulated
     * (abrdf_prepare_huang_table), nearer the converged integral than the per-call
     * quadrature (docs/MODELS.md, "A tabulated huang"). Every candidate is predicted against
     * it, and it is candidate 0 at reference_cost. A choice with the reference's models and
     * parameters is this object: render it as prepared. The coarser quadratures of huang are
     * offered as without it. NULL: the photoreal choice evaluated by abrdf_prepare. */
    const abrdf_prepared *reference;
    double reference_cost; /* cost of one evaluation of `reference`, in the costs' unit;
                              < 0 (the default, -1): unknown, so it cannot win */
} abrdf_budget;

ABRDF_API int abrdf_budget_init_sized(abrdf_budget *b, size_t struct_size);
static inline int abrdf_budget_init(abrdf_budget *b)
{
    return abrdf_budget_init_sized(b, sizeof *b);
}

/* Candidate `index` the budget mode fits for material m: index 0 is the reference (the
 * flowchart's photoreal choice), then every model or pair that can represent m's surface class
 * (docs/SELECTION.md, "3. The selection within a budget"). A lone model comes as
 * (*diffuse = ABRDF_MODEL_NONE, *specular = model).
 * Returns ABRDF_OK, ABRDF_E_RANGE past the last candidate, or an error of abrdf_select for an
 * invalid material. */
ABRDF_API int abrdf_budget_candidate(const abrdf_material *m, int index, abrdf_model *diffuse,
                                     abrdf_model *specular);

/* The error-budget mode of the selection. The reference is the photoreal choice of the
 * paper's flowchart for material m (abrdf_select, goal photoreal, whose trace steps come
 * first). The candidates are every model or diffuse + specular pair that can represent the
 * material's surface class (docs/SELECTION.md, "3. The selection within a budget", lists
 * them; the reference itself is one, with
 * its own parameters and error 0): each is fitted (abrdf_fit) and its image error predicted
 * (abrdf_predict_nmse) against the reference, and its cost read from costs (NULL = the
 * built-in table, abrdf_costs_builtin). The cheapest candidate whose predicted NMSE is
 * below the budget wins, costs within 15 % of that cheapest one counting as equal (of those,
 * the smallest predicted NMSE wins: a calibration cannot tell smaller differences apart,
 * docs/SELECTION.md); costs unknown for a candidate's
 * model exclude it. out receives the choice (goal photoreal, err_nmse the predicted NMSE,
 * err_rel_pct and err_abs the fit's highlight and absolute errors against the reference),
 * params its fitted block. The trace reports, after the flowchart's steps, one
 * ABRDF_STEP_REFERENCE step, one ABRDF_STEP_FIT step per candidate (value = predicted NMSE,
 * threshold = the budget, cost, diffuse and params = the fitted block) and one
 * ABRDF_STEP_BUDGET step that says why the winner won. work: abrdf_fit_workspace_size(NULL,
 * budget->view) bytes. Returns ABRDF_OK, or an error with out->message naming the problem
 * (invalid material or budget, too small a workspace). */
ABRDF_API int abrdf_select_budget(const abrdf_material *m, const abrdf_budget *budget,
                                  const abrdf_costs *costs, abrdf_selection *out,
                                  abrdf_params *params, abrdf_select_trace_fn trace,
                                  void *trace_user, void *work, size_t work_size);

/* The built-in cost table of every model: ns per evaluation on the float batch path as
 * `abrdf calibrate` measured it on the reference machine named in the unit string
 * (docs/SELECTION.md, "3. The selection within a budget"); abrdf calibrate measures the
 * host. */
ABRDF_API int abrdf_costs_builtin(abrdf_costs *out);

#ifdef __cplusplus
}
#endif

#endif /* ABRDF_FIT_H */
