/* cost_of.c - the cost of one model at the parameters a material gives it, on this machine:
 * ns per evaluation on the float batch path (abrdf_eval_batch) and per call through
 * abrdf_eval_prepared_unit (double) and abrdf_eval_prepared_float (and, for disney_specular,
 * abrdf_inline.h's abrdf_ggx_float_eval), each beside the powf Blinn-Phong unit timed in the same run
 * (measure.h: 4096 fixed-seed front-facing pairs warm in cache, median of the repetitions).
 * `abrdf calibrate` and `abrdf bench` time the models at their defaults only; a layered
 * stack, a hair colour or a roughness is measured here.
 *
 *   cost_of MODEL [--set NAME=VALUE ...] [--reps N]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf.h"
#include "cli_args.h"
#include "measure.h"

int main(int argc, char **argv)
{
    const char *cmd = "cost_of";
    if (argc < 2) return cli_fail(cmd, "usage: MODEL [--set NAME=VALUE ...] [--reps N]");
    abrdf_model m;
    if (cli_model(cmd, argv[1], &m)) return CLI_EXIT_USAGE;
    abrdf_params p;
    abrdf_params_init(m, &p);
    measure_opts o;
    measure_defaults(&o, 0);
    for (int i = 2; i < argc; ++i) {
        if (!strcmp(argv[i], "--set") && i + 1 < argc) {
            if (cli_set_param(cmd, m, &p, argv[++i])) return CLI_EXIT_USAGE;
        } else if (!strcmp(argv[i], "--reps") && i + 1 < argc) {
            char *end;
            long r = strtol(argv[++i], &end, 10);
            if (*end || r < 1 || r > 1000)
                return cli_fail(cmd, "--reps must be an integer in [1, 1000], not '%s'", argv[i]);
            o.reps = (int)r;
        } else
            return cli_fail(cmd, "unknown argument '%s'", argv[i]);
    }
    char msg[256];
    if (abrdf_params_check(m, &p, msg, sizeof msg) != ABRDF_OK)
        return cli_fail(cmd, "%s: %s", argv[1], msg);
    measure_set *s = measure_set_new(o.pairs);
    if (!s) return cli_fail(cmd, "out of memory");
    double unit = measure_unit_ns(s, &o);
    double fl = measure_model_params_ns(s, m, &p, 0, &o);
    double per = measure_model_params_ns(s, m, &p, 3, &o);
    double per_f = measure_model_params_ns(s, m, &p, 4, &o);
    double inl = m == ABRDF_DISNEY_SPECULAR ? measure_model_params_ns(s, m, &p, 5, &o) : 0.0;
    measure_set_free(s);
    if (unit <= 0.0 || fl < 0.0 || per < 0.0 || per_f < 0.0 || inl < 0.0)
        return cli_fail(cmd, "timing failed");
    printf("%s: float batch %.4g ns/eval (%.3g units), per call (abrdf_eval_prepared_unit) "
           "%.4g ns (%.3g units), per float call (abrdf_eval_prepared_float) %.4g ns (%.3g "
           "units)",
           abrdf_model_get(m)->name, fl, fl / unit, per, per / unit, per_f, per_f / unit);
    if (m == ABRDF_DISNEY_SPECULAR)
        printf(", inlined (abrdf_ggx_float_eval) %.4g ns (%.3g units)", inl, inl / unit);
    printf("; unit (powf Blinn-Phong loop) %.4g ns, median of %d\n", unit, o.reps);
    return 0;
}
