/* budget.c - the selection's error-budget mode (abrdf_fit.h): the photoreal choice of the
 * paper's flowchart is the reference; every candidate that can represent the material's
 * surface class is fitted to it (fit.c) and its image error predicted (predict.c); the
 * cheapest candidate within the budget wins. The budget is a Table-8 class of the paper
 * (none < 1e-4, slight < 2.5e-4, noticeable < 1e-3; abrdf_select_rules) or a number.
 *
 * The candidates per surface class are one table (below; docs/SELECTION.md prints it): pairs of
 * a diffuse and a specular lobe where the class is a diffuse base under a specular lobe,
 * whole models (hair, cloth, layered) where the class has them, and the reference itself
 * with its own parameters (error 0), so a budget can always be met. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fit_internal.h"

/* ---- the candidates per surface class ----------------------------------------------------- */

#define NONE ABRDF_MODEL_NONE

/* Specular lobes a diffuse base can carry: the microfacet lobes, the paper's Table-1
 * approximations of Blinn-Phong (the performance branch) and its Table-5 energy-conserving
 * lobes (the ones it tested against the GGX lobe, Tables 6 and 7). */
static const abrdf_model spec_general[] = {ABRDF_DISNEY_SPECULAR,
                                           ABRDF_COOK_TORRANCE,
                                           ABRDF_BLINN_PHONG,
                                           ABRDF_PHONG,
                                           ABRDF_F2,
                                           ABRDF_F4,
                                           ABRDF_F8,
                                           ABRDF_F16,
                                           ABRDF_FS,
                                           ABRDF_FKV,
                                           ABRDF_FKUB,
                                           ABRDF_F_PHE,
                                           ABRDF_F_BE,
                                           ABRDF_F_2E,
                                           ABRDF_F_16E,
                                           ABRDF_F_GE,
                                           ABRDF_F_CTPHE,
                                           ABRDF_F_CT2E,
                                           ABRDF_F_CT16E};
#define SPEC_GENERAL ((int)(sizeof spec_general / sizeof spec_general[0]))

typedef struct class_candidates {
    const abrdf_model *diffuse; /* diffuse options (NONE: no diffuse lobe) */
    int diffuse_count;
    const abrdf_model *specular; /* specular options (NONE: the diffuse lobe alone) */
    int specular_count;
    const abrdf_model (*whole)[2]; /* further candidates, as (first, second) lobes */
    int whole_count;
} class_candidates;

static const abrdf_model dif_general[] = {NONE, ABRDF_LAMBERT, ABRDF_DISNEY_DIFFUSE,
                                          ABRDF_OREN_NAYAR};
static const abrdf_model dif_smooth[] = {NONE, ABRDF_LAMBERT, ABRDF_LAMBERT_FRESNEL};
static const abrdf_model dif_cloth[] = {ABRDF_LAMBERT, ABRDF_DISNEY_DIFFUSE, ABRDF_OREN_NAYAR};
static const abrdf_model spec_cloth[] = {NONE, ABRDF_BLINN_PHONG, ABRDF_DISNEY_SPECULAR};
/* Lambert * (1 - F) (Eq. 2) stands for a base seen through a coat's Fresnel transmission. */
static const abrdf_model dif_layered[] = {NONE, ABRDF_LAMBERT, ABRDF_LAMBERT_FRESNEL,
                                          ABRDF_DISNEY_DIFFUSE};
static const abrdf_model aniso_spec[] = {ABRDF_DISNEY_SPECULAR_ANISO};
static const abrdf_model whole_cloth_shiny[][2] = {{NONE, ABRDF_KAJIYA_KAY}};
static const abrdf_model whole_hair[][2] = {{NONE, ABRDF_MARSCHNER}, {NONE, ABRDF_KAJIYA_KAY}};
static const abrdf_model whole_plastic[][2] = {{NONE, ABRDF_WEIDLICH_WILKIE}};
/* a GGX base under a clearcoat lobe (Burley 2012), and Weidlich-Wilkie for a plate over a
 * diffuse base */
static const abrdf_model whole_plate[][2] = {{NONE, ABRDF_WEIDLICH_WILKIE},
                                             {ABRDF_DISNEY_SPECULAR, ABRDF_DISNEY_CLEARCOAT}};
static const abrdf_model whole_metal[][2] = {{ABRDF_DISNEY_SPECULAR, ABRDF_DISNEY_CLEARCOAT}};

#define LIST(a) a, (int)(sizeof a / sizeof a[0])

/* Candidates of a class; `smooth` and `aniso` refine the general class as the flowchart
 * does (r <= smooth_r_max; anisotropy > aniso_min). */
static class_candidates candidates_of(abrdf_surface type, int smooth, int aniso)
{
    class_candidates c = {NULL, 0, NULL, 0, NULL, 0};
    switch (type) {
    case ABRDF_SURFACE_GENERAL:
        if (smooth) {
            c = (class_candidates){LIST(dif_smooth), spec_general, SPEC_GENERAL, NULL, 0};
        } else {
            c = (class_candidates){LIST(dif_general), spec_general, SPEC_GENERAL, NULL, 0};
            if (aniso) c.specular = aniso_spec, c.specular_count = 1;
        }
        break;
    case ABRDF_SURFACE_CLOTH_ROUGH:
        c = (class_candidates){LIST(dif_cloth), LIST(spec_cloth), NULL, 0};
        break;
    case ABRDF_SURFACE_CLOTH_SHINY:
        c = (class_candidates){LIST(dif_cloth), LIST(spec_cloth), LIST(whole_cloth_shiny)};
        break;
    case ABRDF_SURFACE_HAIR: c = (class_candidates){NULL, 0, NULL, 0, LIST(whole_hair)}; break;
    case ABRDF_SURFACE_LAYERED_PLASTIC:
        c = (class_candidates){LIST(dif_layered), spec_general, SPEC_GENERAL, LIST(whole_plastic)};
        break;
    case ABRDF_SURFACE_LAYERED_PLATE:
        c = (class_candidates){LIST(dif_layered), spec_general, SPEC_GENERAL, LIST(whole_plate)};
        break;
    case ABRDF_SURFACE_LAYERED_METAL:
        c = (class_candidates){LIST(dif_layered), spec_general, SPEC_GENERAL, LIST(whole_metal)};
        break;
    default: break;
    }
    return c;
}

/* Candidate k of the class (0: the reference, as given), or 0 past the last. A pair with no
 * diffuse lobe, or a diffuse lobe alone, is returned as (NONE, model). */
static int candidate_get(const class_candidates *c, int k, abrdf_model d, abrdf_model s,
                         int no_diffuse, abrdf_model out[2])
{
    if (k == 0) {
        out[0] = d, out[1] = s;
        return 1;
    }
    --k;
    int pairs = c->diffuse_count * c->specular_count;
    if (k < pairs) {
        abrdf_model dd = c->diffuse[k / c->specular_count], ss = c->specular[k % c->specular_count];
        if (dd == NONE && ss == NONE) return -1;
        if ((dd == NONE) != no_diffuse && c->diffuse_count > 1)
            return -1; /* no diffuse lobe exactly when kd = 0 */
        if (ss == NONE) ss = dd, dd = NONE;
        if (dd == d && ss == s) return -1; /* the reference's own pair: candidate 0 */
        out[0] = dd, out[1] = ss;
        return 1;
    }
    k -= pairs;
    if (k < c->whole_count) {
        out[0] = c->whole[k][0], out[1] = c->whole[k][1];
        if (out[0] == d && out[1] == s) return -1;
        return 1;
    }
    return 0;
}

/* The candidates of m's surface class, refined by the flowchart's reference `ref` (its
 * roughness: smooth or not), and whether m has no diffuse term. */
static void class_of(const abrdf_material *m, const abrdf_selection *ref, class_candidates *cc,
                     int *no_diffuse)
{
    abrdf_material mm;
    abrdf_material_init(&mm);
    memcpy((char *)&mm + sizeof(size_t), (const char *)m + sizeof(size_t),
           (m->struct_size < sizeof mm ? m->struct_size : sizeof mm) - sizeof(size_t));
    const abrdf_select_rules *rules = abrdf_select_rules_get();
    *cc = candidates_of(mm.type, ref->r <= rules->smooth_r_max, mm.anisotropy > rules->aniso_min);
    *no_diffuse = !(mm.kd[0] > 0.0 || mm.kd[1] > 0.0 || mm.kd[2] > 0.0);
}

int abrdf_budget_candidate(const abrdf_material *m, int index, abrdf_model *diffuse,
                           abrdf_model *specular)
{
    if (!m || !diffuse || !specular) return ABRDF_E_NULL;
    if (index < 0) return ABRDF_E_RANGE;
    abrdf_selection sel;
    abrdf_params block;
    abrdf_selection_init(&sel);
    abrdf_params_init(ABRDF_MODEL_NONE, &block);
    int st = abrdf_select(m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, &block, NULL, NULL);
    if (st != ABRDF_OK) return st;
    class_candidates cc;
    int no_diffuse;
    class_of(m, &sel, &cc, &no_diffuse);
    for (int k = 0, seen = 0;; ++k) {
        abrdf_model lobe[2];
        int g = candidate_get(&cc, k, sel.diffuse, sel.specular, no_diffuse, lobe);
        if (g == 0) return ABRDF_E_RANGE;
        if (g < 0) continue;
        if (seen++ == index) {
            *diffuse = lobe[0];
            *specular = lobe[1];
            return ABRDF_OK;
        }
    }
}

/* ---- the budget struct -------------------------------------------------------------------- */

#define END_OF(type, field) (offsetof(type, field) + sizeof(((type *)0)->field))
#define BUDGET_SIZE_0_3 END_OF(abrdf_budget, view)

static void budget_defaults(abrdf_budget *b)
{
    memset(b, 0, sizeof *b);
    b->struct_size = sizeof *b;
    b->max_nmse = abrdf_select_rules_get()->nmse_class_max[1];
    b->metric = ABRDF_FIT_AUTO;
    b->reference_cost = -1.0;
}

int abrdf_budget_init_sized(abrdf_budget *b, size_t struct_size)
{
    if (!b) return ABRDF_E_NULL;
    if (struct_size < BUDGET_SIZE_0_3) return ABRDF_E_SIZE;
    abrdf_budget d;
    budget_defaults(&d);
    memset(b, 0, struct_size);
    memcpy(b, &d, struct_size < sizeof d ? struct_size : sizeof d);
    b->struct_size = struct_size;
    return ABRDF_OK;
}

static const char *const class_names[3] = {"none", "slight", "noticeable"};

int abrdf_budget_class_find(const char *name, double *max_nmse)
{
    if (!name || !max_nmse) return ABRDF_E_NULL;
    for (int i = 0; i < 3; ++i)
        if (!strcmp(name, class_names[i])) {
            *max_nmse = abrdf_select_rules_get()->nmse_class_max[i];
            return ABRDF_OK;
        }
    return ABRDF_E_RANGE;
}

/* ---- the trace ------------------------------------------------------------------------------ */

#define TEXT_MAX 512

typedef struct bwalk {
    abrdf_select_trace_fn trace;
    void *user;
    int steps;
} bwalk;

static void emit(bwalk *w, abrdf_select_step s, const char *fmt, ...)
{
    char text[TEXT_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    s.text = text;
    ++w->steps;
    if (w->trace) w->trace(w->user, &s);
}

/* Forwards the flowchart's steps and counts them. */
static void forward(void *user, const abrdf_select_step *step)
{
    bwalk *w = user;
    ++w->steps;
    if (w->trace) w->trace(w->user, step);
}

static const char *mname(abrdf_model m)
{
    const abrdf_model_info *i = abrdf_model_get(m);
    return i ? i->name : "none";
}

static void pair_text(const abrdf_model lobe[2], char *buf, size_t size)
{
    if (lobe[0] == NONE)
        snprintf(buf, size, "%s", mname(lobe[1]));
    else
        snprintf(buf, size, "%s + %s", mname(lobe[0]), mname(lobe[1]));
}

/* Whether a lobe of the pair reads parameter `name`. */
static int pair_reads(const abrdf_model lobe[2], const char *name)
{
    int id;
    if (abrdf_param_find(name, &id) != ABRDF_OK) return 0;
    for (int l = 0; l < 2; ++l) {
        const abrdf_model_info *mi = abrdf_model_get(lobe[l]);
        for (int k = 0; mi && k < mi->param_count; ++k)
            if (mi->params[k].id == id) return 1;
    }
    return 0;
}

/* The fitted values: kd, ks, f0 and the searched parameters the pair reads. */
static void params_text(const abrdf__brdf *b, char *buf, size_t size)
{
    static const char *const names[] = {
        "kd",         "ks",           "f0",           "n",
        "r",          "sigma",        "anisotropic",  "clearcoat_gloss",
        "k_amp",      "melanin",      "cuticle_tilt", "layer0_r",
        "entry_grid", "internal_grid"};
    size_t len = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
        int id;
        double v[3];
        if (abrdf_param_find(names[i], &id) != ABRDF_OK || !pair_reads(b->lobe, names[i])) continue;
        int n = abrdf_param_read(&b->p, id, v);
        int w;
        if (n == 3 && !(v[0] == v[1] && v[1] == v[2]))
            w = snprintf(buf + len, size - len, "%s%s %.3g,%.3g,%.3g", len ? ", " : "", names[i],
                         v[0], v[1], v[2]);
        else
            w = snprintf(buf + len, size - len, "%s%s %.4g", len ? ", " : "", names[i], v[0]);
        if (w < 0 || (size_t)w >= size - len) break;
        len += (size_t)w;
    }
}

static const char *class_word(double nmse)
{
    const double *c = abrdf_select_rules_get()->nmse_class_max;
    if (nmse < c[0]) return "none";
    if (nmse < c[1]) return "slight";
    if (nmse < c[2]) return "noticeable";
    return "significant";
}

/* "slight (2.5e-4)" for a class bound, else the number. */
static void budget_text(double max, char *buf, size_t size)
{
    const double *c = abrdf_select_rules_get()->nmse_class_max;
    for (int i = 0; i < 3; ++i)
        if (max == c[i]) {
            snprintf(buf, size, "%g (%s)", max, class_names[i]);
            return;
        }
    snprintf(buf, size, "%g", max);
}

/* A lobe's cost with parameters p: the table's entry scaled by the work its parameters ask
 * for (abrdf__cost_scale: huang's quadrature grids); -1 when the table does not know it. */
static double lobe_cost(const abrdf_costs *costs, abrdf_model lobe, const abrdf_params *p)
{
    double v = abrdf_costs_get(costs, lobe);
    return v >= 0.0 ? v * abrdf__cost_scale(lobe, p) : -1.0;
}

/* The cost of a pair: the sum of its lobes', -1 if one is unknown. */
static double pair_cost(const abrdf_costs *costs, const abrdf_model lobe[2], const abrdf_params *p)
{
    double c = 0.0;
    for (int l = 0; l < 2; ++l) {
        if (lobe[l] == NONE) continue;
        double v = lobe_cost(costs, lobe[l], p);
        if (v < 0.0) return -1.0;
        c += v;
    }
    return c;
}

/* The reference computed with a coarser quadrature, the i-th (1, 2, ...): huang with an entry
 * grid i nodes coarser, down to 2 x 2 (docs/MODELS.md, "Convergence on an image", and
 * docs/SELECTION.md: on the mixed scene's lock entry grid 5 is within "slight" of the default;
 * the internal grid 2 was measured there and is not, (5, 2) at 2.6e-4). Nothing is fitted:
 * the model's parameters stay the reference's. 0 when there is no such variant. */
static int coarser_quadrature(const abrdf__brdf *ref, int i, abrdf__brdf *out)
{
    if (ref->lobe[0] != NONE || ref->lobe[1] != ABRDF_HUANG) return 0;
    int n1 = ref->p.entry_grid - i;
    if (n1 < 2) return 0;
    *out = *ref;
    out->prepared = NULL; /* a caller's reference (a table) is not a quadrature */
    out->p.entry_grid = n1;
    return 1;
}

/* ---- the selection ----------------------------------------------------------------------- */

#define SELECTION_SIZE_0_2 END_OF(abrdf_selection, message)

/* What one abrdf_select_budget call shares between its steps: the budget, the costs, the
 * trace, the reference, its candidates and what they are fitted and predicted with. */
typedef struct budget_state {
    abrdf_budget b;
    const abrdf_costs *costs;
    abrdf_costs builtin; /* the costs when the caller gives none */
    bwalk w;
    abrdf__brdf ref;
    double ref_cost;
    class_candidates cc;
    int no_diffuse;
    abrdf__arena a;
    abrdf__pred pr;
    abrdf__fit_set set;
    char bt[64];   /* the budget as text (budget_text) */
    char unit[32]; /* the costs' unit, its first word */
} budget_state;

/* The cheapest candidate within the budget so far. */
typedef struct budget_best {
    abrdf__brdf brdf;
    abrdf_fit_result res;
    double cost, nmse;
    int have;
} budget_best;

/* The caller's budget (NULL: the defaults) in this library's layout, checked: ABRDF_OK, or the
 * status with its message in sel. */
static int budget_read(const abrdf_budget *budget, abrdf_budget *b, abrdf_selection *sel)
{
    budget_defaults(b);
    if (budget) {
        if (budget->struct_size < BUDGET_SIZE_0_3)
            return abrdf__selection_fail(
                sel, ABRDF_E_SIZE,
                "abrdf_budget: struct_size %zu is below its first layout: initialise it "
                "with abrdf_budget_init",
                budget->struct_size);
        memcpy(b, budget, budget->struct_size < sizeof *b ? budget->struct_size : sizeof *b);
        b->struct_size = sizeof *b;
    }
    if (!(b->max_nmse > 0.0 && b->max_nmse <= 1.0))
        return abrdf__selection_fail(sel, ABRDF_E_RANGE, "budget NMSE %g is not in (0, 1]",
                                     b->max_nmse);
    if (!((int)b->metric >= 0 && b->metric < ABRDF_FIT_METRIC_COUNT) || b->resolution < 0 ||
        b->resolution > 5)
        return abrdf__selection_fail(
            sel, ABRDF_E_RANGE, "budget: metric %d is unknown or resolution %d is outside [0, 5]",
            (int)b->metric, b->resolution);
    return ABRDF_OK;
}

/* The caller's prepared reference (abrdf_budget.reference) in place of the photoreal choice
 * bs->ref, once it is known to be that choice: the same one model, every parameter the model
 * reads the same. ABRDF_OK, or ABRDF_E_MODEL (ABRDF_E_NULL: not prepared) with the
 * difference named in sel. */
static int reference_adopt(budget_state *bs, abrdf_selection *sel)
{
    char msg[ABRDF_FIT_MESSAGE_MAX];
    abrdf__brdf given;
    int st = abrdf__brdf_from_prepared(&given, bs->b.reference, msg, sizeof msg);
    if (st != ABRDF_OK) return abrdf__selection_fail(sel, st, "abrdf_budget.reference: %s", msg);
    if (bs->ref.lobe[0] != NONE || given.lobe[1] != bs->ref.lobe[1])
        return abrdf__selection_fail(
            sel, ABRDF_E_MODEL,
            "abrdf_budget.reference is prepared for %s, the photoreal choice is %s%s%s",
            mname(given.lobe[1]), bs->ref.lobe[0] != NONE ? mname(bs->ref.lobe[0]) : "",
            bs->ref.lobe[0] != NONE ? " + " : "", mname(bs->ref.lobe[1]));
    const abrdf_model_info *mi = abrdf_model_get(given.lobe[1]);
    for (int k = 0; k < mi->param_count; ++k) {
        double a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
        int id = mi->params[k].id, n = abrdf_param_read(&bs->ref.p, id, a);
        abrdf_param_read(&given.p, id, b);
        for (int c = 0; c < n; ++c)
            if (a[c] != b[c])
                return abrdf__selection_fail(
                    sel, ABRDF_E_MODEL,
                    "abrdf_budget.reference has %s %g where the photoreal choice has %g",
                    abrdf_param_get(id)->name, b[c], a[c]);
    }
    bs->ref = given;
    return ABRDF_OK;
}

/* The reference (the flowchart's photoreal choice, its steps traced first), its class's
 * candidates, its predicted image and the fit's direction set, in the workspace: ABRDF_OK, or
 * the status with its message in sel. */
static int reference_prepare(budget_state *bs, const abrdf_material *m, abrdf_selection *sel,
                             void *work, size_t work_size)
{
    abrdf_params ref_block;
    abrdf_params_init(ABRDF_MODEL_NONE, &ref_block);
    int st =
        abrdf_select(m, ABRDF_GOAL_PHOTOREAL, NULL, bs->costs, sel, &ref_block, forward, &bs->w);
    if (st != ABRDF_OK) return st;
    char msg[ABRDF_FIT_MESSAGE_MAX];
    if ((st = abrdf__brdf_make(&bs->ref, sel->diffuse, sel->specular, &ref_block, msg,
                               sizeof msg)) != ABRDF_OK)
        return abrdf__selection_fail(sel, st, "%s", msg);
    if (bs->b.reference && (st = reference_adopt(bs, sel)) != ABRDF_OK) return st;
    class_of(m, sel, &bs->cc, &bs->no_diffuse);
    int integrating = (abrdf__brdf_needs(&bs->ref) & ABRDF_NEEDS_INTEGRATION) != 0;
    abrdf__arena_init(&bs->a, work, work_size);
    if ((st = abrdf__pred_prepare(&bs->pr, bs->b.view, &bs->ref, integrating, &bs->a, msg,
                                  sizeof msg)) != ABRDF_OK)
        return abrdf__selection_fail(sel, st, "%s", msg);
    int tangent = abrdf__brdf_uses_tangent(&bs->ref), fibre = abrdf__brdf_is_fibre(&bs->ref);
    if (abrdf__fit_set_make(&bs->set, &bs->ref, tangent, fibre,
                            abrdf__fit_level(bs->b.resolution, integrating), &bs->a) != ABRDF_OK)
        return abrdf__selection_fail(
            sel, ABRDF_E_SIZE, "the workspace (%zu bytes) is too small: abrdf_fit_workspace_size",
            work_size);
    return ABRDF_OK;
}

/* The budget's first step: the bound, the reference, where the error is predicted and how
 * the candidates are fitted. */
static void trace_reference(budget_state *bs)
{
    char names[96];
    abrdf_select_step s = {ABRDF_STEP_REFERENCE,
                           bs->ref.lobe[1],
                           0.0,
                           bs->b.max_nmse,
                           -1.0,
                           -1.0,
                           bs->ref_cost,
                           1,
                           NULL,
                           bs->ref.lobe[0],
                           &bs->ref.p};
    pair_text(bs->ref.lobe, names, sizeof names);
    emit(&bs->w, s,
         "budget: image NMSE < %s against the reference %s (the photoreal choice%s), "
         "predicted on %s; fits by the %s metric on %d direction pairs",
         bs->bt, names, bs->ref.prepared ? ", as the caller prepared it" : "",
         bs->pr.samples && bs->b.view && bs->b.view->term_count ? "the caller's image"
                                                                : "an analytic sphere",
         abrdf_fit_metric_name(bs->b.metric), bs->set.n);
}

/* Fit cand (its lobes set) to the reference by the budget's metric, or with ABRDF_FIT_AUTO by
 * every metric, the best predicted kept; r receives the result: ABRDF_OK, or the status with
 * its message in sel. */
static int candidate_fit(budget_state *bs, abrdf__brdf *cand, abrdf_fit_result *r,
                         abrdf_selection *sel)
{
    abrdf__fit_start(&bs->ref, cand);
    abrdf__brdf start = *cand;
    abrdf_fit_metric first = bs->b.metric == ABRDF_FIT_AUTO ? ABRDF_FIT_L2 : bs->b.metric;
    abrdf__fit_run(&bs->set, &bs->ref, cand, first, 1, &bs->pr, r, &bs->a);
    /* Bieron & Peers 2020: the other metrics' fits too, the best predicted kept. Every
     * candidate: no threshold on the L2 fit's prediction separates the ones the other
     * metrics bring into a class (tools/measure/auto_reach.c: from 3.3e3 to 5.4e-4) */
    if (bs->b.metric == ABRDF_FIT_AUTO && !r->message[0]) {
        for (int q = ABRDF_FIT_L2 + 1; q < ABRDF_FIT_AUTO; ++q) {
            abrdf__brdf c2 = start;
            abrdf_fit_result r2;
            abrdf_fit_result_init(&r2);
            abrdf__fit_run(&bs->set, &bs->ref, &c2, (abrdf_fit_metric)q, 1, &bs->pr, &r2, &bs->a);
            r->evals += r2.evals;
            if (!r2.message[0] && r2.nmse_pred < r->nmse_pred) {
                r2.evals = r->evals;
                *r = r2;
                *cand = c2;
            }
        }
    }
    if (r->message[0]) return abrdf__selection_fail(sel, ABRDF_E_SIZE, "%s", r->message);
    return ABRDF_OK;
}

/* One candidate's step: its fitted parameters, predicted error, cost and verdict. */
static void trace_candidate(budget_state *bs, int is_ref, const abrdf__brdf *cand,
                            const abrdf_fit_result *r, double cost)
{
    char names[96], ptext[320], cs[48];
    int within = r->nmse_pred < bs->b.max_nmse, ranked = cost >= 0.0;
    pair_text(cand->lobe, names, sizeof names);
    params_text(cand, ptext, sizeof ptext);
    if (ranked)
        snprintf(cs, sizeof cs, "%.3g %s", cost, bs->unit);
    else
        snprintf(cs, sizeof cs, "cost unknown");
    abrdf_select_step s = {ABRDF_STEP_FIT, cand->lobe[1], r->nmse_pred, bs->b.max_nmse,
                           r->rel_l2,      -1.0,          cost,         within && ranked,
                           NULL,           cand->lobe[0], &cand->p};
    emit(&bs->w, s, "%s%s: %s; NMSE %.3g %s %g (%s), rel L2 %.3g, highlight %.3g%%, %s: %s", names,
         is_ref ? " (reference)" : "", ptext[0] ? ptext : "no parameters", r->nmse_pred,
         within ? "<" : ">=", bs->b.max_nmse, class_word(r->nmse_pred), r->rel_l2, r->max_rel_pct,
         cs,
         !within  ? "over the budget"
         : ranked ? "within the budget"
                  : "within, but cannot be ranked");
}

/* Costs closer than this fraction of the cheapest are not told apart: between calibration
 * runs on one machine the ratio of two models' costs moves by up to +-15 % (eight runs of
 * `abrdf calibrate`, docs/SELECTION.md), so a saving below it is not one. Of the candidates
 * within the budget that cost at most (1 + COST_TIE) x the cheapest, the lowest predicted
 * NMSE wins. */
#define COST_TIE 0.15
#define MAX_CANDIDATES 192

/* Candidate k (variant: how many coarser quadratures were asked for before it): 1 with
 * cand set and *fitted telling whether it needs fitting, 0 past the last, -1 to skip. */
static int candidate_at(const budget_state *bs, int k, int *variants, abrdf__brdf *cand,
                        int *fitted)
{
    abrdf_model lobe[2];
    int g = candidate_get(&bs->cc, k, bs->ref.lobe[0], bs->ref.lobe[1], bs->no_diffuse, lobe);
    *fitted = 0;
    if (g == 0) /* the class's models done: the reference's cheaper quadratures */
        return coarser_quadrature(&bs->ref, ++*variants, cand) ? 1 : 0;
    if (g < 0) return -1;
    if (k == 0) { /* the reference, as chosen */
        *cand = bs->ref;
        return 1;
    }
    cand->lobe[0] = lobe[0];
    cand->lobe[1] = lobe[1];
    *fitted = 1;
    return 1;
}

/* Candidate cand measured: fitted if it needs to be, its errors and predicted NMSE in r. */
static int candidate_measure(budget_state *bs, abrdf__brdf *cand, int fitted, abrdf_fit_result *r,
                             abrdf_selection *sel)
{
    abrdf_fit_result_init(r);
    if (fitted) return candidate_fit(bs, cand, r, sel);
    /* the reference, or it at a coarser quadrature: nothing to fit */
    abrdf__fit_errors(&bs->set, cand, r);
    r->nmse_pred = abrdf__pred_nmse(&bs->pr, cand);
    return ABRDF_OK;
}

/* What the first pass keeps of each candidate: where it is, and its verdict. */
typedef struct candidate_mark {
    int k, variants, within;
    double cost, nmse;
} candidate_mark;

/* Every candidate in turn (the reference as chosen, the class's models fitted, then the
 * reference's cheaper quadratures), measured and traced; then the cheapest within the budget,
 * costs within COST_TIE counted equal, measured again into best: ABRDF_OK, or the status with
 * its message in sel. */
static int candidates_run(budget_state *bs, budget_best *best, abrdf_selection *sel)
{
    candidate_mark mark[MAX_CANDIDATES];
    int n = 0, variants = 0, st;
    double cheapest = INFINITY;
    for (int k = 0;; ++k) {
        abrdf__brdf cand;
        int fitted, at = variants;
        int g = candidate_at(bs, k, &variants, &cand, &fitted);
        if (g == 0) break;
        if (g < 0) continue;
        if (n == MAX_CANDIDATES) /* the tables above give at most ~120: a table grew too far */
            return abrdf__selection_fail(
                sel, ABRDF_E_SIZE, "abrdf_select_budget: more than %d candidates", MAX_CANDIDATES);
        abrdf_fit_result r;
        if ((st = candidate_measure(bs, &cand, fitted, &r, sel)) != ABRDF_OK) return st;
        double cost = cand.prepared ? bs->ref_cost : pair_cost(bs->costs, cand.lobe, &cand.p);
        trace_candidate(bs, k == 0, &cand, &r, cost);
        mark[n] =
            (candidate_mark){k, at, r.nmse_pred < bs->b.max_nmse && cost >= 0.0, cost, r.nmse_pred};
        if (mark[n].within && cost < cheapest) cheapest = cost;
        ++n;
    }
    const candidate_mark *win = NULL;
    for (int i = 0; i < n; ++i) {
        const candidate_mark *c = &mark[i];
        if (!c->within || c->cost > cheapest * (1.0 + COST_TIE)) continue;
        if (!win || c->nmse < win->nmse || (c->nmse == win->nmse && c->cost < win->cost)) win = c;
    }
    best->have = win != NULL;
    if (!win) { /* costs unknown for every candidate within the budget: the reference */
        best->brdf = bs->ref;
        abrdf_fit_result_init(&best->res);
        abrdf__fit_errors(&bs->set, &best->brdf, &best->res);
        best->res.nmse_pred = 0.0;
        best->cost = bs->ref_cost;
        best->nmse = 0.0;
        return ABRDF_OK;
    }
    /* the winner again (fits are deterministic), without a second trace step */
    int fitted, variants_at = win->variants;
    candidate_at(bs, win->k, &variants_at, &best->brdf, &fitted);
    if ((st = candidate_measure(bs, &best->brdf, fitted, &best->res, sel)) != ABRDF_OK) return st;
    best->cost = win->cost;
    best->nmse = best->res.nmse_pred;
    return ABRDF_OK;
}

/* The budget's last step: the choice and why. */
static void trace_choice(budget_state *bs, const budget_best *best)
{
    char names[96];
    pair_text(best->brdf.lobe, names, sizeof names);
    abrdf_select_step s = {ABRDF_STEP_BUDGET,
                           best->brdf.lobe[1],
                           best->res.nmse_pred,
                           bs->b.max_nmse,
                           -1.0,
                           -1.0,
                           best->cost,
                           1,
                           NULL,
                           best->brdf.lobe[0],
                           &best->brdf.p};
    if (best->have)
        emit(&bs->w, s,
             "%s: the cheapest within NMSE < %s (costs within %.0f %% of it counted equal, "
             "the lowest predicted NMSE of those): %.3g %s (the reference costs %.3g), "
             "predicted NMSE %.3g (%s)",
             names, bs->bt, 100.0 * COST_TIE, best->cost, bs->unit, bs->ref_cost,
             best->res.nmse_pred, class_word(best->res.nmse_pred));
    else
        emit(&bs->w, s, "%s: no candidate within the budget has a known cost: the reference",
             names);
}

/* The choice into the selection: its models, predicted errors, n and r where its lobes read
 * them, and costs. */
static void selection_fill(abrdf_selection *sel, const budget_best *best, const abrdf_costs *costs)
{
    const abrdf__brdf *b = &best->brdf;
    sel->diffuse = b->lobe[0];
    sel->specular = b->lobe[1];
    sel->err_nmse = best->res.nmse_pred;
    sel->err_rel_pct = best->res.max_rel_pct;
    sel->err_abs = best->res.max_abs;
    if (pair_reads(b->lobe, "n")) sel->n = b->p.n;
    if (pair_reads(b->lobe, "r")) sel->r = b->p.r;
    sel->cost_diffuse = b->lobe[0] == NONE ? 0.0 : lobe_cost(costs, b->lobe[0], &b->p);
    sel->cost_specular = b->prepared ? best->cost : lobe_cost(costs, b->lobe[1], &b->p);
    sel->cost_total = best->cost >= 0.0 && isfinite(best->cost) ? best->cost : -1.0;
    sel->cost_unit = costs->unit;
}

/* The choice's parameter block into the caller's, in its layout: ABRDF_OK, or the status with
 * its message in sel. */
static int params_copy(abrdf_params *params, const abrdf__brdf *best, abrdf_selection *sel)
{
    if (params->struct_size < END_OF(abrdf_params, layers))
        return abrdf__selection_fail(sel, ABRDF_E_SIZE,
                                     "abrdf_params: struct_size %zu is below its 0.2.0 layout",
                                     params->struct_size);
    abrdf_params p = best->p;
    size_t size = params->struct_size;
    p.struct_size = size;
    memcpy(params, &p, size < sizeof p ? size : sizeof p);
    return ABRDF_OK;
}

int abrdf_select_budget(const abrdf_material *m, const abrdf_budget *budget,
                        const abrdf_costs *costs, abrdf_selection *out, abrdf_params *params,
                        abrdf_select_trace_fn trace, void *trace_user, void *work, size_t work_size)
{
    if (!out) return ABRDF_E_NULL;
    if (out->struct_size < SELECTION_SIZE_0_2) return ABRDF_E_SIZE;
    abrdf_selection sel;
    abrdf_selection_init(&sel);
    int st = ABRDF_OK;
    budget_state bs;
    bs.w = (bwalk){trace, trace_user, 0};
    budget_best best;
    if (!m || !work) {
        st = abrdf__selection_fail(&sel, ABRDF_E_NULL, "abrdf_select_budget: %s is NULL",
                                   m ? "the workspace" : "the material");
        goto done;
    }
    if ((st = budget_read(budget, &bs.b, &sel)) != ABRDF_OK) goto done;
    bs.costs = costs;
    if (!costs) {
        abrdf_costs_builtin(&bs.builtin);
        bs.costs = &bs.builtin;
    }
    if ((st = reference_prepare(&bs, m, &sel, work, work_size)) != ABRDF_OK) goto done;
    budget_text(bs.b.max_nmse, bs.bt, sizeof bs.bt);
    bs.ref_cost = bs.ref.prepared ? (bs.b.reference_cost >= 0.0 ? bs.b.reference_cost : -1.0)
                                  : pair_cost(bs.costs, bs.ref.lobe, &bs.ref.p);
    trace_reference(&bs);
    strcpy(bs.unit, "units");
    if (bs.costs->unit) sscanf(bs.costs->unit, "%31s", bs.unit);
    if ((st = candidates_run(&bs, &best, &sel)) != ABRDF_OK) goto done;
    trace_choice(&bs, &best);
    selection_fill(&sel, &best, bs.costs);
    if (params) st = params_copy(params, &best.brdf, &sel);
done:
    sel.step_count = bs.w.steps;
    {
        size_t size = out->struct_size;
        sel.struct_size = size;
        memcpy(out, &sel, size < sizeof sel ? size : sizeof sel);
    }
    return st;
}
