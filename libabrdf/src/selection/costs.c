/* costs.c - the cost model: a table of per-model costs (abrdf_select.h) and its default, the
 * paper's Table 4 (cycles on an AMD Zen 4 core, ADD 1, MUL 3, DIV 10), read from the
 * registry's paper_cycles so the numbers live in one place. A measured calibration
 * (abrdf calibrate) replaces it in the tool. */
#include <math.h>

#include "abrdf_internal.h"
#include "abrdf_select.h"
#include "hair.h" /* the default Huang grids */

/* The table's capacity is frozen; the registry must fit in it (compile-time check). */
typedef char
    abrdf__costs_capacity_holds_every_model[ABRDF_MODEL_COUNT <= ABRDF_COSTS_CAPACITY ? 1 : -1];

static int in_table(abrdf_model model) { return (int)model >= 0 && model < ABRDF_COSTS_CAPACITY; }

int abrdf_costs_init(abrdf_costs *c, const char *unit)
{
    if (!c) return ABRDF_E_NULL;
    for (int i = 0; i < ABRDF_COSTS_CAPACITY; ++i) c->cost[i] = -1.0;
    c->unit = unit;
    return ABRDF_OK;
}

int abrdf_costs_set(abrdf_costs *c, abrdf_model model, double cost)
{
    if (!c) return ABRDF_E_NULL;
    if (!in_table(model)) return ABRDF_E_MODEL;
    if (!isfinite(cost)) return ABRDF_E_RANGE;
    c->cost[model] = cost < 0.0 ? -1.0 : cost;
    return ABRDF_OK;
}

double abrdf_costs_get(const abrdf_costs *c, abrdf_model model)
{
    return c && in_table(model) ? c->cost[model] : -1.0;
}

static double huang_nodes(double n1, double n2) { return n1 * n1 * (1.0 + n2 * n2); }

double abrdf__cost_scale(abrdf_model model, const abrdf_params *p)
{
    if (model != ABRDF_HUANG || !p) return 1.0;
    return huang_nodes(p->entry_grid, p->internal_grid) /
           huang_nodes(ABRDF__HUANG_N1, ABRDF__HUANG_N2);
}

int abrdf_costs_paper(abrdf_costs *out)
{
    if (!out) return ABRDF_E_NULL;
    abrdf_costs_init(out, "cycles (paper Table 4, AMD Zen 4)");
    for (int i = 0; i < ABRDF_MODEL_COUNT; ++i) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        if (m && m->paper_cycles >= 0) out->cost[i] = (double)m->paper_cycles;
    }
    return ABRDF_OK;
}
