/* sampler_efficiency.c - how well each model's sampler fits its f_r cos (docs/RENDERER.md,
 * "Importance sampling"): per model (its default parameters) and view angle, the share of
 * samples below the surface, the relative second moment E[w^2]/E[w]^2 of the weight w = f cos
 * / pdf (1 for a sampler proportional to f cos) and the variance of the albedo estimate by
 * cosine-weighted
 * sampling divided by the model's own sampler's (how many times fewer samples the sampler
 * needs for the same noise). Green channel; fixed seeds, so the output repeats.
 *
 *   sampler_efficiency [--quick]      (--quick: a tenth of the samples)
 *
 * Samples per estimate: 2e5, marschner 2e4, huang 1000 (its f_r costs ~2.5 ms). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "abrdf.h"

static double uniform(uint64_t *s) /* SplitMix64, top 53 bits */
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct moments {
    double m1, m2, below;
} moments;

/* Moments of the weight of `sampler_model`'s sampler used for `model`'s f_r. */
static moments measure(abrdf_model model, abrdf_model sampler_model, const abrdf_params *p,
                       const double wo[3], long n, uint64_t seed)
{
    abrdf_params sp;
    abrdf_params_init(sampler_model, &sp);
    const abrdf_params *use = sampler_model == model ? p : &sp;
    abrdf_sample_result r;
    abrdf_sample_result_init(&r);
    moments m = {0, 0, 0};
    for (long i = 0; i < n; ++i) {
        double u1 = uniform(&seed), u2 = uniform(&seed), f[3];
        abrdf_sample(sampler_model, use, NULL, wo, u1, u2, &r);
        double w = r.weight[1];
        if (sampler_model != model) { /* re-weight the cosine sample for model's f_r */
            abrdf_eval(model, p, NULL, r.wi, wo, f);
            w = r.pdf > 0.0 ? f[1] * fmax(r.wi[2], 0.0) / r.pdf : 0.0;
        }
        m.m1 += w;
        m.m2 += w * w;
        m.below += r.wi[2] <= 0.0;
    }
    m.m1 /= n;
    m.m2 /= n;
    m.below /= n;
    return m;
}

int main(int argc, char **argv)
{
    int quick = argc > 1 && !strcmp(argv[1], "--quick");
    static const double thetas[2] = {30.0, 75.0};
    printf("| model | sampler | below, 30° | E[w²]/E[w]², 30° | variance: cosine / own, 30° | "
           "below, 75° | E[w²]/E[w]², 75° | variance: cosine / own, 75° |\n");
    printf("|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < abrdf_model_count(); ++i) {
        abrdf_model model = (abrdf_model)i;
        const abrdf_model_info *info = abrdf_model_get(model);
        if (!info) continue;
        long n = !strcmp(info->name, "huang")       ? 1000
                 : !strcmp(info->name, "marschner") ? 20000
                                                    : 200000;
        if (quick) n /= 10;
        abrdf_params p;
        abrdf_params_init(model, &p);
        printf("| %s | %s |", info->name, abrdf_model_sampler(model)->name);
        for (int t = 0; t < 2; ++t) {
            double th = thetas[t] * 3.14159265358979323846 / 180.0;
            double wo[3] = {sin(th) * cos(0.7), sin(th) * sin(0.7), cos(th)};
            moments own = measure(model, model, &p, wo, n, 1000u + (uint64_t)i);
            moments cos = measure(model, ABRDF_LAMBERT, &p, wo, n, 1000u + (uint64_t)i);
            double r_own = own.m1 > 0.0 ? own.m2 / (own.m1 * own.m1) : 0.0;
            double r_cos = cos.m1 > 0.0 ? cos.m2 / (cos.m1 * cos.m1) : 0.0;
            /* the means agree; the variances are m1^2 (r - 1); "exact": no variance left */
            printf(" %.1f%% | %.3g |", 100.0 * own.below, r_own);
            if (r_own - 1.0 > 1e-12)
                printf(" %.3g |", (r_cos - 1.0) / (r_own - 1.0));
            else
                printf(" exact |");
        }
        printf("\n");
    }
    return 0;
}
