/* metrics.c - NMSE and companions (Zavalniuk & Romanyuk 2024, Sec. 4 and Table 8). */
#include "metrics.h"

#include <math.h>
#include <stddef.h>

int abrdf_metrics_compute(const float *test, const float *ref, int width, int height, int channels,
                          abrdf_metrics *m)
{
    if (!m) return ABRDF_METRICS_BAD_ARGS;
    *m = (abrdf_metrics){0};
    if (!test || !ref || width <= 0 || height <= 0 || channels <= 0) return ABRDF_METRICS_BAD_ARGS;
    size_t n = (size_t)width * (size_t)height * (size_t)channels;
    double sse = 0, energy = 0, max_abs = -1, peak = -INFINITY;
    size_t max_i = 0;
    for (size_t i = 0; i < n; ++i) {
        double t = test[i], r = ref[i];
        if (!isfinite(t) || !isfinite(r)) {
            size_t p = i / (size_t)channels;
            m->max_x = (int)(p % (size_t)width);
            m->max_y = (int)(p / (size_t)width);
            m->max_c = (int)(i % (size_t)channels);
            return ABRDF_METRICS_NONFINITE;
        }
        double d = t - r;
        peak = fmax(peak, fmax(t, r));
        sse += d * d;
        energy += r * r;
        if (fabs(d) > max_abs) {
            max_abs = fabs(d);
            max_i = i;
        }
    }
    m->sse = sse;
    m->ref_energy = energy;
    m->nmse_defined = energy > 0;
    m->nmse = energy > 0 ? sse / energy : 0; /* paper Sec. 4, NMSE */
    m->mse = sse / (double)n;
    m->peak = peak;
    /* Peak = the brightest value present, so that PSNR means something for HDR images too. */
    m->psnr = !(m->mse > 0) ? INFINITY : peak > 0 ? 10 * log10(peak * peak / m->mse) : -INFINITY;
    m->max_abs = max_abs;
    size_t p = max_i / (size_t)channels;
    m->max_x = (int)(p % (size_t)width);
    m->max_y = (int)(p / (size_t)width);
    m->max_c = (int)(max_i % (size_t)channels);
    return ABRDF_METRICS_OK;
}

const char *abrdf_nmse_class(double nmse)
{
    if (!(nmse >= 0)) return "undefined";
    if (nmse < ABRDF_NMSE_SLIGHT) return "none";
    if (nmse < ABRDF_NMSE_NOTICEABLE) return "slight";
    if (nmse < ABRDF_NMSE_SIGNIFICANT) return "noticeable";
    return "significant";
}

const char *abrdf_nmse_class_description(double nmse)
{
    if (!(nmse >= 0)) return "undefined";
    if (nmse < ABRDF_NMSE_SLIGHT) return "no visible difference";
    if (nmse < ABRDF_NMSE_NOTICEABLE) return "slight difference";
    if (nmse < ABRDF_NMSE_SIGNIFICANT) return "noticeable difference";
    return "significant difference";
}
