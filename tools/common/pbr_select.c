/* pbr_select.c - the flowchart over a roughness map (pbr_select.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "budget_run.h"
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

/* ---- the budget mode over a map ---------------------------------------------------------- */

typedef struct group {
    double r, share;
} group;

/* The values (share > 0) in r order, cut into at most PBR_BUDGET_GROUPS groups of about equal
 * share, each at its share-weighted mean r. Returns the count. */
static int quantile_groups(const pbr_range *range, group *g)
{
    int order[PBR_RANGE_MAX], n = 0;
    double total = 0;
    for (int i = 0; i < range->count; ++i)
        if (range->share[i] > 0) order[n++] = i, total += range->share[i];
    for (int a = 1; a < n; ++a) /* insertion sort by r */
        for (int b = a; b > 0 && range->r[order[b]] < range->r[order[b - 1]]; --b) {
            int t = order[b];
            order[b] = order[b - 1], order[b - 1] = t;
        }
    int count = 0;
    double acc = 0, sum_r = 0, sum_w = 0;
    for (int k = 0; k < n; ++k) {
        int i = order[k];
        acc += range->share[i];
        sum_r += range->share[i] * range->r[i], sum_w += range->share[i];
        int last = k == n - 1;
        if (last ||
            (count < PBR_BUDGET_GROUPS - 1 && acc >= total * (count + 1) / PBR_BUDGET_GROUPS)) {
            g[count].r = sum_r / sum_w, g[count].share = sum_w / total;
            ++count, sum_r = sum_w = 0;
        }
    }
    return count;
}

typedef struct pair_stats {
    abrdf_model d, s;
    double nmse[PBR_BUDGET_GROUPS], cost, combined;
    int seen;
    abrdf_params params[PBR_BUDGET_GROUPS]; /* fitted at each group */
} pair_stats;

int pbr_budget_range(const abrdf_pbr *p, const pbr_range *range, double max_nmse,
                     const abrdf_costs *costs, const abrdf_view *view, pbr_budget_choice *out,
                     select_trace *trace, char *msg, size_t msg_size)
{
    return pbr_budget_range_at(p, range, max_nmse, 0, costs, view, out, trace, msg, msg_size);
}

int pbr_budget_range_at(const abrdf_pbr *p, const pbr_range *range, double max_nmse, int resolution,
                        const abrdf_costs *costs, const abrdf_view *view, pbr_budget_choice *out,
                        select_trace *trace, char *msg, size_t msg_size)
{
    group g[PBR_BUDGET_GROUPS];
    int ng =
        range && range->count >= 1 && range->count <= PBR_RANGE_MAX ? quantile_groups(range, g) : 0;
    if (ng < 1) {
        snprintf(msg, msg_size, "a roughness range needs values with shares > 0");
        return -1;
    }
    const char *what = range->what ? range->what : "roughness map";
    enum { MAX_PAIRS = 32 };
    pair_stats *pairs = malloc(MAX_PAIRS * sizeof *pairs); /* ~150 KB: not on the stack */
    if (!pairs) {
        snprintf(msg, msg_size, "out of memory");
        return -1;
    }
    int np = 0, median = 0;
    double below = 0;
    for (int k = 0; k < ng; ++k) { /* the group holding the median texel */
        if (below < 0.5) median = k;
        below += g[k].share;
    }
    memset(out, 0, sizeof *out);
    for (int k = 0; k < ng; ++k) {
        abrdf_pbr q = *p;
        q.roughness = fmin(fmax(g[k].r, 0.0), 1.0);
        abrdf_material am;
        abrdf_material_init(&am);
        if (abrdf_pbr_material(&q, &am) != ABRDF_OK) {
            abrdf_pbr_check(&q, msg, msg_size);
            free(pairs);
            return -1;
        }
        budget_result res;
        if (budget_run_at(&am, max_nmse, resolution, costs, view, &res, msg, msg_size)) {
            free(pairs);
            return -1;
        }
        out->unit = res.sel.cost_unit;
        const abrdf_select_step *cand[64];
        int nc = budget_candidates(&res, cand, 64);
        for (int c = 0; c < nc; ++c) {
            int j = 0;
            while (j < np && !(pairs[j].d == cand[c]->diffuse && pairs[j].s == cand[c]->model)) ++j;
            if (j == np) {
                if (k > 0 || np == MAX_PAIRS) continue; /* a pair the first group did not fit */
                memset(&pairs[np], 0, sizeof pairs[np]);
                pairs[np].d = cand[c]->diffuse, pairs[np].s = cand[c]->model, ++np;
            }
            if (pairs[j].seen != k) continue; /* one fit per group */
            pairs[j].nmse[k] = cand[c]->value, pairs[j].cost = cand[c]->cost, ++pairs[j].seen;
            if (cand[c]->params)
                pairs[j].params[k] = *cand[c]->params;
            else
                abrdf_params_init(ABRDF_MODEL_NONE, &pairs[j].params[k]);
        }
        char text[256];
        snprintf(text, sizeof text,
                 "%s: budget at r %.4g (%.0f%% of the texels): the "
                 "reference there is %s%s%s",
                 what, g[k].r, 100 * g[k].share,
                 res.sel.diffuse != ABRDF_MODEL_NONE && nc ? name_of(cand[0]->diffuse) : "",
                 res.sel.diffuse != ABRDF_MODEL_NONE && nc ? " + " : "",
                 nc ? name_of(cand[0]->model) : "none");
        add_step(trace, nc ? cand[0]->model : ABRDF_MODEL_NONE, g[k].r, g[k].r, text);
        budget_result_free(&res);
    }
    /* each pair fitted at every group: its prediction over the map */
    int best = -1;
    for (int j = 0; j < np; ++j) {
        if (pairs[j].seen != ng) continue;
        pairs[j].combined = 0;
        for (int k = 0; k < ng; ++k) pairs[j].combined += g[k].share * pairs[j].nmse[k];
        int within = pairs[j].combined < max_nmse && pairs[j].cost >= 0;
        char text[320], pair[96];
        pair_name(pairs[j].d, pairs[j].s, pair, sizeof pair);
        snprintf(text, sizeof text,
                 "%s: %s predicts NMSE %.3g over the map (the texels' "
                 "share-weighted mean: texels of equal reference energy), cost %.3g: %s",
                 what, pair, pairs[j].combined, pairs[j].cost,
                 within ? "within" : "over the budget");
        add_step(trace, pairs[j].s, pairs[j].combined, max_nmse, text);
        if (within && (best < 0 || pairs[j].cost < pairs[best].cost)) best = j;
    }
    if (best >= 0) { /* of the pairs within 15 % of the cheapest's cost, the lowest NMSE */
        double limit = pairs[best].cost * 1.15;
        for (int j = 0; j < np; ++j)
            if (pairs[j].seen == ng && pairs[j].combined < max_nmse && pairs[j].cost >= 0 &&
                pairs[j].cost <= limit && pairs[j].combined < pairs[best].combined)
                best = j;
    }
    char text[512], pair[96];
    out->groups = ng;
    for (int k = 0; k < ng; ++k) out->group_r[k] = g[k].r;
    if (best >= 0) {
        out->diffuse = pairs[best].d, out->specular = pairs[best].s;
        out->params = pairs[best].params[median];
        for (int k = 0; k < ng; ++k) out->group_params[k] = pairs[best].params[k];
        out->nmse = pairs[best].combined, out->cost = pairs[best].cost, out->within = 1;
        pair_name(out->diffuse, out->specular, pair, sizeof pair);
        snprintf(text, sizeof text,
                 "%s: the cheapest pair within NMSE %g over the map: %s "
                 "(predicted %.3g)",
                 what, max_nmse, pair, out->nmse);
    } else {
        abrdf_selection sel;
        select_trace t = SELECT_TRACE_INIT;
        int rc = pbr_select_range(p, range, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, &out->params,
                                  &t, msg, msg_size);
        select_trace_free(&t);
        for (int k = 0; k < ng && !rc; ++k) { /* the photoreal choice's block at each r */
            abrdf_pbr q = *p;
            q.roughness = fmin(fmax(g[k].r, 0.0), 1.0);
            abrdf_material am;
            abrdf_selection sk;
            abrdf_material_init(&am);
            abrdf_selection_init(&sk);
            abrdf_params_init(ABRDF_MODEL_NONE, &out->group_params[k]);
            rc = abrdf_pbr_material(&q, &am) != ABRDF_OK ||
                 abrdf_select(&am, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sk, &out->group_params[k],
                              NULL, NULL) != ABRDF_OK;
            if (rc) snprintf(msg, msg_size, "%s", sk.message);
        }
        if (rc) {
            free(pairs);
            return -1;
        }
        out->diffuse = sel.diffuse, out->specular = sel.specular;
        out->nmse = 0, out->cost = -1, out->within = 0;
        pair_name(out->diffuse, out->specular, pair, sizeof pair);
        snprintf(text, sizeof text,
                 "%s: no pair fitted at every value is within NMSE %g over "
                 "the map: the photoreal choice over it, %s",
                 what, max_nmse, pair);
    }
    free(pairs);
    add_step(trace, out->specular, out->nmse, max_nmse, text);
    if (trace->lost) {
        snprintf(msg, msg_size, "out of memory");
        return -1;
    }
    return 0;
}
