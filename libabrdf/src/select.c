/* select.c - the adaptive selection of Zavalniuk & Romanyuk 2024, Fig. 2 (the flowchart):
 * for a material, a goal (performance or photorealism) and tolerances, choose the diffuse
 * and specular models, fill their parameters, predict the error and cost, and record every
 * decision with the number behind it.
 *
 * Every threshold and model choice lives in `rules` below (abrdf_select_rules_get() hands it
 * to the CLI, the docs and the OSL/POV-Ray ports); the code only walks the flowchart.
 * Errors of the Table-1 approximations come from abrdf_approx_error_eval() (computed, not
 * tabulated); costs from the caller's abrdf_costs or the paper's Table 4. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "abrdf_internal.h"

/* ---- the flowchart's data: one table ------------------------------------------------- */

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
    .candidate_count = 7,
    .candidates = {ABRDF_F2, ABRDF_F4, ABRDF_F8, ABRDF_F16, ABRDF_FS, ABRDF_FKV, ABRDF_FKUB},
    .rough_diffuse = ABRDF_DISNEY_DIFFUSE,
    .rough_specular = ABRDF_DISNEY_SPECULAR,
    .rough_specular_aniso = ABRDF_DISNEY_SPECULAR_ANISO,
    .smooth_diffuse = ABRDF_LAMBERT_FRESNEL,
    .smooth_specular = ABRDF_F_2E,
    .special = {
        [ABRDF_SURFACE_GENERAL] = ABRDF_MODEL_COUNT,
        [ABRDF_SURFACE_CLOTH_ROUGH] = ABRDF_NEUBELT_PETTINEO,
        [ABRDF_SURFACE_CLOTH_SHINY] = ABRDF_KAJIYA_KAY,
        [ABRDF_SURFACE_HAIR] = ABRDF_HUANG,
        [ABRDF_SURFACE_LAYERED_PLASTIC] = ABRDF_WEIDLICH_WILKIE,
        [ABRDF_SURFACE_LAYERED_PLATE] = ABRDF_BELCOUR,
        [ABRDF_SURFACE_LAYERED_METAL] = ABRDF_BELCOUR,
    },
    .special_reason = {
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
        [ABRDF_SURFACE_LAYERED_METAL] = "metal under a coat (Eq. 16); Weidlich-Wilkie (Eq. 15) "
            "is poor for a smooth metal under a rough coat: one refraction, no inter-reflection "
            "between coat and metal",
    },
    /* Table 8 of the paper; boundaries half-open [a, b) (MODELS.md B9). */
    .nmse_class_max = {1e-4, 2.5e-4, 1e-3},
    /* Table 6 of the paper, f_2E column: minimum NMSE against the Disney GGX lobe. */
    .nmse_rows = ABRDF_SELECT_NMSE_ROWS,
    .nmse_alpha_g = {1.0, 0.9, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2, 0.1, 0.05, 0.01, 0.005,
                     0.001, 0.0005, 0.0001, 0.00005, 0.00001},
    .nmse_f2e = {0.0517, 0.0596, 0.0577, 0.0555, 0.0558, 0.0548, 0.0472, 0.0465, 0.0445,
                 0.0322, 0.0190, 0.0031, 0.0015, 0.0003, 0.0001, 0.00003, 0.00001, 0.000002},
};

const abrdf_select_rules *abrdf_select_rules_get(void) { return &rules; }

/* ---- names ---------------------------------------------------------------------------- */

static const char *const surface_names[ABRDF_SURFACE_COUNT] = {
    "general", "cloth_rough", "cloth_shiny", "hair", "layered_plastic", "layered_plate",
    "layered_metal"};
static const char *const goal_names[ABRDF_GOAL_COUNT] = {"performance", "photoreal"};

/* The stable names of abrdf.h's enum comments, so the trace can name models that are
 * reserved but not built in; tests hold this list equal to the registry's names. */
static const char *const model_names[ABRDF_MODEL_COUNT] = {
    "lambert", "lambert_fresnel", "disney_diffuse", "oren_nayar", "phong", "blinn_phong",
    "f2", "f4", "f8", "f16", "fs", "fkv", "fkub", "f_phe", "f_be", "f_2e", "f_16e", "f_ge",
    "f_ctphe", "f_ct2e", "f_ct16e", "cook_torrance", "disney_specular",
    "disney_specular_aniso", "disney_clearcoat", "neubelt_pettineo", "kajiya_kay",
    "marschner", "huang", "weidlich_wilkie", "belcour"};

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

const char *abrdf_select_model_name(abrdf_model model)
{
    const abrdf_model_info *m = abrdf_model_get(model);
    if (m) return m->name;
    return ((int)model >= 0 && model < ABRDF_MODEL_COUNT) ? model_names[model] : NULL;
}

void abrdf_material_init(abrdf_material *m)
{
    if (!m) return;
    memset(m, 0, sizeof *m);
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

/* ---- helpers -------------------------------------------------------------------------- */

static int in_range(double v, double lo, double hi) { return v >= lo && v <= hi; } /* NaN: 0 */

static int fail(abrdf_selection *out, int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out->message, sizeof out->message, fmt, ap);
    va_end(ap);
    return status;
}

static abrdf_select_step *add_step(abrdf_selection *out, abrdf_step_kind kind, abrdf_model model,
                                   double value, double threshold, int passed, const char *fmt, ...)
{
    if (out->step_count >= ABRDF_SELECT_MAX_STEPS) return NULL; /* cannot happen: <= 14 steps */
    abrdf_select_step *s = &out->steps[out->step_count++];
    s->kind = kind;
    s->model = model;
    s->value = value;
    s->threshold = threshold;
    s->value2 = -1.0;
    s->threshold2 = -1.0;
    s->cost = -1.0;
    s->passed = passed;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->text, sizeof s->text, fmt, ap);
    va_end(ap);
    return s;
}

/* A limit for the trace: "2%", "0.05", or "no limit". */
static const char *limit_text(double v, const char *suffix, char *buf, size_t size)
{
    if (isinf(v)) snprintf(buf, size, "no limit");
    else snprintf(buf, size, "%g%s", v, suffix);
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
    if (isinf(t->max_rel_pct)) snprintf(rel, sizeof rel, "rel %.3g%%", r);
    else snprintf(rel, sizeof rel, "rel %.3g%% %s %g%%", r, e->max_rel_pct <= t->max_rel_pct ? "<=" : ">", t->max_rel_pct);
    if (isinf(t->max_abs)) snprintf(ab, sizeof ab, "abs %.3g", a);
    else snprintf(ab, sizeof ab, "abs %.3g %s %g", a, e->max_abs <= t->max_abs ? "<=" : ">", t->max_abs);
    snprintf(buf, size, "%s, %s", rel, ab);
}

static void cost_text(double cost, const char *unit, char *buf, size_t size)
{
    if (cost >= 0.0) snprintf(buf, size, "%g %s", cost, unit);
    else snprintf(buf, size, "cost unknown");
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
    for (int i = 0; i < rules.nmse_rows; ++i) {
        double d = fabs(log(a / rules.nmse_alpha_g[i]));
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
        return fail(out, ABRDF_E_RANGE, "unknown surface type %d", (int)m->type);
    if (!(m->n < 0.0) && !in_range(m->n, 0.0, 1e6))
        return fail(out, ABRDF_E_RANGE, "n = %g is outside [0, 1e6] (negative = derive from r)", m->n);
    if (!(m->r < 0.0) && !in_range(m->r, 0.0, 1.0))
        return fail(out, ABRDF_E_RANGE, "r = %g is outside [0, 1] (negative = derive from n)", m->r);
    if (m->n < 0.0 && m->r < 0.0)
        return fail(out, ABRDF_E_RANGE, "neither n nor r is given");
    static const char *const rgb_names[3] = {"kd", "ks", "f0"};
    const double *rgb[3] = {m->kd, m->ks, m->f0};
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c)
            if (!in_range(rgb[k][c], 0.0, 1.0))
                return fail(out, ABRDF_E_RANGE, "%s[%d] = %g is outside [0, 1]", rgb_names[k], c, rgb[k][c]);
    if (!(m->eta <= 0.0) && !in_range(m->eta, 1.0, 4.0))
        return fail(out, ABRDF_E_RANGE, "eta = %g is outside [1, 4] (<= 0 = use f0)", m->eta);
    if (!in_range(m->anisotropy, 0.0, 1.0))
        return fail(out, ABRDF_E_RANGE, "anisotropy = %g is outside [0, 1]", m->anisotropy);
    if (!in_range(m->melanin, 0.0, 1.0) || !in_range(m->redness, 0.0, 1.0))
        return fail(out, ABRDF_E_RANGE, "melanin = %g or redness = %g is outside [0, 1]", m->melanin, m->redness);
    if (!in_range(m->layer_count, 0, ABRDF_MAX_LAYERS))
        return fail(out, ABRDF_E_RANGE, "layer_count = %d is outside [0, %d]", m->layer_count, ABRDF_MAX_LAYERS);
    for (int i = 0; i < m->layer_count; ++i) {
        const abrdf_layer *l = &m->layers[i];
        int ok = in_range(l->eta, 1.0, 4.0) && in_range(l->kappa, 0.0, 10.0) &&
                 in_range(l->r, 0.0, 1.0) && in_range(l->depth, 0.0, 100.0);
        for (int c = 0; c < 3; ++c) ok = ok && in_range(l->sigma_a[c], 0.0, 1e4);
        if (!ok)
            return fail(out, ABRDF_E_RANGE, "layer %d is outside the layer parameter ranges "
                        "(eta [1, 4], kappa [0, 10], r [0, 1], sigma_a [0, 1e4], depth [0, 100])", i);
    }
    return ABRDF_OK;
}

static int check_tolerance(const abrdf_tolerance *t, abrdf_selection *out)
{
    if (!(t->max_rel_pct >= 0.0))
        return fail(out, ABRDF_E_RANGE, "max relative error %g is not >= 0 (INFINITY = no limit)", t->max_rel_pct);
    if (!(t->max_abs >= 0.0))
        return fail(out, ABRDF_E_RANGE, "max absolute error %g is not >= 0 (INFINITY = no limit)", t->max_abs);
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

static void performance(abrdf_selection *out, abrdf_surface type, const abrdf_tolerance *tol,
                        const abrdf_costs *costs, const char *unit)
{
    char rl[32], al[32], cs[48];
    limit_text(tol->max_rel_pct, "%", rl, sizeof rl);
    limit_text(tol->max_abs, "", al, sizeof al);
    add_step(out, ABRDF_STEP_GOAL, ABRDF_MODEL_COUNT, -1.0, -1.0, 1,
             "goal performance: Lambert diffuse + the cheapest Table-1 approximation of "
             "Blinn-Phong within rel %s and abs %s", rl, al);
    if (type != ABRDF_SURFACE_GENERAL)
        add_step(out, ABRDF_STEP_SURFACE, ABRDF_MODEL_COUNT, -1.0, -1.0, 1,
                 "surface %s: not used by the performance branch (Fig. 2 branches on the goal "
                 "first)", surface_names[type]);
    add_step(out, ABRDF_STEP_DIFFUSE, rules.perf_diffuse, -1.0, -1.0, 1,
             "diffuse: %s (Eq. 1)", abrdf_select_model_name(rules.perf_diffuse));

    int best = -1;
    abrdf_approx_error best_err = {0, 0, 0};
    double best_cost = INFINITY;
    for (int i = 0; i < rules.candidate_count; ++i) {
        abrdf_model c = rules.candidates[i];
        const char *name = abrdf_select_model_name(c);
        abrdf_approx_error e;
        int st = abrdf_approx_error_eval(c, out->n, &e);
        double cost = costs->cost[c];
        cost_text(cost, unit, cs, sizeof cs);
        if (st != ABRDF_OK) {
            add_step(out, ABRDF_STEP_CANDIDATE, c, -1.0, tol->max_rel_pct, 0,
                     "%s: error analysis unavailable at n %g (%s): rejected", name, out->n,
                     abrdf_strerror(st));
            continue;
        }
        int rel_ok = e.max_rel_pct <= tol->max_rel_pct, abs_ok = e.max_abs <= tol->max_abs;
        int ranked = cost >= 0.0, ok = rel_ok && abs_ok && ranked;
        char crit[112];
        criteria_text(&e, tol, crit, sizeof crit);
        abrdf_select_step *s = add_step(out, ABRDF_STEP_CANDIDATE, c, e.max_rel_pct,
            tol->max_rel_pct, ok, "%s: %s, %s: %s", name, crit, cs,
            !(rel_ok && abs_ok) ? "rejected" : ranked ? "passes" : "passes, but cannot be ranked");
        if (s) {
            s->value2 = e.max_abs;
            s->threshold2 = tol->max_abs;
            s->cost = cost;
        }
        /* Cheapest first; equal cost: smaller relative, then absolute error. */
        if (ok && (cost < best_cost ||
                   (cost == best_cost && (e.max_rel_pct < best_err.max_rel_pct ||
                                          (e.max_rel_pct == best_err.max_rel_pct &&
                                           e.max_abs < best_err.max_abs))))) {
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
        abrdf_select_step *s = add_step(out, ABRDF_STEP_CHEAPEST, c, best_err.max_rel_pct,
            tol->max_rel_pct, 1, "%s: %s, %s: cheapest that passes", abrdf_select_model_name(c),
            crit, cs);
        if (s) {
            s->value2 = best_err.max_abs;
            s->threshold2 = tol->max_abs;
            s->cost = best_cost;
        }
    } else {
        out->specular = rules.perf_fallback;
        out->err_rel_pct = 0.0; /* Blinn-Phong is the reference of Tables 2 and 3 */
        out->err_abs = 0.0;
        add_step(out, ABRDF_STEP_FALLBACK, rules.perf_fallback, out->n, -1.0, 1,
                 "no Table-1 approximation passes at n %g: %s (Eq. 4), the reference itself",
                 out->n, abrdf_select_model_name(rules.perf_fallback));
    }
}

static void photoreal(abrdf_selection *out, const abrdf_material *m, int n_given, double n_raw)
{
    add_step(out, ABRDF_STEP_GOAL, ABRDF_MODEL_COUNT, -1.0, -1.0, 1,
             "goal photoreal: the model that represents the surface's microstructure");
    abrdf_model special = rules.special[m->type];
    if (special != ABRDF_MODEL_COUNT) {
        add_step(out, ABRDF_STEP_SURFACE, special, -1.0, -1.0, 1, "surface %s: %s",
                 surface_names[m->type], rules.special_reason[m->type]);
        char layers[96] = "";
        if (m->layer_count > 0)
            snprintf(layers, sizeof layers, "; top layer r %g, bottom layer r %g",
                     m->layers[0].r, m->layers[m->layer_count - 1].r);
        add_step(out, ABRDF_STEP_SPECIAL, special, out->r, -1.0, 1,
                 "%s: the whole reflectance (its own diffuse term); r %g%s",
                 abrdf_select_model_name(special), out->r, layers);
        out->diffuse = ABRDF_MODEL_COUNT;
        out->specular = special;
        return;
    }
    add_step(out, ABRDF_STEP_SURFACE, ABRDF_MODEL_COUNT, -1.0, -1.0, 1, "surface general: %s",
             rules.special_reason[ABRDF_SURFACE_GENERAL]);
    double r = out->r;
    int smooth = r <= rules.smooth_r_max;
    add_step(out, ABRDF_STEP_ROUGHNESS, ABRDF_MODEL_COUNT, r, rules.smooth_r_max, smooth,
             "alpha %g %s %g: %s", r, smooth ? "<=" : ">", rules.smooth_r_max,
             smooth ? "smooth" : "rough");
    int aniso = m->anisotropy > rules.aniso_min;
    if (!smooth) {
        out->diffuse = rules.rough_diffuse;
        out->specular = aniso ? rules.rough_specular_aniso : rules.rough_specular;
        add_step(out, ABRDF_STEP_ANISOTROPY, out->specular, m->anisotropy, rules.aniso_min, aniso,
                 "anisotropy %g %s %g: %s (%s)", m->anisotropy, aniso ? ">" : "<=",
                 rules.aniso_min, abrdf_select_model_name(out->specular),
                 aniso ? "anisotropic GGX, Eqs. 5, 7, 8, 9" : "GGX, Eqs. 5, 6, 8, 9");
        add_step(out, ABRDF_STEP_DIFFUSE, out->diffuse, -1.0, -1.0, 1, "diffuse: %s (Eq. 3)",
                 abrdf_select_model_name(out->diffuse));
        /* The microfacet lobe is the reference of the paper's image experiment: no error. */
        return;
    }
    out->diffuse = rules.smooth_diffuse;
    out->specular = rules.smooth_specular;
    if (aniso)
        add_step(out, ABRDF_STEP_ANISOTROPY, ABRDF_MODEL_COUNT, m->anisotropy, rules.aniso_min, 0,
                 "anisotropy %g ignored: the smooth branch has no anisotropic lobe", m->anisotropy);
    add_step(out, ABRDF_STEP_DIFFUSE, out->diffuse, -1.0, -1.0, 1, "diffuse: %s (Eq. 2)",
             abrdf_select_model_name(out->diffuse));
    /* f_2e reads the exponent n: the material's own, or converted from r. */
    double n = n_raw, nc = clampd(n, rules.n_min, rules.n_max);
    if (n_given)
        add_step(out, ABRDF_STEP_EXPONENT, out->specular, nc, -1.0, 1, "%s: n %g (given)%s",
                 abrdf_select_model_name(out->specular), nc, nc != n ? ", clamped to f_2e's range" : "");
    else
        add_step(out, ABRDF_STEP_EXPONENT, out->specular, nc, -1.0, 1,
                 "%s: n %g from r %g by abrdf_alpha_g_to_n(r^2) = 2/alpha_g^2 - 2%s",
                 abrdf_select_model_name(out->specular), nc, r,
                 n > rules.n_max ? " (clamped to 1e6)" : n < rules.n_min ? " (clamped to 1)" : "");
    out->n = nc;
    int row = nmse_row(r * r);
    out->err_nmse = rules.nmse_f2e[row];
    add_step(out, ABRDF_STEP_EXPONENT, out->specular, out->err_nmse, rules.nmse_class_max[0],
             out->err_nmse < rules.nmse_class_max[0],
             "%s vs the GGX lobe: NMSE %g at alpha_g %g (paper, Table 6): %s",
             abrdf_select_model_name(out->specular), out->err_nmse, rules.nmse_alpha_g[row],
             nmse_class(out->err_nmse));
}

/* ---- entry point ---------------------------------------------------------------------- */

int abrdf_select(const abrdf_material *m, abrdf_goal goal, const abrdf_tolerance *tol,
                 const abrdf_costs *costs, abrdf_selection *out)
{
    if (!out) return ABRDF_E_NULL;
    memset(out, 0, sizeof *out);
    out->diffuse = out->specular = ABRDF_MODEL_COUNT;
    out->err_rel_pct = out->err_abs = out->err_nmse = -1.0;
    out->cost_diffuse = out->cost_specular = out->cost_total = -1.0;
    if (!m) return fail(out, ABRDF_E_NULL, "no material");
    if (goal != ABRDF_GOAL_PERFORMANCE && goal != ABRDF_GOAL_PHOTOREAL)
        return fail(out, ABRDF_E_RANGE, "unknown goal %d", (int)goal);
    int st = check_material(m, out);
    if (st != ABRDF_OK) return st;
    abrdf_tolerance t = {rules.default_max_rel_pct, rules.default_max_abs};
    if (tol) t = *tol;
    if ((st = check_tolerance(&t, out)) != ABRDF_OK) return st;
    abrdf_costs paper;
    if (!costs) {
        if ((st = abrdf_costs_paper(&paper)) != ABRDF_OK)
            return fail(out, st, "the paper's cost table is unavailable");
        costs = &paper;
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
    if (n_given) snprintf(nt, sizeof nt, "n %g (given)", out->n);
    else snprintf(nt, sizeof nt, "n %g (from r: 2/alpha_g^2 - 2 = %.4g%s)", out->n, n_raw,
                  n_raw > rules.n_max ? ", clamped" : "");
    if (r_given) snprintf(rt, sizeof rt, "r %g (given)", out->r);
    else snprintf(rt, sizeof rt, "r %.4g (from n: alpha_g = sqrt(2/(n + 2)))", out->r);
    add_step(out, ABRDF_STEP_INPUT, ABRDF_MODEL_COUNT, out->n, -1.0, 1, "%s%s: %s, %s",
             m->name ? "material " : "", m->name ? m->name : "explicit material", nt, rt);

    if (goal == ABRDF_GOAL_PERFORMANCE) {
        performance(out, m->type, &t, costs, unit);
    } else {
        photoreal(out, m, n_given, n_raw);
    }

    fill_params(m, out->specular, out->n, out->r, &out->params);

    /* Costs of what was chosen; the special models carry their own diffuse term. */
    out->cost_specular = costs->cost[out->specular];
    out->cost_diffuse = out->diffuse == ABRDF_MODEL_COUNT ? 0.0 : costs->cost[out->diffuse];
    if (out->cost_specular >= 0.0 && out->cost_diffuse >= 0.0)
        out->cost_total = out->cost_specular + out->cost_diffuse;

    /* Models reserved in the ABI but not built into this library cannot be evaluated yet;
     * the choice stands, and the trace says so. */
    out->available = 1;
    abrdf_model chosen[2] = {out->diffuse, out->specular};
    for (int i = 0; i < 2; ++i) {
        if (chosen[i] == ABRDF_MODEL_COUNT) continue;
        char msg[ABRDF_SELECT_TEXT];
        if (!abrdf_model_get(chosen[i])) {
            out->available = 0;
            add_step(out, ABRDF_STEP_AVAILABLE, chosen[i], -1.0, -1.0, 0,
                     "%s is not built into libabrdf %s: abrdf_eval returns ABRDF_E_MODEL for it",
                     abrdf_select_model_name(chosen[i]), abrdf_version());
        } else if (abrdf_params_check(chosen[i], &out->params, msg, sizeof msg) != ABRDF_OK) {
            return fail(out, ABRDF_E_RANGE, "%s", msg);
        }
    }
    return ABRDF_OK;
}
