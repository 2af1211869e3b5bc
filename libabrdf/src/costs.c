/* costs.c - the default cost model: the paper's Table 4 (cycles on an AMD Zen 4 core,
 * ADD 1, MUL 3, DIV 10), read from the registry's paper_cycles so the numbers live in one
 * place. A measured calibration (abrdf calibrate) replaces it in the tool. */
#include "abrdf_internal.h"

int abrdf_costs_paper(abrdf_costs *out)
{
    if (!out) return ABRDF_E_NULL;
    for (int i = 0; i < ABRDF_MODEL_COUNT; ++i) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        out->cost[i] = (m && m->paper_cycles >= 0) ? (double)m->paper_cycles : -1.0;
    }
    out->unit = "cycles (paper Table 4, AMD Zen 4)";
    return ABRDF_OK;
}
