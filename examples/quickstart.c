/* quickstart.c - evaluate one reflectance model with the installed libabrdf, and sample it.
 *   cc quickstart.c $(pkg-config --cflags --libs abrdf) -o quickstart   (or CMake: see CMakeLists.txt) */
#include <stdio.h>
#include <abrdf.h>
#include <abrdf_inline.h>

int main(void)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p); /* the model's defaults */
    p.r = 0.3;                                    /* perceptual roughness; alpha_g = r^2 */
    abrdf_prepared mat; /* validated and precomputed once, then evaluated per sample */
    int st = abrdf_prepare(ABRDF_DISNEY_SPECULAR, &p, &mat);
    if (st != ABRDF_OK) {
        fprintf(stderr, "abrdf: %s\n", abrdf_strerror(st));
        return 1;
    }
    const double n[3] = {0, 0, 1}, wi[3] = {0.3, 0, 1}, wo[3] = {-0.2, 0.1, 1};
    abrdf_frame frame;
    abrdf_frame_make(n, NULL, &frame); /* N, T, B from the normal */
    double f[3];                       /* f_r per RGB channel, 1/sr, no cosine */
    abrdf_eval_prepared(&mat, &frame, wi, wo, f);
    printf("abrdf %s: disney_specular f_r = %.6f %.6f %.6f\n", abrdf_version(), f[0], f[1], f[2]);

    /* A renderer's per-sample call: directions that are already unit vectors in the local
     * frame (N = +z) need no frame and no normalisation (abrdf_eval_prepared_unit). */
    const double li[3] = {0.287347885566345, 0.0, 0.957826285221151},       /* wi, normalised */
        lo[3] = {-0.195180014589707, 0.097590007294853, 0.975900072948533}; /* wo */
    double fu[3];
    abrdf_eval_prepared_unit(&mat, li, lo, fu);
    printf("the same from unit local directions: %.6f %.6f %.6f\n", fu[0], fu[1], fu[2]);

    /* Many pairs at once, in float on the vector unit: interleaved (x, y, z) rows of local
     * directions in (made unit by the call; a zero row gives 0), (r, g, b) rows out
     * (abrdf_eval_prepared_rows; abrdf_eval_prepared_batch takes one array per axis of unit
     * directions). Here the pair above and a light straight overhead. */
    const float rows_wi[6] = {0.28734789f, 0.0f, 0.95782629f, 0.0f, 0.0f, 1.0f};
    const float rows_wo[6] = {-0.19518001f, 0.09759001f, 0.97590007f,
                              -0.19518001f, 0.09759001f, 0.97590007f};
    float rows_f[6];
    if (abrdf_eval_prepared_rows(&mat, 2, rows_wi, rows_wo, rows_f) != ABRDF_OK) return 1;
    printf("in float, as rows: %.6f %.6f %.6f; light overhead: %.6f %.6f %.6f\n", rows_f[0],
           rows_f[1], rows_f[2], rows_f[3], rows_f[4], rows_f[5]);

    /* A renderer that shades one sample at a time in float: the same float path on one pair
     * (abrdf_eval_prepared_float), bit for bit the rows' first value. */
    float f1[3];
    if (abrdf_eval_prepared_float(&mat, rows_wi, rows_wo, f1) != ABRDF_OK) return 1;
    printf("in float, one pair: %.6f %.6f %.6f\n", f1[0], f1[1], f1[2]);

    /* The same lobe inlined into the caller (abrdf_inline.h, disney_specular only): no call
     * and no test per sample, for directions that are unit vectors; the same bits. */
    abrdf_ggx_float lobe;
    if (abrdf_prepared_ggx_float(&mat, &lobe) != ABRDF_OK) return 1;
    abrdf_ggx_float_eval(&lobe, rows_wi, rows_wo, f1);
    printf("in float, inlined: %.6f %.6f %.6f\n", f1[0], f1[1], f1[2]);

    /* Importance sampling: light directions for the view direction wo, with pdf and weight
     * f_r cos / pdf; their mean weight estimates the directional albedo (docs/RENDERER.md,
     * "Importance sampling"). */
    abrdf_sample_result r;
    abrdf_sample_result_init(&r);
    double albedo = 0.0;
    const int n_samples = 4096;
    for (int i = 0; i < n_samples; ++i) {
        double u1 = (i + 0.5) / n_samples,
               u2 = (i * 0.6180339887498949) - (int)(i * 0.6180339887498949);
        if (abrdf_sample_prepared(&mat, &frame, wo, u1, u2, &r) != ABRDF_OK) return 1;
        albedo += r.weight[0] / n_samples;
    }
    printf("disney_specular albedo for wo by %d samples (%s) = %.3f\n", n_samples,
           abrdf_model_sampler(ABRDF_DISNEY_SPECULAR)->name, albedo);
    return 0;
}
