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

/* abrdf calibrate, Intel Xeon (x86_64, 2 logical cpus, AVX-512), 2026-11-28: the median of
 * eight runs of 7 repetitions each (single runs differ from it by up to 2x on this shared machine) */
static const builtin_cost table[] = {
    {"lambert", 0.8934},
    {"lambert_fresnel", 0.8692},
    {"disney_diffuse", 0.8472},
    {"oren_nayar", 1.308},
    {"phong", 1.823},
    {"blinn_phong", 2.287},
    {"f2", 0.9725},
    {"f4", 1.067},
    {"f8", 1.003},
    {"f16", 1.141},
    {"fs", 0.8296},
    {"fkv", 0.7973},
    {"fkub", 0.9733},
    {"f_phe", 1.756},
    {"f_be", 2.495},
    {"f_2e", 1.266},
    {"f_16e", 1.343},
    {"f_ge", 4.342},
    {"f_ctphe", 3.06},
    {"f_ct2e", 1.185},
    {"f_ct16e", 1.84},
    {"cook_torrance", 3.506},
    {"disney_specular", 1.888},
    {"disney_specular_aniso", 2.247},
    {"disney_clearcoat", 1.72},
    {"neubelt_pettineo", 3.002},
    {"kajiya_kay", 2.701},
    {"marschner", 2336},
    {"huang", 7.352e+05},
    {"weidlich_wilkie", 92.92},
    {"belcour", 410.8},
    /* the measured model: a MERL-size table (tools/bench/measure.c, bench_table), measured
     * later the same day with its vectorised lookup, the same eight-run median */
    {"measured", 18.21},
};

int abrdf_costs_builtin(abrdf_costs *out)
{
    if (!out) return ABRDF_E_NULL;
    abrdf_costs_init(out, "ns/eval (built-in: abrdf calibrate on an Intel Xeon, x86_64)");
    for (size_t i = 0; i < sizeof table / sizeof table[0]; ++i) {
        abrdf_model m;
        if (abrdf_model_find(table[i].model, &m) == ABRDF_OK) abrdf_costs_set(out, m, table[i].ns);
    }
    return ABRDF_OK;
}
