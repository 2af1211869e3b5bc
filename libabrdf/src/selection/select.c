/* select.c - the adaptive selection of Zavalniuk & Romanyuk 2024, Fig. 2 (the flowchart):
 * for a material, a goal (performance or photorealism) and tolerances, choose the diffuse
 * and specular models, fill their parameters, predict the error and cost, and record every
 * decision with the number behind it.
 *
 * Every threshold and model choice lives in `rules` below (abrdf_select_rules_get() hands it
 * to the CLI, the docs and the OSL/POV-Ray ports); the code only walks the flowchart.
 * Errors of the Table-1 approximations come from abrdf_approx_error_eval() (computed, not
 * tabulated); costs from the caller's abrdf_costs or the paper's Table 4.
 *
 * The caller's structs are read and written through their struct_size (abrdf.h, STABLE
 * LAYOUTS): the flowchart works on full-size copies, and only the caller's prefix of each
 * result is copied out. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "abrdf_internal.h"
#include "abrdf_select.h"

/* ---- the flowchart's data: one table ------------------------------------------------- */

static const abrdf_model candidates[] = {ABRDF_F2, ABRDF_F4,  ABRDF_F8,  ABRDF_F16,
                                         ABRDF_FS, ABRDF_FKV, ABRDF_FKUB};

static const abrdf_model special[ABRDF_SURFACE_COUNT] = {
    [ABRDF_SURFACE_GENERAL] = ABRDF_MODEL_NONE,
    [ABRDF_SURFACE_CLOTH_ROUGH] = ABRDF_NEUBELT_PETTINEO,
    [ABRDF_SURFACE_CLOTH_SHINY] = ABRDF_KAJIYA_KAY,
    [ABRDF_SURFACE_HAIR] = ABRDF_HUANG,
    [ABRDF_SURFACE_LAYERED_PLASTIC] = ABRDF_WEIDLICH_WILKIE,
    [ABRDF_SURFACE_LAYERED_PLATE] = ABRDF_BELCOUR,
    [ABRDF_SURFACE_LAYERED_METAL] = ABRDF_BELCOUR,
};

static const char *const special_reason[ABRDF_SURFACE_COUNT] = {
    [ABRDF_SURFACE_GENERAL] = "classified by roughness",
    [ABRDF_SURFACE_CLOTH_ROUGH] = "rough cloth (wool, cotton): inverted-Gaussian velvet "
                                  "distribution with Fresnel (Eq. 10)",
    [ABRDF_SURFACE_CLOTH_SHINY] = "shiny cloth (silk, satin, velvet): highlight around the "
                                  "fibre tangent (Eq. 11)",
    [ABRDF_SURFACE_HAIR] = "microfacet-based R, TT and TRT lobes of an elliptical "
                           "absorbing fibre (Eqs. 12-14)",
    [ABRDF_SURFACE_LAYERED_PLASTIC] = "plastic under a clear coat: refracted base lobe with "
                                      "Fresnel transmission and absorption (Eq. 15)",
    [ABRDF_SURFACE_LAYERED_PLATE] = "transparent plate: adding of layer energies and "
                                    "roughnesses, multiple scattering included (Eq. 16)",
    [ABRDF_SURFACE_LAYERED_METAL] =
        "metal under a coat (Eq. 16); Weidlich-Wilkie (Eq. 15) "
        "is poor for a smooth metal under a rough coat: one refraction, no inter-reflection "
        "between coat and metal",
};

/* Table 6 of the paper, f_2E column: minimum NMSE against the Disney GGX lobe. */
static const double table6_alpha_g[] = {1.0,   0.9,   0.8,    0.7,    0.6,     0.5,
                                        0.4,   0.3,   0.2,    0.1,    0.05,    0.01,
                                        0.005, 0.001, 0.0005, 0.0001, 0.00005, 0.00001};
static const double table6_f2e[] = {0.0517, 0.0596, 0.0577, 0.0555,  0.0558,  0.0548,
                                    0.0472, 0.0465, 0.0445, 0.0322,  0.0190,  0.0031,
                                    0.0015, 0.0003, 0.0001, 0.00003, 0.00001, 0.000002};
#define TABLE6_ROWS ((int)(sizeof table6_f2e / sizeof table6_f2e[0]))
typedef char abrdf__table6_columns_match[sizeof table6_alpha_g == sizeof table6_f2e ? 1 : -1];

static const abrdf_select_rules rules = {
    /* Paper, conclusion and Fig. 2: "alpha <= 0.03 (alpha_g <= 0.001)" is smooth. The
     * comparison is on r itself, inclusive, so r = 0.03 is smooth. */
    .smooth_r_max = 0.03,
    /* Fig. 2 takes Eq. 7 "when the surface is anisotropic": any anisotropy above zero. */
    .aniso_min = 0.0,
    /* The paper leaves the tolerances to the user; these defaults are abrdf's: 2 % keeps
     * the highlight's peak within a just-noticeable step of 8-bit output, 0.05 bounds the
     * worst deviation of the lobe's tail. */
    .default_max_rel_pct = 2.0,
    .default_max_abs = 0.05,
    /* f_2e's normalisation 0.111/n is fitted for n >= 1 (registry range); 1e6 is the
     * parameter's upper bound. An exponent derived from r is clamped into this range. */
    .n_min = 1.0,
    .n_max = 1e6,
    .perf_diffuse = ABRDF_LAMBERT,
    .perf_fallback = ABRDF_BLINN_PHONG,
    .candidate_count = (int)(sizeof candidates / sizeof candidates[0]),
    .candidates = candidates,
    .rough_diffuse = ABRDF_DISNEY_DIFFUSE,
    .rough_specular = ABRDF_DISNEY_SPECULAR,
    .rough_specular_aniso = ABRDF_DISNEY_SPECULAR_ANISO,
    .smooth_diffuse = ABRDF_LAMBERT_FRESNEL,
    .smooth_specular = ABRDF_F_2E,
    .surface_count = ABRDF_SURFACE_COUNT,
    .special = special,
    .special_reason = special_reason,
    /* Table 8 of the paper; boundaries half-open [a, b) (MODELS.md B9). */
    .nmse_class_max = {1e-4, 2.5e-4, 1e-3},
};

const abrdf_select_rules *abrdf_select_rules_get(void) { return &rules; }

int abrdf_select_table6(int row, double *alpha_g, double *nmse_f2e)
{
    if (!alpha_g || !nmse_f2e) return ABRDF_E_NULL;
    if (row < 0 || row >= TABLE6_ROWS) return ABRDF_E_RANGE;
    *alpha_g = table6_alpha_g[row];
    *nmse_f2e = table6_f2e[row];
    return ABRDF_OK;
}

/* ---- names ---------------------------------------------------------------------------- */

static const char *const surface_names[ABRDF_SURFACE_COUNT] = {
    "general",         "cloth_rough",   "cloth_shiny",  "hair",
    "layered_plastic", "layered_plate", "layered_metal"};
static const char *const goal_names[ABRDF_GOAL_COUNT] = {"performance", "photoreal"};
static const char *const step_names[ABRDF_STEP_KIND_COUNT] = {
    "input",     "goal",       "diffuse",  "candidate", "cheapest",  "fallback", "surface",
    "roughness", "anisotropy", "exponent", "special",   "reference", "fit",      "budget"};

const char *abrdf_surface_name(abrdf_surface s)
{
    return ((int)s >= 0 && s < ABRDF_SURFACE_COUNT) ? surface_names[s] : NULL;
}

int abrdf_surface_find(const char *name, abrdf_surface *out)
{
    if (!name || !out) return ABRDF_E_NULL;
    for (int i = 0; i < ABRDF_SURFACE_COUNT; ++i)
        if (!strcmp(name, surface_names[i])) {
            *out = (abrdf_surface)i;
            return ABRDF_OK;
        }
    return ABRDF_E_RANGE;
}

const char *abrdf_goal_name(abrdf_goal g)
{
    return ((int)g >= 0 && g < ABRDF_GOAL_COUNT) ? goal_names[g] : NULL;
}

int abrdf_goal_find(const char *name, abrdf_goal *out)
{
    if (!name || !out) return ABRDF_E_NULL;
    for (int i = 0; i < ABRDF_GOAL_COUNT; ++i)
        if (!strcmp(name, goal_names[i])) {
            *out = (abrdf_goal)i;
            return ABRDF_OK;
        }
    return ABRDF_E_RANGE;
}

const char *abrdf_step_name(abrdf_step_kind kind)
{
    return ((int)kind >= 0 && kind < ABRDF_STEP_KIND_COUNT) ? step_names[kind] : NULL;
}

/* A model's stable name, for the trace (every model the rules name is registered). */
static const char *model_name(abrdf_model model)
{
    const abrdf_model_info *m = abrdf_model_get(model);
    return m ? m->name : "none";
}

/* ---- the caller's structs and their struct_size (abrdf.h, STABLE LAYOUTS) --------------- */

/* End of the last field of a struct's first published layout (0.2.0); later fields are
 * appended after it. */
#define END_OF(type, field) (offsetof(type, field) + sizeof(((type *)0)->field))
#define MATERIAL_SIZE_0_2 END_OF(abrdf_material, layers)
#define TOLERANCE_SIZE_0_2 END_OF(abrdf_tolerance, max_abs)
#define SELECTION_SIZE_0_2 END_OF(abrdf_selection, message)

static size_t min_size(size_t a, size_t b) { return a < b ? a : b; }

/* Copy this library's full struct `full` into the caller's struct of struct_size bytes,
 * which keeps its struct_size. */
static void copy_out(void *dst, const void *full, size_t full_size)
{
    size_t caller = *(const size_t *)dst;
    memcpy((char *)dst + sizeof(size_t), (const char *)full + sizeof(size_t),
           min_size(caller, full_size) - sizeof(size_t));
}

static void material_defaults(abrdf_material *m)
{
    memset(m, 0, sizeof *m);
    m->struct_size = sizeof *m;
    m->type = ABRDF_SURFACE_GENERAL;
    m->n = -1.0;
    m->r = -1.0;
    for (int c = 0; c < 3; ++c) {
        m->kd[c] = 0.8;
        m->ks[c] = 1.0;
        m->f0[c] = 0.04;
    }
    m->eta = -1.0;
    m->melanin = 0.3;
}

static void tolerance_defaults(abrdf_tolerance *t)
{
    memset(t, 0, sizeof *t);
    t->struct_size = sizeof *t;
    t->max_rel_pct = rules.default_max_rel_pct;
    t->max_abs = rules.default_max_abs;
}

static void selection_empty(abrdf_selection *s)
{
    memset(s, 0, sizeof *s);
    s->struct_size = sizeof *s;
    s->diffuse = s->specular = ABRDF_MODEL_NONE;
    s->err_rel_pct = s->err_abs = s->err_nmse = -1.0;
    s->cost_diffuse = s->cost_specular = s->cost_total = -1.0;
}

/* An _init function: this library's defaults in the caller's struct_size bytes (fields of a
 * newer caller beyond this library's layout are zeroed). */
static int init_sized(void *p, size_t struct_size, size_t min, const void *defaults,
                      size_t full_size)
{
    if (!p) return ABRDF_E_NULL;
    if (struct_size < min) return ABRDF_E_SIZE;
    memset(p, 0, struct_size);
    *(size_t *)p = struct_size;
    copy_out(p, defaults, full_size);
    return ABRDF_OK;
}

int abrdf_material_init_sized(abrdf_material *m, size_t struct_size)
{
    abrdf_material d;
    material_defaults(&d);
    return init_sized(m, struct_size, MATERIAL_SIZE_0_2, &d, sizeof d);
}

int abrdf_tolerance_init_sized(abrdf_tolerance *t, size_t struct_size)
{
    abrdf_tolerance d;
    tolerance_defaults(&d);
    return init_sized(t, struct_size, TOLERANCE_SIZE_0_2, &d, sizeof d);
}

int abrdf_selection_init_sized(abrdf_selection *s, size_t struct_size)
{
    abrdf_selection d;
    selection_empty(&d);
    return init_sized(s, struct_size, SELECTION_SIZE_0_2, &d, sizeof d);
}

/* The caller's input in this library's layout: its struct_size bytes over the defaults.
 * 0 if struct_size is below the 0.2.0 layout. */
static int read_in(void *full, size_t full_size, const void *src, size_t min)
{
    size_t caller = *(const size_t *)src;
    if (caller < min) return 0;
    memcpy((char *)full + sizeof(size_t), (const char *)src + sizeof(size_t),
           min_size(caller, full_size) - sizeof(size_t));
    return 1;
}

/* ---- helpers -------------------------------------------------------------------------- */

static int in_range(double v, double lo, double hi) { return v >= lo && v <= hi; } /* NaN: 0 */

int abrdf__selection_fail(abrdf_selection *out, int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out->message, sizeof out->message, fmt, ap);
    va_end(ap);
    return status;
}

/* The flowchart's working state: the result in this library's layout, and the caller's
 * trace callback. */
typedef struct walk {
    abrdf_selection sel;
    abrdf_select_trace_fn trace;
    void *user;
} walk;

/* A trace step's numbers; value2, threshold2 and cost start as -1 (none). */
static abrdf_select_step step(abrdf_step_kind kind, abrdf_model model, double value,
                              double threshold, int passed)
{
    abrdf_select_step s = {kind, model,  value, threshold,        -1.0, -1.0,
                           -1.0, passed, NULL,  ABRDF_MODEL_NONE, NULL};
    return s;
}

/* A trace line: the longest the flowchart writes is under 200 characters. */
#define TEXT_MAX 256

/* Count one decision and hand it, with its text, to the caller's trace. */
static void add_step(walk *w, abrdf_select_step s, const char *fmt, ...)
{
    char text[TEXT_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    s.text = text;
    ++w->sel.step_count;
    if (w->trace) w->trace(w->user, &s);
}

/* A limit for the trace: "2%", "0.05", or "no limit". */
static const char *limit_text(double v, const char *suffix, char *buf, size_t size)
{
    if (isinf(v))
        snprintf(buf, size, "no limit");
    else
        snprintf(buf, size, "%g%s", v, suffix);
    return buf;
}

/* "cycles" from "cycles (paper Table 4, AMD Zen 4)": the unit's first word. */
static void short_unit(const char *unit, char *buf, size_t size)
{
    size_t n = 0;
    if (!unit || !*unit) unit = "units";
    while (unit[n] && unit[n] != ' ' && n + 1 < size) {
        buf[n] = unit[n];
        ++n;
    }
    buf[n] = '\0';
}

/* Errors below this are rounding noise of an exact match (f_m at n = m): shown as 0. */
#define TIDY_ERR 1e-9
static double tidy(double e) { return fabs(e) < TIDY_ERR ? 0.0 : e; }

/* "rel 1.58% <= 2%, abs 0.0344 <= 0.05"; a criterion without limit shows only the value. */
static void criteria_text(const abrdf_approx_error *e, const abrdf_tolerance *t, char *buf,
                          size_t size)
{
    char rel[48], ab[48];
    double r = tidy(e->max_rel_pct), a = tidy(e->max_abs);
    if (isinf(t->max_rel_pct))
        snprintf(rel, sizeof rel, "rel %.3g%%", r);
    else
        snprintf(rel, sizeof rel, "rel %.3g%% %s %g%%", r,
                 e->max_rel_pct <= t->max_rel_pct ? "<=" : ">", t->max_rel_pct);
    if (isinf(t->max_abs))
        snprintf(ab, sizeof ab, "abs %.3g", a);
    else
        snprintf(ab, sizeof ab, "abs %.3g %s %g", a, e->max_abs <= t->max_abs ? "<=" : ">",
                 t->max_abs);
    snprintf(buf, size, "%s, %s", rel, ab);
}

static void cost_text(double cost, const char *unit, char *buf, size_t size)
{
    if (cost >= 0.0)
        snprintf(buf, size, "%g %s", cost, unit);
    else
        snprintf(buf, size, "cost unknown");
}

static const char *nmse_class(double nmse)
{
    if (nmse < rules.nmse_class_max[0]) return "no visible difference";
    if (nmse < rules.nmse_class_max[1]) return "slight difference";
    if (nmse < rules.nmse_class_max[2]) return "noticeable difference";
    return "significant difference";
}

/* Table 6 row nearest to alpha_g on a log scale. */
static int nmse_row(double alpha_g)
{
    double a = fmax(alpha_g, 1e-12), best = INFINITY;
    int row = 0;
    for (int i = 0; i < TABLE6_ROWS; ++i) {
        double d = fabs(log(a / table6_alpha_g[i]));
        if (d < best) {
            best = d;
            row = i;
        }
    }
    return row;
}

static double clampd(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }

/* ---- input validation ----------------------------------------------------------------- */

static int check_material(const abrdf_material *m, abrdf_selection *out)
{
    if (!in_range((double)m->type, 0, ABRDF_SURFACE_COUNT - 1))
        return abrdf__selection_fail(out, ABRDF_E_RANGE, "unknown surface type %d", (int)m->type);
    if (!(m->n < 0.0) && !in_range(m->n, 0.0, 1e6))
        return abrdf__selection_fail(out, ABRDF_E_RANGE,
                                     "n = %g is outside [0, 1e6] (negative = derive from r)", m->n);
    if (!(m->r < 0.0) && !in_range(m->r, 0.0, 1.0))
        return abrdf__selection_fail(out, ABRDF_E_RANGE,
                                     "r = %g is outside [0, 1] (negative = derive from n)", m->r);
    if (m->n < 0.0 && m->r < 0.0)
        return abrdf__selection_fail(out, ABRDF_E_RANGE, "neither n nor r is given");
    static const char *const rgb_names[3] = {"kd", "ks", "f0"};
    const double *rgb[3] = {m->kd, m->ks, m->f0};
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c)
            if (!in_range(rgb[k][c], 0.0, 1.0))
                return abrdf__selection_fail(out, ABRDF_E_RANGE, "%s[%d] = %g is outside [0, 1]",
                                             rgb_names[k], c, rgb[k][c]);
    if (!(m->eta <= 0.0) && !in_range(m->eta, 1.0, 4.0))
        return abrdf__selection_fail(out, ABRDF_E_RANGE,
                                     "eta = %g is outside [1, 4] (<= 0 = use f0)", m->eta);
    if (!in_range(m->anisotropy, 0.0, 1.0))
        return abrdf__selection_fail(out, ABRDF_E_RANGE, "anisotropy = %g is outside [0, 1]",
                                     m->anisotropy);
    if (!in_range(m->melanin, 0.0, 1.0) || !in_range(m->redness, 0.0, 1.0))
        return abrdf__selection_fail(out, ABRDF_E_RANGE,
                                     "melanin = %g or redness = %g is outside [0, 1]", m->melanin,
                                     m->redness);
    if (!in_range(m->layer_count, 0, ABRDF_MAX_LAYERS))
        return abrdf__selection_fail(out, ABRDF_E_RANGE, "layer_count = %d is outside [0, %d]",
                                     m->layer_count, ABRDF_MAX_LAYERS);
    for (int i = 0; i < m->layer_count; ++i) {
        const abrdf_layer *l = &m->layers[i];
        int ok = in_range(l->eta, 1.0, 4.0) && in_range(l->kappa, 0.0, 10.0) &&
                 in_range(l->r, 0.0, 1.0) && in_range(l->depth, 0.0, 100.0);
        for (int c = 0; c < 3; ++c) ok = ok && in_range(l->sigma_a[c], 0.0, 1e4);
        if (!ok)
            return abrdf__selection_fail(
                out, ABRDF_E_RANGE,
                "layer %d is outside the layer parameter ranges "
                "(eta [1, 4], kappa [0, 10], r [0, 1], sigma_a [0, 1e4], depth [0, 100])",
                i);
    }
    return ABRDF_OK;
}

static int check_tolerance(const abrdf_tolerance *t, abrdf_selection *out)
{
    if (!(t->max_rel_pct >= 0.0))
        return abrdf__selection_fail(out, ABRDF_E_RANGE,
                                     "max relative error %g is not >= 0 (INFINITY = no limit)",
                                     t->max_rel_pct);
    if (!(t->max_abs >= 0.0))
        return abrdf__selection_fail(out, ABRDF_E_RANGE,
                                     "max absolute error %g is not >= 0 (INFINITY = no limit)",
                                     t->max_abs);
    return ABRDF_OK;
}

/* ---- parameters of the chosen models -------------------------------------------------- */

static void fill_params(const abrdf_material *m, abrdf_model spec, double n, double r,
                        abrdf_params *p)
{
    abrdf_params_init(spec, p); /* library defaults even for a model not built in */
    for (int c = 0; c < 3; ++c) {
        p->kd[c] = m->kd[c];
        p->ks[c] = m->ks[c];
        p->f0[c] = m->f0[c];
    }
    if (m->eta > 0.0) {
        double f = (m->eta - 1.0) / (m->eta + 1.0); /* Schlick 1994: F0 of a dielectric */
        p->f0[0] = p->f0[1] = p->f0[2] = f * f;
        p->eta = m->eta;
    }
    p->n = n;
    p->r = r;
    p->anisotropic = m->anisotropy;
    p->melanin = m->melanin;
    p->redness = m->redness;
    if (m->layer_count > 0) { /* layers below the stack keep the model's defaults */
        p->layer_count = m->layer_count;
        memcpy(p->layers, m->layers, sizeof p->layers[0] * (size_t)m->layer_count);
    }
}

/* ---- the two branches of Fig. 2 ------------------------------------------------------- */

static void performance(walk *w, abrdf_surface type, const abrdf_tolerance *tol,
                        const abrdf_costs *costs, const char *unit)
{
    abrdf_selection *out = &w->sel;
    char rl[32], al[32], cs[48];
    limit_text(tol->max_rel_pct, "%", rl, sizeof rl);
    limit_text(tol->max_abs, "", al, sizeof al);
    add_step(w, step(ABRDF_STEP_GOAL, ABRDF_MODEL_NONE, -1.0, -1.0, 1),
             "goal performance: Lambert diffuse + the cheapest Table-1 approximation of "
             "Blinn-Phong within rel %s and abs %s",
             rl, al);
    if (type != ABRDF_SURFACE_GENERAL)
        add_step(w, step(ABRDF_STEP_SURFACE, ABRDF_MODEL_NONE, -1.0, -1.0, 1),
                 "surface %s: not used by the performance branch (Fig. 2 branches on the goal "
                 "first)",
                 surface_names[type]);
    add_step(w, step(ABRDF_STEP_DIFFUSE, rules.perf_diffuse, -1.0, -1.0, 1), "diffuse: %s (Eq. 1)",
             model_name(rules.perf_diffuse));

    int best = -1;
    abrdf_approx_error best_err = {0, 0, 0};
    double best_cost = INFINITY;
    for (int i = 0; i < rules.candidate_count; ++i) {
        abrdf_model c = rules.candidates[i];
        const char *name = model_name(c);
        abrdf_approx_error e;
        int st = abrdf_approx_error_eval(c, out->n, &e);
        double cost = abrdf_costs_get(costs, c);
        cost_text(cost, unit, cs, sizeof cs);
        if (st != ABRDF_OK) {
            add_step(w, step(ABRDF_STEP_CANDIDATE, c, -1.0, tol->max_rel_pct, 0),
                     "%s: error analysis unavailable at n %g (%s): rejected", name, out->n,
                     abrdf_strerror(st));
            continue;
        }
        int rel_ok = e.max_rel_pct <= tol->max_rel_pct, abs_ok = e.max_abs <= tol->max_abs;
        int ranked = cost >= 0.0, ok = rel_ok && abs_ok && ranked;
        char crit[112];
        criteria_text(&e, tol, crit, sizeof crit);
        abrdf_select_step s = step(ABRDF_STEP_CANDIDATE, c, e.max_rel_pct, tol->max_rel_pct, ok);
        s.value2 = e.max_abs;
        s.threshold2 = tol->max_abs;
        s.cost = cost;
        add_step(w, s, "%s: %s, %s: %s", name, crit, cs,
                 !(rel_ok && abs_ok) ? "rejected"
                 : ranked            ? "passes"
                                     : "passes, but cannot be ranked");
        /* Cheapest first; equal cost: smaller relative, then absolute error. */
        if (ok && (cost < best_cost ||
                   (cost == best_cost &&
                    (e.max_rel_pct < best_err.max_rel_pct ||
                     (e.max_rel_pct == best_err.max_rel_pct && e.max_abs < best_err.max_abs))))) {
            best = i;
            best_cost = cost;
            best_err = e;
        }
    }
    out->diffuse = rules.perf_diffuse;
    if (best >= 0) {
        abrdf_model c = rules.candidates[best];
        out->specular = c;
        out->err_rel_pct = best_err.max_rel_pct;
        out->err_abs = best_err.max_abs;
        cost_text(best_cost, unit, cs, sizeof cs);
        char crit[112];
        criteria_text(&best_err, tol, crit, sizeof crit);
        abrdf_select_step s =
            step(ABRDF_STEP_CHEAPEST, c, best_err.max_rel_pct, tol->max_rel_pct, 1);
        s.value2 = best_err.max_abs;
        s.threshold2 = tol->max_abs;
        s.cost = best_cost;
        add_step(w, s, "%s: %s, %s: cheapest that passes", model_name(c), crit, cs);
    } else {
        out->specular = rules.perf_fallback;
        out->err_rel_pct = 0.0; /* Blinn-Phong is the reference of Tables 2 and 3 */
        out->err_abs = 0.0;
        add_step(w, step(ABRDF_STEP_FALLBACK, rules.perf_fallback, out->n, -1.0, 1),
                 "no Table-1 approximation passes at n %g: %s (Eq. 4), the reference itself",
                 out->n, model_name(rules.perf_fallback));
    }
}

static void photoreal(walk *w, const abrdf_material *m, int n_given, double n_raw)
{
    abrdf_selection *out = &w->sel;
    add_step(w, step(ABRDF_STEP_GOAL, ABRDF_MODEL_NONE, -1.0, -1.0, 1),
             "goal photoreal: the model that represents the surface's microstructure");
    abrdf_model special = rules.special[m->type];
    if (special != ABRDF_MODEL_NONE) {
        add_step(w, step(ABRDF_STEP_SURFACE, special, -1.0, -1.0, 1), "surface %s: %s",
                 surface_names[m->type], rules.special_reason[m->type]);
        char layers[96] = "";
        if (m->layer_count > 0)
            snprintf(layers, sizeof layers, "; top layer r %g, bottom layer r %g", m->layers[0].r,
                     m->layers[m->layer_count - 1].r);
        add_step(w, step(ABRDF_STEP_SPECIAL, special, out->r, -1.0, 1),
                 "%s: the whole reflectance (its own diffuse term); r %g%s", model_name(special),
                 out->r, layers);
        out->diffuse = ABRDF_MODEL_NONE;
        out->specular = special;
        return;
    }
    add_step(w, step(ABRDF_STEP_SURFACE, ABRDF_MODEL_NONE, -1.0, -1.0, 1), "surface general: %s",
             rules.special_reason[ABRDF_SURFACE_GENERAL]);
    double r = out->r;
    int smooth = r <= rules.smooth_r_max;
    add_step(w, step(ABRDF_STEP_ROUGHNESS, ABRDF_MODEL_NONE, r, rules.smooth_r_max, smooth),
             "alpha %g %s %g: %s", r, smooth ? "<=" : ">", rules.smooth_r_max,
             smooth ? "smooth" : "rough");
    int aniso = m->anisotropy > rules.aniso_min;
    if (!smooth) {
        out->diffuse = rules.rough_diffuse;
        out->specular = aniso ? rules.rough_specular_aniso : rules.rough_specular;
        add_step(w,
                 step(ABRDF_STEP_ANISOTROPY, out->specular, m->anisotropy, rules.aniso_min, aniso),
                 "anisotropy %g %s %g: %s (%s)", m->anisotropy, aniso ? ">" : "<=", rules.aniso_min,
                 model_name(out->specular),
                 aniso ? "anisotropic GGX, Eqs. 5, 7, 8, 9" : "GGX, Eqs. 5, 6, 8, 9");
        add_step(w, step(ABRDF_STEP_DIFFUSE, out->diffuse, -1.0, -1.0, 1), "diffuse: %s (Eq. 3)",
                 model_name(out->diffuse));
        /* The microfacet lobe is the reference of the paper's image experiment: no error. */
        return;
    }
    out->diffuse = rules.smooth_diffuse;
    out->specular = rules.smooth_specular;
    if (aniso)
        add_step(w,
                 step(ABRDF_STEP_ANISOTROPY, ABRDF_MODEL_NONE, m->anisotropy, rules.aniso_min, 0),
                 "anisotropy %g ignored: the smooth branch has no anisotropic lobe", m->anisotropy);
    add_step(w, step(ABRDF_STEP_DIFFUSE, out->diffuse, -1.0, -1.0, 1), "diffuse: %s (Eq. 2)",
             model_name(out->diffuse));
    /* f_2e reads the exponent n: the material's own, or converted from r. */
    double n = n_raw, nc = clampd(n, rules.n_min, rules.n_max);
    if (n_given)
        add_step(w, step(ABRDF_STEP_EXPONENT, out->specular, nc, -1.0, 1), "%s: n %g (given)%s",
                 model_name(out->specular), nc, nc != n ? ", clamped to f_2e's range" : "");
    else
        add_step(w, step(ABRDF_STEP_EXPONENT, out->specular, nc, -1.0, 1),
                 "%s: n %g from r %g by abrdf_alpha_g_to_n(r^2) = 2/alpha_g^2 - 2%s",
                 model_name(out->specular), nc, r,
                 n > rules.n_max   ? " (clamped to 1e6)"
                 : n < rules.n_min ? " (clamped to 1)"
                                   : "");
    out->n = nc;
    int row = nmse_row(r * r);
    out->err_nmse = table6_f2e[row];
    add_step(w,
             step(ABRDF_STEP_EXPONENT, out->specular, out->err_nmse, rules.nmse_class_max[0],
                  out->err_nmse < rules.nmse_class_max[0]),
             "%s vs the GGX lobe: NMSE %g at alpha_g %g (paper, Table 6): %s",
             model_name(out->specular), out->err_nmse, table6_alpha_g[row],
             nmse_class(out->err_nmse));
}

/* ---- entry point ---------------------------------------------------------------------- */

/* The flowchart on full-size copies of the caller's structs; w->sel receives the result. */
static int select_full(walk *w, const abrdf_material *m, abrdf_goal goal,
                       const abrdf_tolerance *tol, const abrdf_costs *costs, abrdf_params *params)
{
    abrdf_selection *out = &w->sel;
    if (goal != ABRDF_GOAL_PERFORMANCE && goal != ABRDF_GOAL_PHOTOREAL)
        return abrdf__selection_fail(out, ABRDF_E_RANGE, "unknown goal %d", (int)goal);
    int st = check_material(m, out);
    if (st != ABRDF_OK) return st;
    if ((st = check_tolerance(tol, out)) != ABRDF_OK) return st;
    abrdf_costs paper;
    if (!costs) {
        if ((st = abrdf_costs_paper(&paper)) != ABRDF_OK)
            return abrdf__selection_fail(out, st, "the paper's cost table is unavailable");
        costs = &paper;
    }
    /* cost[] is public: a NaN or infinity written there directly would rank as nothing. */
    for (int i = 0; i < ABRDF_COSTS_CAPACITY; ++i)
        if (!isfinite(costs->cost[i])) {
            const abrdf_model_info *mi = abrdf_model_get((abrdf_model)i);
            return abrdf__selection_fail(
                out, ABRDF_E_RANGE,
                "cost table: model id %d (%s) has cost %g; a cost is a finite number "
                "(< 0: unknown)",
                i, mi ? mi->name : "unregistered", costs->cost[i]);
        }
    char unit[32];
    short_unit(costs->unit, unit, sizeof unit);
    out->cost_unit = costs->unit;
    out->goal = goal;
    out->type = m->type;

    /* n and r: the given one, the other derived (Walter et al. 2007's n <-> alpha_g). */
    int n_given = m->n >= 0.0, r_given = m->r >= 0.0;
    out->n = n_given ? m->n : abrdf_alpha_g_to_n(abrdf_r_to_alpha_g(m->r));
    out->r = r_given ? m->r : abrdf_alpha_g_to_r(abrdf_n_to_alpha_g(m->n));
    double n_raw = out->n;
    if (!n_given) out->n = clampd(out->n, 0.0, rules.n_max);
    char nt[96], rt[96];
    if (n_given)
        snprintf(nt, sizeof nt, "n %g (given)", out->n);
    else
        snprintf(nt, sizeof nt, "n %g (from r: 2/alpha_g^2 - 2 = %.4g%s)", out->n, n_raw,
                 n_raw > rules.n_max ? ", clamped" : "");
    if (r_given)
        snprintf(rt, sizeof rt, "r %g (given)", out->r);
    else
        snprintf(rt, sizeof rt, "r %.4g (from n: alpha_g = sqrt(2/(n + 2)))", out->r);
    add_step(w, step(ABRDF_STEP_INPUT, ABRDF_MODEL_NONE, out->n, -1.0, 1), "%s%s: %s, %s",
             m->name ? "material " : "", m->name ? m->name : "explicit material", nt, rt);

    if (goal == ABRDF_GOAL_PERFORMANCE) {
        performance(w, m->type, tol, costs, unit);
    } else {
        photoreal(w, m, n_given, n_raw);
    }

    fill_params(m, out->specular, out->n, out->r, params);

    /* Costs of what was chosen; the special models carry their own diffuse term. */
    out->cost_specular = abrdf_costs_get(costs, out->specular);
    out->cost_diffuse =
        out->diffuse == ABRDF_MODEL_NONE ? 0.0 : abrdf_costs_get(costs, out->diffuse);
    if (out->cost_specular >= 0.0 && out->cost_diffuse >= 0.0)
        out->cost_total = out->cost_specular + out->cost_diffuse;

    /* Every model the rules name is registered; the material must fit its ranges. */
    abrdf_model chosen[2] = {out->diffuse, out->specular};
    for (int i = 0; i < 2; ++i) {
        char msg[ABRDF_SELECT_MESSAGE_MAX];
        if (chosen[i] != ABRDF_MODEL_NONE &&
            abrdf_params_check(chosen[i], params, msg, sizeof msg) != ABRDF_OK)
            return abrdf__selection_fail(out, ABRDF_E_RANGE, "%s", msg);
    }
    return ABRDF_OK;
}

int abrdf_select(const abrdf_material *m, abrdf_goal goal, const abrdf_tolerance *tol,
                 const abrdf_costs *costs, abrdf_selection *out, abrdf_params *params,
                 abrdf_select_trace_fn trace, void *trace_user)
{
    if (!out) return ABRDF_E_NULL;
    if (out->struct_size < SELECTION_SIZE_0_2) return ABRDF_E_SIZE; /* nowhere to say why */
    walk w;
    selection_empty(&w.sel);
    w.trace = trace;
    w.user = trace_user;
    abrdf_material mm;
    abrdf_tolerance tt;
    abrdf_params pp;
    material_defaults(&mm);
    tolerance_defaults(&tt);
    int st;
    if (!m) {
        st = abrdf__selection_fail(&w.sel, ABRDF_E_NULL, "no material");
    } else if (!read_in(&mm, sizeof mm, m, MATERIAL_SIZE_0_2)) {
        st = abrdf__selection_fail(&w.sel, ABRDF_E_SIZE,
                                   "abrdf_material: struct_size %zu is below the %zu bytes "
                                   "of the 0.2.0 layout: initialise it with abrdf_material_init",
                                   m->struct_size, (size_t)MATERIAL_SIZE_0_2);
    } else if (tol && !read_in(&tt, sizeof tt, tol, TOLERANCE_SIZE_0_2)) {
        st = abrdf__selection_fail(&w.sel, ABRDF_E_SIZE,
                                   "abrdf_tolerance: struct_size %zu is below the %zu bytes "
                                   "of the 0.2.0 layout: initialise it with abrdf_tolerance_init",
                                   tol->struct_size, (size_t)TOLERANCE_SIZE_0_2);
    } else if (params && !abrdf__params_view(ABRDF_MODEL_NONE, params, &pp)) {
        st = abrdf__selection_fail(&w.sel, ABRDF_E_SIZE,
                                   "abrdf_params: struct_size %zu is below the 0.2.0 "
                                   "layout: initialise it with abrdf_params_init",
                                   params->struct_size);
    } else {
        st = select_full(&w, &mm, goal, &tt, costs, &pp);
        if (st == ABRDF_OK && params) copy_out(params, &pp, sizeof pp);
    }
    copy_out(out, &w.sel, sizeof w.sel);
    return st;
}
