/* costs_builtin.c - the built-in cost table of the budget selection (abrdf_fit.h): the cost of
 * every model in ns per evaluation on the float batch path, as `abrdf calibrate` measured it
 * (median of 7 repetitions, CPU-time clock, default parameters) on the machine named in the
 * unit string. A calibration of the host (abrdf calibrate -o FILE; abrdf advise --costs FILE)
 * replaces it; the paper's Table 4 (abrdf_costs_paper) lists only the Table-1 approximations,
 * too few for the budget's candidates. tests/unit/test_fit.c checks that every registered
 * model has an entry. */
#include <stddef.h>

#include "abrdf_fit.h"

typedef struct builtin_cost {
    const char *model; /* stable model name */
    double ns;         /* ns per evaluation */
} builtin_cost;

/* abrdf calibrate, AMD EPYC (x86_64, 2 logical cpus), 2026-11-25 */
static const builtin_cost table[] = {
    {"lambert", 1.017},
    {"lambert_fresnel", 2.76},
    {"disney_diffuse", 2.431},
    {"oren_nayar", 1.617},
    {"phong", 14.04},
    {"blinn_phong", 19.4},
    {"f2", 1.904},
    {"f4", 1.982},
    {"f8", 2.068},
    {"f16", 2.218},
    {"fs", 2.838},
    {"fkv", 2.473},
    {"fkub", 4.016},
    {"f_phe", 14.16},
    {"f_be", 19.83},
    {"f_2e", 1.289},
    {"f_16e", 1.497},
    {"f_ge", 22.03},
    {"f_ctphe", 23.62},
    {"f_ct2e", 3.622},
    {"f_ct16e", 4.118},
    {"cook_torrance", 22.91},
    {"disney_specular", 4.121},
    {"disney_specular_aniso", 4.619},
    {"disney_clearcoat", 3.647},
    {"neubelt_pettineo", 22.64},
    {"kajiya_kay", 15.8},
    {"marschner", 3783},
    {"huang", 7.75e+05},
    {"weidlich_wilkie", 101.1},
    {"belcour", 398.9},
};

int abrdf_costs_builtin(abrdf_costs *out)
{
    if (!out) return ABRDF_E_NULL;
    abrdf_costs_init(out, "ns/eval (built-in: abrdf calibrate on an AMD EPYC, x86_64)");
    for (size_t i = 0; i < sizeof table / sizeof table[0]; ++i) {
        abrdf_model m;
        if (abrdf_model_find(table[i].model, &m) == ABRDF_OK) abrdf_costs_set(out, m, table[i].ns);
    }
    return ABRDF_OK;
}
