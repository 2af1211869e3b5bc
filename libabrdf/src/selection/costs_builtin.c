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

/* abrdf calibrate, AMD EPYC (x86_64, 2 logical cpus, AVX-512), 2026-11-29: the median of eight
 * runs of 7 repetitions each, the machine otherwise idle (the runs agree within 3 %; the
 * measured model's within 25 %). disney_specular and belcour: the median of three later runs,
 * after their kernels got cheaper (disney_specular 0.897-0.898, belcour 105.5-117.3) */
static const builtin_cost table[] = {
    {"lambert", 0.2214},
    {"lambert_fresnel", 0.759},
    {"disney_diffuse", 0.6951},
    {"oren_nayar", 0.5209},
    {"phong", 1.13},
    {"blinn_phong", 1.371},
    {"f2", 0.5399},
    {"f4", 0.5533},
    {"f8", 0.5717},
    {"f16", 0.6542},
    {"fs", 0.6297},
    {"fkv", 0.6112},
    {"fkub", 0.9434},
    {"f_phe", 1.158},
    {"f_be", 1.367},
    {"f_2e", 0.4993},
    {"f_16e", 0.487},
    {"f_ge", 1.884},
    {"f_ctphe", 1.767},
    {"f_ct2e", 0.798},
    {"f_ct16e", 0.8886},
    {"cook_torrance", 1.984},
    {"disney_specular", 0.8979},
    {"disney_specular_aniso", 1.335},
    {"disney_clearcoat", 1.22},
    {"neubelt_pettineo", 2.138},
    {"kajiya_kay", 2.14},
    {"marschner", 507.9},
    {"huang", 2.51e+05},
    {"weidlich_wilkie", 10.66},
    {"belcour", 105.8},
    /* the measured model: a MERL-size table (tools/bench/measure.c, bench_table) */
    {"measured", 20.69},
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
