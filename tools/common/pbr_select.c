/* pbr_select.c - the flowchart over a roughness map (pbr_select.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pbr_select.h"

#define MODEL_BITS 64 /* candidate models tracked in a mask (Table-1 ids are far below) */

/* One value's selection, and what it says about the Table-1 candidates. */
typedef struct value_choice {
    abrdf_model diffuse, specular;
    int reference;             /* the branch predicts no error: the surface's reference */
    unsigned long long passed; /* candidates that pass the tolerances here (bit = model id) */
} value_choice;

/* The worst errors and the cost of each candidate over the values. */
typedef struct candidate_worst {
    double rel[MODEL_BITS], abs[MODEL_BITS], cost[MODEL_BITS];
} candidate_worst;

static int select_at(const abrdf_pbr *p, double r, abrdf_goal goal, const abrdf_tolerance *tol,
                     const abrdf_costs *costs, abrdf_selection *sel, abrdf_params *params,
                     select_trace *trace, char *msg, size_t msg_size)
{
    abrdf_pbr q = *p;
    q.roughness = r;
    abrdf_material am;
    abrdf_material_init(&am);
    if (abrdf_pbr_material(&q, &am) != ABRDF_OK) {
        abrdf_pbr_check(&q, msg, msg_size);
        return -1;
    }
    abrdf_selection_init(sel);
    abrdf_params_init(ABRDF_MODEL_NONE, params);
    if (abrdf_select(&am, goal, tol, costs, sel, params, select_trace_keep, trace) != ABRDF_OK) {
        snprintf(msg, msg_size, "%s", sel->message);
        return -1;
    }
    if (trace->lost) {
        snprintf(msg, msg_size, "out of memory");
        return -1;
    }
    return 0;
}

/* The value's choice, and its candidates folded into w. */
static void note_value(const abrdf_selection *sel, const select_trace *t, value_choice *c,
                       candidate_worst *w)
{
    c->diffuse = sel->diffuse, c->specular = sel->specular;
    c->reference = sel->err_rel_pct < 0 && sel->err_abs < 0 && sel->err_nmse < 0;
    c->passed = 0;
    for (int k = 0; k < t->count; ++k) {
        const abrdf_select_step *st = &t->steps[k];
        if (st->kind != ABRDF_STEP_CANDIDATE || st->model < 0 || st->model >= MODEL_BITS) continue;
        if (st->passed) c->passed |= 1ull << st->model;
        w->rel[st->model] = fmax(w->rel[st->model], st->value);
        w->abs[st->model] = fmax(w->abs[st->model], st->value2);
        w->cost[st->model] = st->cost;
    }
}

static const char *name_of(abrdf_model m)
{
    const abrdf_model_info *mi = abrdf_model_get(m);
    return mi ? mi->name : "none";
}

/* "lambert + f8" */
static void pair_name(abrdf_model d, abrdf_model s, char *buf, size_t size)
{
    if (d == ABRDF_MODEL_NONE)
        snprintf(buf, size, "%s", name_of(s));
    else
        snprintf(buf, size, "%s + %s", name_of(d), name_of(s));
}

/* The weighted median among the values with keep[i] (all if keep is NULL). */
static int median_of(const pbr_range *range, const int *keep)
{
    double total = 0;
    for (int i = 0; i < range->count; ++i)
        if (!keep || keep[i]) total += range->share[i];
    int best = -1;
    for (int i = 0; i < range->count; ++i) {
        if (keep && !keep[i]) continue;
        double below = 0; /* share of the values below r[i] */
        for (int j = 0; j < range->count; ++j)
            if ((!keep || keep[j]) && range->r[j] < range->r[i]) below += range->share[j];
        /* the smallest r whose cumulative share reaches half */
        if (below + range->share[i] >= 0.5 * total && (best < 0 || range->r[i] < range->r[best]))
            best = i;
    }
    if (best < 0) /* every share 0: the middle value */
        for (int i = 0; i < range->count; ++i)
            if (!keep || keep[i]) best = best < 0 || range->r[i] < range->r[best] ? i : best;
    return best;
}

/* The step that states the range and the branch taken. */
static void add_step(select_trace *trace, abrdf_model model, double lo, double hi, const char *text)
{
    abrdf_select_step st;
    memset(&st, 0, sizeof st);
    st.kind = ABRDF_STEP_ROUGHNESS;
    st.model = model;
    st.value = lo, st.value2 = hi;
    st.threshold = st.threshold2 = -1;
    st.cost = -1;
    st.passed = 1;
    st.text = text;
    st.diffuse = ABRDF_MODEL_NONE;
    select_trace_keep(trace, &st);
}

int pbr_select_range(const abrdf_pbr *p, const pbr_range *range, abrdf_goal goal,
                     const abrdf_tolerance *tol, const abrdf_costs *costs, abrdf_selection *sel,
                     abrdf_params *params, select_trace *trace, char *msg, size_t msg_size)
{
    if (!range || range->count < 1 || range->count > PBR_RANGE_MAX) {
        snprintf(msg, msg_size, "a roughness range needs 1 to %d values", PBR_RANGE_MAX);
        return -1;
    }
    value_choice vc[PBR_RANGE_MAX];
    candidate_worst worst;
    for (int m = 0; m < MODEL_BITS; ++m) worst.rel[m] = worst.abs[m] = 0, worst.cost[m] = -1;
    double lo = 1, hi = 0;
    for (int i = 0; i < range->count; ++i) {
        select_trace t = SELECT_TRACE_INIT;
        abrdf_selection s;
        abrdf_params pr;
        if (!(range->r[i] >= 0 && range->r[i] <= 1) || !(range->share[i] >= 0)) {
            snprintf(msg, msg_size, "%s: roughness %g (share %g) outside [0, 1]",
                     range->what ? range->what : "roughness map", range->r[i], range->share[i]);
            return -1;
        }
        int rc = select_at(p, range->r[i], goal, tol, costs, &s, &pr, &t, msg, msg_size);
        if (!rc) note_value(&s, &t, &vc[i], &worst);
        select_trace_free(&t);
        if (rc) return -1;
        lo = fmin(lo, range->r[i]), hi = fmax(hi, range->r[i]);
    }
    /* the distinct branches, with their shares and roughness spans */
    int group_of[PBR_RANGE_MAX], groups = 0, first[PBR_RANGE_MAX];
    double share[PBR_RANGE_MAX], glo[PBR_RANGE_MAX], ghi[PBR_RANGE_MAX], total = 0;
    for (int i = 0; i < range->count; ++i) {
        int g = 0;
        while (g < groups &&
               !(vc[first[g]].diffuse == vc[i].diffuse && vc[first[g]].specular == vc[i].specular))
            ++g;
        if (g == groups) first[g] = i, share[g] = 0, glo[g] = 1, ghi[g] = 0, ++groups;
        group_of[i] = g;
        share[g] += range->share[i], total += range->share[i];
        glo[g] = fmin(glo[g], range->r[i]), ghi[g] = fmax(ghi[g], range->r[i]);
    }
    const char *what = range->what ? range->what : "roughness map";
    char text[1024], pair[96];
    int keep[PBR_RANGE_MAX], chosen = 0;
    abrdf_model perf_model = ABRDF_MODEL_NONE;
    if (groups == 1) {
        pair_name(vc[0].diffuse, vc[0].specular, pair, sizeof pair);
        snprintf(text, sizeof text,
                 "%s: r from %.4g to %.4g over the texels: every value takes "
                 "the same branch, %s",
                 what, lo, hi, pair);
    } else {
        /* which values went which way */
        char ways[640] = "";
        for (int g = 0; g < groups; ++g) {
            char one[160];
            pair_name(vc[first[g]].diffuse, vc[first[g]].specular, pair, sizeof pair);
            snprintf(one, sizeof one, "%sr %.4g..%.4g (%.0f%% of texels): %s", g ? "; " : "",
                     glo[g], ghi[g], total > 0 ? 100 * share[g] / total : 0.0, pair);
            strncat(ways, one, sizeof ways - strlen(ways) - 1);
        }
        if (goal == ABRDF_GOAL_PERFORMANCE) {
            unsigned long long all = ~0ull;
            for (int i = 0; i < range->count; ++i) all &= vc[i].passed;
            double best = INFINITY;
            for (int m = 0; m < MODEL_BITS; ++m)
                if ((all >> m) & 1u && worst.cost[m] >= 0 && worst.cost[m] < best)
                    best = worst.cost[m], perf_model = (abrdf_model)m;
            if (perf_model == ABRDF_MODEL_NONE) perf_model = ABRDF_BLINN_PHONG;
            snprintf(text, sizeof text,
                     "%s: r from %.4g to %.4g crosses the flowchart's "
                     "thresholds (%s); the safe branch: %s, %s",
                     what, lo, hi, ways, name_of(perf_model),
                     perf_model == ABRDF_BLINN_PHONG
                         ? "no approximation passes at every value (Blinn-Phong, the reference)"
                         : "the cheapest approximation that passes at every value");
        } else {
            chosen = -1;
            for (int g = 0; g < groups && chosen < 0; ++g)
                if (vc[first[g]].reference) chosen = g;
            int by_reference = chosen >= 0;
            if (!by_reference) /* no reference branch among them: the most texels' */
                for (int g = 0; g < groups; ++g)
                    if (chosen < 0 || share[g] > share[chosen]) chosen = g;
            pair_name(vc[first[chosen]].diffuse, vc[first[chosen]].specular, pair, sizeof pair);
            snprintf(text, sizeof text,
                     "%s: r from %.4g to %.4g crosses the flowchart's "
                     "thresholds (%s); the safe branch: %s for every texel, %s",
                     what, lo, hi, ways, pair,
                     by_reference ? "the surface's reference model, exact on the other side too"
                                  : "the branch of most texels (no reference branch among them)");
        }
    }
    for (int i = 0; i < range->count; ++i)
        keep[i] = groups == 1 || group_of[i] == chosen || goal == ABRDF_GOAL_PERFORMANCE;
    int med = median_of(range, keep);
    if (select_at(p, range->r[med], goal, tol, costs, sel, params, trace, msg, msg_size)) {
        select_trace_free(trace);
        return -1;
    }
    if (perf_model != ABRDF_MODEL_NONE) { /* the approximation that covers every value */
        abrdf_costs paper;
        abrdf_costs_paper(&paper);
        const abrdf_costs *c = costs ? costs : &paper;
        sel->specular = perf_model;
        int exact = perf_model == ABRDF_BLINN_PHONG;
        sel->err_rel_pct = exact ? 0 : worst.rel[perf_model];
        sel->err_abs = exact ? 0 : worst.abs[perf_model];
        sel->cost_specular = abrdf_costs_get(c, perf_model);
        sel->cost_total = sel->cost_specular >= 0 && sel->cost_diffuse >= 0
                              ? sel->cost_specular + sel->cost_diffuse
                              : -1;
    }
    add_step(trace, sel->specular, lo, hi, text);
    if (trace->lost) {
        select_trace_free(trace);
        snprintf(msg, msg_size, "out of memory");
        return -1;
    }
    return 0;
}
